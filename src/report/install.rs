//! The installation sheet: `install.svg` (the cable laid out straight with a mark where each
//! physical clamp grips it, and one sketch per clamp of its place on the link) and
//! `install.html` (the same picture with the table of places, printable, no scripts).
//!
//! Everything comes from the answer's [`MountingPlan`]: coincident guides are one clamp, the
//! marks are cable lengths from the end at the tool, places are measured from the link's
//! joint axes (see [`crate::mounting::place`]).

use super::summary::capitalized;
use crate::escape::html as escape;
use crate::mounting::{LinkPlace, MountingPlan, PhysicalClamp};
use crate::text_table::{decimal, decimals};
use std::fmt::Write;

/// Width of the sheet (px).
const WIDTH_PX: f64 = 960.0;
/// Margin left and right of the cable strip (px).
const SIDE_PX: f64 = 70.0;
/// Height of the cable strip with its marks (px).
const STRIP_PX: f64 = 150.0;
/// Height of one clamp's sketch (px).
const SKETCH_PX: f64 = 120.0;
/// Length of the link axis in a sketch (px).
const AXIS_PX: f64 = 360.0;

const STYLE: &str = "text{fill:#222;font-family:sans-serif;font-size:13px}\
.heading{font-size:15px;font-weight:bold}\
.cable{stroke:#e8590c;stroke-width:8;stroke-linecap:round}\
.mark line{stroke:#1c4fd8;stroke-width:2}\
.mark text,.clamp{fill:#1c4fd8;font-weight:bold}\
.section{fill:#eef1f4;stroke:#2f3a45;stroke-width:1.5}\
.axis{stroke:#2f3a45;stroke-width:2;stroke-dasharray:8 4}\
.joint{fill:white;stroke:#2f3a45;stroke-width:2}\
.arrow{stroke:#e8590c;stroke-width:3;marker-end:url(#head)}\
.note{fill:#555;font-size:12px}";

/// `install.svg` for `plan`; `title` heads it.
pub fn install_svg(title: &str, plan: &MountingPlan) -> String {
    let height = 40.0 + STRIP_PX + SKETCH_PX * plan.clamps.len() as f64 + 20.0;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH_PX}\" height=\"{height}\" \
         viewBox=\"0 0 {WIDTH_PX} {height}\">\n<style>{STYLE}</style>\n<defs><marker id=\"head\" \
         viewBox=\"0 0 10 10\" refX=\"8\" refY=\"5\" markerWidth=\"5\" markerHeight=\"5\" \
         orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 z\" fill=\"#e8590c\"/></marker></defs>\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
         <text class=\"heading\" x=\"12\" y=\"24\">{}</text>\n",
        escape(title)
    );
    cable_strip(&mut svg, plan, 40.0);
    for (i, clamp) in plan.clamps.iter().enumerate() {
        clamp_sketch(&mut svg, clamp, 40.0 + STRIP_PX + SKETCH_PX * i as f64);
    }
    svg.push_str("</svg>\n");
    svg
}

/// The cable drawn straight, its end at the tool on the left, a mark per clamp.
fn cable_strip(svg: &mut String, plan: &MountingPlan, top: f64) {
    let scale = (WIDTH_PX - 2.0 * SIDE_PX) / plan.length_mm.max(1.0);
    let y = top + 60.0;
    let _ = writeln!(
        svg,
        "<line class=\"cable\" x1=\"{SIDE_PX}\" y1=\"{y}\" x2=\"{:.1}\" y2=\"{y}\"/>",
        WIDTH_PX - SIDE_PX
    );
    svg.push_str("<g class=\"mark\">\n");
    for (i, clamp) in plan.clamps.iter().enumerate() {
        let x = SIDE_PX + clamp.mark_mm * scale;
        // Labels alternate above and below so that close marks stay readable; those at the
        // ends run inward.
        let (label_y, mark_y) = if i % 2 == 0 {
            (y - 26.0, y - 42.0)
        } else {
            (y + 34.0, y + 50.0)
        };
        let anchor = match x {
            x if x < WIDTH_PX / 4.0 => "start",
            x if x > WIDTH_PX * 0.75 => "end",
            _ => "middle",
        };
        let x_text = match anchor {
            "start" => x - 12.0,
            "end" => x + 12.0,
            _ => x,
        };
        let _ = writeln!(
            svg,
            "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\"/>\
             <text x=\"{x_text:.1}\" y=\"{mark_y:.1}\" text-anchor=\"{anchor}\">{}</text>\
             <text x=\"{x_text:.1}\" y=\"{label_y:.1}\" text-anchor=\"{anchor}\">{} mm</text>",
            y - 14.0,
            y + 14.0,
            escape(&clamp.name()),
            decimal(clamp.mark_mm, 0)
        );
    }
    svg.push_str("</g>\n");
    let _ = writeln!(
        svg,
        "<text class=\"note\" x=\"12\" y=\"{:.1}\">Marks: cable length from its end at the \
         tool (left); {}.</text>",
        top + STRIP_PX - 24.0,
        escape(&plan.tolerance_words())
    );
}

/// One clamp: its link's long axis from the joint it is measured from, the clamp at its
/// distance along it, the cable's direction as an arrow, and the place in words.
fn clamp_sketch(svg: &mut String, clamp: &PhysicalClamp, top: f64) {
    let _ = writeln!(
        svg,
        "<text class=\"clamp\" x=\"12\" y=\"{:.1}\">{} on {}, mark {} mm</text>",
        top + 16.0,
        escape(&clamp.name()),
        escape(&clamp.link),
        decimal(clamp.mark_mm, 0)
    );
    let Some(place) = &clamp.place else {
        let _ = writeln!(
            svg,
            "<text class=\"note\" x=\"12\" y=\"{:.1}\">on the robot's base link at {} mm \
             (link frame)</text>",
            top + 36.0,
            decimals(&clamp.xyz_mm, 1)
        );
        return;
    };
    let (x0, y) = (40.0, top + 60.0);
    // The axis spans the link to its next joint, or 1.25 × the clamp's distance.
    let along_mm = place.along_mm.unwrap_or(0.0);
    let span_mm = place
        .next_joint_mm
        .unwrap_or(along_mm.abs() * 1.25)
        .max(along_mm.abs())
        .max(1.0);
    let x = x0 + AXIS_PX * (along_mm / span_mm).clamp(-0.1, 1.0);
    let _ = writeln!(
        svg,
        "<line class=\"axis\" x1=\"{x0}\" y1=\"{y}\" x2=\"{:.1}\" y2=\"{y}\"/>\
         <circle class=\"joint\" cx=\"{x0}\" cy=\"{y}\" r=\"7\"/>\
         <text class=\"note\" x=\"{x0}\" y=\"{:.1}\" text-anchor=\"middle\">{} axis</text>",
        x0 + AXIS_PX,
        y + 26.0,
        escape(&place.joint)
    );
    if let Some(next) = &place.next_joint {
        let _ = writeln!(
            svg,
            "<circle class=\"joint\" cx=\"{x1:.1}\" cy=\"{y}\" r=\"7\"/>\
             <text class=\"note\" x=\"{x1:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{} axis</text>",
            y + 26.0,
            escape(next),
            x1 = x0 + AXIS_PX * (place.next_joint_mm.unwrap_or(span_mm) / span_mm),
        );
    }
    cable_arrow(svg, place, x, y);
    cross_section(svg, place, x0 + AXIS_PX + 70.0, y);
    let _ = writeln!(
        svg,
        "<text class=\"note\" x=\"{:.1}\" y=\"{:.1}\">{}</text>\
         <text class=\"note\" x=\"{:.1}\" y=\"{:.1}\">{}</text>",
        x0 + AXIS_PX + 120.0,
        y - 10.0,
        escape(&place.along_words()),
        x0 + AXIS_PX + 120.0,
        y + 10.0,
        escape(&format!("cable {}", place.cable_direction()))
    );
}

/// The clamp as a dot on the axis and the cable's direction (toward the tool) as an arrow at
/// its angle to the axis.
fn cable_arrow(svg: &mut String, place: &LinkPlace, x: f64, y: f64) {
    let angle = place.cable_to_axis_deg.to_radians();
    let (dx, dy) = (40.0 * angle.cos(), -40.0 * angle.sin());
    let _ = writeln!(
        svg,
        "<line class=\"arrow\" x1=\"{x:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{:.1}\"/>\
         <circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"6\" fill=\"#1c4fd8\"/>",
        x + dx,
        y + dy
    );
}

/// The link seen along its long axis: a circle with the zero side marked and the clamp at its
/// angle, clockwise (the view looks along the axis, so clockwise on paper is clockwise).
fn cross_section(svg: &mut String, place: &LinkPlace, cx: f64, cy: f64) {
    let angle = place.around_deg.to_radians();
    let (px, py) = (cx + 30.0 * angle.sin(), cy - 30.0 * angle.cos());
    let _ = writeln!(
        svg,
        "<circle class=\"section\" cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"24\"/>\
         <text class=\"note\" x=\"{cx:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\
         <line class=\"mark\" x1=\"{cx:.1}\" y1=\"{:.1}\" x2=\"{cx:.1}\" y2=\"{:.1}\" stroke=\"#2f3a45\"/>\
         <circle cx=\"{px:.1}\" cy=\"{py:.1}\" r=\"6\" fill=\"#1c4fd8\"/>",
        cy - 36.0,
        place.zero_side.word(),
        cy - 28.0,
        cy - 20.0,
    );
}

/// `install.html`: the sheet's picture and the table of places, for printing.
pub fn install_html(title: &str, plan: &MountingPlan) -> String {
    let mut rows = String::new();
    for clamp in &plan.clamps {
        let place = clamp
            .place
            .as_ref()
            .map(LinkPlace::describe)
            .unwrap_or_else(|| "on the robot's base link".into());
        let _ = writeln!(
            rows,
            "<tr><td>{}</td><td>{}</td><td class=\"mark\">{}</td><td>{}</td><td>{}</td>\
             <td>{}</td><td>{}</td></tr>",
            escape(&clamp.name()),
            escape(&clamp.link),
            decimal(clamp.mark_mm, 0),
            escape(&place),
            escape(&clamp.placement),
            decimals(&clamp.xyz_mm, 1),
            decimals(&clamp.rpy_deg, 1)
        );
    }
    let cut = plan
        .cut
        .as_ref()
        .map(|cut| format!("<p><b>{}</b>.</p>\n", escape(&capitalized(&cut.describe()))))
        .unwrap_or_default();
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{title}</title>\n<style>\n{PAGE_STYLE}</style>\n</head>\n<body>\n\
         <h1>{title}</h1>\n<p>Cable between the first and the last clamp: <b>{length} mm</b>. \
         {pose}.</p>\n{cut}<p>{tolerance}. The cable before the first clamp and beyond the last \
         is outside this design.</p>\n<img src=\"install.svg\" alt=\"the cable with its clamp \
         marks, and each clamp's place on its link\">\n<table>\n<tr><th>clamp</th><th>link</th>\
         <th>mark (mm from the tool end)</th><th>place on the link</th><th>placement</th>\
         <th>xyz in the link frame (mm)</th><th>rpy (deg)</th></tr>\n{rows}</table>\n\
         </body>\n</html>\n",
        title = escape(title),
        length = decimal(plan.length_mm, 0),
        pose = escape(&capitalized(&plan.installation_words())),
        tolerance = escape(&capitalized(&plan.tolerance_words())),
    )
}

/// Print-friendly styling; system fonts only.
const PAGE_STYLE: &str = "body { font-family: sans-serif; margin: 1em 2em; color: #222; }
table { border-collapse: collapse; margin: 1em 0; }
th, td { border: 1px solid #999; padding: 0.3em 0.6em; text-align: left; vertical-align: top; }
td.mark { text-align: right; font-weight: bold; }
img { max-width: 100%; }
@media print { body { margin: 0; } }
";
