//! The spacing between a link's sites: a hash grid of the sites kept so far, in cells of the
//! spacing, answering "is a kept site of the same facing closer than the spacing?".

use nalgebra::{Point3, Unit, Vector3};
use std::collections::HashMap;

/// Distances this much (relative) below the spacing still count as the spacing: grids laid
/// out exactly `spacing` apart are not thinned by rounding.
const SPACING_ROUNDING: f64 = 1e-9;

/// A kept site: its surface point and outward normal (link frame).
type Kept = (Point3<f64>, Unit<Vector3<f64>>);

/// Sites kept so far on one link (link frame, m).
pub(super) struct SpacingGrid {
    spacing_m: f64,
    /// Two normals with a dot product at least this are of one facing.
    facing_cosine: f64,
    cells: HashMap<[i64; 3], Vec<Kept>>,
}

impl SpacingGrid {
    /// An empty grid for sites `spacing_m` apart within a facing of `facing_cosine`.
    pub fn new(spacing_m: f64, facing_cosine: f64) -> Self {
        SpacingGrid {
            spacing_m,
            facing_cosine,
            cells: HashMap::new(),
        }
    }

    fn cell(&self, p: &Point3<f64>) -> [i64; 3] {
        [p.x, p.y, p.z].map(|x| (x / self.spacing_m).floor() as i64)
    }

    /// Whether a kept site of the same facing as `normal` lies closer than the spacing to
    /// `point`.
    pub fn crowds(&self, point: &Point3<f64>, normal: &Unit<Vector3<f64>>) -> bool {
        let limit = self.spacing_m * (1.0 - SPACING_ROUNDING);
        let [i, j, k] = self.cell(point);
        (-1..=1).any(|di| {
            (-1..=1).any(|dj| {
                (-1..=1).any(|dk| {
                    self.cells
                        .get(&[i + di, j + dj, k + dk])
                        .is_some_and(|sites| {
                            sites.iter().any(|(p, n)| {
                                n.dot(normal) >= self.facing_cosine && (p - point).norm() < limit
                            })
                        })
                })
            })
        })
    }

    /// Keeps a site.
    pub fn insert(&mut self, point: Point3<f64>, normal: Unit<Vector3<f64>>) {
        let cell = self.cell(&point);
        self.cells.entry(cell).or_default().push((point, normal));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_near_site_of_the_same_facing_crowds() {
        let mut grid = SpacingGrid::new(0.02, 30f64.to_radians().cos());
        grid.insert(Point3::new(0.0, 0.0, 0.0), Vector3::z_axis());
        let tilted = |deg: f64| {
            let a = deg.to_radians();
            Unit::new_normalize(Vector3::new(a.sin(), 0.0, a.cos()))
        };
        assert!(grid.crowds(&Point3::new(0.019, 0.0, 0.0), &tilted(29.0)));
        assert!(!grid.crowds(&Point3::new(0.019, 0.0, 0.0), &tilted(31.0)));
        assert!(!grid.crowds(&Point3::new(0.02, 0.0, 0.0), &Vector3::z_axis()));
        assert!(!grid.crowds(&Point3::new(0.015, 0.015, 0.0), &Vector3::z_axis()));
        assert!(grid.crowds(&Point3::new(-0.01, -0.01, 0.0), &Vector3::z_axis()));
    }
}
