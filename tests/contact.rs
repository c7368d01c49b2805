//! The contact metric on hand-made robots, each case against a clearance written out in the
//! test from elementary geometry: spheres, boxes (face, edge, corner), cylinders (side, cap,
//! rim), moved links, clamp zones, a mesh cube against the same box, and the bundled Viper.

use cable_dict::robot::Robot;
use cable_dict::stress::contact::{
    ClampZone, Clearance, ContactError, GuideEnd, Obstacles, min_clearance, min_clearance_to_links,
};
use nalgebra::{Point3, Vector3};
use std::path::Path;

/// Cable radius used throughout (m), the 8 mm SMC cable.
const R: f64 = 0.004;
const TOL: f64 = 1e-9;

/// A robot whose `link_1` (index 1) carries the given `<collision>` elements, moved by a
/// prismatic joint along x (zero at q = 0); `extra` adds links/joints.
fn robot_with(collisions: &str, extra: &str) -> Robot {
    let text = format!(
        r#"<robot name="test">
  <link name="base_link"/>
  <link name="link_1">{collisions}</link>
  <joint name="j1" type="prismatic"><parent link="base_link"/><child link="link_1"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  {extra}
</robot>"#
    );
    match Robot::from_urdf_str(&text, Path::new("test.urdf")) {
        Ok(robot) => robot,
        Err(e) => panic!("test URDF refused: {e}"),
    }
}

fn collision(xyz: &str, rpy: &str, geometry: &str) -> String {
    format!(
        r#"<collision><origin xyz="{xyz}" rpy="{rpy}"/><geometry>{geometry}</geometry></collision>"#
    )
}

/// `n` equal sub-segments from `a` to `b`.
fn line(a: [f64; 3], b: [f64; 3], n: usize) -> Vec<Point3<f64>> {
    let (a, b) = (Point3::from(a), Point3::from(b));
    (0..=n)
        .map(|k| a + (b - a) * (k as f64 / n as f64))
        .collect()
}

/// The minimum clearance at the robot's zero pose, without clamp zones.
fn clearance_at_zero(robot: &Robot, nodes: &[Point3<f64>]) -> Clearance {
    let obstacles = Obstacles::from_robot(robot).expect("obstacles");
    let poses = robot.link_poses(&vec![0.0; robot.dof()]).expect("poses");
    min_clearance(&obstacles, &poses, nodes, R, &[])
        .expect("valid query")
        .expect("something to check")
}

/// Asserts the clearance value and that the reported points and normal are consistent.
fn assert_clearance(c: &Clearance, want: f64, what: &str) {
    assert!(
        (c.clearance_m - want).abs() < TOL,
        "{what}: clearance {} m, want {want} m",
        c.clearance_m
    );
    let gap = c.point_on_link - c.point_on_cable;
    assert!(
        (gap.norm() - want.abs()).abs() < TOL,
        "{what}: the points are {} m apart",
        gap.norm()
    );
    assert!((c.normal.norm() - 1.0).abs() < 1e-12, "{what}: normal");
    assert!(
        (gap - c.normal * (-want)).norm() < TOL,
        "{what}: the points are not along the normal"
    );
}

#[test]
fn sphere_separated_and_penetrating() {
    let robot = robot_with(
        &collision("0.1 0 0.2", "0 0 0", r#"<sphere radius="0.05"/>"#),
        "",
    );
    let centre = Vector3::new(0.1, 0.0, 0.2);
    // A cable along y, beside the centre at distance d along +x: d − 0.05 − r.
    for d in [0.08, 0.054, 0.03] {
        let nodes = line([0.1 + d, -0.1, 0.2], [0.1 + d, 0.1, 0.2], 20);
        let c = clearance_at_zero(&robot, &nodes);
        assert_clearance(&c, d - 0.05 - R, &format!("d = {d}"));
        assert_eq!((c.link, c.collider), (1, 0));
        // The closest axis point is node 10 (y = 0): sub-segment 9 at its end wins the tie.
        assert_eq!(c.sub_segment, 9);
        assert!((c.segment_parameter - 1.0).abs() < 1e-12);
        let on_link = Point3::from(centre + Vector3::new(0.05, 0.0, 0.0));
        assert!((c.point_on_link - on_link).norm() < TOL);
        let on_cable = Point3::new(0.1 + d - R, 0.0, 0.2);
        assert!((c.point_on_cable - on_cable).norm() < TOL);
        assert!((c.normal - Vector3::x()).norm() < 1e-12);
    }
    // Skew: the line through centre + (d, 0, 0) along (0, 1, 1) passes at distance d.
    let d = 0.07;
    let nodes = line([0.1 + d, -0.1, 0.1], [0.1 + d, 0.1, 0.3], 8);
    assert_clearance(&clearance_at_zero(&robot, &nodes), d - 0.05 - R, "skew");
}

#[test]
fn box_face_edge_and_corner_regions() {
    // Half extents (0.2, 0.1, 0.05) centred at (0.1, 0, 0): x ∈ [−0.1, 0.3], y ∈ [−0.1, 0.1],
    // z ∈ [−0.05, 0.05].
    let robot = robot_with(
        &collision("0.1 0 0", "0 0 0", r#"<box size="0.4 0.2 0.1"/>"#),
        "",
    );
    let at = |nodes: Vec<Point3<f64>>| clearance_at_zero(&robot, &nodes);

    // Face: along x, 7 mm above the top face.
    let c = at(line([-0.05, 0.03, 0.057], [0.25, 0.03, 0.057], 30));
    assert_clearance(&c, 0.007 - R, "face");
    assert!((c.normal - Vector3::z()).norm() < 1e-12);
    assert!((c.point_on_link.z - 0.05).abs() < TOL);

    // Edge x = 0.3, z = 0.05 (parallel to y): a cable along y offset by (0.012, 0.009).
    let c = at(line([0.312, -0.05, 0.059], [0.312, 0.05, 0.059], 10));
    assert_clearance(&c, 0.012f64.hypot(0.009) - R, "edge");
    assert!((c.point_on_link.x - 0.3).abs() < TOL && (c.point_on_link.z - 0.05).abs() < TOL);

    // Corner (0.3, 0.1, 0.05): the segment starts at corner + (0.01, 0.02, 0.02) and runs
    // away along +x, so its start is the closest point: |v| − r = 0.03 − r.
    let c = at(line([0.31, 0.12, 0.07], [0.36, 0.12, 0.07], 5));
    assert_clearance(&c, 0.03 - R, "corner");
    assert!((c.point_on_link - Point3::new(0.3, 0.1, 0.05)).norm() < TOL);
    assert_eq!((c.sub_segment, c.segment_parameter), (0, 0.0));

    // Penetrating: along x, 10 mm below the top face, well inside in x and y.
    let c = at(line([0.0, 0.0, 0.04], [0.2, 0.0, 0.04], 20));
    assert_clearance(&c, -0.01 - R, "inside below the top face");
    assert!((c.normal - Vector3::z()).norm() < 1e-12);

    // Piercing vertically 30 mm from the +x face (and 100 mm from ±y): the deepest
    // cross-section is 30 mm deep, for |z| ≤ 20 mm (not the 50 mm the capsule would need to
    // move sideways or the 200 mm along its axis to come out).
    let c = at(line([0.27, 0.0, -0.2], [0.27, 0.0, 0.2], 40));
    assert_clearance(&c, -0.03 - R, "piercing");
    assert!((c.normal - Vector3::x()).norm() < 1e-12);
}

#[test]
fn cylinder_side_cap_and_rim() {
    // Radius 0.06, z from −0.1 to 0.1, on the link origin.
    let robot = robot_with(
        &collision(
            "0 0 0",
            "0 0 0",
            r#"<cylinder radius="0.06" length="0.2"/>"#,
        ),
        "",
    );
    let at = |nodes: Vec<Point3<f64>>| clearance_at_zero(&robot, &nodes);
    // Side, parallel to the axis at ρ = 0.09 (diagonal direction in xy).
    let (cx, cy) = (0.09 * 0.6, 0.09 * 0.8);
    assert_clearance(
        &at(line([cx, cy, -0.05], [cx, cy, 0.05], 10)),
        0.09 - 0.06 - R,
        "side, parallel",
    );
    // Side, across: along y at x = 0.09, z = 0.02.
    let c = at(line([0.09, -0.1, 0.02], [0.09, 0.1, 0.02], 20));
    assert_clearance(&c, 0.09 - 0.06 - R, "side, across");
    assert!((c.normal - Vector3::x()).norm() < 1e-12);
    // Cap: along x, 30 mm above the top cap.
    let c = at(line([-0.03, 0.01, 0.13], [0.03, 0.01, 0.13], 6));
    assert_clearance(&c, 0.03 - R, "cap");
    assert!((c.normal - Vector3::z()).norm() < 1e-12);
    // Rim: along y at x = 0.08, z = 0.12: 20 mm out and 20 mm up from the rim circle.
    let c = at(line([0.08, -0.05, 0.12], [0.08, 0.05, 0.12], 10));
    assert_clearance(&c, 0.02f64.hypot(0.02) - R, "rim");
    assert!((c.point_on_link - Point3::new(0.06, 0.0, 0.1)).norm() < TOL);
    // Penetrating the side: parallel to the axis at ρ = 0.05.
    assert_clearance(
        &at(line([0.05, 0.0, -0.05], [0.05, 0.0, 0.05], 10)),
        -0.01 - R,
        "inside, near the side",
    );
    // Penetrating the cap: along x, 5 mm below the top cap.
    let c = at(line([-0.02, 0.0, 0.095], [0.02, 0.0, 0.095], 4));
    assert_clearance(&c, -0.005 - R, "inside, near the cap");
    assert!((c.normal - Vector3::z()).norm() < 1e-12);

    // The collider's own origin is applied: rolled 90° about x, the axis runs along y.
    let rolled = robot_with(
        &collision(
            "0 0.3 0",
            "1.5707963267948966 0 0",
            r#"<cylinder radius="0.06" length="0.2"/>"#,
        ),
        "",
    );
    let nodes = line([0.09, 0.25, 0.0], [0.09, 0.35, 0.0], 10);
    assert_clearance(
        &clearance_at_zero(&rolled, &nodes),
        0.09 - 0.06 - R,
        "rolled, side",
    );
    let nodes = line([-0.03, 0.43, 0.0], [0.03, 0.43, 0.0], 6);
    assert_clearance(&clearance_at_zero(&rolled, &nodes), 0.03 - R, "rolled, cap");
}

#[test]
fn capsule_collider_between_skew_lines() {
    // Capsule radius 0.03, segment z ∈ [−0.1, 0.1]; a cable along y at x = 0.08, z = 0.05
    // meets it at the common perpendicular: 0.08 − 0.03 − r.
    let robot = robot_with(
        &collision("0 0 0", "0 0 0", r#"<capsule radius="0.03" length="0.2"/>"#),
        "",
    );
    let nodes = line([0.08, -0.1, 0.05], [0.08, 0.1, 0.05], 10);
    assert_clearance(&clearance_at_zero(&robot, &nodes), 0.08 - 0.03 - R, "side");
    // Beyond the end cap: along x at z = 0.15 → 0.05 from the cap centre.
    let nodes = line([-0.1, 0.0, 0.15], [0.1, 0.0, 0.15], 10);
    assert_clearance(&clearance_at_zero(&robot, &nodes), 0.05 - 0.03 - R, "cap");
}

#[test]
fn link_poses_are_applied() {
    // link_1 turns about z at (0.3, 0.2, 0.1) and carries a 0.2 × 0.1 × 0.1 box whose centre
    // is 0.15 out along the link's x axis.
    let text = r#"<robot name="turn">
  <link name="base_link"/>
  <link name="link_1"><collision><origin xyz="0.15 0 0"/>
    <geometry><box size="0.2 0.1 0.1"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base_link"/><child link="link_1"/>
    <origin xyz="0.3 0.2 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"#;
    let robot = Robot::from_urdf_str(text, Path::new("turn.urdf")).expect("valid URDF");
    let obstacles = Obstacles::from_robot(&robot).expect("obstacles");
    for q in [0.6, -1.2, 2.5] {
        let poses = robot.link_poses(&[q]).expect("poses");
        let u = Vector3::new(q.cos(), q.sin(), 0.0);
        let v = Vector3::new(-q.sin(), q.cos(), 0.0);
        let centre = Vector3::new(0.3, 0.2, 0.1) + u * 0.15;
        let vertical = |p: Vector3<f64>| line([p.x, p.y, 0.07], [p.x, p.y, 0.13], 6);
        // Beside the +x face (box half length 0.1), 20 mm in front, 20 mm off-centre.
        let nodes = vertical(centre + u * (0.1 + 0.02) + v * 0.02);
        let c = min_clearance(&obstacles, &poses, &nodes, R, &[])
            .expect("valid")
            .expect("checked");
        assert_clearance(&c, 0.02 - R, &format!("face at q = {q}"));
        assert!((c.normal - u).norm() < 1e-12);
        // Beyond the vertical edge at +x, +y (half width 0.05): offsets 15 mm and 8 mm.
        let nodes = vertical(centre + u * (0.1 + 0.015) + v * (0.05 + 0.008));
        let c = min_clearance(&obstacles, &poses, &nodes, R, &[])
            .expect("valid")
            .expect("checked");
        assert_clearance(&c, 0.015f64.hypot(0.008) - R, &format!("edge at q = {q}"));
    }
}

/// link_1: a box whose top face is z = 0 for x ∈ [0, 1]; link_2 (fixed to link_1): a sphere
/// of radius 0.006 centred 7 mm above x = 0.015 (the middle of sub-segment 1 below).
fn clamp_robot() -> Robot {
    robot_with(
        &collision("0.5 0 -0.05", "0 0 0", r#"<box size="1 0.2 0.1"/>"#),
        &format!(
            r#"<link name="link_2">{}</link>
  <joint name="fix" type="fixed"><parent link="link_1"/><child link="link_2"/></joint>"#,
            collision("0.015 0 0.007", "0 0 0", r#"<sphere radius="0.006"/>"#)
        ),
    )
}

/// Ten 10 mm sub-segments along x: nodes 0–3 lie on the face (axis at z = 0, clearance −r),
/// nodes 4–10 2 mm above it (clearance −2 mm).
fn clamp_nodes() -> Vec<Point3<f64>> {
    (0..=10)
        .map(|k| Point3::new(0.01 * k as f64, 0.0, if k <= 3 { 0.0 } else { 0.002 }))
        .collect()
}

#[test]
fn clamp_zones_exclude_only_their_own_link_near_their_guide() {
    let robot = clamp_robot();
    let obstacles = Obstacles::from_robot(&robot).expect("obstacles");
    let poses = robot.link_poses(&[0.0]).expect("poses");
    let nodes = clamp_nodes();
    let run = |zones: &[ClampZone], links: Option<&[usize]>| {
        match links {
            Some(links) => min_clearance_to_links(&obstacles, &poses, &nodes, R, zones, links),
            None => min_clearance(&obstacles, &poses, &nodes, R, zones),
        }
        .expect("valid")
        .expect("checked")
    };
    // The cable's pitch is 10 mm.
    let start = |length_m| ClampZone::of_length(GuideEnd::Start, 1, length_m, 0.01);
    let own = Some(&[1usize][..]);

    // No zone: the cable lies on its link from the very first sub-segment.
    let c = run(&[], own);
    assert_clearance(&c, -R, "no zone");
    assert_eq!((c.link, c.sub_segment), (1, 0));
    // 30 mm zone: sub-segments 0–2 are excluded; sub-segment 3 still touches at node 3.
    let c = run(&[start(0.03)], own);
    assert_clearance(&c, -R, "30 mm zone");
    assert_eq!((c.link, c.sub_segment), (1, 3));
    assert!((c.segment_parameter - 0.0).abs() < 1e-12);
    // 40 mm zone: what remains is 2 mm above the face.
    let c = run(&[start(0.04)], own);
    assert_clearance(&c, 0.002 - R, "40 mm zone");
    assert_eq!((c.link, c.sub_segment), (1, 4));
    // The zone does not hide the other link: the sphere over sub-segment 1 reaches
    // 0.007 − 0.006 − r = −3 mm, lower than the −2 mm left on link_1.
    let c = run(&[start(0.04)], None);
    assert_clearance(&c, 0.007 - 0.006 - R, "other link inside the zone");
    assert_eq!((c.link, c.collider, c.sub_segment), (2, 0, 1));
    assert!((c.point_on_link - Point3::new(0.015, 0.0, 0.001)).norm() < TOL);
    // A zone on the other link's guide does not exclude link_1.
    let other = ClampZone::of_length(GuideEnd::Start, 2, 0.1, 0.01);
    let c = run(&[other], None);
    assert_eq!((c.link, c.sub_segment), (1, 0));

    // The same from the end guide: reversed nodes, zones measured from node S.
    let reversed: Vec<_> = nodes.iter().rev().copied().collect();
    let end = |length_m| ClampZone::of_length(GuideEnd::End, 1, length_m, 0.01);
    let run_rev = |zones: &[ClampZone]| {
        min_clearance_to_links(&obstacles, &poses, &reversed, R, zones, &[1])
            .expect("valid")
            .expect("checked")
    };
    let c = run_rev(&[end(0.03)]);
    assert_clearance(&c, -R, "30 mm end zone");
    assert_eq!(c.sub_segment, 6);
    let c = run_rev(&[end(0.04)]);
    assert_clearance(&c, 0.002 - R, "40 mm end zone");
    assert_eq!(
        c.sub_segment, 0,
        "first of the sub-segments 2 mm above the face"
    );

    // A zone covering the whole cable leaves nothing to check on that link.
    let none = min_clearance_to_links(&obstacles, &poses, &nodes, R, &[start(1.0)], &[1]);
    assert!(matches!(none, Ok(None)));

    // The zone is a stretch of cable material: the same 30 mm zone on the cable stretched
    // by 0.1 % or shortened by 0.1 % still covers sub-segments 0–2, so the clearance does
    // not jump when the cable breathes in a simulation.
    for factor in [0.999, 1.001] {
        let scaled: Vec<Point3<f64>> = nodes
            .iter()
            .map(|p| Point3::new(p.x * factor, p.y, p.z))
            .collect();
        let c = min_clearance_to_links(&obstacles, &poses, &scaled, R, &[start(0.03)], &[1])
            .expect("valid")
            .expect("checked");
        assert_eq!(c.sub_segment, 3, "scaled by {factor}");
    }
    let zone = |mm: f64| ClampZone::of_length(GuideEnd::Start, 1, mm * 1e-3, 0.01).sub_segments;
    assert_eq!(
        [zone(0.0), zone(20.0), zone(20.5), zone(25.0), zone(-1.0)],
        [0, 2, 3, 3, 0]
    );
}

/// A named cable line (ends in the collider frame) and its expected clearance, if closed-form.
type Case = (&'static str, [f64; 3], [f64; 3], Option<f64>);

/// The 12 outward-wound triangles of the cube ±0.5.
fn unit_cube_stl() -> String {
    let corner = |i: u32| {
        let s = |bit: u32| if i & bit != 0 { 0.5 } else { -0.5 };
        [s(1), s(2), s(4)]
    };
    let triangles = [
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
    let mut text = String::from("solid cube\n");
    for t in triangles {
        text += "facet normal 0 0 0\n outer loop\n";
        for v in t {
            let [x, y, z] = corner(v);
            text += &format!("  vertex {x} {y} {z}\n");
        }
        text += " endloop\nendfacet\n";
    }
    text + "endsolid cube\n"
}

#[test]
fn a_mesh_cube_is_the_same_as_the_box() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("cube.stl"), unit_cube_stl()).expect("write STL");
    let (xyz, rpy) = ("0.1 -0.05 0.2", "0.3 -0.2 0.5");
    let urdf = |geometry: &str| {
        let text = format!(
            r#"<robot name="cube">
  <link name="base_link"/>
  <link name="link_1">{}</link>
  <joint name="j1" type="prismatic"><parent link="base_link"/><child link="link_1"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"#,
            collision(xyz, rpy, geometry)
        );
        let path = dir.path().join("cube.urdf");
        std::fs::write(&path, text).expect("write URDF");
        Robot::from_urdf_file(&path).expect("valid URDF")
    };
    let mesh_robot = urdf(r#"<mesh filename="cube.stl" scale="0.12 0.08 0.06"/>"#);
    let box_robot = urdf(r#"<box size="0.12 0.08 0.06"/>"#);
    let mesh_obstacles = Obstacles::from_robot(&mesh_robot).expect("mesh obstacles");
    assert_eq!(
        mesh_obstacles.winding_meshes().count(),
        0,
        "the cube is closed"
    );
    let box_obstacles = Obstacles::from_robot(&box_robot).expect("box obstacles");
    let poses = box_robot.link_poses(&[0.03]).expect("poses");

    // Cables in the box frame (half extents 0.06, 0.04, 0.03), mapped to the world.
    let frame = poses[1] * box_robot.links[1].colliders[0].origin;
    let cases: [Case; 7] = [
        // Each tilted a little so that its closest point is unique.
        (
            "face",
            [-0.03, 0.0, 0.05],
            [0.03, 0.01, 0.045],
            Some(0.015 - R),
        ),
        (
            "edge",
            [0.07, -0.02, 0.045],
            [0.07, 0.02, 0.04],
            Some(0.01f64.hypot(0.01) - R),
        ),
        (
            "corner",
            [0.07, 0.05, 0.05],
            [0.1, 0.08, 0.09],
            Some(0.01f64.hypot(0.01).hypot(0.02) - R),
        ),
        (
            "shallow",
            [-0.03, 0.0, 0.028],
            [0.03, 0.0, 0.029],
            Some(-0.002 - R),
        ),
        (
            "deep, inside",
            [-0.02, 0.0, -0.004],
            [0.02, 0.0, -0.001],
            Some(-0.029 - R),
        ),
        (
            "piercing",
            [0.05, 0.0, -0.1],
            [0.05, 0.0, 0.1],
            Some(-0.01 - R),
        ),
        ("oblique", [-0.1, -0.07, -0.05], [0.08, 0.06, 0.07], None),
    ];
    for (name, a, b, want) in cases {
        let nodes: Vec<Point3<f64>> = line(a, b, 12).iter().map(|p| frame * p).collect();
        let query = |obstacles| {
            min_clearance(obstacles, &poses, &nodes, R, &[])
                .expect("valid")
                .expect("checked")
        };
        let (m, b) = (query(&mesh_obstacles), query(&box_obstacles));
        if let Some(want) = want {
            assert_clearance(&b, want, name);
        }
        assert_clearance(&m, b.clearance_m, name);
        if name != "oblique" && name != "piercing" {
            // (Where the minimum is a plateau the two may pick different points of it.)
            assert!(
                (m.point_on_link - b.point_on_link).norm() < TOL,
                "{name}: {:?} vs {:?}",
                m.point_on_link,
                b.point_on_link
            );
        }
    }

    // An open mesh (one square, z = 0 in its frame) is a bare surface: listed, and a cable
    // piercing it overlaps by the cable radius only.
    std::fs::write(
        dir.path().join("square.stl"),
        "solid sq\nfacet normal 0 0 1\n outer loop\n  vertex -1 -1 0\n  vertex 1 -1 0\n  \
         vertex 1 1 0\n endloop\nendfacet\nfacet normal 0 0 1\n outer loop\n  \
         vertex -1 -1 0\n  vertex 1 1 0\n  vertex -1 1 0\n endloop\nendfacet\nendsolid sq\n",
    )
    .expect("write STL");
    let square = urdf(r#"<mesh filename="square.stl" scale="0.1 0.1 0.1"/>"#);
    let square_obstacles = Obstacles::from_robot(&square).expect("square obstacles");
    assert_eq!(
        square_obstacles.winding_meshes().collect::<Vec<_>>(),
        [(1, 0)]
    );
    let nodes: Vec<Point3<f64>> = line([0.02, 0.01, -0.05], [0.02, 0.01, 0.05], 10)
        .iter()
        .map(|p| frame * p)
        .collect();
    let c = min_clearance(&square_obstacles, &poses, &nodes, R, &[])
        .expect("valid")
        .expect("checked");
    assert_clearance(&c, -R, "open mesh");

    // A mesh with no area is refused, naming the link and the file.
    std::fs::write(
        dir.path().join("flat.stl"),
        "solid flat\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  \
         vertex 2 0 0\n endloop\nendfacet\nendsolid flat\n",
    )
    .expect("write STL");
    let flat = urdf(r#"<mesh filename="flat.stl"/>"#);
    let err = Obstacles::from_robot(&flat)
        .expect_err("degenerate mesh")
        .to_string();
    assert!(
        err.contains("link_1") && err.contains("flat.stl") && err.contains("zero area"),
        "{err}"
    );
}

#[test]
fn the_reported_link_collider_sub_segment_and_points_are_the_closest() {
    // Three links stacked along z, with spheres; the cable passes closest to the second
    // sphere of link_2.
    let robot = robot_with(
        &collision("0 0 0", "0 0 0", r#"<sphere radius="0.05"/>"#),
        &format!(
            r#"<link name="link_2">{}{}</link>
  <link name="link_3">{}</link>
  <joint name="j2" type="revolute"><parent link="link_1"/><child link="link_2"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="link_2"/><child link="link_3"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>"#,
            collision("-0.2 0 0", "0 0 0", r#"<sphere radius="0.04"/>"#),
            collision("0 0.1 0", "0 0 0", r#"<sphere radius="0.04"/>"#),
            collision("0 0 0", "0 0 0", r#"<sphere radius="0.05"/>"#),
        ),
    );
    let obstacles = Obstacles::from_robot(&robot).expect("obstacles");
    assert_eq!((obstacles.link_count(), obstacles.collider_count()), (4, 4));
    // link_2 turned 90° about z: its second sphere is at (−0.1, 0, 0.3).
    let poses = robot
        .link_poses(&[0.0, std::f64::consts::FRAC_PI_2, 0.0])
        .expect("poses");
    // A cable along x at y = 0.07, z = 0.3, 10 mm sub-segments from x = −0.173: the foot of
    // the perpendicular from that centre, x = −0.1, is 30 % into sub-segment 7.
    let nodes = line([-0.173, 0.07, 0.3], [0.027, 0.07, 0.3], 20);
    let c = min_clearance(&obstacles, &poses, &nodes, R, &[])
        .expect("valid")
        .expect("checked");
    assert_clearance(&c, 0.07 - 0.04 - R, "closest sphere");
    assert_eq!((c.link, c.collider, c.sub_segment), (2, 1, 7));
    assert!((c.segment_parameter - 0.3).abs() < 1e-9);
    assert!((c.point_on_link - Point3::new(-0.1, 0.04, 0.3)).norm() < TOL);
    assert!((c.point_on_cable - Point3::new(-0.1, 0.07 - R, 0.3)).norm() < TOL);
    assert!((c.normal - Vector3::y()).norm() < 1e-12);
    // Restricted to link_3: its sphere at (0, 0, 0.6), 0.3 above the cable, 0.07 aside.
    let c = min_clearance_to_links(&obstacles, &poses, &nodes, R, &[], &[3])
        .expect("valid")
        .expect("checked");
    assert_clearance(&c, 0.3f64.hypot(0.07) - 0.05 - R, "restricted");
    assert_eq!((c.link, c.collider), (3, 0));
}

#[test]
fn exact_ties_go_to_the_lowest_sub_segment_then_link() {
    // link_2 is fixed onto link_1 with the same sphere: every distance ties exactly.
    let sphere = collision("0.2 0 0", "0 0 0", r#"<sphere radius="0.05"/>"#);
    let robot = robot_with(
        &sphere,
        &format!(
            r#"<link name="link_2">{sphere}</link>
  <joint name="fix" type="fixed"><parent link="link_1"/><child link="link_2"/></joint>"#
        ),
    );
    let obstacles = Obstacles::from_robot(&robot).expect("obstacles");
    let poses = robot.link_poses(&[0.0]).expect("poses");
    let nodes = line([0.3, -0.1, 0.0], [0.3, 0.1, 0.0], 4);
    for links in [&[1, 2][..], &[2, 1][..]] {
        let c = min_clearance_to_links(&obstacles, &poses, &nodes, R, &[], links)
            .expect("valid")
            .expect("checked");
        assert_clearance(&c, 0.1 - 0.05 - R, "tie");
        // Node 2 (y = 0) ends sub-segment 1 and starts sub-segment 2.
        assert_eq!((c.sub_segment, c.link), (1, 1));
    }
}

#[test]
fn a_cable_through_the_viper_upper_arm_penetrates_link_2() {
    let robot = Robot::from_urdf_file("robots/viper_s850/viper_s850.urdf").expect("Viper");
    let link_2 = robot.link_index("link_2").expect("link_2");
    let obstacles = Obstacles::from_robot(&robot).expect("obstacles");
    let poses = robot.link_poses(&[0.0; 6]).expect("poses");
    // At q = 0 the upper-arm box (0.505 × 0.16 × 0.15) is centred at (0.2575, 0, 0.335).
    // Along y through its centre, the deepest cross-section is 75 mm (half the height) deep.
    let nodes = line([0.2575, -0.2, 0.335], [0.2575, 0.2, 0.335], 40);
    let c = min_clearance(&obstacles, &poses, &nodes, R, &[])
        .expect("valid")
        .expect("checked");
    assert_eq!(c.link, link_2);
    assert_clearance(&c, -0.075 - R, "through the upper arm");
    assert_eq!(
        c.sub_segment, 19,
        "the plateau |y| ≤ 5 mm starts in sub-segment 19"
    );
    // 20 mm above the box the closest link is still link_2 (the J4 housing of link_3 is
    // 0.0925 − 0.07 = 22.5 mm away).
    let nodes = line([0.2575, -0.2, 0.43], [0.2575, 0.2, 0.43], 40);
    let c = min_clearance(&obstacles, &poses, &nodes, R, &[])
        .expect("valid")
        .expect("checked");
    assert_eq!(c.link, link_2);
    assert_clearance(&c, 0.02 - R, "above the upper arm");
    let link_3 = robot.link_index("link_3").expect("link_3");
    let c = min_clearance_to_links(&obstacles, &poses, &nodes, R, &[], &[link_3])
        .expect("valid")
        .expect("checked");
    assert_clearance(&c, 0.0925 - 0.07 - R, "J4 housing");
}

#[test]
fn invalid_queries_are_refused_and_empty_ones_give_none() {
    let robot = clamp_robot();
    let obstacles = Obstacles::from_robot(&robot).expect("obstacles");
    let poses = robot.link_poses(&[0.0]).expect("poses");
    let nodes = clamp_nodes();
    let err = min_clearance(&obstacles, &poses[..2], &nodes, R, &[]);
    assert!(matches!(
        err,
        Err(ContactError::PoseCount {
            expected: 3,
            got: 2
        })
    ));
    let mut bad = nodes.clone();
    bad[4].y = f64::NAN;
    let err = min_clearance(&obstacles, &poses, &bad, R, &[]).expect_err("NaN node");
    assert!(err.to_string().contains("node 4"), "{err}");
    assert!(min_clearance(&obstacles, &poses, &nodes, -1.0, &[]).is_err());
    let zone = ClampZone::of_length(GuideEnd::Start, 7, 0.01, 0.01);
    assert!(matches!(
        min_clearance(&obstacles, &poses, &nodes, R, &[zone]),
        Err(ContactError::LinkIndex { link: 7, count: 3 })
    ));
    assert!(min_clearance_to_links(&obstacles, &poses, &nodes, R, &[], &[3]).is_err());
    // One node: no sub-segment. No link selected: nothing to check.
    assert!(matches!(
        min_clearance(&obstacles, &poses, &nodes[..1], R, &[]),
        Ok(None)
    ));
    assert!(matches!(
        min_clearance_to_links(&obstacles, &poses, &nodes, R, &[], &[]),
        Ok(None)
    ));
}

#[test]
fn obstacles_can_be_shared_between_threads() {
    fn shareable<T: Send + Sync>() {}
    shareable::<Obstacles>();
}
