//! Worst values, first violation and series, updated one measured instant at a time.

use super::engine::ForceAt;
use super::report::{
    ClampLoadPeak, ClampTurn, Constraint, Failure, FailureCause, GuideSlide, MotionTestReport,
    PieceLifeDamage, PieceTwist, PieceWorst, Place, SLIDE_SAMPLE_S, SegmentNodes, SeriesPoint,
    ShapeFrame, SlidePoint, Violation, Worst,
};
use crate::life::curve::LifeCurve;
use crate::life::damage::PieceHistory;
use crate::setup::{GuideKind, Setup, Thresholds};
use crate::statics::ClampLoad;
use crate::statics::sliding::SlideReading;
use crate::stress::{
    BendRadius, Clearance, CurvatureRange, self_contact_within, twist_per_length_deg_per_m,
};
use nalgebra::Point3;

/// The metrics of one segment at one instant.
pub(super) struct SegmentMeasure {
    /// Index into the setup's segments.
    pub segment: usize,
    /// The cable length between two of its nodes (m).
    pub pitch_m: f64,
    /// Through a sliding guide or out of a retraction: the split or travel (m), and the
    /// retraction's spring force (N).
    pub slid: Option<SlideReading>,
    /// The segment's nodes (m, world frame).
    pub nodes: Vec<Point3<f64>>,
    /// Lowest clearance to the robot, clamp zones excluded.
    pub clearance: Option<Clearance>,
    /// Centreline length / natural length.
    pub stretch: f64,
    /// Tightest joint.
    pub bend: BendRadius,
    /// Curvature at every joint (1/m, [`crate::stress::curvatures_per_m`]).
    pub curvatures_per_m: Vec<f64>,
    /// The curvature vector at every joint in the cross-section's frame
    /// ([`crate::stress::curvature_vectors_per_m`]); empty when the cable has no life curve.
    pub curvature_vectors_per_m: Vec<[f64; 2]>,
    /// Most loaded sub-segment outside the clamp zones in the simulation, if any touched.
    pub contact: Option<ForceAt>,
    /// Largest joint gap (m); 0 for a shape that was not simulated.
    pub max_joint_gap_m: f64,
    /// Total twist between the clamps (rad); `None` where the engine does not model it.
    pub twist_rad: Option<f64>,
    /// The loads on its start and end clamps, when taken at this instant.
    pub loads: Option<(ClampLoad, ClampLoad)>,
}

/// Everything the report keeps, accumulated over the run.
pub(super) struct Tracker<'a> {
    setup: &'a Setup,
    record_series: bool,
    force_is_violation: bool,
    worst_clearance: Option<Worst>,
    worst_stretch: Option<Worst>,
    worst_bend: Option<Worst>,
    worst_twist: Option<Worst>,
    worst_contact_force: Option<Worst>,
    worst_self_clearance: Option<Worst>,
    /// When the next search for any approach of the cable to itself is due (s), while none
    /// is known (see [`Tracker::keep_self_contact`]).
    self_search_due_s: f64,
    first_violation: Option<Violation>,
    pieces: Vec<PieceWorst>,
    /// Per piece (in the order of `pieces`), how its curvature changed so far.
    flex: Vec<CurvatureRange>,
    /// The cable's life curve, and per piece (in the order of `pieces`) its bending and
    /// twisting histories counted so far; `None` without a life curve.
    life: Option<(LifeCurve, Vec<Option<PieceHistory>>)>,
    twists: Vec<PieceTwist>,
    clamp_loads: Vec<ClampLoadPeak>,
    clamp_turns: Vec<ClampTurn>,
    slides: Vec<GuideSlide>,
    max_joint_gap_m: f64,
    series: Vec<SeriesPoint>,
    final_shape: Vec<SegmentNodes>,
    last_time_s: f64,
    shape_interval_s: Option<f64>,
    shapes: Vec<ShapeFrame>,
}

impl<'a> Tracker<'a> {
    /// An empty record; `force_is_violation`: a contact force is a contact violation.
    pub fn new(setup: &'a Setup, record_series: bool, force_is_violation: bool) -> Self {
        Self {
            setup,
            record_series,
            force_is_violation,
            worst_clearance: None,
            worst_stretch: None,
            worst_bend: None,
            worst_twist: None,
            worst_contact_force: None,
            worst_self_clearance: None,
            self_search_due_s: f64::NEG_INFINITY,
            first_violation: None,
            pieces: Vec::new(),
            flex: Vec::new(),
            life: LifeCurve::of(&setup.cable.datasheet).map(|curve| (curve, Vec::new())),
            twists: Vec::new(),
            clamp_loads: Vec::new(),
            clamp_turns: Vec::new(),
            slides: Vec::new(),
            max_joint_gap_m: 0.0,
            series: Vec::new(),
            final_shape: Vec::new(),
            last_time_s: f64::NEG_INFINITY,
            shape_interval_s: None,
            shapes: Vec::new(),
        }
    }

    /// Also keeps the whole cable's shape every `interval_s` (see
    /// [`MotionTestOptions::shape_interval_s`](super::MotionTestOptions::shape_interval_s)).
    pub fn keeping_shapes(mut self, interval_s: Option<f64>) -> Self {
        self.shape_interval_s = interval_s;
        self
    }

    /// Whether a limit has been violated so far.
    pub fn violated(&self) -> bool {
        self.first_violation.is_some()
    }

    /// Takes in the metrics of every segment at `time_s`.
    pub fn record(&mut self, time_s: f64, measures: &[SegmentMeasure]) {
        for measure in measures {
            self.record_segment(time_s, measure);
        }
        self.keep_self_contact(time_s, measures);
        self.keep_twists(time_s, measures);
        self.keep_slides(time_s, measures);
        let clamp_force = self.keep_clamp_loads(time_s, measures);
        if self.record_series {
            let mut point = series_point(time_s, measures);
            point.max_clamp_force_n = clamp_force;
            self.series.push(point);
        }
        self.final_shape = measures
            .iter()
            .map(|m| SegmentNodes {
                segment: m.segment,
                nodes_m: m.nodes.iter().map(|p| [p.x, p.y, p.z]).collect(),
            })
            .collect();
        self.last_time_s = time_s;
        if let Some(interval) = self.shape_interval_s {
            // A little slack, so that rounding in the step times never delays a frame a step.
            let due = self
                .shapes
                .last()
                .is_none_or(|frame| time_s >= frame.time_s + interval * (1.0 - 1e-6));
            if due {
                self.keep_shape();
            }
        }
    }

    /// Adds the current shape as a frame.
    fn keep_shape(&mut self) {
        self.shapes.push(ShapeFrame {
            time_s: self.last_time_s,
            segments: self.final_shape.clone(),
        });
    }

    /// A segment too short at the first pose: `required` is the stretch it would need.
    pub fn record_too_short(&mut self, time_s: f64, segment: usize, required: f64) {
        let thresholds = self.setup.thresholds;
        self.keep_stretch(time_s, segment, required, thresholds);
    }

    /// Keeps the largest turn of the cable in each rotating clamp between two pieces:
    /// `turns` pairs the clamp's guide with the turn (rad) at `time_s`.
    pub fn record_turns(&mut self, time_s: f64, turns: &[(&str, f64)]) {
        for &(guide, turn) in turns {
            let deg = turn.to_degrees();
            match self.clamp_turns.iter_mut().find(|t| t.guide == guide) {
                Some(kept) if deg.abs() > kept.largest_turn_deg.abs() => {
                    (kept.largest_turn_deg, kept.time_s) = (deg, time_s);
                }
                Some(_) => {}
                None => self.clamp_turns.push(ClampTurn {
                    guide: guide.to_owned(),
                    largest_turn_deg: deg,
                    time_s,
                }),
            }
        }
    }

    /// Each sliding guide's and retraction's amount, force and end stop at `time_s`; a pull
    /// on a retraction's end stop is a violation.
    fn keep_slides(&mut self, time_s: f64, measures: &[SegmentMeasure]) {
        let dt = time_s - self.last_time_s;
        for m in measures {
            let (Some(reading), Some((g, kind, _))) = (m.slid, self.setup.slide_of(m.segment))
            else {
                continue;
            };
            let guide = &self.setup.guides[g];
            let travel_max_m = match kind {
                GuideKind::Retraction { travel_max_m, .. } => Some(travel_max_m),
                _ => None,
            };
            let amount = reading.amount_m;
            let point = SlidePoint {
                time_s,
                amount_m: amount,
                force_n: reading.force_n,
            };
            let at = match self.slides.iter().position(|s| s.segment == m.segment) {
                Some(at) => at,
                None => {
                    self.slides.push(GuideSlide {
                        guide: guide.name.clone(),
                        kind: kind.word(),
                        segment: m.segment,
                        segment_name: self.setup.segment_name(m.segment),
                        first_m: amount,
                        least_m: amount,
                        least_time_s: time_s,
                        most_m: amount,
                        most_time_s: time_s,
                        travel_max_m,
                        peak_force_n: reading.force_n,
                        end_stop_s: 0.0,
                        series: vec![point],
                    });
                    self.slides.len() - 1
                }
            };
            let slide = &mut self.slides[at];
            if amount < slide.least_m {
                (slide.least_m, slide.least_time_s) = (amount, time_s);
            }
            if amount > slide.most_m {
                (slide.most_m, slide.most_time_s) = (amount, time_s);
            }
            if let (Some(force), Some(peak)) = (reading.force_n, &mut slide.peak_force_n) {
                *peak = peak.max(force);
            }
            if travel_max_m.is_some_and(|max| amount >= max - 1e-9) && dt > 0.0 {
                slide.end_stop_s += dt;
            }
            let due = slide.series.last().map_or(0.0, |p| p.time_s) + SLIDE_SAMPLE_S;
            if time_s >= due - 1e-9 {
                slide.series.push(point);
            }
            if reading.stop_force_n > STOP_FORCE_TOLERANCE_N {
                let worst = Worst {
                    value: reading.stop_force_n,
                    unit: "N",
                    time_s,
                    segment: m.segment,
                    segment_name: self.setup.segment_name(m.segment),
                    place: Place::default(),
                };
                self.violate(Constraint::Travel, STOP_FORCE_TOLERANCE_N, &worst);
            }
        }
    }

    /// The report, with `failure` if the run itself failed (else a violation's, if any).
    pub fn into_report(mut self, failure: Option<Failure>, run: RunFacts) -> MotionTestReport {
        let last_kept = self.shapes.last().map(|frame| frame.time_s);
        if self.shape_interval_s.is_some()
            && !self.final_shape.is_empty()
            && last_kept != Some(self.last_time_s)
        {
            self.keep_shape();
        }
        let failure = failure.or_else(|| {
            self.first_violation.as_ref().map(|v| Failure {
                cause: FailureCause::Violation,
                reason: v.to_string(),
                segment: Some(v.segment),
            })
        });
        let damage = match self.life {
            Some((curve, histories)) => (self.pieces.iter().zip(histories))
                .filter_map(|(piece, history)| {
                    Some(PieceLifeDamage {
                        segment: piece.segment,
                        segment_name: piece.segment_name.clone(),
                        damage: history?.finish(&curve),
                    })
                })
                .collect(),
            None => Vec::new(),
        };
        MotionTestReport {
            damage,
            passed: failure.is_none(),
            failure,
            first_violation: self.first_violation,
            pieces: self.pieces,
            worst_clearance: self.worst_clearance,
            worst_stretch: self.worst_stretch,
            worst_bend: self.worst_bend,
            worst_twist: self.worst_twist,
            worst_contact_force: self.worst_contact_force,
            worst_self_clearance: self.worst_self_clearance,
            twists: self.twists,
            clamp_loads: self.clamp_loads,
            clamp_turns: self.clamp_turns,
            slides: self.slides,
            max_joint_gap_m: self.max_joint_gap_m,
            series: self.series,
            final_shape: self.final_shape,
            shapes: self.shapes,
            motion_duration_s: run.motion_duration_s,
            steps: run.steps,
            simulated_s: run.simulated_s,
            wall_time_s: run.wall_time_s,
        }
    }

    fn record_segment(&mut self, time_s: f64, measure: &SegmentMeasure) {
        let thresholds = self.setup.thresholds;
        let segment = measure.segment;
        self.max_joint_gap_m = self.max_joint_gap_m.max(measure.max_joint_gap_m);
        if let Some(clearance) = &measure.clearance {
            self.keep_clearance(time_s, segment, clearance, thresholds);
        }
        if let Some(contact) = &measure.contact {
            self.keep_contact(time_s, segment, contact, &measure.nodes);
        }
        self.keep_stretch(time_s, segment, measure.stretch, thresholds);
        self.keep_bend(time_s, segment, measure);
        self.keep_flex(segment, &measure.curvatures_per_m, thresholds);
        self.keep_history(measure);
    }

    /// Counts `measure`'s bending and twisting into its piece's history (with a life curve).
    fn keep_history(&mut self, measure: &SegmentMeasure) {
        let at = self.piece_index(measure.segment);
        let length_m = measure.nodes.len().saturating_sub(1) as f64 * measure.pitch_m;
        let Some((curve, histories)) = &mut self.life else {
            return;
        };
        let twist = measure
            .twist_rad
            .map(|t| twist_per_length_deg_per_m(t, length_m));
        let joints = measure.curvature_vectors_per_m.len();
        histories[at]
            .get_or_insert_with(|| PieceHistory::new(joints))
            .push(curve, &measure.curvature_vectors_per_m, twist);
    }

    /// How `segment`'s curvature changed, with its shape now: once it flexes (by more than
    /// the setup's amount somewhere), its tightest bend so far must keep the flexing radius.
    fn keep_flex(&mut self, segment: usize, curvatures_per_m: &[f64], t: Thresholds) {
        let at = self.piece_index(segment);
        self.flex[at].take(curvatures_per_m);
        let (change, _) = self.flex[at].largest_change();
        let piece = &mut self.pieces[at];
        piece.largest_curvature_change_per_m = change;
        if change <= t.flexing_curvature_change_per_m || piece.flexes {
            return;
        }
        piece.flexes = true;
        piece.bend_radius_limit_m = t.bend_radius_for(true, false);
        let limit = piece.bend_radius_limit_m;
        if let Some(worst) = piece.worst_bend.clone()
            && worst.value < limit
        {
            self.violate(Constraint::FlexingBendRadius, limit, &worst);
        }
    }

    fn keep_clearance(&mut self, time_s: f64, segment: usize, c: &Clearance, t: Thresholds) {
        let place = Place {
            sub_segment: Some(c.sub_segment),
            link: Some(self.link_name(c.link)),
            position_m: Some(xyz(&c.point_on_cable)),
            ..Place::default()
        };
        let worst = Worst {
            value: c.clearance_m,
            unit: "m",
            time_s,
            segment,
            segment_name: self.setup.segment_name(segment),
            place,
        };
        if c.clearance_m < t.contact_clearance_m {
            self.violate(Constraint::Contact, t.contact_clearance_m, &worst);
        }
        let piece = self.piece(segment);
        keep(&mut piece.worst_clearance, worst.clone(), |new, old| {
            new < old
        });
        keep(&mut self.worst_clearance, worst, |new, old| new < old);
    }

    fn keep_stretch(&mut self, time_s: f64, segment: usize, stretch: f64, t: Thresholds) {
        let worst = Worst {
            value: stretch,
            unit: "1",
            time_s,
            segment,
            segment_name: self.setup.segment_name(segment),
            place: Place::default(),
        };
        if stretch > t.stretch {
            self.violate(Constraint::Stretch, t.stretch, &worst);
        }
        let piece = self.piece(segment);
        keep(&mut piece.worst_stretch, worst.clone(), |new, old| {
            new > old
        });
        keep(&mut self.worst_stretch, worst, |new, old| new > old);
    }

    fn keep_bend(&mut self, time_s: f64, segment: usize, m: &SegmentMeasure) {
        let place = Place {
            node: Some(m.bend.node),
            position_m: m.nodes.get(m.bend.node).map(xyz),
            ..Place::default()
        };
        let worst = Worst {
            value: m.bend.radius_m,
            unit: "m",
            time_s,
            segment,
            segment_name: self.setup.segment_name(segment),
            place,
        };
        let piece = self.piece(segment);
        let limit = piece.bend_radius_limit_m;
        if m.bend.radius_m < limit {
            // The flexing radius is a limit of its own only where it is the larger one.
            let constraint = if limit > self.setup.thresholds.min_bend_radius_m {
                Constraint::FlexingBendRadius
            } else {
                Constraint::BendRadius
            };
            self.violate(constraint, limit, &worst);
        }
        let piece = self.piece(segment);
        keep(&mut piece.worst_bend, worst.clone(), |new, old| new < old);
        keep(&mut self.worst_bend, worst, |new, old| new < old);
    }

    /// The worst values of `segment` so far, kept in segment order.
    fn piece(&mut self, segment: usize) -> &mut PieceWorst {
        let at = self.piece_index(segment);
        &mut self.pieces[at]
    }

    /// Where `segment` is in `pieces` (and `flex`), added when new.
    fn piece_index(&mut self, segment: usize) -> usize {
        match self.pieces.binary_search_by_key(&segment, |p| p.segment) {
            Ok(at) => at,
            Err(at) => {
                let piece = PieceWorst {
                    segment,
                    segment_name: self.setup.segment_name(segment),
                    worst_clearance: None,
                    worst_stretch: None,
                    worst_bend: None,
                    flexes: false,
                    largest_curvature_change_per_m: 0.0,
                    bend_radius_limit_m: self.setup.thresholds.bend_radius_for(false, false),
                };
                self.pieces.insert(at, piece);
                self.flex.insert(at, CurvatureRange::default());
                if let Some((_, histories)) = &mut self.life {
                    histories.insert(at, None);
                }
                at
            }
        }
    }

    fn keep_contact(
        &mut self,
        time_s: f64,
        segment: usize,
        contact: &ForceAt,
        nodes: &[Point3<f64>],
    ) {
        let k = contact.sub_segment;
        let midpoint = nodes
            .get(k)
            .zip(nodes.get(k + 1))
            .map(|(a, b)| xyz(&nalgebra::center(a, b)));
        let place = Place {
            sub_segment: Some(k),
            link: contact.link.map(|link| self.link_name(link)),
            position_m: midpoint,
            ..Place::default()
        };
        let worst = Worst {
            value: contact.force_n,
            unit: "N",
            time_s,
            segment,
            segment_name: self.setup.segment_name(segment),
            place,
        };
        if self.force_is_violation && contact.force_n > 0.0 {
            self.violate(Constraint::ContactForce, 0.0, &worst);
        }
        keep(&mut self.worst_contact_force, worst, |new, old| new > old);
    }

    /// The whole cable's clearance to itself: the segments' shapes joined where they meet at
    /// a clamp, so that parts of different segments are checked against each other too.
    ///
    /// Touching is looked for at every step. Approaches closer than the closest one so far are
    /// too, so the closest over the motion is exact once one is known; while none is, a
    /// search for any approach runs every [`SELF_APPROACH_SEARCH_S`] of the motion (the
    /// search for every approach costs several times the search for touching).
    fn keep_self_contact(&mut self, time_s: f64, measures: &[SegmentMeasure]) {
        let cable = &self.setup.cable;
        let (diameter, pitch) = (cable.diameter_m, cable.sub_segment_pitch_m);
        let within = match &self.worst_self_clearance {
            Some(worst) => worst.value.max(0.0) + diameter,
            None if time_s >= self.self_search_due_s => {
                self.self_search_due_s = time_s + SELF_APPROACH_SEARCH_S;
                f64::INFINITY
            }
            None => diameter,
        };
        for run in joined_runs(measures) {
            let Some(itself) = self_contact_within(&run.nodes, diameter, pitch, within) else {
                continue;
            };
            let name = |segment| self.setup.segment_name(segment);
            let (segment, place) = run.failure(itself.sub_segments, name);
            let worst = Worst {
                value: itself.clearance_m,
                unit: "m",
                time_s,
                segment,
                segment_name: self.setup.segment_name(segment),
                place,
            };
            if itself.is_violated() {
                self.violate(Constraint::SelfContact, 0.0, &worst);
            }
            keep(&mut self.worst_self_clearance, worst, |new, old| new < old);
        }
    }

    /// Each piece's largest twist so far (by its magnitude; ties keep the earliest).
    fn keep_twists(&mut self, time_s: f64, measures: &[SegmentMeasure]) {
        for m in measures {
            let Some(twist) = m.twist_rad else {
                continue;
            };
            let length_m = m.nodes.len().saturating_sub(1) as f64 * m.pitch_m;
            let twist_deg = twist.to_degrees();
            let per_m = twist_per_length_deg_per_m(twist, length_m);
            let candidate = PieceTwist {
                segment: m.segment,
                segment_name: self.setup.segment_name(m.segment),
                twist_deg,
                twist_deg_per_m: per_m,
                time_s,
            };
            let worst = Worst {
                value: per_m.abs(),
                unit: "deg/m",
                time_s,
                segment: m.segment,
                segment_name: candidate.segment_name.clone(),
                place: Place::default(),
            };
            if let Some(limit) = self.setup.thresholds.torsion_limit_deg_per_m
                && per_m.abs() > limit
            {
                self.violate(Constraint::Twist, limit, &worst);
            }
            keep(&mut self.worst_twist, worst, |new, old| new > old);
            match self.twists.iter_mut().find(|t| t.segment == m.segment) {
                Some(old) if twist_deg.abs() > old.twist_deg.abs() => *old = candidate,
                Some(_) => {}
                None => self.twists.push(candidate),
            }
        }
    }

    /// Each clamp's largest force and moment so far: a clamp between two simulated pieces
    /// carries the end of the one and the start of the other. Returns the largest force on
    /// one clamp now, when the loads were taken now.
    fn keep_clamp_loads(&mut self, time_s: f64, measures: &[SegmentMeasure]) -> Option<f64> {
        let loads = measures
            .iter()
            .map(|m| m.loads)
            .collect::<Option<Vec<_>>>()?;
        if loads.is_empty() {
            return None;
        }
        let mut largest: f64 = 0.0;
        for clamp in 0..=loads.len() {
            let before = clamp.checked_sub(1).map(|j| loads[j].1);
            let after = loads.get(clamp).map(|l| l.0);
            let total = before
                .unwrap_or(ClampLoad::ZERO)
                .plus(&after.unwrap_or(ClampLoad::ZERO));
            let mut guides = Vec::new();
            if let Some(j) = clamp.checked_sub(1) {
                let (_, b) = self.setup.segment_guides(measures[j].segment);
                guides.push(self.setup.guides[b].name.clone());
            }
            if let Some(m) = measures.get(clamp) {
                let (a, _) = self.setup.segment_guides(m.segment);
                let name = &self.setup.guides[a].name;
                if !guides.contains(name) {
                    guides.push(name.clone());
                }
            }
            let (force, moment) = (total.force_magnitude_n(), total.moment_magnitude_n_m());
            largest = largest.max(force);
            match self.clamp_loads.get_mut(clamp) {
                Some(peak) => {
                    if force > peak.max_force_n {
                        (peak.max_force_n, peak.force_time_s, peak.force_n) =
                            (force, time_s, total.force_n);
                    }
                    if moment > peak.max_moment_n_m {
                        (peak.max_moment_n_m, peak.moment_time_s, peak.moment_n_m) =
                            (moment, time_s, total.moment_n_m);
                    }
                }
                None => self.clamp_loads.push(ClampLoadPeak {
                    guides,
                    max_force_n: force,
                    force_time_s: time_s,
                    force_n: total.force_n,
                    max_moment_n_m: moment,
                    moment_time_s: time_s,
                    moment_n_m: total.moment_n_m,
                }),
            }
        }
        Some(largest)
    }

    /// Records a violation if it is the first one.
    fn violate(&mut self, constraint: Constraint, threshold: f64, at: &Worst) {
        if self.first_violation.is_none() {
            self.first_violation = Some(Violation {
                constraint,
                value: at.value,
                threshold,
                unit: at.unit,
                time_s: at.time_s,
                segment: at.segment,
                segment_name: at.segment_name.clone(),
                place: at.place.clone(),
            });
        }
    }

    fn link_name(&self, link: usize) -> String {
        self.setup
            .robot
            .links
            .get(link)
            .map_or_else(|| format!("link #{link}"), |l| l.name.clone())
    }
}

/// A pull on a retraction's end stop below this (N) is the finite differences' noise.
const STOP_FORCE_TOLERANCE_N: f64 = 0.01;

/// While no approach of the cable to itself is known, how often (s of the motion) a search
/// for one runs; touching is checked at every step.
const SELF_APPROACH_SEARCH_S: f64 = 0.05;

/// Facts about the run the tracker does not see.
pub(super) struct RunFacts {
    pub motion_duration_s: f64,
    pub steps: usize,
    pub simulated_s: f64,
    pub wall_time_s: f64,
}

/// Replaces `slot` by `candidate` when empty or when `better(new, old)`: strict, so ties keep
/// the earliest time, then the lowest segment.
fn keep(slot: &mut Option<Worst>, candidate: Worst, better: fn(f64, f64) -> bool) {
    if slot
        .as_ref()
        .is_none_or(|old| better(candidate.value, old.value))
    {
        *slot = Some(candidate);
    }
}

/// A stretch of cable whose segments meet end to start, and which segment and sub-segment
/// each of its sub-segments is.
struct JoinedRun {
    nodes: Vec<Point3<f64>>,
    owners: Vec<(usize, usize)>,
    /// Sub-segments of each segment, by segment index.
    lengths: std::collections::BTreeMap<usize, usize>,
}

impl JoinedRun {
    /// How many sub-segments sub-segment `k` is from the nearer clamp of its segment.
    fn free_length(&self, k: usize) -> usize {
        let (segment, local) = self.owners[k];
        let length = self.lengths.get(&segment).copied().unwrap_or(0);
        local.min(length.saturating_sub(local + 1))
    }

    /// Of two touching sub-segments, (the one the failure is given to, the other): the one
    /// farther from its clamps swings free, and a longer or rerouted piece there is the
    /// remedy.
    fn blame(&self, k: usize, l: usize) -> (usize, usize) {
        if self.free_length(l) >= self.free_length(k) {
            (l, k)
        } else {
            (k, l)
        }
    }

    /// The segment a contact between sub-segments `pair` is given to, and where: the freer
    /// part's ([`JoinedRun::blame`]), or the 0 mm piece both parts hang from
    /// ([`JoinedRun::coincident_between`]); the place names the other part.
    fn failure(&self, [k, l]: [usize; 2], name: impl Fn(usize) -> String) -> (usize, Place) {
        let (blamed, other) = self.blame(k, l);
        let (other_segment, other_local) = self.owners[other];
        let touches = Some(format!("{} sub-segment {other_local}", name(other_segment)));
        let (segment, local) = self.owners[blamed];
        if let Some(between) = self.coincident_between(other_segment, segment) {
            let place = Place {
                touches,
                ..Place::default()
            };
            return (between, place);
        }
        let middle = nalgebra::center(&self.nodes[blamed], &self.nodes[blamed + 1]);
        let place = Place {
            sub_segment: Some(local),
            position_m: Some(xyz(&middle)),
            touches,
            ..Place::default()
        };
        (segment, place)
    }

    /// A 0 mm piece between segments `a` and `b` (two clamps at one place that the run
    /// passes through): the two touching parts hang from that one place, and separating
    /// the clamps is the remedy.
    fn coincident_between(&self, a: usize, b: usize) -> Option<usize> {
        let (low, high) = (a.min(b), a.max(b));
        (low + 1..high).find(|s| !self.lengths.contains_key(s))
    }
}

/// The segments' shapes joined where one ends at the next one's start clamp (within 1 µm);
/// a gap starts a new run.
fn joined_runs(measures: &[SegmentMeasure]) -> Vec<JoinedRun> {
    let mut runs: Vec<JoinedRun> = Vec::new();
    for m in measures.iter().filter(|m| m.nodes.len() >= 2) {
        let joins = runs
            .last()
            .and_then(|run| run.nodes.last())
            .is_some_and(|end| (end - m.nodes[0]).norm() < 1e-6);
        if !joins {
            runs.push(JoinedRun {
                nodes: vec![m.nodes[0]],
                owners: Vec::new(),
                lengths: Default::default(),
            });
        }
        if let Some(run) = runs.last_mut() {
            run.nodes.extend_from_slice(&m.nodes[1..]);
            run.owners
                .extend((0..m.nodes.len() - 1).map(|k| (m.segment, k)));
            run.lengths.insert(m.segment, m.nodes.len() - 1);
        }
    }
    runs
}

/// The whole cable's metrics at one instant (`pitch_m` the sub-segments' length); the
/// clamp force is the caller's.
fn series_point(time_s: f64, measures: &[SegmentMeasure]) -> SeriesPoint {
    let twists = measures.iter().filter_map(|m| {
        let length = m.nodes.len().saturating_sub(1) as f64 * m.pitch_m;
        let twist = m.twist_rad?;
        (length > 0.0).then(|| twist.abs().to_degrees() / length)
    });
    let clearances = measures
        .iter()
        .filter_map(|m| m.clearance.map(|c| c.clearance_m));
    SeriesPoint {
        time_s,
        min_clearance_m: clearances.reduce(f64::min),
        max_stretch: measures.iter().map(|m| m.stretch).fold(0.0, f64::max),
        min_bend_radius_m: measures
            .iter()
            .map(|m| m.bend.radius_m)
            .fold(f64::INFINITY, f64::min),
        max_contact_force_n: measures
            .iter()
            .filter_map(|m| m.contact.map(|c| c.force_n))
            .fold(0.0, f64::max),
        max_twist_deg_per_m: twists.reduce(f64::max),
        max_clamp_force_n: None,
    }
}

fn xyz(p: &Point3<f64>) -> [f64; 3] {
    [p.x, p.y, p.z]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points `pitch` apart along the polyline through `corners`.
    fn along(corners: &[Point3<f64>], pitch: f64) -> Vec<Point3<f64>> {
        let mut points = vec![corners[0]];
        for pair in corners.windows(2) {
            let steps = ((pair[1] - pair[0]).norm() / pitch).round() as usize;
            points.extend(
                (1..=steps).map(|k| pair[0] + (pair[1] - pair[0]) * (k as f64 / steps as f64)),
            );
        }
        points
    }

    /// Two segments that meet at a clamp, the second coming back across the first: the
    /// joined cable passes through itself although neither segment does alone, and the
    /// violation names the segment and sub-segment where the first is crossed.
    #[test]
    fn parts_of_two_segments_that_cross_are_a_self_contact_violation() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let setup = Setup::from_file(root.join("robots/viper_s850/pick_and_place.toml"))
            .unwrap_or_else(|e| panic!("{e}"));
        let pitch = setup.cable.sub_segment_pitch_m;
        let measure = |segment: usize, nodes: Vec<Point3<f64>>| SegmentMeasure {
            pitch_m: pitch,
            slid: None,
            segment,
            nodes,
            clearance: None,
            stretch: 1.0,
            bend: BendRadius {
                radius_m: f64::INFINITY,
                node: 0,
            },
            curvatures_per_m: Vec::new(),
            curvature_vectors_per_m: Vec::new(),
            contact: None,
            max_joint_gap_m: 0.0,
            twist_rad: None,
            loads: None,
        };
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let first = along(&[p(0.0, 0.0), p(0.3, 0.0)], pitch);
        // Out past the clamp, back, and down across the first segment at x = 205 mm.
        let second = along(
            &[
                p(0.3, 0.0),
                p(0.4, 0.0),
                p(0.4, 0.1),
                p(0.205, 0.1),
                p(0.205, -0.1),
            ],
            pitch,
        );
        let diameter = setup.cable.diameter_m;
        for alone in [&first, &second] {
            let alone = crate::stress::self_contact(alone, diameter, pitch);
            assert!(alone.is_none_or(|c| !c.is_violated()));
        }
        let mut tracker = Tracker::new(&setup, false, false);
        tracker.record(0.5, &[measure(1, first), measure(2, second)]);
        let violation = tracker
            .first_violation
            .expect("the second crosses the first");
        assert_eq!(violation.constraint, Constraint::SelfContact);
        assert!(
            (violation.value + diameter).abs() < 1e-9,
            "{}",
            violation.value
        );
        let worst = tracker.worst_self_clearance.expect("measured");
        assert_eq!(worst.value, violation.value);
        // The failure is the second segment's, whose part swings free; it names the part of
        // the first it crosses, at x = 205 mm.
        assert_eq!(violation.segment, 2);
        let touches = violation.place.touches.as_deref().unwrap_or_default();
        let k: usize = touches
            .rsplit(' ')
            .next()
            .and_then(|k| k.parse().ok())
            .unwrap_or_else(|| panic!("{touches}"));
        assert!(touches.starts_with(&setup.segment_name(1)), "{touches}");
        assert!(
            (k as f64 + 0.5) * pitch > 0.195 && (k as f64 - 0.5) * pitch < 0.215,
            "{k}"
        );
    }
}
