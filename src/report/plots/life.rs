//! `life.svg`: the damage one cycle of the motion does along the cable, piece after piece
//! from the base end, on a logarithmic axis, the clamps marked and the point that fails first
//! circled.

use super::{LIMIT_RED, PlotError, PlotNames, Root, draw_error, finite_range, font, render, text};
use crate::life::estimate::CableLife;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Size of the plot (px).
const SIZE: (u32, u32) = (1000, 500);
/// The axis shows this many decades below the largest damage at most.
const DECADES: f64 = 8.0;
/// Line colour of the damage.
const DAMAGE_BLUE: RGBColor = RGBColor(31, 119, 180);

/// `life.svg` of `life` (pieces in the order of the path from the base end), joints
/// `pitch_mm` apart; `names` gives the pieces their fitter's names.
pub fn life_svg(
    life: &CableLife,
    pitch_mm: f64,
    title: &str,
    names: &PlotNames,
) -> Result<String, PlotError> {
    let (_, top) = finite_range(
        (life.pieces.iter())
            .flat_map(|p| p.damage_per_cycle.iter().copied())
            .filter(|d| *d > 0.0),
    )
    .ok_or(PlotError::Empty("no damage along the cable"))?;
    render(SIZE, |root| draw(root, life, pitch_mm, title, names, top))
}

/// The pieces laid end to end: per piece its start along the cable (mm) and its points
/// `(mm, damage)`, a damage below the axis's floor drawn on it.
fn along(life: &CableLife, pitch_mm: f64, floor: f64) -> Vec<(f64, Vec<(f64, f64)>)> {
    let mut start = 0.0;
    let mut out = Vec::new();
    for piece in &life.pieces {
        let points = (piece.damage_per_cycle.iter().enumerate())
            .map(|(k, d)| (start + k as f64 * pitch_mm, d.max(floor)))
            .collect();
        out.push((start, points));
        start += piece.damage_per_cycle.len().saturating_sub(1) as f64 * pitch_mm;
    }
    out.push((start, Vec::new()));
    out
}

fn draw(
    root: &Root<'_>,
    life: &CableLife,
    pitch_mm: f64,
    title: &str,
    names: &PlotNames,
    top: f64,
) -> Result<(), PlotError> {
    let floor = top / 10f64.powf(DECADES);
    let pieces = along(life, pitch_mm, floor);
    let length = pieces.last().map_or(0.0, |p| p.0).max(pitch_mm);
    text(
        root,
        title,
        (SIZE.0 as i32 / 2, 10),
        &font(24.0),
        (HPos::Center, VPos::Top),
    )?;
    let mut chart = ChartBuilder::on(root)
        .margin(15)
        .margin_top(55)
        .x_label_area_size(50)
        .y_label_area_size(90)
        .build_cartesian_2d(0.0..length, (floor..top * 3.0).log_scale())
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .x_desc("cable length from the first clamp (mm)")
        .y_desc("damage per cycle (log scale)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(font(15.0))
        .axis_desc_style(font(17.0))
        .light_line_style(BLACK.mix(0.04))
        .bold_line_style(BLACK.mix(0.12))
        .draw()
        .map_err(draw_error)?;
    // The clamps between the pieces, and each piece's name over its span.
    for (k, (start, points)) in pieces.iter().enumerate() {
        let clamp = [(*start, floor), (*start, top * 3.0)];
        chart
            .draw_series(LineSeries::new(clamp, BLACK.mix(0.35)))
            .map_err(draw_error)?;
        if let (Some(piece), Some(last)) = (life.pieces.get(k), points.last()) {
            let middle = chart.backend_coord(&(0.5 * (start + last.0), top * 2.0));
            let name = names.piece(&piece.segment_name);
            text(
                root,
                &name,
                middle,
                &font(14.0),
                (HPos::Center, VPos::Center),
            )?;
        }
        chart
            .draw_series(LineSeries::new(
                points.iter().copied(),
                DAMAGE_BLUE.stroke_width(2),
            ))
            .map_err(draw_error)?;
    }
    // The point that fails first.
    let weakest = &life.weakest;
    if let Some(k) = life
        .pieces
        .iter()
        .position(|p| p.segment == weakest.segment)
    {
        let at = (
            pieces[k].0 + weakest.from_start_mm,
            weakest.damage_per_cycle.max(floor),
        );
        chart
            .draw_series([Circle::new(at, 7, LIMIT_RED.stroke_width(2))])
            .map_err(draw_error)?;
        let label = format!("fails first: {:.3e} per cycle", weakest.damage_per_cycle);
        let mut pixel = chart.backend_coord(&at);
        pixel.1 -= 14;
        text(
            root,
            &label,
            pixel,
            &font(14.0).color(&LIMIT_RED),
            (HPos::Center, VPos::Bottom),
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::life::estimate::{PieceLife, Weakest};

    fn life() -> CableLife {
        let piece = |segment: usize, along: Vec<f64>| PieceLife {
            segment,
            segment_name: format!("C{}", segment + 1),
            cycles_to_failure: 1.0 / along.iter().fold(0.0f64, |a, &b| a.max(b)),
            weakest_from_start_mm: 0.0,
            damage_per_cycle: along,
            torsion_damage_per_cycle: 0.0,
        };
        CableLife {
            basis: "rated",
            rated_cycles: Some(5e6),
            rated_bend_radius_mm: Some(80.0),
            rated_torsion_deg_per_m: None,
            conductor_offset_mm: None,
            exponent: 4.0,
            exponent_stated: true,
            cycles_to_failure: 1e7,
            hours_to_failure: None,
            years_to_failure: None,
            weakest: Weakest {
                segment: 2,
                segment_name: "C3".into(),
                from_start_mm: 20.0,
                damage_per_cycle: 1e-7,
            },
            pieces: vec![
                piece(0, vec![1e-9, 2e-9, 0.0, 1e-9]),
                piece(2, vec![5e-8, 1e-8, 1e-7]),
            ],
        }
    }

    /// The pieces follow each other along the cable, a zero damage lies on the axis's floor.
    #[test]
    fn the_pieces_lie_end_to_end() {
        let pieces = along(&life(), 10.0, 1e-15);
        assert_eq!(pieces.len(), 3);
        assert_eq!(pieces[1].0, 30.0);
        assert_eq!(pieces[2].0, 50.0);
        assert_eq!(pieces[0].1[2], (20.0, 1e-15));
        assert_eq!(pieces[1].1[2], (50.0, 1e-7));
        let svg = life_svg(
            &life(),
            10.0,
            "Damage along the cable",
            &PlotNames::default(),
        )
        .expect("drawn");
        assert!(svg.contains("fails first") && svg.contains("C3"), "{svg}");
        let same = life_svg(
            &life(),
            10.0,
            "Damage along the cable",
            &PlotNames::default(),
        );
        assert_eq!(same.ok(), Some(svg));
    }
}
