//! The population sweep report: who can do the task and who cannot, and why; the share who
//! sustain it, with its 95 % confidence interval, for sampled populations.

use super::fmt::{Finding, Level, Table, dur, esc, findings_list, num, opt, pct, unit};
use super::svg::{Scale, Svg, nice_ticks, tick_decimals};
use crate::assess::verdict::Status;
use crate::body::Sex;
use crate::study::sweep::{Problem, Share, Sweep, WorkerOutcome, problem_text, shift_counts};
use std::fmt::Write;

fn verdict(w: &WorkerOutcome, floor: f64) -> (Level, String) {
    if !w.could_not_plan.is_empty() {
        return (
            Level::Warn,
            format!(
                "<b>the optimiser could not plan</b>{}: {}",
                w.retried_from
                    .as_ref()
                    .map(|f| format!(" (also tried from {}’s postures)", esc(f)))
                    .unwrap_or_default(),
                esc(&w.could_not_plan.join("; "))
            ),
        );
    }
    if w.can_do && w.problems.is_empty() {
        // how the worker manages the task, and whether a muscle group gives out
        let (tires, how) = if w.lowest_capacity < floor || w.rest_needed_s.is_none() {
            (
                true,
                format!(
                    "only by changing posture as the muscles tire: capacity falls to {} (floor {}){}",
                    pct(w.lowest_capacity),
                    pct(floor),
                    if w.rest_needed_s.is_none() {
                        "; no rest up to 10× the work time keeps it above the floor"
                    } else {
                        ""
                    }
                ),
            )
        } else {
            match w.minutes_to_exhaustion {
                Some(m) => (
                    true,
                    format!("kept up, a group gives out after {}", dur(60.0 * m)),
                ),
                None if w.exhaustion_verdict == "not_determined" => (
                    true,
                    format!(
                        "kept up, {}",
                        crate::assess::meaning::no_exhaustion_words(
                            &w.exhaustion_verdict,
                            w.minutes_followed
                        )
                    ),
                ),
                None => (false, "no muscle group gives out".to_string()),
            }
        };
        // the shift verdict first: being able to do it says nothing of whether it is acceptable
        let level = match w.shift_status {
            Status::Exceeded => Level::Bad,
            Status::Acceptable if !tires => Level::Ok,
            _ => Level::Warn,
        };
        (
            level,
            format!(
                "shift: {}; physically able to do it ({how})",
                // the status and binding criterion (the details are the worker's plan's)
                esc(w.shift_verdict.split(" — ").next().unwrap_or_default())
            ),
        )
    } else {
        let why: Vec<String> = w.problems.iter().map(|p| esc(&problem_text(p))).collect();
        (
            Level::Bad,
            format!(
                "<b>cannot</b>: {}",
                if why.is_empty() {
                    "—".to_string()
                } else {
                    why.join("; ")
                }
            ),
        )
    }
}

/// k and recovery per muscle group for the task's own worker (every swept worker gets the
/// same values, except where the set gives a region's k by sex).
fn group_parameters(t: &crate::plan::Task) -> String {
    let mut tab = Table::new(
        "sweep-params",
        &[
            "muscle group",
            "region",
            "k",
            "recovery at rest",
            "held forever up to",
        ],
    )
    .numeric(&[2, 3, 4]);
    for (h, p) in t.half_joints.iter().zip(&t.fatigue) {
        tab.row(
            None,
            vec![
                esc(&h.group),
                esc(&h.region),
                format!("{}/min", num(p.k_per_min, 3)),
                format!("{}/min", num(p.r_at(0.0), 3)),
                pct(p.sustainable_load()),
            ],
        );
    }
    format!(
        "<details><summary>k and recovery per muscle group (the task's worker, a {}; sources above)</summary>{}</details>",
        esc(t.worker.sex.name()),
        tab.render()
    )
}

fn kind(p: &Problem) -> &'static str {
    match p {
        Problem::ExceedsStrength { .. } => "a load exceeds a group’s strength",
        Problem::Exhaustion { .. } => "a muscle group is exhausted within the task",
        Problem::OutOfReach { proven: true, .. } => "a target is out of reach",
        Problem::OutOfReach { proven: false, .. } => "a target is not reached",
        Problem::Collision { .. } => "a posture collides with the workstation",
        Problem::OffBalance { .. } => "off balance",
    }
}

fn share_text(s: &Share) -> String {
    format!(
        "{} (95 % CI {}–{}, n = {})",
        pct(s.share),
        pct(s.low),
        pct(s.high),
        s.of
    )
}

/// A forest plot of the shares with their intervals.
fn shares_svg(rows: &[(&str, &Share)]) -> String {
    let (w, row_h) = (560.0, 26.0);
    let h = 30.0 + row_h * rows.len() as f64;
    let (x0, x1) = (90.0, w - 70.0);
    let xs = Scale {
        d0: 0.0,
        d1: 1.0,
        p0: x0,
        p1: x1,
    };
    let mut g = Svg::new(
        w,
        h,
        "share who can do the whole task, with 95 % confidence intervals",
    );
    g.rect(0.0, 0.0, w, h, "fill=\"#ffffff\"");
    for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let x = xs.map(t);
        g.line(x, 6.0, x, h - 18.0, "stroke=\"#e6e9ef\"");
        g.text(
            x,
            h - 6.0,
            &pct(t),
            "font-size=\"9.5\" fill=\"#4a5468\" text-anchor=\"middle\"",
        );
    }
    for (i, (name, s)) in rows.iter().enumerate() {
        let y = 16.0 + row_h * i as f64;
        g.text(
            x0 - 8.0,
            y + 4.0,
            name,
            "font-size=\"11\" fill=\"#1d2b44\" text-anchor=\"end\"",
        );
        g.line(
            xs.map(s.low),
            y,
            xs.map(s.high),
            y,
            "stroke=\"#0072b2\" stroke-width=\"2\"",
        );
        for e in [s.low, s.high] {
            g.line(
                xs.map(e),
                y - 5.0,
                xs.map(e),
                y + 5.0,
                "stroke=\"#0072b2\" stroke-width=\"1.5\"",
            );
        }
        g.circle(xs.map(s.share), y, 4.5, "fill=\"#0072b2\"");
        g.text(
            x1 + 8.0,
            y + 4.0,
            &format!("{} of {}", (s.share * s.of as f64).round(), s.of),
            "font-size=\"10\" fill=\"#4a5468\"",
        );
    }
    g.finish()
}

/// Stature against strength percentile, who can and who cannot.
fn scatter_svg(workers: &[WorkerOutcome]) -> String {
    let (w, h) = (560.0, 300.0);
    let (px0, py0, pw, ph) = (52.0, 12.0, 480.0, 240.0);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in workers {
        lo = lo.min(x.worker.stature_m);
        hi = hi.max(x.worker.stature_m);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return String::new();
    }
    let pad = ((hi - lo) * 0.08).max(0.03);
    let xs = Scale {
        d0: lo - pad,
        d1: hi + pad,
        p0: px0,
        p1: px0 + pw,
    };
    let ys = Scale {
        d0: 0.0,
        d1: 100.0,
        p0: py0 + ph,
        p1: py0,
    };
    let mut g = Svg::new(w, h, "workers by stature and strength percentile");
    g.rect(0.0, 0.0, w, h, "fill=\"#ffffff\"");
    g.rect(px0, py0, pw, ph, "fill=\"#ffffff\" stroke=\"#c9d0db\"");
    for t in [0.0, 25.0, 50.0, 75.0, 100.0] {
        let y = ys.map(t);
        g.line(px0, y, px0 + pw, y, "stroke=\"#eef0f4\"");
        g.text(
            px0 - 4.0,
            y + 3.5,
            &num(t, 0),
            "font-size=\"9.5\" fill=\"#4a5468\" text-anchor=\"end\"",
        );
    }
    let xt = nice_ticks(lo - pad, hi + pad, 6);
    let dp = tick_decimals(&xt);
    for t in &xt {
        let x = xs.map(*t);
        g.line(x, py0 + ph, x, py0 + ph + 3.0, "stroke=\"#7a8394\"");
        g.text(
            x,
            py0 + ph + 14.0,
            &num(*t, dp),
            "font-size=\"9.5\" fill=\"#4a5468\" text-anchor=\"middle\"",
        );
    }
    g.text(
        px0 + pw / 2.0,
        h - 8.0,
        "stature [m]",
        "font-size=\"10.5\" fill=\"#33415c\" text-anchor=\"middle\"",
    );
    g.text(12.0, py0 + ph / 2.0, "strength percentile", &format!("font-size=\"10.5\" fill=\"#33415c\" text-anchor=\"middle\" transform=\"rotate(-90 12 {:.1})\"", py0 + ph / 2.0));
    let label = workers.len() <= 12;
    for x in workers {
        let (cx, cy) = (
            xs.map(x.worker.stature_m),
            ys.map(x.worker.strength_percentile),
        );
        let colour = if x.can_do { "#1a7f37" } else { "#b3261e" };
        match x.worker.sex {
            Sex::Female => g.circle(
                cx,
                cy,
                5.0,
                &format!("fill=\"{colour}\" fill-opacity=\"0.75\" stroke=\"#ffffff\""),
            ),
            Sex::Male => g.rect(
                cx - 4.5,
                cy - 4.5,
                9.0,
                9.0,
                &format!("fill=\"{colour}\" fill-opacity=\"0.75\" stroke=\"#ffffff\""),
            ),
        }
        if label {
            g.text(cx + 7.0, cy + 3.5, &x.label, "font-size=\"9.5\" fill=\"#33415c\" paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\"");
        }
    }
    g.finish()
}

/// The sweep report's body.
pub fn body(s: &Sweep, task: Option<&crate::plan::Task>) -> String {
    let n = s.workers.len();
    let mut o = String::new();
    let _ = write!(
        o,
        "<header><h1>Population sweep: {}</h1><p class=\"meta\">{} workers ({}) · {} plans · capacity floor {} · posture-opt {}</p></header>",
        esc(&s.task),
        n,
        esc(&s.population),
        if s.adaptive {
            "fatigue-adaptive"
        } else {
            "held"
        },
        pct(s.capacity_floor),
        env!("CARGO_PKG_VERSION")
    );
    let shifts: Vec<Status> = s
        .workers
        .iter()
        .filter(|w| w.can_do && w.could_not_plan.is_empty())
        .map(|w| w.shift_status)
        .collect();
    let lv = if n == 0 {
        Level::Info
    } else if s.cannot_do == 0 {
        // able, each of them: the shift verdicts say whether it is acceptable
        if shifts.contains(&Status::Exceeded) {
            Level::Bad
        } else if shifts.iter().all(|&x| x == Status::Acceptable) {
            Level::Ok
        } else {
            Level::Warn
        }
    } else if s.cannot_do == n {
        Level::Bad
    } else {
        Level::Warn
    };
    let _ = write!(
        o,
        "<div class=\"verdict {}\">{} of {} workers cannot do the task{}{}{}.</div>",
        lv.class(),
        s.cannot_do,
        n,
        esc(&shift_counts(s)),
        if s.could_not_plan > 0 {
            format!(
                "; the optimiser could not plan {} (not counted as unable: see below)",
                s.could_not_plan
            )
        } else {
            String::new()
        },
        s.sustain_all
            .as_ref()
            .map(|x| format!(
                "; {} of this population can do the whole task",
                share_text(x)
            ))
            .unwrap_or_default()
    );

    // findings
    let mut f = Vec::new();
    let mut kinds: Vec<(&str, Vec<&str>)> = Vec::new();
    for w in &s.workers {
        for p in &w.problems {
            let k = kind(p);
            match kinds.iter_mut().find(|x| x.0 == k) {
                Some(x) => {
                    if !x.1.contains(&w.label.as_str()) {
                        x.1.push(&w.label)
                    }
                }
                None => kinds.push((k, vec![&w.label])),
            }
        }
    }
    for (k, who) in &kinds {
        f.push(Finding::new(
            Level::Bad,
            format!(
                "{}: {} worker{} ({}).",
                super::fmt::capitalise(k),
                who.len(),
                if who.len() == 1 { "" } else { "s" },
                esc(&who.join(", "))
            ),
        ));
    }
    let can: Vec<&WorkerOutcome> = s.workers.iter().filter(|w| w.can_do).collect();
    if !can.is_empty() {
        let tiring = can
            .iter()
            .filter(|w| w.minutes_to_exhaustion.is_some() || w.shift_status != Status::Acceptable)
            .count();
        f.push(Finding::new(
            if tiring > 0 { Level::Warn } else { Level::Ok },
            format!(
                "{} worker{} can do the task{}.",
                can.len(),
                if can.len() == 1 { "" } else { "s" },
                if tiring > 0 {
                    format!("; for {tiring} of them the pace could not be kept up indefinitely (a group gives out, or a shift criterion is not acceptable)")
                } else {
                    ", at a pace they could keep up indefinitely".into()
                }
            ),
        ));
        if let Some(w) = can
            .iter()
            .min_by(|a, b| a.lowest_capacity.total_cmp(&b.lowest_capacity))
        {
            f.push(Finding::new(
                if w.lowest_capacity < s.capacity_floor {
                    Level::Warn
                } else {
                    Level::Ok
                },
                format!(
                    "Of those who can, {} comes closest to the limit: lowest capacity {} ({}).",
                    esc(&w.label),
                    pct(w.lowest_capacity),
                    esc(&w.lowest_capacity_group)
                ),
            ));
        }
    }
    for (name, sh) in [("women", &s.sustain_women), ("men", &s.sustain_men)] {
        if let Some(x) = sh
            && x.of > 0
        {
            f.push(Finding::new(
                Level::Info,
                format!(
                    "Share of {name} who can do the whole task: {}.",
                    share_text(x)
                ),
            ));
        }
    }
    f.push(Finding::new(
        Level::Info,
        format!("About U: {}.", esc(&s.note)),
    ));
    o.push_str("<section><h2>Findings</h2>");
    o.push_str(&findings_list(&f));
    o.push_str("</section>");

    let shares: Vec<(&str, &Share)> = [
        ("all", &s.sustain_all),
        ("women", &s.sustain_women),
        ("men", &s.sustain_men),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.as_ref().filter(|x| x.of > 0).map(|x| (k, x)))
    .collect();
    if !shares.is_empty() || n >= 2 {
        o.push_str("<section><h2>Who can do it</h2>");
        if !shares.is_empty() {
            let _ = write!(
                o,
                "<figure class=\"chart\">{}<figcaption>Share of the sampled workers who can do the whole task, with its 95 % Wilson score interval.</figcaption></figure>",
                shares_svg(&shares)
            );
        }
        if n >= 2 {
            let _ = write!(
                o,
                "<figure class=\"chart\">{}<figcaption>Each worker by stature and strength percentile: <span class=\"ok-text\">green</span>, can do the task; <span class=\"bad-text\">red</span>, cannot; circles women, squares men.</figcaption></figure>",
                scatter_svg(&s.workers)
            );
        }
        o.push_str("</section>");
    }

    o.push_str("<section><h2>Workers</h2>");
    let mut t = Table::new(
        "workers",
        &[
            "worker",
            "sex, stature, mass",
            "strength percentile",
            "verdict",
            "lowest capacity",
            "RULA / REBA",
            "L5/S1",
            "rest needed per cycle",
            "variants exhausting a group",
            "U (simulated time)",
        ],
    )
    .numeric(&[2, 6]);
    for w in &s.workers {
        let (lv, v) = verdict(w, s.capacity_floor);
        // a load above strength from the first instant: nothing was held, no figures
        let did_not_start = w
            .problems
            .iter()
            .any(|p| matches!(p, Problem::ExceedsStrength { .. }))
            && w.simulated_s <= 0.0;
        t.row(
            Some(lv),
            vec![
                esc(&w.label),
                format!(
                    "{}, {}, {}",
                    esc(w.worker.sex.name()),
                    unit(w.worker.stature_m, 3, "m"),
                    unit(w.worker.mass_kg, 0, "kg")
                ),
                num(w.worker.strength_percentile, 0),
                v,
                if did_not_start {
                    "— (did not start)".into()
                } else {
                    format!(
                        "{} ({})",
                        pct(w.lowest_capacity),
                        esc(&w.lowest_capacity_group)
                    )
                },
                format!(
                    "{} / {}",
                    opt(w.rula_max, |x| x.to_string()),
                    opt(w.reba_max, |x| x.to_string())
                ),
                opt(w.back_compression_max_n, |x| unit(x, 0, "N")),
                w.rest_needed_s
                    .map_or_else(|| "none up to 10× the work time".into(), dur),
                opt(w.exhausted_in_variants, |x| {
                    format!("{x} of {}", crate::assess::uncertainty::VARIANTS.len())
                }),
                if did_not_start {
                    "— (did not start)".into()
                } else {
                    format!("{} ({})", unit(w.total_u_min, 1, "min"), dur(w.simulated_s))
                },
            ],
        );
    }
    o.push_str(&t.render());
    let _ = write!(
        o,
        "<p class=\"meta\">A worker cannot do the task when a load exceeds a muscle group’s strength, a group is exhausted within the task, a target is out of reach (more than 1 cm), a posture collides with the workstation or the worker would lose balance. Each worker’s body is generated from their sex, stature and mass. Note: {}.</p>",
        esc(&s.note)
    );
    o.push_str("</section>");
    if let Some(t) = task {
        let _ = write!(
            o,
            "<section><h2>The task</h2><h3>Phases of one cycle</h3>{}<h3>Fatigue parameters</h3>{}<p class=\"meta\">k per muscle group follows its body region (and the worker's sex where the set gives it); every worker's strength comes from the population tables at their sex and strength percentile.</p></section>",
            super::plan_page::phase_table(t, None),
            super::plan_page::parameter_set_table(&t.fatigue_choice)
        );
        o.push_str(&group_parameters(t));
    }
    o
}
