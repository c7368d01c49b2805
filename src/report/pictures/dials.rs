//! `allowed-ranges.svg`: a dial per axis — its URDF limits, the range the cable allows it and
//! the range it was asked within — as a fitter reads a vendor's range chart. A rotary axis is
//! a circle with 0° at the top and positive values counter-clockwise; a prismatic one a bar.

use crate::escape::html as escape;
use crate::robot::DisplayUnit;
use crate::solve::{AllowedAxis, AllowedRanges, RangeEnd};
use std::fmt::Write;

/// One dial's cell (px).
const CELL_W: f64 = 180.0;
const CELL_H: f64 = 200.0;
/// The dial's radius (px).
const RADIUS: f64 = 58.0;
/// Dials per row.
const PER_ROW: usize = 6;

const LIMITS: &str = "#d5d5d5";
const ALLOWED: &str = "#2e9d4a";
const WITHIN: &str = "#1c4fd8";
const FAILS: &str = "#c62828";

/// Large type: the dials are printed small on the installation sheet.
const STYLE: &str = "text{fill:#222;font-family:sans-serif;font-size:22px;text-anchor:middle}\
.name{font-weight:bold}.note{fill:#555;font-size:16px}";

/// The dials of `allowed`, one per axis, with a key; `None` when no axis was widened (the
/// mounting fails in the box itself).
pub fn dials_svg(allowed: &AllowedRanges) -> Option<String> {
    if allowed.axes.is_empty() {
        return None;
    }
    let rows = allowed.axes.len().div_ceil(PER_ROW);
    let width = CELL_W * allowed.axes.len().min(PER_ROW) as f64;
    let height = CELL_H * rows as f64 + 28.0;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\">\n<style>{STYLE}</style>\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    for (i, axis) in allowed.axes.iter().enumerate() {
        let (x0, y0) = (CELL_W * (i % PER_ROW) as f64, CELL_H * (i / PER_ROW) as f64);
        dial(&mut svg, axis, x0, y0);
    }
    let y = height - 10.0;
    let _ = writeln!(
        svg,
        "<text x=\"{:.0}\" y=\"{y}\" class=\"note\">grey: the joint's limits · green: what the \
         cable allows · blue: the range asked within · red: where the cable fails</text>",
        width / 2.0
    );
    svg.push_str("</svg>\n");
    Some(svg)
}

/// One axis's dial in the cell at (`x0`, `y0`).
fn dial(svg: &mut String, axis: &AllowedAxis, x0: f64, y0: f64) {
    let cx = x0 + CELL_W / 2.0;
    // A long name in smaller type, to stay within its cell (about 0.6 em a character).
    let name_px = (0.9 * CELL_W / (0.6 * axis.joint.chars().count().max(1) as f64)).min(22.0);
    let _ = writeln!(
        svg,
        "<text x=\"{cx}\" y=\"{:.0}\" class=\"name\" style=\"font-size:{name_px:.1}px\">{}</text>",
        y0 + 22.0,
        escape(&axis.joint)
    );
    let words = axis.words();
    let range = words.strip_prefix(&axis.joint).unwrap_or(&words).trim();
    let _ = writeln!(
        svg,
        "<text x=\"{cx}\" y=\"{:.0}\">{}</text>",
        y0 + CELL_H - 10.0,
        escape(range)
    );
    let failures: Vec<f64> = [&axis.below, &axis.above]
        .into_iter()
        .filter_map(|end| match end {
            RangeEnd::Fails { at, .. } => Some(*at),
            _ => None,
        })
        .collect();
    let limits = axis.limits.unwrap_or([-180.0, 180.0]);
    match axis.unit {
        DisplayUnit::Deg => {
            let cy = y0 + 30.0 + RADIUS + 12.0;
            let arc = |svg: &mut String, [a, b]: [f64; 2], colour: &str, width: f64| {
                let _ = writeln!(
                    svg,
                    "<path d=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"{width}\"/>",
                    arc_path(cx, cy, RADIUS, a, b)
                );
            };
            match axis.limits {
                Some(l) => arc(svg, l, LIMITS, 12.0),
                None => arc(svg, [-180.0, 180.0], LIMITS, 12.0),
            }
            arc(svg, axis.allowed, ALLOWED, 12.0);
            arc(svg, axis.within, WITHIN, 5.0);
            let _ = writeln!(
                svg,
                "<line x1=\"{cx}\" y1=\"{:.1}\" x2=\"{cx}\" y2=\"{:.1}\" stroke=\"#222\" \
                 stroke-width=\"1\"/><text x=\"{cx}\" y=\"{:.1}\" class=\"note\">0</text>",
                cy - RADIUS + 9.0,
                cy - RADIUS - 9.0,
                cy - RADIUS + 22.0
            );
            for at in failures {
                let (inner, outer) = (
                    point(cx, cy, RADIUS - 10.0, at),
                    point(cx, cy, RADIUS + 10.0, at),
                );
                let _ = writeln!(
                    svg,
                    "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{FAILS}\" \
                     stroke-width=\"3\"/>",
                    inner.0, inner.1, outer.0, outer.1
                );
            }
        }
        DisplayUnit::Mm => {
            let (left, right, y) = (x0 + 16.0, x0 + CELL_W - 16.0, y0 + 30.0 + RADIUS + 12.0);
            let span = (limits[1] - limits[0]).max(1e-9);
            let x = |v: f64| left + (right - left) * ((v - limits[0]) / span).clamp(0.0, 1.0);
            let bar = |svg: &mut String, [a, b]: [f64; 2], colour: &str, width: f64| {
                let _ = writeln!(
                    svg,
                    "<line x1=\"{:.1}\" y1=\"{y}\" x2=\"{:.1}\" y2=\"{y}\" stroke=\"{colour}\" \
                     stroke-width=\"{width}\"/>",
                    x(a),
                    x(b)
                );
            };
            bar(svg, limits, LIMITS, 12.0);
            bar(svg, axis.allowed, ALLOWED, 12.0);
            bar(svg, axis.within, WITHIN, 5.0);
            for at in failures {
                let _ = writeln!(
                    svg,
                    "<line x1=\"{0:.1}\" y1=\"{1}\" x2=\"{0:.1}\" y2=\"{2}\" stroke=\"{FAILS}\" \
                     stroke-width=\"3\"/>",
                    x(at),
                    y - 12.0,
                    y + 12.0
                );
            }
        }
    }
}

/// The point at `value_deg` on a circle: 0 at the top, positive counter-clockwise.
fn point(cx: f64, cy: f64, r: f64, value_deg: f64) -> (f64, f64) {
    let t = value_deg.to_radians();
    (cx - r * t.sin(), cy - r * t.cos())
}

/// The SVG path of the arc from `a` to `b` (degrees, `a` ≤ `b`, counter-clockwise); a whole
/// circle from a span of a turn or more.
fn arc_path(cx: f64, cy: f64, r: f64, a: f64, b: f64) -> String {
    let (a, b) = (a.min(b), a.max(b));
    if b - a >= 359.9 {
        return format!(
            "M {:.1} {:.1} a {r} {r} 0 1 0 0 {:.1} a {r} {r} 0 1 0 0 {:.1}",
            cx,
            cy - r,
            2.0 * r,
            -2.0 * r
        );
    }
    let (p, q) = (point(cx, cy, r, a), point(cx, cy, r, b));
    let large = u8::from(b - a > 180.0);
    // Counter-clockwise on the page is SVG's sweep flag 0 (its y axis points down).
    format!(
        "M {:.1} {:.1} A {r} {r} 0 {large} 0 {:.1} {:.1}",
        p.0, p.1, q.0, q.1
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quarter turn counter-clockwise from the top ends at the dial's left, a half turn at
    /// its bottom: the sign convention the caption states.
    #[test]
    fn values_go_counter_clockwise_from_the_top() {
        let (x, y) = point(100.0, 100.0, 50.0, 90.0);
        assert!((x - 50.0).abs() < 1e-9 && (y - 100.0).abs() < 1e-9);
        let (x, y) = point(100.0, 100.0, 50.0, 180.0);
        assert!((x - 100.0).abs() < 1e-9 && (y - 150.0).abs() < 1e-9);
        assert!(arc_path(0.0, 0.0, 1.0, -10.0, 200.0).contains(" 0 1 0 "));
        assert!(arc_path(0.0, 0.0, 1.0, -10.0, 100.0).contains(" 0 0 0 "));
    }
}
