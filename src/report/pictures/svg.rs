//! One picture as SVG: the front and side views side by side, the top view under the front
//! one (third-angle layout: front and side share the height axis, front and top the x axis),
//! the legend beside the top view.
//!
//! Inside each view's panel (a nested `<svg class="view front">` etc.) the coordinates are
//! world millimetres rounded to 0.1 mm, the vertical one negated (SVG's y axis points down):
//! a point (x, y, z) is drawn at `x,-z` in the front view, `y,-z` in the side view and
//! `x,-y` in the top view. Robot colliders are `<polygon>`s in `<g class="robot">`, drawn far
//! to near; each cable piece a `<polyline>` in `<g class="cable">`, drawn over the robot so
//! that it is never hidden; clamps `<circle>`s with their names in `<g class="clamps">`.

use super::projection::{View, outline};
use crate::escape::html as escape;
use crate::report::scene::CableTint;
use nalgebra::Point3;
use std::fmt::Write;

/// Width of the whole picture (px) when its height allows.
const WIDTH_PX: f64 = 960.0;
/// Largest height of a picture (px): a tall robot is drawn smaller.
const MAX_HEIGHT_PX: f64 = 1100.0;
/// Room left of a panel for the tick labels and the axis name (px).
const LEFT_PX: f64 = 56.0;
/// Room under a panel for the tick labels and the axis name (px).
const BOTTOM_PX: f64 = 38.0;
/// Room above a panel for its title (px).
const TITLE_PX: f64 = 22.0;
/// Room above everything for the heading (px).
const HEADING_PX: f64 = 30.0;
/// Space between the two columns and the two rows (px).
const GAP_PX: f64 = 24.0;
/// Space right of the side view (px).
const RIGHT_PX: f64 = 12.0;
/// Room around the cable inside a panel, so that the arm around it shows (mm): at least
/// this, or [`PAD_SHARE`] of the cable's largest extent.
const PAD_MM: f64 = 150.0;
/// Share of the cable's largest extent left around it.
const PAD_SHARE: f64 = 0.25;
/// Font size of the labels in the views (px) and the width of one of their characters, as a
/// share of it (sans-serif digits and lower case are narrower; this errs wide).
const LABEL_PX: f64 = 12.0;
const CHAR_SHARE: f64 = 0.62;
/// Largest height of a picture of three views in a row (px).
const ROW_HEIGHT_PX: f64 = 420.0;
/// Radius of a clamp's dot (px).
const DOT_PX: f64 = 5.0;
/// Distances from its dot a label may be put at, each a label's height and a fifth farther
/// than the one before; beyond the first a thin line leads from the dot to the label.
const LABEL_RINGS: usize = 12;
/// Tick spacings to choose from (mm): the smallest that leaves at most [`MAX_TICKS`].
const TICK_STEPS_MM: [f64; 9] = [
    50.0, 100.0, 200.0, 250.0, 500.0, 1000.0, 2000.0, 5000.0, 10000.0,
];
/// Most tick intervals along the longest axis.
const MAX_TICKS: f64 = 10.0;
/// Thinnest cable line (px): a cable thinner than this at the picture's scale is drawn at it.
const MIN_CABLE_PX: f64 = 3.0;

/// Colours and text styles, shared by every element of a class.
const STYLE: &str = "text{fill:#222}\
.heading{font-size:15px;font-weight:bold}\
.frame{fill:none;stroke:#888}\
.grid{stroke:#e4e4e4;fill:none}\
.robot polygon{fill:#8d99a6;fill-opacity:0.45;stroke:#2f3a45;stroke-linejoin:round}\
.cable polyline{fill:none;stroke:#e8590c;stroke-linecap:round;stroke-linejoin:round}\
.clamps circle{fill:#1c4fd8;stroke:white}\
.clamps text{fill:#1c4fd8;font-weight:bold}\
.clamps .leader{stroke:#1c4fd8;stroke-width:0.6px;vector-effect:non-scaling-stroke}\
.view text{paint-order:stroke;stroke:white;stroke-linejoin:round}\
.worst{fill:none;stroke:#d00000}";

/// What one picture shows, in the world frame (mm).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Drawing {
    /// The line at the top of the picture.
    pub heading: String,
    /// The robot's colliders, each as the vertices of its tessellation (mm).
    pub colliders: Vec<Vec<Point3<f64>>>,
    /// The cable pieces: the setup's name (`C1`), nodes (mm) and colour (`#rrggbb`).
    pub cable: Vec<CablePiece>,
    /// The physical clamps: the fitter's name (`1`, `gripper connector`) and the cable
    /// axis's point at the clamp (mm).
    pub clamps: Vec<(String, Point3<f64>)>,
    /// The legend's lines for the cable's colours: colour and meaning.
    pub cable_legend: Vec<CableTint>,
    /// Where the smallest margin is (mm), ringed in red.
    pub marker: Option<Point3<f64>>,
}

/// One cable piece as drawn.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CablePiece {
    /// The setup's name of the piece (`C1`), the polyline's `data-piece` for programs that
    /// read the picture (the picture itself names clamps, not pieces).
    pub name: String,
    /// Its nodes (mm).
    pub nodes: Vec<Point3<f64>>,
    /// Its colour (`#rrggbb`).
    pub colour: String,
}

impl Drawing {
    /// The points the views are cropped to: the cable, its clamps and the ringed place; the
    /// robot's when there is no cable.
    fn focus(&self) -> Vec<&Point3<f64>> {
        let cable = self.cable.iter().flat_map(|piece| &piece.nodes);
        let clamps = self.clamps.iter().map(|(_, p)| p);
        let focus: Vec<&Point3<f64>> = cable.chain(clamps).chain(&self.marker).collect();
        if focus.is_empty() {
            self.colliders.iter().flatten().collect()
        } else {
            focus
        }
    }
}

/// The world box and the scale that every picture of a report shares, so that they can be
/// compared side by side.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    /// Lowest x, y, z shown (mm), a multiple of the tick step.
    lo_mm: [f64; 3],
    /// Highest x, y, z shown (mm), a multiple of the tick step.
    hi_mm: [f64; 3],
    /// Tick and grid spacing on every axis (mm).
    tick_mm: f64,
    /// Pixels per millimetre, the same on every axis and in every view.
    px_per_mm: f64,
    /// Drawn cable width (mm): the cable's diameter, or [`MIN_CABLE_PX`] if that is wider.
    cable_width_mm: f64,
    /// The three views side by side in one row (the installation sheet), not front and side
    /// over top.
    in_a_row: bool,
    /// Font size of the clamp labels (px).
    label_px: f64,
}

impl Layout {
    /// One layout per drawing: the box around its cable (its clamps and ringed place; the
    /// robot where there is no cable) with [`PAD_MM`] or [`PAD_SHARE`] to spare, all at the
    /// one scale that fits the largest of them into [`WIDTH_PX`] × [`MAX_HEIGHT_PX`], so that
    /// the pictures compare side by side. The robot is drawn cut at the box: the pictures
    /// show the cable and the arm around it.
    pub fn for_each(drawings: &[Drawing], cable_diameter_mm: f64) -> Vec<Layout> {
        let mut layouts: Vec<Layout> = drawings.iter().map(Layout::around).collect();
        let px_per_mm = layouts
            .iter()
            .map(|l| l.px_per_mm)
            .fold(f64::INFINITY, f64::min);
        for layout in &mut layouts {
            layout.px_per_mm = px_per_mm;
            layout.cable_width_mm = cable_diameter_mm.max(MIN_CABLE_PX / px_per_mm);
        }
        layouts
    }

    /// The box around `drawing`'s cable and the scale that fits it alone.
    fn around(drawing: &Drawing) -> Layout {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in drawing.focus() {
            for axis in 0..3 {
                lo[axis] = lo[axis].min(p[axis]);
                hi[axis] = hi[axis].max(p[axis]);
            }
        }
        if lo.iter().chain(&hi).any(|v| !v.is_finite()) {
            (lo, hi) = ([-500.0; 3], [500.0; 3]);
        }
        let extent = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
        let pad = PAD_MM.max(PAD_SHARE * extent);
        for axis in 0..3 {
            lo[axis] -= pad;
            hi[axis] += pad;
        }
        let longest = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
        let tick_mm = TICK_STEPS_MM
            .into_iter()
            .find(|step| longest / step <= MAX_TICKS)
            .unwrap_or(TICK_STEPS_MM[TICK_STEPS_MM.len() - 1]);
        let lo_mm = lo.map(|v| (v / tick_mm).floor() * tick_mm);
        let hi_mm = hi.map(|v| (v / tick_mm).ceil() * tick_mm);
        let [x, y, z] = [0, 1, 2].map(|a| hi_mm[a] - lo_mm[a]);
        let across = (WIDTH_PX - 2.0 * LEFT_PX - GAP_PX - RIGHT_PX) / (x + y);
        let down = (MAX_HEIGHT_PX - HEADING_PX - 2.0 * (TITLE_PX + BOTTOM_PX) - GAP_PX) / (z + y);
        let px_per_mm = across.min(down);
        Layout {
            lo_mm,
            hi_mm,
            tick_mm,
            px_per_mm,
            cable_width_mm: MIN_CABLE_PX / px_per_mm,
            in_a_row: false,
            label_px: LABEL_PX,
        }
    }

    /// The three views of `drawing` side by side in [`WIDTH_PX`], at most [`ROW_HEIGHT_PX`]
    /// high, the clamp labels `label_px` high: a picture printed across a page, whose labels
    /// stay readable there.
    pub fn in_a_row(drawing: &Drawing, cable_diameter_mm: f64, label_px: f64) -> Layout {
        let mut layout = Layout::around(drawing);
        let [x, y, z] = [0, 1, 2].map(|a| layout.span_mm(a));
        let across = (WIDTH_PX - 3.0 * LEFT_PX - 2.0 * GAP_PX - RIGHT_PX) / (2.0 * x + y);
        let down = (ROW_HEIGHT_PX - HEADING_PX - TITLE_PX - BOTTOM_PX) / z.max(y);
        layout.px_per_mm = across.min(down);
        layout.cable_width_mm = cable_diameter_mm.max(MIN_CABLE_PX / layout.px_per_mm);
        layout.in_a_row = true;
        layout.label_px = label_px;
        layout
    }

    /// Span of world axis `axis` (mm).
    fn span_mm(&self, axis: usize) -> f64 {
        self.hi_mm[axis] - self.lo_mm[axis]
    }

    /// Size of `view`'s panel (px).
    fn panel_px(&self, view: View) -> [f64; 2] {
        let (right, up) = view.axes();
        [right, up].map(|a| self.span_mm(a) * self.px_per_mm)
    }

    /// Top-left corner of `view`'s panel (px).
    fn panel_origin_px(&self, view: View) -> [f64; 2] {
        let [front_w, front_h] = self.panel_px(View::Front);
        if self.in_a_row {
            let [side_w, _] = self.panel_px(View::Side);
            let y = HEADING_PX + TITLE_PX;
            let side_x = LEFT_PX + front_w + GAP_PX + LEFT_PX;
            return match view {
                View::Front => [LEFT_PX, y],
                View::Side => [side_x, y],
                View::Top => [side_x + side_w + GAP_PX + LEFT_PX, y],
            };
        }
        match view {
            View::Front => [LEFT_PX, HEADING_PX + TITLE_PX],
            View::Side => [LEFT_PX + front_w + GAP_PX + LEFT_PX, HEADING_PX + TITLE_PX],
            View::Top => [
                LEFT_PX,
                HEADING_PX + TITLE_PX + front_h + BOTTOM_PX + GAP_PX + TITLE_PX,
            ],
        }
    }

    /// Size of the whole picture (px).
    fn size_px(&self) -> [f64; 2] {
        if self.in_a_row {
            let [top_x, top_y] = self.panel_origin_px(View::Top);
            let [top_w, _] = self.panel_px(View::Top);
            let tallest = View::ALL
                .iter()
                .map(|&v| self.panel_px(v)[1])
                .fold(0.0, f64::max);
            return [
                (top_x + top_w + RIGHT_PX).ceil(),
                (top_y + tallest + BOTTOM_PX).ceil(),
            ];
        }
        let [side_x, _] = self.panel_origin_px(View::Side);
        let [_, top_y] = self.panel_origin_px(View::Top);
        let [side_w, _] = self.panel_px(View::Side);
        let [_, top_h] = self.panel_px(View::Top);
        [
            (side_x + side_w + RIGHT_PX).ceil(),
            (top_y + top_h + BOTTOM_PX).ceil(),
        ]
    }

    /// `px` screen pixels in panel units (mm).
    fn mm(&self, px: f64) -> f64 {
        px / self.px_per_mm
    }
}

/// The picture of `drawing` on `layout`.
pub(super) fn picture_svg(drawing: &Drawing, layout: &Layout) -> String {
    let [width, height] = layout.size_px();
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"12\">\n<title>{title}</title>\n<style>{STYLE}</style>\n\
         <rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n\
         <text class=\"heading\" x=\"{LEFT_PX}\" y=\"20\">{title}</text>\n",
        w = num(width),
        h = num(height),
        title = escape(&drawing.heading),
    );
    for view in View::ALL {
        push_view(&mut svg, drawing, layout, view);
    }
    if !layout.in_a_row {
        push_legend(&mut svg, drawing, layout);
    }
    svg.push_str("</svg>\n");
    svg
}

/// One view: title, ticks and axis names around the panel, the panel with the geometry.
fn push_view(svg: &mut String, drawing: &Drawing, layout: &Layout, view: View) {
    let [x0, y0] = layout.panel_origin_px(view);
    let [w, h] = layout.panel_px(view);
    let _ = writeln!(
        svg,
        "<text x=\"{}\" y=\"{}\">{}</text>",
        num(x0),
        num(y0 - 7.0),
        view.title()
    );
    push_ticks(svg, layout, view);
    let (right, up) = view.axes();
    let _ = writeln!(
        svg,
        "<svg class=\"view {}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" viewBox=\"{} {} {} {}\">",
        view.name(),
        num(x0),
        num(y0),
        num(w),
        num(h),
        num(layout.lo_mm[right]),
        num(-layout.hi_mm[up]),
        num(layout.span_mm(right)),
        num(layout.span_mm(up)),
    );
    push_grid(svg, layout, view);
    push_robot(svg, drawing, layout, view);
    push_cable(svg, drawing, layout, view);
    push_clamps(svg, drawing, layout, view);
    push_marker(svg, drawing, layout, view);
    svg.push_str("</svg>\n");
    let _ = writeln!(
        svg,
        "<rect class=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>",
        num(x0),
        num(y0),
        num(w),
        num(h)
    );
}

/// The tick values (mm) of world axis `axis`.
fn ticks(layout: &Layout, axis: usize) -> impl Iterator<Item = f64> {
    let step = layout.tick_mm;
    let first = (layout.lo_mm[axis] / step).round() as i64;
    let last = (layout.hi_mm[axis] / step).round() as i64;
    (first..=last).map(move |i| i as f64 * step)
}

/// Tick labels under and left of the panel, and the axis names with their unit.
fn push_ticks(svg: &mut String, layout: &Layout, view: View) {
    let [x0, y0] = layout.panel_origin_px(view);
    let [w, h] = layout.panel_px(view);
    let (right, up) = view.axes();
    let to_px = |v: f64, axis: usize| (v - layout.lo_mm[axis]) * layout.px_per_mm;
    for v in ticks(layout, right) {
        let _ = writeln!(
            svg,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            num(x0 + to_px(v, right)),
            num(y0 + h + 14.0),
            num(v)
        );
    }
    for v in ticks(layout, up) {
        let _ = writeln!(
            svg,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>",
            num(x0 - 4.0),
            num(y0 + h - to_px(v, up) + 4.0),
            num(v)
        );
    }
    let names = ["x (mm)", "y (mm)", "z (mm)"];
    let _ = writeln!(
        svg,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
        num(x0 + 0.5 * w),
        num(y0 + h + 30.0),
        names[right]
    );
    let (x, y) = (x0 - LEFT_PX + 12.0, y0 + 0.5 * h);
    let _ = writeln!(
        svg,
        "<text x=\"{x}\" y=\"{y}\" text-anchor=\"middle\" transform=\"rotate(-90 {x} {y})\">{}</text>",
        names[up],
        x = num(x),
        y = num(y)
    );
}

/// Light lines at the ticks, in panel units.
fn push_grid(svg: &mut String, layout: &Layout, view: View) {
    let (right, up) = view.axes();
    let (lo_r, hi_r) = (layout.lo_mm[right], layout.hi_mm[right]);
    let (lo_u, hi_u) = (layout.lo_mm[up], layout.hi_mm[up]);
    let mut path = String::new();
    for v in ticks(layout, right) {
        let _ = write!(path, "M{} {}V{}", num(v), num(-hi_u), num(-lo_u));
    }
    for v in ticks(layout, up) {
        let _ = write!(path, "M{} {}H{}", num(lo_r), num(-v), num(hi_r));
    }
    let _ = writeln!(
        svg,
        "<path class=\"grid\" stroke-width=\"{}\" d=\"{path}\"/>",
        num(layout.mm(1.0))
    );
}

/// The colliders' outlines, farthest first (by their vertices' mean depth).
fn push_robot(svg: &mut String, drawing: &Drawing, layout: &Layout, view: View) {
    let mean_depth = |points: &[Point3<f64>]| {
        points.iter().map(|p| view.depth(p)).sum::<f64>() / points.len().max(1) as f64
    };
    let mut order: Vec<(f64, &Vec<Point3<f64>>)> = drawing
        .colliders
        .iter()
        .map(|points| (mean_depth(points), points))
        .collect();
    // Stable: colliders at the same depth stay in the robot's order.
    order.sort_by(|a, b| b.0.total_cmp(&a.0));
    open_group(svg, layout, "robot", layout.mm(1.0));
    for (_, points) in order {
        let corners: Vec<[f64; 2]> = outline(view, points);
        let _ = writeln!(svg, "<polygon points=\"{}\"/>", point_list(&corners));
    }
    svg.push_str("</g>\n");
}

/// Opens a `<g class="class">` in a panel: its lines `stroke_width_mm` wide, its labels
/// 12 px high.
fn open_group(svg: &mut String, layout: &Layout, class: &str, stroke_width_mm: f64) {
    let _ = writeln!(
        svg,
        "<g class=\"{class}\" stroke-width=\"{}\" font-size=\"{}\">",
        num(stroke_width_mm),
        num(layout.mm(layout.label_px))
    );
}

/// Each cable piece as a polyline through its nodes, in its margin colour. The pieces are
/// not labelled: the numbered clamps at their ends name them.
fn push_cable(svg: &mut String, drawing: &Drawing, layout: &Layout, view: View) {
    if drawing.cable.is_empty() {
        return;
    }
    open_group(svg, layout, "cable", layout.cable_width_mm);
    for piece in &drawing.cable {
        let projected: Vec<[f64; 2]> = piece.nodes.iter().map(|p| view.project(p)).collect();
        let _ = writeln!(
            svg,
            "<polyline data-piece=\"{}\" style=\"stroke:{}\" points=\"{}\"/>",
            escape(&piece.name),
            escape(&piece.colour),
            point_list(&projected)
        );
    }
    svg.push_str("</g>\n");
}

/// A dot and the name of every clamp, the names placed where they overlap neither each other
/// nor a dot, inside the panel.
fn push_clamps(svg: &mut String, drawing: &Drawing, layout: &Layout, view: View) {
    if drawing.clamps.is_empty() {
        return;
    }
    open_group(svg, layout, "clamps", layout.mm(1.5));
    let anchors: Vec<[f64; 2]> = drawing
        .clamps
        .iter()
        .map(|(_, at)| {
            let [x, y] = view.project(at);
            [x, -y]
        })
        .collect();
    for (_, at) in &drawing.clamps {
        push_circle(svg, view.project(at), layout.mm(DOT_PX), "");
    }
    let (right, up) = view.axes();
    let bounds = LabelBox {
        x: layout.lo_mm[right],
        y: -layout.hi_mm[up],
        w: layout.span_mm(right),
        h: layout.span_mm(up),
    };
    let texts: Vec<&str> = drawing
        .clamps
        .iter()
        .map(|(name, _)| name.as_str())
        .collect();
    let boxes = place_labels(&texts, &anchors, layout.mm(1.0), layout.label_px, &bounds);
    for (b, [x, y]) in boxes.iter().zip(&anchors) {
        // A leader from the dot to the nearest point of a label set apart from it.
        let (nx, ny) = (x.clamp(b.x, b.x + b.w), y.clamp(b.y, b.y + b.h));
        if (nx - x).hypot(ny - y) > layout.mm(DOT_PX + 14.0) {
            let _ = writeln!(
                svg,
                "<line class=\"leader\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>",
                num(*x),
                num(*y),
                num(nx),
                num(ny)
            );
        }
    }
    for ((text, b), [x, _]) in texts.iter().zip(&boxes).zip(&anchors) {
        // The box is an upper bound of the text's width: the text starts at the box's side
        // nearer its dot, so that a label set left of its dot ends next to it.
        let (at, anchor) = if *x > b.x + 0.5 * b.w {
            (b.x + b.w, " text-anchor=\"end\"")
        } else {
            (b.x, "")
        };
        let _ = writeln!(
            svg,
            "<text x=\"{}\" y=\"{}\"{anchor} font-size=\"{}\" stroke-width=\"{}\" \
             data-box=\"{} {} {} {}\">{}</text>",
            num(at),
            num(b.y + 0.8 * b.h),
            num(b.h),
            num(layout.mm(3.0)),
            num(b.x),
            num(b.y),
            num(b.w),
            num(b.h),
            escape(text)
        );
    }
    svg.push_str("</g>\n");
}

/// The place for a `w` × `h` label inside `bounds`, on a grid of half a label's height, that
/// `free` accepts and that is nearest to `anchor`.
fn nearest_free_place(
    bounds: &LabelBox,
    (x, y): (f64, f64),
    (w, h): (f64, f64),
    free: impl Fn(&LabelBox) -> bool,
) -> Option<LabelBox> {
    let step = 0.5 * h;
    let columns = ((bounds.w - w) / step).floor().max(0.0) as usize;
    let rows = ((bounds.h - h) / step).floor().max(0.0) as usize;
    let mut best: Option<(f64, LabelBox)> = None;
    for i in 0..=columns.min(MAX_GRID) {
        for j in 0..=rows.min(MAX_GRID) {
            let b = LabelBox {
                x: bounds.x + i as f64 * step,
                y: bounds.y + j as f64 * step,
                w,
                h,
            };
            let (cx, cy) = (b.x + 0.5 * w, b.y + 0.5 * h);
            let distance = (cx - x).hypot(cy - y);
            if best.is_none_or(|(d, _)| distance < d) && free(&b) {
                best = Some((distance, b));
            }
        }
    }
    best.map(|(_, b)| b)
}

/// Most places along each side of a panel that [`nearest_free_place`] tries.
const MAX_GRID: usize = 200;
/// Widest a clamp label may be, as a share of its panel's width.
const MAX_LABEL_SHARE: f64 = 0.6;

/// A label's box in a panel's drawn coordinates (mm; x right, y down): its top-left corner
/// and size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct LabelBox {
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
}

impl LabelBox {
    /// The area two boxes share.
    fn overlap(&self, other: &LabelBox) -> f64 {
        let w = (self.x + self.w).min(other.x + other.w) - self.x.max(other.x);
        let h = (self.y + self.h).min(other.y + other.h) - self.y.max(other.y);
        w.max(0.0) * h.max(0.0)
    }

    /// Whether it lies wholly inside `bounds`.
    fn inside(&self, bounds: &LabelBox) -> bool {
        self.x >= bounds.x
            && self.y >= bounds.y
            && self.x + self.w <= bounds.x + bounds.w
            && self.y + self.h <= bounds.y + bounds.h
    }
}

/// Boxes for `texts` next to their `anchors` (drawn coordinates, mm; `mm_per_px` the scale):
/// each at the first of eight places around its anchor, at growing distances, that lies
/// inside `bounds` and overlaps neither an earlier label nor any anchor's dot; where none
/// does, the place inside the bounds that overlaps least.
pub(super) fn place_labels(
    texts: &[&str],
    anchors: &[[f64; 2]],
    mm_per_px: f64,
    label_px: f64,
    bounds: &LabelBox,
) -> Vec<LabelBox> {
    let h = label_px * mm_per_px;
    let r = DOT_PX * mm_per_px;
    let dots: Vec<LabelBox> = anchors
        .iter()
        .map(|[x, y]| LabelBox {
            x: x - r,
            y: y - r,
            w: 2.0 * r,
            h: 2.0 * r,
        })
        .collect();
    let mut placed: Vec<LabelBox> = Vec::new();
    for (text, &[x, y]) in texts.iter().zip(anchors) {
        // A label wider than a share of the panel is set smaller until it fits (its box says
        // how): a long fitting name in a small view.
        let natural = text.chars().count().max(1) as f64 * CHAR_SHARE * h;
        let shrink = (MAX_LABEL_SHARE * bounds.w / natural).min(1.0);
        let (w, h) = (natural * shrink, h * shrink);
        let candidates = (1..=LABEL_RINGS).flat_map(|ring| {
            let d = r + 2.0 * mm_per_px + (ring - 1) as f64 * 1.2 * h;
            [
                (x + d, y - h - 0.3 * d),
                (x + d, y + 0.3 * d),
                (x - d - w, y - h - 0.3 * d),
                (x - d - w, y + 0.3 * d),
                (x - 0.5 * w, y - d - h),
                (x - 0.5 * w, y + d),
                (x + d, y - 0.5 * h),
                (x - d - w, y - 0.5 * h),
            ]
        });
        let mut best: Option<(f64, LabelBox)> = None;
        for (bx, by) in candidates {
            let b = LabelBox { x: bx, y: by, w, h };
            if !b.inside(bounds) {
                continue;
            }
            let cost: f64 = placed
                .iter()
                .chain(&dots)
                .map(|other| b.overlap(other))
                .sum();
            if cost == 0.0 {
                best = Some((0.0, b));
                break;
            }
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, b));
            }
        }
        // Nothing free around the anchor: the free place in the whole panel nearest to it
        // (a leader line joins them); only a full panel leaves the least overlap.
        let b = match best {
            Some((0.0, b)) => b,
            _ => nearest_free_place(bounds, (x, y), (w, h), |b: &LabelBox| {
                placed
                    .iter()
                    .chain(&dots)
                    .all(|other| b.overlap(other) == 0.0)
            })
            .or(best.map(|(_, b)| b))
            .unwrap_or(LabelBox {
                x: (x + r).min(bounds.x + bounds.w - w).max(bounds.x),
                y: (y - h).clamp(bounds.y, bounds.y + (bounds.h - h).max(0.0)),
                w,
                h,
            }),
        };
        placed.push(b);
    }
    placed
}

/// A circle of `radius_mm` around the projected point `at`, with more `attributes` (each
/// with a leading space).
fn push_circle(svg: &mut String, at: [f64; 2], radius_mm: f64, attributes: &str) {
    let _ = writeln!(
        svg,
        "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{attributes}/>",
        num(at[0]),
        num(-at[1]),
        num(radius_mm)
    );
}

/// A red ring around the place of the smallest margin.
fn push_marker(svg: &mut String, drawing: &Drawing, layout: &Layout, view: View) {
    if let Some(at) = &drawing.marker {
        let ring = format!(" class=\"worst\" stroke-width=\"{}\"", num(layout.mm(2.5)));
        push_circle(svg, view.project(at), layout.mm(11.0), &ring);
    }
}

/// What the colours mean, in the free corner beside the top view.
fn push_legend(svg: &mut String, drawing: &Drawing, layout: &Layout) {
    let [side_x, _] = layout.panel_origin_px(View::Side);
    let [_, top_y] = layout.panel_origin_px(View::Top);
    let mut entries: Vec<(String, &str)> = vec![(
        "<rect width=\"22\" height=\"12\" y=\"-10\" fill=\"#8d99a6\" fill-opacity=\"0.45\" stroke=\"#2f3a45\"/>".into(),
        "robot (collision shapes)",
    )];
    for tint in &drawing.cable_legend {
        entries.push((
            format!(
                "<path d=\"M0 -4H22\" stroke=\"{}\" stroke-width=\"4\"/>",
                tint.css()
            ),
            tint.legend(),
        ));
    }
    if !drawing.clamps.is_empty() {
        entries.push((
            "<circle cx=\"11\" cy=\"-4\" r=\"5\" fill=\"#1c4fd8\"/>".into(),
            "clamps, numbered as on the installation sheet",
        ));
    }
    if drawing.marker.is_some() {
        entries.push((
            "<circle cx=\"11\" cy=\"-4\" r=\"8\" fill=\"none\" stroke=\"#d00000\" stroke-width=\"2.5\"/>".into(),
            "where a limit is closest or broken",
        ));
    }
    for (i, (symbol, words)) in entries.iter().enumerate() {
        let _ = writeln!(
            svg,
            "<g transform=\"translate({} {})\">{symbol}<text x=\"30\">{words}</text></g>",
            num(side_x),
            num(top_y + 12.0 + 22.0 * i as f64)
        );
    }
}

/// `x,-y x,-y …` of projected points, in panel units.
fn point_list(points: &[[f64; 2]]) -> String {
    let pairs: Vec<String> = points
        .iter()
        .map(|[x, y]| format!("{},{}", num(*x), num(-y)))
        .collect();
    pairs.join(" ")
}

/// `value` rounded to 0.1, without a trailing `.0` and without a negative zero: `12.3`,
/// `-4`, `0`.
fn num(value: f64) -> String {
    let tenths = (value * 10.0).round();
    if tenths == 0.0 {
        return "0".into();
    }
    let text = format!("{:.1}", tenths / 10.0);
    text.strip_suffix(".0").map(str::to_string).unwrap_or(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 400 × 200 × 600 mm box centred at (1000, 2000, 3000) mm, as its eight corners.
    fn box_drawing() -> Drawing {
        let mut corners = Vec::new();
        for x in [800.0, 1200.0] {
            for y in [1900.0, 2100.0] {
                for z in [2700.0, 3300.0] {
                    corners.push(Point3::new(x, y, z));
                }
            }
        }
        Drawing {
            heading: "a box & a cable".into(),
            colliders: vec![corners],
            cable: vec![CablePiece {
                name: "C1".into(),
                nodes: vec![
                    Point3::new(850.0, 1950.0, 2750.0),
                    Point3::new(1150.04, 2050.0, 3250.0),
                ],
                colour: "#e8590c".into(),
            }],
            cable_legend: vec![CableTint::Plain],
            clamps: vec![("G1".into(), Point3::new(850.0, 1950.0, 2750.0))],
            marker: None,
        }
    }

    /// The corners of every `<polygon>`, each list sorted.
    fn polygons(svg: &str) -> Vec<Vec<(f64, f64)>> {
        svg.split("<polygon points=\"")
            .skip(1)
            .map(|rest| {
                let list = &rest[..rest.find('"').expect("closing quote")];
                let mut corners: Vec<(f64, f64)> = list
                    .split(' ')
                    .map(|pair| {
                        let (x, y) = pair.split_once(',').expect("x,y");
                        (x.parse().expect("x"), y.parse().expect("y"))
                    })
                    .collect();
                corners.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
                corners
            })
            .collect()
    }

    #[test]
    fn numbers_are_rounded_to_a_tenth_without_negative_zero() {
        assert_eq!(num(12.34), "12.3");
        assert_eq!(num(-4.0), "-4");
        assert_eq!(num(-0.04), "0");
        assert_eq!(num(1150.04), "1150");
        assert_eq!(num(0.05), "0.1");
    }

    #[test]
    fn the_box_spans_whole_ticks_with_padding_at_one_scale() {
        let layout = Layout::for_each(&[box_drawing()], 8.0).remove(0);
        // The cable spans 500 mm at most, so 150 mm of padding around it: 800 mm is at most
        // 10 ticks of 100 mm.
        assert_eq!(layout.tick_mm, 100.0);
        assert_eq!(layout.lo_mm, [700.0, 1800.0, 2600.0]);
        // The cable reaches x = 1150.04 mm: 1300.04 with the padding, up to the next tick.
        assert_eq!(layout.hi_mm, [1400.0, 2200.0, 3400.0]);
        // One scale: every panel's pixels per mm are the same on both of its axes.
        for view in View::ALL {
            let (right, up) = view.axes();
            let [w, h] = layout.panel_px(view);
            assert!((w / layout.span_mm(right) - layout.px_per_mm).abs() < 1e-12);
            assert!((h / layout.span_mm(up) - layout.px_per_mm).abs() < 1e-12);
        }
        let [width, height] = layout.size_px();
        assert!(
            width <= WIDTH_PX && height <= MAX_HEIGHT_PX,
            "{width} × {height}"
        );
    }

    #[test]
    fn the_picture_draws_the_outline_cable_and_clamp_in_world_millimetres() {
        let layout = Layout::for_each(&[box_drawing()], 8.0).remove(0);
        let svg = picture_svg(&box_drawing(), &layout);
        // Each view's outline is the box's rectangle in that view's world axes (vertical
        // negated): front x–z, side y–z, top x–y.
        let rectangle = |(r0, r1): (f64, f64), (u0, u1): (f64, f64)| {
            let mut corners = vec![(r0, -u0), (r1, -u0), (r0, -u1), (r1, -u1)];
            corners.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
            corners
        };
        let expected = [
            rectangle((800.0, 1200.0), (2700.0, 3300.0)),
            rectangle((1900.0, 2100.0), (2700.0, 3300.0)),
            rectangle((800.0, 1200.0), (1900.0, 2100.0)),
        ];
        assert_eq!(polygons(&svg), expected);
        assert!(svg.contains("points=\"850,-2750 1150,-3250\""));
        assert!(svg.contains("points=\"1950,-2750 2050,-3250\""));
        assert!(svg.contains("points=\"850,-1950 1150,-2050\""));
        // The clamp at (850, 1950, 2750) mm: front (x, −z), side (y, −z), top (x, −y).
        for centre in [
            "cx=\"850\" cy=\"-2750\"",
            "cx=\"1950\" cy=\"-2750\"",
            "cx=\"850\" cy=\"-1950\"",
        ] {
            assert_eq!(svg.matches(centre).count(), 1, "{centre}");
        }
        assert!(svg.contains("a box &amp; a cable"));
        assert!(!svg.contains("class=\"worst\""));
    }

    /// Eight labels crowded on one point near a panel's corner, and long ones: no two boxes
    /// overlap, none covers a dot, every one lies inside the panel.
    #[test]
    fn crowded_labels_neither_overlap_nor_leave_the_panel() {
        let bounds = LabelBox {
            x: 0.0,
            y: 0.0,
            w: 400.0,
            h: 300.0,
        };
        let anchors: Vec<[f64; 2]> = (0..8).map(|i| [12.0 + i as f64, 10.0]).collect();
        let texts = [
            "1",
            "2",
            "gripper connector",
            "3",
            "4",
            "connector",
            "5",
            "bracket",
        ];
        let boxes = place_labels(&texts, &anchors, 1.0, LABEL_PX, &bounds);
        assert_eq!(boxes.len(), texts.len());
        for (i, a) in boxes.iter().enumerate() {
            assert!(a.inside(&bounds), "{i}: {a:?}");
            for b in &boxes[i + 1..] {
                assert_eq!(a.overlap(b), 0.0, "{a:?} and {b:?}");
            }
            for [x, y] in &anchors {
                let dot = LabelBox {
                    x: x - DOT_PX,
                    y: y - DOT_PX,
                    w: 2.0 * DOT_PX,
                    h: 2.0 * DOT_PX,
                };
                assert_eq!(a.overlap(&dot), 0.0, "{a:?} covers the dot at {x}, {y}");
            }
        }
    }
}
