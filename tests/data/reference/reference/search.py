"""Multi-start search for the fatigue-only optimum."""
import time
import warnings

import numpy as np
from scipy.optimize import minimize

from . import model as M
from .nlp import JointNLP, PhaseModel

warnings.filterwarnings("ignore", message="Values in x were outside bounds")

# called at every IPOPT iteration (optimise.py sets it to its time-based checkpoint: every
# computation re-runs its own forward kinematics, so a checkpoint between iterations is safe)
PROGRESS_HOOK = None


def _progress(*_):
    if PROGRESS_HOOK is not None:
        PROGRESS_HOOK()


# ----------------------------------------------------------------------------------------------
# seed templates
# ----------------------------------------------------------------------------------------------
def template(body, rest_q, kind, rng=None):
    """A (not yet feasible) posture template. kind is a dict of joint offsets/values."""
    q = rest_q.copy()
    for name, val in kind.items():
        if name.startswith("*"):      # both sides
            for s in ("r_", "l_"):
                q[body.qidx[s + name[1:]]] = val
        else:
            q[body.qidx[name]] = val
    if rng is not None:
        act = body.act_idx
        span = (body.upper - body.lower)[act]
        q[act] += rng.normal(0, 0.12, len(act)) * np.minimum(span, 2.0)
        q[body.qidx["pelvis_rotation"]] += rng.normal(0, 0.15)
        q[body.qidx["pelvis_tilt"]] += rng.normal(0, 0.15)
    return np.clip(q, body.lower, body.upper)


FAMILIES = {
    "upright": {},
    "upright_elbows_high": {"*elbow_flexion": 1.6, "*shoulder_flexion": 0.3},
    "upright_arms_abducted": {"*shoulder_abduction": 0.6, "*elbow_flexion": 1.0},
    "upright_internal_rot": {"*shoulder_rotation": 0.8, "*elbow_flexion": 1.2},
    "upright_external_rot": {"*shoulder_rotation": -0.6, "*elbow_flexion": 1.2},
    "pronated": {"*forearm_pronation": 1.0, "*elbow_flexion": 1.0},
    "supinated": {"*forearm_pronation": -1.0, "*elbow_flexion": 1.0},
    "stoop_mild": {"lumbar_flexion": 0.3, "pelvis_tilt": 0.3, "*hip_flexion": 0.3},
    "stoop": {"lumbar_flexion": 0.6, "pelvis_tilt": 0.6, "*hip_flexion": 0.6, "*knee_flexion": 0.05},
    "stoop_deep": {"lumbar_flexion": 0.9, "pelvis_tilt": 1.0, "*hip_flexion": 1.0},
    "semi_squat": {"pelvis_tz": -0.12, "*hip_flexion": 0.7, "*knee_flexion": 0.9,
                   "*ankle_dorsiflexion": 0.25, "pelvis_tilt": 0.3, "lumbar_flexion": 0.2},
    "squat": {"pelvis_tz": -0.35, "*hip_flexion": 1.4, "*knee_flexion": 1.9,
              "*ankle_dorsiflexion": 0.3, "pelvis_tilt": 0.6, "lumbar_flexion": 0.3},
    "lean_back": {"lumbar_flexion": -0.2, "pelvis_tilt": -0.1},
    "twist_left": {"lumbar_axial_rotation": 0.5, "pelvis_rotation": 0.3},
    "twist_right": {"lumbar_axial_rotation": -0.5, "pelvis_rotation": -0.3},
    "bend_left": {"lumbar_lateral_bending": 0.3},
    "bend_right": {"lumbar_lateral_bending": -0.3},
    "pelvis_fwd": {"pelvis_tx": 0.05, "*ankle_dorsiflexion": 0.2},
    "pelvis_back": {"pelvis_tx": -0.12, "pelvis_tilt": 0.4, "lumbar_flexion": 0.3,
                    "*knee_flexion": 0.3},
    "wrists_flexed": {"*wrist_flexion": 0.8, "*elbow_flexion": 1.0},
    "wrists_extended": {"*wrist_flexion": -0.8, "*elbow_flexion": 1.0},
    "overhead": {"*shoulder_flexion": 1.6, "*elbow_flexion": 0.6},
}


def seed_list(n_random=12, offset=0):
    """Deterministic list of (name, family, random seed or None)."""
    out = [(name, fam, None) for name, fam in FAMILIES.items()]
    names = list(FAMILIES)
    for i in range(offset, offset + n_random):
        fam = names[(7 * i) % len(names)]
        out.append((f"{fam}+rand{i}", FAMILIES[fam], 1000 + i))
    return out


# ----------------------------------------------------------------------------------------------
# projection of a template onto the constraints
# ----------------------------------------------------------------------------------------------
def project(pm, q_seed, maxiter=200):
    """Closest posture to q_seed (weighted) satisfying hand, feet, clearance and balance."""
    b = pm.body
    w = np.ones(b.nq)
    w[b.unact_idx] = 0.3
    f0 = np.zeros(b.H)

    def obj(q):
        d = q - q_seed
        return 0.5 * float(d @ (w * d)), w * d

    ne = 3 * len(pm.hands) + 12

    cons = [
        {"type": "eq", "fun": lambda q: pm.eq(q, f0)[:ne],
         "jac": lambda q: pm.eq(q, f0, jac=True)[1][:ne]},
        {"type": "ineq", "fun": lambda q: pm.ineq(q), "jac": lambda q: pm.ineq(q, jac=True)[1]},
    ]
    res = minimize(obj, q_seed, jac=True, method="SLSQP", constraints=cons,
                   bounds=list(zip(b.lower, b.upper)), options={"maxiter": maxiter, "ftol": 1e-10})
    q = np.clip(res.x, b.lower, b.upper)
    return q


# ----------------------------------------------------------------------------------------------
# local solve
# ----------------------------------------------------------------------------------------------
def _merit(nlp, x):
    """What a local solve's candidates are ranked by: the total U, or with zones the objective
    ln(U + 1e-3) + 10 sum v (its penalty over the optimised phases only)."""
    if getattr(nlp, "zones", False):
        return nlp.obj_value(x)
    return nlp.total_u(x)


def violation(nlp, x):
    """Largest constraint violation over ALL constraints (every clearance pair)."""
    e = nlp.eq(x)
    i = nlp.ineq(x)
    qs, _ = nlp.split(x)
    full = min(nlp.pm[gi].min_clearance_slack(qs[k]) for k, gi in enumerate(nlp.groups))
    return max(float(np.max(np.abs(e))) if len(e) else 0.0, float(max(0.0, -np.min(i))),
               max(0.0, -full))


def set_active(nlp, x, threshold):
    qs, _ = nlp.split(x)
    for k, gi in enumerate(nlp.groups):
        nlp.pm[gi].set_active(qs[k], threshold)


def add_active(nlp, x, threshold):
    qs, _ = nlp.split(x)
    changed = False
    for k, gi in enumerate(nlp.groups):
        changed |= nlp.pm[gi].add_active(qs[k], threshold)
    return changed


def solve(nlp, x0, maxiter=400, rounds=4, ftol=1e-10, log=None, threshold=0.08):
    """SLSQP on the pairs within `threshold` of their clearance, re-run with more pairs if a
    left-out pair ends violated, and restarted with a rescaled objective until it stops
    improving."""
    bounds = nlp.bounds()
    lo = np.array([a for a, _ in bounds])
    hi = np.array([b for _, b in bounds])
    x = np.clip(x0, lo, hi)
    set_active(nlp, x, threshold)
    best = None
    nit = 0
    r = 0
    while r < rounds:
        cons = [{"type": "eq", "fun": nlp.eq, "jac": nlp.eq_jac},
                {"type": "ineq", "fun": nlp.ineq, "jac": nlp.ineq_jac}]
        res = minimize(nlp.obj_value, x, jac=nlp.obj_grad, method="SLSQP", constraints=cons, bounds=bounds,
                       options={"maxiter": maxiter, "ftol": ftol}, callback=_progress)
        nit += res.nit
        xn = np.clip(res.x, lo, hi)
        fn = _merit(nlp, xn)
        vn = violation(nlp, xn)
        if log:
            log(f"   round {r}: status {res.status} nit {res.nit} f {fn:.8g} viol {vn:.2e} "
                f"active {sum(len(nlp.pm[g].active) for g in nlp.groups)} ({res.message})")
        if vn > 1e-6 and add_active(nlp, xn, threshold):
            # a left-out pair got violated: restart from the last point with more pairs
            if best is None or vn < best[2]:
                x = xn
            r += 1
            continue
        improved = best is None or (vn < 1e-6 and (best[2] >= 1e-6 or fn < best[1] - 1e-9 * abs(best[1]))) \
            or (best[2] >= 1e-6 and vn < best[2])
        if improved:
            gain = None if best is None else best[1] - fn
            best = (xn, fn, vn)
            x = xn
            add_active(nlp, x, threshold)
            if gain is not None and vn < 1e-6 and gain < 1e-8 * abs(fn) and res.status == 0:
                break
        else:
            break
        r += 1
    if best is None:
        best = (x, _merit(nlp, x), violation(nlp, x))
    return best[0], best[1], best[2], nit


def initial_x(nlp, qs):
    fs = [nlp.pm[gi].loads_from_q(qs[i]) for i, gi in enumerate(nlp.groups)]
    return nlp.pack(qs, fs)


# ----------------------------------------------------------------------------------------------
# IPOPT (interior point, KKT-based termination) on the same NLP
# ----------------------------------------------------------------------------------------------
class _IpoptProblem:
    def __init__(self, nlp):
        self.nlp = nlp
        self.n_eq = len(nlp.eq(self._x0))
        self.n_in = len(nlp.ineq(self._x0))

    def objective(self, x):
        return self.nlp.obj_value(x)

    def gradient(self, x):
        return self.nlp.obj_grad(x)

    def constraints(self, x):
        return np.concatenate([self.nlp.eq(x), self.nlp.ineq(x)])

    def jacobian(self, x):
        J = np.vstack([self.nlp.eq_jac(x), self.nlp.ineq_jac(x)])
        return J[self.rows, self.cols]

    def jacobianstructure(self):
        return self.rows, self.cols

    def intermediate(self, alg_mod, iter_count, obj_value, inf_pr, inf_du, mu, d_norm,
                     regularization_size, alpha_du, alpha_pr, ls_trials):
        # our own CPU-time limit (checked every iteration, restoration phase included)
        if PROGRESS_HOOK is not None:
            PROGRESS_HOOK()
        return time.process_time() - self.cpu0 < self.cpu_limit


def _structure(nlp, x):
    """Sparsity pattern: each phase's constraints depend on its own q and f only."""
    nq, H, k = nlp.body.nq, nlp.body.H, nlp.k
    rows, cols = [], []
    r0 = 0
    qs, fs = nlp.split(x)
    blocks_eq = []
    for i, gi in enumerate(nlp.groups):
        v = nlp.pm[gi].eq(qs[i], fs[i])
        blocks_eq.append(len(v))
    blocks_in = []
    for i, gi in enumerate(nlp.groups):
        v = nlp.pm[gi].ineq(qs[i])
        blocks_in.append(len(v) + nlp.nz)
    for i in range(k):
        m = blocks_eq[i]
        cidx = list(range(i * nq, (i + 1) * nq)) + list(range(k * nq + i * H, k * nq + (i + 1) * H))
        for rr in range(r0, r0 + m):
            rows += [rr] * len(cidx)
            cols += cidx
        r0 += m
    for i in range(k):
        m = blocks_in[i]
        cidx = list(range(i * nq, (i + 1) * nq)) + (nlp.v_cols(i) if nlp.zones else [])
        for rr in range(r0, r0 + m):
            rows += [rr] * len(cidx)
            cols += cidx
        r0 += m
    if getattr(nlp, "capacity", False) and nlp.weights is None:
        # capacity rows: each depends on the loads of every optimised phase (dense in f)
        m = len(nlp.capacity_rows(x))
        cidx = list(range(k * nq, k * nq + k * H))
        for rr in range(r0, r0 + m):
            rows += [rr] * len(cidx)
            cols += cidx
        r0 += m
        blocks_in.append(m)
    return np.array(rows), np.array(cols), sum(blocks_eq), sum(blocks_in)


def solve_ipopt(nlp, x0, tol=1e-9, maxiter=3000, threshold=0.08, log=None, print_level=0,
                max_cpu_time=60.0):
    import cyipopt

    bounds = nlp.bounds()
    lo = np.array([a for a, _ in bounds])
    hi = np.array([b for _, b in bounds])
    x = np.clip(x0, lo, hi)
    set_active(nlp, x, threshold)
    best = None
    for attempt in range(4):
        rows, cols, neq, nin = _structure(nlp, x)
        prob = _IpoptProblem.__new__(_IpoptProblem)
        prob.nlp, prob.rows, prob.cols = nlp, rows, cols
        prob.cpu0, prob.cpu_limit = time.process_time(), float(max_cpu_time)
        cl = np.zeros(neq + nin)
        cu = np.concatenate([np.zeros(neq), np.full(nin, 2e19)])
        p = cyipopt.Problem(n=len(x), m=neq + nin, problem_obj=prob, lb=lo, ub=hi, cl=cl, cu=cu)
        p.add_option("hessian_approximation", "limited-memory")
        p.add_option("limited_memory_max_history", 50)
        p.add_option("tol", tol)
        p.add_option("constr_viol_tol", 1e-10)
        p.add_option("acceptable_tol", 1e-7)
        p.add_option("acceptable_iter", 30)
        p.add_option("max_iter", maxiter)
        p.add_option("print_level", print_level)
        p.add_option("sb", "yes")
        p.add_option("mu_strategy", "adaptive")
        p.add_option("bound_relax_factor", 0.0)
        p.add_option("honor_original_bounds", "yes")
        p.add_option("max_cpu_time", float(max_cpu_time) * 1.5)
        xn, info = p.solve(x)
        xn = np.clip(xn, lo, hi)
        fn = _merit(nlp, xn)
        vn = violation(nlp, xn)
        if log:
            log(f"   ipopt: status {info['status']} f {fn:.10g} viol {vn:.2e} ({info['status_msg'][:60]})")
        if best is None or (vn <= 1e-6 and (best[2] > 1e-6 or fn < best[1])):
            best = (xn, fn, vn, info["status"])
        if vn > 1e-6 and add_active(nlp, xn, threshold):
            x = xn
            continue
        break
    return best


def ik_project(pm, q_t, iters=80, mu=1e-8):
    """Hands and feet on their targets, staying close (weighted) to the template q_t:
    repeated minimum-weighted-norm corrections of the linearised equality constraints, joints at
    a limit that the step would push further being frozen."""
    b = pm.body
    w = np.ones(b.nq)
    w[b.unact_idx] = 0.3
    q = np.clip(q_t.copy(), b.lower, b.upper)
    ne = 3 * len(pm.hands) + 12
    for it in range(iters):
        e, J = pm.kin_eq(q)
        if np.max(np.abs(e)) < 1e-11:
            break
        d0 = np.zeros(b.nq) if it > iters // 2 else 0.2 * (q_t - q)
        Winv = 1.0 / w
        for _ in range(6):
            A = (J * Winv) @ J.T + mu * np.eye(ne)
            lam = -np.linalg.solve(A, e + J @ d0)
            dq = d0 + Winv * (J.T @ lam)
            push = ((q <= b.lower + 1e-12) & (dq < 0)) | ((q >= b.upper - 1e-12) & (dq > 0))
            if not push.any():
                break
            Winv = Winv.copy()
            Winv[push] = 0.0
            d0 = d0.copy()
            d0[push] = 0.0
        n = np.linalg.norm(dq)
        if n > 0.3:
            dq *= 0.3 / n
        q = np.clip(q + dq, b.lower, b.upper)
    return q


def warm_start(nlp, x0, max_cpu_time=15.0):
    """Cheap pre-solve with the total U after ONE cycle (nearly linear in the loads, no
    exhaustion) as objective: brings a raw seed to a sane, feasible region before the real
    objective, which can be exponentially steep far from good postures."""
    nlp.set_cycles(1)
    try:
        r = solve_ipopt(nlp, x0, max_cpu_time=max_cpu_time, tol=1e-5)
        x = r[0] if r is not None else x0
    finally:
        nlp.set_cycles(None)
    return x


def restore(pm, q0, max_nfev=200, push=2e-3):
    """Feasibility restoration: least squares of the hand/feet errors and the hinge violations of
    the clearance and balance constraints (scipy least_squares, bounds), then an SLSQP
    projection. Robust from seeds far from the feasible set."""
    from scipy.optimize import least_squares

    b, t = pm.body, pm.task
    pm.active = np.arange(pm.n_dist)
    pm._cache_key = None
    nk = 3 * len(pm.hands) + 12

    def parts(q, jac):
        e = pm.evaluate(q, jac)
        kin, J = pm.kin_eq(q) if jac else (pm.kin_eq(q)[0], None)
        d = e["dist"] - t.clearance - push
        bal = pm.edges_n @ e["p"] - pm.edges_o - t.balance_margin - push
        return e, kin, J, d, bal

    def res(q):
        e, kin, J, d, bal = parts(q, False)
        return np.concatenate([10 * kin, np.minimum(d, 0), np.minimum(bal, 0)])

    def jac(q):
        e, kin, J, d, bal = parts(q, True)
        Jd = e["dist_J"] * (d < 0)[:, None]
        Jb = (pm.edges_n @ e["dp"]) * (bal < 0)[:, None]
        return np.vstack([10 * J, Jd, Jb])

    lo, hi = b.lower, b.upper
    x0 = np.clip(q0, lo + 1e-9, hi - 1e-9)
    r = least_squares(res, x0, jac=jac, bounds=(lo, hi), method="trf", max_nfev=max_nfev,
                      xtol=1e-12, ftol=1e-12, gtol=1e-12)
    q = np.clip(r.x, lo, hi)
    q = project(pm, q, maxiter=150)
    pm.active = np.arange(pm.n_dist)
    pm._cache_key = None
    return q


def restore_zones(pm, q_t, w_zone=0.5, w_reg=0.02, push=2e-3, max_nfev=300):
    """Zone-respecting feasibility restoration of a seed (zoned search, run 7): scipy
    least_squares (trf, joint bounds) of
      10 x the hand/feet errors, the hinge violations of every clearance pair (obstacles, self,
      held boxes) and of the balance margin (each pushed 2 mm inside), the gaze hinge,
      w_zone x the zone rows' excesses (g_i + 1e-3 rad)_+ and w_reg x (q - q_t),
    started from the TEMPLATE q_t itself; then the SLSQP projection (project) onto the hard
    constraints. Why: ik_project alone (minimum-weighted-norm steps of the hands and feet only)
    lands, for a task whose targets are far from the hanging hands (hold_and_place), on postures
    stooped 100-150 deg with the arms overhead, inside the table, off balance and looking away;
    IPOPT's restoration from there ignores the zones and stalls on absurd local solutions. Here
    the zones and the gaze pull the restored seed upright and the clearance rows out of the
    obstacles before the real NLP starts."""
    from scipy.optimize import least_squares

    b, t, pr = pm.body, pm.task, pm.prob
    gi = pm.gi
    L = pr.zone_limits[gi]
    pts = pr.gaze_points[gi] if pr.zones else []
    pm.active = np.arange(pm.n_dist)
    pm._cache_key = None

    def res(q):
        e = pm.evaluate(q, False)
        kin = pm.kin_eq(q)[0]
        d = e["dist"] - t.clearance - push
        bal = pm.edges_n @ e["p"] - pm.edges_o - t.balance_margin - push
        g = pr.zm.rows(q, L) + 1e-3
        out = [10 * kin, np.minimum(d, 0), np.minimum(bal, 0), w_zone * np.maximum(g, 0),
               w_reg * (q - q_t)]
        if pts:
            out.append(np.minimum(pr.zm.gaze_values(q, pts) - push, 0))
        return np.concatenate(out)

    def jac(q):
        e = pm.evaluate(q, True)
        kin, J = pm.kin_eq(q)
        d = e["dist"] - t.clearance - push
        bal = pm.edges_n @ e["p"] - pm.edges_o - t.balance_margin - push
        g, Jg = pr.zm.rows_jac(q, L)
        g = g + 1e-3
        out = [10 * J, e["dist_J"] * (d < 0)[:, None], (pm.edges_n @ e["dp"]) * (bal < 0)[:, None],
               w_zone * Jg * (g > 0)[:, None], w_reg * np.eye(b.nq)]
        if pts:
            gv, gJ = pr.zm.gaze_jac(q, pts)
            out.append(gJ * (gv - push < 0)[:, None])
        return np.vstack(out)

    lo, hi = b.lower, b.upper
    x0 = np.clip(q_t, lo + 1e-9, hi - 1e-9)
    r = least_squares(res, x0, jac=jac, bounds=(lo, hi), method="trf", max_nfev=max_nfev,
                      xtol=1e-12, ftol=1e-12, gtol=1e-12)
    q = np.clip(r.x, lo, hi)
    pm.active = np.arange(pm.n_dist)
    pm._cache_key = None
    q = project(pm, q, maxiter=150)
    pm.active = np.arange(pm.n_dist)
    pm._cache_key = None
    return q
