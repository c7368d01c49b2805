//! [`CableWorld`]: a whole cable (one or more segments) and optionally the robot, in rapier.

use nalgebra::{Point3, Rotation3, UnitQuaternion, Vector3};
use rapier3d::prelude::{PhysicsWorld, RigidBodyHandle};
use std::ops::Range;

use super::build::{
    MAX_LINK_GROUPS, SegmentShape, SubSegmentModel, check_shapes, checked_pose, insert_guides,
    insert_segment, link_group, sub_segment_poses,
};
use super::convert::{from_rapier_pose, to_rapier_pose, to_rapier_vector};
use super::error::{BlowUpQuantity, RigidChainError, invalid};
use super::record::{ContactTally, SegmentRecord, StepRecord};
use super::robot::{checked_link_poses, insert_links};
use super::settings::DynamicsSettings;
use crate::cable::CableSpec;
use crate::pose::Pose;
use crate::robot::Robot;
use crate::stress::{min_bend_radius, stretch};

/// A whole cable — one or several segments, each clamped by its two guides, consecutive
/// segments sharing a guide — simulated as the discrete cable of the crate, optionally with
/// the robot's links as kinematic obstacles.
///
/// Model: each sub-segment is a dynamic rigid body (mass `ρ l`, inertia of a solid cylinder of
/// the cable's diameter, a capsule collider of the cable's radius). Adjacent sub-segments,
/// and the end sub-segments and their guides, are joined at the node they share by a joint
/// with the three linear axes locked and angular springs (bending `kb` about the two axes
/// across the cable, torsion `kt` about it) pulling towards the rest state, in which the two
/// bodies' frames are aligned (a guide's frame plays the neighbouring sub-segment, its +z
/// along the cable). Guides are kinematic bodies without colliders; cable colliders touch
/// robot colliders only, and each link has a collision group of its own so that
/// [`CableWorld::ignore_contacts`] can exempt single links (the clamp zone at a guide).
///
/// Use: [`CableWorld::new`], optionally [`CableWorld::add_robot`], then per step set the
/// kinematic targets ([`CableWorld::move_guides`], [`CableWorld::move_robot`]) and call
/// [`CableWorld::step`].
pub struct CableWorld {
    world: PhysicsWorld,
    model: SubSegmentModel,
    settings: DynamicsSettings,
    guides: Vec<RigidBodyHandle>,
    segments: Vec<Vec<RigidBodyHandle>>,
    links: Option<Vec<Option<RigidBodyHandle>>>,
    steps: usize,
    failure: Option<RigidChainError>,
}

impl CableWorld {
    /// Builds the cable of `segments` (each from its initial shape) with `settings`.
    ///
    /// Errors ([`RigidChainError::InvalidInput`]): invalid settings or cable values, no segment,
    /// a segment with no sub-segment, node/frame counts that differ, non-finite values,
    /// chords not one pitch long (1 % tolerance) or end nodes off their guide origins, and
    /// consecutive segments whose shared guide poses differ (1e-6 m / 1e-6 rad).
    pub fn new(
        cable: &CableSpec,
        segments: &[SegmentShape],
        settings: &DynamicsSettings,
    ) -> Result<Self, RigidChainError> {
        settings.validate()?;
        let model = SubSegmentModel::new(cable)?;
        let guide_poses = check_shapes(segments, &model)?;
        let mut world = physics_world(settings);
        let guides = insert_guides(&mut world, &guide_poses);
        let bodies = segments
            .iter()
            .enumerate()
            .map(|(m, shape)| {
                let ends = (guides[m], guides[m + 1]);
                insert_segment(
                    &mut world,
                    m,
                    &sub_segment_poses(shape),
                    ends,
                    &model,
                    settings,
                )
            })
            .collect();
        Ok(Self {
            world,
            model,
            settings: settings.clone(),
            guides,
            segments: bodies,
            links: None,
            steps: 0,
            failure: None,
        })
    }

    /// Adds the robot's link colliders as kinematic obstacles, each link at `link_poses[i]`
    /// (indexed like `robot.links`, e.g. from [`Robot::link_poses`]). Box, cylinder, sphere,
    /// capsule and mesh shapes are supported. A second call is refused.
    pub fn add_robot(&mut self, robot: &Robot, link_poses: &[Pose]) -> Result<(), RigidChainError> {
        if self.links.is_some() {
            return Err(invalid("the robot was already added to this cable world"));
        }
        let links = insert_links(
            &mut self.world,
            robot,
            link_poses,
            self.settings.contact_friction,
        )?;
        self.links = Some(links);
        Ok(())
    }

    /// Stops contacts between the sub-segments `sub_segments` of segment `segment` and robot
    /// link `link` (indexed like `robot.links`), before or after [`CableWorld::add_robot`].
    /// For the clamp zone at a guide: there the cable is held against the guide's own link by
    /// the clamp, and the stress checks do not count that contact either.
    pub fn ignore_contacts(
        &mut self,
        segment: usize,
        sub_segments: Range<usize>,
        link: usize,
    ) -> Result<(), RigidChainError> {
        let bodies = self
            .segments
            .get(segment)
            .and_then(|bodies| bodies.get(sub_segments.clone()))
            .ok_or_else(|| {
                invalid(format!(
                    "no sub-segments {sub_segments:?} in segment {segment} of this cable"
                ))
            })?;
        if link >= MAX_LINK_GROUPS {
            return Err(invalid(format!(
                "link index {link}: only the first {MAX_LINK_GROUPS} links can be obstacles"
            )));
        }
        for body in bodies {
            for &collider in self.world.bodies[*body].colliders() {
                let collider = &mut self.world.colliders[collider];
                let mut groups = collider.collision_groups();
                groups.filter = groups.filter.difference(link_group(link));
                collider.set_collision_groups(groups);
            }
        }
        Ok(())
    }

    /// Sets the guides' poses to reach by the end of the next step, one per guide
    /// (`segments + 1`, from the first segment's start guide to the last segment's end guide).
    /// Large jumps are followed, but the cable is dragged along within one step: move guides
    /// in small increments.
    pub fn move_guides(&mut self, guide_poses: &[Pose]) -> Result<(), RigidChainError> {
        if guide_poses.len() != self.guides.len() {
            return Err(invalid(format!(
                "expected {} guide poses (segments + 1), got {}",
                self.guides.len(),
                guide_poses.len()
            )));
        }
        let checked = guide_poses
            .iter()
            .enumerate()
            .map(|(g, pose)| checked_pose(pose, &format!("guide {g}")))
            .collect::<Result<Vec<_>, _>>()?;
        for (handle, pose) in self.guides.iter().zip(&checked) {
            self.world.bodies[*handle].set_next_kinematic_position(to_rapier_pose(pose));
        }
        Ok(())
    }

    /// Sets the robot links' poses to reach by the end of the next step (indexed like
    /// `robot.links`). Refused before [`CableWorld::add_robot`].
    pub fn move_robot(&mut self, link_poses: &[Pose]) -> Result<(), RigidChainError> {
        let Some(links) = &self.links else {
            return Err(invalid(
                "move_robot before add_robot: there is no robot to move",
            ));
        };
        let poses = checked_link_poses(link_poses, links.len())?;
        for (handle, pose) in links.iter().zip(&poses) {
            if let Some(handle) = handle {
                self.world.bodies[*handle].set_next_kinematic_position(to_rapier_pose(pose));
            }
        }
        Ok(())
    }

    /// Advances the simulation by one time step and measures every segment.
    ///
    /// Returns [`RigidChainError::BlowUp`] when a body's state became non-finite, a sub-segment
    /// moves faster than the speed bound, a joint's anchors separate beyond the gap bound, or
    /// a segment stretches beyond the stretch bound (see
    /// [`BlowUpBounds`](super::BlowUpBounds)). After an error the world is unusable: every
    /// further call returns the same error.
    pub fn step(&mut self) -> Result<StepRecord, RigidChainError> {
        if let Some(failure) = &self.failure {
            return Err(failure.clone());
        }
        self.world.step();
        self.steps += 1;
        let result = self.check_and_record();
        if let Err(error) = &result {
            self.failure = Some(error.clone());
        }
        result
    }

    /// The `S + 1` nodes of segment `segment` (m): its start guide origin, the joints between
    /// its sub-segments (midpoint of the two bodies' anchors) and its end guide origin.
    /// `None` for a segment index out of range.
    pub fn segment_nodes(&self, segment: usize) -> Option<Vec<Point3<f64>>> {
        let bodies = self.segments.get(segment)?;
        let half = Vector3::new(0.0, 0.0, 0.5 * self.model.pitch_m);
        let poses: Vec<Pose> = bodies.iter().map(|h| self.body_pose(*h)).collect();
        let mut nodes = Vec::with_capacity(bodies.len() + 1);
        nodes.push(self.guide_pose(segment).translation.vector.into());
        for pair in poses.windows(2) {
            let head = pair[0] * Point3::from(half);
            let tail = pair[1] * Point3::from(-half);
            nodes.push(nalgebra::center(&head, &tail));
        }
        nodes.push(self.guide_pose(segment + 1).translation.vector.into());
        Some(nodes)
    }

    /// The `S + 1` node frames of segment `segment` (columns normal, binormal, tangent): the
    /// start guide's orientation, the mean orientation of the two sub-segments meeting at
    /// each interior node (its tangent bisects their axes), the end guide's orientation.
    /// `None` for a segment index out of range.
    pub fn segment_frames(&self, segment: usize) -> Option<Vec<Rotation3<f64>>> {
        let bodies = self.segments.get(segment)?;
        let rotations: Vec<UnitQuaternion<f64>> =
            bodies.iter().map(|h| self.body_pose(*h).rotation).collect();
        let mut frames = Vec::with_capacity(bodies.len() + 1);
        frames.push(self.guide_pose(segment).rotation.to_rotation_matrix());
        for pair in rotations.windows(2) {
            frames.push(mean_rotation(&pair[0], &pair[1]).to_rotation_matrix());
        }
        frames.push(self.guide_pose(segment + 1).rotation.to_rotation_matrix());
        Some(frames)
    }

    /// World poses of the `S` sub-segment bodies of segment `segment` (centre at the chord
    /// midpoint, local z along the sub-segment from the start guide's side). `None` out of
    /// range.
    pub fn sub_segment_poses(&self, segment: usize) -> Option<Vec<Pose>> {
        let bodies = self.segments.get(segment)?;
        Some(bodies.iter().map(|h| self.body_pose(*h)).collect())
    }

    /// Current pose of guide `guide` (0 ..= segments). `None` out of range.
    pub fn guide(&self, guide: usize) -> Option<Pose> {
        self.guides.get(guide).map(|_| self.guide_pose(guide))
    }

    /// Simulated time: steps taken × time step (s).
    pub fn time_s(&self) -> f64 {
        self.steps as f64 * self.settings.time_step_s
    }

    /// Steps taken so far.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Number of segments.
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// Number of sub-segments `S` of segment `segment`; `None` out of range.
    pub fn sub_segment_count(&self, segment: usize) -> Option<usize> {
        self.segments.get(segment).map(Vec::len)
    }

    /// The settings the world was built with.
    pub fn settings(&self) -> &DynamicsSettings {
        &self.settings
    }

    /// Pose of a body in double precision.
    fn body_pose(&self, handle: RigidBodyHandle) -> Pose {
        from_rapier_pose(self.world.bodies[handle].position())
    }

    /// Pose of guide `g` (index checked by the callers).
    fn guide_pose(&self, g: usize) -> Pose {
        self.body_pose(self.guides[g])
    }

    /// The blow-up checks and the measurements of one step.
    fn check_and_record(&self) -> Result<StepRecord, RigidChainError> {
        self.check_quarantine()?;
        let contacts = ContactTally::collect(&self.world, &self.segments, &self.settings);
        let segments = (0..self.segments.len())
            .map(|m| self.segment_record(m, &contacts))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(StepRecord {
            time_s: self.time_s(),
            segments,
        })
    }

    /// Rapier disables bodies whose state went non-finite; that is a blow-up.
    fn check_quarantine(&self) -> Result<(), RigidChainError> {
        let Some(&handle) = self.world.quarantine().bodies().first() else {
            return Ok(());
        };
        let (segment, sub_segment) = self
            .segments
            .iter()
            .enumerate()
            .find_map(|(m, bodies)| {
                bodies
                    .iter()
                    .position(|h| *h == handle)
                    .map(|s| (m, Some(s)))
            })
            .unwrap_or((0, None));
        Err(self.blow_up(
            segment,
            sub_segment,
            BlowUpQuantity::NonFinite,
            f64::NAN,
            0.0,
        ))
    }

    /// Speeds, joint gaps, stretch, bend radius and contacts of segment `m`.
    fn segment_record(
        &self,
        m: usize,
        contacts: &ContactTally,
    ) -> Result<SegmentRecord, RigidChainError> {
        self.check_speeds(m)?;
        let max_joint_gap_m = self.check_joint_gaps(m)?;
        let nodes = self.segment_nodes(m).unwrap_or_default();
        let natural = self.segments[m].len() as f64 * self.model.pitch_m;
        let stretch = stretch(&nodes, natural);
        let bound = self.settings.bounds.max_stretch;
        if stretch.is_nan() || stretch > bound {
            return Err(self.blow_up(m, None, BlowUpQuantity::Stretch, stretch, bound));
        }
        let axis = |g: usize| self.guide_pose(g).rotation * Vector3::z();
        let bend = min_bend_radius(&nodes, &axis(m), &axis(m + 1), self.model.pitch_m);
        Ok(SegmentRecord {
            contact: contacts.segment(m),
            stretch,
            min_bend: bend,
            max_joint_gap_m,
        })
    }

    /// Finite state and the speed bound, per sub-segment.
    fn check_speeds(&self, m: usize) -> Result<(), RigidChainError> {
        let bound = self.settings.bounds.max_speed_m_s;
        for (s, handle) in self.segments[m].iter().enumerate() {
            let body = &self.world.bodies[*handle];
            let finite = body.position().is_finite()
                && body.linvel().is_finite()
                && body.angvel().is_finite();
            if !finite {
                return Err(self.blow_up(m, Some(s), BlowUpQuantity::NonFinite, f64::NAN, 0.0));
            }
            let speed = f64::from(body.linvel().length());
            if speed > bound {
                return Err(self.blow_up(m, Some(s), BlowUpQuantity::Speed, speed, bound));
            }
        }
        Ok(())
    }

    /// Distance between the two anchors of every joint of segment `m`, guide joints included;
    /// returns the largest (m).
    fn check_joint_gaps(&self, m: usize) -> Result<f64, RigidChainError> {
        let bound = self.settings.bounds.max_joint_gap_pitches * self.model.pitch_m;
        let half = Vector3::new(0.0, 0.0, 0.5 * self.model.pitch_m);
        let poses: Vec<Pose> = self.segments[m]
            .iter()
            .map(|h| self.body_pose(*h))
            .collect();
        let mut heads = vec![Point3::from(self.guide_pose(m).translation.vector)];
        heads.extend(poses.iter().map(|p| p * Point3::from(half)));
        let mut tails: Vec<Point3<f64>> = poses.iter().map(|p| p * Point3::from(-half)).collect();
        tails.push(self.guide_pose(m + 1).translation.vector.into());
        let mut largest = 0.0_f64;
        for (s, (head, tail)) in heads.iter().zip(&tails).enumerate() {
            let gap = (head - tail).norm();
            largest = largest.max(gap);
            if gap.is_nan() || gap > bound {
                return Err(self.blow_up(m, Some(s), BlowUpQuantity::JointGap, gap, bound));
            }
        }
        Ok(largest)
    }

    fn blow_up(
        &self,
        segment: usize,
        sub_segment: Option<usize>,
        quantity: BlowUpQuantity,
        value: f64,
        bound: f64,
    ) -> RigidChainError {
        RigidChainError::BlowUp {
            step: self.steps,
            time_s: self.time_s(),
            segment,
            sub_segment,
            quantity,
            value,
            bound,
        }
    }
}

/// An empty rapier world stepped as `settings` say.
fn physics_world(settings: &DynamicsSettings) -> PhysicsWorld {
    let mut world = PhysicsWorld::new();
    world.gravity = to_rapier_vector(&settings.gravity_m_s2);
    world.integration_parameters.dt = settings.time_step_s as f32;
    world.integration_parameters.num_solver_iterations = settings.substeps;
    world.integration_parameters.num_internal_pgs_iterations = settings.sweeps_per_substep;
    // length_unit is 1 m, so the normalized distance is in metres.
    world.integration_parameters.normalized_prediction_distance =
        settings.contact_prediction_m as f32;
    world
}

/// The rotation halfway between two rotations (normalised quaternion mean, sign-aligned).
fn mean_rotation(a: &UnitQuaternion<f64>, b: &UnitQuaternion<f64>) -> UnitQuaternion<f64> {
    let sign = if a.coords.dot(&b.coords) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let sum = a.quaternion() + b.quaternion() * sign;
    UnitQuaternion::try_new(sum, 1e-12).unwrap_or(*a)
}
