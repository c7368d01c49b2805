//! One part of a mesh collider: a closed shell, or the loose shells together, prepared for
//! exact distance queries — nearest points through a BVH, the segment minimum of the signed
//! distance, and the side of a point.

use super::super::primitives::SegmentMin;
use super::triangle::{Feature, closest_point_triangle, segment_triangle};
use super::winding::WindingTree;
use crate::robot::shells;
use nalgebra::{Point3, Vector3};
use parry3d::bounding_volume::Aabb;
use parry3d::math::Vector as GlamVector;
use parry3d::partitioning::{Bvh, BvhBuildStrategy, BvhNode, TraversalAction};
use std::collections::HashMap;

/// How a part tells inside from outside.
#[derive(Debug, Clone)]
enum Side {
    /// A closed shell: the pseudo-normal at the nearest feature.
    PseudoNormals {
        /// Pseudo-normal of edge k = (v_k, v_k+1) of each triangle.
        edge_normals: Vec<[Vector3<f64>; 3]>,
        /// Angle-weighted pseudo-normal of each vertex.
        vertex_normals: Vec<Vector3<f64>>,
    },
    /// Loose shells: the winding number's magnitude above ½.
    Winding(WindingTree),
}

/// One part of a mesh collider prepared for distance queries in its own frame (metres).
#[derive(Clone)]
pub(in crate::stress::contact) struct SolidMesh {
    /// The part's own vertices (only those its triangles use).
    vertices: Vec<Point3<f64>>,
    /// Non-degenerate triangles only.
    triangles: Vec<[u32; 3]>,
    /// Unit normals of the triangles' winding (outward for closed shells).
    face_normals: Vec<Vector3<f64>>,
    side: Side,
    /// Bounding box of the vertices.
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    bvh: Bvh,
}

impl std::fmt::Debug for SolidMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SolidMesh")
            .field("vertices", &self.vertices.len())
            .field("triangles", &self.triangles.len())
            .field("closed", &self.is_closed_shell())
            .finish()
    }
}

/// The nearest surface point to a query point.
#[derive(Debug, Clone, Copy)]
pub(in crate::stress::contact) struct Nearest {
    pub distance: f64,
    pub q: Point3<f64>,
    triangle: usize,
    feature: Feature,
}

impl SolidMesh {
    /// The part over `triangles` (indices into `vertices`, valid), with its own compact
    /// vertex list; `None` when no triangle has an area. `closed`: a closed shell, wound
    /// outward.
    pub(super) fn part(
        vertices: &[Point3<f64>],
        triangles: &[[u32; 3]],
        closed: bool,
    ) -> Option<SolidMesh> {
        let mut index: HashMap<u32, u32> = HashMap::new();
        let mut own = Vec::new();
        let mut kept = Vec::with_capacity(triangles.len());
        let mut face_normals = Vec::with_capacity(triangles.len());
        for t in triangles {
            let [a, b, c] = t.map(|v| vertices[v as usize]);
            // Zero-area triangles add nothing a neighbour does not cover (closed shells have
            // none; see `shells`).
            if shells::is_zero_area(&a, &b, &c) {
                continue;
            }
            kept.push(t.map(|v| {
                *index.entry(v).or_insert_with(|| {
                    own.push(vertices[v as usize]);
                    (own.len() - 1) as u32
                })
            }));
            face_normals.push((b - a).cross(&(c - a)).normalize());
        }
        if kept.is_empty() {
            return None;
        }
        let (lo, hi) = own.iter().fold(
            (
                Vector3::repeat(f64::INFINITY),
                Vector3::repeat(f64::NEG_INFINITY),
            ),
            |(lo, hi), p| (lo.inf(&p.coords), hi.sup(&p.coords)),
        );
        let side = if closed {
            pseudo_normals(&own, &kept, &face_normals)
        } else {
            Side::Winding(WindingTree::new(&own, &kept))
        };
        Some(SolidMesh {
            lo,
            hi,
            bvh: build_bvh(&own, &kept),
            vertices: own,
            triangles: kept,
            face_normals,
            side,
        })
    }

    /// Whether this part is one closed shell (its inside told by pseudo-normals) rather than
    /// the loose shells of a mesh (told by the winding number).
    pub fn is_closed_shell(&self) -> bool {
        matches!(self.side, Side::PseudoNormals { .. })
    }

    fn corners(&self, triangle: usize) -> [Point3<f64>; 3] {
        self.triangles[triangle].map(|v| self.vertices[v as usize])
    }

    /// Squared distance from `p` to the plane of a triangle: a lower bound for the triangle.
    fn plane_distance2(&self, triangle: usize, p: &Point3<f64>) -> f64 {
        let a = self.vertices[self.triangles[triangle][0] as usize];
        self.face_normals[triangle].dot(&(p - a)).powi(2)
    }

    /// The nearest surface point to `p`.
    pub fn nearest(&self, p: &Point3<f64>) -> Nearest {
        let to_triangle = |ti: usize| {
            let [a, b, c] = self.corners(ti);
            closest_point_triangle(p, &a, &b, &c)
        };
        // A best-first descent (parry, f32 costs) finds a near triangle quickly; its exact
        // distance then prunes the exact depth-first pass.
        let seed = self.bvh.find_best(
            f32::MAX,
            |node: &BvhNode, _| aabb_point_distance2(node, p) as f32,
            |leaf, best| {
                let ti = leaf as usize;
                if self.plane_distance2(ti, p) as f32 >= best {
                    return None;
                }
                Some((p - to_triangle(ti).0).norm_squared() as f32)
            },
        );
        let mut best = Nearest {
            distance: f64::INFINITY,
            q: *p,
            triangle: 0,
            feature: Feature::Face,
        };
        let mut best_d2 = f64::INFINITY;
        if let Some((leaf, _)) = seed {
            let ti = leaf as usize;
            let (q, feature) = to_triangle(ti);
            best_d2 = (p - q).norm_squared();
            best = Nearest {
                distance: 0.0,
                q,
                triangle: ti,
                feature,
            };
        }
        // Ties are pruned too (`>=`): any nearest point serves, and flat regions (a fan of cap
        // triangles) would otherwise all be visited.
        self.bvh.traverse(|node: &BvhNode| {
            if aabb_point_distance2(node, p) >= best_d2 {
                return TraversalAction::Prune;
            }
            if let Some(leaf) = node.leaf_data() {
                let ti = leaf as usize;
                // The triangle's plane is no farther than the triangle.
                if self.plane_distance2(ti, p) >= best_d2 {
                    return TraversalAction::Prune;
                }
                let (q, feature) = to_triangle(ti);
                let d2 = (p - q).norm_squared();
                if d2 < best_d2 {
                    best_d2 = d2;
                    best = Nearest {
                        distance: 0.0,
                        q,
                        triangle: ti,
                        feature,
                    };
                }
            }
            TraversalAction::Continue
        });
        best.distance = best_d2.sqrt();
        best
    }

    /// Whether `p`, whose nearest surface point is `nearest`, lies inside.
    pub fn is_inside(&self, p: &Point3<f64>, nearest: &Nearest) -> bool {
        if nearest.distance == 0.0 || self.outside_box(p) {
            return false;
        }
        match &self.side {
            Side::PseudoNormals {
                edge_normals,
                vertex_normals,
            } => {
                let t = nearest.triangle;
                let normal = match nearest.feature {
                    Feature::Face => self.face_normals[t],
                    Feature::Edge(k) => edge_normals[t][k],
                    Feature::Vertex(k) => vertex_normals[self.triangles[t][k] as usize],
                };
                (p - nearest.q).dot(&normal) < 0.0
            }
            Side::Winding(tree) => {
                tree.winding_number(&self.vertices, &self.triangles, p)
                    .abs()
                    > 0.5
            }
        }
    }

    /// A lower bound on the signed distance of anything in the box `lo`…`hi`: the distance
    /// between it and the bounding box when they are apart (everything there is outside),
    /// −∞ when they meet (it may be inside).
    pub(super) fn box_lower_bound(&self, lo: &Vector3<f64>, hi: &Vector3<f64>) -> f64 {
        let gap2: f64 = (0..3)
            .map(|i| {
                (self.lo[i] - hi[i])
                    .max(lo[i] - self.hi[i])
                    .max(0.0)
                    .powi(2)
            })
            .sum();
        if gap2 > 0.0 {
            gap2.sqrt()
        } else {
            f64::NEG_INFINITY
        }
    }

    /// Whether `p` lies outside the bounding box (then outside the solid: a winding number
    /// above ½ needs the surface on more than one side).
    fn outside_box(&self, p: &Point3<f64>) -> bool {
        (0..3).any(|i| p[i] < self.lo[i] || p[i] > self.hi[i])
    }

    /// Unit outward normal of the triangle `nearest` lies on.
    pub fn face_normal(&self, nearest: &Nearest) -> Vector3<f64> {
        self.face_normals[nearest.triangle]
    }

    /// Minimum signed distance along the segment `a → b` — exact when it is at most `cutoff`
    /// (m); otherwise possibly just some value above `cutoff` (the search inside a solid, the
    /// costly part, stops once it cannot get below it).
    pub fn segment_min(&self, a: &Point3<f64>, b: &Point3<f64>, cutoff: f64) -> SegmentMin {
        let e = b - a;
        let length = e.norm();
        if cutoff.is_finite() {
            // The signed distance is 1-Lipschitz: within half the length of the midpoint's.
            let mid = a + e * 0.5;
            let nearest = self.nearest(&mid);
            let sd = if self.is_inside(&mid, &nearest) {
                -nearest.distance
            } else {
                nearest.distance
            };
            if sd - 0.5 * length > cutoff {
                return SegmentMin { t: 0.5, sd };
            }
        }
        let seg_min = a.coords.inf(&b.coords);
        let seg_max = a.coords.sup(&b.coords);
        let mut best = SegmentMin {
            t: 0.0,
            sd: f64::INFINITY,
        };
        let mut best_d2 = f64::INFINITY;
        let seed = self.bvh.find_best(
            f32::MAX,
            |node: &BvhNode, _| aabb_aabb_distance2(node, &seg_min, &seg_max) as f32,
            |leaf, _| Some(segment_triangle(a, &e, &self.corners(leaf as usize)).d2 as f32),
        );
        if let Some((leaf, _)) = seed {
            let hit = segment_triangle(a, &e, &self.corners(leaf as usize));
            best_d2 = hit.d2;
            best.t = hit.t;
        }
        // Parameters where the segment passes through the plane of a triangle at (or within
        // rounding of) the triangle: the only places it can go from outside to inside.
        let mut cuts: Vec<f64> = Vec::new();
        self.bvh.traverse(|node: &BvhNode| {
            if aabb_aabb_distance2(node, &seg_min, &seg_max) > best_d2 {
                return TraversalAction::Prune;
            }
            if let Some(leaf) = node.leaf_data() {
                let tri = self.corners(leaf as usize);
                let hit = segment_triangle(a, &e, &tri);
                if let Some(t) = hit.cut {
                    cuts.push(t);
                }
                if hit.d2 < best_d2 || (hit.d2 == best_d2 && hit.t < best.t) {
                    best_d2 = hit.d2;
                    best.t = hit.t;
                }
            }
            TraversalAction::Continue
        });
        best.sd = best_d2.sqrt();
        if cuts.is_empty() && (self.outside_box(a) || self.outside_box(b)) {
            // One side only, and an end is outside the bounding box: all outside.
            return best;
        }
        // Split at the cuts; every piece lies on one side, told by its midpoint.
        let pieces: &[f64] = if cuts.is_empty() {
            &[0.0, 1.0]
        } else {
            cuts.push(0.0);
            cuts.push(1.0);
            cuts.sort_unstable_by(f64::total_cmp);
            cuts.dedup();
            &cuts
        };
        let mut deepest: Option<SegmentMin> = None;
        for w in pieces.windows(2) {
            let (t0, t1) = (w[0], w[1]);
            let mid = a + e * (0.5 * (t0 + t1));
            let nearest = self.nearest(&mid);
            if !self.is_inside(&mid, &nearest) {
                continue;
            }
            // Depth is 1-Lipschitz along the segment: bounded by the midpoint's plus half the
            // piece's length.
            if -(nearest.distance + 0.5 * (t1 - t0) * length) > cutoff {
                let piece = SegmentMin {
                    t: 0.5 * (t0 + t1),
                    sd: -nearest.distance,
                };
                deepest = Some(deepest.map_or(piece, |d| d.min(piece)));
                continue;
            }
            let piece = self.deepest_in(a, &e, t0, t1, cutoff);
            deepest = Some(deepest.map_or(piece, |d| d.min(piece)));
        }
        deepest.unwrap_or(best)
    }

    /// The point of `a + t·e`, t ∈ [t0, t1] (all inside), farthest from the surface.
    ///
    /// Nine samples, then around the best one: cutting lines while the nearest features are
    /// faces (the depth is then locally linear, and for a concave depth — inside a convex
    /// mesh — two tangent lines bound the maximum, so reaching their intersection proves it),
    /// else a golden-section search down to 1e-13 m along the segment. Exact for convex
    /// meshes; a local maximum for others. Stops after the samples when even the best bound
    /// cannot reach below `cutoff`.
    fn deepest_in(
        &self,
        a: &Point3<f64>,
        e: &Vector3<f64>,
        t0: f64,
        t1: f64,
        cutoff: f64,
    ) -> SegmentMin {
        // Depth and, on a face, its slope d(depth)/dt.
        let probe = |t: f64| {
            let nearest = self.nearest(&(a + e * t));
            let slope = (nearest.feature == Feature::Face)
                .then(|| -self.face_normals[nearest.triangle].dot(e));
            (nearest.distance, slope)
        };
        const SAMPLES: usize = 8;
        let at = |i: usize| t0 + (t1 - t0) * i as f64 / SAMPLES as f64;
        let mut samples = [(0.0, None); SAMPLES + 1];
        for (i, sample) in samples.iter_mut().enumerate() {
            *sample = probe(at(i));
        }
        let mut best_i = 0;
        for i in 1..=SAMPLES {
            if samples[i].0 > samples[best_i].0 {
                best_i = i;
            }
        }
        let (best_u, best_slope) = samples[best_i];
        let mut best = SegmentMin {
            t: at(best_i),
            sd: -best_u,
        };
        // Between two samples the depth is at most the meeting point of their Lipschitz cones.
        let length = e.norm();
        let step = (t1 - t0) / SAMPLES as f64 * length;
        let bound = samples
            .windows(2)
            .map(|w| 0.5 * (w[0].0 + w[1].0 + step))
            .fold(best_u, f64::max);
        if -bound > cutoff {
            return best;
        }
        // Deepest at an end of the piece, still descending there.
        match (best_i, best_slope) {
            (0, Some(s)) if s <= 0.0 => return best,
            (SAMPLES, Some(s)) if s >= 0.0 => return best,
            _ => {}
        }
        let (i_lo, i_hi) = (best_i.saturating_sub(1), (best_i + 1).min(SAMPLES));
        let (mut lo, mut hi) = (at(i_lo), at(i_hi));
        let ((mut u_lo, mut s_lo), (mut u_hi, mut s_hi)) = (samples[i_lo], samples[i_hi]);
        for _ in 0..64 {
            let (Some(sl), Some(sh)) = (s_lo, s_hi) else {
                break;
            };
            if sl <= sh {
                break;
            }
            let tc = ((u_hi - u_lo) + sl * lo - sh * hi) / (sl - sh);
            if !(lo..=hi).contains(&tc) {
                break;
            }
            let line = u_lo + sl * (tc - lo);
            let (uc, sc) = probe(tc);
            best = best.min(SegmentMin { t: tc, sd: -uc });
            if line - uc <= 1e-13 {
                return best;
            }
            match sc {
                Some(s) if s > 0.0 => (lo, u_lo, s_lo) = (tc, uc, sc),
                Some(s) if s < 0.0 => (hi, u_hi, s_hi) = (tc, uc, sc),
                _ => break,
            }
        }
        let depth = |t: f64| probe(t).0;
        let tolerance = if length > 0.0 { 1e-13 / length } else { 1.0 };
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let mut x1 = hi - ratio * (hi - lo);
        let mut x2 = lo + ratio * (hi - lo);
        let (mut f1, mut f2) = (depth(x1), depth(x2));
        while hi - lo > tolerance {
            if f1 >= f2 {
                hi = x2;
                (x2, f2) = (x1, f1);
                x1 = hi - ratio * (hi - lo);
                f1 = depth(x1);
            } else {
                lo = x1;
                (x1, f1) = (x2, f2);
                x2 = lo + ratio * (hi - lo);
                f2 = depth(x2);
            }
        }
        for (t, u) in [(x1, f1), (x2, f2)] {
            best = best.min(SegmentMin { t, sd: -u });
        }
        best
    }
}

/// The pseudo-normals of a closed shell wound outward: of each edge the sum of its two
/// triangles' normals, of each vertex the angle-weighted sum of its triangles' normals.
fn pseudo_normals(
    vertices: &[Point3<f64>],
    triangles: &[[u32; 3]],
    face_normals: &[Vector3<f64>],
) -> Side {
    let mut edge_normals = vec![[Vector3::zeros(); 3]; triangles.len()];
    for uses in shells::EdgeTable::new(triangles).groups() {
        let sum: Vector3<f64> = uses.iter().map(|e| face_normals[e.triangle]).sum();
        for e in uses {
            edge_normals[e.triangle][e.slot] = sum;
        }
    }
    let mut vertex_normals = vec![Vector3::zeros(); vertices.len()];
    for (t, n) in triangles.iter().zip(face_normals) {
        for k in 0..3 {
            let p = vertices[t[k] as usize];
            let u = vertices[t[(k + 1) % 3] as usize] - p;
            let w = vertices[t[(k + 2) % 3] as usize] - p;
            vertex_normals[t[k] as usize] += n * u.angle(&w);
        }
    }
    Side::PseudoNormals {
        edge_normals,
        vertex_normals,
    }
}

/// BVH over the triangles' bounding boxes, rounded outward to f32 so they contain the f64
/// triangles.
fn build_bvh(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Bvh {
    let down = |v: f64| {
        let f = v as f32;
        if f64::from(f) > v { f.next_down() } else { f }
    };
    let up = |v: f64| {
        let f = v as f32;
        if f64::from(f) < v { f.next_up() } else { f }
    };
    let aabbs: Vec<Aabb> = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| vertices[v as usize].coords);
            let lo = a.inf(&b).inf(&c);
            let hi = a.sup(&b).sup(&c);
            Aabb::new(
                GlamVector::new(down(lo.x), down(lo.y), down(lo.z)),
                GlamVector::new(up(hi.x), up(hi.y), up(hi.z)),
            )
        })
        .collect();
    Bvh::from_leaves(BvhBuildStrategy::Binned, &aabbs)
}

fn node_bounds(node: &BvhNode) -> (Vector3<f64>, Vector3<f64>) {
    let (lo, hi) = (node.mins(), node.maxs());
    (
        Vector3::new(lo.x.into(), lo.y.into(), lo.z.into()),
        Vector3::new(hi.x.into(), hi.y.into(), hi.z.into()),
    )
}

fn aabb_point_distance2(node: &BvhNode, p: &Point3<f64>) -> f64 {
    let (lo, hi) = node_bounds(node);
    (0..3)
        .map(|i| (lo[i] - p[i]).max(p[i] - hi[i]).max(0.0).powi(2))
        .sum()
}

fn aabb_aabb_distance2(node: &BvhNode, lo2: &Vector3<f64>, hi2: &Vector3<f64>) -> f64 {
    let (lo, hi) = node_bounds(node);
    (0..3)
        .map(|i| (lo[i] - hi2[i]).max(lo2[i] - hi[i]).max(0.0).powi(2))
        .sum()
}
