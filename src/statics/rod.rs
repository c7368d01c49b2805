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
//!   end (the masses at clamped nodes do no work).
//!
//! The twist couples every node with every other through `Ψ`: its Hessian is the banded
//! `(kt/S) Ψ ∇²Ψ` plus the rank-one `(kt/S) ∇Ψ ∇Ψᵀ`, which the Newton step handles by
//! Sherman–Morrison so that the linear algebra stays banded.

use nalgebra::{Matrix3, Point3, Rotation3, Unit, Vector3};

use super::banded::SymmetricBand;
use super::joint::{Edge, EdgePairDerivatives, bending, reference_twist};
use super::retract::restore_lengths;
use crate::cable::CableSpec;
use crate::pose::Pose;

/// Material and load parameters of the discrete cable model (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodParameters {
    /// Sub-segment pitch `l` (m).
    pub pitch_m: f64,
    /// Bending spring per joint `kb` (N·m/rad).
    pub bending_stiffness_nm_per_rad: f64,
    /// Torsion spring per joint `kt` (N·m/rad).
    pub torsion_stiffness_nm_per_rad: f64,
    /// Axial stiffness `EA` (N).
    pub axial_stiffness_n: f64,
    /// Mass per length `ρ` (kg/m).
    pub mass_per_length_kg_m: f64,
    /// Gravitational acceleration (m/s²), e.g. `(0, 0, −9.81)` with z up.
    pub gravity_m_s2: Vector3<f64>,
}

impl RodParameters {
    /// The discrete model of `cable` under `gravity_m_s2`.
    pub fn new(cable: &CableSpec, gravity_m_s2: Vector3<f64>) -> Self {
        Self {
            pitch_m: cable.sub_segment_pitch_m,
            bending_stiffness_nm_per_rad: cable.bending_stiffness_nm_per_rad,
            torsion_stiffness_nm_per_rad: cable.torsion_stiffness_nm_per_rad,
            axial_stiffness_n: cable.axial_stiffness_n,
            mass_per_length_kg_m: cable.mass_per_length_kg_m,
            gravity_m_s2,
        }
    }
}

/// One side of a joint: a cable edge (by index) or a guide axis (fixed unit vector).
#[derive(Debug, Clone, Copy)]
enum Side {
    Cable(usize),
    Guide(Vector3<f64>),
}

/// A segment's boundary conditions and parameters; evaluates energies of node sets.
#[derive(Debug, Clone)]
pub(crate) struct Rod {
    params: RodParameters,
    start: Pose,
    /// The end guide; `None` for a free end.
    end: Option<Pose>,
    sub_segments: usize,
}

/// The potential energy of a shape, term by term (J).
#[derive(Debug, Clone, Copy, PartialEq)]
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
#[derive(Debug, Clone)]
pub(crate) struct Evaluation {
    pub(crate) energy: f64,
    pub(crate) terms: EnergyTerms,
    /// `∂E/∂x` over the free coordinates (N).
    pub(crate) gradient: Vec<f64>,
    /// Total twist Ψ (rad), on the branch nearest the reference passed in.
    pub(crate) twist: f64,
    /// `∂Ψ/∂x` over the free coordinates (1/m); empty for a free end.
    pub(crate) twist_gradient: Vec<f64>,
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
        }
    }

    /// Number of free nodes: interior nodes, plus the last node for a free end.
    pub(crate) fn free_nodes(&self) -> usize {
        self.sub_segments - usize::from(self.end.is_some())
    }

    /// Twist stiffness of the whole segment `kt / S` (N·m/rad); 0 for a free end.
    pub(crate) fn twist_stiffness(&self) -> f64 {
        if self.end.is_some() {
            self.params.torsion_stiffness_nm_per_rad / self.sub_segments as f64
        } else {
            0.0
        }
    }

    pub(crate) fn params(&self) -> &RodParameters {
        &self.params
    }

    /// All `S + 1` nodes: the clamped ones and the free coordinates `x`.
    pub(crate) fn nodes(&self, x: &[f64]) -> Vec<Point3<f64>> {
        let mut nodes = Vec::with_capacity(self.sub_segments + 1);
        nodes.push(Point3::from(self.start.translation.vector));
        nodes.extend(x.chunks_exact(3).map(|c| Point3::new(c[0], c[1], c[2])));
        if let Some(end) = &self.end {
            nodes.push(Point3::from(end.translation.vector));
        }
        nodes
    }

    /// Free coordinates of a full node list (`S + 1` nodes).
    pub(crate) fn free_coordinates(&self, nodes: &[Point3<f64>]) -> Vec<f64> {
        nodes[1..=self.free_nodes()]
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .collect()
    }

    /// `x + step · direction`, moved back onto the edge lengths the linearized step
    /// predicts (module `retract`); unretracted if that fails.
    pub(crate) fn retracted_step(&self, x: &[f64], direction: &[f64], step: f64) -> Vec<f64> {
        let trial: Vec<f64> = x.iter().zip(direction).map(|(x, d)| x + step * d).collect();
        let nodes = self.nodes(x);
        let moves = self.nodes(direction);
        let mut targets = Vec::with_capacity(self.sub_segments);
        for i in 0..self.sub_segments {
            let edge = nodes[i + 1] - nodes[i];
            let mut change = Vector3::zeros();
            for (node, sign) in [(i + 1, 1.0), (i, -1.0)] {
                if self.free_index(node).is_some() {
                    change += sign * moves[node].coords;
                }
            }
            targets.push(edge.norm() + step * edge.normalize().dot(&change));
        }
        let free: Vec<bool> = (0..=self.sub_segments)
            .map(|k| self.free_index(k).is_some())
            .collect();
        let mut trial_nodes = self.nodes(&trial);
        if restore_lengths(&mut trial_nodes, &targets, &free) {
            self.free_coordinates(&trial_nodes)
        } else {
            trial
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
        let nodes = self.nodes(x);
        let edges: Vec<Edge> = nodes.windows(2).map(|w| Edge::new(w[1] - w[0])).collect();
        let mut assembly = Assembly::new(self, hessian);
        let twist = match &self.end {
            Some(end) => unwrap_near(self.transported_twist(&edges, end), twist_reference),
            None => 0.0,
        };
        let stretch = self.add_stretch(&edges, &mut assembly);
        let (bend, twist_gradient) = self.add_joints(&edges, twist, &mut assembly);
        let gravity = self.add_gravity(&nodes, &mut assembly);
        let terms = EnergyTerms {
            stretch_j: stretch,
            bending_j: bend,
            twist_j: 0.5 * self.twist_stiffness() * twist * twist,
            gravity_j: gravity,
        };
        Evaluation {
            energy: terms.total_j(),
            terms,
            gradient: assembly.gradient,
            twist,
            twist_gradient,
        }
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
            assembly.add_edge_gradient(i, &(k * extension * edge.unit));
            if assembly.wants_hessian() {
                let along = edge.unit * edge.unit.transpose();
                let across = Matrix3::identity() - along;
                let block = k * (along + (extension / edge.length) * across);
                assembly.add_edge_hessian(i, i, &block);
            }
        }
        energy
    }

    /// The joints in order: (incoming side, outgoing side, is a guide joint).
    fn joints(&self, edges: &[Edge]) -> Vec<(Side, Side, bool)> {
        let count = edges.len();
        let mut joints = Vec::with_capacity(count + 1);
        joints.push((Side::Guide(self.start_axis()), Side::Cable(0), true));
        joints.extend((1..count).map(|j| (Side::Cable(j - 1), Side::Cable(j), false)));
        if let Some(end) = &self.end {
            let axis = end.rotation * Vector3::z();
            joints.push((Side::Cable(count - 1), Side::Guide(axis), true));
        }
        joints
    }

    /// Adds every joint's bending and, with a clamped end, twist (`k Ψ ∇Ψ` and the banded
    /// `k Ψ ∇²Ψ`) in one pass; returns the bending energy and `∂Ψ/∂x`.
    fn add_joints(&self, edges: &[Edge], twist: f64, assembly: &mut Assembly) -> (f64, Vec<f64>) {
        let kb = self.params.bending_stiffness_nm_per_rad;
        let twist_scale = self.twist_stiffness() * twist;
        let mut twist_gradient = Assembly::new(self, None);
        let mut energy = 0.0;
        for (incoming, outgoing, at_guide) in self.joints(edges) {
            let stiffness = if at_guide { 2.0 * kb } else { kb };
            let (a, b) = (side_edge(incoming, edges), side_edge(outgoing, edges));
            let mut derivatives = bending(&a, &b, stiffness);
            energy += derivatives.value;
            if self.end.is_some() {
                let twist_derivatives = reference_twist(&a, &b);
                twist_gradient.add_pair(incoming, outgoing, &twist_derivatives, 1.0);
                derivatives.add_scaled(&twist_derivatives, twist_scale);
            }
            assembly.add_pair(incoming, outgoing, &derivatives, 1.0);
        }
        (energy, twist_gradient.gradient)
    }

    fn add_gravity(&self, nodes: &[Point3<f64>], assembly: &mut Assembly) -> f64 {
        let node_mass = self.params.mass_per_length_kg_m * self.params.pitch_m;
        let mut energy = 0.0;
        for (k, node) in nodes.iter().enumerate() {
            if self.free_index(k).is_none() {
                continue;
            }
            let mass = if k == self.sub_segments {
                0.5 * node_mass
            } else {
                node_mass
            };
            let weight = mass * self.params.gravity_m_s2;
            energy -= weight.dot(&node.coords);
            assembly.add_node_gradient(k, &-weight);
        }
        energy
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
        Side::Guide(axis) => Edge {
            unit: axis,
            length: 1.0,
        },
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

/// Collects gradient entries and Hessian blocks given per edge, mapped onto free nodes.
struct Assembly<'a> {
    rod: &'a Rod,
    gradient: Vec<f64>,
    hessian: Option<&'a mut SymmetricBand>,
}

impl<'a> Assembly<'a> {
    fn new(rod: &'a Rod, hessian: Option<&'a mut SymmetricBand>) -> Self {
        Self {
            rod,
            gradient: vec![0.0; 3 * rod.free_nodes()],
            hessian,
        }
    }

    fn wants_hessian(&self) -> bool {
        self.hessian.is_some()
    }

    fn add_node_gradient(&mut self, node: usize, g: &Vector3<f64>) {
        if let Some(i) = self.rod.free_index(node) {
            for (slot, value) in self.gradient[3 * i..3 * i + 3].iter_mut().zip(g.iter()) {
                *slot += value;
            }
        }
    }

    /// `∂/∂e_i` becomes `+` on node `i + 1` and `−` on node `i`.
    fn add_edge_gradient(&mut self, edge: usize, g: &Vector3<f64>) {
        self.add_node_gradient(edge + 1, g);
        self.add_node_gradient(edge, &-g);
    }

    fn add_edge_hessian(&mut self, p: usize, q: usize, block: &Matrix3<f64>) {
        let (rod, Some(hessian)) = (self.rod, self.hessian.as_deref_mut()) else {
            return;
        };
        for (row_node, row_sign) in [(p + 1, 1.0), (p, -1.0)] {
            for (column_node, column_sign) in [(q + 1, 1.0), (q, -1.0)] {
                if let (Some(r), Some(c)) = (rod.free_index(row_node), rod.free_index(column_node))
                {
                    hessian.add_node_block(r, c, &(row_sign * column_sign * block));
                }
            }
        }
    }

    /// Adds `scale ×` the derivatives of a joint function; guide sides carry no unknowns.
    fn add_pair(&mut self, a: Side, b: Side, d: &EdgePairDerivatives, scale: f64) {
        let sides = [(a, d.grad_a), (b, d.grad_b)];
        for (side, gradient) in sides {
            if let Side::Cable(i) = side {
                self.add_edge_gradient(i, &(scale * gradient));
            }
        }
        if !self.wants_hessian() {
            return;
        }
        let blocks = [
            (a, a, d.hess_aa),
            (a, b, d.hess_ab),
            (b, a, d.hess_ba),
            (b, b, d.hess_bb),
        ];
        for (row, column, block) in blocks {
            if let (Side::Cable(p), Side::Cable(q)) = (row, column) {
                self.add_edge_hessian(p, q, &(scale * block));
            }
        }
    }
}
