//! Benchmark of `min_clearance` on the bundled Viper s850 at a typical working pose, with a
//! 50-sub-segment (10 mm) cable running along the forearm 15–45 mm from its surface:
//!
//! - all 8 links (12 colliders), no clamp zones;
//! - the same with 30 mm clamp zones on link_3 and link_4;
//! - only the forearm's own link and its neighbours (link_3, link_4, link_5);
//! - the same cable 70 mm closer to the axis, so it runs inside the forearm tube;
//! - a cable 0.5 m away from the arm (everything culled);
//! - the forearm tube alone as a closed 1024-triangle STL mesh, with the same cable beside it
//!   and pushed into it;
//! - the cable's closest approach to itself (`self_contact`): the same 50 sub-segments (which
//!   never come back toward each other: every pair is looked at), the same searched only
//!   below 20 mm as the attachment test asks (`self_contact_within`), and a loop of 150
//!   sub-segments that nearly closes (a ring hanging between two clamps 12 cm apart).

use std::hint::black_box;

use cable_dict::robot::Robot;
use cable_dict::stress::contact::{
    ClampZone, GuideEnd, Obstacles, min_clearance, min_clearance_to_links,
};
use cable_dict::stress::{self_contact, self_contact_within};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Point3, Vector3};

const SUB_SEGMENTS: usize = 50;
const PITCH_M: f64 = 0.010;
const RADIUS_M: f64 = 0.004;

/// 50 sub-segments alongside the forearm (link_4's z axis), `offset_m` from its axis plus a
/// 30 mm bow, from the top of link_3's J4 housing (the link_4 frame) to beyond the
/// wrist.
fn forearm_cable(
    robot: &Robot,
    poses: &[cable_dict::pose::Pose],
    offset_m: f64,
) -> Vec<Point3<f64>> {
    let link_4 = robot.link_index("link_4").expect("link_4");
    let frame = poses[link_4];
    let along = frame.rotation * Vector3::z();
    let side = frame.rotation * Vector3::x();
    let length = SUB_SEGMENTS as f64 * PITCH_M;
    (0..=SUB_SEGMENTS)
        .map(|k| {
            let s = k as f64 / SUB_SEGMENTS as f64;
            let bow = 0.03 * (std::f64::consts::PI * s).sin();
            frame * Point3::origin() + along * (s * length * 0.95) + side * (offset_m + bow)
        })
        .collect()
}

fn bench_contact(c: &mut Criterion) {
    let robot = Robot::from_urdf_file("robots/viper_s850/viper_s850.urdf").expect("Viper");
    let obstacles = Obstacles::from_robot(&robot).expect("obstacles");
    // A typical working pose (deg): 20, −35, 110, 30, 45, 0.
    let q: Vec<f64> = [20.0f64, -35.0, 110.0, 30.0, 45.0, 0.0]
        .iter()
        .map(|d| d.to_radians())
        .collect();
    let poses = robot.link_poses(&q).expect("poses");
    let link = |name: &str| robot.link_index(name).expect("link");
    let (link_3, link_4, link_5) = (link("link_3"), link("link_4"), link("link_5"));

    let near = forearm_cable(&robot, &poses, 0.08);
    let inside = forearm_cable(&robot, &poses, 0.04 - 0.03);
    let far: Vec<Point3<f64>> = near
        .iter()
        .map(|p| p + Vector3::new(0.0, 1.0, 0.5))
        .collect();
    let zones = [
        ClampZone::of_length(GuideEnd::Start, link_3, 0.03, PITCH_M),
        ClampZone::of_length(GuideEnd::End, link_4, 0.03, PITCH_M),
    ];
    for (name, nodes) in [("near", &near), ("inside", &inside), ("far", &far)] {
        let found = min_clearance(&obstacles, &poses, nodes, RADIUS_M, &[]).expect("valid");
        if let Some(found) = found {
            eprintln!(
                "{name}: clearance {:.2} mm to {} (sub-segment {})",
                found.clearance_m * 1e3,
                robot.links[found.link].name,
                found.sub_segment
            );
        }
    }

    c.bench_function("contact: forearm cable, 50 sub-segments, all links", |b| {
        b.iter(|| min_clearance(&obstacles, &poses, black_box(&near), RADIUS_M, &[]))
    });
    c.bench_function(
        "contact: forearm cable, 50 sub-segments, clamp zones",
        |b| b.iter(|| min_clearance(&obstacles, &poses, black_box(&near), RADIUS_M, &zones)),
    );
    c.bench_function("contact: forearm cable, 50 sub-segments, links 3-5", |b| {
        let links = [link_3, link_4, link_5];
        b.iter(|| {
            min_clearance_to_links(&obstacles, &poses, black_box(&near), RADIUS_M, &[], &links)
        })
    });
    c.bench_function("contact: forearm cable pushed into the forearm", |b| {
        b.iter(|| min_clearance(&obstacles, &poses, black_box(&inside), RADIUS_M, &[]))
    });
    c.bench_function("contact: cable far from the arm", |b| {
        b.iter(|| min_clearance(&obstacles, &poses, black_box(&far), RADIUS_M, &[]))
    });
    c.bench_function("contact: Obstacles::from_robot (Viper)", |b| {
        b.iter(|| Obstacles::from_robot(black_box(&robot)))
    });

    // The forearm tube (r 60 mm, 230 mm long) as a mesh, in the world at link_4's q = 0 pose
    // frame, i.e. the mesh robot's only link sits where link_4 is in the Viper pose above.
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("tube.stl"), tube_stl(0.06, 0.23, 256)).expect("write");
    let urdf = r#"<robot name="tube"><link name="base_link"/>
  <link name="tube"><collision><origin xyz="0 0 0.115"/>
    <geometry><mesh filename="tube.stl"/></geometry></collision></link>
  <joint name="j" type="prismatic"><parent link="base_link"/><child link="tube"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"#;
    let path = dir.path().join("tube.urdf");
    std::fs::write(&path, urdf).expect("write");
    let tube = Robot::from_urdf_file(&path).expect("tube robot");
    let tube_obstacles = Obstacles::from_robot(&tube).expect("tube obstacles");
    let link_4 = poses[link_4];
    let tube_poses = [cable_dict::pose::Pose::identity(), link_4];
    for (name, nodes) in [("near", &near), ("inside", &inside)] {
        if let Ok(Some(found)) = min_clearance(&tube_obstacles, &tube_poses, nodes, RADIUS_M, &[]) {
            eprintln!(
                "mesh tube, {name}: clearance {:.3} mm",
                found.clearance_m * 1e3
            );
        }
    }
    c.bench_function("contact: 1024-triangle mesh tube, cable beside it", |b| {
        b.iter(|| {
            min_clearance(
                &tube_obstacles,
                &tube_poses,
                black_box(&near),
                RADIUS_M,
                &[],
            )
        })
    });
    c.bench_function("contact: 1024-triangle mesh tube, cable inside it", |b| {
        b.iter(|| {
            min_clearance(
                &tube_obstacles,
                &tube_poses,
                black_box(&inside),
                RADIUS_M,
                &[],
            )
        })
    });
}

/// ASCII STL of a closed cylinder (radius, length along z from −length/2, `n` sides):
/// 4·n outward triangles.
fn tube_stl(radius: f64, length: f64, n: usize) -> String {
    let ring = |i: usize, z: f64| {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        [radius * a.cos(), radius * a.sin(), z]
    };
    let (lo, hi) = (-0.5 * length, 0.5 * length);
    let mut triangles = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        triangles.push([ring(i, lo), ring(j, lo), ring(j, hi)]);
        triangles.push([ring(i, lo), ring(j, hi), ring(i, hi)]);
        triangles.push([[0.0, 0.0, hi], ring(i, hi), ring(j, hi)]);
        triangles.push([[0.0, 0.0, lo], ring(j, lo), ring(i, lo)]);
    }
    let mut text = String::from("solid tube\n");
    for t in triangles {
        text += "facet normal 0 0 0\n outer loop\n";
        for [x, y, z] in t {
            text += &format!("  vertex {x} {y} {z}\n");
        }
        text += " endloop\nendfacet\n";
    }
    text + "endsolid tube\n"
}

/// The clearance of a cable to itself, next to the robot clearance it is checked with.
fn bench_self_contact(c: &mut Criterion) {
    let robot = Robot::from_urdf_file("robots/viper_s850/viper_s850.urdf").expect("Viper");
    let q: Vec<f64> = [20.0f64, -35.0, 110.0, 30.0, 45.0, 0.0]
        .iter()
        .map(|d| d.to_radians())
        .collect();
    let poses = robot.link_poses(&q).expect("poses");
    let cable = forearm_cable(&robot, &poses, 0.08);
    let diameter = 2.0 * RADIUS_M;
    c.bench_function("self_contact/forearm cable, 50 sub-segments", |b| {
        b.iter(|| self_contact(black_box(&cable), diameter, PITCH_M))
    });
    // As the attachment test asks: only approaches closer than the robot is (here 20 mm).
    c.bench_function(
        "self_contact/forearm cable, 50 sub-segments, within 20 mm",
        |b| b.iter(|| self_contact_within(black_box(&cable), diameter, PITCH_M, 0.02 + diameter)),
    );
    // 150 sub-segments around a circle from one clamp to another 12 cm beside it.
    let ring: Vec<Point3<f64>> = (0..=150)
        .map(|k| {
            let a = 0.25 * std::f64::consts::TAU * 0.1
                + 0.95 * std::f64::consts::TAU * k as f64 / 150.0;
            Point3::new(0.24 * a.sin(), 0.0, 0.24 * (a.cos() - 1.0))
        })
        .collect();
    c.bench_function("self_contact/hanging ring, 150 sub-segments", |b| {
        b.iter(|| self_contact(black_box(&ring), diameter, PITCH_M))
    });
}

criterion_group!(benches, bench_contact, bench_self_contact);
criterion_main!(benches);
