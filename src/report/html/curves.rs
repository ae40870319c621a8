//! Capacity over time per muscle group: an overview of the groups that fall lowest (distinct
//! colours and dash patterns, labelled at the right, the others in grey) and one small panel per
//! group so that no curve hides another.
//!
//! The plan gives each group's capacity at the end of every held step; within a step it moves
//! monotonically, so the step ends trace the curve. Long tasks have thousands of steps: the time
//! axis is cut into short slices and each slice keeps its lowest and highest capacity. The
//! overview draws the lowest (the capacity falls during work and rises in the rests: the lower
//! edge is what matters); the panels draw the whole band.

use super::analysis::GroupCourse;
use super::fmt::{dur, esc, num, pct};
use super::svg::{Scale, Svg, nice_ticks, spread, tick_decimals};
use crate::plan::Plan;
use std::fmt::Write;

/// Colours and dash patterns of the highlighted groups (Okabe & Ito's colour-blind-safe set).
const COLOURS: [&str; 6] = [
    "#d55e00", "#0072b2", "#009e73", "#cc79a7", "#e69f00", "#56b4e9",
];
const DASHES: [&str; 6] = ["", "8 3", "3 2", "10 3 2 3", "5 2 1 2", "2 2"];
/// Groups highlighted, and grey groups behind them.
const HIGHLIGHT: usize = 6;
const GREY: usize = 10;
/// Curves closer than this everywhere (capacity, fraction of strength) are drawn as one.
const COINCIDE: f64 = 2e-3;

/// "left and right shoulder flexors" for a pair of sides, else the names joined by " = ".
fn joined_names(names: &[String]) -> String {
    if let [a, b] = names {
        for (x, y) in [("left ", "right "), ("right ", "left ")] {
            if let (Some(ra), Some(rb)) = (a.strip_prefix(x), b.strip_prefix(y))
                && ra == rb
            {
                return format!("left and right {ra}");
            }
        }
    }
    names.join(" = ")
}
/// Time slices across the task.
const SLICES: usize = 360;

/// (t \[s\], capacity) at the start and at every step's end.
fn series(plan: &Plan, h: usize) -> Vec<(f64, f64)> {
    let st = &plan.steps;
    let mut v = Vec::with_capacity(st.len() + 1);
    v.push((0.0, 1.0));
    for (t, state) in st.course(h) {
        let c = state.capacity;
        if t.is_finite() && c.is_finite() {
            v.push((t, c));
        }
    }
    v
}

/// Per time slice: (t at the slice's middle, lowest, highest); short series are kept as they are.
fn slices(pts: &[(f64, f64)], t_end: f64) -> Vec<(f64, f64, f64)> {
    if pts.len() <= 2 * SLICES || t_end <= 0.0 {
        return pts.iter().map(|p| (p.0, p.1, p.1)).collect();
    }
    let mut out: Vec<(f64, f64, f64)> = Vec::with_capacity(SLICES + 1);
    let width = t_end / SLICES as f64;
    let mut cur: Option<(usize, f64, f64)> = None;
    for &(t, c) in pts {
        let k = ((t / width).floor() as usize).min(SLICES - 1);
        match cur {
            Some((ck, lo, hi)) if ck == k => cur = Some((ck, lo.min(c), hi.max(c))),
            _ => {
                if let Some((ck, lo, hi)) = cur {
                    out.push(((ck as f64 + 0.5) * width, lo, hi));
                }
                cur = Some((k, c, c));
            }
        }
    }
    if let Some((ck, lo, hi)) = cur {
        out.push(((ck as f64 + 0.5) * width, lo, hi));
    }
    if let (Some(first), Some(p0)) = (out.first_mut(), pts.first()) {
        first.0 = p0.0;
    }
    out
}

/// The time axis: minutes for tasks of two minutes or more, else seconds.
fn time_unit(t_end: f64) -> (f64, &'static str) {
    if t_end >= 120.0 {
        (60.0, "min")
    } else {
        (1.0, "s")
    }
}

fn short(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        let mut t: String = s.chars().take(n.saturating_sub(1)).collect();
        t.push('…');
        t
    }
}

fn dash_attr(i: usize) -> String {
    let d = DASHES[i % DASHES.len()];
    if d.is_empty() {
        String::new()
    } else {
        format!(" stroke-dasharray=\"{d}\"")
    }
}

/// Axes with ticks and labels in `g`; returns (x scale, y scale).
#[allow(clippy::too_many_arguments)]
fn axes(
    g: &mut Svg,
    x0: f64,
    y0: f64,
    w: f64,
    h: f64,
    t_end: f64,
    xticks: usize,
    ylabels: bool,
    font: f64,
) -> (Scale, Scale) {
    let (div, _) = time_unit(t_end);
    let xs = Scale {
        d0: 0.0,
        d1: t_end / div,
        p0: x0,
        p1: x0 + w,
    };
    let ys = Scale {
        d0: 0.0,
        d1: 1.0,
        p0: y0 + h,
        p1: y0,
    };
    g.rect(x0, y0, w, h, "fill=\"#ffffff\" stroke=\"#c9d0db\"");
    let yt = if h > 120.0 {
        vec![0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
    } else {
        vec![0.0, 0.5, 1.0]
    };
    for &v in &yt {
        let y = ys.map(v);
        g.line(x0, y, x0 + w, y, "stroke=\"#eef0f4\"");
        if ylabels || v == 0.0 || v == 1.0 {
            g.text(
                x0 - 4.0,
                y + font / 3.0,
                &num(v, 1),
                &format!("font-size=\"{font}\" fill=\"#4a5468\" text-anchor=\"end\""),
            );
        }
    }
    let xt = nice_ticks(0.0, t_end / div, xticks);
    let dp = tick_decimals(&xt);
    for &v in &xt {
        let x = xs.map(v);
        g.line(x, y0 + h, x, y0 + h + 3.0, "stroke=\"#7a8394\"");
        g.text(
            x,
            y0 + h + 3.0 + font,
            &num(v, dp),
            &format!("font-size=\"{font}\" fill=\"#4a5468\" text-anchor=\"middle\""),
        );
    }
    (xs, ys)
}

/// The capacity figures of `plan` (`courses` lowest first, `floor` the capacity floor).
pub fn capacity_figures(plan: &Plan, courses: &[GroupCourse], floor: f64) -> String {
    let t_end = plan
        .steps
        .t_s
        .iter()
        .zip(&plan.steps.duration_s)
        .map(|(t, d)| t + d)
        .fold(0.0, f64::max);
    if plan.steps.is_empty() || t_end <= 0.0 {
        return "<p class=\"meta\">No steps were simulated: there is no capacity curve to draw.</p>".into();
    }
    let tired: Vec<&GroupCourse> = courses.iter().filter(|c| c.lowest < 1.0 - 1e-6).collect();
    if tired.is_empty() {
        return "<p>No muscle group tires in this task: every capacity stays at 100\u{a0}%.</p>"
            .into();
    }
    // Groups whose curves coincide (a symmetric two-handed hold tires left and right alike) are
    // one line with both names, so that no curve hides under another.
    let group_name = |h: usize| {
        plan.half_joints
            .get(h)
            .map(|x| x.group.clone())
            .unwrap_or("?".into())
    };
    let mut hi: Vec<&GroupCourse> = Vec::new();
    let mut data: Vec<Vec<(f64, f64, f64)>> = Vec::new();
    let mut labels: Vec<Vec<String>> = Vec::new();
    let mut used = 0;
    for c in &tired {
        if hi.len() == HIGHLIGHT {
            break;
        }
        used += 1;
        let d = slices(&series(plan, c.h), t_end);
        let same = data.iter().position(|e| {
            e.len() == d.len()
                && e.iter()
                    .zip(&d)
                    .all(|(a, b)| (a.1 - b.1).abs() < COINCIDE && (a.2 - b.2).abs() < COINCIDE)
        });
        match same {
            Some(i) => labels[i].push(group_name(c.h)),
            None => {
                hi.push(c);
                data.push(d);
                labels.push(vec![group_name(c.h)]);
            }
        }
    }
    let labels: Vec<String> = labels.iter().map(|l| joined_names(l)).collect();
    let grey: Vec<&GroupCourse> = tired.iter().skip(used).take(GREY).copied().collect();
    let rest: Vec<&GroupCourse> = courses.iter().skip(used + grey.len()).collect();
    let name = |i: usize| labels[i].as_str();
    let (div, tu) = time_unit(t_end);
    let mut o = String::new();

    // overview
    let (w, h) = (780.0, 310.0);
    let (px0, py0, pw, ph) = (44.0, 14.0, 486.0, 250.0);
    let mut g = Svg::new(w, h, "capacity over time, the groups that fall lowest");
    g.rect(0.0, 0.0, w, h, "fill=\"#ffffff\"");
    let (xs, ys) = axes(&mut g, px0, py0, pw, ph, t_end, 8, true, 10.0);
    g.text(
        px0 + pw / 2.0,
        h - 8.0,
        &format!("time [{tu}]"),
        "font-size=\"10.5\" fill=\"#33415c\" text-anchor=\"middle\"",
    );
    g.text(12.0, py0 + ph / 2.0, "capacity (share of strength)", &format!("font-size=\"10.5\" fill=\"#33415c\" text-anchor=\"middle\" transform=\"rotate(-90 12 {:.1})\"", py0 + ph / 2.0));
    g.viewport(px0, py0, pw, ph);
    let local = |s: Scale, p0: f64| Scale {
        p0: s.p0 - p0,
        p1: s.p1 - p0,
        ..s
    };
    let (lx, ly) = (local(xs, px0), local(ys, py0));
    for c in &grey {
        let pts: Vec<(f64, f64)> = slices(&series(plan, c.h), t_end)
            .iter()
            .map(|p| (lx.map(p.0 / div), ly.map(p.1)))
            .collect();
        g.polyline(&pts, "stroke=\"#c3c8d1\" stroke-width=\"1\"");
    }
    if floor.is_finite() && floor > 0.0 && floor < 1.0 {
        let y = ly.map(floor);
        g.line(
            0.0,
            y,
            pw,
            y,
            "stroke=\"#222222\" stroke-width=\"1\" stroke-dasharray=\"6 4\"",
        );
        // the label above the line, at the end where no highlighted curve passes under it
        let busy = |from: f64, to: f64| {
            data.iter().flatten().any(|p| {
                let t = p.0 / div / (t_end / div).max(1e-12);
                t >= from && t <= to && p.1 >= floor - 0.01 && p.1 <= floor + 0.07
            })
        };
        let text = format!("capacity floor {}", num(floor, 2));
        if busy(0.0, 0.3) && !busy(0.7, 1.0) {
            g.text(pw - 4.0, y - 3.0, &text, "font-size=\"9.5\" fill=\"#222222\" text-anchor=\"end\" paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\"");
        } else {
            g.text(4.0, y - 3.0, &text, "font-size=\"9.5\" fill=\"#222222\" paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\"");
        }
    }
    for (i, d) in data.iter().enumerate().rev() {
        let pts: Vec<(f64, f64)> = d.iter().map(|p| (lx.map(p.0 / div), ly.map(p.1))).collect();
        g.polyline(
            &pts,
            &format!(
                "stroke=\"{}\" stroke-width=\"2\"{} stroke-linejoin=\"round\"",
                COLOURS[i],
                dash_attr(i)
            ),
        );
    }
    let s = &plan.summary;
    if s.lowest_capacity.is_finite() && s.lowest_capacity_t_s.is_finite() {
        g.circle(
            lx.map(s.lowest_capacity_t_s / div),
            ly.map(s.lowest_capacity),
            4.0,
            "fill=\"none\" stroke=\"#111111\" stroke-width=\"1.5\"",
        );
    }
    g.end_viewport();
    // labels at the right, apart
    let ends: Vec<f64> = data
        .iter()
        .map(|d| ys.map(d.last().map_or(1.0, |p| p.1)))
        .collect();
    let pos = spread(&ends, 13.0, py0 + 6.0, py0 + ph - 2.0);
    let lx0 = px0 + pw + 8.0;
    for i in 0..hi.len() {
        let colour = COLOURS[i];
        g.line(
            px0 + pw,
            ends[i],
            lx0 + 4.0,
            pos[i],
            &format!("stroke=\"{colour}\" stroke-width=\"0.8\""),
        );
        g.line(
            lx0 + 4.0,
            pos[i],
            lx0 + 24.0,
            pos[i],
            &format!("stroke=\"{colour}\" stroke-width=\"2\"{}", dash_attr(i)),
        );
        g.text(
            lx0 + 28.0,
            pos[i] + 3.5,
            &short(name(i), 40),
            &format!("font-size=\"10.5\" fill=\"{colour}\" font-weight=\"600\""),
        );
    }
    let _ = write!(
        o,
        "<figure class=\"chart\">{}<figcaption>Capacity of the {} muscle groups that fall lowest (each line: the lowest capacity in each of {} time slices; the capacity falls while a group works and rises in the rests). ○ lowest capacity at any time: {} ({}, at {}). {}{}</figcaption></figure>",
        g.finish(),
        hi.len(),
        SLICES,
        pct(s.lowest_capacity),
        esc(plan
            .half_joint(&s.lowest_capacity_half_joint)
            .map(|i| plan.half_joints[i].group.as_str())
            .unwrap_or(&s.lowest_capacity_half_joint)),
        dur(s.lowest_capacity_t_s),
        if grey.is_empty() {
            String::new()
        } else {
            format!("Grey: the next {} groups. ", grey.len())
        },
        match rest
            .iter()
            .map(|c| c.lowest)
            .fold(None, |a: Option<f64>, b| Some(a.map_or(b, |x| x.min(b))))
        {
            Some(m) if !rest.is_empty() => format!(
                "The other {} groups never fall below {}.",
                rest.len(),
                pct(m)
            ),
            _ => String::new(),
        }
    );

    // small multiples
    let cols = 3;
    let rows = hi.len().div_ceil(cols);
    let (cw, chh) = (260.0, 170.0);
    let mut g = Svg::new(
        cw * cols as f64,
        chh * rows as f64,
        "capacity over time, one panel per muscle group",
    );
    g.rect(
        0.0,
        0.0,
        cw * cols as f64,
        chh * rows as f64,
        "fill=\"#ffffff\"",
    );
    for (i, c) in hi.iter().enumerate() {
        let (ox, oy) = ((i % cols) as f64 * cw, (i / cols) as f64 * chh);
        let colour = COLOURS[i];
        g.text(
            ox + 6.0,
            oy + 12.0,
            &short(name(i), 40),
            &format!("font-size=\"10.5\" font-weight=\"600\" fill=\"{colour}\""),
        );
        let sub = format!(
            "lowest {} (at {}) · end {}",
            pct(c.lowest),
            dur(c.lowest_t_s),
            pct(c.end)
        );
        g.text(
            ox + 6.0,
            oy + 24.0,
            &sub,
            "font-size=\"9\" fill=\"#4a5468\"",
        );
        g.text(
            ox + 6.0,
            oy + 35.0,
            &format!("highest load {}", pct(c.max_load)),
            "font-size=\"9\" fill=\"#c62828\"",
        );
        let (ax, ay, aw, ah) = (ox + 30.0, oy + 42.0, cw - 42.0, chh - 62.0);
        let (xs, ys) = axes(&mut g, ax, ay, aw, ah, t_end, 4, false, 8.5);
        g.viewport(ax, ay, aw, ah);
        let (lx, ly) = (local(xs, ax), local(ys, ay));
        let d = &data[i];
        let mut band: Vec<(f64, f64)> =
            d.iter().map(|p| (lx.map(p.0 / div), ly.map(p.2))).collect();
        band.extend(d.iter().rev().map(|p| (lx.map(p.0 / div), ly.map(p.1))));
        g.polygon(
            &band,
            &format!("fill=\"{colour}\" fill-opacity=\"0.25\" stroke=\"none\""),
            None,
        );
        let line: Vec<(f64, f64)> = d.iter().map(|p| (lx.map(p.0 / div), ly.map(p.1))).collect();
        g.polyline(
            &line,
            &format!("stroke=\"{colour}\" stroke-width=\"1.6\"{}", dash_attr(i)),
        );
        if floor.is_finite() && floor > 0.0 && floor < 1.0 {
            let y = ly.map(floor);
            g.line(
                0.0,
                y,
                aw,
                y,
                "stroke=\"#222222\" stroke-width=\"0.8\" stroke-dasharray=\"5 3\"",
            );
        }
        if c.max_load > 0.0 && c.max_load <= 1.2 {
            let y = ly.map(c.max_load.min(1.0));
            g.line(
                0.0,
                y,
                aw,
                y,
                "stroke=\"#c62828\" stroke-width=\"1\" stroke-dasharray=\"1.5 2\"",
            );
        }
        g.end_viewport();
    }
    let _ = write!(
        o,
        "<figure class=\"chart\">{}<figcaption>The same groups one by one: shaded, the range of the capacity within each time slice; black dashed, the capacity floor; red dotted, the group's highest load — a group is exhausted when its capacity falls to the load it holds. Time in {tu}.</figcaption></figure>",
        g.finish()
    );
    o
}
