//! How far a cable shape is stretched beyond its natural length.

use nalgebra::Point3;

/// Centerline length of the shape divided by the cable's natural length (1 = unstretched).
pub fn stretch(nodes: &[Point3<f64>], natural_length_m: f64) -> f64 {
    let length: f64 = nodes.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    length / natural_length_m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stretch_is_polyline_length_over_natural_length() {
        let nodes: Vec<_> = (0..=5)
            .map(|k| Point3::new(0.0, 0.0, 0.01 * k as f64))
            .collect();
        assert!((stretch(&nodes, 0.05) - 1.0).abs() < 1e-12);
        assert!((stretch(&nodes, 0.04) - 1.25).abs() < 1e-12);
    }
}
