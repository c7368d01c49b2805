//! The static margins of the answer: each piece re-solved at its test poses.

use super::data::Margin;
use crate::attachment::{Evaluator, Metrics, SegmentPoses, TestPose};
use crate::path::CablePath;

/// A limit's name, threshold, value in the metrics, and sign (+1: the value must stay above
/// the threshold, −1: below).
type LimitOf = (&'static str, f64, fn(&Metrics) -> Option<f64>, f64);

/// The smallest margin of each limit over the test poses, for every segment with a cable.
pub(super) fn margins(
    evaluator: &Evaluator<'_>,
    poses: &SegmentPoses,
    path: &CablePath,
) -> Vec<Margin> {
    let setup = evaluator.setup();
    let limits = &setup.thresholds;
    let mut margins = Vec::new();
    for (m, pv) in path.pieces() {
        let checked: Vec<(&TestPose, Metrics)> = poses.poses[m]
            .iter()
            .filter_map(|pose| Some((pose, evaluator.check(m, &pv, pose).metrics?)))
            .collect();
        let limits_of: [LimitOf; 3] = [
            (
                "contact",
                limits.contact_clearance_m,
                |x| x.clearance_m,
                1.0,
            ),
            ("stretch", limits.stretch, |x| Some(x.stretch), -1.0),
            (
                "bend_radius",
                limits.min_bend_radius_m,
                |x| Some(x.min_bend_radius_m).filter(|r| r.is_finite()),
                1.0,
            ),
        ];
        for (constraint, threshold, value_of, sign) in limits_of {
            let binding = checked
                .iter()
                .filter_map(|(pose, metrics)| {
                    value_of(metrics).map(|v| (pose, v, sign * (v - threshold)))
                })
                .min_by(|a, b| a.2.total_cmp(&b.2));
            if let Some((pose, value, margin)) = binding {
                margins.push(Margin {
                    segment: setup.segment_name(m),
                    constraint,
                    value,
                    threshold,
                    margin,
                    sample: pose.sample,
                    time_s: pose.time_s,
                    reason: pose.reason.clone(),
                });
            }
        }
    }
    margins
}
