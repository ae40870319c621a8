//! Static holding torques, Jacobians and their derivatives, on a preallocated workspace.
//!
//! Conventions: world frame x forward, y left, z up; metres, radians, newtons, N·m.
//! `q_rad[i]` is the position of the moving joint with q index `i` (radians; metres for a
//! prismatic joint). For a posture q, a hand frame h, a force `F` that the environment applies
//! on the hand (a carried load of m kg: `F = m·g`) and gravity `g` (default `(0, 0, −9.81)`):
//!
//! * `τ_gravity(q)`: the torque each joint must produce to hold the posture against gravity,
//!   `τ_gravity = −Σ_links J_c(l)ᵀ m_l g`;
//! * `τ_load(q) = −J_h(q)ᵀ F`;
//! * holding torque `τ = τ_gravity + τ_load`; τ > 0: the joint must push in its positive
//!   direction (about its axis by the right-hand rule);
//! * `J_h`: the 3×n positional Jacobian of the hand frame origin, world axes.
//!
//! With `a_j` the world axis of joint j, `o_j` its world origin, `V_j = Σ_{l ∈ subtree(j)} m_l
//! (c_l − o_j)` and `W_j = p_h − o_j` (zero if the hand is not below j), a revolute joint holds
//! `τ_j = −a_j·(V_j × g) − a_j·(W_j × F)`; a prismatic one `τ_j = −a_j·(M_j g + F)`. The derivative
//! `∂τ/∂q` follows from the rigid motion of the subtree (see [`holding_torque_derivative`]).

use super::model::{BodyModel, JointKind};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix3xX, Vector3};

/// Earth's gravity in the world frame [m/s²].
pub const GRAVITY_M_S2: Vector3<f64> = Vector3::new(0.0, 0.0, -9.81);

/// Workspace for statics; sized once for a model, reused for every posture. Per-joint arrays are
/// indexed by q index; per-body arrays by rigid body (0 = root, `k + 1` = moved by q index k).
#[derive(Debug, Clone)]
pub struct StaticsData {
    /// World rotation and position of each rigid body frame.
    pub body_rot: Vec<Matrix3<f64>>,
    pub body_pos: Vec<Vector3<f64>>,
    /// World axis and origin of each moving joint.
    pub axis_w: Vec<Vector3<f64>>,
    pub origin_w: Vec<Vector3<f64>>,
    /// First mass moment Σ m c [kg·m] of the subtree below each joint.
    sub_moment: Vec<Vector3<f64>>,
    body_moment: Vec<Vector3<f64>>,
    /// Per q index: a×V (gravity lever), a×W (hand lever; 0 if the hand is not below),
    /// a×g, a×F, and whether the joint carries the hand.
    a_cross_v: Vec<Vector3<f64>>,
    a_cross_w: Vec<Vector3<f64>>,
    a_cross_g: Vec<Vector3<f64>>,
    a_cross_f: Vec<Vector3<f64>>,
    carries_hand: Vec<bool>,
    /// (sin, cos) of each revolute joint angle, computed in one batch ahead of the chain.
    sin_cos: Vec<(f64, f64)>,
    /// Hand frame link, position, and the force on it from the last [`holding_torques`] call.
    pub hand_link: usize,
    pub hand_pos_m: Vector3<f64>,
    pub force_on_hand_n: Vector3<f64>,
    pub gravity_m_s2: Vector3<f64>,
    /// 3×nq positional Jacobian of the hand frame origin.
    pub jacobian: Matrix3xX<f64>,
    pub tau_gravity_nm: DVector<f64>,
    pub tau_load_nm: DVector<f64>,
    pub tau_nm: DVector<f64>,
    /// ∂τ/∂q (nq×nq), filled by [`holding_torque_derivative`].
    pub dtau_dq: DMatrix<f64>,
}

impl StaticsData {
    pub fn new(model: &BodyModel) -> Self {
        let nq = model.nq();
        let nb = model.bodies.len();
        StaticsData {
            body_rot: vec![Matrix3::identity(); nb],
            body_pos: vec![Vector3::zeros(); nb],
            axis_w: vec![Vector3::zeros(); nq],
            origin_w: vec![Vector3::zeros(); nq],
            sub_moment: vec![Vector3::zeros(); nq],
            body_moment: vec![Vector3::zeros(); nb],
            a_cross_v: vec![Vector3::zeros(); nq],
            a_cross_w: vec![Vector3::zeros(); nq],
            a_cross_g: vec![Vector3::zeros(); nq],
            a_cross_f: vec![Vector3::zeros(); nq],
            carries_hand: vec![false; nq],
            sin_cos: vec![(0.0, 1.0); nq],
            hand_link: 0,
            hand_pos_m: Vector3::zeros(),
            force_on_hand_n: Vector3::zeros(),
            gravity_m_s2: GRAVITY_M_S2,
            jacobian: Matrix3xX::zeros(nq),
            tau_gravity_nm: DVector::zeros(nq),
            tau_load_nm: DVector::zeros(nq),
            tau_nm: DVector::zeros(nq),
            dtau_dq: DMatrix::zeros(nq, nq),
        }
    }

    /// World rotation and position of link `l` after [`forward_kinematics`].
    pub fn link_pose(&self, model: &BodyModel, l: usize) -> (Matrix3<f64>, Vector3<f64>) {
        let lb = &model.link_in_body[l];
        let r = self.body_rot[lb.body];
        (r * lb.rot, self.body_pos[lb.body] + r * lb.pos)
    }

    /// World position of a point given in link `l`'s frame.
    pub fn link_point(&self, model: &BodyModel, l: usize, p: &Vector3<f64>) -> Vector3<f64> {
        let lb = &model.link_in_body[l];
        let r = self.body_rot[lb.body];
        self.body_pos[lb.body] + r * (lb.pos + lb.rot * p)
    }
}

/// Rotation by `angle` about unit `axis` (Rodrigues).
#[inline]
fn axis_angle(axis: &Vector3<f64>, (s, c): (f64, f64)) -> Matrix3<f64> {
    let t = 1.0 - c;
    let (x, y, z) = (axis.x, axis.y, axis.z);
    Matrix3::new(
        t * x * x + c,
        t * x * y - s * z,
        t * x * z + s * y,
        t * x * y + s * z,
        t * y * y + c,
        t * y * z - s * x,
        t * x * z - s * y,
        t * y * z + s * x,
        t * z * z + c,
    )
}

/// `r0 · R(sign·e_k, θ)` from `(sin θ, cos θ)`, rotating only the two columns that change.
/// Built from whole columns (no partial writes into a matrix that is read back at once).
#[inline]
fn rotate_about_coordinate_axis(
    r0: &Matrix3<f64>,
    k: usize,
    sign: f64,
    (s, c): (f64, f64),
) -> Matrix3<f64> {
    let s = sign * s;
    let (c0, c1, c2) = (
        r0.column(0).into_owned(),
        r0.column(1).into_owned(),
        r0.column(2).into_owned(),
    );
    // R about e_k maps e_i -> c e_i + s e_j and e_j -> -s e_i + c e_j, (i, j, k) cyclic
    match k {
        0 => Matrix3::from_columns(&[c0, c1 * c + c2 * s, c2 * c - c1 * s]),
        1 => Matrix3::from_columns(&[c0 * c - c2 * s, c1, c2 * c + c0 * s]),
        _ => Matrix3::from_columns(&[c0 * c + c1 * s, c1 * c - c0 * s, c2]),
    }
}

/// Forward kinematics over the moving joints: world pose of every rigid body and world axis and
/// origin of every moving joint. `q_rad.len()` must be `model.nq()`.
pub fn forward_kinematics(model: &BodyModel, data: &mut StaticsData, q_rad: &[f64]) {
    debug_assert_eq!(q_rad.len(), model.nq());
    // The sines and cosines are independent of each other: computing them first lets the CPU
    // overlap them instead of stalling the serial chain below on each one.
    for (sc, q) in data.sin_cos.iter_mut().zip(q_rad) {
        *sc = q.sin_cos();
    }
    // In a chain, a joint's parent body is the previous joint's: keep that pose in registers
    // instead of reading back what was just stored (a store-to-load round trip on the critical path).
    let mut prev_body = 0;
    let mut prev_r = data.body_rot[0];
    let mut prev_p = data.body_pos[0];
    for (k, &ji) in model.joint_of_q.iter().enumerate() {
        let j = &model.joints[ji];
        let pb = model.q_parent_body[k];
        let (rp, pp) = if pb == prev_body {
            (prev_r, prev_p)
        } else {
            (data.body_rot[pb], data.body_pos[pb])
        };
        let r0 = rp * model.q_body_rot_joint[k];
        let o = pp + rp * model.q_body_pos_joint[k];
        let a = r0 * j.axis;
        let (rc, pc) = if j.kind == JointKind::Prismatic {
            (r0, o + a * q_rad[k])
        } else {
            let rc = match j.axis_coordinate {
                Some((ax, sign)) => rotate_about_coordinate_axis(&r0, ax, sign, data.sin_cos[k]),
                None => r0 * axis_angle(&j.axis, data.sin_cos[k]),
            };
            (rc, o)
        };
        data.axis_w[k] = a;
        data.origin_w[k] = pc;
        data.body_rot[k + 1] = rc;
        data.body_pos[k + 1] = pc;
        prev_body = k + 1;
        prev_r = rc;
        prev_p = pc;
    }
}

/// Computes forward kinematics, the hand Jacobian and the holding torques for posture `q_rad`,
/// hand frame link `hand_link`, force `force_on_hand_n` applied on the hand by the environment,
/// and gravity `gravity_m_s2`. Results land in `data`; nothing is allocated.
pub fn holding_torques(
    model: &BodyModel,
    data: &mut StaticsData,
    q_rad: &[f64],
    hand_link: usize,
    force_on_hand_n: &Vector3<f64>,
    gravity_m_s2: &Vector3<f64>,
) {
    forward_kinematics(model, data, q_rad);
    let hand_body = model.link_in_body[hand_link].body;
    data.hand_link = hand_link;
    data.hand_pos_m = data.link_point(model, hand_link, &Vector3::zeros());
    data.force_on_hand_n = *force_on_hand_n;
    data.gravity_m_s2 = *gravity_m_s2;
    for (b, body) in model.bodies.iter().enumerate() {
        data.body_moment[b] = if body.mass_kg > 0.0 {
            body.mass_kg * (data.body_rot[b] * body.com_m + data.body_pos[b])
        } else {
            Vector3::zeros()
        };
    }
    // Subtree moments, leaves first. Bodies below k + 1 were folded into it already; along a chain
    // (parent body k of joint k) the running sum stays in a register for the next iteration.
    let mut carry = Vector3::zeros();
    let mut carry_to = usize::MAX;
    for k in (0..model.nq()).rev() {
        let mut m = data.body_moment[k + 1];
        if carry_to == k + 1 {
            m += carry;
        }
        data.sub_moment[k] = m;
        let pb = model.q_parent_body[k];
        if pb == k && k > 0 {
            carry = m;
            carry_to = pb;
        } else {
            data.body_moment[pb] += m;
            carry_to = usize::MAX;
        }
    }
    let g = *gravity_m_s2;
    let f = *force_on_hand_n;
    for (k, &ji) in model.joint_of_q.iter().enumerate() {
        let a = data.axis_w[k];
        let carries_hand = model.q_moves_body(k, hand_body);
        data.carries_hand[k] = carries_hand;
        let mass = model.q_subtree_mass_kg[k];
        let (tg, tl, col) = if model.joints[ji].kind == JointKind::Prismatic {
            data.a_cross_v[k] = Vector3::zeros();
            data.a_cross_w[k] = Vector3::zeros();
            let tg = -a.dot(&(mass * g));
            if carries_hand {
                (tg, -a.dot(&f), a)
            } else {
                (tg, 0.0, Vector3::zeros())
            }
        } else {
            let o = data.origin_w[k];
            // τ_g = −a·(V×g) = −g·(a×V); τ_load = −a·(W×F) = −F·(a×W); J column = a×W
            let av = a.cross(&(data.sub_moment[k] - mass * o));
            let aw = if carries_hand {
                a.cross(&(data.hand_pos_m - o))
            } else {
                Vector3::zeros()
            };
            data.a_cross_v[k] = av;
            data.a_cross_w[k] = aw;
            (-g.dot(&av), -f.dot(&aw), aw)
        };
        data.tau_gravity_nm[k] = tg;
        data.tau_load_nm[k] = tl;
        data.tau_nm[k] = tg + tl;
        data.jacobian.fixed_view_mut::<3, 1>(0, k).copy_from(&col);
    }
}

/// ∂τ/∂q of the holding torque at the posture of the last [`holding_torques`] call, into
/// `data.dtau_dq` (row: torque of joint j, column: q_i). Analytic, from the rigid motion of each
/// subtree: for revolute joints,
///
/// * i a strict ancestor of j (a_j and V_j, W_j turn with q_i): `a_j·(V_j×(a_i×g)) + a_j·(W_j×(a_i×F))`;
/// * i in the subtree of j, i = j included (only subtree(i) moves): `−a_j·((a_i×V_i)×g) − a_j·((a_i×W_i)×F)`;
/// * otherwise 0; prismatic joints translate their subtree (`∂V_j = M_i a_i`) and turn nothing.
pub fn holding_torque_derivative(model: &BodyModel, data: &mut StaticsData) {
    // With the triple-product identity a·(V×c) = c·(a×V), both revolute cases are dot products of
    // quantities cached by `holding_torques`:
    //   i strict ancestor of j:  (a_i×g)·(a_j×V_j) + (a_i×F)·(a_j×W_j)
    //   i in subtree of j:       (a_i×V_i)·(a_j×g) + (a_i×W_i)·(a_j×F)
    let g = data.gravity_m_s2;
    let f = data.force_on_hand_n;
    let nq = model.nq();
    for k in 0..nq {
        data.a_cross_g[k] = data.axis_w[k].cross(&g);
        data.a_cross_f[k] = data.axis_w[k].cross(&f);
    }
    for row in 0..nq {
        let row_prismatic = model.q_joint(row).kind == JointKind::Prismatic;
        for col in 0..nq {
            let col_prismatic = model.q_joint(col).kind == JointKind::Prismatic;
            let strict_ancestor = col != row && model.q_is_ancestor_or_self(col, row);
            let in_subtree = model.q_is_ancestor_or_self(row, col);
            let d = match (row_prismatic, col_prismatic) {
                (false, false) if strict_ancestor => {
                    data.a_cross_g[col].dot(&data.a_cross_v[row])
                        + data.a_cross_f[col].dot(&data.a_cross_w[row])
                }
                (false, false) if in_subtree => {
                    data.a_cross_v[col].dot(&data.a_cross_g[row])
                        + data.a_cross_w[col].dot(&data.a_cross_f[row])
                }
                (true, false) if strict_ancestor => {
                    // τ_j = −a_j·(M_j g + F): a_j turns with q_i
                    let load = model.q_subtree_mass_kg[row] * g
                        + if data.carries_hand[row] {
                            f
                        } else {
                            Vector3::zeros()
                        };
                    -data.axis_w[col].cross(&data.axis_w[row]).dot(&load)
                }
                (false, true) if in_subtree && col != row => {
                    // subtree(i) translates along a_i: ∂V_j = M_i a_i, ∂W_j = a_i (if it carries the hand)
                    let (aj, ai) = (data.axis_w[row], data.axis_w[col]);
                    let mut d = -aj.dot(&(model.q_subtree_mass_kg[col] * ai).cross(&g));
                    if data.carries_hand[col] {
                        d -= aj.dot(&ai.cross(&f));
                    }
                    d
                }
                _ => 0.0,
            };
            data.dtau_dq[(row, col)] = d;
        }
    }
}
