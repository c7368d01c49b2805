//! Segments: one per pair of consecutive guides, with their candidate lengths.

use super::error::Source;
use super::guides::{runs_through, same_pose};
use super::raw::{RawGuide, RawLengths, RawSegment};
use super::{Guide, GuideKind, LengthRange, MAX_SUB_SEGMENTS, SegmentSpec, SetupError};
use toml::Spanned;

/// Validates the `[[segments]]` list against the guides, ΔS and the pitch (m).
pub(super) fn build(
    src: Source,
    guides: &[Guide],
    raw: &Spanned<Vec<Spanned<RawSegment>>>,
    (delta_s, pitch_m): (usize, f64),
) -> Result<Vec<SegmentSpec>, SetupError> {
    let expected = guides.len() - 1;
    if raw.get_ref().len() != expected {
        return Err(src.error(
            raw.span(),
            "segments",
            format!(
                "{} segments given, but {} guides need exactly {expected} \
                 (one per pair of consecutive guides)",
                raw.get_ref().len(),
                guides.len()
            ),
        ));
    }
    raw.get_ref()
        .iter()
        .enumerate()
        .map(|(m, entry)| segment(src, guides, m, entry.get_ref(), (delta_s, pitch_m)))
        .collect()
}

fn segment(
    src: Source,
    guides: &[Guide],
    m: usize,
    raw: &RawSegment,
    (delta_s, pitch_m): (usize, f64),
) -> Result<SegmentSpec, SetupError> {
    let (a, b) = (&guides[m], &guides[m + 1]);
    check_end(src, &raw.from, &format!("segments[{m}].from"), &a.name)?;
    check_end(src, &raw.to, &format!("segments[{m}].to"), &b.name)?;
    let intra_link = a.body == b.body;
    let key = format!("segments[{m}].lengths");
    let range = length_range(src, &key, &raw.lengths, delta_s)?;
    // The segments on either side of a guide the cable runs through are one piece: the
    // span through it, never 0 mm on one side.
    let through = [m, m + 1].into_iter().find(|&g| runs_through(guides, g));
    if let (Some(g), true) = (through, range.allow_zero) {
        return Err(src.error(
            raw.lengths.allow_zero.span(),
            format!("{key}.allow_zero"),
            format!(
                "the cable runs on through {}: {} to {} is one side of the piece through it, \
                 which has cable on both sides (S = 0 is not offered here)",
                guides[g].name, a.name, b.name
            ),
        ));
    }
    if range.allow_zero {
        check_zero(src, &key, &raw.lengths, a, b, intra_link)?;
    }
    let zero = range.allow_zero.then_some(0);
    let series = (range.min..=range.max).step_by(range.step);
    let lengths = match through.is_some() {
        true => Vec::new(),
        false => zero.into_iter().chain(series).collect(),
    };
    if let Some(GuideKind::Retraction { travel_max_m, .. }) = b.kinds.first()
        && b.kinds.len() == 1
    {
        check_stored(src, &key, raw, (a, b), *travel_max_m, pitch_m)?;
    }
    Ok(SegmentSpec {
        guides: (m, m + 1),
        lengths,
        intra_link,
        range,
        through: None,
    })
}

/// The spans over optional guides: for every pair of guides `a < b − 1` with only optional
/// guides between them, the piece of cable from `a` to `b` when those clamps are left out,
/// its lengths the sums of the skipped segments' ranges (in steps of their steps' greatest
/// common divisor, which divides ΔS as each of them does). Refused, at the optional guide:
/// a span whose ends are on one link (that is S = 0 of an intra-link segment), or longer than
/// [`MAX_SUB_SEGMENTS`].
pub(super) fn spans(
    src: Source,
    guides: &[Guide],
    raw_guides: &[Spanned<RawGuide>],
    declared: &[SegmentSpec],
) -> Result<Vec<SegmentSpec>, SetupError> {
    let mut spans = Vec::new();
    for a in 0..guides.len() {
        // Every guide strictly between a and b is optional.
        for b in a + 2..guides.len() {
            let skipped = b - 1;
            if runs_through(guides, skipped) && b == a + 2 {
                let piece = joined(guides, declared, (a, b), Some(skipped)).map_err(|max| {
                    let kind = raw_guides[skipped].get_ref().kind.as_ref();
                    src.error(
                        kind.map_or(0..0, Spanned::span),
                        format!("guides[{skipped}].kind"),
                        format!(
                            "the cable from {} through {} to {} could be {max} sub-segments \
                             long, more than the {MAX_SUB_SEGMENTS} a piece may have",
                            guides[a].name, guides[skipped].name, guides[b].name
                        ),
                    )
                })?;
                spans.push(piece);
                break;
            }
            if !guides[skipped].optional {
                break;
            }
            let fail = |problem: String| {
                let optional = raw_guides[skipped].get_ref().optional.as_ref();
                let span = optional.map_or(0..0, Spanned::span);
                src.error(span, format!("guides[{skipped}].optional"), problem)
            };
            if guides[a].body == guides[b].body {
                return Err(fail(format!(
                    "leaving {} out joins {} and {}, both on one link: a clamp that may be \
                     left out within one link is S = 0 of its segment (`allow_zero = true`)",
                    guides[skipped].name, guides[a].name, guides[b].name
                )));
            }
            let span = joined(guides, declared, (a, b), None).map_err(|max| {
                fail(format!(
                    "the cable from {} to {} without the clamps between could be {max} \
                     sub-segments long, more than the {MAX_SUB_SEGMENTS} a piece may have",
                    guides[a].name, guides[b].name
                ))
            })?;
            spans.push(span);
        }
    }
    Ok(spans)
}

/// The piece from guide `a` to guide `b` that stands for the declared segments between them
/// (a span over optional guides, or the piece `through` a sliding guide or a retraction's
/// outlet, whose stored cable at rest is the first segment's only length): its lengths the
/// sums of their ranges, in steps of their steps' greatest common divisor (which divides ΔS
/// as each of them does). `Err` with the longest sum when it is more than
/// [`MAX_SUB_SEGMENTS`].
fn joined(
    guides: &[Guide],
    declared: &[SegmentSpec],
    (a, b): (usize, usize),
    through: Option<usize>,
) -> Result<SegmentSpec, usize> {
    let ranges = || declared[a..b].iter().map(|s| s.range);
    let min: usize = ranges().map(|r| r.min).sum();
    let max: usize = ranges().map(|r| r.max).sum();
    if max > MAX_SUB_SEGMENTS {
        return Err(max);
    }
    let step = ranges().map(|r| r.step).fold(0, gcd);
    Ok(SegmentSpec {
        guides: (a, b),
        lengths: (min..=max).step_by(step).collect(),
        intra_link: guides[a].body == guides[b].body,
        range: LengthRange {
            min,
            max,
            step,
            allow_zero: false,
        },
        through,
    })
}

/// The segment from a retraction's inlet `a` to its outlet `b` is the cable stored in the
/// unit at rest: one length (`min = max`, no S = 0), long enough to give out the whole
/// travel beyond the straight run between them.
fn check_stored(
    src: Source,
    key: &str,
    raw: &RawSegment,
    (a, b): (&Guide, &Guide),
    travel_max_m: f64,
    pitch_m: f64,
) -> Result<(), SetupError> {
    let lengths = &raw.lengths;
    let (min, max) = (*lengths.min.get_ref(), *lengths.max.get_ref());
    if min != max || *lengths.allow_zero.get_ref() {
        return Err(src.error(
            raw.lengths.max.span(),
            format!("{key}.max"),
            format!(
                "{} to {} is the cable stored in the retraction system at rest: one length \
                 (min = max, no allow_zero), not {min} to {max}",
                a.name, b.name
            ),
        ));
    }
    let outlet = b.pose_in_body(0).translation.vector;
    let straight_m = (0..a.configurations.len())
        .map(|c| (a.pose_in_body(c).translation.vector - outlet).norm())
        .fold(0.0, f64::max);
    let stored_m = min as f64 * pitch_m;
    if stored_m < straight_m + travel_max_m {
        return Err(src.error(
            raw.lengths.min.span(),
            format!("{key}.min"),
            format!(
                "{:.0} mm stored between {} and {} cannot give out the {:.0} mm of travel \
                 beyond their {:.0} mm straight run: at least {} sub-segments",
                stored_m * 1e3,
                a.name,
                b.name,
                travel_max_m * 1e3,
                straight_m * 1e3,
                ((straight_m + travel_max_m) / pitch_m).ceil()
            ),
        ));
    }
    Ok(())
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// `from` / `to` must name the guides the segment's position implies.
fn check_end(
    src: Source,
    value: &Spanned<String>,
    key: &str,
    expected: &str,
) -> Result<(), SetupError> {
    if value.get_ref() == expected {
        return Ok(());
    }
    Err(src.error(
        value.span(),
        key,
        format!(
            "\"{}\" but this segment joins guide {expected}: segment m runs from the m-th to \
             the (m+1)-th guide, in the order of [[guides]]",
            value.get_ref()
        ),
    ))
}

/// `min ≥ 1`, `min ≤ max`, `step ≥ 1`, `(max − min) % step = 0` and `delta_s % step = 0`
/// (so that the robustness neighbours S ± k·ΔS lie on the series).
fn length_range(
    src: Source,
    key: &str,
    raw: &RawLengths,
    delta_s: usize,
) -> Result<LengthRange, SetupError> {
    let (min, max, step) = (*raw.min.get_ref(), *raw.max.get_ref(), *raw.step.get_ref());
    let fail =
        |span, field: &str, problem: String| src.error(span, format!("{key}.{field}"), problem);
    if min == 0 {
        return Err(fail(
            raw.min.span(),
            "min",
            "min must be ≥ 1; S = 0 is asked for with `allow_zero = true`".into(),
        ));
    }
    if max > MAX_SUB_SEGMENTS {
        return Err(fail(
            raw.max.span(),
            "max",
            format!(
                "max = {max} sub-segments, more than the {MAX_SUB_SEGMENTS} a segment may have \
                 (its cable is solved node by node)"
            ),
        ));
    }
    if max < min {
        return Err(fail(
            raw.max.span(),
            "max",
            format!("max = {max} is below min = {min}"),
        ));
    }
    if step == 0 {
        return Err(fail(raw.step.span(), "step", "step must be ≥ 1".into()));
    }
    if !(max - min).is_multiple_of(step) {
        return Err(fail(
            raw.max.span(),
            "max",
            format!(
                "max − min = {} is not a multiple of step = {step}",
                max - min
            ),
        ));
    }
    if !delta_s.is_multiple_of(step) {
        return Err(fail(
            raw.step.span(),
            "step",
            format!(
                "step = {step} does not divide robustness.delta_s = {delta_s}: the robustness \
                 test needs the lengths S ± k·ΔS among the candidates"
            ),
        ));
    }
    Ok(LengthRange {
        min,
        max,
        step,
        allow_zero: *raw.allow_zero.get_ref(),
    })
}

/// S = 0 (the two guides coincide) needs both guides on one link, and two fixed guides only
/// coincide if they are at the same pose.
fn check_zero(
    src: Source,
    key: &str,
    raw: &RawLengths,
    a: &Guide,
    b: &Guide,
    intra_link: bool,
) -> Result<(), SetupError> {
    let span = raw.allow_zero.span();
    if !intra_link {
        return Err(src.error(
            span,
            format!("{key}.allow_zero"),
            format!(
                "S = 0 is only allowed for intra-link segments, but {} and {} are on \
                 different links",
                a.name, b.name
            ),
        ));
    }
    let pose_a = a.pose_in_body(0);
    if a.fixed && b.fixed && !same_pose(&pose_a, &b.pose_in_body(0)) {
        return Err(src.error(
            span,
            format!("{key}.allow_zero"),
            format!(
                "{} and {} are both fixed at different poses, so they can never coincide (S = 0)",
                a.name, b.name
            ),
        ));
    }
    Ok(())
}
