//! What a failed motion test teaches the search: how far the cable of a segment swings past
//! its static shapes.
//!
//! A chain fails the motion test where one of its pieces bends tighter, or comes closer to
//! the robot, than the limit allows, while the same piece held the limit at every pose of the
//! static sweep: the cable swung. The difference between the piece's least static value
//! over the motion and the simulated value at the failure is its *swing*. A piece of the
//! same clamp pair (the same loop, a few centimetres longer or shorter) swings about as far,
//! and so does, less surely, another loop of the same segment. Before a chain goes to the
//! motion test, each of its pieces must keep its least static value at least a swing inside
//! the limit: the pair's own swing where one was measured, else the smallest swing measured
//! in its segment. A piece that does not is *set aside*, not dropped: when no chain is left
//! without the pieces set aside, they all come back and the search goes on without learned
//! margins, so that a path the motion test would pass is never ruled out by a guess — only
//! tried later ([`Learned`]).
//!
//! A loop that swings into another part of the cable teaches no number: the static sweep
//! solves pieces alone and knows no distance between two of them. Its clamp pair is marked
//! instead, and the pair's other lengths are set aside the same way, so that the budget goes
//! to other clamp places before it comes back to lengths of a loop seen touching.

use crate::attachment::SweptLeast;
use crate::motion_test::{Constraint, Violation};
use crate::path::Pv;
use crate::setup::Thresholds;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// How far a cable swung past its static shapes, per limit (m); `None`: not measured.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Swing {
    /// Bend radius lost (m).
    pub bend_radius_m: Option<f64>,
    /// Clearance to the robot lost (m).
    pub clearance_m: Option<f64>,
}

impl Swing {
    /// The larger of each limit's swing (`pick` = max) or the smaller (`pick` = min).
    fn merge(&mut self, other: &Swing, pick: fn(f64, f64) -> f64) {
        let merge = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => Some(pick(a, b)),
            (a, b) => a.or(b),
        };
        self.bend_radius_m = merge(self.bend_radius_m, other.bend_radius_m);
        self.clearance_m = merge(self.clearance_m, other.clearance_m);
    }
}

/// A piece set aside by a learned margin, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct SetAside {
    /// The segment (C1 = 0).
    pub segment: usize,
    /// The piece.
    pub pv: Pv,
    /// For people: the least static value, the margin and where it was learned.
    pub why: String,
}

/// The swings learned from the failed motion tests so far.
#[derive(Debug, Default)]
pub struct Learned {
    /// Per segment and clamp pair `(segment, start, end)`: the largest swing measured.
    pairs: BTreeMap<(usize, usize, usize), Swing>,
    /// Per segment: the smallest swing measured on any of its pairs.
    segments: BTreeMap<usize, Swing>,
    /// Clamp pairs `(segment, start, end)` one of whose pieces touched another part of the
    /// cable in a motion test.
    touched: BTreeSet<(usize, usize, usize)>,
}

impl Learned {
    /// Learns from a motion test that failed with `violation` in piece `pv` of segment `m`,
    /// whose static shapes over the motion had the least values `least`. Only the bend
    /// radius and the clearance to the robot teach a swing; a self-contact marks the clamp
    /// pair; the other limits teach nothing.
    pub fn learn(&mut self, m: usize, pv: &Pv, violation: &Violation, least: &SweptLeast) {
        if violation.constraint == Constraint::SelfContact {
            self.touched.insert((m, pv.start, pv.end));
            return;
        }
        let swing = match violation.constraint {
            // A flexing piece swings as any other: its swing is the same dynamics.
            Constraint::BendRadius | Constraint::FlexingBendRadius => Swing {
                bend_radius_m: Some(least.bend_radius_m - violation.value),
                clearance_m: None,
            },
            Constraint::Contact => Swing {
                bend_radius_m: None,
                clearance_m: least.clearance_m.map(|c| c - violation.value),
            },
            _ => return,
        };
        // A static value below the simulated one teaches nothing (the sweep missed it).
        let positive = |v: Option<f64>| v.filter(|v| v.is_finite() && *v > 0.0);
        let swing = Swing {
            bend_radius_m: positive(swing.bend_radius_m),
            clearance_m: positive(swing.clearance_m),
        };
        if swing == Swing::default() {
            return;
        }
        (self.pairs.entry((m, pv.start, pv.end)).or_default()).merge(&swing, f64::max);
        match self.segments.get_mut(&m) {
            Some(known) => known.merge(&swing, f64::min),
            None => {
                self.segments.insert(m, swing);
            }
        }
    }

    /// The swing piece `pv` of segment `m` must keep inside the limits: its pair's, else
    /// its segment's (each limit on its own).
    fn swing(&self, m: usize, pv: &Pv) -> Swing {
        let mut swing = self.segments.get(&m).copied().unwrap_or_default();
        if let Some(pair) = self.pairs.get(&(m, pv.start, pv.end)) {
            swing.bend_radius_m = pair.bend_radius_m.or(swing.bend_radius_m);
            swing.clearance_m = pair.clearance_m.or(swing.clearance_m);
        }
        swing
    }

    /// Why piece `pv` of segment `m`, whose static shapes over the motion had the least
    /// values `least`, would likely fail the motion test as measured pieces did; `None` when
    /// it keeps every learned swing inside the limits `thresholds`.
    pub fn doubt(
        &self,
        m: usize,
        pv: &Pv,
        least: &SweptLeast,
        thresholds: &Thresholds,
    ) -> Option<String> {
        if self.touched.contains(&(m, pv.start, pv.end)) {
            return Some(
                "a loop of its clamp pair swung into another part of the cable in a motion test"
                    .into(),
            );
        }
        // The same limits a sweep stops below ([`Learned::needed`]), compared the same way;
        // a piece that flexed keeps its swing inside the flexing radius.
        let needed = self.needed(m, pv, thresholds)?;
        let limit = thresholds.bend_radius_for(least.flexes, false);
        let mm = |v: f64| v * 1e3;
        if let Some(swing) = self.swing(m, pv).bend_radius_m
            && least.bend_radius_m < limit + swing
        {
            return Some(format!(
                "its static bend radius {:.2} mm is within the {:.2} mm its loop swung below the \
                 static one in a motion test ({} {:.1} mm)",
                mm(least.bend_radius_m),
                mm(swing),
                if least.flexes {
                    "flexing limit"
                } else {
                    "limit"
                },
                mm(limit)
            ));
        }
        if let (Some(clearance), Some(limit)) = (least.clearance_m, needed.clearance_m)
            && clearance < limit
        {
            return Some(format!(
                "its static clearance {:.2} mm is within the {:.2} mm its loop swung toward the \
                 robot in a motion test (limit {:.1} mm)",
                mm(clearance),
                mm(limit - thresholds.contact_clearance_m),
                mm(thresholds.contact_clearance_m)
            ));
        }
        None
    }

    /// The least values below which piece `pv` of segment `m` is doubted ([`Learned::doubt`]):
    /// the limits plus its swing; `None` when nothing was learned for it. A sweep may stop as
    /// soon as a value falls below them.
    pub fn needed(&self, m: usize, pv: &Pv, thresholds: &Thresholds) -> Option<SweptLeast> {
        if self.touched.contains(&(m, pv.start, pv.end)) {
            // Set aside whatever its static shapes: its sweep can stop at the first pose.
            return Some(SweptLeast::NONE);
        }
        let swing = self.swing(m, pv);
        if swing == Swing::default() {
            return None;
        }
        Some(SweptLeast {
            bend_radius_m: swing
                .bend_radius_m
                .map_or(f64::NEG_INFINITY, |s| thresholds.min_bend_radius_m + s),
            clearance_m: swing
                .clearance_m
                .map(|s| thresholds.contact_clearance_m + s),
            flexes: false,
        })
    }

    /// How many clamp pairs had a piece touch another part of the cable in a motion test.
    pub fn touched_pairs(&self) -> usize {
        self.touched.len()
    }

    /// The swings learned per segment (the smallest over its pairs), in segment order.
    pub fn by_segment(&self) -> impl Iterator<Item = (usize, &Swing)> {
        self.segments.iter().map(|(&m, swing)| (m, swing))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion_test::Place;

    fn violation(constraint: Constraint, value_m: f64, segment: usize) -> Violation {
        Violation {
            constraint,
            value: value_m,
            threshold: 0.0,
            unit: "m",
            time_s: 0.0,
            segment,
            segment_name: format!("C{}", segment + 1),
            place: Place::default(),
        }
    }

    fn least(bend_radius_m: f64, clearance_m: Option<f64>) -> SweptLeast {
        SweptLeast {
            bend_radius_m,
            clearance_m,
            flexes: false,
        }
    }

    fn pv(sub_segments: usize, start: usize, end: usize) -> Pv {
        Pv {
            sub_segments,
            start,
            end,
        }
    }

    fn thresholds() -> Thresholds {
        Thresholds {
            contact_clearance_m: 0.0,
            stretch: 1.02,
            min_bend_radius_m: 0.048,
            min_bend_radius_source: crate::setup::BendRadiusSource::Setup,
            clamp_zone_m: 0.02,
            static_bend_margin_m: 0.0,
            cable_flexing_bend_radius_m: None,
            torsion_limit_deg_per_m: None,
            flexing_curvature_change_per_m: 1.0,
        }
    }

    #[test]
    fn a_swing_is_the_static_least_minus_the_simulated_value_and_sets_aside_what_keeps_less() {
        let mut learned = Learned::default();
        let t = thresholds();
        // A loop of pair (0, 1) held 48.5 mm at rest and bent to 47.8 mm: it swung 0.7 mm.
        let failed = pv(30, 0, 1);
        learned.learn(
            0,
            &failed,
            &violation(Constraint::BendRadius, 0.0478, 0),
            &least(0.0485, None),
        );
        let swing = learned
            .swing(0, &pv(31, 0, 1))
            .bend_radius_m
            .expect("learned");
        assert!((swing - 0.0007).abs() < 1e-12);
        // Its neighbour 10 mm longer at 48.6 mm keeps less than 48 + 0.7: set aside; one at
        // 48.8 mm keeps more: tried.
        assert!(
            learned
                .doubt(0, &pv(31, 0, 1), &least(0.0486, None), &t)
                .is_some()
        );
        assert!(
            learned
                .doubt(0, &pv(32, 0, 1), &least(0.0488, None), &t)
                .is_none()
        );
        // Another segment learned nothing; a clearance is not judged by a bend swing.
        assert!(
            learned
                .doubt(1, &pv(31, 0, 1), &least(0.0481, None), &t)
                .is_none()
        );
        assert!(learned.swing(0, &failed).clearance_m.is_none());
    }

    #[test]
    fn a_piece_that_flexed_keeps_its_swing_inside_the_flexing_radius() {
        let mut learned = Learned::default();
        let t = Thresholds {
            cable_flexing_bend_radius_m: Some(0.080),
            ..thresholds()
        };
        // A flexing loop held 80.3 mm at rest and bent to 79.9 mm: it swung 0.4 mm.
        let flexing = |bend_radius_m| SweptLeast {
            flexes: true,
            ..least(bend_radius_m, None)
        };
        let violation = violation(Constraint::FlexingBendRadius, 0.0799, 0);
        learned.learn(0, &pv(30, 0, 1), &violation, &flexing(0.0803));
        // A neighbour that flexes at 80.2 mm keeps less than 80 + 0.4: set aside; at 80.5 mm
        // it keeps more. The same 80.2 mm in a piece that does not flex is far from its
        // fixed 48 mm: tried.
        assert!((learned.doubt(0, &pv(31, 0, 1), &flexing(0.0802), &t)).is_some());
        assert!((learned.doubt(0, &pv(31, 0, 1), &flexing(0.0805), &t)).is_none());
        assert!((learned.doubt(0, &pv(31, 0, 1), &least(0.0802, None), &t)).is_none());
    }

    #[test]
    fn a_pair_keeps_its_largest_swing_and_the_segment_its_smallest() {
        let mut learned = Learned::default();
        let bend = |v| violation(Constraint::BendRadius, v, 2);
        learned.learn(2, &pv(40, 3, 4), &bend(0.0479), &least(0.0484, None)); // 0.5 mm
        learned.learn(2, &pv(42, 3, 4), &bend(0.0475), &least(0.0490, None)); // 1.5 mm
        learned.learn(2, &pv(50, 5, 6), &bend(0.0479), &least(0.0481, None)); // 0.2 mm
        let close = |a: Option<f64>, b: f64| (a.expect("learned") - b).abs() < 1e-12;
        assert!(close(learned.swing(2, &pv(44, 3, 4)).bend_radius_m, 0.0015));
        assert!(close(learned.swing(2, &pv(50, 5, 6)).bend_radius_m, 0.0002));
        // A pair never measured takes the segment's smallest swing.
        assert!(close(learned.swing(2, &pv(45, 7, 8)).bend_radius_m, 0.0002));
        let segments: Vec<(usize, Swing)> = learned.by_segment().map(|(m, s)| (m, *s)).collect();
        assert_eq!(segments.len(), 1);
        assert!(close(segments[0].1.bend_radius_m, 0.0002));
    }

    #[test]
    fn a_contact_failure_teaches_a_clearance_swing_and_other_limits_teach_nothing() {
        let mut learned = Learned::default();
        let t = thresholds();
        let piece = pv(20, 0, 0);
        // Clear by 3 mm at rest, 0.5 mm into the robot in motion: 3.5 mm.
        learned.learn(
            0,
            &piece,
            &violation(Constraint::Contact, -0.0005, 0),
            &least(0.06, Some(0.003)),
        );
        assert!(
            learned
                .doubt(0, &pv(21, 0, 0), &least(0.06, Some(0.0034)), &t)
                .is_some()
        );
        assert!(
            learned
                .doubt(0, &pv(22, 0, 0), &least(0.06, Some(0.0036)), &t)
                .is_none()
        );
        // Stretch failures, self-contact failures and a static value below the simulated
        // one (the sweep missed it) teach no swing.
        let mut other = Learned::default();
        other.learn(
            0,
            &piece,
            &violation(Constraint::Stretch, 1.03, 0),
            &least(0.05, Some(0.01)),
        );
        other.learn(
            0,
            &piece,
            &violation(Constraint::SelfContact, -0.001, 0),
            &least(0.05, None),
        );
        other.learn(
            0,
            &piece,
            &violation(Constraint::BendRadius, 0.0479, 0),
            &least(0.0470, None),
        );
        assert_eq!(other.by_segment().count(), 0);
    }

    #[test]
    fn a_loop_that_touched_the_cable_sets_aside_its_pair_and_no_other() {
        let mut learned = Learned::default();
        let t = thresholds();
        learned.learn(
            0,
            &pv(40, 2, 3),
            &violation(Constraint::SelfContact, -0.0001, 0),
            &least(0.06, Some(0.01)),
        );
        assert_eq!(learned.touched_pairs(), 1);
        // Every length of that pair, whatever its static values; its sweep need not go on.
        let far = least(1.0, Some(1.0));
        assert!(learned.doubt(0, &pv(44, 2, 3), &far, &t).is_some());
        let needed = learned.needed(0, &pv(44, 2, 3), &t).expect("needed");
        assert!(needed.bend_radius_m > 1.0);
        // Another pair of the segment, and the same pair in another segment: tried.
        assert!(learned.doubt(0, &pv(40, 2, 4), &far, &t).is_none());
        assert!(learned.doubt(1, &pv(40, 2, 3), &far, &t).is_none());
        assert!(learned.needed(0, &pv(40, 2, 4), &t).is_none());
    }
}
