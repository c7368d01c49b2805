//! Xacro files, the real ones committed unexpanded (tests/data/robots/kuka_kr6_support/urdf/
//! kr6r900sixx.xacro and what it includes, see its PROVENANCE.md): refused at the line of
//! their first use of xacro with the way to expand them without ROS (docs/robots.md, "Xacro
//! packages"); a file named `.xacro` that uses no xacro is a URDF and loads. That the
//! expansion gives the committed URDF is scripts/check-xacro-route.sh's check, run by CI.

use crate::common;
use cable_dict::robot::Robot;
use std::path::{Path, PathBuf};

fn robots() -> PathBuf {
    crate::common::root().join("tests/data/robots")
}

/// The refusal of the robot file `path`, which must be refused.
fn refusal(path: &Path) -> (String, Option<usize>) {
    let error = Robot::from_urdf_file(path).expect_err("a xacro file is refused");
    assert_eq!(error.file_path(), path, "{error}");
    (error.to_string(), error.line())
}

/// The advice every xacro refusal carries, for the file `name` expanded into `expanded`.
fn assert_advice(message: &str, name: &str, expanded: &str) {
    for part in [
        "this is a xacro file, not a URDF".to_string(),
        "no ROS needed".to_string(),
        "`pip install xacro`".to_string(),
        format!("then `xacro {name} > {expanded}`"),
        "`name:=value`".to_string(),
        format!("point the setup's `robot` (or the command) at {expanded}"),
        format!(
            "`$(find pkg)`, which PyPI's xacro resolves only with ROS, run `scripts/expand-xacro.sh {name} {expanded}`"
        ),
        "how `$(find pkg)` and `package://` paths resolve: docs/robots.md, \"Xacro packages\""
            .to_string(),
    ] {
        assert!(message.contains(&part), "«{part}» missing from «{message}»");
    }
}

#[test]
fn the_real_xacro_files_are_refused_at_their_first_xacro_use_with_how_to_expand_them() {
    let robot = robots().join("kuka_kr6_support/urdf/kr6r900sixx.xacro");
    let (message, line) = refusal(&robot);
    // Line 3: `<xacro:include filename="$(find kuka_kr6_support)/urdf/kr6r900sixx_macro.xacro" />`
    // (line 2 only declares the namespace on <robot>).
    assert_eq!(line, Some(3), "{message}");
    let expected = format!(
        "{}:3: <xacro:include> is a xacro element; ",
        robot.display()
    );
    assert!(message.starts_with(&expected), "{message}");
    assert_advice(&message, "kr6r900sixx.xacro", "kr6r900sixx.urdf");

    // The files it includes: the macro (its own includes first) and a property file.
    let macro_file = robots().join("kuka_kr6_support/urdf/kr6r900sixx_macro.xacro");
    let (message, line) = refusal(&macro_file);
    assert_eq!(line, Some(3), "{message}");
    assert!(
        message.contains(":3: <xacro:include> is a xacro element"),
        "{message}"
    );
    let constants = robots().join("kuka_resources/urdf/common_constants.xacro");
    let (message, line) = refusal(&constants);
    assert_eq!(line, Some(4), "{message}");
    assert!(
        message.contains(":4: <xacro:property> is a xacro element"),
        "{message}"
    );
    assert_advice(&message, "common_constants.xacro", "common_constants.urdf");

    // The command line says the same, on standard error, with exit status 2.
    let output = common::binary()
        .args(["robot-info", "kr6r900sixx.xacro"])
        .current_dir(robot.parent().expect("folder"))
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("kr6r900sixx.xacro:3: <xacro:include> is a xacro element"),
        "{stderr}"
    );
    assert_advice(&stderr, "kr6r900sixx.xacro", "kr6r900sixx.urdf");
}

#[test]
fn the_suggested_output_never_overwrites_the_input_and_odd_names_are_quoted() {
    let dir = tempfile::tempdir().expect("temp dir");
    let uses_xacro =
        std::fs::read_to_string(robots().join("kuka_kr6_support/urdf/kr6r900sixx.xacro"))
            .expect("committed xacro");
    for (name, command) in [
        // A URDF's name on a xacro file: `xacro robot.urdf > robot.urdf` would empty it.
        ("robot.urdf", "`xacro robot.urdf > robot.expanded.urdf`"),
        ("arm.urdf.xacro", "`xacro arm.urdf.xacro > arm.urdf`"),
        ("ARM.URDF.XACRO", "`xacro ARM.URDF.XACRO > ARM.urdf`"),
        ("arm.xml", "`xacro arm.xml > arm.xml.expanded.urdf`"),
        ("my arm.xacro", "`xacro 'my arm.xacro' > 'my arm.urdf'`"),
        ("it's.xacro", r"`xacro 'it'\''s.xacro' > 'it'\''s.urdf'`"),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, &uses_xacro).expect("write");
        let (message, line) = refusal(&path);
        assert_eq!(line, Some(3), "{message}");
        assert!(
            message.contains(command),
            "{name}: «{command}» not in «{message}»"
        );
    }
}

#[test]
fn a_file_named_urdf_xacro_that_uses_no_xacro_is_a_urdf_and_loads() {
    // The committed hand-expanded KR 6 R900 sixx (it keeps no xacro), its package:// meshes
    // named by absolute file:// URIs, under a .urdf.xacro name.
    let package = robots().join("kuka_kr6_support");
    let urdf = std::fs::read_to_string(package.join("urdf/kr6r900sixx.urdf")).expect("urdf");
    let moved = urdf.replace(
        "package://kuka_kr6_support/",
        &format!("file://{}/", package.display()),
    );
    assert_ne!(moved, urdf, "the URDF names its meshes by package://");
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("kr6r900sixx.urdf.xacro");
    std::fs::write(&path, &moved).expect("write");
    let as_xacro = Robot::from_urdf_file(&path).expect("a .urdf.xacro without xacro loads");
    let as_urdf = Robot::from_urdf_file(package.join("urdf/kr6r900sixx.urdf")).expect("urdf");
    let names = |robot: &Robot| {
        (
            robot
                .links
                .iter()
                .map(|l| l.name.clone())
                .collect::<Vec<_>>(),
            robot
                .joints
                .iter()
                .map(|j| j.name.clone())
                .collect::<Vec<_>>(),
        )
    };
    assert_eq!(names(&as_xacro), names(&as_urdf));
    assert_eq!(
        (as_xacro.name.as_str(), as_xacro.dof()),
        ("kuka_kr6r900sixx", 6)
    );
}
