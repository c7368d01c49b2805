//! Fuzzes the trusted-keys reader (public key lines, comments, key decoding): any text must
//! give keys or an error naming the line, never a panic.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = cable_dict::provenance::TrustedKeys::parse(text, std::path::Path::new("keys"));
    }
});
