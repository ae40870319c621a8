//! The revised NIOSH lifting equation (`posture_opt::assess::niosh`) against the Applications
//! Manual: Waters TR, Putz-Anderson V, Garg A (1994), *Applications Manual for the Revised NIOSH
//! Lifting Equation*, DHHS (NIOSH) Publication No. 94-110 (revised September 2021, which corrects
//! typographical errors and keeps the formulas, multipliers and limitations of 1994). "p. N" is
//! the manual's printed page.
//!
//! * Table 5 (Frequency Multiplier, p. 15) and Table 7 (Coupling Multiplier, p. 18) are typed
//!   below from the manual and checked cell by cell, in both forms of the equation.
//! * The multiplier formulas (p. 7) and their limits (pp. 8–15) are checked at hand-computed
//!   points.
//! * Worked examples: Example 5 (pp. 47–50) is reproduced in full; Example 4 (pp. 44–46) is
//!   reproduced at the origin from its published multipliers (its destination only as a
//!   consistency check, see the test); the duration rules of p. 14 and the interpolation rule of
//!   p. 7 (applied in Example 7, pp. 56–57) are checked. Examples 1–3 and 6–10 could not be
//!   reproduced: the manual's job-analysis text and worksheets for them were not available to
//!   this build.
//! * The composite lifting index (pp. 26–28) is checked on a three-task job worked by hand.
//!
//! The manual's worksheets multiply multipliers rounded to two decimals and round the RWL and LI
//! to one decimal (p. 29: "multipliers are rounded to two places to the right of the decimal and
//! weight limit … and lifting index values … are rounded to one place"); the module computes at
//! full precision, so each example is checked both ways: the worksheet arithmetic on the rounded
//! multipliers gives the published value exactly, and the full-precision value is within one
//! rounding step of it ("you might obtain slightly different values … These differences should
//! not be significant", p. 29).

use approx::assert_abs_diff_eq;
use posture_opt::assess::niosh::{
    Adjustment, Coupling, EquationForm, KG_PER_LB, LOAD_CONSTANT_KG, LOAD_CONSTANT_LB, Lift,
    LiftGeometry, M_PER_IN, NioshError, Point, PointResult, WorkDuration, assess_lift, composite,
};

/// Rounds half away from zero, as the manual's worksheets do (a small offset keeps e.g. 0.895
/// from rounding down through its binary representation).
fn round(x: f64, decimals: i32) -> f64 {
    let p = 10f64.powi(decimals);
    ((x * p) + 1e-9_f64.copysign(x)).round() / p
}

fn inch(x: f64) -> f64 {
    x * M_PER_IN
}

fn geometry(h_m: f64, v_m: f64, asymmetry_deg: f64) -> LiftGeometry {
    LiftGeometry {
        h_m,
        v_m,
        asymmetry_deg,
    }
}

/// A metric lift: H 25 cm, V 75 → 100 cm, no twist, good coupling, 0.2 lifts/min for ≤ 1 h.
/// Every multiplier is 1, so RWL = LC = 23 kg.
fn ideal() -> Lift {
    Lift {
        name: "ideal".into(),
        load_kg: 10.0,
        max_load_kg: None,
        origin: geometry(0.25, 0.75, 0.0),
        destination: geometry(0.25, 1.00, 0.0),
        freq_per_min: 0.2,
        duration: WorkDuration::UpTo1h,
        coupling: Coupling::Good,
        control_at_destination: false,
        form: EquationForm::Metric,
    }
}

/// The worksheet's RWL (p. 29): LC times the multipliers rounded to two decimals, rounded to one
/// decimal; in the form's mass unit.
fn worksheet_rwl(p: &PointResult, lc: f64) -> f64 {
    let m = &p.multipliers;
    round(
        lc * round(m.hm, 2)
            * round(m.vm, 2)
            * round(m.dm, 2)
            * round(m.am, 2)
            * round(m.fm, 2)
            * round(m.cm, 2),
        1,
    )
}

// ---------------------------------------------------------------------------------------------
// Table 5 (p. 15) and Table 7 (p. 18), cell by cell
// ---------------------------------------------------------------------------------------------

/// Table 5 rows: frequency (lifts/min; the first row is "≤ 0.2") and FM for ≤ 1 h (V < 30 in,
/// V ≥ 30 in), > 1 but ≤ 2 h (V < 30, V ≥ 30), > 2 but ≤ 8 h (V < 30, V ≥ 30). The manual's
/// footnote: values of V are in inches (75 cm in the metric form, Table 7). Last printed row:
/// "> 15": .00 everywhere.
const TABLE_5: [(f64, [f64; 6]); 17] = [
    (0.2, [1.00, 1.00, 0.95, 0.95, 0.85, 0.85]),
    (0.5, [0.97, 0.97, 0.92, 0.92, 0.81, 0.81]),
    (1.0, [0.94, 0.94, 0.88, 0.88, 0.75, 0.75]),
    (2.0, [0.91, 0.91, 0.84, 0.84, 0.65, 0.65]),
    (3.0, [0.88, 0.88, 0.79, 0.79, 0.55, 0.55]),
    (4.0, [0.84, 0.84, 0.72, 0.72, 0.45, 0.45]),
    (5.0, [0.80, 0.80, 0.60, 0.60, 0.35, 0.35]),
    (6.0, [0.75, 0.75, 0.50, 0.50, 0.27, 0.27]),
    (7.0, [0.70, 0.70, 0.42, 0.42, 0.22, 0.22]),
    (8.0, [0.60, 0.60, 0.35, 0.35, 0.18, 0.18]),
    (9.0, [0.52, 0.52, 0.30, 0.30, 0.00, 0.15]),
    (10.0, [0.45, 0.45, 0.26, 0.26, 0.00, 0.13]),
    (11.0, [0.41, 0.41, 0.00, 0.23, 0.00, 0.00]),
    (12.0, [0.37, 0.37, 0.00, 0.21, 0.00, 0.00]),
    (13.0, [0.00, 0.34, 0.00, 0.00, 0.00, 0.00]),
    (14.0, [0.00, 0.31, 0.00, 0.00, 0.00, 0.00]),
    (15.0, [0.00, 0.28, 0.00, 0.00, 0.00, 0.00]),
];

const DURATIONS: [WorkDuration; 3] = [
    WorkDuration::UpTo1h,
    WorkDuration::UpTo2h,
    WorkDuration::UpTo8h,
];

/// FM of a lift at `freq` lifts/min, `duration`, origin V below or above the threshold, in
/// `form`.
fn fm(freq: f64, duration: WorkDuration, v_low: bool, form: EquationForm) -> f64 {
    let (low, high) = match form {
        EquationForm::Metric => (0.50, 1.00),
        EquationForm::UsCustomary => (inch(20.0), inch(40.0)),
    };
    let v = if v_low { low } else { high };
    let l = Lift {
        freq_per_min: freq,
        duration,
        origin: geometry(0.25, v, 0.0),
        destination: geometry(0.25, v + 0.40, 0.0),
        form,
        ..ideal()
    };
    assess_lift(&l).unwrap().origin.multipliers.fm
}

/// Every printed cell of Table 5 (17 rows × 6 columns, plus the "> 15" row), in the metric and
/// the U.S.-customary form.
#[test]
fn table_5_every_cell() {
    for form in [EquationForm::Metric, EquationForm::UsCustomary] {
        for (f, row) in TABLE_5 {
            for (col, expected) in row.iter().enumerate() {
                let (duration, v_low) = (DURATIONS[col / 2], col % 2 == 0);
                let got = fm(f, duration, v_low, form);
                assert_abs_diff_eq!(got, *expected, epsilon = 1e-12);
            }
        }
        for col in 0..6 {
            assert_eq!(
                fm(16.0, DURATIONS[col / 2], col % 2 == 0, form),
                0.0,
                "> 15"
            );
        }
    }
}

/// "For lifting less frequently than once per 5 minutes, set F = .2 lifts/minute" (Table 5
/// footnote; p. 14).
#[test]
fn table_5_below_0_2_lifts_per_minute_uses_0_2() {
    let l = Lift {
        freq_per_min: 0.05,
        duration: WorkDuration::UpTo8h,
        ..ideal()
    };
    let r = assess_lift(&l).unwrap();
    assert_eq!(r.freq_used_per_min, 0.2);
    assert_eq!(r.origin.multipliers.fm, 0.85);
    assert!(
        r.adjustments
            .contains(&Adjustment::FrequencyRaisedToMinimum)
    );
}

/// "When the measured frequency is not a whole number, the appropriate multiplier must be
/// interpolated between the frequency values in the table for the two values that are closest
/// to the actual frequency" (p. 7); Example 7 (pp. 56–57) interpolates between 2 and 3
/// lifts/min for 2.4 lifts/min. By hand (≤ 1 h): .91 + 0.4 × (.88 − .91) = .898. Also 0.35
/// lifts/min, ≤ 8 h: .85 + 0.5 × (.81 − .85) = .83; 7.5 lifts/min, ≤ 2 h: .42 + 0.5 ×
/// (.35 − .42) = .385.
#[test]
fn table_5_interpolates_between_rows() {
    for v_low in [true, false] {
        assert_abs_diff_eq!(
            fm(2.4, WorkDuration::UpTo1h, v_low, EquationForm::UsCustomary),
            0.898,
            epsilon = 1e-12
        );
    }
    assert_abs_diff_eq!(
        fm(0.35, WorkDuration::UpTo8h, true, EquationForm::Metric),
        0.83,
        epsilon = 1e-12
    );
    assert_abs_diff_eq!(
        fm(7.5, WorkDuration::UpTo2h, false, EquationForm::Metric),
        0.385,
        epsilon = 1e-12
    );
}

/// "Lifting above the maximum frequency results in a RWL of 0.0" (p. 14): 9 lifts/min for
/// > 2 h with the hands starting below 30 in (Table 5: .00).
#[test]
fn table_5_above_the_maximum_frequency_gives_rwl_0() {
    let l = Lift {
        freq_per_min: 9.0,
        duration: WorkDuration::UpTo8h,
        origin: geometry(0.25, 0.50, 0.0),
        ..ideal()
    };
    let r = assess_lift(&l).unwrap();
    assert_eq!(r.origin.multipliers.fm, 0.0);
    assert_eq!(r.rwl_kg, 0.0);
    assert_eq!(r.lifting_index, None);
    assert!(r.adjustments.contains(&Adjustment::FrequencyBeyondMaximum));
}

/// Table 7 (p. 18): coupling multiplier for V < 30 in (75 cm) and V ≥ 30 in (75 cm):
/// Good 1.00 / 1.00, Fair 0.95 / 1.00, Poor 0.90 / 0.90. CM uses V at the end being evaluated
/// (the Example 4 worksheet, p. 46, has CM .95 at the origin at 22 in and 1.0 at the destination
/// at 59 in, both Fair).
#[test]
fn table_7_every_cell() {
    let table_7 = [
        (Coupling::Good, 1.00, 1.00),
        (Coupling::Fair, 0.95, 1.00),
        (Coupling::Poor, 0.90, 0.90),
    ];
    for form in [EquationForm::Metric, EquationForm::UsCustomary] {
        let (low, high) = match form {
            EquationForm::Metric => (0.60, 0.90),
            EquationForm::UsCustomary => (inch(22.0), inch(59.0)),
        };
        for (coupling, below, above) in table_7 {
            let l = Lift {
                coupling,
                origin: geometry(0.25, low, 0.0),
                destination: geometry(0.25, high, 0.0),
                control_at_destination: true,
                form,
                ..ideal()
            };
            let r = assess_lift(&l).unwrap();
            assert_eq!(r.origin.multipliers.cm, below, "{coupling:?} below 30 in");
            assert_eq!(
                r.destination.unwrap().multipliers.cm,
                above,
                "{coupling:?} above"
            );
        }
    }
    // The threshold itself: "V ≥ 30 in (75 cm)" is the second column.
    let at = |v: f64| {
        let l = Lift {
            coupling: Coupling::Fair,
            origin: geometry(0.25, v, 0.0),
            ..ideal()
        };
        assess_lift(&l).unwrap().origin.multipliers.cm
    };
    assert_eq!(at(0.75), 1.00);
    assert_eq!(at(0.749), 0.95);
}

// ---------------------------------------------------------------------------------------------
// Multiplier formulas (p. 7) and their limits (pp. 8–15)
// ---------------------------------------------------------------------------------------------

/// Metric formulas (p. 7), by hand: H = 40 cm → HM = 25/40 = .625; V = 30 cm → VM = 1 −
/// .003 × |30 − 75| = .865; D = 70 cm → DM = .82 + 4.5/70 = .884286; A = 30° → AM = 1 − .0032 ×
/// 30 = .904; F = 1/min, ≤ 2 h → FM = .88; Fair, V < 75 cm → CM = .95.
/// RWL = 23 × .625 × .865 × .884286 × .904 × .88 × .95 = 8.30981 kg; LI = 10 / 8.30981 = 1.2034.
#[test]
fn metric_formulas_by_hand() {
    let l = Lift {
        origin: geometry(0.40, 0.30, 30.0),
        destination: geometry(0.40, 1.00, 0.0),
        freq_per_min: 1.0,
        duration: WorkDuration::UpTo2h,
        coupling: Coupling::Fair,
        ..ideal()
    };
    let r = assess_lift(&l).unwrap();
    let m = r.origin.multipliers;
    assert_abs_diff_eq!(m.hm, 0.625, epsilon = 1e-12);
    assert_abs_diff_eq!(m.vm, 0.865, epsilon = 1e-12);
    assert_abs_diff_eq!(m.dm, 0.884_285_714, epsilon = 1e-9);
    assert_abs_diff_eq!(m.am, 0.904, epsilon = 1e-12);
    assert_abs_diff_eq!(m.fm, 0.88, epsilon = 1e-12);
    assert_abs_diff_eq!(m.cm, 0.95, epsilon = 1e-12);
    assert_abs_diff_eq!(r.rwl_kg, 8.309_81, epsilon = 1e-5);
    assert_abs_diff_eq!(r.lifting_index.unwrap(), 1.203_40, epsilon = 1e-5);
    // Frequency-independent RWL (FM = 1, p. 26): 8.30981 / .88 = 9.44297 kg.
    assert_abs_diff_eq!(r.fi_rwl_kg, 9.442_97, epsilon = 1e-5);
}

/// Under ideal conditions the RWL is the load constant: 23 kg (metric), 51 lb (customary, p. 7).
#[test]
fn ideal_lift_gives_the_load_constant() {
    let r = assess_lift(&ideal()).unwrap();
    assert_abs_diff_eq!(r.rwl_kg, LOAD_CONSTANT_KG, epsilon = 1e-12);
    assert_eq!(LOAD_CONSTANT_KG, 23.0);
    let l = Lift {
        origin: geometry(inch(10.0), inch(30.0), 0.0),
        destination: geometry(inch(10.0), inch(40.0), 0.0),
        form: EquationForm::UsCustomary,
        ..ideal()
    };
    let r = assess_lift(&l).unwrap();
    assert_abs_diff_eq!(r.rwl_kg / KG_PER_LB, LOAD_CONSTANT_LB, epsilon = 1e-9);
    assert_eq!(LOAD_CONSTANT_LB, 51.0);
}

/// Limits of the variables: H below 10 in (25 cm) is set to 10 in (HM = 1), above 25 in (63 cm)
/// HM = 0 (p. 8); V above 70 in (175 cm) VM = 0 (p. 9); D below 10 in (25 cm) is set to 10 in
/// (DM = 1) (pp. 10–11); "If A > 135°, then AM is set equal to zero, which results in a RWL of
/// zero, or no load" (p. 12).
#[test]
fn variable_limits() {
    let r = assess_lift(&Lift {
        origin: geometry(0.15, 0.75, 0.0),
        destination: geometry(0.15, 0.85, 0.0),
        ..ideal()
    })
    .unwrap();
    assert_eq!(
        (r.origin.multipliers.hm, r.origin.multipliers.dm),
        (1.0, 1.0)
    );
    assert!(
        r.adjustments
            .contains(&Adjustment::HorizontalRaisedToMinimum { at: Point::Origin })
    );
    assert!(r.adjustments.contains(&Adjustment::DistanceRaisedToMinimum));

    let r = assess_lift(&Lift {
        origin: geometry(0.65, 0.75, 0.0),
        ..ideal()
    })
    .unwrap();
    assert_eq!(r.origin.multipliers.hm, 0.0);
    assert_eq!(r.rwl_kg, 0.0);

    let r = assess_lift(&Lift {
        origin: geometry(inch(26.0), inch(30.0), 0.0),
        destination: geometry(inch(10.0), inch(40.0), 0.0),
        form: EquationForm::UsCustomary,
        ..ideal()
    })
    .unwrap();
    assert_eq!(r.origin.multipliers.hm, 0.0);

    let r = assess_lift(&Lift {
        origin: geometry(0.25, 1.80, 0.0),
        destination: geometry(0.25, 1.70, 0.0),
        ..ideal()
    })
    .unwrap();
    assert_eq!(r.origin.multipliers.vm, 0.0);

    let r = assess_lift(&Lift {
        origin: geometry(0.25, 0.75, 140.0),
        ..ideal()
    })
    .unwrap();
    assert_eq!(r.origin.multipliers.am, 0.0);
    assert_eq!(r.rwl_kg, 0.0);
    // A = 135° is still inside: AM = 1 − .0032 × 135 = .568.
    let r = assess_lift(&Lift {
        origin: geometry(0.25, 0.75, 135.0),
        ..ideal()
    })
    .unwrap();
    assert_abs_diff_eq!(r.origin.multipliers.am, 0.568, epsilon = 1e-12);
}

/// Lowering is assessed like lifting, with D = |V_destination − V_origin| (p. 10).
#[test]
fn lowering_uses_the_same_distance() {
    let up = Lift {
        origin: geometry(0.25, 0.20, 0.0),
        destination: geometry(0.25, 1.20, 0.0),
        ..ideal()
    };
    let down = Lift {
        origin: up.destination,
        destination: up.origin,
        ..up.clone()
    };
    let (a, b) = (assess_lift(&up).unwrap(), assess_lift(&down).unwrap());
    // D = 100 cm: DM = .82 + 4.5/100 = .865.
    assert_abs_diff_eq!(a.origin.multipliers.dm, 0.865, epsilon = 1e-12);
    assert_eq!(a.origin.multipliers.dm, b.origin.multipliers.dm);
}

// ---------------------------------------------------------------------------------------------
// Duration categories (pp. 13–14)
// ---------------------------------------------------------------------------------------------

/// p. 14: "30 minutes of lifting, 10 minutes of light work, then 45 minutes of lifting" does not
/// meet the short category's 1.0 recovery ratio, so the sessions add up to 75 minutes: moderate
/// duration (> 1 h, ≤ 2 h). With a 30-minute recovery instead, each session is short (≤ 1 h).
/// Long is > 2 h and ≤ 8 h; "No weight limits are provided for more than eight hours of work".
#[test]
fn duration_categories() {
    assert_eq!(
        WorkDuration::from_hours((30.0 + 45.0) / 60.0),
        Ok(WorkDuration::UpTo2h)
    );
    assert_eq!(
        WorkDuration::from_hours(45.0 / 60.0),
        Ok(WorkDuration::UpTo1h)
    );
    assert_eq!(WorkDuration::from_hours(1.0), Ok(WorkDuration::UpTo1h));
    assert_eq!(WorkDuration::from_hours(2.0), Ok(WorkDuration::UpTo2h));
    assert_eq!(WorkDuration::from_hours(2.5), Ok(WorkDuration::UpTo8h));
    assert_eq!(WorkDuration::from_hours(8.0), Ok(WorkDuration::UpTo8h));
    assert_eq!(
        WorkDuration::from_hours(8.5),
        Err(NioshError::DurationOutOfRange(8.5))
    );
    assert!(WorkDuration::from_hours(0.0).is_err());
}

// ---------------------------------------------------------------------------------------------
// Worked examples of the Applications Manual
// ---------------------------------------------------------------------------------------------

/// Example 5, "Dish-Washing Machine Unloading" (pp. 47–50, worksheet Figure 16).
///
/// Published job description and analysis: trays lifted from a conveyor at the end of a
/// dishwashing machine onto a cart, 45 min to 1 h, 5 lifts/min. Origin H = 20 in, V = 44 in,
/// A = 30°; destination H = 20 in, V = 7 in, A = 30°; trays 20 lb; coupling Good; significant
/// control at the destination; FM = .80 (Table 5). Published: "the RWL is 14.4 lbs at the
/// origin and 13.3 lbs at the destination"; "The LI at the origin is 20/14.4 or 1.4 and the LI
/// at the destination is 1.5"; "the smallest multipliers … are .50 for the HM, .80 for the FM,
/// .83 for the VM, and .90 for the AM".
///
/// Worksheet arithmetic by hand: HM = 10/20 = .50; VM origin = 1 − .0075 × 14 = .895 → .90,
/// destination 1 − .0075 × 23 = .8275 → .83; D = 37 in → DM = .82 + 1.8/37 = .8686 → .87;
/// AM = 1 − .0032 × 30 = .904 → .90; CM 1.00. Origin 51 × .50 × .90 × .87 × .90 × .80 × 1.00 =
/// 14.376 → 14.4 lb; destination 51 × .50 × .83 × .87 × .90 × .80 = 13.258 → 13.3 lb.
/// Full precision: 14.337 lb and 13.256 lb; LI 1.395 and 1.509.
#[test]
fn example_5_dish_washing_machine_unloading() {
    let l = Lift {
        name: "Example 5".into(),
        load_kg: 20.0 * KG_PER_LB,
        max_load_kg: None,
        origin: geometry(inch(20.0), inch(44.0), 30.0),
        destination: geometry(inch(20.0), inch(7.0), 30.0),
        freq_per_min: 5.0,
        duration: WorkDuration::UpTo1h,
        coupling: Coupling::Good,
        control_at_destination: true,
        form: EquationForm::UsCustomary,
    };
    let r = assess_lift(&l).unwrap();
    let (o, d) = (r.origin, r.destination.unwrap());
    let mo = o.multipliers;
    assert_eq!(
        [mo.hm, mo.vm, mo.dm, mo.am, mo.fm, mo.cm].map(|x| round(x, 2)),
        [0.50, 0.90, 0.87, 0.90, 0.80, 1.00]
    );
    assert_eq!(round(d.multipliers.vm, 2), 0.83);
    assert_eq!(worksheet_rwl(&o, LOAD_CONSTANT_LB), 14.4);
    assert_eq!(worksheet_rwl(&d, LOAD_CONSTANT_LB), 13.3);
    assert_abs_diff_eq!(o.rwl_kg / KG_PER_LB, 14.337_25, epsilon = 1e-4);
    assert_abs_diff_eq!(d.rwl_kg / KG_PER_LB, 13.255_95, epsilon = 1e-4);
    assert_eq!(round(o.lifting_index.unwrap(), 1), 1.4);
    assert_eq!(round(d.lifting_index.unwrap(), 1), 1.5);
    // The lower RWL governs the task (p. 26).
    assert_eq!(r.governing, Point::Destination);
    assert_eq!(r.rwl_kg, d.rwl_kg);
    assert_eq!(round(r.lifting_index.unwrap(), 1), 1.5);
}

/// Example 4, "Package Inspection" (pp. 44–46, worksheet Figure 14), at the origin.
///
/// Published: packages of 26 lb; origin V = 22 in with H ≤ 10 in (HM 1.0) and no twist (AM
/// 1.0); destination V = 59 in, so D = 37 in; coupling Fair (CM .95 at the origin, V < 30 in;
/// 1.0 at the destination); FM .88; origin worksheet RWL 51 × 1.0 × .94 × .87 × 1.0 × .88 × .95
/// = 34.868 → 34.9 lb.
///
/// The frequency and duration behind FM = .88 are not in the transcription available here;
/// 3 lifts/min for ≤ 1 h is one Table 5 cell that gives .88 (1 lift/min for 1–2 h is another),
/// and the origin result depends on them only through FM.
///
/// Consistency check, not a reproduction: the published destination RWL, 15.2 lb, follows
/// from the worksheet arithmetic with HM .50 (H = 20 in) and AM 1.0 (A = 0°): 51 × .50 × .78 ×
/// .87 × 1.0 × .88 × 1.0 = 15.228 → 15.2 lb (VM = 1 − .0075 × 29 = .7825 → .78); those two
/// destination values are inferred, not read from the manual.
#[test]
fn example_4_package_inspection() {
    let l = Lift {
        name: "Example 4".into(),
        load_kg: 26.0 * KG_PER_LB,
        max_load_kg: None,
        origin: geometry(inch(10.0), inch(22.0), 0.0),
        destination: geometry(inch(20.0), inch(59.0), 0.0),
        freq_per_min: 3.0,
        duration: WorkDuration::UpTo1h,
        coupling: Coupling::Fair,
        control_at_destination: true,
        form: EquationForm::UsCustomary,
    };
    let r = assess_lift(&l).unwrap();
    let o = r.origin;
    let m = o.multipliers;
    assert_eq!(
        [m.hm, m.vm, m.dm, m.am, m.fm, m.cm].map(|x| round(x, 2)),
        [1.0, 0.94, 0.87, 1.0, 0.88, 0.95]
    );
    assert_eq!(worksheet_rwl(&o, LOAD_CONSTANT_LB), 34.9);
    // Full precision: 51 × .94 × .868649 × .88 × .95 = 34.81 lb.
    assert_abs_diff_eq!(o.rwl_kg / KG_PER_LB, 34.81, epsilon = 0.01);
    let d = r.destination.unwrap();
    assert_eq!(round(d.multipliers.cm, 2), 1.0);
    assert_eq!(worksheet_rwl(&d, LOAD_CONSTANT_LB), 15.2);
}

// ---------------------------------------------------------------------------------------------
// Multi-task procedure (pp. 26–28)
// ---------------------------------------------------------------------------------------------

/// Three tasks, ≤ 1 h, metric, worked by hand with the multi-task procedure (pp. 26–28):
/// * T1: 12 kg, H 40 cm (HM .625), V 75 → 125 cm (VM 1, D 50: DM .82 + 4.5/50 = .91), Good,
///   1 lift/min: FIRWL = 23 × .625 × .91 = 13.08125 kg; FM(1) = .94; STRWL = 12.296375;
///   STLI = 12 / 12.296375 = .975897; FILI = 12 / 13.08125 = .917344.
/// * T2: 8 kg, H 25, V 50 → 100 cm (VM .925, DM .91), A 30° (AM .904), Fair at 50 cm (CM .95),
///   2 lifts/min: FIRWL = 23 × .925 × .91 × .904 × .95 = 16.626583; FM(2) = .91;
///   STLI = 8 / 15.130190 = .528744; FILI = 8 / 16.626583 = .481157.
/// * T3: 5 kg, H 50 (HM .5), V 30 → 90 cm (VM .865, D 60: DM .895), Poor (CM .90), 3 lifts/min:
///   FIRWL = 23 × .5 × .865 × .895 × .90 = 8.012711; FM(3) = .88; STLI = 5 / 7.051186 = .709101;
///   FILI = 5 / 8.012711 = .624009.
///
/// Renumbered by decreasing STLI (p. 27): T1, T3, T2. CLI = STLI₁ + FILI₂ (1/FM₁,₂ − 1/FM₁) +
/// FILI₃ (1/FM₁,₂,₃ − 1/FM₁,₂), with FM from Table 5 at the summed frequencies (p. 28): FM₁ =
/// FM(1) = .94, FM₁,₂ = FM(1 + 3 = 4) = .84, FM₁,₂,₃ = FM(4 + 2 = 6) = .75 (the two V columns
/// agree for ≤ 1 h at these rows). CLI = .975897 + .624009 × (1/.84 − 1/.94) + .481157 ×
/// (1/.75 − 1/.84) = .975897 + .079028 + .068737 = 1.123663.
#[test]
fn composite_lifting_index_three_tasks_by_hand() {
    let t1 = Lift {
        name: "T1".into(),
        load_kg: 12.0,
        origin: geometry(0.40, 0.75, 0.0),
        destination: geometry(0.40, 1.25, 0.0),
        freq_per_min: 1.0,
        ..ideal()
    };
    let t2 = Lift {
        name: "T2".into(),
        load_kg: 8.0,
        origin: geometry(0.25, 0.50, 30.0),
        destination: geometry(0.25, 1.00, 0.0),
        coupling: Coupling::Fair,
        freq_per_min: 2.0,
        ..ideal()
    };
    let t3 = Lift {
        name: "T3".into(),
        load_kg: 5.0,
        origin: geometry(0.50, 0.30, 0.0),
        destination: geometry(0.50, 0.90, 0.0),
        coupling: Coupling::Poor,
        freq_per_min: 3.0,
        ..ideal()
    };
    let r = composite(&[t1, t2, t3]).unwrap();
    assert_abs_diff_eq!(r.lifts[0].fi_rwl_kg, 13.08125, epsilon = 1e-9);
    assert_abs_diff_eq!(r.lifts[0].st_li.unwrap(), 0.975_897, epsilon = 1e-6);
    assert_abs_diff_eq!(r.lifts[1].fi_rwl_kg, 16.626_583, epsilon = 1e-6);
    assert_abs_diff_eq!(r.lifts[1].fi_li.unwrap(), 0.481_157, epsilon = 1e-6);
    assert_abs_diff_eq!(r.lifts[2].fi_rwl_kg, 8.012_711, epsilon = 1e-6);
    assert_abs_diff_eq!(r.lifts[2].st_li.unwrap(), 0.709_101, epsilon = 1e-6);
    assert_eq!(r.order, vec![0, 2, 1]);
    let cum: Vec<f64> = r.terms.iter().map(|t| t.cumulative_freq_per_min).collect();
    assert_eq!(cum, vec![1.0, 4.0, 6.0]);
    let fms: Vec<f64> = r.terms.iter().map(|t| t.fm_cumulative).collect();
    assert_eq!(fms, vec![0.94, 0.84, 0.75]);
    assert_abs_diff_eq!(r.terms[1].contribution.unwrap(), 0.079_028, epsilon = 1e-6);
    assert_abs_diff_eq!(r.terms[2].contribution.unwrap(), 0.068_737, epsilon = 1e-6);
    assert_abs_diff_eq!(r.cli.unwrap(), 1.123_663, epsilon = 1e-6);
}

/// A job of one task: the CLI is that task's STLI (p. 28, the sum has no ΔLI terms).
#[test]
fn composite_of_one_task_is_its_stli() {
    let l = Lift {
        freq_per_min: 4.0,
        ..ideal()
    };
    let single = assess_lift(&l).unwrap();
    // By hand: FIRWL 23, FM(4) = .84: STLI = 10 / 19.32 = .517598.
    assert_abs_diff_eq!(single.st_li.unwrap(), 10.0 / 19.32, epsilon = 1e-12);
    let r = composite(std::slice::from_ref(&l)).unwrap();
    assert_eq!(r.cli, single.st_li);
}

/// "If more than one task has the same STLI value, assign the lower task number to the task
/// with the highest frequency" (p. 57). 0.1 and 0.2 lifts/min both use F = .2, so the STLIs are
/// equal.
#[test]
fn composite_ties_put_the_higher_frequency_first() {
    let slow = Lift {
        name: "slow".into(),
        freq_per_min: 0.1,
        ..ideal()
    };
    let fast = Lift {
        name: "fast".into(),
        freq_per_min: 0.2,
        ..ideal()
    };
    let r = composite(&[slow, fast]).unwrap();
    assert_eq!(r.order, vec![1, 0]);
}

/// Inputs without a meaning are refused with the field named (and nothing panics).
#[test]
fn invalid_inputs_are_refused() {
    let e = assess_lift(&Lift {
        load_kg: -1.0,
        ..ideal()
    })
    .unwrap_err();
    assert!(
        e.to_string().starts_with("load_kg must be at least 0"),
        "{e}"
    );
    let e = assess_lift(&Lift {
        origin: geometry(f64::NAN, 0.75, 0.0),
        ..ideal()
    })
    .unwrap_err();
    assert!(e.to_string().contains("origin.h_m"), "{e}");
    assert!(matches!(
        assess_lift(&Lift {
            origin: geometry(0.25, 0.75, 200.0),
            ..ideal()
        }),
        Err(NioshError::AsymmetryOutOfRange { .. })
    ));
    assert_eq!(composite(&[]), Err(NioshError::NoLifts));
}

// ---------------------------------------------------------------------------------------------
// A task's declared lift, measured on its planned postures (`assess::lifting`)
// ---------------------------------------------------------------------------------------------

/// A two-handed box lift from a cart to a shelf, planned, then put through the equation. The
/// task variables are measured by hand on the planned postures with the manual's definitions:
/// H is the horizontal distance from the mid-point between the ankles to the point on the floor
/// below the mid-point of the hands (p. 7), V the height of that mid-point (p. 9), D the
/// difference of V (p. 10), A the angle between the line to the point below the hands and the
/// mid-sagittal line of the neutral posture (the feet's forward direction, +x) (p. 12); F one
/// lift per cycle (lifts/min averaged over the work, p. 13), the duration category from the
/// task's length (pp. 13–14), the load the box (4 kg). Hand positions come from the worker's
/// forward kinematics at the planned joint angles.
#[test]
fn task_lift_is_measured_on_the_planned_postures() {
    use posture_opt::assess::lifting::assess_lifts;
    use posture_opt::body::{StaticsData, forward_kinematics};
    use posture_opt::plan::{Task, plan_task};

    let yaml = r#"name: box to shelf
worker: {sex: female, stature_m: 1.62, mass_kg: 62.0, strength_percentile: 50}
workstation:
  obstacles:
    - {name: shelf, box: {size_m: [0.40, 1.20, 0.02]}, position_m: [0.75, -0.10, 1.09]}
    - {name: cart, box: {size_m: [0.50, 0.40, 0.80]}, position_m: [0.40, -0.65, 0.40]}
    - {name: floor, plane: {normal: [0, 0, 1]}, position_m: [0, 0, 0]}
phases:
  - {name: lift, object: {center_m: [0.38, -0.45, 0.95], grip_width_m: 0.30, size_m: [0.25, 0.30, 0.20]}, load_kg: 4.0, duration_s: 2.0}
  - {name: place, object: {center_m: [0.52, -0.15, 1.22], grip_width_m: 0.30, size_m: [0.25, 0.30, 0.20]}, load_kg: 4.0, duration_s: 3.0}
lifts:
  - {name: box to shelf, origin: lift, destination: place, coupling: good}
rest_s: 7.0
cycles: 10
"#;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("lift.yaml");
    std::fs::write(&path, yaml).unwrap();
    let task = Task::from_file(&path).unwrap();
    let plan = plan_task(&task).unwrap();
    let lifting = assess_lifts(&task, &plan)
        .expect("the task declares a lift")
        .unwrap();
    assert_eq!(lifting.lifts.len(), 1);
    assert!(lifting.composite.is_none());
    let r = &lifting.lifts[0];

    // Hand mid-point of a phase, from forward kinematics of its planned posture.
    let mut data = StaticsData::new(&task.model, 2);
    let mut hands_mid = |p: usize| {
        forward_kinematics(&task.model, &mut data, &plan.summary.phases[p].q_rad);
        let pts: Vec<nalgebra::Vector3<f64>> = task.phases[p]
            .hands()
            .map(|h| {
                let (link, _) = task.hand_links[h].clone().unwrap();
                data.link_point(&task.model, link, &nalgebra::Vector3::zeros())
            })
            .collect();
        assert_eq!(pts.len(), 2, "a two-handed lift");
        (pts[0] + pts[1]) / 2.0
    };
    let (o, d) = (hands_mid(0), hands_mid(1));
    let st = task.stance.as_ref().unwrap();
    let ankles =
        (st.world_from_foot[0].translation.vector + st.world_from_foot[1].translation.vector) / 2.0;
    let h = |m: nalgebra::Vector3<f64>| (m.x - ankles.x).hypot(m.y - ankles.y);
    let a = |m: nalgebra::Vector3<f64>| (m.y - ankles.y).atan2(m.x - ankles.x).to_degrees().abs();

    let mo = r.origin.multipliers;
    assert_abs_diff_eq!(mo.h_cm, 100.0 * h(o), epsilon = 1e-6);
    assert_abs_diff_eq!(mo.v_cm, 100.0 * o.z, epsilon = 1e-6);
    assert_abs_diff_eq!(mo.asymmetry_deg, a(o), epsilon = 1e-6);
    assert_abs_diff_eq!(mo.d_cm, 100.0 * (d.z - o.z).abs(), epsilon = 1e-6);
    // One lift per 12 s cycle: 5 lifts/min; 10 cycles = 2 min of work: ≤ 1 h.
    assert_abs_diff_eq!(r.freq_per_min, 5.0, epsilon = 1e-12);
    assert_eq!(r.duration, WorkDuration::UpTo1h);
    assert_abs_diff_eq!(r.load_kg, 4.0, epsilon = 1e-9);
    assert_eq!(r.coupling, Coupling::Good);
    assert!(!r.control_at_destination && r.destination.is_none());
    // The metric equation with those variables, by the formulas of p. 7 and Table 5.
    let hm = 25.0 / (100.0 * h(o)).max(25.0);
    let vm = 1.0 - 0.003 * (100.0 * o.z - 75.0).abs();
    let dm = 0.82 + 4.5 / (100.0 * (d.z - o.z).abs()).max(25.0);
    let am = 1.0 - 0.0032 * a(o);
    let fm = 0.80; // Table 5, ≤ 1 h, 5 lifts/min: .80 in both V columns
    let rwl = 23.0 * hm * vm * dm * am * fm * 1.0;
    assert!(100.0 * h(o) <= 63.0 && o.z <= 1.75);
    assert_abs_diff_eq!(r.rwl_kg, rwl, epsilon = 1e-9);
    assert_abs_diff_eq!(r.lifting_index.unwrap(), 4.0 / rwl, epsilon = 1e-9);
}

/// "No weight limits are provided for more than eight hours of work" (p. 14): a task whose
/// lifting lasts 10 h has no NIOSH result; the assessment must say so rather than use the
/// "> 2 but ≤ 8 hours" column.
#[test]
fn task_longer_than_8_hours_has_no_weight_limit() {
    use posture_opt::assess::lifting::assess_lifts;
    use posture_opt::plan::{Task, plan_task_with};

    // 3000 cycles of 12 s: 10 h.
    let yaml = r#"name: ten hours of lifting
worker: {sex: female, stature_m: 1.62, mass_kg: 62.0, strength_percentile: 50}
workstation:
  obstacles:
    - {name: floor, plane: {normal: [0, 0, 1]}, position_m: [0, 0, 0]}
phases:
  - {name: lift, object: {center_m: [0.38, -0.20, 0.95], grip_width_m: 0.30, size_m: [0.25, 0.30, 0.20]}, load_kg: 4.0, duration_s: 2.0}
  - {name: place, object: {center_m: [0.45, -0.10, 1.15], grip_width_m: 0.30, size_m: [0.25, 0.30, 0.20]}, load_kg: 4.0, duration_s: 3.0}
lifts:
  - {name: box up, origin: lift, destination: place}
rest_s: 7.0
cycles: 3000
"#;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ten_hours.yaml");
    std::fs::write(&path, yaml).unwrap();
    let task = Task::from_file(&path).unwrap();
    assert!((task.duration_s() - 36_000.0).abs() < 1e-6);
    let plan = plan_task_with(&task, crate::common::held(true)).unwrap();
    let r = assess_lifts(&task, &plan).expect("the task declares a lift");
    assert!(
        matches!(r, Err(NioshError::DurationOutOfRange(_))),
        "got {:?}",
        r.map(|l| l.lifts[0].duration)
    );
}

/// The report's words for a lift whose destination lies beyond NIOSH's 63 cm of horizontal
/// reach (HM = 0, RWL = 0): the lifting index is "not defined" with the reason and the value
/// (not a bare "-"), and with control at the destination both ends are given, the governing one
/// named — the manual asks for both ends' multipliers (Waters et al. 1994, p. 11).
#[test]
fn a_lift_beyond_the_equations_range_says_why() {
    let mut l = ideal();
    l.origin = geometry(0.57, 0.88, 0.0);
    l.destination = geometry(0.665, 1.525, 0.0);
    l.control_at_destination = true;
    let r = assess_lift(&l).unwrap();
    assert_eq!(r.rwl_kg, 0.0);
    assert_eq!(r.governing, Point::Destination);
    let lines = posture_opt::report::text::lift_lines(&r);
    assert!(
        lines[0].contains("lifting index not defined: H 66.5 cm beyond 63 cm (HM = 0)"),
        "{lines:?}"
    );
    assert_eq!(lines.len(), 3, "{lines:?}");
    let origin_li = r.origin.lifting_index.unwrap();
    assert!(
        lines[1].contains("at the origin")
            && lines[1].contains(&format!("lifting index {origin_li:.2}")),
        "{lines:?}"
    );
    assert!(
        lines[2].contains("at the destination")
            && lines[2].contains("governs")
            && lines[2].contains("not defined"),
        "{lines:?}"
    );
    // the index that decides the task is not defined, with the reason, and ranks as the worst
    // class of risk
    use posture_opt::assess::lifting::{Lifting, risk_key};
    let deciding = Lifting {
        lifts: vec![r.clone()],
        composite: None,
    }
    .deciding_index();
    assert_eq!(
        deciding,
        Err("'ideal' at the destination: H 66.5 cm beyond 63 cm (HM = 0)".into())
    );
    assert!(risk_key(Some(&deciding)) > risk_key(Some(&Ok(5.0))));
    assert!(risk_key(Some(&Ok(5.0))) > risk_key(Some(&Ok(1.5))));
    assert!(risk_key(Some(&Ok(1.5))) > risk_key(Some(&Ok(0.9))));
    assert_eq!(risk_key(Some(&Ok(0.9))), risk_key(None));
    // the same lift without control at the destination: only the origin is assessed, and the
    // destination's H beyond 63 cm is said (an ergonomist's trial found it silent)
    l.control_at_destination = false;
    let r = assess_lift(&l).unwrap();
    assert_eq!(r.governing, Point::Origin);
    assert!(r.destination.is_none());
    assert_abs_diff_eq!(
        r.uncontrolled_destination_h_cm.unwrap(),
        66.5,
        epsilon = 1e-9
    );
    let lines = posture_opt::report::text::lift_lines(&r);
    assert_eq!(lines.len(), 2, "{lines:?}");
    assert!(
        lines[1].contains("its H is 66.5 cm, beyond 63 cm")
            && lines[1].contains("control_at_destination"),
        "{lines:?}"
    );
    // within range: a number, and one line without control at the destination
    let lines = posture_opt::report::text::lift_lines(&assess_lift(&ideal()).unwrap());
    assert_eq!(
        lines,
        ["NIOSH lift 'ideal': RWL 23.0 kg, lifting index 0.43"]
    );
}
