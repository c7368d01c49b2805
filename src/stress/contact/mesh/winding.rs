//! The generalized winding number of a triangle soup (Jacobson et al. 2013), evaluated exactly
//! through a bounding-volume tree.
//!
//! The winding number of wound triangles at `p` is the sum of their signed solid angles seen
//! from `p`, over 4π: 1 inside a closed outward surface, 0 outside, 2 where two overlap, and
//! in between near a hole. A point is inside when its magnitude exceeds ½.
//!
//! Summing every triangle costs O(n). The tree makes it exact and cheap: for a node whose box
//! does not contain `p`, its triangles plus any surface spanning their boundary loops form a
//! closed surface with `p` outside it, so the node's solid angle equals that of the spanning
//! surface — a fan from the box centre over the node's boundary edges, usually far fewer than
//! its triangles (none at all for a closed patch).

use nalgebra::{Point3, Vector3};

/// Leaves hold at most this many triangles.
const LEAF_SIZE: usize = 8;

/// A node of the tree over a range of [`WindingTree::order`].
#[derive(Debug, Clone)]
struct Node {
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    /// Triangles `order[first..first + count]`.
    first: usize,
    count: usize,
    /// Children (indices into `nodes`), none for a leaf.
    children: Option<[usize; 2]>,
    /// Its boundary edges `boundary[start..end]`, when fewer than its triangles.
    fan: Option<(usize, usize)>,
}

/// Triangles prepared for winding-number queries.
#[derive(Debug, Clone)]
pub(super) struct WindingTree {
    nodes: Vec<Node>,
    /// Triangle indices in leaf order.
    order: Vec<usize>,
    /// Directed boundary edges of the nodes that keep them (vertex indices).
    boundary: Vec<[u32; 2]>,
}

impl WindingTree {
    /// Builds the tree over `triangles` (indices into `vertices`, assumed valid).
    pub fn new(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> WindingTree {
        let centroid = |t: usize| {
            let [a, b, c] = triangles[t].map(|v| vertices[v as usize].coords);
            (a + b + c) / 3.0
        };
        let mut tree = WindingTree {
            nodes: Vec::new(),
            order: (0..triangles.len()).collect(),
            boundary: Vec::new(),
        };
        // Nodes are built top-down by an explicit stack (depth is log₂ n by median splits);
        // boundaries bottom-up afterwards, children before parents.
        tree.nodes
            .push(tree.node_over(vertices, triangles, 0, triangles.len()));
        let mut stack = vec![0];
        while let Some(n) = stack.pop() {
            let (first, count) = (tree.nodes[n].first, tree.nodes[n].count);
            if count <= LEAF_SIZE {
                continue;
            }
            let axis = (tree.nodes[n].hi - tree.nodes[n].lo).imax();
            let half = count / 2;
            tree.order[first..first + count].select_nth_unstable_by(half, |&i, &j| {
                centroid(i)[axis]
                    .total_cmp(&centroid(j)[axis])
                    .then(i.cmp(&j))
            });
            let left = tree.nodes.len();
            tree.nodes
                .push(tree.node_over(vertices, triangles, first, half));
            tree.nodes
                .push(tree.node_over(vertices, triangles, first + half, count - half));
            tree.nodes[n].children = Some([left, left + 1]);
            stack.extend([left, left + 1]);
        }
        // Children have higher indices than their parent: walk backwards.
        let mut edges_of: Vec<Vec<[u32; 2]>> = vec![Vec::new(); tree.nodes.len()];
        for n in (0..tree.nodes.len()).rev() {
            let edges = match tree.nodes[n].children {
                None => {
                    let node = &tree.nodes[n];
                    let own = tree.order[node.first..node.first + node.count]
                        .iter()
                        .flat_map(|&t| {
                            let [a, b, c] = triangles[t];
                            [[a, b], [b, c], [c, a]]
                        })
                        .collect();
                    cancel(own)
                }
                Some([l, r]) => {
                    let mut both = std::mem::take(&mut edges_of[l]);
                    both.append(&mut std::mem::take(&mut edges_of[r]));
                    cancel(both)
                }
            };
            if edges.len() < tree.nodes[n].count {
                let start = tree.boundary.len();
                tree.boundary.extend_from_slice(&edges);
                tree.nodes[n].fan = Some((start, tree.boundary.len()));
            }
            edges_of[n] = edges;
        }
        tree
    }

    fn node_over(
        &self,
        vertices: &[Point3<f64>],
        triangles: &[[u32; 3]],
        first: usize,
        count: usize,
    ) -> Node {
        let (lo, hi) = self.order[first..first + count]
            .iter()
            .flat_map(|&t| triangles[t])
            .fold(
                (
                    Vector3::repeat(f64::INFINITY),
                    Vector3::repeat(f64::NEG_INFINITY),
                ),
                |(lo, hi), v| {
                    let p = vertices[v as usize].coords;
                    (lo.inf(&p), hi.sup(&p))
                },
            );
        Node {
            lo,
            hi,
            first,
            count,
            children: None,
            fan: None,
        }
    }

    /// The winding number at `p` of `triangles` (the same the tree was built over).
    pub fn winding_number(
        &self,
        vertices: &[Point3<f64>],
        triangles: &[[u32; 3]],
        p: &Point3<f64>,
    ) -> f64 {
        let corner = |v: u32| vertices[v as usize].coords - p.coords;
        let mut total = 0.0;
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            let outside = (0..3).any(|i| p[i] < node.lo[i] || p[i] > node.hi[i]);
            if let (true, Some((start, end))) = (outside, node.fan) {
                let apex = 0.5 * (node.lo + node.hi) - p.coords;
                total += self.boundary[start..end]
                    .iter()
                    .map(|&[u, v]| solid_angle(&apex, &corner(u), &corner(v)))
                    .sum::<f64>();
                continue;
            }
            match node.children {
                Some([l, r]) => stack.extend([l, r]),
                None => {
                    total += self.order[node.first..node.first + node.count]
                        .iter()
                        .map(|&t| {
                            let [a, b, c] = triangles[t].map(corner);
                            solid_angle(&a, &b, &c)
                        })
                        .sum::<f64>();
                }
            }
        }
        total / (4.0 * std::f64::consts::PI)
    }
}

/// Directed edges with every pair (u, v), (v, u) removed: what is left bounds the patch.
fn cancel(mut edges: Vec<[u32; 2]>) -> Vec<[u32; 2]> {
    edges.sort_unstable_by_key(|&[u, v]| (u.min(v), u.max(v), u > v));
    let mut out = Vec::new();
    for group in
        edges.chunk_by(|a, b| a[0].min(a[1]) == b[0].min(b[1]) && a[0].max(a[1]) == b[0].max(b[1]))
    {
        let (u, v) = (group[0][0].min(group[0][1]), group[0][0].max(group[0][1]));
        let net: i64 = group.iter().map(|e| if e[0] == u { 1 } else { -1 }).sum();
        let edge = if net > 0 { [u, v] } else { [v, u] };
        out.extend(std::iter::repeat_n(edge, net.unsigned_abs() as usize));
    }
    out
}

/// Signed solid angle of the triangle (a, b, c) seen from the origin (Van Oosterom & Strackee
/// 1983): positive when the origin lies behind it (on the side opposite its winding's
/// normal), as every triangle of an outward surface is seen from inside.
fn solid_angle(a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) -> f64 {
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let numerator = a.dot(&b.cross(c));
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * numerator.atan2(denominator)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An outward icosphere-like octahedron subdivided: closed, so 1 inside and 0 outside.
    fn octahedron() -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
        let vertices = vec![
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(-1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, -1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
            Point3::new(0.0, 0.0, -1.0),
        ];
        let triangles = vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        (vertices, triangles)
    }

    /// The sum over every triangle, without the tree: the reference.
    fn direct(vertices: &[Point3<f64>], triangles: &[[u32; 3]], p: &Point3<f64>) -> f64 {
        triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| vertices[v as usize] - p);
                solid_angle(&a, &b, &c)
            })
            .sum::<f64>()
            / (4.0 * std::f64::consts::PI)
    }

    #[test]
    fn a_closed_surface_winds_once_inside_and_never_outside() {
        let (v, t) = octahedron();
        let tree = WindingTree::new(&v, &t);
        let inside = tree.winding_number(&v, &t, &Point3::new(0.1, 0.2, -0.3));
        assert!((inside - 1.0).abs() < 1e-12, "{inside}");
        let outside = tree.winding_number(&v, &t, &Point3::new(0.9, 0.9, 0.1));
        assert!(outside.abs() < 1e-12, "{outside}");
    }

    #[test]
    fn the_tree_agrees_with_the_direct_sum_on_an_open_fan() {
        // A wavy open grid of 20 × 20 squares: many nodes with boundaries.
        let n = 20u32;
        let vertices: Vec<Point3<f64>> = (0..=n)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| {
                let (x, y) = (f64::from(i) / 10.0 - 1.0, f64::from(j) / 10.0 - 1.0);
                Point3::new(x, y, 0.2 * (3.0 * x).sin() * (2.0 * y).cos())
            })
            .collect();
        let at = |i: u32, j: u32| i * (n + 1) + j;
        let triangles: Vec<[u32; 3]> = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .flat_map(|(i, j)| {
                [
                    [at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                    [at(i, j), at(i + 1, j + 1), at(i, j + 1)],
                ]
            })
            .collect();
        let tree = WindingTree::new(&vertices, &triangles);
        for p in [
            Point3::new(0.0, 0.0, 0.5),
            Point3::new(0.33, -0.71, -0.05),
            Point3::new(1.5, 0.2, 0.1),
            Point3::new(-0.95, 0.95, 0.01),
        ] {
            let (got, want) = (
                tree.winding_number(&vertices, &triangles, &p),
                direct(&vertices, &triangles, &p),
            );
            assert!(
                (got - want).abs() < 1e-12,
                "{p:?}: tree {got}, direct {want}"
            );
            assert!(got.abs() < 0.5, "an open sheet has no inside: {got}");
        }
    }
}
