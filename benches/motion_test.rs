//! Motion-test benchmark: the whole 145-sub-segment cable of a plausible path on the bundled
//! Viper s850 pick-and-place setup (C1 60, C2 20, C3 30, C4 35 sub-segments; every segment
//! clear of the robot in the static check at sampled poses), simulated through the first
//! 0.5 s of the bundled pick-and-place motion at the default settings (1/240 s steps of 16
//! substeps of 4 sweeps), clearance, stretch and bend radius measured every step, no settle tail.
//!
//! The figure to read is the time per run: divided by 0.5 it is the wall time per simulated
//! second. Setup, motion and path loading are outside the measurement.

use std::hint::black_box;
use std::time::Duration;

use cable_dict::motion::Motion;
use cable_dict::motion_test::{MotionTestOptions, run};
use cable_dict::path::CablePath;
use cable_dict::setup::Setup;
use criterion::{Criterion, criterion_group, criterion_main};

/// Simulated motion (s).
const SIMULATED_S: f64 = 0.5;

fn bench_motion_test(c: &mut Criterion) {
    let setup = Setup::from_file("robots/viper_s850/pick_and_place.toml").expect("setup");
    let full = Motion::from_csv_file(&setup.robot, "motions/viper_s850/pick_and_place.csv")
        .expect("motion");
    let keep = full.times_s().iter().filter(|&&t| t <= SIMULATED_S).count();
    let motion = Motion::new(
        &setup.robot,
        full.times_s()[..keep].to_vec(),
        full.samples()[..keep].to_vec(),
    )
    .expect("truncated motion");
    let path = CablePath {
        lengths: vec![60, 20, 30, 35],
        configurations: vec![6, 5, 3, 4, 0],
    };
    let options = MotionTestOptions {
        settle_tail_s: 0.0,
        ..MotionTestOptions::for_setup(&setup)
    };
    let mut group = c.benchmark_group("motion_test");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(15));
    group.bench_function("pick_and_place 0.5 s, 145 sub-segments", |b| {
        b.iter(|| {
            let report = run(&setup, &path, &motion, &options).expect("motion test");
            black_box(report.steps)
        })
    });
    group.finish();
}

criterion_group!(benches, bench_motion_test);
criterion_main!(benches);
