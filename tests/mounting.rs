//! The mounting plan (`cable_dict::mounting`) against references computed another way: a
//! clamp's place on a hand-made arm whose answer is known by construction, the places of a
//! bundled answer against the world geometry of the robot at its installation pose, and the
//! cable marks and crossed joints against the result JSON's pieces and the attachment test's
//! traversed joints.

use crate::common;

use cable_dict::mounting::{
    AlongFrom, LinkKind, LinkPlace, Turn, ZeroSide, link_features, link_place,
};
use cable_dict::pose::pose_from_mm_deg;
use cable_dict::robot::Robot;
use common::run;
use nalgebra::{Point3, Vector3};
use serde_json::Value;
use std::path::Path;

/// An arm with one link of every kind, in round numbers, at its zero pose (the turret
/// vertical, everything after it along world +x, z up):
///
/// - `base`: a 300 × 300 × 200 mm box standing on the floor (z = 0), `j1` (z) on its top;
/// - `turret` (roll: it reaches 300 mm along `j1`, `j2` lies only 100 mm off it): a cylinder
///   from z = 0 to 300 mm in its frame, `j2` (y) at (100, 0, 400) mm;
/// - `upper` (arm, parallel axes): a box from x = −50 to 550 mm whose middle is at y = 50 mm,
///   `j3` (y) at 500 mm;
/// - `elbow` (arm along the next axis: `j4`'s axis, x, passes through `j3`'s at the joint):
///   `j4` at 100 mm along x;
/// - `forearm` (roll: `j5`'s axis crosses `j4`'s 400 mm along it): a tube from x = 50 to
///   350 mm;
/// - `wrist` (arm along the next axis): `j6` (x) at 80 mm along x;
/// - `flange` (no joint after it): a disc from x = −10 to 0 mm, `tool0` on its face.
const KINDS: &str = r#"<robot name="kinds">
  <link name="base"><collision><origin xyz="0 0 0.1"/><geometry><box size="0.3 0.3 0.2"/></geometry></collision></link>
  <link name="turret"><collision><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.1" length="0.3"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0.25 0.05 0"/><geometry><box size="0.6 0.1 0.12"/></geometry></collision></link>
  <link name="elbow"><collision><origin xyz="0.05 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="forearm"><collision><origin xyz="0.2 0 0" rpy="0 1.5707963267948966 0"/><geometry><cylinder radius="0.05" length="0.3"/></geometry></collision></link>
  <link name="wrist"><collision><origin xyz="0.04 0 0"/><geometry><box size="0.08 0.08 0.08"/></geometry></collision></link>
  <link name="flange"><collision><origin xyz="-0.005 0 0" rpy="0 1.5707963267948966 0"/><geometry><cylinder radius="0.03" length="0.01"/></geometry></collision></link>
  <link name="tool0"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="turret"/><origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="turret"/><child link="upper"/><origin xyz="0.1 0 0.4"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="upper"/><child link="elbow"/><origin xyz="0.5 0 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j4" type="revolute"><parent link="elbow"/><child link="forearm"/><origin xyz="0.1 0 0"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j5" type="revolute"><parent link="forearm"/><child link="wrist"/><origin xyz="0.4 0 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j6" type="revolute"><parent link="wrist"/><child link="flange"/><origin xyz="0.08 0 0"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="tool0_joint" type="fixed"><parent link="flange"/><child link="tool0"/><origin xyz="0 0 0"/></joint>
</robot>"#;

/// The place of a clamp at `xyz_mm` with its cable along `rpy_deg` on `link` of the `KINDS`
/// arm at its zero pose.
fn place_on_kinds(link: &str, xyz_mm: [f64; 3], rpy_deg: [f64; 3]) -> LinkPlace {
    let robot = Robot::from_urdf_str(KINDS, Path::new("kinds.urdf")).expect("valid URDF");
    let poses = robot.link_poses(&[0.0; 6]).expect("joints");
    let link = robot.link_index(link).expect("link");
    link_place(&robot, link, &pose_from_mm_deg(xyz_mm, rpy_deg), &poses).expect("measurable")
}

/// `a` and `b` within a micrometre (or a microdegree).
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

/// The difference of two angles in degrees, in (−180, 180].
fn angle_error(a: f64, b: f64) -> f64 {
    (a - b + 180.0).rem_euclid(360.0) - 180.0
}

/// Every kind of link of the `KINDS` arm: the kind, the feature the distance along starts
/// from, the distance itself, the distance of the cable's axis from the line, the angle and
/// the side the cable leans to, each known by construction.
#[test]
fn every_kind_of_link_is_measured_from_its_features() {
    // Base: 150 mm above the mounting face (the floor), 120 mm from the j1 axis. Seen from
    // above, clockwise from the front (+x): −y is at 90°, +y at 270°.
    for (xyz, around) in [
        ([120.0, 0.0, 150.0], 0.0),
        ([0.0, 120.0, 150.0], 270.0),
        ([0.0, -120.0, 150.0], 90.0),
    ] {
        let place = place_on_kinds("base", xyz, [0.0; 3]);
        assert_eq!(
            (place.kind, place.along_from),
            (LinkKind::Base, AlongFrom::MountingFace)
        );
        assert!(close(place.along_mm.expect("measured"), 150.0), "{place:?}");
        assert!(close(place.off_axis_mm, 120.0));
        assert!(
            angle_error(place.around_deg, around).abs() < 1e-6,
            "{place:?}"
        );
        assert_eq!(place.zero_side, ZeroSide::Front);
        assert!(place.seen_from_above);
        assert!(
            place
                .describe()
                .contains("150 mm from the base's mounting face along the j1 axis")
        );
        assert!(
            place
                .describe()
                .contains("cable along the link, toward the arm")
        );
    }

    // Turret: 100 mm above its seam with the base, 300 mm below the j2 axis (at 400 mm), the
    // cable's axis 112 mm from j1 on the −y side. Seen from the base end (from below),
    // clockwise from the front (+x) runs to +y: −y is at 270°.
    let place = place_on_kinds("turret", [0.0, -112.0, 100.0], [0.0; 3]);
    assert_eq!(
        (place.kind, place.along_from),
        (LinkKind::Roll, AlongFrom::Seam)
    );
    assert!(close(place.along_mm.expect("measured"), 100.0));
    assert!(close(place.next_joint_mm.expect("j2"), 400.0));
    assert!(close(place.off_axis_mm, 112.0));
    assert!(
        angle_error(place.around_deg, 270.0).abs() < 1e-6,
        "{place:?}"
    );
    assert_eq!(place.base_side_below, Some(true));
    let words = place.describe();
    assert!(
        words.contains(
            "100 mm along the j1 axis from the seam with base (300 mm before the j2 axis)"
        ),
        "{words}"
    );
    assert!(
        words.contains("seen from the base end (from below)"),
        "{words}"
    );

    // Upper arm: 200 mm from the j2 axis toward j3 along its centre line (y = 50 mm), the
    // cable's axis 72 mm above it (the top: 0°), the cable along the arm.
    let place = place_on_kinds("upper", [200.0, 50.0, 72.0], [0.0, 90.0, 0.0]);
    assert_eq!(
        (place.kind, place.along_from),
        (LinkKind::Arm, AlongFrom::JointAxis)
    );
    assert!(close(place.along_mm.expect("measured"), 200.0));
    assert!(close(place.next_joint_mm.expect("j3"), 500.0));
    assert!(close(place.off_axis_mm, 72.0));
    assert!(angle_error(place.around_deg, 0.0).abs() < 1e-6);
    assert_eq!(place.zero_side, ZeroSide::Top);
    assert!(
        place
            .describe()
            .contains("200 mm from the j2 axis toward j3")
    );
    assert!(place.describe().contains("cable along the link, toward j3"));
    // On the +y side (270°: clockwise looking toward j3 runs top → −y → bottom → +y), the
    // cable running up, square to the arm: turned clockwise (from 270° toward the top).
    let place = place_on_kinds("upper", [200.0, 112.0, 0.0], [0.0, 0.0, 0.0]);
    assert!(close(place.off_axis_mm, 62.0));
    assert!(
        angle_error(place.around_deg, 270.0).abs() < 1e-6,
        "{place:?}"
    );
    assert_eq!(place.cable_turn, Some(Turn::Clockwise));
    assert!(
        place
            .cable_direction()
            .starts_with("across the link, square to its axis, turned clockwise")
    );
    // Its mirror on the −y side, the cable running up: anticlockwise.
    let place = place_on_kinds("upper", [200.0, -12.0, 0.0], [0.0, 0.0, 0.0]);
    assert!(
        angle_error(place.around_deg, 90.0).abs() < 1e-6,
        "{place:?}"
    );
    assert_eq!(place.cable_turn, Some(Turn::Anticlockwise));
    // Leaning toward j3 at 60° from the arm (the cable in the x–z plane, on the top).
    let place = place_on_kinds("upper", [200.0, 50.0, 72.0], [0.0, 60.0, 0.0]);
    assert!(close(place.cable_to_axis_deg, 30.0), "{place:?}");
    assert_eq!(place.cable_turn, Some(Turn::Outward));
    assert!(
        place
            .cable_direction()
            .contains("30° from its axis toward j3, pointing away")
    );

    // Elbow: j4's axis (x) passes through j3's at the joint: along j4's axis, from j3's.
    let place = place_on_kinds("elbow", [50.0, 0.0, 62.0], [0.0, 90.0, 0.0]);
    assert_eq!(
        (place.kind, place.along_from),
        (LinkKind::Arm, AlongFrom::JointAxis)
    );
    assert!(place.line_is_next_axis);
    assert!(close(place.along_mm.expect("measured"), 50.0));
    assert!(
        place
            .describe()
            .contains("50 mm along the j4 axis from the j3 axis")
    );
    assert!(place.describe().contains("62 mm from the j4 axis"));

    // Forearm: 150 mm along j4 from its seam with the elbow (the tube starts at 50 mm), 200 mm
    // before the j5 axis (at 400 mm).
    let place = place_on_kinds("forearm", [200.0, 0.0, 62.0], [0.0, 90.0, 0.0]);
    assert_eq!(
        (place.kind, place.along_from),
        (LinkKind::Roll, AlongFrom::Seam)
    );
    assert!(close(place.along_mm.expect("measured"), 150.0));
    assert!(close(place.next_joint_mm.expect("j5"), 350.0));
    assert!(
        place.describe().contains(
            "150 mm along the j4 axis from the seam with elbow (200 mm before the j5 axis)"
        )
    );
    assert!(place.describe().contains("seen from the elbow end"));
    assert!(place.describe().contains("toward j5"));

    // Flange: a connector 30 mm beyond the flange face, 50 mm off the j6 axis on top; one
    // 5 mm behind it.
    let place = place_on_kinds("flange", [30.0, 0.0, 50.0], [0.0, 90.0, 0.0]);
    assert_eq!(
        (place.kind, place.along_from),
        (LinkKind::Flange, AlongFrom::FlangeFace)
    );
    assert!(close(place.along_mm.expect("measured"), 30.0));
    assert!(close(place.off_axis_mm, 50.0));
    assert!(
        place
            .describe()
            .contains("30 mm beyond the flange face, along the j6 axis")
    );
    assert!(
        place
            .describe()
            .contains("cable along the link, toward the tool")
    );
    let place = place_on_kinds("flange", [-5.0, 0.0, 40.0], [0.0, 90.0, 0.0]);
    assert!(place.describe().contains("5 mm behind the flange face"));
}

/// A link without collision shapes has no seam or face: the place says so in words instead of
/// giving a number from the link frame; a roll link without shapes is measured from the next
/// joint's axis, the one feature it still has.
#[test]
fn a_link_without_shapes_says_what_cannot_be_measured() {
    let bare = KINDS
        .lines()
        .filter(|line| {
            !line.contains("<link name=\"forearm\"") && !line.contains("<link name=\"flange\"")
        })
        .collect::<Vec<_>>()
        .join("\n")
        .replace(
            "<link name=\"tool0\"/>",
            "<link name=\"tool0\"/><link name=\"forearm\"/><link name=\"flange\"/>",
        );
    let robot = Robot::from_urdf_str(&bare, Path::new("bare.urdf")).expect("valid URDF");
    let poses = robot.link_poses(&[0.0; 6]).expect("joints");
    let at = |link: &str, xyz: [f64; 3]| {
        let link = robot.link_index(link).expect("link");
        link_place(
            &robot,
            link,
            &pose_from_mm_deg(xyz, [0.0, 90.0, 0.0]),
            &poses,
        )
        .expect("place")
    };
    let forearm = at("forearm", [200.0, 0.0, 62.0]);
    assert_eq!(forearm.along_from, AlongFrom::NextAxis);
    assert!(close(forearm.along_mm.expect("from j5"), -200.0));
    let flange = at("flange", [30.0, 0.0, 50.0]);
    assert_eq!(
        (flange.along_from, flange.along_mm),
        (AlongFrom::Unmeasured, None)
    );
    assert!(
        flange
            .describe()
            .contains("the model has no shape of this link to measure from")
    );
}

/// With the upper arm raised straight up (j2 turned −90°), "top" is undefined along it: 0° is
/// then the front (world +x).
#[test]
fn a_vertical_link_is_measured_from_the_front() {
    let robot = Robot::from_urdf_str(KINDS, Path::new("kinds.urdf")).expect("valid URDF");
    let poses = robot
        .link_poses(&[0.0, -std::f64::consts::FRAC_PI_2, 0.0, 0.0, 0.0, 0.0])
        .expect("joints");
    let upper = robot.link_index("upper").expect("upper");
    // In the raised arm's frame, world +x (the front) is −z of the link.
    let clamp = pose_from_mm_deg([200.0, 50.0, -72.0], [0.0; 3]);
    let place = link_place(&robot, upper, &clamp, &poses).expect("a moving link");
    assert_eq!(place.zero_side, ZeroSide::Front);
    assert!(angle_error(place.around_deg, 0.0).abs() < 1e-6, "{place:?}");
    assert!(close(place.along_mm.expect("measured"), 200.0));
    assert_eq!(place.base_side_below, Some(true));
}

/// The kind of every link of the four public robot descriptions in tests/data and of the
/// Viper, as their drawings show them: turrets and wrist rolls turn about their own axis,
/// upper arms and offset wrists reach toward the next joint, the last link is a flange.
#[test]
fn the_links_of_real_robots_are_the_kinds_their_drawings_show() {
    use LinkKind::{Arm, Base, Flange, Roll};
    let robots: [(&str, &[(&str, LinkKind)]); 5] = [
        (
            "robots/viper_s850/viper_s850.urdf",
            &[
                ("base_link", Base),
                ("link_1", Roll),
                ("link_2", Arm),
                ("link_3", Arm),
                ("link_4", Roll),
                ("link_5", Arm),
                ("link_6", Flange),
            ],
        ),
        (
            "tests/data/robots/ur_description/urdf/ur5.urdf",
            &[
                ("base_link", Base),
                ("shoulder_link", Roll),
                ("upper_arm_link", Arm),
                ("forearm_link", Arm),
                ("wrist_1_link", Arm),
                ("wrist_2_link", Arm),
                ("wrist_3_link", Flange),
            ],
        ),
        (
            "tests/data/robots/kuka_kr6_support/urdf/kr6r900sixx.urdf",
            &[
                ("base_link", Base),
                ("link_1", Roll),
                ("link_2", Arm),
                ("link_4", Roll),
                ("link_5", Arm),
                ("link_6", Flange),
            ],
        ),
        (
            "tests/data/robots/abb_irb2400_support/urdf/irb2400.urdf",
            &[
                ("base_link", Base),
                ("link_1", Roll),
                ("link_2", Arm),
                ("link_3", Arm),
                ("link_4", Roll),
                ("link_5", Arm),
                ("link_6", Flange),
            ],
        ),
        (
            "tests/data/robots/franka_description/urdf/panda.urdf",
            &[
                ("panda_link1", Roll),
                ("panda_link2", Arm),
                ("panda_link4", Arm),
                ("panda_link5", Roll),
                ("panda_link6", Arm),
                ("panda_link7", Flange),
            ],
        ),
    ];
    for (file, links) in robots {
        let robot = Robot::from_urdf_file(file).expect("robot");
        let poses = robot.link_poses(&vec![0.0; robot.dof()]).expect("joints");
        for &(link, kind) in links {
            let index = robot.link_index(link).expect("link");
            let features = link_features(&robot, index, &poses).expect("features");
            assert_eq!(features.kind, kind, "{file} {link}");
            // Every robot here has shapes on these links: nothing is left unmeasured.
            assert_ne!(
                features.along_from.0,
                AlongFrom::Unmeasured,
                "{file} {link}"
            );
        }
    }
}

/// On the real robots' meshes, a roll link's seam and a flange's face are the ends of the
/// link's STL vertices along the axis, read here from the STL files directly: a point placed
/// at a known distance from them, off the axis and around it, is found there.
#[test]
fn places_on_real_meshes_are_measured_from_the_stl_ends() {
    let cases = [
        (
            "tests/data/robots/kuka_kr6_support/urdf/kr6r900sixx.urdf",
            "link_4",
            false,
        ),
        (
            "tests/data/robots/abb_irb2400_support/urdf/irb2400.urdf",
            "link_4",
            false,
        ),
        (
            "tests/data/robots/ur_description/urdf/ur5.urdf",
            "wrist_3_link",
            true,
        ),
        (
            "tests/data/robots/kuka_kr6_support/urdf/kr6r900sixx.urdf",
            "link_6",
            true,
        ),
    ];
    for (file, link, flange) in cases {
        let robot = Robot::from_urdf_file(file).expect("robot");
        let poses = robot.link_poses(&vec![0.0; robot.dof()]).expect("joints");
        let index = robot.link_index(link).expect("link");
        let features = link_features(&robot, index, &poses).expect("features");
        let axis = features.line.into_inner();
        // The link's STL vertices in its frame, from the file the URDF names.
        let along: Vec<f64> = stl_vertices_in_link(file, link)
            .iter()
            .map(|v| (v - features.origin_m).dot(&axis))
            .collect();
        let end = if flange {
            along.iter().copied().fold(f64::NEG_INFINITY, f64::max)
        } else {
            along.iter().copied().fold(f64::INFINITY, f64::min)
        };
        // 40 mm from the end toward the tool, 90 mm off the axis, on a side square to it.
        let side = axis
            .cross(&Vector3::z())
            .try_normalize(1e-6)
            .unwrap_or_else(|| axis.cross(&Vector3::x()).normalize());
        let point = features.origin_m + axis * (end + 0.04) + side * 0.09;
        let clamp = cable_dict::pose::Pose::translation(point.x, point.y, point.z);
        let place = link_place(&robot, index, &clamp, &poses).expect("place");
        assert!(
            (place.along_mm.expect("measured") - 40.0).abs() < 1e-6,
            "{file} {link}: {place:?}"
        );
        assert!(
            (place.off_axis_mm - 90.0).abs() < 1e-6,
            "{file} {link}: {place:?}"
        );
    }
}

/// The vertices of `link`'s STL collision meshes in the link frame, read with the URDF's
/// `<collision>` origin and the `package://` folder convention of tests/data/robots.
fn stl_vertices_in_link(urdf: &str, link: &str) -> Vec<Point3<f64>> {
    let robot = urdf_rs::read_file(urdf).expect("URDF");
    let link = robot.links.iter().find(|l| l.name == link).expect("link");
    let mut vertices = Vec::new();
    for collision in &link.collision {
        let urdf_rs::Geometry::Mesh { filename, scale } = &collision.geometry else {
            continue;
        };
        let path = filename
            .strip_prefix("package://")
            .map(|p| Path::new("tests/data/robots").join(p))
            .expect("package URI");
        let mut file = std::fs::File::open(&path).expect("STL");
        let mesh = stl_io::read_stl(&mut file).expect("STL");
        let s = scale.map(|s| s.0).unwrap_or([1.0; 3]);
        let o = &collision.origin;
        let pose = cable_dict::pose::pose_from_xyz_rpy(o.xyz.0, o.rpy.0);
        vertices.extend(mesh.vertices.iter().map(|v| {
            pose * Point3::new(v[0] as f64 * s[0], v[1] as f64 * s[1], v[2] as f64 * s[2])
        }));
    }
    assert!(!vertices.is_empty(), "{urdf}: meshes");
    vertices
}

/// The robot-level pick-and-place answer: its marks are the result JSON's piece lengths
/// summed from the connector end; guides joined by a 0 mm piece are one clamp; each mounted
/// piece crosses the joints the attachment test traversed for it; and each clamp's place,
/// rebuilt from the world positions of the joints at the installation pose, is the one said.
#[test]
fn the_mounting_plan_agrees_with_the_pieces_and_the_robot() {
    let output = run(&[
        "solve",
        "--setup",
        "robots/viper_s850/pick_and_place.toml",
        "motions/viper_s850/pick_and_place.csv",
        "--json",
        "--no-motion-test",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let result: Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let pieces = result["ecpv"]["segments"].as_array().expect("pieces");
    let plan = &result["mounting"];
    let clamps = plan["clamps"].as_array().expect("clamps");

    // Marks: from the end, summing the JSON's pieces; a 0 mm piece merges its guides.
    let lengths: Vec<f64> = pieces
        .iter()
        .map(|p| p["length_mm"].as_f64().expect("length"))
        .collect();
    let total: f64 = lengths.iter().sum();
    let mut expected: Vec<(Vec<String>, f64)> = Vec::new();
    let mut from_start = 0.0;
    for (i, piece) in pieces.iter().enumerate() {
        let from = piece["from_guide"].as_str().expect("guide").to_string();
        if i == 0 {
            expected.push((vec![from], total));
        }
        from_start += lengths[i];
        let to = piece["to_guide"].as_str().expect("guide").to_string();
        if lengths[i] == 0.0 {
            expected.last_mut().expect("a clamp").0.push(to);
        } else {
            expected.push((vec![to], total - from_start));
        }
    }
    assert!(
        lengths.contains(&0.0),
        "this answer joins two guides: {lengths:?}"
    );
    assert_eq!(clamps.len(), expected.len());
    for (clamp, (guides, mark)) in clamps.iter().zip(&expected) {
        let names: Vec<&str> = clamp["guides"]
            .as_array()
            .expect("guides")
            .iter()
            .map(|g| g.as_str().expect("name"))
            .collect();
        assert_eq!(&names, guides);
        assert!((clamp["mark_mm"].as_f64().expect("mark") - mark).abs() < 1e-9);
    }
    assert_eq!(clamps.last().expect("end")["fitting"], "gripper connector");
    assert_eq!(plan["piece_tolerance_mm"], 20.0);

    // Crossed joints: the attachment test's traversed joints of the same pieces.
    for piece in plan["pieces"].as_array().expect("mounted pieces") {
        let from = clamps[piece["from_clamp"].as_u64().expect("index") as usize]["guides"]
            .as_array()
            .expect("guides")
            .last()
            .expect("guide")
            .clone();
        let segment = result["sets"]
            .as_array()
            .expect("sets")
            .iter()
            .find(|s| s["from_guide"] == from)
            .expect("the segment from that clamp");
        assert_eq!(piece["across_joints"], segment["traversed_joints"]);
    }

    // Places: from the world positions of the joints and the clamp at the installation pose.
    // On the Viper, link_4's forearm tube starts at its frame origin and link_6's flange face
    // is its frame origin (viper_s850.urdf's comments): there the seam and the face are the
    // origins, and the roll axes point from the origin toward the next joint or the tool.
    let setup = cable_dict::setup::Setup::from_file("robots/viper_s850/pick_and_place.toml")
        .expect("setup");
    let poses = &setup
        .installation
        .as_ref()
        .expect("installation pose")
        .link_poses;
    for clamp in clamps {
        let named = clamp["guides"].as_array().expect("guides");
        let guide = setup
            .guides
            .iter()
            .find(|g| {
                named.iter().any(|n| n == g.name.as_str())
                    && (g.fixed || clamp["fitting"].is_null())
            })
            .expect("guide");
        let configuration = guide
            .configurations
            .iter()
            .find(|c| c.name == clamp["placement"])
            .expect("placement");
        let world = poses[guide.link] * configuration.pose * Point3::origin();
        let robot = &setup.robot;
        let body = guide.body;
        let moving = &robot.joints[robot.links[body].parent_joint.expect("moved")];
        let start = poses[body] * Point3::origin();
        let place = &clamp["place"];
        let axis = match place["kind"].as_str().expect("kind") {
            "arm" => {
                let next = place["next_joint"].as_str().expect("next");
                let next = robot.joints.iter().find(|j| j.name == next).expect("joint");
                (poses[next.child_link] * Point3::origin() - start).normalize()
            }
            "roll" | "flange" => {
                let axis = poses[body].rotation * moving.axis.into_inner();
                let parent = poses[moving.parent_link] * Point3::origin();
                if (parent - start).dot(&axis) > 0.0 {
                    -axis
                } else {
                    axis
                }
            }
            other => panic!("{other}"),
        };
        let along = (world - start).dot(&axis);
        let off = ((world - start) - axis * along).norm();
        assert!((place["along_mm"].as_f64().expect("along") - along * 1e3).abs() < 1e-6);
        assert!((place["off_axis_mm"].as_f64().expect("off") - off * 1e3).abs() < 1e-6);
        // The angle from the top (world up, squared to the axis), clockwise looking along.
        let up = Vector3::z() - axis * axis.dot(&Vector3::z());
        if up.norm() > 0.3 {
            let radial = (world - start) - axis * along;
            let clockwise = axis.cross(&up.normalize());
            let angle = radial
                .dot(&clockwise)
                .atan2(radial.dot(&up.normalize()))
                .to_degrees();
            let said = place["around_deg"].as_f64().expect("around");
            let error = (said - angle + 180.0).rem_euclid(360.0) - 180.0;
            assert!(error.abs() < 1e-6, "{said} against {angle}");
        }
    }
    // The fitter's numbers: clamps to mount 1…n from the base side, the connector named.
    let numbers: Vec<Value> = clamps.iter().map(|c| c["number"].clone()).collect();
    assert_eq!(numbers, [Value::from(1), Value::from(2), Value::Null]);
}

/// With allowances in the cable file the cut length is the length between the clamps plus
/// both, in the JSON and in the printed summary; without them there is none.
#[test]
fn the_cut_length_adds_the_cable_files_allowances() {
    let root = crate::common::root();
    let dir = tempfile::tempdir().expect("temporary folder");
    let cable = std::fs::read_to_string(root.join("cables/smc_le_cp_3.toml")).expect("cable");
    let cable_path = dir.path().join("cable.toml");
    let with_allowances =
        format!("{cable}tool_end_allowance_mm = 40.0\nbase_end_allowance_mm = 1500.0\n");
    std::fs::write(&cable_path, with_allowances).expect("write cable");
    let bundled_cable = format!("cable = {:?}", root.join("cables/smc_le_cp_3.toml"));
    let setup =
        common::bundled_setup_text().replace(&bundled_cable, &format!("cable = {cable_path:?}"));
    let setup_path = dir.path().join("setup.toml");
    std::fs::write(&setup_path, setup).expect("write setup");
    let setup_arg = setup_path.to_str().expect("utf-8");
    let motion = root.join("motions/viper_s850/pick_and_place.csv");
    let motion_arg = motion.to_str().expect("utf-8");
    let args = [
        "solve",
        "--setup",
        setup_arg,
        motion_arg,
        "--no-motion-test",
    ];
    let json = run(&[&args[..], &["--json"]].concat());
    assert!(
        json.status.success(),
        "{}",
        String::from_utf8_lossy(&json.stderr)
    );
    let result: Value = serde_json::from_slice(&json.stdout).expect("JSON");
    let length = result["mounting"]["length_mm"].as_f64().expect("length");
    let total = result["total_length_mm"].as_f64().expect("total");
    assert_eq!(length, total);
    let cut = &result["mounting"]["cut"];
    assert_eq!(cut["total_mm"].as_f64(), Some(length + 40.0 + 1500.0));
    let text = String::from_utf8(run(&args).stdout).expect("utf-8");
    let said = format!(
        "cut {:.0} mm: {length:.0} mm between the clamps",
        length + 1540.0
    );
    assert!(text.contains(&said), "{text}");

    let plain = run(&[
        "solve",
        "--setup",
        "robots/viper_s850/pick_and_place.toml",
        motion_arg,
        "--no-motion-test",
        "--json",
    ]);
    let result: Value = serde_json::from_slice(&plain.stdout).expect("JSON");
    assert!(result["mounting"]["cut"].is_null());
}

/// A UR5 with a clamp on the flange joined to the tool's connector by a 0 mm piece: the two
/// are the connector, a fitting — named, not numbered, not counted as a clamp to mount, its
/// position given in the frame of the link its row names (tool0, where it is declared). With
/// no tool modelled the connector hangs 60 mm beyond the flange in free space, which is
/// warned of; a tool body around it silences the warning.
#[test]
fn a_clamp_on_a_fitting_is_the_fitting_and_a_fitting_in_free_space_is_warned_of() {
    let root = common::root();
    let limits = common::limits("\"cable\"");
    let setup_text = |bodies: &str| {
        format!(
            r#"robot = {robot:?}
cable = {cable:?}
gravity_m_s2 = [0.0, 0.0, -9.81]
install_joints_deg = [0.0, -90.0, 90.0, -90.0, -90.0, 0.0]
max_guides_per_link = 2
{limits}[[guides]]
name = "G1"
link = "forearm_link"
configurations = [{{ name = "top", position_mm = [-200.0, 0.0, 130.0], rpy_deg = [0.0, -90.0, 0.0] }}]
[[guides]]
name = "G2"
link = "wrist_3_link"
configurations = [{{ name = "side", position_mm = [50.0, 0.0, 60.0], rpy_deg = [0.0, 0.0, 0.0] }}]
[[guides]]
name = "G3"
link = "tool0"
fixed = {{ name = "connector", position_mm = [50.0, 0.0, 60.0], rpy_deg = [0.0, 0.0, 0.0] }}
[[segments]]
from = "G1"
to = "G2"
lengths = {{ min = 30, max = 60, step = 1, allow_zero = false }}
[[segments]]
from = "G2"
to = "G3"
lengths = {{ min = 5, max = 10, step = 1, allow_zero = true }}
{bodies}"#,
            robot = root.join("tests/data/robots/ur_description/urdf/ur5.urdf"),
            cable = root.join("cables/smc_le_cp_3.toml"),
        )
    };
    let dir = tempfile::tempdir().expect("temporary folder");
    let plan_of = |bodies: &str| {
        let file = dir.path().join("setup.toml");
        std::fs::write(&file, setup_text(bodies)).expect("write");
        let setup = cable_dict::setup::Setup::from_file(&file).unwrap_or_else(|e| panic!("{e}"));
        let path = cable_dict::path::CablePath::through_every_guide(vec![40, 0], vec![0, 0, 0]);
        cable_dict::mounting::mounting_plan(&setup, &path)
    };
    let plan = plan_of("");
    assert_eq!(plan.clamps.len(), 2);
    assert_eq!(plan.clamps_to_mount(), 1);
    let connector = &plan.clamps[1];
    assert_eq!(connector.guides, ["G2", "G3"]);
    assert_eq!(connector.fitting.as_deref(), Some("connector"));
    assert_eq!(
        (connector.number, connector.name()),
        (None, "connector".to_string())
    );
    assert_eq!(connector.link, "tool0");
    assert_eq!(connector.xyz_mm, [50.0, 0.0, 60.0]);
    assert_eq!(plan.clamps[0].number, Some(1));
    assert_eq!(plan.piece_name(0), "1 → connector");
    // tool0 lies on the flange face: the connector is 60 mm beyond it, 50 mm off the axis.
    let place = connector.place.as_ref().expect("place");
    assert_eq!(place.kind, LinkKind::Flange);
    assert!(
        (place.along_mm.expect("measured") - 60.0).abs() < 0.5,
        "{place:?}"
    );
    assert!((place.off_axis_mm - 50.0).abs() < 1e-6);
    // Free space: 60 mm beyond the flange, farther than FREE_SPACE_MM from every surface.
    let distance = connector.free_space_mm.expect("in free space");
    assert!(
        distance > cable_dict::mounting::FREE_SPACE_MM && distance < 100.0,
        "{distance}"
    );
    let warnings = plan.warnings();
    assert_eq!(warnings.len(), 1);
    assert!(
        warnings[0].starts_with("the connector (G2 = G3) hangs in free space"),
        "{warnings:?}"
    );
    assert!(warnings[0].contains("[[bodies]]"));
    // A tool body the connector sits on (its cable axis 5 mm off the body's side).
    let tool = "[[bodies]]\nname = \"tool\"\nlink = \"tool0\"\nposition_mm = [0.0, 0.0, 50.0]\nrpy_deg = [0.0, 0.0, 0.0]\nbox_mm = [90.0, 90.0, 100.0]\n";
    let plan = plan_of(tool);
    assert_eq!(plan.clamps[1].free_space_mm, None);
    assert!(plan.warnings().is_empty());
}

/// `[pendant_angles]` turns the installation pose into the pendant's angles: `sign × URDF +
/// offset`, printed beside the description's; a joint the robot does not turn, a sign that is
/// not ±1 and an offset beyond ±360° are refused with the key.
#[test]
fn pendant_angles_print_the_installation_pose_as_the_pendant_shows_it() {
    let base = common::bundled_setup_text();
    let dir = tempfile::tempdir().expect("temporary folder");
    let load = |pendant: &str| {
        // A top-level table must come before the [[...]] arrays of tables.
        let text = base.replacen("[thresholds]", &format!("{pendant}\n[thresholds]"), 1);
        let file = dir.path().join("setup.toml");
        std::fs::write(&file, text).expect("write");
        cable_dict::setup::Setup::from_file(&file)
    };
    let setup = load("[pendant_angles]\njoint_2 = { sign = -1, offset_deg = 90.0 }\njoint_3 = { sign = 1, offset_deg = -180.0 }")
        .unwrap_or_else(|e| panic!("{e}"));
    // The installation pose has joint_2 −68.6° and joint_3 216.4°.
    let path = cable_dict::path::CablePath::through_every_guide(vec![28, 0, 34], vec![0, 0, 0, 0]);
    let plan = cable_dict::mounting::mounting_plan(&setup, &path);
    let pose = plan.installation_pose.as_ref().expect("a pose");
    let pendant: Vec<Option<f64>> = pose.iter().map(|j| j.pendant).collect();
    let expected = [
        None,
        Some(68.6 + 90.0),
        Some(216.4 - 180.0),
        None,
        None,
        None,
    ];
    for (got, want) in pendant.iter().zip(expected) {
        match (got, want) {
            (Some(g), Some(w)) => assert!((g - w).abs() < 1e-9, "{g} against {w}"),
            (g, w) => assert_eq!(*g, w),
        }
    }
    assert!(
        plan.installation_words()
            .contains("joint_2 -68.6 deg (pendant 158.6)")
    );
    for (pendant, key) in [
        (
            "[pendant_angles]\nno_such_joint = { sign = 1, offset_deg = 0.0 }",
            "pendant_angles.no_such_joint",
        ),
        (
            "[pendant_angles]\njoint_2 = { sign = 2, offset_deg = 0.0 }",
            "pendant_angles.joint_2.sign",
        ),
        (
            "[pendant_angles]\njoint_2 = { sign = 1, offset_deg = 400.0 }",
            "pendant_angles.joint_2.offset_deg",
        ),
    ] {
        let error = load(pendant).expect_err("refused").to_string();
        assert!(error.contains(key), "{error}");
    }
}
