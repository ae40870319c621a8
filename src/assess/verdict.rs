//! The shift verdict: whether the planned pace can be kept up over the shift, judged by several
//! independent criteria, and which of them binds.
//!
//! The fatigue model alone is not enough to call a pace sustainable: a muscle whose modelled
//! capacity settles four points above a 35 %MVC overhead hold is, by every field criterion, not
//! working acceptably. The verdict therefore takes the worst of:
//!
//! 1. **Fatigue model** (Ma et al. 2009 with recovery, [`super::meaning`]): a group giving out
//!    within the task exceeds; giving out later if the pace were kept up, or capacities that had
//!    not settled when the replay stopped, is a caution; settling above every load is acceptable.
//! 2. **Jonsson's load levels** (B. Jonsson, Measurement and evaluation of local muscular strain
//!    in the shoulder during constrained work, J Hum Ergol 11:73–88, 1982): over the work cycle,
//!    the static load level (the 10th percentile of the load's time distribution) should not
//!    exceed 2 %MVC and must not exceed 5 %MVC; the mean load level should not exceed 10 %MVC and
//!    must not exceed 14 %MVC; the peak level (90th percentile) should not exceed 50 %MVC and
//!    must not exceed 70 %MVC. Between the two figures is a caution, above the second exceeded.
//!    Applied to the shoulder, elbow, wrist/grip and neck groups ([`JONSSON_REGIONS`]), where
//!    Jonsson and the studies after him measured; ASSUMPTION: a group's joint torque as a share
//!    of its strength stands for its muscles' %MVC (Jonsson used EMG), and the legs' and trunk's
//!    small static loads in standing, for which the limits were not derived, are not judged.
//! 3. **ISO 11226:2000** (Ergonomics — evaluation of static working postures; EN 1005-4:2005
//!    gives the same zones for static postures of the trunk and upper arm): each body segment on
//!    its own, for every hold longer than 4 s (the standards' static posture) of the segment
//!    beyond a zone's limit — consecutive phases in which it stays beyond that limit are one hold
//!    of their total time, judged at their largest angle ([`segment_holds`]; the rest ends a
//!    hold) — trunk inclination 0–20° is
//!    acceptable, 20–60° only for its maximum acceptable holding time, beyond 60° or leaning
//!    back not acceptable; trunk lateral bending or axial rotation beyond 10° not acceptable;
//!    upper-arm elevation 0–20° acceptable, 20–60° only for its holding time, beyond 60° not
//!    acceptable (no arm support is modelled); head inclination 0–25° acceptable, 25–85° only for
//!    its holding time, beyond 85° or backward not acceptable; neck flexion (head against trunk)
//!    beyond 25° not acceptable. The holding times are straight lines between the end points
//!    [`ISO_TRUNK_HOLD`], [`ISO_ARM_HOLD`] and [`ISO_HEAD_HOLD`], read from the standard's figures
//!    as secondary sources reproduce them; the original figures were not available to check
//!    here. Backward lean and head extension are judged beyond
//!    [`ISO_BACKWARD_TOLERANCE_DEG`] (ASSUMPTION: less is not visible to an observer).
//! 4. **EN 1005-4** (postures and movements in relation to machinery) for the segments' holds of
//!    4 s or less (postures in movement): trunk lateral bending or axial rotation beyond 10°, or an
//!    upper arm raised beyond 60° against the vertical, is not acceptable at 2 or more times a
//!    minute and conditionally acceptable (a caution) less often; an upper arm raised 20–60° at 2
//!    or more times a minute is conditionally acceptable. A movement's frequency is how often a
//!    cycle takes the segment beyond that limit, per minute. The zones are as secondary
//!    summaries of the standard give them (the standard's text was not available here).
//! 6. **NIOSH's low-back limits**: the highest L5/S1 compression within the action limit of
//!    3400 N is acceptable, up to the maximum permissible limit of 6400 N a caution, above it
//!    exceeded (NIOSH Work practices guide for manual lifting, 1981, as used by Waters et al.
//!    1993); a declared lift's lifting index (or the composite index) at most 1 acceptable, up to
//!    3 a caution, above 3 exceeded (Waters et al. 1994, Applications manual: LI > 1 puts some
//!    workers at increased risk, LI > 3 many).
//! 5. **Rohmert (1973)**: a hold above 100 %MVC, or longer than Rohmert's endurance time at its
//!    load, or a cycle whose rest is shorter than Rohmert's rest allowance ([`super::rest`]),
//!    exceeds; holds above 15 %MVC covered by enough rest are a caution (Rohmert's curve: only
//!    loads below about 15 %MVC can be held without a rest allowance); none above 15 % is
//!    acceptable.
//!
//! "Indefinitely" is said only when every criterion is acceptable. The solver's status comes
//! first. A target farther than the body is long, or inside an obstacle, is a proven "cannot be
//! done". Targets, clearances or balance the optimiser did not achieve without such proof make
//! the verdict "not determined", with the reason. A feasible plan is a witness: a phase whose
//! local solve did not converge (nor stop at a numerically stationary, feasible point:
//! [`crate::plan::sqp::SqpOutcome::determined`]) leaves the verdict "acceptable" when the plan
//! passes every criterion (a finished plan can only do better), and makes it "not determined"
//! when the plan fails one (a finished plan may pass).

use super::lifting::Lifting;
use super::meaning::{Meaning, last_cycle_loads};
use super::niosh::{Adjustment, Point};
use super::phase::PhaseAssessment;
use super::rest::{RestAdvice, rohmert_endurance_min};
use crate::assess::angles::{ArmAngles, BodyAngles};
use crate::plan::sqp::Stop;
use crate::plan::{Plan, Task};
use serde::Serialize;

/// How a criterion judges the plan; ordered from best to worst.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The criterion does not apply to this task (no static posture, no declared lift).
    NotApplicable,
    Acceptable,
    Caution,
    Exceeded,
    NotDetermined,
}

impl Status {
    pub fn words(self) -> &'static str {
        match self {
            Status::NotApplicable => "not applicable",
            Status::Acceptable => "acceptable",
            Status::Caution => "caution",
            Status::Exceeded => "exceeded",
            Status::NotDetermined => "not determined",
        }
    }
}

/// One criterion's judgement.
#[derive(Debug, Clone, Serialize)]
pub struct Criterion {
    /// "fatigue_model", "jonsson_static", "jonsson_mean", "jonsson_peak", "iso_11226",
    /// "en_1005_4", "rohmert", "niosh_low_back".
    pub id: &'static str,
    /// The criterion in words.
    pub name: &'static str,
    pub status: Status,
    /// What it found, with its figures.
    pub words: String,
    pub source: &'static str,
}

/// The shift verdict.
#[derive(Debug, Clone, Serialize)]
pub struct ShiftVerdict {
    pub status: Status,
    /// The criterion that decides the verdict (the first, in the order listed, of the worst
    /// status); `None` when the solver's status or a proven impossibility decides it.
    pub binding: Option<&'static str>,
    /// The verdict in one sentence, naming the binding criterion.
    pub headline: String,
    /// Why the verdict is not determined (the optimiser's failures), when it is not.
    pub not_determined: Vec<String>,
    pub criteria: Vec<Criterion>,
}

impl ShiftVerdict {
    /// The criterion with `id` ("iso_11226", "niosh_lifting", …), if the verdict has it.
    pub fn criterion(&self, id: &str) -> Option<&Criterion> {
        self.criteria.iter().find(|c| c.id == id)
    }
}

/// The regions whose groups Jonsson's load levels judge.
pub const JONSSON_REGIONS: [&str; 4] = ["shoulder", "elbow", "grip", "neck"];
/// Jonsson (1982): (should not exceed, must not exceed) as fractions of MVC.
pub const JONSSON_STATIC: (f64, f64) = (0.02, 0.05);
pub const JONSSON_MEAN: (f64, f64) = (0.10, 0.14);
pub const JONSSON_PEAK: (f64, f64) = (0.50, 0.70);
/// ISO 11226 Figure 3 (upper-arm elevation).
pub use crate::plan::zones::ARM_HOLD as ISO_ARM_HOLD;
/// ISO 11226 (head inclination).
pub use crate::plan::zones::HEAD_HOLD as ISO_HEAD_HOLD;
pub use crate::plan::zones::HoldingTime;
pub use crate::plan::zones::ISO_BACKWARD_TOLERANCE_DEG;
/// ISO 11226 / EN 1005-4: a posture held longer than this is static \[s\].
pub use crate::plan::zones::STATIC_HOLD_S as ISO_STATIC_S;
/// ISO 11226 Figure 2 (trunk inclination).
pub use crate::plan::zones::TRUNK_HOLD as ISO_TRUNK_HOLD;

const JONSSON_SOURCE: &str = "Jonsson B. (1982) J Hum Ergol 11:73-88";
const ISO_SOURCE: &str = "ISO 11226:2000; EN 1005-4:2005";
const EN_SOURCE: &str = "EN 1005-4:2005+A1:2008 (postures in movement)";
/// The force on the hands from which a phase exerts more than the "no or minimal external force"
/// ISO 11226 and EN 1005-4 cover \[N\]: the weight of 3 kg, the mass from which ISO 11228-1
/// treats handling an object as lifting. ASSUMPTION: neither standard puts a figure on
/// "minimal".
pub const MINIMAL_FORCE_N: f64 = 3.0 * 9.80665;

/// What a pass of ISO 11226 or EN 1005-4 does not cover: the phases whose hands exert more than
/// the minimal external force. Their postures are still judged (a posture not acceptable without
/// force is not acceptable with it), but the standards' acceptance says nothing of the force;
/// NIOSH's lifting equation and the load criteria judge that. `None` when every phase is within.
fn beyond_minimal_force(task: &Task) -> Option<String> {
    let forceful: Vec<(&str, f64)> = task
        .phases
        .iter()
        .map(|p| (p.name.as_str(), p.total_force_n().norm()))
        .filter(|(_, f)| *f >= MINIMAL_FORCE_N)
        .collect();
    let (_, most) = forceful
        .iter()
        .copied()
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    let names: Vec<String> = forceful.iter().map(|(n, _)| format!("'{n}'")).collect();
    Some(format!(
        "{} exert{} up to {most:.0} N on the hands, beyond the minimal external force this standard covers (the load criteria judge it)",
        names.join(", "),
        if names.len() == 1 { "s" } else { "" }
    ))
}

/// A pass's words with what it does not cover ([`beyond_minimal_force`]).
fn within_scope(task: &Task, status: Status, words: String) -> String {
    match (status, beyond_minimal_force(task)) {
        (Status::Acceptable | Status::Caution, Some(note)) => format!("{words}; {note}"),
        _ => words,
    }
}

/// EN 1005-4: a movement repeated this often or more per minute is "high frequency".
pub const EN_HIGH_FREQUENCY_PER_MIN: f64 = 2.0;
const ROHMERT_SOURCE: &str = "Rohmert W. (1973) Applied Ergonomics 4(3):158-162";
const MODEL_SOURCE: &str = "Ma et al. (2009) with recovery";

/// A time distribution's `p`-quantile: the smallest level at or below which the load stays for
/// at least the share `p` of the time. `levels`: (load, duration) pairs.
pub fn time_quantile(levels: &[(f64, f64)], p: f64) -> f64 {
    let mut v: Vec<(f64, f64)> = levels.iter().copied().filter(|l| l.1 > 0.0).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = v.iter().map(|l| l.1).sum();
    let mut acc = 0.0;
    for (f, d) in &v {
        acc += d;
        if acc >= p * total * (1.0 - 1e-12) {
            return *f;
        }
    }
    v.last().map_or(0.0, |l| l.0)
}

/// The time-weighted mean of (load, duration) pairs.
pub fn time_mean(levels: &[(f64, f64)]) -> f64 {
    let total: f64 = levels.iter().map(|l| l.1.max(0.0)).sum();
    if total <= 0.0 {
        return 0.0;
    }
    levels.iter().map(|l| l.0 * l.1.max(0.0)).sum::<f64>() / total
}

fn graded(value: f64, limits: (f64, f64)) -> Status {
    if value > limits.1 {
        Status::Exceeded
    } else if value > limits.0 {
        Status::Caution
    } else {
        Status::Acceptable
    }
}

fn pct(f: f64) -> String {
    format!("{:.0} %MVC", 100.0 * f)
}

/// Judges `plan` of `task` by every criterion (its meaning, phase assessments and rest advice
/// already computed).
pub fn shift_verdict(
    task: &Task,
    plan: &Plan,
    meaning: &Meaning,
    phases: &[PhaseAssessment],
    rest: &RestAdvice,
    lifting: Option<&Lifting>,
    variants_exhausted: Option<usize>,
) -> ShiftVerdict {
    let loads = last_cycle_loads(task, plan);
    let holds = task.holds();
    let capable = (
        phases.iter().map(|p| p.capable_men).fold(1.0, f64::min),
        phases.iter().map(|p| p.capable_women).fold(1.0, f64::min),
    );
    // in the order that picks the binding criterion among equals: what the task's geometry
    // decides, then the postures, the low back and strength, then the load levels and fatigue
    let criteria = vec![
        lifting_index(lifting),
        iso_11226(task, phases, &holds),
        en_1005_4(task, phases, &holds),
        low_back(phases),
        strength(capable),
        jonsson(task, &loads, "jonsson_mean"),
        jonsson(task, &loads, "jonsson_static"),
        jonsson(task, &loads, "jonsson_peak"),
        rohmert(task, &loads, rest, &holds),
        fatigue_model(task, plan, meaning, rest, variants_exhausted),
    ];
    // criteria the postures do not change (the lifting index is the task's geometry): what they
    // find holds whatever the optimiser did
    let geometric = criteria
        .iter()
        .find(|c| c.id == "niosh_lifting" && c.status == Status::Exceeded)
        .map(|c| {
            (
                c.id,
                format!(
                    "{} — {} (from the task's geometry, whatever the posture)",
                    c.name, c.words
                ),
            )
        });
    // the solver's status before any criterion: what the plan proves, and what it leaves open
    let mut unproven = Vec::new();
    let mut proven = Vec::new();
    let mut unconverged = Vec::new();
    for s in &plan.summary.phases {
        let problems: Vec<String> = s.problems();
        if !s.reachable
            && (s.beyond_reach_m.is_some()
                || s.target_inside.is_some()
                || s.target_blocked.is_some())
        {
            proven.extend(problems);
        } else {
            unproven.extend(
                problems
                    .into_iter()
                    .map(|p| format!("the optimiser found no acceptable posture: {p}")),
            );
        }
        if !s.solve.determined() {
            unconverged.push(format!(
                "the optimiser did not converge on '{}' ({}, optimality residual {:.1e})",
                s.phase,
                match s.solve.stop {
                    Stop::IterationLimit => "iteration limit",
                    Stop::QpFailed => "a QP failed",
                    _ => "stalled",
                },
                s.kkt_residual
            ));
        }
    }
    if plan.summary.rest_clearance_m < 0.0 {
        unproven.push(format!(
            "the optimiser found no rest posture clear of '{}'",
            plan.summary
                .rest_closest
                .as_deref()
                .unwrap_or("an obstacle")
        ));
    }
    if !proven.is_empty() {
        return ShiftVerdict {
            status: Status::Exceeded,
            binding: None,
            headline: format!("cannot be done: {}", proven.join("; ")),
            not_determined: Vec::new(),
            criteria,
        };
    }
    if !unproven.is_empty() {
        let not_determined: Vec<String> = unproven.into_iter().chain(unconverged).collect();
        if let Some(g) = geometric {
            return geometric_verdict(task, g, not_determined, criteria);
        }
        return ShiftVerdict {
            status: Status::NotDetermined,
            binding: None,
            headline: format!(
                "not determined: {}; the plan found is not a feasible one, and that does not prove that none is",
                not_determined.join("; ")
            ),
            not_determined,
            criteria,
        };
    }
    let worst = criteria
        .iter()
        .map(|c| c.status)
        .max()
        .unwrap_or(Status::Acceptable);
    let binding = criteria.iter().find(|c| c.status == worst);
    let others: Vec<&str> = criteria
        .iter()
        .filter(|c| c.status == worst && Some(c.id) != binding.map(|b| b.id))
        .map(|c| c.name)
        .collect();
    let also = if others.is_empty() {
        String::new()
    } else {
        format!(" (also {})", others.join(", "))
    };
    // the headline names the binding criterion with its first two findings (three when that is
    // all: "(and 1 more)" hides what one more clause would say)
    let short = |w: &str| {
        let parts: Vec<&str> = w.split("; ").collect();
        if parts.len() > 3 {
            format!(
                "{}; {} (and {} more under the criterion)",
                parts[0],
                parts[1],
                parts.len() - 2
            )
        } else {
            w.to_string()
        }
    };
    // A feasible plan is a witness: what it passes, the best plan passes too. What it fails is
    // proven only when the optimiser finished; else it is not determined.
    if !unconverged.is_empty() && worst > Status::Acceptable {
        let b = binding.expect("a criterion is worse than acceptable");
        if let Some(g) = geometric {
            return geometric_verdict(task, g, unconverged, criteria);
        }
        return ShiftVerdict {
            status: Status::NotDetermined,
            binding: None,
            headline: format!(
                "not determined: {}; the plan it found is {} by {} — {}{also}, and a finished plan may do better",
                unconverged.join("; "),
                b.status.words(),
                b.name,
                short(&b.words)
            ),
            not_determined: unconverged,
            criteria,
        };
    }
    let headline = match (worst, binding) {
        (Status::NotApplicable | Status::Acceptable, _) | (_, None) => format!(
            "acceptable: this pace can be kept up indefinitely by every criterion checked (NIOSH's lifting index and low-back limits, ISO 11226 static postures, EN 1005-4 movements, the share strong enough, Jonsson's load levels, Rohmert's endurance, the fatigue model); {}",
            criteria.last().map_or("", |c| c.words.as_str())
        ),
        (Status::Caution, Some(b)) => format!(
            "conditionally acceptable, not to be called sustainable indefinitely: {} — {}{also}",
            b.name,
            short(&b.words)
        ),
        (Status::Exceeded, Some(b)) => format!(
            "not acceptable over the task's {}: {} — {}{also}",
            crate::assess::meaning::time_words(task.duration_s()),
            b.name,
            short(&b.words)
        ),
        (Status::NotDetermined, Some(b)) => {
            format!("not determined: {} — {}{also}", b.name, short(&b.words))
        }
    };
    let headline = if unconverged.is_empty() {
        headline
    } else {
        format!(
            "{headline} (a witness: {}; a finished plan can only do better)",
            unconverged.join("; ")
        )
    };
    ShiftVerdict {
        status: worst,
        binding: binding.filter(|_| worst > Status::Acceptable).map(|b| b.id),
        headline,
        not_determined: Vec::new(),
        criteria,
    }
}

/// The verdict when a criterion the postures do not change is exceeded while the rest are not
/// determined: "not acceptable" by that criterion, the rest named as open.
fn geometric_verdict(
    task: &Task,
    (id, words): (&'static str, String),
    not_determined: Vec<String>,
    criteria: Vec<Criterion>,
) -> ShiftVerdict {
    ShiftVerdict {
        status: Status::Exceeded,
        binding: Some(id),
        headline: format!(
            "not acceptable over the task's {}: {words}; the posture-dependent criteria are not determined: {}",
            crate::assess::meaning::time_words(task.duration_s()),
            not_determined.join("; ")
        ),
        not_determined,
        criteria,
    }
}

fn fatigue_model(
    task: &Task,
    plan: &Plan,
    m: &Meaning,
    rest: &RestAdvice,
    variants_exhausted: Option<usize>,
) -> Criterion {
    let lowest = plan.summary.lowest_capacity;
    let floor = rest.capacity_floor;
    let mut status = match m.exhaustion_verdict {
        _ if !m.problems.is_empty() => Status::NotDetermined,
        "gives_out"
            if m.minutes_to_exhaustion
                .is_some_and(|t| t * 60.0 <= task.duration_s()) =>
        {
            Status::Exceeded
        }
        "gives_out" | "not_determined" => Status::Caution,
        _ => Status::Acceptable,
    };
    let mut words = m.words.clone();
    if status == Status::Acceptable {
        // settling is not enough: capacity kept above the planning floor, and no parameter
        // variant exhausting a group within the task
        if lowest < floor {
            status = Status::Caution;
            words.push_str(&format!(
                "; but capacity falls to {:.0} % at its lowest, below the {:.0} % kept in reserve",
                100.0 * lowest,
                100.0 * floor
            ));
        }
        if let Some(n) = variants_exhausted.filter(|n| *n > 0) {
            status = Status::Caution;
            words.push_str(&format!(
                "; {n} of the 9 fatigue-parameter variants exhaust a group within the task"
            ));
        }
    }
    Criterion {
        id: "fatigue_model",
        name: "the fatigue model",
        status,
        words,
        source: MODEL_SOURCE,
    }
}

fn jonsson(task: &Task, loads: &[Vec<f64>], id: &'static str) -> Criterion {
    let (name, limits, what) = match id {
        "jonsson_static" => (
            "Jonsson's static load level",
            JONSSON_STATIC,
            "static load level (held 90 % of the cycle)",
        ),
        "jonsson_mean" => (
            "Jonsson's mean load level",
            JONSSON_MEAN,
            "mean load over the cycle",
        ),
        _ => (
            "Jonsson's peak load level",
            JONSSON_PEAK,
            "peak load level (exceeded 10 % of the cycle)",
        ),
    };
    let durations = phase_durations(task);
    let mut worst: Option<(f64, usize)> = None;
    for (h, hj) in task.half_joints.iter().enumerate() {
        if !JONSSON_REGIONS.contains(&hj.region.as_str()) {
            continue;
        }
        let levels: Vec<(f64, f64)> = loads
            .iter()
            .zip(&durations)
            .map(|(l, d)| (l[h].max(0.0), *d))
            .collect();
        let v = match id {
            "jonsson_static" => time_quantile(&levels, 0.1),
            "jonsson_mean" => time_mean(&levels),
            _ => time_quantile(&levels, 0.9),
        };
        if worst.is_none_or(|w| v > w.0) {
            worst = Some((v, h));
        }
    }
    let (status, words) = match worst {
        None => (
            Status::Acceptable,
            "no shoulder, arm, wrist or neck groups in this body".to_string(),
        ),
        Some((v, h)) => {
            let status = graded(v, limits);
            let against = match status {
                Status::Acceptable => format!("within the recommended {}", pct(limits.0)),
                Status::Caution => format!(
                    "above the recommended {} but within the limit of {}",
                    pct(limits.0),
                    pct(limits.1)
                ),
                _ => format!("above the limit of {}", pct(limits.1)),
            };
            (
                status,
                if v < 5e-4 {
                    // no group is worse than another: name none
                    format!(
                        "every shoulder, arm, wrist and neck group's {what} is 0.0 %MVC, {against}"
                    )
                } else {
                    format!(
                        "the {}' {what} is {:.1} %MVC, {against}",
                        task.half_joints[h].group,
                        100.0 * v
                    )
                },
            )
        }
    };
    Criterion {
        id,
        name,
        status,
        words,
        source: JONSSON_SOURCE,
    }
}

/// Durations of the phases and the rest, in the order of [`last_cycle_loads`].
fn phase_durations(task: &Task) -> Vec<f64> {
    task.phases
        .iter()
        .map(|p| p.duration_s)
        .chain(std::iter::once(task.rest_s))
        .collect()
}

/// A body segment's posture beyond its neutral zone through consecutive phases of the cycle:
/// ISO 11226 and EN 1005-4 judge each segment's posture on its own, so a head bowed through
/// three short phases in a row is one static posture held their total time, although no phase
/// alone lasts 4 s.
struct SegmentHold {
    /// The phases, in the cycle's order (from the last phase to the first when the cycle has no
    /// rest and the posture is held across its end).
    phases: Vec<usize>,
    /// Their total duration \[s\].
    hold_s: f64,
    /// How often a cycle brings the segment beyond its neutral zone, per minute of work.
    per_min: f64,
}

impl SegmentHold {
    /// The phases' names: "'place'", "'reach', 'bring' and 'place'" (each name once).
    fn names(&self, task: &Task) -> String {
        let mut names: Vec<String> = Vec::new();
        for &p in &self.phases {
            let n = format!("'{}'", task.phases[p].name);
            if !names.contains(&n) {
                names.push(n);
            }
        }
        match names.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
            _ => names.concat(),
        }
    }

    /// ", each held 5 s" for a hold longer than a movement's 4 s (static too), else nothing.
    fn held_words(&self) -> String {
        if self.hold_s > ISO_STATIC_S {
            format!(", each held {:.0} s", self.hold_s)
        } else {
            String::new()
        }
    }

    /// The largest of `value` over the hold's phases.
    fn worst(&self, value: impl Fn(usize) -> f64) -> f64 {
        self.phases
            .iter()
            .map(|&p| value(p))
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// The runs of consecutive phases in which `beyond(p)` holds: a segment's holds beyond its
/// neutral zone. The rest breaks a run (the worker's arms hang, the trunk and head are upright);
/// without rest a run may go on from the cycle's last phase to its first. A segment beyond its
/// zone in every phase of a cycle without rest is one hold of the cycle's length (as
/// [`Task::holds`] counts a cycle of the same work).
fn segment_holds(task: &Task, beyond: impl Fn(usize) -> bool) -> Vec<SegmentHold> {
    let n = task.phases.len();
    let on: Vec<bool> = (0..n).map(&beyond).collect();
    if !on.iter().any(|&b| b) {
        return Vec::new();
    }
    let wraps = task.rest_s <= 0.0;
    let mut runs: Vec<Vec<usize>> = Vec::new();
    if on.iter().all(|&b| b) {
        runs.push((0..n).collect());
    } else {
        // start after a phase that is not beyond, so that a run across the cycle's end is whole
        let start = if wraps {
            (0..n).find(|&p| !on[p]).map_or(0, |p| p + 1)
        } else {
            0
        };
        let mut current: Vec<usize> = Vec::new();
        for k in 0..n {
            let p = (start + k) % n;
            if !wraps && p == 0 && !current.is_empty() {
                runs.push(std::mem::take(&mut current));
            }
            if on[p] {
                current.push(p);
            } else if !current.is_empty() {
                runs.push(std::mem::take(&mut current));
            }
        }
        if !current.is_empty() {
            runs.push(current);
        }
    }
    let per_min = runs.len() as f64 * 60.0 / task.cycle_s().max(1e-9);
    runs.into_iter()
        .map(|phases| SegmentHold {
            hold_s: phases.iter().map(|&p| task.phases[p].duration_s).sum(),
            phases,
            per_min,
        })
        .collect()
}

/// The holds in which a segment's `angle` (rounded to the degree) is beyond `limit_deg`.
fn holds_beyond(
    task: &Task,
    phases: &[PhaseAssessment],
    angle: &dyn Fn(&BodyAngles) -> f64,
    limit_deg: f64,
) -> Vec<SegmentHold> {
    segment_holds(task, |p| {
        phases
            .get(p)
            .and_then(|pa| pa.angles.as_ref())
            .is_some_and(|a| angle(a).round() > limit_deg)
    })
}

/// A segment's largest angle over a hold's phases, rounded to the degree.
fn worst_deg(
    h: &SegmentHold,
    phases: &[PhaseAssessment],
    angle: &dyn Fn(&BodyAngles) -> f64,
) -> f64 {
    h.worst(|p| {
        phases[p]
            .angles
            .as_ref()
            .map_or(f64::NEG_INFINITY, |a| angle(a).round())
    })
}

/// A graded segment's words for one hold: an upper arm whose elevation is mostly backward in the
/// hold's worst phase (its flexion against the trunk negative and larger than its abduction) is
/// "behind the trunk," not "raised" (ISO 11226 and EN 1005-4 grade the elevation either way; a
/// trial read "left upper arm raised 46°" for a free arm swung back).
fn segment_words(
    words: &str,
    h: &SegmentHold,
    phases: &[PhaseAssessment],
    angle: &dyn Fn(&BodyAngles) -> f64,
) -> String {
    let side: fn(&BodyAngles) -> ArmAngles = if words.starts_with("right upper arm") {
        |a: &BodyAngles| a.right
    } else if words.starts_with("left upper arm") {
        |a: &BodyAngles| a.left
    } else {
        return words.to_string();
    };
    let worst = h
        .phases
        .iter()
        .filter_map(|&p| phases.get(p)?.angles.as_ref())
        .max_by(|a, b| angle(a).total_cmp(&angle(b)));
    match worst.map(side) {
        Some(arm)
            if arm.upper_arm_flexion_deg < 0.0
                && -arm.upper_arm_flexion_deg >= arm.upper_arm_abduction_deg.abs() =>
        {
            words.replace(" raised", " behind the trunk,")
        }
        _ => words.to_string(),
    }
}

/// A segment an angle of which to judge, in words: "trunk twisted".
type SegmentAngle = (&'static str, fn(&BodyAngles) -> f64);

/// The segments whose zones are graded by angle, with their holding-time lines: the trunk's
/// inclination (ISO 11226 Figure 2) and each upper arm's elevation (Figure 3). Beyond 60° not
/// acceptable; 20–60° acceptable up to a holding time that falls with the angle (static) or at
/// fewer than 2 a minute (EN 1005-4, movements).
const GRADED: [(SegmentAngle, HoldingTime); 3] = [
    (("trunk inclined", |a| a.trunk_flexion_deg), ISO_TRUNK_HOLD),
    (
        ("right upper arm raised", |a| {
            a.right.upper_arm_elevation_deg
        }),
        ISO_ARM_HOLD,
    ),
    (
        ("left upper arm raised", |a| a.left.upper_arm_elevation_deg),
        ISO_ARM_HOLD,
    ),
];

/// The head's inclination, graded by ISO 11226 for static postures: beyond 85° not acceptable,
/// 25–85° up to its holding time.
const HEAD_INCLINED: (SegmentAngle, HoldingTime) =
    (("head inclined", |a| a.head_inclination_deg), ISO_HEAD_HOLD);

/// The trunk's asymmetry: beyond 10° not acceptable (static), or at 2 or more a minute
/// (movements).
const TRUNK_ASYMMETRY: [SegmentAngle; 3] = [
    ("trunk bent sideways", |a| a.trunk_side_bend_deg.abs()),
    ("trunk twisted", |a| a.trunk_twist_deg.abs()),
    ("trunk turned against the feet", |a| {
        a.trunk_turn_deg().abs()
    }),
];

fn iso_11226(task: &Task, phases: &[PhaseAssessment], holds: &[(f64, f64)]) -> Criterion {
    let mut exceeded = Vec::new();
    let is_static = |h: &&SegmentHold| h.hold_s > ISO_STATIC_S;
    // a posture held longer than 4 s, by the same work or by a segment beyond a zone
    let mut judged = (0..phases.len().min(task.phases.len()))
        .filter(|&p| holds.get(p).map_or(task.phases[p].duration_s, |h| h.0) > ISO_STATIC_S)
        .count();
    let beyond =
        |angle: &dyn Fn(&BodyAngles) -> f64, limit: f64| holds_beyond(task, phases, angle, limit);
    for ((words, angle), line) in GRADED.into_iter().chain([HEAD_INCLINED]) {
        // beyond the line's end (60°; the head's 85°): not acceptable held
        let mut flagged = Vec::new();
        for h in beyond(&angle, line.to_deg).iter().filter(is_static) {
            judged += 1;
            flagged.extend(h.phases.iter().copied());
            exceeded.push(format!(
                "{}: {} {:.0}° from the vertical, held {:.0} s (beyond {:.0}°)",
                h.names(task),
                segment_words(words, h, phases, &angle),
                worst_deg(h, phases, &angle),
                h.hold_s,
                line.to_deg
            ));
        }
        // from the line's start (20°; the head's 25°): up to the holding time of its largest
        // angle (held beyond the end as above)
        for h in beyond(&angle, line.from_deg).iter().filter(is_static) {
            judged += 1;
            if h.phases.iter().any(|p| flagged.contains(p)) {
                continue;
            }
            let t = worst_deg(h, phases, &angle).min(line.to_deg);
            let max_s = line.max_hold_s(t);
            if h.hold_s > max_s {
                exceeded.push(format!(
                    "{}: {} {t:.0}° held {:.0} s (at most {max_s:.0} s)",
                    h.names(task),
                    segment_words(words, h, phases, &angle),
                    h.hold_s
                ));
            }
        }
    }
    // beyond these not acceptable held, whatever the time: leaning back, the trunk's asymmetry,
    // the head tilted back
    let not_acceptable: [(SegmentAngle, f64, &str); 5] = [
        (
            ("trunk leaning back", |a| -a.trunk_flexion_deg),
            ISO_BACKWARD_TOLERANCE_DEG,
            "",
        ),
        (TRUNK_ASYMMETRY[0], 10.0, " (beyond 10°)"),
        (TRUNK_ASYMMETRY[1], 10.0, " (beyond 10°)"),
        (TRUNK_ASYMMETRY[2], 10.0, " (beyond 10°)"),
        (
            ("head tilted back", |a| -a.head_inclination_deg),
            ISO_BACKWARD_TOLERANCE_DEG,
            "",
        ),
    ];
    for ((what, angle), limit, beyond_words) in not_acceptable {
        for h in beyond(&angle, limit).iter().filter(is_static) {
            judged += 1;
            exceeded.push(format!(
                "{}: {what} {:.0}°{beyond_words}",
                h.names(task),
                worst_deg(h, phases, &angle)
            ));
        }
    }
    // the neck flexed beyond 25° against the trunk not acceptable
    let neck = |a: &BodyAngles| a.neck_flexion_deg;
    for h in beyond(&neck, 25.0).iter().filter(is_static) {
        judged += 1;
        exceeded.push(format!(
            "{}: neck flexed {:.0}° against the trunk (beyond 25°), held {:.0} s",
            h.names(task),
            worst_deg(h, phases, &neck),
            h.hold_s
        ));
    }
    let (status, words) = if !exceeded.is_empty() {
        (
            Status::Exceeded,
            format!("postures not acceptable: {}", exceeded.join("; ")),
        )
    } else if judged == 0 {
        (
            Status::NotApplicable,
            format!(
                "no posture is held longer than {ISO_STATIC_S:.0} s (no static posture to judge)"
            ),
        )
    } else {
        (
            Status::Acceptable,
            format!(
                "every posture held longer than {ISO_STATIC_S:.0} s is within the acceptable zones and holding times"
            ),
        )
    };
    Criterion {
        id: "iso_11226",
        name: "ISO 11226 static postures",
        status,
        words: within_scope(task, status, words),
        source: ISO_SOURCE,
    }
}

fn en_1005_4(task: &Task, phases: &[PhaseAssessment], holds: &[(f64, f64)]) -> Criterion {
    let mut exceeded = Vec::new();
    let mut caution = Vec::new();
    // a posture held 4 s or less, by the same work
    let judged = (0..phases.len().min(task.phases.len()))
        .filter(|&p| {
            let hold_s = holds.get(p).map_or(task.phases[p].duration_s, |h| h.0);
            hold_s > 0.0 && hold_s <= ISO_STATIC_S
        })
        .count();
    // a segment's movement: each time it goes beyond a zone, so many times a minute, however
    // long it stays there (a trunk bent 38° for 5 s three times a minute is static for ISO 11226
    // and a repeated movement for EN 1005-4: judging it static alone rated bending longer
    // better than bending briefly, an ergonomist's trial found)
    let moves = |angle: &dyn Fn(&BodyAngles) -> f64, limit: f64| {
        let mut v = holds_beyond(task, phases, angle, limit);
        v.retain(|h| h.hold_s > 0.0);
        v
    };
    let mut out = |bad: bool, what: String| {
        if bad {
            exceeded.push(what)
        } else {
            caution.push(what)
        }
    };
    for ((words, angle), _) in GRADED {
        // "trunk inclined" reads "trunk flexed" in a movement
        let words = words.replace("trunk inclined", "trunk flexed");
        for h in moves(&angle, 60.0) {
            let high = h.per_min >= EN_HIGH_FREQUENCY_PER_MIN;
            out(
                high,
                format!(
                    "{}: {} {:.0}° from the vertical (beyond 60°), one of {:.1} movements a minute beyond 60°{}",
                    h.names(task),
                    segment_words(&words, &h, phases, &angle),
                    worst_deg(&h, phases, &angle),
                    h.per_min,
                    h.held_words()
                ),
            );
        }
        for h in moves(&angle, 20.0) {
            let worst = worst_deg(&h, phases, &angle);
            if h.per_min >= EN_HIGH_FREQUENCY_PER_MIN && worst <= 60.0 {
                out(
                    false,
                    format!(
                        "{}: {} {worst:.0}° from the vertical (20–60°, conditionally acceptable), one of {:.1} movements a minute beyond 20°{}",
                        h.names(task),
                        segment_words(&words, &h, phases, &angle),
                        h.per_min,
                        h.held_words()
                    ),
                );
            }
        }
    }
    for (what, angle) in TRUNK_ASYMMETRY {
        for h in moves(&angle, 10.0) {
            out(
                h.per_min >= EN_HIGH_FREQUENCY_PER_MIN,
                format!(
                    "{}: {what} {:.0}° (beyond 10°), one of {:.1} movements a minute beyond 10°{}",
                    h.names(task),
                    worst_deg(&h, phases, &angle),
                    h.per_min,
                    h.held_words()
                ),
            );
        }
    }
    let (status, words) = if !exceeded.is_empty() {
        (
            Status::Exceeded,
            format!("movements not acceptable: {}", exceeded.join("; ")),
        )
    } else if !caution.is_empty() {
        (
            Status::Caution,
            format!("conditionally acceptable: {}", caution.join("; ")),
        )
    } else if judged == 0 {
        (
            Status::NotApplicable,
            "every posture is held longer than 4 s (judged as static postures)".to_string(),
        )
    } else {
        (
            Status::Acceptable,
            "every movement posture is within the acceptable zones".to_string(),
        )
    };
    Criterion {
        id: "en_1005_4",
        name: "EN 1005-4 postures in movement",
        status,
        words: within_scope(task, status, words),
        source: EN_SOURCE,
    }
}

fn rohmert(task: &Task, loads: &[Vec<f64>], rest: &RestAdvice, holds: &[(f64, f64)]) -> Criterion {
    // Rohmert's rule is for static work: the holds longer than 4 s, each as one hold
    let mut too_long = Vec::new();
    let mut over = Vec::new();
    let mut above = None::<(f64, usize)>;
    let mut judged = 0;
    for (p, ph) in task.phases.iter().enumerate() {
        if p > 0 && task.phases[p - 1].same_work(ph) {
            continue;
        }
        let hold_s = holds.get(p).map_or(ph.duration_s, |h| h.0);
        if hold_s <= ISO_STATIC_S {
            continue;
        }
        judged += 1;
        for (h, &f) in loads[p].iter().enumerate() {
            if f > 1.0 {
                over.push(format!(
                    "the {} in '{}'",
                    task.half_joints[h].group, ph.name
                ));
            } else if f > 0.15 {
                let t_s = 60.0 * rohmert_endurance_min(f);
                if hold_s > t_s {
                    too_long.push(format!(
                        "'{}': the {} hold {} for {:.0} s, longer than Rohmert's endurance of {:.0} s",
                        ph.name,
                        task.half_joints[h].group,
                        pct(f),
                        hold_s,
                        t_s
                    ));
                }
                if above.is_none_or(|a| f > a.0) {
                    above = Some((f, h));
                }
            }
        }
    }
    // the rest summary's figure, so that the criterion and the summary name the same group
    // and time (both count the holds longer than 4 s, over every planned cycle)
    let need = rest.rohmert.rest_s_per_cycle;
    let need_group = task
        .half_joints
        .iter()
        .find(|h| h.id == rest.rohmert.limiting_half_joint)
        .map_or("", |h| h.group.as_str());
    let (status, words) = if judged == 0 {
        (
            Status::NotApplicable,
            format!(
                "no work is held longer than {ISO_STATIC_S:.0} s in one posture, so no muscle load is static (Rohmert's rule is for static holds)"
            ),
        )
    } else if !over.is_empty() {
        (
            Status::Exceeded,
            format!(
                "loads above 100 %MVC ({}): Rohmert's rule has no answer",
                over.join(", ")
            ),
        )
    } else if !too_long.is_empty() {
        (Status::Exceeded, too_long.join("; "))
    } else if need > rest.current_rest_s + 1e-9 {
        (
            Status::Exceeded,
            format!(
                "the {need_group} need {need:.1} s of rest per cycle by Rohmert's rest allowance for their static holds; the cycle has {:.1} s",
                rest.current_rest_s
            ),
        )
    } else if let Some((f, h)) = above {
        (
            Status::Caution,
            format!(
                "the {} hold {} statically (above Rohmert's 15 %MVC): sustainable only with the rest the cycle gives ({:.1} s, of which Rohmert asks {:.1} s{})",
                task.half_joints[h].group,
                pct(f),
                rest.current_rest_s,
                need,
                if need_group.is_empty() || need_group == task.half_joints[h].group {
                    String::new()
                } else {
                    format!(", for the {need_group}")
                }
            ),
        )
    } else {
        (
            Status::Acceptable,
            "no static hold above 15 %MVC (no rest allowance needed)".to_string(),
        )
    };
    Criterion {
        id: "rohmert",
        name: "Rohmert's endurance and rest allowance",
        status,
        words,
        source: ROHMERT_SOURCE,
    }
}

/// NIOSH's lifting index of the declared lifts (the composite index for several): the task's
/// geometry, whatever the posture. At most 1 is acceptable; above 1 the lift is to be redesigned
/// (Waters et al. 1994: an increased risk for some workers; ISO 11228-1:2003 asks for
/// redesign above 1), above 3 many workers are at elevated risk.
fn lifting_index(lifting: Option<&Lifting>) -> Criterion {
    let li = lifting.and_then(|l| {
        l.composite
            .as_ref()
            .and_then(|c| c.cli.map(|x| (x, "composite lifting index".to_string())))
            .or_else(|| {
                l.lifts
                    .iter()
                    .filter_map(|r| {
                        r.lifting_index
                            .map(|x| (x, format!("lifting index of '{}'", r.name)))
                    })
                    .max_by(|a, b| a.0.total_cmp(&b.0))
            })
    });
    // a declared lift outside the equation's limits has no lifting index: RWL = 0, no load is
    // recommended (Waters et al. 1994, pp. 6-8: a multiplier beyond its range is 0)
    let outside: Vec<String> = lifting
        .map(|l| {
            l.lifts
                .iter()
                .filter(|r| r.lifting_index.is_none())
                .map(|r| {
                    let at = |p: &Point| match p {
                        Point::Origin => "origin",
                        Point::Destination => "destination",
                    };
                    let why: Vec<String> = r
                        .adjustments
                        .iter()
                        .filter_map(|a| match a {
                            Adjustment::VerticalBeyondMaximum { at: p } => {
                                Some(format!("the hands above 175 cm at the {}", at(p)))
                            }
                            Adjustment::HorizontalBeyondMaximum { at: p } => Some(format!(
                                "the load more than 63 cm in front of the ankles at the {}",
                                at(p)
                            )),
                            Adjustment::AsymmetryBeyondMaximum { at: p } => {
                                Some(format!("asymmetry beyond 135° at the {}", at(p)))
                            }
                            Adjustment::DistanceBeyondMaximum => {
                                Some("a vertical travel beyond 175 cm".to_string())
                            }
                            Adjustment::FrequencyBeyondMaximum => Some(
                                "more lifts a minute than the frequency table allows".to_string(),
                            ),
                            _ => None,
                        })
                        .collect();
                    format!(
                        "'{}' is outside the lifting equation's limits ({}): its recommended weight limit is 0, no load is recommended",
                        r.name,
                        if why.is_empty() {
                            "a multiplier is 0".to_string()
                        } else {
                            why.join(", ")
                        }
                    )
                })
                .collect()
        })
        .unwrap_or_default();
    let (status, words) = match li {
        _ if !outside.is_empty() => (Status::Exceeded, outside.join("; ")),
        None => (Status::NotApplicable, "no lift declared".to_string()),
        Some((x, what)) if x > 3.0 => (
            Status::Exceeded,
            format!("{what} {x:.2}, above 3: many workers at elevated risk"),
        ),
        Some((x, what)) if x > 1.0 => (
            Status::Exceeded,
            format!(
                "{what} {x:.2}, above 1: an increased risk for some workers; redesign the lift"
            ),
        ),
        Some((x, what)) => (
            Status::Acceptable,
            format!("{what} {x:.2}, at most 1: nearly all healthy workers"),
        ),
    };
    Criterion {
        id: "niosh_lifting",
        name: "NIOSH's lifting index",
        status,
        words,
        source: "Waters et al. (1993, 1994); ISO 11228-1:2003",
    }
}

/// The share strong enough for every load in the plan's postures, against NIOSH 1981's
/// population limits (as 3DSSPP uses them): 99 % of men and 75 % of women (action limit),
/// 25 % of men (maximum permissible limit).
fn strength((men, women): (f64, f64)) -> Criterion {
    let status = if men >= 0.99 && women >= 0.75 {
        Status::Acceptable
    } else if men >= 0.25 {
        Status::Caution
    } else {
        Status::Exceeded
    };
    Criterion {
        id: "strength",
        name: "the share strong enough",
        status,
        words: format!(
            "{} of men and {} of women are strong enough for every load ({})",
            share_words(men),
            share_words(women),
            match status {
                Status::Acceptable => "within the design limit of 99 % of men and 75 % of women",
                _ if men < 0.25 => "below the upper limit of 25 % of men",
                _ if men < 0.99 && women < 0.75 => {
                    "both below the design limit of 99 % of men and 75 % of women"
                }
                _ if men < 0.99 => "men below the design limit of 99 %; women within their 75 %",
                _ => "women below the design limit of 75 %; men within their 99 %",
            }
        ),
        source: "NIOSH (1981) Work practices guide for manual lifting; 3DSSPP's strength limits",
    }
}

/// A share of people in words, rounded down to 0.1 % so that a share short of a limit never
/// prints as the limit (98.96 % reads "98.9 %").
fn share_words(x: f64) -> String {
    format!("{:.1} %", super::share_percent_floor(x, 1))
}

/// The highest L5/S1 compression of the plan's postures against NIOSH's 1981 limits.
fn low_back(phases: &[PhaseAssessment]) -> Criterion {
    let back = phases
        .iter()
        .filter_map(|p| p.low_back.as_ref().map(|b| (b.compression_n, &p.phase)))
        .fold(None::<(f64, &String)>, |a, b| match a {
            Some(x) if x.0 >= b.0 => Some(x),
            _ => Some(b),
        });
    let (status, words) = match back {
        None => (
            Status::NotApplicable,
            "no low-back estimate for this body".to_string(),
        ),
        Some((c, phase)) => {
            let lim = super::low_back::BackParams::default();
            let (al, mpl) = (lim.compression_action_limit_n, lim.compression_max_limit_n);
            let s = graded(c, (al, mpl));
            (
                s,
                format!(
                    "L5/S1 compression up to {c:.0} N ('{phase}'), {}",
                    match s {
                        Status::Acceptable => format!("within NIOSH's action limit of {al:.0} N"),
                        Status::Caution => format!(
                            "above NIOSH's action limit of {al:.0} N (controls required), within the maximum of {mpl:.0} N"
                        ),
                        _ => format!("above NIOSH's maximum permissible limit of {mpl:.0} N"),
                    }
                ),
            )
        }
    };
    Criterion {
        id: "niosh_low_back",
        name: "NIOSH's low-back limits",
        status,
        words,
        source: "NIOSH (1981) Work practices guide for manual lifting (3400 / 6400 N)",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-computed: 20 s at 35 % and 20 s at 2 %: mean 18.5 %, the 10th percentile 2 %, the
    /// 90th 35 %; the median is the lower level (half the time at or below 2 %).
    #[test]
    fn time_distribution_levels() {
        let l = [(0.35, 20.0), (0.02, 20.0)];
        assert!((time_mean(&l) - 0.185).abs() < 1e-12);
        assert_eq!(time_quantile(&l, 0.1), 0.02);
        assert_eq!(time_quantile(&l, 0.5), 0.02);
        assert_eq!(time_quantile(&l, 0.9), 0.35);
        // 85 % of the time at 25 %, 15 % at 0: the level held 90 % of the time is 0 (25 % is
        // held only 85 % of the time); the 20th percentile is 25 %
        let l = [(0.25, 85.0), (0.0, 15.0)];
        assert_eq!(time_quantile(&l, 0.1), 0.0);
        assert_eq!(time_quantile(&l, 0.2), 0.25);
    }

    #[test]
    fn shares_round_down_but_not_below_their_decimal_value() {
        // 0.57 and 0.29 are stored just below their decimal value (100x = 56.99..., 28.99...);
        // flooring must not drop them a whole step, while a share short of a limit stays short.
        for (x, dp, want) in [
            (0.57, 0, 57.0),
            (0.29, 0, 29.0),
            (0.58, 1, 58.0),
            (0.9896, 0, 98.0),
            (0.98999, 0, 98.0),
            (0.986, 1, 98.6),
            (1.0, 0, 100.0),
            (0.0, 1, 0.0),
        ] {
            assert_eq!(
                super::super::share_percent_floor(x, dp),
                want,
                "{x} at {dp}"
            );
        }
        assert_eq!(share_words(0.57), "57.0 %");
        assert_eq!(share_words(0.9999), "99.9 %");
    }

    /// The share strong enough names which sex falls short of the 3DSSPP/NIOSH design limits
    /// (99 % of men, 75 % of women) and never prints a share short of a limit as the limit.
    #[test]
    fn share_strong_enough_names_who_falls_short() {
        let c = strength((0.986, 0.922));
        assert_eq!(c.status, Status::Caution);
        assert!(
            c.words.starts_with("98.6 % of men and 92.2 % of women"),
            "{}",
            c.words
        );
        assert!(
            c.words
                .contains("men below the design limit of 99 %; women within"),
            "{}",
            c.words
        );
        let c = strength((0.99996, 0.70));
        assert_eq!(c.status, Status::Caution);
        assert!(
            c.words
                .contains("women below the design limit of 75 %; men within"),
            "{}",
            c.words
        );
        let c = strength((0.98996, 0.7499));
        assert!(
            c.words.starts_with("98.9 % of men and 74.9 % of women"),
            "{}",
            c.words
        );
        assert!(c.words.contains("both below"), "{}", c.words);
        assert_eq!(strength((0.20, 0.05)).status, Status::Exceeded);
        assert_eq!(strength((0.99, 0.75)).status, Status::Acceptable);
    }

    /// ISO 11226's holding-time lines: 4 min at 20°, 1 min at 60° (trunk), 2.5 min at 40°.
    #[test]
    fn holding_time_lines() {
        assert_eq!(ISO_TRUNK_HOLD.max_hold_s(20.0), 240.0);
        assert_eq!(ISO_TRUNK_HOLD.max_hold_s(60.0), 60.0);
        assert_eq!(ISO_TRUNK_HOLD.max_hold_s(40.0), 150.0);
        assert_eq!(ISO_ARM_HOLD.max_hold_s(40.0), 120.0);
        // head: 8 min at 25°, 1 min at 85°; 35° for 6 min 50 s as reproduced
        assert_eq!(ISO_HEAD_HOLD.max_hold_s(25.0), 480.0);
        assert_eq!(ISO_HEAD_HOLD.max_hold_s(85.0), 60.0);
        assert!((ISO_HEAD_HOLD.max_hold_s(35.0) - 410.0).abs() < 1e-9);
    }

    #[test]
    fn grading_follows_the_two_figures() {
        assert_eq!(graded(0.10, JONSSON_MEAN), Status::Acceptable);
        assert_eq!(graded(0.12, JONSSON_MEAN), Status::Caution);
        assert_eq!(graded(0.175, JONSSON_MEAN), Status::Exceeded);
        assert!(Status::NotDetermined > Status::Exceeded);
    }
}
