//! `compare` and `sweep`: ranking, the JSON documents, populations, and cross-checks against
//! `plan`.

use posture_opt::sweep::{sampled_population, standard_population};

mod common;
use common::run;

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = run(args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn compare_ranks_and_agrees_with_plan() {
    let c = json(&[
        "compare",
        "tasks/overhead_drilling.yaml",
        "tasks/shelf_high.yaml",
        "tasks/shelf.yaml",
        "tasks/shelf_lowered.yaml",
        "--json",
    ]);
    let l = c["layouts"].as_array().unwrap();
    assert_eq!(l.len(), 4);
    let files: Vec<&str> = l.iter().map(|x| x["file"].as_str().unwrap()).collect();
    // The shelf layouts hold the hour and rank by total U (lower boards, less shoulder
    // flexion: lower U); the drilling task exhausts and ranks last although its U is smallest.
    assert_eq!(
        files,
        [
            "tasks/shelf_lowered.yaml",
            "tasks/shelf.yaml",
            "tasks/shelf_high.yaml",
            "tasks/overhead_drilling.yaml"
        ]
    );
    assert!(l[3]["exhaustion"]["t_s"].as_f64().unwrap() > 0.0);
    assert!(l[3]["total_u_min"].as_f64() < l[0]["total_u_min"].as_f64());
    for i in 0..2 {
        assert!(l[i]["total_u_min"].as_f64() < l[i + 1]["total_u_min"].as_f64());
        assert!(l[i]["exhaustion"].is_null());
    }
    // Lowering the boards relieves the shoulder flexors and needs less rest.
    assert!(l[0]["worst_u_min"].as_f64() < l[1]["worst_u_min"].as_f64());
    assert!(
        l[0]["rest"]["model"]["rest_s_per_cycle"].as_f64()
            < l[1]["rest"]["model"]["rest_s_per_cycle"].as_f64()
    );
    for (i, x) in l.iter().enumerate() {
        assert_eq!(x["rank"], i + 1);
        for key in [
            "total_u_min",
            "worst_half_joint",
            "worst_group",
            "worst_u_min",
            "min_capacity",
            "exhaustion",
            "rula_max",
            "rest",
        ] {
            assert!(x.get(key).is_some(), "{key} missing");
        }
    }
    // The comparison's figures are the plan's.
    let p = json(&["plan", "tasks/shelf.yaml", "--json"]);
    assert_eq!(l[1]["total_u_min"], p["summary"]["total_u"]);
    assert_eq!(l[1]["worst_u_min"], p["summary"]["worst_u"]);
    assert_eq!(l[1]["rula_max"], p["summary"]["rula_max"]);
    assert_eq!(
        l[1]["rest"]["model"]["rest_s_per_cycle"],
        p["rest"]["model"]["rest_s_per_cycle"]
    );
    // The lowest capacity over time is at most every step's capacity.
    let minc = l[1]["min_capacity"].as_f64().unwrap();
    for s in p["steps"].as_array().unwrap() {
        for c in s["capacity"].as_object().unwrap().values() {
            assert!(c.as_f64().unwrap() >= minc - 1e-15);
        }
    }
    // The text table names both rest rules.
    let (code, out, _) = run(&["compare", "tasks/shelf.yaml", "tasks/shelf_high.yaml"]);
    assert_eq!(code, 0);
    assert!(out.contains("rest needed, model") && out.contains("Rohmert"));
    assert!(out.contains("best layout: tasks/shelf.yaml"));
}

#[test]
fn compare_refuses_bad_input_by_name() {
    let (code, _, err) = run(&["compare", "tasks/shelf.yaml"]);
    assert_eq!(code, 2, "{err}");
    let (code, _, err) = run(&["compare", "tasks/shelf.yaml", "tasks/nope.yaml"]);
    assert_eq!(code, 2);
    assert!(err.contains("tasks/nope.yaml"), "{err}");
    let (code, _, err) = run(&[
        "compare",
        "tasks/shelf.yaml",
        "tasks/shelf_high.yaml",
        "--capacity-floor",
        "1.5",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--capacity-floor"), "{err}");
}

#[test]
fn standard_population_uses_the_tabulated_percentiles() {
    let p = standard_population();
    let statures: Vec<f64> = p.iter().map(|m| m.worker.stature_m).collect();
    // Pheasant (US adults 19-65): women 1520/1625/1730 mm, men 1640/1755/1870 mm (rounded to
    // 5 mm in the table; mean ± 1.645 SD here).
    let expected = [1.520, 1.625, 1.730, 1.640, 1.755, 1.870];
    for (s, e) in statures.iter().zip(expected) {
        assert!((s - e).abs() < 0.005, "{s} vs {e}");
    }
    let pct: Vec<f64> = p.iter().map(|m| m.worker.strength_percentile).collect();
    assert_eq!(pct, [5.0, 50.0, 95.0, 5.0, 50.0, 95.0]);
}

#[test]
fn sampled_population_is_reproducible_and_has_the_stated_spread() {
    let a = sampled_population(4000, 42);
    assert_eq!(a, sampled_population(4000, 42));
    assert_ne!(a, sampled_population(4000, 43));
    let men: Vec<f64> = a
        .iter()
        .filter(|m| m.worker.sex == posture_opt::body::Sex::Male)
        .map(|m| m.worker.stature_m)
        .collect();
    let n = men.len() as f64;
    let mean = men.iter().sum::<f64>() / n;
    let sd = (men.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    // 2000 men: the mean is within 4 standard errors of 1.755 m, the SD within 10 % of 71 mm.
    assert!((mean - 1.755).abs() < 4.0 * 0.071 / n.sqrt(), "{mean}");
    assert!((sd - 0.071).abs() < 0.0071, "{sd}");
    for m in &a {
        m.worker.validate().unwrap();
    }
}

#[test]
fn sweep_finds_who_cannot_do_the_task() {
    let s = json(&["sweep", "tasks/shelf.yaml", "--json"]);
    let w = s["workers"].as_array().unwrap();
    assert_eq!(w.len(), 6);
    let by = |label: &str| w.iter().find(|x| x["label"] == label).unwrap().clone();
    // The 50th-percentile man has the body of robots/worker.urdf: the same plan as `plan`.
    let p = json(&["plan", "tasks/shelf.yaml", "--json"]);
    let m50 = by("P50 man");
    assert_eq!(m50["can_do"], true);
    assert!(
        (m50["total_u_min"].as_f64().unwrap() - p["summary"]["total_u"].as_f64().unwrap()).abs()
            < 1e-9
    );
    // The 5th-percentile woman cannot: exhaustion, with the group, the phase and the time.
    let w5 = by("P5 woman");
    assert_eq!(w5["can_do"], false);
    let prob = &w5["problems"][0];
    assert_eq!(prob["kind"], "exhaustion");
    assert!(prob["phase"].as_str().is_some() && prob["half_joint"].as_str().is_some());
    let cannot = w.iter().filter(|x| x["can_do"] == false).count();
    assert_eq!(s["cannot_do"], cannot);
    // Stronger, larger workers fare no worse: the 95th-percentile man can do it.
    assert_eq!(by("P95 man")["can_do"], true);
    // Sampled workers, text table.
    let (code, out, err) = run(&["sweep", "tasks/shelf.yaml", "--sample", "4", "--seed", "3"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("#000") && out.contains("#003"), "{out}");
    assert!(out.contains("workers cannot do the task"));
}
