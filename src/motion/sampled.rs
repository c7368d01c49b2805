//! [`Motion`]: a validated, sampled joint trajectory.

use super::MotionError;
use super::units::ColumnUnit;
use crate::robot::Robot;

/// A robot motion: joint vectors (SI: rad / m, joint-vector order) at strictly increasing
/// times (s).
///
/// Built only through [`Motion::new`] (or the CSV reader, which calls it), so every motion
/// has at least one sample, one value per actuated joint, finite values within the joint
/// limits and strictly increasing times. Joint values are kept on the doubles that print
/// exactly in degrees (millimetres for prismatic joints), so writing a motion as CSV and
/// reading it back gives the same bits.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    joint_names: Vec<String>,
    rotary: Vec<bool>,
    times_s: Vec<f64>,
    samples: Vec<Vec<f64>>,
}

impl Motion {
    /// Validates samples against `robot`: `times_s[i]` (s) is the time of `samples[i]`, a
    /// joint vector (rad / m) in the robot's joint-vector order.
    ///
    /// Each value moves by at most an ulp or two to a value that round-trips exactly through
    /// the CSV unit (degrees or millimetres).
    pub fn new(
        robot: &Robot,
        times_s: Vec<f64>,
        samples: Vec<Vec<f64>>,
    ) -> Result<Motion, MotionError> {
        check_times(&times_s, samples.len())?;
        let rotary: Vec<bool> = (0..robot.dof())
            .map(|j| robot.actuated_joint(j).kind.is_rotary())
            .collect();
        let mut snapped = samples;
        for (i, sample) in snapped.iter_mut().enumerate() {
            robot.check_limits(sample).map_err(|e| {
                MotionError::data(format!("sample {i} (t = {} s): {e}", times_s[i]))
            })?;
            for (value, &rotary) in sample.iter_mut().zip(&rotary) {
                *value = ColumnUnit::display(rotary).snap(*value);
            }
        }
        Ok(Motion {
            joint_names: (0..robot.dof())
                .map(|j| robot.actuated_joint(j).name.clone())
                .collect(),
            rotary,
            times_s,
            samples: snapped,
        })
    }

    /// The actuated joints' URDF names, in joint-vector order.
    pub fn joint_names(&self) -> &[String] {
        &self.joint_names
    }

    /// Whether each joint is rotary (rad) rather than prismatic (m), in joint-vector order.
    pub fn rotary(&self) -> &[bool] {
        &self.rotary
    }

    /// Number of joints per sample.
    pub fn dof(&self) -> usize {
        self.joint_names.len()
    }

    /// Number of samples (at least 1).
    pub fn len(&self) -> usize {
        self.times_s.len()
    }

    /// Always false: a motion has at least one sample.
    pub fn is_empty(&self) -> bool {
        self.times_s.is_empty()
    }

    /// Sample times (s), strictly increasing.
    pub fn times_s(&self) -> &[f64] {
        &self.times_s
    }

    /// All joint vectors (rad / m), one per sample.
    pub fn samples(&self) -> &[Vec<f64>] {
        &self.samples
    }

    /// Time from the first to the last sample (s).
    pub fn duration_s(&self) -> f64 {
        self.times_s[self.len() - 1] - self.times_s[0]
    }

    /// The values (rad / m) of joint-vector entry `joint` at every sample, or `None` when
    /// `joint >= dof()`.
    pub fn joint_series(&self, joint: usize) -> Option<Vec<f64>> {
        (joint < self.dof()).then(|| self.samples.iter().map(|s| s[joint]).collect())
    }

    /// The joint vector (rad / m) at time `t_s`: linear interpolation between the samples
    /// around it, clamped to the first / last sample outside the motion.
    pub fn joints_at(&self, t_s: f64) -> Vec<f64> {
        let after = self.times_s.partition_point(|&t| t <= t_s);
        if after == 0 {
            return self.samples[0].clone();
        }
        if after == self.len() {
            return self.samples[self.len() - 1].clone();
        }
        let (t0, t1) = (self.times_s[after - 1], self.times_s[after]);
        let w = (t_s - t0) / (t1 - t0);
        let (q0, q1) = (&self.samples[after - 1], &self.samples[after]);
        q0.iter().zip(q1).map(|(a, b)| a + w * (b - a)).collect()
    }

    /// Per joint, the largest speed (rad/s or m/s) between consecutive samples (finite
    /// differences); zeros for a single-sample motion.
    pub fn peak_speeds(&self) -> Vec<f64> {
        let mut peaks = vec![0.0_f64; self.dof()];
        for i in 1..self.len() {
            let dt = self.times_s[i] - self.times_s[i - 1];
            for (j, peak) in peaks.iter_mut().enumerate() {
                let speed = (self.samples[i][j] - self.samples[i - 1][j]).abs() / dt;
                *peak = peak.max(speed);
            }
        }
        peaks
    }

    /// Per joint, the smallest and largest value (rad / m) over the motion.
    pub fn ranges(&self) -> Vec<(f64, f64)> {
        (0..self.dof())
            .map(|j| {
                self.samples
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                        (lo.min(s[j]), hi.max(s[j]))
                    })
            })
            .collect()
    }
}

/// At least one sample, one time per sample, finite and strictly increasing times.
/// The longest a motion may last (s): every chain's motion test integrates the whole
/// motion, so a time typed wrong — a row an hour after the one before — would buy CPU-hours
/// with a few bytes. Room for a long program and for the stress motions of axis ranges (two
/// strokes of at most [`super::MAX_STROKE_S`] each, and their rests).
pub const MAX_MOTION_DURATION_S: f64 = 1800.0;

fn check_times(times_s: &[f64], samples: usize) -> Result<(), MotionError> {
    if times_s.is_empty() {
        return Err(MotionError::data("a motion needs at least one sample"));
    }
    if times_s.len() != samples {
        return Err(MotionError::data(format!(
            "{} times but {samples} joint vectors",
            times_s.len()
        )));
    }
    if let Some(i) = times_s.iter().position(|t| !t.is_finite()) {
        return Err(MotionError::data(format!(
            "sample {i}: time {} is not a finite number",
            times_s[i]
        )));
    }
    if let Some(i) = (1..times_s.len()).find(|&i| times_s[i] - times_s[0] > MAX_MOTION_DURATION_S) {
        return Err(MotionError::data(format!(
            "sample {i}: t = {} s is more than {MAX_MOTION_DURATION_S} s after the first \
             sample's {} s — the longest motion the tool simulates (a time typed wrong? a longer \
             program is several motions of a cell)",
            times_s[i], times_s[0]
        )));
    }
    if let Some(i) = (1..times_s.len()).find(|&i| times_s[i] <= times_s[i - 1]) {
        return Err(MotionError::data(format!(
            "sample {i}: time {} s is not after the previous sample's {} s",
            times_s[i],
            times_s[i - 1]
        )));
    }
    Ok(())
}
