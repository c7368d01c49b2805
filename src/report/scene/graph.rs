//! The node tree: the robot copies (links, colliders, guide markers), the main cable as
//! animatable pieces and the snapshots with their swept tubes.

use super::document::Builder;
use super::mesh::{TriangleMesh, cable_joint_sphere, collar, shape_mesh, unit_cable_cylinder};
use super::tube::swept_tube;
use super::{COLOUR_VARIANTS, CableTint, ClampPart, DamageLevel, SceneError, SceneSpec, Snapshot};
use crate::pose::Pose;
use crate::robot::Shape;
use gltf_json::scene::UnitQuaternion as GltfQuaternion;
use gltf_json::{Index, Material, Mesh, Node};
use nalgebra::{Point3, UnitQuaternion, Vector3};

/// Outer radius of a guide marker, in cable radii.
const GUIDE_OUTER_RADII: f64 = 2.5;
/// Length of a guide marker along the guide's z axis (m).
const GUIDE_LENGTH_M: f64 = 0.012;

/// What a mesh shows, which decides its material.
#[derive(Debug, Clone, Copy)]
pub(super) enum Paint {
    /// Light grey.
    Robot,
    /// The cable, orange or by its margin.
    Cable(CableTint),
    /// A guide marker, by its part.
    Guide(ClampPart),
    /// The cable by its damage per cycle (the second colour variant).
    Damage(DamageLevel),
}

impl Paint {
    /// Material name, base colour (linear RGBA) and roughness.
    fn material(self) -> (&'static str, [f32; 4], f32) {
        // The cable's and the guides' colours: opaque, half rough.
        let opaque = |name, [r, g, b]: [f32; 3]| (name, [r, g, b, 1.0], 0.5);
        match self {
            Paint::Robot => ("robot", [0.8, 0.8, 0.8, 1.0], 0.7),
            Paint::Cable(tint) => {
                let name = match tint {
                    CableTint::Plain => "cable",
                    CableTint::Ample => "cable, ample margin",
                    CableTint::Tight => "cable, tight margin",
                    CableTint::Exceeded => "cable, limit exceeded",
                };
                opaque(name, tint.linear_rgb())
            }
            Paint::Guide(part) => {
                let name = match part {
                    ClampPart::Rigid => "guide",
                    ClampPart::Rotating => "guide, rotating clamp",
                    ClampPart::Swivel => "guide, swivel",
                    ClampPart::Sliding => "guide, sliding",
                    ClampPart::Retraction => "guide, retraction outlet",
                };
                opaque(name, part.linear_rgb())
            }
            Paint::Damage(level) => {
                let name = match level {
                    DamageLevel::Slight => "cable, slight damage",
                    DamageLevel::Low => "cable, low damage",
                    DamageLevel::Raised => "cable, raised damage",
                    DamageLevel::Worst => "cable, worst damage",
                };
                opaque(name, level.linear_rgb())
            }
        }
    }

    /// The material slot of this paint.
    fn slot(self) -> usize {
        match self {
            Paint::Robot => 0,
            Paint::Cable(tint) => 1 + tint as usize,
            Paint::Damage(level) => 1 + CableTint::ALL.len() + level as usize,
            Paint::Guide(part) => 1 + CableTint::ALL.len() + DamageLevel::ALL.len() + part as usize,
        }
    }
}

/// The scene's materials, each made when first used (so none is left unused).
#[derive(Default)]
pub(super) struct Materials {
    made: [Option<Index<Material>>;
        1 + CableTint::ALL.len() + DamageLevel::ALL.len() + ClampPart::ALL.len()],
}

impl Materials {
    /// The material of `paint`.
    pub fn get(&mut self, builder: &mut Builder, paint: Paint) -> Index<Material> {
        let slot = &mut self.made[paint.slot()];
        *slot.get_or_insert_with(|| {
            let (name, rgba, roughness) = paint.material();
            builder.material(name, rgba, roughness)
        })
    }
}

/// Meshes drawn more than once: the colliders and guide markers of every robot copy and the
/// pieces of the main cable.
pub(super) struct SharedMeshes {
    /// Per link, per collider.
    colliders: Vec<Vec<Index<Mesh>>>,
    /// The guide marker of each part used (indexed like [`ClampPart::ALL`]).
    guide: [Option<Index<Mesh>>; ClampPart::ALL.len()],
    /// Per tint (indexed like [`CableTint::ALL`]) and damage level (indexed like
    /// [`DamageLevel::ALL`], then one for a line without damage) used by a main cable line:
    /// the unit cylinder of a sub-segment and the sphere of a node.
    segment: PerColour,
    joint: PerColour,
}

/// A mesh per tint and damage level ([`SharedMeshes`]).
type PerColour = [[Option<Index<Mesh>>; DamageLevel::ALL.len() + 1]; CableTint::ALL.len()];

/// The damage column of [`PerColour`] for `level` (`None`: no damage given).
fn damage_slot(level: Option<DamageLevel>) -> usize {
    level.map_or(DamageLevel::ALL.len(), |l| l as usize)
}

/// The damage levels of a main cable line's sub-segments (the worse of its two nodes) and
/// nodes; `None` each where the spec gives it no damage.
pub(super) fn line_levels(
    spec: &SceneSpec<'_>,
    line: &str,
    nodes: usize,
) -> (Vec<Option<DamageLevel>>, Vec<Option<DamageLevel>>) {
    let worst = spec.worst_damage();
    let at_nodes: Vec<Option<DamageLevel>> = match spec.damage_of(line) {
        Some(damage) => (damage.iter())
            .map(|&d| Some(DamageLevel::of(d, worst)))
            .collect(),
        None => vec![None; nodes],
    };
    let at_segments = at_nodes.windows(2).map(|w| w[0].max(w[1])).collect();
    (at_segments, at_nodes)
}

impl SharedMeshes {
    /// Tessellates every collider once, the guide marker if there are guides and the cable
    /// pieces if the main scene has cable lines.
    pub fn new(
        builder: &mut Builder,
        spec: &SceneSpec<'_>,
        materials: &mut Materials,
    ) -> Result<SharedMeshes, SceneError> {
        let mut colliders = Vec::with_capacity(spec.robot.links.len());
        for link in &spec.robot.links {
            let mut meshes = Vec::with_capacity(link.colliders.len());
            for (i, collider) in link.colliders.iter().enumerate() {
                let name = format!("{} collider {i}: {}", link.name, describe(&collider.shape));
                let mesh = shape_mesh(&collider.shape);
                meshes.push(painted_mesh(
                    builder,
                    materials,
                    &name,
                    &mesh,
                    Paint::Robot,
                )?);
            }
            colliders.push(meshes);
        }
        let r = spec.cable_radius_m;
        let mut shared = SharedMeshes {
            colliders,
            guide: [None; ClampPart::ALL.len()],
            segment: Default::default(),
            joint: Default::default(),
        };
        for part in ClampPart::ALL {
            if !spec.guides.iter().any(|g| g.part == part) {
                continue;
            }
            let (name, marker) = match part {
                ClampPart::Rigid => (
                    "guide marker",
                    collar(r, GUIDE_OUTER_RADII * r, GUIDE_LENGTH_M),
                ),
                ClampPart::Rotating => (
                    "guide marker, rotating clamp",
                    collar(r, 1.6 * GUIDE_OUTER_RADII * r, 0.5 * GUIDE_LENGTH_M),
                ),
                ClampPart::Swivel => (
                    "guide marker, swivel",
                    cable_joint_sphere(GUIDE_OUTER_RADII * r),
                ),
                ClampPart::Sliding => (
                    "guide marker, sliding guide",
                    collar(r, 0.8 * GUIDE_OUTER_RADII * r, 2.0 * GUIDE_LENGTH_M),
                ),
                ClampPart::Retraction => (
                    "guide marker, retraction outlet",
                    collar(r, 2.5 * GUIDE_OUTER_RADII * r, GUIDE_LENGTH_M),
                ),
            };
            let mesh = painted_mesh(builder, materials, name, &marker, Paint::Guide(part))?;
            shared.guide[part as usize] = Some(mesh);
        }
        if !spec.damage.is_empty() {
            builder.variants(&COLOUR_VARIANTS);
        }
        // The colours the main cable uses, each made once, in a fixed order.
        let mut used = std::collections::BTreeSet::new();
        for line in &spec.main.cable {
            let tint = spec.tint_of(&line.name);
            let (segments, nodes) = line_levels(spec, &line.name, line.nodes_m.len());
            used.extend(segments.into_iter().map(|level| (tint, level, false)));
            used.extend(nodes.into_iter().map(|level| (tint, level, true)));
        }
        for (tint, level, joint) in used {
            // The plain meshes keep the names they had before tints existed.
            let mut suffix = match tint {
                CableTint::Plain => String::new(),
                _ => format!(", {}", Paint::Cable(tint).material().0),
            };
            let paint = Paint::Cable(tint);
            let mut variants = Vec::new();
            if let Some(level) = level {
                let damage = Paint::Damage(level);
                suffix += &format!(" | {}", damage.material().0);
                variants.push((materials.get(builder, paint), 0));
                variants.push((materials.get(builder, damage), 1));
            }
            let (name, mesh) = match joint {
                false => (
                    format!("cable sub-segment (unit length){suffix}"),
                    unit_cable_cylinder(r),
                ),
                true => (format!("cable node{suffix}"), cable_joint_sphere(r)),
            };
            let material = materials.get(builder, paint);
            let made = builder.mesh_in_variants(&name, &mesh, material, &variants)?;
            let slots = match joint {
                false => &mut shared.segment,
                true => &mut shared.joint,
            };
            slots[tint as usize][damage_slot(level)] = Some(made);
        }
        Ok(shared)
    }
}

/// A mesh in the material of `paint`.
fn painted_mesh(
    builder: &mut Builder,
    materials: &mut Materials,
    name: &str,
    mesh: &TriangleMesh,
    paint: Paint,
) -> Result<Index<Mesh>, SceneError> {
    let material = materials.get(builder, paint);
    builder.mesh(name, mesh, material)
}

/// A shape's description, with only the file name of a mesh.
fn describe(shape: &Shape) -> String {
    match shape {
        Shape::Mesh(mesh) => {
            let file = mesh.file.file_name().unwrap_or(mesh.file.as_os_str());
            format!(
                "mesh {} ({} triangles)",
                file.to_string_lossy(),
                mesh.triangles.len()
            )
        }
        other => other.describe(),
    }
}

/// Node translation, rotation and scale.
#[derive(Debug, Clone, Copy)]
pub(super) struct Trs {
    pub translation: Vector3<f64>,
    pub rotation: UnitQuaternion<f64>,
    pub scale: Vector3<f64>,
}

impl Trs {
    /// The transform of a pose (unit scale).
    pub fn of_pose(pose: &Pose) -> Trs {
        Trs {
            translation: pose.translation.vector,
            rotation: pose.rotation,
            scale: Vector3::repeat(1.0),
        }
    }

    /// A translation only.
    pub fn at(point: &Point3<f64>) -> Trs {
        Trs::of_pose(&Pose::translation(point.x, point.y, point.z))
    }

    /// Maps the unit cylinder (z from 0 to 1) onto the segment from `a` to `b`.
    pub fn segment(a: &Point3<f64>, b: &Point3<f64>) -> Trs {
        let delta = b - a;
        let rotation =
            UnitQuaternion::rotation_between(&Vector3::z(), &delta).unwrap_or_else(|| {
                // Zero length (any rotation) or pointing along -z (half a turn about x).
                let angle = if delta.z < 0.0 {
                    std::f64::consts::PI
                } else {
                    0.0
                };
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), angle)
            });
        Trs {
            translation: a.coords,
            rotation,
            scale: Vector3::new(1.0, 1.0, delta.norm()),
        }
    }

    /// A node with this transform (identity parts left out).
    pub fn node(&self, mesh: Option<Index<Mesh>>) -> Node {
        Node {
            mesh,
            translation: (self.translation != Vector3::zeros()).then(|| f32x3(&self.translation)),
            rotation: (self.rotation != UnitQuaternion::identity())
                .then(|| gltf_quaternion(&self.rotation)),
            scale: (self.scale != Vector3::repeat(1.0)).then(|| f32x3(&self.scale)),
            ..Default::default()
        }
    }
}

/// A vector as `f32` components.
pub(super) fn f32x3(v: &Vector3<f64>) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

/// A rotation as glTF's (x, y, z, w) quaternion.
pub(super) fn quaternion_xyzw(q: &UnitQuaternion<f64>) -> [f32; 4] {
    let c = q.coords;
    [c.x as f32, c.y as f32, c.z as f32, c.w as f32]
}

fn gltf_quaternion(q: &UnitQuaternion<f64>) -> GltfQuaternion {
    GltfQuaternion(quaternion_xyzw(q))
}

/// The root node turning the robot's z-up world into glTF's y-up one (−90° about x).
pub(super) fn world_root(builder: &mut Builder) -> Index<Node> {
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let node = Node {
        rotation: Some(GltfQuaternion([-h, 0.0, 0.0, h])),
        ..Default::default()
    };
    builder.node("robot world (z up)", node)
}

/// A copy of the robot under `parent`: one node per link at `link_poses`, with its colliders
/// and guide markers. Returns the link nodes, indexed like the robot's links.
pub(super) fn robot_copy(
    builder: &mut Builder,
    spec: &SceneSpec<'_>,
    link_poses: &[Pose],
    meshes: &SharedMeshes,
    parent: Index<Node>,
) -> Vec<Index<Node>> {
    let mut link_nodes = Vec::with_capacity(spec.robot.links.len());
    for (l, (link, pose)) in spec.robot.links.iter().zip(link_poses).enumerate() {
        let node = builder.node(link.name.clone(), Trs::of_pose(pose).node(None));
        builder.add_child(parent, node);
        let collider_meshes = meshes.colliders.get(l).map_or(&[][..], Vec::as_slice);
        for (i, (collider, &mesh)) in link.colliders.iter().zip(collider_meshes).enumerate() {
            let child = builder.node(
                format!("{} collider {i}", link.name),
                Trs::of_pose(&collider.origin).node(Some(mesh)),
            );
            builder.add_child(node, child);
        }
        for guide in spec.guides.iter().filter(|g| g.link == l) {
            let marker = builder.node(
                guide.name.clone(),
                Trs::of_pose(&guide.pose_in_link).node(meshes.guide[guide.part as usize]),
            );
            builder.add_child(node, marker);
        }
        link_nodes.push(node);
    }
    link_nodes
}

/// The nodes of one main cable line, for the animation.
pub(super) struct LineNodes {
    /// One per sub-segment (node k to node k + 1).
    pub segments: Vec<Index<Node>>,
    /// One sphere per cable node.
    pub joints: Vec<Index<Node>>,
}

/// The main cable under `parent`: per line a node holding its sub-segments (the unit
/// cylinder scaled onto each) and a sphere at every node.
pub(super) fn main_cable(
    builder: &mut Builder,
    spec: &SceneSpec<'_>,
    meshes: &SharedMeshes,
    parent: Index<Node>,
) -> Vec<LineNodes> {
    let lines = &spec.main.cable;
    let mut all = Vec::with_capacity(lines.len());
    for line in lines {
        let tint = spec.tint_of(&line.name) as usize;
        let line_node = builder.node(line.name.clone(), Node::default());
        builder.add_child(parent, line_node);
        let nodes = &line.nodes_m;
        let (segment_levels, node_levels) = line_levels(spec, &line.name, nodes.len());
        let mut segments = Vec::with_capacity(nodes.len().saturating_sub(1));
        for (k, pair) in nodes.windows(2).enumerate() {
            let mesh = meshes.segment[tint][damage_slot(segment_levels[k])];
            let node = Trs::segment(&pair[0], &pair[1]).node(mesh);
            let segment = builder.node(format!("{} sub-segment {k}", line.name), node);
            builder.add_child(line_node, segment);
            segments.push(segment);
        }
        let mut joints = Vec::with_capacity(nodes.len());
        for (k, point) in nodes.iter().enumerate() {
            let joint = builder.node(
                format!("{} node {k}", line.name),
                Trs::at(point).node(meshes.joint[tint][damage_slot(node_levels[k])]),
            );
            builder.add_child(line_node, joint);
            joints.push(joint);
        }
        all.push(LineNodes { segments, joints });
    }
    all
}

/// A snapshot under `parent`: a robot copy and one swept tube per cable line, shifted by
/// the snapshot's offset.
pub(super) fn snapshot(
    builder: &mut Builder,
    spec: &SceneSpec<'_>,
    snapshot: &Snapshot,
    meshes: &SharedMeshes,
    materials: &mut Materials,
    parent: Index<Node>,
) -> Result<Index<Node>, SceneError> {
    let offset = Trs::at(&Point3::from(snapshot.offset_m));
    let node = builder.node(snapshot.name.clone(), offset.node(None));
    builder.add_child(parent, node);
    robot_copy(builder, spec, &snapshot.scene.link_poses, meshes, node);
    for line in &snapshot.scene.cable {
        let tube = swept_tube(&line.nodes_m, spec.cable_radius_m);
        let name = format!("{}: {}", snapshot.name, line.name);
        let paint = Paint::Cable(spec.tint_of(&line.name));
        let mesh = painted_mesh(builder, materials, &name, &tube, paint)?;
        let line_node = builder.node(
            line.name.clone(),
            Node {
                mesh: Some(mesh),
                ..Default::default()
            },
        );
        builder.add_child(node, line_node);
    }
    Ok(node)
}
