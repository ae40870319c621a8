//! The three-compartment model: simulation against its sustained-load closed form.

use posture_opt::fatigue::{FatigueModel, Region, ThreeCompartment};

#[test]
fn simulated_endurance_matches_closed_form() {
    for region in Region::ALL {
        let m = ThreeCompartment::for_region(region);
        for &f in &[0.3, 0.5, 0.7] {
            let et = m.endurance_time_s(f).unwrap();
            let mut s = m.fresh();
            let dt = 0.05;
            let mut t = 0.0;
            while m.capacity(&s) >= f && t < 1e5 {
                m.hold(&mut s, f, dt);
                t += dt;
            }
            // closed form neglects MA's rise (≈ 1/LD = 0.1 s)
            assert!(
                (t - et).abs() < 0.01 * et + 0.5,
                "{region:?} f={f}: sim {t} vs closed {et}"
            );
        }
    }
}

#[test]
fn compartments_stay_a_partition_and_recover_at_rest() {
    let m = ThreeCompartment::for_region(Region::Shoulder);
    let mut s = m.fresh();
    m.hold(&mut s, 0.4, 60.0);
    let tired = m.capacity(&s);
    assert!((s.ma + s.mr + s.mf - 1.0).abs() < 1e-9);
    assert!(tired < 1.0);
    m.hold(&mut s, 0.0, 120.0);
    assert!(m.capacity(&s) > tired);
    assert!((s.ma + s.mr + s.mf - 1.0).abs() < 1e-9);
}

#[test]
fn light_load_is_never_exhausting() {
    // ET exists only when R(1 − TL)/(F·TL) < 1; for the ankle at 5 %: 0.00058·0.95/(0.00589·0.05) = 1.87
    assert_eq!(
        ThreeCompartment::for_region(Region::Ankle).endurance_time_s(0.05),
        None
    );
}
