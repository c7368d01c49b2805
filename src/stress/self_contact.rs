//! How close a cable comes to itself: the smallest distance between two of its sub-segments
//! that are not the same stretch of cable bending, less the cable's diameter. Negative: the
//! cable passes through itself, which no real cable can (docs/architecture.md, "Self-contact").
//!
//! Two sub-segments closer along the cable than half a turn around the cable's own radius
//! (`π d / 2`) are excluded: a cable bent as tightly as it physically can (radius `d/2`)
//! brings such points within `d` without touching itself. Beyond that gap any approach
//! within `d` is contact; a cable that holds a bend radius `R ≥ d` keeps points up to `π R`
//! apart along it at least `2 R sin(g / 2R)` apart in space (Schur's comparison theorem), so
//! bent cables are not flagged.
//!
//! The search is exact and cheap: the sub-segments are grouped in runs of [`RUN`] with a
//! bounding sphere each, run pairs are visited by increasing lower bound, and the search stops
//! when no remaining pair can beat the closest found.

use super::contact::segment_segment_distance;
use nalgebra::Point3;
use serde::Serialize;

/// Sub-segments per bounding sphere.
const RUN: usize = 8;

/// The closest approach of a cable to itself.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SelfContact {
    /// Centreline distance − diameter (m) at the closest approach; negative where the cable
    /// passes through itself.
    pub clearance_m: f64,
    /// The two sub-segments (0-based from the cable's start, the first below the second).
    pub sub_segments: [usize; 2],
}

impl SelfContact {
    /// True when the cable touches or passes through itself.
    pub fn is_violated(&self) -> bool {
        self.clearance_m < 0.0
    }
}

/// Watches a cable through a sequence of shapes — the steps of turning a clamp, say — and
/// keeps where along the sequence it first touched or passed through itself: by overlapping
/// in a shape, or by crossing between two shapes (`crossed`, e.g.
/// [`crate::statics::turns::passed_through_itself`]), which neither shape shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstSelfContact {
    diameter_m: f64,
    pitch_m: f64,
    /// The sequence's parameter (e.g. the clamp's extra turn, rad) at the first contact.
    pub at: Option<f64>,
}

impl FirstSelfContact {
    /// A watch for a cable of `diameter_m` in sub-segments of `pitch_m`.
    pub fn new(diameter_m: f64, pitch_m: f64) -> Self {
        FirstSelfContact {
            diameter_m,
            pitch_m,
            at: None,
        }
    }

    /// Takes in the shape `nodes` at `at`, reached from the previous one `crossed` or not.
    pub fn step(&mut self, at: f64, nodes: &[Point3<f64>], crossed: bool) {
        if self.at.is_some() {
            return;
        }
        let touches =
            self_contact(nodes, self.diameter_m, self.pitch_m).is_some_and(|c| c.is_violated());
        if touches || crossed {
            self.at = Some(at);
        }
    }
}

/// Arc length (m) below which two parts of a cable of `diameter_m` are the same stretch of
/// cable bending, not two parts touching: half a turn around its own radius.
pub fn self_contact_gap_m(diameter_m: f64) -> f64 {
    0.5 * std::f64::consts::PI * diameter_m
}

/// The closest approach of the polyline `nodes` (sub-segments of about `pitch_m`) to itself,
/// for a cable of `diameter_m`; `None` when no part of it comes back toward another (a straight
/// or gently bent cable) or it is too short to have two sub-segments far enough apart.
///
/// An approach is a pair of sub-segments at least [`self_contact_gap_m`] apart along the
/// cable whose distance is a local minimum over the pairs next to it (one step along the cable
/// at either end): where two parts of the cable come back toward each other, as across a loop
/// or the two legs of a U-turn. Pairs at the edge of the excluded gap are not approaches (a
/// cable's distance to its own neighbourhood grows away from it), unless the cable reaches its
/// end there. A pair closer than the diameter is always one: the cable touches itself.
pub fn self_contact(nodes: &[Point3<f64>], diameter_m: f64, pitch_m: f64) -> Option<SelfContact> {
    self_contact_within(nodes, diameter_m, pitch_m, f64::INFINITY)
}

/// [`self_contact`] for approaches whose centreline distance is below `within_m` only: the
/// closest approach when it is, `None` otherwise. Cheaper where only near approaches matter
/// (a piece's stored clearance margin is the lower of its clearance to the robot and to
/// itself).
pub fn self_contact_within(
    nodes: &[Point3<f64>],
    diameter_m: f64,
    pitch_m: f64,
    within_m: f64,
) -> Option<SelfContact> {
    let segments = nodes.len().checked_sub(1)?;
    let skip = skipped_neighbours(diameter_m, pitch_m);
    if segments <= skip + 1 {
        return None;
    }
    let runs = bounding_runs(nodes, segments);
    let mut pairs = run_pairs(&runs, skip);
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    // Each sub-segment's middle and half length: two are at least the distance of their
    // middles less both half lengths apart, a bound that skips most pairs of a cable that
    // does not come back toward itself.
    let middles: Vec<(Point3<f64>, f64)> = nodes
        .windows(2)
        .map(|w| (nalgebra::center(&w[0], &w[1]), 0.5 * (w[1] - w[0]).norm()))
        .collect();
    let mut best: Option<(f64, [usize; 2])> = None;
    let mut block = Block::default();
    for (lower, a, b) in pairs {
        let bound = best.map_or(within_m, |(d, _)| d.min(within_m));
        if lower >= bound {
            break;
        }
        block.reset(&runs[a].range, &runs[b].range, segments);
        for i in runs[a].range.clone() {
            let first_j = runs[b].range.start.max(i + skip + 1);
            for j in first_j..runs[b].range.end {
                let bound = best.map_or(within_m, |(d, _)| d.min(within_m));
                let ((mi, hi), (mj, hj)) = (middles[i], middles[j]);
                if (mi - mj).norm() - hi - hj >= bound {
                    continue;
                }
                let d = block.get(nodes, i, j);
                if d < bound
                    && is_approach(&mut block, nodes, (i, j), d, (skip, segments, diameter_m))
                {
                    best = Some((d, [i, j]));
                }
            }
        }
    }
    best.map(|(distance, sub_segments)| SelfContact {
        clearance_m: distance - diameter_m,
        sub_segments,
    })
}

/// Whether the pair `(i, j)` at distance `d` is an approach: closer than the diameter, or
/// off the domain's inner edge `j = i + skip + 1` with no pair one step away in the domain
/// (`j ≥ i + skip + 1`, both below `segments`) closer.
fn is_approach(
    block: &mut Block,
    nodes: &[Point3<f64>],
    (i, j): (usize, usize),
    d: f64,
    (skip, segments, diameter_m): (usize, usize, f64),
) -> bool {
    if d < diameter_m {
        return true;
    }
    if j == i + skip + 1 {
        return false;
    }
    let neighbours = [
        i.checked_sub(1).map(|p| (p, j)),
        (i + 1 + skip < j).then_some((i + 1, j)),
        Some((i, j - 1)),
        (j + 1 < segments).then_some((i, j + 1)),
    ];
    neighbours
        .into_iter()
        .flatten()
        .all(|(a, b)| block.get(nodes, a, b) >= d)
}

/// The distances of a run pair's sub-segments and their neighbours one step away, each
/// computed once, when first asked for.
#[derive(Default)]
struct Block {
    rows: std::ops::Range<usize>,
    columns: std::ops::Range<usize>,
    distances: Vec<f64>,
}

impl Block {
    /// Empty, for rows `a` and columns `b`, each widened by one sub-segment.
    fn reset(&mut self, a: &std::ops::Range<usize>, b: &std::ops::Range<usize>, segments: usize) {
        self.rows = a.start.saturating_sub(1)..(a.end + 1).min(segments);
        self.columns = b.start.saturating_sub(1)..(b.end + 1).min(segments);
        self.distances.clear();
        self.distances
            .resize(self.rows.len() * self.columns.len(), f64::NAN);
    }

    /// The distance of sub-segments `i` and `j` (within the rows and columns).
    fn get(&mut self, nodes: &[Point3<f64>], i: usize, j: usize) -> f64 {
        let width = self.columns.len();
        let slot = &mut self.distances[(i - self.rows.start) * width + (j - self.columns.start)];
        if slot.is_nan() {
            *slot = segment_distance(&nodes[i], &nodes[i + 1], &nodes[j], &nodes[j + 1]);
        }
        *slot
    }
}

/// How many sub-segments on either side of one are the same stretch of cable: those whose
/// gap along the cable, `(j − i − 1)·pitch`, is below [`self_contact_gap_m`].
fn skipped_neighbours(diameter_m: f64, pitch_m: f64) -> usize {
    let gap = self_contact_gap_m(diameter_m) / pitch_m;
    // Sub-segments j = i + 1 … i + skip are skipped: (skip)·pitch ≥ gap.
    (gap.ceil().max(1.0) as usize).min(usize::MAX / 4)
}

/// A run of consecutive sub-segments and a sphere holding them.
struct Run {
    range: std::ops::Range<usize>,
    center: Point3<f64>,
    radius: f64,
}

fn bounding_runs(nodes: &[Point3<f64>], segments: usize) -> Vec<Run> {
    (0..segments)
        .step_by(RUN)
        .map(|first| {
            let range = first..(first + RUN).min(segments);
            let points = &nodes[range.start..=range.end];
            let (mut low, mut high) = (points[0].coords, points[0].coords);
            for p in points {
                low = low.inf(&p.coords);
                high = high.sup(&p.coords);
            }
            let center = Point3::from(0.5 * (low + high));
            let radius = points
                .iter()
                .map(|p| (p - center).norm())
                .fold(0.0, f64::max);
            Run {
                range,
                center,
                radius,
            }
        })
        .collect()
}

/// Every pair of runs `a ≤ b` holding at least one pair of sub-segments more than `skip`
/// apart, with the lower bound of their distance.
fn run_pairs(runs: &[Run], skip: usize) -> Vec<(f64, usize, usize)> {
    let mut pairs = Vec::new();
    for (a, first) in runs.iter().enumerate() {
        for (b, second) in runs.iter().enumerate().skip(a) {
            if second.range.end - 1 < first.range.start + skip + 1 {
                continue;
            }
            let lower = (second.center - first.center).norm() - first.radius - second.radius;
            pairs.push((lower.max(0.0), a, b));
        }
    }
    pairs
}

/// The distance between the segments `p0 p1` and `q0 q1`.
fn segment_distance(p0: &Point3<f64>, p1: &Point3<f64>, q0: &Point3<f64>, q1: &Point3<f64>) -> f64 {
    segment_segment_distance(p0, &(p1 - p0), q0, &(q1 - q0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The distance between two segments by sampling both finely: an independent reference.
    fn sampled_distance(p: [Point3<f64>; 2], q: [Point3<f64>; 2]) -> f64 {
        let n = 400;
        let at = |s: [Point3<f64>; 2], k: usize| s[0] + (s[1] - s[0]) * (k as f64 / n as f64);
        (0..=n)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| (at(p, i) - at(q, j)).norm())
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn segment_distance_matches_sampling_in_every_configuration() {
        let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
        let cases = [
            (
                [p(0., 0., 0.), p(1., 0., 0.)],
                [p(0.5, -1., 0.3), p(0.5, 1., 0.3)],
            ), // crossing
            (
                [p(0., 0., 0.), p(1., 0., 0.)],
                [p(2., 1., 0.), p(3., 1., 0.)],
            ), // end to end
            (
                [p(0., 0., 0.), p(1., 0., 0.)],
                [p(0.2, 0.5, 0.), p(0.8, 0.5, 0.)],
            ), // parallel
            (
                [p(0., 0., 0.), p(1., 0., 0.)],
                [p(1.5, 0., 0.), p(3., 0., 0.)],
            ), // collinear
            (
                [p(0., 0., 0.), p(0., 0., 0.)],
                [p(1., 1., 1.), p(2., 1., 0.)],
            ), // a point
            (
                [p(0., 0., 0.), p(1., 1., 1.)],
                [p(0.3, 0.9, -0.2), p(-0.4, 0.2, 1.1)],
            ),
        ];
        for (a, b) in cases {
            let exact = segment_distance(&a[0], &a[1], &b[0], &b[1]);
            let sampled = sampled_distance(a, b);
            assert!(exact <= sampled + 1e-12, "{a:?} {b:?}: {exact} > {sampled}");
            assert!(sampled - exact < 5e-3, "{a:?} {b:?}: {exact} vs {sampled}");
        }
    }

    /// A helix of radius r and pitch h: each turn is h from the next along the axis, so the
    /// closest approach of sub-segments a turn apart is about h (less the chord's sagitta).
    fn helix(radius: f64, rise_per_turn: f64, turns: f64, pitch: f64) -> Vec<Point3<f64>> {
        let arc_per_turn = (4.0 * PI * PI * radius * radius + rise_per_turn.powi(2)).sqrt();
        let count = (turns * arc_per_turn / pitch).round() as usize;
        (0..=count)
            .map(|k| {
                let phase = 2.0 * PI * turns * k as f64 / count as f64;
                Point3::new(
                    radius * phase.cos(),
                    radius * phase.sin(),
                    rise_per_turn * phase / (2.0 * PI),
                )
            })
            .collect()
    }

    #[test]
    fn a_helix_comes_as_close_to_itself_as_its_rise_per_turn() {
        let (radius, diameter, pitch) = (0.05, 0.008, 0.002);
        // Rises above the excluded gap (π d / 2 = 12.6 mm) meet sub-segments just beyond it
        // first, not a turn away.
        for rise in [0.004, 0.006, 0.010] {
            let nodes = helix(radius, rise, 3.0, pitch);
            let contact = self_contact(&nodes, diameter, pitch).expect("three turns");
            let distance = contact.clearance_m + diameter;
            // Closest points lie on chords a turn apart: within the chords' sagitta of h.
            let sagitta = pitch * pitch / (8.0 * radius);
            assert!(
                (distance - rise).abs() <= sagitta + 1e-9,
                "rise {rise}: {distance}"
            );
            let [i, j] = contact.sub_segments;
            let per_turn = nodes.len() as f64 / 3.0;
            assert!(((j - i) as f64 - per_turn).abs() < 2.0, "{i} {j}");
            assert_eq!(contact.is_violated(), rise < diameter, "rise {rise}");
        }
    }

    /// The closest approach by trying every pair, with the rule written out on the whole
    /// distance matrix: a pair in the domain that is closer than the diameter, or off the
    /// domain's inner edge with no pair one step away in the domain closer.
    fn brute_force(nodes: &[Point3<f64>], diameter: f64, skip: usize) -> Option<(f64, [usize; 2])> {
        let n = nodes.len() - 1;
        let d = |i: usize, j: usize| {
            segment_distance(&nodes[i], &nodes[i + 1], &nodes[j], &nodes[j + 1])
        };
        let in_domain = |i: isize, j: isize| i >= 0 && j < n as isize && j > i + skip as isize;
        let mut best: Option<(f64, [usize; 2])> = None;
        for i in 0..n {
            for j in i + skip + 1..n {
                let here = d(i, j);
                let minimum = j > i + skip + 1
                    && [(-1, 0), (1, 0), (0, -1), (0, 1)].iter().all(|(di, dj)| {
                        let (a, b) = (i as isize + di, j as isize + dj);
                        !in_domain(a, b) || d(a as usize, b as usize) >= here
                    });
                if (here < diameter || minimum) && best.is_none_or(|(b, _)| here < b) {
                    best = Some((here, [i, j]));
                }
            }
        }
        best
    }

    /// The bounded search finds the same closest approach as trying every pair, on a figure
    /// eight whose lobes cross, on the same lifted clear of each other, and on a hanging loop.
    #[test]
    fn the_bounded_search_equals_trying_every_pair() {
        let (diameter, pitch) = (0.008, 0.005);
        let skip = skipped_neighbours(diameter, pitch);
        for lift in [0.003, 0.02] {
            // Most of a planar figure eight (its ends 100 mm apart) with a lift at the cross.
            let nodes: Vec<Point3<f64>> = (0..=118)
                .map(|k| {
                    let s = -0.25 * PI + 1.5 * PI * k as f64 / 118.0;
                    Point3::new(0.1 * s.sin(), 0.05 * (2.0 * s).sin(), lift * s.cos())
                })
                .collect();
            let (distance, pair) = brute_force(&nodes, diameter, skip).expect("an approach");
            let found = self_contact(&nodes, diameter, pitch).expect("long enough");
            assert_eq!(found.sub_segments, pair, "lift {lift}");
            assert_eq!(found.clearance_m, distance - diameter);
            assert_eq!(
                found.is_violated(),
                2.0 * lift < diameter,
                "lift {lift}: {distance}"
            );
        }
        let helix = helix(0.05, 0.03, 2.2, pitch);
        let (distance, pair) = brute_force(&helix, diameter, skip).expect("an approach");
        let found = self_contact(&helix, diameter, pitch).expect("long enough");
        assert_eq!(
            (found.sub_segments, found.clearance_m),
            (pair, distance - diameter)
        );
    }

    /// A straight cable does not come back toward itself: no approach at all (the old rule
    /// reported its neighbourhood, (3 − 1) pitches less the diameter, for every straight
    /// cable). A U-turn's legs, 2R apart, are its closest approach; a searched `within` below
    /// it finds nothing, above it the same.
    #[test]
    fn a_straight_cable_has_no_approach_and_a_u_turn_its_legs() {
        let (diameter, pitch) = (0.008, 0.01);
        let straight: Vec<Point3<f64>> = (0..=60)
            .map(|k| Point3::new(k as f64 * pitch, 0.0, 0.0))
            .collect();
        assert_eq!(self_contact(&straight, diameter, pitch), None);
        // Legs 300 mm long along x, 2R = 100 mm apart, joined by a half circle of R = 50 mm.
        let radius = 0.05;
        let mut u_turn: Vec<Point3<f64>> = (0..=30)
            .map(|k| Point3::new(0.3 - k as f64 * pitch, radius, 0.0))
            .collect();
        let arc = (PI * radius / pitch).round() as usize;
        u_turn.extend((1..arc).map(|k| {
            let phase = PI / 2.0 + PI * k as f64 / arc as f64;
            Point3::new(radius * phase.cos(), radius * phase.sin(), 0.0)
        }));
        u_turn.extend((0..=30).map(|k| Point3::new(k as f64 * pitch, -radius, 0.0)));
        let found = self_contact(&u_turn, diameter, pitch).expect("the legs");
        assert!(
            (found.clearance_m - (2.0 * radius - diameter)).abs() < 1e-9,
            "{found:?}"
        );
        let [i, j] = found.sub_segments;
        assert!(i < 30 && j > 30 + arc, "both on the legs: {i} {j}");
        assert_eq!(self_contact_within(&u_turn, diameter, pitch, 0.09), None);
        assert_eq!(
            self_contact_within(&u_turn, diameter, pitch, 0.11),
            Some(found)
        );
    }

    /// A straight cable, or one bent around a circle of radius d (a quarter turn), never
    /// touches itself at any pitch; a circle closed on itself does.
    #[test]
    fn straight_and_bent_cables_do_not_touch_themselves_a_closed_ring_does() {
        let diameter = 0.008;
        for pitch in [0.001, 0.0025, 0.005, 0.01, 0.02] {
            let straight: Vec<Point3<f64>> = (0..=40)
                .map(|k| Point3::new(k as f64 * pitch, 0.0, 0.0))
                .collect();
            if let Some(contact) = self_contact(&straight, diameter, pitch) {
                assert!(!contact.is_violated(), "pitch {pitch}: {contact:?}");
            }
            let radius = 2.0 * diameter;
            let arc = |turn: f64| -> Vec<Point3<f64>> {
                let count = (2.0 * PI * radius * turn / pitch).round().max(1.0) as usize;
                (0..=count)
                    .map(|k| {
                        let phase = 2.0 * PI * turn * k as f64 / count as f64;
                        Point3::new(radius * phase.cos(), radius * phase.sin(), 0.0)
                    })
                    .collect()
            };
            if let Some(contact) = self_contact(&arc(0.5), diameter, pitch) {
                assert!(
                    !contact.is_violated(),
                    "pitch {pitch}: half a ring {contact:?}"
                );
            }
            if pitch <= 0.005 {
                let ring = self_contact(&arc(1.05), diameter, pitch).expect("a ring");
                assert!(ring.is_violated(), "pitch {pitch}: a closed ring {ring:?}");
            }
        }
    }
}
