//! Motion-test benchmark, both engines in one run: the whole cable of the bundled
//! pick-and-place solution (C1 54, C2 20, C3 40, C4 20 sub-segments; guide configurations
//! 5, 1, 1, 2, 0 of robots/viper_s850/hand_written/pick_and_place.toml, realistic SMC cable) simulated
//! through the first 2 s of the bundled pick-and-place motion (joint 1 starts its
//! acceleration), clearance, stretch and bend radius measured every step, no settle tail:
//!
//! - the implicit engine (BDF2 on the statics' energy, steps of 1/240 s);
//! - the rigid chain in rapier3d (the paper's kind of simulation, 1/240 s steps of 16
//!   substeps of 4 sweeps).
//!
//! The time per run divided by 2 is the wall time per simulated second; the ratio of the two
//! is the speed-up. Setup, motion and path loading are outside the measurement.

use std::hint::black_box;
use std::time::Duration;

use cable_dict::motion::Motion;
use cable_dict::motion_test::{EngineKind, MotionTestOptions, run};
use cable_dict::path::CablePath;
use cable_dict::setup::Setup;
use criterion::{Criterion, criterion_group, criterion_main};

/// Simulated motion (s).
const SIMULATED_S: f64 = 2.0;

fn bench_motion_test(c: &mut Criterion) {
    let setup =
        Setup::from_file("robots/viper_s850/hand_written/pick_and_place.toml").expect("setup");
    let full = Motion::from_csv_file(&setup.robot, "motions/viper_s850/pick_and_place.csv")
        .expect("motion");
    let keep = full.times_s().iter().filter(|&&t| t <= SIMULATED_S).count();
    let motion = Motion::new(
        &setup.robot,
        full.times_s()[..keep].to_vec(),
        full.samples()[..keep].to_vec(),
    )
    .expect("truncated motion");
    let path = CablePath::through_every_guide(vec![54, 20, 40, 20], vec![5, 1, 1, 2, 0]);
    let mut group = c.benchmark_group("motion_test");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(20));
    for (name, engine) in [
        ("implicit", EngineKind::Implicit),
        ("rigid chain", EngineKind::RigidChain),
    ] {
        let options = MotionTestOptions {
            settle_tail_s: 0.0,
            ..MotionTestOptions::new(engine.with_defaults(setup.gravity_m_s2))
        };
        group.bench_function(
            format!("{name}, pick_and_place d*, 2 s, 134 sub-segments"),
            |b| {
                b.iter(|| {
                    let report = run(&setup, &path, &motion, &options).expect("motion test");
                    black_box(report.steps)
                })
            },
        );
    }
    group.finish();
}

criterion_group!(benches, bench_motion_test);
criterion_main!(benches);
