//! Bodies a setup attaches to the robot (`[[bodies]]`): the gripper or camera the URDF does
//! not describe is an obstacle like the links — a cable through it is in contact by the
//! depth the closed form of its shape gives — clamp zones at guides on its link leave it out,
//! bad entries are refused naming the key, and a setup without bodies keeps its hash.

use crate::common::{self, root};
use cable_dict::robot::Shape;
use cable_dict::setup::Setup;
use cable_dict::stress::{GuideEnd, Obstacles, min_clearance, min_clearance_to_links};
use nalgebra::{Point3, Vector3};

/// A one-segment setup from link_4 to a connector on link_6, with `bodies` appended.
fn setup_text(bodies: &str) -> String {
    format!(
        r#"robot = "robots/viper_s850/viper_s850.urdf"
cable = "cables/smc_le_cp_3.toml"
gravity_m_s2 = [0.0, 0.0, -9.81]
max_guides_per_link = 1

{limits}
[[guides]]
name = "G1"
link = "link_4"
configurations = [{{ name = "back", position_mm = [-72.0, 0.0, 150.0], rpy_deg = [0.0, 0.0, 180.0] }}]

[[guides]]
name = "G2"
link = "link_6"
fixed = {{ name = "connector", position_mm = [60.0, 0.0, 85.0], rpy_deg = [0.0, 0.0, 0.0] }}

[[segments]]
from = "G1"
to = "G2"
lengths = {{ min = 30, max = 40, step = 1, allow_zero = false }}
{bodies}"#,
        limits = common::limits("\"cable\"")
    )
}

fn load(text: &str) -> Result<Setup, String> {
    Setup::from_toml_str(text, &root().join("setup.toml")).map_err(|e| e.to_string())
}

const GRIPPER: &str = r#"
[[bodies]]
name = "gripper"
link = "link_6"
position_mm = [0.0, 0.0, 50.0]
rpy_deg = [0.0, 0.0, 30.0]
box_mm = [44.0, 40.0, 100.0]
"#;

#[test]
fn a_cable_through_the_gripper_touches_it_by_the_boxs_closed_form_depth() {
    let setup = load(&setup_text(GRIPPER)).unwrap_or_else(|e| panic!("{e}"));
    let link_6 = setup.robot.link_index("link_6").unwrap();
    let body = setup.robot.links[link_6]
        .colliders
        .iter()
        .find(|c| c.attached.as_deref() == Some("gripper"))
        .expect("the body is a collider of link_6");
    assert!(matches!(body.shape, Shape::Box { .. }));
    let obstacles = Obstacles::from_robot(&setup.robot).unwrap();
    let q = vec![0.3, -0.6, 2.2, 0.4, 0.5, -0.2];
    let poses = setup.robot.link_poses(&q).unwrap();
    let flange = poses[link_6];
    // A straight cable across the box's middle along its local x (rotated 30° about z): the
    // deepest axis point is the box centre line, 20 mm from the ±y faces — depth 20 mm plus
    // the 4 mm cable radius.
    let along = Vector3::new(30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0);
    let nodes: Vec<Point3<f64>> = (0..=10)
        .map(|k| {
            let s = (k as f64 - 5.0) * 0.02;
            flange * (Point3::new(0.0, 0.0, 0.05) + along * s)
        })
        .collect();
    let c = min_clearance(&obstacles, &poses, &nodes, 0.004, &[])
        .unwrap()
        .expect("checked");
    assert_eq!(setup.robot.links[c.link].name, "link_6");
    assert!((c.clearance_m - (-0.020 - 0.004)).abs() < 1e-12, "{c:?}");
    // The same cable 50 mm beside the box (its +y face at 20 mm): clear by 30 − 4 mm.
    let side =
        flange.rotation * Vector3::new(-(30f64.to_radians().sin()), 30f64.to_radians().cos(), 0.0);
    let beside: Vec<Point3<f64>> = nodes.iter().map(|p| p + side * 0.05).collect();
    let c = min_clearance_to_links(&obstacles, &poses, &beside, 0.004, &[], &[link_6])
        .unwrap()
        .expect("checked");
    assert!((c.clearance_m - 0.026).abs() < 1e-9, "{c:?}");
}

#[test]
fn a_clamp_zone_on_the_bodys_link_leaves_the_body_out() {
    let setup = load(&setup_text(GRIPPER)).unwrap_or_else(|e| panic!("{e}"));
    let link_6 = setup.robot.link_index("link_6").unwrap();
    let obstacles = Obstacles::from_robot(&setup.robot).unwrap();
    let poses = setup.robot.link_poses(&[0.0; 6]).unwrap();
    // Two sub-segments (20 mm, the clamp zone) ending inside the box, at the end guide.
    let nodes: Vec<Point3<f64>> = (0..=2)
        .map(|k| poses[link_6] * Point3::new(0.0, 0.0, 0.09 - 0.01 * k as f64))
        .collect();
    let zone = setup.clamp_zone(GuideEnd::End, link_6);
    assert_eq!(zone.sub_segments, 2);
    let none = min_clearance(&obstacles, &poses, &nodes, 0.004, &[zone]).unwrap();
    assert!(none.is_none_or(|c| c.link != link_6), "{none:?}");
    let touching = min_clearance(&obstacles, &poses, &nodes, 0.004, &[]).unwrap();
    assert!(touching.is_some_and(|c| c.link == link_6 && c.clearance_m < 0.0));
}

#[test]
fn body_shapes_are_read_in_millimetres_and_a_mesh_is_embedded() {
    let dir = tempfile::tempdir().unwrap();
    // A 10 × 20 × 30 mm box as an ASCII STL in millimetres, scaled to metres.
    let stl = cube_stl([10.0, 20.0, 30.0]);
    std::fs::write(dir.path().join("camera.stl"), stl).unwrap();
    let bodies = r#"
[[bodies]]
name = "lens"
link = "link_6"
position_mm = [-65.0, 0.0, 150.0]
rpy_deg = [0.0, 0.0, 0.0]
cylinder_mm = { radius = 16.0, length = 40.0 }

[[bodies]]
name = "ball"
link = "link_5"
position_mm = [0.0, 0.0, 0.0]
rpy_deg = [0.0, 0.0, 0.0]
sphere_radius_mm = 50.0

[[bodies]]
name = "camera"
link = "link_6"
position_mm = [-65.0, 0.0, 100.0]
rpy_deg = [0.0, 0.0, 0.0]
mesh = "camera.stl"
mesh_scale = [0.001, 0.001, 0.001]
"#;
    let text = setup_text(bodies)
        .replace(
            "robots/viper_s850/viper_s850.urdf",
            &root()
                .join("robots/viper_s850/viper_s850.urdf")
                .display()
                .to_string(),
        )
        .replace(
            "cables/smc_le_cp_3.toml",
            &root().join("cables/smc_le_cp_3.toml").display().to_string(),
        );
    let path = dir.path().join("setup.toml");
    let setup = Setup::from_toml_str(&text, &path).unwrap_or_else(|e| panic!("{e}"));
    let attached = |name: &str| {
        setup
            .robot
            .links
            .iter()
            .flat_map(|l| &l.colliders)
            .find(|c| c.attached.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("{name}"))
    };
    assert!(
        matches!(attached("lens").shape, Shape::Cylinder { radius_m, length_m } if radius_m == 0.016 && length_m == 0.04)
    );
    assert!(matches!(attached("ball").shape, Shape::Sphere { radius_m } if radius_m == 0.05));
    let Shape::Mesh(mesh) = &attached("camera").shape else {
        panic!("a mesh");
    };
    let extent = mesh
        .vertices
        .iter()
        .fold(Vector3::zeros(), |e: Vector3<f64>, v| {
            e.sup(&v.coords.abs())
        });
    assert!(
        (extent - Vector3::new(0.005, 0.010, 0.015)).norm() < 1e-9,
        "{extent:?}"
    );
    assert!(setup.robot.mesh_files.iter().any(|f| f.uri == "camera.stl"));
    // As a dictionary reloads it: the texts and the embedded files, no file on disk.
    std::fs::remove_file(dir.path().join("camera.stl")).unwrap();
    let again = Setup::from_texts(
        &setup.text,
        &path,
        &setup.robot_text,
        &setup.cable_text,
        &setup.robot.mesh_files,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(again.content_hash, setup.content_hash);
}

#[test]
fn bad_bodies_are_refused_naming_the_key_and_bodies_change_the_hash() {
    let plain = load(&setup_text("")).unwrap();
    let with = load(&setup_text(GRIPPER)).unwrap();
    assert_ne!(plain.content_hash, with.content_hash);
    let cases = [
        (
            GRIPPER.replace(
                "box_mm = [44.0, 40.0, 100.0]",
                "box_mm = [44.0, 0.0, 100.0]",
            ),
            "bodies[0].box_mm",
        ),
        (
            GRIPPER.replace("link = \"link_6\"", "link = \"link_9\""),
            "bodies[0].link",
        ),
        (
            GRIPPER.replace(
                "box_mm = [44.0, 40.0, 100.0]",
                "sphere_radius_mm = 5.0\nbox_mm = [1.0, 1.0, 1.0]",
            ),
            "exactly one",
        ),
        (
            GRIPPER.replace("box_mm = [44.0, 40.0, 100.0]", ""),
            "exactly one",
        ),
        (
            GRIPPER.replace("box_mm = [44.0, 40.0, 100.0]", "mesh = \"no_such.stl\""),
            "bodies[0].mesh",
        ),
        (format!("{GRIPPER}{GRIPPER}"), "used twice"),
        (
            GRIPPER.replace(
                "position_mm = [0.0, 0.0, 50.0]",
                "position_mm = [0.0, nan, 50.0]",
            ),
            "bodies[0].position_mm",
        ),
    ];
    for (bodies, says) in cases {
        let err = load(&setup_text(&bodies)).expect_err(says);
        assert!(
            err.contains(says) && err.contains("setup.toml"),
            "{says}: {err}"
        );
    }
}

/// An ASCII STL of a box of `size` (mm) centred on the origin, wound outward.
fn cube_stl(size: [f64; 3]) -> String {
    let h = size.map(|s| s / 2.0);
    let v = |i: usize| {
        [
            if i & 1 != 0 { h[0] } else { -h[0] },
            if i & 2 != 0 { h[1] } else { -h[1] },
            if i & 4 != 0 { h[2] } else { -h[2] },
        ]
    };
    let faces = [
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    let mut out = String::from("solid box\n");
    for f in faces {
        out.push_str("facet normal 0 0 0\n outer loop\n");
        for i in f {
            let [x, y, z] = v(i);
            out.push_str(&format!("  vertex {x} {y} {z}\n"));
        }
        out.push_str(" endloop\nendfacet\n");
    }
    out + "endsolid box\n"
}

/// A connector written inside the gripper's body (an easy slip once the tool is modelled) is
/// named in a warning when the setup is read: every piece into it would touch the body.
#[test]
fn a_clamp_inside_a_body_is_warned_about_naming_the_body() {
    let dir = tempfile::tempdir().unwrap();
    let text = setup_text(GRIPPER)
        .replace(
            "robots/viper_s850/viper_s850.urdf",
            &root()
                .join("robots/viper_s850/viper_s850.urdf")
                .display()
                .to_string(),
        )
        .replace(
            "cables/smc_le_cp_3.toml",
            &root().join("cables/smc_le_cp_3.toml").display().to_string(),
        );
    let path = dir.path().join("setup.toml");
    let run = |text: &str| {
        std::fs::write(&path, text).unwrap();
        common::binary()
            .args(["sites", path.to_str().unwrap()])
            .output()
            .unwrap()
    };
    let clear = run(&text);
    assert!(clear.status.success());
    assert!(!String::from_utf8_lossy(&clear.stderr).contains("inside"));
    // The connector 20 mm off the flange axis, 30 mm beyond the flange: inside the 44 × 40 mm
    // box, 20 mm from its nearest face (the box is turned 30° about z).
    let buried = run(&text.replace(
        "position_mm = [60.0, 0.0, 85.0]",
        "position_mm = [0.0, 0.0, 30.0]",
    ));
    let stderr = String::from_utf8_lossy(&buried.stderr);
    assert!(buried.status.success(), "{stderr}");
    assert!(
        stderr.contains("G2 \"connector\"")
            && stderr.contains("20.0 mm inside body \"gripper\" on link_6"),
        "{stderr}"
    );
}
