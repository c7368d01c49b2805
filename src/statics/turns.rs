//! Twist beyond what the guide frames say: whole turns of the end clamp about the cable.
//!
//! A clamp frame fixes the cable's twist only modulo a full turn, so a cable whose fixed end
//! was turned twice before it was clamped cannot be described by its frames. Its equilibrium
//! is reached the way the cable got there: the end clamp is turned about its own axis in
//! small steps, each solved from the previous shape with the twist continued (not wrapped
//! back to `(−π, π]`), until the extra angle is reached. After whole turns the clamp frame is
//! the one given and the total twist is larger by `2π` per turn.

use super::{Equilibrium, FarEnd, RodParameters, SolverOptions, StaticSolver, StaticsError};
use crate::pose::Pose;
use nalgebra::{Isometry3, Point3, Vector3};

/// Largest turn of the end clamp between two solves (rad): 15°.
pub const TURN_STEP_RAD: f64 = 15.0 * std::f64::consts::PI / 180.0;
/// Smallest step tried when a larger one does not converge (rad): 0.1°.
pub const MIN_TURN_STEP_RAD: f64 = 0.1 * std::f64::consts::PI / 180.0;

/// The equilibrium of a segment whose end clamp is turned by `extra_rad` about its own +z
/// axis (right-handed) beyond the frame `end`, from the shape `initial_nodes` with the twist
/// branch `initial_twist_rad` ([`super::solve_segment`]). `each_step` sees every equilibrium
/// on the way with the extra angle reached, the first at 0, and whether the cable passed
/// through itself during that step ([`passed_through_itself`]).
#[allow(clippy::too_many_arguments)]
pub fn solve_turned(
    solver: &mut StaticSolver,
    params: &RodParameters,
    start: &Pose,
    end: &Pose,
    initial_nodes: &[Point3<f64>],
    initial_twist_rad: Option<f64>,
    extra_rad: f64,
    options: &SolverOptions,
    mut each_step: impl FnMut(f64, &Equilibrium, bool),
) -> Result<Equilibrium, StaticsError> {
    if !extra_rad.is_finite() {
        return Err(StaticsError::InvalidInput {
            what: format!("the extra turn of the end clamp is {extra_rad} rad"),
        });
    }
    let clamp = FarEnd::Clamped(*end);
    let mut current = solver.solve(
        params,
        start,
        &clamp,
        initial_nodes,
        initial_twist_rad,
        options,
    )?;
    each_step(0.0, &current, false);
    let (mut reached, mut step) = (0.0_f64, TURN_STEP_RAD.copysign(extra_rad));
    while reached != extra_rad {
        // (The tolerance keeps rounding in the sum of steps from adding a last step of 1 ulp.)
        let next = if (extra_rad - reached).abs() <= step.abs() * (1.0 + 1e-9) {
            extra_rad
        } else {
            reached + step
        };
        let turned = turned_clamp(end, next, extra_rad);
        let branch = current.twist_rad + (next - reached);
        match solver.solve(
            params,
            start,
            &turned,
            &current.nodes,
            Some(branch),
            options,
        ) {
            Ok(equilibrium) => {
                let crossed =
                    passed_through_itself(current.twist_rad, equilibrium.twist_rad, next - reached);
                current = equilibrium;
                reached = next;
                each_step(reached, &current, crossed);
                step = (2.0 * step).clamp(-TURN_STEP_RAD, TURN_STEP_RAD);
            }
            Err(StaticsError::NotConverged {
                reason,
                iterations,
                residual_n,
            }) if step.abs() / 2.0 < MIN_TURN_STEP_RAD => {
                return Err(StaticsError::NotConverged {
                    reason: format!(
                        "turning the end clamp stopped at {:.1}° of {:.1}° ({reason}): the \
                         twisted cable has no equilibrium nearby (it may have to pass through \
                         itself)",
                        reached.to_degrees(),
                        extra_rad.to_degrees()
                    ),
                    iterations,
                    residual_n,
                });
            }
            Err(StaticsError::NotConverged { .. }) => step /= 2.0,
            Err(invalid) => return Err(invalid),
        }
    }
    Ok(current)
}

/// True when a step that turned the end clamp by `turned_rad` took the total twist from
/// `before_rad` to `after_rad` by more than half a turn off the turn itself. Twist and
/// writhe change together and continuously while the cable moves without crossing itself
/// (their sum is fixed by the clamps: Călugăreanu's theorem), so in a small step the twist
/// follows the clamp; a jump of about two turns is the writhe jumping as one part of the
/// cable passes through another — which the shapes before and after, each clear of itself,
/// do not show.
pub fn passed_through_itself(before_rad: f64, after_rad: f64, turned_rad: f64) -> bool {
    (after_rad - before_rad - turned_rad).abs() > std::f64::consts::PI
}

/// The end clamp turned by `angle` about its +z axis; exactly `end` once whole turns are
/// reached (no rounding left in the frame).
fn turned_clamp(end: &Pose, angle: f64, extra_rad: f64) -> FarEnd {
    let whole_turns = (extra_rad / std::f64::consts::TAU).fract() == 0.0;
    if angle == extra_rad && whole_turns {
        return FarEnd::Clamped(*end);
    }
    FarEnd::Clamped(end * Isometry3::rotation(Vector3::z() * angle))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::pose_from_xyz_rpy;
    use crate::statics::Holds;
    use std::f64::consts::{FRAC_PI_2, TAU};

    fn params(gravity_m_s2: f64, torsion_over_bending: f64) -> RodParameters {
        let bending = 0.05 * 0.01;
        RodParameters {
            pitch_m: 0.01,
            bending_stiffness_n_m2: bending,
            torsion_stiffness_n_m2: torsion_over_bending * bending,
            axial_stiffness_n: 1e3,
            mass_per_length_kg_m: 0.1,
            gravity_m_s2: Vector3::new(0.0, 0.0, -gravity_m_s2),
            holds: Holds::RIGID,
        }
    }

    fn straight(from: Point3<f64>, to: Point3<f64>, count: usize) -> Vec<Point3<f64>> {
        (0..=count)
            .map(|k| from + (to - from) * (k as f64 / count as f64))
            .collect()
    }

    /// The equilibrium after turning the end clamp by `extra_rad`, and the angles of its steps.
    fn turned(
        params: &RodParameters,
        (start, end): (&Pose, &Pose),
        nodes: &[Point3<f64>],
        extra_rad: f64,
    ) -> (Equilibrium, Vec<f64>) {
        let mut steps = Vec::new();
        let options = SolverOptions::default();
        let mut solver = StaticSolver::default();
        let record = |angle, _: &Equilibrium, _| steps.push(angle);
        let equilibrium = solve_turned(
            &mut solver,
            params,
            start,
            end,
            nodes,
            None,
            extra_rad,
            &options,
            record,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        (equilibrium, steps)
    }

    /// Between coaxial clamps its own length apart, without gravity, a turn of the end clamp
    /// is pure twist: the cable stays straight and stores ½ (GJ/L) (2π)², the closed form of a
    /// twisted shaft (below the twist at which a clamped rod buckles, 2.86π EI/GJ = 18 rad).
    #[test]
    fn a_taut_straight_cable_takes_a_whole_turn_as_pure_twist() {
        let params = params(0.0, 0.5);
        let (start, end) = (
            Pose::identity(),
            pose_from_xyz_rpy([0.0, 0.0, 0.2], [0.0; 3]),
        );
        let nodes = straight(Point3::origin(), Point3::new(0.0, 0.0, 0.2), 20);
        let (twisted, steps) = turned(&params, (&start, &end), &nodes, TAU);
        assert_eq!(steps.len(), 25, "0°, then 24 steps of 15°: {steps:?}");
        assert!(
            (twisted.twist_rad - TAU).abs() < 1e-9,
            "{}",
            twisted.twist_rad
        );
        let closed_form = 0.5 * params.torsion_stiffness_n_m2 / 0.2 * TAU * TAU;
        assert!((twisted.energy.twist_j - closed_form).abs() < 1e-9 * closed_form);
        let off_axis = twisted
            .nodes
            .iter()
            .map(|p| p.x.hypot(p.y))
            .fold(0.0, f64::max);
        assert!(off_axis < 1e-9, "{off_axis}");
    }

    /// A sagging cable is symmetric under the mirror y → −y that holds its clamps and
    /// gravity; the mirror turns a right-handed turn into a left-handed one. So the shapes
    /// after +1 and −1 turn are mirror images and their twists opposite: the continuation
    /// has no preferred hand.
    #[test]
    fn opposite_turns_give_mirror_image_shapes() {
        let params = params(9.81, 0.7);
        let along_x = [0.0, FRAC_PI_2, 0.0];
        let start = pose_from_xyz_rpy([0.0; 3], along_x);
        let end = pose_from_xyz_rpy([0.15, 0.0, 0.0], along_x);
        let nodes: Vec<Point3<f64>> = (0..=20)
            .map(|k| {
                let t = k as f64 / 20.0;
                Point3::new(0.15 * t, 0.0, -0.08 * (std::f64::consts::PI * t).sin())
            })
            .collect();
        let solve = |turns: f64| turned(&params, (&start, &end), &nodes, turns * TAU).0;
        let (right, left) = (solve(1.0), solve(-1.0));
        assert!((right.twist_rad + left.twist_rad).abs() < 1e-7);
        assert!(right.twist_rad > 5.0, "{}", right.twist_rad);
        let out_of_plane = right.nodes.iter().map(|p| p.y.abs()).fold(0.0, f64::max);
        assert!(
            out_of_plane > 1e-3,
            "the twisted loop writhes: {out_of_plane}"
        );
        for (r, l) in right.nodes.iter().zip(&left.nodes) {
            let mirrored = Point3::new(r.x, -r.y, r.z);
            assert!((mirrored - l).norm() < 1e-7, "{r} vs {l}");
        }
    }
}
