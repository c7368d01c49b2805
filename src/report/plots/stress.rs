//! `stress.svg`: the motion test's stress series — clearance, stretch, bend radius — over
//! time, each against its limit, with the worst instants and the first violation marked;
//! then the largest twist per metre of a piece and the largest force on a clamp, which have
//! no limit here.

use super::{
    LIMIT_RED, PlotError, PlotNames, Root, draw_error, finite_range, font, padded, render, short,
    text,
};
use crate::motion_test::{Constraint, GuideSlide, MotionTestReport, SlidePoint, Violation, Worst};
use crate::setup::Thresholds;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Size of the plot (px).
const SIZE: (u32, u32) = (1000, 1400);
/// Height of the title and verdict above the panels (px).
const HEAD_PX: u32 = 72;
/// Room right of each plotting area for the limit's label (px).
const RIGHT_PX: u32 = 125;
/// Bend radii above this many times the limit are drawn at it (a straight cable's is ∞).
const BEND_CLIP_FACTOR: f64 = 5.0;
/// Longest failure reason shown in full (characters).
const MAX_REASON_CHARS: usize = 110;

/// One stacked panel, values in plot units (mm or dimensionless).
struct Panel {
    /// Header, e.g. `min clearance`.
    name: String,
    /// Y axis label with unit.
    y_desc: String,
    /// (time s, value) per series entry; `None` (nothing to draw) breaks the line.
    points: Vec<Option<(f64, f64)>>,
    color: RGBColor,
    /// The limit and its label; `None` for a value without a limit.
    limit: Option<f64>,
    limit_label: String,
    /// (time s, value, label) of the worst instant.
    worst: Option<(f64, f64, String)>,
    /// (time s, label) of the first violation when it belongs to this panel.
    violation: Option<(f64, String)>,
}

/// `stress.svg`: three stacked panels over the motion test's time axis — min clearance (mm),
/// max stretch, min bend radius (mm, clipped at 5× the limit) — each with its limit from
/// `thresholds` as a red dashed line and its worst instant marked and labelled. A failed
/// test marks its first violation with a red vertical line in the panel of its constraint
/// (contact force in the clearance panel) and says FAILED with the reason under the title.
/// The series of a failed candidate stop early: the curves end there.
pub fn stress_svg(
    test: &MotionTestReport,
    thresholds: &Thresholds,
    title: &str,
    names: &PlotNames,
) -> Result<String, PlotError> {
    let times = test.series.iter().map(|p| p.time_s);
    let (t0, t_last) = finite_range(times).ok_or(PlotError::Empty("no stress series"))?;
    let t1 = t_last.max(t0 + test.motion_duration_s);
    let (t0, t1) = if t1 > t0 {
        (t0, t1)
    } else {
        padded(t0, t1, 0.0)
    };
    let panels = panels(test, thresholds, names);
    // Five panels fill the page; more (sliding guides, retractions) lengthen it.
    let height = SIZE
        .1
        .max(HEAD_PX + (SIZE.1 - HEAD_PX) / 5 * panels.len() as u32);
    render((SIZE.0, height), |root| {
        draw_head(root, test, title, names)?;
        let (_, body) = root.split_vertically(HEAD_PX);
        let areas = body.split_evenly((panels.len(), 1));
        for (i, (panel, area)) in panels.iter().zip(&areas).enumerate() {
            let last = i + 1 == panels.len();
            draw_panel(root, area, panel, (t0, t1), last)?;
        }
        Ok(())
    })
}

/// The panels: the three limits, then twist and clamp force when the engine measured them.
fn panels(test: &MotionTestReport, thresholds: &Thresholds, names: &PlotNames) -> Vec<Panel> {
    let mut panels = vec![
        clearance_panel(test, thresholds, names),
        stretch_panel(test, thresholds, names),
        bend_panel(test, thresholds, names),
    ];
    if test.series.iter().any(|p| p.max_twist_deg_per_m.is_some()) {
        panels.push(twist_panel(test, names));
    }
    if test.series.iter().any(|p| p.max_clamp_force_n.is_some()) {
        panels.push(clamp_force_panel(test, names));
    }
    let limit_panels = panels.len();
    panels.extend(test.slides.iter().flat_map(|s| slide_panels(s, names)));
    if let Some(v) = test.first_violation.as_ref().filter(|_| !test.passed) {
        let i = match v.constraint {
            // The cable touching itself is contact too: shown in the clearance panel.
            Constraint::Contact | Constraint::ContactForce | Constraint::SelfContact => 0,
            Constraint::Stretch => 1,
            // A retraction out of travel: its travel panel.
            Constraint::Travel => (test.slides.iter())
                .position(|s| s.segment == v.segment && s.travel_max_m.is_some())
                .map_or(1, |k| limit_panels + slide_panel_index(test, k)),
            Constraint::BendRadius | Constraint::FlexingBendRadius => 2,
            // The twist panel follows the three limits when the engine measured twist.
            Constraint::Twist => 3.min(limit_panels - 1),
        };
        panels[i].violation = Some((v.time_s, violation_label(v, names)));
    }
    panels
}

/// The panels of a sliding guide (the cable before it, mm) or a retraction (its travel against
/// its stops, mm; its spring's force, N), over the motion.
fn slide_panels(slide: &GuideSlide, names: &PlotNames) -> Vec<Panel> {
    let piece = names.piece(&slide.segment_name);
    // Safe in SVG text, as the piece's name is.
    let guide = crate::escape::terminal(&slide.guide);
    let series = |value: &dyn Fn(&SlidePoint) -> Option<f64>| -> Vec<Option<(f64, f64)>> {
        (slide.series.iter())
            .map(|p| value(p).map(|v| (p.time_s, v)))
            .collect()
    };
    match slide.travel_max_m {
        None => vec![Panel {
            name: format!("cable before sliding guide {guide} ({piece})"),
            y_desc: "length (mm)".into(),
            points: series(&|p| Some(p.amount_m * 1e3)),
            color: RGBColor(127, 127, 127),
            limit: None,
            limit_label: String::new(),
            worst: Some((
                slide.most_time_s,
                slide.most_m * 1e3,
                format!("slid {:.0} mm", (slide.most_m - slide.least_m) * 1e3),
            )),
            violation: None,
        }],
        Some(travel) => vec![
            Panel {
                name: format!("travel of retraction {guide} ({piece})"),
                y_desc: "cable pulled out (mm)".into(),
                points: series(&|p| Some(p.amount_m * 1e3)),
                color: RGBColor(230, 90, 5),
                limit: Some(travel * 1e3),
                limit_label: format!("end stop {:.0} mm", travel * 1e3),
                worst: Some((
                    slide.most_time_s,
                    slide.most_m * 1e3,
                    format!("most {:.0} mm", slide.most_m * 1e3),
                )),
                violation: None,
            },
            Panel {
                name: format!("spring force of retraction {guide}"),
                y_desc: "force (N)".into(),
                points: series(&|p| p.force_n),
                color: RGBColor(140, 60, 10),
                limit: None,
                limit_label: String::new(),
                worst: slide
                    .peak_force_n
                    .map(|f| (slide.most_time_s, f, format!("up to {f:.2} N"))),
                violation: None,
            },
        ],
    }
}

/// Index among the slide panels of the first panel of slide `k` (a retraction has two).
fn slide_panel_index(test: &MotionTestReport, k: usize) -> usize {
    (test.slides.iter().take(k))
        .map(|s| 1 + usize::from(s.travel_max_m.is_some()))
        .sum()
}

/// The largest twist per metre of any piece (magnitude), from the cable as laid.
fn twist_panel(test: &MotionTestReport, names: &PlotNames) -> Panel {
    let worst = test
        .twists
        .iter()
        .max_by(|a, b| a.twist_deg_per_m.abs().total_cmp(&b.twist_deg_per_m.abs()))
        .map(|t| {
            let label = format!(
                "worst {:.0}°/m at {:.3} s ({})",
                t.twist_deg_per_m.abs(),
                t.time_s,
                names.piece(&t.segment_name)
            );
            (t.time_s, t.twist_deg_per_m.abs(), label)
        });
    Panel {
        name: "largest twist of a piece".into(),
        y_desc: "twist (deg/m, from the cable as laid)".into(),
        points: test
            .series
            .iter()
            .map(|p| p.max_twist_deg_per_m.map(|v| (p.time_s, v)))
            .collect(),
        color: RGBColor(214, 39, 40),
        limit: None,
        limit_label: String::new(),
        worst,
        violation: None,
    }
}

/// The largest force on any clamp, at the instants the loads were taken.
fn clamp_force_panel(test: &MotionTestReport, names: &PlotNames) -> Panel {
    let worst = test
        .clamp_loads
        .iter()
        .max_by(|a, b| a.max_force_n.total_cmp(&b.max_force_n))
        .map(|c| {
            let label = format!(
                "worst {:.2} N at {:.3} s ({})",
                c.max_force_n,
                c.force_time_s,
                names.clamp(&c.guides)
            );
            (c.force_time_s, c.max_force_n, label)
        });
    Panel {
        name: "largest force on a clamp".into(),
        y_desc: "force (N)".into(),
        points: test
            .series
            .iter()
            .filter_map(|p| p.max_clamp_force_n.map(|v| Some((p.time_s, v))))
            .collect(),
        color: RGBColor(140, 86, 75),
        limit: None,
        limit_label: String::new(),
        worst,
        violation: None,
    }
}

fn clearance_panel(test: &MotionTestReport, thresholds: &Thresholds, names: &PlotNames) -> Panel {
    let limit_mm = thresholds.contact_clearance_m * 1e3;
    Panel {
        name: "min clearance".into(),
        y_desc: "clearance (mm)".into(),
        points: test
            .series
            .iter()
            .map(|p| p.min_clearance_m.map(|c| (p.time_s, c * 1e3)))
            .collect(),
        color: RGBColor(31, 119, 180),
        limit: Some(limit_mm),
        limit_label: format!("limit {} mm", short(limit_mm, 1)),
        worst: worst(&test.worst_clearance, 1e3, f64::INFINITY, names, |v| {
            format!("{v:.2} mm")
        }),
        violation: None,
    }
}

fn stretch_panel(test: &MotionTestReport, thresholds: &Thresholds, names: &PlotNames) -> Panel {
    Panel {
        name: "max stretch".into(),
        y_desc: "stretch (length / natural length)".into(),
        points: test
            .series
            .iter()
            .map(|p| Some((p.time_s, p.max_stretch)))
            .collect(),
        color: RGBColor(44, 160, 44),
        limit: Some(thresholds.stretch),
        limit_label: format!("limit {}", short(thresholds.stretch, 2)),
        worst: worst(&test.worst_stretch, 1.0, f64::INFINITY, names, |v| {
            format!("{v:.4}")
        }),
        violation: None,
    }
}

/// Bend radii in mm, clipped at 5× the limit (or at the largest finite radius when the
/// limit is 0).
fn bend_panel(test: &MotionTestReport, thresholds: &Thresholds, names: &PlotNames) -> Panel {
    let limit_mm = thresholds.min_bend_radius_m * 1e3;
    let radii_mm = test.series.iter().map(|p| p.min_bend_radius_m * 1e3);
    let cap_mm = if limit_mm > 0.0 {
        BEND_CLIP_FACTOR * limit_mm
    } else {
        finite_range(radii_mm).map_or(1e3, |(_, hi)| hi.max(1.0))
    };
    Panel {
        name: "min bend radius".into(),
        y_desc: format!("bend radius (mm, clipped at {} mm)", short(cap_mm, 0)),
        points: test
            .series
            .iter()
            .map(|p| Some((p.time_s, (p.min_bend_radius_m * 1e3).min(cap_mm))))
            .collect(),
        color: RGBColor(148, 103, 189),
        limit: Some(limit_mm),
        limit_label: format!("limit {} mm", short(limit_mm, 1)),
        worst: worst(&test.worst_bend, 1e3, cap_mm, names, |v| {
            format!("{v:.2} mm")
        }),
        violation: None,
    }
}

/// The worst instant in plot units (`scale`, drawn at most at `cap`) with its label
/// `worst 3.20 mm at 1.234 s (C3)`.
fn worst(
    worst: &Option<Worst>,
    scale: f64,
    cap: f64,
    names: &PlotNames,
    value: impl Fn(f64) -> String,
) -> Option<(f64, f64, String)> {
    let w = worst.as_ref()?;
    let v = w.value * scale;
    let label = format!(
        "worst {} at {:.3} s ({})",
        value(v),
        w.time_s,
        names.piece(&w.segment_name)
    );
    Some((w.time_s, v.min(cap), label))
}

/// `violation: contact -3.20 mm at 1.238 s (piece 2 → 3)`.
fn violation_label(v: &Violation, names: &PlotNames) -> String {
    let value = match v.unit {
        "m" => format!("{:.2} mm", v.value * 1e3),
        "N" => format!("{:.3} N", v.value),
        _ => format!("{:.4}", v.value),
    };
    format!(
        "violation: {} {value} at {:.3} s ({})",
        v.constraint,
        v.time_s,
        names.piece(&v.segment_name)
    )
}

/// Title, and the verdict under it: `passed`, or `FAILED: reason` in red.
fn draw_head(
    root: &Root<'_>,
    test: &MotionTestReport,
    title: &str,
    names: &PlotNames,
) -> Result<(), PlotError> {
    let center = SIZE.0 as i32 / 2;
    let top = (HPos::Center, VPos::Top);
    text(root, title, (center, 10), &font(26.0), top)?;
    let (verdict, color) = match (&test.failure, test.passed) {
        (_, true) => ("motion test passed".to_string(), RGBColor(0, 120, 0)),
        (Some(f), false) => {
            let reason = names.failure().unwrap_or_else(|| f.reason.clone());
            (format!("FAILED: {}", clip(&reason)), LIMIT_RED)
        }
        (None, false) => ("FAILED".to_string(), LIMIT_RED),
    };
    text(root, &verdict, (center, 42), &font(18.0).color(&color), top)
}

/// `reason`, cut to [`MAX_REASON_CHARS`] with an ellipsis.
fn clip(reason: &str) -> String {
    if reason.chars().count() <= MAX_REASON_CHARS {
        return reason.to_string();
    }
    let cut: String = reason.chars().take(MAX_REASON_CHARS - 1).collect();
    format!("{cut}…")
}

/// One panel in `area`: series, limit, worst instant, violation; texts on `root` (absolute
/// pixels). Only the `last` (bottom) panel names the time axis.
fn draw_panel(
    root: &Root<'_>,
    area: &Root<'_>,
    panel: &Panel,
    (t0, t1): (f64, f64),
    last: bool,
) -> Result<(), PlotError> {
    let values = panel.points.iter().flatten().map(|p| p.1);
    let extra = [panel.limit, panel.worst.as_ref().map(|w| w.1)];
    let (y0, y1) = finite_range(values.chain(extra.into_iter().flatten()))
        .map_or((0.0, 1.0), |(lo, hi)| padded(lo, hi, 0.08));
    let mut chart = ChartBuilder::on(area)
        .margin_top(30)
        .margin_left(15)
        .margin_right(RIGHT_PX)
        .margin_bottom(if last { 10 } else { 4 })
        .x_label_area_size(if last { 50 } else { 26 })
        .y_label_area_size(80)
        .build_cartesian_2d(t0..t1, y0..y1)
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .x_desc(if last { "time (s)" } else { "" })
        .y_desc(panel.y_desc.as_str())
        .label_style(font(15.0))
        .axis_desc_style(font(16.0))
        .y_labels(6)
        .y_label_formatter(&|v| short(*v, 0))
        .light_line_style(TRANSPARENT)
        .bold_line_style(BLACK.mix(0.12))
        .draw()
        .map_err(draw_error)?;
    draw_runs(&mut chart, panel)?;
    let limit_style = LIMIT_RED.stroke_width(2);
    if let Some(limit) = panel.limit {
        let line = [(t0, limit), (t1, limit)];
        chart
            .draw_series(DashedLineSeries::new(line, 8, 5, limit_style))
            .map_err(draw_error)?;
    }
    if let Some((t, _)) = &panel.violation {
        let line = LineSeries::new([(*t, y0), (*t, y1)], limit_style);
        chart.draw_series(line).map_err(draw_error)?;
    }
    if let Some((t, v, _)) = &panel.worst {
        let ring = Circle::new((*t, *v), 6, BLACK.stroke_width(2));
        chart.draw_series([ring]).map_err(draw_error)?;
    }
    let (x_px, _) = chart.plotting_area().get_pixel_range();
    if let Some(limit) = panel.limit {
        let limit_px = chart.backend_coord(&(t1, limit));
        let red = font(15.0).color(&LIMIT_RED);
        let left = (HPos::Left, VPos::Center);
        text(
            root,
            &panel.limit_label,
            (x_px.end + 8, limit_px.1),
            &red,
            left,
        )?;
    }
    draw_header(root, area, panel, (x_px.start, x_px.end))
}

/// The series as polylines, broken where a value is missing.
fn draw_runs<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    panel: &Panel,
) -> Result<(), PlotError> {
    let style = panel.color.stroke_width(2);
    let finite = |p: &Option<(f64, f64)>| p.filter(|(t, v)| t.is_finite() && v.is_finite());
    let points: Vec<Option<(f64, f64)>> = panel.points.iter().map(finite).collect();
    for run in points.split(Option::is_none) {
        if !run.is_empty() {
            let line = LineSeries::new(run.iter().flatten().copied(), style);
            chart.draw_series(line).map_err(draw_error)?;
        }
    }
    Ok(())
}

/// Above the plotting area (`x_px`: its pixel columns): the panel's name and worst instant
/// on the left, the violation in red on the right.
fn draw_header(
    root: &Root<'_>,
    area: &Root<'_>,
    panel: &Panel,
    x_px: (i32, i32),
) -> Result<(), PlotError> {
    let y = area.get_base_pixel().1 + 16;
    let header = match &panel.worst {
        Some((_, _, label)) => format!("{} — {label}", panel.name),
        None => panel.name.to_string(),
    };
    let style = font(17.0);
    text(
        root,
        &header,
        (x_px.0, y),
        &style,
        (HPos::Left, VPos::Center),
    )?;
    if let Some((_, label)) = &panel.violation {
        let red = style.color(&LIMIT_RED);
        text(root, label, (x_px.1, y), &red, (HPos::Right, VPos::Center))?;
    }
    Ok(())
}
