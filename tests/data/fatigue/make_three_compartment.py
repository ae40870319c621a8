#!/usr/bin/env python3
"""Reference values for tests/suite/three_compartment.rs: the three-compartment (3CC) fatigue model of
Xia & Frey-Law (2008) with the joint parameters of Frey-Law, Looft & Heitsman (2012, J Biomech
45:1803, Table 1), integrated with scipy (solve_ivp, DOP853, rtol 1e-12), independently of the
library's RK4.

Model (fractions of the motor-unit pool; rates 1/s): dMA/dt = C - F MA, dMR/dt = -C + R MF,
dMF/dt = F MA - R MF, from MR = 1, MA = MF = 0. Controller toward the target load TL with
LD = LR = 10/s: C = LD (TL - MA) while MA < TL and MR > TL - MA. Endurance time (ET): the first t
with MR + MA < TL -- which is exactly the end of that controller regime, so ET is the first root
of MR + MA - TL of a linear ODE.

Also computes, per joint, the "implied" power curve ET = b0 f^b1 for which the published (F, R)
is the least-squares optimum of the 10-90 %MVC errors (the two normal equations
sum e_i dET_i/dF = 0 and sum e_i dET_i/dR = 0, e_i = ET_i - b0 f_i^b1), and the statistic
S = sqrt(sum e_i^2)/n against those curves and against the Frey-Law & Avin (2010) curves.

Run from the repository root:  python3 tests/data/fatigue/make_three_compartment.py
Writes tests/data/fatigue/three_compartment_reference.json.
"""
import json
import math
import os

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

L = 10.0
# Frey-Law et al. (2012) Table 1 (1/s)
FR = {"ankle": (0.00589, 0.00058), "knee": (0.01500, 0.00149), "trunk": (0.00755, 0.00075),
      "shoulder": (0.01820, 0.00168), "elbow": (0.00912, 0.00094), "grip": (0.00980, 0.00064),
      "general": (0.00970, 0.00091)}
# Frey-Law & Avin (2010) Table 2 power curves, ET [s] = b0 f^b1
CURVE = {"general": (21.92, -1.98), "ankle": (34.71, -2.06), "trunk": (22.69, -2.27),
         "elbow": (17.98, -2.21), "grip": (33.55, -1.61), "knee": (19.38, -1.88),
         "shoulder": (14.86, -1.83)}
GRIDS = {"10-90": [i / 100 for i in range(10, 91, 10)], "15-95": [i / 100 for i in range(15, 96, 10)]}


def et(F, R, tl):
    def rhs(_t, y):
        ma, mr, mf = y
        c = L * (tl - ma)
        return [c - F * ma, -c + R * mf, F * ma - R * mf]

    def fail(_t, y):
        return y[0] + y[1] - tl
    fail.terminal = True
    fail.direction = -1
    sol = solve_ivp(rhs, (0.0, 1e6), [0.0, 1.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14,
                    events=[fail])
    assert sol.status == 1, (F, R, tl)
    return float(sol.t_events[0][0])


def implied_curve(F, R, grid):
    f = np.array(grid)
    m = np.array([et(F, R, x) for x in grid])
    h = 1e-6
    dF = np.array([(et(F * (1 + h), R, x) - et(F * (1 - h), R, x)) / (2 * h * F) for x in grid])
    dR = np.array([(et(F, R * (1 + h), x) - et(F, R * (1 - h), x)) / (2 * h * R) for x in grid])

    def b0_from(d, b1):
        g = f ** b1
        return float((m * d).sum() / (g * d).sum())

    b1 = brentq(lambda b: b0_from(dF, b) - b0_from(dR, b), -3.0, -1.2, xtol=1e-12)
    return b0_from(dF, b1), b1


def stat(model, curve):
    e = np.array(model) - np.array(curve)
    return float(math.sqrt((e * e).sum()) / len(e)), float(math.sqrt((e * e).mean())), \
        float((e / np.array(curve)).mean() * 100)


def main():
    out = {"_generated_by": "tests/data/fatigue/make_three_compartment.py (scipy solve_ivp DOP853, rtol 1e-12)",
           "L_per_s": L, "grids_fmvc": GRIDS, "joints": {}}
    for j, (F, R) in FR.items():
        b0, b1 = CURVE[j]
        ib0, ib1 = implied_curve(F, R, GRIDS["10-90"])
        d = {"F_per_s": F, "R_per_s": R, "b0_s": b0, "b1": b1, "implied_b0_s": ib0, "implied_b1": ib1}
        for g, grid in GRIDS.items():
            model = [et(F, R, x) for x in grid]
            curve = [b0 * x ** b1 for x in grid]
            implied = [ib0 * x ** ib1 for x in grid]
            s, rms, rel = stat(model, curve)
            si, rmsi, reli = stat(model, implied)
            d[g] = {"model_et_s": model, "rms_s_vs_2010": rms, "paper_statistic_s_vs_2010": s,
                    "paper_statistic_s_vs_implied": si, "mean_rel_pct_vs_implied": reli}
        out["joints"][j] = d
        print(j, f"implied {ib0:.4f} {ib1:.4f}", {g: round(d[g]["paper_statistic_s_vs_implied"], 3) for g in GRIDS},
              "rms vs 2010", round(d["10-90"]["rms_s_vs_2010"], 3))
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "three_compartment_reference.json")
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
        fh.write("\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
