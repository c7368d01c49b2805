//! The setup file: which robot, which cable, where guides may go, which segment lengths to
//! try, and the stress limits — everything `solve` and `build` need besides the motion.
//!
//! A setup is a TOML file (full reference: `docs/setup-format.md`). Paths are relative to the
//! setup file; numbers carry their unit in the key name; every key is required and unknown
//! keys are refused, so a typo never falls back to a default:
//!
//! ```toml
//! robot = "viper_s850.urdf"                # URDF, relative to this file
//! cable = "../../cables/smc_le_cp_3.toml"  # cable spec, relative to this file
//! gravity_m_s2 = [0.0, 0.0, -9.81]         # in the robot's base frame
//! max_guides_per_link = 2                  # most guides declared on one link
//!
//! [thresholds]
//! contact_clearance_mm = 0.0   # contact when the cable comes closer to the robot than this
//! stretch = 1.02               # centreline length / natural length
//! min_bend_radius_mm = "cable" # the cable file's value, or a number of mm
//! clamp_zone_mm = 20.0         # cable next to a guide not checked against the guide's link
//! static_bend_margin_mm = 4.0  # optional (default 0): extra radius the static tests demand
//! flexing_curvature_change_per_m = 1.0 # optional (default 1): a piece whose curvature
//!                              # changes more than this somewhere keeps the flexing radius
//!
//! [robustness]
//! delta_s = 1                  # ΔS, sub-segments
//! range = 2                    # R: S ± k·ΔS, k = 1…R must pass too
//!
//! [[guides]]                   # from the base end of the cable to the tool end
//! name = "G1"
//! link = "link_3"
//! configurations = [           # candidate poses in the link frame; +z = towards the tool
//!   { name = "back", position_mm = [-172.0, 0.0, 100.0], rpy_deg = [0.0, 0.0, 180.0] },
//! ]
//!
//! [[guides]]
//! name = "G2"
//! link = "link_6"
//! fixed = { name = "connector", position_mm = [60.0, 0.0, 85.0], rpy_deg = [0.0, 0.0, 0.0] }
//!
//! [[segments]]                 # one per pair of consecutive guides
//! from = "G1"
//! to = "G2"
//! lengths = { min = 20, max = 60, step = 1, allow_zero = false }  # sub-segments
//! ```
//!
//! **S = 0.** A segment whose two guides sit on one link (an *intra-link* segment, links joined
//! by fixed joints counting as one) may list `allow_zero = true`: S = 0 means only one clamp is
//! mounted there, i.e. the two guides coincide. It is represented by pose equality: the S = 0
//! PVs that make sense are exactly the pairs of configurations with the same pose
//! ([`Setup::is_admissible`]). So that such pairs exist, the loader adds *coincident copies*
//! ([`ConfigurationOrigin::Coincident`], named `G2/back`): for every such segment Cm, from the
//! base end to the tool end, every configuration of Gm is copied into G(m+1) unless G(m+1) is
//! fixed; then, from the tool end back, the configurations that come from a fixed guide are
//! copied from G(m+1) into Gm unless Gm is fixed. A copy whose pose the target already has is
//! not added. A segment with S > 0 between two coincident configurations is not admissible
//! either (a loop leaving and re-entering one clamp).
//!
//! [`Setup::content_hash`] identifies a setup by content: FNV-1a (64 bit) over a canonical
//! byte serialization of the loaded values (robot model, cable, guides, segments, thresholds),
//! so comments, whitespace, key order and file locations do not change it; see
//! [`Setup::canonical_bytes`].

mod bodies;
mod catalogue;
mod coincide;
mod error;
mod guides;
mod hash;
mod install;
mod load;
mod raw;
mod segments;
mod sites;

pub use catalogue::{
    Catalogue, ConfigurationEntry, DirectionEntry, GuideEntry, ReferenceAxes, SegmentEntry,
    SiteEntry,
};
pub use error::SetupError;
pub use guides::PoseIndex;

/// True when two clamp poses in one frame are the same place: positions within
/// [`COINCIDENCE_TOLERANCE_M`], orientations within [`COINCIDENCE_TOLERANCE_RAD`].
pub fn same_place(a: &Pose, b: &Pose) -> bool {
    guides::same_pose(a, b)
}
pub use hash::fnv1a64;
pub use install::{Installation, turn_about_axis};

use crate::cable::CableSpec;
use crate::pose::Pose;
use crate::robot::Robot;
use crate::stress::{ClampZone, GuideEnd};
use nalgebra::Vector3;
use std::path::{Path, PathBuf};

/// Two configurations coincide when their origins are closer than this (m)…
pub const COINCIDENCE_TOLERANCE_M: f64 = 1e-9;
/// …and their orientations differ by less than this angle (rad).
pub const COINCIDENCE_TOLERANCE_RAD: f64 = 1e-9;

/// A validated setup, SI inside.
#[derive(Debug, Clone)]
pub struct Setup {
    /// The setup file.
    pub source: PathBuf,
    /// The setup file's text, verbatim.
    pub text: String,
    /// The robot.
    pub robot: Robot,
    /// The URDF file, resolved against the setup file's folder.
    pub robot_path: PathBuf,
    /// The URDF file's text, verbatim (meshes it references are not included).
    pub robot_text: String,
    /// The cable.
    pub cable: CableSpec,
    /// The cable file, resolved against the setup file's folder.
    pub cable_path: PathBuf,
    /// The cable file's text, verbatim.
    pub cable_text: String,
    /// Gravitational acceleration in the robot's base frame (m/s²).
    pub gravity_m_s2: Vector3<f64>,
    /// Most guides allowed on one link (links joined by fixed joints count as one).
    pub max_guides_per_link: usize,
    /// Guides G1 … G(M+1), from the base end of the cable to the tool end.
    pub guides: Vec<Guide>,
    /// The pieces of cable the search considers: first the declared segments C1 … CM
    /// (segment `m` runs from `guides[m]` to `guides[m + 1]`), then one *span* for every pair
    /// of guides with only optional guides between them (from `guides[a]` to `guides[b]`,
    /// `b > a + 1`: the cable when those clamps are left out). See
    /// [`SegmentSpec::guides`].
    pub segments: Vec<SegmentSpec>,
    /// M, the number of declared segments (the first entries of `segments`).
    pub declared_segments: usize,
    /// Stress limits.
    pub thresholds: Thresholds,
    /// Robustness test parameters.
    pub robustness: Robustness,
    /// The robot pose at which the cable is installed untwisted (`install_joints_deg`); the
    /// twist references of the clamps are derived from it. `None`: the configurations'
    /// declared +x axes are the twist references.
    pub installation: Option<Installation>,
    /// How the robot's pendant shows the angles of some joints (`[pendant_angles]`), so that
    /// the installation pose is printed as the fitter enters it; not part of the physics.
    pub pendant_angles: Vec<PendantAngle>,
    /// FNV-1a 64 of [`Setup::canonical_bytes`].
    pub content_hash: u64,
}

/// The pendant's angle of a joint from the robot description's: `sign × URDF + offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendantAngle {
    /// Index into the joint vector.
    pub joint: usize,
    /// +1 or −1.
    pub sign: f64,
    /// Added after the sign (deg).
    pub offset_deg: f64,
}

impl PendantAngle {
    /// The pendant's angle (deg) of the description's `urdf_deg`.
    pub fn of(&self, urdf_deg: f64) -> f64 {
        self.sign * urdf_deg + self.offset_deg
    }
}

/// A guide (clamp) and the configurations it may take.
#[derive(Debug, Clone)]
pub struct Guide {
    /// Name as written, e.g. `G1`.
    pub name: String,
    /// Index into `Robot::links` of the link named in the file.
    pub link: usize,
    /// Index of the link the guide moves with: `link`, or its nearest ancestor reached
    /// through fixed joints only. Two guides with the same `body` are on one link.
    pub body: usize,
    /// Pose of `link`'s frame in `body`'s frame (identity when they are the same link).
    pub link_in_body: Pose,
    /// True for a guide with a single, given configuration (`fixed = {…}`), e.g. a connector.
    pub fixed: bool,
    /// True when the search may leave this clamp out (`optional = true`): the cable then
    /// runs from the previous mounted clamp to the next one (a span, see
    /// [`Setup::segments`]).
    pub optional: bool,
    /// Candidate configurations: the declared ones first, then coincident copies.
    pub configurations: Vec<GuideConfiguration>,
    /// The kinds of clamp it may be, simplest first (`[Rigid]` unless the file says
    /// otherwise); its configurations hold one copy of each pose per kind, in this order.
    pub kinds: Vec<GuideKind>,
    /// For a guide with a site generator, its sites (with their surface points and normals)
    /// in the order `ConfigurationOrigin::Generated { site }` indexes; `None` otherwise.
    pub generated: Option<crate::sites::GeneratedSites>,
}

/// How a guide holds the cable (docs/setup-format.md, "Guide kinds").
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum GuideKind {
    /// Position, direction and the turn about the cable's axis held: the paper's clamp.
    #[default]
    Rigid,
    /// Position and direction held; the cable turns freely about its own axis (no torque):
    /// twist relief.
    Rotating,
    /// Position held; the cable's direction turns freely within a cone about the guide's +z,
    /// and about its own axis (a ball joint: no moment).
    Swivel {
        /// The cone's half-angle (rad), in (0, π].
        cone_rad: f64,
    },
    /// Position and direction held; the cable slides through (and turns in) it, so the
    /// length on either side changes with the pose: a ring or roller between two clamps.
    Sliding {
        /// Coulomb friction coefficient of the guide on the cable (0: frictionless).
        friction: f64,
    },
    /// The outlet of a retraction system: a sliding guide whose cable behind it is stored in
    /// the unit (from the previous guide, its inlet) and pulled back by a spring.
    Retraction {
        /// The spring's force at zero travel, the unit resting on its stop (N).
        preload_n: f64,
        /// The force's growth per metre of cable pulled out (N/m).
        rate_n_per_m: f64,
        /// The most cable the unit gives out (m).
        travel_max_m: f64,
    },
}

impl GuideKind {
    /// The word the setup file and the answer use.
    pub fn word(&self) -> &'static str {
        match self {
            GuideKind::Rigid => "rigid",
            GuideKind::Rotating => "rotating",
            GuideKind::Swivel { .. } => "swivel",
            GuideKind::Sliding { .. } => "sliding",
            GuideKind::Retraction { .. } => "retraction",
        }
    }

    /// Its parameters in SI, in a fixed order (for the content hash): none for a rigid or
    /// rotating clamp.
    pub fn parameters(&self) -> Vec<f64> {
        match *self {
            GuideKind::Rigid | GuideKind::Rotating => Vec::new(),
            GuideKind::Swivel { cone_rad } => vec![cone_rad],
            GuideKind::Sliding { friction } => vec![friction],
            GuideKind::Retraction {
                preload_n,
                rate_n_per_m,
                travel_max_m,
            } => vec![preload_n, rate_n_per_m, travel_max_m],
        }
    }

    /// Whether the cable slides through it (a sliding guide or a retraction's outlet): the
    /// pieces on either side are one piece of the search, their split found by the solver.
    pub fn slides(&self) -> bool {
        matches!(
            self,
            GuideKind::Sliding { .. } | GuideKind::Retraction { .. }
        )
    }

    /// How simple the part is: the search prefers the simplest of equally good ones.
    pub fn rank(&self) -> usize {
        match self {
            GuideKind::Rigid => 0,
            GuideKind::Rotating => 1,
            GuideKind::Swivel { .. } => 2,
            GuideKind::Sliding { .. } => 3,
            GuideKind::Retraction { .. } => 4,
        }
    }
}

/// Where a piece through a swivel clamp between two pieces is held ([`Setup::swivel_of`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwivelSplit {
    /// The swivel clamp (index into [`Setup::guides`]).
    pub guide: usize,
    /// Its cone's half-angle (rad).
    pub cone_rad: f64,
    /// Sub-segments of the piece before it: the clamp holds that node.
    pub before: usize,
}

/// One candidate pose of a guide.
#[derive(Debug, Clone)]
pub struct GuideConfiguration {
    /// Name as written (`back`), or `G2/back` for a coincident copy of G2's `back`.
    pub name: String,
    /// Pose of the guide frame in its link's frame (m); +z is the cable direction towards the
    /// tool end, +x the reference for the cable's twist.
    pub pose: Pose,
    /// Position as written, in the frame of the link that declared it (mm).
    pub position_mm: [f64; 3],
    /// URDF roll, pitch, yaw as written (deg).
    pub rpy_deg: [f64; 3],
    /// Where the configuration comes from.
    pub origin: ConfigurationOrigin,
    /// How the clamp in this configuration holds the cable (a guide that offers several
    /// kinds has one configuration per kind and pose).
    pub kind: GuideKind,
}

/// Where a guide configuration comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConfigurationOrigin {
    /// Written in the setup file, at this 1-based line.
    Declared {
        /// 1-based line of the configuration in the setup file.
        line: usize,
    },
    /// Generated by a `sites = {…}` entry at this 1-based line: site number `site` of the
    /// guide's generator.
    Generated {
        /// 1-based line of the `sites` entry in the setup file.
        line: usize,
        /// Index of the site in the generator's list (several directions share one site).
        site: usize,
    },
    /// Added so that the guide can coincide with another one (S = 0): a copy of
    /// `guides[guide].configurations[configuration]`, which is a declared configuration.
    Coincident {
        /// Index of the guide that declared it.
        guide: usize,
        /// Index of the configuration in that guide's list.
        configuration: usize,
    },
}

/// Most sub-segments a segment's candidate lengths (and R·ΔS) may reach: 100 m at a 10 mm
/// pitch, beyond any robot; the static solver's time and memory grow with the count, and a
/// bound here keeps every length sum and product far from overflow.
pub const MAX_SUB_SEGMENTS: usize = 10_000;

/// Candidate lengths of one segment (or span).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SegmentSpec {
    /// Indices into [`Setup::guides`] of its start and end guides: `(m, m + 1)` for declared
    /// segment `m`, `(a, b)` with only optional guides between for a span.
    pub guides: (usize, usize),
    /// Candidate sub-segment counts S, ascending: `0` first when allowed, then
    /// `min, min + step, …, max`. Natural length = S · `sub_segment_pitch_m`. A span's range
    /// runs from the sum of its segments' `min` to the sum of their `max`, in steps of the
    /// greatest common divisor of their steps.
    pub lengths: Vec<usize>,
    /// True when both guides are on one link (same [`Guide::body`]).
    pub intra_link: bool,
    /// The range as written.
    pub range: LengthRange,
    /// For the piece through a sliding guide, a retraction's outlet or a swivel clamp between
    /// two pieces, that guide (its only configuration): the cable runs from `guides.0`
    /// through it to `guides.1`, its split found by the solver (sliding, retraction) or
    /// given by [`Setup::swivel_of`]. The declared segments on either side of such a guide
    /// have no lengths: they are never pieces alone.
    pub through: Option<usize>,
}

/// `lengths = { min, max, step, allow_zero }` as written (sub-segments).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LengthRange {
    /// Smallest non-zero S.
    pub min: usize,
    /// Largest S.
    pub max: usize,
    /// Spacing of the series.
    pub step: usize,
    /// Whether S = 0 is a candidate (intra-link segments only).
    pub allow_zero: bool,
}

/// Stress limits, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thresholds {
    /// A cable closer to the robot than this is in contact (m); 0 = touching is contact.
    pub contact_clearance_m: f64,
    /// Largest allowed centreline length / natural length (dimensionless, ≥ 1).
    pub stretch: f64,
    /// Smallest allowed bend radius (m).
    pub min_bend_radius_m: f64,
    /// Whether `min_bend_radius_m` was taken from the cable file (`"cable"`) or written.
    pub min_bend_radius_source: BendRadiusSource,
    /// Cable length next to a guide not checked for contact with the guide's own link (m).
    pub clamp_zone_m: f64,
    /// Bend radius the quasi-static tests (attachment, robustness, static sweep) demand on top
    /// of `min_bend_radius_m` (m), kept for the cable's swing in the motion test, which checks
    /// `min_bend_radius_m` itself. 0 = the reference paper's test.
    pub static_bend_margin_m: f64,
    /// The cable datasheet's flexing bend radius (m); `None` when it states none (flexing
    /// pieces then keep the fixed one).
    pub cable_flexing_bend_radius_m: Option<f64>,
    /// Largest twist per length (deg/m) from the cable datasheet; `None`: not limited.
    pub torsion_limit_deg_per_m: Option<f64>,
    /// A piece flexes when somewhere along it the curvature changes by more than this over
    /// the motion (1/m); it must then keep the flexing bend radius.
    pub flexing_curvature_change_per_m: f64,
}

/// [`Thresholds::flexing_curvature_change_per_m`] when the setup does not set it (1/m): a
/// point that goes from straight to a 1 m radius, or from 60 mm to 57 mm, flexes.
pub const DEFAULT_FLEXING_CURVATURE_CHANGE_PER_M: f64 = 1.0;

impl Thresholds {
    /// The bend radius a static equilibrium must keep (m): the limit plus the static margin.
    pub fn static_min_bend_radius_m(&self) -> f64 {
        self.min_bend_radius_m + self.static_bend_margin_m
    }

    /// The bend radius a flexing piece must keep (m): the datasheet's flexing radius, never
    /// below the fixed one (a setup may raise that).
    pub fn flexing_bend_radius_m(&self) -> f64 {
        self.cable_flexing_bend_radius_m
            .map_or(self.min_bend_radius_m, |r| r.max(self.min_bend_radius_m))
    }

    /// The bend radius a piece must keep (m), `flexing` or fixed, with the static margin
    /// when `static_shape`.
    pub fn bend_radius_for(&self, flexing: bool, static_shape: bool) -> f64 {
        let radius = if flexing {
            self.flexing_bend_radius_m()
        } else {
            self.min_bend_radius_m
        };
        radius
            + if static_shape {
                self.static_bend_margin_m
            } else {
                0.0
            }
    }

    /// Twist per length (deg/m, magnitude) above the torsion limit, as a margin: limit − it
    /// (infinite without a limit).
    pub fn twist_margin_deg_per_m(&self, twist_deg_per_m: f64) -> f64 {
        self.torsion_limit_deg_per_m
            .map_or(f64::INFINITY, |limit| limit - twist_deg_per_m.abs())
    }
}

/// Where the minimum bend radius comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BendRadiusSource {
    /// `min_bend_radius_mm = "cable"`: the cable file's `min_bend_radius_mm`.
    Cable,
    /// A number written in the setup file.
    Setup,
}

/// Robustness test parameters (the paper's D2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Robustness {
    /// ΔS (sub-segments, ≥ 1).
    pub delta_s: usize,
    /// R: lengths S ± k·ΔS for k = 1…R must pass too (0 disables the test).
    pub range: usize,
}

impl Setup {
    /// Reads and validates a setup file; the robot and cable files it names are loaded too.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Setup, SetupError> {
        load::from_file(path.as_ref())
    }

    /// Validates a setup file's text; `source` names it in messages and anchors the relative
    /// robot and cable paths.
    pub fn from_toml_str(text: &str, source: &Path) -> Result<Setup, SetupError> {
        load::from_str(text, source, None)
    }

    /// Rebuilds a setup from the three texts a [`Setup`] keeps (`text`, `robot_text`,
    /// `cable_text`) and its robot's mesh files (`robot.mesh_files`), e.g. as embedded in a
    /// dictionary: no file is read. The result has the same content hash as the setup the
    /// texts came from.
    pub fn from_texts(
        text: &str,
        source: &Path,
        robot_text: &str,
        cable_text: &str,
        meshes: &[crate::robot::MeshFile],
    ) -> Result<Setup, SetupError> {
        load::from_str(text, source, Some((robot_text, cable_text, meshes)))
    }

    /// The clamp zone at `end` of a segment whose guide there is screwed onto `link`:
    /// `thresholds.clamp_zone_m` of cable, counted in the cable's sub-segments.
    pub fn clamp_zone(&self, end: GuideEnd, link: usize) -> ClampZone {
        ClampZone::of_length(
            end,
            link,
            self.thresholds.clamp_zone_m,
            self.cable.sub_segment_pitch_m,
        )
    }

    /// Number of segments the search considers: the declared ones and the spans.
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// How many clamp configurations each guide has, in guide order: the layers of the
    /// graph the chains of pieces run through.
    pub fn configuration_counts(&self) -> Vec<usize> {
        self.guides.iter().map(|g| g.configurations.len()).collect()
    }

    /// Every segment's start and end guide, in segment order ([`Setup::segment_guides`]).
    pub fn segment_ends(&self) -> Vec<(usize, usize)> {
        (0..self.segment_count())
            .map(|m| self.segment_guides(m))
            .collect()
    }

    /// The kinds of the clamps at the ends of segment `m`'s piece between configurations
    /// `(start, end)` of its guides.
    pub fn piece_kinds(&self, m: usize, (start, end): (usize, usize)) -> (GuideKind, GuideKind) {
        let (a, b) = self.segment_guides(m);
        (
            self.guides[a].configurations[start].kind,
            self.guides[b].configurations[end].kind,
        )
    }

    /// Whether every clamp segment `m`'s pieces can end in is rigid and nothing holds them
    /// between (no swivel or sliding guide the piece runs through): what a dictionary
    /// answers for.
    pub fn segment_is_rigid(&self, m: usize) -> bool {
        let (a, b) = self.segment_guides(m);
        self.segments[m].through.is_none()
            && [a, b].iter().all(|&g| {
                (self.guides[g].configurations.iter()).all(|c| c.kind == GuideKind::Rigid)
            })
    }

    /// For segment `m` through a sliding guide or a retraction's outlet: that guide, its kind
    /// and the cable a retraction stores at rest (sub-segments; 0 for a sliding guide).
    pub fn slide_of(&self, m: usize) -> Option<(usize, GuideKind, usize)> {
        let g = self.segments[m].through?;
        let kind = self.guides[g].configurations.first()?.kind;
        let stored = match kind {
            GuideKind::Retraction { .. } => self.segments[g - 1].range.min,
            GuideKind::Swivel { .. } => return None,
            _ => 0,
        };
        Some((g, kind, stored))
    }

    /// For a piece of segment `m` through a swivel clamp between two pieces, `sub_segments`
    /// long: the clamp, its cone and how much of the piece lies before it. The pieces either
    /// side share what the piece has beyond their two shortest lengths in proportion to how
    /// much their declared windows allow (`max − min`), each within its window: a window of
    /// one length fixes that side. The swivel clamp is mounted at that mark; the search
    /// judges the one split (docs/architecture.md, "A swivel clamp between two pieces").
    pub fn swivel_of(&self, m: usize, sub_segments: usize) -> Option<SwivelSplit> {
        let g = self.segments[m].through?;
        let GuideKind::Swivel { cone_rad } = self.guides[g].configurations.first()?.kind else {
            return None;
        };
        let (before, after) = (self.segments[g - 1].range, self.segments[g].range);
        let spare = sub_segments.saturating_sub(before.min + after.min);
        let (wide_before, wide) = (
            before.max - before.min,
            (before.max - before.min) + (after.max - after.min),
        );
        let share = match wide {
            0 => 0,
            _ => (spare * wide_before + wide / 2) / wide,
        };
        let first = (before.min + share)
            .clamp(before.min, before.max)
            .max(sub_segments.saturating_sub(after.max))
            .min(sub_segments.saturating_sub(1))
            .max(1);
        Some(SwivelSplit {
            guide: g,
            cone_rad,
            before: first,
        })
    }

    /// Whether segment `m` has candidate lengths: not those on either side of a sliding guide
    /// or a retraction's outlet, which are one piece through it.
    pub fn has_candidates(&self, m: usize) -> bool {
        !self.segments[m].lengths.is_empty()
    }

    /// Indices into [`Setup::guides`] of segment `m`'s start and end guides: `(m, m + 1)`
    /// for a declared segment, the guides a span joins for a span.
    pub fn segment_guides(&self, m: usize) -> (usize, usize) {
        self.segments[m].guides
    }

    /// How people call segment `m`: `C3` for a declared segment, `C2–C3` for the span that
    /// takes the place of C2 and C3 (their shared clamp left out).
    pub fn segment_name(&self, m: usize) -> String {
        let (a, b) = self.segment_guides(m);
        if b == a + 1 {
            format!("C{b}")
        } else {
            format!("C{}–C{b}", a + 1)
        }
    }

    /// The segments (declared and spans) that start at guide `g`.
    pub fn segments_from(&self, g: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.segments.len()).filter(move |&m| self.segments[m].guides.0 == g)
    }

    /// The segments (declared and spans) that end at guide `g`.
    pub fn segments_into(&self, g: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.segments.len()).filter(move |&m| self.segments[m].guides.1 == g)
    }

    /// True when segment `m`'s guides are on one link.
    pub fn is_intra_link(&self, m: usize) -> bool {
        self.segments[m].intra_link
    }

    /// |D0,m|: the number of parameter vectors (S, P_m, P_(m+1)) of segment `m`, i.e.
    /// |lengths| × |configurations of G_m| × |configurations of G_(m+1)|, coincident copies
    /// included. Some of them are not admissible ([`Setup::is_admissible`]). Saturates at
    /// `usize::MAX` (a generated catalogue can be made arbitrarily large).
    pub fn pv_count(&self, m: usize) -> usize {
        let (a, b) = self.segment_guides(m);
        self.segments[m]
            .lengths
            .len()
            .saturating_mul(self.guides[a].configurations.len())
            .saturating_mul(self.guides[b].configurations.len())
    }

    /// True when configuration `ca` of guide `ga` and `cb` of guide `gb` are the same place:
    /// one body, and poses equal within the coincidence tolerances.
    pub fn coincident(&self, ga: usize, ca: usize, gb: usize, cb: usize) -> bool {
        let (a, b) = (&self.guides[ga], &self.guides[gb]);
        if a.body != b.body {
            return false;
        }
        guides::same_pose(&a.pose_in_body(ca), &b.pose_in_body(cb))
    }

    /// Whether the PV (S = `s`, configuration `i` of G_m, `j` of G_(m+1)) of segment `m`
    /// describes a real cable: S = 0 exactly when the two configurations coincide.
    pub fn is_admissible(&self, m: usize, s: usize, i: usize, j: usize) -> bool {
        let (a, b) = self.segment_guides(m);
        (s == 0) == self.coincident(a, i, b, j)
    }

    /// How many pairs of segment `m`'s start and end configurations are the same place
    /// ([`Setup::coincident`]), counted through a hash grid of places, not pair by pair (two
    /// guides may have 10⁵ configurations each).
    pub fn coincident_pair_count(&self, m: usize) -> usize {
        let (a, b) = self.segment_guides(m);
        let (ga, gb) = (&self.guides[a], &self.guides[b]);
        if ga.body != gb.body {
            return 0;
        }
        let mut ends = PoseIndex::default();
        for c in 0..gb.configurations.len() {
            ends.insert(&gb.pose_in_body(c), c);
        }
        (0..ga.configurations.len())
            .map(|c| ends.count(&ga.pose_in_body(c)))
            .sum()
    }

    /// Number of admissible PVs of segment `m` (at most [`Setup::pv_count`]).
    pub fn admissible_pv_count(&self, m: usize) -> usize {
        let (a, b) = self.segment_guides(m);
        let (na, nb) = (
            self.guides[a].configurations.len(),
            self.guides[b].configurations.len(),
        );
        let coincident = self.coincident_pair_count(m);
        self.segments[m]
            .lengths
            .iter()
            .map(|&s| {
                if s == 0 {
                    coincident
                } else {
                    na.saturating_mul(nb) - coincident
                }
            })
            .sum()
    }

    /// World pose of configuration `c` of guide `g`, given the link poses of
    /// `Robot::link_poses`.
    pub fn guide_world_pose(&self, link_poses: &[Pose], g: usize, c: usize) -> Pose {
        let guide = &self.guides[g];
        link_poses[guide.link] * guide.configurations[c].pose
    }

    /// The content hash as 16 lowercase hexadecimal digits.
    pub fn content_hash_hex(&self) -> String {
        format!("{:016x}", self.content_hash)
    }

    /// The canonical serialization that [`Setup::content_hash`] hashes (see `hash.rs`):
    /// a version tag, then every loaded value in a fixed order — numbers as little-endian
    /// bit patterns (−0.0 written as +0.0), strings and lists length-prefixed.
    pub fn canonical_bytes(&self) -> Vec<u8> {
        hash::canonical_bytes(self)
    }

    /// The setup restricted to inter-link segments (the paper's method 1: one mounted guide
    /// per link): every intra-link segment keeps only S = 0, the guides and
    /// `max_guides_per_link` stay as declared, and the content hash is recomputed. Fails
    /// naming the segment when an intra-link segment does not allow S = 0.
    pub fn inter_link_only(&self) -> Result<Setup, SetupError> {
        let mut setup = self.clone();
        for (m, segment) in setup.segments.iter_mut().enumerate() {
            if !segment.intra_link {
                continue;
            }
            if !segment.range.allow_zero {
                return Err(SetupError {
                    file: self.source.clone(),
                    line: None,
                    key: Some(format!("segments[{m}].lengths.allow_zero")),
                    problem: format!(
                        "segment C{} is intra-link but does not allow S = 0, so it cannot be \
                         left out for one guide per link",
                        m + 1
                    ),
                });
            }
            segment.lengths = vec![0];
        }
        setup.content_hash = fnv1a64(&setup.canonical_bytes());
        Ok(setup)
    }
}

impl Guide {
    /// Index of the configuration called `name` (as in results and reports).
    pub fn configuration_index(&self, name: &str) -> Option<usize> {
        self.configurations.iter().position(|c| c.name == name)
    }

    /// Pose of configuration `c` in the frame of [`Guide::body`].
    pub fn pose_in_body(&self, c: usize) -> Pose {
        self.link_in_body * self.configurations[c].pose
    }
}
