//! The posture QP, on a fixed sparsity pattern, solved by clarabel (the crate's only clarabel
//! user). The solver is built once per pattern and its data updated in place between SQP
//! iterations (presolve off).
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
    /// The last solution: primal x and dual z (clarabel's `Px + q + Aᵀz = 0`).
    pub x: Vec<f64>,
    pub z: Vec<f64>,
    /// QP solves and interior-point iterations so far.
    pub solves: u64,
    pub ipm_iterations: u64,
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

    fn csc_a(&self) -> CscMatrix<f64> {
        let mut colptr = vec![0usize; self.cols.n_var + 1];
        let mut rowval = Vec::with_capacity(self.a_pattern.len());
        for &(row, col) in &self.a_pattern {
            colptr[col + 1] += 1;
            rowval.push(row);
        }
        for c in 0..self.cols.n_var {
            colptr[c + 1] += colptr[c];
        }
        CscMatrix::new(
            self.rows.n_row,
            self.cols.n_var,
            colptr,
            rowval,
            self.a_nz.clone(),
        )
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

    /// Solves with the staged data; returns whether clarabel reports a (nearly) solved problem.
    pub fn solve(&mut self) -> Result<bool, QpError> {
        self.gather_p();
        match &mut self.solver {
            Some(s) => {
                s.update_P(&self.p_nz)
                    .map_err(|e| QpError::Update(e.to_string()))?;
                s.update_A(&self.a_nz)
                    .map_err(|e| QpError::Update(e.to_string()))?;
                s.update_q(&self.q)
                    .map_err(|e| QpError::Update(e.to_string()))?;
                s.update_b(&self.b)
                    .map_err(|e| QpError::Update(e.to_string()))?;
            }
            None => {
                let cones: [SupportedConeT<f64>; 2] = [
                    ZeroConeT(self.rows.n_zero),
                    NonnegativeConeT(self.rows.n_row - self.rows.n_zero),
                ];
                let s = DefaultSolver::new(
                    &self.csc_p(),
                    &self.q,
                    &self.csc_a(),
                    &self.b,
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
        if ok {
            self.x.copy_from_slice(&s.solution.x);
            self.z.copy_from_slice(&s.solution.z);
        }
        Ok(ok)
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
