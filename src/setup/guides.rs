//! Guides: their links, their declared configurations, their order and count per link.

use super::error::Source;
use super::raw::{RawConfiguration, RawGuide};
use super::sites::{GeneratorEstimate, SiteContext, check_generated_total};
use super::{ConfigurationOrigin, Guide, GuideConfiguration, GuideKind, SetupError};
use crate::pose::{Pose, pose_from_mm_deg};
use crate::robot::Robot;
use crate::sites::MIN_SPACING_M;
use std::collections::{HashMap, HashSet};
use toml::Spanned;

type RawGuides = Spanned<Vec<Spanned<RawGuide>>>;

/// Validates the `[[guides]]` list: names, links, configurations, base→tool order and the
/// number of guides per link.
pub(super) fn build(
    src: Source,
    robot: &Robot,
    raw: &RawGuides,
    max_per_link: usize,
    sites: &SiteContext,
) -> Result<Vec<Guide>, SetupError> {
    if raw.get_ref().len() < 2 {
        return Err(src.error(
            raw.span(),
            "guides",
            "at least two guides are needed (a cable path has at least one segment)",
        ));
    }
    check_generated_total(src, raw.span(), robot, &generators(robot, raw.get_ref()))?;
    let mut guides: Vec<Guide> = Vec::new();
    for (g, entry) in raw.get_ref().iter().enumerate() {
        let guide = guide(src, robot, g, entry.get_ref(), sites)?;
        if let Some(same) = guides.iter().find(|other| other.name == guide.name) {
            let name = &entry.get_ref().name;
            return Err(src.error(
                name.span(),
                format!("guides[{g}].name"),
                format!("guide name \"{}\" is used twice", same.name),
            ));
        }
        guides.push(guide);
    }
    check_order(src, robot, raw, &guides)?;
    check_optional_ends(src, raw, &guides)?;
    check_slides(src, raw, &guides)?;
    check_per_link(src, robot, raw, &guides, max_per_link)?;
    Ok(guides)
}

/// The site generators among `raw`'s guides, as far as they can be read (the others are
/// refused later, one by one, with their own messages).
fn generators(robot: &Robot, raw: &[Spanned<RawGuide>]) -> Vec<GeneratorEstimate> {
    raw.iter()
        .enumerate()
        .filter_map(|(g, entry)| {
            let guide = entry.get_ref();
            let sites = guide.sites.as_ref()?.get_ref();
            let spacing_mm = *sites.spacing_mm.get_ref();
            let generated = guide.configurations.is_none() && guide.fixed.is_none();
            let readable = spacing_mm.is_finite() && spacing_mm * 1e-3 >= MIN_SPACING_M;
            (generated && readable).then_some(GeneratorEstimate {
                guide: g,
                link: robot.link_index(guide.link.get_ref())?,
                spacing_mm,
                directions: sites.directions_deg.get_ref().len(),
            })
        })
        .collect()
}

fn guide(
    src: Source,
    robot: &Robot,
    g: usize,
    raw: &RawGuide,
    sites: &SiteContext,
) -> Result<Guide, SetupError> {
    let name = checked_name(src, &raw.name, &format!("guides[{g}].name"))?;
    let link = link_named(src, robot, &raw.link, format!("guides[{g}].link"))?;
    let (body, link_in_body) = robot.moving_body(link);
    let fixed = raw.fixed.is_some();
    let (generated, configurations) = match &raw.sites {
        Some(generator) if raw.configurations.is_none() && !fixed => {
            let key = format!("guides[{g}].sites");
            let (generated, configurations) =
                sites.configurations(src, robot, link, &key, generator)?;
            (Some(generated), configurations)
        }
        _ => (
            None,
            configurations(src, &configuration_entries(src, g, raw)?)?,
        ),
    };
    Ok(Guide {
        name,
        link,
        body,
        link_in_body,
        fixed,
        optional: raw.optional.as_ref().is_some_and(|o| *o.get_ref()),
        configurations,
        kinds: kinds(src, g, raw)?,
        generated,
    })
}

/// The kinds of clamp `raw` may be, simplest first: `kind` (a word or a list of them) with
/// each kind's own keys (a swivel's `cone_deg`, a sliding guide's `friction_coefficient`, a
/// retraction's `preload_n`, `rate_n_per_mm`, `travel_mm` and `stored_from`). A guide the
/// cable slides through is one kind alone: it decides which pieces there are.
fn kinds(src: Source, g: usize, raw: &RawGuide) -> Result<Vec<GuideKind>, SetupError> {
    let key = format!("guides[{g}].kind");
    let numbers = [
        ("cone_deg", &raw.cone_deg, "swivel"),
        ("friction_coefficient", &raw.friction_coefficient, "sliding"),
        ("preload_n", &raw.preload_n, "retraction"),
        ("rate_n_per_mm", &raw.rate_n_per_mm, "retraction"),
        ("travel_mm", &raw.travel_mm, "retraction"),
    ];
    let own_keys = (numbers.iter())
        .map(|(name, value, owner)| (*name, value.as_ref().map(Spanned::span), *owner))
        .chain([(
            "stored_from",
            raw.stored_from.as_ref().map(Spanned::span),
            "retraction",
        )]);
    let words: Vec<&toml::Value> = match raw.kind.as_ref().map(Spanned::get_ref) {
        None => Vec::new(),
        Some(toml::Value::Array(list)) => list.iter().collect(),
        Some(one) => vec![one],
    };
    let offered = |word: &str| words.iter().any(|w| w.as_str() == Some(word));
    for (name, span, owner) in own_keys {
        if let (Some(span), false) = (span, offered(owner)) {
            return Err(src.error(
                span,
                format!("guides[{g}].{name}"),
                format!("{name} is a {owner}'s: this guide offers no {owner} (kind = \"{owner}\")"),
            ));
        }
    }
    let Some(kind) = &raw.kind else {
        return Ok(vec![GuideKind::Rigid]);
    };
    if words.is_empty() {
        return Err(src.error(kind.span(), key, "an empty list: name at least one kind"));
    }
    // A number the kind needs, checked against `valid` (what it must be, said when not).
    let number = |value: &Option<Spanned<f64>>,
                  name: &str,
                  what: &str,
                  valid: fn(f64) -> bool,
                  must: &str|
     -> Result<f64, SetupError> {
        let Some(value) = value else {
            return Err(src.error(kind.span(), key.clone(), format!("{what} needs {name}")));
        };
        let v = *value.get_ref();
        if !(v.is_finite() && valid(v)) {
            return Err(src.error(
                value.span(),
                format!("guides[{g}].{name}"),
                format!("{v}: {must}"),
            ));
        }
        Ok(v)
    };
    let swivel = || -> Result<GuideKind, SetupError> {
        let deg = number(
            &raw.cone_deg,
            "cone_deg",
            "a swivel",
            |d| d > 0.0 && d <= 180.0,
            "a cone's half-angle is in (0, 180] deg",
        )?;
        Ok(GuideKind::Swivel {
            cone_rad: deg.to_radians(),
        })
    };
    let sliding = || -> Result<GuideKind, SetupError> {
        let friction = number(
            &raw.friction_coefficient,
            "friction_coefficient",
            "a sliding guide (its Coulomb coefficient on the cable, 0 for none)",
            |f| (0.0..=2.0).contains(&f),
            "a friction coefficient is in [0, 2]",
        )?;
        Ok(GuideKind::Sliding { friction })
    };
    let retraction = || -> Result<GuideKind, SetupError> {
        let what = "a retraction";
        let non_negative = |v: f64| v >= 0.0;
        let preload_n = number(
            &raw.preload_n,
            "preload_n",
            what,
            non_negative,
            "a force ≥ 0 N",
        )?;
        let rate = number(
            &raw.rate_n_per_mm,
            "rate_n_per_mm",
            what,
            non_negative,
            "a spring rate ≥ 0 N/mm",
        )?;
        let travel = number(
            &raw.travel_mm,
            "travel_mm",
            what,
            |t| t > 0.0 && t <= 5000.0,
            "a travel in (0, 5000] mm",
        )?;
        if raw.stored_from.is_none() {
            return Err(src.error(
                kind.span(),
                key.clone(),
                "a retraction needs stored_from: the guide its stored cable comes from (its \
                 inlet, the guide before it)",
            ));
        }
        Ok(GuideKind::Retraction {
            preload_n,
            rate_n_per_m: rate * 1e3,
            travel_max_m: travel * 1e-3,
        })
    };
    let mut kinds: Vec<GuideKind> = Vec::new();
    for word in &words {
        let refuse = |problem: String| src.error(kind.span(), key.clone(), problem);
        let kind = match word.as_str() {
            Some("rigid") => GuideKind::Rigid,
            Some("rotating") => GuideKind::Rotating,
            Some("swivel") => swivel()?,
            Some("sliding") => sliding()?,
            Some("retraction") => retraction()?,
            _ => {
                return Err(refuse(format!(
                    "{word}: a kind is \"rigid\", \"rotating\", \"swivel\", \"sliding\" or \
                     \"retraction\" (or a list of clamp kinds the search may choose from)"
                )));
            }
        };
        if kinds.iter().any(|k| k.word() == kind.word()) {
            return Err(refuse(format!("\"{}\" is named twice", kind.word())));
        }
        if kind.slides() && words.len() > 1 {
            return Err(refuse(format!(
                "a {} guide is not one of several kinds to choose from: the cable slides \
                 through it, which changes which pieces there are; offer it alone",
                kind.word()
            )));
        }
        kinds.push(kind);
    }
    kinds.sort_by_key(GuideKind::rank);
    Ok(kinds)
}

/// Gives each guide one configuration per pose and kind it offers, the kinds in the order
/// of [`Guide::kinds`] (the simplest first, so that of equally short paths the search keeps
/// the simplest part): run after every pose is known (coincident copies included).
pub(super) fn expand_kinds(guides: &mut [Guide]) {
    for guide in guides.iter_mut() {
        if guide.kinds == [GuideKind::Rigid] {
            continue;
        }
        let poses = std::mem::take(&mut guide.configurations);
        for kind in &guide.kinds {
            guide
                .configurations
                .extend(poses.iter().map(|c| GuideConfiguration {
                    name: match kind {
                        GuideKind::Rigid => c.name.clone(),
                        other => format!("{} ({})", c.name, other.word()),
                    },
                    kind: *kind,
                    ..c.clone()
                }));
        }
    }
}

/// The index of the link `name` names, refused at `key` with the robot's links when it has
/// none of that name.
pub(super) fn link_named(
    src: Source,
    robot: &Robot,
    name: &Spanned<String>,
    key: String,
) -> Result<usize, SetupError> {
    robot.link_index(name.get_ref()).ok_or_else(|| {
        let known: Vec<&str> = robot.links.iter().map(|l| l.name.as_str()).collect();
        src.error(
            name.span(),
            key,
            format!(
                "link \"{}\" is not in the robot {} (links: {})",
                name.get_ref(),
                robot.source.display(),
                known.join(", ")
            ),
        )
    })
}

/// The configuration entries with their keys (`guides[g].configurations[c]` or
/// `guides[g].fixed`); exactly one of the two keys must be given.
fn configuration_entries<'r>(
    src: Source,
    g: usize,
    raw: &'r RawGuide,
) -> Result<Vec<(String, &'r Spanned<RawConfiguration>)>, SetupError> {
    if let Some(generator) = &raw.sites {
        return Err(src.error(
            generator.span(),
            format!("guides[{g}]"),
            "give one of `configurations = [...]`, `fixed = {...}` and `sites = {...}`",
        ));
    }
    match (&raw.configurations, &raw.fixed) {
        (Some(list), None) if list.get_ref().is_empty() => Err(src.error(
            list.span(),
            format!("guides[{g}].configurations"),
            "the candidate list is empty: give at least one configuration",
        )),
        (Some(list), None) => Ok(list
            .get_ref()
            .iter()
            .enumerate()
            .map(|(c, entry)| (format!("guides[{g}].configurations[{c}]"), entry))
            .collect()),
        (None, Some(single)) => Ok(vec![(format!("guides[{g}].fixed"), single)]),
        (Some(list), Some(_)) => Err(src.error(
            list.span(),
            format!("guides[{g}]"),
            "give one of `configurations = [...]`, `fixed = {...}` and `sites = {...}`",
        )),
        (None, None) => Err(src.error(
            raw.name.span(),
            format!("guides[{g}]"),
            "missing `configurations = [...]` (candidates), `fixed = {...}` (one given pose) \
             or `sites = {...}` (sites generated on the link's surfaces)",
        )),
    }
}

fn configurations(
    src: Source,
    entries: &[(String, &Spanned<RawConfiguration>)],
) -> Result<Vec<GuideConfiguration>, SetupError> {
    let mut list: Vec<GuideConfiguration> = Vec::new();
    let mut names: HashSet<String> = HashSet::new();
    let mut poses = PoseIndex::default();
    for (key, entry) in entries {
        let configuration = configuration(src, key, entry)?;
        if names.contains(&configuration.name) {
            return Err(src.error(
                entry.get_ref().name.span(),
                format!("{key}.name"),
                format!(
                    "configuration name \"{}\" is used twice in this guide",
                    configuration.name
                ),
            ));
        }
        if let Some(twin) = poses.find(&configuration.pose) {
            return Err(src.error(
                entry.span(),
                key,
                format!(
                    "configuration \"{}\" has the same pose as \"{}\"",
                    configuration.name, list[twin].name
                ),
            ));
        }
        names.insert(configuration.name.clone());
        poses.insert(&configuration.pose, list.len());
        list.push(configuration);
    }
    Ok(list)
}

fn configuration(
    src: Source,
    key: &str,
    entry: &Spanned<RawConfiguration>,
) -> Result<GuideConfiguration, SetupError> {
    let raw = entry.get_ref();
    let name = checked_name(src, &raw.name, &format!("{key}.name"))?;
    let position_mm = src.finite3(&raw.position_mm, format!("{key}.position_mm"))?;
    let rpy_deg = src.finite3(&raw.rpy_deg, format!("{key}.rpy_deg"))?;
    Ok(GuideConfiguration {
        name,
        pose: pose_from_mm_deg(position_mm, rpy_deg),
        position_mm,
        rpy_deg,
        origin: ConfigurationOrigin::Declared {
            line: src.line_of(entry.span().start),
        },
        kind: GuideKind::Rigid,
    })
}

/// Poses equal within the coincidence tolerances.
pub(super) fn same_pose(a: &Pose, b: &Pose) -> bool {
    (a.translation.vector - b.translation.vector).norm() < super::COINCIDENCE_TOLERANCE_M
        && a.rotation.angle_to(&b.rotation) < super::COINCIDENCE_TOLERANCE_RAD
}

/// Clamp poses found by pose without comparing each with all others (a catalogue may hold
/// 10⁵ of them): a hash grid of cells wider than the coincidence tolerance, so that a pose
/// that is the same place ([`super::same_place`]) as an indexed one lies in the same or a
/// neighbouring cell.
#[derive(Debug, Default)]
pub struct PoseIndex {
    cells: HashMap<[i64; 3], Vec<(Pose, usize)>>,
}

/// Cell width of [`PoseIndex`] (m): above the coincidence tolerance.
const CELL_M: f64 = 1e-6;

impl PoseIndex {
    /// `poses` indexed by their positions in the slice.
    pub fn of(poses: &[Pose]) -> PoseIndex {
        let mut index = PoseIndex::default();
        for (k, pose) in poses.iter().enumerate() {
            index.insert(pose, k);
        }
        index
    }

    fn cell(pose: &Pose) -> [i64; 3] {
        // `as` saturates: far or non-finite positions share the edge cells, still correct.
        pose.translation
            .vector
            .map(|x| (x / CELL_M).floor() as i64)
            .into()
    }

    /// The smallest index of an inserted pose that is [`same_pose`] as `pose`.
    pub fn find(&self, pose: &Pose) -> Option<usize> {
        self.same_as(pose).min()
    }

    /// How many inserted poses are [`same_pose`] as `pose`.
    pub fn count(&self, pose: &Pose) -> usize {
        self.same_as(pose).count()
    }

    /// The indices of the inserted poses [`same_pose`] as `pose`: those in its cell and the
    /// neighbouring ones.
    fn same_as<'i>(&'i self, pose: &'i Pose) -> impl Iterator<Item = usize> + 'i {
        let [x, y, z] = Self::cell(pose);
        let near = (-1..=1i64).flat_map(move |dx| {
            (-1..=1i64).flat_map(move |dy| {
                (-1..=1i64).map(move |dz| {
                    [
                        x.saturating_add(dx),
                        y.saturating_add(dy),
                        z.saturating_add(dz),
                    ]
                })
            })
        });
        near.flat_map(|key| self.cells.get(&key).into_iter().flatten())
            .filter(move |(other, _)| same_pose(other, pose))
            .map(|(_, index)| *index)
    }

    /// Adds `pose` under `index`.
    pub fn insert(&mut self, pose: &Pose, index: usize) {
        self.cells
            .entry(Self::cell(pose))
            .or_default()
            .push((*pose, index));
    }
}

/// A non-empty name without `/` (reserved for coincident copies such as `G2/back`).
fn checked_name(src: Source, name: &Spanned<String>, key: &str) -> Result<String, SetupError> {
    let text = name.get_ref().trim();
    if text.is_empty() || text.contains('/') {
        return Err(src.error(
            name.span(),
            key,
            format!(
                "\"{}\": a name must be non-empty and must not contain `/`",
                name.get_ref()
            ),
        ));
    }
    Ok(text.to_string())
}

/// True when `ancestor` is `link` or on the path from `link` to the root.
fn is_same_or_ancestor(robot: &Robot, ancestor: usize, mut link: usize) -> bool {
    loop {
        if link == ancestor {
            return true;
        }
        match robot.links[link].parent_joint {
            Some(j) => link = robot.joints[j].parent_link,
            None => return false,
        }
    }
}

/// Each guide must sit on the previous guide's link or a link further towards the tool.
fn check_order(
    src: Source,
    robot: &Robot,
    raw: &RawGuides,
    guides: &[Guide],
) -> Result<(), SetupError> {
    for (g, pair) in guides.windows(2).enumerate() {
        let (before, after) = (&pair[0], &pair[1]);
        if !is_same_or_ancestor(robot, before.body, after.body) {
            let link = &raw.get_ref()[g + 1].get_ref().link;
            return Err(src.error(
                link.span(),
                format!("guides[{}].link", g + 1),
                format!(
                    "guide {} on {} comes after {} on {}, but {} is not {} or a link after it \
                     towards the tool; list guides from the base end of the cable to the tool end",
                    after.name,
                    robot.links[after.link].name,
                    before.name,
                    robot.links[before.link].name,
                    robot.links[after.body].name,
                    robot.links[before.body].name,
                ),
            ));
        }
    }
    Ok(())
}

/// The first and the last guide are where the cable's design starts and ends: neither may be
/// left out.
fn check_optional_ends(src: Source, raw: &RawGuides, guides: &[Guide]) -> Result<(), SetupError> {
    for g in [0, guides.len() - 1] {
        if let (true, Some(optional)) = (guides[g].optional, &raw.get_ref()[g].get_ref().optional) {
            return Err(src.error(
                optional.span(),
                format!("guides[{g}].optional"),
                format!(
                    "{} is the {} guide, where the cable path {}: it cannot be left out",
                    guides[g].name,
                    if g == 0 { "first" } else { "last" },
                    if g == 0 { "starts" } else { "ends" }
                ),
            ));
        }
    }
    Ok(())
}

/// Whether the cable runs through guide `g` between two pieces that are one piece of the
/// search: a sliding guide, a retraction's outlet, or a swivel clamp between two pieces.
pub(super) fn runs_through(guides: &[Guide], g: usize) -> bool {
    through_kind(guides, g).is_some()
}

/// The kind that makes the cable run through guide `g` ([`runs_through`]), if one does.
fn through_kind(guides: &[Guide], g: usize) -> Option<&GuideKind> {
    let between = g != 0 && g + 1 != guides.len();
    let swivel = |k: &&GuideKind| matches!(k, GuideKind::Swivel { .. });
    (guides[g].kinds.iter()).find(|k| k.slides() || (between && swivel(k)))
}

/// A guide the cable runs through between two pieces that are one piece of the search (a
/// sliding guide, a retraction's outlet, a swivel clamp between two pieces) sits between
/// two clamps that are always mounted, has one place (`fixed`, or one configuration) and
/// one kind: the search does not move it nor choose its kind. One the cable slides through
/// has its two clamps on different links (else its split never changes). A retraction's
/// `stored_from` names the guide before it, its inlet, on its own link.
fn check_slides(src: Source, raw: &RawGuides, guides: &[Guide]) -> Result<(), SetupError> {
    let last = guides.len() - 1;
    for (g, guide) in guides.iter().enumerate() {
        let Some(kind) = through_kind(guides, g) else {
            continue;
        };
        let entry = raw.get_ref()[g].get_ref();
        let kind_span = entry.kind.as_ref().map_or(raw.span(), |k| k.span());
        let refuse = |problem: String| {
            Err(src.error(kind_span.clone(), format!("guides[{g}].kind"), problem))
        };
        let word = kind.word();
        if guide.kinds.len() > 1 {
            return refuse(format!(
                "{} is between two pieces of cable: a {word} clamp there is its only kind in \
                 this version (the pieces either side are one piece of the search through it)",
                guide.name
            ));
        }
        if g == 0 || g == last {
            return refuse(format!(
                "{} is the {} guide: a {word} guide sits between two clamps",
                guide.name,
                if g == 0 { "first" } else { "last" }
            ));
        }
        if guide.optional {
            return refuse(format!(
                "{} is optional: a {word} guide is always there (leave out a clamp instead)",
                guide.name
            ));
        }
        if guide.configurations.len() != 1 || guide.generated.is_some() {
            return refuse(format!(
                "{} has {} places: a {word} guide has one (`fixed = {{…}}`, or one \
                 configuration); the search does not move it in this version",
                guide.name,
                guide.configurations.len()
            ));
        }
        for n in [g - 1, g + 1] {
            let neighbour = &guides[n];
            if neighbour.optional || runs_through(guides, n) {
                return refuse(format!(
                    "{} is next to {}, which is {}: the clamps on either side of a {word} guide \
                     are always mounted and hold the cable",
                    guide.name,
                    neighbour.name,
                    if neighbour.optional {
                        "optional"
                    } else {
                        "one the cable runs through"
                    }
                ));
            }
        }
        if kind.slides() && guides[g - 1].body == guides[g + 1].body {
            return refuse(format!(
                "{} and {} on either side of {} are on one link: the cable through a {word} \
                 guide between them cannot change its split as the robot moves",
                guides[g - 1].name,
                guides[g + 1].name,
                guide.name
            ));
        }
        if let (GuideKind::Retraction { .. }, Some(stored)) = (kind, &entry.stored_from) {
            let inlet = &guides[g - 1];
            let key = format!("guides[{g}].stored_from");
            if stored.get_ref() != &inlet.name {
                return Err(src.error(
                    stored.span(),
                    key,
                    format!(
                        "\"{}\" but the guide before {} is {}: the stored cable runs from the \
                         unit's inlet, the guide before its outlet",
                        stored.get_ref(),
                        guide.name,
                        inlet.name
                    ),
                ));
            }
            if inlet.body != guide.body {
                return Err(src.error(
                    stored.span(),
                    key,
                    format!(
                        "{} is on another link than {}: a retraction system's inlet and outlet \
                         are on the unit, on one link",
                        inlet.name, guide.name
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// At most `max` guides on one link (links joined by fixed joints count as one).
fn check_per_link(
    src: Source,
    robot: &Robot,
    raw: &RawGuides,
    guides: &[Guide],
    max: usize,
) -> Result<(), SetupError> {
    for (g, guide) in guides.iter().enumerate() {
        let sharing: Vec<&str> = guides[..=g]
            .iter()
            .filter(|other| other.body == guide.body)
            .map(|other| other.name.as_str())
            .collect();
        if sharing.len() > max {
            let link = &raw.get_ref()[g].get_ref().link;
            return Err(src.error(
                link.span(),
                format!("guides[{g}].link"),
                format!(
                    "{} guides ({}) on {}, but max_guides_per_link = {max}",
                    sharing.len(),
                    sharing.join(", "),
                    robot.links[guide.body].name
                ),
            ));
        }
    }
    Ok(())
}

/// Warns (the run goes on) about every written clamp configuration whose cable axis lies
/// inside a solid of its own link — the link's shapes, a body the setup attached, the links
/// fixed to it: a connector placed inside the tool's body, say. The cable cannot leave such
/// a clamp without touching, so every piece there fails; the warning says why up front.
/// Generated sites are checked when they are generated.
pub(super) fn warn_buried_clamps(
    src: Source,
    robot: &Robot,
    guides: &[Guide],
    sites: &SiteContext,
) {
    let Ok(obstacles) = sites.obstacles(robot) else {
        return; // the contact stages refuse such a robot with the message
    };
    let Ok(poses) = robot.link_poses(&vec![0.0; robot.dof()]) else {
        return;
    };
    for guide in guides {
        let rigid = robot.rigidly_attached(guide.link);
        for c in &guide.configurations {
            if !matches!(c.origin, ConfigurationOrigin::Declared { .. }) {
                continue;
            }
            let at = poses[guide.link] * nalgebra::Point3::from(c.pose.translation.vector);
            let found = crate::stress::min_clearance_to_links(
                obstacles,
                &poses,
                &[at, at],
                0.0,
                &[],
                &rigid,
            );
            let Ok(Some(nearest)) = found else { continue };
            if nearest.clearance_m < -1e-6 {
                let link = &robot.links[nearest.link];
                let what = match &link.colliders[nearest.collider].attached {
                    Some(body) => format!("body \"{body}\" on {}", link.name),
                    None => format!("{}'s collision shape #{}", link.name, nearest.collider + 1),
                };
                log::warn!(
                    "{}: guide {} \"{}\": its clamp's cable axis lies {:.1} mm inside {what}; \
                     the cable cannot leave it without touching — move the clamp out",
                    src.file.display(),
                    guide.name,
                    c.name,
                    -nearest.clearance_m * 1e3
                );
            }
        }
    }
}
