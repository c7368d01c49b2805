//! A piece of cable through a swivel clamp between its two end clamps: one cable, continuous
//! through the clamp, one of its nodes held there ([`Pin`]). The clamp takes force and no
//! moment (its direction turns with the cable's within its cone) and lets the cable turn
//! about its axis, so the piece's bending passes from one side to the other and its twist
//! is that of the whole piece between the end clamps.

use super::{Equilibrium, FarEnd, Pin, RodParameters, SolverOptions, StaticSolver, StaticsError};
use crate::geometry::{connect, sag_direction};
use crate::pose::Pose;
use crate::setup::SwivelSplit;
use nalgebra::Point3;

/// A swivel clamp between two pieces, where the cable runs through it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwivelThrough {
    /// The clamp's pose: the cable passes through its origin, the cone about its +z.
    pub clamp: Pose,
    /// Half-angle of the cone (rad).
    pub cone_rad: f64,
    /// Sub-segments before the clamp and after it.
    pub sub_segments: (usize, usize),
}

impl SwivelThrough {
    /// The swivel at `clamp` on a piece of `sub_segments`, held where `split` says.
    pub fn new(clamp: Pose, split: &SwivelSplit, sub_segments: usize) -> SwivelThrough {
        SwivelThrough {
            clamp,
            cone_rad: split.cone_rad,
            sub_segments: (split.before, sub_segments.saturating_sub(split.before)),
        }
    }

    /// How it holds the piece's node at the clamp.
    pub fn pin(&self) -> Pin {
        Pin::held_by(&self.clamp, self.sub_segments.0, self.cone_rad)
    }
}

/// The equilibrium of the piece from the clamp `start` through `swivel` to the clamp `end`
/// at the cable's pitch (`params.pitch_m`), and the static solves it took: from `warm`
/// (`S + 1` nodes, e.g. the previous pose's, carried along) when given and it converges,
/// else from the connected geometry of either side joined at the clamp along its axis.
pub fn solve_through_swivel(
    solver: &mut StaticSolver,
    params: &RodParameters,
    (start, swivel, end): (&Pose, &SwivelThrough, &Pose),
    warm: Option<&[Point3<f64>]>,
    options: &SolverOptions,
) -> Result<(Equilibrium, usize), StaticsError> {
    let (before, after) = swivel.sub_segments;
    if before == 0 || after == 0 {
        return Err(StaticsError::InvalidInput {
            what: "each side of a swivel clamp between two pieces needs sub-segments".into(),
        });
    }
    let pin = swivel.pin();
    let far = FarEnd::Clamped(*end);
    let warm = warm.filter(|n| n.len() == before + after + 1);
    if let Some(nodes) = warm
        && let Ok(solved) =
            solver.solve_pinned(params, (start, Some(&pin), &far), nodes, None, options)
    {
        return Ok((solved, 1));
    }
    let sag = sag_direction(&params.gravity_m_s2);
    let side = |(a, b): (&Pose, &Pose), n: usize| {
        connect(a, b, n, params.pitch_m, &sag).map_err(|e| StaticsError::InvalidInput {
            what: format!(
                "no start shape for {:.4} m of cable to or from the swivel clamp: {e}",
                n as f64 * params.pitch_m
            ),
        })
    };
    let first = side((start, &swivel.clamp), before)?;
    let second = side((&swivel.clamp, end), after)?;
    let nodes: Vec<Point3<f64>> = (first.nodes.iter())
        .chain(second.nodes.iter().skip(1))
        .copied()
        .collect();
    let solved = solver.solve_pinned(params, (start, Some(&pin), &far), &nodes, None, options)?;
    Ok((solved, 1 + usize::from(warm.is_some())))
}
