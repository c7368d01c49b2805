//! Guide sites generated from the robot's collision geometry, and the clamps' twist references
//! derived from the installed cable's route.

use crate::common::{self, root};
use crate::reference;

use cable_dict::motion::Motion;
use cable_dict::pose::Pose;
use cable_dict::robot::{Robot, Shape};
use cable_dict::setup::{ConfigurationOrigin, Guide, GuideConfiguration, Setup};
use cable_dict::sites::reference::AxisRule;
use cable_dict::sites::{FACING_TOLERANCE_DEG, GeneratedSites, Site, reference_axes};
use nalgebra::{Matrix3, Point3, SymmetricEigen, Vector3};
use reference::mesh_solid::ReferenceSolid;
use std::f64::consts::PI;
use std::path::PathBuf;

fn setup(name: &str) -> Setup {
    Setup::from_file(root().join("robots/viper_s850").join(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// Distance from `p` (in the shape's frame) to a box, cylinder or sphere surface, from the
/// textbook closed forms (outside points only).
fn distance_to_shape(shape: &Shape, p: &Point3<f64>) -> f64 {
    match shape {
        Shape::Box { half_extents_m: h } => {
            let outside = Vector3::new(
                (p.x.abs() - h.x).max(0.0),
                (p.y.abs() - h.y).max(0.0),
                (p.z.abs() - h.z).max(0.0),
            );
            outside.norm()
        }
        Shape::Cylinder { radius_m, length_m } => {
            let radial = (p.x.hypot(p.y) - radius_m).max(0.0);
            let axial = (p.z.abs() - 0.5 * length_m).max(0.0);
            radial.hypot(axial)
        }
        Shape::Sphere { radius_m } => (p.coords.norm() - radius_m).max(0.0),
        other => panic!("no closed form for {}", other.describe()),
    }
}

/// Every generated site of the bundled setups stands exactly the cable radius plus the clamp
/// height (8 mm) off its link's nearest collision surface, and clears every other link by at
/// least that much at the installation pose; its cable direction lies in the surface
/// (perpendicular to the normal, which is the frame's x axis).
#[test]
fn generated_sites_stand_off_their_link_by_the_cable_radius_plus_the_clamp() {
    for (file, radius_mm) in [("pick_and_place.toml", 4.0), ("inspection.toml", 3.0)] {
        let setup = setup(file);
        let standoff = (radius_mm + 8.0) * 1e-3;
        let install = setup.installation.as_ref().expect("install pose");
        for guide in setup.guides.iter().filter(|g| !g.fixed) {
            let mut generated = 0;
            for c in &guide.configurations {
                if !matches!(c.origin, ConfigurationOrigin::Generated { .. }) {
                    continue;
                }
                generated += 1;
                let world =
                    install.link_poses[guide.link] * Point3::from(c.pose.translation.vector);
                let nearest = setup
                    .robot
                    .links
                    .iter()
                    .enumerate()
                    .flat_map(|(l, link)| {
                        let pose = install.link_poses[l];
                        link.colliders.iter().map(move |col| {
                            let local = (pose * col.origin).inverse() * world;
                            (l, distance_to_shape(&col.shape, &local))
                        })
                    })
                    .collect::<Vec<_>>();
                let own = nearest
                    .iter()
                    .filter(|(l, _)| *l == guide.link)
                    .map(|(_, d)| *d)
                    .fold(f64::INFINITY, f64::min);
                let any = nearest
                    .iter()
                    .map(|(_, d)| *d)
                    .fold(f64::INFINITY, f64::min);
                assert!((own - standoff).abs() < 1e-9, "{file} {}: {own}", c.name);
                assert!(any > standoff - 1e-4 - 1e-9, "{file} {}: {any}", c.name);
                let x = c.pose.rotation * Vector3::x();
                let z = c.pose.rotation * Vector3::z();
                assert!(x.dot(&z).abs() < 1e-12);
            }
            assert!(
                generated >= 8,
                "{file} {}: {generated} configurations",
                guide.name
            );
        }
    }
}

/// Direction 0° runs along the link's long axis where the surface is parallel to it: on
/// link_4 (a forearm tube along z with the wrist fork beyond it) that is +z, so on the tube
/// the four directions are +z, across, −z, across the other way.
#[test]
fn directions_are_measured_from_the_links_long_axis() {
    let setup = setup("pick_and_place.toml");
    let g2 = &setup.guides[1];
    let tube_sites: Vec<_> = g2
        .configurations
        .iter()
        .filter(|c| {
            let x = c.pose.rotation * Vector3::x();
            x.z.abs() < 1e-12 && c.pose.translation.vector.z < 0.2
        })
        .collect();
    assert!(tube_sites.len() >= 8);
    for c in tube_sites {
        let z = c.pose.rotation * Vector3::z();
        let angle = c.name.rsplit(' ').next().expect("angle");
        let expected = match angle {
            "0°" => Vector3::z(),
            "180°" => -Vector3::z(),
            _ => {
                assert!(z.z.abs() < 1e-12, "{}: {z}", c.name);
                continue;
            }
        };
        assert!((z - expected).norm() < 1e-12, "{}: {z}", c.name);
    }
}

/// The hand-written pick-and-place setup's +x axes were transported by hand along the route
/// at the motion's first pose: G3's from G4 "arm r190 z65 up72" (which took the connector's),
/// G2's from G3 "fork side x40 z280 t5" (its comments say so). Installed at that pose, the
/// tool's derived twist reference of those pieces is within a degree of the hand frames at
/// every length: the angle it would turn their end clamps by is below 1°. (Across joints 5
/// and 6, from G3 to G4, the hand frames are 18–44° off the derived reference, and off the
/// hanging cable's too: that transport was wrong, see docs/design-space.md.)
#[test]
fn derived_twist_references_reproduce_the_hand_transported_frames() {
    let source: PathBuf = root().join("robots/viper_s850/hand_written/pick_and_place.toml");
    let text = std::fs::read_to_string(&source).unwrap_or_else(|e| panic!("{e}"));
    let hand = Setup::from_toml_str(&text, &source).unwrap_or_else(|e| panic!("{e}"));
    let motion = Motion::from_csv_file(
        &hand.robot,
        root().join("motions/viper_s850/pick_and_place.csv"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let first: Vec<String> = motion.samples()[0]
        .iter()
        .map(|v| format!("{:.6}", v.to_degrees()))
        .collect();
    let installed_text = text.replace(
        "max_guides_per_link = 2",
        &format!(
            "max_guides_per_link = 2\ninstall_joints_deg = [{}]",
            first.join(", ")
        ),
    );
    let installed =
        Setup::from_toml_str(&installed_text, &source).unwrap_or_else(|e| panic!("{e}"));
    let index = |g: usize, name: &str| {
        installed.guides[g]
            .configuration_index(name)
            .unwrap_or_else(|| panic!("no {name}"))
    };
    let routes = [
        (1, "fork bracket x-65 y107 z330", "fork side x40 z280 t5"),
        (3, "arm r190 z65 up72", "gripper connector"),
    ];
    for (m, from, to) in routes {
        let pair = (index(m, from), index(m + 1, to));
        for &s in installed.segments[m].lengths.iter().filter(|&&s| s > 0) {
            let turn = installed.installed_twist_rad(m, s, pair).to_degrees();
            assert!(turn.abs() < 1.0, "C{} S = {s}: {turn:.2}°", m + 1);
        }
    }
    // Without an installation pose nothing is derived: the written axes are the reference.
    assert_eq!(hand.installed_twist_rad(2, 40, (0, 0)), 0.0);
}

/// Turning the end clamp by the derived reference leaves the piece untwisted along its route
/// at the installation pose: the connected geometry between the turned clamps has no twist
/// mismatch left, for every length of a few pieces of the robot-level setup.
#[test]
fn the_turned_end_clamp_leaves_the_installed_route_untwisted() {
    let setup = setup("pick_and_place.toml");
    let install = setup.installation.as_ref().expect("install pose");
    let sag = cable_dict::geometry::sag_direction(&setup.gravity_m_s2);
    let mut checked = 0;
    for m in 0..setup.segment_count() {
        let (a, b) = setup.segment_guides(m);
        let (na, nb) = (
            setup.guides[a].configurations.len(),
            setup.guides[b].configurations.len(),
        );
        for (i, j) in [(0, 0), (na / 2, nb / 3), (na - 1, nb - 1)] {
            for &s in setup.segments[m].lengths.iter().step_by(7) {
                if !setup.is_admissible(m, s, i, j) || s == 0 {
                    continue;
                }
                let (start, end) = setup.clamp_poses(&install.link_poses, m, s, (i, j));
                let pitch = setup.cable.sub_segment_pitch_m;
                let Ok(route) = cable_dict::geometry::connect(&start, &end, s, pitch, &sag) else {
                    continue;
                };
                assert!(route.twist_correction_rad.abs() < 1e-9, "C{} {s}", m + 1);
                checked += 1;
            }
        }
    }
    assert!(checked > 20, "{checked}");
}

fn refused(text: &str) -> String {
    let source = root().join("robots/viper_s850/probe.toml");
    match Setup::from_toml_str(text, &source) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    }
}

/// Bad generators are refused with the file, the line, the key and what is wrong.
#[test]
fn bad_site_generators_are_refused_with_the_key() {
    let text = std::fs::read_to_string(root().join("robots/viper_s850/pick_and_place.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let no_install = text.replace(
        "install_joints_deg = [0.0, -68.6, 216.4, 0.0, 32.2, 0.0]\n",
        "",
    );
    let message = refused(&no_install);
    assert!(
        message.contains("guides[0].sites") && message.contains("install_joints_deg"),
        "{message}"
    );
    let tiny = text.replacen("spacing_mm = 80.0", "spacing_mm = 0.5", 1);
    let message = refused(&tiny);
    assert!(message.contains("guides[0].sites.spacing_mm"), "{message}");
    let dense = text.replacen("spacing_mm = 80.0", "spacing_mm = 1.0", 1);
    let message = refused(&dense);
    assert!(message.contains("raise spacing_mm"), "{message}");
    let twice = text.replacen("[0.0, 90.0, 180.0, 270.0]", "[0.0, 360.0]", 1);
    let message = refused(&twice);
    assert!(
        message.contains("directions_deg") && message.contains("360° is the same direction as 0°"),
        "{message}"
    );
    let nowhere = text.replacen(
        "directions_deg = [0.0, 90.0, 180.0, 270.0] }",
        "directions_deg = [0.0], region = { z_mm = [5000.0, 6000.0] } }",
        1,
    );
    let message = refused(&nowhere);
    assert!(message.contains("inside the region"), "{message}");

    let out_of_limits = text.replace("0.0, -68.6, 216.4", "0.0, -68.6, 316.4");
    let message = refused(&out_of_limits);
    assert!(
        message.contains("install_joints_deg") && message.contains("joint_3"),
        "{message}"
    );
    let line = message.split(':').nth(1).unwrap_or_default();
    assert!(line.trim().parse::<usize>().is_ok(), "{message}");
}

/// A region keeps only the sites whose surface point lies inside it.
#[test]
fn a_region_keeps_only_its_part_of_the_link() {
    let path = root().join("robots/viper_s850/pick_and_place.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let fork_only = text.replacen(
        "name = \"G2\"\nlink = \"link_4\"\nsites = { spacing_mm = 80.0, clamp_height_mm = 8.0, directions_deg = [0.0, 90.0, 180.0, 270.0] }",
        "name = \"G2\"\nlink = \"link_4\"\nsites = { spacing_mm = 80.0, clamp_height_mm = 8.0, directions_deg = [0.0, 90.0, 180.0, 270.0], region = { min_mm = [-100.0, -100.0, 230.0], max_mm = [100.0, 100.0, 400.0] } }",
        1,
    );
    assert_ne!(fork_only, text);
    let all = Setup::from_toml_str(&text, &path).unwrap_or_else(|e| panic!("{e}"));
    let fork = Setup::from_toml_str(&fork_only, &path).unwrap_or_else(|e| panic!("{e}"));
    let own = |s: &Setup| {
        s.guides[1]
            .configurations
            .iter()
            .filter(|c| matches!(c.origin, ConfigurationOrigin::Generated { .. }))
            .map(|c| c.pose.translation.vector)
            .collect::<Vec<_>>()
    };
    let (all, fork) = (own(&all), own(&fork));
    assert!(!fork.is_empty() && fork.len() < all.len());
    // The fork box spans z 230-345 mm; the sites stand 12 mm off its faces.
    assert!(fork.iter().all(|p| p.z > 0.230 - 0.012 - 1e-9));
    assert!(fork.iter().all(|p| all.contains(p)));
}

/// Sites on an STL mesh: the base of the test robot of `tests/data/urdf_real` is a box mesh
/// in millimetres (x ±100, y ±80, z 0–100 mm, `make_meshes.py`). Every site generated on it
/// stands the standoff off that box (the closed form of the box, not the mesh), with the
/// frame's x axis along the face's outward normal; sites on the top face too close to the
/// wall of link_1's tube standing on it are dropped.
#[test]
fn sites_on_an_stl_mesh_stand_off_its_faces() {
    let limits = common::limits("\"cable\"");
    let package = root().join("tests/data/urdf_real/my_robot_description/urdf");
    let cable = root().join("cables/smc_le_cp_3.toml");
    let text = format!(
        r#"robot = "robot.urdf"
cable = '{}'
gravity_m_s2 = [0.0, 0.0, -9.81]
max_guides_per_link = 1
install_joints_deg = [0.0, 0.0]

{limits}
[[guides]]
name = "G1"
link = "base_link"
sites = {{ spacing_mm = 40.0, clamp_height_mm = 8.0, directions_deg = [0.0, 90.0] }}

[[guides]]
name = "G2"
link = "link_2"
fixed = {{ name = "front", position_mm = [120.0, 0.0, 100.0], rpy_deg = [0.0, 0.0, 0.0] }}

[[segments]]
from = "G1"
to = "G2"
lengths = {{ min = 40, max = 60, step = 1, allow_zero = false }}
"#,
        cable.display()
    );
    let setup =
        Setup::from_toml_str(&text, &package.join("setup.toml")).unwrap_or_else(|e| panic!("{e}"));
    let standoff = 0.004 + 0.008;
    let block = Shape::Box {
        half_extents_m: Vector3::new(0.1, 0.08, 0.05),
    };
    let configurations = &setup.guides[0].configurations;
    assert!(configurations.len() >= 2 * 30, "{}", configurations.len());
    for c in configurations {
        let p = Point3::from(c.pose.translation.vector - Vector3::new(0.0, 0.0, 0.05));
        let distance = distance_to_shape(&block, &p);
        assert!((distance - standoff).abs() < 1e-9, "{}: {distance}", c.name);
        let x = c.pose.rotation * Vector3::x();
        let on_face = (0..3).any(|k| (x[k].abs() - 1.0).abs() < 1e-12);
        assert!(on_face, "{}: normal {x}", c.name);
        // Not on the top face within the standoff of the wall of link_1's tube (radii 40
        // and 50 mm at its corners; inside its bore there is room).
        let radial = p.x.hypot(p.y);
        let near_wall = radial > 0.04 * (PI / 12.0).cos() - standoff && radial < 0.05 + standoff;
        assert!(!(x.z > 0.5 && near_wall), "{}", c.name);
    }
}

/// `cable-dict sites` lists every guide with the number of configurations the loaded setup
/// has and the candidate pieces per segment, and draws one marker per configuration.
#[test]
fn the_sites_command_lists_and_draws_what_is_searched() {
    let file = root().join("robots/viper_s850/inspection.toml");
    let setup = Setup::from_file(&file).unwrap_or_else(|e| panic!("{e}"));
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let glb = dir.path().join("sites.glb");
    let output = common::run(&[
        "sites",
        &file.display().to_string(),
        "--gltf",
        &glb.display().to_string(),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8_lossy(&output.stdout);
    for guide in &setup.guides {
        let n = guide.configurations.len();
        let head = format!(
            "{} on {}: {n} configuration",
            guide.name, setup.robot.links[guide.link].name
        );
        assert!(text.contains(&head), "{head} in\n{text}");
    }
    for m in 0..setup.segment_count() {
        assert!(
            text.contains(&format!("= {} (", setup.pv_count(m))),
            "C{}",
            m + 1
        );
    }
    let scene = std::fs::read(&glb).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(&scene[..4], b"glTF");
    let markers = |name: &str| {
        scene
            .windows(name.len())
            .filter(|w| *w == name.as_bytes())
            .count()
    };
    let g1 = setup.guides[0].configurations.len();
    assert!(
        markers("\"G1 (site ") >= g1,
        "{} markers for {g1}",
        markers("\"G1 (site ")
    );
}

/// A guide generated on a link that has no collision shape (nor a link fixed to it) is
/// refused naming the link: there is nothing to mount a clamp on.
#[test]
fn sites_on_a_link_without_shapes_are_refused() {
    let limits = common::limits("\"cable\"");
    let urdf = r#"<robot name="two">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="arm"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
</robot>"#;
    let cable = std::fs::read_to_string(root().join("cables/smc_le_cp_3.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let text = format!(
        r#"robot = "two.urdf"
cable = "cable.toml"
gravity_m_s2 = [0.0, 0.0, -9.81]
max_guides_per_link = 1
install_joints_deg = [0.0]

{limits}
[[guides]]
name = "G1"
link = "base"
sites = {{ spacing_mm = 50.0, clamp_height_mm = 8.0, directions_deg = [0.0] }}

[[guides]]
name = "G2"
link = "arm"
sites = {{ spacing_mm = 50.0, clamp_height_mm = 8.0, directions_deg = [0.0] }}

[[segments]]
from = "G1"
to = "G2"
lengths = {{ min = 30, max = 40, step = 1, allow_zero = false }}
"#
    );
    let source = root().join("tests/data/two.toml");
    let message = match Setup::from_texts(&text, &source, urdf, &cable, &[]) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        message.contains("guides[1].sites") && message.contains("arm has no collision shapes"),
        "{message}"
    );
}

/// A catalogue too fine to search is refused before anything is allocated for it, with the
/// count per segment and what to change: 10 mm spacing on the arm gives billions
/// of candidate pieces.
#[test]
fn a_catalogue_too_large_to_search_is_refused_with_its_count() {
    let path = root().join("robots/viper_s850/pick_and_place.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let fine = text.replace("spacing_mm = 80.0", "spacing_mm = 10.0");
    let setup = Setup::from_toml_str(&fine, &path).unwrap_or_else(|e| panic!("{e}"));
    let counted: u128 = (0..setup.segment_count())
        .map(|m| setup.pv_count(m) as u128)
        .sum();
    assert!(counted > cable_dict::attachment::MAX_CANDIDATE_PIECES);
    let motion = Motion::from_csv_file(
        &setup.robot,
        root().join("motions/viper_s850/pick_and_place.csv"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let options = cable_dict::solve::SolveOptions::default();
    let message = match cable_dict::solve::solve(&setup, &motion, &options) {
        Ok(_) => panic!("a search of {counted} pieces was started"),
        Err(e) => e.to_string(),
    };
    assert!(
        message.contains(&format!("{counted} candidate pieces")),
        "{message}"
    );
    assert!(message.contains("raise spacing_mm"), "{message}");
}

// ---------------------------------------------------------------------------------------------
// Issue 25: a robot-level setup on the real UR5 (STL meshes of several shells each).

/// The UR5 site setup: sites on forearm_link, wrist_1_link, wrist_2_link (80 mm) and
/// wrist_3_link, the flange (20 mm).
fn ur5() -> Setup {
    Setup::from_file(root().join("tests/data/ur5/sites_setup.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Every generated guide of a setup with its sites.
fn generated(setup: &Setup) -> Vec<(usize, GeneratedSites)> {
    setup
        .guides
        .iter()
        .enumerate()
        .filter_map(|(g, guide)| guide.generated.clone().map(|s| (g, s)))
        .collect()
}

/// A mesh collider as the reference reads it from its STL file, with its world pose.
struct Solid {
    link: usize,
    pose: Pose,
    mesh: ReferenceSolid,
}

impl Solid {
    fn local(&self, world: &Point3<f64>) -> [f64; 3] {
        let p = self.pose.inverse() * world;
        [p.x, p.y, p.z]
    }
}

/// Every collider of the robot at `link_poses`, read by the reference (all UR5 colliders are
/// meshes in metres).
fn solids(robot: &Robot, link_poses: &[Pose]) -> Vec<Solid> {
    let mut all = Vec::new();
    for (l, link) in robot.links.iter().enumerate() {
        for collider in &link.colliders {
            let Shape::Mesh(mesh) = &collider.shape else {
                panic!("{}: not a mesh", link.name);
            };
            all.push(Solid {
                link: l,
                pose: link_poses[l] * collider.origin,
                mesh: ReferenceSolid::from_stl(&mesh.file, 1.0),
            });
        }
    }
    all
}

/// Every site of the UR5 setup has its cable axis outside every link's solid (ray parity per
/// shell, the reference's union) and at least the standoff minus 0.1 mm from every link by
/// the reference's brute-force distance at the installation pose; the point 0.2 mm above its
/// surface point is outside every solid too (a surface point inside another shell or link is
/// no site). The sites are those of the guides' configurations, in their order.
#[test]
fn ur5_sites_are_outside_every_link_by_the_reference() {
    let setup = ur5();
    let install = setup.installation.as_ref().expect("install pose");
    let solids = solids(&setup.robot, &install.link_poses);
    let standoff = 0.004 + 0.008;
    let (mut checked, mut undecided) = (0, 0);
    for (g, generated) in generated(&setup) {
        let guide = &setup.guides[g];
        for (k, site) in generated.sites.iter().enumerate() {
            let c = first_configuration(guide, k);
            assert_eq!(Point3::from(c.pose.translation.vector), site.position);
            let to_world = install.link_poses[guide.link];
            let axis = to_world * site.position;
            let above = to_world * (site.surface_point + 2e-4 * site.normal.into_inner());
            for solid in &solids {
                let name = &setup.robot.links[solid.link].name;
                for (what, p) in [("cable axis", axis), ("surface point + 0.2 mm", above)] {
                    match solid.mesh.inside(solid.local(&p)) {
                        Some(inside) => {
                            assert!(!inside, "{} site {k}: {what} inside {name}", guide.name)
                        }
                        None => undecided += 1,
                    }
                }
                let distance = solid.mesh.distance(solid.local(&axis));
                assert!(
                    distance >= standoff - 1e-4,
                    "{} site {k}: {:.2} mm from {name}",
                    guide.name,
                    distance * 1e3
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 7 * 60, "{checked} site-link pairs");
    assert!(
        undecided * 100 < checked,
        "{undecided} undecided of {checked}"
    );
}

/// The first configuration (direction) of generated site `k` of a guide.
fn first_configuration(guide: &Guide, k: usize) -> &GuideConfiguration {
    guide
        .configurations
        .iter()
        .find(|c| matches!(c.origin, ConfigurationOrigin::Generated { site, .. } if site == k))
        .unwrap_or_else(|| panic!("{}: no configuration of site {k}", guide.name))
}

/// Pairs of one guide's sites that are of one facing (normals within the tolerance) and
/// closer than the spacing.
fn crowded_pairs(sites: &[Site], spacing_m: f64) -> Vec<(usize, usize, f64)> {
    let facing = FACING_TOLERANCE_DEG.to_radians().cos();
    let mut pairs = Vec::new();
    for (i, a) in sites.iter().enumerate() {
        for (j, b) in sites.iter().enumerate().skip(i + 1) {
            let distance = (a.surface_point - b.surface_point).norm();
            if a.normal.dot(&b.normal) >= facing && distance < spacing_m * (1.0 - 1e-9) {
                pairs.push((i, j, distance));
            }
        }
    }
    pairs
}

/// No two sites of one facing on one link are closer than the spacing: on every link of
/// the UR5 setup and of the bundled Viper setups (boxes and cylinders).
#[test]
fn sites_of_one_facing_keep_the_spacing_on_every_link() {
    let setups = [
        ur5(),
        setup("pick_and_place.toml"),
        setup("inspection.toml"),
    ];
    for setup in &setups {
        for (g, generated) in generated(setup) {
            let crowded = crowded_pairs(&generated.sites, generated.spec.spacing_m);
            assert!(
                crowded.is_empty(),
                "{} {}: {crowded:?}",
                setup.source.display(),
                setup.guides[g].name
            );
        }
    }
}

/// The UR5 flange face (wrist_3_link, 75 mm across, its outward normal +z of the link) at
/// 20 mm: its sites are at least 20 mm apart, about one per 20 × 20 mm of its area (the
/// issue had 42 sites there, the closest pair 2.6 mm apart).
#[test]
fn the_ur5_flange_face_keeps_the_spacing() {
    let setup = ur5();
    let (_, flange) = generated(&setup)
        .into_iter()
        .find(|(g, _)| setup.guides[*g].name == "G4")
        .expect("G4");
    let face: Vec<Site> = flange
        .sites
        .iter()
        .filter(|s| s.normal.z > 0.999)
        .cloned()
        .collect();
    for (i, a) in face.iter().enumerate() {
        for b in &face[i + 1..] {
            let distance = (a.surface_point - b.surface_point).norm();
            assert!(distance >= 0.02 - 1e-9, "{:.1} mm", distance * 1e3);
        }
    }
    let area_per_site = PI * 0.0375 * 0.0375 / (0.02 * 0.02);
    assert!(
        (0.6 * area_per_site..=1.2 * area_per_site).contains(&(face.len() as f64)),
        "{} face sites for {area_per_site:.1} spacing² of face",
        face.len()
    );
}

/// Generating the sites again gives the same sites in the same order, on one thread or
/// several.
#[test]
fn sites_are_the_same_at_any_thread_count() {
    let load = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap_or_else(|e| panic!("{e}"));
        pool.install(|| {
            let setup = ur5();
            (setup.content_hash, generated(&setup))
        })
    };
    let one = load(1);
    assert_eq!(one, load(1));
    assert_eq!(one, load(3));
}

// ---------------------------------------------------------------------------------------------
// The reference axis cable directions are measured from.

/// A robot of one link with the given `<collision>` elements (and a second, empty link).
fn one_link_robot(collisions: &str) -> Robot {
    let urdf = format!(
        r#"<robot name="probe">
  <link name="base">{collisions}</link>
  <link name="arm"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 2"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
</robot>"#
    );
    Robot::from_urdf_str(&urdf, &root().join("probe.urdf")).unwrap_or_else(|e| panic!("{e}"))
}

fn collision(xyz: &str, rpy: &str, geometry: &str) -> String {
    format!(
        r#"<collision><origin xyz="{xyz}" rpy="{rpy}"/><geometry>{geometry}</geometry></collision>"#
    )
}

/// A long box along x has reference +x (from the link origin toward its centre); a disc-like
/// cylinder has its axis (here tilted to y, its centroid on −y); a cube falls back to the
/// link's z axis.
#[test]
fn the_reference_is_the_long_axis_the_disc_axis_or_z() {
    let long = one_link_robot(&collision(
        "0.1 0 0",
        "0 0 0",
        r#"<box size="0.4 0.1 0.08"/>"#,
    ));
    let axes = reference_axes(&long, 0, None);
    assert_eq!(axes.rule, AxisRule::LongAxis);
    assert!(
        (axes.primary.into_inner() - Vector3::x()).norm() < 1e-9,
        "{axes:?}"
    );
    let disc = one_link_robot(&collision(
        "0 -0.02 0",
        "1.5707963267948966 0 0",
        r#"<cylinder radius="0.06" length="0.02"/>"#,
    ));
    let axes = reference_axes(&disc, 0, None);
    assert_eq!(axes.rule, AxisRule::DiscAxis);
    assert!(
        (axes.primary.into_inner() + Vector3::y()).norm() < 1e-9,
        "{axes:?}"
    );
    let cube = one_link_robot(&collision(
        "0.3 0.2 0.1",
        "0 0 0",
        r#"<box size="0.1 0.1 0.1"/>"#,
    ));
    let axes = reference_axes(&cube, 0, None);
    assert_eq!(axes.rule, AxisRule::LinkZ);
    assert_eq!(axes.primary.into_inner(), Vector3::z());
}

/// A setup on a probe robot with one generator on `base`.
fn probe_setup(collisions: &str, sites: &str) -> Result<Setup, String> {
    let limits = common::limits("\"cable\"");
    let urdf = format!(
        r#"<robot name="probe">
  <link name="base">{collisions}</link>
  <link name="arm"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 2"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
</robot>"#
    );
    let cable = std::fs::read_to_string(root().join("cables/smc_le_cp_3.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let text = format!(
        r#"robot = "probe.urdf"
cable = "cable.toml"
gravity_m_s2 = [0.0, 0.0, -9.81]
max_guides_per_link = 1
install_joints_deg = [0.0]

{limits}
[[guides]]
name = "G1"
link = "base"
sites = {sites}

[[guides]]
name = "G2"
link = "arm"
fixed = {{ name = "end", position_mm = [0.0, 0.0, 0.0], rpy_deg = [0.0, 0.0, 0.0] }}

[[segments]]
from = "G1"
to = "G2"
lengths = {{ min = 30, max = 40, step = 1, allow_zero = false }}
"#
    );
    Setup::from_texts(
        &text,
        &root().join("tests/data/probe.toml"),
        &urdf,
        &cable,
        &[],
    )
    .map_err(|e| e.to_string())
}

/// `reference_axis` replaces the long axis: on a long box along x, `"z"` makes 0° run along
/// z on the ±y faces, and `[0, 1, 1]` along (0, 1, 1) projected; a non-axis is refused with
/// the key.
#[test]
fn a_reference_axis_in_the_setup_overrides_the_long_axis() {
    let boxed = collision("0 0 0", "0 0 0", r#"<box size="0.4 0.1 0.08"/>"#);
    let direction_at = |setup: &Setup, normal: Vector3<f64>| {
        let c = setup.guides[0]
            .configurations
            .iter()
            .find(|c| {
                (c.pose.rotation * Vector3::x() - normal).norm() < 1e-9 && c.name.ends_with(" 0°")
            })
            .expect("a site on that face");
        c.pose.rotation * Vector3::z()
    };
    let generator = |axis: &str| {
        format!(
            "{{ spacing_mm = 50.0, clamp_height_mm = 8.0, directions_deg = [0.0, 90.0]{axis} }}"
        )
    };
    let long = probe_setup(&boxed, &generator("")).unwrap_or_else(|e| panic!("{e}"));
    assert!((direction_at(&long, Vector3::y()) - Vector3::x()).norm() < 1e-9);
    let z = probe_setup(&boxed, &generator(", reference_axis = \"z\""))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!((direction_at(&z, Vector3::y()) - Vector3::z()).norm() < 1e-9);
    // On the +z face the normal is the reference itself: the second axis, x (largest spread
    // across z).
    assert!((direction_at(&z, Vector3::z()) - Vector3::x()).norm() < 1e-9);
    let tilted = probe_setup(&boxed, &generator(", reference_axis = [0, 1, 1]"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        (direction_at(&tilted, Vector3::x()) - Vector3::new(0.0, 1.0, 1.0).normalize()).norm()
            < 1e-9
    );
    for bad in ["\"w\"", "[0, 0, 0]", "[1, 2]", "3"] {
        let message = probe_setup(&boxed, &generator(&format!(", reference_axis = {bad}")))
            .err()
            .unwrap_or_else(|| panic!("{bad} accepted"));
        assert!(
            message.contains("guides[0].sites.reference_axis"),
            "{message}"
        );
    }
}

/// The covariance of a link's surface (link frame), computed here from the reference's
/// triangles with the edge-midpoint rule (exact for quadratics), and its centroid.
fn surface_spread(solids: &[&Solid]) -> (Matrix3<f64>, Vector3<f64>) {
    let (mut area, mut first, mut second) = (0.0, Vector3::zeros(), Matrix3::zeros());
    for solid in solids {
        for t in solid.mesh.triangles() {
            let [a, b, c] = t.map(|v| solid.pose * Point3::from(v));
            let weight = 0.5 * (b - a).cross(&(c - a)).norm();
            for m in [a + (b - a) * 0.5, b + (c - b) * 0.5, c + (a - c) * 0.5] {
                area += weight / 3.0;
                first += weight / 3.0 * m.coords;
                second += weight / 3.0 * m.coords * m.coords.transpose();
            }
        }
    }
    let centroid = first / area;
    (second / area - centroid * centroid.transpose(), centroid)
}

/// On the UR5's wrist_1 and wrist_2 links the link's z axis is the joint axis, across the
/// arm; the reference is the housing's long axis, which runs along the arm toward the next
/// joint (its origin lies on that axis), not about the flange. It is the axis of largest
/// spread of the link's surface computed here from the STL triangles, ≥ 1.2× the next,
/// pointing toward the centroid; and a site on the housing's side has direction 0° along it.
/// The flange (wrist_3_link) is disc-like: its reference is the flange axis, its z.
#[test]
fn on_the_ur5_wrist_links_the_reference_runs_along_the_arm() {
    let setup = ur5();
    let robot = &setup.robot;
    let at_origin = vec![Pose::identity(); robot.links.len()];
    let solids = solids(robot, &at_origin);
    for (g, generated) in generated(&setup) {
        let guide = &setup.guides[g];
        let name = &robot.links[guide.link].name;
        let own: Vec<&Solid> = solids.iter().filter(|s| s.link == guide.link).collect();
        let (spread, centroid) = surface_spread(&own);
        let eigen = SymmetricEigen::new(spread);
        let mut order = [0, 1, 2];
        order.sort_by(|&i, &j| eigen.eigenvalues[j].total_cmp(&eigen.eigenvalues[i]));
        let value = |k: usize| eigen.eigenvalues[order[k]];
        let vector = |k: usize| eigen.eigenvectors.column(order[k]).into_owned();
        let axes = reference_axes(robot, guide.link, None);
        let primary = axes.primary.into_inner();
        match name.as_str() {
            "wrist_1_link" | "wrist_2_link" => {
                assert!(
                    value(0) >= 1.2 * value(1),
                    "{name}: {:?}",
                    eigen.eigenvalues
                );
                assert_eq!(axes.rule, AxisRule::LongAxis);
                assert!(primary.dot(&vector(0)).abs() > 0.9999, "{name}: {primary}");
                assert!(primary.dot(&centroid) > 0.0, "{name}: {primary} {centroid}");
                let child = robot
                    .joints
                    .iter()
                    .find(|j| j.parent_link == guide.link)
                    .expect("a child joint");
                let towards_next = child.origin.translation.vector.normalize();
                assert!(
                    primary.dot(&towards_next).abs() > 0.99,
                    "{name}: {primary} {towards_next}"
                );
                assert!(primary.z.abs() < 0.1, "{name}: {primary}");
                let mut along = 0;
                for (k, site) in generated.sites.iter().enumerate() {
                    if site.normal.dot(&primary).abs() > 0.5 {
                        continue;
                    }
                    let zero = first_configuration(guide, k);
                    let cable = zero.pose.rotation * Vector3::z();
                    assert!(cable.dot(&primary) > 0.85, "{name} site {k}: {cable}");
                    along += 1;
                }
                assert!(along >= 3, "{name}: {along} sites on the housing's side");
            }
            "wrist_3_link" => {
                assert_eq!(
                    axes.rule,
                    AxisRule::DiscAxis,
                    "{name}: {:?}",
                    eigen.eigenvalues
                );
                assert!(primary.dot(&vector(2)).abs() > 0.9999, "{name}: {primary}");
                assert!(primary.z.abs() > 0.999, "{name}: {primary}");
            }
            "forearm_link" => {
                assert_eq!(axes.rule, AxisRule::LongAxis);
                assert!(primary.dot(&vector(0)).abs() > 0.9999, "{name}: {primary}");
            }
            other => panic!("{other}"),
        }
    }
}

/// `cable-dict sites --json` on the UR5 setup: every guide; per generated site its link,
/// collider, cable axis point 12 mm out from its surface point along its unit normal, its
/// reference axis and per direction the angle, a unit vector in the surface that is the
/// reference turned by that angle about the normal, and the index and name of the
/// configuration the search uses; the hand-written connector with its position and rpy, and
/// its coincident copy.
#[test]
fn the_sites_command_writes_every_site_as_json() {
    let setup = ur5();
    let output = common::run(&["sites", "tests/data/ur5/sites_setup.toml", "--json"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_slice(&output.stdout).unwrap_or_else(|e| panic!("{e}"));
    let vector = |v: &serde_json::Value| {
        let a: Vec<f64> = v
            .as_array()
            .expect("array")
            .iter()
            .map(|x| x.as_f64().expect("number"))
            .collect();
        Vector3::new(a[0], a[1], a[2])
    };
    let guides = json["guides"].as_array().expect("guides");
    assert_eq!(guides.len(), setup.guides.len());
    let generated = generated(&setup);
    for (guide, report) in setup.guides.iter().zip(guides) {
        assert_eq!(report["name"], guide.name.as_str());
        let configurations = report["configurations"].as_array().expect("configurations");
        assert_eq!(configurations.len(), guide.configurations.len());
        let Some((_, sites)) = generated
            .iter()
            .find(|(g, _)| setup.guides[*g].name == guide.name)
        else {
            assert_eq!(report["kind"], "fixed");
            let c = &configurations[0];
            assert_eq!(vector(&c["position_mm"]), Vector3::new(50.0, 0.0, 60.0));
            assert_eq!(vector(&c["rpy_deg"]), Vector3::zeros());
            assert_eq!(c["origin"], "declared");
            continue;
        };
        assert_eq!(report["kind"], "sites");
        let listed = report["sites"].as_array().expect("sites");
        assert_eq!(listed.len(), sites.sites.len());
        for (k, (site, expected)) in listed.iter().zip(&sites.sites).enumerate() {
            assert_eq!(site["site"], k);
            assert_eq!(site["link"], setup.robot.links[expected.link].name.as_str());
            assert_eq!(site["collider"], expected.collider);
            let n = vector(&site["normal"]);
            let axis = vector(&site["reference_axis"]);
            assert!((n.norm() - 1.0).abs() < 1e-6 && (axis.norm() - 1.0).abs() < 1e-6);
            let position = vector(&site["position_mm"]);
            let out = position - vector(&site["surface_point_mm"]);
            assert!((out - 12.0 * n).norm() < 1e-6, "{k}: {out}");
            let zero = (axis - axis.dot(&n) * n).normalize();
            for d in site["directions"].as_array().expect("directions") {
                let angle = d["angle_deg"].as_f64().expect("angle").to_radians();
                let direction = vector(&d["direction"]);
                let turned = angle.cos() * zero + angle.sin() * n.cross(&zero);
                assert!(
                    (direction - turned).norm() < 1e-6,
                    "{k}: {direction} {turned}"
                );
                let c = &configurations[d["configuration"].as_u64().expect("index") as usize];
                assert_eq!(c["name"], d["name"]);
                assert_eq!(c["site"], k);
                assert!((vector(&c["position_mm"]) - position).norm() < 1e-6);
            }
        }
    }
    let g4 = &guides[3]["configurations"];
    let copy = g4
        .as_array()
        .expect("configurations")
        .iter()
        .find(|c| c["origin"] == "coincident")
        .expect("the connector's copy");
    assert_eq!(copy["copy_of"], "G5/connector");
}
