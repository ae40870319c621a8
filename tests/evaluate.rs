//! Evaluating recordings: a held posture reproduces the model's MET, a plan's timeline gives the
//! plan's capacities and U, live and offline agree exactly, bad recordings are located.

use posture_opt::body::Worker;
use posture_opt::evaluate::{evaluate_recording, EvalSetup};
use posture_opt::fatigue::MaParams;
use posture_opt::plan::plan_with_baseline;
use posture_opt::task::Task;
use std::io::Write;
use std::process::{Command, Stdio};

fn root() -> &'static str {
    env!("CARGO_MANIFEST_DIR")
}

fn setup(r_per_min: f64) -> EvalSetup {
    EvalSetup::from_robot(
        format!("{}/robots/worker.urdf", root()).as_ref(),
        "hand_grip",
        &Worker::MALE_50,
        MaParams::new(1.0, r_per_min).unwrap(),
    )
    .unwrap()
}

#[test]
fn a_held_posture_reproduces_met() {
    let s = setup(0.0);
    // upright, elbow at 90°, 5 kg in the hand, held for 20 minutes (sampled irregularly)
    let mut rec = String::from("t_s,r_elbow_flexion,load_kg\n");
    for t in [0.0, 0.7, 3.0, 61.3, 200.0, 1200.0] {
        rec.push_str(&format!("{t},1.5707963267948966,5\n"));
    }
    let r = evaluate_recording(&s, &rec, false, "held.csv").unwrap();
    let h = r
        .half_joints
        .iter()
        .position(|id| id == "r_elbow_flexion+")
        .unwrap();
    let f = r.load[0][h];
    assert!(f > 0.1 && f < 0.9, "{f}");
    let met_s = -f.ln() / f * 60.0; // Eq. 8, k = 1 /min
    let e = r
        .exhaustions
        .iter()
        .find(|e| e.half_joint == "r_elbow_flexion+")
        .expect("the elbow flexors exhaust");
    assert!(
        (e.t_s - met_s).abs() < 1e-9 * met_s,
        "{} vs MET {met_s}",
        e.t_s
    );
    // and capacity after 200 s is e^{-k f t}
    assert!((r.capacity[4][h] - (-f * 200.0 / 60.0).exp()).abs() < 1e-12);
}

#[test]
fn a_plans_timeline_gives_the_plans_capacities_and_u() {
    let t = Task::from_file(format!("{}/tasks/shelf.yaml", root())).unwrap();
    let (p, _) = plan_with_baseline(&t, true).unwrap();
    let rec = posture_opt::report::plan_recording_csv(&p);
    let r = evaluate_recording(&setup(0.3), &rec, false, "plan.csv").unwrap();
    assert_eq!(r.t_s.len(), p.steps.len() + 1);
    for (i, step) in p.steps.iter().enumerate() {
        for (h, id) in r.half_joints.iter().enumerate() {
            // the state at sample i+1 is the state at the end of step i
            assert!(
                (r.capacity[i + 1][h] - step.capacity[id]).abs() < 1e-9,
                "{id} step {i}"
            );
            assert!(
                (r.fatigue_u[i + 1][h] - step.fatigue_u[id]).abs()
                    < 1e-9 * step.fatigue_u[id].max(1.0),
                "{id} step {i}"
            );
            assert!((r.load[i][h] - step.load[id]).abs() < 1e-12);
        }
    }
}

#[test]
fn live_and_offline_agree_exactly() {
    let rec_path = format!("{}/recordings/shelf_plan.csv", root());
    let robot = format!("{}/robots/worker.urdf", root());
    let bin = env!("CARGO_BIN_EXE_posture-opt");
    let off = Command::new(bin)
        .args([
            "evaluate",
            &rec_path,
            "--robot",
            &robot,
            "--r-per-min",
            "0.3",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(off.status.success());
    let off: serde_json::Value = serde_json::from_slice(&off.stdout).unwrap();
    let mut child = Command::new(bin)
        .args([
            "evaluate",
            "--stream",
            "--robot",
            &robot,
            "--r-per-min",
            "0.3",
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let text = std::fs::read_to_string(&rec_path).unwrap();
    let mut stdin = child.stdin.take().unwrap();
    // feed from another thread: the child answers line by line, and both pipes must keep moving
    let feeder = std::thread::spawn(move || stdin.write_all(text.as_bytes()).unwrap());
    let live = child.wait_with_output().unwrap();
    feeder.join().unwrap();
    assert!(live.status.success());
    let lines: Vec<serde_json::Value> = String::from_utf8(live.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let ids: Vec<String> = off["half_joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap().to_string())
        .collect();
    assert_eq!(lines.len(), off["t_s"].as_array().unwrap().len());
    for (i, l) in lines.iter().enumerate() {
        assert_eq!(l["t_s"].as_f64(), off["t_s"][i].as_f64());
        for (h, id) in ids.iter().enumerate() {
            assert_eq!(
                l["capacity"][id].as_f64().unwrap(),
                off["capacity"][i][h].as_f64().unwrap(),
                "sample {i} {id}"
            );
            assert_eq!(
                l["fatigue_u"][id].as_f64().unwrap(),
                off["fatigue_u"][i][h].as_f64().unwrap(),
                "sample {i} {id}"
            );
        }
    }
}

#[test]
fn bad_recordings_are_located_and_nothing_is_written() {
    let s = setup(0.0);
    let e = evaluate_recording(&s, "t_s,r_knee,load_kg\n0,0,0\n", false, "r.csv")
        .unwrap_err()
        .to_string();
    assert!(e.contains("r.csv: line 1") && e.contains("r_knee"), "{e}");
    let e = evaluate_recording(
        &s,
        "t_s,r_elbow_flexion,load_kg\n0,0,0\n1,0.5,2\n1,0.5,2\n",
        false,
        "r.csv",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("line 4, column 1 (t_s)") && e.contains("does not increase"),
        "{e}"
    );
    let e = evaluate_recording(&s, "t_s,r_elbow_flexion,load_kg\n0,,0\n", false, "r.csv")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 2, column 2 (r_elbow_flexion)") && e.contains("missing"),
        "{e}"
    );
    let e = evaluate_recording(&s, "t_s,r_elbow_flexion,load_kg\n0,inf,0\n", false, "r.csv")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 2, column 2") && e.contains("not finite"),
        "{e}"
    );
    let e = evaluate_recording(&s, "t_s,r_elbow_flexion,load_kg\n0,0.1\n", false, "r.csv")
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 2, column 3 (load_kg)"), "{e}");
    // the CLI leaves no output file behind on error
    let dir = std::env::temp_dir().join(format!("posture-opt-eval-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "t_s,r_elbow_flexion,load_kg\n0,0,0\n-1,0,0\n").unwrap();
    let out = dir.join("out.csv");
    let o = Command::new(env!("CARGO_BIN_EXE_posture-opt"))
        .args([
            "evaluate",
            bad.to_str().unwrap(),
            "--robot",
            &format!("{}/robots/worker.urdf", root()),
            "--csv",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("line 3, column 1"));
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn live_mode_answers_each_sample_before_the_next_arrives() {
    use std::io::BufRead;
    let robot = format!("{}/robots/worker.urdf", root());
    let mut child = Command::new(env!("CARGO_BIN_EXE_posture-opt"))
        .args(["evaluate", "--stream", "--robot", &robot])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
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
    stdin.write_all(b"t_s,r_elbow_flexion,load_kg\n").unwrap();
    for (i, t) in [0.0, 0.5, 1.25].iter().enumerate() {
        stdin.write_all(format!("{t},1.2,3\n").as_bytes()).unwrap();
        stdin.flush().unwrap();
        // the answer must arrive while stdin stays open
        let l = rx
            .recv_timeout(std::time::Duration::from_secs(20))
            .expect("a line per sample, flushed");
        let v: serde_json::Value = serde_json::from_str(&l).unwrap();
        assert_eq!(v["t_s"].as_f64().unwrap(), *t, "sample {i}");
    }
    drop(stdin);
    assert!(child.wait().unwrap().success());
}
