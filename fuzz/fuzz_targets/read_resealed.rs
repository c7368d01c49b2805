//! Fuzzes the dictionary reader past its checksums: the input's section checksums, table
//! checksum, announced length and preamble checksum are recomputed before the bytes reach
//! `cable_dict::dictionary::check_bytes`, so mutations land in the bincode header, the
//! segment table, the record counts and the records themselves. On any input the reader must
//! return an error, never panic.
#![no_main]

use xxhash_rust::xxh3::xxh3_64;

const PREAMBLE: usize = 64;
const ENTRY: usize = 32;
const SECTIONS: usize = 4;

fn word(bytes: &[u8], at: usize) -> u64 {
    let mut w = [0u8; 8];
    w.copy_from_slice(&bytes[at..at + 8]);
    u64::from_le_bytes(w)
}

/// Rewrites every checksum and the length field so that they match the bytes.
fn reseal(bytes: &mut [u8]) {
    let table_end = PREAMBLE + SECTIONS * ENTRY;
    if bytes.len() < table_end {
        return;
    }
    for i in 0..SECTIONS {
        let at = PREAMBLE + i * ENTRY;
        let (offset, len) = (word(bytes, at + 8), word(bytes, at + 16));
        let end = offset.checked_add(len).filter(|&e| e <= bytes.len() as u64);
        if let Some(end) = end {
            let sum = xxh3_64(&bytes[offset as usize..end as usize]);
            bytes[at + 24..at + 32].copy_from_slice(&sum.to_le_bytes());
        }
    }
    let len = bytes.len() as u64;
    bytes[16..24].copy_from_slice(&len.to_le_bytes());
    let table = xxh3_64(&bytes[PREAMBLE..table_end]);
    bytes[32..40].copy_from_slice(&table.to_le_bytes());
    let preamble = xxh3_64(&bytes[..56]);
    bytes[56..64].copy_from_slice(&preamble.to_le_bytes());
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let mut bytes = data.to_vec();
    reseal(&mut bytes);
    let _ = cable_dict::dictionary::check_bytes(&bytes);
});
