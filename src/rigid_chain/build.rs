//! Building the discrete cable in a rapier world: sub-segment bodies, their colliders and the
//! spring joints between them and to the guides.

use nalgebra::{Matrix3, Point3, Rotation3, UnitQuaternion, Vector3};
use rapier3d::prelude::{
    ColliderBuilder, GenericJointBuilder, Group, InteractionGroups, InteractionTestMode,
    JointAxesMask, JointAxis, MassProperties, MotorModel, PhysicsWorld, RigidBodyBuilder,
    RigidBodyHandle,
};

use super::convert::{to_rapier_pose, to_rapier_vector};
use super::error::{RigidChainError, invalid};
use super::settings::DynamicsSettings;
use crate::cable::CableSpec;
use crate::geometry::ConnectedGeometry;
use crate::pose::Pose;

/// Collision group of cable colliders; they only interact with robot links.
pub(super) const CABLE_GROUP: Group = Group::GROUP_1;
/// Robot links with colliders that can have a collision group of their own (bits 1 to 31), so
/// that a cable collider can ignore single links (the clamp zone at a guide).
pub(super) const MAX_LINK_GROUPS: usize = 31;

/// Collision group of the colliders of robot link `link` (< [`MAX_LINK_GROUPS`]).
pub(super) fn link_group(link: usize) -> Group {
    debug_assert!(link < MAX_LINK_GROUPS);
    Group::from_bits_truncate(1 << (link + 1))
}

/// Every link's collision group: what a cable collider interacts with by default.
fn all_link_groups() -> Group {
    Group::all().difference(CABLE_GROUP)
}
/// Tag in the upper 64 bits of a cable collider's `user_data` (segment and sub-segment below).
pub(super) const CABLE_TAG: u128 = 1 << 64;
/// Tag in the upper 64 bits of a robot collider's `user_data` (link index below).
pub(super) const ROBOT_TAG: u128 = 2 << 64;
/// How far (in pitches) a shape's chord may differ from the pitch, or its end nodes from the
/// guide origins: the joints start assembled within this, and the solver closes the rest.
const CHORD_TOLERANCE_PITCHES: f64 = 0.01;
/// Consecutive segments share a guide: their poses there must agree within this (m, rad).
const SHARED_GUIDE_TOLERANCE: f64 = 1e-6;

/// The shape a segment starts from, between its two guide frames (SI units).
///
/// `nodes` are `S + 1` points from the start guide origin to the end guide origin, adjacent
/// ones one sub-segment pitch apart (within 1 %); `frames` are the `S + 1` node frames
/// (columns normal, binormal, tangent), as in [`ConnectedGeometry`].
#[derive(Debug, Clone, Copy)]
pub struct SegmentShape<'a> {
    /// Pose of the start guide (its +z is the cable direction there).
    pub start_guide: Pose,
    /// Pose of the end guide (its +z is the cable direction there).
    pub end_guide: Pose,
    /// `S + 1` nodes (m).
    pub nodes: &'a [Point3<f64>],
    /// `S + 1` node frames.
    pub frames: &'a [Rotation3<f64>],
}

impl<'a> SegmentShape<'a> {
    /// The shape of a connected geometry between the guides it was built for.
    pub fn from_connected(start: &Pose, end: &Pose, geometry: &'a ConnectedGeometry) -> Self {
        Self {
            start_guide: *start,
            end_guide: *end,
            nodes: &geometry.nodes,
            frames: &geometry.frames,
        }
    }

    /// Number of sub-segments `S` (0 for an empty shape).
    pub fn sub_segment_count(&self) -> usize {
        self.nodes.len().saturating_sub(1)
    }
}

/// The rigid sub-segment of a cable, derived once from its [`CableSpec`].
#[derive(Debug, Clone, Copy)]
pub(super) struct SubSegmentModel {
    /// Pitch `l` (m).
    pub pitch_m: f64,
    /// Cable radius (m).
    pub radius_m: f64,
    /// Mass `ρ l` (kg).
    pub mass_kg: f64,
    /// Principal moments of inertia of a solid cylinder about its centre (kg·m²), z = axis.
    pub inertia_kg_m2: Vector3<f64>,
    /// Bending spring per joint (N·m/rad).
    pub bending_nm_per_rad: f64,
    /// Torsion spring per joint (N·m/rad).
    pub torsion_nm_per_rad: f64,
}

impl SubSegmentModel {
    /// The sub-segment of `cable`; refuses non-finite or non-positive values (the fields of a
    /// [`CableSpec`] are public, so a hand-made one is checked here too).
    pub fn new(cable: &CableSpec) -> Result<Self, RigidChainError> {
        let values = [
            ("diameter", cable.diameter_m),
            ("mass per length", cable.mass_per_length_kg_m),
            ("bending stiffness", cable.bending_stiffness_nm_per_rad()),
            ("torsion stiffness", cable.torsion_stiffness_nm_per_rad()),
            ("sub-segment pitch", cable.sub_segment_pitch_m),
        ];
        if let Some((name, value)) = values.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Err(invalid(format!(
                "cable `{}`: {name} = {value} must be finite and > 0",
                cable.name
            )));
        }
        let (l, r) = (cable.sub_segment_pitch_m, 0.5 * cable.diameter_m);
        let mass = cable.mass_per_length_kg_m * l;
        let across = mass * (3.0 * r * r + l * l) / 12.0;
        Ok(Self {
            pitch_m: l,
            radius_m: r,
            mass_kg: mass,
            inertia_kg_m2: Vector3::new(across, across, 0.5 * mass * r * r),
            bending_nm_per_rad: cable.bending_stiffness_nm_per_rad(),
            torsion_nm_per_rad: cable.torsion_stiffness_nm_per_rad(),
        })
    }
}

/// Checks a pose and returns it with a renormalised rotation.
pub(super) fn checked_pose(pose: &Pose, what: &str) -> Result<Pose, RigidChainError> {
    let finite = pose.translation.vector.iter().all(|v| v.is_finite())
        && pose.rotation.coords.iter().all(|v| v.is_finite());
    let norm = pose.rotation.coords.norm();
    if !finite || norm < 1e-6 {
        return Err(invalid(format!(
            "{what}: pose must be finite with a non-zero rotation quaternion, got translation {:?}, quaternion {:?}",
            pose.translation.vector.as_slice(),
            pose.rotation.coords.as_slice()
        )));
    }
    let rotation = UnitQuaternion::new_normalize(*pose.rotation.quaternion());
    Ok(Pose::from_parts(pose.translation, rotation))
}

/// Checks the shapes of a whole cable and returns the `segments + 1` guide poses.
pub(super) fn check_shapes(
    shapes: &[SegmentShape],
    model: &SubSegmentModel,
) -> Result<Vec<Pose>, RigidChainError> {
    if shapes.is_empty() {
        return Err(invalid("a cable needs at least one segment"));
    }
    let mut guides = Vec::with_capacity(shapes.len() + 1);
    for (m, shape) in shapes.iter().enumerate() {
        let start = checked_pose(&shape.start_guide, &format!("segment {m} start guide"))?;
        let end = checked_pose(&shape.end_guide, &format!("segment {m} end guide"))?;
        if let Some(previous) = guides.last() {
            check_shared_guide(previous, &start, m)?;
        } else {
            guides.push(start);
        }
        check_shape(shape, &start, &end, model.pitch_m, m)?;
        guides.push(end);
    }
    Ok(guides)
}

/// The end guide of segment `m − 1` must be the start guide of segment `m`.
fn check_shared_guide(previous_end: &Pose, start: &Pose, m: usize) -> Result<(), RigidChainError> {
    let offset = (previous_end.translation.vector - start.translation.vector).norm();
    let angle = previous_end.rotation.angle_to(&start.rotation);
    if offset > SHARED_GUIDE_TOLERANCE || angle > SHARED_GUIDE_TOLERANCE {
        return Err(invalid(format!(
            "segment {m} must start at the end guide of segment {}: they are {:.3e} m and {:.3e} rad apart",
            m - 1,
            offset,
            angle
        )));
    }
    Ok(())
}

/// Node and frame counts, finiteness, chord lengths and end nodes of one segment's shape.
fn check_shape(
    shape: &SegmentShape,
    start: &Pose,
    end: &Pose,
    pitch: f64,
    m: usize,
) -> Result<(), RigidChainError> {
    let s = shape.sub_segment_count();
    if s == 0 {
        return Err(invalid(format!(
            "segment {m}: a segment needs at least one sub-segment (got {} nodes)",
            shape.nodes.len()
        )));
    }
    if shape.frames.len() != shape.nodes.len() {
        return Err(invalid(format!(
            "segment {m}: {} nodes but {} frames (need one frame per node)",
            shape.nodes.len(),
            shape.frames.len()
        )));
    }
    let finite_nodes = shape.nodes.iter().all(|p| p.iter().all(|v| v.is_finite()));
    let finite_frames = shape
        .frames
        .iter()
        .all(|f| f.matrix().iter().all(|v| v.is_finite()));
    if !finite_nodes || !finite_frames {
        return Err(invalid(format!("segment {m}: non-finite node or frame")));
    }
    let tolerance = CHORD_TOLERANCE_PITCHES * pitch;
    for (k, pair) in shape.nodes.windows(2).enumerate() {
        let chord = (pair[1] - pair[0]).norm();
        if (chord - pitch).abs() > tolerance {
            return Err(invalid(format!(
                "segment {m}: nodes {k} and {} are {:.4} mm apart, not one pitch ({:.4} mm)",
                k + 1,
                chord * 1e3,
                pitch * 1e3
            )));
        }
    }
    let ends = [(0, start), (s, end)];
    for (k, guide) in ends {
        let offset = (shape.nodes[k].coords - guide.translation.vector).norm();
        if offset > tolerance {
            return Err(invalid(format!(
                "segment {m}: node {k} is {:.4} mm from its guide origin",
                offset * 1e3
            )));
        }
    }
    Ok(())
}

/// Initial world poses of a shape's `S` sub-segments (see [`sub_segment_pose`]).
pub(super) fn sub_segment_poses(shape: &SegmentShape) -> Vec<Pose> {
    (0..shape.sub_segment_count())
        .map(|s| sub_segment_pose(&shape.nodes[s], &shape.nodes[s + 1], &shape.frames[s]))
        .collect()
}

/// World pose of the sub-segment from `a` to `b`: centre at the chord midpoint, local z along
/// the chord, local x the node frame's normal made perpendicular to the chord.
fn sub_segment_pose(a: &Point3<f64>, b: &Point3<f64>, frame: &Rotation3<f64>) -> Pose {
    let chord = b - a;
    let z = chord
        .try_normalize(0.0)
        .unwrap_or_else(|| frame * Vector3::z());
    let perpendicular = |v: Vector3<f64>| (v - v.dot(&z) * z).try_normalize(1e-6);
    let x = perpendicular(frame * Vector3::x())
        .or_else(|| perpendicular(frame * Vector3::y()))
        .or_else(|| perpendicular(Vector3::x()))
        .or_else(|| perpendicular(Vector3::y()))
        .unwrap_or_else(Vector3::z);
    let y = z.cross(&x);
    let rotation = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, y, z]));
    Pose::from_parts(
        nalgebra::Translation3::from(nalgebra::center(a, b).coords),
        UnitQuaternion::from_rotation_matrix(&rotation),
    )
}

/// Inserts the kinematic guide bodies (no colliders).
pub(super) fn insert_guides(world: &mut PhysicsWorld, guides: &[Pose]) -> Vec<RigidBodyHandle> {
    guides
        .iter()
        .map(|pose| {
            world.insert_body(
                RigidBodyBuilder::kinematic_position_based().pose(to_rapier_pose(pose)),
            )
        })
        .collect()
}

/// Inserts the sub-segment bodies of segment `m` at `poses` and joins them to each other and
/// to the guide bodies `start` and `end`.
pub(super) fn insert_segment(
    world: &mut PhysicsWorld,
    m: usize,
    poses: &[Pose],
    (start, end): (RigidBodyHandle, RigidBodyHandle),
    model: &SubSegmentModel,
    settings: &DynamicsSettings,
) -> Vec<RigidBodyHandle> {
    let bodies: Vec<RigidBodyHandle> = poses
        .iter()
        .enumerate()
        .map(|(s, pose)| insert_sub_segment(world, m, s, pose, model, settings))
        .collect();
    let half = 0.5 * model.pitch_m;
    let (tail, head) = (Vector3::new(0.0, 0.0, -half), Vector3::new(0.0, 0.0, half));
    let joint = |anchor1: Vector3<f64>, anchor2: Vector3<f64>, scale: f64| {
        spring_joint(
            &anchor1,
            &anchor2,
            model,
            scale,
            settings.joint_damping_nms_per_rad,
        )
    };
    // A guide joint stands for half a sub-segment (the guide axis is the tangent at the
    // node, not a neighbouring chord), so its springs are twice as stiff: the same model as
    // `statics` (see docs/cable-statics.md).
    let mut pairs = vec![(start, bodies[0], joint(Vector3::zeros(), tail, 2.0))];
    for pair in bodies.windows(2) {
        pairs.push((pair[0], pair[1], joint(head, tail, 1.0)));
    }
    pairs.push((
        bodies[bodies.len() - 1],
        end,
        joint(head, Vector3::zeros(), 2.0),
    ));
    for (body1, body2, joint) in pairs {
        world.impulse_joints.insert(body1, body2, joint, true);
    }
    bodies
}

/// One dynamic sub-segment with its capsule collider.
fn insert_sub_segment(
    world: &mut PhysicsWorld,
    m: usize,
    s: usize,
    pose: &Pose,
    model: &SubSegmentModel,
    settings: &DynamicsSettings,
) -> RigidBodyHandle {
    let mass = MassProperties::new(
        rapier3d::math::Vector::ZERO,
        model.mass_kg as f32,
        to_rapier_vector(&model.inertia_kg_m2),
    );
    let body = RigidBodyBuilder::dynamic()
        .pose(to_rapier_pose(pose))
        .additional_mass_properties(mass)
        .linear_damping(settings.linear_damping_per_s as f32)
        .angular_damping(settings.angular_damping_per_s as f32)
        .can_sleep(false);
    let collider = ColliderBuilder::capsule_z((0.5 * model.pitch_m) as f32, model.radius_m as f32)
        .density(0.0)
        .friction(settings.contact_friction as f32)
        .collision_groups(InteractionGroups::new(
            CABLE_GROUP,
            all_link_groups(),
            InteractionTestMode::And,
        ))
        .user_data(CABLE_TAG | ((m as u128) << 32) | s as u128);
    world.insert(body, collider).0
}

/// The joint at a node: the three linear axes locked at the anchors (in each body's frame),
/// the three angular axes free but pulled back to the rest orientation (both joint frames
/// aligned) by force-based position motors: `kb` about the bending axes x and y of the first
/// body's joint frame, `kt` about its z axis (the cable axis), both times `scale`.
fn spring_joint(
    anchor1: &Vector3<f64>,
    anchor2: &Vector3<f64>,
    model: &SubSegmentModel,
    scale: f64,
    damping: f64,
) -> GenericJointBuilder {
    let springs = [
        (JointAxis::AngX, scale * model.bending_nm_per_rad),
        (JointAxis::AngY, scale * model.bending_nm_per_rad),
        (JointAxis::AngZ, scale * model.torsion_nm_per_rad),
    ];
    springs.into_iter().fold(
        GenericJointBuilder::new(JointAxesMask::LIN_AXES)
            .local_anchor1(to_rapier_vector(anchor1))
            .local_anchor2(to_rapier_vector(anchor2))
            .contacts_enabled(false),
        |joint, (axis, stiffness)| {
            joint
                .motor_position(axis, 0.0, stiffness as f32, damping as f32)
                .motor_model(axis, MotorModel::ForceBased)
        },
    )
}
