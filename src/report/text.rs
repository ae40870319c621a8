//! The human summary of a plan and its assessment.

use crate::assess::Assessment;
use crate::assess::rest::RestAdvice;
use crate::plan::{Plan, Task};
use std::fmt::Write;

/// Work/rest advice as text lines; `rohmert_applies`: whether the task holds a posture long enough
/// for Rohmert's rule (the shift verdict's Rohmert criterion is not "not applicable").
pub fn rest_summary(r: &RestAdvice, p: &Plan, rohmert_applies: bool) -> String {
    let group = |id: &str| {
        p.half_joint(id)
            .map(|i| p.half_joints[i].group.clone())
            .unwrap_or(id.to_string())
    };
    let mut o = String::new();
    let _ = writeln!(
        o,
        "work and rest: {:.1} s of work and {:.1} s of rest per cycle",
        r.work_s_per_cycle, r.current_rest_s
    );
    match r.model.rest_s_per_cycle {
        Some(x) => {
            let _ = writeln!(
                o,
                "  model: {x:.1} s of rest per cycle keeps every capacity >= {:.2} (lowest now {:.2}, {})",
                r.capacity_floor,
                r.model.min_capacity_current,
                group(&r.model.limiting_half_joint)
            );
        }
        None => {
            let _ = writeln!(o, "  model: {}", r.model.note);
        }
    }
    if !rohmert_applies {
        let _ = writeln!(
            o,
            "  Rohmert (1973) rest allowance: not applicable (no work is held longer than {:.0} s in one posture, so no muscle load is static; the rule is for static holds)",
            crate::assess::verdict::ISO_STATIC_S
        );
    } else if r.rohmert.rest_s_per_cycle < 0.05 {
        let _ = writeln!(
            o,
            "  Rohmert (1973) rest allowance: none needed (no hold above 15 %MVC long enough to need it)"
        );
    } else {
        let _ = writeln!(
            o,
            "  Rohmert (1973) rest allowance: {:.1} s per cycle ({})",
            r.rohmert.rest_s_per_cycle,
            group(&r.rohmert.limiting_half_joint)
        );
    }
    o
}

/// A NIOSH lift in words: its RWL and lifting index (or why the index is not defined: a
/// multiplier at 0 puts the lift outside the equation's range), and with control at the
/// destination each end's, the governing one named.
pub fn lift_lines(r: &crate::assess::niosh::LiftResult) -> Vec<String> {
    use crate::assess::niosh::{Point, PointResult};
    let li = |x: Option<f64>, p: &PointResult| match x {
        Some(x) => format!("lifting index {x:.2}"),
        None => format!(
            "lifting index not defined: {} — outside the equation's range, no load is recommended",
            p.zero_reasons().join(", ")
        ),
    };
    let governing = match (r.governing, &r.destination) {
        (Point::Destination, Some(d)) => d,
        _ => &r.origin,
    };
    let mut v = vec![format!(
        "NIOSH lift '{}': RWL {:.1} kg, {}",
        r.name,
        r.rwl_kg,
        li(r.lifting_index, governing)
    )];
    if let Some(h) = r.uncontrolled_destination_h_cm {
        v.push(format!(
            "  the destination is not assessed (no control declared there), but its H is {h:.1} cm, beyond 63 cm (HM = 0): where placing it needs control, declare control_at_destination"
        ));
    }
    if let Some(d) = &r.destination {
        for (p, x) in [(Point::Origin, &r.origin), (Point::Destination, d)] {
            v.push(format!(
                "  at the {} (H {:.1} cm, V {:.1} cm{}): RWL {:.1} kg, {}",
                p.words(),
                x.multipliers.h_cm,
                x.multipliers.v_cm,
                if p == r.governing { ", governs" } else { "" },
                x.rwl_kg,
                li(x.lifting_index, x)
            ));
        }
    }
    v
}

fn pct(x: f64) -> String {
    format!("{:.0} %", 100.0 * x)
}

/// A share of people strong enough, rounded down: 98.6 % reads "98 %", never the 99 % design
/// limit it falls short of.
fn share(x: f64) -> String {
    format!("{:.0} %", crate::assess::share_percent_floor(x, 0))
}

/// A readable summary: the verdict first, then per phase the posture in words, the most-loaded
/// groups, RULA/REBA and the low back, then fatigue, the baselines and work/rest.
pub fn plan_summary(task: &Task, p: &Plan, a: &Assessment) -> String {
    let s = &p.summary;
    let mut o = String::new();
    let w = &task.worker;
    let _ = writeln!(
        o,
        "{} — {} plan for a {} of {:.3} m and {:.0} kg (strength percentile {:.0})",
        p.task,
        if s.adaptive {
            "fatigue-adaptive"
        } else {
            "held (not re-planned)"
        },
        w.sex.name(),
        w.stature_m,
        w.mass_kg,
        w.strength_percentile
    );
    let _ = writeln!(
        o,
        "fatigue parameters: {} ({}){}; {:.0} min planned in {} cycles of {:.0} s",
        p.fatigue_parameters.set,
        p.fatigue_model,
        sustainable_words(&p.half_joints),
        s.planned_duration_s / 60.0,
        task.cycles,
        task.cycle_s()
    );
    let _ = writeln!(o);
    let _ = writeln!(o, "VERDICT: {}", a.verdict.headline);
    for c in &a.verdict.criteria {
        let _ = writeln!(o, "  [{}] {}: {}", c.status.words(), c.name, c.words);
    }
    let _ = writeln!(
        o,
        "strong enough for every load: {} of men, {} of women; RULA up to {}, REBA up to {}{}",
        share(a.capable_men),
        share(a.capable_women),
        a.rula_max.map(|x| x.to_string()).unwrap_or("-".into()),
        a.reba_max.map(|x| x.to_string()).unwrap_or("-".into()),
        match (a.back_compression_max_n, &a.back_compression_phase) {
            (Some(c), Some(ph)) => format!("; L5/S1 compression up to {c:.0} N ('{ph}')"),
            _ => String::new(),
        }
    );
    let _ = writeln!(o);
    // the feet's lines when the task places the feet (fixed ones never move)
    let steps = task
        .stance
        .as_ref()
        .is_some_and(|st| st.placement.is_some());
    let m2 = |x: f64| (x * 100.0).round() / 100.0 + 0.0;
    for (ph, pa) in s.phases.iter().zip(&a.phases) {
        let _ = writeln!(
            o,
            "phase '{}': {}{}",
            ph.phase,
            if pa.posture_words.is_empty() {
                "posture planned".to_string()
            } else {
                pa.posture_words.clone()
            },
            if ph.reachable {
                String::new()
            } else {
                match (&ph.target_inside, &ph.target_blocked) {
                    (Some(o), _) => format!(
                        " — TARGET NOT REACHABLE: it lies inside '{o}' (the hand stops {:.0} mm from it)",
                        1000.0 * ph.hand_error_m
                    ),
                    // the hand's distance is the optimiser's; the target's fault is the shortfall
                    (None, Some(b)) => format!(
                        " — TARGET NOT REACHABLE: {b} (the hand stops {:.0} mm from it)",
                        1000.0 * ph.hand_error_m
                    ),
                    (None, None) => format!(
                        " — TARGET {} by {:.0} mm (standing where the task allows, balance kept)",
                        if ph.beyond_reach_m.is_some() {
                            "OUT OF REACH"
                        } else {
                            "NOT REACHED (no posture that reaches it found; within the body's length)"
                        },
                        1000.0 * ph.hand_error_m,
                    ),
                }
            }
        );
        let loaded: Vec<String> = ph
            .most_loaded
            .iter()
            .map(|(h, f)| {
                let g = p
                    .half_joint(h)
                    .map(|i| p.half_joints[i].group.clone())
                    .unwrap_or(h.clone());
                format!("{g} {}", pct(*f))
            })
            .collect();
        if let Some(f) = ph.feet.as_ref().filter(|_| steps) {
            let _ = writeln!(
                o,
                "  feet: {} (left sole at ({:.2}, {:.2}) m, right at ({:.2}, {:.2}) m)",
                f.words,
                m2(f.left.sole_center_m[0]),
                m2(f.left.sole_center_m[1]),
                m2(f.right.sole_center_m[0]),
                m2(f.right.sole_center_m[1])
            );
        }
        if !ph.outside_zones.is_empty() {
            let what: Vec<String> = ph
                .outside_zones
                .iter()
                .map(|z| {
                    format!(
                        "{} {:.0}° (at most {:.0}°, {})",
                        z.what, z.angle_deg, z.limit_deg, z.source
                    )
                })
                .collect();
            let why = if p.summary.zones && ph.converged {
                "the least the search found"
            } else if p.summary.zones {
                "the optimiser did not converge"
            } else {
                "zones not kept"
            };
            let _ = writeln!(
                o,
                "  outside the acceptable zones ({why}): {}",
                what.join("; ")
            );
        }
        let _ = writeln!(o, "  most loaded: {}", loaded.join(", "));
        let mut line = Vec::new();
        if let Some(r) = &pa.rula {
            line.push(format!("RULA {} ({} arm)", r.grand_score, r.side));
        }
        if let Some(r) = &pa.reba {
            line.push(format!("REBA {}", r.reba_score));
        }
        if let Some(b) = &pa.low_back {
            line.push(format!(
                "L5/S1 {:.0} N compression, {:.0} N shear",
                b.compression_n, b.shear_resultant_n
            ));
        }
        line.push(format!(
            "capable: men {}, women {}",
            share(pa.capable_men),
            share(pa.capable_women)
        ));
        if let Some(m) = ph.balance_margin_m {
            line.push(format!("balance margin {:.0} mm", 1000.0 * m));
        }
        line.push(format!("clearance {:.0} mm", 1000.0 * ph.min_clearance_m));
        let _ = writeln!(o, "  {}", line.join("; "));
        let _ = writeln!(
            o,
            "  optimiser: {} (KKT residual {:.1e}, {} iterations, best of {} starts: #{})",
            if ph.converged {
                "converged"
            } else if ph.solve.determined() {
                "stationary to the objective's precision"
            } else {
                "NOT converged"
            },
            ph.kkt_residual,
            ph.iterations,
            ph.search.seeds,
            ph.search.best_seed + 1
        );
    }
    if let Some(f) = s.rest_feet.as_ref().filter(|_| steps) {
        let _ = writeln!(
            o,
            "back to rest: feet: {} ({} steps per cycle)",
            f.words,
            s.steps_per_cycle()
        );
    }
    let _ = writeln!(o);
    let mut caps: Vec<(usize, f64)> = s.final_capacity.iter().copied().enumerate().collect();
    caps.sort_by(|a, b| a.1.total_cmp(&b.1));
    let c: Vec<String> = caps
        .iter()
        .take(4)
        .map(|(h, c)| format!("{} {:.2}", p.half_joints[*h].group, c))
        .collect();
    let _ = writeln!(o, "lowest capacities at the end: {}", c.join(", "));
    let _ = writeln!(
        o,
        "lowest capacity at any time: {:.2} ({}, at {:.0} s)",
        s.lowest_capacity,
        p.half_joint(&s.lowest_capacity_half_joint)
            .map(|i| p.half_joints[i].group.clone())
            .unwrap_or_default(),
        s.lowest_capacity_t_s
    );
    let _ = writeln!(
        o,
        "total fatigue index U = {:.2} min over {:.0} min{} (worst: {} {:.2} min); {} re-plans, {} QP solves",
        s.total_u,
        s.duration_s / 60.0,
        match &s.exhaustion {
            Some(e) => format!(
                " of the task's {:.0} (the plan stops where the {} give out)",
                s.planned_duration_s / 60.0,
                e.group
            ),
            None => String::new(),
        },
        p.half_joint(&s.worst_half_joint)
            .map(|i| p.half_joints[i].group.clone())
            .unwrap_or_default(),
        s.worst_u,
        s.replans,
        s.qp_solves
    );
    for b in &s.baselines {
        // a baseline that gives out stops early: its U is of a shorter run and reads like
        // little fatigue ("0.00 min"), so it is not printed
        let _ = writeln!(
            o,
            "  against {}: {}",
            b.name.replace('_', " "),
            match &b.exhaustion {
                Some(e) => format!("it cannot be done: {}", e.describe()),
                None => format!(
                    "{:.2} min (posture-opt {:+.0} %)",
                    b.total_u,
                    100.0 * b.change
                ),
            }
        );
    }
    if let Some(Ok(l)) = &a.lifting {
        for r in &l.lifts {
            for line in lift_lines(r) {
                let _ = writeln!(o, "{line}");
            }
        }
        if let Some(c) = &l.composite
            && let Some(cli) = c.cli
        {
            let _ = writeln!(o, "NIOSH composite lifting index {cli:.2}");
        }
        if let Some(w) = crate::assess::lifting::stance_words(task) {
            let _ = writeln!(o, "  ({w})");
        }
    }
    o.push_str(&rest_summary(&a.rest, p, a.rohmert_applies()));
    if let Some(u) = &a.uncertainty {
        o.push_str(&sensitivity_table(u));
    }
    o
}

/// How the key results move across the parameter set's documented ranges.
pub fn sensitivity_table(u: &crate::assess::uncertainty::Sensitivity) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "parameter uncertainty ({}: {}); exhausted in {} of {} variants",
        u.parameter_set,
        u.method,
        u.exhausted_in,
        u.outcomes.len()
    );
    let _ = writeln!(
        o,
        "  {:<16} {:>22} {:>16} {:>16}",
        "variant", "time to exhaustion", "lowest capacity", "rest per cycle"
    );
    for v in &u.outcomes {
        let _ = writeln!(
            o,
            "  {:<16} {:>22} {:>16} {:>16}",
            v.variant,
            match (v.minutes_to_exhaustion, v.exhausted_in_task) {
                (_, true) => "within the task".to_string(),
                (Some(m), false) => format!("{m:.0} min"),
                (None, false) => crate::assess::meaning::no_exhaustion_words(
                    v.exhaustion_verdict,
                    v.minutes_followed,
                ),
            },
            format!("{:.2}", v.lowest_capacity),
            v.rest_needed_s
                .map(|r| format!("{r:.1} s"))
                .unwrap_or("cannot help".into())
        );
    }
    o
}

/// "; sustainable load 7.7–8.0 %MVC" over the plan's muscle groups (nothing without recovery).
fn sustainable_words(groups: &[crate::plan::result::HalfJointInfo]) -> String {
    let (lo, hi) = groups.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), g| {
        (lo.min(g.sustainable_load), hi.max(g.sustainable_load))
    });
    if groups.is_empty() || hi <= 0.0 {
        return String::new();
    }
    if (hi - lo) * 100.0 < 0.05 {
        format!("; sustainable load {:.1} %MVC", 100.0 * hi)
    } else {
        format!(
            "; sustainable load {:.1}–{:.1} %MVC by muscle group",
            100.0 * lo,
            100.0 * hi
        )
    }
}
