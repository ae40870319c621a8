"""Independent reference model of posture-opt's optimisation problem (docs: optimisation-problem.md).

Everything here follows the written specification only:
  * the task, its distinct phases, the stance and the obstacles;
  * the body (URDF via Pinocchio as a fixed-base tree rooted at `floor`), its collision shapes;
  * strength (MVC with PCHIP posture curves), half-joint loads;
  * statics with the 5-step ground-reaction split (internal wrench (lambda, m_x, m_y) between the
    feet by minimum-norm least squares, the moments bounded by the soles);
  * the fatigue schedule (reference.fatigue) and the constraints.
"""
import math
import os
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import yaml
from scipy.stats import norm

from . import fatigue as fat
from . import geometry as geo

HERE = os.path.dirname(os.path.abspath(__file__))
INPUTS = os.path.join(os.path.dirname(HERE), "inputs")
G_DEFAULT = np.array([0.0, 0.0, -9.81])


# ----------------------------------------------------------------------------------------------
# PCHIP (Fritsch & Carlson with Moler's end slopes), held constant outside the table
# ----------------------------------------------------------------------------------------------
class Pchip:
    def __init__(self, x, y):
        x = np.asarray(x, float)
        y = np.asarray(y, float)
        assert np.all(np.diff(x) > 0)
        self.x, self.y = x, y
        n = len(x)
        h = np.diff(x)
        delta = np.diff(y) / h
        d = np.zeros(n)
        if n == 2:
            d[:] = delta[0]
        else:
            for k in range(1, n - 1):
                if delta[k - 1] * delta[k] <= 0:
                    d[k] = 0.0
                else:
                    w1 = 2 * h[k] + h[k - 1]
                    w2 = h[k] + 2 * h[k - 1]
                    d[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k])
            d[0] = self._end(h[0], h[1], delta[0], delta[1])
            d[-1] = self._end(h[-1], h[-2], delta[-1], delta[-2])
        self.d = d

    @staticmethod
    def _end(h0, h1, del0, del1):
        dd = ((2 * h0 + h1) * del0 - h0 * del1) / (h0 + h1)
        if np.sign(dd) != np.sign(del0):
            dd = 0.0
        elif np.sign(del0) != np.sign(del1) and abs(dd) > abs(3 * del0):
            dd = 3 * del0
        return dd

    def __call__(self, xq):
        """Value and derivative at scalar xq."""
        x, y, d = self.x, self.y, self.d
        # held constant beyond the table; AT an end point the one-sided (inner) slope is returned,
        # which is the derivative along feasible directions when the end point is a joint limit
        if xq < x[0]:
            return y[0], 0.0
        if xq > x[-1]:
            return y[-1], 0.0
        k = int(np.searchsorted(x, xq) - 1)
        k = min(max(k, 0), len(x) - 2)
        h = x[k + 1] - x[k]
        t = (xq - x[k]) / h
        h00 = 2 * t ** 3 - 3 * t ** 2 + 1
        h10 = t ** 3 - 2 * t ** 2 + t
        h01 = -2 * t ** 3 + 3 * t ** 2
        h11 = t ** 3 - t ** 2
        val = h00 * y[k] + h10 * h * d[k] + h01 * y[k + 1] + h11 * h * d[k + 1]
        dh00 = 6 * t ** 2 - 6 * t
        dh10 = 3 * t ** 2 - 4 * t + 1
        dh01 = -6 * t ** 2 + 6 * t
        dh11 = 3 * t ** 2 - 2 * t
        der = (dh00 * y[k] + dh10 * h * d[k] + dh01 * y[k + 1] + dh11 * h * d[k + 1]) / h
        return val, der


# ----------------------------------------------------------------------------------------------
# small rotation helpers
# ----------------------------------------------------------------------------------------------
def rpy_to_R(rpy):
    r, p, y = rpy
    return pin.rpy.rpyToMatrix(r, p, y)


def skew(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def cross(a, b):
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def Rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


# ----------------------------------------------------------------------------------------------
# Body
# ----------------------------------------------------------------------------------------------
class Body:
    def __init__(self, urdf_path, strength_path, sex, percentile, gravity):
        self.urdf_path = urdf_path
        self.model = pin.buildModelFromUrdf(urdf_path)
        self.model.gravity.linear = np.asarray(gravity, float)
        self.gravity = np.asarray(gravity, float)
        self.data = self.model.createData()
        m = self.model
        assert m.nq == m.nv
        self.nq = m.nq
        self.joint_names = [None] * m.nq
        for j in range(1, m.njoints):
            assert m.joints[j].nq == 1
            self.joint_names[m.joints[j].idx_q] = m.names[j]
        self.qidx = {n: i for i, n in enumerate(self.joint_names)}
        self.lower = np.array(m.lowerPositionLimit, float)
        self.upper = np.array(m.upperPositionLimit, float)
        self.total_mass = float(sum(m.inertias[j].mass for j in range(m.njoints)))

        with open(strength_path) as fh:
            st = yaml.safe_load(fh)
        self.unactuated = list(st["unactuated"])
        self.actuated = [n for n in self.joint_names if n not in self.unactuated]
        self.act_idx = np.array([self.qidx[n] for n in self.actuated])
        self.unact_idx = np.array([self.qidx[n] for n in self.unactuated])
        self._build_strength(st, sex, percentile)

        fr = lambda name: m.getFrameId(name)
        self.fid = {n: fr(n) for n in ("r_hand_grip", "l_hand_grip", "r_foot", "l_foot")}
        self._parse_shapes()
        # the arms (statement section 4, "held objects"): the rigid bodies on one hand's path to
        # the root but not on the other's (URDF links, the hand frames' own links included)
        paths = {}
        for h in ("r_hand_grip", "l_hand_grip"):
            path, link = [], h
            while link is not None:
                path.append(link)
                link = self.parent_link.get(link)
            paths[h] = set(path)
        self.arm_links = paths["r_hand_grip"] ^ paths["l_hand_grip"]

    # --- strength -----------------------------------------------------------------------------
    def _build_strength(self, st, sex, percentile):
        z = float(norm.ppf(percentile / 100.0)) if percentile != 50 else 0.0
        entries = {}
        for e in st["half_joints"]:
            sides = e.get("sides")
            names = [f"{s}_{e['joint']}" for s in sides] if sides else [e["joint"]]
            for i, jn in enumerate(names):
                side = sides[i] if sides else None
                ms = e[sex]
                base = max(ms["mean_nm"] + z * ms["sd_nm"], 0.05 * ms["mean_nm"])
                curves = []
                for c in e.get("posture", []) or []:
                    # a curve is keyed on the angle of `joint`, or (since 2026-12-05) on the SUM
                    # of the angles of `joint` and of every joint in `plus` (statement §2
                    # "Strength"); each name takes the muscle group's side if it has no prefix
                    qis = []
                    for cj in [c["joint"]] + list(c.get("plus", []) or []):
                        full = cj if cj in self.qidx else (f"{side}_{cj}" if side else cj)
                        assert full in self.qidx, full
                        qis.append(self.qidx[full])
                    curves.append((np.array(qis, dtype=np.int64),
                                   Pchip(np.radians(c["deg"]), c["factor"])))
                entries[(jn, e["direction"])] = dict(base=base, region=e["region"], curves=curves,
                                                     mean=ms["mean_nm"])
        self.half_names = []
        self.half = []
        for jn in self.actuated:
            for d in ("+", "-"):
                self.half_names.append(jn + d)
                self.half.append(entries[(jn, d)])
        self.H = len(self.half)
        self.regions = [h["region"] for h in self.half]
        # a scale per actuated joint for the torque-balance constraints
        self.tau_scale = np.array([max(self.half[2 * a]["mean"], self.half[2 * a + 1]["mean"])
                                   for a in range(len(self.actuated))])

    def mvc(self, q, with_grad=False):
        """MVC per half-joint [H], optionally d MVC / dq as a dense [H, nq]."""
        out = np.empty(self.H)
        grad = np.zeros((self.H, self.nq)) if with_grad else None
        for i, h in enumerate(self.half):
            vals = []
            ders = []
            for qis, pc in h["curves"]:
                v, dv = pc(float(np.sum(q[qis])))
                vals.append(v)
                ders.append((qis, dv))
            prod = h["base"] * (np.prod(vals) if vals else 1.0)
            out[i] = prod
            if with_grad:
                for k, (qis, dv) in enumerate(ders):
                    others = np.prod([vals[j] for j in range(len(vals)) if j != k]) if len(vals) > 1 else 1.0
                    for qi in qis:          # d(sum)/dq_j = 1 for every joint of the sum
                        grad[i, qi] += h["base"] * others * dv
        return out, grad

    # --- collision shapes ---------------------------------------------------------------------
    def _parse_shapes(self):
        root = ET.parse(self.urdf_path).getroot()
        m = self.model
        self.capsules = []   # dicts: link, frame id, a, b (local), r
        self.boxes = []      # dicts: link, frame id, center, R (local), half
        self.parent_link = {}
        for j in root.findall("joint"):
            self.parent_link[j.find("child").get("link")] = j.find("parent").get("link")
        self.first_box = {}
        for link in root.findall("link"):
            name = link.get("name")
            for k, col in enumerate(link.findall("collision")):
                o = col.find("origin")
                xyz = np.array([float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()])
                rpy = np.array([float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()])
                R = rpy_to_R(rpy)
                g = col.find("geometry")[0]
                fid = m.getFrameId(name)
                if g.tag == "cylinder":
                    L = float(g.get("length"))
                    r = float(g.get("radius"))
                    ax = R @ np.array([0, 0, L / 2])
                    self.capsules.append(dict(link=name, fid=fid, a=xyz - ax, b=xyz + ax, r=r))
                elif g.tag == "sphere":
                    r = float(g.get("radius"))
                    self.capsules.append(dict(link=name, fid=fid, a=xyz.copy(), b=xyz.copy(), r=r))
                elif g.tag == "box":
                    size = np.array([float(v) for v in g.get("size").split()])
                    bx = dict(link=name, fid=fid, center=xyz, R=R, half=size / 2)
                    self.boxes.append(bx)
                    if k == 0:
                        # a sole is the bottom face of the link's first <collision> box
                        self.first_box[name] = bx
                else:
                    raise ValueError(f"unsupported collision geometry {g.tag}")
        self.cap_links = [c["link"] for c in self.capsules]
        # the sole of each foot: bottom (-z of the box frame) face of the first collision box
        self.sole = {}
        for foot in ("r_foot", "l_foot"):
            bx = self.first_box[foot]
            self.sole[foot] = dict(center=bx["center"] + bx["R"] @ np.array([0, 0, -bx["half"][2]]),
                                   R=bx["R"], half=bx["half"])
        # reduced parent among links that carry capsules
        capset = set(self.cap_links)

        def cap_parent(link):
            p = self.parent_link.get(link)
            while p is not None and p not in capset:
                p = self.parent_link.get(p)
            return p

        self.cap_parent = {l: cap_parent(l) for l in capset}

    # --- kinematics ---------------------------------------------------------------------------
    def fk(self, q):
        pin.computeJointJacobians(self.model, self.data, q)
        pin.updateFramePlacements(self.model, self.data)

    def frame_pose(self, fid):
        M = self.data.oMf[fid]
        return np.array(M.translation), np.array(M.rotation)

    def frame_jac(self, fid):
        return pin.getFrameJacobian(self.model, self.data, fid, pin.LOCAL_WORLD_ALIGNED)

    def point_jac(self, fid, p, J=None):
        """3 x nq Jacobian of a world point p rigidly attached to frame fid (after fk)."""
        if J is None:
            J = self.frame_jac(fid)
        r = p - self.data.oMf[fid].translation
        Jw = J[3:]
        return J[:3] - np.array([r[1] * Jw[2] - r[2] * Jw[1], r[2] * Jw[0] - r[0] * Jw[2],
                                 r[0] * Jw[1] - r[1] * Jw[0]])

    def world_capsules(self):
        out = []
        for c in self.capsules:
            o, R = self.frame_pose(c["fid"])
            out.append((o + R @ c["a"], o + R @ c["b"], c["r"]))
        return out

    def q_from_dict(self, d, base=None):
        q = np.zeros(self.nq) if base is None else np.array(base, float)
        for k, v in d.items():
            if k in self.qidx:
                q[self.qidx[k]] = float(v)
        return q

    def q_to_dict(self, q):
        return {n: float(q[i]) for i, n in enumerate(self.joint_names)}


# ----------------------------------------------------------------------------------------------
# Task
# ----------------------------------------------------------------------------------------------
class Phase:
    pass


class Task:
    def __init__(self, task_path, urdf_override=None, rest_path=None):
        self.path = task_path
        with open(task_path) as fh:
            t = yaml.safe_load(fh)
        self.raw = t
        self.name = t.get("name", os.path.basename(task_path))
        self.key = os.path.splitext(os.path.basename(task_path))[0]
        w = t["worker"]
        self.sex = w["sex"]
        self.stature = float(w["stature_m"])
        self.percentile = float(w.get("strength_percentile", 50))
        self.gravity = np.array(t.get("gravity_m_s2", G_DEFAULT), float)
        if urdf_override:
            urdf = urdf_override
        elif t.get("robot"):
            urdf = os.path.join(INPUTS, os.path.basename(t["robot"]))
        else:
            urdf = os.path.join(INPUTS, f"{self.key}.worker.urdf")
        strength = os.path.join(INPUTS, "worker.strength.yaml")
        self.body = Body(urdf, strength, self.sex, self.percentile, self.gravity)

        st = t.get("stance") or {}
        self.stance_width = float(st.get("width_m", 0.21 * self.stature))
        self.stance_forward = float(st.get("forward_m", 0.0))
        self.toe_out = math.radians(float(st.get("toe_out_deg", 0.0)))
        obj = t.get("objective") or {}
        self.clearance = float(obj.get("clearance_m", 0.01))
        self.balance_margin = float(obj.get("balance_margin_m", 0.02))

        # fatigue parameter set
        with open(os.path.join(INPUTS, "fatigue_sets.yaml")) as fh:
            fs = yaml.safe_load(fh)
        setname = (t.get("fatigue") or {}).get("parameters", fs.get("default_set", "default-2026"))
        pset = [s for s in fs["sets"] if s["name"] == setname][0]
        self.fatigue_set = setname
        rec = pset["recovery"]
        if rec["form"] == "none":
            self.r_rest, self.f_lim = 0.0, 1.0
        else:
            self.r_rest, self.f_lim = float(rec["rest_per_min"]), float(rec["limit_fmvc"])
        ks = []
        for reg in self.body.regions:
            k = pset["regions"][reg]["k"]
            over = (pset.get(self.sex) or {}).get(reg)
            if over is not None:
                k = over["k"]
            ks.append(float(k))
        self.ks = np.array(ks)

        self._parse_phases(t)
        self.rest_s = float(t.get("rest_s", 0.0))
        self.cycles = int(t.get("cycles", 1))
        # schedule of one cycle
        P = len(self.groups)
        self.step_idx = np.array([ph.group for ph in self.phases] + [P], np.int64)
        self.step_dur = np.array([ph.duration for ph in self.phases] + [self.rest_s], float) / 60.0
        if self.rest_s <= 0:
            self.step_idx = self.step_idx[:-1]
            self.step_dur = self.step_dur[:-1]

        rp = rest_path or os.path.join(INPUTS, f"{self.key}.rest_posture.json")
        import json
        with open(rp) as fh:
            self.rest_q = self.body.q_from_dict(json.load(fh))

        self._build_obstacles(t)
        self._build_stance()

    def schedule(self):
        """One cycle as the reference evaluates it, for replaying a plan as a recording: each step
        names the posture it holds (a distinct phase's name or "rest"), its duration [s] and the
        forces [N] the environment applies at the right and left hands."""
        steps = [dict(phase=ph.name, posture=self.groups[ph.group]["name"], duration_s=ph.duration,
                      right_force_n=[float(v) for v in ph.forces["r"]],
                      left_force_n=[float(v) for v in ph.forces["l"]]) for ph in self.phases]
        if self.rest_s > 0:
            steps.append(dict(phase="rest", posture="rest", duration_s=self.rest_s,
                              right_force_n=[0.0, 0.0, 0.0], left_force_n=[0.0, 0.0, 0.0]))
        return dict(cycles=self.cycles, steps=steps)

    def _parse_phases(self, t):
        g = self.gravity
        self.phases = []
        groups = []
        for i, p in enumerate(t["phases"]):
            ph = Phase()
            ph.name = p.get("name", f"phase {i}")
            ph.duration = float(p["duration_s"])
            targets = {}
            ph.held = None
            if "object" in p:
                c = np.array(p["object"]["center_m"], float)
                gw = float(p["object"]["grip_width_m"])
                targets["r"] = c - np.array([0, gw / 2, 0])
                targets["l"] = c + np.array([0, gw / 2, 0])
                # held object (statement section 4): an axis-aligned box of size_m at center_m,
                # size_m by default 0.30 x grip_width_m x 0.25
                size = p["object"].get("size_m")
                if size is None:
                    size = [0.30, gw, 0.25]
                ph.held = (c, np.array(size, float) / 2)
            elif "targets" in p:
                if p["targets"].get("right_m") is not None:
                    targets["r"] = np.array(p["targets"]["right_m"], float)
                if p["targets"].get("left_m") is not None:
                    targets["l"] = np.array(p["targets"]["left_m"], float)
            elif "target_m" in p:
                hand = p.get("hand", "right")
                targets["l" if hand == "left" else "r"] = np.array(p["target_m"], float)
            total = np.zeros(3)
            if p.get("load_kg"):
                total += float(p["load_kg"]) * g
            if p.get("hand_force_n") is not None:
                total += np.array(p["hand_force_n"], float)
            forces = {"r": np.zeros(3), "l": np.zeros(3)}
            if len(targets) == 2:
                sL = float(p.get("left_share", 0.5))
                forces["r"] = (1 - sL) * total
                forces["l"] = sL * total
            elif len(targets) == 1:
                forces[list(targets)[0]] = total
            ph.targets = targets
            ph.forces = forces
            # gaze (statement: gaze_m, or without one the mean of the phase's hand targets)
            ph.gaze_free = bool(p.get("gaze_free", False))
            ph.gaze_m = None if p.get("gaze_m") is None else np.array(p["gaze_m"], float)
            ph.gaze_point = ph.gaze_m if ph.gaze_m is not None else \
                np.mean(np.array(list(targets.values())), axis=0)
            # "same work": same targets, hand forces and gaze (for the zones' holds)
            ph.work_key = (tuple((h, tuple(np.round(v, 12))) for h, v in sorted(targets.items())),
                           tuple(np.round(forces["r"], 12)), tuple(np.round(forces["l"], 12)),
                           ph.gaze_free, None if ph.gaze_m is None else tuple(np.round(ph.gaze_m, 12)))
            key = (tuple((h, tuple(np.round(v, 12))) for h, v in sorted(targets.items())),
                   tuple(np.round(forces["r"], 12)), tuple(np.round(forces["l"], 12)))
            for gi, gk in enumerate(groups):
                if gk == key:
                    ph.group = gi
                    break
            else:
                groups.append(key)
                ph.group = len(groups) - 1
            self.phases.append(ph)
        self.groups = []
        for gi in range(len(groups)):
            members = [ph for ph in self.phases if ph.group == gi]
            # the held boxes of every phase that shares the posture (distinct boxes once)
            held = []
            for m_ in members:
                if m_.held is not None and not any(
                        np.array_equal(m_.held[0], c) and np.array_equal(m_.held[1], h)
                        for c, h in held):
                    held.append(m_.held)
            self.groups.append(dict(name=members[0].name, members=[m.name for m in members],
                                    targets=members[0].targets, forces=members[0].forces,
                                    held=held))
        self.P = len(self.groups)

    def _build_obstacles(self, t):
        self.obstacles = []
        for o in (t.get("workstation") or {}).get("obstacles", []) or []:
            pos = np.array(o.get("position_m", [0, 0, 0]), float)
            rot = np.eye(3)
            if o.get("rpy_deg") is not None:
                # task-format.md: obstacles are oriented by `rpy_rad`; `rpy_deg` is not a field
                raise ValueError(f"obstacle {o.get('name')}: unknown field rpy_deg (use rpy_rad)")
            if o.get("rpy_rad") is not None:
                rot = rpy_to_R(np.array(o["rpy_rad"], float))
            ob = dict(name=o.get("name", "obstacle"), kind=None, center=pos, R=rot,
                      half=np.zeros(3), radius=0.0, half_h=0.0, normal=np.zeros(3), offset=0.0,
                      floor=False)
            if "box" in o:
                ob["kind"] = 0
                ob["half"] = np.array(o["box"]["size_m"], float) / 2
            elif "cylinder" in o:
                ob["kind"] = 1
                cy = o["cylinder"]
                ob["radius"] = float(cy["radius_m"])
                ob["half_h"] = float(cy.get("length_m", cy.get("height_m"))) / 2
            elif "plane" in o:
                ob["kind"] = 2
                n = np.array(o["plane"]["normal"], float)
                n = n / np.linalg.norm(n)
                ob["normal"] = n
                ob["offset"] = float(n @ pos)
                # floor: upward normal, at or below z = 0
                ob["floor"] = bool(n[2] > 1 - 1e-12 and pos[2] <= 0.0)
            else:
                raise ValueError(f"unknown obstacle {o}")
            self.obstacles.append(ob)

    def _build_stance(self):
        b = self.body
        self.foot_target = {}
        hw = self.stance_width / 2
        for foot, sgn in (("l_foot", +1), ("r_foot", -1)):
            c = np.array([self.stance_forward, sgn * hw, 0.0])
            R = Rz(sgn * self.toe_out)
            # the sole centre (link frame) lands on c, the link frame orientation is R
            pos = c - R @ b.sole[foot]["center"]
            self.foot_target[foot] = (pos, R)
        # support polygon at the stance (for the optimiser; the evaluator uses the actual feet)
        pts = []
        for foot in ("l_foot", "r_foot"):
            pos, R = self.foot_target[foot]
            pts += list(self.sole_corners(foot, pos, R))
        self.stance_hull = geo.convex_hull_2d(pts)
        self.stance_edges = geo.hull_edges(self.stance_hull)

    def sole_corners(self, foot, pos, R):
        s = self.body.sole[foot]
        out = []
        for sx in (-1, 1):
            for sy in (-1, 1):
                loc = s["center"] + s["R"] @ np.array([sx * s["half"][0], sy * s["half"][1], 0])
                w = pos + R @ loc
                out.append(w[:2])
        return out


# ----------------------------------------------------------------------------------------------
# Statics
# ----------------------------------------------------------------------------------------------
def statics(body, q, F_R, F_L, M_R=None, M_L=None, details=False):
    """Holding torques with the ground split of the specification (section 2).

    Returns (tau[nq], p[2]) or a dict when details=True."""
    m, d = body.model, body.data
    body.fk(q)
    com = np.array(pin.centerOfMass(m, d, q))
    tau = np.array(pin.computeGeneralizedGravity(m, d, q))
    gvec = body.gravity
    M = body.total_mass
    M_R = np.zeros(3) if M_R is None else M_R
    M_L = np.zeros(3) if M_L is None else M_L
    xR = d.oMf[body.fid["r_hand_grip"]].translation.copy()
    xL = d.oMf[body.fid["l_hand_grip"]].translation.copy()
    JR = body.frame_jac(body.fid["r_hand_grip"])
    JL = body.frame_jac(body.fid["l_hand_grip"])
    tau -= JR[:3].T @ F_R + JR[3:].T @ M_R + JL[:3].T @ F_L + JL[3:].T @ M_L
    # 1. resultant of the non-ground loads, ground wrench about the origin
    F_ext = M * gvec + F_R + F_L
    M_ext = M * cross(com, gvec) + cross(xR, F_R) + cross(xL, F_L) + M_R + M_L
    F = -F_ext
    Mg = -M_ext
    p = np.array([-Mg[1] / F[2], Mg[0] / F[2]])
    T = Mg[2] - (p[0] * F[1] - p[1] * F[0])
    # sole centres
    cs = {}
    Jf = {}
    for foot in ("l_foot", "r_foot"):
        o, R = body.frame_pose(body.fid[foot])
        cs[foot] = o + R @ body.sole[foot]["center"]
        Jf[foot] = body.frame_jac(body.fid[foot])
    cL, cR = cs["l_foot"], cs["r_foot"]
    # 2. share of the left foot
    dLR = (cL - cR)[:2]
    s = float(np.clip(((p - cR[:2]) @ dLR) / (dLR @ dLR), 0.0, 1.0))
    shares = {"l_foot": s, "r_foot": 1.0 - s}
    # 3. per-foot centres of pressure and forces
    delta = p - (s * cL[:2] + (1 - s) * cR[:2])
    h = max(com[2], 0.05)
    A = np.array([p[0], p[1], 0.0]) + F * h / F[2]
    e = np.array([dLR[0], dLR[1], 0.0]) / np.linalg.norm(dLR)
    g_lam = np.zeros(body.nq)
    g_x = np.zeros(body.nq)
    g_y = np.zeros(body.nq)
    foot_loads = {}
    for foot in ("l_foot", "r_foot"):
        pi = np.array([cs[foot][0] + delta[0], cs[foot][1] + delta[1], 0.0])
        Fi = shares[foot] * F[2] * (A - pi) / h
        Mi = np.array([0, 0, shares[foot] * T])
        Jp = body.point_jac(body.fid[foot], pi, Jf[foot])
        tau -= Jp.T @ Fi + Jf[foot][3:].T @ Mi
        sign = SIGMA[foot]
        g_lam -= sign * (Jp.T @ e)
        # J_w(foot)^T x_hat, J_w(foot)^T y_hat: rows 3, 4 of the LOCAL_WORLD_ALIGNED frame Jacobian
        g_x -= sign * Jf[foot][3]
        g_y -= sign * Jf[foot][4]
        foot_loads[foot] = (pi, Fi, Mi)
    # 4. internal wrench w = (lambda, m_x, m_y) minimising the squared actuated torques
    G = np.empty((body.nq, 3))
    G[:, 0], G[:, 1], G[:, 2] = g_lam, g_x, g_y
    Ga = G[body.act_idx]
    tau0a = tau[body.act_idx]
    w_star = min_norm_lstsq(Ga, tau0a)
    # 5. the soles bound the moments
    Fz_i = {foot: float(foot_loads[foot][1][2]) for foot in foot_loads}
    m_star = w_star[1:]
    axes = {}
    for foot in ("l_foot", "r_foot"):
        R = d.oMf[body.fid[foot]].rotation
        nu, nv = math.hypot(R[0, 0], R[1, 0]), math.hypot(R[0, 1], R[1, 1])
        axes[foot] = ((R[0, 0] / nu, R[1, 0] / nu), (R[0, 1] / nv, R[1, 1] / nv))
    alpha = sole_alpha(m_star, F[2], Fz_i, delta, axes, {f: body.sole[f]["half"] for f in cs})
    if alpha == 1.0:
        w = w_star.copy()
    else:
        mx, my = alpha * m_star[0], alpha * m_star[1]
        gl = Ga[:, 0]
        gg = float(gl @ gl)
        lam_ = -float(gl @ (tau0a + mx * Ga[:, 1] + my * Ga[:, 2])) / gg if gg > 0 else 0.0
        w = np.array([lam_, mx, my])
    tau0 = tau
    tau = tau0 + G @ w
    if not details:
        return tau, p
    lam, mx, my = (float(v) for v in w)
    cop, free = {}, {}
    loads_final = {}
    for foot in ("l_foot", "r_foot"):
        sg = SIGMA[foot]
        pi, Fi, Mi = foot_loads[foot]
        Fi = Fi + sg * lam * e
        Mi = Mi + sg * np.array([mx, my, 0.0])
        loads_final[foot] = (pi, Fi, Mi)
        if mx == 0.0 and my == 0.0:
            D = np.zeros(2)
        else:
            D = sg * np.array([-my, mx]) / Fz_i[foot]
        cop[foot] = np.array([pi[0] + D[0], pi[1] + D[1], 0.0])
        free[foot] = shares[foot] * T - (D[0] * Fi[1] - D[1] * Fi[0])
    return dict(tau=tau, p=p, T=T, s=s, lam=lam, m_x=mx, m_y=my, w=w, w_star=w_star, alpha=alpha,
                tau0=tau0, G=G, e=e, delta=delta, sole_axes=axes, foot_Fz=Fz_i,
                com=com, F=F, M=Mg, h=h, A=A, c=cs,
                foot_loads=loads_final, foot_cop=cop, foot_free_moment=free, xR=xR, xL=xL)


SIGMA = {"l_foot": 1.0, "r_foot": -1.0}
EIG_CUTOFF = 1e-12


def min_norm_lstsq(G, t):
    """Minimum-norm w minimising |t + G w|^2: the minimum-norm solution of (G^T G) w = -G^T t,
    eigenvalues of G^T G below EIG_CUTOFF x the largest treated as zero (section 2, step 4)."""
    A = G.T @ G
    rhs = -(G.T @ t)
    mu, V = np.linalg.eigh(A)
    top = float(mu.max())
    if not top > 0.0:
        return np.zeros(G.shape[1])
    keep = mu >= EIG_CUTOFF * top
    Vk = V[:, keep]
    return Vk @ ((Vk.T @ rhs) / mu[keep])


def sole_alpha(m_star, Fz, Fz_i, delta, axes, half):
    """The largest alpha in [0, 1] keeping every foot's moved centre of pressure within
    max(half-extent, its offset from the sole centre) along the foot's x and y axes (step 5).
    delta: o_i = p_i - c_i (horizontal), the same for both feet; axes[foot] = (u_i, v_i)."""
    if not Fz > 0.0:
        return 0.0
    mx, my = float(m_star[0]), float(m_star[1])
    if mx == 0.0 and my == 0.0:
        return 1.0
    ox, oy = float(delta[0]), float(delta[1])
    alpha = 1.0
    for foot in ("l_foot", "r_foot"):
        if not Fz_i[foot] > 0.0:
            return 0.0
        sg = SIGMA[foot] / Fz_i[foot]
        Dx, Dy = -sg * my, sg * mx
        for (ax, ay), a_half in zip(axes[foot], (float(half[foot][0]), float(half[foot][1]))):
            a = ox * ax + oy * ay
            b = Dx * ax + Dy * ay
            B = max(a_half, abs(a))
            if b > 0.0:
                alpha = min(alpha, (B - a) / b)
            elif b < 0.0:
                alpha = min(alpha, (-B - a) / b)
    return float(alpha) if alpha > 0.0 else 0.0


def half_loads(body, q, tau):
    mvc, _ = body.mvc(q)
    ta = tau[body.act_idx]
    f = np.empty(body.H)
    f[0::2] = np.maximum(ta, 0.0) / mvc[0::2]
    f[1::2] = np.maximum(-ta, 0.0) / mvc[1::2]
    return f, mvc


# ----------------------------------------------------------------------------------------------
# Clearance pairs
# ----------------------------------------------------------------------------------------------
class Pairs:
    """The clearance pairs of the specification for a task."""

    def __init__(self, task):
        b = task.body
        self.task = task
        nc = len(b.capsules)
        # self pairs: capsules on different links, not parent/child in the capsule tree,
        # not overlapping by more than 0.02 m at q = 0
        b.fk(np.zeros(b.nq))
        caps0 = b.world_capsules()
        self.self_pairs = []
        self.self_excluded = []
        for i in range(nc):
            for j in range(i + 1, nc):
                li, lj = b.capsules[i]["link"], b.capsules[j]["link"]
                if li == lj:
                    continue
                if b.cap_parent.get(li) == lj or b.cap_parent.get(lj) == li:
                    self.self_excluded.append((li, lj, "parent-child"))
                    continue
                dist, _, _ = geo.seg_seg(caps0[i][0], caps0[i][1], caps0[j][0], caps0[j][1])
                dist -= caps0[i][2] + caps0[j][2]
                if dist < -0.02:
                    self.self_excluded.append((li, lj, f"overlap {dist:.4f} at q=0"))
                    continue
                self.self_pairs.append((i, j))
        # capsule-obstacle pairs: all
        self.obs_pairs = [(i, k) for i in range(nc) for k in range(len(task.obstacles))]
        # held objects (statement section 4): per distinct phase, every capsule outside the arms
        # against each held box of the phases sharing the posture (appended after the self pairs)
        self.nonarm_caps = [i for i in range(nc) if b.capsules[i]["link"] not in b.arm_links]
        self.held_pairs = [[(i, k) for i in self.nonarm_caps for k in range(len(g["held"]))]
                           for g in task.groups]
        # foot-box vs obstacle pairs (constant under the stance constraint; evaluated, not optimised)
        self.box_pairs = []
        for bi, bx in enumerate(b.boxes):
            for k, ob in enumerate(task.obstacles):
                foot_box = bx["link"] in ("r_foot", "l_foot") and b.first_box.get(bx["link"]) is bx
                if foot_box and ob["kind"] == 2 and ob["floor"]:
                    continue
                self.box_pairs.append((bi, k))

    def n_pairs(self, gi=None):
        """Rows of distances(gi): obstacle, self and (for a distinct phase gi) held-object pairs."""
        return len(self.obs_pairs) + len(self.self_pairs) + \
            (len(self.held_pairs[gi]) if gi is not None else 0)

    def names(self, gi=None):
        b, t = self.task.body, self.task
        out = [f"{b.capsules[i]['link']} | {t.obstacles[k]['name']}" for i, k in self.obs_pairs]
        out += [f"{b.capsules[i]['link']} | {b.capsules[j]['link']}" for i, j in self.self_pairs]
        if gi is not None:
            out += [f"{b.capsules[i]['link']} | held object" + (f" {k}" if k else "")
                    for i, k in self.held_pairs[gi]]
        return out

    def _arrays(self):
        if getattr(self, "_arr", None) is None:
            t = self.task
            obs = t.obstacles
            self._arr = dict(
                okind=np.array([o["kind"] for o in obs], np.int64),
                ocenter=np.array([o["center"] for o in obs], float).reshape(-1, 3),
                oR=np.array([o["R"] for o in obs], float).reshape(-1, 3, 3),
                ohalf=np.array([o["half"] for o in obs], float).reshape(-1, 3),
                oradius=np.array([o["radius"] for o in obs], float),
                ohalf_h=np.array([o["half_h"] for o in obs], float),
                onormal=np.array([o["normal"] for o in obs], float).reshape(-1, 3),
                ooffset=np.array([o["offset"] for o in obs], float),
                obs_pairs=np.array(self.obs_pairs, np.int64).reshape(-1, 2),
                self_pairs=np.array(self.self_pairs, np.int64).reshape(-1, 2),
                rad=np.array([c["r"] for c in t.body.capsules], float))
        return self._arr

    def _held_arrays(self, gi):
        if getattr(self, "_harr", None) is None:
            self._harr = {}
        if gi not in self._harr:
            held = self.task.groups[gi]["held"]
            n = len(held)
            self._harr[gi] = dict(
                okind=np.zeros(n, np.int64),
                ocenter=np.array([c for c, _ in held], float).reshape(-1, 3),
                oR=np.array([np.eye(3)] * n, float).reshape(-1, 3, 3),   # axis-aligned
                ohalf=np.array([h for _, h in held], float).reshape(-1, 3),
                oradius=np.zeros(n), ohalf_h=np.zeros(n), onormal=np.zeros((n, 3)),
                ooffset=np.zeros(n),
                pairs=np.array(self.held_pairs[gi], np.int64).reshape(-1, 2))
        return self._harr[gi]

    def distances(self, with_jac=False, rows=None, gi=None):
        """Signed distances (after body.fk) of capsule-obstacle then self pairs, then (for a
        distinct phase gi) the non-arm capsules against the phase's held boxes; optional Jacobian
        (only for the listed rows when rows is given; the other rows are zero)."""
        b = self.task.body
        ar = self._arrays()
        caps = b.world_capsules()
        A = np.array([c[0] for c in caps])
        B = np.array([c[1] for c in caps])
        dist, w1, w2, nrm = geo.all_distances(A, B, ar["rad"], ar["okind"], ar["ocenter"], ar["oR"],
                                              ar["ohalf"], ar["oradius"], ar["ohalf_h"],
                                              ar["onormal"], ar["ooffset"], ar["obs_pairs"],
                                              ar["self_pairs"])
        nh = len(self.held_pairs[gi]) if gi is not None else 0
        if nh:
            ha = self._held_arrays(gi)
            hd, hw1, hw2, hn = geo.all_distances(A, B, ar["rad"], ha["okind"], ha["ocenter"],
                                                 ha["oR"], ha["ohalf"], ha["oradius"],
                                                 ha["ohalf_h"], ha["onormal"], ha["ooffset"],
                                                 ha["pairs"], np.zeros((0, 2), np.int64))
            dist = np.concatenate([dist, hd])
            w1 = np.vstack([w1, hw1])
            w2 = np.vstack([w2, hw2])
            nrm = np.vstack([nrm, hn])
        if not with_jac:
            return dist, None
        n = len(dist)
        J = np.zeros((n, b.nq))
        fj = {}

        def jac(ci, p):
            fid = b.capsules[ci]["fid"]
            if fid not in fj:
                fj[fid] = b.frame_jac(fid)
            return b.point_jac(fid, p, fj[fid])

        no = len(self.obs_pairs)
        ns = len(self.self_pairs)
        for r in (range(n) if rows is None else rows):
            if r < no:
                ci = self.obs_pairs[r][0]
                J[r] = nrm[r] @ jac(ci, w1[r])
            elif r < no + ns:
                ci, cj = self.self_pairs[r - no]
                J[r] = nrm[r] @ (jac(ci, w1[r]) - jac(cj, w2[r]))
            else:
                ci = self.held_pairs[gi][r - no - ns][0]
                J[r] = nrm[r] @ jac(ci, w1[r])
        return dist, J

    def box_distances(self):
        b, t = self.task.body, self.task
        out = []
        for bi, k in self.box_pairs:
            bx = b.boxes[bi]
            o, R = b.frame_pose(bx["fid"])
            ob = t.obstacles[k]
            dd = geo.box_obstacle_distance(o + R @ bx["center"], R @ bx["R"], bx["half"], ob["kind"],
                                           ob["center"], ob["R"], ob["half"], ob["radius"],
                                           ob["half_h"], ob["normal"], ob["offset"])
            out.append((f"{bx['link']} (box) | {ob['name']}", dd))
        return out


# ----------------------------------------------------------------------------------------------
# Evaluation of a plan
# ----------------------------------------------------------------------------------------------
ZONE_WEIGHT = 10.0    # statement: "the objective adds 10 * sum v_i (per radian, per distinct posture)"
U_OFFSET = 1e-3       # statement: fatigue term ln(sum U + 1e-3)


class Problem:
    def __init__(self, task, zones=False):
        self.task = task
        self.body = task.body
        self.pairs = Pairs(task)
        # zones + gaze (statement section 4), optional; with zones the fatigue-only objective is
        # ln(sum U + 1e-3) + 10 * sum of the zone slacks
        self.zones = bool(zones)
        from . import zones as Z
        self.Z = Z
        self.zm = Z.ZoneModel(self.body)
        self.zone_limits, self.holds = Z.group_limits(task)
        # the hold's limits alone (without the free hand's 10 deg, statement of 2026-12-07):
        # the "row above" against which the statement's plan reports zone excesses
        self.zone_limits_hold, _ = Z.group_limits(task, free_arm=False)
        self.gaze_points = Z.group_gaze_points(task) if self.zm.has_gaze else [[] for _ in range(task.P)]
        # rest loads (no hand load)
        tau, p = statics(self.body, task.rest_q, np.zeros(3), np.zeros(3))
        self.rest_loads, _ = half_loads(self.body, task.rest_q, tau)

    def zone_slacks(self, gi, q):
        """The smallest feasible slacks of a posture: v_i = max(g_i(q), 0) [rad]."""
        return np.maximum(self.zm.rows(q, self.zone_limits[gi]), 0.0)

    def objective(self, total_u, qs):
        """The plan's objective: total U without zones; ln(U + 1e-3) + 10 sum v with zones."""
        if not self.zones:
            return float(total_u)
        pen = sum(float(self.zone_slacks(gi, q).sum()) for gi, q in enumerate(qs))
        return math.log(total_u + U_OFFSET) + ZONE_WEIGHT * pen

    def loads_matrix(self, phase_loads):
        return np.vstack(list(phase_loads) + [self.rest_loads])

    def fatigue(self, phase_loads):
        t = self.task
        L = self.loads_matrix(phase_loads)
        U, c, tex = fat.simulate_real(L, t.ks, t.step_idx, t.step_dur, t.cycles, t.r_rest, t.f_lim)
        return U, c, tex

    def fatigue_grad(self, phase_loads):
        t = self.task
        L = self.loads_matrix(phase_loads).astype(np.complex128)
        U, G = fat.simulate_grad(L, t.ks, t.step_idx, t.step_dur, t.cycles, t.r_rest, t.f_lim,
                                 t.P)
        return U, G

    def hand_errors(self, gi):
        t, b = self.task, self.body
        out = {}
        for h, tgt in t.groups[gi]["targets"].items():
            x = b.data.oMf[b.fid[f"{h}_hand_grip"]].translation
            out[h] = np.array(x) - tgt
        return out

    def foot_errors(self):
        t, b = self.task, self.body
        out = {}
        for foot in ("l_foot", "r_foot"):
            pos, R = b.frame_pose(b.fid[foot])
            pt, Rt = t.foot_target[foot]
            out[foot] = (pos - pt, pin.log3(Rt.T @ R))
        return out

    def evaluate(self, postures, rest_q=None):
        """postures: list of q (one per distinct phase). Returns a JSON-able report."""
        t, b = self.task, self.body
        rest_q = t.rest_q if rest_q is None else rest_q
        report = dict(task=t.key, task_name=t.name, fatigue_set=t.fatigue_set, cycles=t.cycles,
                      rest_s=t.rest_s, stance=dict(width_m=t.stance_width, forward_m=t.stance_forward,
                                                   toe_out_deg=math.degrees(t.toe_out)),
                      clearance_m=t.clearance, balance_margin_m=t.balance_margin)
        phase_loads = []
        preps = []
        max_unact = 0.0
        for gi, q in enumerate(list(postures) + [rest_q]):
            is_rest = gi == t.P
            if is_rest:
                FR = FL = np.zeros(3)
                gname = "rest"
            else:
                FR, FL = t.groups[gi]["forces"]["r"], t.groups[gi]["forces"]["l"]
                gname = t.groups[gi]["name"]
            st = statics(b, q, FR, FL, details=True)
            f, mvc = half_loads(b, q, st["tau"])
            unact = st["tau"][b.unact_idx]
            max_unact = max(max_unact, float(np.max(np.abs(unact))))
            if not is_rest:
                phase_loads.append(f)
            b.fk(q)
            hgi = None if is_rest else gi
            dist, _ = self.pairs.distances(gi=hgi)
            nob = len(self.pairs.obs_pairs)
            nself = len(self.pairs.self_pairs)
            names = self.pairs.names(gi=hgi)
            box = self.pairs.box_distances()
            # support polygon from the actual feet
            pts = []
            for foot in ("l_foot", "r_foot"):
                pos, R = b.frame_pose(b.fid[foot])
                pts += t.sole_corners(foot, pos, R)
            hull = geo.convex_hull_2d(pts)
            bal = geo.point_polygon_signed_distance(st["p"], hull)
            ferr = self.foot_errors()
            herr = self.hand_errors(gi) if not is_rest else {}
            lim_viol = np.maximum(b.lower - q, 0) + np.maximum(q - b.upper, 0)
            obs_min_i = int(np.argmin(dist[:nob])) if nob else None
            self_min_i = nob + int(np.argmin(dist[nob:nob + nself])) if nself else None
            held_min_i = nob + nself + int(np.argmin(dist[nob + nself:])) \
                if len(dist) > nob + nself else None
            rep = dict(
                name=gname,
                members=t.groups[gi]["members"] if not is_rest else ["rest"],
                posture=b.q_to_dict(q),
                hand_force_r=FR.tolist(), hand_force_l=FL.tolist(),
                torques={n: float(st["tau"][b.qidx[n]]) for n in b.actuated},
                unactuated_torques={n: float(st["tau"][b.qidx[n]]) for n in b.unactuated},
                loads={b.half_names[i]: float(f[i]) for i in range(b.H)},
                mvc={b.half_names[i]: float(mvc[i]) for i in range(b.H)},
                centre_of_pressure=st["p"].tolist(), left_share=st["s"], lambda_internal=st["lam"],
                internal_wrench=dict(w_star=st["w_star"].tolist(), alpha=st["alpha"],
                                     **{"lambda": st["lam"]}, m_x=st["m_x"], m_y=st["m_y"]),
                feet={f: dict(centre_of_pressure=st["foot_cop"][f].tolist(),
                              free_moment=float(st["foot_free_moment"][f]),
                              force=st["foot_loads"][f][1].tolist()) for f in ("l_foot", "r_foot")},
                com=st["com"].tolist(),
                residuals=dict(
                    hand_error_m={h: float(np.linalg.norm(v)) for h, v in herr.items()},
                    foot_position_error_m={k: float(np.linalg.norm(v[0])) for k, v in ferr.items()},
                    foot_orientation_error_rad={k: float(np.linalg.norm(v[1])) for k, v in ferr.items()},
                    min_clearance_obstacle_m=float(dist[obs_min_i]) if obs_min_i is not None else None,
                    min_clearance_obstacle_pair=names[obs_min_i] if obs_min_i is not None else None,
                    min_clearance_self_m=float(dist[self_min_i]) if self_min_i is not None else None,
                    min_clearance_self_pair=names[self_min_i] if self_min_i is not None else None,
                    # held objects: the non-arm capsules against the held boxes of the phases
                    # sharing the posture (None without a held box; a value above geometry.FAR is
                    # a lower bound)
                    min_clearance_held_m=float(dist[held_min_i]) if held_min_i is not None else None,
                    min_clearance_held_pair=names[held_min_i] if held_min_i is not None else None,
                    min_clearance_foot_box_m=min((d for _, d in box), default=None),
                    balance_margin_m=bal,
                    joint_limit_violation_rad=float(lim_viol.max()),
                    max_unactuated_torque_nm=float(np.max(np.abs(unact))),
                ))
            if not is_rest:
                Z = self.Z
                L = self.zone_limits[gi]
                th = self.zm.angles(q)
                g = self.zm.rows(q, L)
                Lh = self.zone_limits_hold[gi]
                rep["zones"] = [dict(row=Z.ROW_NAMES[i], angle_deg=math.degrees(th[i]),
                                     limit_deg=math.degrees(L[i]), g=float(g[i]),
                                     slack_rad=float(max(g[i], 0.0)),
                                     excess_deg=float(max(math.degrees(th[i] - L[i]), 0.0)),
                                     # against the hold's limit (differs from limit_deg only on
                                     # a free hand's upper-arm row)
                                     limit_hold_deg=math.degrees(Lh[i]),
                                     excess_hold_deg=float(max(math.degrees(th[i] - Lh[i]), 0.0)))
                                for i in range(Z.NROW)]
                rep["zone_slack_sum_rad"] = float(np.maximum(g, 0).sum())
                pts = self.gaze_points[gi]
                if pts:
                    gv = self.zm.gaze_values(q, pts)
                    rep["residuals"]["gaze_margin"] = float(gv.min())
                    rep["residuals"]["gaze_angle_deg"] = self.zm.gaze_angles_deg(q, pts)
                    rep["gaze_points"] = [list(map(float, x)) for x in pts]
            preps.append(rep)
        U, c, tex = self.fatigue(phase_loads)
        total = float(U.sum())
        ex = tex >= 0
        report["total_u_min"] = total
        report["u_per_half_joint"] = {b.half_names[i]: float(U[i]) for i in range(b.H)}
        report["capacity_end"] = {b.half_names[i]: float(c[i]) for i in range(b.H)}
        report["min_capacity_end"] = float(c.min())
        report["exhausted"] = bool(ex.any())
        report["exhaustion_time_min"] = float(tex[ex].min()) if ex.any() else None
        report["exhausted_half_joints"] = {b.half_names[i]: float(tex[i]) for i in np.where(ex)[0]}
        report["max_unactuated_torque_nm"] = max_unact
        report["phases"] = preps[:-1]
        report["rest"] = preps[-1]
        report["zones_on"] = self.zones
        report["objective"] = self.objective(total, list(postures))
        report["feasible"] = feasibility(report, t, gaze=self.zones)
        return report


def feasibility(report, task, tol_eq=1e-4, tol_ineq=1e-6, tol_lim=1e-9, gaze=False):
    bad = []
    for ph in report["phases"]:
        r = ph["residuals"]
        if gaze and r.get("gaze_margin") is not None and r["gaze_margin"] < -tol_ineq:
            bad.append(f"{ph['name']}: gaze margin {r['gaze_margin']:.3g}")
        for h, v in r["hand_error_m"].items():
            if v > tol_eq:
                bad.append(f"{ph['name']}: hand {h} error {v:.3g}")
        for k, v in r["foot_position_error_m"].items():
            if v > tol_eq:
                bad.append(f"{ph['name']}: {k} position error {v:.3g}")
        for k, v in r["foot_orientation_error_rad"].items():
            if v > tol_eq:
                bad.append(f"{ph['name']}: {k} orientation error {v:.3g}")
        for key in ("min_clearance_obstacle_m", "min_clearance_self_m", "min_clearance_foot_box_m",
                    "min_clearance_held_m"):
            v = r.get(key)
            if v is not None and v < task.clearance - tol_ineq:
                bad.append(f"{ph['name']}: {key} {v:.4g}")
        if r["balance_margin_m"] < task.balance_margin - tol_ineq:
            bad.append(f"{ph['name']}: balance margin {r['balance_margin_m']:.4g}")
        if r["joint_limit_violation_rad"] > tol_lim:
            bad.append(f"{ph['name']}: joint limit violation {r['joint_limit_violation_rad']:.3g}")
    return dict(ok=not bad, violations=bad)


def load_task(key_or_path):
    p = key_or_path
    if not os.path.exists(p):
        p = os.path.join(INPUTS, f"{key_or_path}.yaml")
    return Task(p)
