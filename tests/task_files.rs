//! Task files: errors name the file, the line/column or field, and what is wrong; an out-of-reach
//! target gives the nearest reachable posture and the plan says so.

use posture_opt::plan::plan_with_baseline;
use posture_opt::task::Task;
use std::path::PathBuf;

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("posture-opt-tasks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const BASE: &str = "name: t
worker: {sex: male, stature_m: 1.755, mass_kg: 78.0}
workstation:
  obstacles:
    - {name: floor, plane: {normal: [0, 0, 1]}}
phases:
  - {name: hold, target_m: [0.35, -0.2, 1.0], load_kg: 2.0, duration_s: 5.0}
rest_s: 5.0
cycles: 10
";

#[test]
fn a_minimal_task_loads_with_a_generated_body() {
    let t = Task::from_file(write("ok.yaml", BASE)).unwrap();
    assert_eq!(t.robot, "generated from worker");
    assert_eq!(t.half_joints.len(), 20);
    assert!((t.cycle_s() - 10.0).abs() < 1e-12);
    assert!((t.phases[0].hand_force_n.z + 2.0 * 9.81).abs() < 1e-12);
}

#[test]
fn errors_name_file_and_place() {
    let e = Task::from_file(write(
        "unknown.yaml",
        &BASE.replace("rest_s: 5.0", "rest_s: 5.0\nresting: 3"),
    ))
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("unknown.yaml") && e.contains("resting") && e.contains("line 9"),
        "{e}"
    );
    let e = Task::from_file(write(
        "neg.yaml",
        &BASE.replace("duration_s: 5.0", "duration_s: -5.0"),
    ))
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("neg.yaml") && e.contains("phases[0] (hold).duration_s") && e.contains("-5"),
        "{e}"
    );
    let e = Task::from_file(write(
        "nan.yaml",
        &BASE.replace("load_kg: 2.0", "load_kg: .nan"),
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("load_kg"), "{e}");
    let e = Task::from_file(write("robot.yaml", &format!("robot: nowhere.urdf\n{BASE}")))
        .unwrap_err()
        .to_string();
    assert!(e.contains("robot") && e.contains("nowhere.urdf"), "{e}");
    let e = Task::from_file(write("frame.yaml", &format!("hand_frame: nose\n{BASE}")))
        .unwrap_err()
        .to_string();
    assert!(e.contains("hand_frame") && e.contains("nose"), "{e}");
    let e = Task::from_file(write(
        "box.yaml",
        &BASE.replace(
            "{name: floor, plane: {normal: [0, 0, 1]}}",
            "{name: shelf, box: {size_m: [0.4, 0, 0.02]}}",
        ),
    ))
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("workstation.obstacles") && e.contains("shelf") && e.contains("size_m"),
        "{e}"
    );
    let e = Task::from_file(write(
        "cycles.yaml",
        &BASE.replace("cycles: 10", "cycles: 0"),
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("cycles"), "{e}");
    let e = Task::from_file(write(
        "k.yaml",
        &format!("{BASE}fatigue: {{k_per_min: -1}}\n"),
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("fatigue.k_per_min"), "{e}");
    let e = Task::from_file(write(
        "ov.yaml",
        &format!("{BASE}fatigue: {{overrides: {{knee: {{k_per_min: 2}}}}}}\n"),
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("fatigue.overrides.knee"), "{e}");
    let e = Task::from_file("/nonexistent/task.yaml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("/nonexistent/task.yaml"), "{e}");
}

#[test]
fn out_of_reach_target_gives_nearest_posture_and_says_so() {
    let t = Task::from_file(write(
        "far.yaml",
        &BASE.replace("[0.35, -0.2, 1.0]", "[1.5, -0.2, 1.0]"),
    ))
    .unwrap();
    let (p, _) = plan_with_baseline(&t, true).unwrap();
    let ph = &p.summary.phases[0];
    assert!(!ph.reachable);
    // arm length ≈ 0.2817 + 0.2689 + 0.75·0.0862 ≈ 0.61 m (×1.755/1.741) and the trunk can lean:
    // the target 1.5 m ahead stays far out of reach
    assert!(
        ph.hand_error_m > 0.3 && ph.hand_error_m < 1.2,
        "{}",
        ph.hand_error_m
    );
    assert!(posture_opt::report::plan_summary(&p).contains("OUT OF REACH"));
}
