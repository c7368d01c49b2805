//! The bundled Viper s850 URDF against the standard-DH closed form of the Viper s850.
//!
//! The reference is computed here from the DH table alone, with its own 4×4 matrices, so it
//! shares nothing with the URDF loader or the forward kinematics under test.

use cable_dict::robot::Robot;
use nalgebra::{Matrix3, Matrix4, Vector3};

const URDF: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/robots/viper_s850/viper_s850.urdf"
);

/// Standard DH rows (d mm, a mm, alpha deg) of the Viper s850; theta_i = q_i, no offsets.
const DH: [(f64, f64, f64); 6] = [
    (335.0, 75.0, -90.0),
    (0.0, 365.0, 0.0),
    (0.0, -90.0, 90.0),
    (405.0, 0.0, -90.0),
    (0.0, 0.0, 90.0),
    (80.0, 0.0, 0.0),
];

/// Published joint ranges (deg).
const LIMITS_DEG: [(f64, f64); 6] = [
    (-170.0, 170.0),
    (-190.0, 45.0),
    (-29.0, 256.0),
    (-190.0, 190.0),
    (-120.0, 120.0),
    (-360.0, 360.0),
];

/// `Rz(theta) · Tz(d) · Tx(a) · Rx(alpha)` written out.
fn dh_matrix(theta: f64, d: f64, a: f64, alpha: f64) -> Matrix4<f64> {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    Matrix4::new(
        ct,
        -st * ca,
        st * sa,
        a * ct, //
        st,
        ct * ca,
        -ct * sa,
        a * st, //
        0.0,
        sa,
        ca,
        d, //
        0.0,
        0.0,
        0.0,
        1.0,
    )
}

fn dh_flange(q: &[f64; 6]) -> Matrix4<f64> {
    q.iter()
        .zip(DH)
        .fold(Matrix4::identity(), |t, (&theta, (d, a, alpha))| {
            t * dh_matrix(theta, d * 1e-3, a * 1e-3, alpha.to_radians())
        })
}

/// Angle of a rotation matrix, from `atan2(sin, cos)` — unlike `acos` of the trace it stays
/// accurate near zero, where the comparison is made.
fn rotation_angle(r: &Matrix3<f64>) -> f64 {
    let axis_times_sin = Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    );
    (axis_times_sin.norm() / 2.0).atan2((r.trace() - 1.0) / 2.0)
}

/// Deterministic pseudo-random numbers in [0, 1) (xorshift64*), so failures reproduce.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn configurations() -> Vec<[f64; 6]> {
    let lower = LIMITS_DEG.map(|(l, _)| l.to_radians());
    let upper = LIMITS_DEG.map(|(_, u)| u.to_radians());
    let mut configs = vec![
        [0.0; 6],
        lower,
        upper,
        std::array::from_fn(|i| if i % 2 == 0 { lower[i] } else { upper[i] }),
        std::array::from_fn(|i| if i % 2 == 1 { lower[i] } else { upper[i] }),
        [0.0, -90f64.to_radians(), 180f64.to_radians(), 0.0, 0.0, 0.0],
    ];
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for _ in 0..10 {
        configs.push(std::array::from_fn(|i| {
            lower[i] + (upper[i] - lower[i]) * rng.next()
        }));
    }
    configs
}

#[test]
fn flange_pose_equals_the_dh_closed_form() {
    let robot = Robot::from_urdf_file(URDF).expect("bundled URDF loads");
    let tool0 = robot.link_index("tool0").expect("tool0 exists");
    let configs = configurations();
    assert!(configs.len() >= 12);
    let (mut worst_position, mut worst_angle) = (0.0_f64, 0.0_f64);
    for q in &configs {
        robot
            .check_limits(q)
            .expect("test configurations are within limits");
        let pose = robot.link_poses(q).expect("6 joints")[tool0];
        let reference = dh_flange(q);
        let position_error = (pose.translation.vector - reference.fixed_view::<3, 1>(0, 3)).norm();
        let rotation: Matrix3<f64> = reference.fixed_view::<3, 3>(0, 0).into();
        let relative = pose.rotation.to_rotation_matrix().matrix().transpose() * rotation;
        let angle = rotation_angle(&relative);
        worst_position = worst_position.max(position_error);
        worst_angle = worst_angle.max(angle);
        assert!(
            position_error < 1e-9,
            "q = {q:?}: position off by {position_error} m"
        );
        assert!(angle < 1e-9, "q = {q:?}: orientation off by {angle} rad");
    }
    println!(
        "worst over {} configurations: {worst_position:e} m, {worst_angle:e} rad",
        configs.len()
    );
}

#[test]
fn urdf_limits_are_the_published_ranges() {
    let robot = Robot::from_urdf_file(URDF).expect("bundled URDF loads");
    assert_eq!(robot.dof(), 6);
    for (i, (lower, upper)) in LIMITS_DEG.iter().enumerate() {
        let joint = robot.actuated_joint(i);
        assert_eq!(joint.name, format!("joint_{}", i + 1));
        let limits = joint.limits.expect("revolute joints have limits");
        assert!(
            (limits.lower.to_degrees() - lower).abs() < 1e-9,
            "{}",
            joint.name
        );
        assert!(
            (limits.upper.to_degrees() - upper).abs() < 1e-9,
            "{}",
            joint.name
        );
    }
}

#[test]
fn zero_pose_matches_the_described_posture() {
    let robot = Robot::from_urdf_file(URDF).expect("bundled URDF loads");
    let poses = robot.link_poses(&[0.0; 6]).expect("6 joints");
    let origin = |name: &str| {
        poses[robot.link_index(name).expect("link exists")]
            .translation
            .vector
    };
    let upper_arm = origin("link_3") - origin("link_2");
    let forearm = origin("link_5") - origin("link_4");
    assert!(
        upper_arm.normalize().dot(&Vector3::x()) > 1.0 - 1e-12,
        "upper arm along +X"
    );
    assert!(
        forearm.normalize().dot(&Vector3::z()) > 1.0 - 1e-12,
        "forearm along +Z"
    );
    let flange = poses[robot.link_index("tool0").expect("tool0 exists")];
    assert!(
        (flange.rotation * Vector3::z() - Vector3::z()).norm() < 1e-12,
        "flange faces +Z"
    );
    // Flange position from the DH table alone: x = a1 + a2 + a3, z = d1 + d4 + d6.
    let expected = Vector3::new(0.075 + 0.365 - 0.090, 0.0, 0.335 + 0.405 + 0.080);
    assert!((flange.translation.vector - expected).norm() < 1e-12);
}

#[test]
fn every_arm_link_has_collision_geometry() {
    let robot = Robot::from_urdf_file(URDF).expect("bundled URDF loads");
    for name in [
        "base_link",
        "link_1",
        "link_2",
        "link_3",
        "link_4",
        "link_5",
        "link_6",
    ] {
        let link = &robot.links[robot.link_index(name).expect("link exists")];
        assert!(!link.colliders.is_empty(), "{name} has no collision shape");
    }
}
