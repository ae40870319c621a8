#!/usr/bin/env python3
"""Reference values for tests/suite/fatigue_recovery.rs, by numerical integration (scipy solve_ivp,
DOP853, rtol 1e-12) of the model as documented, independently of the library's closed forms:

    dc/dt = -k f c + R(f) (1 - c),   dU/dt = f / c^2      (t in minutes)
    R(f)  = R_rest x^2 (3 - 2x), x = 1 - f/f_lim for f < f_lim, 0 otherwise (perfusion form)
    exhaustion: first time c <= f while f is held.

Parameters: the `default-2026` set of data/fatigue_sets.yaml (k per region from the Frey-Law &
Avin 2010 power curves; R_rest = 0.37 /min, f_lim = 0.085) -- repeated below; the Rust test checks
that the shipped set still has these values. The literature scenarios (Gonzales & Scheuermann 2007,
Bystrom et al. 1991, Sahlin & Ren 1989, ...) are described in tests/data/fatigue/literature/.

Run from the repository root:  python3 tests/data/fatigue/make_reference.py
Writes tests/data/fatigue/reference_default_2026.json.
"""
import json
import math
import os

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

RTOL, ATOL = 1e-12, 1e-15
R_REST, F_LIM = 0.37, 0.085
K = {"general": 0.8430, "trunk": 0.6506, "neck": 0.8430, "shoulder": 1.3967, "elbow": 0.8601,
     "grip": 0.7335, "hip": 0.8430, "knee": 1.0302, "ankle": 0.5004}
K_LOW = {"general": 0.5884, "trunk": 0.4541, "neck": 0.5884, "shoulder": 0.9747, "elbow": 0.6003,
         "grip": 0.5119, "hip": 0.5884, "knee": 0.7190, "ankle": 0.3492}
K_ELBOW = {"female": 0.7376, "male": 1.0315}
R_REST_HIGH, F_LIM_HIGH = 0.4923, 0.15


def perfusion(rest, lim):
    def r(f):
        x = 1.0 - f / lim
        return rest * x * x * (3.0 - 2.0 * x) if x > 0.0 else 0.0
    return r


def const(r0):
    return lambda f: r0


R_DEF = perfusion(R_REST, F_LIM)


def hold(c0, u0, f, k, rec, t_min, stop_at_load=False):
    """Integrates a hold of f for t_min from (c0, u0). Returns (c, u, t_exhausted or None)."""
    if t_min <= 0.0:
        return c0, u0, None
    r = rec(f)

    def rhs(_t, y):
        c = y[0]
        return [-k * f * c + r * (1.0 - c), f / (c * c)]

    events = None
    if stop_at_load and f > 0.0:
        def ev(_t, y):
            return y[0] - f
        ev.terminal = True
        ev.direction = -1
        events = [ev]
        if c0 <= f:
            return c0, u0, 0.0
    sol = solve_ivp(rhs, (0.0, t_min), [c0, u0], method="DOP853", rtol=RTOL, atol=ATOL,
                    events=events)
    assert sol.success, sol.message
    te = None
    if events is not None and len(sol.t_events[0]) > 0:
        te = float(sol.t_events[0][0])
    return float(sol.y[0, -1]), float(sol.y[1, -1]), te


def endurance_min(f, k, rec, c0=1.0, t_max=1440.0):
    """Sustained hold: time (min) until c = f, or inf if not within t_max (24 h)."""
    _, _, te = hold(c0, 0.0, f, k, rec, t_max, stop_at_load=True)
    return math.inf if te is None else te


def intermittent_min(f, on_s, off_s, k, rec, t_max_s=86400.0):
    """f held for on_s, rest (f = 0) for off_s, repeated from c = 1: time (min) to exhaustion, or
    inf if not exhausted within t_max_s (24 h)."""
    c, t = 1.0, 0.0
    on, off = on_s / 60.0, off_s / 60.0
    while t * 60.0 < t_max_s:
        c1, _, te = hold(c, 0.0, f, k, rec, on, stop_at_load=True)
        if te is not None:
            return t + te
        c, t = c1, t + on
        c, _, _ = hold(c, 0.0, 0.0, k, rec, off)
        t += off
    return math.inf


def fstar(k, rec):
    """Largest load whose equilibrium capacity R/(k f + R) is >= f."""
    return brentq(lambda f: rec(f) / (k * f + rec(f)) - f if rec(f) > 0 else -f, 1e-12, 1.0,
                  xtol=1e-15, rtol=1e-15)


def main():
    out = {"_generated_by": "tests/data/fatigue/make_reference.py (scipy solve_ivp DOP853, rtol 1e-12)",
           "params": {"R_rest_per_min": R_REST, "f_lim": F_LIM, "k_per_min": K, "k_low_per_min": K_LOW,
                      "k_elbow_by_sex": K_ELBOW, "R_rest_high": R_REST_HIGH, "f_lim_high": F_LIM_HIGH}}
    loads = [0.10, 0.15, 0.20, 0.25, 0.30, 0.40, 0.50, 0.60, 0.70, 0.80]
    out["met_s"] = {g: {f"{f:.2f}": endurance_min(f, K[g], R_DEF) * 60.0 for f in loads} for g in K}
    out["met_s_elbow_by_sex_50pct"] = {s: endurance_min(0.5, k, R_DEF) * 60.0 for s, k in K_ELBOW.items()}
    out["fstar"] = {g: fstar(K[g], R_DEF) for g in K}
    fav = perfusion(R_REST_HIGH, F_LIM_HIGH)
    out["favourable_met_15pct_min"] = {g: endurance_min(0.15, K_LOW[g], fav) for g in K}
    out["favourable_fstar"] = {g: fstar(K_LOW[g], fav) for g in K}
    out["bjorksten_general_7_9pct_min"] = endurance_min(0.079, K["general"], R_DEF)
    out["mathiassen_shoulder_min"] = {f"{f:.2f}": endurance_min(f, K["shoulder"], R_DEF) for f in (0.10, 0.15, 0.21)}
    out["sjogaard_knee_5pct_60min_capacity"] = hold(1.0, 0.0, 0.05, K["knee"], R_DEF, 60.0)[0]
    out["shoulder_7pct_480min_capacity"] = hold(1.0, 0.0, 0.07, K["shoulder"], R_DEF, 480.0)[0]
    out["rest_after_half_capacity"] = {f"{t:g}": hold(0.5, 0.0, 0.0, 1.0, R_DEF, t)[0] for t in (0.25, 0.5, 1, 2, 5, 10)}
    # Sahlin & Ren 1989: knee, 66 %MVC to fatigue, rest, hold again
    kk = K["knee"]
    first = endurance_min(0.66, kk, R_DEF)
    sahlin = {}
    for rest in (1.2, 2.0, 4.0):
        c = hold(0.66, 0.0, 0.0, kk, R_DEF, rest)[0]
        sahlin[f"{rest:g}"] = {"second_over_first": endurance_min(0.66, kk, R_DEF, c0=c) / first, "capacity_after_rest": c}
    out["sahlin_knee_66pct"] = sahlin
    # Stull & Kearney 1978: grip 50 %MVC, first bout 120.25 s (k calibrated on it), 5 s rest
    k_sk = brentq(lambda k: endurance_min(0.5, k, R_DEF) * 60.0 - 120.25, 0.1, 5.0, xtol=1e-14)
    c = hold(0.5, 0.0, 0.0, k_sk, R_DEF, 5.0 / 60.0)[0]
    out["stull_kearney"] = {"k_per_min": k_sk, "second_over_first_5s": endurance_min(0.5, k_sk, R_DEF, c0=c) * 60.0 / 120.25}
    # Gonzales & Scheuermann 2007: grip 50 %MVC, 5 s on / 5 s off
    g = {}
    for m in (0.95, 1.0, 1.02, 1.05):
        g[f"{m:g}"] = intermittent_min(0.5, 5.0, 5.0, K["grip"], perfusion(R_REST * m, F_LIM)) * 60.0
    out["gonzales_grip_50pct_5on_5off_s"] = g
    # Bystrom et al. 1991: grip 25 %MVC; k calibrated within the study on the continuous 16.2 min
    k_b = brentq(lambda k: endurance_min(0.25, k, R_DEF) - 16.2, 0.05, 5.0, xtol=1e-14)
    out["bystrom"] = {"k_per_min": k_b, "intermittent_min": intermittent_min(0.25, 180.0, 10.0, k_b, R_DEF)}
    # ma2009 (k = 1, R = 0)
    out["ma2009_met_min"] = {f"{f:.2f}": endurance_min(f, 1.0, const(0.0)) for f in (0.05, 0.2, 0.4, 0.5, 0.6, 0.8)}
    # implementation cases
    c, u, _ = hold(1.0, 0.0, 0.4, K["shoulder"], R_DEF, 100.0 / 60.0)
    out["shoulder_40pct_100s"] = {"capacity": c, "u_min": u}
    c, u, _ = hold(0.9, 0.0, 0.05, 1.0, const(R_DEF(0.05)), 30.0)
    out["a3_a8_low_load"] = {"capacity": c, "u_min": u}
    c, u, _ = hold(1.0, 0.0, 0.3, 1.0, const(0.0), 2.0)
    out["a8_no_recovery"] = {"capacity": c, "u_min": u}
    out["legacy_const_R0_3_k1"] = {"fstar": fstar(1.0, const(0.3)),
                                   "met_40pct_min": endurance_min(0.4, 1.0, const(0.3))}
    def finite(v):  # JSON has no infinity: "never exhausted (within 24 h)" is written as null
        if isinstance(v, dict):
            return {k: finite(x) for k, x in v.items()}
        return None if isinstance(v, float) and math.isinf(v) else v
    out = finite(out)
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference_default_2026.json")
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1, allow_nan=False)
        fh.write("\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
