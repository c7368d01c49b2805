//! Cable physics benchmarks, each comparison measured in one run:
//!
//! - **static solve**: the equilibrium of a 3D S-bend with a 45° torsion mismatch under
//!   gravity (SMC cable, 10 mm pitch), 250 mm and 500 mm, from the Hermite + RMF connected
//!   geometry: quasi-static Newton solver vs. rapier3d relaxation. The
//!   target is < 1 ms for the quasi-static 500 mm solve.
//! - **table 6** (the paper's comparison): the connected geometry by Hermite + RMF vs. by
//!   linear deformation (a straight cable dragged into place in rapier), and the totals
//!   connected + convergent: Hermite + quasi-static, Hermite + rapier (the paper's own new
//!   method), linear + rapier (the previous method). A coaxial slack span (guides 80 % of the
//!   cable length apart, both along +x), as in the paper's figure.

use std::hint::black_box;
use std::time::Duration;

use cable_dict::cable::CableSpec;
use cable_dict::geometry::connect;
use cable_dict::pose::{Pose, pose_from_xyz_rpy};
use cable_dict::rigid_chain::{
    ConvergenceWindow, DynamicsSettings, LinearConnect, SegmentShape, connect_linear, relax,
};
use cable_dict::statics::{FarEnd, RodParameters, SolverOptions, solve_segment};
use criterion::{
    BenchmarkGroup, Criterion, criterion_group, criterion_main, measurement::WallTime,
};
use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};

const GRAVITY: Vector3<f64> = Vector3::new(0.0, 0.0, -9.81);

fn smc() -> CableSpec {
    match CableSpec::from_file("cables/smc_le_cp_3_paper.toml") {
        Ok(cable) => cable,
        Err(e) => panic!("{e}"),
    }
}

/// Guide frame whose +z axis is world +x, at `x_m` on the x axis.
fn along_x(x_m: f64) -> Pose {
    pose_from_xyz_rpy([x_m, 0.0, 0.0], [0.0, std::f64::consts::FRAC_PI_2, 0.0])
}

/// The connected-geometry benchmark's S-bend, scaled to the cable length.
fn s_bend(length_m: f64) -> (Pose, Pose) {
    let tilt = Rotation3::from_axis_angle(&Vector3::y_axis(), 60f64.to_radians());
    let roll = Rotation3::from_axis_angle(&Vector3::z_axis(), 45f64.to_radians());
    let end = Isometry3::from_parts(
        Translation3::new(0.6 * length_m, 0.2 * length_m, 0.1 * length_m),
        UnitQuaternion::from_rotation_matrix(&(tilt * roll)),
    );
    (along_x(0.0), end)
}

/// A segment benchmark case: guides, sub-segment count, label.
struct Case {
    label: String,
    start: Pose,
    end: Pose,
    sub_segments: usize,
}

impl Case {
    fn hermite(&self, cable: &CableSpec) -> cable_dict::geometry::ConnectedGeometry {
        let down = -Vector3::z_axis();
        match connect(
            &self.start,
            &self.end,
            self.sub_segments,
            cable.sub_segment_pitch_m,
            &down,
        ) {
            Ok(geometry) => geometry,
            Err(e) => panic!("{}: {e}", self.label),
        }
    }
}

fn cases(shape: fn(f64) -> (Pose, Pose), name: &str) -> Vec<Case> {
    [25, 50]
        .into_iter()
        .map(|sub_segments| {
            let (start, end) = shape(sub_segments as f64 * 0.01);
            Case {
                label: format!("{name} {} mm", sub_segments * 10),
                start,
                end,
                sub_segments,
            }
        })
        .collect()
}

fn coaxial(length_m: f64) -> (Pose, Pose) {
    (along_x(0.0), along_x(0.8 * length_m))
}

fn quasi_static(cable: &CableSpec, case: &Case, nodes: &[nalgebra::Point3<f64>], twist: f64) {
    let params = RodParameters::new(cable, GRAVITY);
    let result = solve_segment(
        &params,
        &case.start,
        &FarEnd::Clamped(case.end),
        black_box(nodes),
        Some(twist),
        &SolverOptions::default(),
    );
    if let Err(e) = result {
        panic!("{}: {e}", case.label);
    }
}

fn rapier_relax(
    cable: &CableSpec,
    case: &Case,
    geometry_nodes: &[nalgebra::Point3<f64>],
    frames: &[Rotation3<f64>],
) {
    let shape = SegmentShape {
        start_guide: case.start,
        end_guide: case.end,
        nodes: black_box(geometry_nodes),
        frames,
    };
    let settings = DynamicsSettings::relaxation(GRAVITY);
    if let Err(e) = relax(cable, &shape, &settings, &ConvergenceWindow::default()) {
        panic!("{}: {e}", case.label);
    }
}

fn linear(cable: &CableSpec, case: &Case) -> cable_dict::rigid_chain::Relaxation {
    let settings = DynamicsSettings::relaxation(GRAVITY);
    match connect_linear(
        cable,
        &case.start,
        &case.end,
        case.sub_segments,
        &settings,
        &LinearConnect::default(),
    ) {
        Ok(relaxation) => relaxation,
        Err(e) => panic!("{}: {e}", case.label),
    }
}

fn slow_group<'a>(c: &'a mut Criterion, name: &str) -> BenchmarkGroup<'a, WallTime> {
    let mut group = c.benchmark_group(name);
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(5));
    group
}

fn bench_static_solve(c: &mut Criterion) {
    let cable = smc();
    let mut group = slow_group(c, "static solve");
    for case in cases(s_bend, "S-bend") {
        let geometry = case.hermite(&cable);
        group.bench_function(format!("quasi-static {}", case.label), |b| {
            b.iter(|| {
                quasi_static(
                    &cable,
                    &case,
                    &geometry.nodes,
                    geometry.twist_correction_rad,
                )
            })
        });
        group.bench_function(format!("rapier relaxation {}", case.label), |b| {
            b.iter(|| rapier_relax(&cable, &case, &geometry.nodes, &geometry.frames))
        });
    }
    group.finish();
}

fn bench_table_6(c: &mut Criterion) {
    let cable = smc();
    let mut group = slow_group(c, "table 6");
    for case in cases(coaxial, "coaxial") {
        group.bench_function(format!("connected hermite+rmf {}", case.label), |b| {
            b.iter(|| case.hermite(&cable))
        });
        group.bench_function(format!("connected linear {}", case.label), |b| {
            b.iter(|| linear(&cable, &case))
        });
        group.bench_function(format!("total hermite+quasi-static {}", case.label), |b| {
            b.iter(|| {
                let geometry = case.hermite(&cable);
                quasi_static(
                    &cable,
                    &case,
                    &geometry.nodes,
                    geometry.twist_correction_rad,
                )
            })
        });
        group.bench_function(format!("total hermite+rapier {}", case.label), |b| {
            b.iter(|| {
                let geometry = case.hermite(&cable);
                rapier_relax(&cable, &case, &geometry.nodes, &geometry.frames)
            })
        });
        group.bench_function(format!("total linear+rapier {}", case.label), |b| {
            b.iter(|| {
                let connected = linear(&cable, &case);
                rapier_relax(&cable, &case, &connected.nodes, &connected.frames)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_static_solve, bench_table_6);
criterion_main!(benches);
