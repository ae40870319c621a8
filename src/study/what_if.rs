//! What would change the plan: the phase that matters most, re-planned with its hands' target
//! moved toward the worker's elbow height — the height the ergonomics literature recommends for
//! handling — and the whole task planned again with the same options, so that the report can say
//! in numbers what a workstation change would do ("raising the pallet 10 cm lowers …").
//!
//! The phase: the one with the highest L5/S1 compression when a phase exceeds NIOSH's action
//! limit, else the one whose posture the targets force farthest beyond the acceptable zones
//! (ISO 11226 / EN 1005-4, summed excess), else the one where the group whose capacity falls
//! lowest holds its highest load. The comparison gives the zones' summed excess first. The
//! move: toward standing elbow height (0.630 × stature, Drillis & Contini 1966), by at most
//! [`MAX_MOVE_M`]; no what-if when the target is already within [`NEAR_ELBOW_M`] of it.

use crate::assess::{Assessment, assess};
use crate::plan::{Plan, PlanError, PlanOptions, Task, plan_task_with};
use nalgebra::Vector3;
use serde::Serialize;

/// Largest move of the target \[m\].
pub const MAX_MOVE_M: f64 = 0.10;

/// A target this close to elbow height \[m\] is left where it is.
pub const NEAR_ELBOW_M: f64 = 0.05;

/// Standing elbow height as a fraction of stature (Drillis & Contini 1966).
pub const ELBOW_HEIGHT_PER_STATURE: f64 = 0.630;

/// The figures of one plan that the what-if compares.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Figures {
    /// Total U per hour of simulated work \[min/h\].
    pub u_per_hour_min: f64,
    pub lowest_capacity: f64,
    pub back_compression_max_n: Option<f64>,
    pub capable_women: f64,
    pub exhausted: bool,
    /// The postures' excess beyond ISO 11226 / EN 1005-4's acceptable zones, summed over the
    /// cycle's phases and zones \[deg\] (`phases[].outside_zones`).
    pub zone_excess_deg: f64,
}

/// `+12 %` from `a` to `b` ("from 0" when `a` is not positive).
pub fn relative_change(a: f64, b: f64) -> String {
    if a > 0.0 {
        let x = 100.0 * (b / a - 1.0);
        if x.abs() < 1.0 {
            format!("{x:+.1} %")
        } else {
            format!("{x:+.0} %")
        }
    } else {
        "from 0".into()
    }
}

impl Figures {
    /// What changes from these figures to `after`, in words, one item per figure.
    pub fn changes_to(&self, after: &Figures) -> Vec<String> {
        let mut v = Vec::new();
        if self.zone_excess_deg > 0.0 || after.zone_excess_deg > 0.0 {
            v.push(format!(
                "postures beyond the acceptable zones (ISO 11226 / EN 1005-4) by {:.0}° → {:.0}° (summed over phases)",
                self.zone_excess_deg, after.zone_excess_deg
            ));
        }
        v.push(format!(
            "fatigue per hour {:.1} → {:.1} min/h ({})",
            self.u_per_hour_min,
            after.u_per_hour_min,
            relative_change(self.u_per_hour_min, after.u_per_hour_min)
        ));
        if let (Some(a), Some(b)) = (self.back_compression_max_n, after.back_compression_max_n) {
            v.push(format!("highest L5/S1 compression {a:.0} → {b:.0} N"));
        }
        v.push(format!(
            "lowest capacity {:.0} % → {:.0} %",
            100.0 * self.lowest_capacity,
            100.0 * after.lowest_capacity
        ));
        v.push(format!(
            "women strong enough {:.0} % → {:.0} %",
            100.0 * self.capable_women,
            100.0 * after.capable_women
        ));
        if after.exhausted && !self.exhausted {
            v.push("but a muscle group is then exhausted within the task".into());
        }
        v
    }
}

/// A workstation change and what it does.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WhatIf {
    pub phase: String,
    /// Vertical move of the phase's hand targets (and held object) \[m\], + up.
    pub dz_m: f64,
    pub elbow_height_m: f64,
    pub before: Figures,
    pub after: Figures,
    /// What makes the changed task impossible as planned (then the change is not advised).
    pub problems: Vec<String>,
}

fn figures(plan: &Plan, a: &Assessment) -> Figures {
    let s = &plan.summary;
    Figures {
        u_per_hour_min: if s.duration_s > 0.0 {
            s.total_u / (s.duration_s / 3600.0)
        } else {
            0.0
        },
        lowest_capacity: s.lowest_capacity,
        back_compression_max_n: a.back_compression_max_n,
        capable_women: a.capable_women,
        exhausted: s.exhaustion.is_some(),
        zone_excess_deg: zone_excess_deg(plan),
    }
}

/// The plan's excess beyond the acceptable zones \[deg\], summed over phases and zones.
fn zone_excess_deg(plan: &Plan) -> f64 {
    (0..plan.summary.phases.len())
        .map(|p| phase_zone_excess_deg(plan, p))
        .sum()
}

/// Phase `p`'s excess beyond the acceptable zones \[deg\], summed over zones.
fn phase_zone_excess_deg(plan: &Plan, p: usize) -> f64 {
    plan.summary.phases.get(p).map_or(0.0, |x| {
        x.outside_zones
            .iter()
            .map(|z| z.angle_deg - z.limit_deg)
            .sum()
    })
}

/// The phase a what-if moves (see the module documentation).
pub fn phase_to_move(task: &Task, plan: &Plan, a: &Assessment) -> Option<usize> {
    use crate::assess::low_back::CompressionVerdict;
    let back = |p: usize| a.phases.get(p).and_then(|x| x.low_back.as_ref());
    let compression = |p: usize| back(p).map_or(0.0, |b| b.compression_n);
    let n = task.phases.len();
    if let Some(p) = (0..n)
        .filter(|&p| {
            back(p).is_some_and(|b| b.compression_verdict != CompressionVerdict::WithinActionLimit)
        })
        .max_by(|&x, &y| compression(x).total_cmp(&compression(y)))
    {
        return Some(p);
    }
    // a posture the targets force beyond the acceptable zones: the largest excess
    let excess = |p: usize| phase_zone_excess_deg(plan, p);
    if plan.summary.zones
        && let Some(p) = (0..n)
            .filter(|&p| excess(p) > 0.0)
            .max_by(|&x, &y| excess(x).total_cmp(&excess(y)))
    {
        return Some(p);
    }
    let h = plan.half_joint(&plan.summary.lowest_capacity_half_joint)?;
    let load = |p: usize| {
        plan.postures
            .iter()
            .filter(|r| r.phase == task.phases[p].name)
            .filter_map(|r| r.load.get(h).copied())
            .fold(0.0, f64::max)
    };
    (0..n)
        .filter(|&p| load(p) > 0.0)
        .max_by(|&x, &y| load(x).total_cmp(&load(y)))
}

/// Moves phase `p`'s targets toward elbow height, plans the changed task with `opts` (without
/// baselines) and compares. `None` when the phase has no target or sits near elbow height.
pub fn what_if(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    opts: PlanOptions,
    floor: f64,
) -> Result<Option<WhatIf>, PlanError> {
    let Some(p) = phase_to_move(task, plan, a) else {
        return Ok(None);
    };
    let ph = &task.phases[p];
    let heights: Vec<f64> = ph.targets_m.iter().flatten().map(|t| t.z).collect();
    if heights.is_empty() {
        return Ok(None);
    }
    let z = heights.iter().sum::<f64>() / heights.len() as f64;
    let elbow = ELBOW_HEIGHT_PER_STATURE * task.worker.stature_m;
    if (elbow - z).abs() < NEAR_ELBOW_M {
        return Ok(None);
    }
    let dz = (elbow - z).clamp(-MAX_MOVE_M, MAX_MOVE_M);
    let mut changed = task.clone();
    // every phase doing the same work moves with it (they share one place)
    for q in &mut changed.phases {
        if q.same_work(ph) {
            for t in q.targets_m.iter_mut().flatten() {
                *t += Vector3::new(0.0, 0.0, dz);
            }
            if let Some(o) = q.object.as_mut() {
                o.center_m[2] += dz;
            }
        }
    }
    let opts = PlanOptions {
        baselines: false,
        ..opts
    };
    let plan2 = plan_task_with(&changed, opts)?;
    let a2 = assess(&changed, &plan2, floor);
    Ok(Some(WhatIf {
        phase: ph.name.clone(),
        dz_m: dz,
        elbow_height_m: elbow,
        before: figures(plan, a),
        after: figures(&plan2, &a2),
        problems: plan2.problems(),
    }))
}
