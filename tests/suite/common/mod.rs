//! Shared by the command-line tests: run the binary (with a time limit, standard input, a working
//! directory), check the exit-code contract, and scan outputs for non-finite numbers.
//!
//! The contract (src/bin/posture-opt/main.rs): exit 0 = ok, 2 = bad input with a message naming
//! the file and the field or line, 1 = internal failure; never a panic, never a signal.
#![allow(dead_code)]

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The binary under test.
pub fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_posture-opt")
}

/// The package root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A path under the package root, as a string.
pub fn rel(p: &str) -> String {
    root().join(p).display().to_string()
}

/// Runs `posture-opt ARGS` in the package root: (exit code, stdout, stderr). A run killed by a
/// signal gives -1.
pub fn run(args: &[&str]) -> (i32, String, String) {
    let o = Run::new(args).go();
    (o.code.unwrap_or(-1), o.stdout_text(), o.stderr.clone())
}

/// What one run did.
#[derive(Debug, Clone)]
pub struct Out {
    /// Exit code; `None` when killed by a signal or by the time limit.
    pub code: Option<i32>,
    pub stdout: Vec<u8>,
    pub stderr: String,
    pub elapsed: Duration,
    pub timed_out: bool,
    /// Peak resident memory \[kB\] seen while it ran (Linux: VmHWM, polled), if known.
    pub peak_rss_kb: Option<u64>,
    /// What was run, for messages.
    pub what: String,
}

impl Out {
    pub fn stdout_text(&self) -> String {
        String::from_utf8_lossy(&self.stdout).into_owned()
    }

    /// Standard output as one JSON document (panics with the context when it is not).
    pub fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.stdout).unwrap_or_else(|e| {
            panic!(
                "{}: standard output is not one JSON document ({e}):\n{}",
                self.what,
                truncate(&self.stdout_text(), 2000)
            )
        })
    }

    /// Exit 0, no panic; the stdout text scanned for non-finite numbers.
    pub fn ok(&self) -> &Self {
        assert!(
            !self.timed_out,
            "{}: timed out after {:?}",
            self.what, self.elapsed
        );
        assert_eq!(
            self.code,
            Some(0),
            "{}: expected exit 0\nstderr: {}",
            self.what,
            truncate(&self.stderr, 3000)
        );
        assert_no_panic(self);
        let bad = scan_text(&self.stdout_text());
        assert!(
            bad.is_empty(),
            "{}: non-finite or absurd numbers in the output: {bad:?}",
            self.what
        );
        self
    }

    /// Exit 2 with a message on standard error that contains every one of `needles`.
    pub fn bad(&self, needles: &[&str]) -> &Self {
        assert!(
            !self.timed_out,
            "{}: timed out after {:?}",
            self.what, self.elapsed
        );
        assert_eq!(
            self.code,
            Some(2),
            "{}: expected exit 2\nstdout: {}\nstderr: {}",
            self.what,
            truncate(&self.stdout_text(), 2000),
            truncate(&self.stderr, 2000)
        );
        assert_no_panic(self);
        assert!(
            self.stderr.trim_start().starts_with("error:") || self.stderr.contains("error:"),
            "{}: exit 2 without an error message: {}",
            self.what,
            truncate(&self.stderr, 2000)
        );
        for n in needles {
            assert!(
                self.stderr.contains(n),
                "{}: the message does not name '{n}':\n{}",
                self.what,
                truncate(&self.stderr, 3000)
            );
        }
        self
    }
}

/// No panic, no abort, no signal.
pub fn assert_no_panic(o: &Out) {
    assert!(
        !o.stderr.contains("panicked") && !o.stderr.contains("RUST_BACKTRACE"),
        "{}: panicked:\n{}",
        o.what,
        truncate(&o.stderr, 3000)
    );
    assert!(
        o.code.is_some() || o.timed_out,
        "{}: killed by a signal (abort, stack overflow?):\n{}",
        o.what,
        truncate(&o.stderr, 3000)
    );
}

pub fn truncate(s: &str, n: usize) -> String {
    if s.len() <= n {
        return s.to_string();
    }
    let mut end = n;
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}… ({} bytes in all)", &s[..end], s.len())
}

/// A run being set up.
pub struct Run {
    args: Vec<String>,
    cwd: PathBuf,
    stdin: Option<Vec<u8>>,
    stdout_to: Option<std::fs::File>,
    timeout: Duration,
    /// Read this many bytes of standard output, then close it (a reader that went away).
    close_stdout_after: Option<usize>,
}

impl Run {
    pub fn new<S: AsRef<str>>(args: &[S]) -> Self {
        Run {
            args: args.iter().map(|a| a.as_ref().to_string()).collect(),
            cwd: root(),
            stdin: None,
            stdout_to: None,
            timeout: Duration::from_secs(600),
            close_stdout_after: None,
        }
    }
    pub fn cwd(mut self, dir: &Path) -> Self {
        self.cwd = dir.to_path_buf();
        self
    }
    pub fn stdin(mut self, bytes: impl Into<Vec<u8>>) -> Self {
        self.stdin = Some(bytes.into());
        self
    }
    /// Standard output goes to this file (e.g. /dev/full).
    pub fn stdout_file(mut self, f: std::fs::File) -> Self {
        self.stdout_to = Some(f);
        self
    }
    pub fn timeout(mut self, t: Duration) -> Self {
        self.timeout = t;
        self
    }
    pub fn close_stdout_after(mut self, n: usize) -> Self {
        self.close_stdout_after = Some(n);
        self
    }

    pub fn go(self) -> Out {
        let what = format!("posture-opt {}", describe_args(&self.args));
        let mut cmd = Command::new(bin());
        cmd.current_dir(&self.cwd)
            .args(&self.args)
            .env_remove("RUST_BACKTRACE")
            .stdin(if self.stdin.is_some() {
                Stdio::piped()
            } else {
                Stdio::null()
            })
            .stderr(Stdio::piped());
        match self.stdout_to {
            Some(f) => cmd.stdout(Stdio::from(f)),
            None => cmd.stdout(Stdio::piped()),
        };
        let start = Instant::now();
        let mut child = cmd.spawn().expect("spawn posture-opt");
        let stdin_thread = self.stdin.map(|bytes| {
            let mut w = child.stdin.take().unwrap();
            std::thread::spawn(move || {
                let _ = w.write_all(&bytes);
            })
        });
        let close_after = self.close_stdout_after;
        let out_thread = child.stdout.take().map(|mut r| {
            std::thread::spawn(move || {
                let mut buf = Vec::new();
                match close_after {
                    Some(n) => {
                        let mut b = vec![0u8; n];
                        let _ = r.read_exact(&mut b);
                        buf.extend_from_slice(&b);
                        drop(r);
                    }
                    None => {
                        let _ = r.read_to_end(&mut buf);
                    }
                }
                buf
            })
        });
        let mut err = child.stderr.take().unwrap();
        let err_thread = std::thread::spawn(move || {
            // bounded: a runaway error message must not exhaust the test's memory
            let mut buf = Vec::new();
            let _ = (&mut err).take(16 << 20).read_to_end(&mut buf);
            let _ = std::io::copy(&mut err, &mut std::io::sink());
            buf
        });
        let mut timed_out = false;
        let mut peak_rss_kb = None;
        let status_path = format!("/proc/{}/status", child.id());
        let status = loop {
            if let Some(hwm) = vm_hwm_kb(&status_path) {
                peak_rss_kb = Some(hwm.max(peak_rss_kb.unwrap_or(0)));
            }
            if let Some(s) = child.try_wait().expect("wait") {
                break s;
            }
            if start.elapsed() > self.timeout {
                timed_out = true;
                let _ = child.kill();
                break child.wait().expect("wait");
            }
            std::thread::sleep(Duration::from_millis(5));
        };
        let elapsed = start.elapsed();
        if let Some(t) = stdin_thread {
            let _ = t.join();
        }
        let stdout = out_thread.map(|t| t.join().unwrap()).unwrap_or_default();
        let stderr = String::from_utf8_lossy(&err_thread.join().unwrap()).into_owned();
        Out {
            code: if timed_out { None } else { status.code() },
            stdout,
            stderr,
            elapsed,
            timed_out,
            peak_rss_kb,
            what,
        }
    }
}

/// VmHWM (peak resident set) of a running process from /proc \[kB\].
fn vm_hwm_kb(status_path: &str) -> Option<u64> {
    let s = std::fs::read_to_string(status_path).ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn describe_args(args: &[String]) -> String {
    args.iter()
        .map(|a| {
            if a.len() > 120 {
                format!("<{} bytes>", a.len())
            } else {
                a.clone()
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Non-finite or absurd numbers in text (a table, CSV, HTML, JSON): `inf`, `NaN`, `infinity`
/// as words, and numbers of magnitude 1e300 or more (1.8e308 is f64::MAX, a common sentinel).
pub fn scan_text(s: &str) -> Vec<String> {
    let mut bad = Vec::new();
    for tok in s.split(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '.' | '+' | '-' | '_')))
    {
        if tok.is_empty() {
            continue;
        }
        let t = tok.trim_start_matches(['+', '-']).to_ascii_lowercase();
        let t = t.trim_end_matches('.');
        if matches!(t, "inf" | "infinity" | "nan") {
            bad.push(tok.to_string());
            continue;
        }
        if (tok.as_bytes()[0].is_ascii_digit() || tok.starts_with(['-', '+', '.']))
            && let Ok(x) = tok.trim_end_matches('.').parse::<f64>()
            && (!x.is_finite() || x.abs() >= 1e300)
        {
            bad.push(truncate(tok, 40));
        }
        if bad.len() > 20 {
            break;
        }
    }
    bad
}

/// Keys whose value may be null (Rust `Option` fields and schema defaults); any other null in a
/// JSON output is a number that was NaN or infinite (serde_json writes those as null).
pub const NULLABLE_KEYS: &[&str] = &[
    "binding",
    "retried_from",
    "angles",
    "back_compression_max_n",
    "back_compression_phase",
    "balance_margin_m",
    "beyond_reach_m",
    "centre_of_pressure_m",
    "cli",
    "closest",
    "composite",
    "contribution",
    "cycle_s",
    "default",
    "destination",
    "deviation",
    "every_s",
    "evidence",
    "exhausted_in_variants",
    "exhaustion",
    "feet",
    "gaze_m",
    "area_m",
    "fi_li",
    "fi_lifting_index",
    "first_to_give_out",
    "floor",
    "fm_previous_cumulative",
    "ground",
    "hand_height_m",
    "left_foot_share",
    "lifting",
    "lifting_index",
    "lifting_outside_limits",
    "uncontrolled_destination_h_cm",
    "low_back",
    "max_group",
    "max_load_kg",
    "max_load_phase",
    "measured",
    "met_min",
    "min_balance_margin_m",
    "min_capacity_at_recommended",
    "minutes_to_exhaustion",
    "name",
    "object",
    "reba",
    "reba_max",
    "rest_closest",
    "rest_feet",
    "rest_needed_s",
    "rest_s_per_cycle",
    "row",
    "rula",
    "rula_max",
    "rula_other_arm",
    "share_group",
    "st_li",
    "target_inside",
    "target_blocked",
    "hand_frames",
    "hand_position_m",
    "replan_every_s",
    "parameter_set",
    "problem",
    "worst_phase",
    "verdict_phase",
    "phase",
    "limit",
    "origin_phase",
    "destination_phase",
];

/// Non-finite numbers in a JSON document: nulls where a number belongs (serde_json writes NaN
/// and infinity as null), and numbers of magnitude 1e300 or more. Returns their paths.
pub fn scan_json(v: &serde_json::Value) -> Vec<String> {
    let mut bad = Vec::new();
    walk(v, "$", None, &mut bad);
    bad
}

fn walk(v: &serde_json::Value, path: &str, key: Option<&str>, bad: &mut Vec<String>) {
    use serde_json::Value;
    if bad.len() > 20 {
        return;
    }
    match v {
        Value::Null => {
            if !key.is_some_and(|k| NULLABLE_KEYS.contains(&k)) {
                bad.push(format!("{path} = null"));
            }
        }
        Value::Number(n) => {
            if let Some(x) = n.as_f64()
                && (!x.is_finite() || x.abs() >= 1e300)
            {
                bad.push(format!("{path} = {x}"));
            }
        }
        Value::String(_) | Value::Bool(_) => {}
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                // array elements inherit their key (e.g. hand_frames: [..., null])
                walk(x, &format!("{path}[{i}]"), key, bad);
            }
        }
        Value::Object(m) => {
            for (k, x) in m {
                walk(x, &format!("{path}.{k}"), Some(k), bad);
            }
        }
    }
}

/// Parses standard output as JSON (a document, or JSON lines) and scans every value.
pub fn assert_json_finite(o: &Out) {
    let text = o.stdout_text();
    let docs: Vec<serde_json::Value> = match serde_json::from_str(&text) {
        Ok(v) => vec![v],
        Err(_) => text
            .lines()
            .filter(|l| !l.trim().is_empty())
            .map(|l| {
                serde_json::from_str(l)
                    .unwrap_or_else(|e| panic!("{}: not JSON ({e}): {}", o.what, truncate(l, 500)))
            })
            .collect(),
    };
    for d in &docs {
        let bad = scan_json(d);
        assert!(
            bad.is_empty(),
            "{}: non-finite values in JSON: {bad:?}",
            o.what
        );
    }
}

/// A fresh temporary directory.
pub fn tempdir() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("posture-opt-test-")
        .tempdir()
        .expect("temporary directory")
}

/// Writes `text` to `dir/name` and returns the path.
pub fn write(dir: &Path, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
    let p = dir.join(name);
    if let Some(parent) = p.parent() {
        std::fs::create_dir_all(parent).unwrap();
    }
    std::fs::write(&p, text).unwrap();
    p
}

/// A quick one-phase task (planning takes seconds): the generated worker holds `load_kg` at a
/// comfortable target for `duration_s`, `cycles` times with `rest_s` of rest.
pub fn quick_task(name: &str, load_kg: f64, duration_s: f64, rest_s: f64, cycles: u64) -> String {
    format!(
        "name: {name}\nworker: {{sex: male, stature_m: 1.755, mass_kg: 78.0}}\nphases:\n  - {{name: hold, target_m: [0.35, -0.2, 1.0], load_kg: {load_kg}, duration_s: {duration_s}}}\nrest_s: {rest_s}\ncycles: {cycles}\n"
    )
}

/// Plan options for a held plan (no re-planning), with or without the three baselines.
pub fn held(baselines: bool) -> posture_opt::plan::PlanOptions {
    posture_opt::plan::PlanOptions {
        adapt: false,
        baselines,
        ..posture_opt::plan::PlanOptions::default()
    }
}

/// A shipped task (`tasks/NAME.yaml`) and its held plan with the default options and the three
/// baselines: planned once per test run and shared, for the tests that read the same plan without
/// changing its task or options (a plan is deterministic, tested in
/// `plan_truth::planning_is_deterministic`; the baselines are planned after it and change none of
/// it).
pub fn shipped_plan(name: &str) -> &'static (posture_opt::plan::Task, posture_opt::plan::Plan) {
    use std::collections::BTreeMap;
    use std::sync::{Mutex, OnceLock};
    type Cell = OnceLock<(posture_opt::plan::Task, posture_opt::plan::Plan)>;
    static PLANS: Mutex<BTreeMap<String, &'static Cell>> = Mutex::new(BTreeMap::new());
    let cell: &'static Cell = PLANS
        .lock()
        .unwrap()
        .entry(name.to_string())
        .or_insert_with(|| Box::leak(Box::new(OnceLock::new())));
    // planned outside the map's lock: other plans go on meanwhile, the same one waits
    cell.get_or_init(|| {
        let task =
            posture_opt::plan::Task::from_file(root().join(format!("tasks/{name}.yaml"))).unwrap();
        let plan = posture_opt::plan::plan_task_with(&task, held(true)).unwrap();
        (task, plan)
    })
}
