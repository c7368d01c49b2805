//! Benchmark of `min_clearance` on a real robot's STL meshes: the UR5 of tests/data/robots
//! (ROS-Industrial's collision meshes: 446–1176 triangles a link, up to six overlapping
//! shells, some wound inward) at a folded pose (joints 0, −90, 90, −90, −90, 0 deg:
//! forearm horizontal along +x, flange down), with a 50-sub-segment (10 mm) cable:
//!
//! - along the top of the forearm, 15–45 mm above its tube (a bow), all links;
//! - the same cable 40 mm lower, inside the forearm tube;
//! - the same cable 1 m away (everything culled);
//! - `Obstacles::from_robot` for the UR5 (the meshes' shells analysed, BVHs built).
//!
//! It uses only the API that existed before the mesh solids were split into shells, so the
//! same file measures both versions (docs/physics.md, "Contact with the robot").

use std::hint::black_box;

use cable_dict::robot::Robot;
use cable_dict::stress::contact::{Obstacles, min_clearance};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Point3, Vector3};

const SUB_SEGMENTS: usize = 50;
const PITCH_M: f64 = 0.010;
const RADIUS_M: f64 = 0.004;

/// 50 sub-segments from x = 40 mm to 440 mm (world), 16.5 mm off the arm's plane (the forearm
/// tube's axis), `height_m` above the forearm axis plus a 30 mm bow.
fn forearm_cable(height_m: f64) -> Vec<Point3<f64>> {
    (0..=SUB_SEGMENTS)
        .map(|k| {
            let s = k as f64 / SUB_SEGMENTS as f64;
            let bow = 0.03 * (std::f64::consts::PI * s).sin();
            Point3::new(
                0.04 + s * SUB_SEGMENTS as f64 * PITCH_M * 0.8,
                0.0165,
                0.514 + height_m + bow,
            )
        })
        .collect()
}

fn bench_real_meshes(c: &mut Criterion) {
    let urdf = "tests/data/robots/ur_description/urdf/ur5.urdf";
    let robot = Robot::from_urdf_file(urdf).expect("UR5");
    let obstacles = Obstacles::from_robot(&robot).expect("obstacles");
    let q: Vec<f64> = [0.0f64, -90.0, 90.0, -90.0, -90.0, 0.0]
        .iter()
        .map(|d| d.to_radians())
        .collect();
    let poses = robot.link_poses(&q).expect("poses");
    let near = forearm_cable(0.053);
    let inside = forearm_cable(0.013);
    let far: Vec<Point3<f64>> = near
        .iter()
        .map(|p| p + Vector3::new(0.0, 1.0, 0.5))
        .collect();
    for (name, nodes) in [("near", &near), ("inside", &inside), ("far", &far)] {
        if let Ok(Some(found)) = min_clearance(&obstacles, &poses, nodes, RADIUS_M, &[]) {
            eprintln!(
                "UR5 {name}: clearance {:.2} mm to {} (sub-segment {})",
                found.clearance_m * 1e3,
                robot.links[found.link].name,
                found.sub_segment
            );
        }
    }
    c.bench_function("contact: UR5 meshes, cable along the forearm", |b| {
        b.iter(|| min_clearance(&obstacles, &poses, black_box(&near), RADIUS_M, &[]))
    });
    c.bench_function("contact: UR5 meshes, cable inside the forearm", |b| {
        b.iter(|| min_clearance(&obstacles, &poses, black_box(&inside), RADIUS_M, &[]))
    });
    c.bench_function("contact: UR5 meshes, cable far from the arm", |b| {
        b.iter(|| min_clearance(&obstacles, &poses, black_box(&far), RADIUS_M, &[]))
    });
    c.bench_function("contact: Obstacles::from_robot (UR5 meshes)", |b| {
        b.iter(|| Obstacles::from_robot(black_box(&robot)))
    });
}

criterion_group!(benches, bench_real_meshes);
criterion_main!(benches);
