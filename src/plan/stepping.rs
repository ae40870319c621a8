//! Stepping and turning: where a posture puts the feet, the steps between consecutive states of
//! a cycle (rest → each phase in order → rest), their cost in the objective, and the words for
//! them.
//!
//! **The cost of a step.** A foot that moves by `Δc` (sole centre, on the floor) and turns by
//! `Δψ` between two consecutive states travels `D = √(|Δc|² + (ℓ Δψ)²)`, `ℓ` its sole's
//! half-length (the toe's arc per radian). It costs `w · D²/(D² + D₀²)` with `D₀ =`
//! [`STEP_SCALE_M`]: about `w` for a real step, nothing for no step, smooth in between, so that
//! standing still stays possible and a shuffle of a few millimetres buys nothing. `w` is the
//! task's `objective.step_weight` in the objective's units (the fatigue term is the logarithm of
//! the total fatigue index: a weight of 0.01 makes one step worth 1 % of the task's fatigue).

use super::asymmetry::Asymmetry;
use super::posture::PostureWork;
use super::task::Task;
use crate::body::JointKind;
use crate::body::stance::{FeetNow, wrap_pi};
use crate::body::{BodyModel, StaticsData};
use nalgebra::Vector3;
use serde::Serialize;

/// `D₀` of the step cost \[m\]: a foot moved this far costs half a step.
pub const STEP_SCALE_M: f64 = 0.05;

/// A foot counts as having stepped when its sole centre moves farther than this \[m\] ...
pub const STEP_MOVE_M: f64 = 0.03;

/// ... or it turns by more than this \[deg\].
pub const STEP_TURN_DEG: f64 = 10.0;

/// One foot on the floor: its sole centre and yaw.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FootPose {
    /// Sole centre (x, y) \[m\], world.
    pub sole_center_m: [f64; 2],
    /// The foot's heading, its link's x axis, about the vertical from world x \[deg\].
    pub yaw_deg: f64,
}

/// Where a phase's posture puts the feet, and how the worker got there from the state before.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PhaseFeet {
    /// The left and right foot.
    pub left: FootPose,
    pub right: FootPose,
    /// Feet that moved (more than [`STEP_MOVE_M`] or [`STEP_TURN_DEG`]) since the state before:
    /// the previous phase, or the rest stance before the first phase.
    pub steps: u32,
    /// Change of the feet's mean heading since the state before \[deg\] (positive: to the left).
    pub turn_deg: f64,
    /// Move of the point between the sole centres since the state before, in the earlier
    /// heading's axes: (forward, to the left) \[m\].
    pub moved_m: [f64; 2],
    /// The change in words ("turns 45° to the right, one step").
    pub words: String,
}

/// The feet of a posture (after its statics in `pw`), or `None` for a body without feet.
pub fn feet_of(task: &Task, pw: &PostureWork) -> Option<FeetNow> {
    let st = task.stance.as_ref()?;
    Some(FeetNow::at(&task.model, &pw.data, &st.feet))
}

fn pose(f: &FeetNow, i: usize) -> FootPose {
    FootPose {
        sole_center_m: [f.sole_center_m[i].x, f.sole_center_m[i].y],
        yaw_deg: f.yaw_rad[i].to_degrees(),
    }
}

/// How the feet got from `before` to `now`.
pub fn describe(before: &FeetNow, now: &FeetNow) -> PhaseFeet {
    let mut steps = 0;
    for i in 0..2 {
        let moved = (now.sole_center_m[i] - before.sole_center_m[i]).norm();
        let turned = wrap_pi(now.yaw_rad[i] - before.yaw_rad[i])
            .to_degrees()
            .abs();
        if moved > STEP_MOVE_M || turned > STEP_TURN_DEG {
            steps += 1;
        }
    }
    let (g0, g1) = (before.geometry(), now.geometry());
    let turn_deg = wrap_pi(g1.heading_rad - g0.heading_rad).to_degrees();
    let mid = |f: &FeetNow| (f.sole_center_m[0] + f.sole_center_m[1]) / 2.0;
    let d = mid(now) - mid(before);
    let (s, c) = g0.heading_rad.sin_cos();
    let moved_m = [c * d.x + s * d.y, -s * d.x + c * d.y];
    let mut parts = Vec::new();
    if turn_deg.abs() >= 5.0 {
        parts.push(format!(
            "turns {:.0}° to the {}",
            turn_deg.abs(),
            if turn_deg > 0.0 { "left" } else { "right" }
        ));
    }
    let mut moves = Vec::new();
    if moved_m[0].abs() >= 0.05 {
        moves.push(format!(
            "{:.2} m {}",
            moved_m[0].abs(),
            if moved_m[0] > 0.0 { "forward" } else { "back" }
        ));
    }
    if moved_m[1].abs() >= 0.05 {
        moves.push(format!(
            "{:.2} m to the {}",
            moved_m[1].abs(),
            if moved_m[1] > 0.0 { "left" } else { "right" }
        ));
    }
    if !moves.is_empty() {
        parts.push(format!("moves {}", moves.join(" and ")));
    }
    parts.push(match steps {
        0 => "feet in place".to_string(),
        1 => "one step".to_string(),
        _ => "two steps".to_string(),
    });
    PhaseFeet {
        left: pose(now, 0),
        right: pose(now, 1),
        steps,
        turn_deg,
        moved_m,
        words: parts.join(", "),
    }
}

/// The costs of where one posture puts the feet: its steps against the fixed feet of its
/// neighbouring states, and its phases' asymmetry ([`super::asymmetry`]).
#[derive(Debug, Clone, Default)]
pub struct Stepping {
    /// Cost of one step (objective units); 0 turns the cost off.
    pub weight: f64,
    /// The neighbouring states' feet, each with how many transitions it stands for.
    pub neighbours: Vec<(FeetNow, f64)>,
    /// The asymmetry of the posture's phases (no loads: off).
    pub asymmetry: Asymmetry,
}

impl Stepping {
    /// The cost of standing on `feet` (see the module docs).
    pub fn value(&self, task: &Task, feet: &FeetNow) -> f64 {
        let Some(st) = &task.stance else { return 0.0 };
        let mut v = 0.0;
        if self.weight != 0.0 {
            for (nb, mult) in &self.neighbours {
                for i in 0..2 {
                    let x = travel2(feet, nb, i, st.feet[i].half_length_m);
                    v += mult * x / (x + STEP_SCALE_M * STEP_SCALE_M);
                }
            }
        }
        self.weight * v + self.asymmetry.value(feet)
    }

    /// Whether the cost depends on the posture at all (steps to price, or an asymmetry term).
    pub fn is_active(&self) -> bool {
        (self.weight != 0.0 && !self.neighbours.is_empty()) || !self.asymmetry.loads.is_empty()
    }

    /// Adds the cost's gradient in q at the forward kinematics in `data` to `grad`.
    pub fn add_gradient(&self, task: &Task, data: &StaticsData, feet: &FeetNow, grad: &mut [f64]) {
        if !self.is_active() {
            return;
        }
        let steps = self.weight != 0.0 && !self.neighbours.is_empty();
        let Some(st) = &task.stance else { return };
        let m: &BodyModel = &task.model;
        let d02 = STEP_SCALE_M * STEP_SCALE_M;
        let (gc_asym, gpsi_asym) = self.asymmetry.feet_gradient(feet);
        for i in 0..2 {
            let f = &st.feet[i];
            let l = f.half_length_m;
            // ∂(cost)/∂(c, ψ): the steps' travel² summed over the neighbours, weighted by φ′,
            // and the asymmetry's
            let (mut gc, mut gpsi) = (gc_asym[i], gpsi_asym[i]);
            if steps {
                for (nb, mult) in &self.neighbours {
                    let x = travel2(feet, nb, i, l);
                    let dphi = d02 / ((x + d02) * (x + d02));
                    let dc = feet.sole_center_m[i] - nb.sole_center_m[i];
                    let dpsi = wrap_pi(feet.yaw_rad[i] - nb.yaw_rad[i]);
                    gc += self.weight * mult * dphi * 2.0 * dc;
                    gpsi += self.weight * mult * dphi * 2.0 * l * l * dpsi;
                }
            }
            let c3: Vector3<f64> = data.link_point(m, f.link, &f.sole_center_in_link_m);
            let x = data.link_pose(m, f.link).0 * Vector3::x();
            let body = m.link_in_body[f.link].body;
            for &k in m.q_path_of_body(body) {
                let a = data.axis_w[k];
                let (dc, dpsi) = if m.q_joint(k).kind == JointKind::Prismatic {
                    (a.xy(), 0.0)
                } else {
                    (a.cross(&(c3 - data.origin_w[k])).xy(), yaw_rate(&x, &a))
                };
                grad[k] += gc.dot(&dc) + gpsi * dpsi;
            }
        }
    }
}

/// The rate of change of the heading `atan2(x_y, x_x)` of a unit vector `x` turning at angular
/// velocity `w`: `w_z` for a horizontal `x`, less what a tilted `x` loses to the other axes.
pub fn yaw_rate(x: &Vector3<f64>, w: &Vector3<f64>) -> f64 {
    let h2 = (x.x * x.x + x.y * x.y).max(1e-300);
    w.z - x.z * (w.x * x.x + w.y * x.y) / h2
}

/// `D²` of foot `i` between `a` and `b` \[m²\].
fn travel2(a: &FeetNow, b: &FeetNow, i: usize, half_length_m: f64) -> f64 {
    let dc = a.sole_center_m[i] - b.sole_center_m[i];
    let dpsi = wrap_pi(a.yaw_rad[i] - b.yaw_rad[i]);
    dc.norm_squared() + half_length_m * half_length_m * dpsi * dpsi
}

/// The step cost of a whole cycle: `weight` × the cost of every transition rest → phase 1 → …
/// → phase n → rest, for the feet of each phase (`None` entries: a body without feet).
pub fn cycle_cost(task: &Task, weight: f64, rest: &FeetNow, phases: &[FeetNow]) -> f64 {
    let mut v = 0.0;
    let mut before = *rest;
    for f in phases.iter().chain(std::iter::once(rest)) {
        let s = Stepping {
            weight,
            neighbours: vec![(before, 1.0)],
            asymmetry: Asymmetry::default(),
        };
        v += s.value(task, f);
        before = *f;
    }
    v
}
