// Index loops over parallel per-joint / per-half-joint arrays read clearer than zipped iterators.
#![allow(clippy::needless_range_loop)]
//! Sequential QP for one phase's posture: linearise statics at the current posture, solve the
//! phase QP, accept the step if the merit function does not increase (else halve the trust
//! region), repeat to convergence. The QP's clarabel solver and all buffers live in [`SqpWork`]
//! and are reused across iterations, phases and re-plans.

use super::objective::FatigueObjective;
use super::qp::{PhaseQp, QpError};
use crate::body::{holding_torque_derivative, holding_torques, BodyModel, HalfJoint, StaticsData};
use crate::workstation::{Clearance, Workstation};
use nalgebra::Vector3;

/// Optimiser settings (documented defaults).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SqpSettings {
    /// Initial trust region per joint \[rad\].
    pub trust_region_rad: f64,
    /// Stop when the step is below this \[rad\] ...
    pub step_tolerance_rad: f64,
    /// ... or after this many iterations.
    pub max_iterations: usize,
    /// Weight of the squared hand-target error [1/m²]: 1 mm of error costs as much as a 1e-3
    /// change of the objective J (ln of total fatigue).
    pub target_weight: f64,
    /// Comfort: weight of the squared distance from the neutral posture [1/rad²].
    pub comfort_weight: f64,
    /// Weight of the squared step [1/rad²] (damping).
    pub step_weight: f64,
    /// Capacity slack: quadratic and linear weights.
    pub capacity_weight: f64,
    /// Minimum clearance between body capsules and obstacles \[m\].
    pub clearance_m: f64,
    /// Obstacles closer than this enter the QP as constraints \[m\].
    pub clearance_horizon_m: f64,
    /// Collision rows reserved in the QP (the closest pairs are kept).
    pub max_collision_rows: usize,
}

impl Default for SqpSettings {
    fn default() -> Self {
        SqpSettings {
            trust_region_rad: 0.3,
            step_tolerance_rad: 1e-3,
            max_iterations: 60,
            target_weight: 1e9,
            comfort_weight: 1e-2,
            step_weight: 1e-3,
            capacity_weight: 1e3,
            clearance_m: 0.01,
            clearance_horizon_m: 0.10,
            max_collision_rows: 8,
        }
    }
}

/// One phase's optimisation problem.
pub struct PhaseInput<'a> {
    pub hand_link: usize,
    pub target_m: Vector3<f64>,
    pub force_on_hand_n: Vector3<f64>,
    pub gravity_m_s2: Vector3<f64>,
    pub half_joints: &'a [HalfJoint],
    pub objective: &'a FatigueObjective,
    pub q_neutral_rad: &'a [f64],
    pub workstation: &'a Workstation,
    pub settings: SqpSettings,
}

/// Outcome of one phase's SQP.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PhaseSolution {
    pub iterations: usize,
    pub qp_solves: usize,
    pub converged: bool,
    pub hand_error_m: f64,
    pub min_clearance_m: f64,
    /// J = ln(total predicted fatigue + ε) at the solution.
    pub objective: f64,
}

/// Reusable buffers and the QP for a model.
pub struct SqpWork {
    pub qp: PhaseQp,
    f: Vec<f64>,
    grad: Vec<f64>,
    hess: Vec<f64>,
    /// Clearances of the current posture, with the link each belongs to.
    clear: Vec<(usize, Clearance)>,
    clear_scratch: Vec<Clearance>,
    q_trial: Vec<f64>,
    /// Capsules per link with their body: (link, a, b, radius).
    capsules: Vec<(usize, Vector3<f64>, Vector3<f64>, f64)>,
}

impl SqpWork {
    pub fn new(model: &BodyModel, settings: &SqpSettings) -> Self {
        let capsules = model
            .links
            .iter()
            .enumerate()
            .filter(|(l, _)| model.link_in_body[*l].body != 0)
            .flat_map(|(l, link)| {
                link.capsules
                    .iter()
                    .map(move |c| (l, c.a.coords, c.b.coords, c.radius_m))
            })
            .collect();
        let nh = 2 * model.nq();
        SqpWork {
            qp: PhaseQp::new(model.nq(), settings.max_collision_rows),
            f: vec![0.0; nh],
            grad: vec![0.0; nh],
            hess: vec![0.0; nh],
            clear: Vec::with_capacity(64),
            clear_scratch: Vec::with_capacity(16),
            q_trial: vec![0.0; model.nq()],
            capsules,
        }
    }
}

/// Relative loads of all half-joints at the posture/torques in `data`.
fn loads(half_joints: &[HalfJoint], data: &StaticsData, q: &[f64], f: &mut [f64]) {
    for (i, h) in half_joints.iter().enumerate() {
        f[i] = h.load(data.tau_nm[h.q_index], q[h.q_index]);
    }
}

/// Clearances of all body capsules within the horizon, with their links, into `out`; returns
/// the smallest distance.
fn clearances(
    model: &BodyModel,
    data: &StaticsData,
    capsules: &[(usize, Vector3<f64>, Vector3<f64>, f64)],
    ws: &Workstation,
    within: f64,
    scratch: &mut Vec<Clearance>,
    out: &mut Vec<(usize, Clearance)>,
) -> f64 {
    out.clear();
    let mut min_d = f64::INFINITY;
    for (l, a, b, r) in capsules {
        let aw = data.link_point(model, *l, a);
        let bw = data.link_point(model, *l, b);
        scratch.clear();
        ws.clearances(&aw, &bw, *r, within, scratch);
        for c in scratch.iter() {
            min_d = min_d.min(c.distance_m);
            out.push((*l, *c));
        }
    }
    min_d
}

/// Merit of posture `q`: the objective plus target, comfort and clearance penalties.
fn merit(
    model: &BodyModel,
    data: &mut StaticsData,
    work: &mut SqpWork,
    input: &PhaseInput,
    q: &[f64],
) -> (f64, f64, f64, f64) {
    holding_torques(
        model,
        data,
        q,
        input.hand_link,
        &input.force_on_hand_n,
        &input.gravity_m_s2,
    );
    loads(input.half_joints, data, q, &mut work.f);
    let j = input
        .objective
        .eval(&work.f, &mut work.grad, &mut work.hess);
    let err = (data.hand_pos_m - input.target_m).norm();
    let s = &input.settings;
    let comfort: f64 = q
        .iter()
        .zip(input.q_neutral_rad)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        * s.comfort_weight;
    let min_d = clearances(
        model,
        data,
        &work.capsules,
        input.workstation,
        s.clearance_horizon_m,
        &mut work.clear_scratch,
        &mut work.clear,
    );
    let pen: f64 = work
        .clear
        .iter()
        .map(|(_, c)| (s.clearance_m - c.distance_m).max(0.0).powi(2))
        .sum::<f64>()
        * s.target_weight;
    let cap: f64 = work
        .f
        .iter()
        .zip(input.objective.capacity.iter())
        .map(|(f, c)| (f - c).max(0.0))
        .map(|v| s.capacity_weight * (v * v + v))
        .sum();
    (
        j + s.target_weight * err * err + comfort + pen + cap,
        err,
        min_d,
        j,
    )
}

/// Optimises the posture `q` (in/out, radians) of one phase.
pub fn solve_phase(
    model: &BodyModel,
    data: &mut StaticsData,
    work: &mut SqpWork,
    input: &PhaseInput,
    q: &mut [f64],
) -> Result<PhaseSolution, QpError> {
    let n = model.nq();
    let s = input.settings;
    for (i, qi) in q.iter_mut().enumerate() {
        let j = model.q_joint(i);
        *qi = qi.clamp(j.lower_rad, j.upper_rad);
    }
    let mut rho = s.trust_region_rad;
    let mut sol = PhaseSolution::default();
    let (mut m0, _, _, _) = merit(model, data, work, input, q);
    while sol.iterations < s.max_iterations {
        sol.iterations += 1;
        // Linearise at q.
        holding_torques(
            model,
            data,
            q,
            input.hand_link,
            &input.force_on_hand_n,
            &input.gravity_m_s2,
        );
        holding_torque_derivative(model, data);
        loads(input.half_joints, data, q, &mut work.f);
        input
            .objective
            .eval(&work.f, &mut work.grad, &mut work.hess);
        clearances(
            model,
            data,
            &work.capsules,
            input.workstation,
            s.clearance_horizon_m,
            &mut work.clear_scratch,
            &mut work.clear,
        );
        work.clear
            .sort_by(|a, b| a.1.distance_m.total_cmp(&b.1.distance_m));
        work.clear.truncate(s.max_collision_rows);

        let qp = &mut work.qp;
        let (r, c) = (qp.rows(), qp.cols());
        qp.clear_a();
        qp.b.iter_mut().for_each(|x| *x = 0.0);
        for i in 0..n {
            qp.p_diag[c.dq + i] = 2.0 * (s.comfort_weight + s.step_weight);
            qp.q[c.dq + i] = 2.0 * s.comfort_weight * (q[i] - input.q_neutral_rad[i]);
        }
        for (h, hj) in input.half_joints.iter().enumerate() {
            let mvc = hj.mvc_at(q[hj.q_index]);
            let tau = data.tau_nm[hj.q_index];
            let (col, s_bar, cap_row) = match hj.direction {
                crate::body::Direction::Positive => {
                    (c.s_plus + hj.q_index, tau.max(0.0), r.cap_plus + hj.q_index)
                }
                crate::body::Direction::Negative => (
                    c.s_minus + hj.q_index,
                    (-tau).max(0.0),
                    r.cap_minus + hj.q_index,
                ),
            };
            let gs = work.grad[h] / mvc;
            let hs = work.hess[h] / (mvc * mvc);
            qp.p_diag[col] = hs.max(1e-9);
            qp.q[col] = gs - hs * s_bar;
            qp.set_a(cap_row, col, 1.0 / mvc);
            qp.set_a(cap_row, c.v, -1.0);
            qp.b[cap_row] = input.objective.capacity[h];
        }
        for k in 0..3 {
            qp.p_diag[c.e + k] = 2.0 * s.target_weight;
            qp.q[c.e + k] = 0.0;
        }
        qp.p_diag[c.v] = 2.0 * s.capacity_weight;
        qp.q[c.v] = s.capacity_weight;
        for row in 0..n {
            for col in 0..n {
                qp.set_a(r.torque + row, c.dq + col, data.dtau_dq[(row, col)]);
            }
            qp.set_a(r.torque + row, c.s_plus + row, -1.0);
            qp.set_a(r.torque + row, c.s_minus + row, 1.0);
            qp.b[r.torque + row] = -data.tau_nm[row];
            qp.set_a(r.s_plus_nonneg + row, c.s_plus + row, -1.0);
            qp.set_a(r.s_minus_nonneg + row, c.s_minus + row, -1.0);
        }
        let target_err = input.target_m - data.hand_pos_m;
        for k in 0..3 {
            for col in 0..n {
                qp.set_a(r.target + k, c.dq + col, data.jacobian[(k, col)]);
            }
            qp.set_a(r.target + k, c.e + k, 1.0);
            qp.b[r.target + k] = target_err[k];
        }
        qp.set_a(r.v_nonneg, c.v, -1.0);
        for i in 0..n {
            qp.set_a(r.step_upper + i, c.dq + i, 1.0);
            qp.set_a(r.step_lower + i, c.dq + i, -1.0);
        }
        for row in 0..s.max_collision_rows {
            qp.b[r.collision + row] = 1.0;
        }
        for (row, (link, cl)) in work.clear.iter().enumerate() {
            let body = model.link_in_body[*link].body;
            for k in 0..n {
                if model.q_moves_body(k, body) {
                    let jc = data.axis_w[k].cross(&(cl.point_m - data.origin_w[k]));
                    let jc = if model.q_joint(k).kind == crate::body::JointKind::Prismatic {
                        data.axis_w[k]
                    } else {
                        jc
                    };
                    qp.set_a(r.collision + row, c.dq + k, -cl.normal.dot(&jc));
                }
            }
            qp.b[r.collision + row] = cl.distance_m - s.clearance_m;
        }

        // Trust-region loop: shrink until the merit does not increase.
        loop {
            let qp = &mut work.qp;
            for i in 0..n {
                let j = model.q_joint(i);
                qp.b[r.step_upper + i] = (j.upper_rad - q[i]).min(rho).max(0.0);
                qp.b[r.step_lower + i] = (q[i] - j.lower_rad).min(rho).max(0.0);
            }
            sol.qp_solves += 1;
            let ok = qp.solve()?;
            if !ok {
                rho *= 0.5;
                if rho < s.step_tolerance_rad {
                    break;
                }
                continue;
            }
            let step_inf = qp.x[..n].iter().fold(0.0f64, |m, d| m.max(d.abs()));
            if step_inf < s.step_tolerance_rad {
                // The model sees no worthwhile step: a stationary point at this resolution.
                sol.converged = true;
                break;
            }
            for i in 0..n {
                work.q_trial[i] = q[i] + work.qp.x[i];
            }
            let trial = std::mem::take(&mut work.q_trial);
            let (m1, _, _, _) = merit(model, data, work, input, &trial);
            work.q_trial = trial;
            if m1 <= m0 + 1e-12 * m0.abs().max(1.0) {
                q.copy_from_slice(&work.q_trial);
                m0 = m1;
                if step_inf >= 0.9 * rho {
                    rho = (2.0 * rho).min(s.trust_region_rad); // the step hit the radius: widen it
                }
                break;
            }
            // Shrink below the rejected step, not just below the old radius.
            rho = 0.25 * step_inf.min(rho);
            if rho < s.step_tolerance_rad {
                sol.converged = true; // no descent step exists at this resolution
                break;
            }
        }
        if sol.converged || rho < s.step_tolerance_rad {
            sol.converged = true;
            break;
        }
    }
    let (_, err, min_d, j) = merit(model, data, work, input, q);
    sol.hand_error_m = err;
    sol.min_clearance_m = min_d;
    sol.objective = j;
    Ok(sol)
}
