//! A one-joint robot written for closed-form checks: a spindle turning about the vertical
//! axis under a fixed base, with no geometry (nothing to touch), and the setups, cables and
//! motions the tests build on it.

use cable_dict::motion::Motion;
use cable_dict::motion_test::{MotionTestOptions, MotionTestReport, run};
use cable_dict::path::CablePath;
use cable_dict::setup::Setup;
use std::path::Path;

/// One revolute joint about z: `base` (fixed) and `spindle`. No geometry: nothing to touch.
const SPINDLE_URDF: &str = r#"<robot name="spindle">
  <link name="base"/>
  <link name="spindle"/>
  <joint name="turn" type="revolute">
    <parent link="base"/>
    <child link="spindle"/>
    <origin xyz="0 0 0" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-3.1" upper="3.1" effort="10" velocity="3"/>
  </joint>
</robot>
"#;

/// An 8 mm cable whose datasheet states both radii and a torsion limit (`{fixed}`,
/// `{flexing}` mm, `{torsion}` deg/m).
pub fn cable_text(fixed_mm: f64, flexing_mm: f64, torsion_deg_per_m: f64) -> String {
    format!(
        "name = \"test cable\"\n\
         diameter_mm = 8.0\n\
         mass_per_length_kg_m = 0.1\n\
         bending_stiffness_n_m2 = 6.0e-3\n\
         torsion_stiffness_n_m2 = 7.8e-3\n\
         min_bend_radius_fixed_mm = {fixed_mm}\n\
         min_bend_radius_flexing_mm = {flexing_mm}\n\
         torsion_limit_deg_per_m = {torsion_deg_per_m}\n"
    )
}

/// A setup on the spindle with two guides (one configuration each, `start` and `end`:
/// `link`, position in mm, rpy in degrees) and one segment of `length` sub-segments, in
/// `dir`, its cable stating the limits given.
pub fn spindle_setup(
    dir: &Path,
    start: (&str, [f64; 3], [f64; 3]),
    end: (&str, [f64; 3], [f64; 3]),
    length: usize,
    cable: &str,
) -> Setup {
    let path = spindle_setup_file(dir, start, end, length, cable, "");
    Setup::from_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The file [`spindle_setup`] writes, with `end_keys` (lines) added to the end guide's
/// table, e.g. `kind = "rotating"`; its path.
pub fn spindle_setup_file(
    dir: &Path,
    start: (&str, [f64; 3], [f64; 3]),
    end: (&str, [f64; 3], [f64; 3]),
    length: usize,
    cable: &str,
    end_keys: &str,
) -> std::path::PathBuf {
    std::fs::write(dir.join("spindle.urdf"), SPINDLE_URDF).unwrap();
    std::fs::write(dir.join("cable.toml"), cable).unwrap();
    let guide = |name: &str, (link, xyz, rpy): (&str, [f64; 3], [f64; 3])| {
        format!(
            "[[guides]]\nname = \"{name}\"\nlink = \"{link}\"\nconfigurations = [\n  \
             {{ name = \"only\", position_mm = {xyz:?}, rpy_deg = {rpy:?} }},\n]\n"
        )
    };
    let text = format!(
        "robot = \"spindle.urdf\"\ncable = \"cable.toml\"\ngravity_m_s2 = [0.0, 0.0, -9.81]\n\
         max_guides_per_link = 2\ninstall_joints_deg = [0.0]\n\n{}\n{}\n{}\n\
         [[segments]]\nfrom = \"G1\"\nto = \"G2\"\n\
         lengths = {{ min = {length}, max = {length}, step = 1, allow_zero = false }}\n",
        crate::common::limits("\"cable\""),
        guide("G1", start),
        guide("G2", end) + end_keys,
    );
    let path = dir.join("setup.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// A straight cable of 40 sub-segments (0.4 m) hanging from the base along the axis to the
/// spindle, both clamps pointing down the cable.
pub fn hanging_straight(dir: &Path, cable: &str) -> Setup {
    let down = [180.0, 0.0, 0.0];
    spindle_setup(
        dir,
        ("base", [0.0, 0.0, 400.0], down),
        ("spindle", [0.0, 0.0, 0.0], down),
        40,
        cable,
    )
}

/// The spindle turning from 0 to `to_deg` in `duration_s`, then held as long again.
pub fn turning(setup: &Setup, to_deg: f64, duration_s: f64) -> Motion {
    let to = to_deg.to_radians();
    Motion::new(
        &setup.robot,
        vec![0.0, duration_s, 2.0 * duration_s],
        vec![vec![0.0], vec![to], vec![to]],
    )
    .unwrap()
}

pub fn motion_test(setup: &Setup, length: usize, motion: &Motion) -> MotionTestReport {
    let path = CablePath::through_every_guide(vec![length], vec![0, 0]);
    run(setup, &path, motion, &MotionTestOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}
