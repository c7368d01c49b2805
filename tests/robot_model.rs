//! URDF loading and forward kinematics on small hand-made robots, against closed forms
//! written out in each test, and every refusal the loader promises.

use cable_dict::robot::{JointVectorError, Robot, Shape};
use nalgebra::{Rotation3, Vector3};
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

fn load(text: &str) -> Result<Robot, String> {
    Robot::from_urdf_str(text, Path::new("test.urdf")).map_err(|e| e.to_string())
}

fn refusal(text: &str) -> String {
    load(text).expect_err("the URDF must be refused")
}

/// base —(j1: revolute about z, at height 1)→ a —(j2: prismatic along x, 1 m out)→ b
/// —(j3: fixed, 0.5 up, yaw 90°)→ c; and b —(m: continuous about y, mimics j1 ×2 + 0.1)→ d.
const MIXED: &str = r#"<robot name="mixed">
  <link name="base"/> <link name="a"/> <link name="b"/> <link name="c"/> <link name="d"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <origin xyz="0 0 1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="2"/></joint>
  <joint name="j2" type="prismatic"><parent link="a"/><child link="b"/>
    <origin xyz="1 0 0"/><axis xyz="2 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="j3" type="fixed"><parent link="b"/><child link="c"/>
    <origin xyz="0 0 0.5" rpy="0 0 1.5707963267948966"/></joint>
  <joint name="m" type="continuous"><parent link="b"/><child link="d"/>
    <axis xyz="0 1 0"/><mimic joint="j1" multiplier="2" offset="0.1"/></joint>
</robot>"#;

#[test]
fn revolute_prismatic_fixed_and_mimic_joints_follow_their_closed_forms() {
    let robot = load(MIXED).expect("valid URDF");
    assert_eq!(
        robot.dof(),
        2,
        "the mimic and fixed joints are not in the joint vector"
    );
    let (q1, q2) = (0.7, 0.3);
    let poses = robot.link_poses(&[q1, q2]).expect("2 values");
    let pose = |name: &str| poses[robot.link_index(name).expect("link")];
    // b: rotate (1 + q2, 0, 0) by q1 about z, lift by 1 (the axis "2 0 0" is normalised).
    let b = Vector3::new((1.0 + q2) * q1.cos(), (1.0 + q2) * q1.sin(), 1.0);
    assert!((pose("b").translation.vector - b).norm() < 1e-14);
    // c: 0.5 above b, yawed by q1 + 90°.
    assert!((pose("c").translation.vector - (b + Vector3::new(0.0, 0.0, 0.5))).norm() < 1e-14);
    let c_x = Vector3::new((q1 + FRAC_PI_2).cos(), (q1 + FRAC_PI_2).sin(), 0.0);
    assert!((pose("c").rotation * Vector3::x() - c_x).norm() < 1e-14);
    // d: at b, rotated by Rz(q1) then Ry(2 q1 + 0.1).
    let d = Rotation3::from_axis_angle(&Vector3::z_axis(), q1)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), 2.0 * q1 + 0.1);
    let d_pose = pose("d");
    assert!((d_pose.translation.vector - b).norm() < 1e-14);
    assert!((d_pose.rotation.to_rotation_matrix().matrix() - d.matrix()).norm() < 1e-14);
}

#[test]
fn joint_vectors_are_checked_for_length_finiteness_and_limits() {
    let robot = load(MIXED).expect("valid URDF");
    assert!(matches!(
        robot.link_poses(&[0.1]),
        Err(JointVectorError::Length {
            expected: 2,
            got: 1,
            ..
        })
    ));
    assert!(matches!(
        robot.link_poses(&[f64::NAN, 0.0]),
        Err(JointVectorError::NotFinite { .. })
    ));
    match robot.check_limits(&[0.0, 0.6]) {
        Err(JointVectorError::OutOfLimits { joint, unit, .. }) => {
            assert_eq!(joint, "j2");
            assert_eq!(unit.to_string(), "mm");
        }
        other => panic!("expected OutOfLimits for j2, got {other:?}"),
    }
    assert!(
        robot.check_limits(&[1.0, 0.5]).is_ok(),
        "limits are inclusive"
    );
    // Beyond limits is still computable where the caller does not ask for checking.
    assert!(robot.link_poses(&[5.0, 2.0]).is_ok());
}

fn one_joint(joint: &str) -> String {
    format!(r#"<robot name="r"><link name="a"/><link name="b"/>{joint}</robot>"#)
}

#[test]
fn refusals_name_the_file_the_line_and_the_problem() {
    let cases: [(&str, String, &str); 8] = [
        ("no movable joint", one_joint(r#"<joint name="f" type="fixed"><parent link="a"/><child link="b"/></joint>"#), "no movable joint"),
        ("unknown link", one_joint(r#"<joint name="j" type="continuous"><parent link="a"/><child link="zz"/></joint>"#), "test.urdf:1: <joint name=\"j\">: its child link 'zz' is not defined"),
        ("missing limit", one_joint(r#"<joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint>"#), "range is empty"),
        ("inverted limit", one_joint(r#"<joint name="j" type="revolute"><parent link="a"/><child link="b"/><limit lower="1" upper="-1" velocity="1"/></joint>"#), "range is empty"),
        ("zero axis", one_joint(r#"<joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 0"/></joint>"#), "not a usable direction"),
        ("planar", one_joint(r#"<joint name="j" type="planar"><parent link="a"/><child link="b"/></joint>"#), "not supported"),
        ("mimic of fixed", r#"<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
            <joint name="f" type="fixed"><parent link="a"/><child link="b"/></joint>
            <joint name="m" type="continuous"><parent link="b"/><child link="c"/><mimic joint="f"/></joint></robot>"#.into(), "must name an actuated joint"),
        ("two roots", r#"<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
            <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>"#.into(), "links a, c have no parent joint"),
    ];
    for (what, urdf, expected) in cases {
        let message = refusal(&urdf);
        assert!(message.contains(expected), "{what}: got «{message}»");
        assert!(
            message.starts_with("test.urdf"),
            "{what}: no file name in «{message}»"
        );
    }
}

#[test]
fn a_cycle_and_a_second_parent_are_refused() {
    let cycle = r#"<robot name="r"><link name="root"/><link name="a"/><link name="b"/>
        <joint name="r" type="continuous"><parent link="root"/><child link="a"/></joint>
        <joint name="x" type="continuous"><parent link="a"/><child link="b"/></joint>
        <joint name="y" type="continuous"><parent link="b"/><child link="a"/></joint></robot>"#;
    assert!(refusal(cycle).contains("already the child of joint 'r'"));
    let pure_cycle = r#"<robot name="r"><link name="a"/><link name="b"/>
        <joint name="x" type="continuous"><parent link="a"/><child link="b"/></joint>
        <joint name="y" type="continuous"><parent link="b"/><child link="a"/></joint></robot>"#;
    assert!(refusal(pure_cycle).contains("cycle"));
}

#[test]
fn malformed_xml_and_xacro_are_refused_with_the_file_name() {
    let unclosed = refusal("<robot name='r'>\n<link name='a'>");
    assert!(
        unclosed.starts_with("test.urdf:2: the document ends"),
        "{unclosed}"
    );
    let bad_number = refusal(&MIXED.replace(r#"<origin xyz="1 0 0"/>"#, r#"<origin xyz="1 0"/>"#));
    assert!(
        bad_number.starts_with("test.urdf:6: <origin xyz=\"1 0\">: expected 3 numbers"),
        "{bad_number}"
    );
    let xacro = r#"<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
        <xacro:property name="l" value="1"/><link name="a"/></robot>"#;
    let message = refusal(xacro);
    assert!(
        message.starts_with("test.urdf:2: <xacro:property> is a xacro element")
            && message.contains("`pip install xacro`")
            && message.contains("`xacro test.urdf > test.expanded.urdf`"),
        "{message}"
    );
    // A file named .xacro is judged by what it holds: one that uses no xacro is a URDF.
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("arm.urdf.xacro");
    std::fs::write(&path, MIXED).expect("write");
    let robot = Robot::from_urdf_file(&path).expect("a .xacro without xacro loads");
    assert_eq!((robot.name.as_str(), robot.dof()), ("mixed", 2));
    std::fs::write(&path, xacro).expect("write");
    let message = Robot::from_urdf_file(&path).expect_err("xacro").to_string();
    assert!(
        message.starts_with(&format!("{}:2: <xacro:property>", path.display()))
            && message.contains("`xacro arm.urdf.xacro > arm.urdf`"),
        "{message}"
    );
    let missing = Robot::from_urdf_file(dir.path().join("none.urdf"))
        .expect_err("missing file")
        .to_string();
    assert!(
        missing.contains("none.urdf") && missing.contains("cannot read"),
        "{missing}"
    );
}

#[test]
fn primitive_shapes_keep_urdf_dimensions_and_bad_ones_are_refused() {
    let shapes = one_joint(r#"<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>"#)
        .replace(
            r#"<link name="b"/>"#,
            r#"<link name="b">
              <collision><origin xyz="0 0 0.1"/><geometry><box size="0.2 0.4 0.6"/></geometry></collision>
              <collision><geometry><cylinder radius="0.05" length="0.3"/></geometry></collision>
              <collision><geometry><sphere radius="0.07"/></geometry></collision>
              <collision><geometry><capsule radius="0.02" length="0.1"/></geometry></collision>
            </link>"#,
        );
    let robot = load(&shapes).expect("valid shapes");
    let colliders = &robot.links[robot.link_index("b").expect("b")].colliders;
    assert_eq!(colliders.len(), 4);
    assert!(
        matches!(colliders[0].shape, Shape::Box { half_extents_m } if half_extents_m == Vector3::new(0.1, 0.2, 0.3))
    );
    assert!((colliders[0].origin.translation.vector.z - 0.1).abs() < 1e-15);
    assert!(matches!(
        colliders[1].shape,
        Shape::Cylinder {
            radius_m: 0.05,
            length_m: 0.3
        }
    ));
    assert!(matches!(
        colliders[2].shape,
        Shape::Sphere { radius_m: 0.07 }
    ));
    assert!(matches!(
        colliders[3].shape,
        Shape::Capsule {
            radius_m: 0.02,
            length_m: 0.1
        }
    ));

    let bad = shapes.replace(r#"radius="0.07""#, r#"radius="-0.07""#);
    let message = refusal(&bad);
    assert!(
        message.contains("<link name=\"b\">")
            && message.contains("<collision> #3")
            && message.contains("sphere radius"),
        "{message}"
    );
}

/// A unit right tetrahedron as ASCII STL (vertices in millimetres).
const TETRAHEDRON_STL: &str = include_str!("data/tetrahedron.stl");

fn mesh_robot(filename: &str) -> String {
    one_joint(r#"<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>"#).replace(
        r#"<link name="b"/>"#,
        &format!(
            r#"<link name="b"><collision><geometry><mesh filename="{filename}" scale="0.001 0.002 0.001"/></geometry></collision></link>"#
        ),
    )
}

#[test]
fn stl_meshes_resolve_relative_and_package_paths_and_are_scaled() {
    let root = tempfile::tempdir().expect("temp dir");
    let package = root.path().join("my_robot_description");
    std::fs::create_dir_all(package.join("meshes")).expect("mkdir");
    std::fs::create_dir_all(package.join("urdf")).expect("mkdir");
    std::fs::write(package.join("meshes/t.stl"), TETRAHEDRON_STL).expect("write stl");

    for filename in [
        "../meshes/t.stl",
        "package://my_robot_description/meshes/t.stl",
    ] {
        let urdf_path = package.join("urdf/robot.urdf");
        std::fs::write(&urdf_path, mesh_robot(filename)).expect("write urdf");
        let robot = Robot::from_urdf_file(&urdf_path).unwrap_or_else(|e| panic!("{filename}: {e}"));
        let collider = &robot.links[robot.link_index("b").expect("b")].colliders[0];
        let Shape::Mesh(mesh) = &collider.shape else {
            panic!("{filename}: not a mesh")
        };
        assert_eq!(mesh.triangles.len(), 4, "{filename}");
        let extent = mesh
            .vertices
            .iter()
            .fold(Vector3::zeros(), |m: Vector3<f64>, p| m.sup(&p.coords));
        // 10 mm scaled by (0.001, 0.002, 0.001).
        assert!(
            (extent - Vector3::new(0.010, 0.020, 0.010)).norm() < 1e-9,
            "{filename}: {extent:?}"
        );
    }
}

#[test]
fn missing_unreadable_and_non_stl_meshes_are_refused() {
    // A link to a device is named as what it is, not as missing.
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("junk.stl"), "this is not an STL file").expect("write");
    std::fs::write(dir.path().join("arm.dae"), "<COLLADA/>").expect("write");
    std::os::unix::fs::symlink("/dev/zero", dir.path().join("zero.stl")).expect("link");
    let cases = [
        ("meshes/none.stl", "does not exist"),
        ("zero.stl", "zero.stl is not a regular file (a device)"),
        (
            "package://no_such_package/none.stl",
            "no folder named 'no_such_package'",
        ),
        ("junk.stl", "not a readable STL file"),
        ("arm.dae", "only STL meshes are supported"),
    ];
    for (filename, expected) in cases {
        let urdf_path = dir.path().join("robot.urdf");
        std::fs::write(&urdf_path, mesh_robot(filename)).expect("write urdf");
        let message = Robot::from_urdf_file(&urdf_path)
            .expect_err(filename)
            .to_string();
        assert!(message.contains(expected), "{filename}: «{message}»");
        assert!(
            message.contains("robot.urdf:1: <link name=\"b\">"),
            "{filename}: «{message}»"
        );
    }
}
