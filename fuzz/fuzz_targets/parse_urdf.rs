//! Fuzzes the URDF reader (XML nesting check, urdf-rs, validation, collision shapes): any
//! text must give a robot or an error, never a panic, a stack overflow or a hang.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = cable_dict::robot::Robot::from_urdf_str(text, std::path::Path::new("fuzz.urdf"));
    }
});
