//! Fuzzes the cable file reader: any text must give a cable or an error, never a panic.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = cable_dict::cable::CableSpec::from_toml_str(text, std::path::Path::new("fuzz.toml"));
    }
});
