//! Fatigue over many repetitions of one cycle of held loads, at a cost that does not grow with
//! the number of cycles — what the planner's objective needs for an 8-hour or a 24-hour shift.
//!
//! A muscle group holds the loads `f_i` for `t_i` in turn, and the cycle repeats `N` times. Each
//! held step maps capacity affinely (`c ↦ a_i + (c − a_i) s_i`, `s_i = e^{−λ_i t_i}`), so one
//! cycle is an affine map `c ↦ A c + B` and the capacity at the start of cycle n is exactly
//! `c_n = c* + (c_0 − c*) Aⁿ` with the periodic steady state `c* = B / (1 − A)`. The U gained in
//! one cycle, `u(c)`, is the chain of the steps' exact increments. The total is `Σ_{n<N} u(c_n)`:
//!
//! * without recovery in any step, `u(c) = u(1)/c²` and `c_n = c_0 Aⁿ`, so the sum is the
//!   geometric closed form `u(1)/c_0² · (e^{2NL} − 1)/(e^{2L} − 1)` with `L = −ln A`, kept in a
//!   scaled form ([`ScaledU`]) so that paper-model shifts of any length never overflow;
//! * cycles are summed exactly until `|c_n − c*| ≤ 10⁻³ c*`, and the rest in closed form from
//!   the second-order expansion of `u` about `c*` (geometric sums of `δ` and `δ²`; the neglected
//!   third-order term is below 10⁻⁹ of the total);
//! * when a slow transient (`L < 0.2` per cycle) has not settled after [`EXACT_CYCLES`] exact
//!   cycles (a long task), the rest is summed by the Euler–Maclaurin
//!   formula to its B₄ term: `Σ φ(j) = ∫φ + (φ(0) + φ(m−1))/2 + (φ'(m−1) − φ'(0))/12 −
//!   (φ'''(m−1) − φ'''(0))/720`, with `φ(x) = u(c* + δ e^{−Lx})`; the integral becomes
//!   `(1/L) ∫ u(c*+y) d ln|y|` over the transient's range, by 12-point Gauss–Legendre on panels
//!   0.5 wide in `ln|y|`. φ varies at rates up to 2L (U grows like `e^{2Lx}` when recovery is
//!   negligible), so the first neglected term is about `(2L)⁵/30240` of the transient's scale
//!   (below 1.2·10⁻⁵ for `L < 0.2`).
//!
//! Everything is generic over [`Real`], so one pass gives the value and, with [`Dual2`](super::dual::Dual2),
//! its first and second derivatives with respect to one step's load.

use super::dual::Real;
use super::ma::MaParams;

/// One held step of a cycle: relative load and duration \[min\].
#[derive(Debug, Clone, Copy)]
pub struct HeldStep<T> {
    pub f: T,
    pub t_min: f64,
}

/// A fatigue index `u · e^{ln_scale}` \[min\]: `ln_scale` is 0 unless the value would overflow.
#[derive(Debug, Clone, Copy)]
pub struct ScaledU<T> {
    pub u: T,
    pub ln_scale: f64,
}

/// Total U over the cycles (added to what the group had) and the capacity after them.
#[derive(Debug, Clone, Copy)]
pub struct CyclesOutcome<T> {
    pub u_min: ScaledU<T>,
    pub capacity_end: T,
}

/// A step with its per-step constants precomputed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Prepared<T> {
    f: T,
    /// No recovery during the step: `c1 = c0 s`, `ΔU = e2 / c0²`.
    no_recovery: bool,
    lambda: T,
    a: T,
    /// `e^{−λt}` and `1 − e^{−λt}` (formed without cancellation for small λt).
    s: T,
    one_minus_s: T,
    /// `e^{λt} − 1` (recovery, λt ≤ 30) or `(e^{2kft} − 1)/2k` (no recovery).
    xm1_or_e2: T,
    lt: T,
    big: bool,
}

const LT_SWITCH: f64 = 30.0;

/// Cycles summed exactly before a transient that has not settled is summed by Euler–Maclaurin.
/// The Euler–Maclaurin tail costs about a thousand cycle evaluations (its Gauss–Legendre panels),
/// so fewer cycles than that are cheaper, and exact, summed one by one.
pub const EXACT_CYCLES: u64 = 1024;

#[inline]
fn g_of_w<T: Real>(w: T) -> T {
    if w.val().abs() < 1e-3 {
        T::cst(0.5) + w * (T::cst(-2.0 / 3.0) + w * (T::cst(0.75) - w * 0.8))
    } else {
        (w.ln_1p() - w / (w + 1.0)) / (w * w)
    }
}

impl<T: Real> Prepared<T> {
    fn new(p: &MaParams, st: &HeldStep<T>) -> Self {
        Self::from_rates(p.k_per_min, st.f, recovery_rate(p, st.f), st.t_min)
    }

    /// Holding `f` for `t` minutes with fatigue rate `k` and recovery rate `r` (per minute).
    pub(crate) fn from_rates(k: f64, f: T, r: T, t: f64) -> Self {
        let lambda = f * k + r;
        if r.val() == 0.0 {
            let x = f * (k * t);
            return Prepared {
                f,
                no_recovery: true,
                lambda,
                a: T::cst(0.0),
                s: (-x).exp(),
                one_minus_s: -(-x).exp_m1(),
                xm1_or_e2: (x * 2.0).exp_m1() / (2.0 * k),
                lt: x,
                big: false,
            };
        }
        let a = r / lambda;
        let lt = lambda * t;
        let big = lt.val() > LT_SWITCH;
        let s = (-lt).exp();
        Prepared {
            f,
            no_recovery: false,
            lambda,
            a,
            s,
            one_minus_s: -(-lt).exp_m1(),
            xm1_or_e2: if big { T::cst(0.0) } else { lt.exp_m1() },
            lt,
            big,
        }
    }

    /// Capacity after the step from capacity `c0`.
    #[inline]
    pub(crate) fn capacity(&self, c0: T) -> T {
        if self.no_recovery {
            c0 * self.s
        } else if !self.big {
            // c1 = c0 e^{−λt} + a (1 − e^{−λt}): two non-negative terms, so a small capacity
            // keeps its relative precision (a + (c0 − a) e^{−λt} would cancel)
            let xm1 = self.xm1_or_e2;
            (c0 + self.a * xm1) / (xm1 + 1.0)
        } else {
            c0 * self.s + self.a * self.one_minus_s
        }
    }

    /// Capacity after the step and the U gained, from capacity `c0`.
    #[inline]
    pub(crate) fn apply(&self, c0: T) -> (T, T) {
        let c1 = self.capacity(c0);
        if self.no_recovery {
            return (c1, self.xm1_or_e2 / (c0 * c0));
        }
        let a = self.a;
        let f = self.f;
        if !self.big {
            let xm1 = self.xm1_or_e2;
            let y = xm1 / c0;
            let w = a * y;
            let du = f / self.lambda * y * (T::cst(1.0) / (c0 * (w + 1.0)) + g_of_w(w) * y);
            (c1, du)
        } else {
            // ΔU = f/(λa²)·h(w) + f/(λ a c0)·w/(1+w), w = a (e^{λt} − 1)/c0, h(w) = ln(1+w) −
            // w/(1+w) ≥ 0: no cancellation however small a = R/λ is; w is formed from its
            // logarithm, so e^{λt} never overflows.
            let ln_w = (a / c0).ln() + self.lt + (-self.s).ln_1p();
            let (h_over_a2, q) = if ln_w.val() > 36.0 {
                // w > 4e15: ln(1+w) = ln w + 1/w to double precision.
                let inv_w = (-ln_w).exp();
                let q = T::cst(1.0) / (inv_w + 1.0);
                ((ln_w + inv_w - q) / a / a, q)
            } else {
                let w = ln_w.exp();
                // h(w)/a² = g(w)·(w/a)², with w/a = (e^{λt} − 1)/c0 formed without a.
                let y = (ln_w - a.ln()).exp();
                (g_of_w(w) * y * y, w / (w + 1.0))
            };
            let du = f / self.lambda * (h_over_a2 + q / (a * c0));
            (c1, du)
        }
    }
}

/// `R(f)` for a generic number (the form of [`crate::fatigue::Recovery`], differentiable).
fn recovery_rate<T: Real>(p: &MaParams, f: T) -> T {
    use super::ma::Recovery;
    match p.recovery {
        Recovery::None => T::cst(0.0),
        Recovery::Constant { r_per_min } => T::cst(r_per_min),
        Recovery::Perfusion {
            rest_per_min,
            limit_fmvc,
        } => {
            let x = -(f / limit_fmvc) + 1.0;
            if x.val() > 0.0 {
                x * x * (-(x * 2.0) + 3.0) * rest_per_min
            } else {
                T::cst(0.0)
            }
        }
    }
}

/// The chain of one cycle's steps.
struct Cycle<T> {
    steps: Vec<Prepared<T>>,
}

impl<T: Real> Cycle<T> {
    /// U gained over one cycle from capacity `c`, and the capacity after it.
    #[inline]
    fn run(&self, c: T) -> (T, T) {
        let mut c = c;
        let mut u = T::cst(0.0);
        for s in &self.steps {
            let (c1, du) = s.apply(c);
            u = u + du;
            c = c1;
        }
        (u, c)
    }
    #[inline]
    fn u(&self, c: T) -> T {
        self.run(c).0
    }
}

/// Gauss–Legendre nodes and weights on [−1, 1], 12 points.
const GL12: [(f64, f64); 6] = [
    (0.125_233_408_511_468_9, 0.249_147_045_813_402_8),
    (0.367_831_498_998_180_2, 0.233_492_536_538_354_8),
    (0.587_317_954_286_617_4, 0.203_167_426_723_065_9),
    (0.769_902_674_194_304_7, 0.160_078_328_543_346_2),
    (0.904_117_256_370_474_9, 0.106_939_325_995_318_4),
    (0.981_560_634_246_719_3, 0.047_175_336_386_511_8),
];

/// U accumulated by a muscle group (parameters `p`, capacity `c0` now) over `n_cycles`
/// repetitions of `steps`, and its capacity at the end. Exact up to the stated expansion
/// errors (see the module docs); O(1) in `n_cycles`.
///
/// ```
/// use posture_opt::fatigue::{MaParams, MaState};
/// use posture_opt::fatigue::schedule::{repeated_cycles, HeldStep};
/// let p = MaParams::new(1.0, 0.5).unwrap();
/// let steps = [HeldStep { f: 0.3, t_min: 0.1 }, HeldStep { f: 0.0, t_min: 0.05 }];
/// let total = repeated_cycles(&p, &steps, 1.0, 500);
/// // the same by holding every step of every cycle
/// let mut s = MaState::FRESH;
/// for _ in 0..500 { for st in &steps { p.hold(&mut s, st.f, st.t_min * 60.0); } }
/// assert!((total.u_min.u - s.fatigue_u_min).abs() < 1e-7 * s.fatigue_u_min);
/// assert!((total.capacity_end - s.capacity).abs() < 1e-12);
/// ```
pub fn repeated_cycles<T: Real>(
    p: &MaParams,
    steps: &[HeldStep<T>],
    c0: f64,
    n_cycles: u64,
) -> CyclesOutcome<T> {
    let cycle = Cycle {
        steps: steps.iter().map(|s| Prepared::new(p, s)).collect(),
    };
    let zero = T::cst(0.0);
    let c0t = T::cst(c0);
    if n_cycles == 0 || cycle.steps.is_empty() {
        return CyclesOutcome {
            u_min: ScaledU {
                u: zero,
                ln_scale: 0.0,
            },
            capacity_end: c0t,
        };
    }
    // Cycle map c ↦ A c + B; ln A = −Σ λ_i t_i.
    let mut a_map = T::cst(1.0);
    let mut b_map = zero;
    let mut ln_a = zero;
    for s in &cycle.steps {
        a_map = a_map * s.s;
        b_map = b_map * s.s + s.a * s.one_minus_s;
        ln_a = ln_a - s.lt;
    }
    let big_l = -ln_a.val();
    if big_l <= 0.0 {
        // Nothing loaded and nothing recovering: capacity and U stay.
        return CyclesOutcome {
            u_min: ScaledU {
                u: zero,
                ln_scale: 0.0,
            },
            capacity_end: c0t,
        };
    }
    if cycle.steps.iter().all(|s| s.no_recovery) {
        return no_recovery_total(&cycle, c0t, ln_a, n_cycles);
    }
    let c_star = b_map / -ln_a.exp_m1();
    let mut c = c0t;
    let mut u = zero;
    let mut n = 0u64;
    let slow = big_l < 0.2;
    while n < n_cycles {
        let delta = c.val() - c_star.val();
        let settled = delta.abs() <= 1e-3 * c_star.val();
        if settled || (slow && n >= EXACT_CYCLES) {
            let m = n_cycles - n;
            let tail = if settled {
                taylor_tail(&cycle, c_star, c - c_star, a_map, ln_a, m)
            } else {
                euler_maclaurin_tail(&cycle, c_star, c - c_star, ln_a, m)
            };
            u = u + tail;
            c = c_star + (c - c_star) * (ln_a * m as f64).exp();
            n = n_cycles;
            break;
        }
        let (du, c1) = cycle.run(c);
        u = u + du;
        c = c1;
        n += 1;
    }
    let _ = n;
    if !u.val().is_finite() {
        // U passed the largest double: the value in logarithms (its derivatives are meaningless
        // so far past exhaustion and are dropped).
        let (ln_u, ln_c) = log_domain_cycles(&cycle, c0, n_cycles);
        return CyclesOutcome {
            u_min: ScaledU {
                u: T::cst(1.0),
                ln_scale: ln_u,
            },
            capacity_end: T::cst(ln_c.exp()),
        };
    }
    CyclesOutcome {
        u_min: ScaledU { u, ln_scale: 0.0 },
        capacity_end: c,
    }
}

/// `ln(e^x + e^y)`.
fn ln_add(x: f64, y: f64) -> f64 {
    let (hi, lo) = if x >= y { (x, y) } else { (y, x) };
    if lo == f64::NEG_INFINITY {
        hi
    } else {
        hi + (lo - hi).exp().ln_1p()
    }
}

/// The cycles held one by one with U and capacity in logarithms: `(ln U, ln c_end)`.
/// Without recovery the rate is k = λ/f (only called where U overflows, so f > 0 somewhere).
fn log_domain_cycles<T: Real>(cycle: &Cycle<T>, c0: f64, n_cycles: u64) -> (f64, f64) {
    let mut ln_u = f64::NEG_INFINITY;
    let mut ln_c = c0.ln();
    for _ in 0..n_cycles {
        for st in &cycle.steps {
            let f = st.f.val();
            if st.no_recovery {
                let x = st.lt.val();
                if f > 0.0 && x > 0.0 {
                    // ΔU = (e^{2x} − 1) / (2k c0²), with 1/(2k) = xm1_or_e2 / (e^{2x} − 1)
                    let ln_em1 = if 2.0 * x > 1.0 {
                        2.0 * x + (-(-2.0 * x).exp()).ln_1p()
                    } else {
                        (2.0 * x).exp_m1().ln()
                    };
                    // without recovery λ = k f
                    let ln_2k = (2.0 * st.lambda.val() / f).ln();
                    ln_u = ln_add(ln_u, ln_em1 - ln_2k - 2.0 * ln_c);
                }
                ln_c -= x;
            } else {
                let c = ln_c.exp();
                let (c1, du) = st.apply(T::cst(c));
                if f > 0.0 {
                    let du = du.val();
                    let ln_du = if du.is_finite() && c > 0.0 {
                        du.ln()
                    } else {
                        // c0 → 0: ΔU → f/(λ a c0) (the w/(1+w) → 1 term dominates).
                        (f / (st.lambda.val() * st.a.val())).ln() - ln_c
                    };
                    ln_u = ln_add(ln_u, ln_du);
                }
                ln_c = c1.val().max(f64::MIN_POSITIVE).ln();
            }
        }
    }
    (ln_u, ln_c)
}

/// The lowest capacity a group reaches at the end of the steps marked in `mask` over
/// `n_cycles` repetitions (capacity falls through a loaded step, so a step's end is its lowest
/// point; across cycles the capacity at a given step moves monotonically toward its periodic
/// steady state, so the first and the last cycle bound it). With its derivatives when `T` is
/// [`Dual2`](super::dual::Dual2).
pub fn lowest_end_capacity<T: Real>(
    p: &MaParams,
    steps: &[HeldStep<T>],
    mask: &[bool],
    c0: f64,
    n_cycles: u64,
) -> T {
    let cycle = Cycle {
        steps: steps.iter().map(|s| Prepared::new(p, s)).collect(),
    };
    let mut a_map = T::cst(1.0);
    let mut b_map = T::cst(0.0);
    let mut ln_a = T::cst(0.0);
    for s in &cycle.steps {
        a_map = a_map * s.s;
        b_map = b_map * s.s + s.a * s.one_minus_s;
        ln_a = ln_a - s.lt;
    }
    let first = T::cst(c0);
    let last = if n_cycles <= 1 || -ln_a.val() <= 0.0 {
        first
    } else if cycle.steps.iter().all(|s| s.no_recovery) {
        (ln_a * (n_cycles - 1) as f64).exp() * c0
    } else {
        let c_star = b_map / -ln_a.exp_m1();
        c_star + (first - c_star) * (ln_a * (n_cycles - 1) as f64).exp()
    };
    let mut lowest = T::cst(f64::INFINITY);
    for start in [first, last] {
        let mut c = start;
        for (s, m) in cycle.steps.iter().zip(mask) {
            c = s.apply(c).0;
            if *m && c.val() < lowest.val() {
                lowest = c;
            }
        }
    }
    lowest
}

/// Without recovery: `u(c) = u(1)/c²`, `c_n = c_0 Aⁿ`, total `u(1)/c0² · (e^{2NL} − 1)/(e^{2L} − 1)`.
fn no_recovery_total<T: Real>(cycle: &Cycle<T>, c0: T, ln_a: T, n_cycles: u64) -> CyclesOutcome<T> {
    let (u1, _) = cycle.run(T::cst(1.0));
    let l2 = -ln_a * 2.0; // 2L
    let n = n_cycles as f64;
    let z = l2 * n; // 2NL
    // (e^z − 1)/(e^{2L} − 1) = e^{z} · (1 − e^{−z}) / (e^{2L} − 1): scale out e^{z} when large.
    let (ratio, ln_scale) = if z.val() < 600.0 {
        (z.exp_m1() / l2.exp_m1(), 0.0)
    } else {
        (
            (-(-z).exp() + 1.0) / l2.exp_m1() * (z - z.val()).exp(),
            z.val(),
        )
    };
    let c_end_ln = c0.ln() + ln_a * n;
    CyclesOutcome {
        u_min: ScaledU {
            u: u1 / (c0 * c0) * ratio,
            ln_scale,
        },
        capacity_end: c_end_ln.exp(),
    }
}

/// `Σ_{j<m} u(c* + δ A^j)` for small `δ`: `m u(c*) + u' δ G₁ + ½ u'' δ² G₂`.
fn taylor_tail<T: Real>(cycle: &Cycle<T>, c_star: T, delta: T, a_map: T, ln_a: T, m: u64) -> T {
    let h = (delta.val().abs()).max(1e-6 * c_star.val());
    let u0 = cycle.u(c_star);
    let up = cycle.u(c_star + h);
    let um = cycle.u(c_star - h);
    let u1 = (up - um) / (2.0 * h);
    let u2 = (up - u0 * 2.0 + um) / (h * h);
    let mf = m as f64;
    let am = (ln_a * mf).exp();
    let g1 = (-am + 1.0) / (-a_map + 1.0);
    let g2 = (-am * am + 1.0) / (-a_map * a_map + 1.0);
    u0 * mf + u1 * delta * g1 + u2 * delta * delta * g2 * 0.5
}

/// `Σ_{j<m} φ(j)`, `φ(x) = u(c* + δ e^{−Lx})`, by Euler–Maclaurin with the integral by
/// Gauss–Legendre in `y = δ e^{−Lx}`.
fn euler_maclaurin_tail<T: Real>(cycle: &Cycle<T>, c_star: T, delta: T, ln_a: T, m: u64) -> T {
    let mf = m as f64;
    let big_l = -ln_a; // > 0
    let u_star = cycle.u(c_star);
    let y0 = delta;
    let y1 = delta * (ln_a * (mf - 1.0)).exp();
    // ∫_0^{m−1} φ dx = (1/L) ∫_{ln|y1|}^{ln|y0|} u(c* + y) d ln|y|: composite Gauss–Legendre on
    // panels at most 0.5 wide in ln|y| (u varies like 1/c², so it is smooth in ln|y| even when
    // c* ≪ |δ|). Where |y| < 1e-14 c*, φ = u* to double precision: that part is u* times its
    // length in x. u itself is integrated (not u − u*), so a c* far below the transient's
    // capacities, where u* dwarfs the transient's u, cannot cancel.
    let sign = if delta.val() < 0.0 { -1.0 } else { 1.0 };
    let ln_hi = (delta * sign).ln();
    let ln_lo_full = ln_hi + ln_a * (mf - 1.0);
    let cut = (1e-14 * c_star.val().max(f64::MIN_POSITIVE)).ln();
    let ln_lo = if ln_lo_full.val() < cut {
        T::cst(cut.min(ln_hi.val()))
    } else {
        ln_lo_full
    };
    let width = (ln_hi - ln_lo).val();
    let panels = ((width / 0.5).ceil() as usize).clamp(1, 4000);
    let step = (ln_hi - ln_lo) / panels as f64;
    let mut integral = T::cst(0.0);
    for p in 0..panels {
        let mid = ln_lo + step * (p as f64 + 0.5);
        for &(x, w) in &GL12 {
            for sgn in [-1.0, 1.0] {
                let y = (mid + step * (0.5 * x * sgn)).exp() * sign;
                integral = integral + cycle.u(c_star + y) * (step * (0.5 * w));
            }
        }
    }
    let integral = (integral + u_star * (ln_lo - ln_lo_full)) / big_l;
    let phi0 = cycle.u(c_star + y0);
    let phi1 = cycle.u(c_star + y1);
    // With g(y) = u(c* + y) and d/dx = −L y d/dy:
    //   φ' = −L y g',  φ''' = −L³ (y g' + 3 y² g'' + y³ g''').
    let du_dc = |c: T| {
        let h = 1e-6 * c.val();
        (cycle.u(c + h) - cycle.u(c - h)) / (2.0 * h)
    };
    let d3phi = |y: T| {
        let c = c_star + y;
        let h = 0.02 * c.val();
        let (um2, um1, u0, up1, up2) = (
            cycle.u(c - 2.0 * h),
            cycle.u(c - h),
            cycle.u(c),
            cycle.u(c + h),
            cycle.u(c + 2.0 * h),
        );
        let g2 = (up1 - u0 * 2.0 + um1) / (h * h);
        let g3 = (up2 - up1 * 2.0 + um1 * 2.0 - um2) / (2.0 * h * h * h);
        -big_l * big_l * big_l * (y * du_dc(c) + y * y * g2 * 3.0 + y * y * y * g3)
    };
    let dphi0 = -big_l * y0 * du_dc(c_star + y0);
    let dphi1 = -big_l * y1 * du_dc(c_star + y1);
    // Euler–Maclaurin to the B₄ term: + (φ'(b) − φ'(a))/12 − (φ'''(b) − φ'''(a))/720.
    integral + (phi0 + phi1) * 0.5 + (dphi1 - dphi0) / 12.0 - (d3phi(y1) - d3phi(y0)) / 720.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fatigue::dual::Dual2;
    use crate::fatigue::ma::{MaState, Recovery};

    fn simulate(p: &MaParams, steps: &[(f64, f64)], c0: f64, n: u64) -> (f64, f64) {
        let mut s = MaState {
            capacity: c0,
            fatigue_u_min: 0.0,
        };
        for _ in 0..n {
            for &(f, t) in steps {
                p.hold(&mut s, f, t * 60.0);
            }
        }
        (s.fatigue_u_min, s.capacity)
    }

    fn params() -> Vec<MaParams> {
        vec![
            MaParams::default(),
            MaParams::new(1.4, 0.3).unwrap(),
            MaParams::new(0.8, 0.02).unwrap(),
            MaParams::with_recovery(
                1.4,
                Recovery::Perfusion {
                    rest_per_min: 0.37,
                    limit_fmvc: 0.085,
                },
            )
            .unwrap(),
        ]
    }

    #[test]
    fn matches_step_by_step_holds() {
        let cycles: [&[(f64, f64)]; 4] = [
            &[(0.3, 0.05), (0.1, 0.03), (0.0, 0.1)],
            &[(0.05, 0.2), (0.0, 0.02)],
            &[(0.6, 0.02), (0.25, 0.05), (0.0, 0.05), (0.15, 0.1)],
            &[(0.0, 0.1)],
        ];
        for p in params() {
            for steps in cycles {
                for &n in &[1u64, 7, 60, 180, 1440] {
                    for &c0 in &[1.0, 0.55] {
                        let hs: Vec<HeldStep<f64>> = steps
                            .iter()
                            .map(|&(f, t_min)| HeldStep { f, t_min })
                            .collect();
                        let r = repeated_cycles(&p, &hs, c0, n);
                        let (u, c) = simulate(&p, steps, c0, n);
                        let total = r.u_min.u * r.u_min.ln_scale.exp();
                        assert!(
                            (total - u).abs() <= 2e-6 * u.max(1e-12),
                            "{p:?} {steps:?} n={n} c0={c0}: {total} vs {u}"
                        );
                        assert!(
                            (r.capacity_end - c).abs() < 1e-9,
                            "capacity {} vs {c}",
                            r.capacity_end
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for p in params() {
            for &f in &[0.0, 0.07, 0.19, 0.35] {
                let run = |x: Dual2| {
                    let hs = [
                        HeldStep {
                            f: Dual2 {
                                v: 0.2,
                                d: 0.0,
                                dd: 0.0,
                            },
                            t_min: 0.05,
                        },
                        HeldStep { f: x, t_min: 0.04 },
                        HeldStep {
                            f: Dual2 {
                                v: 0.0,
                                d: 0.0,
                                dd: 0.0,
                            },
                            t_min: 0.1,
                        },
                    ];
                    repeated_cycles(&p, &hs, 0.9, 300).u_min.u
                };
                let d = run(Dual2::variable(f));
                let h = 1e-5;
                let v = |x: f64| {
                    run(Dual2 {
                        v: x,
                        d: 0.0,
                        dd: 0.0,
                    })
                    .v
                };
                let (vp, vm) = (v(f + h), v(f - h));
                // central differences, or second-order one-sided ones at f = 0
                let fd1 = if f > h {
                    (vp - vm) / (2.0 * h)
                } else {
                    (-3.0 * d.v + 4.0 * vp - v(f + 2.0 * h)) / (2.0 * h)
                };
                assert!(
                    (d.d - fd1).abs() <= 1e-5 * fd1.abs().max(1e-6),
                    "{p:?} f={f}: {} vs {fd1}",
                    d.d
                );
                if f > h {
                    let fd2 = (vp - 2.0 * d.v + vm) / (h * h);
                    assert!(
                        (d.dd - fd2).abs() <= 1e-3 * fd2.abs().max(1.0),
                        "{p:?} f={f}: {} vs {fd2}",
                        d.dd
                    );
                }
            }
        }
    }

    #[test]
    fn paper_model_long_shift_scales_instead_of_overflowing() {
        let p = MaParams::default();
        let hs = [
            HeldStep { f: 0.5, t_min: 0.5 },
            HeldStep { f: 0.0, t_min: 0.1 },
        ];
        let r = repeated_cycles(&p, &hs, 1.0, 8 * 100);
        // ln U = ln(u(1)) + 2NL − ln(e^{2L} − 1) with u(1) = (e^{2kft} − 1)/2k, L = kft
        let l = 0.25f64;
        let expected = ((2.0 * l).exp_m1() / 2.0).ln() + 2.0 * 800.0 * l - (2.0 * l).exp_m1().ln();
        let got = r.u_min.u.ln() + r.u_min.ln_scale;
        assert!(
            (got - expected).abs() < 1e-9 * expected,
            "{got} vs {expected}"
        );
    }
}
