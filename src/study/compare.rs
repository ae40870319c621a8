//! Layout comparison: the same work planned on several workstation layouts, side by side and
//! ranked, with the ranking's robustness across the fatigue parameters' ranges.
//!
//! **Ranking** (best first, [`RANKING_RULE`]): what decides a layout for an ergonomist first —
//! whether the worker can do it (every target reached, no collision, balance kept), no load above
//! a group's strength, no exhaustion within the task, NIOSH's lifting index where lifts are
//! declared, postures within ISO 11226 / EN 1005-4, L5/S1 compression against NIOSH's limits, the
//! share strong enough, the shift verdict — and only then the fatigue model's finer figures
//! (time to exhaustion, lowest capacity, fatigue per hour) and the worst RULA.
//!
//! **Robustness**: every layout's plan is replayed under the nine parameter variants of
//! [`crate::assess::uncertainty`]; the ranking is redone per variant and the best layout's wins
//! against each other layout are counted ("B beats A for 9 of 9 parameter variants").
//!
//! **Shards**: [`shard_indices`] splits the layouts deterministically (layout `j` goes to shard
//! `j mod n`); each shard's [`LayoutOutcome`]s merge with [`Comparison::from_outcomes`] into the
//! same table and document as one run.

use super::shard::Shard;
use crate::assess::meaning::no_exhaustion_words;
use crate::assess::{Assessment, assess};
use crate::plan::result::Exhaustion;
use crate::plan::{Plan, PlanError, PlanOptions, Task, plan_task_with};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;
use std::fmt::Write;

/// One parameter variant's figures for a layout (what the ranking needs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VariantFigures {
    pub variant: String,
    pub exhausted_in_task: bool,
    pub minutes_to_exhaustion: Option<f64>,
    /// As the plan's `meaning.exhaustion_verdict`, and how long the pace was followed \[min\].
    pub exhaustion_verdict: String,
    pub minutes_followed: f64,
    pub lowest_capacity: f64,
    pub rest_needed_s: Option<f64>,
}

/// One layout's outcome: every number has one meaning, as in `plan`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LayoutOutcome {
    /// Position in the list of layouts given (shards keep it, for a deterministic merge).
    pub index: usize,
    /// 1 = best.
    pub rank: usize,
    pub file: String,
    pub task: String,
    /// The worker can do it: every target reached, no collision, balance kept.
    pub feasible: bool,
    /// What makes it infeasible, in words.
    pub problems: Vec<String>,
    /// Why the shift verdict for this layout is not determined (as the plan's
    /// `verdict.not_determined`: a target, clearance or balance the optimiser did not achieve
    /// without proof that none can; or a phase it did not finish in a plan that fails a
    /// criterion). An infeasible layout with reasons here is "not determined", not "cannot".
    #[serde(default)]
    pub not_determined: Vec<String>,
    /// The shift verdict's status ("acceptable", "caution", "exceeded", "not_determined") and
    /// its headline, naming the binding criterion.
    pub shift_status: crate::assess::verdict::Status,
    pub shift_verdict: String,
    /// The NIOSH lifting index that decides the layout: the composite index (CLI) when several
    /// lifts are declared, else the largest lift's LI; null without declared lifts.
    #[serde(default)]
    pub lifting_index: Option<f64>,
    /// Why the lifting index is not defined, when a declared lift lies outside the lifting
    /// equation's limits (an RWL of 0: no load is recommended; `lifting_index` is then null):
    /// "'table to shelf' at the destination: H 66.5 cm beyond 63 cm (HM = 0)". Such a layout
    /// ranks after every layout whose index is defined.
    #[serde(default)]
    pub lifting_outside_limits: Option<String>,
    /// The worse of the ISO 11226 (static postures) and EN 1005-4 (movements) criteria of the
    /// shift verdict, and its findings.
    pub posture_status: crate::assess::verdict::Status,
    pub posture_findings: String,
    /// Smallest clearance of any planned posture to an obstacle or the body itself \[m\], and what.
    pub min_clearance_m: f64,
    pub closest: Option<String>,
    /// Smallest balance margin of any phase \[m\].
    pub min_balance_margin_m: Option<f64>,
    pub planned_duration_s: f64,
    pub simulated_duration_s: f64,
    pub total_u_min: f64,
    /// Total U per hour of simulated work \[min/h\].
    pub u_per_hour_min: f64,
    pub worst_group: String,
    pub worst_u_min: f64,
    /// Lowest capacity at any time of the task, whose, and when.
    pub lowest_capacity: f64,
    pub lowest_capacity_group: String,
    pub lowest_capacity_t_s: f64,
    pub exhaustion: Option<Exhaustion>,
    /// Minutes until a group gives out at this pace (`None`: read `exhaustion_verdict`).
    pub minutes_to_exhaustion: Option<f64>,
    /// As the plan's `meaning.exhaustion_verdict` ("gives_out", "never", "not_determined"),
    /// and how long the pace was followed \[min\].
    pub exhaustion_verdict: String,
    pub minutes_followed: f64,
    /// Largest share of a rested muscle's endurance one hold uses.
    pub endurance_share: f64,
    pub rula_max: Option<i32>,
    pub reba_max: Option<u8>,
    pub back_compression_max_n: Option<f64>,
    pub capable_women: f64,
    pub capable_men: f64,
    pub current_rest_s: f64,
    /// Rest per cycle the model needs to keep every capacity above the floor.
    pub rest_needed_s: Option<f64>,
    pub rest_note: String,
    /// The same figures under each parameter variant (empty without a named parameter set).
    pub variants: Vec<VariantFigures>,
}

/// How robust the winner is against one other layout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Robustness {
    pub other: String,
    /// Parameter variants in which the best layout ranks above `other`.
    pub wins: usize,
    pub variants: usize,
}

/// The comparison document (`posture-opt compare --json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    pub adaptive: bool,
    pub fatigue_only: bool,
    pub capacity_floor: f64,
    pub ranking_rule: String,
    /// Ranked, best first.
    pub layouts: Vec<LayoutOutcome>,
    /// The best layout against each other one, across the parameter variants.
    pub robustness: Vec<Robustness>,
    /// Findings in plain words.
    pub findings: Vec<String>,
}

/// A shard's result: the outcomes of its layouts (`posture-opt compare --shard i/n --json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompareShard {
    pub kind: String,
    pub shard: String,
    pub adaptive: bool,
    pub fatigue_only: bool,
    pub capacity_floor: f64,
    pub layouts_total: usize,
    /// Every layout's [`Task::fingerprint`], in the order given: shards merge only when they
    /// were made from the same files.
    pub layout_fingerprints: Vec<String>,
    pub outcomes: Vec<LayoutOutcome>,
}

pub const SHARD_KIND: &str = "posture-opt compare shard";

/// Most layouts in one comparison (split larger studies into shards).
pub const MAX_LAYOUTS: usize = 1000;

pub const RANKING_RULE: &str = "feasible first (targets reached, no collision, balance kept), then no load above strength, then no exhaustion within the task (later exhaustion better), then NIOSH's lifting index where lifts are declared (at most 1 before at most 3 before above 3 before not defined (a lift outside the equation's limits), and above 1 the lower index, as reported to two decimals), then postures within ISO 11226 and EN 1005-4 (acceptable before conditionally acceptable before not acceptable), then L5/S1 compression within NIOSH's action limit (3400 N) before above it before above the maximum (6400 N), and above the action limit the lower compression, then the share strong enough (99 % of men and 75 % of women before 25 % of men before fewer, NIOSH 1981), then the shift verdict (acceptable before caution before exceeded: the fatigue model, Jonsson's load levels, Rohmert's rest), then longer time to exhaustion at this pace, then higher lowest capacity at any time, then lower U per hour of simulated work, then lower worst RULA";

/// A planned layout: its plan and assessment (for reports).
pub struct Planned {
    pub plan: Plan,
    pub assessment: Assessment,
}

/// The outcome of one planned layout.
pub fn outcome(
    index: usize,
    file: &str,
    task: &Task,
    plan: &Plan,
    a: &Assessment,
) -> LayoutOutcome {
    let s = &plan.summary;
    let problems = plan.problems();
    let mut min_clearance = f64::INFINITY;
    let mut closest = None;
    let mut min_margin: Option<f64> = None;
    for p in &s.phases {
        if let Some(m) = p.balance_margin_m {
            min_margin = Some(min_margin.map_or(m, |x: f64| x.min(m)));
        }
        if p.min_clearance_m < min_clearance {
            min_clearance = p.min_clearance_m;
            closest = p.closest.clone();
        }
    }
    let group = |id: &str| {
        task.half_joints
            .iter()
            .find(|h| h.id == id)
            .map(|h| h.group.clone())
            .unwrap_or_else(|| id.to_string())
    };
    let variants = a
        .uncertainty
        .as_ref()
        .map(|u| {
            u.outcomes
                .iter()
                .map(|o| VariantFigures {
                    variant: o.variant.to_string(),
                    exhausted_in_task: o.exhausted_in_task,
                    minutes_to_exhaustion: o.minutes_to_exhaustion,
                    exhaustion_verdict: o.exhaustion_verdict.to_string(),
                    minutes_followed: o.minutes_followed,
                    lowest_capacity: o.lowest_capacity,
                    rest_needed_s: o.rest_needed_s,
                })
                .collect()
        })
        .unwrap_or_default();
    let posture = a
        .verdict
        .criteria
        .iter()
        .filter(|c| c.id == "iso_11226" || c.id == "en_1005_4")
        .max_by_key(|c| c.status);
    LayoutOutcome {
        index,
        rank: 0,
        file: file.to_string(),
        task: plan.task.clone(),
        feasible: problems.is_empty(),
        problems,
        not_determined: a.verdict.not_determined.clone(),
        shift_status: a.verdict.status,
        shift_verdict: a.verdict.headline.clone(),
        lifting_index: a.lifting_index().and_then(Result::ok),
        lifting_outside_limits: a.lifting_index().and_then(Result::err),
        posture_status: posture.map_or(crate::assess::verdict::Status::Acceptable, |c| c.status),
        posture_findings: posture.map_or(String::new(), |c| c.words.clone()),
        min_clearance_m: if min_clearance.is_finite() {
            min_clearance
        } else {
            0.0
        },
        closest,
        min_balance_margin_m: min_margin,
        planned_duration_s: s.planned_duration_s,
        simulated_duration_s: s.duration_s,
        total_u_min: s.total_u,
        u_per_hour_min: if s.duration_s > 0.0 {
            s.total_u * 3600.0 / s.duration_s
        } else {
            0.0
        },
        worst_group: group(&s.worst_half_joint),
        worst_u_min: s.worst_u,
        lowest_capacity: s.lowest_capacity,
        lowest_capacity_group: group(&s.lowest_capacity_half_joint),
        lowest_capacity_t_s: s.lowest_capacity_t_s,
        exhaustion: s.exhaustion.clone(),
        minutes_to_exhaustion: a.meaning.minutes_to_exhaustion,
        exhaustion_verdict: a.meaning.exhaustion_verdict.to_string(),
        minutes_followed: a.meaning.minutes_followed,
        endurance_share: a.meaning.endurance_share,
        rula_max: a.rula_max,
        reba_max: a.reba_max,
        back_compression_max_n: a.back_compression_max_n,
        capable_women: a.capable_women,
        capable_men: a.capable_men,
        current_rest_s: a.rest.current_rest_s,
        rest_needed_s: a.rest.model.rest_s_per_cycle,
        rest_note: a.rest.model.note.clone(),
        variants,
    }
}

impl LayoutOutcome {
    /// The deciding lifting index, or why it is not defined; `None` without declared lifts.
    pub fn lifting(&self) -> Option<Result<f64, String>> {
        crate::assess::lifting::from_fields(self.lifting_index, &self.lifting_outside_limits)
    }
}

/// The figures the ranking compares.
struct Key {
    feasible: bool,
    problems: usize,
    exceeds: bool,
    /// The lifting index's class (0: at most 1, 1: at most 3, 2: above), then the index above 1.
    li: (u8, f64),
    postures: crate::assess::verdict::Status,
    /// NIOSH's class of the L5/S1 compression, then the compression above the action limit.
    back: (u8, f64),
    capable: u8,
    exhausted_at_s: f64,
    shift: crate::assess::verdict::Status,
    minutes_to_exhaustion: f64,
    lowest_capacity: f64,
    u_per_hour: f64,
    rula: i32,
}

fn key(o: &LayoutOutcome, variant: Option<usize>) -> Key {
    let v = variant.and_then(|i| o.variants.get(i));
    let exhausted_at_s = match v {
        Some(v) if v.exhausted_in_task => o.exhaustion.as_ref().map_or(0.0, |e| e.t_s),
        Some(_) => f64::INFINITY,
        None => o.exhaustion.as_ref().map_or(f64::INFINITY, |e| e.t_s),
    };
    Key {
        feasible: o.feasible,
        problems: o.problems.len(),
        exceeds: o.exhaustion.as_ref().is_some_and(|e| e.exceeds_strength),
        back: back_key(o.back_compression_max_n),
        exhausted_at_s,
        li: crate::assess::lifting::risk_key(o.lifting().as_ref()),
        postures: o.posture_status,
        capable: capable_class(o.capable_men, o.capable_women),
        shift: o.shift_status,
        minutes_to_exhaustion: v
            .map_or(o.minutes_to_exhaustion, |v| v.minutes_to_exhaustion)
            .unwrap_or(f64::INFINITY),
        lowest_capacity: v.map_or(o.lowest_capacity, |v| v.lowest_capacity),
        u_per_hour: o.u_per_hour_min,
        rula: o.rula_max.unwrap_or(0),
    }
}

/// NIOSH's class of the L5/S1 compression — 0: within the action limit (3400 N), 1: above it,
/// 2: above the maximum permissible limit (6400 N); 0 without a low-back estimate — and, above
/// the action limit, the compression itself: NIOSH counts every compression within the limit as
/// safe, while above it the risk of injury grows with the compression (Waters et al. 1993), so
/// there a lower compression ranks better.
fn back_key(compression_n: Option<f64>) -> (u8, f64) {
    let limits = crate::assess::low_back::BackParams::default();
    match compression_n {
        Some(c) if c > limits.compression_max_limit_n => (2, c),
        Some(c) if c > limits.compression_action_limit_n => (1, c),
        _ => (0, 0.0),
    }
}

/// The population-strength class of NIOSH's 1981 Work practices guide — 0: at least 99 % of men
/// and 75 % of women strong enough (its action limit), 1: at least 25 % of men (its maximum
/// permissible limit), 2: fewer.
fn capable_class(men: f64, women: f64) -> u8 {
    if men >= 0.99 && women >= 0.75 {
        0
    } else if men >= 0.25 {
        1
    } else {
        2
    }
}

fn order_keys(a: &Key, b: &Key) -> Ordering {
    b.feasible
        .cmp(&a.feasible)
        .then(a.problems.cmp(&b.problems))
        .then(a.exceeds.cmp(&b.exceeds))
        .then(b.exhausted_at_s.total_cmp(&a.exhausted_at_s))
        .then(a.li.0.cmp(&b.li.0))
        .then(a.li.1.total_cmp(&b.li.1))
        .then(a.postures.cmp(&b.postures))
        .then(a.back.0.cmp(&b.back.0))
        .then(a.back.1.total_cmp(&b.back.1))
        .then(a.capable.cmp(&b.capable))
        .then(a.shift.cmp(&b.shift))
        .then(b.minutes_to_exhaustion.total_cmp(&a.minutes_to_exhaustion))
        .then(b.lowest_capacity.total_cmp(&a.lowest_capacity))
        .then(a.u_per_hour.total_cmp(&b.u_per_hour))
        .then(a.rula.cmp(&b.rula))
}

/// Orders two outcomes by [`RANKING_RULE`] (the set's values; `variant`: under that variant).
pub fn rank_order(a: &LayoutOutcome, b: &LayoutOutcome, variant: Option<usize>) -> Ordering {
    order_keys(&key(a, variant), &key(b, variant)).then(a.index.cmp(&b.index))
}

impl Comparison {
    /// Ranks outcomes (from one run or merged shards) into the comparison document.
    pub fn from_outcomes(
        mut layouts: Vec<LayoutOutcome>,
        adaptive: bool,
        fatigue_only: bool,
        floor: f64,
    ) -> Self {
        layouts.sort_by_key(|o| o.index);
        layouts.sort_by(|a, b| rank_order(a, b, None));
        for (i, o) in layouts.iter_mut().enumerate() {
            o.rank = i + 1;
        }
        let n_var = layouts.iter().map(|o| o.variants.len()).min().unwrap_or(0);
        let robustness = match layouts.split_first() {
            Some((best, rest)) if n_var > 0 => rest
                .iter()
                .map(|o| Robustness {
                    other: o.file.clone(),
                    wins: (0..n_var)
                        .filter(|&v| rank_order(best, o, Some(v)) == Ordering::Less)
                        .count(),
                    variants: n_var,
                })
                .collect(),
            _ => Vec::new(),
        };
        let findings = findings(&layouts, &robustness);
        Comparison {
            adaptive,
            fatigue_only,
            capacity_floor: floor,
            ranking_rule: RANKING_RULE.to_string(),
            layouts,
            robustness,
            findings,
        }
    }
}

fn findings(layouts: &[LayoutOutcome], robustness: &[Robustness]) -> Vec<String> {
    let mut f = Vec::new();
    let Some(best) = layouts.first() else {
        return f;
    };
    f.push(format!("best layout: {} ({})", best.file, verdict(best)));
    for o in &layouts[1..] {
        f.push(format!("{}: {}", o.file, verdict(o)));
        f.push(what_changes(best, o));
    }
    for r in robustness {
        f.push(format!(
            "{} ranks above {} for {} of {} parameter variants",
            best.file, r.other, r.wins, r.variants
        ));
    }
    if layouts.iter().any(|o| !o.feasible) && !best.feasible {
        f.push("no layout is feasible for this worker: see the problems listed".into());
    }
    f
}

/// The first criterion of the ranking on which `best` beats `o`, in words with both figures
/// (`o`'s first).
pub fn decisive(best: &LayoutOutcome, o: &LayoutOutcome) -> String {
    let (a, b) = (key(best, None), key(o, None));
    let li = |o: &LayoutOutcome| crate::assess::lifting::index_words(o.lifting().as_ref());
    if a.feasible != b.feasible || a.problems != b.problems {
        "whether it can be done as planned".into()
    } else if a.exceeds != b.exceeds {
        "no load above strength".into()
    } else if a.exhausted_at_s != b.exhausted_at_s {
        "no exhaustion within the task".into()
    } else if a.li != b.li {
        format!("NIOSH's lifting index ({} → {})", li(o), li(best))
    } else if a.postures != b.postures {
        format!(
            "postures within ISO 11226 / EN 1005-4 ({} → {})",
            o.posture_status.words(),
            best.posture_status.words()
        )
    } else if a.back != b.back {
        format!(
            "L5/S1 compression ({:.0} → {:.0} N)",
            o.back_compression_max_n.unwrap_or(0.0),
            best.back_compression_max_n.unwrap_or(0.0)
        )
    } else if a.capable != b.capable {
        format!(
            "the share strong enough (men {:.0} % → {:.0} %, women {:.0} % → {:.0} %)",
            100.0 * o.capable_men,
            100.0 * best.capable_men,
            100.0 * o.capable_women,
            100.0 * best.capable_women
        )
    } else if a.shift != b.shift {
        format!(
            "the shift verdict ({} → {})",
            o.shift_status.words(),
            best.shift_status.words()
        )
    } else if a.minutes_to_exhaustion != b.minutes_to_exhaustion {
        "a later exhaustion at this pace".into()
    } else if a.lowest_capacity != b.lowest_capacity {
        "a higher lowest capacity".into()
    } else if a.u_per_hour != b.u_per_hour {
        "less fatigue per hour".into()
    } else if a.rula != b.rula {
        "a lower worst RULA".into()
    } else {
        "nothing: the two tie and keep the order given".into()
    }
}

/// What choosing the best layout instead of `o` changes, in plain words and numbers: the
/// deciding criteria first, and every figure that moves the other way says why in the same
/// sentence.
fn what_changes(best: &LayoutOutcome, o: &LayoutOutcome) -> String {
    use super::what_if::relative_change;
    let why = decisive(best, o);
    let worse = |what: String| format!("{what} (worse here; the ranking puts {why} before it)");
    let mut parts = Vec::new();
    if let Some(w) = super::what_if::lifting_change(o.lifting().as_ref(), best.lifting().as_ref()) {
        parts.push(if w.worse { worse(w.words) } else { w.words });
    }
    let line = format!(
        "postures (ISO 11226 / EN 1005-4) {} → {}",
        o.posture_status.words(),
        best.posture_status.words()
    );
    parts.push(if best.posture_status > o.posture_status {
        worse(line)
    } else {
        line
    });
    if let (Some(x), Some(y)) = (o.back_compression_max_n, best.back_compression_max_n) {
        let line = format!("highest L5/S1 compression {x:.0} → {y:.0} N");
        parts.push(if y > x + 0.5 { worse(line) } else { line });
    }
    let line = format!(
        "women strong enough {:.0} % → {:.0} %",
        100.0 * o.capable_women,
        100.0 * best.capable_women
    );
    parts.push(if best.capable_women + 5e-3 < o.capable_women {
        worse(line)
    } else {
        line
    });
    let line = format!(
        "fatigue per hour {:.1} → {:.1} min/h ({})",
        o.u_per_hour_min,
        best.u_per_hour_min,
        relative_change(o.u_per_hour_min, best.u_per_hour_min)
    );
    parts.push(if best.u_per_hour_min > o.u_per_hour_min * (1.0 + 1e-3) {
        worse(line)
    } else {
        line
    });
    // a group's fatigue compares only over the same simulated time (a plan that exhausts a group
    // stops there)
    let same_time = (o.simulated_duration_s - best.simulated_duration_s).abs()
        <= 1e-9 * o.simulated_duration_s.max(1.0);
    if o.worst_group == best.worst_group && o.worst_u_min > 0.0 && same_time {
        parts.push(format!(
            "the {}' fatigue {}",
            best.worst_group,
            relative_change(o.worst_u_min, best.worst_u_min)
        ));
    }
    let line = format!(
        "lowest capacity at any time {:.0} % ({}) → {:.0} % ({})",
        100.0 * o.lowest_capacity,
        o.lowest_capacity_group,
        100.0 * best.lowest_capacity,
        best.lowest_capacity_group
    );
    parts.push(if best.lowest_capacity + 5e-3 < o.lowest_capacity {
        worse(line)
    } else {
        line
    });
    if let (Some(x), Some(y)) = (o.rest_needed_s, best.rest_needed_s) {
        let line = format!(
            "rest per cycle that keeps every capacity above the capacity threshold {x:.1} → {y:.1} s"
        );
        parts.push(if y > x + 0.05 { worse(line) } else { line });
    }
    if best.exhaustion.is_some() && o.exhaustion.is_none() {
        parts.push(worse(
            "a muscle group is then exhausted within the task".into(),
        ));
    }
    format!(
        "{} instead of {} (decided by {why}): {}",
        best.file,
        o.file,
        parts.join("; ")
    )
}

/// One layout's verdict in words.
pub fn verdict(o: &LayoutOutcome) -> String {
    if !o.feasible && !o.not_determined.is_empty() {
        return format!("not determined: {}", o.not_determined.join("; "));
    }
    if !o.feasible {
        return format!("cannot be done: {}", o.problems.join("; "));
    }
    if let Some(e) = &o.exhaustion {
        return e.describe();
    }
    // the shift verdict leads; the fatigue figures follow
    let fatigue = match o.minutes_to_exhaustion {
        Some(m) => format!("kept up, the first group gives out after {:.1} h", m / 60.0),
        None if o.exhaustion_verdict == "not_determined" => format!(
            "kept up, {}",
            no_exhaustion_words(&o.exhaustion_verdict, o.minutes_followed)
        ),
        None => "no muscle group gives out at this pace".to_string(),
    };
    format!(
        "{}; fatigue: {fatigue}; lowest capacity {:.0} % ({})",
        o.shift_verdict,
        100.0 * o.lowest_capacity,
        o.lowest_capacity_group
    )
}

/// Plans and assesses layouts `indices` of `tasks` (in parallel).
pub fn plan_layouts(
    files: &[String],
    tasks: &[Task],
    indices: &[usize],
    opts: PlanOptions,
    floor: f64,
    on_done: &(dyn Fn() + Sync),
) -> Result<Vec<(LayoutOutcome, Planned)>, PlanError> {
    indices
        .par_iter()
        .map(|&i| {
            let plan = plan_task_with(&tasks[i], opts)?;
            let assessment = assess(&tasks[i], &plan, floor);
            let done = (
                outcome(i, &files[i], &tasks[i], &plan, &assessment),
                Planned { plan, assessment },
            );
            on_done();
            Ok(done)
        })
        .collect()
}

/// Plans every layout (in parallel) and ranks them. `files[i]` names `tasks[i]`; `on_done` is
/// called as each layout's plan is done (a progress display).
pub fn compare(
    files: &[String],
    tasks: &[Task],
    opts: PlanOptions,
    floor: f64,
    on_done: &(dyn Fn() + Sync),
) -> Result<(Comparison, Vec<Planned>), PlanError> {
    let all: Vec<usize> = (0..tasks.len()).collect();
    let results = plan_layouts(files, tasks, &all, opts, floor, on_done)?;
    let (outcomes, planned): (Vec<_>, Vec<_>) = results.into_iter().unzip();
    let c = Comparison::from_outcomes(outcomes, opts.adapt, opts.fatigue_only, floor);
    // planned in the ranking's order
    let mut planned: Vec<Option<Planned>> = planned.into_iter().map(Some).collect();
    let ordered = c
        .layouts
        .iter()
        .filter_map(|o| planned.get_mut(o.index).and_then(Option::take))
        .collect();
    Ok((c, ordered))
}

/// Runs one shard of a comparison.
pub fn compare_shard(
    files: &[String],
    tasks: &[Task],
    shard: Shard,
    opts: PlanOptions,
    floor: f64,
    on_done: &(dyn Fn() + Sync),
) -> Result<CompareShard, PlanError> {
    let idx = shard.indices(tasks.len());
    let results = plan_layouts(files, tasks, &idx, opts, floor, on_done)?;
    Ok(CompareShard {
        kind: SHARD_KIND.into(),
        shard: shard.to_string(),
        adaptive: opts.adapt,
        fatigue_only: opts.fatigue_only,
        capacity_floor: floor,
        layouts_total: tasks.len(),
        layout_fingerprints: tasks.iter().map(Task::fingerprint).collect(),
        outcomes: results.into_iter().map(|r| r.0).collect(),
    })
}

/// Why shard results do not merge.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    #[error("{file}: not a compare shard (kind '{kind}')")]
    Kind { file: String, kind: String },
    #[error(
        "{file}: made with other options than {first} (adaptive, fatigue-only, capacity floor and layout count must agree)"
    )]
    Options { file: String, first: String },
    #[error(
        "{file}: made from other layout files than {first} (layout {index}'s task, robot or parameter file differs)"
    )]
    Files {
        file: String,
        first: String,
        index: usize,
    },
    #[error("{file}: {field}: {problem}")]
    Value {
        file: String,
        field: String,
        problem: String,
    },
    #[error("layout {index} appears in two shards ({file})")]
    Twice { index: usize, file: String },
    #[error("the shards cover {got} of {total} layouts: missing {missing:?}")]
    Missing {
        got: usize,
        total: usize,
        missing: Vec<usize>,
    },
}

/// A merge whose shards claim more items than they hold by more than this is refused before
/// the missing items are listed (a corrupt or hostile total would otherwise be allocated for).
pub const MERGE_SLACK: usize = 1_000_000;

/// Checks every number of a shard read back from a file as an input: finite, within its range
/// (capacities and population shares 0..1, fatigue and durations >= 0, indices within the
/// layout count). The error names the field.
fn check_shard_values(s: &CompareShard) -> Result<(), (String, String)> {
    let finite = |v: f64, f: String, lo: f64, hi: f64| -> Result<(), (String, String)> {
        if v.is_finite() && v >= lo && v <= hi {
            Ok(())
        } else {
            Err((
                f,
                format!("must be a finite number within {lo}..{hi}, got {v}"),
            ))
        }
    };
    let big = f64::MAX;
    if !(s.capacity_floor.is_finite() && s.capacity_floor > 0.0 && s.capacity_floor < 1.0) {
        return Err((
            "capacity_floor".into(),
            format!("must be between 0 and 1, got {}", s.capacity_floor),
        ));
    }
    if s.layouts_total == 0 || s.layouts_total > MAX_LAYOUTS {
        return Err((
            "layouts_total".into(),
            format!("must be 1..{MAX_LAYOUTS}, got {}", s.layouts_total),
        ));
    }
    if s.outcomes.len() > s.layouts_total {
        return Err((
            "outcomes".into(),
            format!(
                "holds {} layouts, more than layouts_total ({})",
                s.outcomes.len(),
                s.layouts_total
            ),
        ));
    }
    for (i, o) in s.outcomes.iter().enumerate() {
        let f = |name: &str| format!("outcomes[{i}].{name}");
        if o.index >= s.layouts_total {
            return Err((
                f("index"),
                format!(
                    "must be below layouts_total ({}), got {}",
                    s.layouts_total, o.index
                ),
            ));
        }
        finite(o.min_clearance_m, f("min_clearance_m"), -big, big)?;
        if let Some(m) = o.min_balance_margin_m {
            finite(m, f("min_balance_margin_m"), -big, big)?;
        }
        finite(o.planned_duration_s, f("planned_duration_s"), 0.0, big)?;
        finite(o.simulated_duration_s, f("simulated_duration_s"), 0.0, big)?;
        finite(o.total_u_min, f("total_u_min"), 0.0, big)?;
        finite(o.u_per_hour_min, f("u_per_hour_min"), 0.0, big)?;
        finite(o.worst_u_min, f("worst_u_min"), 0.0, big)?;
        finite(o.lowest_capacity, f("lowest_capacity"), 0.0, 1.0)?;
        finite(o.lowest_capacity_t_s, f("lowest_capacity_t_s"), 0.0, big)?;
        if let Some(e) = &o.exhaustion {
            finite(e.t_s, f("exhaustion.t_s"), 0.0, big)?;
            finite(e.load, f("exhaustion.load"), 0.0, big)?;
        }
        if let Some(m) = o.minutes_to_exhaustion {
            finite(m, f("minutes_to_exhaustion"), 0.0, big)?;
        }
        finite(o.minutes_followed, f("minutes_followed"), 0.0, big)?;
        finite(o.endurance_share, f("endurance_share"), 0.0, big)?;
        if let Some(li) = o.lifting_index {
            finite(li, f("lifting_index"), 0.0, big)?;
            if o.lifting_outside_limits.is_some() {
                return Err((
                    f("lifting_outside_limits"),
                    "is given with a lifting index: an index outside the equation's limits is not defined".into(),
                ));
            }
        }
        if let Some(c) = o.back_compression_max_n {
            finite(c, f("back_compression_max_n"), 0.0, big)?;
        }
        finite(o.capable_women, f("capable_women"), 0.0, 1.0)?;
        finite(o.capable_men, f("capable_men"), 0.0, 1.0)?;
        finite(o.current_rest_s, f("current_rest_s"), 0.0, big)?;
        if let Some(r) = o.rest_needed_s {
            finite(r, f("rest_needed_s"), 0.0, big)?;
        }
        for (j, v) in o.variants.iter().enumerate() {
            let g = |name: &str| format!("outcomes[{i}].variants[{j}].{name}");
            if let Some(m) = v.minutes_to_exhaustion {
                finite(m, g("minutes_to_exhaustion"), 0.0, big)?;
            }
            finite(v.minutes_followed, g("minutes_followed"), 0.0, big)?;
            finite(v.lowest_capacity, g("lowest_capacity"), 0.0, 1.0)?;
            if let Some(r) = v.rest_needed_s {
                finite(r, g("rest_needed_s"), 0.0, big)?;
            }
        }
    }
    Ok(())
}

/// Merges shard results (`names` name them in messages) into one comparison. Every shard's
/// numbers are checked as inputs first (see `check_shard_values`).
pub fn merge(shards: &[(String, CompareShard)]) -> Result<Comparison, MergeError> {
    let Some((first_name, first)) = shards.first() else {
        return Err(MergeError::Missing {
            got: 0,
            total: 0,
            missing: Vec::new(),
        });
    };
    // the shards must hold every layout: a claimed total beyond what they hold is refused
    // before anything is allocated for it
    let held: usize = shards.iter().map(|(_, s)| s.outcomes.len()).sum();
    if first.layouts_total > held.saturating_add(MERGE_SLACK) {
        return Err(MergeError::Missing {
            got: held,
            total: first.layouts_total,
            missing: Vec::new(),
        });
    }
    for (name, s) in shards {
        check_shard_values(s).map_err(|(field, problem)| MergeError::Value {
            file: name.clone(),
            field,
            problem,
        })?;
    }
    let mut seen = vec![false; first.layouts_total];
    let mut outcomes = Vec::new();
    for (name, s) in shards {
        if s.kind != SHARD_KIND {
            return Err(MergeError::Kind {
                file: name.clone(),
                kind: s.kind.clone(),
            });
        }
        if s.adaptive != first.adaptive
            || s.fatigue_only != first.fatigue_only
            || s.capacity_floor != first.capacity_floor
            || s.layouts_total != first.layouts_total
        {
            return Err(MergeError::Options {
                file: name.clone(),
                first: first_name.clone(),
            });
        }
        if s.layout_fingerprints.len() != s.layouts_total
            || s.layout_fingerprints != first.layout_fingerprints
        {
            let index = (0..s.layouts_total)
                .find(|&i| s.layout_fingerprints.get(i) != first.layout_fingerprints.get(i))
                .unwrap_or(0);
            return Err(MergeError::Files {
                file: name.clone(),
                first: first_name.clone(),
                index,
            });
        }
        for o in &s.outcomes {
            match seen.get_mut(o.index) {
                Some(x) if !*x => *x = true,
                _ => {
                    return Err(MergeError::Twice {
                        index: o.index,
                        file: name.clone(),
                    });
                }
            }
            outcomes.push(o.clone());
        }
    }
    let missing: Vec<usize> = (0..seen.len()).filter(|&i| !seen[i]).collect();
    if !missing.is_empty() {
        return Err(MergeError::Missing {
            got: seen.len() - missing.len(),
            total: seen.len(),
            missing,
        });
    }
    Ok(Comparison::from_outcomes(
        outcomes,
        first.adaptive,
        first.fatigue_only,
        first.capacity_floor,
    ))
}

fn opt_s(v: Option<f64>) -> String {
    v.map_or("rest cannot help".into(), |x| format!("{x:.1} s"))
}

/// The comparison as a text table: one column per layout, best first.
pub fn comparison_table(c: &Comparison) -> String {
    let mut rows: Vec<(String, Vec<String>)> = Vec::new();
    let mut row = |name: &str, f: &dyn Fn(&LayoutOutcome) -> String| {
        rows.push((name.to_string(), c.layouts.iter().map(f).collect()));
    };
    row("rank", &|o| o.rank.to_string());
    row("file", &|o| o.file.clone());
    row("feasible", &|o| {
        if o.feasible {
            "yes".into()
        } else if !o.not_determined.is_empty() {
            format!("NOT DETERMINED: {}", o.not_determined.join("; "))
        } else {
            format!("NO: {}", o.problems.join("; "))
        }
    });
    row("shift verdict", &|o| {
        // the status and the binding criterion; the findings below give the details
        o.shift_verdict
            .split(" — ")
            .next()
            .unwrap_or_default()
            .to_string()
    });
    row("NIOSH lifting index", &|o| match o.lifting() {
        None => "—".into(),
        lifting => crate::assess::lifting::index_words(lifting.as_ref()),
    });
    row("postures (ISO 11226 / EN 1005-4)", &|o| {
        o.posture_status.words().to_string()
    });
    row("exhaustion", &|o| match &o.exhaustion {
        Some(e) => e.describe(),
        None => "none".into(),
    });
    row(
        "time to exhaustion at this pace",
        &|o| match o.minutes_to_exhaustion {
            Some(m) => crate::assess::meaning::time_words(60.0 * m),
            None => no_exhaustion_words(&o.exhaustion_verdict, o.minutes_followed),
        },
    );
    row("lowest capacity (any time)", &|o| {
        format!(
            "{:.0} % {}",
            100.0 * o.lowest_capacity,
            o.lowest_capacity_group
        )
    });
    row("endurance used by one hold", &|o| {
        format!("{:.0} %", 100.0 * o.endurance_share)
    });
    row("total U [min]", &|o| format!("{:.2}", o.total_u_min));
    row("U per hour simulated [min]", &|o| {
        format!("{:.2}", o.u_per_hour_min)
    });
    row("most fatigued group", &|o| {
        format!("{} ({:.2} min)", o.worst_group, o.worst_u_min)
    });
    row("closest clearance", &|o| {
        format!(
            "{:.0} mm{}",
            1000.0 * o.min_clearance_m,
            o.closest
                .as_ref()
                .map(|c| format!(" to {c}"))
                .unwrap_or_default()
        )
    });
    row("balance margin", &|o| {
        o.min_balance_margin_m
            .map_or("—".into(), |m| format!("{:.0} mm", 1000.0 * m))
    });
    row("worst RULA / REBA", &|o| {
        format!(
            "{} / {}",
            o.rula_max.map_or("—".into(), |r| r.to_string()),
            o.reba_max.map_or("—".into(), |r| r.to_string())
        )
    });
    row("L5/S1 compression", &|o| {
        o.back_compression_max_n
            .map_or("—".into(), |n| format!("{n:.0} N"))
    });
    row("capable women / men", &|o| {
        format!(
            "{:.0} % / {:.0} %",
            100.0 * o.capable_women,
            100.0 * o.capable_men
        )
    });
    row("rest per cycle now", &|o| {
        format!("{:.1} s", o.current_rest_s)
    });
    row(
        &format!("rest needed (capacity kept above {:.2})", c.capacity_floor),
        &|o| opt_s(o.rest_needed_s),
    );
    let w0 = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(0);
    let widths: Vec<usize> = (0..c.layouts.len())
        .map(|i| {
            rows.iter()
                .map(|r| r.1[i].chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut o = String::new();
    for (name, cells) in &rows {
        let _ = write!(o, "{name:<w0$}");
        for (cell, w) in cells.iter().zip(&widths) {
            let _ = write!(o, "  {cell:<w$}");
        }
        let _ = writeln!(o);
    }
    let _ = writeln!(o, "\nranking: {}", c.ranking_rule);
    for f in &c.findings {
        let _ = writeln!(o, "- {f}");
    }
    o
}
