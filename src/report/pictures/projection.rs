//! Orthographic projections of the world frame (z up) onto the front, side and top views,
//! and the outline of a collider in a view (the convex hull of its projected vertices).

use nalgebra::Point3;

/// A view of the world frame: which world axes run right and up, and which way is away from
/// the viewer. Every view keeps its axes growing to the right and upwards (none is mirrored).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum View {
    /// x to the right, z up, seen from −y.
    Front,
    /// y to the right, z up, seen from +x.
    Side,
    /// x to the right, y up, seen from +z.
    Top,
}

impl View {
    /// The three views, in drawing order.
    pub const ALL: [View; 3] = [View::Front, View::Side, View::Top];

    /// `(right, up)`: the world axes (0 = x, 1 = y, 2 = z) along the view's horizontal and
    /// vertical.
    pub fn axes(self) -> (usize, usize) {
        match self {
            View::Front => (0, 2),
            View::Side => (1, 2),
            View::Top => (0, 1),
        }
    }

    /// Lower-case name, also the SVG class of the view's panel.
    pub fn name(self) -> &'static str {
        match self {
            View::Front => "front",
            View::Side => "side",
            View::Top => "top",
        }
    }

    /// The panel's title: the view and where it is seen from.
    pub fn title(self) -> &'static str {
        match self {
            View::Front => "From the robot's right (−y), x–z",
            View::Side => "From the robot's front (+x), y–z",
            View::Top => "From above (+z), x–y",
        }
    }

    /// `(right, up)` coordinates of `p` in the view (same unit as `p`).
    pub fn project(self, p: &Point3<f64>) -> [f64; 2] {
        let (right, up) = self.axes();
        [p[right], p[up]]
    }

    /// How far `p` is from the viewer, up to a constant: what the far-to-near drawing order
    /// sorts by.
    pub fn depth(self, p: &Point3<f64>) -> f64 {
        match self {
            View::Front => p.y,
            View::Side => -p.x,
            View::Top => -p.z,
        }
    }
}

/// The outline of `points` (mm) seen in `view`: the convex hull of their projections
/// rounded to 0.1 mm, counter-clockwise with right to the right and up upwards, without
/// collinear points. The exact silhouette of a convex collider (box, cylinder, sphere,
/// capsule) to the drawing's resolution; a mesh's convex outline.
pub(super) fn outline(view: View, points: &[Point3<f64>]) -> Vec<[f64; 2]> {
    // On the 0.1 mm grid the hull is computed exactly in integers: no rounding error can
    // turn a point on a straight edge into a corner or drop a true corner.
    let tenths: Vec<[i64; 2]> = points
        .iter()
        .map(|p| view.project(p).map(|v| (v * 10.0).round() as i64))
        .collect();
    convex_hull(tenths)
        .into_iter()
        .map(|p| p.map(|v| v as f64 / 10.0))
        .collect()
}

/// Andrew's monotone chain; fewer than three distinct points are returned as they are.
fn convex_hull(mut points: Vec<[i64; 2]>) -> Vec<[i64; 2]> {
    points.sort_unstable();
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let mut lower: Vec<[i64; 2]> = Vec::new();
    for &p in &points {
        push_turning_left(&mut lower, p);
    }
    let mut upper: Vec<[i64; 2]> = Vec::new();
    for &p in points.iter().rev() {
        push_turning_left(&mut upper, p);
    }
    // Each chain ends where the other starts.
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// Pushes `p` onto a hull chain after dropping the points it makes a right turn or a
/// straight line at.
fn push_turning_left(chain: &mut Vec<[i64; 2]>, p: [i64; 2]) {
    while let [.., a, b] = chain[..] {
        // i128: the products of two coordinate differences cannot overflow.
        let cross = i128::from(b[0] - a[0]) * i128::from(p[1] - a[1])
            - i128::from(b[1] - a[1]) * i128::from(p[0] - a[0]);
        if cross > 0 {
            break;
        }
        chain.pop();
    }
    chain.push(p);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_keep_right_handed_axes_and_look_from_the_named_side() {
        // Right × up is the direction towards the viewer for an unmirrored view.
        let towards_viewer = |view: View| {
            let (right, up) = view.axes();
            let e = |i: usize| nalgebra::Vector3::ith(i, 1.0);
            e(right).cross(&e(up))
        };
        assert_eq!(towards_viewer(View::Front), -nalgebra::Vector3::y());
        assert_eq!(towards_viewer(View::Side), nalgebra::Vector3::x());
        assert_eq!(towards_viewer(View::Top), nalgebra::Vector3::z());
        // Depth grows away from the viewer.
        let near = Point3::new(1.0, -1.0, 1.0);
        let far = Point3::new(-1.0, 1.0, -1.0);
        for view in View::ALL {
            assert!(view.depth(&far) > view.depth(&near), "{view:?}");
        }
    }

    #[test]
    fn hull_of_a_square_with_inner_and_edge_points_is_its_corners() {
        let hull = convex_hull(vec![[0, 0], [2, 0], [1, 0], [2, 2], [0, 2], [1, 1], [2, 2]]);
        assert_eq!(hull, vec![[0, 0], [2, 0], [2, 2], [0, 2]]);
    }

    #[test]
    fn hull_of_two_points_is_both() {
        assert_eq!(
            convex_hull(vec![[2, 1], [0, 0], [2, 1]]),
            vec![[0, 0], [2, 1]]
        );
    }
}
