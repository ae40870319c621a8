// Index loops over parallel per-joint / per-half-joint arrays read clearer than zipped iterators.
#![allow(clippy::needless_range_loop)]
//! The fatigue objective of the posture QP, and why it has this form.
//!
//! Per half-joint h (parameters k_h, R_h; capacity c_h and index U_h now), the phases of a cycle
//! load it with an average `f̄_h = ΔF_h / T` over the remaining horizon T, where
//! `ΔF_h = base_h + f_h · w` is the normalised load-time \[min\] (`f_h` this phase's load, `w` the
//! minutes this phase is held over the horizon, `base_h` what the other phases and the rests
//! add). The predicted index at the horizon end is the model's closed form for `f̄_h` held from
//! `(c_h, U_h)` for T: with R = 0 it is exact for any load history
//! (`U_h(T) = U_h + (e^{2k ΔF} − 1) / (2k c_h²)`, Eq. 6); with recovery it treats the cycle's
//! load as its average, accurate when a cycle is short against 1/(k f + R) (20 s against
//! minutes here). Plans are always evaluated with the exact step-by-step updates.
//!
//! **Scaling.** Σ_h U_h(T) spans many orders of magnitude (e^{2kΔF} for an hour of work without
//! recovery), so the optimiser minimises `J = ln(Σ_h U_h(T) + ε)`: a strictly increasing
//! transform of the total, so the same minimiser, with gradients `U_h'/S` that are order one
//! however large U gets. The Hessian is replaced by its diagonal upper bound `U_h''/S` (the
//! dropped `−(U'/S)(U'/S)ᵀ` term is negative semidefinite), which keeps the QP convex and
//! separable. Without recovery everything is computed in log space (no overflow); with
//! recovery U grows at most linearly (c ≥ R/(k+R)) and derivatives of the closed form are taken
//! by central differences. ε = 0.001 min keeps J finite when nothing is loaded.

use crate::fatigue::units::min_to_s;
use crate::fatigue::{MaParams, MaState};

/// Objective inputs, one entry per half-joint.
#[derive(Debug, Clone, Default)]
pub struct FatigueObjective {
    pub params: Vec<MaParams>,
    pub capacity: Vec<f64>,
    pub fatigue_u_min: Vec<f64>,
    /// ΔF contributed by the other phases and rests over the horizon \[min\].
    pub base_min: Vec<f64>,
    /// Minutes this phase is held over the horizon.
    pub weight_min: f64,
    /// The remaining horizon \[min\].
    pub horizon_min: f64,
}

/// ε of the objective \[min\].
pub const EPSILON_U_MIN: f64 = 1e-3;

impl FatigueObjective {
    /// ln U_h(T) for this phase's load `f` on half-joint h, without overflow.
    pub fn log_u_end(&self, h: usize, f: f64) -> f64 {
        let p = &self.params[h];
        let c = self.capacity[h];
        let u0 = self.fatigue_u_min[h].max(0.0);
        let df = self.base_min[h] + f * self.weight_min;
        if p.recovery == crate::fatigue::Recovery::None {
            let z = 2.0 * p.k_per_min * df;
            let log_scale = -(2.0 * p.k_per_min * c * c).ln();
            if z < 600.0 {
                (u0 + z.exp_m1() * log_scale.exp()).max(1e-300).ln()
            } else {
                z + log_scale
            }
        } else {
            (u0 + self.du_recovery(h, df)).max(1e-300).ln()
        }
    }

    /// U increment over the horizon for load-time `df` \[min\] with recovery (closed form).
    fn du_recovery(&self, h: usize, df: f64) -> f64 {
        let t_min = self.horizon_min.max(1e-9);
        let mut st = MaState {
            capacity: self.capacity[h],
            fatigue_u_min: 0.0,
        };
        self.params[h].hold(&mut st, (df / t_min).max(0.0), min_to_s(t_min));
        st.fatigue_u_min
    }

    /// J for this phase's loads `f`; fills `grad[h] = ∂J/∂f_h` and `hess[h]` (diagonal bound).
    pub fn eval(&self, f: &[f64], grad: &mut [f64], hess: &mut [f64]) -> f64 {
        let n = f.len();
        let mut m = EPSILON_U_MIN.ln();
        for h in 0..n {
            let lu = self.log_u_end(h, f[h]);
            grad[h] = lu; // stash ln U_h(T)
            m = m.max(lu);
        }
        let mut sum = (EPSILON_U_MIN.ln() - m).exp();
        for g in grad.iter().take(n) {
            sum += (g - m).exp();
        }
        let log_s = m + sum.ln();
        let w = self.weight_min;
        for h in 0..n {
            let p = &self.params[h];
            if p.recovery == crate::fatigue::Recovery::None {
                // U' = e^{z}/c² · w, U'' = 2k U' · w (z = 2kΔF)
                let z = 2.0 * p.k_per_min * (self.base_min[h] + f[h] * w);
                let d = (z - 2.0 * self.capacity[h].ln() - log_s).exp() * w;
                grad[h] = d;
                hess[h] = 2.0 * p.k_per_min * d * w;
            } else {
                let df = self.base_min[h] + f[h] * w;
                let step = 1e-4 * df.abs().max(1e-3);
                let (um, u0, up) = (
                    self.du_recovery(h, (df - step).max(0.0)),
                    self.du_recovery(h, df),
                    self.du_recovery(h, df + step),
                );
                let lo = df - (df - step).max(0.0);
                let d1 = (up - um) / (step + lo);
                let d2 = if lo > 0.0 {
                    (up - 2.0 * u0 + um) / (step * step)
                } else {
                    0.0
                };
                let inv_s = (-log_s).exp();
                grad[h] = d1 * w * inv_s;
                hess[h] = d2.max(0.0) * w * w * inv_s;
            }
        }
        log_s
    }
}
