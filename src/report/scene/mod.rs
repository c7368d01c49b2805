//! The 3D scene of a cable path as a glTF 2.0 binary (`.glb`): the robot's collision shapes,
//! the cable as a tube of its diameter, the guides, one node per critical pose and an
//! animation of robot and cable over the motion test.
//!
//! [`SceneSpec`] says what to draw in the robot's world frame (z up, metres); [`to_glb`]
//! turns it into the bytes of a `.glb` file (y up, as glTF requires: a root node turns
//! the robot's frame into glTF's).

mod animation;
mod check;
mod document;
mod error;
mod glb;
mod graph;
mod mesh;
mod tube;

pub use error::SceneError;

use crate::pose::Pose;
use crate::robot::Robot;
use nalgebra::{Point3, Vector3};

/// The `.glb` bytes of the scene; the same spec always gives the same bytes.
///
/// Layout (node names in quotes): a root `"robot world (z up)"` turning z up into glTF's
/// y up holds `"robot"` (one node per link at its pose in [`SceneSpec::main`], holding one
/// node per collider and the guide markers of the link), `"cable"` when the main scene has
/// cable lines (per line a node holding `"<line> sub-segment <k>"` nodes, a shared unit
/// cylinder scaled onto nodes k and k + 1, and `"<line> node <k>"` spheres), and one node
/// per snapshot (a robot copy and one swept tube per cable line, translated by the
/// snapshot's offset). The animation, if any, moves the main robot's link nodes and the
/// main cable's pieces. Indices k are 0-based.
///
/// Refused (see [`SceneError`]) when link pose counts differ from the robot's links, a cable
/// line has fewer than two nodes, a value is not finite, a guide's link does not exist, or
/// the animation's times are not strictly increasing from 0 or its frames differ from
/// [`SceneSpec::main`] in cable lines or node counts.
pub fn to_glb(spec: &SceneSpec<'_>) -> Result<Vec<u8>, SceneError> {
    check::check_spec(spec)?;
    let mut builder = document::Builder::new();
    let mut materials = graph::Materials::default();
    let meshes = graph::SharedMeshes::new(&mut builder, spec, &mut materials)?;
    let root = graph::world_root(&mut builder);
    let robot = builder.node("robot", gltf_json::Node::default());
    builder.add_child(root, robot);
    let links = graph::robot_copy(&mut builder, spec, &spec.main.link_poses, &meshes, robot);
    let mut lines = Vec::new();
    if !spec.main.cable.is_empty() {
        let cable = builder.node("cable", gltf_json::Node::default());
        builder.add_child(root, cable);
        lines = graph::main_cable(&mut builder, spec, &meshes, cable);
    }
    for snapshot in &spec.snapshots {
        graph::snapshot(&mut builder, spec, snapshot, &meshes, &mut materials, root)?;
    }
    for animation in spec.animations() {
        animation::add_animation(&mut builder, &animation, &links, &lines);
    }
    builder.finish(vec![root])
}

/// One collider as the vertices of the mesh [`to_glb`] draws for it, in the world frame.
#[derive(Debug, Clone, PartialEq)]
pub struct ColliderPoints {
    /// Index into `robot.links` of its link.
    pub link: usize,
    /// The tessellation's vertices in the world frame (m).
    pub points_m: Vec<Point3<f64>>,
}

/// Every collider of `robot` with the links at `link_poses`, tessellated as in the scene,
/// link by link: so that a drawing made from them shows the shapes the scene and the
/// physics use.
pub fn collider_points(robot: &Robot, link_poses: &[Pose]) -> Vec<ColliderPoints> {
    let mut colliders = Vec::new();
    for (link, (l, pose)) in robot.links.iter().zip(link_poses).enumerate() {
        for collider in &l.colliders {
            let to_world = pose * collider.origin;
            let mesh = mesh::shape_mesh(&collider.shape);
            colliders.push(ColliderPoints {
                link,
                points_m: mesh.positions.iter().map(|p| to_world * p).collect(),
            });
        }
    }
    colliders
}

/// What a scene shows, in the robot's world frame (metres, z up).
#[derive(Debug, Clone)]
pub struct SceneSpec<'a> {
    /// The robot: every link's colliders are drawn.
    pub robot: &'a Robot,
    /// Cable radius (m): half its diameter.
    pub cable_radius_m: f64,
    /// The robot and cable as shown when no animation plays.
    pub main: PoseScene,
    /// The guides, each drawn as a marker moving with its link.
    pub guides: Vec<GuideMark>,
    /// Robot and cable over time (the motion test); `None` when there is nothing to animate.
    pub animation: Option<SceneAnimation>,
    /// The motion tests of a cell's other motions, one animation each (names distinct from
    /// `animation`'s), moving the same main copy.
    pub other_motions: Vec<SceneAnimation>,
    /// Robot and cable at the installation pose, written as a still animation named
    /// [`INSTALLATION_ANIMATION`] that moves the main copy there (so that a viewer can show
    /// it); same cable lines and node counts as [`SceneSpec::main`]. `None`: not shown.
    pub installation: Option<PoseScene>,
    /// Extra static copies of robot and cable, e.g. one per critical pose.
    pub snapshots: Vec<Snapshot>,
    /// The colour of each cable line by its margin, by line name; lines not named here are
    /// drawn in the plain cable colour.
    pub tints: Vec<(String, CableTint)>,
    /// Damage per cycle at every node of a main cable line (Miner's sum per round, ≥ 0), by
    /// line name. When given, the main cable can also be coloured by it: the scene offers
    /// the material variants [`COLOUR_VARIANTS`] (glTF's `KHR_materials_variants`), each
    /// sub-segment and node painted by its [`DamageLevel`] in the second. Empty: margins only.
    pub damage: Vec<(String, Vec<f64>)>,
}

/// The two colourings of the main cable a scene with [`SceneSpec::damage`] offers, as glTF
/// material variants: by margin ([`CableTint`], the default) and by damage per cycle
/// ([`DamageLevel`]).
pub const COLOUR_VARIANTS: [&str; 2] = ["margins", "damage per cycle"];

/// How much damage a part of the cable takes per cycle, in decades below the most damaged
/// point of the cable: where it will break first stands out, and so do the places that take
/// a tenth or a hundredth of that.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum DamageLevel {
    /// Less than a thousandth of the worst (or none).
    Slight,
    /// A thousandth to a hundredth of the worst.
    Low,
    /// A hundredth to a tenth of the worst.
    Raised,
    /// Within a factor of ten of the worst: where the cable breaks first.
    Worst,
}

impl DamageLevel {
    /// Every level, in the order of the materials.
    pub const ALL: [DamageLevel; 4] = [
        DamageLevel::Slight,
        DamageLevel::Low,
        DamageLevel::Raised,
        DamageLevel::Worst,
    ];

    /// The level of damage `damage` on a cable whose most damaged point takes `worst` (both
    /// per cycle): decades below `worst`; [`DamageLevel::Slight`] when `worst` is not > 0.
    pub fn of(damage: f64, worst: f64) -> DamageLevel {
        if !(worst > 0.0 && damage > 0.0) {
            return DamageLevel::Slight;
        }
        match damage / worst {
            r if r >= 0.1 => DamageLevel::Worst,
            r if r >= 0.01 => DamageLevel::Raised,
            r if r >= 0.001 => DamageLevel::Low,
            _ => DamageLevel::Slight,
        }
    }

    /// Its colour as the scene's material gives it (linear RGB, 0–1): pale blue to dark red.
    pub fn linear_rgb(self) -> [f32; 3] {
        match self {
            DamageLevel::Slight => [0.45, 0.65, 0.85],
            DamageLevel::Low => [0.95, 0.85, 0.45],
            DamageLevel::Raised => [0.95, 0.35, 0.05],
            DamageLevel::Worst => [0.45, 0.0, 0.2],
        }
    }

    /// The same colour for a page (`#rrggbb`, sRGB).
    pub fn css(self) -> String {
        css_of(self.linear_rgb())
    }

    /// What the colour says, for a legend.
    pub fn legend(self) -> &'static str {
        match self {
            DamageLevel::Slight => "under 1/1000 of the worst damage per cycle",
            DamageLevel::Low => "1/1000 to 1/100 of it",
            DamageLevel::Raised => "1/100 to 1/10 of it",
            DamageLevel::Worst => "within a factor of 10 of the worst: where it breaks first",
        }
    }
}

/// A linear RGB colour as `#rrggbb` (sRGB).
fn css_of([r, g, b]: [f32; 3]) -> String {
    let srgb = |c: f32| {
        let c = f64::from(c.clamp(0.0, 1.0));
        let v = if c <= 0.003_130_8 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        };
        (v * 255.0).round() as u8
    };
    format!("#{:02x}{:02x}{:02x}", srgb(r), srgb(g), srgb(b))
}

impl SceneSpec<'_> {
    /// The tint of the cable line `name`.
    pub fn tint_of(&self, name: &str) -> CableTint {
        self.tints
            .iter()
            .find(|(line, _)| line == name)
            .map_or(CableTint::Plain, |(_, tint)| *tint)
    }

    /// The damage per cycle at the nodes of main cable line `name`, if given.
    pub fn damage_of(&self, name: &str) -> Option<&[f64]> {
        (self.damage.iter())
            .find(|(line, _)| line == name)
            .map(|(_, damage)| damage.as_slice())
    }

    /// The most damage per cycle at any node of the main cable (0 when none is given).
    pub fn worst_damage(&self) -> f64 {
        (self.damage.iter())
            .flat_map(|(_, d)| d.iter().copied())
            .fold(0.0, f64::max)
    }
}

/// A cable line's colour: plain, or how close its piece comes to a limit (ordered from no
/// information to worst).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum CableTint {
    /// Orange: no margin shown.
    Plain,
    /// Green: every limit with room to spare.
    Ample,
    /// Amber: close to a limit (the rule: [`crate::report::views::margin_tints`]).
    Tight,
    /// Red: a limit is exceeded.
    Exceeded,
}

impl CableTint {
    /// Every tint, in the order of the materials.
    pub const ALL: [CableTint; 4] = [
        CableTint::Plain,
        CableTint::Ample,
        CableTint::Tight,
        CableTint::Exceeded,
    ];

    /// Its colour as the scene's material gives it (linear RGB, 0–1).
    pub fn linear_rgb(self) -> [f32; 3] {
        match self {
            CableTint::Plain => [1.0, 0.45, 0.05],
            CableTint::Ample => [0.1, 0.55, 0.15],
            CableTint::Tight => [1.0, 0.75, 0.0],
            CableTint::Exceeded => [0.85, 0.03, 0.03],
        }
    }

    /// The same colour for a page or a picture (`#rrggbb`, sRGB): what the 3D view shows.
    pub fn css(self) -> String {
        css_of(self.linear_rgb())
    }

    /// The colour's name, for a legend in words.
    pub fn colour_word(self) -> &'static str {
        match self {
            CableTint::Plain => "orange",
            CableTint::Ample => "green",
            CableTint::Tight => "amber",
            CableTint::Exceeded => "red",
        }
    }

    /// What the colour says, for a legend.
    pub fn legend(self) -> &'static str {
        match self {
            CableTint::Plain => "cable",
            CableTint::Ample => "cable: every limit with room to spare",
            CableTint::Tight => "cable: close to a limit",
            CableTint::Exceeded => "cable: a limit exceeded",
        }
    }
}

/// The robot and the cable at one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseScene {
    /// World pose of every link (indexed like `robot.links`).
    pub link_poses: Vec<Pose>,
    /// Cable centrelines, one polyline per drawn segment (nodes in the world frame, m).
    pub cable: Vec<CableLine>,
}

/// One cable segment's centreline.
#[derive(Debug, Clone, PartialEq)]
pub struct CableLine {
    /// Node name prefix, e.g. `C3`.
    pub name: String,
    /// Nodes from the start guide to the end guide (world frame, m); at least two.
    pub nodes_m: Vec<Point3<f64>>,
}

/// A guide (clamp) on a link.
#[derive(Debug, Clone, PartialEq)]
pub struct GuideMark {
    /// E.g. `G3 (link_3/top_40)`.
    pub name: String,
    /// The clamp's short label in pictures, e.g. `G3`.
    pub clamp: String,
    /// Index into `robot.links` of the link it moves with.
    pub link: usize,
    /// The guide's frame in the link frame; its +z axis is the cable direction.
    pub pose_in_link: Pose,
    /// The part there, which decides the marker's shape and colour.
    pub part: ClampPart,
}

/// The part a guide marker shows: each drawn its own way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default)]
pub enum ClampPart {
    /// A clamp holding the cable rigidly: a blue collar.
    #[default]
    Rigid,
    /// A rotating clamp (the cable turns in it): a wider, flatter teal ring.
    Rotating,
    /// A swivel (ball joint): a purple ball.
    Swivel,
    /// A sliding guide (the cable slides through): a long, thin grey sleeve.
    Sliding,
    /// A retraction system's outlet: a wide orange drum.
    Retraction,
}

impl ClampPart {
    /// Every part, in the order of the materials.
    pub const ALL: [ClampPart; 5] = [
        ClampPart::Rigid,
        ClampPart::Rotating,
        ClampPart::Swivel,
        ClampPart::Sliding,
        ClampPart::Retraction,
    ];

    /// Its colour as the scene's material gives it (linear RGB, 0–1).
    pub fn linear_rgb(self) -> [f32; 3] {
        match self {
            ClampPart::Rigid => [0.1, 0.3, 0.9],
            ClampPart::Rotating => [0.0, 0.6, 0.55],
            ClampPart::Swivel => [0.55, 0.15, 0.8],
            ClampPart::Sliding => [0.45, 0.45, 0.45],
            ClampPart::Retraction => [0.9, 0.35, 0.02],
        }
    }

    /// The same colour for a page (`#rrggbb`, sRGB).
    pub fn css(self) -> String {
        css_of(self.linear_rgb())
    }

    /// What the marker shows, for a legend.
    pub fn legend(self) -> &'static str {
        match self {
            ClampPart::Rigid => "clamp (a collar)",
            ClampPart::Rotating => "rotating clamp (a flat ring)",
            ClampPart::Swivel => "swivel (a ball)",
            ClampPart::Sliding => "sliding guide (a long grey sleeve)",
            ClampPart::Retraction => "retraction outlet (an orange drum)",
        }
    }
}

/// Robot and cable over time: keyframes at `times_s`.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneAnimation {
    /// Animation name, e.g. `motion test`.
    pub name: String,
    /// Keyframe times (s, strictly increasing, first at 0).
    pub times_s: Vec<f64>,
    /// Per keyframe, the robot and the cable. Every frame has the same cable lines with the
    /// same node counts as [`SceneSpec::main`].
    pub frames: Vec<PoseScene>,
}

/// The name of the animation that holds the installation pose.
pub const INSTALLATION_ANIMATION: &str = "installation pose";

impl SceneSpec<'_> {
    /// Every animation the scene writes: the motion test, the other motions', the
    /// installation pose.
    pub fn animations(&self) -> impl Iterator<Item = SceneAnimation> + '_ {
        let motions = self.animation.iter().chain(&self.other_motions).cloned();
        motions.chain(self.installation_animation())
    }

    /// The installation pose as the animation the scene writes: the pose held for one
    /// second (two equal keyframes: a clip of no duration is not played by every viewer).
    pub fn installation_animation(&self) -> Option<SceneAnimation> {
        self.installation.as_ref().map(|pose| SceneAnimation {
            name: INSTALLATION_ANIMATION.into(),
            times_s: vec![0.0, 1.0],
            frames: vec![pose.clone(), pose.clone()],
        })
    }
}

/// A static copy of robot and cable, shifted so that it does not overlap the main one.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Node name, e.g. `critical pose 3: C1 joint_1 max, t = 1.250 s`.
    pub name: String,
    /// The robot and the cable.
    pub scene: PoseScene,
    /// Shift of the whole copy in the world frame (m).
    pub offset_m: Vector3<f64>,
}
