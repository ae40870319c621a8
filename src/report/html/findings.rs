//! The plan's findings in plain words: the verdict, then what an ergonomist checks — the hardest
//! phase and why, capacity, strength, reach, collisions, balance, observational scores, the low
//! back, lifting, rest, the baselines and how much the parameters' uncertainty matters.

use super::analysis::{GroupCourse, PhaseStrain, WorstWhy};
use super::fmt::{Finding, Level, capitalise, dur, esc, mm, num, pct, unit};
use crate::assess::Assessment;
use crate::assess::verdict::Status;
use crate::plan::result::{Exhaustion, PhaseSummary};
use crate::plan::{Plan, Task};

/// A half-joint's muscle group in words.
pub fn group(plan: &Plan, id: &str) -> String {
    plan.half_joint(id)
        .map(|i| plan.half_joints[i].group.clone())
        .unwrap_or_else(|| id.to_string())
}

/// A phase name, quoted and escaped.
pub fn q(name: &str) -> String {
    format!("‘{}’", esc(name))
}

/// What makes a phase impossible, in words (escaped HTML); empty when nothing does.
pub fn phase_problems(p: &PhaseSummary) -> Vec<String> {
    p.problems().iter().map(|x| esc(x)).collect()
}

/// An exhaustion in words (escaped HTML).
pub fn exhaustion_html(e: &Exhaustion) -> String {
    if e.exceeds_strength {
        format!(
            "the {} exceed their strength in {}: the load is {} of their strength (MVC) from the first instant",
            esc(&e.group),
            q(&e.phase),
            pct(e.load)
        )
    } else {
        format!(
            "the {} are exhausted after {} in {} (holding {} of their strength)",
            esc(&e.group),
            dur(e.t_s),
            q(&e.phase),
            pct(e.load)
        )
    }
}

/// The verdict: can the worker do it, and for how long.
pub fn verdict(plan: &Plan, a: &Assessment) -> Finding {
    let s = &plan.summary;
    // the plan's problems (every phase's and the rest posture's), as the text verdict has them
    let problems: Vec<String> = plan.problems().iter().map(|x| esc(x)).collect();
    let m = &a.meaning;
    let left = format!(
        "At the end {} of the {}’ strength is left; the lowest capacity at any time is {} ({}, at {}).",
        pct(m.capacity_left),
        esc(&m.capacity_left_group),
        pct(s.lowest_capacity),
        esc(&group(plan, &s.lowest_capacity_half_joint)),
        dur(s.lowest_capacity_t_s)
    );
    let v = &a.verdict;
    // one verdict, the shift verdict's, in the text, the JSON and here; a plan that gives out
    // says so right after it (the shift verdict counts it in its fatigue criterion)
    if let Some(e) = &s.exhaustion {
        let mut t = format!(
            "{}. As planned, {}.",
            capitalise(&esc(&v.headline)),
            exhaustion_html(e)
        );
        if !problems.is_empty() {
            t.push_str(&format!(" Also: {}.", problems.join("; ")));
        }
        return Finding::new(Level::Bad, t);
    }
    let level = level_of(v.status);
    let head = capitalise(&esc(&v.headline));
    // the fatigue model's own words are in the criteria list; the box adds the capacity figures
    Finding::new(level, format!("{head}. {left}"))
}

/// A criterion's status as a finding's level.
fn level_of(status: Status) -> Level {
    match status {
        Status::NotApplicable | Status::Acceptable => Level::Ok,
        Status::Caution | Status::NotDetermined => Level::Warn,
        Status::Exceeded => Level::Bad,
    }
}

/// The shift criteria one by one, as the verdict weighed them.
pub fn criteria_finding(a: &Assessment) -> Finding {
    let items: Vec<String> = a
        .verdict
        .criteria
        .iter()
        .map(|c| {
            format!(
                "<li><b>{}</b> ({}): {} <small>[{}]</small></li>",
                esc(c.name),
                c.status.words(),
                esc(&c.words),
                esc(c.source)
            )
        })
        .collect();
    Finding::new(
        level_of(a.verdict.status),
        format!(
            "Shift criteria (the verdict is the worst of them; “indefinitely” only when all are acceptable):<ul>{}</ul>",
            items.join("")
        ),
    )
}

/// The findings under the verdict.
pub fn findings(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    strain: &[PhaseStrain],
    courses: &[GroupCourse],
    worst: Option<(usize, WorstWhy)>,
) -> Vec<Finding> {
    let s = &plan.summary;
    let floor = a.rest.capacity_floor;
    let mut f = Vec::new();
    let gname = |h: usize| {
        plan.half_joints
            .get(h)
            .map(|x| esc(&x.group))
            .unwrap_or_default()
    };

    // the hardest phase
    if let Some((p, why)) = worst {
        let ph = &task.phases[p];
        let st = &strain[p];
        let words = a
            .phases
            .get(p)
            .map(|x| x.posture_words.as_str())
            .filter(|w| !w.is_empty())
            .map(|w| format!(" Posture: {}.", esc(w)))
            .unwrap_or_default();
        let loaded = s
            .phases
            .get(p)
            .map(|x| {
                x.most_loaded
                    .iter()
                    .map(|(h, l)| format!("{} {}", esc(&group(plan, h)), pct(*l)))
                    .collect::<Vec<_>>()
                    .join(", ")
            })
            .unwrap_or_default();
        let (level, why_text) = match why {
            WorstWhy::Problem => (
                Level::Bad,
                format!(
                    "the worker cannot do it: {}",
                    s.phases
                        .get(p)
                        .map(phase_problems)
                        .unwrap_or_default()
                        .join("; ")
                ),
            ),
            WorstWhy::Exhaustion => (
                Level::Bad,
                s.exhaustion
                    .as_ref()
                    .map(exhaustion_html)
                    .unwrap_or_default(),
            ),
            WorstWhy::Hazard => (Level::Bad, esc(&super::analysis::hazards(a, p).join("; "))),
            WorstWhy::Limiting(h) => {
                let f = st.loads.get(h).copied().unwrap_or(f64::NAN);
                let share = super::analysis::params(plan)
                    .get(h)
                    .copied()
                    .flatten()
                    .and_then(|q| q.met_min(f))
                    .map_or(0.0, |m| ph.duration_s / (60.0 * m).max(1e-9));
                (
                    if s.lowest_capacity < floor {
                        Level::Warn
                    } else {
                        Level::Info
                    },
                    format!(
                        "the {}, whose capacity falls lowest ({}), hold {} of their strength here, {} per cycle ({} of a rested muscle’s endurance each time)",
                        gname(h),
                        pct(s.lowest_capacity),
                        pct(f),
                        dur(ph.duration_s),
                        pct(share)
                    ),
                )
            }
            WorstWhy::Endurance => (
                if st.endurance_share >= 1.0 {
                    Level::Bad
                } else if st.endurance_share >= 0.5 {
                    Level::Warn
                } else {
                    Level::Info
                },
                format!(
                    "each {} hold uses {} of a rested muscle’s endurance — the {} at {} of their strength",
                    dur(ph.duration_s),
                    pct(st.endurance_share),
                    st.share_group.map(gname).unwrap_or_default(),
                    pct(st
                        .share_group
                        .and_then(|h| st.loads.get(h).copied())
                        .unwrap_or(f64::NAN))
                ),
            ),
            WorstWhy::Load | WorstWhy::Compared => (
                Level::Info,
                format!(
                    "the highest load: the {} at {} of their strength",
                    st.max_group.map(gname).unwrap_or_default(),
                    pct(st.max_load)
                ),
            ),
        };
        // every criterion that makes it the worst, not only the first
        let also = super::analysis::hazards(a, p);
        let why_text = if why == WorstWhy::Hazard || also.is_empty() {
            why_text
        } else {
            format!("{why_text}; also {}", esc(&also.join("; ")))
        };
        f.push(
            Finding::new(
                level,
                format!(
                    "<b>Hardest phase: {}</b> — {}. Most loaded: {}.{}",
                    q(&ph.name),
                    why_text,
                    if loaded.is_empty() {
                        "—".into()
                    } else {
                        loaded
                    },
                    words
                ),
            )
            .pinned(),
        );
    }

    // capacity
    if s.exhaustion.is_none() {
        let lowest = s.lowest_capacity;
        let below: Vec<String> = courses
            .iter()
            .filter(|c| c.lowest < floor)
            .take(4)
            .map(|c| format!("{} {}", gname(c.h), pct(c.lowest)))
            .collect();
        f.push(Finding::new(
            if lowest < floor { Level::Warn } else { Level::Ok },
            if below.is_empty() {
                format!(
                    "Every muscle group keeps at least {} of its strength at all times, above the capacity floor of {}.",
                    pct(lowest),
                    pct(floor)
                )
            } else {
                {
                    let more = courses.iter().filter(|c| c.lowest < floor).count().saturating_sub(below.len());
                    format!(
                        "Capacity falls below the floor of {}: {}{}.",
                        pct(floor),
                        below.join(", "),
                        if more > 0 { format!(" and {more} more groups") } else { String::new() }
                    )
                }
            },
        ));
    }

    // strength
    {
        let (men, women) = (a.capable_men, a.capable_women);
        let least = a
            .phases
            .iter()
            .flat_map(|p| p.capable.iter().map(move |c| (c, &p.phase)))
            .min_by(|x, y| x.0.women.min(x.0.men).total_cmp(&y.0.women.min(y.0.men)));
        // graded as the shift verdict grades it (NIOSH 1981's design limits)
        let level = a
            .verdict
            .criterion("strength")
            .map_or(Level::Ok, |c| level_of(c.status));
        f.push(Finding::new(
            level,
            format!(
                "Strong enough for every load of the task: {} of women, {} of men (the design limit: 99 % of men and 75 % of women){}.",
                pct(women),
                pct(men),
                least
                    .map(|(c, ph)| format!(
                        " (the limit: the {} must produce {} in {})",
                        esc(&c.group),
                        unit(c.required_nm, 0, "N·m"),
                        q(ph)
                    ))
                    .unwrap_or_default()
            ),
        ));
    }

    // acceptable posture zones
    {
        let outside: Vec<String> = s
            .phases
            .iter()
            .filter(|p| !p.outside_zones.is_empty())
            .map(|p| {
                let z: Vec<String> = p
                    .outside_zones
                    .iter()
                    .map(|z| {
                        format!(
                            "{} {:.0}° (at most {:.0}°, {})",
                            esc(&z.what),
                            z.angle_deg,
                            z.limit_deg,
                            esc(&z.source)
                        )
                    })
                    .collect();
                format!("{}: {}", q(&p.phase), z.join("; "))
            })
            .collect();
        let text = if outside.is_empty() {
            "Every posture is within the angles the planner keeps (ISO 11226 and EN 1005-4's limits for the trunk, upper arms, head and neck held in each phase, and RULA's and REBA's wrist zones); how often and how long they are held is judged in the shift criteria.".to_string()
        } else if s.zones {
            format!(
                "Outside the acceptable zones of ISO 11226 / EN 1005-4 where the targets force it (the plan keeps the zones elsewhere and makes each excess the least the search found): {}. Moving these targets is the layout change that removes them.",
                outside.join("; ")
            )
        } else {
            format!(
                "Outside the acceptable zones of ISO 11226 / EN 1005-4 (planned without them, --no-zones): {}.",
                outside.join("; ")
            )
        };
        f.push(Finding::new(
            if outside.is_empty() {
                Level::Ok
            } else {
                Level::Warn
            },
            text,
        ));
    }

    // reach, collisions, balance
    let unreachable: Vec<&PhaseSummary> = s.phases.iter().filter(|p| !p.reachable).collect();
    if unreachable.is_empty() {
        let worst_err = s.phases.iter().map(|p| p.hand_error_m).fold(0.0, f64::max);
        f.push(Finding::new(
            Level::Ok,
            format!(
                "Every hand target is reached (largest hand error {}).",
                mm(worst_err)
            ),
        ));
    } else {
        for p in unreachable {
            f.push(Finding::new(
                Level::Bad,
                format!("{}.", capitalise(&phase_problems(p)[0])),
            ));
        }
    }
    let collide: Vec<&PhaseSummary> = s
        .phases
        .iter()
        .filter(|p| p.min_clearance_m < 0.0)
        .collect();
    if collide.is_empty() {
        if let Some(p) = s
            .phases
            .iter()
            .min_by(|a, b| a.min_clearance_m.total_cmp(&b.min_clearance_m))
        {
            let tight = p.min_clearance_m < task.objective.clearance_m - 5e-4;
            f.push(Finding::new(
                if tight { Level::Warn } else { Level::Ok },
                format!(
                    "No collision: the smallest clearance is {} in {}{}.",
                    mm(p.min_clearance_m),
                    q(&p.phase),
                    p.closest
                        .as_deref()
                        .map(|c| format!(" ({})", esc(c)))
                        .unwrap_or_default()
                ),
            ));
        }
    } else {
        for p in collide {
            f.push(Finding::new(
                Level::Bad,
                format!(
                    "Collision in {}: {} into {}.",
                    q(&p.phase),
                    mm(-p.min_clearance_m),
                    esc(p.closest.as_deref().unwrap_or("an obstacle"))
                ),
            ));
        }
    }
    let margins: Vec<(&PhaseSummary, f64)> = s
        .phases
        .iter()
        .filter_map(|p| p.balance_margin_m.map(|m| (p, m)))
        .collect();
    if let Some((p, m)) = margins.iter().min_by(|a, b| a.1.total_cmp(&b.1)) {
        f.push(if *m < 0.0 {
            Finding::new(
                Level::Bad,
                format!(
                    "Off balance in {}: the centre of pressure is {} outside {}.",
                    q(&p.phase),
                    mm(-m),
                    task.supports()
                ),
            )
        } else {
            Finding::new(
                if *m < task.objective.balance_margin_m - 5e-4 { Level::Warn } else { Level::Ok },
                format!(
                    "Balance is kept in every phase: the centre of pressure stays at least {} inside {} (least in {}).",
                    mm(*m),
                    task.supports(),
                    q(&p.phase)
                ),
            )
        });
    }

    // observational scores
    if let Some((p, r)) = a
        .phases
        .iter()
        .filter_map(|p| p.rula.as_ref().map(|r| (p, r)))
        .fold(
            None,
            |b: Option<(
                &crate::assess::phase::PhaseAssessment,
                &crate::assess::rula::Rula,
            )>,
             x| match b {
                Some(y) if y.1.grand_score >= x.1.grand_score => Some(y),
                _ => Some(x),
            },
        )
    {
        let reba = a
            .phases
            .iter()
            .filter_map(|p| p.reba.as_ref().map(|r| (p, r)))
            .fold(
                None,
                |b: Option<(
                    &crate::assess::phase::PhaseAssessment,
                    &crate::assess::reba::Reba,
                )>,
                 x| match b {
                    Some(y) if y.1.reba_score >= x.1.reba_score => Some(y),
                    _ => Some(x),
                },
            );
        let level = match (r.grand_score, reba.map(|x| x.1.reba_score)) {
            (7.., _) | (_, Some(11..)) => Level::Bad,
            (5..=6, _) | (_, Some(8..=10)) => Level::Warn,
            (3..=4, _) | (_, Some(4..=7)) => Level::Info,
            _ => Level::Ok,
        };
        f.push(Finding::new(
            level,
            format!(
                "RULA up to {} in {} (action level {}: {}){}.",
                r.grand_score,
                q(&p.phase),
                r.action_level,
                esc(r.action),
                reba.map(|(rp, rb)| format!(
                    "; REBA up to {} in {} ({} risk: {})",
                    rb.reba_score,
                    q(&rp.phase),
                    rb.risk.level.label(),
                    esc(rb.risk.action)
                ))
                .unwrap_or_default()
            ),
        ));
    }

    // low back
    if let (Some(c), Some(ph)) = (a.back_compression_max_n, &a.back_compression_phase) {
        let limits = a
            .phases
            .iter()
            .find_map(|p| {
                p.low_back.as_ref().map(|b| {
                    (
                        b.params.compression_action_limit_n,
                        b.params.compression_max_limit_n,
                    )
                })
            })
            .unwrap_or((3400.0, 6400.0));
        let level = if c > limits.1 {
            Level::Bad
        } else if c > limits.0 {
            Level::Warn
        } else {
            Level::Ok
        };
        f.push(Finding::new(
            level,
            format!(
                "L5/S1 compression up to {} in {}: {} the {} action limit ({} maximum permissible limit, NIOSH 1981).",
                unit(c, 0, "N"),
                q(ph),
                if c > limits.1 {
                    "above the maximum permissible limit and"
                } else if c > limits.0 {
                    "above"
                } else {
                    "below"
                },
                unit(limits.0, 0, "N"),
                unit(limits.1, 0, "N")
            ),
        ));
    }

    // lifting
    match &a.lifting {
        Some(Ok(l)) => {
            for r in &l.lifts {
                let li = r.lifting_index;
                f.push(Finding::new(
                    match li {
                        // as the shift verdict's lifting-index criterion: redesign above 1
                        Some(x) if x > 1.0 => Level::Bad,
                        Some(_) => Level::Ok,
                        None => Level::Bad,
                    },
                    match li {
                        Some(x) => format!(
                            "NIOSH lift {}: lifting index {} (load {} against a recommended weight limit of {}){}.",
                            q(&r.name),
                            num(x, 2),
                            unit(r.load_kg, 1, "kg"),
                            unit(r.rwl_kg, 1, "kg"),
                            if x > 3.0 {
                                " — most workers are at increased risk"
                            } else if x > 1.0 {
                                " — some workers are at increased risk; redesign the lift"
                            } else {
                                ""
                            }
                        ),
                        None => format!(
                            "NIOSH lift {}: outside the equation’s limits, no load is recommended (RWL 0).",
                            q(&r.name)
                        ),
                    },
                ));
            }
            if let Some(c) = l.composite.as_ref().and_then(|c| c.cli) {
                f.push(Finding::new(
                    if c > 1.0 { Level::Bad } else { Level::Ok },
                    format!("NIOSH composite lifting index {}.", num(c, 2)),
                ));
            }
        }
        Some(Err(e)) => f.push(Finding::new(
            Level::Info,
            format!(
                "The NIOSH lifting equation could not be applied: {}.",
                esc(e)
            ),
        )),
        None => {}
    }

    // rest
    let r = &a.rest;
    f.push(match r.model.rest_s_per_cycle {
        Some(x) if x <= r.current_rest_s + 1e-9 => Finding::new(
            Level::Ok,
            format!(
                "Rest: the {} of rest per cycle are enough to keep every capacity at or above {} (the model needs {}).",
                dur(r.current_rest_s),
                pct(r.capacity_floor),
                dur(x)
            ),
        ),
        Some(x) => Finding::new(
            Level::Warn,
            format!(
                "Rest: {} per cycle would keep every capacity at or above {}; the task gives {}.",
                dur(x),
                pct(r.capacity_floor),
                dur(r.current_rest_s)
            ),
        ),
        None => Finding::new(Level::Warn, format!("Rest: {}.", esc(&r.model.note))),
    });

    // baselines
    for b in &s.baselines {
        let name = esc(&b.name.replace('_', " "));
        let text = match (&b.exhaustion, &s.exhaustion) {
            (Some(be), None) => (
                Level::Ok,
                format!(
                    "Against the {name} plan ({}): that plan cannot be done — {}; posture-opt’s plan lasts the whole task.",
                    esc(&b.description),
                    exhaustion_html(be)
                ),
            ),
            (Some(be), Some(e)) => (
                if be.t_s < e.t_s {
                    Level::Info
                } else {
                    Level::Warn
                },
                format!(
                    "Against the {name} plan ({}): it fails too — {}; posture-opt’s plan lasts {}.",
                    esc(&b.description),
                    exhaustion_html(be),
                    dur(e.t_s)
                ),
            ),
            (None, Some(_)) => (
                Level::Warn,
                format!(
                    "Against the {name} plan ({}): that plan lasts the whole task, posture-opt’s does not.",
                    esc(&b.description)
                ),
            ),
            (None, None) => (
                if b.change <= -0.005 {
                    Level::Ok
                } else {
                    Level::Info
                },
                format!(
                    "Against the {name} plan ({}): posture-opt’s postures {} (total fatigue index U {} against {} min).",
                    esc(&b.description),
                    if b.change.abs() < 0.005 {
                        "cause about the same fatigue".to_string()
                    } else if b.change < 0.0 {
                        format!("cause {} less fatigue", pct(-b.change))
                    } else {
                        format!("cause {} more fatigue", pct(b.change))
                    },
                    num(s.total_u, 1),
                    num(b.total_u, 1)
                ),
            ),
        };
        f.push(Finding::new(text.0, text.1));
    }

    // uncertainty
    if let Some(u) = &a.uncertainty {
        let n = u.outcomes.len();
        let lo = u
            .outcomes
            .iter()
            .map(|o| o.lowest_capacity)
            .fold(f64::INFINITY, f64::min);
        let hi = u
            .outcomes
            .iter()
            .map(|o| o.lowest_capacity)
            .fold(f64::NEG_INFINITY, f64::max);
        let exhausted: Vec<String> = u
            .outcomes
            .iter()
            .filter(|o| o.exhausted_in_task)
            .map(|o| esc(o.variant))
            .collect();
        let level = if exhausted.is_empty() {
            Level::Ok
        } else if s.exhaustion.is_some() {
            Level::Info
        } else {
            Level::Warn
        };
        f.push(Finding::new(
            level,
            format!(
                "Uncertainty of the muscle parameters ({} variants of {}): a group is exhausted within the task in {} of {}{}; the lowest capacity ranges from {} to {}.",
                n,
                esc(&u.parameter_set),
                exhausted.len(),
                n,
                if exhausted.is_empty() { String::new() } else { format!(" ({})", exhausted.join(", ")) },
                pct(lo),
                pct(hi)
            ),
        ));
    }

    // the optimiser
    let not_conv: Vec<&PhaseSummary> = s.phases.iter().filter(|p| !p.converged).collect();
    if !not_conv.is_empty() {
        let worst = not_conv.iter().map(|p| p.kkt_residual).fold(0.0, f64::max);
        f.push(Finding::new(
            Level::Info,
            format!(
                "The optimiser stopped before its convergence test was met in {} of {} phases (KKT residual up to {}): those postures are feasible but may not be the best.",
                not_conv.len(),
                s.phases.len(),
                if worst.is_finite() { format!("{worst:.1e}") } else { "—".into() }
            ),
        ));
    }
    f
}

/// " (and 'bench top', which it rests on, with 'parts bin')", or nothing.
fn surface_words(surfaces: &[String]) -> String {
    match surfaces {
        [] => String::new(),
        [support] => format!(" (and {}, which it rests on)", q(support)),
        [support, more @ ..] => format!(
            " (and {}, which it rests on, with {})",
            q(support),
            more.iter().map(|m| q(m)).collect::<Vec<_>>().join(", ")
        ),
    }
}

/// A what-if's change in words, for a sentence that goes on "would …" or with a comma.
fn change_words(c: &crate::study::what_if::Change) -> String {
    use crate::study::what_if::Change;
    match c {
        Change::MoveWork {
            phase,
            dz_m,
            elbow_height_m,
            seated,
            surfaces,
        } => format!(
            "placing the work of {}{} {} {}, toward this worker’s {}elbow height ({})",
            q(phase),
            surface_words(surfaces),
            mm(dz_m.abs()),
            if *dz_m > 0.0 { "up" } else { "down" },
            if *seated { "seated " } else { "" },
            super::fmt::unit(*elbow_height_m, 2, "m")
        ),
        Change::BringWorkCloser {
            phase,
            dx_m,
            dy_m,
            beyond_m,
            surfaces,
            short_of_feet,
        } => format!(
            "placing the work of {}{} {} closer, toward the normal working area in front of the worker (the hand's sweep with the elbow at the side, centred {} from the work{})",
            q(phase),
            surface_words(surfaces),
            mm(dx_m.hypot(*dy_m)),
            mm(*beyond_m),
            if *short_of_feet {
                format!(
                    "; as far as leaves {} between {} and the feet",
                    mm(crate::study::what_if::FEET_ROOM_M),
                    surfaces.first().map_or("the work".to_string(), |n| q(n))
                )
            } else {
                String::new()
            }
        ),
        Change::MoveGaze { phase, dz_m } => format!(
            "placing what {} looks at {} {}, where the normal line of sight ({}° below the horizontal, MIL-STD-1472) meets it",
            q(phase),
            mm(dz_m.abs()),
            if *dz_m > 0.0 { "higher" } else { "lower" },
            crate::plan::task::LINE_OF_SIGHT_BELOW_DEG
        ),
        Change::StandingArea { half_side_m } => format!(
            "letting the worker step and turn within {} × {} of floor around the stance (the task fixes the feet)",
            super::fmt::unit(2.0 * half_side_m, 1, "m"),
            super::fmt::unit(2.0 * half_side_m, 1, "m")
        ),
    }
}

/// The verdict's recommendation from the advised what-if ([`crate::study::what_if::advice`]):
/// "Letting the worker step … would lower fatigue per hour by 59 % (142.6 → 58.6 min/h)", or
/// "… would keep every muscle group from giving out" when it ends an exhaustion.
pub fn advice_sentence(w: &crate::study::what_if::WhatIf) -> String {
    let lifting = crate::study::what_if::lifting_change(
        w.before.lifting().as_ref(),
        w.after.lifting().as_ref(),
    );
    if w.lowers_lifting_risk() {
        use crate::assess::lifting::index_words;
        return format!(
            "<b>{} would bring NIOSH's lifting index from {} to {}</b> (fatigue per hour {:.1} → {:.1} min/h; see “What would change it”).",
            capitalise(&change_words(&w.change)),
            esc(&index_words(w.before.lifting().as_ref())),
            esc(&index_words(w.after.lifting().as_ref())),
            w.before.u_per_hour_min,
            w.after.u_per_hour_min
        );
    }
    let lifting = lifting.map_or(String::new(), |l| format!("; {}", esc(&l.words)));
    if w.eases_postures() {
        return format!(
            "<b>{} would bring the postures beyond ISO 11226 / EN 1005-4's acceptable zones from {:.0}° to {:.0}°</b> (summed over the phases; fatigue per hour {:.1} → {:.1} min/h{lifting}; see “What would change it”).",
            capitalise(&change_words(&w.change)),
            w.before.zone_excess_deg,
            w.after.zone_excess_deg,
            w.before.u_per_hour_min,
            w.after.u_per_hour_min
        );
    }
    if w.ends_exhaustion() {
        return format!(
            "<b>{} would keep every muscle group from giving out</b> (fatigue per hour {:.1} → {:.1} min/h, the first until a group gives out{lifting}; see “What would change it”).",
            capitalise(&change_words(&w.change)),
            w.before.u_per_hour_min,
            w.after.u_per_hour_min
        );
    }
    format!(
        "<b>{} would lower fatigue per hour by {:.0} %</b> ({:.1} → {:.1} min/h{lifting}; see “What would change it”).",
        capitalise(&change_words(&w.change)),
        100.0 * (1.0 - w.after.u_per_hour_min / w.before.u_per_hour_min),
        w.before.u_per_hour_min,
        w.after.u_per_hour_min
    )
}

/// "What would change it", from a what-if plan the tool ran.
pub fn what_if_finding(w: &crate::study::what_if::WhatIf) -> Finding {
    let change = format!("{}, ", change_words(&w.change));
    let head =
        format!("<b>What would change it</b> (the task planned again by posture-opt): {change}");
    let text = if w.problems.is_empty() {
        let mut t = format!("changes {}", w.before.changes_to(&w.after).join("; "));
        if !w.not_converged.is_empty() {
            let names: Vec<String> = w.not_converged.iter().map(|p| format!("'{p}'")).collect();
            t += &format!(
                " (the optimiser stopped short of convergence on {} of the changed plan: these are the figures of the plan it stopped at, and a finished plan may do better)",
                names.join(", ")
            );
        }
        t
    } else {
        // the planner's failure to find a clean plan, not proof that the change cannot work
        format!(
            "not assessed: the plan posture-opt found for it is not one to act on ({}), so its figures are not given",
            w.problems.join("; ")
        )
    };
    // next to the hardest phase, which it would change (the verdict points to it)
    Finding::new(Level::Info, format!("{head}{}.", esc(&text))).pinned()
}
