//! L5/S1 compression and shear (`posture_opt::assess::low_back`), single-equivalent-muscle model
//! (Chaffin DB, Andersson GBJ, Martin BJ, *Occupational Biomechanics*, 4th ed., Wiley 2006, the
//! static sagittal-plane low-back model): one equivalent extensor, parallel to the spine at a
//! moment arm E ≈ 5 cm behind the L5/S1 joint centre, balances the sagittal moment of everything
//! above L5/S1:
//!
//! ```text
//! F_muscle = M_sagittal / E,   compression = F_muscle + (component of the load along the spine),
//! anterior shear = component of the load along the anterior axis.
//! ```
//!
//! Limits: compression action limit 3400 N and maximum permissible limit 6400 N (NIOSH, *Work
//! Practices Guide for Manual Lifting*, DHHS (NIOSH) Publication No. 81-122, 1981; 3.4 kN is the
//! biomechanical criterion of the revised lifting equation, Waters et al. 1993, Ergonomics
//! 36(7):749–776); shear 1000 N for occasional loading (Gallagher & Marras 2012, Clinical
//! Biomechanics 27(10):973–978).
//!
//! Every expected value is derived by hand in the test's comment. World frame: x forward, y left,
//! z up; g = 9.81 m/s².

use approx::assert_abs_diff_eq;
use posture_opt::assess::low_back::{
    BackParams, BalancingMuscle, CompressionVerdict, LowBackError, LumbarLoad, ShearVerdict,
    low_back,
};

const G: f64 = 9.81;

/// Upright spine: the spine axis is +z, the anterior axis +x.
fn upright(moment_nm: [f64; 3], force_n: [f64; 3]) -> LumbarLoad {
    LumbarLoad {
        moment_nm,
        force_n,
        spine_axis: [0.0, 0.0, 1.0],
        forward_axis: [1.0, 0.0, 0.0],
    }
}

/// The published constants: E = 5 cm (Chaffin et al.), 3400 N / 6400 N (NIOSH 1981), 1000 N
/// shear (Gallagher & Marras 2012).
#[test]
fn default_parameters_are_the_published_ones() {
    let p = BackParams::default();
    assert_eq!(p.erector_moment_arm_m, 0.05);
    assert_eq!(p.compression_action_limit_n, 3400.0);
    assert_eq!(p.compression_max_limit_n, 6400.0);
    assert_eq!(p.shear_limit_n, 1000.0);
}

/// Upright, no hand load, a 50 N·m flexion moment about L5/S1 (the upper body's weight acting in
/// front of the joint) and an upper body of 40 kg.
///
/// By hand: a flexion moment turns the trunk forward, i.e. about +y (left) for a body facing +x:
/// M = (0, 50, 0) N·m. Extensor force = M / E = 50 / 0.05 = 1000 N, along the spine. The upper
/// body's weight W = 40 · 9.81 = 392.4 N acts straight down the vertical spine. Compression =
/// 1000 + 392.4 = 1392.4 N; anterior shear = W · (anterior axis · −z) = 0.
#[test]
fn upright_50_nm_with_a_5_cm_extensor_arm() {
    let w = 40.0 * G;
    let r = low_back(
        &upright([0.0, 50.0, 0.0], [0.0, 0.0, -w]),
        &BackParams::default(),
    )
    .unwrap();
    assert_abs_diff_eq!(r.sagittal_moment_nm, 50.0, epsilon = 1e-12);
    assert_abs_diff_eq!(r.extensor_force_n, 1000.0, epsilon = 1e-9);
    assert_abs_diff_eq!(r.muscle_compression_n, 1000.0, epsilon = 1e-9);
    assert_abs_diff_eq!(r.load_compression_n, 392.4, epsilon = 1e-9);
    assert_abs_diff_eq!(r.compression_n, 1392.4, epsilon = 1e-9);
    assert_abs_diff_eq!(r.shear_ap_n, 0.0, epsilon = 1e-12);
    assert_abs_diff_eq!(r.shear_resultant_n, 0.0, epsilon = 1e-12);
    assert_eq!(r.balancing_muscle, BalancingMuscle::Extensors);
    assert_eq!(r.flexor_force_n, 0.0);
    assert_eq!(r.compression_verdict, CompressionVerdict::WithinActionLimit);
    assert_eq!(r.shear_verdict, ShearVerdict::WithinLimit);
}

/// The same load with a 6 cm extensor moment arm: 50 / 0.06 = 833.333 N of muscle force;
/// compression 833.333 + 392.4 = 1225.733 N. The muscle force is inversely proportional to E.
#[test]
fn extensor_moment_arm_scales_the_muscle_force() {
    let p = BackParams {
        erector_moment_arm_m: 0.06,
        ..BackParams::default()
    };
    let r = low_back(&upright([0.0, 50.0, 0.0], [0.0, 0.0, -40.0 * G]), &p).unwrap();
    assert_abs_diff_eq!(r.extensor_force_n, 50.0 / 0.06, epsilon = 1e-9);
    assert_abs_diff_eq!(r.compression_n, 833.333_333 + 392.4, epsilon = 1e-5);
}

/// Upright, 15 kg held in both hands 0.45 m in front of L5/S1 (0.30 m above it), upper body
/// 40 kg centred 0.02 m in front of L5/S1.
///
/// By hand, moments about L5/S1 (M_y = r_x · W for a weight W at horizontal distance r_x):
/// hands 0.45 · 147.15 = 66.2175 N·m; upper body 0.02 · 392.4 = 7.848 N·m; M = 74.0655 N·m.
/// Extensor = 74.0655 / 0.05 = 1481.31 N. Load along the spine = 147.15 + 392.4 = 539.55 N.
/// Compression = 2020.86 N. The height of the hands does not enter.
#[test]
fn upright_holding_15_kg_at_45_cm() {
    let (wh, wb) = (15.0 * G, 40.0 * G);
    // M = Σ r × F with F = (0, 0, −W): M_y = −r_x·F_z = r_x·W.
    let m = [0.0, 0.45 * wh + 0.02 * wb, 0.0];
    let r = low_back(&upright(m, [0.0, 0.0, -(wh + wb)]), &BackParams::default()).unwrap();
    assert_abs_diff_eq!(r.sagittal_moment_nm, 74.0655, epsilon = 1e-9);
    assert_abs_diff_eq!(r.extensor_force_n, 1481.31, epsilon = 1e-9);
    assert_abs_diff_eq!(r.load_compression_n, 539.55, epsilon = 1e-9);
    assert_abs_diff_eq!(r.compression_n, 2020.86, epsilon = 1e-9);
}

/// Stoop: trunk flexed 45°. Spine axis s = (sin 45°, 0, cos 45°), anterior axis
/// f = (cos 45°, 0, −sin 45°), lateral axis s × f = (0, 1, 0).
///
/// Upper body 40 kg with its centre 0.30 m up the spine: horizontal lever 0.30 · sin 45° =
/// 0.212132 m → 0.212132 · 392.4 = 83.2406 N·m. 15 kg in the hands 0.45 m in front of L5/S1:
/// 66.2175 N·m. M = 149.4581 N·m → extensor 2989.162 N. Total weight 539.55 N: along the spine
/// 539.55 · cos 45° = 381.5194 N (compression), along the anterior axis
/// (−539.55 z)·f = 539.55 · sin 45° = 381.5194 N (anterior shear: the upper body slides
/// forward). Compression = 2989.162 + 381.519 = 3370.681 N: just inside the 3400 N action
/// limit.
#[test]
fn stoop_45_degrees_with_15_kg() {
    let (sn, cs) = (45f64.to_radians().sin(), 45f64.to_radians().cos());
    let (wh, wb) = (15.0 * G, 40.0 * G);
    let m = [0.0, 0.30 * sn * wb + 0.45 * wh, 0.0];
    let load = LumbarLoad {
        moment_nm: m,
        force_n: [0.0, 0.0, -(wh + wb)],
        spine_axis: [sn, 0.0, cs],
        forward_axis: [cs, 0.0, -sn],
    };
    let r = low_back(&load, &BackParams::default()).unwrap();
    assert_abs_diff_eq!(r.sagittal_moment_nm, 149.4581, epsilon = 1e-4);
    assert_abs_diff_eq!(r.extensor_force_n, 2989.162, epsilon = 1e-3);
    assert_abs_diff_eq!(r.load_compression_n, 381.5194, epsilon = 1e-4);
    assert_abs_diff_eq!(r.compression_n, 3370.681, epsilon = 1e-3);
    assert_abs_diff_eq!(r.shear_ap_n, 381.5194, epsilon = 1e-4);
    assert_abs_diff_eq!(r.shear_lateral_n, 0.0, epsilon = 1e-9);
    assert_abs_diff_eq!(r.lateral_axis[1], 1.0, epsilon = 1e-12);
    assert_eq!(r.compression_verdict, CompressionVerdict::WithinActionLimit);
    // 5 kg more in the hands (0.45 · 49.05 = 22.0725 N·m → +441.45 N of muscle force,
    // +34.68 N along the spine) passes the action limit: 3846.81 N.
    let extra = 5.0 * G;
    let load = LumbarLoad {
        moment_nm: [0.0, m[1] + 0.45 * extra, 0.0],
        force_n: [0.0, 0.0, -(wh + wb + extra)],
        ..load
    };
    let r = low_back(&load, &BackParams::default()).unwrap();
    assert_abs_diff_eq!(
        r.compression_n,
        3370.681 + 441.45 + extra * cs,
        epsilon = 1e-3
    );
    assert_eq!(r.compression_verdict, CompressionVerdict::AboveActionLimit);
}

/// The NIOSH (1981) compression limits and the 1000 N shear limit, at and beyond each limit
/// (the module treats "at the limit" as within it). Upright, no moment: compression = the load
/// along the spine; shear = the horizontal load.
#[test]
fn limits_flag_compression_and_shear() {
    let p = BackParams::default();
    let c = |n: f64| low_back(&upright([0.0; 3], [0.0, 0.0, -n]), &p).unwrap();
    assert_eq!(
        c(3399.0).compression_verdict,
        CompressionVerdict::WithinActionLimit
    );
    assert_eq!(
        c(3400.0).compression_verdict,
        CompressionVerdict::WithinActionLimit
    );
    assert_eq!(
        c(3401.0).compression_verdict,
        CompressionVerdict::AboveActionLimit
    );
    assert_eq!(
        c(6400.0).compression_verdict,
        CompressionVerdict::AboveActionLimit
    );
    assert_eq!(
        c(6401.0).compression_verdict,
        CompressionVerdict::AboveMaximumPermissibleLimit
    );
    // 3401 N of compression from a moment: 3000 N of load + 20 N·m / 0.05 m = 400 N.
    let r = low_back(&upright([0.0, 20.05, 0.0], [0.0, 0.0, -3000.0]), &p).unwrap();
    assert_abs_diff_eq!(r.compression_n, 3401.0, epsilon = 1e-9);
    assert_eq!(r.compression_verdict, CompressionVerdict::AboveActionLimit);

    let s = |fx: f64, fy: f64| low_back(&upright([0.0; 3], [fx, fy, -500.0]), &p).unwrap();
    assert_eq!(s(1000.0, 0.0).shear_verdict, ShearVerdict::WithinLimit);
    assert_eq!(s(1001.0, 0.0).shear_verdict, ShearVerdict::AboveLimit);
    // Resultant of 800 N anterior and 700 N lateral: √(800² + 700²) = 1063.01 N > 1000 N.
    let r = s(800.0, 700.0);
    assert_abs_diff_eq!(r.shear_ap_n, 800.0, epsilon = 1e-12);
    assert_abs_diff_eq!(r.shear_lateral_n, 700.0, epsilon = 1e-12);
    assert_abs_diff_eq!(r.shear_resultant_n, 1063.0146, epsilon = 1e-4);
    assert_eq!(r.shear_verdict, ShearVerdict::AboveLimit);
    // Custom limits are used as given (e.g. Gallagher & Marras' 700 N for 100–1000 loadings a
    // day).
    let strict = BackParams {
        shear_limit_n: 700.0,
        ..p
    };
    let r = low_back(&upright([0.0; 3], [750.0, 0.0, -500.0]), &strict).unwrap();
    assert_eq!(r.shear_verdict, ShearVerdict::AboveLimit);
}

/// A load behind the spine pulls the trunk backward: an extension moment (about −y), balanced by
/// the trunk flexors at their moment arm (0.08 m by default, an assumption of the module, not
/// part of Chaffin's SEM). 16 N·m / 0.08 m = 200 N; compression 200 + 400 = 600 N.
#[test]
fn extension_moment_is_balanced_by_the_flexors() {
    let r = low_back(
        &upright([0.0, -16.0, 0.0], [0.0, 0.0, -400.0]),
        &BackParams::default(),
    )
    .unwrap();
    assert_eq!(r.balancing_muscle, BalancingMuscle::Flexors);
    assert_eq!(r.extensor_force_n, 0.0);
    assert_abs_diff_eq!(r.flexor_force_n, 200.0, epsilon = 1e-9);
    assert_abs_diff_eq!(r.compression_n, 600.0, epsilon = 1e-9);
}

/// 10 kg in the right hand 0.20 m to the right of L5/S1 (y = −0.20 m), upright: M = r × F =
/// (−0.20, 0, 0) × (0, 0, −98.1) = (r_y F_z, 0, 0) = (19.62, 0, 0) N·m: a lateral-bending moment
/// (about the anterior axis) of 19.62 N·m and no sagittal moment. The sagittal SEM balances no
/// lateral moment, so no muscle force; compression = 98.1 N (the hand load alone here).
#[test]
fn lateral_and_twisting_moments_are_reported_not_balanced() {
    let r = low_back(
        &upright([19.62, 0.0, 0.0], [0.0, 0.0, -98.1]),
        &BackParams::default(),
    )
    .unwrap();
    assert_abs_diff_eq!(r.lateral_moment_nm, 19.62, epsilon = 1e-12);
    assert_abs_diff_eq!(r.sagittal_moment_nm, 0.0, epsilon = 1e-12);
    assert_eq!(r.balancing_muscle, BalancingMuscle::None);
    assert_abs_diff_eq!(r.compression_n, 98.1, epsilon = 1e-12);
    // A twisting moment (about the spine axis) is reported as well.
    let r = low_back(
        &upright([0.0, 0.0, 12.0], [0.0, 0.0, -98.1]),
        &BackParams::default(),
    )
    .unwrap();
    assert_abs_diff_eq!(r.axial_moment_nm, 12.0, epsilon = 1e-12);
    assert_abs_diff_eq!(r.compression_n, 98.1, epsilon = 1e-12);
}

/// A worker facing +y (the whole stoop turned 90° about z) gets the same compression and shear:
/// the model works in the spine's own axes.
#[test]
fn facing_direction_does_not_matter() {
    let (sn, cs) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    let a = LumbarLoad {
        moment_nm: [0.0, 90.0, 0.0],
        force_n: [0.0, 0.0, -500.0],
        spine_axis: [sn, 0.0, cs],
        forward_axis: [cs, 0.0, -sn],
    };
    let turn = |v: [f64; 3]| [-v[1], v[0], v[2]];
    let b = LumbarLoad {
        moment_nm: turn(a.moment_nm),
        force_n: turn(a.force_n),
        spine_axis: turn(a.spine_axis),
        forward_axis: turn(a.forward_axis),
    };
    let p = BackParams::default();
    let (ra, rb) = (low_back(&a, &p).unwrap(), low_back(&b, &p).unwrap());
    // By hand: 90 / 0.05 = 1800 N + 500 · cos 30° = 433.013 N → 2233.013 N; shear 500 · sin 30°
    // = 250 N anterior.
    assert_abs_diff_eq!(ra.compression_n, 2233.0127, epsilon = 1e-4);
    assert_abs_diff_eq!(ra.shear_ap_n, 250.0, epsilon = 1e-9);
    assert_abs_diff_eq!(rb.compression_n, ra.compression_n, epsilon = 1e-9);
    assert_abs_diff_eq!(rb.shear_ap_n, ra.shear_ap_n, epsilon = 1e-9);
}

/// Inputs the model cannot evaluate are refused with the field named; nothing panics.
#[test]
fn invalid_inputs_are_refused() {
    let p = BackParams::default();
    let ok = upright([0.0, 10.0, 0.0], [0.0, 0.0, -400.0]);
    let e = low_back(
        &LumbarLoad {
            moment_nm: [0.0, f64::NAN, 0.0],
            ..ok
        },
        &p,
    )
    .unwrap_err();
    assert!(matches!(e, LowBackError::NotFinite { .. }), "{e}");
    assert!(e.to_string().contains("moment_nm[1]"), "{e}");
    let e = low_back(
        &LumbarLoad {
            spine_axis: [0.0, 0.0, 2.0],
            ..ok
        },
        &p,
    )
    .unwrap_err();
    assert!(matches!(e, LowBackError::NotUnit { .. }), "{e}");
    let e = low_back(
        &LumbarLoad {
            forward_axis: [0.0, 0.0, 1.0],
            ..ok
        },
        &p,
    )
    .unwrap_err();
    assert!(matches!(e, LowBackError::NotPerpendicular { .. }), "{e}");
    for bad in [0.0, -0.05, 0.5, f64::NAN] {
        let q = BackParams {
            erector_moment_arm_m: bad,
            ..p
        };
        assert!(
            matches!(
                low_back(&ok, &q),
                Err(LowBackError::MomentArmOutOfRange { .. })
            ),
            "E = {bad}"
        );
    }
    let q = BackParams {
        compression_action_limit_n: 7000.0,
        ..p
    };
    assert!(matches!(
        low_back(&ok, &q),
        Err(LowBackError::LimitsOutOfOrder { .. })
    ));
    let q = BackParams {
        shear_limit_n: 0.0,
        ..p
    };
    assert!(matches!(
        low_back(&ok, &q),
        Err(LowBackError::LimitNotPositive { .. })
    ));
}
