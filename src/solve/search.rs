//! The search for the answer: the chains of pieces in non-decreasing length (decided up front,
//! or lazily in rounds), each offered to the static sweep and the motion test until one passes.

use super::certify::{Certification, Certified};
use super::chains::Chains;
use super::learn::{Learned, SetAside};
use super::life::{GoalStep, Goals, path_life};
use super::options::{SolveError, SolveOptions};
use super::sweep::{CellSweep, ChainSweep, Dropped};
use crate::attachment::{ConnectMethod, Evaluator, SegmentPoses, SweptLeast};
use crate::dictionary::MotionLookup;
use crate::life::estimate::CableLife;
use crate::motion::Cell;
use crate::motion_test::{self, MotionTestOptions, MotionTestReport, Violation};
use crate::path::{CablePath, Pv};
use crate::setup::Setup;
use std::time::Instant;

/// The motion tests over `chains`; with a dictionary's lookup (and the exact test it is
/// checked against), each chain certified before it is offered ([`Certified`]).
pub(super) fn search_chains(
    setup: &Setup,
    cell: &Cell,
    options: &SolveOptions,
    chains: &mut dyn Chains,
    certify: Option<(&Evaluator<'_>, &SegmentPoses, &MotionLookup<'_>)>,
) -> Result<(MotionSearch, Certification), SolveError> {
    let Some((evaluator, poses, lookup)) = certify else {
        let outcome = motion_tests(setup, cell, chains, options)?;
        return Ok((outcome, Certification::default()));
    };
    let mut certified = Certified::new(chains, evaluator, poses, lookup);
    let outcome = motion_tests(setup, cell, &mut certified, options)?;
    let certification = certified.certification;
    log::info!(
        "certified: {} stored pieces solved exactly, {} records contradicted",
        certification.pieces_solved,
        certification.disagreements.len()
    );
    Ok((outcome, certification))
}

/// One chain offered to the motion test.
pub(crate) struct Tried {
    /// The chain.
    pub path: CablePath,
    /// Per motion of the cell, its motion test; `None` where it did not run (an earlier
    /// motion failed); empty when the chain was not tested (`--no-motion-test`).
    pub runs: Vec<Option<MotionTestReport>>,
    /// The motion the chain is judged by: the one it failed, else the first.
    pub judged: Option<usize>,
    /// Its predicted life (cycles), when it held every limit and a life goal asked for it.
    pub life_cycles: Option<f64>,
    /// Why a chain that held every limit is not the answer: the life goal (`None`: it is,
    /// or it failed a limit).
    pub short_lived: Option<String>,
}

impl Tried {
    /// The motion test the chain is judged by (`None`: not tested).
    pub fn report(&self) -> Option<&MotionTestReport> {
        self.runs.get(self.judged?)?.as_ref()
    }

    /// It held every limit and the life goal: `None` when not tested.
    pub fn passed(&self) -> Option<bool> {
        self.report()
            .map(|r| r.passed && self.short_lived.is_none())
    }
}

/// What the search for d* did.
pub(crate) struct MotionSearch {
    /// The chains put to the dynamic test, in order.
    pub tried: Vec<Tried>,
    /// Index of the one that passed.
    pub winner: Option<usize>,
    /// Why the search stopped without one (empty otherwise).
    pub stop: String,
    /// It stopped because the budget of motion tests was spent, chains left.
    pub budget_spent: bool,
    /// Distinct motion poses of the static sweep (0 when it did not run).
    pub sweep_poses: usize,
    /// PVs swept.
    pub swept: usize,
    /// PVs the sweep dropped, in the order found.
    pub dropped: Vec<Dropped>,
    /// Wall time spent sweeping (s).
    pub sweep_s: f64,
    /// Wall time of the chain searches between motion tests (s), attachment tests a lazy
    /// search ran for them not included.
    pub chain_s: f64,
    /// Wall time of the dynamic motion tests (s).
    pub motion_test_s: f64,
    /// The swings learned from the failed motion tests.
    pub learned: Learned,
    /// Pieces set aside by a learned swing, in the order found.
    pub set_aside: Vec<SetAside>,
    /// The pieces set aside came back: no chain was left without them (from then on the
    /// search went on without learned margins), or the answer passed and they came back to
    /// find the shortest untried chain.
    pub set_aside_restored: bool,
    /// The answer passed with pieces set aside: the shortest chain with them of the pieces
    /// decided (sub-segments), when shorter than the answer — untried (a shorter one of
    /// pieces not yet decided may exist).
    pub shortest_untried: Option<usize>,
    /// When the budget was spent: the shortest chain left untested, pieces set aside
    /// included (`None`: no chain was left, or the budget was not spent).
    pub next_untried: Option<CablePath>,
}

impl MotionSearch {
    /// Nothing tried yet.
    pub(super) fn new() -> Self {
        MotionSearch {
            tried: Vec::new(),
            winner: None,
            stop: String::new(),
            budget_spent: false,
            sweep_poses: 0,
            swept: 0,
            dropped: Vec::new(),
            sweep_s: 0.0,
            chain_s: 0.0,
            motion_test_s: 0.0,
            learned: Learned::default(),
            set_aside: Vec::new(),
            set_aside_restored: false,
            shortest_untried: None,
            next_untried: None,
        }
    }

    fn stopped(mut self, stop: impl Into<String>) -> Self {
        self.stop = stop.into();
        self
    }
}

/// The search for d*: the shortest chain of what is left of D2 is swept statically (its
/// failing PVs dropped, then the next chain) and put to the dynamic motion test of every
/// motion of `cell`; after a failure that belongs to a segment, that segment's PV is dropped
/// and the search goes on, for at most `k_best` chains tested. Segments are independent
/// between clamps, so every chain with a failed PV fails too: this tries, in non-decreasing
/// length, exactly the chains of the k-best enumeration that contain no PV already seen
/// failing.
fn motion_tests(
    setup: &Setup,
    cell: &Cell,
    chains: &mut dyn Chains,
    options: &SolveOptions,
) -> Result<MotionSearch, SolveError> {
    let mut outcome = MotionSearch::new();
    if !options.motion_test {
        let path = timed_shortest(&mut outcome, chains)?;
        let untested = |path| Tried {
            path,
            runs: Vec::new(),
            judged: None,
            life_cycles: None,
            short_lived: None,
        };
        outcome.tried.extend(path.map(untested));
        outcome.winner = (!outcome.tried.is_empty()).then_some(0);
        return Ok(outcome);
    }
    // The sweep is a cheap static filter in front of the dynamic test: always the
    // quasi-static solver, whatever the attachment test used.
    let evaluator = Evaluator::new(setup, ConnectMethod::Hermite)?;
    let test_options = test_options(setup, options);
    let mut sweep = match options.static_sweep {
        true => Some(CellSweep::new(&evaluator, setup, cell, &test_options)?),
        false => None,
    };
    outcome.sweep_poses = sweep.as_ref().map_or(0, CellSweep::pose_count);
    // The motions in the order they are tried: the last one a chain failed first, as the
    // likeliest to fail the next chain too.
    // An axis-range grid is a list of static poses: the attachment test's, never simulated.
    let mut order: Vec<usize> = (0..cell.len())
        .filter(|&i| cell.motions[i].grid.is_none())
        .collect();
    let first_simulated = order.first().copied().unwrap_or(0);
    let mut test = |path: &CablePath| -> Result<Tested, SolveError> {
        let mut runs: Vec<Option<MotionTestReport>> = vec![None; cell.len()];
        for &i in &order.clone() {
            let report = motion_test::run(setup, path, &cell.motions[i].motion, &test_options)?;
            let failed = !report.passed;
            runs[i] = Some(report);
            if failed {
                order.retain(|&k| k != i);
                order.insert(0, i);
                return Ok(Tested::of(runs, i, cell));
            }
        }
        let mut tested = Tested::of(runs, first_simulated, cell);
        if options.life_goal.is_some() {
            let runs = (cell.motions.iter().zip(&tested.runs))
                .map(|(m, run)| (m.cycles_per_hour, run.as_ref()));
            tested.life = path_life(setup, runs);
        }
        Ok(tested)
    };
    let sweep = sweep.as_mut().map(|s| s as &mut dyn ChainSweep);
    try_chains(setup, chains, options, sweep, &mut test, outcome)
}

/// The motion test as a solve runs it, and `check` after it: stopping at the first violation
/// only shortens failing runs (a passing path is simulated through the whole motion either
/// way, series included), so a path checked gives the margins its solve reported.
pub(super) fn test_options(setup: &Setup, options: &SolveOptions) -> MotionTestOptions {
    MotionTestOptions {
        stop_at_first_violation: true,
        shape_interval_s: options.shape_interval_s,
        ..MotionTestOptions::new(options.engine.with_defaults(setup.gravity_m_s2))
    }
}

/// What one motion test said, as the search needs it.
pub(super) struct Tested {
    /// The chain held every limit over every motion.
    pub passed: bool,
    /// The segment its failure belongs to, if one.
    pub segment: Option<usize>,
    /// The first limit violated, if one.
    pub violation: Option<Violation>,
    /// The motion whose test found it (the first motion when the chain passed).
    pub motion: usize,
    /// For people: the failure, or `passed`.
    pub reason: String,
    /// Per motion, its whole report (kept with the chain tried; empty for a test that
    /// keeps none).
    pub runs: Vec<Option<MotionTestReport>>,
    /// Its predicted life, when it passed and a life goal asked for it.
    pub life: Option<CableLife>,
}

impl Tested {
    /// The verdict of `runs`, judged by motion `judged`'s (the one that failed, if one).
    fn of(runs: Vec<Option<MotionTestReport>>, judged: usize, cell: &Cell) -> Tested {
        let report = runs[judged].as_ref();
        let failure = report.and_then(|r| r.failure.as_ref());
        let reason = failure.map_or("passed".to_string(), |f| f.reason.clone());
        Tested {
            passed: report.is_some_and(|r| r.passed),
            segment: failure.and_then(|f| f.segment),
            violation: report.and_then(|r| r.first_violation.clone()),
            motion: judged,
            reason: match failure {
                Some(_) => cell.label(judged, &reason),
                None => reason,
            },
            runs,
            life: None,
        }
    }
}

/// The motion tests over `chains`, shortest first, each chain swept by `sweep` (when given)
/// before `test` simulates it; learning from failures as [`super::learn`] says unless
/// `options.learn` is off.
pub(super) fn try_chains(
    setup: &Setup,
    chains: &mut dyn Chains,
    options: &SolveOptions,
    mut sweep: Option<&mut dyn ChainSweep>,
    test: &mut dyn FnMut(&CablePath) -> Result<Tested, SolveError>,
    mut outcome: MotionSearch,
) -> Result<MotionSearch, SolveError> {
    let mut goals = Goals::default();
    while outcome.tried.len() < options.k_best {
        let path = timed_shortest(&mut outcome, chains)?;
        // Longest life: no chain longer than the shortest passing one plus the window.
        let beyond = |p: &CablePath| {
            let mm = p.total_sub_segments() as f64 * setup.cable.sub_segment_pitch_m * 1e3;
            goals.beyond(mm)
        };
        if let Some(best) = goals.best.filter(|_| path.as_ref().is_none_or(beyond)) {
            outcome.winner = Some(best);
            return Ok(outcome);
        }
        let Some(path) = path else {
            if outcome.set_aside.is_empty() || outcome.set_aside_restored {
                return Ok(
                    outcome.stopped("no chain is left of the robust pieces that did not fail it")
                );
            }
            // Only guesses stood in the way: every piece set aside comes back, untried.
            log::info!(
                "no chain is left without the {} pieces set aside by learned swings: they \
                 come back, and the search goes on without learned margins",
                outcome.set_aside.len()
            );
            restore_set_aside(&mut outcome, chains);
            continue;
        };
        if let Some(sweep) = sweep.as_deref_mut() {
            let learning = options.learn && !outcome.set_aside_restored;
            // A piece the learned swings will doubt needs no sweep past the pose that
            // decides it.
            let stops: Vec<Option<SweptLeast>> = path
                .pieces()
                .map(|(m, pv)| {
                    let needed = outcome.learned.needed(m, &pv, &setup.thresholds);
                    needed.filter(|_| learning)
                })
                .collect();
            let clock = Instant::now();
            let failed = sweep.failing(&path, &stops)?;
            outcome.sweep_s += clock.elapsed().as_secs_f64();
            outcome.swept = sweep.swept();
            if !failed.is_empty() {
                for (m, pv, failure) in &failed {
                    log::debug!(
                        "static sweep drops {} {pv:?}: {}",
                        setup.segment_name(*m),
                        failure.detail
                    );
                    chains.drop_piece(*m, pv);
                }
                outcome.dropped.extend(failed);
                continue;
            }
            if learning {
                let doubted = doubted_pieces(&*sweep, &outcome.learned, setup, &path);
                if !doubted.is_empty() {
                    for aside in &doubted {
                        log::debug!(
                            "set aside {} {:?}: {}",
                            setup.segment_name(aside.segment),
                            aside.pv,
                            aside.why
                        );
                        chains.drop_piece(aside.segment, &aside.pv);
                    }
                    outcome.set_aside.extend(doubted);
                    continue;
                }
            }
        }
        let clock = Instant::now();
        let tested = test(&path)?;
        outcome.motion_test_s += clock.elapsed().as_secs_f64();
        log::info!(
            "motion test {}: {:.0} mm, {}",
            outcome.tried.len() + 1,
            path.total_sub_segments() as f64 * setup.cable.sub_segment_pitch_m * 1e3,
            tested.reason
        );
        let mut failed_segment = tested.segment;
        let passed = tested.passed;
        let length_mm = path.total_sub_segments() as f64 * setup.cable.sub_segment_pitch_m * 1e3;
        // A life goal judges a chain that held every limit by its predicted life.
        let life_verdict = match (passed, options.life_goal, &tested.life) {
            (true, Some(goal), life) => Some(goals.judge(goal, life.as_ref(), length_mm)),
            _ => None,
        };
        if let (Some(sweep), Some(violation)) = (sweep.as_deref(), &tested.violation) {
            let m = violation.segment;
            for (_, pv) in path.pieces().filter(|&(segment, _)| segment == m) {
                if let Some(least) = sweep.least_in(tested.motion, m, &pv) {
                    outcome.learned.learn(m, &pv, violation, &least);
                }
            }
        }
        outcome.tried.push(Tried {
            path: path.clone(),
            judged: (!tested.runs.is_empty()).then_some(tested.motion),
            runs: tested.runs,
            life_cycles: tested.life.as_ref().map(|l| l.cycles_to_failure),
            short_lived: None,
        });
        let tried = outcome.tried.len() - 1;
        let judged_by_life = life_verdict.is_some();
        if let Some(verdict) = life_verdict {
            match goals.after(verdict, tried, &mut outcome.tried) {
                GoalStep::Answer(winner) => {
                    outcome.winner = Some(winner);
                    return Ok(outcome);
                }
                // Every chain with its weakest piece lives no longer: it goes.
                GoalStep::GoOn(weakest) => failed_segment = weakest,
            }
        }
        if passed && !judged_by_life {
            outcome.winner = Some(outcome.tried.len() - 1);
            if !outcome.set_aside.is_empty() && !outcome.set_aside_restored {
                // Say how much shorter a path with the pieces set aside could be.
                restore_set_aside(&mut outcome, chains);
                let shorter = (chains.shortest_known()?)
                    .map(|p| p.total_sub_segments())
                    .filter(|&s| s < path.total_sub_segments());
                outcome.shortest_untried = shorter;
            }
            return Ok(outcome);
        }
        let Some(m) = failed_segment else {
            return Ok(outcome.stopped("the last failure belongs to no single segment"));
        };
        for (_, failed) in path.pieces().filter(|&(segment, _)| segment == m) {
            chains.drop_piece(m, &failed);
        }
    }
    if let Some(best) = goals.best {
        outcome.winner = Some(best);
        return Ok(outcome);
    }
    let budget = options.k_best;
    outcome.budget_spent = true;
    if !outcome.set_aside.is_empty() && !outcome.set_aside_restored {
        restore_set_aside(&mut outcome, chains);
    }
    outcome.next_untried = timed_shortest(&mut outcome, chains)?;
    Ok(outcome.stopped(format!(
        "the budget of {budget} motion tests (--k-best) is spent"
    )))
}

/// The shortest chain, its search's time added to `outcome`.
fn timed_shortest(
    outcome: &mut MotionSearch,
    chains: &mut dyn Chains,
) -> Result<Option<CablePath>, SolveError> {
    let clock = Instant::now();
    let path = chains.shortest();
    outcome.chain_s += clock.elapsed().as_secs_f64();
    path
}

/// Puts every piece set aside back on the chains; learned margins set nothing aside from now.
fn restore_set_aside(outcome: &mut MotionSearch, chains: &mut dyn Chains) {
    for aside in &outcome.set_aside {
        chains.restore_piece(aside.segment, &aside.pv);
    }
    outcome.set_aside_restored = true;
}

/// The pieces of `path` whose static shapes keep a learned swing not inside the limits,
/// each with why.
fn doubted_pieces(
    sweep: &dyn ChainSweep,
    learned: &Learned,
    setup: &Setup,
    path: &CablePath,
) -> Vec<SetAside> {
    let doubt = |(m, pv): (usize, Pv)| {
        let least = sweep.least(m, &pv)?;
        let why = learned.doubt(m, &pv, &least, &setup.thresholds)?;
        Some(SetAside {
            segment: m,
            pv,
            why,
        })
    };
    path.pieces().filter_map(doubt).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attachment::{ConnectMethod, Evaluator, SegmentPoses};
    use crate::fixtures::{exhaustive_robust, narrow_pick_and_place};
    use crate::motion_test::{Constraint, Place};
    use crate::solve::LifeGoal;
    use crate::solve::chains::{Decided, chain_search};
    use std::collections::BTreeMap;

    /// A cable whose every piece has a least static bend radius over the motion and a swing
    /// below it in the motion test, both fixed numbers: the motion test of a chain fails at
    /// its first piece whose static radius minus swing is below the limit. Loops of one
    /// clamp pair swing alike (a pair's swing, ±10 % with the length); segments differ.
    struct Synthetic {
        limit_m: f64,
        least_m: BTreeMap<(usize, Pv), f64>,
        swing_m: BTreeMap<(usize, Pv), f64>,
        swept: usize,
    }

    /// A number in [0, 1) from `key`, the same on every machine.
    fn unit(key: &[usize]) -> f64 {
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for &k in key {
            h = (h ^ k as u64).wrapping_mul(0x0100_0000_01b3);
            h ^= h >> 29;
        }
        (h % 1_000_003) as f64 / 1_000_003.0
    }

    impl Synthetic {
        /// The cable of world `seed` over the pieces `d2`.
        fn over(d2: &[Vec<Pv>], limit_m: f64, seed: usize) -> Synthetic {
            let segment_swing_m = [3.0e-3, 2.0e-3, 3.5e-3];
            let mut least_m = BTreeMap::new();
            let mut swing_m = BTreeMap::new();
            for (m, pieces) in d2.iter().enumerate() {
                for pv in pieces {
                    let (s, a, b) = (pv.sub_segments, pv.start, pv.end);
                    least_m.insert((m, *pv), limit_m + 6e-3 * unit(&[seed, m, s, a, b]));
                    let pair = 0.5 + unit(&[seed, m, a, b, 7]);
                    let length = 0.9 + 0.2 * unit(&[seed, m, s, a, b, 11]);
                    swing_m.insert((m, *pv), segment_swing_m[m % 3] * pair * length);
                }
            }
            Synthetic {
                limit_m,
                least_m,
                swing_m,
                swept: 0,
            }
        }

        /// The simulated radius of a piece.
        fn dynamic_m(&self, m: usize, pv: &Pv) -> f64 {
            self.least_m[&(m, *pv)] - self.swing_m[&(m, *pv)]
        }

        /// The motion test of `path`.
        fn test(&self, path: &CablePath) -> Tested {
            let failing = path
                .pieces()
                .find(|(m, pv)| self.dynamic_m(*m, pv) < self.limit_m);
            Tested {
                passed: failing.is_none(),
                segment: failing.map(|(m, _)| m),
                violation: failing.map(|(m, pv)| Violation {
                    constraint: Constraint::BendRadius,
                    value: self.dynamic_m(m, &pv),
                    threshold: self.limit_m,
                    unit: "m",
                    time_s: 0.0,
                    segment: m,
                    segment_name: format!("C{}", m + 1),
                    place: Place::default(),
                }),
                motion: 0,
                reason: String::new(),
                runs: Vec::new(),
                life: None,
            }
        }
    }

    impl ChainSweep for Synthetic {
        fn failing(
            &mut self,
            path: &CablePath,
            _: &[Option<SweptLeast>],
        ) -> Result<Vec<Dropped>, SolveError> {
            self.swept += path.pieces().count();
            Ok(Vec::new())
        }

        fn least(&self, m: usize, pv: &Pv) -> Option<SweptLeast> {
            Some(SweptLeast {
                bend_radius_m: self.least_m[&(m, *pv)],
                ..SweptLeast::NONE
            })
        }

        fn swept(&self) -> usize {
            self.swept
        }
    }

    /// The search over the robust sets `d2` with the synthetic cable of world `seed` (one
    /// copy swept, one simulated), learning or not.
    fn search(
        setup: &Setup,
        d2: &[Vec<Pv>],
        limit_m: f64,
        seed: usize,
        learn: bool,
    ) -> MotionSearch {
        let options = SolveOptions {
            k_best: 100_000,
            learn,
            ..SolveOptions::default()
        };
        let mut chains = Decided::new(setup, d2.to_vec());
        let oracle = Synthetic::over(d2, limit_m, seed);
        let mut test = |path: &CablePath| Ok(oracle.test(path));
        let mut cable = Synthetic::over(d2, limit_m, seed);
        let sweep: &mut dyn ChainSweep = &mut cable;
        try_chains(
            setup,
            &mut chains,
            &options,
            Some(sweep),
            &mut test,
            MotionSearch::new(),
        )
        .unwrap_or_else(|e| panic!("{e}"))
    }

    /// The narrow pick-and-place setup and its robust sets, decided exhaustively.
    fn robust_sets() -> (Setup, Vec<Vec<Pv>>) {
        let (setup, motion) = narrow_pick_and_place();
        let poses = SegmentPoses::new(&setup, &motion).unwrap_or_else(|e| panic!("{e}"));
        let evaluator =
            Evaluator::new(&setup, ConnectMethod::Hermite).unwrap_or_else(|e| panic!("{e}"));
        let d2 = exhaustive_robust(&evaluator, &poses);
        (setup, d2)
    }

    /// A life per piece of world `seed` (1–10 million cycles); a chain lives as long as its
    /// weakest piece.
    fn synthetic_life(path: &CablePath, seed: usize) -> CableLife {
        let lives: Vec<(usize, f64)> = path
            .pieces()
            .map(|(m, pv)| {
                let key = [seed, m, pv.sub_segments, pv.start, pv.end, 13];
                (m, 1e6 * (1.0 + 9.0 * unit(&key)))
            })
            .collect();
        let (segment, cycles) = lives
            .iter()
            .copied()
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        CableLife {
            basis: "rated",
            rated_cycles: None,
            rated_bend_radius_mm: None,
            rated_torsion_deg_per_m: None,
            conductor_offset_mm: None,
            exponent: 4.0,
            exponent_stated: true,
            cycles_to_failure: cycles,
            hours_to_failure: None,
            years_to_failure: None,
            weakest: crate::life::estimate::Weakest {
                segment,
                segment_name: format!("C{}", segment + 1),
                from_start_mm: 0.0,
                damage_per_cycle: 1.0 / cycles,
            },
            pieces: Vec::new(),
        }
    }

    /// Both life goals against every chain in non-decreasing length: the shortest chain that
    /// passes and lives N is the one `--min-life-cycles` answers (by length); the longest-lived
    /// of the passing chains within the window is `--prefer life`'s (by life), in twelve
    /// synthetic worlds.
    #[test]
    fn life_goals_answer_what_every_chain_in_order_says() {
        let (setup, d2) = robust_sets();
        let limit_m = 48e-3;
        let pitch_mm = setup.cable.sub_segment_pitch_m * 1e3;
        let (mut longer, mut better) = (0, 0);
        for seed in 0..12 {
            let oracle = Synthetic::over(&d2, limit_m, seed);
            let passing: Vec<(usize, f64)> = chain_search(&setup, &d2)
                .unwrap_or_else(|e| panic!("{e}"))
                .k_best()
                .filter(|path| oracle.test(path).passed)
                .map(|p| {
                    (
                        p.total_sub_segments(),
                        synthetic_life(&p, seed).cycles_to_failure,
                    )
                })
                .take(400)
                .collect();
            let (first_length, first_life) = passing[0];
            let run = |goal: LifeGoal| {
                let options = SolveOptions {
                    k_best: 100_000,
                    learn: false,
                    life_goal: Some(goal),
                    ..SolveOptions::default()
                };
                let mut chains = Decided::new(&setup, d2.clone());
                let mut test = |path: &CablePath| {
                    let mut tested = oracle.test(path);
                    tested.life = tested.passed.then(|| synthetic_life(path, seed));
                    Ok(tested)
                };
                let mut cable = Synthetic::over(&d2, limit_m, seed);
                let outcome = try_chains(
                    &setup,
                    &mut chains,
                    &options,
                    Some(&mut cable as &mut dyn ChainSweep),
                    &mut test,
                    MotionSearch::new(),
                )
                .unwrap_or_else(|e| panic!("{e}"));
                let winner = &outcome.tried[outcome.winner.expect("an answer")].path;
                (
                    winner.total_sub_segments(),
                    synthetic_life(winner, seed).cycles_to_failure,
                )
            };
            let asked = 1.2 * first_life;
            let reference = passing.iter().find(|(_, life)| *life >= asked);
            if let Some(&(length, _)) = reference {
                let (got_length, got_life) = run(LifeGoal::AtLeast { cycles: asked });
                assert_eq!(got_length, length, "seed {seed}");
                assert!(got_life >= asked, "seed {seed}");
                longer += usize::from(length > first_length);
            }
            let window = 4;
            let best = passing
                .iter()
                .filter(|(length, _)| *length <= first_length + window)
                .map(|&(_, life)| life)
                .fold(0.0, f64::max);
            let within_mm = window as f64 * pitch_mm;
            let (got_length, got_life) = run(LifeGoal::Longest { within_mm });
            assert_eq!(got_life, best, "seed {seed}");
            assert!(got_length <= first_length + window, "seed {seed}");
            better += usize::from(got_life > first_life);
        }
        // The goals were not met by the first passing chain in most worlds.
        assert!(
            longer >= 6 && better >= 6,
            "{longer} longer, {better} longer-lived"
        );
    }

    #[test]
    fn learning_never_rules_out_a_passing_chain_without_saying_so_and_spends_fewer_tests() {
        let (setup, d2) = robust_sets();
        let limit_m = 48e-3;
        let (mut learned_tests, mut strict_tests) = (0, 0);
        for seed in 0..12 {
            // The reference: every chain, shortest first, put to the motion test until one
            // passes — no piece dropped, nothing learned.
            let oracle = Synthetic::over(&d2, limit_m, seed);
            let reference = chain_search(&setup, &d2)
                .unwrap_or_else(|e| panic!("{e}"))
                .k_best()
                .find(|path| oracle.test(path).passed)
                .expect("some chain passes");
            let shortest = reference.total_sub_segments();

            let strict = search(&setup, &d2, limit_m, seed, false);
            let strict_answer =
                &strict.tried[strict.winner.expect("the strict search passes")].path;
            assert_eq!(strict_answer.total_sub_segments(), shortest, "seed {seed}");

            let learned = search(&setup, &d2, limit_m, seed, true);
            let answer = &learned.tried[learned.winner.expect("the learning search passes")].path;
            assert!(oracle.test(answer).passed, "seed {seed}");
            let length = answer.total_sub_segments();
            assert!(length >= shortest, "seed {seed}");
            if length > shortest {
                // Longer than the shortest passing chain: only because pieces were set
                // aside, and the answer says how short a chain with them can be.
                let untried = learned
                    .shortest_untried
                    .expect("the shorter chain is named");
                assert!(untried <= shortest, "seed {seed}: {untried} > {shortest}");
            }
            learned_tests += learned.tried.len();
            strict_tests += strict.tried.len();
        }
        assert!(
            2 * learned_tests < strict_tests,
            "learning took {learned_tests} motion tests over the worlds, the strict order \
             {strict_tests}: not half"
        );
    }
}
