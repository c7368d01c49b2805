//! The robot arm: its kinematic tree, forward kinematics and collision geometry.
//!
//! A [`Robot`] is loaded from a URDF file ([`Robot::from_urdf_file`]) and validated once, so
//! every later computation can index links and joints without checks. Links and joints are
//! stored in topological order (every parent before its children), which lets forward
//! kinematics run as one pass over the joints.
//!
//! The *joint vector* holds one value per actuated joint (revolute, continuous or prismatic,
//! and not a mimic joint) in the order the joints appear in the URDF document: radians for
//! rotary joints, metres for prismatic ones.

mod collision;
mod error;
pub mod info;
mod kinematics;
mod load;
mod locate;
mod mesh;
pub mod shells;

pub use collision::{Collider, Shape, TriMesh};
pub use error::{JointVectorError, RobotError};
pub use mesh::MeshFile;

use crate::pose::Pose;
use nalgebra::{Unit, Vector3};
use std::path::PathBuf;

/// A robot arm as a tree of rigid links connected by joints.
#[derive(Debug, Clone)]
pub struct Robot {
    /// The `name` attribute of the URDF `<robot>` element.
    pub name: String,
    /// The URDF file it was loaded from (for messages).
    pub source: PathBuf,
    /// Links in topological order; `links[0]` is the root (base).
    pub links: Vec<Link>,
    /// Joints in topological order: a joint comes after the joint of its parent link.
    pub joints: Vec<Joint>,
    /// For each joint-vector entry, the index into `joints` of the joint it drives.
    pub actuated: Vec<usize>,
    /// The mesh files the colliders were read from, in the order first used (empty for a
    /// robot of primitive shapes): what a dictionary embeds with the URDF.
    pub mesh_files: Vec<MeshFile>,
}

/// A rigid body of the arm with its collision geometry.
#[derive(Debug, Clone)]
pub struct Link {
    /// The URDF link name.
    pub name: String,
    /// Index into [`Robot::joints`] of the joint whose child this link is; `None` for the root.
    pub parent_joint: Option<usize>,
    /// Collision shapes, posed in this link's frame.
    pub colliders: Vec<Collider>,
}

/// The kind of relative motion a joint allows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Rotation about the axis within limits.
    Revolute,
    /// Rotation about the axis without limits.
    Continuous,
    /// Translation along the axis within limits.
    Prismatic,
    /// No motion.
    Fixed,
}

impl JointKind {
    /// The URDF `type` attribute for this kind.
    pub fn urdf_name(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Continuous => "continuous",
            JointKind::Prismatic => "prismatic",
            JointKind::Fixed => "fixed",
        }
    }

    /// True for joints whose value is an angle (radians), false for lengths (metres).
    pub fn is_rotary(self) -> bool {
        matches!(self, JointKind::Revolute | JointKind::Continuous)
    }

    /// Factor from SI to the unit people read (deg per rad, or mm per m) and the unit.
    pub fn display_unit(self) -> (f64, DisplayUnit) {
        if self.is_rotary() {
            (180.0 / std::f64::consts::PI, DisplayUnit::Deg)
        } else {
            (1e3, DisplayUnit::Mm)
        }
    }
}

/// The unit a joint's value is shown in: written `deg` or `mm` (text and JSON alike).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum DisplayUnit {
    /// Degrees, for rotary joints.
    Deg,
    /// Millimetres, for prismatic joints.
    Mm,
}

impl DisplayUnit {
    /// What follows a value in text: `°` (no space) or ` mm`.
    pub fn suffix(self) -> &'static str {
        match self {
            DisplayUnit::Deg => "°",
            DisplayUnit::Mm => " mm",
        }
    }
}

impl std::fmt::Display for DisplayUnit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            DisplayUnit::Deg => "deg",
            DisplayUnit::Mm => "mm",
        })
    }
}

/// Where a joint's value comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JointDrive {
    /// A fixed joint: no value.
    None,
    /// The joint-vector entry `index`.
    Actuated {
        /// Index into the joint vector.
        index: usize,
    },
    /// `multiplier · q[index] + offset`, following another (actuated) joint.
    Mimic {
        /// Index into the joint vector of the mimicked joint.
        index: usize,
        /// Gear ratio (dimensionless, or m/rad across kinds).
        multiplier: f64,
        /// Offset in the joint's own unit (rad or m).
        offset: f64,
    },
}

/// Position limits of a joint, in its own unit (rad for rotary, m for prismatic joints).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointLimits {
    /// Lowest allowed value.
    pub lower: f64,
    /// Highest allowed value.
    pub upper: f64,
    /// Speed limit (rad/s or m/s); `None` where the URDF gives none (0 or missing).
    pub velocity: Option<f64>,
}

/// A joint between a parent and a child link.
#[derive(Debug, Clone)]
pub struct Joint {
    /// The URDF joint name.
    pub name: String,
    /// Motion type.
    pub kind: JointKind,
    /// Index into [`Robot::links`] of the parent link.
    pub parent_link: usize,
    /// Index into [`Robot::links`] of the child link.
    pub child_link: usize,
    /// Pose of the joint frame in the parent link frame (the URDF `<origin>`).
    pub origin: Pose,
    /// Unit axis of rotation or translation in the joint frame.
    pub axis: Unit<Vector3<f64>>,
    /// Position limits; `None` for continuous and fixed joints.
    pub limits: Option<JointLimits>,
    /// What drives the joint.
    pub drive: JointDrive,
}

impl Robot {
    /// Loads and validates a URDF file (see [`Robot::from_urdf_str`] for what is checked).
    pub fn from_urdf_file(path: impl AsRef<std::path::Path>) -> Result<Robot, RobotError> {
        load::from_file(path.as_ref())
    }

    /// Loads a URDF document; `source` names it in messages and anchors relative mesh paths.
    ///
    /// Refused with a located message: XML or URDF syntax errors, xacro (`<xacro:…>` elements
    /// or attributes, `${…}` or `$(…)` substitutions; the `xmlns:xacro` declaration alone is
    /// accepted), duplicate names, joints that reference unknown links, links with two
    /// parents, several roots or cycles, zero axes, unsupported joint types (floating, planar,
    /// spherical), inverted or empty limits, mimic joints that follow a non-actuated joint,
    /// non-positive shape dimensions, mesh files that are missing or not STL, and robots with
    /// no movable joint.
    pub fn from_urdf_str(text: &str, source: &std::path::Path) -> Result<Robot, RobotError> {
        load::from_str(text, source, None)
    }

    /// [`Robot::from_urdf_str`] with the mesh files given (as a dictionary embeds them)
    /// instead of read: a URI the URDF names that is not among `meshes` is an error.
    pub fn from_urdf_str_with_meshes(
        text: &str,
        source: &std::path::Path,
        meshes: &[MeshFile],
    ) -> Result<Robot, RobotError> {
        load::from_str(text, source, Some(meshes))
    }

    /// A robot of one fixed link `world` without colliders: the frame a scene of a segment in
    /// free space is drawn in.
    pub fn world_only() -> Robot {
        Robot {
            name: "world".into(),
            source: PathBuf::new(),
            links: vec![Link {
                name: "world".into(),
                parent_joint: None,
                colliders: Vec::new(),
            }],
            joints: Vec::new(),
            actuated: Vec::new(),
            mesh_files: Vec::new(),
        }
    }

    /// Number of entries in a joint vector.
    pub fn dof(&self) -> usize {
        self.actuated.len()
    }

    /// The joint driven by joint-vector entry `index`.
    pub fn actuated_joint(&self, index: usize) -> &Joint {
        &self.joints[self.actuated[index]]
    }

    /// Index of the link called `name`.
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }

    /// The link `link` moves with — its nearest ancestor reached through fixed joints only —
    /// and the pose of `link`'s frame in that link's frame (identity for `link` itself).
    pub fn moving_body(&self, mut link: usize) -> (usize, Pose) {
        let mut link_in_body = Pose::identity();
        while let Some(j) = self.links[link].parent_joint {
            let joint = &self.joints[j];
            if joint.kind != JointKind::Fixed {
                break;
            }
            link_in_body = joint.origin * link_in_body;
            link = joint.parent_link;
        }
        (link, link_in_body)
    }

    /// Adds `shape`, posed at `origin` in `link`'s frame, to the link's colliders as the body
    /// `name` a setup attaches (a tool, a camera): an obstacle like the link's own shapes.
    pub fn attach_body(&mut self, link: usize, name: &str, origin: Pose, shape: Shape) {
        self.links[link].colliders.push(Collider {
            origin,
            shape,
            attached: Some(name.to_string()),
        });
    }

    /// Reads the STL mesh `uri` of an attached body, scaled: a file relative to `folder`, or
    /// the file of that URI among `embedded` (a dictionary's). The file joins
    /// [`Robot::mesh_files`] so that a dictionary embeds it with the URDF's meshes.
    pub fn read_body_mesh(
        &mut self,
        uri: &str,
        scale: Vector3<f64>,
        folder: &std::path::Path,
        embedded: Option<&[MeshFile]>,
    ) -> Result<TriMesh, String> {
        let source = match embedded {
            Some(files) => mesh::MeshSource::Embedded(files),
            None => mesh::MeshSource::Files(folder),
        };
        let (mesh, file) = mesh::load_mesh(uri, scale, source)?;
        if !self.mesh_files.iter().any(|f| f.uri == file.uri) {
            self.mesh_files.push(file);
        }
        Ok(mesh)
    }

    /// `link` and the links joined to it through fixed joints (parents and children): the
    /// links that move as one body.
    pub fn rigidly_attached(&self, link: usize) -> Vec<usize> {
        let body = self.moving_body(link).0;
        (0..self.links.len())
            .filter(|&l| self.moving_body(l).0 == body)
            .collect()
    }

    /// Index into the joint vector of the actuated joint called `name`.
    pub fn actuated_index(&self, name: &str) -> Option<usize> {
        self.actuated
            .iter()
            .position(|&j| self.joints[j].name == name)
    }
}
