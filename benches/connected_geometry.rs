//! Benchmark of `connect` between two typical guide frames, 10 mm pitch, sagging towards −z:
//!
//! - S-bend: start along +x, end at (0.6, 0.2, 0.1)·cable length, tilted 30° up and rolled
//!   45° about its axis (25 and 50 sub-segments; both curves are built, the bowed one has the
//!   lower bending energy and is placed);
//! - coaxial slack: both guides along +x, 400 mm apart, 500 mm of cable (50 sub-segments; the
//!   Hermite curve folds, the bowed one is placed).
//!
//! Target: < 20 µs for 50 sub-segments.

use std::hint::black_box;

use cable_dict::geometry::connect;
use cable_dict::pose::{Pose, pose_from_xyz_rpy};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};

const PITCH_M: f64 = 0.010;

/// Guide frame whose +z axis is world +x (pitch +90°), at `x_m` on the x axis.
fn along_x(x_m: f64) -> Pose {
    pose_from_xyz_rpy([x_m, 0.0, 0.0], [0.0, std::f64::consts::FRAC_PI_2, 0.0])
}

fn s_bend(length_m: f64) -> (Pose, Pose) {
    let tilt = Rotation3::from_axis_angle(&Vector3::y_axis(), 60f64.to_radians());
    let roll = Rotation3::from_axis_angle(&Vector3::z_axis(), 45f64.to_radians());
    let end = Isometry3::from_parts(
        Translation3::new(0.6 * length_m, 0.2 * length_m, 0.1 * length_m),
        UnitQuaternion::from_rotation_matrix(&(tilt * roll)),
    );
    (along_x(0.0), end)
}

fn bench_connect(c: &mut Criterion) {
    let down = -Vector3::z_axis();
    let mut cases: Vec<(String, Pose, Pose, usize)> = [25, 50]
        .into_iter()
        .map(|sub_segments| {
            let (start, end) = s_bend(sub_segments as f64 * PITCH_M);
            let name = format!("connect S-bend {sub_segments} sub-segments");
            (name, start, end, sub_segments)
        })
        .collect();
    cases.push((
        "connect coaxial slack (bowed) 50 sub-segments".into(),
        along_x(0.0),
        along_x(0.4),
        50,
    ));
    for (name, start, end, sub_segments) in cases {
        c.bench_function(&name, |b| {
            b.iter(|| {
                connect(
                    black_box(&start),
                    black_box(&end),
                    black_box(sub_segments),
                    PITCH_M,
                    &down,
                )
            })
        });
    }
}

criterion_group!(benches, bench_connect);
criterion_main!(benches);
