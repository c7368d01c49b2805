//! Structure-aware fuzzing of dictionaries: a valid dictionary (and two shards of it) is
//! edited field by field — header numbers, directions, catalogues, records, margins, the
//! embedded setup, URDF and cable texts — by operations decoded from the input, then
//! re-encoded with valid checksums (a forger's file). Every reader must refuse it or work
//! with it, never panic: `check_bytes`, `open` + `verify` + `setup`, lookups of stored pieces
//! at a few directions, and `merge` of an edited shard with its genuine sibling.
#![no_main]

use cable_dict::dictionary::format::{MarginRecord, ShardRange};
use cable_dict::dictionary::{BuildOptions, Built, Dictionary, build, check_bytes, merge};
use cable_dict::setup::Setup;
use nalgebra::Vector3;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The fixture dictionary and its two shards, built once per process.
fn bases() -> &'static (Built, [Built; 2]) {
    static BASES: OnceLock<(Built, [Built; 2])> = OnceLock::new();
    BASES.get_or_init(|| {
        let setup = Setup::from_file(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/dict_setup.toml"))
            .expect("the fixture setup loads");
        let options = |shard| BuildOptions { directions: 8, shard };
        let whole = build(&setup, &options(None)).expect("builds");
        let shards = [0, 1].map(|i| build(&setup, &options(Some((i, 2)))).expect("builds"));
        (whole, shards)
    })
}

/// Reads operations of 10 bytes (kind, index, 8 value bytes) and applies them.
fn edit(built: &mut Built, data: &[u8]) {
    for op in data.chunks_exact(10) {
        let (kind, index) = (op[0], op[1] as usize);
        let mut word = [0u8; 8];
        word.copy_from_slice(&op[2..10]);
        let v = u64::from_le_bytes(word);
        let x = f64::from_bits(v);
        let h = &mut built.header;
        match kind % 16 {
            0 => h.directions.count = v as u32,
            1 => h.directions.covering_radius_rad = x,
            2 => h.directions.gravity_m_s2 = x,
            3 => h.directions.probes = v as u32,
            4 => {
                let n = built.directions.len().max(1);
                if let Some(d) = built.directions.get_mut(index % n) {
                    d[(v % 3) as usize] = x;
                }
            }
            5 => {
                let n = built.pvs.len().max(1);
                if let Some(r) = built.pvs.get_mut(index % n) {
                    match v % 7 {
                        0 => r.sub_segments = (v >> 8) as u32,
                        1 => r.link = (v >> 8) as u16,
                        2 => r.start = (v >> 8) as u16,
                        3 => r.end = (v >> 8) as u16,
                        4 => r.flags = (v >> 8) as u16,
                        5 => r.error_factor = [(v >> 8) as u8, (v >> 16) as u8, (v >> 24) as u8],
                        _ => r.reserved = (v >> 8) as u8,
                    }
                }
            }
            6 => {
                let n = built.results.len().max(1);
                if let Some(m) = built.results.get_mut(index % n) {
                    *m = MarginRecord {
                        clearance: v as i16,
                        stretch: (v >> 16) as i16,
                        bend: (v >> 32) as i16,
                    };
                }
            }
            7 => {
                let n = h.links.len().max(1);
                if let Some(link) = h.links.get_mut(index % n) {
                    match v % 6 {
                        0 => link.first_pv = v >> 8,
                        1 => link.d1_all = v >> 8,
                        2 => link.margin_error[(v >> 8) as usize % 3] = x,
                        3 => link.lengths.push((v >> 8) as u32),
                        4 => {
                            link.lengths.pop();
                        }
                        _ => {
                            let k = (v >> 8) as usize % link.lengths.len().max(1);
                            if let Some(s) = link.lengths.get_mut(k) {
                                *s = (v >> 16) as u32;
                            }
                        }
                    }
                }
            }
            8 => {
                let n = h.links.len().max(1);
                if let Some(link) = h.links.get_mut(index % n) {
                    let c = (v % 251) as usize % link.clamps.len().max(1);
                    match (v >> 8) % 4 {
                        0 => {
                            link.clamps.truncate(c);
                        }
                        1 => {
                            if let Some(clamp) = link.clamps.get(c).cloned() {
                                link.clamps.push(clamp);
                            }
                        }
                        2 => {
                            if let Some(clamp) = link.clamps.get_mut(c) {
                                clamp.position_m[(v >> 16) as usize % 3] = x;
                            }
                        }
                        _ => {
                            if let Some(clamp) = link.clamps.get_mut(c) {
                                clamp.rotation_xyzw[(v >> 16) as usize % 4] = x;
                            }
                        }
                    }
                }
            }
            9 => splice(&mut h.setup.text, index, v),
            10 => splice(&mut h.setup.robot_text, index, v),
            11 => splice(&mut h.setup.cable_text, index, v),
            12 => h.pv_total = v,
            13 => h.shard = Some(ShardRange { index: v as u32, count: (v >> 32) as u32, first_pv: index as u64, end_pv: v >> 8 }),
            14 => {
                let keep = (v as usize) % (built.pvs.len() + 1);
                built.pvs.truncate(keep);
            }
            _ => {
                let keep = (v as usize) % (built.results.len() + 1);
                built.results.truncate(keep);
            }
        }
    }
}

/// Replaces one byte of `text` (at a char boundary; the text stays UTF-8) or truncates it.
fn splice(text: &mut String, index: usize, v: u64) {
    let at = (v as usize >> 8) % (text.len() + 1);
    if !text.is_char_boundary(at) {
        return;
    }
    match index % 3 {
        0 => text.truncate(at),
        1 => text.insert(at, char::from((v & 0x7f) as u8)),
        _ => {
            // Repeating a part triples at most; bounded so that the harness itself stays
            // small (the readers' own limits are what is under test).
            let copies = (v & 3) as usize;
            if text.len() + (text.len() - at) * copies <= 1 << 20 {
                let rest = text.split_off(at);
                text.push_str(&rest.repeat(copies));
            }
        }
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new("/dev/shm").exists().then(|| PathBuf::from("/dev/shm")).unwrap_or_else(std::env::temp_dir);
    dir.join(format!("cable-dict-fuzz-{}-{name}", std::process::id()))
}

fn exercise(path: &Path) {
    let Ok(dictionary) = Dictionary::open(path) else {
        return;
    };
    if dictionary.verify().is_err() {
        return;
    }
    let _ = dictionary.setup();
    let downs = [Vector3::new(0.0, 0.0, -1.0), Vector3::new(0.6, -0.8, 0.0), Vector3::new(f64::NAN, 0.0, 1.0)];
    for record in dictionary.pv_records().iter().take(16) {
        for down in &downs {
            let _ = dictionary.answer_at(usize::from(record.link), &record.pv(), down);
        }
    }
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let (whole, shards) = bases();
    let Some((&which, ops)) = data.split_first() else {
        return;
    };
    if which % 2 == 0 {
        let mut built = whole.clone();
        edit(&mut built, ops);
        let Ok(bytes) = built.to_bytes() else {
            return;
        };
        // What verify refuses in memory it refuses on disk too: only an accepted file is
        // worth opening, looking up and loading.
        if check_bytes(&bytes).is_err() {
            return;
        }
        let path = scratch("whole.cdict");
        if std::fs::write(&path, &bytes).is_ok() {
            exercise(&path);
        }
        let _ = std::fs::remove_file(&path);
    } else {
        let mut edited = shards[0].clone();
        edit(&mut edited, ops);
        let paths = [scratch("shard0.cdict"), scratch("shard1.cdict")];
        let written = edited.to_bytes().ok().and_then(|bytes| {
            std::fs::write(&paths[0], bytes).ok()?;
            std::fs::write(&paths[1], shards[1].to_bytes().ok()?).ok()
        });
        if written.is_some() {
            let _ = merge(&paths, None);
        }
        for path in &paths {
            let _ = std::fs::remove_file(path);
        }
    }
});
