//! `cable-dict motion`: a waypoint file → a sampled motion CSV, and a summary.

use super::output::{Failure, emit, print_json, tidy};
use cable_dict::motion::{Generated, WaypointFile};
use cable_dict::robot::Robot;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// The waypoint file (TOML: robot, sample rate, speed scale, acceleration, profile,
    /// waypoints; see motions/README.md).
    waypoints: PathBuf,
    /// The motion CSV to write (degrees; replaced atomically).
    #[arg(short, long, value_name = "CSV")]
    output: PathBuf,
    /// Print the summary as JSON (SI units; speeds in rad/s or m/s).
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct JointSummary {
    name: String,
    /// "rad" or "m": the unit of min/max (and per second, of the speeds).
    unit: &'static str,
    min: f64,
    max: f64,
    peak_speed: f64,
    speed_limit: Option<f64>,
}

#[derive(Serialize)]
struct WaypointSummary {
    name: String,
    arrive_s: f64,
    depart_s: f64,
}

#[derive(Serialize)]
struct Summary {
    output: PathBuf,
    robot: String,
    profile: &'static str,
    speed_scale: f64,
    sample_rate_hz: f64,
    samples: usize,
    duration_s: f64,
    joints: Vec<JointSummary>,
    waypoints: Vec<WaypointSummary>,
}

pub fn run(args: Args) -> Result<(), Failure> {
    let file = WaypointFile::from_file(&args.waypoints).map_err(Failure::input)?;
    let robot = Robot::from_urdf_file(&file.robot_urdf).map_err(|e| {
        let context = format!("{}: `robot`", file.source.display());
        Failure::input(anyhow::Error::new(e).context(context))
    })?;
    let generated = file.generate(&robot).map_err(Failure::input)?;
    generated
        .motion
        .write_csv(&args.output, &file.csv_comment())
        .map_err(Failure::input)?;
    let summary = summarize(&args, &file, &robot, &generated);
    if args.json {
        print_json(&summary)
    } else {
        emit(&text(&summary, &robot))
    }
}

fn summarize(args: &Args, file: &WaypointFile, robot: &Robot, generated: &Generated) -> Summary {
    let motion = &generated.motion;
    let joints = (motion.ranges().into_iter().zip(motion.peak_speeds()))
        .enumerate()
        .map(|(j, ((min, max), peak_speed))| {
            let joint = robot.actuated_joint(j);
            JointSummary {
                name: joint.name.clone(),
                unit: if joint.kind.is_rotary() { "rad" } else { "m" },
                min,
                max,
                peak_speed,
                speed_limit: joint.limits.and_then(|l| l.velocity),
            }
        })
        .collect();
    Summary {
        output: args.output.clone(),
        robot: robot.name.clone(),
        profile: file.profile.name(),
        speed_scale: file.speed_scale,
        sample_rate_hz: file.sample_rate_hz,
        samples: motion.len(),
        duration_s: motion.duration_s(),
        joints,
        waypoints: generated
            .waypoints
            .iter()
            .map(|w| WaypointSummary {
                name: w.name.clone(),
                arrive_s: w.arrive_s,
                depart_s: w.depart_s,
            })
            .collect(),
    }
}

/// The summary for people: degrees (mm), per-joint table, waypoint timing.
fn text(summary: &Summary, robot: &Robot) -> String {
    let mut out = format!(
        "{}: {} samples over {:.3} s ({} profile, speed scale {}, {} Hz)\n\n",
        summary.output.display(),
        summary.samples,
        summary.duration_s,
        summary.profile,
        summary.speed_scale,
        summary.sample_rate_hz
    );
    let _ = writeln!(
        out,
        "{:<12} {:>10} {:>10} {:>10} {:>12} {:>12} {:>6}",
        "joint", "min", "max", "range", "peak speed", "limit", "use %"
    );
    for (j, joint) in summary.joints.iter().enumerate() {
        let (scale, unit) = robot.actuated_joint(j).kind.display_unit();
        let limit = joint.speed_limit.map_or("-".to_string(), |v| {
            format!("{:.1} {unit}/s", tidy(v * scale))
        });
        let share = joint.speed_limit.map_or("-".to_string(), |v| {
            format!("{:.1}", 100.0 * joint.peak_speed / v)
        });
        let _ = writeln!(
            out,
            "{:<12} {:>10} {:>10} {:>10} {:>12} {:>12} {:>6}",
            joint.name,
            format!("{:.2} {unit}", tidy(joint.min * scale)),
            format!("{:.2} {unit}", tidy(joint.max * scale)),
            format!("{:.2} {unit}", tidy((joint.max - joint.min) * scale)),
            format!("{:.1} {unit}/s", tidy(joint.peak_speed * scale)),
            limit,
            share
        );
    }
    out.push_str("\nwaypoint                    arrive s   depart s\n");
    for w in &summary.waypoints {
        let _ = writeln!(
            out,
            "{:<26} {:>10.3} {:>10.3}",
            w.name, w.arrive_s, w.depart_s
        );
    }
    out
}
