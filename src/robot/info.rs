//! What a URDF describes, as this crate understood it: joints, links, collision shapes and
//! each mesh's shells with what can be trusted of them (`cable-dict robot-info`; the JSON
//! format: docs/commands.md). Serialized as it is; the command renders it as tables.

use super::shells::{SelfCrossing, Shell, ShellKind};
use super::{Collider, Joint, JointDrive, Robot, Shape, TriMesh};
use crate::pose::Pose;
use serde::Serialize;

/// What `cable-dict robot-info` reports of a robot: joints, links, collision shapes, mesh warnings.
#[derive(Serialize)]
pub struct RobotInfo {
    /// Its name.
    pub name: String,
    /// The URDF file it was read from.
    pub source: String,
    /// Actuated joints.
    pub dof: usize,
    /// Every joint, in the file's order.
    pub joints: Vec<JointInfo>,
    /// Every link, in the file's order.
    pub links: Vec<LinkInfo>,
    /// Meshes whose solid cannot be fully trusted.
    pub warnings: Vec<WarningInfo>,
}

/// A mesh whose inside is ill-defined somewhere.
#[derive(Serialize)]
pub struct WarningInfo {
    /// The link whose mesh it is.
    pub link: String,
    /// The mesh file.
    pub file: String,
    /// What is wrong with it (open edges, no consistent winding).
    pub problem: String,
    /// The whole warning, as the text output prints it.
    pub message: String,
}

/// One joint: its kind, links, frame, axis and limits.
#[derive(Serialize)]
pub struct JointInfo {
    /// Its name.
    pub name: String,
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// The parent link.
    pub parent: String,
    /// The child link.
    pub child: String,
    /// Its frame in the parent's (or link's) frame.
    pub origin: PoseInfo,
    /// The joint axis (unit, joint frame).
    pub axis: [f64; 3],
    /// Index in the joint vector, for actuated joints.
    pub joint_vector_index: Option<usize>,
    /// `[joint, multiplier, offset]` for mimic joints.
    pub mimic: Option<(String, f64, f64)>,
    /// Lower limit (rad or m), if any.
    pub lower: Option<f64>,
    /// Upper limit (rad or m), if any.
    pub upper: Option<f64>,
    /// Velocity limit (rad/s or m/s), if any.
    pub velocity: Option<f64>,
}

/// A frame as the URDF writes it.
#[derive(Serialize)]
pub struct PoseInfo {
    /// Translation (m).
    pub xyz_m: [f64; 3],
    /// URDF roll, pitch, yaw (rad).
    pub rpy_rad: [f64; 3],
}

/// One link and its collision shapes.
#[derive(Serialize)]
pub struct LinkInfo {
    /// Its name.
    pub name: String,
    /// Its collision shapes.
    pub colliders: Vec<ColliderInfo>,
}

/// One collision shape: its kind, frame, size and (for a mesh) what was found in it.
#[derive(Serialize)]
pub struct ColliderInfo {
    /// Its frame in the parent's (or link's) frame.
    pub origin: PoseInfo,
    /// `box`, `cylinder`, `sphere` or `mesh`.
    pub shape: &'static str,
    /// Shape dimensions in metres: box size, radius (+ length), or mesh triangle count.
    pub description: String,
    /// For a mesh: its shells and surface, as the tool reads them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<MeshInfo>,
}

/// A collision mesh: what the file holds and how the tool understands its solid. The solid is
/// the union of the shells' insides; a closed shell's inside is exact, a loose one's is decided
/// by the winding number of the loose triangles.
#[derive(Serialize)]
pub struct MeshInfo {
    /// The file read.
    pub file: String,
    /// Triangles in the file.
    pub triangles: usize,
    /// Distinct vertex positions.
    pub vertices: usize,
    /// Pieces of surface connected across edges of exactly two triangles.
    pub shells: usize,
    /// Shells that are closed, consistently wound and not self-crossing.
    pub closed_shells: usize,
    /// The other shells.
    pub loose_shells: usize,
    /// Edges of only one triangle (holes), over all shells.
    pub open_edges: usize,
    /// Edges used by more than two triangles: where shells meet.
    pub shared_edges: usize,
    /// Triangles the file winds against their neighbours (turned by the tool).
    pub triangles_wound_against_neighbours: usize,
    /// Closed shells the file winds inward (turned outward by the tool).
    pub shells_wound_inward: usize,
    /// Shells with two triangles crossing each other.
    pub self_crossing_shells: usize,
    /// Closed shells too large to check for self-crossing (treated as loose).
    pub shells_not_checked_for_self_crossing: usize,
    /// Shells no winding makes consistent.
    pub shells_without_consistent_winding: usize,
    /// Triangles with three distinct but collinear corners.
    pub zero_area_triangles: usize,
    /// Triangles with two corners at the same vertex (dropped).
    pub collapsed_triangles: usize,
    /// Volume enclosed by the closed shells (m³).
    pub volume_m3: f64,
    /// Bounding box of the vertices in the mesh frame (m).
    pub min_m: [f64; 3],
    /// Bounding box of the vertices in the mesh frame (m).
    pub max_m: [f64; 3],
    /// Each shell, in the order of its first triangle in the file.
    pub shell_list: Vec<ShellInfo>,
    /// Why the solid cannot be fully trusted, if it cannot.
    #[serde(skip)]
    pub distrust: Option<String>,
}

/// One connected shell of a mesh and what can be trusted of it.
#[derive(Serialize)]
pub struct ShellInfo {
    /// "closed" or "loose".
    pub kind: &'static str,
    /// Triangles.
    pub triangles: usize,
    /// Edges used by one triangle only.
    pub open_edges: usize,
    /// Edges used by more than two of its triangles.
    pub shared_edges: usize,
    /// Triangles turned to agree with their neighbours.
    pub triangles_wound_against_neighbours: usize,
    /// Whether the shell was wound inward (and is turned).
    pub wound_inward: bool,
    /// Whether one winding fits every triangle.
    pub consistent_winding: bool,
    /// Triangles without area.
    pub zero_area_triangles: usize,
    /// `null` when not checked (a shell not closed, or too large).
    pub self_crossing: Option<bool>,
    /// Enclosed volume (m³), closed shells only.
    pub volume_m3: Option<f64>,
    /// Bounding box, low corner (m).
    pub min_m: [f64; 3],
    /// Bounding box, high corner (m).
    pub max_m: [f64; 3],
}

impl RobotInfo {
    /// What the report says of it.
    pub fn of(robot: &Robot) -> Self {
        RobotInfo {
            name: robot.name.clone(),
            source: robot.source.display().to_string(),
            dof: robot.dof(),
            joints: robot
                .joints
                .iter()
                .map(|j| JointInfo::of(robot, j))
                .collect(),
            links: robot
                .links
                .iter()
                .map(|l| LinkInfo {
                    name: l.name.clone(),
                    colliders: l.colliders.iter().map(ColliderInfo::of).collect(),
                })
                .collect(),
            warnings: Vec::new(),
        }
        .with_warnings()
    }

    /// Fills `warnings` from the links' meshes.
    fn with_warnings(mut self) -> Self {
        self.warnings = self
            .links
            .iter()
            .flat_map(|link| {
                link.colliders.iter().filter_map(|c| {
                    let mesh = c.mesh.as_ref()?;
                    let problem = mesh.distrust.clone()?;
                    Some(WarningInfo {
                        message: format!(
                            "link '{}', mesh {}: {problem}: inside/outside near them is \
                             decided by the winding number and can be wrong there",
                            link.name, mesh.file
                        ),
                        link: link.name.clone(),
                        file: mesh.file.clone(),
                        problem,
                    })
                })
            })
            .collect();
        self
    }
}

impl JointInfo {
    /// What the report says of it.
    pub fn of(robot: &Robot, joint: &Joint) -> Self {
        let limits = joint.limits;
        JointInfo {
            name: joint.name.clone(),
            kind: joint.kind.urdf_name(),
            parent: robot.links[joint.parent_link].name.clone(),
            child: robot.links[joint.child_link].name.clone(),
            origin: PoseInfo::of(&joint.origin),
            axis: joint.axis.into_inner().into(),
            joint_vector_index: match joint.drive {
                JointDrive::Actuated { index } => Some(index),
                _ => None,
            },
            mimic: match joint.drive {
                JointDrive::Mimic {
                    index,
                    multiplier,
                    offset,
                } => Some((robot.actuated_joint(index).name.clone(), multiplier, offset)),
                _ => None,
            },
            lower: limits.map(|l| l.lower),
            upper: limits.map(|l| l.upper),
            velocity: limits.and_then(|l| l.velocity),
        }
    }
}

impl PoseInfo {
    /// What the report says of it.
    pub fn of(pose: &Pose) -> Self {
        let (roll, pitch, yaw) = pose.rotation.euler_angles();
        PoseInfo {
            xyz_m: pose.translation.vector.into(),
            rpy_rad: [roll, pitch, yaw],
        }
    }
}

impl ColliderInfo {
    /// What the report says of it.
    pub fn of(collider: &Collider) -> Self {
        let shape = match collider.shape {
            Shape::Box { .. } => "box",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Capsule { .. } => "capsule",
            Shape::Mesh(_) => "mesh",
        };
        ColliderInfo {
            origin: PoseInfo::of(&collider.origin),
            shape,
            description: collider.shape.describe(),
            mesh: match &collider.shape {
                Shape::Mesh(mesh) => Some(MeshInfo::of(mesh)),
                _ => None,
            },
        }
    }
}

impl MeshInfo {
    /// What the report says of it.
    pub fn of(mesh: &TriMesh) -> Self {
        let found = mesh.shells();
        let shells = &found.shells;
        let count = |f: fn(&Shell) -> bool| shells.iter().filter(|s| f(s)).count();
        let sum = |f: fn(&Shell) -> usize| shells.iter().map(f).sum::<usize>();
        let (min, max) = mesh
            .triangles
            .iter()
            .flatten()
            .filter_map(|&v| mesh.vertices.get(v as usize))
            .fold(
                ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                |(lo, hi), p| {
                    (
                        [0, 1, 2].map(|k| lo[k].min(p[k])),
                        [0, 1, 2].map(|k| hi[k].max(p[k])),
                    )
                },
            );
        MeshInfo {
            file: mesh.file.display().to_string(),
            triangles: mesh.triangles.len(),
            vertices: mesh.vertices.len(),
            shells: shells.len(),
            closed_shells: count(|s| s.kind == ShellKind::Closed),
            loose_shells: count(|s| s.kind == ShellKind::Loose),
            open_edges: found.open_edges(),
            shared_edges: found.shared_edges,
            triangles_wound_against_neighbours: sum(|s| s.rewound_triangles),
            shells_wound_inward: count(|s| s.inverted),
            self_crossing_shells: count(|s| s.self_crossing == SelfCrossing::Yes),
            shells_not_checked_for_self_crossing: count(unchecked_for_crossing),
            shells_without_consistent_winding: count(|s| s.non_orientable),
            zero_area_triangles: sum(|s| s.zero_area_triangles),
            collapsed_triangles: found.collapsed_triangles,
            volume_m3: shells
                .iter()
                .filter(|s| s.kind == ShellKind::Closed)
                .map(|s| s.volume_m3)
                .sum(),
            min_m: min,
            max_m: max,
            shell_list: shells.iter().map(ShellInfo::of).collect(),
            distrust: found.distrust(),
        }
    }

    /// Two lines for the text output (mm, cm³), indented by `indent`.
    pub fn text(&self, indent: &str) -> String {
        let mm = |lo: f64, hi: f64| format!("{}…{}", one_decimal(lo * 1e3), one_decimal(hi * 1e3));
        let mut shells = format!(
            "{} ({} closed",
            plural(self.shells, "shell", "shells"),
            self.closed_shells
        );
        if self.loose_shells > 0 {
            shells += &format!(", {} loose", self.loose_shells);
        }
        shells += ")";
        let volume = one_decimal(self.volume_m3 * 1e6);
        let enclosed = if self.closed_shells == 0 {
            "no closed shell to enclose a volume".to_string()
        } else if self.loose_shells > 0 {
            format!("{volume} cm³ enclosed by the closed shells")
        } else {
            format!("{volume} cm³ enclosed")
        };
        let mut surface = vec![
            plural(self.open_edges, "open edge", "open edges"),
            plural(
                self.shared_edges,
                "edge shared by more than two triangles",
                "edges shared by more than two triangles",
            ) + if self.shared_edges > 0 {
                " (where shells meet)"
            } else {
                ""
            },
            plural(
                self.shells_wound_inward,
                "shell wound inward",
                "shells wound inward",
            ) + if self.shells_wound_inward > 0 {
                " (turned outward)"
            } else {
                ""
            },
        ];
        let optional = [
            (
                self.triangles_wound_against_neighbours,
                "triangle wound against its neighbours (turned)",
                "triangles wound against their neighbours (turned)",
            ),
            (
                self.shells_without_consistent_winding,
                "shell with no consistent winding",
                "shells with no consistent winding",
            ),
            (
                self.self_crossing_shells,
                "self-crossing shell",
                "self-crossing shells",
            ),
            (
                self.shells_not_checked_for_self_crossing,
                "shell too large to check for self-crossing",
                "shells too large to check for self-crossing",
            ),
            (
                self.zero_area_triangles,
                "zero-area triangle",
                "zero-area triangles",
            ),
            (
                self.collapsed_triangles,
                "collapsed triangle (dropped)",
                "collapsed triangles (dropped)",
            ),
        ];
        surface.extend(
            optional
                .iter()
                .filter(|(n, ..)| *n > 0)
                .map(|&(n, one, many)| plural(n, one, many)),
        );
        format!(
            "mesh {}: {}, {}, {shells}, {enclosed}, box x {}, y {}, z {} mm\n{indent}{}",
            self.file,
            plural(self.triangles, "triangle", "triangles"),
            plural(self.vertices, "vertex", "vertices"),
            mm(self.min_m[0], self.max_m[0]),
            mm(self.min_m[1], self.max_m[1]),
            mm(self.min_m[2], self.max_m[2]),
            surface.join(", ")
        )
    }
}

/// `n` and the noun, singular for one.
fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// One decimal, without a minus sign on a value that rounds to zero.
fn one_decimal(value: f64) -> String {
    let text = format!("{value:.1}");
    if text == "-0.0" { "0.0".into() } else { text }
}

/// A closed, consistently wound shell without zero-area triangles whose self-crossing check
/// was given up (too many overlapping triangles).
fn unchecked_for_crossing(s: &Shell) -> bool {
    s.self_crossing == SelfCrossing::GivenUp
}

impl ShellInfo {
    /// What the report says of it.
    pub fn of(shell: &Shell) -> Self {
        let closed = shell.kind == ShellKind::Closed;
        ShellInfo {
            kind: if closed { "closed" } else { "loose" },
            triangles: shell.triangles.len(),
            open_edges: shell.open_edges,
            shared_edges: shell.non_manifold_edges,
            triangles_wound_against_neighbours: shell.rewound_triangles,
            wound_inward: shell.inverted,
            consistent_winding: !shell.non_orientable,
            zero_area_triangles: shell.zero_area_triangles,
            self_crossing: match shell.self_crossing {
                SelfCrossing::Yes => Some(true),
                SelfCrossing::No => Some(false),
                SelfCrossing::NotChecked | SelfCrossing::GivenUp => None,
            },
            volume_m3: closed.then_some(shell.volume_m3),
            min_m: shell.min.coords.into(),
            max_m: shell.max.coords.into(),
        }
    }
}
