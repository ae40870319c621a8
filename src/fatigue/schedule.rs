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
use super::ma::{MaParams, MaState};

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
    /// The fast deficit at the end (0 except under the routed recovery).
    pub fast_deficit_end: T,
}

/// A step of the single-rate model (capacity alone) with its per-step constants precomputed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Single<T> {
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

impl<T: Real> Single<T> {
    /// Holding `f` for `t` minutes with fatigue rate `k` and recovery rate `r` (per minute).
    pub(crate) fn from_rates(k: f64, f: T, r: T, t: f64) -> Self {
        let lambda = f * k + r;
        if r.val() == 0.0 {
            let x = f * (k * t);
            return Single {
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
        Single {
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

/// `x²(3 − 2x)` of a generic number.
#[inline]
fn smoothstep<T: Real>(x: T) -> T {
    x * x * (-(x * 2.0) + 3.0)
}

/// The perfusion share `x²(3 − 2x)`, `x = 1 − f/f_lim`, 0 from `f_lim` up, of a generic number.
#[inline]
fn perfusion_share<T: Real>(f: T, limit_fmvc: f64) -> T {
    let x = -(f / limit_fmvc) + 1.0;
    if x.val() > 0.0 {
        smoothstep(x)
    } else {
        T::cst(0.0)
    }
}

/// `R(f)` for a generic number (the form of [`crate::fatigue::Recovery`], differentiable; the
/// slow deficit's rate for the routed form).
fn recovery_rate<T: Real>(p: &MaParams, f: T) -> T {
    use super::ma::Recovery;
    match p.recovery {
        Recovery::None => T::cst(0.0),
        Recovery::Constant { r_per_min } => T::cst(r_per_min),
        Recovery::Perfusion {
            rest_per_min,
            limit_fmvc,
        }
        | Recovery::Routed {
            slow_rest_per_min: rest_per_min,
            limit_fmvc,
            ..
        } => perfusion_share(f, limit_fmvc) * rest_per_min,
    }
}

/// The fast deficit's rate `R_fast(f)` and the fast share `φ(f)` of new fatigue, for a generic
/// number (both 0 except for the routed form).
fn fast_rate_and_share<T: Real>(p: &MaParams, f: T) -> (T, T) {
    use super::ma::{ROUTE_FROM_FMVC, ROUTE_FULL_FMVC, Recovery};
    match p.recovery {
        Recovery::Routed {
            fast_rest_per_min,
            limit_fmvc,
            fast_share_max,
            ..
        } => {
            let x = (f - ROUTE_FROM_FMVC) / (ROUTE_FULL_FMVC - ROUTE_FROM_FMVC);
            let share = if x.val() <= 0.0 {
                T::cst(0.0)
            } else if x.val() >= 1.0 {
                T::cst(fast_share_max)
            } else {
                smoothstep(x) * fast_share_max
            };
            (perfusion_share(f, limit_fmvc) * fast_rest_per_min, share)
        }
        _ => (T::cst(0.0), T::cst(0.0)),
    }
}

/// A muscle group's state as the steps move it: capacity `c` and the fast deficit `d` (0 except
/// under the routed recovery).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Point<T> {
    pub c: T,
    pub d: T,
}

/// `E(τ) = (e^{−R_f τ} − e^{−λτ}) / (λ − R_f)` (formed without cancellation when λ ≈ R_f): the
/// capacity a unit of fast deficit has given back, beyond what the slow rate gives, after τ.
#[inline]
fn fast_refill<T: Real>(lambda: T, r_f: T, tau: f64) -> T {
    let x = (lambda - r_f) * tau;
    let decay = (-lambda * tau).exp();
    if x.val().abs() < 1e-4 {
        // e^{−λτ} τ (e^x − 1)/x
        decay * tau * (x * (x * (1.0 / 24.0) + 1.0 / 6.0) * x + x * 0.5 + 1.0)
    } else {
        ((-r_f * tau).exp() - decay) / (lambda - r_f)
    }
}

/// The fast deficit's recovery during a light step (the routed form below `f_lim`). With the
/// fast deficit `d0` at the step's start, `d(τ) = d0 e^{−R_f τ}` and the capacity is the
/// single-rate model's plus `(R_f − R_s) d0 E(τ)`; U = ∫ f/c² has no closed form along two
/// exponentials and is summed by Gauss–Legendre (8 points on panels at most 2 wide in `R_f τ`
/// and `λτ`, graded near the start where the capacity rises steeply from far below) over
/// `[0, t_q]`, where `R_f t_q ≤ 40`; beyond `t_q` the fast deficit is below `e^{−40}` of itself
/// and the single-rate closed form takes over.
#[derive(Debug, Clone, Copy)]
struct Fast<T> {
    r_f: T,
    /// `R_f − R_s ≥ 0`.
    g: T,
    /// `e^{−R_f t}`.
    q: T,
    /// `E(t)`.
    e_t: T,
    t_q: f64,
    panels: u32,
    /// The single-rate step over `t − t_q` (`None` when `t_q = t`).
    after: Option<Single<T>>,
}

/// Gauss–Legendre nodes and weights on [−1, 1], 8 points.
const GL8: [(f64, f64); 4] = [
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_3),
];

/// A held step with its per-step constants precomputed: the single-rate step of the capacity,
/// and under the routed recovery the fast share of its new fatigue and the fast deficit's
/// recovery.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Prepared<T> {
    one: Single<T>,
    /// `φ(f)`: the share of the capacity lost in this step that goes to the fast deficit.
    phi: T,
    fast: Option<Fast<T>>,
}

impl<T: Real> Prepared<T> {
    pub(crate) fn new(p: &MaParams, st: &HeldStep<T>) -> Self {
        let (k, f, t) = (p.k_per_min, st.f, st.t_min);
        let r = recovery_rate(p, f);
        let one = Single::from_rates(k, f, r, t);
        let (r_f, phi) = fast_rate_and_share(p, f);
        let fast = (r_f.val() > 0.0 && t > 0.0).then(|| {
            let t_q = t.min(40.0 / r_f.val());
            let span = r_f.val().max(one.lambda.val()) * t_q;
            Fast {
                r_f,
                g: r_f - r,
                q: (-r_f * t).exp(),
                e_t: fast_refill(one.lambda, r_f, t),
                t_q,
                panels: ((span / 2.0).ceil() as u32).clamp(1, 256),
                after: (t_q < t).then(|| Single::from_rates(k, f, r, t - t_q)),
            }
        });
        Prepared { one, phi, fast }
    }

    /// The step's single-rate part.
    pub(crate) fn single(&self) -> &Single<T> {
        &self.one
    }

    /// The state after the step from `x`.
    #[inline]
    pub(crate) fn capacity(&self, x: Point<T>) -> Point<T> {
        match &self.fast {
            Some(fs) if x.d.val() != 0.0 => Point {
                c: self.one.capacity(x.c) + fs.g * x.d * fs.e_t,
                d: fs.q * x.d,
            },
            _ => {
                let c1 = self.one.capacity(x.c);
                Point {
                    c: c1,
                    d: self.routed_d(x, c1),
                }
            }
        }
    }

    /// The fast deficit after a step without fast recovery: it gains `φ` of the capacity lost.
    #[inline]
    fn routed_d(&self, x: Point<T>, c1: T) -> T {
        if self.phi.val() == 0.0 {
            x.d
        } else {
            x.d + self.phi * (x.c - c1)
        }
    }

    /// The state after the step from `x` and the U gained.
    #[inline]
    pub(crate) fn apply(&self, x: Point<T>) -> (Point<T>, T) {
        match &self.fast {
            Some(fs) if x.d.val() != 0.0 => {
                let one = &self.one;
                let (c0, d0) = (x.c, x.d);
                let c_at = |tau: f64| {
                    one.a
                        + (c0 - one.a) * (-one.lambda * tau).exp()
                        + fs.g * d0 * fast_refill(one.lambda, fs.r_f, tau)
                };
                let du = if one.f.val() == 0.0 {
                    T::cst(0.0)
                } else {
                    // Panels: a capacity that starts far below where it is heading rises
                    // steeply, over `τ_c = c0 / |dc/dτ(0)|`, so the first panels grade from
                    // τ_c, doubling (1/c² has its pole at least one panel width away from each
                    // of them), up to the uniform width
                    let uniform = fs.t_q / fs.panels as f64;
                    let slope = (one.lambda * (one.a - c0) + fs.g * d0).val().abs();
                    let tau_c = if slope > 0.0 {
                        c0.val() / slope
                    } else {
                        f64::INFINITY
                    };
                    let mut acc = T::cst(0.0);
                    let mut start = 0.0;
                    while start < fs.t_q {
                        let width = if tau_c < uniform {
                            start.max(tau_c).min(uniform)
                        } else {
                            uniform
                        }
                        .min(fs.t_q - start);
                        let mid = start + 0.5 * width;
                        for &(node, w) in &GL8 {
                            for sgn in [-1.0, 1.0] {
                                let c = c_at(mid + 0.5 * width * node * sgn);
                                acc = acc + T::cst(0.5 * width * w) / (c * c);
                            }
                        }
                        start += width;
                        if fs.t_q - start <= 1e-12 * fs.t_q {
                            break;
                        }
                    }
                    let mut du = one.f * acc;
                    if let Some(after) = &fs.after {
                        du = du + after.apply(c_at(fs.t_q)).1;
                    }
                    du
                };
                (
                    Point {
                        c: one.capacity(c0) + fs.g * d0 * fs.e_t,
                        d: fs.q * d0,
                    },
                    du,
                )
            }
            _ => {
                let (c1, du) = self.one.apply(x.c);
                (
                    Point {
                        c: c1,
                        d: self.routed_d(x, c1),
                    },
                    du,
                )
            }
        }
    }

    /// The step as an affine map of the state, `x ↦ M x + v`: `(M, v)` with `M` row-major
    /// `[[c←c, c←d], [d←c, d←d]]`.
    fn affine(&self) -> ([T; 4], [T; 2]) {
        let one = &self.one;
        let zero = T::cst(0.0);
        let (m_cd, m_dd) = match &self.fast {
            Some(fs) => (fs.g * fs.e_t, fs.q),
            None => (zero, T::cst(1.0)),
        };
        // heavy steps: d gains φ (c0 − c1) = φ (1 − s) c0 (no recovery: v = 0)
        let m_dc = if self.phi.val() == 0.0 {
            zero
        } else {
            self.phi * one.one_minus_s
        };
        ([one.s, m_cd, m_dc, m_dd], [one.a * one.one_minus_s, zero])
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
            let (c1, du) = s.one.apply(c);
            u = u + du;
            c = c1;
        }
        (u, c)
    }
    #[inline]
    fn u(&self, c: T) -> T {
        self.run(c).0
    }
    /// U gained over one cycle from state `x` (capacity and fast deficit), and the state after.
    #[inline]
    fn run2(&self, x: Point<T>) -> (T, Point<T>) {
        let mut x = x;
        let mut u = T::cst(0.0);
        for s in &self.steps {
            let (x1, du) = s.apply(x);
            u = u + du;
            x = x1;
        }
        (u, x)
    }
    /// Whether any step sends new fatigue to the fast deficit.
    fn feeds_fast(&self) -> bool {
        self.steps.iter().any(|s| s.phi.val() != 0.0)
    }
    fn recovers(&self) -> bool {
        self.steps.iter().any(|s| !s.one.no_recovery)
    }
    /// The cycle as an affine map of the state (see [`Prepared::affine`]).
    fn affine(&self) -> ([T; 4], [T; 2]) {
        let zero = T::cst(0.0);
        let (mut m, mut v) = ([T::cst(1.0), zero, zero, T::cst(1.0)], [zero, zero]);
        for s in &self.steps {
            let (ms, vs) = s.affine();
            m = mat_mul(ms, m);
            let mv = mat_vec(ms, v);
            v = [mv[0] + vs[0], mv[1] + vs[1]];
        }
        (m, v)
    }
}

fn mat_mul<T: Real>(a: [T; 4], b: [T; 4]) -> [T; 4] {
    [
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
    ]
}

fn mat_vec<T: Real>(a: [T; 4], x: [T; 2]) -> [T; 2] {
    [a[0] * x[0] + a[1] * x[1], a[2] * x[0] + a[3] * x[1]]
}

/// `Mⁿ` by repeated squaring.
fn mat_pow<T: Real>(m: [T; 4], mut n: u64) -> [T; 4] {
    let (zero, one) = (T::cst(0.0), T::cst(1.0));
    let mut out = [one, zero, zero, one];
    let mut base = m;
    while n > 0 {
        if n & 1 == 1 {
            out = mat_mul(out, base);
        }
        base = mat_mul(base, base);
        n >>= 1;
    }
    out
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
/// let total = repeated_cycles(&p, &steps, &MaState::FRESH, 500);
/// // the same by holding every step of every cycle
/// let mut s = MaState::FRESH;
/// for _ in 0..500 { for st in &steps { p.hold(&mut s, st.f, st.t_min * 60.0); } }
/// assert!((total.u_min.u - s.fatigue_u_min).abs() < 1e-7 * s.fatigue_u_min);
/// assert!((total.capacity_end - s.capacity).abs() < 1e-12);
/// ```
pub fn repeated_cycles<T: Real>(
    p: &MaParams,
    steps: &[HeldStep<T>],
    start: &MaState,
    n_cycles: u64,
) -> CyclesOutcome<T> {
    let cycle = Cycle {
        steps: steps.iter().map(|s| Prepared::new(p, s)).collect(),
    };
    let (c0, d0) = (start.capacity, start.fast_deficit);
    if n_cycles == 0 || cycle.steps.is_empty() {
        return CyclesOutcome {
            u_min: ScaledU {
                u: T::cst(0.0),
                ln_scale: 0.0,
            },
            capacity_end: T::cst(c0),
            fast_deficit_end: T::cst(d0),
        };
    }
    if d0 != 0.0 || cycle.feeds_fast() {
        return routed_cycles(&cycle, c0, d0, n_cycles);
    }
    single_cycles(&cycle, c0, n_cycles)
}

/// [`repeated_cycles`] of the single-rate model: the state is the capacity alone.
fn single_cycles<T: Real>(cycle: &Cycle<T>, c0: f64, n_cycles: u64) -> CyclesOutcome<T> {
    let zero = T::cst(0.0);
    let c0t = T::cst(c0);
    // Cycle map c ↦ A c + B; ln A = −Σ λ_i t_i.
    let mut a_map = T::cst(1.0);
    let mut b_map = zero;
    let mut ln_a = zero;
    for s in cycle.steps.iter().map(Prepared::single) {
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
            fast_deficit_end: zero,
        };
    }
    if !cycle.recovers() {
        return no_recovery_total(cycle, c0t, ln_a, n_cycles);
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
                taylor_tail(|c| cycle.u(c), c_star, c - c_star, a_map, ln_a, m)
            } else {
                euler_maclaurin_tail(|c| cycle.u(c), c_star, c - c_star, ln_a, m)
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
        return overflowed(cycle, c0, n_cycles, zero);
    }
    CyclesOutcome {
        u_min: ScaledU { u, ln_scale: 0.0 },
        capacity_end: c,
        fast_deficit_end: zero,
    }
}

/// [`repeated_cycles`] with a fast deficit (the routed recovery): the state `(c, d)` moves by a
/// 2 × 2 affine map per cycle, `x ↦ M x + v`, whose eigenvalues are real (M is a product of
/// non-negative matrices). Cycles are summed exactly until the faster mode has died out (the
/// state within 10⁻¹³ of the line through the periodic steady state `x*` along the slower
/// mode's eigenvector); from there the state moves along that line, `c − c* = δ ρⁿ`, and the
/// rest is summed by the single-rate model's tails with `u` evaluated along the line. Without
/// recovery in any step the capacity is the single-rate model's and the fast deficit gains
/// `φ` of each loss. A cycle whose slower mode leaves the capacity unchanged, or whose modes
/// have not separated after [`EXACT_CYCLES`] cycles, is summed exactly to the end (O(n)).
fn routed_cycles<T: Real>(cycle: &Cycle<T>, c0: f64, d0: f64, n_cycles: u64) -> CyclesOutcome<T> {
    let zero = T::cst(0.0);
    let (m, v) = cycle.affine();
    if !cycle.recovers() {
        // c_n = c0 Aⁿ as without routing; d gains κ c per cycle (κ = M's d←c entry)
        let single = single_cycles(cycle, c0, n_cycles);
        let ln_a = cycle.steps.iter().fold(zero, |acc, s| acc - s.one.lt);
        let geometric = if ln_a.val() < 0.0 {
            (ln_a * n_cycles as f64).exp_m1() / ln_a.exp_m1()
        } else {
            T::cst(n_cycles as f64)
        };
        return CyclesOutcome {
            fast_deficit_end: m[2] * c0 * geometric + d0,
            ..single
        };
    }
    // the periodic steady state x* = (I − M)⁻¹ v
    let (a11, a12, a21, a22) = (-m[0] + 1.0, -m[1], -m[2], -m[3] + 1.0);
    let det = a11 * a22 - a12 * a21;
    let star = Point {
        c: (a22 * v[0] - a12 * v[1]) / det,
        d: (a11 * v[1] - a21 * v[0]) / det,
    };
    // the slower mode: the larger eigenvalue ρ and its eigenvector, scaled to a unit of capacity
    let trace = m[0] + m[3];
    let disc = trace * trace - (m[0] * m[3] - m[1] * m[2]) * 4.0;
    let rho = (trace + if disc.val() > 0.0 { disc.sqrt() } else { zero }) * 0.5;
    let (e1, e2) = ([m[1], rho - m[0]], [rho - m[3], m[2]]);
    let norm = |e: &[T; 2]| e[0].val().hypot(e[1].val());
    let e = if norm(&e1) >= norm(&e2) { e1 } else { e2 };
    let line = (e[0].val().abs() > 1e-9 * norm(&e) && rho.val() > 0.0).then(|| e[1] / e[0]);
    let ln_rho = rho.ln();
    let slow = -ln_rho.val() < 0.2;
    let mut x = Point {
        c: T::cst(c0),
        d: T::cst(d0),
    };
    let mut u = zero;
    let mut n = 0u64;
    while n < n_cycles {
        if let Some(w) = line {
            let dc = x.c - star.c;
            let off = (x.d - star.d).val() - w.val() * dc.val();
            let settled = dc.val().abs() <= 1e-3 * star.c.val();
            if off.abs() <= 1e-13 && (settled || (slow && n >= EXACT_CYCLES)) {
                let left = n_cycles - n;
                let along = |c: T| {
                    cycle
                        .run2(Point {
                            c,
                            d: star.d + w * (c - star.c),
                        })
                        .0
                };
                u = u + if settled {
                    taylor_tail(along, star.c, dc, rho, ln_rho, left)
                } else {
                    euler_maclaurin_tail(along, star.c, dc, ln_rho, left)
                };
                let decay = (ln_rho * left as f64).exp();
                x = Point {
                    c: star.c + dc * decay,
                    d: star.d + (x.d - star.d) * decay,
                };
                break;
            }
        }
        let (du, x1) = cycle.run2(x);
        u = u + du;
        x = x1;
        n += 1;
    }
    if !u.val().is_finite() {
        // U passed the largest double: bounded by the single-rate model's value in logarithms
        // (the fast deficit only gives capacity back sooner).
        return overflowed(cycle, c0, n_cycles, x.d);
    }
    CyclesOutcome {
        u_min: ScaledU { u, ln_scale: 0.0 },
        capacity_end: x.c,
        fast_deficit_end: x.d,
    }
}

/// The outcome of cycles whose U passed the largest double: U and the capacity from the
/// single-rate steps held in logarithms.
fn overflowed<T: Real>(cycle: &Cycle<T>, c0: f64, n_cycles: u64, d_end: T) -> CyclesOutcome<T> {
    let (ln_u, ln_c) = log_domain_cycles(cycle, c0, n_cycles);
    CyclesOutcome {
        u_min: ScaledU {
            u: T::cst(1.0),
            ln_scale: ln_u,
        },
        capacity_end: T::cst(ln_c.exp()),
        fast_deficit_end: d_end,
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
        for st in cycle.steps.iter().map(Prepared::single) {
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
/// `n_cycles` repetitions from `start` (capacity falls through a loaded step, so a step's end is
/// its lowest point; across cycles the capacity at a given step moves monotonically toward its
/// periodic steady state — with a fast deficit, once its faster mode has died out, within a few
/// cycles — so the first and the last cycle bound it). With its derivatives when `T` is
/// [`Dual2`](super::dual::Dual2).
pub fn lowest_end_capacity<T: Real>(
    p: &MaParams,
    steps: &[HeldStep<T>],
    mask: &[bool],
    start: &MaState,
    n_cycles: u64,
) -> T {
    let cycle = Cycle {
        steps: steps.iter().map(|s| Prepared::new(p, s)).collect(),
    };
    let mut a_map = T::cst(1.0);
    let mut b_map = T::cst(0.0);
    let mut ln_a = T::cst(0.0);
    for s in cycle.steps.iter().map(Prepared::single) {
        a_map = a_map * s.s;
        b_map = b_map * s.s + s.a * s.one_minus_s;
        ln_a = ln_a - s.lt;
    }
    let first = Point {
        c: T::cst(start.capacity),
        d: T::cst(start.fast_deficit),
    };
    let last = if n_cycles <= 1 || -ln_a.val() <= 0.0 {
        first
    } else if !cycle.recovers() {
        Point {
            c: (ln_a * (n_cycles - 1) as f64).exp() * start.capacity,
            ..first
        }
    } else if start.fast_deficit != 0.0 || cycle.feeds_fast() {
        // x* + M^{n−1} (x0 − x*)
        let (m, v) = cycle.affine();
        let (a11, a12, a21, a22) = (-m[0] + 1.0, -m[1], -m[2], -m[3] + 1.0);
        let det = a11 * a22 - a12 * a21;
        let star = [
            (a22 * v[0] - a12 * v[1]) / det,
            (a11 * v[1] - a21 * v[0]) / det,
        ];
        let moved = mat_vec(
            mat_pow(m, n_cycles - 1),
            [first.c - star[0], first.d - star[1]],
        );
        Point {
            c: star[0] + moved[0],
            d: star[1] + moved[1],
        }
    } else {
        let c_star = b_map / -ln_a.exp_m1();
        Point {
            c: c_star + (first.c - c_star) * (ln_a * (n_cycles - 1) as f64).exp(),
            ..first
        }
    };
    let mut lowest = T::cst(f64::INFINITY);
    for start in [first, last] {
        let mut x = start;
        for (s, m) in cycle.steps.iter().zip(mask) {
            x = s.capacity(x);
            if *m && x.c.val() < lowest.val() {
                lowest = x.c;
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
        fast_deficit_end: T::cst(0.0),
    }
}

/// `Σ_{j<m} u(c* + δ A^j)` for small `δ`: `m u(c*) + u' δ G₁ + ½ u'' δ² G₂`.
fn taylor_tail<T: Real>(u: impl Fn(T) -> T, c_star: T, delta: T, a_map: T, ln_a: T, m: u64) -> T {
    let h = (delta.val().abs()).max(1e-6 * c_star.val());
    let u0 = u(c_star);
    let up = u(c_star + h);
    let um = u(c_star - h);
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
fn euler_maclaurin_tail<T: Real>(u: impl Fn(T) -> T, c_star: T, delta: T, ln_a: T, m: u64) -> T {
    let mf = m as f64;
    let big_l = -ln_a; // > 0
    let u_star = u(c_star);
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
                integral = integral + u(c_star + y) * (step * (0.5 * w));
            }
        }
    }
    let integral = (integral + u_star * (ln_lo - ln_lo_full)) / big_l;
    let phi0 = u(c_star + y0);
    let phi1 = u(c_star + y1);
    // With g(y) = u(c* + y) and d/dx = −L y d/dy:
    //   φ' = −L y g',  φ''' = −L³ (y g' + 3 y² g'' + y³ g''').
    let du_dc = |c: T| {
        let h = 1e-6 * c.val();
        (u(c + h) - u(c - h)) / (2.0 * h)
    };
    let d3phi = |y: T| {
        let c = c_star + y;
        let h = 0.02 * c.val();
        let (um2, um1, u0, up1, up2) = (u(c - 2.0 * h), u(c - h), u(c), u(c + h), u(c + 2.0 * h));
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
            ..MaState::FRESH
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
            routed(1.4, 0.4),
        ]
    }

    fn routed(k: f64, share: f64) -> MaParams {
        MaParams::with_recovery(
            k,
            Recovery::Routed {
                slow_rest_per_min: 0.319,
                fast_rest_per_min: 20.0,
                limit_fmvc: 0.085,
                fast_share_max: share,
            },
        )
        .unwrap()
    }

    #[test]
    fn routed_cycles_match_step_by_step_holds_from_any_state() {
        // heavy steps feed the fast deficit, light ones drain it; some cycles settle within a
        // few cycles, some (short rests) only slowly
        let cycles: [&[(f64, f64)]; 4] = [
            &[(0.6, 0.05), (0.03, 0.1)],
            &[(0.4, 0.2), (0.0, 0.02), (0.1, 0.1), (0.02, 0.05)],
            &[(0.35, 0.1), (0.0, 0.01)],
            &[(0.05, 0.3), (0.0, 0.1)],
        ];
        let p = routed(1.4, 0.4);
        for steps in cycles {
            for &n in &[1u64, 7, 60, 180, 1440] {
                for start in [
                    MaState::FRESH,
                    MaState {
                        capacity: 0.55,
                        fatigue_u_min: 0.0,
                        fast_deficit: 0.2,
                    },
                ] {
                    let hs: Vec<HeldStep<f64>> = steps
                        .iter()
                        .map(|&(f, t_min)| HeldStep { f, t_min })
                        .collect();
                    let r = repeated_cycles(&p, &hs, &start, n);
                    let mut s = start;
                    for _ in 0..n {
                        for &(f, t) in steps {
                            p.hold(&mut s, f, t * 60.0);
                        }
                    }
                    let total = r.u_min.u * r.u_min.ln_scale.exp();
                    let u = s.fatigue_u_min;
                    assert!(
                        (total - u).abs() <= 2e-6 * u.max(1e-12),
                        "{steps:?} n={n} {start:?}: {total} vs {u}"
                    );
                    assert!(
                        (r.capacity_end - s.capacity).abs() < 1e-9,
                        "{steps:?} n={n}"
                    );
                    assert!(
                        (r.fast_deficit_end - s.fast_deficit).abs() < 1e-9,
                        "{steps:?} n={n}: {} vs {}",
                        r.fast_deficit_end,
                        s.fast_deficit
                    );
                    let mask = vec![true; hs.len()];
                    let lowest = lowest_end_capacity(&p, &hs, &mask, &start, n);
                    // the lowest step end over the cycles, by holding them all
                    let mut s = start;
                    let mut seen = f64::INFINITY;
                    for _ in 0..n {
                        for &(f, t) in steps {
                            p.hold(&mut s, f, t * 60.0);
                            seen = seen.min(s.capacity);
                        }
                    }
                    assert!(
                        (lowest - seen).abs() < 1e-9,
                        "{steps:?} n={n}: {lowest} vs {seen}"
                    );
                }
            }
        }
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
                        let r = repeated_cycles(
                            &p,
                            &hs,
                            &MaState {
                                capacity: c0,
                                ..MaState::FRESH
                            },
                            n,
                        );
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
                    repeated_cycles(
                        &p,
                        &hs,
                        &MaState {
                            capacity: 0.9,
                            ..MaState::FRESH
                        },
                        300,
                    )
                    .u_min
                    .u
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
        let r = repeated_cycles(&p, &hs, &MaState::FRESH, 8 * 100);
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
