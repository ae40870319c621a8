//! Task files (YAML) → a validated [`Task`]: names resolved, units and ranges checked.
//!
//! A task describes one worker doing a cycle of phases — hand targets for one or both hands, the
//! load held, a duration — repeated for a number of cycles with a rest per cycle, standing at a
//! workstation with obstacles. See `tasks/*.yaml` and `docs/task-format.md` (generated from the
//! JSON Schema that `posture-opt schema` prints). Units: metres, kilograms, newtons, seconds,
//! radians (degrees where a field says `_deg`); world frame x forward, y left, z up, floor at z = 0.

use crate::body::seat::{ISCHIA_BELOW_HIPS_PER_STATURE, Seat};
use crate::body::stance::{Foot, Placement, Stance};
use crate::body::worker::{LEFT_FOOT_LINK, RIGHT_FOOT_LINK, worker_geometry};
use crate::body::{
    BodyModel, GRAVITY_M_S2, HalfJoint, StrengthTable, Worker, resolve_half_joints, worker_urdf,
};
use crate::fatigue::params::{ParameterSet, ParameterSets};
use crate::fatigue::{MaParams, Recovery};
use crate::workstation::{ObstacleSpec, Workstation};
use nalgebra::{Vector2, Vector3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Longest task accepted \[s\] (a year).
pub const MAX_DURATION_S: f64 = 365.0 * 24.0 * 3600.0;

/// Shortest hold (and rest, when there is one) of a phase \[s\]: a millisecond.
pub const MIN_DURATION_S: f64 = 1e-3;
/// Heaviest load accepted \[kg\] (a tonne).
pub const MAX_LOAD_KG: f64 = 1000.0;
/// Largest hand force component accepted \[N\].
pub const MAX_HAND_FORCE_N: f64 = 10_000.0;
/// Largest gravity accepted \[m/s²\] (three g).
pub const MAX_GRAVITY_M_S2: f64 = 3.0 * 9.81;
/// Smallest gravity accepted \[m/s²\] (a tenth of g): below it, strength and balance say nothing.
pub const MIN_GRAVITY_M_S2: f64 = 0.1 * 9.81;
/// Largest angle between gravity and straight down (−z, the world's vertical) \[deg\]: the
/// worker stands on a floor at z = 0 with z up.
pub const MAX_GRAVITY_TILT_DEG: f64 = 30.0;
/// Most moving joints of a body `plan` (and compare, sweep) plans: the optimiser's time grows
/// with about the cube of the joints (a 64-joint chain with collision capsules took over six minutes for one phase).
pub const MAX_PLAN_MOVING_JOINTS: usize = 48;
/// Most held steps a plan may have (cycles × (phases + rest)): bounds time and memory.
pub const MAX_STEPS: u64 = 400_000;
/// Most phases per cycle.
pub const MAX_PHASES: usize = 200;
/// Largest coordinate of a target or obstacle \[m\].
pub const MAX_COORDINATE_M: f64 = 1000.0;

/// The task file as written.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TaskFile {
    /// A short title for reports.
    pub name: String,
    /// Who does the task.
    pub worker: Worker,
    /// URDF body, relative to the task file. Absent: the whole-body worker is generated from
    /// `worker` (de Leva 1996 segments).
    #[serde(default)]
    pub robot: Option<String>,
    /// Frame of the right hand's grip (default `r_hand_grip`).
    #[serde(default)]
    pub hand_frame: Option<String>,
    /// Frame of the left hand's grip (default `l_hand_grip` when the body has it).
    #[serde(default)]
    pub left_hand_frame: Option<String>,
    /// Gravity \[m/s²\], world frame; default (0, 0, −9.81). Magnitude 0.1 g–3 g, pointing down:
    /// within 30° of −z (the world has z up and the floor at z = 0).
    #[serde(default)]
    pub gravity_m_s2: Option<[f64; 3]>,
    /// Where the feet stand (bodies with a floating pelvis).
    #[serde(default)]
    pub stance: Option<StanceFile>,
    /// A seat: given, the worker sits on it in every phase and at rest (the generated worker).
    #[serde(default)]
    pub seat: Option<SeatFile>,
    /// Obstacles of the workstation.
    #[serde(default)]
    pub workstation: WorkstationFile,
    /// The phases of one cycle, in order.
    pub phases: Vec<PhaseFile>,
    /// How many times the cycle repeats (1 or more).
    pub cycles: u32,
    /// Rest at the end of each cycle \[s\]: standing, arms hanging, no load. Default 0.
    #[serde(default)]
    pub rest_s: f64,
    /// When to re-plan as capacity falls.
    #[serde(default)]
    pub replan: ReplanFile,
    /// Fatigue model parameters.
    #[serde(default)]
    pub fatigue: FatigueFile,
    /// What the optimiser weighs besides fatigue.
    #[serde(default)]
    pub objective: ObjectiveFile,
    /// Lifts for the NIOSH lifting equation: which phases a lift starts and ends in.
    #[serde(default)]
    pub lifts: Vec<LiftFile>,
}

/// Hand-to-object coupling (NIOSH's classes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "lowercase")]
pub enum CouplingName {
    Good,
    #[default]
    Fair,
    Poor,
}

/// A lift of the task, for the revised NIOSH lifting equation.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LiftFile {
    pub name: String,
    /// The phase where the lift starts (the hands take the load).
    pub origin: String,
    /// The phase where it ends.
    pub destination: String,
    /// Hand-to-object coupling (default fair).
    #[serde(default)]
    pub coupling: CouplingName,
    /// The load must be placed with control at the destination (default false).
    #[serde(default)]
    pub control_at_destination: bool,
}

/// A checked lift: phase indices.
#[derive(Debug, Clone, PartialEq)]
pub struct Lift {
    pub name: String,
    pub origin: usize,
    pub destination: usize,
    pub coupling: CouplingName,
    pub control_at_destination: bool,
}

/// Stance on both feet.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StanceFile {
    /// Distance between the sole centres \[m\]; default the worker's shoulder width
    /// (0.21 × stature).
    #[serde(default)]
    pub width_m: Option<f64>,
    /// Sole centres this far forward of the origin \[m\]; default 0.
    #[serde(default)]
    pub forward_m: f64,
    /// Each foot turned outward by this much \[deg\], 0..45; default 0.
    #[serde(default)]
    pub toe_out_deg: f64,
    /// Foot links (left, right) of a custom robot; default `l_foot`, `r_foot`.
    #[serde(default)]
    pub feet: Option<[String; 2]>,
    /// The standing area \[m\]: a convex polygon on the floor, as (x, y) corners in order. Given,
    /// the planner places both feet in each phase (steps and turns) with every sole inside it;
    /// absent, the feet stay on the stance above in every phase.
    #[serde(default)]
    pub area_m: Option<Vec<[f64; 2]>>,
}

/// A seat the worker sits on, feet on the floor where the stance puts them.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SeatFile {
    /// Height of the seat's top above the floor \[m\], 0.25..1.0.
    pub height_m: f64,
    /// Centre of the seat's top in plan (x, y) \[m\]: behind the feet, for a worker facing +x.
    pub position_m: [f64; 2],
    /// Depth (front to back) and width of the top \[m\], each 0.2..1.0; default 0.40 × 0.45.
    #[serde(default)]
    pub size_m: Option<[f64; 2]>,
    /// The direction the seat faces \[deg\], about the vertical from +x (−180..180); default 0.
    #[serde(default)]
    pub yaw_deg: f64,
}

/// The workstation.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WorkstationFile {
    #[serde(default)]
    pub obstacles: Vec<ObstacleSpec>,
}

/// Which hand a one-handed phase uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "lowercase")]
pub enum HandName {
    #[default]
    Right,
    Left,
}

/// Targets for each hand \[m\], world frame.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HandTargetsFile {
    /// The right hand's target \[m\]; absent: the right hand is free (it hangs, unloaded, its
    /// upper arm within 10° of the vertical).
    #[serde(default)]
    pub right_m: Option<[f64; 3]>,
    /// The left hand's target \[m\]; absent: the left hand is free.
    #[serde(default)]
    pub left_m: Option<[f64; 3]>,
}

/// An object held with both hands.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ObjectFile {
    /// Where the object's centre (between the hands) must be \[m\].
    pub center_m: [f64; 3],
    /// Distance between the hands \[m\], along the world y axis (left hand on +y).
    pub grip_width_m: f64,
    /// Size of the object (x, y, z) \[m\]: the box the worker's body keeps clear of (the arms that
    /// hold it excepted) and the figures draw; default 0.30 × grip width × 0.25 (x, y,
    /// z).
    #[serde(default)]
    pub size_m: Option<[f64; 3]>,
}

/// One phase of the cycle: give exactly one of `target_m`, `targets` or `object`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PhaseFile {
    pub name: String,
    /// One-handed: the hand's target \[m\], world frame. The other hand is free: it hangs,
    /// unloaded, its upper arm within 10° of the vertical.
    #[serde(default)]
    pub target_m: Option<[f64; 3]>,
    /// The hand of a one-handed phase (default right).
    #[serde(default)]
    pub hand: HandName,
    /// A target per hand.
    #[serde(default)]
    pub targets: Option<HandTargetsFile>,
    /// An object held with both hands.
    #[serde(default)]
    pub object: Option<ObjectFile>,
    /// A carried load \[kg\] (force = mass × gravity), 0..1000 ...
    #[serde(default)]
    pub load_kg: Option<f64>,
    /// ... or the force the environment applies on the hands in total \[N\], world frame.
    #[serde(default)]
    pub hand_force_n: Option<[f64; 3]>,
    /// Share of a two-handed load on the left hand, 0..1; default 0.5.
    #[serde(default)]
    pub left_share: Option<f64>,
    /// How long the posture is held \[s\], 0.001..31536000 (a millisecond to a year).
    pub duration_s: f64,
    /// Where the worker looks \[m\], world frame (a body with a `head` link): the head turns so
    /// that this point lies within the eyes' comfortable cone (see `docs/worker.md`, "Looking
    /// at the work"). Absent: the middle of the phase's hand targets.
    #[serde(default)]
    pub gaze_m: Option<[f64; 3]>,
    /// The worker need not look at anything in this phase (work done by feel): the head is free.
    /// Not with `gaze_m`.
    #[serde(default)]
    pub gaze_free: bool,
}

/// When to re-plan.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ReplanFile {
    /// Re-plan at most every this many cycles (default 1) ...
    #[serde(default = "one")]
    pub every_cycles: u32,
    /// ... or every this many seconds (whichever is given; cycles if both).
    #[serde(default)]
    pub every_s: Option<f64>,
    /// ... and only when some capacity moved by more than this since the last plan (default 0.05).
    #[serde(default = "default_capacity_tolerance")]
    pub capacity_tolerance: f64,
}

fn one() -> u32 {
    1
}
fn default_capacity_tolerance() -> f64 {
    0.05
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

/// Fatigue parameters: a named set (default `default-2026`), optionally overridden.
///
/// Older task files that give only `k_per_min` and/or `recovery_per_min` keep their meaning:
/// one k for every muscle group and a constant recovery rate acting under load as at rest (the
/// model's printout names the load below which that holds forever).
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FatigueFile {
    /// Named parameter set: `default-2026`, `routed-2026` (two-deficit recovery), `frey-law-avin-2010` or `ma2009`.
    #[serde(default)]
    pub parameters: Option<String>,
    /// A parameter set in a file (relative to the task file), e.g. written by `posture-opt fit`;
    /// instead of `parameters`.
    #[serde(default)]
    pub parameters_file: Option<String>,
    /// Fatigue rate k \[1/min\] for every muscle group (0.01..20).
    #[serde(default)]
    pub k_per_min: Option<f64>,
    /// A constant recovery rate R \[1/min\], under load as at rest (0..20; the older form).
    #[serde(default)]
    pub recovery_per_min: Option<f64>,
    /// Perfusion-limited recovery: the rate at rest and the load where recovery stops.
    #[serde(default)]
    pub recovery: Option<RecoveryFile>,
    /// Overrides per body region (trunk, neck, shoulder, elbow, grip, hip, knee, ankle) or
    /// half-joint id (`r_shoulder_flexion+`).
    #[serde(default)]
    pub overrides: BTreeMap<String, FatigueOverride>,
}

/// Perfusion-limited recovery parameters.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RecoveryFile {
    /// Recovery rate at rest \[1/min\], 0..20.
    pub rest_per_min: f64,
    /// Load (fraction of MVC) from which recovery stops, 0.01..1.
    pub limit_fmvc: f64,
}

/// Per-region or per-group fatigue override.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FatigueOverride {
    #[serde(default)]
    pub k_per_min: Option<f64>,
    #[serde(default)]
    pub recovery_per_min: Option<f64>,
}

/// The optimiser's weights besides fatigue.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ObjectiveFile {
    /// Weight of the joint-range discomfort term (0 = fatigue only; default 0.1, 0..100).
    #[serde(default = "default_discomfort")]
    pub discomfort_weight: f64,
    /// Weight of the assessment-zone part of the discomfort term: trunk twist and side bend
    /// beyond 10°, leaning back beyond 5°, the wrist bent beyond 15° or deviated beyond 10°
    /// priced quadratically (default 0 = off, 0..1000; on the shipped tasks 300 keeps every
    /// posture within a few degrees of these zones at 4 to 76 % more fatigue, 30 only partly).
    #[serde(default)]
    pub zone_weight: f64,
    /// Smallest distance between the body and an obstacle \[m\] (default 0.01, 0..0.5).
    #[serde(default = "default_clearance")]
    pub clearance_m: f64,
    /// Smallest distance of the centre of pressure inside the support polygon \[m\]
    /// (default 0.02, 0..0.2).
    #[serde(default = "default_margin")]
    pub balance_margin_m: f64,
    /// Cost of one step of a foot between consecutive phases, in the objective's units (its
    /// fatigue term is the logarithm of the total fatigue index: 0.01 makes a step worth 1 % of
    /// the task's fatigue; default 0.01, 0..10). Only where the planner places the feet.
    #[serde(default = "default_step_weight")]
    pub step_weight: f64,
    /// Weight of the asymmetry cost: each phase's angle between the hands' load and the feet's
    /// mid-sagittal plane priced as `−ln` of NIOSH's asymmetry multiplier `1 − 0.0032·A`, the
    /// mean over the cycle's phases (default 1: a cycle done wholly at A counts as its fatigue
    /// divided by the multiplier; 0..10). Only where the planner places the feet.
    #[serde(default = "default_asymmetry_weight")]
    pub asymmetry_weight: f64,
}

fn default_step_weight() -> f64 {
    0.01
}
fn default_asymmetry_weight() -> f64 {
    1.0
}
fn default_discomfort() -> f64 {
    0.1
}
fn default_clearance() -> f64 {
    0.01
}
fn default_margin() -> f64 {
    0.02
}

impl Default for ObjectiveFile {
    fn default() -> Self {
        ObjectiveFile {
            discomfort_weight: default_discomfort(),
            zone_weight: 0.0,
            clearance_m: default_clearance(),
            balance_margin_m: default_margin(),
            step_weight: default_step_weight(),
            asymmetry_weight: default_asymmetry_weight(),
        }
    }
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

/// The two hands; index 0 right, 1 left.
pub const HANDS: [&str; 2] = ["right", "left"];

/// An object held in both hands (for the figures).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HeldObject {
    pub center_m: [f64; 3],
    pub size_m: [f64; 3],
}

/// One phase, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Phase {
    pub name: String,
    /// Target of each hand (right, left); `None`: that hand is free (hanging, unloaded).
    pub targets_m: [Option<Vector3<f64>>; 2],
    /// Force the environment applies on each hand \[N\].
    pub hand_force_n: [Vector3<f64>; 2],
    pub duration_s: f64,
    pub object: Option<HeldObject>,
    /// Where the worker looks.
    pub gaze: Gaze,
}

/// Where a phase's worker looks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Gaze {
    /// Nowhere in particular (work done by feel, or a body without a head).
    Free,
    /// At the middle of the phase's hand targets, wherever they are moved.
    Targets,
    /// At this point \[m\], world frame.
    Point(Vector3<f64>),
}

impl Phase {
    /// Same targets, hand forces and gaze: the same work, hence the same optimal posture.
    pub fn same_work(&self, other: &Phase) -> bool {
        self.targets_m == other.targets_m
            && self.hand_force_n == other.hand_force_n
            && self.gaze_m() == other.gaze_m()
    }

    /// The point the worker looks at \[m\], world frame (`None`: the head is free).
    pub fn gaze_m(&self) -> Option<Vector3<f64>> {
        match self.gaze {
            Gaze::Free => None,
            Gaze::Point(p) => Some(p),
            Gaze::Targets => {
                let (sum, n) = self
                    .targets_m
                    .iter()
                    .flatten()
                    .fold((Vector3::zeros(), 0.0), |(s, n), t| (s + t, n + 1.0));
                (n > 0.0).then(|| sum / n)
            }
        }
    }

    /// Total force on the hands \[N\].
    pub fn total_force_n(&self) -> Vector3<f64> {
        self.hand_force_n[0] + self.hand_force_n[1]
    }

    /// Hands used.
    pub fn hands(&self) -> impl Iterator<Item = usize> + '_ {
        (0..2).filter(|&h| self.targets_m[h].is_some())
    }
}

/// How the fatigue parameters were chosen, for reports.
#[derive(Debug, Clone, Serialize)]
pub struct FatigueChoice {
    /// Named set, or "legacy" for an older task file's k / constant recovery.
    pub set: String,
    pub description: String,
    pub k_source: String,
    pub recovery_source: String,
}

/// The optimiser's settings from the task.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectiveSettings {
    pub discomfort_weight: f64,
    /// Weight of the assessment zones within the discomfort term (0 = off).
    pub zone_weight: f64,
    pub clearance_m: f64,
    pub balance_margin_m: f64,
    /// Cost of one step between consecutive phases (objective units).
    pub step_weight: f64,
    /// Weight of the NIOSH-shaped asymmetry cost (objective units).
    pub asymmetry_weight: f64,
}

/// A validated task.
#[derive(Debug, Clone)]
pub struct Task {
    /// The file as written (e.g. to plan it again for another worker).
    pub source: TaskFile,
    pub name: String,
    pub path: PathBuf,
    /// The URDF used (file path, or "generated from worker").
    pub robot: String,
    /// The robot and strength files read (for output-safety checks).
    pub input_files: Vec<PathBuf>,
    pub model: BodyModel,
    /// Hand frames (right, left): link index and name; `None` if the body lacks that hand.
    pub hand_links: [Option<(usize, String)>; 2],
    /// The head and its eyes, when the body has a link named `head` with a shape: the
    /// phases' gaze applies.
    pub head: Option<Head>,
    pub worker: Worker,
    pub gravity_m_s2: Vector3<f64>,
    pub stance: Option<Stance>,
    /// q indices of joints without muscles.
    pub unactuated: Vec<usize>,
    pub half_joints: Vec<HalfJoint>,
    /// Fatigue parameters per half-joint (same order as `half_joints`).
    pub fatigue: Vec<MaParams>,
    pub fatigue_choice: FatigueChoice,
    /// The parameter set, when the task uses one (for the uncertainty analysis).
    pub parameter_set: Option<ParameterSet>,
    pub workstation: Workstation,
    pub phases: Vec<Phase>,
    pub cycles: u32,
    pub rest_s: f64,
    pub replan_every_cycles: u32,
    pub replan_every_s: Option<f64>,
    pub capacity_tolerance: f64,
    pub objective: ObjectiveSettings,
    pub lifts: Vec<Lift>,
}

impl TaskFile {
    /// Parses task YAML (not yet validated); `path` names it in messages.
    pub fn from_yaml_str(text: &str, path: &Path) -> Result<Self, TaskError> {
        let p = path.display().to_string();
        serde_saphyr::from_str(text).map_err(|e| TaskError::Parse {
            path: p.clone(),
            // the parser's excerpt names its source `<input>`: name the file instead
            message: crate::schema::explain_parse_error(&e.to_string()).replace("<input>", &p),
        })
    }
}

impl Task {
    /// Per phase, how long its posture is held without a break (the run of consecutive phases of the
    /// same work it belongs to, across the cycle's end when there is no rest) \[s\], and how often
    /// such a run starts per minute.
    pub fn holds(&self) -> Vec<(f64, f64)> {
        let n = self.phases.len();
        if n == 0 {
            return Vec::new();
        }
        let mut run = vec![0usize; n];
        let mut r = 0;
        for p in 1..n {
            if !self.phases[p].same_work(&self.phases[p - 1]) {
                r += 1;
            }
            run[p] = r;
        }
        let wraps =
            n > 1 && self.rest_s <= 0.0 && self.phases[n - 1].same_work(&self.phases[0]) && r > 0;
        if wraps {
            let last = r;
            for x in run.iter_mut() {
                if *x == last {
                    *x = 0;
                }
            }
        }
        let mut total = vec![0.0; r + 1];
        for p in 0..n {
            total[run[p]] += self.phases[p].duration_s;
        }
        let cycle = self.cycle_s().max(1e-9);
        (0..n)
            .map(|p| {
                let ph = &self.phases[p];
                let mut runs: Vec<usize> = (0..n)
                    .filter(|&o| self.phases[o].same_work(ph))
                    .map(|o| run[o])
                    .collect();
                runs.dedup();
                runs.sort_unstable();
                runs.dedup();
                (total[run[p]], runs.len() as f64 * 60.0 / cycle)
            })
            .collect()
    }

    /// Length of one cycle \[s\].
    pub fn cycle_s(&self) -> f64 {
        self.phases.iter().map(|p| p.duration_s).sum::<f64>() + self.rest_s
    }
    /// Planned duration of the whole task \[s\].
    pub fn duration_s(&self) -> f64 {
        self.cycle_s() * self.cycles as f64
    }

    /// Joint names in q order.
    pub fn joint_names(&self) -> Vec<String> {
        (0..self.model.nq())
            .map(|i| self.model.q_joint(i).name.clone())
            .collect()
    }

    /// Half-joint ids in order.
    pub fn half_joint_ids(&self) -> Vec<String> {
        self.half_joints.iter().map(|h| h.id.clone()).collect()
    }

    /// SHA-256 (hex) of what the task was made from: the task as parsed (so formatting and
    /// comments do not count) and the bytes of every file it read (robot, strength table,
    /// parameter file). Shards of one study carry it so that a merge can refuse results made
    /// from different files.
    pub fn fingerprint(&self) -> String {
        use sha2::{Digest, Sha256};
        let mut h = Sha256::new();
        h.update(serde_json::to_vec(&self.source).unwrap_or_default());
        for f in &self.input_files {
            h.update(b"\0file\0");
            match std::fs::read(f) {
                Ok(bytes) => h.update(&bytes),
                Err(_) => h.update(f.display().to_string().as_bytes()),
            }
        }
        format!("{:x}", h.finalize())
    }

    /// Reads and validates a task file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, TaskError> {
        let path = path.as_ref();
        let p = path.display().to_string();
        let text = crate::io::read_text(path).map_err(|e| TaskError::Io {
            path: p.clone(),
            message: e.to_string(),
        })?;
        Self::from_yaml_str(&text, path)
    }

    /// Parses and validates task YAML; `path` names it in messages and locates a relative robot.
    pub fn from_yaml_str(text: &str, path: &Path) -> Result<Self, TaskError> {
        Self::from_task_file(TaskFile::from_yaml_str(text, path)?, path)
    }

    /// Validates a parsed task; `path` locates the robot and names the file in messages.
    pub fn from_task_file(f: TaskFile, path: &Path) -> Result<Self, TaskError> {
        let source = f.clone();
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
            Some(g) => check_gravity(g).map_err(|e| field("gravity_m_s2", e))?,
            None => GRAVITY_M_S2,
        };
        let mut input_files = Vec::new();
        let table_default = StrengthTable::default_table();
        // the file a strength-table problem is reported against: the table beside the URDF
        // when one was read, else the robot (its URDF efforts) or the generated worker
        let mut table_origin = None;
        let (model, robot, table, generated) = match &f.robot {
            Some(r) => {
                let urdf = path.parent().unwrap_or(Path::new(".")).join(r);
                let model =
                    BodyModel::from_urdf_file(&urdf).map_err(|e| field("robot", e.to_string()))?;
                if let Ok(text) = crate::io::read_text(&urdf)
                    && let Some(made_for) = generated_for(&text)
                {
                    let w = &f.worker;
                    // the sex is compared without case (earlier versions wrote "Male"); only
                    // the fields that differ are named
                    let mut differ = Vec::new();
                    if !made_for.0.eq_ignore_ascii_case(w.sex.name()) {
                        differ.push(format!(
                            "sex {} (the task's worker: {})",
                            made_for.0,
                            w.sex.name()
                        ));
                    }
                    if (made_for.1 - w.stature_m).abs() > 5e-4 {
                        differ.push(format!(
                            "stature {} m (the task's worker: {} m)",
                            made_for.1, w.stature_m
                        ));
                    }
                    if (made_for.2 - w.mass_kg).abs() > 5e-3 {
                        differ.push(format!(
                            "mass {} kg (the task's worker: {} kg)",
                            made_for.2, w.mass_kg
                        ));
                    }
                    if !differ.is_empty() {
                        return Err(field(
                            "robot",
                            format!(
                                "{} was generated for another worker: {}; regenerate it (posture-opt robot --sex {} --stature-m {} --mass-kg {} --out ...) or leave robot out to generate the worker",
                                urdf.display(),
                                differ.join(", "),
                                w.sex.name(),
                                w.stature_m,
                                w.mass_kg
                            ),
                        ));
                    }
                }
                input_files.push(urdf.clone());
                let sp = StrengthTable::path_beside(&urdf);
                let table = if sp.exists() {
                    input_files.push(sp.clone());
                    table_origin = Some(format!(
                        "{} (strength table of {})",
                        sp.display(),
                        urdf.display()
                    ));
                    StrengthTable::from_file(&sp).map_err(|e| field("robot", e.to_string()))?
                } else {
                    table_default
                };
                let generated = model.links.iter().any(|l| l.name == RIGHT_FOOT_LINK)
                    && model.q_index("pelvis_tx").is_ok();
                (model, urdf.display().to_string(), table, generated)
            }
            None => {
                let text = worker_urdf(&f.worker, &table_default)
                    .map_err(|e| field("worker", e.to_string()))?;
                let model = BodyModel::from_urdf_str(&text, "generated worker")
                    .map_err(|e| field("worker", e.to_string()))?;
                (
                    model,
                    "generated from worker".to_string(),
                    table_default,
                    true,
                )
            }
        };
        if model.nq() == 0 {
            return Err(field(
                "robot",
                "the robot has no moving joints: there is no posture to plan".into(),
            ));
        }
        if model.nq() > MAX_PLAN_MOVING_JOINTS {
            return Err(field(
                "robot",
                format!(
                    "{robot} has {} moving joints; a plan takes at most {MAX_PLAN_MOVING_JOINTS} (the optimiser's time grows with about their cube): fix joints that do not matter for the task (type=\"fixed\")",
                    model.nq()
                ),
            ));
        }
        let hand_names = [
            f.hand_frame.clone().unwrap_or_else(|| "r_hand_grip".into()),
            f.left_hand_frame
                .clone()
                .unwrap_or_else(|| "l_hand_grip".into()),
        ];
        let hand_links = [
            model
                .frame_link(&hand_names[0])
                .ok()
                .map(|l| (l, hand_names[0].clone())),
            model
                .frame_link(&hand_names[1])
                .ok()
                .map(|l| (l, hand_names[1].clone())),
        ];
        if hand_links[0].is_none() && (f.hand_frame.is_some() || hand_links[1].is_none()) {
            let frames: Vec<&str> = model.links.iter().map(|l| l.name.as_str()).collect();
            return Err(field(
                "hand_frame",
                format!(
                    "'{}' is not a link of the robot{} (links: {})",
                    hand_names[0],
                    crate::schema::did_you_mean(&hand_names[0], frames.iter().copied()),
                    frames.join(", ")
                ),
            ));
        }
        if f.left_hand_frame.is_some() && hand_links[1].is_none() {
            return Err(field(
                "left_hand_frame",
                format!(
                    "'{}' is not a link of the robot{}",
                    hand_names[1],
                    crate::schema::did_you_mean(
                        &hand_names[1],
                        model.links.iter().map(|l| l.name.as_str())
                    )
                ),
            ));
        }
        let half_joints = resolve_half_joints(
            &model,
            &table,
            &f.worker,
            table_origin.as_deref().unwrap_or(&robot),
        )
        .map_err(|e| field("robot", e.to_string()))?;
        let unactuated: Vec<usize> = table
            .unactuated
            .iter()
            .filter_map(|j| model.q_index(j).ok())
            .collect();

        // Stance.
        let stance = if unactuated.is_empty() {
            if f.stance.is_some() {
                return Err(field(
                    "stance",
                    "this robot has a fixed base (no unactuated joints in its strength table): it does not stand on feet".into(),
                ));
            }
            None
        } else {
            let sf = f.stance.clone().unwrap_or_default();
            let feet_names = sf
                .feet
                .clone()
                .unwrap_or([LEFT_FOOT_LINK.to_string(), RIGHT_FOOT_LINK.to_string()]);
            let foot = |i: usize| {
                Foot::from_link(&model, &feet_names[i]).map_err(|e| {
                    // the foot's problem is in the robot's file: name it, not the model's name
                    let e = match e {
                        crate::body::BodyError::Invalid {
                            element, problem, ..
                        } => format!("{robot}: {element}: {problem}"),
                        other => format!("{robot}: {other}"),
                    };
                    field(
                        "stance.feet",
                        format!("{e} (a floating-base robot stands on two feet)"),
                    )
                })
            };
            if feet_names[0] == feet_names[1] {
                return Err(field(
                    "stance.feet",
                    format!(
                        "names '{}' twice; the two feet must be two different frames",
                        feet_names[0]
                    ),
                ));
            }
            let feet = [foot(0)?, foot(1)?];
            let width = match sf.width_m {
                Some(w) if w.is_finite() && (0.05..=1.5).contains(&w) => w,
                Some(w) => {
                    return Err(field(
                        "stance.width_m",
                        format!("must be within 0.05..1.5 m, got {w}"),
                    ));
                }
                None if generated => 2.0 * worker_geometry(&f.worker).shoulder_half_width_m,
                None => 0.3,
            };
            if !(sf.forward_m.is_finite() && sf.forward_m.abs() <= 2.0) {
                return Err(field(
                    "stance.forward_m",
                    format!("must be within ±2 m, got {}", sf.forward_m),
                ));
            }
            if !(sf.toe_out_deg.is_finite() && (0.0..=45.0).contains(&sf.toe_out_deg)) {
                return Err(field(
                    "stance.toe_out_deg",
                    format!("must be within 0..45°, got {}", sf.toe_out_deg),
                ));
            }
            let nominal = Stance::new(feet, width, sf.forward_m, sf.toe_out_deg.to_radians());
            match &sf.area_m {
                None => Some(nominal),
                Some(area) => {
                    let placement = placement(area, &sf, &nominal, width, &field)?;
                    Some(nominal.with_placement(placement))
                }
            }
        };

        let stance = match (&f.seat, stance) {
            (None, stance) => stance,
            (Some(_), None) => {
                return Err(field(
                    "seat",
                    "this robot has a fixed base: it cannot sit".into(),
                ));
            }
            (Some(sf), Some(st)) => {
                let seat = seat(sf, &model, &f.worker, generated, &field)?;
                seat_within_reach_of_the_feet(&seat, &st, &f.worker, &field)?;
                Some(st.with_seat(seat))
            }
        };
        if f.seat.is_some() && f.stance.as_ref().is_some_and(|s| s.area_m.is_some()) {
            return Err(field(
                "stance.area_m",
                "a seated worker's feet stay where the stance puts them: give a standing area or a seat, not both".into(),
            ));
        }

        let file_set = match &f.fatigue.parameters_file {
            Some(name) => {
                if f.fatigue.parameters.is_some() {
                    return Err(field(
                        "fatigue.parameters_file",
                        "give parameters or parameters_file, not both".into(),
                    ));
                }
                let fp = path.parent().unwrap_or(Path::new(".")).join(name);
                let text = crate::io::read_text(&fp)
                    .map_err(|e| field("fatigue.parameters_file", e.to_string()))?;
                input_files.push(fp.clone());
                Some(
                    ParameterSet::from_yaml_str(&text, &fp.display().to_string())
                        .map_err(|e| field("fatigue.parameters_file", e))?,
                )
            }
            None => None,
        };
        let (fatigue, fatigue_choice, parameter_set) =
            resolve_fatigue(&f.fatigue, file_set, &half_joints, &f.worker, &field)?;

        // Where the standing worker's hips are (the feet's midpoint forward, at 53 % of the
        // stature): an obstacle holding that point encloses the worker, passes through him, or
        // is a plane whose solid side is his. The planner would search for minutes for a posture
        // out of it; it is refused at once.
        let hips = stance.as_ref().map(|st| match &st.seat {
            Some(seat) => {
                let c = seat
                    .outline_m
                    .iter()
                    .fold(nalgebra::Vector2::zeros(), |a, b| a + b)
                    / 4.0;
                Vector3::new(c.x, c.y, seat.height_m - seat.contact_in_link_m.z)
            }
            None => Vector3::new(
                f.stance.as_ref().map_or(0.0, |s| s.forward_m),
                0.0,
                0.53 * f.worker.stature_m,
            ),
        });
        let workstation = Workstation::new(f.workstation.obstacles)
            .map_err(|e| field("workstation.obstacles", e.to_string()))?;
        if let Some(hips) = hips {
            for (i, o) in workstation.obstacles.iter().enumerate() {
                if !o.contains(&hips) {
                    continue;
                }
                let why = match &o.spec.shape {
                    crate::workstation::ShapeSpec::Plane { normal } => format!(
                        "the worker stands on its solid side (a plane's normal points from the solid toward free space; this one, {normal:?}, points away from the worker)"
                    ),
                    crate::workstation::ShapeSpec::Cylinder { .. } => {
                        "it passes through the worker".to_string()
                    }
                    crate::workstation::ShapeSpec::Box { .. } => {
                        "it encloses the worker or passes through him".to_string()
                    }
                };
                return Err(field(
                    &format!("workstation.obstacles[{i}] ({})", o.spec.name),
                    format!(
                        "holds the standing worker's hips ({:.2}, {:.2}, {:.2}) m: {why}; the worker stands at the origin facing +x, so move or resize the obstacle",
                        hips.x, hips.y, hips.z
                    ),
                ));
            }
        }

        if f.phases.is_empty() {
            return Err(field("phases", "at least one phase is needed".into()));
        }
        if f.phases.len() > MAX_PHASES {
            return Err(field(
                "phases",
                format!(
                    "at most {MAX_PHASES} phases per cycle, got {}",
                    f.phases.len()
                ),
            ));
        }
        let mut phases = Vec::with_capacity(f.phases.len());
        let has_head = Head::of(&model).is_some();
        for (i, ph) in f.phases.iter().enumerate() {
            if let Some(j) = f.phases[..i].iter().position(|p| p.name == ph.name) {
                return Err(field(
                    &format!("phases[{i}].name"),
                    format!(
                        "'{}' is also the name of phases[{j}]; phase names must be unique (lifts and reports name phases)",
                        ph.name
                    ),
                ));
            }
            phases.push(check_phase(i, ph, &hand_links, &gravity, has_head, &field)?);
        }
        if f.cycles == 0 {
            return Err(field("cycles", "must be at least 1".into()));
        }
        if !(f.rest_s.is_finite()
            && (f.rest_s == 0.0 || (MIN_DURATION_S..=MAX_DURATION_S).contains(&f.rest_s)))
        {
            return Err(field(
                "rest_s",
                format!("must be 0 or within 1 ms and a year, got {} s", f.rest_s),
            ));
        }
        let steps = f.cycles as u64 * (phases.len() as u64 + u64::from(f.rest_s > 0.0));
        if steps > MAX_STEPS {
            return Err(field(
                "cycles",
                format!(
                    "{} cycles of {} steps make {steps} held steps, more than the {MAX_STEPS} a plan may have (time and memory); plan a shorter stretch or longer phases",
                    f.cycles,
                    phases.len() + usize::from(f.rest_s > 0.0)
                ),
            ));
        }
        let cycle_s: f64 = phases.iter().map(|p| p.duration_s).sum::<f64>() + f.rest_s;
        if cycle_s * f.cycles as f64 > MAX_DURATION_S {
            return Err(field(
                "cycles",
                format!(
                    "the task would last {:.0} days; at most a year is planned",
                    cycle_s * f.cycles as f64 / 86400.0
                ),
            ));
        }
        if f.replan.every_cycles == 0 {
            return Err(field("replan.every_cycles", "must be >= 1".into()));
        }
        if let Some(s) = f.replan.every_s
            && !(s.is_finite() && s > 0.0 && s <= MAX_DURATION_S)
        {
            return Err(field(
                "replan.every_s",
                format!("must be within 0 s and a year, got {s}"),
            ));
        }
        if !(f.replan.capacity_tolerance.is_finite()
            && (0.0..1.0).contains(&f.replan.capacity_tolerance))
        {
            return Err(field(
                "replan.capacity_tolerance",
                format!("must be in [0, 1), got {}", f.replan.capacity_tolerance),
            ));
        }
        let mut lifts = Vec::with_capacity(f.lifts.len());
        for (i, l) in f.lifts.iter().enumerate() {
            let find = |what: &str, name: &str| {
                phases.iter().position(|p| p.name == name).ok_or_else(|| {
                    field(
                        &format!("lifts[{i}] ({}).{what}", l.name),
                        format!(
                            "'{name}' is not a phase of the task{}",
                            crate::schema::did_you_mean(
                                name,
                                phases.iter().map(|p| p.name.as_str())
                            )
                        ),
                    )
                })
            };
            let origin = find("origin", &l.origin)?;
            let destination = find("destination", &l.destination)?;
            if origin == destination {
                return Err(field(
                    &format!("lifts[{i}] ({}).destination", l.name),
                    format!(
                        "is '{}', the lift's origin too; a lift moves the load from one phase to another",
                        l.destination
                    ),
                ));
            }
            lifts.push(Lift {
                name: l.name.clone(),
                origin,
                destination,
                coupling: l.coupling,
                control_at_destination: l.control_at_destination,
            });
        }
        let o = &f.objective;
        if !(o.discomfort_weight.is_finite() && (0.0..=100.0).contains(&o.discomfort_weight)) {
            return Err(field(
                "objective.discomfort_weight",
                format!("must be within 0..100, got {}", o.discomfort_weight),
            ));
        }
        if !(o.zone_weight.is_finite() && (0.0..=1000.0).contains(&o.zone_weight)) {
            return Err(field(
                "objective.zone_weight",
                format!("must be within 0..1000, got {}", o.zone_weight),
            ));
        }
        if !(o.clearance_m.is_finite() && (0.0..=0.5).contains(&o.clearance_m)) {
            return Err(field(
                "objective.clearance_m",
                format!("must be within 0..0.5 m, got {}", o.clearance_m),
            ));
        }
        if !(o.balance_margin_m.is_finite() && (0.0..=0.2).contains(&o.balance_margin_m)) {
            return Err(field(
                "objective.balance_margin_m",
                format!("must be within 0..0.2 m, got {}", o.balance_margin_m),
            ));
        }
        if !(o.step_weight.is_finite() && (0.0..=10.0).contains(&o.step_weight)) {
            return Err(field(
                "objective.step_weight",
                format!("must be within 0..10, got {}", o.step_weight),
            ));
        }
        if !(o.asymmetry_weight.is_finite() && (0.0..=10.0).contains(&o.asymmetry_weight)) {
            return Err(field(
                "objective.asymmetry_weight",
                format!("must be within 0..10, got {}", o.asymmetry_weight),
            ));
        }
        let head = Head::of(&model);
        Ok(Task {
            head,
            source,
            name: f.name,
            path: path.to_path_buf(),
            robot,
            input_files,
            model,
            hand_links,
            worker: f.worker,
            gravity_m_s2: gravity,
            stance,
            unactuated,
            half_joints,
            fatigue,
            fatigue_choice,
            parameter_set,
            workstation,
            phases,
            cycles: f.cycles,
            rest_s: f.rest_s,
            replan_every_cycles: f.replan.every_cycles,
            replan_every_s: f.replan.every_s,
            capacity_tolerance: f.replan.capacity_tolerance,
            objective: ObjectiveSettings {
                discomfort_weight: o.discomfort_weight,
                zone_weight: o.zone_weight,
                clearance_m: o.clearance_m,
                balance_margin_m: o.balance_margin_m,
                step_weight: o.step_weight,
                asymmetry_weight: o.asymmetry_weight,
            },
            lifts,
        })
    }
}

type FieldErr<'a> = dyn Fn(&str, String) -> TaskError + 'a;

fn check_point(v: &[f64; 3], at: &str, field: &FieldErr) -> Result<Vector3<f64>, TaskError> {
    if v.iter()
        .all(|x| x.is_finite() && x.abs() <= MAX_COORDINATE_M)
    {
        Ok(Vector3::from(*v))
    } else {
        Err(field(
            at,
            format!("must be finite and within ±{MAX_COORDINATE_M} m, got {v:?}"),
        ))
    }
}

fn check_phase(
    i: usize,
    ph: &PhaseFile,
    hand_links: &[Option<(usize, String)>; 2],
    gravity: &Vector3<f64>,
    has_head: bool,
    field: &FieldErr,
) -> Result<Phase, TaskError> {
    let at = |name: &str| format!("phases[{i}] ({}).{name}", ph.name);
    if !(ph.duration_s.is_finite()
        && ph.duration_s >= MIN_DURATION_S
        && ph.duration_s <= MAX_DURATION_S)
    {
        return Err(field(
            &at("duration_s"),
            format!(
                "must be at least 1 ms and at most a year, got {} s",
                ph.duration_s
            ),
        ));
    }
    let given = [
        ph.target_m.is_some(),
        ph.targets.is_some(),
        ph.object.is_some(),
    ];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(field(
            &at("target_m"),
            "give exactly one of target_m (one hand), targets (per hand) or object (both hands)"
                .into(),
        ));
    }
    let mut targets: [Option<Vector3<f64>>; 2] = [None, None];
    let mut object = None;
    if let Some(t) = &ph.target_m {
        let h = match ph.hand {
            HandName::Right => 0,
            HandName::Left => 1,
        };
        targets[h] = Some(check_point(t, &at("target_m"), field)?);
    }
    if let Some(ts) = &ph.targets {
        if let Some(t) = &ts.right_m {
            targets[0] = Some(check_point(t, &at("targets.right_m"), field)?);
        }
        if let Some(t) = &ts.left_m {
            targets[1] = Some(check_point(t, &at("targets.left_m"), field)?);
        }
        if targets.iter().all(|t| t.is_none()) {
            return Err(field(&at("targets"), "give right_m, left_m or both".into()));
        }
    }
    if let Some(o) = &ph.object {
        let c = check_point(&o.center_m, &at("object.center_m"), field)?;
        if !(o.grip_width_m.is_finite() && (0.05..=2.0).contains(&o.grip_width_m)) {
            return Err(field(
                &at("object.grip_width_m"),
                format!("must be within 0.05..2 m, got {}", o.grip_width_m),
            ));
        }
        let half = Vector3::new(0.0, o.grip_width_m / 2.0, 0.0);
        targets = [Some(c - half), Some(c + half)];
        let size = match o.size_m {
            Some(s) if s.iter().all(|x| x.is_finite() && *x > 0.0 && *x <= 5.0) => s,
            Some(s) => {
                return Err(field(
                    &at("object.size_m"),
                    format!("must be within 0..5 m each, got {s:?}"),
                ));
            }
            None => [0.3, o.grip_width_m, 0.25],
        };
        object = Some(HeldObject {
            center_m: o.center_m,
            size_m: size,
        });
    }
    for h in 0..2 {
        if targets[h].is_some() && hand_links[h].is_none() {
            return Err(field(
                &at("hand"),
                format!("the robot has no {} hand frame", super::task::HANDS[h]),
            ));
        }
    }
    let total = match (ph.load_kg, ph.hand_force_n) {
        (Some(_), Some(_)) => {
            return Err(field(
                &at("load_kg"),
                "give load_kg or hand_force_n, not both".into(),
            ));
        }
        (Some(m), None) if m.is_finite() && (0.0..=MAX_LOAD_KG).contains(&m) => gravity * m,
        (Some(m), None) => {
            return Err(field(
                &at("load_kg"),
                format!("must be between 0 and {MAX_LOAD_KG} kg, got {m}"),
            ));
        }
        (None, Some(fv))
            if fv
                .iter()
                .all(|x| x.is_finite() && x.abs() <= MAX_HAND_FORCE_N) =>
        {
            Vector3::from(fv)
        }
        (None, Some(fv)) => {
            return Err(field(
                &at("hand_force_n"),
                format!("components must be finite and within ±{MAX_HAND_FORCE_N} N, got {fv:?}"),
            ));
        }
        (None, None) => Vector3::zeros(),
    };
    let two = targets[0].is_some() && targets[1].is_some();
    let left_share = match ph.left_share {
        Some(s) if !two => {
            let _ = s;
            return Err(field(
                &at("left_share"),
                "only a two-handed phase shares its load".into(),
            ));
        }
        Some(s) if s.is_finite() && (0.0..=1.0).contains(&s) => s,
        Some(s) => {
            return Err(field(
                &at("left_share"),
                format!("must be within 0..1, got {s}"),
            ));
        }
        None if two => 0.5,
        None if targets[1].is_some() => 1.0,
        None => 0.0,
    };
    let gaze = match ph.gaze_m {
        Some(_) if ph.gaze_free => {
            return Err(field(
                &at("gaze_free"),
                "a phase with gaze_m looks at it: give gaze_m or gaze_free, not both".into(),
            ));
        }
        Some(g) if g.iter().all(|x| x.is_finite() && x.abs() <= 100.0) => {
            Gaze::Point(Vector3::from(g))
        }
        Some(g) => {
            return Err(field(
                &at("gaze_m"),
                format!("must be finite and within ±100 m, got {g:?}"),
            ));
        }
        // the worker looks at the work
        None if !ph.gaze_free && has_head => Gaze::Targets,
        None => Gaze::Free,
    };
    Ok(Phase {
        name: ph.name.clone(),
        targets_m: targets,
        hand_force_n: [total * (1.0 - left_share), total * left_share],
        duration_s: ph.duration_s,
        object,
        gaze,
    })
}

fn check_rate(
    name: &str,
    v: Option<f64>,
    positive: bool,
    field: &FieldErr,
) -> Result<Option<f64>, TaskError> {
    use crate::fatigue::ma::{K_MAX_PER_MIN, K_MIN_PER_MIN, R_MAX_PER_MIN};
    match v {
        Some(x) if positive && x.is_finite() && (K_MIN_PER_MIN..=K_MAX_PER_MIN).contains(&x) => {
            Ok(Some(x))
        }
        Some(x) if !positive && x.is_finite() && (0.0..=R_MAX_PER_MIN).contains(&x) => Ok(Some(x)),
        Some(x) => Err(field(
            name,
            if positive {
                format!("must be within {K_MIN_PER_MIN}..{K_MAX_PER_MIN} 1/min, got {x}")
            } else {
                format!("must be within 0..{R_MAX_PER_MIN} 1/min, got {x}")
            },
        )),
        None => Ok(None),
    }
}

/// The worker a generated URDF was made for (sex, stature, mass), from its header comment.
fn generated_for(urdf: &str) -> Option<(String, f64, f64)> {
    let line = urdf
        .lines()
        .take(5)
        .find(|l| l.contains("Generated by posture-opt:"))?;
    let rest = line.split("Generated by posture-opt:").nth(1)?;
    let mut parts = rest.split(',').map(str::trim);
    let sex = parts.next()?.to_string();
    let stature = parts
        .next()?
        .strip_prefix("stature ")?
        .strip_suffix(" m")?
        .parse()
        .ok()?;
    let mass = parts
        .next()?
        .strip_prefix("mass ")?
        .strip_suffix(" kg")?
        .parse()
        .ok()?;
    Some((sex, stature, mass))
}

/// Fatigue parameters per half-joint from the task's `fatigue` section.
fn resolve_fatigue(
    ff: &FatigueFile,
    file_set: Option<ParameterSet>,
    half_joints: &[HalfJoint],
    worker: &Worker,
    field: &FieldErr,
) -> Result<(Vec<MaParams>, FatigueChoice, Option<ParameterSet>), TaskError> {
    let sets = ParameterSets::shipped();
    let legacy = ff.parameters.is_none()
        && ff.recovery.is_none()
        && (ff.k_per_min.is_some() || ff.recovery_per_min.is_some());
    let set_name = ff.parameters.clone().unwrap_or(sets.default_set.clone());
    let set = if let Some(fs) = file_set {
        Some(fs)
    } else if legacy {
        None
    } else {
        Some(sets.get(&set_name).cloned().ok_or_else(|| {
            field(
                "fatigue.parameters",
                format!(
                    "unknown parameter set '{set_name}'{}; choose one of: {}",
                    crate::schema::did_you_mean(&set_name, sets.names().into_iter()),
                    sets.names().join(", ")
                ),
            )
        })?)
    };
    let k0 = check_rate("fatigue.k_per_min", ff.k_per_min, true, field)?;
    let r0 = check_rate(
        "fatigue.recovery_per_min",
        ff.recovery_per_min,
        false,
        field,
    )?;
    let rec_override = match ff.recovery {
        Some(r) => {
            let rec = Recovery::Perfusion {
                rest_per_min: r.rest_per_min,
                limit_fmvc: r.limit_fmvc,
            };
            rec.validate()
                .map_err(|e| field("fatigue.recovery", e.to_string()))?;
            Some(rec)
        }
        None => None,
    };
    for key in ff.overrides.keys() {
        if !half_joints.iter().any(|h| &h.id == key || &h.region == key) {
            let names = half_joints
                .iter()
                .map(|h| h.region.as_str())
                .chain(half_joints.iter().map(|h| h.id.as_str()));
            return Err(field(
                &format!("fatigue.overrides.{key}"),
                format!(
                    "is neither a body region nor a half-joint id of the model{}",
                    crate::schema::did_you_mean(key, names)
                ),
            ));
        }
    }
    let mut out = Vec::with_capacity(half_joints.len());
    for h in half_joints {
        let (mut k, mut rec) = match &set {
            Some(s) => (
                s.k(&h.region, worker.sex, crate::fatigue::params::Bound::Value),
                s.recovery.recovery(),
            ),
            None => (1.0, Recovery::None),
        };
        if let Some(x) = k0 {
            k = x;
        }
        if let Some(r) = r0 {
            rec = if r == 0.0 {
                Recovery::None
            } else {
                Recovery::Constant { r_per_min: r }
            };
        }
        if let Some(r) = rec_override {
            rec = r;
        }
        for key in [&h.region, &h.id] {
            if let Some(o) = ff.overrides.get(key) {
                if let Some(x) = check_rate(
                    &format!("fatigue.overrides.{key}.k_per_min"),
                    o.k_per_min,
                    true,
                    field,
                )? {
                    k = x;
                }
                if let Some(x) = check_rate(
                    &format!("fatigue.overrides.{key}.recovery_per_min"),
                    o.recovery_per_min,
                    false,
                    field,
                )? {
                    rec = if x == 0.0 {
                        Recovery::None
                    } else {
                        Recovery::Constant { r_per_min: x }
                    };
                }
            }
        }
        out.push(MaParams::with_recovery(k, rec).map_err(|e| field("fatigue", e.to_string()))?);
    }
    let choice = match &set {
        Some(s) => FatigueChoice {
            set: s.name.clone(),
            description: s.description.clone(),
            k_source: s.k_source.clone(),
            recovery_source: match (&s.recovery, &s.recovery_source) {
                (crate::fatigue::params::RecoverySpec::None, _) => {
                    "no recovery (Ma et al. 2009)".into()
                }
                (_, Some(own)) => own.clone(),
                _ => sets
                    .recovery_sources
                    .values()
                    .cloned()
                    .collect::<Vec<_>>()
                    .join("; "),
            },
        },
        None => FatigueChoice {
            set: "legacy".into(),
            description: "an older task file's single k and constant recovery rate (acting under load as at rest)".into(),
            k_source: "task file".into(),
            recovery_source: "task file (constant rate)".into(),
        },
    };
    Ok((out, choice, set))
}

/// Checks a task's gravity: finite, between [`MIN_GRAVITY_M_S2`] and [`MAX_GRAVITY_M_S2`], and
/// within [`MAX_GRAVITY_TILT_DEG`] of straight down (−z).
pub fn check_gravity(g: [f64; 3]) -> Result<Vector3<f64>, String> {
    let v = Vector3::from(g);
    let norm = v.norm();
    if !(g.iter().all(|x| x.is_finite()) && (MIN_GRAVITY_M_S2..=MAX_GRAVITY_M_S2).contains(&norm)) {
        return Err(format!(
            "must be finite with a magnitude within {MIN_GRAVITY_M_S2:.3}..{MAX_GRAVITY_M_S2:.2} m/s² (0.1 to 3 g), got {g:?}"
        ));
    }
    let tilt_deg = (-v.z / norm).clamp(-1.0, 1.0).acos().to_degrees();
    if tilt_deg > MAX_GRAVITY_TILT_DEG {
        return Err(format!(
            "must point down (−z: the world frame has z up and the floor at z = 0), within {MAX_GRAVITY_TILT_DEG}° of vertical; {g:?} is {tilt_deg:.1}° from straight down"
        ));
    }
    Ok(v)
}

/// Lateral distance between the sole centres a placed stance keeps within \[m\] (see
/// `docs/worker.md`, "Stepping and turning").
pub const STANCE_WIDTH_RANGE_M: (f64, f64) = (0.15, 0.60);

/// Largest fore-aft offset between the sole centres of a placed stance \[m\].
pub const STANCE_STAGGER_MAX_M: f64 = 0.40;

/// The left foot's yaw minus the right's in a placed stance \[deg\] (toe-out positive).
pub const STANCE_RELATIVE_YAW_RANGE_DEG: (f64, f64) = (-10.0, 60.0);

/// Where the planner may place the feet: the task's standing area and the human ranges of a
/// stance, widened to hold the nominal stance when it lies outside them.
fn placement(
    pts: &[[f64; 2]],
    sf: &StanceFile,
    nominal: &Stance,
    width_m: f64,
    field: &dyn Fn(&str, String) -> TaskError,
) -> Result<Placement, TaskError> {
    let area: Vec<Vector2<f64>> = {
        if pts.len() < 3 || pts.len() > 32 {
            return Err(field(
                "stance.area_m",
                format!("needs 3 to 32 corners (x, y) in order, got {}", pts.len()),
            ));
        }
        if let Some((i, p)) = pts.iter().enumerate().find(|(_, p)| {
            !(p[0].is_finite() && p[1].is_finite() && p[0].abs() <= 10.0 && p[1].abs() <= 10.0)
        }) {
            return Err(field(
                &format!("stance.area_m[{i}]"),
                format!("must be finite and within ±10 m, got {p:?}"),
            ));
        }
        let v: Vec<Vector2<f64>> = pts.iter().map(|p| Vector2::new(p[0], p[1])).collect();
        // convex, in order: every turn has the same sign and none is degenerate
        let n = v.len();
        let turns: Vec<f64> = (0..n)
            .map(|i| {
                let (a, b, c) = (v[i], v[(i + 1) % n], v[(i + 2) % n]);
                (b - a).perp(&(c - b))
            })
            .collect();
        let convex = turns.iter().all(|t| *t > 1e-9) || turns.iter().all(|t| *t < -1e-9);
        // a simple convex polygon turns once (a star's edges turn twice or more)
        let turning: f64 = (0..n)
            .map(|i| {
                let (a, b, c) = (v[i], v[(i + 1) % n], v[(i + 2) % n]);
                let (u, w) = (b - a, c - b);
                u.perp(&w).atan2(u.dot(&w))
            })
            .sum();
        if !convex || (turning.abs() - std::f64::consts::TAU).abs() > 1e-6 {
            return Err(field(
            "stance.area_m",
            "must be a convex polygon with its corners in order (no three in line, no crossing edges); give the convex part of the floor the worker uses".into(),
        ));
        }
        v
    };
    let nominal_relative_yaw_deg = 2.0 * sf.toe_out_deg;
    let p = Placement::new(
        &area,
        (
            STANCE_WIDTH_RANGE_M.0.min(width_m),
            STANCE_WIDTH_RANGE_M.1.max(width_m),
        ),
        STANCE_STAGGER_MAX_M,
        (
            STANCE_RELATIVE_YAW_RANGE_DEG
                .0
                .min(nominal_relative_yaw_deg)
                .to_radians(),
            STANCE_RELATIVE_YAW_RANGE_DEG
                .1
                .max(nominal_relative_yaw_deg)
                .to_radians(),
        ),
    );
    // the rest posture stands on the nominal stance: its soles must be in the area
    for c in &nominal.support_polygon_m {
        if p.area_edges().any(|(nrm, d)| nrm.dot(c) > d + 1e-9) {
            return Err(field(
                "stance.area_m",
                format!(
                    "must hold the stance's soles (the worker rests there between cycles): the sole corner ({:.3}, {:.3}) m is outside",
                    c.x, c.y
                ),
            ));
        }
    }
    Ok(p)
}

/// The seat of a task, checked: the generated worker's pelvis rests on it.
fn seat(
    sf: &SeatFile,
    model: &BodyModel,
    worker: &Worker,
    generated: bool,
    field: &dyn Fn(&str, String) -> TaskError,
) -> Result<Seat, TaskError> {
    let pelvis = model.frame_link("pelvis").ok().filter(|_| generated).ok_or_else(|| {
        field(
            "seat",
            "only the generated worker sits (its pelvis rests on the seat): leave robot out, or use a robot file posture-opt generated".into(),
        )
    })?;
    if !(sf.height_m.is_finite() && (0.25..=1.0).contains(&sf.height_m)) {
        return Err(field(
            "seat.height_m",
            format!("must be within 0.25..1.0 m, got {}", sf.height_m),
        ));
    }
    for (i, x) in sf.position_m.iter().enumerate() {
        if !(x.is_finite() && x.abs() <= 2.0) {
            return Err(field(
                &format!("seat.position_m[{i}]"),
                format!("must be within ±2 m, got {x}"),
            ));
        }
    }
    let [depth, width] = sf.size_m.unwrap_or([0.40, 0.45]);
    for (name, x) in [("seat.size_m[0]", depth), ("seat.size_m[1]", width)] {
        if !(x.is_finite() && (0.2..=1.0).contains(&x)) {
            return Err(field(name, format!("must be within 0.2..1.0 m, got {x}")));
        }
    }
    if !(sf.yaw_deg.is_finite() && sf.yaw_deg.abs() <= 180.0) {
        return Err(field(
            "seat.yaw_deg",
            format!("must be within −180..180°, got {}", sf.yaw_deg),
        ));
    }
    Ok(Seat::new(
        pelvis,
        Vector3::new(0.0, 0.0, -ISCHIA_BELOW_HIPS_PER_STATURE * worker.stature_m),
        sf.height_m,
        nalgebra::Vector2::new(sf.position_m[0], sf.position_m[1]),
        [depth, width],
        sf.yaw_deg.to_radians(),
    ))
}

/// Refuses a seat the worker cannot sit on with the feet on the stance: a top above the
/// standing hips (the legs straight), or an outline farther from either sole centre than the
/// legs reach from a pelvis resting on it (thigh and shank straight, from the hip above the seat's
/// nearest point to the ankle).
fn seat_within_reach_of_the_feet(
    seat: &Seat,
    stance: &Stance,
    worker: &Worker,
    field: &dyn Fn(&str, String) -> TaskError,
) -> Result<(), TaskError> {
    let g = worker_geometry(worker);
    let hips_seated_m = seat.height_m - seat.contact_in_link_m.z;
    if hips_seated_m >= g.hip_height_m {
        return Err(field(
            "seat.height_m",
            format!(
                "{} m is too high to sit on: the worker's hips would be {hips_seated_m:.2} m above the floor, higher than the {:.2} m they stand at (lower the seat below {:.2} m)",
                seat.height_m,
                g.hip_height_m,
                g.hip_height_m + seat.contact_in_link_m.z
            ),
        ));
    }
    let legs_m = g.hip_height_m - g.ankle_height_m;
    let drop_m = hips_seated_m - g.ankle_height_m;
    let reach_m = (legs_m * legs_m - drop_m * drop_m).max(0.0).sqrt();
    for (i, foot) in stance.feet.iter().enumerate() {
        let sole = stance.world_from_foot[i] * nalgebra::Point3::from(foot.sole_center_in_link_m);
        let p = nalgebra::Vector2::new(sole.x, sole.y);
        // distance from the sole centre to the seat's outline (0 inside)
        let nearest = seat
            .outline_m
            .iter()
            .enumerate()
            .map(|(k, a)| {
                let b = seat.outline_m[(k + 1) % seat.outline_m.len()];
                let t = ((p - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
                (p - (a + t * (b - a))).norm()
            })
            .fold(f64::INFINITY, f64::min);
        let d = if seat.margin_m(&p) >= 0.0 {
            0.0
        } else {
            nearest
        };
        if d > reach_m + foot.half_length_m {
            return Err(field(
                "seat.position_m",
                format!(
                    "the seat is {d:.2} m from the {} foot's place on the stance, but seated the worker's legs reach {:.2} m: move the seat or the stance (stance.forward_m) closer",
                    if i == 0 { "left" } else { "right" },
                    reach_m + foot.half_length_m
                ),
            ));
        }
    }
    Ok(())
}

impl Task {
    /// The worker sits on a seat.
    pub fn seated(&self) -> bool {
        self.stance.as_ref().is_some_and(|st| st.seat.is_some())
    }

    /// What carries the worker, for sentences: "the seat and the feet" or "the feet".
    pub fn supports(&self) -> &'static str {
        if self.seated() {
            "the seat and the feet"
        } else {
            "the feet"
        }
    }

    /// The same task with the feet held on the nominal stance in every phase.
    pub fn with_fixed_feet(&self) -> Task {
        let mut t = self.clone();
        if let Some(st) = t.stance.as_mut() {
            st.placement = None;
        }
        t
    }
}

/// The head's eyes: where they are and where they look, in the `head` link's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Head {
    pub link: usize,
    /// The point between the eyes \[m\]: the front of the head's shape at its middle height.
    pub eye_in_link_m: Vector3<f64>,
    /// The normal line of sight (unit): [`LINE_OF_SIGHT_BELOW_DEG`] below the head's forward x.
    pub sight_in_link: Vector3<f64>,
}

/// The normal line of sight lies this far below the head's horizontal \[deg\]: 15° (MIL-STD-1472,
/// the normal line of sight 10-15° below the horizontal; Grandjean, Fitting the Task to the Man).
pub const LINE_OF_SIGHT_BELOW_DEG: f64 = 15.0;

/// The eyes move comfortably this far about the normal line of sight \[deg\] (MIL-STD-1472:
/// optimum eye rotation ±15°); a gaze point beyond it turns the head.
pub const GAZE_CONE_HALF_ANGLE_DEG: f64 = 15.0;

impl Head {
    /// The head of `model`: its link named `head` with a collision shape (the generated
    /// worker's), `None` otherwise.
    pub fn of(model: &BodyModel) -> Option<Head> {
        let link = model.frame_link("head").ok()?;
        let c = model.links[link].capsules.first()?;
        let mid = (c.a.coords + c.b.coords) / 2.0;
        let down = LINE_OF_SIGHT_BELOW_DEG.to_radians();
        Some(Head {
            link,
            eye_in_link_m: mid + Vector3::x() * (0.8 * c.radius_m),
            sight_in_link: Vector3::new(down.cos(), 0.0, -down.sin()),
        })
    }
}
