//! Layout comparison: the same work planned on several workstation layouts, side by side and
//! ranked.
//!
//! Ranking (best first): a layout whose plan exhausts no muscle group beats one that does (and
//! among those that do, later exhaustion is better); then fewer unreachable targets; then lower
//! total fatigue index U per hour of planned work (the total U itself when all layouts plan the
//! same duration); then the lower worst RULA score.

use crate::plan::{plan_with_baseline, Exhaustion, Plan, PlanError};
use crate::rest::{rest_advice, RestAdvice};
use crate::task::Task;
use rayon::prelude::*;
use serde::Serialize;
use std::cmp::Ordering;
use std::fmt::Write;

/// One layout's outcome.
#[derive(Debug, Clone, Serialize)]
pub struct LayoutOutcome {
    /// 1 = best.
    pub rank: usize,
    pub file: String,
    pub task: String,
    pub planned_duration_s: f64,
    pub simulated_duration_s: f64,
    pub total_u_min: f64,
    pub total_u_per_hour_min: f64,
    pub baseline_total_u_min: Option<f64>,
    pub worst_half_joint: String,
    /// The most-fatigued muscle group (largest U).
    pub worst_group: String,
    pub worst_u_min: f64,
    /// Lowest capacity at any time of the task.
    pub min_capacity: f64,
    pub min_capacity_half_joint: String,
    pub exhaustion: Option<Exhaustion>,
    pub unreachable_phases: Vec<String>,
    pub rula_max: Option<i32>,
    pub rula_worst_phase: Option<String>,
    pub rest: RestAdvice,
}

/// The comparison document (`posture-opt compare --json`).
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    pub adaptive: bool,
    pub capacity_floor: f64,
    pub ranking_rule: &'static str,
    /// Ranked, best first.
    pub layouts: Vec<LayoutOutcome>,
}

pub const RANKING_RULE: &str = "no exhaustion first (later exhaustion better), then fewer unreachable targets, then lower total U per hour of work, then lower worst RULA";

/// A planned layout: its outcome and its plan (for reports).
pub struct Planned {
    pub outcome: LayoutOutcome,
    pub plan: Plan,
}

fn outcome(file: &str, task: &Task, plan: &Plan, floor: f64) -> LayoutOutcome {
    let s = &plan.summary;
    let worst_group = task
        .half_joints
        .iter()
        .find(|h| h.id == s.worst_half_joint)
        .map(|h| h.group.clone())
        .unwrap_or_default();
    let (min_capacity, min_capacity_half_joint) = plan.lowest_capacity();
    let rula_worst_phase = s
        .phases
        .iter()
        .filter_map(|p| p.rula.as_ref().map(|r| (r.grand_score, &p.phase)))
        .rev()
        .max_by_key(|(g, _)| *g)
        .map(|(_, p)| p.clone());
    LayoutOutcome {
        rank: 0,
        file: file.to_string(),
        task: plan.task.clone(),
        planned_duration_s: s.planned_duration_s,
        simulated_duration_s: s.duration_s,
        total_u_min: s.total_u,
        total_u_per_hour_min: s.total_u * 3600.0 / s.planned_duration_s,
        baseline_total_u_min: s.baseline_total_u,
        worst_half_joint: s.worst_half_joint.clone(),
        worst_group,
        worst_u_min: s.worst_u,
        min_capacity,
        min_capacity_half_joint,
        exhaustion: s.exhaustion.clone(),
        unreachable_phases: s
            .phases
            .iter()
            .filter(|p| !p.reachable)
            .map(|p| p.phase.clone())
            .collect(),
        rula_max: s.rula_max,
        rula_worst_phase,
        rest: rest_advice(task, plan, floor),
    }
}

/// Orders two outcomes by [`RANKING_RULE`].
pub fn rank_order(a: &LayoutOutcome, b: &LayoutOutcome) -> Ordering {
    let ex = |o: &LayoutOutcome| o.exhaustion.as_ref().map_or(f64::INFINITY, |e| e.t_s);
    ex(b)
        .total_cmp(&ex(a))
        .then(a.unreachable_phases.len().cmp(&b.unreachable_phases.len()))
        .then(a.total_u_per_hour_min.total_cmp(&b.total_u_per_hour_min))
        .then(a.rula_max.unwrap_or(0).cmp(&b.rula_max.unwrap_or(0)))
}

/// Plans every layout (in parallel) and ranks them. `files[i]` names `tasks[i]`.
pub fn compare(
    files: &[String],
    tasks: &[Task],
    adapt: bool,
    floor: f64,
) -> Result<(Comparison, Vec<Planned>), PlanError> {
    let mut planned: Vec<Planned> = files
        .par_iter()
        .zip(tasks.par_iter())
        .map(|(file, task)| {
            let (plan, _) = plan_with_baseline(task, adapt)?;
            Ok(Planned {
                outcome: outcome(file, task, &plan, floor),
                plan,
            })
        })
        .collect::<Result<_, PlanError>>()?;
    planned.sort_by(|a, b| rank_order(&a.outcome, &b.outcome));
    for (i, p) in planned.iter_mut().enumerate() {
        p.outcome.rank = i + 1;
    }
    let comparison = Comparison {
        adaptive: adapt,
        capacity_floor: floor,
        ranking_rule: RANKING_RULE,
        layouts: planned.iter().map(|p| p.outcome.clone()).collect(),
    };
    Ok((comparison, planned))
}

fn opt_s(v: Option<f64>) -> String {
    v.map_or("—".into(), |x| format!("{x:.1} s"))
}

/// The comparison as a text table: one column per layout, best first.
pub fn comparison_table(c: &Comparison) -> String {
    let mut rows: Vec<(String, Vec<String>)> = Vec::new();
    let mut row = |name: &str, f: &dyn Fn(&LayoutOutcome) -> String| {
        rows.push((name.to_string(), c.layouts.iter().map(f).collect()));
    };
    row("rank", &|o| o.rank.to_string());
    row("file", &|o| o.file.clone());
    row("total U [min]", &|o| format!("{:.2}", o.total_u_min));
    row("total U per hour [min]", &|o| {
        format!("{:.2}", o.total_u_per_hour_min)
    });
    row("worst group", &|o| {
        format!("{} ({})", o.worst_half_joint, o.worst_group)
    });
    row("worst group U [min]", &|o| format!("{:.2}", o.worst_u_min));
    row("min capacity", &|o| {
        format!("{:.2} {}", o.min_capacity, o.min_capacity_half_joint)
    });
    row("first exhaustion", &|o| match &o.exhaustion {
        Some(e) => format!("{:.0} s {} in '{}'", e.t_s, e.half_joint, e.phase),
        None => "none".into(),
    });
    row("unreachable targets", &|o| {
        if o.unreachable_phases.is_empty() {
            "none".into()
        } else {
            o.unreachable_phases.join(", ")
        }
    });
    row("worst RULA", &|o| match (o.rula_max, &o.rula_worst_phase) {
        (Some(r), Some(p)) => format!("{r} ('{p}')"),
        _ => "n/a (not the worker body)".into(),
    });
    row("rest per cycle now", &|o| {
        format!("{:.1} s", o.rest.current_rest_s)
    });
    row(
        &format!("rest needed, model (floor {:.2})", c.capacity_floor),
        &|o| match o.rest.model.rest_s_per_cycle {
            Some(r) => format!("{r:.1} s"),
            None => "rest cannot help".into(),
        },
    );
    row("rest needed, Rohmert 1973", &|o| {
        opt_s(Some(o.rest.rohmert.rest_s_per_cycle))
    });
    let w0 = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(0);
    let widths: Vec<usize> = (0..c.layouts.len())
        .map(|i| {
            rows.iter()
                .map(|r| r.1[i].chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut o = String::new();
    for (name, cells) in &rows {
        let _ = write!(o, "{name:<w0$}");
        for (cell, w) in cells.iter().zip(&widths) {
            let _ = write!(o, "  {cell:<w$}");
        }
        let _ = writeln!(o);
    }
    let _ = writeln!(o, "\nranking: {}", c.ranking_rule);
    if let Some(best) = c.layouts.first() {
        let _ = writeln!(o, "best layout: {} ({})", best.file, best.task);
    }
    o
}
