//! `joints.svg`: the joint values of the motion over time, with the test poses of every
//! inter-link segment marked on the joints it traverses (as in the paper's figures of
//! joint-angle time series with critical poses).

use super::{
    PlotError, Root, draw_error, finite_range, font, padded, palette, render, short, text,
};
use crate::motion::Motion;
use crate::solve::SegmentReport;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Size of the plot without its legend (px).
const SIZE: (u32, u32) = (850, 600);
/// Least room right of the plotting area for the legend (px).
const LEGEND_WIDTH_PX: u32 = 150;
/// Width of a legend character (px): an upper estimate for 16 px sans-serif text, so
/// that the longest name fits (the legend widens the plot, it never cuts a name).
const LEGEND_CHAR_PX: u32 = 10;
/// Legend labels longer than this are shortened in the middle (`shoulder…joint_1`).
const LEGEND_MAX_CHARS: usize = 60;
/// Radius of a test-pose marker (px).
const MARKER_RADIUS_PX: i32 = 5;

/// Joint curves: matplotlib's "tab10".
const JOINT_COLORS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Segment markers: dark colours that stand out on the joint curves.
const SEGMENT_COLORS: [RGBColor; 6] = [
    RGBColor(0, 0, 0),
    RGBColor(200, 0, 200),
    RGBColor(0, 110, 110),
    RGBColor(120, 80, 0),
    RGBColor(0, 0, 140),
    RGBColor(110, 110, 0),
];

/// One joint's curve: (time s, value deg or mm) per sample.
struct Curve {
    label: String,
    points: Vec<(f64, f64)>,
}

/// The test poses of one inter-link segment.
struct Marks {
    label: String,
    /// Times of the test poses (s).
    times_s: Vec<f64>,
    /// (time s, value deg or mm) of every test pose × traversed joint.
    points: Vec<(f64, f64)>,
}

/// `joints.svg`: one line per joint of `motion` over time (rotary joints in degrees,
/// prismatic ones in millimetres, labelled `(mm)`), and for every inter-link segment of
/// `segments` its test poses: a marker on each traversed joint's curve and a dashed vertical
/// line at the pose's time, coloured per segment. Intra-link segments are not marked: their
/// poses derive from the inter-link ones.
pub fn joints_svg(
    motion: &Motion,
    segments: &[SegmentReport],
    title: &str,
) -> Result<String, PlotError> {
    let curves = curves(motion);
    if curves.is_empty() {
        return Err(PlotError::Empty("the motion has no joints"));
    }
    let marks: Vec<Marks> = segments
        .iter()
        .filter(|s| s.kind == "inter-link")
        .map(|s| segment_marks(motion, s))
        .collect();
    let y_label = if motion.rotary().iter().all(|&r| r) {
        "joint angle (deg)"
    } else {
        "joint value (deg; prismatic: mm)"
    };
    let legend_px = legend_width_px(&curves, &marks);
    let size = (SIZE.0 + legend_px, SIZE.1);
    render(size, |root| {
        draw(root, &curves, &marks, (title, y_label), legend_px)
    })
}

/// Room for the legend: its glyph, gap and longest label.
fn legend_width_px(curves: &[Curve], marks: &[Marks]) -> u32 {
    let longest = curves
        .iter()
        .map(|c| &c.label)
        .chain(marks.iter().map(|m| &m.label))
        .map(|label| label.chars().count())
        .max()
        .unwrap_or(0);
    LEGEND_WIDTH_PX.max(52 + LEGEND_CHAR_PX * longest as u32)
}

/// `label`, shortened in the middle to [`LEGEND_MAX_CHARS`] characters when longer.
fn legend_label(label: &str) -> String {
    let count = label.chars().count();
    if count <= LEGEND_MAX_CHARS {
        return label.to_string();
    }
    let half = (LEGEND_MAX_CHARS - 1) / 2;
    let head: String = label.chars().take(half).collect();
    let tail: String = label.chars().skip(count - half).collect();
    format!("{head}…{tail}")
}

/// A joint value in plot units: degrees for a rotary joint (rad), mm for a prismatic one (m).
fn plot_value(value: f64, rotary: bool) -> f64 {
    if rotary {
        value.to_degrees()
    } else {
        value * 1e3
    }
}

/// One curve per joint, in joint-vector order.
fn curves(motion: &Motion) -> Vec<Curve> {
    let names = motion.joint_names();
    (0..motion.dof())
        .map(|j| {
            let rotary = motion.rotary()[j];
            let points = motion
                .times_s()
                .iter()
                .zip(motion.samples())
                .map(|(&t, q)| (t, plot_value(q[j], rotary)))
                .collect();
            let label = if rotary {
                legend_label(&names[j])
            } else {
                format!("{} (mm)", legend_label(&names[j]))
            };
            Curve { label, points }
        })
        .collect()
}

/// The markers of one segment: every test pose on every traversed joint the motion has. The
/// value is the motion's own sample (on the curve), or the pose's when the sample is out of
/// range.
fn segment_marks(motion: &Motion, segment: &SegmentReport) -> Marks {
    let joints: Vec<usize> = segment
        .traversed_joints
        .iter()
        .filter_map(|name| motion.joint_names().iter().position(|n| n == name))
        .collect();
    let mut times_s = Vec::new();
    let mut points = Vec::new();
    for pose in &segment.test_poses {
        let sample = motion.samples().get(pose.sample);
        let time_s = sample.map_or(pose.time_s, |_| motion.times_s()[pose.sample]);
        times_s.push(time_s);
        for &j in &joints {
            let value = match sample {
                Some(q) => Some(plot_value(q[j], motion.rotary()[j])),
                None => pose.joints.get(j).copied(),
            };
            points.extend(value.map(|v| (time_s, v)));
        }
    }
    Marks {
        label: segment.segment.clone(),
        times_s,
        points,
    }
}

/// Draws the whole plot.
fn draw(
    root: &Root<'_>,
    curves: &[Curve],
    marks: &[Marks],
    (title, y_label): (&str, &str),
    legend_px: u32,
) -> Result<(), PlotError> {
    let all = curves.iter().flat_map(|c| &c.points);
    let (t0, t1) = finite_range(all.clone().map(|p| p.0)).ok_or(PlotError::Empty("no times"))?;
    let (y0, y1) = finite_range(all.map(|p| p.1)).ok_or(PlotError::Empty("no joint values"))?;
    let (t0, t1) = if t1 > t0 {
        (t0, t1)
    } else {
        padded(t0, t1, 0.0)
    };
    let (y0, y1) = padded(y0, y1, 0.05);
    let mut chart = ChartBuilder::on(root)
        .caption(title, font(26.0))
        .margin(15)
        .margin_right(legend_px)
        .x_label_area_size(50)
        .y_label_area_size(75)
        .build_cartesian_2d(t0..t1, y0..y1)
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc(y_label)
        .label_style(font(16.0))
        .axis_desc_style(font(18.0))
        .y_label_formatter(&|v| short(*v, 0))
        .light_line_style(TRANSPARENT)
        .bold_line_style(BLACK.mix(0.12))
        .draw()
        .map_err(draw_error)?;
    for (k, segment) in marks.iter().enumerate() {
        let style = palette(&SEGMENT_COLORS, k).mix(0.6).stroke_width(1);
        for &t in &segment.times_s {
            let line = DashedLineSeries::new([(t, y0), (t, y1)], 6, 4, style);
            chart.draw_series(line).map_err(draw_error)?;
        }
    }
    for (j, curve) in curves.iter().enumerate() {
        let style = palette(&JOINT_COLORS, j).stroke_width(2);
        let line = LineSeries::new(curve.points.iter().copied(), style);
        chart.draw_series(line).map_err(draw_error)?;
    }
    for (k, segment) in marks.iter().enumerate() {
        let style = palette(&SEGMENT_COLORS, k).filled();
        let markers = segment
            .points
            .iter()
            .map(|&p| Circle::new(p, MARKER_RADIUS_PX, style));
        chart.draw_series(markers).map_err(draw_error)?;
    }
    let (x_px, y_px) = chart.plotting_area().get_pixel_range();
    legend(root, curves, marks, (x_px.end + 20, y_px.start + 10))
}

/// The legend right of the plotting area, top-left corner at `at` (px): a line per joint,
/// then, after a blank row, a marker per segment.
fn legend(
    root: &Root<'_>,
    curves: &[Curve],
    marks: &[Marks],
    at: (i32, i32),
) -> Result<(), PlotError> {
    let rows = curves.len() + marks.len() + 1;
    let row_px = (440 / rows.max(1)).clamp(12, 24) as i32;
    let style = font(16.0);
    let anchor = (HPos::Left, VPos::Center);
    for (j, curve) in curves.iter().enumerate() {
        let y = at.1 + j as i32 * row_px;
        let color = palette(&JOINT_COLORS, j).stroke_width(3);
        let glyph = PathElement::new(vec![(at.0, y), (at.0 + 24, y)], color);
        root.draw(&glyph).map_err(draw_error)?;
        text(root, &curve.label, (at.0 + 32, y), &style, anchor)?;
    }
    for (k, segment) in marks.iter().enumerate() {
        let y = at.1 + (curves.len() + 1 + k) as i32 * row_px;
        let color = palette(&SEGMENT_COLORS, k).filled();
        let glyph = Circle::new((at.0 + 12, y), MARKER_RADIUS_PX, color);
        root.draw(&glyph).map_err(draw_error)?;
        text(root, &segment.label, (at.0 + 32, y), &style, anchor)?;
    }
    Ok(())
}
