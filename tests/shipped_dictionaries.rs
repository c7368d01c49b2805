//! The dictionaries shipped in `dictionaries/` are exactly what `cable-dict build` makes of
//! the bundled setups today: each is rebuilt with the parameters its header records (the
//! direction count) and compared byte for byte. A change to the solver, the metrics or a
//! bundled setup that alters any result fails here until the files are rebuilt
//! (docs/dictionaries.md).

use cable_dict::dictionary::{BuildOptions, Dictionary, build};
use cable_dict::setup::Setup;

fn rebuilds_to_the_same_bytes(name: &str) {
    let shipped = format!("dictionaries/viper_s850_{name}.cdict");
    let dictionary = Dictionary::open(&shipped).expect("the shipped dictionary opens");
    dictionary.verify().expect("and verifies");
    let header = dictionary.header();
    let setup_path = format!("robots/viper_s850/hand_written/{}", header.setup.file_name);
    let setup = Setup::from_file(&setup_path).expect("bundled setup");
    assert_eq!(
        header.setup_hash, setup.content_hash,
        "{shipped} was built from another version of {setup_path}: rebuild it"
    );
    let options = BuildOptions {
        directions: header.directions.count as usize,
        shard: None,
    };
    let rebuilt = build(&setup, &options)
        .expect("builds")
        .to_bytes()
        .expect("encodes");
    let bytes = std::fs::read(&shipped).expect("readable");
    assert!(
        rebuilt == bytes,
        "{shipped} differs from a rebuild ({} vs {} bytes): rebuild it with \
         `cable-dict build {setup_path} -o {shipped} --directions {}`",
        rebuilt.len(),
        bytes.len(),
        options.directions
    );
}

#[test]
fn the_shipped_pick_and_place_dictionary_rebuilds_to_the_same_bytes() {
    rebuilds_to_the_same_bytes("pick_and_place");
}

#[test]
fn the_shipped_inspection_dictionary_rebuilds_to_the_same_bytes() {
    rebuilds_to_the_same_bytes("inspection");
}
