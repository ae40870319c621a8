//! The task's lifts through the revised NIOSH lifting equation, measured on the planned postures.
//!
//! For each declared lift (origin and destination phases): H is the horizontal distance from the
//! mid-point between the ankles to the point below the mid-point of the hands, V the hands'
//! mid-point height above the floor, A the angle between the line from the ankles' mid-point to
//! the point below the hands and the worker's forward direction (the feet's mean heading in
//! that phase: the mid-sagittal line of the neutral posture), D the vertical travel.
//! The frequency is one lift per cycle; the duration category follows from the task's length;
//! the load is the heavier of the two phases' hand loads. Several lifts give a composite
//! lifting index.

use super::niosh::{
    CompositeResult, Coupling, EquationForm, Lift, LiftGeometry, LiftResult, NioshError,
    WorkDuration, assess_lift, composite,
};
use crate::body::stance::{FeetNow, wrap_pi};
use crate::plan::posture::PostureWork;
use crate::plan::task::CouplingName;
use crate::plan::{Plan, Task};
use nalgebra::Vector3;
use serde::Serialize;

/// The task's NIOSH results.
#[derive(Debug, Clone, Serialize)]
pub struct Lifting {
    pub lifts: Vec<LiftResult>,
    /// The composite lifting index when the task has several lifts.
    pub composite: Option<CompositeResult>,
}

impl Lifting {
    /// The lifting index that decides the task: the composite index (CLI) when several lifts
    /// are declared, else the lift's LI. `Err` with the reason in words when a lift lies outside
    /// the equation's limits (a multiplier of 0, so an RWL of 0: no load is recommended) —
    /// "'table to shelf' at the destination: H 66.5 cm beyond 63 cm (HM = 0)" — or the lifts'
    /// combination is (an FIRWL or FM of 0).
    pub fn deciding_index(&self) -> Result<f64, String> {
        for r in &self.lifts {
            if r.lifting_index.is_none() {
                let ends = std::iter::once((super::niosh::Point::Origin, &r.origin)).chain(
                    r.destination
                        .iter()
                        .map(|d| (super::niosh::Point::Destination, d)),
                );
                let reasons: Vec<String> = ends
                    .filter(|(_, x)| x.lifting_index.is_none())
                    .map(|(p, x)| format!("at the {}: {}", p.words(), x.zero_reasons().join(", ")))
                    .collect();
                return Err(format!("'{}' {}", r.name, reasons.join("; ")));
            }
        }
        match &self.composite {
            Some(c) => c.cli.ok_or_else(|| {
                "the lifts' composite index (a term's multiplier is 0 at their combined frequency)"
                    .to_string()
            }),
            None => Ok(self
                .lifts
                .iter()
                .filter_map(|r| r.lifting_index)
                .fold(0.0, f64::max)),
        }
    }
}

/// A deciding index from the two fields a document stores it in (`lifting_index`, null when not
/// defined; `lifting_outside_limits`, why not).
pub fn from_fields(
    index: Option<f64>,
    outside_limits: &Option<String>,
) -> Option<Result<f64, String>> {
    match (outside_limits, index) {
        (Some(why), _) => Some(Err(why.clone())),
        (None, Some(x)) => Some(Ok(x)),
        (None, None) => None,
    }
}

/// A deciding index in words: "1.07", "not defined (outside the equation's limits)", or "none"
/// (no lifts declared).
pub fn index_words(index: Option<&Result<f64, String>>) -> String {
    match index {
        None => "none".into(),
        Some(Ok(x)) => format!("{x:.2}"),
        Some(Err(_)) => "not defined (outside the equation's limits)".into(),
    }
}

/// A lifting index at the precision NIOSH reports it (two decimals: the Applications manual's
/// worked examples): two indices that round alike are the same index, so that a difference the
/// solver's last digits make (1.009045 against 1.009166, an asymmetry of 0.18° against 0.20°)
/// decides no ranking.
pub fn reported(index: f64) -> f64 {
    (index * 100.0).round() / 100.0
}

/// Where H and A are measured from, in words: the lifting index follows the feet, so a reader
/// comparing it with a field measurement needs to know whose feet (`None` without a stance).
pub fn stance_words(task: &Task) -> Option<&'static str> {
    let st = task.stance.as_ref()?;
    Some(if st.placement.is_some() {
        "H and A are measured from the ankles where the plan places the feet in each phase (the worker steps and turns within the task's standing area); with the feet fixed they would differ"
    } else {
        "H and A are measured from the ankles where the task fixes the feet"
    })
}

/// The lifting index's risk class for ranking — 0: at most 1 (nearly all healthy workers), 1: at
/// most 3 (an increased risk for some), 2: above 3 (many workers at elevated risk; Waters et al.
/// 1994, Applications manual), 3: outside the equation's limits (no load is recommended) — and,
/// above 1, the index itself as reported ([`reported`]; lower ranks better). `None` (no lifts
/// declared) is class 0.
pub fn risk_key(index: Option<&Result<f64, String>>) -> (u8, f64) {
    match index.map(|i| i.as_ref().map(|x| reported(*x))) {
        Some(Err(_)) => (3, 0.0),
        Some(Ok(x)) if x > 3.0 => (2, x),
        Some(Ok(x)) if x > 1.0 => (1, x),
        _ => (0, 0.0),
    }
}

fn geometry(task: &Task, plan: &Plan, pw: &mut PostureWork, p: usize) -> Option<LiftGeometry> {
    let ph = &task.phases[p];
    let q = &plan.summary.phases[p].q_rad;
    pw.statics(task, q, &ph.hand_force_n);
    let hands: Vec<Vector3<f64>> = (0..2)
        .filter(|&h| ph.targets_m[h].is_some())
        .filter_map(|h| pw.hand_position(task, h))
        .collect();
    if hands.is_empty() {
        return None;
    }
    let mid = hands.iter().fold(Vector3::zeros(), |a, b| a + b) / hands.len() as f64;
    // the mid-sagittal line of the neutral posture runs through the ankles' mid-point along the
    // feet's mean heading (where the feet stand in this phase: a worker who turns his feet
    // toward the load lifts it without asymmetry)
    let (ankles, heading) = match &task.stance {
        Some(st) => {
            let ankle = |i: usize| {
                pw.data
                    .link_point(&task.model, st.feet[i].link, &Vector3::zeros())
            };
            let feet = FeetNow::at(&task.model, &pw.data, &st.feet);
            ((ankle(0) + ankle(1)) / 2.0, feet.geometry().heading_rad)
        }
        None => (Vector3::zeros(), 0.0),
    };
    let d = Vector3::new(mid.x - ankles.x, mid.y - ankles.y, 0.0);
    let h = d.norm();
    let a = if h > 1e-9 {
        wrap_pi(d.y.atan2(d.x) - heading).to_degrees()
    } else {
        0.0
    };
    Some(LiftGeometry {
        h_m: h,
        v_m: mid.z,
        asymmetry_deg: a.abs(),
    })
}

/// The NIOSH assessment of the task's lifts (`None` without lifts).
pub fn assess_lifts(task: &Task, plan: &Plan) -> Option<Result<Lifting, NioshError>> {
    if task.lifts.is_empty() {
        return None;
    }
    let mut pw = PostureWork::new(task);
    let g = task.gravity_m_s2.norm().max(1e-9);
    let hours = task.duration_s() / 3600.0;
    let duration = match WorkDuration::from_hours(hours.max(1e-6)) {
        Ok(d) => d,
        Err(e) => return Some(Err(e)),
    };
    let mut lifts = Vec::with_capacity(task.lifts.len());
    for l in &task.lifts {
        let (Some(origin), Some(destination)) = (
            geometry(task, plan, &mut pw, l.origin),
            geometry(task, plan, &mut pw, l.destination),
        ) else {
            continue;
        };
        let load = task.phases[l.origin]
            .total_force_n()
            .norm()
            .max(task.phases[l.destination].total_force_n().norm())
            / g;
        lifts.push(Lift {
            name: l.name.clone(),
            load_kg: load,
            max_load_kg: None,
            origin,
            destination,
            freq_per_min: 60.0 / task.cycle_s(),
            duration,
            coupling: match l.coupling {
                CouplingName::Good => Coupling::Good,
                CouplingName::Fair => Coupling::Fair,
                CouplingName::Poor => Coupling::Poor,
            },
            control_at_destination: l.control_at_destination,
            form: EquationForm::Metric,
        });
    }
    let results: Result<Vec<LiftResult>, NioshError> = lifts.iter().map(assess_lift).collect();
    Some(results.and_then(|r| {
        let comp = if lifts.len() > 1 {
            Some(composite(&lifts)?)
        } else {
            None
        };
        Ok(Lifting {
            lifts: r,
            composite: comp,
        })
    }))
}
