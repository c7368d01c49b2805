//! The chain search against references computed another way: brute-force enumeration of
//! every PV combination (random small layered instances, shuffled inputs), hand-computed
//! optima, matrix products for the count of a large instance, and a bounded depth-first
//! enumeration pruned by per-segment minima for its first chains.

use std::collections::{BTreeSet, HashSet};

use cable_dict::chain::{ChainError, ChainSearch, PvSide};
use cable_dict::path::{CablePath, Pv};

/// splitmix64: a small deterministic PRNG so that every instance is reproducible.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `lo..=hi` (the modulo bias is irrelevant here).
    fn range(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as usize
    }

    fn shuffle<T>(&mut self, items: &mut [T]) {
        for i in (1..items.len()).rev() {
            items.swap(i, self.range(0, i));
        }
    }
}

fn pv(sub_segments: usize, start: usize, end: usize) -> Pv {
    Pv {
        sub_segments,
        start,
        end,
    }
}

fn search(config_counts: &[usize], segments: &[Vec<Pv>]) -> ChainSearch {
    match ChainSearch::new(config_counts, segments) {
        Ok(search) => search,
        Err(e) => panic!("valid instance refused: {e}"),
    }
}

/// A random layered instance: guide configuration counts and per-segment PV lists with
/// short lengths (so that equal totals are common), parallel PVs and duplicates.
fn random_instance(rng: &mut Rng, max_pvs: usize) -> (Vec<usize>, Vec<Vec<Pv>>) {
    let segment_count = rng.range(2, 5);
    let config_counts: Vec<usize> = (0..=segment_count).map(|_| rng.range(1, 5)).collect();
    let segments = (0..segment_count)
        .map(|m| {
            let mut pvs: Vec<Pv> = Vec::new();
            for _ in 0..rng.range(0, max_pvs) {
                if !pvs.is_empty() && rng.range(0, 4) == 0 {
                    pvs.push(pvs[rng.range(0, pvs.len() - 1)]);
                } else {
                    let start = rng.range(0, config_counts[m] - 1);
                    let end = rng.range(0, config_counts[m + 1] - 1);
                    pvs.push(pv(rng.range(0, 4), start, end));
                }
            }
            pvs
        })
        .collect();
    (config_counts, segments)
}

/// Every chain, by trying every combination of one distinct PV per segment and keeping those
/// `CablePath::from_pvs` accepts, sorted by (total length, PV sequence).
fn brute_force(segments: &[Vec<Pv>]) -> Vec<CablePath> {
    let distinct: Vec<Vec<Pv>> = segments
        .iter()
        .map(|pvs| {
            pvs.iter()
                .copied()
                .collect::<BTreeSet<Pv>>()
                .into_iter()
                .collect()
        })
        .collect();
    let mut chains: Vec<(usize, Vec<Pv>)> = Vec::new();
    let mut choice = vec![0usize; distinct.len()];
    if distinct.iter().any(Vec::is_empty) {
        return Vec::new();
    }
    loop {
        let pvs: Vec<Pv> = choice.iter().zip(&distinct).map(|(&i, d)| d[i]).collect();
        if CablePath::from_pvs(&pvs).is_some() {
            chains.push((pvs.iter().map(|p| p.sub_segments).sum(), pvs));
        }
        // Odometer increment over the combinations.
        let mut digit = 0;
        loop {
            if digit == choice.len() {
                chains.sort();
                return chains
                    .iter()
                    .filter_map(|(_, pvs)| CablePath::from_pvs(pvs))
                    .collect();
            }
            choice[digit] += 1;
            if choice[digit] < distinct[digit].len() {
                break;
            }
            choice[digit] = 0;
            digit += 1;
        }
    }
}

/// Everything observable about a search, for comparisons between searches.
fn outputs(search: &ChainSearch, guides: usize) -> (Option<CablePath>, u128, Vec<CablePath>) {
    let used: Vec<Vec<usize>> = (0..guides).map(|g| search.used_configurations(g)).collect();
    let mut all: Vec<CablePath> = search.k_best().collect();
    // Append the used configurations as a pseudo-path so one equality covers them too.
    all.push(CablePath::through_every_guide(Vec::new(), used.concat()));
    (search.shortest(), search.chain_count(), all)
}

#[test]
fn random_instances_match_brute_force() {
    let mut with_chains = 0;
    for seed in 0..200 {
        let mut rng = Rng(seed);
        let (config_counts, segments) = random_instance(&mut rng, 15);
        let expected = brute_force(&segments);
        let search = search(&config_counts, &segments);
        let context = format!("seed {seed}: {config_counts:?} {segments:?}");

        assert_eq!(search.shortest(), expected.first().cloned(), "{context}");
        assert_eq!(search.chain_count(), expected.len() as u128, "{context}");
        let all: Vec<CablePath> = search.k_best().collect();
        assert_eq!(all, expected, "{context}");
        for (g, &n) in config_counts.iter().enumerate() {
            let used: BTreeSet<usize> = expected.iter().map(|p| p.configurations[g]).collect();
            let used: Vec<usize> = used.into_iter().collect();
            assert_eq!(search.used_configurations(g), used, "{context}, guide {g}");
            assert!(used.iter().all(|&c| c < n));
        }
        with_chains += usize::from(!expected.is_empty());
    }
    // The generator must exercise both outcomes, most instances having chains.
    assert!(
        with_chains > 100,
        "only {with_chains} instances have chains"
    );
    assert!(with_chains < 200, "every instance has chains");
}

#[test]
fn taking_a_few_equals_the_start_of_the_full_order() {
    for seed in 0..50 {
        let mut rng = Rng(1000 + seed);
        let (config_counts, segments) = random_instance(&mut rng, 15);
        let expected = brute_force(&segments);
        let search = search(&config_counts, &segments);
        let k = rng.range(0, 6);
        let few: Vec<CablePath> = search.k_best().take(k).collect();
        assert_eq!(few[..], expected[..k.min(expected.len())], "seed {seed}");
        let mut iter = search.k_best();
        iter.by_ref().for_each(drop);
        assert_eq!(iter.next(), None, "fused after the end, seed {seed}");
    }
}

#[test]
fn input_order_and_duplicates_do_not_change_anything() {
    for seed in 0..60 {
        let mut rng = Rng(5000 + seed);
        let (config_counts, segments) = random_instance(&mut rng, 15);
        let reference = outputs(&search(&config_counts, &segments), config_counts.len());
        for variant in 0..4 {
            let mut shuffled = segments.clone();
            for pvs in &mut shuffled {
                // Extra copies of existing PVs, then a random order.
                for _ in 0..variant {
                    if !pvs.is_empty() {
                        let copy = pvs[rng.range(0, pvs.len() - 1)];
                        pvs.push(copy);
                    }
                }
                rng.shuffle(pvs);
            }
            let got = outputs(&search(&config_counts, &shuffled), config_counts.len());
            assert_eq!(got, reference, "seed {seed}, variant {variant}");
        }
    }
}

#[test]
fn per_segment_greedy_is_not_a_chain_but_the_search_finds_the_optimum() {
    // Shortest PV of each segment on its own: (1, 0→0) and (1, 1→0) disagree on guide 1.
    let segments = vec![
        vec![pv(1, 0, 0), pv(5, 0, 1)],
        vec![pv(1, 1, 0), pv(10, 0, 0)],
    ];
    let search = search(&[1, 2, 1], &segments);
    assert_eq!(
        CablePath::from_pvs(&[pv(1, 0, 0), pv(1, 1, 0)]),
        None,
        "greedy picks are not a chain"
    );
    let best = search.shortest().expect("a chain");
    // By hand: 5 + 1 = 6 beats 1 + 10 = 11.
    assert_eq!(best.lengths, vec![5, 1]);
    assert_eq!(best.configurations, vec![0, 1, 0]);
    assert_eq!(search.chain_count(), 2);
    let totals: Vec<usize> = search.k_best().map(|p| p.total_sub_segments()).collect();
    assert_eq!(totals, vec![6, 11]);
}

#[test]
fn forward_greedy_is_a_chain_but_not_optimal() {
    // Taking the shortest first PV (1, 0→0) forces (10, 0→0) next: 11. Optimum 2 + 1 = 3.
    let segments = vec![
        vec![pv(1, 0, 0), pv(2, 0, 1)],
        vec![pv(10, 0, 0), pv(1, 1, 0), pv(1, 1, 0)],
    ];
    let best = search(&[1, 2, 1], &segments).shortest().expect("a chain");
    assert_eq!(best.lengths, vec![2, 1]);
    assert_eq!(best.configurations, vec![0, 1, 0]);
}

#[test]
fn equal_lengths_come_out_in_lexicographic_pv_order() {
    // Seven chains; three of length 4 and two of length 5. Listed by hand: by total, then by
    // first PV (1,0→0) < (2,0→1) < (2,1→0) < (3,0→0).
    let segments = vec![
        vec![pv(2, 1, 0), pv(2, 0, 1), pv(1, 0, 0), pv(3, 0, 0)],
        vec![pv(2, 1, 0), pv(2, 0, 0), pv(3, 0, 0)],
    ];
    let search = search(&[2, 2, 1], &segments);
    let got: Vec<(Vec<usize>, Vec<usize>)> = search
        .k_best()
        .map(|p| (p.lengths, p.configurations))
        .collect();
    let expected = vec![
        (vec![1, 2], vec![0, 0, 0]),
        (vec![1, 3], vec![0, 0, 0]),
        (vec![2, 2], vec![0, 1, 0]),
        (vec![2, 2], vec![1, 0, 0]),
        (vec![2, 3], vec![1, 0, 0]),
        (vec![3, 2], vec![0, 0, 0]),
        (vec![3, 3], vec![0, 0, 0]),
    ];
    assert_eq!(got, expected);
}

#[test]
fn an_empty_segment_means_no_chain_not_an_error() {
    let search = search(&[2, 2, 2], &[vec![pv(1, 0, 1)], vec![]]);
    assert_eq!(search.shortest(), None);
    assert_eq!(search.chain_count(), 0);
    assert_eq!(search.k_best().count(), 0);
    assert!(search.used_configurations(0).is_empty());
}

#[test]
fn out_of_range_configurations_name_segment_pv_and_bound() {
    let segments = vec![
        vec![pv(1, 0, 0)],
        vec![pv(1, 0, 0), pv(2, 1, 0), pv(3, 0, 2)],
    ];
    let error = ChainSearch::new(&[1, 2, 2], &segments).expect_err("end 2 of guide 2");
    assert_eq!(
        error,
        ChainError::OutOfRange {
            segment: 1,
            pv_index: 2,
            pv: pv(3, 0, 2),
            side: PvSide::End,
            guide: 2,
            configuration: 2,
            config_count: 2,
        }
    );
    let message = error.to_string();
    for part in [
        "segment 1",
        "PV 2",
        "end configuration 2",
        "guide 2",
        "2 configurations",
    ] {
        assert!(message.contains(part), "{message:?} lacks {part:?}");
    }

    let segments = vec![vec![pv(1, 0, 0), pv(4, 3, 1)], vec![pv(1, 0, 0)]];
    let error = ChainSearch::new(&[3, 2, 1], &segments).expect_err("start 3 of guide 0");
    assert!(matches!(
        error,
        ChainError::OutOfRange {
            segment: 0,
            pv_index: 1,
            side: PvSide::Start,
            guide: 0,
            configuration: 3,
            config_count: 3,
            ..
        }
    ));
    let message = error.to_string();
    assert!(message.contains("segment 0, PV 1"), "{message:?}");
    assert!(message.contains("start configuration 3"), "{message:?}");
}

#[test]
fn length_mismatch_and_no_segments_are_errors() {
    let segments = vec![vec![pv(1, 0, 0)], vec![pv(1, 0, 0)]];
    let error = ChainSearch::new(&[1, 1], &segments).expect_err("one count short");
    assert_eq!(
        error,
        ChainError::LengthMismatch {
            guides: 2,
            segments: 2
        }
    );
    let message = error.to_string();
    assert!(
        message.contains("2 segments") && message.contains("expected 3"),
        "{message:?}"
    );
    assert!(ChainSearch::new(&[1, 1, 1, 1], &segments).is_err());
    assert_eq!(
        ChainSearch::new(&[1], &[]).expect_err("no segments"),
        ChainError::NoSegments
    );
}

/// `segments[m]` with `per_segment` random PVs (lengths 10..=400) between `configs` start and
/// end configurations, plus some explicit duplicates.
fn large_instance(seed: u64, configs: usize, per_segment: usize) -> Vec<Vec<Pv>> {
    let mut rng = Rng(seed);
    (0..4)
        .map(|_| {
            let mut pvs: Vec<Pv> = (0..per_segment)
                .map(|_| {
                    let (start, end) = (rng.range(0, configs - 1), rng.range(0, configs - 1));
                    pv(rng.range(10, 400), start, end)
                })
                .collect();
            for i in 0..100 {
                pvs.push(pvs[i * 7]);
            }
            pvs
        })
        .collect()
}

/// Chains no longer than `limit`, by depth-first search pruned with each remaining segment's
/// shortest PV (ignoring connectivity, so no dynamic programming is involved).
fn chains_up_to(segments: &[Vec<Pv>], limit: usize) -> Vec<(usize, Vec<Pv>)> {
    let distinct: Vec<BTreeSet<Pv>> = segments
        .iter()
        .map(|s| s.iter().copied().collect())
        .collect();
    let min_rest: Vec<usize> = (0..=distinct.len())
        .map(|m| {
            distinct[m..]
                .iter()
                .map(|s| {
                    s.iter()
                        .map(|p| p.sub_segments)
                        .min()
                        .unwrap_or(usize::MAX / 8)
                })
                .sum()
        })
        .collect();
    let mut found = Vec::new();
    let mut stack = vec![(0usize, Vec::<Pv>::new())];
    while let Some((length, prefix)) = stack.pop() {
        let m = prefix.len();
        if m == distinct.len() {
            found.push((length, prefix));
            continue;
        }
        for &p in &distinct[m] {
            let joins = prefix.last().is_none_or(|last| last.end == p.start);
            if joins && length + p.sub_segments + min_rest[m + 1] <= limit {
                let mut next = prefix.clone();
                next.push(p);
                stack.push((length + p.sub_segments, next));
            }
        }
    }
    found.sort();
    found
}

#[test]
fn large_instance_count_and_first_chains() {
    const CONFIGS: usize = 12;
    let segments = large_instance(42, CONFIGS, 3000);
    let search = search(&[CONFIGS; 5], &segments);

    // |D3| = 1ᵀ·A_0·A_1·A_2·A_3·1 with A_m[i][j] the number of distinct PVs i → j.
    let mut row = vec![1u128; CONFIGS];
    for pvs in &segments {
        let mut matrix = vec![vec![0u128; CONFIGS]; CONFIGS];
        for p in pvs.iter().collect::<HashSet<&Pv>>() {
            matrix[p.start][p.end] += 1;
        }
        row = (0..CONFIGS)
            .map(|j| (0..CONFIGS).map(|i| row[i] * matrix[i][j]).sum())
            .collect();
    }
    let expected_count: u128 = row.iter().sum();
    assert_eq!(search.chain_count(), expected_count);
    assert!(expected_count > 10_000_000_000, "{expected_count}");

    let first: Vec<CablePath> = search.k_best().take(50).collect();
    assert_eq!(first.len(), 50);
    assert_eq!(Some(&first[0]), search.shortest().as_ref());
    let totals: Vec<usize> = first.iter().map(CablePath::total_sub_segments).collect();
    assert!(totals.windows(2).all(|w| w[0] <= w[1]), "{totals:?}");
    assert_eq!(first.iter().collect::<HashSet<_>>().len(), 50, "distinct");

    // Every chain no longer than the 50th, found without the DP: the first 50 of them.
    let bounded = chains_up_to(&segments, totals[49]);
    assert!(bounded.len() >= 50);
    let expected: Vec<CablePath> = bounded[..50]
        .iter()
        .filter_map(|(_, pvs)| CablePath::from_pvs(pvs))
        .collect();
    assert_eq!(first, expected);
}

/// A random graph with skip pieces: guides 0…G, the consecutive pieces (g, g + 1) and some
/// that jump over one or two guides, each with random PVs.
/// Configuration counts per guide, each piece's (start, end) guides, each piece's PVs.
type SkippingInstance = (Vec<usize>, Vec<(usize, usize)>, Vec<Vec<Pv>>);

fn random_skipping_instance(rng: &mut Rng) -> SkippingInstance {
    let guides = rng.range(3, 6);
    let config_counts: Vec<usize> = (0..guides).map(|_| rng.range(1, 3)).collect();
    let mut ends: Vec<(usize, usize)> = (0..guides - 1).map(|g| (g, g + 1)).collect();
    for a in 0..guides {
        for b in a + 2..guides.min(a + 4) {
            if rng.range(0, 2) == 0 {
                ends.push((a, b));
            }
        }
    }
    let pieces = ends
        .iter()
        .map(|&(a, b)| {
            (0..rng.range(0, 6))
                .map(|_| {
                    let start = rng.range(0, config_counts[a] - 1);
                    let end = rng.range(0, config_counts[b] - 1);
                    pv(rng.range(0, 5), start, end)
                })
                .collect()
        })
        .collect();
    (config_counts, ends, pieces)
}

/// Every chain of a graph with skip pieces, by depth-first enumeration of every route of
/// pieces from guide 0 to the last guide and every agreeing choice of distinct PVs, sorted
/// by (total length, sequence of (PV, piece)).
fn brute_force_routes(last: usize, ends: &[(usize, usize)], pieces: &[Vec<Pv>]) -> Vec<CablePath> {
    fn extend(
        last: usize,
        ends: &[(usize, usize)],
        pieces: &[Vec<BTreeSet<Pv>>],
        at: (usize, Option<usize>),
        chain: &mut Vec<(Pv, usize)>,
        found: &mut Vec<(usize, Vec<(Pv, usize)>)>,
    ) {
        let (guide, config) = at;
        if guide == last {
            let total = chain.iter().map(|(pv, _)| pv.sub_segments).sum();
            found.push((total, chain.clone()));
            return;
        }
        for (p, &(a, b)) in ends.iter().enumerate() {
            if a != guide {
                continue;
            }
            for pv in &pieces[p][0] {
                if config.is_some_and(|c| c != pv.start) {
                    continue;
                }
                chain.push((*pv, p));
                extend(last, ends, pieces, (b, Some(pv.end)), chain, found);
                chain.pop();
            }
        }
    }
    let distinct: Vec<Vec<BTreeSet<Pv>>> = pieces
        .iter()
        .map(|pvs| vec![pvs.iter().copied().collect()])
        .collect();
    let mut found = Vec::new();
    extend(
        last,
        ends,
        &distinct,
        (0, None),
        &mut Vec::new(),
        &mut found,
    );
    found.sort();
    found
        .iter()
        .map(|(_, chain)| {
            let pieces: Vec<(usize, Pv)> = chain.iter().map(|&(pv, p)| (p, pv)).collect();
            CablePath::from_pieces(&pieces).expect("agreeing pieces")
        })
        .collect()
}

/// With pieces that jump over guides (optional clamps left out), the shortest chain, the
/// count, every chain in order and the used configurations equal a brute-force enumeration
/// of every route.
#[test]
fn skip_pieces_match_brute_force_over_every_route() {
    let mut skipping = 0;
    for seed in 0..300 {
        let mut rng = Rng(9000 + seed);
        let (config_counts, ends, pieces) = random_skipping_instance(&mut rng);
        let expected = brute_force_routes(config_counts.len() - 1, &ends, &pieces);
        let search = match ChainSearch::over(&config_counts, &ends, &pieces) {
            Ok(search) => search,
            Err(e) => panic!("seed {seed}: refused: {e}"),
        };
        let context = format!("seed {seed}: {config_counts:?} {ends:?} {pieces:?}");
        assert_eq!(search.shortest(), expected.first().cloned(), "{context}");
        assert_eq!(search.chain_count(), expected.len() as u128, "{context}");
        let all: Vec<CablePath> = search.k_best().collect();
        assert_eq!(all, expected, "{context}");
        for g in 0..config_counts.len() {
            let used: BTreeSet<usize> = expected
                .iter()
                .flat_map(|path| {
                    let guides = std::iter::once(0)
                        .chain(path.segments.iter().map(|&p| ends[p].1))
                        .collect::<Vec<_>>();
                    guides
                        .into_iter()
                        .zip(path.configurations.clone())
                        .filter(move |&(guide, _)| guide == g)
                        .map(|(_, c)| c)
                })
                .collect();
            let used: Vec<usize> = used.into_iter().collect();
            assert_eq!(search.used_configurations(g), used, "{context}, guide {g}");
        }
        skipping += usize::from(
            expected
                .first()
                .is_some_and(|p| p.segments.len() < config_counts.len() - 1),
        );
    }
    assert!(
        skipping > 30,
        "only {skipping} shortest chains skip a guide"
    );
}

#[test]
fn a_skip_piece_must_run_forward_within_the_guides() {
    let pieces = vec![vec![pv(1, 0, 0)], vec![pv(1, 0, 0)]];
    for ends in [
        vec![(0, 1), (1, 1)],
        vec![(0, 1), (1, 3)],
        vec![(0, 1), (2, 1)],
    ] {
        let error = ChainSearch::over(&[1, 1, 1], &ends, &pieces).expect_err("bad ends");
        assert!(
            matches!(error, ChainError::PieceEnds { piece: 1, .. }),
            "{ends:?}: {error}"
        );
    }
    let error = ChainSearch::over(&[1, 1, 1], &[(0, 2)], &pieces).expect_err("counts");
    assert_eq!(error, ChainError::PieceCount { ends: 1, pieces: 2 });
}
