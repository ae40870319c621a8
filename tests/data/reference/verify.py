#!/usr/bin/env python3
"""Self-checks of the reference implementation; writes results/verification.json (or --out FILE).

1. fatigue: closed-form steps vs numerical ODE integration (scipy solve_ivp, rtol 1e-12), and a
   whole schedule (3 cycles of a task) integrated numerically vs the step-by-step closed forms;
2. fatigue gradients: forward-mode/complex-step derivatives vs central finite differences;
3. PCHIP: our implementation vs scipy.interpolate.PchipInterpolator (values and slopes);
4. statics: unactuated (pelvis) torques ~ 0 after the ground split; the split reproduces the
   ground wrench; d(sum tau_act^2)/d lambda = 0; holding torques vs an independent computation
   (finite differences of the potential energy plus J^T F from finite differences of positions);
4b. the internal wrench and the soles (steps 4-5 of the split), recomputed here with Jacobians
   from finite differences: (a) no pelvis torque, forces and moments balance; (b) w* minimises
   sum tau_act^2 (no perturbation lowers it), lambda re-solved optimally when alpha < 1; (c) the
   reported centres of pressure stay within their soles (or do not move outward), a bound is
   active when alpha < 1; (d) the reported per-foot wrench equals the applied one;
5. NLP Jacobians (hands, feet, torque identity, clearances, balance) vs finite differences;
6. distances vs brute-force sampling;
8. posture zones (25 rows) and gaze: angles on hand-built postures, limits, holds, Jacobians;
   the pelvis heading f from its hip axis (statement of 2026-12-06, third revision: trunk
   inclination, side bending and turn rows), its fallbacks, a listed and tilted pelvis, and the
   trunk inclination's continuity as the pelvis's tilt passes 90 deg; the trunk's turn against
   the feet (rows 24-25) vs frame yaws, an analytic Jacobian and 5-point differences at 40 random
   postures, its sign on fixed feet, and tilted pelvises (a stoop about the hip axis turns
   nothing);
9. held objects: the arms (links on one hand's path to the root only), the held-box pairs per
   distinct phase, their distances vs brute-force sampling and Jacobian rows vs finite
   differences, and the feasibility report (a box on the trunk violates, one at a hand does not);
10. a free hand's upper arm (statement of 2026-12-07, session 15): the arm row of a hand the
   phase gives no target limited to min(hold's limit, 10 deg) (shelf, bench_assembly: the left;
   shelf_two_hands: neither), the row's value at and past it, both limits in the evaluation;
11. capacity (statement section 4, option --capacity): the rows vs a brute-force replay of every
   cycle, and their Jacobian vs central finite differences (joint and per-phase NLP).
"""
import json
import math
import os
import sys

import numpy as np
import pinocchio as pin
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
        for _qis, pc in h["curves"]:
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


def check_plus_curves():
    """Curves keyed on a sum of joint angles (`plus:`, statement §2 "Strength"): the MVC gradient
    vs central differences at random postures, the value depending on the sum only, and the
    trunk extensors of a P50 man against Chaffin et al. Table 4.5 (288 / 232 / 171 N m at a trunk
    inclination of 20 / 40 / 60 deg)."""
    import math
    import yaml
    here = os.path.dirname(os.path.abspath(__file__))
    spath = os.path.join(M.INPUTS, "worker.strength.yaml")
    with open(spath) as fh:
        st = yaml.safe_load(fh)
    plus_curves = [(e["joint"], e["direction"], c) for e in st["half_joints"]
                   for c in (e.get("posture") or []) if c.get("plus")]
    body = M.Body(os.path.join(M.INPUTS, "worker.urdf"), spath, "male", 50, M.G_DEFAULT)
    hi = body.half_names.index("lumbar_flexion-")
    qidx = body.qidx
    iL, iP = qidx["lumbar_flexion"], qidx["pelvis_tilt"]
    ok_struct = (any(j == "lumbar_flexion" and d == "-" and c["joint"] == "lumbar_flexion"
                     and list(c["plus"]) == ["pelvis_tilt"] for j, d, c in plus_curves)
                 and sorted(body.half[hi]["curves"][0][0].tolist()) == sorted([iL, iP]))
    # gradient vs central differences, random postures inside the limits (trunk inclination
    # spread over the whole table), both sexes' bodies are the same code path
    rng = np.random.default_rng(11)
    lo = np.where(np.isfinite(body.lower), body.lower, -1.0)
    up = np.where(np.isfinite(body.upper), body.upper, 1.0)
    worst = 0.0
    worst_sum = 0.0
    h = 1e-7
    for _ in range(40):
        q = lo + (up - lo) * (0.05 + 0.9 * rng.random(body.nq))
        q[iL] = math.radians(rng.uniform(-22, 75))
        q[iP] = math.radians(rng.uniform(-25, 40))
        mv, G = body.mvc(q, with_grad=True)
        for i in range(body.nq):
            qp = q.copy()
            qp[i] += h
            qm = q.copy()
            qm[i] -= h
            fd = (body.mvc(qp)[0] - body.mvc(qm)[0]) / (2 * h)
            worst = max(worst, float(np.max(np.abs(fd - G[:, i]) / (np.abs(mv) + 1.0))))
        # the extensors' value depends on lumbar + pelvis only through the sum
        q2 = q.copy()
        s_ = q[iL] + q[iP]
        q2[iL], q2[iP] = 0.3 * s_, 0.7 * s_
        worst_sum = max(worst_sum, abs(body.mvc(q2)[0][hi] - mv[hi]))
    gL, gP = G[hi, iL], G[hi, iP]
    rec("plus-keyed curve (trunk extensors: lumbar_flexion + pelvis_tilt): MVC gradient vs "
        "central FD, 40 postures (max err / (|MVC| + 1)); value a function of the sum [N m]",
        dict(grad=worst, sum_only=worst_sum, structure=ok_struct,
             last_dlumbar=float(gL), last_dpelvis=float(gP)),
        ok_struct and worst < 1e-6 and worst_sum < 1e-9 and gL == gP)
    # lumbar 10 deg + pelvis 10 deg == lumbar 20 deg + pelvis 0 deg; P50 man vs Chaffin Table 4.5
    q0 = np.zeros(body.nq)
    qa = q0.copy()
    qa[iL], qa[iP] = math.radians(10), math.radians(10)
    qb = q0.copy()
    qb[iL] = math.radians(20)
    va, vb = body.mvc(qa)[0][hi], body.mvc(qb)[0][hi]
    chaffin = {}
    worst_c = 0.0
    for deg, ref in ((20, 288.0), (40, 232.0), (60, 171.0)):
        for split in (0.0, 0.5, 1.0):       # all on the lumbar, half/half, all on the pelvis
            q = q0.copy()
            q[iL], q[iP] = math.radians(deg * (1 - split)), math.radians(deg * split)
            v = float(body.mvc(q)[0][hi])
            chaffin[f"{deg} deg (pelvis share {split})"] = v
            worst_c = max(worst_c, abs(v - ref))
    rec("plus-keyed curve: MVC(lumbar 10, pelvis 10 deg) = MVC(lumbar 20, pelvis 0 deg); P50 man's "
        "trunk extensors at trunk inclination 20/40/60 deg = 288/232/171 N m (Chaffin et al. "
        "Table 4.5) within 0.1",
        dict(mvc_10_10=float(va), mvc_20_0=float(vb), diff=float(abs(va - vb)), chaffin=chaffin,
             max_abs_err=worst_c),
        abs(va - vb) < 1e-12 and worst_c < 0.1)


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


# ----------------------------------------------------------------------------------------------
# Steps 4-5 of the ground split (internal wrench, soles bounding the moments), checked with
# quantities recomputed here: link masses and positions from forward kinematics, the soles from the
# URDF text, foot Jacobians from finite differences of positions and rotations (no Pinocchio
# Jacobians), the actuated set from the strength file.
# ----------------------------------------------------------------------------------------------
def _soles_from_urdf(path):
    """Sole of each foot: bottom face of the link's first <collision> box (centre in the link
    frame, half-length along x, half-width along y)."""
    import xml.etree.ElementTree as ET
    root = ET.parse(path).getroot()
    out = {}
    for link in root.findall("link"):
        if link.get("name") not in ("l_foot", "r_foot"):
            continue
        col = link.findall("collision")[0]
        o = col.find("origin")
        xyz = np.array([float(v) for v in o.get("xyz", "0 0 0").split()])
        assert o.get("rpy") in (None, "0 0 0"), "sole boxes are axis-aligned with their links here"
        size = np.array([float(v) for v in col.find("geometry").find("box").get("size").split()])
        out[link.get("name")] = (xyz - np.array([0, 0, size[2] / 2]), size[0] / 2, size[1] / 2)
    return out


def _fd_frame_jacobians(body, q, fid, h=1e-6):
    """Positional Jacobian of the frame origin and angular Jacobian (world axes) by central
    differences of the frame placement."""
    import pinocchio as pin
    m, d = body.model, body.data

    def pose(qq):
        pin.forwardKinematics(m, d, qq)
        pin.updateFramePlacements(m, d)
        return d.oMf[fid].translation.copy(), d.oMf[fid].rotation.copy()

    o0, R0 = pose(q)
    Jo = np.zeros((3, body.nq))
    Jw = np.zeros((3, body.nq))
    for i in range(body.nq):
        qp = q.copy()
        qp[i] += h
        qm = q.copy()
        qm[i] -= h
        op, Rp = pose(qp)
        om, Rm = pose(qm)
        Jo[:, i] = (op - om) / (2 * h)
        W = (Rp - Rm) / (2 * h) @ R0.T
        Jw[:, i] = (W[2, 1] - W[1, 2]) / 2, (W[0, 2] - W[2, 0]) / 2, (W[1, 0] - W[0, 1]) / 2
    pose(q)
    return o0, R0, Jo, Jw


def _ground_wrench(body, q, FR, FL):
    """-(resultant of gravity and the hand forces) and its moment about the world origin."""
    import pinocchio as pin
    m, d = body.model, body.data
    pin.forwardKinematics(m, d, q)
    pin.updateFramePlacements(m, d)
    g = body.gravity
    F = np.zeros(3)
    Mo = np.zeros(3)
    for j in range(1, m.njoints):
        I = m.inertias[j]
        if I.mass > 0:
            x = d.oMi[j].act(I.lever)
            F += I.mass * g
            Mo += np.cross(x, I.mass * g)
    for hand, Fh in (("r_hand_grip", FR), ("l_hand_grip", FL)):
        x = d.oMf[m.getFrameId(hand)].translation
        F += Fh
        Mo += np.cross(x, Fh)
    return -F, -Mo


def check_internal_wrench():
    import yaml
    rng = np.random.default_rng(2024)
    sig = {"l_foot": 1.0, "r_foot": -1.0}
    hand_loads = [("none", np.zeros(3), np.zeros(3)),
                  ("right 40 N down", np.array([0, 0, -40.0]), np.zeros(3)),
                  ("both 60 N forward", np.array([60.0, 0, 0]), np.array([60.0, 0, 0])),
                  ("left 80 N sideways", np.zeros(3), np.array([0, 80.0, 0])),
                  ("mixed", np.array([0, -50.0, 30.0]), np.array([20.0, 0, -60.0]))]
    worst = dict(unact=0.0, force=0.0, moment=0.0, opt_star=0.0, opt_final=0.0, grad_star=0.0,
                 grad_lam=0.0, wstar=0.0, sole=0.0, outward=0.0, active=0.0, wrench=0.0,
                 wrench_total=0.0, moments_scaled=0.0)
    n = dict(cases=0, alpha1=0, alpha_mid=0, alpha0_sole=0, alpha0_unloaded=0, started_outside=0)
    for key in ("shelf", "bench_assembly"):
        t = M.load_task(key)
        b = t.body
        soles = _soles_from_urdf(b.urdf_path)
        strength = os.path.splitext(b.urdf_path)[0] + ".strength.yaml"
        if not os.path.exists(strength):
            strength = os.path.join(os.path.dirname(b.urdf_path), "worker.strength.yaml")
        with open(strength) as fh:
            unact = set(yaml.safe_load(fh)["unactuated"])
        act = np.array([i for i, nm in enumerate(b.joint_names) if nm not in unact])
        unact_i = np.array([i for i, nm in enumerate(b.joint_names) if nm in unact])
        pr = M.Problem(t)
        nlp = JointNLP(pr)
        postures = []
        fams = list(S.FAMILIES.values())
        for trial in range(8):
            fam = fams[rng.integers(len(fams))]
            postures.append(S.ik_project(nlp.pm[0], S.template(b, t.rest_q, fam, rng)))
        for trial in range(4):
            # random actuated joints within limits, pelvis at rest (the feet are then anywhere)
            q = t.rest_q.copy()
            lo, hi = np.maximum(b.lower[act], -2.0), np.minimum(b.upper[act], 2.0)
            q[act] = lo + rng.random(len(act)) * (hi - lo)
            postures.append(q)
        for q in postures:
            feet = {}
            for foot in ("l_foot", "r_foot"):
                o, R, Jo, Jw = _fd_frame_jacobians(b, q, b.fid[foot])
                cen, au, av = soles[foot]
                c = o + R @ cen
                u = R[:2, 0] / np.linalg.norm(R[:2, 0])
                v = R[:2, 1] / np.linalg.norm(R[:2, 1])
                feet[foot] = dict(o=o, c=c, u=u, v=v, au=au, av=av, Jo=Jo, Jw=Jw)
            dLR = (feet["l_foot"]["c"] - feet["r_foot"]["c"])[:2]
            e = np.array([dLR[0], dLR[1], 0.0]) / np.linalg.norm(dLR)
            for lname, FR, FL in hand_loads:
                st = M.statics(b, q, FR, FL, details=True)
                n["cases"] += 1
                tau = st["tau"]
                Fg, Mg = _ground_wrench(b, q, FR, FL)
                # (a) unactuated torques zero; the feet's loads balance the ground wrench
                worst["unact"] = max(worst["unact"], float(np.max(np.abs(tau[unact_i]))))
                Fs = sum(st["foot_loads"][f][1] for f in feet)
                Ms = sum(np.cross(st["foot_loads"][f][0], st["foot_loads"][f][1]) + st["foot_loads"][f][2]
                         for f in feet)
                worst["force"] = max(worst["force"], float(np.max(np.abs(Fs - Fg))))
                worst["moment"] = max(worst["moment"], float(np.max(np.abs(Ms - Mg))))
                # internal-wrench columns from the finite-difference Jacobians
                cols = np.zeros((b.nq, 3))
                for f, ft in feet.items():
                    pi = st["foot_loads"][f][0]
                    r = pi - ft["o"]
                    Jp = ft["Jo"] - np.cross(r[:, None], ft["Jw"], axis=0)   # J_p = J_o - [r]x J_w
                    cols[:, 0] -= sig[f] * (Jp.T @ e)
                    cols[:, 1] -= sig[f] * ft["Jw"][0]
                    cols[:, 2] -= sig[f] * ft["Jw"][1]
                Ga = cols[act]
                w = np.array([st["lam"], st["m_x"], st["m_y"]])
                tau0a = tau[act] - Ga @ w            # the torques before the internal wrench
                ta_star = tau0a + Ga @ st["w_star"]

                def sumsq(wv):
                    r_ = tau0a + Ga @ wv
                    return float(r_ @ r_)

                # (b) w* minimises sum tau_act^2: no direction lowers it (unit-scaled steps)
                f_star = sumsq(st["w_star"])
                dirs = list(np.vstack([np.eye(3), -np.eye(3)])) + list(rng.normal(size=(12, 3)))
                for dvec in dirs:
                    dvec = dvec / np.linalg.norm(dvec)
                    for eps in (1e-3, 1e-1, 1.0):
                        dec = f_star - sumsq(st["w_star"] + eps * dvec * np.array([10.0, 1.0, 1.0]))
                        worst["opt_star"] = max(worst["opt_star"], dec / max(f_star, 1.0))
                gs = Ga.T @ ta_star / (np.linalg.norm(Ga, axis=0) * max(np.linalg.norm(ta_star), 1e-12))
                worst["grad_star"] = max(worst["grad_star"], float(np.max(np.abs(gs))))
                # w* against an independent least-squares solve (well-conditioned G only)
                if np.linalg.cond(Ga) < 1e6:
                    wl = np.linalg.lstsq(Ga, -tau0a, rcond=None)[0]
                    worst["wstar"] = max(worst["wstar"], float(np.max(np.abs(wl - st["w_star"]) /
                                                                    (np.abs(wl) + 1.0))))
                alpha = st["alpha"]
                ms = st["w_star"][1:]
                worst["moments_scaled"] = max(worst["moments_scaled"],
                                              float(np.max(np.abs(w[1:] - alpha * ms))))
                if alpha == 1.0:
                    n["alpha1"] += 1
                    for dvec in dirs:
                        dvec = dvec / np.linalg.norm(dvec)
                        dec = sumsq(w) - sumsq(w + 1e-2 * dvec * np.array([10.0, 1.0, 1.0]))
                        worst["opt_final"] = max(worst["opt_final"], dec / max(sumsq(w), 1.0))
                else:
                    # lambda re-solved for the bounded moments: optimal along lambda
                    r_ = tau0a + Ga @ w
                    gl = abs(float(Ga[:, 0] @ r_)) / (np.linalg.norm(Ga[:, 0]) * max(np.linalg.norm(r_), 1e-12))
                    worst["grad_lam"] = max(worst["grad_lam"], gl)
                # (c) the reported centres of pressure within the soles (or not moved outward)
                act_ratio = 0.0
                any_unloaded = False
                for f, ft in feet.items():
                    pi = st["foot_loads"][f][0]
                    cop = st["foot_cop"][f]
                    worst["sole"] = max(worst["sole"], abs(float(cop[2])))
                    if st["foot_loads"][f][1][2] <= 0.0:
                        any_unloaded = True
                    o_h = (pi - ft["c"])[:2]
                    d_h = (cop - ft["c"])[:2]
                    for ax, half in ((ft["u"], ft["au"]), (ft["v"], ft["av"])):
                        a0 = float(o_h @ ax)
                        a1 = float(d_h @ ax)
                        if abs(a0) > half:
                            n["started_outside"] += 1
                            worst["outward"] = max(worst["outward"], abs(a1) - abs(a0))
                        else:
                            worst["sole"] = max(worst["sole"], abs(a1) - half)
                        act_ratio = max(act_ratio, abs(a1) / max(half, abs(a0)))
                if alpha < 1.0:
                    if alpha == 0.0 and any_unloaded and np.any(ms != 0.0):
                        n["alpha0_unloaded"] += 1
                    else:
                        n["alpha_mid" if alpha > 0 else "alpha0_sole"] += 1
                        worst["active"] = max(worst["active"], 1.0 - act_ratio)
                # (d) the reported per-foot wrench is the applied wrench
                Mtot = np.zeros(3)
                for f in feet:
                    pi, Fi, _ = st["foot_loads"][f]
                    share = st["s"] if f == "l_foot" else 1.0 - st["s"]
                    Mi = np.array([sig[f] * st["m_x"], sig[f] * st["m_y"], share * st["T"]])
                    cop = st["foot_cop"][f]
                    rep = np.cross(cop, Fi) + np.array([0, 0, st["foot_free_moment"][f]])
                    app = np.cross(pi, Fi) + Mi
                    worst["wrench"] = max(worst["wrench"], float(np.max(np.abs(rep - app))))
                    Mtot += rep
                worst["wrench_total"] = max(worst["wrench_total"], float(np.max(np.abs(Mtot - Mg))))
    rec(f"internal wrench: cases (postures x hand loads), alpha = 1 / 0 < alpha < 1 / alpha = 0 at a "
        f"sole bound / alpha = 0 for an unloaded foot / axes starting outside a sole",
        [n["cases"], n["alpha1"], n["alpha_mid"], n["alpha0_sole"], n["alpha0_unloaded"],
         n["started_outside"]],
        n["alpha1"] > 0 and n["alpha_mid"] > 0 and n["alpha0_sole"] + n["alpha0_unloaded"] > 0)
    rec("(a) split: max |unactuated (pelvis) torque| [N m]", worst["unact"], worst["unact"] < 1e-8)
    rec("(a) split: feet forces = ground force (independent resultant) [N]", worst["force"],
        worst["force"] < 1e-9)
    rec("(a) split: feet moments = ground moment about the origin (independent) [N m]",
        worst["moment"], worst["moment"] < 1e-9)
    rec("(b) w*: no perturbation of (lambda, m_x, m_y) lowers sum tau_act^2 (max relative decrease)",
        worst["opt_star"], worst["opt_star"] < 1e-9)
    rec("(b) w*: |G^T tau| / (|g_k| |tau|) with FD Jacobians", worst["grad_star"], worst["grad_star"] < 1e-7)
    rec("(b) w* vs numpy.linalg.lstsq on the FD-Jacobian G (max rel err)", worst["wstar"], worst["wstar"] < 1e-5)
    rec("(b) alpha = 1: the final w is not improved by any perturbation (max relative decrease)",
        worst["opt_final"], worst["opt_final"] < 1e-9)
    rec("(b) alpha < 1: lambda optimal for the bounded moments, |g_lam . tau| / (|g_lam| |tau|)",
        worst["grad_lam"], worst["grad_lam"] < 1e-7)
    rec("(b) final moments = alpha (m*_x, m*_y) (max abs err)", worst["moments_scaled"],
        worst["moments_scaled"] < 1e-12)
    rec("(c) reported centres of pressure within the soles [m beyond; also |z|]", worst["sole"],
        worst["sole"] < 1e-9)
    rec("(c) a centre of pressure starting outside its sole did not move outward [m]",
        worst["outward"], worst["outward"] < 1e-9)
    rec("(c) alpha < 1 (all feet loaded): a sole bound is active (1 - max |coord|/bound)",
        worst["active"], worst["active"] < 1e-9)
    rec("(d) per-foot reported wrench (force at the CoP + free moment) = applied wrench [N m]",
        worst["wrench"], worst["wrench"] < 1e-9)
    rec("(d) the reported wrenches sum to the ground moment [N m]", worst["wrench_total"],
        worst["wrench_total"] < 1e-9)


def check_nlp_jacobians():
    worst = {}
    alphas = []
    # (lean_back and twist_left give postures whose sole bound is active with 0 < alpha < 1)
    for key, fams in (("shelf", ("stoop_mild", "lean_back")), ("pallet", ("stoop_mild",)),
                      ("bench_assembly", ("twist_left", "upright_internal_rot"))):
        t = M.load_task(key)
        pr = M.Problem(t)
        nlp = JointNLP(pr)
        rng = np.random.default_rng(11)
        for gi, fam in ((gi, fam) for fam in fams for gi in range(t.P)):
            pm = nlp.pm[gi]
            q = S.ik_project(pm, S.template(t.body, t.rest_q, S.FAMILIES[fam], rng))
            # stay 1e-4 inside the joint limits: the strength curves are held constant beyond
            # their tables, so a central difference straddling a table end (often a joint limit)
            # is not a derivative
            q = np.clip(q, t.body.lower + 1e-4, t.body.upper - 1e-4)
            f = pm.loads_from_q(q) + 0.01
            pm.active = np.arange(pm.n_dist)
            pm._cache_key = None
            v, Jq, Jf = pm.eq(q, f, jac=True)
            vi, Ji = pm.ineq(q, jac=True)
            # the statics' derivative the NLP uses (central differences, FD_STEP) against central
            # differences of the new split at a 10x larger step (a kink of alpha between them
            # would show); alpha of the posture recorded to show which branch was exercised
            st = M.statics(t.body, q, pm.FR, pm.FL, details=True)
            alphas.append(round(float(st["alpha"]), 4))
            dtau = pm.evaluate(q, True)["dtau"]
            h2 = 1e-5
            fd2 = np.zeros_like(dtau)
            for i in range(len(q)):
                qp = q.copy()
                qp[i] += h2
                qm = q.copy()
                qm[i] -= h2
                fd2[:, i] = (pm._statics(qp)[0] - pm._statics(qm)[0]) / (2 * h2)
            worst["statics torques d tau/dq vs FD step 1e-5"] = max(
                worst.get("statics torques d tau/dq vs FD step 1e-5", 0.0), float(np.max(np.abs(dtau - fd2))))
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
    rec("NLP Jacobian postures: alpha of the sole bound (shelf, pallet, bench_assembly phases)", alphas,
        any(0.0 < a < 1.0 for a in alphas))
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


# ----------------------------------------------------------------------------------------------
# 7. obstacles oriented by rpy_rad (task-format.md), against a hand computation
# ----------------------------------------------------------------------------------------------
def _hand_rpy(r, p, y):
    """URDF convention written out: R = Rz(y) Ry(p) Rx(r)."""
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    Ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return Rz @ Ry @ Rx


def check_rotated_box():
    t = M.load_task("shelf")
    raw = {"workstation": {"obstacles": [
        {"name": "yawed", "box": {"size_m": [0.4, 0.2, 0.2]}, "position_m": [1.0, 0.0, 1.0],
         "rpy_rad": [0.0, 0.0, np.pi / 4]},
        {"name": "tilted", "box": {"size_m": [0.4, 0.2, 0.2]}, "position_m": [1.0, 0.0, 1.0],
         "rpy_rad": [0.3, -0.5, 1.1]}]}}
    t._build_obstacles(raw)
    ob, ob2 = t.obstacles
    errs = []
    # (a) yaw 45 deg: a point 0.5 m from the centre along the box's own x axis is 0.5 - 0.2 away
    c = np.array([1.0, 0.0, 1.0])
    p = c + 0.5 * np.array([np.cos(np.pi / 4), np.sin(np.pi / 4), 0.0])
    d, _ = geo.point_box_sd(p, ob["center"], ob["R"], ob["half"])
    errs.append(abs(d - 0.3))
    # (b) the same box, a point 0.5 m along WORLD x: in box axes (0.5 cos45, -0.5 sin45, 0),
    # outside the half-extents (0.2, 0.1) by (0.15355, 0.25355): distance their norm
    p = c + np.array([0.5, 0.0, 0.0])
    d, _ = geo.point_box_sd(p, ob["center"], ob["R"], ob["half"])
    hand = np.hypot(0.5 * np.sqrt(0.5) - 0.2, 0.5 * np.sqrt(0.5) - 0.1)
    errs.append(abs(d - hand))
    # (c) inside: the centre is 0.1 deep (smallest half-extent) -> signed distance -0.1
    d, _ = geo.point_box_sd(c, ob["center"], ob["R"], ob["half"])
    errs.append(abs(d + 0.1))
    # (d) roll-pitch-yaw: the rotation equals Rz(y) Ry(p) Rx(r) written out, and a point at box
    # coordinates (0.3, 0.25, -0.05) is at distance hypot(0.1, 0.15) from it
    Rh = _hand_rpy(0.3, -0.5, 1.1)
    errs.append(float(np.max(np.abs(ob2["R"] - Rh))))
    p = c + Rh @ np.array([0.3, 0.25, -0.05])
    d, _ = geo.point_box_sd(p, ob2["center"], ob2["R"], ob2["half"])
    errs.append(abs(d - np.hypot(0.1, 0.15)))
    # (e) a zero-length capsule (radius 0.02) at that point: the capsule-obstacle distance
    dd, _, _ = geo.capsule_obstacle(p, p, 0.02, 0, ob2["center"], ob2["R"], ob2["half"], 0.0, 0.0,
                                    np.zeros(3), 0.0)
    errs.append(abs(dd - (np.hypot(0.1, 0.15) - 0.02)))
    # (f) rpy_deg is refused (not a field of task-format.md)
    refused = False
    try:
        t._build_obstacles({"workstation": {"obstacles": [
            {"name": "x", "box": {"size_m": [1, 1, 1]}, "rpy_deg": [0, 0, 45]}]}})
    except ValueError:
        refused = True
    t._build_obstacles(t.raw)
    rec("rotated box obstacle (rpy_rad) vs hand computation (max abs err)", max(errs),
        max(errs) < 1e-12 and refused)


# ----------------------------------------------------------------------------------------------
# 8. posture zones and gaze (statement section 4)
# ----------------------------------------------------------------------------------------------
def _R(axis, deg):
    a = np.radians(deg)
    c, s = np.cos(a), np.sin(a)
    if axis == "x":
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == "y":
        return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def check_zone_angles():
    from reference import zones as Z
    I = np.eye(3)
    down = np.array([0.0, 0.0, -1.0])
    nowr = [(0.0, 0.0), (0.0, 0.0)]
    names = Z.ROW_NAMES
    worst = 0.0
    cases = []

    def expect(label, got, exp):
        nonlocal worst
        e = np.zeros(Z.NROW)
        for k, v in exp.items():
            e[names.index(k)] = np.radians(v)
        # rows come in +/- pairs: fill the mirrored row
        pairs = [(0, 1), (2, 3), (4, 5), (8, 9), (11, 12), (13, 14), (15, 16), (17, 18), (19, 20),
                 (21, 22), (23, 24)]
        for i, j in pairs:
            if e[i] == 0 and e[j] != 0:
                e[i] = -e[j]
            elif e[j] == 0 and e[i] != 0:
                e[j] = -e[i]
        err = float(np.max(np.abs(got - e)))
        worst = max(worst, err)
        cases.append((label, np.degrees(err)))

    # trunk flexed 30 deg forward (pelvis level): trunk inclination 30; the head and the hanging
    # arms go with the trunk (head inclination 30, arm elevation 30); neck angles 0
    RT = _R("y", 30)
    expect("trunk flexed 30", Z.angles_from_frames(I, RT, RT, RT @ down, RT @ down, 0.0, nowr),
           {"trunk inclination (forward)": 30, "head inclination (forward)": 30,
            "right upper-arm elevation": 30, "left upper-arm elevation": 30})
    # trunk leaning back 10
    RT = _R("y", -10)
    expect("trunk back 10", Z.angles_from_frames(I, RT, RT, down, down, 0.0, nowr),
           {"trunk leaning back": 10, "head tilted back": 10})
    # trunk bent 15 deg to the left (rotation about -x tilts z towards +y)
    RT = _R("x", -15)
    expect("trunk side bend left 15", Z.angles_from_frames(I, RT, RT, down, down, 0.0, nowr),
           {"trunk side bending left": 15})
    # trunk twisted 20 deg left while flexed 30: R_T = Ry(30) Rz(20): inclination 30, twist 20
    RT = _R("y", 30) @ _R("z", 20)
    expect("trunk flexed 30 + twist 20", Z.angles_from_frames(I, RT, I, down, down, 0.0, nowr),
           {"trunk inclination (forward)": 30, "trunk twist left": 20,
            "trunk turn against the feet left": 20, "neck flexion": -30})
    # the same with feet given: the feet point 30 and 10 deg to the right (mean heading -20): the
    # pelvis is turned 20 deg left against them, the turn is 20 + 20
    fx = [_R("z", -30) @ [1.0, 0, 0], _R("z", -10) @ [1.0, 0, 0]]
    expect("twist 20, feet at -30/-10", Z.angles_from_frames(I, RT, I, down, down, 0.0, nowr, fx),
           {"trunk inclination (forward)": 30, "trunk twist left": 20,
            "trunk turn against the feet left": 40, "neck flexion": -30})
    # a foot whose x axis is vertical is left out: the other foot (heading +25) alone sets h
    fx = [np.array([0.0, 0.0, 1.0]), _R("z", 25) @ _R("y", 40) @ [1.0, 0, 0]]
    expect("one foot vertical, other heading 25", Z.angles_from_frames(I, I, I, down, down, 0.0, nowr, fx),
           {"trunk turn against the feet right": 25})
    # feet pointing opposite ways: |h| < 1e-9, the pelvis turn is 0 (the row is the twist)
    fx = [np.array([1.0, 0, 0]), np.array([-1.0, 0, 0])]
    expect("feet opposed", Z.angles_from_frames(I, RT, I, down, down, 0.0, nowr, fx),
           {"trunk inclination (forward)": 30, "trunk twist left": 20,
            "trunk turn against the feet left": 20, "neck flexion": -30})
    # the whole body turned 40 deg about the vertical (pelvis and trunk): nothing changes
    RP = _R("z", 40)
    expect("body turned 40", Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr), {})
    # head turned 50 deg left and tilted back 20 deg in its own plane: R_H = Rz(50) Ry(-20)
    # (trunk upright): head back 20, neck flexion -20, neck side bending 0
    RH = _R("z", 50) @ _R("y", -20)
    expect("head turned 50, back 20", Z.angles_from_frames(I, I, RH, down, down, np.radians(50), nowr),
           {"head tilted back": 20, "neck flexion": -20, "neck twist left": 50})
    # head bent 12 deg to the left against an upright trunk
    RH = _R("x", -12)
    expect("neck side bend left 12", Z.angles_from_frames(I, I, RH, down, down, 0.0, nowr),
           {"neck side bending left": 12})
    # arm raised forward to horizontal: elevation 90; the other abducted 45
    expect("arms 90 / 45", Z.angles_from_frames(I, I, I, np.array([1.0, 0, 0]),
                                                 np.array([0.0, np.sqrt(0.5), -np.sqrt(0.5)]), 0.0, nowr),
           {"right upper-arm elevation": 90, "left upper-arm elevation": 45})
    # wrists: joints directly
    expect("wrists", Z.angles_from_frames(I, I, I, down, down, 0.0,
                                          [(np.radians(17), np.radians(-8)), (np.radians(-25), np.radians(6))]),
           {"right wrist flexion": 17, "right wrist radial deviation": -8, "left wrist flexion": -25,
            "left wrist radial deviation": 6})
    # pelvis heading from the hip axis (statement of 2026-12-06, second revision): the pelvis
    # (and trunk and head with it) tilted 60 deg forward about its hip axis, feet straight ahead:
    # trunk and head inclination 60, no turn
    RP = _R("y", 60)
    fx0 = [np.array([1.0, 0, 0]), np.array([1.0, 0, 0])]
    expect("pelvis tilted 60, feet ahead", Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr, fx0),
           {"trunk inclination (forward)": 60, "head inclination (forward)": 60})
    # the same pelvis turned 25 deg left on the feet (R_P = Rz(25) Ry(60)): turn left 25
    RP = _R("z", 25) @ _R("y", 60)
    expect("pelvis tilted 60 turned 25, feet ahead", Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr, fx0),
           {"trunk inclination (forward)": 60, "head inclination (forward)": 60,
            "trunk turn against the feet left": 25})
    # ... and without foot links the pelvis's turn is 0: the row is the twist (0)
    expect("pelvis tilted 60 turned 25, no feet", Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr),
           {"trunk inclination (forward)": 60, "head inclination (forward)": 60})
    # the pelvis heading f from its hip axis for the trunk inclination and side bending too
    # (statement of 2026-12-06, third revision). The worker's pelvis chain is
    # Rz(rotation) Rx(-list) Ry(tilt). Listed 20 deg, tilted 60 deg, the trunk continuing the
    # pelvis: the hip axis R_P y = (0, cos 20, -sin 20) gives f = x, so with a = R_P z =
    # (sin 60, sin 20 cos 60, cos 20 cos 60): inclination atan2(sin 60, cos 20 cos 60) = 61.518 deg,
    # side bending left asin(sin 20 cos 60) = 9.846 deg (the x-axis heading, turned by
    # -atan(sin 20 tan 60) = -30.6 deg, gave other values: reported below); the head continuing the
    # trunk: head inclination the same; the same turned -35 deg about the vertical: the same angles
    s20, c20 = math.sin(math.radians(20)), math.cos(math.radians(20))
    s60, c60 = math.sin(math.radians(60)), math.cos(math.radians(60))
    incl_exp = math.degrees(math.atan2(s60, c20 * c60))
    side_exp = math.degrees(math.asin(s20 * c60))
    x_axis_would_give = {}
    for rot in (0.0, -35.0):
        RP = _R("z", rot) @ _R("x", -20) @ _R("y", 60)
        expect(f"pelvis listed 20, tilted 60, turned {rot:g}, trunk continuing it: f from the hip axis",
               Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr),
               {"trunk inclination (forward)": incl_exp, "trunk side bending left": side_exp,
                "head inclination (forward)": incl_exp})
        # what the previous f (R_P x on the floor) gave, for the report
        fo = Z.x_axis_heading(RP)
        lo = np.cross([0.0, 0.0, 1.0], fo)
        a_ = RP[:, 2]
        x_axis_would_give[f"turned {rot:g}"] = dict(
            inclination_deg=math.degrees(math.atan2(float(a_ @ fo), float(a_[2]))),
            side_bending_deg=math.degrees(math.asin(float(a_ @ lo))))
    # tilted past vertical: the trunk inclination is the tilt, continuous across 90 deg (the
    # x-axis heading turned over there and the inclination jumped by about 180 deg)
    incl_tilt = {}
    for tilt in (89.9, 90.0, 90.1, 95.0):
        RP = _R("y", tilt)
        th_ = Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr, fx0)
        incl_tilt[tilt] = math.degrees(th_[0])
        expect(f"pelvis tilted {tilt:g}, trunk continuing it", th_,
               {"trunk inclination (forward)": tilt, "head inclination (forward)": tilt})
    jump = incl_tilt[90.1] - incl_tilt[89.9]
    worst = max(worst, abs(math.radians(jump - 0.2)))
    cases.append(("inclination(tilt 90.1) - inclination(tilt 89.9) = 0.2 deg", abs(jump - 0.2)))
    # listed 20 deg and tilted through 90: atan2(sin t, cos 20 cos t), continuous
    incl_list = {}
    for tilt in (89.9, 90.1, 95.0):
        RP = _R("x", -20) @ _R("y", tilt)
        th_ = Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr)
        incl_list[tilt] = math.degrees(th_[0])
        e_ = math.degrees(math.atan2(math.sin(math.radians(tilt)), c20 * math.cos(math.radians(tilt))))
        worst = max(worst, abs(th_[0] - math.radians(e_)))
        cases.append((f"listed 20, tilted {tilt:g}: inclination atan2(sin t, cos 20 cos t) = {e_:.6f}",
                       abs(math.degrees(th_[0]) - e_)))
    x_axis_tilt = {}
    for tilt in (89.9, 90.1):
        RP = _R("y", tilt)
        fo = Z.x_axis_heading(RP)
        x_axis_tilt[tilt] = math.degrees(math.atan2(float(RP[:, 2] @ fo), float(RP[2, 2])))
    # the fallbacks: hip axis vertical (listed 90 deg, heading -20): R_P x on the floor; both
    # axes vertical (not a rotation; only the code path): world x
    g = Z.hip_axis_heading(_R("z", -20) @ _R("x", 90))
    err = float(np.max(np.abs(g - np.array([math.cos(math.radians(-20)), math.sin(math.radians(-20)), 0.0]))))
    g2 = Z.hip_axis_heading(np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [1.0, 1.0, 0.0]]))
    err = max(err, float(np.max(np.abs(g2 - np.array([1.0, 0.0, 0.0])))))
    worst = max(worst, err)
    cases.append(("f fallbacks: hip axis vertical -> R_P x on the floor; both vertical -> world x",
                  np.degrees(err)))
    # turn-row cases (f, from the hip axis, is also the turn rows' g):
    turn_cases = []
    # the worker's pelvis chain Rz(rotation) Rx(-list) Ry(tilt): listed 20 deg, tilted 60 deg, turned
    # theta = -35 deg on feet at +10/+10: the hip axis gives theta - 10 = -45 (the x axis would give
    # theta + atan(sin 20 tan 60) - 10 = -14.4); the trunk twisted a further 15 deg left: -30
    RP = _R("z", -35) @ _R("x", 20) @ _R("y", 60)
    fx10 = [_R("z", 10) @ [1.0, 0, 0]] * 2
    th_ = Z.angles_from_frames(RP, RP @ _R("z", 15), RP, down, down, 0.0, nowr, fx10)
    turn_cases.append(("listed 20, tilted 60, turned -35 on feet at +10, twist +15", th_[23], th_[24], -30.0))
    # tilted 90 deg (its x axis vertical, f falls back to world x): the hip axis still gives theta
    RP = _R("z", 40) @ _R("y", 90)
    th_ = Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr, fx0)
    turn_cases.append(("tilted 90, turned 40, feet ahead", th_[23], th_[24], 40.0))
    # listed 90 deg (the hip axis vertical): f falls back to the x axis's heading (-20)
    RP = _R("z", -20) @ _R("x", 90)
    th_ = Z.angles_from_frames(RP, RP, RP, down, down, 0.0, nowr, fx0)
    turn_cases.append(("listed 90 (hip axis vertical), heading -20, feet ahead", th_[23], th_[24], -20.0))
    for label, left, right, exp_deg in turn_cases:
        err = max(abs(left - np.radians(exp_deg)), abs(right + np.radians(exp_deg)))
        worst = max(worst, err)
        cases.append((label, np.degrees(err)))
    g = Z.hip_axis_heading(_R("z", 30) @ _R("x", -20) @ _R("y", 75))
    err = float(np.max(np.abs(g - np.array([np.cos(np.radians(30)), np.sin(np.radians(30)), 0.0]))))
    worst = max(worst, err)
    cases.append(("hip_axis_heading of Rz(30) Rx(-20) Ry(75) = (cos 30, sin 30, 0)", np.degrees(err)))
    # the same from joint space: lumbar_flexion 30 deg only on the worker
    t = M.load_task("shelf")
    zm = Z.ZoneModel(t.body)
    q = np.zeros(t.body.nq)
    q[t.body.qidx["lumbar_flexion"]] = np.radians(30)
    expect("joints: lumbar_flexion 30", zm.angles(q),
           {"trunk inclination (forward)": 30, "head inclination (forward)": 30,
            "right upper-arm elevation": 30, "left upper-arm elevation": 30})
    q = np.zeros(t.body.nq)
    q[t.body.qidx["neck_flexion"]] = np.radians(-20)
    q[t.body.qidx["r_wrist_flexion"]] = 0.3
    q[t.body.qidx["l_wrist_deviation"]] = -0.2
    expect("joints: neck_flexion -20, wrists", zm.angles(q),
           {"head tilted back": 20, "neck flexion": -20, "right wrist flexion": np.degrees(0.3),
            "left wrist radial deviation": np.degrees(-0.2)})
    q = np.zeros(t.body.nq)
    q[t.body.qidx["lumbar_axial_rotation"]] = np.radians(25)
    q[t.body.qidx["neck_axial_rotation"]] = np.radians(-30)
    expect("joints: lumbar twist 25, neck twist -30", zm.angles(q),
           {"trunk twist left": 25, "trunk turn against the feet left": 25, "neck twist right": 30})
    # joint space: the worker's pelvis listed 20 deg and tilted 60 deg, lumbar straight (the
    # trunk continues the pelvis; the frames' orientations are checked, then the expected values)
    q = np.zeros(t.body.nq)
    q[t.body.qidx["pelvis_list"]] = np.radians(20)
    q[t.body.qidx["pelvis_tilt"]] = np.radians(60)
    q[t.body.qidx["pelvis_rotation"]] = np.radians(-35)
    th_ = zm.angles(q)
    RPj = zm.data.oMf[zm.f_pelvis].rotation
    RTj = zm.data.oMf[zm.f_trunk].rotation
    chain_err = max(float(np.max(np.abs(RPj - _R("z", -35) @ _R("x", -20) @ _R("y", 60)))),
                    float(np.max(np.abs(RTj - RPj))))
    worst = max(worst, chain_err)
    cases.append(("joints: pelvis chain Rz(rotation) Rx(-list) Ry(tilt), trunk = pelvis", chain_err))
    exp_j = {"trunk inclination (forward)": incl_exp, "trunk side bending left": side_exp}
    err = max(abs(math.degrees(th_[names.index(k)]) - v) for k, v in exp_j.items())
    worst = max(worst, math.radians(err))
    cases.append(("joints: pelvis_list 20, pelvis_tilt 60, pelvis_rotation -35: inclination, side bending", err))
    for tilt in (89.9, 90.1):
        q = np.zeros(t.body.nq)
        q[t.body.qidx["pelvis_tilt"]] = np.radians(tilt)
        q[t.body.qidx["pelvis_list"]] = np.radians(20)
        incl_list[f"joints {tilt}"] = math.degrees(zm.angles(q)[0])
    jl = incl_list["joints 90.1"] - incl_list["joints 89.9"]
    cases.append(("joints: listed 20, inclination(tilt 90.1) - inclination(tilt 89.9) (deg)", jl))
    ok_cont = 0.15 < jl < 0.25 and abs(jl - (incl_list[90.1] - incl_list[89.9])) < 1e-9
    rec("zone angles on hand-built postures (max abs err, deg)",
        {"worst_deg": float(np.degrees(worst)), "cases": cases,
         "pelvis_listed_20_tilted_60": dict(inclination_deg=incl_exp, side_bending_left_deg=side_exp,
                                            x_axis_heading_would_give=x_axis_would_give),
         "inclination_across_tilt_90_deg": {str(k): v for k, v in incl_tilt.items()},
         "inclination_listed_20_across_tilt_90_deg": {str(k): v for k, v in incl_list.items()},
         "x_axis_heading_would_give_across_tilt_90_deg": {str(k): v for k, v in x_axis_tilt.items()}},
        np.degrees(worst) < 1e-9 and ok_cont)

    # limits
    L = Z.limits_for_hold
    checks = [
        (np.degrees(L(3.0)[0]), 60.0), (np.degrees(L(60.0)[0]), 60.0),
        (np.degrees(L(150.0)[0]), 40.0),           # 2.5 min: 20 + 40 (4 - 2.5)/3
        (np.degrees(L(150.0)[6]), 30.0),           # 2.5 min arm: 20 + 40 (3 - 2.5)/2
        (np.degrees(L(300.0)[0]), 20.0), (np.degrees(L(200.0)[6]), 20.0),
        (np.degrees(L(10.0)[1]), 5.0), (np.degrees(L(10.0)[8]), 85.0),
        (np.degrees(L(10.0)[10]), 25.0), (np.degrees(L(10.0)[13]), 45.0),
        (np.degrees(L(10.0)[15]), 15.0), (np.degrees(L(10.0)[17]), 10.0),
        (np.degrees(L(10.0)[23]), 10.0), (np.degrees(L(10.0)[24]), 10.0),
        (np.degrees(L(600.0)[23]), 10.0), (np.degrees(L(600.0)[24]), 10.0)]
    err = max(abs(a - b) for a, b in checks)
    err = max(err, 0.0 if (len(L(10.0)) == Z.NROW == len(Z.ROW_NAMES) == 25 and
                           Z.ROW_NAMES[23:] == ["trunk turn against the feet left",
                                                "trunk turn against the feet right"]) else 1.0)
    # the upper-arm row (cos L - cos theta)/sin L: 0 at the limit, about theta - L near it
    th = np.radians(61.0)
    Lr = np.radians(60.0)
    row = (np.cos(Lr) - np.cos(th)) / np.sin(Lr)
    err = max(err, abs(row - (th - Lr)) - 1e-4)
    rec("zone limits from the hold (max abs err, deg)", err, err < 1e-9)

    # holds: consecutive same-work runs, wrapping over the cycle's end when there is no rest
    class P:
        def __init__(self, w, d):
            self.work_key, self.duration = w, d

    class T:
        pass

    tt = T()
    tt.phases = [P("a", 10), P("a", 20), P("b", 5), P("a", 30)]
    tt.rest_s = 0.0
    h0 = Z.phase_holds(tt)
    tt.rest_s = 5.0
    h1 = Z.phase_holds(tt)
    ok = h0 == [60, 60, 5, 60] and h1 == [30, 30, 5, 30]
    rec("hold durations (no rest: wraps; with rest: does not)", {"no_rest": h0, "rest": h1}, ok)


def check_gaze_and_zone_jacobians():
    from reference import zones as Z
    out = {}
    t = M.load_task("bench_assembly")
    b = t.body
    zm = Z.ZoneModel(b)
    # eye point by hand from the URDF: head cylinder centre (0, 0, 0.12113), radius 0.0877
    q = np.zeros(b.nq)
    zm._fk(q)
    Mh = zm.data.oMf[zm.f_head]
    eye = Mh.translation + Mh.rotation @ np.array([0.8 * 0.0877, 0.0, 0.12113])
    # a point on the line of sight (15 deg down, straight ahead) -> angle 0, margin 1 - cos 15
    p_on = eye + 0.7 * np.array([np.cos(np.radians(15)), 0.0, -np.sin(np.radians(15))])
    # a point straight ahead at eye height -> angle 15 (on the cone), margin 0
    p_lvl = eye + np.array([0.5, 0.0, 0.0])
    # 40 deg below horizontal, 10 deg to the left: angle between by hand
    dv = np.array([np.cos(np.radians(40)) * np.cos(np.radians(10)),
                   np.cos(np.radians(40)) * np.sin(np.radians(10)), -np.sin(np.radians(40))])
    s = np.array([np.cos(np.radians(15)), 0.0, -np.sin(np.radians(15))])
    p_off = eye + 0.6 * dv
    v = zm.gaze_values(q, [p_on, p_lvl, p_off])
    exp = np.array([1 - np.cos(np.radians(15)), 0.0, float(s @ dv) - np.cos(np.radians(15))])
    e1 = float(np.max(np.abs(v - exp)))
    # head turned 30 deg left (neck twist): a point 30 deg left on the line of sight is on it
    q2 = q.copy()
    q2[b.qidx["neck_axial_rotation"]] = np.radians(30)
    zm._fk(q2)
    Mh2 = zm.data.oMf[zm.f_head]
    eye2 = Mh2.translation + Mh2.rotation @ np.array([0.8 * 0.0877, 0.0, 0.12113])
    p2 = eye2 + 0.5 * (_R("z", 30) @ s)
    e1 = max(e1, abs(zm.gaze_values(q2, [p2])[0] - (1 - np.cos(np.radians(15)))))
    out["gaze_values_vs_hand_max_err"] = e1
    # Jacobians (central differences, h = 1e-6) vs 5-point differences with h = 1e-4 at random
    # postures
    rng = np.random.default_rng(7)
    pr = M.Problem(t, zones=True)
    worst_g, worst_z = 0.0, 0.0
    for _ in range(5):
        qr = b.lower + rng.random(b.nq) * (b.upper - b.lower)
        qr[b.qidx["pelvis_tz"]] = 0.9
        pts = [np.array([0.45, -0.2, 1.0]), np.array([0.4, 0.3, 0.9])]
        _, Jg = zm.gaze_jac(qr, pts)
        _, Jz = zm.rows_jac(qr, pr.zone_limits[1])
        h = 1e-4
        for i in range(b.nq):
            def fg(dx):
                qq = qr.copy()
                qq[i] += dx
                return zm.gaze_values(qq, pts)

            def fz(dx):
                qq = qr.copy()
                qq[i] += dx
                return zm.rows(qq, pr.zone_limits[1])
            dg = (-fg(2 * h) + 8 * fg(h) - 8 * fg(-h) + fg(-2 * h)) / (12 * h)
            dz = (-fz(2 * h) + 8 * fz(h) - 8 * fz(-h) + fz(-2 * h)) / (12 * h)
            worst_g = max(worst_g, float(np.max(np.abs(dg - Jg[:, i]))))
            worst_z = max(worst_z, float(np.max(np.abs(dz - Jz[:, i]))))
    out["gaze_jac_max_err"] = worst_g
    out["zone_jac_max_err"] = worst_z
    rec("gaze values vs hand computation; gaze and zone Jacobians vs 5-point differences", out,
        e1 < 1e-12 and worst_g < 1e-6 and worst_z < 1e-6)
    # the NLP with zones: inequality Jacobian (zone + gaze rows, slack columns) and objective
    # gradient vs central differences
    nlp = JointNLP(pr)
    qs = [S.ik_project(nlp.pm[gi], t.rest_q) for gi in range(t.P)]
    x = S.initial_x(nlp, qs)
    S.set_active(nlp, x, 0.08)
    J = nlp.ineq_jac(x)
    g = nlp.obj_grad(x)
    worst_i, worst_o = 0.0, 0.0
    idx = list(rng.choice(len(x), 20, replace=False)) + [len(x) - 1, len(x) - 30]
    for i in idx:
        xp = x.copy()
        xp[i] += 1e-6
        xm = x.copy()
        xm[i] -= 1e-6
        worst_i = max(worst_i, float(np.max(np.abs((nlp.ineq(xp) - nlp.ineq(xm)) / 2e-6 - J[:, i]))))
        worst_o = max(worst_o, abs((nlp.obj_value(xp) - nlp.obj_value(xm)) / 2e-6 - g[i]))
    # the objective by the statement's formula from its parts
    U = nlp.total_u(x)
    vs = nlp.split_v(x)
    f_exp = np.log(U + 1e-3) + 10 * sum(v.sum() for v in vs)
    e_obj = abs(nlp.obj_value(x) - f_exp)
    rec("NLP with zones: ineq Jacobian, objective gradient vs central differences; objective "
        "= ln(U + 1e-3) + 10 sum v", dict(ineq_jac=worst_i, obj_grad=worst_o, obj_formula=e_obj),
        worst_i < 1e-5 and worst_o < 1e-5 and e_obj < 1e-12)


def _yaw(v):
    return math.atan2(float(v[1]), float(v[0]))


def _wrap_pi(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def check_turn_rows():
    """Rows 24-25, the trunk's turn against the feet (statement of 2026-12-06), at 40 random
    postures of each worker: (a) the value against an independent computation from Pinocchio
    frame placements (twist from the matrix R_P^T R_T as atan2(R10 - R01, R00 + R11), the pelvis
    turn as the yaw of the pelvis heading minus the circular mean of the feet's yaws; for an
    upright trunk (pelvis_tilt, pelvis_list, lumbar_flexion, lumbar_lateral_bending 0) the yaw of the trunk minus
    that mean; the pelvis heading's yaw is the yaw of R_P y minus 90 deg, the hip-axis heading); (b) the rows' Jacobian (rows_jac, central differences) against an analytic one
    from the frames' angular Jacobians (LOCAL_WORLD_ALIGNED) and against 5-point differences;
    (c) signs: the pelvis turned +theta (left) on fixed feet by pelvis_rotation with the hips'
    rotations keeping both feet's yaw at 0 gives row 'left' = +theta; both hips rotated so the
    feet turn left under a still pelvis gives 'right'; (d) the worker's pelvis tilted 60 deg and
    listed 20 deg, legs straight: pelvis turn = pelvis_rotation - the feet's mean yaw (exact for
    the hip-axis heading, since R_P = Rz(rotation) Rx(-list) Ry(tilt)) = atan(sin 20 tan 60) (the
    feet follow the pelvis's x axis; the x-axis heading of before gave 0, reported)."""
    from reference import zones as Z
    out = {}
    worst_v, worst_up, worst_an, worst_fd = 0.0, 0.0, 0.0, 0.0
    n_up = 0
    for key, seed in (("shelf", 11), ("bench_assembly", 12)):
        t = M.load_task(key)
        b = t.body
        zm = Z.ZoneModel(b)
        m, d = zm.model, zm.data
        assert m.nq == m.nv
        L = M.Problem(t, zones=True).zone_limits[0]
        rng = np.random.default_rng(seed)
        upright = ("pelvis_tilt", "pelvis_list", "lumbar_flexion", "lumbar_lateral_bending")
        assert all(j in b.qidx for j in upright)
        upright = [j for j in upright if j in b.qidx]
        for k in range(20):
            q = b.lower + rng.random(b.nq) * (b.upper - b.lower)
            q[b.qidx["pelvis_tz"]] = 0.9
            up = k % 2 == 1
            if up:
                for j in upright:
                    q[b.qidx[j]] = 0.0
            th = zm.angles(q)
            RP = d.oMf[zm.f_pelvis].rotation
            RT = d.oMf[zm.f_trunk].rotation
            R = RP.T @ RT
            twist = math.atan2(R[1, 0] - R[0, 1], R[0, 0] + R[1, 1])
            fyaw = [_yaw(d.oMf[f].rotation[:, 0]) for f in zm.f_feet]
            mean_feet = math.atan2(sum(math.sin(a) for a in fyaw), sum(math.cos(a) for a in fyaw))
            # the pelvis heading from its hip axis: the yaw of R_P y minus 90 deg
            pturn = _wrap_pi(_yaw(RP[:, 1]) - math.pi / 2 - mean_feet)
            exp = twist + pturn
            worst_v = max(worst_v, abs(_wrap_pi(th[23] - exp)), abs(th[23] + th[24]),
                          abs(th[23] - th[4] - pturn))
            if up:
                n_up += 1
                # the trunk's own heading against the feet: the same angle (mod 2 pi)
                worst_up = max(worst_up, abs(_wrap_pi(th[23] - (_yaw(RT[:, 0]) - mean_feet))))
            # Jacobians
            g0, J = zm.rows_jac(q, L)
            pin.computeJointJacobians(m, d, q)
            pin.updateFramePlacements(m, d)
            W = {}
            for name, f in (("P", zm.f_pelvis), ("T", zm.f_trunk), ("r", zm.f_feet[0]),
                            ("l", zm.f_feet[1])):
                W[name] = pin.getFrameJacobian(m, d, f, pin.LOCAL_WORLD_ALIGNED)[3:]
            # twist = atan2(s, c), s = R10 - R01, c = R00 + R11, dR = RP^T ([wT] - [wP]) RT
            s_, c_ = R[1, 0] - R[0, 1], R[0, 0] + R[1, 1]
            jt = np.zeros(b.nq)
            jp = np.zeros(b.nq)
            for i in range(b.nq):
                dR = RP.T @ (pin.skew(W["T"][:, i]) - pin.skew(W["P"][:, i])) @ RT
                ds, dc = dR[1, 0] - dR[0, 1], dR[0, 0] + dR[1, 1]
                jt[i] = (c_ * ds - s_ * dc) / (s_ * s_ + c_ * c_)

                def dyaw(x, w):
                    dx = np.cross(w, x)
                    return (x[0] * dx[1] - x[1] * dx[0]) / (x[0] ** 2 + x[1] ** 2)
                xr, xl = d.oMf[zm.f_feet[0]].rotation[:, 0], d.oMf[zm.f_feet[1]].rotation[:, 0]
                ur = np.array([xr[0], xr[1], 0.0]) / math.hypot(xr[0], xr[1])
                ul = np.array([xl[0], xl[1], 0.0]) / math.hypot(xl[0], xl[1])
                h = ur + ul
                zc = np.array([0.0, 0.0, 1.0])
                dh = dyaw(xr, W["r"][:, i]) * np.cross(zc, ur) + dyaw(xl, W["l"][:, i]) * np.cross(zc, ul)
                dhy = (h[0] * dh[1] - h[1] * dh[0]) / (h[0] ** 2 + h[1] ** 2)
                jp[i] = dyaw(RP[:, 1], W["P"][:, i]) - dhy
            ja = jt + jp
            worst_an = max(worst_an, float(np.max(np.abs(J[23] - ja))), float(np.max(np.abs(J[24] + ja))))
            hh = 1e-4
            for i in range(b.nq):
                def fz(dx):
                    qq = q.copy()
                    qq[i] += dx
                    return zm.rows(qq, L)[23:25]
                dz = (-fz(2 * hh) + 8 * fz(hh) - 8 * fz(-hh) + fz(-2 * hh)) / (12 * hh)
                worst_fd = max(worst_fd, float(np.max(np.abs(dz - J[23:25, i]))))
    out.update(value_max_err_rad=worst_v, upright_trunk_yaw_max_err_rad=worst_up, n_upright=n_up,
               jac_vs_analytic_max_err=worst_an, jac_vs_5point_max_err=worst_fd, n_postures=40)
    ok = worst_v < 1e-12 and worst_up < 1e-9 and worst_an < 1e-6 and worst_fd < 1e-6
    # signs on the male worker, legs straight
    t = M.load_task("shelf")
    b = t.body
    zm = Z.ZoneModel(b)
    theta = math.radians(20)
    q = np.zeros(b.nq)
    q[b.qidx["pelvis_tz"]] = 0.9
    q[b.qidx["pelvis_rotation"]] = theta

    def foot_yaw(qq, k):
        zm.angles(qq)
        return _yaw(zm.data.oMf[zm.f_feet[k]].rotation[:, 0])

    hips = {}
    for k, j in enumerate(("r_hip_rotation", "l_hip_rotation")):
        # the hip rotation that brings this foot's yaw back to 0 (bisection on [-1, 1] rad)
        lo, hi = -1.0, 1.0
        flo = foot_yaw(np.where(np.arange(b.nq) == b.qidx[j], lo, q), k)
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            qq = q.copy()
            qq[b.qidx[j]] = mid
            fm = foot_yaw(qq, k)
            if (fm > 0) == (flo > 0):
                lo, flo = mid, fm
            else:
                hi = mid
        hips[j] = 0.5 * (lo + hi)
    for j, v in hips.items():
        q[b.qidx[j]] = v
    th = zm.angles(q)
    feet_yaw = [foot_yaw(q, 0), foot_yaw(q, 1)]
    s1 = dict(pelvis_rotation_deg=20.0, hips_deg={j: math.degrees(v) for j, v in hips.items()},
              feet_yaw_deg=[math.degrees(a) for a in feet_yaw],
              turn_left_deg=math.degrees(th[23]), turn_right_deg=math.degrees(th[24]),
              twist_deg=math.degrees(th[4]))
    ok1 = (max(abs(a) for a in feet_yaw) < 1e-9 and abs(math.degrees(th[23]) - 20) < 1e-6
           and abs(th[4]) < 1e-12 and th[24] < 0)
    # the pelvis still, right hip +theta, left hip -theta: on this model both feet then turn left
    # (their yaw +theta), so the pelvis is turned theta to the RIGHT against them
    q2 = np.zeros(b.nq)
    q2[b.qidx["pelvis_tz"]] = 0.9
    q2[b.qidx["r_hip_rotation"]] = theta
    q2[b.qidx["l_hip_rotation"]] = -theta
    th2 = zm.angles(q2)
    fy2 = [foot_yaw(q2, 0), foot_yaw(q2, 1)]
    s2 = dict(r_hip_rotation_deg=20.0, l_hip_rotation_deg=-20.0,
              feet_yaw_deg=[math.degrees(a) for a in fy2],
              turn_left_deg=math.degrees(th2[23]), turn_right_deg=math.degrees(th2[24]))
    ok2 = abs(math.degrees(th2[24]) - 20) < 1e-6 and min(fy2) > 0
    # plus a lumbar twist of 5 deg left on top of the first: the turn adds up to 25 left
    q3 = q.copy()
    q3[b.qidx["lumbar_axial_rotation"]] = math.radians(5)
    th3 = zm.angles(q3)
    s3 = dict(turn_left_deg=math.degrees(th3[23]), twist_deg=math.degrees(th3[4]))
    ok3 = abs(math.degrees(th3[23]) - 25) < 1e-6 and abs(math.degrees(th3[4]) - 5) < 1e-6
    # (d) tilted pelvis on the worker: pelvis_tilt 60, pelvis_list 20, pelvis_rotation theta in
    # {0, 20, -35} deg, lumbar and legs straight: the pelvis's turn is theta minus the feet's
    # circular mean yaw (measured); the feet follow the pelvis's x axis here (legs straight), whose
    # yaw is theta - atan(sin 20 tan 60), so the turn is atan(sin 20 tan 60) = 30.642 deg for every
    # theta, where the x-axis heading of before gave 0
    s4 = []
    ok4 = True
    for th_deg in (0.0, 20.0, -35.0):
        q4 = np.zeros(b.nq)
        q4[b.qidx["pelvis_tz"]] = 0.9
        q4[b.qidx["pelvis_tilt"]] = math.radians(60)
        q4[b.qidx["pelvis_list"]] = math.radians(20)
        q4[b.qidx["pelvis_rotation"]] = math.radians(th_deg)
        th4 = zm.angles(q4)
        fy = [foot_yaw(q4, 0), foot_yaw(q4, 1)]
        mf = math.atan2(sum(math.sin(a) for a in fy), sum(math.cos(a) for a in fy))
        exp4 = _wrap_pi(math.radians(th_deg) - mf)
        RP4 = zm.data.oMf[zm.f_pelvis].rotation
        xaxis = _wrap_pi(_yaw(RP4[:, 0]) - mf)
        e4 = abs(th4[23] - exp4)
        s4.append(dict(pelvis_rotation_deg=th_deg, feet_yaw_deg=[math.degrees(a) for a in fy],
                       turn_left_deg=math.degrees(th4[23]), expected_deg=math.degrees(exp4),
                       twist_deg=math.degrees(th4[4]), x_axis_heading_would_give_deg=math.degrees(xaxis)))
        e4 = max(e4, abs(th4[23] - math.atan(math.sin(math.radians(20)) * math.tan(math.radians(60)))))
        ok4 = ok4 and e4 < 1e-12 and abs(th4[4]) < 1e-12
    out.update(sign_pelvis_turned_left_on_fixed_feet=s1, sign_hips_r_plus_l_minus=s2,
               sign_plus_lumbar_twist_5=s3, tilted_listed_pelvis=s4)
    rec("turn against the feet (rows 24-25, pelvis heading from the hip axis): values vs frame "
        "yaws at 40 random postures, Jacobian vs analytic and 5-point differences, signs on "
        "fixed feet, a tilted and listed pelvis", out,
        ok and ok1 and ok2 and ok3 and ok4)


# ----------------------------------------------------------------------------------------------
# 9. held objects (statement section 4): the arms, the pairs per distinct phase, the distances
#    against brute-force sampling, the Jacobian rows, and the feasibility report
# ----------------------------------------------------------------------------------------------
def check_held_objects():
    out = {}
    ok = True
    # (a) the arms: the links on one hand's path to the root but not on the other's, for both
    # workers (robots/worker.urdf and the generated bench_assembly worker); their capsules are
    # the hands, forearms and upper arms (the shoulder links carry no collision shape)
    exp = {f"{s}_{n}" for s in "rl" for n in ("hand_grip", "hand", "wrist_flexion_link", "forearm",
                                               "elbow_flexion_link", "upper_arm",
                                               "shoulder_abduction_link", "shoulder_flexion_link")}
    for key in ("pallet", "bench_assembly"):
        b = M.load_task(key).body
        caps = sorted(set(l for l in b.cap_links if l in b.arm_links))
        out[f"{key}: arm links"] = sorted(b.arm_links)
        out[f"{key}: arm capsules"] = caps
        ok = ok and b.arm_links == exp and caps == sorted(f"{s}_{n}" for s in "rl"
                                                          for n in ("forearm", "hand", "upper_arm"))
    # (b) the pairs: pallet 4 distinct phases, one box each; shelf_two_hands' repeated picks and
    # carries share a posture and their (identical) box is counted once; tasks without objects
    # have none
    for key in ("pallet", "shelf_two_hands", "shelf", "bench_assembly"):
        t = M.load_task(key)
        pr = M.Problem(t)
        nb = [len(g["held"]) for g in t.groups]
        npairs = [len(p) for p in pr.pairs.held_pairs]
        out[f"{key}: held boxes / pairs per distinct phase"] = [nb, npairs]
        nn = len(pr.pairs.nonarm_caps)
        want = [1] * t.P if key in ("pallet", "shelf_two_hands") else [0] * t.P
        ok = ok and nb == want and npairs == [nn * k for k in want] and nn == 7
    # (c) held distances (after fk) vs brute-force sampling of each capsule's axis against the box,
    # and (d) their Jacobian rows vs central differences, at projected postures of pallet
    t = M.load_task("pallet")
    pr = M.Problem(t)
    nlp = JointNLP(pr)
    b = t.body
    rng = np.random.default_rng(21)
    worst_d, worst_j, n_checked = 0.0, 0.0, 0
    ts = np.linspace(0, 1, 2001)
    for gi in range(t.P):
        pm = nlp.pm[gi]
        q = S.ik_project(pm, S.template(b, t.rest_q, S.FAMILIES["stoop_mild"], rng))
        q = np.clip(q, b.lower + 1e-4, b.upper - 1e-4)
        b.fk(q)
        nrow = pr.pairs.n_pairs(gi)
        h0 = len(pr.pairs.obs_pairs) + len(pr.pairs.self_pairs)
        dist, J = pr.pairs.distances(with_jac=True, gi=gi)
        assert len(dist) == nrow == pm.n_dist
        caps = b.world_capsules()
        for r, (ci, k) in enumerate(pr.pairs.held_pairs[gi]):
            c, hf = t.groups[gi]["held"][k]
            a, bb, rad = caps[ci]
            pts = a + ts[:, None] * (bb - a)
            brute = min(geo.point_box_sd(x, c, np.eye(3), hf)[0] for x in pts) - rad
            if brute < geo.FAR:
                worst_d = max(worst_d, abs(dist[h0 + r] - brute))
                n_checked += 1
        hstep = 1e-6
        FD = np.zeros((nrow - h0, b.nq))
        for i in range(b.nq):
            qp = q.copy()
            qp[i] += hstep
            qm = q.copy()
            qm[i] -= hstep
            b.fk(qp)
            dp, _ = pr.pairs.distances(gi=gi)
            b.fk(qm)
            dm, _ = pr.pairs.distances(gi=gi)
            FD[:, i] = (dp[h0:] - dm[h0:]) / (2 * hstep)
        b.fk(q)
        keep = dist[h0:] > -0.005
        if keep.any():
            worst_j = max(worst_j, float(np.max(np.abs(J[h0:] - FD)[keep])))
    out["held distances vs brute-force sampling (max abs err, sampling 5e-4)"] = worst_d
    out["held distance rows checked"] = n_checked
    out["held Jacobian rows vs FD (max abs err)"] = worst_j
    ok = ok and worst_d < 1e-3 and n_checked > 0 and worst_j < 1e-4
    # (e) feasibility: a posture with the held box moved onto the trunk is reported infeasible
    # (and its pair named); a box around the hands only (the arms are excluded) is not
    t = M.load_task("pallet")
    g = t.groups[2]
    q = S.ik_project(JointNLP(M.Problem(t)).pm[2],
                     S.template(t.body, t.rest_q, S.FAMILIES["upright"], None))
    t.body.fk(q)
    trunk = [c for c in t.body.capsules if c["link"] == "trunk"][0]
    o, R = t.body.frame_pose(trunk["fid"])
    mid = o + R @ (0.5 * (trunk["a"] + trunk["b"]))
    g["held"] = [(mid, np.array([0.05, 0.05, 0.05]))]
    rep = M.Problem(t).evaluate([q] * t.P)
    r1 = rep["phases"][2]["residuals"]
    bad = [v for v in rep["feasible"]["violations"] if "min_clearance_held_m" in v]
    xr = t.body.data.oMf[t.body.fid["r_hand_grip"]].translation.copy()
    g["held"] = [(xr, np.array([0.01, 0.01, 0.01]))]
    rep2 = M.Problem(t).evaluate([q] * t.P)
    r2 = rep2["phases"][2]["residuals"]
    out["box on the trunk: min_clearance_held_m, pair, violations"] = [
        r1["min_clearance_held_m"], r1["min_clearance_held_pair"], bad]
    out["box at the right hand: min_clearance_held_m, pair"] = [
        r2["min_clearance_held_m"], r2["min_clearance_held_pair"]]
    ok = ok and r1["min_clearance_held_m"] < 0 and r1["min_clearance_held_pair"] == "trunk | held object" \
        and len(bad) == 1 and r2["min_clearance_held_m"] > 0.0
    rec("held objects (non-arm capsules vs each distinct phase's held boxes): arm links, pairs, "
        "distances vs sampling, Jacobian rows vs FD, feasibility report", out, ok)


def check_free_arm_limit():
    """Statement of 2026-12-07 (session 15): the upper-arm row of a free hand (a hand the phase
    gives no target) is limited to min(the hold's limit, 10 deg); the hand with a target keeps
    the hold's limit. shelf and bench_assembly give only the right hand targets (the left is
    free in every phase); shelf_two_hands holds an object with both hands (both keep the hold's
    60 deg); a phase with a left-hand target only frees the right arm; the evaluation reports
    the limit and, as limit_hold_deg, the hold's limit (the row above)."""
    from reference import zones as Z
    out = {}
    ok = True
    d10, d60 = 10.0, 60.0
    for key, exp_r, exp_l in (("shelf", d60, d10), ("bench_assembly", d60, d10),
                              ("shelf_two_hands", d60, d60)):
        t = M.load_task(key)
        pr = M.Problem(t, zones=True)
        per = {}
        for gi, g in enumerate(t.groups):
            L = np.degrees(pr.zone_limits[gi])
            Lh = np.degrees(pr.zone_limits_hold[gi])
            hands = sorted(t.phases[[p.group for p in t.phases].index(gi)].targets)
            per[g["name"]] = dict(hands_with_targets=hands, right_arm_deg=float(L[6]),
                                  left_arm_deg=float(L[7]), hold_right_deg=float(Lh[6]),
                                  hold_left_deg=float(Lh[7]))
            other = [i for i in range(Z.NROW) if i not in Z.ARM_ROWS]
            ok = ok and abs(L[6] - exp_r) < 1e-9 and abs(L[7] - exp_l) < 1e-9 \
                and abs(Lh[6] - d60) < 1e-9 and abs(Lh[7] - d60) < 1e-9 \
                and np.array_equal(L[other], Lh[other])
        out[key] = per
    # a phase with a left-hand target only (the right hand free), and a long hold (arm 20 deg
    # from 3 min: the free arm keeps 10 deg; a hold's limit below 10 deg does not occur)
    class _Ph:
        pass
    ph = _Ph()
    ph.targets = {"l": np.zeros(3)}
    cases = {}
    for hold in (2.0, 10.0, 150.0, 600.0):
        L = np.degrees(Z.limits_for_phase(ph, hold))
        Lh = np.degrees(Z.limits_for_hold(hold))
        cases[f"left target only, hold {hold} s: right, left arm [deg]"] = [float(L[6]), float(L[7])]
        ok = ok and abs(L[6] - min(Lh[6], d10)) < 1e-9 and abs(L[7] - Lh[7]) < 1e-9
    ph.targets = {"r": np.zeros(3), "l": np.zeros(3)}
    L = np.degrees(Z.limits_for_phase(ph, 150.0))
    cases["both targets, hold 150 s: right, left arm [deg]"] = [float(L[6]), float(L[7])]
    ok = ok and abs(L[6] - 30.0) < 1e-9 and abs(L[7] - 30.0) < 1e-9
    ph.targets = {}
    L = np.degrees(Z.limits_for_phase(ph, 150.0, free_arm=False))
    cases["no targets, free_arm=False, hold 150 s: right, left arm [deg]"] = [float(L[6]), float(L[7])]
    ok = ok and abs(L[6] - 30.0) < 1e-9 and abs(L[7] - 30.0) < 1e-9
    out["limits_for_phase"] = cases
    # the row at the free arm's limit: (cos L - cos theta)/sin L = 0 at theta = 10 deg, about
    # theta - L [rad] at 11 deg; and Problem.evaluate reports both limits
    t = M.load_task("shelf")
    pr = M.Problem(t, zones=True)
    zm = pr.zm
    q = t.rest_q.copy()
    b = t.body
    row = {}
    for th_deg in (10.0, 11.0):
        # raise the left upper arm forward until its elevation is th_deg (bisection on the
        # shoulder flexion joint, the rest at the rest posture)
        j = b.qidx["l_shoulder_flexion"]
        lo, hi = b.lower[j], b.upper[j]
        f = lambda x: (lambda qq: np.degrees(zm.angles(qq)[7]))(np.r_[q[:j], x, q[j + 1:]])
        base = f(q[j])
        # search the side of the current value that increases the elevation
        xs = np.linspace(lo, hi, 401)
        vals = np.array([f(x) for x in xs])
        sc = np.nonzero(np.sign(vals[:-1] - th_deg) != np.sign(vals[1:] - th_deg))[0]
        k = int(sc[np.argmin(np.abs(xs[sc] - q[j]))])   # the crossing nearest the rest value
        a, c = xs[k], xs[k + 1]
        for _ in range(80):
            m = 0.5 * (a + c)
            if (f(a) - th_deg) * (f(m) - th_deg) <= 0:
                c = m
            else:
                a = m
        qq = q.copy()
        qq[j] = 0.5 * (a + c)
        g = zm.rows(qq, pr.zone_limits[0])[7]
        row[th_deg] = float(g)
        if th_deg == 11.0:
            rep = pr.evaluate([qq] * t.P)
            z = rep["phases"][0]["zones"][7]
            out["shelf evaluate, left arm at 11 deg: limit, hold limit, excess, excess vs hold [deg]"] = [
                z["limit_deg"], z["limit_hold_deg"], z["excess_deg"], z["excess_hold_deg"]]
            ok = ok and abs(z["limit_deg"] - 10.0) < 1e-9 and abs(z["limit_hold_deg"] - 60.0) < 1e-9 \
                and abs(z["excess_deg"] - 1.0) < 1e-6 and z["excess_hold_deg"] == 0.0
        out[f"rest elevation {base:.3f} deg; left arm row at {th_deg} deg"] = float(g)
    exp11 = (math.cos(math.radians(10.0)) - math.cos(math.radians(11.0))) / math.sin(math.radians(10.0))
    out["left arm row at 11 deg: expected (cos 10 - cos 11)/sin 10 (about 1 deg in rad x 1.05)"] = exp11
    ok = ok and abs(row[10.0]) < 1e-9 and abs(row[11.0] - exp11) < 1e-9
    rec("free hand's upper arm (statement of 2026-12-07): limit min(hold's, 10 deg) on the row of "
        "a hand without a target, the other arm and rows unchanged, evaluate reports both", out, ok)


def check_capacity():
    """11. capacity constraint (statement section 4, "capacity (no muscle group gives out)", option
    --capacity): (a) the rows' per (phase, half-joint) minimum of step-end capacities (closed form,
    first and last cycle) vs a brute-force replay of every step of every cycle with the
    closed-form step; (b) the rows' Jacobian (complex step) vs central finite differences, for the
    joint NLP and a per-phase NLP (other phases' loads fixed)."""
    import time
    key = "shelf_two_hands"
    t = M.load_task(key)
    pr = M.Problem(t)
    pr.capacity = True
    nlp = JointNLP(pr)
    rng = np.random.default_rng(7)
    fams = list(S.FAMILIES)
    worst_v, worst_row, worst_j, worst_jp, times = 0.0, 0.0, 0.0, 0.0, []
    ns = len(t.step_idx)
    ncyc = 2 if t.cycles > 1 else 1
    for trial in range(4):
        qs = [np.clip(S.template(t.body, t.rest_q, S.FAMILIES[fams[(trial + gi) % len(fams)]], rng),
                      t.body.lower, t.body.upper) for gi in range(t.P)]
        # loads scaled so that capacities fall well below 1 but the task is not all exhausted
        fs = [np.clip(nlp.pm[gi].loads_from_q(q), 0.0, 0.6) + rng.uniform(0.0, 0.05, t.body.H)
              for gi, q in enumerate(qs)]
        x = np.concatenate(list(qs) + list(fs))
        t0 = time.perf_counter()
        val = nlp.capacity_rows(x)
        times.append(time.perf_counter() - t0)
        # brute force: replay all cycles, min step-end capacity per (phase, half-joint)
        H = t.body.H
        L = np.vstack(fs + [pr.rest_loads])
        c = np.ones(H)
        cmin = np.full((t.P, H), np.inf)
        for cyc in range(t.cycles):
            for s_, (row, T) in enumerate(zip(t.step_idx, t.step_dur)):
                for h in range(H):
                    c[h] = fat.step_real(c[h], L[row, h], t.ks[h], T, t.r_rest, t.f_lim)[0]
                if row < t.P:
                    cmin[row] = np.minimum(cmin[row], c)
        # rows -> capacities; min per (phase, half-joint)
        cap = np.full((t.P, H), np.inf)
        r = 0
        for s_ in range(ns):
            p = t.step_idx[s_]
            if p >= t.P:
                continue
            for n in range(ncyc):
                cap[p] = np.minimum(cap[p], val[r:r + H] + L[p] + 0.02)
                r += H
        worst_v = max(worst_v, float(np.max(np.abs(cap - cmin))))
        # one row directly: last cycle, first step
        worst_row = max(worst_row, float(np.max(np.abs((val[H:2 * H] + L[t.step_idx[0]] + 0.02)
                                                       - _replay_step_end(t, L, 0)))))
        # (b) Jacobian vs central differences over the load columns (q columns must be zero)
        v0, J = nlp.capacity_rows(x, jac=True)
        k, nq = nlp.k, t.body.nq
        hstep = 1e-6
        FD = np.zeros_like(J)
        for j in range(k * nq, k * (nq + H)):
            xp = x.copy()
            xp[j] += hstep
            xm = x.copy()
            xm[j] -= hstep
            FD[:, j] = (nlp.capacity_rows(xp) - nlp.capacity_rows(xm)) / (2 * hstep)
        worst_j = max(worst_j, float(np.max(np.abs(J - FD))), float(np.max(np.abs(J[:, :k * nq]))))
        # per-phase NLP (phase trial % P optimised, the others fixed at fs)
        gi = trial % t.P
        pn = JointNLP(pr, phases=[gi])
        pn.fixed_loads = fs
        xg = np.concatenate([qs[gi], fs[gi]])
        vg, Jg = pn.capacity_rows(xg, jac=True)
        FDg = np.zeros_like(Jg)
        for j in range(nq, nq + H):
            xp = xg.copy()
            xp[j] += hstep
            xm = xg.copy()
            xm[j] -= hstep
            FDg[:, j] = (pn.capacity_rows(xp) - pn.capacity_rows(xm)) / (2 * hstep)
        worst_jp = max(worst_jp, float(np.max(np.abs(Jg - FDg))),
                       float(np.max(np.abs(np.sort(vg) - np.sort(v0)))))
    rec(f"capacity rows ({key}, {t.cycles} cycles, 4 random postures): min step-end capacity per "
        "(phase, half-joint) from the closed form (first and last cycle) vs brute-force replay of "
        "every cycle (max abs err)", worst_v, worst_v < 1e-9)
    rec("capacity rows: last-cycle step-end capacity of the first step vs replay (max abs err)",
        worst_row, worst_row < 1e-9)
    rec("capacity rows: Jacobian (complex step) vs central FD, joint NLP (max abs err; q columns 0)",
        worst_j, worst_j < 1e-6)
    rec("capacity rows: per-phase NLP Jacobian vs central FD and same rows as the joint NLP "
        "(max abs err)", worst_jp, worst_jp < 1e-6)
    rec("capacity rows: time of one evaluation (value only) [s], rows per evaluation",
        [float(np.median(times)), int(len(val))], True)


def _replay_step_end(t, L, s0):
    """Capacity at the end of step s0 of the last cycle, by replaying every step."""
    H = L.shape[1]
    c = np.ones(H)
    for cyc in range(t.cycles):
        for s_, (row, T) in enumerate(zip(t.step_idx, t.step_dur)):
            for h in range(H):
                c[h] = fat.step_real(c[h], L[row, h], t.ks[h], T, t.r_rest, t.f_lim)[0]
            if cyc == t.cycles - 1 and s_ == s0:
                return c.copy()


if __name__ == "__main__":
    check_fatigue()
    check_fatigue_grad()
    check_pchip()
    check_plus_curves()
    check_statics()
    check_internal_wrench()
    check_nlp_jacobians()
    check_distances()
    check_rotated_box()
    check_zone_angles()
    check_gaze_and_zone_jacobians()
    check_turn_rows()
    check_held_objects()
    check_free_arm_limit()
    check_capacity()
    here = os.path.dirname(os.path.abspath(__file__))
    out = os.path.join(here, "results", "verification.json")
    if "--out" in sys.argv:
        out = sys.argv[sys.argv.index("--out") + 1]
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out, "w") as fh:
        json.dump(OUT, fh, indent=1)
    print("all ok" if all(v["ok"] for v in OUT.values()) else "SOME CHECKS FAILED")
