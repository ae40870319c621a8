#!/usr/bin/env python3
"""Can a recovery with a fast and a slow component fit the short-rest data of Stull & Kearney
(1978) together with the intermittent-work, recovery and low-load data the shipped recovery was
fitted to?  The study behind docs/fatigue-parameters.md, "A fast and a slow component".

Models (normalised, per muscle group, time in MINUTES; c = capacity, f = relative load; k per
region as shipped in default-2026, which this study keeps; R(f) = R_rest x^2 (3 - 2x) with
x = 1 - f/f_lim below f_lim and 0 above, the shipped perfusion shape, for each pool's rate):

  single      dc/dt = -k f c + R(f)(1 - c)                         (the shipped model)
  mixture     two independent Ma units sharing k and the load, c = w c_fast + (1 - w) c_slow,
              each recovering at its own rate (fast, slow)
  routed      two deficits, c = 1 - D_fast - D_slow, the new fatigue routed by the load:
                dD_fast/dt = phi(f) k f c - R_fast(f) D_fast
                dD_slow/dt = (1 - phi(f)) k f c - R_slow(f) D_slow
              phi(f) = phi_max s((f - 0.25)/0.25), s the smoothstep x^2(3 - 2x) clamped to [0, 1]:
              no fast share up to 25 %MVC (Bystrom et al.'s load, where pauses help as the single
              model says), all of phi_max from 50 %MVC (where blood flow stops; Sadamoto et al.
              1983). ASSUMPTION: the ramp's ends; phi_max, R_fast, R_slow and f_lim are fitted.
              Below 25 %MVC from rest the routed model IS the single model.

Exhaustion: capacity falls to the load.  Every step is solved exactly (the routed model by the
matrix exponential of its linear system).  Loss: squared log errors, capped at ln 10, as
fit_recovery.py, over Gonzales & Scheuermann 2007, Bystrom et al. 1991, Sahlin & Ren 1989
(1.2 min), Stull & Kearney 1978 (5 s and 2560 s), Bjorksten & Jonsson 1977, Sjogaard et al. 1986
and Mathiassen & Ahsberg 1999 (mean of its three points); Sahlin & Ren's "still depressed after
4 min" adds 1 when broken.  Reads the data files as fit_recovery.py does.  numpy and scipy only.

Run:  python3 docs/tools/fit_two_pools.py      (about 5-10 minutes on one core)
"""
import math
import os
import sys

import numpy as np
from scipy.linalg import expm
from scipy.optimize import minimize

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fit_recovery import load_data  # noqa: E402

# default-2026's k per region [1/min] (docs/fatigue-parameters.md, section 3)
K = {"grip": 0.7335, "knee": 1.0302, "general": 0.8430, "shoulder": 1.3967}
R_MAX = 20.0  # the product's largest recovery rate [1/min]
LOG10 = math.log(10.0)


def perfusion(f, rest, f_lim):
    x = 1.0 - f / f_lim
    return rest * x * x * (3.0 - 2.0 * x) if x > 0.0 else 0.0


def smoothstep(x):
    x = min(1.0, max(0.0, x))
    return x * x * (3.0 - 2.0 * x)


class Routed:
    """The routed two-deficit model (the mixture and the single model are special cases of the
    same linear system: see `Mixture`)."""

    def __init__(self, phi_max, r_fast, r_slow, f_lim):
        self.phi_max, self.r_fast, self.r_slow, self.f_lim = phi_max, r_fast, r_slow, f_lim
        self.cache = {}

    def phi(self, f):
        return self.phi_max * smoothstep((f - 0.25) / 0.25)

    def matrix(self, k, f):
        a, b = self.phi(f) * k * f, (1.0 - self.phi(f)) * k * f
        rf, rs = perfusion(f, self.r_fast, self.f_lim), perfusion(f, self.r_slow, self.f_lim)
        return np.array([[-a - rf, -a, a], [-b, -b - rs, b], [0.0, 0.0, 0.0]])

    def fresh(self):
        return np.zeros(2)

    def capacity(self, s):
        return 1.0 - s[0] - s[1]

    def step(self, s, k, f, t):
        key = (k, f, t)
        e = self.cache.get(key)
        if e is None:
            e = expm(self.matrix(k, f) * t)
            if len(self.cache) < 4096:
                self.cache[key] = e
        return (e @ np.array([s[0], s[1], 1.0]))[:2]


class Mixture(Routed):
    """Two independent Ma units: a fraction w of the capacity recovers at r_fast, the rest at
    r_slow.  State: the two units' capacities."""

    def __init__(self, w, r_fast, r_slow, f_lim):
        super().__init__(0.0, r_fast, r_slow, f_lim)
        self.w = w

    def fresh(self):
        return np.ones(2)

    def capacity(self, s):
        return self.w * s[0] + (1.0 - self.w) * s[1]

    def step(self, s, k, f, t):
        out = []
        for c, rest in zip(s, (self.r_fast, self.r_slow)):
            r = perfusion(f, rest, self.f_lim)
            lam = k * f + r
            out.append(c if lam <= 0.0 else r / lam + (c - r / lam) * math.exp(-lam * t))
        return np.array(out)


def endurance(m, s, k, f, t_max=1440.0):
    """Minutes until the capacity falls to f while f is held from state s (inf: never)."""
    if m.capacity(s) <= f:
        return 0.0
    if m.capacity(m.step(s, k, f, t_max)) > f:
        return math.inf
    lo, hi = 0.0, t_max
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if m.capacity(m.step(s, k, f, mid)) > f:
            lo = mid
        else:
            hi = mid
    return lo


def intermittent(m, k, f, on_s, off_s, t_max_min=1440.0):
    """Seconds to exhaustion working on_s at f and resting off_s, repeated, from rest."""
    s, t = m.fresh(), 0.0
    while t < t_max_min * 60.0:
        s1 = m.step(s, k, f, on_s / 60.0)
        if m.capacity(s1) <= f:
            return t + 60.0 * endurance(m, s, k, f)
        s = m.step(s1, k, 0.0, off_s / 60.0)
        t += on_s + off_s
    return math.inf


def second_over_first(m, k, f, rest_min):
    first = endurance(m, m.fresh(), k, f)
    s = m.step(m.step(m.fresh(), k, f, first), k, 0.0, rest_min)
    return endurance(m, s, k, f) / first


def checks(m, d):
    """(name, model, measured) for every data point."""
    out = []
    g = d["gonzales"]["pooled"]
    out.append(("Gonzales & Scheuermann 2007, grip 50 %MVC 5 s/5 s [s]",
                intermittent(m, K["grip"], g["f"], g["on_s"], g["off_s"]), g["et_s"]))
    b = d["bystrom"]
    k_b = -math.log(b["continuous"]["f"]) / (b["continuous"]["f"] * b["continuous"]["tlim_min"])
    i = b["intermittent"]
    out.append(("Bystrom et al. 1991, grip 25 %MVC, 10-s pause every 3 min [min]",
                intermittent(m, k_b, i["f"], i["on_s"], i["off_s"]) / 60.0, i["tlim_min"]))
    for row in d["sahlin"]:
        if row["quantity"] == "endurance_ratio" and row["use"] == "fit":
            out.append(("Sahlin & Ren 1989, knee 66 %%MVC, 2nd/1st after %.1f min" % row["rest_min"],
                        second_over_first(m, K["knee"], row["f"], row["rest_min"]), row["value"]))
    for row in d["stull"]:
        k_sk = math.log(1.0 / row["f"]) / (row["f"] * row["first_bout_s"] / 60.0)
        out.append(("Stull & Kearney 1978, grip 50 %%MVC, 2nd/1st after %g s" % row["rest_s"],
                    second_over_first(m, k_sk, row["f"], row["rest_s"] / 60.0), row["second_over_first"]))
    bj = d["bjorksten"]["sustained"]
    out.append(("Bjorksten & Jonsson 1977, %.1f %%MVC held [min]" % (100 * bj["mean_force_frac"]),
                endurance(m, m.fresh(), K["general"], bj["mean_force_frac"]), bj["duration_min"]))
    sj = d["sjogaard"]
    s = m.step(m.fresh(), K["knee"], sj["f"], sj["duration_min"])
    out.append(("Sjogaard et al. 1986, knee 5 %MVC 60 min, MVC loss",
                1.0 - m.capacity(s), 1.0 - sj["capacity_after"]))
    for row in d["mathiassen"]:
        out.append(("Mathiassen & Ahsberg 1999, shoulder %.0f %%MVC [min]" % (100 * row["f"]),
                    endurance(m, m.fresh(), K["shoulder"], row["f"]), row["met_min"]))
    return out


def depressed_after_4_min(m):
    return second_over_first(m, K["knee"], 0.66, 4.0) < 1.0


def log_err2(model, data):
    if not math.isfinite(model) or model <= 0.0:
        return LOG10 ** 2
    return min(abs(math.log(model / data)), LOG10) ** 2


def loss(m, d):
    total = 0.0
    for name, model, data in checks(m, d):
        if name.startswith("Mathiassen"):
            total += log_err2(model, data) / 3.0
        else:
            total += log_err2(model, data)
    return total + (0.0 if depressed_after_4_min(m) else 1.0)


def logistic(v):
    return 1.0 / (1.0 + math.exp(-v))


def logit(p):
    return math.log(p / (1.0 - p))


def fit(make, x0s, d):
    best = None
    for x0 in x0s:
        r = minimize(lambda x: loss(make(x), d), np.array(x0, float), method="Nelder-Mead",
                     options=dict(maxiter=500, xatol=1e-3, fatol=1e-5))
        if best is None or r.fun < best.fun:
            best = r
    return make(best.x), best.fun


def report(title, m, d, params):
    print("\n%s: %s" % (title, params))
    print("  loss %.4f (Sahlin & Ren still depressed after 4 min: %s)" % (loss(m, d), depressed_after_4_min(m)))
    for name, model, data in checks(m, d):
        err = "" if not math.isfinite(model) else "%+.0f %%" % (100.0 * (model / data - 1.0))
        print("  %-62s measured %8.3f  model %8.3f  %s" % (name, data, model, err))


def main():
    d = load_data()
    single = Routed(0.0, R_MAX, 0.37, 0.085)  # phi = 0: the fast pool is never used
    report("single (shipped: R_rest 0.37 /min, f_lim 0.085)", single, d, "")

    def params(x):
        """(share, R_fast, R_slow, f_lim) from unbounded x."""
        return (logistic(x[0]), min(R_MAX, math.exp(x[1])), min(R_MAX, math.exp(x[2])),
                0.03 + 0.2 * logistic(x[3]))

    mix, _ = fit(lambda x: Mixture(*params(x)), [[logit(0.2), math.log(4.7), math.log(0.23), logit(0.26)],
                            [logit(0.4), math.log(5.0), math.log(0.05), logit(0.275)]], d)
    report("mixture of two Ma units", mix, d,
           "w %.3f, R_fast %.3f, R_slow %.3f /min, f_lim %.4f" % (mix.w, mix.r_fast, mix.r_slow, mix.f_lim))

    routed, _ = fit(lambda x: Routed(*params(x)), [[logit(0.15), math.log(19.0), math.log(0.32), logit(0.275)],
                                  [logit(0.3), math.log(6.0), math.log(0.25), logit(0.275)]], d)
    report("routed two deficits", routed, d,
           "phi_max %.3f, R_fast %.3f, R_slow %.3f /min, f_lim %.4f"
           % (routed.phi_max, routed.r_fast, routed.r_slow, routed.f_lim))


if __name__ == "__main__":
    main()
