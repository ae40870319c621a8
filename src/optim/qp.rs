//! The per-phase QP, assembled on a fixed sparsity pattern and solved by clarabel. The solver is
//! built once per pattern and its data updated in place between SQP iterations (presolve off).
//!
//! Variables `x = [Δq (n), s⁺ (n), s⁻ (n), e (3), v]`: posture step, split torques
//! (`τ̄ + D Δq = s⁺ − s⁻`, so each half-joint load `s±/MVC±` is linear and its sign is chosen
//! by the solver), hand-target slack `e`, capacity slack `v`. Rows: torque split (n, =),
//! target (3, =), `s⁺, s⁻, v ≥ 0`, step bounds (joint limits ∩ trust region), capacity
//! `s±/MVC± − v ≤ c±`, and `K` collision rows `−nᵀ J_c Δq ≤ d − d_min`.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    SupportedConeT, ZeroConeT,
};

/// Why a QP could not be set up or solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QpError {
    #[error("QP setup failed: {0}")]
    Setup(String),
    #[error("QP data update failed: {0}")]
    Update(String),
}

/// Dense staging of the QP data; `solve` gathers it into the sparse pattern.
pub struct PhaseQp {
    pub n: usize,
    pub k_collision: usize,
    pub n_var: usize,
    pub n_row: usize,
    /// Dense A (row-major, n_row × n_var), b, diagonal of P, q.
    pub a: Vec<f64>,
    pub b: Vec<f64>,
    pub p_diag: Vec<f64>,
    pub q: Vec<f64>,
    /// (row, col) of each stored nonzero of A, in CSC order.
    a_pattern: Vec<(usize, usize)>,
    a_nz: Vec<f64>,
    p_nz: Vec<f64>,
    solver: Option<DefaultSolver<f64>>,
    /// The last solution.
    pub x: Vec<f64>,
    /// QP solves and interior-point iterations so far.
    pub solves: u64,
    pub ipm_iterations: u64,
}

/// Row offsets of each block.
#[derive(Debug, Clone, Copy)]
pub struct Rows {
    pub torque: usize,
    pub target: usize,
    pub s_plus_nonneg: usize,
    pub s_minus_nonneg: usize,
    pub v_nonneg: usize,
    pub step_upper: usize,
    pub step_lower: usize,
    pub cap_plus: usize,
    pub cap_minus: usize,
    pub collision: usize,
}

/// Column offsets.
#[derive(Debug, Clone, Copy)]
pub struct Cols {
    pub dq: usize,
    pub s_plus: usize,
    pub s_minus: usize,
    pub e: usize,
    pub v: usize,
}

impl PhaseQp {
    pub fn rows(&self) -> Rows {
        let n = self.n;
        Rows {
            torque: 0,
            target: n,
            s_plus_nonneg: n + 3,
            s_minus_nonneg: 2 * n + 3,
            v_nonneg: 3 * n + 3,
            step_upper: 3 * n + 4,
            step_lower: 4 * n + 4,
            cap_plus: 5 * n + 4,
            cap_minus: 6 * n + 4,
            collision: 7 * n + 4,
        }
    }

    pub fn cols(&self) -> Cols {
        let n = self.n;
        Cols {
            dq: 0,
            s_plus: n,
            s_minus: 2 * n,
            e: 3 * n,
            v: 3 * n + 3,
        }
    }

    /// A QP for `n` joints with room for `k_collision` collision rows.
    pub fn new(n: usize, k_collision: usize) -> Self {
        let n_var = 3 * n + 4;
        let n_row = 7 * n + 4 + k_collision;
        let mut qp = PhaseQp {
            n,
            k_collision,
            n_var,
            n_row,
            a: vec![0.0; n_row * n_var],
            b: vec![0.0; n_row],
            p_diag: vec![0.0; n_var],
            q: vec![0.0; n_var],
            a_pattern: Vec::new(),
            a_nz: Vec::new(),
            p_nz: vec![0.0; n_var],
            solver: None,
            x: vec![0.0; n_var],
            solves: 0,
            ipm_iterations: 0,
        };
        let (r, c) = (qp.rows(), qp.cols());
        let mut pat: Vec<(usize, usize)> = Vec::new();
        for i in 0..n {
            let col = c.dq + i;
            for row in 0..n {
                pat.push((r.torque + row, col));
            }
            for k in 0..3 {
                pat.push((r.target + k, col));
            }
            pat.push((r.step_upper + i, col));
            pat.push((r.step_lower + i, col));
            for k in 0..k_collision {
                pat.push((r.collision + k, col));
            }
        }
        for i in 0..n {
            pat.push((r.torque + i, c.s_plus + i));
            pat.push((r.s_plus_nonneg + i, c.s_plus + i));
            pat.push((r.cap_plus + i, c.s_plus + i));
        }
        for i in 0..n {
            pat.push((r.torque + i, c.s_minus + i));
            pat.push((r.s_minus_nonneg + i, c.s_minus + i));
            pat.push((r.cap_minus + i, c.s_minus + i));
        }
        for k in 0..3 {
            pat.push((r.target + k, c.e + k));
        }
        pat.push((r.v_nonneg, c.v));
        for i in 0..n {
            pat.push((r.cap_plus + i, c.v));
        }
        for i in 0..n {
            pat.push((r.cap_minus + i, c.v));
        }
        pat.sort_by_key(|&(row, col)| (col, row));
        qp.a_nz = vec![0.0; pat.len()];
        qp.a_pattern = pat;
        qp
    }

    /// Clears A (dense staging) before a fill.
    pub fn clear_a(&mut self) {
        self.a.iter_mut().for_each(|x| *x = 0.0);
    }

    #[inline]
    pub fn set_a(&mut self, row: usize, col: usize, v: f64) {
        self.a[row * self.n_var + col] = v;
    }

    fn csc_a(&self) -> CscMatrix<f64> {
        let mut colptr = vec![0usize; self.n_var + 1];
        let mut rowval = Vec::with_capacity(self.a_pattern.len());
        for &(row, col) in &self.a_pattern {
            colptr[col + 1] += 1;
            rowval.push(row);
        }
        for c in 0..self.n_var {
            colptr[c + 1] += colptr[c];
        }
        CscMatrix::new(self.n_row, self.n_var, colptr, rowval, self.a_nz.clone())
    }

    fn csc_p(&self) -> CscMatrix<f64> {
        CscMatrix::new(
            self.n_var,
            self.n_var,
            (0..=self.n_var).collect(),
            (0..self.n_var).collect(),
            self.p_nz.clone(),
        )
    }

    /// Solves with the staged data; returns whether clarabel reports a (nearly) solved problem.
    pub fn solve(&mut self) -> Result<bool, QpError> {
        for (nz, &(row, col)) in self.a_nz.iter_mut().zip(&self.a_pattern) {
            *nz = self.a[row * self.n_var + col];
        }
        self.p_nz.copy_from_slice(&self.p_diag);
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
                let settings = DefaultSettingsBuilder::default()
                    .verbose(false)
                    .presolve_enable(false)
                    .max_iter(200)
                    .tol_gap_abs(1e-6)
                    .tol_gap_rel(1e-6)
                    .tol_feas(1e-6)
                    .build()
                    .map_err(|e| QpError::Setup(e.to_string()))?;
                let n_eq = self.n + 3;
                let cones: [SupportedConeT<f64>; 2] =
                    [ZeroConeT(n_eq), NonnegativeConeT(self.n_row - n_eq)];
                let s = DefaultSolver::new(
                    &self.csc_p(),
                    &self.q,
                    &self.csc_a(),
                    &self.b,
                    &cones,
                    settings,
                )
                .map_err(|e| QpError::Setup(e.to_string()))?;
                self.solver = Some(s);
            }
        }
        let s = self.solver.as_mut().expect("solver built above");
        s.solve();
        self.solves += 1;
        let ok = matches!(
            s.solution.status,
            SolverStatus::Solved | SolverStatus::AlmostSolved
        );
        if ok {
            self.x.copy_from_slice(&s.solution.x);
        }
        self.ipm_iterations += u64::from(s.solution.iterations);
        Ok(ok)
    }
}
