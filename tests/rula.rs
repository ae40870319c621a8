//! RULA: scores worked out by hand from McAtamney & Corlett's (1993) tables, and the posture
//! geometry measured on the default worker at postures whose angles are known.

use posture_opt::body::{BodyModel, StaticsData};
use posture_opt::rula::{score, RulaActivity, RulaPosture};

fn neutral() -> RulaPosture {
    RulaPosture {
        upper_arm_flexion_deg: 0.0,
        upper_arm_abduction_deg: 0.0,
        elbow_flexion_deg: 80.0,
        hand_across_midline: false,
        hand_out_to_side: false,
        wrist_flexion_deg: 0.0,
        wrist_deviation_deg: 0.0,
        wrist_twist_fraction: 0.0,
        trunk_flexion_deg: 0.0,
        trunk_twist_deg: 0.0,
        trunk_side_bend_deg: 0.0,
    }
}

const LIGHT: RulaActivity = RulaActivity {
    load_kg: 0.5,
    held_s: 3.0,
    repeats_per_min: 1.0,
};

#[test]
fn neutral_posture_light_load_scores_one() {
    // Upper arm 1, lower arm 1, wrist 1, twist 1 -> A = 1; C = 1.
    // Neck 1, trunk 1, legs 1 -> B = 1; D = 1. Table C[1][1] = 1.
    let r = score(&neutral(), &LIGHT);
    assert_eq!(
        (r.upper_arm, r.lower_arm, r.wrist, r.wrist_twist),
        (1, 1, 1, 1)
    );
    assert_eq!(
        (r.posture_a, r.score_c, r.posture_b, r.score_d),
        (1, 1, 1, 1)
    );
    assert_eq!((r.grand_score, r.action_level), (1, 1));
}

#[test]
fn worked_example_by_hand() {
    // Upper arm 50 deg flexion -> 3; elbow 80 deg, in front -> 1; wrist 10 deg -> 2, not
    // deviated; twist mid-range -> 1. Table A row (3, 1) = [3,3,4,4,4,4,5,5], column
    // (wrist 2, twist 1) = 3rd -> A = 4. Held 3 s, 3 times a minute: muscle use 0. 4 kg
    // intermittent: force 1. C = 5.
    // Trunk 15 deg flexion -> 2, no twist or bend; neck 1, legs 1: Table B row 1 =
    // [1,3,2,3,...], column (trunk 2, legs 1) = 3rd -> B = 2; D = 2 + 0 + 1 = 3.
    // Table C row 5 = [4,4,4,5,6,7,7], column 3 -> 4: action level 2.
    let p = RulaPosture {
        upper_arm_flexion_deg: 50.0,
        wrist_flexion_deg: 10.0,
        trunk_flexion_deg: 15.0,
        ..neutral()
    };
    let a = RulaActivity {
        load_kg: 4.0,
        held_s: 3.0,
        repeats_per_min: 3.0,
    };
    let r = score(&p, &a);
    assert_eq!(
        (r.upper_arm, r.lower_arm, r.wrist, r.wrist_twist),
        (3, 1, 2, 1)
    );
    assert_eq!(r.posture_a, 4);
    assert_eq!(r.score_c, 5);
    assert_eq!((r.trunk, r.posture_b, r.score_d), (2, 2, 3));
    assert_eq!((r.grand_score, r.action_level), (4, 2));
    // Every worksheet step is there, in order, and step 15 carries the grand score.
    let steps: Vec<&str> = r.worksheet.iter().map(|w| w.step).collect();
    assert_eq!(
        steps,
        [
            "1", "1a", "2", "2a", "3", "3a", "4", "5", "6", "7", "8", "9", "10", "10a", "10b",
            "11", "12", "13", "14", "14b", "15"
        ]
    );
    assert_eq!(r.worksheet.last().unwrap().score, 4);
    assert_eq!(r.worksheet[0].measured, Some(50.0));
}

#[test]
fn worst_case_by_hand() {
    // Upper arm 100 deg and abducted -> 4 + 1 = 5; elbow 120 deg across the midline -> 3;
    // wrist 30 deg and deviated -> 4; twist at the end of range -> 2: Table A row (5, 3) =
    // [6,6,6,7,7,7,7,8], last column -> 8. Repeated 6/min: +1; 12 kg repeated: +3. C = 12.
    // Trunk 70 deg, twisted and side-bent -> 6; Table B row 1 column (6, 1) = 7; D = 11.
    // Table C clamps C to 8 and D to 7: 7, action level 4.
    let p = RulaPosture {
        upper_arm_flexion_deg: 100.0,
        upper_arm_abduction_deg: 40.0,
        elbow_flexion_deg: 120.0,
        hand_across_midline: true,
        hand_out_to_side: false,
        wrist_flexion_deg: -30.0,
        wrist_deviation_deg: 20.0,
        wrist_twist_fraction: 0.9,
        trunk_flexion_deg: 70.0,
        trunk_twist_deg: -20.0,
        trunk_side_bend_deg: 15.0,
    };
    let a = RulaActivity {
        load_kg: 12.0,
        held_s: 2.0,
        repeats_per_min: 6.0,
    };
    let r = score(&p, &a);
    assert_eq!(
        (r.upper_arm, r.lower_arm, r.wrist, r.wrist_twist),
        (5, 3, 4, 2)
    );
    assert_eq!((r.posture_a, r.score_c), (8, 12));
    assert_eq!((r.trunk, r.posture_b, r.score_d), (6, 7, 11));
    assert_eq!((r.grand_score, r.action_level), (7, 4));
}

#[test]
fn static_hold_and_extension_rules() {
    // Upper arm 30 deg extension -> 2; a 90 s hold counts as static: muscle use +1, and 3 kg
    // static -> force 2.
    let p = RulaPosture {
        upper_arm_flexion_deg: -30.0,
        ..neutral()
    };
    let a = RulaActivity {
        load_kg: 3.0,
        held_s: 90.0,
        repeats_per_min: 0.5,
    };
    let r = score(&p, &a);
    assert_eq!(r.upper_arm, 2);
    // Table A row (2, 1) first column: 2. C = 2 + 1 + 2 = 5.
    assert_eq!((r.posture_a, r.score_c), (2, 5));
    // B = 1, D = 1 + 1 + 2 = 4; Table C row 5 column 4 = 5.
    assert_eq!((r.score_d, r.grand_score), (4, 5));
}

fn worker() -> BodyModel {
    BodyModel::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf")).unwrap()
}

fn posture(model: &BodyModel, set: &[(&str, f64)]) -> RulaPosture {
    let mut q = vec![0.0; model.nq()];
    for (name, deg) in set {
        q[model.q_index(name).unwrap()] = deg.to_radians();
    }
    let mut data = StaticsData::new(model);
    RulaPosture::from_worker(model, &mut data, &q).unwrap()
}

#[test]
fn geometry_of_known_postures() {
    let m = worker();
    // Standing, arm hanging: upper arm 0, elbow straight, trunk upright.
    let p = posture(&m, &[]);
    assert!(p.upper_arm_flexion_deg.abs() < 1e-9);
    assert!(p.elbow_flexion_deg.abs() < 1e-9);
    assert!(p.trunk_flexion_deg.abs() < 1e-9);
    assert!(!p.hand_across_midline && !p.hand_out_to_side);

    // Shoulder flexed 90 deg, elbow 90 deg, trunk 30 deg forward: the angles come back from
    // the geometry (the upper arm is measured against the trunk, not the vertical).
    let p = posture(
        &m,
        &[
            ("r_shoulder_flexion", 90.0),
            ("r_elbow_flexion", 90.0),
            ("lumbar_flexion", 30.0),
        ],
    );
    assert!((p.upper_arm_flexion_deg - 90.0).abs() < 1e-6, "{p:?}");
    assert!((p.elbow_flexion_deg - 90.0).abs() < 1e-6, "{p:?}");
    assert!((p.trunk_flexion_deg - 30.0).abs() < 1e-6, "{p:?}");
    assert!(p.upper_arm_abduction_deg.abs() < 1e-6);

    // Arm raised 40 deg sideways: 40 deg elevation, 40 deg out of the sagittal plane.
    let p = posture(&m, &[("r_shoulder_abduction", 40.0)]);
    assert!((p.upper_arm_flexion_deg - 40.0).abs() < 1e-6, "{p:?}");
    assert!((p.upper_arm_abduction_deg - 40.0).abs() < 1e-6, "{p:?}");

    // Arm back 30 deg: extension.
    let p = posture(&m, &[("r_shoulder_flexion", -30.0)]);
    assert!((p.upper_arm_flexion_deg + 30.0).abs() < 1e-6, "{p:?}");

    // Side bend 15 deg to the left shows as trunk side bend of 15 deg.
    let p = posture(&m, &[("lumbar_lateral_bending", 15.0)]);
    assert!((p.trunk_side_bend_deg.abs() - 15.0).abs() < 1e-6, "{p:?}");

    // Forearm pronated to its limit (1.4 rad): end of the twisting range.
    let p = posture(&m, &[("r_forearm_pronation", 1.4_f64.to_degrees())]);
    assert!((p.wrist_twist_fraction - 1.0).abs() < 1e-9);
}

#[test]
fn other_bodies_are_refused_by_name() {
    let m = BodyModel::from_urdf_file(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/two_link.urdf"
    ))
    .unwrap();
    let mut data = StaticsData::new(&m);
    let q = vec![0.0; m.nq()];
    let e = RulaPosture::from_worker(&m, &mut data, &q).unwrap_err();
    assert!(e.to_string().contains("pelvis"), "{e}");
}
