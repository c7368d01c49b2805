//! Fuzzes the dictionary reader on arbitrary bytes.
//!
//! `cable_dict::dictionary::check_bytes` parses the preamble, section table and bincode
//! header of a `.cdict` file and verifies every section checksum. On any input it must
//! return an error, never panic.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = cable_dict::dictionary::check_bytes(data);
});
