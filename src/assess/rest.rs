//! Work and rest: how much rest per cycle keeps every muscle group's capacity above a floor.
//!
//! Two answers, side by side:
//!
//! * **Model** (Ma et al. 2009 with the recovery term `dc/dt = −k f c + R(f) (1 − c)`): the plan's
//!   phase loads are replayed cycle by cycle, exactly (closed forms per held step), with a rest
//!   of `r` seconds (rest posture, no load) at the end of each cycle. The smallest `r` (to 0.1 s)
//!   for which every group's capacity stays at or above the floor — and above its load, so
//!   nothing is exhausted — over the task's cycles is found by bisection. Capacity is monotone
//!   within a held step, so checking step ends is exact. The postures are the plan's; more or
//!   less rest would let the adaptive planner choose slightly different ones (not re-planned).
//!   With `R = 0` (the paper's model) rest restores nothing and only "no rest needed" or
//!   "rest cannot help" are possible answers. The bisection stops at 0.1 s or 10⁻³ of the
//!   cycle's work time, whichever is coarser (at most 40 replays).
//! * **Rohmert (1973)**, the classic rest-allowance rule for static work: a hold of `t` minutes
//!   at relative load `f > 0.15` needs `RA = 18 · (t/T)^1.4 · (f − 0.15)^0.5` of `t` as rest,
//!   where `T(f) = −1.5 + 2.1/f − 0.6/f² + 0.1/f³` min is Rohmert's endurance time (Table 2's
//!   rohmert-general). The rule is for static work: only holds longer than 4 s count (a hold:
//!   the run of consecutive phases of the same work, `t` its whole length, its allowance shared
//!   by its phases). Per group, the rest of a cycle is the sum over its holds; the cycle needs
//!   the largest group's (the shift verdict's Rohmert criterion states the same figure). Source: W. Rohmert, Problems of determination of rest
//!   allowances, Part 2, Applied Ergonomics 4(3):158–162 (1973), formula as commonly cited; the
//!   original was not available to check here.
//!
//! The floor is a planning choice (default [`DEFAULT_CAPACITY_FLOOR`], an ASSUMPTION: keep 70 %
//! of MVC available).

use crate::fatigue::ma::CycleMap;
use crate::fatigue::{MaParams, MaState};
use crate::plan::zones::STATIC_HOLD_S;
use crate::plan::{Plan, Task};
use serde::Serialize;

/// Default capacity floor (fraction of MVC) — an ASSUMPTION, not from the literature.
pub const DEFAULT_CAPACITY_FLOOR: f64 = 0.7;

/// The model's answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelRest {
    /// Lowest capacity over the task with the task's own rest, and where.
    pub min_capacity_current: f64,
    pub limiting_half_joint: String,
    /// Rest per cycle \[s\] that keeps every capacity at or above the floor; `None`: no amount
    /// of rest does (see `note`).
    pub rest_s_per_cycle: Option<f64>,
    pub min_capacity_at_recommended: Option<f64>,
    pub note: String,
}

/// Rohmert's rest allowance for one half-joint.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RohmertGroup {
    pub half_joint: String,
    pub rest_s_per_cycle: f64,
}

/// Rohmert's answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RohmertRest {
    pub rest_s_per_cycle: f64,
    pub limiting_half_joint: String,
    /// Groups needing any rest, largest first.
    pub groups: Vec<RohmertGroup>,
    /// Holds above 100 % MVC, for which the rule has no answer.
    pub over_mvc: Vec<String>,
}

/// Rest advice for a plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RestAdvice {
    pub capacity_floor: f64,
    pub current_rest_s: f64,
    pub work_s_per_cycle: f64,
    pub model: ModelRest,
    pub rohmert: RohmertRest,
}

/// Rohmert's endurance time \[min\] at relative load `f` (valid for 0.15 < f ≤ 1).
pub fn rohmert_endurance_min(f: f64) -> f64 {
    -1.5 + 2.1 / f - 0.6 / (f * f) + 0.1 / (f * f * f)
}

/// Rohmert's rest allowance as a fraction of a hold of `hold_s` seconds at load `f`
/// (0 at or below 15 % MVC; `None` above 100 % MVC).
///
/// ```
/// use posture_opt::assess::rest::{rohmert_allowance, rohmert_endurance_min};
/// // T(0.5) = -1.5 + 4.2 - 2.4 + 0.8 = 1.1 min; holding that long needs 18·√0.35 ≈ 10.65 × t
/// assert!((rohmert_endurance_min(0.5) - 1.1).abs() < 1e-12);
/// assert!((rohmert_allowance(0.5, 66.0).unwrap() - 10.649).abs() < 1e-3);
/// ```
pub fn rohmert_allowance(f: f64, hold_s: f64) -> Option<f64> {
    if f <= 0.15 {
        return Some(0.0);
    }
    if f > 1.0 {
        return None;
    }
    let t_min = hold_s / 60.0;
    Some(18.0 * (t_min / rohmert_endurance_min(f)).powf(1.4) * (f - 0.15).sqrt())
}

/// Loads of each half-joint in the plan's rest posture.
pub fn rest_loads(plan: &Plan) -> Vec<f64> {
    plan.postures
        .iter()
        .find(|p| p.phase == "rest")
        .map(|p| p.load.clone())
        .unwrap_or_else(|| vec![0.0; plan.half_joint_ids.len()])
}

/// The per-cycle work of a plan: for each cycle, the posture (index into `plan.postures`) of each
/// phase. Cycles the plan did not complete repeat the last complete one.
fn cycle_postures(task: &Task, plan: &Plan) -> Option<Vec<Vec<usize>>> {
    let done = plan.summary.cycles_done as usize;
    let mut cycles: Vec<Vec<usize>> = vec![Vec::with_capacity(task.phases.len()); done];
    let st = &plan.steps;
    for i in 0..st.t_s.len() {
        if st.phase(i) == "rest" && plan.postures[st.posture[i]].phase == "rest" {
            continue;
        }
        if let Some(c) = cycles.get_mut(st.cycle[i] as usize) {
            c.push(st.posture[i]);
        }
    }
    let last = cycles.last()?.clone();
    cycles.resize(task.cycles as usize, last);
    Some(cycles)
}

/// Replays the task with `rest_s` per cycle: (smallest margin above max(floor, load), lowest
/// capacity, its half-joint).
#[allow(clippy::too_many_arguments)]
fn replay(
    task: &Task,
    params: &[MaParams],
    plan: &Plan,
    cycles: &[Vec<usize>],
    f_rest: &[f64],
    rest_s: f64,
    floor: f64,
    state: &mut [MaState],
) -> (f64, f64, usize) {
    state.fill(MaState::FRESH);
    let mut margin = f64::INFINITY;
    let mut min_c = (f64::INFINITY, 0);
    let mut check = |state: &[MaState], f: &[f64]| {
        for (h, s) in state.iter().enumerate() {
            margin = margin.min(s.capacity - floor.max(f[h]));
            if s.capacity < min_c.0 {
                min_c = (s.capacity, h);
            }
        }
    };
    let mut run = |cycle: &[usize], state: &mut [MaState]| {
        for (p, &pi) in cycle.iter().enumerate() {
            let f = &plan.postures[pi].load;
            for (h, s) in state.iter_mut().enumerate() {
                params[h].hold(s, f[h], task.phases[p].duration_s);
            }
            check(state, f);
        }
        if rest_s > 0.0 {
            for (h, s) in state.iter_mut().enumerate() {
                params[h].hold(s, f_rest[h], rest_s);
            }
            check(state, f_rest);
        }
    };
    // The cycles after the last re-plan are all alike: the first and the last of them are held
    // step by step, those between are skipped in closed form. Each step's end capacity is an
    // increasing affine function of the capacity at its cycle's start, which moves monotonically
    // from cycle to cycle ([`CycleMap`]), so over alike cycles the margins and capacities are
    // extreme at the first or the last: the answer is the step-by-step one, in time independent
    // of the number of cycles.
    let n = cycles.len();
    let tail = (1..n)
        .rev()
        .find(|&i| cycles[i] != cycles[i - 1])
        .unwrap_or(0);
    for cycle in &cycles[..(tail + 1).min(n)] {
        run(cycle, state);
    }
    let alike_after = n.saturating_sub(tail + 1);
    if alike_after >= 2 {
        let cycle = &cycles[tail];
        for (h, s) in state.iter_mut().enumerate() {
            let steps = cycle
                .iter()
                .enumerate()
                .map(|(p, &pi)| (plan.postures[pi].load[h], task.phases[p].duration_s))
                .chain((rest_s > 0.0).then_some((f_rest[h], rest_s)));
            s.capacity =
                CycleMap::new(&params[h], steps).after(s.capacity, (alike_after - 1) as f64);
        }
    }
    if alike_after >= 1 {
        run(&cycles[n - 1], state);
    }
    (margin, min_c.0, min_c.1)
}

/// Rest advice for `plan` (a plan of `task`) with capacity floor `floor` in (0, 1).
pub fn rest_advice(task: &Task, plan: &Plan, floor: f64) -> RestAdvice {
    rest_advice_with(task, plan, floor, &task.fatigue)
}

/// [`rest_advice`] with other fatigue parameters (one per half-joint), for the uncertainty
/// analysis: the plan's postures, another muscle.
pub fn rest_advice_with(task: &Task, plan: &Plan, floor: f64, params: &[MaParams]) -> RestAdvice {
    let work_s: f64 = task.phases.iter().map(|p| p.duration_s).sum();
    let ids = |h: usize| task.half_joints[h].id.clone();
    let rohmert = rohmert_rest(task, plan);
    let model = match cycle_postures(task, plan) {
        None => ModelRest {
            min_capacity_current: plan.summary.lowest_capacity,
            limiting_half_joint: plan.summary.lowest_capacity_half_joint.clone(),
            rest_s_per_cycle: None,
            min_capacity_at_recommended: None,
            note: "a muscle group is exhausted within the first cycle: rest between cycles cannot help; lower the load or change the layout".into(),
        },
        Some(cycles) => {
            let f_rest = rest_loads(plan);
            let mut state = vec![MaState::FRESH; task.half_joints.len()];
            let (_, c_now, h_now) = replay(task, params, plan, &cycles, &f_rest, task.rest_s, floor, &mut state);
            let feasible = |r: f64, st: &mut [MaState]| {
                replay(task, params, plan, &cycles, &f_rest, r, floor, st).0 >= 0.0
            };
            let r_max = 10.0 * work_s;
            let any_recovery = params.iter().any(|p| p.r_at(0.0) > 0.0);
            // Feasibility need not be monotone in the rest: a rest posture that loads a group
            // above its recovery limit tires it during rest, so a long rest can break the floor
            // that a short one keeps. Scan upward for the first rest that keeps it, then refine.
            let grid_s = (r_max / 200.0).max(0.1);
            let mut first_ok = None;
            let mut last_bad = 0.0;
            let mut r = 0.0;
            while r <= r_max + 1e-9 {
                if feasible(r, &mut state) {
                    first_ok = Some(r);
                    break;
                }
                last_bad = r;
                r += grid_s;
            }
            let (rest, note) = match first_ok {
                Some(0.0) => (Some(0.0), "no rest needed to stay above the floor".to_string()),
                None => {
                    let why = if any_recovery {
                        format!(
                            "no rest up to {r_max:.0} s per cycle (10x the work time) keeps every group above the floor: a single cycle's work takes it too low, or the rest posture itself tires a group; lower the load or change the layout"
                        )
                    } else {
                        "the fatigue model has no recovery (R = 0): rest restores nothing; give recovery_per_min in the task to size rests".to_string()
                    };
                    (None, why)
                }
                Some(ok) => {
                    let (mut lo, mut hi) = (last_bad, ok);
                    let resolution = 0.05;
                    let mut replays = 0;
                    while hi - lo > resolution && replays < 40 {
                        replays += 1;
                        let mid = 0.5 * (lo + hi);
                        if feasible(mid, &mut state) {
                            hi = mid;
                        } else {
                            lo = mid;
                        }
                    }
                    // rounded up to 0.1 s, and checked there (the floor may break again above)
                    let mut r = (hi * 10.0).ceil() / 10.0;
                    if !feasible(r, &mut state) {
                        r = hi;
                    }
                    (
                        Some(r),
                        "smallest rest per cycle keeping every capacity at or above the floor, with the plan's postures".to_string(),
                    )
                }
            };
            let c_rec =
                rest.map(|r| replay(task, params, plan, &cycles, &f_rest, r, floor, &mut state).1);
            ModelRest {
                min_capacity_current: c_now,
                limiting_half_joint: ids(h_now),
                rest_s_per_cycle: rest,
                min_capacity_at_recommended: c_rec,
                note,
            }
        }
    };
    RestAdvice {
        capacity_floor: floor,
        current_rest_s: task.rest_s,
        work_s_per_cycle: work_s,
        model,
        rohmert,
    }
}

fn rohmert_rest(task: &Task, plan: &Plan) -> RohmertRest {
    let nh = task.half_joints.len();
    let mut need = vec![0.0_f64; nh];
    let mut over = vec![false; nh];
    let mut per_cycle = vec![0.0_f64; nh];
    let mut cycle = u32::MAX;
    let st = &plan.steps;
    // Rohmert's rule is for static holds: a phase's hold (the run of phases of the same work it
    // belongs to) longer than 4 s, its allowance that of the whole hold, shared by its steps
    // (as the shift verdict's criterion counts it)
    // each posture's static hold, looked up once (not per step: a task may have 10⁵ cycles)
    let holds = task.holds();
    let static_hold_s: Vec<Option<f64>> = plan
        .postures
        .iter()
        .map(|posture| {
            if posture.phase == "rest" {
                return None;
            }
            let p = task.phases.iter().position(|ph| ph.name == posture.phase)?;
            holds.get(p).map(|h| h.0).filter(|&h| h > STATIC_HOLD_S)
        })
        .collect();
    for i in 0..st.t_s.len() {
        let posture = &plan.postures[st.posture[i]];
        let Some(hold_s) = static_hold_s[st.posture[i]] else {
            continue;
        };
        if st.cycle[i] != cycle {
            for h in 0..nh {
                need[h] = need[h].max(per_cycle[h]);
            }
            per_cycle.fill(0.0);
            cycle = st.cycle[i];
        }
        for (h, &f) in posture.load.iter().enumerate() {
            match rohmert_allowance(f, hold_s) {
                Some(ra) => per_cycle[h] += ra * st.duration_s[i],
                None => over[h] = true,
            }
        }
    }
    for h in 0..nh {
        need[h] = need[h].max(per_cycle[h]);
    }
    let mut groups: Vec<RohmertGroup> = (0..nh)
        .filter(|&h| need[h] > 0.0)
        .map(|h| RohmertGroup {
            half_joint: task.half_joints[h].id.clone(),
            rest_s_per_cycle: need[h],
        })
        .collect();
    groups.sort_by(|a, b| b.rest_s_per_cycle.total_cmp(&a.rest_s_per_cycle));
    let (rest, limiting) = groups
        .first()
        .map(|g| (g.rest_s_per_cycle, g.half_joint.clone()))
        .unwrap_or((0.0, String::new()));
    RohmertRest {
        rest_s_per_cycle: rest,
        limiting_half_joint: limiting,
        groups,
        over_mvc: (0..nh)
            .filter(|&h| over[h])
            .map(|h| task.half_joints[h].id.clone())
            .collect(),
    }
}
