//! The evaluator: samples in, fatigue state out, one sample at a time (offline and live use the
//! same code, so they agree exactly).

use super::{EvalError, Sample};
use crate::fatigue::MaState;
use crate::plan::Task;
use crate::plan::posture::PostureWork;
use nalgebra::Vector3;
use serde::Serialize;

/// A group that could no longer hold its load.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct ExhaustionEvent {
    pub t_s: f64,
    pub half_joint: String,
    pub group: String,
    pub load: f64,
    /// The load was above the group's capacity when it began (at a rested group: above its
    /// strength), not worn down to it.
    pub exceeds_capacity_at_start: bool,
}

/// Samples whose angles lie outside the joint's range by more than this \[rad\] are counted.
pub const RANGE_TOLERANCE_RAD: f64 = 0.1;
/// Outside the range by more than this \[rad\] while the value read as degrees would fit: the
/// recording is refused with the hint `--degrees`.
pub const DEGREES_SUSPECT_RAD: f64 = 0.5;

/// Largest |time| of a sample \[s\] (about 32 years).
pub const MAX_TIME_S: f64 = 1e9;

/// Largest |joint value| of a sample (rad, or m for a prismatic joint).
pub const MAX_JOINT_VALUE: f64 = 1000.0;

/// Largest fatigue index a group may reach \[min\]: far beyond any real hold (U grows like
/// `e^{2kF}` once a group is held past exhaustion), and small enough that a sum over every
/// group stays far below the largest double. A recording that goes beyond is refused.
pub const MAX_FATIGUE_U_MIN: f64 = 1e250;

/// The evaluation state: the task's body, worker and fatigue parameters, a statics workspace and
/// every half-joint's fatigue state.
pub struct Evaluator<'t> {
    task: &'t Task,
    work: PostureWork,
    pub state: Vec<MaState>,
    /// Loads of the last sample (held until the next one).
    pub loads: Vec<f64>,
    exhausted: Vec<bool>,
    last_t_s: Option<f64>,
    first_t_s: Option<f64>,
    pub events: Vec<ExhaustionEvent>,
    /// Lowest capacity at any time, its half-joint and time.
    pub lowest: (f64, usize, f64),
    /// Samples with an angle outside its joint's range by more than [`RANGE_TOLERANCE_RAD`].
    pub outside_range: u64,
    pub samples: u64,
    /// Whether the body stands on its feet (floor reaction split between them).
    pub standing: bool,
}

impl<'t> Evaluator<'t> {
    pub fn new(task: &'t Task) -> Self {
        let n = task.half_joints.len();
        Evaluator {
            task,
            work: PostureWork::new(task),
            state: vec![MaState::FRESH; n],
            loads: vec![0.0; n],
            exhausted: vec![false; n],
            last_t_s: None,
            first_t_s: None,
            events: Vec::new(),
            lowest: (1.0, 0, 0.0),
            outside_range: 0,
            samples: 0,
            standing: task.stance.is_some(),
        }
    }

    pub fn task(&self) -> &Task {
        self.task
    }

    /// Checks a sample's angles against the joint ranges: `Err((q index, value))` when one lies
    /// so far outside that the recording looks like degrees read as radians.
    pub fn check_range(&mut self, q_rad: &[f64]) -> Result<(), (usize, f64)> {
        let m = &self.task.model;
        let mut outside = false;
        for (k, &v) in q_rad.iter().enumerate() {
            let j = m.q_joint(k);
            if !matches!(j.kind, crate::body::JointKind::Revolute) {
                continue;
            }
            let beyond = (j.lower_rad - v).max(v - j.upper_rad);
            if beyond > RANGE_TOLERANCE_RAD {
                outside = true;
            }
            let as_deg = v.to_radians();
            let fits_as_deg = as_deg >= j.lower_rad - RANGE_TOLERANCE_RAD
                && as_deg <= j.upper_rad + RANGE_TOLERANCE_RAD;
            if beyond > DEGREES_SUSPECT_RAD && fits_as_deg {
                return Err((k, v));
            }
        }
        if outside {
            self.outside_range += 1;
        }
        Ok(())
    }

    /// Takes the next sample: holds the previous loads until its time (exactly), records any
    /// group that could no longer hold its load, then computes this sample's loads. Returns the
    /// number of new exhaustion events.
    pub fn push(&mut self, s: &Sample) -> Result<usize, EvalError> {
        if s.q_rad.len() != self.task.model.nq() {
            return Err(EvalError::Length {
                expected: self.task.model.nq(),
                got: s.q_rad.len(),
            });
        }
        if !s.t_s.is_finite()
            || s.q_rad.iter().any(|v| !v.is_finite())
            || s.hand_force_n
                .iter()
                .any(|f| !f.iter().all(|v| v.is_finite()))
        {
            return Err(EvalError::NotFinite { t_s: s.t_s });
        }
        // values without physical meaning: a recording longer than a year, times beyond ±10⁹ s,
        // joint values beyond ±1000 rad (or m)
        let implausible = |problem: String| EvalError::Implausible {
            t_s: s.t_s,
            problem,
        };
        if s.t_s.abs() > MAX_TIME_S {
            return Err(implausible(format!(
                "time beyond ±{MAX_TIME_S:e} s; give seconds from the recording's start"
            )));
        }
        if let Some(t0) = self.first_t_s
            && s.t_s - t0 > crate::plan::task::MAX_DURATION_S
        {
            return Err(implausible(
                "the recording spans more than a year".to_string(),
            ));
        }
        if let Some((k, v)) = s
            .q_rad
            .iter()
            .enumerate()
            .find(|(_, v)| v.abs() > MAX_JOINT_VALUE)
        {
            return Err(implausible(format!(
                "{} = {v:e} is beyond ±{MAX_JOINT_VALUE} (rad or m)",
                self.task.model.q_joint(k).name
            )));
        }
        let before = self.events.len();
        if let Some(t0) = self.last_t_s {
            if s.t_s <= t0 {
                return Err(EvalError::Time {
                    t_s: s.t_s,
                    previous_t_s: t0,
                });
            }
            let dt = s.t_s - t0;
            for h in 0..self.state.len() {
                let f = self.loads[h];
                let p = &self.task.fatigue[h];
                if !self.exhausted[h]
                    && let Some(te) = p.time_to_exhaustion_s(self.state[h].capacity, f)
                    && te < dt
                {
                    self.exhausted[h] = true;
                    let hj = &self.task.half_joints[h];
                    self.events.push(ExhaustionEvent {
                        t_s: t0 + te,
                        half_joint: hj.id.clone(),
                        group: hj.group.clone(),
                        load: f,
                        exceeds_capacity_at_start: te <= 0.0,
                    });
                }
                p.hold(&mut self.state[h], f, dt);
                let u = self.state[h].fatigue_u_min;
                if u.is_nan() || u > MAX_FATIGUE_U_MIN {
                    let hj = &self.task.half_joints[h];
                    let since = self
                        .events
                        .iter()
                        .rev()
                        .find(|e| e.half_joint == hj.id)
                        .map(|e| format!(" (it could no longer hold its load from {:.1} s)", e.t_s))
                        .unwrap_or_default();
                    return Err(implausible(format!(
                        "the previous sample, held {dt:.1} s until this one, drives the fatigue index of the {} beyond {MAX_FATIGUE_U_MIN:e} min{since}: a load held that far past exhaustion has no meaning; the recording has a gap — add the samples in between or split it there",
                        hj.group
                    )));
                }
                if self.state[h].capacity < self.lowest.0 {
                    self.lowest = (self.state[h].capacity, h, s.t_s);
                }
            }
        } else {
            self.first_t_s = Some(s.t_s);
        }
        self.last_t_s = Some(s.t_s);
        self.samples += 1;
        let forces: [Vector3<f64>; 2] = s.hand_force_n;
        self.work.statics(self.task, &s.q_rad, &forces);
        self.work
            .half_joint_loads(self.task, &s.q_rad, &mut self.loads);
        for h in 0..self.loads.len() {
            if !self.loads[h].is_finite() {
                self.loads[h] = 0.0;
            }
            if self.exhausted[h] && self.state[h].capacity >= self.loads[h] {
                self.exhausted[h] = false; // able again: a later exhaustion is a new event
            }
        }
        Ok(self.events.len() - before)
    }

    /// Time of the first and last sample.
    pub fn span_s(&self) -> (f64, f64) {
        (self.first_t_s.unwrap_or(0.0), self.last_t_s.unwrap_or(0.0))
    }

    /// Balance margin of the last sample, for a standing body.
    pub fn last_left_foot_share(&self) -> Option<f64> {
        self.work.ground.as_ref().map(|g| g.left_share)
    }
}
