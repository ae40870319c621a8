//! Static holding torques, Jacobians, the centre of mass and their derivatives, on a
//! preallocated workspace.
//!
//! Conventions: world frame x forward, y left, z up; metres, radians, newtons, N·m.
//! `q_rad[i]` is the position of the moving joint with q index `i` (radians; metres for a
//! prismatic joint). For a posture q, external loads — forces `F_e` that the environment applies
//! at points `p_e` fixed on links, and pure moments `M_e` — and gravity `g` (default
//! `(0, 0, −9.81)`):
//!
//! * `τ_gravity(q)`: the torque each joint must produce to hold the posture against gravity,
//!   `τ_gravity = −Σ_links J_c(l)ᵀ m_l g`;
//! * `τ_load(q) = −Σ_e (J_p(e)ᵀ F_e + J_ω(e)ᵀ M_e)`;
//! * holding torque `τ = τ_gravity + τ_load`; τ > 0: the joint must push in its positive
//!   direction (about its axis by the right-hand rule). A carried load of m kg is `F = m·g`.
//!
//! With `a_j` the world axis of joint j, `o_j` its world origin and `V_j = Σ_{l ∈ subtree(j)}
//! m_l (c_l − o_j)`, a revolute joint holds `τ_j = −a_j·(V_j × g) − Σ_{e below j}
//! a_j·((p_e − o_j) × F_e + M_e)`; a prismatic one `τ_j = −a_j·(M_j g + Σ_{e below j} F_e)`.
//! The derivative `∂τ/∂q` follows from the rigid motion of each subtree
//! ([`holding_torque_derivative`]). The centre of mass's Jacobian falls out of the same subtree
//! moments: its column for a revolute joint is `a_k × V_k / M`.

use super::model::{BodyModel, JointKind};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix3xX, Vector3};

/// Earth's gravity in the world frame [m/s²].
pub const GRAVITY_M_S2: Vector3<f64> = Vector3::new(0.0, 0.0, -9.81);

/// A load the environment applies on the body: a force at a point fixed on a link, and a pure
/// moment, both in world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLoad {
    pub link: usize,
    /// The point of application in the link's frame.
    pub point_in_link_m: Vector3<f64>,
    pub force_n: Vector3<f64>,
    pub moment_nm: Vector3<f64>,
}

impl PointLoad {
    /// A force at a link's frame origin.
    pub fn force_at(link: usize, force_n: Vector3<f64>) -> Self {
        PointLoad {
            link,
            point_in_link_m: Vector3::zeros(),
            force_n,
            moment_nm: Vector3::zeros(),
        }
    }
}

/// Workspace for statics; sized once for a model and a number of external loads, reused for
/// every posture. Per-joint arrays are indexed by q index; per-body arrays by rigid body
/// (0 = root, `k + 1` = moved by q index k).
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
    /// Per rigid body, then per subtree after [`apply_loads`]: the external loads' resultant force
    /// and moment about the world origin.
    ext_force: Vec<Vector3<f64>>,
    ext_moment: Vec<Vector3<f64>>,
    /// Per q index: a×V (gravity lever) and a×g.
    a_cross_v: Vec<Vector3<f64>>,
    a_cross_g: Vec<Vector3<f64>>,
    /// Per (q index, load), for [`holding_torque_derivative`]: a×(p_e − o), zero if the load is
    /// not below the joint (row-major by q).
    a_cross_w: Vec<Vector3<f64>>,
    /// Per (q index, load): a×F_e.
    a_cross_f: Vec<Vector3<f64>>,
    /// The rigid body of each load the two arrays above were last laid out for: their entries
    /// for joints that do not move the load stay zero while the bodies stay the same.
    load_bodies: Vec<usize>,
    /// (sin, cos) of each revolute joint angle, computed in one batch ahead of the chain.
    sin_cos: Vec<(f64, f64)>,
    /// The loads of the last [`holding_torques`] call, and their world points.
    pub loads: Vec<PointLoad>,
    pub load_point_w: Vec<Vector3<f64>>,
    pub gravity_m_s2: Vector3<f64>,
    pub tau_gravity_nm: DVector<f64>,
    pub tau_load_nm: DVector<f64>,
    pub tau_nm: DVector<f64>,
    /// Whole-body centre of mass and its 3×nq Jacobian (after [`holding_torques`]).
    pub com_m: Vector3<f64>,
    pub com_jacobian: Matrix3xX<f64>,
    /// ∂τ/∂q (nq×nq), filled by [`holding_torque_derivative`].
    pub dtau_dq: DMatrix<f64>,
}

impl StaticsData {
    /// A workspace for `model` with room for `n_loads` external loads.
    pub fn new(model: &BodyModel, n_loads: usize) -> Self {
        let nq = model.nq();
        let nb = model.bodies.len();
        StaticsData {
            body_rot: vec![Matrix3::identity(); nb],
            body_pos: vec![Vector3::zeros(); nb],
            axis_w: vec![Vector3::zeros(); nq],
            origin_w: vec![Vector3::zeros(); nq],
            sub_moment: vec![Vector3::zeros(); nq],
            body_moment: vec![Vector3::zeros(); nb],
            ext_force: vec![Vector3::zeros(); nb],
            ext_moment: vec![Vector3::zeros(); nb],
            a_cross_v: vec![Vector3::zeros(); nq],
            a_cross_g: vec![Vector3::zeros(); nq],
            a_cross_w: vec![Vector3::zeros(); nq * n_loads],
            a_cross_f: vec![Vector3::zeros(); nq * n_loads],
            load_bodies: Vec::with_capacity(n_loads),
            sin_cos: vec![(0.0, 1.0); nq],
            loads: Vec::with_capacity(n_loads),
            load_point_w: vec![Vector3::zeros(); n_loads],
            gravity_m_s2: GRAVITY_M_S2,
            tau_gravity_nm: DVector::zeros(nq),
            tau_load_nm: DVector::zeros(nq),
            tau_nm: DVector::zeros(nq),
            com_m: Vector3::zeros(),
            com_jacobian: Matrix3xX::zeros(nq),
            dtau_dq: DMatrix::zeros(nq, nq),
        }
    }

    /// Most loads this workspace takes.
    pub fn capacity(&self) -> usize {
        self.load_point_w.len()
    }

    /// World rotation and position of link `l` after [`forward_kinematics`].
    #[inline]
    pub fn link_pose(&self, model: &BodyModel, l: usize) -> (Matrix3<f64>, Vector3<f64>) {
        let lb = &model.link_in_body[l];
        let r = self.body_rot[lb.body];
        (r * lb.rot, self.body_pos[lb.body] + r * lb.pos)
    }

    /// World position of a point given in link `l`'s frame.
    #[inline]
    pub fn link_point(&self, model: &BodyModel, l: usize, p: &Vector3<f64>) -> Vector3<f64> {
        let lb = &model.link_in_body[l];
        let r = self.body_rot[lb.body];
        self.body_pos[lb.body] + r * (lb.pos + lb.rot * p)
    }

    /// Positional Jacobian (3×nq) of world point `p_w` moving with link `l`, into `out`.
    pub fn point_jacobian(
        &self,
        model: &BodyModel,
        l: usize,
        p_w: &Vector3<f64>,
        out: &mut Matrix3xX<f64>,
    ) {
        let body = model.link_in_body[l].body;
        for k in 0..model.nq() {
            let col = if !model.q_moves_body(k, body) {
                Vector3::zeros()
            } else if model.q_joint(k).kind == JointKind::Prismatic {
                self.axis_w[k]
            } else {
                self.axis_w[k].cross(&(p_w - self.origin_w[k]))
            };
            out.fixed_view_mut::<3, 1>(0, k).copy_from(&col);
        }
    }

    /// Angular Jacobian (3×nq) of link `l`, into `out`.
    pub fn angular_jacobian(&self, model: &BodyModel, l: usize, out: &mut Matrix3xX<f64>) {
        let body = model.link_in_body[l].body;
        for k in 0..model.nq() {
            let col =
                if model.q_moves_body(k, body) && model.q_joint(k).kind != JointKind::Prismatic {
                    self.axis_w[k]
                } else {
                    Vector3::zeros()
                };
            out.fixed_view_mut::<3, 1>(0, k).copy_from(&col);
        }
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
    // overlap them instead of stalling the serial chain below on each one. The `libm` crate's
    // sincos (musl's algorithm in Rust, within an ulp of the C library's) is about a third
    // faster here than the call into the C library.
    for ((sc, q), &ji) in data.sin_cos.iter_mut().zip(q_rad).zip(&model.joint_of_q) {
        if model.joints[ji].kind != JointKind::Prismatic {
            *sc = libm::sincos(*q);
        }
    }
    // In a chain, a joint's parent body is the previous joint's: keep that pose in registers.
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
        // the generated worker's joint frames are never rotated in their bodies
        let r0 = if model.q_body_rot_is_identity[k] {
            rp
        } else {
            rp * model.q_body_rot_joint[k]
        };
        let o = if model.q_body_pos_is_zero[k] {
            pp
        } else {
            pp + rp * model.q_body_pos_joint[k]
        };
        let a = match j.axis_coordinate {
            Some((ax, sign)) => r0.column(ax) * sign,
            None => r0 * j.axis,
        };
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

/// Computes forward kinematics, the centre of mass with its Jacobian, and the holding torques
/// for posture `q_rad` under `loads` (at most the workspace's capacity) and gravity
/// `gravity_m_s2`. Results land in `data`; nothing is allocated.
pub fn holding_torques(
    model: &BodyModel,
    data: &mut StaticsData,
    q_rad: &[f64],
    loads: &[PointLoad],
    gravity_m_s2: &Vector3<f64>,
) {
    forward_kinematics(model, data, q_rad);
    mass_moments(model, data);
    apply_loads(model, data, loads, gravity_m_s2);
}

/// Subtree first mass moments, the centre of mass and its Jacobian, and the gravity levers,
/// after [`forward_kinematics`].
pub fn mass_moments(model: &BodyModel, data: &mut StaticsData) {
    for (b, body) in model.bodies.iter().enumerate() {
        data.body_moment[b] = if body.mass_kg > 0.0 {
            body.mass_kg * (data.body_rot[b] * body.com_m + data.body_pos[b])
        } else {
            Vector3::zeros()
        };
    }
    let total = model.mass_kg;
    let inv_m = if total > 0.0 { 1.0 / total } else { 0.0 };
    // Subtree moments, leaves first, with each joint's gravity lever and centre-of-mass
    // Jacobian column as soon as its subtree is complete. Along a chain (parent body k of joint
    // k) the running sum stays in a register for the next iteration.
    let mut carry = Vector3::zeros();
    let mut carry_to = usize::MAX;
    for k in (0..model.nq()).rev() {
        let mut m = data.body_moment[k + 1];
        if carry_to == k + 1 {
            m += carry;
        }
        data.sub_moment[k] = m;
        let a = data.axis_w[k];
        let mass = model.q_subtree_mass_kg[k];
        let (av, col) = if model.q_joint(k).kind == JointKind::Prismatic {
            (Vector3::zeros(), a * (mass * inv_m))
        } else {
            let av = a.cross(&(m - mass * data.origin_w[k]));
            (av, av * inv_m)
        };
        data.a_cross_v[k] = av;
        data.com_jacobian
            .fixed_view_mut::<3, 1>(0, k)
            .copy_from(&col);
        let pb = model.q_parent_body[k];
        if pb == k && k > 0 {
            carry = m;
            carry_to = pb;
        } else {
            data.body_moment[pb] += m;
            carry_to = usize::MAX;
        }
    }
    data.com_m = if total > 0.0 {
        data.body_moment[0] / total
    } else {
        Vector3::zeros()
    };
}

/// The torques of gravity and `loads`, after [`mass_moments`].
pub fn apply_loads(
    model: &BodyModel,
    data: &mut StaticsData,
    loads: &[PointLoad],
    gravity_m_s2: &Vector3<f64>,
) {
    let ne = loads.len();
    assert!(
        ne <= data.capacity(),
        "statics workspace sized for {} loads, given {ne}",
        data.capacity()
    );
    data.loads.clear();
    data.loads.extend_from_slice(loads);
    data.gravity_m_s2 = *gravity_m_s2;
    for (e, ld) in loads.iter().enumerate() {
        data.load_point_w[e] = data.link_point(model, ld.link, &ld.point_in_link_m);
    }
    // Each load's force and moment about the world origin on its body, summed over subtrees
    // leaves first: a revolute joint holds τ = −a·(M_sub − o × F_sub), a prismatic one
    // τ = −a·F_sub — one pass over the joints however many loads there are.
    data.ext_force.fill(Vector3::zeros());
    data.ext_moment.fill(Vector3::zeros());
    for (e, ld) in loads.iter().enumerate() {
        let b = model.link_in_body[ld.link].body;
        data.ext_force[b] += ld.force_n;
        data.ext_moment[b] += data.load_point_w[e].cross(&ld.force_n) + ld.moment_nm;
    }
    let g = *gravity_m_s2;
    // along a chain (parent body k of joint k) the running sums stay in registers
    let (mut carry_f, mut carry_m, mut carry_to) = (Vector3::zeros(), Vector3::zeros(), usize::MAX);
    for (k, &ji) in model.joint_of_q.iter().enumerate().rev() {
        let a = data.axis_w[k];
        let (mut f, mut m) = (data.ext_force[k + 1], data.ext_moment[k + 1]);
        if carry_to == k + 1 {
            f += carry_f;
            m += carry_m;
        }
        let (tg, tl) = if model.joints[ji].kind == JointKind::Prismatic {
            (-a.dot(&(model.q_subtree_mass_kg[k] * g)), -a.dot(&f))
        } else {
            (
                -g.dot(&data.a_cross_v[k]),
                -a.dot(&(m - data.origin_w[k].cross(&f))),
            )
        };
        data.tau_gravity_nm[k] = tg;
        data.tau_load_nm[k] = tl;
        data.tau_nm[k] = tg + tl;
        let pb = model.q_parent_body[k];
        if pb == k && k > 0 {
            (carry_f, carry_m, carry_to) = (f, m, pb);
        } else {
            data.ext_force[pb] += f;
            data.ext_moment[pb] += m;
            carry_to = usize::MAX;
        }
    }
}

/// The per-(joint, load) levers `a×(p_e − o)` and `a×F_e` of the last [`apply_loads`]: both
/// zero for every joint that does not move the load, and `a×(p_e − o)` zero for prismatic
/// joints. The arrays are cleared only when a load moves to another body; each load visits only
/// its own path.
fn load_levers(model: &BodyModel, data: &mut StaticsData) {
    let ne = data.loads.len();
    let same_bodies = data.load_bodies.len() == ne
        && data
            .loads
            .iter()
            .zip(&data.load_bodies)
            .all(|(ld, &b)| model.link_in_body[ld.link].body == b);
    if !same_bodies {
        data.a_cross_w.fill(Vector3::zeros());
        data.a_cross_f.fill(Vector3::zeros());
        data.load_bodies.clear();
        let bodies = data.loads.iter().map(|ld| model.link_in_body[ld.link].body);
        data.load_bodies.extend(bodies);
    }
    let stride = data.capacity();
    for e in 0..ne {
        let (ld, p) = (data.loads[e], data.load_point_w[e]);
        for &k in model.q_path_of_body(model.link_in_body[ld.link].body) {
            let a = data.axis_w[k];
            let idx = k * stride + e;
            data.a_cross_f[idx] = a.cross(&ld.force_n);
            if model.q_joint(k).kind != JointKind::Prismatic {
                data.a_cross_w[idx] = a.cross(&(p - data.origin_w[k]));
            }
        }
    }
}

/// ∂τ/∂q of the holding torque at the posture and loads of the last [`holding_torques`] call
/// (loads fixed in the world), into `data.dtau_dq` (row: torque of joint j, column: q_i).
/// Analytic, from the rigid motion of each subtree (rotating a whole subtree together with the
/// world-fixed forces leaves its torques unchanged, which turns every case into dot products of
/// cached levers): for revolute joints,
///
/// * i a strict ancestor of j: `(a_i×g)·(a_j×V_j) + Σ_e [(a_i×F_e)·(a_j×W_je) + a_j·(a_i×M_e)]`;
/// * i in the subtree of j, i = j included: `(a_i×V_i)·(a_j×g) + Σ_{e below i} (a_i×W_ie)·(a_j×F_e)`;
/// * otherwise 0; prismatic joints translate their subtree (`∂V_j = M_i a_i`) and turn nothing.
pub fn holding_torque_derivative(model: &BodyModel, data: &mut StaticsData) {
    let g = data.gravity_m_s2;
    let nq = model.nq();
    let ne = data.loads.len();
    let stride = data.capacity();
    for k in 0..nq {
        data.a_cross_g[k] = data.axis_w[k].cross(&g);
    }
    load_levers(model, data);
    for row in 0..nq {
        let row_prismatic = model.q_joint(row).kind == JointKind::Prismatic;
        for col in 0..nq {
            let col_prismatic = model.q_joint(col).kind == JointKind::Prismatic;
            let strict_ancestor = col != row && model.q_is_ancestor_or_self(col, row);
            let in_subtree = model.q_is_ancestor_or_self(row, col);
            let d = match (row_prismatic, col_prismatic) {
                (false, false) if strict_ancestor => {
                    let mut d = data.a_cross_g[col].dot(&data.a_cross_v[row]);
                    let (ai, aj) = (data.axis_w[col], data.axis_w[row]);
                    for e in 0..ne {
                        let ir = row * stride + e;
                        let ld = &data.loads[e];
                        if !model.q_moves_body(row, model.link_in_body[ld.link].body) {
                            continue;
                        }
                        d += ai.cross(&ld.force_n).dot(&data.a_cross_w[ir])
                            + aj.dot(&ai.cross(&ld.moment_nm));
                    }
                    d
                }
                (false, false) if in_subtree => {
                    let mut d = data.a_cross_v[col].dot(&data.a_cross_g[row]);
                    for e in 0..ne {
                        d +=
                            data.a_cross_w[col * stride + e].dot(&data.a_cross_f[row * stride + e]);
                    }
                    d
                }
                (true, false) if strict_ancestor => {
                    // τ_j = −a_j·(M_j g + Σ F_e): a_j turns with q_i
                    let mut load = model.q_subtree_mass_kg[row] * g;
                    for e in 0..ne {
                        if model.q_moves_body(row, model.link_in_body[data.loads[e].link].body) {
                            load += data.loads[e].force_n;
                        }
                    }
                    -data.axis_w[col].cross(&data.axis_w[row]).dot(&load)
                }
                (false, true) if in_subtree && col != row => {
                    // subtree(i) translates along a_i: ∂V_j = M_i a_i, ∂W_je = a_i (loads below i)
                    let (aj, ai) = (data.axis_w[row], data.axis_w[col]);
                    let mut d = -aj.dot(&(model.q_subtree_mass_kg[col] * ai).cross(&g));
                    for e in 0..ne {
                        let ld = &data.loads[e];
                        if model.q_moves_body(col, model.link_in_body[ld.link].body) {
                            d -= aj.dot(&ai.cross(&ld.force_n));
                        }
                    }
                    d
                }
                _ => 0.0,
            };
            data.dtau_dq[(row, col)] = d;
        }
    }
}
