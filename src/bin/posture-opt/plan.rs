//! `posture-opt plan TASK.yaml`: plan, assess, print, and write the requested files.

use crate::common::{AssessArgs, Outputs, bad, lib_err, print_json, stdout};
use posture_opt::assess::assess;
use posture_opt::plan::{Task, plan_task_with};
use posture_opt::report::{PlanDocument, csv, text};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Task file (YAML).
    task: PathBuf,
    #[command(flatten)]
    assess: AssessArgs,
    /// Also write the timeline as CSV.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Also write the plan as a recording for `evaluate` (t_s, joints, hand forces).
    #[arg(long)]
    recording: Option<PathBuf>,
}

pub fn run(a: Args) -> anyhow::Result<()> {
    crate::common::check_stdout()?;
    let task = Task::from_file(&a.task).map_err(lib_err)?;
    let mut inputs: Vec<&std::path::Path> = vec![&a.task];
    inputs.extend(task.input_files.iter().map(|p| p.as_path()));
    if a.csv.is_some() && a.csv == a.recording {
        return Err(bad("--csv and --recording name the same file"));
    }
    Outputs::precheck(
        &[
            ("--csv", &a.csv),
            ("--recording", &a.recording),
            ("--report", &a.assess.report),
        ],
        &inputs,
    )?;
    let plan = plan_task_with(&task, a.assess.plan_options()).map_err(|e| anyhow::anyhow!(e))?;
    let assessment = assess(&task, &plan, a.assess.capacity_floor);
    let mut out = Outputs::new(&inputs);
    out.add_stream("--csv", &a.csv, |w| csv::write_plan_csv(&plan, w));
    out.add("--recording", &a.recording, || {
        Ok(csv::plan_recording_csv(&plan))
    })?;
    out.add("--report", &a.assess.report, || {
        // the report's "what would change it": the task planned again with the hardest phase
        // moved toward elbow height, and with the worker free to step
        let what_ifs = posture_opt::study::what_if::what_ifs(
            &task,
            &plan,
            &assessment,
            a.assess.plan_options(),
            a.assess.capacity_floor,
        )
        .map_err(|e| anyhow::anyhow!(e))?;
        Ok(
            posture_opt::report::html::plan_report(&task, &plan, &assessment, &what_ifs)
                .map_err(lib_err)?
                .into_bytes(),
        )
    })?;
    out.write()?;
    if a.assess.json {
        print_json(&PlanDocument {
            plan: &plan,
            assessment: &assessment,
        })
    } else {
        stdout(text::plan_summary(&task, &plan, &assessment).as_bytes())
    }
}
