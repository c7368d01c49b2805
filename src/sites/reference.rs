//! The axis cable directions are measured from: the long axis of a link's collision geometry.
//!
//! The geometry is the surface of every collider of the link and of the links fixed to it, in
//! the link's frame. Its spread along a direction is the area-weighted variance of the surface
//! about its centroid; the principal axes are the eigenvectors of that covariance (exact
//! closed forms for boxes, cylinders, spheres and capsules, per triangle for meshes). The
//! reference axis is
//!
//! 1. the axis of largest spread, when its spread is at least [`DISTINCT_SPREAD_RATIO`] times
//!    the next one's (a forearm, a wrist housing);
//! 2. else the axis of smallest spread, when the middle spread is at least that ratio times
//!    it (a flat, disc-like link such as a flange: the disc's axis);
//! 3. else the link's z axis (a cube, a ball).
//!
//! A principal axis points from the link frame's origin toward the centroid (its sign is
//! otherwise arbitrary); when the centroid lies within [`CENTROID_SIGN_FRACTION`] of the
//! geometry's extent along the axis from the origin, the axis's largest link-frame component is
//! made positive instead. The second axis, used where the surface normal is within 17° of the
//! reference, is the direction of largest spread across the reference (the principal axis of
//! the covariance projected onto the plane perpendicular to it, same sign rule) when that
//! spread is at least the ratio times the other; else the link axis (x, y, z in that order)
//! most nearly perpendicular to the reference, projected onto that plane.

use crate::pose::Pose;
use crate::robot::Shape;
use nalgebra::{Matrix3, SymmetricEigen, Unit, Vector3};
use std::f64::consts::PI;

/// A spread counts as distinct when it is at least this many times the next one (variances,
/// i.e. 1.1× in standard deviation).
pub const DISTINCT_SPREAD_RATIO: f64 = 1.2;
/// A centroid this close to the origin along an axis (as a fraction of the geometry's extent
/// along it) does not decide the axis's sign.
pub const CENTROID_SIGN_FRACTION: f64 = 0.01;

/// Which rule gave a link's reference axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisRule {
    /// The principal axis of largest spread.
    LongAxis,
    /// The principal axis of smallest spread of a flat link.
    DiscAxis,
    /// No distinct principal axis: the link's z axis.
    LinkZ,
    /// Named in the setup (`reference_axis`).
    Given,
}

impl AxisRule {
    /// The rule's name as `cable-dict sites --json` writes it.
    pub fn name(self) -> &'static str {
        match self {
            AxisRule::LongAxis => "long axis",
            AxisRule::DiscAxis => "disc axis",
            AxisRule::LinkZ => "link z",
            AxisRule::Given => "setup",
        }
    }
}

/// The axes a link's cable directions are measured from (link frame, unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceAxes {
    /// The reference axis.
    pub primary: Unit<Vector3<f64>>,
    /// Perpendicular to `primary`: used where the surface normal is nearly parallel to it.
    pub second: Unit<Vector3<f64>>,
    /// How `primary` was chosen.
    pub rule: AxisRule,
}

/// Area-weighted moments of a surface: its area, `∫ x dA` and `∫ x xᵀ dA` (m², m³, m⁴).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceMoments {
    area_m2: f64,
    first: Vector3<f64>,
    second: Matrix3<f64>,
}

impl Default for SurfaceMoments {
    fn default() -> Self {
        SurfaceMoments {
            area_m2: 0.0,
            first: Vector3::zeros(),
            second: Matrix3::zeros(),
        }
    }
}

impl SurfaceMoments {
    /// A patch of `area_m2` centred at `centre` whose points vary about it by `variance`
    /// along the frame's axes, uncorrelated.
    fn patch(area_m2: f64, centre: Vector3<f64>, variance: Vector3<f64>) -> Self {
        SurfaceMoments {
            area_m2,
            first: area_m2 * centre,
            second: area_m2 * (centre * centre.transpose() + Matrix3::from_diagonal(&variance)),
        }
    }

    /// The moments of a shape's whole surface in its own frame.
    pub fn of_shape(shape: &Shape) -> Self {
        match shape {
            Shape::Box { half_extents_m: h } => box_moments(h),
            Shape::Cylinder { radius_m, length_m } => {
                let half = 0.5 * length_m;
                side_moments(*radius_m, half)
                    + disc_moments(*radius_m, half)
                    + disc_moments(*radius_m, -half)
            }
            Shape::Sphere { radius_m } => {
                let r2 = radius_m * radius_m;
                Self::patch(4.0 * PI * r2, Vector3::zeros(), Vector3::repeat(r2 / 3.0))
            }
            Shape::Capsule { radius_m, length_m } => {
                let half = 0.5 * length_m;
                side_moments(*radius_m, half)
                    + hemisphere_moments(*radius_m, half, 1.0)
                    + hemisphere_moments(*radius_m, -half, -1.0)
            }
            Shape::Mesh(mesh) => super::surface::mesh_triangles(mesh)
                .map(|[a, b, c]| triangle_moments(&a.coords, &b.coords, &c.coords))
                .fold(Self::default(), |sum, m| sum + m),
        }
    }

    /// The same surface seen from a frame in which its own frame is at `pose`.
    pub fn transformed(&self, pose: &Pose) -> Self {
        let r = pose.rotation.to_rotation_matrix().into_inner();
        let t = pose.translation.vector;
        let first = r * self.first;
        SurfaceMoments {
            area_m2: self.area_m2,
            first: first + self.area_m2 * t,
            second: r * self.second * r.transpose()
                + first * t.transpose()
                + t * first.transpose()
                + self.area_m2 * t * t.transpose(),
        }
    }

    /// The surface's area (m²).
    pub fn area_m2(&self) -> f64 {
        self.area_m2
    }

    /// The area-weighted mean of the surface points (m).
    pub fn centroid(&self) -> Vector3<f64> {
        self.first / self.area_m2
    }

    /// The area-weighted covariance of the surface points about the centroid (m²).
    pub fn covariance(&self) -> Matrix3<f64> {
        let c = self.centroid();
        let m = self.second / self.area_m2 - c * c.transpose();
        0.5 * (m + m.transpose())
    }
}

impl std::ops::Add for SurfaceMoments {
    type Output = SurfaceMoments;

    fn add(self, other: SurfaceMoments) -> SurfaceMoments {
        SurfaceMoments {
            area_m2: self.area_m2 + other.area_m2,
            first: self.first + other.first,
            second: self.second + other.second,
        }
    }
}

fn box_moments(h: &Vector3<f64>) -> SurfaceMoments {
    let mut sum = SurfaceMoments::default();
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for sign in [1.0, -1.0] {
            let mut centre = Vector3::zeros();
            centre[axis] = sign * h[axis];
            let mut variance = Vector3::zeros();
            variance[u] = h[u] * h[u] / 3.0;
            variance[v] = h[v] * h[v] / 3.0;
            sum = sum + SurfaceMoments::patch(4.0 * h[u] * h[v], centre, variance);
        }
    }
    sum
}

/// The side of a cylinder about z from `−half` to `half`.
fn side_moments(radius: f64, half: f64) -> SurfaceMoments {
    let r2 = radius * radius;
    SurfaceMoments::patch(
        4.0 * PI * radius * half,
        Vector3::zeros(),
        Vector3::new(r2 / 2.0, r2 / 2.0, half * half / 3.0),
    )
}

/// A disc of `radius` at height `z` about the z axis.
fn disc_moments(radius: f64, z: f64) -> SurfaceMoments {
    let r2 = radius * radius;
    SurfaceMoments::patch(
        PI * r2,
        Vector3::new(0.0, 0.0, z),
        Vector3::new(r2 / 4.0, r2 / 4.0, 0.0),
    )
}

/// The hemisphere of `radius` centred at height `z` on the `side` (±1) of its centre: by
/// Archimedes its height above the centre is uniform in [0, r].
fn hemisphere_moments(radius: f64, z: f64, side: f64) -> SurfaceMoments {
    let r2 = radius * radius;
    SurfaceMoments::patch(
        2.0 * PI * r2,
        Vector3::new(0.0, 0.0, z + side * 0.5 * radius),
        Vector3::new(r2 / 3.0, r2 / 3.0, r2 / 12.0),
    )
}

/// A triangle: area A, `∫ x dA = A·s/3`, `∫ x xᵀ dA = A/12·(a aᵀ + b bᵀ + c cᵀ + s sᵀ)` with
/// `s = a + b + c`.
fn triangle_moments(a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) -> SurfaceMoments {
    let area = 0.5 * (b - a).cross(&(c - a)).norm();
    let s = a + b + c;
    let outer = |v: &Vector3<f64>| v * v.transpose();
    SurfaceMoments {
        area_m2: area,
        first: area / 3.0 * s,
        second: area / 12.0 * (outer(a) + outer(b) + outer(c) + outer(&s)),
    }
}

/// A link's geometry as the reference rules see it: its surface moments and how far it
/// reaches along a direction (link frame).
pub struct LinkGeometry<'a> {
    /// Every collider with its pose in the link frame.
    pub shapes: Vec<(&'a Shape, Pose)>,
}

impl LinkGeometry<'_> {
    /// The moments of all the surfaces together.
    pub fn moments(&self) -> SurfaceMoments {
        self.shapes
            .iter()
            .map(|(shape, pose)| SurfaceMoments::of_shape(shape).transformed(pose))
            .fold(SurfaceMoments::default(), |sum, m| sum + m)
    }

    /// The geometry's length along the unit direction `d` (m).
    fn extent_m(&self, d: &Vector3<f64>) -> f64 {
        let reach = |d: &Vector3<f64>| {
            self.shapes
                .iter()
                .map(|(shape, pose)| shape.support_m(pose, d))
                .fold(f64::NEG_INFINITY, f64::max)
        };
        reach(d) + reach(&-d)
    }

    /// The reference axes by the rules of the module documentation; `given` (unit, link
    /// frame) replaces the primary axis.
    pub fn reference_axes(&self, given: Option<Unit<Vector3<f64>>>) -> ReferenceAxes {
        let moments = self.moments();
        let usable = moments.area_m2() > 0.0 && moments.covariance().iter().all(|v| v.is_finite());
        let (primary, rule) = match given {
            Some(axis) => (axis, AxisRule::Given),
            None if usable => self.principal_axis(&moments),
            None => (Vector3::z_axis(), AxisRule::LinkZ),
        };
        let across = usable
            .then(|| self.spread_across(&moments, &primary))
            .flatten();
        let second = across.unwrap_or_else(|| perpendicular_link_axis(&primary));
        ReferenceAxes {
            primary,
            second,
            rule,
        }
    }

    /// Rules 1–3 of the module documentation.
    fn principal_axis(&self, moments: &SurfaceMoments) -> (Unit<Vector3<f64>>, AxisRule) {
        let [(large, long), (middle, _), (small, flat)] = principal(&moments.covariance());
        if large >= DISTINCT_SPREAD_RATIO * middle && large > 0.0 {
            (self.signed(long, moments), AxisRule::LongAxis)
        } else if middle >= DISTINCT_SPREAD_RATIO * small && middle > 0.0 {
            (self.signed(flat, moments), AxisRule::DiscAxis)
        } else {
            (Vector3::z_axis(), AxisRule::LinkZ)
        }
    }

    /// The direction of largest spread perpendicular to `axis`, when distinct.
    fn spread_across(
        &self,
        moments: &SurfaceMoments,
        axis: &Unit<Vector3<f64>>,
    ) -> Option<Unit<Vector3<f64>>> {
        let p = Matrix3::identity() - axis.into_inner() * axis.transpose();
        let projected = p * moments.covariance() * p;
        // The projected covariance has a zero eigenvalue along `axis`; the two others are the
        // spreads across it.
        let [(large, long), (middle, _), _] = principal(&projected);
        (large >= DISTINCT_SPREAD_RATIO * middle && large > 0.0).then(|| self.signed(long, moments))
    }

    /// `axis` pointed from the origin toward the centroid, or by its largest component.
    fn signed(&self, axis: Vector3<f64>, moments: &SurfaceMoments) -> Unit<Vector3<f64>> {
        let along = moments.centroid().dot(&axis);
        let decisive = along.abs() > CENTROID_SIGN_FRACTION * self.extent_m(&axis);
        let sign = if decisive {
            along.signum()
        } else {
            axis[axis.iamax()].signum()
        };
        Unit::new_normalize(sign * axis)
    }
}

/// Eigenvalues and unit eigenvectors of a symmetric matrix, largest first (ties by the
/// decomposition's order).
fn principal(m: &Matrix3<f64>) -> [(f64, Vector3<f64>); 3] {
    let eigen = SymmetricEigen::new(*m);
    let mut pairs: Vec<(f64, Vector3<f64>)> = (0..3)
        .map(|k| {
            (
                eigen.eigenvalues[k],
                eigen.eigenvectors.column(k).normalize(),
            )
        })
        .collect();
    pairs.sort_by(|a, b| b.0.total_cmp(&a.0));
    [pairs[0], pairs[1], pairs[2]]
}

/// The link axis (x, y, z; the first on ties) most nearly perpendicular to `axis`, projected
/// onto the plane perpendicular to it.
pub fn perpendicular_link_axis(axis: &Unit<Vector3<f64>>) -> Unit<Vector3<f64>> {
    let k = (0..3)
        .min_by(|&i, &j| axis[i].abs().total_cmp(&axis[j].abs()).then(i.cmp(&j)))
        .unwrap_or(0);
    let e = Vector3::ith(k, 1.0);
    Unit::new_normalize(e - e.dot(axis) * axis.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::TriMesh;
    use nalgebra::{Isometry3, Point3};

    fn geometry(shape: &Shape) -> LinkGeometry<'_> {
        LinkGeometry {
            shapes: vec![(shape, Isometry3::identity())],
        }
    }

    /// The box's closed form against the same box as 12 triangles.
    #[test]
    fn box_moments_match_its_triangles() {
        let h = Vector3::new(0.1, 0.05, 0.02);
        let corner = |i: usize| {
            Point3::new(
                if i & 1 == 1 { h.x } else { -h.x },
                if i & 2 == 2 { h.y } else { -h.y },
                if i & 4 == 4 { h.z } else { -h.z },
            )
        };
        let faces = [
            [0, 4, 6, 2],
            [1, 3, 7, 5],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 2, 3, 1],
            [4, 5, 7, 6],
        ];
        let triangles = faces
            .iter()
            .flat_map(|[a, b, c, d]| [[*a, *b, *c], [*a, *c, *d]])
            .collect();
        let mesh = Shape::Mesh(TriMesh {
            file: "box.stl".into(),
            vertices: (0..8).map(corner).collect(),
            triangles,
        });
        let pose = Isometry3::new(Vector3::new(0.3, -0.2, 0.1), Vector3::new(0.4, 0.2, -0.7));
        let exact = SurfaceMoments::of_shape(&Shape::Box { half_extents_m: h }).transformed(&pose);
        let meshed = SurfaceMoments::of_shape(&mesh).transformed(&pose);
        assert!((exact.area_m2() - meshed.area_m2()).abs() < 1e-15);
        assert!((exact.centroid() - meshed.centroid()).norm() < 1e-12);
        assert!((exact.covariance() - meshed.covariance()).norm() < 1e-12);
    }

    #[test]
    fn a_long_box_has_its_long_axis_and_a_cube_falls_back_to_z() {
        let long = Shape::Box {
            half_extents_m: Vector3::new(0.2, 0.05, 0.04),
        };
        let axes = geometry(&long).reference_axes(None);
        assert_eq!(axes.rule, AxisRule::LongAxis);
        // Centred on the origin: the largest component is made positive.
        assert!((axes.primary.into_inner() - Vector3::x()).norm() < 1e-12);
        assert!((axes.second.into_inner() - Vector3::y()).norm() < 1e-12);
        let cube = Shape::Box {
            half_extents_m: Vector3::repeat(0.05),
        };
        let axes = geometry(&cube).reference_axes(None);
        assert_eq!(axes.rule, AxisRule::LinkZ);
        assert_eq!(axes.primary, Vector3::z_axis());
        assert!((axes.second.into_inner() - Vector3::x()).norm() < 1e-12);
    }

    #[test]
    fn a_disc_has_its_axis_pointing_to_its_centroid() {
        let disc = Shape::Cylinder {
            radius_m: 0.04,
            length_m: 0.01,
        };
        let below = LinkGeometry {
            shapes: vec![(&disc, Isometry3::translation(0.0, 0.0, -0.005))],
        };
        let axes = below.reference_axes(None);
        assert_eq!(axes.rule, AxisRule::DiscAxis);
        assert!((axes.primary.into_inner() + Vector3::z()).norm() < 1e-12);
        // Across a disc's axis nothing is distinct: the link's x axis.
        assert!((axes.second.into_inner() - Vector3::x()).norm() < 1e-12);
    }

    #[test]
    fn a_given_axis_replaces_the_primary_one() {
        let long = Shape::Box {
            half_extents_m: Vector3::new(0.2, 0.05, 0.04),
        };
        let axes = geometry(&long).reference_axes(Some(Vector3::z_axis()));
        assert_eq!(axes.rule, AxisRule::Given);
        assert_eq!(axes.primary, Vector3::z_axis());
        // Across z the box spreads most along x.
        assert!((axes.second.into_inner() - Vector3::x()).norm() < 1e-12);
    }
}
