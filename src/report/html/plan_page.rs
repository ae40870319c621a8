//! The plan report's sections.

use super::ReportError;
use super::analysis::{GroupCourse, PhaseStrain, group_courses, phase_strain, worst_phase};
use super::body_view::{self, Scene, View};
use super::curves::capacity_figures;
use super::findings::{self, group, q};
use super::fmt::{
    DASH, Finding, Level, Table, dur, esc, findings_list, kv_table, mm, num, opt, pct, share, unit,
};
use crate::assess::Assessment;
use crate::fatigue::Recovery;
use crate::plan::task::HANDS;
use crate::plan::{Plan, Task};
use std::fmt::Write;

/// A point as "(x, y, z)" in metres.
pub fn point(p: &[f64; 3]) -> String {
    format!("({}, {}, {})", num(p[0], 2), num(p[1], 2), num(p[2], 2))
}

/// The worker in one line (escaped HTML).
pub fn worker_line(task: &Task) -> String {
    let w = &task.worker;
    format!(
        "{}, {} tall, {}, strength percentile {}",
        w.sex.name(),
        unit(w.stature_m, 3, "m"),
        unit(w.mass_kg, 0, "kg"),
        num(w.strength_percentile, 0)
    )
}

fn hands_text(task: &Task, p: usize) -> String {
    let ph = &task.phases[p];
    match (
        &ph.object,
        ph.targets_m[0].is_some(),
        ph.targets_m[1].is_some(),
    ) {
        (Some(o), _, _) => format!(
            "both hands, object {} × {} × {} m",
            num(o.size_m[0], 2),
            num(o.size_m[1], 2),
            num(o.size_m[2], 2)
        ),
        (None, true, true) => "both hands".into(),
        (None, true, false) => "right hand".into(),
        (None, false, true) => "left hand".into(),
        _ => DASH.into(),
    }
}

fn targets_text(task: &Task, p: usize) -> String {
    let ph = &task.phases[p];
    if let Some(o) = &ph.object {
        return format!("object centre {}", point(&o.center_m));
    }
    let v: Vec<String> = (0..2)
        .filter_map(|h| {
            ph.targets_m[h].map(|t| {
                let s = point(&[t.x, t.y, t.z]);
                if ph.targets_m[1 - h].is_some() {
                    format!("{} {s}", HANDS[h])
                } else {
                    s
                }
            })
        })
        .collect();
    if v.is_empty() {
        DASH.into()
    } else {
        v.join("<br>")
    }
}

fn target_height(task: &Task, p: usize) -> f64 {
    let ph = &task.phases[p];
    if let Some(o) = &ph.object {
        return o.center_m[2];
    }
    let z: Vec<f64> = ph.targets_m.iter().flatten().map(|t| t.z).collect();
    if z.is_empty() {
        f64::NAN
    } else {
        z.iter().sum::<f64>() / z.len() as f64
    }
}

fn lift_text(task: &Task, p: usize) -> String {
    let v: Vec<String> = task
        .lifts
        .iter()
        .filter_map(|l| {
            if l.origin == p {
                Some(format!("start of lift {}", q(&l.name)))
            } else if l.destination == p {
                Some(format!("end of lift {}", q(&l.name)))
            } else {
                None
            }
        })
        .collect();
    if v.is_empty() {
        DASH.into()
    } else {
        v.join("<br>")
    }
}

fn load_kg(task: &Task, p: usize) -> f64 {
    let g = task.gravity_m_s2.norm().max(1e-9);
    task.phases[p].total_force_n().norm() / g
}

/// The worker and the task.
fn worker_and_task(task: &Task, plan: &Plan, a: &Assessment) -> String {
    let s = &plan.summary;
    let w = &task.worker;
    let mut o = String::from("<div class=\"two\"><div><h3>Worker</h3>");
    o.push_str(&kv_table(&[
        ("sex", esc(w.sex.name())),
        (
            "stature",
            format!(
                "{} (percentile {} of the worker’s sex)",
                unit(w.stature_m, 3, "m"),
                num(
                    crate::study::sweep::stature_percentile(w.sex, w.stature_m),
                    0
                )
            ),
        ),
        (
            "body mass",
            format!(
                "{} (percentile {})",
                unit(w.mass_kg, 1, "kg"),
                num(crate::study::sweep::mass_percentile(w.sex, w.mass_kg), 0)
            ),
        ),
        (
            "strength percentile",
            format!("{} (of the worker’s sex)", num(w.strength_percentile, 0)),
        ),
        ("body model", esc(&plan.robot)),
    ]));
    o.push_str("</div><div><h3>Task</h3>");
    let simulated = if (s.duration_s - s.planned_duration_s).abs() > 1e-6 {
        format!(
            " — simulated {} (stopped at the exhaustion)",
            dur(s.duration_s)
        )
    } else {
        String::new()
    };
    o.push_str(&kv_table(&[
        (
            "cycles",
            format!(
                "{} × {} ({} work + {} rest)",
                task.cycles,
                dur(task.cycle_s()),
                dur(a.rest.work_s_per_cycle),
                dur(task.rest_s)
            ),
        ),
        (
            "duration",
            format!("{}{simulated}", dur(s.planned_duration_s)),
        ),
        (
            "plan",
            format!(
                "{}{}",
                if s.adaptive {
                    format!(
                        "fatigue-adaptive: re-planned {} times as capacity fell",
                        s.replans
                    )
                } else {
                    "held: the first plan’s postures all task".to_string()
                },
                if s.fatigue_only {
                    "; fatigue only (no discomfort term)"
                } else {
                    ""
                }
            ),
        ),
        (
            "fatigue model",
            format!(
                "{} — parameter set {}",
                esc(&plan.fatigue_model),
                esc(&plan.fatigue_parameters.set)
            ),
        ),
        (
            "capacity floor",
            format!("{} (for the rest advice)", pct(a.rest.capacity_floor)),
        ),
    ]));
    o.push_str("</div></div>");
    o
}

/// The phases of one cycle.
/// The phases of one cycle (`a`: the plan's assessment, for the hand heights reached).
pub(super) fn phase_table(task: &Task, a: Option<&Assessment>) -> String {
    let mut t = Table::new(
        "phases",
        &[
            "#",
            "phase",
            "hands",
            "target [m] (x, y, z)",
            "height above the floor",
            "load",
            "held",
            "lift",
        ],
    )
    .numeric(&[0, 5, 6]);
    for (p, ph) in task.phases.iter().enumerate() {
        let zt = target_height(task, p);
        let reached = a
            .and_then(|a| a.phases.get(p))
            .and_then(|x| x.hand_height_m);
        let height = match reached {
            Some(z) if (z - zt).abs() > 0.01 => {
                format!("{} (hands reach {})", unit(zt, 2, "m"), unit(z, 2, "m"))
            }
            _ => unit(zt, 2, "m"),
        };
        t.row(
            None,
            vec![
                (p + 1).to_string(),
                esc(&ph.name),
                hands_text(task, p),
                targets_text(task, p),
                height,
                unit(load_kg(task, p), 1, "kg"),
                dur(ph.duration_s),
                lift_text(task, p),
            ],
        );
    }
    if task.rest_s > 0.0 {
        t.row(
            None,
            vec![
                DASH.into(),
                "rest".into(),
                "arms hanging".into(),
                DASH.into(),
                DASH.into(),
                unit(0.0, 1, "kg"),
                dur(task.rest_s),
                DASH.into(),
            ],
        );
    }
    t.render()
}

/// The groups that fall lowest.
fn groups_table(task: &Task, plan: &Plan, courses: &[GroupCourse], floor: f64) -> String {
    let mut t = Table::new(
        "groups",
        &[
            "muscle group",
            "lowest capacity (when)",
            "at the end",
            "highest load (phase)",
            "held forever up to",
            "endurance used per hold",
        ],
    )
    .numeric(&[4, 5]);
    for c in courses.iter().take(12) {
        let hj = &plan.half_joints[c.h];
        let level = if c.max_load > 0.0 && c.lowest <= c.max_load + 1e-9 {
            Level::Bad
        } else if c.lowest < floor {
            Level::Warn
        } else {
            Level::Ok
        };
        t.row(
            Some(level),
            vec![
                format!("{}<br><small>{}</small>", esc(&hj.group), esc(&hj.id)),
                format!("{} ({})", pct(c.lowest), dur(c.lowest_t_s)),
                pct(c.end),
                format!(
                    "{}{}",
                    pct(c.max_load),
                    c.max_load_phase
                        .map(|p| format!(" ({})", q(&task.phases[p].name)))
                        .unwrap_or_default()
                ),
                pct(hj.sustainable_load),
                pct(c.endurance_share),
            ],
        );
    }
    format!(
        "{}<p class=\"meta\">The 12 groups whose capacity falls lowest, of {}. Row colour: red, the capacity falls to the load (exhaustion); amber, below the capacity floor of {}; green, above it. “Held forever up to”: the largest load the group can hold without ever tiring out (its recovery balances its fatigue). “Endurance used per hold”: one hold’s duration against the time a rested muscle can hold that load.</p>",
        t.render(),
        plan.half_joints.len(),
        pct(floor)
    )
}

/// One phase: figures and numbers.
fn phase_card(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    p: usize,
    scene: &Scene,
    frame: &body_view::Frame,
    strain: &PhaseStrain,
) -> String {
    let ph = &task.phases[p];
    let sm = &plan.summary.phases[p];
    let pa = a.phases.get(p);
    let problems = findings::phase_problems(sm);
    let mut o = String::new();
    let _ = write!(
        o,
        "<div class=\"phase\"><h3>{}. {} <span class=\"meta\">— {}, {}, held {}</span></h3>",
        p + 1,
        esc(&ph.name),
        hands_text(task, p),
        unit(load_kg(task, p), 1, "kg"),
        dur(ph.duration_s)
    );
    o.push_str(&body_view::views_html(
        task,
        scene,
        frame,
        &format!("{}. {}", p + 1, ph.name),
    ));
    let mut rows: Vec<(&str, String)> = Vec::new();
    rows.push((
        "posture",
        pa.map(|x| x.posture_words.as_str())
            .filter(|w| !w.is_empty())
            .map(esc)
            .unwrap_or_else(|| DASH.into()),
    ));
    rows.push((
        "hands",
        if problems.is_empty() {
            format!("on target (error {})", mm(sm.hand_error_m))
        } else {
            format!("<span class=\"bad-text\">{}</span>", problems.join("; "))
        },
    ));
    let loaded: Vec<String> = sm
        .most_loaded
        .iter()
        .map(|(h, l)| format!("{} {}", esc(&group(plan, h)), pct(*l)))
        .collect();
    rows.push((
        "most loaded (share of strength)",
        if loaded.is_empty() {
            DASH.into()
        } else {
            loaded.join(", ")
        },
    ));
    rows.push((
        "endurance used per hold",
        match strain.share_group {
            Some(h) => format!(
                "{} of a rested muscle’s endurance — the {} at {} of their strength",
                pct(strain.endurance_share),
                esc(&plan.half_joints[h].group),
                pct(strain.loads.get(h).copied().unwrap_or(f64::NAN))
            ),
            None => "none: no group is loaded enough to tire".into(),
        },
    ));
    if let Some(pa) = pa {
        if let Some(r) = &pa.rula {
            rows.push((
                "RULA",
                format!(
                    "<b>{}</b> ({} arm) — action level {}: {}",
                    r.grand_score,
                    esc(&r.side),
                    r.action_level,
                    esc(r.action)
                ),
            ));
        }
        if let Some(r) = &pa.reba {
            rows.push((
                "REBA",
                format!(
                    "<b>{}</b> — {} risk: {}",
                    r.reba_score,
                    r.risk.level.label(),
                    esc(r.risk.action)
                ),
            ));
        }
        if let Some(b) = &pa.low_back {
            rows.push((
                "L5/S1",
                format!(
                    "compression {} (action limit {}, maximum {}), shear {} (limit {})",
                    unit(b.compression_n, 0, "N"),
                    unit(b.params.compression_action_limit_n, 0, "N"),
                    unit(b.params.compression_max_limit_n, 0, "N"),
                    unit(b.shear_resultant_n, 0, "N"),
                    unit(b.params.shear_limit_n, 0, "N")
                ),
            ));
        }
        rows.push((
            "strong enough",
            format!(
                "{} of women, {} of men{}",
                share(pa.capable_women),
                share(pa.capable_men),
                pa.capable
                    .first()
                    .map(|c| format!(
                        " (limit: {}, {})",
                        esc(&c.group),
                        unit(c.required_nm, 0, "N·m")
                    ))
                    .unwrap_or_default()
            ),
        ));
    }
    if let Some(m) = sm.balance_margin_m {
        let record = plan.postures.iter().rev().find(|r| r.phase == ph.name);
        let share = record.and_then(|r| r.left_foot_share);
        let seat = record.and_then(|r| r.seat_share);
        rows.push((
            "balance",
            format!(
                "centre of pressure {} {} {}{}{}",
                mm(m.abs()),
                if m >= 0.0 { "inside" } else { "outside" },
                task.supports(),
                seat.map(|s| format!("; {} of the weight on the seat", pct(s)))
                    .unwrap_or_default(),
                share
                    .map(|s| format!(
                        "; {} {}on the left foot",
                        pct(s),
                        if seat.is_some() { "" } else { "of the weight " }
                    ))
                    .unwrap_or_default()
            ),
        ));
    }
    rows.push((
        "clearance",
        format!(
            "{}{}",
            mm(sm.min_clearance_m),
            sm.closest
                .as_deref()
                .map(|c| format!(" ({})", esc(c)))
                .unwrap_or_default()
        ),
    ));
    if !sm.at_limits.is_empty() {
        rows.push(("joints at a limit", esc(&sm.at_limits.join(", "))));
    }
    o.push_str(&kv_table(&rows));
    o.push_str("</div>");
    o
}

fn scores_table(a: &Assessment) -> String {
    let mut t = Table::new(
        "scores",
        &[
            "phase",
            "RULA",
            "arm",
            "upper arm",
            "lower arm",
            "wrist",
            "neck",
            "trunk",
            "legs",
            "RULA action",
            "REBA",
            "REBA risk",
        ],
    )
    .numeric(&[1, 3, 4, 5, 6, 7, 8, 10]);
    for p in &a.phases {
        let level = match (
            p.rula.as_ref().map(|r| r.grand_score),
            p.reba.as_ref().map(|r| r.reba_score),
        ) {
            (Some(7..), _) | (_, Some(11..)) => Some(Level::Bad),
            (Some(5..=6), _) | (_, Some(8..=10)) => Some(Level::Warn),
            (Some(_), _) | (_, Some(_)) => Some(Level::Ok),
            _ => None,
        };
        let r = p.rula.as_ref();
        t.row(
            level,
            vec![
                esc(&p.phase),
                opt(r, |r| format!("<b>{}</b>", r.grand_score)),
                opt(r, |r| esc(&r.side)),
                opt(r, |r| r.upper_arm.to_string()),
                opt(r, |r| r.lower_arm.to_string()),
                opt(r, |r| r.wrist.to_string()),
                opt(r, |r| r.neck.to_string()),
                opt(r, |r| r.trunk.to_string()),
                opt(r, |r| r.legs.to_string()),
                opt(r, |r| format!("{}: {}", r.action_level, esc(r.action))),
                opt(p.reba.as_ref(), |r| format!("<b>{}</b>", r.reba_score)),
                opt(p.reba.as_ref(), |r| esc(r.risk.level.label())),
            ],
        );
    }
    t.render()
}

fn back_and_strength_table(a: &Assessment) -> String {
    let mut t = Table::new(
        "back",
        &[
            "phase",
            "L5/S1 compression",
            "shear",
            "verdict",
            "women strong enough",
            "men strong enough",
            "limiting group",
        ],
    )
    .numeric(&[1, 2, 4, 5]);
    for p in &a.phases {
        let b = p.low_back.as_ref();
        let verdict = b.map(|b| {
            if b.compression_n > b.params.compression_max_limit_n {
                (Level::Bad, "above the maximum permissible limit")
            } else if b.compression_n > b.params.compression_action_limit_n {
                (Level::Warn, "above the action limit")
            } else if b.shear_resultant_n > b.params.shear_limit_n {
                (Level::Warn, "shear above its limit")
            } else {
                (Level::Ok, "within the limits")
            }
        });
        let cap = p.capable_women.min(p.capable_men);
        let cap_level = if cap < 0.5 {
            Level::Bad
        } else if cap < 0.75 {
            Level::Warn
        } else {
            Level::Ok
        };
        let level = verdict.map_or(cap_level, |v| v.0.min(cap_level));
        t.row(
            Some(level),
            vec![
                esc(&p.phase),
                opt(b, |b| unit(b.compression_n, 0, "N")),
                opt(b, |b| unit(b.shear_resultant_n, 0, "N")),
                opt(verdict, |v| v.1.to_string()),
                share(p.capable_women),
                share(p.capable_men),
                opt(p.capable.first(), |c| {
                    format!("{} ({})", esc(&c.group), unit(c.required_nm, 0, "N·m"))
                }),
            ],
        );
    }
    t.render()
}

fn lifting_section(task: &Task, a: &Assessment) -> String {
    let Some(l) = &a.lifting else {
        return String::new();
    };
    let mut o = String::from("<h3>Lifting (revised NIOSH equation)</h3>");
    match l {
        Err(e) => {
            let _ = write!(o, "<p>The equation could not be applied: {}.</p>", esc(e));
        }
        Ok(l) => {
            let mut t = Table::new(
                "niosh",
                &[
                    "lift",
                    "end",
                    "load",
                    "H",
                    "V",
                    "D",
                    "A",
                    "frequency",
                    "RWL",
                    "lifting index",
                ],
            )
            .numeric(&[2, 3, 4, 5, 6, 7, 8, 9]);
            let mut undefined = Vec::new();
            for r in &l.lifts {
                use crate::assess::niosh::Point;
                // each end with control at the destination (the governing one marked), else
                // the origin alone
                let ends: Vec<(Point, &crate::assess::niosh::PointResult)> = match &r.destination {
                    Some(d) => vec![(Point::Origin, &r.origin), (Point::Destination, d)],
                    None => vec![(Point::Origin, &r.origin)],
                };
                let several = ends.len() > 1;
                for (p, x) in ends {
                    let m = &x.multipliers;
                    // graded as the index is reported (1.004 reads 1.00: at most 1)
                    let level = match x.lifting_index.map(crate::assess::lifting::reported) {
                        Some(v) if v > 3.0 => Level::Bad,
                        Some(v) if v > 1.0 => Level::Warn,
                        Some(_) => Level::Ok,
                        None => Level::Bad,
                    };
                    if x.lifting_index.is_none() {
                        undefined.push(format!(
                            "{} at the {}: {}",
                            esc(&r.name),
                            p.words(),
                            esc(&x.zero_reasons().join(", "))
                        ));
                    }
                    t.row(
                        Some(level),
                        vec![
                            esc(&r.name),
                            format!(
                                "{}{}",
                                p.words(),
                                if several && p == r.governing {
                                    " (governs)"
                                } else {
                                    ""
                                }
                            ),
                            unit(r.load_kg, 1, "kg"),
                            unit(m.h_cm, 0, "cm"),
                            unit(m.v_cm, 0, "cm"),
                            unit(m.d_cm, 0, "cm"),
                            unit(m.asymmetry_deg, 0, "°"),
                            unit(r.freq_per_min, 2, "/min"),
                            unit(x.rwl_kg, 1, "kg"),
                            match x.lifting_index {
                                Some(v) => format!("<b>{}</b>", num(v, 2)),
                                None => "<b>not defined</b>".into(),
                            },
                        ],
                    );
                }
            }
            o.push_str(&t.render());
            if !undefined.is_empty() {
                let _ = write!(
                    o,
                    "<p>Lifting index not defined (a multiplier is 0: the lift is outside the equation's range and no load is recommended; Waters et al. 1994): {}.</p>",
                    undefined.join("; ")
                );
            }
            let far: Vec<String> = l
                .lifts
                .iter()
                .filter_map(|r| {
                    r.uncontrolled_destination_h_cm
                        .map(|h| format!("{} (H {})", esc(&r.name), unit(h, 1, "cm")))
                })
                .collect();
            if !far.is_empty() {
                let _ = write!(
                    o,
                    "<p>Destination not assessed (no control declared there), but beyond the equation's 63 cm of horizontal reach (HM = 0): {}. Where placing the load needs control, declare <code>control_at_destination</code>.</p>",
                    far.join("; ")
                );
            }
            if let Some(c) = l.composite.as_ref().and_then(|c| c.cli) {
                let _ = write!(o, "<p>Composite lifting index: <b>{}</b>.</p>", num(c, 2));
            }
            o.push_str("<p class=\"meta\">Lifting index ≤ 1: nearly all healthy workers can do the lift; above 1 some, above 3 most workers are at increased risk of low-back injury (Waters et al. 1993).");
            if let Some(w) = crate::assess::lifting::stance_words(task) {
                let _ = write!(o, " {}.", esc(w));
            }
            o.push_str("</p>");
        }
    }
    o
}

fn rest_section(plan: &Plan, a: &Assessment) -> String {
    let r = &a.rest;
    let mut o = String::new();
    o.push_str(&kv_table(&[
        (
            "work and rest per cycle",
            format!("{} of work, {} of rest", dur(r.work_s_per_cycle), dur(r.current_rest_s)),
        ),
        (
            "the fatigue model",
            match r.model.rest_s_per_cycle {
                Some(x) => format!(
                    "<b>{}</b> of rest per cycle keeps every capacity at or above {} (lowest then {}; now {}, {})",
                    dur(x),
                    pct(r.capacity_floor),
                    opt(r.model.min_capacity_at_recommended, pct),
                    pct(r.model.min_capacity_current),
                    esc(&group(plan, &r.model.limiting_half_joint))
                ),
                None => format!("<span class=\"bad-text\">{}</span>", esc(&r.model.note)),
            },
        ),
        (
            "Rohmert (1973) rest allowance",
            if !a.rohmert_applies() {
                format!(
                    "not applicable (no work is held longer than {:.0} s in one posture, so no muscle load is static; the rule is for static holds)",
                    crate::assess::verdict::ISO_STATIC_S
                )
            } else {
            format!(
                "<b>{}</b> per cycle{}{}",
                dur(r.rohmert.rest_s_per_cycle),
                if r.rohmert.limiting_half_joint.is_empty() {
                    " (no hold above 15 % of strength)".to_string()
                } else {
                    format!(" (limited by the {})", esc(&group(plan, &r.rohmert.limiting_half_joint)))
                },
                if r.rohmert.over_mvc.is_empty() {
                    String::new()
                } else {
                    format!(
                        "; no answer for holds above 100 % of strength: {}",
                        esc(&r.rohmert.over_mvc.iter().map(|h| group(plan, h)).collect::<Vec<_>>().join(", "))
                    )
                }
            )
            },
        ),
        (
            "which to use",
            "the fatigue model's figure: it replays every cycle of the task, so fatigue that accumulates from cycle to cycle is counted; Rohmert's allowance sizes the rest after one hold from a rested muscle and does not accumulate, which is why it is far smaller".into(),
        ),
    ]));
    o
}

fn baselines_section(plan: &Plan) -> String {
    let s = &plan.summary;
    if s.baselines.is_empty() {
        return "<p>No baselines were planned.</p>".into();
    }
    let mut t = Table::new(
        "baselines",
        &[
            "plan",
            "how its postures are chosen",
            "outcome",
            "fatigue index U",
            "posture-opt’s difference",
        ],
    )
    .numeric(&[3]);
    t.row(
        None,
        vec![
            "<b>posture-opt</b>".into(),
            "fatigue-aware, planned over the whole task".into(),
            match &s.exhaustion {
                Some(e) => format!(
                    "<span class=\"bad-text\">{}</span>",
                    findings::exhaustion_html(e)
                ),
                None => format!("lasts the whole task ({})", dur(s.duration_s)),
            },
            unit(s.total_u, 1, "min"),
            DASH.into(),
        ],
    );
    for b in &s.baselines {
        let (level, outcome, diff) = match (&b.exhaustion, &s.exhaustion) {
            (Some(e), _) => (
                Level::Bad,
                format!(
                    "<span class=\"bad-text\">{}</span>",
                    findings::exhaustion_html(e)
                ),
                "not comparable: it stops early".to_string(),
            ),
            (None, Some(_)) => (
                Level::Ok,
                format!("lasts the whole task ({})", dur(b.duration_s)),
                "posture-opt’s plan stops early".into(),
            ),
            (None, None) => (
                Level::Ok,
                format!("lasts the whole task ({})", dur(b.duration_s)),
                if b.change.abs() < 0.005 {
                    "about the same fatigue".to_string()
                } else if b.change < 0.0 {
                    format!("{} less fatigue", pct(-b.change))
                } else {
                    format!("{} more fatigue", pct(b.change))
                },
            ),
        };
        t.row(
            Some(level),
            vec![
                esc(&b.name.replace('_', " ")),
                esc(&b.description),
                outcome,
                unit(b.total_u, 1, "min"),
                diff,
            ],
        );
    }
    format!(
        "{}<p class=\"meta\">U, the fatigue index summed over the muscle groups, is only compared between plans that last the whole task: a plan that stops at an exhaustion accumulates U over a shorter time.</p>",
        t.render()
    )
}

fn uncertainty_section(plan: &Plan, task: &Task, a: &Assessment) -> String {
    let Some(u) = &a.uncertainty else {
        return "<p>The task does not use a named parameter set with documented ranges: no uncertainty analysis.</p>".into();
    };
    let mut t = Table::new(
        "uncertainty",
        &[
            "parameter variant",
            "exhausted within the task (as planned)?",
            "the final postures held from the start: time to exhaustion",
            "lowest capacity at any time",
            "rest needed per cycle",
        ],
    )
    .numeric(&[2, 3, 4]);
    let _ = plan;
    for o in &u.outcomes {
        let early = o
            .minutes_to_exhaustion
            .is_some_and(|m| 60.0 * m <= task.duration_s());
        t.row(
            Some(if o.exhausted_in_task {
                Level::Bad
            } else if early {
                Level::Warn
            } else {
                Level::Ok
            }),
            vec![
                esc(o.variant),
                if o.exhausted_in_task {
                    "yes".into()
                } else {
                    "no".into()
                },
                match o.minutes_to_exhaustion {
                    Some(m) if 60.0 * m <= task.duration_s() && !o.exhausted_in_task => {
                        format!(
                            "{} (shorter than the task: the plan lasts only by changing posture)",
                            dur(60.0 * m)
                        )
                    }
                    Some(m) if 60.0 * m <= task.duration_s() => {
                        format!("{} (within the task)", dur(60.0 * m))
                    }
                    Some(m) => dur(60.0 * m),
                    None => crate::assess::meaning::no_exhaustion_words(
                        o.exhaustion_verdict,
                        o.minutes_followed,
                    ),
                },
                format!(
                    "{} ({})",
                    pct(o.lowest_capacity),
                    esc(&o.lowest_capacity_group)
                ),
                o.rest_needed_s.map_or_else(
                    || "no rest up to 10× the work time keeps every group above the floor".into(),
                    dur,
                ),
            ],
        );
    }
    format!(
        "<p>Parameter set {}: {}. In {} of {} variants a muscle group is exhausted within the task.</p>{}",
        esc(&u.parameter_set),
        esc(u.method),
        u.exhausted_in,
        u.outcomes.len(),
        t.render()
    )
}

fn recovery_text(r: &Recovery) -> String {
    match *r {
        Recovery::None => "none".into(),
        Recovery::Constant { r_per_min } => format!("constant {}/min", num(r_per_min, 3)),
        Recovery::Perfusion {
            rest_per_min,
            limit_fmvc,
        } => format!(
            "{}/min at rest, none from {} of strength",
            num(rest_per_min, 3),
            pct(limit_fmvc)
        ),
        Recovery::Routed {
            slow_rest_per_min,
            fast_rest_per_min,
            limit_fmvc,
            fast_share_max,
        } => format!(
            "two deficits: slow {}/min and fast {}/min at rest, none from {} of strength; up to {} of new fatigue to the fast one above 25 % of strength",
            num(slow_rest_per_min, 3),
            num(fast_rest_per_min, 1),
            pct(limit_fmvc),
            pct(fast_share_max)
        ),
    }
}

/// The fatigue parameter set of a task, with its sources.
pub(super) fn parameter_set_table(fp: &crate::plan::task::FatigueChoice) -> String {
    kv_table(&[
        (
            "parameter set",
            format!("<b>{}</b> — {}", esc(&fp.set), esc(&fp.description)),
        ),
        ("fatigue rate k", esc(&fp.k_source)),
        ("recovery", esc(&fp.recovery_source)),
    ])
}

pub(super) fn parameters_section(plan: &Plan, courses: &[GroupCourse]) -> String {
    let fp = &plan.fatigue_parameters;
    let mut o = kv_table(&[
        (
            "parameter set",
            format!("<b>{}</b> — {}", esc(&fp.set), esc(&fp.description)),
        ),
        ("fatigue rate k", esc(&fp.k_source)),
        ("recovery", esc(&fp.recovery_source)),
    ]);
    // strength sources, numbered once
    let mut sources: Vec<&str> = Vec::new();
    for h in &plan.half_joints {
        if !sources.contains(&h.strength_source.as_str()) {
            sources.push(&h.strength_source);
        }
    }
    let lowest = |h: usize| {
        courses
            .iter()
            .find(|c| c.h == h)
            .map_or(f64::NAN, |c| c.lowest)
    };
    let mut t = Table::new(
        "params",
        &[
            "muscle group",
            "id",
            "strength (MVC)",
            "k",
            "recovery",
            "held forever up to",
            "lowest capacity",
            "strength source",
        ],
    )
    .numeric(&[2, 3, 5, 6]);
    for (i, h) in plan.half_joints.iter().enumerate() {
        let src = sources
            .iter()
            .position(|s| *s == h.strength_source)
            .map_or(0, |x| x + 1);
        t.row(
            None,
            vec![
                esc(&h.group),
                format!("<small>{}</small>", esc(&h.id)),
                unit(h.mvc_nm, 0, "N·m"),
                format!("{}/min", num(h.k_per_min, 3)),
                recovery_text(&h.recovery),
                pct(h.sustainable_load),
                pct(lowest(i)),
                format!("[{src}]"),
            ],
        );
    }
    o.push_str(&t.render());
    o.push_str("<h3>Strength sources</h3><ol class=\"sources\">");
    for s in sources {
        let _ = write!(o, "<li>{}</li>", esc(s));
    }
    o.push_str("</ol>");
    o
}

fn optimiser_section(plan: &Plan) -> String {
    let mut t = Table::new(
        "optimiser",
        &[
            "phase",
            "converged",
            "stop",
            "iterations",
            "KKT residual",
            "hand error",
            "starts (kept)",
        ],
    )
    .numeric(&[3, 4, 5]);
    for p in &plan.summary.phases {
        t.row(
            Some(if p.converged { Level::Ok } else { Level::Warn }),
            vec![
                esc(&p.phase),
                if p.converged {
                    "yes".into()
                } else {
                    "no".into()
                },
                esc(&serde_json::to_value(p.solve.stop)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_default()),
                p.iterations.to_string(),
                if p.kkt_residual.is_finite() {
                    format!("{:.1e}", p.kkt_residual)
                } else {
                    DASH.into()
                },
                mm(p.hand_error_m),
                format!("{} (#{})", p.search.seeds, p.search.best_seed + 1),
            ],
        );
    }
    format!(
        "{}<p class=\"meta\">Re-plans: {}; QP solves: {}; SQP iterations: {}.</p>",
        t.render(),
        plan.summary.replans,
        plan.summary.qp_solves,
        plan.summary.sqp_iterations
    )
}

/// The plan report's body (inside `<body>`).
pub fn body(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    what_ifs: &[crate::study::what_if::WhatIf],
) -> Result<String, ReportError> {
    let n = task.phases.len().min(plan.summary.phases.len());
    let strain = phase_strain(task, plan);
    let courses = group_courses(task, plan, &strain);
    let worst = worst_phase(task, plan, a, &strain);
    let scenes: Vec<Scene> = (0..n)
        .map(|p| body_view::scene(task, &plan.summary.phases[p].q_rad, Some(p)))
        .collect::<Result<_, _>>()?;
    let refs: Vec<&Scene> = scenes.iter().collect();
    let views = [View::Side, View::Front, View::Top];
    let frame = body_view::frame(task, &refs, &views, 1000.0, 470.0);
    let floor = a.rest.capacity_floor;

    let mut o = String::new();
    let _ = write!(
        o,
        "<header><h1>{}</h1><p class=\"meta\">Plan report — {} · {} cycles of {} · posture-opt {}</p></header>",
        esc(&plan.task),
        worker_line(task),
        task.cycles,
        dur(task.cycle_s()),
        env!("CARGO_PKG_VERSION")
    );
    let mut v = findings::verdict(plan, a);
    let mut f: Vec<Finding> = findings::findings(task, plan, a, &strain, &courses, worst);
    f.insert(0, findings::criteria_finding(a));
    for (i, w) in what_ifs.iter().enumerate() {
        f.insert((1 + i).min(f.len()), findings::what_if_finding(w));
    }
    // a fatigue verdict that is fine does not hide the problems found otherwise
    let problems = f.iter().filter(|x| x.level == Level::Bad).count();
    if v.level != Level::Bad && problems > 0 {
        v.level = Level::Warn;
        let _ = write!(
            v.html,
            " <b>But {} below {} a problem.</b>",
            if problems == 1 {
                "one finding".to_string()
            } else {
                format!("{problems} findings")
            },
            if problems == 1 { "shows" } else { "show" }
        );
    }
    // the change that would help most, when one clearly would
    if let Some(w) = crate::study::what_if::advice(what_ifs) {
        let _ = write!(v.html, " {}", findings::advice_sentence(w));
    }
    let _ = write!(
        o,
        "<div class=\"verdict {}\">{}</div>",
        v.level.class(),
        v.html
    );
    o.push_str("<section><h2>Findings</h2>");
    o.push_str(&findings_list(&f));
    o.push_str("</section>");

    o.push_str("<section><h2>Worker and task</h2>");
    o.push_str(&worker_and_task(task, plan, a));
    o.push_str("<h3>Phases of one cycle</h3>");
    o.push_str(&phase_table(task, Some(a)));
    o.push_str("</section>");

    o.push_str("<section class=\"major\"><h2>Capacity over time</h2>");
    o.push_str(&capacity_figures(plan, &courses, floor));
    o.push_str("<h3>Muscle groups that fall lowest</h3>");
    o.push_str(&groups_table(task, plan, &courses, floor));
    o.push_str("</section>");

    let _ = write!(
        o,
        "<section class=\"major\"><h2>Postures</h2><p class=\"meta\">Each phase’s posture in the {} plan, drawn from the body model’s joint angles; all views at the same scale.</p>",
        if plan.summary.adaptive && plan.summary.replans > 0 {
            "last (re-planned)"
        } else {
            ""
        }
    );
    for p in 0..n {
        o.push_str(&phase_card(
            task, plan, a, p, &scenes[p], &frame, &strain[p],
        ));
    }
    o.push_str("</section>");

    o.push_str("<section class=\"major\"><h2>Observational methods and strength</h2><h3>RULA and REBA per phase</h3>");
    o.push_str(&scores_table(a));
    o.push_str("<p class=\"meta\">RULA after McAtamney &amp; Corlett (1993), scored for the arm that scores worse; REBA after Hignett &amp; McAtamney (2000). Scores come from the planned joint angles.</p>");
    o.push_str("<h3>Low back and share of workers strong enough</h3>");
    o.push_str(&back_and_strength_table(a));
    o.push_str("<p class=\"meta\">L5/S1 compression with a single equivalent muscle (Chaffin); NIOSH (1981) action limit 3400 N and maximum permissible limit 6400 N. “Strong enough”: the share of women and of men whose strength at this posture exceeds the torque each muscle group must produce.</p>");
    o.push_str(&lifting_section(task, a));
    o.push_str("</section>");

    o.push_str("<section><h2>Work and rest</h2>");
    o.push_str(&rest_section(plan, a));
    o.push_str("</section>");

    o.push_str("<section><h2>Against simpler ways to choose postures</h2>");
    o.push_str(&baselines_section(plan));
    o.push_str("</section>");

    o.push_str("<section><h2>How much the muscle parameters matter</h2>");
    o.push_str(&uncertainty_section(plan, task, a));
    o.push_str("</section>");

    o.push_str(
        "<section class=\"major\"><h2>Appendix: the model’s parameters per muscle group</h2>",
    );
    o.push_str(&parameters_section(plan, &courses));
    o.push_str("<h3>Optimiser</h3>");
    o.push_str(&optimiser_section(plan));
    o.push_str("</section>");
    Ok(o)
}
