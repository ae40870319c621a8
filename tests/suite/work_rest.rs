//! Work and rest: Rohmert's rule against the published formula worked by hand, and the recovery
//! model's recommended rest checked by an independent numerical integration of
//! `dc/dt = −k f c + R(f) (1 − c)` (RK4, 10 ms steps) over the plan's cycles.
//!
//! The tasks are tiny one-phase holds of the generated worker (planning takes seconds).

use posture_opt::assess::rest::{
    RestAdvice, rest_advice, rohmert_allowance, rohmert_endurance_min,
};
use posture_opt::fatigue::Recovery;
use posture_opt::plan::{Plan, PlanOptions, Task, plan_task_with};

/// A one-phase task: the right hand holds `load_kg` at a comfortable target for `hold_s`,
/// `cycles` times, with `rest_s` of rest, and the given `fatigue:` section (YAML flow map).
fn hold_task(load_kg: f64, hold_s: f64, rest_s: f64, cycles: u32, fatigue: &str) -> String {
    format!(
        "name: held box\nworker: {{sex: male, stature_m: 1.755, mass_kg: 78.0}}\nphases:\n  - {{name: hold, target_m: [0.35, -0.2, 1.0], load_kg: {load_kg}, duration_s: {hold_s}}}\nrest_s: {rest_s}\ncycles: {cycles}\nfatigue: {fatigue}\n"
    )
}

fn plan_text(text: &str) -> (Task, Plan) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("task.yaml");
    std::fs::write(&path, text).unwrap();
    let task = Task::from_file(&path).unwrap();
    let opts = PlanOptions {
        baselines: false,
        ..Default::default()
    };
    let plan = plan_task_with(&task, opts).unwrap();
    (task, plan)
}

// ---------------------------------------------------------------------------------------------
// Rohmert (1973), as commonly cited: endurance T(f) = −1.5 + 2.1/f − 0.6/f² + 0.1/f³ [min] and
// rest allowance RA = 18 · (t/T)^1.4 · (f − 0.15)^0.5, a fraction of the hold time t (×100 for
// per cent), none at or below 15 % MVC.

fn rohmert_t_min(f: f64) -> f64 {
    -1.5 + 2.1 / f - 0.6 / f.powi(2) + 0.1 / f.powi(3)
}

fn rohmert_rest_s(f: f64, hold_s: f64) -> f64 {
    if f <= 0.15 {
        return 0.0;
    }
    18.0 * (hold_s / 60.0 / rohmert_t_min(f)).powf(1.4) * (f - 0.15).sqrt() * hold_s
}

#[test]
fn rohmert_formula_by_hand() {
    // T(0.5) = −1.5 + 4.2 − 2.4 + 0.8 = 1.1 min; T(1) = −1.5 + 2.1 − 0.6 + 0.1 = 0.1 min.
    assert!((rohmert_endurance_min(0.5) - 1.1).abs() < 1e-12);
    assert!((rohmert_endurance_min(1.0) - 0.1).abs() < 1e-12);
    // T(0.25) = −1.5 + 8.4 − 9.6 + 6.4 = 3.7 min.
    assert!((rohmert_endurance_min(0.25) - 3.7).abs() < 1e-12);
    // A hold as long as the endurance time: RA = 18 · 1 · √0.35.
    let ra = rohmert_allowance(0.5, 66.0).unwrap();
    assert!((ra - 18.0 * 0.35_f64.sqrt()).abs() < 1e-9, "{ra}");
    // Half of it: 18 · 0.5^1.4 · √0.35.
    let ra = rohmert_allowance(0.5, 33.0).unwrap();
    assert!(
        (ra - 18.0 * 0.5_f64.powf(1.4) * 0.35_f64.sqrt()).abs() < 1e-9,
        "{ra}"
    );
    // 25 % MVC held 37 s = T/6: 18 · (1/6)^1.4 · √0.10.
    let ra = rohmert_allowance(0.25, 37.0).unwrap();
    assert!(
        (ra - 18.0 * (1.0_f64 / 6.0).powf(1.4) * 0.1_f64.sqrt()).abs() < 1e-9,
        "{ra}"
    );
    // At or below 15 % MVC no rest, whatever the hold; above MVC no answer.
    assert_eq!(rohmert_allowance(0.15, 600.0), Some(0.0));
    assert_eq!(rohmert_allowance(0.05, 3600.0), Some(0.0));
    assert_eq!(rohmert_allowance(1.2, 1.0), None);
}

/// Rohmert's rest per cycle for a plan, worked out from the plan's held steps: per group, the sum
/// over a cycle's holds of RA·t, the largest cycle; the plan needs its largest group's.
fn rohmert_by_hand(plan: &Plan) -> Vec<(String, f64)> {
    let st = &plan.steps;
    let nh = plan.half_joint_ids.len();
    let n_cycles = st.cycle.iter().copied().max().map_or(0, |c| c as usize + 1);
    let mut per = vec![vec![0.0_f64; nh]; n_cycles];
    for i in 0..st.t_s.len() {
        let posture = &plan.postures[st.posture[i]];
        if posture.phase == "rest" {
            continue;
        }
        for (h, &f) in posture.load.iter().enumerate() {
            per[st.cycle[i] as usize][h] += rohmert_rest_s(f, st.duration_s[i]);
        }
    }
    let mut need: Vec<(String, f64)> = (0..nh)
        .map(|h| {
            let worst = per.iter().map(|c| c[h]).fold(0.0, f64::max);
            (plan.half_joint_ids[h].clone(), worst)
        })
        .filter(|(_, r)| *r > 0.0)
        .collect();
    need.sort_by(|a, b| b.1.total_cmp(&a.1));
    need
}

fn check_rohmert(plan: &Plan, advice: &RestAdvice) {
    let need = rohmert_by_hand(plan);
    assert!(!need.is_empty(), "no group is held above 15 % MVC");
    let r = &advice.rohmert;
    assert!(
        (r.rest_s_per_cycle - need[0].1).abs() <= 1e-9 * need[0].1.max(1.0),
        "library {} s, by hand {} s",
        r.rest_s_per_cycle,
        need[0].1
    );
    assert_eq!(r.limiting_half_joint, need[0].0);
    assert_eq!(r.groups.len(), need.len());
    for (g, (id, s)) in r.groups.iter().zip(&need) {
        assert_eq!(&g.half_joint, id);
        assert!((g.rest_s_per_cycle - s).abs() <= 1e-9 * s.max(1.0), "{id}");
    }
    assert!(r.over_mvc.is_empty());
}

// ---------------------------------------------------------------------------------------------
// The recovery model, integrated independently.

/// R(f) [1/min] from the plan's description of a group's recovery (the forms documented in
/// data/fatigue_sets.yaml: none, constant, perfusion R_rest · x²(3 − 2x), x = 1 − f/f_lim).
fn recovery_rate_per_min(r: &Recovery, f: f64) -> f64 {
    match *r {
        Recovery::None => 0.0,
        Recovery::Constant { r_per_min } => r_per_min,
        Recovery::Perfusion {
            rest_per_min,
            limit_fmvc,
        } => {
            let x = 1.0 - f / limit_fmvc;
            if x > 0.0 {
                rest_per_min * x * x * (3.0 - 2.0 * x)
            } else {
                0.0
            }
        }
        Recovery::Routed { .. } => panic!("this reference integrates the single-rate forms"),
    }
}

/// The plan's loads: per cycle, per phase, per half-joint; and the rest posture's loads.
fn plan_loads(task: &Task, plan: &Plan) -> (Vec<Vec<Vec<f64>>>, Vec<f64>) {
    assert!(plan.summary.exhaustion.is_none());
    assert_eq!(plan.summary.cycles_done, task.cycles);
    let st = &plan.steps;
    let mut cycles = vec![Vec::new(); task.cycles as usize];
    for i in 0..st.t_s.len() {
        let p = &plan.postures[st.posture[i]];
        if p.phase == "rest" {
            continue;
        }
        cycles[st.cycle[i] as usize].push(p.load.clone());
    }
    assert!(cycles.iter().all(|c| c.len() == task.phases.len()));
    let rest = plan
        .postures
        .iter()
        .find(|p| p.phase == "rest")
        .expect("the plan has a rest posture")
        .load
        .clone();
    (cycles, rest)
}

/// RK4 with 10 ms steps over the task with `rest_s` of rest per cycle: the smallest margin
/// c − max(floor, f) at any step, and the lowest capacity.
fn rk4(task: &Task, plan: &Plan, rest_s: f64, floor: f64) -> (f64, f64) {
    let (cycles, f_rest) = plan_loads(task, plan);
    let dt = 0.01;
    let mut margin = f64::INFINITY;
    let mut lowest = f64::INFINITY;
    for (h, info) in plan.half_joints.iter().enumerate() {
        let k = info.k_per_min / 60.0;
        let mut c = 1.0_f64;
        let mut hold = |c: &mut f64, f: f64, dur: f64| {
            let r = recovery_rate_per_min(&info.recovery, f) / 60.0;
            let d = |c: f64| -k * f * c + r * (1.0 - c);
            let n = ((dur / dt).round() as usize).max(1);
            let h_ = dur / n as f64;
            for _ in 0..n {
                let k1 = d(*c);
                let k2 = d(*c + 0.5 * h_ * k1);
                let k3 = d(*c + 0.5 * h_ * k2);
                let k4 = d(*c + h_ * k3);
                *c += h_ / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
                margin = margin.min(*c - floor.max(f));
                lowest = lowest.min(*c);
            }
        };
        for cycle in &cycles {
            for (p, f) in cycle.iter().enumerate() {
                hold(&mut c, f[h], task.phases[p].duration_s);
            }
            if rest_s > 0.0 {
                hold(&mut c, f_rest[h], rest_s);
            }
        }
    }
    (margin, lowest)
}

#[test]
fn recommended_rest_is_the_smallest_that_keeps_the_floor() {
    // 6 kg held 10 s, ten times, no rest; a constant recovery rate R = 0.3 /min (the older task
    // form: under load as at rest), so dc/dt = −k f c + R (1 − c) exactly.
    let (task, plan) = plan_text(&hold_task(6.0, 10.0, 0.0, 10, "{recovery_per_min: 0.3}"));
    assert!(
        plan.half_joints
            .iter()
            .all(|h| h.recovery == Recovery::Constant { r_per_min: 0.3 })
    );
    let floor = 0.7;
    let advice = rest_advice(&task, &plan, floor);
    assert_eq!(advice.capacity_floor, floor);
    assert_eq!(advice.current_rest_s, 0.0);
    assert_eq!(advice.work_s_per_cycle, 10.0);

    // Without rest the floor is broken — the independent integration agrees with the plan's own
    // simulation of the lowest capacity.
    let (m0, low0) = rk4(&task, &plan, 0.0, floor);
    assert!(m0 < 0.0, "{m0}");
    assert!((low0 - plan.summary.lowest_capacity).abs() < 1e-6, "{low0}");
    assert!((advice.model.min_capacity_current - low0).abs() < 1e-6);
    assert!(advice.model.min_capacity_current < floor);

    let r = advice
        .model
        .rest_s_per_cycle
        .expect("recovery lets rest help");
    assert!(r > 0.0 && r < 10.0 * advice.work_s_per_cycle, "{r}");
    // On the 0.1 s grid.
    assert!((r * 10.0 - (r * 10.0).round()).abs() < 1e-9, "{r}");
    // At the recommendation the floor (and every load) is kept ...
    let (m, low) = rk4(&task, &plan, r, floor);
    assert!(m >= -1e-9, "margin at the recommended {r} s: {m}");
    let c_rec = advice.model.min_capacity_at_recommended.unwrap();
    assert!(c_rec >= floor - 1e-12);
    assert!((c_rec - low).abs() < 1e-6, "{c_rec} vs {low}");
    // ... 0.2 s less breaks it, and so does every shorter rest (0.5 s grid): it is the smallest.
    let (m, _) = rk4(&task, &plan, r - 0.2, floor);
    assert!(m < 0.0, "margin at {} s: {m}", r - 0.2);
    let mut s = 0.0;
    while s < r - 0.2 {
        let (m, _) = rk4(&task, &plan, s, floor);
        assert!(
            m < 0.0,
            "{s} s of rest already keeps the floor (margin {m}), yet {r} s is recommended"
        );
        s += 0.5;
    }

    // Rohmert's figure is the published formula applied to the plan's holds (checked in
    // `check_rohmert`); it has no memory across cycles, so it is not ordered against the model's.
    check_rohmert(&plan, &advice);
    assert!(advice.rohmert.rest_s_per_cycle > 0.0);
}

#[test]
fn without_recovery_rest_cannot_help() {
    // The ma2009 set: Ma et al. (2009) exactly, R = 0 for every group.
    let (task, plan) = plan_text(&hold_task(6.0, 10.0, 2.0, 3, "{parameters: ma2009}"));
    assert!(
        plan.half_joints
            .iter()
            .all(|h| h.recovery == Recovery::None)
    );
    assert!(plan.half_joints.iter().all(|h| h.recovery_per_min == 0.0));
    let floor = 0.9;
    let advice = rest_advice(&task, &plan, floor);
    // Three holds take the shoulder flexors below 0.9, far from exhaustion.
    assert!(plan.summary.exhaustion.is_none());
    assert!(advice.model.min_capacity_current < floor);
    // Capacity only falls without recovery: more rest never raises the lowest margin.
    let work = advice.work_s_per_cycle;
    let mut last = f64::INFINITY;
    for rest in [0.0, 2.0, 10.0, 60.0, 10.0 * work] {
        let (m, _) = rk4(&task, &plan, rest, floor);
        assert!(
            m < 0.0,
            "{rest} s of rest keeps the floor without recovery?"
        );
        assert!(
            m <= last + 1e-12,
            "more rest raised the margin: {m} > {last}"
        );
        last = m;
    }
    assert_eq!(advice.model.rest_s_per_cycle, None);
    assert_eq!(advice.model.min_capacity_at_recommended, None);
    assert!(
        advice.model.note.contains("no recovery"),
        "{}",
        advice.model.note
    );
    // A floor the plan never reaches needs no rest at all.
    let low = advice.model.min_capacity_current;
    let advice = rest_advice(&task, &plan, 0.5 * low);
    assert_eq!(advice.model.rest_s_per_cycle, Some(0.0));
    // Rohmert's rule does not know about recovery rates: the same formula by hand.
    check_rohmert(&plan, &advice);
}

/// The default parameter set (perfusion-limited recovery): a group the rest posture loads above
/// the set's limit load (8.5 % MVC) does not recover while resting, so whether a rest keeps the
/// floor need not be monotone in its length. The advice must find the smallest rest that works,
/// checked here against an independent integration.
#[test]
fn recommended_rest_with_perfusion_recovery() {
    let (task, plan) = plan_text(&hold_task(3.0, 10.0, 0.0, 10, "{parameters: default-2026}"));
    let floor = 0.7;
    let advice = rest_advice(&task, &plan, floor);
    let (m0, _) = rk4(&task, &plan, 0.0, floor);
    assert!(m0 < 0.0, "{m0}");
    // The first rest (0.5 s grid) that keeps the floor, by the independent integration.
    let r_max = 10.0 * advice.work_s_per_cycle;
    let mut first = None;
    let mut s = 0.5;
    while s <= r_max {
        if rk4(&task, &plan, s, floor).0 >= 0.0 {
            first = Some(s);
            break;
        }
        s += 0.5;
    }
    let first = first.expect("some rest keeps the floor");
    let r = advice.model.rest_s_per_cycle.unwrap_or_else(|| {
        panic!(
            "{first} s of rest keeps every capacity above {floor}, but the advice is: {}",
            advice.model.note
        )
    });
    assert!(r <= first + 1e-9, "{r} s recommended, {first} s suffices");
    assert!(rk4(&task, &plan, r, floor).0 >= -1e-9);
    assert!(rk4(&task, &plan, r - 0.2, floor).0 < 0.0);
}
