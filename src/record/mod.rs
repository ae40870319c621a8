//! Recorded work: joint angles and hand loads over time, evaluated into a fatigue timeline,
//! offline (a file, streamed through in bounded memory) or live (one sample per line).
//!
//! **Hold rule** (zero-order hold): each sample's posture and hand loads hold from its time until
//! the next sample's. On receiving sample i+1 every half-joint holds the load computed from
//! sample i for `t(i+1) − t(i)` with the exact closed forms of the fatigue model, so any sampling
//! rate, irregular too, is exact for that rule. The state reported with a sample is the state at
//! its time (before its own load acts); the last sample's load acts for no time.
//!
//! **Body and muscle**: a task file gives the body (the generated worker or a URDF), the worker,
//! the stance and the fatigue parameters; its phases are not used. Without one, the generated
//! worker of [`default_setup`] is used. A standing body's floor reaction is split between the
//! feet as in planning ([`crate::body::stance`]), at the feet where the recording puts them.
//!
//! **Inputs**: CSV ([`csv_recording`]) and OpenSim `.mot`/`.sto` with a mapping file
//! ([`opensim`]).

pub mod csv_recording;
pub mod evaluator;
pub mod opensim;
pub mod run;

pub use evaluator::{Evaluator, ExhaustionEvent};
pub use run::{Evaluation, Input, Options, StreamLine, evaluate, stream};

use crate::plan::{Task, TaskError, TaskFile};
use nalgebra::Vector3;

/// One sample: time, posture, the force the environment applies on each hand (right, left).
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    pub t_s: f64,
    pub q_rad: Vec<f64>,
    pub hand_force_n: [Vector3<f64>; 2],
}

impl Sample {
    /// A sample at rest posture zero for a body with `nq` joints.
    pub fn zeros(nq: usize) -> Self {
        Sample {
            t_s: 0.0,
            q_rad: vec![0.0; nq],
            hand_force_n: [Vector3::zeros(); 2],
        }
    }
}

/// Why a recording was refused (line and column are 1-based).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RecordingError {
    #[error("{source_name}: line 1: {problem}")]
    Header {
        source_name: String,
        problem: String,
    },
    #[error("{source_name}: line {line}, column {column} ({name}): {problem}")]
    Cell {
        source_name: String,
        line: usize,
        column: usize,
        name: String,
        problem: String,
    },
    #[error("{source_name}: line {line}: {problem}")]
    Line {
        source_name: String,
        line: usize,
        problem: String,
    },
    #[error("{0}")]
    OpenSim(String),
}

/// Why a sample could not be evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvalError {
    #[error("time {t_s} does not increase (previous sample at {previous_t_s})")]
    Time { t_s: f64, previous_t_s: f64 },
    #[error("a sample needs {expected} joint angles, got {got}")]
    Length { expected: usize, got: usize },
    #[error("sample at t = {t_s}: every value must be finite")]
    NotFinite { t_s: f64 },
    #[error("sample at t = {t_s} s: {problem}")]
    Implausible { t_s: f64, problem: String },
}

/// The task that sets up an evaluation without a task file: the generated whole-body worker
/// described by `worker`, the default stance and fatigue parameters (`parameters`: a named set).
pub fn default_setup(
    worker: crate::body::Worker,
    parameters: Option<&str>,
) -> Result<Task, TaskError> {
    let mut fatigue = serde_json::Map::new();
    if let Some(p) = parameters {
        fatigue.insert("parameters".into(), p.into());
    }
    let v = serde_json::json!({
        "name": "recording",
        "worker": worker,
        "phases": [{"name": "recorded", "target_m": [0.4, -0.2, 1.0], "duration_s": 1.0}],
        "cycles": 1,
        "fatigue": fatigue,
    });
    let f: TaskFile = serde_json::from_value(v).map_err(|e| TaskError::Parse {
        path: "(evaluation set-up)".into(),
        message: e.to_string(),
    })?;
    Task::from_task_file(f, std::path::Path::new("(evaluation set-up)"))
}
