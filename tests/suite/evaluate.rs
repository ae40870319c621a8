//! Evaluating recorded work (`posture_opt::record`, `posture-opt evaluate`).
//!
//! * a held posture reproduces the Ma et al. (2009) closed forms, with the load worked out here
//!   from the body's masses and lever arms and the MVC from the strength table;
//! * with load-dependent recovery, the evaluation agrees with an independent RK4 integration of
//!   the model's differential equations under the zero-order hold rule;
//! * offline evaluation and streaming (library and command line) agree exactly, and streaming
//!   answers each sample as it arrives;
//! * a plan written as a recording evaluates to the plan's own capacities and fatigue index;
//! * bad recordings exit with code 2, a message that locates the problem, and no output file.

use crate::common;

use common::{Run, bin, rel, tempdir, write};
use nalgebra::Vector3;
use posture_opt::body::{PointLoad, StaticsData, forward_kinematics, holding_torques};
use posture_opt::plan::Task;
use posture_opt::record::{self, Input, Options};
use std::f64::consts::FRAC_PI_2;
use std::io::{BufRead, Write};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

/// Earth's gravity \[m/s²\] (the task format's documented default, (0, 0, −9.81)).
const G: f64 = 9.81;

/// Elbow flexor MVC of the 50th-percentile man at the reference posture (elbow 90°, forearm
/// neutral) \[N·m\]: robots/worker.strength.yaml, `elbow_flexion` "+", male mean 77.0 N·m; at the
/// 50th percentile z = 0, so the MVC is the mean.
const ELBOW_FLEXOR_MVC_NM: f64 = 77.0;

/// The elbow flexors' posture factor at elbow flexion `deg` (forearm neutral), at the grid points
/// of robots/worker.strength.yaml: `deg: [0, 30, 60, 90, 120, 150]`,
/// `factor: [0.60, 0.80, 0.95, 1.00, 0.90, 0.70]`.
fn elbow_flexor_factor(deg: f64) -> f64 {
    match deg as i64 {
        60 => 0.95,
        90 => 1.0,
        120 => 0.90,
        other => panic!("no grid point at {other}°"),
    }
}

/// A task file that only sets up the body and the fatigue parameters for an evaluation.
fn setup_task(dir: &Path, fatigue: &str) -> (std::path::PathBuf, Task) {
    let text = format!(
        "name: evaluation set-up\n\
         worker: {{sex: male, stature_m: 1.755, mass_kg: 78.0}}\n\
         phases:\n  - {{name: unused, target_m: [0.35, -0.2, 1.0], duration_s: 1.0}}\n\
         cycles: 1\n\
         fatigue: {fatigue}\n"
    );
    let p = write(dir, "setup.yaml", text);
    let t = Task::from_file(&p).unwrap();
    (p, t)
}

/// The posture of the recordings below: standing upright, arms hanging, the right elbow flexed
/// by `elbow_rad` (so the forearm points forward at π/2).
fn posture(t: &Task, elbow_rad: f64) -> Vec<f64> {
    let mut q = vec![0.0; t.model.nq()];
    q[t.model.q_index("r_elbow_flexion").unwrap()] = elbow_rad;
    q
}

/// The torque the right elbow must produce to hold posture `q` with `load_kg` in the right hand
/// \[N·m, about the joint's axis\], as a sum of lever arms: every mass the elbow carries and the
/// load at the grip, each `(p − o) × m g`, projected on the joint's axis. Only the kinematics
/// (joint origin and axis, link positions) come from the library.
fn elbow_torque_by_levers(t: &Task, q: &[f64], load_kg: f64) -> f64 {
    let m = &t.model;
    let mut d = StaticsData::new(m, 0);
    forward_kinematics(m, &mut d, q);
    let e = m.q_index("r_elbow_flexion").unwrap();
    let joint = m.joint_of_q[e];
    let (a, o) = (d.axis_w[e], d.origin_w[e]);
    let g = Vector3::new(0.0, 0.0, -G);
    let mut tau = 0.0;
    for (l, link) in m.links.iter().enumerate() {
        if link.mass_kg > 0.0 && m.moves_link(joint, l) {
            let c = d.link_point(m, l, &link.com_m.coords);
            tau -= a.dot(&(c - o).cross(&(link.mass_kg * g)));
        }
    }
    let grip = m
        .links
        .iter()
        .position(|l| l.name == "r_hand_grip")
        .unwrap();
    let p = d.link_point(m, grip, &Vector3::zeros());
    tau -= a.dot(&(p - o).cross(&(load_kg * g)));
    tau
}

/// The same torque at elbow 90° (forearm horizontal) straight from de Leva (1996) Table 4 (male)
/// and the grip at 75 % of the hand, scaled to the worker's stature: a check that the body is
/// the one intended, to the URDF's printed precision.
fn elbow_torque_de_leva_at_90(load_kg: f64) -> f64 {
    let (mass, s) = (78.0, 1.755 / 1.741);
    let (forearm_len, hand_len) = (0.2689 * s, 0.0862 * s);
    let forearm = 0.0162 * mass * 0.4574 * forearm_len;
    let hand = 0.0061 * mass * (forearm_len + 0.79 * hand_len);
    let load = load_kg * (forearm_len + 0.75 * hand_len);
    G * (forearm + hand + load)
}

fn rel_diff(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

fn evaluate_text(t: &Task, text: &str, name: &str) -> record::Evaluation {
    record::evaluate(
        t,
        Input::Csv {
            reader: std::io::Cursor::new(text.as_bytes()),
            name: name.into(),
        },
        &Options::default(),
        None,
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn half_joint(t: &Task, id: &str) -> usize {
    t.half_joints.iter().position(|h| h.id == id).unwrap()
}

#[test]
fn the_load_is_the_elbow_torque_over_the_mvc_worked_out_by_hand() {
    let dir = tempdir();
    let (_, t) = setup_task(dir.path(), "{k_per_min: 0.7}");
    let q = posture(&t, FRAC_PI_2);
    let load_kg = 3.0;
    let by_levers = elbow_torque_by_levers(&t, &q, load_kg);
    // de Leva: the URDF prints masses to 0.1 g and centres to 0.01 mm, so 1e-4 relative
    let by_table = elbow_torque_de_leva_at_90(load_kg);
    assert!(
        rel_diff(by_levers, by_table) < 1e-4,
        "levers {by_levers} vs de Leva {by_table}"
    );
    // the library's statics called directly agree with the lever sum to rounding
    let m = &t.model;
    let mut d = StaticsData::new(m, 1);
    let grip = t.hand_links[0].as_ref().unwrap().0;
    let f = PointLoad::force_at(grip, Vector3::new(0.0, 0.0, -G * load_kg));
    holding_torques(m, &mut d, &q, &[f], &Vector3::new(0.0, 0.0, -G));
    let e = m.q_index("r_elbow_flexion").unwrap();
    assert!(
        rel_diff(d.tau_nm[e], by_levers) < 1e-12,
        "{} vs {by_levers}",
        d.tau_nm[e]
    );
    // holding a weight with the elbow bent loads the flexors (positive direction), and the
    // half-joint's MVC at this posture is the table's reference value
    assert!(by_levers > 0.0);
    let h = half_joint(&t, "r_elbow_flexion+");
    assert!(
        t.half_joints[h].group.contains("elbow flexors"),
        "{}",
        t.half_joints[h].group
    );
    assert!(rel_diff(t.half_joints[h].mvc_at(&q), ELBOW_FLEXOR_MVC_NM) < 1e-12);
}

#[test]
fn a_held_posture_follows_the_closed_forms_without_recovery() {
    let dir = tempdir();
    // legacy form: one k for every group, no recovery (Ma et al. 2009 exactly)
    let k = 0.7;
    let (_, t) = setup_task(dir.path(), &format!("{{k_per_min: {k}}}"));
    let q = posture(&t, FRAC_PI_2);
    let load_kg = 3.0;
    let f = elbow_torque_by_levers(&t, &q, load_kg) / ELBOW_FLEXOR_MVC_NM;
    assert!(f > 0.1 && f < 0.5, "f = {f}");
    // held for 20 minutes, sampled irregularly; every sample repeats the posture and the load
    let times = [0.0, 0.7, 3.0, 61.3, 200.0, 450.25, 899.0, 1200.0];
    let mut rec = String::from("t_s,r_elbow_flexion,load_kg\n");
    for s in times {
        rec.push_str(&format!("{s},{},{load_kg}\n", FRAC_PI_2));
    }
    let ev = evaluate_text(&t, &rec, "held.csv");
    let (flex, ext) = (
        half_joint(&t, "r_elbow_flexion+"),
        half_joint(&t, "r_elbow_flexion-"),
    );
    assert_eq!(ev.samples, times.len() as u64);
    assert_eq!(ev.timeline.stride, 1);
    assert_eq!(ev.timeline.t_s, times.to_vec());
    for (i, &s) in times.iter().enumerate() {
        let tl = &ev.timeline;
        assert!(
            rel_diff(tl.load[i][flex], f) < 1e-12,
            "load {} vs {f}",
            tl.load[i][flex]
        );
        assert_eq!(tl.load[i][ext], 0.0, "the extensors hold nothing");
        let t_min = s / 60.0;
        let c = (-k * f * t_min).exp();
        let u = ((2.0 * k * f * t_min).exp() - 1.0) / (2.0 * k);
        // the program composes per-interval exact updates; the closed form is one expression:
        // they differ by rounding only
        assert!(
            rel_diff(tl.capacity[i][flex], c) < 1e-12,
            "t = {s}: c {} vs {c}",
            tl.capacity[i][flex]
        );
        if s == 0.0 {
            assert_eq!(tl.fatigue_u_min[i][flex], 0.0);
        } else {
            assert!(
                rel_diff(tl.fatigue_u_min[i][flex], u) < 1e-12,
                "t = {s}: U {} vs {u}",
                tl.fatigue_u_min[i][flex]
            );
        }
    }
    assert!(rel_diff(ev.final_capacity[flex], (-k * f * 20.0).exp()) < 1e-12);
    assert!(
        rel_diff(
            ev.final_fatigue_u_min[flex],
            ((2.0 * k * f * 20.0).exp() - 1.0) / (2.0 * k)
        ) < 1e-12
    );
    // exhaustion when c = f: MET = −ln f / (k f) minutes (paper Eq. 8), inside an interval
    let met_s = -f.ln() / (k * f) * 60.0;
    assert!(met_s > 450.25 && met_s < 1200.0, "MET {met_s} s");
    let e = ev
        .exhaustions
        .iter()
        .find(|e| e.half_joint == "r_elbow_flexion+")
        .expect("the elbow flexors exhaust");
    assert!(
        rel_diff(e.t_s, met_s) < 1e-9,
        "exhausted at {} s, MET {met_s} s",
        e.t_s
    );
    assert!(!e.exceeds_capacity_at_start);
    assert!(rel_diff(e.load, f) < 1e-12);
    // total U is the sum over groups
    let sum: f64 = ev.final_fatigue_u_min.iter().sum();
    assert!(rel_diff(ev.total_u_min, sum) < 1e-12);
}

/// RK4 of `dc/dt = −k f c + R(f)(1 − c)`, `dU/dt = f / c²` (t in minutes) over `dt_s` from
/// `(c, u)` with `n` steps.
fn rk4(k: f64, r: f64, f: f64, c: f64, u: f64, dt_s: f64, n: usize) -> (f64, f64) {
    let rhs = |c: f64| (-k * f * c + r * (1.0 - c), f / (c * c));
    let h = dt_s / 60.0 / n as f64;
    let (mut c, mut u) = (c, u);
    for _ in 0..n {
        let k1 = rhs(c);
        let k2 = rhs(c + 0.5 * h * k1.0);
        let k3 = rhs(c + 0.5 * h * k2.0);
        let k4 = rhs(c + h * k3.0);
        c += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        u += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
    }
    (c, u)
}

#[test]
fn with_recovery_the_evaluation_matches_an_independent_integration() {
    let dir = tempdir();
    // perfusion-limited recovery R(f) = R_rest x² (3 − 2x), x = 1 − f / f_lim (0 from f_lim up)
    let (k, r_rest, f_lim) = (0.9, 0.5, 0.25);
    let (_, t) = setup_task(
        dir.path(),
        &format!("{{k_per_min: {k}, recovery: {{rest_per_min: {r_rest}, limit_fmvc: {f_lim}}}}}"),
    );
    let recovery = |f: f64| {
        let x = 1.0 - f / f_lim;
        if x > 0.0 {
            r_rest * x * x * (3.0 - 2.0 * x)
        } else {
            0.0
        }
    };
    // (time [s], elbow [deg], load [kg]): work, rest with the forearm held up, other angles
    let rows = [
        (0.0, 90.0, 4.0),
        (45.0, 90.0, 0.0),
        (75.5, 120.0, 2.0),
        (140.0, 60.0, 6.0),
        (180.0, 90.0, 0.0),
        (300.0, 90.0, 5.0),
        (333.3, 120.0, 1.0),
        (400.0, 90.0, 0.0),
    ];
    let mut rec = String::from("t_s,r_elbow_flexion,load_kg\n");
    for (s, deg, kg) in rows {
        rec.push_str(&format!("{s},{},{kg}\n", f64::to_radians(deg)));
    }
    let ev = evaluate_text(&t, &rec, "intermittent.csv");
    let h = half_joint(&t, "r_elbow_flexion+");
    let loads: Vec<f64> = rows
        .iter()
        .map(|&(_, deg, kg)| {
            let q = posture(&t, deg.to_radians());
            elbow_torque_by_levers(&t, &q, kg) / (ELBOW_FLEXOR_MVC_NM * elbow_flexor_factor(deg))
        })
        .collect();
    // the recording spans loads with full, partial and no recovery
    assert!(
        loads.iter().any(|&f| f > f_lim) && loads.iter().any(|&f| f < 0.5 * f_lim),
        "{loads:?}"
    );
    let (mut c, mut u) = (1.0, 0.0);
    for i in 0..rows.len() {
        let tl = &ev.timeline;
        assert_eq!(tl.t_s[i], rows[i].0);
        assert!(
            rel_diff(tl.load[i][h], loads[i]) < 1e-12,
            "sample {i}: load {} vs {}",
            tl.load[i][h],
            loads[i]
        );
        // RK4 with 0.01 s steps: error ~ (λh)⁴ per unit time, λ < 1.5/min, h < 2e-4 min
        assert!(
            rel_diff(tl.capacity[i][h], c) < 1e-10,
            "sample {i}: c {} vs {c}",
            tl.capacity[i][h]
        );
        if u > 0.0 {
            assert!(
                rel_diff(tl.fatigue_u_min[i][h], u) < 1e-10,
                "sample {i}: U {} vs {u}",
                tl.fatigue_u_min[i][h]
            );
        }
        if let Some(next) = rows.get(i + 1) {
            // zero-order hold: sample i's load acts until sample i + 1
            let dt = next.0 - rows[i].0;
            (c, u) = rk4(
                k,
                recovery(loads[i]),
                loads[i],
                c,
                u,
                dt,
                (dt / 0.01).ceil() as usize,
            );
        }
    }
    assert!(rel_diff(ev.final_capacity[h], c) < 1e-10);
    assert!(rel_diff(ev.final_fatigue_u_min[h], u) < 1e-10);
    // recovery did act: without it capacity would be lower
    let mut c_none = 1.0;
    for i in 0..rows.len() - 1 {
        c_none *= (-k * loads[i] * (rows[i + 1].0 - rows[i].0) / 60.0).exp();
    }
    assert!(c > c_none + 0.01, "with recovery {c}, without {c_none}");
}

/// A number passed through JSON text and back, as a value printed by the program is.
fn via_json(x: f64) -> f64 {
    serde_json::from_str(&serde_json::to_string(&x).unwrap()).unwrap()
}

/// A reader that hands out at most `n` bytes per read, like a pipe fed piecemeal.
struct Trickle<'a> {
    data: &'a [u8],
    n: usize,
}

impl std::io::Read for Trickle<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let k = self.n.min(buf.len()).min(self.data.len());
        buf[..k].copy_from_slice(&self.data[..k]);
        self.data = &self.data[k..];
        Ok(k)
    }
}

#[test]
fn offline_and_streaming_agree_exactly_in_the_library() {
    let t = record::default_setup(posture_opt::body::Worker::MALE_50, None).unwrap();
    let text = std::fs::read_to_string(rel("recordings/shelf_plan.csv")).unwrap();
    let ev = evaluate_text(&t, &text, "shelf_plan.csv");
    assert!(ev.samples > 1000);
    assert_eq!(ev.timeline.stride, 1, "every sample is in the timeline");
    for n in [usize::MAX, 7] {
        let mut out = Vec::new();
        let count = record::stream(
            &t,
            Trickle {
                data: text.as_bytes(),
                n,
            },
            "stdin",
            &Options::default(),
            &mut out,
        )
        .unwrap();
        assert_eq!(count, ev.samples);
        let lines: Vec<serde_json::Value> = out
            .split(|b| *b == b'\n')
            .filter(|l| !l.is_empty())
            .map(|l| serde_json::from_slice(l).unwrap())
            .collect();
        assert_eq!(
            lines.len() as u64,
            ev.samples + 1,
            "a first line naming the columns, then one per sample"
        );
        let ids: Vec<&str> = lines[0]["half_joint_ids"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap())
            .collect();
        assert_eq!(
            ids,
            ev.half_joint_ids
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>()
        );
        let mut events = 0;
        for (i, l) in lines[1..].iter().enumerate() {
            assert_eq!(l["t_s"].as_f64().unwrap(), via_json(ev.timeline.t_s[i]));
            for h in 0..ids.len() {
                assert_eq!(
                    l["capacity"][h].as_f64().unwrap(),
                    via_json(ev.timeline.capacity[i][h]),
                    "sample {i} {}",
                    ids[h]
                );
                assert_eq!(
                    l["fatigue_u_min"][h].as_f64().unwrap(),
                    via_json(ev.timeline.fatigue_u_min[i][h]),
                    "sample {i} {}",
                    ids[h]
                );
            }
            events += l["exhausted"].as_array().unwrap().len();
        }
        assert_eq!(events, ev.exhaustions.len());
        let last = lines.last().unwrap();
        for h in 0..ids.len() {
            assert_eq!(
                last["capacity"][h].as_f64().unwrap(),
                via_json(ev.final_capacity[h])
            );
            assert_eq!(
                last["fatigue_u_min"][h].as_f64().unwrap(),
                via_json(ev.final_fatigue_u_min[h])
            );
        }
    }
    // the recording did fatigue someone: the comparison is not between fresh states
    assert!(
        ev.final_capacity.iter().any(|&c| c < 0.99),
        "{:?}",
        ev.final_capacity
    );
}

#[test]
fn offline_and_streaming_agree_exactly_on_the_command_line() {
    let path = rel("recordings/shelf_plan.csv");
    let text = std::fs::read(&path).unwrap();
    let off = Run::new(&["evaluate", path.as_str(), "--json"]).go();
    off.ok();
    let off = off.json();
    let live = Run::new(&["evaluate", "--stream"]).stdin(text).go();
    live.ok();
    let lines: Vec<serde_json::Value> = live
        .stdout_text()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let n = off["samples"].as_u64().unwrap() as usize;
    assert_eq!(lines.len(), n + 1);
    assert_eq!(off["timeline"]["stride"].as_u64(), Some(1));
    let nh = off["half_joint_ids"].as_array().unwrap().len();
    assert_eq!(lines[0]["half_joint_ids"], off["half_joint_ids"]);
    for i in 0..n {
        let l = &lines[i + 1];
        assert_eq!(l["t_s"], off["timeline"]["t_s"][i]);
        for h in 0..nh {
            assert_eq!(
                l["capacity"][h], off["timeline"]["capacity"][i][h],
                "sample {i}, half-joint {h}"
            );
            assert_eq!(
                l["fatigue_u_min"][h], off["timeline"]["fatigue_u_min"][i][h],
                "sample {i}, half-joint {h}"
            );
        }
    }
    assert_eq!(lines[n]["capacity"], off["final_capacity"]);
    assert_eq!(lines[n]["fatigue_u_min"], off["final_fatigue_u_min"]);
}

#[test]
fn streaming_answers_each_sample_before_the_next_arrives() {
    let mut child = Command::new(bin())
        .args(["evaluate", "--stream"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let stdout = child.stdout.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(stdout).lines() {
            if tx.send(line.unwrap()).is_err() {
                break;
            }
        }
    });
    let wait = Duration::from_secs(30);
    stdin.write_all(b"t_s,r_elbow_flexion,load_kg\n").unwrap();
    stdin.flush().unwrap();
    let head: serde_json::Value =
        serde_json::from_str(&rx.recv_timeout(wait).expect("the column line")).unwrap();
    let ids = head["half_joint_ids"].as_array().unwrap();
    let h = ids.iter().position(|v| v == "r_elbow_flexion+").unwrap();
    let mut previous = 1.0;
    for (i, s) in [0.0, 0.5, 1.25, 30.0].iter().enumerate() {
        stdin.write_all(format!("{s},1.2,3\n").as_bytes()).unwrap();
        stdin.flush().unwrap();
        // the answer must come while standard input stays open
        let l = rx
            .recv_timeout(wait)
            .unwrap_or_else(|_| panic!("no answer to sample {i} within {wait:?}"));
        let v: serde_json::Value = serde_json::from_str(&l).unwrap();
        assert_eq!(v["t_s"].as_f64().unwrap(), *s, "sample {i}");
        let c = v["capacity"][h].as_f64().unwrap();
        if i == 0 {
            assert_eq!(c, 1.0);
        } else {
            assert!(
                c < previous,
                "holding 3 kg wears the elbow flexors down: {c} after {previous}"
            );
        }
        previous = c;
    }
    drop(stdin);
    assert!(child.wait().unwrap().success());
}

/// Seconds apart that are not binary fractions, two phases and a rest (re-planned as capacity
/// falls where a re-plan lowers the fatigue): the recording has several postures and irregular
/// steps.
const PLAN_TASK: &str = "name: two holds
worker: {sex: male, stature_m: 1.755, mass_kg: 78.0}
phases:
  - {name: hold, target_m: [0.35, -0.2, 1.0], load_kg: 4.0, duration_s: 20.1}
  - {name: high, target_m: [0.30, -0.25, 1.35], load_kg: 2.0, duration_s: 12.3}
rest_s: 7.7
cycles: 4
";

#[test]
fn a_plan_written_as_a_recording_evaluates_to_the_plans_own_fatigue() {
    let dir = tempdir();
    let task = write(dir.path(), "task.yaml", PLAN_TASK);
    let rec = dir.path().join("plan.csv");
    let (task_s, rec_s) = (task.display().to_string(), rec.display().to_string());
    let plan = Run::new(&[
        "plan",
        task_s.as_str(),
        "--recording",
        rec_s.as_str(),
        "--json",
    ])
    .go();
    plan.ok();
    let p = plan.json();
    let ev = Run::new(&[
        "evaluate",
        rec_s.as_str(),
        "--task",
        task_s.as_str(),
        "--json",
    ])
    .go();
    ev.ok();
    let e = ev.json();
    let s = &p["summary"];
    assert!(
        s["exhaustion"].is_null(),
        "the plan must run its course for the comparison"
    );
    // the two phases' postures and the rest posture at least
    let distinct: std::collections::BTreeSet<u64> = p["steps"]["posture"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .collect();
    assert!(
        distinct.len() >= 3,
        "the recording should hold several postures"
    );
    assert_eq!(p["half_joint_ids"], e["half_joint_ids"]);
    let steps = &p["steps"];
    let n_steps = steps["t_s"].as_array().unwrap().len();
    assert_eq!(n_steps, 4 * 3);
    // one sample at the start of every step, and one at the end of the last
    assert_eq!(e["samples"].as_u64().unwrap() as usize, n_steps + 1);
    assert!(e["exhaustions"].as_array().unwrap().is_empty());
    assert_eq!(e["samples_outside_range"].as_u64(), Some(0));
    // The plan holds each step's posture and loads for its duration with the model's exact
    // closed forms; the evaluator holds sample i's posture and loads until sample i + 1 with the
    // same closed forms. The loads are recomputed from the same posture (printed exactly) and
    // hand forces, so they agree to the bit; the only difference is that the evaluator's step is
    // t(i+1) − t(i) of the printed cumulative times rather than the phase's duration, which
    // differ by a few ulps of the elapsed time (< 1e-13 s here). Capacity and U move by about
    // λ·dt/60 per unit of dt (λ ≲ 1/min), so relative differences stay near 1e-16; 1e-12 leaves
    // room for rounding and would still catch a wrong load, hold rule or time step (≥ 1e-4).
    let tol = 1e-12;
    let nh = p["half_joint_ids"].as_array().unwrap().len();
    let num = |v: &serde_json::Value| v.as_f64().unwrap();
    for h in 0..nh {
        let (a, b) = (num(&s["final_capacity"][h]), num(&e["final_capacity"][h]));
        assert!(
            rel_diff(b, a) < tol,
            "final capacity of {}: plan {a}, evaluation {b}",
            p["half_joint_ids"][h]
        );
    }
    let (a, b) = (num(&s["total_u"]), num(&e["total_u_min"]));
    assert!(
        a > 0.0 && rel_diff(b, a) < tol,
        "total U: plan {a}, evaluation {b}"
    );
    assert!(rel_diff(num(&e["duration_s"]), num(&s["duration_s"])) < tol);
    // step by step: the sample after step i carries the state at the step's end, and sample i
    // the step's loads
    let tl = &e["timeline"];
    assert_eq!(tl["stride"].as_u64(), Some(1));
    for i in 0..n_steps {
        assert_eq!(num(&tl["t_s"][i]), num(&steps["t_s"][i]));
        let posture = steps["posture"][i].as_u64().unwrap() as usize;
        for h in 0..nh {
            let (a, b) = (
                num(&steps["capacity"][i][h]),
                num(&tl["capacity"][i + 1][h]),
            );
            assert!(
                rel_diff(b, a) < tol,
                "step {i}, half-joint {h}: capacity {a} vs {b}"
            );
            let (a, b) = (
                num(&steps["fatigue_u_min"][i][h]),
                num(&tl["fatigue_u_min"][i + 1][h]),
            );
            assert!(
                (b - a).abs() <= tol * a.abs(),
                "step {i}, half-joint {h}: U {a} vs {b}"
            );
            let (a, b) = (
                num(&p["postures"][posture]["load"][h]),
                num(&tl["load"][i][h]),
            );
            assert_eq!(a, b, "step {i}, half-joint {h}: load");
        }
    }
}

/// Runs `posture-opt evaluate FILE --csv OUT` on a bad recording in a fresh directory: exit 2,
/// the message contains every needle and the file's path, and nothing is written.
fn refused(name: &str, text: &str, needles: &[&str]) {
    let dir = tempdir();
    let file = write(dir.path(), name, text);
    let out = dir.path().join("out.csv");
    let (file_s, out_s) = (file.display().to_string(), out.display().to_string());
    let o = Run::new(&["evaluate", file_s.as_str(), "--csv", out_s.as_str()]).go();
    let mut all = vec![file_s.as_str()];
    all.extend_from_slice(needles);
    o.bad(&all);
    assert!(
        !out.exists(),
        "{name}: an output was written for a bad recording"
    );
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        left,
        vec![std::ffi::OsString::from(name)],
        "{name}: files left behind"
    );
}

#[test]
fn bad_recordings_are_located_and_nothing_is_written() {
    let head = "t_s,r_elbow_flexion,load_kg\n";
    // time that does not increase: the message names the line and the column
    refused(
        "repeat.csv",
        &format!("{head}0,0.5,1\n1,0.5,2\n1,0.5,2\n"),
        &["line 4", "column 1 (time)", "does not increase"],
    );
    refused(
        "back.csv",
        &format!("{head}0,0.5,1\n-1,0.5,2\n"),
        &["line 3", "column 1 (time)", "does not increase"],
    );
    // not-a-number, infinite, not a number, empty
    refused(
        "nan.csv",
        &format!("{head}0,0.5,1\n1,NaN,2\n"),
        &["line 3, column 2 (r_elbow_flexion)", "not finite"],
    );
    refused(
        "inf.csv",
        &format!("{head}0,0.5,1\n1,0.5,inf\n"),
        &["line 3, column 3 (load_kg)", "not finite"],
    );
    refused(
        "word.csv",
        &format!("{head}0,abc,1\n"),
        &[
            "line 2, column 2 (r_elbow_flexion)",
            "'abc' is not a number",
        ],
    );
    refused(
        "empty_cell.csv",
        &format!("{head}0,0.5,1\n1,0.5,\n"),
        &["line 3, column 3 (load_kg)", "missing value"],
    );
    refused(
        "nan_time.csv",
        &format!("{head}0,0.5,1\nNaN,0.5,2\n"),
        &["line 3, column 1 (t_s)", "not finite"],
    );
    // wrong column names
    refused(
        "typo.csv",
        "t_s,r_elbw_flexion,load_kg\n0,0.5,1\n",
        &[
            "line 1",
            "column 2",
            "r_elbw_flexion",
            "did you mean 'r_elbow_flexion'",
        ],
    );
    refused(
        "knee.csv",
        "t_s,r_knee,load_kg\n0,0.5,1\n",
        &["line 1", "column 2", "'r_knee'"],
    );
    refused(
        "first.csv",
        "time_s,r_elbow_flexion,load_kg\n0,0.5,1\n",
        &["line 1", "first column", "t_s", "'time_s'"],
    );
    refused(
        "twice.csv",
        "t_s,r_elbow_flexion,r_elbow_flexion\n0,0.5,0.5\n",
        &["line 1", "column 3", "twice"],
    );
    // missing columns: a row too short, a force without all three components
    refused(
        "short.csv",
        &format!("{head}0,0.5,1\n1,0.5\n"),
        &["line 3, column 3 (load_kg)", "missing value"],
    );
    refused(
        "force.csv",
        "t_s,r_elbow_flexion,force_x_n,force_z_n\n0,0.5,0,-10\n",
        &["line 1", "force", "three columns"],
    );
    refused(
        "long.csv",
        &format!("{head}0,0.5,1\n1,0.5,1,7\n"),
        &["line 3", "more values"],
    );
    // degrees written where radians are read
    let degrees = format!("{head}0,30,1\n1,90,2\n2,120,2\n");
    refused(
        "degrees.csv",
        &degrees,
        &["line 2", "r_elbow_flexion", "30", "--degrees"],
    );
    refused("nothing.csv", head, &["no samples"]);
    // the same file with --degrees is fine, and then the output is written (one row per sample)
    let dir = tempdir();
    let file = write(dir.path(), "degrees.csv", &degrees);
    let out = dir.path().join("out.csv");
    let (file_s, out_s) = (file.display().to_string(), out.display().to_string());
    Run::new(&[
        "evaluate",
        file_s.as_str(),
        "--degrees",
        "--csv",
        out_s.as_str(),
    ])
    .go()
    .ok();
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(
        written.starts_with("t_s,capacity_"),
        "{}",
        &written[..written.len().min(200)]
    );
    assert_eq!(written.lines().count(), 4);
}

#[test]
fn bad_samples_are_located_in_the_library_and_on_standard_input() {
    use posture_opt::record::RecordingError;
    use posture_opt::record::run::RunError;
    let t = record::default_setup(posture_opt::body::Worker::MALE_50, None).unwrap();
    let r = record::evaluate(
        &t,
        Input::Csv {
            reader: std::io::Cursor::new(
                "t_s,r_elbow_flexion,load_kg\n0,0.5,1\n1,NaN,2\n".as_bytes(),
            ),
            name: "r.csv".into(),
        },
        &Options::default(),
        None,
    );
    match r {
        Err(RunError::Recording(RecordingError::Cell {
            source_name,
            line,
            column,
            name,
            ..
        })) => {
            assert_eq!(
                (source_name.as_str(), line, column, name.as_str()),
                ("r.csv", 3, 2, "r_elbow_flexion")
            );
        }
        other => panic!(
            "expected a located cell error, got {:?}",
            other.map(|e| e.samples)
        ),
    }
    // live: the samples before the bad one are answered, then exit 2 naming the line
    let o = Run::new(&["evaluate", "--stream"])
        .stdin("t_s,r_elbow_flexion,load_kg\n0,0.5,1\n1,0.5,1\n0.5,0.5,1\n")
        .go();
    o.bad(&["stdin: line 4", "column 1 (time)", "does not increase"]);
    assert_eq!(
        o.stdout_text().lines().count(),
        3,
        "column line and two samples before the bad one"
    );
}
