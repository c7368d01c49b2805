//! What one step measures: contact forces, stretch and bend radius per segment.

use rapier3d::prelude::{ContactPair, PhysicsWorld, RigidBodyHandle};

use super::build::{CABLE_TAG, ROBOT_TAG};
use super::settings::DynamicsSettings;
use crate::stress::BendRadius;

/// Measurements after one step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRecord {
    /// Simulated time at the end of the step (s).
    pub time_s: f64,
    /// One record per segment, in cable order.
    pub segments: Vec<SegmentRecord>,
}

/// Measurements of one segment after a step.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentRecord {
    /// Contact forces between its sub-segments and the robot's links.
    pub contact: ContactSummary,
    /// [`stretch`](crate::stress::stretch) of the segment's nodes (1 = natural length).
    pub stretch: f64,
    /// [`min_bend_radius`](crate::stress::min_bend_radius) of the nodes, guide axes included.
    pub min_bend: BendRadius,
    /// Largest distance between the two anchors of a joint, guide joints included (m): the
    /// solver's constraint error, ≈ 0.1 mm at the presets' substep (it grows like the
    /// substep squared, see [`DynamicsSettings`](super::DynamicsSettings)).
    pub max_joint_gap_m: f64,
}

/// Contact forces of one segment with the robot during a step.
///
/// A contact force is the normal contact impulse the solver applied over the step divided by
/// the step length (N); friction is not included.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSummary {
    /// Force on each sub-segment, summed over all robot colliders (N), `S` entries.
    pub per_sub_segment_n: Vec<f64>,
    /// Sum over the segment (N).
    pub total_n: f64,
    /// The sub-segment with the largest force, if any force is non-zero.
    pub max: Option<SubSegmentContact>,
}

/// The most loaded sub-segment of a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SubSegmentContact {
    /// Sub-segment index (0 at the start guide).
    pub sub_segment: usize,
    /// Force on it, summed over all robot colliders (N).
    pub force_n: f64,
    /// Index into `robot.links` of the link pushing it hardest.
    pub link: usize,
}

/// Contact forces gathered from the narrow phase after a step.
pub(super) struct ContactTally {
    /// Per segment, per sub-segment.
    forces: Vec<Vec<Tally>>,
}

/// The contact force on one sub-segment.
#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    /// Sum over robot colliders (N).
    force_n: f64,
    /// The link of the largest single contact pair and that pair's force (N).
    strongest: Option<(usize, f64)>,
}

impl ContactTally {
    /// Sums, per sub-segment, the normal impulses of its contact pairs with robot colliders.
    pub fn collect(
        world: &PhysicsWorld,
        segments: &[Vec<RigidBodyHandle>],
        settings: &DynamicsSettings,
    ) -> Self {
        let mut forces: Vec<Vec<Tally>> = segments
            .iter()
            .map(|b| vec![Tally::default(); b.len()])
            .collect();
        let tag = |handle| world.colliders.get(handle).map(|c| c.user_data);
        for pair in world.narrow_phase.contact_pairs() {
            let (Some(a), Some(b)) = (tag(pair.collider1), tag(pair.collider2)) else {
                continue;
            };
            let (cable, link) = match (decode(a), decode(b)) {
                (Tagged::Cable(m, s), Tagged::Link(i)) | (Tagged::Link(i), Tagged::Cable(m, s)) => {
                    ((m, s), i)
                }
                _ => continue,
            };
            let force = touching_impulse(pair) / settings.time_step_s;
            let Some(entry) = forces.get_mut(cable.0).and_then(|f| f.get_mut(cable.1)) else {
                continue;
            };
            if force > 0.0 {
                entry.force_n += force;
                if entry.strongest.is_none_or(|(_, largest)| force > largest) {
                    entry.strongest = Some((link, force));
                }
            }
        }
        Self { forces }
    }

    /// The contact summary of segment `m`.
    pub fn segment(&self, m: usize) -> ContactSummary {
        let forces = self.forces.get(m).map(Vec::as_slice).unwrap_or_default();
        let per_sub_segment_n: Vec<f64> = forces.iter().map(|f| f.force_n).collect();
        let max = forces
            .iter()
            .enumerate()
            .filter_map(|(s, f)| f.strongest.map(|(link, _)| (s, f.force_n, link)))
            .fold(None, |best: Option<SubSegmentContact>, (s, force, link)| {
                if best.is_none_or(|b| force > b.force_n) {
                    Some(SubSegmentContact {
                        sub_segment: s,
                        force_n: force,
                        link,
                    })
                } else {
                    best
                }
            });
        ContactSummary {
            total_n: per_sub_segment_n.iter().sum(),
            per_sub_segment_n,
            max,
        }
    }
}

/// Largest gap (m) at which a contact point's impulse counts as contact. Rapier also pushes
/// pairs that are still apart (speculative contacts, and impulses warm-started from earlier
/// steps): measured 0.3–2.5 N on cable sub-segments 3.5–19.6 mm from a link sliding past.
/// Those are solver predictions, not touching; a cable pressed onto a link stays within
/// −0.25…+0.43 mm of it.
const CONTACT_GAP_M: f64 = 1e-3;

/// Sum of the normal impulses of the pair's solver contact points within [`CONTACT_GAP_M`].
fn touching_impulse(pair: &ContactPair) -> f64 {
    pair.solver_manifolds()
        .iter()
        .flat_map(|manifold| &manifold.points)
        .filter(|point| f64::from(point.dist) <= CONTACT_GAP_M)
        .map(|point| f64::from(point.data.impulse))
        .sum()
}

/// What a collider's `user_data` says it is.
enum Tagged {
    /// Sub-segment `s` of segment `m`.
    Cable(usize, usize),
    /// A collider of robot link `i`.
    Link(usize),
    /// Not ours.
    Other,
}

fn decode(user_data: u128) -> Tagged {
    let low = user_data & u128::from(u64::MAX);
    let index = |v: u128| usize::try_from(v).unwrap_or(usize::MAX);
    match user_data & !u128::from(u64::MAX) {
        CABLE_TAG => Tagged::Cable(index(low >> 32), index(low & 0xffff_ffff)),
        ROBOT_TAG => Tagged::Link(index(low)),
        _ => Tagged::Other,
    }
}
