//! Global search for one phase's posture: deterministic multi-start.
//!
//! Local minima must not decide the answer, so a phase is solved from several starting postures:
//! the previous plan's posture (when re-planning), the standing rest posture, and — for the
//! generated worker — a stoop, a squat, a trunk turned toward the target and two arm
//! configurations (for other bodies: fixed, seeded perturbations of the rest posture). Each is
//! first brought onto the hand targets and the stance by [`solve_ik`], then improved by a few SQP
//! iterations; the most promising ([`SearchSettings::finalists`]) are solved to convergence and
//! the best feasible one is kept. The planner's cross-seeding pass searches from the other
//! phases' postures instead ([`PhaseSolver::extra_seeds`]), all solved to convergence.
//! The starts' local solves run in parallel (rayon), each a function of its start alone.
//! Everything is deterministic: the same problem gives the same posture, whatever posture the
//! search started from and whatever the number of threads.

use super::ik::{IkSettings, solve_ik};
use super::objective::{Discomfort, LoadCost, Shape};
use super::posture::{PostureWork, Scene};
use super::qp::QpError;
use super::sqp::{PhaseProblem, SqpOutcome, SqpSettings, SqpWork, solve_phase};
use super::stepping::Stepping;
use super::task::Task;
use super::zones::ZoneLimits;
use crate::workstation::Workstation;
use nalgebra::Vector3;
use serde::Serialize;
use std::f64::consts::FRAC_PI_2;

/// How far [`PhaseSolver::forearms_turned`] turns a loaded hand's forearm from neutral \[rad\]
/// (70°, within the worker's ±80° of pronation and supination). ASSUMPTION: far enough that the
/// hand's load falls mostly on the wrist's flexors or extensors (cos 70° = 0.34 of it left on
/// the deviators), short of the range's end.
pub const FOREARM_TURN_RAD: f64 = 70.0 * std::f64::consts::PI / 180.0;

/// Multi-start settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchSettings {
    /// SQP iterations given to every seed before choosing the finalists.
    pub screen_iterations: usize,
    /// Seeds solved to convergence.
    pub finalists: usize,
    /// Screen the starts in reverse order (ties between equally good starts then go the other
    /// way): a plan that changes with it depends on the order of its seeds, not on the problem.
    pub reversed: bool,
}

impl Default for SearchSettings {
    fn default() -> Self {
        SearchSettings {
            screen_iterations: 3,
            finalists: 2,
            reversed: false,
        }
    }
}

/// What the search did, for the record.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct SearchStats {
    pub seeds: usize,
    /// Index of the seed the kept posture came from (0 = the first seed).
    pub best_seed: usize,
    /// The kept posture's objective and the first seed's (after the full solve, when it was a
    /// finalist; else after screening).
    pub best_objective: f64,
    pub first_seed_objective: f64,
}

/// The solver of one task: posture workspace, QP and SQP buffers, discomfort, rest posture.
pub struct PhaseSolver<'t> {
    pub task: &'t Task,
    pub scene: Scene,
    pub pw: PostureWork,
    pub work: SqpWork,
    pub discomfort: Discomfort,
    pub search: SearchSettings,
    pub settings: SqpSettings,
    /// Standing at rest (set by the planner).
    pub q_rest: Vec<f64>,
    /// Further starting postures of the next multi-start (the planner sets them to the other
    /// groups' postures in its cross-seeding rounds); when not empty, the given start is always
    /// a finalist, so the search can only improve on it.
    pub extra_seeds: Vec<Vec<f64>>,
    /// Every converged, feasible posture the multi-starts found since the caller last cleared
    /// it (the planner's pool of local optima per group, see `Planner::pool_swap`).
    pub pool: Vec<Vec<f64>>,
    /// The cost of steps to and from the neighbouring phases of the next solves (set by the
    /// planner per group; empty: no cost).
    pub stepping: Stepping,
    /// The held objects of the next solves' phases (set by the planner per group; `None`: none).
    pub held: Option<Workstation>,
    /// Further buffers for the multi-start's solves on other threads (made as needed, kept).
    spares: Vec<(PostureWork, SqpWork)>,
    /// The settings `work` was made with (its QP's precision and row counts), for the spares.
    built_with: SqpSettings,
}

/// A phase to solve: targets, hand forces, and how its cost is weighed.
pub struct PhaseSpec<'a> {
    pub targets_m: [Option<Vector3<f64>>; 2],
    pub hand_force_n: [Vector3<f64>; 2],
    pub discomfort_weight: f64,
    /// The discomfort's shape (the objective's, or the fatigue-only seeds' measure).
    pub shape: Shape,
    pub capacity: &'a [f64],
    /// Where the worker looks (`None`: anywhere).
    pub gaze_m: Option<Vector3<f64>>,
    /// The acceptable posture zones (`None`: unconstrained).
    pub zones: Option<ZoneLimits>,
}

fn set(task: &Task, q: &mut [f64], name: &str, v: f64) {
    if let Ok(k) = task.model.q_index(name) {
        let j = task.model.q_joint(k);
        q[k] = v.clamp(j.lower_rad, j.upper_rad);
    }
}

/// Where a seated worker's rest solve starts: the pelvis over the seat's centre with the seat
/// point on its top, hips and knees bent 90° (the solve brings the feet onto the stance); `None`
/// for a standing body.
pub fn seated_start(task: &Task) -> Option<Vec<f64>> {
    let seat = task.stance.as_ref()?.seat.as_ref()?;
    let m = &task.model;
    let mut q = vec![0.0; m.nq()];
    let mut data = crate::body::StaticsData::new(m, 0);
    crate::body::forward_kinematics(m, &mut data, &q);
    let (_, hips) = data.link_pose(m, seat.link);
    let c = seat
        .outline_m
        .iter()
        .fold(nalgebra::Vector2::zeros(), |a, b| a + b)
        / seat.outline_m.len() as f64;
    set(task, &mut q, "pelvis_tx", c.x - hips.x);
    set(task, &mut q, "pelvis_ty", c.y - hips.y);
    set(
        task,
        &mut q,
        "pelvis_tz",
        seat.height_m - seat.contact_in_link_m.z - hips.z,
    );
    for side in ["r_", "l_"] {
        set(task, &mut q, &format!("{side}hip_flexion"), FRAC_PI_2);
        set(task, &mut q, &format!("{side}knee_flexion"), FRAC_PI_2);
    }
    Some(q)
}

impl<'t> PhaseSolver<'t> {
    pub fn new(task: &'t Task, settings: SqpSettings) -> Result<Self, QpError> {
        let scene = Scene::new(task);
        let work = SqpWork::new(task, &scene, settings)?;
        Ok(PhaseSolver {
            task,
            pw: PostureWork::new(task),
            work,
            discomfort: Discomfort::new(task),
            scene,
            search: SearchSettings::default(),
            settings,
            q_rest: vec![0.0; task.model.nq()],
            extra_seeds: Vec::new(),
            pool: Vec::new(),
            stepping: Stepping::default(),
            held: None,
            spares: Vec::new(),
            built_with: settings,
        })
    }

    /// QP solves so far (on every thread's buffers).
    pub fn qp_solves(&self) -> u64 {
        self.work.qp.solves + self.spares.iter().map(|(_, w)| w.qp.solves).sum::<u64>()
    }

    /// Interior-point iterations of all QP solves so far (on every thread's buffers).
    pub fn ipm_iterations(&self) -> u64 {
        self.work.qp.ipm_iterations
            + self
                .spares
                .iter()
                .map(|(_, w)| w.qp.ipm_iterations)
                .sum::<u64>()
    }

    /// `q` with the forearm of every hand that holds a load pronated and, as a second posture,
    /// supinated ([`FOREARM_TURN_RAD`] from mid-position; none for a body without
    /// `r_forearm_pronation` / `l_forearm_pronation` joints or a phase without a hand load).
    /// Which wrist muscles carry the hand's load is a choice between local optima: with the
    /// forearm in mid-position the load's moment falls on the wrist's deviators, turned on its
    /// flexors or extensors, and a local solve from one does not reach the other (turning the
    /// forearm a little loads a second muscle group at once while it relieves the first only
    /// to second order). The planner's forearm round starts from these turns of the posture it
    /// improves.
    pub fn forearms_turned(&self, q: &[f64], hand_force_n: &[Vector3<f64>; 2]) -> Vec<Vec<f64>> {
        let m = &self.task.model;
        [FOREARM_TURN_RAD, -FOREARM_TURN_RAD]
            .iter()
            .filter_map(|&turn| {
                let mut turned = q.to_vec();
                for (h, side) in ["r_", "l_"].iter().enumerate() {
                    if hand_force_n[h] != Vector3::zeros()
                        && let Ok(k) = m.q_index(&format!("{side}forearm_pronation"))
                    {
                        let j = m.q_joint(k);
                        turned[k] = turn.clamp(j.lower_rad, j.upper_rad);
                    }
                }
                (turned != q).then_some(turned)
            })
            .collect()
    }

    /// Starting postures for a phase with these targets (before IK).
    pub fn seeds(&self, targets: &[Option<Vector3<f64>>; 2]) -> Vec<Vec<f64>> {
        let t = self.task;
        let rest = self.q_rest.clone();
        let mut out = vec![rest.clone()];
        let worker =
            t.model.q_index("lumbar_flexion").is_ok() && t.model.q_index("pelvis_tz").is_ok();
        let centre = targets
            .iter()
            .flatten()
            .fold(Vector3::zeros(), |a, b| a + b)
            / targets.iter().flatten().count().max(1) as f64;
        if worker {
            let mut stoop = rest.clone();
            set(t, &mut stoop, "lumbar_flexion", 0.5);
            set(t, &mut stoop, "pelvis_tilt", 0.35);
            out.push(stoop);
            let mut squat = rest.clone();
            let tz = t.model.q_index("pelvis_tz").map(|k| rest[k]).unwrap_or(0.0);
            set(t, &mut squat, "pelvis_tz", tz - 0.25);
            for side in ["r_", "l_"] {
                set(t, &mut squat, &format!("{side}hip_flexion"), 0.9);
                set(t, &mut squat, &format!("{side}knee_flexion"), 1.3);
                set(t, &mut squat, &format!("{side}ankle_dorsiflexion"), 0.35);
            }
            set(t, &mut squat, "lumbar_flexion", 0.2);
            out.push(squat);
            let azimuth = centre.y.atan2(centre.x.max(0.05));
            let mut twist = rest.clone();
            set(t, &mut twist, "lumbar_axial_rotation", 0.5 * azimuth);
            set(t, &mut twist, "pelvis_rotation", 0.3 * azimuth);
            out.push(twist);
            // placed feet: the rest posture turned to face the work and stepped up to it, the
            // stance's centre a forearm's length short of the targets (within the area)
            if let (Some(pl), Ok(kx), Ok(ky), Ok(kr)) = (
                t.stance.as_ref().and_then(|st| st.placement.as_ref()),
                t.model.q_index("pelvis_tx"),
                t.model.q_index("pelvis_ty"),
                t.model.q_index("pelvis_rotation"),
            ) {
                let st = t.stance.as_ref().expect("placed feet stand");
                let c0 = st
                    .support_polygon_m
                    .iter()
                    .fold(nalgebra::Vector2::zeros(), |a, b| a + b)
                    / st.support_polygon_m.len().max(1) as f64;
                let to = centre.xy() - c0;
                if to.norm() > 0.05 {
                    let az = to.y.atan2(to.x);
                    let dir = nalgebra::Vector2::new(az.cos(), az.sin());
                    let (lo, hi) = pl.area_m.iter().fold(
                        (
                            nalgebra::Vector2::repeat(f64::INFINITY),
                            nalgebra::Vector2::repeat(f64::NEG_INFINITY),
                        ),
                        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
                    );
                    let margin = nalgebra::Vector2::repeat(0.2);
                    let c1 = (centre.xy() - 0.35 * dir)
                        .sup(&(lo + margin))
                        .inf(&(hi - margin));
                    let p0 = nalgebra::Vector2::new(rest[kx], rest[ky]) - c0;
                    let rot = nalgebra::Rotation2::new(az);
                    let p1 = c1 + rot * p0;
                    let mut facing = rest.clone();
                    set(t, &mut facing, "pelvis_rotation", rest[kr] + az);
                    set(t, &mut facing, "pelvis_tx", p1.x);
                    set(t, &mut facing, "pelvis_ty", p1.y);
                    out.push(facing);
                }
            }
            let geo = crate::body::worker::worker_geometry(&t.worker);
            let elevation = (centre.z - geo.shoulder_height_m).atan2(centre.x.max(0.05));
            for (abd, rot) in [(0.1, 0.0), (0.6, -0.6)] {
                let mut arm = rest.clone();
                for (h, side) in ["r_", "l_"].iter().enumerate() {
                    if targets[h].is_some() {
                        set(
                            t,
                            &mut arm,
                            &format!("{side}shoulder_flexion"),
                            1.3 + elevation,
                        );
                        set(t, &mut arm, &format!("{side}shoulder_abduction"), abd);
                        set(t, &mut arm, &format!("{side}shoulder_rotation"), rot);
                        set(t, &mut arm, &format!("{side}elbow_flexion"), 0.6);
                    }
                }
                out.push(arm);
            }
        } else {
            // Seeded perturbations of the rest posture (splitmix64, fixed seed).
            let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
            let mut next = || {
                state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
                let mut z = state;
                z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
            };
            for _ in 0..4 {
                let mut q = rest.clone();
                for (k, qk) in q.iter_mut().enumerate() {
                    let j = t.model.q_joint(k);
                    let (lo, hi) = (
                        j.lower_rad.max(-std::f64::consts::PI),
                        j.upper_rad.min(std::f64::consts::PI),
                    );
                    *qk = (*qk + 0.3 * (hi - lo) * (2.0 * next() - 1.0))
                        .clamp(j.lower_rad, j.upper_rad);
                }
                out.push(q);
            }
        }
        out
    }

    /// Solves one phase from `start` (local), or globally from the seeds when `multistart`.
    /// `q` receives the posture: the best that meets the targets, the feet, the balance and the
    /// clearances, or, when no posture does, the nearest one that keeps everything but the
    /// targets ([`Self::nearest_feasible`]).
    pub fn solve(
        &mut self,
        spec: &PhaseSpec,
        cost: &mut dyn LoadCost,
        start: Option<&[f64]>,
        multistart: bool,
        q: &mut Vec<f64>,
    ) -> Result<(SqpOutcome, SearchStats), QpError> {
        let (mut out, stats) = self.solve_elastic(spec, cost, start, multistart, q)?;
        if (out.hand_error_m > REACH_TOL_M || out.feasibility > INFEASIBLE_M)
            && let Some((nq, nout)) = self.nearest_feasible(spec, cost, q)?
        {
            *q = nq;
            out = nout;
        }
        Ok((out, stats))
    }

    /// [`Self::solve`] with the targets, feet, balance and clearances as penalties only.
    fn solve_elastic(
        &mut self,
        spec: &PhaseSpec,
        cost: &mut dyn LoadCost,
        start: Option<&[f64]>,
        multistart: bool,
        q: &mut Vec<f64>,
    ) -> Result<(SqpOutcome, SearchStats), QpError> {
        let mut starts: Vec<Vec<f64>> = Vec::new();
        if let Some(s) = start {
            starts.push(s.to_vec());
        }
        let keep_start = multistart && start.is_some() && !self.extra_seeds.is_empty();
        if keep_start {
            starts.append(&mut self.extra_seeds);
        } else if multistart || starts.is_empty() {
            starts.extend(self.seeds(&spec.targets_m));
        }
        // Bring every start onto the targets and the stance.
        for s in starts.iter_mut() {
            let reference = s.clone();
            solve_ik(
                self.task,
                &mut self.pw,
                &spec.targets_m,
                &reference,
                s,
                IkSettings::default(),
            );
        }
        if self.search.reversed {
            starts.reverse();
        }
        let full = self.settings;
        if starts.len() == 1 {
            let mut qq = starts.pop().unwrap_or_default();
            let out = self.run(spec, cost, &mut qq, full)?;
            *q = qq;
            return Ok((
                out,
                SearchStats {
                    seeds: 1,
                    best_seed: 0,
                    best_objective: out.objective,
                    first_seed_objective: out.objective,
                },
            ));
        }
        let screen = SqpSettings {
            max_iterations: self.search.screen_iterations,
            ..full
        };
        let mut screened: Vec<(f64, usize, Vec<f64>, SqpOutcome)> = self
            .run_all(spec, cost, starts, screen)?
            .into_iter()
            .enumerate()
            .map(|(i, (s, out))| (rank(&out), i, s, out))
            .collect();
        let first_screen = screened[0].3.objective;
        screened.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let n_seeds = screened.len();
        let mut best: Option<(f64, usize, Vec<f64>, SqpOutcome)> = None;
        let mut first_full = None;
        // a cross-seeding search solves every start to convergence: with no screening cut, which
        // seeds go on does not hinge on the screening's last digits, and the start is among them
        let finalists = if keep_start {
            usize::MAX
        } else {
            self.search.finalists.max(1)
        };
        let (order, finals): (Vec<usize>, Vec<Vec<f64>>) = screened
            .into_iter()
            .take(finalists)
            .map(|(_, i, s, _)| (i, s))
            .unzip();
        let solved = self.run_all(spec, cost, finals, full)?;
        for (i, (s, out)) in order.into_iter().zip(solved) {
            if i == 0 {
                first_full = Some(out.objective);
            }
            let r = rank(&out);
            if r < 1e6 {
                self.pool.push(s.clone());
            }
            if best
                .as_ref()
                .is_none_or(|b| r < b.0 || (r == b.0 && i < b.1))
            {
                best = Some((r, i, s, out));
            }
        }
        let (_, bi, bq, bout) = best.expect("at least one finalist");
        *q = bq;
        Ok((
            bout,
            SearchStats {
                seeds: n_seeds,
                best_seed: bi,
                best_objective: bout.objective,
                first_seed_objective: first_full.unwrap_or(first_screen),
            },
        ))
    }

    /// A target out of reach (of the hand, or of a hand that keeps the balance): the elastic
    /// solve reaches as far as it can, but it trades the hand's distance against the feet and the
    /// balance margin (their slacks are penalties too), so its posture may lean off balance or
    /// slide a foot. The posture reported instead is the
    /// best one that keeps every other constraint exactly: each hand's target is moved back on
    /// the line from where that hand is at rest toward the real target, and the farthest point
    /// still reached with feet, balance and clearances intact is found by bisection (local
    /// solves from the previous feasible posture). `None` when even the rest-side end fails.
    fn nearest_feasible(
        &mut self,
        spec: &PhaseSpec,
        cost: &mut dyn LoadCost,
        q_elastic: &[f64],
    ) -> Result<Option<(Vec<f64>, SqpOutcome)>, QpError> {
        let task = self.task;
        let q_rest = self.q_rest.clone();
        self.pw.statics(task, &q_rest, &[Vector3::zeros(); 2]);
        let anchor: [Option<Vector3<f64>>; 2] =
            std::array::from_fn(|h| self.pw.hand_position(task, h));
        let along = |lambda: f64| -> [Option<Vector3<f64>>; 2] {
            std::array::from_fn(|h| match (spec.targets_m[h], anchor[h]) {
                (Some(t), Some(a)) => Some(a + lambda * (t - a)),
                (t, _) => t,
            })
        };
        let full = self.settings;
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        let mut found: Option<(Vec<f64>, SqpOutcome)> = None;
        for i in 0..NEAREST_BISECTIONS {
            // try the rest-side end once first if nothing has worked yet
            let lambda = if i == NEAREST_BISECTIONS - 1 && found.is_none() {
                0.0
            } else {
                0.5 * (lo + hi)
            };
            let proxy = PhaseSpec {
                targets_m: along(lambda),
                hand_force_n: spec.hand_force_n,
                discomfort_weight: spec.discomfort_weight,
                shape: spec.shape,
                capacity: spec.capacity,
                gaze_m: spec.gaze_m,
                zones: spec.zones,
            };
            let mut qq = found
                .as_ref()
                .map_or_else(|| q_elastic.to_vec(), |(q, _)| q.clone());
            solve_ik(
                task,
                &mut self.pw,
                &proxy.targets_m,
                &qq.clone(),
                &mut qq,
                IkSettings::default(),
            );
            let out = self.run(&proxy, cost, &mut qq, full)?;
            if out.hand_error_m <= FEASIBLE_TOL && out.feasibility <= FEASIBLE_TOL {
                lo = lambda;
                found = Some((qq, out));
            } else {
                hi = lambda;
            }
        }
        Ok(found.map(|(q, mut out)| {
            // the error against the real targets
            self.pw.statics(task, &q, &spec.hand_force_n);
            out.hand_error_m = (0..2)
                .filter_map(|h| Some((self.pw.hand_position(task, h)? - spec.targets_m[h]?).norm()))
                .fold(0.0, f64::max);
            (q, out)
        }))
    }

    fn run(
        &mut self,
        spec: &PhaseSpec,
        cost: &mut dyn LoadCost,
        q: &mut [f64],
        settings: SqpSettings,
    ) -> Result<SqpOutcome, QpError> {
        let (fixed, pw, work, _) = self.parts();
        fixed.run_in(pw, work, spec, cost, q, settings)
    }

    /// What the local solves read, and the buffers they write: the solver's own and the spares.
    #[allow(clippy::type_complexity)]
    fn parts(
        &mut self,
    ) -> (
        Fixed<'_, 't>,
        &mut PostureWork,
        &mut SqpWork,
        &mut Vec<(PostureWork, SqpWork)>,
    ) {
        (
            Fixed {
                task: self.task,
                scene: &self.scene,
                discomfort: &self.discomfort,
                stepping: &self.stepping,
                held: self.held.as_ref(),
                settings: self.settings,
                built_with: self.built_with,
            },
            &mut self.pw,
            &mut self.work,
            &mut self.spares,
        )
    }

    /// Solves from each start, on as many threads as rayon gives; returns the postures and
    /// outcomes in the starts' order. Each local solve is a function of its problem and start
    /// alone (fresh curvature, penalties and QP solver: [`solve_phase`]), so the answer is the
    /// serial one whatever the number of threads; `cost` is copied for each solve
    /// ([`LoadCost::fork`]).
    fn run_all(
        &mut self,
        spec: &PhaseSpec,
        cost: &dyn LoadCost,
        starts: Vec<Vec<f64>>,
        settings: SqpSettings,
    ) -> Result<Vec<(Vec<f64>, SqpOutcome)>, QpError> {
        use rayon::prelude::*;
        use std::sync::{Mutex, MutexGuard, PoisonError};
        fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
            m.lock().unwrap_or_else(PoisonError::into_inner)
        }
        let (fixed, pw, work, spare) = self.parts();
        // the solver's own buffers first, then the spares, then new ones
        let own = Mutex::new(Some((pw, work)));
        let spares = Mutex::new(std::mem::take(spare));
        let results: Vec<Result<(Vec<f64>, SqpOutcome), QpError>> = starts
            .into_par_iter()
            .map(|mut q| {
                let mut c = cost.fork();
                let taken = lock(&own).take();
                let r = if let Some((pw, work)) = taken {
                    let r = fixed.run_in(pw, work, spec, &mut *c, &mut q, settings);
                    *lock(&own) = Some((pw, work));
                    r
                } else {
                    let popped = lock(&spares).pop();
                    let (mut pw, mut work) = match popped {
                        Some(b) => b,
                        None => (
                            PostureWork::new(fixed.task),
                            SqpWork::new(fixed.task, fixed.scene, fixed.built_with)?,
                        ),
                    };
                    let r = fixed.run_in(&mut pw, &mut work, spec, &mut *c, &mut q, settings);
                    lock(&spares).push((pw, work));
                    r
                };
                r.map(|out| (q, out))
            })
            .collect();
        *spare = spares.into_inner().unwrap_or_else(PoisonError::into_inner);
        results.into_iter().collect()
    }
}

/// What every local solve of a phase solver reads and none changes.
struct Fixed<'a, 't> {
    task: &'t Task,
    scene: &'a Scene,
    discomfort: &'a Discomfort,
    stepping: &'a Stepping,
    held: Option<&'a Workstation>,
    settings: SqpSettings,
    /// The settings the solver's own buffers were made with (for new spares).
    built_with: SqpSettings,
}

impl Fixed<'_, '_> {
    /// One local solve in the given buffers.
    fn run_in(
        &self,
        pw: &mut PostureWork,
        work: &mut SqpWork,
        spec: &PhaseSpec,
        cost: &mut dyn LoadCost,
        q: &mut [f64],
        settings: SqpSettings,
    ) -> Result<SqpOutcome, QpError> {
        work.settings = settings;
        let mut prob = PhaseProblem {
            targets_m: spec.targets_m,
            hand_force_n: spec.hand_force_n,
            cost,
            discomfort: self.discomfort,
            discomfort_weight: spec.discomfort_weight,
            shape: spec.shape,
            capacity: spec.capacity,
            gaze_m: spec.gaze_m,
            stepping: self.stepping,
            zones: spec.zones,
            held: self.held,
        };
        let r = solve_phase(self.task, self.scene, pw, work, &mut prob, q);
        work.settings = self.settings;
        r
    }
}

/// A hand this far from its target \[m\] has not reached it (the planner's "out of reach").
pub const REACH_TOL_M: f64 = 0.01;

/// Bisection steps of [`PhaseSolver::nearest_feasible`] (the reach found to 2⁻⁸ of the way).
const NEAREST_BISECTIONS: usize = 8;

/// A solve violating its feet, balance or clearances by more than this \[m\] (typically a hand
/// that reaches by leaning off balance) is replaced by the nearest feasible posture.
const INFEASIBLE_M: f64 = 1e-3;

/// Largest violation of a feasible solve \[m or rad\].
const FEASIBLE_TOL: f64 = 1e-4;

/// Ranks outcomes: feasible (targets met, no collision or balance violation) first, then by
/// objective. Infeasible ones rank by their violation.
fn rank(o: &SqpOutcome) -> f64 {
    let violation = o.hand_error_m.max(o.feasibility);
    if violation <= 1e-4 {
        o.objective
    } else {
        1e6 + violation
    }
}
