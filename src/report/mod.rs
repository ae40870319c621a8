//! Plan outputs: the human summary and the CSV timeline (JSON is the serde form of [`Plan`]).

pub mod figures;
pub mod html;

use crate::plan::Plan;
use crate::rest::RestAdvice;
use serde::Serialize;
use std::fmt::Write;

/// The `plan --json` document: the plan (DESIGN §6) with the work/rest advice added.
#[derive(Serialize)]
pub struct PlanDocument<'a> {
    #[serde(flatten)]
    pub plan: &'a Plan,
    pub rest: &'a RestAdvice,
}

/// Work/rest advice as text lines.
pub fn rest_summary(r: &RestAdvice) -> String {
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
                "  model (recovery): {x:.1} s of rest per cycle keeps every capacity >= {:.2} (lowest now {:.2}, {})",
                r.capacity_floor, r.model.min_capacity_current, r.model.limiting_half_joint
            );
        }
        None => {
            let _ = writeln!(o, "  model (recovery): {}", r.model.note);
        }
    }
    let _ = writeln!(
        o,
        "  Rohmert (1973) rest allowance: {:.1} s per cycle{}",
        r.rohmert.rest_s_per_cycle,
        if r.rohmert.limiting_half_joint.is_empty() {
            String::new()
        } else {
            format!(" ({})", r.rohmert.limiting_half_joint)
        }
    );
    o
}

/// A readable summary: per phase posture and most-loaded groups, capacity at the end, time to
/// exhaustion if any, total U against the baseline.
pub fn plan_summary(p: &Plan) -> String {
    let s = &p.summary;
    let mut o = String::new();
    let _ = writeln!(
        o,
        "{} — {} plan, {} ({}), hand frame {}",
        p.task,
        if s.adaptive {
            "fatigue-adaptive"
        } else {
            "baseline (no adaptation)"
        },
        p.fatigue_model,
        p.robot,
        p.hand_frame
    );
    let _ = writeln!(o, "planned {:.0} s, simulated {:.0} s ({} cycles), {} re-plans, {} QP solves, {} SQP iterations\n", s.planned_duration_s, s.duration_s, s.cycles_done, s.replans, s.qp_solves, s.sqp_iterations);
    for ph in &s.phases {
        let _ = writeln!(
            o,
            "phase '{}': hand error {:.1} mm{}, clearance {:.0} mm{}",
            ph.phase,
            ph.hand_error_m * 1000.0,
            if ph.reachable {
                ""
            } else {
                " — TARGET OUT OF REACH: nearest reachable posture"
            },
            ph.min_clearance_m * 1000.0,
            ph.rula
                .as_ref()
                .map(|r| format!(
                    ", RULA {} (action level {}: {})",
                    r.grand_score, r.action_level, r.action
                ))
                .unwrap_or_default()
        );
        let q: Vec<String> = ph
            .q_rad
            .iter()
            .filter(|(_, v)| v.abs() > 0.005)
            .map(|(k, v)| format!("{k} {:.0}°", v.to_degrees()))
            .collect();
        let _ = writeln!(
            o,
            "  posture: {}",
            if q.is_empty() {
                "neutral".into()
            } else {
                q.join(", ")
            }
        );
        let l: Vec<String> = ph
            .most_loaded
            .iter()
            .map(|(h, f)| format!("{h} {:.0}%", 100.0 * f))
            .collect();
        let _ = writeln!(o, "  most loaded: {}", l.join(", "));
    }
    if let Some(last) = p.steps.last() {
        let mut caps: Vec<(&String, &f64)> = last.capacity.iter().collect();
        caps.sort_by(|a, b| a.1.total_cmp(b.1));
        let c: Vec<String> = caps
            .iter()
            .take(5)
            .map(|(h, c)| format!("{h} {:.2}", c))
            .collect();
        let _ = writeln!(o, "\nlowest capacities at the end: {}", c.join(", "));
    }
    match &s.exhaustion {
        Some(e) => {
            let _ = writeln!(
                o,
                "EXHAUSTION at {:.0} s: {} ({}) can no longer hold {:.0}% MVC in phase '{}'",
                e.t_s,
                e.half_joint,
                e.group,
                100.0 * e.load,
                e.phase
            );
        }
        None => {
            let _ = writeln!(o, "no muscle group exhausted");
        }
    }
    let _ = write!(
        o,
        "total fatigue index U = {:.2} min (worst: {} {:.2} min)",
        s.total_u, s.worst_half_joint, s.worst_u
    );
    if let (Some(b), Some(c)) = (s.baseline_total_u, s.change_vs_baseline) {
        let _ = write!(o, "; baseline {:.2} min ({:+.1}%)", b, 100.0 * c);
        if let Some(te) = s.baseline_exhaustion_t_s {
            let _ = write!(
                o,
                "\nthe baseline exhausts at {te:.0} s: totals cover different durations"
            );
        }
    }
    let _ = writeln!(o);
    o
}

/// The timeline as CSV: one row per step; q, torque, capacity and U columns per joint/half-joint.
pub fn plan_csv(p: &Plan) -> String {
    let mut o = String::new();
    let Some(first) = p.steps.first() else {
        return o;
    };
    let joints: Vec<&String> = first.q_rad.keys().collect();
    let hjs: Vec<&String> = first.capacity.keys().collect();
    let _ = write!(
        o,
        "t_s,duration_s,cycle,phase,hand_x_m,hand_y_m,hand_z_m,force_x_n,force_y_n,force_z_n"
    );
    for j in &joints {
        let _ = write!(o, ",q_{j}_rad");
    }
    for j in &joints {
        let _ = write!(o, ",torque_{j}_nm");
    }
    for h in &hjs {
        let _ = write!(o, ",load_{h},capacity_{h},u_{h}_min");
    }
    let _ = writeln!(o);
    for s in &p.steps {
        let _ = write!(
            o,
            "{},{},{},\"{}\",{},{},{},{},{},{}",
            s.t_s,
            s.duration_s,
            s.cycle,
            s.phase.replace('"', "\"\""),
            s.hand_position_m[0],
            s.hand_position_m[1],
            s.hand_position_m[2],
            s.hand_force_n[0],
            s.hand_force_n[1],
            s.hand_force_n[2]
        );
        for j in &joints {
            let _ = write!(o, ",{}", s.q_rad[*j]);
        }
        for j in &joints {
            let _ = write!(o, ",{}", s.torque_nm[*j]);
        }
        for h in &hjs {
            let _ = write!(o, ",{},{},{}", s.load[*h], s.capacity[*h], s.fatigue_u[*h]);
        }
        let _ = writeln!(o);
    }
    o
}

/// The plan as a recording for `posture-opt evaluate`: one sample at the start of every step
/// (its posture and hand force) and a closing sample at the end of the last step, so that under
/// the zero-order hold each step's load acts for exactly its duration.
pub fn plan_recording_csv(p: &Plan) -> String {
    let mut o = String::new();
    let Some(first) = p.steps.first() else {
        return o;
    };
    let joints: Vec<&String> = first.q_rad.keys().collect();
    o.push_str("t_s");
    for j in &joints {
        let _ = write!(o, ",{j}");
    }
    o.push_str(",force_x_n,force_y_n,force_z_n\n");
    let row = |o: &mut String, t: f64, s: &crate::plan::Step| {
        let _ = write!(o, "{t}");
        for j in &joints {
            let _ = write!(o, ",{}", s.q_rad[*j]);
        }
        let _ = writeln!(
            o,
            ",{},{},{}",
            s.hand_force_n[0], s.hand_force_n[1], s.hand_force_n[2]
        );
    };
    for s in &p.steps {
        row(&mut o, s.t_s, s);
    }
    let last = p.steps.last().expect("non-empty");
    row(&mut o, last.t_s + last.duration_s, last);
    o
}
