//! Attachment-test benchmarks on the bundled pick-and-place setup (realistic SMC cable) and
//! motion, measured in one run:
//!
//! - **static solves with continuation**: every segment's candidate lengths (and the
//!   robustness lengths beyond them) between its first guide configurations, at its first
//!   test pose, each solved from the last ones ([`Evaluator::first_rejections`], what the
//!   attachment test does for every guide pair): 122 solves from 10 to 77 sub-segments, the
//!   attachment test's mix; the time divided by 122 is the cost of one static solve with its
//!   connected geometry (the first two lengths of a pair) and stress checks;
//! - **static solve from the connected geometry**: one of those PVs (S = 55) solved from its
//!   Hermite start shape alone ([`Evaluator::check`]), as every solve was before continuation;
//! - **attachment test**: the whole test of the bundled setup (all four segments, their
//!   robustness lengths, every test pose), on the machine's threads.

use std::hint::black_box;
use std::time::Duration;

use cable_dict::attachment::{
    ConnectMethod, Evaluator, SegmentPoses, TestPose, admissible_pvs, attachment_test, needed_pvs,
};
use cable_dict::motion::Motion;
use cable_dict::path::Pv;
use cable_dict::setup::Setup;
use criterion::{Criterion, criterion_group, criterion_main};

fn bench_attachment(c: &mut Criterion) {
    let setup =
        Setup::from_file("robots/viper_s850/hand_written/pick_and_place.toml").expect("setup");
    let motion = Motion::from_csv_file(&setup.robot, "motions/viper_s850/pick_and_place.csv")
        .expect("motion");
    let poses = SegmentPoses::new(&setup, &motion).expect("poses");
    let evaluator = Evaluator::new(&setup, ConnectMethod::Hermite).expect("evaluator");
    // Per segment: the lengths (> 0) the attachment test evaluates for its first guide
    // configurations, at its first test pose.
    let robustness = setup.robustness;
    let work: Vec<(usize, Vec<usize>, &[TestPose])> = (0..setup.segment_count())
        .map(|m| {
            let first_pair: Vec<Pv> = admissible_pvs(&setup, m)
                .into_iter()
                .filter(|pv| (pv.start, pv.end) == (0, 0))
                .collect();
            let lengths = needed_pvs(&first_pair, robustness.delta_s, robustness.range)
                .iter()
                .map(|pv| pv.sub_segments)
                .filter(|&s| s > 0)
                .collect();
            (m, lengths, &poses.poses[m][..1])
        })
        .collect();
    let solves: usize = work.iter().map(|(_, lengths, _)| lengths.len()).sum();
    let mut group = c.benchmark_group("attachment");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(5));
    group.bench_function(
        format!("static solves with continuation ({solves} solves)"),
        |b| {
            b.iter(|| {
                for (m, lengths, pose) in &work {
                    black_box(evaluator.first_rejections(*m, (0, 0), lengths, pose));
                }
            })
        },
    );
    let pv = Pv {
        sub_segments: 55,
        start: 0,
        end: 0,
    };
    group.bench_function(
        "C1 static solve from the connected geometry (S = 55)",
        |b| b.iter(|| black_box(evaluator.check(0, &pv, &poses.poses[0][0]))),
    );
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    group.bench_function("whole attachment test, bundled pick-and-place", |b| {
        b.iter(|| black_box(attachment_test(&evaluator, &poses)))
    });
    group.finish();
}

criterion_group!(benches, bench_attachment);
criterion_main!(benches);
