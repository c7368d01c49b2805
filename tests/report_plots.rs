//! The three SVG plots of the report folder, read back with an XML parser and checked against
//! references computed here: the data are known sines and parabolas, the SVG coordinates are
//! mapped back to data through an axis transform inferred from two points of the drawing.

use cable_dict::motion::Motion;
use cable_dict::motion_test::{
    Constraint, Failure, FailureCause, MotionTestReport, Place, SeriesPoint, Violation, Worst,
};
use cable_dict::report::plots::{PlotError, joints_svg, sets_svg, stress_svg};
use cable_dict::robot::Robot;
use cable_dict::setup::{BendRadiusSource, Thresholds};
use cable_dict::solve::{PoseSummary, SegmentReport};
use quick_xml::events::Event;
use std::collections::BTreeMap;
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------------
// A minimal SVG reader.

/// One element: tag name, attributes, text content (trimmed).
#[derive(Debug, Clone)]
struct Elem {
    name: String,
    attrs: BTreeMap<String, String>,
    text: String,
}

impl Elem {
    fn attr(&self, key: &str) -> &str {
        self.attrs.get(key).map_or("", String::as_str)
    }

    fn num(&self, key: &str) -> f64 {
        self.attr(key)
            .parse()
            .unwrap_or_else(|_| panic!("{} has no numeric {key}: {self:?}", self.name))
    }

    /// The vertices of a polyline.
    fn points(&self) -> Vec<(f64, f64)> {
        self.attr("points")
            .split_whitespace()
            .map(|p| {
                let (x, y) = p.split_once(',').expect("x,y");
                (x.parse().expect("x"), y.parse().expect("y"))
            })
            .collect()
    }

    /// Stroke colour as (r, g, b).
    fn stroke(&self) -> Option<(u8, u8, u8)> {
        rgb(self.attr("stroke"))
    }

    fn filled(&self) -> bool {
        !matches!(self.attr("fill"), "" | "none")
    }
}

fn rgb(hex: &str) -> Option<(u8, u8, u8)> {
    let hex = hex.strip_prefix('#')?;
    let byte = |i: usize| u8::from_str_radix(hex.get(i..i + 2)?, 16).ok();
    Some((byte(0)?, byte(2)?, byte(4)?))
}

fn is_red((r, g, b): (u8, u8, u8)) -> bool {
    r > 180 && g < 60 && b < 60
}

/// Reads the whole document: every event up to `Eof` must parse, tags must balance, the root
/// must be `svg`. Returns every element in document order.
fn parse(svg: &str) -> Vec<Elem> {
    let mut reader = quick_xml::Reader::from_str(svg);
    let mut elems: Vec<Elem> = Vec::new();
    let mut open: Vec<usize> = Vec::new();
    loop {
        let event = reader.read_event().expect("well-formed XML");
        match event {
            Event::Start(ref e) | Event::Empty(ref e) => {
                let name = String::from_utf8(e.name().as_ref().to_vec()).expect("utf-8");
                let mut attrs = BTreeMap::new();
                for a in e.attributes() {
                    let a = a.expect("attribute");
                    let key = String::from_utf8(a.key.as_ref().to_vec()).expect("utf-8");
                    attrs.insert(key, a.unescape_value().expect("value").into_owned());
                }
                assert!(!elems.is_empty() || name == "svg", "root element is {name}");
                assert!(
                    elems.is_empty() || !open.is_empty(),
                    "{name} outside the root"
                );
                elems.push(Elem {
                    name,
                    attrs,
                    text: String::new(),
                });
                if matches!(event, Event::Start(_)) {
                    open.push(elems.len() - 1);
                }
            }
            Event::End(_) => {
                open.pop().expect("balanced tags");
            }
            Event::Text(t) => {
                let content = t.decode().expect("utf-8").into_owned();
                if let Some(&i) = open.last() {
                    elems[i].text.push_str(&content);
                }
            }
            Event::GeneralRef(r) => {
                let name = r.decode().expect("utf-8").into_owned();
                let resolved = match r.resolve_char_ref().expect("char ref") {
                    Some(c) => c.to_string(),
                    None => quick_xml::escape::resolve_predefined_entity(&name)
                        .expect("predefined entity")
                        .to_string(),
                };
                if let Some(&i) = open.last() {
                    elems[i].text.push_str(&resolved);
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    assert!(open.is_empty(), "unclosed elements at the end");
    assert_eq!(elems.first().map(|e| e.name.as_str()), Some("svg"));
    for e in &mut elems {
        e.text = e.text.trim().to_string();
    }
    elems
}

fn named<'a>(elems: &'a [Elem], name: &str) -> Vec<&'a Elem> {
    elems.iter().filter(|e| e.name == name).collect()
}

fn texts(elems: &[Elem]) -> Vec<&str> {
    named(elems, "text")
        .iter()
        .map(|e| e.text.as_str())
        .collect()
}

fn has_text(elems: &[Elem], wanted: &str) -> bool {
    texts(elems).contains(&wanted)
}

/// The y-axis tick labels (right-aligned numbers): (value, pixel y).
fn y_ticks(elems: &[Elem]) -> Vec<(f64, f64)> {
    named(elems, "text")
        .iter()
        .filter(|t| t.attr("text-anchor") == "end")
        .filter_map(|t| Some((t.text.parse::<f64>().ok()?, t.num("y"))))
        .collect()
}

/// The linear map `pixel = a·value + b` through two (value, pixel) pairs.
fn linear((v0, p0): (f64, f64), (v1, p1): (f64, f64)) -> impl Fn(f64) -> f64 {
    let a = (p1 - p0) / (v1 - v0);
    move |v| p0 + a * (v - v0)
}

// ---------------------------------------------------------------------------------------------
// Inputs.

const SAMPLES: usize = 201;
const DURATION_S: f64 = 4.0;

/// Joint `j` at `t` (deg): a sine each, inside the Viper s850's limits.
fn joint_deg(j: usize, t: f64) -> f64 {
    let (center, amplitude, freq_hz, phase) = [
        (0.0, 90.0, 0.25, 0.0),
        (-60.0, 40.0, 0.5, 0.3),
        (100.0, 60.0, 0.25, 1.0),
        (0.0, 150.0, 0.125, 0.0),
        (30.0, 60.0, 0.375, 2.0),
        (-100.0, 200.0, 0.2, 0.5),
    ][j];
    center + amplitude * (2.0 * PI * freq_hz * t + phase).sin()
}

fn time(i: usize) -> f64 {
    DURATION_S * i as f64 / (SAMPLES - 1) as f64
}

fn motion() -> Motion {
    let robot = Robot::from_urdf_file(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/robots/viper_s850/viper_s850.urdf"
    ))
    .expect("bundled robot");
    let times: Vec<f64> = (0..SAMPLES).map(time).collect();
    let samples = times
        .iter()
        .map(|&t| (0..6).map(|j| joint_deg(j, t).to_radians()).collect())
        .collect();
    Motion::new(&robot, times, samples).expect("valid motion")
}

fn pose(sample: usize, reason: &str) -> PoseSummary {
    let t = time(sample);
    PoseSummary {
        motion: 0,
        sample,
        time_s: t,
        joints: (0..6).map(|j| joint_deg(j, t)).collect(),
        reason: reason.into(),
    }
}

fn segment(
    name: &str,
    kind: &'static str,
    joints: &[&str],
    poses: Vec<PoseSummary>,
    d: [usize; 4],
) -> SegmentReport {
    SegmentReport {
        segment: name.into(),
        from_guide: "G1".into(),
        to_guide: "G2".into(),
        kind,
        traversed_joints: joints.iter().map(|s| s.to_string()).collect(),
        test_poses: poses,
        d0: d[0],
        d0_pruned: d[1],
        d1: d[2],
        d2: d[3],
        rejections: BTreeMap::new(),
        evaluations: 0,
        static_solves: 0,
    }
}

/// C1 and C3 inter-link (2 × 3 and 2 × 2 markers), C2 intra-link (not marked).
fn segments() -> Vec<SegmentReport> {
    vec![
        segment(
            "C1",
            "inter-link",
            &["joint_2", "joint_3"],
            vec![pose(0, "start"), pose(37, "joint_2 max"), pose(150, "end")],
            [4800, 2300, 310, 42],
        ),
        segment(
            "C2",
            "intra-link",
            &[],
            vec![pose(60, "gravity"), pose(61, "gravity")],
            [1200, 1200, 57, 9],
        ),
        segment(
            "C3",
            "inter-link",
            &["joint_4", "joint_5"],
            vec![pose(90, "joint_4 max"), pose(170, "joint_5 min")],
            [5000, 800, 3, 0],
        ),
    ]
}

// ---------------------------------------------------------------------------------------------
// joints.svg

#[test]
fn joints_svg_draws_every_sample_and_marks_the_inter_link_test_poses() {
    let motion = motion();
    let segments = segments();
    let svg = joints_svg(&motion, &segments, "joint angles").expect("plot");
    std::fs::write(std::env::temp_dir().join("cable_dict_joints.svg"), &svg).ok();
    let elems = parse(&svg);
    assert_eq!(
        svg,
        joints_svg(&motion, &segments, "joint angles").expect("plot")
    );

    for name in ["joint angles", "joint_1", "joint_6", "C1", "C3", "time (s)"] {
        assert!(has_text(&elems, name), "no text {name:?}");
    }
    assert!(!has_text(&elems, "C2"), "intra-link segment in the legend");

    let curves: Vec<Vec<(f64, f64)>> = named(&elems, "polyline")
        .iter()
        .map(|p| p.points())
        .filter(|p| p.len() == SAMPLES)
        .collect();
    assert_eq!(curves.len(), 6, "one polyline per joint with every sample");

    // Axis transform from two points: time from joint 1's first and last sample, angle from
    // the lowest and the highest reference value over all joints.
    let x = linear(
        (time(0), curves[0][0].0),
        (DURATION_S, curves[0][SAMPLES - 1].0),
    );
    let all = (0..6).flat_map(|j| (0..SAMPLES).map(move |i| (j, i)));
    let value = |&(j, i): &(usize, usize)| joint_deg(j, time(i));
    let lo = all
        .clone()
        .min_by(|a, b| value(a).total_cmp(&value(b)))
        .expect("samples");
    let hi = all
        .clone()
        .max_by(|a, b| value(a).total_cmp(&value(b)))
        .expect("samples");
    let y = linear(
        (value(&lo), curves[lo.0][lo.1].1),
        (value(&hi), curves[hi.0][hi.1].1),
    );
    assert!(y(1.0) < y(0.0), "angles grow upwards");
    // The axis is in degrees: the tick labels sit where the curves put their values.
    let ticks = y_ticks(&elems);
    assert!(ticks.len() >= 4, "{ticks:?}");
    for &(deg, py) in &ticks {
        assert!(
            (py - y(deg)).abs() <= 1.5,
            "tick {deg} at y {py}, want {}",
            y(deg)
        );
    }
    for (j, curve) in curves.iter().enumerate() {
        for (i, &(px, py)) in curve.iter().enumerate() {
            let (t, deg) = (time(i), joint_deg(j, time(i)));
            assert!(
                (px - x(t)).abs() <= 1.0,
                "joint {j} sample {i}: x {px} vs {}",
                x(t)
            );
            assert!(
                (py - y(deg)).abs() <= 1.0,
                "joint {j} sample {i}: y {py} vs {}",
                y(deg)
            );
        }
    }

    // Markers: one filled circle per (test pose × traversed joint) of the inter-link
    // segments, on the joint's curve at the pose's sample; one colour per segment.
    let on_curve = |c: &&Elem| {
        let p = (c.num("cx"), c.num("cy"));
        curves
            .iter()
            .flatten()
            .any(|q| (p.0 - q.0).abs() <= 1.0 && (p.1 - q.1).abs() <= 1.0)
    };
    let circles = named(&elems, "circle");
    let markers: Vec<&Elem> = circles
        .iter()
        .copied()
        .filter(|c| c.filled())
        .filter(on_curve)
        .collect();
    let expected: Vec<(&str, usize, usize)> = segments
        .iter()
        .filter(|s| s.kind == "inter-link")
        .flat_map(|s| {
            s.test_poses.iter().flat_map(move |p| {
                s.traversed_joints.iter().map(move |name| {
                    let j = name["joint_".len()..]
                        .parse::<usize>()
                        .expect("joint number")
                        - 1;
                    (s.segment.as_str(), j, p.sample)
                })
            })
        })
        .collect();
    assert_eq!(expected.len(), 10);
    assert_eq!(markers.len(), expected.len(), "markers on the curves");
    let mut fills: BTreeMap<&str, Vec<String>> = BTreeMap::new();
    for &(seg, j, i) in &expected {
        let (px, py) = (x(time(i)), y(joint_deg(j, time(i))));
        let found = markers
            .iter()
            .find(|c| (c.num("cx") - px).abs() <= 1.0 && (c.num("cy") - py).abs() <= 1.0)
            .unwrap_or_else(|| panic!("no marker of {seg} on joint {} at sample {i}", j + 1));
        fills
            .entry(seg)
            .or_default()
            .push(found.attr("fill").to_string());
    }
    for list in fills.values() {
        assert!(list.iter().all(|f| f == &list[0]), "one colour per segment");
    }
    assert_ne!(fills["C1"][0], fills["C3"][0], "segments differ in colour");

    // A dashed vertical line at every inter-link test pose's time, none at C2's.
    let vertical_xs: Vec<f64> = named(&elems, "polyline")
        .iter()
        .map(|p| p.points())
        .filter(|p| p.len() == 2 && p[0].0 == p[1].0 && p[0].1 != p[1].1)
        .map(|p| p[0].0)
        .collect();
    for &(_, _, i) in &expected {
        assert!(
            vertical_xs.iter().any(|&vx| (vx - x(time(i))).abs() <= 1.0),
            "line at sample {i}"
        );
    }
    for i in [60, 61] {
        assert!(
            !vertical_xs.iter().any(|&vx| (vx - x(time(i))).abs() <= 1.0),
            "C2 marked"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// stress.svg

const SERIES: usize = 151;
const CLEARANCE_MIN_MM: f64 = 3.2;
const CLEARANCE_MIN_T: f64 = 1.24;

fn series_time(i: usize) -> f64 {
    0.02 * i as f64
}

/// Clearance (mm): a parabola with its minimum 3.2 mm at 1.24 s; not checked at t = 0.
fn clearance_mm(i: usize) -> Option<f64> {
    let t = series_time(i);
    (i > 0).then(|| CLEARANCE_MIN_MM + 5.0 * (t - CLEARANCE_MIN_T).powi(2))
}

fn stretch(i: usize) -> f64 {
    1.0 + 0.01 * (PI * series_time(i) / 3.0).sin()
}

/// Bend radius (mm): straight (∞) for t < 0.3 s, then a parabola with its minimum 50 mm at 2 s.
fn bend_mm(i: usize) -> f64 {
    let t = series_time(i);
    if t < 0.3 {
        f64::INFINITY
    } else {
        50.0 + 40.0 * (t - 2.0).powi(2)
    }
}

fn thresholds(clearance_mm: f64) -> Thresholds {
    Thresholds {
        contact_clearance_m: clearance_mm * 1e-3,
        stretch: 1.05,
        min_bend_radius_m: 0.03,
        min_bend_radius_source: BendRadiusSource::Setup,
        clamp_zone_m: 0.02,
        static_bend_margin_m: 0.0,
        cable_flexing_bend_radius_m: None,
        torsion_limit_deg_per_m: None,
        flexing_curvature_change_per_m: 1.0,
    }
}

fn worst(value: f64, unit: &'static str, time_s: f64, segment: usize) -> Option<Worst> {
    Some(Worst {
        value,
        unit,
        time_s,
        segment,
        segment_name: format!("C{}", segment + 1),
        place: Place::default(),
    })
}

/// A passing test over the first `points` series entries.
fn stress_report(points: usize) -> MotionTestReport {
    let series = (0..points)
        .map(|i| SeriesPoint {
            time_s: series_time(i),
            min_clearance_m: clearance_mm(i).map(|c| c * 1e-3),
            max_stretch: stretch(i),
            min_bend_radius_m: bend_mm(i) * 1e-3,
            max_contact_force_n: 0.0,
            max_twist_deg_per_m: None,
            max_clamp_force_n: None,
        })
        .collect();
    MotionTestReport {
        passed: true,
        failure: None,
        first_violation: None,
        worst_clearance: worst(CLEARANCE_MIN_MM * 1e-3, "m", CLEARANCE_MIN_T, 2),
        worst_stretch: worst(1.01, "1", 1.5, 0),
        worst_twist: None,
        worst_bend: worst(0.05, "m", 2.0, 1),
        worst_contact_force: None,
        worst_self_clearance: None,
        pieces: Vec::new(),
        twists: Vec::new(),
        damage: Vec::new(),
        clamp_loads: Vec::new(),
        clamp_turns: Vec::new(),
        slides: Vec::new(),
        max_joint_gap_m: 1e-4,
        series,
        final_shape: Vec::new(),
        shapes: Vec::new(),
        motion_duration_s: 3.0,
        steps: points,
        simulated_s: series_time(points.max(1) - 1),
        wall_time_s: 1.0,
    }
}

/// The test failing at the first instant the clearance is below `limit_mm` (or, for
/// `ContactForce`, with a contact force there): the series stop at that instant.
fn failing_report(limit_mm: f64, constraint: Constraint) -> (MotionTestReport, usize) {
    let i = (1..SERIES)
        .find(|&i| clearance_mm(i).is_some_and(|c| c < limit_mm))
        .expect("a violation");
    let mut report = stress_report(i + 1);
    let (value, threshold, unit) = match constraint {
        Constraint::ContactForce => (0.125, 0.0, "N"),
        _ => (clearance_mm(i).unwrap_or(0.0) * 1e-3, limit_mm * 1e-3, "m"),
    };
    let violation = Violation {
        constraint,
        value,
        threshold,
        unit,
        time_s: series_time(i),
        segment: 2,
        segment_name: "C3".into(),
        place: Place::default(),
    };
    report.passed = false;
    report.failure = Some(Failure {
        cause: FailureCause::Violation,
        reason: violation.to_string(),
        segment: Some(2),
    });
    report.first_violation = Some(violation);
    report.worst_clearance = worst(
        clearance_mm(i).unwrap_or(0.0) * 1e-3,
        "m",
        series_time(i),
        2,
    );
    report.worst_stretch = worst(stretch(i), "1", series_time(i), 0);
    report.worst_bend = worst(bend_mm(i) * 1e-3, "m", series_time(i), 1);
    (report, i)
}

/// The three series polylines (more than 2 vertices), in panel order.
fn series_lines(elems: &[Elem]) -> Vec<Vec<(f64, f64)>> {
    named(elems, "polyline")
        .iter()
        .map(|p| p.points())
        .filter(|p| p.len() > 2)
        .collect()
}

/// Red 2-vertex polylines: (horizontal y values, vertical (x, y range)).
fn red_lines(elems: &[Elem]) -> (Vec<f64>, Vec<(f64, f64, f64)>) {
    let mut horizontal = Vec::new();
    let mut vertical = Vec::new();
    for p in named(elems, "polyline") {
        let pts = p.points();
        if pts.len() != 2 || !p.stroke().is_some_and(is_red) {
            continue;
        }
        if pts[0].1 == pts[1].1 {
            horizontal.push(pts[0].1);
        } else if pts[0].0 == pts[1].0 {
            vertical.push((pts[0].0, pts[0].1.min(pts[1].1), pts[0].1.max(pts[1].1)));
        }
    }
    (horizontal, vertical)
}

/// `pixel = f(value)` of a panel from the vertices of its lowest and highest `values`.
fn panel_y(line: &[(f64, f64)], values: &[f64]) -> impl Fn(f64) -> f64 {
    let lo = (0..values.len())
        .min_by(|&a, &b| values[a].total_cmp(&values[b]))
        .expect("values");
    let hi = (0..values.len())
        .max_by(|&a, &b| values[a].total_cmp(&values[b]))
        .expect("values");
    linear((values[lo], line[lo].1), (values[hi], line[hi].1))
}

#[test]
fn stress_svg_draws_series_limits_and_worst_instants() {
    let report = stress_report(SERIES);
    let limits = thresholds(2.0);
    let svg = stress_svg(&report, &limits, "motion test", &Default::default()).expect("plot");
    std::fs::write(std::env::temp_dir().join("cable_dict_stress.svg"), &svg).ok();
    assert_eq!(
        svg,
        stress_svg(&report, &limits, "motion test", &Default::default()).expect("plot")
    );
    let elems = parse(&svg);
    assert!(has_text(&elems, "motion test"));
    assert!(texts(&elems).iter().any(|t| t.contains("passed")));
    assert!(!texts(&elems).iter().any(|t| t.contains("FAILED")));

    // One vertex per drawn entry: the clearance has no value at t = 0, the infinite bend
    // radii are clipped, not dropped.
    let lines = series_lines(&elems);
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[0].len(), SERIES - 1);
    assert_eq!(lines[1].len(), SERIES);
    assert_eq!(lines[2].len(), SERIES);

    let clearance: Vec<f64> = (1..SERIES).filter_map(clearance_mm).collect();
    let stretches: Vec<f64> = (0..SERIES).map(stretch).collect();
    let cap_mm = 5.0 * 30.0;
    let bends: Vec<f64> = (0..SERIES).map(|i| bend_mm(i).min(cap_mm)).collect();
    let ys = [
        panel_y(&lines[0], &clearance),
        panel_y(&lines[1], &stretches),
        panel_y(&lines[2], &bends),
    ];
    for (line, (values, y)) in lines
        .iter()
        .zip([&clearance, &stretches, &bends].iter().zip(&ys))
    {
        for (&(_, py), &v) in line.iter().zip(values.iter()) {
            assert!((py - y(v)).abs() <= 1.5, "vertex {py} vs {}", y(v));
        }
    }
    assert!(bend_mm(0).is_infinite() && (lines[2][0].1 - ys[2](cap_mm)).abs() <= 1.0);
    // Units (mm, 1, mm): every tick label sits where its panel's curve puts that value.
    let ticks = y_ticks(&elems);
    for (p, y) in ys.iter().enumerate() {
        let matching = ticks
            .iter()
            .filter(|&&(v, py)| (py - y(v)).abs() <= 1.5)
            .count();
        assert!(
            matching >= 3,
            "panel {p}: {matching} ticks match in {ticks:?}"
        );
    }
    for &(v, py) in &ticks {
        assert!(
            ys.iter().any(|y| (py - y(v)).abs() <= 1.5),
            "tick {v} at {py} fits no panel"
        );
    }

    // The three limits: red dashes at the limit's height in each panel.
    let (horizontal, vertical) = red_lines(&elems);
    assert!(vertical.is_empty(), "no violation line for a passing test");
    for (y, limit) in ys.iter().zip([2.0, 1.05, 30.0]) {
        let at = y(limit);
        let dashes = horizontal
            .iter()
            .filter(|&&h| (h - at).abs() <= 1.5)
            .count();
        let mut heights = horizontal.clone();
        heights.dedup();
        assert!(
            dashes >= 5,
            "limit {limit}: {dashes} dashes at y {at}; red at {heights:?}"
        );
    }
    for label in ["limit 2.0 mm", "limit 1.05", "limit 30.0 mm"] {
        assert!(has_text(&elems, label), "no {label:?}");
    }

    // The worst instants, labelled with value, time and segment, ringed on the curve.
    for label in [
        "worst 3.20 mm at 1.240 s (C3)",
        "worst 1.0100 at 1.500 s (C1)",
        "worst 50.00 mm at 2.000 s (C2)",
    ] {
        assert!(
            texts(&elems).iter().any(|t| t.contains(label)),
            "no {label:?} in {:?}",
            texts(&elems)
        );
    }
    let x = linear(
        (series_time(1), lines[0][0].0),
        (series_time(SERIES - 1), lines[0][SERIES - 2].0),
    );
    let (wx, wy) = (x(CLEARANCE_MIN_T), ys[0](CLEARANCE_MIN_MM));
    assert!(
        named(&elems, "circle")
            .iter()
            .any(|c| (c.num("cx") - wx).abs() <= 1.5 && (c.num("cy") - wy).abs() <= 1.5),
        "no ring at the worst clearance ({wx}, {wy})"
    );
}

#[test]
fn stress_svg_marks_the_first_violation_of_a_failed_test() {
    let limit_mm = 5.0;
    let (report, last) = failing_report(limit_mm, Constraint::Contact);
    let svg = stress_svg(
        &report,
        &thresholds(limit_mm),
        "motion test",
        &Default::default(),
    )
    .expect("plot");
    std::fs::write(
        std::env::temp_dir().join("cable_dict_stress_failed.svg"),
        &svg,
    )
    .ok();
    let elems = parse(&svg);
    let all = texts(&elems);

    let reason = report
        .failure
        .as_ref()
        .map(|f| f.reason.clone())
        .unwrap_or_default();
    assert!(
        all.iter()
            .any(|t| t.contains("FAILED") && t.contains(&reason)),
        "{all:?}"
    );
    let t_v = series_time(last);
    let value_mm = clearance_mm(last).unwrap_or(0.0);
    let label = format!("violation: contact {value_mm:.2} mm at {t_v:.3} s (C3)");
    assert!(all.contains(&label.as_str()), "no {label:?} in {all:?}");

    // The series end at the violation.
    let lines = series_lines(&elems);
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[0].len(), last);
    assert_eq!(lines[1].len(), last + 1);

    // A red vertical line at the violation's time, spanning the clearance panel.
    let x = linear((series_time(1), lines[0][0].0), (t_v, lines[0][last - 1].0));
    let (_, vertical) = red_lines(&elems);
    assert_eq!(vertical.len(), 1, "{vertical:?}");
    let (vx, top, bottom) = vertical[0];
    assert!(
        (vx - x(t_v)).abs() <= 1.0,
        "violation line at x {vx}, want {}",
        x(t_v)
    );
    assert!(
        lines[0].iter().all(|&(_, y)| top <= y && y <= bottom),
        "not in the clearance panel"
    );
    assert!(
        lines[1].iter().all(|&(_, y)| y > bottom),
        "stretch panel below"
    );
}

#[test]
fn stress_svg_puts_a_contact_force_violation_in_the_clearance_panel() {
    let (report, last) = failing_report(5.0, Constraint::ContactForce);
    let svg = stress_svg(&report, &thresholds(5.0), "force", &Default::default()).expect("plot");
    let elems = parse(&svg);
    let label = format!(
        "violation: contact force 0.125 N at {:.3} s (C3)",
        series_time(last)
    );
    assert!(has_text(&elems, &label), "no {label:?}");
    let lines = series_lines(&elems);
    let (_, vertical) = red_lines(&elems);
    assert_eq!(vertical.len(), 1);
    let (_, top, bottom) = vertical[0];
    assert!(lines[0].iter().all(|&(_, y)| top <= y && y <= bottom));
}

#[test]
fn stress_svg_refuses_an_empty_series() {
    let report = stress_report(0);
    let result = stress_svg(&report, &thresholds(2.0), "empty", &Default::default());
    assert!(matches!(result, Err(PlotError::Empty(_))), "{result:?}");
}

// ---------------------------------------------------------------------------------------------
// sets.svg

#[test]
fn sets_svg_draws_log_scaled_bars_with_their_counts() {
    let segments = segments();
    let svg = sets_svg(&segments, "set sizes").expect("plot");
    std::fs::write(std::env::temp_dir().join("cable_dict_sets.svg"), &svg).ok();
    assert_eq!(svg, sets_svg(&segments, "set sizes").expect("plot"));
    let elems = parse(&svg);
    for name in [
        "set sizes",
        "C1",
        "C2",
        "C3",
        "candidates",
        "after pruning",
        "hold the limits",
        "robust",
    ] {
        assert!(has_text(&elems, name), "no text {name:?}");
    }
    let counts: Vec<usize> = segments
        .iter()
        .flat_map(|s| [s.d0, s.d0_pruned, s.d1, s.d2])
        .collect();
    for c in &counts {
        assert!(has_text(&elems, &c.to_string()), "no label {c}");
    }

    // Bars: the filled rectangles standing on the common baseline (the most frequent bottom
    // edge), one per non-zero count, left to right in segment and set order.
    let rects: Vec<&Elem> = named(&elems, "rect")
        .into_iter()
        .filter(|r| r.filled())
        .collect();
    let bottom = |r: &&Elem| (r.num("y") + r.num("height")) as i64;
    let mut tally: BTreeMap<i64, usize> = BTreeMap::new();
    for r in &rects {
        *tally.entry(bottom(r)).or_default() += 1;
    }
    let baseline = tally
        .iter()
        .max_by_key(|(_, n)| **n)
        .map(|(b, _)| *b)
        .expect("rects");
    let mut bars: Vec<&Elem> = rects
        .into_iter()
        .filter(|r| bottom(r) == baseline)
        .collect();
    bars.sort_by(|a, b| a.num("x").total_cmp(&b.num("x")));
    let nonzero: Vec<usize> = counts.iter().copied().filter(|&c| c > 0).collect();
    assert_eq!(bars.len(), nonzero.len(), "one bar per non-zero count");
    assert_eq!(nonzero.len(), 4 * segments.len() - 1);

    // Heights from the common baseline grow as log10 of the counts: fitted on the largest and
    // smallest count, every other bar within a pixel and a half.
    let heights: Vec<f64> = bars.iter().map(|r| r.num("height")).collect();
    let lo = (0..nonzero.len())
        .min_by_key(|&i| nonzero[i])
        .expect("bars");
    let hi = (0..nonzero.len())
        .max_by_key(|&i| nonzero[i])
        .expect("bars");
    let h = linear(
        ((nonzero[lo] as f64).log10(), heights[lo]),
        ((nonzero[hi] as f64).log10(), heights[hi]),
    );
    for (&c, &height) in nonzero.iter().zip(&heights) {
        let want = h((c as f64).log10());
        assert!(
            (height - want).abs() <= 1.5,
            "count {c}: height {height}, want {want}"
        );
    }
    assert!(heights[lo] > 0.0, "a count of 3 has a visible bar");
    // Against the axis: the tick labels 1, 10, 100, … fix pixel = a·log10(value) + b; every
    // bar's top sits at its count.
    let ticks = y_ticks(&elems);
    assert!(ticks.len() >= 4, "{ticks:?}");
    let (first, last) = (ticks[0], ticks[ticks.len() - 1]);
    let y = linear((first.0.log10(), first.1), (last.0.log10(), last.1));
    for &(v, py) in &ticks {
        assert!(
            (py - y(v.log10())).abs() <= 1.0,
            "tick {v} not on a log axis"
        );
    }
    for (bar, &c) in bars.iter().zip(&nonzero) {
        let top = bar.num("y");
        let want = y((c as f64).log10());
        assert!(
            (top - want).abs() <= 1.5,
            "count {c}: top {top}, want {want}"
        );
    }

    // One colour per set: bars of the same set share it, the four differ.
    let fill = |i: usize| bars[i].attr("fill");
    assert_eq!(fill(0), fill(4));
    assert_eq!(fill(1), fill(5));
    let distinct: std::collections::BTreeSet<&str> = (0..4).map(fill).collect();
    assert_eq!(distinct.len(), 4);
}

#[test]
fn sets_svg_refuses_no_segments() {
    assert!(matches!(sets_svg(&[], "none"), Err(PlotError::Empty(_))));
}

#[test]
fn sets_svg_turns_labels_wider_than_their_bar() {
    let segments: Vec<SegmentReport> = (1..=10)
        .map(|i| {
            let name = format!("C{i}");
            segment(
                &name,
                "inter-link",
                &[],
                vec![],
                [123_456, 54_321, 987, 12 * i],
            )
        })
        .collect();
    let svg = sets_svg(&segments, "many segments").expect("plot");
    std::fs::write(std::env::temp_dir().join("cable_dict_sets_many.svg"), &svg).ok();
    let elems = parse(&svg);
    let label = named(&elems, "text")
        .into_iter()
        .find(|t| t.text == "123456")
        .expect("label of |D0|");
    assert!(
        label.attr("transform").starts_with("rotate(270"),
        "{label:?}"
    );
    let short = named(&elems, "text")
        .into_iter()
        .find(|t| t.text == "12")
        .expect("label of C1's |D2|");
    assert!(
        short.attr("transform").starts_with("rotate(270"),
        "all turn alike"
    );

    let few = parse(&sets_svg(&self::segments(), "few").expect("plot"));
    let label = named(&few, "text")
        .into_iter()
        .find(|t| t.text == "4800")
        .expect("label");
    assert_eq!(
        label.attr("transform"),
        "",
        "labels that fit stay horizontal"
    );
}

/// Long joint names are shown whole: the legend widens the plot instead of running off its
/// edge. A legend label starts at its `x` and needs at least 8 px per character
/// of 16 px text; it must end inside the picture.
#[test]
fn joints_svg_legend_fits_long_joint_names() {
    let urdf = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/robots/viper_s850/viper_s850.urdf"
    ))
    .expect("bundled robot");
    let long = |j: usize| format!("left_arm_assembly_shoulder_and_wrist_axis_{j}_joint");
    let mut renamed = urdf.clone();
    for j in 1..=6 {
        renamed = renamed.replace(&format!("\"joint_{j}\""), &format!("\"{}\"", long(j)));
    }
    let robot = Robot::from_urdf_str(&renamed, std::path::Path::new("long.urdf")).expect("robot");
    let times: Vec<f64> = (0..SAMPLES).map(time).collect();
    let samples = times
        .iter()
        .map(|&t| (0..6).map(|j| joint_deg(j, t).to_radians()).collect())
        .collect();
    let motion = Motion::new(&robot, times, samples).expect("valid motion");
    let svg = joints_svg(&motion, &[], "joint angles").expect("plot");
    let elems = parse(&svg);
    let width: f64 = named(&elems, "svg")[0]
        .attr("width")
        .trim_end_matches("px")
        .parse()
        .expect("width");
    for j in 1..=6 {
        let name = long(j);
        let label = elems
            .iter()
            .find(|e| e.name == "text" && e.text == name)
            .unwrap_or_else(|| panic!("{name} shown whole"));
        let end = label.num("x") + 8.0 * name.chars().count() as f64;
        assert!(
            end <= width,
            "{name} ends at {end} px, the picture is {width} px wide"
        );
    }
}
