//! Benchmark of `connect` on an S-bend between two typical guide frames: start along +x, end
//! tilted 30° up and rolled 45° about its axis, at (0.6, 0.2, 0.1)·cable length.
//! Target: < 20 µs for 50 sub-segments.

use std::hint::black_box;

use cable_dict::geometry::connect;
use cable_dict::pose::{Pose, pose_from_xyz_rpy};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};

const PITCH_M: f64 = 0.010;

fn s_bend(length_m: f64) -> (Pose, Pose) {
    // pitch +90° turns the guide's +z onto the world +x axis.
    let start = pose_from_xyz_rpy([0.0, 0.0, 0.0], [0.0, std::f64::consts::FRAC_PI_2, 0.0]);
    let tilt = Rotation3::from_axis_angle(&Vector3::y_axis(), 60f64.to_radians());
    let roll = Rotation3::from_axis_angle(&Vector3::z_axis(), 45f64.to_radians());
    let end = Isometry3::from_parts(
        Translation3::new(0.6 * length_m, 0.2 * length_m, 0.1 * length_m),
        UnitQuaternion::from_rotation_matrix(&(tilt * roll)),
    );
    (start, end)
}

fn bench_connect(c: &mut Criterion) {
    for sub_segments in [25, 50] {
        let (start, end) = s_bend(sub_segments as f64 * PITCH_M);
        let name = format!("connect S-bend {sub_segments} sub-segments");
        c.bench_function(&name, |b| {
            b.iter(|| {
                connect(
                    black_box(&start),
                    black_box(&end),
                    black_box(sub_segments),
                    PITCH_M,
                )
            })
        });
    }
}

criterion_group!(benches, bench_connect);
criterion_main!(benches);
