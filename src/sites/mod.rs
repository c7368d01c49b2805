//! Clamp sites generated from the robot's geometry: where on a link a guide may be screwed
//! on, and which ways the cable may leave it.
//!
//! A site is a point on one of the link's collision surfaces (boxes, cylinders, spheres,
//! capsules, STL meshes; see [`surface`]), moved out along the surface normal by the clamp's
//! standoff — the cable radius plus the clamp height — so the cable axis runs there. Sites
//! closer than that standoff to any other collider of the robot at the installation pose are
//! dropped (a corner, a neighbouring housing). At each site the cable runs parallel to the
//! surface, in one of a few stated directions about the normal, measured from the link's z
//! axis projected onto the surface (its x axis where the normal is within 17° of z). The
//! guide frame's x axis is the surface normal; the twist the cable really has at the clamp is
//! derived from its route (see `setup::install`), so this x axis is only a convention.

pub mod surface;

use crate::pose::Pose;
use crate::robot::Robot;
use crate::stress::contact::{Obstacles, min_clearance};
use nalgebra::{Isometry3, Point3, Rotation3, Unit, UnitQuaternion, Vector3};

/// Most surface points one generator may keep, estimated from the surface area before any
/// is allocated.
pub const MAX_SURFACE_POINTS: usize = 100_000;
/// Most points one generator may visit before thinning (a mesh's triangles on their grids).
pub const MAX_SAMPLING_WORK: usize = 20_000_000;
/// Smallest spacing accepted (m).
pub const MIN_SPACING_M: f64 = 1e-3;
/// A site may come this much closer to another collider than its standoff (m): rounding, and
/// the surface the site stands on itself.
const STANDOFF_SLACK_M: f64 = 1e-4;
/// Where the normal is within this of the link's z axis (|n·z| above it), directions are
/// measured from x instead: cos 17°.
const AXIS_PARALLEL_COSINE: f64 = 0.956;

/// How to generate one guide's sites on its link.
#[derive(Debug, Clone, PartialEq)]
pub struct SiteSpec {
    /// Distance between neighbouring sites on a surface (m).
    pub spacing_m: f64,
    /// Height of the clamp between the surface and the cable's outer surface (m).
    pub clamp_height_m: f64,
    /// Cable directions at each site: angles (rad) about the surface normal from the link's z
    /// axis projected onto the surface.
    pub directions_rad: Vec<f64>,
    /// Only surface points inside this part of the link.
    pub region: Region,
}

/// The part of a link where sites are generated (link frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Region {
    /// The whole link.
    Everywhere,
    /// An axis-aligned box (m).
    Box {
        /// Lowest corner.
        min_m: Point3<f64>,
        /// Highest corner.
        max_m: Point3<f64>,
    },
    /// A range of the link's z coordinate (m), e.g. a stretch of a forearm tube.
    AlongZ {
        /// Lowest z.
        min_m: f64,
        /// Highest z.
        max_m: f64,
    },
}

impl Region {
    fn contains(&self, p: &Point3<f64>) -> bool {
        match self {
            Region::Everywhere => true,
            Region::Box { min_m, max_m } => (0..3).all(|k| min_m[k] <= p[k] && p[k] <= max_m[k]),
            Region::AlongZ { min_m, max_m } => *min_m <= p.z && p.z <= *max_m,
        }
    }
}

/// One generated clamp site (link frame, m).
#[derive(Debug, Clone, PartialEq)]
pub struct Site {
    /// Index of the link whose collider the site stands on.
    pub link: usize,
    /// Index of the collider in that link's list.
    pub collider: usize,
    /// The surface point under the clamp.
    pub surface_point: Point3<f64>,
    /// Outward surface normal there.
    pub normal: Unit<Vector3<f64>>,
    /// Where the cable axis runs: the surface point moved out by the standoff.
    pub position: Point3<f64>,
}

/// Why no sites could be generated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SiteError {
    /// The spacing would give more surface points than [`MAX_SURFACE_POINTS`].
    #[error(
        "about {estimated:.0} surface points at this spacing (at most {MAX_SURFACE_POINTS}): \
         raise spacing_mm"
    )]
    TooMany {
        /// The estimated count.
        estimated: f64,
    },
    /// The link's meshes would need more than [`MAX_SAMPLING_WORK`] grid points at this
    /// spacing (long thin triangles).
    #[error(
        "sampling the meshes at this spacing visits about {work:.0} points (at most \
         {MAX_SAMPLING_WORK}): raise spacing_mm"
    )]
    TooMuchWork {
        /// The grid points counted.
        work: f64,
    },
    /// No collider of the link, or none inside the region, or every site too close to the
    /// robot.
    #[error("{0}")]
    Empty(String),
    /// The robot's collision geometry cannot be queried.
    #[error("the robot's collision geometry: {0}")]
    Geometry(String),
}

/// The sites of `spec` on the colliders of `link` and of every link fixed to it, in `link`'s
/// frame, for a cable of `cable_radius_m`; `link_poses` (the installation pose) place the
/// other links for the clearance check.
pub fn generate(
    robot: &Robot,
    obstacles: &Obstacles,
    link: usize,
    spec: &SiteSpec,
    cable_radius_m: f64,
    link_poses: &[Pose],
) -> Result<Vec<Site>, SiteError> {
    let rigid = rigidly_attached(robot, link);
    let colliders = || rigid.iter().flat_map(|&l| &robot.links[l].colliders);
    let total = |measure: fn(&crate::robot::Shape, f64) -> f64| -> f64 {
        colliders().map(|c| measure(&c.shape, spec.spacing_m)).sum()
    };
    if colliders().next().is_none() {
        return Err(SiteError::Empty(format!(
            "{} has no collision shapes, nor has any link fixed to it: nothing to mount a \
             clamp on",
            robot.links[link].name
        )));
    }
    let estimated = total(surface::estimated_count);
    if estimated > MAX_SURFACE_POINTS as f64 {
        return Err(SiteError::TooMany { estimated });
    }
    let work = total(surface::sampling_work);
    if work > MAX_SAMPLING_WORK as f64 {
        return Err(SiteError::TooMuchWork { work });
    }
    let standoff = cable_radius_m + spec.clamp_height_m;
    let link_in_world = link_poses[link];
    let mut sites = Vec::new();
    let mut in_region = 0usize;
    for &l in &rigid {
        let to_link = link_in_world.inverse() * link_poses[l];
        for (c, collider) in robot.links[l].colliders.iter().enumerate() {
            let shape_in_link = to_link * collider.origin;
            for sample in surface::sample(&collider.shape, spec.spacing_m) {
                let surface_point = shape_in_link * sample.point;
                if !spec.region.contains(&surface_point) {
                    continue;
                }
                in_region += 1;
                let normal = Unit::new_normalize(shape_in_link * sample.normal.into_inner());
                let position = surface_point + standoff * normal.into_inner();
                let world = link_in_world * position;
                if clearance(obstacles, link_poses, &world)? >= standoff - STANDOFF_SLACK_M {
                    sites.push(Site {
                        link: l,
                        collider: c,
                        surface_point,
                        normal,
                        position,
                    });
                }
            }
        }
    }
    if sites.is_empty() {
        let name = &robot.links[link].name;
        return Err(SiteError::Empty(match in_region {
            0 => format!("no collision surface of {name} lies inside the region"),
            n => format!(
                "all {n} surface points of {name} in the region are closer than the standoff \
                 ({:.1} mm) to the robot at the installation pose",
                standoff * 1e3
            ),
        }));
    }
    Ok(sites)
}

/// `link` and the links joined to it through fixed joints (parents and children).
fn rigidly_attached(robot: &Robot, link: usize) -> Vec<usize> {
    let root = robot.moving_body(link).0;
    (0..robot.links.len())
        .filter(|&l| robot.moving_body(l).0 == root)
        .collect()
}

/// Distance (m) from a world point to the nearest collider of the robot.
fn clearance(
    obstacles: &Obstacles,
    link_poses: &[Pose],
    point: &Point3<f64>,
) -> Result<f64, SiteError> {
    let nodes = [*point, *point];
    let nearest = min_clearance(obstacles, link_poses, &nodes, 0.0, &[])
        .map_err(|e| SiteError::Geometry(e.to_string()))?;
    Ok(nearest.map_or(f64::INFINITY, |c| c.clearance_m))
}

/// The guide frame at `site` for the cable direction `angle_rad` about the surface normal,
/// measured from the link's z axis projected onto the surface: +z along the cable, +x the
/// normal.
pub fn site_frame(site: &Site, angle_rad: f64) -> Pose {
    let n = site.normal.into_inner();
    let axis = if n.z.abs() > AXIS_PARALLEL_COSINE {
        Vector3::x()
    } else {
        Vector3::z()
    };
    let reference = (axis - axis.dot(&n) * n).normalize();
    let sideways = n.cross(&reference);
    let z = angle_rad.cos() * reference + angle_rad.sin() * sideways;
    let y = z.cross(&n);
    let rotation = Rotation3::from_basis_unchecked(&[n, y, z]);
    Isometry3::from_parts(
        site.position.coords.into(),
        UnitQuaternion::from_rotation_matrix(&rotation),
    )
}
