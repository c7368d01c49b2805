//! Brute-force reference for "is this point inside the solid?" and "how far is it from the
//! mesh?" on triangle meshes such as the STL collision meshes of robot descriptions.
//!
//! This module is an *independent* judge of the crate's contact code: it uses only `std`
//! (its own STL reader, its own geometry, `f64` throughout) and nothing from the `cable_dict`
//! crate. It trades all speed for being obviously right:
//!
//! - **Shells** are the connected components of triangles that share a vertex *position*
//!   (exact equality of the coordinates, `-0.0` counted as `0.0`).
//! - **Inside** is inside the *union* of the shells. For each shell the parity of the number of
//!   crossings of a ray from the point (Möller–Trumbore, crossing when `t > 0`) says whether the
//!   point is inside that shell; parity ignores how the triangles are wound, so shells wound
//!   inwards (or with a flipped triangle) give the same answer. The point is inside when some
//!   shell says so. A shell nested in another (a modelled cavity) therefore does not hollow the
//!   solid out: the union fills it. This is done for five fixed ray directions; when they do not
//!   all agree (a ray through an edge or a vertex, a shell with a hole) the answer is `None` and
//!   callers skip the point.
//! - **Distance** is the unsigned distance to the nearest point of any triangle, by a loop over
//!   all triangles and the closest point on a triangle found by its Voronoi regions (vertex,
//!   edge or face) expressed with barycentric coordinates.

use std::collections::HashMap;
use std::f64::consts::{LN_2, LOG10_2, SQRT_2};
use std::path::Path;

/// A triangle: three vertices, in metres.
pub type Triangle = [[f64; 3]; 3];

/// Ray directions for the parity test: fixed, not axis-aligned, in different octants, built from
/// irrational numbers so that a ray from a point with "round" coordinates does not run along a
/// face or through an edge of a mesh with "round" vertices. (They need not be unit vectors.)
const RAY_DIRECTIONS: [[f64; 3]; 5] = [
    // √2, √3 − 1, π − 3
    [SQRT_2, 0.732_050_807_57, 0.141_592_653_59],
    // −(e − 2), √5 − 2, 1/√7
    [-0.718_281_828_46, 0.236_067_977_50, 0.377_964_473_01],
    // log10(2), −(golden ratio − 1), ln 2
    [LOG10_2, -0.618_033_988_75, LN_2],
    // −(Euler–Mascheroni γ), −(√2 − 1), −(∛2 − 1)
    [-0.577_215_664_90, -0.414_213_562_37, -0.259_921_049_89],
    // Catalan's constant, ζ(3) − 1, −2^(−1/4)
    [0.915_965_594_18, 0.202_056_903_16, -0.840_896_415_25],
];

pub struct ReferenceSolid {
    /// Triangles in metres, in the mesh frame, as read (winding untouched).
    triangles: Vec<Triangle>,
    /// The shell of each triangle, `0..shells`.
    shell_of: Vec<usize>,
    shells: usize,
}

impl ReferenceSolid {
    /// Reads a binary or ASCII STL and multiplies every coordinate by `scale` (e.g. `0.001` for
    /// a mesh in millimetres). Panics with a message when the file cannot be read or parsed.
    ///
    /// A file is binary when its length is exactly `84 + 50 n` with `n` the triangle count in
    /// bytes 80..84 (whatever its header says: binary files that begin with "solid" exist);
    /// otherwise it is read as ASCII, taking every `vertex x y z` line in order, three per facet.
    pub fn from_stl(path: &Path, scale: f64) -> ReferenceSolid {
        let bytes =
            std::fs::read(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
        let triangles = if is_binary_stl(&bytes) {
            parse_binary_stl(&bytes)
        } else {
            parse_ascii_stl(&bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        };
        let scaled = triangles
            .into_iter()
            .map(|t| t.map(|v| v.map(|x| x * scale)))
            .collect();
        ReferenceSolid::from_triangles(scaled)
    }

    pub fn from_triangles(triangles: Vec<Triangle>) -> ReferenceSolid {
        let (shell_of, shells) = shells_by_shared_vertices(&triangles);
        ReferenceSolid {
            triangles,
            shell_of,
            shells,
        }
    }

    pub fn triangles(&self) -> &[Triangle] {
        &self.triangles
    }

    /// The shell (`0..shell_count()`) of each triangle, in the order of `triangles()`.
    pub fn shell_of(&self) -> &[usize] {
        &self.shell_of
    }

    /// Number of shells: connected components of triangles sharing a vertex position.
    pub fn shell_count(&self) -> usize {
        self.shells
    }

    /// Whether `p` is inside the union of the shells: `Some(answer)` when the five ray directions
    /// agree, `None` when they do not (skip such points).
    pub fn inside(&self, p: [f64; 3]) -> Option<bool> {
        let first = self.inside_along(p, RAY_DIRECTIONS[0]);
        for d in &RAY_DIRECTIONS[1..] {
            if self.inside_along(p, *d) != first {
                return None;
            }
        }
        Some(first)
    }

    /// The union answer for one ray: inside when the ray crosses some shell an odd number of
    /// times.
    fn inside_along(&self, p: [f64; 3], d: [f64; 3]) -> bool {
        let mut odd = vec![false; self.shells];
        for (t, &s) in self.triangles.iter().zip(&self.shell_of) {
            if ray_crosses_triangle(p, d, t) {
                odd[s] = !odd[s];
            }
        }
        odd.into_iter().any(|o| o)
    }

    /// Whether `p` is inside shell `shell` alone (ray parity over its triangles), `None` when
    /// the five directions disagree.
    pub fn inside_shell(&self, p: [f64; 3], shell: usize) -> Option<bool> {
        let along = |d: [f64; 3]| {
            self.triangles
                .iter()
                .zip(&self.shell_of)
                .filter(|&(t, &s)| s == shell && ray_crosses_triangle(p, d, t))
                .count()
                % 2
                == 1
        };
        let first = along(RAY_DIRECTIONS[0]);
        RAY_DIRECTIONS[1..]
            .iter()
            .all(|&d| along(d) == first)
            .then_some(first)
    }

    /// Unsigned distance from `p` to the nearest point of shell `shell`'s triangles.
    pub fn distance_to_shell(&self, p: [f64; 3], shell: usize) -> f64 {
        self.triangles
            .iter()
            .zip(&self.shell_of)
            .filter(|&(_, &s)| s == shell)
            .map(|(t, _)| norm(sub(p, closest_point_on_triangle(p, t))))
            .fold(f64::INFINITY, f64::min)
    }

    /// Unsigned distance from `p` to the nearest point of any triangle (`+∞` for no triangles).
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        self.triangles
            .iter()
            .map(|t| norm(sub(p, closest_point_on_triangle(p, t))))
            .fold(f64::INFINITY, f64::min)
    }

    /// Axis-aligned bounding box `(min, max)` of all vertices.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in self.triangles.iter().flatten() {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        (lo, hi)
    }
}

// ---------------------------------------------------------------------------------------------
// STL reading

fn is_binary_stl(bytes: &[u8]) -> bool {
    if bytes.len() < 84 {
        return false;
    }
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    n.checked_mul(50).and_then(|b| b.checked_add(84)) == Some(bytes.len())
}

/// Binary STL: 80-byte header, `u32` count, then per facet a normal (ignored), three vertices
/// (`f32` little-endian) and a 2-byte attribute.
fn parse_binary_stl(bytes: &[u8]) -> Vec<Triangle> {
    let f = |at: usize| {
        f64::from(f32::from_le_bytes([
            bytes[at],
            bytes[at + 1],
            bytes[at + 2],
            bytes[at + 3],
        ]))
    };
    let n = (bytes.len() - 84) / 50;
    (0..n)
        .map(|i| {
            // Skip the facet's normal (12 bytes); then three vertices of 12 bytes each.
            let at = 84 + 50 * i + 12;
            let v = |k: usize| [f(at + 12 * k), f(at + 12 * k + 4), f(at + 12 * k + 8)];
            [v(0), v(1), v(2)]
        })
        .collect()
}

/// ASCII STL: every `vertex x y z` in order, grouped by three.
fn parse_ascii_stl(bytes: &[u8]) -> Result<Vec<Triangle>, String> {
    let text = String::from_utf8_lossy(bytes);
    let mut vertices = Vec::new();
    for (line_no, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("vertex") {
            continue;
        }
        let mut v = [0.0; 3];
        for x in &mut v {
            *x = words
                .next()
                .and_then(|w| w.parse::<f64>().ok())
                .ok_or_else(|| format!("line {}: bad vertex", line_no + 1))?;
        }
        vertices.push(v);
    }
    if vertices.len() % 3 != 0 {
        return Err(format!(
            "{} vertices is not a multiple of 3",
            vertices.len()
        ));
    }
    Ok(vertices
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect())
}

// ---------------------------------------------------------------------------------------------
// Shells

/// Union–find over triangles, joining every two triangles that have a vertex at the same
/// position. Returns the shell of each triangle (numbered in order of first appearance) and the
/// number of shells.
fn shells_by_shared_vertices(triangles: &[Triangle]) -> (Vec<usize>, usize) {
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut parent: Vec<usize> = (0..triangles.len()).collect();
    let mut first_with_vertex: HashMap<[u64; 3], usize> = HashMap::new();
    for (i, t) in triangles.iter().enumerate() {
        for v in t {
            // `+ 0.0` turns −0.0 into +0.0 so that the two compare equal, as they do as numbers.
            let key = v.map(|x| (x + 0.0).to_bits());
            let j = *first_with_vertex.entry(key).or_insert(i);
            let (a, b) = (find(&mut parent, i), find(&mut parent, j));
            parent[a] = b;
        }
    }
    let mut number: HashMap<usize, usize> = HashMap::new();
    let mut shell_of = Vec::with_capacity(triangles.len());
    for i in 0..triangles.len() {
        let root = find(&mut parent, i);
        let next = number.len();
        shell_of.push(*number.entry(root).or_insert(next));
    }
    let count = number.len();
    (shell_of, count)
}

// ---------------------------------------------------------------------------------------------
// Geometry

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add_scaled(a: [f64; 3], s: f64, b: [f64; 3]) -> [f64; 3] {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Möller–Trumbore: does the ray `p + t d`, `t > 0`, cross the triangle? Solves
/// `p + t d = a + u (b − a) + v (c − a)` by Cramer's rule; a crossing needs `u ≥ 0`, `v ≥ 0`,
/// `u + v ≤ 1` and `t > 0`. A ray in the triangle's plane (determinant 0) does not cross it.
pub fn ray_crosses_triangle(p: [f64; 3], d: [f64; 3], t: &Triangle) -> bool {
    let e1 = sub(t[1], t[0]);
    let e2 = sub(t[2], t[0]);
    let h = cross(d, e2);
    let det = dot(e1, h);
    if det == 0.0 || !det.is_finite() {
        return false;
    }
    let s = sub(p, t[0]);
    let u = dot(s, h) / det;
    if !(0.0..=1.0).contains(&u) {
        return false;
    }
    let q = cross(s, e1);
    let v = dot(d, q) / det;
    if v < 0.0 || u + v > 1.0 {
        return false;
    }
    let along = dot(e2, q) / det;
    along > 0.0
}

/// The point of the segment `a b` nearest to `p`.
fn closest_point_on_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    if len2 == 0.0 {
        return a;
    }
    let s = (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0);
    add_scaled(a, s, ab)
}

/// The point of the triangle `a b c` nearest to `p`.
///
/// With `ab = b − a`, `ac = c − a`, the nearest point is in one of seven Voronoi regions, tested
/// in turn from the dot products of `ab`, `ac` with `p − a`, `p − b`, `p − c`:
/// vertex `a` (`p` is behind both edges leaving `a`), vertex `b`, edge `ab` (the barycentric
/// weight of `c` of the projection is ≤ 0 and `p` projects inside the edge), vertex `c`,
/// edge `ac`, edge `bc`, and otherwise the face (the projection of `p` on the plane, with
/// barycentric weights `va : vb : vc`, all positive).
///
/// A degenerate triangle (its vertices on a line or one point) has no face region: its
/// nearest point is on one of its three edges.
pub fn closest_point_on_triangle(p: [f64; 3], t: &Triangle) -> [f64; 3] {
    let [a, b, c] = *t;
    let ab = sub(b, a);
    let ac = sub(c, a);
    let n = cross(ab, ac);
    if dot(n, n) <= (f64::EPSILON * f64::EPSILON) * dot(ab, ab) * dot(ac, ac) {
        return [
            closest_point_on_segment(p, a, b),
            closest_point_on_segment(p, b, c),
            closest_point_on_segment(p, c, a),
        ]
        .into_iter()
        .min_by(|x, y| dot(sub(p, *x), sub(p, *x)).total_cmp(&dot(sub(p, *y), sub(p, *y))))
        .unwrap_or(a);
    }

    // Vertex region a.
    let ap = sub(p, a);
    let d1 = dot(ab, ap);
    let d2 = dot(ac, ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    // Vertex region b.
    let bp = sub(p, b);
    let d3 = dot(ab, bp);
    let d4 = dot(ac, bp);
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    // Edge region ab: vc is (proportional to) the barycentric weight of c.
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return add_scaled(a, d1 / (d1 - d3), ab);
    }
    // Vertex region c.
    let cp = sub(p, c);
    let d5 = dot(ab, cp);
    let d6 = dot(ac, cp);
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    // Edge region ac: vb is (proportional to) the barycentric weight of b.
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return add_scaled(a, d2 / (d2 - d6), ac);
    }
    // Edge region bc: va is (proportional to) the barycentric weight of a.
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return add_scaled(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b));
    }
    // Face region: barycentric (va, vb, vc) / (va + vb + vc).
    let sum = va + vb + vc;
    add_scaled(add_scaled(a, vb / sum, ab), vc / sum, ac)
}
