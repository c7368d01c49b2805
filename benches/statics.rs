//! Quasi-static equilibrium of one segment from the Hermite + RMF connected geometry: a 3D
//! S-bend with a 45° torsion mismatch between the guides, under gravity, SMC cable, 10 mm
//! pitch, 250 mm and 500 mm of cable. Target: under 1 ms for 500 mm.

use std::hint::black_box;

use cable_dict::cable::CableSpec;
use cable_dict::geometry::connect;
use cable_dict::pose::{Pose, pose_from_xyz_rpy};
use cable_dict::statics::{FarEnd, RodParameters, SolverOptions, solve_segment};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};

/// The connected-geometry benchmark's S-bend, scaled to the cable length.
fn s_bend(length_m: f64) -> (Pose, Pose) {
    let tilt = Rotation3::from_axis_angle(&Vector3::y_axis(), 60f64.to_radians());
    let roll = Rotation3::from_axis_angle(&Vector3::z_axis(), 45f64.to_radians());
    let end = Isometry3::from_parts(
        Translation3::new(0.6 * length_m, 0.2 * length_m, 0.1 * length_m),
        UnitQuaternion::from_rotation_matrix(&(tilt * roll)),
    );
    (pose_from_xyz_rpy([0.0; 3], [0.0, std::f64::consts::FRAC_PI_2, 0.0]), end)
}

fn bench_static(c: &mut Criterion) {
    let cable = match CableSpec::from_file("cables/smc_le_cp_3.toml") {
        Ok(cable) => cable,
        Err(e) => panic!("{e}"),
    };
    let params = RodParameters::new(&cable, Vector3::new(0.0, 0.0, -9.81));
    let options = SolverOptions::default();
    for sub_segments in [25, 50] {
        let length = sub_segments as f64 * cable.sub_segment_pitch_m;
        let (start, end) = s_bend(length);
        let down = -Vector3::z_axis();
        let connected = match connect(&start, &end, sub_segments, cable.sub_segment_pitch_m, &down) {
            Ok(g) => g,
            Err(e) => panic!("{e}"),
        };
        let name = format!("quasi-static S-bend {} mm", sub_segments * 10);
        c.bench_function(&name, |b| {
            b.iter(|| {
                solve_segment(
                    &params,
                    &start,
                    &FarEnd::Clamped(end),
                    black_box(&connected.nodes),
                    None,
                    &options,
                )
            })
        });
    }
}

criterion_group!(benches, bench_static);
criterion_main!(benches);
