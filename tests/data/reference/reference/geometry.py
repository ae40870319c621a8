"""Signed distances between capsules, boxes, vertical cylinders and half-spaces (numba).

Every function returns the signed distance (negative when overlapping) together with the witness
point on the capsule's axis (or the capsules' axes) and the unit normal n such that moving the
witness point on the first shape by dp changes the distance by n . dp (to first order).
"""
import math

import numpy as np
from numba import njit


FAR = 0.3  # beyond this a capsule-obstacle distance is reported as a lower bound


@njit(cache=True)
def seg_seg(p1, q1, p2, q2):
    """Closest points of segments [p1,q1] and [p2,q2] (Ericson, Real-Time Collision Detection 5.1.9).
    Returns (dist, c1, c2)."""
    d1 = q1 - p1
    d2 = q2 - p2
    r = p1 - p2
    a = d1 @ d1
    e = d2 @ d2
    f = d2 @ r
    eps = 1e-14
    if a <= eps and e <= eps:
        s = 0.0
        t = 0.0
    elif a <= eps:
        s = 0.0
        t = min(max(f / e, 0.0), 1.0)
    else:
        c = d1 @ r
        if e <= eps:
            t = 0.0
            s = min(max(-c / a, 0.0), 1.0)
        else:
            b = d1 @ d2
            denom = a * e - b * b
            if denom > eps * a * e:
                s = min(max((b * f - c * e) / denom, 0.0), 1.0)
            else:
                s = 0.0
            t = (b * s + f) / e
            if t < 0.0:
                t = 0.0
                s = min(max(-c / a, 0.0), 1.0)
            elif t > 1.0:
                t = 1.0
                s = min(max((b - c) / a, 0.0), 1.0)
    c1 = p1 + d1 * s
    c2 = p2 + d2 * t
    dv = c1 - c2
    return math.sqrt(dv @ dv), c1, c2


@njit(cache=True)
def point_box_sd(p, center, R, half):
    """Signed distance of point p to an oriented box and its gradient (world)."""
    loc = R.T @ (p - center)
    qv = np.abs(loc) - half
    out = np.maximum(qv, 0.0)
    no = math.sqrt(out @ out)
    mx = qv.max()
    g = np.zeros(3)
    if no > 0.0:
        for i in range(3):
            g[i] = math.copysign(out[i] / no, loc[i]) if out[i] > 0.0 else 0.0
        sd = no
    else:
        ax = np.argmax(qv)
        g[ax] = 1.0 if loc[ax] >= 0.0 else -1.0
        sd = mx
    return sd, R @ g


@njit(cache=True)
def point_cyl_sd(p, center, radius, half_h):
    """Signed distance of p to a cylinder with vertical axis (world z) and its gradient."""
    dx = p[0] - center[0]
    dy = p[1] - center[1]
    dz = p[2] - center[2]
    r = math.sqrt(dx * dx + dy * dy)
    d1 = r - radius
    d2 = abs(dz) - half_h
    o1 = max(d1, 0.0)
    o2 = max(d2, 0.0)
    no = math.sqrt(o1 * o1 + o2 * o2)
    if r > 1e-15:
        ux = dx / r
        uy = dy / r
    else:
        ux = 1.0
        uy = 0.0
    sz = 1.0 if dz >= 0.0 else -1.0
    g = np.zeros(3)
    if no > 0.0:
        g[0] = ux * o1 / no
        g[1] = uy * o1 / no
        g[2] = sz * o2 / no
        return no, g
    if d1 >= d2:
        g[0] = ux
        g[1] = uy
        return d1, g
    g[2] = sz
    return d2, g


@njit(cache=True)
def _seg_convex_sd(a, b, kind, center, R, half, radius, half_h):
    """min over t in [0,1] of the (convex) signed distance of a + t (b - a) to a box (kind 0) or a
    vertical cylinder (kind 1): golden-section search. Returns (sd, witness, normal)."""
    gr = (math.sqrt(5.0) - 1.0) / 2.0
    lo = 0.0
    hi = 1.0
    d = b - a
    if math.sqrt(d @ d) < 1e-12:
        x = a.copy()
        if kind == 0:
            sd, g = point_box_sd(x, center, R, half)
        else:
            sd, g = point_cyl_sd(x, center, radius, half_h)
        return sd, x, g
    x1 = hi - gr * (hi - lo)
    x2 = lo + gr * (hi - lo)

    def ev(t):
        x = a + t * d
        if kind == 0:
            return point_box_sd(x, center, R, half)[0]
        return point_cyl_sd(x, center, radius, half_h)[0]

    f1 = ev(x1)
    f2 = ev(x2)
    for _ in range(80):
        if f1 < f2:
            hi = x2
            x2 = x1
            f2 = f1
            x1 = hi - gr * (hi - lo)
            f1 = ev(x1)
        else:
            lo = x1
            x1 = x2
            f1 = f2
            x2 = lo + gr * (hi - lo)
            f2 = ev(x2)
        if hi - lo < 1e-13:
            break
    t = 0.5 * (lo + hi)
    # the end points may be better (monotone case)
    best_t = t
    best = ev(t)
    f0 = ev(0.0)
    if f0 < best:
        best = f0
        best_t = 0.0
    f1e = ev(1.0)
    if f1e < best:
        best = f1e
        best_t = 1.0
    x = a + best_t * d
    if kind == 0:
        sd, g = point_box_sd(x, center, R, half)
    else:
        sd, g = point_cyl_sd(x, center, radius, half_h)
    return sd, x, g


@njit(cache=True)
def capsule_obstacle(a, b, r, kind, center, R, half, radius, half_h, normal, offset):
    """Signed distance between capsule (axis a-b, radius r) and an obstacle:
    kind 0 box (center, R, half sizes), 1 vertical cylinder (center, radius, half height),
    2 half-space {x : normal.x <= offset} (solid behind the plane).
    Returns (dist, witness on axis, normal pointing away from the obstacle)."""
    if kind == 2:
        da = normal @ a - offset
        db = normal @ b - offset
        if da <= db:
            return da - r, a.copy(), normal.copy()
        return db - r, b.copy(), normal.copy()
    # cheap lower bound from the segment's bounding sphere: far pairs skip the exact search
    mid = 0.5 * (a + b)
    hl = 0.5 * math.sqrt((b - a) @ (b - a))
    if kind == 0:
        sdm, gm = point_box_sd(mid, center, R, half)
    else:
        sdm, gm = point_cyl_sd(mid, center, radius, half_h)
    if sdm - hl - r > FAR:
        return sdm - hl - r, mid, gm
    sd, x, g = _seg_convex_sd(a, b, kind, center, R, half, radius, half_h)
    return sd - r, x, g


def box_corners(center, R, half):
    s = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float)
    return center + (s * half) @ R.T


def box_obstacle_distance(center, R, half, kind, ocenter, oR, ohalf, oradius, ohalf_h, onormal,
                          ooffset):
    """Signed distance (lower bound when overlapping) between a body box and an obstacle.
    Used only for the feet, which are fixed by the stance. Computed as the minimum over the box
    of the obstacle's convex signed-distance function (exact when separated)."""
    from scipy.optimize import minimize

    if kind == 2:
        return float(np.min(box_corners(center, R, half) @ onormal - ooffset))

    def fun(u):
        x = center + R @ u
        if kind == 0:
            sd, g = point_box_sd(x, ocenter, oR, ohalf)
        else:
            sd, g = point_cyl_sd(x, ocenter, oradius, ohalf_h)
        return sd, R.T @ g

    best = np.inf
    starts = [np.zeros(3)] + [c for c in (box_corners(np.zeros(3), np.eye(3), half))]
    for u0 in starts:
        res = minimize(fun, u0, jac=True, method="L-BFGS-B",
                       bounds=[(-half[i], half[i]) for i in range(3)],
                       options={"ftol": 1e-15, "gtol": 1e-12, "maxiter": 500})
        best = min(best, float(res.fun))
    return best


def convex_hull_2d(points):
    """Andrew's monotone chain; returns counter-clockwise vertices."""
    pts = sorted(set((float(x), float(y)) for x, y in points))
    if len(pts) <= 2:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    upper = []
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def hull_edges(hull):
    """Inward unit normals n and offsets o of the hull edges: inside <=> n.p - o >= 0 for all."""
    ns, os_ = [], []
    m = len(hull)
    for i in range(m):
        a = hull[i]
        b = hull[(i + 1) % m]
        t = (b - a) / np.linalg.norm(b - a)
        n = np.array([-t[1], t[0]])  # left normal = inward for a CCW polygon
        ns.append(n)
        os_.append(n @ a)
    return np.array(ns), np.array(os_)


def point_polygon_signed_distance(p, hull):
    """Distance of p to the boundary of a convex polygon, positive inside."""
    n, o = hull_edges(hull)
    vals = n @ p - o
    if np.all(vals >= 0):
        return float(vals.min())
    # outside: Euclidean distance to the polygon
    best = np.inf
    m = len(hull)
    for i in range(m):
        a = hull[i]
        b = hull[(i + 1) % m]
        ab = b - a
        t = np.clip((p - a) @ ab / (ab @ ab), 0, 1)
        best = min(best, float(np.linalg.norm(p - (a + t * ab))))
    return -best


@njit(cache=True)
def all_distances(A, B, rad, okind, ocenter, oR, ohalf, oradius, ohalf_h, onormal, ooffset,
                  obs_pairs, self_pairs):
    """Batch version: capsule-obstacle pairs then capsule-capsule pairs.
    Returns dist[n], w1[n,3] (witness on the first capsule's axis), w2[n,3] (on the second
    capsule's axis, self pairs only), nrm[n,3] (unit normal, distance gradient wrt w1)."""
    no = obs_pairs.shape[0]
    ns = self_pairs.shape[0]
    n = no + ns
    dist = np.empty(n)
    w1 = np.zeros((n, 3))
    w2 = np.zeros((n, 3))
    nrm = np.zeros((n, 3))
    for r in range(no):
        ci = obs_pairs[r, 0]
        k = obs_pairs[r, 1]
        d, x, g = capsule_obstacle(A[ci], B[ci], rad[ci], okind[k], ocenter[k], oR[k], ohalf[k],
                                   oradius[k], ohalf_h[k], onormal[k], ooffset[k])
        dist[r] = d
        w1[r] = x
        nrm[r] = g
    for r in range(ns):
        i = self_pairs[r, 0]
        j = self_pairs[r, 1]
        d, c1, c2 = seg_seg(A[i], B[i], A[j], B[j])
        dist[no + r] = d - rad[i] - rad[j]
        w1[no + r] = c1
        w2[no + r] = c2
        if d > 1e-12:
            nrm[no + r] = (c1 - c2) / d
    return dist, w1, w2, nrm
