//! Fuzzes the signature-file reader and checker: any text must give the number of signatures
//! that hold for the fixed dictionary bytes `b"fuzz"`, or an error naming the line — never a
//! panic. The seed corpus holds a valid line, so mutations reach the Ed25519 verification.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = cable_dict::provenance::check_text(text, b"fuzz");
    }
});
