//! The solids in a triangle mesh as vendors ship it: split into shells, each wound
//! consistently and outward, and judged on whether its inside can be told from its surface.
//!
//! A collision STL of a real robot is rarely one clean closed surface. It is several shells
//! (a housing, a motor cover, screw heads), meeting along shared edges or overlapping inside
//! the link; some are wound inward, some have a few open edges. The link's solid is the union
//! of the shells' insides. [`analyse`] finds the shells:
//!
//! - triangles are connected across edges used by exactly two triangles of the mesh, so
//!   shells that merely share an edge (four uses) come apart;
//! - each shell is wound consistently (a breadth-first walk turns a triangle that traverses a
//!   shared edge the same way as its neighbour) and, if it is closed, outward (by the sign of
//!   its enclosed volume); an open shell keeps the winding most of its triangles came with;
//! - a shell is [`ShellKind::Closed`] when every edge is used by exactly two of its
//!   triangles, its winding is consistent, no triangle has zero area and no two triangles
//!   that share no corner cross each other. For such a shell the side of a point follows
//!   from the surface near it (pseudo-normals, in the contact module); everything else is
//!   [`ShellKind::Loose`] and its inside is decided by the winding number of all loose
//!   triangles together (see `docs/architecture.md`, "Contact with real meshes").

use nalgebra::{Point3, Vector3};

/// How the inside of a shell can be decided.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShellKind {
    /// A closed, consistently wound, non-self-intersecting surface of non-zero volume.
    Closed,
    /// Anything else: open edges, edges of more than two triangles, no consistent winding,
    /// zero-area triangles, self-crossing or zero volume.
    Loose,
}

/// Whether a shell's surface passes through itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SelfCrossing {
    /// Not looked for: the shell is loose anyway (open, non-manifold, no consistent winding or
    /// zero-area triangles).
    NotChecked,
    /// No two triangles that share no corner cross.
    No,
    /// Two triangles that share no corner cross.
    Yes,
    /// More candidate pairs than the work limit: given up, the shell treated as loose.
    GivenUp,
}

/// One connected piece of a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Shell {
    /// Its triangles (indices into the mesh's vertices), wound as described in the module
    /// documentation.
    pub triangles: Vec<[u32; 3]>,
    /// How its inside is decided.
    pub kind: ShellKind,
    /// Edges used by only one of its triangles.
    pub open_edges: usize,
    /// Edges used by more than two of its triangles.
    pub non_manifold_edges: usize,
    /// Triangles the file winds against their neighbours (the smaller of the two camps).
    pub rewound_triangles: usize,
    /// Whether no consistent winding exists (a Möbius-like surface).
    pub non_orientable: bool,
    /// Whether the file winds the whole shell inward (turned outward here; closed shells only).
    pub inverted: bool,
    /// Triangles of zero area (three distinct but collinear corners).
    pub zero_area_triangles: usize,
    /// Whether two of its triangles that share no corner cross each other.
    pub self_crossing: SelfCrossing,
    /// Enclosed volume after winding (m³); meaningful for closed shells.
    pub volume_m3: f64,
    /// Bounding box of its vertices (m).
    pub min: Point3<f64>,
    /// Bounding box of its vertices (m).
    pub max: Point3<f64>,
}

/// What [`analyse`] found in a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshShells {
    /// The shells, in the order of their first triangle in the file.
    pub shells: Vec<Shell>,
    /// Triangles dropped because two of their corners are the same vertex.
    pub collapsed_triangles: usize,
    /// Edges used by more than two triangles of the whole mesh: where shells meet.
    pub shared_edges: usize,
}

impl MeshShells {
    /// Shells whose inside is decided by the winding number.
    pub fn loose(&self) -> impl Iterator<Item = &Shell> {
        self.shells.iter().filter(|s| s.kind == ShellKind::Loose)
    }

    /// Open edges over all shells.
    pub fn open_edges(&self) -> usize {
        self.shells.iter().map(|s| s.open_edges).sum()
    }

    /// Why the mesh's solid cannot be fully trusted, if it cannot: open edges or a surface
    /// with no consistent winding leave the inside ill-defined near them.
    pub fn distrust(&self) -> Option<String> {
        let open = self.open_edges();
        let non_orientable = self.shells.iter().filter(|s| s.non_orientable).count();
        let mut reasons = Vec::new();
        match open {
            0 => {}
            1 => reasons.push("an open edge (a hole in its surface)".into()),
            n => reasons.push(format!("{n} open edges (holes in its surface)")),
        }
        match non_orientable {
            0 => {}
            1 => reasons.push("a shell with no consistent winding".into()),
            n => reasons.push(format!("{n} shells with no consistent winding")),
        }
        (!reasons.is_empty()).then(|| reasons.join(" and "))
    }
}

/// Pairs of triangles checked for crossing per triangle at most (beyond it the self-crossing
/// check of a shell is given up and the shell treated as loose).
const CROSSING_PAIRS_PER_TRIANGLE: usize = 64;

/// Splits a mesh into shells and winds, classifies and measures each (see the module
/// documentation). Triangles naming a vertex beyond `vertices` are ignored.
pub fn analyse(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> MeshShells {
    let valid = |t: &[u32; 3]| t.iter().all(|&v| (v as usize) < vertices.len());
    let kept: Vec<[u32; 3]> = triangles
        .iter()
        .filter(|t| valid(t) && t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
        .copied()
        .collect();
    let collapsed_triangles = triangles.iter().filter(|t| valid(t)).count() - kept.len();
    let edges = EdgeTable::new(&kept);
    let shared_edges = edges.groups().filter(|g| g.len() > 2).count();
    let shells = components(&kept, &edges)
        .into_iter()
        .map(|members| shell(vertices, &kept, &members))
        .collect();
    MeshShells {
        shells,
        collapsed_triangles,
        shared_edges,
    }
}

/// One use of an undirected edge by a triangle.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EdgeUse {
    /// The edge as (lower, higher) vertex index.
    pub key: (u32, u32),
    /// Index of the triangle.
    pub triangle: usize,
    /// Which of the triangle's edges: from its corner `slot` to corner `(slot + 1) % 3`.
    pub slot: usize,
    /// Whether the triangle traverses it from the lower to the higher vertex.
    pub forward: bool,
}

/// Every edge use of a set of triangles, grouped by edge (sorted: deterministic and without
/// hashing).
pub(crate) struct EdgeTable {
    uses: Vec<EdgeUse>,
}

impl EdgeTable {
    /// The uses of every edge of `triangles`.
    pub fn new(triangles: &[[u32; 3]]) -> EdgeTable {
        let mut uses: Vec<EdgeUse> = triangles
            .iter()
            .enumerate()
            .flat_map(|(triangle, t)| {
                (0..3).map(move |slot| {
                    let (u, v) = (t[slot], t[(slot + 1) % 3]);
                    EdgeUse {
                        key: (u.min(v), u.max(v)),
                        triangle,
                        slot,
                        forward: u < v,
                    }
                })
            })
            .collect();
        uses.sort_unstable_by_key(|e| (e.key, e.triangle, e.slot));
        EdgeTable { uses }
    }

    /// The uses of each edge, edge by edge.
    pub fn groups(&self) -> impl Iterator<Item = &[EdgeUse]> {
        self.uses.chunk_by(|a, b| a.key == b.key)
    }
}

/// Triangles connected across edges of exactly two uses, as lists of triangle indices, in
/// the order of their lowest triangle.
fn components(triangles: &[[u32; 3]], edges: &EdgeTable) -> Vec<Vec<usize>> {
    let mut parent: Vec<usize> = (0..triangles.len()).collect();
    fn root(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    for group in edges.groups() {
        if let [a, b] = group {
            let (ra, rb) = (root(&mut parent, a.triangle), root(&mut parent, b.triangle));
            // The lower root wins, so a component's root is its lowest triangle.
            parent[ra.max(rb)] = ra.min(rb);
        }
    }
    let mut index_of_root = vec![usize::MAX; triangles.len()];
    let mut out: Vec<Vec<usize>> = Vec::new();
    for t in 0..triangles.len() {
        let r = root(&mut parent, t);
        if index_of_root[r] == usize::MAX {
            index_of_root[r] = out.len();
            out.push(Vec::new());
        }
        out[index_of_root[r]].push(t);
    }
    out
}

/// Builds one shell from its triangles (indices into `all`).
fn shell(vertices: &[Point3<f64>], all: &[[u32; 3]], members: &[usize]) -> Shell {
    let mut triangles: Vec<[u32; 3]> = members.iter().map(|&t| all[t]).collect();
    let edges = EdgeTable::new(&triangles);
    let (mut open_edges, mut non_manifold_edges) = (0, 0);
    for group in edges.groups() {
        match group.len() {
            1 => open_edges += 1,
            2 => {}
            _ => non_manifold_edges += 1,
        }
    }
    let winding = consistent_winding(triangles.len(), &edges);
    let flips = winding.flip.iter().filter(|&&f| f).count();
    // Keep the winding most triangles came with.
    let keep_majority = flips * 2 > triangles.len();
    for (t, &flip) in triangles.iter_mut().zip(&winding.flip) {
        if flip != keep_majority {
            t.swap(1, 2);
        }
    }
    let closed = open_edges == 0 && non_manifold_edges == 0;
    let mut volume = signed_volume(vertices, &triangles);
    let inverted = closed && volume < 0.0;
    if inverted {
        triangles.iter_mut().for_each(|t| t.swap(1, 2));
        volume = -volume;
    }
    let zero_area_triangles = triangles
        .iter()
        .filter(|t| {
            let [a, b, c] = t.map(|v| vertices[v as usize]);
            is_zero_area(&a, &b, &c)
        })
        .count();
    let self_crossing = if closed && !winding.conflict && zero_area_triangles == 0 {
        crossing_pair(vertices, &triangles)
    } else {
        SelfCrossing::NotChecked
    };
    let kind = if self_crossing == SelfCrossing::No && volume > 0.0 {
        ShellKind::Closed
    } else {
        ShellKind::Loose
    };
    let (min, max) = bounds(vertices, &triangles);
    Shell {
        kind,
        open_edges,
        non_manifold_edges,
        rewound_triangles: flips.min(triangles.len() - flips),
        non_orientable: winding.conflict,
        inverted,
        zero_area_triangles,
        self_crossing,
        volume_m3: volume,
        min,
        max,
        triangles,
    }
}

/// A winding of a shell's triangles that agrees across every edge of two uses.
struct Winding {
    /// Per triangle: turn it relative to the file.
    flip: Vec<bool>,
    /// Some edge could not be made to agree.
    conflict: bool,
}

/// Breadth-first over edges of exactly two uses from the first triangle of each connected
/// part: a neighbour that traverses the shared edge the same way is turned.
fn consistent_winding(count: usize, edges: &EdgeTable) -> Winding {
    let mut neighbours: Vec<Vec<(usize, bool)>> = vec![Vec::new(); count];
    for group in edges.groups() {
        if let [a, b] = group {
            // Agreeing windings traverse a shared edge in opposite directions.
            let same_direction = a.forward == b.forward;
            neighbours[a.triangle].push((b.triangle, same_direction));
            neighbours[b.triangle].push((a.triangle, same_direction));
        }
    }
    let mut flip = vec![false; count];
    let mut seen = vec![false; count];
    let mut conflict = false;
    let mut queue = std::collections::VecDeque::new();
    for start in 0..count {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        queue.push_back(start);
        while let Some(t) = queue.pop_front() {
            for &(n, same_direction) in &neighbours[t] {
                let wanted = flip[t] ^ same_direction;
                if seen[n] {
                    conflict |= flip[n] != wanted;
                } else {
                    seen[n] = true;
                    flip[n] = wanted;
                    queue.push_back(n);
                }
            }
        }
    }
    Winding { flip, conflict }
}

/// Enclosed volume (m³) of wound triangles, measured from their vertices' centre (which keeps
/// the sum well conditioned far from the origin).
fn signed_volume(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> f64 {
    let corners = || triangles.iter().flat_map(|t| t.iter());
    let n = (3 * triangles.len()).max(1) as f64;
    let centre = corners().fold(Vector3::zeros(), |s, &v| s + vertices[v as usize].coords) / n;
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| vertices[v as usize].coords - centre);
            a.dot(&b.cross(&c))
        })
        .sum::<f64>()
        / 6.0
}

/// Whether a triangle has no area to rounding: its cross product vanishes against its
/// longest edge (the rule the contact module uses to drop triangles).
pub(crate) fn is_zero_area(a: &Point3<f64>, b: &Point3<f64>, c: &Point3<f64>) -> bool {
    let cross = (b - a).cross(&(c - a));
    let longest = (b - a)
        .norm_squared()
        .max((c - b).norm_squared())
        .max((a - c).norm_squared());
    cross.norm() <= 1e-12 * longest
}

fn bounds(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> (Point3<f64>, Point3<f64>) {
    let (lo, hi) = triangles.iter().flat_map(|t| t.iter()).fold(
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), &v| {
            let p = vertices[v as usize].coords;
            (lo.inf(&p), hi.sup(&p))
        },
    );
    (Point3::from(lo), Point3::from(hi))
}

/// Whether two triangles that share no corner cross each other: a sweep over the
/// triangles' extents along the axis where they overlap least, then an exact-sign test on
/// each overlapping pair; given up when the candidate pairs exceed the work limit.
fn crossing_pair(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> SelfCrossing {
    let corners = |t: &[u32; 3]| t.map(|v| vertices[v as usize]);
    let (lo, hi) = bounds(vertices, triangles);
    let boxes: Vec<(Vector3<f64>, Vector3<f64>)> = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = corners(t);
            (
                a.coords.inf(&b.coords).inf(&c.coords),
                a.coords.sup(&b.coords).sup(&c.coords),
            )
        })
        .collect();
    // The triangles' summed extent along an axis over the mesh's: how many neighbours a
    // triangle meets in a sweep along it (a tube's long triangles all overlap along its axis).
    let crowding = |k: usize| {
        boxes.iter().map(|(a, b)| b[k] - a[k]).sum::<f64>() / (hi[k] - lo[k]).max(f64::MIN_POSITIVE)
    };
    let axis = (0..3)
        .min_by(|&i, &j| crowding(i).total_cmp(&crowding(j)))
        .unwrap_or(0);
    let mut order: Vec<usize> = (0..triangles.len()).collect();
    order.sort_unstable_by(|&i, &j| {
        boxes[i].0[axis]
            .total_cmp(&boxes[j].0[axis])
            .then(i.cmp(&j))
    });
    let budget = CROSSING_PAIRS_PER_TRIANGLE.saturating_mul(triangles.len().max(16));
    let mut pairs = 0usize;
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if boxes[j].0[axis] > boxes[i].1[axis] {
                break;
            }
            let overlap =
                (0..3).all(|d| boxes[i].0[d] <= boxes[j].1[d] && boxes[j].0[d] <= boxes[i].1[d]);
            let (ti, tj) = (&triangles[i], &triangles[j]);
            if !overlap || ti.iter().any(|v| tj.contains(v)) {
                continue;
            }
            pairs += 1;
            if pairs > budget {
                return SelfCrossing::GivenUp;
            }
            if triangles_cross(&corners(ti), &corners(tj)) {
                return SelfCrossing::Yes;
            }
        }
    }
    SelfCrossing::No
}

/// Whether an edge of either triangle passes strictly through the other (touching and
/// coplanar contact are not crossings).
fn triangles_cross(s: &[Point3<f64>; 3], t: &[Point3<f64>; 3]) -> bool {
    (0..3).any(|k| segment_pierces(&s[k], &s[(k + 1) % 3], t))
        || (0..3).any(|k| segment_pierces(&t[k], &t[(k + 1) % 3], s))
}

/// Signed volume of the tetrahedron (a, b, c, d), times six.
fn orient(a: &Point3<f64>, b: &Point3<f64>, c: &Point3<f64>, d: &Point3<f64>) -> f64 {
    (b - a).cross(&(c - a)).dot(&(d - a))
}

/// Whether the segment p–q crosses the triangle strictly: its ends on opposite sides of the
/// plane and the line inside all three edges.
fn segment_pierces(p: &Point3<f64>, q: &Point3<f64>, t: &[Point3<f64>; 3]) -> bool {
    let [a, b, c] = t;
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if !(sp > 0.0 && sq < 0.0 || sp < 0.0 && sq > 0.0) {
        return false;
    }
    let (e0, e1, e2) = (orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a));
    e0 > 0.0 && e1 > 0.0 && e2 > 0.0 || e0 < 0.0 && e1 < 0.0 && e2 < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cube of edge `size` at `at`, wound outward: 8 vertices, 12 triangles.
    fn cube(at: [f64; 3], size: f64) -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
        let v = |x: f64, y: f64, z: f64| {
            Point3::new(at[0] + x * size, at[1] + y * size, at[2] + z * size)
        };
        let vertices = vec![
            v(0., 0., 0.),
            v(1., 0., 0.),
            v(1., 1., 0.),
            v(0., 1., 0.),
            v(0., 0., 1.),
            v(1., 0., 1.),
            v(1., 1., 1.),
            v(0., 1., 1.),
        ];
        let triangles = vec![
            [0, 2, 1],
            [0, 3, 2],
            [4, 5, 6],
            [4, 6, 7],
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ];
        (vertices, triangles)
    }

    fn join(
        a: (Vec<Point3<f64>>, Vec<[u32; 3]>),
        b: (Vec<Point3<f64>>, Vec<[u32; 3]>),
    ) -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
        let offset = a.0.len() as u32;
        let mut vertices = a.0;
        vertices.extend(b.0);
        let mut triangles = a.1;
        triangles.extend(b.1.iter().map(|t| t.map(|v| v + offset)));
        (vertices, triangles)
    }

    #[test]
    fn a_cube_is_one_closed_shell_of_its_volume() {
        let (v, t) = cube([0.0; 3], 2.0);
        let found = analyse(&v, &t);
        assert_eq!(found.shells.len(), 1);
        let shell = &found.shells[0];
        assert_eq!(shell.kind, ShellKind::Closed);
        assert!((shell.volume_m3 - 8.0).abs() < 1e-12);
        assert!(!shell.inverted);
        assert_eq!(shell.rewound_triangles, 0);
        assert_eq!(found.distrust(), None);
    }

    #[test]
    fn an_inward_cube_is_turned_and_a_flipped_triangle_rewound() {
        let (v, mut t) = cube([0.0; 3], 1.0);
        t.iter_mut().for_each(|t| t.swap(0, 1));
        let found = analyse(&v, &t);
        assert!(found.shells[0].inverted);
        assert!((found.shells[0].volume_m3 - 1.0).abs() < 1e-12);

        let (v, mut t) = cube([0.0; 3], 1.0);
        t[5].swap(0, 1);
        let shell = &analyse(&v, &t).shells[0];
        assert_eq!(shell.rewound_triangles, 1);
        assert_eq!(shell.kind, ShellKind::Closed);
        assert!((shell.volume_m3 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn overlapping_cubes_are_two_shells_and_cubes_sharing_an_edge_too() {
        let (v, t) = join(cube([0.0; 3], 1.0), cube([0.5, 0.5, 0.5], 1.0));
        let found = analyse(&v, &t);
        assert_eq!(found.shells.len(), 2);
        assert!(found.shells.iter().all(|s| s.kind == ShellKind::Closed));

        // Two cubes touching along the edge x = 1, y = 1 (the same two vertex indices):
        // that edge has four uses and the cubes come apart as two closed shells.
        let (v, mut t) = join(cube([0.0; 3], 1.0), cube([1.0, 1.0, 0.0], 1.0));
        // Weld the second cube's (0,0,0) and (0,0,1) corners onto the first's (1,1,0) and
        // (1,1,1).
        for tri in t.iter_mut() {
            for c in tri.iter_mut() {
                *c = match *c {
                    8 => 2,
                    12 => 6,
                    other => other,
                };
            }
        }
        let found = analyse(&v, &t);
        assert_eq!(found.shared_edges, 1);
        assert_eq!(found.shells.len(), 2);
        assert!(found.shells.iter().all(|s| s.kind == ShellKind::Closed));
    }

    #[test]
    fn a_cube_with_a_hole_is_loose_and_distrusted() {
        let (v, mut t) = cube([0.0; 3], 1.0);
        t.remove(3);
        let found = analyse(&v, &t);
        assert_eq!(found.shells[0].kind, ShellKind::Loose);
        assert_eq!(found.shells[0].open_edges, 3);
        assert!(found.distrust().is_some_and(|d| d.contains("3 open edges")));
    }

    #[test]
    fn a_closed_shell_folded_through_itself_is_loose() {
        // The cube's corner (0, 0, 1) pulled through the bottom face: the top triangles
        // now cross the bottom ones.
        let (mut v, t) = cube([0.0; 3], 1.0);
        v[4] = Point3::new(0.3, 0.6, -1.0);
        let shell = &analyse(&v, &t).shells[0];
        assert_eq!(shell.self_crossing, SelfCrossing::Yes);
        assert_eq!(shell.kind, ShellKind::Loose);

        let s = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
        ];
        let through = [
            Point3::new(0.2, 0.2, -1.0),
            Point3::new(0.2, 0.2, 1.0),
            Point3::new(2.0, 2.0, 0.5),
        ];
        assert!(triangles_cross(&s, &through));
        let apart = through.map(|p| p + Vector3::new(5.0, 0.0, 0.0));
        assert!(!triangles_cross(&s, &apart));
    }
}
