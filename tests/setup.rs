//! Setup files: the bundled Viper s850 setups (candidate counts worked out by hand, guides
//! clear of the robot by elementary geometry), every refusal of a broken setup with its file,
//! line and key, and the content hash's stability.

use crate::common::{self, root};
use cable_dict::pose::Pose;
use cable_dict::robot::{Robot, Shape};
use cable_dict::setup::{BendRadiusSource, ConfigurationOrigin, Setup};
use nalgebra::{Point3, Vector2, Vector3};
use std::path::{Path, PathBuf};

fn bundled(name: &str) -> Setup {
    let path = root().join("robots/viper_s850/hand_written").join(name);
    Setup::from_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

// ---------------------------------------------------------------------------------------------
// Bundled setups
// ---------------------------------------------------------------------------------------------

#[test]
fn bundled_setups_have_the_papers_guide_layout() {
    for (file, cable_name, radius_m) in [
        ("pick_and_place.toml", "SMC", 0.048),
        ("inspection.toml", "GEV", 0.060),
    ] {
        let setup = bundled(file);
        let link = |g: usize| setup.robot.links[setup.guides[g].link].name.clone();
        let names: Vec<&str> = setup.guides.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["G1", "G2", "G3", "G4", "G5"], "{file}");
        let links: Vec<String> = (0..5).map(link).collect();
        assert_eq!(
            links,
            ["link_3", "link_4", "link_4", "link_6", "link_6"],
            "{file}"
        );
        let fixed: Vec<bool> = setup.guides.iter().map(|g| g.fixed).collect();
        assert_eq!(fixed, [false, false, false, false, true], "{file}");
        let intra: Vec<bool> = (0..4).map(|m| setup.is_intra_link(m)).collect();
        assert_eq!(intra, [false, true, false, true], "{file}");
        assert!(setup.cable.name.contains(cable_name), "{file}");
        assert_eq!(setup.gravity_m_s2, Vector3::new(0.0, 0.0, -9.81));
        let t = setup.thresholds;
        assert_eq!(t.min_bend_radius_source, BendRadiusSource::Cable);
        assert!((t.min_bend_radius_m - radius_m).abs() < 1e-15, "{file}");
        assert_eq!((t.contact_clearance_m, t.stretch), (0.0, 1.02));
        assert_eq!(
            (setup.robustness.delta_s, setup.robustness.range),
            (1, 2),
            "{file}"
        );
        for guide in &setup.guides[..4] {
            let declared = declared_count(guide);
            assert!((4..=8).contains(&declared), "{file} {}", guide.name);
        }
        // The raw texts are kept verbatim.
        let read = |path: &Path| std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(setup.text, read(&setup.source));
        assert_eq!(setup.robot_text, read(&setup.robot_path));
        assert_eq!(setup.cable_text, read(&setup.cable_path));
        let robot_path = setup
            .robot_path
            .canonicalize()
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(robot_path.ends_with("robots/viper_s850/viper_s850.urdf"));
    }
}

fn declared_count(guide: &cable_dict::setup::Guide) -> usize {
    guide
        .configurations
        .iter()
        .filter(|c| matches!(c.origin, ConfigurationOrigin::Declared { .. }))
        .count()
}

#[test]
fn d0_sizes_are_the_products_worked_out_by_hand() {
    // Lengths per segment (sub-segments): pick and place C1 45..=75, C2 {0} ∪ 14..=34,
    // C3 32..=64, C4 {0} ∪ 12..=32; inspection C1 5..=60, C2 {0} ∪ 2..=30, C3 8..=70,
    // C4 {0} ∪ 4..=35.
    // Configurations: pick and place G1 7, G2 4, G3 8 + 4 copies of G2 (S2 = 0); inspection
    // G1 7, G2 6, G3 6 + 6 copies of G2; both G4 6 + the connector (S4 = 0), G5 1.
    for (file, [l1, l2, l3, l4], [g1, g2, g3, g4, g5]) in [
        (
            "pick_and_place.toml",
            [31, 1 + 21, 33, 1 + 21],
            [7, 4, 8 + 4, 6 + 1, 1],
        ),
        (
            "inspection.toml",
            [56, 1 + 29, 63, 1 + 32],
            [7, 6, 6 + 6, 6 + 1, 1],
        ),
    ] {
        let setup = bundled(file);
        let counts: Vec<usize> = setup
            .guides
            .iter()
            .map(|g| g.configurations.len())
            .collect();
        assert_eq!(counts, [g1, g2, g3, g4, g5], "{file}");
        let want = [l1 * g1 * g2, l2 * g2 * g3, l3 * g3 * g4, l4 * g4 * g5];
        let got: Vec<usize> = (0..4).map(|m| setup.pv_count(m)).collect();
        assert_eq!(got, want, "{file}");
        // Admissible: S = 0 only for a configuration and its copy (one pair per G2
        // configuration on C2, 1 on C4), S > 0 for every other pair.
        let admissible = [
            l1 * g1 * g2,
            g2 + (l2 - 1) * (g2 * g3 - g2),
            l3 * g3 * g4,
            1 + (l4 - 1) * (g4 * g5 - 1),
        ];
        let got: Vec<usize> = (0..4).map(|m| setup.admissible_pv_count(m)).collect();
        assert_eq!(got, admissible, "{file}");
    }
}

#[test]
fn s_zero_is_a_configuration_paired_with_its_coincident_copy() {
    let setup = bundled("pick_and_place.toml");
    let (g2, g3, g4) = (&setup.guides[1], &setup.guides[2], &setup.guides[3]);
    // G3 ends with a copy of each G2 configuration (after its 8 declared ones), same pose in
    // the shared link frame.
    for (c, original) in g2.configurations.iter().enumerate() {
        let copy = &g3.configurations[8 + c];
        assert_eq!(copy.name, format!("G2/{}", original.name));
        assert_eq!(
            copy.origin,
            ConfigurationOrigin::Coincident {
                guide: 1,
                configuration: c
            }
        );
        assert!((copy.pose.translation.vector - original.pose.translation.vector).norm() < 1e-15);
        assert!(setup.is_admissible(1, 0, c, 8 + c));
        assert!(!setup.is_admissible(1, 5, c, 8 + c));
        assert!(!setup.is_admissible(1, 0, c, 0));
    }
    // G4's last configuration is the fixed connector of G5.
    let connector = g4.configurations.last().unwrap_or_else(|| panic!("empty"));
    assert_eq!(connector.name, "G5/gripper connector");
    assert_eq!(connector.position_mm, [60.0, 0.0, 85.0]);
    assert!(setup.is_admissible(3, 0, 6, 0));
    assert!(!setup.is_admissible(3, 0, 0, 0));
    // Inter-link segments never list S = 0.
    assert!(setup.segments[0].lengths.iter().all(|&s| s > 0));
    assert!(setup.segments[2].lengths.iter().all(|&s| s > 0));
    assert_eq!(setup.segments[1].lengths[..3], [0, 14, 15]);
}

#[test]
fn inter_link_only_keeps_s_zero_on_intra_link_segments() {
    let setup = bundled("pick_and_place.toml");
    let method1 = setup.inter_link_only().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(method1.segments[1].lengths, [0]);
    assert_eq!(method1.segments[3].lengths, [0]);
    assert_eq!(method1.segments[0].lengths, setup.segments[0].lengths);
    assert_ne!(method1.content_hash, setup.content_hash);
}

// ---------------------------------------------------------------------------------------------
// Guides are outside the robot
// ---------------------------------------------------------------------------------------------

/// Signed distance (m) from a point to a collision shape, in the shape's frame.
fn shape_distance(shape: &Shape, p: &Point3<f64>) -> f64 {
    match shape {
        Shape::Box { half_extents_m: h } => {
            let q = p.coords.abs() - h;
            q.map(|v| v.max(0.0)).norm() + q.max().min(0.0)
        }
        Shape::Cylinder { radius_m, length_m } => {
            let q = Vector2::new(p.xy().coords.norm() - radius_m, p.z.abs() - length_m / 2.0);
            q.map(|v| v.max(0.0)).norm() + q.max().min(0.0)
        }
        Shape::Sphere { radius_m } => p.coords.norm() - radius_m,
        Shape::Capsule { radius_m, length_m } => {
            let z = p.z.clamp(-length_m / 2.0, length_m / 2.0);
            (p.coords - Vector3::new(0.0, 0.0, z)).norm() - radius_m
        }
        Shape::Mesh(_) => panic!("the bundled robot has no meshes"),
    }
}

/// The smallest signed distance from a world point to any collider, with the link's name.
fn robot_distance(robot: &Robot, link_poses: &[Pose], point: &Point3<f64>) -> (f64, String) {
    let mut nearest = (f64::INFINITY, String::new());
    for (link, pose) in robot.links.iter().zip(link_poses) {
        for collider in &link.colliders {
            let local = (pose * collider.origin).inverse_transform_point(point);
            let d = shape_distance(&collider.shape, &local);
            if d < nearest.0 {
                nearest = (d, link.name.clone());
            }
        }
    }
    nearest
}

#[test]
fn point_distances_match_hand_values() {
    let cube = Shape::Box {
        half_extents_m: Vector3::new(1.0, 2.0, 3.0),
    };
    assert!((shape_distance(&cube, &Point3::new(4.0, 0.0, 0.0)) - 3.0).abs() < 1e-15);
    assert!((shape_distance(&cube, &Point3::new(4.0, 6.0, 3.0)) - 5.0).abs() < 1e-15);
    assert!((shape_distance(&cube, &Point3::new(0.5, 0.0, 0.0)) + 0.5).abs() < 1e-15);
    let can = Shape::Cylinder {
        radius_m: 1.0,
        length_m: 2.0,
    };
    assert!((shape_distance(&can, &Point3::new(3.0, 4.0, 0.0)) - 4.0).abs() < 1e-15);
    assert!((shape_distance(&can, &Point3::new(0.0, 0.0, 3.0)) - 2.0).abs() < 1e-15);
    assert!((shape_distance(&can, &Point3::new(4.0, 0.0, 5.0)) - 5.0).abs() < 1e-15);
}

/// Every configuration (copies included) of every guide, at the joint vector `q_deg`, is at
/// least `margin` outside every collider.
fn assert_guides_clear(setup: &Setup, q_deg: [f64; 6], margin: f64) {
    let q: Vec<f64> = q_deg.iter().map(|d| d.to_radians()).collect();
    let poses = setup.robot.link_poses(&q).unwrap_or_else(|e| panic!("{e}"));
    for (g, guide) in setup.guides.iter().enumerate() {
        for (c, configuration) in guide.configurations.iter().enumerate() {
            let world = setup.guide_world_pose(&poses, g, c);
            let (d, link) = robot_distance(
                &setup.robot,
                &poses,
                &Point3::from(world.translation.vector),
            );
            assert!(
                d >= margin,
                "{} {} at q = {q_deg:?}: {:.1} mm from {link}",
                guide.name,
                configuration.name,
                d * 1e3
            );
        }
    }
}

#[test]
fn guides_at_the_zero_pose_are_outside_the_robot_by_the_cable_radius() {
    for file in ["pick_and_place.toml", "inspection.toml"] {
        let setup = bundled(file);
        assert_guides_clear(&setup, [0.0; 6], setup.cable.diameter_m / 2.0);
    }
}

#[test]
fn guides_at_working_poses_are_outside_the_robot_by_the_cable_radius() {
    // Tool down over a table in front, to the side, and a wrist turned for inspection.
    let poses = [
        [0.0, -30.0, 120.0, 0.0, 90.0, 0.0],
        [-90.0, -45.0, 135.0, 40.0, 60.0, 90.0],
        [30.0, -20.0, 100.0, -120.0, -70.0, 180.0],
    ];
    for file in ["pick_and_place.toml", "inspection.toml"] {
        let setup = bundled(file);
        for q in poses {
            assert_guides_clear(&setup, q, setup.cable.diameter_m / 2.0);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Refusals
// ---------------------------------------------------------------------------------------------

/// A small valid setup: G1 on link_3, G2 and a fixed G3 on link_4 (S2 may be 0).
fn small_setup() -> String {
    let root = root();
    format!(
        r#"robot = "{robot}"
cable = "{cable}"
gravity_m_s2 = [0.0, 0.0, -9.81]
max_guides_per_link = 2

{limits}
[[guides]]
name = "G1"
link = "link_3"
configurations = [
  {{ name = "back", position_mm = [-172.0, 0.0, 100.0], rpy_deg = [0.0, 0.0, 180.0] }},
  {{ name = "left", position_mm = [-90.0, 82.0, 100.0], rpy_deg = [0.0, 0.0, 90.0] }},
]

[[guides]]
name = "G2"
link = "link_4"
configurations = [
  {{ name = "low", position_mm = [-72.0, 0.0, 60.0], rpy_deg = [0.0, 0.0, 180.0] }},
  {{ name = "high", position_mm = [-72.0, 0.0, 150.0], rpy_deg = [0.0, 0.0, 180.0] }},
]

[[guides]]
name = "G3"
link = "link_4"
fixed = {{ name = "top", position_mm = [-72.0, 0.0, 200.0], rpy_deg = [0.0, 0.0, 180.0] }}

[[segments]]
from = "G1"
to = "G2"
lengths = {{ min = 10, max = 40, step = 1, allow_zero = false }}

[[segments]]
from = "G2"
to = "G3"
lengths = {{ min = 3, max = 20, step = 1, allow_zero = true }}
"#,
        robot = root.join("robots/viper_s850/viper_s850.urdf").display(),
        cable = root.join("cables/smc_le_cp_3_paper.toml").display(),
        limits = common::limits("\"cable\""),
    )
}

/// Writes `text` as `setup.toml` in a fresh temporary folder and loads it.
fn load_text(text: &str) -> (tempfile::TempDir, PathBuf, Result<Setup, String>) {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let path = dir.path().join("setup.toml");
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    let result = Setup::from_file(&path).map_err(|e| e.to_string());
    (dir, path, result)
}

/// 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("`{needle}` not in the text"));
    text[..at].matches('\n').count() + 1
}

/// The small setup with `from` replaced by `to` is refused; the message names the file, the
/// line of `at` (in the broken text) and contains every one of `says`.
fn assert_refused(from: &str, to: &str, at: &str, says: &[&str]) {
    let good = small_setup();
    assert!(good.contains(from), "`{from}` not in the small setup");
    let broken = good.replacen(from, to, 1);
    let (_dir, path, result) = load_text(&broken);
    let message = match result {
        Ok(_) => panic!("accepted with `{from}` → `{to}`"),
        Err(message) => message,
    };
    let place = format!("{}:{}:", path.display(), line_of(&broken, at));
    assert!(
        message.starts_with(&place),
        "`{to}`: expected `{place}` in: {message}"
    );
    for word in says {
        assert!(
            message.contains(word),
            "`{to}`: expected `{word}` in: {message}"
        );
    }
}

#[test]
fn the_small_setup_loads_with_the_expected_sizes() {
    let (_dir, _path, result) = load_text(&small_setup());
    let setup = result.unwrap_or_else(|e| panic!("{e}"));
    // G2 gains the fixed G3 pose (S2 = 0 means G2 is not mounted and the cable runs to G3).
    let counts: Vec<usize> = setup
        .guides
        .iter()
        .map(|g| g.configurations.len())
        .collect();
    assert_eq!(counts, [2, 3, 1]);
    assert_eq!(setup.guides[1].configurations[2].name, "G3/top");
    assert_eq!(setup.pv_count(0), 31 * 2 * 3);
    assert_eq!(setup.pv_count(1), 19 * 3);
    assert_eq!(setup.admissible_pv_count(1), 1 + 18 * 2);
    assert_eq!(setup.segment_guides(1), (1, 2));
}

#[test]
fn unknown_keys_are_refused() {
    assert_refused(
        "max_guides_per_link = 2",
        "max_guides_per_link = 2\ncolour = \"red\"",
        "colour",
        &["unknown field `colour`"],
    );
    assert_refused(
        "stretch = 1.02",
        "stretch = 1.02\nstrech = 1.05",
        "strech",
        &["thresholds: unknown field `strech`"],
    );
    assert_refused(
        "name = \"G2\"",
        "name = \"G2\"\nlnk = \"link_4\"",
        "lnk",
        &["guides[1]: unknown field `lnk`"],
    );
    assert_refused(
        "{ name = \"low\", ",
        "{ name = \"low\", yaw_deg = 3.0, ",
        "yaw_deg",
        &["guides[1]: unknown field `yaw_deg`"],
    );
    assert_refused(
        "allow_zero = false }",
        "allow_zero = false, zero = true }",
        "zero = true",
        &["segments[0]: unknown field `zero`"],
    );
}

#[test]
fn missing_keys_are_refused() {
    assert_refused(
        "stretch = 1.02\n",
        "",
        "[thresholds]",
        &["thresholds: missing field `stretch`"],
    );
    assert_refused(
        "clamp_zone_mm = 20.0\n",
        "",
        "[thresholds]",
        &["missing field `clamp_zone_mm`"],
    );
    assert_refused(
        "gravity_m_s2 = [0.0, 0.0, -9.81]\n",
        "",
        "robot",
        &["missing field `gravity_m_s2`"],
    );
    assert_refused(
        ", rpy_deg = [0.0, 0.0, 90.0] }",
        " }",
        "{ name = \"left\"",
        &["guides[0]: missing field `rpy_deg`"],
    );
    assert_refused(
        "step = 1, allow_zero = false",
        "allow_zero = false",
        "lengths = { min = 10",
        &["segments[0]: missing field `step`"],
    );
    // A guide needs candidates or a fixed pose.
    assert_refused(
        "fixed = { name = \"top\", position_mm = [-72.0, 0.0, 200.0], rpy_deg = [0.0, 0.0, 180.0] }\n",
        "",
        "name = \"G3\"",
        &["guides[2]", "configurations", "fixed"],
    );
    assert_refused(
        "link = \"link_4\"\nfixed",
        "link = \"link_4\"\nconfigurations = [\n  { name = \"x\", position_mm = [0.0, 0.0, 0.0], rpy_deg = [0.0, 0.0, 0.0] },\n]\nfixed",
        "configurations = [\n  { name = \"x\"",
        &["guides[2]", "give one of"],
    );
}

#[test]
fn bad_links_and_guide_order_are_refused() {
    assert_refused(
        "link = \"link_3\"",
        "link = \"link_9\"",
        "link_9",
        &["guides[0].link", "\"link_9\" is not in the robot", "link_6"],
    );
    // G2 on link_2 comes after G1 on link_3: not towards the tool.
    assert_refused(
        "name = \"G2\"\nlink = \"link_4\"",
        "name = \"G2\"\nlink = \"link_2\"",
        "link_2",
        &["guides[1].link", "from the base end"],
    );
    // Three guides on link_4 with at most 2 per link.
    assert_refused(
        "link = \"link_3\"",
        "link = \"link_4\"",
        "link = \"link_4\"\nfixed",
        &[
            "guides[2].link",
            "3 guides (G1, G2, G3) on link_4",
            "max_guides_per_link = 2",
        ],
    );
    assert_refused(
        "max_guides_per_link = 2",
        "max_guides_per_link = 1",
        "link = \"link_4\"\nfixed",
        &["guides[2].link", "max_guides_per_link = 1"],
    );
    assert_refused(
        "max_guides_per_link = 2",
        "max_guides_per_link = 0",
        "max_guides_per_link",
        &["max_guides_per_link", "at least 1"],
    );
}

#[test]
fn bad_configurations_are_refused() {
    assert_refused(
        "configurations = [\n  { name = \"low\", position_mm = [-72.0, 0.0, 60.0], rpy_deg = [0.0, 0.0, 180.0] },\n  { name = \"high\", position_mm = [-72.0, 0.0, 150.0], rpy_deg = [0.0, 0.0, 180.0] },\n]",
        "configurations = []",
        "configurations = []",
        &["guides[1].configurations", "empty"],
    );
    assert_refused(
        "name = \"high\"",
        "name = \"low\"",
        "name = \"low\", position_mm = [-72.0, 0.0, 150.0]",
        &["guides[1].configurations[1].name", "\"low\" is used twice"],
    );
    assert_refused(
        "position_mm = [-72.0, 0.0, 150.0]",
        "position_mm = [-72.0, 0.0, 60.0]",
        "{ name = \"high\"",
        &["guides[1].configurations[1]", "same pose as \"low\""],
    );
    assert_refused(
        "name = \"G3\"",
        "name = \"G2\"",
        "name = \"G2\"\nlink = \"link_4\"\nfixed",
        &["guides[2].name", "\"G2\" is used twice"],
    );
    assert_refused(
        "name = \"left\"",
        "name = \"le/ft\"",
        "le/ft",
        &["guides[0].configurations[1].name", "`/`"],
    );
}

#[test]
fn non_finite_numbers_are_refused() {
    assert_refused(
        "[-90.0, 82.0, 100.0]",
        "[-90.0, nan, 100.0]",
        "nan",
        &["guides[0].configurations[1].position_mm", "finite"],
    );
    assert_refused(
        "rpy_deg = [0.0, 0.0, 90.0]",
        "rpy_deg = [0.0, inf, 90.0]",
        "inf",
        &["guides[0].configurations[1].rpy_deg", "finite"],
    );
    assert_refused(
        "[0.0, 0.0, -9.81]",
        "[0.0, 0.0, -inf]",
        "gravity_m_s2",
        &["gravity_m_s2", "finite"],
    );
    assert_refused(
        "stretch = 1.02",
        "stretch = nan",
        "stretch",
        &["thresholds.stretch", "finite"],
    );
    assert_refused(
        "min_bend_radius_mm = \"cable\"",
        "min_bend_radius_mm = inf",
        "min_bend_radius_mm",
        &["thresholds.min_bend_radius_mm", "finite"],
    );
    assert_refused(
        "clamp_zone_mm = 20.0",
        "clamp_zone_mm = -1.0",
        "clamp_zone_mm",
        &["thresholds.clamp_zone_mm", "≥ 0"],
    );
    assert_refused(
        "clamp_zone_mm = 20.0",
        "clamp_zone_mm = 20.0\nstatic_bend_margin_mm = -0.5",
        "static_bend_margin_mm",
        &["thresholds.static_bend_margin_mm", "≥ 0"],
    );
    assert_refused(
        "[-72.0, 0.0, 200.0]",
        "[-72.0, 0.0, nan]",
        "nan",
        &["guides[2].fixed.position_mm", "finite"],
    );
}

#[test]
fn bad_thresholds_and_robustness_are_refused() {
    assert_refused(
        "min_bend_radius_mm = \"cable\"",
        "min_bend_radius_mm = \"cabel\"",
        "min_bend_radius_mm",
        &["thresholds.min_bend_radius_mm", "\"cabel\"", "\"cable\""],
    );
    assert_refused(
        "stretch = 1.02",
        "stretch = 0.9",
        "stretch",
        &["thresholds.stretch", "≥ 1"],
    );
    assert_refused(
        "[0.0, 0.0, -9.81]",
        "[0.0, 0.0, 0.0]",
        "gravity_m_s2",
        &["gravity_m_s2", "zero"],
    );
    assert_refused(
        "delta_s = 1",
        "delta_s = 0",
        "delta_s",
        &["robustness.delta_s", "at least 1"],
    );
}

#[test]
fn bad_segments_are_refused() {
    // S = 0 across a joint.
    assert_refused(
        "allow_zero = false",
        "allow_zero = true",
        "lengths = { min = 10",
        &["segments[0].lengths.allow_zero", "intra-link", "G1 and G2"],
    );
    // The series does not end on max.
    assert_refused(
        "min = 10, max = 40, step = 1",
        "min = 10, max = 41, step = 2",
        "lengths = { min = 10",
        &["segments[0].lengths.max", "not a multiple of step = 2"],
    );
    // A step that skips the robustness neighbours S ± ΔS.
    assert_refused(
        "min = 10, max = 40, step = 1",
        "min = 10, max = 40, step = 2",
        "lengths = { min = 10",
        &["segments[0].lengths.step", "delta_s = 1"],
    );
    assert_refused(
        "min = 10, max = 40",
        "min = 10, max = 9",
        "lengths = { min = 10",
        &["segments[0].lengths.max", "below min"],
    );
    assert_refused(
        "min = 3, max = 20",
        "min = 0, max = 20",
        "lengths = { min = 0",
        &["segments[1].lengths.min", "allow_zero"],
    );
    assert_refused(
        "min = 10, max = 40, step = 1",
        "min = 10, max = 40, step = 0",
        "lengths = { min = 10",
        &["segments[0].lengths.step", "≥ 1"],
    );
    assert_refused(
        "min = 10, max = 40",
        "min = -10, max = 40",
        "lengths = { min = -10",
        &["-10"],
    );
    // One segment for three guides.
    assert_refused(
        "\n[[segments]]\nfrom = \"G2\"\nto = \"G3\"\nlengths = { min = 3, max = 20, step = 1, allow_zero = true }\n",
        "\n",
        "[[segments]]",
        &["segments", "1 segments given, but 3 guides need exactly 2"],
    );
    assert_refused(
        "from = \"G2\"",
        "from = \"G1\"",
        "from = \"G1\"\nto = \"G3\"",
        &["segments[1].from", "joins guide G2"],
    );
}

#[test]
fn unreadable_robot_and_cable_files_are_refused() {
    let good = small_setup();
    let robot_line = line_of(&good, "robot =");
    let broken = good.replacen("viper_s850.urdf", "missing.urdf", 1);
    let (_dir, path, result) = load_text(&broken);
    let message = result.err().unwrap_or_default();
    assert!(message.starts_with(&format!("{}:{robot_line}: robot:", path.display())));
    assert!(message.contains("missing.urdf"), "{message}");
    let cable_line = line_of(&good, "cable =");
    let broken = good.replacen("smc_le_cp_3_paper.toml", "viper_s850/viper_s850.urdf", 1);
    let broken = broken.replacen("cables/viper", "robots/viper", 1);
    let (_dir, path, result) = load_text(&broken);
    let message = result.err().unwrap_or_default();
    assert!(
        message.starts_with(&format!("{}:{cable_line}: cable:", path.display())),
        "{message}"
    );
    let (_dir, path, result) = load_text("robot = [");
    let message = result.err().unwrap_or_default();
    assert!(
        message.starts_with(&format!("{}:1:", path.display())),
        "{message}"
    );
}

#[test]
fn relative_paths_are_resolved_against_the_setup_file() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let sub = dir.path().join("setups");
    std::fs::create_dir(&sub).unwrap_or_else(|e| panic!("{e}"));
    let copy = |from: &str, to: &Path| {
        std::fs::copy(root().join(from), to).unwrap_or_else(|e| panic!("{e}"));
    };
    copy(
        "robots/viper_s850/viper_s850.urdf",
        &dir.path().join("arm.urdf"),
    );
    copy("cables/smc_le_cp_3_paper.toml", &sub.join("cable.toml"));
    let good = small_setup();
    let text = good
        .replacen(&*line_text(&good, "robot ="), "robot = \"../arm.urdf\"", 1)
        .replacen(&*line_text(&good, "cable ="), "cable = \"cable.toml\"", 1);
    std::fs::write(sub.join("setup.toml"), &text).unwrap_or_else(|e| panic!("{e}"));
    let setup = Setup::from_file(sub.join("setup.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(setup.robot_path, sub.join("../arm.urdf"));
    assert_eq!(setup.cable_path, sub.join("cable.toml"));
    // Same content as the original files: same hash.
    let (_dir, _path, original) = load_text(&good);
    let original = original.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(setup.content_hash, original.content_hash);
}

/// The whole line of `text` that starts with `start`.
fn line_text(text: &str, start: &str) -> String {
    text.lines()
        .find(|l| l.starts_with(start))
        .unwrap_or_else(|| panic!("no line starts with `{start}`"))
        .to_string()
}

// ---------------------------------------------------------------------------------------------
// Content hash
// ---------------------------------------------------------------------------------------------

fn hash_of(text: &str) -> u64 {
    let (_dir, _path, result) = load_text(text);
    result.unwrap_or_else(|e| panic!("{e}")).content_hash
}

#[test]
fn content_hash_is_the_same_for_two_loads_and_for_layout_edits() {
    let good = small_setup();
    let reference = hash_of(&good);
    assert_eq!(hash_of(&good), reference);
    let bundled_a = bundled("pick_and_place.toml");
    let bundled_b = bundled("pick_and_place.toml");
    assert_eq!(bundled_a.content_hash, bundled_b.content_hash);
    assert_eq!(bundled_a.content_hash_hex().len(), 16);
    assert_ne!(
        bundled_a.content_hash,
        bundled("inspection.toml").content_hash
    );
    // Comments, blank lines, spacing, number spelling and the order of top-level keys.
    let edits = [
        good.replace(
            "\n[thresholds]",
            "\n# a comment\n\n[thresholds]   # another",
        ),
        good.replace("stretch = 1.02", "stretch    =    1.020"),
        good.replace("delta_s = 1", "delta_s = 1 # ΔS"),
        good.replace("[-172.0, 0.0, 100.0]", "[ -172, 0, 1e2 ]"),
        good.replace(
            "gravity_m_s2 = [0.0, 0.0, -9.81]\nmax_guides_per_link = 2",
            "max_guides_per_link = 2\ngravity_m_s2 = [0.0, 0.0, -9.81]",
        ),
        good.replace("\n", "\r\n"),
    ];
    for edited in &edits {
        assert_ne!(edited, &good);
        assert_eq!(hash_of(edited), reference, "{edited}");
    }
}

#[test]
fn content_hash_changes_with_any_one_value() {
    let good = small_setup();
    let reference = hash_of(&good);
    let changes = [
        ("[0.0, 0.0, -9.81]", "[0.0, 0.0, -9.80]"),
        ("max_guides_per_link = 2", "max_guides_per_link = 3"),
        ("contact_clearance_mm = 0.0", "contact_clearance_mm = 1.0"),
        ("stretch = 1.02", "stretch = 1.03"),
        (
            "min_bend_radius_mm = \"cable\"",
            "min_bend_radius_mm = 50.0",
        ),
        ("clamp_zone_mm = 20.0", "clamp_zone_mm = 21.0"),
        (
            "clamp_zone_mm = 20.0",
            "clamp_zone_mm = 20.0\nstatic_bend_margin_mm = 1.0",
        ),
        ("delta_s = 1", "delta_s = 2"),
        ("range = 2", "range = 3"),
        ("\"G1\"", "\"Ga\""),
        ("link = \"link_3\"", "link = \"link_2\""),
        ("name = \"back\"", "name = \"rear\""),
        ("[-172.0, 0.0, 100.0]", "[-172.0, 0.0, 100.5]"),
        ("rpy_deg = [0.0, 0.0, 90.0]", "rpy_deg = [0.0, 1.0, 90.0]"),
        ("name = \"top\"", "name = \"tip\""),
        ("[-72.0, 0.0, 200.0]", "[-72.0, 0.0, 201.0]"),
        ("min = 10, max = 40", "min = 11, max = 40"),
        ("min = 10, max = 40", "min = 10, max = 41"),
        (
            "min = 3, max = 20, step = 1, allow_zero = true",
            "min = 3, max = 20, step = 1, allow_zero = false",
        ),
        ("smc_le_cp_3_paper.toml", "gev_c6hf_paper.toml"),
    ];
    for (from, to) in changes {
        assert!(good.contains(from), "`{from}`");
        let changed = good.replace(from, to);
        assert_ne!(hash_of(&changed), reference, "`{from}` → `{to}`");
    }
}

#[test]
fn content_hash_changes_with_the_robot_and_the_cable_files() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let urdf = std::fs::read_to_string(root().join("robots/viper_s850/viper_s850.urdf"))
        .unwrap_or_else(|e| panic!("{e}"));
    let cable = std::fs::read_to_string(root().join("cables/smc_le_cp_3_paper.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let good = small_setup();
    let setup_text = good
        .replacen(&*line_text(&good, "robot ="), "robot = \"arm.urdf\"", 1)
        .replacen(&*line_text(&good, "cable ="), "cable = \"cable.toml\"", 1);
    let load = |urdf: &str, cable: &str| {
        std::fs::write(dir.path().join("arm.urdf"), urdf).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(dir.path().join("cable.toml"), cable).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(dir.path().join("s.toml"), &setup_text).unwrap_or_else(|e| panic!("{e}"));
        Setup::from_file(dir.path().join("s.toml"))
            .unwrap_or_else(|e| panic!("{e}"))
            .content_hash
    };
    let reference = load(&urdf, &cable);
    // Comments in either file do not count…
    assert_eq!(
        load(
            &urdf.replace("<robot name", "<!-- x -->\n<robot name"),
            &format!("# x\n{cable}")
        ),
        reference
    );
    // …a collider size, a joint limit or a cable value do.
    let edits = [
        urdf.replace(
            "radius=\"0.06\" length=\"0.23\"",
            "radius=\"0.061\" length=\"0.23\"",
        ),
        urdf.replace("upper=\"0.7853981633974483\"", "upper=\"0.78\""),
    ];
    for edited in &edits {
        assert_ne!(edited, &urdf);
        assert_ne!(load(edited, &cable), reference);
    }
    let stiffer = cable.replace(
        "bending_stiffness_nm_per_rad = 5.1e-2",
        "bending_stiffness_nm_per_rad = 5.2e-2",
    );
    assert_ne!(stiffer, cable);
    assert_ne!(load(&urdf, &stiffer), reference);
}

#[test]
fn a_setup_rebuilt_from_its_kept_texts_has_the_same_hash() {
    let setup = bundled("inspection.toml");
    // A folder without the robot and cable files: the kept texts are enough.
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let source = dir.path().join("robots/viper_s850/inspection.toml");
    let rebuilt = Setup::from_texts(
        &setup.text,
        &source,
        &setup.robot_text,
        &setup.cable_text,
        &[],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(rebuilt.content_hash, setup.content_hash);
    assert_eq!(rebuilt.canonical_bytes(), setup.canonical_bytes());
    assert_eq!(rebuilt.source, source);
}

#[test]
fn the_example_in_the_format_documentation_loads() {
    let doc = std::fs::read_to_string(root().join("docs/setup-format.md"))
        .unwrap_or_else(|e| panic!("{e}"));
    let start = doc
        .find("```toml\n")
        .unwrap_or_else(|| panic!("no example"))
        + 8;
    let end = start
        + doc[start..]
            .find("```")
            .unwrap_or_else(|| panic!("open block"));
    let source = root().join("robots/viper_s850/example.toml");
    let setup = Setup::from_toml_str(&doc[start..end], &source).unwrap_or_else(|e| panic!("{e}"));
    // G2 gains a copy of the fixed G3: S2 = 0 means the cable runs from G2's place to G3.
    let counts: Vec<usize> = setup
        .guides
        .iter()
        .map(|g| g.configurations.len())
        .collect();
    assert_eq!(counts, [2, 2, 1]);
    assert_eq!(setup.pv_count(0), 56 * 2 * 2);
    assert_eq!(setup.pv_count(1), 30 * 2);
}

/// The same places between two guides, counted through a hash grid of places
/// (`Setup::coincident_pair_count`, what `sites` and the estimates count with), are those a
/// comparison of every pair finds — on the site-generated setups, whose intra-link segments
/// pair every clamp place with its copy on the next guide.
#[test]
fn coincident_pairs_counted_through_places_are_those_every_pair_compared_finds() {
    for file in [
        "robots/viper_s850/pick_and_place.toml",
        "robots/viper_s850/whole_arm.toml",
        "tests/data/ur5/robot_level.toml",
    ] {
        let setup = Setup::from_file(root().join(file)).unwrap_or_else(|e| panic!("{e}"));
        let mut found = 0;
        for m in 0..setup.segment_count() {
            let (a, b) = setup.segment_guides(m);
            let (na, nb) = (
                setup.guides[a].configurations.len(),
                setup.guides[b].configurations.len(),
            );
            let every_pair = (0..na)
                .flat_map(|i| (0..nb).map(move |j| (i, j)))
                .filter(|&(i, j)| setup.coincident(a, i, b, j))
                .count();
            assert_eq!(
                setup.coincident_pair_count(m),
                every_pair,
                "{file} segment {m}"
            );
            found += every_pair;
        }
        assert!(found > 0, "{file}: some places are shared");
    }
}
