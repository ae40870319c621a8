//! Work and rest: Rohmert's rule against hand-computed values, and the model's recommended rest
//! checked by an independent numerical integration of dc/dt = −k f c + R (1 − c).

use posture_opt::plan::plan_with_baseline;
use posture_opt::rest::{rest_advice, rest_loads, rohmert_allowance, rohmert_endurance_min};
use posture_opt::task::{Task, TaskFile};

fn task_path(name: &str) -> String {
    format!("{}/tasks/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn rohmert_by_hand() {
    // T(0.5) = −1.5 + 4.2 − 2.4 + 0.8 = 1.1 min.
    assert!((rohmert_endurance_min(0.5) - 1.1).abs() < 1e-12);
    // A hold as long as the endurance time: RA = 18 · 1 · sqrt(0.35).
    let ra = rohmert_allowance(0.5, 66.0).unwrap();
    assert!((ra - 18.0 * 0.35_f64.sqrt()).abs() < 1e-9, "{ra}");
    // Half the endurance time: 18 · 0.5^1.4 · sqrt(0.35).
    let ra = rohmert_allowance(0.5, 33.0).unwrap();
    assert!((ra - 18.0 * 0.5_f64.powf(1.4) * 0.35_f64.sqrt()).abs() < 1e-9);
    // At or below 15 % MVC no rest; above MVC no answer.
    assert_eq!(rohmert_allowance(0.15, 600.0), Some(0.0));
    assert_eq!(rohmert_allowance(1.2, 1.0), None);
}

/// Lowest margin c − max(floor, f) over the task, by RK4 with 10 ms steps.
fn rk4_margin(
    task: &Task,
    loads: &[Vec<Vec<f64>>],
    f_rest: &[f64],
    rest_s: f64,
    floor: f64,
) -> f64 {
    let dt = 0.01;
    let mut margin = f64::INFINITY;
    for (h, p) in task.fatigue.iter().enumerate() {
        let (k, r) = (p.k_per_min / 60.0, p.r_per_min / 60.0);
        let mut c = 1.0_f64;
        let mut hold = |c: &mut f64, f: f64, dur: f64| {
            let n = (dur / dt).round() as usize;
            let h_ = dur / n.max(1) as f64;
            let d = |c: f64| -k * f * c + r * (1.0 - c);
            for _ in 0..n {
                let k1 = d(*c);
                let k2 = d(*c + 0.5 * h_ * k1);
                let k3 = d(*c + 0.5 * h_ * k2);
                let k4 = d(*c + h_ * k3);
                *c += h_ / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
                margin = margin.min(*c - floor.max(f));
            }
        };
        for cycle in loads {
            for (ph, f) in cycle.iter().enumerate() {
                hold(&mut c, f[h], task.phases[ph].duration_s);
            }
            hold(&mut c, f_rest[h], rest_s);
        }
    }
    margin
}

#[test]
fn recommended_rest_is_the_smallest_that_keeps_the_floor() {
    let task = Task::from_file(task_path("shelf.yaml")).unwrap();
    let (plan, _) = plan_with_baseline(&task, true).unwrap();
    let floor = 0.7;
    let advice = rest_advice(&task, &plan, floor);
    let r = advice
        .model
        .rest_s_per_cycle
        .expect("recovery lets rest help");
    // The task's own 6 s rest lets the shoulder flexors drop below 0.7 (the plan's summary).
    assert!(r > task.rest_s, "{r}");
    assert!(advice.model.min_capacity_current < floor);
    assert!(advice.model.min_capacity_at_recommended.unwrap() >= floor);

    // Loads per cycle from the plan's steps, rest loads in the rest posture.
    let n_ph = task.phases.len();
    let mut loads = vec![Vec::new(); task.cycles as usize];
    for s in plan.steps.iter().filter(|s| s.target_position_m.is_some()) {
        loads[s.cycle as usize].push(
            task.half_joints
                .iter()
                .map(|h| s.load[&h.id])
                .collect::<Vec<f64>>(),
        );
    }
    assert!(loads.iter().all(|c| c.len() == n_ph));
    let f_rest = rest_loads(&task);
    let at = rk4_margin(&task, &loads, &f_rest, r, floor);
    let below = rk4_margin(&task, &loads, &f_rest, r - 0.2, floor);
    assert!(at >= -1e-6, "margin at the recommended rest {at}");
    assert!(
        below < 0.0,
        "margin 0.2 s below the recommended rest {below}"
    );
    // Rohmert's rule for the same plan: positive but far less (it has no memory across cycles).
    assert!(advice.rohmert.rest_s_per_cycle > 0.0);
    assert!(advice.rohmert.rest_s_per_cycle < r);
    assert_eq!(advice.rohmert.limiting_half_joint, "r_shoulder_flexion+");
}

#[test]
fn without_recovery_rest_cannot_help() {
    let text = std::fs::read_to_string(task_path("shelf.yaml")).unwrap();
    let mut f: TaskFile = serde_saphyr::from_str(&text).unwrap();
    f.fatigue.recovery_per_min = Some(0.0);
    f.cycles = 3;
    let task = Task::from_task_file(f, std::path::Path::new(&task_path("shelf.yaml"))).unwrap();
    let (plan, _) = plan_with_baseline(&task, true).unwrap();
    // Three cycles take the shoulder flexors below 0.9 but not near exhaustion.
    assert!(plan.summary.exhaustion.is_none());
    let advice = rest_advice(&task, &plan, 0.9);
    assert!(advice.model.min_capacity_current < 0.9);
    assert_eq!(advice.model.rest_s_per_cycle, None);
    assert!(
        advice.model.note.contains("no recovery"),
        "{}",
        advice.model.note
    );
    // A floor the plan never reaches needs no rest at all.
    let advice = rest_advice(&task, &plan, 0.5);
    assert_eq!(advice.model.rest_s_per_cycle, Some(0.0));
}
