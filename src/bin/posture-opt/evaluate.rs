//! `posture-opt evaluate RECORDING`: recorded work (CSV, or OpenSim .mot/.sto with a mapping)
//! into a fatigue timeline; `--stream` evaluates samples from standard input as they come.

use crate::common::{ClosedOutput, bad, lib_err, parse_sex, print_json, stdout};
use posture_opt::body::{Sex, Worker};
use posture_opt::plan::Task;
use posture_opt::record::opensim::Mapping;
use posture_opt::record::{self, Evaluation, Input, Options, run::RunError};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// Recording: CSV (t_s, joint columns, hand loads) or OpenSim .mot/.sto (needs --mapping).
    /// Leave out with --stream.
    recording: Option<PathBuf>,
    /// Read CSV samples from standard input and print one JSON line per sample.
    #[arg(long)]
    stream: bool,
    /// Task file giving the body, worker, stance and fatigue parameters (its phases are not
    /// used). Without it: the generated worker described by --sex etc.
    #[arg(long)]
    task: Option<PathBuf>,
    /// Worker without --task.
    #[arg(long, value_parser = parse_sex, default_value = "male", conflicts_with = "task")]
    sex: Sex,
    #[arg(long, default_value_t = 1.755, conflicts_with = "task")]
    stature_m: f64,
    #[arg(long, default_value_t = 78.0, conflicts_with = "task")]
    mass_kg: f64,
    #[arg(long, default_value_t = 50.0, conflicts_with = "task")]
    strength_percentile: f64,
    /// Named fatigue parameter set without --task.
    #[arg(long, conflicts_with = "task")]
    parameters: Option<String>,
    /// CSV angles are in degrees.
    #[arg(long)]
    degrees: bool,
    /// Mapping of an OpenSim recording's coordinates onto the body's joints (YAML); the
    /// Rajagopal et al. (2016) model's is data/opensim/rajagopal2016.mapping.yaml.
    #[arg(long)]
    mapping: Option<PathBuf>,
    /// Constant load [kg] in the right hand when the recording has no load columns.
    #[arg(long, default_value_t = 0.0)]
    right_load_kg: f64,
    /// Constant load [kg] in the left hand when the recording has no load columns.
    #[arg(long, default_value_t = 0.0)]
    left_load_kg: f64,
    /// Also write every sample's capacity, U and load per group as CSV.
    #[arg(long)]
    csv: Option<PathBuf>,
    #[arg(long)]
    json: bool,
}

fn setup(a: &Args) -> anyhow::Result<Task> {
    match &a.task {
        Some(p) => Task::from_file(p).map_err(lib_err),
        None => record::default_setup(
            Worker {
                sex: a.sex,
                stature_m: a.stature_m,
                mass_kg: a.mass_kg,
                strength_percentile: a.strength_percentile,
            },
            a.parameters.as_deref(),
        )
        .map_err(lib_err),
    }
}

fn options(a: &Args) -> anyhow::Result<Options> {
    for (name, v) in [
        ("--right-load-kg", a.right_load_kg),
        ("--left-load-kg", a.left_load_kg),
    ] {
        if !(v.is_finite() && (0.0..=posture_opt::plan::task::MAX_LOAD_KG).contains(&v)) {
            return Err(bad(format!(
                "{name} must be 0..{} kg, got {v}",
                posture_opt::plan::task::MAX_LOAD_KG
            )));
        }
    }
    Ok(Options {
        degrees: a.degrees,
        hand_load_kg: [a.right_load_kg, a.left_load_kg],
    })
}

fn run_err(e: RunError) -> anyhow::Error {
    match e {
        RunError::Write(m) if m.contains("Broken pipe") => anyhow::anyhow!(ClosedOutput),
        e => bad(e.to_string()),
    }
}

pub fn run(a: Args) -> anyhow::Result<()> {
    if a.stream {
        crate::common::check_stdout()?;
        if let Some(p) = &a.recording {
            return Err(bad(format!(
                "--stream reads samples from standard input; evaluate a file without --stream (got {})",
                p.display()
            )));
        }
        if a.csv.is_some() || a.json || a.mapping.is_some() {
            return Err(bad(
                "--stream writes JSON lines to standard output: --csv, --json and --mapping do not apply",
            ));
        }
        let task = setup(&a)?;
        let opts = options(&a)?;
        let stdin = std::io::stdin().lock();
        let mut out = std::io::stdout().lock();
        record::stream(&task, stdin, "stdin", &opts, &mut out).map_err(run_err)?;
        return Ok(());
    }
    let Some(rec) = &a.recording else {
        return Err(bad(
            "give a recording file, or --stream to read samples from standard input",
        ));
    };
    let task = setup(&a)?;
    let opts = options(&a)?;
    let name = rec.display().to_string();
    let meta = posture_opt::io::check_input(rec).map_err(lib_err)?;
    let _ = meta;
    let mut inputs: Vec<&Path> = vec![rec];
    if let Some(t) = &a.task {
        inputs.push(t);
    }
    if let Some(m) = &a.mapping {
        inputs.push(m);
    }
    inputs.extend(task.input_files.iter().map(|p| p.as_path()));
    let file = std::fs::File::open(rec).map_err(|e| bad(format!("{name}: {e}")))?;
    let reader = std::io::BufReader::with_capacity(1 << 16, file);
    let ext = rec
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let input = if ext == "mot" || ext == "sto" {
        let Some(mp) = &a.mapping else {
            return Err(bad(format!(
                "{name}: an OpenSim recording needs --mapping (the coordinates' names, signs and offsets on the body's joints); for the Rajagopal (2016) model: data/opensim/rajagopal2016.mapping.yaml"
            )));
        };
        let text = posture_opt::io::read_text(mp).map_err(lib_err)?;
        let mapping = Mapping::from_yaml_str(&text, &mp.display().to_string()).map_err(lib_err)?;
        Input::OpenSim {
            reader,
            name: name.clone(),
            mapping,
        }
    } else {
        if a.mapping.is_some() {
            return Err(bad(
                "--mapping applies to OpenSim .mot/.sto recordings only",
            ));
        }
        Input::Csv {
            reader,
            name: name.clone(),
        }
    };
    let ev = match &a.csv {
        Some(csv_path) => {
            let mut set = posture_opt::io::OutputSet::new();
            for p in &inputs {
                set.input(p);
            }
            set.add("--csv", csv_path, Vec::new());
            set.check().map_err(lib_err)?;
            let mut tmp = posture_opt::io::TempOutput::beside(csv_path).map_err(lib_err)?;
            let ev = {
                let w: &mut dyn std::io::Write = tmp.writer();
                record::evaluate(&task, input, &opts, Some(w)).map_err(run_err)?
            };
            tmp.commit().map_err(lib_err)?;
            ev
        }
        None => record::evaluate(&task, input, &opts, None).map_err(run_err)?,
    };
    if a.json {
        print_json(&ev)
    } else {
        stdout(summary(&ev).as_bytes())
    }
}

fn summary(e: &Evaluation) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "{}: {} samples over {:.1} s ({}); body {}; fatigue parameters {}",
        e.source, e.samples, e.duration_s, e.hold_rule, e.robot, e.fatigue_parameters
    );
    let mut idx: Vec<usize> = (0..e.half_joint_ids.len()).collect();
    idx.sort_by(|&a, &b| e.final_capacity[a].total_cmp(&e.final_capacity[b]));
    let _ = writeln!(
        o,
        "{:<34} {:>9} {:>10}",
        "muscle group", "capacity", "U [min]"
    );
    for &h in idx.iter().take(8) {
        let _ = writeln!(
            o,
            "{:<34} {:>9.3} {:>10.3}",
            e.groups[h], e.final_capacity[h], e.final_fatigue_u_min[h]
        );
    }
    let _ = writeln!(
        o,
        "lowest capacity at any time: {:.3} ({}) at {:.1} s",
        e.lowest_capacity, e.lowest_capacity_group, e.lowest_capacity_t_s
    );
    if e.exhaustions.is_empty() {
        let _ = writeln!(o, "no muscle group exhausted");
    }
    for x in e.exhaustions.iter().take(20) {
        let _ = writeln!(
            o,
            "{} at {:.1} s: the {} can no longer hold {:.0} % MVC",
            if x.exceeds_capacity_at_start {
                "EXCEEDS CAPACITY"
            } else {
                "EXHAUSTED"
            },
            x.t_s,
            x.group,
            100.0 * x.load
        );
    }
    if e.exhaustions.len() > 20 {
        let _ = writeln!(
            o,
            "... {} exhaustion events in all (see --json)",
            e.exhaustions.len()
        );
    }
    if e.samples_outside_range > 0 {
        let _ = writeln!(
            o,
            "note: {} samples hold an angle outside its joint's range (by more than 0.1 rad)",
            e.samples_outside_range
        );
    }
    let _ = writeln!(
        o,
        "total U = {:.3} min (most: {} {:.3} min)",
        e.total_u_min, e.worst_group, e.worst_u_min
    );
    let _ = std::io::stderr().flush();
    o
}
