// Index loops over parallel per-joint / per-half-joint arrays read clearer than zipped iterators.
#![allow(clippy::needless_range_loop)]
//! The planning loop: optimise → hold → update fatigue exactly → re-plan as capacity falls.
//!
//! Each cycle holds every phase's posture for its duration (one [`Step`] per phase) and then
//! rests (arms hanging, no load). Every half-joint's capacity and U are updated with the exact
//! closed forms of the fatigue model for the step's constant load. The adaptive planner solves
//! with the whole remaining task as horizon and re-plans at the start of a cycle when the
//! re-plan interval has passed **and** some capacity has moved by more than the tolerance since
//! the last plan. The baseline (`--no-adapt`) is the same optimiser with fatigue ignored: fresh
//! capacities, a one-cycle horizon, solved once and held all task.

use crate::body::{holding_torques, StaticsData};
use crate::fatigue::{MaParams, MaState};
use crate::optim::{
    solve_phase, FatigueObjective, PhaseInput, PhaseSolution, QpError, SqpSettings, SqpWork,
};
use crate::rula::{self, Rula, RulaActivity, RulaPosture};
use crate::task::Task;
use nalgebra::Vector3;
use serde::Serialize;
use std::collections::BTreeMap;

/// Why planning failed (an internal failure: the task was already validated).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    #[error("optimiser failed in phase '{phase}': {source}")]
    Qp { phase: String, source: QpError },
}

#[derive(Debug, Clone, Serialize)]
pub struct HalfJointInfo {
    pub id: String,
    pub joint: String,
    pub direction: String,
    pub group: String,
    pub region: String,
    pub mvc_nm: f64,
    pub k_per_min: f64,
    pub recovery_per_min: f64,
    pub source: String,
}

/// One held posture with constant load.
#[derive(Debug, Clone, Serialize)]
pub struct Step {
    pub t_s: f64,
    pub duration_s: f64,
    pub phase: String,
    pub cycle: u32,
    pub q_rad: BTreeMap<String, f64>,
    pub hand_position_m: [f64; 3],
    pub target_position_m: Option<[f64; 3]>,
    pub hand_force_n: [f64; 3],
    pub torque_nm: BTreeMap<String, f64>,
    /// Relative load of each half-joint during the step.
    pub load: BTreeMap<String, f64>,
    pub capacity: BTreeMap<String, f64>,
    pub fatigue_u: BTreeMap<String, f64>,
    /// Posture-dependent MVCs of the step [N·m] (only half-joints whose strength varies).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub mvc_nm: BTreeMap<String, f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Exhaustion {
    pub t_s: f64,
    pub half_joint: String,
    pub group: String,
    pub phase: String,
    pub load: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct PhaseSummary {
    pub phase: String,
    /// Posture of the last plan \[rad\].
    pub q_rad: BTreeMap<String, f64>,
    pub hand_error_m: f64,
    pub reachable: bool,
    pub min_clearance_m: f64,
    /// The three most-loaded half-joints (relative load), in the last plan's posture.
    pub most_loaded: Vec<(String, f64)>,
    /// RULA of the posture (default worker body only; `None` for other bodies).
    pub rula: Option<Rula>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub adaptive: bool,
    pub duration_s: f64,
    pub planned_duration_s: f64,
    pub cycles_done: u32,
    pub total_u: f64,
    pub worst_half_joint: String,
    pub worst_u: f64,
    /// Lowest capacity at the end of the simulated task.
    pub min_capacity: f64,
    pub min_capacity_half_joint: String,
    pub exhaustion: Option<Exhaustion>,
    pub replans: u32,
    pub qp_solves: u64,
    pub sqp_iterations: u64,
    pub phases: Vec<PhaseSummary>,
    /// Highest RULA grand score over the phases (default worker body only).
    pub rula_max: Option<i32>,
    /// Filled by [`plan_with_baseline`]: the baseline's total U and the relative change.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub baseline_total_u: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub change_vs_baseline: Option<f64>,
    /// The baseline's simulated duration and exhaustion (a plan that exhausts ends early, so
    /// its total U is over a shorter time: compare exhaustion times first).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub baseline_duration_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub baseline_exhaustion_t_s: Option<f64>,
}

/// A plan: the DESIGN §6 `plan` document.
#[derive(Debug, Clone, Serialize)]
pub struct Plan {
    pub task: String,
    pub robot: String,
    pub hand_frame: String,
    pub fatigue_model: String,
    pub half_joints: Vec<HalfJointInfo>,
    pub steps: Vec<Step>,
    pub summary: Summary,
}

impl Plan {
    /// Lowest capacity at any time of the plan and its half-joint (step ends suffice: capacity
    /// is monotone within a held step). 1 and "" for a plan without steps.
    pub fn lowest_capacity(&self) -> (f64, String) {
        self.steps.iter().flat_map(|st| st.capacity.iter()).fold(
            (1.0_f64, String::new()),
            |a, (h, &c)| {
                if c < a.0 {
                    (c, h.clone())
                } else {
                    a
                }
            },
        )
    }
}

/// The planner for one task: owns the statics workspace, the SQP buffers and the QP solver.
pub struct Planner<'t> {
    task: &'t Task,
    pub settings: SqpSettings,
    data: StaticsData,
    work: SqpWork,
    /// Phase postures of the previous plan: the next plan's first guess (warm start).
    warm_start: Option<Vec<Vec<f64>>>,
}

struct Ctx {
    state: Vec<MaState>,
    q_phase: Vec<Vec<f64>>,
    f_phase: Vec<Vec<f64>>,
    f_rest: Vec<f64>,
    sols: Vec<PhaseSolution>,
    replans: u32,
    sqp_iterations: u64,
}

impl<'t> Planner<'t> {
    pub fn new(task: &'t Task) -> Self {
        let settings = SqpSettings::default();
        Planner {
            task,
            settings,
            data: StaticsData::new(&task.model),
            work: SqpWork::new(&task.model, &settings),
            warm_start: None,
        }
    }

    /// Interior-point iterations of all QP solves so far.
    pub fn ipm_iterations(&self) -> u64 {
        self.work.qp.ipm_iterations
    }

    fn loads_at(&mut self, q: &[f64], force: &Vector3<f64>, out: &mut [f64]) {
        let t = self.task;
        holding_torques(
            &t.model,
            &mut self.data,
            q,
            t.hand_link,
            force,
            &t.gravity_m_s2,
        );
        for (i, h) in t.half_joints.iter().enumerate() {
            out[i] = h.load(self.data.tau_nm[h.q_index], q[h.q_index]);
        }
    }

    /// Initial posture guess: upper arm forward and elbow bent (away from singular straight arm).
    fn initial_guess(&self) -> Vec<f64> {
        let m = &self.task.model;
        let mut q = vec![0.0; m.nq()];
        for (i, v) in q.iter_mut().enumerate() {
            let j = m.q_joint(i);
            let guess: f64 = if j.name.contains("elbow") {
                1.0
            } else if j.name.contains("shoulder_flexion") {
                0.6
            } else {
                0.0
            };
            *v = guess.clamp(j.lower_rad, j.upper_rad);
        }
        q
    }

    /// Solves every phase's posture for the given state and horizon (cycles).
    fn replan(&mut self, ctx: &mut Ctx, fresh: bool, horizon_cycles: f64) -> Result<(), PlanError> {
        let t = self.task;
        let nh = t.half_joints.len();
        let fresh_state = vec![MaState::FRESH; nh];
        let st = if fresh { &fresh_state } else { &ctx.state };
        let w: Vec<f64> = t
            .phases
            .iter()
            .map(|p| p.duration_s * horizon_cycles / 60.0)
            .collect();
        let w_rest = t.rest_s * horizon_cycles / 60.0;
        let q_neutral = vec![0.0; t.model.nq()];
        let mut obj = FatigueObjective {
            params: t.fatigue.clone(),
            horizon_min: t.cycle_s() * horizon_cycles / 60.0,
            capacity: st.iter().map(|s| s.capacity).collect(),
            fatigue_u_min: st.iter().map(|s| s.fatigue_u_min).collect(),
            base_min: vec![0.0; nh],
            weight_min: 0.0,
        };
        // Phases with the same target and hand force have the same optimal posture: solve one
        // representative per group, with the group's combined hold time.
        let rep: Vec<usize> = (0..t.phases.len())
            .map(|p| {
                (0..=p)
                    .find(|&o| t.phases[o].same_work(&t.phases[p]))
                    .unwrap_or(p)
            })
            .collect();
        let sweeps = if ctx.replans == 0 { 2 } else { 1 };
        for _sweep in 0..sweeps {
            for p in (0..t.phases.len()).filter(|&p| rep[p] == p) {
                let group_w: f64 = (0..t.phases.len())
                    .filter(|&o| rep[o] == p)
                    .map(|o| w[o])
                    .sum();
                for h in 0..nh {
                    obj.base_min[h] = ctx.f_rest[h] * w_rest
                        + (0..t.phases.len())
                            .filter(|&o| rep[o] != p)
                            .map(|o| ctx.f_phase[o][h] * w[o])
                            .sum::<f64>();
                }
                obj.weight_min = group_w;
                let ph = &t.phases[p];
                let input = PhaseInput {
                    hand_link: t.hand_link,
                    target_m: ph.target_m,
                    force_on_hand_n: ph.hand_force_n,
                    gravity_m_s2: t.gravity_m_s2,
                    half_joints: &t.half_joints,
                    objective: &obj,
                    q_neutral_rad: &q_neutral,
                    workstation: &t.workstation,
                    settings: self.settings,
                };
                let sol = solve_phase(
                    &t.model,
                    &mut self.data,
                    &mut self.work,
                    &input,
                    &mut ctx.q_phase[p],
                )
                .map_err(|source| PlanError::Qp {
                    phase: ph.name.clone(),
                    source,
                })?;
                ctx.sqp_iterations += sol.iterations as u64;
                let q = ctx.q_phase[p].clone();
                let mut f = std::mem::take(&mut ctx.f_phase[p]);
                self.loads_at(&q, &ph.hand_force_n, &mut f);
                for o in (0..t.phases.len()).filter(|&o| rep[o] == p) {
                    ctx.sols[o] = sol;
                    if o != p {
                        ctx.q_phase[o] = q.clone();
                        ctx.f_phase[o] = f.clone();
                    }
                }
                ctx.f_phase[p] = f;
            }
        }
        ctx.replans += 1;
        Ok(())
    }

    fn names_map(&self, v: impl Iterator<Item = f64>) -> BTreeMap<String, f64> {
        (0..self.task.model.nq())
            .map(|i| self.task.model.q_joint(i).name.clone())
            .zip(v)
            .collect()
    }

    fn hj_map(&self, v: impl Iterator<Item = f64>) -> BTreeMap<String, f64> {
        self.task
            .half_joints
            .iter()
            .map(|h| h.id.clone())
            .zip(v)
            .collect()
    }

    /// Plans the task: adaptive (`adapt = true`) or the fatigue-unaware baseline.
    pub fn plan(&mut self, adapt: bool) -> Result<Plan, PlanError> {
        let t = self.task;
        let nh = t.half_joints.len();
        let n_ph = t.phases.len();
        let q_phase = match &self.warm_start {
            Some(w) => w.clone(),
            None => vec![self.initial_guess(); n_ph],
        };
        let mut ctx = Ctx {
            state: vec![MaState::FRESH; nh],
            q_phase,
            f_phase: vec![vec![0.0; nh]; n_ph],
            f_rest: vec![0.0; nh],
            sols: vec![PhaseSolution::default(); n_ph],
            replans: 0,
            sqp_iterations: 0,
        };
        let q_rest = vec![0.0; t.model.nq()];
        let mut f_rest = vec![0.0; nh];
        self.loads_at(&q_rest, &Vector3::zeros(), &mut f_rest);
        ctx.f_rest = f_rest;
        let qp_solves_before = self.work.qp.solves;

        if adapt {
            self.replan(&mut ctx, false, t.cycles as f64)?;
        } else {
            self.replan(&mut ctx, true, 1.0)?;
        }
        let mut last_plan_capacity: Vec<f64> = ctx.state.iter().map(|s| s.capacity).collect();
        let mut last_plan_cycle = 0u32;
        let mut last_plan_t = 0.0;

        let mut steps = Vec::with_capacity((t.cycles as usize) * (n_ph + 1));
        let mut time = 0.0;
        let mut exhaustion = None;
        let mut f = vec![0.0; nh];
        let mut cycles_done = 0;
        'cycles: for cycle in 0..t.cycles {
            if adapt && cycle > 0 {
                let interval_passed = match t.replan_every_s {
                    Some(s) => time - last_plan_t >= s,
                    None => cycle - last_plan_cycle >= t.replan_every_cycles,
                };
                let moved = ctx
                    .state
                    .iter()
                    .zip(&last_plan_capacity)
                    .any(|(s, c)| (s.capacity - c).abs() > t.capacity_tolerance);
                if interval_passed && moved {
                    self.replan(&mut ctx, false, (t.cycles - cycle) as f64)?;
                    last_plan_capacity = ctx.state.iter().map(|s| s.capacity).collect();
                    last_plan_cycle = cycle;
                    last_plan_t = time;
                }
            }
            let n_steps = n_ph + usize::from(t.rest_s > 0.0);
            for si in 0..n_steps {
                let (name, q, force, target, mut dur) = if si < n_ph {
                    let ph = &t.phases[si];
                    (
                        ph.name.clone(),
                        ctx.q_phase[si].clone(),
                        ph.hand_force_n,
                        Some(ph.target_m),
                        ph.duration_s,
                    )
                } else {
                    (
                        "rest".to_string(),
                        q_rest.clone(),
                        Vector3::zeros(),
                        None,
                        t.rest_s,
                    )
                };
                self.loads_at(&q, &force, &mut f);
                // Can every group hold its load for the whole step?
                let mut ex: Option<(f64, usize)> = None;
                for h in 0..nh {
                    if let Some(te) = t.fatigue[h].time_to_exhaustion_s(ctx.state[h].capacity, f[h])
                    {
                        if te < dur && ex.is_none_or(|(t0, _)| te < t0) {
                            ex = Some((te, h));
                        }
                    }
                }
                if let Some((te, h)) = ex {
                    dur = te;
                    exhaustion = Some(Exhaustion {
                        t_s: time + te,
                        half_joint: t.half_joints[h].id.clone(),
                        group: t.half_joints[h].group.clone(),
                        phase: name.clone(),
                        load: f[h],
                    });
                }
                for h in 0..nh {
                    MaParams::hold(&t.fatigue[h], &mut ctx.state[h], f[h], dur);
                }
                let mvc: BTreeMap<String, f64> = t
                    .half_joints
                    .iter()
                    .filter(|h| h.posture_slope_per_rad.is_some())
                    .map(|h| (h.id.clone(), h.mvc_at(q[h.q_index])))
                    .collect();
                steps.push(Step {
                    t_s: time,
                    duration_s: dur,
                    phase: name,
                    cycle,
                    q_rad: self.names_map(q.iter().copied()),
                    hand_position_m: [
                        self.data.hand_pos_m.x,
                        self.data.hand_pos_m.y,
                        self.data.hand_pos_m.z,
                    ],
                    target_position_m: target.map(|v| [v.x, v.y, v.z]),
                    hand_force_n: [force.x, force.y, force.z],
                    torque_nm: self.names_map(self.data.tau_nm.iter().copied()),
                    load: self.hj_map(f.iter().copied()),
                    capacity: self.hj_map(ctx.state.iter().map(|s| s.capacity)),
                    fatigue_u: self.hj_map(ctx.state.iter().map(|s| s.fatigue_u_min)),
                    mvc_nm: mvc,
                });
                time += dur;
                if exhaustion.is_some() {
                    break 'cycles;
                }
            }
            cycles_done = cycle + 1;
        }

        let (worst_h, worst_u) = ctx
            .state
            .iter()
            .enumerate()
            .map(|(h, s)| (h, s.fatigue_u_min))
            .fold((0, f64::MIN), |a, b| if b.1 > a.1 { b } else { a });
        let (minc_h, minc) = ctx
            .state
            .iter()
            .enumerate()
            .map(|(h, s)| (h, s.capacity))
            .fold((0, f64::MAX), |a, b| if b.1 < a.1 { b } else { a });
        let phases = (0..n_ph)
            .map(|p| {
                let mut loaded: Vec<(String, f64)> = t
                    .half_joints
                    .iter()
                    .zip(&ctx.f_phase[p])
                    .map(|(h, f)| (h.id.clone(), *f))
                    .collect();
                loaded.sort_by(|a, b| b.1.total_cmp(&a.1));
                loaded.truncate(3);
                let sol = ctx.sols[p];
                let ph = &t.phases[p];
                let repeats = t.phases.iter().filter(|o| o.same_work(ph)).count() as f64;
                let activity = RulaActivity {
                    load_kg: ph.hand_force_n.norm() / t.gravity_m_s2.norm().max(1e-9),
                    held_s: ph.duration_s,
                    repeats_per_min: repeats * 60.0 / t.cycle_s(),
                };
                let rula = RulaPosture::from_worker(&t.model, &mut self.data, &ctx.q_phase[p])
                    .ok()
                    .map(|posture| rula::score(&posture, &activity));
                PhaseSummary {
                    phase: t.phases[p].name.clone(),
                    q_rad: self.names_map(ctx.q_phase[p].iter().copied()),
                    hand_error_m: sol.hand_error_m,
                    reachable: sol.hand_error_m <= 0.01,
                    min_clearance_m: if sol.min_clearance_m.is_finite() {
                        sol.min_clearance_m
                    } else {
                        self.settings.clearance_horizon_m
                    },
                    most_loaded: loaded,
                    rula,
                }
            })
            .collect::<Vec<PhaseSummary>>();
        let rula_max = phases
            .iter()
            .filter_map(|p| p.rula.as_ref().map(|r| r.grand_score))
            .max();
        if self.warm_start.is_none() {
            self.warm_start = Some(ctx.q_phase.clone());
        }
        let any_recovery = t.fatigue.iter().any(|p| p.r_at(0.0) > 0.0);
        Ok(Plan {
            task: t.name.clone(),
            robot: t.robot.clone(),
            hand_frame: t.hand_frame.clone(),
            fatigue_model: if any_recovery {
                "ma2009+recovery".into()
            } else {
                "ma2009".into()
            },
            half_joints: t
                .half_joints
                .iter()
                .zip(&t.fatigue)
                .map(|(h, p)| HalfJointInfo {
                    id: h.id.clone(),
                    joint: h.joint.clone(),
                    direction: h.direction.symbol().into(),
                    group: h.group.clone(),
                    region: h.region.clone(),
                    mvc_nm: h.mvc_nm,
                    k_per_min: p.k_per_min,
                    recovery_per_min: p.r_at(0.0),
                    source: h.source.clone(),
                })
                .collect(),
            steps,
            summary: Summary {
                adaptive: adapt,
                duration_s: time,
                planned_duration_s: t.duration_s(),
                cycles_done,
                total_u: ctx.state.iter().map(|s| s.fatigue_u_min).sum(),
                worst_half_joint: t.half_joints[worst_h].id.clone(),
                worst_u,
                min_capacity: minc,
                min_capacity_half_joint: t.half_joints[minc_h].id.clone(),
                exhaustion,
                replans: ctx.replans,
                qp_solves: self.work.qp.solves - qp_solves_before,
                sqp_iterations: ctx.sqp_iterations,
                phases,
                rula_max,
                baseline_total_u: None,
                change_vs_baseline: None,
                baseline_duration_s: None,
                baseline_exhaustion_t_s: None,
            },
        })
    }
}

/// The adaptive plan with the baseline's total U in its summary (what `posture-opt plan` runs).
pub fn plan_with_baseline(task: &Task, adapt: bool) -> Result<(Plan, Plan), PlanError> {
    let mut planner = Planner::new(task);
    let baseline = planner.plan(false)?;
    let mut main = if adapt {
        planner.plan(true)?
    } else {
        baseline.clone()
    };
    main.summary.baseline_total_u = Some(baseline.summary.total_u);
    main.summary.baseline_duration_s = Some(baseline.summary.duration_s);
    main.summary.baseline_exhaustion_t_s = baseline.summary.exhaustion.as_ref().map(|e| e.t_s);
    main.summary.change_vs_baseline = Some(if baseline.summary.total_u > 0.0 {
        main.summary.total_u / baseline.summary.total_u - 1.0
    } else {
        0.0
    });
    Ok((main, baseline))
}
