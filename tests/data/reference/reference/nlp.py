"""The planning problem as a smooth NLP.

Decision vector x = [q_1 .. q_P, f_1 .. f_P]: one posture per distinct phase and, per phase, one
slack load per half-joint (f_p[2a] = load of joint a's '+' group, f_p[2a+1] of its '-' group).
The torque identity  tau_a(q_p) = f+ MVC+(q_p) - f- MVC-(q_p)  is an equality constraint, with
f >= 0. The objective (total U) is increasing in every load, so at an optimum one of f+, f- is
zero and f = max(+-tau, 0)/MVC exactly: the reformulation removes the kink of max(., 0) at zero
torque without changing the optimum. The final plans are re-evaluated from the postures alone by
model.Problem.evaluate.
"""
import math

import numpy as np
import pinocchio as pin

from . import fatigue as fat
from . import model as M


class PhaseModel:
    """Values and Jacobians of one phase's constraints as functions of its posture q."""

    FD_STEP = 1e-6

    def __init__(self, prob, gi, margin=1e-7):
        self.prob = prob
        self.task = prob.task
        self.body = prob.body
        self.gi = gi
        g = self.task.groups[gi]
        self.FR = g["forces"]["r"]
        self.FL = g["forces"]["l"]
        self.targets = g["targets"]
        self.hands = sorted(self.targets)
        self.edges_n, self.edges_o = self.task.stance_edges
        self.margin = margin
        self.n_eq = 3 * len(self.hands) + 12 + len(self.body.actuated)
        # obstacle, self and held-object pairs (the last: this phase's held boxes)
        self.n_dist = prob.pairs.n_pairs(gi)
        self.n_ineq = self.n_dist + len(self.edges_o)
        self._cache_key = None
        self._cache = None
        self.active = np.arange(self.n_dist)  # distance pairs passed to the solver

    def set_active(self, q, threshold):
        """Keep the pairs whose clearance is below clearance + threshold at q."""
        e = self.evaluate(q, False)
        self.active = np.where(e["dist"] < self.task.clearance + threshold)[0]
        self._cache_key = None
        return self.active

    def add_active(self, q, threshold):
        e = self.evaluate(q, False)
        new = np.where(e["dist"] < self.task.clearance + threshold)[0]
        before = len(self.active)
        self.active = np.union1d(self.active, new)
        self._cache_key = None
        return len(self.active) > before

    def _statics(self, q):
        tau, p = M.statics(self.body, q, self.FR, self.FL)
        return tau[self.body.act_idx], p

    def evaluate(self, q, jac):
        key = (q.tobytes(), jac)
        if self._cache_key is not None:
            if self._cache_key[0] == key[0] and (self._cache_key[1] or not jac):
                return self._cache
        b, t = self.body, self.task
        nq = b.nq
        out = {}
        tau, p = self._statics(q)
        out["tau"], out["p"] = tau, p
        mvc, dmvc = b.mvc(q, with_grad=jac)
        out["mvc"], out["dmvc"] = mvc, dmvc
        b.fk(q)
        # hands
        he, hJ = [], []
        for h in self.hands:
            fid = b.fid[f"{h}_hand_grip"]
            he.append(b.data.oMf[fid].translation - self.targets[h])
            if jac:
                hJ.append(b.frame_jac(fid)[:3])
        # feet
        fe, fJ = [], []
        for foot in ("l_foot", "r_foot"):
            fid = b.fid[foot]
            pos, R = b.frame_pose(fid)
            pt, Rt = t.foot_target[foot]
            Rerr = Rt.T @ R
            fe.append(pos - pt)
            fe.append(pin.log3(Rerr))
            if jac:
                J = b.frame_jac(fid)
                fJ.append(J[:3])
                fJ.append(pin.Jlog3(Rerr) @ (R.T @ J[3:]))
        out["hand"] = np.concatenate(he) if he else np.zeros(0)
        out["feet"] = np.concatenate(fe)
        dist, dJ = self.prob.pairs.distances(with_jac=jac, rows=self.active if jac else None,
                                             gi=self.gi)
        out["dist"] = dist
        if jac:
            out["hand_J"] = np.vstack(hJ) if hJ else np.zeros((0, nq))
            out["feet_J"] = np.vstack(fJ)
            out["dist_J"] = dJ
            # finite differences of the statics (torques and centre of pressure)
            h = self.FD_STEP
            dtau = np.zeros((len(tau), nq))
            dp = np.zeros((2, nq))
            for i in range(nq):
                qp = q.copy()
                qp[i] += h
                qm = q.copy()
                qm[i] -= h
                tp, pp = self._statics(qp)
                tm, pm = self._statics(qm)
                dtau[:, i] = (tp - tm) / (2 * h)
                dp[:, i] = (pp - pm) / (2 * h)
            out["dtau"], out["dp"] = dtau, dp
        self._cache_key = key
        self._cache = out
        return out

    def kin_eq(self, q):
        """Hand and foot errors and their Jacobians only (for the IK projection)."""
        b, t = self.body, self.task
        b.fk(q)
        e, J = [], []
        for h in self.hands:
            fid = b.fid[f"{h}_hand_grip"]
            e.append(b.data.oMf[fid].translation - self.targets[h])
            J.append(b.frame_jac(fid)[:3])
        for foot in ("l_foot", "r_foot"):
            fid = b.fid[foot]
            pos, R = b.frame_pose(fid)
            pt, Rt = t.foot_target[foot]
            Rerr = Rt.T @ R
            Jf = b.frame_jac(fid)
            e += [pos - pt, pin.log3(Rerr)]
            J += [Jf[:3], pin.Jlog3(Rerr) @ (R.T @ Jf[3:])]
        return np.concatenate(e), np.vstack(J)

    # --- constraint blocks (values, Jacobians wrt q and wrt f) --------------------------------
    def eq(self, q, f, jac=False):
        e = self.evaluate(q, jac)
        b = self.body
        S = b.tau_scale
        mvc = e["mvc"]
        r_tau = (e["tau"] - f[0::2] * mvc[0::2] + f[1::2] * mvc[1::2]) / S
        val = np.concatenate([e["hand"], e["feet"], r_tau])
        if not jac:
            return val
        nh = len(e["hand"])
        na = len(b.actuated)
        Jq = np.zeros((len(val), b.nq))
        Jf = np.zeros((len(val), b.H))
        Jq[:nh] = e["hand_J"]
        Jq[nh:nh + 12] = e["feet_J"]
        dm = e["dmvc"]
        Jq[nh + 12:] = (e["dtau"] - f[0::2, None] * dm[0::2] + f[1::2, None] * dm[1::2]) / S[:, None]
        ar = np.arange(na)
        Jf[nh + 12 + ar, 2 * ar] = -mvc[0::2] / S
        Jf[nh + 12 + ar, 2 * ar + 1] = mvc[1::2] / S
        return val, Jq, Jf

    def ineq(self, q, jac=False):
        e = self.evaluate(q, jac)
        t = self.task
        a = self.active
        cl = e["dist"][a] - t.clearance - self.margin
        bal = self.edges_n @ e["p"] - self.edges_o - t.balance_margin - self.margin
        pts = self.prob.gaze_points[self.gi] if self.prob.zones else []
        if pts:
            if jac:
                gv, gJ = self.prob.zm.gaze_jac(q, pts)
            else:
                gv = self.prob.zm.gaze_values(q, pts)
            gv = gv - self.margin
        else:
            gv, gJ = np.zeros(0), np.zeros((0, self.body.nq))
        val = np.concatenate([cl, bal, gv])
        if not jac:
            return val
        Jq = np.vstack([e["dist_J"][a], self.edges_n @ e["dp"], gJ])
        return val, Jq

    def min_clearance_slack(self, q):
        """Smallest clearance slack over all pairs (not only the active ones)."""
        e = self.evaluate(q, False)
        return float(np.min(e["dist"] - self.task.clearance))

    def loads_from_q(self, q):
        tau, p = self._statics(q)
        mvc, _ = self.body.mvc(q)
        f = np.zeros(self.body.H)
        f[0::2] = np.maximum(tau, 0) / mvc[0::2]
        f[1::2] = np.maximum(-tau, 0) / mvc[1::2]
        return f


class JointNLP:
    """All distinct phases together with the true fatigue objective (or, if weights are given,
    a single phase with the linearised objective sum_h w_h f_h)."""

    def __init__(self, prob, phases=None, weights=None):
        self.prob = prob
        self.body = prob.body
        self.task = prob.task
        self.groups = list(range(self.task.P)) if phases is None else list(phases)
        self.pm = [PhaseModel(prob, gi) for gi in range(self.task.P)]
        self.weights = weights  # dict gi -> w[H] for a linearised objective
        self.fixed_loads = None  # loads of phases not optimised (for a partial joint problem)
        nq, H = self.body.nq, self.body.H
        self.k = len(self.groups)
        # zones: one elastic slack per zone row per distinct posture, appended after the loads
        self.zones = bool(prob.zones)
        self.nz = prob.Z.NROW if self.zones else 0
        self.n = self.k * (nq + H + self.nz)
        self.obj_scale = 1.0
        # the solvers minimise log(total U): the same minimisers, far better conditioned when U
        # spans orders of magnitude (a nearly exhausted muscle group makes U grow like e^{2kft})
        self.log_objective = True
        # warm-up objective: the total U after this many cycles instead of the task's (None: all)
        self.cycles_override = None
        self._vcache = None
        self._gcache = None
        # capacity rows (statement section 4, "capacity"): on when prob.capacity is set
        self.capacity = bool(getattr(prob, "capacity", False))

    CAP_MARGIN = 0.02

    def capacity_rows(self, x, jac=False):
        """Rows c_{s,n}[h] - f_{p(s)}[h] - 0.02 >= 0 for every step s holding a phase's posture
        (rest excluded), n in {first, last cycle} (one if cycles == 1), every half-joint h; the
        capacities from fat.capacity_ends (closed form). Derivative wrt the loads by the complex
        step (whole load row at once: half-joints are independent), as simulate_grad does; zero
        wrt q and the zone slacks. Jx has the full width n."""
        t = self.task
        qs, fs = self.split(x)
        L, step_idx = self._fatigue_args(fs)
        P = t.P
        steps = np.where(step_idx < P)[0]          # permuted row index < P: a phase, not rest
        ncyc = 2 if t.cycles > 1 else 1
        Lc = L.astype(np.complex128)
        C = fat.capacity_ends(Lc, t.ks, step_idx, t.step_dur, t.cycles, t.r_rest, t.f_lim)
        H = L.shape[1]
        val = np.concatenate([C[s, n].real - L[step_idx[s]] - self.CAP_MARGIN
                              for s in steps for n in range(ncyc)]) if len(steps) else np.zeros(0)
        if not jac:
            return val
        nq, k = self.body.nq, self.k
        Jx = np.zeros((len(val), self.n))
        hs = 1e-30
        for i in range(k):                          # permuted row i = optimised phase i
            Lp = Lc.copy()
            Lp[i] += 1j * hs
            Cp = fat.capacity_ends(Lp, t.ks, step_idx, t.step_dur, t.cycles, t.r_rest, t.f_lim)
            r = 0
            for s in steps:
                for n in range(ncyc):
                    d = Cp[s, n].imag / hs
                    if step_idx[s] == i:
                        d = d - 1.0
                    Jx[r + np.arange(H), k * nq + i * H + np.arange(H)] = d
                    r += H
        return val, Jx

    def split(self, x):
        nq, H, k = self.body.nq, self.body.H, self.k
        qs = [x[i * nq:(i + 1) * nq] for i in range(k)]
        fs = [x[k * nq + i * H:k * nq + (i + 1) * H] for i in range(k)]
        return qs, fs

    def split_v(self, x):
        nq, H, k, nz = self.body.nq, self.body.H, self.k, self.nz
        o = k * (nq + H)
        return [x[o + i * nz:o + (i + 1) * nz] for i in range(k)]

    def v_cols(self, i):
        nq, H, k, nz = self.body.nq, self.body.H, self.k, self.nz
        o = k * (nq + H)
        return list(range(o + i * nz, o + (i + 1) * nz))

    def pack(self, qs, fs, vs=None):
        if self.zones:
            if vs is None:
                vs = [np.maximum(self.prob.zm.rows(q, self.prob.zone_limits[gi]), 0.0) + 1e-6
                      for q, gi in zip(qs, self.groups)]
            return np.concatenate(list(qs) + list(fs) + list(vs))
        return np.concatenate(list(qs) + list(fs))

    def bounds(self):
        b = self.body
        lo = list(b.lower) * self.k + [0.0] * (b.H * self.k) + [0.0] * (self.nz * self.k)
        hi = list(b.upper) * self.k + [20.0] * (b.H * self.k) + [10.0] * (self.nz * self.k)
        return list(zip(lo, hi))

    def all_loads(self, fs):
        loads = [None] * self.task.P
        for i, gi in enumerate(self.groups):
            loads[gi] = fs[i]
        for gi in range(self.task.P):
            if loads[gi] is None:
                loads[gi] = self.fixed_loads[gi]
        return loads

    def _fatigue_args(self, fs):
        t = self.task
        loads = self.all_loads(fs)
        L = np.vstack(loads + [self.prob.rest_loads])
        order = self.groups + [gi for gi in range(t.P) if gi not in self.groups]
        perm = order + [t.P]
        inv_idx = np.argsort(np.array(perm))
        step_idx = inv_idx[t.step_idx].astype(np.int64)
        return np.ascontiguousarray(L[perm]), step_idx

    def obj_value(self, x):
        self._vcache_x = x
        key = x.tobytes()
        if self._vcache is not None and self._vcache[0] == key:
            return self._transform(self._vcache[1])
        qs, fs = self.split(x)
        if self.weights is not None:
            val = sum(float(self.weights[gi] @ fs[i]) for i, gi in enumerate(self.groups))
        else:
            t = self.task
            L, step_idx = self._fatigue_args(fs)
            U = fat.simulate_value(L, t.ks, step_idx, t.step_dur, self._cycles(), t.r_rest, t.f_lim)
            val = float(U.sum())
        self._vcache = (key, val)
        return self._transform(val)

    def obj_grad(self, x):
        key = x.tobytes()
        if self._gcache is not None and self._gcache[0] == key:
            return self._gcache[1]
        qs, fs = self.split(x)
        nq, H, k = self.body.nq, self.body.H, self.k
        g = np.zeros_like(x)
        if self.weights is not None:
            for i, gi in enumerate(self.groups):
                g[k * nq + i * H:k * nq + (i + 1) * H] = self.weights[gi]
        else:
            t = self.task
            L, step_idx = self._fatigue_args(fs)
            U, G = fat.simulate_fwd(L, t.ks, step_idx, t.step_dur, self._cycles(), t.r_rest,
                                    t.f_lim, self.k)
            val = float(U.sum())
            self._vcache = (key, val)
            for i in range(self.k):
                g[k * nq + i * H:k * nq + (i + 1) * H] = G[i]
            if self.zones:
                from .model import U_OFFSET, ZONE_WEIGHT
                g = g / (val + U_OFFSET)
                g[k * (nq + H):] = ZONE_WEIGHT
            elif self.log_objective:
                g = g / val
        self._gcache = (key, g)
        return g

    def _cycles(self):
        return self.task.cycles if self.cycles_override is None else int(self.cycles_override)

    def set_cycles(self, n):
        self.cycles_override = n
        self._vcache = None
        self._gcache = None

    def _transform(self, val):
        if self.zones and self.weights is None:
            from .model import U_OFFSET, ZONE_WEIGHT
            x = self._vcache_x
            pen = float(sum(v.sum() for v in self.split_v(x)))
            return math.log(val + U_OFFSET) + ZONE_WEIGHT * pen
        if self.weights is None and self.log_objective:
            return math.log(val)
        return val

    def objective(self, x):
        return self.obj_value(x), self.obj_grad(x)

    def total_u(self, x):
        """The (slack) total U itself, whatever the solver's objective."""
        self.obj_value(x)
        return self._vcache[1]

    def eq(self, x):
        qs, fs = self.split(x)
        return np.concatenate([self.pm[gi].eq(qs[i], fs[i]) for i, gi in enumerate(self.groups)])

    def eq_jac(self, x):
        qs, fs = self.split(x)
        nq, H, k = self.body.nq, self.body.H, self.k
        blocks = []
        for i, gi in enumerate(self.groups):
            v, Jq, Jf = self.pm[gi].eq(qs[i], fs[i], jac=True)
            B = np.zeros((len(v), self.n))
            B[:, i * nq:(i + 1) * nq] = Jq
            B[:, k * nq + i * H:k * nq + (i + 1) * H] = Jf
            blocks.append(B)
        return np.vstack(blocks)

    def ineq(self, x):
        qs, fs = self.split(x)
        out = []
        vs = self.split_v(x) if self.zones else None
        for i, gi in enumerate(self.groups):
            out.append(self.pm[gi].ineq(qs[i]))
            if self.zones:
                # elastic zone rows: v_i - g_i(q) >= 0
                out.append(vs[i] - self.prob.zm.rows(qs[i], self.prob.zone_limits[gi]))
        if self.capacity and self.weights is None:
            out.append(self.capacity_rows(x))
        return np.concatenate(out)

    def ineq_jac(self, x):
        qs, fs = self.split(x)
        nq = self.body.nq
        blocks = []
        for i, gi in enumerate(self.groups):
            v, Jq = self.pm[gi].ineq(qs[i], jac=True)
            B = np.zeros((len(v), self.n))
            B[:, i * nq:(i + 1) * nq] = Jq
            blocks.append(B)
            if self.zones:
                _, Jg = self.prob.zm.rows_jac(qs[i], self.prob.zone_limits[gi])
                Bz = np.zeros((self.nz, self.n))
                Bz[:, i * nq:(i + 1) * nq] = -Jg
                Bz[:, self.v_cols(i)] = np.eye(self.nz)
                blocks.append(Bz)
        if self.capacity and self.weights is None:
            blocks.append(self.capacity_rows(x, jac=True)[1])
        return np.vstack(blocks)
