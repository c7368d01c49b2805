//! The damage one cycle of a motion does along one piece of cable: every joint's bending
//! history counted for conductors all around the cable, the piece's twist history counted
//! once (the twist is uniform along a piece), Miner's sum of each counted cycle's damage.

use super::curve::LifeCurve;
use super::rainflow::Counter;
use serde::Serialize;

/// Conductor angles around the cable whose bending is counted (every 15° over half a turn:
/// the opposite side sees the same ranges). The projection of the curvature on the nearest
/// angle is at least cos 7.5° = 0.991 of the largest, a life at most 0.991^(−k) too long.
pub const CONDUCTOR_ANGLES: usize = 12;

/// The histories of one piece over one cycle of a motion, counted as they come.
#[derive(Debug, Clone)]
pub struct PieceHistory {
    /// Per joint, per conductor angle: the bending counter and its damage so far.
    bending: Vec<[(Counter, f64); CONDUCTOR_ANGLES]>,
    /// The twist per length counter and its damage so far.
    torsion: (Counter, f64),
    /// `(cos φ, sin φ)` of the conductor angles.
    angles: [(f64, f64); CONDUCTOR_ANGLES],
}

impl PieceHistory {
    /// Empty histories of a piece with `joints` joints ([`crate::stress::curvatures_per_m`]).
    pub fn new(joints: usize) -> PieceHistory {
        PieceHistory {
            bending: vec![std::array::from_fn(|_| (Counter::default(), 0.0)); joints],
            torsion: (Counter::default(), 0.0),
            angles: std::array::from_fn(|k| {
                let phi = std::f64::consts::PI * k as f64 / CONDUCTOR_ANGLES as f64;
                (phi.cos(), phi.sin())
            }),
        }
    }

    /// Takes in the piece's shape at one instant: its curvature vectors
    /// ([`crate::stress::curvature_vectors_per_m`], one per joint) and its twist per length
    /// (deg/m; `None` where the engine has no twist). A shape with another number of joints
    /// is ignored.
    pub fn push(
        &mut self,
        curve: &LifeCurve,
        curvatures: &[[f64; 2]],
        twist_deg_per_m: Option<f64>,
    ) {
        if curvatures.len() == self.bending.len() {
            for (joint, [k1, k2]) in self.bending.iter_mut().zip(curvatures) {
                for ((counter, damage), (cos, sin)) in joint.iter_mut().zip(self.angles) {
                    counter.push(k1 * cos + k2 * sin, |range| {
                        *damage += curve.bending_damage(range)
                    });
                }
            }
        }
        if let Some(twist) = twist_deg_per_m {
            let (counter, damage) = &mut self.torsion;
            counter.push(twist, |range| *damage += curve.torsion_damage(range));
        }
    }

    /// The damage of one cycle: the histories closed as the motion repeats.
    pub fn finish(self, curve: &LifeCurve) -> PieceDamage {
        let (counter, mut torsion) = self.torsion;
        counter.close_periodic(|range, count| torsion += count * curve.torsion_damage(range));
        let bending: Vec<f64> = self
            .bending
            .into_iter()
            .map(|joint| {
                joint
                    .into_iter()
                    .map(|(counter, mut damage)| {
                        counter.close_periodic(|range, count| {
                            damage += count * curve.bending_damage(range)
                        });
                        damage
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        PieceDamage { bending, torsion }
    }
}

/// What one cycle of a motion does to one piece (Miner's sum, 1 = failure).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PieceDamage {
    /// Per joint (node 0 at the start clamp), the bending damage of its worst conductor.
    pub bending: Vec<f64>,
    /// The twisting damage, the same all along the piece.
    pub torsion: f64,
}

impl PieceDamage {
    /// The damage at joint `k`: its bending and the piece's twisting.
    pub fn at(&self, k: usize) -> f64 {
        self.bending.get(k).copied().unwrap_or(0.0) + self.torsion
    }

    /// The most damaged joint and its damage per cycle (joint 0 for a piece without joints).
    pub fn worst(&self) -> (usize, f64) {
        (0..self.bending.len().max(1))
            .map(|k| (k, self.at(k)))
            .fold((0, f64::NEG_INFINITY), |best, (k, d)| {
                if d > best.1 { (k, d) } else { best }
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cable::RatedLife;

    fn curve(bend_mm: Option<f64>, torsion: Option<f64>) -> LifeCurve {
        LifeCurve::from_rated(&RatedLife {
            cycles: 1e6,
            bend_radius_m: bend_mm.map(|r| r * 1e-3),
            torsion_deg_per_m: torsion,
            exponent: 4.0,
            exponent_stated: true,
        })
    }

    /// The rated test repeated: a piece flexed from straight to the rated radius and back
    /// while twisted between ±the rated torsion, at any bending direction — one cycle of it
    /// is one rated life's share, at the bent joint; a straight joint takes only the twist.
    #[test]
    fn the_rated_test_does_the_rated_damage() {
        let curve = curve(Some(80.0), Some(360.0));
        for direction in [0.0f64, 0.4, 2.0] {
            let mut history = PieceHistory::new(2);
            let steps = 52;
            for k in 0..=steps {
                let s = (std::f64::consts::PI * k as f64 / steps as f64).sin();
                let bend = s / 0.080;
                let twist = 360.0 * (std::f64::consts::TAU * k as f64 / steps as f64).sin();
                let vector = [bend * direction.cos(), bend * direction.sin()];
                history.push(&curve, &[vector, [0.0, 0.0]], Some(twist));
            }
            let damage = history.finish(&curve);
            // Conductor angles every 15°: the bent one within cos(7.5°) of the plane.
            let worst = damage.at(0) * 1e6;
            assert!(
                worst <= 1.0 + 1e-9 && worst > 0.5 + 0.5 * 0.991f64.powi(4),
                "{worst}"
            );
            assert!((damage.at(1) * 1e6 - 0.5).abs() < 1e-9, "{}", damage.at(1));
            assert_eq!(damage.worst().0, 0);
        }
    }

    /// Bending one way and then the other is one cycle of twice the range, not two of one:
    /// 2⁴ / 2 = 8 times the damage of bending one way twice.
    #[test]
    fn a_reversed_bend_counts_its_whole_range() {
        let curve = curve(Some(100.0), None);
        let run = |signs: [f64; 4]| {
            let mut history = PieceHistory::new(1);
            for s in signs {
                history.push(&curve, &[[s * 10.0, 0.0]], None);
            }
            history.finish(&curve).at(0)
        };
        let one_way = run([0.0, 1.0, 0.0, 1.0]);
        let both_ways = run([0.0, 1.0, 0.0, -1.0]);
        assert!((one_way * 1e6 - 2.0).abs() < 1e-9, "{one_way}");
        assert!(
            (both_ways / one_way - 8.0).abs() < 1e-9,
            "{}",
            both_ways / one_way
        );
    }
}
