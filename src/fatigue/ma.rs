//! The dynamic muscle fatigue model of Ma, Chablat, Bennis & Zhang (2009), normalised, with a
//! load-dependent recovery term.
//!
//! Per muscle group, with `c = F_cem / MVC` (capacity) and `f = F_load / MVC` (relative load):
//!
//! * paper Eq. 2: `dc/dt = -k f c`; Eq. 1: `dU/dt = f / c²` (U in minutes);
//! * with recovery: `dc/dt = -k f c + R(f) (1 - c)`, where the recovery rate `R(f)` depends on
//!   the load held ([`Recovery`]). `R ≡ 0` is the paper exactly.
//!
//! For a load held constant over a step, `R(f)` is constant too, so both equations have closed
//! forms and a step of any length is one exact O(1) update ([`MaParams::hold`]); nothing here
//! integrates with small time steps. With `λ = k f + R(f)`, `a = c∞ = R(f) / λ`, `b = c0 − a`:
//!
//! * `c(t) = a + b e^{−λt}`;
//! * `U(t) − U(0) = ∫ f / c(τ)² dτ = f/(λa²) · ln(1 + w) − f/(λa) · (1/c(t) − 1/c0)` with
//!   `w = (a/c0)(e^{λt} − 1)`. For `λt ≤ 30` it is evaluated as
//!   `f/λ · y · [1/(c0 (1 + w)) + g(w) y]`, `y = (e^{λt} − 1)/c0`,
//!   `g(w) = (ln(1+w) − w/(1+w))/w²` (series for small `w`), which stays exact as `a → 0` (where
//!   it becomes paper Eq. 6, `(1/c1² − 1/c0²)/(2k)`); beyond, `ln(1 + w)` is taken as
//!   `λt + ln(a/c0) + ln(1 + (b/a) e^{−λt})`, so holds of days neither overflow nor lose the
//!   linear growth `f t / c∞²` of U at equilibrium;
//! * without recovery, `c(t) = c0 e^{−kft}`, `U(t) − U(0) = (e^{2kft} − 1)/(2k c0²)`.
//!
//! Where U exceeds what a double can hold (a muscle group driven far past exhaustion), the update
//! says so ([`MaParams::hold`] returns `false`) instead of returning a wrong number.

use super::units::s_to_min;
use serde::Serialize;

/// Largest documented fatigue rate k \[1/min\] (the literature's fitted k lie within 0.1–5).
pub const K_MAX_PER_MIN: f64 = 20.0;
/// Smallest documented fatigue rate k \[1/min\].
pub const K_MIN_PER_MIN: f64 = 0.01;
/// Largest documented recovery rate \[1/min\] (a half-time of about 2 s).
pub const R_MAX_PER_MIN: f64 = 20.0;

/// How capacity recovers: the rate `R(f)` \[1/min\] in `dc/dt = −k f c + R(f)(1 − c)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "form", rename_all = "snake_case")]
pub enum Recovery {
    /// No recovery: Ma et al. (2009) exactly.
    None,
    /// A constant rate, acting under load as at rest (the form of earlier task files'
    /// `recovery_per_min`; it lets every load below `f*` be held forever).
    Constant { r_per_min: f64 },
    /// Perfusion-limited recovery: the rate falls with the load held, as muscle blood flow does
    /// when intramuscular pressure rises, `R(f) = R_rest · x²(3 − 2x)` with `x = 1 − f/f_lim`
    /// below the limit load `f_lim`, and 0 at and above it (C¹ in f at both ends). At rest
    /// (`f = 0`) the rate is `R_rest`; from `f_lim` up the model is the paper's exactly.
    Perfusion { rest_per_min: f64, limit_fmvc: f64 },
    /// Two deficits, a fast and a slow one, `c = 1 − D_fast − D_slow`, the new fatigue routed
    /// between them by the load held (docs/fatigue-parameters.md, "A fast and a slow component"):
    /// `dD_fast/dt = φ(f) k f c − R_fast(f) D_fast`, `dD_slow/dt = (1 − φ(f)) k f c − R_slow(f)
    /// D_slow`. Each rate has the perfusion form of [`Recovery::Perfusion`] with the same limit
    /// load; the fast share `φ(f)` is 0 up to [`ROUTE_FROM_FMVC`] and rises by a smoothstep to
    /// `fast_share_max` at [`ROUTE_FULL_FMVC`]. With no fast deficit and loads below 25 %MVC it
    /// is [`Recovery::Perfusion`] with `R_rest = slow_rest_per_min` exactly.
    Routed {
        slow_rest_per_min: f64,
        fast_rest_per_min: f64,
        limit_fmvc: f64,
        fast_share_max: f64,
    },
}

/// The load from which new fatigue starts to go to the fast deficit (ASSUMPTION: Byström et
/// al. 1991's 25 %MVC, where short pauses help only as the single-rate model says).
pub const ROUTE_FROM_FMVC: f64 = 0.25;
/// The load from which the fast share is at its maximum (Sadamoto et al. 1983: muscle blood flow
/// stops at about 50 %MVC; the ramp's ends are ASSUMPTION).
pub const ROUTE_FULL_FMVC: f64 = 0.5;

/// `x²(3 − 2x)`, the C¹ ramp of the perfusion rate and of the routing.
#[inline]
fn smoothstep(x: f64) -> f64 {
    x * x * (3.0 - 2.0 * x)
}

impl Recovery {
    /// The recovery rate \[1/min\] while holding relative load `f ≥ 0`.
    #[inline]
    pub fn rate_per_min(&self, f: f64) -> f64 {
        match *self {
            Recovery::None => 0.0,
            Recovery::Constant { r_per_min } => r_per_min,
            Recovery::Perfusion {
                rest_per_min,
                limit_fmvc,
            }
            | Recovery::Routed {
                slow_rest_per_min: rest_per_min,
                limit_fmvc,
                ..
            } => rest_per_min * perfusion_share(f, limit_fmvc),
        }
    }

    /// The fast deficit's recovery rate \[1/min\] while holding `f` (0 for the single-rate forms).
    #[inline]
    pub fn fast_rate_per_min(&self, f: f64) -> f64 {
        match *self {
            Recovery::Routed {
                fast_rest_per_min,
                limit_fmvc,
                ..
            } => fast_rest_per_min * perfusion_share(f, limit_fmvc),
            _ => 0.0,
        }
    }

    /// The share `φ(f)` of new fatigue that goes to the fast deficit (0 for the single-rate
    /// forms).
    #[inline]
    pub fn fast_share(&self, f: f64) -> f64 {
        match *self {
            Recovery::Routed { fast_share_max, .. } => {
                let x =
                    ((f - ROUTE_FROM_FMVC) / (ROUTE_FULL_FMVC - ROUTE_FROM_FMVC)).clamp(0.0, 1.0);
                fast_share_max * smoothstep(x)
            }
            _ => 0.0,
        }
    }

    /// The rate at rest (`f = 0`) \[1/min\] (the slow deficit's, for the routed form).
    pub fn rest_rate_per_min(&self) -> f64 {
        self.rate_per_min(0.0)
    }

    /// Checks the parameters against their documented ranges.
    pub fn validate(&self) -> Result<(), FatigueError> {
        let rate_ok = |r: f64| r.is_finite() && (0.0..=R_MAX_PER_MIN).contains(&r);
        match *self {
            Recovery::None => Ok(()),
            Recovery::Constant { r_per_min } if rate_ok(r_per_min) => Ok(()),
            Recovery::Constant { r_per_min } => Err(FatigueError::BadR(r_per_min)),
            Recovery::Perfusion {
                rest_per_min,
                limit_fmvc,
            } => {
                if !rate_ok(rest_per_min) {
                    Err(FatigueError::BadR(rest_per_min))
                } else if !(limit_fmvc.is_finite() && (0.01..=1.0).contains(&limit_fmvc)) {
                    Err(FatigueError::BadLimit(limit_fmvc))
                } else {
                    Ok(())
                }
            }
            Recovery::Routed {
                slow_rest_per_min,
                fast_rest_per_min,
                limit_fmvc,
                fast_share_max,
            } => {
                if !(rate_ok(slow_rest_per_min) && slow_rest_per_min > 0.0) {
                    Err(FatigueError::BadR(slow_rest_per_min))
                } else if !rate_ok(fast_rest_per_min) || fast_rest_per_min < slow_rest_per_min {
                    Err(FatigueError::BadFastRate {
                        fast: fast_rest_per_min,
                        slow: slow_rest_per_min,
                    })
                } else if !(limit_fmvc.is_finite()
                    && (0.01..=ROUTE_FROM_FMVC).contains(&limit_fmvc))
                {
                    Err(FatigueError::BadRoutedLimit(limit_fmvc))
                } else if !(fast_share_max.is_finite() && (0.0..=1.0).contains(&fast_share_max)) {
                    Err(FatigueError::BadShare(fast_share_max))
                } else {
                    Ok(())
                }
            }
        }
    }
}

/// The perfusion-limited share of the resting rate at load `f`: `x²(3 − 2x)`, `x = 1 − f/f_lim`,
/// 0 from `f_lim` up.
#[inline]
fn perfusion_share(f: f64, limit_fmvc: f64) -> f64 {
    let x = 1.0 - f / limit_fmvc;
    if x > 0.0 { smoothstep(x) } else { 0.0 }
}

/// Parameters of one muscle group (half-joint) under the Ma et al. model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MaParams {
    /// Fatigue rate k [1/min]; the paper uses k = 1 (Table 1).
    pub k_per_min: f64,
    /// Recovery `R(f)`.
    pub recovery: Recovery,
}

impl Default for MaParams {
    /// The paper's parameters: k = 1 min⁻¹, no recovery.
    fn default() -> Self {
        MaParams {
            k_per_min: 1.0,
            recovery: Recovery::None,
        }
    }
}

/// Capacity and fatigue index of one muscle group.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MaState {
    /// Capacity c = F_cem / MVC, in (0, 1].
    pub capacity: f64,
    /// Fatigue index U \[min\], ≥ 0 (paper Eq. 1, 6).
    pub fatigue_u_min: f64,
    /// The part of the lost capacity held in the fast deficit, in [0, 1 − capacity]; 0 except
    /// under the routed recovery ([`Recovery::Routed`]).
    #[serde(skip_serializing_if = "is_zero")]
    pub fast_deficit: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl MaState {
    /// A rested muscle group: c = 1, U = 0.
    pub const FRESH: MaState = MaState {
        capacity: 1.0,
        fatigue_u_min: 0.0,
        fast_deficit: 0.0,
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
    #[error(
        "fatigue rate k must be finite and within {K_MIN_PER_MIN}..{K_MAX_PER_MIN} 1/min, got {0}"
    )]
    BadK(f64),
    #[error("recovery rate must be finite and within 0..{R_MAX_PER_MIN} 1/min, got {0}")]
    BadR(f64),
    #[error("recovery limit load f_lim must be within 0.01..1 (fraction of MVC), got {0}")]
    BadLimit(f64),
    #[error(
        "the routed recovery's limit load f_lim must be within 0.01..{ROUTE_FROM_FMVC} (fraction of MVC, below the load where fatigue starts to go to the fast deficit), got {0}"
    )]
    BadRoutedLimit(f64),
    #[error(
        "the fast recovery rate must be finite, within 0..{R_MAX_PER_MIN} 1/min and at least the slow rate ({slow}), got {fast}"
    )]
    BadFastRate { fast: f64, slow: f64 },
    #[error("the fast share of new fatigue must be within 0..1, got {0}")]
    BadShare(f64),
    #[error("relative load f = F_load/MVC must be finite and in [0, 1] for {what}, got {value}")]
    BadLoad { what: &'static str, value: f64 },
    #[error("{what} must be finite and >= 0, got {value}")]
    BadValue { what: &'static str, value: f64 },
}

/// Smallest capacity the state keeps, so that c stays in (0, 1] even after absurdly long holds.
const C_FLOOR: f64 = f64::MIN_POSITIVE;

/// Exact capacity and U increment of holding `f` for `t_min` from capacity `c0`, with fatigue
/// rate `k` and recovery rate `r` (both per minute, `r` the rate for this load).
/// Returns `(c1, ΔU)`; ΔU may be infinite when it exceeds a double.
#[inline]
pub fn step_exact(k: f64, r: f64, f: f64, c0: f64, t_min: f64) -> (f64, f64) {
    let recovery = if r == 0.0 {
        Recovery::None
    } else {
        Recovery::Constant { r_per_min: r }
    };
    let p = MaParams {
        k_per_min: k,
        recovery,
    };
    let mut s = MaState {
        capacity: c0,
        ..MaState::FRESH
    };
    p.prepare_min(f, t_min).hold(&mut s);
    (s.capacity, s.fatigue_u_min)
}

/// A load held for a time, its per-step constants (exponentials) computed once, for a replay that
/// holds the same load for the same time many times (every cycle of a long task): each update is
/// then a few multiplications, and exactly — bit for bit — what [`MaParams::hold`] gives (which
/// is built on it).
#[derive(Debug, Clone, Copy)]
pub struct PreparedHold {
    f: f64,
    /// `None`: nothing changes (no load and no recovery, or no time).
    step: Option<super::schedule::Prepared<f64>>,
}

impl PreparedHold {
    fn new(p: &MaParams, f: f64, t_min: f64) -> Self {
        let changes = !(p.k_per_min * f + p.r_at(f) <= 0.0 || t_min <= 0.0);
        PreparedHold {
            f,
            step: changes.then(|| {
                super::schedule::Prepared::new(p, &super::schedule::HeldStep { f, t_min })
            }),
        }
    }

    /// The held step's constants, unless the group does not change from `state` (unloaded and
    /// fully rested: the common case of a muscle group the task never loads, whose exact update
    /// returns the same numbers, bit for bit).
    #[inline]
    fn changing(&self, state: &MaState) -> Option<&super::schedule::Prepared<f64>> {
        self.step
            .as_ref()
            .filter(|_| !(self.f == 0.0 && state.capacity == 1.0 && state.fast_deficit == 0.0))
    }

    fn point(state: &MaState) -> super::schedule::Point<f64> {
        super::schedule::Point {
            c: state.capacity,
            d: state.fast_deficit,
        }
    }

    /// The capacity after the step from `state`, alone (the same number [`PreparedHold::hold`]
    /// gives, without the fatigue index's logarithms).
    #[inline]
    pub fn capacity(&self, state: &MaState) -> f64 {
        self.changing(state).map_or(state.capacity, |p| {
            p.capacity(Self::point(state)).c.clamp(C_FLOOR, 1.0)
        })
    }

    /// Moves `state`'s capacity and fast deficit over the step, as [`PreparedHold::hold`] does,
    /// leaving its fatigue index alone.
    #[inline]
    pub fn advance(&self, state: &mut MaState) {
        if let Some(p) = self.changing(state) {
            let x = p.capacity(Self::point(state));
            state.capacity = x.c.clamp(C_FLOOR, 1.0);
            state.fast_deficit = x.d.clamp(0.0, 1.0);
        }
    }

    /// Updates `state` as [`MaParams::hold`]; false once U no longer fits in a double.
    #[inline]
    pub fn hold(&self, state: &mut MaState) -> bool {
        let Some(p) = self.changing(state) else {
            return true;
        };
        let (x, du) = p.apply(Self::point(state));
        state.capacity = x.c.clamp(C_FLOOR, 1.0);
        state.fast_deficit = x.d.clamp(0.0, 1.0);
        let du = if self.f == 0.0 { 0.0 } else { du.max(0.0) };
        let u = state.fatigue_u_min + du;
        if u.is_finite() {
            state.fatigue_u_min = u;
            true
        } else {
            state.fatigue_u_min = f64::MAX;
            false
        }
    }
}

impl MaParams {
    /// Checked constructor with a constant recovery rate `r_per_min` (0: the paper's model).
    pub fn new(k_per_min: f64, r_per_min: f64) -> Result<Self, FatigueError> {
        let recovery = if r_per_min == 0.0 {
            Recovery::None
        } else {
            Recovery::Constant { r_per_min }
        };
        Self::with_recovery(k_per_min, recovery)
    }

    /// Checked constructor with any recovery form.
    pub fn with_recovery(k_per_min: f64, recovery: Recovery) -> Result<Self, FatigueError> {
        if !(k_per_min.is_finite() && (K_MIN_PER_MIN..=K_MAX_PER_MIN).contains(&k_per_min)) {
            return Err(FatigueError::BadK(k_per_min));
        }
        recovery.validate()?;
        Ok(MaParams {
            k_per_min,
            recovery,
        })
    }

    /// Recovery rate \[1/min\] while holding `f`.
    #[inline]
    pub fn r_at(&self, f: f64) -> f64 {
        self.recovery.rate_per_min(f)
    }

    /// Holds relative load `f ≥ 0` for `dt_s` seconds: exact update of capacity and U.
    /// Returns `false` when U no longer fits in a double (U is then left at `f64::MAX`): the
    /// group was held far past exhaustion and its index has no meaningful value.
    ///
    /// Inputs are trusted (checked at the boundary): `f` finite and ≥ 0, `dt_s` finite and ≥ 0.
    ///
    /// ```
    /// use posture_opt::fatigue::{MaParams, MaState};
    /// let p = MaParams::default(); // k = 1/min, no recovery
    /// let mut s = MaState::FRESH;
    /// assert!(p.hold(&mut s, 0.5, 60.0)); // 50 %MVC for one minute
    /// assert!((s.capacity - (-0.5f64).exp()).abs() < 1e-15);
    /// // Eq. 6: U = (e^{2kF} - 1) / 2k with F = 0.5 min
    /// assert!((s.fatigue_u_min - (1f64.exp() - 1.0) / 2.0).abs() < 1e-14);
    /// ```
    #[inline]
    pub fn hold(&self, state: &mut MaState, f: f64, dt_s: f64) -> bool {
        self.prepare(f, dt_s).hold(state)
    }

    /// Holding `f` for `dt_s` seconds prepared once, for holding it again and again
    /// ([`PreparedHold`]).
    #[inline]
    pub fn prepare(&self, f: f64, dt_s: f64) -> PreparedHold {
        self.prepare_min(f, s_to_min(dt_s))
    }

    fn prepare_min(&self, f: f64, t_min: f64) -> PreparedHold {
        PreparedHold::new(self, f, t_min)
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
        let r = self.r_at(f);
        let lambda = self.k_per_min * f + r;
        let c_inf = r / lambda;
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

    /// Time \[s\] until capacity falls to the held load `f` from `state`, if that happens within
    /// `dt_s`; `Some(0)` if it starts at or below it. With a fast deficit and a light load (the
    /// routed recovery below its limit load) the capacity has no closed-form inverse and the
    /// time is found by bisection on the exact step.
    pub fn time_to_exhaustion_within_s(&self, state: &MaState, f: f64, dt_s: f64) -> Option<f64> {
        if f <= 0.0 {
            return None;
        }
        if state.capacity <= f {
            return Some(0.0);
        }
        if state.fast_deficit == 0.0 || self.recovery.fast_rate_per_min(f) == 0.0 {
            return self
                .time_to_exhaustion_s(state.capacity, f)
                .filter(|&t| t < dt_s);
        }
        let capacity_after = |t_s: f64| {
            let mut s = *state;
            self.prepare(f, t_s).advance(&mut s);
            s.capacity
        };
        if capacity_after(dt_s) > f {
            return None;
        }
        let (mut lo, mut hi) = (0.0, dt_s);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if capacity_after(mid) > f {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-12 * dt_s {
                break;
            }
        }
        Some(hi)
    }

    /// Maximum endurance time \[min\] of a fresh muscle holding `f` (paper Eq. 8 without
    /// recovery: `MET = -ln f / (k f)`).
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

    /// The largest load a rested group can hold forever: the `f*` where recovery's equilibrium
    /// `c∞ = R(f)/(k f + R(f))` equals the load (bisection on the exact condition
    /// `R(f)(1 − f) = k f²`). 0 without recovery.
    ///
    /// ```
    /// use posture_opt::fatigue::MaParams;
    /// // constant R: f* = (−R + √(R² + 4kR)) / 2k
    /// let p = MaParams::new(1.0, 0.3).unwrap();
    /// let closed = (-0.3 + (0.09f64 + 1.2).sqrt()) / 2.0;
    /// assert!((p.sustainable_load() - closed).abs() < 1e-12);
    /// ```
    pub fn sustainable_load(&self) -> f64 {
        let margin = |f: f64| self.r_at(f) * (1.0 - f) - self.k_per_min * f * f;
        if self.r_at(0.0) == 0.0 {
            return 0.0;
        }
        // margin(0) = R(0) > 0, margin(1) = −k < 0, and margin decreases in f.
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if margin(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-15 {
                break;
            }
        }
        0.5 * (lo + hi)
    }
}

/// A cycle of held steps as a map of the capacity at its start: `c ↦ A c + B`. Each step held
/// at load `f` for `t` is `c ↦ c∞ + (c − c∞) e^{−λt}` (`λ = k f + R(f)`, `c∞ = R/λ`), so a cycle
/// is affine with slope `A = e^{−Σλt} > 0`, and `n` cycles take `c0` to `c* + (c0 − c*) Aⁿ`
/// (`c* = B/(1 − A)`): monotone in `n`, which is what lets a long run of identical cycles be
/// skipped in O(1) when only capacities are wanted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleMap {
    /// `ln A` (≤ 0).
    pub ln_a: f64,
    /// `B`.
    pub b: f64,
}

impl CycleMap {
    /// The map of holding `(load, seconds)` steps in order with `p`.
    pub fn new(p: &MaParams, steps: impl IntoIterator<Item = (f64, f64)>) -> Self {
        let (mut ln_a, mut b) = (0.0f64, 0.0f64);
        for (f, t_s) in steps {
            let r = p.r_at(f);
            let lambda = p.k_per_min * f + r;
            if !(lambda > 0.0 && t_s > 0.0) {
                continue;
            }
            let lt = -lambda * s_to_min(t_s);
            // the step: c ↦ s c + c∞ (1 − s), s = e^{lt}
            b = b * lt.exp() + (r / lambda) * -lt.exp_m1();
            ln_a += lt;
        }
        CycleMap { ln_a, b }
    }

    /// Capacity after `n` cycles from `c0` (kept within the state's bounds, like [`MaParams::hold`]).
    pub fn after(&self, c0: f64, n: f64) -> f64 {
        if n <= 0.0 || self.ln_a >= 0.0 {
            return c0;
        }
        let c_star = self.b / -self.ln_a.exp_m1();
        (c_star + (c0 - c_star) * (self.ln_a * n).exp()).clamp(C_FLOOR, 1.0)
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
    /// instants over `[0, t_end_s]` (each sample exact, chained step by step). Samples stop
    /// early where U would no longer fit in a double.
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
            if !self.hold(&mut s, f, dt) {
                break;
            }
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
/// The three slices must be equally long (shorter ones bound the loop). Returns `false` if any
/// group's U overflowed (see [`MaParams::hold`]).
#[inline]
pub fn hold_all(params: &[MaParams], states: &mut [MaState], loads: &[f64], dt_s: f64) -> bool {
    let mut ok = true;
    for ((p, s), &f) in params.iter().zip(states.iter_mut()).zip(loads) {
        ok &= p.hold(s, f, dt_s);
    }
    ok
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The routed model's equations as docs/fatigue-parameters.md states them, integrated by
    /// classical Runge–Kutta with 0.36-ms steps: `(capacity, fast deficit, U)` after holding
    /// each `(f, seconds)` in turn from rest.
    fn integrate(k: f64, rec: (f64, f64, f64, f64), holds: &[(f64, f64)]) -> (f64, f64, f64) {
        let (slow, fast, f_lim, share) = rec;
        let ramp = |x: f64| {
            let x = x.clamp(0.0, 1.0);
            x * x * (3.0 - 2.0 * x)
        };
        let perf = |f: f64| {
            if f < f_lim {
                ramp(1.0 - f / f_lim)
            } else {
                0.0
            }
        };
        let (mut df, mut ds, mut u) = (0.0f64, 0.0f64, 0.0f64);
        for &(f, t_s) in holds {
            let phi = share * ramp((f - 0.25) / 0.25);
            let (rf, rs) = (fast * perf(f), slow * perf(f));
            let deriv = |df: f64, ds: f64| {
                let c = 1.0 - df - ds;
                (
                    phi * k * f * c - rf * df,
                    (1.0 - phi) * k * f * c - rs * ds,
                    f / (c * c),
                )
            };
            let n = (t_s / 60.0 / 6e-6).ceil() as usize;
            let h = t_s / 60.0 / n as f64;
            for _ in 0..n {
                let a = deriv(df, ds);
                let b = deriv(df + 0.5 * h * a.0, ds + 0.5 * h * a.1);
                let c = deriv(df + 0.5 * h * b.0, ds + 0.5 * h * b.1);
                let d = deriv(df + h * c.0, ds + h * c.1);
                df += h / 6.0 * (a.0 + 2.0 * b.0 + 2.0 * c.0 + d.0);
                ds += h / 6.0 * (a.1 + 2.0 * b.1 + 2.0 * c.1 + d.1);
                u += h / 6.0 * (a.2 + 2.0 * b.2 + 2.0 * c.2 + d.2);
            }
        }
        (1.0 - df - ds, df, u)
    }

    #[test]
    fn routed_holds_match_an_integration_of_the_stated_equations() {
        let rec = (0.319, 20.0, 0.085, 0.4);
        let p = MaParams::with_recovery(
            1.4,
            Recovery::Routed {
                slow_rest_per_min: rec.0,
                fast_rest_per_min: rec.1,
                limit_fmvc: rec.2,
                fast_share_max: rec.3,
            },
        )
        .unwrap();
        // heavy holds feed the fast deficit (0.6, 0.35), light ones drain it with U still
        // growing (0.03, 0.02: the last one long enough to pass the quadrature's 40 half-lives),
        // a rest, and a load between the limit and the routing (0.1)
        let holds = [
            (0.6, 40.0),
            (0.03, 6.0),
            (0.0, 10.0),
            (0.1, 5.0),
            (0.35, 5.0),
            (0.02, 200.0),
            (0.45, 3.0),
            (0.0, 1.0),
        ];
        let mut s = MaState::FRESH;
        for (i, &(f, t)) in holds.iter().enumerate() {
            assert!(p.hold(&mut s, f, t));
            let (c, d, u) = integrate(1.4, rec, &holds[..=i]);
            assert!(
                (s.capacity - c).abs() < 1e-9,
                "step {i}: c {} vs {c}",
                s.capacity
            );
            assert!(
                (s.fast_deficit - d).abs() < 1e-9,
                "step {i}: d {} vs {d}",
                s.fast_deficit
            );
            assert!(
                (s.fatigue_u_min - u).abs() < 1e-9 * u,
                "step {i}: U {} vs {u}",
                s.fatigue_u_min
            );
        }
        assert!(s.fast_deficit > 0.0);
    }

    #[test]
    fn routed_below_the_routing_load_is_the_single_rate_model() {
        let routed = MaParams::with_recovery(
            0.9,
            Recovery::Routed {
                slow_rest_per_min: 0.37,
                fast_rest_per_min: 20.0,
                limit_fmvc: 0.085,
                fast_share_max: 0.134,
            },
        )
        .unwrap();
        let single = MaParams::with_recovery(
            0.9,
            Recovery::Perfusion {
                rest_per_min: 0.37,
                limit_fmvc: 0.085,
            },
        )
        .unwrap();
        let (mut a, mut b) = (MaState::FRESH, MaState::FRESH);
        for &(f, t) in &[
            (0.2, 30.0),
            (0.05, 5.0),
            (0.25, 60.0),
            (0.0, 20.0),
            (0.12, 300.0),
        ] {
            routed.hold(&mut a, f, t);
            single.hold(&mut b, f, t);
            assert_eq!(a, b);
        }
    }

    #[test]
    fn the_routed_form_is_checked() {
        let r = |slow, fast, lim, share| {
            MaParams::with_recovery(
                1.0,
                Recovery::Routed {
                    slow_rest_per_min: slow,
                    fast_rest_per_min: fast,
                    limit_fmvc: lim,
                    fast_share_max: share,
                },
            )
        };
        assert!(r(0.3, 20.0, 0.085, 0.1).is_ok());
        assert!(matches!(
            r(0.3, 0.2, 0.085, 0.1),
            Err(FatigueError::BadFastRate { .. })
        ));
        assert!(matches!(
            r(0.3, 20.0, 0.3, 0.1),
            Err(FatigueError::BadRoutedLimit(_))
        ));
        assert!(matches!(
            r(0.3, 20.0, 0.085, 1.5),
            Err(FatigueError::BadShare(_))
        ));
        assert!(matches!(
            r(0.0, 20.0, 0.085, 0.1),
            Err(FatigueError::BadR(_))
        ));
    }
}
