//! What the reports derive from a plan: each phase's loads in the last plan and how much of a
//! rested muscle's endurance one hold uses, each muscle group's lowest capacity, and the phase
//! that matters most.

use crate::assess::Assessment;
use crate::fatigue::MaParams;
use crate::plan::{Plan, Task};

/// One phase's strain in the last plan.
#[derive(Debug, Clone)]
pub struct PhaseStrain {
    /// Relative load per half-joint (the last posture planned for this phase).
    pub loads: Vec<f64>,
    /// The largest share of a rested muscle's endurance one hold of this phase uses, and whose.
    pub endurance_share: f64,
    pub share_group: Option<usize>,
    /// The largest relative load, and whose.
    pub max_load: f64,
    pub max_group: Option<usize>,
}

/// The fatigue parameters of each half-joint of the plan.
pub fn params(plan: &Plan) -> Vec<Option<MaParams>> {
    plan.half_joints
        .iter()
        .map(|h| MaParams::with_recovery(h.k_per_min, h.recovery).ok())
        .collect()
}

/// The strain of every phase of `task` in `plan`'s last postures.
pub fn phase_strain(task: &Task, plan: &Plan) -> Vec<PhaseStrain> {
    let nh = plan.half_joints.len();
    let mut loads: Vec<Option<Vec<f64>>> = vec![None; task.phases.len()];
    let st = &plan.steps;
    for i in 0..st.len() {
        let Some(pr) = plan.postures.get(st.posture[i]) else {
            continue;
        };
        if pr.phase == "rest" && st.phase(i) == "rest" {
            continue;
        }
        if let Some(p) = task.phases.iter().position(|p| p.name == st.phase(i)) {
            loads[p] = Some(pr.load.clone());
        }
    }
    // phases never held (an exhaustion before them): the first posture planned for them
    for (p, l) in loads.iter_mut().enumerate() {
        if l.is_none() {
            *l = plan
                .postures
                .iter()
                .rev()
                .find(|r| r.phase == task.phases[p].name)
                .map(|r| r.load.clone());
        }
    }
    let par = params(plan);
    task.phases
        .iter()
        .zip(loads)
        .map(|(ph, l)| {
            let loads = l.unwrap_or_else(|| vec![0.0; nh]);
            let mut s = PhaseStrain {
                endurance_share: 0.0,
                share_group: None,
                max_load: 0.0,
                max_group: None,
                loads: Vec::new(),
            };
            for (h, &f) in loads.iter().enumerate() {
                if f.is_finite() && f > s.max_load {
                    s.max_load = f;
                    s.max_group = Some(h);
                }
                let met = par.get(h).copied().flatten().and_then(|p| p.met_min(f));
                if let Some(m) = met {
                    let share = ph.duration_s / (60.0 * m).max(1e-9);
                    if share.is_finite() && share > s.endurance_share {
                        s.endurance_share = share;
                        s.share_group = Some(h);
                    }
                }
            }
            s.loads = loads;
            s
        })
        .collect()
}

/// A muscle group's course over the task.
#[derive(Debug, Clone)]
pub struct GroupCourse {
    pub h: usize,
    /// Lowest capacity at any step's end, and when \[s\].
    pub lowest: f64,
    pub lowest_t_s: f64,
    /// Capacity at the end.
    pub end: f64,
    /// Highest load held in any phase, and in which.
    pub max_load: f64,
    pub max_load_phase: Option<usize>,
    /// Largest endurance share of one hold.
    pub endurance_share: f64,
}

/// Every group's course, lowest capacity first.
pub fn group_courses(task: &Task, plan: &Plan, strain: &[PhaseStrain]) -> Vec<GroupCourse> {
    let nh = plan.half_joints.len();
    let par = params(plan);
    let st = &plan.steps;
    let mut v: Vec<GroupCourse> = (0..nh)
        .map(|h| {
            let (mut lowest, mut lowest_t_s) = (1.0_f64, 0.0);
            for (t_end_s, state) in st.course(h) {
                let c = state.capacity;
                if c.is_finite() && c < lowest {
                    lowest = c;
                    lowest_t_s = t_end_s;
                }
            }
            let mut g = GroupCourse {
                h,
                lowest,
                lowest_t_s,
                end: plan
                    .summary
                    .final_capacity
                    .get(h)
                    .copied()
                    .unwrap_or(f64::NAN),
                max_load: 0.0,
                max_load_phase: None,
                endurance_share: 0.0,
            };
            // every posture held, not only the last plan's: re-planning moves load between
            // groups, and a group's highest load may come from an earlier plan
            let held = st.posture.iter().enumerate().filter_map(|(i, &k)| {
                let p = task.phases.iter().position(|p| p.name == st.phase(i))?;
                Some((p, plan.postures.get(k)?.load.get(h).copied()?))
            });
            let last = strain
                .iter()
                .enumerate()
                .map(|(p, s)| (p, s.loads.get(h).copied().unwrap_or(0.0)));
            for (p, f) in held.chain(last) {
                if f.is_finite() && f > g.max_load {
                    g.max_load = f;
                    g.max_load_phase = Some(p);
                }
                if let Some(m) = par.get(h).copied().flatten().and_then(|q| q.met_min(f)) {
                    let share = task.phases[p].duration_s / (60.0 * m).max(1e-9);
                    if share.is_finite() && share > g.endurance_share {
                        g.endurance_share = share;
                    }
                }
            }
            g
        })
        .collect();
    v.sort_by(|a, b| a.lowest.total_cmp(&b.lowest).then(a.h.cmp(&b.h)));
    v
}

/// Why a phase is the one that matters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorstWhy {
    /// A target out of reach, a collision or a loss of balance.
    Problem,
    /// The exhaustion happens in this phase.
    Exhaustion,
    /// A hazard the field's limits name: L5/S1 compression above NIOSH's action limit, or fewer
    /// than 75 % of women strong enough (the NIOSH/3DSSPP design limit).
    Hazard,
    /// The muscle group whose capacity falls lowest holds its highest load here.
    Limiting(usize),
    /// The largest share of a rested muscle's endurance per hold.
    Endurance,
    /// The largest load.
    Load,
    /// Not this layout's own hardest phase: shown because it is the hardest of another layout
    /// (the comparison report draws one phase for every layout).
    Compared,
}

/// Share of women who must be strong enough for a phase (NIOSH's design criterion, as 3DSSPP
/// uses it).
pub const DESIGN_CAPABLE_WOMEN: f64 = 0.75;

/// The hazards of phase `p` by the field's limits, in words (empty: none).
pub fn hazards(a: &Assessment, p: usize) -> Vec<String> {
    let mut out = Vec::new();
    let Some(pa) = a.phases.get(p) else {
        return out;
    };
    if let Some(b) = &pa.low_back {
        use crate::assess::low_back::CompressionVerdict as V;
        let limits = crate::assess::low_back::BackParams::default();
        match b.compression_verdict {
            V::AboveMaximumPermissibleLimit => out.push(format!(
                "L5/S1 compression {:.0} N, above NIOSH's maximum permissible limit ({:.0} N)",
                b.compression_n, limits.compression_max_limit_n
            )),
            V::AboveActionLimit => out.push(format!(
                "L5/S1 compression {:.0} N, above NIOSH's action limit ({:.0} N)",
                b.compression_n, limits.compression_action_limit_n
            )),
            V::WithinActionLimit => {}
        }
    }
    // REBA's high and very high risk bands (8–10: action necessary soon; 11–15: now;
    // Hignett & McAtamney 2000): an ergonomist's trial found the plan naming a REBA 2 phase
    // hardest beside a REBA 9 lift
    if let Some(r) = pa.reba.as_ref().filter(|r| r.reba_score >= 8) {
        out.push(format!(
            "REBA {} ({} risk: action necessary{})",
            r.reba_score,
            r.risk.level.label(),
            if r.reba_score >= 11 { " now" } else { " soon" }
        ));
    }
    if pa.capable_women < DESIGN_CAPABLE_WOMEN {
        out.push(format!(
            "only {:.0} % of women are strong enough, below the design limit of {:.0} %",
            100.0 * pa.capable_women,
            100.0 * DESIGN_CAPABLE_WOMEN
        ));
    }
    out
}

/// The phase that matters most: one the worker cannot do, else the one where a group gives
/// out, else the one with the most hazards by the field's limits ([`hazards`]: L5/S1 above
/// NIOSH's action limit, REBA 8 or more, fewer women strong enough than the design limit; ties:
/// the higher L5/S1 compression), else the one where the group that falls lowest holds its highest load,
/// else the largest endurance share, else the largest load.
pub fn worst_phase(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    strain: &[PhaseStrain],
) -> Option<(usize, WorstWhy)> {
    let n = task.phases.len().min(plan.summary.phases.len());
    if n == 0 {
        return None;
    }
    let problem = |p: &crate::plan::result::PhaseSummary| {
        !p.reachable || p.min_clearance_m < 0.0 || p.balance_margin_m.is_some_and(|m| m < 0.0)
    };
    if let Some(p) = plan.summary.phases[..n].iter().position(problem) {
        return Some((p, WorstWhy::Problem));
    }
    if let Some(e) = &plan.summary.exhaustion
        && let Some(p) = task.phases.iter().position(|p| p.name == e.phase)
    {
        return Some((p, WorstWhy::Exhaustion));
    }
    let compression = |p: usize| {
        a.phases
            .get(p)
            .and_then(|x| x.low_back.as_ref())
            .map_or(0.0, |b| b.compression_n)
    };
    if let Some(p) = (0..n)
        .filter(|&p| !hazards(a, p).is_empty())
        .max_by(|&x, &y| {
            hazards(a, x)
                .len()
                .cmp(&hazards(a, y).len())
                .then(compression(x).total_cmp(&compression(y)))
                .then(y.cmp(&x))
        })
    {
        return Some((p, WorstWhy::Hazard));
    }
    if plan.summary.lowest_capacity < 0.999
        && let Some(h) = plan.half_joint(&plan.summary.lowest_capacity_half_joint)
    {
        let load = |p: usize| {
            strain
                .get(p)
                .and_then(|s| s.loads.get(h))
                .copied()
                .unwrap_or(0.0)
        };
        if let Some(p) = (0..n)
            .filter(|&p| load(p) > 0.0)
            .max_by(|&a, &b| load(a).total_cmp(&load(b)).then(b.cmp(&a)))
        {
            return Some((p, WorstWhy::Limiting(h)));
        }
    }
    let best = |key: &dyn Fn(&PhaseStrain) -> f64| {
        (0..n.min(strain.len()))
            .filter(|&p| key(&strain[p]) > 0.0)
            .max_by(|&a, &b| key(&strain[a]).total_cmp(&key(&strain[b])).then(b.cmp(&a)))
    };
    if let Some(p) = best(&|s| s.endurance_share) {
        return Some((p, WorstWhy::Endurance));
    }
    best(&|s| s.max_load)
        .map(|p| (p, WorstWhy::Load))
        .or(Some((0, WorstWhy::Load)))
}
