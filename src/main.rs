//! posture-opt command line: parses arguments, calls the library, prints. Exit codes: 0 ok,
//! 2 bad input, 1 internal failure.

use anyhow::{anyhow, Context, Result};
use clap::{Parser, Subcommand};
use nalgebra::Vector3;
use posture_opt::body::{
    statics_report, worker_urdf, BodyModel, Sex, StrengthTable, Worker, GRAVITY_M_S2,
};
use posture_opt::fatigue::{FatigueError, MaParams};
use posture_opt::report::html;
use posture_opt::validation::{dynamic_validation, plots, static_validation};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "posture-opt",
    version,
    about = "Fatigue-aware posture planning (Ma et al. 2009 dynamic muscle fatigue model)"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Reproduce the paper's validations.
    Validate {
        #[command(subcommand)]
        which: ValidateWhich,
    },
    /// Maximum endurance time and the capacity / fatigue-index curve for a held load.
    Met {
        /// Relative load f = F_load/MVC in (0, 1], or a range START:END:STEP.
        #[arg(long)]
        fmvc: String,
        /// Fatigue rate k [1/min].
        #[arg(long, default_value_t = 1.0)]
        k_per_min: f64,
        /// Recovery rate R [1/min] (0 = the paper's model).
        #[arg(long, default_value_t = 0.0)]
        r_per_min: f64,
        /// Samples of the curve between 0 and the endurance time.
        #[arg(long, default_value_t = 10)]
        points: usize,
        #[arg(long)]
        json: bool,
    },
    /// Joint positions, Jacobian and holding torques of any URDF at one posture (DESIGN §6).
    Statics {
        /// URDF file.
        #[arg(long)]
        robot: PathBuf,
        /// Link or joint whose frame origin is the hand point.
        #[arg(long)]
        frame: String,
        /// Joint positions NAME=RAD[,NAME=RAD...]; joints not named are at 0.
        #[arg(long)]
        q: Option<String>,
        /// A carried load in the hand [kg] (force = mass × gravity).
        #[arg(long, conflicts_with = "hand_force")]
        hand_load_kg: Option<f64>,
        /// Force the environment applies on the hand, FX,FY,FZ [N], world frame.
        #[arg(long, allow_hyphen_values = true)]
        hand_force: Option<String>,
        /// Gravity GX,GY,GZ [m/s²] (default 0,0,-9.81).
        #[arg(long, allow_hyphen_values = true)]
        gravity: Option<String>,
        #[arg(long)]
        json: bool,
    },
    /// Plan postures for a task file: fatigue-adaptive (default) or the baseline.
    Plan {
        /// Task file (YAML).
        task: PathBuf,
        #[command(flatten)]
        assess: AssessArgs,
        /// Also write the timeline as CSV.
        #[arg(long)]
        csv: Option<PathBuf>,
        /// Also write the plan as a recording for `evaluate` (t_s, joints, force_*_n).
        #[arg(long)]
        recording: Option<PathBuf>,
    },
    /// Compare workstation layouts (task files): side by side, ranked.
    Compare {
        /// Two or more task files (YAML), one per layout.
        #[arg(required = true, num_args = 2..)]
        tasks: Vec<PathBuf>,
        #[command(flatten)]
        assess: AssessArgs,
    },
    /// Plan one task for a population of workers: who cannot do it, and where.
    Sweep {
        /// Task file (YAML); the worker and robot in it are replaced by each population member.
        task: PathBuf,
        /// Sample this many workers instead of the 5th/50th/95th-percentile men and women.
        #[arg(long)]
        sample: Option<usize>,
        /// Seed of the sample.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        #[command(flatten)]
        assess: AssessArgs,
    },
    /// Evaluate recorded work (joint angles and hand load over time) into a fatigue timeline.
    Evaluate {
        /// Recording (CSV: t_s, joint columns, load_kg or force_x_n/_y_n/_z_n); not with --stream.
        #[arg(required_unless_present = "stream")]
        recording: Option<PathBuf>,
        #[arg(long)]
        robot: PathBuf,
        #[arg(long, default_value = "hand_grip")]
        hand_frame: String,
        /// Joint columns are in degrees.
        #[arg(long)]
        degrees: bool,
        #[arg(long, value_enum, default_value = "male")]
        sex: Sex,
        #[arg(long, default_value_t = 1.755)]
        stature_m: f64,
        #[arg(long, default_value_t = 78.0)]
        mass_kg: f64,
        #[arg(long, default_value_t = 50.0)]
        strength_percentile: f64,
        #[arg(long, default_value_t = 1.0)]
        k_per_min: f64,
        #[arg(long, default_value_t = 0.0)]
        r_per_min: f64,
        /// Live: read the header and then one sample per line from standard input, write one
        /// JSON line per sample.
        #[arg(long, conflicts_with_all = ["json", "csv"])]
        stream: bool,
        #[arg(long)]
        json: bool,
        #[arg(long)]
        csv: Option<PathBuf>,
    },
    /// Write the URDF of a standing worker (and its strength table beside it).
    Robot {
        #[arg(long, value_enum)]
        sex: Sex,
        #[arg(long)]
        stature_m: f64,
        #[arg(long)]
        mass_kg: f64,
        /// Strength percentile (1-99) of the worker's sex.
        #[arg(long, default_value_t = 50.0)]
        strength_percentile: f64,
        /// Output URDF file (its strength table goes to NAME.strength.yaml); stdout if absent.
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

/// Options shared by `plan`, `compare` and `sweep`.
#[derive(clap::Args)]
struct AssessArgs {
    /// The fatigue-unaware baseline: fresh capacities, solved once, held all task.
    #[arg(long)]
    no_adapt: bool,
    /// Write the result as one JSON document on standard output.
    #[arg(long)]
    json: bool,
    /// Also write a self-contained HTML report.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Capacity floor for the work/rest advice (fraction of MVC, strictly between 0 and 1).
    #[arg(long, default_value_t = posture_opt::rest::DEFAULT_CAPACITY_FLOOR, value_parser = parse_floor)]
    capacity_floor: f64,
}

fn parse_floor(s: &str) -> std::result::Result<f64, String> {
    match s.parse::<f64>() {
        Ok(f) if f.is_finite() && f > 0.0 && f < 1.0 => Ok(f),
        _ => Err(format!("must be a number between 0 and 1, got '{s}'")),
    }
}

#[derive(Subcommand)]
enum ValidateWhich {
    /// Table 2: Eq. 8 against 24 published MET models (Pearson r, ICC).
    Static {
        #[arg(long, default_value_t = 1.0)]
        k_per_min: f64,
        #[arg(long)]
        json: bool,
        /// Write SVG figures (paper Fig. 1-8) into this directory.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
    /// §4: Liu et al. at MVC, Freund-Takala, Wexler's trend, Frey-Law & Avin endurance curves.
    Dynamic {
        #[arg(long, default_value_t = 1.0)]
        k_per_min: f64,
        #[arg(long)]
        json: bool,
        /// Write SVG figures (paper Fig. 10 and endurance curves) into this directory.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
}

/// An error caused by the user's input (exit 2).
#[derive(Debug)]
struct BadInput(String);
impl std::fmt::Display for BadInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}
impl std::error::Error for BadInput {}

fn bad(msg: impl Into<String>) -> anyhow::Error {
    anyhow!(BadInput(msg.into()))
}

fn lib_err(e: impl Into<posture_opt::Error>) -> anyhow::Error {
    let e: posture_opt::Error = e.into();
    if e.is_bad_input() {
        bad(e.to_string())
    } else {
        anyhow!(e)
    }
}

fn check_k(k: f64) -> Result<MaParams> {
    MaParams::new(k, 0.0).map_err(|e| bad(format!("--k-per-min: {e}")))
}

fn parse_fmvc(s: &str) -> Result<Vec<f64>> {
    let num = |t: &str| -> Result<f64> {
        t.trim()
            .parse::<f64>()
            .map_err(|_| bad(format!("--fmvc: '{t}' is not a number")))
    };
    let values = match s.split(':').collect::<Vec<_>>().as_slice() {
        [one] => vec![num(one)?],
        [a, b, c] => {
            let (a, b, c) = (num(a)?, num(b)?, num(c)?);
            if !(c.is_finite() && c > 0.0 && a.is_finite() && b.is_finite()) || b < a {
                return Err(bad(format!(
                    "--fmvc: range '{s}' needs START <= END and STEP > 0"
                )));
            }
            let n = ((b - a) / c + 1e-9).floor() as usize;
            if n > 10_000 {
                return Err(bad(format!(
                    "--fmvc: range '{s}' has more than 10000 levels"
                )));
            }
            (0..=n).map(|i| a + c * i as f64).collect()
        }
        _ => {
            return Err(bad(format!(
                "--fmvc: '{s}' is neither a number nor START:END:STEP"
            )))
        }
    };
    for &f in &values {
        if !(f.is_finite() && f > 0.0 && f <= 1.0) {
            return Err(lib_err(FatigueError::BadLoad {
                what: "--fmvc",
                value: f,
            }));
        }
    }
    Ok(values)
}

fn parse_vec3(opt: &str, s: &str) -> Result<Vector3<f64>> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(bad(format!("{opt}: expected X,Y,Z, got '{s}'")));
    }
    let mut v = [0.0; 3];
    for (i, p) in parts.iter().enumerate() {
        v[i] = p
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| bad(format!("{opt}: '{p}' is not a finite number")))?;
    }
    Ok(Vector3::from(v))
}

fn parse_q(s: &str) -> Result<Vec<(String, f64)>> {
    s.split(',')
        .filter(|p| !p.trim().is_empty())
        .map(|p| {
            let (name, val) = p
                .split_once('=')
                .ok_or_else(|| bad(format!("--q: '{p}' is not NAME=RAD")))?;
            let v = val
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    bad(format!(
                        "--q: {name}: '{val}' is not a finite number of radians"
                    ))
                })?;
            Ok((name.trim().to_string(), v))
        })
        .collect()
}

/// Writes every output atomically, only after all of them were produced.
fn write_outputs(outputs: &[(PathBuf, String)]) -> Result<()> {
    for (path, text) in outputs {
        posture_opt::io::write_atomic(path, text.as_bytes()).map_err(|e| bad(e.to_string()))?;
    }
    Ok(())
}

fn print_json(v: &impl serde::Serialize) -> Result<()> {
    let mut out = std::io::stdout().lock();
    serde_json::to_writer_pretty(&mut out, v)?;
    writeln!(out)?;
    Ok(())
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Validate {
            which:
                ValidateWhich::Static {
                    k_per_min,
                    json,
                    plot,
                },
        } => {
            check_k(k_per_min)?;
            let v = static_validation(k_per_min);
            if let Some(dir) = &plot {
                let files = plots::static_figures(&v, dir).map_err(lib_err)?;
                eprintln!("wrote {} figures into {}", files.len(), dir.display());
            }
            if json {
                print_json(&v)
            } else {
                print!("{}", posture_opt::validation::report::static_table(&v));
                Ok(())
            }
        }
        Command::Validate {
            which:
                ValidateWhich::Dynamic {
                    k_per_min,
                    json,
                    plot,
                },
        } => {
            check_k(k_per_min)?;
            let v = dynamic_validation(k_per_min);
            if let Some(dir) = &plot {
                let files = plots::dynamic_figures(&v, dir).map_err(lib_err)?;
                eprintln!("wrote {} figures into {}", files.len(), dir.display());
            }
            if json {
                print_json(&v)
            } else {
                print!("{}", posture_opt::validation::report::dynamic_table(&v));
                Ok(())
            }
        }
        Command::Statics {
            robot,
            frame,
            q,
            hand_load_kg,
            hand_force,
            gravity,
            json,
        } => {
            let model = BodyModel::from_urdf_file(&robot).map_err(lib_err)?;
            let gravity = match gravity {
                Some(g) => parse_vec3("--gravity", &g)?,
                None => GRAVITY_M_S2,
            };
            let force = match (hand_load_kg, hand_force) {
                (Some(m), _) if !(m.is_finite() && m >= 0.0) => {
                    return Err(bad(format!(
                        "--hand-load-kg must be finite and >= 0, got {m}"
                    )))
                }
                (Some(m), _) => gravity * m,
                (None, Some(f)) => parse_vec3("--hand-force", &f)?,
                (None, None) => Vector3::zeros(),
            };
            let q = q.as_deref().map(parse_q).transpose()?.unwrap_or_default();
            let report = statics_report(&model, &frame, &q, force, gravity)
                .map_err(|e| bad(format!("{}: {e}", robot.display())))?;
            if json {
                print_json(&report)
            } else {
                println!(
                    "frame {} at ({:.4}, {:.4}, {:.4}) m",
                    report.frame, report.position_m[0], report.position_m[1], report.position_m[2]
                );
                println!(
                    "{:<26} {:>9} {:>12} {:>12} {:>12}",
                    "joint", "q [rad]", "gravity N·m", "load N·m", "total N·m"
                );
                for j in &report.joints {
                    println!(
                        "{:<26} {:>9.4} {:>12.3} {:>12.3} {:>12.3}",
                        j.name, j.q_rad, j.gravity_torque_nm, j.load_torque_nm, j.torque_nm
                    );
                }
                Ok(())
            }
        }
        Command::Evaluate {
            recording,
            robot,
            hand_frame,
            degrees,
            sex,
            stature_m,
            mass_kg,
            strength_percentile,
            k_per_min,
            r_per_min,
            stream,
            json,
            csv,
        } => {
            let worker = Worker {
                sex,
                stature_m,
                mass_kg,
                strength_percentile,
            };
            let params = MaParams::new(k_per_min, r_per_min).map_err(lib_err)?;
            let setup =
                posture_opt::evaluate::EvalSetup::from_robot(&robot, &hand_frame, &worker, params)
                    .map_err(|e| bad(e.to_string()))?;
            if stream {
                return posture_opt::evaluate::stream(
                    &setup,
                    degrees,
                    std::io::stdin().lock(),
                    std::io::stdout().lock(),
                )
                .map_err(|e| match e {
                    posture_opt::evaluate::StreamError::Recording(r) => bad(r.to_string()),
                    posture_opt::evaluate::StreamError::Io(io) => anyhow!(io),
                });
            }
            let path = recording.expect("clap requires a recording without --stream");
            let name = path.display().to_string();
            let text = std::fs::read_to_string(&path)
                .map_err(|e| bad(format!("{name}: cannot read: {e}")))?;
            let report = posture_opt::evaluate::evaluate_recording(&setup, &text, degrees, &name)
                .map_err(|e| bad(e.to_string()))?;
            if let Some(p) = csv {
                posture_opt::io::write_atomic(&p, report.to_csv().as_bytes())
                    .map_err(|e| bad(e.to_string()))?;
            }
            if json {
                print_json(&report)
            } else {
                print!("{}", report.summary_text());
                Ok(())
            }
        }
        Command::Plan {
            task,
            assess:
                AssessArgs {
                    no_adapt,
                    json,
                    report,
                    capacity_floor,
                },
            csv,
            recording,
        } => {
            let t = posture_opt::task::Task::from_file(&task).map_err(|e| bad(e.to_string()))?;
            let (plan, _baseline) = posture_opt::plan::plan_with_baseline(&t, !no_adapt)?;
            let rest = posture_opt::rest::rest_advice(&t, &plan, capacity_floor);
            // Everything is computed before anything is written.
            let mut outputs: Vec<(PathBuf, String)> = Vec::new();
            if let Some(path) = csv {
                outputs.push((path, posture_opt::report::plan_csv(&plan)));
            }
            if let Some(path) = recording {
                outputs.push((path, posture_opt::report::plan_recording_csv(&plan)));
            }
            if let Some(path) = report {
                let file = task.display().to_string();
                let layout = html::Layout {
                    file: &file,
                    task: &t,
                    plan: &plan,
                    rest: &rest,
                };
                outputs.push((path, html::plan_report(&layout)?));
            }
            write_outputs(&outputs)?;
            if json {
                print_json(&posture_opt::report::PlanDocument {
                    plan: &plan,
                    rest: &rest,
                })
            } else {
                print!("{}", posture_opt::report::plan_summary(&plan));
                print!("{}", posture_opt::report::rest_summary(&rest));
                Ok(())
            }
        }
        Command::Compare {
            tasks,
            assess:
                AssessArgs {
                    no_adapt,
                    json,
                    report,
                    capacity_floor,
                },
        } => {
            let files: Vec<String> = tasks.iter().map(|p| p.display().to_string()).collect();
            let loaded = tasks
                .iter()
                .map(posture_opt::task::Task::from_file)
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| bad(e.to_string()))?;
            let (cmp, planned) =
                posture_opt::compare::compare(&files, &loaded, !no_adapt, capacity_floor)?;
            if let Some(path) = report {
                let layouts: Vec<html::Layout> = planned
                    .iter()
                    .map(|p| {
                        let i = files
                            .iter()
                            .position(|f| *f == p.outcome.file)
                            .expect("every planned layout comes from a file");
                        html::Layout {
                            file: &files[i],
                            task: &loaded[i],
                            plan: &p.plan,
                            rest: &p.outcome.rest,
                        }
                    })
                    .collect();
                write_outputs(&[(path, html::compare_report(&cmp, &layouts)?)])?;
            }
            if json {
                print_json(&cmp)
            } else {
                print!("{}", posture_opt::compare::comparison_table(&cmp));
                Ok(())
            }
        }
        Command::Sweep {
            task,
            sample,
            seed,
            assess:
                AssessArgs {
                    no_adapt,
                    json,
                    report,
                    capacity_floor,
                },
        } => {
            let name = task.display().to_string();
            let text = std::fs::read_to_string(&task)
                .map_err(|e| bad(format!("{name}: cannot read: {e}")))?;
            let file: posture_opt::task::TaskFile =
                serde_saphyr::from_str(&text).map_err(|e| bad(format!("{name}: {e}")))?;
            let (members, population) = match sample {
                Some(0) => return Err(bad("--sample must be at least 1")),
                Some(n) if n > 100_000 => return Err(bad("--sample must be at most 100000")),
                Some(n) => (
                    posture_opt::sweep::sampled_population(n, seed),
                    format!("{n} sampled workers, seed {seed}"),
                ),
                None => (
                    posture_opt::sweep::standard_population(),
                    "5th/50th/95th-percentile women and men".to_string(),
                ),
            };
            let bar = indicatif::ProgressBar::new(members.len() as u64);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "{spinner} planning workers [{bar:30}] {pos}/{len} {elapsed_precise} (eta {eta})",
                )
                .expect("valid template")
                .progress_chars("=> "),
            );
            let result = posture_opt::sweep::sweep(
                &file,
                &task,
                &members,
                &population,
                !no_adapt,
                capacity_floor,
                &|| bar.inc(1),
            );
            bar.finish_and_clear();
            let sw = result.map_err(|e| match e {
                posture_opt::sweep::SweepError::Task { .. } => bad(e.to_string()),
                posture_opt::sweep::SweepError::Plan { .. } => anyhow!(e),
            })?;
            if let Some(path) = report {
                write_outputs(&[(path, html::sweep_report(&sw))])?;
            }
            if json {
                print_json(&sw)
            } else {
                print!("{}", posture_opt::sweep::sweep_table(&sw));
                Ok(())
            }
        }
        Command::Robot {
            sex,
            stature_m,
            mass_kg,
            strength_percentile,
            out,
        } => {
            let w = Worker {
                sex,
                stature_m,
                mass_kg,
                strength_percentile,
            };
            let table = StrengthTable::default_table();
            let urdf = worker_urdf(&w, &table).map_err(lib_err)?;
            match out {
                Some(path) => {
                    posture_opt::io::write_atomic(&path, urdf.as_bytes())
                        .map_err(|e| bad(e.to_string()))?;
                    let sp = StrengthTable::path_beside(&path);
                    posture_opt::io::write_atomic(
                        &sp,
                        posture_opt::body::strength::DEFAULT_TABLE_YAML.as_bytes(),
                    )
                    .map_err(|e| bad(e.to_string()))?;
                    eprintln!("wrote {} and {}", path.display(), sp.display());
                    Ok(())
                }
                None => {
                    print!("{urdf}");
                    Ok(())
                }
            }
        }
        Command::Met {
            fmvc,
            k_per_min,
            r_per_min,
            points,
            json,
        } => {
            let p = MaParams::new(k_per_min, r_per_min).map_err(lib_err)?;
            if points == 0 || points > 100_000 {
                return Err(bad("--points must be between 1 and 100000"));
            }
            let levels = parse_fmvc(&fmvc)?;
            let report = posture_opt::fatigue::met_report(&p, &levels, points);
            if json {
                print_json(&report)
            } else {
                print!("{}", posture_opt::validation::report::met_table(&report));
                Ok(())
            }
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli).context("posture-opt") {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let bad_input = e.chain().any(|c| c.downcast_ref::<BadInput>().is_some());
            eprintln!("error: {}", e.root_cause());
            if bad_input {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}
