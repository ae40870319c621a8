//! The generated default worker: a standing whole body from a worker description, as URDF.
//!
//! Segments, masses and centres of mass: de Leva (1996), J Biomech 29:1223, Table 4 (adjusted
//! Zatsiorsky–Seluyanov), lengths scaled by stature / reference stature (male 1.741 m, female
//! 1.735 m), masses by body mass, CM measured from the proximal endpoint listed there. The trunk
//! is de Leva's upper + middle trunk (SUPR–OMPH) above the lumbosacral joint and the lower trunk
//! (OMPH–MIDH) as the pelvis; the head is VERT–C7 (head and neck). Heights of the ankle, of
//! L5/S1 above the hip joint centres, of the shoulders, and the widths of hips, shoulders and
//! feet are fractions of stature or of foot length — ASSUMPTIONS where marked (after Drillis &
//! Contini 1966), not measurements. Joint ranges of motion: AAOS (1965), as reprinted in Greene &
//! & Heckman (1994), see [`RANGES_DEG`] and `docs/body.md`.
//!
//! Frames (world at the floor): x forward, y left, z up. At q = 0 the worker stands upright with
//! the feet under the hip joints, legs straight, arms hanging with the palms facing the thighs
//! (thumbs forward). The pelvis floats on six unactuated joints (`pelvis_tx/ty/tz`,
//! `pelvis_rotation` about z, `pelvis_list` about −x, `pelvis_tilt` about y, in that order), the
//! names of OpenSim's full-body models; the feet stand on the floor through the statics' stance
//! (see [`crate::body::stance`]). Joint signs (positive direction), left joints mirroring right
//! ones (x and z components of the axis negated):
//! * `lumbar_flexion` bends the trunk forward; `lumbar_lateral_bending` to the left;
//!   `lumbar_axial_rotation` turns it to the left; `neck_*` the same for the head on the trunk;
//! * `*_shoulder_flexion` raises the arm forward; `*_shoulder_abduction` sideways (away from the
//!   body); `*_shoulder_rotation` is internal rotation; `*_elbow_flexion` flexes;
//!   `*_forearm_pronation` pronates; `*_wrist_flexion` flexes toward the palm;
//!   `*_wrist_deviation` is radial deviation;
//! * `*_hip_flexion` raises the thigh forward; `*_hip_abduction` moves it away from the midline;
//!   `*_hip_rotation` is internal rotation; `*_knee_flexion` flexes; `*_ankle_dorsiflexion`
//!   lifts the toes (tilts the shank forward over a planted foot); `*_ankle_inversion` turns the
//!   sole toward the midline.

use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// Sex of a worker, for anthropometry and strength.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Sex {
    Male,
    Female,
}

impl std::str::FromStr for Sex {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "male" => Ok(Sex::Male),
            "female" => Ok(Sex::Female),
            _ => Err(format!("'{s}' is not a sex: give male or female")),
        }
    }
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Worker {
    pub sex: Sex,
    /// Stature \[m\], 1.2..2.3.
    pub stature_m: f64,
    /// Body mass \[kg\], 30..200.
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

/// One de Leva (1996) Table 4 segment: mass fraction, CM fraction of length from the proximal
/// endpoint, length \[m\] of the reference subject.
#[derive(Debug, Clone, Copy)]
struct Segment {
    mass: f64,
    cm: f64,
    len: f64,
}

const fn seg(mass: f64, cm: f64, len: f64) -> Segment {
    Segment { mass, cm, len }
}

/// de Leva (1996) Table 4 for one sex.
struct DeLeva {
    ref_stature_m: f64,
    /// VERT–C7, CM from the vertex.
    head: Segment,
    /// SUPR–XIPH, CM from SUPR.
    upper_trunk: Segment,
    /// XIPH–OMPH, CM from XIPH.
    middle_trunk: Segment,
    /// OMPH–MIDH, CM from OMPH.
    lower_trunk: Segment,
    upper_arm: Segment,
    forearm: Segment,
    /// Wrist joint centre to MET3.
    hand: Segment,
    thigh: Segment,
    /// Knee joint centre to lateral malleolus.
    shank: Segment,
    /// Heel to toe tip, CM from the heel.
    foot: Segment,
}

const DE_LEVA_MALE: DeLeva = DeLeva {
    ref_stature_m: 1.741,
    head: seg(0.0694, 0.5002, 0.2429),
    upper_trunk: seg(0.1596, 0.2999, 0.1707),
    middle_trunk: seg(0.1633, 0.4502, 0.2155),
    lower_trunk: seg(0.1117, 0.6115, 0.1457),
    upper_arm: seg(0.0271, 0.5772, 0.2817),
    forearm: seg(0.0162, 0.4574, 0.2689),
    hand: seg(0.0061, 0.7900, 0.0862),
    thigh: seg(0.1416, 0.4095, 0.4222),
    shank: seg(0.0433, 0.4459, 0.4340),
    foot: seg(0.0137, 0.4415, 0.2581),
};

const DE_LEVA_FEMALE: DeLeva = DeLeva {
    ref_stature_m: 1.735,
    head: seg(0.0668, 0.4841, 0.2437),
    upper_trunk: seg(0.1545, 0.2077, 0.1425),
    middle_trunk: seg(0.1465, 0.4512, 0.2053),
    lower_trunk: seg(0.1247, 0.4920, 0.1815),
    upper_arm: seg(0.0255, 0.5754, 0.2751),
    forearm: seg(0.0138, 0.4559, 0.2643),
    hand: seg(0.0056, 0.7474, 0.0780),
    thigh: seg(0.1478, 0.3612, 0.3685),
    shank: seg(0.0481, 0.4416, 0.4323),
    foot: seg(0.0129, 0.4014, 0.2283),
};

/// Proportions that de Leva's table does not give (ASSUMPTIONS, after Drillis & Contini 1966
/// where a fraction of stature is used).
pub mod proportions {
    /// Lateral malleolus (ankle joint) above the floor, fraction of stature.
    pub const ANKLE_Z: f64 = 0.039;
    /// Hip joint centres: half their distance, fraction of stature.
    pub const HIP_HALF_WIDTH: f64 = 0.05;
    /// L5/S1 above the mid-hip point, fraction of the lower-trunk (OMPH–MIDH) length.
    pub const L5S1_ABOVE_MIDH: f64 = 0.35;
    /// Shoulder joint centres below suprasternale, fraction of stature.
    pub const SHOULDER_BELOW_SUPR: f64 = 0.018;
    /// Shoulder joint centres: half their distance, fraction of stature.
    pub const SHOULDER_HALF_WIDTH: f64 = 0.105;
    /// Ankle above the foot, measured from the heel, fraction of foot length.
    pub const ANKLE_FROM_HEEL: f64 = 0.25;
    /// Foot breadth, fraction of foot length.
    pub const FOOT_BREADTH: f64 = 0.38;
    /// Grip centre along the hand, fraction of the wrist–MET3 length.
    pub const GRIP_ALONG_HAND: f64 = 0.75;
}

/// Capsule radii for a 1.755 m worker \[m\], scaled by stature (ASSUMPTIONS, for clearance only).
mod radius {
    pub const TRUNK: f64 = 0.11;
    pub const PELVIS: f64 = 0.10;
    pub const HEAD: f64 = 0.095;
    pub const UPPER_ARM: f64 = 0.045;
    pub const FOREARM: f64 = 0.036;
    pub const HAND: f64 = 0.025;
    pub const THIGH: f64 = 0.065;
    pub const SHANK: f64 = 0.045;
}

/// Ranges of motion \[deg\] in this worker's signs: (joint without side prefix, lower, upper).
/// AAOS (1965) *Joint Motion: Method of Measuring and Recording*, as reprinted in Greene &
/// Heckman (1994) *The Clinical Measurement of Joint Motion*; shoulder adduction below −30° is
/// an ASSUMPTION (the arm meets the trunk in the frontal plane). `docs/body.md` has the table.
pub const RANGES_DEG: [(&str, f64, f64); 20] = [
    ("lumbar_flexion", -25.0, 80.0),
    ("lumbar_lateral_bending", -35.0, 35.0),
    ("lumbar_axial_rotation", -45.0, 45.0),
    ("neck_flexion", -45.0, 45.0),
    ("neck_lateral_bending", -45.0, 45.0),
    ("neck_axial_rotation", -60.0, 60.0),
    ("shoulder_flexion", -60.0, 180.0),
    ("shoulder_abduction", -30.0, 180.0),
    ("shoulder_rotation", -90.0, 70.0),
    ("elbow_flexion", 0.0, 150.0),
    ("forearm_pronation", -80.0, 80.0),
    ("wrist_flexion", -70.0, 80.0),
    ("wrist_deviation", -30.0, 20.0),
    ("hip_flexion", -30.0, 120.0),
    ("hip_abduction", -30.0, 45.0),
    ("hip_rotation", -45.0, 45.0),
    ("knee_flexion", 0.0, 135.0),
    ("ankle_dorsiflexion", -50.0, 20.0),
    ("ankle_inversion", -15.0, 35.0),
    // the pelvis' orientation on the floating base: bounds of the search, not a range of motion
    ("pelvis_tilt", -30.0, 100.0),
];

/// Bounds of the pelvis' floating base that are not ranges of motion: rotation \[deg\] and list
/// \[deg\]; translations are bounded in metres by the generator (±0.6 m forward, ±0.5 m sideways,
/// down to the floor).
const PELVIS_ROTATION_DEG: f64 = 90.0;
const PELVIS_LIST_DEG: f64 = 30.0;

/// The range \[rad\] of a worker joint (side prefix `r_`/`l_` ignored).
pub fn range_rad(joint: &str) -> Option<(f64, f64)> {
    let base = joint
        .strip_prefix("r_")
        .or_else(|| joint.strip_prefix("l_"))
        .unwrap_or(joint);
    RANGES_DEG
        .iter()
        .find(|r| r.0 == base)
        .map(|r| (r.1.to_radians(), r.2.to_radians()))
}

/// Moving joints of the default worker, in URDF (and q) order.
pub const JOINTS: [&str; 38] = [
    "pelvis_tx",
    "pelvis_ty",
    "pelvis_tz",
    "pelvis_rotation",
    "pelvis_list",
    "pelvis_tilt",
    "lumbar_flexion",
    "lumbar_lateral_bending",
    "lumbar_axial_rotation",
    "neck_flexion",
    "neck_lateral_bending",
    "neck_axial_rotation",
    "r_shoulder_flexion",
    "r_shoulder_abduction",
    "r_shoulder_rotation",
    "r_elbow_flexion",
    "r_forearm_pronation",
    "r_wrist_flexion",
    "r_wrist_deviation",
    "l_shoulder_flexion",
    "l_shoulder_abduction",
    "l_shoulder_rotation",
    "l_elbow_flexion",
    "l_forearm_pronation",
    "l_wrist_flexion",
    "l_wrist_deviation",
    "r_hip_flexion",
    "r_hip_abduction",
    "r_hip_rotation",
    "r_knee_flexion",
    "r_ankle_dorsiflexion",
    "r_ankle_inversion",
    "l_hip_flexion",
    "l_hip_abduction",
    "l_hip_rotation",
    "l_knee_flexion",
    "l_ankle_dorsiflexion",
    "l_ankle_inversion",
];

/// The six unactuated joints of the floating pelvis.
pub const PELVIS_JOINTS: [&str; 6] = [
    "pelvis_tx",
    "pelvis_ty",
    "pelvis_tz",
    "pelvis_rotation",
    "pelvis_list",
    "pelvis_tilt",
];

/// Frames the worker carries for tasks: hand grips and soles.
pub const RIGHT_HAND_FRAME: &str = "r_hand_grip";
pub const LEFT_HAND_FRAME: &str = "l_hand_grip";
pub const RIGHT_FOOT_LINK: &str = "r_foot";
pub const LEFT_FOOT_LINK: &str = "l_foot";

/// Geometry of a generated worker that other parts need (stance, reports) \[m\].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WorkerGeometry {
    pub ankle_height_m: f64,
    pub hip_height_m: f64,
    pub hip_half_width_m: f64,
    pub l5s1_height_m: f64,
    pub shoulder_height_m: f64,
    pub shoulder_half_width_m: f64,
    pub foot_length_m: f64,
    pub foot_breadth_m: f64,
}

struct Urdf(String);

type Capsule = (f64, [f64; 3], [f64; 3]);

impl Urdf {
    fn link(&mut self, name: &str, mass: f64, com: [f64; 3], capsule: Option<Capsule>) {
        let _ = writeln!(self.0, "  <link name=\"{name}\">");
        self.inertial(mass, com);
        if let Some((radius, a, b)) = capsule {
            // A capsule as a URDF cylinder along z between a and b (posture-opt reads cylinders
            // as capsules: same axis segment and radius).
            let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let mid = [
                (a[0] + b[0]) / 2.0,
                (a[1] + b[1]) / 2.0,
                (a[2] + b[2]) / 2.0,
            ];
            // rotation taking z to d: pitch about y then roll about x
            let (roll, pitch) = if len > 0.0 {
                let (x, y, z) = (d[0] / len, d[1] / len, d[2] / len);
                ((-y).atan2((x * x + z * z).sqrt()), x.atan2(z))
            } else {
                (0.0, 0.0)
            };
            let _ = writeln!(
                self.0,
                "    <collision><origin xyz=\"{:.5} {:.5} {:.5}\" rpy=\"{roll:.6} {pitch:.6} 0\"/><geometry><cylinder radius=\"{radius:.4}\" length=\"{len:.4}\"/></geometry></collision>",
                mid[0], mid[1], mid[2]
            );
        }
        let _ = writeln!(self.0, "  </link>");
    }

    fn inertial(&mut self, mass: f64, com: [f64; 3]) {
        if mass > 0.0 {
            // Inertia does not enter statics; a small positive diagonal keeps other tools happy.
            let _ = writeln!(
                self.0,
                "    <inertial><origin xyz=\"{:.5} {:.5} {:.5}\"/><mass value=\"{mass:.4}\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>",
                com[0], com[1], com[2]
            );
        }
    }

    fn box_link(&mut self, name: &str, mass: f64, com: [f64; 3], centre: [f64; 3], size: [f64; 3]) {
        let _ = writeln!(self.0, "  <link name=\"{name}\">");
        self.inertial(mass, com);
        let _ = writeln!(
            self.0,
            "    <collision><origin xyz=\"{:.5} {:.5} {:.5}\"/><geometry><box size=\"{:.4} {:.4} {:.4}\"/></geometry></collision>",
            centre[0], centre[1], centre[2], size[0], size[1], size[2]
        );
        let _ = writeln!(self.0, "  </link>");
    }

    fn empty(&mut self, name: &str) {
        let _ = writeln!(self.0, "  <link name=\"{name}\"/>");
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
        limits: (f64, f64),
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
            let _ = writeln!(
                self.0,
                "    <axis xyz=\"{} {} {}\"/>",
                axis[0], axis[1], axis[2]
            );
            let _ = writeln!(
                self.0,
                "    <limit lower=\"{:.6}\" upper=\"{:.6}\" effort=\"{effort:.1}\" velocity=\"3\"/>",
                limits.0, limits.1
            );
        }
        let _ = writeln!(self.0, "  </joint>");
    }

    /// A chain of revolute joints at one point, with massless links between them; returns the
    /// last child's name.
    fn revolute_chain(
        &mut self,
        parent: &str,
        at: [f64; 3],
        joints: &[(&str, [f64; 3])],
        last_child: &str,
        effort: &dyn Fn(&str) -> f64,
    ) {
        let mut from = parent.to_string();
        for (i, (name, axis)) in joints.iter().enumerate() {
            let child = if i + 1 == joints.len() {
                last_child.to_string()
            } else {
                let c = format!("{name}_link");
                self.empty(&c);
                c
            };
            let xyz = if i == 0 { at } else { [0.0; 3] };
            let lim = range_rad(name).expect("every worker joint has a range");
            self.joint(
                name,
                "revolute",
                &from,
                &child,
                xyz,
                *axis,
                lim,
                effort(name),
            );
            from = child;
        }
    }
}

/// Side of an arm or leg: the prefix and the mirror sign of y.
#[derive(Clone, Copy)]
enum Side {
    Right,
    Left,
}

impl Side {
    fn prefix(self) -> &'static str {
        match self {
            Side::Right => "r_",
            Side::Left => "l_",
        }
    }
    /// +1 for left (y > 0), −1 for right.
    fn y(self) -> f64 {
        match self {
            Side::Right => -1.0,
            Side::Left => 1.0,
        }
    }
    /// Mirror of a right-side axis: x and z components negated for the left side.
    fn axis(self, right: [f64; 3]) -> [f64; 3] {
        match self {
            Side::Right => right,
            Side::Left => [-right[0], right[1], -right[2]],
        }
    }
}

/// The geometry of a worker (lengths and heights \[m\]).
pub fn worker_geometry(w: &Worker) -> WorkerGeometry {
    let d = de_leva(w.sex);
    let h = w.stature_m;
    let s = h / d.ref_stature_m;
    use proportions::*;
    let ankle = ANKLE_Z * h;
    let hip = ankle + (d.shank.len + d.thigh.len) * s;
    let l5s1 = hip + L5S1_ABOVE_MIDH * d.lower_trunk.len * s;
    let supr = hip + (d.lower_trunk.len + d.middle_trunk.len + d.upper_trunk.len) * s;
    let foot = d.foot.len * s;
    WorkerGeometry {
        ankle_height_m: ankle,
        hip_height_m: hip,
        hip_half_width_m: HIP_HALF_WIDTH * h,
        l5s1_height_m: l5s1,
        shoulder_height_m: supr - SHOULDER_BELOW_SUPR * h,
        shoulder_half_width_m: SHOULDER_HALF_WIDTH * h,
        foot_length_m: foot,
        foot_breadth_m: FOOT_BREADTH * foot,
    }
}

fn de_leva(sex: Sex) -> &'static DeLeva {
    match sex {
        Sex::Male => &DE_LEVA_MALE,
        Sex::Female => &DE_LEVA_FEMALE,
    }
}

/// Writes the URDF of a standing worker. `effort` for each joint is the larger of its two
/// half-joint MVCs from `strength` (a fallback for tools that read only the URDF).
pub fn worker_urdf(
    w: &Worker,
    strength: &super::strength::StrengthTable,
) -> Result<String, WorkerError> {
    w.validate()?;
    let d = de_leva(w.sex);
    let h = w.stature_m;
    let m = w.mass_kg;
    let s = h / d.ref_stature_m;
    let r = h / 1.755;
    let g = worker_geometry(w);
    let effort = |j: &str| strength.max_mvc_nm(j, w).unwrap_or(0.0);

    let mut u = Urdf(String::new());
    let _ = writeln!(u.0, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        u.0,
        "<!-- Generated by posture-opt: {}, stature {h} m, mass {m} kg, strength percentile {}.\n     de Leva (1996) segment parameters; sources and assumptions in docs/body.md. -->",
        w.sex.name(),
        w.strength_percentile
    );
    let _ = writeln!(u.0, "<robot name=\"worker\">");
    // Floating pelvis: three translations, then yaw, list and tilt.
    u.empty("floor");
    // (joint, kind, axis, limits)
    type PelvisJoint<'a> = (&'a str, &'a str, [f64; 3], (f64, f64));
    let pelvis_chain: [PelvisJoint; 6] = [
        ("pelvis_tx", "prismatic", [1.0, 0.0, 0.0], (-0.6, 0.6)),
        ("pelvis_ty", "prismatic", [0.0, 1.0, 0.0], (-0.5, 0.5)),
        (
            "pelvis_tz",
            "prismatic",
            [0.0, 0.0, 1.0],
            (-g.hip_height_m, 0.05),
        ),
        (
            "pelvis_rotation",
            "revolute",
            [0.0, 0.0, 1.0],
            (
                -PELVIS_ROTATION_DEG.to_radians(),
                PELVIS_ROTATION_DEG.to_radians(),
            ),
        ),
        (
            "pelvis_list",
            "revolute",
            [-1.0, 0.0, 0.0],
            (-PELVIS_LIST_DEG.to_radians(), PELVIS_LIST_DEG.to_radians()),
        ),
        (
            "pelvis_tilt",
            "revolute",
            [0.0, 1.0, 0.0],
            range_rad("pelvis_tilt").expect("pelvis tilt bounds"),
        ),
    ];
    let mut parent = "floor".to_string();
    for (i, (name, kind, axis, lim)) in pelvis_chain.iter().enumerate() {
        let child = if i == 5 {
            "pelvis".to_string()
        } else {
            format!("{name}_link")
        };
        if i < 5 {
            u.empty(&child);
        } else {
            // lower trunk (OMPH–MIDH), CM from OMPH; the pelvis frame is at mid-hip
            let lt = d.lower_trunk;
            let com_z = (1.0 - lt.cm) * lt.len * s;
            u.link(
                "pelvis",
                lt.mass * m,
                [0.0, 0.0, com_z],
                Some((
                    radius::PELVIS * r,
                    [0.0, g.hip_half_width_m * 0.6, com_z],
                    [0.0, -g.hip_half_width_m * 0.6, com_z],
                )),
            );
        }
        let xyz = if i == 2 {
            [0.0, 0.0, g.hip_height_m]
        } else {
            [0.0; 3]
        };
        u.joint(name, kind, &parent, &child, xyz, *axis, *lim, 0.0);
        parent = child;
    }

    // Trunk: upper + middle trunk above L5/S1.
    let l5s1_dz = g.l5s1_height_m - g.hip_height_m;
    let (ut, mt) = (d.upper_trunk, d.middle_trunk);
    let omph = (d.lower_trunk.len * s) - l5s1_dz; // above L5/S1
    let xiph = omph + mt.len * s;
    let supr = xiph + ut.len * s;
    let mt_com = xiph - mt.cm * mt.len * s;
    let ut_com = supr - ut.cm * ut.len * s;
    let trunk_mass = (ut.mass + mt.mass) * m;
    let trunk_com = (ut.mass * ut_com + mt.mass * mt_com) / (ut.mass + mt.mass);
    u.link(
        "trunk",
        trunk_mass,
        [0.0, 0.0, trunk_com],
        Some((
            radius::TRUNK * r,
            // from the abdomen up: below it the trunk's capsule would meet the thighs' at the
            // hip joints in any flexion (an artefact of capsules, not a collision)
            [0.0, 0.0, 0.10 * h],
            [0.0, 0.0, supr - 0.06 * h],
        )),
    );
    u.revolute_chain(
        "pelvis",
        [0.0, 0.0, l5s1_dz],
        &[
            ("lumbar_flexion", [0.0, 1.0, 0.0]),
            ("lumbar_lateral_bending", [-1.0, 0.0, 0.0]),
            ("lumbar_axial_rotation", [0.0, 0.0, 1.0]),
        ],
        "trunk",
        &effort,
    );

    // Head and neck (VERT–C7), CM from the vertex; the neck joint at C7.
    let hd = d.head;
    let c7_above_l5s1 = (h - hd.len * s) - g.l5s1_height_m;
    let head_len = hd.len * s;
    u.link(
        "head",
        hd.mass * m,
        [0.0, 0.0, head_len * (1.0 - hd.cm)],
        Some((
            radius::HEAD * r,
            [0.0, 0.0, head_len * 0.45],
            [0.0, 0.0, (head_len - radius::HEAD * r).max(head_len * 0.45)],
        )),
    );
    u.revolute_chain(
        "trunk",
        [0.0, 0.0, c7_above_l5s1],
        &[
            ("neck_flexion", [0.0, 1.0, 0.0]),
            ("neck_lateral_bending", [-1.0, 0.0, 0.0]),
            ("neck_axial_rotation", [0.0, 0.0, 1.0]),
        ],
        "head",
        &effort,
    );

    // Arms.
    let (ua, fa, hand) = (d.upper_arm, d.forearm, d.hand);
    let (lua, lfa, lh) = (ua.len * s, fa.len * s, hand.len * s);
    let shoulder_dz = g.shoulder_height_m - g.l5s1_height_m;
    for side in [Side::Right, Side::Left] {
        let p = side.prefix();
        let n = |j: &str| format!("{p}{j}");
        let upper = n("upper_arm");
        u.link(
            &upper,
            ua.mass * m,
            [0.0, 0.0, -ua.cm * lua],
            Some((radius::UPPER_ARM * r, [0.0; 3], [0.0, 0.0, -lua])),
        );
        let names = [
            n("shoulder_flexion"),
            n("shoulder_abduction"),
            n("shoulder_rotation"),
        ];
        u.revolute_chain(
            "trunk",
            [0.0, side.y() * g.shoulder_half_width_m, shoulder_dz],
            &[
                (&names[0], side.axis([0.0, -1.0, 0.0])),
                (&names[1], side.axis([-1.0, 0.0, 0.0])),
                (&names[2], side.axis([0.0, 0.0, 1.0])),
            ],
            &upper,
            &effort,
        );
        let forearm = n("forearm");
        u.link(
            &forearm,
            fa.mass * m,
            [0.0, 0.0, -fa.cm * lfa],
            Some((radius::FOREARM * r, [0.0; 3], [0.0, 0.0, -lfa])),
        );
        let elbow = [n("elbow_flexion"), n("forearm_pronation")];
        u.revolute_chain(
            &upper,
            [0.0, 0.0, -lua],
            &[
                (&elbow[0], side.axis([0.0, -1.0, 0.0])),
                (&elbow[1], side.axis([0.0, 0.0, 1.0])),
            ],
            &forearm,
            &effort,
        );
        let hand_link = n("hand");
        u.link(
            &hand_link,
            hand.mass * m,
            [0.0, 0.0, -hand.cm * lh],
            Some((radius::HAND * r, [0.0; 3], [0.0, 0.0, -lh])),
        );
        let wrist = [n("wrist_flexion"), n("wrist_deviation")];
        u.revolute_chain(
            &forearm,
            [0.0, 0.0, -lfa],
            &[
                (&wrist[0], side.axis([1.0, 0.0, 0.0])),
                (&wrist[1], side.axis([0.0, -1.0, 0.0])),
            ],
            &hand_link,
            &effort,
        );
        let grip = n("hand_grip");
        u.empty(&grip);
        u.joint(
            &format!("{grip}_fixed"),
            "fixed",
            &hand_link,
            &grip,
            [0.0, 0.0, -proportions::GRIP_ALONG_HAND * lh],
            [0.0; 3],
            (0.0, 0.0),
            0.0,
        );
    }

    // Legs.
    let (th, sh, ft) = (d.thigh, d.shank, d.foot);
    let (lth, lsh, lft) = (th.len * s, sh.len * s, ft.len * s);
    let ankle = g.ankle_height_m;
    for side in [Side::Right, Side::Left] {
        let p = side.prefix();
        let n = |j: &str| format!("{p}{j}");
        let thigh = n("thigh");
        u.link(
            &thigh,
            th.mass * m,
            [0.0, 0.0, -th.cm * lth],
            Some((
                radius::THIGH * r,
                [0.0, 0.0, -0.12 * lth],
                [0.0, 0.0, -0.9 * lth],
            )),
        );
        let hip = [n("hip_flexion"), n("hip_abduction"), n("hip_rotation")];
        u.revolute_chain(
            "pelvis",
            [0.0, side.y() * g.hip_half_width_m, 0.0],
            &[
                (&hip[0], side.axis([0.0, -1.0, 0.0])),
                (&hip[1], side.axis([-1.0, 0.0, 0.0])),
                (&hip[2], side.axis([0.0, 0.0, 1.0])),
            ],
            &thigh,
            &effort,
        );
        let shank = n("shank");
        u.link(
            &shank,
            sh.mass * m,
            [0.0, 0.0, -sh.cm * lsh],
            Some((
                radius::SHANK * r,
                [0.0, 0.0, -0.08 * lsh],
                [0.0, 0.0, -0.85 * lsh],
            )),
        );
        let knee = n("knee_flexion");
        u.revolute_chain(
            &thigh,
            [0.0, 0.0, -lth],
            &[(&knee, side.axis([0.0, 1.0, 0.0]))],
            &shank,
            &effort,
        );
        // Foot: a box from the heel to the toe tip, from the sole up to the ankle; CM from the heel.
        let foot = n("foot");
        let heel_x = -proportions::ANKLE_FROM_HEEL * lft;
        u.box_link(
            &foot,
            ft.mass * m,
            [heel_x + ft.cm * lft, 0.0, -ankle / 2.0],
            [heel_x + lft / 2.0, 0.0, -ankle / 2.0],
            [lft, g.foot_breadth_m, ankle],
        );
        let ank = [n("ankle_dorsiflexion"), n("ankle_inversion")];
        u.revolute_chain(
            &shank,
            [0.0, 0.0, -lsh],
            &[
                (&ank[0], side.axis([0.0, -1.0, 0.0])),
                (&ank[1], side.axis([1.0, 0.0, 0.0])),
            ],
            &foot,
            &effort,
        );
    }
    let _ = writeln!(u.0, "</robot>");
    Ok(u.0)
}
