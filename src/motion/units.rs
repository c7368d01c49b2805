//! Units of joint values at file boundaries, and the values that survive a CSV round trip.

/// The unit of one joint column of a motion CSV (the suffix of its header).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ColumnUnit {
    /// Degrees (`_deg`), rotary joints.
    Deg,
    /// Radians (`_rad`), rotary joints.
    Rad,
    /// Millimetres (`_mm`), prismatic joints.
    Mm,
    /// Metres (`_m`), prismatic joints.
    M,
}

impl ColumnUnit {
    /// The unit people read: degrees for rotary joints, millimetres for prismatic ones.
    pub(crate) fn display(rotary: bool) -> Self {
        if rotary {
            ColumnUnit::Deg
        } else {
            ColumnUnit::Mm
        }
    }

    /// Parses a header suffix (`deg`, `rad`, `mm`, `m`).
    pub(crate) fn from_suffix(suffix: &str) -> Option<Self> {
        match suffix {
            "deg" => Some(ColumnUnit::Deg),
            "rad" => Some(ColumnUnit::Rad),
            "mm" => Some(ColumnUnit::Mm),
            "m" => Some(ColumnUnit::M),
            _ => None,
        }
    }

    /// The header suffix (without the underscore), also the unit's display name.
    pub(crate) fn suffix(self) -> &'static str {
        match self {
            ColumnUnit::Deg => "deg",
            ColumnUnit::Rad => "rad",
            ColumnUnit::Mm => "mm",
            ColumnUnit::M => "m",
        }
    }

    /// True for angle units.
    pub(crate) fn is_rotary(self) -> bool {
        matches!(self, ColumnUnit::Deg | ColumnUnit::Rad)
    }

    /// A value in this unit converted to SI (rad or m).
    pub(crate) fn to_si(self, value: f64) -> f64 {
        match self {
            ColumnUnit::Deg => value.to_radians(),
            ColumnUnit::Mm => value / 1e3,
            ColumnUnit::Rad | ColumnUnit::M => value,
        }
    }

    /// An SI value (rad or m) expressed in this unit.
    pub(crate) fn in_unit(self, value: f64) -> f64 {
        match self {
            ColumnUnit::Deg => value.to_degrees(),
            ColumnUnit::Mm => value * 1e3,
            ColumnUnit::Rad | ColumnUnit::M => value,
        }
    }

    /// The number to write for the SI value `si`: a double `v` with `to_si(v) == si` when one
    /// lies within a few ulps of `in_unit(si)` (then writing and reading is bit-exact), else
    /// the plain conversion.
    pub(crate) fn exact_value(self, si: f64) -> f64 {
        let first = self.in_unit(si);
        let (mut up, mut down) = (first, first);
        if self.to_si(first) == si {
            return first;
        }
        for _ in 0..SEARCH_ULPS {
            up = up.next_up();
            down = down.next_down();
            if self.to_si(up) == si {
                return up;
            }
            if self.to_si(down) == si {
                return down;
            }
        }
        first
    }

    /// `si` moved (by at most an ulp or two) to the nearest value that round-trips exactly
    /// through this unit, without a negative zero.
    pub(crate) fn snap(self, si: f64) -> f64 {
        self.to_si(self.exact_value(si)) + 0.0
    }
}

/// How many ulps either side of the plain conversion [`ColumnUnit::exact_value`] searches.
const SEARCH_ULPS: usize = 4;

#[cfg(test)]
mod tests {
    use super::ColumnUnit;

    /// A deterministic stream of doubles spread over ±400 (xorshift).
    fn values(n: usize) -> impl Iterator<Item = f64> {
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        (0..n).map(move |_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 800.0 - 400.0
        })
    }

    #[test]
    fn snapped_values_round_trip_exactly_and_snapping_is_idempotent() {
        for unit in [ColumnUnit::Deg, ColumnUnit::Mm] {
            for si in values(200_000).map(|v| v / 50.0) {
                let snapped = unit.snap(si);
                assert!((snapped - si).abs() <= 4.0 * f64::EPSILON * si.abs());
                let written = unit.exact_value(snapped);
                assert_eq!(unit.to_si(written), snapped, "{unit:?} {si:e}");
                let parsed: f64 = written.to_string().parse().expect("Display round-trips");
                assert_eq!(parsed, written);
                assert_eq!(unit.snap(snapped), snapped);
            }
        }
    }
}
