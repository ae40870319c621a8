//! Self-contained HTML reports of `plan`, `compare` and `sweep`: findings in plain words first,
//! then the worker and the phases, capacity over time, the whole body drawn in every phase's
//! posture with the workstation, the observational scores, rest, baselines, uncertainty and the
//! model's parameters with their sources.
//!
//! One file: inline CSS ([`style.css`](style.css)) and inline SVG, no scripts, fonts, images or
//! links, so it opens offline and prints to PDF (A4, page breaks before the big sections). Text
//! from task files (task, phase and obstacle names) is escaped; missing or non-finite numbers
//! print as "—".
//!
//! * [`fmt`]: escaping, numbers, levels, tables; [`svg`]: the SVG writer;
//! * [`analysis`]: loads per phase, endurance used, each group's lowest capacity, the hardest
//!   phase; [`findings`]: the plan's findings in words;
//! * [`body_view`]: whole-body figures; [`curves`]: capacity over time;
//! * [`plan_page`], [`compare_page`], [`sweep_page`]: the three reports.

mod analysis;
mod body_view;
mod compare_page;
mod curves;
mod findings;
mod fmt;
mod plan_page;
mod svg;
mod sweep_page;

use crate::assess::Assessment;
use crate::plan::{Plan, Task};
use crate::study::compare::{Comparison, Planned};
use crate::study::sweep::Sweep;

/// Why a report could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    #[error("cannot draw a figure: {0}")]
    Figure(String),
}

const STYLE: &str = include_str!("style.css");

/// The whole page around `body`.
fn document(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><title>{}</title><style>{STYLE}</style></head><body>{body}<footer class=\"meta\">posture-opt {} — fatigue: Ma, Chablat, Bennis &amp; Zhang (2009) with the recovery of the parameter set named above; RULA: McAtamney &amp; Corlett (1993); REBA: Hignett &amp; McAtamney (2000); NIOSH lifting equation: Waters et al. (1993); rest allowance: Rohmert (1973). The postures are a model’s: check them against the real task.</footer></body></html>\n",
        fmt::esc(title),
        env!("CARGO_PKG_VERSION")
    )
}

/// The report of one plan and its assessment.
/// `what_ifs`: workstation changes the tool planned ([`crate::study::what_if`]), each reported
/// as "what would change it".
pub fn plan_report(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    what_ifs: &[crate::study::what_if::WhatIf],
) -> Result<String, ReportError> {
    let body = plan_page::body(task, plan, a, what_ifs)?;
    Ok(document(&format!("Plan: {}", plan.task), &body))
}

/// The report of a comparison; `tasks[i]` and `planned[i]` are in `c.layouts`' ranked order.
pub fn compare_report(
    c: &Comparison,
    tasks: &[&Task],
    planned: &[Planned],
) -> Result<String, ReportError> {
    let body = compare_page::body(c, tasks, planned)?;
    Ok(document("Layout comparison", &body))
}

/// The report of a population sweep: who cannot do the task, and why.
/// `task`: the swept task (its phases and fatigue parameters are shown; each worker's body is
/// generated from the worker).
pub fn sweep_report(s: &Sweep, task: Option<&crate::plan::Task>) -> Result<String, ReportError> {
    Ok(document(
        &format!("Population sweep: {}", s.task),
        &sweep_page::body(s, task),
    ))
}
