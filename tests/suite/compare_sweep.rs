//! `compare` and `sweep`: the ranking rule, agreement with `plan`, shards, populations against
//! their published sources, and refusals of bad input.
//!
//! The tasks are tiny one-phase holds of the generated worker written to a temporary directory
//! (each plan takes seconds); commands run there, so the documents name files relatively.

use posture_opt::body::Sex;
use posture_opt::plan::{Task, TaskFile};
use posture_opt::study::compare::RANKING_RULE;
use posture_opt::study::sweep::{sampled_population, standard_population};
use serde_json::Value;
use statrs::distribution::{ContinuousCDF, Normal};
use std::cmp::Ordering;
use std::path::Path;
use std::sync::OnceLock;

use crate::common;
use common::{Out, Run, scan_json, tempdir, write};

/// `posture-opt ARGS` run in `dir`.
fn cli(dir: &Path, args: &[&str]) -> Out {
    Run::new(args).cwd(dir).go()
}

/// `posture-opt ARGS` in `dir`, which must succeed with one JSON document whose numbers are all
/// finite (a sweep of the standard population has no sampled shares: those may be null).
fn json(dir: &Path, args: &[&str]) -> Value {
    let o = cli(dir, args);
    o.ok();
    let v = o.json();
    let bad: Vec<String> = scan_json(&v)
        .into_iter()
        .filter(|p| !(p.starts_with("$.sustain_") && p.ends_with(" = null")))
        .collect();
    assert!(
        bad.is_empty(),
        "{}: non-finite values in JSON: {bad:?}",
        o.what
    );
    v
}

/// One held phase: the right hand holds `load_kg` at `target` for 10 s, `cycles` times, 5 s rest.
fn hold(name: &str, target: [f64; 3], load_kg: f64, cycles: u32) -> String {
    format!(
        "name: {name}\nworker: {{sex: male, stature_m: 1.755, mass_kg: 78.0, strength_percentile: 50}}\nworkstation:\n  obstacles:\n    - {{name: floor, plane: {{normal: [0, 0, 1]}}, position_m: [0, 0, 0]}}\nphases:\n  - {{name: place, target_m: [{}, {}, {}], load_kg: {load_kg}, duration_s: 10.0}}\nrest_s: 5.0\ncycles: {cycles}\n",
        target[0], target[1], target[2]
    )
}

/// The layouts' body: a fixed-base arm (planning it takes milliseconds). The shoulder is at
/// (0, −0.25, 1.25) m; upper arm and forearm are 0.35 m long (reach 0.70 m) and weigh 2.0 and
/// 1.5 kg; strength is each joint's `<limit effort>` (the strength file beside it has no
/// entries).
const ARM_URDF: &str = r#"<?xml version="1.0"?>
<robot name="test_arm">
  <link name="torso">
    <inertial><origin xyz="0 0 1.0"/><mass value="30"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><origin xyz="0 0 1.0"/><geometry><box size="0.3 0.3 0.6"/></geometry></collision>
  </link>
  <link name="shoulder_link"/>
  <link name="upper">
    <inertial><origin xyz="0.175 0 0"/><mass value="2.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0.175 0 0" rpy="0 1.5707963 0"/><geometry><cylinder radius="0.04" length="0.35"/></geometry></collision>
  </link>
  <link name="fore">
    <inertial><origin xyz="0.175 0 0"/><mass value="1.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0.175 0 0" rpy="0 1.5707963 0"/><geometry><cylinder radius="0.035" length="0.35"/></geometry></collision>
  </link>
  <link name="tip"/>
  <joint name="shoulder_yaw" type="revolute">
    <parent link="torso"/><child link="shoulder_link"/>
    <origin xyz="0 -0.25 1.25"/><axis xyz="0 0 1"/>
    <limit lower="-3.1" upper="3.1" effort="60" velocity="1"/>
  </joint>
  <joint name="shoulder_pitch" type="revolute">
    <parent link="shoulder_link"/><child link="upper"/>
    <axis xyz="0 1 0"/>
    <limit lower="-3.1" upper="3.1" effort="60" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/>
    <origin xyz="0.35 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2.8" upper="2.8" effort="40" velocity="1"/>
  </joint>
  <joint name="tip_fixed" type="fixed">
    <parent link="fore"/><child link="tip"/><origin xyz="0.35 0 0"/>
  </joint>
</robot>
"#;
const ARM_STRENGTH: &str = "unactuated: []\nhalf_joints: []\n";
const SHOULDER: [f64; 3] = [0.0, -0.25, 1.25];
const REACH_M: f64 = 0.70;

/// Three shelf layouts for the same 4 kg box held 10 s, four times. The shoulder holds the box's
/// weight at a moment arm equal to the hand's horizontal distance from it:
/// * `easy.yaml`: a shelf below the shoulder, close (0.25 m forward);
/// * `high.yaml`: a shelf above the shoulder at nearly arm's length (0.60 m forward) — a longer
///   moment arm for the same box (and the arm's own weight further out): more load, less
///   endurance;
/// * `reach.yaml`: a shelf 1.00 m in front of the shoulder, 0.30 m beyond the arm's reach.
const LAYOUTS: [(&str, [f64; 3]); 3] = [
    ("easy.yaml", [0.25, -0.25, 1.0]),
    ("high.yaml", [0.60, -0.25, 1.3]),
    ("reach.yaml", [1.0, -0.25, 1.25]),
];

fn layout(name: &str, target: [f64; 3]) -> String {
    format!(
        "name: {name}\nworker: {{sex: male, stature_m: 1.755, mass_kg: 78.0}}\nrobot: arm.urdf\nhand_frame: tip\nphases:\n  - {{name: place, target_m: [{}, {}, {}], load_kg: 4.0, duration_s: 10.0}}\nrest_s: 5.0\ncycles: 4\n",
        target[0], target[1], target[2]
    )
}

fn write_layouts(dir: &Path) {
    write(dir, "arm.urdf", ARM_URDF);
    write(dir, "arm.strength.yaml", ARM_STRENGTH);
    for (file, target) in LAYOUTS {
        write(dir, file, layout(file, target));
    }
}

/// The layouts given in an order unlike the expected ranking.
const GIVEN: [&str; 3] = ["reach.yaml", "high.yaml", "easy.yaml"];

/// One unsharded `compare --json` of the layouts, shared by the tests that need it.
fn unsharded_comparison() -> &'static Value {
    static C: OnceLock<Value> = OnceLock::new();
    C.get_or_init(|| {
        let dir = tempdir();
        write_layouts(dir.path());
        let mut args = vec!["compare"];
        args.extend(GIVEN);
        args.push("--json");
        json(dir.path(), &args)
    })
}

fn num(v: &Value) -> Option<f64> {
    v.as_f64()
}

/// Same value: numbers within 1e-9 (relative), everything else equal.
fn same(a: &Value, b: &Value, what: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-300),
                "{what}: {x} vs {y}"
            );
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(x.len(), y.len(), "{what}: {a} vs {b}");
            for (k, v) in x {
                same(v, &y[k], &format!("{what}.{k}"));
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{what}: lengths");
            for (i, (u, v)) in x.iter().zip(y).enumerate() {
                same(u, v, &format!("{what}[{i}]"));
            }
        }
        _ => assert_eq!(a, b, "{what}"),
    }
}

/// RANKING_RULE, written out from its text: feasible first, then no load above strength, then no
/// exhaustion within the task (later better), then L5/S1 compression by NIOSH's class (within
/// 3400 N, above, above 6400 N) and above 3400 N the lower, then longer time to exhaustion at this
/// pace, then higher lowest capacity, then lower U per hour of simulated work, then lower worst
/// RULA.
fn rule_order(a: &Value, b: &Value) -> Ordering {
    let feasible = |o: &Value| o["feasible"].as_bool().unwrap();
    let exceeds = |o: &Value| {
        o["exhaustion"]["exceeds_strength"]
            .as_bool()
            .unwrap_or(false)
    };
    let exhausted_at = |o: &Value| num(&o["exhaustion"]["t_s"]).unwrap_or(f64::INFINITY);
    let minutes = |o: &Value| num(&o["minutes_to_exhaustion"]).unwrap_or(f64::INFINITY);
    let lowest = |o: &Value| num(&o["lowest_capacity"]).unwrap();
    let u_h = |o: &Value| num(&o["u_per_hour_min"]).unwrap();
    let rula = |o: &Value| o["rula_max"].as_i64().unwrap_or(0);
    let back = |o: &Value| match num(&o["back_compression_max_n"]) {
        Some(c) if c > 6400.0 => (2, c),
        Some(c) if c > 3400.0 => (1, c),
        _ => (0, 0.0),
    };
    // the lifting index's class (Waters et al. 1994: at most 1, at most 3, above), then above 1
    // the index
    let li = |o: &Value| match num(&o["lifting_index"]) {
        Some(x) if x > 3.0 => (2, x),
        Some(x) if x > 1.0 => (1, x),
        _ => (0, 0.0),
    };
    let status = |v: &Value| match v.as_str().unwrap() {
        "not_applicable" => -1,
        "acceptable" => 0,
        "caution" => 1,
        "exceeded" => 2,
        _ => 3,
    };
    // NIOSH 1981: 99 % of men and 75 % of women, then 25 % of men
    let capable = |o: &Value| {
        let (m, w) = (
            num(&o["capable_men"]).unwrap(),
            num(&o["capable_women"]).unwrap(),
        );
        if m >= 0.99 && w >= 0.75 {
            0
        } else if m >= 0.25 {
            1
        } else {
            2
        }
    };
    feasible(b)
        .cmp(&feasible(a))
        .then(exceeds(a).cmp(&exceeds(b)))
        .then(exhausted_at(b).total_cmp(&exhausted_at(a)))
        .then(li(a).0.cmp(&li(b).0))
        .then(li(a).1.total_cmp(&li(b).1))
        .then(status(&a["posture_status"]).cmp(&status(&b["posture_status"])))
        .then(back(a).0.cmp(&back(b).0))
        .then(back(a).1.total_cmp(&back(b).1))
        .then(capable(a).cmp(&capable(b)))
        .then(status(&a["shift_status"]).cmp(&status(&b["shift_status"])))
        .then(minutes(b).total_cmp(&minutes(a)))
        .then(lowest(b).total_cmp(&lowest(a)))
        .then(u_h(a).total_cmp(&u_h(b)))
        .then(rula(a).cmp(&rula(b)))
}

/// Largest load of a half-joint over a plan's working postures.
fn max_load(plan: &Value, id: &str) -> f64 {
    let h = plan["half_joint_ids"]
        .as_array()
        .unwrap()
        .iter()
        .position(|x| x == id)
        .unwrap();
    plan["postures"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["phase"] != "rest")
        .map(|p| p["load"][h].as_f64().unwrap())
        .fold(0.0, f64::max)
}

#[test]
fn compare_ranks_by_its_rule_and_agrees_with_plan() {
    let c = unsharded_comparison();
    assert_eq!(c["ranking_rule"], RANKING_RULE);
    assert_eq!(c["capacity_floor"], 0.7);
    assert_eq!(c["adaptive"], true);
    let l = c["layouts"].as_array().unwrap();
    assert_eq!(l.len(), 3);
    // The order physics gives: close, then at nearly arm's length, then out of reach.
    let files: Vec<&str> = l.iter().map(|x| x["file"].as_str().unwrap()).collect();
    assert_eq!(files, ["easy.yaml", "high.yaml", "reach.yaml"]);
    for (i, x) in l.iter().enumerate() {
        assert_eq!(x["rank"], i + 1);
        // `index` is the position on the command line.
        let idx = x["index"].as_u64().unwrap() as usize;
        assert_eq!(GIVEN[idx], files[i]);
    }
    // Each adjacent pair is in the order of the documented rule.
    for w in l.windows(2) {
        assert_ne!(
            rule_order(&w[0], &w[1]),
            Ordering::Greater,
            "{} ranked above {} against the rule",
            w[0]["file"],
            w[1]["file"]
        );
    }
    // The unreachable shelf: infeasible, and it says so.
    let reach = &l[2];
    assert_eq!(reach["feasible"], false);
    let problems: Vec<&str> = reach["problems"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_str().unwrap())
        .collect();
    assert!(
        problems.iter().any(|p| p.contains("out of reach")),
        "{problems:?}"
    );
    // The two reachable shelves: the far, high one loads the shoulder flexors more and leaves
    // less capacity and endurance (its moment arm is longer, the box the same).
    let (easy, high) = (&l[0], &l[1]);
    for x in [easy, high] {
        assert_eq!(x["feasible"], true);
        assert!(x["problems"].as_array().unwrap().is_empty());
        assert!(x["exhaustion"].is_null());
    }
    assert!(num(&high["lowest_capacity"]) < num(&easy["lowest_capacity"]));
    let m = |x: &Value| num(&x["minutes_to_exhaustion"]).unwrap_or(f64::INFINITY);
    assert!(m(high) < m(easy));
    // An infeasible layout loses under every parameter variant.
    let rob = c["robustness"].as_array().unwrap();
    assert_eq!(rob.len(), 2);
    for r in rob {
        assert_eq!(r["variants"], 9);
        if r["other"] == "reach.yaml" {
            assert_eq!(r["wins"], 9);
        }
    }
    assert!(
        c["findings"][0]
            .as_str()
            .unwrap()
            .starts_with("best layout: easy.yaml")
    );

    // Every layout's numbers are those of planning its file alone.
    let dir = tempdir();
    write_layouts(dir.path());
    let mut plans = Vec::new();
    for x in l {
        let file = x["file"].as_str().unwrap();
        let p = json(dir.path(), &["plan", file, "--json"]);
        let (s, a) = (&p["summary"], &p["assessment"]);
        same(&x["task"], &p["task"], "task");
        same(&x["total_u_min"], &s["total_u"], "total_u");
        same(&x["worst_u_min"], &s["worst_u"], "worst_u");
        same(
            &x["lowest_capacity"],
            &s["lowest_capacity"],
            "lowest_capacity",
        );
        same(
            &x["lowest_capacity_t_s"],
            &s["lowest_capacity_t_s"],
            "lowest_capacity_t_s",
        );
        same(&x["simulated_duration_s"], &s["duration_s"], "duration_s");
        same(
            &x["planned_duration_s"],
            &s["planned_duration_s"],
            "planned_duration_s",
        );
        same(&x["exhaustion"], &s["exhaustion"], "exhaustion");
        let u_h = s["total_u"].as_f64().unwrap() * 3600.0 / s["duration_s"].as_f64().unwrap();
        same(&x["u_per_hour_min"], &Value::from(u_h), "U per hour");
        same(
            &x["minutes_to_exhaustion"],
            &a["meaning"]["minutes_to_exhaustion"],
            "minutes",
        );
        same(
            &x["endurance_share"],
            &a["meaning"]["endurance_share"],
            "endurance_share",
        );
        same(&x["rula_max"], &a["rula_max"], "rula_max");
        same(&x["reba_max"], &a["reba_max"], "reba_max");
        same(
            &x["back_compression_max_n"],
            &a["back_compression_max_n"],
            "back",
        );
        same(&x["capable_women"], &a["capable_women"], "capable_women");
        same(&x["capable_men"], &a["capable_men"], "capable_men");
        same(
            &x["current_rest_s"],
            &a["rest"]["current_rest_s"],
            "current rest",
        );
        same(
            &x["rest_needed_s"],
            &a["rest"]["model"]["rest_s_per_cycle"],
            "rest needed",
        );
        // The worst group is the plan's most fatigued half-joint, in words.
        let worst = s["worst_half_joint"].as_str().unwrap();
        let group = p["half_joints"]
            .as_array()
            .unwrap()
            .iter()
            .find(|h| h["id"] == worst)
            .unwrap()["group"]
            .clone();
        assert_eq!(x["worst_group"], group);
        // Feasible exactly when every phase of the plan is reached, clear and balanced.
        let ok = s["phases"].as_array().unwrap().iter().all(|ph| {
            ph["reachable"] == true
                && ph["min_clearance_m"].as_f64().unwrap() >= 0.0
                && ph["balance_margin_m"].as_f64().is_none_or(|m| m >= 0.0)
        });
        assert_eq!(x["feasible"], ok, "{file}");
        // The lowest capacity is at most every step's capacity.
        let minc = s["lowest_capacity"].as_f64().unwrap();
        for row in p["steps"]["capacity"].as_array().unwrap() {
            for c in row.as_array().unwrap() {
                assert!(c.as_f64().unwrap() >= minc - 1e-15);
            }
        }
        plans.push(p);
    }
    // The shoulder's lifting muscles carry more in the far layout.
    let id = "shoulder_pitch-";
    assert!(max_load(&plans[1], id) > max_load(&plans[0], id));
    // The unreachable shelf is missed by its distance from the shoulder less the arm's reach.
    let d = (0..3)
        .map(|i| (LAYOUTS[2].1[i] - SHOULDER[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let miss = plans[2]["summary"]["phases"][0]["hand_error_m"]
        .as_f64()
        .unwrap();
    assert!((miss - (d - REACH_M)).abs() < 0.005, "missed by {miss} m");
    for p in &plans[..2] {
        assert!(p["summary"]["phases"][0]["hand_error_m"].as_f64().unwrap() < 0.001);
    }

    // The text table: the same best layout and the rule.
    let o = cli(dir.path(), &["compare", "high.yaml", "easy.yaml"]);
    o.ok();
    let text = o.stdout_text();
    assert!(text.contains("best layout: easy.yaml"), "{text}");
    assert!(text.contains(&format!("ranking: {RANKING_RULE}")), "{text}");
}

#[test]
fn compare_shards_merge_into_the_unsharded_comparison() {
    let dir = tempdir();
    let d = dir.path();
    write_layouts(d);
    let mut shard_files = Vec::new();
    for (i, s) in ["1/2", "2/2"].iter().enumerate() {
        let mut args = vec!["compare"];
        args.extend(GIVEN);
        args.extend(["--shard", s, "--json"]);
        let v = json(d, &args);
        assert_eq!(v["shard"], *s);
        assert_eq!(v["layouts_total"], 3);
        // Layout j belongs to shard j mod 2.
        let idx: Vec<u64> = v["outcomes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|o| o["index"].as_u64().unwrap())
            .collect();
        assert_eq!(idx, if i == 0 { vec![0, 2] } else { vec![1] });
        let name = format!("shard{}.json", i + 1);
        write(d, &name, serde_json::to_vec(&v).unwrap());
        shard_files.push(name);
    }
    // In either order, the shards merge into the one-run comparison: ranking and numbers.
    let whole = unsharded_comparison();
    for order in [[0, 1], [1, 0]] {
        let merged = json(
            d,
            &[
                "compare",
                "--merge",
                &shard_files[order[0]],
                &shard_files[order[1]],
                "--json",
            ],
        );
        let files = |c: &Value| -> Vec<Value> {
            c["layouts"]
                .as_array()
                .unwrap()
                .iter()
                .map(|o| o["file"].clone())
                .collect()
        };
        assert_eq!(files(&merged), files(whole));
        same(&merged, whole, "merged");
    }
    // Merging needs every shard exactly once, and shard results.
    cli(d, &["compare", "--merge", "shard1.json"]).bad(&["missing"]);
    // a shard claiming an absurd total is refused, not allocated for
    let mut huge: Value =
        serde_json::from_slice(&std::fs::read(d.join("shard1.json")).unwrap()).unwrap();
    huge["layouts_total"] = Value::from(1u64 << 60);
    write(d, "huge.json", serde_json::to_vec(&huge).unwrap());
    cli(d, &["compare", "--merge", "huge.json"]).bad(&["cover", "of 1152921504606846976"]);
    cli(
        d,
        &[
            "compare",
            "--merge",
            "shard1.json",
            "shard2.json",
            "shard2.json",
        ],
    )
    .bad(&["shard2.json"]);
    cli(d, &["compare", "--merge", "shard1.json", "easy.yaml"]).bad(&["easy.yaml"]);
    // Shards merge only when they were made from the same files. Shard 2/2 (layout 1,
    // high.yaml) run again after high.yaml's rest changed does not merge with shard 1/2; after a
    // comment alone was added it does; after the robot file changed it does not.
    let mut args = vec!["compare"];
    args.extend(GIVEN);
    args.extend(["--shard", "2/2", "--json"]);
    let rerun = |name: &str| {
        let v = json(d, &args);
        write(d, name, serde_json::to_vec(&v).unwrap());
    };
    let high = layout("high.yaml", LAYOUTS[1].1);
    write(d, "high.yaml", high.replace("rest_s: 5.0", "rest_s: 6.0"));
    rerun("shard2_rest.json");
    cli(
        d,
        &["compare", "--merge", "shard1.json", "shard2_rest.json"],
    )
    .bad(&[
        "shard2_rest.json",
        "other layout files than shard1.json",
        "layout 1",
    ]);
    write(
        d,
        "high.yaml",
        format!("# the same layout, commented\n{high}"),
    );
    rerun("shard2_comment.json");
    json(
        d,
        &[
            "compare",
            "--merge",
            "shard1.json",
            "shard2_comment.json",
            "--json",
        ],
    );
    write(d, "arm.urdf", format!("{ARM_URDF}\n<!-- edited -->\n"));
    rerun("shard2_robot.json");
    cli(
        d,
        &["compare", "--merge", "shard1.json", "shard2_robot.json"],
    )
    .bad(&["shard2_robot.json", "other layout files"]);
}

#[test]
fn compare_and_sweep_refuse_bad_input_by_name() {
    let dir = tempdir();
    let d = dir.path();
    write_layouts(d);
    let bad = hold("bad", [0.35, -0.2, 1.0], 4.0, 4).replace("duration_s: 10.0", "duration_s: -1");
    write(d, "bad.yaml", bad);
    // compare
    cli(d, &["compare"]).bad(&[]);
    cli(d, &["compare", "easy.yaml", "nope.yaml"]).bad(&["nope.yaml"]);
    cli(d, &["compare", "easy.yaml", "bad.yaml"]).bad(&["bad.yaml", "duration_s"]);
    cli(
        d,
        &[
            "compare",
            "easy.yaml",
            "high.yaml",
            "--capacity-floor",
            "1.5",
        ],
    )
    .bad(&["--capacity-floor"]);
    cli(
        d,
        &["compare", "easy.yaml", "high.yaml", "--capacity-floor", "0"],
    )
    .bad(&["--capacity-floor"]);
    cli(d, &["compare", "easy.yaml", "high.yaml", "--shard", "3/2"]).bad(&["--shard"]);
    cli(d, &["compare", "easy.yaml", "high.yaml", "--shard", "0/2"]).bad(&["--shard"]);
    cli(d, &["compare", "--merge", "--shard", "1/2", "easy.yaml"]).bad(&["--shard"]);
    cli(d, &["compare", "--merge", "easy.yaml"]).bad(&["easy.yaml"]);
    // sweep
    cli(d, &["sweep"]).bad(&[]);
    cli(d, &["sweep", "nope.yaml"]).bad(&["nope.yaml"]);
    cli(d, &["sweep", "bad.yaml"]).bad(&["bad.yaml", "duration_s"]);
    cli(d, &["sweep", "easy.yaml", "high.yaml"]).bad(&["--merge"]);
    cli(d, &["sweep", "easy.yaml", "--sample", "0"]).bad(&["--sample"]);
    cli(d, &["sweep", "easy.yaml", "--sample", "100001"]).bad(&["--sample"]);
    cli(d, &["sweep", "easy.yaml", "--sample", "many"]).bad(&["--sample"]);
    cli(d, &["sweep", "easy.yaml", "--seed", "x"]).bad(&["--seed"]);
    cli(d, &["sweep", "easy.yaml", "--capacity-floor", "1"]).bad(&["--capacity-floor"]);
    cli(d, &["sweep", "easy.yaml", "--capacity-floor", "-0.5"]).bad(&["--capacity-floor"]);
    for tol in ["1e-3", "0", "-1e-9", "nan", "tight"] {
        for sub in [
            &["plan", "easy.yaml"][..],
            &["compare", "easy.yaml", "high.yaml"],
            &["sweep", "easy.yaml"],
        ] {
            let args: Vec<&str> = sub.iter().copied().chain(["--qp-tolerance", tol]).collect();
            cli(d, &args).bad(&["--qp-tolerance"]);
        }
    }
    cli(d, &["sweep", "easy.yaml", "--shard", "2/1"]).bad(&["--shard"]);
    cli(d, &["sweep", "--merge", "easy.yaml"]).bad(&["easy.yaml"]);
    cli(d, &["sweep", "--merge", "nope.json"]).bad(&["nope.json"]);
}

/// `--qp-tolerance` reaches the solver: at the default's own value (1e-9) the plan is the default
/// plan bit for bit, while the loosest allowed value (1e-4) stops the interior-point solves
/// earlier and so changes the plan's digits — and still plans the task (a valid plan, every
/// number finite).
#[test]
fn the_qp_tolerance_option_reaches_the_solver() {
    let dir = tempdir();
    let d = dir.path();
    write_layouts(d);
    let text = |args: &[&str]| {
        let o = cli(d, args);
        o.ok();
        o.stdout_text()
    };
    assert_eq!(
        text(&["plan", "easy.yaml", "--json"]),
        text(&["plan", "easy.yaml", "--json", "--qp-tolerance", "1e-9"])
    );
    assert_ne!(
        text(&["plan", "easy.yaml", "--json"]),
        text(&["plan", "easy.yaml", "--json", "--qp-tolerance", "1e-4"]),
        "the option did not reach the solver"
    );
    let loose = json(
        d,
        &["plan", "easy.yaml", "--json", "--qp-tolerance", "1e-4"],
    );
    assert!(
        loose["summary"]["total_u"]
            .as_f64()
            .is_some_and(|u| u > 0.0)
    );
}

// ---------------------------------------------------------------------------------------------
// Populations.

/// Stature [mm] of US adults aged 19–65 (Pheasant, *Bodyspace*, as tabulated by the CityU Online
/// Anthropometry pages, chapter 2, "Stature"): 5th, 50th, 95th percentile and SD. The
/// percentiles are rounded to 5 mm there.
const PHEASANT_US_WOMEN: ([f64; 3], f64) = ([1520.0, 1625.0, 1730.0], 64.0);
const PHEASANT_US_MEN: ([f64; 3], f64) = ([1640.0, 1755.0, 1870.0], 71.0);
/// The standard normal 95th percentile (tables: 1.6449).
const Z95: f64 = 1.644_853_626_951_472_2;

fn pheasant(sex: Sex) -> ([f64; 3], f64) {
    match sex {
        Sex::Female => PHEASANT_US_WOMEN,
        Sex::Male => PHEASANT_US_MEN,
    }
}

/// Checks (label, sex, stature [m], strength percentile) of a standard population member in
/// position `i` (women P5, P50, P95, then men) against the table.
fn check_standard_member(i: usize, label: &str, sex: Sex, stature_m: f64, pct: f64) {
    let (want_sex, name) = if i < 3 {
        (Sex::Female, "woman")
    } else {
        (Sex::Male, "man")
    };
    let (pcts, sd) = pheasant(want_sex);
    let j = i % 3;
    let p = [5.0, 50.0, 95.0][j];
    assert_eq!(sex, want_sex);
    assert_eq!(label, format!("P{p} {name}"));
    // Within the table's 5 mm rounding.
    let mm = 1000.0 * stature_m;
    assert!(
        (mm - pcts[j]).abs() <= 2.5,
        "{label}: {mm} mm vs {} mm",
        pcts[j]
    );
    // The median is the tabulated one, and the spread is the tabulated SD (to its 1 mm).
    if j == 1 {
        assert!((mm - pcts[1]).abs() < 1e-6, "{label}: {mm}");
    } else {
        let implied_sd = (mm - pcts[1]).abs() / Z95;
        assert!(
            (implied_sd - sd).abs() <= 0.5,
            "{label}: SD {implied_sd} vs {sd}"
        );
    }
    // Strength independent of body size (as 3DSSPP treats them): the median for everyone.
    assert_eq!(pct, 50.0, "{label}");
}

/// The shipped strength table (robots/worker.strength.yaml, every number with its source):
/// (half-joint id, male (mean, sd), female (mean, sd)) [N·m].
type StrengthRow = (String, (f64, f64), (f64, f64));
fn strength_table() -> Vec<StrengthRow> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/robots/worker.strength.yaml"
    ))
    .unwrap();
    let v: Value = serde_saphyr::from_str(&text).unwrap();
    let mut out = Vec::new();
    for e in v["half_joints"].as_array().unwrap() {
        let joint = e["joint"].as_str().unwrap();
        let names: Vec<String> = match e["sides"].as_array() {
            Some(sides) => sides
                .iter()
                .map(|s| format!("{}_{joint}", s.as_str().unwrap()))
                .collect(),
            None => vec![joint.to_string()],
        };
        let ms = |s: &str| {
            (
                e[s]["mean_nm"].as_f64().unwrap(),
                e[s]["sd_nm"].as_f64().unwrap(),
            )
        };
        for n in names {
            out.push((
                format!("{n}{}", e["direction"].as_str().unwrap()),
                ms("male"),
                ms("female"),
            ));
        }
    }
    out
}

#[test]
fn standard_population_uses_the_tabulated_percentiles() {
    let p = standard_population();
    assert_eq!(p.len(), 6);
    for (i, m) in p.iter().enumerate() {
        let w = &m.worker;
        check_standard_member(i, &m.label, w.sex, w.stature_m, w.strength_percentile);
        w.validate().unwrap();
    }
    // Body mass (an ASSUMPTION in the code, no table) at least grows with the percentile.
    for s in [0, 3] {
        assert!(p[s].worker.mass_kg < p[s + 1].worker.mass_kg);
        assert!(p[s + 1].worker.mass_kg < p[s + 2].worker.mass_kg);
    }
    // Strength: each worker's MVC of every muscle group is the table's mean + z·SD for the sex
    // and strength percentile (here the median, z = 0; the table's rule floors it at 5 % of the
    // mean).
    let table = strength_table();
    let base: TaskFile = serde_saphyr::from_str(&hold("s", [0.35, -0.2, 1.0], 1.0, 1)).unwrap();
    for m in &p {
        let mut f = base.clone();
        f.worker = m.worker;
        f.robot = None;
        let task = Task::from_task_file(f, Path::new("standard.yaml")).unwrap();
        let z = match m.worker.strength_percentile {
            5.0 => -Z95,
            50.0 => 0.0,
            95.0 => Z95,
            x => panic!("percentile {x}"),
        };
        let mut checked = 0;
        for h in &task.half_joints {
            let (_, male, female) = table
                .iter()
                .find(|(id, _, _)| *id == h.id)
                .unwrap_or_else(|| panic!("{} is not in the strength table", h.id));
            let (mean, sd) = match m.worker.sex {
                Sex::Male => *male,
                Sex::Female => *female,
            };
            let want = (mean + z * sd).max(0.05 * mean);
            assert!(
                (h.mvc_nm - want).abs() <= 1e-9 * want,
                "{} {}: {} vs {want}",
                m.label,
                h.id,
                h.mvc_nm
            );
            checked += 1;
        }
        assert!(checked > 40, "{checked} muscle groups");
    }
}

fn mean_sd(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

#[test]
fn sampled_population_is_reproducible_and_has_the_stated_spread() {
    let n = 6000;
    let a = sampled_population(n, 42);
    assert_eq!(a.len(), n);
    assert_eq!(a, sampled_population(n, 42));
    let b = sampled_population(n, 43);
    assert_ne!(a, b);
    // A smaller sample from the same seed is the start of the larger one.
    assert_eq!(sampled_population(10, 42)[..], a[..10]);
    for (i, m) in a.iter().enumerate() {
        m.worker.validate().unwrap();
        assert_eq!(m.label, format!("#{i:03}"));
        // Sex alternates, women first.
        assert_eq!(
            m.worker.sex,
            if i % 2 == 0 { Sex::Female } else { Sex::Male }
        );
    }
    // Every check below is a 4-standard-error bound (a false alarm about 1 in 16000 each).
    for sex in [Sex::Female, Sex::Male] {
        let of: Vec<_> = a
            .iter()
            .filter(|m| m.worker.sex == sex)
            .map(|m| m.worker)
            .collect();
        let k = of.len() as f64;
        // Stature: normal with the table's median and SD.
        let (pcts, sd_mm) = pheasant(sex);
        let (mu, sigma) = (pcts[1] / 1000.0, sd_mm / 1000.0);
        let s: Vec<f64> = of.iter().map(|w| w.stature_m).collect();
        let (m, sd) = mean_sd(&s);
        assert!(
            (m - mu).abs() < 4.0 * sigma / k.sqrt(),
            "{sex:?} mean stature {m}"
        );
        // SE of a normal sample's SD: σ / √(2(k − 1)).
        assert!(
            (sd - sigma).abs() < 4.0 * sigma / (2.0 * (k - 1.0)).sqrt(),
            "{sex:?} stature SD {sd}"
        );
        // The share of the sample below the table's P5 and P95 values is the normal
        // probability of those values (binomial SE √(p(1−p)/k)).
        let normal = Normal::new(mu, sigma).unwrap();
        for j in [0usize, 2] {
            let p = normal.cdf(pcts[j] / 1000.0);
            let below = s.iter().filter(|x| 1000.0 * **x < pcts[j]).count() as f64 / k;
            assert!(
                (below - p).abs() < 4.0 * (p * (1.0 - p) / k).sqrt(),
                "{sex:?}: {below} below {} mm, expected {p}",
                pcts[j]
            );
        }
        // ln(mass): normal with the stated median (P50) and the spread of the stated P5..P95.
        let masses: [f64; 3] = match sex {
            Sex::Female => [47.0, 62.0, 84.0],
            Sex::Male => [60.0, 78.0, 100.0],
        };
        let ln_sigma = (masses[2] / masses[0]).ln() / (2.0 * Z95);
        let lm: Vec<f64> = of.iter().map(|w| w.mass_kg.ln()).collect();
        let (m, sd) = mean_sd(&lm);
        assert!(
            (m - masses[1].ln()).abs() < 4.0 * ln_sigma / k.sqrt(),
            "{sex:?} ln mass {m}"
        );
        assert!(
            (sd - ln_sigma).abs() < 4.0 * ln_sigma / (2.0 * (k - 1.0)).sqrt() + 1e-3,
            "{sex:?} ln mass SD {sd} vs {ln_sigma}"
        );
        // Stature–ln(mass) correlation 0.45 (Fisher z, SE 1/√(k − 3)).
        let (ms, ss) = mean_sd(&s);
        let (ml, sl) = mean_sd(&lm);
        let r = s
            .iter()
            .zip(&lm)
            .map(|(x, y)| (x - ms) * (y - ml))
            .sum::<f64>()
            / ((k - 1.0) * ss * sl);
        assert!(
            (r.atanh() - 0.45_f64.atanh()).abs() < 4.0 / (k - 3.0).sqrt(),
            "{sex:?} correlation {r}"
        );
        // Strength percentile uniform on [1, 99]: mean 50, SD 98/√12, a quarter below 25.5.
        let pc: Vec<f64> = of.iter().map(|w| w.strength_percentile).collect();
        assert!(pc.iter().all(|p| (1.0..=99.0).contains(p)));
        let (m, sd) = mean_sd(&pc);
        let sigma_u = 98.0 / 12.0_f64.sqrt();
        assert!(
            (m - 50.0).abs() < 4.0 * sigma_u / k.sqrt(),
            "{sex:?} percentile mean {m}"
        );
        // Var(s²) = (μ₄ − σ⁴ (k − 3)/(k − 1)) / k ≈ 0.8 σ⁴ / k for a uniform (μ₄ = 1.8 σ⁴).
        let se_var = sigma_u.powi(2) * (0.8 / k).sqrt();
        assert!(
            (sd * sd - sigma_u * sigma_u).abs() < 4.0 * se_var,
            "{sex:?} percentile SD {sd}"
        );
        let q = pc.iter().filter(|p| **p < 25.5).count() as f64 / k;
        assert!((q - 0.25).abs() < 4.0 * (0.25 * 0.75 / k).sqrt(), "{q}");
    }
}

/// A heavy box: 22 kg held in one hand at elbow height, three times (12 kg, its load until the
/// planner kept the strength curves in its capacity rows, every worker of the standard
/// population now holds; 20 kg, since the wrists have posture zones: the planner finds a deep
/// stoop with the arm hanging for the smaller women too).
fn heavy_task() -> String {
    hold("heavy box", [0.35, -0.2, 1.0], 22.0, 3)
}

#[test]
fn sweep_a_heavy_load_finds_who_cannot() {
    let dir = tempdir();
    let d = dir.path();
    write(d, "heavy.yaml", heavy_task());
    let s = json(d, &["sweep", "heavy.yaml", "--json"]);
    assert_eq!(s["population"], "P5/P50/P95 women and men");
    assert!(s["sustain_all"].is_null());
    let w = s["workers"].as_array().unwrap();
    assert_eq!(w.len(), 6);
    // The standard population, as tabulated.
    for (i, x) in w.iter().enumerate() {
        assert_eq!(x["index"], i);
        let sex = match x["worker"]["sex"].as_str().unwrap() {
            "female" => Sex::Female,
            _ => Sex::Male,
        };
        check_standard_member(
            i,
            x["label"].as_str().unwrap(),
            sex,
            x["worker"]["stature_m"].as_f64().unwrap(),
            x["worker"]["strength_percentile"].as_f64().unwrap(),
        );
    }
    // Proven unable, not planned and able partition the workers: a worker the optimiser could
    // not plan is never counted as unable, and one counted unable has a proven problem.
    let not_planned = |x: &Value| !x["could_not_plan"].as_array().unwrap().is_empty();
    let cannot = w
        .iter()
        .filter(|x| x["can_do"] == false && !not_planned(x))
        .count();
    assert_eq!(s["cannot_do"], cannot);
    assert_eq!(
        s["could_not_plan"],
        w.iter().filter(|x| not_planned(x)).count()
    );
    for x in w {
        if not_planned(x) {
            assert_eq!(x["can_do"], false);
        } else if x["can_do"] == false {
            assert!(x["problems"].as_array().unwrap().iter().any(|p| {
                matches!(p["kind"].as_str(), Some("exhaustion" | "exceeds_strength"))
                    || p["proven"] == true
            }));
        }
    }
    // Someone cannot, someone can.
    assert!(w.iter().any(|x| x["can_do"] == false));
    assert!(w.iter().any(|x| x["can_do"] == true));
    for x in w {
        let problems = x["problems"].as_array().unwrap();
        assert_eq!(x["can_do"], problems.is_empty(), "{}", x["label"]);
        for p in problems {
            // This reachable hold fails only by the muscles, named with the phase.
            let kind = p["kind"].as_str().unwrap();
            assert!(kind == "exhaustion" || kind == "exceeds_strength", "{p}");
            assert_eq!(p["phase"], "place");
            assert!(p["group"].as_str().is_some_and(|g| !g.is_empty()));
        }
    }
    // The text and the HTML lead each able worker's row with the shift verdict (a trial read
    // "can do it" beside an ISO 11226 failure), and the summary counts the verdicts of the able.
    let sweep: posture_opt::study::sweep::Sweep = serde_json::from_value(s.clone()).unwrap();
    let table = posture_opt::study::sweep::sweep_table(&sweep);
    let html = posture_opt::report::html::sweep_report(&sweep, None).unwrap();
    let able: Vec<&posture_opt::study::sweep::WorkerOutcome> =
        sweep.workers.iter().filter(|w| w.can_do).collect();
    for w in &able {
        let row = table
            .lines()
            .find(|l| l.starts_with(&format!("{:<12} ", w.label)))
            .unwrap();
        let binding = w.shift_verdict.split(" — ").next().unwrap();
        assert!(
            row.contains(&format!("shift: {binding}; physically able to do it (")),
            "{row}"
        );
        assert!(
            html.contains(&format!(
                "shift: {}; physically able to do it (",
                binding.replace('\'', "&#39;")
            )),
            "{binding}"
        );
    }
    let count = |status| able.iter().filter(|w| w.shift_status == status).count();
    use posture_opt::assess::verdict::Status;
    let mut expected = Vec::new();
    for (status, words) in [
        (Status::Exceeded, "not acceptable"),
        (Status::NotDetermined, "not determined"),
        (Status::Caution, "conditionally acceptable"),
        (Status::Acceptable, "acceptable"),
    ] {
        if count(status) > 0 {
            expected.push(format!("{words} for {}", count(status)));
        }
    }
    let summary = format!(
        "{} of 6 workers cannot do the task; of the {} able, the shift is {}",
        sweep.cannot_do,
        able.len(),
        expected.join(", ")
    );
    assert!(table.contains(&summary), "{summary}\n{table}");
    // No order by stature is asserted: the standard population's workers share the 50th
    // strength percentile and strength does not scale with body size (docs/strength.md), so a
    // taller, heavier worker is not a stronger one (measured 2026-12-05 at 22 kg: the P5 and P50
    // women can, the P95 woman cannot; the P5 man cannot, the P50 and P95 men can).
}

/// The 95 % Wilson score interval (Wilson 1927) for k of n.
fn wilson_by_hand(k: usize, n: usize) -> (f64, f64, f64) {
    let z = 1.959_963_984_540_054; // standard normal 97.5th percentile
    let (n, p) = (n as f64, k as f64 / n as f64);
    let centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
    let half = z / (1.0 + z * z / n) * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
    (p, (centre - half).max(0.0), (centre + half).min(1.0))
}

#[test]
fn sweep_shards_merge_into_the_unsharded_sweep() {
    let dir = tempdir();
    let d = dir.path();
    write(d, "heavy.yaml", heavy_task());
    let sample = ["--sample", "2", "--seed", "11"];
    let mut args = vec!["sweep", "heavy.yaml", "--json"];
    args.extend(sample);
    let whole = json(d, &args);
    assert_eq!(whole["population"], "sampled n=2 seed=11");
    // The workers are the seeded sample.
    let members = sampled_population(2, 11);
    let w = whole["workers"].as_array().unwrap();
    assert_eq!(w.len(), 2);
    for (x, m) in w.iter().zip(&members) {
        assert_eq!(x["label"], m.label.as_str());
        let back: posture_opt::body::Worker = serde_json::from_value(x["worker"].clone()).unwrap();
        assert_eq!(back, m.worker);
    }
    // The shares who can do it, with Wilson intervals worked by hand.
    for (key, pick) in [
        ("sustain_all", None),
        ("sustain_women", Some("female")),
        ("sustain_men", Some("male")),
    ] {
        let of: Vec<&Value> = w
            .iter()
            .filter(|x| pick.is_none_or(|s| x["worker"]["sex"] == s))
            .collect();
        let k = of.iter().filter(|x| x["can_do"] == true).count();
        let (p, lo, hi) = wilson_by_hand(k, of.len());
        let sh = &whole[key];
        assert_eq!(sh["of"], of.len(), "{key}");
        for (name, v) in [("share", p), ("low", lo), ("high", hi)] {
            assert!(
                (sh[name].as_f64().unwrap() - v).abs() < 1e-12,
                "{key}.{name}: {} vs {v}",
                sh[name]
            );
        }
    }
    // Shards 1/2 (worker 0, a woman) and 2/2 (worker 1, a man), run as separate processes from the seed,
    // merge into the same document, in either order.
    let mut names = Vec::new();
    for (i, s) in ["1/2", "2/2"].iter().enumerate() {
        let mut args = vec!["sweep", "heavy.yaml", "--shard", s];
        args.extend(sample);
        let v = json(d, &args);
        assert_eq!(v["workers_total"], 2);
        let idx: Vec<u64> = v["workers"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x["index"].as_u64().unwrap())
            .collect();
        assert_eq!(idx, [i as u64]);
        let name = format!("sweep{}.json", i + 1);
        write(d, &name, serde_json::to_vec(&v).unwrap());
        names.push(name);
    }
    for order in [[0, 1], [1, 0]] {
        let merged = json(
            d,
            &[
                "sweep",
                "--merge",
                &names[order[0]],
                &names[order[1]],
                "--json",
            ],
        );
        same(&merged, &whole, "merged sweep");
    }
    // Every shard exactly once.
    cli(d, &["sweep", "--merge", "sweep1.json"]).bad(&["missing"]);
    cli(
        d,
        &[
            "sweep",
            "--merge",
            "sweep1.json",
            "sweep2.json",
            "sweep1.json",
        ],
    )
    .bad(&["sweep1.json"]);
    // A shard planned --fatigue-only does not merge with one planned with the discomfort term,
    // nor one whose task fingerprint differs (made from other files).
    let mut args = vec!["sweep", "heavy.yaml", "--shard", "2/2", "--fatigue-only"];
    args.extend(sample);
    let v = json(d, &args);
    assert_eq!(v["fatigue_only"], true);
    write(d, "sweep2_fatigue.json", serde_json::to_vec(&v).unwrap());
    cli(
        d,
        &["sweep", "--merge", "sweep1.json", "sweep2_fatigue.json"],
    )
    .bad(&["sweep2_fatigue.json", "fatigue-only"]);
    let mut args = vec!["sweep", "heavy.yaml", "--shard", "2/2"];
    args.extend(sample);
    let mut v = json(d, &args);
    assert_eq!(v["fatigue_only"], false);
    // the same task planned again merges; a different fingerprint (another file) does not
    write(d, "sweep2_again.json", serde_json::to_vec(&v).unwrap());
    json(
        d,
        &[
            "sweep",
            "--merge",
            "sweep1.json",
            "sweep2_again.json",
            "--json",
        ],
    );
    v["task_fingerprint"] = Value::from("0".repeat(64));
    write(d, "sweep2_other.json", serde_json::to_vec(&v).unwrap());
    cli(d, &["sweep", "--merge", "sweep1.json", "sweep2_other.json"])
        .bad(&["sweep2_other.json", "other files"]);
}

/// The shipped pallet pair: lifting 8 kg boxes from a pallet at 0.30 m, or from the same pallet
/// on a lift table. The lift table lowers the lifting index and the L5/S1 compression (a
/// shallower stoop): an ergonomist picks the lift table, and so must `compare`. (With the trunk
/// extensors as weak in a stoop as Chaffin et al. tabulate, the floor pallet's plan exhausts a
/// group within a minute; a group's fatigue is then not compared, the two plans' simulated times
/// differing.)
#[test]
fn compare_ranks_the_raised_pallet_first() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let v = json(
        root,
        &[
            "compare",
            "tasks/pallet.yaml",
            "tasks/pallet_raised.yaml",
            "--json",
        ],
    );
    let layouts = v["layouts"].as_array().unwrap();
    let by_file = |f: &str| {
        layouts
            .iter()
            .find(|l| l["file"].as_str().unwrap().ends_with(f))
            .unwrap()
    };
    let (floor, raised) = (by_file("pallet.yaml"), by_file("pallet_raised.yaml"));
    let back = |l: &Value| num(&l["back_compression_max_n"]).unwrap();
    assert!(
        back(raised) < back(floor),
        "L5/S1 {} N raised vs {} N on the floor",
        back(raised),
        back(floor)
    );
    assert_eq!(raised["rank"], 1, "{v:#}");
    assert_eq!(floor["rank"], 2);
    a_lift_outside_the_equation_ranks_last(raised);
    let duration = |l: &Value| num(&l["simulated_duration_s"]).unwrap();
    if duration(floor) != duration(raised) {
        for f in v["findings"].as_array().unwrap() {
            let f = f.as_str().unwrap();
            assert!(
                !f.contains("' fatigue "),
                "a group's fatigue over unequal times: {f}"
            );
        }
    }
}

/// NIOSH's lifting index in the ranking, on a real layout's outcome given three indices: a lift
/// outside the equation's limits (RWL 0, no load recommended: the index is not defined) ranks
/// after an index above 3, which ranks after one above 1 (Waters et al. 1994, Applications
/// manual); the deciding sentence says "not defined" rather than skipping the lift.
fn a_lift_outside_the_equation_ranks_last(layout: &Value) {
    use posture_opt::study::compare::{LayoutOutcome, decisive, rank_order};
    let with = |li: Option<f64>, outside: Option<&str>| {
        let mut o: LayoutOutcome = serde_json::from_value(layout.clone()).unwrap();
        o.lifting_index = li;
        o.lifting_outside_limits = outside.map(str::to_string);
        o
    };
    let undefined = with(
        None,
        Some("'table to shelf' at the destination: H 66.5 cm beyond 63 cm (HM = 0)"),
    );
    let (high, moderate) = (with(Some(3.4), None), with(Some(1.45), None));
    assert_eq!(
        rank_order(&high, &undefined, None),
        std::cmp::Ordering::Less
    );
    assert_eq!(rank_order(&moderate, &high, None), std::cmp::Ordering::Less);
    assert_eq!(
        rank_order(&moderate, &undefined, None),
        std::cmp::Ordering::Less
    );
    // indices that NIOSH would report alike (two decimals) tie: a difference of the solver's
    // last digits (an asymmetry of 0.18° against 0.20°, an ergonomist's trial) decides nothing
    let (a, b) = (with(Some(1.009045), None), with(Some(1.009166), None));
    assert_eq!(
        decisive(&a, &b),
        "nothing: the two tie and keep the order given"
    );
    let why = decisive(&moderate, &undefined);
    assert_eq!(
        why,
        "NIOSH's lifting index (not defined (outside the equation's limits) → 1.45)"
    );
}
