//! The generated worker (de Leva 1996) and half-joint strength scaling, worked by hand.

use nalgebra::Vector3;
use posture_opt::body::strength::normal_quantile;
use posture_opt::body::{
    holding_torques, resolve_half_joints, worker_urdf, BodyModel, Direction, Sex, StaticsData,
    StrengthTable, Worker, GRAVITY_M_S2,
};

fn worker(sex: Sex, h: f64, m: f64, p: f64) -> Worker {
    Worker {
        sex,
        stature_m: h,
        mass_kg: m,
        strength_percentile: p,
    }
}

#[test]
fn shipped_default_is_the_generated_50th_percentile_man() {
    let generated = worker_urdf(&Worker::MALE_50, &StrengthTable::default_table()).unwrap();
    let shipped =
        std::fs::read_to_string(format!("{}/robots/worker.urdf", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
    assert_eq!(generated, shipped, "robots/worker.urdf must be `posture-opt robot --sex male --stature-m 1.755 --mass-kg 78` output");
}

#[test]
fn masses_follow_de_leva() {
    let w = worker(Sex::Female, 1.62, 60.0, 50.0);
    let m = BodyModel::from_urdf_str(
        &worker_urdf(&w, &StrengthTable::default_table()).unwrap(),
        "gen",
    )
    .unwrap();
    let mass = |l: &str| m.links[m.frame_link(l).unwrap()].mass_kg;
    // de Leva female: upper arm 2.55 %, forearm 1.38 %, hand 0.56 %, torso 30.10 %, head 6.68 %
    assert!((mass("r_upper_arm") - 0.0255 * 60.0).abs() < 1e-3);
    assert!((mass("r_forearm") - 0.0138 * 60.0).abs() < 1e-3);
    assert!((mass("r_hand") - 0.0056 * 60.0).abs() < 1e-3);
    assert!((mass("trunk") - 30.10 / 100.0 * 60.0).abs() < 1e-3);
    assert!((mass("head") - 0.0668 * 60.0).abs() < 1e-3);
    assert!((mass("l_arm") - (0.0255 + 0.0138 + 0.0056) * 60.0).abs() < 1e-3);
    // arm lengths scale with stature from de Leva's female reference (1.735 m): 0.2751 + 0.2643
    let mut d = StaticsData::new(&m);
    holding_torques(
        &m,
        &mut d,
        &vec![0.0; m.nq()],
        m.frame_link("r_hand").unwrap(),
        &Vector3::zeros(),
        &GRAVITY_M_S2,
    );
    let shoulder = d.link_pose(&m, m.frame_link("r_upper_arm").unwrap()).1;
    let wrist = d.hand_pos_m;
    assert!(((shoulder - wrist).norm() - (0.2751 + 0.2643) * 1.62 / 1.735).abs() < 1e-4);
}

#[test]
fn holding_the_forearm_horizontal_by_hand() {
    // Upright, upper arm hanging, elbow at 90°: the elbow holds forearm + hand against gravity.
    let w = Worker::MALE_50;
    let m = BodyModel::from_urdf_str(
        &worker_urdf(&w, &StrengthTable::default_table()).unwrap(),
        "gen",
    )
    .unwrap();
    let mut q = vec![0.0; m.nq()];
    q[m.q_index("r_elbow_flexion").unwrap()] = std::f64::consts::FRAC_PI_2;
    let mut d = StaticsData::new(&m);
    holding_torques(
        &m,
        &mut d,
        &q,
        m.frame_link("hand_grip").unwrap(),
        &Vector3::new(0.0, 0.0, -2.0 * 9.81),
        &GRAVITY_M_S2,
    );
    let s = 1.755 / 1.741;
    let (lfa, lh) = (0.2689 * s, 0.0862 * s);
    let (mf, mh) = (0.0162 * 78.0, 0.0061 * 78.0);
    let expected = 9.81 * (mf * 0.4574 * lfa + mh * (lfa + 0.79 * lh) + 2.0 * (lfa + 0.75 * lh));
    let tau = d.tau_nm[m.q_index("r_elbow_flexion").unwrap()];
    // the URDF stores lengths to 10 µm and masses to 0.1 g
    assert!(
        (tau - expected).abs() < 1e-4 * expected,
        "{tau} vs {expected}"
    );
    // the shoulder (flexion) holds the same moment about its own axis: the forearm is in front of it
    let tau_sh = d.tau_nm[m.q_index("r_shoulder_flexion").unwrap()];
    assert!((tau_sh - expected).abs() < 1e-4 * expected);
}

#[test]
fn strength_scaling_by_hand() {
    let t = StrengthTable::default_table();
    // reference man: the table value
    assert_eq!(
        t.mvc_nm("r_elbow_flexion", Direction::Positive, &Worker::MALE_50)
            .unwrap(),
        70.0
    );
    // woman, 60 kg, 50th: 70 × 0.55 × (60/78)^0.667
    let w = worker(Sex::Female, 1.62, 60.0, 50.0);
    let expected = 70.0 * 0.55 * (60.0f64 / 78.0).powf(0.667);
    assert!(
        (t.mvc_nm("r_elbow_flexion", Direction::Positive, &w)
            .unwrap()
            - expected)
            .abs()
            < 1e-9
    );
    // 5th-percentile man: z = −1.6449, × (1 − 1.6449 × 0.25)
    let w5 = worker(Sex::Male, 1.755, 78.0, 5.0);
    let v = t
        .mvc_nm("r_elbow_flexion", Direction::Positive, &w5)
        .unwrap();
    assert!((v - 70.0 * (1.0 - 1.6448536 * 0.25)).abs() < 1e-5, "{v}");
    assert!((normal_quantile(0.975) - 1.959964).abs() < 1e-6);
    assert!((normal_quantile(0.5)).abs() < 1e-12);
    assert!((normal_quantile(0.01) + 2.326348).abs() < 1e-6);
}

#[test]
fn half_joints_resolve_with_urdf_fallback() {
    let root = env!("CARGO_MANIFEST_DIR");
    let m = BodyModel::from_urdf_file(format!("{root}/robots/worker.urdf")).unwrap();
    let hjs =
        resolve_half_joints(&m, &StrengthTable::default_table(), &Worker::MALE_50, "t").unwrap();
    assert_eq!(hjs.len(), 20);
    assert!(hjs
        .iter()
        .any(|h| h.id == "r_elbow_flexion+" && h.group == "elbow flexors"));
    // half-joint load: elbow flexors see positive torque only
    let e = hjs.iter().find(|h| h.id == "r_elbow_flexion+").unwrap();
    assert_eq!(e.load(-10.0, 0.0), 0.0);
    assert!((e.load(35.0, 0.0) - 0.5).abs() < 1e-12);
    // shoulder flexors weaken with flexion: 90 N·m at 0, 90·(1 − 0.297·π/4) at 45°
    let s = hjs.iter().find(|h| h.id == "r_shoulder_flexion+").unwrap();
    assert!(
        (s.mvc_at(std::f64::consts::FRAC_PI_4)
            - 90.0 * (1.0 - 0.297 * std::f64::consts::FRAC_PI_4))
            .abs()
            < 1e-9
    );
    // a URDF joint without table entry falls back to <limit effort>
    let two = BodyModel::from_urdf_file(format!("{root}/tests/data/two_link.urdf")).unwrap();
    let hjs =
        resolve_half_joints(&two, &StrengthTable::default_table(), &Worker::MALE_50, "t").unwrap();
    assert_eq!(hjs[0].mvc_nm, 80.0);
    assert!(hjs[0].source.contains("URDF <limit effort>"));
}

#[test]
fn bad_strength_files_are_named() {
    let e = StrengthTable::from_yaml_str("reference_worker: {sex: male, stature_m: 1.7, mass_kg: 70}\nmass_exponent: 0.6\ncoefficient_of_variation: 0.2\nhalf_joints:\n  - {joint: a, direction: \"+\", group: g, region: r, mvc_nm: -3, female_factor: 0.5, source: s}\n", "s.yaml").unwrap_err().to_string();
    assert!(
        e.contains("s.yaml") && e.contains("half_joints[0]") && e.contains("mvc_nm"),
        "{e}"
    );
    let e = StrengthTable::from_yaml_str("reference_worker: {sex: male, stature_m: 1.7, mass_kg: 70}\nmass_exponent: 0.6\ncoefficient_of_variation: 0.2\nbogus: 1\nhalf_joints: []\n", "s.yaml").unwrap_err().to_string();
    assert!(e.contains("s.yaml") && e.contains("bogus"), "{e}");
}

#[test]
fn worker_ranges_are_checked() {
    let t = StrengthTable::default_table();
    assert!(worker_urdf(&worker(Sex::Male, 3.0, 80.0, 50.0), &t).is_err());
    assert!(worker_urdf(&worker(Sex::Male, 1.8, f64::NAN, 50.0), &t).is_err());
    assert!(worker_urdf(&worker(Sex::Male, 1.8, 80.0, 100.0), &t).is_err());
}
