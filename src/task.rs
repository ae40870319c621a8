//! Task files (YAML) → a validated [`Task`]: names resolved, units checked.
//!
//! A task describes one worker doing a cycle of phases (hand target, hand load, duration) for a
//! number of cycles, with a rest per cycle, at a workstation with obstacles. See `tasks/*.yaml`.
//! Units: metres, kilograms, newtons, seconds, radians; world frame x forward, y left, z up.

use crate::body::{
    resolve_half_joints, worker_urdf, BodyModel, HalfJoint, StrengthTable, Worker, GRAVITY_M_S2,
};
use crate::fatigue::MaParams;
use crate::workstation::{ObstacleSpec, Workstation};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The task file as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskFile {
    pub name: String,
    pub worker: Worker,
    /// URDF path relative to the task file; absent: the worker's body is generated from `worker`.
    #[serde(default)]
    pub robot: Option<String>,
    #[serde(default = "default_hand_frame")]
    pub hand_frame: String,
    #[serde(default)]
    pub gravity_m_s2: Option<[f64; 3]>,
    #[serde(default)]
    pub workstation: WorkstationFile,
    pub phases: Vec<PhaseFile>,
    pub cycles: u32,
    /// Rest at the end of each cycle \[s\], arms hanging, no load.
    #[serde(default)]
    pub rest_s: f64,
    #[serde(default)]
    pub replan: ReplanFile,
    #[serde(default)]
    pub fatigue: FatigueFile,
}

fn default_hand_frame() -> String {
    "hand_grip".into()
}

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkstationFile {
    #[serde(default)]
    pub obstacles: Vec<ObstacleSpec>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhaseFile {
    pub name: String,
    /// Hand target \[m\], world frame.
    pub target_m: [f64; 3],
    /// A carried load \[kg\] (force = mass × gravity) ...
    #[serde(default)]
    pub load_kg: Option<f64>,
    /// ... or the force the environment applies on the hand \[N\].
    #[serde(default)]
    pub hand_force_n: Option<[f64; 3]>,
    pub duration_s: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReplanFile {
    /// Re-plan at most every this many cycles...
    #[serde(default = "one")]
    pub every_cycles: u32,
    /// ... or every this many seconds (whichever is given; cycles if both).
    #[serde(default)]
    pub every_s: Option<f64>,
    /// ... and only when some capacity moved by more than this since the last plan.
    #[serde(default = "default_capacity_tolerance")]
    pub capacity_tolerance: f64,
}

fn one() -> u32 {
    1
}
fn default_capacity_tolerance() -> f64 {
    0.02
}

impl Default for ReplanFile {
    fn default() -> Self {
        ReplanFile {
            every_cycles: 1,
            every_s: None,
            capacity_tolerance: default_capacity_tolerance(),
        }
    }
}

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FatigueFile {
    /// Fatigue rate k [1/min] for every muscle group (default 1, the paper).
    #[serde(default)]
    pub k_per_min: Option<f64>,
    /// Recovery rate R [1/min] for every muscle group (default 0, the paper).
    #[serde(default)]
    pub recovery_per_min: Option<f64>,
    /// Overrides per body region (trunk, shoulder, elbow, grip, ...) or half-joint id.
    #[serde(default)]
    pub overrides: BTreeMap<String, FatigueOverride>,
}

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FatigueOverride {
    #[serde(default)]
    pub k_per_min: Option<f64>,
    #[serde(default)]
    pub recovery_per_min: Option<f64>,
}

/// Why a task file was refused; every message names the file and the field or line.
#[derive(Debug, thiserror::Error)]
pub enum TaskError {
    #[error("{path}: cannot read: {message}")]
    Io { path: String, message: String },
    #[error("{path}: {message}")]
    Parse { path: String, message: String },
    #[error("{path}: {field}: {problem}")]
    Field {
        path: String,
        field: String,
        problem: String,
    },
}

/// One phase, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Phase {
    pub name: String,
    pub target_m: Vector3<f64>,
    pub hand_force_n: Vector3<f64>,
    pub duration_s: f64,
}

impl Phase {
    /// Same hand target and hand force: the same work, hence the same optimal posture.
    pub fn same_work(&self, other: &Phase) -> bool {
        self.target_m == other.target_m && self.hand_force_n == other.hand_force_n
    }
}

/// A validated task.
#[derive(Debug)]
pub struct Task {
    pub name: String,
    pub path: PathBuf,
    /// The URDF used (file path, or "generated from worker").
    pub robot: String,
    pub model: BodyModel,
    pub hand_frame: String,
    pub hand_link: usize,
    pub worker: Worker,
    pub gravity_m_s2: Vector3<f64>,
    pub half_joints: Vec<HalfJoint>,
    /// Fatigue parameters per half-joint (same order as `half_joints`).
    pub fatigue: Vec<MaParams>,
    pub workstation: Workstation,
    pub phases: Vec<Phase>,
    pub cycles: u32,
    pub rest_s: f64,
    pub replan_every_cycles: u32,
    pub replan_every_s: Option<f64>,
    pub capacity_tolerance: f64,
}

impl Task {
    /// Length of one cycle \[s\].
    pub fn cycle_s(&self) -> f64 {
        self.phases.iter().map(|p| p.duration_s).sum::<f64>() + self.rest_s
    }
    /// Planned duration of the whole task \[s\].
    pub fn duration_s(&self) -> f64 {
        self.cycle_s() * self.cycles as f64
    }

    /// Reads and validates a task file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, TaskError> {
        let path = path.as_ref();
        let p = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| TaskError::Io {
            path: p.clone(),
            message: e.to_string(),
        })?;
        let file: TaskFile = serde_saphyr::from_str(&text).map_err(|e| TaskError::Parse {
            path: p.clone(),
            message: e.to_string(),
        })?;
        Self::from_task_file(file, path)
    }

    /// Validates a parsed task; `path` locates the robot and names the file in messages.
    pub fn from_task_file(f: TaskFile, path: &Path) -> Result<Self, TaskError> {
        let p = path.display().to_string();
        let field = |field: &str, problem: String| TaskError::Field {
            path: p.clone(),
            field: field.to_string(),
            problem,
        };
        f.worker
            .validate()
            .map_err(|e| field("worker", e.to_string()))?;
        let gravity = match f.gravity_m_s2 {
            Some(g) if g.iter().all(|x| x.is_finite()) => Vector3::from(g),
            Some(g) => return Err(field("gravity_m_s2", format!("must be finite, got {g:?}"))),
            None => GRAVITY_M_S2,
        };
        let table_default = StrengthTable::default_table();
        let (model, robot, table) = match &f.robot {
            Some(r) => {
                let urdf = path.parent().unwrap_or(Path::new(".")).join(r);
                let model =
                    BodyModel::from_urdf_file(&urdf).map_err(|e| field("robot", e.to_string()))?;
                let sp = StrengthTable::path_beside(&urdf);
                let table = if sp.exists() {
                    StrengthTable::from_file(&sp).map_err(|e| field("robot", e.to_string()))?
                } else {
                    table_default
                };
                (model, urdf.display().to_string(), table)
            }
            None => {
                let text = worker_urdf(&f.worker, &table_default)
                    .map_err(|e| field("worker", e.to_string()))?;
                let model = BodyModel::from_urdf_str(&text, "generated worker")
                    .map_err(|e| field("worker", e.to_string()))?;
                (model, "generated from worker".to_string(), table_default)
            }
        };
        let hand_link = model
            .frame_link(&f.hand_frame)
            .map_err(|e| field("hand_frame", e.to_string()))?;
        let half_joints = resolve_half_joints(&model, &table, &f.worker, &robot)
            .map_err(|e| field("robot", e.to_string()))?;

        // Fatigue parameters: global, then region, then half-joint overrides.
        let check_rate =
            |name: String, v: Option<f64>, positive: bool| -> Result<Option<f64>, TaskError> {
                match v {
                    Some(x) if x.is_finite() && (x > 0.0 || (!positive && x == 0.0)) => Ok(Some(x)),
                    Some(x) => Err(field(
                        &name,
                        format!(
                            "must be finite and {} 0, got {x}",
                            if positive { ">" } else { ">=" }
                        ),
                    )),
                    None => Ok(None),
                }
            };
        let k0 = check_rate("fatigue.k_per_min".into(), f.fatigue.k_per_min, true)?.unwrap_or(1.0);
        let r0 = check_rate(
            "fatigue.recovery_per_min".into(),
            f.fatigue.recovery_per_min,
            false,
        )?
        .unwrap_or(0.0);
        for key in f.fatigue.overrides.keys() {
            if !half_joints.iter().any(|h| &h.id == key || &h.region == key) {
                return Err(field(
                    &format!("fatigue.overrides.{key}"),
                    "is neither a body region nor a half-joint id of the model".into(),
                ));
            }
        }
        let mut fatigue = Vec::with_capacity(half_joints.len());
        for h in &half_joints {
            let (mut k, mut r) = (k0, r0);
            for key in [&h.region, &h.id] {
                if let Some(o) = f.fatigue.overrides.get(key) {
                    if let Some(x) = check_rate(
                        format!("fatigue.overrides.{key}.k_per_min"),
                        o.k_per_min,
                        true,
                    )? {
                        k = x;
                    }
                    if let Some(x) = check_rate(
                        format!("fatigue.overrides.{key}.recovery_per_min"),
                        o.recovery_per_min,
                        false,
                    )? {
                        r = x;
                    }
                }
            }
            fatigue.push(MaParams::new(k, r).map_err(|e| field("fatigue", e.to_string()))?);
        }

        let workstation = Workstation::new(f.workstation.obstacles)
            .map_err(|e| field("workstation.obstacles", e.to_string()))?;
        if f.phases.is_empty() {
            return Err(field("phases", "at least one phase is needed".into()));
        }
        let mut phases = Vec::with_capacity(f.phases.len());
        for (i, ph) in f.phases.iter().enumerate() {
            let at = |name: &str| format!("phases[{i}] ({}).{name}", ph.name);
            if !ph.target_m.iter().all(|x| x.is_finite()) {
                return Err(field(
                    &at("target_m"),
                    format!("must be finite, got {:?}", ph.target_m),
                ));
            }
            if !(ph.duration_s.is_finite() && ph.duration_s > 0.0) {
                return Err(field(
                    &at("duration_s"),
                    format!("must be finite and > 0 s, got {}", ph.duration_s),
                ));
            }
            let force = match (ph.load_kg, ph.hand_force_n) {
                (Some(_), Some(_)) => {
                    return Err(field(
                        &at("load_kg"),
                        "give load_kg or hand_force_n, not both".into(),
                    ))
                }
                (Some(m), None) if m.is_finite() && (0.0..=100.0).contains(&m) => gravity * m,
                (Some(m), None) => {
                    return Err(field(
                        &at("load_kg"),
                        format!("must be between 0 and 100 kg, got {m}"),
                    ))
                }
                (None, Some(fv)) if fv.iter().all(|x| x.is_finite() && x.abs() <= 2000.0) => {
                    Vector3::from(fv)
                }
                (None, Some(fv)) => {
                    return Err(field(
                        &at("hand_force_n"),
                        format!("components must be finite and within ±2000 N, got {fv:?}"),
                    ))
                }
                (None, None) => Vector3::zeros(),
            };
            phases.push(Phase {
                name: ph.name.clone(),
                target_m: Vector3::from(ph.target_m),
                hand_force_n: force,
                duration_s: ph.duration_s,
            });
        }
        if f.cycles == 0 || f.cycles > 100_000 {
            return Err(field(
                "cycles",
                format!("must be between 1 and 100000, got {}", f.cycles),
            ));
        }
        if !(f.rest_s.is_finite() && f.rest_s >= 0.0) {
            return Err(field(
                "rest_s",
                format!("must be finite and >= 0 s, got {}", f.rest_s),
            ));
        }
        if f.replan.every_cycles == 0 {
            return Err(field("replan.every_cycles", "must be >= 1".into()));
        }
        if let Some(s) = f.replan.every_s {
            if !(s.is_finite() && s > 0.0) {
                return Err(field(
                    "replan.every_s",
                    format!("must be finite and > 0 s, got {s}"),
                ));
            }
        }
        if !(f.replan.capacity_tolerance.is_finite()
            && (0.0..1.0).contains(&f.replan.capacity_tolerance))
        {
            return Err(field(
                "replan.capacity_tolerance",
                format!("must be in [0, 1), got {}", f.replan.capacity_tolerance),
            ));
        }
        Ok(Task {
            name: f.name,
            path: path.to_path_buf(),
            robot,
            model,
            hand_frame: f.hand_frame,
            hand_link,
            worker: f.worker,
            gravity_m_s2: gravity,
            half_joints,
            fatigue,
            workstation,
            phases,
            cycles: f.cycles,
            rest_s: f.rest_s,
            replan_every_cycles: f.replan.every_cycles,
            replan_every_s: f.replan.every_s,
            capacity_tolerance: f.replan.capacity_tolerance,
        })
    }
}
