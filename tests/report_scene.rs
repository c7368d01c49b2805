//! The glTF scene writer, read back through the `gltf` crate and checked against the inputs:
//! forward kinematics for the link nodes, the centreline polylines for the cable tubes and
//! sub-segments, the URDF's dimensions for the colliders.
//!
//! Set `CABLE_DICT_SCENE_OUT=/path/scene.glb` (and `CABLE_DICT_SHAPES_OUT=/path/shapes.glb`)
//! to keep the test scenes, e.g. for the Khronos validator: `scripts/validate-gltf.sh
//! /path/scene.glb`.

use cable_dict::pose::pose_from_mm_deg;
use cable_dict::report::scene::{
    COLOUR_VARIANTS, CableLine, CableTint, ClampPart, GuideMark, INSTALLATION_ANIMATION, PoseScene,
    SceneAnimation, SceneError, SceneSpec, Snapshot, to_glb,
};
use cable_dict::robot::Robot;
use gltf::animation::Property;
use gltf::animation::util::ReadOutputs;
use nalgebra::{Matrix3, Matrix4, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use std::f64::consts::PI;

const RADIUS: f64 = 0.006;
const TIMES: [f64; 3] = [0.0, 0.5, 1.25];
const JOINTS: [[f64; 6]; 3] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.4, -0.3, 0.5, 0.8, -0.6, 1.2],
    [-0.7, 0.5, -0.2, -1.1, 0.9, -2.0],
];
/// Cable nodes per line.
const NODES: [usize; 2] = [20, 8];

/// The z-up robot world as seen in glTF's y-up world: (x, y, z) → (x, z, −y).
fn y_up() -> Matrix4<f64> {
    Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0).to_homogeneous()
}

fn robot() -> Robot {
    Robot::from_urdf_file("robots/viper_s850/viper_s850.urdf").expect("the Viper loads")
}

fn link(robot: &Robot, name: &str) -> usize {
    robot.link_index(name).expect("link exists")
}

/// A polyline of `n` nodes from `a` to `b`: a sagging chord with a helical wobble that
/// vanishes at both ends.
fn cable_polyline(a: Point3<f64>, b: Point3<f64>, n: usize, phase: f64) -> Vec<Point3<f64>> {
    (0..n)
        .map(|k| {
            let s = k as f64 / (n - 1) as f64;
            let chord = (b - a).norm();
            let sag = Vector3::new(0.0, 0.0, -0.2 * chord * 4.0 * s * (1.0 - s));
            let angle = 2.0 * PI * s + phase;
            let wobble =
                Vector3::new(angle.cos(), angle.sin(), 0.0) * 0.05 * chord * (PI * s).sin();
            a + (b - a) * s + sag + wobble
        })
        .collect()
}

/// Robot and cable at joint vector `q`: C1 from link_2 to link_4, C2 from link_4 to tool0.
fn pose_scene(robot: &Robot, q: &[f64; 6], phase: f64) -> PoseScene {
    let poses = robot.link_poses(q).expect("6 joints");
    let on = |name: &str, p: [f64; 3]| poses[link(robot, name)] * Point3::from(p);
    let (a, b, c) = (
        on("link_2", [0.05, 0.0, 0.1]),
        on("link_4", [0.0, 0.08, 0.05]),
        on("tool0", [0.0, 0.06, -0.03]),
    );
    PoseScene {
        link_poses: poses,
        cable: vec![
            CableLine {
                name: "C1".into(),
                nodes_m: cable_polyline(a, b, NODES[0], phase),
            },
            CableLine {
                name: "C2".into(),
                nodes_m: cable_polyline(b, c, NODES[1], -phase),
            },
        ],
    }
}

fn spec(robot: &Robot) -> SceneSpec<'_> {
    let frames: Vec<PoseScene> = JOINTS
        .iter()
        .enumerate()
        .map(|(i, q)| pose_scene(robot, q, 0.4 * i as f64))
        .collect();
    SceneSpec {
        robot,
        cable_radius_m: RADIUS,
        main: frames[0].clone(),
        guides: vec![
            GuideMark {
                name: "G1 (link_2/side)".into(),
                clamp: "G1".into(),
                link: link(robot, "link_2"),
                pose_in_link: pose_from_mm_deg([100.0, 0.0, 100.0], [0.0, 90.0, 0.0]),
                part: ClampPart::Rigid,
            },
            GuideMark {
                name: "G2 (link_4/top)".into(),
                clamp: "G2".into(),
                link: link(robot, "link_4"),
                pose_in_link: pose_from_mm_deg([0.0, 80.0, 50.0], [-90.0, 0.0, 30.0]),
                part: ClampPart::Rigid,
            },
        ],
        animation: Some(SceneAnimation {
            name: "motion test".into(),
            times_s: TIMES.to_vec(),
            frames: frames.clone(),
        }),
        other_motions: Vec::new(),
        snapshots: vec![
            Snapshot {
                name: "critical pose 1: C1 joint_2 min, t = 0.500 s".into(),
                scene: frames[1].clone(),
                offset_m: Vector3::new(1.5, 0.0, 0.0),
            },
            Snapshot {
                name: "critical pose 2: C2 joint_5 max, t = 1.250 s".into(),
                scene: frames[2].clone(),
                offset_m: Vector3::new(0.0, -1.5, 0.2),
            },
        ],
        tints: Vec::new(),
        damage: Vec::new(),
        installation: None,
    }
}

/// The scene's bytes, also written to the file named by environment variable `keep_in`
/// when it is set.
fn glb_kept(spec: &SceneSpec<'_>, keep_in: &str) -> Vec<u8> {
    let bytes = to_glb(spec).expect("the scene is written");
    if let Some(path) = std::env::var_os(keep_in) {
        std::fs::write(path, &bytes).unwrap_or_else(|e| panic!("write {keep_in}: {e}"));
    }
    bytes
}

/// The test scene's bytes, also written to `CABLE_DICT_SCENE_OUT` when set.
fn glb(spec: &SceneSpec<'_>) -> Vec<u8> {
    glb_kept(spec, "CABLE_DICT_SCENE_OUT")
}

/// The document and its binary chunk.
fn import(bytes: &[u8]) -> (gltf::Document, Vec<u8>) {
    let gltf = gltf::Gltf::from_slice(bytes).expect("the gltf crate reads it");
    let blob = gltf.blob.clone().expect("a BIN chunk");
    (gltf.document, blob)
}

fn trs_matrix(t: [f32; 3], r: [f32; 4], s: [f32; 3]) -> Matrix4<f64> {
    let [t, s] = [t, s].map(|v| Vector3::new(v[0], v[1], v[2]).cast::<f64>());
    let q = Quaternion::new(r[3], r[0], r[1], r[2]).cast::<f64>();
    Translation3::from(t).to_homogeneous()
        * UnitQuaternion::from_quaternion(q).to_homogeneous()
        * Matrix4::new_nonuniform_scaling(&s)
}

/// World matrix (glTF frame) of every node reachable from the default scene.
fn world_matrices(doc: &gltf::Document) -> Vec<Option<Matrix4<f64>>> {
    fn visit(node: gltf::Node<'_>, parent: Matrix4<f64>, out: &mut Vec<Option<Matrix4<f64>>>) {
        let (t, r, s) = node.transform().decomposed();
        let world = parent * trs_matrix(t, r, s);
        assert!(
            out[node.index()].is_none(),
            "node {} has two parents",
            node.index()
        );
        out[node.index()] = Some(world);
        for child in node.children() {
            visit(child, world, out);
        }
    }
    let mut out = vec![None; doc.nodes().len()];
    let scene = doc.default_scene().expect("a default scene");
    for node in scene.nodes() {
        visit(node, Matrix4::identity(), &mut out);
    }
    out
}

fn child<'a>(node: &gltf::Node<'a>, name: &str) -> gltf::Node<'a> {
    node.children()
        .find(|c| c.name() == Some(name))
        .unwrap_or_else(|| panic!("{:?} has no child {name}", node.name()))
}

fn root(doc: &gltf::Document) -> gltf::Node<'_> {
    let scene = doc.default_scene().expect("a default scene");
    let roots: Vec<_> = scene.nodes().collect();
    assert_eq!(roots.len(), 1);
    roots[0].clone()
}

fn assert_matrix_near(got: &Matrix4<f64>, want: &Matrix4<f64>, tol: f64, what: &str) {
    let error = (got - want).abs().max();
    assert!(
        error < tol,
        "{what}: off by {error}\n got {got}\nwant {want}"
    );
}

fn positions(mesh: &gltf::Mesh<'_>, blob: &[u8]) -> Vec<Point3<f64>> {
    let primitive = mesh.primitives().next().expect("a primitive");
    let reader = primitive.reader(|_| Some(blob));
    reader
        .read_positions()
        .expect("POSITION")
        .map(|p| Point3::new(p[0], p[1], p[2]).cast::<f64>())
        .collect()
}

#[test]
fn counts_names_and_keyframes_survive_the_round_trip() {
    let robot = robot();
    let spec = spec(&robot);
    let bytes = glb(&spec);
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!(bytes[4..8], 2u32.to_le_bytes());
    assert_eq!(bytes[8..12], (bytes.len() as u32).to_le_bytes());
    let (doc, _) = import(&bytes);

    let links = robot.links.len();
    let colliders: usize = robot.links.iter().map(|l| l.colliders.len()).sum();
    let guides = spec.guides.len();
    let lines = spec.main.cable.len();
    let cable_nodes: usize = NODES.iter().map(|n| 1 + (n - 1) + n).sum();
    let snapshots = spec.snapshots.len();
    let copy = links + colliders + guides;
    // root, robot, cable, main copy, main cable, snapshots (node, copy, one tube per line)
    let expected_nodes = 3 + copy + cable_nodes + snapshots * (1 + copy + lines);
    assert_eq!(doc.nodes().len(), expected_nodes);
    // one per collider, guide marker, unit cylinder, joint sphere, one tube per snapshot line
    assert_eq!(doc.meshes().len(), colliders + 3 + snapshots * lines);
    assert_eq!(doc.materials().len(), 3);
    assert_eq!(doc.scenes().len(), 1);

    let root = root(&doc);
    assert_eq!(root.name(), Some("robot world (z up)"));
    let names: Vec<_> = root
        .children()
        .map(|c| c.name().map(str::to_owned))
        .collect();
    let mut want = vec![Some("robot".to_owned()), Some("cable".to_owned())];
    want.extend(spec.snapshots.iter().map(|s| Some(s.name.clone())));
    assert_eq!(names, want);
    let link_names: Vec<_> = child(&root, "robot")
        .children()
        .map(|c| c.name().map(str::to_owned))
        .collect();
    let want: Vec<_> = robot.links.iter().map(|l| Some(l.name.clone())).collect();
    assert_eq!(link_names, want);
    let c1 = child(&child(&root, "cable"), "C1");
    assert_eq!(c1.children().count(), 2 * NODES[0] - 1);
    assert!(c1.children().any(|c| c.name() == Some("C1 sub-segment 7")));

    let animations: Vec<_> = doc.animations().collect();
    assert_eq!(animations.len(), 1);
    assert_eq!(animations[0].name(), Some("motion test"));
    let segments: usize = NODES.iter().map(|n| n - 1).sum();
    let joints: usize = NODES.iter().sum();
    assert_eq!(
        animations[0].channels().count(),
        2 * links + 3 * segments + joints
    );
    let (_, blob) = import(&bytes);
    for channel in animations[0].channels() {
        let reader = channel.reader(|_| Some(&blob[..]));
        let times: Vec<f32> = reader.read_inputs().expect("times").collect();
        let want: Vec<f32> = TIMES.iter().map(|&t| t as f32).collect();
        assert_eq!(times, want);
    }
}

#[test]
fn link_and_guide_nodes_sit_at_the_forward_kinematics_poses() {
    let robot = robot();
    let spec = spec(&robot);
    let (doc, _) = import(&glb(&spec));
    let world = world_matrices(&doc);
    let root = root(&doc);
    let copies = std::iter::once((child(&root, "robot"), &spec.main, Vector3::zeros())).chain(
        spec.snapshots
            .iter()
            .map(|s| (child(&root, &s.name), &s.scene, s.offset_m)),
    );
    for (copy, scene, offset) in copies {
        for (l, link_node) in copy.children().filter(|c| c.mesh().is_none()).enumerate() {
            let pose = Translation3::from(offset) * scene.link_poses[l];
            let got = world[link_node.index()].expect("reachable");
            let what = format!("{:?} link {}", copy.name(), robot.links[l].name);
            assert_matrix_near(&got, &(y_up() * pose.to_homogeneous()), 1e-6, &what);
            for guide in spec.guides.iter().filter(|g| g.link == l) {
                let marker = child(&link_node, &guide.name);
                let want = y_up() * (pose * guide.pose_in_link).to_homogeneous();
                assert_matrix_near(
                    &world[marker.index()].expect("reachable"),
                    &want,
                    1e-6,
                    &guide.name,
                );
            }
        }
    }
}

fn distance_to_segment(p: &Point3<f64>, a: &Point3<f64>, b: &Point3<f64>) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

fn distance_to_polyline(p: &Point3<f64>, nodes: &[Point3<f64>]) -> f64 {
    nodes
        .windows(2)
        .map(|w| distance_to_segment(p, &w[0], &w[1]))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn snapshot_tubes_lie_at_the_cable_radius_around_their_centrelines() {
    let robot = robot();
    let spec = spec(&robot);
    let (doc, blob) = import(&glb(&spec));
    let world = world_matrices(&doc);
    let root = root(&doc);
    for snapshot in &spec.snapshots {
        let node = child(&root, &snapshot.name);
        for line in &snapshot.scene.cable {
            let tube = child(&node, &line.name);
            // Back to the robot's world frame, without the snapshot's offset.
            let to_robot = Translation3::from(-snapshot.offset_m).to_homogeneous()
                * y_up().transpose()
                * world[tube.index()].expect("reachable");
            let vertices: Vec<Point3<f64>> = positions(&tube.mesh().expect("a tube mesh"), &blob)
                .iter()
                .map(|p| to_robot.transform_point(p))
                .collect();
            assert!(
                vertices.len() >= 12 * line.nodes_m.len(),
                "{}: {} vertices",
                line.name,
                vertices.len()
            );
            for p in &vertices {
                let d = distance_to_polyline(p, &line.nodes_m);
                assert!(
                    (d - RADIUS).abs() < 1e-6,
                    "{} {}: vertex {p:?} at {d} m",
                    snapshot.name,
                    line.name
                );
            }
            for k in 0..line.nodes_m.len() {
                assert_surrounded(&vertices, &line.nodes_m, k);
            }
        }
    }
}

/// Around node `k`, in every direction normal to the centreline, some vertex lies within
/// two radii (the tube is not one-sided).
fn assert_surrounded(vertices: &[Point3<f64>], nodes: &[Point3<f64>], k: usize) {
    let (before, after) = (
        nodes[k.saturating_sub(1)],
        nodes[(k + 1).min(nodes.len() - 1)],
    );
    let t = (after - before).normalize();
    let e1 = t.cross(&Vector3::z()).normalize();
    let e2 = t.cross(&e1);
    for i in 0..8 {
        let angle = PI / 4.0 * i as f64;
        let u = e1 * angle.cos() + e2 * angle.sin();
        let found = vertices.iter().any(|v| {
            let d = v - nodes[k];
            let across = d - t * d.dot(&t);
            d.norm() < 2.0 * RADIUS && across.normalize().dot(&u) > (PI / 6.0).cos()
        });
        assert!(found, "node {k}: no vertex towards {u:?}");
    }
}

#[test]
fn box_collider_vertices_are_at_the_urdf_half_extents() {
    let robot = robot();
    let (doc, blob) = import(&glb(&spec(&robot)));
    let root = root(&doc);
    let link_2 = child(&child(&root, "robot"), "link_2");
    let collider = child(&link_2, "link_2 collider 0");
    let vertices = positions(&collider.mesh().expect("a mesh"), &blob);
    // <box size="0.505 0.16 0.15"/>
    let half = Vector3::new(0.2525, 0.08, 0.075);
    assert_eq!(vertices.len(), 24);
    let mut corners = std::collections::BTreeSet::new();
    for p in &vertices {
        assert!((p.coords.abs() - half).abs().max() < 1e-6, "{p:?}");
        corners.insert([p.x > 0.0, p.y > 0.0, p.z > 0.0]);
    }
    assert_eq!(corners.len(), 8);
    // <cylinder radius="0.115" length="0.21"/> on base_link.
    let base = child(&child(&root, "robot"), "base_link");
    let cylinder = positions(
        &child(&base, "base_link collider 0").mesh().expect("mesh"),
        &blob,
    );
    for p in &cylinder {
        let r = p.x.hypot(p.y);
        assert!(r < 0.115 + 1e-6 && p.z.abs() < 0.105 + 1e-6, "{p:?}");
        assert!(
            (r - 0.115).abs() < 1e-6 || (p.z.abs() - 0.105).abs() < 1e-6,
            "{p:?}"
        );
    }
}

/// Output values of every channel of `node`, per property, as f64 rows.
fn channel_values(
    anim: &gltf::Animation<'_>,
    blob: &[u8],
    node: usize,
) -> Vec<(Property, Vec<Vec<f64>>)> {
    anim.channels()
        .filter(|c| c.target().node().index() == node)
        .map(|c| {
            let reader = c.reader(|_| Some(blob));
            let rows: Vec<Vec<f64>> = match reader.read_outputs().expect("outputs") {
                ReadOutputs::Translations(t) => t.map(|v| v.map(f64::from).to_vec()).collect(),
                ReadOutputs::Scales(s) => s.map(|v| v.map(f64::from).to_vec()).collect(),
                ReadOutputs::Rotations(r) => {
                    r.into_f32().map(|v| v.map(f64::from).to_vec()).collect()
                }
                ReadOutputs::MorphTargetWeights(_) => panic!("no morph targets expected"),
            };
            (c.target().property(), rows)
        })
        .collect()
}

/// The node's local matrix at keyframe `f` from its animation channels (rest TRS elsewhere).
fn animated_matrix(
    node: &gltf::Node<'_>,
    channels: &[(Property, Vec<Vec<f64>>)],
    f: usize,
) -> Matrix4<f64> {
    let (t, r, s) = node.transform().decomposed();
    let (mut t, mut r, mut s) = (t.map(f64::from), r.map(f64::from), s.map(f64::from));
    for (property, rows) in channels {
        let row = &rows[f];
        match property {
            Property::Translation => t = [row[0], row[1], row[2]],
            Property::Rotation => r = [row[0], row[1], row[2], row[3]],
            Property::Scale => s = [row[0], row[1], row[2]],
            Property::MorphTargetWeights => {}
        }
    }
    trs_matrix(
        t.map(|v| v as f32),
        r.map(|v| v as f32),
        s.map(|v| v as f32),
    )
}

#[test]
fn animated_nodes_follow_the_frames() {
    let robot = robot();
    let spec = spec(&robot);
    let animation = spec.animation.as_ref().expect("animated");
    let (doc, blob) = import(&glb(&spec));
    assert_eq!(doc.animations().count(), 1);
    let anim = doc.animations().next().expect("one animation");
    assert_follows(&doc, &blob, &anim, &spec, animation);
}

/// The installation pose is a second animation, by its name: two keyframes holding the main
/// copy's links and cable pieces at the given pose.
#[test]
fn the_installation_pose_is_a_still_animation() {
    let robot = robot();
    let mut spec = spec(&robot);
    spec.installation = Some(pose_scene(&robot, &JOINTS[2], 0.9));
    let (doc, blob) = import(&glb(&spec));
    let names: Vec<&str> = doc.animations().filter_map(|a| a.name()).collect();
    assert_eq!(names, ["motion test", INSTALLATION_ANIMATION]);
    let anim = doc.animations().nth(1).expect("the installation pose");
    let still = spec.installation_animation().expect("an installation pose");
    assert_eq!(still.times_s, [0.0, 1.0]);
    assert_follows(&doc, &blob, &anim, &spec, &still);
    // A pose whose pieces differ from the main scene's is refused.
    spec.installation.as_mut().expect("pose").cable.pop();
    assert!(to_glb(&spec).is_err());
}

/// Every link node and cable piece of the main copy follows `animation`'s frames in `anim`.
fn assert_follows(
    doc: &gltf::Document,
    blob: &[u8],
    anim: &gltf::Animation<'_>,
    spec: &SceneSpec<'_>,
    animation: &SceneAnimation,
) {
    let root = root(doc);
    let mut checked = 0;
    for (i, line) in spec.main.cable.iter().enumerate() {
        let line_node = child(&child(&root, "cable"), &line.name);
        for k in 0..line.nodes_m.len() - 1 {
            let node = child(&line_node, &format!("{} sub-segment {k}", line.name));
            let channels = channel_values(anim, blob, node.index());
            assert_eq!(channels.len(), 3, "T, R and S of sub-segment {k}");
            for (f, frame) in animation.frames.iter().enumerate() {
                let m = animated_matrix(&node, &channels, f);
                let nodes = &frame.cable[i].nodes_m;
                for (local, want) in [
                    (Point3::origin(), nodes[k]),
                    (Point3::new(0.0, 0.0, 1.0), nodes[k + 1]),
                ] {
                    let got = m.transform_point(&local);
                    assert!(
                        (got - want).norm() < 1e-6,
                        "{} frame {f} sub-segment {k}: {got} vs {want}",
                        line.name
                    );
                }
                checked += 1;
            }
        }
        for k in 0..line.nodes_m.len() {
            let node = child(&line_node, &format!("{} node {k}", line.name));
            let channels = channel_values(anim, blob, node.index());
            for (f, frame) in animation.frames.iter().enumerate() {
                let got = animated_matrix(&node, &channels, f).transform_point(&Point3::origin());
                assert!(
                    (got - frame.cable[i].nodes_m[k]).norm() < 1e-6,
                    "{} node {k} frame {f}",
                    line.name
                );
            }
        }
    }
    assert_eq!(checked, animation.frames.len() * (NODES[0] + NODES[1] - 2));
    for (l, link_node) in child(&root, "robot").children().enumerate() {
        let channels = channel_values(anim, blob, link_node.index());
        assert_eq!(channels.len(), 2, "T and R of link {l}");
        for (f, frame) in animation.frames.iter().enumerate() {
            let m = animated_matrix(&link_node, &channels, f);
            assert_matrix_near(
                &m,
                &frame.link_poses[l].to_homogeneous(),
                1e-6,
                &format!("link {l} frame {f}"),
            );
        }
        // Consecutive keyframe quaternions on the same side: interpolation takes the short way.
        for (property, rows) in &channels {
            if *property == Property::Rotation {
                for pair in rows.windows(2) {
                    let dot: f64 = pair[0].iter().zip(&pair[1]).map(|(a, b)| a * b).sum();
                    assert!(dot >= 0.0, "link {l}: {pair:?}");
                }
            }
        }
    }
}

#[test]
fn normals_are_unit_and_triangles_wind_counter_clockwise_around_them() {
    let robot = robot();
    let (doc, blob) = import(&glb(&spec(&robot)));
    for mesh in doc.meshes() {
        for primitive in mesh.primitives() {
            let reader = primitive.reader(|_| Some(&blob[..]));
            let p: Vec<Vector3<f64>> = reader
                .read_positions()
                .expect("positions")
                .map(|v| Vector3::from(v).cast())
                .collect();
            let n: Vec<Vector3<f64>> = reader
                .read_normals()
                .expect("normals")
                .map(|v| Vector3::from(v).cast())
                .collect();
            assert_eq!(p.len(), n.len());
            for v in &n {
                assert!(
                    (v.norm() - 1.0).abs() < 1e-6,
                    "{:?}: normal {v:?}",
                    mesh.name()
                );
            }
            let indices: Vec<u32> = reader.read_indices().expect("indices").into_u32().collect();
            assert_eq!(indices.len() % 3, 0);
            for t in indices.chunks(3) {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize);
                let face = (p[b] - p[a]).cross(&(p[c] - p[a]));
                let normal = n[a] + n[b] + n[c];
                assert!(
                    face.dot(&normal) > 0.0,
                    "{:?}: triangle {t:?} winds against its normals",
                    mesh.name()
                );
            }
        }
    }
}

#[test]
fn the_same_spec_gives_the_same_bytes() {
    let robot = robot();
    let spec = spec(&robot);
    assert_eq!(
        to_glb(&spec).expect("first"),
        to_glb(&spec).expect("second")
    );
}

#[test]
fn inconsistent_specs_are_refused_with_the_matching_error() {
    let robot = robot();
    let good = spec(&robot);
    let with_animation = |edit: &dyn Fn(&mut SceneAnimation)| {
        let mut spec = good.clone();
        edit(spec.animation.as_mut().expect("animated"));
        to_glb(&spec).expect_err("refused")
    };

    let error = with_animation(&|a| {
        a.frames[1].cable[0].nodes_m.pop();
    });
    assert!(
        matches!(
            &error,
            SceneError::FrameNodeCount {
                frame: 1,
                index: 0,
                got: 19,
                expected: 20,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(error.to_string().contains("C1"), "{error}");
    let error = with_animation(&|a| a.times_s[2] = 0.5);
    assert!(
        matches!(error, SceneError::TimesNotIncreasing { index: 2, .. }),
        "{error:?}"
    );
    let error = with_animation(&|a| a.times_s[0] = 0.1);
    assert!(
        matches!(error, SceneError::FirstKeyframe { .. }),
        "{error:?}"
    );
    let error = with_animation(&|a| {
        a.frames[2].cable.pop();
    });
    assert!(
        matches!(
            error,
            SceneError::FrameLineCount {
                frame: 2,
                got: 1,
                expected: 2
            }
        ),
        "{error:?}"
    );
    let error = with_animation(&|a| {
        a.frames[0].link_poses.pop();
    });
    assert!(
        matches!(error, SceneError::LinkPoseCount { .. }),
        "{error:?}"
    );
    let error = with_animation(&|a| {
        a.times_s.pop();
    });
    assert!(
        matches!(
            error,
            SceneError::KeyframeCount {
                times: 2,
                frames: 3,
                ..
            }
        ),
        "{error:?}"
    );

    let mut spec = good.clone();
    spec.snapshots[0].scene.cable[1].nodes_m.truncate(1);
    let error = to_glb(&spec).expect_err("one node");
    assert!(
        matches!(error, SceneError::TooFewNodes { nodes: 1, .. }),
        "{error:?}"
    );
    let mut spec = good.clone();
    spec.main.cable[0].nodes_m[3].x = f64::NAN;
    let error = to_glb(&spec).expect_err("NaN");
    assert!(matches!(error, SceneError::NonFinite { .. }), "{error:?}");
    let mut spec = good.clone();
    spec.guides[1].link = robot.links.len();
    let error = to_glb(&spec).expect_err("no such link");
    assert!(matches!(error, SceneError::GuideLink { .. }), "{error:?}");
    let mut spec = good.clone();
    spec.cable_radius_m = 0.0;
    assert!(matches!(to_glb(&spec), Err(SceneError::CableRadius(_))));
}

/// A unit right tetrahedron as ASCII STL (vertices in millimetres).
const TETRAHEDRON_STL: &str = include_str!("data/tetrahedron.stl");

#[test]
fn spheres_capsules_and_stl_meshes_are_drawn_to_size() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("t.stl"), TETRAHEDRON_STL).expect("write stl");
    let urdf = r#"<robot name="shapes">
      <link name="a">
        <collision><geometry><sphere radius="0.05"/></geometry></collision>
        <collision><origin xyz="0 0 0.3"/><geometry><capsule radius="0.04" length="0.2"/></geometry></collision>
      </link>
      <link name="b"><collision><geometry><mesh filename="t.stl" scale="0.001 0.002 0.001"/></geometry></collision></link>
      <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
    </robot>"#;
    let path = dir.path().join("shapes.urdf");
    std::fs::write(&path, urdf).expect("write urdf");
    let robot = Robot::from_urdf_file(&path).expect("loads");
    let spec = SceneSpec {
        robot: &robot,
        cable_radius_m: 0.005,
        main: PoseScene {
            link_poses: robot.link_poses(&[0.3]).expect("1 joint"),
            cable: Vec::new(),
        },
        guides: Vec::new(),
        animation: None,
        other_motions: Vec::new(),
        snapshots: Vec::new(),
        tints: Vec::new(),
        damage: Vec::new(),
        installation: None,
    };
    let (doc, blob) = import(&glb_kept(&spec, "CABLE_DICT_SHAPES_OUT"));
    // root, robot, 2 links, 3 colliders: no cable node without cable lines
    assert_eq!(doc.nodes().len(), 2 + 2 + 3);
    assert_eq!(
        doc.materials().len(),
        1,
        "only the robot's material is used"
    );
    assert_eq!(doc.meshes().len(), 3);
    assert_eq!(doc.animations().count(), 0);
    let robot_node = child(&root(&doc), "robot");
    let a = child(&robot_node, "a");
    for p in positions(&child(&a, "a collider 0").mesh().expect("sphere"), &blob) {
        assert!((p.coords.norm() - 0.05).abs() < 1e-6, "sphere {p:?}");
    }
    let capsule = child(&a, "a collider 1");
    assert_eq!(capsule.transform().decomposed().0, [0.0, 0.0, 0.3]);
    for p in positions(&capsule.mesh().expect("capsule"), &blob) {
        let axis = Point3::new(0.0, 0.0, p.z.clamp(-0.1, 0.1));
        assert!(((p - axis).norm() - 0.04).abs() < 1e-6, "capsule {p:?}");
    }
    let b = child(&robot_node, "b");
    let tetra = positions(&child(&b, "b collider 0").mesh().expect("mesh"), &blob);
    assert_eq!(tetra.len(), 12, "three own vertices per triangle");
    let corners = [
        [0.0, 0.0, 0.0],
        [0.01, 0.0, 0.0],
        [0.0, 0.02, 0.0],
        [0.0, 0.0, 0.01],
    ];
    for p in &tetra {
        assert!(
            corners.iter().any(|c| (p - Point3::from(*c)).norm() < 1e-6),
            "{p:?}"
        );
    }
}

/// A tinted line's sub-segments, nodes and snapshot tube use its tint's material (its colour
/// as the scene promises: red for an exceeded limit), untinted lines keep the plain cable
/// material, and no material is left unused.
#[test]
fn tinted_cable_lines_wear_their_margin_colour() {
    let robot = robot();
    let mut spec = spec(&robot);
    spec.tints = vec![("C1".into(), CableTint::Exceeded)];
    let (doc, _) = import(&glb(&spec));
    let mut checked = 0;
    let material_of = |node: &gltf::Node<'_>| {
        let mesh = node.mesh().expect("a mesh");
        let primitive = mesh.primitives().next().expect("a primitive");
        primitive.material().name().unwrap_or_default().to_string()
    };
    for node in doc.nodes() {
        let name = node.name().unwrap_or_default();
        // Sub-segments, nodes and snapshot tubes; the main lines' holder nodes have no mesh.
        let line = match name.split_whitespace().next() {
            Some(line @ ("C1" | "C2")) if node.mesh().is_some() => line,
            _ => continue,
        };
        checked += 1;
        let expected = if line == "C1" {
            "cable, limit exceeded"
        } else {
            "cable"
        };
        assert_eq!(material_of(&node), expected, "{name}");
    }
    let snapshots = spec.snapshots.len();
    let nodes: usize = spec
        .main
        .cable
        .iter()
        .map(|l| 2 * l.nodes_m.len() - 1)
        .sum();
    assert_eq!(checked, nodes + 2 * snapshots);
    let red = doc
        .materials()
        .find(|m| m.name() == Some("cable, limit exceeded"))
        .expect("the red material");
    let [r, g, b, _] = red.pbr_metallic_roughness().base_color_factor();
    assert!(r > 0.5 && g < 0.1 && b < 0.1, "{r} {g} {b}");
    for material in doc.materials() {
        let used = doc.meshes().any(|mesh| {
            mesh.primitives()
                .any(|p| p.material().index() == material.index())
        });
        assert!(used, "{:?} is unused", material.name());
    }
}

/// Damage per cycle along C1 (C2 has none): the scene offers two colourings as glTF material
/// variants, and in the second every sub-segment of C1 wears the colour of the worse of its
/// two nodes' decade below the cable's worst (≥ 1/10, 1/100, 1/1000 of it, or less), every
/// node its own, while the first keeps the margin colour; C2 keeps its one material. Without
/// damage no variant is declared; damage that does not fit the line is refused.
#[test]
fn damage_per_cycle_colours_the_cable_in_a_second_variant() {
    let robot = robot();
    let mut spec = spec(&robot);
    spec.tints = vec![("C1".into(), CableTint::Tight)];
    // 3e-6 at node 0, falling by a factor 2 per node: decades at nodes 4, 7, 10 (3e-6 / 2^k).
    let damage: Vec<f64> = (0..NODES[0]).map(|k| 3e-6 / 2f64.powi(k as i32)).collect();
    spec.damage = vec![("C1".into(), damage.clone())];
    let (doc, _) = import(&glb(&spec));
    let names: Vec<String> = (doc.variants().expect("variants"))
        .map(|v| v.name().to_owned())
        .collect();
    assert_eq!(names, COLOUR_VARIANTS);
    // The level's material by hand: decades below the worst (3e-6).
    let expected = |d: f64| match d / 3e-6 {
        r if r >= 0.1 => "cable, worst damage",
        r if r >= 0.01 => "cable, raised damage",
        r if r >= 0.001 => "cable, low damage",
        _ => "cable, slight damage",
    };
    let mut seen = std::collections::BTreeSet::new();
    for node in doc.nodes() {
        let name = node.name().unwrap_or_default().to_owned();
        let Some(mesh) = node.mesh() else { continue };
        let words: Vec<&str> = name.split_whitespace().collect();
        let (line, kind, k) = match words[..] {
            [line @ ("C1" | "C2"), kind @ ("sub-segment" | "node"), k] => {
                (line, kind, k.parse::<usize>().expect("an index"))
            }
            _ => continue,
        };
        let primitive = mesh.primitives().next().expect("a primitive");
        let default = primitive.material().name().unwrap_or_default().to_owned();
        let mappings: Vec<(Vec<u32>, String)> = (primitive.mappings())
            .map(|m| {
                (
                    m.variants().to_vec(),
                    m.material().name().unwrap_or_default().into(),
                )
            })
            .collect();
        if line == "C2" {
            assert_eq!(default, "cable", "{name}");
            assert!(mappings.is_empty(), "{name}: {mappings:?}");
            continue;
        }
        let worst = match kind {
            "node" => damage[k],
            _ => damage[k].max(damage[k + 1]),
        };
        assert_eq!(default, "cable, tight margin", "{name}");
        let want = vec![
            (vec![0], "cable, tight margin".to_owned()),
            (vec![1], expected(worst).to_owned()),
        ];
        assert_eq!(mappings, want, "{name}");
        seen.insert(expected(worst));
    }
    assert_eq!(seen.len(), 4, "every level drawn: {seen:?}");
    // Every material is some primitive's, by default or in a variant.
    for material in doc.materials() {
        let used = doc
            .meshes()
            .flat_map(|m| m.primitives().collect::<Vec<_>>())
            .any(|p| {
                p.material().index() == material.index()
                    || p.mappings()
                        .any(|m| m.material().index() == material.index())
            });
        assert!(used, "{:?} is unused", material.name());
    }

    spec.damage.clear();
    let (plain, _) = import(&glb(&spec));
    assert!(plain.variants().is_none());

    for (damage, says) in [
        (vec![("C3".to_owned(), vec![0.0; 4])], "no such line"),
        (
            vec![("C1".to_owned(), vec![0.0; NODES[0] - 1])],
            "19 values for 20 nodes",
        ),
        (
            vec![(
                "C1".to_owned(),
                [vec![f64::NAN], vec![0.0; NODES[0] - 1]].concat(),
            )],
            "node 0",
        ),
        (
            vec![(
                "C1".to_owned(),
                [vec![-1.0], vec![0.0; NODES[0] - 1]].concat(),
            )],
            "node 0",
        ),
    ] {
        spec.damage = damage;
        let error = to_glb(&spec).expect_err("refused");
        assert!(matches!(error, SceneError::Damage { .. }), "{error:?}");
        assert!(error.to_string().contains(says), "{error}");
    }
}

/// Each part is drawn its own way: a rigid clamp's collar, a rotating clamp's flat ring
/// (wider, half as long), a swivel's ball of the collar's outer radius, each in its colour;
/// a scene of rigid clamps only has the one marker it always had.
#[test]
fn guide_markers_show_the_part() {
    let robot = robot();
    let mut parts = spec(&robot);
    parts.guides[0].part = ClampPart::Rotating;
    let mut swivel = parts.guides[1].clone();
    swivel.name = "G3 (link_4/ball)".into();
    swivel.part = ClampPart::Swivel;
    parts.guides.push(swivel);
    let (doc, blob) = import(&glb(&parts));
    let marker = |name: &str| {
        doc.nodes()
            .find(|n| n.name() == Some(name))
            .and_then(|n| n.mesh())
            .unwrap_or_else(|| panic!("{name} has a marker"))
    };
    // Extents of a marker mesh in its own frame: (radius across, length along z).
    let extent = |mesh: &gltf::Mesh<'_>| {
        let points = positions(mesh, &blob);
        let across = points.iter().map(|p| p.x.hypot(p.y)).fold(0.0, f64::max);
        let (low, high) = points
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), p| (l.min(p.z), h.max(p.z)));
        (across, high - low)
    };
    let material = |mesh: &gltf::Mesh<'_>| {
        let primitive = mesh.primitives().next().expect("a primitive");
        primitive.material().name().unwrap_or_default().to_owned()
    };
    let rotating = marker("G1 (link_2/side)");
    let rigid = marker("G2 (link_4/top)");
    let ball = marker("G3 (link_4/ball)");
    assert_eq!(material(&rigid), "guide");
    assert_eq!(material(&rotating), "guide, rotating clamp");
    assert_eq!(material(&ball), "guide, swivel");
    let (rigid_across, rigid_along) = extent(&rigid);
    let (ring_across, ring_along) = extent(&rotating);
    let (ball_across, ball_along) = extent(&ball);
    assert!(
        (ring_across / rigid_across - 1.6).abs() < 0.05,
        "{ring_across} {rigid_across}"
    );
    assert!(
        (ring_along / rigid_along - 0.5).abs() < 0.05,
        "{ring_along} {rigid_along}"
    );
    // The ball: as wide as it is long, the collar's outer radius.
    assert!((ball_across - rigid_across).abs() < 0.05 * rigid_across);
    assert!((ball_along - 2.0 * ball_across).abs() < 0.05 * ball_along);

    let plain = spec(&robot);
    let (doc, _) = import(&glb(&plain));
    let markers: Vec<String> = (doc.meshes())
        .filter_map(|m| m.name().map(str::to_owned))
        .filter(|n| n.starts_with("guide marker"))
        .collect();
    assert_eq!(markers, ["guide marker"]);
}
