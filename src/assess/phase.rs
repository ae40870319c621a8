//! Everything an ergonomist reads off one planned posture: its angles and a description in words,
//! RULA and REBA, the low back's compression and shear, and the share of men and women strong
//! enough for every muscle group's load.

use super::angles::{ArmAngles, BodyAngles};
use super::low_back::{BackParams, LowBack, LumbarLoad, low_back};
use super::reba::{self, Reba, RebaActivity, RebaPosture, RebaSide, RebaThresholds};
use super::rula::{Rula, RulaActivity, score_body};
use crate::body::strength::normal_cdf;
use crate::body::{Direction, JointKind};
use crate::plan::posture::PostureWork;
use crate::plan::{Plan, Task};
use nalgebra::Vector3;
use serde::Serialize;

/// Share of men and women strong enough for a load.
#[derive(Debug, Clone, Serialize)]
pub struct Capable {
    pub half_joint: String,
    pub group: String,
    /// The torque this group must produce \[N·m\].
    pub required_nm: f64,
    /// Share of the population (0..1) whose strength at this posture exceeds it.
    pub men: f64,
    pub women: f64,
}

/// The assessment of one phase's posture.
#[derive(Debug, Clone, Serialize)]
pub struct PhaseAssessment {
    pub phase: String,
    /// The posture in words ("trunk flexed 20°, twisted 15° to the left").
    pub posture_words: String,
    /// Height of the hands above the floor \[m\] (mean of the hands used).
    pub hand_height_m: Option<f64>,
    pub load_kg: f64,
    pub angles: Option<BodyAngles>,
    /// RULA of the arm that scores worse (and the other arm's, for the record).
    pub rula: Option<Rula>,
    pub rula_other_arm: Option<Rula>,
    pub reba: Option<Reba>,
    /// L5/S1 compression and shear (bodies with a lumbar joint).
    pub low_back: Option<LowBack>,
    /// The least capable muscle groups, lowest first (at most 5), and the lowest shares.
    pub capable: Vec<Capable>,
    pub capable_men: f64,
    pub capable_women: f64,
}

/// How a phase is used (RULA/REBA activity): load, hold time, repetition.
fn activity(task: &Task, p: usize) -> (f64, f64, f64) {
    let ph = &task.phases[p];
    let g = task.gravity_m_s2.norm().max(1e-9);
    let load_kg = ph.total_force_n().norm() / g;
    let repeats = task.phases.iter().filter(|o| o.same_work(ph)).count() as f64;
    (load_kg, ph.duration_s, repeats * 60.0 / task.cycle_s())
}

/// The resultant force and moment about L5/S1 of everything above it (upper-body weight and the
/// hand loads), after the statics in `pw`; and the trunk's axes. `None` without a lumbar joint.
fn lumbar_load(task: &Task, pw: &PostureWork) -> Option<LumbarLoad> {
    let m = &task.model;
    let k = m.q_index("lumbar_flexion").ok()?;
    let trunk = m.frame_link("trunk").ok()?;
    let d = &pw.data;
    let o = d.origin_w[k];
    let g = task.gravity_m_s2;
    // mass and first moment of the subtree above L5/S1
    let mut mass = 0.0;
    let mut first = Vector3::zeros();
    for (b, body) in m.bodies.iter().enumerate().skip(1) {
        if m.q_is_ancestor_or_self(k, b - 1) && body.mass_kg > 0.0 {
            mass += body.mass_kg;
            first += body.mass_kg * (d.body_rot[b] * body.com_m + d.body_pos[b]);
        }
    }
    let mut force = mass * g;
    let mut moment = (first - mass * o).cross(&g);
    for (e, ld) in d.loads.iter().enumerate() {
        let body = m.link_in_body[ld.link].body;
        if m.q_moves_body(k, body) {
            force += ld.force_n;
            moment += (d.load_point_w[e] - o).cross(&ld.force_n) + ld.moment_nm;
        }
    }
    let (r_trunk, _) = d.link_pose(m, trunk);
    let up = r_trunk * Vector3::z();
    let fwd = r_trunk * Vector3::x();
    Some(LumbarLoad {
        moment_nm: [moment.x, moment.y, moment.z],
        force_n: [force.x, force.y, force.z],
        spine_axis: [up.x, up.y, up.z],
        forward_axis: [fwd.x, fwd.y, fwd.z],
    })
}

/// The posture in words, from its angles.
pub fn describe(a: &BodyAngles) -> String {
    let mut parts = Vec::new();
    let side = |v: f64| if v > 0.0 { "left" } else { "right" };
    let tf = a.trunk_flexion_deg;
    if tf.abs() < 5.0 {
        parts.push("trunk upright".to_string());
    } else if tf > 0.0 {
        parts.push(format!("trunk flexed {tf:.0}°"));
    } else {
        parts.push(format!("trunk extended {:.0}°", -tf));
    }
    // a turn or bend to one side, named from `min_deg` on
    let sideways = |parts: &mut Vec<String>, what: &str, v: f64, min_deg: f64| {
        if v.abs() >= min_deg {
            parts.push(format!("{what} {:.0}° to the {}", v.abs(), side(v)));
        }
    };
    sideways(&mut parts, "twisted", a.trunk_twist_deg, 5.0);
    sideways(&mut parts, "bent", a.trunk_side_bend_deg, 5.0);
    if a.neck_flexion_deg.abs() >= 10.0 {
        parts.push(if a.neck_flexion_deg > 0.0 {
            format!("neck flexed {:.0}° against the trunk", a.neck_flexion_deg)
        } else {
            format!(
                "neck extended {:.0}° against the trunk",
                -a.neck_flexion_deg
            )
        });
    }
    sideways(&mut parts, "head turned", a.neck_twist_deg, 10.0);
    sideways(&mut parts, "head bent", a.neck_side_bend_deg, 5.0);
    for (name, arm) in [("right", &a.right), ("left", &a.left)] {
        describe_upper_arm(&mut parts, name, arm);
        // a forearm turned far from mid-position (named from 45°, about half its range): which
        // wrist muscles carry the hand's load, and RULA's wrist twist
        let turn = arm.forearm_pronation_deg;
        if turn.abs() >= 45.0 {
            let how = if turn > 0.0 { "pronated" } else { "supinated" };
            parts.push(format!("{name} forearm {how} {:.0}°", turn.abs()));
        }
    }
    // planted feet and a turned pelvis: the hips rotate (named from 15°, a third of their range)
    if !a.seated && a.pelvis_turn_deg.abs() >= 15.0 {
        parts.push(format!(
            "pelvis turned {:.0}° to the {} of the feet",
            a.pelvis_turn_deg.abs(),
            side(a.pelvis_turn_deg)
        ));
    }
    let knees = a.right_knee_flexion_deg.max(a.left_knee_flexion_deg);
    if a.seated {
        parts.push("sitting".into());
    } else if knees >= 30.0 {
        parts.push(format!("knees bent {knees:.0}°"));
    }
    if !a.both_feet_bear_weight && !a.seated {
        parts.push("weight on one foot".into());
    }
    parts.join(", ")
}

/// The upper arm in words, when raised 20° or more against the trunk (forward or out to the
/// side).
fn describe_upper_arm(parts: &mut Vec<String>, name: &str, arm: &ArmAngles) {
    if !(arm.upper_arm_flexion_deg.abs() >= 20.0 || arm.upper_arm_abduction_deg >= 20.0) {
        return;
    }
    // angles against the trunk, as RULA and REBA take them (a stooped trunk with arms hanging
    // has its arms far forward of the trunk)
    let sagittal = if arm.upper_arm_flexion_deg >= 0.0 {
        format!(
            "raised {:.0}° forward of the trunk",
            arm.upper_arm_flexion_deg
        )
    } else {
        format!("{:.0}° behind the trunk", -arm.upper_arm_flexion_deg)
    };
    // an arm hanging in a stoop is far forward of the trunk and still hangs: said so first
    // (within the planner's free-arm limit of the vertical)
    if arm.upper_arm_elevation_deg.round() <= crate::plan::zones::FREE_ARM_DEG {
        let against = sagittal.trim_start_matches("raised ");
        parts.push(format!(
            "{name} upper arm hanging, {:.0}° from the vertical ({against})",
            arm.upper_arm_elevation_deg
        ));
        return;
    }
    // and its elevation from the vertical, the angle ISO 11226 and EN 1005-4 judge (a trial read
    // "raised 56° forward of the trunk" here and "raised 61° from the vertical" in the verdict
    // for the same arm)
    parts.push(format!(
        "{name} upper arm {sagittal}{} ({:.0}° from the vertical)",
        if arm.upper_arm_abduction_deg >= 20.0 {
            format!(", {:.0}° out to the side", arm.upper_arm_abduction_deg)
        } else {
            String::new()
        },
        arm.upper_arm_elevation_deg
    ));
}

/// Assesses the last planned posture of every phase of `plan`.
pub fn assess_phases(task: &Task, plan: &Plan) -> Vec<PhaseAssessment> {
    let mut pw = PostureWork::new(task);
    let thresholds = RebaThresholds::default();
    task.phases
        .iter()
        .enumerate()
        .map(|(p, ph)| {
            let q = &plan.summary.phases[p].q_rad;
            pw.statics(task, q, &ph.hand_force_n);
            let share = pw.ground.map(|g| g.left_share);
            let seated = pw.ground.is_some_and(|g| g.seat.is_some());
            let mut data = pw.data.clone();
            let angles = BodyAngles::measure(&task.model, &mut data, q, share)
                .ok()
                .map(|a| BodyAngles { seated, ..a });
            let (load_kg, held_s, repeats) = activity(task, p);
            let right_heavier = ph.hand_force_n[0].norm() >= ph.hand_force_n[1].norm();
            // scored as stated: to the whole degree
            let scored = angles.as_ref().map(BodyAngles::to_whole_degrees);
            let (rula, rula_other) = match &scored {
                Some(a) => {
                    let (r, o) = score_body(
                        a,
                        &RulaActivity {
                            load_kg,
                            held_s,
                            repeats_per_min: repeats,
                        },
                        right_heavier,
                    );
                    (Some(r), Some(o))
                }
                None => (None, None),
            };
            let reba = scored.as_ref().map(|a| {
                let side = |arm: &super::angles::ArmAngles| RebaSide {
                    upper_arm_flexion_deg: arm.upper_arm_flexion_deg,
                    upper_arm_abduction_deg: arm.upper_arm_abduction_deg,
                    shoulder_raised: false,
                    arm_supported_or_leaning: false,
                    elbow_flexion_deg: arm.elbow_flexion_deg,
                    wrist_flexion_deg: arm.wrist_flexion_deg,
                    wrist_deviated_or_twisted: thresholds.wrist_deviated_or_twisted(
                        arm.wrist_deviation_deg,
                        arm.forearm_pronation_deg,
                    ),
                };
                reba::score(
                    &RebaPosture {
                        trunk_flexion_deg: a.trunk_flexion_deg,
                        trunk_side_bend_deg: a.trunk_side_bend_deg,
                        trunk_twist_deg: a.trunk_twist_deg,
                        neck_flexion_deg: a.neck_flexion_deg,
                        neck_side_bend_deg: a.neck_side_bend_deg,
                        neck_twist_deg: a.neck_twist_deg,
                        bilateral_weight_bearing: a.both_feet_bear_weight || a.seated,
                        sitting: a.seated,
                        knee_flexion_deg: a.right_knee_flexion_deg.max(a.left_knee_flexion_deg),
                        right: side(&a.right),
                        left: side(&a.left),
                    },
                    &RebaActivity {
                        load_kg,
                        shock_or_rapid_force: false,
                        coupling: reba::Coupling::Fair,
                        static_over_1_min: held_s > 60.0,
                        repeated_over_4_per_min: repeats > 4.0,
                        rapid_large_posture_change_or_unstable_base: false,
                    },
                    &thresholds,
                )
            });
            let low =
                lumbar_load(task, &pw).and_then(|l| low_back(&l, &BackParams::default()).ok());
            let mut capable: Vec<Capable> = task
                .half_joints
                .iter()
                .filter_map(|h| {
                    let tau = pw.data.tau_nm[h.q_index];
                    let required = match h.direction {
                        Direction::Positive => tau.max(0.0),
                        Direction::Negative => (-tau).max(0.0),
                    };
                    if required <= 0.0 || task.model.q_joint(h.q_index).kind == JointKind::Prismatic
                    {
                        return None;
                    }
                    let factor = h.posture_factor(q);
                    let share = |s: &crate::body::strength::MeanSd| {
                        if s.sd_nm <= 0.0 {
                            if s.mean_nm * factor > required {
                                1.0
                            } else {
                                0.0
                            }
                        } else {
                            1.0 - normal_cdf((required / factor - s.mean_nm) / s.sd_nm)
                        }
                    };
                    Some(Capable {
                        half_joint: h.id.clone(),
                        group: h.group.clone(),
                        required_nm: required,
                        men: share(&h.male),
                        women: share(&h.female),
                    })
                })
                .collect();
            capable.sort_by(|a, b| a.women.min(a.men).total_cmp(&b.women.min(b.men)));
            let capable_men = capable.iter().map(|c| c.men).fold(1.0, f64::min);
            let capable_women = capable.iter().map(|c| c.women).fold(1.0, f64::min);
            capable.truncate(5);
            let hands: Vec<Vector3<f64>> = (0..2)
                .filter(|&h| ph.targets_m[h].is_some())
                .filter_map(|h| pw.hand_position(task, h))
                .collect();
            PhaseAssessment {
                phase: ph.name.clone(),
                posture_words: angles.as_ref().map(describe).unwrap_or_default(),
                hand_height_m: (!hands.is_empty())
                    .then(|| hands.iter().map(|v| v.z).sum::<f64>() / hands.len() as f64),
                load_kg,
                angles,
                rula,
                rula_other_arm: rula_other,
                reba,
                low_back: low,
                capable,
                capable_men,
                capable_women,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assess::angles::ArmAngles;

    fn arm(flexion_deg: f64, abduction_deg: f64, elevation_deg: f64) -> ArmAngles {
        ArmAngles {
            upper_arm_flexion_deg: flexion_deg,
            upper_arm_abduction_deg: abduction_deg,
            upper_arm_elevation_deg: elevation_deg,
            ..ArmAngles::default()
        }
    }

    /// A free arm hanging beside a trunk stooped 38° is 28° forward of the trunk and 10° from the
    /// vertical: it reads as hanging; a working arm raised 53° from the vertical reads as raised.
    #[test]
    fn an_arm_hanging_in_a_stoop_reads_as_hanging() {
        let a = BodyAngles {
            trunk_flexion_deg: 38.0,
            right: arm(62.0, 57.0, 53.0),
            left: arm(28.0, 0.0, 10.0),
            ..BodyAngles::default()
        };
        let w = describe(&a);
        assert!(
            w.contains("left upper arm hanging, 10° from the vertical (28° forward of the trunk)"),
            "{w}"
        );
        assert!(
            w.contains("right upper arm raised 62° forward of the trunk, 57° out to the side (53° from the vertical)"),
            "{w}"
        );
        let back = BodyAngles {
            left: arm(-21.0, 0.0, 8.0),
            ..a
        };
        assert!(
            describe(&back)
                .contains("left upper arm hanging, 8° from the vertical (21° behind the trunk)"),
            "{}",
            describe(&back)
        );
    }

    /// A forearm turned 45° or more from mid-position is named, pronated or supinated; less is
    /// not (the shelf's carry holds the box on a forearm supinated 70°).
    #[test]
    fn a_forearm_turned_far_is_named() {
        let mut a = BodyAngles::default();
        a.right.forearm_pronation_deg = -70.2;
        a.left.forearm_pronation_deg = 44.0;
        let w = describe(&a);
        assert!(w.contains("right forearm supinated 70°"), "{w}");
        assert!(!w.contains("left forearm"), "{w}");
        a.left.forearm_pronation_deg = 45.0;
        assert!(
            describe(&a).contains("left forearm pronated 45°"),
            "{}",
            describe(&a)
        );
    }
}
