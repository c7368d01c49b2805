//! Clamp catalogues: every place a setup offers a clamp on each link, gathered from all the
//! guides on that link. A dictionary stores every ordered pair of one link's clamps, so any
//! setup whose intra-link guides draw their configurations from the catalogue — the same
//! robot and cable, any subset of places, any guide count — can use it.

use crate::pose::Pose;
use crate::setup::{Guide, GuideConfiguration, GuideKind, PoseIndex, Setup};
use std::collections::BTreeSet;

/// The clamp places of one link, as a setup the attachment test can solve.
#[derive(Debug, Clone)]
pub struct LinkCatalogue {
    /// Index into `robot.links` of the link the clamps move with.
    pub body: usize,
    /// The build setup reduced to one intra-link segment between two guides on `body` that
    /// both offer every place of the catalogue (poses in the link's frame, named
    /// `G2/site 3 …`; guides in setup order, their configurations in theirs, places seen
    /// before skipped), its lengths the catalogue's candidate lengths: what the evaluator
    /// solves, with the build setup's robot, cable, gravity, limits and installation pose.
    pub setup: Setup,
}

impl LinkCatalogue {
    /// The clamp places, in the order the dictionary indexes them.
    pub fn clamps(&self) -> &[GuideConfiguration] {
        &self.setup.guides[0].configurations
    }
}

/// The catalogue of every link of `setup` with two or more distinct clamp places, in link
/// order, each with `candidate_lengths` (sub-segments, ascending).
pub fn link_catalogues(setup: &Setup, candidate_lengths: &[usize]) -> Vec<LinkCatalogue> {
    let bodies: BTreeSet<usize> = setup.guides.iter().map(|g| g.body).collect();
    bodies
        .into_iter()
        .filter_map(|body| {
            let clamps = clamps_on(setup, body);
            (clamps.len() >= 2).then(|| LinkCatalogue {
                body,
                setup: as_setup(setup, body, clamps, candidate_lengths),
            })
        })
        .collect()
}

/// The distinct clamp places of the guides on `body`, posed in the body's frame.
fn clamps_on(setup: &Setup, body: usize) -> Vec<GuideConfiguration> {
    let mut clamps: Vec<GuideConfiguration> = Vec::new();
    let mut places = PoseIndex::default();
    for guide in setup.guides.iter().filter(|g| g.body == body) {
        for (c, configuration) in guide.configurations.iter().enumerate() {
            let pose: Pose = guide.pose_in_body(c);
            if places.find(&pose).is_some() {
                continue;
            }
            places.insert(&pose, clamps.len());
            let name = if configuration.name.contains('/') {
                configuration.name.clone()
            } else {
                format!("{}/{}", guide.name, configuration.name)
            };
            // A dictionary answers for rigid clamps: a place, whatever part sits there.
            clamps.push(GuideConfiguration {
                name,
                pose,
                kind: GuideKind::Rigid,
                ..configuration.clone()
            });
        }
    }
    clamps
}

/// `setup` with two guides on `body`, each offering every place of `clamps`, and one
/// intra-link segment between them.
fn as_setup(
    setup: &Setup,
    body: usize,
    clamps: Vec<GuideConfiguration>,
    lengths: &[usize],
) -> Setup {
    let guide = |name: &str| Guide {
        name: name.into(),
        link: body,
        body,
        link_in_body: Pose::identity(),
        fixed: false,
        optional: false,
        configurations: clamps.clone(),
        kinds: vec![GuideKind::Rigid],
        generated: None,
    };
    let mut catalogue = setup.clone();
    catalogue.guides = vec![guide("from"), guide("to")];
    let mut segment = setup.segments[0].clone();
    segment.guides = (0, 1);
    segment.lengths = lengths.to_vec();
    segment.intra_link = true;
    catalogue.segments = vec![segment];
    catalogue.declared_segments = 1;
    catalogue
}
