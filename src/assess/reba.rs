//! REBA — Rapid Entire Body Assessment (Hignett & McAtamney 2000).
//!
//! Source: S. Hignett, L. McAtamney, "Rapid Entire Body Assessment (REBA)",
//! *Applied Ergonomics* 31 (2000) 201–205, doi:10.1016/S0003-6870(99)00039-3.
//! Step numbers in the output follow the widely used one-page "REBA Employee
//! Assessment Worksheet" (Ergonomics Plus, "based on Technical note: Rapid
//! Entire Body Assessment (REBA), Hignett, McAtamney, Applied Ergonomics 31
//! (2000) 201-205"), which numbers the neck 1, trunk 2, legs 3, Table A 4,
//! load/force 5, Score A 6, upper arm 7, lower arm 8, wrist 9, Table B 10,
//! coupling 11, Score B 12 and activity 13. The Table C look-up (unnumbered
//! on the sheet) is reported as step `"C"` and the final score as `"REBA"`.
//!
//! # What this module does
//!
//! [`score`] takes joint angles already expressed the way REBA defines them
//! ([`RebaPosture`], [`RebaSide`]), the task factors ([`RebaActivity`]) and the
//! judgement thresholds that turn continuous angles into REBA's yes/no flags
//! ([`RebaThresholds`]), and returns a [`Reba`] holding every worksheet step as
//! a [`StepRow`] (measured values, the rule that applied, the score), for the
//! right and for the left arm, plus the combined result.
//!
//! # Scoring rules (as printed in the paper)
//!
//! | body part | band | score | change |
//! |---|---|---|---|
//! | trunk | upright | 1 | +1 if twisting or side flexed |
//! | | 0–20° flexion, 0–20° extension | 2 | |
//! | | 20–60° flexion, >20° extension | 3 | |
//! | | >60° flexion | 4 | |
//! | neck | 0–20° flexion | 1 | +1 if twisting or side flexed |
//! | | >20° flexion or in extension | 2 | |
//! | legs | bilateral weight bearing, walking or sitting | 1 | +1 if knee(s) 30–60° flexion |
//! | | unilateral / feather weight bearing / unstable | 2 | +2 if knee(s) >60° flexion (not for sitting) |
//! | load/force | <5 kg / 5–10 kg / >10 kg | 0 / 1 / 2 | +1 shock or rapid build-up of force |
//! | upper arm | 20° extension to 20° flexion | 1 | +1 abducted or rotated |
//! | | >20° extension, 20–45° flexion | 2 | +1 shoulder raised |
//! | | 45–90° flexion | 3 | −1 leaning, arm supported or gravity assisted |
//! | | >90° flexion | 4 | |
//! | lower arm | 60–100° flexion | 1 | |
//! | | <60° or >100° flexion | 2 | |
//! | wrist | 0–15° flexion/extension | 1 | +1 if deviated or twisted |
//! | | >15° flexion/extension | 2 | |
//! | coupling | good / fair / poor / unacceptable | 0 / 1 / 2 / 3 | |
//! | activity | static >1 min; repeated >4/min; rapid large changes or unstable base | +1 each | |
//!
//! Score A = Table A + load/force; Score B = Table B + coupling;
//! REBA = Table C(Score A, Score B) + activity (1–15).
//!
//! ## Boundary convention
//!
//! The paper prints closed ranges that share end points ("0–20°", "20–60°")
//! and strict ones ("<5 kg", ">60°"). This module places a value in the
//! printed band whose closed range contains it; where two printed bands share
//! an end point the *less severe* band applies; strict inequalities are
//! honoured as printed. Hence trunk 20° → 2, 60° → 3; neck 20° → 1; upper arm
//! 20° → 1, 45° → 2, 90° → 3; lower arm 60° and 100° → 1; wrist 15° → 1;
//! knee 30° and 60° → +1 (the printed "between 30 and 60°" is closed and no
//! band below 30° is printed); load 5 kg and 10 kg → 1 ("<5 kg" is strict).
//! Yes/no flags derived from angles ([`RebaThresholds`]) fire only when the
//! magnitude is strictly greater than the threshold.
//!
//! ## Single "+1" for twist *or* side bend
//!
//! The paper gives one "+1 if twisting or side flexed" for the trunk and the
//! neck (and one "+1 if abducted or rotated" for the upper arm). The worksheet
//! lists "twisted: +1" and "side bending: +1" on separate lines; adding both
//! would give trunk 6 or neck 4, which Table A does not have (trunk rows 1–5,
//! neck columns 1–3), so this module adds a single +1 when either applies.
//!
//! ## Left / right rule
//!
//! REBA scores one arm at a time and does not say how to combine them. The
//! authors' later chapter (Hignett & McAtamney, in Marras & Karwowski (eds),
//! *Fundamentals and Assessment Tools for Occupational Ergonomics*, 2006,
//! ch. 42) notes that "it is also possible to score both sides and then choose
//! the highest score". This module always scores both arms (group A is shared)
//! and reports the **worse (higher) final REBA score**, naming the side
//! ([`GoverningSide`]); on a tie it reports [`GoverningSide::Tie`]. Because
//! every row of Table C is non-decreasing in Score B, this equals the score
//! obtained by taking the larger Score B forward into Table C.
//!
//! ## Non-finite input
//!
//! [`score`] never panics. A NaN angle or load is scored as the worst band of
//! that item (and a NaN angle behind a yes/no flag sets the flag) and a
//! warning is recorded in [`Reba::warnings`]; ±∞ falls in the band it
//! compares into. [`try_score`] rejects non-finite input, negative loads and
//! invalid thresholds with a [`RebaError`] instead.
//!
//! ## Sources checked and discrepancies
//!
//! Tables A, B and C were checked cell by cell (`tests/suite/reba.rs`) against
//! the Ergonomics Plus worksheet, the INSHT (Spain) 2015 reprint of Table C
//! and two partial reprints; no published source disagreed on any cell.
//! Rule wording differs between the paper and the worksheet (load in lb,
//! twist and side bend listed as separate +1s, no "rotated"/"gravity
//! assisted" upper-arm items on the sheet); several open-source
//! transcriptions contain wrong cells. `reba.md` lists them.
//!
//! ## Known gaps of this input format
//!
//! * Sitting (`sitting`) exempts the knee adjustment: the paper marks the
//!   knee adjustment "not for sitting"; posture-opt reads it for the whole
//!   adjustment (a seated knee bend is the seat's, not a semi-squat).
//! * Upper-arm *rotation* (the paper's "abducted **or rotated**") is not an
//!   input; only abduction is scored.
//!
//! # How posture-opt computes the inputs (the generated worker, docs/body.md)
//!
//! World frame x forward, y left, z up; q = 0 is upright standing, arms
//! hanging, palms facing the thighs.
//!
//! * `trunk_flexion_deg` — angle of the trunk's long axis (pelvis → thorax)
//!   from world vertical, in the sagittal plane of the pelvis heading: for
//!   small `pelvis_list`, `pelvis_tilt + lumbar_flexion`. Side bend ≈
//!   `pelvis_list + lumbar_lateral_bending` (frontal-plane angle from
//!   vertical); twist = `lumbar_axial_rotation` (thorax relative to pelvis;
//!   `pelvis_rotation` is the whole-body heading, not a twist).
//! * `neck_*` — head relative to trunk: `neck_flexion`,
//!   `neck_lateral_bending`, `neck_axial_rotation`.
//! * `knee_flexion_deg` = max(`r_knee_flexion`, `l_knee_flexion`);
//!   `bilateral_weight_bearing` from the contact solution (both soles on the
//!   floor carrying load).
//! * Arms (per side, `r_*` / `l_*`; the left joints mirror the right ones so
//!   the same formulas apply): `upper_arm_flexion_deg` and
//!   `upper_arm_abduction_deg` are the humerus angles relative to the thorax
//!   (`*_shoulder_flexion`, `*_shoulder_abduction` for moderate elevation;
//!   see `reba.md` for the geometric definition), `elbow_flexion_deg` =
//!   `*_elbow_flexion`, `wrist_flexion_deg` = `*_wrist_flexion`,
//!   `wrist_deviated_or_twisted` from `*_wrist_deviation` and
//!   `*_forearm_pronation` via [`RebaThresholds::wrist_deviated_or_twisted`].
//!   `shoulder_raised` and `arm_supported_or_leaning` come from the task
//!   description (the worker has no shoulder-girdle joint).

#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing,
    clippy::unreachable,
    clippy::todo
)]

use serde::{Deserialize, Serialize};
use thiserror::Error;

// ---------------------------------------------------------------------------
// Inputs
// ---------------------------------------------------------------------------

/// One arm (group B) of a REBA posture, angles in degrees as REBA defines them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RebaSide {
    /// Upper-arm flexion relative to the trunk in the sagittal plane:
    /// + flexion (arm forward), − extension (arm behind the trunk).
    pub upper_arm_flexion_deg: f64,
    /// Upper-arm abduction relative to the trunk (arm raised sideways away
    /// from the body); negative values (adduction across the body) never
    /// count as abducted.
    pub upper_arm_abduction_deg: f64,
    /// The shoulder (shoulder girdle) is raised: +1.
    pub shoulder_raised: bool,
    /// The arm is supported, the person is leaning on it, or the posture is
    /// gravity assisted: −1.
    pub arm_supported_or_leaning: bool,
    /// Elbow flexion, 0 = straight arm.
    pub elbow_flexion_deg: f64,
    /// Wrist flexion (+) / extension (−).
    pub wrist_flexion_deg: f64,
    /// The wrist is deviated (radial/ulnar) or twisted: +1.
    pub wrist_deviated_or_twisted: bool,
}

/// A whole-body posture as REBA measures it, angles in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RebaPosture {
    /// Trunk flexion from vertical: + forward, − extension (leaning back).
    pub trunk_flexion_deg: f64,
    /// Trunk lateral bending (either direction; the magnitude is used).
    pub trunk_side_bend_deg: f64,
    /// Trunk axial twist relative to the pelvis (magnitude is used).
    pub trunk_twist_deg: f64,
    /// Neck (head relative to trunk) flexion: + forward, − extension.
    pub neck_flexion_deg: f64,
    /// Neck lateral bending (magnitude is used).
    pub neck_side_bend_deg: f64,
    /// Neck axial twist (magnitude is used).
    pub neck_twist_deg: f64,
    /// Both feet bear weight (bilateral weight bearing, walking or sitting).
    /// `false` means unilateral or feather weight bearing or an unstable
    /// posture.
    pub bilateral_weight_bearing: bool,
    /// Knee flexion, the larger of the two knees (0 = straight).
    pub knee_flexion_deg: f64,
    /// The worker sits: the paper exempts sitting from the knee adjustment (default false).
    #[serde(default)]
    pub sitting: bool,
    /// Right arm.
    pub right: RebaSide,
    /// Left arm.
    pub left: RebaSide,
}

/// Hand–load coupling (paper, coupling table).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Coupling {
    /// Well-fitting handle and a mid-range power grip: 0.
    Good,
    /// Hand hold acceptable but not ideal, or coupling acceptable via another
    /// part of the body: +1.
    Fair,
    /// Hand hold not acceptable although possible: +2.
    Poor,
    /// Awkward, unsafe grip, no handles; coupling unacceptable using other
    /// parts of the body: +3.
    Unacceptable,
}

impl Coupling {
    /// The coupling score (0–3).
    pub fn score(self) -> u8 {
        match self {
            Coupling::Good => 0,
            Coupling::Fair => 1,
            Coupling::Poor => 2,
            Coupling::Unacceptable => 3,
        }
    }

    /// The paper's description of this coupling category.
    pub fn description(self) -> &'static str {
        match self {
            Coupling::Good => "good: well fitting handle and a mid range power grip",
            Coupling::Fair => {
                "fair: hand hold acceptable but not ideal, or coupling acceptable via another part of the body"
            }
            Coupling::Poor => "poor: hand hold not acceptable although possible",
            Coupling::Unacceptable => {
                "unacceptable: awkward, unsafe grip, no handles; coupling unacceptable using other parts of the body"
            }
        }
    }

    fn name(self) -> &'static str {
        match self {
            Coupling::Good => "good",
            Coupling::Fair => "fair",
            Coupling::Poor => "poor",
            Coupling::Unacceptable => "unacceptable",
        }
    }
}

/// Task factors: load, coupling and activity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RebaActivity {
    /// Load or force handled, in kg.
    pub load_kg: f64,
    /// Shock or rapid build-up of force: +1 to the load/force score.
    pub shock_or_rapid_force: bool,
    /// Hand–load coupling (applies to both hands).
    pub coupling: Coupling,
    /// One or more body parts are static, e.g. held for longer than 1 min: +1.
    pub static_over_1_min: bool,
    /// Repeated small-range actions, e.g. more than 4 times per minute (not
    /// counting walking): +1.
    pub repeated_over_4_per_min: bool,
    /// Action causes rapid large-range changes in posture or an unstable
    /// base: +1.
    pub rapid_large_posture_change_or_unstable_base: bool,
}

/// Judgement thresholds applied to continuous angles where REBA only says
/// "yes/no" or "upright". All values are in degrees and must be finite and
/// non-negative ([`RebaThresholds::validate`]).
///
/// Defaults and their provenance (see `reba.md` for the discussion):
///
/// | field | default | provenance |
/// |---|---|---|
/// | `trunk_upright_tolerance_deg` | 5 | ASSUMPTION: measurement dead band around "upright" (the paper gives no number; open-source REBA tools use 5°) |
/// | `neck_extension_tolerance_deg` | 5 | ASSUMPTION: same dead band before neck extension counts as "in extension" |
/// | `trunk_side_bend_deg` | 10 | ISO 11226:2000 / EN 1005-4 neutral zone for trunk lateral flexion (±10°) |
/// | `trunk_twist_deg` | 10 | EN 1005-4-style "twisting clearly visible" limit of 10° |
/// | `neck_side_bend_deg` | 10 | ISO 11226:2000 / EN 1005-4 neutral zone for head/neck lateral bending (±10°) |
/// | `neck_twist_deg` | 10 | ASSUMPTION: same 10° as the other twist/side-bend flags |
/// | `upper_arm_abduction_deg` | 20 | ISO 11226:2000 / EN 1005-4: upper-arm elevation 0–20° acceptable without restriction |
/// | `wrist_deviation_deg` | 10 | ASSUMPTION: radial/ulnar deviation beyond 10° counts as "deviated" |
/// | `forearm_twist_deg` | 45 | ASSUMPTION: pronation/supination beyond mid-range (≈ half of an 80–90° range) counts as "twisted" |
///
/// The last two are used by [`RebaThresholds::wrist_deviated_or_twisted`],
/// the helper the product uses to fill [`RebaSide::wrist_deviated_or_twisted`].
///
/// When deserialised, missing fields take their default values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct RebaThresholds {
    /// |trunk flexion/extension| at or below this counts as "upright" (score 1).
    pub trunk_upright_tolerance_deg: f64,
    /// Neck extension of at most this many degrees is not yet "in extension"
    /// (it stays in the 0–20° band, score 1).
    pub neck_extension_tolerance_deg: f64,
    /// |trunk side bend| above this counts as "side flexed".
    pub trunk_side_bend_deg: f64,
    /// |trunk twist| above this counts as "twisting".
    pub trunk_twist_deg: f64,
    /// |neck side bend| above this counts as "side flexed".
    pub neck_side_bend_deg: f64,
    /// |neck twist| above this counts as "twisting".
    pub neck_twist_deg: f64,
    /// Upper-arm abduction above this counts as "abducted".
    pub upper_arm_abduction_deg: f64,
    /// |wrist radial/ulnar deviation| above this counts as "deviated".
    pub wrist_deviation_deg: f64,
    /// |forearm pronation/supination from mid position| above this counts as
    /// "twisted".
    pub forearm_twist_deg: f64,
}

impl Default for RebaThresholds {
    fn default() -> Self {
        RebaThresholds {
            trunk_upright_tolerance_deg: 5.0,
            neck_extension_tolerance_deg: 5.0,
            trunk_side_bend_deg: 10.0,
            trunk_twist_deg: 10.0,
            neck_side_bend_deg: 10.0,
            neck_twist_deg: 10.0,
            upper_arm_abduction_deg: 20.0,
            wrist_deviation_deg: 10.0,
            forearm_twist_deg: 45.0,
        }
    }
}

impl RebaThresholds {
    /// Checks that every threshold is finite and non-negative.
    pub fn validate(&self) -> Result<(), RebaError> {
        let fields = [
            (
                "trunk_upright_tolerance_deg",
                self.trunk_upright_tolerance_deg,
            ),
            (
                "neck_extension_tolerance_deg",
                self.neck_extension_tolerance_deg,
            ),
            ("trunk_side_bend_deg", self.trunk_side_bend_deg),
            ("trunk_twist_deg", self.trunk_twist_deg),
            ("neck_side_bend_deg", self.neck_side_bend_deg),
            ("neck_twist_deg", self.neck_twist_deg),
            ("upper_arm_abduction_deg", self.upper_arm_abduction_deg),
            ("wrist_deviation_deg", self.wrist_deviation_deg),
            ("forearm_twist_deg", self.forearm_twist_deg),
        ];
        for (field, value) in fields {
            if !value.is_finite() || value < 0.0 {
                return Err(RebaError::InvalidThreshold { field, value });
            }
        }
        Ok(())
    }

    /// The REBA wrist flag from the worker's joints: `true` when
    /// |`deviation_deg`| > `wrist_deviation_deg` or |`forearm_rotation_deg`|
    /// (pronation/supination from the mid position, thumbs forward) >
    /// `forearm_twist_deg`. A NaN input sets the flag (conservative).
    pub fn wrist_deviated_or_twisted(&self, deviation_deg: f64, forearm_rotation_deg: f64) -> bool {
        exceeds(deviation_deg, self.wrist_deviation_deg)
            || exceeds(forearm_rotation_deg, self.forearm_twist_deg)
    }
}

// ---------------------------------------------------------------------------
// Errors
// ---------------------------------------------------------------------------

/// Errors reported by the checked entry points ([`try_score`], the table
/// look-ups and [`RebaSubscores::evaluate`]). [`score`] itself never fails.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RebaError {
    /// An input angle or load is NaN or infinite.
    #[error("input `{field}` is not finite ({value})")]
    NonFinite {
        /// Name of the offending input.
        field: &'static str,
        /// The value received.
        value: f64,
    },
    /// The load is negative.
    #[error("load_kg must be >= 0, got {0}")]
    NegativeLoad(f64),
    /// A threshold is NaN, infinite or negative.
    #[error("threshold `{field}` must be finite and >= 0, got {value}")]
    InvalidThreshold {
        /// Name of the offending threshold.
        field: &'static str,
        /// The value received.
        value: f64,
    },
    /// A body-part or intermediate score is outside the range of its table.
    #[error("{what} = {value} is outside {min}..={max}")]
    ScoreOutOfRange {
        /// Which score.
        what: &'static str,
        /// The value received.
        value: u8,
        /// Smallest allowed value.
        min: u8,
        /// Largest allowed value.
        max: u8,
    },
}

// ---------------------------------------------------------------------------
// Tables (Hignett & McAtamney 2000, Tables A, B and C)
// ---------------------------------------------------------------------------

/// Table A, indexed `[trunk − 1][neck − 1][legs − 1]` (trunk 1–5, neck 1–3,
/// legs 1–4). Checked cell by cell against an independently typed copy of
/// the Ergonomics Plus worksheet in `tests/suite/reba.rs`.
pub const TABLE_A: [[[u8; 4]; 3]; 5] = [
    // trunk 1: neck 1, neck 2, neck 3 (each legs 1..4)
    [[1, 2, 3, 4], [1, 2, 3, 4], [3, 3, 5, 6]],
    // trunk 2
    [[2, 3, 4, 5], [3, 4, 5, 6], [4, 5, 6, 7]],
    // trunk 3
    [[2, 4, 5, 6], [4, 5, 6, 7], [5, 6, 7, 8]],
    // trunk 4
    [[3, 5, 6, 7], [5, 6, 7, 8], [6, 7, 8, 9]],
    // trunk 5
    [[4, 6, 7, 8], [6, 7, 8, 9], [7, 8, 9, 9]],
];

/// Table B, indexed `[upper arm − 1][lower arm − 1][wrist − 1]` (upper arm
/// 1–6, lower arm 1–2, wrist 1–3).
pub const TABLE_B: [[[u8; 3]; 2]; 6] = [
    // upper arm 1: lower arm 1, lower arm 2 (each wrist 1..3)
    [[1, 2, 2], [1, 2, 3]],
    [[1, 2, 3], [2, 3, 4]],
    [[3, 4, 5], [4, 5, 5]],
    [[4, 5, 5], [5, 6, 7]],
    [[6, 7, 8], [7, 8, 8]],
    [[7, 8, 8], [8, 9, 9]],
];

/// Table C, indexed `[Score A − 1][Score B − 1]` (both 1–12).
pub const TABLE_C: [[u8; 12]; 12] = [
    [1, 1, 1, 2, 3, 3, 4, 5, 6, 7, 7, 7],
    [1, 2, 2, 3, 4, 4, 5, 6, 6, 7, 7, 8],
    [2, 3, 3, 3, 4, 5, 6, 7, 7, 8, 8, 8],
    [3, 4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9],
    [4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9, 9],
    [6, 6, 6, 7, 8, 8, 9, 9, 10, 10, 10, 10],
    [7, 7, 7, 8, 9, 9, 9, 10, 10, 11, 11, 11],
    [8, 8, 8, 9, 10, 10, 10, 10, 10, 11, 11, 11],
    [9, 9, 9, 10, 10, 10, 11, 11, 11, 12, 12, 12],
    [10, 10, 10, 11, 11, 11, 11, 12, 12, 12, 12, 12],
    [11, 11, 11, 11, 12, 12, 12, 12, 12, 12, 12, 12],
    [12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12],
];

fn check_range(what: &'static str, value: u8, min: u8, max: u8) -> Result<usize, RebaError> {
    if (min..=max).contains(&value) {
        Ok(usize::from(value - min))
    } else {
        Err(RebaError::ScoreOutOfRange {
            what,
            value,
            min,
            max,
        })
    }
}

fn lookup_a(t: usize, n: usize, l: usize) -> Option<u8> {
    TABLE_A.get(t)?.get(n)?.get(l).copied()
}

fn lookup_b(u: usize, l: usize, w: usize) -> Option<u8> {
    TABLE_B.get(u)?.get(l)?.get(w).copied()
}

fn lookup_c(a: usize, b: usize) -> Option<u8> {
    TABLE_C.get(a)?.get(b).copied()
}

/// Table A look-up: trunk 1–5, neck 1–3, legs 1–4 → posture score A (1–9).
pub fn table_a(trunk: u8, neck: u8, legs: u8) -> Result<u8, RebaError> {
    let t = check_range("trunk score", trunk, 1, 5)?;
    let n = check_range("neck score", neck, 1, 3)?;
    let l = check_range("legs score", legs, 1, 4)?;
    // Indices were range-checked above; the fallback is unreachable.
    Ok(lookup_a(t, n, l).unwrap_or(9))
}

/// Table B look-up: upper arm 1–6, lower arm 1–2, wrist 1–3 → posture
/// score B (1–9).
pub fn table_b(upper_arm: u8, lower_arm: u8, wrist: u8) -> Result<u8, RebaError> {
    let u = check_range("upper arm score", upper_arm, 1, 6)?;
    let l = check_range("lower arm score", lower_arm, 1, 2)?;
    let w = check_range("wrist score", wrist, 1, 3)?;
    Ok(lookup_b(u, l, w).unwrap_or(9))
}

/// Table C look-up: Score A 1–12, Score B 1–12 → Table C score (1–12).
pub fn table_c(score_a: u8, score_b: u8) -> Result<u8, RebaError> {
    let a = check_range("score A", score_a, 1, 12)?;
    let b = check_range("score B", score_b, 1, 12)?;
    Ok(lookup_c(a, b).unwrap_or(12))
}

/// Zero-based index for a 1-based score, clamped to `len` entries.
fn idx(score: u8, len: usize) -> usize {
    usize::from(score.max(1) - 1).min(len.saturating_sub(1))
}

// The scorer only produces in-range sub-scores; clamping (and the worst-cell
// fallback) keeps the look-ups total so that `score` can never panic.
fn table_a_clamped(trunk: u8, neck: u8, legs: u8) -> u8 {
    lookup_a(idx(trunk, 5), idx(neck, 3), idx(legs, 4)).unwrap_or(9)
}

fn table_b_clamped(upper_arm: u8, lower_arm: u8, wrist: u8) -> u8 {
    lookup_b(idx(upper_arm, 6), idx(lower_arm, 2), idx(wrist, 3)).unwrap_or(9)
}

fn table_c_clamped(score_a: u8, score_b: u8) -> u8 {
    lookup_c(idx(score_a, 12), idx(score_b, 12)).unwrap_or(12)
}

// ---------------------------------------------------------------------------
// Risk / action levels (paper, action-level table)
// ---------------------------------------------------------------------------

/// REBA risk level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RiskLevel {
    /// REBA score 1.
    Negligible,
    /// REBA score 2–3.
    Low,
    /// REBA score 4–7.
    Medium,
    /// REBA score 8–10.
    High,
    /// REBA score 11–15.
    VeryHigh,
}

impl RiskLevel {
    /// Lower-case label as used in the paper ("negligible" … "very high").
    pub fn label(self) -> &'static str {
        match self {
            RiskLevel::Negligible => "negligible",
            RiskLevel::Low => "low",
            RiskLevel::Medium => "medium",
            RiskLevel::High => "high",
            RiskLevel::VeryHigh => "very high",
        }
    }
}

/// The paper's action-level row for a REBA score.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct RiskBand {
    /// Risk level.
    pub level: RiskLevel,
    /// Action level 0–4.
    pub action_level: u8,
    /// The REBA score range of this band, as printed.
    pub score_range: &'static str,
    /// Action (including further assessment), as printed in the paper.
    pub action: &'static str,
}

/// The risk band (paper's action-level table) for a final REBA score:
/// 1 negligible (action level 0, "None necessary"), 2–3 low (1, "May be
/// necessary"), 4–7 medium (2, "Necessary"), 8–10 high (3, "Necessary
/// soon"), 11–15 very high (4, "Necessary NOW"). Scores below 1 are treated
/// as 1 and scores above 15 as 15.
pub fn risk_band(reba_score: u8) -> RiskBand {
    match reba_score {
        0 | 1 => RiskBand {
            level: RiskLevel::Negligible,
            action_level: 0,
            score_range: "1",
            action: "None necessary",
        },
        2 | 3 => RiskBand {
            level: RiskLevel::Low,
            action_level: 1,
            score_range: "2-3",
            action: "May be necessary",
        },
        4..=7 => RiskBand {
            level: RiskLevel::Medium,
            action_level: 2,
            score_range: "4-7",
            action: "Necessary",
        },
        8..=10 => RiskBand {
            level: RiskLevel::High,
            action_level: 3,
            score_range: "8-10",
            action: "Necessary soon",
        },
        _ => RiskBand {
            level: RiskLevel::VeryHigh,
            action_level: 4,
            score_range: "11-15",
            action: "Necessary NOW",
        },
    }
}

// ---------------------------------------------------------------------------
// Output
// ---------------------------------------------------------------------------

/// Which arm a [`SideResult`] belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// Right arm.
    Right,
    /// Left arm.
    Left,
}

/// The side whose final REBA score is reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GoverningSide {
    /// The right arm gives the higher final score.
    Right,
    /// The left arm gives the higher final score.
    Left,
    /// Both arms give the same final score.
    Tie,
}

/// A measured or intermediate value shown on a worksheet row.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MeasuredValue {
    /// An angle in degrees.
    Degrees(f64),
    /// A mass in kilograms.
    Kilograms(f64),
    /// A yes/no input.
    Flag(bool),
    /// A score from an earlier step.
    Score(u8),
    /// A named category (e.g. the coupling class).
    Category(&'static str),
}

/// One named value on a worksheet row.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Measured {
    /// What the value is (e.g. `"trunk flexion"`).
    pub name: &'static str,
    /// The value.
    pub value: MeasuredValue,
}

/// One worksheet step: what was measured, which rule applied, the score.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepRow {
    /// Step number on the REBA Employee Assessment Worksheet (`"1"`–`"13"`),
    /// `"C"` for the Table C look-up and `"REBA"` for the final score.
    pub step: &'static str,
    /// Step name (e.g. `"Trunk"`).
    pub name: &'static str,
    /// Measured values or earlier scores that entered this step.
    pub measured: Vec<Measured>,
    /// The rule(s) that applied, in words.
    pub rule: String,
    /// The score of this step.
    pub score: u8,
}

/// Group A (trunk, neck, legs) and the load/force score; shared by both arms.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupAResult {
    /// Step 1: neck score (1–3).
    pub neck: StepRow,
    /// Step 2: trunk score (1–5).
    pub trunk: StepRow,
    /// Step 3: legs score (1–4), including the knee-flexion adjustment.
    pub legs: StepRow,
    /// Step 4: Table A posture score (1–9).
    pub table_a: StepRow,
    /// Step 5: load/force score (0–3).
    pub load_force: StepRow,
    /// Step 6: Score A = Table A + load/force (1–12).
    pub score_a: StepRow,
}

/// Group B and the final score for one arm.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SideResult {
    /// Which arm.
    pub side: Side,
    /// Step 7: upper-arm score (1–6).
    pub upper_arm: StepRow,
    /// Step 8: lower-arm score (1–2).
    pub lower_arm: StepRow,
    /// Step 9: wrist score (1–3).
    pub wrist: StepRow,
    /// Step 10: Table B posture score (1–9).
    pub table_b: StepRow,
    /// Step 11: coupling score (0–3).
    pub coupling: StepRow,
    /// Step 12: Score B = Table B + coupling (1–12).
    pub score_b: StepRow,
    /// Table C score from Score A and this arm's Score B (1–12).
    pub table_c: StepRow,
    /// Step 13: activity score (0–3).
    pub activity: StepRow,
    /// Final REBA score for this arm = Table C + activity (1–15).
    pub reba_score: StepRow,
    /// Risk band of this arm's final score.
    pub risk: RiskBand,
}

/// The full REBA assessment of one posture.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reba {
    /// Group A steps (1–6), shared by both arms.
    pub group_a: GroupAResult,
    /// Right-arm steps (7–13, Table C, final).
    pub right: SideResult,
    /// Left-arm steps (7–13, Table C, final).
    pub left: SideResult,
    /// The side whose score is reported (higher final score; `Tie` if equal).
    pub governing_side: GoverningSide,
    /// The reported REBA score: the higher of the two arms' final scores.
    pub reba_score: u8,
    /// Risk level and action level of the reported score.
    pub risk: RiskBand,
    /// The rule used to combine the two arms, in words.
    pub side_rule: &'static str,
    /// The thresholds that were applied.
    pub thresholds: RebaThresholds,
    /// Input problems that were handled conservatively (NaN, implausible
    /// magnitudes, negative load). Empty for ordinary input.
    pub warnings: Vec<String>,
}

impl Reba {
    /// The result of the governing side (the right arm on a tie).
    pub fn governing(&self) -> &SideResult {
        match self.governing_side {
            GoverningSide::Left => &self.left,
            GoverningSide::Right | GoverningSide::Tie => &self.right,
        }
    }

    /// All worksheet rows of one side in worksheet order: group A steps
    /// 1–6, then that arm's steps 7–12, Table C, 13 and the final score.
    pub fn rows(&self, side: Side) -> Vec<&StepRow> {
        let g = &self.group_a;
        let s = match side {
            Side::Right => &self.right,
            Side::Left => &self.left,
        };
        vec![
            &g.neck,
            &g.trunk,
            &g.legs,
            &g.table_a,
            &g.load_force,
            &g.score_a,
            &s.upper_arm,
            &s.lower_arm,
            &s.wrist,
            &s.table_b,
            &s.coupling,
            &s.score_b,
            &s.table_c,
            &s.activity,
            &s.reba_score,
        ]
    }
}

/// The combination rule reported in [`Reba::side_rule`].
pub const SIDE_RULE: &str = "Both arms are scored with the shared group A; the reported REBA score is \
     the higher of the two final scores and its side is named (tie if equal). REBA itself scores one \
     side at a time; Hignett & McAtamney (2006) note both sides may be scored and the highest taken.";

// ---------------------------------------------------------------------------
// Sub-score entry point (for assessments scored by an observer)
// ---------------------------------------------------------------------------

/// Body-part scores as an observer writes them on the worksheet, for
/// combining through Tables A, B and C without angles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct RebaSubscores {
    /// Trunk score 1–5 (with its adjustment).
    pub trunk: u8,
    /// Neck score 1–3 (with its adjustment).
    pub neck: u8,
    /// Legs score 1–4 (with the knee adjustment).
    pub legs: u8,
    /// Load/force score 0–3.
    pub load_force: u8,
    /// Upper-arm score 1–6 (with its adjustments).
    pub upper_arm: u8,
    /// Lower-arm score 1–2.
    pub lower_arm: u8,
    /// Wrist score 1–3 (with its adjustment).
    pub wrist: u8,
    /// Coupling score 0–3.
    pub coupling: u8,
    /// Activity score 0–3.
    pub activity: u8,
}

/// Result of [`RebaSubscores::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct SubscoreResult {
    /// Table A posture score.
    pub table_a: u8,
    /// Score A = Table A + load/force.
    pub score_a: u8,
    /// Table B posture score.
    pub table_b: u8,
    /// Score B = Table B + coupling.
    pub score_b: u8,
    /// Table C score.
    pub table_c: u8,
    /// Final REBA score = Table C + activity.
    pub reba_score: u8,
    /// Risk band of the final score.
    pub risk: RiskBand,
}

impl RebaSubscores {
    /// Runs the body-part scores through Tables A, B and C.
    pub fn evaluate(&self) -> Result<SubscoreResult, RebaError> {
        check_range("load/force score", self.load_force, 0, 3)?;
        check_range("coupling score", self.coupling, 0, 3)?;
        check_range("activity score", self.activity, 0, 3)?;
        let ta = table_a(self.trunk, self.neck, self.legs)?;
        let tb = table_b(self.upper_arm, self.lower_arm, self.wrist)?;
        let score_a = ta + self.load_force;
        let score_b = tb + self.coupling;
        let tc = table_c(score_a, score_b)?;
        let reba_score = tc + self.activity;
        Ok(SubscoreResult {
            table_a: ta,
            score_a,
            table_b: tb,
            score_b,
            table_c: tc,
            reba_score,
            risk: risk_band(reba_score),
        })
    }
}

// ---------------------------------------------------------------------------
// Scoring
// ---------------------------------------------------------------------------

/// `|value| > threshold`, with NaN counting as exceeding (conservative).
fn exceeds(value: f64, threshold: f64) -> bool {
    value.is_nan() || value.abs() > threshold
}

fn deg(name: &'static str, v: f64) -> Measured {
    Measured {
        name,
        value: MeasuredValue::Degrees(v),
    }
}

fn flag(name: &'static str, v: bool) -> Measured {
    Measured {
        name,
        value: MeasuredValue::Flag(v),
    }
}

fn sc(name: &'static str, v: u8) -> Measured {
    Measured {
        name,
        value: MeasuredValue::Score(v),
    }
}

/// Collects warnings about suspicious input.
struct Warnings(Vec<String>);

impl Warnings {
    fn angle(&mut self, field: &str, v: f64) {
        if v.is_nan() {
            self.0.push(format!(
                "{field} is NaN: scored in the worst band / flag set"
            ));
        } else if v.abs() > 180.0 {
            self.0.push(format!(
                "{field} = {v} deg is outside +/-180 deg; scored as given"
            ));
        }
    }
}

/// "+1 if twisting or side flexed" for trunk or neck.
fn twist_or_side(side_bend: f64, side_thr: f64, twist: f64, twist_thr: f64) -> (bool, String) {
    let s = exceeds(side_bend, side_thr);
    let t = exceeds(twist, twist_thr);
    let text = format!(
        "side bend |{:.1}| {} {:.1} deg, twist |{:.1}| {} {:.1} deg",
        side_bend.abs(),
        if s { ">" } else { "<=" },
        side_thr,
        twist.abs(),
        if t { ">" } else { "<=" },
        twist_thr
    );
    (s || t, text)
}

fn trunk_step(p: &RebaPosture, t: &RebaThresholds) -> StepRow {
    let f = p.trunk_flexion_deg;
    let tol = t.trunk_upright_tolerance_deg;
    let (base, band) = if f.is_nan() {
        (4, "NaN flexion: worst band (>60 deg flexion)".to_string())
    } else if f.abs() <= tol {
        (1, format!("upright (|flexion| <= {tol:.1} deg tolerance)"))
    } else if (0.0..=20.0).contains(&f) {
        (2, "0-20 deg flexion".to_string())
    } else if (-20.0..0.0).contains(&f) {
        (2, "0-20 deg extension".to_string())
    } else if f > 20.0 && f <= 60.0 {
        (3, "20-60 deg flexion".to_string())
    } else if f < -20.0 {
        (3, ">20 deg extension".to_string())
    } else {
        (4, ">60 deg flexion".to_string())
    };
    let (adj, adj_text) = twist_or_side(
        p.trunk_side_bend_deg,
        t.trunk_side_bend_deg,
        p.trunk_twist_deg,
        t.trunk_twist_deg,
    );
    let score = base + u8::from(adj);
    StepRow {
        step: "2",
        name: "Trunk",
        measured: vec![
            deg("trunk flexion", f),
            deg("trunk side bend", p.trunk_side_bend_deg),
            deg("trunk twist", p.trunk_twist_deg),
        ],
        rule: format!(
            "{band} -> {base}; {adj_text} -> {}; trunk score {score}",
            if adj {
                "+1 (twisting or side flexed)"
            } else {
                "+0"
            }
        ),
        score,
    }
}

fn neck_step(p: &RebaPosture, t: &RebaThresholds) -> StepRow {
    let f = p.neck_flexion_deg;
    let tol = t.neck_extension_tolerance_deg;
    let (base, band) = if f.is_nan() {
        (
            2,
            "NaN flexion: worst band (>20 deg flexion or extension)".to_string(),
        )
    } else if f > 20.0 {
        (2, ">20 deg flexion".to_string())
    } else if f >= 0.0 {
        (1, "0-20 deg flexion".to_string())
    } else if f >= -tol {
        (
            1,
            format!("extension within {tol:.1} deg tolerance: 0-20 deg band"),
        )
    } else {
        (2, "in extension".to_string())
    };
    let (adj, adj_text) = twist_or_side(
        p.neck_side_bend_deg,
        t.neck_side_bend_deg,
        p.neck_twist_deg,
        t.neck_twist_deg,
    );
    let score = base + u8::from(adj);
    StepRow {
        step: "1",
        name: "Neck",
        measured: vec![
            deg("neck flexion", f),
            deg("neck side bend", p.neck_side_bend_deg),
            deg("neck twist", p.neck_twist_deg),
        ],
        rule: format!(
            "{band} -> {base}; {adj_text} -> {}; neck score {score}",
            if adj {
                "+1 (twisting or side flexed)"
            } else {
                "+0"
            }
        ),
        score,
    }
}

fn legs_step(p: &RebaPosture) -> StepRow {
    let (base, band) = if p.bilateral_weight_bearing {
        (1, "bilateral weight bearing, walking or sitting -> 1")
    } else {
        (
            2,
            "unilateral weight bearing, feather weight bearing or unstable posture -> 2",
        )
    };
    let k = p.knee_flexion_deg;
    let (adj, knee) = if p.sitting {
        (0, "sitting: no knee adjustment -> +0")
    } else if k.is_nan() {
        (2, "NaN knee flexion: worst adjustment +2")
    } else if k > 60.0 {
        (2, "knee(s) >60 deg flexion -> +2")
    } else if k >= 30.0 {
        (1, "knee(s) 30-60 deg flexion -> +1")
    } else {
        (0, "knee(s) <30 deg flexion -> +0")
    };
    let score = base + adj;
    StepRow {
        step: "3",
        name: "Legs",
        measured: vec![
            flag("bilateral weight bearing", p.bilateral_weight_bearing),
            flag("sitting", p.sitting),
            deg("knee flexion (larger knee)", k),
        ],
        rule: format!("{band}; {knee}; legs score {score}"),
        score,
    }
}

fn load_step(a: &RebaActivity) -> StepRow {
    let kg = a.load_kg;
    let (base, band) = if kg.is_nan() {
        (2, "NaN load: worst band (>10 kg)")
    } else if kg > 10.0 {
        (2, ">10 kg -> 2")
    } else if kg >= 5.0 {
        (1, "5-10 kg -> 1")
    } else {
        (0, "<5 kg -> 0")
    };
    let score = base + u8::from(a.shock_or_rapid_force);
    StepRow {
        step: "5",
        name: "Load/force",
        measured: vec![
            Measured {
                name: "load",
                value: MeasuredValue::Kilograms(kg),
            },
            flag("shock or rapid build-up of force", a.shock_or_rapid_force),
        ],
        rule: format!(
            "{band}; {}; load/force score {score}",
            if a.shock_or_rapid_force {
                "shock or rapid build-up of force +1"
            } else {
                "no shock +0"
            }
        ),
        score,
    }
}

fn upper_arm_step(s: &RebaSide, t: &RebaThresholds) -> StepRow {
    let f = s.upper_arm_flexion_deg;
    let (base, band): (u8, &str) = if f.is_nan() {
        (4, "NaN flexion: worst band (>90 deg flexion)")
    } else if f > 90.0 {
        (4, ">90 deg flexion")
    } else if f > 45.0 {
        (3, "45-90 deg flexion")
    } else if f > 20.0 {
        (2, "20-45 deg flexion")
    } else if f >= -20.0 {
        (1, "20 deg extension to 20 deg flexion")
    } else {
        (2, ">20 deg extension")
    };
    let abd = s.upper_arm_abduction_deg;
    let abducted = abd.is_nan() || abd > t.upper_arm_abduction_deg;
    let raw = i16::from(base) + i16::from(abducted) + i16::from(s.shoulder_raised)
        - i16::from(s.arm_supported_or_leaning);
    let clamped = raw.clamp(1, 6);
    let score = u8::try_from(clamped).unwrap_or(1);
    let clamp_note = if raw != clamped {
        format!(" (clamped from {raw})")
    } else {
        String::new()
    };
    StepRow {
        step: "7",
        name: "Upper arm",
        measured: vec![
            deg("upper arm flexion", f),
            deg("upper arm abduction", abd),
            flag("shoulder raised", s.shoulder_raised),
            flag(
                "arm supported / leaning / gravity assisted",
                s.arm_supported_or_leaning,
            ),
        ],
        rule: format!(
            "{band} -> {base}; abduction {:.1} {} {:.1} deg -> {}; shoulder raised -> {}; supported/leaning -> {}; upper arm score {score}{clamp_note}",
            abd,
            if abducted { ">" } else { "<=" },
            t.upper_arm_abduction_deg,
            if abducted { "+1" } else { "+0" },
            if s.shoulder_raised { "+1" } else { "+0" },
            if s.arm_supported_or_leaning {
                "-1"
            } else {
                "+0"
            },
        ),
        score,
    }
}

fn lower_arm_step(s: &RebaSide) -> StepRow {
    let e = s.elbow_flexion_deg;
    let (score, band) = if e.is_nan() {
        (2, "NaN elbow flexion: worst band -> 2")
    } else if (60.0..=100.0).contains(&e) {
        (1, "60-100 deg flexion -> 1")
    } else {
        (2, "<60 deg or >100 deg flexion -> 2")
    };
    StepRow {
        step: "8",
        name: "Lower arm",
        measured: vec![deg("elbow flexion", e)],
        rule: format!("{band}; lower arm score {score}"),
        score,
    }
}

fn wrist_step(s: &RebaSide) -> StepRow {
    let w = s.wrist_flexion_deg;
    let (base, band) = if w.is_nan() {
        (2, "NaN wrist flexion: worst band (>15 deg)")
    } else if w.abs() <= 15.0 {
        (1, "0-15 deg flexion/extension")
    } else {
        (2, ">15 deg flexion/extension")
    };
    let score = base + u8::from(s.wrist_deviated_or_twisted);
    StepRow {
        step: "9",
        name: "Wrist",
        measured: vec![
            deg("wrist flexion", w),
            flag("wrist deviated or twisted", s.wrist_deviated_or_twisted),
        ],
        rule: format!(
            "{band} -> {base}; deviated or twisted -> {}; wrist score {score}",
            if s.wrist_deviated_or_twisted {
                "+1"
            } else {
                "+0"
            }
        ),
        score,
    }
}

fn activity_step(a: &RebaActivity) -> StepRow {
    let score = u8::from(a.static_over_1_min)
        + u8::from(a.repeated_over_4_per_min)
        + u8::from(a.rapid_large_posture_change_or_unstable_base);
    let mut parts = Vec::new();
    if a.static_over_1_min {
        parts.push("one or more body parts static (held >1 min) +1");
    }
    if a.repeated_over_4_per_min {
        parts.push("repeated small range actions (>4/min) +1");
    }
    if a.rapid_large_posture_change_or_unstable_base {
        parts.push("rapid large range changes in posture or unstable base +1");
    }
    let rule = if parts.is_empty() {
        "no activity factor applies -> 0".to_string()
    } else {
        format!("{}; activity score {score}", parts.join("; "))
    };
    StepRow {
        step: "13",
        name: "Activity",
        measured: vec![
            flag("static >1 min", a.static_over_1_min),
            flag("repeated >4/min", a.repeated_over_4_per_min),
            flag(
                "rapid large posture change or unstable base",
                a.rapid_large_posture_change_or_unstable_base,
            ),
        ],
        rule,
        score,
    }
}

fn side_result(
    side: Side,
    s: &RebaSide,
    score_a: u8,
    a: &RebaActivity,
    t: &RebaThresholds,
) -> SideResult {
    let upper_arm = upper_arm_step(s, t);
    let lower_arm = lower_arm_step(s);
    let wrist = wrist_step(s);
    let tb = table_b_clamped(upper_arm.score, lower_arm.score, wrist.score);
    let table_b = StepRow {
        step: "10",
        name: "Table B",
        measured: vec![
            sc("upper arm score", upper_arm.score),
            sc("lower arm score", lower_arm.score),
            sc("wrist score", wrist.score),
        ],
        rule: format!(
            "Table B[upper arm {}][lower arm {}][wrist {}] = {tb}",
            upper_arm.score, lower_arm.score, wrist.score
        ),
        score: tb,
    };
    let c = a.coupling.score();
    let coupling = StepRow {
        step: "11",
        name: "Coupling",
        measured: vec![Measured {
            name: "coupling",
            value: MeasuredValue::Category(a.coupling.name()),
        }],
        rule: format!("{} -> +{c}", a.coupling.description()),
        score: c,
    };
    let sb = tb + c;
    let score_b = StepRow {
        step: "12",
        name: "Score B",
        measured: vec![sc("Table B", tb), sc("coupling", c)],
        rule: format!("Table B {tb} + coupling {c} = {sb}"),
        score: sb,
    };
    let tc = table_c_clamped(score_a, sb);
    let table_c = StepRow {
        step: "C",
        name: "Table C",
        measured: vec![sc("Score A", score_a), sc("Score B", sb)],
        rule: format!("Table C[Score A {score_a}][Score B {sb}] = {tc}"),
        score: tc,
    };
    let activity = activity_step(a);
    let fin = tc + activity.score;
    let risk = risk_band(fin);
    let reba_score = StepRow {
        step: "REBA",
        name: "REBA score",
        measured: vec![sc("Table C", tc), sc("activity", activity.score)],
        rule: format!(
            "Table C {tc} + activity {} = {fin}: {} risk, action level {} ({})",
            activity.score,
            risk.level.label(),
            risk.action_level,
            risk.action
        ),
        score: fin,
    };
    SideResult {
        side,
        upper_arm,
        lower_arm,
        wrist,
        table_b,
        coupling,
        score_b,
        table_c,
        activity,
        reba_score,
        risk,
    }
}

fn collect_warnings(p: &RebaPosture, a: &RebaActivity, t: &RebaThresholds) -> Vec<String> {
    let mut w = Warnings(Vec::new());
    w.angle("trunk_flexion_deg", p.trunk_flexion_deg);
    w.angle("trunk_side_bend_deg", p.trunk_side_bend_deg);
    w.angle("trunk_twist_deg", p.trunk_twist_deg);
    w.angle("neck_flexion_deg", p.neck_flexion_deg);
    w.angle("neck_side_bend_deg", p.neck_side_bend_deg);
    w.angle("neck_twist_deg", p.neck_twist_deg);
    w.angle("knee_flexion_deg", p.knee_flexion_deg);
    for (name, s) in [("right", &p.right), ("left", &p.left)] {
        w.angle(
            &format!("{name}.upper_arm_flexion_deg"),
            s.upper_arm_flexion_deg,
        );
        w.angle(
            &format!("{name}.upper_arm_abduction_deg"),
            s.upper_arm_abduction_deg,
        );
        w.angle(&format!("{name}.elbow_flexion_deg"), s.elbow_flexion_deg);
        w.angle(&format!("{name}.wrist_flexion_deg"), s.wrist_flexion_deg);
    }
    if a.load_kg.is_nan() {
        w.0.push("load_kg is NaN: scored as >10 kg".to_string());
    } else if a.load_kg < 0.0 {
        w.0.push(format!(
            "load_kg = {} is negative: scored as <5 kg",
            a.load_kg
        ));
    }
    if let Err(e) = t.validate() {
        w.0.push(format!("{e}; comparisons use the value as given"));
    }
    w.0
}

/// Scores a posture with REBA for both arms and combines them (see the
/// module documentation for the rules, the boundary convention and the
/// left/right rule). Never panics; see [`try_score`] for a checked version.
pub fn score(p: &RebaPosture, a: &RebaActivity, thresholds: &RebaThresholds) -> Reba {
    let t = thresholds;
    let warnings = collect_warnings(p, a, t);

    let neck = neck_step(p, t);
    let trunk = trunk_step(p, t);
    let legs = legs_step(p);
    let ta = table_a_clamped(trunk.score, neck.score, legs.score);
    let table_a = StepRow {
        step: "4",
        name: "Table A",
        measured: vec![
            sc("trunk score", trunk.score),
            sc("neck score", neck.score),
            sc("legs score", legs.score),
        ],
        rule: format!(
            "Table A[trunk {}][neck {}][legs {}] = {ta}",
            trunk.score, neck.score, legs.score
        ),
        score: ta,
    };
    let load_force = load_step(a);
    let sa = ta + load_force.score;
    let score_a = StepRow {
        step: "6",
        name: "Score A",
        measured: vec![sc("Table A", ta), sc("load/force", load_force.score)],
        rule: format!("Table A {ta} + load/force {} = {sa}", load_force.score),
        score: sa,
    };

    let right = side_result(Side::Right, &p.right, sa, a, t);
    let left = side_result(Side::Left, &p.left, sa, a, t);
    let (r, l) = (right.reba_score.score, left.reba_score.score);
    let governing_side = match r.cmp(&l) {
        std::cmp::Ordering::Greater => GoverningSide::Right,
        std::cmp::Ordering::Less => GoverningSide::Left,
        std::cmp::Ordering::Equal => GoverningSide::Tie,
    };
    let reba_score = r.max(l);

    Reba {
        group_a: GroupAResult {
            neck,
            trunk,
            legs,
            table_a,
            load_force,
            score_a,
        },
        right,
        left,
        governing_side,
        reba_score,
        risk: risk_band(reba_score),
        side_rule: SIDE_RULE,
        thresholds: *t,
        warnings,
    }
}

/// Like [`score`], but rejects non-finite angles or loads, negative loads
/// and invalid thresholds.
pub fn try_score(
    p: &RebaPosture,
    a: &RebaActivity,
    thresholds: &RebaThresholds,
) -> Result<Reba, RebaError> {
    thresholds.validate()?;
    let mut fields: Vec<(&'static str, f64)> = vec![
        ("trunk_flexion_deg", p.trunk_flexion_deg),
        ("trunk_side_bend_deg", p.trunk_side_bend_deg),
        ("trunk_twist_deg", p.trunk_twist_deg),
        ("neck_flexion_deg", p.neck_flexion_deg),
        ("neck_side_bend_deg", p.neck_side_bend_deg),
        ("neck_twist_deg", p.neck_twist_deg),
        ("knee_flexion_deg", p.knee_flexion_deg),
        ("load_kg", a.load_kg),
    ];
    for (prefix, s) in [
        (
            [
                "right.upper_arm_flexion_deg",
                "right.upper_arm_abduction_deg",
                "right.elbow_flexion_deg",
                "right.wrist_flexion_deg",
            ],
            &p.right,
        ),
        (
            [
                "left.upper_arm_flexion_deg",
                "left.upper_arm_abduction_deg",
                "left.elbow_flexion_deg",
                "left.wrist_flexion_deg",
            ],
            &p.left,
        ),
    ] {
        fields.push((prefix[0], s.upper_arm_flexion_deg));
        fields.push((prefix[1], s.upper_arm_abduction_deg));
        fields.push((prefix[2], s.elbow_flexion_deg));
        fields.push((prefix[3], s.wrist_flexion_deg));
    }
    for (field, value) in fields {
        if !value.is_finite() {
            return Err(RebaError::NonFinite { field, value });
        }
    }
    if a.load_kg < 0.0 {
        return Err(RebaError::NegativeLoad(a.load_kg));
    }
    Ok(score(p, a, thresholds))
}
