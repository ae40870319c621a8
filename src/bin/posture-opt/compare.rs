//! `posture-opt compare A.yaml B.yaml ...`: layouts planned side by side and ranked; with
//! `--shard i/n` one deterministic part of them, and `--merge` joins the parts.

use crate::common::{AssessArgs, Outputs, bad, lib_err, print_json, stdout};
use posture_opt::io::read_text;
use posture_opt::plan::Task;
use posture_opt::study::compare::{self, CompareShard, Comparison};
use posture_opt::study::shard::Shard;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Task files, one per layout (or, with --merge, shard results written by --shard --json).
    #[arg(required = true)]
    files: Vec<PathBuf>,
    #[command(flatten)]
    assess: AssessArgs,
    /// Run only shard i of n (e.g. 2/4): layout j belongs to shard j mod n; print its outcomes as
    /// JSON for --merge.
    #[arg(long, conflicts_with_all = ["merge", "report"])]
    shard: Option<Shard>,
    /// The files are shard results: merge them into one comparison.
    #[arg(long)]
    merge: bool,
}

pub fn run(a: Args) -> anyhow::Result<()> {
    if a.merge {
        return merge(&a);
    }
    if a.files.len() > compare::MAX_LAYOUTS {
        return Err(bad(format!(
            "at most {} layouts per comparison (use --shard to split)",
            compare::MAX_LAYOUTS
        )));
    }
    let names: Vec<String> = a.files.iter().map(|p| p.display().to_string()).collect();
    let tasks: Vec<Task> = a
        .files
        .iter()
        .map(|p| Task::from_file(p).map_err(lib_err))
        .collect::<anyhow::Result<_>>()?;
    let mut inputs: Vec<&std::path::Path> = a.files.iter().map(|p| p.as_path()).collect();
    for t in &tasks {
        inputs.extend(t.input_files.iter().map(|p| p.as_path()));
    }
    let opts = a.assess.plan_options();
    let todo = a
        .shard
        .map_or(tasks.len(), |s| s.indices(tasks.len()).len());
    let bar = crate::common::progress_bar(todo, "layouts");
    if todo > 4 {
        crate::common::say(format_args!(
            "planning {todo} layouts; each takes seconds to a minute (one at a time per core)"
        ));
    }
    let on_done = || bar.inc(1);
    if let Some(shard) = a.shard {
        let s = compare::compare_shard(
            &names,
            &tasks,
            shard,
            opts,
            a.assess.capacity_floor,
            &on_done,
        )
        .map_err(|e| anyhow::anyhow!(e))?;
        bar.finish_and_clear();
        return print_json(&s);
    }
    Outputs::precheck(&[("--report", &a.assess.report)], &inputs)?;
    let (c, planned) = compare::compare(&names, &tasks, opts, a.assess.capacity_floor, &on_done)
        .map_err(|e| anyhow::anyhow!(e))?;
    bar.finish_and_clear();
    let mut out = Outputs::new(&inputs);
    out.add("--report", &a.assess.report, || {
        let ordered: Vec<&Task> = c.layouts.iter().map(|o| &tasks[o.index]).collect();
        Ok(
            posture_opt::report::html::compare_report(&c, &ordered, &planned)
                .map_err(lib_err)?
                .into_bytes(),
        )
    })?;
    out.write()?;
    print(&c, a.assess.json)
}

fn print(c: &Comparison, json: bool) -> anyhow::Result<()> {
    if json {
        print_json(c)
    } else {
        stdout(compare::comparison_table(c).as_bytes())
    }
}

fn merge(a: &Args) -> anyhow::Result<()> {
    if a.assess.report.is_some() {
        return Err(bad(
            "--report needs the plans: run compare without --merge for a report",
        ));
    }
    let mut shards = Vec::with_capacity(a.files.len());
    for p in &a.files {
        let name = p.display().to_string();
        let text = read_text(p).map_err(lib_err)?;
        let s: CompareShard = serde_json::from_str(&text)
            .map_err(|e| bad(format!("{name}: not a compare shard result: {e}")))?;
        shards.push((name, s));
    }
    let c = compare::merge(&shards).map_err(lib_err)?;
    print(&c, a.assess.json)
}
