//! How the key results move across the documented ranges of the fatigue parameters.
//!
//! The task's parameter set gives every value (k per region, the recovery's rest rate and limit
//! load) with a range (`docs/fatigue-parameters.md`). Nine variants span it: the values; each of
//! the three parameters alone at the low and at the high end of its range; and the two corners
//! where all three make the muscle tire fastest (k high, rest rate low, limit low) and slowest.
//! Each variant holds the plan's postures (planned with the set's values) and replays the task:
//! the question is how much the verdict depends on the muscle, not what another plan would be.

use super::meaning::{meaning_with, replay_plan};
use super::rest::rest_advice_with;
use crate::fatigue::params::Bound;
use crate::fatigue::{MaParams, Recovery};
use crate::plan::{Plan, Task};
use serde::Serialize;

/// One parameter variant: a name and the bound of each parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Variant {
    pub name: &'static str,
    pub k: Bound,
    pub rest_rate: Bound,
    pub limit_load: Bound,
}

/// The nine variants, the set's values first.
pub const VARIANTS: [Variant; 9] = [
    v("values", Bound::Value, Bound::Value, Bound::Value),
    v("k low", Bound::Low, Bound::Value, Bound::Value),
    v("k high", Bound::High, Bound::Value, Bound::Value),
    v("rest rate low", Bound::Value, Bound::Low, Bound::Value),
    v("rest rate high", Bound::Value, Bound::High, Bound::Value),
    v("limit load low", Bound::Value, Bound::Value, Bound::Low),
    v("limit load high", Bound::Value, Bound::Value, Bound::High),
    v("tires fastest", Bound::High, Bound::Low, Bound::Low),
    v("tires slowest", Bound::Low, Bound::High, Bound::High),
];

const fn v(name: &'static str, k: Bound, rest_rate: Bound, limit_load: Bound) -> Variant {
    Variant {
        name,
        k,
        rest_rate,
        limit_load,
    }
}

/// The fatigue parameters of every half-joint of `task` under `variant`; `None` when the task
/// does not use a named parameter set (an older file's single k and rate have no ranges) or a
/// half-joint's parameters were overridden in the task (kept as given).
pub fn variant_params(task: &Task, variant: &Variant) -> Option<Vec<MaParams>> {
    let set = task.parameter_set.as_ref()?;
    let sex = task.worker.sex;
    let out = task
        .half_joints
        .iter()
        .zip(&task.fatigue)
        .map(|(h, given)| {
            let k_value = set.k(&h.region, sex, Bound::Value);
            let overridden =
                given.k_per_min != k_value || given.recovery != set.recovery.recovery();
            if overridden {
                return *given;
            }
            let k = set.k(&h.region, sex, variant.k);
            let recovery: Recovery = set.recovery_at(variant.rest_rate, variant.limit_load);
            MaParams::with_recovery(k, recovery).unwrap_or(*given)
        })
        .collect();
    Some(out)
}

/// The key results under one variant.
#[derive(Debug, Clone, Serialize)]
pub struct Outcome {
    pub variant: &'static str,
    /// Minutes until a group gives out at the task's pace (`None`: read `exhaustion_verdict`).
    pub minutes_to_exhaustion: Option<f64>,
    /// As the plan's `meaning.exhaustion_verdict`, and how long the pace was followed \[min\].
    pub exhaustion_verdict: &'static str,
    pub minutes_followed: f64,
    /// Whether a group is exhausted within the planned task.
    pub exhausted_in_task: bool,
    /// Lowest capacity at any time of the task, and whose.
    pub lowest_capacity: f64,
    pub lowest_capacity_group: String,
    /// Rest per cycle the model needs to stay above the floor (`None`: rest cannot help).
    pub rest_needed_s: Option<f64>,
}

/// The sensitivity table of a plan.
#[derive(Debug, Clone, Serialize)]
pub struct Sensitivity {
    pub parameter_set: String,
    pub method: &'static str,
    pub outcomes: Vec<Outcome>,
    /// How many variants exhaust a group within the task.
    pub exhausted_in: usize,
}

/// What the table says about its method.
pub const METHOD: &str = "the plan's postures replayed with each parameter at the low and high end of its documented range, and with all three at the fastest- and slowest-tiring corner";

/// The key results of `plan` under one parameter variant.
pub fn outcome(
    task: &Task,
    plan: &Plan,
    floor: f64,
    variant: &Variant,
    params: &[MaParams],
) -> Outcome {
    let m = meaning_with(task, plan, params);
    let r = replay_plan(plan, params);
    let rest = rest_advice_with(task, plan, floor, params);
    Outcome {
        variant: variant.name,
        minutes_to_exhaustion: m.minutes_to_exhaustion,
        exhaustion_verdict: m.exhaustion_verdict,
        minutes_followed: m.minutes_followed,
        exhausted_in_task: r.exhaustion.is_some(),
        lowest_capacity: r.lowest_capacity,
        lowest_capacity_group: task.half_joints[r.lowest_half_joint].group.clone(),
        rest_needed_s: rest.model.rest_s_per_cycle,
    }
}

/// The sensitivity table of `plan`; `None` for a task without a named parameter set.
pub fn sensitivity(task: &Task, plan: &Plan, floor: f64) -> Option<Sensitivity> {
    let set = task.parameter_set.as_ref()?;
    let mut outcomes = Vec::with_capacity(VARIANTS.len());
    for variant in &VARIANTS {
        let params = variant_params(task, variant)?;
        outcomes.push(outcome(task, plan, floor, variant, &params));
    }
    Some(Sensitivity {
        parameter_set: set.name.clone(),
        method: METHOD,
        exhausted_in: outcomes.iter().filter(|o| o.exhausted_in_task).count(),
        outcomes,
    })
}
