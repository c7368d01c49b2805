//! The installation sheet, one printed A4 landscape page a fitter mounts the cable from
//! alone: `install.html` (no script) with a title block that ties it to its job, the arm at
//! the installation pose from three sides with the clamps numbered (`installation-pose.svg`),
//! the steps, one row per clamp (its place in words, how the cable leaves it, how high its
//! axis stands off the surface, the largest load on it), the cable laid out straight with its
//! marks (`install.svg`), the pieces with their largest twist, and the cut.
//!
//! Every wording comes from the answer's [`MountingPlan`] and its rows
//! ([`crate::mounting::rows`]), and from the motion test's twist and load rows
//! ([`super::text::load_rows`]): the sheet says nothing of its own about a clamp.

use super::pictures::Picture;
use super::summary::capitalized;
use super::text::LoadRow;
use crate::escape::html as escape;
use crate::mounting::{self, MountingPlan, rows};
use crate::solve::{AllowedAxis, AllowedRanges};
use std::fmt::Write;

/// Width of the strip picture (px).
const WIDTH_PX: f64 = 1000.0;
/// Margin left and right of the cable strip (px).
const SIDE_PX: f64 = 90.0;
/// Height of the strip picture (px).
const STRIP_PX: f64 = 86.0;
/// Height of the arm's picture on the page with no clamp rows (mm), what each row takes from
/// it, and the least it keeps; its width follows, leaving the rest of the row to the steps.
const PICTURE_MM: f64 = 88.0;
const PICTURE_PER_ROW_MM: f64 = 8.0;
const MIN_PICTURE_MM: f64 = 45.0;
/// Height of the allowed ranges' dials beside the strip (mm), and what the arm's picture
/// gives way to them and their step.
const DIALS_MM: f64 = 22.0;
const DIALS_GIVE_MM: f64 = 12.0;

/// What the sheet is about, for its title block.
#[derive(Debug, Clone, PartialEq)]
pub struct TitleBlock {
    /// `viper_s850 (robots/viper_s850/viper_s850.urdf)`.
    pub robot: String,
    /// `SMC LE-CP (8 mm), part number …`.
    pub cable: String,
    /// The motion file, or what stands in for it.
    pub motion: String,
    /// The setup file.
    pub setup: String,
    /// The setup's content hash (16 hexadecimal digits).
    pub setup_hash: String,
    /// `2026-11-28`: the day the sheet was made (`SOURCE_DATE_EPOCH` when set).
    pub date: String,
}

/// The sheet's inputs besides the plan.
#[derive(Debug, Clone, PartialEq)]
pub struct Sheet<'a> {
    /// The answer as mounted.
    pub plan: &'a MountingPlan,
    /// The title block.
    pub title: TitleBlock,
    /// The picture of the arm at the installation pose, if the report has one.
    pub picture: Option<&'a Picture>,
    /// The largest twist per piece and load per clamp over the motion test.
    pub loads: Vec<LoadRow>,
    /// The range each axis allows, when found (its dials are `allowed-ranges.svg`).
    pub allowed: Option<&'a AllowedRanges>,
}

const STRIP_STYLE: &str = "text{fill:#222;font-family:sans-serif;font-size:15px}\
.mark line{stroke:#1c4fd8;stroke-width:2}\
.mark text{fill:#1c4fd8;font-weight:bold}\
.note{fill:#555;font-size:13px}";

/// `install.svg`: the cable drawn straight, its end at the tool on the left, a mark per
/// physical clamp with its number and its mark.
pub fn install_svg(plan: &MountingPlan, cable_colour: &str) -> String {
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH_PX}\" height=\"{STRIP_PX}\" \
         viewBox=\"0 0 {WIDTH_PX} {STRIP_PX}\">\n<style>{STRIP_STYLE}</style>\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    let scale = (WIDTH_PX - 2.0 * SIDE_PX) / plan.length_mm.max(1.0);
    let y = 44.0;
    let _ = writeln!(
        svg,
        "<line x1=\"{SIDE_PX}\" y1=\"{y}\" x2=\"{:.1}\" y2=\"{y}\" stroke=\"{}\" \
         stroke-width=\"9\" stroke-linecap=\"round\"/>",
        WIDTH_PX - SIDE_PX,
        escape(cable_colour)
    );
    let _ = writeln!(
        svg,
        "<text class=\"note\" x=\"4\" y=\"{:.1}\">tool end</text>\
         <text class=\"note\" x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">base end</text>",
        y + 4.0,
        WIDTH_PX - 4.0,
        y + 4.0
    );
    svg.push_str("<g class=\"mark\">\n");
    for (i, row) in rows::clamp_rows(plan).iter().enumerate() {
        let x = SIDE_PX + plan.clamps[i].mark_mm * scale;
        // Names above, marks below; neighbours closer than a label alternate up and down.
        let crowded = i % 2 == 1;
        let (name_y, mark_y) = if crowded {
            (y - 28.0, y + 34.0)
        } else {
            (y - 14.0, y + 20.0)
        };
        let anchor = match x {
            x if x < WIDTH_PX * 0.2 => "start",
            x if x > WIDTH_PX * 0.8 => "end",
            _ => "middle",
        };
        let _ = writeln!(
            svg,
            "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\"/>\
             <text x=\"{x:.1}\" y=\"{name_y:.1}\" text-anchor=\"{anchor}\">{}</text>\
             <text x=\"{x:.1}\" y=\"{mark_y:.1}\" text-anchor=\"{anchor}\">{} mm</text>",
            y - 10.0,
            y + 10.0,
            escape(&row.name),
            row.mark_mm
        );
    }
    svg.push_str("</g>\n</svg>\n");
    svg
}

/// `install.html`: the sheet, one A4 landscape page, no script.
pub fn install_html(sheet: &Sheet<'_>) -> String {
    let plan = sheet.plan;
    let mut html = String::new();
    let title = "Cable installation sheet";
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{title}</title>\n<style>\n{PAGE_STYLE}</style>\n</head>\n<body>\n"
    );
    title_block(&mut html, title, &sheet.title);
    html.push_str("<div class=\"top\">\n");
    if let Some(picture) = sheet.picture {
        // The picture gives way to the table's rows: one page holds both.
        // … and to the dials' row and their step.
        let dials_mm = if sheet.allowed.is_some() {
            DIALS_GIVE_MM
        } else {
            0.0
        };
        let rows = plan.clamps.len() + plan.sliding_parts.len();
        let height_mm = (PICTURE_MM - PICTURE_PER_ROW_MM * rows as f64 - dials_mm)
            .max(MIN_PICTURE_MM - dials_mm);
        let _ = writeln!(
            html,
            "<figure class=\"arm\"><img style=\"height: {height_mm:.0}mm\" src=\"{}\" alt=\"the robot at the installation pose \
             from its right, its front and above, the clamps numbered\"><figcaption>{}</figcaption>\
             </figure>",
            escape(&picture.file),
            escape(&picture.caption)
        );
    }
    steps(&mut html, plan, sheet.allowed);
    html.push_str("</div>\n");
    clamp_table(&mut html, plan, &sheet.loads);
    for warning in plan.warnings() {
        let _ = writeln!(
            html,
            "<p class=\"warning\"><b>Warning:</b> {}.</p>",
            escape(&capitalized(&warning))
        );
    }
    // The dials beside the strip: its height leaves the row's width free.
    html.push_str(
        "<div class=\"strip\"><img class=\"strip\" src=\"install.svg\" alt=\"the cable laid \
         out straight, each clamp's mark from the tool end\">",
    );
    if sheet.allowed.is_some() {
        let _ = write!(
            html,
            "<img class=\"dials\" style=\"height: {DIALS_MM}mm\" src=\"allowed-ranges.svg\" \
             alt=\"a dial per axis: its limits and the range the cable allows it\">"
        );
    }
    html.push_str("</div>\n");
    pieces_and_cut(&mut html, plan, &sheet.loads);
    html.push_str("</body>\n</html>\n");
    html
}

/// Robot, cable, motion, setup and its hash, date, tool version.
fn title_block(html: &mut String, title: &str, t: &TitleBlock) {
    let cells = [
        ("robot", t.robot.as_str()),
        ("cable", t.cable.as_str()),
        ("motion", t.motion.as_str()),
        ("setup", t.setup.as_str()),
        ("setup content hash", t.setup_hash.as_str()),
        ("date", t.date.as_str()),
        ("made by", concat!("cable-dict ", env!("CARGO_PKG_VERSION"))),
    ];
    let _ = write!(
        html,
        "<table class=\"title\"><tr><th class=\"name\" rowspan=\"2\">{title}</th>"
    );
    for (label, _) in &cells {
        let _ = write!(html, "<th>{label}</th>");
    }
    html.push_str("</tr>\n<tr>");
    for (_, value) in &cells {
        let _ = write!(html, "<td>{}</td>", escape(value));
    }
    html.push_str("</tr></table>\n");
}

/// What to do, in order.
fn steps(html: &mut String, plan: &MountingPlan, allowed: Option<&AllowedRanges>) {
    let end = plan.clamps.last().map(|c| c.in_words()).unwrap_or_default();
    let fitting_end = plan.clamps.last().is_some_and(|c| c.fitting.is_some());
    let mut steps = vec![
        format!("{}.", capitalized(&plan.installation_words())),
        format!("{}.", capitalized(&mounting::cut_words(plan))),
    ];
    if fitting_end {
        steps.push(format!("Plug the cable's end into {end}."));
    }
    steps.push(format!(
        "Mark the cable at each clamp's mark, its length from where it leaves {end} (mark \
         0; strip below), not from the cut end; {}.",
        plan.tolerance_words()
    ));
    steps.push(
        "Mount each clamp as its row says (distances are to the cable's axis, not the clamp's \
         foot) and close it on its mark, the cable leaving as the row says."
            .into(),
    );
    if let Some(allowed) = allowed {
        let ranges: Vec<String> = allowed.axes.iter().map(AllowedAxis::words).collect();
        steps.push(format!(
            "Last check: jog each axis alone to its ends, the others anywhere in {} (the dials \
             below): the cable holds over {}.",
            allowed.within,
            ranges.join(", ")
        ));
    }
    html.push_str("<section class=\"steps\"><h2>Steps</h2>\n<ol>\n");
    for step in steps {
        let _ = writeln!(html, "<li>{}</li>", escape(&step));
    }
    html.push_str("</ol>\n</section>\n");
}

/// One row per clamp or fitting.
fn clamp_table(html: &mut String, plan: &MountingPlan, loads: &[LoadRow]) {
    html.push_str(
        "<table class=\"clamps\">\n<tr><th>clamp</th><th>on</th><th>mark (mm from the tool \
         end)</th><th>along the link</th><th>around it (distances to the cable's axis)</th>\
         <th>the cable leaves</th><th>the cable's axis above the surface (clamp and cable \
         radius)</th><th>largest load in the motion test</th></tr>\n",
    );
    for row in rows::clamp_rows(plan)
        .into_iter()
        .chain(rows::sliding_rows(plan))
    {
        let note = row
            .note
            .as_deref()
            .map(|n| format!("<br><span class=\"note\">{}</span>", escape(n)))
            .unwrap_or_default();
        let load = loads
            .iter()
            .find(|l| l.name == row.name)
            .map(|l| escape(&l.short))
            .unwrap_or_default();
        let height = match &row.height_mm {
            Some(mm) => format!("{mm} mm"),
            None => escape(&row.height),
        };
        let _ = writeln!(
            html,
            "<tr><td><span class=\"name\">{}</span>{note}</td><td>{}</td>\
             <td class=\"mark\">{}</td><td>{}</td><td>{}</td><td>{}</td><td>{height}</td>\
             <td>{load}</td></tr>",
            escape(&row.name),
            escape(&row.link),
            row.mark_mm,
            escape(&row.along),
            escape(&row.around),
            escape(&row.cable),
        );
    }
    html.push_str("</table>\n");
}

/// The pieces with their largest twist, and the length.
fn pieces_and_cut(html: &mut String, plan: &MountingPlan, loads: &[LoadRow]) {
    html.push_str("<p class=\"pieces\">");
    let pieces: Vec<String> = rows::piece_rows(plan)
        .into_iter()
        .map(|piece| {
            let twist = loads
                .iter()
                .find(|l| l.name == format!("piece {}", piece.name))
                .map(|l| format!(", largest twist {}", l.short))
                .unwrap_or_default();
            format!(
                "<b>{}</b>: {} mm {}{}",
                escape(&piece.name),
                piece.length_mm,
                escape(&piece.across),
                escape(&twist)
            )
        })
        .collect();
    let _ = writeln!(
        html,
        "{}. Pieces (twist from the cable as laid): {}.</p>",
        escape(&capitalized(&rows::length_words(plan))),
        pieces.join("; ")
    );
    html.push_str(
        "<p class=\"small\">The cable before the first clamp and beyond the last is outside \
         this design. A joint's axis is the centre of its housing; a seam is where a link \
         turns against the one before it. Placements in the link frames for CAD: \
         result.json, \"mounting\".</p>\n",
    );
}

/// Print styling for one A4 landscape page; system fonts only.
const PAGE_STYLE: &str = "@page { size: A4 landscape; margin: 8mm; }
* { box-sizing: border-box; }
body { font-family: sans-serif; font-size: 8.5pt; color: #222; margin: 0 auto; max-width: 281mm; }
h2 { font-size: 10pt; margin: 0 0 1mm 0; }
table { border-collapse: collapse; width: 100%; }
th, td { border: 1px solid #999; padding: 0.6mm 1.2mm; text-align: left; vertical-align: top; }
table.title { margin-bottom: 2mm; font-size: 8.5pt; }
table.title th { background: #eef1f4; font-weight: normal; font-size: 8pt; }
table.title th.name { font-size: 12pt; font-weight: bold; background: white; }
.top { display: flex; gap: 4mm; align-items: flex-start; }
figure.arm { margin: 0; flex: 0 0 auto; width: min-content; }
figure.arm img { width: auto; max-width: 170mm; display: block; }
figcaption { font-size: 8pt; color: #555; }
.steps { flex: 1 1 auto; }
.steps ol { margin: 0; padding-left: 5mm; font-size: 8pt; }
.steps li { margin-bottom: 1mm; }
.warning { color: #a40000; margin: 1mm 0; }
table.clamps { margin-top: 2mm; font-size: 8pt; }
table.clamps th { background: #eef1f4; }
.name { font-weight: bold; color: #1c4fd8; white-space: nowrap; }
td.mark { text-align: right; font-weight: bold; white-space: nowrap; }
.note { font-weight: normal; color: #555; font-size: 8pt; }
img.strip { width: 100%; max-height: 16mm; object-fit: contain; display: block; margin: 1mm 0; }
div.strip { display: flex; gap: 4mm; align-items: center; margin: 1mm 0; }
div.strip img.strip { flex: 1; min-width: 0; }
img.dials { max-width: 40%; }
p { margin: 1mm 0; }
.small { font-size: 8pt; color: #555; }
@media print { body { max-width: none; } }
";
