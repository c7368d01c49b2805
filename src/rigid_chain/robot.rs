//! The robot's links as kinematic obstacles for the cable.

use nalgebra::{UnitQuaternion, Vector3};
use rapier3d::prelude::{
    ColliderBuilder, InteractionGroups, InteractionTestMode, PhysicsWorld, RigidBodyBuilder,
    RigidBodyHandle,
};

use super::build::{CABLE_GROUP, MAX_LINK_GROUPS, ROBOT_TAG, checked_pose, link_group};
use super::convert::{to_rapier_point, to_rapier_pose};
use super::error::{RigidChainError, invalid};
use crate::pose::Pose;
use crate::robot::{Collider, Robot, Shape};

/// Checks one pose per link and returns them renormalised.
pub(super) fn checked_link_poses(
    link_poses: &[Pose],
    links: usize,
) -> Result<Vec<Pose>, RigidChainError> {
    if link_poses.len() != links {
        return Err(invalid(format!(
            "expected {links} link poses (one per robot link), got {}",
            link_poses.len()
        )));
    }
    link_poses
        .iter()
        .enumerate()
        .map(|(i, pose)| checked_pose(pose, &format!("link {i}")))
        .collect()
}

/// Inserts one kinematic body per link that has colliders, at its pose, with the link's
/// colliders attached; `None` for links without collision geometry.
pub(super) fn insert_links(
    world: &mut PhysicsWorld,
    robot: &Robot,
    link_poses: &[Pose],
    friction: f64,
) -> Result<Vec<Option<RigidBodyHandle>>, RigidChainError> {
    let poses = checked_link_poses(link_poses, robot.links.len())?;
    if let Some((i, link)) = robot
        .links
        .iter()
        .enumerate()
        .find(|(i, link)| *i >= MAX_LINK_GROUPS && !link.colliders.is_empty())
    {
        return Err(invalid(format!(
            "link `{}` (index {i}) has colliders, but only the first {MAX_LINK_GROUPS} links \
             can be obstacles (one collision group each)",
            link.name
        )));
    }
    let mut handles = Vec::with_capacity(robot.links.len());
    for (i, (link, pose)) in robot.links.iter().zip(&poses).enumerate() {
        if link.colliders.is_empty() {
            handles.push(None);
            continue;
        }
        let builders = link
            .colliders
            .iter()
            .map(|c| collider_builder(c, i, friction))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| invalid(format!("link `{}`: {e}", link.name)))?;
        let body = world
            .insert_body(RigidBodyBuilder::kinematic_position_based().pose(to_rapier_pose(pose)));
        for builder in builders {
            world
                .colliders
                .insert_with_parent(builder, body, &mut world.bodies);
        }
        handles.push(Some(body));
    }
    Ok(handles)
}

/// The rapier collider of a URDF collision shape, posed in its link's frame.
fn collider_builder(
    collider: &Collider,
    link: usize,
    friction: f64,
) -> Result<ColliderBuilder, String> {
    let f = |v: f64| v as f32;
    // Rapier's cylinder is along its local y, URDF's along z: turn y into z.
    let y_to_z = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2);
    let (builder, frame) = match &collider.shape {
        Shape::Box { half_extents_m: h } => (ColliderBuilder::cuboid(f(h.x), f(h.y), f(h.z)), None),
        Shape::Cylinder { radius_m, length_m } => (
            ColliderBuilder::cylinder(f(0.5 * length_m), f(*radius_m)),
            Some(y_to_z),
        ),
        Shape::Sphere { radius_m } => (ColliderBuilder::ball(f(*radius_m)), None),
        Shape::Capsule { radius_m, length_m } => (
            ColliderBuilder::capsule_z(f(0.5 * length_m), f(*radius_m)),
            None,
        ),
        Shape::Mesh(mesh) => {
            let vertices = mesh.vertices.iter().map(to_rapier_point).collect();
            let builder = ColliderBuilder::trimesh(vertices, mesh.triangles.clone())
                .map_err(|e| format!("mesh {}: {e}", mesh.file.display()))?;
            (builder, None)
        }
    };
    let mut origin = collider.origin;
    if let Some(turn) = frame {
        origin.rotation *= turn;
    }
    Ok(builder
        .position(to_rapier_pose(&origin))
        .density(0.0)
        .friction(f(friction))
        .collision_groups(InteractionGroups::new(
            link_group(link),
            CABLE_GROUP,
            InteractionTestMode::And,
        ))
        .user_data(ROBOT_TAG | link as u128))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_urdf_cylinder_keeps_its_axis_along_z() {
        let collider = Collider {
            origin: Pose::identity(),
            shape: Shape::Cylinder {
                radius_m: 0.05,
                length_m: 0.4,
            },
            attached: None,
        };
        let built = collider_builder(&collider, 0, 0.5).unwrap().build();
        let aabb = built.compute_aabb();
        assert!((aabb.maxs.z - 0.2).abs() < 1e-6, "{aabb:?}");
        assert!((aabb.maxs.y - 0.05).abs() < 1e-6, "{aabb:?}");
    }
}
