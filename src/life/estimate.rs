//! The cable's predicted life: the damage of every motion of a cell added up per point of the
//! cable, weighted by how often each runs, and the point that fails first.

use super::curve::{LifeBasis, LifeCurve};
use super::damage::PieceDamage;
use serde::Serialize;

/// Hours in a year of running around the clock.
pub const HOURS_PER_YEAR: f64 = 24.0 * 365.0;

/// One motion's damage to the cable, piece by piece, and its weight.
#[derive(Debug, Clone, Copy)]
pub struct MotionDamage<'a> {
    /// How many times it runs per hour; `None` when not stated.
    pub cycles_per_hour: Option<f64>,
    /// Per piece: its segment index, its name and the damage one run does to it.
    pub pieces: &'a [(usize, &'a str, &'a PieceDamage)],
}

/// The predicted life of a cable path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CableLife {
    /// What the life curve rests on: `rated` (the datasheet's rated life) or `copper`
    /// (annealed copper's strain–life line at the conductors' offset).
    pub basis: &'static str,
    /// The rated point's cycles (`rated`).
    pub rated_cycles: Option<f64>,
    /// Its bend radius (mm); `None` when the rating is for torsion alone.
    pub rated_bend_radius_mm: Option<f64>,
    /// Its torsion (±deg/m); `None` when the rating is for bending alone.
    pub rated_torsion_deg_per_m: Option<f64>,
    /// The conductors' offset the strain is taken at (mm, `copper`).
    pub conductor_offset_mm: Option<f64>,
    /// The life curve's exponent.
    pub exponent: f64,
    /// Whether the cable file stated the exponent (else the default).
    pub exponent_stated: bool,
    /// Cycles to failure: of the motion, or for a cell of one round of all its motions, each
    /// run as often as its `cycles_per_hour` says (once each when not every one says).
    pub cycles_to_failure: f64,
    /// Hours to failure, when every motion states its cycles per hour.
    pub hours_to_failure: Option<f64>,
    /// The same in years of running around the clock.
    pub years_to_failure: Option<f64>,
    /// The point that fails first.
    pub weakest: Weakest,
    /// Per piece, its own life and damage along it.
    pub pieces: Vec<PieceLife>,
}

/// The point of the cable that fails first.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Weakest {
    /// Index of its piece's segment.
    pub segment: usize,
    /// Its piece's segment name (`C2`).
    pub segment_name: String,
    /// Length of cable from the piece's start clamp (mm).
    pub from_start_mm: f64,
    /// Its damage per round (Miner's sum, 1 = failure).
    pub damage_per_cycle: f64,
}

/// One piece's life.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PieceLife {
    /// Index into the setup's segments.
    pub segment: usize,
    /// The segment's name.
    pub segment_name: String,
    /// Rounds to failure of its weakest point.
    pub cycles_to_failure: f64,
    /// Where that point is: cable length from the piece's start clamp (mm).
    pub weakest_from_start_mm: f64,
    /// Damage per round at every joint from the start clamp, one sub-segment apart (bending
    /// of the worst conductor plus twisting).
    pub damage_per_cycle: Vec<f64>,
    /// The part of it twisting does (the same all along the piece).
    pub torsion_damage_per_cycle: f64,
}

impl CableLife {
    /// The life of a path from the damage of each motion (`motions`); `pitch_mm` is the
    /// sub-segment length that places joints along a piece. A round runs every motion once;
    /// with every motion's cycles per hour, the damage per hour weights each by its rate and
    /// names the weakest point. `None` without a piece.
    pub fn of(curve: &LifeCurve, motions: &[MotionDamage<'_>], pitch_mm: f64) -> Option<CableLife> {
        let rates: Option<Vec<f64>> = motions.iter().map(|m| m.cycles_per_hour).collect();
        let per_round = along_pieces(motions, &vec![1.0; motions.len()]);
        let per_hour = rates.as_ref().map(|rates| along_pieces(motions, rates));
        let pieces: Vec<PieceLife> = per_round
            .into_iter()
            .map(|(segment, segment_name, along, torsion)| {
                let (joint, worst) = worst_of(&along);
                PieceLife {
                    segment,
                    segment_name,
                    cycles_to_failure: 1.0 / worst,
                    weakest_from_start_mm: joint as f64 * pitch_mm,
                    damage_per_cycle: along,
                    torsion_damage_per_cycle: torsion,
                }
            })
            .collect();
        // The weakest point: by the damage per hour when the rates are known, else per round.
        let ranked = per_hour.as_ref().map_or_else(
            || {
                pieces
                    .iter()
                    .map(|p| (p.segment, p.damage_per_cycle.clone()))
                    .collect()
            },
            |hourly| {
                hourly
                    .iter()
                    .map(|p| (p.0, p.2.clone()))
                    .collect::<Vec<_>>()
            },
        );
        let (segment, joint, worst) = ranked
            .iter()
            .map(|(segment, along)| {
                let (joint, worst) = worst_of(along);
                (*segment, joint, worst)
            })
            .fold(None, |best: Option<(usize, usize, f64)>, c| match best {
                Some(b) if b.2 >= c.2 => Some(b),
                _ => Some(c),
            })?;
        let piece = pieces.iter().find(|p| p.segment == segment)?;
        let hours = per_hour.map(|_| 1.0 / worst);
        let (rated, offset) = match curve.basis {
            LifeBasis::Rated(rated) => (Some(rated), None),
            LifeBasis::Copper { conductor_offset_m } => (None, Some(conductor_offset_m)),
        };
        let law = curve.bending.or(curve.torsion);
        Some(CableLife {
            basis: if rated.is_some() { "rated" } else { "copper" },
            rated_cycles: rated.map(|r| r.cycles),
            rated_bend_radius_mm: rated.and_then(|r| r.bend_radius_m).map(|r| r * 1e3),
            rated_torsion_deg_per_m: rated.and_then(|r| r.torsion_deg_per_m),
            conductor_offset_mm: offset.map(|o| o * 1e3),
            exponent: law.map_or(f64::NAN, |l| l.exponent),
            exponent_stated: rated.is_some_and(|r| r.exponent_stated),
            cycles_to_failure: 1.0 / piece.damage_per_cycle[joint],
            hours_to_failure: hours,
            years_to_failure: hours.map(|h| h / HOURS_PER_YEAR),
            weakest: Weakest {
                segment,
                segment_name: piece.segment_name.clone(),
                from_start_mm: joint as f64 * pitch_mm,
                damage_per_cycle: piece.damage_per_cycle[joint],
            },
            pieces,
        })
    }
}

/// Per piece (by segment): its name, the damage at every joint weighted by `weights` and
/// summed over the motions (twisting included), and the twisting part.
fn along_pieces(
    motions: &[MotionDamage<'_>],
    weights: &[f64],
) -> Vec<(usize, String, Vec<f64>, f64)> {
    let mut pieces: Vec<(usize, String, Vec<f64>, f64)> = Vec::new();
    for (motion, weight) in motions.iter().zip(weights) {
        for &(segment, name, damage) in motion.pieces {
            let at = match pieces.iter().position(|p| p.0 == segment) {
                Some(at) => at,
                None => {
                    pieces.push((segment, name.to_string(), Vec::new(), 0.0));
                    pieces.len() - 1
                }
            };
            let piece = &mut pieces[at];
            let joints = damage.bending.len().max(1);
            if piece.2.len() < joints {
                piece.2.resize(joints, 0.0);
            }
            for (k, sum) in piece.2.iter_mut().enumerate() {
                *sum += weight * damage.at(k);
            }
            piece.3 += weight * damage.torsion;
        }
    }
    pieces.sort_by_key(|p| p.0);
    pieces
}

/// The joint of the largest damage and that damage (joint 0 when all are 0).
fn worst_of(along: &[f64]) -> (usize, f64) {
    along.iter().enumerate().fold(
        (0, 0.0),
        |best, (k, &d)| if d > best.1 { (k, d) } else { best },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cable::RatedLife;

    fn rated() -> LifeCurve {
        LifeCurve::from_rated(&RatedLife {
            cycles: 1e6,
            bend_radius_m: Some(0.08),
            torsion_deg_per_m: None,
            exponent: 4.0,
            exponent_stated: false,
        })
    }

    /// Two motions: A damages C1's joint 2 by 1e-6 a run, B C2's joint 0 by 4e-6. A round
    /// (each once) fails C2 first after 250 000 rounds; at 100 runs of A and 10 of B an hour,
    /// A does 1e-4 an hour at C1 against B's 4e-5 at C2: C1 fails first, after 10 000 h.
    #[test]
    fn motions_add_up_by_how_often_they_run() {
        let a1 = PieceDamage {
            bending: vec![0.0, 0.5e-6, 1e-6],
            torsion: 0.0,
        };
        let b2 = PieceDamage {
            bending: vec![4e-6, 0.0],
            torsion: 0.0,
        };
        let a = [(0, "C1", &a1)];
        let b = [(1, "C2", &b2)];
        let motions = |ra: Option<f64>, rb: Option<f64>| {
            [
                MotionDamage {
                    cycles_per_hour: ra,
                    pieces: &a,
                },
                MotionDamage {
                    cycles_per_hour: rb,
                    pieces: &b,
                },
            ]
        };
        let rounds = CableLife::of(&rated(), &motions(None, Some(10.0)), 10.0).expect("life");
        assert_eq!(rounds.weakest.segment_name, "C2");
        assert!((rounds.cycles_to_failure - 250_000.0).abs() < 1e-6);
        assert_eq!(rounds.hours_to_failure, None);
        let hourly =
            CableLife::of(&rated(), &motions(Some(100.0), Some(10.0)), 10.0).expect("life");
        assert_eq!(hourly.weakest.segment_name, "C1");
        assert_eq!(hourly.weakest.from_start_mm, 20.0);
        let hours = hourly.hours_to_failure.expect("hours");
        assert!((hours - 10_000.0).abs() < 1e-6, "{hours}");
        assert!((hourly.years_to_failure.expect("years") - hours / 8760.0).abs() < 1e-12);
        assert!((hourly.pieces[0].cycles_to_failure - 1e6).abs() < 1e-6);
    }
}
