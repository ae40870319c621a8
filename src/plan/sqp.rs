//! Sequential quadratic programming for one phase's posture.
//!
//! Each iteration linearises the statics, the hand targets, the feet, the clearances and the
//! balance at the current posture and solves the QP of [`super::qp`] for a step `d`.
//!
//! **Globalisation: an ℓ1 exact-penalty line search with a second-order correction.** The merit
//! is `φ(q) = J(q) + μ_eq ‖c_eq(q)‖₁ + μ_geo·(largest clearance/balance violation) + μ_cap·(largest
//! capacity excess)`, the same penalties the QP's elastic slacks carry, so the QP step is a descent
//! direction for φ. A full step is accepted when φ falls by a fraction of the QP's predicted
//! decrease; if it does not — typically because a curved constraint (the hand on its target)
//! makes a good long step look infeasible to first order (the Maratos effect) — a second-order
//! correction brings the trial posture back onto the curved targets and feet and out of any
//! clearance or balance constraint it crossed (Newton projection, [`restore`]), tried at every
//! trial step length; only if that fails too does the step shrink. The step is bounded by a
//! fixed box (0.5 rad, 0.2 m), not by a shrinking trust region.
//!
//! **The equality penalty follows the multipliers.** A solve starts with `μ_eq` =
//! [`SqpSettings::mu_eq`] (1 per metre or radian) and, after every QP, raises it to twice the
//! largest multiplier of the target and feet rows, rounded up to a power of two
//! ([`raise_penalty`]; the textbook exact-penalty rule `μ > ‖z‖∞`, with a margin). A fixed
//! penalty of 10³ per metre, three orders above those multipliers (J is a log of minutes), made a
//! step's second-order miss of a tenth of a millimetre outweigh its fall in J, and the line search
//! cut the steps 64–128-fold iteration after iteration (on the shelf task 22 full solves ended
//! at the iteration limit that way).
//!
//! **Curvature start.** The QP's posture block is `B + D + δI`: `D` the discomfort's exact
//! diagonal, δ the damping, and `B` a damped BFGS (Powell) approximation of the rest of the
//! Lagrangian's curvature in q. `B` does not start from a scaled identity but from the
//! Jacobian of the objective's explicit posture gradient (the strength's posture dependence
//! through the torques, the MVC curves and the load cost's exact curvature, derived
//! analytically; the step cost's by differences of its gradient), symmetrised and with its
//! eigenvalues raised to 10⁻³ ([`start_curvature`]): what the curvature is when the multipliers
//! are zero. BFGS then adds what the constraints' curvature contributes (the torques' and the
//! hands' second derivatives) along the steps. The damped BFGS update acts on the whole model
//! `B + D` (its pair is the Lagrangian's whole gradient change), so `B` may carry negative
//! curvature — the fatigue terms' concavity along a nearly free joint, the forearm's rotation say,
//! against the discomfort's curvature there — as long as `B + D/2` stays positive definite
//! ([`keep_model_positive`]). When `B` was kept positive on its own, the model overstated the
//! curvature along such directions by up to `D`: full steps too short by that factor, a linear
//! tail of tens of iterations (the pairs' `sᵀy` down to −7·10⁴ `sᵀBs`, Powell's damping at
//! θ → 0). Measured on the nine shipped tasks (held plans),
//! the two together converge 40 of 43 phases where the fixed penalty and identity start
//! converged 32, and the plans' totals move by at most 1e-5 (relative) when only the QP's
//! precision changes, where they moved by up to 2.7 %; either change alone did not do that.
//!
//! **Stopping test: the KKT residual** of the problem at the current posture, with the
//! multipliers of the QP solved there: stationarity `‖Px₀ + q + Aᵀz‖∞` over the posture and torque
//! variables (x₀ the current point in the QP's variables), feasibility (largest target, feet,
//! clearance and balance violation, metres or radians) and complementarity (largest
//! `|z_i·slack_i|` of the inequality rows). A phase is `converged` when all three are below
//! [`SqpSettings::tol_kkt`] (default 1e-5); otherwise the solve reports why it stopped.

use super::objective::{Discomfort, LoadCost, Shape};
use super::posture::{Contact, PostureWork, Row, Scene, geometry_row_count};
use super::qp::{PostureQp, QpError, QpPrecision, QpSizes};
use super::stepping::Stepping;
use super::task::Task;
use super::zones::{ZONE_PENALTY_PER_RAD, ZONE_ROWS, ZoneLimits, ZoneWork};
use crate::body::Direction;
use crate::workstation::Workstation;
use nalgebra::Vector3;
use serde::Serialize;

/// Optimiser settings (documented defaults).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SqpSettings {
    pub max_iterations: usize,
    /// Largest step of a revolute joint \[rad\] and of a prismatic one \[m\] per iteration.
    pub step_box_rad: f64,
    pub step_box_m: f64,
    /// KKT tolerance (stationarity, feasibility in m or rad, complementarity).
    pub tol_kkt: f64,
    /// ℓ1 penalties: equality rows (per m or rad; the starting value, raised during a solve to
    /// follow the multipliers, see the module doc), clearances and balance (per m), capacity.
    pub mu_eq: f64,
    pub mu_geo: f64,
    pub mu_cap: f64,
    /// Damping of the posture step \[1/rad²\].
    pub damping: f64,
    /// Contacts closer than this enter the QP \[m\].
    pub contact_horizon_m: f64,
    /// Clearance rows reserved in the QP (the closest contacts are kept).
    pub clearance_rows: usize,
    /// Quadratic penalty of the equality rows' slacks (per m² or rad²).
    pub mu_eq_quadratic: f64,
    /// The QP solver's precision.
    pub precision: QpPrecision,
}

impl Default for SqpSettings {
    fn default() -> Self {
        SqpSettings {
            max_iterations: 60,
            step_box_rad: 0.5,
            step_box_m: 0.2,
            tol_kkt: 1e-5,
            mu_eq: 1.0,
            mu_geo: 1e3,
            mu_cap: 1e2,
            damping: 1e-4,
            contact_horizon_m: 0.10,
            clearance_rows: 12,
            mu_eq_quadratic: 1e8,
            precision: QpPrecision::default(),
        }
    }
}

/// Why a solve stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Stop {
    /// The KKT residual is below the tolerance.
    #[default]
    Converged,
    /// The iteration limit was reached.
    IterationLimit,
    /// No step along the QP's direction (nor its second-order correction) lowers the merit.
    LineSearch,
    /// The QP solver failed.
    QpFailed,
}

/// Outcome of one phase's SQP.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct SqpOutcome {
    pub converged: bool,
    pub stop: Stop,
    pub iterations: usize,
    pub qp_solves: usize,
    pub kkt_residual: f64,
    pub stationarity: f64,
    pub feasibility: f64,
    pub complementarity: f64,
    /// The objective J at the solution (fatigue cost + discomfort).
    pub objective: f64,
    /// Largest hand error \[m\].
    pub hand_error_m: f64,
    /// Smallest clearance \[m\] (contacts within the horizon; the horizon if none).
    pub min_clearance_m: f64,
    /// Balance margin \[m\] (standing bodies; infinity otherwise).
    pub balance_margin_m: f64,
}

/// A solve that stops short of the tolerance — no step lowers the merit function, or the
/// iteration limit — counts as stationary at a feasible point (constraint violation at most
/// [`STALL_FEASIBILITY`]) whose KKT residual is at most this: 100 × the default tolerance. There
/// the objective's own rounding, not the solver, holds the descent up (the shipped tasks' stalls
/// end with feasibility ~1e-16 and residuals 1e-5..1e-4; at the iteration limit, shelf_lowered's
/// 'carry' at QP tolerance 1e-8 ends at 1.07e-5 with the same posture and total as the converged
/// solve at 1e-9). Why the solver stopped says nothing more about the point than its residual.
pub const STALL_KKT: f64 = 1e-3;
/// See [`STALL_KKT`].
pub const STALL_FEASIBILITY: f64 = 1e-6;

impl SqpOutcome {
    /// Whether the solve's answer is determined: converged, or stopped (no descent, or the
    /// iteration limit) at a numerically stationary, feasible point ([`STALL_KKT`]). A failed QP,
    /// or a stop far from stationarity, is not.
    pub fn determined(&self) -> bool {
        self.converged
            || (matches!(self.stop, Stop::LineSearch | Stop::IterationLimit)
                && self.feasibility <= STALL_FEASIBILITY
                && self.kkt_residual <= STALL_KKT)
    }
}

/// One phase's problem.
pub struct PhaseProblem<'a> {
    pub targets_m: [Option<Vector3<f64>>; 2],
    pub hand_force_n: [Vector3<f64>; 2],
    pub cost: &'a mut dyn LoadCost,
    pub discomfort: &'a Discomfort,
    pub discomfort_weight: f64,
    /// The discomfort's shape (its zones' and end penalty's weights).
    pub shape: Shape,
    /// Capacity bound per half-joint (the load it may hold).
    pub capacity: &'a [f64],
    /// Where the worker looks (`None`: anywhere).
    pub gaze_m: Option<Vector3<f64>>,
    /// The cost of the steps to and from the neighbouring phases.
    pub stepping: &'a Stepping,
    /// The acceptable posture zones (`None`: unconstrained).
    pub zones: Option<ZoneLimits>,
    /// The phase's held objects, obstacles to the body other than the arms (`None`: none).
    pub held: Option<&'a Workstation>,
}

/// Buffers and the QP of one task.
pub struct SqpWork {
    pub qp: PostureQp,
    pub settings: SqpSettings,
    /// The equality rows' ℓ1 penalty of the solve under way (starts at `settings.mu_eq`).
    mu_eq: f64,
    /// Scratch of [`keep_model_positive`] (n × n).
    model: nalgebra::DMatrix<f64>,
    /// The explicit curvature (row-major n × n, [`explicit_curvature`]) and its scratch: the
    /// load cost's exact diagonal curvature, each half-joint's load gradient in q (nh × n), the
    /// loads' share of J's gradient in q, a dense MVC gradient, the MVC's second derivatives;
    /// the posture moved and the step cost's gradient either side (differences).
    hess: Vec<f64>,
    load_curv: Vec<f64>,
    df_dq: Vec<f64>,
    v_dq: Vec<f64>,
    m_dense: Vec<f64>,
    mvc_hess: Vec<(usize, usize, f64)>,
    q_fd: Vec<f64>,
    g_plus: Vec<f64>,
    g_minus: Vec<f64>,
    f: Vec<f64>,
    grad: Vec<f64>,
    curv: Vec<f64>,
    dq_grad: Vec<f64>,
    dq_curv: Vec<f64>,
    row: Vec<f64>,
    x0: Vec<f64>,
    stat: Vec<f64>,
    ax: Vec<f64>,
    q_trial: Vec<f64>,
    mvc_grad: Vec<(usize, f64)>,
    /// Equality residuals at the current point (targets then feet), for the SOC.
    eq_res: Vec<f64>,
    /// Damped BFGS approximation of the Lagrangian's curvature in q beyond the discomfort's
    /// exact diagonal (row-major n × n), and the last iterate's q, Lagrangian gradient and duals.
    bfgs: Vec<f64>,
    last_q: Vec<f64>,
    last_grad_l: Vec<f64>,
    last_z: Vec<f64>,
    /// The last iterate's contacts, row by row (link, other side), and a scratch of their
    /// multipliers.
    last_contacts: Vec<(usize, (u8, usize))>,
    z_scratch: Vec<f64>,
    have_last: bool,
    first_update: bool,
    reset_once: bool,
    grad_l: Vec<f64>,
    bs: Vec<f64>,
    /// Scratch of the BFGS update (step, gradient change, damped change) and of the line
    /// search (the scaled step, the trial before its correction), posture-sized; and of the
    /// predicted decrease, QP-variable-sized.
    sv: Vec<f64>,
    y: Vec<f64>,
    r: Vec<f64>,
    step: Vec<f64>,
    q_plain: Vec<f64>,
    xr: Vec<f64>,
    px: Vec<f64>,
    /// The posture zones' evaluator (`None`: the body is not the generated worker) and its
    /// rows' gradients.
    zone_work: Option<ZoneWork>,
    zone_grad: [Vec<f64>; ZONE_ROWS],
}

/// Merit terms of a posture.
#[derive(Debug, Clone, Copy, Default)]
struct Merit {
    phi: f64,
    j: f64,
    eq_l1: f64,
    eq_inf: f64,
    geo: f64,
    cap: f64,
    hand_err: f64,
    min_clear: f64,
    margin: f64,
    /// The posture zones' rows and the sum of their violations \[rad\].
    zone_g: [f64; ZONE_ROWS],
    zone_l1: f64,
}

impl SqpWork {
    pub fn new(task: &Task, scene: &Scene, settings: SqpSettings) -> Result<Self, QpError> {
        let n = task.model.nq();
        let a = scene.actuated.len();
        let m = 6 + task
            .stance
            .as_ref()
            .map_or(0, |st| 12 + usize::from(st.seat.is_some()));
        let e = geometry_row_count(task);
        let sizes = QpSizes {
            n,
            a,
            m,
            c: 2 * a,
            k: settings.clearance_rows,
            e,
            z: ZONE_ROWS,
        };
        let nh = task.half_joints.len();
        // each capacity row's posture variables: those its strength curve depends on
        let capacity_q: Vec<(usize, usize)> = task
            .half_joints
            .iter()
            .filter_map(|hj| {
                let row = scene.actuated_row[hj.q_index]?;
                let split = match hj.direction {
                    Direction::Positive => row,
                    Direction::Negative => a + row,
                };
                Some(
                    hj.posture
                        .iter()
                        .flat_map(|p| p.q_indices.iter())
                        .map(move |&k| (split, k)),
                )
            })
            .flatten()
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .collect();
        Ok(SqpWork {
            qp: PostureQp::new(sizes, settings.precision, &capacity_q)?,
            settings,
            mu_eq: settings.mu_eq,
            model: nalgebra::DMatrix::zeros(n, n),
            hess: vec![0.0; n * n],
            load_curv: vec![0.0; nh],
            df_dq: vec![0.0; nh * n],
            v_dq: vec![0.0; n],
            m_dense: vec![0.0; n],
            mvc_hess: Vec::with_capacity(16),
            q_fd: vec![0.0; n],
            g_plus: vec![0.0; n],
            g_minus: vec![0.0; n],
            f: vec![0.0; nh],
            grad: vec![0.0; nh],
            curv: vec![0.0; nh],
            dq_grad: vec![0.0; n],
            dq_curv: vec![0.0; n],
            row: vec![0.0; n],
            x0: vec![0.0; sizes.cols().n_var],
            stat: vec![0.0; sizes.cols().n_var],
            ax: vec![0.0; sizes.rows().n_row],
            q_trial: vec![0.0; n],
            mvc_grad: Vec::with_capacity(4),
            eq_res: vec![0.0; m],
            bfgs: vec![0.0; n * n],
            last_q: vec![0.0; n],
            last_grad_l: vec![0.0; n],
            last_z: vec![0.0; sizes.rows().n_row],
            last_contacts: Vec::with_capacity(settings.clearance_rows),
            z_scratch: vec![0.0; settings.clearance_rows],
            have_last: false,
            first_update: true,
            reset_once: false,
            grad_l: vec![0.0; n],
            bs: vec![0.0; n],
            sv: vec![0.0; n],
            y: vec![0.0; n],
            r: vec![0.0; n],
            step: vec![0.0; n],
            q_plain: vec![0.0; n],
            xr: vec![0.0; sizes.cols().n_var],
            px: vec![0.0; sizes.cols().n_var],
            zone_work: ZoneWork::new(&task.model),
            zone_grad: std::array::from_fn(|_| vec![0.0; n]),
        })
    }
}

/// Equality residuals (target − actual) at the posture in `pw` (after its statics): 3 per hand
/// (zero for a free hand), then 6 per foot, then the seat's height; into `out`.
fn equality_residuals(
    task: &Task,
    pw: &PostureWork,
    targets: &[Option<Vector3<f64>>; 2],
    out: &mut [f64],
) {
    for h in 0..2 {
        let r = match (targets[h], pw.hand_position(task, h)) {
            (Some(t), Some(p)) => t - p,
            _ => Vector3::zeros(),
        };
        out[3 * h..3 * h + 3].copy_from_slice(r.as_slice());
    }
    if task.stance.is_some() {
        for i in 0..2 {
            let (dp, dr) = pw.foot_error(task, i);
            out[6 + 6 * i..9 + 6 * i].copy_from_slice(dp.as_slice());
            out[9 + 6 * i..12 + 6 * i].copy_from_slice(dr.as_slice());
        }
    }
    if let Some(dz) = pw.seat_error(task) {
        out[18] = dz;
    }
}

fn merit(
    task: &Task,
    scene: &Scene,
    pw: &mut PostureWork,
    work: &mut SqpWork,
    prob: &mut PhaseProblem,
    q: &[f64],
) -> Merit {
    let s = work.settings;
    pw.statics(task, q, &prob.hand_force_n);
    pw.half_joint_loads(task, q, &mut work.f);
    let steps = pw
        .ground
        .map_or(0.0, |g| prob.stepping.value(task, &g.feet));
    let mut zone_g = [0.0; ZONE_ROWS];
    let mut zone_l1 = 0.0;
    if let (Some(z), Some(lim)) = (&work.zone_work, &prob.zones) {
        z.rows(&task.model, &pw.data, q, lim, &mut zone_g);
        zone_l1 = zone_g.iter().map(|g| g.max(0.0)).sum();
    }
    let j = prob.cost.value(&work.f)
        + prob.discomfort_weight * prob.discomfort.value(q, prob.shape)
        + steps
        + ZONE_PENALTY_PER_RAD * zone_l1;
    let mut res = std::mem::take(&mut work.eq_res);
    equality_residuals(task, pw, &prob.targets_m, &mut res);
    let eq_l1: f64 = res.iter().map(|x| x.abs()).sum();
    let eq_inf = res.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let hand_err = (0..2)
        .filter(|&h| prob.targets_m[h].is_some())
        .map(|h| Vector3::new(res[3 * h], res[3 * h + 1], res[3 * h + 2]).norm())
        .fold(0.0, f64::max);
    work.eq_res = res;
    let min_clear = pw.clearances(task, scene, s.contact_horizon_m, prob.held);
    let clear_viol = (task.objective.clearance_m - min_clear).max(0.0);
    let margin = pw.ground.map(|g| g.margin_m).unwrap_or(f64::INFINITY);
    let bal_viol = (task.objective.balance_margin_m - margin).max(0.0);
    let place_viol = match (&task.stance, pw.ground) {
        (Some(st), Some(g)) => st.placement.as_ref().map_or(0.0, |pl| {
            pl.violation_m(
                &g.feet,
                0.5 * (st.feet[0].half_length_m + st.feet[1].half_length_m),
            )
        }),
        _ => 0.0,
    };
    let gaze_viol = match (&task.head, &prob.gaze_m) {
        (Some(h), Some(t)) => pw.gaze(task, h, t).0.max(0.0),
        _ => 0.0,
    };
    let geo = clear_viol.max(bal_viol).max(place_viol).max(gaze_viol);
    let mut cap = 0.0f64;
    for (h, &f) in work.f.iter().enumerate() {
        let bound = match prob.cost.capacity_bound(h, f) {
            Some((c, _)) => c.min(prob.capacity[h]),
            None => prob.capacity[h],
        };
        cap = cap.max(f - bound);
    }
    let cap = cap.max(0.0);
    Merit {
        phi: j + work.mu_eq * eq_l1 + s.mu_geo * geo + s.mu_cap * cap,
        j,
        eq_l1,
        eq_inf,
        geo,
        cap,
        hand_err,
        min_clear: if min_clear.is_finite() {
            min_clear
        } else {
            s.contact_horizon_m
        },
        margin,
        zone_g,
        zone_l1,
    }
}

/// Largest step of a joint per iteration.
fn step_box(s: SqpSettings, kind: crate::body::JointKind) -> f64 {
    if kind == crate::body::JointKind::Prismatic {
        s.step_box_m
    } else {
        s.step_box_rad
    }
}

/// The objective's explicit dependence on the posture at `q`, after the statics of `q` in
/// `pw`: the load cost's gradient and curvature in the half-joints' loads (`work.grad`,
/// `work.curv`), and the QP's linear term in Δq (`work.dq_grad`) — the discomfort's gradient plus
/// the strength's posture dependence, `−∂J/∂f_h · s̄_h ∂MVC_h/∂q / MVC_h²` with the torque `s̄_h`
/// held (the torques are QP variables) — with the discomfort's diagonal curvature (`work.dq_curv`).
fn posture_terms(
    task: &Task,
    scene: &Scene,
    pw: &PostureWork,
    work: &mut SqpWork,
    prob: &mut PhaseProblem,
    q: &[f64],
) {
    pw.half_joint_loads(task, q, &mut work.f);
    prob.cost.eval(&work.f, &mut work.grad, &mut work.curv);
    work.dq_grad.iter_mut().for_each(|x| *x = 0.0);
    work.dq_curv.iter_mut().for_each(|x| *x = 0.0);
    prob.discomfort.eval(
        q,
        prob.discomfort_weight,
        prob.shape,
        &mut work.dq_grad,
        &mut work.dq_curv,
    );
    if let Some(g) = pw.ground {
        prob.stepping
            .add_gradient(task, &pw.data, &g.feet, &mut work.dq_grad);
    }
    for (h, hj) in task.half_joints.iter().enumerate() {
        if scene.actuated_row[hj.q_index].is_none() || !hj.posture_dependent() {
            continue;
        }
        let tau = pw.data.tau_nm[hj.q_index];
        let s_bar = match hj.direction {
            Direction::Positive => tau.max(0.0),
            Direction::Negative => (-tau).max(0.0),
        };
        if s_bar > 0.0 {
            let mvc = hj.mvc_at(q);
            hj.mvc_gradient(q, &mut work.mvc_grad);
            for &(k, dm) in &work.mvc_grad {
                work.dq_grad[k] -= work.grad[h] * s_bar * dm / (mvc * mvc);
            }
        }
    }
}

/// Smallest eigenvalue of the curvature a solve starts from \[1/rad²\].
const START_CURVATURE_FLOOR: f64 = 1e-3;

/// Finite-difference step of the step cost's share of the starting curvature \[rad or m\].
const START_CURVATURE_STEP: f64 = 1e-6;

/// The Jacobian of the explicit posture gradient of [`posture_terms`] (row-major n × n,
/// `work.hess[i·n + k] = ∂g_i/∂q_k`) at `q`, after [`build_qp`] there (the statics of `q`, their
/// Jacobian `∂τ/∂q` and the loads in `pw` and `work`), less the discomfort's diagonal (the QP
/// adds it exactly; its curvature is exact and the discomfort separable, so nothing of it is
/// left). The strength's share `g_i = −Σ_h a_h ∂M_h/∂q_i`, `a_h = G_h s̄_h / M_h²` (G = ∂J/∂f,
/// s̄ the torque held, M the MVC), is differentiated analytically:
/// `∂g_i/∂q_k = −Σ_h (∂a_h/∂q_k ∂M_h/∂q_i + a_h ∂²M_h/∂q_i∂q_k)` with
/// `∂a_h/∂q_k = ∂G_h/∂q_k s̄_h/M_h² + G_h ∂s̄_h/∂q_k /M_h² − 2 G_h s̄_h ∂M_h/∂q_k /M_h³`, and
/// `∂G_h/∂q_k = Σ_l ∂²J/∂f_h∂f_l ∂f_l/∂q_k` through the loads `f_l = s̄_l/M_l` of every
/// half-joint (the load cost's exact curvature, [`LoadCost::exact_curvature`]). The step cost's
/// share (placed feet) by central differences of its gradient (kinematics only).
fn explicit_curvature(
    task: &Task,
    scene: &Scene,
    pw: &mut PostureWork,
    work: &mut SqpWork,
    prob: &mut PhaseProblem,
    q: &[f64],
) {
    let n = task.model.nq();
    work.hess.iter_mut().for_each(|x| *x = 0.0);
    let c = prob
        .cost
        .exact_curvature(&work.f, &mut work.grad, &mut work.load_curv);
    // ∂f_h/∂q for every half-joint, and ∂J_loads/∂q = Σ_h G_h ∂f_h/∂q
    work.v_dq.iter_mut().for_each(|x| *x = 0.0);
    for (h, hj) in task.half_joints.iter().enumerate() {
        let row = &mut work.df_dq[h * n..(h + 1) * n];
        let sigma = hj.direction.sign();
        let held = sigma * pw.data.tau_nm[hj.q_index];
        if held <= 0.0 {
            row.iter_mut().for_each(|x| *x = 0.0);
            continue;
        }
        let mvc = hj.mvc_at(q);
        for (k, x) in row.iter_mut().enumerate() {
            *x = sigma * pw.dtau_dq[(hj.q_index, k)] / mvc;
        }
        if hj.posture_dependent() {
            hj.mvc_gradient(q, &mut work.mvc_grad);
            for &(k, dm) in &work.mvc_grad {
                row[k] -= held * dm / (mvc * mvc);
            }
        }
        for (v, x) in work.v_dq.iter_mut().zip(row.iter()) {
            *v += work.grad[h] * x;
        }
    }
    for (h, hj) in task.half_joints.iter().enumerate() {
        let sigma = hj.direction.sign();
        let held = sigma * pw.data.tau_nm[hj.q_index];
        if scene.actuated_row[hj.q_index].is_none() || !hj.posture_dependent() || held <= 0.0 {
            continue;
        }
        let g = work.grad[h];
        let mvc = hj.mvc_at(q);
        let (m2, m3) = (mvc * mvc, mvc * mvc * mvc);
        hj.mvc_gradient(q, &mut work.mvc_grad);
        for &(k, dm) in &work.mvc_grad {
            work.m_dense[k] = dm;
        }
        for k in 0..n {
            let dg = work.load_curv[h] * work.df_dq[h * n + k] - c * g * work.v_dq[k];
            let ds = sigma * pw.dtau_dq[(hj.q_index, k)];
            let da = dg * held / m2 + g * ds / m2 - 2.0 * g * held * work.m_dense[k] / m3;
            for &(i, dm) in &work.mvc_grad {
                work.hess[i * n + k] -= da * dm;
            }
        }
        for &(k, _) in &work.mvc_grad {
            work.m_dense[k] = 0.0;
        }
        let a = g * held / m2;
        hj.mvc_hessian(q, &mut work.mvc_hess);
        for &(i, k, d2m) in &work.mvc_hess {
            work.hess[i * n + k] -= a * d2m;
        }
    }
    if pw.ground.is_some() && prob.stepping.is_active() {
        let mut qf = std::mem::take(&mut work.q_fd);
        let (mut gp, mut gm) = (
            std::mem::take(&mut work.g_plus),
            std::mem::take(&mut work.g_minus),
        );
        qf.copy_from_slice(q);
        for k in 0..n {
            let j = task.model.q_joint(k);
            let hi = (q[k] + START_CURVATURE_STEP).min(j.upper_rad);
            let lo = (q[k] - START_CURVATURE_STEP).max(j.lower_rad);
            for (x, g) in [(lo, &mut gm), (hi, &mut gp)] {
                qf[k] = x;
                pw.statics(task, &qf, &prob.hand_force_n);
                g.iter_mut().for_each(|v| *v = 0.0);
                if let Some(r) = pw.ground {
                    prob.stepping.add_gradient(task, &pw.data, &r.feet, g);
                }
            }
            qf[k] = q[k];
            for i in 0..n {
                work.hess[i * n + k] += (gp[i] - gm[i]) / (hi - lo);
            }
        }
        (work.q_fd, work.g_plus, work.g_minus) = (qf, gp, gm);
        pw.statics(task, q, &prob.hand_force_n);
    }
}

/// The curvature a solve starts from, into the BFGS part: [`explicit_curvature`] symmetrised,
/// with its eigenvalues raised to [`START_CURVATURE_FLOOR`]. It is the Lagrangian's curvature in
/// q with the multipliers at zero: it leaves out only what the constraints' curvature adds (the
/// torques' and the hands' second derivatives), which BFGS learns along the steps. One
/// eigendecomposition per solve. Called after [`build_qp`] at `q`.
fn start_curvature(
    task: &Task,
    scene: &Scene,
    pw: &mut PostureWork,
    work: &mut SqpWork,
    prob: &mut PhaseProblem,
    q: &[f64],
) {
    let n = task.model.nq();
    explicit_curvature(task, scene, pw, work, prob, q);
    raise_eigenvalues(n, &work.hess, |_| 0.0, &mut work.bfgs);
    work.first_update = false;
    work.have_last = false;
}

/// Fills the QP at posture `q` (linearisation in `pw`, contacts in `pw.contacts`).
fn build_qp(
    task: &Task,
    scene: &Scene,
    pw: &mut PostureWork,
    work: &mut SqpWork,
    prob: &mut PhaseProblem,
    q: &[f64],
) {
    let s = work.settings;
    pw.linearise(task, q, &prob.hand_force_n);
    posture_terms(task, scene, pw, work, prob, q);
    let mut res = std::mem::take(&mut work.eq_res);
    equality_residuals(task, pw, &prob.targets_m, &mut res);
    pw.clearances(task, scene, s.contact_horizon_m, prob.held);
    pw.contacts
        .sort_by(|a, b| a.distance_m.total_cmp(&b.distance_m));
    pw.contacts.truncate(s.clearance_rows);

    let n = task.model.nq();
    let qp = &mut work.qp;
    qp.clear();
    let (c, r) = (qp.cols, qp.rows);
    let sz = qp.sizes;
    // Posture terms: discomfort and damping, and the strength's posture dependence.
    for k in 0..n {
        qp.q[c.dq + k] = work.dq_grad[k];
    }
    // Capacity rows, one per half-joint: f − c(f) ≤ 0 linearised at f̄ in the half-joint's own
    // load, (1 − c′) f ≤ c(f̄) − c′ f̄, with f = s/MVC(q) to first order in the torque-split
    // variable s and in the few joints the strength curve depends on (without the latter the
    // QP's steps walked into the bound where a strength curve falls: the line search then
    // stalled).
    for i in 0..sz.c {
        let rr = r.cap + i;
        qp.set_a(rr, c.v_cap, -1.0);
        qp.b[rr] = 1e3;
    }
    for (h, hj) in task.half_joints.iter().enumerate() {
        let Some(row) = scene.actuated_row[hj.q_index] else {
            continue;
        };
        let mvc = hj.mvc_at(q);
        let tau = pw.data.tau_nm[hj.q_index];
        let (split, s_bar) = match hj.direction {
            Direction::Positive => (row, tau.max(0.0)),
            Direction::Negative => (sz.a + row, (-tau).max(0.0)),
        };
        let col = c.s_plus + split;
        let gs = work.grad[h] / mvc;
        let hs = work.curv[h] / (mvc * mvc);
        qp.p_diag[col] = hs.max(1e-12);
        qp.q[col] = gs - hs * s_bar;
        let (bound, slope) = match prob.cost.capacity_bound(h, work.f[h]) {
            Some((cb, d)) if cb < prob.capacity[h] => (cb, d),
            _ => (prob.capacity[h], 0.0),
        };
        let rr = r.cap + split;
        qp.set_a(rr, col, (1.0 - slope) / mvc);
        qp.b[rr] = bound - slope * work.f[h];
        // the load s/MVC(q) to first order in the posture too: −s̄ ∂MVC/∂q / MVC²
        if hj.posture_dependent() && s_bar > 0.0 {
            hj.mvc_gradient(q, &mut work.mvc_grad);
            for &(k, dm) in &work.mvc_grad {
                qp.set_a(rr, c.dq + k, -(1.0 - slope) * s_bar * dm / (mvc * mvc));
            }
        }
    }
    // Torque split rows.
    for (row, &j) in scene.actuated.iter().enumerate() {
        for k in 0..n {
            qp.set_a(r.torque + row, c.dq + k, pw.dtau_dq[(j, k)]);
        }
        qp.set_a(r.torque + row, c.s_plus + row, -1.0);
        qp.set_a(r.torque + row, c.s_minus + row, 1.0);
        qp.b[r.torque + row] = -pw.data.tau_nm[j];
    }
    // Equality rows with elastic slacks.
    for h in 0..2 {
        if prob.targets_m[h].is_some() {
            pw.hand_jacobian(task, h);
            for d in 0..3 {
                for k in 0..n {
                    qp.set_a(r.eq + 3 * h + d, c.dq + k, pw.jac[(d, k)]);
                }
            }
        }
    }
    if task.stance.is_some() {
        for i in 0..2 {
            pw.foot_jacobians(task, i);
            for d in 0..3 {
                for k in 0..n {
                    qp.set_a(r.eq + 6 + 6 * i + d, c.dq + k, pw.jac[(d, k)]);
                    qp.set_a(r.eq + 9 + 6 * i + d, c.dq + k, pw.jac2[(d, k)]);
                }
            }
        }
        if pw.seat_jacobian(task) {
            for k in 0..n {
                qp.set_a(r.eq + 18, c.dq + k, pw.jac[(2, k)]);
            }
        }
    }
    // ... split by sign at the ℓ1 penalty of the merit: a target is given up only where the
    // merit gives it up.
    let e_rows = r.nonneg + 2 * sz.a + 2 + sz.z;
    for i in 0..sz.m {
        qp.set_a(r.eq + i, c.e + i, 1.0);
        qp.set_a(r.eq + i, c.e + sz.m + i, -1.0);
        qp.set_a(e_rows + i, c.e + i, -1.0);
        qp.set_a(e_rows + sz.m + i, c.e + sz.m + i, -1.0);
        qp.b[r.eq + i] = res[i];
        for col in [c.e + i, c.e + sz.m + i] {
            qp.p_diag[col] = 2.0 * s.mu_eq_quadratic;
            qp.q[col] = work.mu_eq;
        }
    }
    work.eq_res = res;
    // Non-negativity of the torques and the slacks.
    for i in 0..2 * sz.a {
        qp.set_a(r.nonneg + i, c.s_plus + i, -1.0);
    }
    qp.set_a(r.nonneg + 2 * sz.a, c.v_cap, -1.0);
    qp.set_a(r.nonneg + 2 * sz.a + 1, c.v_geo, -1.0);
    qp.q[c.v_cap] = s.mu_cap;
    qp.q[c.v_geo] = s.mu_geo;
    qp.p_diag[c.v_cap] = 1e-6;
    qp.p_diag[c.v_geo] = 1e-6;
    // Joint limits: one row per joint, for its nearer limit within the step box; the step box
    // on both sides is applied to the step afterwards.
    for k in 0..n {
        let j = task.model.q_joint(k);
        let (up, down) = (j.upper_rad - q[k], q[k] - j.lower_rad);
        if up <= down {
            qp.set_a(r.limit + k, c.dq + k, 1.0);
            qp.b[r.limit + k] = up.clamp(0.0, 1e3);
        } else {
            qp.set_a(r.limit + k, c.dq + k, -1.0);
            qp.b[r.limit + k] = down.clamp(0.0, 1e3);
        }
    }
    // Clearances: d + ∇d·Δq ≥ d_min  ⇔  −∇d·Δq − v ≤ d − d_min (unused rows: 0 ≤ 1).
    let contacts = std::mem::take(&mut pw.contacts);
    for row in 0..sz.k {
        let rr = r.clearance + row;
        qp.set_a(rr, c.v_geo, -1.0);
        match contacts.get(row) {
            Some(ct) => {
                pw.contact_gradient(task, ct, &mut work.row);
                for k in 0..n {
                    qp.set_a(rr, c.dq + k, -work.row[k]);
                }
                qp.b[rr] = ct.distance_m - task.objective.clearance_m;
            }
            None => qp.b[rr] = 1.0,
        }
    }
    pw.contacts = contacts;
    // Standing rows (balance, and the placed feet's area and ranges): g + ∇g·Δq − v ≤ 0
    // (unused rows: 0 ≤ 1).
    let mut row = 0;
    pw.geometry_rows(task, prob.gaze_m.as_ref(), |_, g, grad| {
        let rr = r.balance + row;
        for (k, v) in grad.iter().enumerate().take(n) {
            qp.set_a(rr, c.dq + k, *v);
        }
        qp.set_a(rr, c.v_geo, -1.0);
        qp.b[rr] = -g;
        row += 1;
    });
    debug_assert!(row <= sz.e);
    for rr in r.balance + row..r.balance + sz.e {
        qp.set_a(rr, c.v_geo, -1.0);
        qp.b[rr] = 1.0;
    }
    // Posture zones, each with its own slack: g + ∇g·Δq − v_i ≤ 0, v_i ≥ 0 at the zones'
    // penalty per radian (unused rows: 0 ≤ 1).
    let mut g = [0.0; ZONE_ROWS];
    let zones = match (work.zone_work.as_mut(), prob.zones.as_ref()) {
        (Some(z), Some(lim)) => {
            z.rows_and_gradients(&task.model, q, lim, &mut g, &mut work.zone_grad);
            true
        }
        _ => false,
    };
    for i in 0..sz.z {
        let rr = r.zone + i;
        qp.set_a(rr, c.v_zone + i, -1.0);
        qp.set_a(r.nonneg + 2 * sz.a + 2 + i, c.v_zone + i, -1.0);
        qp.q[c.v_zone + i] = ZONE_PENALTY_PER_RAD;
        qp.p_diag[c.v_zone + i] = 1e-6;
        if zones {
            for k in 0..n {
                qp.set_a(rr, c.dq + k, work.zone_grad[i][k]);
            }
            qp.b[rr] = -g[i];
        } else {
            qp.b[rr] = 1.0;
        }
    }
}

/// Largest diagonal entry of the BFGS part before it is reset \[1/rad²\].
const BFGS_LARGEST: f64 = 1e4;

/// Initial curvature of the BFGS part \[1/rad²\] (scale of J's curvature in q).
const BFGS_INITIAL: f64 = 0.05;

/// Forgets the learnt curvature.
fn reset_curvature(work: &mut SqpWork) {
    let n = work.qp.sizes.n;
    work.have_last = false;
    work.first_update = true;
    work.bfgs.iter_mut().for_each(|x| *x = 0.0);
    for k in 0..n {
        work.bfgs[k * n + k] = BFGS_INITIAL;
    }
}

/// Gradient of the Lagrangian in q at the QP just built, with duals `z`: `q_q + A_qᵀ z`.
fn lagrangian_gradient(work: &mut SqpWork, z_from_last: bool) {
    let n = work.qp.sizes.n;
    let z = if z_from_last {
        &work.last_z
    } else {
        &work.qp.z
    };
    work.qp.at_z_posture(z, &mut work.grad_l);
    for k in 0..n {
        work.grad_l[k] += work.qp.q[work.qp.cols.dq + k];
    }
}

/// Damped BFGS update (Powell) of the curvature model `B + D` with the step since the last
/// iterate (`D` the discomfort's exact diagonal, here; the update goes to `B`), the model kept
/// positive definite, then the QP's posture block of P: `B + D` + damping. The gradient
/// change is the Lagrangian's with the last QP's multipliers at both iterates, each clearance
/// multiplier on the row of its own contact ([`match_clearance_duals`]): with a multiplier left
/// on a row that holds another contact now, the pair saw curvature of the wrong sign and the
/// damping stalled the solves (pallet's lift ended at the iteration limit).
fn update_curvature(work: &mut SqpWork, q: &[f64]) {
    let n = work.qp.sizes.n;
    if work.have_last {
        lagrangian_gradient(work, true);
        let (mut sv, mut y, mut r) = (
            std::mem::take(&mut work.sv),
            std::mem::take(&mut work.y),
            std::mem::take(&mut work.r),
        );
        for k in 0..n {
            sv[k] = q[k] - work.last_q[k];
        }
        // the pair of the whole model B + D (D the discomfort's exact diagonal here)
        for k in 0..n {
            y[k] = work.grad_l[k] - work.last_grad_l[k];
        }
        if work.first_update {
            // Shanno–Phua: scale the initial B to the curvature seen along the first step
            // beyond the discomfort's
            for k in 0..n {
                r[k] = y[k] - work.dq_curv[k] * sv[k];
            }
            let sr: f64 = (0..n).map(|i| sv[i] * r[i]).sum();
            if sr > 1e-16 {
                let rr: f64 = r.iter().map(|v| v * v).sum();
                let scale = (rr / sr).clamp(1e-4, 1e4);
                for i in 0..n {
                    for j in 0..n {
                        work.bfgs[i * n + j] = if i == j { scale } else { 0.0 };
                    }
                }
            }
        }
        work.first_update = false;
        for i in 0..n {
            work.bs[i] =
                (0..n).map(|j| work.bfgs[i * n + j] * sv[j]).sum::<f64>() + work.dq_curv[i] * sv[i];
        }
        let sbs: f64 = (0..n).map(|i| sv[i] * work.bs[i]).sum();
        let sy: f64 = (0..n).map(|i| sv[i] * y[i]).sum();
        if sbs > 1e-16 {
            let theta = if sy >= 0.2 * sbs {
                1.0
            } else {
                0.8 * sbs / (sbs - sy)
            };
            for i in 0..n {
                r[i] = theta * y[i] + (1.0 - theta) * work.bs[i];
            }
            let sr: f64 = (0..n).map(|i| sv[i] * r[i]).sum();
            if sr > 1e-16 {
                for i in 0..n {
                    for j in 0..n {
                        work.bfgs[i * n + j] += r[i] * r[j] / sr - work.bs[i] * work.bs[j] / sbs;
                    }
                }
            }
        }
        (work.sv, work.y, work.r) = (sv, y, r);
    }
    // A curvature far beyond the problem's scale comes from steps across kinks (a torque
    // changing sign, a contact or capacity row switching): it freezes the steps. Start again.
    let largest = (0..n).map(|k| work.bfgs[k * n + k]).fold(0.0f64, f64::max);
    if largest > BFGS_LARGEST {
        reset_curvature(work);
    }
    keep_model_positive(work);
    let damping = work.settings.damping;
    let qp = &mut work.qp;
    for i in 0..n {
        for j in 0..n {
            qp.p_dq[i * n + j] = work.bfgs[i * n + j];
        }
        qp.p_dq[i * n + i] += work.dq_curv[i] + damping;
    }
}

/// The share of the discomfort's exact curvature `D` the curvature model keeps whatever BFGS
/// learns: `B` may cancel the rest, not all of it. With `B + D` only positive definite, pallet's
/// grasp took steps so long along directions where `B` had cancelled `D` that the line search
/// stalled far from stationarity (KKT residual 0.41); keeping a quarter or a half of `D`, it
/// converges as before, and the shelf's plan takes 2450–2471 QPs instead of 2396 with none kept
/// and 3171 with `B` kept positive on its own (2026-12-07, session 11).
const MODEL_KEEPS_OF_DISCOMFORT: f64 = 0.5;

/// Keeps the curvature model above [`MODEL_KEEPS_OF_DISCOMFORT`] of the discomfort's curvature
/// `D`: `B + (1 − share)·D` positive definite, its eigenvalues at least
/// [`START_CURVATURE_FLOOR`]. `B` may carry negative curvature; `D` moves with the posture. A
/// Cholesky factorisation tells; only where it fails are the eigenvalues raised.
fn keep_model_positive(work: &mut SqpWork) {
    let n = work.qp.sizes.n;
    let d = |i: usize, work: &SqpWork| (1.0 - MODEL_KEEPS_OF_DISCOMFORT) * work.dq_curv[i];
    let mut m = std::mem::replace(&mut work.model, nalgebra::DMatrix::zeros(0, 0));
    for i in 0..n {
        for k in 0..n {
            m[(i, k)] = 0.5 * (work.bfgs[i * n + k] + work.bfgs[k * n + i])
                + if i == k {
                    d(i, work) - START_CURVATURE_FLOOR
                } else {
                    0.0
                };
        }
    }
    if let Some(c) = nalgebra::Cholesky::new(m) {
        work.model = c.unpack_dirty();
        return;
    }
    let bfgs = work.bfgs.clone();
    let shift: Vec<f64> = (0..n).map(|i| d(i, work)).collect();
    raise_eigenvalues(n, &bfgs, |i| shift[i], &mut work.bfgs);
    work.model = nalgebra::DMatrix::zeros(n, n);
}

/// `out = V·max(Λ, floor)·Vᵀ − S`, where `V Λ Vᵀ` is the eigendecomposition of the symmetric
/// part of the row-major `n × n` matrix `m` plus the diagonal `S` (`shift(i)` on row `i`): the
/// nearest matrix whose sum with `S` has its eigenvalues at least [`START_CURVATURE_FLOOR`].
/// Allocates (an eigendecomposition); called once per local solve and on the curvature model's
/// rare repairs.
fn raise_eigenvalues(n: usize, m: &[f64], shift: impl Fn(usize) -> f64, out: &mut [f64]) {
    let diag = |i: usize, k: usize| if i == k { shift(i) } else { 0.0 };
    let sym = nalgebra::DMatrix::from_fn(n, n, |i, k| {
        0.5 * (m[i * n + k] + m[k * n + i]) + diag(i, k)
    });
    let eig = sym.symmetric_eigen();
    let v = &eig.eigenvectors;
    for i in 0..n {
        for k in 0..n {
            out[i * n + k] = (0..n)
                .map(|e| v[(i, e)] * eig.eigenvalues[e].max(START_CURVATURE_FLOOR) * v[(k, e)])
                .sum::<f64>()
                - diag(i, k);
        }
    }
}

/// Remembers the iterate, its Lagrangian gradient and the duals for the next BFGS update.
fn remember_iterate(work: &mut SqpWork, contacts: &[Contact], q: &[f64]) {
    lagrangian_gradient(work, false);
    work.last_q.copy_from_slice(q);
    work.last_grad_l.copy_from_slice(&work.grad_l);
    work.last_z.copy_from_slice(&work.qp.z);
    work.last_contacts.clear();
    work.last_contacts
        .extend(contacts.iter().map(|c| (c.link, c.other.id())));
    work.have_last = true;
}

/// The last iterate's clearance multipliers moved to the rows of the same contacts at the new
/// iterate (the rows hold the closest contacts in order of distance, so a row may hold another
/// contact there): the BFGS pair must difference the Lagrangian of the same constraints. A
/// contact new at this iterate gets no multiplier.
fn match_clearance_duals(work: &mut SqpWork, contacts: &[Contact]) {
    if !work.have_last {
        return;
    }
    let r = work.qp.rows.clearance;
    let k = work.qp.sizes.k;
    work.z_scratch[..k].copy_from_slice(&work.last_z[r..r + k]);
    for slot in 0..k {
        let z = contacts
            .get(slot)
            .and_then(|c| {
                work.last_contacts
                    .iter()
                    .position(|&id| id == (c.link, c.other.id()))
            })
            .map_or(0.0, |i| work.z_scratch[i]);
        work.last_z[r + slot] = z;
    }
}

/// Raises the equality rows' penalty to twice the largest equality multiplier of the QP just
/// solved, rounded up to a power of two (so that small changes of the multipliers leave it
/// where it is), and the current merit with it. The penalty never falls during a solve.
fn raise_penalty(work: &mut SqpWork, m0: &mut Merit) {
    let r = work.qp.rows;
    let z_max = work.qp.z[r.eq..r.eq + work.qp.sizes.m]
        .iter()
        .fold(0.0f64, |a, z| a.max(z.abs()));
    let wanted = 2.0 * z_max;
    if wanted > work.mu_eq && wanted.is_finite() {
        let wanted = 2f64.powi(wanted.log2().ceil() as i32);
        m0.phi += (wanted - work.mu_eq) * m0.eq_l1;
        work.mu_eq = wanted;
    }
}

/// The current point in the QP's variables (no step, torques split, slacks at the violations).
fn current_point(task: &Task, scene: &Scene, pw: &PostureWork, work: &mut SqpWork, m: &Merit) {
    let c = work.qp.cols;
    work.x0.iter_mut().for_each(|x| *x = 0.0);
    for (row, &j) in scene.actuated.iter().enumerate() {
        let tau = pw.data.tau_nm[j];
        work.x0[c.s_plus + row] = tau.max(0.0);
        work.x0[c.s_minus + row] = (-tau).max(0.0);
    }
    for (i, r) in work.eq_res.iter().enumerate() {
        work.x0[c.e + i] = r.max(0.0);
        work.x0[c.e + work.qp.sizes.m + i] = (-r).max(0.0);
    }
    work.x0[c.v_cap] = m.cap;
    work.x0[c.v_geo] = m.geo;
    for (i, g) in m.zone_g.iter().enumerate() {
        work.x0[c.v_zone + i] = g.max(0.0);
    }
    let _ = task;
}

/// KKT residual at the current point with the QP's multipliers: (stationarity, complementarity).
fn kkt(work: &mut SqpWork) -> (f64, f64) {
    let qp = &work.qp;
    let c = qp.cols;
    qp.stationarity(&work.x0, &mut work.stat);
    let stationarity = work.stat[..c.e].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    qp.a_times(&work.x0, &mut work.ax);
    let r = qp.rows;
    // the penalty slacks' own bounds are not constraints of the problem
    let slack_rows = (r.nonneg + 2 * qp.sizes.a)..r.limit;
    let complementarity = (r.n_zero..r.n_row)
        .filter(|i| !slack_rows.contains(i))
        .map(|i| (qp.z[i] * (qp.b[i] - work.ax[i]).max(0.0)).abs())
        .fold(0.0f64, f64::max);
    (stationarity, complementarity)
}

/// The ℓ1 merit's decrease predicted by the QP's solution: the quadratic model of the objective
/// over the posture and torque variables, from the current point `x0` to the solution, plus each
/// penalty times the fall of its linearised violation (equality slacks `e`, `v_cap`, `v_geo`).
fn predicted_decrease(work: &mut SqpWork, m0: &Merit) -> f64 {
    let (mut xr, mut px) = (std::mem::take(&mut work.xr), std::mem::take(&mut work.px));
    let qp = &work.qp;
    let c = qp.cols;
    let s = work.settings;
    let e_after: f64 = qp.x[c.e..c.v_cap].iter().map(|v| v.abs()).sum();
    let objective = quadratic_model(qp, &work.x0, &mut xr, &mut px)
        - quadratic_model(qp, &qp.x, &mut xr, &mut px);
    (work.xr, work.px) = (xr, px);
    let zone_after: f64 = qp.x[c.v_zone..c.n_var].iter().map(|v| v.max(0.0)).sum();
    let violations = work.mu_eq * (m0.eq_l1 - e_after)
        + s.mu_geo * (m0.geo - qp.x[c.v_geo].max(0.0))
        + s.mu_cap * (m0.cap - qp.x[c.v_cap].max(0.0))
        + ZONE_PENALTY_PER_RAD * (m0.zone_l1 - zone_after);
    (objective + violations).max(0.0)
}

/// The QP objective's quadratic model over the posture and torque variables at `x` (its slack
/// entries left out), with scratch `xr` and `px` (QP-variable-sized).
fn quadratic_model(qp: &PostureQp, x: &[f64], xr: &mut [f64], px: &mut [f64]) -> f64 {
    let c = qp.cols;
    xr.copy_from_slice(x);
    xr[c.e..].iter_mut().for_each(|v| *v = 0.0);
    qp.p_times(xr, px);
    (0..c.e)
        .map(|i| 0.5 * px[i] * xr[i] + qp.q[i] * xr[i])
        .sum()
}

/// Optimises the posture `q` (in/out) of one phase.
pub fn solve_phase(
    task: &Task,
    scene: &Scene,
    pw: &mut PostureWork,
    work: &mut SqpWork,
    prob: &mut PhaseProblem,
    q: &mut [f64],
) -> Result<SqpOutcome, QpError> {
    let n = task.model.nq();
    let s = work.settings;
    for (k, qk) in q.iter_mut().enumerate() {
        let j = task.model.q_joint(k);
        *qk = qk.clamp(j.lower_rad, j.upper_rad);
    }
    let mut out = SqpOutcome::default();
    work.mu_eq = s.mu_eq;
    // a local solve is a function of its problem and start alone
    work.qp.forget_solver();
    let mut m0 = merit(task, scene, pw, work, prob, q);
    work.reset_once = false;
    let mut first = true;
    loop {
        build_qp(task, scene, pw, work, prob, q);
        if first {
            start_curvature(task, scene, pw, work, prob, q);
            first = false;
        }
        match_clearance_duals(work, &pw.contacts);
        update_curvature(work, q);
        out.qp_solves += 1;
        if !work.qp.solve()? {
            out.stop = Stop::QpFailed;
            break;
        }
        remember_iterate(work, &pw.contacts, q);
        raise_penalty(work, &mut m0);
        current_point(task, scene, pw, work, &m0);
        let (stat, comp) = kkt(work);
        let feas = m0.eq_inf.max(m0.geo);
        out.stationarity = stat;
        out.complementarity = comp;
        out.feasibility = feas;
        out.kkt_residual = stat.max(comp).max(feas);
        if out.kkt_residual <= s.tol_kkt {
            out.converged = true;
            out.stop = Stop::Converged;
            break;
        }
        if out.iterations >= s.max_iterations {
            out.stop = Stop::IterationLimit;
            break;
        }
        out.iterations += 1;
        // Predicted decrease of the ℓ1 merit by the QP's model: the objective's quadratic model
        // (posture and torque variables) plus the penalties times the fall of the linearised
        // violations (the QP's slacks) from their values now.
        let pred = predicted_decrease(work, &m0);
        // the step box: the whole step scaled (its direction kept), then the limits' far sides
        let scale = (0..n)
            .map(|k| work.qp.x[k].abs() / step_box(s, task.model.q_joint(k).kind))
            .fold(1.0f64, f64::max);
        let mut d = std::mem::take(&mut work.step);
        for (k, dk) in d.iter_mut().enumerate() {
            let j = task.model.q_joint(k);
            *dk = (q[k] + work.qp.x[k] / scale).clamp(j.lower_rad, j.upper_rad) - q[k];
        }
        let mut accepted = false;
        let mut alpha = 1.0;
        while alpha >= 1e-8 {
            for k in 0..n {
                work.q_trial[k] = q[k] + alpha * d[k];
            }
            let mut trial = std::mem::take(&mut work.q_trial);
            let enough = |m1: &Merit| {
                m1.phi <= m0.phi - 1e-4 * alpha * pred || (pred <= 1e-14 && m1.phi < m0.phi)
            };
            let mut m1 = merit(task, scene, pw, work, prob, &trial);
            if !enough(&m1) {
                // Second-order correction: back onto the curved targets and feet, and out of any
                // clearance or balance constraint the step crossed.
                let mut plain = std::mem::take(&mut work.q_plain);
                plain.copy_from_slice(&trial);
                restore(
                    task,
                    scene,
                    pw,
                    prob,
                    &mut trial,
                    work.settings.contact_horizon_m,
                );
                let m2 = merit(task, scene, pw, work, prob, &trial);
                if m2.phi < m1.phi {
                    m1 = m2;
                } else {
                    trial.copy_from_slice(&plain);
                }
                work.q_plain = plain;
            }
            work.q_trial = trial;
            if enough(&m1) {
                q.copy_from_slice(&work.q_trial);
                m0 = m1;
                accepted = true;
                break;
            }
            alpha *= 0.5;
        }
        work.step = d;
        if !accepted && !work.reset_once {
            // The curvature learnt across kinks (torques changing sign) can stall the steps:
            // forget it once and retry from the same posture.
            work.reset_once = true;
            reset_curvature(work);
            continue;
        }
        if !accepted {
            out.stop = Stop::LineSearch;
            break;
        }
    }
    let m = merit(task, scene, pw, work, prob, q);
    out.objective = m.j;
    out.hand_error_m = m.hand_err;
    out.min_clearance_m = m.min_clear;
    out.balance_margin_m = m.margin;
    Ok(out)
}

/// Returns `q` onto the hand targets and the stance, and back to the boundary of any clearance
/// or balance constraint it violates, by Newton projection (minimum-norm steps
/// `Δ = Jᵀ(JJᵀ)⁻¹ r`, at most eight) within the joint limits: the optimiser's second-order
/// correction. Returns the largest remaining residual \[m or rad\]. The phase's hand targets,
/// gaze point and held objects come from `prob`.
pub fn restore(
    task: &Task,
    scene: &Scene,
    pw: &mut PostureWork,
    prob: &PhaseProblem,
    q: &mut [f64],
    horizon_m: f64,
) -> f64 {
    use nalgebra::{DMatrix, DVector};
    let (targets, gaze_m, held) = (&prob.targets_m, prob.gaze_m.as_ref(), prob.held);
    let n = task.model.nq();
    let zero = [Vector3::zeros(); 2];
    let mut worst = f64::INFINITY;
    let mut rows: Vec<(f64, Vec<f64>)> = Vec::with_capacity(24);
    let mut grad = vec![0.0; n];
    let mut best = (f64::INFINITY, q.to_vec());
    for it in 0..=8 {
        pw.statics(task, q, &zero);
        rows.clear();
        for h in 0..2 {
            if let (Some(t), Some(p)) = (targets[h], pw.hand_position(task, h)) {
                pw.hand_jacobian(task, h);
                for d in 0..3 {
                    rows.push((t[d] - p[d], (0..n).map(|k| pw.jac[(d, k)]).collect()));
                }
            }
        }
        if task.stance.is_some() {
            for i in 0..2 {
                let (dp, dr) = pw.foot_error(task, i);
                pw.foot_jacobians(task, i);
                for d in 0..3 {
                    rows.push((dp[d], (0..n).map(|k| pw.jac[(d, k)]).collect()));
                    rows.push((dr[d], (0..n).map(|k| pw.jac2[(d, k)]).collect()));
                }
            }
            if let Some(dz) = pw.seat_error(task) {
                pw.seat_jacobian(task);
                rows.push((dz, (0..n).map(|k| pw.jac[(2, k)]).collect()));
            }
        }
        // violated clearances: d(q) = d_min
        pw.clearances(task, scene, horizon_m, held);
        let contacts: Vec<_> = pw
            .contacts
            .iter()
            .filter(|c| c.distance_m < task.objective.clearance_m)
            .copied()
            .collect();
        for c in &contacts {
            pw.contact_gradient(task, c, &mut grad);
            rows.push((task.objective.clearance_m - c.distance_m, grad.clone()));
        }
        // violated geometric rows back to their bounds, ∇g·Δ = −g: the gaze, the placed feet,
        // and the most violated balance edge
        let mut worst_balance: Option<(f64, Vec<f64>)> = None;
        pw.geometry_rows(task, gaze_m, |kind, g, grad| {
            if g <= 0.0 {
                return;
            }
            if kind != Row::Balance {
                rows.push((-g, grad.to_vec()));
            } else if worst_balance.as_ref().is_none_or(|(w, _)| g > *w) {
                worst_balance = Some((g, grad.to_vec()));
            }
        });
        if let Some((g, grad)) = worst_balance {
            rows.push((-g, grad));
        }
        if rows.is_empty() {
            return 0.0;
        }
        let w = rows.iter().fold(0.0f64, |m, r| m.max(r.0.abs()));
        if w < best.0 {
            best = (w, q.to_vec());
        }
        if it >= 3 && w > worst * 0.5 {
            break; // not converging (out of reach, or limits in the way)
        }
        worst = w;
        if worst < 1e-13 || it == 8 {
            break;
        }
        let m = rows.len();
        let jm = DMatrix::<f64>::from_fn(m, n, |r, k| rows[r].1[k]);
        let e = DVector::<f64>::from_fn(m, |r, _| rows[r].0);
        let mut jjt = &jm * jm.transpose();
        for r in 0..m {
            jjt[(r, r)] += 1e-12;
        }
        let Some(chol) = jjt.cholesky() else { break };
        let dq = jm.transpose() * chol.solve(&e);
        if !dq.iter().all(|x| x.is_finite()) {
            break;
        }
        let scale = (dq.amax() / 0.2).max(1.0);
        for k in 0..n {
            let j = task.model.q_joint(k);
            q[k] = (q[k] + dq[k] / scale).clamp(j.lower_rad, j.upper_rad);
        }
    }
    // the last step is not checked above: keep the best posture seen
    let _ = worst;
    q.copy_from_slice(&best.1);
    best.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fatigue::MaState;
    use crate::plan::objective::FatigueCost;
    use crate::plan::posture::Other;
    use crate::plan::search::PhaseSolver;
    use crate::plan::stepping::feet_of;

    /// The Jacobian of [`posture_terms`]' posture gradient by central differences, the statics
    /// and the load cost evaluated afresh at every moved posture, less the discomfort's diagonal:
    /// what [`explicit_curvature`] must give.
    fn by_differences(
        task: &Task,
        scene: &Scene,
        pw: &mut PostureWork,
        work: &mut SqpWork,
        prob: &mut PhaseProblem,
        q: &[f64],
    ) -> Vec<f64> {
        let n = task.model.nq();
        let step = 1e-6;
        let mut out = vec![0.0; n * n];
        let mut qf = q.to_vec();
        for k in 0..n {
            let mut g = [vec![0.0; n], vec![0.0; n]];
            for (side, x) in [q[k] - step, q[k] + step].into_iter().enumerate() {
                qf[k] = x;
                pw.statics(task, &qf, &prob.hand_force_n);
                posture_terms(task, scene, pw, work, prob, &qf);
                g[side].copy_from_slice(&work.dq_grad);
            }
            qf[k] = q[k];
            for i in 0..n {
                out[i * n + k] = (g[1][i] - g[0][i]) / (2.0 * step);
            }
        }
        pw.statics(task, q, &prob.hand_force_n);
        posture_terms(task, scene, pw, work, prob, q);
        for k in 0..n {
            out[k * n + k] -= work.dq_curv[k];
        }
        out
    }

    /// The BFGS pair differences the Lagrangian of the same constraints: a clearance row's
    /// multiplier follows its contact when the rows' order of distance changes, and a contact
    /// new at this iterate gets none.
    #[test]
    fn clearance_multipliers_follow_their_contacts() {
        let path = format!("{}/tasks/shelf.yaml", env!("CARGO_MANIFEST_DIR"));
        let task = Task::from_file(&path).unwrap();
        let mut solver = PhaseSolver::new(&task, SqpSettings::default()).unwrap();
        let work = &mut solver.work;
        let contact = |link: usize, other: Other, distance_m: f64| Contact {
            distance_m,
            link,
            point_m: Vector3::zeros(),
            normal: Vector3::z(),
            other,
        };
        let before = [
            contact(3, Other::Obstacle(0), 0.010),
            contact(5, Other::HeldObject, 0.012),
            contact(
                7,
                Other::Body {
                    link: 2,
                    point_m: Vector3::zeros(),
                },
                0.020,
            ),
        ];
        let r = work.qp.rows.clearance;
        work.qp.z.iter_mut().for_each(|z| *z = 0.0);
        for (i, z) in [0.5, 0.25, 0.125].into_iter().enumerate() {
            work.qp.z[r + i] = z;
        }
        remember_iterate(work, &before, &vec![0.0; task.model.nq()]);
        // the held object is now closest, the obstacle second, the self-contact gone (its
        // witness point moved: the same contact), and a new obstacle third
        let after = [
            contact(5, Other::HeldObject, 0.009),
            contact(3, Other::Obstacle(0), 0.011),
            contact(
                7,
                Other::Body {
                    link: 2,
                    point_m: Vector3::x(),
                },
                0.015,
            ),
            contact(3, Other::Obstacle(1), 0.030),
        ];
        match_clearance_duals(work, &after);
        assert_eq!(&work.last_z[r..r + 5], &[0.25, 0.5, 0.125, 0.0, 0.0]);
    }

    /// The analytic start curvature against central differences of the gradient it
    /// differentiates, at postures where the strength curves are off their plateaus (trunk
    /// flexed, shoulder raised, elbow and knees bent) and the fatigue cost's curvature is large:
    /// on the shelf task (fixed feet) and on the side transfer with a step cost to another
    /// stance (placed feet). Every entry within 1e-4 of the matrix's largest.
    #[test]
    fn the_start_curvature_is_the_derivative_of_the_explicit_gradient() {
        for (file, steps) in [("shelf.yaml", false), ("side_transfer.yaml", true)] {
            let path = format!("{}/tasks/{file}", env!("CARGO_MANIFEST_DIR"));
            let task = Task::from_file(&path).unwrap();
            let mut solver = PhaseSolver::new(&task, SqpSettings::default()).unwrap();
            let (n, nh) = (task.model.nq(), task.half_joints.len());
            let mut q = vec![0.0; n];
            for (name, v) in [
                ("lumbar_flexion", 0.45),
                ("r_shoulder_flexion", 1.1),
                ("r_elbow_flexion", 0.7),
                ("l_shoulder_flexion", 0.5),
                ("r_knee_flexion", 0.3),
                ("l_knee_flexion", 0.2),
                ("lumbar_axial_rotation", 0.15),
            ] {
                if let Ok(k) = task.model.q_index(name) {
                    q[k] = v;
                }
            }
            let phase = &task.phases[0];
            solver.pw.statics(&task, &q, &phase.hand_force_n);
            let mut f = vec![0.0; nh];
            solver.pw.half_joint_loads(&task, &q, &mut f);
            let stepping = if steps {
                let mut other = q.clone();
                let kr = task.model.q_index("pelvis_rotation").unwrap();
                other[kr] += 0.4;
                solver.pw.statics(&task, &other, &phase.hand_force_n);
                let feet = feet_of(&task, &solver.pw).unwrap();
                Stepping {
                    weight: 1.0,
                    neighbours: vec![(feet, 2.0)],
                    ..Stepping::default()
                }
            } else {
                Stepping::default()
            };
            // the phase holds twice its loads at q, so that its fatigue is well under way
            let loads: Vec<f64> = f.iter().map(|x| 2.0 * x).collect();
            let phase_loads = vec![loads.clone(); task.phases.len()];
            let mut cost = FatigueCost::new(
                &task,
                &[0],
                &phase_loads,
                &f,
                &vec![MaState::FRESH; nh],
                task.cycles as u64,
            );
            let big = vec![10.0; nh];
            let discomfort = solver.discomfort.clone();
            let mut prob = PhaseProblem {
                targets_m: phase.targets_m,
                hand_force_n: phase.hand_force_n,
                cost: &mut cost,
                discomfort: &discomfort,
                discomfort_weight: 1.0,
                shape: Shape::of(&task),
                capacity: &big,
                gaze_m: None,
                stepping: &stepping,
                zones: None,
                held: None,
            };
            let (scene, pw, work) = (&solver.scene, &mut solver.pw, &mut solver.work);
            build_qp(&task, scene, pw, work, &mut prob, &q);
            explicit_curvature(&task, scene, pw, work, &mut prob, &q);
            let analytic = work.hess.clone();
            let fd = by_differences(&task, scene, pw, work, &mut prob, &q);
            let largest = fd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(largest > 1e-2, "{file}: nothing to compare ({largest})");
            // the strength's cross terms are there: entries off the diagonal
            let off = (0..n * n)
                .filter(|&e| e / n != e % n && fd[e].abs() > 1e-3 * largest)
                .count();
            assert!(off > 10, "{file}: {off} off-diagonal entries");
            for i in 0..n {
                for k in 0..n {
                    let (a, d) = (analytic[i * n + k], fd[i * n + k]);
                    assert!(
                        (a - d).abs() <= 1e-4 * largest,
                        "{file}: ∂g/∂q ({}, {}) {a} vs differences {d} (largest {largest})",
                        task.model.q_joint(i).name,
                        task.model.q_joint(k).name
                    );
                }
            }
        }
    }
}
