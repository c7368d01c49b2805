//! Checks a [`SceneSpec`] before anything is written, so that building the document can
//! index links, frames and nodes without further checks.

use super::{CableLine, PoseScene, SceneAnimation, SceneError, SceneSpec};
use crate::pose::Pose;
use crate::robot::{Robot, Shape};

/// Refuses a spec that cannot be drawn (see [`SceneError`] for the cases).
pub(super) fn check_spec(spec: &SceneSpec<'_>) -> Result<(), SceneError> {
    let radius = spec.cable_radius_m;
    if !(finite32(radius) && radius > 0.0) {
        return Err(SceneError::CableRadius(radius));
    }
    check_robot(spec.robot)?;
    check_pose_scene("main", &spec.main, spec.robot)?;
    for guide in &spec.guides {
        if guide.link >= spec.robot.links.len() {
            return Err(SceneError::GuideLink {
                guide: guide.name.clone(),
                link: guide.link,
                links: spec.robot.links.len(),
            });
        }
        check_pose(
            "guides",
            &format!("the pose of guide '{}'", guide.name),
            &guide.pose_in_link,
        )?;
    }
    for (line, damage) in &spec.damage {
        check_damage(spec, line, damage)?;
    }
    for animation in spec.animations() {
        check_animation(&animation, spec)?;
    }
    for snapshot in &spec.snapshots {
        let scene = format!("snapshot '{}'", snapshot.name);
        check_pose_scene(&scene, &snapshot.scene, spec.robot)?;
        if !snapshot.offset_m.iter().all(|&v| finite32(v)) {
            return Err(non_finite(&scene, "the offset"));
        }
    }
    Ok(())
}

/// One value per node of a main cable line, each finite and ≥ 0.
fn check_damage(spec: &SceneSpec<'_>, line: &str, damage: &[f64]) -> Result<(), SceneError> {
    let refuse = |why: String| SceneError::Damage {
        line: line.to_owned(),
        why,
    };
    let Some(main) = spec.main.cable.iter().find(|l| l.name == line) else {
        return Err(refuse("the main scene has no such line".into()));
    };
    if damage.len() != main.nodes_m.len() {
        return Err(refuse(format!(
            "{} values for {} nodes",
            damage.len(),
            main.nodes_m.len()
        )));
    }
    match damage.iter().position(|d| !(finite32(*d) && *d >= 0.0)) {
        Some(k) => Err(refuse(format!(
            "node {k}: {} is not a finite value ≥ 0",
            damage[k]
        ))),
        None => Ok(()),
    }
}

/// True when `value` is finite also as an `f32`.
pub(super) fn finite32(value: f64) -> bool {
    value.is_finite() && value.abs() <= f64::from(f32::MAX)
}

fn non_finite(scene: &str, what: &str) -> SceneError {
    SceneError::NonFinite {
        scene: scene.to_owned(),
        what: what.to_owned(),
    }
}

/// Mesh colliders must index their own vertices (primitive shapes are checked by tessellation).
fn check_robot(robot: &Robot) -> Result<(), SceneError> {
    for link in &robot.links {
        for (collider, shape) in link.colliders.iter().map(|c| &c.shape).enumerate() {
            let Shape::Mesh(mesh) = shape else { continue };
            let vertices = mesh.vertices.len();
            for (triangle, indices) in mesh.triangles.iter().enumerate() {
                if let Some(&vertex) = indices.iter().find(|&&i| i as usize >= vertices) {
                    return Err(SceneError::MeshIndex {
                        link: link.name.clone(),
                        collider,
                        triangle,
                        vertex,
                        vertices,
                    });
                }
            }
        }
    }
    Ok(())
}

fn check_pose(scene: &str, what: &str, pose: &Pose) -> Result<(), SceneError> {
    let values = pose
        .translation
        .vector
        .iter()
        .chain(pose.rotation.coords.iter());
    if values.copied().all(finite32) {
        Ok(())
    } else {
        Err(non_finite(scene, what))
    }
}

fn check_pose_scene(scene: &str, pose_scene: &PoseScene, robot: &Robot) -> Result<(), SceneError> {
    if pose_scene.link_poses.len() != robot.links.len() {
        return Err(SceneError::LinkPoseCount {
            scene: scene.to_owned(),
            got: pose_scene.link_poses.len(),
            expected: robot.links.len(),
        });
    }
    for (link, pose) in robot.links.iter().zip(&pose_scene.link_poses) {
        check_pose(scene, &format!("the pose of link '{}'", link.name), pose)?;
    }
    pose_scene
        .cable
        .iter()
        .try_for_each(|line| check_line(scene, line))
}

fn check_line(scene: &str, line: &CableLine) -> Result<(), SceneError> {
    if line.nodes_m.len() < 2 {
        return Err(SceneError::TooFewNodes {
            scene: scene.to_owned(),
            line: line.name.clone(),
            nodes: line.nodes_m.len(),
        });
    }
    match line
        .nodes_m
        .iter()
        .position(|p| !p.iter().copied().all(finite32))
    {
        Some(k) => Err(non_finite(
            scene,
            &format!("node {k} of cable line '{}'", line.name),
        )),
        None => Ok(()),
    }
}

fn check_animation(animation: &SceneAnimation, spec: &SceneSpec<'_>) -> Result<(), SceneError> {
    check_times(animation)?;
    for (frame, pose_scene) in animation.frames.iter().enumerate() {
        check_pose_scene(&format!("animation frame {frame}"), pose_scene, spec.robot)?;
        check_same_lines(frame, pose_scene, &spec.main)?;
    }
    Ok(())
}

fn check_times(animation: &SceneAnimation) -> Result<(), SceneError> {
    let name = || animation.name.clone();
    let (times, frames) = (animation.times_s.len(), animation.frames.len());
    if times != frames {
        return Err(SceneError::KeyframeCount {
            animation: name(),
            times,
            frames,
        });
    }
    let Some(&first) = animation.times_s.first() else {
        return Err(SceneError::NoKeyframes { animation: name() });
    };
    if let Some(k) = animation.times_s.iter().position(|&t| !finite32(t)) {
        return Err(non_finite(
            &format!("animation '{}'", animation.name),
            &format!("keyframe time {k}"),
        ));
    }
    if first != 0.0 {
        return Err(SceneError::FirstKeyframe {
            animation: name(),
            time: first,
        });
    }
    for (index, pair) in animation.times_s.windows(2).enumerate() {
        let (previous, time) = (pair[0], pair[1]);
        if !(time > previous && (time as f32) > (previous as f32)) {
            return Err(SceneError::TimesNotIncreasing {
                animation: name(),
                index: index + 1,
                previous,
                time,
            });
        }
    }
    Ok(())
}

fn check_same_lines(
    frame: usize,
    pose_scene: &PoseScene,
    main: &PoseScene,
) -> Result<(), SceneError> {
    if pose_scene.cable.len() != main.cable.len() {
        return Err(SceneError::FrameLineCount {
            frame,
            got: pose_scene.cable.len(),
            expected: main.cable.len(),
        });
    }
    for (index, (line, main_line)) in pose_scene.cable.iter().zip(&main.cable).enumerate() {
        if line.nodes_m.len() != main_line.nodes_m.len() {
            return Err(SceneError::FrameNodeCount {
                frame,
                index,
                line: main_line.name.clone(),
                got: line.nodes_m.len(),
                expected: main_line.nodes_m.len(),
            });
        }
    }
    Ok(())
}
