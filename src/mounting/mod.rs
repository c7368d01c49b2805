//! The answer as the workshop mounts it: physical clamps (guides that coincide on a 0 mm
//! piece are one clamp), each with its place on the link measured from the link's features
//! ([`place`]), the mark on the cable where it grips (length from the cable's end at the
//! tool), the robot pose to lay the cable at, and the length tolerance the search tested.

pub mod place;

use crate::path::CablePath;
use crate::robot::{JointKind, Robot};
use crate::setup::Setup;
use crate::text_table::decimal;
pub use place::{LinkPlace, link_place};
use serde::Serialize;

/// What a fitter needs to mount one answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MountingPlan {
    /// Physical clamps from the cable's start (base side) to its end (tool side).
    pub clamps: Vec<PhysicalClamp>,
    /// The cable between consecutive physical clamps, from the start.
    pub pieces: Vec<MountedPiece>,
    /// Cable length from the first clamp to the last (mm).
    pub length_mm: f64,
    /// Every piece also held its limits this much shorter and longer (mm): the robustness
    /// test's R·ΔS.
    pub piece_tolerance_mm: f64,
    /// The length to cut with the cable file's allowances at its ends; `None` when the file
    /// gives none.
    pub cut: Option<CutLength>,
    /// The robot pose at which the cable is laid untwisted; `None` when the setup gives none
    /// (the clamps' declared frames are then the twist references).
    pub installation_pose: Option<Vec<JointValue>>,
}

/// The cable to cut: the designed length and the cable file's allowances (mm).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CutLength {
    /// Beyond the last clamp into the connector at the tool (0 when not given).
    pub tool_end_mm: f64,
    /// Before the first clamp, to the base or the controller (0 when not given).
    pub base_end_mm: f64,
    /// The sum with the length between the clamps.
    pub total_mm: f64,
}

impl MountingPlan {
    /// `each piece also held every limit 20 mm shorter and longer: put each mark within
    /// ±10 mm` (a mark off by half the tolerance keeps both neighbouring pieces inside it).
    pub fn tolerance_words(&self) -> String {
        format!(
            "each piece also held every limit {} mm shorter and longer: put each mark within \
             ±{} mm",
            decimal(self.piece_tolerance_mm, 0),
            decimal(self.piece_tolerance_mm / 2.0, 0)
        )
    }

    /// `lay the cable untwisted along its route with the robot at its installation pose:
    /// joint_1 0.0 deg, …`, or what stands in for a pose the setup does not give.
    pub fn installation_words(&self) -> String {
        match &self.installation_pose {
            Some(pose) => {
                let joints: Vec<String> = pose
                    .iter()
                    .map(|j| format!("{} {} {}", j.joint, decimal(j.value, 1), j.unit))
                    .collect();
                format!(
                    "lay the cable untwisted along its route with the robot at its installation \
                     pose: {}",
                    joints.join(", ")
                )
            }
            None => "the setup gives no installation pose: each clamp's twist reference is its \
                     frame's +x axis as written"
                .into(),
        }
    }
}

impl CutLength {
    /// `cut 2160 mm: 620 mm between the clamps, 40 mm into the connector at the tool,
    /// 1500 mm from the first clamp to the base (the cable file's allowances)`.
    pub fn describe(&self) -> String {
        let between = self.total_mm - self.tool_end_mm - self.base_end_mm;
        format!(
            "cut {} mm: {} mm between the clamps, {} mm into the connector at the tool, {} mm \
             from the first clamp to the base (the cable file's allowances)",
            decimal(self.total_mm, 0),
            decimal(between, 0),
            decimal(self.tool_end_mm, 0),
            decimal(self.base_end_mm, 0)
        )
    }
}

/// One clamp (or fitting) on the robot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PhysicalClamp {
    /// The setup's guides it stands for, e.g. `["G2", "G3"]` when G3 coincides with G2.
    pub guides: Vec<String>,
    /// `start`, `clamp` or `end`: the first and last of the path are the cable's ends.
    pub role: &'static str,
    /// For a fixed guide (a connector or fitting), its name as written, e.g. `gripper
    /// connector`; `None` for a clamp placed by the search.
    pub fitting: Option<String>,
    /// The link it is screwed onto.
    pub link: String,
    /// The placement's name (generated site or configuration).
    pub placement: String,
    /// Position in the link frame (mm).
    pub xyz_mm: [f64; 3],
    /// URDF roll, pitch, yaw in the link frame (deg); +z of that frame is the cable
    /// direction toward the tool.
    pub rpy_deg: [f64; 3],
    /// The place measured from the link's features; `None` on the robot's root link.
    pub place: Option<LinkPlace>,
    /// Where it grips the cable: cable length from the end at the tool (mm).
    pub mark_mm: f64,
}

impl PhysicalClamp {
    /// `G2 = G3`, or `G4 (gripper connector)`.
    pub fn label(&self) -> String {
        let guides = self.guides.join(" = ");
        match &self.fitting {
            Some(fitting) => format!("{guides} ({fitting})"),
            None => guides,
        }
    }
}

/// The cable between two physical clamps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MountedPiece {
    /// Index into [`MountingPlan::clamps`] of its start clamp; it ends at the next one.
    pub from_clamp: usize,
    /// Natural length (mm).
    pub length_mm: f64,
    /// The joints it crosses, base side first (empty when both clamps are on one link).
    pub across_joints: Vec<String>,
}

/// One joint of the installation pose, in display units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointValue {
    /// The joint's name.
    pub joint: String,
    /// Its value (deg for rotary joints, mm for prismatic ones).
    pub value: f64,
    /// `deg` or `mm`.
    pub unit: &'static str,
}

/// The mounting plan of `path` in `setup`.
pub fn mounting_plan(setup: &Setup, path: &CablePath) -> MountingPlan {
    let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
    let mounted: Vec<(usize, usize)> = path
        .guides(setup)
        .zip(path.configurations.iter().copied())
        .collect();
    let lengths_mm: Vec<f64> = path
        .pieces()
        .map(|(_, pv)| pv.sub_segments as f64 * pitch_mm)
        .collect();
    let length_mm: f64 = lengths_mm.iter().sum();
    let link_poses = installation_link_poses(setup);
    let mut clamps: Vec<PhysicalClamp> = Vec::new();
    let mut pieces: Vec<MountedPiece> = Vec::new();
    // The body and the distance from the start of the last physical clamp.
    let mut last: Option<(usize, f64)> = None;
    let mut from_start_mm = 0.0;
    for (i, &(g, c)) in mounted.iter().enumerate() {
        let before_mm = i.checked_sub(1).map(|p| lengths_mm[p]);
        from_start_mm += before_mm.unwrap_or(0.0);
        if let (Some(0.0), Some(clamp)) = (before_mm, clamps.last_mut()) {
            // A 0 mm piece: the two guides are one clamp.
            clamp.guides.push(setup.guides[g].name.clone());
            continue;
        }
        let body = setup.guides[g].body;
        if let Some((start_body, start_mm)) = last {
            pieces.push(MountedPiece {
                from_clamp: clamps.len() - 1,
                length_mm: from_start_mm - start_mm,
                across_joints: joints_between(&setup.robot, start_body, body),
            });
        }
        last = Some((body, from_start_mm));
        let mark_mm = length_mm - from_start_mm;
        clamps.push(physical_clamp(setup, g, c, &link_poses, mark_mm));
    }
    let count = clamps.len();
    for (i, clamp) in clamps.iter_mut().enumerate() {
        clamp.role = match i {
            0 => "start",
            i if i + 1 == count => "end",
            _ => "clamp",
        };
    }
    MountingPlan {
        clamps,
        pieces,
        length_mm,
        piece_tolerance_mm: (setup.robustness.range * setup.robustness.delta_s) as f64 * pitch_mm,
        cut: cut_length(setup, length_mm),
        installation_pose: setup
            .installation
            .as_ref()
            .map(|i| joint_values(setup, &i.joints)),
    }
}

fn physical_clamp(
    setup: &Setup,
    g: usize,
    c: usize,
    link_poses: &[crate::pose::Pose],
    mark_mm: f64,
) -> PhysicalClamp {
    let guide = &setup.guides[g];
    let configuration = &guide.configurations[c];
    let clamp_in_body = guide.link_in_body * configuration.pose;
    PhysicalClamp {
        guides: vec![guide.name.clone()],
        role: "clamp",
        fitting: guide.fixed.then(|| configuration.name.clone()),
        link: setup.robot.links[guide.link].name.clone(),
        placement: configuration.name.clone(),
        xyz_mm: configuration.position_mm,
        rpy_deg: configuration.rpy_deg,
        place: link_place(&setup.robot, guide.body, &clamp_in_body, link_poses),
        mark_mm,
    }
}

/// The cut length when the cable file gives an allowance.
fn cut_length(setup: &Setup, length_mm: f64) -> Option<CutLength> {
    let cable = &setup.cable;
    if cable.tool_end_allowance_m.is_none() && cable.base_end_allowance_m.is_none() {
        return None;
    }
    let tool_end_mm = cable.tool_end_allowance_m.unwrap_or(0.0) * 1e3;
    let base_end_mm = cable.base_end_allowance_m.unwrap_or(0.0) * 1e3;
    Some(CutLength {
        tool_end_mm,
        base_end_mm,
        total_mm: length_mm + tool_end_mm + base_end_mm,
    })
}

/// The link poses at the installation pose, or with every joint at 0 when the setup has
/// none (the "top" of a link is then its top at the zero pose).
fn installation_link_poses(setup: &Setup) -> Vec<crate::pose::Pose> {
    match &setup.installation {
        Some(installation) => installation.link_poses.clone(),
        None => setup
            .robot
            .link_poses(&vec![0.0; setup.robot.dof()])
            .unwrap_or_else(|_| vec![crate::pose::Pose::identity(); setup.robot.links.len()]),
    }
}

/// The joints on the way from link `a` to link `b` that move (fixed joints left out), in the
/// order the cable crosses them from `a`.
pub fn joints_between(robot: &Robot, a: usize, b: usize) -> Vec<String> {
    let up_a = ancestors(robot, a);
    let up_b = ancestors(robot, b);
    let common = up_a.iter().find(|link| up_b.contains(link)).copied();
    let climb = |chain: &[usize]| -> Vec<usize> {
        chain
            .iter()
            .take_while(|&&link| Some(link) != common)
            .filter_map(|&link| robot.links[link].parent_joint)
            .collect()
    };
    let mut joints = climb(&up_a);
    joints.extend(climb(&up_b).into_iter().rev());
    joints
        .into_iter()
        .filter(|&j| robot.joints[j].kind != JointKind::Fixed)
        .map(|j| robot.joints[j].name.clone())
        .collect()
}

/// `link` and its ancestors up to the root.
fn ancestors(robot: &Robot, mut link: usize) -> Vec<usize> {
    let mut chain = vec![link];
    while let Some(joint) = robot.links[link].parent_joint {
        link = robot.joints[joint].parent_link;
        if chain.contains(&link) || chain.len() > robot.links.len() {
            break;
        }
        chain.push(link);
    }
    chain
}

/// The joint vector in display units, with the names of the actuated joints.
fn joint_values(setup: &Setup, joints: &[f64]) -> Vec<JointValue> {
    joints
        .iter()
        .enumerate()
        .map(|(i, &value)| {
            let joint = setup.robot.actuated_joint(i);
            let (scale, unit) = joint.kind.display_unit();
            JointValue {
                joint: joint.name.clone(),
                value: value * scale,
                unit,
            }
        })
        .collect()
}
