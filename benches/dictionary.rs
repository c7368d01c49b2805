//! Benchmarks of dictionary access: `Dictionary::open` followed by one PV lookup, on a small
//! dictionary (the test fixture setup, 16 directions, ~25 kB) and on one 100× larger (the
//! same setup, 2560 directions, ~2.6 MB). Opening checks the structure and the header only,
//! so both should take the same time; `verify` (every checksum) is measured on both for
//! contrast, and it does grow with the file.

use std::hint::black_box;
use std::path::{Path, PathBuf};

use cable_dict::dictionary::{BuildOptions, Dictionary, build, write_dictionary};
use cable_dict::path::Pv;
use cable_dict::setup::Setup;
use criterion::{Criterion, criterion_group, criterion_main};

const SETUP: &str = "tests/data/dict_setup.toml";
/// The fixture's one clamp catalogue (link_4: G2's two places and G3's other one).
const LINK: usize = 0;

fn built_file(dir: &Path, directions: usize) -> PathBuf {
    let setup = Setup::from_file(SETUP).expect("fixture setup");
    let options = BuildOptions {
        directions,
        shard: None,
    };
    let built = build(&setup, &options).expect("builds");
    let path = dir.join(format!("fixture-{directions}.cdict"));
    write_dictionary(&path, &built).expect("written");
    path
}

fn open_and_lookup(path: &Path) -> usize {
    let dictionary = Dictionary::open(path).expect("opens");
    // G2 "left z250" → G3 "back z280", 60 mm.
    let pv = Pv {
        sub_segments: 6,
        start: 0,
        end: 2,
    };
    dictionary.lookup(LINK, &pv).map_or(0, |(_, rows)| {
        rows.iter().filter(|r| r.values().is_some()).count()
    })
}

fn dictionary_access(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp dir");
    for (label, directions) in [("small", 16), ("100x", 2560)] {
        let path = built_file(dir.path(), directions);
        let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        c.bench_function(&format!("open+lookup {label} ({bytes} B)"), |b| {
            b.iter(|| black_box(open_and_lookup(black_box(&path))))
        });
        let dictionary = Dictionary::open(&path).expect("opens");
        c.bench_function(&format!("verify {label} ({bytes} B)"), |b| {
            b.iter(|| black_box(dictionary.verify().is_ok()))
        });
    }
}

criterion_group!(benches, dictionary_access);
criterion_main!(benches);
