//! The comparison report: layouts side by side in ranked order, their verdicts and problems,
//! how robust the ranking is to the muscle parameters, and each layout's hardest phase drawn.

use super::ReportError;
use super::analysis::{WorstWhy, group_courses, phase_strain, worst_phase};
use super::body_view::{self, Scene, View};
use super::findings::q;
use super::fmt::{
    DASH, Finding, Level, Table, dur, esc, findings_list, kv_table, mm, num, opt, pct, share, unit,
};
use super::plan_page::worker_line;
use crate::plan::Task;
use crate::study::compare::{Comparison, LayoutOutcome, Planned, verdict};
use std::fmt::Write;

/// Layouts drawn at most (the table lists them all).
const MAX_DRAWN: usize = 12;

/// A layout's colour: its shift verdict's, or worse if it cannot be done or tires out (a layout
/// not acceptable over the shift is never shown as fine, however well its muscles hold out).
fn level(o: &LayoutOutcome) -> Level {
    use crate::assess::verdict::Status;
    if !o.feasible || o.exhaustion.is_some() || o.shift_status == Status::Exceeded {
        Level::Bad
    } else if o.minutes_to_exhaustion.is_some()
        || matches!(o.shift_status, Status::Caution | Status::NotDetermined)
    {
        Level::Warn
    } else {
        Level::Ok
    }
}

fn robust_level(wins: usize, of: usize) -> Level {
    if wins == of {
        Level::Ok
    } else if 2 * wins > of {
        Level::Info
    } else {
        Level::Warn
    }
}

/// The comparison's findings with a level each (they follow `Comparison::findings`' order: the
/// best layout; for every other layout its verdict and what choosing the best instead changes;
/// the robustness lines; then a closing remark).
fn findings_html(c: &Comparison) -> Vec<Finding> {
    let n = c.layouts.len();
    let r = c.robustness.len();
    let per_layout = 1 + 2 * n.saturating_sub(1);
    c.findings
        .iter()
        .enumerate()
        .map(|(i, text)| {
            let lv = if c.findings.len() >= per_layout + r {
                if i == 0 {
                    level(&c.layouts[0])
                } else if i < per_layout {
                    if (i - 1) % 2 == 0 {
                        level(&c.layouts[1 + (i - 1) / 2])
                    } else {
                        Level::Info
                    }
                } else if i < per_layout + r {
                    let x = &c.robustness[i - per_layout];
                    robust_level(x.wins, x.variants)
                } else {
                    Level::Bad
                }
            } else {
                Level::Info
            };
            // capitalised unless it starts with a file name
            let first = text.split_whitespace().next().unwrap_or("");
            let text = if first.contains('/') || first.contains('.') {
                text.clone()
            } else {
                super::fmt::capitalise(text)
            };
            Finding::new(lv, esc(&text))
        })
        .chain(other_measures(c))
        .collect()
}

/// Where another layout is better than the best one by measures the ranking does not weigh
/// first (strength, low back, observational scores).
fn other_measures(c: &Comparison) -> Vec<Finding> {
    let Some(best) = c.layouts.first() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for o in &c.layouts[1..] {
        let mut better = Vec::new();
        if o.capable_women > best.capable_women + 0.05 {
            better.push(format!(
                "strong enough for {} of women (against {})",
                share(o.capable_women),
                share(best.capable_women)
            ));
        }
        if o.capable_men > best.capable_men + 0.05 {
            better.push(format!(
                "strong enough for {} of men (against {})",
                share(o.capable_men),
                share(best.capable_men)
            ));
        }
        if let (Some(x), Some(y)) = (o.back_compression_max_n, best.back_compression_max_n)
            && (x < y - 150.0 || (x <= 3400.0 && y > 3400.0))
        {
            better.push(format!(
                "L5/S1 compression up to {} (against {})",
                unit(x, 0, "N"),
                unit(y, 0, "N")
            ));
        }
        if let (Some(x), Some(y)) = (o.rula_max, best.rula_max)
            && x < y
        {
            better.push(format!("RULA up to {x} (against {y})"));
        }
        if let (Some(x), Some(y)) = (o.reba_max, best.reba_max)
            && x < y
        {
            better.push(format!("REBA up to {x} (against {y})"));
        }
        if !better.is_empty() {
            out.push(Finding::new(
                Level::Warn,
                format!(
                    "By other measures {} is better than {}: {}; {} ranks first on {}.",
                    esc(&o.file),
                    esc(&best.file),
                    better.join("; "),
                    esc(&best.file),
                    esc(&crate::study::compare::decisive(best, o))
                ),
            ));
        }
    }
    out
}

fn ranking_tables(c: &Comparison) -> String {
    let mut t = Table::new(
        "ranking",
        &[
            "rank",
            "layout",
            "verdict",
            "NIOSH lifting index",
            "postures (ISO 11226 / EN 1005-4)",
            "lowest capacity at any time",
            "time to exhaustion at this pace",
            "endurance used per hold",
        ],
    )
    .numeric(&[0]);
    for o in &c.layouts {
        t.row(
            Some(level(o)),
            vec![
                o.rank.to_string(),
                format!("<b>{}</b><br><small>{}</small>", esc(&o.task), esc(&o.file)),
                esc(&verdict(o)),
                match o.lifting() {
                    None => "—".into(),
                    Some(Ok(x)) => num(x, 2),
                    Some(Err(why)) => format!(
                        "not defined<br><small>{}</small>",
                        esc(&format!("outside the equation's limits: {why}"))
                    ),
                },
                esc(o.posture_status.words()),
                format!(
                    "{} ({}, at {})",
                    pct(o.lowest_capacity),
                    esc(&o.lowest_capacity_group),
                    dur(o.lowest_capacity_t_s)
                ),
                o.minutes_to_exhaustion.map_or_else(
                    || {
                        crate::assess::meaning::no_exhaustion_words(
                            &o.exhaustion_verdict,
                            o.minutes_followed,
                        )
                    },
                    |m| dur(60.0 * m),
                ),
                pct(o.endurance_share),
            ],
        );
    }
    let mut u = Table::new(
        "measures",
        &[
            "rank",
            "layout",
            "RULA",
            "REBA",
            "L5/S1 compression",
            "strong enough (women / men)",
            "smallest clearance",
            "balance margin",
            "rest needed / given",
            "U per hour",
        ],
    )
    .numeric(&[0, 2, 3, 4, 7, 9]);
    for o in &c.layouts {
        u.row(
            None,
            vec![
                o.rank.to_string(),
                esc(&o.file),
                opt(o.rula_max, |x| x.to_string()),
                opt(o.reba_max, |x| x.to_string()),
                opt(o.back_compression_max_n, |x| {
                    if x > 3400.0 {
                        format!("<span class=\"warn-text\">{}</span>", unit(x, 0, "N"))
                    } else {
                        unit(x, 0, "N")
                    }
                }),
                format!("{} / {}", share(o.capable_women), share(o.capable_men)),
                format!(
                    "{}{}",
                    mm(o.min_clearance_m),
                    o.closest
                        .as_deref()
                        .map(|x| format!(" <small>({})</small>", esc(x)))
                        .unwrap_or_default()
                ),
                opt(o.min_balance_margin_m, mm),
                format!(
                    "{} / {}",
                    o.rest_needed_s
                        .map_or_else(|| "rest cannot help".to_string(), dur),
                    dur(o.current_rest_s)
                ),
                unit(o.u_per_hour_min, 1, "min/h"),
            ],
        );
    }
    format!(
        "{}<p class=\"meta\">Ranking: {}.</p><h3>Other measures</h3>{}<p class=\"meta\">Rest needed keeps every capacity at or above {}. U per hour: the fatigue index summed over the muscle groups per hour of simulated work (a layout that stops at an exhaustion is simulated for less time).</p>",
        t.render(),
        esc(&c.ranking_rule),
        u.render(),
        pct(c.capacity_floor)
    )
}

fn robustness_section(c: &Comparison) -> String {
    let Some(best) = c.layouts.first() else {
        return String::new();
    };
    if c.robustness.is_empty() {
        return "<p>The layouts do not use a named parameter set with ranges: no robustness analysis.</p>".into();
    }
    let mut t = Table::new(
        "robust",
        &["", "parameter variants in which it ranks above", "share"],
    )
    .numeric(&[2]);
    for r in &c.robustness {
        let share = if r.variants > 0 {
            r.wins as f64 / r.variants as f64
        } else {
            f64::NAN
        };
        t.row(
            Some(robust_level(r.wins, r.variants)),
            vec![
                format!("{} above {}", esc(&best.file), esc(&r.other)),
                format!(
                    "{} of {} <span class=\"bar\"><span style=\"width:{}%\"></span></span>",
                    r.wins,
                    r.variants,
                    num((100.0 * share).clamp(0.0, 100.0), 0).replace(DASH, "0")
                ),
                pct(share),
            ],
        );
    }
    let mut o = t.render();
    // variants × layouts
    let n_var = c
        .layouts
        .iter()
        .map(|l| l.variants.len())
        .min()
        .unwrap_or(0);
    if n_var > 0 && c.layouts.len() <= 6 {
        let mut head: Vec<String> = vec!["parameter variant".into()];
        head.extend(c.layouts.iter().map(|l| format!("#{} {}", l.rank, l.file)));
        let head_ref: Vec<&str> = head.iter().map(String::as_str).collect();
        let mut v = Table::new("variants", &head_ref);
        for i in 0..n_var {
            let mut row = vec![esc(&c.layouts[0].variants[i].variant)];
            for l in &c.layouts {
                let f = &l.variants[i];
                row.push(if f.exhausted_in_task {
                    format!(
                        "<span class=\"bad-text\">exhausted</span>, lowest {}",
                        pct(f.lowest_capacity)
                    )
                } else {
                    format!(
                        "lowest {}{}",
                        pct(f.lowest_capacity),
                        f.minutes_to_exhaustion
                            .map(|m| format!(", gives out after {}", dur(60.0 * m)))
                            .unwrap_or_default()
                    )
                });
            }
            v.row(None, row);
        }
        o.push_str("<h3>Each layout under each parameter variant</h3>");
        o.push_str(&v.render());
    }
    o
}

/// One layout's card: verdict, problems, numbers and its hardest phase drawn.
fn card(
    o: &LayoutOutcome,
    task: &Task,
    p: &Planned,
    frame: Option<(&Scene, &body_view::Frame, usize, WorstWhy)>,
) -> String {
    let lv = level(o);
    let mut s = String::new();
    let _ = write!(
        s,
        "<div class=\"card {}\"><h3>#{} {} <span class=\"meta\">— {}</span></h3><p>{} {}</p>",
        lv.class(),
        o.rank,
        esc(&o.task),
        esc(&o.file),
        super::fmt::badge(lv),
        esc(&verdict(o))
    );
    if !o.problems.is_empty() {
        s.push_str("<ul class=\"problems\">");
        for pr in &o.problems {
            let _ = write!(s, "<li>{}</li>", esc(pr));
        }
        s.push_str("</ul>");
    }
    let m = &p.assessment.meaning;
    s.push_str(&kv_table(&[
        ("worker", worker_line(task)),
        (
            "lowest capacity at any time",
            format!(
                "{} ({}, at {})",
                pct(o.lowest_capacity),
                esc(&o.lowest_capacity_group),
                dur(o.lowest_capacity_t_s)
            ),
        ),
        (
            "capacity left at the end",
            format!("{} ({})", pct(m.capacity_left), esc(&m.capacity_left_group)),
        ),
        (
            "time to exhaustion at this pace",
            match (o.minutes_to_exhaustion, &m.first_to_give_out) {
                (Some(x), Some(g)) => format!("{} (the {})", dur(60.0 * x), esc(g)),
                (Some(x), None) => dur(60.0 * x),
                _ if o.exhaustion_verdict == "not_determined" => {
                    crate::assess::meaning::no_exhaustion_words(
                        &o.exhaustion_verdict,
                        o.minutes_followed,
                    )
                }
                _ => "never: every group settles above its loads".into(),
            },
        ),
        (
            "endurance used per hold",
            format!(
                "{} ({} in {})",
                pct(m.endurance_share),
                esc(&m.endurance_group),
                q(&m.endurance_phase)
            ),
        ),
    ]));
    if let Some((scene, fr, ph, why)) = frame {
        let name = task.phases.get(ph).map(|x| x.name.as_str()).unwrap_or("");
        let hazards = esc(&super::analysis::hazards(&p.assessment, ph).join("; "));
        let why = match why {
            WorstWhy::Problem => "the worker cannot do it",
            WorstWhy::Exhaustion => "a muscle group gives out",
            WorstWhy::Hazard => hazards.as_str(),
            WorstWhy::Compared => "the hardest phase of the lowest-ranked layout, for comparison",
            WorstWhy::Limiting(_) => "the muscle group that falls lowest is loaded most",
            WorstWhy::Endurance => "the most endurance used per hold",
            WorstWhy::Load => "the highest load",
        };
        let words = p
            .assessment
            .phases
            .get(ph)
            .map(|x| x.posture_words.as_str())
            .filter(|w| !w.is_empty())
            .map(|w| format!(" Posture: {}.", esc(w)))
            .unwrap_or_default();
        let _ = write!(
            s,
            "<p><b>Hardest phase: {}</b> ({why}).{words}</p>",
            q(name)
        );
        s.push_str(&body_view::views_html(
            task,
            scene,
            fr,
            &format!("#{} {}", o.rank, name),
        ));
    }
    // what an ergonomist hands on with each layout: its phases and the model's parameters
    let strain = phase_strain(task, &p.plan);
    let courses = group_courses(task, &p.plan, &strain);
    let _ = write!(
        s,
        "<details open><summary>Phases of one cycle</summary>{}</details><details><summary>The fatigue model's parameters per muscle group, with sources</summary>{}</details>",
        super::plan_page::phase_table(task, Some(&p.assessment)),
        super::plan_page::parameters_section(&p.plan, &courses)
    );
    s.push_str("</div>");
    s
}

/// The comparison report's body.
pub fn body(c: &Comparison, tasks: &[&Task], planned: &[Planned]) -> Result<String, ReportError> {
    let n = c.layouts.len().min(tasks.len()).min(planned.len());
    // each drawn layout's hardest phase, at one shared scale
    let mut drawn: Vec<Option<(Scene, body_view::Frame, usize, WorstWhy)>> = Vec::with_capacity(n);
    let focus: Option<String> = planned.len().checked_sub(1).and_then(|last| {
        let (task, plan) = (tasks[last], &planned[last].plan);
        let strain = phase_strain(task, plan);
        worst_phase(task, plan, &planned[last].assessment, &strain)
            .map(|(p, _)| task.phases[p].name.clone())
    });
    for i in 0..n {
        if i >= MAX_DRAWN {
            drawn.push(None);
            continue;
        }
        let (task, plan) = (tasks[i], &planned[i].plan);
        let strain = phase_strain(task, plan);
        // every layout shows the same phase when it can: the hardest phase of the lowest-ranked
        // layout, where the layouts differ most
        let own = worst_phase(task, plan, &planned[i].assessment, &strain);
        let same = focus.as_ref().and_then(|name| {
            task.phases
                .iter()
                .position(|p| &p.name == name)
                .map(|p| match own {
                    Some((q, why)) if q == p => (p, why),
                    _ => (p, WorstWhy::Compared),
                })
        });
        match same.or(own) {
            Some((p, why)) if p < plan.summary.phases.len() => {
                let sc = body_view::scene(task, &plan.summary.phases[p].q_rad, Some(p))?;
                let fr = body_view::frame(
                    task,
                    &[&sc],
                    &[View::Side, View::Front, View::Top],
                    1000.0,
                    420.0,
                );
                drawn.push(Some((sc, fr, p, why)));
            }
            _ => drawn.push(None),
        }
    }
    let scale = drawn
        .iter()
        .flatten()
        .map(|d| d.1.scale())
        .fold(f64::INFINITY, f64::min);
    for d in drawn.iter_mut().flatten() {
        d.1.set_scale(scale);
    }

    let mut o = String::new();
    let _ = write!(
        o,
        "<header><h1>Layout comparison</h1><p class=\"meta\">{} layouts · {} plans{} · capacity kept above {} · posture-opt {}</p></header>",
        c.layouts.len(),
        if c.adaptive {
            "fatigue-adaptive"
        } else {
            "held"
        },
        if c.fatigue_only { ", fatigue only" } else { "" },
        pct(c.capacity_floor),
        env!("CARGO_PKG_VERSION")
    );
    if let Some(best) = c.layouts.first() {
        let _ = write!(
            o,
            "<div class=\"verdict {}\">Best layout: <b>{}</b> ({}) — {}.</div>",
            level(best).class(),
            esc(&best.task),
            esc(&best.file),
            esc(&verdict(best))
        );
    } else {
        o.push_str("<div class=\"verdict info\">No layouts were compared.</div>");
    }
    o.push_str("<section><h2>Findings</h2>");
    o.push_str(&findings_list(&findings_html(c)));
    o.push_str("</section><section><h2>Ranking</h2>");
    o.push_str(&ranking_tables(c));
    o.push_str("</section><section><h2>How robust is the ranking?</h2>");
    o.push_str(&robustness_section(c));
    o.push_str("</section><section class=\"major\"><h2>The layouts side by side</h2>");
    if c.layouts.len() > MAX_DRAWN {
        let _ = write!(
            o,
            "<p class=\"meta\">The first {MAX_DRAWN} layouts are drawn; the tables above list all {}.</p>",
            c.layouts.len()
        );
    }
    for i in 0..n {
        let d = drawn[i].as_ref().map(|(s, f, p, w)| (s, f, *p, *w));
        o.push_str(&card(&c.layouts[i], tasks[i], &planned[i], d));
    }
    o.push_str("</section>");
    Ok(o)
}
