//! Clamp sites generated from the robot's geometry: where on a link a guide may be screwed
//! on, and which ways the cable may leave it.
//!
//! A site is a point on one of the link's own collision surfaces (boxes, cylinders, spheres,
//! capsules, STL meshes; see [`surface`]; not a body a setup attached, such as the gripper),
//! moved out along the outward surface normal by the
//! clamp's standoff — the cable radius plus the clamp height — so the cable axis runs there.
//! The sites of a link (with the links fixed to it) are picked from dense candidates on all
//! its colliders at once ([`generate`]): in order along [`SWEEP_DIRECTION`], a candidate is
//! kept unless a kept site of the same facing (normals within [`FACING_TOLERANCE_DEG`]) is
//! closer than the spacing, or its cable axis point is closer than the standoff to any
//! collider of the robot at the installation pose (inside a link, a corner, a neighbouring
//! housing; the surface point itself then lies inside no other solid). At each site the
//! cable runs parallel to the surface, in one of a few stated directions about the normal,
//! measured from the link's reference axis projected onto the surface ([`reference`]: the
//! long axis of the link's geometry unless the setup names one; its second axis where the
//! normal is within 17° of it). The guide frame's x axis is the surface normal; the twist the
//! cable really has at the clamp is derived from its route (see `setup::install`), so this x
//! axis is only a convention.

pub mod reference;
mod spacing;
pub mod surface;

use crate::pose::Pose;
use crate::robot::{Collider, Robot};
use crate::stress::contact::{Obstacles, min_clearance};
use nalgebra::{Isometry3, Point3, Rotation3, Unit, UnitQuaternion, Vector3};
use reference::{LinkGeometry, ReferenceAxes};
use spacing::SpacingGrid;

/// Most surface points one generator may keep, estimated from the surface area before any
/// is allocated.
pub const MAX_SURFACE_POINTS: usize = 100_000;
/// Most points one generator may visit before thinning (a mesh's triangles on their grids).
pub const MAX_SAMPLING_WORK: usize = 20_000_000;
/// Smallest spacing accepted (m).
pub const MIN_SPACING_M: f64 = 1e-3;
/// Two sites are of one facing when their normals are within this angle (deg); sites of one
/// facing are at least the spacing apart. 60°: on the UR5's curved housings this keeps about
/// one site per spacing² (30° gave 2.1–2.6, letting sites crowd around a tube 30° apart),
/// while the faces at a box edge (90°) stay two facings.
pub const FACING_TOLERANCE_DEG: f64 = 60.0;
const _: () = assert!(FACING_TOLERANCE_DEG > 0.0 && FACING_TOLERANCE_DEG < 90.0);
/// Candidates are taken in order of their position along this direction of the link frame
/// (ties in the order they were sampled): a sweep, which packs them about one per spacing².
pub const SWEEP_DIRECTION: [f64; 3] = [
    0.267_261_241_912_424_4,
    0.534_522_483_824_848_8,
    0.801_783_725_737_273_2,
];
/// A site may come this much closer to another collider than its standoff (m): rounding, and
/// the surface the site stands on itself.
pub const STANDOFF_SLACK_M: f64 = 1e-4;
/// Where the normal is within 17° of the reference axis (|n·a| above this, cos 17°),
/// directions are measured from the second axis instead.
pub const AXIS_PARALLEL_COSINE: f64 = 0.956_304_755_963_035_4;

/// How to generate one guide's sites on its link.
#[derive(Debug, Clone, PartialEq)]
pub struct SiteSpec {
    /// Distance between neighbouring sites on a surface (m).
    pub spacing_m: f64,
    /// Height of the clamp between the surface and the cable's outer surface (m).
    pub clamp_height_m: f64,
    /// Cable directions at each site: angles (rad) about the surface normal from the site's
    /// reference axis projected onto the surface.
    pub directions_rad: Vec<f64>,
    /// Only surface points inside this part of the link.
    pub region: Region,
    /// The reference axis named in the setup (unit, link frame); `None`: the long axis of the
    /// link's geometry (see [`reference`]).
    pub reference_axis: Option<Unit<Vector3<f64>>>,
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
    /// The axis the cable directions are measured from (unit; its projection onto the surface
    /// is direction 0°): the link's reference axis, or its second axis where the normal is
    /// within 17° of the reference.
    pub reference_axis: Unit<Vector3<f64>>,
}

/// A guide's generated sites and the spec they were made with.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneratedSites {
    /// The generator as the setup gives it.
    pub spec: SiteSpec,
    /// The sites, in the order of the guide's configurations.
    pub sites: Vec<Site>,
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

/// A surface point of one of a link's colliders that may become a site (link frame, m).
#[derive(Debug, Clone, Copy)]
struct Candidate {
    link: usize,
    collider: usize,
    point: Point3<f64>,
    normal: Unit<Vector3<f64>>,
}

/// The sites of `spec` on the colliders of `link` and of every link fixed to it, in `link`'s
/// frame, for a cable of `cable_radius_m`; `link_poses` (the installation pose) place the
/// other links for the clearance check. Same input, same sites in the same order.
pub fn generate(
    robot: &Robot,
    obstacles: &Obstacles,
    link: usize,
    spec: &SiteSpec,
    cable_radius_m: f64,
    link_poses: &[Pose],
) -> Result<Vec<Site>, SiteError> {
    check_work(robot, link, spec.spacing_m)?;
    let axes = reference_axes(robot, link, spec.reference_axis);
    let standoff = cable_radius_m + spec.clamp_height_m;
    let facing_cosine = FACING_TOLERANCE_DEG.to_radians().cos();
    let mut kept = SpacingGrid::new(spec.spacing_m, facing_cosine);
    let mut sites = Vec::new();
    let mut in_region = 0usize;
    for candidate in candidates(robot, link, spec.spacing_m) {
        if !spec.region.contains(&candidate.point) {
            continue;
        }
        in_region += 1;
        if kept.crowds(&candidate.point, &candidate.normal) {
            continue;
        }
        let position = candidate.point + standoff * candidate.normal.into_inner();
        let world = link_poses[link] * position;
        if clearance(obstacles, link_poses, &world)? < standoff - STANDOFF_SLACK_M {
            continue;
        }
        kept.insert(candidate.point, candidate.normal);
        sites.push(Site {
            link: candidate.link,
            collider: candidate.collider,
            surface_point: candidate.point,
            normal: candidate.normal,
            position,
            reference_axis: reference_at(&axes, &candidate.normal),
        });
    }
    if sites.is_empty() {
        return Err(empty(robot, link, in_region, standoff));
    }
    Ok(sites)
}

/// A collider clamps may be mounted on: one of the robot's own (not a body a setup attached,
/// such as the gripper), of `link` or a link fixed to it.
struct Surface<'r> {
    /// Index of its link.
    link: usize,
    /// Index in that link's colliders.
    index: usize,
    collider: &'r Collider,
    /// Pose of the collider's frame in `link`'s frame.
    in_link: Pose,
}

/// The mounting surfaces of `link` (see [`Surface`]).
fn mounting_surfaces(robot: &Robot, link: usize) -> Vec<Surface<'_>> {
    rigid_frames(robot, link)
        .into_iter()
        .flat_map(|(l, to_link)| {
            robot.links[l]
                .colliders
                .iter()
                .enumerate()
                .filter(|(_, c)| c.attached.is_none())
                .map(move |(index, collider)| Surface {
                    link: l,
                    index,
                    collider,
                    in_link: to_link * collider.origin,
                })
        })
        .collect()
}

/// About how many surface points a generator at `spacing_m` finds on `link` and the links
/// fixed to it: their mounting surfaces' area over the spacing squared, known before any is
/// sampled.
pub fn estimated_surface_points(robot: &Robot, link: usize, spacing_m: f64) -> f64 {
    mounting_surfaces(robot, link)
        .iter()
        .map(|s| surface::estimated_count(&s.collider.shape, spacing_m))
        .sum()
}

/// Refuses a spacing that would sample too many points, before anything is allocated.
fn check_work(robot: &Robot, link: usize, spacing_m: f64) -> Result<(), SiteError> {
    let surfaces = mounting_surfaces(robot, link);
    let colliders = || surfaces.iter().map(|s| s.collider);
    if colliders().next().is_none() {
        return Err(SiteError::Empty(format!(
            "{} has no collision shapes, nor has any link fixed to it: nothing to mount a \
             clamp on",
            robot.links[link].name
        )));
    }
    let estimated = estimated_surface_points(robot, link, spacing_m);
    if estimated > MAX_SURFACE_POINTS as f64 {
        return Err(SiteError::TooMany { estimated });
    }
    let work: f64 = colliders()
        .map(|c| surface::sampling_work(&c.shape, spacing_m))
        .sum();
    if work > MAX_SAMPLING_WORK as f64 {
        return Err(SiteError::TooMuchWork { work });
    }
    Ok(())
}

/// The surface samples of every collider of `link` and the links fixed to it, in `link`'s
/// frame, in sweep order (see [`SWEEP_DIRECTION`]).
fn candidates(robot: &Robot, link: usize, spacing_m: f64) -> Vec<Candidate> {
    let mut all = Vec::new();
    for s in mounting_surfaces(robot, link) {
        all.extend(
            surface::sample(&s.collider.shape, spacing_m)
                .into_iter()
                .map(|sample| Candidate {
                    link: s.link,
                    collider: s.index,
                    point: s.in_link * sample.point,
                    normal: Unit::new_normalize(s.in_link * sample.normal.into_inner()),
                }),
        );
    }
    let sweep = Vector3::from(SWEEP_DIRECTION);
    // A stable sort: equal keys keep the sampling order.
    all.sort_by(|a, b| {
        a.point
            .coords
            .dot(&sweep)
            .total_cmp(&b.point.coords.dot(&sweep))
    });
    all
}

/// The reference axes of `link` (with the links fixed to it), link frame: `given` or the
/// long axis of its collision geometry (see [`reference`]).
pub fn reference_axes(
    robot: &Robot,
    link: usize,
    given: Option<Unit<Vector3<f64>>>,
) -> ReferenceAxes {
    let shapes = mounting_surfaces(robot, link)
        .into_iter()
        .map(|s| (&s.collider.shape, s.in_link))
        .collect();
    LinkGeometry { shapes }.reference_axes(given)
}

/// The axis directions are measured from at a site with this outward normal: the primary
/// axis, or the second where the normal is within 17° of it.
fn reference_at(axes: &ReferenceAxes, normal: &Unit<Vector3<f64>>) -> Unit<Vector3<f64>> {
    if normal.dot(&axes.primary).abs() > AXIS_PARALLEL_COSINE {
        axes.second
    } else {
        axes.primary
    }
}

fn empty(robot: &Robot, link: usize, in_region: usize, standoff: f64) -> SiteError {
    let name = &robot.links[link].name;
    SiteError::Empty(match in_region {
        0 => format!("no collision surface of {name} lies inside the region"),
        n => format!(
            "all {n} surface points of {name} in the region are closer than the standoff \
             ({:.1} mm) to the robot at the installation pose",
            standoff * 1e3
        ),
    })
}

/// Every link fixed to `link` (itself included) with its pose in `link`'s frame.
fn rigid_frames(robot: &Robot, link: usize) -> Vec<(usize, Pose)> {
    let (_, link_in_body) = robot.moving_body(link);
    let body_to_link = link_in_body.inverse();
    robot
        .rigidly_attached(link)
        .into_iter()
        .map(|l| (l, body_to_link * robot.moving_body(l).1))
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
/// measured from the site's reference axis projected onto the surface: +z along the cable,
/// +x the normal.
pub fn site_frame(site: &Site, angle_rad: f64) -> Pose {
    let n = site.normal.into_inner();
    let axis = site.reference_axis.into_inner();
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
