//! SVG plots of the report folder: the motion's joint angles with the test poses of the
//! inter-link segments (`joints.svg`), the motion test's stress series against the limits
//! (`stress.svg`), the attachment test's set sizes per segment (`sets.svg`), and the damage
//! one cycle does along the cable (`life.svg`).
//!
//! Drawn with plotters' SVG backend and no font files: text stays SVG `<text>`, so the plots
//! are small, searchable and the same bytes for the same input.

mod joints;
mod life;
mod sets;
mod stress;

pub use joints::joints_svg;
pub use life::life_svg;
pub use sets::sets_svg;
pub use stress::stress_svg;

/// The fitter's names a plot of the motion test uses (`piece 1 → 2`, `clamp 2`), by the
/// setup's names; a name without one is shown as the setup gives it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PlotNames {
    /// `(C3, piece 2 → gripper connector)`.
    pub pieces: Vec<(String, String)>,
    /// `(G2, clamp 2)` for every guide of every physical clamp.
    pub clamps: Vec<(String, String)>,
    /// Why the test failed, in these names; `None` to show the test's own reason.
    pub failure: Option<String>,
}

impl PlotNames {
    /// The fitter's name of the setup's piece `segment`, safe in SVG text (plotters escapes
    /// markup, not the control characters XML forbids).
    pub fn piece(&self, segment: &str) -> String {
        let name = self
            .pieces
            .iter()
            .find(|(s, _)| s == segment)
            .map_or(segment, |(_, name)| name.as_str());
        crate::escape::terminal(name).into_owned()
    }

    /// The fitter's name of the clamp holding `guides`, safe in SVG text.
    pub fn clamp(&self, guides: &[String]) -> String {
        let name = guides
            .iter()
            .find_map(|g| self.clamps.iter().find(|(n, _)| n == g))
            .map_or_else(|| guides.join(" = "), |(_, name)| name.clone());
        crate::escape::terminal(&name).into_owned()
    }

    /// Why the test failed in these names, safe in SVG text.
    pub fn failure(&self) -> Option<String> {
        self.failure
            .as_deref()
            .map(|f| crate::escape::terminal(f).into_owned())
    }
}

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Why a plot could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The input has no data for this plot (no samples, no series, no segments).
    #[error("nothing to plot: {0}")]
    Empty(&'static str),
    /// plotters refused to draw (its error, as text).
    #[error("drawing the plot failed: {0}")]
    Draw(String),
}

/// A drawing area of a plot rendered into a string: the whole image or a part of it.
type Root<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// Font family of every text: resolved by the viewer, no font file needed.
const FONT: &str = "sans-serif";

/// Red of the limits and the violation.
const LIMIT_RED: RGBColor = RGBColor(220, 0, 0);

/// Renders an SVG of `size` (px) on a white background with `draw`.
fn render(
    size: (u32, u32),
    draw: impl FnOnce(&Root<'_>) -> Result<(), PlotError>,
) -> Result<String, PlotError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        draw(&root)?;
        root.present().map_err(draw_error)?;
    }
    Ok(svg)
}

/// plotters' error as a [`PlotError`].
fn draw_error(error: impl std::fmt::Display) -> PlotError {
    PlotError::Draw(error.to_string())
}

/// Text style of `size_px` (plotters' size; the SVG font size is ≈ 0.8 of it).
fn font(size_px: f64) -> TextStyle<'static> {
    (FONT, size_px).into_font().color(&BLACK)
}

/// Draws `text` at pixel `at` of `root` with its `anchor` there.
fn text(
    root: &Root<'_>,
    text: &str,
    at: (i32, i32),
    style: &TextStyle<'_>,
    anchor: (HPos, VPos),
) -> Result<(), PlotError> {
    let style = style.pos(Pos::new(anchor.0, anchor.1));
    root.draw(&Text::new(text.to_string(), at, style))
        .map_err(draw_error)
}

/// `lo..hi` widened by `pad` of its span on both sides; a point or an empty span becomes a
/// unit-wide range around it.
fn padded(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    let span = hi - lo;
    if span > 1e-12 * lo.abs().max(hi.abs()).max(1.0) {
        (lo - pad * span, hi + pad * span)
    } else {
        (lo - 0.5, hi + 0.5)
    }
}

/// Smallest and largest of the finite `values`, `None` when there is none.
fn finite_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold(None, |range, v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((f64::min(lo, v), f64::max(hi, v))),
        })
}

/// `value` with the fewest decimals (at least `min`, at most 4) that show it exactly to
/// 1e-9: `10.0`, `0.25`, `1.05`.
fn short(value: f64, min: usize) -> String {
    let decimals = (min..=4)
        .find(|&d| {
            let scale = 10f64.powi(d as i32);
            ((value * scale).round() / scale - value).abs() < 1e-9
        })
        .unwrap_or(4);
    format!("{value:.decimals$}")
}

/// A deterministic colour of a palette, cycling.
fn palette(colors: &[RGBColor], i: usize) -> RGBColor {
    colors[i % colors.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_keeps_needed_decimals() {
        assert_eq!(short(10.0, 1), "10.0");
        assert_eq!(short(0.25, 1), "0.25");
        assert_eq!(short(1.05, 2), "1.05");
        assert_eq!(short(1.0 / 3.0, 1), "0.3333");
    }

    #[test]
    fn padded_widens_degenerate_ranges() {
        assert_eq!(padded(2.0, 2.0, 0.1), (1.5, 2.5));
        assert_eq!(padded(0.0, 10.0, 0.1), (-1.0, 11.0));
    }

    #[test]
    fn finite_range_skips_non_finite() {
        let range = finite_range([f64::INFINITY, 3.0, f64::NAN, -1.0]);
        assert_eq!(range, Some((-1.0, 3.0)));
        assert_eq!(finite_range([f64::INFINITY]), None);
    }
}
