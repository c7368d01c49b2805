//! Exact (f64) signed distances from a line segment to the primitive collision shapes, each in
//! its own frame (URDF conventions: centred on the origin, axis along z).
//!
//! For a convex solid the signed distance `sd(p)` (negative inside) is a convex function of
//! `p`, so along a segment `p(t) = a + t·(b − a)` it is convex in `t`. Each shape splits
//! `[0, 1]` at the parameters where the closed form of `sd` changes (a coordinate crossing a
//! face plane, the cylinder wall, or zero); inside each piece the minimiser has a closed form
//! (or, on a cylinder rim, a safeguarded Newton solve), so the minimum is found exactly, up to
//! rounding, by evaluating `sd` at every candidate.

use nalgebra::{Point3, Vector3};

/// The lowest signed distance along a segment and where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SegmentMin {
    /// Parameter in [0, 1] along the segment of a point where the minimum is reached.
    pub t: f64,
    /// Signed distance (m) of that point to the surface; negative inside.
    pub sd: f64,
}

impl SegmentMin {
    /// The lower of two, the lower `t` on an exact tie.
    pub fn min(self, other: SegmentMin) -> SegmentMin {
        if other.sd < self.sd || (other.sd == self.sd && other.t < self.t) {
            other
        } else {
            self
        }
    }
}

/// A point's signed distance and its nearest surface point: `p = q + sd·n`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Projection {
    /// Signed distance (m); negative inside.
    pub sd: f64,
    /// The nearest point on the surface.
    pub q: Point3<f64>,
    /// Unit outward normal of the surface at `q`.
    pub n: Vector3<f64>,
}

/// Parameter in [0, 1] of the point of segment `a + t·e` nearest to `p`.
pub(super) fn closest_t_on_segment(p: &Point3<f64>, a: &Point3<f64>, e: &Vector3<f64>) -> f64 {
    let ee = e.norm_squared();
    if ee > 0.0 {
        ((p - a).dot(e) / ee).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Closest points of segments `p1 + s·d1` and `p2 + t·d2`, s, t ∈ [0, 1] (Ericson, *Real-Time
/// Collision Detection*, §5.1.9); returns `(s, t)`.
pub(super) fn closest_segment_segment(
    p1: &Point3<f64>,
    d1: &Vector3<f64>,
    p2: &Point3<f64>,
    d2: &Vector3<f64>,
) -> (f64, f64) {
    let r = p1 - p2;
    let a = d1.norm_squared();
    let e = d2.norm_squared();
    let f = d2.dot(&r);
    if a <= 0.0 && e <= 0.0 {
        return (0.0, 0.0);
    }
    if a <= 0.0 {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(&r);
    if e <= 0.0 {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    // Parallel (or nearly): any s works as a start, the clamping below finds the minimum.
    let mut s = if denom > 1e-12 * a * e {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Distance between two segments: `p1 + s d1` and `p2 + t d2`, `s, t ∈ [0, 1]`.
pub(crate) fn segment_segment_distance(
    p1: &Point3<f64>,
    d1: &Vector3<f64>,
    p2: &Point3<f64>,
    d2: &Vector3<f64>,
) -> f64 {
    let (s, t) = closest_segment_segment(p1, d1, p2, d2);
    ((p1 + d1 * s) - (p2 + d2 * t)).norm()
}

/// Any unit vector perpendicular to `v` (for normals at degenerate points).
fn unit_or(v: Vector3<f64>, fallback: Vector3<f64>) -> Vector3<f64> {
    let norm = v.norm();
    if norm > 0.0 { v / norm } else { fallback }
}

/// √(x² + y²) without `hypot`'s overflow care (and cost): lengths here are metres.
fn norm2(x: f64, y: f64) -> f64 {
    (x * x + y * y).sqrt()
}

fn sign(v: f64) -> f64 {
    if v < 0.0 { -1.0 } else { 1.0 }
}

// ---------------------------------------------------------------------------------------------
// Sphere

/// Sphere of `radius` centred on the origin: minimum of `sd` along `a → b`.
pub(super) fn sphere_segment(radius: f64, a: &Point3<f64>, b: &Point3<f64>) -> SegmentMin {
    let e = b - a;
    let t = closest_t_on_segment(&Point3::origin(), a, &e);
    SegmentMin {
        t,
        sd: (a + e * t).coords.norm() - radius,
    }
}

/// Projection of `p` onto a sphere of `radius` centred on the origin.
pub(super) fn sphere_project(radius: f64, p: &Point3<f64>) -> Projection {
    let d = p.coords.norm();
    let n = unit_or(p.coords, Vector3::z());
    Projection {
        sd: d - radius,
        q: Point3::from(n * radius),
        n,
    }
}

// ---------------------------------------------------------------------------------------------
// Capsule

/// Capsule of `radius` around the z segment ±`half_length`: minimum of `sd` along `a → b`.
pub(super) fn capsule_segment(
    radius: f64,
    half_length: f64,
    a: &Point3<f64>,
    b: &Point3<f64>,
) -> SegmentMin {
    let e = b - a;
    let p2 = Point3::new(0.0, 0.0, -half_length);
    let d2 = Vector3::new(0.0, 0.0, 2.0 * half_length);
    let (t, s) = closest_segment_segment(a, &e, &p2, &d2);
    SegmentMin {
        t,
        sd: ((a + e * t) - (p2 + d2 * s)).norm() - radius,
    }
}

/// Projection of `p` onto a capsule of `radius` around the z segment ±`half_length`.
pub(super) fn capsule_project(radius: f64, half_length: f64, p: &Point3<f64>) -> Projection {
    let c = Point3::new(0.0, 0.0, p.z.clamp(-half_length, half_length));
    let v = p - c;
    let n = unit_or(v, Vector3::x());
    Projection {
        sd: v.norm() - radius,
        q: c + n * radius,
        n,
    }
}

// ---------------------------------------------------------------------------------------------
// Box

/// Signed distance of `p` to the box with half extents `h` centred on the origin.
pub(super) fn box_sd(h: &Vector3<f64>, p: &Point3<f64>) -> f64 {
    let d = p.coords.abs() - h;
    let outside = d.map(|v| v.max(0.0)).norm();
    if outside > 0.0 { outside } else { d.max() }
}

/// Box with half extents `h` centred on the origin: minimum of `sd` along `a → b`.
pub(super) fn box_segment(h: &Vector3<f64>, a: &Point3<f64>, b: &Point3<f64>) -> SegmentMin {
    let e = b - a;
    // Piece boundaries: every coordinate crossing −h, 0 or +h.
    let mut cuts = [0.0; 11];
    let mut n = 0;
    cuts[n] = 0.0;
    n += 1;
    for i in 0..3 {
        if e[i] != 0.0 {
            for c in [-h[i], 0.0, h[i]] {
                let t = (c - a[i]) / e[i];
                if t > 0.0 && t < 1.0 {
                    cuts[n] = t;
                    n += 1;
                }
            }
        }
    }
    cuts[n] = 1.0;
    n += 1;
    let cuts = &mut cuts[..n];
    cuts.sort_unstable_by(f64::total_cmp);

    let eval = |t: f64| SegmentMin {
        t,
        sd: box_sd(h, &(a + e * t)),
    };
    let mut best = eval(cuts[0]);
    for &t in &cuts[1..] {
        best = best.min(eval(t));
    }
    for w in cuts.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        if t1 <= t0 {
            continue;
        }
        let mid = a + e * (0.5 * (t0 + t1));
        let s = mid.coords.map(sign);
        let outside = [0, 1, 2].map(|i| mid[i].abs() > h[i]);
        let within = |t: f64| t > t0 && t < t1;
        if outside.iter().any(|&o| o) {
            // sd² = Σ_outside (s_i·p_i − h_i)²: a parabola in t.
            let (mut num, mut den) = (0.0, 0.0);
            for i in (0..3).filter(|&i| outside[i]) {
                num += (s[i] * a[i] - h[i]) * s[i] * e[i];
                den += e[i] * e[i];
            }
            if den > 0.0 {
                let t = -num / den;
                if within(t) {
                    best = best.min(eval(t));
                }
            }
        } else {
            // sd = max_i (s_i·p_i − h_i), three lines: the minimum is at a crossing.
            for (i, j) in [(0, 1), (0, 2), (1, 2)] {
                let slope = s[i] * e[i] - s[j] * e[j];
                if slope != 0.0 {
                    let t = ((s[j] * a[j] - h[j]) - (s[i] * a[i] - h[i])) / slope;
                    if within(t) {
                        best = best.min(eval(t));
                    }
                }
            }
        }
    }
    best
}

/// Projection of `p` onto the box with half extents `h` centred on the origin.
pub(super) fn box_project(h: &Vector3<f64>, p: &Point3<f64>) -> Projection {
    let d = p.coords.abs() - h;
    if d.iter().any(|&v| v > 0.0) {
        let q = Point3::from(p.coords.zip_map(h, |v, hi| v.clamp(-hi, hi)));
        let v = p - q;
        let sd = v.norm();
        return Projection { sd, q, n: v / sd };
    }
    // Inside: the nearest face is the one with the largest (least negative) d_i.
    let k = d.imax();
    let s = sign(p[k]);
    let mut q = *p;
    q[k] = s * h[k];
    let mut n = Vector3::zeros();
    n[k] = s;
    Projection { sd: d[k], q, n }
}

// ---------------------------------------------------------------------------------------------
// Cylinder

/// Signed distance of `p` to the cylinder of `radius` and z half-length `half` on the origin.
pub(super) fn cylinder_sd(radius: f64, half: f64, p: &Point3<f64>) -> f64 {
    let dr = norm2(p.x, p.y) - radius;
    let dz = p.z.abs() - half;
    if dr > 0.0 || dz > 0.0 {
        norm2(dr.max(0.0), dz.max(0.0))
    } else {
        dr.max(dz)
    }
}

/// Real roots of `c2·t² + c1·t + c0 = 0` (none for a degenerate or constant polynomial).
fn quadratic_roots(c2: f64, c1: f64, c0: f64) -> [Option<f64>; 2] {
    if c2 == 0.0 {
        return [(c1 != 0.0).then(|| -c0 / c1), None];
    }
    let disc = c1 * c1 - 4.0 * c2 * c0;
    if disc < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (c1 + sign(c1) * disc.sqrt());
    let r1 = q / c2;
    let r2 = if q != 0.0 { c0 / q } else { r1 };
    [Some(r1), Some(r2)]
}

/// Cylinder of `radius`, z half-length `half`, on the origin: minimum of `sd` along `a → b`.
pub(super) fn cylinder_segment(
    radius: f64,
    half: f64,
    a: &Point3<f64>,
    b: &Point3<f64>,
) -> SegmentMin {
    let e = b - a;
    // ρ(t)² = qa·t² + qb·t + qc (distance from the axis, squared).
    let qa = e.x * e.x + e.y * e.y;
    let qb = 2.0 * (a.x * e.x + a.y * e.y);
    let qc = a.x * a.x + a.y * a.y;
    let t_axis = if qa > 0.0 { -qb / (2.0 * qa) } else { 0.0 };

    let mut cuts = [0.0; 7];
    let mut n = 1; // cuts[0] = 0
    let add = |cuts: &mut [f64; 7], n: &mut usize, t: f64| {
        if t > 0.0 && t < 1.0 {
            cuts[*n] = t;
            *n += 1;
        }
    };
    if qa > 0.0 {
        for t in quadratic_roots(qa, qb, qc - radius * radius)
            .into_iter()
            .flatten()
        {
            add(&mut cuts, &mut n, t);
        }
    }
    if e.z != 0.0 {
        for c in [-half, 0.0, half] {
            add(&mut cuts, &mut n, (c - a.z) / e.z);
        }
    }
    cuts[n] = 1.0;
    n += 1;
    let cuts = &mut cuts[..n];
    cuts.sort_unstable_by(f64::total_cmp);

    let eval = |t: f64| SegmentMin {
        t,
        sd: cylinder_sd(radius, half, &(a + e * t)),
    };
    let mut best = eval(cuts[0]);
    for &t in &cuts[1..] {
        best = best.min(eval(t));
    }
    for w in cuts.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        if t1 <= t0 {
            continue;
        }
        let within = |t: f64| t > t0 && t < t1;
        let mid = a + e * (0.5 * (t0 + t1));
        let s = sign(mid.z);
        let out_r = norm2(mid.x, mid.y) > radius;
        let out_z = mid.z.abs() > half;
        match (out_r, out_z) {
            // Beside the wall: sd = ρ − R, lowest where ρ is.
            (true, false) => {
                if within(t_axis) {
                    best = best.min(eval(t_axis));
                }
            }
            // Above/below a cap: sd linear in t, minimum at a piece end (already evaluated).
            (false, true) => {}
            // Beyond the rim: distance to the rim circle, convex in t.
            (true, true) => {
                let t = rim_minimiser(radius, half, s, (qa, qb, qc), a.z, e.z, t0, t1);
                best = best.min(eval(t));
            }
            // Inside: sd = max(ρ − R, s·z − H); the minimum is where ρ is lowest or where the
            // two are equal: ρ = L(t) = s·z(t) − H + R, squared into a quadratic.
            (false, false) => {
                if within(t_axis) {
                    best = best.min(eval(t_axis));
                }
                let (l0, l1) = (s * a.z - half + radius, s * e.z);
                let roots = quadratic_roots(qa - l1 * l1, qb - 2.0 * l0 * l1, qc - l0 * l0);
                for t in roots.into_iter().flatten() {
                    if within(t) && l0 + l1 * t >= 0.0 {
                        best = best.min(eval(t));
                    }
                }
            }
        }
    }
    best
}

/// Minimiser over [t0, t1] of f(t) = (ρ(t) − R)² + (s·z(t) − H)², convex there because the
/// piece lies beyond the rim (ρ > R, s·z > H). Newton on f′ inside a shrinking bracket.
#[allow(clippy::too_many_arguments)]
fn rim_minimiser(
    radius: f64,
    half: f64,
    s: f64,
    (qa, qb, qc): (f64, f64, f64),
    az: f64,
    ez: f64,
    t0: f64,
    t1: f64,
) -> f64 {
    // f′(t)/2 and f″(t)/2.
    let derivs = |t: f64| {
        let rho = (qa * t * t + qb * t + qc).max(0.0).sqrt();
        let w = s * (az + ez * t) - half;
        if rho <= 0.0 {
            return (w * s * ez, ez * ez);
        }
        let rho1 = (qa * t + 0.5 * qb) / rho;
        let rho2 = (qa - rho1 * rho1) / rho;
        (
            (rho - radius) * rho1 + w * s * ez,
            rho1 * rho1 + (rho - radius) * rho2 + ez * ez,
        )
    };
    let (mut lo, mut hi) = (t0, t1);
    if derivs(lo).0 >= 0.0 {
        return lo;
    }
    if derivs(hi).0 <= 0.0 {
        return hi;
    }
    let mut t = 0.5 * (lo + hi);
    for _ in 0..100 {
        let (g, h) = derivs(t);
        if g == 0.0 {
            return t;
        }
        if g < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let step = if h > 0.0 { g / h } else { f64::INFINITY };
        if step.abs() <= 4.0 * f64::EPSILON {
            return t;
        }
        let newton = t - step;
        t = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo <= 4.0 * f64::EPSILON {
            return t;
        }
    }
    t
}

/// Projection of `p` onto the cylinder of `radius` and z half-length `half` on the origin.
pub(super) fn cylinder_project(radius: f64, half: f64, p: &Point3<f64>) -> Projection {
    let rho = norm2(p.x, p.y);
    let dr = rho - radius;
    let dz = p.z.abs() - half;
    if dr > 0.0 || dz > 0.0 {
        let scale = if rho > radius { radius / rho } else { 1.0 };
        let q = Point3::new(p.x * scale, p.y * scale, p.z.clamp(-half, half));
        let v = p - q;
        let sd = v.norm();
        return Projection { sd, q, n: v / sd };
    }
    if dr >= dz {
        let u = if rho > 0.0 {
            Vector3::new(p.x / rho, p.y / rho, 0.0)
        } else {
            Vector3::x()
        };
        Projection {
            sd: dr,
            q: Point3::new(u.x * radius, u.y * radius, p.z),
            n: u,
        }
    } else {
        let s = sign(p.z);
        Projection {
            sd: dz,
            q: Point3::new(p.x, p.y, s * half),
            n: Vector3::new(0.0, 0.0, s),
        }
    }
}
