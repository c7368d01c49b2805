//! Benchmark of the chain search on an instance the size of the real problem: 4 segments,
//! guide configuration counts 7, 12, 12, 7, 1 and about 2000, 2000, 5000, 200 robust PVs per
//! segment (lengths 20–200 sub-segments, random but fixed):
//!
//! - `ChainSearch::new` followed by `shortest`;
//! - the first 100 chains of `k_best` on a search built once.

use std::hint::black_box;

use cable_dict::chain::ChainSearch;
use cable_dict::path::Pv;
use criterion::{Criterion, criterion_group, criterion_main};

const CONFIG_COUNTS: [usize; 5] = [7, 12, 12, 7, 1];
const PV_COUNTS: [usize; 4] = [2000, 2000, 5000, 200];

/// splitmix64, so that the instance is the same on every run.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

fn instance() -> Vec<Vec<Pv>> {
    let mut state = 7;
    let mut below = |n: usize| (splitmix(&mut state) % n as u64) as usize;
    (0..PV_COUNTS.len())
        .map(|m| {
            (0..PV_COUNTS[m])
                .map(|_| Pv {
                    sub_segments: 20 + below(181),
                    start: below(CONFIG_COUNTS[m]),
                    end: below(CONFIG_COUNTS[m + 1]),
                })
                .collect()
        })
        .collect()
}

fn bench_chain(c: &mut Criterion) {
    let segments = instance();
    c.bench_function("chain new + shortest (7/12/12/7/1, 9200 PVs)", |b| {
        b.iter(|| {
            let search = ChainSearch::new(&CONFIG_COUNTS, black_box(&segments)).expect("valid");
            search.shortest()
        })
    });
    let search = ChainSearch::new(&CONFIG_COUNTS, &segments).expect("valid");
    c.bench_function("chain first 100 of k_best (7/12/12/7/1, 9200 PVs)", |b| {
        b.iter(|| black_box(&search).k_best().take(100).count())
    });
}

criterion_group!(benches, bench_chain);
criterion_main!(benches);
