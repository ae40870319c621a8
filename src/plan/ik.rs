//! Inverse kinematics for starting postures: damped least squares on the hand targets and the
//! feet, pulled toward a reference posture in the null space, within the joint limits. Cheap (no
//! QP); its postures only seed the SQP, which then honours every constraint.

use super::posture::PostureWork;
use super::task::Task;
use nalgebra::{DMatrix, DVector, Vector3};

/// Settings of the seed IK.
#[derive(Debug, Clone, Copy)]
pub struct IkSettings {
    pub iterations: usize,
    /// Damping λ² of the least squares.
    pub damping: f64,
    /// Pull toward the reference posture per iteration (fraction).
    pub pull: f64,
    /// Stop when every residual is below this \[m or rad\].
    pub tolerance: f64,
}

impl Default for IkSettings {
    fn default() -> Self {
        IkSettings {
            iterations: 40,
            damping: 1e-3,
            pull: 0.05,
            tolerance: 1e-4,
        }
    }
}

/// Moves `q` toward satisfying the hand targets and the stance, starting from `q` and pulled
/// toward `q_ref`. Returns the largest remaining residual.
pub fn solve_ik(
    task: &Task,
    pw: &mut PostureWork,
    targets: &[Option<Vector3<f64>>; 2],
    q_ref: &[f64],
    q: &mut [f64],
    s: IkSettings,
) -> f64 {
    let n = task.model.nq();
    let rows = 6 + if task.stance.is_some() { 12 } else { 0 };
    let mut jm = DMatrix::<f64>::zeros(rows, n);
    let mut e = DVector::<f64>::zeros(rows);
    let zero = [Vector3::zeros(); 2];
    let mut worst = f64::INFINITY;
    for _ in 0..s.iterations {
        pw.statics(task, q, &zero);
        jm.fill(0.0);
        e.fill(0.0);
        for h in 0..2 {
            if let (Some(t), Some(p)) = (targets[h], pw.hand_position(task, h)) {
                let r = t - p;
                pw.hand_jacobian(task, h);
                for d in 0..3 {
                    e[3 * h + d] = r[d];
                    for k in 0..n {
                        jm[(3 * h + d, k)] = pw.jac[(d, k)];
                    }
                }
            }
        }
        if task.stance.is_some() {
            for i in 0..2 {
                let (dp, dr) = pw.foot_error(task, i);
                pw.foot_jacobians(task, i);
                for d in 0..3 {
                    e[6 + 6 * i + d] = dp[d];
                    e[9 + 6 * i + d] = dr[d];
                    for k in 0..n {
                        jm[(6 + 6 * i + d, k)] = pw.jac[(d, k)];
                        jm[(9 + 6 * i + d, k)] = pw.jac2[(d, k)];
                    }
                }
            }
        }
        worst = e.amax();
        if worst < s.tolerance {
            break;
        }
        // (JᵀJ + λ²I) Δq = Jᵀe + λ² · pull · (q_ref − q)
        let mut a = jm.transpose() * &jm;
        let mut b = jm.transpose() * &e;
        for k in 0..n {
            a[(k, k)] += s.damping;
            b[k] += s.damping * s.pull * (q_ref[k] - q[k]) * 10.0;
        }
        let Some(chol) = a.cholesky() else { break };
        let dq = chol.solve(&b);
        if !dq.iter().all(|x| x.is_finite()) {
            break;
        }
        let scale = (dq.amax() / 0.4).max(1.0);
        for k in 0..n {
            let j = task.model.q_joint(k);
            q[k] = (q[k] + dq[k] / scale).clamp(j.lower_rad, j.upper_rad);
        }
    }
    worst
}
