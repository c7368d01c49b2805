//! The dictionaries shipped in `dictionaries/` are exactly what `cable-dict build` makes of
//! the bundled setups today: each is rebuilt with the parameters its header records (the
//! direction count) and compared byte for byte. A change to the solver, the metrics or a
//! bundled setup that alters any result fails here until the files are rebuilt
//! (docs/dictionaries.md). The rebuild is the one the dictionary tests share.

use cable_dict::dictionary::Dictionary;
use cable_dict::setup::Setup;

/// Rebuilds `dictionaries/viper_s850_{name}.cdict` from `setup_path` with the direction count
/// its header records (the build other tests share) and compares the bytes.
fn rebuilds_to_the_same_bytes(name: &str, setup_path: &'static str) {
    let shipped = format!("dictionaries/viper_s850_{name}.cdict");
    let dictionary = Dictionary::open(&shipped).expect("the shipped dictionary opens");
    dictionary.verify().expect("and verifies");
    let header = dictionary.header();
    assert!(
        setup_path.ends_with(&format!("/{}", header.setup.file_name)),
        "{shipped} was built from {}, not {setup_path}",
        header.setup.file_name
    );
    let setup = Setup::from_file(setup_path).expect("bundled setup");
    assert_eq!(
        header.setup_hash, setup.content_hash,
        "{shipped} was built from another version of {setup_path}: rebuild it"
    );
    let directions = header.directions.count as usize;
    let rebuilt = crate::common::built_dictionary(setup_path, directions);
    let rebuilt = std::fs::read(rebuilt.path()).expect("the rebuild is readable");
    let bytes = std::fs::read(&shipped).expect("readable");
    assert!(
        rebuilt == bytes,
        "{shipped} differs from a rebuild ({} vs {} bytes): rebuild it with \
         `cable-dict build {setup_path} -o {shipped} --directions {directions}`",
        rebuilt.len(),
        bytes.len(),
    );
}

#[test]
fn the_shipped_pick_and_place_dictionary_rebuilds_to_the_same_bytes() {
    rebuilds_to_the_same_bytes(
        "pick_and_place",
        "robots/viper_s850/hand_written/pick_and_place.toml",
    );
}

#[test]
fn the_shipped_inspection_dictionary_rebuilds_to_the_same_bytes() {
    rebuilds_to_the_same_bytes(
        "inspection",
        "robots/viper_s850/hand_written/inspection.toml",
    );
}
