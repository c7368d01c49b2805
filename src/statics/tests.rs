//! Checks of the energy's derivatives against finite differences of the energy itself.

use super::banded::SymmetricBand;
use super::rod::Rod;
use super::*;
use crate::pose::pose_from_xyz_rpy;

fn params() -> RodParameters {
    RodParameters {
        pitch_m: 0.01,
        bending_stiffness_n_m2: 0.051 * 0.01,
        torsion_stiffness_n_m2: 1.5 * 0.01,
        axial_stiffness_n: 1e3,
        mass_per_length_kg_m: 0.26,
        gravity_m_s2: Vector3::new(0.0, 0.0, -9.81),
        holds: Holds::RIGID,
    }
}

/// The clamp holds the derivative checks run with: rigid, a swivel at either end (cones
/// narrower than the configuration's end angles, so that both bend beyond them), a rotating
/// clamp.
const HOLDS: [Holds; 4] = [
    Holds::RIGID,
    Holds {
        start: Hold::Swivel { cone_rad: 0.2 },
        end: Hold::Rigid,
    },
    Holds {
        start: Hold::Rigid,
        end: Hold::Swivel { cone_rad: 0.1 },
    },
    Holds {
        start: Hold::Rotating,
        end: Hold::Rigid,
    },
];

/// A bent, twisted, slightly stretched 3D configuration of 8 sub-segments.
fn twisted_rod(end_free: bool) -> (Rod, Vec<f64>) {
    twisted_rod_held(end_free, Holds::RIGID)
}

/// Every case the derivative checks run: each of [`HOLDS`] with a clamped and a free end,
/// and a swivel clamp holding node 4 (a little off it, its cone narrower than the turn of
/// the node's edges from its axis) between rigid clamps and before a free end.
fn cases() -> Vec<(bool, Holds, Option<Pin>)> {
    let pin = Pin {
        node: 4,
        position: Point3::new(0.027, 0.011, 0.012),
        axis: Vector3::new(0.9, 0.3, -0.3).normalize(),
        cone_rad: 0.05,
    };
    let mut cases: Vec<(bool, Holds, Option<Pin>)> = [false, true]
        .into_iter()
        .flat_map(|f| HOLDS.map(|h| (f, h, None)))
        .collect();
    cases.extend([
        (false, Holds::RIGID, Some(pin)),
        (true, HOLDS[3], Some(pin)),
    ]);
    cases
}

/// [`twisted_rod`] with the clamps' holds `holds`.
fn twisted_rod_held(end_free: bool, holds: Holds) -> (Rod, Vec<f64>) {
    twisted_rod_pinned(end_free, holds, None)
}

/// [`twisted_rod_held`] with a swivel clamp `pin` between its ends.
fn twisted_rod_pinned(end_free: bool, holds: Holds, pin: Option<Pin>) -> (Rod, Vec<f64>) {
    let start = pose_from_xyz_rpy([0.0; 3], [0.0, 1.2, 0.3]);
    let end = pose_from_xyz_rpy([0.05, 0.03, -0.02], [0.9, 2.0, -0.4]);
    let nodes: Vec<Point3<f64>> = (0..=8)
        .map(|k| {
            let t = k as f64 / 8.0;
            Point3::new(
                0.05 * t + 0.01 * (3.0 * t).sin(),
                0.03 * t * t + 0.004 * (5.0 * t).cos() - 0.004 * (1.0 - t),
                -0.02 * t + 0.015 * (std::f64::consts::PI * t).sin(),
            )
        })
        .collect();
    let rod = Rod::new(
        RodParameters { holds, ..params() },
        start,
        (!end_free).then_some(end),
        8,
    )
    .with_pin(pin);
    let x = rod.free_coordinates(&nodes);
    (rod, x)
}

fn energy(rod: &Rod, x: &[f64], reference: f64) -> f64 {
    rod.evaluate(x, reference, None).energy
}

/// The swivels of [`HOLDS`] bend beyond their cones in the test configuration: each bends it
/// more than a pin (a cone of π) would.
#[test]
fn the_test_swivels_bend_beyond_their_cones() {
    let pin = Hold::Swivel {
        cone_rad: std::f64::consts::PI,
    };
    let bending = |holds: Holds| {
        let (rod, x) = twisted_rod_held(false, holds);
        rod.evaluate(&x, 0.0, None).terms.bending_j
    };
    for holds in &HOLDS[1..3] {
        let pinned = Holds {
            start: if holds.start == Hold::Rigid {
                Hold::Rigid
            } else {
                pin
            },
            end: if holds.end == Hold::Rigid {
                Hold::Rigid
            } else {
                pin
            },
        };
        assert!(bending(*holds) > bending(pinned) + 1e-9, "{holds:?}");
    }
}

#[test]
fn gradient_matches_finite_differences_of_the_energy() {
    for (free, holds, pin) in cases() {
        let (rod, x) = twisted_rod_pinned(free, holds, pin);
        let at = rod.evaluate(&x, 0.0, None);
        let h = 1e-7;
        for i in 0..x.len() {
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[i] += h;
            minus[i] -= h;
            let numeric =
                (energy(&rod, &plus, at.twist) - energy(&rod, &minus, at.twist)) / (2.0 * h);
            let scale = super::newton::max_abs(&at.gradient);
            assert!(
                (at.gradient[i] - numeric).abs() < 1e-6 * scale,
                "free end {free}, {holds:?}, {pin:?}, coordinate {i}: {} vs {numeric}",
                at.gradient[i]
            );
        }
    }
}

#[test]
fn twist_gradient_matches_finite_differences_of_the_transported_twist() {
    let (rod, x) = twisted_rod(false);
    let at = rod.evaluate(&x, 0.0, None);
    let h = 1e-7;
    for i in 0..x.len() {
        let (mut plus, mut minus) = (x.clone(), x.clone());
        plus[i] += h;
        minus[i] -= h;
        let numeric = (rod.evaluate(&plus, at.twist, None).twist
            - rod.evaluate(&minus, at.twist, None).twist)
            / (2.0 * h);
        assert!(
            (at.twist_gradient[i] - numeric).abs() < 1e-6,
            "coordinate {i}: {} vs {numeric}",
            at.twist_gradient[i]
        );
    }
}

#[test]
fn hessian_matches_finite_differences_of_the_gradient() {
    for (free, holds, pin) in cases() {
        let (rod, x) = twisted_rod_pinned(free, holds, pin);
        let n = x.len();
        let mut band = SymmetricBand::zeros(n);
        let at = rod.evaluate(&x, 0.0, Some(&mut band));
        let k = rod.twist_stiffness();
        let h = 1e-7;
        let mut worst: f64 = 0.0;
        let mut scale: f64 = 0.0;
        for j in 0..n {
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[j] += h;
            minus[j] -= h;
            let gp = rod.evaluate(&plus, at.twist, None).gradient;
            let gm = rod.evaluate(&minus, at.twist, None).gradient;
            let mut unit = vec![0.0; n];
            unit[j] = 1.0;
            let column = band.multiply(&unit);
            for i in 0..n {
                let rank_one = if free {
                    0.0
                } else {
                    k * at.twist_gradient[i] * at.twist_gradient[j]
                };
                let numeric = (gp[i] - gm[i]) / (2.0 * h);
                worst = worst.max((column[i] + rank_one - numeric).abs());
                scale = scale.max(numeric.abs());
            }
        }
        assert!(
            worst < 1e-5 * scale,
            "free end {free}, {holds:?}, {pin:?}: {worst:e} of {scale:e}"
        );
    }
}

/// The swivel clamp of [`cases`] bends the node's edges beyond its cone in the test
/// configuration, so that the checks above see the cone's terms.
#[test]
fn the_test_pin_bends_beyond_its_cone() {
    for (free, holds, pin) in cases() {
        let Some(pin) = pin else { continue };
        let bending = |cone_rad: f64| {
            let (rod, x) = twisted_rod_pinned(free, holds, Some(Pin { cone_rad, ..pin }));
            rod.evaluate(&x, 0.0, None).terms.bending_j
        };
        assert!(bending(pin.cone_rad) > bending(std::f64::consts::PI) + 1e-9);
    }
}
