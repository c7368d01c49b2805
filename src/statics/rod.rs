//! The potential energy of one clamped cable segment as a function of its free node
//! positions, with its gradient and banded Hessian.
//!
//! Energy terms (SI units; `S` sub-segments of pitch `l`, nodes `x_0 … x_S`, edges
//! `e_i = x_{i+1} − x_i`):
//!
//! - **stretch**: `Σ ½ (EA/l)(|e_i| − l)²`;
//! - **bending**: at every joint, the bending energy of [`super::joint::bending`] with
//!   stiffness `kb`; at a guide joint (guide axis against the first or last edge) `2 kb`:
//!   that joint turns through half a sub-segment's worth of curvature (a cable on a circle
//!   leaving a clamp tangentially meets its first chord at half the chord angle), so it takes
//!   half a joint's compliance;
//! - **twist**: the cable is isotropic, so at equilibrium its twist is uniform, and the
//!   torsion springs reduce to one, `½ (kt/S) Ψ²` (`S − 1` interior joints `kt` and two guide
//!   joints `2 kt` in series). `Ψ` is the total twist: the angle about the end guide's axis
//!   from the start guide's x axis, parallel-transported along the guide axes and every
//!   edge, to the end guide's x axis. A free end carries no twist;
//! - **gravity**: `−Σ m_k g·x_k`, a lumped mass `ρ l` per interior node, `ρ l / 2` at a free
//!   end (the masses at clamped nodes do no work);
//! - **a swivel clamp between the ends** ([`Pin`]), if any: a stiff spring on the node it
//!   holds, and the bending of that node's two edges beyond its cone; it frees the twist.
//!
//! The twist couples every node with every other through `Ψ`: its Hessian is the banded
//! `(kt/S) Ψ ∇²Ψ` plus the rank-one `(kt/S) ∇Ψ ∇Ψᵀ`, which the Newton step handles by
//! Sherman–Morrison so that the linear algebra stays banded.
//!
//! An implicit time step of the dynamics (module [`crate::dynamics`]) minimizes the same
//! energy plus an **inertial term** `½ Σ w_k |x_k − a_k|²` over the free nodes ([`Inertia`]):
//! `w_k = m_k / h²` and `a_k` the position the node would reach by inertia alone. It adds
//! only to the diagonal, so the structure and the Newton solver stay those of the statics.

use nalgebra::{Matrix3, Point3, Rotation3, Unit, Vector3};

use super::banded::SymmetricBand;
use super::joint::{Edge, EdgePairDerivatives, bending, cone_bending, reference_twist};
use super::retract::{Retraction, restore_lengths};
use crate::cable::CableSpec;
use crate::pose::Pose;
use crate::setup::GuideKind;

/// Material and load parameters of the discrete cable model (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodParameters {
    /// Sub-segment pitch `l` (m).
    pub pitch_m: f64,
    /// Bending stiffness `EI` (N·m²); the joints' springs are `kb = EI / l`.
    pub bending_stiffness_n_m2: f64,
    /// Torsional stiffness `GJ` (N·m²); the joints' springs are `kt = GJ / l`.
    pub torsion_stiffness_n_m2: f64,
    /// Axial stiffness `EA` (N).
    pub axial_stiffness_n: f64,
    /// Mass per length `ρ` (kg/m).
    pub mass_per_length_kg_m: f64,
    /// Gravitational acceleration (m/s²), e.g. `(0, 0, −9.81)` with z up.
    pub gravity_m_s2: Vector3<f64>,
    /// How the clamps at the piece's ends hold it ([`Holds::RIGID`]: the paper's clamps).
    pub holds: Holds,
}

/// How a clamp holds the end of a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Hold {
    /// Position, direction and the turn about the cable's axis held: the clamp takes force,
    /// bending moment and torque.
    Rigid,
    /// Position and direction held; the cable turns freely about its own axis (a rotating
    /// clamp: no torque, so the piece's twist relaxes).
    Rotating,
    /// Position held; the direction turns freely within a cone of half-angle `cone_rad`
    /// about the clamp's +z, and is held at the cone's edge beyond it; the cable turns
    /// freely about its axis (a ball joint: no moment at all within the cone). `cone_rad ≥ π`
    /// is a pin.
    Swivel {
        /// Half-angle of the cone (rad).
        cone_rad: f64,
    },
}

impl Hold {
    /// How a clamp of `kind` holds the cable.
    pub fn of(kind: GuideKind) -> Hold {
        match kind {
            GuideKind::Rigid => Hold::Rigid,
            GuideKind::Rotating => Hold::Rotating,
            GuideKind::Swivel { cone_rad } => Hold::Swivel { cone_rad },
            // The cable turns in a ring it slides through; the ring holds its direction.
            GuideKind::Sliding { .. } | GuideKind::Retraction { .. } => Hold::Rotating,
        }
    }

    /// Whether the cable may turn about its own axis at this clamp.
    pub fn frees_twist(self) -> bool {
        !matches!(self, Hold::Rigid)
    }
}

/// How the clamps at both ends of a piece hold it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Holds {
    /// The start clamp.
    pub start: Hold,
    /// The end clamp (ignored for a free end).
    pub end: Hold,
}

impl Holds {
    /// Both ends rigid.
    pub const RIGID: Holds = Holds {
        start: Hold::Rigid,
        end: Hold::Rigid,
    };

    /// How clamps of kinds `start` and `end` hold a piece between them.
    pub fn of((start, end): (GuideKind, GuideKind)) -> Holds {
        Holds {
            start: Hold::of(start),
            end: Hold::of(end),
        }
    }

    /// The same holds with the cable free to turn between the clamps, as a swivel clamp
    /// between them lets it: the start clamp's turn freed where it held it (its bending
    /// unchanged). For the loads of a piece through a swivel, computed without the swivel.
    pub fn turning(self) -> Holds {
        Holds {
            start: match self.start {
                Hold::Rigid => Hold::Rotating,
                other => other,
            },
            ..self
        }
    }

    /// Whether the piece's twist relaxes: one of its clamps lets the cable turn.
    pub fn free_twist(&self) -> bool {
        self.start.frees_twist() || self.end.frees_twist()
    }
}

impl RodParameters {
    /// The discrete model of `cable` under `gravity_m_s2`.
    pub fn new(cable: &CableSpec, gravity_m_s2: Vector3<f64>) -> Self {
        Self {
            pitch_m: cable.sub_segment_pitch_m,
            bending_stiffness_n_m2: cable.bending_stiffness_n_m2,
            torsion_stiffness_n_m2: cable.torsion_stiffness_n_m2,
            axial_stiffness_n: cable.axial_stiffness_n,
            mass_per_length_kg_m: cable.mass_per_length_kg_m,
            gravity_m_s2,
            holds: Holds::RIGID,
        }
    }
}

/// One side of a joint: a cable edge (by index) or a guide axis (fixed unit vector) and how
/// that guide holds the cable.
#[derive(Debug, Clone, Copy)]
enum Side {
    Cable(usize),
    Guide(Vector3<f64>, Hold),
}

/// A segment's boundary conditions and parameters; evaluates energies of node sets.
#[derive(Debug, Clone)]
pub(crate) struct Rod {
    params: RodParameters,
    start: Pose,
    /// The end guide; `None` for a free end.
    end: Option<Pose>,
    sub_segments: usize,
    inertia: Option<Inertia>,
    pin: Option<Pin>,
}

/// A swivel clamp between the two ends of a piece: it holds node `node` at `position` and
/// lets the cable's direction there turn freely within a cone of half-angle `cone_rad` about
/// `axis` (held at the cone's edge beyond it) and the cable turn about its own axis — a ball
/// joint the cable runs through, continuous: it carries force, no moment.
///
/// The node is held by a stiff spring, [`PIN_STIFFNESS_PER_AXIAL`] times a sub-segment's
/// axial stiffness: it stays within `F·l / (100·EA)` of the clamp (0.1 µm for 10 N on a
/// 10⁴ N cable at a 10 mm pitch), and the node keeps its place among the unknowns so that
/// the structure of the problem, the dynamics and the solver stay those of a free piece.
/// Beyond the cone each edge at the node bends against the cone's edge as it would against a
/// clamp held there ([`cone_bending`], twice a joint's stiffness, as at a guide).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pin {
    /// The node the clamp holds (`1 ≤ node < S`).
    pub node: usize,
    /// Where (m).
    pub position: Point3<f64>,
    /// The cone's axis: the clamp's +z (unit).
    pub axis: Vector3<f64>,
    /// Half-angle of the cone (rad); `≥ π` lets the direction turn every way.
    pub cone_rad: f64,
}

impl Pin {
    /// The swivel clamp at the pose `clamp` (its origin, the cone about its +z) holding node
    /// `node`.
    pub fn held_by(clamp: &Pose, node: usize, cone_rad: f64) -> Pin {
        Pin {
            node,
            position: Point3::from(clamp.translation.vector),
            axis: clamp.rotation * Vector3::z(),
            cone_rad,
        }
    }
}

/// The pin's spring over a sub-segment's axial stiffness `EA / l`.
pub const PIN_STIFFNESS_PER_AXIAL: f64 = 100.0;

/// The inertial term `½ Σ w_k |x_k − a_k|²` of an implicit time step, over the free nodes.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Inertia {
    /// `w_k` per free node (N/m): the node's mass over the squared effective step.
    pub(crate) weights: Vec<f64>,
    /// `a_k`, three coordinates per free node (m).
    pub(crate) anchors: Vec<f64>,
}

/// The potential energy of a shape, term by term (J).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EnergyTerms {
    /// Axial springs.
    pub stretch_j: f64,
    /// Bending springs, guide joints included.
    pub bending_j: f64,
    /// Torsion, `½ (kt/S) Ψ²`.
    pub twist_j: f64,
    /// Gravity, `−Σ m g·x` (zero at the origin).
    pub gravity_j: f64,
}

impl EnergyTerms {
    /// The sum of all terms (J).
    pub fn total_j(&self) -> f64 {
        self.stretch_j + self.bending_j + self.twist_j + self.gravity_j
    }
}

/// Energy, gradient and total twist at one configuration.
#[derive(Debug, Clone, Default)]
pub(crate) struct Evaluation {
    /// The objective: the potential energy plus the inertial term, if any (J).
    pub(crate) energy: f64,
    pub(crate) terms: EnergyTerms,
    /// `∂E/∂x` over the free coordinates (N).
    pub(crate) gradient: Vec<f64>,
    /// Total twist Ψ (rad), on the branch nearest the reference passed in.
    pub(crate) twist: f64,
    /// `∂Ψ/∂x` over the free coordinates (1/m); empty for a free end.
    pub(crate) twist_gradient: Vec<f64>,
}

/// Buffers an evaluation reuses, so that a Newton iteration allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct Scratch {
    nodes: Vec<Point3<f64>>,
    edges: Vec<Edge>,
    moves: Vec<Point3<f64>>,
    targets: Vec<f64>,
    free: Vec<bool>,
    retraction: Retraction,
}

impl Rod {
    pub(crate) fn new(
        params: RodParameters,
        start: Pose,
        end: Option<Pose>,
        sub_segments: usize,
    ) -> Self {
        Self {
            params,
            start,
            end,
            sub_segments,
            inertia: None,
            pin: None,
        }
    }

    /// The same rod with a swivel clamp holding one of its interior nodes.
    pub(crate) fn with_pin(mut self, pin: Option<Pin>) -> Self {
        self.pin = pin.filter(|p| p.node >= 1 && p.node < self.sub_segments);
        self
    }

    /// The same rod with the inertial term of a time step (one weight per free node, three
    /// anchor coordinates per free node).
    pub(crate) fn with_inertia(mut self, inertia: Inertia) -> Self {
        debug_assert_eq!(inertia.weights.len(), self.free_nodes());
        debug_assert_eq!(inertia.anchors.len(), 3 * self.free_nodes());
        self.inertia = Some(inertia);
        self
    }

    /// The inertial term's buffers back, for the next step.
    pub(crate) fn into_inertia(self) -> Option<Inertia> {
        self.inertia
    }

    /// Lumped mass of node `k` (kg): `ρ l` inside, `ρ l / 2` at a free end.
    pub(crate) fn node_mass(&self, k: usize) -> f64 {
        let mass = self.params.mass_per_length_kg_m * self.params.pitch_m;
        if k == self.sub_segments && self.end.is_none() {
            0.5 * mass
        } else {
            mass
        }
    }

    /// Number of free nodes: interior nodes, plus the last node for a free end.
    pub(crate) fn free_nodes(&self) -> usize {
        self.sub_segments - usize::from(self.end.is_some())
    }

    /// Twist stiffness of the whole segment `kt / S` (N·m/rad); 0 for a free end or a clamp
    /// that lets the cable turn.
    pub(crate) fn twist_stiffness(&self) -> f64 {
        if self.end.is_some() && !self.twist_free() {
            self.params.torsion_stiffness_n_m2 / self.params.pitch_m / self.sub_segments as f64
        } else {
            0.0
        }
    }

    /// Whether the cable may turn about its axis somewhere between its end clamps: at a
    /// clamp that lets it, or at a swivel clamp between them (no torque anywhere then).
    fn twist_free(&self) -> bool {
        self.params.holds.free_twist() || self.pin.is_some()
    }

    pub(crate) fn params(&self) -> &RodParameters {
        &self.params
    }

    /// All `S + 1` nodes: the clamped ones and the free coordinates `x`.
    pub(crate) fn nodes(&self, x: &[f64]) -> Vec<Point3<f64>> {
        let mut nodes = Vec::with_capacity(self.sub_segments + 1);
        self.fill_nodes(x, &mut nodes);
        nodes
    }

    /// [`Rod::nodes`] into `nodes`.
    fn fill_nodes(&self, x: &[f64], nodes: &mut Vec<Point3<f64>>) {
        nodes.clear();
        nodes.push(Point3::from(self.start.translation.vector));
        nodes.extend(x.chunks_exact(3).map(|c| Point3::new(c[0], c[1], c[2])));
        if let Some(end) = &self.end {
            nodes.push(Point3::from(end.translation.vector));
        }
    }

    /// Free coordinates of a full node list (`S + 1` nodes).
    pub(crate) fn free_coordinates(&self, nodes: &[Point3<f64>]) -> Vec<f64> {
        nodes[1..=self.free_nodes()]
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .collect()
    }

    /// `x + step · direction` into `trial`, moved back onto the edge lengths the linearized
    /// step predicts (module `retract`); unretracted if that fails.
    pub(crate) fn retracted_step(
        &self,
        x: &[f64],
        direction: &[f64],
        step: f64,
        trial: &mut Vec<f64>,
        scratch: &mut Scratch,
    ) {
        trial.clear();
        trial.extend(x.iter().zip(direction).map(|(x, d)| x + step * d));
        self.fill_nodes(x, &mut scratch.nodes);
        self.fill_nodes(direction, &mut scratch.moves);
        scratch.targets.clear();
        for i in 0..self.sub_segments {
            let edge = scratch.nodes[i + 1] - scratch.nodes[i];
            let mut change = Vector3::zeros();
            for (node, sign) in [(i + 1, 1.0), (i, -1.0)] {
                if self.free_index(node).is_some() {
                    change += sign * scratch.moves[node].coords;
                }
            }
            let length = edge.norm();
            scratch
                .targets
                .push(length + step * edge.dot(&change) / length);
        }
        scratch.free.clear();
        scratch
            .free
            .extend((0..=self.sub_segments).map(|k| self.free_index(k).is_some()));
        // A swivel clamp's node stays where the step puts it: its spring is far stiffer than
        // the cable, so the lengths give way around it.
        if let Some(pin) = &self.pin {
            scratch.free[pin.node] = false;
        }
        self.fill_nodes(trial, &mut scratch.nodes);
        if restore_lengths(
            &mut scratch.nodes,
            &scratch.targets,
            &scratch.free,
            &mut scratch.retraction,
        ) {
            trial.clear();
            for p in &scratch.nodes[1..=self.free_nodes()] {
                trial.extend_from_slice(&[p.x, p.y, p.z]);
            }
        }
    }

    fn free_index(&self, node: usize) -> Option<usize> {
        (node >= 1 && node <= self.free_nodes()).then(|| node - 1)
    }

    fn start_axis(&self) -> Vector3<f64> {
        self.start.rotation * Vector3::z()
    }

    /// Energy, gradient and twist at `x`; fills `hessian` (banded part) when given.
    /// `twist_reference` picks the branch of Ψ (the previous iterate's value).
    pub(crate) fn evaluate(
        &self,
        x: &[f64],
        twist_reference: f64,
        hessian: Option<&mut SymmetricBand>,
    ) -> Evaluation {
        let mut evaluation = Evaluation::default();
        self.evaluate_into(
            x,
            twist_reference,
            hessian,
            &mut evaluation,
            &mut Scratch::default(),
        );
        evaluation
    }

    /// [`Rod::evaluate`] into `out`, reusing its vectors and `scratch`; `hessian` (if
    /// given) is overwritten.
    pub(crate) fn evaluate_into(
        &self,
        x: &[f64],
        twist_reference: f64,
        mut hessian: Option<&mut SymmetricBand>,
        out: &mut Evaluation,
        scratch: &mut Scratch,
    ) {
        self.fill_nodes(x, &mut scratch.nodes);
        scratch.edges.clear();
        scratch
            .edges
            .extend(scratch.nodes.windows(2).map(|w| Edge::new(w[1] - w[0])));
        let (nodes, edges) = (&scratch.nodes, &scratch.edges);
        let coordinates = 3 * self.free_nodes();
        reset(&mut out.gradient, coordinates);
        reset(
            &mut out.twist_gradient,
            if self.end.is_some() { coordinates } else { 0 },
        );
        let twist = match &self.end {
            Some(_) if self.twist_free() => 0.0,
            Some(end) => unwrap_near(self.transported_twist(edges, end), twist_reference),
            None => 0.0,
        };
        if let Some(h) = hessian.as_deref_mut() {
            h.reset(coordinates);
        }
        let mut assembly = Assembly {
            rod: self,
            gradient: &mut out.gradient,
            twist_gradient: &mut out.twist_gradient,
            hessian,
        };
        let stretch = self.add_stretch(edges, &mut assembly);
        let bend = self.add_joints(edges, twist, &mut assembly);
        let gravity = self.add_gravity(nodes, &mut assembly);
        let inertial = self.add_inertia(x, &mut assembly);
        let (held, cone) = self.add_pin(nodes, edges, &mut assembly);
        out.terms = EnergyTerms {
            stretch_j: stretch + held,
            bending_j: bend + cone,
            twist_j: 0.5 * self.twist_stiffness() * twist * twist,
            gravity_j: gravity,
        };
        out.energy = out.terms.total_j() + inertial;
        out.twist = twist;
    }

    fn add_stretch(&self, edges: &[Edge], assembly: &mut Assembly) -> f64 {
        let (pitch, k) = (
            self.params.pitch_m,
            self.params.axial_stiffness_n / self.params.pitch_m,
        );
        let mut energy = 0.0;
        for (i, edge) in edges.iter().enumerate() {
            let extension = edge.length - pitch;
            energy += 0.5 * k * extension * extension;
            let force = k * extension * edge.unit;
            assembly.add_node_gradient(i + 1, &force);
            assembly.add_node_gradient(i, &-force);
            if assembly.hessian.is_some() {
                let along = edge.unit * edge.unit.transpose();
                let across = Matrix3::identity() - along;
                let block = k * (along + (extension / edge.length) * across);
                assembly.add_hessian_block(i, i, &block);
                assembly.add_hessian_block(i + 1, i + 1, &block);
                assembly.add_hessian_block(i + 1, i, &-block);
            }
        }
        energy
    }

    /// Adds every joint's bending and, with a clamped end, twist (`k Ψ ∇Ψ` and the banded
    /// `k Ψ ∇²Ψ`) in one pass, and `∂Ψ/∂x`; returns the bending energy.
    fn add_joints(&self, edges: &[Edge], twist: f64, assembly: &mut Assembly) -> f64 {
        let twist_scale = self.twist_stiffness() * twist;
        let mut energy = 0.0;
        for joint in 0..=edges.len() {
            let Some((incoming, outgoing, stiffness)) = self.joint(joint, edges.len()) else {
                break;
            };
            let (a, b) = (side_edge(incoming, edges), side_edge(outgoing, edges));
            let with_hessian = assembly.hessian.is_some();
            let mut derivatives =
                joint_bending((incoming, outgoing), (&a, &b), stiffness, with_hessian);
            energy += derivatives.value;
            if self.end.is_some() {
                let twist_derivatives = reference_twist(&a, &b, with_hessian);
                assembly.add_twist_gradient(incoming, outgoing, &twist_derivatives);
                derivatives.add_scaled(&twist_derivatives, twist_scale);
            }
            assembly.add_joint(incoming, outgoing, &derivatives);
        }
        energy
    }

    fn add_gravity(&self, nodes: &[Point3<f64>], assembly: &mut Assembly) -> f64 {
        let mut energy = 0.0;
        for (k, node) in nodes.iter().enumerate() {
            if self.free_index(k).is_none() {
                continue;
            }
            let weight = self.node_mass(k) * self.params.gravity_m_s2;
            energy -= weight.dot(&node.coords);
            assembly.add_node_gradient(k, &-weight);
        }
        energy
    }

    /// The inertial term of a time step, if any: its value (J).
    fn add_inertia(&self, x: &[f64], assembly: &mut Assembly) -> f64 {
        let Some(inertia) = &self.inertia else {
            return 0.0;
        };
        let mut energy = 0.0;
        for (f, (&weight, (position, anchor))) in inertia
            .weights
            .iter()
            .zip(x.chunks_exact(3).zip(inertia.anchors.chunks_exact(3)))
            .enumerate()
        {
            let offset = Vector3::new(
                position[0] - anchor[0],
                position[1] - anchor[1],
                position[2] - anchor[2],
            );
            energy += 0.5 * weight * offset.norm_squared();
            assembly.add_node_gradient(f + 1, &(weight * offset));
            if assembly.hessian.is_some() {
                assembly.add_hessian_block(f + 1, f + 1, &Matrix3::from_diagonal_element(weight));
            }
        }
        energy
    }

    /// The swivel clamp's terms, if any: the spring holding its node and the bending of the
    /// node's two edges against the cone's edge beyond it (J, J).
    fn add_pin(
        &self,
        nodes: &[Point3<f64>],
        edges: &[Edge],
        assembly: &mut Assembly,
    ) -> (f64, f64) {
        let Some(pin) = &self.pin else {
            return (0.0, 0.0);
        };
        let k = PIN_STIFFNESS_PER_AXIAL * self.params.axial_stiffness_n / self.params.pitch_m;
        let offset = nodes[pin.node] - pin.position;
        assembly.add_node_gradient(pin.node, &(k * offset));
        if assembly.hessian.is_some() {
            assembly.add_hessian_block(pin.node, pin.node, &Matrix3::from_diagonal_element(k));
        }
        let stiffness = 2.0 * self.params.bending_stiffness_n_m2 / self.params.pitch_m;
        let with_hessian = assembly.hessian.is_some();
        let guide = Side::Guide(
            pin.axis,
            Hold::Swivel {
                cone_rad: pin.cone_rad,
            },
        );
        let mut cone = 0.0;
        for sides in [
            (Side::Cable(pin.node - 1), guide),
            (guide, Side::Cable(pin.node)),
        ] {
            let (a, b) = (side_edge(sides.0, edges), side_edge(sides.1, edges));
            let derivatives = joint_bending(sides, (&a, &b), stiffness, with_hessian);
            cone += derivatives.value;
            assembly.add_joint(sides.0, sides.1, &derivatives);
        }
        (0.5 * k * offset.norm_squared(), cone)
    }

    /// The part of the potential energy that depends on the pose of the start clamp (or,
    /// `at_end`, the end clamp) with the free nodes `x` held: the stretch of the edge that
    /// leaves the clamp, the bending of the two joints nearest it and the twist (J). Its
    /// derivatives with respect to the clamp's pose are those of the whole energy, at a
    /// fraction of the cost ([`super::loads`]).
    pub(crate) fn clamp_energy(&self, x: &[f64], twist_reference: f64, at_end: bool) -> f64 {
        let nodes = self.nodes(x);
        let edges: Vec<Edge> = nodes.windows(2).map(|w| Edge::new(w[1] - w[0])).collect();
        let count = edges.len();
        if count == 0 {
            return 0.0;
        }
        let k = self.params.axial_stiffness_n / self.params.pitch_m;
        let edge = if at_end { count - 1 } else { 0 };
        let extension = edges[edge].length - self.params.pitch_m;
        let mut energy = 0.5 * k * extension * extension;
        let joints = if at_end {
            [count.saturating_sub(1), count]
        } else {
            [0, 1.min(count)]
        };
        let mut seen = None;
        for joint in joints {
            if seen == Some(joint) {
                continue;
            }
            seen = Some(joint);
            let Some((incoming, outgoing, stiffness)) = self.joint(joint, count) else {
                continue;
            };
            let (a, b) = (side_edge(incoming, &edges), side_edge(outgoing, &edges));
            energy += joint_bending((incoming, outgoing), (&a, &b), stiffness, false).value;
        }
        if let Some(end) = &self.end
            && !self.twist_free()
        {
            let twist = unwrap_near(self.transported_twist(&edges, end), twist_reference);
            energy += 0.5 * self.twist_stiffness() * twist * twist;
        }
        energy
    }

    /// Joint `joint` of a rod of `count` edges: its two sides and its bending stiffness. Joint
    /// j sits at node j, between edge j − 1 (or the start guide's axis) and edge j (or the end
    /// guide's axis), with twice the stiffness at a guide; a free end has no joint at node S.
    fn joint(&self, joint: usize, count: usize) -> Option<(Side, Side, f64)> {
        let kb = self.params.bending_stiffness_n_m2 / self.params.pitch_m;
        let holds = self.params.holds;
        let incoming = match joint {
            0 => Side::Guide(self.start_axis(), holds.start),
            j => Side::Cable(j - 1),
        };
        let outgoing = match (joint < count, &self.end) {
            (true, _) => Side::Cable(joint),
            (false, Some(end)) => Side::Guide(end.rotation * Vector3::z(), holds.end),
            (false, None) => return None,
        };
        let at_guide = matches!(incoming, Side::Guide(..)) || matches!(outgoing, Side::Guide(..));
        Some((incoming, outgoing, if at_guide { 2.0 * kb } else { kb }))
    }

    /// Ψ on the principal branch `(−π, π]`: the end guide's x axis measured about its z axis
    /// from the start guide's x axis transported along the cable.
    fn transported_twist(&self, edges: &[Edge], end: &Pose) -> f64 {
        let end_axis = end.rotation * Vector3::z();
        let mut normal = self.start.rotation * Vector3::x();
        let mut tangent = self.start_axis();
        for next in edges
            .iter()
            .map(|e| e.unit)
            .chain(std::iter::once(end_axis))
        {
            normal = parallel_transport(&normal, &tangent, &next);
            tangent = next;
        }
        let end_normal = end.rotation * Vector3::x();
        let sine = end_axis.dot(&normal.cross(&end_normal));
        sine.atan2(normal.dot(&end_normal))
    }

    /// Node frames of a configuration with total twist `twist`: columns normal, binormal,
    /// tangent. The tangent at an interior node bisects its two edges; the normal is the
    /// start guide's x axis transported along the cable and turned by `twist · k/S`. The first
    /// and last frames are the guide orientations (the last one transported for a free end).
    pub(crate) fn frames(&self, nodes: &[Point3<f64>], twist: f64) -> Vec<Rotation3<f64>> {
        let count = self.sub_segments;
        let edges: Vec<Vector3<f64>> = nodes
            .windows(2)
            .map(|w| (w[1] - w[0]).normalize())
            .collect();
        let mut frames = Vec::with_capacity(count + 1);
        frames.push(self.start.rotation.to_rotation_matrix());
        let mut normal = self.start.rotation * Vector3::x();
        let mut tangent = self.start_axis();
        for k in 1..=count {
            let incoming = edges[k - 1];
            normal = parallel_transport(&normal, &tangent, &incoming);
            tangent = incoming;
            let node_tangent = match edges.get(k) {
                Some(outgoing) if k < count => (incoming + outgoing).normalize(),
                _ => incoming,
            };
            let node_normal = parallel_transport(&normal, &tangent, &node_tangent);
            let turn = Rotation3::from_axis_angle(
                &Unit::new_unchecked(node_tangent),
                twist * k as f64 / count as f64,
            );
            frames.push(frame_from(&node_tangent, &(turn * node_normal)));
        }
        if let (Some(end), Some(last)) = (&self.end, frames.last_mut()) {
            *last = end.rotation.to_rotation_matrix();
        }
        frames
    }
}

/// The edge a joint side stands for (a guide axis has the pitch as a nominal length; its
/// derivatives are never used).
fn side_edge(side: Side, edges: &[Edge]) -> Edge {
    match side {
        Side::Cable(i) => edges[i],
        Side::Guide(axis, _) => Edge {
            unit: axis,
            length: 1.0,
        },
    }
}

/// The bending of a joint between `sides` with edges `edges`: a swivel clamp's joint bends
/// only beyond its cone ([`cone_bending`]), every other the cable's way ([`bending`]).
fn joint_bending(
    sides: (Side, Side),
    (a, b): (&Edge, &Edge),
    stiffness: f64,
    with_hessian: bool,
) -> EdgePairDerivatives {
    match sides {
        (Side::Guide(_, Hold::Swivel { cone_rad }), _)
        | (_, Side::Guide(_, Hold::Swivel { cone_rad })) => {
            cone_bending(a, b, stiffness, cone_rad, with_hessian)
        }
        _ => bending(a, b, stiffness, with_hessian),
    }
}

/// The rotation with columns `normal` (made perpendicular), `tangent × normal`, `tangent`.
fn frame_from(tangent: &Vector3<f64>, normal: &Vector3<f64>) -> Rotation3<f64> {
    let normal = (normal - normal.dot(tangent) * tangent).normalize();
    let binormal = tangent.cross(&normal);
    Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[normal, binormal, *tangent]))
}

/// `v` rotated by the smallest rotation that takes unit `from` to unit `to` (they must not
/// be opposite: the result is then non-finite, and the energy with it).
pub(crate) fn parallel_transport(
    v: &Vector3<f64>,
    from: &Vector3<f64>,
    to: &Vector3<f64>,
) -> Vector3<f64> {
    // Rodrigues' formula with axis·sin = from × to and cos = from·to, free of trigonometry.
    let axis = from.cross(to);
    let cosine = from.dot(to);
    cosine * v + axis.cross(v) + axis.dot(v) / (1.0 + cosine) * axis
}

/// `angle + 2πk` closest to `reference`.
fn unwrap_near(angle: f64, reference: f64) -> f64 {
    let turns = ((reference - angle) / std::f64::consts::TAU).round();
    angle + turns * std::f64::consts::TAU
}

/// `v` emptied and refilled with `n` zeros, keeping its allocation.
fn reset(v: &mut Vec<f64>, n: usize) {
    v.clear();
    v.resize(n, 0.0);
}

/// Collects gradient entries and Hessian blocks, mapped from nodes onto free nodes.
struct Assembly<'a> {
    rod: &'a Rod,
    gradient: &'a mut [f64],
    /// `∂Ψ/∂x`; empty for a free end.
    twist_gradient: &'a mut [f64],
    hessian: Option<&'a mut SymmetricBand>,
}

/// Adds `g` to node `node`'s three coordinates of `target` (a vector over the free
/// coordinates), if the node is free.
#[inline]
fn add_at_node(rod: &Rod, target: &mut [f64], node: usize, g: &Vector3<f64>) {
    if let Some(i) = rod.free_index(node) {
        for (slot, value) in target[3 * i..3 * i + 3].iter_mut().zip(g.iter()) {
            *slot += value;
        }
    }
}

/// The symmetric part of a block.
fn symmetric(block: &Matrix3<f64>) -> Matrix3<f64> {
    0.5 * (block + block.transpose())
}

impl Assembly<'_> {
    #[inline]
    fn add_node_gradient(&mut self, node: usize, g: &Vector3<f64>) {
        add_at_node(self.rod, self.gradient, node, g);
    }

    /// Adds the node block `(p, q)`, `p ≥ q`, of a symmetric Hessian (both nodes free, else
    /// nothing: clamped nodes carry no unknowns).
    #[inline]
    fn add_hessian_block(&mut self, p: usize, q: usize, block: &Matrix3<f64>) {
        let (rod, Some(hessian)) = (self.rod, self.hessian.as_deref_mut()) else {
            return;
        };
        if let (Some(r), Some(c)) = (rod.free_index(p), rod.free_index(q)) {
            hessian.add_lower_block(r, c, block);
        }
    }

    /// Adds a joint's gradient and (symmetrized) Hessian. A cable edge `i` is
    /// `x_(i+1) − x_i`, so `∂/∂x_i = −∂/∂e`, `∂/∂x_(i+1) = +∂/∂e`; a guide side carries no
    /// unknowns. The twist part of a joint's Hessian is not symmetric on its own (the
    /// reference twist is not a function of the joint's edges alone); the whole Hessian is,
    /// so its symmetric part is assembled.
    fn add_joint(&mut self, a: Side, b: Side, d: &EdgePairDerivatives) {
        match (a, b) {
            (Side::Cable(p), Side::Cable(_)) => {
                self.add_node_gradient(p, &-d.grad_a);
                self.add_node_gradient(p + 1, &(d.grad_a - d.grad_b));
                self.add_node_gradient(p + 2, &d.grad_b);
                if self.hessian.is_none() {
                    return;
                }
                let (aa, ab, ba, bb) = (d.hess_aa, d.hess_ab, d.hess_ba, d.hess_bb);
                // Node blocks H_uv of nodes p, p + 1, p + 2 (u, v = 0, 1, 2).
                let (h01, h10) = (ab - aa, ba - aa);
                let (h12, h21) = (ab - bb, ba - bb);
                self.add_hessian_block(p, p, &symmetric(&aa));
                self.add_hessian_block(p + 1, p, &(0.5 * (h10 + h01.transpose())));
                self.add_hessian_block(p + 2, p, &(-0.5 * (ba + ab.transpose())));
                self.add_hessian_block(p + 1, p + 1, &symmetric(&(aa - ab - ba + bb)));
                self.add_hessian_block(p + 2, p + 1, &(0.5 * (h21 + h12.transpose())));
                self.add_hessian_block(p + 2, p + 2, &symmetric(&bb));
            }
            (Side::Cable(i), Side::Guide(..)) => self.add_edge_terms(i, &d.grad_a, &d.hess_aa),
            (Side::Guide(..), Side::Cable(i)) => self.add_edge_terms(i, &d.grad_b, &d.hess_bb),
            (Side::Guide(..), Side::Guide(..)) => {}
        }
    }

    /// Gradient `g` and Hessian block `h` with respect to edge `i` onto its two nodes.
    fn add_edge_terms(&mut self, i: usize, g: &Vector3<f64>, h: &Matrix3<f64>) {
        self.add_node_gradient(i, &-g);
        self.add_node_gradient(i + 1, g);
        if self.hessian.is_some() {
            let block = symmetric(h);
            self.add_hessian_block(i, i, &block);
            self.add_hessian_block(i + 1, i, &-block);
            self.add_hessian_block(i + 1, i + 1, &block);
        }
    }

    /// Adds a joint's reference-twist gradient to `∂Ψ/∂x`.
    fn add_twist_gradient(&mut self, a: Side, b: Side, d: &EdgePairDerivatives) {
        for (side, g) in [(a, d.grad_a), (b, d.grad_b)] {
            if let Side::Cable(i) = side {
                add_at_node(self.rod, self.twist_gradient, i, &-g);
                add_at_node(self.rod, self.twist_gradient, i + 1, &g);
            }
        }
    }
}
