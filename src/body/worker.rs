//! The generated default worker: a standing upper body from a worker description, as URDF.
//!
//! Segment masses and centre-of-mass positions: de Leva (1996), J Biomech 29:1223, Table 4
//! (Zatsiorsky–Seluyanov adjusted), CM measured from the proximal endpoint listed there.
//! Segment lengths: de Leva's reference lengths scaled by stature / reference stature (male
//! 1.741 m, female 1.735 m). Heights of the lumbar joint, the shoulders and the head are fractions
//! of stature after Drillis & Contini (1966) — ASSUMPTIONS where marked, not measurements.
//!
//! Frames (world at the floor between the feet): x forward, y left, z up. At q = 0 the worker
//! stands upright, the right arm hangs with the palm facing the thigh (thumb forward).
//! Joint signs (positive direction):
//! * `lumbar_flexion` bends the trunk forward; `lumbar_lateral_bending` to the left;
//!   `lumbar_axial_rotation` turns the trunk to the left;
//! * `r_shoulder_flexion` raises the arm forward; `r_shoulder_abduction` sideways (to the
//!   right); `r_shoulder_rotation` is internal rotation;
//! * `r_elbow_flexion` flexes; `r_forearm_pronation` pronates;
//! * `r_wrist_flexion` flexes toward the palm; `r_wrist_deviation` is radial deviation.

use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// Sex of a worker, for anthropometry and strength.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Sex {
    Male,
    Female,
}

impl Sex {
    /// "male" or "female", as in task files.
    pub fn name(self) -> &'static str {
        match self {
            Sex::Male => "male",
            Sex::Female => "female",
        }
    }
}

/// A worker description.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Worker {
    pub sex: Sex,
    pub stature_m: f64,
    pub mass_kg: f64,
    /// Strength percentile (1–99) of the worker's sex; 50 by default.
    #[serde(default = "default_percentile")]
    pub strength_percentile: f64,
}

fn default_percentile() -> f64 {
    50.0
}

/// Why a worker description was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WorkerError {
    #[error("stature_m must be between 1.2 and 2.3 m, got {0}")]
    Stature(f64),
    #[error("mass_kg must be between 30 and 200 kg, got {0}")]
    Mass(f64),
    #[error("strength_percentile must be between 1 and 99, got {0}")]
    Percentile(f64),
}

impl Worker {
    /// The 50th-percentile man: stature 1.755 m, body mass 78 kg (ASSUMPTION: values close to
    /// adult male anthropometric surveys, e.g. ANSUR II means, not a specific dataset).
    pub const MALE_50: Worker = Worker {
        sex: Sex::Male,
        stature_m: 1.755,
        mass_kg: 78.0,
        strength_percentile: 50.0,
    };

    /// Checks the ranges.
    pub fn validate(&self) -> Result<(), WorkerError> {
        if !(self.stature_m.is_finite() && (1.2..=2.3).contains(&self.stature_m)) {
            return Err(WorkerError::Stature(self.stature_m));
        }
        if !(self.mass_kg.is_finite() && (30.0..=200.0).contains(&self.mass_kg)) {
            return Err(WorkerError::Mass(self.mass_kg));
        }
        if !(self.strength_percentile.is_finite()
            && (1.0..=99.0).contains(&self.strength_percentile))
        {
            return Err(WorkerError::Percentile(self.strength_percentile));
        }
        Ok(())
    }
}

/// de Leva (1996) Table 4 values for one sex: mass fraction and CM (fraction of length from the
/// proximal endpoint); lengths \[m\] of the reference subject.
struct DeLeva {
    ref_stature_m: f64,
    upper_arm: (f64, f64, f64),
    forearm: (f64, f64, f64),
    hand: (f64, f64, f64),
    /// Torso SUPR–MIDA: mass fraction, CM from SUPR.
    torso: (f64, f64),
    /// Pelvis MIDA–MIDH.
    pelvis: (f64, f64),
    /// Head VERT–MIDG: mass fraction, CM from vertex.
    head: (f64, f64),
}

const DE_LEVA_MALE: DeLeva = DeLeva {
    ref_stature_m: 1.741,
    upper_arm: (0.0271, 0.5772, 0.2817),
    forearm: (0.0162, 0.4574, 0.2689),
    hand: (0.0061, 0.7900, 0.0862),
    torso: (0.3229, 0.4166),
    pelvis: (0.1117, 0.50),
    head: (0.0694, 0.5976),
};

const DE_LEVA_FEMALE: DeLeva = DeLeva {
    ref_stature_m: 1.735,
    upper_arm: (0.0255, 0.5754, 0.2751),
    forearm: (0.0138, 0.4559, 0.2643),
    hand: (0.0056, 0.7474, 0.0780),
    #[allow(clippy::approx_constant)] // de Leva female torso mass fraction, not log10(2)
    torso: (0.3010, 0.3741),
    pelvis: (0.1247, 0.50),
    head: (0.0668, 0.5894),
};

/// Heights and widths as fractions of stature (ASSUMPTIONS after Drillis & Contini 1966).
mod proportions {
    /// Lumbosacral joint (≈ mid-ASIS level).
    pub const LUMBAR_Z: f64 = 0.56;
    /// Suprasternale.
    pub const SUPRASTERNALE_Z: f64 = 0.81;
    /// Shoulder joint centres.
    pub const SHOULDER_Z: f64 = 0.80;
    pub const SHOULDER_HALF_WIDTH: f64 = 0.105;
    /// Head: vertex at 1.0, mid-gonion at 0.87.
    pub const HEAD_LENGTH: f64 = 0.13;
    /// Grip centre along the hand, fraction of wrist–MET3 length.
    pub const GRIP_ALONG_HAND: f64 = 0.75;
}

/// Capsule radii for a 1.755 m worker \[m\], scaled by stature (ASSUMPTIONS, for clearance only).
const RADIUS_TRUNK: f64 = 0.13;
const RADIUS_UPPER_ARM: f64 = 0.045;
const RADIUS_FOREARM: f64 = 0.038;
const RADIUS_HAND: f64 = 0.03;
const RADIUS_HEAD: f64 = 0.10;

/// Range of motion \[rad\] (ASSUMPTIONS: typical active ranges, AAOS-style tables).
const LIMITS: [(&str, f64, f64); 10] = [
    ("lumbar_flexion", -0.35, 1.4),
    ("lumbar_lateral_bending", -0.5, 0.5),
    ("lumbar_axial_rotation", -0.6, 0.6),
    ("r_shoulder_flexion", -0.85, 3.0),
    ("r_shoulder_abduction", -0.5, 2.6),
    ("r_shoulder_rotation", -1.2, 1.4),
    ("r_elbow_flexion", 0.0, 2.5),
    ("r_forearm_pronation", -1.4, 1.4),
    ("r_wrist_flexion", -1.2, 1.3),
    ("r_wrist_deviation", -0.5, 0.35),
];

/// Moving joints of the default worker, in chain order.
pub const JOINTS: [&str; 10] = [
    "lumbar_flexion",
    "lumbar_lateral_bending",
    "lumbar_axial_rotation",
    "r_shoulder_flexion",
    "r_shoulder_abduction",
    "r_shoulder_rotation",
    "r_elbow_flexion",
    "r_forearm_pronation",
    "r_wrist_flexion",
    "r_wrist_deviation",
];

fn limit(name: &str) -> (f64, f64) {
    LIMITS
        .iter()
        .find(|l| l.0 == name)
        .map(|l| (l.1, l.2))
        .expect("every worker joint has limits")
}

struct Urdf(String);

impl Urdf {
    fn link(
        &mut self,
        name: &str,
        mass: f64,
        com: [f64; 3],
        capsule: Option<(f64, f64, [f64; 3])>,
    ) {
        let _ = writeln!(self.0, "  <link name=\"{name}\">");
        if mass > 0.0 {
            // Inertia does not enter statics; a small positive diagonal keeps other tools happy.
            let _ = writeln!(
                self.0,
                "    <inertial><origin xyz=\"{:.5} {:.5} {:.5}\"/><mass value=\"{mass:.4}\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>",
                com[0], com[1], com[2]
            );
        }
        if let Some((radius, length, mid)) = capsule {
            let _ = writeln!(
                self.0,
                "    <collision><origin xyz=\"{:.5} {:.5} {:.5}\"/><geometry><cylinder radius=\"{radius:.4}\" length=\"{length:.4}\"/></geometry></collision>",
                mid[0], mid[1], mid[2]
            );
        }
        let _ = writeln!(self.0, "  </link>");
    }

    #[allow(clippy::too_many_arguments)] // one URDF <joint> element, one argument per attribute
    fn joint(
        &mut self,
        name: &str,
        kind: &str,
        parent: &str,
        child: &str,
        xyz: [f64; 3],
        axis: [f64; 3],
        effort: f64,
    ) {
        let _ = writeln!(self.0, "  <joint name=\"{name}\" type=\"{kind}\">");
        let _ = writeln!(
            self.0,
            "    <parent link=\"{parent}\"/><child link=\"{child}\"/>"
        );
        let _ = writeln!(
            self.0,
            "    <origin xyz=\"{:.5} {:.5} {:.5}\" rpy=\"0 0 0\"/>",
            xyz[0], xyz[1], xyz[2]
        );
        if kind != "fixed" {
            let (lo, hi) = limit(name);
            let _ = writeln!(
                self.0,
                "    <axis xyz=\"{} {} {}\"/>",
                axis[0], axis[1], axis[2]
            );
            let _ = writeln!(
                self.0,
                "    <limit lower=\"{lo}\" upper=\"{hi}\" effort=\"{effort}\" velocity=\"3\"/>"
            );
        }
        let _ = writeln!(self.0, "  </joint>");
    }
}

/// Writes the URDF of a standing worker. `effort` for each joint is the larger of its two
/// half-joint MVCs from `strength` (a fallback for tools that read only the URDF).
pub fn worker_urdf(
    w: &Worker,
    strength: &super::strength::StrengthTable,
) -> Result<String, WorkerError> {
    w.validate()?;
    let d = match w.sex {
        Sex::Male => &DE_LEVA_MALE,
        Sex::Female => &DE_LEVA_FEMALE,
    };
    let h = w.stature_m;
    let m = w.mass_kg;
    let s = h / d.ref_stature_m;
    let r = h / 1.755;
    let (lua, lfa, lh) = (d.upper_arm.2 * s, d.forearm.2 * s, d.hand.2 * s);
    use proportions::*;
    let trunk_len = (SUPRASTERNALE_Z - LUMBAR_Z) * h;
    let shoulder_dz = (SHOULDER_Z - LUMBAR_Z) * h;
    let sh_y = SHOULDER_HALF_WIDTH * h;
    let effort = |j: &str| strength.max_mvc_nm(j, w).unwrap_or(0.0);

    let mut u = Urdf(String::new());
    let _ = writeln!(u.0, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        u.0,
        "<!-- Generated by posture-opt: {:?}, stature {h} m, mass {m} kg, strength percentile {}.\n     de Leva (1996) segment parameters; see src/body/worker.rs for sources and assumptions. -->",
        w.sex, w.strength_percentile
    );
    let _ = writeln!(u.0, "<robot name=\"worker\">");
    u.link("floor", 0.0, [0.0; 3], None);
    // Pelvis (below the lumbar joint: its mass loads no modelled joint).
    let pelvis_len = 0.09 * h; // MIDA–MIDH, ASSUMPTION
    u.link(
        "pelvis",
        d.pelvis.0 * m,
        [0.0, 0.0, -d.pelvis.1 * pelvis_len],
        None,
    );
    u.joint(
        "floor_to_pelvis",
        "fixed",
        "floor",
        "pelvis",
        [0.0, 0.0, LUMBAR_Z * h],
        [0.0; 3],
        0.0,
    );
    u.link("lumbar_1", 0.0, [0.0; 3], None);
    u.link("lumbar_2", 0.0, [0.0; 3], None);
    u.joint(
        "lumbar_flexion",
        "revolute",
        "pelvis",
        "lumbar_1",
        [0.0; 3],
        [0.0, 1.0, 0.0],
        effort("lumbar_flexion"),
    );
    u.joint(
        "lumbar_lateral_bending",
        "revolute",
        "lumbar_1",
        "lumbar_2",
        [0.0; 3],
        [-1.0, 0.0, 0.0],
        effort("lumbar_lateral_bending"),
    );
    // Torso SUPR–MIDA, CM measured from SUPR.
    let torso_com_z = trunk_len * (1.0 - d.torso.1);
    u.link(
        "trunk",
        d.torso.0 * m,
        [0.0, 0.0, torso_com_z],
        Some((RADIUS_TRUNK * r, trunk_len, [0.0, 0.0, trunk_len / 2.0])),
    );
    u.joint(
        "lumbar_axial_rotation",
        "revolute",
        "lumbar_2",
        "trunk",
        [0.0; 3],
        [0.0, 0.0, 1.0],
        effort("lumbar_axial_rotation"),
    );
    // Head and neck, rigid on the trunk; CM from the vertex.
    let head_base = (1.0 - HEAD_LENGTH - LUMBAR_Z) * h;
    let head_com = HEAD_LENGTH * h * (1.0 - d.head.1);
    u.link(
        "head",
        d.head.0 * m,
        [0.0, 0.0, head_com],
        Some((
            RADIUS_HEAD * r,
            (HEAD_LENGTH * h - 2.0 * RADIUS_HEAD * r).max(0.01),
            [0.0, 0.0, HEAD_LENGTH * h / 2.0],
        )),
    );
    u.joint(
        "neck_fixed",
        "fixed",
        "trunk",
        "head",
        [0.0, 0.0, head_base],
        [0.0; 3],
        0.0,
    );
    // Left arm hanging at the side: one rigid body with the combined mass and CM.
    let (mu, mf, mh) = (d.upper_arm.0 * m, d.forearm.0 * m, d.hand.0 * m);
    let left_com = -(mu * d.upper_arm.1 * lua
        + mf * (lua + d.forearm.1 * lfa)
        + mh * (lua + lfa + d.hand.1 * lh))
        / (mu + mf + mh);
    let arm_len = lua + lfa + lh;
    u.link(
        "l_arm",
        mu + mf + mh,
        [0.0, 0.0, left_com],
        Some((RADIUS_FOREARM * r, arm_len, [0.0, 0.0, -arm_len / 2.0])),
    );
    u.joint(
        "l_shoulder_fixed",
        "fixed",
        "trunk",
        "l_arm",
        [0.0, sh_y, shoulder_dz],
        [0.0; 3],
        0.0,
    );
    // Right arm.
    u.link("r_shoulder_1", 0.0, [0.0; 3], None);
    u.link("r_shoulder_2", 0.0, [0.0; 3], None);
    u.joint(
        "r_shoulder_flexion",
        "revolute",
        "trunk",
        "r_shoulder_1",
        [0.0, -sh_y, shoulder_dz],
        [0.0, -1.0, 0.0],
        effort("r_shoulder_flexion"),
    );
    u.joint(
        "r_shoulder_abduction",
        "revolute",
        "r_shoulder_1",
        "r_shoulder_2",
        [0.0; 3],
        [-1.0, 0.0, 0.0],
        effort("r_shoulder_abduction"),
    );
    u.link(
        "r_upper_arm",
        mu,
        [0.0, 0.0, -d.upper_arm.1 * lua],
        Some((RADIUS_UPPER_ARM * r, lua, [0.0, 0.0, -lua / 2.0])),
    );
    u.joint(
        "r_shoulder_rotation",
        "revolute",
        "r_shoulder_2",
        "r_upper_arm",
        [0.0; 3],
        [0.0, 0.0, 1.0],
        effort("r_shoulder_rotation"),
    );
    u.link("r_elbow", 0.0, [0.0; 3], None);
    u.joint(
        "r_elbow_flexion",
        "revolute",
        "r_upper_arm",
        "r_elbow",
        [0.0, 0.0, -lua],
        [0.0, -1.0, 0.0],
        effort("r_elbow_flexion"),
    );
    u.link(
        "r_forearm",
        mf,
        [0.0, 0.0, -d.forearm.1 * lfa],
        Some((RADIUS_FOREARM * r, lfa, [0.0, 0.0, -lfa / 2.0])),
    );
    u.joint(
        "r_forearm_pronation",
        "revolute",
        "r_elbow",
        "r_forearm",
        [0.0; 3],
        [0.0, 0.0, 1.0],
        effort("r_forearm_pronation"),
    );
    u.link("r_wrist", 0.0, [0.0; 3], None);
    u.joint(
        "r_wrist_flexion",
        "revolute",
        "r_forearm",
        "r_wrist",
        [0.0, 0.0, -lfa],
        [1.0, 0.0, 0.0],
        effort("r_wrist_flexion"),
    );
    u.link(
        "r_hand",
        mh,
        [0.0, 0.0, -d.hand.1 * lh],
        Some((RADIUS_HAND * r, lh, [0.0, 0.0, -lh / 2.0])),
    );
    u.joint(
        "r_wrist_deviation",
        "revolute",
        "r_wrist",
        "r_hand",
        [0.0; 3],
        [0.0, -1.0, 0.0],
        effort("r_wrist_deviation"),
    );
    u.link("hand_grip", 0.0, [0.0; 3], None);
    u.joint(
        "hand_grip_fixed",
        "fixed",
        "r_hand",
        "hand_grip",
        [0.0, 0.0, -GRIP_ALONG_HAND * lh],
        [0.0; 3],
        0.0,
    );
    let _ = writeln!(u.0, "</robot>");
    Ok(u.0)
}
