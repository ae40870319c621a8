//! The self-contained HTML reports of `plan --report`, `compare --report` and `sweep --report`:
//! summary, capacity and fatigue curves, side and front views of every phase's posture with the
//! obstacles, RULA worksheets, work/rest advice, the comparison table (`compare`) and the
//! population table (`sweep`). One file, inline SVG and CSS, no scripts, no external resources.

use super::figures::{bounds, curve_svg, esc, posture_svg, scene, Curve, Scene, View};
use crate::body::StaticsData;
use crate::compare::{Comparison, LayoutOutcome};
use crate::plan::Plan;
use crate::rest::RestAdvice;
use crate::task::Task;
use std::fmt::Write;

/// Failure to draw a figure (internal).
#[derive(Debug, thiserror::Error)]
#[error("cannot draw the report's {what}: {message}")]
pub struct ReportError {
    pub what: String,
    pub message: String,
}

/// One layout to report.
pub struct Layout<'a> {
    pub file: &'a str,
    pub task: &'a Task,
    pub plan: &'a Plan,
    pub rest: &'a RestAdvice,
}

const STYLE: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,sans-serif;margin:24px auto;max-width:1000px;color:#1d2b44;padding:0 12px}\
h1{font-size:26px;margin-bottom:4px}h2{border-bottom:2px solid #1d2b44;padding-bottom:4px;margin-top:36px}\
h3{margin-top:24px}.meta{color:#666;font-size:13px}table{border-collapse:collapse;margin:8px 0;font-size:14px}\
td,th{border:1px solid #ccd;padding:4px 8px;text-align:left;vertical-align:top}th{background:#eef1f7}\
.views{display:flex;gap:8px;flex-wrap:wrap;align-items:flex-end}.phase{border:1px solid #dde;border-radius:6px;padding:8px 12px;margin:12px 0}\
.bad{color:#b00020;font-weight:600}.ok{color:#1a7f37;font-weight:600}details{margin-top:6px}summary{cursor:pointer;color:#345}\
.fig{margin:8px 0}";

fn row(o: &mut String, k: &str, v: &str) {
    let _ = write!(o, "<tr><th>{}</th><td>{}</td></tr>", esc(k), v);
}

fn summary_table(o: &mut String, l: &Layout) {
    let s = &l.plan.summary;
    o.push_str("<table class=\"summary\">");
    row(o, "task file", &esc(l.file));
    row(
        o,
        "plan",
        &format!(
            "{}, fatigue model {}, body {}",
            if s.adaptive {
                "fatigue-adaptive"
            } else {
                "baseline (no adaptation)"
            },
            esc(&l.plan.fatigue_model),
            esc(&l.plan.robot)
        ),
    );
    row(
        o,
        "duration",
        &format!(
            "planned {:.0} s, simulated {:.0} s ({} cycles of {:.1} s)",
            s.planned_duration_s,
            s.duration_s,
            s.cycles_done,
            l.task.cycle_s()
        ),
    );
    let base = match (s.baseline_total_u, s.change_vs_baseline) {
        (Some(b), Some(c)) => format!("; baseline {b:.2} min ({:+.1} %)", 100.0 * c),
        _ => String::new(),
    };
    row(
        o,
        "total fatigue index U",
        &format!("{:.2} min{}", s.total_u, base),
    );
    row(
        o,
        "most-fatigued group",
        &format!("{} (U = {:.2} min)", esc(&s.worst_half_joint), s.worst_u),
    );
    let (min_c, min_h) = l.plan.lowest_capacity();
    row(
        o,
        "lowest capacity (at any time)",
        &format!("{min_c:.2} ({})", esc(&min_h)),
    );
    row(
        o,
        "exhaustion",
        &match &s.exhaustion {
            Some(e) => format!(
                "<span class=\"bad\">at {:.0} s: {} ({}) cannot hold {:.0} % MVC in '{}'</span>",
                e.t_s,
                esc(&e.half_joint),
                esc(&e.group),
                100.0 * e.load,
                esc(&e.phase)
            ),
            None => "<span class=\"ok\">none</span>".into(),
        },
    );
    if let Some(te) = s.baseline_exhaustion_t_s {
        row(o, "baseline exhaustion", &format!("at {te:.0} s"));
    }
    row(
        o,
        "worst RULA grand score",
        &s.rula_max
            .map_or("n/a (not the worker body)".into(), |r| r.to_string()),
    );
    o.push_str("</table>");
}

fn rest_table(o: &mut String, r: &RestAdvice) {
    o.push_str("<table>");
    row(
        o,
        "work per cycle / rest now",
        &format!("{:.1} s / {:.1} s", r.work_s_per_cycle, r.current_rest_s),
    );
    row(
        o,
        &format!(
            "model: rest per cycle for capacity ≥ {:.2}",
            r.capacity_floor
        ),
        &match r.model.rest_s_per_cycle {
            Some(x) => format!(
                "<b>{x:.1} s</b> (lowest capacity then {:.2}); now the lowest is {:.2} ({})",
                r.model.min_capacity_at_recommended.unwrap_or(f64::NAN),
                r.model.min_capacity_current,
                esc(&r.model.limiting_half_joint)
            ),
            None => format!("<span class=\"bad\">{}</span>", esc(&r.model.note)),
        },
    );
    row(
        o,
        "Rohmert (1973) rest allowance",
        &format!(
            "<b>{:.1} s</b> per cycle{}",
            r.rohmert.rest_s_per_cycle,
            if r.rohmert.limiting_half_joint.is_empty() {
                " (no hold above 15 % MVC)".to_string()
            } else {
                format!(" (limited by {})", esc(&r.rohmert.limiting_half_joint))
            }
        ),
    );
    o.push_str("</table>");
}

fn phases_html(o: &mut String, l: &Layout) -> Result<(), ReportError> {
    let t = l.task;
    let mut data = StaticsData::new(&t.model);
    let mut scenes: Vec<Scene> = Vec::with_capacity(t.phases.len());
    for (p, ph) in l.plan.summary.phases.iter().enumerate() {
        let mut q = vec![0.0; t.model.nq()];
        for (name, v) in &ph.q_rad {
            let i = t.model.q_index(name).map_err(|e| ReportError {
                what: "posture".into(),
                message: e.to_string(),
            })?;
            q[i] = *v;
        }
        scenes.push(scene(
            &t.model,
            &mut data,
            &q,
            t.hand_link,
            t.phases.get(p).map(|x| x.target_m),
        ));
    }
    let refs: Vec<&Scene> = scenes.iter().collect();
    let b_side = bounds(&refs, &t.workstation, View::Side);
    let b_front = bounds(&refs, &t.workstation, View::Front);
    // One scale for every view: at most 300 px tall and 480 px wide.
    let extent = |b: ((f64, f64), (f64, f64)), axis: usize| match axis {
        0 => b.1 .0 - b.0 .0,
        _ => b.1 .1 - b.0 .1,
    };
    let px_per_m = (300.0 / extent(b_side, 1).max(extent(b_front, 1)))
        .min(480.0 / extent(b_side, 0).max(extent(b_front, 0)));
    for (ph, sc) in l.plan.summary.phases.iter().zip(&scenes) {
        let _ = write!(o, "<div class=\"phase\"><h4>{}</h4>", esc(&ph.phase));
        o.push_str("<div class=\"views\">");
        for (view, b) in [(View::Side, b_side), (View::Front, b_front)] {
            let w = (b.1 .0 - b.0 .0) * px_per_m;
            o.push_str(&posture_svg(sc, &t.workstation, view, b, w));
        }
        o.push_str("</div><p>");
        let _ = write!(
            o,
            "hand error {:.1} mm{}, clearance {:.0} mm. Most loaded: {}.",
            1000.0 * ph.hand_error_m,
            if ph.reachable {
                ""
            } else {
                " <span class=\"bad\">(target out of reach)</span>"
            },
            1000.0 * ph.min_clearance_m,
            ph.most_loaded
                .iter()
                .map(|(h, f)| format!("{} {:.0} %", esc(h), 100.0 * f))
                .collect::<Vec<_>>()
                .join(", ")
        );
        if let Some(r) = &ph.rula {
            let _ = write!(
                o,
                " <b>RULA {}</b> (action level {}: {}).</p><details><summary>RULA worksheet</summary><table><tr><th>step</th><th>item</th><th>measured</th><th>rule</th><th>score</th></tr>",
                r.grand_score,
                r.action_level,
                esc(r.action)
            );
            for w in &r.worksheet {
                let _ = write!(
                    o,
                    "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                    w.step,
                    esc(w.item),
                    w.measured.map_or(String::new(), |m| format!("{m:.1}")),
                    esc(&w.rule),
                    w.score
                );
            }
            o.push_str("</table></details>");
        } else {
            o.push_str("</p>");
        }
        o.push_str("</div>");
    }
    Ok(())
}

fn layout_section(o: &mut String, l: &Layout, heading: &str) -> Result<(), ReportError> {
    let fig = |what: &str, r: Result<String, String>| {
        r.map_err(|message| ReportError {
            what: what.into(),
            message,
        })
    };
    let _ = write!(o, "<section><h2>{}</h2>", esc(heading));
    summary_table(o, l);
    o.push_str("<h3>Capacity and fatigue over time</h3><div class=\"fig\">");
    o.push_str(&fig(
        "capacity curves",
        curve_svg(l.plan, Curve::Capacity, Some(l.rest.capacity_floor)),
    )?);
    o.push_str("</div><div class=\"fig\">");
    o.push_str(&fig(
        "fatigue curves",
        curve_svg(l.plan, Curve::FatigueU, None),
    )?);
    let _ = write!(
        o,
        "</div><p class=\"meta\">Coloured: the {} groups with the lowest capacity; grey: the others. Dashed: capacity floor {:.2}.</p>",
        super::figures::HIGHLIGHTED,
        l.rest.capacity_floor
    );
    o.push_str("<h3>Work and rest</h3>");
    rest_table(o, l.rest);
    o.push_str("<h3>Postures (last plan), with the workstation</h3>");
    phases_html(o, l)?;
    o.push_str("</section>");
    Ok(())
}

fn document(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width\"><title>{}</title><style>{STYLE}</style></head><body><h1>{}</h1><p class=\"meta\">posture-opt {} — Ma, Chablat, Bennis &amp; Zhang (2009) dynamic fatigue model; RULA after McAtamney &amp; Corlett (1993); rest allowance after Rohmert (1973).</p>{}</body></html>\n",
        esc(title),
        esc(title),
        env!("CARGO_PKG_VERSION"),
        body
    )
}

/// The report of one plan.
pub fn plan_report(l: &Layout) -> Result<String, ReportError> {
    let mut body = String::new();
    layout_section(&mut body, l, &l.plan.task)?;
    Ok(document(&format!("Plan: {}", l.plan.task), &body))
}

/// A comparison-table column: heading and cell.
type Column<'a> = (&'a str, &'a dyn Fn(&LayoutOutcome) -> String);

fn comparison_html(o: &mut String, c: &Comparison) {
    let cols: &[Column] = &[
        ("rank", &|x| x.rank.to_string()),
        ("layout", &|x| {
            format!("{}<br><small>{}</small>", esc(&x.task), esc(&x.file))
        }),
        ("total U [min]", &|x| format!("{:.2}", x.total_u_min)),
        ("most-fatigued group (U)", &|x| {
            format!("{} ({:.2} min)", esc(&x.worst_half_joint), x.worst_u_min)
        }),
        ("min capacity", &|x| {
            format!("{:.2} {}", x.min_capacity, esc(&x.min_capacity_half_joint))
        }),
        ("first exhaustion", &|x| match &x.exhaustion {
            Some(e) => format!(
                "<span class=\"bad\">{:.0} s, {}</span>",
                e.t_s,
                esc(&e.half_joint)
            ),
            None => "<span class=\"ok\">none</span>".into(),
        }),
        ("worst RULA", &|x| {
            x.rula_max.map_or("n/a".into(), |r| r.to_string())
        }),
        (
            "rest needed (model)",
            &|x| match x.rest.model.rest_s_per_cycle {
                Some(r) => format!("{r:.1} s"),
                None => "<span class=\"bad\">rest cannot help</span>".into(),
            },
        ),
        ("rest (Rohmert)", &|x| {
            format!("{:.1} s", x.rest.rohmert.rest_s_per_cycle)
        }),
    ];
    o.push_str("<h2>Comparison</h2><table><tr>");
    for (h, _) in cols {
        let _ = write!(o, "<th>{}</th>", esc(h));
    }
    o.push_str("</tr>");
    for l in &c.layouts {
        o.push_str("<tr>");
        for (_, f) in cols {
            let _ = write!(o, "<td>{}</td>", f(l));
        }
        o.push_str("</tr>");
    }
    let _ = write!(
        o,
        "</table><p class=\"meta\">Ranking: {}. Rest needed keeps every capacity ≥ {:.2}.</p>",
        esc(c.ranking_rule),
        c.capacity_floor
    );
}

/// The report of a comparison; `layouts` in the comparison's (ranked) order.
pub fn compare_report(c: &Comparison, layouts: &[Layout]) -> Result<String, ReportError> {
    let mut body = String::new();
    comparison_html(&mut body, c);
    for (o, l) in c.layouts.iter().zip(layouts) {
        layout_section(&mut body, l, &format!("{}. {}", o.rank, o.task))?;
    }
    Ok(document("Layout comparison", &body))
}

/// The report of a population sweep: who cannot do the task, and where.
pub fn sweep_report(s: &crate::sweep::Sweep) -> String {
    let mut o = String::new();
    let _ = write!(
        o,
        "<p>{} workers ({}), {} plans, capacity floor {:.2}: <span class=\"{}\">{} cannot do the task</span>.</p>",
        s.workers.len(),
        esc(&s.population),
        if s.adaptive { "adaptive" } else { "baseline" },
        s.capacity_floor,
        if s.cannot_do > 0 { "bad" } else { "ok" },
        s.cannot_do
    );
    o.push_str("<table><tr><th>worker</th><th>sex</th><th>stature [m]</th><th>mass [kg]</th><th>strength percentile</th><th>total U [min]</th><th>lowest capacity</th><th>worst RULA</th><th>rest needed per cycle</th><th>can do the task?</th></tr>");
    for w in &s.workers {
        let _ = write!(
            o,
            "<tr><td>{}</td><td>{}</td><td>{:.3}</td><td>{:.0}</td><td>{:.0}</td><td>{:.2}</td><td>{:.2} {}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(&w.label),
            w.worker.sex.name(),
            w.worker.stature_m,
            w.worker.mass_kg,
            w.worker.strength_percentile,
            w.total_u_min,
            w.min_capacity,
            esc(&w.min_capacity_half_joint),
            w.rula_max.map_or("n/a".into(), |r| r.to_string()),
            w.rest_needed_s
                .map_or("rest cannot help".into(), |r| format!("{r:.1} s")),
            if w.can_do {
                "<span class=\"ok\">yes</span>".to_string()
            } else {
                format!(
                    "<span class=\"bad\">no: {}</span>",
                    w.problems
                        .iter()
                        .map(|p| esc(&crate::sweep::problem_text(p)))
                        .collect::<Vec<_>>()
                        .join("; ")
                )
            }
        );
    }
    o.push_str("</table><p class=\"meta\">A worker cannot do the task when a muscle group is exhausted, a target is out of reach (more than 1 cm) or a posture collides with an obstacle. Bodies are generated per worker; see the README for the population data and its assumptions.</p>");
    document(&format!("Population sweep: {}", s.task), &o)
}
