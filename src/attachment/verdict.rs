//! What one piece at one pose comes to: the limit it violates first, how far past it, and its
//! margins — the words of every verdict the attachment test, a dictionary and a diagnosis give.

use crate::cable::CableSpec;
use crate::geometry::ConnectError;
use crate::pose::Pose;
use crate::setup::{Setup, Thresholds};
use crate::stress::contact::Clearance;
use crate::stress::{min_bend_radius, self_contact_within, stretch, twist_per_length_deg_per_m};
use nalgebra::{Point3, Vector3};
use serde::Serialize;

/// How many margins a verdict has: clearance, stretch, curvature and twist.
pub const MARGIN_COUNT: usize = 4;

/// The margins of one piece at one pose, in the order of [`Margins::to_array`].
pub type MarginValues = [f64; MARGIN_COUNT];

/// The stress limit a PV violates first (in the order contact, self-contact, stretch,
/// bend, twist), or why it could not be evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Rejection {
    /// The cable is shorter than the distance between its guides.
    TooShort,
    /// The connected geometry or the static solver failed (reported, not fatal).
    Diverged,
    /// Clearance to the robot below the contact threshold.
    Contact,
    /// The cable touches or passes through itself.
    SelfContact,
    /// Centreline length / natural length above the stretch threshold.
    Stretch,
    /// Bend radius below the minimum.
    Bend,
    /// Twist per length above the cable's torsion limit.
    Twist,
}

impl Rejection {
    /// Every kind, in report order.
    pub const ALL: [Rejection; 7] = [
        Rejection::TooShort,
        Rejection::Diverged,
        Rejection::Contact,
        Rejection::SelfContact,
        Rejection::Stretch,
        Rejection::Bend,
        Rejection::Twist,
    ];

    /// Short name for people.
    pub fn name(self) -> &'static str {
        match self {
            Rejection::TooShort => "too short",
            Rejection::Diverged => "solver failed",
            Rejection::Contact => "contact",
            Rejection::SelfContact => "touches itself",
            Rejection::Stretch => "stretch",
            Rejection::Bend => "bend radius",
            Rejection::Twist => "twist",
        }
    }
}

/// How a PV failed the attachment test: which limit, how far past it, where on the cable and
/// at which test pose — what a diagnosis of "no path" ranks its nearest misses by.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Miss {
    /// The first limit violated.
    pub rejection: Rejection,
    /// How far past the limit, relative to it: contact (with the robot or itself), the
    /// clearance deficit over the cable's diameter; stretch (and a cable too short for its clamps), the excess stretch
    /// over the allowed excess; bend, the radius deficit over the minimum radius; twist, the
    /// excess twist per length over the limit. Infinite
    /// when nothing was measured (a failed solve, a verdict read from a dictionary).
    pub severity: f64,
    /// The measured value: clearance to the robot or to itself (m), stretch ratio, bend
    /// radius (m), or twist per length (deg/m, magnitude); NaN when not measured.
    pub value: f64,
    /// Index of the test pose where it failed first (in the order the poses were tried:
    /// the lazy search tries the poses that rejected most pieces first).
    pub pose: usize,
    /// Where along the piece (m of cable from its start clamp); NaN for the whole piece.
    pub at_m: f64,
}

impl Miss {
    /// A verdict without measurements (e.g. from a dictionary).
    pub fn unmeasured(rejection: Rejection) -> Miss {
        Miss {
            rejection,
            severity: f64::INFINITY,
            value: f64::NAN,
            pose: 0,
            at_m: f64::NAN,
        }
    }

    /// The miss of a limit a lookup found violated at test pose `pose`, from the looked-up
    /// margins `[clearance mm, stretch, curvature 1/m, twist deg/m]` (unmeasured without
    /// them). The place on the cable is not known.
    pub fn looked_up(
        setup: &Setup,
        rejection: Rejection,
        margins: Option<MarginValues>,
        pose: usize,
    ) -> Miss {
        let limits = &setup.thresholds;
        let unmeasured = Miss {
            pose,
            ..Miss::unmeasured(rejection)
        };
        let Some([clearance_mm, stretch, curvature, twist]) = margins else {
            return unmeasured;
        };
        let (severity, value) = match rejection {
            Rejection::Contact => (
                -clearance_mm * 1e-3 / setup.cable.diameter_m,
                limits.contact_clearance_m + clearance_mm * 1e-3,
            ),
            Rejection::Stretch => {
                let value = limits.stretch - stretch;
                (
                    (value - 1.0) / (limits.stretch - 1.0).max(1e-12) - 1.0,
                    value,
                )
            }
            Rejection::Bend => {
                let limit = limits.static_min_bend_radius_m();
                let radius = 1.0 / (1.0 / limit - curvature);
                ((limit - radius) / limit, radius)
            }
            Rejection::Twist => match limits.torsion_limit_deg_per_m {
                Some(limit) => ((-twist) / limit, limit - twist),
                None => return unmeasured,
            },
            // A looked-up clearance margin is the lower of the two clearances.
            Rejection::TooShort | Rejection::Diverged | Rejection::SelfContact => {
                return unmeasured;
            }
        };
        Miss {
            rejection,
            severity: severity.max(0.0),
            value,
            pose,
            at_m: f64::NAN,
        }
    }

    /// The miss of a failed `check` at test pose `pose`; `None` when it passed.
    pub(super) fn of(
        check: &Check,
        setup: &Setup,
        pose: usize,
        guides: &(Pose, Pose),
        sub_segments: usize,
    ) -> Option<Miss> {
        let rejection = check.rejection?;
        let limits = &setup.thresholds;
        let pitch = setup.cable.sub_segment_pitch_m;
        let excess = |stretch: f64| (stretch - 1.0) / (limits.stretch - 1.0).max(1e-12) - 1.0;
        let measured = |severity: f64, value: f64, at_m: f64| Miss {
            rejection,
            severity: severity.max(0.0),
            value,
            pose,
            at_m,
        };
        Some(match (rejection, check.metrics) {
            (Rejection::TooShort, _) => {
                let distance = (guides.1.translation.vector - guides.0.translation.vector).norm();
                let stretch = distance / (sub_segments as f64 * pitch);
                // Short of reaching at all: the stretch it would need beyond 1, over the
                // allowed excess (within the stretch limit it is still a miss, not a near hit).
                let needed = (stretch - 1.0) / (limits.stretch - 1.0).max(1e-12);
                measured(needed, stretch, f64::NAN)
            }
            (Rejection::Contact, Some(m)) => {
                let clearance = m.clearance_m.unwrap_or(f64::NAN);
                let deficit = limits.contact_clearance_m - clearance;
                let at = m
                    .clearance_sub_segment
                    .map_or(f64::NAN, |k| (f64::from(k) + 0.5) * pitch);
                measured(deficit / setup.cable.diameter_m, clearance, at)
            }
            (Rejection::SelfContact, Some(m)) => {
                let clearance = m.self_clearance_m;
                let at = (f64::from(m.self_contact_sub_segments[0]) + 0.5) * pitch;
                measured(-clearance / setup.cable.diameter_m, clearance, at)
            }
            (Rejection::Stretch, Some(m)) => measured(excess(m.stretch), m.stretch, f64::NAN),
            (Rejection::Bend, Some(m)) => {
                // A bend refused above the fixed radius was refused for flexing.
                let fixed = limits.static_min_bend_radius_m();
                let limit = match m.min_bend_radius_m >= fixed {
                    true => limits.bend_radius_for(true, true),
                    false => fixed,
                };
                let at = m.min_bend_node as f64 * pitch;
                measured(
                    (limit - m.min_bend_radius_m) / limit,
                    m.min_bend_radius_m,
                    at,
                )
            }
            (Rejection::Twist, Some(m)) => {
                let limit = limits.torsion_limit_deg_per_m.unwrap_or(f64::INFINITY);
                let twist = m.twist_deg_per_m.abs();
                measured((twist - limit) / limit, twist, f64::NAN)
            }
            _ => Miss {
                pose,
                ..Miss::unmeasured(rejection)
            },
        })
    }
}

/// The stress metrics of one equilibrium shape.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Metrics {
    /// Lowest signed clearance to the robot (m), clamp zones excluded; `None` when nothing
    /// was checked.
    pub clearance_m: Option<f64>,
    /// Link of the lowest clearance (index into `robot.links`; u32 keeps `Check` small).
    pub clearance_link: Option<u32>,
    /// Sub-segment of the lowest clearance.
    pub clearance_sub_segment: Option<u32>,
    /// The cable's clearance to itself (m, [`crate::stress::self_contact`]); infinite when no
    /// part of the piece comes back toward another closer than it was asked to look
    /// (`self_within_m` of [`Metrics::of_shape`]).
    pub self_clearance_m: f64,
    /// The two sub-segments of the lowest clearance to itself (0, 0 when not measured).
    pub self_contact_sub_segments: [u32; 2],
    /// Centreline length / natural length.
    pub stretch: f64,
    /// Smallest bend radius (m); infinite for a straight cable.
    pub min_bend_radius_m: f64,
    /// Node of the smallest bend radius (0 = start guide).
    pub min_bend_node: usize,
    /// Twist per length (deg/m, signed: right-handed about the cable toward the tool),
    /// relative to the cable as installed; uniform along the piece. 0 where the model has
    /// no twist (the rapier baseline).
    pub twist_deg_per_m: f64,
}

impl Metrics {
    /// The metrics of a cable shape: `nodes` of a piece of `cable` held by clamps at `start`
    /// and `end` (their +z the cable direction), with its lowest clearance to the robot
    /// (`None` when nothing was checked); approaches of the cable to itself are looked for
    /// where its centreline comes closer than `self_within_m` (touching is always found: pass
    /// at least the diameter); `twist_rad` is its total twist between the clamps. The one
    /// measure of a shape for every caller: the attachment test and `cable-dict segment`.
    pub fn of_shape(
        cable: &CableSpec,
        (nodes, pitch): (&[Point3<f64>], f64),
        (start, end): (&Pose, &Pose),
        clearance: Option<&Clearance>,
        self_within_m: f64,
        twist_rad: f64,
    ) -> Metrics {
        let z = |pose: &Pose| pose.rotation.transform_vector(&Vector3::z());
        let bend = min_bend_radius(nodes, &z(start), &z(end), pitch);
        let within = self_within_m.max(cable.diameter_m);
        let itself = self_contact_within(nodes, cable.diameter_m, pitch, within);
        let sub_segments = nodes.len().saturating_sub(1);
        Metrics {
            clearance_m: clearance.map(|c| c.clearance_m),
            // Link and sub-segment indices are bounded by the robot and the segment lengths.
            clearance_link: clearance.map(|c| c.link as u32),
            clearance_sub_segment: clearance.map(|c| c.sub_segment as u32),
            self_clearance_m: itself.map_or(f64::INFINITY, |c| c.clearance_m),
            // Sub-segment indices are bounded by the setup's segment lengths (u32 keeps
            // `Check` small: it is returned by value in every solve).
            self_contact_sub_segments: itself.map_or([0; 2], |c| c.sub_segments.map(|k| k as u32)),
            stretch: stretch(nodes, sub_segments as f64 * pitch),
            min_bend_radius_m: bend.radius_m,
            min_bend_node: bend.node,
            twist_deg_per_m: twist_per_length_deg_per_m(twist_rad, sub_segments as f64 * pitch),
        }
    }
}

/// How far an equilibrium is from each limit, positive when the limit holds: what a
/// dictionary stores per PV and direction ([`crate::dictionary::format::MarginRecord`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Margins {
    /// The lower of clearance − contact limit and the clearance to itself (mm): both are
    /// contact, and one stored margin keeps the dictionary's records as they are; infinite
    /// when neither was measured.
    pub clearance_mm: f64,
    /// Stretch limit − stretch.
    pub stretch: f64,
    /// 1/(minimum bend radius) − 1/(bend radius) (1/m): curvature, so that a straight cable
    /// has a finite margin and the value changes smoothly with the shape.
    pub curvature_per_m: f64,
    /// Torsion limit − |twist per length| (deg/m); infinite when the cable states no limit.
    pub twist_deg_per_m: f64,
}

impl Margins {
    /// The margins of `metrics` against `limits` (the static bend radius, margin included).
    pub fn of(metrics: &Metrics, limits: &Thresholds) -> Margins {
        Margins {
            clearance_mm: metrics
                .clearance_m
                .map_or(f64::INFINITY, |c| (c - limits.contact_clearance_m) * 1e3)
                .min(metrics.self_clearance_m * 1e3),
            stretch: limits.stretch - metrics.stretch,
            curvature_per_m: 1.0 / limits.static_min_bend_radius_m()
                - 1.0 / metrics.min_bend_radius_m,
            twist_deg_per_m: limits.twist_margin_deg_per_m(metrics.twist_deg_per_m),
        }
    }

    /// `[clearance_mm, stretch, curvature_per_m, twist_deg_per_m]`.
    pub fn to_array(self) -> MarginValues {
        [
            self.clearance_mm,
            self.stretch,
            self.curvature_per_m,
            self.twist_deg_per_m,
        ]
    }

    /// The limit `[clearance, stretch, curvature, twist]` margins violate first, in the
    /// order of [`Evaluator::check`](super::Evaluator::check) (contact, stretch, bend,
    /// twist); `None` when all are non-negative.
    pub fn first_violation(margins: MarginValues) -> Option<Rejection> {
        let kinds = [
            Rejection::Contact,
            Rejection::Stretch,
            Rejection::Bend,
            Rejection::Twist,
        ];
        kinds
            .into_iter()
            .zip(margins)
            .find(|(_, m)| *m < 0.0)
            .map(|(k, _)| k)
    }
}

/// The outcome of one PV at one pose.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// The metrics, when an equilibrium was found (and the segment has a cable).
    pub metrics: Option<Metrics>,
    /// The first violated limit, `None` when all three hold.
    pub rejection: Option<Rejection>,
    /// Why, for people (only for a rejection).
    pub detail: Option<String>,
}

impl Check {
    pub(super) fn pass(metrics: Option<Metrics>) -> Check {
        Check {
            metrics,
            rejection: None,
            detail: None,
        }
    }

    pub(super) fn fail(rejection: Rejection, detail: String, metrics: Option<Metrics>) -> Check {
        Check {
            metrics,
            rejection: Some(rejection),
            detail: Some(detail),
        }
    }

    /// True when all three limits hold.
    pub fn passed(&self) -> bool {
        self.rejection.is_none()
    }
}

/// The first limit `metrics` violates, in the order contact, self-contact, stretch, bend,
/// twist.
pub(super) fn verdict(setup: &Setup, metrics: Metrics) -> Check {
    let limits = &setup.thresholds;
    if let (Some(clearance), Some(link)) = (metrics.clearance_m, metrics.clearance_link)
        && clearance < limits.contact_clearance_m
    {
        let detail = format!(
            "clearance {:.1} mm to {} (limit {:.1} mm)",
            clearance * 1e3,
            setup.robot.links[link as usize].name,
            limits.contact_clearance_m * 1e3
        );
        return Check::fail(Rejection::Contact, detail, Some(metrics));
    }
    if metrics.self_clearance_m < 0.0 {
        let ([i, j], clearance) = (metrics.self_contact_sub_segments, metrics.self_clearance_m);
        let detail = format!(
            "the cable passes through itself: sub-segments {i} and {j} are {:.1} mm apart, \
             centre to centre, less than its diameter {:.1} mm",
            (clearance + setup.cable.diameter_m) * 1e3,
            setup.cable.diameter_m * 1e3
        );
        return Check::fail(Rejection::SelfContact, detail, Some(metrics));
    }
    if metrics.stretch > limits.stretch {
        let detail = format!("stretch {:.4} (limit {})", metrics.stretch, limits.stretch);
        return Check::fail(Rejection::Stretch, detail, Some(metrics));
    }
    if metrics.min_bend_radius_m < limits.static_min_bend_radius_m() {
        let detail = format!(
            "bend radius {:.1} mm at node {} (limit {:.1} mm{})",
            metrics.min_bend_radius_m * 1e3,
            metrics.min_bend_node,
            limits.static_min_bend_radius_m() * 1e3,
            static_margin_note(limits)
        );
        return Check::fail(Rejection::Bend, detail, Some(metrics));
    }
    if let Some(limit) = limits.torsion_limit_deg_per_m
        && metrics.twist_deg_per_m.abs() > limit
    {
        let detail = format!(
            "twist {:.0}°/m (limit ±{limit:.0}°/m)",
            metrics.twist_deg_per_m
        );
        return Check::fail(Rejection::Twist, detail, Some(metrics));
    }
    Check::pass(Some(metrics))
}

/// " incl. a 4.0 mm static margin" when the setup asks for one.
pub(super) fn static_margin_note(limits: &Thresholds) -> String {
    if limits.static_bend_margin_m > 0.0 {
        format!(
            " incl. a {:.1} mm static margin",
            limits.static_bend_margin_m * 1e3
        )
    } else {
        String::new()
    }
}

pub(super) fn connect_failure(error: ConnectError) -> Check {
    match error {
        ConnectError::TooShort { .. } => Check::fail(Rejection::TooShort, error.to_string(), None),
        _ => Check::fail(Rejection::Diverged, error.to_string(), None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::Setup;
    use std::path::Path;

    /// A piece 1.25 % too short to reach its clamps ranks behind a contact miss by 0.1 mm:
    /// being within the stretch limit does not make it a near hit.
    #[test]
    fn a_piece_too_short_ranks_behind_a_hair_of_contact() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let setup = Setup::from_file(root.join("robots/viper_s850/pick_and_place.toml"))
            .unwrap_or_else(|e| panic!("{e}"));
        let pitch = setup.cable.sub_segment_pitch_m;
        let (s, stretch) = (32, 1.0125);
        let guides = (
            Pose::identity(),
            Pose::translation(s as f64 * pitch * stretch, 0.0, 0.0),
        );
        let short = Check::fail(Rejection::TooShort, String::new(), None);
        let too_short = Miss::of(&short, &setup, 0, &guides, s).expect("a miss");
        assert!((too_short.value - stretch).abs() < 1e-12);
        // Clearance 0.1 mm below the limit, for the cable's diameter.
        let hair = 1e-4 / setup.cable.diameter_m;
        assert!(
            too_short.severity > 10.0 * hair,
            "{} against {hair}",
            too_short.severity
        );
    }
    /// A piece that passes through itself is refused as such, after contact with the robot
    /// and before stretch and bend; its clearance margin is the clearance to itself when that
    /// is the lower one, so that a dictionary's lookup refuses it too.
    #[test]
    fn a_cable_through_itself_is_refused_and_its_margin_says_so() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let setup = Setup::from_file(root.join("robots/viper_s850/pick_and_place.toml"))
            .unwrap_or_else(|e| panic!("{e}"));
        let metrics = |self_clearance_m: f64, stretch: f64| Metrics {
            clearance_m: Some(0.050),
            clearance_link: Some(1),
            clearance_sub_segment: Some(3),
            self_clearance_m,
            self_contact_sub_segments: [2, 30],
            stretch,
            min_bend_radius_m: 1.0,
            min_bend_node: 4,
            twist_deg_per_m: 0.0,
        };
        let through = verdict(&setup, metrics(-0.002, 1.5));
        assert_eq!(through.rejection, Some(Rejection::SelfContact));
        let detail = through.detail.as_deref().unwrap_or_default();
        assert!(detail.contains("sub-segments 2 and 30"), "{detail}");
        let margins = Margins::of(&metrics(-0.002, 1.0), &setup.thresholds);
        assert!((margins.clearance_mm + 2.0).abs() < 1e-9, "{margins:?}");
        assert_eq!(
            Margins::first_violation(margins.to_array()),
            Some(Rejection::Contact)
        );
        let clear = verdict(&setup, metrics(0.001, 1.0));
        assert!(clear.passed(), "{:?}", clear.detail);
        let miss = Miss::of(
            &through,
            &setup,
            0,
            &(Pose::identity(), Pose::identity()),
            40,
        )
        .expect("a miss");
        assert!((miss.severity - 0.002 / setup.cable.diameter_m).abs() < 1e-12);
        assert!((miss.at_m - 2.5 * setup.cable.sub_segment_pitch_m).abs() < 1e-12);
    }
}
