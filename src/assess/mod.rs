//! What ergonomists report beside fatigue, for a planned posture or a whole plan.
//!
//! * [`angles`]: the body angles observational methods look at;
//! * [`rula`], [`reba`]: RULA (McAtamney & Corlett 1993) and REBA (Hignett & McAtamney 2000) with
//!   their worksheets;
//! * [`niosh`]: the revised NIOSH lifting equation (Waters et al. 1993, Applications Manual 1994);
//! * [`low_back`]: L5/S1 compression and shear (single equivalent muscle, Chaffin et al.);
//! * [`rest`]: work and rest (the fatigue model's recovery against Rohmert's rule);
//! * [`lifting`]: the task's declared lifts through NIOSH; [`phase`]: each phase's posture in
//!   angles and words, RULA, REBA, low back and % capable; [`meaning`]: what U means (time to
//!   exhaustion at this pace, endurance used, capacity left); [`uncertainty`]: how those move
//!   across the fatigue parameters' ranges; [`verdict`]: the shift verdict from all of them.

pub mod angles;
pub mod lifting;
pub mod low_back;
pub mod meaning;
pub mod niosh;
pub mod phase;
pub mod reba;
pub mod rest;
pub mod rula;
pub mod uncertainty;
pub mod verdict;

use crate::plan::{Plan, Task};
use serde::Serialize;

/// Everything assessed about a plan.
#[derive(Debug, Clone, Serialize)]
pub struct Assessment {
    pub phases: Vec<phase::PhaseAssessment>,
    /// The lowest share of men and of women strong enough for every load of the task.
    pub capable_men: f64,
    pub capable_women: f64,
    /// Highest RULA and REBA over the phases.
    pub rula_max: Option<i32>,
    pub reba_max: Option<u8>,
    /// Highest L5/S1 compression \[N\] and its phase.
    pub back_compression_max_n: Option<f64>,
    pub back_compression_phase: Option<String>,
    pub lifting: Option<Result<lifting::Lifting, String>>,
    pub meaning: meaning::Meaning,
    pub rest: rest::RestAdvice,
    /// The shift verdict from every criterion (fatigue model, Jonsson, ISO 11226, Rohmert).
    pub verdict: verdict::ShiftVerdict,
    /// The key results across the fatigue parameters' documented ranges.
    pub uncertainty: Option<uncertainty::Sensitivity>,
}

impl Assessment {
    /// NIOSH's lifting index that decides the task, or why it is not defined
    /// ([`lifting::Lifting::deciding_index`]); `None` without declared lifts (or when the lifts
    /// could not be assessed).
    pub fn lifting_index(&self) -> Option<Result<f64, String>> {
        self.lifting
            .as_ref()?
            .as_ref()
            .ok()
            .map(|l| l.deciding_index())
    }

    /// Whether Rohmert's rest allowance applies: some posture is held long enough to be static
    /// (the verdict's Rohmert criterion is not "not applicable"). Every report words the
    /// allowance from this.
    pub fn rohmert_applies(&self) -> bool {
        self.verdict
            .criteria
            .iter()
            .any(|c| c.id == "rohmert" && c.status != verdict::Status::NotApplicable)
    }
}

/// A share of the population (0..1) as a percentage rounded *down* to `dp` decimals, so a share
/// just short of a design limit never reads as meeting it (0.9896 -> 98 at `dp` 0, never 99).
/// The nudge of 1e-9 keeps binary fractions that are exactly representable in decimal (0.57, whose
/// 100x is 56.999...) from dropping a whole step.
pub fn share_percent_floor(share: f64, dp: i32) -> f64 {
    let scale = 10f64.powi(dp);
    (100.0 * share * scale + 1e-9).floor() / scale
}

/// Assesses a plan of `task` (capacity floor `floor` for the work/rest advice).
pub fn assess(task: &Task, plan: &Plan, floor: f64) -> Assessment {
    let phases = phase::assess_phases(task, plan);
    let capable_men = phases.iter().map(|p| p.capable_men).fold(1.0, f64::min);
    let capable_women = phases.iter().map(|p| p.capable_women).fold(1.0, f64::min);
    let rula_max = phases
        .iter()
        .filter_map(|p| p.rula.as_ref().map(|r| r.grand_score))
        .max();
    let reba_max = phases
        .iter()
        .filter_map(|p| p.reba.as_ref().map(|r| r.reba_score))
        .max();
    let back = phases
        .iter()
        .filter_map(|p| {
            p.low_back
                .as_ref()
                .map(|b| (b.compression_n, p.phase.clone()))
        })
        .fold(None, |a: Option<(f64, String)>, b| match a {
            Some(x) if x.0 >= b.0 => Some(x),
            _ => Some(b),
        });
    let meaning = meaning::meaning(task, plan);
    let rest = rest::rest_advice(task, plan, floor);
    let lifting = lifting::assess_lifts(task, plan).map(|r| r.map_err(|e| e.to_string()));
    let uncertainty = uncertainty::sensitivity(task, plan, floor);
    let verdict = verdict::shift_verdict(
        task,
        plan,
        &meaning,
        &phases,
        &rest,
        lifting.as_ref().and_then(|l| l.as_ref().ok()),
        uncertainty.as_ref().map(|u| u.exhausted_in),
    );
    Assessment {
        verdict,
        capable_men,
        capable_women,
        rula_max,
        reba_max,
        back_compression_max_n: back.as_ref().map(|b| b.0),
        back_compression_phase: back.map(|b| b.1),
        lifting,
        meaning,
        rest,
        uncertainty,
        phases,
    }
}
