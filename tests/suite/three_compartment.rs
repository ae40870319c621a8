//! The three-compartment (3CC) model of Xia & Frey-Law (2008) with the joint parameters of
//! Frey-Law, Looft & Heitsman (2012, J Biomech 45:1803).
//!
//! Expected values: the paper's Table 1 and Table 2 (`tests/data/fatigue/literature/
//! frey_law_2012_tables.csv`); endurance times of the exact continuous model integrated with scipy
//! (`tests/data/fatigue/three_compartment_reference.json`, written by
//! `tests/data/fatigue/make_three_compartment.py`), with the "implied" power curves there: the
//! curves ET = b0 f^b1 for which Table 1's F and R are the least-squares optimum; and an RK4
//! integration of the model written here.
//!
//! Finding reproduced: Table 2's "RMS error" is not the RMS against the Frey-Law & Avin (2010)
//! curves (that is 20.8–413.6 s with the published F, R); it is `S = √(Σe²)/n` (= RMS/3 on the
//! 9-point grids) against the implied curves — for the ankle, trunk, shoulder, elbow and grip
//! (within 0.25 s on the 10–90 %MVC grid, 0.75 s on the 15–95 % test grid), not for the knee and
//! the general curve.

use posture_opt::fatigue::{FatigueModel, Region, ThreeCompartment, ThreeCompartmentState};
use posture_opt::validation::dynamic_validation;
use serde_json::Value;
use std::collections::HashMap;

fn reference() -> Value {
    let path = format!(
        "{}/tests/data/fatigue/three_compartment_reference.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Frey-Law et al. (2012) Tables 1 and 2, by joint.
fn tables() -> HashMap<String, HashMap<String, f64>> {
    let path = format!(
        "{}/tests/data/fatigue/literature/frey_law_2012_tables.csv",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            let values = header[1..]
                .iter()
                .zip(&cells[1..])
                .map(|(h, v)| (h.to_string(), v.parse().unwrap()))
                .collect();
            (cells[0].to_string(), values)
        })
        .collect()
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// Endurance time \[s\] of the library's model: held in 10 ms steps until capacity falls below the
/// load, the crossing located by linear interpolation within the last step.
fn simulated_et_s(m: &ThreeCompartment, f: f64) -> f64 {
    let dt = 0.01;
    let mut s = ThreeCompartmentState::FRESH;
    let mut t = 0.0;
    let mut before = s.capacity();
    loop {
        m.hold(&mut s, f, dt);
        t += dt;
        let c = s.capacity();
        if c < f {
            return t - dt * (f - c) / (before - c);
        }
        before = c;
        assert!(t < 1e5, "no exhaustion");
    }
}

/// Table 1 is what the library uses.
#[test]
fn parameters_are_the_published_ones() {
    let t = tables();
    for region in Region::ALL {
        let row = &t[region.name()];
        assert_eq!(
            region.frey_law_2012_f_r_per_s(),
            (row["F_per_s"], row["R_per_s"]),
            "{region:?}"
        );
        let m = ThreeCompartment::for_region(region);
        assert_eq!((m.ld_per_s, m.lr_per_s), (10.0, 10.0));
        // Looft et al. (2018), Looft & Frey-Law (2020): r = 30 for the hand, 15 elsewhere
        assert_eq!(
            m.rest_multiplier,
            if region == Region::Grip { 30.0 } else { 15.0 }
        );
    }
}

/// The library's RK4 simulation of a sustained hold gives the exact model's endurance time (scipy,
/// 9 loads on each of the paper's two grids, 7 joints) to 1e−4.
#[test]
fn simulated_endurance_matches_the_exact_model() {
    let r = reference();
    for region in Region::ALL {
        let m = ThreeCompartment::for_region(region);
        let j = &r["joints"][region.name()];
        for grid in ["10-90", "15-95"] {
            let loads = r["grids_fmvc"][grid].as_array().unwrap();
            for (f, et) in loads.iter().zip(j[grid]["model_et_s"].as_array().unwrap()) {
                let (f, et) = (num(f), num(et));
                let sim = simulated_et_s(&m, f);
                assert!(
                    (sim / et - 1.0).abs() < 1e-4,
                    "{region:?} {f}: {sim} vs {et}"
                );
            }
        }
    }
}

/// The closed form `ET = −ln(1 − R(1 − TL)/(F TL))/R` (the L → ∞ limit, by hand) is what
/// `endurance_time_s` returns; it differs from the exact L = 10 model by the rise of MA
/// (≈ 1/LD = 0.1 s) and a 2 % change of shape: within 2 % + 0.15 s over 10–95 %MVC.
#[test]
fn closed_form_endurance() {
    let r = reference();
    for region in Region::ALL {
        let m = ThreeCompartment::for_region(region);
        let (f_, r_) = region.frey_law_2012_f_r_per_s();
        for grid in ["10-90", "15-95"] {
            let loads = r["grids_fmvc"][grid].as_array().unwrap();
            for (tl, et) in loads.iter().zip(
                r["joints"][region.name()][grid]["model_et_s"]
                    .as_array()
                    .unwrap(),
            ) {
                let (tl, et) = (num(tl), num(et));
                let by_hand = -(1.0 - r_ * (1.0 - tl) / (f_ * tl)).ln() / r_;
                let closed = m.endurance_time_s(tl).unwrap();
                assert!((closed / by_hand - 1.0).abs() < 1e-12);
                assert!(
                    (closed - et).abs() < 0.02 * et + 0.15,
                    "{region:?} {tl}: {closed} vs {et}"
                );
            }
        }
        assert_eq!(m.endurance_time_s(0.0), None);
        assert_eq!(m.endurance_time_s(1.0), Some(0.0));
    }
}

/// Table 2, reproduced: S = √(Σe²)/n of the library's endurance times against the implied curves
/// equals the published "RMS error" for the ankle, trunk, shoulder, elbow and grip, on the
/// optimisation grid (10–90 %MVC, ±0.25 s) and on the test grid the curves were not built from
/// (15–95 %MVC, ±0.75 s); the mean relative error agrees within 2 (4) percentage points. For the
/// knee and the general curve the same statistic misses by more than 1.5 s on the 10–90 % grid.
#[test]
fn table2_statistic_reproduces_for_five_joints() {
    let r = reference();
    let t = tables();
    for region in Region::ALL {
        let m = ThreeCompartment::for_region(region);
        let j = &r["joints"][region.name()];
        let (b0, b1) = (num(&j["implied_b0_s"]), num(&j["implied_b1"]));
        let published = &t[region.name()];
        for (grid, stat_key, rel_key, tol, rel_tol) in [
            ("10-90", "rms_10_90_s", "mean_rel_10_90_pct", 0.25, 2.0),
            ("15-95", "rms_15_95_s", "mean_rel_15_95_pct", 0.75, 4.0),
        ] {
            let loads: Vec<f64> = r["grids_fmvc"][grid]
                .as_array()
                .unwrap()
                .iter()
                .map(num)
                .collect();
            let n = loads.len() as f64;
            let (mut sq, mut rel) = (0.0, 0.0);
            for &f in &loads {
                let curve = b0 * f.powf(b1);
                let e = simulated_et_s(&m, f) - curve;
                sq += e * e;
                rel += e / curve;
            }
            let s = sq.sqrt() / n;
            let mean_rel = 100.0 * rel / n;
            let paper = published[stat_key];
            match region {
                Region::Knee | Region::General => {
                    if grid == "10-90" {
                        assert!(
                            (s - paper).abs() > 1.5,
                            "{region:?} {grid}: {s} vs {paper} reproduces after all"
                        );
                    }
                }
                _ => {
                    assert!(
                        (s - paper).abs() <= tol,
                        "{region:?} {grid}: S = {s} vs Table 2 {paper}"
                    );
                    if region != Region::Grip {
                        let paper_rel = published[rel_key];
                        assert!(
                            (mean_rel - paper_rel).abs() <= rel_tol,
                            "{region:?} {grid}: {mean_rel} % vs {paper_rel} %"
                        );
                    }
                }
            }
        }
    }
}

/// Against the printed Frey-Law & Avin (2010) curves the published F, R are far from Table 2:
/// RMS 20.8–413.6 s on 10–90 %MVC (scipy reference, ±0.2 s); the library's validation reports the
/// same (simulated in 0.1-s steps).
#[test]
fn rms_against_the_2010_curves() {
    let r = reference();
    let v = dynamic_validation(1.0);
    for region in Region::ALL {
        let j = &r["joints"][region.name()];
        let (b0, b1) = (num(&j["b0_s"]), num(&j["b1"]));
        let expected = num(&j["10-90"]["rms_s_vs_2010"]);
        let m = ThreeCompartment::for_region(region);
        let sq: f64 = (1..=9)
            .map(|i| {
                let f = i as f64 / 10.0;
                (simulated_et_s(&m, f) - b0 * f.powf(b1)).powi(2)
            })
            .sum();
        assert!(((sq / 9.0).sqrt() - expected).abs() < 0.05, "{region:?}");
        let anchor = v
            .frey_law_avin
            .iter()
            .find(|a| a.region == region.name())
            .unwrap();
        assert!(
            (anchor.three_compartment_rms_s - expected).abs() < 0.2,
            "{region:?}: {} vs {expected}",
            anchor.three_compartment_rms_s
        );
        assert!(expected > 2.0 * t_paper(region), "{region:?}");
    }
}

fn t_paper(region: Region) -> f64 {
    tables()[region.name()]["rms_10_90_s"]
}

/// Table 1's observed asymptotes (the sustainable load of the simulated model, %MVC): 0.1 %MVC
/// below it a hold lasts 10 h with capacity above the load; 0.1 %MVC above it, it fails.
#[test]
fn sustainable_load_is_the_published_asymptote() {
    let t = tables();
    for region in Region::ALL {
        let m = ThreeCompartment::for_region(region);
        let asymptote = t[region.name()]["asymptote_observed_pct"] / 100.0;
        for (tl, holds) in [(asymptote - 0.001, true), (asymptote + 0.001, false)] {
            let mut s = ThreeCompartmentState::FRESH;
            let mut lowest = f64::INFINITY;
            for _ in 0..60 {
                m.hold(&mut s, tl, 600.0);
                lowest = lowest.min(s.capacity());
            }
            assert_eq!(
                lowest >= tl,
                holds,
                "{region:?} at {tl}: lowest capacity {lowest}"
            );
        }
        // the L → ∞ asymptote R/(F + R), by hand, lies within 0.03 %MVC below the observed one
        let (f_, r_) = region.frey_law_2012_f_r_per_s();
        let limit = r_ / (f_ + r_);
        assert!(
            asymptote - limit > 0.0 && asymptote - limit < 0.0003,
            "{region:?}: {limit}"
        );
        assert_eq!(m.endurance_time_s(limit * 0.999), None);
    }
}

/// RK4 integration of the 3CC equations written here (1 ms steps), to compare `hold` against.
fn integrate(m: &ThreeCompartment, y0: [f64; 3], u0: f64, tl: f64, dt_s: f64) -> ([f64; 3], f64) {
    let deriv = |y: [f64; 3]| {
        let [ma, mr, mf] = y;
        let c = if ma < tl {
            if mr > tl - ma {
                m.ld_per_s * (tl - ma)
            } else {
                m.ld_per_s * mr
            }
        } else {
            m.lr_per_s * (tl - ma)
        };
        let r = if tl > 0.0 {
            m.r_per_s
        } else {
            m.r_per_s * m.rest_multiplier
        };
        [c - m.f_per_s * ma, -c + r * mf, m.f_per_s * ma - r * mf]
    };
    let du = |y: [f64; 3]| tl / ((y[0] + y[1]) * (y[0] + y[1])) / 60.0;
    let n = (dt_s / 1e-3).round() as usize;
    let h = dt_s / n as f64;
    let (mut y, mut u) = (y0, u0);
    let add =
        |a: [f64; 3], k: [f64; 3], s: f64| [a[0] + s * k[0], a[1] + s * k[1], a[2] + s * k[2]];
    for _ in 0..n {
        let k1 = deriv(y);
        let y2 = add(y, k1, h / 2.0);
        let k2 = deriv(y2);
        let y3 = add(y, k2, h / 2.0);
        let k3 = deriv(y3);
        let y4 = add(y, k3, h);
        let k4 = deriv(y4);
        u += h / 6.0 * (du(y) + 2.0 * du(y2) + 2.0 * du(y3) + du(y4));
        for i in 0..3 {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    (y, u)
}

/// A work–rest history (loads up and down, a rest with the rest multiplier, a load past
/// exhaustion) held by the library equals the integration here; the compartments stay a
/// partition; rest recovers; U grows by ∫ f/c² under load only.
#[test]
fn hold_matches_integration_over_a_history() {
    for region in [Region::Shoulder, Region::Grip, Region::Ankle] {
        let m = ThreeCompartment::for_region(region);
        let mut s = m.fresh();
        let mut y = [0.0, 1.0, 0.0];
        let mut u = 0.0;
        for &(tl, dt) in &[
            (0.4, 60.0),
            (0.2, 30.0),
            (0.0, 120.0),
            (0.7, 45.0),
            (0.95, 30.0),
            (0.1, 20.0),
            (0.0, 300.0),
        ] {
            let before = m.capacity(&s);
            m.hold(&mut s, tl, dt);
            let (y1, u1) = integrate(&m, y, u, tl, dt);
            y = y1;
            u = u1;
            for (got, want) in [s.ma, s.mr, s.mf].iter().zip(y) {
                assert!(
                    (got - want).abs() < 1e-7,
                    "{region:?} TL {tl}: {got} vs {want}"
                );
            }
            assert!(
                (s.fatigue_u_min - u).abs() <= 1e-7 * u.max(1.0),
                "{region:?} TL {tl}: U {} vs {u}",
                s.fatigue_u_min
            );
            assert!((s.ma + s.mr + s.mf - 1.0).abs() < 1e-12);
            assert!(s.ma >= 0.0 && s.mr >= 0.0 && s.mf >= 0.0);
            if tl == 0.0 {
                assert!(m.capacity(&s) > before);
                assert_eq!(m.fatigue_u_min(&s), s.fatigue_u_min);
            }
        }
    }
}

/// At rest the fatigued pool drains at r·R (Looft et al. 2018): after MA has relaxed
/// (1/LR = 0.1 s), MF(t) = MF(0) e^{−r R t} to within the small inflow F·MA.
#[test]
fn rest_recovery_uses_the_multiplier() {
    for region in [Region::Elbow, Region::Grip] {
        let m = ThreeCompartment::for_region(region);
        let mut s = m.fresh();
        m.hold(&mut s, 0.5, 90.0);
        m.hold(&mut s, 0.0, 2.0);
        let mf0 = s.mf;
        m.hold(&mut s, 0.0, 60.0);
        let expected = mf0 * (-m.rest_multiplier * m.r_per_s * 60.0).exp();
        assert!(
            (s.mf / expected - 1.0).abs() < 1e-3,
            "{region:?}: {} vs {expected}",
            s.mf
        );
    }
}
