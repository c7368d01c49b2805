//! `sets.svg`: the attachment test's set sizes per segment — |D0|, |D'0|, |D1|, |D2| — as
//! grouped bars on a logarithmic axis (the counts fall from thousands to a few).

use super::{PlotError, Root, draw_error, font, palette, render, text};
use crate::solve::SegmentReport;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Size of the plot (px).
const SIZE: (u32, u32) = (1000, 600);
/// Bottom of the bars: a count of 1 still gets a visible bar on the log axis.
const BASELINE: f64 = 0.5;
/// Width of a group of four bars (x units: one segment is 1).
const GROUP_WIDTH: f64 = 0.8;
/// Set names, in bar order.
const SET_NAMES: [&str; 4] = ["candidates", "after pruning", "hold the limits", "robust"];
/// One colour per set.
const SET_COLORS: [RGBColor; 4] = [
    RGBColor(150, 150, 150),
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
];
/// Centre line of the legend under the title (px).
const LEGEND_Y_PX: i32 = 55;
/// Estimated width of a digit of a bar label (px).
const DIGIT_PX: f64 = 9.0;

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, LogCoord<f64>>>;

/// `sets.svg`: per segment (`C1` … on the x axis) four bars |D0|, |D'0|, |D1|, |D2| on a
/// logarithmic axis, each labelled with its count; a count of 0 has no bar, only its `0`
/// label.
pub fn sets_svg(segments: &[SegmentReport], title: &str) -> Result<String, PlotError> {
    if segments.is_empty() {
        return Err(PlotError::Empty("no segments"));
    }
    render(SIZE, |root| draw(root, segments, title))
}

/// The four counts of a segment, in [`SET_NAMES`] order.
fn counts(segment: &SegmentReport) -> [usize; 4] {
    [segment.d0, segment.d0_pruned, segment.d1, segment.d2]
}

/// Top of the y axis: the largest count plus a fifth of the decades shown (at least 0.3),
/// room for the labels above the bars.
fn y_top(segments: &[SegmentReport]) -> f64 {
    let max = segments.iter().flat_map(counts).max().unwrap_or(0).max(1) as f64;
    let decades = (max / BASELINE).log10();
    max * 10f64.powf((0.2 * decades).max(0.3))
}

/// Title, legend, axes, bars and labels.
fn draw(root: &Root<'_>, segments: &[SegmentReport], title: &str) -> Result<(), PlotError> {
    let n = segments.len() as f64;
    let top = (HPos::Center, VPos::Top);
    text(root, title, (SIZE.0 as i32 / 2, 10), &font(26.0), top)?;
    legend(root)?;
    let mut chart = ChartBuilder::on(root)
        .margin(15)
        .margin_top(LEGEND_Y_PX + 25)
        .x_label_area_size(55)
        .y_label_area_size(85)
        .build_cartesian_2d(-0.5..n - 0.5, (BASELINE..y_top(segments)).log_scale())
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .x_desc("segment")
        .y_desc("cable pieces (log scale)")
        .y_label_formatter(&|v| format!("{v}"))
        .label_style(font(16.0))
        .axis_desc_style(font(18.0))
        .light_line_style(BLACK.mix(0.04))
        .bold_line_style(BLACK.mix(0.12))
        .draw()
        .map_err(draw_error)?;
    let digits = segments
        .iter()
        .flat_map(counts)
        .map(|c| c.to_string().len());
    let widest_px = digits.max().unwrap_or(1) as f64 * DIGIT_PX;
    let vertical = widest_px > bar_width_px(&chart, segments.len());
    for (i, segment) in segments.iter().enumerate() {
        for (k, count) in counts(segment).into_iter().enumerate() {
            draw_bar(root, &mut chart, (i, k), count, vertical)?;
        }
        let below = chart.backend_coord(&(i as f64, BASELINE));
        let at = (below.0, below.1 + 8);
        text(
            root,
            &segment.segment,
            at,
            &font(17.0),
            (HPos::Center, VPos::Top),
        )?;
    }
    Ok(())
}

/// Centre of bar `k` of group `i` (x units).
fn bar_center(i: usize, k: usize) -> f64 {
    let width = GROUP_WIDTH / SET_NAMES.len() as f64;
    i as f64 - GROUP_WIDTH / 2.0 + (k as f64 + 0.5) * width
}

/// Width of one bar in pixels.
fn bar_width_px(chart: &Chart<'_, '_>, groups: usize) -> f64 {
    let (x_px, _) = chart.plotting_area().get_pixel_range();
    f64::from(x_px.end - x_px.start) / groups as f64 * GROUP_WIDTH / SET_NAMES.len() as f64
}

/// Bar `k` of segment `i` with its count above it, `vertical` when some label of the plot is
/// wider than a bar.
fn draw_bar(
    root: &Root<'_>,
    chart: &mut Chart<'_, '_>,
    (i, k): (usize, usize),
    count: usize,
    vertical: bool,
) -> Result<(), PlotError> {
    let center = bar_center(i, k);
    let half = 0.45 * GROUP_WIDTH / SET_NAMES.len() as f64;
    if count > 0 {
        let corners = [(center - half, BASELINE), (center + half, count as f64)];
        let bar = Rectangle::new(corners, palette(&SET_COLORS, k).filled());
        chart.draw_series([bar]).map_err(draw_error)?;
    }
    let label = count.to_string();
    let top = chart.backend_coord(&(center, (count as f64).max(BASELINE)));
    let style = font(16.0);
    if vertical {
        let turned = style.transform(FontTransform::Rotate270);
        let at = (top.0, top.1 - 4);
        text(root, &label, at, &turned, (HPos::Left, VPos::Center))
    } else {
        let at = (top.0, top.1 - 3);
        text(root, &label, at, &style, (HPos::Center, VPos::Bottom))
    }
}

/// The four set names in a row under the title.
fn legend(root: &Root<'_>) -> Result<(), PlotError> {
    let entry_px = 110;
    let x0 = SIZE.0 as i32 / 2 - entry_px * SET_NAMES.len() as i32 / 2;
    let y = LEGEND_Y_PX;
    for (k, name) in SET_NAMES.iter().enumerate() {
        let x = x0 + k as i32 * entry_px;
        let square = Rectangle::new([(x, y - 7), (x + 14, y + 7)], SET_COLORS[k].filled());
        root.draw(&square).map_err(draw_error)?;
        let anchor = (HPos::Left, VPos::Center);
        text(root, name, (x + 20, y), &font(17.0), anchor)?;
    }
    Ok(())
}
