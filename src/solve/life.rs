//! The predicted life of a path from its motion tests: every motion's damage, weighted by how
//! often it runs — what the report states and what a life goal asks of a chain.

use super::options::LifeGoal;
use super::search::Tried;
use crate::life::curve::LifeCurve;
use crate::life::estimate::{CableLife, MotionDamage};
use crate::motion_test::MotionTestReport;
use crate::setup::Setup;
use crate::text_table::count_words;

/// The life of a path from its motions' runs (`runs`: per motion its cycles per hour and its
/// motion test); `None` without a life curve for the cable, or when a motion's test did not
/// pass whole (an axis-range grid, a failure before the end).
pub(super) fn path_life<'r>(
    setup: &Setup,
    runs: impl Iterator<Item = (Option<f64>, Option<&'r MotionTestReport>)>,
) -> Option<CableLife> {
    let curve = LifeCurve::of(&setup.cable.datasheet)?;
    let runs: Vec<(Option<f64>, &MotionTestReport)> = runs
        .map(|(rate, test)| Some((rate, test.filter(|t| t.passed && !t.damage.is_empty())?)))
        .collect::<Option<_>>()?;
    let tables: Vec<Vec<_>> = (runs.iter())
        .map(|(_, test)| {
            let pieces = test.damage.iter();
            pieces
                .map(|d| (d.segment, d.segment_name.as_str(), &d.damage))
                .collect()
        })
        .collect();
    let damages: Vec<MotionDamage<'_>> = (runs.iter().zip(&tables))
        .map(|((rate, _), pieces)| MotionDamage {
            cycles_per_hour: *rate,
            pieces,
        })
        .collect();
    CableLife::of(&curve, &damages, setup.cable.sub_segment_pitch_m * 1e3)
}

/// What a life goal makes of the chains that hold every limit, in the order the search
/// offers them (non-decreasing length).
///
/// A chain's life is its weakest piece's (the pieces between clamps move independently), so
/// every chain with the weakest piece of a chain judged lives no longer than it: that piece
/// goes, and the search goes on — exactly as it does with a piece that failed a limit.
#[derive(Debug, Default)]
pub(super) struct Goals {
    /// The longest-lived chain so far (index among those tried), for [`LifeGoal::Longest`].
    pub best: Option<usize>,
    best_cycles: f64,
    /// The longest chain [`LifeGoal::Longest`] considers (mm): the first passing one's
    /// length plus the window.
    limit_mm: Option<f64>,
}

/// A life goal's verdict on a chain that held every limit.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum LifeVerdict {
    /// It is the answer.
    Meets,
    /// It lives too short: why, and its weakest piece's segment.
    Falls(String, Option<usize>),
    /// A candidate for the longest life: its cycles and its weakest piece's segment.
    Candidate(f64, Option<usize>),
}

/// What the search does after a life verdict.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum GoalStep {
    /// The chain tried at this index is the answer.
    Answer(usize),
    /// On, without the chain's weakest piece (of this segment).
    GoOn(Option<usize>),
}

impl Goals {
    /// `goal`'s verdict on a chain of `length_mm` that held every limit, with its predicted
    /// `life` (`None`: not predicted).
    pub fn judge(
        &mut self,
        goal: LifeGoal,
        life: Option<&CableLife>,
        length_mm: f64,
    ) -> LifeVerdict {
        let Some(life) = life else {
            return LifeVerdict::Falls("held every limit, but no life was predicted".into(), None);
        };
        let weakest = Some(life.weakest.segment);
        let cycles = life.cycles_to_failure;
        match goal {
            LifeGoal::AtLeast { cycles: asked } if cycles >= asked => LifeVerdict::Meets,
            LifeGoal::AtLeast { cycles: asked } => LifeVerdict::Falls(
                format!(
                    "held every limit, but its predicted life is {} cycles, below the {} asked \
                     (first at {}, {:.0} mm from its start)",
                    count_words(cycles),
                    count_words(asked),
                    life.weakest.segment_name,
                    life.weakest.from_start_mm
                ),
                weakest,
            ),
            LifeGoal::Longest { within_mm } => {
                self.limit_mm.get_or_insert(length_mm + within_mm);
                LifeVerdict::Candidate(cycles, weakest)
            }
        }
    }

    /// Whether a chain of `length_mm` is beyond the window [`LifeGoal::Longest`] considers.
    pub fn beyond(&self, length_mm: f64) -> bool {
        self.limit_mm.is_some_and(|limit| length_mm > limit + 1e-9)
    }

    /// Records `verdict` on chain `index` of `tried` (why one that held every limit is not
    /// the answer) and says what the search does next.
    pub fn after(&mut self, verdict: LifeVerdict, index: usize, tried: &mut [Tried]) -> GoalStep {
        match verdict {
            LifeVerdict::Meets => GoalStep::Answer(index),
            LifeVerdict::Falls(why, weakest) => {
                tried[index].short_lived = Some(why);
                GoalStep::GoOn(weakest)
            }
            LifeVerdict::Candidate(cycles, weakest) => {
                let better = self.best.is_none() || cycles > self.best_cycles;
                let loser = if better {
                    self.best.replace(index)
                } else {
                    Some(index)
                };
                if better {
                    self.best_cycles = cycles;
                }
                if let Some(loser) = loser {
                    let own = tried[loser].life_cycles.unwrap_or(f64::NAN);
                    tried[loser].short_lived = Some(format!(
                        "held every limit; its predicted life of {} cycles is not the longest \
                         within the window (rank {}: {} cycles)",
                        count_words(own),
                        self.best.map_or(0, |b| b + 1),
                        count_words(self.best_cycles)
                    ));
                }
                GoalStep::GoOn(weakest)
            }
        }
    }
}
