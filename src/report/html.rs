//! Self-contained HTML reports (being rewritten for the whole-body worker).

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

pub fn plan_report(_task: &Task, plan: &Plan, _a: &Assessment) -> Result<String, ReportError> {
    Ok(format!("<!doctype html><title>{}</title>", plan.task))
}

pub fn compare_report(c: &Comparison, _tasks: &[&Task], _planned: &[Planned]) -> Result<String, ReportError> {
    Ok(format!("<!doctype html><title>{} layouts</title>", c.layouts.len()))
}

pub fn sweep_report(s: &Sweep) -> Result<String, ReportError> {
    Ok(format!("<!doctype html><title>{}</title>", s.task))
}
