//! JSON output for people and programs: every number that is not an integer is written with
//! at most [`SIGNIFICANT_DIGITS`] significant digits, so that a value computed as
//! `44.422999999999995` reads `44.423` — far below any physical precision of the tool, far
//! above what a reader could mistake for a different value.

use serde::Serialize;
use serde_json::{Number, Value};

/// Significant digits kept in JSON numbers.
pub const SIGNIFICANT_DIGITS: usize = 12;

/// A number for people: rounded to 1e-9 so that unit conversions print as typed (120, not
/// 119.99999999999999), and without a negative zero.
pub fn tidy(value: f64) -> f64 {
    (value * 1e9).round() / 1e9 + 0.0
}

/// `value` as pretty-printed JSON with its numbers rounded to [`SIGNIFICANT_DIGITS`].
pub fn to_pretty_string<T: Serialize + ?Sized>(value: &T) -> serde_json::Result<String> {
    let mut tree = serde_json::to_value(value)?;
    round_numbers(&mut tree);
    serde_json::to_string_pretty(&tree).map(crate::escape::json)
}

fn round_numbers(value: &mut Value) {
    match value {
        Value::Number(n) if n.is_f64() => {
            if let Some(rounded) = n.as_f64().map(round).and_then(Number::from_f64) {
                *n = rounded;
            }
        }
        Value::Array(items) => items.iter_mut().for_each(round_numbers),
        Value::Object(fields) => fields.values_mut().for_each(round_numbers),
        _ => {}
    }
}

/// `x` rounded to [`SIGNIFICANT_DIGITS`] significant digits (through its decimal form, so
/// that the shortest representation of the result is short), a negative zero as zero.
fn round(x: f64) -> f64 {
    let rounded: f64 = format!("{x:.*e}", SIGNIFICANT_DIGITS - 1)
        .parse()
        .unwrap_or(x);
    // -0.0 + 0.0 is +0.0; every other value is unchanged.
    rounded + 0.0
}

/// For `#[serde(skip_serializing_if)]`: an index that is 0 (the first motion of a cell, the
/// only one of a single motion) is left out.
pub fn is_zero(value: &usize) -> bool {
    *value == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_noise_is_rounded_away_and_integers_kept() {
        let text = to_pretty_string(&serde_json::json!({
            "a": 44.422999999999995,
            "b": [85.90000000000002, -0.1 + 0.2, 1e-30 / 3.0],
            "n": 9_007_199_254_740_993u64,
            "t": 4.975322457688607,
            "z": -0.0,
            "s": ([0.0f64; 0].iter().sum::<f64>()),
        }))
        .unwrap();
        let back: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(back["a"], 44.423);
        assert_eq!(back["b"][0], 85.9);
        assert_eq!(back["b"][1], 0.1);
        assert_eq!(back["b"][2], 3.33333333333e-31);
        assert_eq!(back["n"], 9_007_199_254_740_993u64);
        assert_eq!(back["t"], 4.97532245769);
        assert!(!text.contains("-0"), "{text}");
    }
}
