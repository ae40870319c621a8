//! The `statics` report: one posture, one hand frame, per DESIGN §6.

use super::model::{BodyError, BodyModel};
use super::statics::{holding_torques, StaticsData};
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
    let mut d = StaticsData::new(model);
    holding_torques(model, &mut d, &q, hand, &force_on_hand_n, &gravity_m_s2);
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
            let c = d.jacobian.column(i);
            (
                model.q_joint(i).name.clone(),
                serde_json::json!([c[0], c[1], c[2]]),
            )
        })
        .collect();
    Ok(StaticsReport {
        frame: frame.to_string(),
        position_m: [d.hand_pos_m.x, d.hand_pos_m.y, d.hand_pos_m.z],
        joints,
        jacobian,
    })
}
