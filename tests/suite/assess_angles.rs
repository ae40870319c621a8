//! Body angles (`posture_opt::assess::angles::BodyAngles::measure`) on postures of the generated
//! whole-body worker (`robots/worker.urdf`) whose angles are known by construction.
//!
//! The worker's joints (x forward, y left, z up; q = 0 standing upright, arms hanging, palms
//! facing the thighs): `pelvis_tilt` and `lumbar_flexion` both turn about +y (forward bending),
//! `lumbar_lateral_bending` about −x (bending to the left), `lumbar_axial_rotation` about +z
//! (turning to the left); the lumbar chain is flexion → lateral bending → axial rotation. The
//! right shoulder is flexion (−y) → abduction (−x) → rotation (+z), the elbow −y, and the upper
//! arm and forearm point down their links' −z at q = 0; the left side mirrors the right.
//!
//! Each expected angle is derived in the test's comment from those rotations alone: e.g. a trunk
//! bent by R = R_y(θ) R_x(−φ) has its long axis R·z = (sin θ cos φ, sin φ, cos θ cos φ), so its
//! angle from the vertical in the sagittal plane is atan2(sin θ cos φ, cos θ cos φ) = θ and its
//! angle out of the sagittal plane is asin(sin φ) = φ, exactly.

use posture_opt::assess::angles::BodyAngles;
use posture_opt::body::{BodyModel, StaticsData};

const TOL_DEG: f64 = 1e-6;

fn worker() -> BodyModel {
    BodyModel::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf")).unwrap()
}

/// The angles of the worker with the named joints set (degrees; prismatic joints in metres),
/// all others 0, and `share` of the weight on the left foot.
fn angles_with(m: &BodyModel, set: &[(&str, f64)], share: Option<f64>) -> BodyAngles {
    let mut q = vec![0.0; m.nq()];
    for (name, v) in set {
        let i = m
            .q_index(name)
            .unwrap_or_else(|_| panic!("no joint {name}"));
        q[i] = if name.starts_with("pelvis_t") && !name.ends_with("tilt") {
            *v
        } else {
            v.to_radians()
        };
    }
    let mut data = StaticsData::new(m, 2);
    BodyAngles::measure(m, &mut data, &q, share).unwrap()
}

fn angles(set: &[(&str, f64)]) -> BodyAngles {
    angles_with(&worker(), set, Some(0.5))
}

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() < TOL_DEG, "{what}: {a} vs {b}");
}

/// q = 0: every angle 0 (upper arms hanging along the trunk, elbows straight), both feet.
#[test]
fn standing_upright_is_all_zero() {
    let a = angles(&[]);
    for (v, what) in [
        (a.trunk_flexion_deg, "trunk flexion"),
        (a.trunk_side_bend_deg, "trunk side bend"),
        (a.trunk_twist_deg, "trunk twist"),
        (a.neck_flexion_deg, "neck flexion"),
        (a.neck_side_bend_deg, "neck side bend"),
        (a.neck_twist_deg, "neck twist"),
        (a.right.upper_arm_flexion_deg, "right upper arm"),
        (a.left.upper_arm_flexion_deg, "left upper arm"),
        (a.right.upper_arm_abduction_deg, "right abduction"),
        (a.left.upper_arm_abduction_deg, "left abduction"),
        (a.right.elbow_flexion_deg, "right elbow"),
        (a.left.elbow_flexion_deg, "left elbow"),
        (a.right.wrist_twist_fraction, "right twist"),
        (a.right_knee_flexion_deg, "right knee"),
    ] {
        close(v, 0.0, what);
    }
    assert!(a.both_feet_bear_weight);
    assert!(!a.right.hand_across_midline && !a.right.hand_out_to_side);
    assert!(!a.left.hand_across_midline && !a.left.hand_out_to_side);
}

/// Pure lumbar flexion θ = 30°: trunk axis R_y(30°)·z = (sin 30°, 0, cos 30°) → 30° from the
/// vertical, 0° out of the sagittal plane, no twist.
#[test]
fn pure_lumbar_flexion_is_trunk_flexion() {
    let a = angles(&[("lumbar_flexion", 30.0)]);
    close(a.trunk_flexion_deg, 30.0, "trunk flexion");
    close(a.trunk_side_bend_deg, 0.0, "side bend");
    close(a.trunk_twist_deg, 0.0, "twist");
    // The neck and arms are measured against the trunk: still 0.
    close(a.neck_flexion_deg, 0.0, "neck");
    close(
        a.right.upper_arm_flexion_deg,
        0.0,
        "upper arm against the trunk",
    );
}

/// Lumbar extension −15°: trunk leaning back 15° (negative flexion).
#[test]
fn lumbar_extension_is_negative_flexion() {
    let a = angles(&[("lumbar_flexion", -15.0)]);
    close(a.trunk_flexion_deg, -15.0, "trunk flexion");
}

/// Pelvis tilt and lumbar flexion turn about the same axis (+y), so they add: 20° + 30° = 50°.
/// The stoop's heading stays the pelvis's (forward = +x).
#[test]
fn pelvis_tilt_and_lumbar_flexion_add() {
    let a = angles(&[("pelvis_tilt", 20.0), ("lumbar_flexion", 30.0)]);
    close(a.trunk_flexion_deg, 50.0, "trunk flexion");
    close(a.trunk_side_bend_deg, 0.0, "side bend");
    close(a.trunk_twist_deg, 0.0, "twist");
    // Pelvis tilt alone: the trunk inclines with the pelvis.
    let a = angles(&[("pelvis_tilt", 25.0)]);
    close(
        a.trunk_flexion_deg,
        25.0,
        "trunk flexion from the pelvis alone",
    );
}

/// Pure lumbar axial rotation of 30° to the left: the shoulder line turns 30° against the
/// pelvis (left positive); the trunk axis stays vertical.
#[test]
fn pure_twist_is_twist() {
    let a = angles(&[("lumbar_axial_rotation", 30.0)]);
    close(a.trunk_twist_deg, 30.0, "twist");
    close(a.trunk_flexion_deg, 0.0, "flexion");
    close(a.trunk_side_bend_deg, 0.0, "side bend");
    let a = angles(&[("lumbar_axial_rotation", -20.0)]);
    close(a.trunk_twist_deg, -20.0, "twist to the right");
}

/// Hips rotated on planted feet turn the pelvis against the feet: the right hip rotated 30°
/// outward and the left 30° inward (internal rotation positive, docs/body.md) turn both feet 30°
/// to the right under a pelvis that faces ahead, so the pelvis faces 30° to the left of the feet;
/// turning the whole body (`pelvis_rotation`, the feet with it) turns nothing against the feet.
#[test]
fn the_pelvis_turn_is_against_the_feet() {
    let a = angles(&[("r_hip_rotation", -30.0), ("l_hip_rotation", 30.0)]);
    close(a.pelvis_turn_deg, 30.0, "pelvis turned left of the feet");
    assert!(
        posture_opt::assess::phase::describe(&a)
            .contains("pelvis turned 30° to the left of the feet")
    );
    let a = angles(&[("r_hip_rotation", 20.0), ("l_hip_rotation", -20.0)]);
    close(a.pelvis_turn_deg, -20.0, "pelvis turned right of the feet");
    let a = angles(&[("pelvis_rotation", 40.0)]);
    close(a.pelvis_turn_deg, 0.0, "whole body turned");
    assert!(!posture_opt::assess::phase::describe(&a).contains("pelvis turned"));
}

/// Turning the whole body (`pelvis_rotation`, the heading) is not a twist and not a bend: the
/// angles are measured in the pelvis's own heading frame.
#[test]
fn turning_the_whole_body_is_not_a_twist() {
    let a = angles(&[("pelvis_rotation", 40.0), ("lumbar_flexion", 30.0)]);
    close(a.trunk_twist_deg, 0.0, "twist");
    close(
        a.trunk_flexion_deg,
        30.0,
        "flexion in the body's own sagittal plane",
    );
    close(a.trunk_side_bend_deg, 0.0, "side bend");
}

/// Pure lumbar lateral bending φ = 15° to the left: axis R_x(−15°)·z = (0, sin 15°, cos 15°):
/// side bend +15° (left positive), no flexion.
#[test]
fn pure_lateral_bending_is_side_bend() {
    let a = angles(&[("lumbar_lateral_bending", 15.0)]);
    close(a.trunk_side_bend_deg, 15.0, "side bend");
    close(a.trunk_flexion_deg, 0.0, "flexion");
    let a = angles(&[("pelvis_list", -10.0)]);
    close(a.trunk_side_bend_deg, -10.0, "pelvis list to the right");
}

/// Trunk flexed 85° (pelvis tilt 25° + lumbar flexion 60°) with 10° of lumbar lateral bending:
/// axis R_y(85°) R_x(−10°)·z = (sin 85° cos 10°, sin 10°, cos 85° cos 10°). Flexion
/// atan2(sin 85° cos 10°, cos 85° cos 10°) = 85°; side bend asin(sin 10°) = 10°. A side-bend
/// measured as atan2(y, z) in the frontal plane would give atan2(0.174, 0.086) ≈ 63.7° and flag
/// an almost upright-in-the-frontal-plane stoop as severely bent.
#[test]
fn deep_stoop_with_small_side_bend_is_not_a_large_side_bend() {
    let a = angles(&[
        ("pelvis_tilt", 25.0),
        ("lumbar_flexion", 60.0),
        ("lumbar_lateral_bending", 10.0),
    ]);
    close(a.trunk_flexion_deg, 85.0, "flexion");
    close(a.trunk_side_bend_deg, 10.0, "side bend");
    assert!(a.trunk_side_bend_deg.abs() < 20.0);
}

/// Axial rotation of the thorax against the pelvis is the anatomical trunk twist whatever the
/// flexion (REBA: "twisting"; RULA: "trunk is twisting"). Lumbar flexion 60° then axial rotation
/// 20° rotates the trunk 20° about its own long axis, so the twist is 20°.
#[test]
fn twist_in_a_stoop_is_the_axial_rotation() {
    let a = angles(&[("lumbar_flexion", 60.0), ("lumbar_axial_rotation", 20.0)]);
    assert!(
        (a.trunk_twist_deg - 20.0).abs() < 0.5,
        "{}",
        a.trunk_twist_deg
    );
}

/// The trunk flexion itself is unchanged by a twist that follows it in the chain: R_y(60°)
/// R_z(20°)·z = R_y(60°)·z.
#[test]
fn twist_does_not_change_trunk_flexion() {
    let a = angles(&[("lumbar_flexion", 60.0), ("lumbar_axial_rotation", 20.0)]);
    close(a.trunk_flexion_deg, 60.0, "flexion");
    close(a.trunk_side_bend_deg, 0.0, "side bend");
    assert!(a.trunk_twist_deg > 0.0, "twist to the left is positive");
}

/// Neck flexion 20° (chin to chest): the head's axis against the trunk's, 20°; with the trunk
/// flexed 30° the neck is still 20° (it is measured against the trunk). Neck lateral bending
/// 10° → 10°; axial rotation 30° → 30°.
#[test]
fn neck_angles_are_against_the_trunk() {
    let a = angles(&[("neck_flexion", 20.0)]);
    close(a.neck_flexion_deg, 20.0, "neck flexion");
    let a = angles(&[("neck_flexion", 20.0), ("lumbar_flexion", 30.0)]);
    close(a.neck_flexion_deg, 20.0, "neck flexion with the trunk bent");
    close(a.trunk_flexion_deg, 30.0, "trunk");
    let a = angles(&[("neck_lateral_bending", 10.0)]);
    close(a.neck_side_bend_deg, 10.0, "neck side bend");
    let a = angles(&[("neck_axial_rotation", 30.0)]);
    close(a.neck_twist_deg, 30.0, "neck twist");
    let a = angles(&[("neck_flexion", -25.0)]);
    close(a.neck_flexion_deg, -25.0, "neck extension");
}

/// Shoulder flexion θ: upper arm R_y(−θ)·(0, 0, −1) = (sin θ, 0, −cos θ), elevation
/// acos(cos θ) = θ forward, nothing out of the sagittal plane. With the trunk flexed 40° the
/// upper arm is still θ against the trunk.
#[test]
fn upper_arm_flexion_from_shoulder_flexion() {
    for theta in [30.0, 60.0, 90.0, 120.0] {
        let a = angles(&[("r_shoulder_flexion", theta), ("l_shoulder_flexion", theta)]);
        close(a.right.upper_arm_flexion_deg, theta, "right flexion");
        close(a.left.upper_arm_flexion_deg, theta, "left flexion");
        close(a.right.upper_arm_abduction_deg, 0.0, "right abduction");
        close(a.left.upper_arm_abduction_deg, 0.0, "left abduction");
    }
    let a = angles(&[("r_shoulder_flexion", 50.0), ("lumbar_flexion", 40.0)]);
    close(
        a.right.upper_arm_flexion_deg,
        50.0,
        "flexion against the trunk",
    );
}

/// Shoulder extension (flexion −30°): the arm points back, (−sin 30°, 0, −cos 30°): −30°.
#[test]
fn upper_arm_extension_is_negative() {
    let a = angles(&[("r_shoulder_flexion", -30.0)]);
    close(a.right.upper_arm_flexion_deg, -30.0, "extension");
}

/// Shoulder abduction φ (right: about −x; left: about +x): the arm goes out sideways,
/// (0, ∓sin φ, −cos φ): φ out of the sagittal plane (outward positive on both sides), and its
/// elevation from hanging is φ (the module's "flexion" is the elevation, module documentation).
#[test]
fn upper_arm_abduction_from_shoulder_abduction() {
    let a = angles(&[
        ("r_shoulder_abduction", 45.0),
        ("l_shoulder_abduction", 30.0),
    ]);
    close(a.right.upper_arm_abduction_deg, 45.0, "right abduction");
    close(a.left.upper_arm_abduction_deg, 30.0, "left abduction");
    close(a.right.upper_arm_flexion_deg, 45.0, "right elevation");
    close(a.left.upper_arm_flexion_deg, 30.0, "left elevation");
}

/// Upper-arm rotation turns the humerus about its own axis: the shoulder-to-elbow direction,
/// hence the upper-arm angles, do not change.
#[test]
fn humeral_rotation_does_not_move_the_upper_arm() {
    let a = angles(&[("r_shoulder_flexion", 40.0), ("r_shoulder_rotation", 50.0)]);
    close(a.right.upper_arm_flexion_deg, 40.0, "flexion");
    close(a.right.upper_arm_abduction_deg, 0.0, "abduction");
}

/// The elbow's included-angle flexion is the elbow joint angle: the forearm is the upper arm
/// direction turned by the elbow angle about the elbow axis, whatever the shoulder does.
#[test]
fn elbow_included_angle() {
    for e in [30.0, 90.0, 120.0] {
        let a = angles(&[("r_elbow_flexion", e), ("l_elbow_flexion", e)]);
        close(a.right.elbow_flexion_deg, e, "right elbow");
        close(a.left.elbow_flexion_deg, e, "left elbow");
    }
    let a = angles(&[
        ("r_shoulder_flexion", 70.0),
        ("r_shoulder_abduction", 20.0),
        ("r_shoulder_rotation", -30.0),
        ("r_elbow_flexion", 100.0),
    ]);
    close(
        a.right.elbow_flexion_deg,
        100.0,
        "elbow with the shoulder moved",
    );
}

/// Wrist flexion and deviation are the wrist joints; the forearm twist is the pronation as a
/// fraction of its limit (the worker's forearm pronation range is ±80°, so 40° is 0.5).
#[test]
fn wrist_and_forearm() {
    let m = worker();
    let a = angles_with(
        &m,
        &[
            ("r_wrist_flexion", 30.0),
            ("r_wrist_deviation", -10.0),
            ("r_forearm_pronation", 40.0),
            ("l_forearm_pronation", -40.0),
        ],
        Some(0.5),
    );
    close(a.right.wrist_flexion_deg, 30.0, "wrist flexion");
    close(a.right.wrist_deviation_deg, -10.0, "wrist deviation");
    close(a.right.forearm_pronation_deg, 40.0, "pronation");
    let j = m.q_joint(m.q_index("r_forearm_pronation").unwrap());
    close(
        a.right.wrist_twist_fraction,
        40f64.to_radians() / j.upper_rad,
        "twist fraction",
    );
    assert!((j.upper_rad - 80f64.to_radians()).abs() < 1e-3);
    assert!((a.right.wrist_twist_fraction - 0.5).abs() < 1e-3);
    assert!((a.left.wrist_twist_fraction.abs() - 0.5).abs() < 1e-3);
}

/// Knees: each knee's joint angle. Feet: both bear weight when each carries at least 10 % of it.
#[test]
fn knees_and_feet() {
    let m = worker();
    let a = angles_with(
        &m,
        &[("r_knee_flexion", 40.0), ("l_knee_flexion", 70.0)],
        None,
    );
    close(a.right_knee_flexion_deg, 40.0, "right knee");
    close(a.left_knee_flexion_deg, 70.0, "left knee");
    // No stance (no feet) counts as both feet.
    assert!(a.both_feet_bear_weight);
    assert!(angles_with(&m, &[], Some(0.5)).both_feet_bear_weight);
    assert!(angles_with(&m, &[], Some(0.2)).both_feet_bear_weight);
    assert!(!angles_with(&m, &[], Some(0.05)).both_feet_bear_weight);
    assert!(!angles_with(&m, &[], Some(0.97)).both_feet_bear_weight);
}

/// Right arm raised 90° sideways, elbow straight: the hand is an arm's length (> 0.5 m) to the
/// right of the shoulder: "out to the side". The same arm hanging with the elbow at 90° and the
/// humerus rotated 70° inward points the forearm across the body: the hand (forearm ≈ 0.27 m,
/// shoulder 0.18 m right of the mid-plane) ends left of the mid-plane: "across the midline".
#[test]
fn hand_out_to_side_and_across_midline() {
    let a = angles(&[("r_shoulder_abduction", 90.0)]);
    assert!(a.right.hand_out_to_side);
    assert!(!a.right.hand_across_midline);
    let a = angles(&[("r_elbow_flexion", 90.0), ("r_shoulder_rotation", 70.0)]);
    assert!(a.right.hand_across_midline, "{:?}", a.right);
    assert!(!a.right.hand_out_to_side);
    // Mirror: the left arm.
    let a = angles(&[("l_elbow_flexion", 90.0), ("l_shoulder_rotation", 70.0)]);
    assert!(a.left.hand_across_midline, "{:?}", a.left);
}

/// A body that is not the worker is refused with the missing frame's name.
#[test]
fn other_bodies_are_refused() {
    let m = BodyModel::from_urdf_file(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/two_link.urdf"
    ))
    .unwrap();
    let mut data = StaticsData::new(&m, 1);
    let q = vec![0.0; m.nq()];
    let e = BodyAngles::measure(&m, &mut data, &q, None).unwrap_err();
    assert!(e.to_string().contains("pelvis"), "{e}");
}

/// ISO 11226's angles are against the vertical. A trunk flexed 40° forward turns the hanging
/// arm 40° back (it stays along the trunk), so an upper arm flexed 50° against that trunk points
/// 10° forward of straight down and one flexed 130° points 90° from it; the head with the neck
/// flexed 20° on a trunk flexed 30° is inclined 50° (their up axes add); standing upright both
/// are 0; an arm raised 120° with the trunk upright is elevated 120°.
#[test]
fn iso_angles_are_against_the_vertical() {
    let a = angles(&[]);
    close(a.right.upper_arm_elevation_deg, 0.0, "arm hanging");
    close(a.head_inclination_deg, 0.0, "head upright");
    let a = angles(&[("r_shoulder_flexion", 50.0), ("lumbar_flexion", 40.0)]);
    close(
        a.right.upper_arm_elevation_deg,
        10.0,
        "arm against the vertical",
    );
    close(
        a.left.upper_arm_elevation_deg,
        40.0,
        "hanging arm follows the trunk",
    );
    let a = angles(&[("r_shoulder_flexion", 130.0), ("lumbar_flexion", 40.0)]);
    close(a.right.upper_arm_elevation_deg, 90.0, "arm horizontal");
    let a = angles(&[("neck_flexion", 20.0), ("lumbar_flexion", 30.0)]);
    close(a.head_inclination_deg, 50.0, "head inclination");
    let a = angles(&[("neck_flexion", -25.0)]);
    close(a.head_inclination_deg, -25.0, "head tilted back");
    let a = angles(&[("l_shoulder_flexion", 120.0)]);
    close(a.left.upper_arm_elevation_deg, 120.0, "arm raised overhead");
}
