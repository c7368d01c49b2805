//! Fuzzes the setup reader (guides, catalogues, generated sites, segments, limits) with the
//! bundled robot and cable: any setup text must give a setup or an error — never a panic,
//! an allocation sized by a number in the text, or a hang.
#![no_main]

const ROBOT: &str = include_str!("../../robots/viper_s850/viper_s850.urdf");
const CABLE: &str = include_str!("../../cables/smc_le_cp_3.toml");

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let source = std::path::Path::new("robots/viper_s850/fuzz.toml");
        let _ = cable_dict::setup::Setup::from_texts(text, source, ROBOT, CABLE, &[]);
    }
});
