//! The dynamic muscle fatigue model of Ma, Chablat, Bennis & Zhang (2009), normalised, with an
//! optional recovery term.
//!
//! Per muscle group, with `c = F_cem / MVC` (capacity) and `f = F_load / MVC` (relative load):
//!
//! * paper Eq. 2: `dc/dt = -k f c`; Eq. 1: `dU/dt = f / c²` (U in minutes);
//! * recovery extension (not in the 2009 paper, documented assumption):
//!   `dc/dt = -k f c + R (1 - c)`. With `R = 0` this is the paper exactly.
//!
//! For a load held constant over a step, both equations have closed forms, so a step of any length
//! is one exact O(1) update ([`MaParams::hold`]); nothing here integrates with small time steps.
//! With `λ = k f + R` and `c∞ = R / λ`:
//!
//! * `c(t) = c∞ + (c0 - c∞) e^{-λ t}`;
//! * `U(t) - U(0) = ∫ f / c(τ)² dτ`, which with `a = c∞`, `b = c0 - c∞`, `x = e^{λt}` is
//!   `f / (λ a²) · [ln((a x + b) / c0) + b / (a x + b) - b / c0]`, evaluated in a form that stays
//!   accurate as `a → 0` (where it becomes paper Eq. 6, `(1/c1² - 1/c0²) / (2k)`).

use super::units::s_to_min;

/// Parameters of one muscle group (half-joint) under the Ma et al. model.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct MaParams {
    /// Fatigue rate k [1/min]; the paper uses k = 1 (Table 1).
    pub k_per_min: f64,
    /// Recovery rate R [1/min]; 0 reproduces the paper.
    pub r_per_min: f64,
}

impl Default for MaParams {
    /// The paper's parameters: k = 1 min⁻¹, no recovery.
    fn default() -> Self {
        MaParams {
            k_per_min: 1.0,
            r_per_min: 0.0,
        }
    }
}

/// Capacity and fatigue index of one muscle group.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct MaState {
    /// Capacity c = F_cem / MVC, in (0, 1].
    pub capacity: f64,
    /// Fatigue index U \[min\], ≥ 0 (paper Eq. 1, 6).
    pub fatigue_u_min: f64,
}

impl MaState {
    /// A rested muscle group: c = 1, U = 0.
    pub const FRESH: MaState = MaState {
        capacity: 1.0,
        fatigue_u_min: 0.0,
    };
}

impl Default for MaState {
    fn default() -> Self {
        Self::FRESH
    }
}

/// Why a parameter set or a load was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FatigueError {
    #[error("fatigue rate k must be finite and > 0 (1/min), got {0}")]
    BadK(f64),
    #[error("recovery rate R must be finite and >= 0 (1/min), got {0}")]
    BadR(f64),
    #[error("relative load f = F_load/MVC must be finite and in [0, 1] for {what}, got {value}")]
    BadLoad { what: &'static str, value: f64 },
    #[error("{what} must be finite and >= 0, got {value}")]
    BadValue { what: &'static str, value: f64 },
}

/// Smallest capacity the state keeps, so that c stays in (0, 1] even after absurdly long holds.
const C_FLOOR: f64 = f64::MIN_POSITIVE;

/// `(ln(1+w) - w/(1+w)) / w²`, accurate for small |w| (series) and large w.
#[inline]
fn g_of_w(w: f64) -> f64 {
    if w.abs() < 1e-3 {
        // ln(1+w) - w/(1+w) = w²/2 - 2w³/3 + 3w⁴/4 - 4w⁵/5 + ...
        0.5 + w * (-2.0 / 3.0 + w * (0.75 - w * 0.8))
    } else {
        ((w).ln_1p() - w / (1.0 + w)) / (w * w)
    }
}

impl MaParams {
    /// Checked constructor.
    pub fn new(k_per_min: f64, r_per_min: f64) -> Result<Self, FatigueError> {
        if !(k_per_min.is_finite() && k_per_min > 0.0) {
            return Err(FatigueError::BadK(k_per_min));
        }
        if !(r_per_min.is_finite() && r_per_min >= 0.0) {
            return Err(FatigueError::BadR(r_per_min));
        }
        Ok(MaParams {
            k_per_min,
            r_per_min,
        })
    }

    /// Holds relative load `f ≥ 0` for `dt_s` seconds: exact update of capacity and U.
    ///
    /// Inputs are trusted (checked at the boundary): `f` finite and ≥ 0, `dt_s` finite and ≥ 0.
    ///
    /// ```
    /// use posture_opt::fatigue::{MaParams, MaState};
    /// let p = MaParams::default(); // k = 1/min, no recovery
    /// let mut s = MaState::FRESH;
    /// p.hold(&mut s, 0.5, 60.0); // 50 %MVC for one minute
    /// assert!((s.capacity - (-0.5f64).exp()).abs() < 1e-15);
    /// // Eq. 6: U = (e^{2kF} - 1) / 2k with F = 0.5 min
    /// assert!((s.fatigue_u_min - (1f64.exp() - 1.0) / 2.0).abs() < 1e-14);
    /// ```
    #[inline]
    pub fn hold(&self, state: &mut MaState, f: f64, dt_s: f64) {
        let t_min = s_to_min(dt_s);
        let k = self.k_per_min;
        let r = self.r_per_min;
        let c0 = state.capacity;
        let lambda = k * f + r;
        if lambda <= 0.0 || t_min <= 0.0 {
            return;
        }
        let inv_lambda = 1.0 / lambda;
        let c_inf = r * inv_lambda;
        // x1 - 1 = e^{λt} - 1 without cancellation; e^{-λt} = 1 / x1 reuses it.
        let xm1 = (lambda * t_min).exp_m1();
        let decay = 1.0 / (1.0 + xm1);
        let c1 = (c_inf + (c0 - c_inf) * decay).clamp(C_FLOOR, 1.0);
        if f > 0.0 {
            let inv_c0 = 1.0 / c0;
            let y = xm1 * inv_c0;
            let w = c_inf * y;
            let du = f * inv_lambda * y * (inv_c0 / (1.0 + w) + g_of_w(w) * y);
            let u = state.fatigue_u_min + du;
            state.fatigue_u_min = if u.is_finite() { u } else { f64::MAX };
        }
        state.capacity = c1;
    }

    /// Time \[s\] for capacity to go from `c0` to `target` while holding `f`; `None` if it never
    /// gets there (recovery balances the load first, or `f == 0`). `Some(0)` if `c0 ≤ target`.
    pub fn time_to_capacity_s(&self, c0: f64, f: f64, target: f64) -> Option<f64> {
        if c0 <= target {
            return Some(0.0);
        }
        if f <= 0.0 {
            return None;
        }
        let lambda = self.k_per_min * f + self.r_per_min;
        let c_inf = self.r_per_min / lambda;
        if c_inf >= target {
            return None;
        }
        let t_min = ((c0 - c_inf) / (target - c_inf)).ln() / lambda;
        Some(super::units::min_to_s(t_min))
    }

    /// Time \[s\] until capacity falls to the held load `f` (the muscle group can no longer hold
    /// it), starting from capacity `c0`; `None` if it never does or `f == 0`.
    pub fn time_to_exhaustion_s(&self, c0: f64, f: f64) -> Option<f64> {
        if f <= 0.0 {
            return None;
        }
        self.time_to_capacity_s(c0, f, f)
    }

    /// Maximum endurance time \[min\] of a fresh muscle holding `f` (paper Eq. 8 when R = 0:
    /// `MET = -ln f / (k f)`).
    ///
    /// ```
    /// use posture_opt::fatigue::MaParams;
    /// let met = MaParams::default().met_min(0.5).unwrap();
    /// assert!((met - 2.0 * 2f64.ln()).abs() < 1e-12); // -ln(0.5)/0.5
    /// ```
    pub fn met_min(&self, f: f64) -> Option<f64> {
        self.time_to_exhaustion_s(1.0, f)
            .map(super::units::s_to_min)
    }
}

/// Paper Eq. 8 on its own: `MET = -ln f / (k f)` \[min\], for `f` in (0, 1].
pub fn met_min(f: f64, k_per_min: f64) -> f64 {
    -f.ln() / (k_per_min * f)
}

/// One sample of a held-load curve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CurvePoint {
    pub t_s: f64,
    pub capacity: f64,
    pub fatigue_u_min: f64,
}

impl MaParams {
    /// Capacity and U of a fresh muscle group holding `f`, sampled at `n + 1` evenly spaced
    /// instants over `[0, t_end_s]` (each sample exact, chained step by step).
    pub fn hold_curve(&self, f: f64, t_end_s: f64, n: usize) -> Vec<CurvePoint> {
        let n = n.max(1);
        let dt = t_end_s / n as f64;
        let mut s = MaState::FRESH;
        let mut out = Vec::with_capacity(n + 1);
        out.push(CurvePoint {
            t_s: 0.0,
            capacity: s.capacity,
            fatigue_u_min: s.fatigue_u_min,
        });
        for i in 1..=n {
            self.hold(&mut s, f, dt);
            out.push(CurvePoint {
                t_s: dt * i as f64,
                capacity: s.capacity,
                fatigue_u_min: s.fatigue_u_min,
            });
        }
        out
    }
}

/// Holds `loads[i]` on muscle group `i` (parameters `params[i]`, state `states[i]`) for `dt_s`.
/// The three slices must be equally long (shorter ones bound the loop).
#[inline]
pub fn hold_all(params: &[MaParams], states: &mut [MaState], loads: &[f64], dt_s: f64) {
    for ((p, s), &f) in params.iter().zip(states.iter_mut()).zip(loads) {
        p.hold(s, f, dt_s);
    }
}
