//! Plan outputs: the text summary, the CSV timeline and recording, the JSON document and the
//! self-contained HTML report.

pub mod csv;
pub mod html;
pub mod text;

use crate::assess::Assessment;
use crate::plan::Plan;
use serde::Serialize;

/// The `plan --json` document: the plan and its assessment (`docs/interface.md`).
#[derive(Serialize)]
pub struct PlanDocument<'a> {
    #[serde(flatten)]
    pub plan: &'a Plan,
    pub assessment: &'a Assessment,
}
