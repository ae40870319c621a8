//! The `statics` report: one posture of any URDF, its hand frame's position and Jacobian, and
//! every joint's holding torque. A body that stands on two feet (a floating pelvis and foot
//! links with collision boxes, as the generated worker) stands on the floor where the posture
//! puts its feet, the floor's reaction split between them as in planning ([`super::stance`]);
//! any other body hangs from its root.

use super::model::{BodyError, BodyModel};
use super::stance::{Foot, Stance, foot_loads, ground_reaction, settle_internal_force};
use super::statics::{PointLoad, StaticsData, apply_loads, forward_kinematics, mass_moments};
use nalgebra::Vector3;
use serde::Serialize;

/// One joint's statics.
#[derive(Debug, Clone, Serialize)]
pub struct JointStatics {
    pub name: String,
    pub q_rad: f64,
    /// Holding torque from the body's own weight (with its share of the floor's reaction) and
    /// from the hand load \[N·m or N\]; their sum.
    pub gravity_torque_nm: f64,
    pub load_torque_nm: f64,
    pub torque_nm: f64,
}

/// The floor's reaction on a standing body.
#[derive(Debug, Clone, Serialize)]
pub struct FloorReaction {
    /// Force on the left and right foot \[N\], world frame.
    pub left_force_n: [f64; 3],
    pub right_force_n: [f64; 3],
    /// Centre of pressure of the whole reaction \[m\] (floor plane) and its margin inside the
    /// support polygon \[m\] (negative: outside, the body would tip).
    pub centre_of_pressure_m: [f64; 2],
    pub balance_margin_m: f64,
    pub left_share: f64,
}

/// The report.
#[derive(Debug, Clone, Serialize)]
pub struct StaticsReport {
    pub frame: String,
    pub position_m: [f64; 3],
    pub joints: Vec<JointStatics>,
    /// The frame's positional Jacobian: rows x, y, z, columns in the order of `joints`.
    pub jacobian: [Vec<f64>; 3],
    /// Whole-body centre of mass \[m\].
    pub centre_of_mass_m: [f64; 3],
    /// For a standing body: the floor's reaction.
    pub floor: Option<FloorReaction>,
}

/// The generated worker's floating-pelvis joints (no muscles: the floor holds the body).
const PELVIS: [&str; 6] = [
    "pelvis_tx",
    "pelvis_ty",
    "pelvis_tz",
    "pelvis_rotation",
    "pelvis_list",
    "pelvis_tilt",
];

/// A stance under the feet of `model` at posture `q`, when it has feet and a floating pelvis.
fn standing(model: &BodyModel, data: &StaticsData) -> Option<Stance> {
    model.q_index("pelvis_tz").ok()?;
    let left = Foot::from_link(model, "l_foot").ok()?;
    let right = Foot::from_link(model, "r_foot").ok()?;
    let sole = |f: &Foot| data.link_point(model, f.link, &f.sole_center_in_link_m);
    let (l, r) = (sole(&left), sole(&right));
    let mid = (l + r) / 2.0;
    let width = ((l.x - r.x).powi(2) + (l.y - r.y).powi(2)).sqrt();
    // the polygon only serves the margin: the soles where the posture puts them
    let mut st = Stance::new([left, right], width, mid.x, 0.0);
    let heading = (-(l.x - r.x)).atan2(l.y - r.y);
    if heading.abs() > 1e-9 {
        let rot = nalgebra::Rotation2::new(heading);
        for p in st.support_polygon_m.iter_mut() {
            let rel = *p - nalgebra::Vector2::new(mid.x, mid.y);
            *p = rot * rel + nalgebra::Vector2::new(mid.x, mid.y);
        }
    }
    Some(st)
}

/// Holding torques of `model` at the posture given by `(joint name, q)` pairs (others at 0).
pub fn statics_report(
    model: &BodyModel,
    frame: &str,
    q_named: &[(String, f64)],
    force_on_hand_n: Vector3<f64>,
    gravity_m_s2: Vector3<f64>,
) -> Result<StaticsReport, BodyError> {
    let hand = model.frame_link(frame)?;
    let mut q = vec![0.0; model.nq()];
    for (name, v) in q_named {
        q[model.q_index(name)?] = *v;
    }
    let mut d = StaticsData::new(model, 3);
    forward_kinematics(model, &mut d, &q);
    mass_moments(model, &mut d);
    let stance = standing(model, &d);
    // torques with the hand load, and without it: their difference is the load's share
    let mut without = vec![0.0; model.nq()];
    let mut floor = None;
    for pass in 0..2 {
        let force = if pass == 0 {
            Vector3::zeros()
        } else {
            force_on_hand_n
        };
        let hand_load = PointLoad::force_at(hand, force);
        let mut loads = vec![hand_load];
        if let Some(st) = &stance {
            let mut g = ground_reaction(model, &d, st, &[hand_load], &gravity_m_s2);
            loads.extend_from_slice(&foot_loads(model, &d, st, &g));
            apply_loads(model, &mut d, &loads, &gravity_m_s2);
            let actuated: Vec<bool> = (0..model.nq())
                .map(|k| !PELVIS.contains(&model.q_joint(k).name.as_str()))
                .collect();
            let mut scratch = nalgebra::Matrix3xX::zeros(model.nq());
            settle_internal_force(model, &mut d, st, &mut g, &actuated, &mut scratch);
            floor = Some(FloorReaction {
                left_force_n: g.force_n[0].into(),
                right_force_n: g.force_n[1].into(),
                centre_of_pressure_m: g.cop_total_m.into(),
                balance_margin_m: g.margin_m,
                left_share: g.left_share,
            });
        } else {
            apply_loads(model, &mut d, &loads, &gravity_m_s2);
        }
        if pass == 0 {
            without.copy_from_slice(d.tau_nm.as_slice());
        }
    }
    let hand_pos = d.load_point_w[0];
    let mut jac = nalgebra::Matrix3xX::zeros(model.nq());
    d.point_jacobian(model, hand, &hand_pos, &mut jac);
    let joints = (0..model.nq())
        .map(|i| JointStatics {
            name: model.q_joint(i).name.clone(),
            q_rad: q[i],
            gravity_torque_nm: without[i],
            load_torque_nm: d.tau_nm[i] - without[i],
            torque_nm: d.tau_nm[i],
        })
        .collect();
    let row = |r: usize| (0..model.nq()).map(|i| jac[(r, i)]).collect::<Vec<f64>>();
    Ok(StaticsReport {
        frame: frame.to_string(),
        position_m: hand_pos.into(),
        joints,
        jacobian: [row(0), row(1), row(2)],
        centre_of_mass_m: d.com_m.into(),
        floor,
    })
}
