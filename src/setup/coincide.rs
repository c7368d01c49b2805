//! Coincident copies: the configurations added so that S = 0 (two guides at one place) can be
//! expressed as a pair of configurations with equal poses. The rule is stated in the module
//! documentation of [`super`].

use super::guides::PoseIndex;
use super::{ConfigurationOrigin, Guide, GuideConfiguration, SegmentSpec};

/// Adds the coincident copies for every intra-link segment that allows S = 0: first from the
/// base end to the tool end (Gm's configurations into a movable G(m+1)), then back (the
/// configurations that come from a fixed guide, from G(m+1) into a movable Gm).
pub(super) fn add_copies(guides: &mut [Guide], segments: &[SegmentSpec]) {
    let zero = |m: usize| segments[m].intra_link && segments[m].range.allow_zero;
    for m in 0..segments.len() {
        if zero(m) && !guides[m + 1].fixed {
            copy(guides, m, m + 1, false);
        }
    }
    for m in (0..segments.len()).rev() {
        if zero(m) && !guides[m].fixed {
            copy(guides, m + 1, m, true);
        }
    }
}

/// Copies the configurations of guide `from` into guide `to` (same body), skipping poses `to`
/// already has; with `only_from_fixed`, only those declared by a fixed guide.
fn copy(guides: &mut [Guide], from: usize, to: usize, only_from_fixed: bool) {
    let mut copies: Vec<GuideConfiguration> = Vec::new();
    let targets: Vec<_> = (0..guides[to].configurations.len())
        .map(|k| guides[to].pose_in_body(k))
        .collect();
    let mut known = PoseIndex::of(&targets);
    for c in 0..guides[from].configurations.len() {
        let (root_guide, root_configuration) = root_of(from, c, &guides[from].configurations[c]);
        let declared_by = &guides[root_guide];
        let in_body = guides[from].pose_in_body(c);
        let target = &guides[to];
        if known.find(&in_body).is_some() || (only_from_fixed && !declared_by.fixed) {
            continue;
        }
        known.insert(&in_body, target.configurations.len() + copies.len());
        let original = &declared_by.configurations[root_configuration];
        copies.push(GuideConfiguration {
            name: format!("{}/{}", declared_by.name, original.name),
            pose: target.link_in_body.inverse() * in_body,
            position_mm: original.position_mm,
            rpy_deg: original.rpy_deg,
            origin: ConfigurationOrigin::Coincident {
                guide: root_guide,
                configuration: root_configuration,
            },
            kind: original.kind,
        });
    }
    guides[to].configurations.extend(copies);
}

/// The declared or generated configuration a configuration stems from: (guide,
/// configuration).
fn root_of(g: usize, c: usize, configuration: &GuideConfiguration) -> (usize, usize) {
    match configuration.origin {
        ConfigurationOrigin::Declared { .. } | ConfigurationOrigin::Generated { .. } => (g, c),
        ConfigurationOrigin::Coincident {
            guide,
            configuration,
        } => (guide, configuration),
    }
}
