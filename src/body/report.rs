//! The `statics` report: one posture, one hand frame, per DESIGN §6.

use super::model::{BodyError, BodyModel};
use super::statics::{holding_torques, PointLoad, StaticsData};
use nalgebra::Vector3;
use serde::Serialize;

#[derive(Debug, Clone, Serialize)]
pub struct JointStatics {
    pub name: String,
    pub q_rad: f64,
    pub gravity_torque_nm: f64,
    pub load_torque_nm: f64,
    pub torque_nm: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct StaticsReport {
    pub frame: String,
    pub position_m: [f64; 3],
    pub joints: Vec<JointStatics>,
    /// Column of the 3×n positional Jacobian per moving joint, keyed by joint name.
    pub jacobian: serde_json::Map<String, serde_json::Value>,
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
    let mut d = StaticsData::new(model, 1);
    let load = PointLoad::force_at(hand, force_on_hand_n);
    holding_torques(model, &mut d, &q, &[load], &gravity_m_s2);
    let hand_pos = d.load_point_w[0];
    let mut jac = nalgebra::Matrix3xX::zeros(model.nq());
    d.point_jacobian(model, hand, &hand_pos, &mut jac);
    let joints = (0..model.nq())
        .map(|i| JointStatics {
            name: model.q_joint(i).name.clone(),
            q_rad: q[i],
            gravity_torque_nm: d.tau_gravity_nm[i],
            load_torque_nm: d.tau_load_nm[i],
            torque_nm: d.tau_nm[i],
        })
        .collect();
    let jacobian = (0..model.nq())
        .map(|i| {
            let c = jac.column(i);
            (
                model.q_joint(i).name.clone(),
                serde_json::json!([c[0], c[1], c[2]]),
            )
        })
        .collect();
    Ok(StaticsReport {
        frame: frame.to_string(),
        position_m: [hand_pos.x, hand_pos.y, hand_pos.z],
        joints,
        jacobian,
    })
}
