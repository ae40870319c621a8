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
//! range and rises as `((0.1 − u)/0.1)³` toward each limit (`u` the position in the range, 0..1),
//! replacing Marler's steeper `[0.5 sin(…) + 0.5]¹⁰⁰` bumps by a C² polynomial the SQP can
//! follow. A limit the neutral posture sits at (a straight knee or elbow) is not penalised: it
//! is where the joint rests. The task's discomfort is the mean over the cycle's phases, times the task's
//! `discomfort_weight` (default 0.1): in a one-phase task, one joint driven from mid-range to its
//! limit costs as much as about 10 % more fatigue (J is the logarithm of the total), 30° of trunk
//! twist about 1.2 %.

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
pub trait LoadCost {
    /// Value; fills `grad[h] = ∂J/∂f_h` and `curv[h] ≥ 0`, a diagonal curvature bound.
    fn eval(&mut self, f: &[f64], grad: &mut [f64], curv: &mut [f64]) -> f64;
    /// Value only.
    fn value(&mut self, f: &[f64]) -> f64;
    /// The load half-joint `h` may hold in this phase without being exhausted (its lowest
    /// capacity over the task) and the bound's slope in its load here; `None`: no bound.
    fn capacity_bound(&mut self, _h: usize, _f: f64) -> Option<(f64, f64)> {
        None
    }
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
        let r = repeated_cycles(
            &self.task.fatigue[h],
            &self.scratch_value,
            st.capacity,
            self.cycles,
        );
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
        let r = repeated_cycles(
            &self.task.fatigue[h],
            &self.scratch,
            st.capacity,
            self.cycles,
        );
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
            self.state[h].capacity,
            self.cycles,
        );
        let r = (c.v - EXHAUSTION_MARGIN, c.d);
        self.bound_cache[h] = Some((f.to_bits(), r));
        Some(r)
    }

    fn eval(&mut self, f: &[f64], grad: &mut [f64], curv: &mut [f64]) -> f64 {
        let n = f.len();
        let mut terms = Vec::with_capacity(n);
        let mut derivs = Vec::with_capacity(n);
        for h in 0..n {
            let (u, s) = self.cached_total(h, f[h]);
            terms.push((u.v, s));
            derivs.push((u.d, u.dd));
        }
        let mut w = vec![0.0; n];
        let j = log_sum(&terms, &mut w);
        for h in 0..n {
            grad[h] = derivs[h].0 * w[h];
            curv[h] = derivs[h].1.max(0.0) * w[h];
        }
        j
    }

    fn value(&mut self, f: &[f64]) -> f64 {
        let n = f.len();
        let terms: Vec<(f64, f64)> = (0..n).map(|h| self.cached_value(h, f[h])).collect();
        let mut w = vec![0.0; n];
        log_sum(&terms, &mut w)
    }
}

/// The minimum-joint-load baseline's cost: `Σ_h f_h²`.
#[derive(Debug, Clone, Copy, Default)]
pub struct SquaredLoads;

impl LoadCost for SquaredLoads {
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
    /// Per q index: whether the (lower, upper) end is penalised. A limit the neutral posture
    /// sits at (a straight knee or elbow, a foot flat) is the joint's natural rest, not a strain.
    ends: Vec<(bool, bool)>,
}

/// Weight of a joint's displacement term: trunk bending sideways and twisting count ten times an
/// arm or leg joint, trunk flexion and the neck three times (after the joint weights of Marler et
/// al. 2005, which make the torso move last in reaching). ASSUMPTION where not named there.
pub fn displacement_weight(joint: &str) -> f64 {
    match joint {
        "lumbar_lateral_bending" | "lumbar_axial_rotation" => 10.0,
        "lumbar_flexion" => 3.0,
        j if j.starts_with("neck_") => 3.0,
        _ => 1.0,
    }
}

/// Weight of the end-of-range penalty of every joint.
pub const END_WEIGHT: f64 = 1.0;

impl Discomfort {
    /// The actuated joints of `task` with finite ranges; neutral is 0 clamped into the range.
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
                        0.0_f64.clamp(j.lower_rad, j.upper_rad),
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
        Discomfort { ranges, ends }
    }

    /// Value, with gradient and diagonal curvature (≥ 0) added into `grad`/`curv` scaled by `w`.
    pub fn eval(&self, q: &[f64], w: f64, grad: &mut [f64], curv: &mut [f64]) -> f64 {
        let mut total = 0.0;
        for (k, r) in self.ranges.iter().enumerate() {
            let Some((lo, hi, n, a)) = *r else { continue };
            let range = hi - lo;
            let x = (q[k] - n) / range;
            let u = (q[k] - lo) / range;
            let (p, dp, ddp) = end_penalty(u, self.ends[k]);
            total += a * x * x + END_WEIGHT * p;
            grad[k] += w * (2.0 * a * x + END_WEIGHT * dp) / range;
            curv[k] += w * (2.0 * a + END_WEIGHT * ddp.max(0.0)) / (range * range);
        }
        w * total
    }

    /// Value only (unweighted).
    pub fn value(&self, q: &[f64]) -> f64 {
        let mut total = 0.0;
        for (k, r) in self.ranges.iter().enumerate() {
            let Some((lo, hi, n, a)) = *r else { continue };
            let range = hi - lo;
            let x = (q[k] - n) / range;
            total += a * x * x + END_WEIGHT * end_penalty((q[k] - lo) / range, self.ends[k]).0;
        }
        total
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

    #[test]
    fn log_sum_of_scaled_terms() {
        let mut w = [0.0; 2];
        let j = log_sum(&[(2.0, 0.0), (3.0, 1000.0)], &mut w);
        assert!((j - (3f64.ln() + 1000.0)).abs() < 1e-12);
        assert!((w[1] - (1000.0 - j).exp()).abs() < 1e-15);
    }
}
