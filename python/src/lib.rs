//! `posture_opt._posture_opt`: the compiled part of the Python package.
//!
//! Each function mirrors a subcommand of the command line (`src/bin/posture-opt/`): same library
//! calls, same checks, same messages. Results cross into Python as the JSON the command line
//! prints with `--json` (serde_json), and big arrays as raw little-endian `float64` bytes; the
//! Python layer (`posture_opt/__init__.py`) turns them into dicts and numpy arrays. Long work
//! (planning, studies, evaluation) runs with the GIL released.
//!
//! Errors: `posture_opt.Error` (a `ValueError`) for bad input, with the command line's message;
//! `posture_opt.PlanningError` (a `RuntimeError`) when the optimiser fails (the command line's
//! exit code 1).

use nalgebra::Vector3;
use posture_opt::assess::assess;
use posture_opt::body::{BodyModel, GRAVITY_M_S2, Sex, Worker, statics_report};
use posture_opt::plan::task::{MAX_HAND_FORCE_N, MAX_LOAD_KG};
use posture_opt::plan::{PlanError, PlanOptions, Task, TaskError, TaskFile, plan_task_with};
use posture_opt::record::evaluator::{DEGREES_SUSPECT_RAD, RANGE_TOLERANCE_RAD};
use posture_opt::record::opensim::Mapping;
use posture_opt::record::run::{HOLD_RULE, RunError, Timeline};
use posture_opt::record::{self, Evaluation, Evaluator, Input, Sample};
use posture_opt::report::PlanDocument;
use posture_opt::study::compare::{self as cmp, CompareShard};
use posture_opt::study::shard::Shard;
use posture_opt::study::sweep::{self as swp, Sweep, SweepError, SweepShard};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pyo3::create_exception!(
    posture_opt,
    Error,
    PyValueError,
    "Bad input: a task file, recording, option or shard result the library refused. The message \
     is the command line's (it names the file, field, line or option)."
);
pyo3::create_exception!(
    posture_opt,
    PlanningError,
    PyRuntimeError,
    "The optimiser failed on a validated task (the command line's exit code 1)."
);

fn bad(msg: impl Into<String>) -> PyErr {
    Error::new_err(msg.into())
}

fn lib_err(e: impl std::fmt::Display) -> PyErr {
    bad(e.to_string())
}

fn plan_err(e: PlanError) -> PyErr {
    PlanningError::new_err(e.to_string())
}

fn sweep_err(e: SweepError) -> PyErr {
    match e {
        SweepError::Plan { .. } => PlanningError::new_err(e.to_string()),
        e => bad(e.to_string()),
    }
}

fn json(v: &impl serde::Serialize) -> PyResult<String> {
    serde_json::to_string(v)
        .map_err(|e| PyRuntimeError::new_err(format!("cannot serialise the result: {e}")))
}

/// Runs `f` on a pool of `threads` threads (the global pool when `None`).
fn with_threads<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> PyResult<T> {
    match threads {
        None => Ok(f()),
        Some(0) => Err(bad("threads must be at least 1")),
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| PyRuntimeError::new_err(format!("cannot start {n} threads: {e}")))?;
            Ok(pool.install(f))
        }
    }
}

/// Python's `json.loads(text)`.
fn loads<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

fn f64_bytes<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyBytes> {
    let mut b = Vec::with_capacity(v.len() * 8);
    for x in v {
        b.extend_from_slice(&x.to_le_bytes());
    }
    PyBytes::new(py, &b)
}

fn bytes_f64(what: &str, b: &[u8]) -> PyResult<Vec<f64>> {
    if b.len() % 8 != 0 {
        return Err(bad(format!(
            "{what}: {} bytes is not a whole number of float64 values",
            b.len()
        )));
    }
    Ok(b.chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect())
}

// ---------------------------------------------------------------------------------------------
// Tasks

/// A validated task, with the task file it came from (for studies that vary it).
struct TaskData {
    task: Task,
    file: Option<TaskFile>,
}

/// A validated task: body, worker, workstation, phases, fatigue parameters.
///
/// Make one with `posture_opt.load_task` (a file, a dict or YAML text) or
/// `posture_opt.default_setup` (the generated worker, for evaluating recordings).
#[pyclass(name = "Task", module = "posture_opt", frozen)]
struct PyTask {
    inner: Arc<TaskData>,
}

fn parse_task(text: &str, path: &Path) -> Result<(TaskFile, Task), TaskError> {
    let file = TaskFile::from_yaml_str(text, path)?;
    let task = Task::from_task_file(file.clone(), path)?;
    Ok((file, task))
}

fn task_obj(file: TaskFile, task: Task) -> PyTask {
    PyTask {
        inner: Arc::new(TaskData {
            task,
            file: Some(file),
        }),
    }
}

/// Reads and validates a task file (YAML).
#[pyfunction]
fn task_from_file(py: Python<'_>, path: PathBuf) -> PyResult<PyTask> {
    py.detach(|| {
        let p = path.display().to_string();
        let text = posture_opt::io::read_text(&path).map_err(|e| TaskError::Io {
            path: p,
            message: e.to_string(),
        })?;
        parse_task(&text, &path)
    })
    .map(|(f, t)| task_obj(f, t))
    .map_err(lib_err)
}

/// Parses and validates task YAML (or JSON); `path` names it in messages and locates a relative
/// `robot`.
#[pyfunction]
fn task_from_yaml(py: Python<'_>, text: String, path: PathBuf) -> PyResult<PyTask> {
    py.detach(|| parse_task(&text, &path))
        .map(|(f, t)| task_obj(f, t))
        .map_err(lib_err)
}

/// The set-up of an evaluation without a task file: the generated whole-body worker.
#[pyfunction]
#[pyo3(signature = (sex, stature_m, mass_kg, strength_percentile, parameters=None))]
fn default_setup(
    py: Python<'_>,
    sex: &str,
    stature_m: f64,
    mass_kg: f64,
    strength_percentile: f64,
    parameters: Option<String>,
) -> PyResult<PyTask> {
    let sex: Sex = sex.parse().map_err(|e: String| bad(format!("sex: {e}")))?;
    let worker = Worker {
        sex,
        stature_m,
        mass_kg,
        strength_percentile,
    };
    let task = py
        .detach(|| record::default_setup(worker, parameters.as_deref()))
        .map_err(lib_err)?;
    Ok(PyTask {
        inner: Arc::new(TaskData { task, file: None }),
    })
}

#[pymethods]
impl PyTask {
    /// The task's title.
    #[getter]
    fn name(&self) -> String {
        self.inner.task.name.clone()
    }
    /// The file (or the name given for a dict or YAML text).
    #[getter]
    fn path(&self) -> String {
        self.inner.task.path.display().to_string()
    }
    /// The URDF used (a path, or "generated from worker").
    #[getter]
    fn robot(&self) -> String {
        self.inner.task.robot.clone()
    }
    /// Joint names in q order.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.inner.task.joint_names()
    }
    /// Number of joint coordinates.
    #[getter]
    fn nq(&self) -> usize {
        self.inner.task.model.nq()
    }
    /// Half-joint ids (muscle groups) in order, as in results' `half_joint_ids`.
    #[getter]
    fn half_joint_ids(&self) -> Vec<String> {
        self.inner.task.half_joint_ids()
    }
    /// The muscle groups in words, ordered like `half_joint_ids`.
    #[getter]
    fn groups(&self) -> Vec<String> {
        self.inner
            .task
            .half_joints
            .iter()
            .map(|h| h.group.clone())
            .collect()
    }
    /// Phase names of one cycle, in order.
    #[getter]
    fn phases(&self) -> Vec<String> {
        self.inner
            .task
            .phases
            .iter()
            .map(|p| p.name.clone())
            .collect()
    }
    #[getter]
    fn cycles(&self) -> u32 {
        self.inner.task.cycles
    }
    /// Rest at the end of each cycle [s].
    #[getter]
    fn rest_s(&self) -> f64 {
        self.inner.task.rest_s
    }
    /// Length of one cycle [s].
    #[getter]
    fn cycle_s(&self) -> f64 {
        self.inner.task.cycle_s()
    }
    /// Planned duration of the whole task [s].
    #[getter]
    fn duration_s(&self) -> f64 {
        self.inner.task.duration_s()
    }
    /// Gravity [m/s²], world frame.
    #[getter]
    fn gravity_m_s2(&self) -> [f64; 3] {
        let g = self.inner.task.gravity_m_s2;
        [g.x, g.y, g.z]
    }
    /// Hand frames (right, left); None for a hand the body lacks.
    #[getter]
    fn hand_frames(&self) -> [Option<String>; 2] {
        self.inner
            .task
            .hand_links
            .clone()
            .map(|h| h.map(|(_, n)| n))
    }
    /// Whether the body stands on its feet.
    #[getter]
    fn standing(&self) -> bool {
        self.inner.task.stance.is_some()
    }
    /// The fatigue parameter set used.
    #[getter]
    fn fatigue_parameters(&self) -> String {
        self.inner.task.fatigue_choice.set.clone()
    }
    /// The worker: sex, stature_m, mass_kg, strength_percentile.
    #[getter]
    fn worker<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        loads(py, &json(&self.inner.task.worker)?)
    }
    /// The task file as a dict (as written, defaults filled in); None for a set-up made by
    /// `default_setup`. `load_task(task.to_dict(), path=task.path)` makes the same task.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.inner
            .file
            .as_ref()
            .map(|f| loads(py, &json(f)?))
            .transpose()
    }
    fn __repr__(&self) -> String {
        let t = &self.inner.task;
        format!(
            "<posture_opt.Task '{}' ({}): {} phases x {} cycles, {} joints, {} half-joints>",
            t.name,
            t.path.display(),
            t.phases.len(),
            t.cycles,
            t.model.nq(),
            t.half_joints.len()
        )
    }
}

// ---------------------------------------------------------------------------------------------
// Planning and studies

fn plan_options(adapt: bool, fatigue_only: bool, capacity_floor: f64) -> PyResult<PlanOptions> {
    if !(capacity_floor.is_finite() && capacity_floor > 0.0 && capacity_floor < 1.0) {
        return Err(bad(format!(
            "capacity_floor: must be a number between 0 and 1, got '{capacity_floor}'"
        )));
    }
    Ok(PlanOptions {
        adapt,
        fatigue_only,
        ..Default::default()
    })
}

fn shard_of(shard: Option<&str>) -> PyResult<Option<Shard>> {
    shard
        .map(|s| s.parse::<Shard>().map_err(|e| bad(format!("shard: {e}"))))
        .transpose()
}

/// Plans a task and assesses the plan: the `plan --json` document.
#[pyfunction]
#[pyo3(signature = (task, adapt=true, fatigue_only=false, capacity_floor=0.7, zones=true, gaze=true))]
fn plan(
    py: Python<'_>,
    task: &PyTask,
    adapt: bool,
    fatigue_only: bool,
    capacity_floor: f64,
    zones: bool,
    gaze: bool,
) -> PyResult<String> {
    let mut opts = plan_options(adapt, fatigue_only, capacity_floor)?;
    opts.zones = zones;
    opts.gaze = gaze;
    let data = task.inner.clone();
    py.detach(move || {
        let t = &data.task;
        let plan = plan_task_with(t, opts).map_err(plan_err)?;
        let assessment = assess(t, &plan, capacity_floor);
        json(&PlanDocument {
            plan: &plan,
            assessment: &assessment,
        })
    })
}

/// At most this many layouts in one comparison (as the command line).
const MAX_LAYOUTS: usize = 1000;

/// The tasks again, from their files (the study functions take a slice of tasks).
fn rebuild(tasks: &[Arc<TaskData>]) -> PyResult<Vec<Task>> {
    tasks
        .iter()
        .map(|d| {
            let Some(f) = &d.file else {
                return Err(bad(format!(
                    "{}: a study needs a task loaded from a task file, a dict or YAML text",
                    d.task.path.display()
                )));
            };
            Task::from_task_file(f.clone(), &d.task.path).map_err(lib_err)
        })
        .collect()
}

/// Compares layouts: the `compare --json` document, or with `shard` ("i/n") one shard's result.
#[pyfunction]
#[pyo3(signature = (tasks, names, adapt=true, fatigue_only=false, capacity_floor=0.7, shard=None, threads=None))]
#[allow(clippy::too_many_arguments)]
fn compare(
    py: Python<'_>,
    tasks: Vec<PyRef<'_, PyTask>>,
    names: Vec<String>,
    adapt: bool,
    fatigue_only: bool,
    capacity_floor: f64,
    shard: Option<&str>,
    threads: Option<usize>,
) -> PyResult<String> {
    let opts = plan_options(adapt, fatigue_only, capacity_floor)?;
    let shard = shard_of(shard)?;
    if tasks.is_empty() {
        return Err(bad("compare needs at least one layout"));
    }
    if names.len() != tasks.len() {
        return Err(bad(format!(
            "{} names for {} layouts",
            names.len(),
            tasks.len()
        )));
    }
    if shard.is_none() && tasks.len() > MAX_LAYOUTS {
        return Err(bad(format!(
            "at most {MAX_LAYOUTS} layouts per comparison (use shard to split)"
        )));
    }
    let data: Vec<Arc<TaskData>> = tasks.iter().map(|t| t.inner.clone()).collect();
    drop(tasks);
    py.detach(move || {
        let tasks = rebuild(&data)?;
        with_threads(threads, || match shard {
            Some(s) => cmp::compare_shard(&names, &tasks, s, opts, capacity_floor, &|| {})
                .map_err(plan_err)
                .and_then(|r| json(&r)),
            None => cmp::compare(&names, &tasks, opts, capacity_floor, &|| {})
                .map_err(plan_err)
                .and_then(|(c, _)| json(&c)),
        })?
    })
}

/// Merges compare shard results (name, JSON text) into the `compare --json` document.
#[pyfunction]
fn merge_compare(py: Python<'_>, shards: Vec<(String, String)>) -> PyResult<String> {
    py.detach(move || {
        let mut parsed = Vec::with_capacity(shards.len());
        for (name, text) in shards {
            let s: CompareShard = serde_json::from_str(&text)
                .map_err(|e| bad(format!("{name}: not a compare shard result: {e}")))?;
            parsed.push((name, s));
        }
        let c = cmp::merge(&parsed).map_err(lib_err)?;
        json(&c)
    })
}

/// Largest sample (as the command line).
const MAX_SAMPLE: usize = 100_000;

/// One task for a population: the `sweep --json` document, or with `shard` one shard's result.
#[pyfunction]
#[pyo3(signature = (task, sample=None, seed=1, adapt=true, fatigue_only=false, capacity_floor=0.7, shard=None, threads=None))]
#[allow(clippy::too_many_arguments)]
fn sweep(
    py: Python<'_>,
    task: &PyTask,
    sample: Option<usize>,
    seed: u64,
    adapt: bool,
    fatigue_only: bool,
    capacity_floor: f64,
    shard: Option<&str>,
    threads: Option<usize>,
) -> PyResult<String> {
    let opts = plan_options(adapt, fatigue_only, capacity_floor)?;
    let shard_given = shard_of(shard)?;
    let data = task.inner.clone();
    let Some(file) = data.file.clone() else {
        return Err(bad(format!(
            "{}: a sweep needs a task loaded from a task file, a dict or YAML text",
            data.task.path.display()
        )));
    };
    let (members, population, sampled) = match sample {
        Some(0) => return Err(bad("sample must be at least 1")),
        Some(n) if n > MAX_SAMPLE => {
            return Err(bad(format!(
                "sample {n}: at most {MAX_SAMPLE} workers (use shard to spread a larger study)"
            )));
        }
        Some(n) => (
            swp::sampled_population(n, seed),
            format!("sampled n={n} seed={seed}"),
            true,
        ),
        None => (
            swp::standard_population(),
            "P5/P50/P95 women and men".to_string(),
            false,
        ),
    };
    py.detach(move || {
        let path = data.task.path.clone();
        let shard = shard_given.unwrap_or(Shard::ALL);
        let workers = with_threads(threads, || {
            swp::sweep_members(&file, &path, &members, shard, opts, capacity_floor, &|_| {})
        })?
        .map_err(sweep_err)?;
        if shard_given.is_some() {
            return json(&SweepShard::new(
                &file,
                &path,
                shard,
                population,
                sampled,
                opts,
                capacity_floor,
                members.len(),
                workers,
            ));
        }
        let s = Sweep::from_outcomes(
            &file.name,
            &population,
            sampled,
            opts.adapt,
            capacity_floor,
            workers,
        );
        json(&s)
    })
}

/// Merges sweep shard results (name, JSON text) into the `sweep --json` document.
#[pyfunction]
fn merge_sweep(py: Python<'_>, shards: Vec<(String, String)>) -> PyResult<String> {
    py.detach(move || {
        let mut parsed = Vec::with_capacity(shards.len());
        for (name, text) in shards {
            let s: SweepShard = serde_json::from_str(&text)
                .map_err(|e| bad(format!("{name}: not a sweep shard result: {e}")))?;
            parsed.push((name, s));
        }
        let s = swp::merge(&parsed).map_err(lib_err)?;
        json(&s)
    })
}

// ---------------------------------------------------------------------------------------------
// Evaluating recorded work

fn check_loads(hand_load_kg: [f64; 2]) -> PyResult<()> {
    for (name, v) in [
        ("right_load_kg", hand_load_kg[0]),
        ("left_load_kg", hand_load_kg[1]),
    ] {
        if !(v.is_finite() && (0.0..=MAX_LOAD_KG).contains(&v)) {
            return Err(bad(format!("{name} must be 0..{MAX_LOAD_KG} kg, got {v}")));
        }
    }
    Ok(())
}

fn run_err(e: RunError) -> PyErr {
    bad(e.to_string())
}

/// Evaluates a recording file (CSV, or OpenSim .mot/.sto with a mapping): the `evaluate --json`
/// document.
#[pyfunction]
#[pyo3(signature = (task, recording, mapping=None, degrees=false, hand_load_kg=(0.0, 0.0)))]
fn evaluate_file(
    py: Python<'_>,
    task: &PyTask,
    recording: PathBuf,
    mapping: Option<PathBuf>,
    degrees: bool,
    hand_load_kg: (f64, f64),
) -> PyResult<String> {
    let hand_load_kg = [hand_load_kg.0, hand_load_kg.1];
    check_loads(hand_load_kg)?;
    let opts = record::Options {
        degrees,
        hand_load_kg,
    };
    let data = task.inner.clone();
    py.detach(move || {
        let task = &data.task;
        let rec = &recording;
        let name = rec.display().to_string();
        posture_opt::io::check_input(rec).map_err(lib_err)?;
        let file = std::fs::File::open(rec).map_err(|e| bad(format!("{name}: {e}")))?;
        let reader = std::io::BufReader::with_capacity(1 << 16, file);
        let ext = rec.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        let input = if ext == "mot" || ext == "sto" {
            let Some(mp) = &mapping else {
                return Err(bad(format!(
                    "{name}: an OpenSim recording needs a mapping (the coordinates' names, signs and offsets on the body's joints); for the Rajagopal (2016) model: data/opensim/rajagopal2016.mapping.yaml"
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
            if mapping.is_some() {
                return Err(bad("mapping applies to OpenSim .mot/.sto recordings only"));
            }
            Input::Csv { reader, name: name.clone() }
        };
        let ev = record::evaluate(task, input, &opts, None).map_err(run_err)?;
        json(&ev)
    })
}

/// The evaluation of one task's samples, one at a time (owns the task the evaluator borrows).
type Ev<'a> = Evaluator<'a>;
self_cell::self_cell!(
    struct EvalCell {
        owner: Arc<TaskData>,
        #[covariant]
        dependent: Ev,
    }
);

/// An evaluator with what `evaluate` adds around it: the thinned timeline, the per-sample checks.
struct Run {
    cell: EvalCell,
    source: String,
    degrees: bool,
    hand_load_kg: [f64; 2],
    timeline: Timeline,
    last_t_s: Option<f64>,
    pushed: u64,
}

/// The sample's hand forces: given ones, or the constant loads.
type Forces = [Option<[f64; 3]>; 2];

impl Run {
    fn new(data: Arc<TaskData>, source: String, degrees: bool, hand_load_kg: [f64; 2]) -> Self {
        Run {
            cell: EvalCell::new(data, |d| Evaluator::new(&d.task)),
            source,
            degrees,
            hand_load_kg,
            timeline: Timeline::default(),
            last_t_s: None,
            pushed: 0,
        }
    }

    fn task(&self) -> &Task {
        &self.cell.borrow_owner().task
    }

    fn ev(&self) -> &Evaluator<'_> {
        self.cell.borrow_dependent()
    }

    /// Checks and takes the next sample; returns the number of new exhaustion events. A refused
    /// sample leaves the state as it was.
    fn push(&mut self, t_s: f64, q: &[f64], forces: Forces) -> Result<usize, String> {
        let task = self.task();
        let nq = task.model.nq();
        let where_ = format!("{}: sample {} (t = {t_s} s)", self.source, self.pushed);
        if q.len() != nq {
            return Err(format!(
                "{where_}: a sample needs {nq} joint angles, got {}",
                q.len()
            ));
        }
        if !t_s.is_finite() || q.iter().any(|v| !v.is_finite()) {
            return Err(format!("{where_}: every value must be finite"));
        }
        if let Some(t0) = self.last_t_s {
            if t_s <= t0 {
                return Err(format!(
                    "{where_}: time {t_s} does not increase (previous sample at {t0})"
                ));
            }
        }
        let g = task.gravity_m_s2;
        let mut s = Sample::zeros(nq);
        s.t_s = t_s;
        for (k, v) in q.iter().enumerate() {
            s.q_rad[k] = if self.degrees { v.to_radians() } else { *v };
        }
        for h in 0..2 {
            s.hand_force_n[h] = match forces[h] {
                Some(f) => {
                    for v in f {
                        if !v.is_finite() {
                            return Err(format!("{where_}: every value must be finite"));
                        }
                        if v.abs() > MAX_HAND_FORCE_N {
                            return Err(format!(
                                "{where_}: a hand force must be within ±{MAX_HAND_FORCE_N} N, got {v}"
                            ));
                        }
                    }
                    Vector3::from(f)
                }
                None => g * self.hand_load_kg[h],
            };
        }
        // the range check of `evaluate` (counts samples outside the range, refuses degrees)
        let model = &task.model;
        for (k, &v) in s.q_rad.iter().enumerate() {
            let j = model.q_joint(k);
            if !matches!(j.kind, posture_opt::body::JointKind::Revolute) {
                continue;
            }
            let beyond = (j.lower_rad - v).max(v - j.upper_rad);
            let as_deg = v.to_radians();
            let fits_as_deg = as_deg >= j.lower_rad - RANGE_TOLERANCE_RAD
                && as_deg <= j.upper_rad + RANGE_TOLERANCE_RAD;
            if beyond > DEGREES_SUSPECT_RAD && fits_as_deg {
                return Err(format!(
                    "{where_}: {} = {v} rad lies far outside its range [{:.2}, {:.2}] rad, and {v}° would fit: are the angles in degrees? Pass degrees=True",
                    j.name, j.lower_rad, j.upper_rad
                ));
            }
        }
        let i = self.pushed;
        let Run { cell, timeline, .. } = self;
        let new = cell.with_dependent_mut(|_, ev| {
            // counts a sample outside the range; the refusal was checked above
            ev.check_range(&s.q_rad)
                .map_err(|(k, v)| format!("{where_}: q[{k}] = {v} looks like degrees"))?;
            let new = ev.push(&s).map_err(|e| format!("{where_}: {e}"))?;
            timeline.push(i, t_s, ev);
            Ok::<usize, String>(new)
        })?;
        self.last_t_s = Some(t_s);
        self.pushed += 1;
        Ok(new)
    }

    /// The `evaluate --json` document of the samples so far.
    fn document(&self) -> Result<Evaluation, String> {
        if self.pushed == 0 {
            return Err(format!("{}: no samples", self.source));
        }
        Ok(Evaluation::new(
            &self.source,
            self.task(),
            self.ev(),
            self.pushed,
            self.timeline.clone(),
        ))
    }
}

/// Evaluates samples given as arrays (float64 bytes: `t` n, `q` n×nq row-major, `force` n×2×3
/// when `force_given` says a hand's forces are given). Returns the `evaluate --json` document and
/// the per-sample capacity, U and load (n×nh each, float64 bytes).
#[pyfunction]
#[pyo3(signature = (task, t, q, force, force_given, degrees=false, hand_load_kg=(0.0, 0.0), source="arrays".to_string()))]
#[allow(clippy::too_many_arguments)]
fn evaluate_arrays<'py>(
    py: Python<'py>,
    task: &PyTask,
    t: &[u8],
    q: &[u8],
    force: &[u8],
    force_given: (bool, bool),
    degrees: bool,
    hand_load_kg: (f64, f64),
    source: String,
) -> PyResult<(
    String,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
)> {
    let hand_load_kg = [hand_load_kg.0, hand_load_kg.1];
    check_loads(hand_load_kg)?;
    let t = bytes_f64("t", t)?;
    let q = bytes_f64("q", q)?;
    let force = bytes_f64("force", force)?;
    let data = task.inner.clone();
    let nq = data.task.model.nq();
    let nh = data.task.half_joints.len();
    let n = t.len();
    if q.len() != n * nq {
        return Err(bad(format!(
            "q: expected {n} x {nq} values (samples x joints), got {}",
            q.len()
        )));
    }
    let any_force = force_given.0 || force_given.1;
    if any_force && force.len() != n * 6 {
        return Err(bad(format!(
            "force: expected {n} x 2 x 3 values, got {}",
            force.len()
        )));
    }
    let (doc, cap, u, load) = py.detach(move || {
        let mut run = Run::new(data, source, degrees, hand_load_kg);
        let (mut cap, mut u, mut load) = (
            Vec::with_capacity(n * nh),
            Vec::with_capacity(n * nh),
            Vec::with_capacity(n * nh),
        );
        for i in 0..n {
            let mut forces: Forces = [None, None];
            for (h, given) in [force_given.0, force_given.1].into_iter().enumerate() {
                if given {
                    let o = i * 6 + h * 3;
                    forces[h] = Some([force[o], force[o + 1], force[o + 2]]);
                }
            }
            run.push(t[i], &q[i * nq..(i + 1) * nq], forces)
                .map_err(bad)?;
            let ev = run.ev();
            cap.extend(ev.state.iter().map(|s| s.capacity));
            u.extend(ev.state.iter().map(|s| s.fatigue_u_min));
            load.extend_from_slice(&ev.loads);
        }
        let doc = run.document().map_err(bad)?;
        Ok::<_, PyErr>((json(&doc)?, cap, u, load))
    })?;
    Ok((
        doc,
        f64_bytes(py, &cap),
        f64_bytes(py, &u),
        f64_bytes(py, &load),
    ))
}

/// Live evaluation: samples pushed one at a time (the same code as `evaluate`, so both agree
/// exactly).
#[pyclass(name = "_Evaluator", module = "posture_opt")]
struct PyEvaluator {
    run: Run,
}

#[pymethods]
impl PyEvaluator {
    #[new]
    #[pyo3(signature = (task, degrees=false, hand_load_kg=(0.0, 0.0), source="stream".to_string()))]
    fn new(
        task: &PyTask,
        degrees: bool,
        hand_load_kg: (f64, f64),
        source: String,
    ) -> PyResult<Self> {
        let hand_load_kg = [hand_load_kg.0, hand_load_kg.1];
        check_loads(hand_load_kg)?;
        Ok(PyEvaluator {
            run: Run::new(task.inner.clone(), source, degrees, hand_load_kg),
        })
    }

    /// Takes one sample; returns the number of new exhaustion events.
    #[pyo3(signature = (t, q, right_force=None, left_force=None))]
    fn push(
        &mut self,
        t: f64,
        q: Vec<f64>,
        right_force: Option<[f64; 3]>,
        left_force: Option<[f64; 3]>,
    ) -> PyResult<usize> {
        self.run.push(t, &q, [right_force, left_force]).map_err(bad)
    }

    /// Takes many samples (float64 bytes as `evaluate_arrays`); returns the number of new
    /// exhaustion events.
    fn push_many(
        &mut self,
        t: &[u8],
        q: &[u8],
        force: &[u8],
        force_given: (bool, bool),
    ) -> PyResult<usize> {
        let t = bytes_f64("t", t)?;
        let q = bytes_f64("q", q)?;
        let force = bytes_f64("force", force)?;
        let nq = self.run.task().model.nq();
        let n = t.len();
        if q.len() != n * nq {
            return Err(bad(format!(
                "q: expected {n} x {nq} values (samples x joints), got {}",
                q.len()
            )));
        }
        if (force_given.0 || force_given.1) && force.len() != n * 6 {
            return Err(bad(format!(
                "force: expected {n} x 2 x 3 values, got {}",
                force.len()
            )));
        }
        let mut new = 0;
        for i in 0..n {
            let mut forces: Forces = [None, None];
            for (h, given) in [force_given.0, force_given.1].into_iter().enumerate() {
                if given {
                    let o = i * 6 + h * 3;
                    forces[h] = Some([force[o], force[o + 1], force[o + 2]]);
                }
            }
            new += self
                .run
                .push(t[i], &q[i * nq..(i + 1) * nq], forces)
                .map_err(bad)?;
        }
        Ok(new)
    }

    /// Capacity per half-joint now.
    fn capacity<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let v: Vec<f64> = self.run.ev().state.iter().map(|s| s.capacity).collect();
        f64_bytes(py, &v)
    }
    /// Fatigue index U [min] per half-joint now.
    fn fatigue_u_min<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let v: Vec<f64> = self
            .run
            .ev()
            .state
            .iter()
            .map(|s| s.fatigue_u_min)
            .collect();
        f64_bytes(py, &v)
    }
    /// Relative load per half-joint of the last sample (held until the next).
    fn load<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f64_bytes(py, &self.run.ev().loads)
    }
    /// The last `n` exhaustion events as JSON.
    fn last_events(&self, n: usize) -> PyResult<String> {
        let e = &self.run.ev().events;
        json(&e[e.len().saturating_sub(n)..].to_vec())
    }
    /// All exhaustion events as JSON.
    fn events(&self) -> PyResult<String> {
        json(&self.run.ev().events)
    }
    #[getter]
    fn samples(&self) -> u64 {
        self.run.pushed
    }
    #[getter]
    fn t_s(&self) -> Option<f64> {
        self.run.last_t_s
    }
    /// The `evaluate --json` document of the samples so far.
    fn document(&self) -> PyResult<String> {
        json(&self.run.document().map_err(bad)?)
    }
}

// ---------------------------------------------------------------------------------------------
// Statics

/// Holding torques of a body at a posture: the `statics --json` document. The body is a URDF
/// file (`robot`) or a task's body (`task`).
#[pyfunction]
#[pyo3(signature = (robot=None, task=None, frame=None, q=vec![], hand_load_kg=None, hand_force=None, gravity=None))]
#[allow(clippy::too_many_arguments)]
fn statics(
    py: Python<'_>,
    robot: Option<PathBuf>,
    task: Option<&PyTask>,
    frame: Option<String>,
    q: Vec<(String, f64)>,
    hand_load_kg: Option<f64>,
    hand_force: Option<[f64; 3]>,
    gravity: Option<[f64; 3]>,
) -> PyResult<String> {
    let data = task.map(|t| t.inner.clone());
    py.detach(move || {
        let loaded;
        let (model, origin, default_frame, default_gravity): (
            &BodyModel,
            String,
            Option<String>,
            Vector3<f64>,
        ) = match (&robot, &data) {
            (Some(_), Some(_)) => return Err(bad("give robot or task, not both")),
            (Some(r), None) => {
                loaded = BodyModel::from_urdf_file(r).map_err(lib_err)?;
                (&loaded, r.display().to_string(), None, GRAVITY_M_S2)
            }
            (None, Some(d)) => (
                &d.task.model,
                d.task.robot.clone(),
                d.task.hand_links[0].as_ref().map(|(_, n)| n.clone()),
                d.task.gravity_m_s2,
            ),
            (None, None) => return Err(bad("give a robot (URDF file) or a task")),
        };
        let Some(frame) = frame.or(default_frame) else {
            return Err(bad(
                "frame: give the link or joint whose origin is the hand point",
            ));
        };
        let gravity = match gravity {
            Some(g) => {
                for v in g {
                    if !(v.is_finite() && v.abs() <= 3.0 * 9.81) {
                        return Err(bad(format!(
                            "gravity: '{v}' is not a number within ±{}",
                            3.0 * 9.81
                        )));
                    }
                }
                let g = Vector3::from(g);
                if g.norm() > 3.0 * 9.81 {
                    return Err(bad("gravity: magnitude above 3 g"));
                }
                g
            }
            None => default_gravity,
        };
        let force = match (hand_load_kg, hand_force) {
            (Some(_), Some(_)) => return Err(bad("give hand_load_kg or hand_force, not both")),
            (Some(m), _) if !(m.is_finite() && (0.0..=1000.0).contains(&m)) => {
                return Err(bad(format!(
                    "hand_load_kg must be within 0..1000 kg, got {m}"
                )));
            }
            (Some(m), _) => gravity * m,
            (None, Some(f)) => {
                for v in f {
                    if !(v.is_finite() && v.abs() <= 1e4) {
                        return Err(bad(format!(
                            "hand_force: '{v}' is not a number within ±10000"
                        )));
                    }
                }
                Vector3::from(f)
            }
            (None, None) => Vector3::zeros(),
        };
        let mut seen: Vec<&str> = Vec::new();
        for (name, v) in &q {
            if !(v.is_finite() && v.abs() <= 1e3) {
                return Err(bad(format!("q: {name}: '{v}' is not a number of radians")));
            }
            if seen.contains(&name.as_str()) {
                return Err(bad(format!("q: joint '{name}' is given twice")));
            }
            seen.push(name);
        }
        let report = statics_report(model, &frame, &q, force, gravity)
            .map_err(|e| bad(format!("{origin}: {e}")))?;
        json(&report)
    })
}

/// Joint names of a URDF body in q order (the order of `q` arrays).
#[pyfunction]
fn urdf_joint_names(py: Python<'_>, robot: PathBuf) -> PyResult<Vec<String>> {
    py.detach(|| {
        let m = BodyModel::from_urdf_file(&robot).map_err(lib_err)?;
        Ok((0..m.nq()).map(|i| m.q_joint(i).name.clone()).collect())
    })
}

/// The JSON Schema of task files.
#[pyfunction]
fn task_schema() -> PyResult<String> {
    json(&posture_opt::schema::task_schema())
}

#[pymodule]
fn _posture_opt(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<Error>())?;
    m.add("PlanningError", py.get_type::<PlanningError>())?;
    m.add("HOLD_RULE", HOLD_RULE)?;
    m.add(
        "DEFAULT_CAPACITY_FLOOR",
        posture_opt::assess::rest::DEFAULT_CAPACITY_FLOOR,
    )?;
    m.add("RANKING_RULE", cmp::RANKING_RULE)?;
    m.add("MAX_LOAD_KG", MAX_LOAD_KG)?;
    m.add_class::<PyTask>()?;
    m.add_class::<PyEvaluator>()?;
    m.add_function(wrap_pyfunction!(task_from_file, m)?)?;
    m.add_function(wrap_pyfunction!(task_from_yaml, m)?)?;
    m.add_function(wrap_pyfunction!(default_setup, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(merge_compare, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(merge_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_file, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(statics, m)?)?;
    m.add_function(wrap_pyfunction!(task_schema, m)?)?;
    m.add_function(wrap_pyfunction!(urdf_joint_names, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
