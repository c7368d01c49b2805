//! Fuzzes the waypoint file reader: any text must give waypoints or an error, never a panic.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let path = std::path::Path::new("fuzz.toml");
        let _ = cable_dict::motion::WaypointFile::from_toml_str(text, path);
    }
});
