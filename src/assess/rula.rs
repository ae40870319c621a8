//! RULA, the Rapid Upper Limb Assessment of McAtamney & Corlett (1993, Applied Ergonomics
//! 24(2):91–99), scored from a posture of the whole-body worker, with every worksheet step
//! recorded (what was measured, which rule applied, the score).
//!
//! Tables A, B and C are those of the 1993 paper (several later worksheets print a variant of
//! Table A for upper-arm scores 2–4; the paper's version is used). The angles come from the
//! posture's geometry ([`BodyAngles`]): trunk against the vertical, neck against the trunk, arms
//! against the trunk, the wrist joints, the knees and the feet's weight shares. What a posture
//! does not say is fixed by documented ASSUMPTIONS, listed in [`Rula::assumptions`]:
//! * the shoulder girdle is not modelled (never "raised") and the arm is never supported;
//! * "neutral" means within [`NEUTRAL_TOLERANCE_DEG`] (5°), and the "+1 if twisted / bent /
//!   abducted" adjustments apply beyond [`ADJUSTMENT_THRESHOLD_DEG`] (upper-arm abduction
//!   beyond 20°); the wrist is "at or near the end of its twisting range" beyond 75 % of the
//!   forearm joint's range on that side; the hand works "out to the side" when it is more than
//!   10 cm lateral of the shoulder, "across the midline" when it is on the other side of the
//!   trunk's mid-plane; legs score 1 when both feet bear weight, 2 otherwise;
//! * **sides**: RULA scores one arm; both are scored and the worse grand score is reported
//!   (ties: the arm holding more load, else the right), as RULA's authors advise for
//!   asymmetric work.

use super::angles::{ArmAngles, BodyAngles};
use serde::Serialize;

/// Within this many degrees of neutral counts as neutral (pose tolerance).
pub const NEUTRAL_TOLERANCE_DEG: f64 = 5.0;
/// Twist and side-bend (trunk) and deviation (wrist) beyond this many degrees add +1.
pub const ADJUSTMENT_THRESHOLD_DEG: f64 = 10.0;
/// Upper arm abducted (out of the sagittal plane) beyond this many degrees adds +1.
pub const ABDUCTION_THRESHOLD_DEG: f64 = 20.0;
/// The wrist twist is "near the end of range" beyond this fraction of the joint's limit.
pub const TWIST_END_FRACTION: f64 = 0.75;
/// The hand is "out to the side" beyond this lateral distance from the shoulder \[m\].
pub const OUT_TO_SIDE_M: f64 = 0.10;

/// Table A of McAtamney & Corlett (1993): [upper arm 1–6][lower arm 1–3][wrist 1–4 × twist 1–2].
const TABLE_A: [[[u8; 8]; 3]; 6] = [
    [
        [1, 2, 2, 2, 2, 3, 3, 3],
        [2, 2, 2, 2, 3, 3, 3, 3],
        [2, 3, 3, 3, 3, 3, 4, 4],
    ],
    [
        [2, 3, 3, 3, 3, 4, 4, 4],
        [3, 3, 3, 3, 3, 4, 4, 4],
        [3, 4, 4, 4, 4, 4, 5, 5],
    ],
    [
        [3, 3, 4, 4, 4, 4, 5, 5],
        [3, 4, 4, 4, 4, 4, 5, 5],
        [4, 4, 4, 4, 4, 5, 5, 5],
    ],
    [
        [4, 4, 4, 4, 4, 5, 5, 5],
        [4, 4, 4, 4, 4, 5, 5, 5],
        [4, 4, 4, 5, 5, 5, 6, 6],
    ],
    [
        [5, 5, 5, 5, 5, 6, 6, 7],
        [5, 6, 6, 6, 6, 7, 7, 7],
        [6, 6, 6, 7, 7, 7, 7, 8],
    ],
    [
        [7, 7, 7, 7, 7, 8, 8, 9],
        [8, 8, 8, 8, 8, 9, 9, 9],
        [9, 9, 9, 9, 9, 9, 9, 9],
    ],
];

/// Table B: [neck 1–6][trunk 1–6 × legs 1–2].
const TABLE_B: [[u8; 12]; 6] = [
    [1, 3, 2, 3, 3, 4, 5, 5, 6, 6, 7, 7],
    [2, 3, 2, 3, 4, 5, 5, 5, 6, 7, 7, 7],
    [3, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 7],
    [5, 5, 5, 6, 6, 7, 7, 7, 7, 7, 8, 8],
    [7, 7, 7, 7, 7, 8, 8, 8, 8, 8, 8, 8],
    [8, 8, 8, 8, 8, 8, 8, 9, 9, 9, 9, 9],
];

/// Table C: [score C 1–8+][score D 1–7+].
const TABLE_C: [[u8; 7]; 8] = [
    [1, 2, 3, 3, 4, 5, 5],
    [2, 2, 3, 4, 4, 5, 5],
    [3, 3, 3, 4, 4, 5, 6],
    [3, 3, 3, 4, 5, 6, 6],
    [4, 4, 4, 5, 6, 7, 7],
    [4, 4, 5, 6, 6, 7, 7],
    [5, 5, 6, 6, 7, 7, 7],
    [5, 5, 6, 7, 7, 7, 7],
];

/// The angles and positions RULA looks at (degrees; flexion positive).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RulaPosture {
    /// Upper arm elevation from the trunk's downward axis; negative when the arm points back
    /// (extension).
    pub upper_arm_flexion_deg: f64,
    /// Upper arm's angle out of the trunk's sagittal plane, outward positive.
    pub upper_arm_abduction_deg: f64,
    /// Included-angle flexion of the elbow (0 = straight arm).
    pub elbow_flexion_deg: f64,
    pub hand_across_midline: bool,
    pub hand_out_to_side: bool,
    pub wrist_flexion_deg: f64,
    pub wrist_deviation_deg: f64,
    /// Forearm pronation as a fraction of the joint's limit on that side (0 = mid-range).
    pub wrist_twist_fraction: f64,
    /// Trunk's inclination from the vertical in the pelvis's sagittal plane, forward positive.
    pub trunk_flexion_deg: f64,
    pub trunk_twist_deg: f64,
    pub trunk_side_bend_deg: f64,
    /// Head against the trunk, flexion positive.
    pub neck_flexion_deg: f64,
    pub neck_twist_deg: f64,
    pub neck_side_bend_deg: f64,
    /// Both feet bear weight.
    pub legs_supported: bool,
}

/// How the posture is used: what the hand holds and how often / long the posture recurs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RulaActivity {
    /// Load in the hand \[kg\] (hand force magnitude / g).
    pub load_kg: f64,
    /// How long the posture is held at a time \[s\].
    pub held_s: f64,
    /// How many times per minute the posture recurs.
    pub repeats_per_min: f64,
}

/// One line of the RULA worksheet.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorksheetStep {
    /// Step number as on the worksheet ("1", "1a", ..., "15").
    pub step: &'static str,
    pub item: &'static str,
    /// What was measured (degrees, kg or repetitions per minute), if anything.
    pub measured: Option<f64>,
    /// The rule that applied.
    pub rule: String,
    pub score: i32,
}

/// A RULA assessment: the worksheet, the intermediate scores and the grand score.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Rula {
    pub side: String,
    pub worksheet: Vec<WorksheetStep>,
    pub upper_arm: i32,
    pub lower_arm: i32,
    pub wrist: i32,
    pub wrist_twist: i32,
    pub posture_a: i32,
    pub score_c: i32,
    pub neck: i32,
    pub trunk: i32,
    pub legs: i32,
    pub posture_b: i32,
    pub score_d: i32,
    /// Grand score 1–7.
    pub grand_score: i32,
    /// Action level 1–4.
    pub action_level: i32,
    pub action: &'static str,
    pub assumptions: Vec<&'static str>,
}

const ASSUMPTIONS: [&str; 4] = [
    "legs: both feet bear weight (each at least 10 % of it) scores 1, else 2",
    "sides: both arms are scored and the worse grand score is reported",
    "shoulder girdle not modelled (never raised); arm never supported",
    "thresholds: neutral within 5 deg; twist/side-bend/deviation beyond 10 deg, abduction beyond 20 deg, wrist twist beyond 75% of the joint limit, hand > 10 cm lateral of the shoulder = out to side",
];

impl RulaPosture {
    /// RULA's view of one arm (and of the trunk, neck and legs) of measured body angles.
    pub fn from_angles(b: &BodyAngles, arm: &ArmAngles) -> Self {
        RulaPosture {
            upper_arm_flexion_deg: arm.upper_arm_flexion_deg,
            upper_arm_abduction_deg: arm.upper_arm_abduction_deg,
            elbow_flexion_deg: arm.elbow_flexion_deg,
            hand_across_midline: arm.hand_across_midline,
            hand_out_to_side: arm.hand_out_to_side,
            wrist_flexion_deg: arm.wrist_flexion_deg,
            wrist_deviation_deg: arm.wrist_deviation_deg,
            wrist_twist_fraction: arm.wrist_twist_fraction,
            trunk_flexion_deg: b.trunk_flexion_deg,
            trunk_twist_deg: b.trunk_twist_deg,
            trunk_side_bend_deg: b.trunk_side_bend_deg,
            neck_flexion_deg: b.neck_flexion_deg,
            neck_twist_deg: b.neck_twist_deg,
            neck_side_bend_deg: b.neck_side_bend_deg,
            legs_supported: b.both_feet_bear_weight || b.seated,
        }
    }
}

fn step(
    step: &'static str,
    item: &'static str,
    measured: Option<f64>,
    rule: impl Into<String>,
    score: i32,
) -> WorksheetStep {
    WorksheetStep {
        step,
        item,
        measured,
        rule: rule.into(),
        score,
    }
}

/// Action level (1–4) and its wording for a grand score.
pub fn action_level(grand: i32) -> (i32, &'static str) {
    match grand {
        ..=2 => (
            1,
            "acceptable if not maintained or repeated for long periods",
        ),
        3..=4 => (2, "investigate further; changes may be needed"),
        5..=6 => (3, "investigate further and change soon"),
        _ => (4, "investigate and change immediately"),
    }
}

/// Scores one posture: the RULA worksheet, steps 1–15.
///
/// ```
/// use posture_opt::assess::rula::{score, RulaActivity, RulaPosture};
/// // Upper arm 50° (3), elbow 80° (1), wrist 10° (2), twist mid-range (1): Table A gives 4;
/// // 4 kg intermittent adds 1: C = 5. Trunk 15° (2): Table B gives 2, D = 3. Table C: 4.
/// let p = RulaPosture {
///     upper_arm_flexion_deg: 50.0, upper_arm_abduction_deg: 0.0, elbow_flexion_deg: 80.0,
///     hand_across_midline: false, hand_out_to_side: false, wrist_flexion_deg: 10.0,
///     wrist_deviation_deg: 0.0, wrist_twist_fraction: 0.0, trunk_flexion_deg: 15.0,
///     trunk_twist_deg: 0.0, trunk_side_bend_deg: 0.0, neck_flexion_deg: 5.0,
///     neck_twist_deg: 0.0, neck_side_bend_deg: 0.0, legs_supported: true,
/// };
/// let r = score(&p, &RulaActivity { load_kg: 4.0, held_s: 3.0, repeats_per_min: 3.0 });
/// assert_eq!((r.posture_a, r.score_c, r.score_d, r.grand_score, r.action_level), (4, 5, 3, 4, 2));
/// ```
pub fn score(p: &RulaPosture, a: &RulaActivity) -> Rula {
    let mut ws = Vec::with_capacity(20);
    let tol = NEUTRAL_TOLERANCE_DEG;

    // Step 1: upper arm.
    let f = p.upper_arm_flexion_deg;
    let (ua0, rule) = if f < -20.0 {
        (2, "more than 20 deg extension")
    } else if f <= 20.0 {
        (1, "20 deg extension to 20 deg flexion")
    } else if f <= 45.0 {
        (2, "20 to 45 deg flexion")
    } else if f <= 90.0 {
        (3, "45 to 90 deg flexion")
    } else {
        (4, "more than 90 deg flexion")
    };
    ws.push(step("1", "upper arm position", Some(f), rule, ua0));
    let abducted = p.upper_arm_abduction_deg > ABDUCTION_THRESHOLD_DEG;
    let ua_adj = i32::from(abducted);
    ws.push(step(
        "1a",
        "upper arm adjustment",
        Some(p.upper_arm_abduction_deg),
        if abducted {
            "abducted: +1 (shoulder not raised, arm not supported)"
        } else {
            "not abducted, shoulder not raised, arm not supported: +0"
        },
        ua_adj,
    ));
    let upper_arm = (ua0 + ua_adj).clamp(1, 6);

    // Step 2: lower arm.
    let e = p.elbow_flexion_deg;
    let la0 = if (60.0..=100.0).contains(&e) { 1 } else { 2 };
    ws.push(step(
        "2",
        "lower arm position",
        Some(e),
        if la0 == 1 {
            "60 to 100 deg flexion"
        } else {
            "less than 60 or more than 100 deg flexion"
        },
        la0,
    ));
    let la_adj = i32::from(p.hand_across_midline || p.hand_out_to_side);
    ws.push(step(
        "2a",
        "lower arm adjustment",
        None,
        match (p.hand_across_midline, p.hand_out_to_side) {
            (true, _) => "working across the midline: +1",
            (_, true) => "working out to the side of the body: +1",
            _ => "in front of the body: +0",
        },
        la_adj,
    ));
    let lower_arm = (la0 + la_adj).clamp(1, 3);

    // Step 3: wrist.
    let w = p.wrist_flexion_deg.abs();
    let (wr0, rule) = if w <= tol {
        (1, "neutral")
    } else if w <= 15.0 {
        (2, "0 to 15 deg flexion or extension")
    } else {
        (3, "more than 15 deg flexion or extension")
    };
    ws.push(step(
        "3",
        "wrist position",
        Some(p.wrist_flexion_deg),
        rule,
        wr0,
    ));
    let bent = p.wrist_deviation_deg.abs() > ADJUSTMENT_THRESHOLD_DEG;
    ws.push(step(
        "3a",
        "wrist adjustment",
        Some(p.wrist_deviation_deg),
        if bent {
            "bent from the midline (radial/ulnar deviation): +1"
        } else {
            "not bent from the midline: +0"
        },
        i32::from(bent),
    ));
    let wrist = (wr0 + i32::from(bent)).clamp(1, 4);

    // Step 4: wrist twist.
    let near_end = p.wrist_twist_fraction.abs() > TWIST_END_FRACTION;
    let wrist_twist = if near_end { 2 } else { 1 };
    ws.push(step(
        "4",
        "wrist twist",
        Some(p.wrist_twist_fraction),
        if near_end {
            "at or near the end of the twisting range"
        } else {
            "mainly in mid-range"
        },
        wrist_twist,
    ));

    // Step 5: Table A.
    let posture_a = TABLE_A[(upper_arm - 1) as usize][(lower_arm - 1) as usize]
        [((wrist - 1) * 2 + wrist_twist - 1) as usize] as i32;
    ws.push(step(
        "5",
        "posture score A (Table A)",
        None,
        format!(
            "upper arm {upper_arm}, lower arm {lower_arm}, wrist {wrist}, wrist twist {wrist_twist}"
        ),
        posture_a,
    ));

    // Steps 6, 7: muscle use and force, shared by both halves of the sheet.
    let static_or_repeated = a.held_s > 60.0 || a.repeats_per_min >= 4.0;
    let muscle = i32::from(static_or_repeated);
    let muscle_rule = if a.held_s > 60.0 {
        "mainly static (held longer than 1 min): +1"
    } else if a.repeats_per_min >= 4.0 {
        "repeated 4 or more times per minute: +1"
    } else {
        "neither static nor repeated 4 times per minute: +0"
    };
    ws.push(step(
        "6",
        "muscle use (arm and wrist)",
        Some(a.repeats_per_min),
        muscle_rule,
        muscle,
    ));
    let (force, force_rule) = if a.load_kg < 2.0 {
        (0, "less than 2 kg")
    } else if a.load_kg < 10.0 {
        if static_or_repeated {
            (2, "2 to 10 kg, static or repeated")
        } else {
            (1, "2 to 10 kg, intermittent")
        }
    } else if static_or_repeated {
        (3, "10 kg or more, static or repeated")
    } else {
        (2, "10 kg or more, intermittent")
    };
    ws.push(step(
        "7",
        "force / load (arm and wrist)",
        Some(a.load_kg),
        force_rule,
        force,
    ));
    let score_c = posture_a + muscle + force;
    ws.push(step(
        "8",
        "wrist and arm score C",
        None,
        "posture score A + muscle use + force",
        score_c,
    ));

    // Steps 9-11: neck, trunk, legs.
    let nf = p.neck_flexion_deg;
    let (nk0, rule) = if nf < -tol {
        (4, "in extension")
    } else if nf <= 10.0 {
        (1, "0 to 10 deg flexion")
    } else if nf <= 20.0 {
        (2, "10 to 20 deg flexion")
    } else {
        (3, "more than 20 deg flexion")
    };
    ws.push(step("9", "neck position", Some(nf), rule, nk0));
    let n_twist = p.neck_twist_deg.abs() > ADJUSTMENT_THRESHOLD_DEG;
    let n_side = p.neck_side_bend_deg.abs() > ADJUSTMENT_THRESHOLD_DEG;
    ws.push(step(
        "9a",
        "neck adjustment: twist",
        Some(p.neck_twist_deg),
        if n_twist {
            "twisted: +1"
        } else {
            "not twisted: +0"
        },
        i32::from(n_twist),
    ));
    ws.push(step(
        "9b",
        "neck adjustment: side bend",
        Some(p.neck_side_bend_deg),
        if n_side {
            "side-bending: +1"
        } else {
            "not side-bending: +0"
        },
        i32::from(n_side),
    ));
    let neck = (nk0 + i32::from(n_twist) + i32::from(n_side)).clamp(1, 6);
    let tf = p.trunk_flexion_deg;
    let (tr0, rule) = if tf.abs() <= tol {
        (1, "upright")
    } else if tf <= 20.0 {
        (2, "0 to 20 deg flexion (or extension)")
    } else if tf <= 60.0 {
        (3, "20 to 60 deg flexion")
    } else {
        (4, "more than 60 deg flexion")
    };
    ws.push(step("10", "trunk position", Some(tf), rule, tr0));
    let twisted = p.trunk_twist_deg.abs() > ADJUSTMENT_THRESHOLD_DEG;
    let side = p.trunk_side_bend_deg.abs() > ADJUSTMENT_THRESHOLD_DEG;
    ws.push(step(
        "10a",
        "trunk adjustment: twist",
        Some(p.trunk_twist_deg),
        if twisted {
            "twisted: +1"
        } else {
            "not twisted: +0"
        },
        i32::from(twisted),
    ));
    ws.push(step(
        "10b",
        "trunk adjustment: side bend",
        Some(p.trunk_side_bend_deg),
        if side {
            "side-bending: +1"
        } else {
            "not side-bending: +0"
        },
        i32::from(side),
    ));
    let trunk = (tr0 + i32::from(twisted) + i32::from(side)).clamp(1, 6);
    let legs = if p.legs_supported { 1 } else { 2 };
    ws.push(step(
        "11",
        "legs",
        None,
        if p.legs_supported {
            "legs and feet supported, weight on both feet: 1"
        } else {
            "weight on one foot (the other carries less than 10 %): 2"
        },
        legs,
    ));
    let posture_b = TABLE_B[(neck - 1) as usize][((trunk - 1) * 2 + legs - 1) as usize] as i32;
    ws.push(step(
        "12",
        "posture score B (Table B)",
        None,
        format!("neck {neck}, trunk {trunk}, legs {legs}"),
        posture_b,
    ));
    ws.push(step(
        "13",
        "muscle use (neck, trunk, legs)",
        Some(a.repeats_per_min),
        muscle_rule,
        muscle,
    ));
    ws.push(step(
        "14",
        "force / load (neck, trunk, legs)",
        Some(a.load_kg),
        force_rule,
        force,
    ));
    let score_d = posture_b + muscle + force;
    ws.push(step(
        "14b",
        "neck, trunk and legs score D",
        None,
        "posture score B + muscle use + force",
        score_d,
    ));
    let grand_score =
        TABLE_C[(score_c.clamp(1, 8) - 1) as usize][(score_d.clamp(1, 7) - 1) as usize] as i32;
    let (action_level, action) = action_level(grand_score);
    ws.push(step(
        "15",
        "grand score (Table C)",
        None,
        format!("score C {score_c}, score D {score_d}: action level {action_level}, {action}"),
        grand_score,
    ));
    Rula {
        side: "right".into(),
        worksheet: ws,
        upper_arm,
        lower_arm,
        wrist,
        wrist_twist,
        posture_a,
        score_c,
        neck,
        trunk,
        legs,
        posture_b,
        score_d,
        grand_score,
        action_level,
        action,
        assumptions: ASSUMPTIONS.to_vec(),
    }
}

/// RULA of both arms of a measured posture; the worse grand score is kept (ties: the arm with
/// more load, `right_heavier` — else the right). Returns (the reported one, the other arm's).
pub fn score_body(b: &BodyAngles, a: &RulaActivity, right_heavier: bool) -> (Rula, Rula) {
    let mut r = score(&RulaPosture::from_angles(b, &b.right), a);
    let mut l = score(&RulaPosture::from_angles(b, &b.left), a);
    r.side = "right".into();
    l.side = "left".into();
    if l.grand_score > r.grand_score || (l.grand_score == r.grand_score && !right_heavier) {
        (l, r)
    } else {
        (r, l)
    }
}
