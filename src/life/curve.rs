//! The cable's life curve: how many cycles of a bending or a twisting range a conductor
//! survives — from the datasheet's rated life, or, when the datasheet gives none, from a
//! strain–life line of annealed copper.
//!
//! A datasheet rates a cable for `N` cycles flexed from straight to a radius `R` and back
//! (a curvature range of 1/R) and twisted between ±`T` per metre (a range of 2T). Away from
//! that point the life follows a power law of the range with the exponent `k` the cable file
//! states (or [`DEFAULT_LIFE_EXPONENT`](crate::cable::DEFAULT_LIFE_EXPONENT)): a conductor's
//! strain is proportional to the curvature and to the twist per length at a given distance
//! from the cable's axis, so a power law in strain (the Basquin and Coffin–Manson laws) is one
//! in these ranges, whatever that distance. When the rating combines bending and torsion, a
//! rated cycle's damage is shared equally between them, so that one rated cycle of both is
//! exactly one `N`-th of the life.
//!
//! Without a rating, the copper's strain range is the curvature range times the cable file's
//! `conductor_offset_mm` (and, for twisting, the shear strain range over √3, von Mises), and
//! its life the elastic line of Manson's universal slopes (S. S. Manson, *Fatigue: a complex
//! subject — some simple approximations*, Exp. Mech. 5 (1965) 193–226, as stated in
//! NASA CR-134841, eq. 2): Δε = 3.5 σu/E · N^(−0.12), with annealed copper's ultimate strength
//! and Young's modulus ([`COPPER_ULTIMATE_STRENGTH_PA`], [`COPPER_YOUNGS_MODULUS_PA`]). The
//! plastic line is left out (it needs the reduction of area, which no source found states
//! legibly for annealed copper): a lower bound on the life, tightest at high cycles.

use crate::cable::{Datasheet, RatedLife};

/// Ultimate tensile strength of annealed (tough-pitch) copper, 224 MPa: Smithells Metals
/// Reference Book, 8th ed., Table 22.7 (OFHC 216 MPa; datasheets of C11000 220–230 MPa).
pub const COPPER_ULTIMATE_STRENGTH_PA: f64 = 224e6;
/// Young's modulus of copper, 117 GPa (17 000 ksi): copper.org's data for C10100–C11000, and
/// Smithells Table 22.7.
pub const COPPER_YOUNGS_MODULUS_PA: f64 = 117e9;
/// The slope of the elastic line of Manson's universal slopes (N^(−0.12)): its exponent in
/// ranges is 1/0.12.
pub const UNIVERSAL_ELASTIC_SLOPE: f64 = 0.12;

/// What a life curve was built from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LifeBasis {
    /// The datasheet's rated life.
    Rated(RatedLife),
    /// Annealed copper's strain–life line at the conductors' offset (m).
    Copper {
        /// The distance whose strain is the curvature times it (m).
        conductor_offset_m: f64,
    },
}

/// Cycles to failure `cycles · (range / range_at)^(−exponent)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    /// Cycles to failure at `range_at`.
    pub cycles: f64,
    /// The range those cycles are rated at (the history's unit).
    pub range_at: f64,
    /// The exponent `k` (> 0).
    pub exponent: f64,
}

impl PowerLaw {
    /// Cycles to failure at `range` (infinite for a range of 0).
    pub fn cycles_to_failure(&self, range: f64) -> f64 {
        self.cycles * (range / self.range_at).powf(-self.exponent)
    }

    /// The damage of one cycle of `range` (Miner's rule: its share of the life).
    pub fn damage(&self, range: f64) -> f64 {
        if range > 0.0 {
            1.0 / self.cycles_to_failure(range)
        } else {
            0.0
        }
    }
}

/// The life curve of a cable: bending cycles by their curvature range (1/m), twisting cycles
/// by their range of twist per length (deg/m); `None` for what the rating does not cover.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LifeCurve {
    /// Bending: cycles to failure by curvature range (1/m).
    pub bending: Option<PowerLaw>,
    /// Torsion: cycles to failure by range of twist per length (deg/m).
    pub torsion: Option<PowerLaw>,
    /// What it was built from.
    pub basis: LifeBasis,
}

impl LifeCurve {
    /// The curve of a cable's datasheet: its rated point, else annealed copper at its
    /// conductors' offset; `None` when it states neither.
    pub fn of(datasheet: &Datasheet) -> Option<LifeCurve> {
        match (&datasheet.rated_life, datasheet.conductor_offset_m) {
            (Some(rated), _) => Some(LifeCurve::from_rated(rated)),
            (None, Some(offset)) => Some(LifeCurve::copper(offset)),
            (None, None) => None,
        }
    }

    /// Annealed copper's elastic strain–life line (module documentation) for a conductor
    /// `offset_m` from the cable's axis.
    pub fn copper(offset_m: f64) -> LifeCurve {
        // The strain range that fails in one cycle; the curvature and twist ranges giving it.
        let strain = 3.5 * COPPER_ULTIMATE_STRENGTH_PA / COPPER_YOUNGS_MODULUS_PA;
        let law = |range_at: f64| PowerLaw {
            cycles: 1.0,
            range_at,
            exponent: 1.0 / UNIVERSAL_ELASTIC_SLOPE,
        };
        LifeCurve {
            bending: Some(law(strain / offset_m)),
            torsion: Some(law((3f64.sqrt() * strain / offset_m).to_degrees())),
            basis: LifeBasis::Copper {
                conductor_offset_m: offset_m,
            },
        }
    }

    /// The curve through the datasheet's rated point.
    pub fn from_rated(rated: &RatedLife) -> LifeCurve {
        let both = rated.bend_radius_m.is_some() && rated.torsion_deg_per_m.is_some();
        // A rated cycle of both shares its damage equally.
        let cycles = if both { 2.0 } else { 1.0 } * rated.cycles;
        let law = |range_at: f64| PowerLaw {
            cycles,
            range_at,
            exponent: rated.exponent,
        };
        LifeCurve {
            bending: rated.bend_radius_m.map(|r| law(1.0 / r)),
            torsion: rated.torsion_deg_per_m.map(|t| law(2.0 * t)),
            basis: LifeBasis::Rated(*rated),
        }
    }

    /// The damage of one bending cycle of curvature range `range_per_m`; 0 when bending is
    /// not rated.
    pub fn bending_damage(&self, range_per_m: f64) -> f64 {
        self.bending.map_or(0.0, |law| law.damage(range_per_m))
    }

    /// The damage of one twisting cycle of range `range_deg_per_m`; 0 when torsion is not
    /// rated.
    pub fn torsion_damage(&self, range_deg_per_m: f64) -> f64 {
        self.torsion.map_or(0.0, |law| law.damage(range_deg_per_m))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rated(bend_mm: Option<f64>, torsion: Option<f64>) -> RatedLife {
        RatedLife {
            cycles: 5e6,
            bend_radius_m: bend_mm.map(|r| r * 1e-3),
            torsion_deg_per_m: torsion,
            exponent: 4.0,
            exponent_stated: true,
        }
    }

    /// One rated cycle — flexed from straight to the rated radius and twisted between ±the
    /// rated torsion — is exactly one rated life's share; each alone is half of it when both
    /// are rated, all of it when only one is.
    #[test]
    fn the_rated_point_is_the_rated_life() {
        let both = LifeCurve::from_rated(&rated(Some(80.0), Some(360.0)));
        let cycle = both.bending_damage(1.0 / 0.080) + both.torsion_damage(720.0);
        assert!((cycle * 5e6 - 1.0).abs() < 1e-12, "{cycle}");
        assert!((both.bending_damage(12.5) * 1e7 - 1.0).abs() < 1e-12);
        let bending = LifeCurve::from_rated(&rated(Some(80.0), None));
        assert!((bending.bending_damage(12.5) * 5e6 - 1.0).abs() < 1e-12);
        assert_eq!(bending.torsion_damage(720.0), 0.0);
        let torsion = LifeCurve::from_rated(&rated(None, Some(360.0)));
        assert!((torsion.torsion_damage(720.0) * 5e6 - 1.0).abs() < 1e-12);
    }

    /// Copper's line, by hand: a conductor 0.05 mm from the axis (a fine strand's radius)
    /// bent over a curvature range of 20 1/m strains by 1e-3; 3.5 · 224/117 000 = 6.70e-3
    /// fails in one cycle, so N = (1e-3 / 6.70e-3)^(−1/0.12) ≈ 7.6e6. Twisted by 1 rad/m
    /// (57.3°/m) it shears by 5e-5, an equivalent strain of 2.89e-5.
    #[test]
    fn copper_follows_the_elastic_universal_slope() {
        let curve = LifeCurve::copper(0.05e-3);
        let one_cycle: f64 = 3.5 * 224.0 / 117_000.0;
        let n = (1e-3 / one_cycle).powf(-1.0 / 0.12);
        let bending = curve.bending.expect("copper bends");
        assert!((bending.cycles_to_failure(20.0) / n - 1.0).abs() < 1e-12);
        assert!((n - 7.6e6).abs() < 0.1e6, "{n}");
        let twist = curve.torsion.expect("copper twists");
        let shear = 1.0 * 0.05e-3;
        let expected = (shear / 3f64.sqrt() / one_cycle).powf(-1.0 / 0.12);
        let got = twist.cycles_to_failure(1f64.to_degrees());
        assert!(
            (got / expected - 1.0).abs() < 1e-9,
            "{got} against {expected}"
        );
    }

    /// The life falls as a range grows, by the exponent: twice the range, 2⁴ times fewer
    /// cycles.
    #[test]
    fn life_falls_with_the_range() {
        let curve = LifeCurve::from_rated(&rated(Some(80.0), Some(360.0)));
        let law = curve.bending.expect("rated");
        let mut last = f64::INFINITY;
        for k in 1..50 {
            let n = law.cycles_to_failure(0.5 * k as f64);
            assert!(n < last, "{n} at {k}");
            last = n;
        }
        let ratio = law.cycles_to_failure(10.0) / law.cycles_to_failure(20.0);
        assert!((ratio - 16.0).abs() < 1e-9);
        assert_eq!(law.damage(0.0), 0.0);
    }
}
