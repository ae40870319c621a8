//! What the optimiser minimises, and why it has this form.
//!
//! **Fatigue.** The plan's cost is the total fatigue index at the end of the remaining task,
//! `S = Σ_h U_h(end)`, predicted exactly: each half-joint h holds, cycle after cycle, the load of
//! every phase and of the rest in turn, and [`repeated_cycles`] gives its U after the remaining
//! cycles in O(1) from the closed forms (module [`crate::fatigue::schedule`]). While one phase's
//! posture is optimised, the other phases' loads stay fixed, so each half-joint's total is a
//! function of one number, its load in this phase; forward-mode second derivatives ([`Dual2`])
//! give its slope and curvature.
//!
//! **Scaling.** S spans many orders of magnitude (e^{2kΔF} for a long shift without recovery), so
//! the optimiser minimises `J = ln(S + ε)`: strictly increasing in S, so the same minimiser, with
//! gradients `U_h'/S` of order one however large U gets. The QP's Hessian keeps the diagonal
//! `U_h''/S` (the dropped `−(U'/S)(U'/S)ᵀ` is negative semidefinite), which keeps it convex and
//! separable. ε = 0.001 min keeps J finite when nothing is loaded.
//!
//! **Discomfort** (on by default, off with `--fatigue-only`): after the joint-range discomfort of
//! the Santos posture-prediction work (Marler, Yang, Arora & Abdel-Malek 2005, "Study of a new
//! discomfort function for posture prediction", SAE 2005-01-2680), per actuated joint
//! `γ_i ((q − q_N)/(q_U − q_L))²` (displacement from the neutral posture, normalised by the
//! range, with joint weights γ that make the trunk's sideways bending and twisting the costliest,
//! [`displacement_weight`]) plus an end-of-range penalty that is zero in the middle 80 % of the
//! range and rises as `3·((0.1 − u)/0.1)³` toward each limit (`u` the position in the range, 0..1),
//! replacing Marler's steeper `[0.5 sin(…) + 0.5]¹⁰⁰` bumps by a C² polynomial the SQP can
//! follow. A limit the neutral posture sits at (a straight knee or elbow) is not penalised: it
//! is where the joint rests. The task's discomfort is the mean over the cycle's phases, times the task's
//! `discomfort_weight` (default 0.1): in a one-phase task, one joint driven from mid-range to its
//! limit costs as much as about 40 % more fatigue (J is the logarithm of the total;
//! `0.1·(0.5² + 3)` = 0.33 in J). The end weight 3 ([`END_WEIGHT`]) was measured on the nine
//! shipped tasks: at 1 the plans parked the wrist or the shoulder at a limit where that saved a
//! few per cent of fatigue (shelf's 'place high board', shelf_heavy's 'carry'); at 3 no phase
//! sits at a limit; at 10 six of the nine held plans tired more and one (shelf_lowered) moved by
//! 2.5 % with the QP's precision.
//!
//! **Assessment zones** (off by default; the task's `objective.zone_weight`). The standards'
//! acceptable zones of the trunk, upper arms and head are constraints ([`super::zones`]); this
//! soft term prices RULA's and REBA's zones beyond them (the wrist among them). Twisting, bending
//! sideways, leaning back and bending the wrist cost the worker almost no gravity moment, so
//! neither fatigue nor the gentle displacement term keeps a plan from them, and RULA and REBA
//! score them high. Each of those directions gets a zone around neutral (10° of trunk twist, 15°
//! of wrist flexion, …: [`assessment_zone_deg`]) and, beyond it, `zone_weight · (excess/range)²`
//! (the square's onset smoothed over the first 2 % of the range, [`ZONE_ONSET`], so that the term
//! is C²). At `zone_weight` 30, in a one-phase task a held trunk twist of 15° costs as much as
//! about 3.5 % more fatigue, 20° about 8 %, 30° about 28 % (twist range ±45°: about
//! `0.1·(10·(θ/90°)² + 30·((θ−10.9°)/90°)²)` added to J). It is off by default because, measured
//! on the nine shipped tasks, it trades fatigue and the share of women strong enough for the
//! postures' scores, and the global search does not yet find that trade reliably (README, The
//! planner).

use super::task::Task;
use crate::fatigue::MaState;
use crate::fatigue::dual::{Dual2, Real};
use crate::fatigue::schedule::{HeldStep, lowest_end_capacity, repeated_cycles};

/// ε of `J = ln(S + ε)` \[min\].
pub const EPSILON_U_MIN: f64 = 1e-3;

/// The plan keeps every load this far below the lowest capacity its group reaches (fraction of
/// MVC), so that a plan at the edge does not tip into exhaustion.
pub const EXHAUSTION_MARGIN: f64 = 0.02;

/// A joint this close to a limit (fraction of its range) is reported as at the limit.
pub const AT_LIMIT_FRACTION: f64 = 0.01;

/// Fraction of a joint's range, at each end, where the end-of-range penalty acts.
pub const END_ZONE: f64 = 0.1;

/// A cost of one phase's posture in terms of the half-joints' loads in that phase.
pub trait LoadCost: Send + Sync {
    /// Value; fills `grad[h] = ∂J/∂f_h` and `curv[h] ≥ 0`, a diagonal curvature bound.
    fn eval(&mut self, f: &[f64], grad: &mut [f64], curv: &mut [f64]) -> f64;
    /// The exact second derivatives at `f`, with the gradient into `grad`:
    /// `∂²J/∂f_h∂f_k = diag[h]·δ_hk − c·grad[h]·grad[k]`; returns `c`. By default
    /// [`Self::eval`]'s diagonal is exact (`c = 0`).
    fn exact_curvature(&mut self, f: &[f64], grad: &mut [f64], diag: &mut [f64]) -> f64 {
        self.eval(f, grad, diag);
        0.0
    }
    /// Value only.
    fn value(&mut self, f: &[f64]) -> f64;
    /// The load half-joint `h` may hold in this phase without being exhausted (its lowest
    /// capacity over the task) and the bound's slope in its load here; `None`: no bound.
    fn capacity_bound(&mut self, _h: usize, _f: f64) -> Option<(f64, f64)> {
        None
    }
    /// A copy for a solve on another thread (its caches, if any, give the same numbers).
    fn fork(&self) -> Box<dyn LoadCost + '_>;
}

/// The fatigue cost of one phase (a group of phases sharing a posture) over the remaining task.
#[derive(Debug, Clone)]
pub struct FatigueCost<'t> {
    task: &'t Task,
    /// Per half-joint, its load in each step of the cycle (phases in order, then the rest).
    step_loads: Vec<Vec<f64>>,
    /// Step durations \[min\] and whether a step belongs to the optimised group.
    step_t_min: Vec<f64>,
    in_group: Vec<bool>,
    state: Vec<MaState>,
    cycles: u64,
    scratch: Vec<HeldStep<Dual2>>,
    scratch_value: Vec<HeldStep<f64>>,
    /// Per half-joint, the last load it was evaluated at (its bits) with its total and the
    /// capacity bound there: a group's load often stays exactly where it was between calls (0
    /// for the unloaded direction of every joint), and the totals are deterministic.
    total_cache: Vec<Option<(u64, Dual2, f64)>>,
    /// The same for the value alone (the line search needs no derivatives; plain numbers cost
    /// about a third of [`Dual2`]s).
    value_cache: Vec<Option<(u64, f64, f64)>>,
    bound_cache: Vec<Option<(u64, (f64, f64))>>,
    /// Scratch of the log-sum: each half-joint's (scaled total, ln scale) and weight.
    terms: Vec<(f64, f64)>,
    weights: Vec<f64>,
}

impl<'t> FatigueCost<'t> {
    /// The cost of the phases `group` (sharing one posture) given every phase's current loads
    /// `phase_loads[p][h]`, the rest's loads `rest_loads[h]`, the state now and the cycles left.
    pub fn new(
        task: &'t Task,
        group: &[usize],
        phase_loads: &[Vec<f64>],
        rest_loads: &[f64],
        state: &[MaState],
        cycles: u64,
    ) -> Self {
        let nh = task.half_joints.len();
        let mut step_t_min: Vec<f64> = task.phases.iter().map(|p| p.duration_s / 60.0).collect();
        let mut in_group: Vec<bool> = (0..task.phases.len()).map(|p| group.contains(&p)).collect();
        let rest = task.rest_s > 0.0;
        if rest {
            step_t_min.push(task.rest_s / 60.0);
            in_group.push(false);
        }
        let step_loads = (0..nh)
            .map(|h| {
                let mut v: Vec<f64> = phase_loads.iter().map(|f| f[h]).collect();
                if rest {
                    v.push(rest_loads[h]);
                }
                v
            })
            .collect();
        FatigueCost {
            task,
            step_loads,
            step_t_min,
            in_group,
            state: state.to_vec(),
            cycles,
            scratch: Vec::with_capacity(task.phases.len() + 1),
            scratch_value: Vec::with_capacity(task.phases.len() + 1),
            total_cache: vec![None; nh],
            value_cache: vec![None; nh],
            bound_cache: vec![None; nh],
            terms: Vec::with_capacity(nh),
            weights: Vec::with_capacity(nh),
        }
    }

    /// Replaces the loads of phase `p` (after it was re-optimised).
    pub fn set_phase_loads(&mut self, p: usize, f: &[f64]) {
        for (h, v) in self.step_loads.iter_mut().enumerate() {
            v[p] = f[h];
        }
        self.total_cache.iter_mut().for_each(|c| *c = None);
        self.value_cache.iter_mut().for_each(|c| *c = None);
        self.bound_cache.iter_mut().for_each(|c| *c = None);
    }

    /// [`Self::total`] at load `f` with its derivatives, from the cache when `f` is unchanged.
    fn cached_total(&mut self, h: usize, f: f64) -> (Dual2, f64) {
        let bits = f.to_bits();
        if let Some((b, u, s)) = self.total_cache[h]
            && b == bits
        {
            return (u, s);
        }
        let (u, s) = self.total(h, Dual2::variable(f));
        self.total_cache[h] = Some((bits, u, s));
        (u, s)
    }

    /// One cycle's held steps of half-joint `h` into `out`: load `f` in the group's phases, the
    /// fixed loads elsewhere.
    fn cycle_steps<T: Real>(&self, h: usize, f: T, out: &mut Vec<HeldStep<T>>) {
        out.clear();
        for (s, &t_min) in self.step_t_min.iter().enumerate() {
            let load = if self.in_group[s] {
                f
            } else {
                T::cst(self.step_loads[h][s])
            };
            out.push(HeldStep { f: load, t_min });
        }
    }

    /// [`Self::total`]'s value alone, from either cache when `f` is unchanged.
    fn cached_value(&mut self, h: usize, f: f64) -> (f64, f64) {
        let bits = f.to_bits();
        if let Some((b, u, s)) = self.total_cache[h]
            && b == bits
        {
            return (u.v, s);
        }
        if let Some((b, u, s)) = self.value_cache[h]
            && b == bits
        {
            return (u, s);
        }
        let mut steps = std::mem::take(&mut self.scratch_value);
        self.cycle_steps(h, f, &mut steps);
        self.scratch_value = steps;
        let st = self.state[h];
        let r = repeated_cycles(&self.task.fatigue[h], &self.scratch_value, &st, self.cycles);
        let s = r.u_min.ln_scale;
        let u = r.u_min.u + st.fatigue_u_min * (-s).exp();
        self.value_cache[h] = Some((bits, u, s));
        (u, s)
    }

    /// Total U at the end \[min\] of half-joint `h` if it holds `f` in the group's phases, as
    /// (scaled value, ln scale).
    fn total(&mut self, h: usize, f: Dual2) -> (Dual2, f64) {
        let mut steps = std::mem::take(&mut self.scratch);
        self.cycle_steps(h, f, &mut steps);
        self.scratch = steps;
        let st = self.state[h];
        let r = repeated_cycles(&self.task.fatigue[h], &self.scratch, &st, self.cycles);
        let s = r.u_min.ln_scale;
        let u0 = st.fatigue_u_min * (-s).exp();
        (
            Dual2 {
                v: r.u_min.u.v + u0,
                ..r.u_min.u
            },
            s,
        )
    }

    /// The predicted total at the end with the loads as they are, per half-joint \[min\].
    pub fn totals_now(&mut self) -> Vec<f64> {
        (0..self.step_loads.len())
            .map(|h| {
                let f = self.group_load(h);
                let (u, s) = self.total(
                    h,
                    Dual2 {
                        v: f,
                        d: 0.0,
                        dd: 0.0,
                    },
                );
                u.v * s.exp()
            })
            .collect()
    }

    fn group_load(&self, h: usize) -> f64 {
        self.in_group
            .iter()
            .position(|&g| g)
            .map(|s| self.step_loads[h][s])
            .unwrap_or(0.0)
    }
}

/// `ln(Σ_h u_h e^{s_h} + ε)` and its per-term weights `e^{s_h}/(S + ε)`, without overflow.
fn log_sum(terms: &[(f64, f64)], weights: &mut [f64]) -> f64 {
    let eps_ln = EPSILON_U_MIN.ln();
    let mut m = eps_ln;
    for &(u, s) in terms {
        if u > 0.0 {
            m = m.max(u.ln() + s);
        }
    }
    let mut sum = (eps_ln - m).exp();
    for &(u, s) in terms {
        if u > 0.0 {
            sum += (u.ln() + s - m).exp();
        }
    }
    let log_s = m + sum.ln();
    for (w, &(_, s)) in weights.iter_mut().zip(terms) {
        *w = (s - log_s).exp();
    }
    log_s
}

impl LoadCost for FatigueCost<'_> {
    fn fork(&self) -> Box<dyn LoadCost + '_> {
        Box::new(self.clone())
    }
    fn capacity_bound(&mut self, h: usize, f: f64) -> Option<(f64, f64)> {
        if let Some((b, r)) = self.bound_cache[h]
            && b == f.to_bits()
        {
            return Some(r);
        }
        let mut steps = std::mem::take(&mut self.scratch);
        self.cycle_steps(h, Dual2::variable(f), &mut steps);
        self.scratch = steps;
        let c = lowest_end_capacity(
            &self.task.fatigue[h],
            &self.scratch,
            &self.in_group,
            &self.state[h],
            self.cycles,
        );
        let r = (c.v - EXHAUSTION_MARGIN, c.d);
        self.bound_cache[h] = Some((f.to_bits(), r));
        Some(r)
    }

    fn eval(&mut self, f: &[f64], grad: &mut [f64], curv: &mut [f64]) -> f64 {
        let j = self.derivatives(f, grad, curv);
        for c in curv.iter_mut() {
            *c = c.max(0.0);
        }
        j
    }

    /// `J = ln(S + ε)`, `S = Σ_h U_h`: `∂²J/∂f_h∂f_k = δ_hk U_h″/(S + ε) − ∂J/∂f_h · ∂J/∂f_k`.
    fn exact_curvature(&mut self, f: &[f64], grad: &mut [f64], diag: &mut [f64]) -> f64 {
        self.derivatives(f, grad, diag);
        1.0
    }

    fn value(&mut self, f: &[f64]) -> f64 {
        let mut terms = std::mem::take(&mut self.terms);
        terms.clear();
        terms.extend((0..f.len()).map(|h| self.cached_value(h, f[h])));
        let mut w = std::mem::take(&mut self.weights);
        w.resize(f.len(), 0.0);
        let j = log_sum(&terms, &mut w);
        (self.terms, self.weights) = (terms, w);
        j
    }
}

impl FatigueCost<'_> {
    /// J, its gradient `∂J/∂f_h = U_h′/(S + ε)` and the diagonal `U_h″/(S + ε)` of its
    /// curvature (the whole curvature less the rank-one `−∇J ∇Jᵀ` of the logarithm).
    fn derivatives(&mut self, f: &[f64], grad: &mut [f64], diag: &mut [f64]) -> f64 {
        let n = f.len();
        let mut terms = std::mem::take(&mut self.terms);
        terms.clear();
        for h in 0..n {
            let (u, s) = self.cached_total(h, f[h]);
            terms.push((u.v, s));
            grad[h] = u.d;
            diag[h] = u.dd;
        }
        let mut w = std::mem::take(&mut self.weights);
        w.resize(n, 0.0);
        let j = log_sum(&terms, &mut w);
        for h in 0..n {
            grad[h] *= w[h];
            diag[h] *= w[h];
        }
        (self.terms, self.weights) = (terms, w);
        j
    }
}

/// The minimum-joint-load baseline's cost: `Σ_h f_h²`.
#[derive(Debug, Clone, Copy, Default)]
pub struct SquaredLoads;

impl LoadCost for SquaredLoads {
    fn fork(&self) -> Box<dyn LoadCost + '_> {
        Box::new(*self)
    }
    fn eval(&mut self, f: &[f64], grad: &mut [f64], curv: &mut [f64]) -> f64 {
        for (i, &x) in f.iter().enumerate() {
            grad[i] = 2.0 * x;
            curv[i] = 2.0;
        }
        self.value(f)
    }
    fn value(&mut self, f: &[f64]) -> f64 {
        f.iter().map(|x| x * x).sum()
    }
}

/// No load cost (the nearest-to-neutral baseline: discomfort only).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoLoadCost;

impl LoadCost for NoLoadCost {
    fn fork(&self) -> Box<dyn LoadCost + '_> {
        Box::new(*self)
    }
    fn eval(&mut self, f: &[f64], grad: &mut [f64], curv: &mut [f64]) -> f64 {
        for i in 0..f.len() {
            grad[i] = 0.0;
            curv[i] = 0.0;
        }
        0.0
    }
    fn value(&mut self, _f: &[f64]) -> f64 {
        0.0
    }
}

/// Joint-range discomfort of a posture (see the module docs).
#[derive(Debug, Clone)]
pub struct Discomfort {
    /// Per q index: Some((lower, upper, neutral, weight)) for actuated joints with a finite range.
    ranges: Vec<Option<(f64, f64, f64, f64)>>,
    /// Per q index: the assessment zone (below, above neutral) \[rad\] beyond which a solve's
    /// zone weight prices the excess ([`assessment_zone_deg`]); infinite where none.
    zones: Vec<(f64, f64)>,
    /// Per q index: whether the (lower, upper) end is penalised. A limit the neutral posture
    /// sits at (a straight knee or elbow, a foot flat) is the joint's natural rest, not a strain.
    ends: Vec<(bool, bool)>,
}

/// Weight of a joint's displacement term: trunk bending sideways and twisting count ten times an
/// arm or leg joint, trunk flexion and the neck three times (after the joint weights of Marler et
/// al. 2005, which make the torso move last in reaching), the neck's twist and the hips' rotation
/// ten times, as the trunk's twist. ASSUMPTION where not named there. The neck's twist: RULA and
/// REBA score a twisted neck as they score a twisted trunk, and with a weight of 3 the plans
/// looked at their work with the head turned to its 45° limit and the trunk turned the other way
/// (shelf's 'pick from cart': the turn cost the neck nothing the fatigue term sees). The hips'
/// rotation turns the pelvis on planted feet: at weight 1 the plans turned the pelvis 20° one way
/// and the lumbar spine 10° the other within the zones' turn against the feet (shelf_high's
/// 'carry'), and which of such near-ties a plan took moved its total 1.4 % with the QP's
/// precision. The forearm's rotation three times: a hand target gives no hand orientation, so at
/// weight 1 a plan could hold a box with the forearm supinated 65° and the wrist flexed to its
/// 15° zone edge or with both neutral for about the same fatigue (shelf_high's 'place low
/// board'; the QP's precision picked one, 0.026 apart in the objective); people keep the forearm
/// near its mid-position (ASSUMPTION, as the neck's bending).
pub fn displacement_weight(joint: &str) -> f64 {
    match joint {
        "lumbar_lateral_bending"
        | "lumbar_axial_rotation"
        | "neck_axial_rotation"
        | "r_hip_rotation"
        | "l_hip_rotation" => 10.0,
        "r_forearm_pronation" | "l_forearm_pronation" => 3.0,
        "lumbar_flexion" => 3.0,
        j if j.starts_with("neck_") => 3.0,
        _ => 1.0,
    }
}

/// Weight of the end-of-range penalty of every joint (see the module doc for why 3).
pub const END_WEIGHT: f64 = 3.0;

/// The discomfort term's shape: the weights of its assessment zones and of its end-of-range
/// penalty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shape {
    pub zone_weight: f64,
    pub end_weight: f64,
}

impl Shape {
    /// The objective's: the task's `objective.zone_weight` and [`END_WEIGHT`].
    pub fn of(task: &Task) -> Self {
        Shape {
            zone_weight: task.objective.zone_weight,
            end_weight: END_WEIGHT,
        }
    }

    /// The nearest-to-neutral measure of a fatigue-only plan's starting postures, the same
    /// whatever the task's comfort settings: displacement only, no zones, no end penalty.
    pub const DISPLACEMENT: Shape = Shape {
        zone_weight: 0.0,
        end_weight: 0.0,
    };
}

/// The excess (fraction of the range) over which the zone penalty's curvature rises from 0 to
/// its full value: the penalty is C², so the SQP's curvature model does not jump at a zone's edge.
pub const ZONE_ONSET: f64 = 0.02;

/// The zone penalty of an excess `x ≥ 0` (fraction of the range), with its first and second
/// derivatives: `x³/(3δ)` up to δ = [`ZONE_ONSET`], then `x² − δx + δ²/3` (value, slope and
/// curvature continuous at δ; beyond it, `(x − δ/2)² + δ²/12`: a square shifted by half the onset).
fn zone_penalty(x: f64) -> (f64, f64, f64) {
    let d = ZONE_ONSET;
    if x <= 0.0 {
        (0.0, 0.0, 0.0)
    } else if x < d {
        (x * x * x / (3.0 * d), x * x / d, 2.0 * x / d)
    } else {
        (x * x - d * x + d * d / 3.0, 2.0 * x - d, 2.0)
    }
}

/// The zone around neutral (degrees below, above) within which RULA, REBA and ISO 11226 score a
/// joint as neutral or mildly loaded, for the directions where the plans' awkward postures cost
/// little fatigue (a twist, a sideways bend, a bent wrist or a leaning back carry almost no
/// gravity moment): beyond it, posture-opt prices the excess quadratically, so a plan leaves the
/// zone only when that buys clearly less fatigue. Trunk and neck flexion get no upper bound here:
/// the fatigue term already prices them (the trunk's and the head's weight), and a zone there
/// would trade a stoop for a deep squat the knees pay for. `None`: no zone.
///
/// * trunk extension 5° (REBA scores extension as flexion; ISO 11226:2000: a backward
///   inclination without support is not acceptable);
/// * trunk lateral bending and twist 10° each side (RULA and REBA add a point for any; 10° is an
///   ASSUMPTION: what an observer scoring RULA from the side would not see);
/// * neck extension 5° (RULA: any extension scores 4), lateral bending and twist 10° (RULA and
///   REBA +1; 10° as for the trunk, ASSUMPTION);
/// * wrist flexion and extension 15° (RULA: beyond 15° scores 3; REBA: beyond 15° scores 2),
///   deviation 10° (RULA +1 for any; 10°, ASSUMPTION).
pub fn assessment_zone_deg(joint: &str) -> Option<(f64, f64)> {
    let j = joint
        .strip_prefix("r_")
        .or_else(|| joint.strip_prefix("l_"))
        .unwrap_or(joint);
    match j {
        "lumbar_flexion" => Some((5.0, f64::INFINITY)),
        "lumbar_lateral_bending" | "lumbar_axial_rotation" => Some((10.0, 10.0)),
        "neck_flexion" => Some((5.0, f64::INFINITY)),
        "neck_lateral_bending" | "neck_axial_rotation" => Some((10.0, 10.0)),
        "wrist_flexion" => Some((15.0, 15.0)),
        "wrist_deviation" => Some((10.0, 10.0)),
        _ => None,
    }
}

/// A joint's neutral angle \[rad\]: 0 (upright standing, arms hanging), except that a seated
/// worker's hips and knees are neutral bent at right angles — the 90-90-90 sitting posture of
/// seating guidance (e.g. Collins 2001 for the weight it puts on the feet). ASSUMPTION: the
/// seat's height is near the popliteal height; a higher or lower seat moves the legs from it.
pub fn neutral_rad(joint: &str, seated: bool) -> f64 {
    let j = joint
        .strip_prefix("r_")
        .or_else(|| joint.strip_prefix("l_"))
        .unwrap_or(joint);
    if seated && matches!(j, "hip_flexion" | "knee_flexion") {
        std::f64::consts::FRAC_PI_2
    } else {
        0.0
    }
}

impl Discomfort {
    /// The actuated joints of `task` with finite ranges; neutral is [`neutral_rad`] clamped into
    /// the range.
    pub fn new(task: &Task) -> Self {
        let m = &task.model;
        let ranges = (0..m.nq())
            .map(|k| {
                let j = m.q_joint(k);
                if task.unactuated.contains(&k)
                    || !(j.lower_rad.is_finite() && j.upper_rad.is_finite())
                    || j.upper_rad - j.lower_rad <= 1e-9
                {
                    None
                } else {
                    Some((
                        j.lower_rad,
                        j.upper_rad,
                        neutral_rad(&j.name, task.seated()).clamp(j.lower_rad, j.upper_rad),
                        displacement_weight(&j.name),
                    ))
                }
            })
            .collect::<Vec<_>>();
        let ends = ranges
            .iter()
            .map(|r| match *r {
                Some((lo, hi, n, _)) => {
                    let u = (n - lo) / (hi - lo);
                    (u >= END_ZONE, u <= 1.0 - END_ZONE)
                }
                None => (false, false),
            })
            .collect();
        let zones = (0..m.nq())
            .map(
                |k| match (&ranges[k], assessment_zone_deg(&m.q_joint(k).name)) {
                    (Some(_), Some((below, above))) => (below.to_radians(), above.to_radians()),
                    _ => (f64::INFINITY, f64::INFINITY),
                },
            )
            .collect();
        Discomfort {
            ranges,
            ends,
            zones,
        }
    }

    /// The assessment-zone excess of joint `k` at `q` \[rad\], signed (negative below).
    fn zone_excess(&self, k: usize, q: f64, neutral: f64) -> f64 {
        let (below, above) = self.zones[k];
        let d = q - neutral;
        if d > above {
            d - above
        } else if d < -below {
            d + below
        } else {
            0.0
        }
    }

    /// Joint `k`'s term at `q` \[rad\] of the given shape (zones and end penalty weighted): value, slope × range, curvature bound (≥ 0) ×
    /// range² and the range; `None` for a joint without a finite range. (The slope and
    /// curvature are scaled by the range only where they are added up, so that the arithmetic,
    /// and with it the search's numerical path, is the same as without zones when the zones are
    /// off.)
    fn joint_term(&self, k: usize, q: f64, shape: Shape) -> Option<(f64, f64, f64, f64)> {
        let Shape {
            zone_weight,
            end_weight,
        } = shape;
        let (lo, hi, n, a) = self.ranges[k]?;
        let range = hi - lo;
        let x = (q - n) / range;
        let (p, dp, ddp) = end_penalty((q - lo) / range, self.ends[k]);
        let e = self.zone_excess(k, q, n) / range;
        let (z, dz, ddz) = zone_penalty(e.abs());
        Some((
            a * x * x + end_weight * p + zone_weight * z,
            2.0 * a * x + end_weight * dp + zone_weight * dz * e.signum(),
            2.0 * a + end_weight * ddp.max(0.0) + zone_weight * ddz,
            range,
        ))
    }

    /// Value, with gradient and diagonal curvature (≥ 0) added into `grad`/`curv` scaled by `w`;
    /// of the given shape.
    pub fn eval(&self, q: &[f64], w: f64, shape: Shape, grad: &mut [f64], curv: &mut [f64]) -> f64 {
        let mut total = 0.0;
        for (k, &qk) in q.iter().enumerate().take(self.ranges.len()) {
            let Some((v, dv, ddv, range)) = self.joint_term(k, qk, shape) else {
                continue;
            };
            total += v;
            grad[k] += w * dv / range;
            curv[k] += w * ddv / (range * range);
        }
        w * total
    }

    /// Value only (unweighted), of the given shape.
    pub fn value(&self, q: &[f64], shape: Shape) -> f64 {
        (0..self.ranges.len())
            .filter_map(|k| self.joint_term(k, q[k], shape))
            .fold(0.0, |total, (v, _, _, _)| total + v)
    }

    /// The joints of `q` clear of their limits by more than five times [`AT_LIMIT_FRACTION`] of
    /// their range (per q index).
    pub fn clear_of_limits(&self, q: &[f64]) -> Vec<bool> {
        let mut clear = vec![true; q.len()];
        for (k, _, _) in self.near_limits(q, 5.0 * AT_LIMIT_FRACTION) {
            clear[k] = false;
        }
        clear
    }

    /// Whether `q` has a joint at a limit ([`AT_LIMIT_FRACTION`]) among those `clear` marks as
    /// well clear of it: the margin keeps the verdict from hinging on a solver's last digits.
    pub fn parks_beyond(&self, q: &[f64], clear: &[bool]) -> bool {
        self.near_limits(q, AT_LIMIT_FRACTION)
            .iter()
            .any(|&(k, _, _)| clear[k])
    }

    /// Joints closer to a limit than `fraction` of their range: (q index, which end, distance
    /// as a fraction of the range).
    pub fn near_limits(&self, q: &[f64], fraction: f64) -> Vec<(usize, bool, f64)> {
        let mut out = Vec::new();
        for (k, r) in self.ranges.iter().enumerate() {
            let Some((lo, hi, _, _)) = *r else { continue };
            let range = hi - lo;
            let (dl, du) = ((q[k] - lo) / range, (hi - q[k]) / range);
            let (lower_on, upper_on) = self.ends[k];
            if dl < fraction && lower_on {
                out.push((k, false, dl));
            } else if du < fraction && upper_on {
                out.push((k, true, du));
            }
        }
        out
    }
}

/// End-of-range penalty of the position `u` (0..1) in the range, with its first and second
/// derivatives in `u`; `(lower, upper)` say which ends are penalised.
fn end_penalty(u: f64, (lower, upper): (bool, bool)) -> (f64, f64, f64) {
    let z = END_ZONE;
    let mut p = (0.0, 0.0, 0.0);
    if lower && u < z {
        let t = (z - u) / z;
        p.0 += t * t * t;
        p.1 += -3.0 * t * t / z;
        p.2 += 6.0 * t / (z * z);
    }
    if upper && u > 1.0 - z {
        let t = (u - (1.0 - z)) / z;
        p.0 += t * t * t;
        p.1 += 3.0 * t * t / z;
        p.2 += 6.0 * t / (z * z);
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn end_penalty_is_zero_inside_and_smooth_at_the_zone() {
        assert_eq!(end_penalty(0.5, (true, true)), (0.0, 0.0, 0.0));
        assert_eq!(end_penalty(0.1, (true, true)).0, 0.0);
        assert!((end_penalty(0.0, (true, true)).0 - 1.0).abs() < 1e-15);
        assert!((end_penalty(1.0, (true, true)).0 - 1.0).abs() < 1e-15);
        let h = 1e-6;
        for &u in &[0.03, 0.95, 0.099] {
            let fd = (end_penalty(u + h, (true, true)).0 - end_penalty(u - h, (true, true)).0)
                / (2.0 * h);
            assert!((end_penalty(u, (true, true)).1 - fd).abs() < 1e-5);
        }
    }

    /// The trunk-twist term against its hand derivation: displacement `10·(θ/90°)²` plus, at
    /// zone_weight 30, the zone's smoothed `30·((|θ|−10°)/90°)²` beyond 10°; no end penalty
    /// below 36° (the middle 80 % of ±45°); slope equal to the value's central difference;
    /// slope and curvature continuous across the zone's edge and the end of its onset.
    #[test]
    fn assessment_zone_prices_the_twist_beyond_ten_degrees() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/shelf.yaml");
        let task = Task::from_file(path).unwrap();
        let k = task.model.q_index("lumbar_axial_rotation").unwrap();
        let d = Discomfort::new(&task);
        let zone_weight = 30.0;
        let zoned = Shape {
            zone_weight,
            end_weight: END_WEIGHT,
        };
        let plain_shape = Shape {
            zone_weight: 0.0,
            end_weight: END_WEIGHT,
        };
        let j = task.model.q_joint(k);
        let range = j.upper_rad - j.lower_rad;
        let range_deg = range.to_degrees();
        assert!((range_deg - 90.0).abs() < 1e-3, "twist range {range_deg}°");
        let base = vec![0.0; task.model.nq()];
        let at = |theta_deg: f64| {
            let mut q = base.clone();
            q[k] = theta_deg.to_radians();
            q
        };
        let hand = |theta_deg: f64| {
            // beyond the onset, the shifted square (x − δ/2)² + δ²/12; within it, x³/(3δ)
            let x = (theta_deg.abs() - 10.0).max(0.0) / range_deg;
            let zone = if x < ZONE_ONSET {
                x.powi(3) / (3.0 * ZONE_ONSET)
            } else {
                (x - ZONE_ONSET / 2.0).powi(2) + ZONE_ONSET.powi(2) / 12.0
            };
            10.0 * (theta_deg / range_deg).powi(2) + zone_weight * zone
        };
        for theta in [
            -30.0, -12.0, -10.5, 0.0, 5.0, 10.0, 11.0, 15.0, 20.0, 30.0, 35.0,
        ] {
            let got = d.value(&at(theta), zoned) - d.value(&base, zoned);
            assert!(
                (got - hand(theta)).abs() < 1e-9,
                "θ {theta}°: {got} vs {}",
                hand(theta)
            );
            // with the default zone_weight 0, the displacement alone
            let plain = d.value(&at(theta), plain_shape) - d.value(&base, plain_shape);
            assert!((plain - 10.0 * (theta / range_deg).powi(2)).abs() < 1e-9);
        }
        let slope = |theta_deg: f64| {
            let (mut g, mut c) = (vec![0.0; base.len()], vec![0.0; base.len()]);
            d.eval(&at(theta_deg), 1.0, zoned, &mut g, &mut c);
            (g[k], c[k])
        };
        let h = 1e-6;
        for theta in [-25.0_f64, -11.0, 5.0, 10.9, 20.0, 33.0] {
            let q = theta.to_radians();
            let fd = (d.value(&at((q + h).to_degrees()), zoned)
                - d.value(&at((q - h).to_degrees()), zoned))
                / (2.0 * h);
            let (g, c) = slope(theta);
            assert!((g - fd).abs() < 1e-6, "θ {theta}°: slope {g} vs {fd}");
            assert!(c > 0.0);
        }
        // slope and curvature continuous at the zone's edge and at the end of the onset
        let onset_deg = 10.0 + ZONE_ONSET * range_deg;
        for edge in [10.0, onset_deg] {
            let (inside, outside) = (slope(edge - 1e-7), slope(edge + 1e-7));
            assert!(
                (inside.0 - outside.0).abs() < 1e-5,
                "{edge}°: {inside:?} {outside:?}"
            );
            assert!(
                (inside.1 - outside.1).abs() < 1e-4,
                "{edge}°: {inside:?} {outside:?}"
            );
        }
        // beyond the onset the curvature bound includes the zone's full 2·30/range²
        let beyond = slope(onset_deg + 1.0).1;
        assert!((beyond - 2.0 * (10.0 + zone_weight) / (range * range)).abs() < 1e-9);
    }

    /// The fatigue cost's exact curvature in the loads, `diag·δ − c·∇J ∇Jᵀ`, against central
    /// differences of its gradient: every entry (the rank-one term couples all half-joints)
    /// within 1e-5 of the largest, on the shelf task with the first phase's loads moved.
    #[test]
    fn the_fatigue_costs_curvature_is_the_derivative_of_its_gradient() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/shelf.yaml");
        let task = Task::from_file(path).unwrap();
        let nh = task.half_joints.len();
        // loads between 0 and 0.3, some half-joints unloaded
        let f: Vec<f64> = (0..nh)
            .map(|h| {
                if h % 3 == 0 {
                    0.0
                } else {
                    0.02 + 0.28 * ((h * 7) % 11) as f64 / 10.0
                }
            })
            .collect();
        let phase_loads = vec![f.clone(); task.phases.len()];
        let fresh = vec![MaState::FRESH; nh];
        let mut cost = FatigueCost::new(&task, &[0], &phase_loads, &f, &fresh, task.cycles as u64);
        let (mut g, mut diag) = (vec![0.0; nh], vec![0.0; nh]);
        let c = cost.exact_curvature(&f, &mut g, &mut diag);
        assert_eq!(c, 1.0);
        let mut clipped = vec![0.0; nh];
        let j = cost.eval(&f, &mut vec![0.0; nh], &mut clipped);
        assert_eq!(j, cost.value(&f));
        let step = 1e-6;
        let mut exact = vec![vec![0.0; nh]; nh];
        let mut fd = vec![vec![0.0; nh]; nh];
        let mut largest = 0.0f64;
        for k in 0..nh {
            let mut gk = [vec![0.0; nh], vec![0.0; nh]];
            for (side, x) in [f[k] - step, f[k] + step].into_iter().enumerate() {
                let mut moved = f.clone();
                moved[k] = x.max(0.0);
                cost.eval(&moved, &mut gk[side], &mut vec![0.0; nh]);
            }
            let width = (f[k] + step) - (f[k] - step).max(0.0);
            for h in 0..nh {
                fd[h][k] = (gk[1][h] - gk[0][h]) / width;
                exact[h][k] = if h == k { diag[h] } else { 0.0 } - c * g[h] * g[k];
                largest = largest.max(fd[h][k].abs());
            }
        }
        assert!(largest > 1e-3, "nothing to compare: {largest}");
        for h in 0..nh {
            // eval's diagonal is the exact one, clipped at zero
            assert_eq!(clipped[h], diag[h].max(0.0));
            for k in 0..nh {
                assert!(
                    (exact[h][k] - fd[h][k]).abs() <= 1e-5 * largest,
                    "({h}, {k}): {} vs differences {}",
                    exact[h][k],
                    fd[h][k]
                );
            }
        }
    }

    #[test]
    fn log_sum_of_scaled_terms() {
        let mut w = [0.0; 2];
        let j = log_sum(&[(2.0, 0.0), (3.0, 1000.0)], &mut w);
        assert!((j - (3f64.ln() + 1000.0)).abs() < 1e-12);
        assert!((w[1] - (1000.0 - j).exp()).abs() < 1e-15);
    }
}
