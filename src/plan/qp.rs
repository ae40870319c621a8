//! The posture QP, on a fixed sparsity pattern, solved by clarabel (the crate's only clarabel
//! user). The solver is built at the first QP of each local solve and its data updated in place
//! between that solve's SQP iterations (presolve off). It is built afresh for every local solve
//! ([`PostureQp::forget_solver`]) because clarabel's data updates keep the equilibration of the
//! QP the solver was built with: a reused solver made each solve depend on the solves before it
//! (so on the order of the multi-start's seeds, and on which thread ran them).
//!
//! The solver is given the QP reduced to what can matter ([`PostureQp::solve`]): the torques
//! that keep their sign substituted (the unknowns are then the posture and the few torques near
//! zero), the equality rows hard while their multipliers stay below the slacks' penalty and then
//! eliminated (the posture step written on their null space, so that the solver's dense block is
//! the posture's free directions alone), and the joint-limit, capacity, clearance, balance and
//! zone rows a short step cannot reach left out. The solution is
//! checked against everything left out, and what it violates is put back and the QP solved
//! again; the solver is also rebuilt when the reduction changes.
//!
//! Variables `x = [Δq (n), s⁺ (a), s⁻ (a), e⁺ (m), e⁻ (m), v_cap, v_geo, v_zone (z)]`: the posture step, the actuated
//! joints' torques split by sign (`τ̄ + D Δq = s⁺ − s⁻`, so every half-joint's load `s±/MVC±` is
//! linear and the sign of each torque is chosen by the solver), a slack per equality row (hand
//! targets, feet) split by sign, `e⁺ − e⁻`, at the merit's ℓ1 penalty (and a stiff quadratic
//! one) — so the QP stays solvable when a target is out of reach and returns the nearest
//! posture, and violates a target only where the merit would — and one slack each for the capacity rows and for
//! the geometric inequalities (clearances and balance), with linear penalties, and one slack per
//! posture-zone row (an ℓ1 penalty each: [`super::zones`]).
//! Rows: torque split (a, =), targets and feet (m, =), `s⁺, s⁻, v ≥ 0`, one joint-limit row per
//! joint (its nearer limit; the step box keeps the other out of reach), one capacity row per
//! half-joint (on its own torque-split variable, the shared slack and the few posture variables
//! its strength depends on, so the rows cost the factorisation almost nothing, where rows over
//! every load variable made the whole torque block dense), `K` clearance rows, `E` balance rows and `Z` zone rows.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT,
    SolverStatus, SupportedConeT, ZeroConeT,
};

/// Why a QP could not be set up or solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QpError {
    #[error("QP setup failed: {0}")]
    Setup(String),
    #[error("QP data update failed: {0}")]
    Update(String),
}

/// Sizes of the QP.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QpSizes {
    /// Posture variables.
    pub n: usize,
    /// Actuated joints.
    pub a: usize,
    /// Equality rows (targets and feet).
    pub m: usize,
    /// Capacity rows: one per half-joint (torque-split variable), `2a`.
    pub c: usize,
    /// Clearance rows.
    pub k: usize,
    /// Balance rows.
    pub e: usize,
    /// Posture-zone rows, each with its own slack.
    pub z: usize,
}

/// Column offsets.
#[derive(Debug, Clone, Copy)]
pub struct Cols {
    pub dq: usize,
    pub s_plus: usize,
    pub s_minus: usize,
    pub e: usize,
    pub v_cap: usize,
    pub v_geo: usize,
    /// The posture zones' slacks (`z` of them).
    pub v_zone: usize,
    pub n_var: usize,
}

/// Row offsets.
#[derive(Debug, Clone, Copy)]
pub struct Rows {
    pub torque: usize,
    pub eq: usize,
    pub nonneg: usize,
    pub limit: usize,
    pub cap: usize,
    pub clearance: usize,
    pub balance: usize,
    pub zone: usize,
    pub n_row: usize,
    pub n_zero: usize,
}

impl QpSizes {
    pub fn cols(&self) -> Cols {
        let dq = 0;
        let s_plus = dq + self.n;
        let s_minus = s_plus + self.a;
        let e = s_minus + self.a;
        let v_cap = e + 2 * self.m;
        let v_geo = v_cap + 1;
        let v_zone = v_geo + 1;
        Cols {
            dq,
            s_plus,
            s_minus,
            e,
            v_cap,
            v_geo,
            v_zone,
            n_var: v_zone + self.z,
        }
    }

    pub fn rows(&self) -> Rows {
        let c = self.cols();
        let torque = 0;
        let eq = torque + self.a;
        let nonneg = eq + self.m;
        let limit = nonneg + 2 * self.a + 2 + self.z + 2 * self.m;
        let cap = limit + self.n;
        let clearance = cap + self.c;
        let balance = clearance + self.k;
        let zone = balance + self.e;
        let _ = c;
        Rows {
            torque,
            eq,
            nonneg,
            limit,
            cap,
            clearance,
            balance,
            zone,
            n_row: zone + self.z,
            n_zero: self.a + self.m,
        }
    }
}

/// The QP's data on its fixed pattern, and the solver.
pub struct PostureQp {
    pub sizes: QpSizes,
    pub cols: Cols,
    pub rows: Rows,
    /// Index of each (row, col) in the stored nonzeros, `u32::MAX` where the pattern has none.
    slot: Vec<u32>,
    a_pattern: Vec<(usize, usize)>,
    pub a_nz: Vec<f64>,
    pub b: Vec<f64>,
    /// Diagonal of P outside the posture block (the posture block is `p_dq`).
    pub p_diag: Vec<f64>,
    /// The posture block of P, dense, row-major n × n (symmetric; its upper triangle is used).
    pub p_dq: Vec<f64>,
    pub q: Vec<f64>,
    solver: Option<DefaultSolver<f64>>,
    settings: DefaultSettings<f64>,
    /// Each stored entry's index in `a_pattern` by column: column `c`'s entries are
    /// `a_colptr[c]..a_colptr[c + 1]`.
    a_colptr: Vec<usize>,
    /// How each actuated joint's torque enters the solver's problem ([`Split`]).
    split: Vec<Split>,
    /// Whether the equality rows' slacks are variables of the solver's problem (else the rows
    /// are hard and the slacks 0).
    elastic: bool,
    /// Rows given to the solver (the others are left out: [`Self::solve`]) and columns (the
    /// others are 0 or functions of the posture step), and each one's index among them
    /// (`usize::MAX`: left out).
    kept: Vec<bool>,
    live: Vec<bool>,
    red_row: Vec<usize>,
    red_col: Vec<usize>,
    /// The structure the solver was built for: kept rows, live columns, torque splits, and
    /// whether the posture was projected on the equality rows' null space.
    built_for: (Vec<bool>, Vec<bool>, Vec<Split>, bool),
    /// The hard equality rows eliminated ([`Self::project`]): `Δq = Δq_p + Z y`, `y` the
    /// solver's first `n_y` columns. Kept for the expansion: the rows used, the particular
    /// step, Z (n × n_y, column-major) and the thin factors `Jᵀ = Q₁ R` of the rows used.
    projected: Option<Projection>,
    /// The solver's problem: its A's entries (full row and column, in its column order) and
    /// values, its P's (upper triangle) and values, q and b.
    red_pat: Vec<(usize, usize)>,
    red_nz: Vec<f64>,
    red_p_pat: Vec<(usize, usize)>,
    red_p_nz: Vec<f64>,
    red_q: Vec<f64>,
    red_b: Vec<f64>,
    /// The problem with the torques of the one-signed joints substituted: each row's entries
    /// on the posture columns (n_row × n, row-major), b, q and P's posture block.
    sub_a_dq: Vec<f64>,
    sub_b: Vec<f64>,
    sub_q: Vec<f64>,
    sub_p_dq: Vec<f64>,
    /// Rows that touch a substituted torque (dense over the posture in the solver's problem).
    densified: Vec<bool>,
    /// Rows with posture entries in the pattern.
    has_dq: Vec<bool>,
    /// Screenable rows given to the solver at some QP of this local solve (they stay).
    sticky: Vec<bool>,
    /// Scratch: `Ax`, the rows wanted.
    ax: Vec<f64>,
    want: Vec<bool>,
    /// Whether the solver's problem is reduced (on by default; off solves every QP whole).
    pub screen: bool,
    /// The last solution: primal x and dual z (clarabel's `Px + q + Aᵀz = 0`).
    pub x: Vec<f64>,
    pub z: Vec<f64>,
    /// QP solves and interior-point iterations so far.
    pub solves: u64,
    pub ipm_iterations: u64,
}

/// A screenable row is left out of a QP when its slack exceeds this multiple of its norm over
/// the posture columns: no posture step shorter than this (rad or m, Euclidean) reaches it. The
/// check after the solve puts back any row a longer step violates.
const SCREEN_REACH: f64 = 0.05;

/// A row left out is violated at the reduced solution when `A_i x − b_i` exceeds this times
/// `1 + |b_i|`.
const SCREEN_TOL: f64 = 1e-9;

/// A variable left at zero is set free when the bound `x ≥ 0` holding it needs a multiplier
/// below `−SCREEN_DUAL_TOL (1 + |q_x|)` (`q_x` its linear cost): the objective would fall if it
/// rose.
const SCREEN_DUAL_TOL: f64 = 1e-9;

/// The posture step written on the null space of the hard equality rows.
#[derive(Debug, Clone)]
struct Projection {
    /// The equality rows with a nonzero posture part (the others read `0 = 0`).
    rows: Vec<usize>,
    dq_p: Vec<f64>,
    n_y: usize,
    z: nalgebra::DMatrix<f64>,
    q1: nalgebra::DMatrix<f64>,
    r: nalgebra::DMatrix<f64>,
}

/// How an actuated joint's torque `τ = τ̄ + D Δq` enters the solver's problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Split {
    /// Both signs are variables: `s⁺ − s⁻ = τ`, `s± ≥ 0`.
    Both,
    /// The torque keeps its sign: `s⁺ = τ̄ + D Δq` is substituted and `s⁻ = 0` (or the
    /// reverse). The sign bound is left out and checked after the solve.
    Plus,
    Minus,
}

/// Solver precision of the QP (clarabel's gap and feasibility tolerances).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QpPrecision {
    pub tol_gap: f64,
    pub tol_feas: f64,
}

impl Default for QpPrecision {
    fn default() -> Self {
        QpPrecision {
            tol_gap: 1e-9,
            tol_feas: 1e-9,
        }
    }
}

/// Each flagged entry's index among the flagged ones (`usize::MAX` for the others), into `map`;
/// returns how many are flagged.
fn index_among(flags: &[bool], map: &mut [usize]) -> usize {
    let mut next = 0;
    for (m, &f) in map.iter_mut().zip(flags) {
        *m = if f {
            next += 1;
            next - 1
        } else {
            usize::MAX
        };
    }
    next
}

impl PostureQp {
    /// A QP with the given sizes and solver precision; `capacity_q` adds, per capacity row, the
    /// posture variables its strength depends on (pairs of capacity row, posture variable).
    pub fn new(
        sizes: QpSizes,
        precision: QpPrecision,
        capacity_q: &[(usize, usize)],
    ) -> Result<Self, QpError> {
        let cols = sizes.cols();
        let rows = sizes.rows();
        let (n, a, m) = (sizes.n, sizes.a, sizes.m);
        let mut pat: Vec<(usize, usize)> = Vec::new();
        for j in 0..n {
            let col = cols.dq + j;
            for r in 0..a {
                pat.push((rows.torque + r, col));
            }
            for r in 0..m {
                pat.push((rows.eq + r, col));
            }
            pat.push((rows.limit + j, col));
            for r in 0..sizes.k {
                pat.push((rows.clearance + r, col));
            }
            for r in 0..sizes.e {
                pat.push((rows.balance + r, col));
            }
            for r in 0..sizes.z {
                pat.push((rows.zone + r, col));
            }
        }
        for i in 0..a {
            pat.push((rows.torque + i, cols.s_plus + i));
            pat.push((rows.torque + i, cols.s_minus + i));
            pat.push((rows.nonneg + i, cols.s_plus + i));
            pat.push((rows.nonneg + a + i, cols.s_minus + i));
        }
        // one capacity row per torque-split variable (half-joint): its own load only, so the
        // rows add no fill to the KKT factorisation
        for r in 0..sizes.c {
            pat.push((rows.cap + r, cols.s_plus + r));
        }
        for &(r, k) in capacity_q {
            pat.push((rows.cap + r, cols.dq + k));
        }
        for i in 0..m {
            pat.push((rows.eq + i, cols.e + i));
            pat.push((rows.eq + i, cols.e + m + i));
            pat.push((rows.nonneg + 2 * a + 2 + sizes.z + i, cols.e + i));
            pat.push((rows.nonneg + 2 * a + 2 + sizes.z + m + i, cols.e + m + i));
        }
        pat.push((rows.nonneg + 2 * a, cols.v_cap));
        pat.push((rows.nonneg + 2 * a + 1, cols.v_geo));
        for r in 0..sizes.c {
            pat.push((rows.cap + r, cols.v_cap));
        }
        for r in 0..sizes.k {
            pat.push((rows.clearance + r, cols.v_geo));
        }
        for r in 0..sizes.e {
            pat.push((rows.balance + r, cols.v_geo));
        }
        for r in 0..sizes.z {
            pat.push((rows.nonneg + 2 * a + 2 + r, cols.v_zone + r));
            pat.push((rows.zone + r, cols.v_zone + r));
        }
        pat.sort_by_key(|&(row, col)| (col, row));
        pat.dedup();
        let mut slot = vec![u32::MAX; rows.n_row * cols.n_var];
        for (i, &(r, c)) in pat.iter().enumerate() {
            slot[r * cols.n_var + c] = i as u32;
        }
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .presolve_enable(false)
            .max_iter(200)
            .tol_gap_abs(precision.tol_gap)
            .tol_gap_rel(precision.tol_gap)
            .tol_feas(precision.tol_feas)
            // Iterative refinement of the KKT solves is off: it took 40 % of the solver's time
            // and changed neither the solutions' accuracy at the tolerances above nor the plans'
            // quality (measured on the shipped tasks).
            .iterative_refinement_enable(false)
            .static_regularization_constant(1e-8)
            .direct_solve_method("qdldl".into())
            .build()
            .map_err(|e| QpError::Setup(e.to_string()))?;
        let mut qp = PostureQp {
            sizes,
            cols,
            rows,
            slot,
            a_nz: vec![0.0; pat.len()],
            a_pattern: pat,
            b: vec![0.0; rows.n_row],
            p_diag: vec![0.0; cols.n_var],
            p_dq: vec![0.0; sizes.n * sizes.n],
            q: vec![0.0; cols.n_var],
            solver: None,
            settings,
            a_colptr: Vec::new(),
            split: vec![Split::Both; a],
            elastic: true,
            kept: vec![true; rows.n_row],
            live: vec![true; cols.n_var],
            red_row: (0..rows.n_row).collect(),
            red_col: (0..cols.n_var).collect(),
            built_for: (Vec::new(), Vec::new(), Vec::new(), false),
            projected: None,
            red_pat: Vec::new(),
            red_nz: Vec::new(),
            red_p_pat: Vec::new(),
            red_p_nz: Vec::new(),
            red_q: Vec::new(),
            red_b: Vec::new(),
            sub_a_dq: vec![0.0; rows.n_row * n],
            sub_b: vec![0.0; rows.n_row],
            sub_q: vec![0.0; cols.n_var],
            sub_p_dq: vec![0.0; n * n],
            densified: vec![false; rows.n_row],
            has_dq: vec![false; rows.n_row],
            sticky: vec![false; rows.n_row],
            ax: vec![0.0; rows.n_row],
            want: vec![true; rows.n_row],
            screen: true,
            x: vec![0.0; cols.n_var],
            z: vec![0.0; rows.n_row],
            solves: 0,
            ipm_iterations: 0,
        };
        let mut a_colptr = vec![0usize; cols.n_var + 1];
        for &(_, c) in &qp.a_pattern {
            a_colptr[c + 1] += 1;
        }
        for c in 0..cols.n_var {
            a_colptr[c + 1] += a_colptr[c];
        }
        qp.a_colptr = a_colptr;
        for &(r, c) in &qp.a_pattern {
            qp.has_dq[r] |= c < n;
        }
        qp.forget_solver();
        Ok(qp)
    }

    /// `x_iᵀ (P x)_i` helper: `(P x)_i` for the posture block and the diagonal.
    pub fn p_times(&self, x: &[f64], out: &mut [f64]) {
        let n = self.sizes.n;
        for i in 0..self.cols.n_var {
            out[i] = if i < n {
                (0..n).map(|j| self.p_dq[i * n + j] * x[j]).sum()
            } else {
                self.p_diag[i] * x[i]
            };
        }
    }

    /// Zeroes A, b, P and q before a fill.
    pub fn clear(&mut self) {
        self.a_nz.iter_mut().for_each(|x| *x = 0.0);
        self.b.iter_mut().for_each(|x| *x = 0.0);
        self.p_diag.iter_mut().for_each(|x| *x = 0.0);
        self.p_dq.iter_mut().for_each(|x| *x = 0.0);
        self.q.iter_mut().for_each(|x| *x = 0.0);
    }

    /// Sets A\[row, col\] (must be in the pattern).
    #[inline]
    pub fn set_a(&mut self, row: usize, col: usize, v: f64) {
        let s = self.slot[row * self.cols.n_var + col];
        debug_assert!(s != u32::MAX, "({row}, {col}) is not in the QP's pattern");
        self.a_nz[s as usize] = v;
    }

    /// Adds to A\[row, col\] (must be in the pattern).
    #[inline]
    pub fn add_a(&mut self, row: usize, col: usize, v: f64) {
        let s = self.slot[row * self.cols.n_var + col];
        debug_assert!(s != u32::MAX, "({row}, {col}) is not in the QP's pattern");
        self.a_nz[s as usize] += v;
    }

    /// A\[row, col\] (0 outside the pattern).
    #[inline]
    pub fn a(&self, row: usize, col: usize) -> f64 {
        match self.slot[row * self.cols.n_var + col] {
            u32::MAX => 0.0,
            s => self.a_nz[s as usize],
        }
    }

    /// The column an actuated joint's substituted torque lives in, and the one left at zero.
    fn split_cols(&self, joint: usize) -> Option<(usize, usize)> {
        let (p, m) = (self.cols.s_plus + joint, self.cols.s_minus + joint);
        match self.split[joint] {
            Split::Both => None,
            Split::Plus => Some((p, m)),
            Split::Minus => Some((m, p)),
        }
    }

    /// The bound row `−x ≤ 0` of a slack or torque column (`None`: the posture).
    fn bound_row(&self, col: usize) -> Option<usize> {
        let (c, r, sz) = (self.cols, self.rows, self.sizes);
        let nn = r.nonneg;
        if col < c.s_plus {
            None
        } else if col < c.e {
            Some(nn + (col - c.s_plus))
        } else if col < c.v_cap {
            Some(nn + 2 * sz.a + 2 + sz.z + (col - c.e))
        } else if col == c.v_cap {
            Some(nn + 2 * sz.a)
        } else if col == c.v_geo {
            Some(nn + 2 * sz.a + 1)
        } else {
            Some(nn + 2 * sz.a + 2 + (col - c.v_zone))
        }
    }

    /// `Σ_r A[r, col] z_r` over the rows but `skip`.
    fn col_dot(&self, col: usize, z: &[f64], skip: usize) -> f64 {
        (self.a_colptr[col]..self.a_colptr[col + 1])
            .filter(|&k| self.a_pattern[k].0 != skip)
            .map(|k| self.a_nz[k] * z[self.a_pattern[k].0])
            .sum()
    }

    /// Drops the solver and the reductions chosen so far: the next [`Self::solve`] builds it
    /// from its own data, so that its scaling and rows (and so its answer) do not depend on
    /// earlier QPs.
    pub fn forget_solver(&mut self) {
        self.solver = None;
        let r = self.rows.limit;
        self.sticky[r..].iter_mut().for_each(|k| *k = false);
        self.split.iter_mut().for_each(|s| *s = Split::Plus);
        self.elastic = !self.screen;
    }

    /// The rows that may be left out: the capacity rows, clearances, balance and posture zones
    /// (the equalities, bounds and joint limits always stay).
    fn screenable(&self) -> std::ops::Range<usize> {
        if self.projected.is_some() {
            // the joint limits are dense over the null space's coordinates
            self.rows.limit..self.rows.n_row
        } else {
            self.rows.cap..self.rows.n_row
        }
    }

    /// Chooses each joint's torque split: a joint whose torque no short step can turn round
    /// ([`SCREEN_REACH`] times the norm of its posture gradient) keeps its sign and its torque
    /// is substituted; the others (and any once found to turn round in this local solve: they
    /// stay) keep both signs as variables.
    fn choose_splits(&mut self) {
        let n = self.sizes.n;
        for i in 0..self.sizes.a {
            if !self.screen {
                self.split[i] = Split::Both;
                continue;
            }
            if self.split[i] == Split::Both {
                continue;
            }
            let t = self.rows.torque + i;
            let tau = -self.b[t];
            let norm = (0..n)
                .map(|k| self.a(t, self.cols.dq + k).powi(2))
                .sum::<f64>()
                .sqrt();
            self.split[i] = if tau > SCREEN_REACH * norm {
                Split::Plus
            } else if -tau > SCREEN_REACH * norm {
                Split::Minus
            } else {
                Split::Both
            };
        }
    }

    /// The problem with the one-signed torques substituted (`sub_*`): a torque column `x_c`
    /// defined by its split row `A_t,dq Δq + A_t,c x_c = b_t` is `α + wᵀΔq`, `α = b_t / A_t,c`,
    /// `w = −A_t,dq / A_t,c`; every other row on it gains `A_r,c w` on the posture and loses
    /// `A_r,c α` from b, P's posture block gains `P_cc w wᵀ` and q `(P_cc α + q_c) w`.
    fn substitute(&mut self) {
        let n = self.sizes.n;
        self.sub_a_dq.iter_mut().for_each(|v| *v = 0.0);
        for (k, &(r, c)) in self.a_pattern.iter().enumerate() {
            if c < n {
                self.sub_a_dq[r * n + c] = self.a_nz[k];
            }
        }
        self.sub_b.copy_from_slice(&self.b);
        self.sub_q.copy_from_slice(&self.q);
        self.sub_p_dq.copy_from_slice(&self.p_dq);
        self.densified.iter_mut().for_each(|d| *d = false);
        for i in 0..self.sizes.a {
            let Some((c, _)) = self.split_cols(i) else {
                continue;
            };
            let t = self.rows.torque + i;
            let at = self.a(t, c);
            let alpha = self.b[t] / at;
            for k in self.a_colptr[c]..self.a_colptr[c + 1] {
                let r = self.a_pattern[k].0;
                if r == t {
                    continue;
                }
                let coef = self.a_nz[k];
                for j in 0..n {
                    self.sub_a_dq[r * n + j] -= coef * self.sub_a_dq[t * n + j] / at;
                }
                self.sub_b[r] -= coef * alpha;
                self.densified[r] = true;
            }
            let h = self.p_diag[c];
            let lin = h * alpha + self.q[c];
            for j in 0..n {
                let wj = -self.sub_a_dq[t * n + j] / at;
                self.sub_q[self.cols.dq + j] += lin * wj;
                if h != 0.0 {
                    for l in 0..n {
                        let wl = -self.sub_a_dq[t * n + l] / at;
                        self.sub_p_dq[j * n + l] += h * wj * wl;
                    }
                }
            }
        }
    }

    /// With hard equality rows (not [`Self::elastic`]), writes the posture step on their null
    /// space: `Δq = Δq_p + Z y`, `Δq_p` the least-norm step meeting them and Z an orthonormal
    /// basis of their null space (from the QR factors `Jᵀ = Q R`). Every row's posture part
    /// becomes `A_dq Z` over `y` (stored in the first `n_y` posture columns) and its b loses
    /// `A_dq Δq_p`; P's posture block becomes `Zᵀ P Z` and q `Zᵀ (q + P Δq_p)`. The equality
    /// rows leave the solver's problem (the factorisation no longer carries them over the dense
    /// posture block) and their multipliers are recovered in [`Self::expand`]. Contradictory
    /// rows set the slacks free; dependent rows stay in the solver's problem.
    fn project(&mut self) {
        use nalgebra::{DMatrix, DVector};
        self.projected = None;
        let (n, m, r) = (self.sizes.n, self.sizes.m, self.rows);
        if !self.screen || self.elastic || m == 0 {
            return;
        }
        let used: Vec<usize> = (r.eq..r.eq + m)
            .filter(|&i| self.sub_a_dq[i * n..(i + 1) * n].iter().any(|&v| v != 0.0))
            .collect();
        if (r.eq..r.eq + m).any(|i| !used.contains(&i) && self.sub_b[i] != 0.0) {
            self.elastic = true;
            return;
        }
        let k = used.len();
        if k == 0 || k >= n {
            return;
        }
        let jt = DMatrix::from_fn(n, k, |row, col| self.sub_a_dq[used[col] * n + row]);
        let qr = jt.qr();
        let rr = qr.r();
        let largest = (0..k).map(|i| rr[(i, i)].abs()).fold(0.0f64, f64::max);
        if (0..k).any(|i| rr[(i, i)].abs() <= 1e-9 * largest) {
            return;
        }
        let mut qt = DMatrix::<f64>::identity(n, n);
        qr.q_tr_mul(&mut qt);
        let q1 = qt.rows(0, k).transpose();
        let z = qt.rows(k, n - k).transpose();
        let b = DVector::from_fn(k, |i, _| self.sub_b[used[i]]);
        let Some(w) = rr.transpose().solve_lower_triangular(&b) else {
            return;
        };
        let dq_p = &q1 * w;
        let n_y = n - k;
        let mut row_y = vec![0.0; n_y];
        for row in 0..r.n_row {
            if !self.has_dq[row] && !self.densified[row] {
                continue;
            }
            self.densified[row] = true;
            let a = &self.sub_a_dq[row * n..(row + 1) * n];
            self.sub_b[row] -= (0..n).map(|j| a[j] * dq_p[j]).sum::<f64>();
            for (c, v) in row_y.iter_mut().enumerate() {
                *v = (0..n).map(|j| a[j] * z[(j, c)]).sum();
            }
            let a = &mut self.sub_a_dq[row * n..(row + 1) * n];
            a[..n_y].copy_from_slice(&row_y);
            a[n_y..].iter_mut().for_each(|v| *v = 0.0);
        }
        let p = DMatrix::from_row_slice(n, n, &self.sub_p_dq);
        let q = DVector::from_column_slice(&self.sub_q[..n]);
        let qy = z.transpose() * (q + &p * &dq_p);
        let py = z.transpose() * &p * &z;
        self.sub_p_dq.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..n_y {
            for j in 0..n_y {
                self.sub_p_dq[i * n + j] = 0.5 * (py[(i, j)] + py[(j, i)]);
            }
        }
        for j in 0..n {
            self.sub_q[j] = if j < n_y { qy[j] } else { 0.0 };
        }
        self.projected = Some(Projection {
            rows: used,
            dq_p: dq_p.iter().copied().collect(),
            n_y,
            z: z.into_owned(),
            q1: q1.into_owned(),
            r: rr,
        });
    }

    /// Which rows and columns the solver's problem has: every row and column but the bound
    /// rows and columns of the substituted or zeroed torques, the split rows of substituted
    /// torques, the equality slacks unless [`Self::elastic`], and the screenable rows that a
    /// short step cannot reach — a row `A_i x ≤ b_i` whose slack at `x = 0` exceeds
    /// [`SCREEN_REACH`] times its norm over the posture columns — and that no earlier QP of
    /// this local solve needed (a row once given stays until [`Self::forget_solver`]: fewer
    /// re-solves and rebuilds). A capacity row of a joint with both signs stays.
    fn choose_rows(&mut self, want: &mut [bool]) {
        let (n, a, r) = (self.sizes.n, self.sizes.a, self.rows);
        want.iter_mut().for_each(|w| *w = true);
        if !self.screen {
            self.elastic = true;
            self.live.iter_mut().for_each(|l| *l = true);
            return;
        }
        for i in self.screenable() {
            let norm = self.sub_a_dq[i * n..(i + 1) * n]
                .iter()
                .map(|v| v * v)
                .sum::<f64>()
                .sqrt();
            // a capacity row on a torque variable reaches as far as the torque does
            let torque_reach = match i.checked_sub(r.cap) {
                Some(k) if k < 2 * a && self.split[k % a] == Split::Both => {
                    let t = r.torque + k % a;
                    let d = self.sub_a_dq[t * n..(t + 1) * n]
                        .iter()
                        .map(|v| v * v)
                        .sum::<f64>()
                        .sqrt();
                    self.a(i, self.cols.s_plus + k).abs() * d
                }
                _ => 0.0,
            };
            want[i] = self.sticky[i] || self.sub_b[i] <= SCREEN_REACH * (norm + torque_reach);
        }
        for i in 0..a {
            want[r.torque + i] = self.split[i] == Split::Both;
        }
        self.set_live(want);
    }

    /// The live columns for the rows `want`, and the bound rows of the others left out.
    fn set_live(&mut self, want: &mut [bool]) {
        let (c, r, sz) = (self.cols, self.rows, self.sizes);
        for col in 0..c.n_var {
            let live = if col < c.s_plus {
                self.projected.as_ref().is_none_or(|p| col - c.dq < p.n_y)
            } else if col < c.e {
                self.split[(col - c.s_plus) % sz.a] == Split::Both
            } else if col < c.v_cap {
                self.elastic
            } else if col >= c.v_zone {
                want[r.zone + col - c.v_zone]
            } else {
                true
            };
            self.live[col] = live;
            if let Some(b) = self.bound_row(col) {
                want[b] = live;
            }
        }
        for i in r.eq..r.eq + sz.m {
            want[i] = self.projected.is_none();
        }
    }

    /// Sets the kept rows and their maps, and the solver problem's pattern when they changed;
    /// returns whether the structure changed (the solver must be built again).
    fn keep_rows(&mut self, want: &[bool]) -> bool {
        let changed = want != self.kept.as_slice()
            || self.live != self.built_for.1
            || self.split != self.built_for.2
            || self.projected.is_some() != self.built_for.3
            || self.built_for.0.is_empty();
        if !changed {
            return false;
        }
        self.kept.copy_from_slice(want);
        for i in self.screenable() {
            self.sticky[i] |= self.kept[i];
        }
        let n = self.sizes.n;
        let n_kept = index_among(&self.kept, &mut self.red_row);
        self.red_b.resize(n_kept, 0.0);
        let n_live = index_among(&self.live, &mut self.red_col);
        self.red_q.resize(n_live, 0.0);
        self.red_pat.clear();
        for col in (0..self.cols.n_var).filter(|&j| self.live[j]) {
            for row in (0..self.rows.n_row).filter(|&i| self.kept[i]) {
                let stored = self.slot[row * self.cols.n_var + col] != u32::MAX;
                if stored || (col < n && self.densified[row]) {
                    self.red_pat.push((row, col));
                }
            }
        }
        self.red_nz.resize(self.red_pat.len(), 0.0);
        self.red_p_pat.clear();
        for col in (0..self.cols.n_var).filter(|&j| self.live[j]) {
            if col < n {
                self.red_p_pat.extend((0..=col).map(|i| (i, col)));
            } else {
                self.red_p_pat.push((col, col));
            }
        }
        self.red_p_nz.resize(self.red_p_pat.len(), 0.0);
        self.built_for = (
            self.kept.clone(),
            self.live.clone(),
            self.split.clone(),
            self.projected.is_some(),
        );
        true
    }

    /// The solver problem's values from the substituted problem.
    fn gather(&mut self) {
        let n = self.sizes.n;
        for (v, &(r, c)) in self.red_nz.iter_mut().zip(&self.red_pat) {
            *v = if c < n {
                self.sub_a_dq[r * n + c]
            } else {
                self.a_nz[self.slot[r * self.cols.n_var + c] as usize]
            };
        }
        for (v, &(i, j)) in self.red_p_nz.iter_mut().zip(&self.red_p_pat) {
            *v = if j < n {
                self.sub_p_dq[i * n + j]
            } else {
                self.p_diag[j]
            };
        }
        for (i, &k) in self.kept.iter().enumerate() {
            if k {
                self.red_b[self.red_row[i]] = self.sub_b[i];
            }
        }
        for (j, &l) in self.live.iter().enumerate() {
            if l {
                self.red_q[self.red_col[j]] = self.sub_q[j];
            }
        }
    }

    fn csc(
        &self,
        pat: &[(usize, usize)],
        nz: &[f64],
        n_row: usize,
        rows: &[usize],
    ) -> CscMatrix<f64> {
        let n_col = self.red_q.len();
        let mut colptr = vec![0usize; n_col + 1];
        let mut rowval = Vec::with_capacity(pat.len());
        for &(r, c) in pat {
            colptr[self.red_col[c] + 1] += 1;
            rowval.push(rows[r]);
        }
        for c in 0..n_col {
            colptr[c + 1] += colptr[c];
        }
        CscMatrix::new(n_row, n_col, colptr, rowval, nz.to_vec())
    }

    /// The whole QP's x and z from the solver's solution: substituted torques `α + wᵀΔq`, zeroed
    /// columns 0; left-out rows' multipliers 0, but a substituted torque's split row's and a
    /// zeroed column's bound row's, which follow from the stationarity of that column.
    fn expand(&mut self, x: &[f64], z: &[f64]) {
        let n = self.sizes.n;
        for (j, xj) in self.x.iter_mut().enumerate() {
            *xj = match self.red_col[j] {
                usize::MAX => 0.0,
                c => x[c],
            };
        }
        for (i, zi) in self.z.iter_mut().enumerate() {
            *zi = match self.red_row[i] {
                usize::MAX => 0.0,
                r => z[r],
            };
        }
        if let Some(pj) = &self.projected {
            // Δq = Δq_p + Z y
            for k in 0..n {
                self.x[k] = pj.dq_p[k] + (0..pj.n_y).map(|c| pj.z[(k, c)] * x[c]).sum::<f64>();
            }
        }
        for i in 0..self.sizes.a {
            let Some((c, _)) = self.split_cols(i) else {
                continue;
            };
            let t = self.rows.torque + i;
            let at = self.a(t, c);
            let dot: f64 = (0..n).map(|k| self.a(t, k) * self.x[k]).sum();
            self.x[c] = (self.b[t] - dot) / at;
        }
        for i in 0..self.sizes.a {
            let Some((c, _)) = self.split_cols(i) else {
                continue;
            };
            let t = self.rows.torque + i;
            let at = self.a(t, c);
            let rest = self.p_diag[c] * self.x[c] + self.q[c] + self.col_dot(c, &self.z, t);
            self.z[t] = -rest / at;
        }
        if let Some(pj) = self.projected.take() {
            // the equality rows' multipliers: Jᵀ z_eq = −g, g the whole QP's posture
            // stationarity without them; least squares through Jᵀ = Q₁ R
            let eq = self.rows.eq..self.rows.eq + self.sizes.m;
            let mut g = nalgebra::DVector::<f64>::zeros(n);
            for k in 0..n {
                g[k] = (0..n)
                    .map(|j| self.p_dq[k * n + j] * self.x[j])
                    .sum::<f64>()
                    + self.q[k];
            }
            for (v, &(r, c)) in self.a_nz.iter().zip(&self.a_pattern) {
                if c < n && !eq.contains(&r) {
                    g[c] += v * self.z[r];
                }
            }
            let rhs = -(pj.q1.transpose() * g);
            if let Some(z_eq) = pj.r.solve_upper_triangular(&rhs) {
                for (i, &row) in pj.rows.iter().enumerate() {
                    self.z[row] = z_eq[i];
                }
            }
            self.projected = Some(pj);
        }
        for col in self.cols.s_plus..self.cols.n_var {
            if !self.live[col] && !self.is_substituted(col) {
                let b = self.bound_row(col).expect("a slack or torque column");
                // −x ≤ 0: q_c + Σ_{r ≠ b} A_rc z_r − z_b = 0 at x = 0
                self.z[b] = self.q[col] + self.col_dot(col, &self.z, b);
            }
        }
    }

    fn is_substituted(&self, col: usize) -> bool {
        let c = self.cols;
        if !(c.s_plus..c.e).contains(&col) {
            return false;
        }
        let i = (col - c.s_plus) % self.sizes.a;
        self.split_cols(i).is_some_and(|(s, _)| s == col)
    }

    /// Solves with the staged data; returns whether clarabel reports a (nearly) solved problem.
    ///
    /// The solver's problem is the whole QP reduced to what can matter, and its solution is
    /// checked against what was left out:
    /// * a joint whose torque keeps its sign has its torque substituted (`s⁺ = τ̄ + D Δq`,
    ///   `s⁻ = 0`, or the reverse), so that the problem's unknowns are the posture and the few
    ///   torques near zero; if the solution turns a substituted torque round, or the bound
    ///   holding its zeroed sign needs a negative multiplier, the joint gets both signs back;
    /// * the equality rows are hard until a solution's multiplier exceeds the slacks' ℓ1
    ///   penalty (or the hard rows cannot be met): then the slacks are set free;
    /// * the capacity, clearance, balance and zone rows a short step cannot reach are left out
    ///   (they are dense over the posture, and each one kept grows the factorisation of every
    ///   interior-point iteration); a row the solution violates is put back.
    ///
    /// Then the problem is solved again. A reduced solution that passes every check meets the
    /// whole QP's optimality conditions, with the multipliers recovered in [`Self::expand`].
    pub fn solve(&mut self) -> Result<bool, QpError> {
        let mut want = std::mem::take(&mut self.want);
        // the slacks stay free only while the targets conflict (the last solution used them);
        // a multiplier above the penalty is not kept: the SQP raises the penalty after a solve
        if self.screen && self.elastic {
            let c = self.cols;
            self.elastic = self.x[c.e..c.v_cap].iter().any(|v| v.abs() > SCREEN_TOL);
        }
        self.choose_splits();
        self.substitute();
        self.project();
        self.choose_rows(&mut want);
        let (mut xs, mut zs) = (Vec::new(), Vec::new());
        loop {
            if self.keep_rows(&want) {
                self.solver = None;
            }
            self.gather();
            match &mut self.solver {
                Some(s) => {
                    s.update_P(&self.red_p_nz)
                        .map_err(|e| QpError::Update(e.to_string()))?;
                    s.update_A(&self.red_nz)
                        .map_err(|e| QpError::Update(e.to_string()))?;
                    s.update_q(&self.red_q)
                        .map_err(|e| QpError::Update(e.to_string()))?;
                    s.update_b(&self.red_b)
                        .map_err(|e| QpError::Update(e.to_string()))?;
                }
                None => {
                    let n_kept = self.red_b.len();
                    let n_zero = (0..self.rows.n_zero).filter(|&i| self.kept[i]).count();
                    let cones: [SupportedConeT<f64>; 2] =
                        [ZeroConeT(n_zero), NonnegativeConeT(n_kept - n_zero)];
                    let p = self.csc(
                        &self.red_p_pat,
                        &self.red_p_nz,
                        self.red_q.len(),
                        &self.red_col,
                    );
                    let a = self.csc(&self.red_pat, &self.red_nz, n_kept, &self.red_row);
                    let s = DefaultSolver::new(
                        &p,
                        &self.red_q,
                        &a,
                        &self.red_b,
                        &cones,
                        self.settings.clone(),
                    )
                    .map_err(|e| QpError::Setup(e.to_string()))?;
                    self.solver = Some(s);
                }
            }
            let s = self.solver.as_mut().expect("solver built above");
            s.solve();
            self.solves += 1;
            self.ipm_iterations += u64::from(s.solution.iterations);
            let ok = matches!(
                s.solution.status,
                SolverStatus::Solved | SolverStatus::AlmostSolved
            );
            if !ok {
                if !self.elastic {
                    // the hard equality rows may be what cannot be met
                    self.elastic = true;
                    self.substitute();
                    self.project();
                    self.choose_rows(&mut want);
                    continue;
                }
                self.want = want;
                return Ok(false);
            }
            xs.clear();
            xs.extend_from_slice(&s.solution.x);
            zs.clear();
            zs.extend_from_slice(&s.solution.z);
            self.expand(&xs, &zs);
            if !self.screen || !self.recheck(&mut want) {
                self.want = want;
                return Ok(true);
            }
        }
    }

    /// Checks the expanded solution against what the solver's problem left out; marks what
    /// must go back in (rows in `want`, joints' both signs, the equality slacks) and returns
    /// whether anything must.
    fn recheck(&mut self, want: &mut [bool]) -> bool {
        let mut again = false;
        let mut ax = std::mem::take(&mut self.ax);
        self.a_times(&self.x, &mut ax);
        for i in self.screenable() {
            if !self.kept[i] && ax[i] - self.b[i] > SCREEN_TOL * (1.0 + self.b[i].abs()) {
                self.sticky[i] = true;
                again = true;
            }
        }
        self.ax = ax;
        for i in 0..self.sizes.a {
            let Some((c, d)) = self.split_cols(i) else {
                continue;
            };
            let t = self.rows.torque + i;
            let turned = self.x[c] < -SCREEN_TOL * (1.0 + self.b[t].abs());
            let zd = self.z[self.bound_row(d).expect("a torque column")];
            if turned || zd < -SCREEN_DUAL_TOL * (1.0 + self.q[d].abs()) {
                self.split[i] = Split::Both;
                again = true;
            }
        }
        if !self.elastic {
            let c = self.cols;
            for col in c.e..c.v_cap {
                let zb = self.z[self.bound_row(col).expect("a slack column")];
                if zb < -SCREEN_DUAL_TOL * (1.0 + self.q[col].abs()) {
                    self.elastic = true;
                    again = true;
                }
            }
        }
        if again {
            self.substitute();
            self.project();
            self.choose_rows(want);
        }
        again
    }

    /// `Px + q + Aᵀz` at `x` with the last duals (the QP's stationarity residual), into `out`.
    pub fn stationarity(&self, x: &[f64], out: &mut [f64]) {
        self.p_times(x, out);
        for (o, q) in out.iter_mut().zip(&self.q) {
            *o += q;
        }
        for (k, &(r, c)) in self.a_pattern.iter().enumerate() {
            out[c] += self.a_nz[k] * self.z[r];
        }
    }

    /// `(Aᵀ z)` restricted to the posture columns, into `out` (length n).
    pub fn at_z_posture(&self, z: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|o| *o = 0.0);
        for (k, &(r, c)) in self.a_pattern.iter().enumerate() {
            if c < self.sizes.n {
                out[c] += self.a_nz[k] * z[r];
            }
        }
    }

    /// `Ax` into `out` (length n_row).
    pub fn a_times(&self, x: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|o| *o = 0.0);
        for (k, &(r, c)) in self.a_pattern.iter().enumerate() {
            out[r] += self.a_nz[k] * x[c];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A QP over a two-joint step with two clearance rows: `min ½|Δq|² − 3 Δq₀ + 10³ v`, with
    /// `Δq₀ − v ≤ 1` and `Δq₁ − v ≤ 5` (`v ≥ 0`, the clearances' shared slack) and joint limits
    /// `Δq ≤ 10`. The first row is far from the start (slack 1, left out at first) but the
    /// unconstrained step (Δq₀ = 3) crosses it: the check must put it back, and the answer is
    /// the whole QP's, Δq = (1, 0) with the row's multiplier 2.
    fn qp(screen: bool) -> PostureQp {
        let sizes = QpSizes {
            n: 2,
            a: 0,
            m: 0,
            c: 0,
            k: 2,
            e: 0,
            z: 0,
        };
        let mut qp = PostureQp::new(sizes, QpPrecision::default(), &[]).unwrap();
        qp.screen = screen;
        let (r, c) = (qp.rows, qp.cols);
        qp.clear();
        qp.p_dq[0] = 1.0;
        qp.p_dq[3] = 1.0;
        qp.q[c.dq] = -3.0;
        qp.q[c.v_cap] = 1e3;
        qp.q[c.v_geo] = 1e3;
        qp.set_a(r.nonneg, c.v_cap, -1.0);
        qp.set_a(r.nonneg + 1, c.v_geo, -1.0);
        for j in 0..2 {
            qp.set_a(r.limit + j, c.dq + j, 1.0);
            qp.b[r.limit + j] = 10.0;
            qp.set_a(r.clearance + j, c.dq + j, 1.0);
            qp.set_a(r.clearance + j, c.v_geo, -1.0);
        }
        qp.b[r.clearance] = 1.0;
        qp.b[r.clearance + 1] = 5.0;
        qp
    }

    #[test]
    fn rows_left_out_are_put_back_when_the_step_crosses_them() {
        let (mut whole, mut screened) = (qp(false), qp(true));
        assert!(whole.solve().unwrap() && screened.solve().unwrap());
        let c = whole.cols;
        for x in [&whole.x, &screened.x] {
            assert!(
                (x[c.dq] - 1.0).abs() < 1e-6 && x[c.dq + 1].abs() < 1e-6,
                "{x:?}"
            );
        }
        let r = whole.rows.clearance;
        for z in [&whole.z, &screened.z] {
            assert!((z[r] - 2.0).abs() < 1e-6 && z[r + 1].abs() < 1e-6, "{z:?}");
        }
        // the screened QP left both clearance rows out, then solved again with the first back
        assert_eq!((whole.solves, screened.solves), (1, 2));
        assert!(screened.kept[r] && !screened.kept[r + 1]);
        // the next QP keeps the row put back, and needs one solve
        assert!(screened.solve().unwrap());
        assert_eq!(screened.solves, 3);
    }

    /// A cleared QP over a two-joint step with `sizes` (`n` = 2), P's posture block the
    /// identity and both joints' limit rows `Δq ≤ 10`.
    fn unit_qp(screen: bool, a: usize, m: usize, c: usize) -> PostureQp {
        let sizes = QpSizes {
            n: 2,
            a,
            m,
            c,
            k: 0,
            e: 0,
            z: 0,
        };
        let mut qp = PostureQp::new(sizes, QpPrecision::default(), &[]).unwrap();
        qp.screen = screen;
        qp.forget_solver();
        qp.clear();
        qp.p_dq[0] = 1.0;
        qp.p_dq[3] = 1.0;
        for j in 0..2 {
            qp.set_a(qp.rows.limit + j, qp.cols.dq + j, 1.0);
            qp.b[qp.rows.limit + j] = 10.0;
        }
        qp
    }

    /// Every row's multiplier of the reduced QP (recovered where the solver had no row) is the
    /// whole QP's.
    fn same_multipliers(whole: &PostureQp, reduced: &PostureQp, what: &str) {
        for i in 0..whole.rows.n_row {
            assert!(
                (whole.z[i] - reduced.z[i]).abs() < 1e-5,
                "{what}: z[{i}] {} {}",
                whole.z[i],
                reduced.z[i]
            );
        }
    }

    /// A QP with one joint whose torque is `τ = 1 + Δq₀` and one target row `Δq₁ = ½`:
    /// `min ½|Δq|² + g (s⁺ + s⁻) + μ (e⁺ + e⁻)` (the slacks' quadratic penalty negligible).
    /// Closed forms: for `g < 1` the torque keeps its sign, `Δq₀ = −g`; for `g ≥ 1` it ends
    /// at zero, `Δq₀ = −1`; for `μ ≥ ½` the target is met, `Δq₁ = ½`; below, `Δq₁ = μ`.
    fn split_qp(screen: bool, g: f64, mu: f64) -> PostureQp {
        let mut qp = unit_qp(screen, 1, 1, 2);
        let (r, c) = (qp.rows, qp.cols);
        qp.set_a(r.torque, c.dq, 1.0);
        qp.set_a(r.torque, c.s_plus, -1.0);
        qp.set_a(r.torque, c.s_minus, 1.0);
        qp.b[r.torque] = -1.0;
        qp.set_a(r.eq, c.dq + 1, 1.0);
        qp.set_a(r.eq, c.e, 1.0);
        qp.set_a(r.eq, c.e + 1, -1.0);
        qp.b[r.eq] = 0.5;
        for (i, col) in [c.s_plus, c.s_minus, c.v_cap, c.v_geo, c.e, c.e + 1]
            .into_iter()
            .enumerate()
        {
            let row = [r.nonneg, r.nonneg + 1, r.nonneg + 2, r.nonneg + 3][..]
                .get(i)
                .copied()
                .unwrap_or(r.nonneg + 4 + (i - 4));
            qp.set_a(row, col, -1.0);
        }
        qp.q[c.s_plus] = g;
        qp.q[c.s_minus] = g;
        qp.q[c.e] = mu;
        qp.q[c.e + 1] = mu;
        qp.p_diag[c.e] = 1e-9;
        qp.p_diag[c.e + 1] = 1e-9;
        qp.q[c.v_cap] = 1e3;
        qp.q[c.v_geo] = 1e3;
        qp.p_diag[c.v_cap] = 1e-6;
        qp.p_diag[c.v_geo] = 1e-6;
        for j in 0..2 {
            qp.set_a(r.cap + j, [c.s_plus, c.s_minus][j], 1.0);
            qp.set_a(r.cap + j, c.v_cap, -1.0);
            qp.b[r.cap + j] = 1e3;
        }
        qp
    }

    #[test]
    fn the_reduced_qp_has_the_whole_qps_solution_and_multipliers() {
        // (g, μ, Δq₀, Δq₁, solves of the reduced QP)
        for (g, mu, dq0, dq1, solves) in [
            (0.3, 1.0, -0.3, 0.5, 1), // sign kept, target met: one solve
            (2.0, 1.0, -1.0, 0.5, 2), // the substituted torque turns round: both signs back
            (0.3, 0.1, -0.3, 0.1, 2), // the target's multiplier exceeds μ: slacks set free
        ] {
            let (mut whole, mut reduced) = (split_qp(false, g, mu), split_qp(true, g, mu));
            assert!(whole.solve().unwrap() && reduced.solve().unwrap());
            let c = whole.cols;
            for x in [&whole.x, &reduced.x] {
                assert!(
                    (x[c.dq] - dq0).abs() < 1e-6 && (x[c.dq + 1] - dq1).abs() < 1e-6,
                    "g {g}, μ {mu}: {x:?}"
                );
            }
            for (a, b) in whole.x.iter().zip(&reduced.x) {
                assert!(
                    (a - b).abs() < 1e-6,
                    "g {g}, μ {mu}: x {:?} {:?}",
                    whole.x,
                    reduced.x
                );
            }
            same_multipliers(&whole, &reduced, &format!("g {g}, μ {mu}"));
            assert_eq!((whole.solves, reduced.solves), (1, solves), "g {g}, μ {mu}");
        }
    }

    /// An equality row without posture entries reads `0 = b`: with `b = 0` the null-space
    /// step leaves it out; with `b ≠ 0` it cannot be met and the slacks take it (at the
    /// penalty `μ`), the posture step unchanged. Both against the whole QP.
    #[test]
    fn an_empty_equality_row_is_skipped_or_taken_by_its_slacks() {
        for b in [0.0, 0.3] {
            let build = |screen: bool| {
                let mut qp = unit_qp(screen, 0, 2, 0);
                let (r, c) = (qp.rows, qp.cols);
                qp.q[c.dq] = -1.0;
                qp.set_a(r.eq, c.dq + 1, 1.0);
                qp.b[r.eq] = 0.5;
                qp.b[r.eq + 1] = b;
                for i in 0..2 {
                    qp.set_a(r.eq + i, c.e + i, 1.0);
                    qp.set_a(r.eq + i, c.e + 2 + i, -1.0);
                }
                for (k, col) in [c.v_cap, c.v_geo, c.e, c.e + 1, c.e + 2, c.e + 3]
                    .into_iter()
                    .enumerate()
                {
                    qp.set_a(r.nonneg + k, col, -1.0);
                    qp.q[col] = 1.0;
                    qp.p_diag[col] = 1e-9;
                }
                qp
            };
            let (mut whole, mut reduced) = (build(false), build(true));
            assert!(whole.solve().unwrap() && reduced.solve().unwrap());
            let c = whole.cols;
            for x in [&whole.x, &reduced.x] {
                assert!((x[c.dq] - 1.0).abs() < 1e-6 && (x[c.dq + 1] - 0.5).abs() < 1e-6);
                assert!((x[c.e + 1] - x[c.e + 3] - b).abs() < 1e-6, "b {b}: {x:?}");
            }
            same_multipliers(&whole, &reduced, &format!("b {b}"));
        }
    }
}
