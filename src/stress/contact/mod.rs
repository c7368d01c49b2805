//! Contact: the signed clearance between the cable and the robot's links.
//!
//! The discrete cable is a polyline of nodes; sub-segment `k` (node `k` → node `k + 1`) is a
//! capsule of the cable's radius. Its clearance to a link collider is the distance between the
//! two surfaces when they are apart, and minus the penetration depth when they overlap:
//!
//! `clearance = min over the points p of the sub-segment's axis of sd(p) − r`,
//!
//! with `sd` the signed distance to the collider's solid (negative inside) and `r` the cable
//! radius. Apart, this is the exact surface-to-surface distance. Overlapping, it is minus the
//! depth of the deepest cross-section of the cable: the depth of the axis point farthest
//! inside, plus `r` — the penetration of the ball of radius `r` there. (That is not the
//! minimum translation that would separate the whole capsule: a sub-segment piercing a thin
//! plate reports half the plate thickness plus `r`, not the plate's lateral extent.)
//!
//! Everything is computed in f64: closed forms per primitive (box, cylinder, sphere, capsule;
//! see `primitives`), exact segment–triangle distances for meshes with parry's BVH to cull
//! triangles. parry's own distance and contact queries are not used: in this build parry is
//! f32 (rapier3d, not rapier3d-f64) and its GJK stops at a relative tolerance of about 1e-3,
//! which gave errors up to a millimetre on 5 cm distances — too coarse against a zero-contact
//! threshold — and it treats a triangle mesh as a hollow shell (a cable deep inside reports a
//! positive distance to the surface).
//!
//! A mesh is the union of its shells' solids, whatever the file's shells, overlaps, winding
//! or holes: a part per closed shell, its inside decided by angle-weighted pseudo-normals, and
//! one for all its loose shells, decided by the winding number (see `mesh` and
//! [`crate::robot::shells`]); its signed distance is the minimum over the parts. Depth is
//! exact for convex shells and a local maximum for others.
//!
//! Each query culls with enclosing capsules of the colliders and bounding spheres of chunks of
//! the cable, nearest colliders first, so only the pairs that can still beat the best so far
//! are computed exactly; the result does not depend on the culling.
//!
//! Near each guide the cable is clamped onto the guide's own link and legitimately touches it;
//! [`ClampZone`]s exclude those sub-segments from the check against that one link.

mod mesh;
mod primitives;

pub(crate) use primitives::segment_segment_distance;
#[cfg(test)]
mod tests;

use crate::pose::Pose;
use crate::robot::{Robot, Shape};
use mesh::MeshSolid;
use nalgebra::{Point3, Vector3};
use primitives::{Projection, SegmentMin};
use std::path::PathBuf;

/// Why obstacles cannot be built or a clearance query cannot be answered.
#[derive(Debug, thiserror::Error)]
pub enum ContactError {
    /// A mesh collider with no usable triangle or with invalid indices or vertices.
    #[error("link '{link}', <collision> #{collider}: degenerate mesh {}: {problem}", file.display())]
    DegenerateMesh {
        /// Link name.
        link: String,
        /// 1-based number of the collider within the link (as in the URDF).
        collider: usize,
        /// The mesh file.
        file: PathBuf,
        /// What is wrong.
        problem: String,
    },
    /// A primitive collider with a non-finite or non-positive dimension or origin.
    #[error("link '{link}', <collision> #{collider}: {problem}")]
    InvalidShape {
        /// Link name.
        link: String,
        /// 1-based number of the collider within the link (as in the URDF).
        collider: usize,
        /// What is wrong.
        problem: String,
    },
    /// The link poses do not match the robot the obstacles were built from.
    #[error("{got} link poses given, the robot has {expected} links")]
    PoseCount {
        /// Number of links.
        expected: usize,
        /// Number of poses given.
        got: usize,
    },
    /// A link pose with a NaN or infinite value.
    #[error("the pose of link {link} is not finite")]
    NonFinitePose {
        /// Index of the link.
        link: usize,
    },
    /// A link index (in a clamp zone or a link subset) beyond the robot's links.
    #[error("link index {link} is out of range: the robot has {count} links")]
    LinkIndex {
        /// The index given.
        link: usize,
        /// Number of links.
        count: usize,
    },
    /// A cable node with a NaN or infinite coordinate.
    #[error("cable node {index} is not finite: ({}, {}, {})", node.x, node.y, node.z)]
    NonFiniteNode {
        /// Node index.
        index: usize,
        /// Its coordinates (m).
        node: Point3<f64>,
    },
    /// A negative or non-finite cable radius.
    #[error("cable radius {0} m must be finite and ≥ 0")]
    Radius(f64),
}

/// A collider shape in its own frame, ready for exact distance queries (metres).
#[derive(Debug, Clone)]
enum Geometry {
    Sphere { radius: f64 },
    Capsule { radius: f64, half_length: f64 },
    Cuboid { half: Vector3<f64> },
    Cylinder { radius: f64, half_length: f64 },
    Mesh(Box<MeshSolid>),
}

impl Geometry {
    /// Minimum of `sd` along `a → b`; exact when at most `cutoff` (m), otherwise possibly
    /// only known to be above it (meshes stop early).
    fn segment_min(&self, a: &Point3<f64>, b: &Point3<f64>, cutoff: f64) -> SegmentMin {
        match self {
            Geometry::Sphere { radius } => primitives::sphere_segment(*radius, a, b),
            Geometry::Capsule {
                radius,
                half_length,
            } => primitives::capsule_segment(*radius, *half_length, a, b),
            Geometry::Cuboid { half } => primitives::box_segment(half, a, b),
            Geometry::Cylinder {
                radius,
                half_length,
            } => primitives::cylinder_segment(*radius, *half_length, a, b),
            Geometry::Mesh(mesh) => mesh.segment_min(a, b, cutoff),
        }
    }

    /// Projection of `p`; `inside` (known from the segment query) decides a mesh's side.
    fn project(&self, p: &Point3<f64>, inside: bool) -> Projection {
        match self {
            Geometry::Sphere { radius } => primitives::sphere_project(*radius, p),
            Geometry::Capsule {
                radius,
                half_length,
            } => primitives::capsule_project(*radius, *half_length, p),
            Geometry::Cuboid { half } => primitives::box_project(half, p),
            Geometry::Cylinder {
                radius,
                half_length,
            } => primitives::cylinder_project(*radius, *half_length, p),
            Geometry::Mesh(mesh) => mesh.project(p, inside),
        }
    }
}

/// A capsule enclosing a collider, in the collider's frame: a cheap lower bound on distance.
#[derive(Debug, Clone, Copy)]
struct Bound {
    from: Point3<f64>,
    to: Point3<f64>,
    radius: f64,
}

impl Bound {
    /// The capsule around the segment ±`half` along axis `axis` containing the shape.
    fn along(axis: usize, centre: Vector3<f64>, half: f64, radius: f64) -> Bound {
        let mut d = Vector3::zeros();
        d[axis] = half;
        Bound {
            from: Point3::from(centre - d),
            to: Point3::from(centre + d),
            radius,
        }
    }

    fn of(geometry: &Geometry) -> Bound {
        let origin = Vector3::zeros();
        match geometry {
            Geometry::Sphere { radius } => Bound::along(2, origin, 0.0, *radius),
            Geometry::Capsule {
                radius,
                half_length,
            }
            | Geometry::Cylinder {
                radius,
                half_length,
            } => Bound::along(2, origin, *half_length, *radius),
            Geometry::Cuboid { half } => {
                let axis = half.imax();
                let (j, k) = ((axis + 1) % 3, (axis + 2) % 3);
                Bound::along(axis, origin, half[axis], half[j].hypot(half[k]))
            }
            Geometry::Mesh(mesh) => {
                let vertices = mesh.vertices();
                let (lo, hi) = vertices.iter().fold(
                    (
                        Vector3::repeat(f64::INFINITY),
                        Vector3::repeat(f64::NEG_INFINITY),
                    ),
                    |(lo, hi), p| (lo.inf(&p.coords), hi.sup(&p.coords)),
                );
                let extent = hi - lo;
                let axis = extent.imax();
                let centre = 0.5 * (lo + hi);
                let mut bound = Bound::along(axis, centre, 0.5 * extent[axis], 0.0);
                let d = bound.to - bound.from;
                bound.radius = vertices
                    .iter()
                    .map(|p| {
                        let t = primitives::closest_t_on_segment(p, &bound.from, &d);
                        (p - (bound.from + d * t)).norm()
                    })
                    .fold(0.0, f64::max);
                bound
            }
        }
    }
}

/// One link collider prepared for clearance queries.
#[derive(Debug, Clone)]
struct Obstacle {
    link: usize,
    /// 0-based index into the link's colliders.
    collider: usize,
    /// The collider frame in the link frame.
    origin: Pose,
    geometry: Geometry,
    bound: Bound,
}

/// The robot's collision geometry prepared once (f64 shapes, mesh BVHs) for many clearance
/// queries at different poses.
#[derive(Debug, Clone)]
pub struct Obstacles {
    /// Ordered by link, then by collider within the link.
    obstacles: Vec<Obstacle>,
    link_count: usize,
}

impl Obstacles {
    /// Converts every collider of every link.
    ///
    /// Refused, naming the link and the collider: non-finite origins or dimensions, and meshes
    /// with invalid indices, non-finite vertices or no triangle of non-zero area. A mesh is the
    /// union of its closed shells and its loose shells (see the module documentation).
    pub fn from_robot(robot: &Robot) -> Result<Obstacles, ContactError> {
        let mut obstacles = Vec::new();
        for (li, link) in robot.links.iter().enumerate() {
            for (ci, collider) in link.colliders.iter().enumerate() {
                let invalid = |problem: String| ContactError::InvalidShape {
                    link: link.name.clone(),
                    collider: ci + 1,
                    problem,
                };
                let o = &collider.origin;
                if !(o.translation.vector.iter().all(|v| v.is_finite())
                    && o.rotation.coords.iter().all(|v| v.is_finite()))
                {
                    return Err(invalid("the origin is not finite".into()));
                }
                let geometry =
                    geometry_of(&collider.shape).map_err(|problem| match &collider.shape {
                        Shape::Mesh(mesh) => ContactError::DegenerateMesh {
                            link: link.name.clone(),
                            collider: ci + 1,
                            file: mesh.file.clone(),
                            problem,
                        },
                        _ => invalid(problem),
                    })?;
                obstacles.push(Obstacle {
                    link: li,
                    collider: ci,
                    origin: collider.origin,
                    bound: Bound::of(&geometry),
                    geometry,
                });
            }
        }
        Ok(Obstacles {
            obstacles,
            link_count: robot.links.len(),
        })
    }

    /// Number of links of the robot (the length `link_poses` must have).
    pub fn link_count(&self) -> usize {
        self.link_count
    }

    /// Number of colliders over all links.
    pub fn collider_count(&self) -> usize {
        self.obstacles.len()
    }

    /// `(link, collider)` of every mesh with loose shells (open edges, edges of more than
    /// two triangles, self-crossing), whose inside there is decided by the winding number.
    pub fn winding_meshes(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.obstacles.iter().filter_map(|ob| match &ob.geometry {
            Geometry::Mesh(mesh) if mesh.has_loose_part() => Some((ob.link, ob.collider)),
            _ => None,
        })
    }
}

fn geometry_of(shape: &Shape) -> Result<Geometry, String> {
    let check = |what: &str, values: &[f64], allow_zero: bool| {
        if values
            .iter()
            .all(|v| v.is_finite() && (*v > 0.0 || allow_zero && *v == 0.0))
        {
            Ok(())
        } else {
            Err(format!("{what} {values:?} must be finite and > 0"))
        }
    };
    Ok(match shape {
        Shape::Box { half_extents_m } => {
            check("box half extents", half_extents_m.as_slice(), false)?;
            Geometry::Cuboid {
                half: *half_extents_m,
            }
        }
        Shape::Cylinder { radius_m, length_m } => {
            check("cylinder radius/length", &[*radius_m, *length_m], false)?;
            Geometry::Cylinder {
                radius: *radius_m,
                half_length: 0.5 * length_m,
            }
        }
        Shape::Sphere { radius_m } => {
            check("sphere radius", &[*radius_m], false)?;
            Geometry::Sphere { radius: *radius_m }
        }
        Shape::Capsule { radius_m, length_m } => {
            check("capsule radius", &[*radius_m], false)?;
            check("capsule length", &[*length_m], true)?;
            Geometry::Capsule {
                radius: *radius_m,
                half_length: 0.5 * length_m,
            }
        }
        Shape::Mesh(mesh) => {
            Geometry::Mesh(Box::new(MeshSolid::new(&mesh.vertices, &mesh.triangles)?))
        }
    })
}

/// Which end of the cable segment a guide sits at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GuideEnd {
    /// The start guide, at node 0.
    Start,
    /// The end guide, at the last node.
    End,
}

/// Where a guide clamps the cable onto its own link: near it, contact with that link is
/// expected and not checked.
///
/// The zone is a stretch of the cable's material — its first `sub_segments` sub-segments
/// counted from the guide — not a distance along its current shape: a zone measured along
/// the shape would gain or lose a sub-segment whenever the cable stretches or shortens by a
/// hair, and the clearance would jump with it. Sub-segments in the zone are not checked
/// against `link`, but still against every other link.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ClampZone {
    /// The guide's end of the segment.
    pub end: GuideEnd,
    /// Index into `robot.links` of the link the guide is screwed onto.
    pub link: usize,
    /// Sub-segments from the guide not checked against `link`.
    pub sub_segments: usize,
}

/// Slack on clamp-zone lengths (m) so that a zone of exactly `n` pitches covers `n`
/// sub-segments despite rounding.
const CLAMP_SLACK_M: f64 = 1e-9;

impl ClampZone {
    /// The zone of the first `length_m` of cable from the guide, for sub-segments of natural
    /// length `pitch_m`: sub-segment `k` (counted from the guide) is in it when its near end
    /// lies less than `length_m` of cable from the guide, `k·pitch_m < length_m` (with 1 nm of
    /// slack, so a zone of `n` pitches covers exactly `n` sub-segments). A length that is not
    /// positive (or NaN) gives an empty zone.
    pub fn of_length(end: GuideEnd, link: usize, length_m: f64, pitch_m: f64) -> ClampZone {
        let count = ((length_m - CLAMP_SLACK_M) / pitch_m).ceil();
        ClampZone {
            end,
            link,
            // `as` saturates: NaN and negative counts give 0, an infinite one every
            // sub-segment.
            sub_segments: count.max(0.0) as usize,
        }
    }
}

/// The closest approach of a cable shape to the robot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearance {
    /// Signed clearance (m): the surface distance when apart, minus the penetration depth of
    /// the deepest cable cross-section when overlapping (see the module documentation).
    pub clearance_m: f64,
    /// Index into `robot.links`.
    pub link: usize,
    /// Index into that link's `colliders`.
    pub collider: usize,
    /// The sub-segment `k` (node `k` → node `k + 1`).
    pub sub_segment: usize,
    /// Where along the sub-segment's axis the closest approach is, in [0, 1] from node `k`.
    pub segment_parameter: f64,
    /// The cable surface point closest to (or deepest in) the link (world frame, m).
    pub point_on_cable: Point3<f64>,
    /// The nearest link surface point (world frame, m); `point_on_link − point_on_cable` has
    /// length `|clearance_m|`.
    pub point_on_link: Point3<f64>,
    /// Unit outward normal of the link surface at `point_on_link` (world frame).
    pub normal: Vector3<f64>,
}

/// The lowest signed clearance between the cable and every link collider, clamp zones
/// excluded; `None` when nothing is checked (fewer than two nodes, or no collider outside the
/// clamp zones).
///
/// `link_poses` are the world poses of the links (as from [`Robot::link_poses`]), `nodes` the
/// cable's nodes in the world frame (m), `cable_radius_m` its radius (m). Ties go to the lowest
/// sub-segment, then the lowest link, then the lowest collider.
pub fn min_clearance(
    obstacles: &Obstacles,
    link_poses: &[Pose],
    nodes: &[Point3<f64>],
    cable_radius_m: f64,
    clamp_zones: &[ClampZone],
) -> Result<Option<Clearance>, ContactError> {
    search(
        obstacles,
        link_poses,
        nodes,
        cable_radius_m,
        clamp_zones,
        None,
    )
}

/// Like [`min_clearance`], checking only the links listed in `links` (indices into
/// `robot.links`, in any order) — e.g. a segment's own link and its neighbours.
pub fn min_clearance_to_links(
    obstacles: &Obstacles,
    link_poses: &[Pose],
    nodes: &[Point3<f64>],
    cable_radius_m: f64,
    clamp_zones: &[ClampZone],
    links: &[usize],
) -> Result<Option<Clearance>, ContactError> {
    if let Some(&link) = links.iter().find(|&&l| l >= obstacles.link_count) {
        return Err(ContactError::LinkIndex {
            link,
            count: obstacles.link_count,
        });
    }
    search(
        obstacles,
        link_poses,
        nodes,
        cable_radius_m,
        clamp_zones,
        Some(links),
    )
}

/// The best pair so far, ordered by (clearance, sub-segment, obstacle index): obstacles are
/// sorted by link and collider, so this is the documented tie-break.
#[derive(Clone, Copy)]
struct Best {
    clearance: f64,
    sub_segment: usize,
    obstacle: usize,
    t: f64,
}

impl Best {
    fn beaten_by(&self, clearance: f64, sub_segment: usize, obstacle: usize) -> bool {
        clearance < self.clearance
            || clearance == self.clearance
                && (sub_segment, obstacle) < (self.sub_segment, self.obstacle)
    }
}

fn validate(
    obstacles: &Obstacles,
    link_poses: &[Pose],
    nodes: &[Point3<f64>],
    cable_radius_m: f64,
    clamp_zones: &[ClampZone],
) -> Result<(), ContactError> {
    if link_poses.len() != obstacles.link_count {
        return Err(ContactError::PoseCount {
            expected: obstacles.link_count,
            got: link_poses.len(),
        });
    }
    if let Some(link) = link_poses.iter().position(|p| {
        !(p.translation.vector.iter().all(|v| v.is_finite())
            && p.rotation.coords.iter().all(|v| v.is_finite()))
    }) {
        return Err(ContactError::NonFinitePose { link });
    }
    if let Some(index) = nodes.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(ContactError::NonFiniteNode {
            index,
            node: nodes[index],
        });
    }
    if !(cable_radius_m.is_finite() && cable_radius_m >= 0.0) {
        return Err(ContactError::Radius(cable_radius_m));
    }
    for zone in clamp_zones {
        if zone.link >= obstacles.link_count {
            return Err(ContactError::LinkIndex {
                link: zone.link,
                count: obstacles.link_count,
            });
        }
    }
    Ok(())
}

/// The cable is culled in chunks of consecutive sub-segments, at most this many chunks.
const MAX_CHUNKS: usize = 16;

/// Obstacles handled without a heap allocation (more fall back to a `Vec`).
const INLINE_OBSTACLES: usize = 32;

/// An obstacle to check, with its bounding capsule in the world frame.
#[derive(Clone, Copy)]
struct Candidate {
    /// Lower bound on its clearance to any chunk of the cable (m).
    lower: f64,
    /// Index into `Obstacles::obstacles`.
    index: usize,
    /// Collider frame in the world.
    world: Pose,
    /// Bounding capsule axis start and direction (world) and radius plus cable radius.
    from: Point3<f64>,
    axis: Vector3<f64>,
    reach: f64,
    /// Sub-segments `first..last` are outside this link's clamp zones.
    first: usize,
    last: usize,
}

impl Candidate {
    fn empty() -> Candidate {
        Candidate {
            lower: 0.0,
            index: 0,
            world: Pose::identity(),
            from: Point3::new(0.0, 0.0, 0.0),
            axis: Vector3::new(0.0, 0.0, 0.0),
            reach: 0.0,
            first: 0,
            last: 0,
        }
    }
}

/// Distance from `p` to the segment `from + t·axis`, t ∈ [0, 1].
fn point_segment_distance(p: &Point3<f64>, from: &Point3<f64>, axis: &Vector3<f64>) -> f64 {
    let t = primitives::closest_t_on_segment(p, from, axis);
    (p - (from + axis * t)).norm()
}

fn search(
    obstacles: &Obstacles,
    link_poses: &[Pose],
    nodes: &[Point3<f64>],
    radius: f64,
    clamp_zones: &[ClampZone],
    links: Option<&[usize]>,
) -> Result<Option<Clearance>, ContactError> {
    validate(obstacles, link_poses, nodes, radius, clamp_zones)?;
    if nodes.len() < 2 {
        return Ok(None);
    }
    let sub_segments = nodes.len() - 1;

    // Bounding spheres of chunks of consecutive sub-segments.
    let chunk_len = sub_segments.div_ceil(MAX_CHUNKS);
    let chunk_count = sub_segments.div_ceil(chunk_len);
    let chunk_range = |c: usize| c * chunk_len..((c + 1) * chunk_len).min(sub_segments);
    let mut spheres = [(Point3::origin(), 0.0); MAX_CHUNKS];
    for (c, sphere) in spheres.iter_mut().enumerate().take(chunk_count) {
        let range = chunk_range(c);
        let chunk = &nodes[range.start..=range.end];
        let (lo, hi) = chunk.iter().fold(
            (
                Vector3::repeat(f64::INFINITY),
                Vector3::repeat(f64::NEG_INFINITY),
            ),
            |(lo, hi), p| (lo.inf(&p.coords), hi.sup(&p.coords)),
        );
        let centre = Point3::from(0.5 * (lo + hi));
        let r = chunk
            .iter()
            .map(|p| (p - centre).norm())
            .fold(0.0, f64::max);
        *sphere = (centre, r);
    }
    let spheres = &spheres[..chunk_count];

    // The obstacles to check, nearest (by lower bound) first.
    let mut inline = [Candidate::empty(); INLINE_OBSTACLES];
    let mut heap = Vec::new();
    let buffer: &mut [Candidate] = if obstacles.obstacles.len() <= INLINE_OBSTACLES {
        &mut inline
    } else {
        heap.resize(obstacles.obstacles.len(), Candidate::empty());
        &mut heap
    };
    let mut count = 0;
    for (index, ob) in obstacles.obstacles.iter().enumerate() {
        if links.is_some_and(|l| !l.contains(&ob.link)) {
            continue;
        }
        let (mut skip_start, mut skip_end) = (0, 0);
        for zone in clamp_zones.iter().filter(|z| z.link == ob.link) {
            let n = zone.sub_segments.min(sub_segments);
            match zone.end {
                GuideEnd::Start => skip_start = skip_start.max(n),
                GuideEnd::End => skip_end = skip_end.max(n),
            }
        }
        if skip_start + skip_end >= sub_segments {
            continue;
        }
        let world = link_poses[ob.link] * ob.origin;
        let from = world * ob.bound.from;
        let axis = world * ob.bound.to - from;
        let reach = ob.bound.radius + radius;
        let lower = spheres
            .iter()
            .map(|(centre, r)| point_segment_distance(centre, &from, &axis) - r)
            .fold(f64::INFINITY, f64::min)
            - reach;
        buffer[count] = Candidate {
            lower,
            index,
            world,
            from,
            axis,
            reach,
            first: skip_start,
            last: sub_segments - skip_end,
        };
        count += 1;
    }
    let candidates = &mut buffer[..count];
    candidates.sort_unstable_by(|a, b| a.lower.total_cmp(&b.lower).then(a.index.cmp(&b.index)));

    let mut best: Option<Best> = None;
    let best_clearance = |best: &Option<Best>| best.map_or(f64::INFINITY, |b| b.clearance);
    for cand in candidates.iter() {
        // Sorted by lower bound: nothing after this can do better.
        if cand.lower > best_clearance(&best) {
            break;
        }
        let geometry = &obstacles.obstacles[cand.index].geometry;
        let inverse = cand.world.inverse();
        for (c, (centre, r)) in spheres.iter().enumerate() {
            let range = chunk_range(c);
            let (first, last) = (range.start.max(cand.first), range.end.min(cand.last));
            if first >= last
                || point_segment_distance(centre, &cand.from, &cand.axis) - r - cand.reach
                    > best_clearance(&best)
            {
                continue;
            }
            for k in first..last {
                let (a, b) = (&nodes[k], &nodes[k + 1]);
                let lower =
                    segment_segment_distance(a, &(b - a), &cand.from, &cand.axis) - cand.reach;
                if lower > best_clearance(&best) {
                    continue;
                }
                let cutoff = best_clearance(&best) + radius;
                let found = geometry.segment_min(&(inverse * a), &(inverse * b), cutoff);
                let clearance = found.sd - radius;
                if best.is_none_or(|b| b.beaten_by(clearance, k, cand.index)) {
                    best = Some(Best {
                        clearance,
                        sub_segment: k,
                        obstacle: cand.index,
                        t: found.t,
                    });
                }
            }
        }
    }
    Ok(best.map(|best| describe(obstacles, link_poses, nodes, radius, &best)))
}

/// The points and normal of the winning pair, in the world frame.
fn describe(
    obstacles: &Obstacles,
    link_poses: &[Pose],
    nodes: &[Point3<f64>],
    radius: f64,
    best: &Best,
) -> Clearance {
    let ob = &obstacles.obstacles[best.obstacle];
    let world = link_poses[ob.link] * ob.origin;
    let (a, b) = (nodes[best.sub_segment], nodes[best.sub_segment + 1]);
    let axis_point = a + (b - a) * best.t;
    let local = world.inverse() * axis_point;
    let projection = ob.geometry.project(&local, best.clearance + radius < 0.0);
    let normal = world.rotation * projection.n;
    Clearance {
        clearance_m: best.clearance,
        link: ob.link,
        collider: ob.collider,
        sub_segment: best.sub_segment,
        segment_parameter: best.t,
        point_on_cable: axis_point - normal * radius,
        point_on_link: world * projection.q,
        normal,
    }
}
