//! What the subcommands share: error kinds and exit codes, standard output, outputs, options.

use anyhow::anyhow;
use posture_opt::io::OutputSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// An error caused by the user's input (exit 2).
#[derive(Debug)]
pub struct BadInput(pub String);
impl std::fmt::Display for BadInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}
impl std::error::Error for BadInput {}

/// The reader of standard output went away (exit 2: the answer was not delivered).
#[derive(Debug)]
pub struct ClosedOutput;
impl std::fmt::Display for ClosedOutput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("standard output closed (its reader went away): the answer was not delivered")
    }
}
impl std::error::Error for ClosedOutput {}

pub fn bad(msg: impl Into<String>) -> anyhow::Error {
    anyhow!(BadInput(msg.into()))
}

/// A library error: bad input (exit 2) unless the library says otherwise.
pub fn lib_err(e: impl std::fmt::Display) -> anyhow::Error {
    bad(e.to_string())
}

/// Writes a line to standard error; an unwritable standard error (a closed pipe, a full disk)
/// is ignored rather than a panic, as `eprintln!` would.
pub fn say(msg: std::fmt::Arguments) {
    let mut e = std::io::stderr().lock();
    let _ = e.write_fmt(msg).and_then(|_| e.write_all(b"\n"));
}

/// A progress bar on standard error over `n` items named `what` ("workers", "layouts"), with the
/// time elapsed and an estimate of the time left; drawn only when standard error is a terminal.
pub fn progress_bar(n: usize, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(n as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{{bar:40}} {{pos}}/{{len}} {what}, {{elapsed}} elapsed, about {{eta}} left"
        ))
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

/// Whether standard output was closed when the program started (`>&-`). Rust's runtime puts
/// /dev/null on a closed standard descriptor before `main`, so every write would succeed and the
/// answer be lost; the descriptor is therefore looked at before that, by a constructor the
/// loader runs before the runtime's start (Linux: `/proc/self/fd/1` missing while
/// `/proc/self/fd` exists). Elsewhere it is never seen as closed.
static STDOUT_CLOSED_AT_START: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

#[cfg(target_os = "linux")]
extern "C" fn probe_stdout() {
    let closed = std::fs::symlink_metadata("/proc/self/fd").is_ok()
        && std::fs::read_link("/proc/self/fd/1").is_err();
    STDOUT_CLOSED_AT_START.store(closed, std::sync::atomic::Ordering::Relaxed);
}

// SAFETY: a plain function pointer in the initialiser list; the function touches only an
// atomic and makes two system calls through std (no runtime state it needs is uninitialised).
#[cfg(target_os = "linux")]
#[used]
#[unsafe(link_section = ".init_array")]
static PROBE_STDOUT: extern "C" fn() = probe_stdout;

/// Refuses to start work whose answer goes to a standard output that was closed.
pub fn check_stdout() -> anyhow::Result<()> {
    if STDOUT_CLOSED_AT_START.load(std::sync::atomic::Ordering::Relaxed) {
        return Err(bad(
            "standard output is closed: the answer would be lost (redirect it to a file, or to /dev/null to discard it)",
        ));
    }
    Ok(())
}

/// Maps a result to the exit code, printing the error. A closed standard output (a pipe whose
/// reader left) is an error too: the answer was not delivered.
pub fn exit(r: anyhow::Result<()>) -> ExitCode {
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let bad_input = e.chain().any(|c| {
                c.downcast_ref::<BadInput>().is_some() || c.downcast_ref::<ClosedOutput>().is_some()
            });
            say(format_args!("error: {e}"));
            if bad_input {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

/// Writes to standard output: a closed one, a pipe whose reader left, or any other failure (a
/// full disk) is reported with exit 2.
pub fn stdout(bytes: &[u8]) -> anyhow::Result<()> {
    write_stdout(|out| out.write_all(bytes))
}

/// Runs `write` on a buffered standard output and flushes it, with [`stdout`]'s errors.
fn write_stdout(write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> anyhow::Result<()> {
    check_stdout()?;
    let mut out = std::io::BufWriter::with_capacity(1 << 16, std::io::stdout().lock());
    let r = write(&mut out).and_then(|_| out.flush());
    match r {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Err(anyhow!(ClosedOutput)),
        Err(e) => Err(bad(format!("cannot write to standard output: {e}"))),
    }
}

/// Serialises to pretty JSON (serde) straight onto standard output, without a copy of the
/// document in memory (a plan of many cycles is hundreds of megabytes of JSON).
pub fn print_json(v: &impl serde::Serialize) -> anyhow::Result<()> {
    write_stdout(|out| {
        serde_json::to_writer_pretty(&mut *out, v).map_err(std::io::Error::from)?;
        out.write_all(b"\n")
    })
}

/// The outputs of one run, checked against its inputs, written all or none.
pub struct Outputs<'a> {
    set: OutputSet<'a>,
}

impl<'a> Outputs<'a> {
    pub fn new(inputs: &[&Path]) -> Self {
        let mut set = OutputSet::new();
        for p in inputs {
            set.input(p);
        }
        Outputs { set }
    }
    pub fn add(
        &mut self,
        what: &str,
        path: &Option<PathBuf>,
        bytes: impl FnOnce() -> anyhow::Result<Vec<u8>>,
    ) -> anyhow::Result<()> {
        if let Some(p) = path {
            self.set.add(what, p, bytes()?);
        }
        Ok(())
    }
    /// An output written by `write` as it is produced, when the set is written.
    pub fn add_stream(
        &mut self,
        what: &str,
        path: &Option<PathBuf>,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()> + 'a,
    ) {
        if let Some(p) = path {
            self.set.add_stream(what, p, write);
        }
    }
    /// Checks every output before the (possibly long) work starts.
    pub fn precheck(paths: &[(&str, &Option<PathBuf>)], inputs: &[&Path]) -> anyhow::Result<()> {
        let mut set = OutputSet::new();
        for p in inputs {
            set.input(p);
        }
        for (what, p) in paths {
            if let Some(p) = p {
                set.add(what, p, Vec::new());
            }
        }
        set.check().map(|_| ()).map_err(|e| bad(e.to_string()))
    }
    pub fn write(self) -> anyhow::Result<()> {
        self.set.write_all().map_err(|e| bad(e.to_string()))
    }
}

/// Options shared by `plan`, `compare` and `sweep`.
#[derive(clap::Args, Clone)]
pub struct AssessArgs {
    /// Plan once for the whole task and hold the postures (no re-planning as capacity falls).
    #[arg(long)]
    pub no_adapt: bool,
    /// Minimise fatigue only (no joint-range discomfort term, no step or asymmetry cost); the
    /// acceptable posture zones stay (off with --no-zones).
    #[arg(long)]
    pub fatigue_only: bool,
    /// Leave the postures free of ISO 11226 / EN 1005-4's acceptable zones (the unconstrained
    /// optimum, for comparison).
    #[arg(long)]
    pub no_zones: bool,
    /// Leave every phase's head free instead of looking at its work (for comparison).
    #[arg(long)]
    pub no_gaze: bool,
    /// Write the result as one JSON document on standard output.
    #[arg(long)]
    pub json: bool,
    /// Also write a self-contained HTML report.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Capacity floor for the work/rest advice (fraction of MVC, strictly between 0 and 1).
    #[arg(long, default_value_t = posture_opt::assess::rest::DEFAULT_CAPACITY_FLOOR, value_parser = parse_floor, allow_negative_numbers = true)]
    pub capacity_floor: f64,
    /// The QP solver's gap and feasibility tolerance (1e-12 to 1e-4; default 1e-9). A plan, or a
    /// ranking, that changes with it hinges on the solver's numerical path, not on the task.
    #[arg(long, value_parser = parse_qp_tolerance, allow_hyphen_values = true)]
    pub qp_tolerance: Option<f64>,
}

fn parse_qp_tolerance(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(t) if t.is_finite() && (1e-12..=1e-4).contains(&t) => Ok(t),
        _ => Err(format!("must be a number from 1e-12 to 1e-4, got '{s}'")),
    }
}

fn parse_floor(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(f) if f.is_finite() && f > 0.0 && f < 1.0 => Ok(f),
        _ => Err(format!("must be a number between 0 and 1, got '{s}'")),
    }
}

impl AssessArgs {
    pub fn plan_options(&self) -> posture_opt::plan::PlanOptions {
        let mut opts = posture_opt::plan::PlanOptions {
            adapt: !self.no_adapt,
            fatigue_only: self.fatigue_only,
            zones: !self.no_zones,
            gaze: !self.no_gaze,
            ..Default::default()
        };
        if let Some(t) = self.qp_tolerance {
            opts.sqp.precision = posture_opt::plan::qp::QpPrecision {
                tol_gap: t,
                tol_feas: t,
            };
        }
        opts
    }
}

/// Parses `--sex`.
pub fn parse_sex(s: &str) -> Result<posture_opt::body::Sex, String> {
    s.parse()
}
