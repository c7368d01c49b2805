//! Triangle meshes as obstacles: exact (f64) distances, with parry's BVH for culling.
//!
//! A mesh collider ([`MeshSolid`]) is the union of its shells' solids (see
//! [`crate::robot::shells`]). Each closed shell becomes one part ([`SolidMesh`]) whose inside
//! is decided by angle-weighted pseudo-normals at the nearest feature (Bærentzen & Aanæs
//! 2005): exact for a closed, consistently wound surface, and cheap, since the nearest
//! feature is found anyway. All loose shells together (open edges, edges of more than two
//! triangles, self-crossing) become one more part whose inside is where the winding number
//! exceeds ½ — right for overlapping and touching pieces and for inconsistent winding, and a
//! smooth guess across a hole. The mesh's signed distance is the minimum over its parts: the
//! exact distance to the union's surface outside it, and inside minus the depth below the
//! surface of the part the point is deepest in (the union's own depth is at least that).

mod part;
mod triangle;
mod winding;

use super::primitives::{Projection, SegmentMin};
use crate::robot::shells::{self, ShellKind};
use nalgebra::{Point3, Vector3};
pub(super) use part::{Nearest, SolidMesh};

/// A mesh collider: the union of its parts' solids.
#[derive(Debug, Clone)]
pub(super) struct MeshSolid {
    parts: Vec<SolidMesh>,
    /// The mesh's vertices (m, mesh frame), for its bounding capsule.
    vertices: Vec<Point3<f64>>,
}

impl MeshSolid {
    /// Splits a mesh into its parts (see [`solids_of`]).
    pub fn new(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Result<MeshSolid, String> {
        Ok(MeshSolid {
            parts: solids_of(vertices, triangles)?,
            vertices: vertices.to_vec(),
        })
    }

    /// The mesh vertices (m, mesh frame).
    pub fn vertices(&self) -> &[Point3<f64>] {
        &self.vertices
    }

    /// Whether some part is loose shells, its inside decided by the winding number.
    pub fn has_loose_part(&self) -> bool {
        self.parts.iter().any(|p| !p.is_closed_shell())
    }

    /// Minimum over the parts of their signed distance along `a → b`; exact when at most
    /// `cutoff` (m). A part whose bounding box is farther from the segment's than the best so
    /// far is skipped: its solid lies in its box, so nothing there can be nearer.
    pub fn segment_min(&self, a: &Point3<f64>, b: &Point3<f64>, cutoff: f64) -> SegmentMin {
        let (lo, hi) = (a.coords.inf(&b.coords), a.coords.sup(&b.coords));
        let mut best = SegmentMin {
            t: 0.0,
            sd: f64::INFINITY,
        };
        for part in &self.parts {
            let limit = cutoff.min(best.sd);
            if part.box_lower_bound(&lo, &hi) > limit {
                continue;
            }
            best = best.min(part.segment_min(a, b, limit));
        }
        best
    }

    /// The signed distance of `p`, its nearest surface point and the outward normal there;
    /// `inside` (known from the segment query) picks the part `p` lies deepest in, otherwise
    /// the nearest part.
    pub fn project(&self, p: &Point3<f64>, inside: bool) -> Projection {
        let nearest: Vec<(&SolidMesh, Nearest)> = self
            .parts
            .iter()
            .map(|part| (part, part.nearest(p)))
            .collect();
        let deepest = || {
            nearest
                .iter()
                .filter(|(part, n)| part.is_inside(p, n))
                .max_by(|x, y| x.1.distance.total_cmp(&y.1.distance))
        };
        let closest = || {
            nearest
                .iter()
                .min_by(|x, y| x.1.distance.total_cmp(&y.1.distance))
        };
        // A mesh has at least one part; `else` only guards that invariant.
        let Some(&(part, nearest)) = inside.then(deepest).flatten().or_else(closest) else {
            return Projection {
                sd: 0.0,
                q: *p,
                n: Vector3::z(),
            };
        };
        let u = nearest.distance;
        if u == 0.0 {
            Projection {
                sd: 0.0,
                q: nearest.q,
                n: part.face_normal(&nearest),
            }
        } else if inside {
            Projection {
                sd: -u,
                q: nearest.q,
                n: (nearest.q - p) / u,
            }
        } else {
            Projection {
                sd: u,
                q: nearest.q,
                n: (p - nearest.q) / u,
            }
        }
    }
}

/// Splits a mesh into its parts: one per closed shell, then one for every loose shell
/// together; the error text says what is wrong with the mesh.
pub(super) fn solids_of(
    vertices: &[Point3<f64>],
    triangles: &[[u32; 3]],
) -> Result<Vec<SolidMesh>, String> {
    if let Some(i) = vertices
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        return Err(format!("vertex {i} is not finite"));
    }
    if let Some((i, t)) = triangles
        .iter()
        .enumerate()
        .find(|(_, t)| t.iter().any(|&v| v as usize >= vertices.len()))
    {
        return Err(format!(
            "triangle {i} uses vertex {t:?} but the mesh has {} vertices",
            vertices.len()
        ));
    }
    let found = shells::analyse(vertices, triangles);
    let mut parts: Vec<SolidMesh> = found
        .shells
        .iter()
        .filter(|s| s.kind == ShellKind::Closed)
        .filter_map(|s| SolidMesh::part(vertices, &s.triangles, true))
        .collect();
    let loose: Vec<[u32; 3]> = found
        .loose()
        .flat_map(|s| s.triangles.iter().copied())
        .collect();
    parts.extend(SolidMesh::part(vertices, &loose, false));
    if parts.is_empty() {
        return Err(format!("all {} triangles have zero area", triangles.len()));
    }
    Ok(parts)
}
