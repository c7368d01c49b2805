//! What `segment` prints: the JSON document and its text rendering.

use super::super::output::Failure;
use super::obstacles::{ContactMetric, Scene};
use super::{Args, Solver, Stage};
use cable_dict::attachment::Metrics as ShapeMetrics;
use cable_dict::cable::CableSpec;
use cable_dict::pose::matrix_rows;
use cable_dict::segment::{Connected, Converged};
use nalgebra::{Point3, Rotation3};
use serde::Serialize;
use std::fmt;

#[derive(Serialize)]
pub struct SegmentReport {
    stage: Stage,
    cable: String,
    /// `hermite` (the paper's curve), `bowed` (slack taken by a bow along gravity) or
    /// `linear` (a straight cable dragged into place by the physics engine).
    curve: &'static str,
    /// `null` for `linear`.
    alpha_m: Option<f64>,
    /// Bow height of the `bowed` curve (m); 0 for `hermite`, `null` for `linear`.
    bow_m: Option<f64>,
    length_mm: f64,
    sub_segments: usize,
    pitch_mm: f64,
    /// `null` for `linear`.
    twist_correction_deg: Option<f64>,
    connect_time_us: f64,
    /// S+1 nodes from the start guide to the end guide inclusive.
    nodes_mm: Vec<[f64; 3]>,
    /// Node frames, row-major rotations (columns: normal, binormal, tangent).
    frames: Vec<[[f64; 3]; 3]>,
    metrics: Metrics,
    /// The equilibrium, for `--stage converged`.
    #[serde(skip_serializing_if = "Option::is_none")]
    converged: Option<ConvergedReport>,
}

#[derive(Serialize)]
struct ConvergedReport {
    solver: Solver,
    /// Newton iterations (quasi-static) or simulation steps (rapier).
    iterations: usize,
    /// Largest force left on a node (N, quasi-static) or node motion over the last
    /// convergence window (m, rapier).
    residual: f64,
    residual_unit: &'static str,
    solve_time_us: f64,
    /// Total twist between the guides (deg), whole turns of `--twist-turns` included;
    /// `null` for rapier.
    twist_deg: Option<f64>,
    /// `--twist-turns`.
    twist_turns: i32,
    /// The extra turn of the end guide (deg) at which the cable first passed through itself
    /// on the way; `null` when it never did.
    self_contact_from_deg: Option<f64>,
    nodes_mm: Vec<[f64; 3]>,
    frames: Vec<[[f64; 3]; 3]>,
    metrics: Metrics,
}

#[derive(Serialize)]
struct Metrics {
    /// `null` for a straight cable (infinite radius).
    min_bend_radius_mm: Option<f64>,
    min_bend_radius_node: usize,
    cable_min_bend_radius_mm: f64,
    stretch: f64,
    /// Closest approach to the robot, with `--robot`.
    #[serde(skip_serializing_if = "Option::is_none")]
    contact: Option<ContactMetric>,
    /// Closest approach of the cable to itself; `null` for a cable too short to meet itself.
    self_contact: Option<SelfContactMetric>,
}

/// How close the cable comes to itself.
#[derive(Serialize)]
struct SelfContactMetric {
    /// Distance between the two closest sub-segments (not the same stretch of cable bending)
    /// less the cable diameter (mm); negative: the cable passes through itself.
    min_clearance_mm: f64,
    /// The cable touches or passes through itself: not a shape a real cable can take.
    violation: bool,
    /// Where: the two sub-segments (0-based from the start guide).
    #[serde(rename = "where")]
    sub_segments: [usize; 2],
}

impl SegmentReport {
    pub fn new(
        cable: &CableSpec,
        args: &Args,
        sub_segments: usize,
        shape: &Connected,
        scene: Option<&Scene>,
    ) -> Result<Self, Failure> {
        Ok(SegmentReport {
            stage: args.stage,
            cable: cable.name.clone(),
            curve: shape.curve,
            alpha_m: shape.alpha_m,
            bow_m: shape.bow_m,
            length_mm: natural_length_m(cable, sub_segments) * 1e3,
            sub_segments,
            pitch_mm: cable.sub_segment_pitch_m * 1e3,
            twist_correction_deg: shape.twist_correction_rad.map(f64::to_degrees),
            connect_time_us: shape.time_us,
            nodes_mm: millimetres(&shape.nodes),
            frames: rows(&shape.frames),
            metrics: Metrics::of(cable, args, &shape.nodes, scene)?,
            converged: None,
        })
    }

    pub fn add_converged(
        &mut self,
        cable: &CableSpec,
        args: &Args,
        shape: &Converged,
        scene: Option<&Scene>,
    ) -> Result<(), Failure> {
        self.converged = Some(ConvergedReport {
            solver: args.solver,
            iterations: shape.iterations,
            residual: shape.residual,
            residual_unit: shape.residual_unit,
            solve_time_us: shape.time_us,
            twist_deg: shape.twist_rad.map(f64::to_degrees),
            twist_turns: args.twist_turns,
            self_contact_from_deg: shape.self_contact_from_deg,
            nodes_mm: millimetres(&shape.nodes),
            frames: rows(&shape.frames),
            metrics: Metrics::of(cable, args, &shape.nodes, scene)?,
        });
        Ok(())
    }
}

fn natural_length_m(cable: &CableSpec, sub_segments: usize) -> f64 {
    sub_segments as f64 * cable.sub_segment_pitch_m
}

fn millimetres(nodes: &[Point3<f64>]) -> Vec<[f64; 3]> {
    nodes.iter().map(|p| (p.coords * 1e3).into()).collect()
}

fn rows(frames: &[Rotation3<f64>]) -> Vec<[[f64; 3]; 3]> {
    frames.iter().map(matrix_rows).collect()
}

impl Metrics {
    /// Bend radius, stretch and (with a robot) contact of `nodes` between the guides of
    /// `args`.
    fn of(
        cable: &CableSpec,
        args: &Args,
        nodes: &[Point3<f64>],
        scene: Option<&Scene>,
    ) -> Result<Self, Failure> {
        let contact = match scene {
            Some(scene) => scene.contact(nodes)?,
            None => None,
        };
        // The attachment test's own measure of a shape (its robot clearance is the setup's;
        // here the scene's, reported apart).
        let shape = ShapeMetrics::of_shape(
            cable,
            (nodes, cable.sub_segment_pitch_m),
            (&args.start, &args.end),
            None,
            f64::INFINITY,
            0.0,
        );
        let self_contact = shape
            .self_clearance_m
            .is_finite()
            .then(|| SelfContactMetric {
                min_clearance_mm: shape.self_clearance_m * 1e3,
                violation: shape.self_clearance_m < 0.0,
                sub_segments: shape.self_contact_sub_segments.map(|k| k as usize),
            });
        let bend_m = shape.min_bend_radius_m;
        Ok(Metrics {
            self_contact,
            min_bend_radius_mm: bend_m.is_finite().then_some(bend_m * 1e3),
            min_bend_radius_node: shape.min_bend_node,
            cable_min_bend_radius_mm: cable.min_bend_radius_m * 1e3,
            stretch: shape.stretch,
            contact,
        })
    }
}

impl fmt::Display for SegmentReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{} cable, {} mm = {} sub-segments of {} mm",
            self.cable, self.length_mm, self.sub_segments, self.pitch_mm
        )?;
        writeln!(
            f,
            "connected geometry ({}, {:.0} µs)",
            self.curve, self.connect_time_us
        )?;
        if let Some(alpha) = self.alpha_m {
            writeln!(f, "  alpha             {alpha:.6} m")?;
        }
        if let Some(bow) = self.bow_m.filter(|b| *b != 0.0) {
            writeln!(f, "  bow               {bow:.6} m")?;
        }
        if let Some(twist) = self.twist_correction_deg {
            writeln!(f, "  twist correction  {twist:.3}°")?;
        }
        match self.converged {
            // The start shape is not a cable at rest: only the equilibrium is judged.
            Some(_) => self.metrics.write(f, false)?,
            None => self.metrics.write(f, true)?,
        }
        let mut nodes = &self.nodes_mm;
        if let Some(c) = &self.converged {
            writeln!(f, "static equilibrium ({} solver)", c.solver.describe())?;
            writeln!(
                f,
                "  iterations        {} (residual {:.1e} {}, {:.0} µs)",
                c.iterations, c.residual, c.residual_unit, c.solve_time_us
            )?;
            if let Some(twist) = c.twist_deg {
                // No "-0.000°" for a twist that rounds to zero.
                let twist = if twist.abs() < 5e-4 { 0.0 } else { twist };
                let turns = match c.twist_turns {
                    0 => String::new(),
                    n => format!(" ({n:+} whole turns of the end guide)"),
                };
                writeln!(f, "  twist             {twist:.3}°{turns}")?;
            }
            if let Some(angle) = c.self_contact_from_deg {
                writeln!(
                    f,
                    "  the cable passed through itself from {angle:.0}° of the turning on: the \
                     model has no self-contact forces, so the shapes from there are not physical"
                )?;
            }
            c.metrics.write(f, true)?;
            nodes = &c.nodes_mm;
        }
        writeln!(f, "  nodes (mm):")?;
        for (i, p) in nodes.iter().enumerate() {
            writeln!(f, "    {i:>4}  {:>9.3} {:>9.3} {:>9.3}", p[0], p[1], p[2])?;
        }
        Ok(())
    }
}

impl Metrics {
    /// The metrics, each against its limit when `judged`.
    fn write(&self, f: &mut fmt::Formatter<'_>, judged: bool) -> fmt::Result {
        match self.min_bend_radius_mm {
            Some(r) => {
                let verdict = match (judged, r >= self.cable_min_bend_radius_mm) {
                    (false, _) => "",
                    (true, true) => ": ok",
                    (true, false) => ": bent below it",
                };
                writeln!(
                    f,
                    "  min bend radius   {r:.1} mm at node {} (cable minimum {:.1} mm{verdict})",
                    self.min_bend_radius_node, self.cable_min_bend_radius_mm
                )?;
            }
            None => writeln!(f, "  min bend radius   ∞ (straight)")?,
        }
        writeln!(f, "  stretch           {:.6}", self.stretch)?;
        if let Some(c) = &self.self_contact {
            let verdict = match (judged, c.violation) {
                (false, _) => "",
                (true, false) => ": ok",
                (true, true) => ": passes through itself, not a real cable's shape",
            };
            writeln!(
                f,
                "  self-clearance    {:.1} mm between sub-segments {} and {}{verdict}",
                c.min_clearance_mm, c.sub_segments[0], c.sub_segments[1]
            )?;
        }
        if let Some(c) = &self.contact {
            let verdict = match (judged, c.violation) {
                (false, _) => "",
                (true, false) => ": ok",
                (true, true) => ": touches the robot",
            };
            writeln!(
                f,
                "  min clearance     {:.1} mm to {} at sub-segment {} (threshold {:.1} mm{verdict})",
                c.min_clearance_mm, c.link, c.sub_segment, c.threshold_mm
            )?;
        }
        Ok(())
    }
}
