//! The planning loop: optimise every phase's posture → hold → update fatigue exactly → re-plan as
//! capacity falls; and the baselines an ergonomist compares with.
//!
//! **Across phases.** Phases with the same targets and hand forces share one posture (a group).
//! The groups are optimised in turn, each with the others' loads fixed, against the same
//! objective (total fatigue at the end of the task plus the groups' time-weighted discomfort);
//! passes repeat until the objective falls by less than 10⁻⁴ (relative) or five passes are done.
//! Every group solve starts from its current posture and only accepts steps that lower the
//! objective, so the passes' objectives never increase ([`Summary::passes`] records them), and the
//! sequence converges. The first pass searches globally ([`super::search`]); later passes and
//! re-plans refine locally.
//!
//! **Cross-seeding.** The first pass searches each group with the others still at their
//! nearest-to-neutral postures, so its choice of basin is made in the wrong context, and local
//! passes cannot leave it. Once the passes have settled, one more pass searches every group from
//! its own posture and from each other group's (neighbouring phases of a task often share a good
//! posture family: a carry and a place, two picks), its own posture always among the finalists,
//! then local passes resume. The round can only lower the objective (its start is kept unless a
//! seed beats it), and it ends the search when it finds nothing better. With the discomfort term
//! on, a round that parks a joint at a limit the plan before it kept well clear of is undone:
//! that is how it lowers fatigue on the shelf tasks (the right shoulder extended to its limit and
//! the trunk turned), which an ergonomist rejects, and the term's end penalty alone (weighed
//! against fatigue) does not stop it. Every seed of the round is solved to convergence and the
//! limit test has a five-fold margin, so the plan does not depend on the QP's precision (tested).
//!
//! **In time.** Each cycle holds every phase's posture for its duration and then rests, standing
//! with the arms hanging. Every half-joint's capacity and U are updated with the exact closed
//! forms for the step's constant load. The plan re-plans at the start of a cycle when the
//! re-plan interval has passed **and** some capacity has moved by more than the tolerance since
//! the last plan, with the remaining task as horizon.
//!
//! **Baselines**, all held for the whole task and evaluated with the same exact simulation:
//! fatigue-unaware (the same optimiser with fresh capacities and a one-cycle horizon, started
//! from the plan's first postures), minimum
//! joint load (sum of squared relative loads), and the nearest-to-neutral posture reaching the
//! targets (discomfort only).

use super::asymmetry::Asymmetry;
use super::objective::{
    AT_LIMIT_FRACTION, Discomfort, FatigueCost, LoadCost, NoLoadCost, Shape, SquaredLoads,
};
use super::posture::{Other, PostureWork};
use super::qp::QpError;
use super::result::*;
use super::search::{self, PhaseSolver, PhaseSpec, SearchSettings, SearchStats};
use super::sqp::{SqpOutcome, SqpSettings};
use super::stepping::{self, Stepping};
use super::task::Task;
use super::zones::{self, ZONE_PENALTY_PER_RAD, ZoneLimits, ZoneWork};
use crate::body::stance::FeetNow;
use crate::fatigue::{MaParams, MaState, PreparedHold};
use nalgebra::{Vector2, Vector3};
use std::collections::HashMap;

/// Why planning failed (an internal failure: the task was already validated).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    #[error("optimiser failed in phase '{phase}': {source}")]
    Qp { phase: String, source: QpError },
    #[error(
        "starting postures: {given} given for {phases} phases of {nq} coordinates each (phase {phase} has {len})"
    )]
    Hint {
        given: usize,
        phases: usize,
        nq: usize,
        phase: usize,
        len: usize,
    },
}

/// How to plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanOptions {
    /// Re-plan as capacity falls (false: the first plan, optimal for the whole task with each
    /// phase's posture held throughout, is held).
    pub adapt: bool,
    /// Minimise fatigue only (no discomfort term, no step cost, no asymmetry cost); the posture
    /// zones are constraints and stay unless [`Self::zones`] is false.
    pub fatigue_only: bool,
    /// Keep the postures within the acceptable zones of ISO 11226 and EN 1005-4
    /// ([`super::zones`]; false: the unconstrained optimum, for comparison).
    pub zones: bool,
    /// Each phase looks at its work (its gaze point, [`super::task::Phase::gaze_m`]); false: the
    /// head is free in every phase, for comparison.
    pub gaze: bool,
    /// Compute the three baselines.
    pub baselines: bool,
    /// After the first plan's passes settle, search every group again from the other groups'
    /// postures ([`CROSS_ROUNDS`] rounds), then every group whose hand holds a load from its
    /// posture with that forearm turned (the forearm round); false stops at the settled passes.
    pub cross_seeding: bool,
    /// After the first plan's search, swap groups' postures for other local optima the search
    /// found where that lowers the whole objective ([`Planner`]'s pool swap); false keeps the
    /// searched plan.
    pub pool_swap: bool,
    pub sqp: SqpSettings,
    /// The multi-start's settings.
    pub search: SearchSettings,
}

impl Default for PlanOptions {
    fn default() -> Self {
        PlanOptions {
            adapt: true,
            fatigue_only: false,
            zones: true,
            gaze: true,
            baselines: true,
            cross_seeding: true,
            pool_swap: true,
            sqp: SqpSettings::default(),
            search: SearchSettings::default(),
        }
    }
}

/// A zone is reported as exceeded beyond this margin \[deg\] (the solver's tolerance is far
/// smaller; the report's angles are rounded to degrees).
pub const ZONE_REPORT_TOLERANCE_DEG: f64 = 0.5;

/// Most coordination passes.
pub const MAX_PASSES: usize = 5;
/// Passes stop when the objective falls by less than this (relative).
pub const PASS_TOLERANCE: f64 = 1e-4;
/// Cross-seeding rounds after the passes of a global search have settled: every group is
/// searched again from its posture and from every other group's, then passes resume.
pub const CROSS_ROUNDS: usize = 1;
/// A search after the first passes have settled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Round {
    /// Every group searched again from its posture and from every other group's.
    Cross,
    /// Every group with a loaded hand searched again from its posture and from it with the
    /// loaded forearms turned ([`super::search::PhaseSolver::forearms_turned`]).
    Forearms,
}

/// Coordination passes of the fatigue-unaware baseline (it starts from the main plan).
pub const BASELINE_PASSES: usize = 2;
/// SQP iterations a re-plan allows each phase (it starts from the previous plan's posture): with
/// 15 the re-planned shelf phases stopped unconverged at the cap in 4 of 6, with 40 none does, for
/// 2 % more QPs.
pub const REPLAN_ITERATIONS: usize = 40;

/// The planner of one task.
pub struct Planner<'t> {
    task: &'t Task,
    solver: PhaseSolver<'t>,
    /// Groups of phases sharing a posture; each group's representative is its first phase.
    groups: Vec<Vec<usize>>,
    rest_loads: Vec<f64>,
    rest_solve: SqpOutcome,
    qp_solves_before: u64,
    /// The first plan's postures (the fatigue-unaware baseline starts from them).
    first_plan: Option<GroupPostures>,
    /// The nearest-to-neutral reaching postures (the first plan's start, a baseline).
    neutral: Option<GroupPostures>,
    /// The least-squared-loads postures (a baseline, and a whole-plan start of the first plan).
    min_load: Option<GroupPostures>,
    /// Cross-seeding rounds of a global search (set from [`PlanOptions::cross_seeding`]).
    cross_rounds: usize,
    /// Whether the first plan ends with a pool swap (set from [`PlanOptions::pool_swap`]).
    swap: bool,
    /// Per group, every local optimum the first plan's searches found (for [`Self::pool_swap`]).
    pools: Vec<Vec<Vec<f64>>>,
    /// Per phase, a posture to start the first plan's global search from as well (another
    /// worker's plan: [`Self::hint`]).
    hint: Option<Vec<Vec<f64>>>,
    /// Per group, the acceptable posture zones (the tightest of its phases'), whether they are
    /// kept ([`PlanOptions::zones`]), and their evaluator (`None`: not the generated worker).
    group_zones: Vec<ZoneLimits>,
    zones_on: bool,
    /// Whether the phases look at their gaze points ([`PlanOptions::gaze`]).
    gaze_on: bool,
    zone_work: Option<ZoneWork>,
    /// Per group, its phases' held objects as obstacles ([`super::held::objects`]).
    held: Vec<Option<crate::workstation::Workstation>>,
}

/// Postures of every group, with their solve records.
#[derive(Clone)]
struct GroupPostures {
    q: Vec<Vec<f64>>,
    solves: Vec<SqpOutcome>,
    stats: Vec<SearchStats>,
}

impl<'t> Planner<'t> {
    /// Builds the solver and the rest posture (standing, arms hanging, relaxed: least squared
    /// loads and discomfort, clear of the workstation, balanced).
    pub fn new(task: &'t Task, sqp: SqpSettings) -> Result<Self, PlanError> {
        let qp_err = |phase: &str| {
            let phase = phase.to_string();
            move |source| PlanError::Qp { phase, source }
        };
        let mut solver = PhaseSolver::new(task, sqp).map_err(qp_err("rest"))?;
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for p in 0..task.phases.len() {
            match groups
                .iter_mut()
                .find(|g| task.phases[g[0]].same_work(&task.phases[p]))
            {
                Some(g) => g.push(p),
                None => groups.push(vec![p]),
            }
        }
        let phase_zones = zones::planning_limits(task);
        let group_zones: Vec<ZoneLimits> = groups
            .iter()
            .map(|m| {
                m.iter()
                    .skip(1)
                    .fold(phase_zones[m[0]], |z, &p| z.tighter(&phase_zones[p]))
            })
            .collect();
        // Rest posture: from the standing zero posture, brought onto the stance.
        let nh = task.half_joints.len();
        let ones = vec![10.0; nh];
        let spec = PhaseSpec {
            targets_m: [None, None],
            hand_force_n: [Vector3::zeros(); 2],
            discomfort_weight: 1.0,
            shape: Shape::of(task),
            capacity: &ones,
            gaze_m: None,
            zones: None,
        };
        // (a seated worker's from the seat, hips and knees bent)
        let zero = search::seated_start(task).unwrap_or_else(|| vec![0.0; task.model.nq()]);
        let mut q_rest = zero.clone();
        // the worker rests on the nominal stance, wherever the phases place the feet
        let (rest_solve, _) = if task.stance.as_ref().is_some_and(|s| s.placement.is_some()) {
            let fixed = task.with_fixed_feet();
            PhaseSolver::new(&fixed, sqp)
                .map_err(qp_err("rest"))?
                .solve(&spec, &mut SquaredLoads, Some(&zero), false, &mut q_rest)
        } else {
            solver.solve(&spec, &mut SquaredLoads, Some(&zero), false, &mut q_rest)
        }
        .map_err(qp_err("rest"))?;
        solver.q_rest = q_rest.clone();
        let mut rest_loads = vec![0.0; nh];
        solver.pw.statics(task, &q_rest, &[Vector3::zeros(); 2]);
        solver.pw.half_joint_loads(task, &q_rest, &mut rest_loads);
        let held = groups
            .iter()
            .map(|m| super::held::objects(task, m))
            .collect();
        Ok(Planner {
            task,
            qp_solves_before: solver.qp_solves(),
            solver,
            held,
            groups,
            rest_loads,
            rest_solve,
            first_plan: None,
            neutral: None,
            min_load: None,
            pools: Vec::new(),
            swap: true,
            cross_rounds: CROSS_ROUNDS,
            hint: None,
            group_zones,
            zones_on: true,
            gaze_on: true,
            zone_work: ZoneWork::new(&task.model),
        })
    }

    /// Adds, per phase, a posture the first plan's global search starts from beside its own
    /// (e.g. the postures another worker's plan found for the same task): the search then
    /// starts from the nearest-to-neutral posture and this one instead of its generic seeds.
    /// `q_rad_per_phase` has one posture of the model's coordinates per phase.
    pub fn hint(&mut self, q_rad_per_phase: &[Vec<f64>]) -> Result<(), PlanError> {
        let (n, nq) = (self.task.phases.len(), self.task.model.nq());
        let bad = q_rad_per_phase
            .iter()
            .position(|q| q.len() != nq || q.iter().any(|x| !x.is_finite()));
        if q_rad_per_phase.len() != n || bad.is_some() {
            let phase = bad.unwrap_or(0);
            return Err(PlanError::Hint {
                given: q_rad_per_phase.len(),
                phases: n,
                nq,
                phase,
                len: q_rad_per_phase.get(phase).map_or(0, Vec::len),
            });
        }
        self.hint = Some(q_rad_per_phase.to_vec());
        Ok(())
    }

    /// The rest posture.
    pub fn rest_posture(&self) -> &[f64] {
        &self.solver.q_rest
    }

    /// Interior-point iterations of all QP solves so far.
    pub fn ipm_iterations(&self) -> u64 {
        self.solver.ipm_iterations()
    }

    fn loads_of(&mut self, q: &[f64], forces: &[Vector3<f64>; 2]) -> Vec<f64> {
        let mut f = vec![0.0; self.task.half_joints.len()];
        self.solver.pw.statics(self.task, q, forces);
        self.solver.pw.half_joint_loads(self.task, q, &mut f);
        f
    }

    fn phase_loads(&mut self, gp: &GroupPostures) -> Vec<Vec<f64>> {
        let t = self.task;
        let mut out = vec![Vec::new(); t.phases.len()];
        for (g, members) in self.groups.clone().iter().enumerate() {
            let f = self.loads_of(&gp.q[g], &t.phases[members[0]].hand_force_n);
            for &p in members {
                out[p] = f.clone();
            }
        }
        out
    }

    fn group_weight(&self, g: usize, fatigue_only: bool) -> f64 {
        if fatigue_only {
            return 0.0;
        }
        let t = self.task;
        t.objective.discomfort_weight * self.groups[g].len() as f64 / t.phases.len() as f64
    }

    /// The feet of posture `q` (kinematics only), for a standing body.
    fn feet_at(&mut self, q: &[f64]) -> Option<FeetNow> {
        self.solver.pw.statics(self.task, q, &[Vector3::zeros(); 2]);
        stepping::feet_of(self.task, &self.solver.pw)
    }

    /// Whether the planner places the feet (the task gives a standing area).
    fn feet_placed(&self) -> bool {
        self.task
            .stance
            .as_ref()
            .is_some_and(|s| s.placement.is_some())
    }

    /// The step cost's weight: the task's, when the planner places the feet and the objective
    /// is not fatigue alone.
    fn step_weight(&self, fatigue_only: bool) -> f64 {
        if fatigue_only || !self.feet_placed() {
            0.0
        } else {
            self.task.objective.step_weight
        }
    }

    /// The asymmetry cost's weight: the task's, when the planner places the feet and the
    /// objective is not fatigue alone.
    fn asymmetry_weight(&self, fatigue_only: bool) -> f64 {
        if fatigue_only || !self.feet_placed() {
            0.0
        } else {
            self.task.objective.asymmetry_weight
        }
    }

    /// The asymmetry cost of group `g`'s posture: each of its phases' load centre, at the
    /// weight's share per phase of the cycle.
    fn asymmetry_for(&self, g: usize, fatigue_only: bool) -> Asymmetry {
        let w = self.asymmetry_weight(fatigue_only);
        if w == 0.0 {
            return Asymmetry::default();
        }
        let per_phase = w / self.task.phases.len() as f64;
        let loads = self.groups[g]
            .iter()
            .filter_map(|&p| {
                let t: Vec<_> = self.task.phases[p].targets_m.iter().flatten().collect();
                (!t.is_empty()).then(|| {
                    let c = t.iter().fold(Vector3::zeros(), |a, &b| a + b) / t.len() as f64;
                    (Vector2::new(c.x, c.y), per_phase)
                })
            })
            .collect();
        Asymmetry { loads }
    }

    /// The step cost of group `g` against its neighbouring states in the cycle (the phase
    /// before and after each of its phases, the rest stance at the cycle's ends), with the
    /// other groups' postures `gp` held.
    fn stepping_for(&mut self, g: usize, gp: &GroupPostures, fatigue_only: bool) -> Stepping {
        let weight = self.step_weight(fatigue_only);
        let asymmetry = self.asymmetry_for(g, fatigue_only);
        if weight == 0.0 {
            return Stepping {
                asymmetry,
                ..Stepping::default()
            };
        }
        let rest = self.solver.q_rest.clone();
        let np = self.task.phases.len();
        let group_of = |p: usize| self.groups.iter().position(|m| m.contains(&p));
        let members = self.groups[g].clone();
        let mut nbs: Vec<Option<usize>> = Vec::new(); // None: rest
        for &p in &members {
            let prev = if p == 0 { None } else { group_of(p - 1) };
            let next = if p + 1 == np { None } else { group_of(p + 1) };
            for nb in [prev, next] {
                if nb != Some(g) {
                    nbs.push(nb);
                }
            }
        }
        let mut neighbours = Vec::new();
        for nb in nbs {
            let q = match nb {
                Some(h) => gp.q[h].clone(),
                None => rest.clone(),
            };
            if let Some(f) = self.feet_at(&q) {
                neighbours.push((f, 1.0));
            }
        }
        Stepping {
            weight,
            neighbours,
            asymmetry,
        }
    }

    /// The step and asymmetry costs of a whole cycle with postures `gp`.
    fn cycle_step_cost(&mut self, gp: &GroupPostures, fatigue_only: bool) -> f64 {
        let mut asym = 0.0;
        for g in 0..self.groups.len() {
            let a = self.asymmetry_for(g, fatigue_only);
            if !a.loads.is_empty()
                && let Some(f) = self.feet_at(&gp.q[g].clone())
            {
                asym += a.value(&f);
            }
        }
        let weight = self.step_weight(fatigue_only);
        if weight == 0.0 {
            return asym;
        }
        let rest = self.solver.q_rest.clone();
        let Some(rest_feet) = self.feet_at(&rest) else {
            return asym;
        };
        let mut feet = Vec::with_capacity(self.task.phases.len());
        for p in 0..self.task.phases.len() {
            let g = self.groups.iter().position(|m| m.contains(&p)).unwrap_or(0);
            let q = gp.q[g].clone();
            feet.extend(self.feet_at(&q));
        }
        asym + stepping::cycle_cost(self.task, weight, &rest_feet, &feet)
    }

    /// The whole objective for postures `gp`: fatigue J plus the groups' weighted discomfort
    /// and the cycle's steps.
    fn total_objective(
        &mut self,
        gp: &GroupPostures,
        state: &[MaState],
        cycles: u64,
        fatigue_only: bool,
    ) -> f64 {
        let (j, d) = self.objective_parts(gp, state, cycles, fatigue_only);
        j + d
    }

    /// The objective's fatigue term (ln of the predicted total U over the horizon, monotone in
    /// it) and its posture term, for the postures held over `cycles` from `state`.
    fn objective_parts(
        &mut self,
        gp: &GroupPostures,
        state: &[MaState],
        cycles: u64,
        fatigue_only: bool,
    ) -> (f64, f64) {
        let loads = self.phase_loads(gp);
        let mut cost = FatigueCost::new(
            self.task,
            &self.groups[0],
            &loads,
            &self.rest_loads,
            state,
            cycles,
        );
        let j = cost.value(&loads[self.groups[0][0]]);
        let d: f64 = (0..self.groups.len())
            .map(|g| {
                self.group_weight(g, fatigue_only)
                    * self.solver.discomfort.value(&gp.q[g], Shape::of(self.task))
            })
            .sum();
        let z: f64 = (0..self.groups.len())
            .map(|g| self.zone_penalty(g, &gp.q[g], fatigue_only))
            .sum();
        (j, d + self.cycle_step_cost(gp, fatigue_only) + z)
    }

    /// The posture zones group `g` keeps: `None` when the plan is asked without them. They are
    /// constraints, not comfort: a fatigue-only plan keeps them too.
    fn zones_for(&self, g: usize, _fatigue_only: bool) -> Option<ZoneLimits> {
        (self.zones_on && self.zone_work.is_some()).then(|| self.group_zones[g])
    }

    /// The zones' penalty of group `g` at posture `q` (the objective's term).
    fn zone_penalty(&mut self, g: usize, q: &[f64], fatigue_only: bool) -> f64 {
        match (self.zones_for(g, fatigue_only), self.zone_work.as_mut()) {
            (Some(lim), Some(z)) => {
                ZONE_PENALTY_PER_RAD * z.violation_rad(&self.task.model, q, &lim)
            }
            _ => 0.0,
        }
    }

    /// Optimises every group's posture for the state and horizon; `multistart` searches the
    /// first pass globally. Returns the objective after each pass.
    fn optimise(
        &mut self,
        gp: &mut GroupPostures,
        state: &[MaState],
        cycles: u64,
        fatigue_only: bool,
        multistart: bool,
        max_passes: usize,
    ) -> Result<Vec<f64>, PlanError> {
        let t = self.task;
        let capacity: Vec<f64> = state.iter().map(|s| s.capacity).collect();
        let mut loads = self.phase_loads(gp);
        let mut passes = Vec::new();
        let mut last = f64::INFINITY;
        // the searches after the first passes settle, last first: the cross-seeding rounds, then
        // the forearm round (only with cross-seeding on and a global search)
        let mut pending: Vec<Round> = Vec::new();
        if multistart && self.cross_rounds > 0 {
            pending.push(Round::Forearms);
            if self.groups.len() > 1 {
                pending.extend(std::iter::repeat_n(Round::Cross, self.cross_rounds));
            }
        }
        // the round under way (its search is this pass), passes since the last search, and the
        // plan before the round
        let mut round: Option<Round> = None;
        let mut since = 0;
        let mut before: Option<(GroupPostures, usize)> = None;
        loop {
            let global = multistart && passes.is_empty();
            for g in 0..self.groups.len() {
                let members = self.groups[g].clone();
                let rep = &t.phases[members[0]];
                let mut cost =
                    FatigueCost::new(t, &members, &loads, &self.rest_loads, state, cycles);
                let spec = PhaseSpec {
                    targets_m: rep.targets_m,
                    hand_force_n: rep.hand_force_n,
                    discomfort_weight: self.group_weight(g, fatigue_only),
                    shape: Shape::of(t),
                    capacity: &capacity,
                    gaze_m: rep.gaze_m().filter(|_| self.gaze_on),
                    zones: self.zones_for(g, fatigue_only),
                };
                let start = gp.q[g].clone();
                let mut q = start.clone();
                self.solver.extra_seeds = match round {
                    Some(Round::Cross) => (0..self.groups.len())
                        .filter(|&h| h != g)
                        .map(|h| gp.q[h].clone())
                        .collect(),
                    Some(Round::Forearms) => self.solver.forearms_turned(&start, &rep.hand_force_n),
                    None if global => self
                        .hint
                        .as_ref()
                        .map_or(Vec::new(), |h| vec![h[members[0]].clone()]),
                    None => Vec::new(),
                };
                // a forearm round searches the groups with a turn; the others take a local pass
                let search = global
                    || round == Some(Round::Cross)
                    || (round == Some(Round::Forearms) && !self.solver.extra_seeds.is_empty());
                self.solver.pool.clear();
                self.solver.stepping = self.stepping_for(g, gp, fatigue_only);
                self.solver.held = self.held[g].clone();
                let (out, stats) = self
                    .solver
                    .solve(&spec, &mut cost, Some(&start), search, &mut q)
                    .map_err(|source| PlanError::Qp {
                        phase: rep.name.clone(),
                        source,
                    })?;
                self.solver.extra_seeds.clear();
                self.pools[g].append(&mut self.solver.pool);
                gp.q[g] = q;
                gp.solves[g] = out;
                if global {
                    gp.stats[g] = stats;
                }
                let f = self.loads_of(&gp.q[g], &rep.hand_force_n);
                for &p in &members {
                    loads[p] = f.clone();
                }
            }
            let j = self.total_objective(gp, state, cycles, fatigue_only);
            passes.push(j);
            since += 1;
            let settled = (last - j).abs() <= PASS_TOLERANCE * j.abs().max(1.0);
            last = j;
            round = None;
            if !(settled || since >= max_passes) {
                continue;
            }
            // A round that ends higher than the plan before it is undone (each group's search
            // lowers its own objective with the others held, which the passes after it need not
            // keep where a phase ends unconverged); so is, with the discomfort term on, one that
            // parks a joint at a limit the plan before it kept well clear of (the search only
            // traded the term's end penalty for fatigue).
            if let Some((gp0, n0)) = before.take()
                && (j > passes[n0 - 1] || !fatigue_only && self.parks_at_a_limit(gp, &gp0))
            {
                *gp = gp0;
                passes.truncate(n0);
                last = passes.last().copied().unwrap_or(f64::INFINITY);
                loads = self.phase_loads(gp);
            }
            // the next round with something to search, if any
            let next = loop {
                match pending.pop() {
                    Some(Round::Forearms)
                        if (0..self.groups.len()).all(|g| {
                            let rep = &t.phases[self.groups[g][0]];
                            self.solver
                                .forearms_turned(&gp.q[g], &rep.hand_force_n)
                                .is_empty()
                        }) => {}
                    other => break other,
                }
            };
            match next {
                None => break,
                Some(r) => {
                    round = Some(r);
                    since = 0;
                    before = Some((gp.clone(), passes.len()));
                }
            }
        }
        Ok(passes)
    }

    /// Greedy swaps among the local optima the searches found: each group's posture is replaced
    /// by any posture of its pool that lowers the whole objective (the other groups held), keeps
    /// every load within its capacity bound and, with the discomfort term on, is no more awkward
    /// than the posture it replaces, until no swap helps. The per-group searches
    /// choose each posture with the others as they were then; a posture that lost to another
    /// early can win once the other groups have moved (after the final pool swap of the
    /// independent reference search). Only objective evaluations: no QP. Returns whether any
    /// posture changed.
    fn pool_swap(
        &mut self,
        gp: &mut GroupPostures,
        state: &[MaState],
        cycles: u64,
        fatigue_only: bool,
    ) -> bool {
        let mut best = self.total_objective(gp, state, cycles, fatigue_only);
        let mut changed = false;
        for _ in 0..MAX_PASSES {
            let mut improved = false;
            let pools = std::mem::take(&mut self.pools);
            for (g, pool) in pools.iter().enumerate() {
                for cand in pool {
                    if !fatigue_only {
                        // a swap parks no joint at a limit the posture it replaces kept clear of
                        // (the objective's end penalty alone let shelf trade a 70° wrist for
                        // less U); the trunk's twist and the other zones are the objective's
                        let d = &self.solver.discomfort;
                        if d.parks_beyond(cand, &d.clear_of_limits(&gp.q[g])) {
                            continue;
                        }
                    }
                    let old = std::mem::replace(&mut gp.q[g], cand.clone());
                    let j = self.total_objective(gp, state, cycles, fatigue_only);
                    if j < best - PASS_TOLERANCE * best.abs().max(1.0)
                        && self.within_capacity(gp, state, cycles)
                    {
                        best = j;
                        improved = true;
                    } else {
                        gp.q[g] = old;
                    }
                }
            }
            self.pools = pools;
            changed |= improved;
            if !improved {
                break;
            }
        }
        changed
    }

    /// Whether every half-joint's load in every group stays within the bound the QP's capacity
    /// rows keep it under (its lowest capacity over the task, less the exhaustion margin).
    fn within_capacity(&mut self, gp: &GroupPostures, state: &[MaState], cycles: u64) -> bool {
        let loads = self.phase_loads(gp);
        for members in &self.groups {
            let mut cost =
                FatigueCost::new(self.task, members, &loads, &self.rest_loads, state, cycles);
            let f = &loads[members[0]];
            for (h, &fh) in f.iter().enumerate() {
                if fh > 0.0
                    && let Some((bound, _)) = cost.capacity_bound(h, fh)
                    && fh > bound
                {
                    return false;
                }
            }
        }
        true
    }

    /// Whether postures `gp` bring a joint to a limit that `before` kept well clear of
    /// ([`Discomfort::parks_beyond`]).
    fn parks_at_a_limit(&self, gp: &GroupPostures, before: &GroupPostures) -> bool {
        let d = &self.solver.discomfort;
        gp.q.iter()
            .zip(&before.q)
            .any(|(q, q0)| d.parks_beyond(q, &d.clear_of_limits(q0)))
    }

    /// Postures per group solved once with a load cost of its own (baselines).
    fn solve_independent(
        &mut self,
        cost_of: &mut dyn FnMut() -> Box<dyn LoadCost>,
        weight: f64,
        shape: Shape,
        fatigue_only: bool,
    ) -> Result<GroupPostures, PlanError> {
        let t = self.task;
        let n = self.groups.len();
        let big = vec![10.0; t.half_joints.len()];
        let mut gp = GroupPostures {
            q: vec![self.solver.q_rest.clone(); n],
            solves: vec![SqpOutcome::default(); n],
            stats: vec![SearchStats::default(); n],
        };
        for g in 0..n {
            let rep = &t.phases[self.groups[g][0]];
            let spec = PhaseSpec {
                targets_m: rep.targets_m,
                hand_force_n: rep.hand_force_n,
                discomfort_weight: weight,
                shape,
                capacity: &big,
                gaze_m: rep.gaze_m().filter(|_| self.gaze_on),
                zones: self.zones_for(g, fatigue_only),
            };
            let mut cost = cost_of();
            let mut q = gp.q[g].clone();
            // steps from and back to the rest stance
            let weight = self.step_weight(false);
            let asymmetry = self.asymmetry_for(g, false);
            self.solver.held = self.held[g].clone();
            self.solver.stepping = match self.feet_at(&self.solver.q_rest.clone()) {
                Some(f) if weight > 0.0 => Stepping {
                    weight,
                    neighbours: vec![(f, 2.0)],
                    asymmetry,
                },
                _ => Stepping {
                    asymmetry,
                    ..Stepping::default()
                },
            };
            let (out, stats) = self
                .solver
                .solve(&spec, cost.as_mut(), None, false, &mut q)
                .map_err(|source| PlanError::Qp {
                    phase: rep.name.clone(),
                    source,
                })?;
            gp.q[g] = q;
            gp.solves[g] = out;
            gp.stats[g] = stats;
        }
        Ok(gp)
    }

    /// The first plan's postures: seeded from the nearest-to-neutral reaching postures, then
    /// optimised in passes.
    fn initial(
        &mut self,
        state: &[MaState],
        cycles: u64,
        fatigue_only: bool,
    ) -> Result<(GroupPostures, Vec<f64>), PlanError> {
        // a fatigue-only plan starts from the same postures whatever the comfort term's
        // settings: the seeds' nearest-to-neutral measure is then the displacement alone, no
        // assessment zones and no end penalty. (The rest posture, solved in `new` before the
        // options are known, keeps them; on the nine shipped tasks it lies at least 5° inside
        // every zone and clear of the end zones, where both are zero.)
        let shape = if fatigue_only {
            Shape::DISPLACEMENT
        } else {
            Shape::of(self.task)
        };
        let mut gp =
            self.solve_independent(&mut || Box::new(NoLoadCost), 1.0, shape, fatigue_only)?;
        self.neutral = Some(gp.clone());
        let min_load = self.solve_independent(
            &mut || Box::new(SquaredLoads),
            0.0,
            Shape::of(self.task),
            fatigue_only,
        )?;
        self.min_load = Some(min_load.clone());
        self.pools = vec![Vec::new(); self.groups.len()];
        let mut passes = self.optimise(&mut gp, state, cycles, fatigue_only, true, MAX_PASSES)?;
        let searched = gp.clone();
        if self.swap && self.pool_swap(&mut gp, state, cycles, fatigue_only) {
            let more = self.optimise(&mut gp, state, cycles, fatigue_only, false, MAX_PASSES)?;
            // the local passes after a swap only polish it; should they end above the searched
            // plan (they may not, they start lower), the searched plan is kept
            if more.last() < passes.last() {
                passes.extend(more);
            } else {
                gp = searched;
            }
        }
        // The baselines that do not start from the plan are whole-plan starts: one that the
        // search's plan does not beat on the plan's own objective (the search weighs postures one
        // group at a time, the others held) is optimised further and kept if it ends lower.
        for start in [self.neutral.clone(), Some(min_load)].into_iter().flatten() {
            let j = passes.last().copied().unwrap_or(f64::INFINITY);
            if self.total_objective(&start, state, cycles, fatigue_only) < j {
                let mut other = start;
                let more =
                    self.optimise(&mut other, state, cycles, fatigue_only, false, MAX_PASSES)?;
                if more.last().is_some_and(|&m| m < j) {
                    gp = other;
                    passes.extend(more);
                }
            }
        }
        Ok((gp, passes))
    }

    /// Plans the task.
    pub fn plan(&mut self, opts: PlanOptions) -> Result<Plan, PlanError> {
        let t = self.task;
        let nh = t.half_joints.len();
        let fresh = vec![MaState::FRESH; nh];
        self.qp_solves_before = self.solver.qp_solves();
        self.solver.settings = opts.sqp;
        self.solver.work.settings = opts.sqp;
        self.solver.search = opts.search;
        self.cross_rounds = if opts.cross_seeding { CROSS_ROUNDS } else { 0 };
        self.swap = opts.pool_swap;
        self.zones_on = opts.zones;
        self.gaze_on = opts.gaze;
        let (gp, passes) = self.initial(&fresh, t.cycles as u64, opts.fatigue_only)?;
        self.first_plan = Some(gp.clone());
        let mut plan = self.simulate(gp, passes, opts)?;
        if opts.baselines {
            plan.summary.baselines = self.baselines(&plan, opts)?;
        }
        Ok(plan)
    }

    fn baselines(
        &mut self,
        main: &Plan,
        opts: PlanOptions,
    ) -> Result<Vec<BaselineSummary>, PlanError> {
        let fresh = vec![MaState::FRESH; self.task.half_joints.len()];
        let mut out = Vec::new();
        let blind = {
            let mut gp = self
                .first_plan
                .clone()
                .expect("the main plan was made first");
            let passes = self.optimise(
                &mut gp,
                &fresh,
                1,
                opts.fatigue_only,
                false,
                BASELINE_PASSES,
            )?;
            self.held_baseline(gp, passes, opts)?
        };
        let gp = self.min_load.clone().expect("the main plan was made first");
        let min_load = self.held_baseline(gp, Vec::new(), opts)?;
        let gp = self.neutral.clone().expect("the main plan was made first");
        let neutral = self.held_baseline(gp, Vec::new(), opts)?;
        let total = main.summary.total_u;
        let mut push = |name: &str, description: &str, (objective, p): &(f64, Plan)| {
            out.push(BaselineSummary {
                name: name.into(),
                description: description.into(),
                objective: *objective,
                total_u: p.summary.total_u,
                duration_s: p.summary.duration_s,
                exhaustion: p.summary.exhaustion.clone(),
                change: if p.summary.total_u > 0.0 {
                    total / p.summary.total_u - 1.0
                } else {
                    0.0
                },
            });
        };
        push(
            "fatigue_unaware",
            "the same optimiser with fresh capacities and a one-cycle horizon, held all task",
            &blind,
        );
        push(
            "minimum_joint_load",
            "least sum of squared relative loads per phase, held all task",
            &min_load,
        );
        push(
            "nearest_neutral",
            "the posture nearest to neutral that reaches the targets, held all task",
            &neutral,
        );
        Ok(out)
    }

    /// A baseline's postures held all task: the first plan's objective at them (fresh, the
    /// whole task) and the simulated plan.
    fn held_baseline(
        &mut self,
        gp: GroupPostures,
        passes: Vec<f64>,
        opts: PlanOptions,
    ) -> Result<(f64, Plan), PlanError> {
        let fresh = vec![MaState::FRESH; self.task.half_joints.len()];
        let j = self.total_objective(&gp, &fresh, self.task.cycles as u64, opts.fatigue_only);
        let held = PlanOptions {
            adapt: false,
            baselines: false,
            ..opts
        };
        Ok((j, self.simulate(gp, passes, held)?))
    }

    /// Holds the postures cycle by cycle with exact fatigue updates, re-planning when adaptive.
    fn simulate(
        &mut self,
        mut gp: GroupPostures,
        passes: Vec<f64>,
        opts: PlanOptions,
    ) -> Result<Plan, PlanError> {
        let t = self.task;
        let nh = t.half_joints.len();
        let n_ph = t.phases.len();
        let mut state = vec![MaState::FRESH; nh];
        let mut postures: Vec<PostureRecord> = Vec::new();
        let mut group_posture_index = vec![0usize; self.groups.len()];
        let mut group_loads = vec![Vec::new(); self.groups.len()];
        let record = |planner: &mut Self,
                      gp: &GroupPostures,
                      at: f64,
                      postures: &mut Vec<PostureRecord>,
                      idx: &mut Vec<usize>,
                      loads: &mut Vec<Vec<f64>>| {
            for g in 0..planner.groups.len() {
                let rep = &t.phases[planner.groups[g][0]];
                let rec = planner.posture_record(&gp.q[g], &rep.hand_force_n, &rep.name, at);
                loads[g] = rec.load.clone();
                idx[g] = postures.len();
                postures.push(rec);
            }
        };
        record(
            self,
            &gp,
            0.0,
            &mut postures,
            &mut group_posture_index,
            &mut group_loads,
        );
        let rest_index = postures.len();
        let q_rest = self.solver.q_rest.clone();
        postures.push(self.posture_record(&q_rest, &[Vector3::zeros(); 2], "rest", 0.0));
        let group_of: Vec<usize> = (0..n_ph)
            .map(|p| self.groups.iter().position(|g| g.contains(&p)).unwrap_or(0))
            .collect();

        let mut phase_names: Vec<String> = t.phases.iter().map(|p| p.name.clone()).collect();
        phase_names.push("rest".to_string());
        let mut steps = Steps::new(t.fatigue.clone(), state.to_vec(), phase_names);
        let mut time = 0.0;
        let mut exhaustion: Option<Exhaustion> = None;
        let mut cycles_done = 0;
        let mut replans = 1u32;
        let mut sqp_iterations: u64 = gp.solves.iter().map(|s| s.iterations as u64).sum();
        let mut last_plan_capacity: Vec<f64> = state.iter().map(|s| s.capacity).collect();
        let mut last_plan_cycle = 0u32;
        let mut last_plan_t = 0.0;
        let mut lowest = (1.0f64, 0usize, 0.0f64);
        // each posture held for each duration prepared once (a task repeats a few of them
        // cycle after cycle; the updates are the same numbers as `MaParams::hold`'s)
        let mut prepared: HashMap<(usize, u64), Vec<PreparedHold>> = HashMap::new();
        let n_steps = t.cycles as usize * (n_ph + usize::from(t.rest_s > 0.0));
        steps.t_s.reserve(n_steps);
        'cycles: for cycle in 0..t.cycles {
            if opts.adapt && cycle > 0 {
                let interval_passed = match t.replan_every_s {
                    Some(s) => time - last_plan_t >= s,
                    None => cycle - last_plan_cycle >= t.replan_every_cycles,
                };
                let moved = state
                    .iter()
                    .zip(&last_plan_capacity)
                    .any(|(s, c)| (s.capacity - c).abs() > t.capacity_tolerance);
                if interval_passed && moved {
                    // A re-plan is kept only when it raises neither the predicted fatigue over
                    // the remaining horizon nor the whole objective there, and lowers one of
                    // them; else the current postures are held. Each kept re-plan then ends at or below the total the
                    // held postures would reach from that point, so the adaptive plan never
                    // ends above the held one.
                    let horizon = (t.cycles - cycle) as u64;
                    let before = self.objective_parts(&gp, &state, horizon, opts.fatigue_only);
                    let held = gp.clone();
                    self.solver.settings.max_iterations = REPLAN_ITERATIONS;
                    let r = self.optimise(&mut gp, &state, horizon, opts.fatigue_only, false, 1);
                    self.solver.settings = opts.sqp;
                    r?;
                    sqp_iterations += gp.solves.iter().map(|s| s.iterations as u64).sum::<u64>();
                    let after = self.objective_parts(&gp, &state, horizon, opts.fatigue_only);
                    let lowers = after.0 <= before.0 && after.0 + after.1 <= before.0 + before.1;
                    last_plan_capacity = state.iter().map(|s| s.capacity).collect();
                    last_plan_cycle = cycle;
                    last_plan_t = time;
                    if lowers {
                        record(
                            self,
                            &gp,
                            time,
                            &mut postures,
                            &mut group_posture_index,
                            &mut group_loads,
                        );
                        replans += 1;
                    } else {
                        gp = held;
                    }
                }
            }
            for si in 0..n_ph + usize::from(t.rest_s > 0.0) {
                let (name, pidx, dur) = if si < n_ph {
                    let g = group_of[si];
                    (
                        &t.phases[si].name,
                        group_posture_index[g],
                        t.phases[si].duration_s,
                    )
                } else {
                    (&"rest".to_string(), rest_index, t.rest_s)
                };
                // the posture's loads, as the plan's timeline replays them (Steps::replay)
                let f = &postures[pidx].load;
                let holds = prepared
                    .entry((pidx, dur.to_bits()))
                    .or_insert_with(|| (0..nh).map(|h| t.fatigue[h].prepare(f[h], dur)).collect());
                let mut ex: Option<(f64, usize)> = None;
                for h in 0..nh {
                    let c0 = state[h].capacity;
                    // capacity moves monotonically within the step, so the group gives out
                    // within it only if it starts or ends at or below its load
                    if !(f[h] > 0.0
                        && (c0 <= f[h] || holds[h].capacity(&state[h]) <= f[h] * (1.0 + 1e-9)))
                    {
                        continue;
                    }
                    let te = t.fatigue[h].time_to_exhaustion_within_s(&state[h], f[h], dur);
                    if let Some(te) = te
                        && te < dur
                        && ex.is_none_or(|(t0, _)| te < t0)
                    {
                        ex = Some((te, h));
                    }
                }
                let mut dur = dur;
                if let Some((te, h)) = ex {
                    dur = te;
                    exhaustion = Some(Exhaustion {
                        t_s: time + te,
                        half_joint: t.half_joints[h].id.clone(),
                        group: t.half_joints[h].group.clone(),
                        phase: name.clone(),
                        load: f[h],
                        exceeds_strength: f[h] >= 1.0,
                    });
                }
                for h in 0..nh {
                    if ex.is_some() {
                        MaParams::hold(&t.fatigue[h], &mut state[h], f[h], dur);
                    } else {
                        holds[h].hold(&mut state[h]);
                    }
                    if state[h].capacity < lowest.0 {
                        lowest = (state[h].capacity, h, time + dur);
                    }
                }
                steps.push(time, dur, cycle, pidx, si);
                time += dur;
                if exhaustion.is_some() {
                    break 'cycles;
                }
            }
            cycles_done = cycle + 1;
        }
        let (worst_h, worst_u) = state
            .iter()
            .enumerate()
            .map(|(h, s)| (h, s.fatigue_u_min))
            .fold((0, f64::MIN), |a, b| if b.1 > a.1 { b } else { a });
        let phases = self.phase_summaries(&gp, &group_loads);
        let rest_feet = self.back_to_rest(&gp);
        let (rest_clear, rest_closest) = self.clearance_of(&q_rest);
        steps.set_posture_loads(postures.iter().map(|p| p.load.clone()).collect());
        Ok(Plan {
            task: t.name.clone(),
            robot: t.robot.clone(),
            hand_frames: [
                t.hand_links[0].as_ref().map(|h| h.1.clone()),
                t.hand_links[1].as_ref().map(|h| h.1.clone()),
            ],
            fatigue_model: fatigue_model_name(&t.fatigue),
            fatigue_parameters: t.fatigue_choice.clone(),
            joints: t.joint_names(),
            half_joint_ids: t.half_joint_ids(),
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
                    recovery: p.recovery,
                    recovery_per_min: p.r_at(0.0),
                    sustainable_load: p.sustainable_load(),
                    strength_source: h.source.clone(),
                })
                .collect(),
            postures,
            steps,
            summary: Summary {
                adaptive: opts.adapt,
                fatigue_only: opts.fatigue_only,
                zones: opts.zones && self.zone_work.is_some(),
                gaze: opts.gaze,
                duration_s: time,
                planned_duration_s: t.duration_s(),
                cycles_done,
                total_u: state.iter().map(|s| s.fatigue_u_min).sum(),
                worst_half_joint: t.half_joints[worst_h].id.clone(),
                worst_u,
                lowest_capacity: lowest.0,
                lowest_capacity_half_joint: t.half_joints[lowest.1].id.clone(),
                lowest_capacity_t_s: lowest.2,
                final_capacity: state.iter().map(|s| s.capacity).collect(),
                exhaustion,
                replans,
                qp_solves: self.solver.qp_solves() - self.qp_solves_before,
                sqp_iterations,
                passes,
                phases,
                rest_posture_rad: q_rest,
                rest_clearance_m: rest_clear,
                rest_closest,
                rest_feet,
                baselines: Vec::new(),
            },
        })
    }

    /// How the feet get from the cycle's last phase back to the rest stance (the cycle's last
    /// transition, which the step cost counts as every other).
    fn back_to_rest(&mut self, gp: &GroupPostures) -> Option<stepping::PhaseFeet> {
        let last = self.task.phases.len().checked_sub(1)?;
        let g = self.groups.iter().position(|g| g.contains(&last))?;
        let before = self.feet_at(&gp.q[g].clone())?;
        let rest = self.solver.q_rest.clone();
        let now = self.feet_at(&rest)?;
        Some(stepping::describe(&before, &now))
    }

    fn clearance_of(&mut self, q: &[f64]) -> (f64, Option<String>) {
        let t = self.task;
        self.solver.pw.statics(t, q, &[Vector3::zeros(); 2]);
        let horizon = self.solver.settings.contact_horizon_m;
        let d = self
            .solver
            .pw
            .clearances(t, &self.solver.scene, horizon, None);
        let closest = self
            .solver
            .pw
            .contacts
            .iter()
            .min_by(|a, b| a.distance_m.total_cmp(&b.distance_m))
            .map(|c| describe_contact(t, c.link, &c.other));
        (if d.is_finite() { d } else { horizon }, closest)
    }

    fn posture_record(
        &mut self,
        q: &[f64],
        forces: &[Vector3<f64>; 2],
        phase: &str,
        at: f64,
    ) -> PostureRecord {
        let t = self.task;
        let pw: &mut PostureWork = &mut self.solver.pw;
        pw.statics(t, q, forces);
        let mut load = vec![0.0; t.half_joints.len()];
        pw.half_joint_loads(t, q, &mut load);
        let g = pw.ground;
        PostureRecord {
            phase: phase.into(),
            planned_at_s: at,
            q_rad: q.to_vec(),
            torque_nm: pw.data.tau_nm.iter().copied().collect(),
            load,
            mvc_nm: t.half_joints.iter().map(|h| h.mvc_at(q)).collect(),
            hand_position_m: [0, 1].map(|h| pw.hand_position(t, h).map(|p| [p.x, p.y, p.z])),
            hand_force_n: [0, 1].map(|h| [forces[h].x, forces[h].y, forces[h].z]),
            centre_of_pressure_m: g.map(|g| [g.cop_total_m.x, g.cop_total_m.y]),
            balance_margin_m: g.map(|g| g.margin_m),
            left_foot_share: g.map(|g| g.left_share),
            seat_share: g.and_then(|g| g.seat.map(|s| s.share)),
            centre_of_mass_m: [pw.data.com_m.x, pw.data.com_m.y, pw.data.com_m.z],
        }
    }

    fn phase_summaries(
        &mut self,
        gp: &GroupPostures,
        group_loads: &[Vec<f64>],
    ) -> Vec<PhaseSummary> {
        let t = self.task;
        let d = Discomfort::new(t);
        let arms = super::held::arm_bodies(t);
        // the feet of every phase, and of the rest stance before the first
        let rest = self.solver.q_rest.clone();
        let mut before = self.feet_at(&rest);
        let mut feet = Vec::with_capacity(t.phases.len());
        for p in 0..t.phases.len() {
            let g = self.groups.iter().position(|g| g.contains(&p)).unwrap_or(0);
            let now = self.feet_at(&gp.q[g].clone());
            feet.push(match (&before, &now) {
                (Some(b), Some(n)) => Some(stepping::describe(b, n)),
                _ => None,
            });
            before = now;
        }
        let holds = t.holds();
        let limits = zones::phase_limits(t);
        (0..t.phases.len())
            .map(|p| {
                let g = self.groups.iter().position(|g| g.contains(&p)).unwrap_or(0);
                let q = &gp.q[g];
                let ph = &t.phases[p];
                let outside_zones = match self.zone_work.as_mut() {
                    Some(z) => z
                        .excesses_at(&t.model, q, &limits[p], ZONE_REPORT_TOLERANCE_DEG)
                        .into_iter()
                        .map(|e| ZoneExcess {
                            what: e.zone.words().to_string(),
                            angle_deg: e.angle_deg,
                            limit_deg: e.limit_deg,
                            hold_s: holds[p].0,
                            source: e.zone.source(limits[p].movement).to_string(),
                        })
                        .collect(),
                    None => Vec::new(),
                };
                let mut loaded: Vec<(String, f64)> = t
                    .half_joints
                    .iter()
                    .zip(&group_loads[g])
                    .map(|(h, f)| (h.id.clone(), *f))
                    .collect();
                loaded.sort_by(|a, b| b.1.total_cmp(&a.1));
                loaded.truncate(3);
                let sol = gp.solves[g];
                let target_inside = ph.targets_m.iter().flatten().find_map(|tg| {
                    t.workstation
                        .obstacles
                        .iter()
                        .find(|o| o.contains(tg))
                        .map(|o| o.spec.name.clone())
                });
                let target_blocked = ph.targets_m.iter().enumerate().find_map(|(h, tg)| {
                    super::reach::hand_blocked(t, h, tg.as_ref()?).map(|b| b.words())
                });
                let (_, closest) = {
                    self.solver.pw.statics(t, q, &ph.hand_force_n);
                    let horizon = self.solver.settings.contact_horizon_m;
                    let held = super::held::objects(t, &[p]);
                    self.solver
                        .pw
                        .clearances(t, &self.solver.scene, horizon, held.as_ref());
                    let c = self
                        .solver
                        .pw
                        .contacts
                        .iter()
                        .min_by(|a, b| a.distance_m.total_cmp(&b.distance_m))
                        .map(|c| describe_contact(t, c.link, &c.other));
                    (0.0, c)
                };
                // The held object sits where the task puts it (between the hands' targets):
                // an overlap with an obstacle deeper than resting contact is a collision.
                let (min_clearance_m, closest) = match object_overlap(t, ph) {
                    Some((d, name)) if d < sol.min_clearance_m => {
                        (d, Some(format!("held object ↔ obstacle '{name}'")))
                    }
                    _ => (sol.min_clearance_m, closest),
                };
                // ... and one inside the worker's own body (arms excepted) too.
                let (min_clearance_m, closest) =
                    match super::held::overlap(t, &self.solver.scene, &arms, ph, q) {
                        Some((d, link)) if d < min_clearance_m => {
                            (d, Some(format!("held object ↔ {link}")))
                        }
                        _ => (min_clearance_m, closest),
                    };
                PhaseSummary {
                    phase: ph.name.clone(),
                    q_rad: q.clone(),
                    hand_error_m: sol.hand_error_m,
                    reachable: sol.hand_error_m <= super::search::REACH_TOL_M,
                    beyond_reach_m: ph
                        .targets_m
                        .iter()
                        .enumerate()
                        .filter_map(|(h, tg)| super::reach::beyond_reach_m(t, h, tg.as_ref()?))
                        .reduce(f64::max),
                    target_inside,
                    target_blocked,
                    min_clearance_m,
                    closest,
                    balance_margin_m: sol
                        .balance_margin_m
                        .is_finite()
                        .then_some(sol.balance_margin_m),
                    feet: feet[p].clone(),
                    outside_zones,
                    most_loaded: loaded,
                    at_limits: d
                        .near_limits(q, AT_LIMIT_FRACTION)
                        .into_iter()
                        .map(|(k, _, _)| t.model.q_joint(k).name.clone())
                        .collect(),
                    discomfort: d.value(q, Shape::of(t)),
                    converged: sol.converged,
                    kkt_residual: sol.kkt_residual,
                    iterations: sol.iterations,
                    solve: sol,
                    search: gp.stats[g],
                }
            })
            .collect()
    }

    /// The rest posture's solve record.
    pub fn rest_solve(&self) -> SqpOutcome {
        self.rest_solve
    }
}

/// How far a held object may sink into a surface and still count as resting on it \[m\].
pub const OBJECT_CONTACT_TOL_M: f64 = 0.005;

/// The deepest overlap of phase `ph`'s held object (an axis-aligned box at its place) with an
/// obstacle, when deeper than resting contact: (signed distance \[m\], obstacle name).
pub fn object_overlap(t: &Task, ph: &super::task::Phase) -> Option<(f64, String)> {
    let o = ph.object?;
    let world_from_box =
        nalgebra::Isometry3::translation(o.center_m[0], o.center_m[1], o.center_m[2]);
    let half = Vector3::new(o.size_m[0], o.size_m[1], o.size_m[2]) / 2.0;
    t.workstation
        .obstacles
        .iter()
        .enumerate()
        .filter_map(|(i, ob)| {
            ob.box_clearance(i, &world_from_box, &half, 0.0)
                .map(|c| (c.distance_m, ob.spec.name.clone()))
        })
        .filter(|(d, _)| *d < -OBJECT_CONTACT_TOL_M)
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// A link's name in words: "l_upper_arm" → "left upper arm" (the side prefixes of the
/// generated worker; other names only lose their underscores).
pub(crate) fn link_words(name: &str) -> String {
    let (side, rest) = match (name.strip_prefix("r_"), name.strip_prefix("l_")) {
        (Some(r), _) => ("right ", r),
        (_, Some(r)) => ("left ", r),
        _ => ("", name),
    };
    format!("{side}{}", rest.replace('_', " "))
}

/// "obstacle 'cart'" or "right forearm ↔ trunk".
fn describe_contact(t: &Task, link: usize, other: &Other) -> String {
    let name = |l: usize| link_words(&t.model.links[l].name);
    match other {
        Other::Obstacle(i) => format!(
            "{} ↔ obstacle '{}'",
            name(link),
            t.workstation.obstacles[*i].spec.name
        ),
        Other::Body { link: l2, .. } => format!("{} ↔ {}", name(link), name(*l2)),
        Other::HeldObject => format!("held object ↔ {}", name(link)),
    }
}

/// Plans a task with the default options (adaptive, discomfort on, baselines).
pub fn plan_task(task: &Task) -> Result<Plan, PlanError> {
    plan_task_with(task, PlanOptions::default())
}

/// The fatigue model in words: the paper's, with the recovery forms its parameters use.
fn fatigue_model_name(params: &[crate::fatigue::MaParams]) -> String {
    use crate::fatigue::Recovery;
    let mut forms: Vec<&str> = Vec::new();
    for p in params {
        let form = match p.recovery {
            Recovery::None => continue,
            Recovery::Constant { .. } => "constant-rate",
            Recovery::Perfusion { .. } => "load-dependent (perfusion-limited)",
            Recovery::Routed { .. } => {
                "load-dependent (perfusion-limited) two-deficit (fast and slow)"
            }
        };
        if !forms.contains(&form) {
            forms.push(form);
        }
    }
    forms.sort_unstable();
    if forms.is_empty() {
        "ma2009 (no recovery)".into()
    } else {
        format!("ma2009 with {} recovery", forms.join(" and "))
    }
}

/// Plans a task with the given options.
pub fn plan_task_with(task: &Task, opts: PlanOptions) -> Result<Plan, PlanError> {
    Planner::new(task, opts.sqp)?.plan(opts)
}
