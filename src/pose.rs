//! Rigid poses and the URDF orientation convention.
//!
//! A pose maps coordinates in a local frame (a link, a guide, a cable node) to the parent
//! frame: `x_parent = pose * x_local`. Orientations are given as URDF roll–pitch–yaw, i.e.
//! `R = Rz(yaw) · Ry(pitch) · Rx(roll)` about the fixed parent axes.

use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};

/// A rigid transform (metres) from a local frame to its parent frame.
pub type Pose = Isometry3<f64>;

/// Rotation `Rz(yaw) · Ry(pitch) · Rx(roll)` (radians), the URDF `rpy` convention.
pub fn rotation_from_rpy(roll: f64, pitch: f64, yaw: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::z_axis(), yaw)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), pitch)
        * Rotation3::from_axis_angle(&Vector3::x_axis(), roll)
}

/// Pose from a position in metres and URDF roll–pitch–yaw in radians.
pub fn pose_from_xyz_rpy(xyz_m: [f64; 3], rpy_rad: [f64; 3]) -> Pose {
    let rotation = rotation_from_rpy(rpy_rad[0], rpy_rad[1], rpy_rad[2]);
    Isometry3::from_parts(
        Translation3::new(xyz_m[0], xyz_m[1], xyz_m[2]),
        UnitQuaternion::from_rotation_matrix(&rotation),
    )
}

/// Pose from a position in millimetres and URDF roll–pitch–yaw in degrees — the units people
/// type on the command line and in setup files.
pub fn pose_from_mm_deg(xyz_mm: [f64; 3], rpy_deg: [f64; 3]) -> Pose {
    pose_from_xyz_rpy(xyz_mm.map(|v| v * 1e-3), rpy_deg.map(f64::to_radians))
}

/// The rotation of a pose as a row-major 3×3 matrix (maps local to parent coordinates).
pub fn rotation_rows(pose: &Pose) -> [[f64; 3]; 3] {
    matrix_rows(&pose.rotation.to_rotation_matrix())
}

/// A rotation as a row-major 3×3 matrix.
pub fn matrix_rows(rotation: &Rotation3<f64>) -> [[f64; 3]; 3] {
    let m = rotation.matrix();
    [0, 1, 2].map(|r| [m[(r, 0)], m[(r, 1)], m[(r, 2)]])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The URDF convention written out element by element (REP 103 / urdfdom `setRPY`),
    /// independent of nalgebra's axis–angle composition.
    fn rpy_closed_form(r: f64, p: f64, y: f64) -> [[f64; 3]; 3] {
        let (sr, cr) = r.sin_cos();
        let (sp, cp) = p.sin_cos();
        let (sy, cy) = y.sin_cos();
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    }

    #[test]
    fn rpy_matches_the_urdf_closed_form() {
        for &(r, p, y) in &[(0.3, -1.1, 2.5), (-2.9, 0.2, -0.7), (1.0, 1.5, 3.1)] {
            let got = matrix_rows(&rotation_from_rpy(r, p, y));
            let want = rpy_closed_form(r, p, y);
            for i in 0..3 {
                for j in 0..3 {
                    assert!((got[i][j] - want[i][j]).abs() < 1e-14, "({i},{j})");
                }
            }
        }
    }

    #[test]
    fn mm_deg_pose_converts_units() {
        let pose = pose_from_mm_deg([100.0, -20.0, 5.0], [0.0, 0.0, 90.0]);
        assert!((pose.translation.vector - Vector3::new(0.1, -0.02, 0.005)).norm() < 1e-15);
        let x = pose.rotation * Vector3::x();
        assert!((x - Vector3::y()).norm() < 1e-15);
    }
}
