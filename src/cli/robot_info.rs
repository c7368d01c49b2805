//! `cable-dict robot-info`: what a URDF describes, as the tool understood it.

use super::{Failure, emit, print_json, tidy};
use cable_dict::pose::Pose;
use cable_dict::robot::shells::{SelfCrossing, Shell, ShellKind};
use cable_dict::robot::{Collider, Joint, JointDrive, Robot, Shape, TriMesh};
use cable_dict::text_table::{Align, TextTable};
use serde::Serialize;
use std::fmt;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// The robot's URDF file.
    urdf: PathBuf,
    /// Print JSON instead of tables (SI units: metres, radians).
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> Result<(), Failure> {
    let robot = Robot::from_urdf_file(&args.urdf).map_err(Failure::input)?;
    let report = RobotReport::of(&robot);
    if args.json {
        print_json(&report)
    } else {
        emit(&RobotTables(&robot, &report).to_string())
    }
}

#[derive(Serialize)]
struct RobotReport {
    name: String,
    source: String,
    dof: usize,
    joints: Vec<JointReport>,
    links: Vec<LinkReport>,
    /// Meshes whose solid cannot be fully trusted.
    warnings: Vec<WarningReport>,
}

/// A mesh whose inside is ill-defined somewhere.
#[derive(Serialize)]
struct WarningReport {
    link: String,
    /// The mesh file.
    file: String,
    /// What is wrong with it (open edges, no consistent winding).
    problem: String,
    /// The whole warning, as the text output prints it.
    message: String,
}

#[derive(Serialize)]
struct JointReport {
    name: String,
    #[serde(rename = "type")]
    kind: &'static str,
    parent: String,
    child: String,
    origin: PoseReport,
    axis: [f64; 3],
    /// Index in the joint vector, for actuated joints.
    joint_vector_index: Option<usize>,
    /// `[joint, multiplier, offset]` for mimic joints.
    mimic: Option<(String, f64, f64)>,
    lower: Option<f64>,
    upper: Option<f64>,
    velocity: Option<f64>,
}

#[derive(Serialize)]
struct PoseReport {
    xyz_m: [f64; 3],
    rpy_rad: [f64; 3],
}

#[derive(Serialize)]
struct LinkReport {
    name: String,
    colliders: Vec<ColliderReport>,
}

#[derive(Serialize)]
struct ColliderReport {
    origin: PoseReport,
    shape: &'static str,
    /// Shape dimensions in metres: box size, radius (+ length), or mesh triangle count.
    description: String,
    /// For a mesh: its shells and surface, as the tool reads them.
    #[serde(skip_serializing_if = "Option::is_none")]
    mesh: Option<MeshReport>,
}

/// A collision mesh: what the file holds and how the tool understands its solid. The solid is
/// the union of the shells' insides; a closed shell's inside is exact, a loose one's is decided
/// by the winding number of the loose triangles.
#[derive(Serialize)]
struct MeshReport {
    /// The file read.
    file: String,
    /// Triangles in the file.
    triangles: usize,
    /// Distinct vertex positions.
    vertices: usize,
    /// Pieces of surface connected across edges of exactly two triangles.
    shells: usize,
    /// Shells that are closed, consistently wound and not self-crossing.
    closed_shells: usize,
    /// The other shells.
    loose_shells: usize,
    /// Edges of only one triangle (holes), over all shells.
    open_edges: usize,
    /// Edges used by more than two triangles: where shells meet.
    shared_edges: usize,
    /// Triangles the file winds against their neighbours (turned by the tool).
    triangles_wound_against_neighbours: usize,
    /// Closed shells the file winds inward (turned outward by the tool).
    shells_wound_inward: usize,
    /// Shells with two triangles crossing each other.
    self_crossing_shells: usize,
    /// Closed shells too large to check for self-crossing (treated as loose).
    shells_not_checked_for_self_crossing: usize,
    /// Shells no winding makes consistent.
    shells_without_consistent_winding: usize,
    /// Triangles with three distinct but collinear corners.
    zero_area_triangles: usize,
    /// Triangles with two corners at the same vertex (dropped).
    collapsed_triangles: usize,
    /// Volume enclosed by the closed shells (m³).
    volume_m3: f64,
    /// Bounding box of the vertices in the mesh frame (m).
    min_m: [f64; 3],
    /// Bounding box of the vertices in the mesh frame (m).
    max_m: [f64; 3],
    /// Each shell, in the order of its first triangle in the file.
    shell_list: Vec<ShellReport>,
    /// Why the solid cannot be fully trusted, if it cannot.
    #[serde(skip)]
    distrust: Option<String>,
}

#[derive(Serialize)]
struct ShellReport {
    /// "closed" or "loose".
    kind: &'static str,
    triangles: usize,
    open_edges: usize,
    /// Edges used by more than two of its triangles.
    shared_edges: usize,
    triangles_wound_against_neighbours: usize,
    wound_inward: bool,
    consistent_winding: bool,
    zero_area_triangles: usize,
    /// `null` when not checked (a shell not closed, or too large).
    self_crossing: Option<bool>,
    /// Enclosed volume (m³), closed shells only.
    volume_m3: Option<f64>,
    min_m: [f64; 3],
    max_m: [f64; 3],
}

impl RobotReport {
    fn of(robot: &Robot) -> Self {
        RobotReport {
            name: robot.name.clone(),
            source: robot.source.display().to_string(),
            dof: robot.dof(),
            joints: robot
                .joints
                .iter()
                .map(|j| JointReport::of(robot, j))
                .collect(),
            links: robot
                .links
                .iter()
                .map(|l| LinkReport {
                    name: l.name.clone(),
                    colliders: l.colliders.iter().map(ColliderReport::of).collect(),
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
                    Some(WarningReport {
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

impl JointReport {
    fn of(robot: &Robot, joint: &Joint) -> Self {
        let limits = joint.limits;
        JointReport {
            name: joint.name.clone(),
            kind: joint.kind.urdf_name(),
            parent: robot.links[joint.parent_link].name.clone(),
            child: robot.links[joint.child_link].name.clone(),
            origin: PoseReport::of(&joint.origin),
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

impl PoseReport {
    fn of(pose: &Pose) -> Self {
        let (roll, pitch, yaw) = pose.rotation.euler_angles();
        PoseReport {
            xyz_m: pose.translation.vector.into(),
            rpy_rad: [roll, pitch, yaw],
        }
    }
}

impl ColliderReport {
    fn of(collider: &Collider) -> Self {
        let shape = match collider.shape {
            Shape::Box { .. } => "box",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Capsule { .. } => "capsule",
            Shape::Mesh(_) => "mesh",
        };
        ColliderReport {
            origin: PoseReport::of(&collider.origin),
            shape,
            description: collider.shape.describe(),
            mesh: match &collider.shape {
                Shape::Mesh(mesh) => Some(MeshReport::of(mesh)),
                _ => None,
            },
        }
    }
}

impl MeshReport {
    fn of(mesh: &TriMesh) -> Self {
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
        MeshReport {
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
            shell_list: shells.iter().map(ShellReport::of).collect(),
            distrust: found.distrust(),
        }
    }

    /// Two lines for the text output (mm, cm³), indented by `indent`.
    fn text(&self, indent: &str) -> String {
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

impl ShellReport {
    fn of(shell: &Shell) -> Self {
        let closed = shell.kind == ShellKind::Closed;
        ShellReport {
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

/// The robot as human-readable tables (mm, degrees), with its meshes as reported.
struct RobotTables<'a>(&'a Robot, &'a RobotReport);

impl fmt::Display for RobotTables<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (robot, report) = (self.0, self.1);
        writeln!(
            f,
            "robot '{}' from {}: {} actuated joints",
            robot.name,
            robot.source.display(),
            robot.dof()
        )?;
        writeln!(f)?;
        let mut joints = TextTable::new(
            0,
            &[
                ("#", Align::Left),
                ("joint", Align::Left),
                ("type", Align::Left),
                ("parent → child", Align::Left),
                ("axis", Align::Left),
                ("limits", Align::Right),
                ("max speed", Align::Right),
            ],
        );
        for joint in &robot.joints {
            let index = match joint.drive {
                JointDrive::Actuated { index } => index.to_string(),
                JointDrive::Mimic { index, .. } => format!("={index}"),
                JointDrive::None => "-".into(),
            };
            let (scale, unit) = joint.kind.display_unit();
            let limits = joint.limits.map_or("-".into(), |l| {
                format!(
                    "{:.1} … {:.1} {unit}",
                    tidy(l.lower * scale),
                    tidy(l.upper * scale)
                )
            });
            let speed = joint
                .limits
                .and_then(|l| l.velocity)
                .map_or("-".into(), |v| format!("{:.0} {unit}/s", v * scale));
            let a = joint.axis;
            joints.row(vec![
                index,
                joint.name.clone(),
                joint.kind.urdf_name().to_string(),
                format!(
                    "{} → {}",
                    robot.links[joint.parent_link].name, robot.links[joint.child_link].name
                ),
                format!("({:.2},{:.2},{:.2})", a.x, a.y, a.z),
                limits,
                speed,
            ]);
        }
        write!(f, "{joints}")?;
        writeln!(f)?;
        writeln!(
            f,
            "links and collision shapes (positions in the link frame, mm):"
        )?;
        for (link, link_report) in robot.links.iter().zip(&report.links) {
            writeln!(f, "  {}", link.name)?;
            for (collider, collider_report) in link.colliders.iter().zip(&link_report.colliders) {
                let p = collider.origin.translation.vector * 1e3;
                let shape = match &collider_report.mesh {
                    Some(mesh) => mesh.text("          "),
                    None => collider.shape.describe(),
                };
                writeln!(f, "      at ({:.1}, {:.1}, {:.1}): {shape}", p.x, p.y, p.z)?;
            }
        }
        if !report.warnings.is_empty() {
            writeln!(f)?;
        }
        for warning in &report.warnings {
            writeln!(f, "warning: {}", warning.message)?;
        }
        Ok(())
    }
}
