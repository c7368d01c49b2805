//! The result of a motion test: pass/fail, the worst value of every metric with when and
//! where it happened, the first violation, and optionally the time series.
//!
//! Every type serializes with serde (SI units; a name without a unit is dimensionless or
//! carries its unit in a `unit` field). Non-finite values (the infinite bend radius of a
//! straight cable) serialize as JSON `null`.

use serde::Serialize;
use std::fmt;

/// The outcome of [`run`](super::run).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionTestReport {
    /// True when the cable was simulated through the whole motion and the settle tail
    /// without violating any limit.
    pub passed: bool,
    /// Why the candidate failed; `None` exactly when `passed`.
    pub failure: Option<Failure>,
    /// The first limit violation (earliest time; within one step, lowest segment, then
    /// contact, contact force, stretch, bend radius).
    pub first_violation: Option<Violation>,
    /// Lowest signed clearance to the robot (m; < 0 is a penetration depth), clamp zones
    /// excluded; `None` when nothing was checked.
    pub worst_clearance: Option<Worst>,
    /// Highest stretch (centreline length / natural length).
    pub worst_stretch: Option<Worst>,
    /// Smallest bend radius (m).
    pub worst_bend: Option<Worst>,
    /// Largest twist per length of a piece (deg/m, its magnitude), relative to the cable as
    /// installed; `None` where the engine does not model twist.
    pub worst_twist: Option<Worst>,
    /// Largest contact force on one sub-segment outside the clamp zones in the simulation
    /// (N); `None` when the cable never touched the robot there.
    pub worst_contact_force: Option<Worst>,
    /// Lowest clearance of the whole cable to itself (m: centreline distance − diameter,
    /// [`crate::stress::self_contact`]; < 0 the cable passes through itself), at the first of
    /// the two sub-segments; `None` for a cable too short to meet itself.
    pub worst_self_clearance: Option<Worst>,
    /// Per simulated piece (in segment order), its own worst clearance, stretch and bend
    /// radius over the run: which piece is tightest where, and which of several motions binds
    /// each piece.
    pub pieces: Vec<PieceWorst>,
    /// Per simulated piece, its largest twist over the run (the implicit engine; empty for
    /// the rigid chain, which does not model twist as the statics do).
    pub twists: Vec<PieceTwist>,
    /// Per simulated piece, the damage one cycle of the motion does to it (its bending per
    /// joint, its twisting), counted over the run as the motion repeated; empty when the
    /// cable has no life curve.
    pub damage: Vec<PieceLifeDamage>,
    /// Per clamp of the simulated cable (guides joined by a 0 mm piece are one), the largest
    /// force and moment the cable puts on it, sampled every 20 ms of the motion (the
    /// implicit engine; empty for the rigid chain).
    pub clamp_loads: Vec<ClampLoadPeak>,
    /// Per rotating clamp between two pieces, how far the cable turned in it: the twist it
    /// relieved.
    pub clamp_turns: Vec<ClampTurn>,
    /// Per sliding guide and retraction on the path: how far the cable slid through it,
    /// the spring's force.
    pub slides: Vec<GuideSlide>,
    /// Largest gap between the anchors of two joined bodies over the run (m): the solver's
    /// constraint error, ≈ 0.1 mm at the default settings.
    pub max_joint_gap_m: f64,
    /// One point per measured instant (the initial shape, then every step) when
    /// `record_series` is set; empty otherwise.
    pub series: Vec<SeriesPoint>,
    /// The simulated shape at the last step taken, per simulated segment (empty when the
    /// candidate failed before the simulation started).
    pub final_shape: Vec<SegmentNodes>,
    /// The cable's shape over time, one frame per
    /// [`shape_interval_s`](super::MotionTestOptions::shape_interval_s) and one at the last
    /// instant measured; empty when not asked for. Not serialized: it is bulky.
    #[serde(skip)]
    pub shapes: Vec<ShapeFrame>,
    /// Duration of the motion (s).
    pub motion_duration_s: f64,
    /// Simulation steps taken.
    pub steps: usize,
    /// Simulated time: steps × time step (s).
    pub simulated_s: f64,
    /// Wall-clock time of the whole test, setup of the simulation included (s).
    pub wall_time_s: f64,
}

/// The worst values of one piece of cable over the motion test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PieceWorst {
    /// Index into the setup's segments.
    pub segment: usize,
    /// The segment's name (`C3`).
    pub segment_name: String,
    /// Its lowest clearance to the robot (m), clamp zones excluded; `None` when not checked.
    pub worst_clearance: Option<Worst>,
    /// Its highest stretch.
    pub worst_stretch: Option<Worst>,
    /// Its smallest bend radius (m).
    pub worst_bend: Option<Worst>,
    /// Whether it flexes: somewhere along it the curvature changed by more than the setup's
    /// `flexing_curvature_change_per_m`, so it kept the flexing bend radius.
    pub flexes: bool,
    /// The largest change of curvature at one place over the run (1/m).
    pub largest_curvature_change_per_m: f64,
    /// The bend radius it had to keep (m): the flexing one when it flexes, else the fixed.
    pub bend_radius_limit_m: f64,
}

/// The damage one cycle of the motion does to one piece ([`crate::life::damage`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PieceLifeDamage {
    /// Index into the setup's segments.
    pub segment: usize,
    /// The segment's name (`C3`).
    pub segment_name: String,
    /// Per joint bending and the twisting, Miner's sum per cycle.
    pub damage: crate::life::damage::PieceDamage,
}

/// The largest twist of one piece of cable over the motion test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PieceTwist {
    /// Index into the setup's segments.
    pub segment: usize,
    /// The segment's name (`C3`).
    pub segment_name: String,
    /// The total twist between its clamps at its largest (deg, signed: right-handed about
    /// the cable toward the tool), relative to the cable as installed (laid untwisted at the
    /// installation pose).
    pub twist_deg: f64,
    /// The same per length of the piece (deg/m): the twist is uniform along a piece.
    pub twist_deg_per_m: f64,
    /// When (s, the motion's time axis).
    pub time_s: f64,
}

/// The largest load the cable puts on one clamp over the motion test, world frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClampLoadPeak {
    /// The setup's guides at this clamp (two when a 0 mm piece joins them).
    pub guides: Vec<String>,
    /// The largest force (N) and when (s).
    pub max_force_n: f64,
    /// When the force was largest (s).
    pub force_time_s: f64,
    /// The force then (N, world frame).
    pub force_n: [f64; 3],
    /// The largest moment about the clamp's point (N·m).
    pub max_moment_n_m: f64,
    /// When the moment was largest (s).
    pub moment_time_s: f64,
    /// The moment then (N·m, world frame).
    pub moment_n_m: [f64; 3],
}

/// How far the cable turned in a rotating clamp between two pieces over the motion test,
/// from the cable as laid: the twist the clamp took off the pieces.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClampTurn {
    /// The setup's guide at this clamp.
    pub guide: String,
    /// The largest turn (deg, signed: right-handed about the cable toward the tool).
    pub largest_turn_deg: f64,
    /// When (s).
    pub time_s: f64,
}

/// A sliding guide or a retraction over the run: how far the cable slid through it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GuideSlide {
    /// The setup's guide.
    pub guide: String,
    /// `"sliding"` or `"retraction"`.
    pub kind: &'static str,
    /// The setup's segment of the piece through it (C1 = 0), and its name.
    pub segment: usize,
    /// E.g. `C2–C3`.
    pub segment_name: String,
    /// At the first instant: the cable before a sliding guide, or a retraction's travel (m).
    pub first_m: f64,
    /// The least of it over the run (m), and when.
    pub least_m: f64,
    /// When the least was (s).
    pub least_time_s: f64,
    /// The most of it over the run (m).
    pub most_m: f64,
    /// When the most was (s).
    pub most_time_s: f64,
    /// A retraction's travel (m); `None` for a sliding guide.
    pub travel_max_m: Option<f64>,
    /// A retraction's largest spring force (N).
    pub peak_force_n: Option<f64>,
    /// Time a retraction spent on its end stop (s).
    pub end_stop_s: f64,
    /// Samples every [`SLIDE_SAMPLE_S`] of the run.
    pub series: Vec<SlidePoint>,
}

/// How often (s) a slide's series is sampled.
pub const SLIDE_SAMPLE_S: f64 = 0.01;

/// One sample of a slide.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SlidePoint {
    /// Time (s).
    pub time_s: f64,
    /// The cable before the sliding guide, or the travel (m).
    pub amount_m: f64,
    /// A retraction's spring force (N).
    pub force_n: Option<f64>,
}

/// Why a candidate failed the motion test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Failure {
    /// The kind of failure.
    pub cause: FailureCause,
    /// For people: what, when, where.
    pub reason: String,
    /// The setup's segment (C1 = 0) the failure belongs to, when it belongs to one. Segments
    /// are independent between clamps (each guide holds the cable's position and direction),
    /// so every cable path with this segment's length and guide configurations fails too.
    pub segment: Option<usize>,
}

/// The kinds of failure of a candidate (not errors of the run: the caller goes on with the
/// next candidate).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FailureCause {
    /// A limit was violated (see `first_violation`).
    Violation,
    /// At the motion's first pose a segment's guides are farther apart than its length.
    TooShort,
    /// No initial shape: no connected geometry, no static equilibrium, or a shape the
    /// simulation refused.
    NoInitialShape,
    /// The simulation left its sanity bounds (whether or not a limit was violated before).
    Diverged,
}

/// The three stress limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Constraint {
    /// Clearance to the robot below `contact_clearance_m`.
    Contact,
    /// A contact force in the simulation outside the clamp zones (with
    /// `contact_force_is_violation`; threshold 0 N).
    ContactForce,
    /// Stretch above the `stretch` limit.
    Stretch,
    /// Bend radius below `min_bend_radius_m` (fixed installation).
    BendRadius,
    /// Bend radius of a flexing piece below the cable's flexing radius.
    FlexingBendRadius,
    /// Twist per length above the cable's torsion limit (deg/m).
    Twist,
    /// The cable touches or passes through itself (clearance to itself below 0).
    SelfContact,
    /// A retraction at its end stop with the cable pulling harder than its spring: it ran
    /// out of travel.
    Travel,
}

/// The worst value of one metric over the run, and when and where it happened.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Worst {
    /// The value, in `unit`.
    pub value: f64,
    /// `"m"`, `"N"` or `"1"` (dimensionless).
    pub unit: &'static str,
    /// Time on the motion's time axis (s).
    pub time_s: f64,
    /// Index into the setup's segments (C1 = 0).
    pub segment: usize,
    /// The segment's name (`C2`, or `C2–C3` for a span over optional guides).
    pub segment_name: String,
    /// Where on the segment.
    pub place: Place,
}

/// Where on a segment a value was found; fields that do not apply are `None`.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Place {
    /// Sub-segment `k` (node `k` → node `k + 1`, 0 at the start guide).
    pub sub_segment: Option<usize>,
    /// Node (joint) index, 0 at the start guide, `S` at the end guide.
    pub node: Option<usize>,
    /// The robot link involved (for a contact force, known only when it is the segment's
    /// most loaded sub-segment overall).
    pub link: Option<String>,
    /// The point in the world frame (m): on the cable surface for a clearance, the node for
    /// a bend, the sub-segment's midpoint for a contact force or a self-contact.
    pub position_m: Option<[f64; 3]>,
    /// For a self-contact, the other part of the cable (`C1 sub-segment 31`).
    pub touches: Option<String>,
}

/// A limit violated at one instant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Violation {
    /// Which limit.
    pub constraint: Constraint,
    /// The value found, in `unit`.
    pub value: f64,
    /// The limit, in `unit`.
    pub threshold: f64,
    /// `"m"`, `"N"` or `"1"` (dimensionless).
    pub unit: &'static str,
    /// Time on the motion's time axis (s).
    pub time_s: f64,
    /// Index into the setup's segments (C1 = 0).
    pub segment: usize,
    /// The segment's name (`C2`, or `C2–C3` for a span over optional guides).
    pub segment_name: String,
    /// Where on the segment.
    pub place: Place,
}

/// The metrics of the whole cable at one instant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SeriesPoint {
    /// Time on the motion's time axis (s).
    pub time_s: f64,
    /// Lowest clearance over all segments (m); `None` when nothing was checked.
    pub min_clearance_m: Option<f64>,
    /// Highest stretch over all segments.
    pub max_stretch: f64,
    /// Smallest bend radius over all segments (m).
    pub min_bend_radius_m: f64,
    /// Largest contact force on one sub-segment outside the clamp zones during the step (N);
    /// 0 for the initial shape.
    pub max_contact_force_n: f64,
    /// Largest twist per length over the pieces (deg/m, its magnitude); `None` where the
    /// engine does not model twist.
    pub max_twist_deg_per_m: Option<f64>,
    /// Largest force on one clamp (N), at the instants the loads are taken.
    pub max_clamp_force_n: Option<f64>,
}

/// The whole simulated cable at one instant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShapeFrame {
    /// Time on the motion's time axis (s).
    pub time_s: f64,
    /// Every simulated segment's nodes.
    pub segments: Vec<SegmentNodes>,
}

/// The nodes of one simulated segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SegmentNodes {
    /// Index into the setup's segments.
    pub segment: usize,
    /// `S + 1` nodes from the start guide to the end guide, world frame (m).
    pub nodes_m: Vec<[f64; 3]>,
}

impl Violation {
    /// By how much its limit would have to move for this failure to go (m), for the limits a
    /// user may weigh against a datasheet or a bracket: the bend radius and the clearance to
    /// the robot; `None` for the others.
    pub fn missed_by_m(&self) -> Option<f64> {
        matches!(
            self.constraint,
            Constraint::BendRadius | Constraint::FlexingBendRadius | Constraint::Contact
        )
        .then(|| self.threshold - self.value)
    }

    /// The violation as the worst value of its limit at that instant (a violation is the
    /// worst so far when it happens), so that it is worded as the worst values are.
    pub fn to_worst(&self) -> Worst {
        Worst {
            value: self.value,
            unit: self.unit,
            time_s: self.time_s,
            segment: self.segment,
            segment_name: self.segment_name.clone(),
            place: self.place.clone(),
        }
    }
}

impl fmt::Display for Constraint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Constraint::Contact => "contact",
            Constraint::ContactForce => "contact force",
            Constraint::Stretch => "stretch",
            Constraint::BendRadius => "bend radius",
            Constraint::FlexingBendRadius => "flexing bend radius",
            Constraint::Twist => "twist",
            Constraint::SelfContact => "self-contact",
            Constraint::Travel => "travel",
        })
    }
}

impl fmt::Display for Place {
    /// E.g. `sub-segment 12, link_5` (empty when nothing is known).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        if let Some(k) = self.sub_segment {
            parts.push(format!("sub-segment {k}"));
        }
        if let Some(n) = self.node {
            parts.push(format!("node {n}"));
        }
        if let Some(link) = &self.link {
            parts.push(link.clone());
        }
        if let Some(other) = &self.touches {
            parts.push(format!("touching {other}"));
        }
        f.write_str(&parts.join(", "))
    }
}

impl fmt::Display for Violation {
    /// E.g. `contact: clearance -3.20 mm < 0.00 mm at t = 1.2375 s, segment C3 (sub-segment
    /// 12, link_5)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (what, value, op, limit) = match self.constraint {
            Constraint::Contact => (
                "clearance",
                format!("{:.2} mm", self.value * 1e3),
                "<",
                format!("{:.2} mm", self.threshold * 1e3),
            ),
            Constraint::ContactForce => (
                "force",
                format!("{:.3} N", self.value),
                ">",
                format!("{:.3} N", self.threshold),
            ),
            Constraint::Stretch => (
                "stretch",
                format!("{:.4}", self.value),
                ">",
                format!("{:.4}", self.threshold),
            ),
            Constraint::BendRadius | Constraint::FlexingBendRadius => (
                match self.constraint {
                    Constraint::BendRadius => "bend radius",
                    _ => "bend radius of a flexing piece",
                },
                format!("{:.2} mm", self.value * 1e3),
                "<",
                format!("{:.2} mm", self.threshold * 1e3),
            ),
            Constraint::Twist => (
                "twist",
                format!("{:.0}°/m", self.value),
                ">",
                format!("{:.0}°/m", self.threshold),
            ),
            Constraint::SelfContact => (
                "clearance to itself",
                format!("{:.2} mm", self.value * 1e3),
                "<",
                format!("{:.2} mm", self.threshold * 1e3),
            ),
            Constraint::Travel => (
                "pull on the retraction's end stop",
                format!("{:.2} N", self.value),
                ">",
                format!("{:.2} N", self.threshold),
            ),
        };
        write!(
            f,
            "{}: {what} {value} {op} {limit} at t = {:.2} s, segment {}",
            self.constraint, self.time_s, self.segment_name
        )?;
        let place = self.place.to_string();
        if !place.is_empty() {
            write!(f, " ({place})")?;
        }
        Ok(())
    }
}

impl MotionTestReport {
    /// A few lines for people: verdict, worst values, cost.
    pub fn summary(&self) -> String {
        let verdict = match &self.failure {
            None => "passed".to_string(),
            Some(failure) => format!("failed: {}", failure.reason),
        };
        let worst = |label: &str, w: &Option<Worst>, scale: f64, unit: &str| match w {
            Some(w) => {
                let place = w.place.to_string();
                let place = if place.is_empty() {
                    place
                } else {
                    format!(" ({place})")
                };
                // Stretch is a ratio near 1: four decimals; lengths to 0.1 mm.
                let value = match unit {
                    "mm" => format!("{:.1}", w.value * scale),
                    _ => format!("{:.4}", w.value * scale),
                };
                format!(
                    "{label} {value} {unit} at t = {:.2} s, {}{place}",
                    w.time_s, w.segment_name,
                )
            }
            None => format!("{label}: none"),
        };
        [
            verdict,
            worst("min clearance", &self.worst_clearance, 1e3, "mm"),
            worst("max stretch", &self.worst_stretch, 1.0, ""),
            worst("min bend radius", &self.worst_bend, 1e3, "mm"),
            worst("max contact force", &self.worst_contact_force, 1.0, "N"),
            worst(
                "min clearance to itself",
                &self.worst_self_clearance,
                1e3,
                "mm",
            ),
            format!(
                "{} steps, {:.2} s simulated (the {:.2} s motion, then its last pose held) in \
                 {:.2} s wall{}{}",
                self.steps,
                self.simulated_s,
                self.motion_duration_s,
                self.wall_time_s,
                if self.simulated_s > 0.0 {
                    format!(
                        " ({:.3} s per simulated s)",
                        self.wall_time_s / self.simulated_s
                    )
                } else {
                    String::new()
                },
                if self.max_joint_gap_m > 0.0 {
                    format!(", max joint gap {:.3} mm", self.max_joint_gap_m * 1e3)
                } else {
                    String::new()
                }
            ),
        ]
        .join("\n")
    }
}
