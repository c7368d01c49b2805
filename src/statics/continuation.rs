//! Start shapes for a static solve from the solution of a neighbouring problem: the same
//! segment a moment earlier in a motion (its guides moved a little), or the same guides
//! with a length one step shorter. Newton's method from such a shape needs a few
//! iterations where it needs many from the connected geometry, and it stays on the branch
//! of equilibria it came from — the one a cable moved slowly through the motion, or made a
//! little longer, actually follows.
//!
//! Both predictors end by moving the interior nodes back onto sub-segments of exactly one
//! pitch (the minimum-norm correction of module `retract`), so that the first Newton step
//! starts from a cable, not from a stretched polyline whose axial forces would dwarf the
//! bending ones.

use nalgebra::Point3;

use super::retract::{Retraction, restore_lengths};
use crate::pose::Pose;

/// `nodes` (a solution between the guides `from`) carried along when its guides move to
/// `to`: node `k` of `S` moves by the blend `(1 − k/S)·A + (k/S)·B` of the two guides' rigid
/// motions `A = to.0 ∘ from.0⁻¹`, `B = to.1 ∘ from.1⁻¹`, so that the ends land on the new
/// guides and a segment whose guides move together moves rigidly.
pub fn follow_guides(
    nodes: &[Point3<f64>],
    from: (&Pose, &Pose),
    to: (&Pose, &Pose),
    pitch_m: f64,
) -> Vec<Point3<f64>> {
    let mut moved = carried(nodes, from, to);
    restore_pitch(&mut moved, pitch_m);
    moved
}

/// Two earlier solutions of a sequence of poses (`nearest` the last one), each with its
/// guides, carried to the guides `to` and extrapolated linearly: the shape keeps changing
/// as it did between them (for poses at equal steps, such as a motion's samples).
pub fn follow_guides_extrapolated(
    nearest: (&[Point3<f64>], (&Pose, &Pose)),
    second: (&[Point3<f64>], (&Pose, &Pose)),
    to: (&Pose, &Pose),
    pitch_m: f64,
) -> Vec<Point3<f64>> {
    let mut nodes = carried(nearest.0, nearest.1, to);
    if second.0.len() == nodes.len() {
        let far = carried(second.0, second.1, to);
        for (node, far) in nodes.iter_mut().zip(&far) {
            *node += *node - far;
        }
    }
    restore_pitch(&mut nodes, pitch_m);
    nodes
}

/// [`follow_guides`] before the pitch is restored.
fn carried(nodes: &[Point3<f64>], from: (&Pose, &Pose), to: (&Pose, &Pose)) -> Vec<Point3<f64>> {
    let start_motion = to.0 * from.0.inverse();
    let end_motion = to.1 * from.1.inverse();
    let last = nodes.len().saturating_sub(1).max(1) as f64;
    let mut moved: Vec<Point3<f64>> = nodes
        .iter()
        .enumerate()
        .map(|(k, node)| {
            let s = k as f64 / last;
            let a = start_motion * node;
            let b = end_motion * node;
            Point3::from(a.coords * (1.0 - s) + b.coords * s)
        })
        .collect();
    if let Some(first) = moved.first_mut() {
        *first = Point3::from(to.0.translation.vector);
    }
    if let Some(end) = moved.last_mut() {
        *end = Point3::from(to.1.translation.vector);
    }
    moved
}

/// A start shape of `connected.len() − 1` sub-segments between the guides of a solution
/// `solved` of another length: `connected` (the new length's connected geometry) plus the
/// solution's deviation from its own connected geometry `solved_connected`, at the same
/// fraction of the length.
pub fn change_length(
    solved: &[Point3<f64>],
    solved_connected: &[Point3<f64>],
    connected: &[Point3<f64>],
    pitch_m: f64,
) -> Vec<Point3<f64>> {
    if solved.len() != solved_connected.len() || solved.len() < 2 || connected.len() < 2 {
        return connected.to_vec();
    }
    let new_last = (connected.len() - 1) as f64;
    let mut nodes: Vec<Point3<f64>> = connected
        .iter()
        .enumerate()
        .map(|(k, node)| {
            let f = k as f64 / new_last;
            node + (at_fraction(solved, f) - at_fraction(solved_connected, f))
        })
        .collect();
    restore_pitch(&mut nodes, pitch_m);
    nodes
}

/// A start shape of `sub_segments` between the guides of two or three solutions of other
/// lengths (`earlier[0]` the nearest): the shapes extrapolated in the length by the
/// Lagrange polynomial through them, point by point at the same fraction of the length —
/// no connected geometry needed.
pub fn extrapolate_length(
    earlier: &[&[Point3<f64>]],
    sub_segments: usize,
    pitch_m: f64,
) -> Vec<Point3<f64>> {
    let lengths: Vec<f64> = earlier
        .iter()
        .map(|nodes| (nodes.len() - 1) as f64)
        .collect();
    let target = sub_segments as f64;
    // Lagrange weights of the earlier lengths at the target length.
    let weights: Vec<f64> = (0..lengths.len())
        .map(|i| {
            (0..lengths.len())
                .filter(|&j| j != i)
                .map(|j| (target - lengths[j]) / (lengths[i] - lengths[j]))
                .product()
        })
        .collect();
    let mut nodes: Vec<Point3<f64>> = (0..=sub_segments)
        .map(|k| {
            let f = k as f64 / target;
            let coords: nalgebra::Vector3<f64> = earlier
                .iter()
                .zip(&weights)
                .map(|(shape, w)| at_fraction(shape, f).coords * *w)
                .sum();
            Point3::from(coords)
        })
        .collect();
    restore_pitch(&mut nodes, pitch_m);
    nodes
}

/// The polyline `nodes` at fraction `f` of its node count (linear between nodes).
fn at_fraction(nodes: &[Point3<f64>], f: f64) -> Point3<f64> {
    let last = nodes.len() - 1;
    let u = f * last as f64;
    let i = (u.floor() as usize).min(last - 1);
    let w = u - i as f64;
    nodes[i] + (nodes[i + 1] - nodes[i]) * w
}

/// Moves the interior nodes so that every sub-segment is one pitch long (left as they are
/// if that fails, e.g. for guides farther apart than the cable is long).
fn restore_pitch(nodes: &mut [Point3<f64>], pitch_m: f64) {
    let count = nodes.len();
    if count < 3 {
        return;
    }
    let targets = vec![pitch_m; count - 1];
    let free: Vec<bool> = (0..count).map(|k| k > 0 && k + 1 < count).collect();
    let mut trial = nodes.to_vec();
    if restore_lengths(&mut trial, &targets, &free, &mut Retraction::default()) {
        nodes.copy_from_slice(&trial);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::pose_from_xyz_rpy;

    /// Nodes on a circle of radius 0.2 m, chords of exactly `pitch`.
    fn arc(count: usize, pitch: f64) -> Vec<Point3<f64>> {
        let radius = 0.2;
        let step = 2.0 * (0.5 * pitch / radius).asin();
        (0..count)
            .map(|k| {
                let a = step * k as f64;
                Point3::new(radius * a.sin(), 0.0, -radius * (1.0 - a.cos()))
            })
            .collect()
    }

    /// Guides that move together carry the shape rigidly; the ends land on the new guides.
    #[test]
    fn a_rigid_motion_of_both_guides_moves_the_shape_rigidly() {
        let nodes = arc(21, 0.01);
        let end = nodes[20].coords;
        let from = (Pose::identity(), Pose::translation(end.x, end.y, end.z));
        let motion = pose_from_xyz_rpy([0.1, -0.2, 0.3], [0.3, -0.2, 1.0]);
        let to = (motion * from.0, motion * from.1);
        let moved = follow_guides(&nodes, (&from.0, &from.1), (&to.0, &to.1), 0.01);
        for (a, b) in moved.iter().zip(&nodes) {
            assert!((a - motion * b).norm() < 1e-12, "{a} vs {}", motion * b);
        }
    }

    /// The same length back gives the solution back; a longer one, from its own connected
    /// geometry, gives chords of one pitch between the same guides.
    #[test]
    fn changing_the_length_keeps_the_deviation_and_the_pitch() {
        use crate::geometry::connect;
        use nalgebra::Vector3;
        let start = pose_from_xyz_rpy([0.0; 3], [0.0, 1.2, 0.0]);
        let end = pose_from_xyz_rpy([0.15, 0.02, -0.05], [0.0, 2.2, 0.3]);
        let down = -Vector3::z_axis();
        let connected = |s: usize| connect(&start, &end, s, 0.01, &down).unwrap().nodes;
        let solved_connected = connected(20);
        // A "solution": the connected shape sagging by up to 1 cm, chords restored.
        let mut solved: Vec<Point3<f64>> = solved_connected
            .iter()
            .enumerate()
            .map(|(k, p)| p - Vector3::z() * 0.01 * (std::f64::consts::PI * k as f64 / 20.0).sin())
            .collect();
        restore_pitch(&mut solved, 0.01);
        let same = change_length(&solved, &solved_connected, &solved_connected, 0.01);
        for (a, b) in same.iter().zip(&solved) {
            assert!((a - b).norm() < 1e-9);
        }
        let shape = change_length(&solved, &solved_connected, &connected(22), 0.01);
        assert_eq!(shape.len(), 23);
        assert_eq!((shape[0], shape[22]), (solved[0], solved[20]));
        for w in shape.windows(2) {
            assert!(((w[1] - w[0]).norm() - 0.01).abs() < 1e-12);
        }
    }
}
