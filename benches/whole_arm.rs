//! The whole-arm dress pack of a committed public robot: the ABB IRB 2400's eight clamps from
//! the turret to the tool (`robots/abb_irb2400/whole_arm.toml`, seven pieces, 8.2 million
//! candidate pieces) over the project's machine-tending motion, `solve` end to end — the
//! attachment test, the chain search, the static sweep and the motion tests — with learning
//! from failed motion tests (the default) and strictly shortest first (`--no-learning`,
//! which spends its 50 motion tests unsolved), measured in one run.
//!
//! Each solve takes about a minute on two cores, so criterion's ten samples per function
//! take about 20 minutes: `cargo bench --bench whole_arm`.

use std::hint::black_box;
use std::time::Duration;

use cable_dict::motion::Motion;
use cable_dict::setup::Setup;
use cable_dict::solve::{SolveOptions, Status, solve};
use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};

fn bench_whole_arm(c: &mut Criterion) {
    let setup = Setup::from_file("robots/abb_irb2400/whole_arm.toml").expect("setup");
    let motion = Motion::from_csv_file(&setup.robot, "motions/abb_irb2400/machine_tending.csv")
        .expect("motion");
    let mut group = c.benchmark_group("whole_arm_irb2400");
    group
        .sampling_mode(SamplingMode::Flat)
        .sample_size(10)
        .measurement_time(Duration::from_secs(60));
    for (name, learn) in [("learning", true), ("strict", false)] {
        let options = SolveOptions {
            learn,
            ..SolveOptions::default()
        };
        group.bench_function(name, |b| {
            b.iter(|| {
                let report = solve(&setup, &motion, &options).expect("solves");
                assert!(!learn || report.status == Status::Solved);
                black_box(report)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_whole_arm);
criterion_main!(benches);
