//! How much a piece is twisted: the twist per length a datasheet's torsion limit bounds.

/// Twist per length (deg/m) of a piece of `length_m` twisted by `twist_rad` between its
/// clamps: an isotropic cable's twist is uniform along a piece at equilibrium, so this is
/// the twist per length everywhere on it. 0 for a piece without length.
pub fn twist_per_length_deg_per_m(twist_rad: f64, length_m: f64) -> f64 {
    if length_m > 0.0 {
        twist_rad.to_degrees() / length_m
    } else {
        0.0
    }
}
