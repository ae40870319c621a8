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
//! * when the transient dies fast (`L ≥ 0.2` per cycle), cycles are summed exactly until
//!   `|c_n − c*| ≤ 10⁻³ c*`, and the rest in closed form from the second-order expansion of `u`
//!   about `c*` (geometric sums of `δ` and `δ²`; the neglected third-order term is below 10⁻⁹
//!   of the total);
//! * when it dies slowly, four cycles are summed exactly and the rest by the Euler–Maclaurin
//!   formula: `Σ φ(j) = ∫φ + (φ(0) + φ(m−1))/2 + (φ'(m−1) − φ'(0))/12`, with
//!   `φ(x) = u(c* + δ e^{−Lx})`; the integral becomes `(1/L) ∫ (u(c*+y) − u(c*))/y dy` over the
//!   transient's range, done by 12-point Gauss–Legendre. The first neglected term is
//!   `L³/720` of the transient's scale (below 1.2·10⁻⁵ for `L < 0.2`).
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
#[derive(Clone, Copy)]
struct Prepared<T> {
    f: T,
    /// No recovery during the step: `c1 = c0 s`, `ΔU = e2 / c0²`.
    no_recovery: bool,
    lambda: T,
    a: T,
    s: T,
    /// `e^{λt} − 1` (recovery, λt ≤ 30) or `(e^{2kft} − 1)/2k` (no recovery).
    xm1_or_e2: T,
    lt: T,
    big: bool,
}

const LT_SWITCH: f64 = 30.0;

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
        let k = p.k_per_min;
        let f = st.f;
        let t = st.t_min;
        let r = recovery_rate(p, f);
        let lambda = f * k + r;
        if r.val() == 0.0 {
            let x = f * (k * t);
            return Prepared {
                f,
                no_recovery: true,
                lambda,
                a: T::cst(0.0),
                s: (-x).exp(),
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
            xm1_or_e2: if big { T::cst(0.0) } else { lt.exp_m1() },
            lt,
            big,
        }
    }

    /// Capacity after the step and the U gained, from capacity `c0`.
    #[inline]
    fn apply(&self, c0: T) -> (T, T) {
        if self.no_recovery {
            return (c0 * self.s, self.xm1_or_e2 / (c0 * c0));
        }
        let a = self.a;
        let b = c0 - a;
        let c1 = a + b * self.s;
        let f = self.f;
        if !self.big {
            let y = self.xm1_or_e2 / c0;
            let w = a * y;
            let du = f / self.lambda * y * (T::cst(1.0) / (c0 * (w + 1.0)) + g_of_w(w) * y);
            (c1, du)
        } else {
            let ln_1p_w = self.lt + (a / c0).ln() + (b * self.s / a).ln_1p();
            let du = f / (self.lambda * a * a) * ln_1p_w
                - f * b * (-self.s + 1.0) / (self.lambda * a * c0 * c1);
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
        b_map = b_map * s.s + s.a * (-s.s + 1.0);
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
    let c_star = b_map / (-a_map + 1.0);
    let mut c = c0t;
    let mut u = zero;
    let mut n = 0u64;
    let fast = big_l >= 0.2;
    while n < n_cycles {
        let delta = c.val() - c_star.val();
        let settled = delta.abs() <= 1e-3 * c_star.val();
        if settled || (!fast && n >= 4) {
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
    let u = if u.val().is_finite() { u } else { T::cst(1e300) };
    CyclesOutcome {
        u_min: ScaledU { u, ln_scale: 0.0 },
        capacity_end: c,
    }
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
        b_map = b_map * s.s + s.a * (-s.s + 1.0);
        ln_a = ln_a - s.lt;
    }
    let first = T::cst(c0);
    let last = if n_cycles <= 1 || -ln_a.val() <= 0.0 {
        first
    } else if cycle.steps.iter().all(|s| s.no_recovery) {
        (ln_a * (n_cycles - 1) as f64).exp() * c0
    } else {
        let c_star = b_map / (-a_map + 1.0);
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
fn no_recovery_total<T: Real>(
    cycle: &Cycle<T>,
    c0: T,
    ln_a: T,
    n_cycles: u64,
) -> CyclesOutcome<T> {
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
    // ∫_0^{m−1} (φ − u*) dx = (1/L) ∫_{y1}^{y0} (u(c*+y) − u*)/y dy
    let mid = (y0 + y1) * 0.5;
    let half = (y0 - y1) * 0.5;
    let mut integral = T::cst(0.0);
    for &(x, w) in &GL12 {
        for sgn in [-1.0, 1.0] {
            let y = mid + half * (x * sgn);
            integral = integral + (cycle.u(c_star + y) - u_star) / y * w;
        }
    }
    let integral = integral * half / big_l + u_star * (mf - 1.0);
    let phi0 = cycle.u(c_star + y0);
    let phi1 = cycle.u(c_star + y1);
    // φ'(x) = −L y u'(c* + y)
    let du_dc = |c: T| {
        let h = 1e-6 * c.val().max(1e-3);
        (cycle.u(c + h) - cycle.u(c - h)) / (2.0 * h)
    };
    let dphi0 = -big_l * y0 * du_dc(c_star + y0);
    let dphi1 = -big_l * y1 * du_dc(c_star + y1);
    integral + (phi0 + phi1) * 0.5 + (dphi1 - dphi0) / 12.0
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
                        assert!((r.capacity_end - c).abs() < 1e-9, "capacity {} vs {c}", r.capacity_end);
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
                        HeldStep { f: Dual2 { v: 0.2, d: 0.0, dd: 0.0 }, t_min: 0.05 },
                        HeldStep { f: x, t_min: 0.04 },
                        HeldStep { f: Dual2 { v: 0.0, d: 0.0, dd: 0.0 }, t_min: 0.1 },
                    ];
                    repeated_cycles(&p, &hs, 0.9, 300).u_min.u
                };
                let d = run(Dual2::variable(f));
                let h = 1e-5;
                let v = |x: f64| run(Dual2 { v: x, d: 0.0, dd: 0.0 }).v;
                let (vp, vm) = (v(f + h), v(f - h));
                // central differences, or second-order one-sided ones at f = 0
                let fd1 = if f > h {
                    (vp - vm) / (2.0 * h)
                } else {
                    (-3.0 * d.v + 4.0 * vp - v(f + 2.0 * h)) / (2.0 * h)
                };
                assert!((d.d - fd1).abs() <= 1e-5 * fd1.abs().max(1e-6), "{p:?} f={f}: {} vs {fd1}", d.d);
                if f > h {
                    let fd2 = (vp - 2.0 * d.v + vm) / (h * h);
                    assert!((d.dd - fd2).abs() <= 1e-3 * fd2.abs().max(1.0), "{p:?} f={f}: {} vs {fd2}", d.dd);
                }
            }
        }
    }

    #[test]
    fn paper_model_long_shift_scales_instead_of_overflowing() {
        let p = MaParams::default();
        let hs = [HeldStep { f: 0.5, t_min: 0.5 }, HeldStep { f: 0.0, t_min: 0.1 }];
        let r = repeated_cycles(&p, &hs, 1.0, 8 * 100);
        // ln U = ln(u(1)) + 2NL − ln(e^{2L} − 1) with u(1) = (e^{2kft} − 1)/2k, L = kft
        let l = 0.25f64;
        let expected = ((2.0 * l).exp_m1() / 2.0).ln() + 2.0 * 800.0 * l - (2.0 * l).exp_m1().ln();
        let got = r.u_min.u.ln() + r.u_min.ln_scale;
        assert!((got - expected).abs() < 1e-9 * expected, "{got} vs {expected}");
    }
}
