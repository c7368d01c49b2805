//! Opens a dictionary with the library, checks it, and looks up one cable piece: its three
//! margins (clearance in mm, stretch, curvature in 1/m; negative: the limit is broken) under
//! each stored gravity direction.
//!
//! ```sh
//! cargo run --release --example look_up_piece -- \
//!     dictionaries/viper_s850_pick_and_place.cdict link_4
//! ```

use cable_dict::dictionary::Dictionary;
use cable_dict::path::Pv;
use std::error::Error;
use std::io::Write;

fn main() -> Result<(), Box<dyn Error>> {
    let mut out = std::io::stdout().lock();
    let mut args = std::env::args().skip(1);
    let (Some(file), Some(link)) = (args.next(), args.next()) else {
        return Err("usage: look_up_piece DICT.cdict LINK".into());
    };
    let dictionary = Dictionary::open(&file)?;
    dictionary.verify()?;
    let slot = dictionary
        .link_slot(&link)
        .ok_or_else(|| format!("{file} stores no clamp places on {link}"))?;
    let entry = dictionary.link(slot).ok_or("no catalogue entry")?;
    writeln!(
        out,
        "{link}: {} clamp places, lengths {:?} sub-segments",
        entry.clamps.len(),
        entry.lengths
    )?;
    // The shortest piece from the first clamp place to the second that reaches between them
    // (a shorter one has no equilibrium: no margins).
    let end = usize::from(entry.clamps.len() > 1);
    let (piece, margins) = entry
        .lengths
        .iter()
        .find_map(|&length| {
            let piece = Pv::new(length as usize, 0, end);
            let (_, rows) = dictionary.lookup(slot, &piece)?;
            rows.iter()
                .all(|row| row.values().is_some())
                .then_some((piece, rows))
        })
        .ok_or("no stored length of that pair has margins")?;
    let length = piece.sub_segments;
    let names = [
        &entry.clamps[piece.start].name,
        &entry.clamps[piece.end].name,
    ];
    writeln!(
        out,
        "piece {} → {}, {length} sub-segments:",
        names[0], names[1]
    )?;
    for (direction, record) in dictionary.directions().iter().zip(margins) {
        match record.values() {
            Some([clearance, stretch, bend, twist]) => writeln!(
                out,
                "  gravity {direction:.3?}: clearance {clearance:.1} mm, stretch {stretch:.4}, \
                 curvature {bend:.2} 1/m, twist {twist:.1} deg/m"
            )?,
            None => writeln!(out, "  gravity {direction:.3?}: not measured")?,
        }
    }
    Ok(())
}
