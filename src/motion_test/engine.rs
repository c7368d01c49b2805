//! The simulated cable behind one interface, whichever [`Engine`] moves it: started at rest
//! in the initial equilibria, advanced one step at a time to the guides' and links' poses,
//! read back as nodes (and, for the rigid chain, contact forces).

use super::MotionTestError;
use super::options::Engine;
use super::plan::Plan;
use super::report::{Failure, FailureCause};
use crate::dynamics::{IntegratorSettings, SegmentDynamics};
use crate::pose::Pose;
#[cfg(feature = "rigid-chain")]
use crate::rigid_chain::{CableWorld, ContactSummary, RigidChainError, SegmentShape};
use crate::setup::Setup;
use crate::statics::sliding::{SlideReading, SlideTrack, ThroughEquilibrium};
use crate::statics::swivel::SwivelThrough;
use crate::statics::{Equilibrium, FarEnd, RodParameters, SolverOptions};
use crate::stress::ClampZone;
#[cfg(feature = "rigid-chain")]
use crate::stress::GuideEnd;
use nalgebra::Point3;
use rayon::prelude::*;

/// One simulated segment after a step.
pub(super) struct SegmentState {
    /// `S + 1` nodes, world frame (m); a retraction's free piece only.
    pub nodes: Vec<Point3<f64>>,
    /// The cable length between two nodes (m): the setup's pitch, but for a retraction's
    /// free piece, stretched by its travel.
    pub pitch_m: f64,
    /// Where the nodes start when not at the segment's start clamp: a retraction's outlet.
    pub from: Option<Pose>,
    /// Through a sliding guide or out of a retraction: the split or travel (m) and the
    /// retraction's spring force (N).
    pub slid: Option<SlideReading>,
    /// The most loaded sub-segment outside the clamp zones (rigid chain only).
    pub contact: Option<ForceAt>,
    /// Largest joint gap (m): the rigid chain's constraint error; 0 for the implicit engine,
    /// whose sub-segments are one energy, not jointed bodies.
    pub max_joint_gap_m: f64,
    /// Total twist Ψ between the clamps (rad), relative to the cable as installed; `None`
    /// where the engine does not model it as the statics do (the rigid chain).
    pub twist_rad: Option<f64>,
}

/// The contact force on one sub-segment (rigid chain).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ForceAt {
    /// Sub-segment index.
    pub sub_segment: usize,
    /// Force summed over the robot's colliders (N).
    pub force_n: f64,
    /// Index into `robot.links` of the link pushing hardest, when known.
    pub link: Option<usize>,
}

/// A step the engine could not take: the simulated segment it belongs to, if one, and why.
pub(super) struct Diverged {
    pub segment: Option<usize>,
    pub detail: String,
}

/// One segment of the implicit engine: in motion between its clamps, or (through a sliding
/// guide or out of a retraction) followed quasi-statically with its split carried.
pub(super) enum Simulated {
    /// In motion between its clamps; held between them by a swivel clamp, if any: that
    /// clamp's link and its pose in that link's frame.
    Dynamic(Box<SegmentDynamics>, Option<(usize, Pose)>),
    Through {
        track: Box<SlideTrack>,
        /// The guide's link and its pose in that link's frame.
        guide: (usize, Pose),
        params: RodParameters,
    },
}

impl Simulated {
    /// Steps to the clamps at `(start, end)`, the links at `links`, by the engine's step.
    fn step(
        &mut self,
        (start, end): (Pose, Pose),
        links: &[Pose],
        settings: &IntegratorSettings,
    ) -> Result<(), String> {
        match self {
            Simulated::Dynamic(segment, swivel) => {
                if let Some((link, pose)) = swivel {
                    segment.move_pin(&(links[*link] * *pose));
                }
                segment
                    .step(start, FarEnd::Clamped(end), settings.time_step_s, settings)
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            }
            Simulated::Through {
                track,
                guide: (link, pose),
                params,
            } => {
                let through = links[*link] * *pose;
                track
                    .step(params, (start, through, end), &SolverOptions::STRESS_CHECK)
                    .map_err(|e| e.to_string())
            }
        }
    }

    /// Its state now.
    fn state(&self, pitch_m: f64) -> SegmentState {
        match self {
            Simulated::Dynamic(segment, _) => SegmentState {
                nodes: segment.nodes(),
                pitch_m,
                from: None,
                slid: None,
                contact: None,
                max_joint_gap_m: 0.0,
                twist_rad: Some(segment.twist_rad()),
            },
            Simulated::Through { track, .. } => track_state(track),
        }
    }
}

/// The state of a piece followed through a sliding guide or out of a retraction.
pub(super) fn track_state(track: &SlideTrack) -> SegmentState {
    let (nodes, pitch_m) = track.nodes();
    SegmentState {
        nodes,
        pitch_m,
        from: track.outlet(),
        slid: Some(track.reading()),
        contact: None,
        max_joint_gap_m: 0.0,
        twist_rad: Some(0.0),
    }
}

/// The cable in one of the engines.
pub(super) enum Cable {
    Implicit {
        segments: Vec<Simulated>,
        settings: IntegratorSettings,
        /// The setup's pitch (m).
        pitch_m: f64,
    },
    #[cfg(feature = "rigid-chain")]
    RigidChain {
        world: Box<CableWorld>,
        /// Sub-segments at each end left out of the contact force summary.
        zone_sub_segments: usize,
        /// The setup's pitch (m).
        pitch_m: f64,
    },
}

impl Cable {
    /// The cable at rest in `shapes` (one per simulated segment, between `guides`, with
    /// its clamp zones `zones`), the robot's links at `links`; a shape the engine refuses is
    /// a failed candidate.
    #[cfg_attr(not(feature = "rigid-chain"), allow(unused_variables))]
    pub fn start(
        engine: &Engine,
        (setup, plan): (&Setup, &Plan),
        zones: &[Vec<ClampZone>],
        (guides, links): (&[Pose], &[Pose]),
        (shapes, throughs): (&[Equilibrium], &[Option<ThroughEquilibrium>]),
    ) -> Result<Result<Cable, Failure>, MotionTestError> {
        let refused = |what: String| Failure {
            cause: FailureCause::NoInitialShape,
            reason: format!("the simulation refused the initial shape: {what}"),
            segment: None,
        };
        match engine {
            Engine::Implicit(settings) => {
                let params = RodParameters::new(&setup.cable, setup.gravity_m_s2);
                let mut segments = Vec::with_capacity(shapes.len());
                for (j, (shape, planned)) in shapes.iter().zip(&plan.segments).enumerate() {
                    let params = planned.rod(&params);
                    if let (Some(g), Some(Some(solved))) = (planned.through, throughs.get(j)) {
                        let guide = &setup.guides[g];
                        let configuration = &guide.configurations[0];
                        let through = setup.guide_world_pose(links, g, 0);
                        let track = SlideTrack::start(
                            configuration.kind,
                            solved,
                            (guides[j], through, guides[j + 1]),
                        );
                        segments.push(Simulated::Through {
                            track: Box::new(track),
                            guide: (guide.link, configuration.pose),
                            params,
                        });
                        continue;
                    }
                    let segment = match SegmentDynamics::at_rest(
                        &params,
                        guides[j],
                        FarEnd::Clamped(guides[j + 1]),
                        &shape.nodes,
                        shape.twist_rad,
                    ) {
                        Ok(segment) => segment,
                        Err(e) => return Ok(Err(refused(e.to_string()))),
                    };
                    let swivel = planned.swivel.map(|split| {
                        let clamp = setup.guide_world_pose(links, split.guide, 0);
                        let pin = SwivelThrough::new(clamp, &split, planned.sub_segments).pin();
                        let guide = &setup.guides[split.guide];
                        (pin, (guide.link, guide.configurations[0].pose))
                    });
                    segments.push(match swivel {
                        Some((pin, place)) => {
                            Simulated::Dynamic(Box::new(segment.with_pin(pin)), Some(place))
                        }
                        None => Simulated::Dynamic(Box::new(segment), None),
                    });
                }
                Ok(Ok(Cable::Implicit {
                    segments,
                    settings: *settings,
                    pitch_m: setup.cable.sub_segment_pitch_m,
                }))
            }
            #[cfg(not(feature = "rigid-chain"))]
            Engine::RigidChain(_) => Err(MotionTestError::Options {
                what: "the rigid-chain engine simulates in rapier3d: build with the rigid-chain \
                       feature"
                    .into(),
            }),
            #[cfg(feature = "rigid-chain")]
            Engine::RigidChain(settings) => {
                if let Some(planned) = plan
                    .segments
                    .iter()
                    .find(|s| s.holds != crate::statics::Holds::RIGID || s.through.is_some())
                {
                    return Err(MotionTestError::Options {
                        what: format!(
                            "the rigid-chain engine holds the cable in rigid clamps only, and \
                             {} ends in a rotating or swivel clamp or runs through a sliding \
                             guide: use the implicit engine",
                            setup.segment_name(planned.setup_index)
                        ),
                    });
                }
                let world = match rigid_world(setup, settings, guides, shapes, zones) {
                    Ok(world) => world,
                    Err(e) => return Ok(Err(refused(e.to_string()))),
                };
                let mut world = Box::new(world);
                world
                    .add_robot(&setup.robot, links)
                    .map_err(MotionTestError::Dynamics)?;
                Ok(Ok(Cable::RigidChain {
                    world,
                    zone_sub_segments: setup.clamp_zone(GuideEnd::Start, 0).sub_segments,
                    pitch_m: setup.cable.sub_segment_pitch_m,
                }))
            }
        }
    }

    /// One step to the guides at `guides` and the links at `links`: every segment's state,
    /// or the failure of a diverging simulation (`Ok(Err)`, naming the simulated segment
    /// when it belongs to one).
    #[cfg_attr(not(feature = "rigid-chain"), allow(unused_variables))]
    pub fn advance(
        &mut self,
        guides: &[Pose],
        links: &[Pose],
    ) -> Result<Result<Vec<SegmentState>, Diverged>, MotionTestError> {
        match self {
            Cable::Implicit {
                segments,
                settings,
                pitch_m,
            } => {
                // Segments are independent between clamps: stepped in parallel, each the same
                // computation whatever the thread count.
                let stepped: Vec<Result<(), String>> = segments
                    .par_iter_mut()
                    .enumerate()
                    .map(|(j, segment)| segment.step((guides[j], guides[j + 1]), links, settings))
                    .collect();
                if let Some((j, Err(detail))) = stepped
                    .into_iter()
                    .enumerate()
                    .find(|(_, result)| result.is_err())
                {
                    return Ok(Err(Diverged {
                        segment: Some(j),
                        detail,
                    }));
                }
                Ok(Ok(segments.iter().map(|s| s.state(*pitch_m)).collect()))
            }
            #[cfg(feature = "rigid-chain")]
            Cable::RigidChain {
                world,
                zone_sub_segments,
                pitch_m,
            } => {
                world
                    .move_guides(guides)
                    .and_then(|()| world.move_robot(links))
                    .map_err(MotionTestError::Dynamics)?;
                let record = match world.step() {
                    Ok(record) => record,
                    Err(e @ RigidChainError::BlowUp { segment, .. }) => {
                        return Ok(Err(Diverged {
                            segment: Some(segment),
                            detail: e.to_string(),
                        }));
                    }
                    Err(e) => return Err(MotionTestError::Dynamics(e)),
                };
                Ok(Ok(record
                    .segments
                    .iter()
                    .enumerate()
                    .map(|(j, rec)| {
                        let nodes = world.segment_nodes(j).unwrap_or_default();
                        SegmentState {
                            pitch_m: *pitch_m,
                            from: None,
                            slid: None,
                            contact: force_outside_zones(&rec.contact, *zone_sub_segments),
                            max_joint_gap_m: rec.max_joint_gap_m,
                            nodes,
                            twist_rad: None,
                        }
                    })
                    .collect()))
            }
        }
    }
}

#[cfg(feature = "rigid-chain")]
/// The rapier world of the initial shapes, with each segment's clamp zones exempt from
/// contact with the links their guides sit on.
fn rigid_world(
    setup: &Setup,
    settings: &crate::rigid_chain::DynamicsSettings,
    guides: &[Pose],
    shapes: &[Equilibrium],
    zones: &[Vec<ClampZone>],
) -> Result<CableWorld, RigidChainError> {
    let segment_shapes: Vec<SegmentShape> = shapes
        .iter()
        .enumerate()
        .map(|(j, eq)| SegmentShape {
            start_guide: guides[j],
            end_guide: guides[j + 1],
            nodes: &eq.nodes,
            frames: &eq.frames,
        })
        .collect();
    let mut world = CableWorld::new(&setup.cable, &segment_shapes, settings)?;
    for (j, (zones, eq)) in zones.iter().zip(shapes).enumerate() {
        let sub_segments = eq.nodes.len() - 1;
        for zone in zones {
            let n = zone.sub_segments.min(sub_segments);
            let range = match zone.end {
                GuideEnd::Start => 0..n,
                GuideEnd::End => sub_segments - n..sub_segments,
            };
            world.ignore_contacts(j, range, zone.link)?;
        }
    }
    Ok(world)
}

#[cfg(feature = "rigid-chain")]
/// The sub-segment with the largest contact force among those outside the first and last
/// `zone_sub_segments`; `None` without any force there. Inside a
/// zone the cable legitimately touches its guide's link, and the summary does not say which
/// link a force comes from (only for the most loaded sub-segment), so zones are left out
/// whole; the clearance still checks them against the other links.
fn force_outside_zones(contact: &ContactSummary, zone_sub_segments: usize) -> Option<ForceAt> {
    let forces = &contact.per_sub_segment_n;
    let (first, last) = (
        zone_sub_segments,
        forces.len().saturating_sub(zone_sub_segments),
    );
    let (sub_segment, force_n) = (first..last)
        .filter_map(|k| forces.get(k).map(|&f| (k, f)))
        .filter(|&(_, f)| f > 0.0)
        .fold(None, |best: Option<(usize, f64)>, (k, f)| match best {
            Some((_, largest)) if largest >= f => best,
            _ => Some((k, f)),
        })?;
    let link = contact
        .max
        .filter(|m| m.sub_segment == sub_segment)
        .map(|m| m.link);
    Some(ForceAt {
        sub_segment,
        force_n,
        link,
    })
}
