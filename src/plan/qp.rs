//! The posture QP, on a fixed sparsity pattern, solved by clarabel (the crate's only clarabel
//! user). The solver is built at the first QP of each local solve and its data updated in place
//! between that solve's SQP iterations (presolve off). It is built afresh for every local solve
//! ([`PostureQp::forget_solver`]) because clarabel's data updates keep the equilibration of the
//! QP the solver was built with: a reused solver made each solve depend on the solves before it
//! (so on the order of the multi-start's seeds, and on which thread ran them). The clearance,
//! balance and zone rows a short step cannot reach are left out of the solver's problem and the
//! solution checked against them ([`PostureQp::solve`]); the solver is also rebuilt when a row
//! is put back.
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
    p_nz: Vec<f64>,
    p_colptr: Vec<usize>,
    p_rowval: Vec<usize>,
    pub q: Vec<f64>,
    solver: Option<DefaultSolver<f64>>,
    settings: DefaultSettings<f64>,
    /// Rows given to the solver (the others are inactive rows left out: [`Self::solve`]), and
    /// each row's index among them (`usize::MAX`: left out).
    kept: Vec<bool>,
    red_row: Vec<usize>,
    /// The kept rows' entries of A (indices into `a_nz`, in column order) and their values, and
    /// the kept rows' right-hand sides.
    red_idx: Vec<usize>,
    red_nz: Vec<f64>,
    red_b: Vec<f64>,
    /// Scratch: each row's norm over the posture columns, and `Ax`.
    row_norm: Vec<f64>,
    ax: Vec<f64>,
    want: Vec<bool>,
    /// Whether inactive rows are left out (on by default; off solves every QP whole).
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
            p_nz: Vec::new(),
            p_colptr: Vec::new(),
            p_rowval: Vec::new(),
            q: vec![0.0; cols.n_var],
            solver: None,
            settings,
            kept: vec![true; rows.n_row],
            red_row: (0..rows.n_row).collect(),
            red_idx: Vec::new(),
            red_nz: Vec::new(),
            red_b: Vec::new(),
            row_norm: vec![0.0; rows.n_row],
            ax: vec![0.0; rows.n_row],
            want: vec![true; rows.n_row],
            screen: true,
            x: vec![0.0; cols.n_var],
            z: vec![0.0; rows.n_row],
            solves: 0,
            ipm_iterations: 0,
        };
        // P's pattern: column j of the posture block holds rows 0..=j; other columns their diagonal.
        let mut colptr = vec![0usize];
        let mut rowval = Vec::new();
        for j in 0..cols.n_var {
            if j < sizes.n {
                rowval.extend(0..=j);
            } else {
                rowval.push(j);
            }
            colptr.push(rowval.len());
        }
        qp.p_nz = vec![0.0; rowval.len()];
        qp.p_colptr = colptr;
        qp.p_rowval = rowval;
        qp.forget_solver();
        Ok(qp)
    }

    /// Gathers P's stored values from `p_dq` and `p_diag`.
    fn gather_p(&mut self) {
        let n = self.sizes.n;
        for j in 0..self.cols.n_var {
            for k in self.p_colptr[j]..self.p_colptr[j + 1] {
                let i = self.p_rowval[k];
                self.p_nz[k] = if j < n {
                    self.p_dq[i * n + j]
                } else {
                    self.p_diag[j]
                };
            }
        }
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

    fn csc_p(&self) -> CscMatrix<f64> {
        let n = self.cols.n_var;
        CscMatrix::new(
            n,
            n,
            self.p_colptr.clone(),
            self.p_rowval.clone(),
            self.p_nz.clone(),
        )
    }

    /// A restricted to the kept rows (values from `red_nz`).
    fn csc_a_kept(&self) -> CscMatrix<f64> {
        let n_kept = self.red_b.len();
        let mut colptr = vec![0usize; self.cols.n_var + 1];
        let mut rowval = Vec::with_capacity(self.red_idx.len());
        for &k in &self.red_idx {
            let (row, col) = self.a_pattern[k];
            colptr[col + 1] += 1;
            rowval.push(self.red_row[row]);
        }
        for c in 0..self.cols.n_var {
            colptr[c + 1] += colptr[c];
        }
        CscMatrix::new(n_kept, self.cols.n_var, colptr, rowval, self.red_nz.clone())
    }

    /// Drops the solver and the rows kept so far: the next [`Self::solve`] builds it from its
    /// own data, so that its scaling and rows (and so its answer) do not depend on earlier QPs.
    pub fn forget_solver(&mut self) {
        self.solver = None;
        let r = self.screenable();
        self.kept[r].iter_mut().for_each(|k| *k = false);
    }

    /// The rows that may be left out: clearances, balance and posture zones (the dense rows
    /// over the posture; the equalities, bounds, joint limits and capacity rows always stay).
    fn screenable(&self) -> std::ops::Range<usize> {
        self.rows.clearance..self.rows.n_row
    }

    /// Chooses the rows to give the solver: every row but the screenable ones that a short step
    /// cannot reach — a row `A_i x ≤ b_i` whose slack at `x = 0` exceeds [`SCREEN_REACH`] times
    /// its norm over the posture columns — and that no earlier QP of this local solve needed
    /// (a row once given stays until [`Self::forget_solver`]: fewer re-solves and rebuilds).
    fn choose_rows(&mut self, want: &mut [bool]) {
        want.iter_mut().for_each(|w| *w = true);
        if !self.screen {
            return;
        }
        let n = self.sizes.n;
        self.row_norm.iter_mut().for_each(|x| *x = 0.0);
        for (k, &(r, c)) in self.a_pattern.iter().enumerate() {
            if c < n {
                self.row_norm[r] += self.a_nz[k] * self.a_nz[k];
            }
        }
        for i in self.screenable() {
            let reach = SCREEN_REACH * self.row_norm[i].sqrt();
            want[i] = self.kept[i] || self.b[i] <= reach;
        }
    }

    /// Sets the kept rows and their maps; returns whether they changed.
    fn keep_rows(&mut self, want: &[bool]) -> bool {
        let changed = want != self.kept.as_slice();
        if changed || self.red_b.len() != self.kept.iter().filter(|&&k| k).count() {
            self.kept.copy_from_slice(want);
            let mut next = 0;
            for (i, &k) in self.kept.iter().enumerate() {
                self.red_row[i] = if k {
                    next += 1;
                    next - 1
                } else {
                    usize::MAX
                };
            }
            self.red_idx.clear();
            for (k, &(r, _)) in self.a_pattern.iter().enumerate() {
                if self.kept[r] {
                    self.red_idx.push(k);
                }
            }
            self.red_nz.resize(self.red_idx.len(), 0.0);
            self.red_b.resize(next, 0.0);
        }
        changed
    }

    /// Solves with the staged data; returns whether clarabel reports a (nearly) solved problem.
    ///
    /// Rows that cannot be active are left out of the solver's problem (the clearance, balance
    /// and zone rows are dense over the posture, and each one kept grows the factorisation of
    /// every interior-point iteration); the solution is then checked against every row left out,
    /// and any it violates is put back and the QP solved again. The reduced QP is a relaxation
    /// of the whole one, so a solution of it that meets every row is the whole QP's solution.
    pub fn solve(&mut self) -> Result<bool, QpError> {
        self.gather_p();
        let mut want = std::mem::take(&mut self.want);
        self.choose_rows(&mut want);
        loop {
            let changed = self.keep_rows(&want);
            for (j, &k) in self.red_idx.iter().enumerate() {
                self.red_nz[j] = self.a_nz[k];
            }
            for (i, &k) in self.kept.iter().enumerate() {
                if k {
                    self.red_b[self.red_row[i]] = self.b[i];
                }
            }
            if changed {
                self.solver = None;
            }
            match &mut self.solver {
                Some(s) => {
                    s.update_P(&self.p_nz)
                        .map_err(|e| QpError::Update(e.to_string()))?;
                    s.update_A(&self.red_nz)
                        .map_err(|e| QpError::Update(e.to_string()))?;
                    s.update_q(&self.q)
                        .map_err(|e| QpError::Update(e.to_string()))?;
                    s.update_b(&self.red_b)
                        .map_err(|e| QpError::Update(e.to_string()))?;
                }
                None => {
                    let n_kept = self.red_b.len();
                    let cones: [SupportedConeT<f64>; 2] = [
                        ZeroConeT(self.rows.n_zero),
                        NonnegativeConeT(n_kept - self.rows.n_zero),
                    ];
                    let s = DefaultSolver::new(
                        &self.csc_p(),
                        &self.q,
                        &self.csc_a_kept(),
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
                self.want = want;
                return Ok(false);
            }
            self.x.copy_from_slice(&s.solution.x);
            for (i, zi) in self.z.iter_mut().enumerate() {
                *zi = match self.red_row[i] {
                    usize::MAX => 0.0,
                    r => s.solution.z[r],
                };
            }
            // every row left out must hold at the solution
            let mut ax = std::mem::take(&mut self.ax);
            self.a_times(&self.x, &mut ax);
            let mut violated = false;
            for i in self.screenable() {
                if !self.kept[i] && ax[i] - self.b[i] > SCREEN_TOL * (1.0 + self.b[i].abs()) {
                    want[i] = true;
                    violated = true;
                }
            }
            self.ax = ax;
            if !violated {
                self.want = want;
                return Ok(true);
            }
        }
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
}
