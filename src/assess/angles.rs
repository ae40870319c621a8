//! The angles observational methods (RULA, REBA) look at, measured on a posture of the
//! whole-body worker, in degrees.
//!
//! * **Trunk**: the trunk's long axis against the vertical, in the body's sagittal and frontal
//!   planes (the pelvis's heading, projected on the floor, sets "forward"): so a stoop that tilts
//!   the pelvis counts as trunk flexion, as an observer would see it; side bending is the axis's
//!   angle out of the sagittal plane. Twist: the thorax's rotation about its own long axis
//!   against the pelvis (swing–twist split), whatever the flexion.
//! * **Neck and head**: the head's long axis against the trunk's and against the vertical, in the
//!   head's own planes ([`crate::body::head`]: turning the head does not change how far it is
//!   bent); twist: the neck's axial rotation.
//! * **Upper arm**: the shoulder-to-elbow direction in the trunk frame: flexion is its elevation
//!   from hanging (negative when the arm points back), abduction its angle out of the trunk's
//!   sagittal plane (outward positive).
//! * **Elbow**: the included-angle flexion between upper arm and forearm (0 = straight).
//! * **Wrist**: the wrist joints (flexion, deviation) and the forearm's pronation as a fraction of
//!   its range on that side.
//! * **Legs**: knee flexion of each leg; whether both feet bear weight (each carries at least
//!   [`UNILATERAL_SHARE`] of it).

use crate::body::{BodyModel, StaticsData, forward_kinematics};
use nalgebra::Vector3;
use serde::Serialize;

/// A foot carrying less than this share of the weight does not bear weight (REBA's "unilateral
/// weight bearing"; ASSUMPTION).
pub const UNILATERAL_SHARE: f64 = 0.1;

/// One arm's angles (degrees).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ArmAngles {
    pub upper_arm_flexion_deg: f64,
    pub upper_arm_abduction_deg: f64,
    pub elbow_flexion_deg: f64,
    pub wrist_flexion_deg: f64,
    pub wrist_deviation_deg: f64,
    /// Forearm pronation as a fraction of the joint's range on that side (0 = mid-position).
    pub wrist_twist_fraction: f64,
    /// Forearm pronation (supination negative) from the mid-position, thumb forward.
    pub forearm_pronation_deg: f64,
    /// The upper arm's angle against the vertical (shoulder to elbow against straight down),
    /// whatever the trunk does: ISO 11226's "upper arm elevation".
    pub upper_arm_elevation_deg: f64,
    /// The hand works across the body's midline / more than 10 cm out to the side of the shoulder.
    pub hand_across_midline: bool,
    pub hand_out_to_side: bool,
}

/// The whole body's angles (degrees).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct BodyAngles {
    pub trunk_flexion_deg: f64,
    /// Toward the left positive.
    pub trunk_side_bend_deg: f64,
    /// Toward the left positive.
    pub trunk_twist_deg: f64,
    pub neck_flexion_deg: f64,
    /// The head's long axis against the vertical in the body's sagittal plane (forward positive):
    /// ISO 11226's "head inclination".
    pub head_inclination_deg: f64,
    pub neck_side_bend_deg: f64,
    pub neck_twist_deg: f64,
    pub right: ArmAngles,
    pub left: ArmAngles,
    pub right_knee_flexion_deg: f64,
    pub left_knee_flexion_deg: f64,
    /// The pelvis's heading (square to its hip axis) against the feet's (their mean heading on
    /// the floor), toward the left positive: the turn the hips make on planted feet (the hips'
    /// rotations, for an ergonomist).
    pub pelvis_turn_deg: f64,
    pub both_feet_bear_weight: bool,
    /// The body sits on a seat: set by the caller that knows the supports ([`Self::measure`]
    /// leaves it false).
    pub seated: bool,
}

/// Why angles cannot be measured on a body.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the assessment needs the whole-body worker; '{0}' is not in this model")]
pub struct NotWorker(pub String);

/// The hand "out to the side": more than this lateral of the shoulder \[m\].
pub const OUT_TO_SIDE_M: f64 = 0.10;

impl BodyAngles {
    /// Every angle rounded to the whole degree, as the report states it and an observer reads
    /// it: RULA and REBA score these, so a trunk twisted 10.000000001° by a plan that keeps a
    /// 10° zone is "twisted 10°" in the words and in the score alike (an ergonomist's trial
    /// rescored a "10°" side bend that had scored +1). The wrist's twist fraction is not an
    /// angle and is kept.
    pub fn to_whole_degrees(&self) -> BodyAngles {
        let r = f64::round;
        let arm = |a: &ArmAngles| ArmAngles {
            upper_arm_flexion_deg: r(a.upper_arm_flexion_deg),
            upper_arm_abduction_deg: r(a.upper_arm_abduction_deg),
            elbow_flexion_deg: r(a.elbow_flexion_deg),
            wrist_flexion_deg: r(a.wrist_flexion_deg),
            wrist_deviation_deg: r(a.wrist_deviation_deg),
            forearm_pronation_deg: r(a.forearm_pronation_deg),
            upper_arm_elevation_deg: r(a.upper_arm_elevation_deg),
            ..*a
        };
        BodyAngles {
            trunk_flexion_deg: r(self.trunk_flexion_deg),
            trunk_side_bend_deg: r(self.trunk_side_bend_deg),
            trunk_twist_deg: r(self.trunk_twist_deg),
            neck_flexion_deg: r(self.neck_flexion_deg),
            head_inclination_deg: r(self.head_inclination_deg),
            neck_side_bend_deg: r(self.neck_side_bend_deg),
            neck_twist_deg: r(self.neck_twist_deg),
            right: arm(&self.right),
            left: arm(&self.left),
            right_knee_flexion_deg: r(self.right_knee_flexion_deg),
            left_knee_flexion_deg: r(self.left_knee_flexion_deg),
            pelvis_turn_deg: r(self.pelvis_turn_deg),
            ..*self
        }
    }

    /// The trunk's turn against the feet: its twist against the pelvis plus the pelvis's turn
    /// against the feet (toward the left positive), the twist an observer sees from the feet.
    pub fn trunk_turn_deg(&self) -> f64 {
        self.trunk_twist_deg + self.pelvis_turn_deg
    }

    /// Angles of posture `q_rad` of the generated worker; `left_foot_share` is the share of the
    /// weight on the left foot (from the statics), `None` for a body without feet.
    pub fn measure(
        model: &BodyModel,
        data: &mut StaticsData,
        q_rad: &[f64],
        left_foot_share: Option<f64>,
    ) -> Result<Self, NotWorker> {
        let link = |name: &str| {
            model
                .frame_link(name)
                .map_err(|_| NotWorker(name.to_string()))
        };
        let joint = |name: &str| model.q_index(name).map_err(|_| NotWorker(name.to_string()));
        let (pelvis, trunk, head) = (link("pelvis")?, link("trunk")?, link("head")?);
        forward_kinematics(model, data, q_rad);
        let deg = f64::to_degrees;
        let (r_pelvis, _) = data.link_pose(model, pelvis);
        let (r_trunk, p_trunk) = data.link_pose(model, trunk);
        let (r_head, _) = data.link_pose(model, head);
        // The body's horizontal frame: forward = the pelvis's heading square to its hip axis.
        let fwd = crate::body::heading::pelvis_forward(&r_pelvis);
        let left = Vector3::z().cross(&fwd);
        let t_axis = r_trunk * Vector3::z();
        let trunk_flexion_deg = deg(t_axis.dot(&fwd).atan2(t_axis.z));
        // out of the sagittal plane: well defined also when the trunk is flexed near 90°
        let trunk_side_bend_deg = deg(t_axis.dot(&left).clamp(-1.0, 1.0).asin());
        // Twist: the thorax's rotation about its own long axis against the pelvis (the twist
        // part of the swing–twist split of the pelvis-to-trunk rotation), so a stoop does not
        // shrink it as a floor heading would.
        let r_rel = nalgebra::UnitQuaternion::from_matrix(&(r_pelvis.transpose() * r_trunk));
        let trunk_twist_deg = deg(2.0 * r_rel.k.atan2(r_rel.w));
        let trunk_twist_deg = if trunk_twist_deg > 180.0 {
            trunk_twist_deg - 360.0
        } else if trunk_twist_deg < -180.0 {
            trunk_twist_deg + 360.0
        } else {
            trunk_twist_deg
        };
        let head = crate::body::head::HeadAngles::measure(&r_trunk, &r_head);
        let neck_flexion_deg = deg(head.neck_flexion_rad);
        let head_inclination_deg = deg(head.inclination_rad);
        let neck_side_bend_deg = deg(head.neck_side_bend_rad);
        let neck_twist_deg = deg(q_rad[joint("neck_axial_rotation")?]);
        let arm = |side: &str, outward_sign: f64| -> Result<ArmAngles, NotWorker> {
            let (upper, fore, hand, grip) = (
                link(&format!("{side}upper_arm"))?,
                link(&format!("{side}forearm"))?,
                link(&format!("{side}hand"))?,
                link(&format!("{side}hand_grip"))?,
            );
            let (pron, wflex, wdev) = (
                joint(&format!("{side}forearm_pronation"))?,
                joint(&format!("{side}wrist_flexion"))?,
                joint(&format!("{side}wrist_deviation"))?,
            );
            let o = Vector3::zeros();
            let shoulder = data.link_point(model, upper, &o);
            let elbow = data.link_point(model, fore, &o);
            let wrist = data.link_point(model, hand, &o);
            let grip_w = data.link_point(model, grip, &o);
            let u = (r_trunk.transpose() * (elbow - shoulder)).normalize();
            let v = (r_trunk.transpose() * (wrist - elbow)).normalize();
            let elevation = deg((-u.z).clamp(-1.0, 1.0).acos());
            let down = (elbow - shoulder).normalize();
            let upper_arm_elevation_deg = deg((-down.z).clamp(-1.0, 1.0).acos());
            let outward = outward_sign * u.y;
            let backward = u.x < 0.0 && -u.x >= outward.abs();
            let hand_t = r_trunk.transpose() * (grip_w - p_trunk);
            let shoulder_t = r_trunk.transpose() * (shoulder - p_trunk);
            let pj = model.q_joint(pron);
            let qp = q_rad[pron];
            let twist = if qp >= 0.0 && pj.upper_rad > 0.0 {
                qp / pj.upper_rad
            } else if qp < 0.0 && pj.lower_rad < 0.0 {
                qp / pj.lower_rad
            } else {
                0.0
            };
            Ok(ArmAngles {
                upper_arm_flexion_deg: if backward { -elevation } else { elevation },
                upper_arm_abduction_deg: deg(outward.clamp(-1.0, 1.0).asin()),
                elbow_flexion_deg: deg(u.dot(&v).clamp(-1.0, 1.0).acos()),
                wrist_flexion_deg: deg(q_rad[wflex]),
                wrist_deviation_deg: deg(q_rad[wdev]),
                wrist_twist_fraction: twist,
                forearm_pronation_deg: deg(qp),
                upper_arm_elevation_deg,
                hand_across_midline: -outward_sign * hand_t.y > 0.0,
                hand_out_to_side: outward_sign * (hand_t.y - shoulder_t.y) > OUT_TO_SIDE_M,
            })
        };
        // the right arm's outward is −y, the left's +y
        let right = arm("r_", -1.0)?;
        let left_arm = arm("l_", 1.0)?;
        let (rk, lk) = (joint("r_knee_flexion")?, joint("l_knee_flexion")?);
        // the pelvis's heading against the feet's (a body without the worker's foot links has no
        // feet to turn against: 0)
        let feet = [
            crate::body::worker::RIGHT_FOOT_LINK,
            crate::body::worker::LEFT_FOOT_LINK,
        ]
        .iter()
        .filter_map(|name| model.frame_link(name).ok())
        .map(|l| data.link_pose(model, l).0);
        let pelvis_turn_deg = deg(crate::body::heading::pelvis_turn_rad(&r_pelvis, feet));
        Ok(BodyAngles {
            trunk_flexion_deg,
            trunk_side_bend_deg,
            trunk_twist_deg,
            neck_flexion_deg,
            head_inclination_deg,
            neck_side_bend_deg,
            neck_twist_deg,
            right,
            left: left_arm,
            right_knee_flexion_deg: deg(q_rad[rk]),
            left_knee_flexion_deg: deg(q_rad[lk]),
            pelvis_turn_deg,
            both_feet_bear_weight: left_foot_share
                .is_none_or(|s| (UNILATERAL_SHARE..=1.0 - UNILATERAL_SHARE).contains(&s)),
            seated: false,
        })
    }
}
