//! How a piece's equilibrium is started: from the connected geometry, from the same clamps'
//! shorter lengths at the same pose (continuation over lengths), or from the previous poses
//! of a sweep. The warm start decides which equilibrium Newton finds where a piece has two, so
//! its rules are what keeps a verdict independent of what else is asked
//! (docs/architecture.md, "Attachment test").

use super::evaluate::{ClampTurns, ConnectMethod, Evaluator, Scene, Solved, Warm};
use super::verdict::{Check, Rejection, connect_failure};
use crate::geometry::{connect, reaches, sag_direction};
use crate::pose::Pose;
use crate::statics::{FarEnd, Holds, RodParameters, StaticSolver, continuation};
use nalgebra::Point3;
use std::ops::Range;

impl Evaluator<'_> {
    /// Solves the `wanted` lengths (ascending, > 0) between the `declared` clamp poses (the
    /// end clamp turned by `turns`) in `scene`, in the [`continuation_chains`] that cover
    /// them, each chain by continuation from the connected geometry at its first length, and
    /// hands every length solved (wanted or not), its clamp poses, its check and its
    /// equilibrium (`None` when there is none) to `visit`.
    pub(super) fn continue_lengths(
        &self,
        solver: &mut StaticSolver,
        (m, holds): (usize, Holds),
        (declared, turns): (&(Pose, Pose), &ClampTurns),
        scene: &Scene<'_>,
        wanted: impl Iterator<Item = usize>,
        mut visit: impl FnMut(usize, &(Pose, Pose), &Check, Option<&Solved>),
    ) {
        let pitch = self.setup.cable.sub_segment_pitch_m;
        let chains = match self.method {
            // The rapier baseline relaxes every length from scratch: no chain to follow.
            ConnectMethod::Linear => wanted.map(|length| length..length + 1).collect(),
            ConnectMethod::Hermite => {
                let block = match self.setup.is_intra_link(m) {
                    true => CONTINUATION_BLOCK,
                    false => INTER_LINK_CONTINUATION_BLOCK,
                };
                continuation_chains(wanted, reaching(declared, pitch), block)
            }
        };
        for chain in chains {
            let mut earlier: Vec<Solved> = Vec::with_capacity(3);
            for length in chain {
                let guides = (declared.0, declared.1 * turns.at(self.setup, m, length));
                let (check, solved) =
                    self.next_length(solver, &mut earlier, (m, holds), &guides, length, scene);
                visit(length, &guides, &check, earlier.first().filter(|_| solved));
            }
        }
    }

    /// Checks the next length of a continuation over lengths at one pose: solved from
    /// `earlier` (the last solutions, the nearest first), which it then joins (`true`: it
    /// is `earlier`'s first); from the connected geometry when that fails.
    pub(super) fn next_length(
        &self,
        solver: &mut StaticSolver,
        earlier: &mut Vec<Solved>,
        (m, holds): (usize, Holds),
        guides: &(Pose, Pose),
        length: usize,
        scene: &Scene<'_>,
    ) -> (Check, bool) {
        let piece = (m, holds);
        let mut solved =
            self.solve_warm(solver, piece, guides, length, scene, Warm::Length(earlier));
        // A start shape carried over from other lengths can lead Newton astray where the
        // connected geometry would not: a failed warm solve is retried from it.
        let diverged = |r: &Result<Solved, Check>| {
            r.as_ref()
                .is_err_and(|c| c.rejection == Some(Rejection::Diverged))
        };
        if diverged(&solved) && !earlier.is_empty() {
            solved = self.solve_warm(solver, piece, guides, length, scene, Warm::Length(&[]));
        }
        match solved {
            Ok(solved) => {
                let check = self.judge(m, guides, &solved, scene);
                earlier.insert(0, solved);
                earlier.truncate(EXTRAPOLATION_POINTS);
                (check, true)
            }
            Err(check) => (check, false),
        }
    }

    /// The equilibrium of a piece of segment `m` held by its clamps as `holds` between
    /// `guides` with `sub_segments`, started from a neighbouring solution when `warm` has one
    /// (else from the connected geometry); the linear method always relaxes from scratch
    /// between rigid clamps (the paper's model, for comparison).
    pub(super) fn solve_warm(
        &self,
        solver: &mut StaticSolver,
        (m, holds): (usize, Holds),
        guides: &(Pose, Pose),
        sub_segments: usize,
        scene: &Scene<'_>,
        warm: Warm<'_>,
    ) -> Result<Solved, Check> {
        if self.setup.segments[m].through.is_some() {
            // A sweep starts from the previous pose's split or shape.
            let last = match warm {
                Warm::Poses([(last, _), ..]) => Some(last),
                _ => None,
            };
            return self.solve_through((m, holds), guides, (sub_segments, last), scene);
        }
        if self.method == ConnectMethod::Linear {
            self.count_static_solve(m);
            let nodes = self.relaxed(&guides.0, &guides.1, sub_segments, scene.gravity_m_s2)?;
            return Ok(Solved {
                nodes,
                connected: Vec::new(),
                twist_rad: 0.0,
                pitch_m: self.setup.cable.sub_segment_pitch_m,
                from: None,
                slid_m: None,
            });
        }
        let pitch = self.setup.cable.sub_segment_pitch_m;
        let (start_nodes, connected, twist) = match warm {
            Warm::Poses([(last, at), (second, second_at), ..]) => {
                let nodes = continuation::follow_guides_extrapolated(
                    (&last.nodes, (&at.0, &at.1)),
                    (&second.nodes, (&second_at.0, &second_at.1)),
                    (&guides.0, &guides.1),
                    pitch,
                );
                (nodes, Vec::new(), last.twist_rad)
            }
            Warm::Poses([(last, at)]) => {
                let nodes = continuation::follow_guides(
                    &last.nodes,
                    (&at.0, &at.1),
                    (&guides.0, &guides.1),
                    pitch,
                );
                (nodes, Vec::new(), last.twist_rad)
            }
            Warm::Length(earlier @ [nearest, _, ..]) => {
                reaches(&guides.0, &guides.1, sub_segments, pitch).map_err(connect_failure)?;
                let shapes: Vec<&[Point3<f64>]> = earlier
                    .iter()
                    .map(|solved| solved.nodes.as_slice())
                    .collect();
                let nodes = continuation::extrapolate_length(&shapes, sub_segments, pitch);
                (nodes, Vec::new(), nearest.twist_rad)
            }
            Warm::Length(earlier) => {
                let sag = sag_direction(&scene.gravity_m_s2);
                let connected = connect(&guides.0, &guides.1, sub_segments, pitch, &sag)
                    .map_err(connect_failure)?;
                match earlier
                    .first()
                    .filter(|nearest| !nearest.connected.is_empty())
                {
                    Some(nearest) => {
                        let nodes = continuation::change_length(
                            &nearest.nodes,
                            &nearest.connected,
                            &connected.nodes,
                            pitch,
                        );
                        (nodes, connected.nodes, nearest.twist_rad)
                    }
                    None => (
                        connected.nodes.clone(),
                        connected.nodes,
                        connected.twist_correction_rad,
                    ),
                }
            }
            Warm::Poses([]) => {
                let sag = sag_direction(&scene.gravity_m_s2);
                let connected = connect(&guides.0, &guides.1, sub_segments, pitch, &sag)
                    .map_err(connect_failure)?;
                (connected.nodes, Vec::new(), connected.twist_correction_rad)
            }
        };
        let rod = RodParameters {
            gravity_m_s2: scene.gravity_m_s2,
            holds,
            ..self.rod
        };
        self.count_static_solve(m);
        let solved = solver
            .solve(
                &rod,
                &guides.0,
                &FarEnd::Clamped(guides.1),
                &start_nodes,
                Some(twist),
                &self.solver,
            )
            .map_err(|e| Check::fail(Rejection::Diverged, e.to_string(), None))?;
        Ok(Solved {
            nodes: solved.nodes,
            connected,
            twist_rad: solved.twist_rad,
            pitch_m: pitch,
            from: None,
            slid_m: None,
        })
    }
}

/// Earlier lengths a start shape is extrapolated from: linearly through two. Measured on
/// the bundled pick-and-place attachment test, a quadratic through three took as many Newton
/// steps (3.16 per solve on average).
pub(super) const EXTRAPOLATION_POINTS: usize = 2;

/// Intra-link lengths are continued in blocks of this many sub-segments, `[32k, 32k + 32)`,
/// each started from the connected geometry at its first length that reaches between the
/// clamps: a piece's equilibrium then depends on its clamps, its length and gravity only —
/// not on which other lengths are asked for — so a dictionary built from any setup that
/// offers the clamps stores the equilibrium `solve --setup` finds. Measured on the
/// robot-level pick-and-place attachment test (one run each, on-the-fly intra-link part):
/// blocks of 8 27.3 s, 16 27.6 s, 32 23.5 s; one chain from the shortest length asked for
/// (not history-free) 26.3 s. Nearly taut lengths are slow to solve: blocks of 64 from
/// length 1 made the design-space tests 15 % slower than blocks of 32.
pub const CONTINUATION_BLOCK: usize = 32;

/// Inter-link lengths are continued in shorter blocks, `[4k, 4k + 4)`. No dictionary stores
/// them, so nothing ties them to [`CONTINUATION_BLOCK`]; what they need is only that a
/// verdict not depend on the other lengths asked for, so that the lazy search and the
/// exhaustive test agree. The lazy search asks for a few lengths of a pair at a time, and a
/// long block makes it solve every shorter length of the block first. Measured with the lazy
/// search on 2 cores (attachment test; static solves): blocks of 32, 16, 8, 4, 2 — inspection
/// 3.12 s, 2.94, 2.64, 2.59, 2.79 (89 332, 82 486, 62 925, 50 361, 42 474 solves); the UR5
/// robot-level setup 6.94 s, 6.43, 5.96, 5.22, 4.90; machine tending 0.77 s, 0.74, 0.65,
/// 0.65, 0.67. The exhaustive test pays for it: pick and place 14.3 s with blocks of 32,
/// 19.5 s with blocks of 4.
pub const INTER_LINK_CONTINUATION_BLOCK: usize = 4;

/// The continuation chains covering the `wanted` lengths (ascending, > 0) between clamps
/// that the shortest cable of `reaching` sub-segments reaches: each shorter (too short)
/// length alone; then per block of `block` lengths that holds one, every length from
/// the block's start (at least `reaching`) up to its longest wanted one.
fn continuation_chains(
    wanted: impl Iterator<Item = usize>,
    reaching: usize,
    block: usize,
) -> Vec<Range<usize>> {
    let mut chains: Vec<Range<usize>> = Vec::new();
    for length in wanted {
        if length < reaching {
            chains.push(length..length + 1);
            continue;
        }
        let start = (length / block * block).max(reaching);
        match chains.last_mut() {
            Some(chain) if chain.start == start => chain.end = chain.end.max(length + 1),
            _ => chains.push(start..length + 1),
        }
    }
    chains
}

/// The shortest cable (sub-segments) that reaches between clamps at `guides`.
fn reaching(guides: &(Pose, Pose), pitch_m: f64) -> usize {
    let distance = (guides.1.translation.vector - guides.0.translation.vector).norm();
    (distance / pitch_m).ceil().max(1.0) as usize
}
