//! The mounting plan (`cable_dict::mounting`) against references computed another way: a
//! clamp's place on a hand-made arm whose answer is known by construction, the places of a
//! bundled answer against the world geometry of the robot at its installation pose, and the
//! cable marks and crossed joints against the result JSON's pieces and the attachment test's
//! traversed joints.

mod common;

use cable_dict::mounting::link_place;
use cable_dict::pose::pose_from_mm_deg;
use cable_dict::robot::Robot;
use common::run;
use nalgebra::{Point3, Vector3};
use serde_json::Value;
use std::path::Path;

/// A two-link arm: `arm` turns about the base's z axis at the origin, `forearm` about y at
/// 500 mm along the arm's x axis, and `hand` at 400 mm along the forearm's x axis.
const ARM: &str = r#"<robot name="arm">
  <link name="base"/>
  <link name="arm"/>
  <link name="forearm"/>
  <link name="hand"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="arm"/><child link="forearm"/>
    <origin xyz="0.5 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="wrist" type="revolute">
    <parent link="forearm"/><child link="hand"/>
    <origin xyz="0.4 0 0" rpy="0 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
</robot>"#;

/// On the arm lying along world +x with z up, looking along the arm (toward the elbow): the
/// top is 0°, clockwise runs to the right (world −y) at 90°, the bottom at 180° and the left
/// (world +y) at 270°. A clamp 200 mm along, 60 mm off the axis on each side in turn, its
/// cable along the arm, is found there; one whose cable runs across is said to.
#[test]
fn a_clamp_on_a_known_arm_is_where_it_was_put() {
    let robot = Robot::from_urdf_str(ARM, Path::new("arm.urdf")).expect("valid URDF");
    let poses = robot.link_poses(&[0.0, 0.0, 0.0]).expect("joints");
    let arm = robot.link_index("arm").expect("arm");
    // Cable frame +z along the arm (+x): pitch 90°.
    for (side, yz, around) in [
        ("top", [0.0, 60.0], 0.0),
        ("right", [-60.0, 0.0], 90.0),
        ("bottom", [0.0, -60.0], 180.0),
        ("left", [60.0, 0.0], 270.0),
    ] {
        let clamp = pose_from_mm_deg([200.0, yz[0], yz[1]], [0.0, 90.0, 0.0]);
        let place = link_place(&robot, arm, &clamp, &poses).expect("a moving link");
        assert_eq!(place.from_joint, "shoulder");
        assert_eq!(place.toward.as_deref(), Some("elbow"));
        assert!((place.next_joint_mm.expect("next") - 500.0).abs() < 1e-9);
        assert!((place.along_mm - 200.0).abs() < 1e-9, "{side}: {place:?}");
        assert!((place.off_axis_mm - 60.0).abs() < 1e-9, "{side}: {place:?}");
        let error = (place.around_deg - around + 180.0).rem_euclid(360.0) - 180.0;
        assert!(
            error.abs() < 1e-9,
            "{side}: {} ≠ {around}",
            place.around_deg
        );
        assert_eq!(place.zero_side, "top");
        assert!(place.cable_to_axis_deg < 1e-6, "{side}: {place:?}");
        assert!(place.describe().contains("along the link, toward elbow"));
    }
    let across = pose_from_mm_deg([200.0, 0.0, 60.0], [-90.0, 0.0, 0.0]);
    let place = link_place(&robot, arm, &across, &poses).expect("a moving link");
    assert!((place.cable_to_axis_deg - 90.0).abs() < 1e-9);
    assert!(place.cable_direction().starts_with("across the link, 90°"));
    // The hand has no next joint: its axis is the wrist's, and "up" along it is undefined
    // when the wrist axis is horizontal... it is not here (x), so 0° is the top.
    let hand = robot.link_index("hand").expect("hand");
    let place = link_place(
        &robot,
        hand,
        &pose_from_mm_deg([50.0, 0.0, 30.0], [0.0; 3]),
        &poses,
    )
    .expect("a moving link");
    assert_eq!(place.toward, None);
    assert!((place.along_mm - 50.0).abs() < 1e-9 && (place.off_axis_mm - 30.0).abs() < 1e-9);
    assert!(place.around_deg.abs() < 1e-9);
    // The root link has no joint to measure from.
    assert!(link_place(&robot, 0, &pose_from_mm_deg([0.0; 3], [0.0; 3]), &poses).is_none());
}

/// With the arm raised straight up (elbow turned −90° about y: the forearm along world +z),
/// "top" is undefined for the forearm; 0° is then the front (world +x).
#[test]
fn a_vertical_link_is_measured_from_the_front() {
    let robot = Robot::from_urdf_str(ARM, Path::new("arm.urdf")).expect("valid URDF");
    let poses = robot
        .link_poses(&[0.0, -std::f64::consts::FRAC_PI_2, 0.0])
        .expect("joints");
    let forearm = robot.link_index("forearm").expect("forearm");
    // In the forearm's frame world +x (the front) is −z of the link.
    let clamp = pose_from_mm_deg([100.0, 0.0, -40.0], [0.0; 3]);
    let place = link_place(&robot, forearm, &clamp, &poses).expect("a moving link");
    assert_eq!(place.zero_side, "front");
    assert!(place.around_deg.abs() < 1e-9 || (place.around_deg - 360.0).abs() < 1e-9);
    assert!((place.along_mm - 100.0).abs() < 1e-9);
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
    let setup = cable_dict::setup::Setup::from_file("robots/viper_s850/pick_and_place.toml")
        .expect("setup");
    let poses = &setup
        .installation
        .as_ref()
        .expect("installation pose")
        .link_poses;
    for clamp in clamps {
        let guide = setup
            .guides
            .iter()
            .find(|g| g.name == clamp["guides"][0])
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
        let axis = match clamp["place"]["toward"].as_str() {
            Some(next) => {
                let next = robot.joints.iter().find(|j| j.name == next).expect("joint");
                (poses[next.child_link] * Point3::origin() - start).normalize()
            }
            None => poses[body].rotation * moving.axis.into_inner(),
        };
        let along = (world - start).dot(&axis);
        let off = ((world - start) - axis * along).norm();
        let place = &clamp["place"];
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
}

/// With allowances in the cable file the cut length is the length between the clamps plus
/// both, in the JSON and in the printed summary; without them there is none.
#[test]
fn the_cut_length_adds_the_cable_files_allowances() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().expect("temporary folder");
    let cable = std::fs::read_to_string(root.join("cables/smc_le_cp_3.toml")).expect("cable");
    let cable_path = dir.path().join("cable.toml");
    let with_allowances =
        format!("{cable}tool_end_allowance_mm = 40.0\nbase_end_allowance_mm = 1500.0\n");
    std::fs::write(&cable_path, with_allowances).expect("write cable");
    let setup = std::fs::read_to_string(root.join("robots/viper_s850/pick_and_place.toml"))
        .expect("setup")
        .replace(
            "robot = \"viper_s850.urdf\"",
            &format!(
                "robot = {:?}",
                root.join("robots/viper_s850/viper_s850.urdf")
            ),
        )
        .replace(
            "cable = \"../../cables/smc_le_cp_3.toml\"",
            &format!("cable = {cable_path:?}"),
        );
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
