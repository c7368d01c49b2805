//! The content hash of a setup: FNV-1a (64 bit) over a canonical byte serialization.
//!
//! FNV-1a: start from the offset basis `0xcbf29ce484222325`; for every byte, XOR it into the
//! state, then multiply by the prime `0x100000001b3` (wrapping). It is not a cryptographic
//! hash: it identifies content, it does not authenticate it.
//!
//! The serialization starts with the tag `cable-dict setup v1` and writes every loaded value
//! in a fixed order: the robot model (links, colliders with their poses and dimensions, mesh
//! vertices and triangles, joints with kinds, origins, axes, limits and drives), the cable
//! spec, gravity, `max_guides_per_link`, thresholds, robustness, guides (name, links, fixed,
//! every configuration: name, position mm, rpy deg, pose, origin) and segments (range and
//! candidate list), then the installation pose when there is one, then which guides are
//! optional when any is. Integers are u64 little-endian; floats are their IEEE-754 bit patterns,
//! little-endian, with −0.0 written as +0.0; strings and lists are prefixed by their length.
//! Paths, comments, whitespace and key order never enter it.

use super::{ConfigurationOrigin, Setup};
use crate::cable::CableSpec;
use crate::pose::Pose;
use crate::robot::{Collider, JointDrive, Robot, Shape};

/// FNV-1a, 64 bit, of `bytes`.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes.iter().fold(OFFSET_BASIS, |state, &byte| {
        (state ^ u64::from(byte)).wrapping_mul(PRIME)
    })
}

/// The canonical serialization described in the module documentation.
pub(super) fn canonical_bytes(setup: &Setup) -> Vec<u8> {
    let mut out = Canon(Vec::new());
    out.str("cable-dict setup v1");
    robot(&mut out, &setup.robot);
    cable(&mut out, &setup.cable);
    out.floats(setup.gravity_m_s2.as_slice());
    out.usize(setup.max_guides_per_link);
    let t = &setup.thresholds;
    out.floats(&[
        t.contact_clearance_m,
        t.stretch,
        t.min_bend_radius_m,
        t.clamp_zone_m,
        t.static_bend_margin_m,
    ]);
    // The datasheet's limits, written only when given (older setups keep their hash).
    if t.flexing_curvature_change_per_m != super::DEFAULT_FLEXING_CURVATURE_CHANGE_PER_M {
        out.str("flexing change");
        out.floats(&[t.flexing_curvature_change_per_m]);
    }
    out.usize(setup.robustness.delta_s);
    out.usize(setup.robustness.range);
    guides(&mut out, setup);
    segments(&mut out, setup);
    // Written only when given, so that setups without it keep their hash.
    if let Some(installation) = &setup.installation {
        out.str("installation");
        out.floats(&installation.joints);
    }
    // Likewise the optional guides.
    if setup.guides.iter().any(|g| g.optional) {
        out.str("optional");
        setup.guides.iter().for_each(|g| out.bool(g.optional));
    }
    // And the kinds of clamp, when one is not rigid.
    let rigid = |c: &super::GuideConfiguration| c.kind == super::GuideKind::Rigid;
    if (setup.guides.iter()).any(|g| !g.configurations.iter().all(rigid)) {
        out.str("kinds");
        for guide in &setup.guides {
            for kind in guide.configurations.iter().map(|c| c.kind) {
                out.str(kind.word());
                let parameters = kind.parameters();
                if !parameters.is_empty() {
                    out.floats(&parameters);
                }
            }
        }
    }
    out.0
}

/// The byte sink with one writer per primitive.
struct Canon(Vec<u8>);

impl Canon {
    fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    fn usize(&mut self, v: usize) {
        self.u64(v as u64);
    }

    fn bool(&mut self, v: bool) {
        self.0.push(u8::from(v));
    }

    fn f64(&mut self, v: f64) {
        let v = if v == 0.0 { 0.0 } else { v };
        self.u64(v.to_bits());
    }

    fn floats(&mut self, values: &[f64]) {
        self.usize(values.len());
        values.iter().for_each(|&v| self.f64(v));
    }

    fn str(&mut self, s: &str) {
        self.usize(s.len());
        self.0.extend_from_slice(s.as_bytes());
    }

    fn pose(&mut self, pose: &Pose) {
        let q = pose.rotation.quaternion();
        let t = pose.translation.vector;
        self.floats(&[t.x, t.y, t.z, q.i, q.j, q.k, q.w]);
    }
}

fn robot(out: &mut Canon, robot: &Robot) {
    out.str(&robot.name);
    out.usize(robot.links.len());
    for link in &robot.links {
        out.str(&link.name);
        out.usize(link.parent_joint.map_or(0, |j| j + 1));
        out.usize(link.colliders.len());
        link.colliders.iter().for_each(|c| collider(out, c));
    }
    out.usize(robot.joints.len());
    for joint in &robot.joints {
        out.str(&joint.name);
        out.str(joint.kind.urdf_name());
        out.usize(joint.parent_link);
        out.usize(joint.child_link);
        out.pose(&joint.origin);
        out.floats(joint.axis.as_slice());
        let limits = joint.limits.map_or(vec![], |l| {
            vec![l.lower, l.upper, l.velocity.unwrap_or(f64::INFINITY)]
        });
        out.floats(&limits);
        drive(out, &joint.drive);
    }
    out.usize(robot.actuated.len());
    robot.actuated.iter().for_each(|&j| out.usize(j));
}

fn drive(out: &mut Canon, drive: &JointDrive) {
    match *drive {
        JointDrive::None => out.str("none"),
        JointDrive::Actuated { index } => {
            out.str("actuated");
            out.usize(index);
        }
        JointDrive::Mimic {
            index,
            multiplier,
            offset,
        } => {
            out.str("mimic");
            out.usize(index);
            out.floats(&[multiplier, offset]);
        }
    }
}

fn collider(out: &mut Canon, collider: &Collider) {
    // Written only for a body a setup attached, so that robots without any keep their hash.
    if let Some(name) = &collider.attached {
        out.str("attached");
        out.str(name);
    }
    out.pose(&collider.origin);
    match &collider.shape {
        Shape::Box { half_extents_m } => {
            out.str("box");
            out.floats(half_extents_m.as_slice());
        }
        Shape::Cylinder { radius_m, length_m } => {
            out.str("cylinder");
            out.floats(&[*radius_m, *length_m]);
        }
        Shape::Sphere { radius_m } => {
            out.str("sphere");
            out.floats(&[*radius_m]);
        }
        Shape::Capsule { radius_m, length_m } => {
            out.str("capsule");
            out.floats(&[*radius_m, *length_m]);
        }
        Shape::Mesh(mesh) => {
            out.str("mesh");
            out.usize(mesh.vertices.len());
            mesh.vertices
                .iter()
                .for_each(|v| out.floats(v.coords.as_slice()));
            out.usize(mesh.triangles.len());
            mesh.triangles
                .iter()
                .flatten()
                .for_each(|&i| out.u64(u64::from(i)));
        }
    }
}

fn cable(out: &mut Canon, cable: &CableSpec) {
    out.str(&cable.name);
    out.floats(&[
        cable.diameter_m,
        cable.mass_per_length_kg_m,
        cable.bending_stiffness_n_m2,
        cable.torsion_stiffness_n_m2,
        cable.min_bend_radius_m,
        cable.sub_segment_pitch_m,
        cable.axial_stiffness_n,
    ]);
    // Written only when given, so that cables without them keep their hash.
    let sheet = &cable.datasheet;
    if let Some(r) = sheet.min_bend_radius_flexing_m {
        out.str("flexing radius");
        out.floats(&[r]);
    }
    if let Some(t) = sheet.torsion_limit_deg_per_m {
        out.str("torsion limit");
        out.floats(&[t]);
    }
}

fn guides(out: &mut Canon, setup: &Setup) {
    out.usize(setup.guides.len());
    for guide in &setup.guides {
        out.str(&guide.name);
        out.usize(guide.link);
        out.usize(guide.body);
        out.bool(guide.fixed);
        out.usize(guide.configurations.len());
        for c in &guide.configurations {
            out.str(&c.name);
            out.floats(&c.position_mm);
            out.floats(&c.rpy_deg);
            out.pose(&c.pose);
            match c.origin {
                // The line is where it was written, not what it is: left out.
                ConfigurationOrigin::Declared { .. } => out.str("declared"),
                ConfigurationOrigin::Coincident {
                    guide,
                    configuration,
                } => {
                    out.str("coincident");
                    out.usize(guide);
                    out.usize(configuration);
                }
                ConfigurationOrigin::Generated { site, .. } => {
                    out.str("generated");
                    out.usize(site);
                }
            }
        }
    }
}

/// The declared segments; the spans follow from them and the optional guides.
fn segments(out: &mut Canon, setup: &Setup) {
    let declared = &setup.segments[..setup.declared_segments];
    out.usize(declared.len());
    for segment in declared {
        let r = &segment.range;
        out.usize(r.min);
        out.usize(r.max);
        out.usize(r.step);
        out.bool(r.allow_zero);
        out.bool(segment.intra_link);
        out.usize(segment.lengths.len());
        segment.lengths.iter().for_each(|&s| out.usize(s));
    }
}

#[cfg(test)]
mod tests {
    use super::fnv1a64;

    /// Published FNV-1a 64 test vectors.
    #[test]
    fn fnv1a64_matches_the_reference_vectors() {
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }
}
