//! `robot-info` on collision meshes: per mesh its triangles, shells, surface defects, volume
//! and bounding box, and a warning naming the link and the file when its solid cannot be
//! trusted.
//!
//! The real robot descriptions (tests/data/robots) are judged by the independent STL reader
//! of `reference::mesh_solid` (and by geometry computed here from its triangles), the
//! synthetic cubes by construction; no expected number is taken from the tool's own output.

use crate::reference;

use crate::common::run;
use reference::mesh_solid::{ReferenceSolid, Triangle};
use serde_json::Value;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The four real robots, relative to tests/data/robots.
const ROBOTS: [&str; 4] = [
    "ur_description/urdf/ur5.urdf",
    "franka_description/urdf/panda.urdf",
    "kuka_kr6_support/urdf/kr6r900sixx.urdf",
    "abb_irb2400_support/urdf/irb2400.urdf",
];

fn robots_folder() -> PathBuf {
    crate::common::root().join("tests/data/robots")
}

/// `robot-info --json` of `urdf`, which must succeed.
fn report(urdf: &Path) -> Value {
    let output = run(&["robot-info", urdf.to_str().unwrap(), "--json"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}: {stderr}",
        urdf.display()
    );
    serde_json::from_slice(&output.stdout).expect("JSON")
}

/// `robot-info` text output of `urdf`, which must succeed.
fn text(urdf: &Path) -> String {
    let output = run(&["robot-info", urdf.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}: {stderr}",
        urdf.display()
    );
    String::from_utf8(output.stdout).expect("UTF-8")
}

/// Every mesh collider of a report: (link name, its "mesh" object).
fn meshes(report: &Value) -> Vec<(String, Value)> {
    let mut found = Vec::new();
    for link in report["links"].as_array().expect("links") {
        for collider in link["colliders"].as_array().expect("colliders") {
            if collider["shape"] == "mesh" {
                let mesh = collider["mesh"].clone();
                assert!(mesh.is_object(), "{}: no mesh report", link["name"]);
                found.push((link["name"].as_str().unwrap().to_string(), mesh));
            } else {
                assert!(collider.get("mesh").is_none(), "{collider}");
            }
        }
    }
    found
}

fn number(value: &Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("{value} is not a number"))
}

fn count(value: &Value) -> usize {
    value
        .as_u64()
        .unwrap_or_else(|| panic!("{value} is not a count")) as usize
}

fn point(value: &Value) -> [f64; 3] {
    let a = value.as_array().expect("three numbers");
    assert_eq!(a.len(), 3, "{value}");
    [number(&a[0]), number(&a[1]), number(&a[2])]
}

fn mesh_of<'a>(meshes: &'a [(String, Value)], link: &str) -> &'a Value {
    &meshes
        .iter()
        .find(|(l, _)| l == link)
        .unwrap_or_else(|| panic!("no mesh on {link}"))
        .1
}

/// Bounding box of some triangles.
fn bounds<'a>(triangles: impl IntoIterator<Item = &'a Triangle>) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in triangles.into_iter().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    (lo, hi)
}

/// Signed volume enclosed by triangles as wound (divergence theorem, about their first
/// vertex): positive when `(b − a) × (c − a)` points outward.
fn signed_volume<'a>(triangles: impl IntoIterator<Item = &'a Triangle> + Clone) -> f64 {
    let Some(o) = triangles.clone().into_iter().next().map(|t| t[0]) else {
        return 0.0;
    };
    let sub = |a: [f64; 3]| [a[0] - o[0], a[1] - o[1], a[2] - o[2]];
    triangles
        .into_iter()
        .map(|t| {
            let [a, b, c] = t.map(sub);
            let cross = [
                b[1] * c[2] - b[2] * c[1],
                b[2] * c[0] - b[0] * c[2],
                b[0] * c[1] - b[1] * c[0],
            ];
            (a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2]) / 6.0
        })
        .sum()
}

/// A vertex position as a key (−0.0 counted as 0.0).
fn key(v: [f64; 3]) -> [u64; 3] {
    v.map(|x| (x + 0.0).to_bits())
}

/// Directed edges of triangles (by vertex position), with their uses.
fn directed_edges<'a>(
    triangles: impl IntoIterator<Item = &'a Triangle>,
) -> HashMap<([u64; 3], [u64; 3]), usize> {
    let mut uses = HashMap::new();
    for t in triangles {
        for k in 0..3 {
            *uses.entry((key(t[k]), key(t[(k + 1) % 3]))).or_insert(0) += 1;
        }
    }
    uses
}

/// Edges (undirected, by vertex position) used by more than two triangles.
fn edges_of_more_than_two_triangles(triangles: &[Triangle]) -> usize {
    let mut uses: HashMap<([u64; 3], [u64; 3]), usize> = HashMap::new();
    for ((a, b), n) in directed_edges(triangles) {
        *uses.entry(if a < b { (a, b) } else { (b, a) }).or_insert(0) += n;
    }
    uses.values().filter(|&&n| n > 2).count()
}

#[test]
fn real_robots_report_each_mesh_as_the_independent_reader_reads_it() {
    for robot in ROBOTS {
        let urdf = robots_folder().join(robot);
        let urdf_text = std::fs::read_to_string(&urdf).unwrap();
        // The reference reads the files unscaled: the URDFs must not scale their meshes.
        assert!(!urdf_text.contains("scale="), "{robot} scales a mesh");
        let report = report(&urdf);
        let meshes = meshes(&report);
        assert_eq!(
            meshes.len(),
            urdf_text.matches("<mesh ").count(),
            "{robot}: one report per <mesh> (the copies keep only collision geometry)"
        );
        for (link, mesh) in &meshes {
            let file = mesh["file"].as_str().expect("file");
            let solid = ReferenceSolid::from_stl(Path::new(file), 1.0);
            let what = format!("{robot}, {link}, {file}");
            assert_eq!(count(&mesh["triangles"]), solid.triangles().len(), "{what}");
            let (lo, hi) = solid.bounds();
            let (min, max) = (point(&mesh["min_m"]), point(&mesh["max_m"]));
            for k in 0..3 {
                // Both read the same single-precision numbers; the JSON keeps 12 digits.
                assert!((min[k] - lo[k]).abs() < 1e-9, "{what}: min {min:?} {lo:?}");
                assert!((max[k] - hi[k]).abs() < 1e-9, "{what}: max {max:?} {hi:?}");
            }
            // The report is consistent with itself: its shells hold the triangles that were
            // not dropped, its counts add up.
            let list = mesh["shell_list"].as_array().expect("shell list");
            assert_eq!(list.len(), count(&mesh["shells"]), "{what}");
            assert_eq!(
                count(&mesh["closed_shells"]) + count(&mesh["loose_shells"]),
                count(&mesh["shells"]),
                "{what}"
            );
            let in_shells: usize = list.iter().map(|s| count(&s["triangles"])).sum();
            assert_eq!(
                in_shells + count(&mesh["collapsed_triangles"]),
                solid.triangles().len(),
                "{what}"
            );
            assert!(number(&mesh["volume_m3"]) > 0.0, "{what}");
        }
    }
}

#[test]
fn ur5_forearm_is_six_shells_two_of_them_wound_inward() {
    let urdf = robots_folder().join(ROBOTS[0]);
    let report = report(&urdf);
    let meshes = meshes(&report);
    let mesh = mesh_of(&meshes, "forearm_link");
    let file = mesh["file"].as_str().unwrap();
    assert!(file.ends_with("forearm.stl"), "{file}");
    let solid = ReferenceSolid::from_stl(Path::new(file), 1.0);

    // The reference's shells: vertex-connected components. The UR5's shells are disjoint, so
    // these are the shells the tool finds too.
    let mut shells: Vec<Vec<Triangle>> = vec![Vec::new(); solid.shell_count()];
    for (t, &s) in solid.triangles().iter().zip(solid.shell_of()) {
        shells[s].push(*t);
    }
    assert_eq!(shells.len(), 6);
    // Each is closed and consistently wound (every directed edge used once, its reverse
    // once), so the sign of its volume says whether the file winds it inward.
    for (s, shell) in shells.iter().enumerate() {
        let edges = directed_edges(shell);
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1, "shell {s}: a directed edge used {n} times");
            assert_eq!(edges.get(&(b, a)), Some(&1), "shell {s}: an open edge");
        }
    }
    let volumes: Vec<f64> = shells.iter().map(signed_volume).collect();
    let inward = volumes.iter().filter(|&&v| v < 0.0).count();
    assert_eq!(inward, 2, "{volumes:?}");
    assert_eq!(edges_of_more_than_two_triangles(solid.triangles()), 0);

    assert_eq!(count(&mesh["shells"]), shells.len());
    assert_eq!(count(&mesh["closed_shells"]), shells.len());
    assert_eq!(count(&mesh["shells_wound_inward"]), inward);
    assert_eq!(count(&mesh["open_edges"]), 0);
    assert_eq!(count(&mesh["shared_edges"]), 0);
    assert_eq!(count(&mesh["triangles_wound_against_neighbours"]), 0);
    let total: f64 = volumes.iter().map(|v| v.abs()).sum();
    assert!(
        (number(&mesh["volume_m3"]) - total).abs() < 1e-9 * total,
        "{} vs {total}",
        mesh["volume_m3"]
    );
    // Shell by shell: the reported shell with the same triangles and bounding box has the
    // reference's volume and inwardness.
    let list = mesh["shell_list"].as_array().unwrap();
    let mut matched = vec![false; shells.len()];
    for reported in list {
        let (min, max) = (point(&reported["min_m"]), point(&reported["max_m"]));
        let s = (0..shells.len())
            .find(|&s| {
                let (lo, hi) = bounds(&shells[s]);
                !matched[s]
                    && shells[s].len() == count(&reported["triangles"])
                    && (0..3).all(|k| (lo[k] - min[k]).abs() < 1e-9)
                    && (0..3).all(|k| (hi[k] - max[k]).abs() < 1e-9)
            })
            .unwrap_or_else(|| panic!("no reference shell like {reported}"));
        matched[s] = true;
        assert_eq!(reported["kind"], "closed", "{reported}");
        assert_eq!(reported["wound_inward"], volumes[s] < 0.0, "{reported}");
        let volume = number(&reported["volume_m3"]);
        assert!(
            (volume - volumes[s].abs()).abs() < 1e-9 * volume,
            "{reported}: {}",
            volumes[s]
        );
    }

    let text = text(&urdf);
    let line = text
        .lines()
        .skip_while(|l| !l.contains("forearm.stl"))
        .nth(1)
        .expect("a second line for the forearm mesh");
    assert!(
        line.contains("2 shells wound inward (turned outward)"),
        "{line}"
    );
    assert!(!text.contains("warning"), "{text}");
}

#[test]
fn kuka_link_2_shells_meet_at_shared_edges_without_a_warning() {
    let urdf = robots_folder().join(ROBOTS[2]);
    let report = report(&urdf);
    let meshes = meshes(&report);
    let mesh = mesh_of(&meshes, "link_2");
    let file = mesh["file"].as_str().unwrap();
    assert!(file.ends_with("kr6r900sixx/collision/link_2.stl"), "{file}");
    let solid = ReferenceSolid::from_stl(Path::new(file), 1.0);
    // Counted here from the file: edges where more than two triangles meet (by vertex
    // position, as the tool's vertices are the file's distinct positions).
    let shared = edges_of_more_than_two_triangles(solid.triangles());
    assert!(shared > 0);
    assert_eq!(count(&mesh["shared_edges"]), shared, "{mesh}");
    assert_eq!(count(&mesh["open_edges"]), 0, "{mesh}");
    let warnings = report["warnings"].as_array().expect("warnings");
    assert!(
        warnings.iter().all(|w| w["link"] != "link_2"),
        "{warnings:?}"
    );
    let text = text(&urdf);
    assert!(
        !text
            .lines()
            .any(|l| l.starts_with("warning") && l.contains("link_2")),
        "{text}"
    );
}

/// The 12 triangles of an axis-aligned cube `[0, edge]³`, wound outward.
fn cube(edge: f64) -> Vec<Triangle> {
    let corner = |i: usize| [0, 1, 2].map(|k| if i >> k & 1 == 1 { edge } else { 0.0 });
    let faces = [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ];
    let mut triangles = Vec::new();
    for [a, b, c, d] in faces {
        triangles.push([corner(a), corner(b), corner(c)]);
        triangles.push([corner(a), corner(c), corner(d)]);
    }
    triangles
}

fn write_ascii_stl(path: &Path, triangles: &[Triangle]) {
    let mut text = String::from("solid test\n");
    for t in triangles {
        text += "  facet normal 0 0 0\n    outer loop\n";
        for v in t {
            text += &format!("      vertex {} {} {}\n", v[0], v[1], v[2]);
        }
        text += "    endloop\n  endfacet\n";
    }
    text += "endsolid test\n";
    std::fs::write(path, text).unwrap();
}

/// A URDF of a base and one moving link per `(link, mesh file)`.
fn write_urdf(path: &Path, links: &[(&str, &str)]) {
    let mut text = String::from("<robot name=\"cubes\">\n  <link name=\"base\"/>\n");
    for (k, (link, file)) in links.iter().enumerate() {
        text += &format!(
            "  <link name=\"{link}\"><collision><geometry><mesh filename=\"{file}\"/></geometry>\
             </collision></link>\n  <joint name=\"j{k}\" type=\"revolute\"><parent link=\"base\"/>\
             <child link=\"{link}\"/><axis xyz=\"0 0 1\"/>\
             <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n"
        );
    }
    text += "</robot>\n";
    std::fs::write(path, text).unwrap();
}

/// Exactly representable in single precision, as STL stores it.
const EDGE_M: f64 = 0.125;

#[test]
fn a_cube_with_a_hole_is_warned_about_naming_link_and_file_and_a_clean_cube_is_not() {
    let dir = tempfile::tempdir().unwrap();
    let mut holed = cube(EDGE_M);
    holed.remove(5);
    write_ascii_stl(&dir.path().join("holed.stl"), &holed);
    write_ascii_stl(&dir.path().join("clean.stl"), &cube(EDGE_M));
    let inward: Vec<Triangle> = cube(EDGE_M)
        .into_iter()
        .map(|t| [t[0], t[2], t[1]])
        .collect();
    write_ascii_stl(&dir.path().join("inward.stl"), &inward);

    // The holed cube among others: one warning, naming its link and file.
    let urdf = dir.path().join("holed.urdf");
    write_urdf(
        &urdf,
        &[
            ("clean_link", "clean.stl"),
            ("holed_link", "holed.stl"),
            ("inward_link", "inward.stl"),
        ],
    );
    let report = report(&urdf);
    let warnings = report["warnings"].as_array().expect("warnings");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let warning = &warnings[0];
    assert_eq!(warning["link"], "holed_link");
    assert!(
        warning["file"].as_str().unwrap().ends_with("holed.stl"),
        "{warning}"
    );
    // Removing one triangle of a closed surface opens its three edges.
    assert!(
        warning["problem"]
            .as_str()
            .unwrap()
            .contains("3 open edges"),
        "{warning}"
    );
    let meshes = meshes(&report);
    let holed_mesh = mesh_of(&meshes, "holed_link");
    assert_eq!(count(&holed_mesh["triangles"]), 11);
    assert_eq!(count(&holed_mesh["open_edges"]), 3);
    assert_eq!(count(&holed_mesh["shells"]), 1);
    assert_eq!(count(&holed_mesh["loose_shells"]), 1);
    for (link, inward_shells) in [("clean_link", 0), ("inward_link", 1)] {
        let mesh = mesh_of(&meshes, link);
        assert_eq!(count(&mesh["triangles"]), 12, "{link}");
        assert_eq!(count(&mesh["vertices"]), 8, "{link}");
        assert_eq!(count(&mesh["shells"]), 1, "{link}");
        assert_eq!(count(&mesh["closed_shells"]), 1, "{link}");
        assert_eq!(count(&mesh["open_edges"]), 0, "{link}");
        assert_eq!(count(&mesh["shells_wound_inward"]), inward_shells, "{link}");
        let volume = number(&mesh["volume_m3"]);
        assert!((volume - EDGE_M.powi(3)).abs() < 1e-15, "{link}: {volume}");
        assert_eq!(point(&mesh["min_m"]), [0.0; 3], "{link}");
        assert_eq!(point(&mesh["max_m"]), [EDGE_M; 3], "{link}");
    }

    let text = text(&urdf);
    let warning_lines: Vec<&str> = text.lines().filter(|l| l.starts_with("warning:")).collect();
    assert_eq!(warning_lines.len(), 1, "{text}");
    let line = warning_lines[0];
    for expected in ["link 'holed_link'", "holed.stl", "3 open edges"] {
        assert!(line.contains(expected), "{expected}: {line}");
    }

    // The clean and the inward cube alone: no warning.
    let urdf = dir.path().join("clean.urdf");
    write_urdf(
        &urdf,
        &[("clean_link", "clean.stl"), ("inward_link", "inward.stl")],
    );
    let report = self::report(&urdf);
    assert_eq!(report["warnings"], Value::Array(Vec::new()));
    assert!(!self::text(&urdf).contains("warning"));
}

/// The joint table of every real robot stays aligned whatever its names' lengths (the UR5's
/// `base_link-base_link_inertia` pushed every later column): each column starts at the same
/// character in every row, found from the header's titles.
#[test]
fn the_joint_table_is_aligned_with_long_names() {
    for robot in ROBOTS {
        let urdf = robots_folder().join(robot);
        let output = run(&["robot-info", urdf.to_str().unwrap()]);
        let text = String::from_utf8_lossy(&output.stdout);
        let lines: Vec<&str> = text.lines().collect();
        let header = lines
            .iter()
            .position(|l| l.starts_with("#") && l.contains("parent → child"))
            .expect("a joint table");
        let columns = |line: &str| -> Vec<usize> {
            // Character positions where a cell starts after a run of spaces.
            let chars: Vec<char> = line.chars().collect();
            (1..chars.len())
                .filter(|&i| chars[i] != ' ' && chars[i - 1] == ' ')
                .collect()
        };
        let title = |name: &str| lines[header].split(name).next().unwrap().chars().count();
        let (joint, kind) = (title("joint"), title("type"));
        for line in lines[header + 1..].iter().take_while(|l| !l.is_empty()) {
            let starts = columns(line);
            assert!(starts.contains(&joint), "{robot}: «{line}»");
            assert!(starts.contains(&kind), "{robot}: «{line}»");
        }
    }
}
