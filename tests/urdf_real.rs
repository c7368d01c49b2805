//! Robot descriptions as ROS-Industrial ships them: a URDF that keeps the xacro namespace on
//! `<robot>` but uses no xacro, collision meshes named `package://…` (ASCII and binary STL,
//! scaled and not), loaded also when the URDF, the setup or the waypoint file is named by a
//! bare file name in its own folder. Files that do use xacro are still refused.
//!
//! The package is tests/data/urdf_real/my_robot_description; its meshes are written by
//! tests/data/urdf_real/make_meshes.py, whose parameters the tests restate as their reference.

use crate::common::{self, run_in};
use cable_dict::robot::{Robot, Shape, TriMesh};
use nalgebra::Vector3;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The package folder in the repository.
fn package() -> PathBuf {
    crate::common::root().join("tests/data/urdf_real/my_robot_description")
}

/// What make_meshes.py wrote for a link: triangles, distinct vertices, the bounding box
/// (metres, after the URDF's scale) and the range of the distance from the z axis.
struct Expected {
    link: &'static str,
    file: &'static str,
    triangles: usize,
    vertices: usize,
    min: [f64; 3],
    max: [f64; 3],
    radial: Option<(f64, f64)>,
}

const EXPECTED: [Expected; 3] = [
    // A box in millimetres, x ∈ [-100, 100], y ∈ [-80, 80], z ∈ [0, 100]; the URDF scales it
    // by 0.001.
    Expected {
        link: "base_link",
        file: "meshes/collision/base_link.stl",
        triangles: 12,
        vertices: 8,
        min: [-0.1, -0.08, 0.0],
        max: [0.1, 0.08, 0.1],
        radial: None,
    },
    // A 12-sided tube around z, corners at radii 0.05 and 0.04, z ∈ [0, 0.3]: 8 triangles a
    // side (outer and inner wall, top and bottom annulus).
    Expected {
        link: "link_1",
        file: "meshes/collision/link_1.stl",
        triangles: 96,
        vertices: 48,
        min: [-0.05, -0.05, 0.0],
        max: [0.05, 0.05, 0.3],
        radial: Some((0.04, 0.05)),
    },
    // A prism along y, y ∈ [-0.06, 0.06], over the triangle (0, 0), (0.08, 0), (0, 0.2) in
    // (x, z): two end triangles and three rectangles.
    Expected {
        link: "link_2",
        file: "meshes/collision/link_2.STL",
        triangles: 8,
        vertices: 6,
        min: [0.0, -0.06, 0.0],
        max: [0.08, 0.06, 0.2],
        radial: None,
    },
];

/// The STL files store single-precision floats.
const F32_TOLERANCE_M: f64 = 1e-6;

fn check_mesh(mesh: &TriMesh, expected: &Expected) {
    let link = expected.link;
    assert_eq!(mesh.triangles.len(), expected.triangles, "{link}");
    assert_eq!(mesh.vertices.len(), expected.vertices, "{link}");
    let resolved = mesh.file.canonicalize().expect("the resolved mesh exists");
    let reference = package()
        .join(expected.file)
        .canonicalize()
        .expect("the package's mesh exists");
    assert_eq!(resolved, reference, "{link}");
    let (min, max) = mesh.vertices.iter().fold(
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), p| (lo.inf(&p.coords), hi.sup(&p.coords)),
    );
    for (found, wanted) in [(min, expected.min), (max, expected.max)] {
        assert!(
            (found - Vector3::from(wanted)).amax() < F32_TOLERANCE_M,
            "{link}: bounds {min:?} … {max:?}, expected {:?} … {:?}",
            expected.min,
            expected.max
        );
    }
    if let Some((inner, outer)) = expected.radial {
        let radii: Vec<f64> = mesh.vertices.iter().map(|p| p.x.hypot(p.y)).collect();
        let count = |r: f64| {
            radii
                .iter()
                .filter(|&&x| (x - r).abs() < F32_TOLERANCE_M)
                .count()
        };
        assert_eq!(
            (count(inner), count(outer)),
            (24, 24),
            "{link}: 12 corners at each radius, top and bottom"
        );
    }
}

#[test]
fn a_urdf_with_the_xacro_namespace_but_no_xacro_loads_with_its_package_meshes() {
    let robot =
        Robot::from_urdf_file(package().join("urdf/robot.urdf")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(robot.name, "my_robot");
    assert_eq!(robot.dof(), 2);
    let names: Vec<&str> = robot.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["base_link", "link_1", "link_2", "tool0"]);
    for expected in &EXPECTED {
        let link = &robot.links[robot.link_index(expected.link).expect("link")];
        assert_eq!(link.colliders.len(), 1, "{}", expected.link);
        let Shape::Mesh(mesh) = &link.colliders[0].shape else {
            panic!("{}: not a mesh collider", expected.link)
        };
        check_mesh(mesh, expected);
    }
    let link_2 = &robot.links[robot.link_index("link_2").expect("link_2")];
    assert!((link_2.colliders[0].origin.translation.vector.z - 0.02).abs() < 1e-15);
    let poses = robot.link_poses(&[0.0, 0.0]).expect("two joint values");
    let tool0 = poses[robot.link_index("tool0").expect("tool0")];
    assert!((tool0.translation.vector - Vector3::new(0.0, 0.0, 0.62)).norm() < 1e-12);
}

#[test]
fn robot_info_finds_package_meshes_from_a_bare_file_name() {
    let output = run_in(
        &package().join("urdf"),
        &["robot-info", "robot.urdf", "--json"],
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    let report: Value = serde_json::from_slice(&output.stdout).expect("JSON");
    assert_eq!(report["source"], "robot.urdf");
    let links = report["links"].as_array().expect("links");
    for expected in &EXPECTED {
        let link = links
            .iter()
            .find(|l| l["name"] == expected.link)
            .unwrap_or_else(|| panic!("{} listed", expected.link));
        let description = link["colliders"][0]["description"]
            .as_str()
            .expect("a description");
        assert!(
            description.contains(expected.file)
                && description.ends_with(&format!("({} triangles)", expected.triangles)),
            "{}: {description}",
            expected.link
        );
    }
}

/// Copies the folder `from` into `to`, recursively.
fn copy_folder(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("folder created");
    for entry in std::fs::read_dir(from).expect("folder readable") {
        let entry = entry.expect("entry");
        let target = to.join(entry.file_name());
        if entry.file_type().expect("file type").is_dir() {
            copy_folder(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).expect("file copied");
        }
    }
}

/// A copy of the package in a temporary folder, and its urdf folder.
fn package_copy() -> (tempfile::TempDir, PathBuf) {
    let root = tempfile::tempdir().expect("temp dir");
    copy_folder(&package(), &root.path().join("my_robot_description"));
    let urdf = root.path().join("my_robot_description/urdf");
    (root, urdf)
}

#[test]
fn a_setup_and_a_waypoint_file_beside_the_urdf_work_from_bare_file_names() {
    let (_root, urdf) = package_copy();
    write_setup(
        &urdf,
        1,
        r#"[[guides]]
name = "G1"
link = "link_1"
configurations = [{ name = "side", position_mm = [70.0, 0.0, 200.0], rpy_deg = [0.0, 0.0, 0.0] }]

[[guides]]
name = "G2"
link = "link_2"
configurations = [{ name = "front", position_mm = [120.0, 0.0, 100.0], rpy_deg = [0.0, 0.0, 0.0] }]

[[segments]]
from = "G1"
to = "G2"
lengths = { min = 25, max = 30, step = 1, allow_zero = false }
"#,
    );
    let waypoints = r#"robot = "robot.urdf"
sample_rate_hz = 10.0
speed_scale = 0.5
profile = "trapezoidal"
time_to_full_speed_s = 0.25

[[waypoint]]
joints_deg = [0.0, 0.0]

[[waypoint]]
joints_deg = [30.0, 45.0]
"#;
    std::fs::write(urdf.join("waypoints.toml"), waypoints).expect("waypoints written");

    let motion = run_in(&urdf, &["motion", "waypoints.toml", "-o", "motion.csv"]);
    let stderr = String::from_utf8_lossy(&motion.stderr);
    assert_eq!(motion.status.code(), Some(0), "motion: {stderr}");

    let output = run_in(
        &urdf,
        &["critical-poses", "setup.toml", "motion.csv", "--json"],
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "critical-poses: {stderr}");
    let segments: Value = serde_json::from_slice(&output.stdout).expect("JSON");
    assert_eq!(segments[0]["links"][0], "link_1");
    assert_eq!(segments[0]["links"][1], "link_2");
    assert_eq!(segments[0]["traversed_joints"][0], "joint_2");
}

/// Writes `setup.toml` into `dir` (beside robot.urdf): the paper's cable, gravity, limits and
/// robustness, `max_guides_per_link`, then `guides_and_segments`.
fn write_setup(dir: &Path, max_guides_per_link: usize, guides_and_segments: &str) {
    let limits = common::limits("25.0");
    let cable = crate::common::root().join("cables/smc_le_cp_3_paper.toml");
    let setup = format!(
        r#"robot = "robot.urdf"
cable = '{}'
gravity_m_s2 = [0.0, 0.0, -9.81]
max_guides_per_link = {max_guides_per_link}

{limits}
{guides_and_segments}"#,
        cable.display()
    );
    std::fs::write(dir.join("setup.toml"), setup).expect("setup written");
}

/// A dictionary of a robot with mesh colliders embeds the mesh files: built, the package
/// folder deleted, it still opens, verifies, loads its setup with the same collision meshes
/// (vertex for vertex) and solves a motion with `--dict` alone.
#[test]
fn a_dictionary_embeds_the_mesh_files_and_works_without_them() {
    let (root, urdf) = package_copy();
    write_setup(
        &urdf,
        2,
        r#"[[guides]]
name = "G1"
link = "link_2"
configurations = [
  { name = "front low", position_mm = [60.0, 0.0, 60.0], rpy_deg = [0.0, 0.0, 0.0] },
  { name = "front mid", position_mm = [60.0, 0.0, 100.0], rpy_deg = [0.0, 0.0, 0.0] },
]

[[guides]]
name = "G2"
link = "link_2"
configurations = [{ name = "front high", position_mm = [60.0, 0.0, 160.0], rpy_deg = [0.0, 0.0, 0.0] }]

[[segments]]
from = "G1"
to = "G2"
lengths = { min = 8, max = 12, step = 1, allow_zero = false }
"#,
    );
    std::fs::write(
        urdf.join("waypoints.toml"),
        "robot = \"robot.urdf\"\nsample_rate_hz = 10.0\nspeed_scale = 0.5\nprofile = \"trapezoidal\"\n\
         time_to_full_speed_s = 0.25\n\n[[waypoint]]\njoints_deg = [0.0, 0.0]\n\n\
         [[waypoint]]\njoints_deg = [30.0, 45.0]\n",
    )
    .expect("waypoints written");
    let dict = root.path().join("mesh_robot.cdict");
    let motion = root.path().join("motion.csv");
    let dict_arg = dict.to_str().expect("utf-8");
    let motion_arg = motion.to_str().expect("utf-8");
    for args in [
        &["motion", "waypoints.toml", "-o", motion_arg][..],
        &["build", "setup.toml", "--directions", "16", "-o", dict_arg][..],
    ] {
        let output = run_in(&urdf, args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(0), "{args:?}: {stderr}");
    }
    let from_files = Robot::from_urdf_file(urdf.join("robot.urdf")).expect("robot");
    std::fs::remove_dir_all(root.path().join("my_robot_description")).expect("deleted");

    let dictionary = cable_dict::dictionary::Dictionary::open(&dict).expect("opens");
    dictionary.verify().expect("verifies");
    let embedded = dictionary.setup().expect("the embedded setup loads").robot;
    assert_eq!(embedded.mesh_files, from_files.mesh_files);
    assert_eq!(embedded.mesh_files.len(), 3);
    for (a, b) in embedded.links.iter().zip(&from_files.links) {
        for (ca, cb) in a.colliders.iter().zip(&b.colliders) {
            match (&ca.shape, &cb.shape) {
                (Shape::Mesh(ma), Shape::Mesh(mb)) => {
                    assert_eq!((&ma.vertices, &ma.triangles), (&mb.vertices, &mb.triangles));
                }
                (a, b) => panic!("{} vs {}", a.describe(), b.describe()),
            }
        }
    }
    let output = run_in(root.path(), &["solve", "--dict", dict_arg, motion_arg]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "solve --dict: {stderr}");
    let output = run_in(root.path(), &["info", dict_arg]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("3 mesh files embedded"), "{stdout}");
}

/// A xacro file under a URDF's name: the namespace, a macro and its use.
const REAL_XACRO: &str = r#"<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <!-- a comment does not count: <xacro:property/> -->
  <xacro:macro name="arm" params="prefix">
    <link name="${prefix}base_link"/>
  </xacro:macro>
  <xacro:arm prefix=""/>
</robot>
"#;

#[test]
fn a_urdf_that_uses_xacro_is_still_refused_naming_the_file_and_the_element() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("robot.urdf");
    std::fs::write(&path, REAL_XACRO).expect("written");
    let message = Robot::from_urdf_file(&path)
        .expect_err("xacro elements are refused")
        .to_string();
    let expected = format!(
        "{}:4: <xacro:macro> is a xacro element; this is a xacro file, not a URDF: expand it \
         with PyPI's xacro, no ROS needed (`pip install xacro`, then \
         `xacro robot.urdf > robot.expanded.urdf`",
        path.display()
    );
    assert!(message.starts_with(&expected), "{message}");

    let output = run_in(dir.path(), &["robot-info", "robot.urdf"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("robot.urdf:4: <xacro:macro> is a xacro element"),
        "{stderr}"
    );

    // A substitution alone is xacro too.
    let substituted = REAL_XACRO
        .replace(r#"<xacro:arm prefix=""/>"#, "")
        .replace("<xacro:macro name=\"arm\" params=\"prefix\">", "")
        .replace("</xacro:macro>", "");
    let message = Robot::from_urdf_str(&substituted, Path::new("sub.urdf"))
        .expect_err("substitutions are refused")
        .to_string();
    assert!(
        message.starts_with("sub.urdf:5: <link name=\"${prefix}base_link\">: a xacro substitution"),
        "{message}"
    );
}

/// A URDF of a base and one moving link `arm` whose collision is the mesh `filename`.
fn one_mesh_urdf(filename: &str) -> String {
    format!(
        "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"arm\">\n    \
         <collision><geometry><mesh filename=\"{filename}\"/></geometry></collision>\n  \
         </link>\n  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/>\
         <child link=\"arm\"/><axis xyz=\"0 0 1\"/>\
         <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n</robot>\n"
    )
}

/// The four triangles of the tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) (metres).
const TETRAHEDRON: [[[f32; 3]; 3]; 4] = [
    [[0., 0., 0.], [0., 1., 0.], [1., 0., 0.]],
    [[0., 0., 0.], [1., 0., 0.], [0., 0., 1.]],
    [[0., 0., 0.], [0., 0., 1.], [0., 1., 0.]],
    [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
];

#[test]
fn stl_files_some_exporters_write_load_a_binary_one_headed_solid_and_an_ascii_one_unnamed() {
    let dir = tempfile::tempdir().expect("temp dir");
    // Binary, its 80-byte header beginning with "solid" and a line break (as some CAD
    // exporters write it): taken for ASCII by its first line, it is binary by its length.
    let mut binary = b"solid part\n".to_vec();
    binary.resize(80, b' ');
    binary.extend_from_slice(&(TETRAHEDRON.len() as u32).to_le_bytes());
    for triangle in TETRAHEDRON {
        binary.extend_from_slice(&[0u8; 12]);
        for v in triangle.iter().flatten() {
            binary.extend_from_slice(&v.to_le_bytes());
        }
        binary.extend_from_slice(&[0u8; 2]);
    }
    std::fs::write(dir.path().join("binary.stl"), &binary).expect("written");
    // ASCII whose "solid" line has no name.
    let mut ascii = String::from("solid\n");
    for triangle in TETRAHEDRON {
        ascii += "facet normal 0 0 0\nouter loop\n";
        for v in triangle {
            ascii += &format!("vertex {} {} {}\n", v[0], v[1], v[2]);
        }
        ascii += "endloop\nendfacet\n";
    }
    ascii += "endsolid\n";
    std::fs::write(dir.path().join("ascii.stl"), ascii).expect("written");
    for file in ["binary.stl", "ascii.stl"] {
        let urdf = dir.path().join("robot.urdf");
        std::fs::write(&urdf, one_mesh_urdf(file)).expect("written");
        let robot = Robot::from_urdf_file(&urdf).unwrap_or_else(|e| panic!("{file}: {e}"));
        let Shape::Mesh(mesh) = &robot.links[robot.link_index("arm").unwrap()].colliders[0].shape
        else {
            panic!("{file}: not a mesh")
        };
        assert_eq!(mesh.triangles.len(), 4, "{file}");
        assert_eq!(mesh.vertices.len(), 4, "{file}");
        let shells = mesh.shells();
        assert_eq!(shells.shells.len(), 1, "{file}");
        assert!(
            (shells.shells[0].volume_m3 - 1.0 / 6.0).abs() < 1e-12,
            "{file}"
        );
    }
}
