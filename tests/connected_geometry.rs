//! Integration tests of the connected geometry: every expected value is computed here, from
//! closed forms or from independent numerics (Hermite basis written out, adaptive Simpson
//! quadrature, bisection, golden-section projection), never taken from the code under test.

use std::f64::consts::{FRAC_PI_2, PI};

use cable_dict::geometry::{
    ConnectError, ConnectedGeometry, HermiteCurve, connect, double_reflection,
};
use cable_dict::pose::Pose;
use nalgebra::{
    Isometry3, Matrix3, Point3, Rotation3, Translation3, Unit, UnitQuaternion, Vector3,
};

const PITCH: f64 = 0.01;

// ---------------------------------------------------------------- independent helpers

/// Guide pose at `position` whose +z is `tangent` and whose +x is `normal_hint` made
/// orthogonal to it.
fn guide(position: [f64; 3], tangent: [f64; 3], normal_hint: [f64; 3]) -> Pose {
    let z = Vector3::from(tangent).normalize();
    let hint = Vector3::from(normal_hint);
    let x = (hint - hint.dot(&z) * z).normalize();
    let y = z.cross(&x);
    let rotation = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, y, z]));
    Isometry3::from_parts(
        Translation3::from(Vector3::from(position)),
        UnitQuaternion::from_rotation_matrix(&rotation),
    )
}

/// The same guide turned by `angle` about its own +z axis.
fn rolled(pose: &Pose, angle: f64) -> Pose {
    let mut turned = *pose;
    turned.rotation = pose.rotation * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle);
    turned
}

/// The S-bend used by the benchmark: start along +x, end tilted 30° up and rolled 45°.
fn s_bend(length: f64) -> (Pose, Pose) {
    let start = guide([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    let tilt = Rotation3::from_axis_angle(&Vector3::y_axis(), 60f64.to_radians());
    let roll = Rotation3::from_axis_angle(&Vector3::z_axis(), 45f64.to_radians());
    let end = Isometry3::from_parts(
        Translation3::new(0.6 * length, 0.2 * length, 0.1 * length),
        UnitQuaternion::from_rotation_matrix(&(tilt * roll)),
    );
    (start, end)
}

struct Hermite {
    p0: Vector3<f64>,
    v0: Vector3<f64>,
    p1: Vector3<f64>,
    v1: Vector3<f64>,
}

impl Hermite {
    fn from_guides(start: &Pose, end: &Pose) -> Self {
        Self {
            p0: start.translation.vector,
            v0: start.rotation * Vector3::z(),
            p1: end.translation.vector,
            v1: end.rotation * Vector3::z(),
        }
    }

    fn point(&self, alpha: f64, t: f64) -> Vector3<f64> {
        let (t2, t3) = (t * t, t * t * t);
        (2.0 * t3 - 3.0 * t2 + 1.0) * self.p0
            + (t3 - 2.0 * t2 + t) * alpha * self.v0
            + (-2.0 * t3 + 3.0 * t2) * self.p1
            + (t3 - t2) * alpha * self.v1
    }

    fn velocity(&self, alpha: f64, t: f64) -> Vector3<f64> {
        let t2 = t * t;
        (6.0 * t2 - 6.0 * t) * self.p0
            + (3.0 * t2 - 4.0 * t + 1.0) * alpha * self.v0
            + (-6.0 * t2 + 6.0 * t) * self.p1
            + (3.0 * t2 - 2.0 * t) * alpha * self.v1
    }

    fn acceleration(&self, alpha: f64, t: f64) -> Vector3<f64> {
        (12.0 * t - 6.0) * self.p0
            + (6.0 * t - 4.0) * alpha * self.v0
            + (-12.0 * t + 6.0) * self.p1
            + (6.0 * t - 2.0) * alpha * self.v1
    }

    fn speed(&self, alpha: f64, t: f64) -> f64 {
        self.velocity(alpha, t).norm()
    }

    /// Smallest radius of curvature over 2001 samples (m).
    fn min_bend_radius(&self, alpha: f64) -> f64 {
        (0..=2000)
            .map(|i| {
                let t = i as f64 / 2000.0;
                let (v, a) = (self.velocity(alpha, t), self.acceleration(alpha, t));
                v.norm().powi(3) / v.cross(&a).norm()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Arc length by adaptive Simpson with Richardson correction, tolerance 1e-14 m.
    fn arc_length(&self, alpha: f64) -> f64 {
        let f = |t: f64| self.speed(alpha, t);
        let (a, b) = (0.0, 1.0);
        let whole = (b - a) / 6.0 * (f(a) + 4.0 * f(0.5) + f(b));
        simpson(&f, a, b, f(a), f(0.5), f(b), whole, 1e-14, 60)
    }

    /// α ≥ 0 with arc length `target`, by doubling and 200 bisection steps.
    fn alpha_for_length(&self, target: f64) -> f64 {
        let mut hi = target;
        while self.arc_length(hi) < target {
            hi *= 2.0;
        }
        let mut lo = 0.0;
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.arc_length(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// Distance from `node` to the curve: dense sampling, then golden section.
    fn distance_to_curve(&self, alpha: f64, node: &Point3<f64>) -> f64 {
        let distance = |t: f64| (self.point(alpha, t) - node.coords).norm();
        let samples = 4000;
        let best = (0..=samples)
            .map(|i| i as f64 / samples as f64)
            .min_by(|a, b| distance(*a).total_cmp(&distance(*b)))
            .unwrap();
        let (mut lo, mut hi) = (
            (best - 1.0 / samples as f64).max(0.0),
            (best + 1.0 / samples as f64).min(1.0),
        );
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let (x1, x2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
            if distance(x1) < distance(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        distance(0.5 * (lo + hi)).min(distance(best))
    }
}

#[allow(clippy::too_many_arguments)]
fn simpson(
    f: &dyn Fn(f64) -> f64,
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
    whole: f64,
    tol: f64,
    depth: u32,
) -> f64 {
    let m = 0.5 * (a + b);
    let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
    let (flm, frm) = (f(lm), f(rm));
    let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    let delta = left + right - whole;
    if depth == 0 || delta.abs() <= 15.0 * tol {
        return left + right + delta / 15.0;
    }
    simpson(f, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1)
        + simpson(f, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1)
}

/// Largest element difference between two rotation matrices.
fn matrix_gap(a: &Rotation3<f64>, b: &Rotation3<f64>) -> f64 {
    (a.matrix() - b.matrix()).abs().max()
}

fn rotation_of(pose: &Pose) -> Rotation3<f64> {
    pose.rotation.to_rotation_matrix()
}

/// Checks every invariant of a connected geometry against independent computations and
/// returns (worst chord error, worst distance to the curve, worst end-frame gap).
fn check_geometry(
    start: &Pose,
    end: &Pose,
    sub_segments: usize,
    geometry: &ConnectedGeometry,
) -> (f64, f64, f64) {
    let curve = Hermite::from_guides(start, end);
    assert_eq!(geometry.nodes.len(), sub_segments + 1);
    assert_eq!(geometry.frames.len(), sub_segments + 1);
    let chord_error = geometry
        .nodes
        .windows(2)
        .map(|pair| ((pair[1] - pair[0]).norm() - PITCH).abs())
        .fold(0.0, f64::max);
    assert!(chord_error < 1e-9, "chord error {chord_error:e}");
    assert!((geometry.nodes[0].coords - curve.p0).norm() < 1e-9);
    assert!((geometry.nodes[sub_segments].coords - curve.p1).norm() < 1e-9);
    let off_curve = geometry
        .nodes
        .iter()
        .map(|node| curve.distance_to_curve(geometry.alpha_m, node))
        .fold(0.0, f64::max);
    assert!(off_curve < 1e-9, "node off the curve by {off_curve:e}");
    let frame_gap = matrix_gap(&geometry.frames[0], &rotation_of(start)).max(matrix_gap(
        &geometry.frames[sub_segments],
        &rotation_of(end),
    ));
    assert!(
        frame_gap < 1e-9,
        "end frames differ from the guides by {frame_gap:e}"
    );
    for frame in &geometry.frames {
        let m = frame.matrix();
        assert!((m.transpose() * m - Matrix3::identity()).abs().max() < 1e-12);
        assert!((m.determinant() - 1.0).abs() < 1e-12);
    }
    (chord_error, off_curve, frame_gap)
}

// ---------------------------------------------------------------- rotation-minimizing frames

/// Helix of radius `a` and pitch `2πb`, parametrized by arc length `s`.
struct Helix {
    a: f64,
    b: f64,
}

impl Helix {
    fn c(&self) -> f64 {
        (self.a * self.a + self.b * self.b).sqrt()
    }
    fn point(&self, s: f64) -> Point3<f64> {
        let u = s / self.c();
        Point3::new(self.a * u.cos(), self.a * u.sin(), self.b * u)
    }
    fn tangent(&self, s: f64) -> Vector3<f64> {
        let u = s / self.c();
        Vector3::new(-self.a * u.sin(), self.a * u.cos(), self.b) / self.c()
    }
    fn frenet_normal(&self, s: f64) -> Vector3<f64> {
        let u = s / self.c();
        Vector3::new(-u.cos(), -u.sin(), 0.0)
    }
    fn torsion(&self) -> f64 {
        self.b / (self.a * self.a + self.b * self.b)
    }
    /// Closed-form RMF normal: relative to Frenet it turns by `−τ s`.
    fn rmf_normal(&self, s: f64) -> Vector3<f64> {
        let (n, t) = (self.frenet_normal(s), self.tangent(s));
        let binormal = t.cross(&n);
        let theta = -self.torsion() * s;
        theta.cos() * n + theta.sin() * binormal
    }
}

/// Angle error (rad) of the final RMF normal on the helix sampled at `n` steps.
fn helix_final_angle_error(helix: &Helix, length: f64, n: usize) -> f64 {
    let s: Vec<f64> = (0..=n).map(|i| length * i as f64 / n as f64).collect();
    let points: Vec<_> = s.iter().map(|&s| helix.point(s)).collect();
    let tangents: Vec<_> = s
        .iter()
        .map(|&s| Unit::new_normalize(helix.tangent(s)))
        .collect();
    let first = Unit::new_normalize(helix.frenet_normal(0.0));
    let frames = double_reflection(&points, &tangents, first);
    let got = frames[n] * Vector3::x();
    let want = helix.rmf_normal(length);
    let t = helix.tangent(length);
    got.cross(&want).dot(&t).atan2(got.dot(&want)).abs()
}

#[test]
fn rmf_on_a_helix_converges_at_fourth_order() {
    let helix = Helix { a: 0.05, b: 0.02 };
    let length = 2.0 * (2.0 * PI) * helix.c(); // two turns
    let counts = [12, 24, 48, 96];
    let errors: Vec<f64> = counts
        .iter()
        .map(|&n| helix_final_angle_error(&helix, length, n))
        .collect();
    for i in 0..counts.len() - 1 {
        let order = (errors[i] / errors[i + 1]).log2();
        println!(
            "helix RMF: n = {:3} error {:.3e} rad, n = {:3} error {:.3e} rad, order {order:.3}",
            counts[i],
            errors[i],
            counts[i + 1],
            errors[i + 1]
        );
        assert!(order >= 3.5, "observed order {order}");
    }
}

#[test]
fn rmf_keeps_the_frame_on_a_straight_line() {
    let direction = Unit::new_normalize(Vector3::new(0.3, -0.4, 0.8));
    let normal = Unit::new_normalize(direction.cross(&Vector3::x()));
    let points: Vec<_> = (0..50)
        .map(|i| Point3::new(0.1, 0.2, 0.3) + 0.013 * i as f64 * direction.into_inner())
        .collect();
    let frames = double_reflection(&points, &vec![direction; 50], normal);
    let worst = frames
        .iter()
        .map(|f| matrix_gap(f, &frames[0]))
        .fold(0.0, f64::max);
    println!("straight line: worst frame change {worst:.3e}");
    assert!(worst < 1e-12);
    assert!((frames[0] * Vector3::x() - normal.into_inner()).norm() < 1e-12);
    assert!((frames[0] * Vector3::z() - direction.into_inner()).norm() < 1e-12);
}

#[test]
fn rmf_closes_on_a_planar_circle() {
    let (radius, n) = (0.1, 100);
    let angles: Vec<f64> = (0..=n).map(|i| 2.0 * PI * i as f64 / n as f64).collect();
    let points: Vec<_> = angles
        .iter()
        .map(|u| Point3::new(radius * u.cos(), radius * u.sin(), 0.0))
        .collect();
    let tangents: Vec<_> = angles
        .iter()
        .map(|u| Unit::new_normalize(Vector3::new(-u.sin(), u.cos(), 0.0)))
        .collect();
    for first in [
        Vector3::new(-1.0, 0.0, 0.0),
        Vector3::new(0.0, 0.0, 1.0),
        Vector3::new(-1.0, 0.0, 1.0),
    ] {
        let frames = double_reflection(&points, &tangents, Unit::new_normalize(first));
        let gap = matrix_gap(&frames[n], &frames[0]);
        println!("closed circle: start {first:?}, return gap {gap:.3e}");
        assert!(gap < 1e-9);
    }
}

// ---------------------------------------------------------------- tangent scale α

#[test]
fn alpha_matches_an_independent_reference() {
    let cases = [
        // (label, start, end, target length)
        (
            "bend",
            guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            guide([0.2, 0.0, 0.1], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
            0.35,
        ),
        (
            "bend, large alpha",
            guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            guide([0.2, 0.0, 0.1], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
            3.0,
        ),
        (
            "loop, parallel tangents",
            guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            guide([0.1, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            0.4,
        ),
        (
            "hairpin, opposite tangents",
            guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            guide([0.1, 0.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
            0.3,
        ),
        (
            "coincident guides",
            guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            guide([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            0.3,
        ),
    ];
    for (label, start, end, target) in cases {
        let reference = Hermite::from_guides(&start, &end).alpha_for_length(target);
        let alpha = HermiteCurve::between_guides(&start, &end, 0.0)
            .alpha_for_arc_length(target)
            .unwrap();
        let length = HermiteCurve::between_guides(&start, &end, alpha).arc_length();
        println!(
            "alpha {label}: {alpha:.15} m, reference {reference:.15} m, |Δα| {:.2e} m, |L - target| {:.2e} m",
            (alpha - reference).abs(),
            (length - target).abs()
        );
        assert!(
            (alpha - reference).abs() < 1e-9,
            "{label}: {alpha} vs {reference}"
        );
        assert!((length - target).abs() < 1e-12, "{label}: length {length}");
    }
}

// ---------------------------------------------------------------- connect

#[test]
fn nodes_are_rigid_links_on_the_curve_between_the_guides() {
    let cases = [
        ("S-bend 250 mm", 25, s_bend(0.25)),
        ("S-bend 500 mm", 50, s_bend(0.5)),
        (
            "bend 350 mm",
            35,
            (
                guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
                guide([0.2, 0.0, 0.1], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
            ),
        ),
    ];
    for (label, sub_segments, (start, end)) in cases {
        let geometry = connect(&start, &end, sub_segments, PITCH).unwrap();
        let (chord, off_curve, frame) = check_geometry(&start, &end, sub_segments, &geometry);
        // α exceeds the arc-length α by a relative O((lκ)²): the chords are a little shorter
        // than their arcs.
        let alpha_arc =
            Hermite::from_guides(&start, &end).alpha_for_length(sub_segments as f64 * PITCH);
        let relative = (geometry.alpha_m - alpha_arc) / alpha_arc;
        println!(
            "{label}: chord error {chord:.2e} m, off curve {off_curve:.2e} m, end frames {frame:.2e}, alpha {:.6} m vs arc-length alpha {alpha_arc:.6} m (+{relative:.2e})",
            geometry.alpha_m
        );
        assert!(relative > 0.0 && relative < 0.05, "{label}: {relative}");
    }
}

#[test]
fn a_straight_cable_between_aligned_guides_keeps_its_frame() {
    let start = guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let end = guide([0.0, 0.0, 40.0 * PITCH], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let geometry = connect(&start, &end, 40, PITCH).unwrap();
    check_geometry(&start, &end, 40, &geometry);
    assert_eq!(geometry.alpha_m, 0.0);
    for (k, node) in geometry.nodes.iter().enumerate() {
        assert!((node.coords - Vector3::new(0.0, 0.0, k as f64 * PITCH)).norm() < 1e-12);
    }
    let worst = geometry
        .frames
        .iter()
        .map(|f| matrix_gap(f, &rotation_of(&start)))
        .fold(0.0, f64::max);
    assert!(worst < 1e-12);
}

#[test]
fn end_frames_match_the_guides_also_when_twisted() {
    // Planar bend in the x–z plane with the guide normals along ±y: the RMF keeps +y, so the
    // twist to correct is exactly the end guide's roll.
    let start = guide([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let end = guide([0.2, 0.0, 0.1], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]);
    let (s_start, s_end) = s_bend(0.5);
    let cases = [
        ("planar, untwisted", start, end, Some(0.0), 30),
        (
            "planar, rolled 90°",
            start,
            rolled(&end, FRAC_PI_2),
            Some(FRAC_PI_2),
            30,
        ),
        (
            "planar, rolled -90°",
            start,
            rolled(&end, -FRAC_PI_2),
            Some(-FRAC_PI_2),
            30,
        ),
        (
            "planar, rolled π - 1e-6",
            start,
            rolled(&end, PI - 1e-6),
            Some(PI - 1e-6),
            30,
        ),
        (
            "planar, rolled -π + 1e-6",
            start,
            rolled(&end, -PI + 1e-6),
            Some(-PI + 1e-6),
            30,
        ),
        ("planar, rolled π", start, rolled(&end, PI), None, 30),
        ("S-bend", s_start, s_end, None, 50),
        (
            "S-bend rolled 90°",
            s_start,
            rolled(&s_end, FRAC_PI_2),
            None,
            50,
        ),
    ];
    for (label, start, end, expected_twist, sub_segments) in cases {
        let geometry = connect(&start, &end, sub_segments, PITCH).unwrap();
        let (_, _, frame_gap) = check_geometry(&start, &end, sub_segments, &geometry);
        let twist = geometry.twist_correction_rad;
        println!("{label}: twist {twist:.12} rad, end-frame gap {frame_gap:.2e}");
        assert!(twist > -PI && twist <= PI);
        match expected_twist {
            Some(expected) => assert!(
                (twist - expected).abs() < 1e-9,
                "{label}: {twist} vs {expected}"
            ),
            None if label.contains("π") => assert!((twist.abs() - PI).abs() < 1e-9),
            None => {}
        }
    }
}

#[test]
fn twist_is_distributed_linearly_about_the_tangents() {
    let start = guide([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let end = rolled(
        &guide([0.2, 0.0, 0.1], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        1.0,
    );
    let geometry = connect(&start, &end, 30, PITCH).unwrap();
    // In this planar case the untwisted normal is +y everywhere; frame k is rolled by k/30 rad.
    for (k, frame) in geometry.frames.iter().enumerate() {
        let (normal, tangent) = (frame * Vector3::x(), frame * Vector3::z());
        let roll = Vector3::y()
            .cross(&normal)
            .dot(&tangent)
            .atan2(Vector3::y().dot(&normal));
        assert!((roll - k as f64 / 30.0).abs() < 1e-9, "frame {k}: {roll}");
    }
}

#[test]
fn guides_too_far_apart_are_reported_with_the_needed_stretch() {
    let start = guide([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    let end = guide([0.5, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    let error = connect(&start, &end, 40, PITCH).unwrap_err();
    match &error {
        ConnectError::TooShort {
            distance_m,
            natural_length_m,
            required_stretch,
        } => {
            assert!((distance_m - 0.5).abs() < 1e-12);
            assert!((natural_length_m - 0.4).abs() < 1e-12);
            assert!((required_stretch - 1.25).abs() < 1e-12);
        }
        other => panic!("expected TooShort, got {other:?}"),
    }
    let message = error.to_string();
    assert!(
        message.contains("500.0 mm") && message.contains("400.0 mm") && message.contains("1.250"),
        "{message}"
    );
}

#[test]
fn a_u_loop_with_both_tangents_down_converges() {
    let start = guide([0.0; 3], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]);
    let end = guide([0.1, 0.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]);
    let geometry = connect(&start, &end, 40, PITCH).unwrap();
    let (chord, off_curve, frame) = check_geometry(&start, &end, 40, &geometry);
    println!(
        "U-loop: alpha {:.6} m, chord error {chord:.2e} m, off curve {off_curve:.2e} m, end frames {frame:.2e}",
        geometry.alpha_m
    );
}

#[test]
fn loops_and_coincident_guides_connect() {
    let cases = [
        (
            "coincident guides, crossed tangents",
            guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            guide([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ),
        (
            "hairpin",
            guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            guide([0.1, 0.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
        ),
        (
            "side by side, skew tangents",
            guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            guide([0.1, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
        ),
    ];
    for (label, start, end) in cases {
        let geometry = connect(&start, &end, 40, PITCH).unwrap_or_else(|e| panic!("{label}: {e}"));
        let (chord, off_curve, frame) = check_geometry(&start, &end, 40, &geometry);
        println!(
            "{label}: alpha {:.6} m, chord error {chord:.2e}, off curve {off_curve:.2e}, end frames {frame:.2e}",
            geometry.alpha_m
        );
    }
    // A folded straight line (coincident guides, equal tangents) has cusps: any outcome but
    // a panic is acceptable.
    let folded = guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let _ = connect(&folded, &folded, 40, PITCH);
}

#[test]
fn invalid_input_is_rejected_without_panicking() {
    let (start, end) = s_bend(0.5);
    let invalid = |result: Result<ConnectedGeometry, ConnectError>| {
        matches!(result, Err(ConnectError::InvalidInput { .. }))
    };
    assert!(invalid(connect(&start, &end, 0, PITCH)));
    for pitch in [0.0, -0.01, f64::NAN, f64::INFINITY] {
        assert!(invalid(connect(&start, &end, 50, pitch)), "pitch {pitch}");
    }
    let mut nan_position = end;
    nan_position.translation.vector.x = f64::NAN;
    assert!(invalid(connect(&start, &nan_position, 50, PITCH)));
    let mut nan_rotation = start;
    nan_rotation.rotation =
        UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(f64::NAN, 0.0, 0.0, 0.0));
    assert!(invalid(connect(&nan_rotation, &end, 50, PITCH)));
    let mut infinite = start;
    infinite.translation.vector.z = f64::INFINITY;
    assert!(invalid(connect(&infinite, &end, 50, PITCH)));
    assert!(invalid(connect(&start, &end, usize::MAX, PITCH)));
}

/// Deterministic pseudo-random guide pairs: every call either connects with all invariants,
/// reports TooShort exactly when the guides are farther apart than the cable, or — only for
/// curves that bend tighter than the pitch, where the discrete length can jump — NoSolution.
#[test]
fn random_guide_pairs_connect_or_report_too_short() {
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let (mut connected, mut too_short, mut kinked) = (0, 0, 0);
    for _ in 0..200 {
        let sub_segments = 5 + ((next() + 1.0) * 30.0) as usize;
        let position = [0.3 * next(), 0.3 * next(), 0.3 * next()];
        let start = guide([0.0; 3], [next(), next(), next()], [next(), next(), next()]);
        let end = guide(position, [next(), next(), next()], [next(), next(), next()]);
        let distance = Vector3::from(position).norm();
        match connect(&start, &end, sub_segments, PITCH) {
            Ok(geometry) => {
                check_geometry(&start, &end, sub_segments, &geometry);
                connected += 1;
            }
            Err(ConnectError::TooShort { .. }) => {
                assert!(distance > sub_segments as f64 * PITCH);
                too_short += 1;
            }
            Err(ConnectError::NoSolution { reason }) => {
                let reference = Hermite::from_guides(&start, &end);
                let alpha_arc = reference.alpha_for_length(sub_segments as f64 * PITCH);
                let radius = reference.min_bend_radius(alpha_arc);
                println!(
                    "no solution, min bend radius {:.2} mm: {reason}",
                    radius * 1e3
                );
                assert!(radius < PITCH, "{reason}");
                kinked += 1;
            }
            Err(other) => panic!("{other}"),
        }
    }
    println!(
        "random pairs: {connected} connected, {too_short} too short, {kinked} bent tighter than the pitch"
    );
    assert!(connected > 100);
}

/// Coaxial guides with slack: the Hermite curve stays on their axis, so it can only take the
/// extra length by folding back on itself. The result is either such a folded rigid chain or
/// a NoSolution that says so — a known limit of the Hermite family, reported, not hidden.
#[test]
fn coaxial_guides_with_slack_fold_or_report_the_fold() {
    let start = guide([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    for distance in [0.39, 0.35, 0.3] {
        let end = guide([0.0, 0.0, distance], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        match connect(&start, &end, 40, PITCH) {
            Ok(geometry) => {
                check_geometry(&start, &end, 40, &geometry);
                let off_axis = geometry
                    .nodes
                    .iter()
                    .map(|n| n.x.hypot(n.y))
                    .fold(0.0, f64::max);
                println!(
                    "coaxial {distance} m: folded chain, alpha {:.4} m",
                    geometry.alpha_m
                );
                assert!(off_axis < 1e-12);
            }
            Err(ConnectError::NoSolution { reason }) => {
                println!("coaxial {distance} m: {reason}");
                assert!(reason.contains("folds back"), "{reason}");
            }
            Err(other) => panic!("{other}"),
        }
    }
}
