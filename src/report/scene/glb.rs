//! The GLB container: a 12-byte header, the JSON chunk padded with spaces and the binary
//! chunk padded with zeros (glTF 2.0, section "GLB File Format Specification").

use super::SceneError;

/// `glTF` in ASCII, little-endian.
const MAGIC: u32 = 0x4654_6C67;
const VERSION: u32 = 2;
/// `JSON` in ASCII, little-endian.
const CHUNK_JSON: u32 = 0x4E4F_534A;
/// `BIN\0` in ASCII, little-endian.
const CHUNK_BIN: u32 = 0x004E_4942;

/// The `.glb` bytes of a JSON document and its binary buffer (no BIN chunk when empty).
pub(super) fn pack(json: &[u8], bin: &[u8]) -> Result<Vec<u8>, SceneError> {
    let json_chunk = chunk(CHUNK_JSON, json, b' ')?;
    let bin_chunk = if bin.is_empty() {
        Vec::new()
    } else {
        chunk(CHUNK_BIN, bin, 0)?
    };
    let total = 12 + json_chunk.len() + bin_chunk.len();
    let mut glb = Vec::with_capacity(total);
    glb.extend(MAGIC.to_le_bytes());
    glb.extend(VERSION.to_le_bytes());
    glb.extend(length_u32(total)?.to_le_bytes());
    glb.extend(json_chunk);
    glb.extend(bin_chunk);
    Ok(glb)
}

/// One chunk: length, type and the data padded to 4 bytes with `pad`.
fn chunk(kind: u32, data: &[u8], pad: u8) -> Result<Vec<u8>, SceneError> {
    let padded = data.len().next_multiple_of(4);
    let mut chunk = Vec::with_capacity(8 + padded);
    chunk.extend(length_u32(padded)?.to_le_bytes());
    chunk.extend(kind.to_le_bytes());
    chunk.extend_from_slice(data);
    chunk.resize(8 + padded, pad);
    Ok(chunk)
}

fn length_u32(bytes: usize) -> Result<u32, SceneError> {
    u32::try_from(bytes).map_err(|_| SceneError::TooLarge {
        bytes: bytes as u64,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_and_chunks_are_padded_and_measured() {
        let glb = pack(b"{}", &[1, 2, 3, 4, 5]).expect("small");
        assert_eq!(&glb[0..4], b"glTF");
        assert_eq!(glb[4..8], 2u32.to_le_bytes());
        assert_eq!(glb[8..12], (glb.len() as u32).to_le_bytes());
        assert_eq!(glb[12..16], 4u32.to_le_bytes());
        assert_eq!(&glb[16..20], b"JSON");
        assert_eq!(&glb[20..24], b"{}  ");
        assert_eq!(glb[24..28], 8u32.to_le_bytes());
        assert_eq!(&glb[28..32], b"BIN\0");
        assert_eq!(&glb[32..], &[1, 2, 3, 4, 5, 0, 0, 0]);
    }
}
