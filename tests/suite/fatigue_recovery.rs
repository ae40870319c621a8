//! The shipped `default-2026` parameter set (perfusion-limited recovery) against published
//! endurance and recovery data, and the model's implementation cases under it.
//!
//! Where expected values come from:
//! * **A (implementation)**: derivations by hand written next to each assertion, and
//!   `tests/data/fatigue/reference_default_2026.json`, written by
//!   `tests/data/fatigue/make_reference.py` — numerical integration of the ODE with scipy
//!   (`solve_ivp`, DOP853, rtol 1e−12), independent of the library's closed forms. Tolerance 1e−9
//!   relative (1e−6 where an exhaustion time is found by event detection).
//! * **B (validation)**: the published data in `tests/data/fatigue/literature/` (each file cites its
//!   source). Tolerance bands follow the parameter review's rule (the default-2026 fit's residual at
//!   that point, rounded up to the next 5 %, plus 5 percentage points), stated per case.

use posture_opt::body::Sex;
use posture_opt::fatigue::fit::{MAX_ENDURANCE_S, Measured, Row, predict};
use posture_opt::fatigue::params::{Bound, ParameterSet, ParameterSets};
use posture_opt::fatigue::{MaParams, MaState, Recovery};
use serde_json::Value;
use std::collections::HashMap;

const REGIONS: [&str; 9] = [
    "general", "trunk", "neck", "shoulder", "elbow", "grip", "hip", "knee", "ankle",
];

fn data_path(rel: &str) -> String {
    format!("{}/tests/data/fatigue/{rel}", env!("CARGO_MANIFEST_DIR"))
}

fn reference() -> Value {
    let text = std::fs::read_to_string(data_path("reference_default_2026.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// Rows of a literature CSV (lines starting with `#` are its citation and notes).
fn literature(name: &str) -> Vec<HashMap<String, String>> {
    let text = std::fs::read_to_string(data_path(&format!("literature/{name}"))).unwrap();
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(str::to_string))
                .collect()
        })
        .collect()
}

fn field(row: &HashMap<String, String>, name: &str) -> f64 {
    row[name]
        .parse()
        .unwrap_or_else(|_| panic!("{name}: {}", row[name]))
}

fn default_set() -> ParameterSet {
    let sets = ParameterSets::shipped();
    assert_eq!(sets.default_set, "default-2026");
    sets.get("default-2026").unwrap().clone()
}

/// The region's sex-neutral parameters (the Frey-Law & Avin curves pool both sexes; the elbow's
/// values by sex are checked in `b5_sex_specific_elbow`).
fn params(region: &str) -> MaParams {
    let set = default_set();
    MaParams::with_recovery(set.regions[region].k, set.recovery.recovery()).unwrap()
}

fn rel_err(model: f64, data: f64) -> f64 {
    model / data - 1.0
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

/// Endurance time \[s\] of a fresh group holding `f` for `on_s`, resting `off_s`, repeated (the
/// library's simulation of intermittent work, `fit::predict`); 86 400 s when not exhausted in 24 h.
fn intermittent_s(p: &MaParams, f: f64, on_s: f64, off_s: f64) -> f64 {
    let row = Row {
        line: 0,
        region: "grip".into(),
        load_fmvc: f,
        cycle_s: Some((on_s, off_s)),
        what: Measured::EnduranceS(1.0),
    };
    predict(p, &row)
}

/// `R(f)` of the default set, by hand: 0.37 · x²(3 − 2x), x = 1 − f/0.085 below 0.085.
fn r_default(f: f64) -> f64 {
    let x = 1.0 - f / 0.085;
    if x > 0.0 {
        0.37 * x * x * (3.0 - 2.0 * x)
    } else {
        0.0
    }
}

// ---------------------------------------------------------------------------------------------
// The parameter set the reference values were computed for.
// ---------------------------------------------------------------------------------------------

#[test]
fn shipped_default_set_is_the_one_of_the_reference_values() {
    let set = default_set();
    let r = reference();
    let pr = &r["params"];
    assert_eq!(
        set.recovery.recovery(),
        Recovery::Perfusion {
            rest_per_min: num(&pr["R_rest_per_min"]),
            limit_fmvc: num(&pr["f_lim"]),
        }
    );
    assert_eq!(
        set.recovery_at(Bound::High, Bound::High),
        Recovery::Perfusion {
            rest_per_min: num(&pr["R_rest_high"]),
            limit_fmvc: num(&pr["f_lim_high"]),
        }
    );
    for region in REGIONS {
        assert_eq!(
            set.regions[region].k,
            num(&pr["k_per_min"][region]),
            "{region}"
        );
        for sex in [Sex::Female, Sex::Male] {
            let k = if region == "elbow" {
                num(&pr["k_elbow_by_sex"][if sex == Sex::Female { "female" } else { "male" }])
            } else {
                num(&pr["k_per_min"][region])
            };
            assert_eq!(set.k(region, sex, Bound::Value), k, "{region}");
            if region != "elbow" {
                assert_eq!(
                    set.k(region, sex, Bound::Low),
                    num(&pr["k_low_per_min"][region]),
                    "{region}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// A. Implementation under the default set.
// ---------------------------------------------------------------------------------------------

/// A1–A3: closed forms by hand, k = 1 with the default recovery. A1: 30 %MVC is above the limit
/// (R = 0), `c = 0.8 e^{−0.3·2}`; A2: rest, `c = 1 − 0.5 e^{−0.37·2}`; A3: 5 %MVC,
/// `R(0.05) = 0.37 (7/17)² (3 − 14/17) = 0.37 · 1813/4913`, `c = c∞ + (c0 − c∞) e^{−λt}`.
#[test]
fn a1_a3_closed_forms() {
    let p = MaParams::with_recovery(1.0, default_set().recovery.recovery()).unwrap();
    let hold = |c0: f64, f: f64, t_min: f64| {
        let mut s = MaState {
            capacity: c0,
            fatigue_u_min: 0.0,
            fast_deficit: 0.0,
        };
        assert!(p.hold(&mut s, f, t_min * 60.0));
        s
    };
    assert!(close(
        hold(0.8, 0.3, 2.0).capacity,
        0.8 * (-0.6f64).exp(),
        1e-14
    ));
    assert!(close(
        hold(0.8, 0.3, 2.0).capacity,
        0.439049308875221,
        1e-14
    ));
    assert!(close(
        hold(0.5, 0.0, 2.0).capacity,
        1.0 - 0.5 * (-0.74f64).exp(),
        1e-14
    ));
    let r = 0.37 * 1813.0 / 4913.0;
    assert!(close(p.r_at(0.05), r, 1e-14));
    let lambda = 0.05 + r;
    let c_inf = r / lambda;
    let s = hold(0.9, 0.05, 30.0);
    assert!(close(
        s.capacity,
        c_inf + (0.9 - c_inf) * (-lambda * 30.0).exp(),
        1e-13
    ));
    // A8: U of the same step against the integration
    let reference = reference();
    assert!(close(
        s.capacity,
        num(&reference["a3_a8_low_load"]["capacity"]),
        1e-12
    ));
    assert!(close(
        s.fatigue_u_min,
        num(&reference["a3_a8_low_load"]["u_min"]),
        1e-9
    ));
}

/// A4: R(f) of the default set and its smoothness: R(0) = R_rest, 0 from the limit on, and
/// dR/df = 0 at both ends (C¹: `d/dx [x²(3 − 2x)] = 6x(1 − x)` vanishes at x = 0 and 1).
#[test]
fn a4_recovery_rate_of_the_load() {
    let p = params("shoulder");
    for f in [0.0, 0.02, 0.05, 0.08, 0.0849, 0.085, 0.1, 0.2, 1.0] {
        assert!(
            close(p.r_at(f), r_default(f), 1e-14) || (p.r_at(f) == 0.0 && r_default(f) == 0.0),
            "f={f}"
        );
    }
    assert_eq!(p.r_at(0.0), 0.37);
    assert!(close(p.r_at(0.02), 0.318186444127824, 1e-13));
    assert!(close(p.r_at(0.08), 0.00369020964787299, 1e-12));
    for f in [0.085, 0.1, 0.2, 0.5] {
        assert_eq!(p.r_at(f), 0.0);
    }
    let h = 1e-7;
    assert!(((p.r_at(h) - p.r_at(0.0)) / h).abs() < 1e-4, "slope at 0");
    assert!(
        ((p.r_at(0.085) - p.r_at(0.085 - h)) / h).abs() < 1e-4,
        "slope at the limit"
    );
    // decreasing in between
    let mut last = f64::INFINITY;
    for i in 0..=85 {
        let r = p.r_at(i as f64 / 1000.0);
        assert!(r <= last);
        last = r;
    }
}

/// A5: the shoulder holding 40 %MVC for 100 s, in one step or in 100 steps of 1 s: the same,
/// and equal to the integration.
#[test]
fn a5_step_size_invariance() {
    let p = params("shoulder");
    let mut one = MaState::FRESH;
    p.hold(&mut one, 0.4, 100.0);
    let mut many = MaState::FRESH;
    for _ in 0..100 {
        p.hold(&mut many, 0.4, 1.0);
    }
    assert!((one.capacity - many.capacity).abs() < 1e-12);
    assert!(close(one.fatigue_u_min, many.fatigue_u_min, 1e-11));
    let r = &reference()["shoulder_40pct_100s"];
    assert!(close(one.capacity, num(&r["capacity"]), 1e-11));
    assert!(close(one.fatigue_u_min, num(&r["u_min"]), 1e-9));
}

/// A6, A7, B6a: the paper's set `ma2009` (k = 1, no recovery): MET = −ln f/f (Eq. 8); U at
/// exhaustion `(f⁻² − 1)/2k` (Eq. 6 at c = f); nothing is sustainable; no recovery at rest.
#[test]
fn a6_a7_b6_paper_set() {
    let sets = ParameterSets::shipped();
    let set = sets.get("ma2009").unwrap();
    let reference = reference();
    for region in REGIONS {
        let p = set.params(region, Sex::Female).unwrap();
        assert_eq!(p, MaParams::default(), "{region}");
        assert_eq!(p.sustainable_load(), 0.0);
        for (key, f) in [
            ("0.05", 0.05),
            ("0.20", 0.2),
            ("0.40", 0.4),
            ("0.50", 0.5),
            ("0.60", 0.6),
            ("0.80", 0.8),
        ] {
            let met = p.met_min(f).unwrap();
            assert!(close(met, -f64::ln(f) / f, 1e-13));
            assert!(
                close(met, num(&reference["ma2009_met_min"][key]), 1e-9),
                "f={f}"
            );
        }
        // 50 %MVC: 2 ln 2 min = 83.18 s; U there (0.5⁻² − 1)/2 = 1.5 min
        let mut s = MaState::FRESH;
        p.hold(&mut s, 0.5, 60.0 * 2.0 * 2f64.ln());
        assert!(close(s.capacity, 0.5, 1e-13));
        assert!(close(s.fatigue_u_min, 1.5, 1e-12));
        // 5 %MVC: 59.9 min; rest does not recover
        assert!((p.met_min(0.05).unwrap() - 59.9146).abs() < 1e-4);
        let before = s;
        p.hold(&mut s, 0.0, 600.0);
        assert_eq!(s, before);
    }
}

/// A8 (no recovery): U over a held step is Eq. 6, `(e^{2kft} − 1)/(2k c0²)`.
#[test]
fn a8_fatigue_index_without_recovery() {
    let p = params("shoulder");
    let p1 = MaParams::with_recovery(1.0, p.recovery).unwrap();
    let mut s = MaState::FRESH;
    p1.hold(&mut s, 0.3, 120.0);
    assert!(close(s.fatigue_u_min, (1.2f64).exp_m1() / 2.0, 1e-14));
    assert!(close(s.fatigue_u_min, 1.16005846136827, 1e-13));
    assert!(close(
        s.fatigue_u_min,
        num(&reference()["a8_no_recovery"]["u_min"]),
        1e-10
    ));
}

/// A9 and B2a: the sustainable load f* of every region (c∞(f*) = f*) equals the reference, and
/// lies within 7.0–9.0 %MVC: Björkstén & Jonsson (1977) measured a 60-min sustained limit of
/// 7.9 %MVC; the three-compartment model of Frey-Law et al. (2012) has asymptotes of 6.1–9.4 %MVC
/// (`literature/frey_law_2012_tables.csv`).
#[test]
fn a9_b2a_sustainable_load() {
    let reference = reference();
    let set = default_set();
    for region in REGIONS {
        let p = params(region);
        let fs = p.sustainable_load();
        assert!(
            close(fs, num(&reference["fstar"][region]), 1e-9),
            "{region}: {fs}"
        );
        // by hand: R(f*)(1 − f*) = k f*²
        assert!((r_default(fs) * (1.0 - fs) - p.k_per_min * fs * fs).abs() < 1e-12);
        for sex in [Sex::Female, Sex::Male] {
            let fs = set.params(region, sex).unwrap().sustainable_load();
            assert!((0.070..=0.090).contains(&fs), "{region} {sex:?}: f* = {fs}");
        }
    }
}

/// A10: the default set's sustained endurance times equal the integration.
#[test]
fn a10_sustained_endurance_equals_integration() {
    let reference = reference();
    for region in REGIONS {
        let p = params(region);
        for (key, v) in reference["met_s"][region].as_object().unwrap() {
            let f: f64 = key.parse().unwrap();
            let t = p.time_to_exhaustion_s(1.0, f).unwrap();
            assert!(close(t, num(v), 1e-9), "{region} {f}: {t} vs {v}");
        }
    }
}

/// A11 and B4a: Gonzales & Scheuermann (2007), intermittent handgrip at 50 %MVC, 5 s on / 5 s off,
/// to task failure: 739 s (pooled mean, SE 60 s, n = 22). Model (grip k): exhausted at 734.97 s
/// (reference, 1e−6); band ±25 % (550–925 s), the data's SD being about 280 s.
#[test]
fn a11_b4a_gonzales_scheuermann_intermittent_grip() {
    let data = literature("gonzales_scheuermann_2007_intermittent_grip.csv");
    let pooled = data.iter().find(|r| r["group"] == "pooled").unwrap();
    let (f, on, off, et) = (
        field(pooled, "f"),
        field(pooled, "on_s"),
        field(pooled, "off_s"),
        field(pooled, "et_s"),
    );
    assert_eq!((f, on, off), (0.5, 5.0, 5.0));
    let p = params("grip");
    let t = intermittent_s(&p, f, on, off);
    let r = &reference()["gonzales_grip_50pct_5on_5off_s"];
    assert!(close(t, num(&r["1"]), 1e-6), "{t} vs {}", r["1"]);
    assert!(rel_err(t, et).abs() <= 0.25, "{t} s vs {et} s");
    // exhaustion comes during the 74th work step (cycles of 10 s)
    assert!(t > 730.0 && t < 735.0);
    // sensitivity to R_rest: ×0.95 and ×1.02 as integrated
    for m in ["0.95", "1.02"] {
        let q = MaParams::with_recovery(
            p.k_per_min,
            Recovery::Perfusion {
                rest_per_min: 0.37 * m.parse::<f64>().unwrap(),
                limit_fmvc: 0.085,
            },
        )
        .unwrap();
        assert!(
            close(intermittent_s(&q, f, on, off), num(&r[m]), 1e-6),
            "×{m}"
        );
    }
}

/// A12: with R_rest × 1.05 the same task settles into a periodic state above failure: never
/// exhausted (the simulation ends at its 24-h cap), as the integration finds.
#[test]
fn a12_sustainable_intermittent_task_terminates() {
    let p = MaParams::with_recovery(
        params("grip").k_per_min,
        Recovery::Perfusion {
            rest_per_min: 0.37 * 1.05,
            limit_fmvc: 0.085,
        },
    )
    .unwrap();
    let start = std::time::Instant::now();
    assert_eq!(intermittent_s(&p, 0.5, 5.0, 5.0), MAX_ENDURANCE_S);
    // the integration: not exhausted within 24 h (null)
    assert!(reference()["gonzales_grip_50pct_5on_5off_s"]["1.05"].is_null());
    assert!(start.elapsed().as_secs_f64() < 5.0);
    // the periodic fixed point by hand: per cycle c ↦ α c + β, on: c e^{−k f t_on}, off: 1 − (1 − c) e^{−R t_off}
    let (k, r): (f64, f64) = (p.k_per_min, 0.37 * 1.05);
    let a_on = (-k * 0.5 * 5.0 / 60.0).exp();
    let a_off = (-r * 5.0 / 60.0).exp();
    let (alpha, beta) = (a_on * a_off, 1.0 - a_off);
    let c_start = beta / (1.0 - alpha);
    assert!(
        c_start * a_on > 0.5,
        "lowest capacity of the periodic state {} > load",
        c_start * a_on
    );
}

/// A13: the legacy constant recovery (k = 1, R = 0.3/min) lets loads up to
/// f* = (−R + √(R² + 4kR))/2k = 0.4179 be held forever — a shoulder holding 40 %MVC never tires
/// out. Under the default set the same hold is exhausted after 98.41 s.
#[test]
fn a13_legacy_constant_recovery_vs_default() {
    let legacy = MaParams::new(1.0, 0.3).unwrap();
    let by_hand = (-0.3 + (0.09f64 + 1.2).sqrt()) / 2.0;
    assert!((by_hand - 0.417891).abs() < 1e-6);
    assert!(close(legacy.sustainable_load(), by_hand, 1e-10));
    assert!(close(
        legacy.sustainable_load(),
        num(&reference()["legacy_const_R0_3_k1"]["fstar"]),
        1e-9
    ));
    assert_eq!(legacy.time_to_exhaustion_s(1.0, 0.4), None);
    let t = params("shoulder").time_to_exhaustion_s(1.0, 0.4).unwrap();
    assert!((t - 98.41).abs() < 0.01, "{t}");
}

/// A14, B4b, B4c: Byström, Mathiassen & Fransson-Hall (1991), handgrip at 25 %MVC: continuous
/// 16.2 min; with a 10-s pause every 3 min 23.1 min. k calibrated within the study on the
/// continuous trial (R(0.25) = 0, so by Eq. 8 k = ln 4/(0.25 · 16.2) = 0.342295/min); the
/// intermittent trial is then predicted: 24.43 min (+5.7 %, band ±15 %), and the pauses lengthen
/// endurance by more than 1.2× (data 1.43×).
#[test]
fn a14_b4_bystrom_micropauses() {
    let data = literature("bystrom_1991_micropauses.csv");
    let cont = data
        .iter()
        .find(|r| r["condition"] == "continuous")
        .unwrap();
    let inter = data
        .iter()
        .find(|r| r["condition"] == "intermittent")
        .unwrap();
    let (f, t_cont) = (field(cont, "f"), field(cont, "tlim_min"));
    let k = -f64::ln(f) / (f * t_cont);
    assert!((k - 0.342294904).abs() < 1e-9);
    assert!(close(k, num(&reference()["bystrom"]["k_per_min"]), 1e-9));
    let p = MaParams::with_recovery(k, default_set().recovery.recovery()).unwrap();
    assert!(close(p.met_min(f).unwrap(), t_cont, 1e-12));
    let t = intermittent_s(
        &p,
        field(inter, "f"),
        field(inter, "on_s"),
        field(inter, "off_s"),
    ) / 60.0;
    assert!(
        close(t, num(&reference()["bystrom"]["intermittent_min"]), 1e-6),
        "{t}"
    );
    let measured = field(inter, "tlim_min");
    assert!(
        rel_err(t, measured).abs() <= 0.15,
        "{t} min vs {measured} min"
    );
    assert!(t / t_cont > 1.2, "ratio {}", t / t_cont);
}

/// B4d: intermittent work outlasts sustained work at the same mean load — recovery in the pauses
/// must act (Björkstén & Jonsson 1977: the 60-min limit of the mean force was 14.0 %MVC for
/// intermittent and 7.9 %MVC for sustained contractions). Grip 50 %MVC 5 s/5 s vs 25 %MVC held.
#[test]
fn b4d_intermittent_beats_sustained_at_equal_mean_load() {
    let limits = literature("bjorksten_jonsson_1977_limits.csv");
    let get = |c: &str| {
        field(
            limits.iter().find(|r| r["condition"] == c).unwrap(),
            "mean_force_frac",
        )
    };
    assert!(get("intermittent") > get("sustained"));
    let p = params("grip");
    let inter = intermittent_s(&p, 0.5, 5.0, 5.0);
    let sustained = p.time_to_exhaustion_s(1.0, 0.25).unwrap();
    // by hand, R(0.25) = 0: MET = ln 4/(0.25 k)
    assert!(close(
        sustained,
        60.0 * 4f64.ln() / (0.25 * p.k_per_min),
        1e-12
    ));
    assert!(inter > sustained, "{inter} s vs {sustained} s");
}

// ---------------------------------------------------------------------------------------------
// B1. Sustained endurance vs Frey-Law & Avin (2010).
// ---------------------------------------------------------------------------------------------

/// The curves of Frey-Law & Avin (2010, Ergonomics 53:109, Table 2): ET = b0 f^b1 \[s\].
fn power_curves() -> HashMap<String, (f64, f64)> {
    literature("frey_law_avin_2010_power_curves.csv")
        .iter()
        .map(|r| (r["region"].clone(), (field(r, "b0"), field(r, "b1"))))
        .collect()
}

/// B1: at 20, 40, 60 and 80 %MVC every region's endurance under the default set lies within its
/// band around the Frey-Law & Avin (2010) curve (neck and hip use the 'general' curve). The
/// bands (`literature/frey_law_avin_2010_bands.csv`) are 10–60 %: the one-parameter Eq. 8 is
/// steeper than the power curves (longer at 20–40 %, shorter at 80 %).
#[test]
fn b1_endurance_within_frey_law_avin_bands() {
    let curves = power_curves();
    let bands = literature("frey_law_avin_2010_bands.csv");
    assert_eq!(bands.len(), 28);
    // the coefficients as published
    assert_eq!(curves["shoulder"], (14.86, -1.83));
    assert_eq!(curves["ankle"], (34.71, -2.06));
    let mut failures = Vec::new();
    for band in &bands {
        let (curve, f, tol) = (
            band["region"].as_str(),
            field(band, "f"),
            field(band, "tolerance"),
        );
        let (b0, b1) = curves[curve];
        let data = b0 * f.powf(b1);
        let regions: &[&str] = if curve == "general" {
            &["general", "neck", "hip"]
        } else {
            &[curve]
        };
        for region in regions {
            let model = params(region).time_to_exhaustion_s(1.0, f).unwrap();
            let e = rel_err(model, data);
            if e.abs() > tol {
                failures.push(format!("{region} {f}: model {model:.1} s vs curve {data:.1} s ({:+.1} %, band ±{:.0} %)", 100.0 * e, 100.0 * tol));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    // the worked example: shoulder 40 %MVC, 98.41 s vs 14.86 · 0.4^−1.83 = 79.5 s (+23.8 %)
    assert!((14.86 * 0.4f64.powf(-1.83) - 79.5).abs() < 0.1);
}

/// B1: at 20–60 %MVC the ankle has the longest and the shoulder the shortest endurance of all
/// regions, as in Frey-Law & Avin (2010): ankle most fatigue-resistant, shoulder most fatigable.
#[test]
fn b1_ankle_longest_shoulder_shortest() {
    let curves = power_curves();
    for f in [0.2f64, 0.3, 0.4, 0.5, 0.6] {
        let by_curve: Vec<(&String, f64)> = curves
            .iter()
            .map(|(g, (b0, b1))| (g, b0 * f.powf(*b1)))
            .collect();
        let longest = by_curve
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap()
            .0;
        let shortest = by_curve
            .iter()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap()
            .0;
        assert_eq!(
            (longest.as_str(), shortest.as_str()),
            ("ankle", "shoulder"),
            "the published curves at {f}"
        );
        let model: Vec<(&str, f64)> = REGIONS
            .iter()
            .map(|&g| (g, params(g).time_to_exhaustion_s(1.0, f).unwrap()))
            .collect();
        let longest = model.iter().max_by(|a, b| a.1.total_cmp(&b.1)).unwrap().0;
        let shortest = model.iter().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap().0;
        assert_eq!(
            (longest, shortest),
            ("ankle", "shoulder"),
            "the model at {f}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// B2. Low loads and the sustainable load.
// ---------------------------------------------------------------------------------------------

/// B2b: "no sustained load well above ~15 %MVC lasts forever" — under the default set
/// (f* < 0.16 for every region, sex, and every parameter at either end of its documented range),
/// and with every parameter at its most favourable end (k_low, R_rest = 0.4923, f_lim = 0.15)
/// 15 %MVC still exhausts (shoulder 12.98 min, trunk 27.85 min, ankle 36.22 min, as integrated)
/// and f* ≤ 0.139.
#[test]
fn b2b_no_load_well_above_15pct_is_sustainable() {
    let set = default_set();
    let reference = reference();
    let bounds = [Bound::Low, Bound::Value, Bound::High];
    for region in REGIONS {
        for sex in [Sex::Female, Sex::Male] {
            for kb in bounds {
                for rb in bounds {
                    for lb in bounds {
                        let p = MaParams::with_recovery(
                            set.k(region, sex, kb),
                            set.recovery_at(rb, lb),
                        )
                        .unwrap();
                        let fs = p.sustainable_load();
                        assert!(
                            fs < 0.16,
                            "{region} {sex:?} {kb:?} {rb:?} {lb:?}: f* = {fs}"
                        );
                        assert!(p.time_to_exhaustion_s(1.0, 0.16).is_some());
                    }
                }
            }
        }
        let fav = MaParams::with_recovery(
            set.k(region, Sex::Male, Bound::Low),
            set.recovery_at(Bound::High, Bound::High),
        )
        .unwrap();
        if region != "elbow" {
            let met = fav.met_min(0.15).expect("15 %MVC exhausts");
            assert!(
                close(
                    met,
                    num(&reference["favourable_met_15pct_min"][region]),
                    1e-9
                ),
                "{region}: {met}"
            );
            assert!(close(
                fav.sustainable_load(),
                num(&reference["favourable_fstar"][region]),
                1e-9
            ));
        }
        assert!(fav.sustainable_load() <= 0.139, "{region}");
    }
}

/// B2c: Björkstén & Jonsson (1977): 7.9 %MVC is the 60-min sustained limit. Model (general k):
/// 70.93 min (+18 %); band 45–90 min.
#[test]
fn b2c_bjorksten_jonsson_sustained_limit() {
    let limits = literature("bjorksten_jonsson_1977_limits.csv");
    let row = limits
        .iter()
        .find(|r| r["condition"] == "sustained")
        .unwrap();
    let (f, minutes) = (field(row, "mean_force_frac"), field(row, "duration_min"));
    let met = params("general").met_min(f).unwrap();
    assert!(close(
        met,
        num(&reference()["bjorksten_general_7_9pct_min"]),
        1e-9
    ));
    assert!((45.0..=90.0).contains(&met), "{met} min vs {minutes} min");
}

/// B2d: Mathiassen & Åhsberg (1999), shoulder flexion at 10–21 %MVC:
/// T_lim = 40.609 · exp(−0.097 · %MVC) min. Model (shoulder k) within ±15 %.
#[test]
fn b2d_mathiassen_ahsberg_shoulder() {
    let p = params("shoulder");
    let reference = reference();
    for row in literature("mathiassen_ahsberg_1999_shoulder.csv") {
        let f = field(&row, "f");
        let published = 40.609 * (-0.097 * 100.0 * f).exp();
        assert!(
            (published - field(&row, "met_min")).abs() < 0.01,
            "the regression at {f}"
        );
        let met = p.met_min(f).unwrap();
        assert!(close(
            met,
            num(&reference["mathiassen_shoulder_min"][&format!("{f:.2}")]),
            1e-9
        ));
        assert!(
            rel_err(met, published).abs() <= 0.15,
            "{f}: {met} vs {published}"
        );
    }
}

/// B2e: Sjøgaard, Kiens, Jørgensen & Saltin (1986): knee extension at 5 %MVC for 1 h; MVC was 12 %
/// lower afterwards. The model (capacity 0.726, as integrated) is not exhausted and within
/// 0.65–0.95: it overestimates the loss (27 %), a documented deviation.
#[test]
fn b2e_sjogaard_low_level_hour() {
    let data = literature("sjogaard_1986_low_level.csv");
    let row = &data[0];
    let (f, minutes, after) = (
        field(row, "f"),
        field(row, "duration_min"),
        field(row, "capacity_after"),
    );
    let p = params("knee");
    assert_eq!(p.time_to_exhaustion_s(1.0, f), None);
    let mut s = MaState::FRESH;
    p.hold(&mut s, f, minutes * 60.0);
    assert!(close(
        s.capacity,
        num(&reference()["sjogaard_knee_5pct_60min_capacity"]),
        1e-9
    ));
    assert!(
        (0.65..=0.95).contains(&s.capacity),
        "{} vs {after}",
        s.capacity
    );
    assert!(s.capacity < after);
}

/// B2f: the shoulder at 7 %MVC (below f* = 7.7 %) for 8 h: never exhausted, capacity at
/// c∞ = R(0.07)/(k · 0.07 + R(0.07)) = 0.2378 (by hand).
#[test]
fn b2f_below_the_sustainable_load() {
    let p = params("shoulder");
    assert_eq!(p.time_to_exhaustion_s(1.0, 0.07), None);
    let r = r_default(0.07);
    let c_inf = r / (p.k_per_min * 0.07 + r);
    let mut s = MaState::FRESH;
    assert!(p.hold(&mut s, 0.07, 8.0 * 3600.0));
    assert!(close(s.capacity, c_inf, 1e-9));
    assert!((s.capacity - 0.2378).abs() < 1e-4);
    assert!(close(
        s.capacity,
        num(&reference()["shoulder_7pct_480min_capacity"]),
        1e-9
    ));
}

// ---------------------------------------------------------------------------------------------
// B3. Recovery in rest.
// ---------------------------------------------------------------------------------------------

/// B3a: from capacity 0.5 (50 %MVC held to exhaustion), resting: `c = 1 − 0.5 e^{−0.37 t}`.
#[test]
fn b3a_recovery_at_rest() {
    let reference = reference();
    let p = params("elbow");
    for (key, t_min) in [
        ("0.25", 0.25),
        ("0.5", 0.5),
        ("1", 1.0),
        ("2", 2.0),
        ("5", 5.0),
        ("10", 10.0),
    ] {
        let mut s = MaState {
            capacity: 0.5,
            fatigue_u_min: 1.0,
            fast_deficit: 0.0,
        };
        p.hold(&mut s, 0.0, t_min * 60.0);
        assert!(close(s.capacity, 1.0 - 0.5 * (-0.37 * t_min).exp(), 1e-14));
        assert!(close(
            s.capacity,
            num(&reference["rest_after_half_capacity"][key]),
            1e-12
        ));
        assert_eq!(s.fatigue_u_min, 1.0);
    }
}

/// B3b–d: Sahlin & Ren (1989), knee extension at 66 %MVC to fatigue, rest, again: endurance
/// half-recovered after about 1.2 min, still significantly depressed after 2 and 4 min; MVC back
/// to its pre-contraction value (n.s.) after 2 min. Model: ratio 0.408 at 1.2 min (band
/// 0.35–0.60), < 1 at 2 and 4 min; capacity after 2 min ≥ 0.8 (0.838).
#[test]
fn b3_sahlin_ren_endurance_recovery() {
    let data = literature("sahlin_ren_1989_recovery.csv");
    let half = data.iter().find(|r| r["use"] == "fit").unwrap();
    let (f, rest_half, ratio_half) = (
        field(half, "f"),
        field(half, "rest_min"),
        field(half, "value"),
    );
    let p = params("knee");
    let first = p.time_to_exhaustion_s(1.0, f).unwrap();
    let reference = reference();
    let ratio = |rest_min: f64| {
        let mut s = MaState {
            capacity: f,
            fatigue_u_min: 0.0,
            fast_deficit: 0.0,
        };
        p.hold(&mut s, 0.0, rest_min * 60.0);
        (
            p.time_to_exhaustion_s(s.capacity, f).unwrap() / first,
            s.capacity,
        )
    };
    let (r12, _) = ratio(rest_half);
    assert!(close(
        r12,
        num(&reference["sahlin_knee_66pct"]["1.2"]["second_over_first"]),
        1e-9
    ));
    assert!((0.35..=0.60).contains(&r12), "{r12} vs {ratio_half}");
    for (key, rest) in [("2", 2.0), ("4", 4.0)] {
        let (r, c) = ratio(rest);
        assert!(close(
            r,
            num(&reference["sahlin_knee_66pct"][key]["second_over_first"]),
            1e-9
        ));
        assert!(close(
            c,
            num(&reference["sahlin_knee_66pct"][key]["capacity_after_rest"]),
            1e-12
        ));
        assert!(r < 1.0, "{rest} min: {r}");
    }
    let (_, c2) = ratio(2.0);
    assert!(c2 >= 0.8, "{c2}");
}

/// B3e: Stull & Kearney (1978), handgrip at 50 %MVC to exhaustion (first bout 120.25 s; k
/// calibrated on it: k = ln 2/(0.5 · 120.25/60)), 5 s of rest, again: second bout 20.3 % of the
/// first. The one-time-constant model recovers far less in 5 s (4.3 %, as integrated): a
/// documented deviation; only 0 < ratio < 0.203 is asserted.
#[test]
fn b3e_stull_kearney_micro_pause() {
    let data = literature("stull_kearney_1978_endurance_recovery.csv");
    let row = data.iter().find(|r| field(r, "rest_s") == 5.0).unwrap();
    let (f, first_s, ratio_data) = (
        field(row, "f"),
        field(row, "first_bout_s"),
        field(row, "second_over_first"),
    );
    let k = 2f64.ln() / (f * first_s / 60.0);
    assert!(close(
        k,
        num(&reference()["stull_kearney"]["k_per_min"]),
        1e-9
    ));
    let p = MaParams::with_recovery(k, default_set().recovery.recovery()).unwrap();
    assert!(close(
        p.time_to_exhaustion_s(1.0, f).unwrap(),
        first_s,
        1e-12
    ));
    let mut s = MaState {
        capacity: f,
        fatigue_u_min: 0.0,
        fast_deficit: 0.0,
    };
    p.hold(&mut s, 0.0, field(row, "rest_s"));
    let ratio = p.time_to_exhaustion_s(s.capacity, f).unwrap() / first_s;
    assert!(close(
        ratio,
        num(&reference()["stull_kearney"]["second_over_first_5s"]),
        1e-9
    ));
    assert!(ratio > 0.0 && ratio < ratio_data, "{ratio}");
}

// ---------------------------------------------------------------------------------------------
// B5. Sex-specific elbow.
// ---------------------------------------------------------------------------------------------

/// B5: Avin et al. (2010), 50 %MVC held to failure: elbow flexion women 112.3 ± 6.2 s, men
/// 80.3 ± 5.8 s (significant); ankle dorsiflexion 140.6 vs 129.2 s (n.s.). Model within ±10 % for
/// the elbow; the sets differ between the sexes in the elbow only.
#[test]
fn b5_sex_specific_elbow() {
    let data = literature("avin_2010_sex_differences.csv");
    let set = default_set();
    let reference = reference();
    for row in data.iter().filter(|r| r["region"] == "elbow") {
        let sex = if row["sex"] == "female" {
            Sex::Female
        } else {
            Sex::Male
        };
        let p = set.params("elbow", sex).unwrap();
        let t = p.time_to_exhaustion_s(1.0, field(row, "f")).unwrap();
        assert!(close(
            t,
            num(&reference["met_s_elbow_by_sex_50pct"][row["sex"].as_str()]),
            1e-9
        ));
        let measured = field(row, "et_s");
        assert!(
            rel_err(t, measured).abs() <= 0.10,
            "{}: {t} s vs {measured} s",
            row["sex"]
        );
    }
    for region in REGIONS {
        let same =
            set.params(region, Sex::Female).unwrap() == set.params(region, Sex::Male).unwrap();
        assert_eq!(same, region != "elbow", "{region}");
    }
    let ankle = set.params("ankle", Sex::Female).unwrap();
    assert!((ankle.time_to_exhaustion_s(1.0, 0.5).unwrap() - 166.2).abs() < 0.1);
}
