//! The plan document: what `posture-opt plan --json` prints (contract in `docs/interface.md`).
//!
//! Per-step results are columns: `steps` holds one array per quantity, and the per-joint or
//! per-half-joint ones are arrays of rows ordered like `joints` or `half_joint_ids`. Torques,
//! loads and strengths depend only on the posture and the hand forces, so they live with the
//! `postures` that steps refer to by index.

use crate::fatigue::{MaParams, MaState, PreparedHold, Recovery};
use crate::plan::search::SearchStats;
use crate::plan::sqp::SqpOutcome;
use serde::Serialize;
use std::collections::HashMap;

/// One half-joint (muscle group) of the plan.
#[derive(Debug, Clone, Serialize)]
pub struct HalfJointInfo {
    pub id: String,
    pub joint: String,
    pub direction: String,
    /// The muscle group in words ("right shoulder flexors").
    pub group: String,
    pub region: String,
    /// MVC at the reference posture \[N·m\] for this worker.
    pub mvc_nm: f64,
    pub k_per_min: f64,
    pub recovery: Recovery,
    /// Recovery rate at rest \[1/min\].
    pub recovery_per_min: f64,
    /// The largest load held forever (0 without recovery).
    pub sustainable_load: f64,
    pub strength_source: String,
}

/// A posture held in the plan, with its statics for the hand forces of the phase it serves.
#[derive(Debug, Clone, Serialize)]
pub struct PostureRecord {
    pub phase: String,
    /// Time it was planned \[s\].
    pub planned_at_s: f64,
    pub q_rad: Vec<f64>,
    /// Holding torque per joint \[N·m\] (unactuated joints ≈ 0: balance).
    pub torque_nm: Vec<f64>,
    /// Relative load per half-joint.
    pub load: Vec<f64>,
    /// MVC per half-joint at this posture \[N·m\].
    pub mvc_nm: Vec<f64>,
    /// Hand positions (right, left) \[m\]; null for a hand the body lacks.
    pub hand_position_m: [Option<[f64; 3]>; 2],
    pub hand_force_n: [[f64; 3]; 2],
    /// Centre of pressure \[m\] and balance margin \[m\], share of the weight on the left foot.
    pub centre_of_pressure_m: Option<[f64; 2]>,
    pub balance_margin_m: Option<f64>,
    pub left_foot_share: Option<f64>,
    /// Share of the weight on the seat (a seated worker; absent when standing).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seat_share: Option<f64>,
    /// Centre of mass of the body \[m\].
    pub centre_of_mass_m: [f64; 3],
}

/// The held steps, as columns.
///
/// Capacity and U at each step's end are not stored: they are replayed from the state at the
/// start with the exact update of each step ([`MaParams::hold`] with its posture's loads and its
/// duration, the same operations in the same order as the plan's own run, so bit for bit the
/// same numbers), so that a plan's memory does not grow with its number of steps beyond a few
/// numbers per step. [`Steps::replay`] walks them; the plan document serialises them as the
/// columns `capacity` and `fatigue_u_min`.
#[derive(Debug, Clone, Default)]
pub struct Steps {
    pub t_s: Vec<f64>,
    pub duration_s: Vec<f64>,
    pub cycle: Vec<u32>,
    /// Index into `postures`.
    pub posture: Vec<usize>,
    /// Index into `phase_names`.
    phase: Vec<u32>,
    phase_names: Vec<String>,
    /// Per half-joint: its parameters and its state when the first step starts.
    params: Vec<MaParams>,
    start: Vec<MaState>,
    /// Per posture (as `postures`), the relative load of each half-joint.
    loads: Vec<Vec<f64>>,
}

impl Steps {
    /// No steps yet: a run of the half-joints `params` from `start`, whose steps are named from
    /// `phase_names`. The postures' loads are given once the run is over
    /// ([`Steps::set_posture_loads`]).
    pub fn new(params: Vec<MaParams>, start: Vec<MaState>, phase_names: Vec<String>) -> Self {
        Steps {
            params,
            start,
            phase_names,
            ..Default::default()
        }
    }

    /// Appends a step: its start, duration, cycle, posture index and phase (an index into the
    /// names given to [`Steps::new`]).
    pub fn push(&mut self, t_s: f64, duration_s: f64, cycle: u32, posture: usize, phase: usize) {
        self.t_s.push(t_s);
        self.duration_s.push(duration_s);
        self.cycle.push(cycle);
        self.posture.push(posture);
        self.phase.push(phase as u32);
    }

    /// The relative load of each half-joint in each posture the steps refer to (the plan's
    /// `postures`, in order), from which capacity and U are replayed.
    pub fn set_posture_loads(&mut self, loads: Vec<Vec<f64>>) {
        self.loads = loads;
    }

    /// Number of steps.
    pub fn len(&self) -> usize {
        self.t_s.len()
    }

    pub fn is_empty(&self) -> bool {
        self.t_s.is_empty()
    }

    /// The phase of step `i` ("rest" for the rest between cycles).
    pub fn phase(&self, i: usize) -> &str {
        &self.phase_names[self.phase[i] as usize]
    }

    /// Half-joint `h`'s state at the end of each step, in order, with the step's end time \[s\]
    /// (the same numbers as [`Steps::replay`]'s, for one half-joint only).
    pub fn course(&self, h: usize) -> impl Iterator<Item = (f64, MaState)> + '_ {
        let p = self.params[h];
        let mut state = self.start[h];
        let mut prepared = HashMap::new();
        (0..self.len()).map(move |i| {
            let (posture, d) = (self.posture[i], self.duration_s[i]);
            prepared
                .entry((posture, d.to_bits()))
                .or_insert_with(|| p.prepare(self.loads[posture][h], d))
                .hold(&mut state);
            (self.t_s[i] + d, state)
        })
    }

    /// The half-joints' states at each step's end, in order.
    pub fn replay(&self) -> Replay<'_> {
        Replay {
            steps: self,
            next: 0,
            state: self.start.clone(),
            prepared: HashMap::new(),
        }
    }
}

/// The half-joints' states at the end of each step in turn ([`Steps::replay`]).
#[derive(Debug, Clone)]
pub struct Replay<'a> {
    steps: &'a Steps,
    next: usize,
    state: Vec<MaState>,
    /// Each posture held for each duration, prepared once (the updates are `MaParams::hold`'s,
    /// bit for bit): a long task holds a few of them thousands of times over.
    prepared: HashMap<(usize, u64), Vec<PreparedHold>>,
}

impl Replay<'_> {
    /// The state at the end of the next step (per half-joint), or None after the last.
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> Option<&[MaState]> {
        let st = self.steps;
        let i = self.next;
        if i >= st.len() {
            return None;
        }
        self.next += 1;
        let (posture, d) = (st.posture[i], st.duration_s[i]);
        let holds = self
            .prepared
            .entry((posture, d.to_bits()))
            .or_insert_with(|| {
                st.params
                    .iter()
                    .zip(&st.loads[posture])
                    .map(|(p, &f)| p.prepare(f, d))
                    .collect()
            });
        for (hold, s) in holds.iter().zip(self.state.iter_mut()) {
            hold.hold(s);
        }
        Some(&self.state)
    }
}

/// One column of replayed states, serialised as an array of rows as it is replayed.
struct ReplayedColumn<'a> {
    steps: &'a Steps,
    capacity: bool,
}

impl Serialize for ReplayedColumn<'_> {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let mut seq = ser.serialize_seq(Some(self.steps.len()))?;
        let mut r = self.steps.replay();
        let mut row = Vec::with_capacity(self.steps.params.len());
        while let Some(states) = r.next() {
            row.clear();
            row.extend(states.iter().map(|s| {
                if self.capacity {
                    s.capacity
                } else {
                    s.fatigue_u_min
                }
            }));
            seq.serialize_element(&row)?;
        }
        seq.end()
    }
}

/// The phase column, serialised as names.
struct PhaseColumn<'a>(&'a Steps);

impl Serialize for PhaseColumn<'_> {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        ser.collect_seq((0..self.0.len()).map(|i| self.0.phase(i)))
    }
}

impl Serialize for Steps {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = ser.serialize_struct("Steps", 7)?;
        st.serialize_field("t_s", &self.t_s)?;
        st.serialize_field("duration_s", &self.duration_s)?;
        st.serialize_field("phase", &PhaseColumn(self))?;
        st.serialize_field("cycle", &self.cycle)?;
        st.serialize_field("posture", &self.posture)?;
        st.serialize_field(
            "capacity",
            &ReplayedColumn {
                steps: self,
                capacity: true,
            },
        )?;
        st.serialize_field(
            "fatigue_u_min",
            &ReplayedColumn {
                steps: self,
                capacity: false,
            },
        )?;
        st.end()
    }
}

/// When a muscle group can no longer hold its load.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct Exhaustion {
    pub t_s: f64,
    pub half_joint: String,
    pub group: String,
    pub phase: String,
    pub load: f64,
    /// The load is above the group's strength from the first instant (load > capacity when the
    /// step starts): "exceeds strength (N % MVC)", not a time to exhaustion.
    pub exceeds_strength: bool,
}

impl Exhaustion {
    /// The verdict in words.
    pub fn describe(&self) -> String {
        if self.exceeds_strength {
            format!(
                "the load on the {} exceeds their strength ({:.0} % MVC) in '{}'",
                self.group,
                100.0 * self.load,
                self.phase
            )
        } else {
            format!(
                "{} exhausted at {:.0} s in '{}' (load {:.0} % MVC)",
                self.group,
                self.t_s,
                self.phase,
                100.0 * self.load
            )
        }
    }
}

/// A phase's posture in the last plan, and how it was found.
#[derive(Debug, Clone, Serialize)]
pub struct PhaseSummary {
    pub phase: String,
    pub q_rad: Vec<f64>,
    /// Largest hand error \[m\] (0 when on target).
    pub hand_error_m: f64,
    pub reachable: bool,
    /// How far a target lies beyond any posture's reach (farther from the feet, or the base,
    /// than the body's kinematic chain is long), when it does: then "out of reach" is proven.
    /// `None` for an unreached target within that length: the optimiser found no balanced
    /// posture that reaches it, which does not prove that none exists.
    pub beyond_reach_m: Option<f64>,
    /// The obstacle a target lies inside, if any.
    pub target_inside: Option<String>,
    /// Why a target next to an obstacle is provably beyond the hand's grip point (the obstacle,
    /// the distance, the hand's shape and the clearance, in words), if it is.
    pub target_blocked: Option<String>,
    pub min_clearance_m: f64,
    /// What the closest clearance is to (an obstacle or a body part).
    pub closest: Option<String>,
    pub balance_margin_m: Option<f64>,
    /// Where the feet stand and the steps and turn from the state before (the previous phase,
    /// or the rest stance before the first phase); `None` for a body without feet.
    pub feet: Option<crate::plan::stepping::PhaseFeet>,
    /// The acceptable zones of ISO 11226 / EN 1005-4 this phase's posture goes beyond (by more
    /// than half a degree), with the limit for its hold. With the zones kept (the default) and
    /// the phase's solve converged, each is the smallest excess the targets allow.
    pub outside_zones: Vec<ZoneExcess>,
    /// The three most-loaded half-joints (relative load).
    pub most_loaded: Vec<(String, f64)>,
    /// Joints within 1 % of their range from a limit.
    pub at_limits: Vec<String>,
    pub discomfort: f64,
    pub converged: bool,
    pub kkt_residual: f64,
    pub iterations: usize,
    pub solve: SqpOutcome,
    pub search: SearchStats,
}

/// A posture beyond one of the acceptable zones ([`crate::plan::zones`]).
#[derive(Debug, Clone, Serialize)]
pub struct ZoneExcess {
    /// What goes beyond the zone, in words ("right upper arm raised from the vertical").
    pub what: String,
    pub angle_deg: f64,
    /// The zone's limit for this phase's hold \[deg\].
    pub limit_deg: f64,
    /// How long the posture is held without a break \[s\] (a movement at 4 s or less).
    pub hold_s: f64,
    /// "ISO 11226" or "EN 1005-4".
    pub source: String,
}

/// A baseline plan's figures.
#[derive(Debug, Clone, Serialize)]
pub struct BaselineSummary {
    pub name: String,
    pub description: String,
    pub total_u: f64,
    pub duration_s: f64,
    pub exhaustion: Option<Exhaustion>,
    /// The plan's own objective (its first plan's: fresh, the whole task, held) at this
    /// baseline's postures; the plan's is the last of `passes`.
    pub objective: f64,
    /// posture-opt's total relative to this one's (−0.2 = 20 % less fatigue).
    pub change: f64,
}

/// The plan's summary.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub adaptive: bool,
    pub fatigue_only: bool,
    /// Whether the postures were kept within the acceptable zones (off with `--no-zones`).
    pub zones: bool,
    /// Whether each phase looked at its gaze point (off with `--no-gaze`; a phase with
    /// `gaze_free` or a body without a head looks at nothing either way).
    pub gaze: bool,
    pub duration_s: f64,
    pub planned_duration_s: f64,
    pub cycles_done: u32,
    pub total_u: f64,
    pub worst_half_joint: String,
    pub worst_u: f64,
    /// Lowest capacity at any time of the simulated task, and where.
    pub lowest_capacity: f64,
    pub lowest_capacity_half_joint: String,
    pub lowest_capacity_t_s: f64,
    /// Capacity of every half-joint at the end.
    pub final_capacity: Vec<f64>,
    pub exhaustion: Option<Exhaustion>,
    pub replans: u32,
    pub qp_solves: u64,
    pub sqp_iterations: u64,
    /// The objective after each coordination pass of the first plan (non-increasing).
    pub passes: Vec<f64>,
    pub phases: Vec<PhaseSummary>,
    pub rest_posture_rad: Vec<f64>,
    /// Clearance of the rest posture \[m\] and what it is to.
    pub rest_clearance_m: f64,
    pub rest_closest: Option<String>,
    /// How the feet get back to the rest stance from the last phase (`None` without feet).
    pub rest_feet: Option<crate::plan::stepping::PhaseFeet>,
    pub baselines: Vec<BaselineSummary>,
}

impl Summary {
    /// The feet's steps in one cycle: into each phase and back to the rest stance.
    pub fn steps_per_cycle(&self) -> u32 {
        self.phases
            .iter()
            .filter_map(|p| p.feet.as_ref())
            .chain(self.rest_feet.as_ref())
            .map(|f| f.steps)
            .sum()
    }
}

/// A plan.
#[derive(Debug, Clone, Serialize)]
pub struct Plan {
    pub task: String,
    pub robot: String,
    pub hand_frames: [Option<String>; 2],
    pub fatigue_model: String,
    pub fatigue_parameters: crate::plan::task::FatigueChoice,
    pub joints: Vec<String>,
    pub half_joint_ids: Vec<String>,
    pub half_joints: Vec<HalfJointInfo>,
    pub postures: Vec<PostureRecord>,
    pub steps: Steps,
    pub summary: Summary,
}

impl PhaseSummary {
    /// What makes this phase impossible as planned, in words: a target out of reach or inside an
    /// obstacle, a collision (body or held object), a loss of balance.
    pub fn problems(&self) -> Vec<String> {
        let mut v = Vec::new();
        if !self.reachable {
            v.push(match &self.target_inside {
                Some(o) => format!("'{}': the target lies inside '{o}'", self.phase),
                None if self.target_blocked.is_some() => format!(
                    "'{}': the hand cannot bring its grip point to the target: {}",
                    self.phase,
                    self.target_blocked.as_deref().unwrap_or_default()
                ),
                None if self.beyond_reach_m.is_some() => format!(
                    "'{}': the target is out of reach by {:.0} mm (standing where the task allows, balance kept; it is farther than the body is long)",
                    self.phase,
                    1000.0 * self.hand_error_m
                ),
                None => format!(
                    "'{}': the target was not reached, {:.0} mm short (standing where the task allows, balance kept; no posture that reaches it was found, though it is within the body's length)",
                    self.phase,
                    1000.0 * self.hand_error_m
                ),
            });
        }
        if self.min_clearance_m < 0.0 {
            v.push(format!(
                "'{}': collision, {:.0} mm deep ({})",
                self.phase,
                -1000.0 * self.min_clearance_m,
                self.closest.as_deref().unwrap_or("an obstacle")
            ));
        }
        if let Some(m) = self.balance_margin_m.filter(|m| *m < 0.0) {
            v.push(format!(
                "'{}': off balance, the centre of pressure {:.0} mm outside the feet",
                self.phase,
                -1000.0 * m
            ));
        }
        v
    }
}

impl Plan {
    /// Everything that makes the plan impossible as planned, in words (empty: none): every
    /// phase's problems and a rest posture that collides.
    pub fn problems(&self) -> Vec<String> {
        let s = &self.summary;
        let mut v: Vec<String> = s.phases.iter().flat_map(PhaseSummary::problems).collect();
        if s.rest_clearance_m < 0.0 {
            v.push(format!(
                "rest posture: collision, {:.0} mm deep ({})",
                -1000.0 * s.rest_clearance_m,
                s.rest_closest.as_deref().unwrap_or("an obstacle")
            ));
        }
        v
    }

    /// Index of a half-joint by id.
    pub fn half_joint(&self, id: &str) -> Option<usize> {
        self.half_joint_ids.iter().position(|h| h == id)
    }

    /// Index of a joint by name.
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j == name)
    }

    /// Relative load of half-joint `h` during step `i`.
    pub fn step_load(&self, i: usize, h: usize) -> f64 {
        self.postures[self.steps.posture[i]].load[h]
    }
}
