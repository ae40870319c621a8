//! What the fatigue index means for a task, in words and numbers an ergonomist can use: how long
//! the worker could keep up the pace before a muscle group gives out, how much of its endurance
//! each hold uses, and how much capacity is left at the end of the shift.
//!
//! * **Time to exhaustion at this pace**: the task's cycle kept up from the start with the last
//!   plan's postures, every step held exactly, until a group's capacity falls to its load, the
//!   capacities settle into their periodic steady state ("never"), or a week has passed.
//! * **Endurance used**: for each phase and group, the hold's duration against the maximum
//!   endurance time of that load from a rested muscle (MET); the largest share is reported.
//! * **Capacity left**: the lowest capacity at the end of the task (fraction of strength).

use crate::fatigue::ma::CycleMap;
use crate::fatigue::{MaParams, MaState, PreparedHold};
use crate::plan::{Plan, Task};
use serde::Serialize;
use std::collections::HashMap;

/// Words for a pace no group gives out at within the time followed, by `exhaustion_verdict`:
/// "never (settles)", or "not determined (followed N)" when the capacities had not settled yet.
pub fn no_exhaustion_words(verdict: &str, minutes_followed: f64) -> String {
    if verdict == "not_determined" {
        let h = minutes_followed / 60.0;
        if h >= 1.0 {
            format!("not determined (followed {h:.0} h)")
        } else {
            format!("not determined (followed {minutes_followed:.1} min)")
        }
    } else {
        "never (settles)".into()
    }
}

/// The meaning of a plan's fatigue.
#[derive(Debug, Clone, Serialize)]
pub struct Meaning {
    /// Minutes from the start until a muscle group gives out if the cycle is kept up with the
    /// plan's final postures; `None` when none gave out in the time followed — read it with
    /// `exhaustion_verdict`: "never" or "not_determined".
    pub minutes_to_exhaustion: Option<f64>,
    /// "gives_out" (at `minutes_to_exhaustion`), "never" (every group settled above its loads),
    /// or "not_determined" (the pace was followed for `minutes_followed` — a week, or two
    /// million cycles — without an exhaustion, and the capacities had not settled yet).
    pub exhaustion_verdict: &'static str,
    /// How long the pace was followed \[min\].
    pub minutes_followed: f64,
    /// The group that gives out first, when one does.
    pub first_to_give_out: Option<String>,
    /// The largest share of a rested muscle's endurance one hold uses (0..1+), and where.
    pub endurance_share: f64,
    pub endurance_group: String,
    pub endurance_phase: String,
    /// Lowest capacity at the end of the task, and whose.
    pub capacity_left: f64,
    pub capacity_left_group: String,
    /// What makes the plan impossible as planned (targets out of reach, collisions, loss of
    /// balance); empty when nothing does.
    pub problems: Vec<String>,
    /// A verdict in plain words.
    pub words: String,
}

/// Each phase's loads (one per half-joint) in the plan's last postures, then the rest posture's:
/// `task.phases.len() + 1` rows, in the order of the phases.
pub fn last_cycle_loads(task: &Task, plan: &Plan) -> Vec<Vec<f64>> {
    let nh = task.half_joints.len();
    let n_ph = task.phases.len();
    let mut loads: Vec<Vec<f64>> = vec![vec![0.0; nh]; n_ph + 1];
    let st = &plan.steps;
    for i in 0..st.t_s.len() {
        let pr = &plan.postures[st.posture[i]];
        let idx = if pr.phase == "rest" {
            n_ph
        } else {
            task.phases
                .iter()
                .position(|p| p.name == st.phase(i))
                .unwrap_or(0)
        };
        loads[idx] = pr.load.clone();
    }
    loads
}

/// A time to exhaustion in the unit a reader would say it in: seconds below 2 min (a group out
/// after 43 s is not "after 1 min"), minutes below 2 h, hours beyond.
pub fn time_words(t_s: f64) -> String {
    if t_s < 120.0 {
        format!("{t_s:.0} s")
    } else if t_s < 7200.0 {
        format!("{:.0} min", t_s / 60.0)
    } else {
        format!("{:.1} h", t_s / 3600.0)
    }
}

/// The meaning of `plan`'s fatigue.
pub fn meaning(task: &Task, plan: &Plan) -> Meaning {
    meaning_with(task, plan, &task.fatigue)
}

/// [`meaning`] with other fatigue parameters (one per half-joint): the plan's postures, another
/// muscle (the uncertainty analysis).
pub fn meaning_with(task: &Task, plan: &Plan, params: &[MaParams]) -> Meaning {
    let nh = task.half_joints.len();
    let loads = last_cycle_loads(task, plan);
    let durations: Vec<f64> = task
        .phases
        .iter()
        .map(|p| p.duration_s)
        .chain(std::iter::once(task.rest_s))
        .collect();
    // Keep the pace from the start, at most a week of cycles (and two million), stopping at the
    // periodic steady state. Capacity is affine in its start value over every step and so over a
    // cycle (`CycleMap`): cycle n starts at `c* + (1 − c*) Aⁿ`, falling in n, and each step's
    // start is a fixed affine map of that. A step's exhaustion test is monotone in its start
    // capacity, so the first cycle in which a group gives out in a step is found by bisection on
    // n, exactly, instead of holding every cycle in turn.
    let max_cycles = ((7.0 * 86400.0) / task.cycle_s()).ceil().min(2e6) as u64;
    let cycle_s: f64 = durations.iter().filter(|d| **d > 0.0).sum();
    let steps_of = |h: usize, upto: usize| {
        durations[..upto]
            .iter()
            .zip(&loads)
            .filter(|(d, _)| **d > 0.0)
            .map(move |(d, l)| (l[h], *d))
    };
    // cycles until every group's cycle-start capacity changes by less than 1e-12 per cycle
    let mut settle_cycles = 1u64;
    let maps: Vec<CycleMap> = (0..nh)
        .map(|h| CycleMap::new(&params[h], steps_of(h, durations.len())))
        .collect();
    for map in &maps {
        if map.ln_a >= 0.0 {
            continue;
        }
        let one_minus_a = -map.ln_a.exp_m1();
        let c_star = map.b / one_minus_a;
        // |c_n − c_{n−1}| = (1 − c*)(1 − A) A^{n−1}
        let first = (1.0 - c_star).abs() * one_minus_a;
        let n = if first < 1e-12 {
            1.0
        } else {
            1.0 + ((1e-12 / first).ln() / map.ln_a).floor() + 1.0
        };
        settle_cycles = settle_cycles.max(n.min(u64::MAX as f64) as u64);
    }
    let settled_reached = settle_cycles <= max_cycles;
    let cycles_checked = settle_cycles.min(max_cycles);
    let mut exhausted: Option<(f64, usize)> = None;
    let mut offset_s = 0.0;
    for (s, d) in durations.iter().enumerate() {
        if *d <= 0.0 {
            continue;
        }
        for h in 0..nh {
            let f = loads[s][h];
            let before = CycleMap::new(&params[h], steps_of(h, s));
            let start = |n: u64| before.after(maps[h].after(1.0, n as f64), 1.0);
            let gives_out = |n: u64| {
                params[h]
                    .time_to_exhaustion_s(start(n), f)
                    .filter(|te| te < d)
            };
            if gives_out(cycles_checked - 1).is_none() {
                continue;
            }
            // the first cycle in [0, cycles_checked) in which the group gives out in this step
            let (mut lo, mut hi) = (0u64, cycles_checked - 1);
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if gives_out(mid).is_some() {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            let te = gives_out(lo).unwrap_or(0.0);
            let t_out = lo as f64 * cycle_s + offset_s + te;
            if exhausted.is_none_or(|(t0, _)| t_out < t0) {
                exhausted = Some((t_out, h));
            }
        }
        offset_s += d;
    }
    let t = cycles_checked as f64 * cycle_s;
    let (mut share, mut sh_h, mut sh_p) = (0.0, 0, 0);
    for (p, ph) in task.phases.iter().enumerate() {
        for h in 0..nh {
            if let Some(met) = params[h].met_min(loads[p][h]) {
                let s = ph.duration_s / (met * 60.0).max(1e-9);
                if s > share {
                    (share, sh_h, sh_p) = (s, h, p);
                }
            }
        }
    }
    let replayed = replay_plan(plan, params);
    let (c_left, c_h) = replayed
        .final_capacity
        .iter()
        .enumerate()
        .map(|(h, c)| (*c, h))
        .fold((1.0, 0), |a, b| if b.0 < a.0 { b } else { a });
    let group = |h: usize| task.half_joints[h].group.clone();
    let problems = plan.problems();
    let words = match exhausted {
        _ if !problems.is_empty() => {
            format!("cannot be done as planned: {}", problems.join("; "))
        }
        // the plan as executed (re-planned as the muscles tire) lasts, but its final postures
        // held from the start would not: say both, the plan first
        Some((te, h))
            if te <= task.duration_s()
                && replayed.exhaustion.is_none()
                && plan.summary.exhaustion.is_none() =>
        {
            format!(
                "the task can be done as planned, by changing posture as the muscles tire; the final postures held from the start would tire the {} out after {}; at the end the {} keep {:.0} % of their strength",
                group(h),
                time_words(te),
                group(c_h),
                100.0 * c_left
            )
        }
        Some((te, h)) if te <= task.duration_s() => format!(
            "at this pace the {} give out after {}, before the task's {:.0} min are over",
            group(h),
            time_words(te),
            task.duration_s() / 60.0
        ),
        Some((te, h)) => format!(
            "the task can be done; kept up, the {} would give out after {}; at the end the {} keep {:.0} % of their strength",
            group(h),
            time_words(te),
            group(c_h),
            100.0 * c_left
        ),
        // very short cycles: the replay stopped at its cycle cap before the capacities settled
        None if !settled_reached => format!(
            "no muscle group gave out in the {:.1} h followed at this pace (the capacities had not settled yet: longer was not simulated); at the end of the task the {} keep {:.0} % of their strength",
            t / 3600.0,
            group(c_h),
            100.0 * c_left
        ),
        // the lowest capacity within the task's last cycle: the capacities settle above the
        // loads in the end, but are still falling when the task ends
        None if task.duration_s() - replayed.lowest_t_s <= task.cycle_s() => format!(
            "no muscle group gives out at this pace: every group's capacity would settle above its loads, but it is still falling when the task ends; at the end the {} keep {:.0} % of their strength",
            group(c_h),
            100.0 * c_left
        ),
        None => format!(
            "no muscle group gives out at this pace: every group's capacity settles above its loads; at the end the {} keep {:.0} % of their strength",
            group(c_h),
            100.0 * c_left
        ),
    };
    Meaning {
        minutes_to_exhaustion: exhausted.map(|(te, _)| te / 60.0),
        exhaustion_verdict: match (exhausted, settled_reached) {
            (Some(_), _) => "gives_out",
            (None, true) => "never",
            (None, false) => "not_determined",
        },
        minutes_followed: exhausted.map_or(t, |(te, _)| te) / 60.0,
        first_to_give_out: exhausted.map(|(_, h)| group(h)),
        endurance_share: share,
        endurance_group: group(sh_h),
        endurance_phase: task.phases[sh_p].name.clone(),
        capacity_left: c_left,
        capacity_left_group: group(c_h),
        problems,
        words,
    }
}

/// A plan's steps held again with `params` (one per half-joint): what the fatigue state does.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Replay {
    pub final_capacity: Vec<f64>,
    /// Lowest capacity at any time, its half-joint index and time \[s\].
    pub lowest_capacity: f64,
    pub lowest_half_joint: usize,
    pub lowest_t_s: f64,
    /// First time a group's capacity falls to its load, and which.
    pub exhaustion: Option<(f64, usize)>,
}

/// Holds every step of `plan` exactly with `params`: capacity at the end, lowest capacity at any
/// time (the capacity only falls within a step held at constant load when the load exceeds the
/// recovery's balance, so the lowest is at a step's end or at exhaustion), first exhaustion.
pub fn replay_plan(plan: &Plan, params: &[MaParams]) -> Replay {
    let nh = params.len();
    let mut state = vec![MaState::FRESH; nh];
    let mut r = Replay {
        final_capacity: vec![1.0; nh],
        lowest_capacity: 1.0,
        lowest_half_joint: 0,
        lowest_t_s: 0.0,
        exhaustion: None,
    };
    let st = &plan.steps;
    // each posture held for each duration prepared once: a long task holds a few of them
    // thousands of times over, and only the capacity is wanted here
    let mut prepared: HashMap<(usize, u64), Vec<PreparedHold>> = HashMap::new();
    for i in 0..st.t_s.len() {
        let f = &plan.postures[st.posture[i]].load;
        let d = st.duration_s[i];
        let holds = prepared
            .entry((st.posture[i], d.to_bits()))
            .or_insert_with(|| (0..nh).map(|h| params[h].prepare(f[h], d)).collect());
        for h in 0..nh {
            let before = state[h];
            let c0 = before.capacity;
            holds[h].advance(&mut state[h]);
            // capacity moves monotonically within a step held at one load, so the group gives
            // out within it only if it starts or ends at or below the load: only then is the
            // time sought (a group that starts below its load may recover above it by the end)
            if r.exhaustion.is_none()
                && (c0 <= f[h] || state[h].capacity <= f[h] * (1.0 + 1e-9))
                && let Some(te) = params[h].time_to_exhaustion_within_s(&before, f[h], d)
                && te < d
            {
                r.exhaustion = Some((st.t_s[i] + te, h));
            }
            if state[h].capacity < r.lowest_capacity {
                r.lowest_capacity = state[h].capacity;
                r.lowest_half_joint = h;
                r.lowest_t_s = st.t_s[i] + d;
            }
        }
    }
    r.final_capacity = state.iter().map(|s| s.capacity).collect();
    r
}

#[cfg(test)]
mod tests {
    use super::no_exhaustion_words;

    #[test]
    fn a_null_time_is_never_only_when_the_verdict_says_so() {
        assert_eq!(no_exhaustion_words("never", 1e4), "never (settles)");
        assert_eq!(
            no_exhaustion_words("not_determined", 2000.0 / 60.0),
            "not determined (followed 33.3 min)"
        );
        assert_eq!(
            no_exhaustion_words("not_determined", 7.0 * 24.0 * 60.0),
            "not determined (followed 168 h)"
        );
    }
}
