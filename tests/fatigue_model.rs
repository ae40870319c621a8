//! The Ma et al. model's closed forms against numerical integration of its ODEs, and its
//! invariants as properties.

use posture_opt::fatigue::{met_min, MaParams, MaState};
use proptest::prelude::*;

/// Fine RK4 integration of dc/dt = −k f c + R (1 − c), dU/dt = f / c² (t in minutes).
fn integrate(k: f64, r: f64, f: f64, c0: f64, u0: f64, t_min: f64) -> (f64, f64) {
    let n = 200_000;
    let h = t_min / n as f64;
    let d = |c: f64| (-k * f * c + r * (1.0 - c), f / (c * c));
    let (mut c, mut u) = (c0, u0);
    for _ in 0..n {
        let (a1, b1) = d(c);
        let (a2, b2) = d(c + h / 2.0 * a1);
        let (a3, b3) = d(c + h / 2.0 * a2);
        let (a4, b4) = d(c + h * a3);
        c += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
        u += h / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4);
    }
    (c, u)
}

#[test]
fn closed_form_matches_integration_without_recovery() {
    for &(f, t_min, c0) in &[
        (0.3, 2.0, 1.0),
        (0.8, 0.5, 0.9),
        (0.05, 30.0, 0.6),
        (1.0, 1.0, 1.0),
    ] {
        let p = MaParams::new(1.3, 0.0).unwrap();
        let mut s = MaState {
            capacity: c0,
            fatigue_u_min: 0.25,
        };
        p.hold(&mut s, f, t_min * 60.0);
        let (c, u) = integrate(1.3, 0.0, f, c0, 0.25, t_min);
        assert!(
            (s.capacity - c).abs() < 1e-10 * c.max(1e-3),
            "f={f}: c {} vs {c}",
            s.capacity
        );
        assert!(
            (s.fatigue_u_min - u).abs() < 1e-8 * u,
            "f={f}: U {} vs {u}",
            s.fatigue_u_min
        );
    }
}

#[test]
fn closed_form_matches_integration_with_recovery() {
    // includes a case where c_inf·(e^{λt} − 1) is tiny (series branch) and large ones
    for &(k, r, f, t_min, c0) in &[
        (1.0, 0.5, 0.3, 3.0, 1.0),
        (0.8, 2.0, 0.6, 1.5, 0.7),
        (1.0, 1e-6, 0.4, 0.01, 0.9),
        (1.4, 0.2, 0.15, 20.0, 0.5),
        (1.0, 0.3, 0.0, 5.0, 0.4),
    ] {
        let p = MaParams::new(k, r).unwrap();
        let mut s = MaState {
            capacity: c0,
            fatigue_u_min: 1.0,
        };
        p.hold(&mut s, f, t_min * 60.0);
        let (c, u) = integrate(k, r, f, c0, 1.0, t_min);
        assert!((s.capacity - c).abs() < 1e-10, "c {} vs {c}", s.capacity);
        assert!(
            (s.fatigue_u_min - u).abs() < 1e-8 * u,
            "U {} vs {u}",
            s.fatigue_u_min
        );
    }
}

#[test]
fn paper_eq6_for_a_load_history() {
    // Eq. 6: U(t) = (e^{2kF(t)} − 1)/(2k) with F(t) = ∫ f du, for a piecewise-constant history.
    let p = MaParams::new(0.9, 0.0).unwrap();
    let steps = [(0.2, 30.0), (0.5, 12.0), (0.0, 60.0), (0.35, 45.0)];
    let mut s = MaState::FRESH;
    let mut big_f = 0.0;
    for &(f, dt_s) in &steps {
        p.hold(&mut s, f, dt_s);
        big_f += f * dt_s / 60.0;
    }
    let u = ((2.0 * 0.9 * big_f).exp() - 1.0) / (2.0 * 0.9);
    assert!((s.fatigue_u_min - u).abs() < 1e-13);
    assert!((s.capacity - (-0.9 * big_f).exp()).abs() < 1e-15);
}

#[test]
fn met_by_hand() {
    // f = 0.5, k = 1: MET = ln 2 / 0.5 = 1.386294 min
    assert!((met_min(0.5, 1.0) - 1.3862943611198906).abs() < 1e-15);
    assert_eq!(met_min(1.0, 1.0), 0.0);
    // with recovery R = 0.25, f = 0.5, k = 1: λ = 0.75, c∞ = 1/3, t = ln((1 − 1/3)/(0.5 − 1/3))/0.75 = ln 4 / 0.75
    let p = MaParams::new(1.0, 0.25).unwrap();
    assert!((p.met_min(0.5).unwrap() - 4f64.ln() / 0.75).abs() < 1e-12);
    // a load recovery can balance (c∞ = 0.5 ≥ f = 0.2... λ = 0.2+0.25, c∞ = 0.556) is never exhausting
    assert_eq!(p.met_min(0.2), None);
}

#[test]
fn extreme_holds_stay_finite() {
    let p = MaParams::default();
    let mut s = MaState::FRESH;
    p.hold(&mut s, 1.0, 3600.0 * 24.0);
    assert!(s.capacity > 0.0 && s.capacity <= 1.0);
    assert!(s.fatigue_u_min.is_finite());
}

#[test]
fn rejects_bad_parameters() {
    assert!(MaParams::new(0.0, 0.0).is_err());
    assert!(MaParams::new(f64::NAN, 0.0).is_err());
    assert!(MaParams::new(1.0, -0.1).is_err());
    assert!(MaParams::new(1.0, f64::INFINITY).is_err());
}

proptest! {
    #[test]
    fn capacity_in_unit_interval_and_non_increasing_without_recovery(
        k in 0.1f64..3.0, f in 0.0f64..1.0, dts in proptest::collection::vec(0.0f64..600.0, 1..20)
    ) {
        let p = MaParams::new(k, 0.0).unwrap();
        let mut s = MaState::FRESH;
        for dt in dts {
            let before = s;
            p.hold(&mut s, f, dt);
            prop_assert!(s.capacity > 0.0 && s.capacity <= 1.0);
            prop_assert!(s.capacity <= before.capacity);
            prop_assert!(s.fatigue_u_min >= before.fatigue_u_min);
            if f > 0.0 && dt > 1e-3 {
                prop_assert!(s.fatigue_u_min > before.fatigue_u_min);
            }
        }
    }

    #[test]
    fn rest_with_recovery_rises_toward_one(
        r in 0.01f64..2.0, c0 in 0.01f64..1.0, dt in 0.1f64..600.0
    ) {
        let p = MaParams::new(1.0, r).unwrap();
        let mut s = MaState { capacity: c0, fatigue_u_min: 3.0 };
        p.hold(&mut s, 0.0, dt);
        prop_assert!(s.capacity >= c0 && s.capacity <= 1.0);
        prop_assert!(1.0 - s.capacity <= (1.0 - c0) * (1.0 + 1e-12));
        prop_assert_eq!(s.fatigue_u_min, 3.0);
    }

    #[test]
    fn holding_for_met_brings_capacity_to_the_load(
        k in 0.2f64..3.0, r in 0.0f64..0.5, f in 0.05f64..1.0
    ) {
        let p = MaParams::new(k, r).unwrap();
        if let Some(t_s) = p.time_to_exhaustion_s(1.0, f) {
            let mut s = MaState::FRESH;
            p.hold(&mut s, f, t_s);
            prop_assert!((s.capacity - f).abs() < 1e-9, "c = {} f = {}", s.capacity, f);
        } else {
            // never exhausted: recovery's equilibrium is at or above the load
            prop_assert!(r / (k * f + r) >= f);
        }
    }

    #[test]
    fn splitting_a_step_changes_nothing(
        k in 0.2f64..3.0, r in 0.0f64..1.0, f in 0.0f64..1.0, dt in 0.0f64..900.0, split in 0.0f64..1.0
    ) {
        let p = MaParams::new(k, r).unwrap();
        let mut one = MaState::FRESH;
        p.hold(&mut one, f, dt);
        let mut two = MaState::FRESH;
        p.hold(&mut two, f, dt * split);
        p.hold(&mut two, f, dt * (1.0 - split));
        prop_assert!((one.capacity - two.capacity).abs() < 1e-12);
        prop_assert!((one.fatigue_u_min - two.fatigue_u_min).abs() <= 1e-9 * one.fatigue_u_min.max(1.0));
    }
}
