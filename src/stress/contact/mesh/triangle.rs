//! Closest points on one triangle: to a point, and to a line segment (with where the segment
//! crosses the triangle's plane).

use super::super::primitives::closest_segment_segment;
use nalgebra::{Point3, Vector3};

/// The part of a triangle a nearest point lies on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Feature {
    /// Vertex k.
    Vertex(usize),
    /// Edge k, from vertex k to vertex (k + 1) mod 3.
    Edge(usize),
    Face,
}

/// Nearest point of triangle abc to `p` and the feature it lies on (Ericson, *Real-Time
/// Collision Detection*, §5.1.5).
pub(super) fn closest_point_triangle(
    p: &Point3<f64>,
    a: &Point3<f64>,
    b: &Point3<f64>,
    c: &Point3<f64>,
) -> (Point3<f64>, Feature) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(&ap);
    let d2 = ac.dot(&ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (*a, Feature::Vertex(0));
    }
    let bp = p - b;
    let d3 = ab.dot(&bp);
    let d4 = ac.dot(&bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (*b, Feature::Vertex(1));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, Feature::Edge(0));
    }
    let cp = p - c;
    let d5 = ab.dot(&cp);
    let d6 = ac.dot(&cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (*c, Feature::Vertex(2));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, Feature::Edge(2));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, Feature::Edge(1));
    }
    let denom = 1.0 / (va + vb + vc);
    (a + ab * (vb * denom) + ac * (vc * denom), Feature::Face)
}

/// Closest approach of segment `a + t·e` to a triangle.
pub(super) struct SegmentTriangle {
    /// Squared distance.
    pub d2: f64,
    /// Segment parameter of a closest point.
    pub t: f64,
    /// Where the segment crosses the triangle's plane, if that is on (or within rounding of)
    /// the triangle.
    pub cut: Option<f64>,
}

pub(super) fn segment_triangle(
    a: &Point3<f64>,
    e: &Vector3<f64>,
    tri: &[Point3<f64>; 3],
) -> SegmentTriangle {
    let [p0, p1, p2] = tri;
    let n = (p1 - p0).cross(&(p2 - p0));
    let d0 = n.dot(&(a - p0));
    let d1 = d0 + n.dot(e);
    let mut cut = None;
    if (d0 > 0.0 && d1 < 0.0) || (d0 < 0.0 && d1 > 0.0) {
        let t = d0 / (d0 - d1);
        let x = a + e * t;
        // Edge functions, scaled by |n|²; a relative slack lets a crossing through a shared
        // edge or vertex register on both sides instead of on neither.
        let slack = -1e-9 * n.norm_squared();
        let edge = |u: &Point3<f64>, v: &Point3<f64>| n.dot(&(v - u).cross(&(x - u)));
        let (w0, w1, w2) = (edge(p0, p1), edge(p1, p2), edge(p2, p0));
        if w0 >= slack && w1 >= slack && w2 >= slack {
            cut = Some(t);
            if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                return SegmentTriangle { d2: 0.0, t, cut };
            }
        }
    }
    // No crossing: a closest pair has an endpoint of the segment or a point on an edge.
    let mut best = SegmentTriangle {
        d2: f64::INFINITY,
        t: 0.0,
        cut,
    };
    let b = a + e;
    for (t, p) in [(0.0, a), (1.0, &b)] {
        let (q, _) = closest_point_triangle(p, p0, p1, p2);
        let d2 = (p - q).norm_squared();
        if d2 < best.d2 {
            best.d2 = d2;
            best.t = t;
        }
    }
    for k in 0..3 {
        let (u, v) = (tri[k], tri[(k + 1) % 3]);
        let (s, w) = closest_segment_segment(a, e, &u, &(v - u));
        let d2 = ((a + e * s) - (u + (v - u) * w)).norm_squared();
        if d2 < best.d2 || (d2 == best.d2 && s < best.t) {
            best.d2 = d2;
            best.t = s;
        }
    }
    best
}
