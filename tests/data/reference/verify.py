#!/usr/bin/env python3
"""Self-checks of the reference implementation; writes results/verification.json.

1. fatigue: closed-form steps vs numerical ODE integration (scipy solve_ivp, rtol 1e-12), and a
   whole schedule (3 cycles of a task) integrated numerically vs the step-by-step closed forms;
2. fatigue gradients: forward-mode/complex-step derivatives vs central finite differences;
3. PCHIP: our implementation vs scipy.interpolate.PchipInterpolator (values and slopes);
4. statics: unactuated (pelvis) torques ~ 0 after the ground split; the split reproduces the
   ground wrench; d(sum tau_act^2)/d lambda = 0; holding torques vs an independent computation
   (finite differences of the potential energy plus J^T F from finite differences of positions);
5. NLP Jacobians (hands, feet, torque identity, clearances, balance) vs finite differences;
6. distances vs brute-force sampling.
"""
import json
import os
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import PchipInterpolator

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference import fatigue as fat  # noqa: E402
from reference import geometry as geo  # noqa: E402
from reference import model as M  # noqa: E402
from reference import search as S  # noqa: E402
from reference.nlp import JointNLP  # noqa: E402

OUT = {}


def rec(name, value, ok):
    OUT[name] = dict(value=value, ok=bool(ok))
    print(f"{'OK ' if ok else 'BAD'} {name}: {value}")


def check_fatigue():
    rr, fl = 0.37, 0.085
    worst = 0.0
    cases = [(1.0, 0.3, 1.3967, 0.05), (0.8, 0.05, 0.843, 0.2), (0.7, 0.0849, 0.5, 1.0),
             (0.9, 0.0, 0.7, 0.3), (0.6, 0.08499999, 1.0, 2.0), (0.95, 0.5, 1.0315, 0.5),
             (0.5, 0.01, 0.6506, 5.0), (0.3, 0.2, 0.7376, 0.1), (1.0, 1e-9, 1.0, 1.0)]
    for c0, f, k, T in cases:
        cT, dU = fat.step_real(c0, f, k, T, rr, fl)
        R = rr * (1 - f / fl) ** 2 * (3 - 2 * (1 - f / fl)) if f < fl else 0.0
        sol = solve_ivp(lambda t, y: [-k * f * y[0] + R * (1 - y[0]), f / y[0] ** 2], [0, T],
                        [c0, 0.0], rtol=1e-12, atol=1e-15, method="DOP853")
        e = max(abs(cT - sol.y[0, -1]), abs(dU - sol.y[1, -1]) / max(abs(sol.y[1, -1]), 1e-12))
        worst = max(worst, e)
    rec("fatigue step closed form vs ODE (max rel err)", worst, worst < 1e-9)
    # no-recovery closed form (e^{2kfT}-1)/(2k c0^2)
    c0, f, k, T = 0.8, 0.3, 1.2, 0.7
    cT, dU = fat.step_real(c0, f, k, T, 0.0, 1.0)
    exact = (np.exp(2 * k * f * T) - 1) / (2 * k * c0 ** 2)
    rec("fatigue no-recovery closed form", abs(dU - exact) / exact, abs(dU - exact) / exact < 1e-13)
    # whole schedule: shelf task, 3 cycles, random loads, ODE with piecewise-constant load
    t = M.load_task("shelf")
    rng = np.random.default_rng(3)
    L = np.vstack([rng.random((t.P, 64)) * 0.3, rng.random((1, 64)) * 0.1])
    L[:, :8] = 0.0
    cycles = 3
    U = fat.simulate_value(L, t.ks, t.step_idx, t.step_dur, cycles, t.r_rest, t.f_lim)
    worst = 0.0
    for h in range(0, 64, 7):
        y = np.array([1.0, 0.0])
        for cyc in range(cycles):
            for row, T in zip(t.step_idx, t.step_dur):
                f = L[row, h]
                k = t.ks[h]
                R = t.r_rest * (1 - f / t.f_lim) ** 2 * (3 - 2 * (1 - f / t.f_lim)) if f < t.f_lim else 0.0
                sol = solve_ivp(lambda tt, yy: [-k * f * yy[0] + R * (1 - yy[0]), f / yy[0] ** 2],
                                [0, T], y, rtol=1e-12, atol=1e-15, method="DOP853")
                y = sol.y[:, -1]
        worst = max(worst, abs(y[1] - U[h]) / max(abs(U[h]), 1e-12))
    rec("fatigue schedule (3 cycles) closed forms vs ODE (max rel err)", worst, worst < 1e-8)
    # exhaustion time: a load held to exhaustion, compared with bisection on the closed form
    Lx = np.zeros((2, 1))
    Lx[0, 0] = 0.5
    Ux, cx, tex = fat.simulate_real(Lx, np.array([1.0]), np.array([0], np.int64), np.array([10.0]),
                                    1, 0.37, 0.085)
    # c = c0 e^{-k f t} (R = 0 above f_lim): c = f at t = ln(1/f)/(k f)
    exact = np.log(1 / 0.5) / 0.5
    rec("exhaustion time (hold 50 %MVC, k = 1)", float(abs(tex[0] - exact)), abs(tex[0] - exact) < 1e-12)


def check_fatigue_grad():
    t = M.load_task("pallet")
    pr = M.Problem(t)
    rng = np.random.default_rng(0)
    L = np.vstack([rng.random((t.P, 64)) * 0.2, pr.rest_loads[None]])
    args = (t.ks, t.step_idx, t.step_dur, t.cycles, t.r_rest, t.f_lim)
    U, G = fat.simulate_fwd(L, *args, t.P)
    U2, G2 = fat.simulate_grad(L.astype(complex), *args, t.P)
    worst = 0.0
    h = 1e-6
    for p in range(t.P):
        Lp = L.copy()
        Lp[p] += h
        Lm = L.copy()
        Lm[p] -= h
        fd = (fat.simulate_value(Lp, *args) - fat.simulate_value(Lm, *args)) / (2 * h)
        worst = max(worst, float(np.max(np.abs(fd - G[p]) / (np.abs(G[p]) + 1e-8))))
    rec("fatigue gradient (forward mode) vs central FD (max rel err)", worst, worst < 1e-5)
    e = float(np.max(np.abs(G - G2) / (np.abs(G2) + 1e-12)))
    rec("fatigue gradient forward mode vs full complex step", e, e < 1e-10)


def check_pchip():
    t = M.load_task("shelf")
    worst = 0.0
    n = 0
    for h in t.body.half:
        for qi, pc in h["curves"]:
            ref = PchipInterpolator(pc.x, pc.y)
            dref = ref.derivative()
            for xq in np.linspace(pc.x[0] + 1e-9, pc.x[-1] - 1e-9, 301):
                v, d = pc(xq)
                worst = max(worst, abs(v - ref(xq)), abs(d - dref(xq)) * 1e-2)
                n += 1
            # held constant outside
            v0, d0 = pc(pc.x[0] - 0.3)
            v1, d1 = pc(pc.x[-1] + 0.3)
            worst = max(worst, abs(v0 - pc.y[0]), abs(v1 - pc.y[-1]), abs(d0), abs(d1))
    rec(f"PCHIP vs scipy PchipInterpolator ({n} points)", worst, worst < 1e-12)


def independent_torques(body, q, FR, FL, st):
    """tau = dV/dq (V = -sum m g.x) - sum J^T F, with J from FD of positions (no Pinocchio
    Jacobians), external loads = hand forces + the ground forces and free moments of the split."""
    import pinocchio as pin
    m, d = body.model, body.data
    h = 1e-6
    nq = body.nq

    def potential(qq):
        pin.forwardKinematics(m, d, qq)
        V = 0.0
        for j in range(1, m.njoints):
            I = m.inertias[j]
            if I.mass > 0:
                x = d.oMi[j].act(I.lever)
                V -= I.mass * body.gravity @ x
        return V

    def point(qq, fid, local):
        pin.forwardKinematics(m, d, qq)
        pin.updateFramePlacements(m, d)
        return d.oMf[fid].act(local)

    def rot(qq, fid):
        pin.forwardKinematics(m, d, qq)
        pin.updateFramePlacements(m, d)
        return d.oMf[fid].rotation.copy()

    # local coordinates of the load points
    body.fk(q)
    loads = []
    for hand, F in (("r_hand_grip", FR), ("l_hand_grip", FL)):
        loads.append((body.fid[hand], np.zeros(3), F, np.zeros(3)))
    for foot in ("l_foot", "r_foot"):
        pi, Fi, Mi = st["foot_loads"][foot]
        o, R = body.frame_pose(body.fid[foot])
        loads.append((body.fid[foot], R.T @ (pi - o), Fi, Mi))
    tau = np.zeros(nq)
    for i in range(nq):
        qp = q.copy()
        qp[i] += h
        qm = q.copy()
        qm[i] -= h
        tau[i] = (potential(qp) - potential(qm)) / (2 * h)
        for fid, loc, F, Mo in loads:
            dx = (point(qp, fid, loc) - point(qm, fid, loc)) / (2 * h)
            Rp, Rm = rot(qp, fid), rot(qm, fid)
            # angular velocity (world) from dR R^T
            W = (Rp - Rm) / (2 * h) @ rot(q, fid).T
            w = np.array([W[2, 1], W[0, 2], W[1, 0]])
            tau[i] -= dx @ F + w @ Mo
    return tau


def check_statics():
    worst_unact = 0.0
    worst_indep = 0.0
    worst_wrench = 0.0
    worst_lam = 0.0
    for key in ("shelf", "shelf_two_hands", "bench_assembly", "pallet"):
        t = M.load_task(key)
        b = t.body
        pr = M.Problem(t)
        nlp = JointNLP(pr)
        rng = np.random.default_rng(7)
        for gi in range(t.P):
            for trial in range(3):
                fam = list(S.FAMILIES.values())[rng.integers(len(S.FAMILIES))]
                q = S.ik_project(nlp.pm[gi], S.template(b, t.rest_q, fam, rng))
                FR, FL = t.groups[gi]["forces"]["r"], t.groups[gi]["forces"]["l"]
                st = M.statics(b, q, FR, FL, details=True)
                tau = st["tau"]
                worst_unact = max(worst_unact, float(np.max(np.abs(tau[b.unact_idx]))))
                # the split's feet loads reproduce the ground wrench about the origin
                Fs = sum(fl[1] for fl in st["foot_loads"].values())
                Ms = sum(M.cross(fl[0], fl[1]) + fl[2] for fl in st["foot_loads"].values())
                worst_wrench = max(worst_wrench, float(np.max(np.abs(Fs - st["F"]))),
                                   float(np.max(np.abs(Ms - st["M"]))))
                # optimality of lambda: d/dlam sum tau_act^2 = 0 (with g from a perturbation)
                if trial == 0:
                    ti = independent_torques(b, q, FR, FL, st)
                    worst_indep = max(worst_indep, float(np.max(np.abs(ti - tau))))
        # lambda optimality (on the rest posture): recompute tau for lambda +- eps via loads
        q = t.rest_q
        st = M.statics(b, q, np.zeros(3), np.zeros(3), details=True)
        e = np.append((st["c"]["l_foot"] - st["c"]["r_foot"])[:2], 0.0)
        e /= np.linalg.norm(e)
        b.fk(q)
        JL = b.point_jac(b.fid["l_foot"], st["foot_loads"]["l_foot"][0])
        JR = b.point_jac(b.fid["r_foot"], st["foot_loads"]["r_foot"][0])
        g = -(JL.T @ e) + JR.T @ e
        worst_lam = max(worst_lam, abs(float(g[b.act_idx] @ st["tau"][b.act_idx])))
    rec("max |unactuated (pelvis) torque| after the ground split [N m]", worst_unact, worst_unact < 1e-8)
    rec("feet loads reproduce the ground wrench (max abs err)", worst_wrench, worst_wrench < 1e-9)
    rec("holding torques vs independent FD potential-energy/virtual-work computation [N m]",
        worst_indep, worst_indep < 1e-5)
    rec("internal force lambda optimal: |sum g_j tau_j| [N m^2]", worst_lam, worst_lam < 1e-8)


def check_nlp_jacobians():
    worst = {}
    for key in ("shelf", "pallet"):
        t = M.load_task(key)
        pr = M.Problem(t)
        nlp = JointNLP(pr)
        rng = np.random.default_rng(11)
        for gi in range(t.P):
            pm = nlp.pm[gi]
            q = S.ik_project(pm, S.template(t.body, t.rest_q, S.FAMILIES["stoop_mild"], rng))
            # stay 1e-4 inside the joint limits: the strength curves are held constant beyond
            # their tables, so a central difference straddling a table end (often a joint limit)
            # is not a derivative
            q = np.clip(q, t.body.lower + 1e-4, t.body.upper - 1e-4)
            f = pm.loads_from_q(q) + 0.01
            pm.active = np.arange(pm.n_dist)
            pm._cache_key = None
            v, Jq, Jf = pm.eq(q, f, jac=True)
            vi, Ji = pm.ineq(q, jac=True)
            h = 1e-6
            FDq = np.zeros_like(Jq)
            FDi = np.zeros_like(Ji)
            for i in range(len(q)):
                qp = q.copy()
                qp[i] += h
                qm = q.copy()
                qm[i] -= h
                FDq[:, i] = (pm.eq(qp, f) - pm.eq(qm, f)) / (2 * h)
                FDi[:, i] = (pm.ineq(qp) - pm.ineq(qm)) / (2 * h)
            FDf = np.zeros_like(Jf)
            for i in range(len(f)):
                fp = f.copy()
                fp[i] += h
                fm = f.copy()
                fm[i] -= h
                FDf[:, i] = (pm.eq(q, fp) - pm.eq(q, fm)) / (2 * h)
            nh = 3 * len(pm.hands)
            parts = {"hands": slice(0, nh), "feet": slice(nh, nh + 12), "torque identity": slice(nh + 12, None)}
            for name, sl in parts.items():
                e = float(np.max(np.abs(Jq[sl] - FDq[sl])))
                worst[name] = max(worst.get(name, 0.0), e)
            worst["torque identity wrt loads"] = max(worst.get("torque identity wrt loads", 0.0),
                                                     float(np.max(np.abs(Jf - FDf))))
            # distances: compare rows whose FD is smooth (skip pairs at a switch of witness)
            nd = pm.n_dist
            # rows of overlapping pairs (deep inside a box the distance is a max of face distances
            # and not differentiable) are left out
            keep = vi[:nd] + t.clearance > -0.005
            e = np.abs(Ji[:nd] - FDi[:nd])[keep].max(axis=1)
            worst["clearances (median row)"] = max(worst.get("clearances (median row)", 0.0), float(np.median(e)))
            worst["clearances (max row)"] = max(worst.get("clearances (max row)", 0.0), float(np.max(e)))
            worst["balance"] = max(worst.get("balance", 0.0), float(np.max(np.abs(Ji[nd:] - FDi[nd:]))))
    for k, v in worst.items():
        rec(f"NLP Jacobian vs FD: {k} (max abs err)", v, v < 1e-4)


def check_distances():
    rng = np.random.default_rng(5)
    worst = 0.0
    for trial in range(200):
        a = rng.normal(0, 0.3, 3)
        b = a + rng.normal(0, 0.3, 3)
        r = 0.05
        c = rng.normal(0, 0.3, 3)
        R = M.rpy_to_R(rng.uniform(-np.pi, np.pi, 3))
        half = rng.uniform(0.05, 0.3, 3)
        d, x, g = geo.capsule_obstacle(a, b, r, 0, c, R, half, 0.0, 0.0, np.zeros(3), 0.0)
        ts = np.linspace(0, 1, 4001)
        pts = a + ts[:, None] * (b - a)
        sds = np.array([geo.point_box_sd(p, c, R, half)[0] for p in pts])
        brute = sds.min() - r
        if brute < geo.FAR:
            worst = max(worst, abs(d - brute))
        # cylinder
        d2, _, _ = geo.capsule_obstacle(a, b, r, 1, c, np.eye(3), half, 0.2, 0.3, np.zeros(3), 0.0)
        sds2 = np.array([geo.point_cyl_sd(p, c, 0.2, 0.3)[0] for p in pts])
        if sds2.min() - r < geo.FAR:
            worst = max(worst, abs(d2 - (sds2.min() - r)))
        # segment-segment
        p2 = rng.normal(0, 0.3, 3)
        q2 = p2 + rng.normal(0, 0.3, 3)
        dd, c1, c2 = geo.seg_seg(a, b, p2, q2)
        pts2 = p2 + ts[::8, None] * (q2 - p2)
        brute = np.min(np.linalg.norm(pts[::8, None, :] - pts2[None, :, :], axis=2))
        worst = max(worst, dd - brute if dd > brute else 0.0)
        if brute - dd > 1e-3:
            worst = max(worst, brute - dd)
    rec("distances vs brute-force sampling (max abs err, sampling 1e-3)", worst, worst < 1e-3)


if __name__ == "__main__":
    check_fatigue()
    check_fatigue_grad()
    check_pchip()
    check_statics()
    check_nlp_jacobians()
    check_distances()
    here = os.path.dirname(os.path.abspath(__file__))
    os.makedirs(os.path.join(here, "results"), exist_ok=True)
    with open(os.path.join(here, "results", "verification.json"), "w") as fh:
        json.dump(OUT, fh, indent=1)
    print("all ok" if all(v["ok"] for v in OUT.values()) else "SOME CHECKS FAILED")
