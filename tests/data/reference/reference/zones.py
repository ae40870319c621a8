"""Acceptable posture zones and the gaze constraint (optimisation-problem.md section 4).

Written from the statement only:
  * 25 zone rows per phase posture, g_i = theta_i - L_i <= 0 (the upper-arm rows are
    (cos L - cos theta)/sin L, as the statement writes them), elastic with slack v_i >= 0;
    the pelvis's forward heading f (used by the trunk inclination atan2(a.f, a_z), the side
    bending asin(a.l), l = z x f, and the turn rows) is taken from its hip axis since the
    statement's third revision of 2026-12-06: f = (R_P y with its z dropped, normalised) x z; if
    that projection is shorter than 1e-9, the horizontal unit vector along R_P x projected on the
    floor; world x if that one is too (hip_axis_heading). A stoop (a tilt about the hip axis)
    leaves f level and unchanged, and the trunk inclination is continuous as the tilt passes 90
    deg. (Before: f = R_P x projected on the floor, world x if shorter than 1e-9; from the
    statement's second revision to its third, the turn rows alone used the hip-axis heading.)
    rows 24-25 (statement of 2026-12-06): the trunk's turn against the feet = the trunk twist
    (wrap(2 atan2(k, w)) of R_P^T R_T) + the pelvis's turn against the feet
    atan2((h x g)_z, h.g), h = sum of the unit horizontal projections of the x axes of the links
    r_foot and l_foot (a projection shorter than 1e-9 left out; the pelvis's turn is 0 if
    |h| < 1e-9 or the body has no such links, so the row is the twist), g = f, the pelvis's
    heading from its hip axis; the sum is not wrapped (the statement says so);
  * limits from the phase's hold (run of consecutive phases of the same work: same targets, hand
    forces and gaze; across the cycle's end when the task has no rest); a posture shared by
    several phases takes the smallest limit per row;
  * a free hand's upper arm (statement of 2026-12-07, session 15): where the phase gives that
    hand no target, the arm row's limit is min(the hold's limit, 10 deg) (limits_for_phase);
  * gaze: eye point e = head cylinder's middle + 0.8 r along the head link's x; line of sight
    s = R_H (cos 15deg, 0, -sin 15deg); row s.d_hat - cos 15deg >= 0.
Jacobians: central finite differences of the kinematics (FD_STEP), checked in verify.py.
"""
import math

import numpy as np
import pinocchio as pin

DEG = math.pi / 180.0
FD_STEP = 1e-6

ROW_NAMES = [
    "trunk inclination (forward)", "trunk leaning back",
    "trunk side bending left", "trunk side bending right",
    "trunk twist left", "trunk twist right",
    "right upper-arm elevation", "left upper-arm elevation",
    "head inclination (forward)", "head tilted back",
    "neck flexion",
    "neck side bending left", "neck side bending right",
    "neck twist left", "neck twist right",
    "right wrist flexion", "right wrist extension",
    "right wrist radial deviation", "right wrist ulnar deviation",
    "left wrist flexion", "left wrist extension",
    "left wrist radial deviation", "left wrist ulnar deviation",
    "trunk turn against the feet left", "trunk turn against the feet right",
]
NROW = len(ROW_NAMES)
ARM_ROWS = (6, 7)
TWIST_ROWS = (4, 5)
TURN_ROWS = (23, 24)


def _wrap(a):
    """wrap to (-pi, pi]"""
    a = math.fmod(a + math.pi, 2 * math.pi)
    if a <= 0:
        a += 2 * math.pi
    return a - math.pi


def _unit_or(v, fallback):
    n = np.linalg.norm(v)
    return v / n if n >= 1e-9 else np.array(fallback, float)


def time_limit(t_min, T20, T60):
    """20 deg + 40 deg * clamp((T20 - t)/(T20 - T60), 0, 1) [rad]"""
    x = min(max((T20 - t_min) / (T20 - T60), 0.0), 1.0)
    return (20.0 + 40.0 * x) * DEG


def limits_for_hold(hold_s):
    """The 25 limits [rad] for a hold of hold_s seconds (a hold <= 4 s is a movement: the
    trunk and arm limits are then 60 deg, the same value the formula gives for t <= 1 min)."""
    t = hold_s / 60.0
    if hold_s <= 4.0:
        trunk = arm = 60.0 * DEG
        head = 85.0 * DEG
    else:
        trunk = time_limit(t, 4.0, 1.0)
        arm = time_limit(t, 3.0, 1.0)
        # head inclination: 25 deg + 60 deg * clamp((8 - t)/(8 - 1), 0, 1)
        head = (25.0 + 60.0 * min(max((8.0 - t) / 7.0, 0.0), 1.0)) * DEG
    L = np.array([
        trunk, 5 * DEG,
        10 * DEG, 10 * DEG,
        10 * DEG, 10 * DEG,
        arm, arm,
        head, 5 * DEG,
        25 * DEG,
        10 * DEG, 10 * DEG,
        45 * DEG, 45 * DEG,
        15 * DEG, 15 * DEG,
        10 * DEG, 10 * DEG,
        15 * DEG, 15 * DEG,
        10 * DEG, 10 * DEG,
        10 * DEG, 10 * DEG,     # trunk turned against the feet: 10 deg each way
    ])
    return L


class ZoneModel:
    def __init__(self, body):
        self.body = body
        m = body.model
        self.model = m
        self.data = m.createData()
        fid = m.getFrameId
        self.f_pelvis, self.f_trunk, self.f_head = fid("pelvis"), fid("trunk"), fid("head")
        self.f_arm = {s: (fid(f"{s}_upper_arm"), fid(f"{s}_forearm")) for s in ("r", "l")}
        # the feet (the turn against the feet is 0 for a body without these links)
        self.f_feet = [fid(n) for n in ("r_foot", "l_foot") if m.existFrame(n)]
        if len(self.f_feet) != 2:
            self.f_feet = []
        q = body.qidx
        self.i_neck_twist = q["neck_axial_rotation"]
        self.i_wrist = {s: (q[f"{s}_wrist_flexion"], q[f"{s}_wrist_deviation"]) for s in ("r", "l")}
        # gaze: the head link's collision cylinder
        self.has_gaze = False
        for c in body.capsules:
            if c["link"] == "head" and c.get("kind", "cylinder") == "cylinder" and \
                    np.linalg.norm(c["b"] - c["a"]) > 0:
                mid = 0.5 * (c["a"] + c["b"])
                self.eye_local = mid + 0.8 * c["r"] * np.array([1.0, 0.0, 0.0])
                self.has_gaze = True
                break
        self.sight_local = np.array([math.cos(15 * DEG), 0.0, -math.sin(15 * DEG)])

    def _fk(self, q):
        pin.forwardKinematics(self.model, self.data, q)
        pin.updateFramePlacements(self.model, self.data)

    def feet_x(self):
        """World x axes of the links r_foot and l_foot (after _fk); [] without them."""
        return [self.data.oMf[f].rotation[:, 0].copy() for f in self.f_feet]

    def angles(self, q):
        """The 25 signed angles theta_i [rad] in row order (row sign applied; arm rows: theta)."""
        self._fk(q)
        d = self.data
        arms = []
        for s in ("r", "l"):
            pu = d.oMf[self.f_arm[s][0]].translation
            pf = d.oMf[self.f_arm[s][1]].translation
            arms.append(pf - pu)
        wr = [(q[self.i_wrist[s][0]], q[self.i_wrist[s][1]]) for s in ("r", "l")]
        return angles_from_frames(d.oMf[self.f_pelvis].rotation, d.oMf[self.f_trunk].rotation,
                                  d.oMf[self.f_head].rotation, arms[0], arms[1],
                                  q[self.i_neck_twist], wr, feet_x=self.feet_x())

    def raw(self, q):
        """The unsigned named quantities, for reports and checks [rad]."""
        t = self.angles(q)
        return dict(trunk_inclination=t[0], trunk_side_bending=t[2], trunk_twist=t[4],
                    r_upper_arm=t[6], l_upper_arm=t[7], head_inclination=t[8], neck_flexion=t[10],
                    neck_side_bending=t[11], neck_twist=t[13], r_wrist_flexion=t[15],
                    r_wrist_deviation=t[17], l_wrist_flexion=t[19], l_wrist_deviation=t[21],
                    trunk_turn_against_feet=t[23], pelvis_turn_against_feet=t[23] - t[4])

    def rows(self, q, L):
        """g_i(q) = theta_i - L_i (arm rows (cos L - cos theta)/sin L)."""
        th = self.angles(q)
        g = th - L
        for r in ARM_ROWS:
            g[r] = (math.cos(L[r]) - math.cos(th[r])) / math.sin(L[r])
        return g

    def rows_jac(self, q, L, h=FD_STEP):
        g0 = self.rows(q, L)
        J = np.zeros((NROW, len(q)))
        for i in range(len(q)):
            qp = q.copy()
            qp[i] += h
            qm = q.copy()
            qm[i] -= h
            gp = self.rows(qp, L)
            gm = self.rows(qm, L)
            dg = gp - gm
            # twist and turn rows: guard the wrap at +-pi (of the twist and of the pelvis turn)
            for r in TWIST_ROWS + TURN_ROWS:
                dg[r] = _wrap(dg[r])
            J[:, i] = dg / (2 * h)
        return g0, J

    # --- gaze -----------------------------------------------------------------------------------
    def gaze_values(self, q, points):
        """s.d_hat - cos 15deg per gaze point (>= 0 feasible)."""
        self._fk(q)
        M = self.data.oMf[self.f_head]
        e = M.translation + M.rotation @ self.eye_local
        s = M.rotation @ self.sight_local
        out = []
        for p in points:
            dv = np.asarray(p, float) - e
            out.append(float(s @ dv) / float(np.linalg.norm(dv)) - math.cos(15 * DEG))
        return np.array(out)

    def gaze_angles_deg(self, q, points):
        v = self.gaze_values(q, points) + math.cos(15 * DEG)
        return [math.degrees(math.acos(max(-1.0, min(1.0, x)))) for x in v]

    def gaze_jac(self, q, points, h=FD_STEP):
        v0 = self.gaze_values(q, points)
        J = np.zeros((len(points), len(q)))
        for i in range(len(q)):
            qp = q.copy()
            qp[i] += h
            qm = q.copy()
            qm[i] -= h
            J[:, i] = (self.gaze_values(qp, points) - self.gaze_values(qm, points)) / (2 * h)
        return v0, J


def x_axis_heading(RP):
    """The horizontal unit vector along R_P x projected on the floor; world x if that
    projection is shorter than 1e-9 (the pelvis heading f of the statement before its third
    revision of 2026-12-06; now only the fallback of hip_axis_heading)."""
    f = np.array(RP[:, 0], float)
    f[2] = 0.0
    return _unit_or(f, [1.0, 0.0, 0.0])


def hip_axis_heading(RP, fallback=None):
    """The pelvis's forward heading from its hip axis (the statement's f since its third
    revision of 2026-12-06, used by the trunk inclination, side bending and turn rows):
    (R_P y with its z dropped, normalised) x z; if that projection is shorter than 1e-9, the
    fallback (default: x_axis_heading(RP), the horizontal unit vector along R_P x projected on
    the floor, world x if that one is too). A tilt about the hip axis (a stoop) leaves it level
    and unchanged."""
    y = np.array(RP[:, 1], float)
    y[2] = 0.0
    n = np.linalg.norm(y)
    if n < 1e-9:
        return x_axis_heading(RP) if fallback is None else np.array(fallback, float)
    y /= n
    return np.array([y[1], -y[0], 0.0])   # y x z


def pelvis_turn(g, feet_x):
    """The pelvis's turn against the feet: atan2((h x g)_z, h.g), g the pelvis's heading from its
    hip axis (hip_axis_heading), h the sum of the unit horizontal projections of the feet's x
    axes (one shorter than 1e-9 left out); 0 if |h| < 1e-9 or there are no feet. Positive: the
    pelvis heading g turned to the left of h."""
    h = np.zeros(3)
    for x in feet_x:
        p = np.array(x, float)
        p[2] = 0.0
        n = np.linalg.norm(p)
        if n >= 1e-9:
            h += p / n
    if np.linalg.norm(h) < 1e-9:
        return 0.0
    return math.atan2(float(h[0] * g[1] - h[1] * g[0]), float(h @ g))


def angles_from_frames(RP, RT, RH, arm_r, arm_l, neck_twist, wrists, feet_x=()):
    """The statement's formulas from the world rotations of pelvis, trunk and head, the vectors
    upper-arm origin -> forearm origin, the neck twist joint, (flexion, deviation) per wrist and
    the world x axes of the links r_foot, l_foot (none: the turn against the feet is the twist)."""
    z = np.array([0.0, 0.0, 1.0])
    # f: the pelvis's heading from its hip axis (statement of 2026-12-06, third revision), with
    # the statement's fallbacks (the x axis's floor projection, then world x)
    f = hip_axis_heading(RP)
    l = np.cross(z, f)
    a = RT[:, 2]
    b = RH[:, 2]
    th_trunk = math.atan2(float(a @ f), float(a[2]))
    side = math.asin(max(-1.0, min(1.0, float(a @ l))))
    quat = pin.Quaternion(np.asarray(RP).T @ np.asarray(RT))
    quat.normalize()
    twist = _wrap(2.0 * math.atan2(quat.z, quat.w))
    arms = []
    for v in (arm_r, arm_l):
        e = np.asarray(v, float) / np.linalg.norm(v)
        arms.append(math.acos(max(-1.0, min(1.0, -float(e[2])))))
    yH = RH[:, 1]
    lH = np.array(yH, float)
    lH[2] = 0.0
    lH = _unit_or(lH, [0.0, 1.0, 0.0])
    fH = np.cross(lH, z)
    head_incl = math.atan2(float(b @ fH), float(b[2]))
    c = RT.T @ b
    lT = RT.T @ yH
    lT[2] = 0.0
    lT = _unit_or(lT, [0.0, 1.0, 0.0])
    fT = np.cross(lT, z)
    neck_flex = math.atan2(float(c @ fT), float(c[2]))
    neck_side = math.asin(max(-1.0, min(1.0, float(c @ lT))))
    nt = float(neck_twist)
    wr = []
    for fl, dv in wrists:
        wr += [fl, -fl, dv, -dv]
    turn = twist + pelvis_turn(f, feet_x)   # g = f; not wrapped
    return np.array([th_trunk, -th_trunk, side, -side, twist, -twist, arms[0], arms[1],
                     head_incl, -head_incl, neck_flex, neck_side, -neck_side, nt, -nt] + wr
                    + [turn, -turn])


def phase_holds(task):
    """Per phase (cycle order): its hold [s], the total duration of the run of consecutive phases
    with the same work (targets, hand forces, gaze) it belongs to; the run wraps over the cycle's
    end when the task has no rest."""
    ph = task.phases
    n = len(ph)
    work = [p.work_key for p in ph]
    wrap = task.rest_s <= 0
    holds = []
    for i in range(n):
        if wrap and all(w == work[0] for w in work):
            holds.append(sum(p.duration for p in ph))
            continue
        tot = ph[i].duration
        j = i - 1
        while True:
            if j < 0:
                if not wrap:
                    break
                j += n
            if j == i or work[j] != work[i]:
                break
            tot += ph[j].duration
            j -= 1
        j = i + 1
        while True:
            if j >= n:
                if not wrap:
                    break
                j -= n
            if j == i or work[j] != work[i]:
                break
            tot += ph[j].duration
            j += 1
        holds.append(tot)
    return holds


FREE_ARM_LIMIT = 10.0 * DEG


def limits_for_phase(phase, hold_s, free_arm=True):
    """The 25 limits [rad] of one phase: limits_for_hold(hold_s), and (statement of 2026-12-07,
    session 15) the upper-arm row of a free hand -- a hand the phase gives no target (the task
    reader's phase.targets has no "r" / "l" key) -- limited to min(L, 10 deg). free_arm=False
    gives the hold's limits alone (the "row above", against which the plan reports excesses)."""
    L = limits_for_hold(hold_s).copy()
    if free_arm:
        for row, hand in zip(ARM_ROWS, ("r", "l")):
            if hand not in phase.targets:
                L[row] = min(L[row], FREE_ARM_LIMIT)
    return L


def group_limits(task, free_arm=True):
    """Per distinct posture: the row-wise smallest limit over the phases that share it (each
    phase's limits from limits_for_phase: its hold's, a free hand's upper arm within 10 deg)."""
    holds = phase_holds(task)
    out = []
    for gi in range(task.P):
        Ls = [limits_for_phase(p, holds[i], free_arm)
              for i, p in enumerate(task.phases) if p.group == gi]
        out.append(np.min(np.vstack(Ls), axis=0))
    return out, holds


def group_gaze_points(task):
    """Per distinct posture: the distinct gaze points of its phases that are not gaze_free."""
    out = []
    for gi in range(task.P):
        pts = []
        for p in task.phases:
            if p.group != gi or p.gaze_free:
                continue
            g = p.gaze_point
            if not any(np.allclose(g, x, atol=0, rtol=0) for x in pts):
                pts.append(g)
        out.append(pts)
    return out
