//! `posture-opt sweep TASK.yaml`: one task for a population of workers.

use crate::common::{AssessArgs, Outputs, bad, lib_err, print_json, stdout};
use posture_opt::io::read_text;
use posture_opt::plan::TaskFile;
use posture_opt::study::shard::Shard;
use posture_opt::study::sweep::{self, Sweep, SweepShard};
use std::io::Write;
use std::path::PathBuf;
use std::sync::Mutex;

#[derive(clap::Args)]
pub struct Args {
    /// Task file (or, with --merge, shard results written by --shard).
    #[arg(required = true)]
    files: Vec<PathBuf>,
    #[command(flatten)]
    assess: AssessArgs,
    /// Sample this many workers (sex alternating, stature, mass and strength percentile drawn)
    /// instead of the 5th/50th/95th-percentile women and men.
    #[arg(long)]
    sample: Option<usize>,
    /// Seed of the sample.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Run only shard i of n (e.g. 2/4): worker j belongs to shard j mod n; print its outcomes as
    /// JSON for --merge.
    #[arg(long, conflicts_with_all = ["merge", "report"])]
    shard: Option<Shard>,
    /// The files are shard results: merge them into one sweep.
    #[arg(long)]
    merge: bool,
    /// Print each worker's outcome as one JSON line as soon as it is planned (large samples).
    #[arg(long, conflicts_with_all = ["merge", "json", "report"])]
    stream: bool,
}

pub fn run(a: Args) -> anyhow::Result<()> {
    crate::common::check_stdout()?;
    if a.merge {
        return merge(&a);
    }
    let [task_path] = a.files.as_slice() else {
        return Err(bad(
            "sweep plans one task file (several files only with --merge)",
        ));
    };
    let name = task_path.display().to_string();
    let text = read_text(task_path).map_err(lib_err)?;
    let file: TaskFile = serde_saphyr::from_str(&text).map_err(|e| {
        bad(format!(
            "{name}: {}",
            posture_opt::schema::explain_parse_error(&e.to_string())
        ))
    })?;
    // validate once for the task's own worker, so a bad file fails before the sweep
    let task = posture_opt::plan::Task::from_task_file(file.clone(), task_path).map_err(lib_err)?;
    let pop = match a.sample {
        Some(n) => sweep::Population::Sampled { n, seed: a.seed },
        None => sweep::Population::Standard,
    };
    let members = pop.members().map_err(|e| bad(format!("--sample: {e}")))?;
    let (population, sampled) = (pop.label(), pop.is_sampled());
    let shard = a.shard.unwrap_or(Shard::ALL);
    let todo = shard.indices(members.len()).len();
    let mut inputs: Vec<&std::path::Path> = vec![task_path];
    inputs.extend(task.input_files.iter().map(|p| p.as_path()));
    Outputs::precheck(&[("--report", &a.assess.report)], &inputs)?;
    let opts = a.assess.plan_options();
    let started = std::time::Instant::now();
    let bar = crate::common::progress_bar(todo, "workers");
    if todo > 6 {
        crate::common::say(format_args!(
            "planning {todo} workers; each takes seconds to a minute (two plans run at a time per core pair)"
        ));
    }
    // a line that could not be written (the reader left, a full disk): the run fails at the end
    let out_lock: Mutex<Option<std::io::Error>> = Mutex::new(None);
    let stream = a.stream;
    let on_done = |w: &sweep::WorkerOutcome| {
        bar.inc(1);
        if stream {
            let mut failed = out_lock.lock().unwrap_or_else(|p| p.into_inner());
            if failed.is_none()
                && let Ok(line) = serde_json::to_string(w)
            {
                let mut o = std::io::stdout().lock();
                if let Err(e) = writeln!(o, "{line}").and_then(|_| o.flush()) {
                    *failed = Some(e);
                }
            }
        }
    };
    let workers = sweep::sweep_members(
        &file,
        task_path,
        &members,
        shard,
        opts,
        a.assess.capacity_floor,
        &on_done,
    )
    .map_err(|e| anyhow::anyhow!(e))?;
    bar.finish_and_clear();
    if todo > 6 {
        crate::common::say(format_args!(
            "planned {todo} workers in {:.0} s",
            started.elapsed().as_secs_f64()
        ));
    }
    if stream {
        return match out_lock.into_inner().unwrap_or_else(|p| p.into_inner()) {
            None => Ok(()),
            Some(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
                Err(anyhow::anyhow!(crate::common::ClosedOutput))
            }
            Some(e) => Err(bad(format!("cannot write to standard output: {e}"))),
        };
    }
    if a.shard.is_some() {
        return print_json(&SweepShard::new(
            &file,
            task_path,
            shard,
            population,
            sampled,
            opts,
            a.assess.capacity_floor,
            members.len(),
            workers,
        ));
    }
    let s = Sweep::from_outcomes(
        &file.name,
        &population,
        sampled,
        opts.adapt,
        a.assess.capacity_floor,
        workers,
    );
    let mut out = Outputs::new(&inputs);
    out.add("--report", &a.assess.report, || {
        Ok(posture_opt::report::html::sweep_report(&s, Some(&task))
            .map_err(lib_err)?
            .into_bytes())
    })?;
    out.write()?;
    print(&s, a.assess.json)
}

fn print(s: &Sweep, json: bool) -> anyhow::Result<()> {
    if json {
        print_json(s)
    } else {
        stdout(sweep::sweep_table(s).as_bytes())
    }
}

fn merge(a: &Args) -> anyhow::Result<()> {
    if a.assess.report.is_some() {
        return Err(bad("--report is not available with --merge"));
    }
    let mut shards = Vec::with_capacity(a.files.len());
    for p in &a.files {
        let name = p.display().to_string();
        let text = read_text(p).map_err(lib_err)?;
        let s: SweepShard = serde_json::from_str(&text)
            .map_err(|e| bad(format!("{name}: not a sweep shard result: {e}")))?;
        shards.push((name, s));
    }
    let s = sweep::merge(&shards).map_err(lib_err)?;
    print(&s, a.assess.json)
}
