//! The motion test's worst moment, as the report shows it: where it failed, else the smallest
//! margin to a limit relative to the limit's scale. One rule for the worst-moment picture and
//! the 3D view's marked moment.

use crate::motion_test::{Constraint, MotionTestReport};
use crate::setup::Thresholds;

/// The motion test's instant with the smallest margin to a limit, and where.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct SmallestMargin {
    pub constraint: Constraint,
    /// In the limit's unit (m, N or a ratio).
    pub value: f64,
    pub limit: f64,
    pub time_s: f64,
    /// Index of the cable piece (C1 = 0).
    pub segment: usize,
    pub position_m: Option<[f64; 3]>,
    /// The test failed here (its first violation).
    pub violated: bool,
}

/// Where the motion test failed; else the worst of clearance, stretch, each piece's bend
/// radius and the twist, each relative to its limit as the diagnosis ranks its nearest
/// misses (clearance over the cable's diameter, stretch over the allowed excess, bend radius
/// over the radius the piece keeps, twist over the torsion limit).
/// `None` when nothing was measured.
pub(super) fn smallest_margin(
    test: &MotionTestReport,
    limits: &Thresholds,
    cable_diameter_m: f64,
) -> Option<SmallestMargin> {
    if let Some(v) = &test.first_violation {
        return Some(SmallestMargin {
            constraint: v.constraint,
            value: v.value,
            limit: v.threshold,
            time_s: v.time_s,
            segment: v.segment,
            position_m: v.place.position_m,
            violated: true,
        });
    }
    let mut worst = vec![
        (
            Constraint::Contact,
            &test.worst_clearance,
            limits.contact_clearance_m,
        ),
        (Constraint::Stretch, &test.worst_stretch, limits.stretch),
    ];
    // Each piece's bend against the radius it had to keep (flexing or fixed).
    for piece in &test.pieces {
        let constraint = if piece.flexes {
            Constraint::FlexingBendRadius
        } else {
            Constraint::BendRadius
        };
        worst.push((constraint, &piece.worst_bend, piece.bend_radius_limit_m));
    }
    if test.pieces.is_empty() {
        worst.push((
            Constraint::BendRadius,
            &test.worst_bend,
            limits.min_bend_radius_m,
        ));
    }
    if let Some(limit) = limits.torsion_limit_deg_per_m {
        worst.push((Constraint::Twist, &test.worst_twist, limit));
    }
    worst
        .into_iter()
        .filter_map(|(constraint, worst, limit)| {
            let w = worst.as_ref()?;
            let relative = match constraint {
                Constraint::Contact => (w.value - limit) / cable_diameter_m,
                Constraint::Stretch => (limit - w.value) / (limit - 1.0).max(1e-12),
                Constraint::Twist => (limit - w.value) / limit,
                _ => (w.value - limit) / limit,
            };
            let margin = SmallestMargin {
                constraint,
                value: w.value,
                limit,
                time_s: w.time_s,
                segment: w.segment,
                position_m: w.place.position_m,
                violated: false,
            };
            Some((relative, margin))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, margin)| margin)
}

/// `clearance to the robot 5.4 mm (limit 0.0 mm)`.
pub(super) fn limit_words(constraint: Constraint, value: f64, limit: f64) -> String {
    match constraint {
        Constraint::Contact => format!(
            "clearance to the robot {} (limit {})",
            millimetres(value),
            millimetres(limit)
        ),
        Constraint::ContactForce => format!("contact force on the robot {value:.2} N (limit 0 N)"),
        Constraint::Stretch => format!("stretch {value:.4} (limit {limit:.4})"),
        Constraint::BendRadius => format!(
            "bend radius {} (limit {})",
            millimetres(value),
            millimetres(limit)
        ),
        Constraint::FlexingBendRadius => format!(
            "bend radius {} of a flexing piece (flexing limit {})",
            millimetres(value),
            millimetres(limit)
        ),
        Constraint::Twist => format!("twist {value:.0}°/m (limit ±{limit:.0}°/m)"),
        Constraint::SelfContact => format!(
            "clearance of the cable to itself {} (limit {})",
            millimetres(value),
            millimetres(limit)
        ),
        Constraint::Travel => format!(
            "a retraction out of travel: the cable pulls {value:.2} N more than its spring at \
             the end stop (limit {limit:.2} N)"
        ),
    }
}

/// `length_m` in mm to 0.1 mm, or to 0.01 mm when that would show a nonzero value as 0.0
/// (a contact 0.03 mm deep).
fn millimetres(length_m: f64) -> String {
    let mm = length_m * 1e3;
    if mm != 0.0 && mm.abs() < 0.05 {
        format!("{mm:.2} mm")
    } else {
        format!("{mm:.1} mm")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_smallest_margin_is_relative_to_each_limit() {
        use crate::motion_test::{Place, Worst};
        let worst = |value: f64, time_s: f64, segment: usize| Worst {
            value,
            unit: "m",
            time_s,
            segment,
            segment_name: format!("C{}", segment + 1),
            place: Place::default(),
        };
        let limits = Thresholds {
            contact_clearance_m: 0.0,
            stretch: 1.02,
            min_bend_radius_m: 0.048,
            min_bend_radius_source: crate::setup::BendRadiusSource::Cable,
            clamp_zone_m: 0.02,
            static_bend_margin_m: 0.0,
            cable_flexing_bend_radius_m: None,
            torsion_limit_deg_per_m: None,
            flexing_curvature_change_per_m: 1.0,
        };
        // Clearance 4 mm of an 8 mm cable: 0.5. Stretch 1.015: 0.25 of the allowed 0.02 left.
        // Bend 62 mm against 48 mm: 0.29.
        let mut test = MotionTestReport {
            passed: true,
            failure: None,
            first_violation: None,
            worst_clearance: Some(worst(0.004, 1.0, 0)),
            worst_stretch: Some(worst(1.015, 2.0, 1)),
            worst_bend: Some(worst(0.062, 3.0, 2)),
            worst_twist: None,
            worst_contact_force: None,
            worst_self_clearance: None,
            pieces: Vec::new(),
            twists: Vec::new(),
            damage: Vec::new(),
            clamp_loads: Vec::new(),
            clamp_turns: Vec::new(),
            slides: Vec::new(),
            max_joint_gap_m: 0.0,
            series: Vec::new(),
            final_shape: Vec::new(),
            shapes: Vec::new(),
            motion_duration_s: 4.0,
            steps: 960,
            simulated_s: 4.0,
            wall_time_s: 0.0,
        };
        let found = smallest_margin(&test, &limits, 0.008).expect("a margin");
        assert_eq!((found.constraint, found.time_s), (Constraint::Stretch, 2.0));
        test.worst_bend = Some(worst(0.050, 3.0, 2));
        let found = smallest_margin(&test, &limits, 0.008).expect("a margin");
        assert_eq!(
            (found.constraint, found.segment),
            (Constraint::BendRadius, 2)
        );
        assert!(!found.violated);
        // A failed test is drawn where it failed, whatever the worst values were.
        test.first_violation = Some(crate::motion_test::Violation {
            constraint: Constraint::Contact,
            value: -0.001,
            threshold: 0.0,
            unit: "m",
            time_s: 1.5,
            segment: 1,
            segment_name: "C2".into(),
            place: Place::default(),
        });
        let found = smallest_margin(&test, &limits, 0.008).expect("a margin");
        assert_eq!((found.constraint, found.time_s), (Constraint::Contact, 1.5));
        assert!(found.violated);
    }
}
