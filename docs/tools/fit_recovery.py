#!/usr/bin/env python3
"""Fit of the recovery term and of k per body region of the Ma, Chablat, Bennis & Zhang (2009)
dynamic fatigue model: the evidence behind data/fatigue_sets.yaml (docs/fatigue-parameters.md).

Model (normalised, per muscle group, time in MINUTES):
    dc/dt = -k f c + R(f) (1 - c)        c = F_cem/MVC (1 = rested), f = F_load/MVC
    dU/dt = f / c^2
For a step held at constant f, R is constant and the exact solution is
    c(t) = c_inf + (c0 - c_inf) exp(-(k f + R) t),   c_inf = R / (k f + R).
Exhaustion = first time c falls to f.  Intermittent tasks are simulated step by step with this closed form.

Reads every published data point from the CSV files (looked up
in tests/data/fatigue_fit/, then tests/data/fatigue/literature/), fits
    * k per region (Frey-Law & Avin 2010 power curves, 20-80 %MVC),
    * the recovery parameters of several candidate forms of R(f),
prints goodness of fit per dataset and writes fitted.json and parameter_sets.yaml to --out.
The recommended form is the one the product calls `perfusion` (here `smoothstep`), with
R_rest = rest_per_min and f_occ = limit_fmvc in data/fatigue_sets.yaml.
Only numpy and scipy are used.
Run from anywhere:  python3 docs/tools/fit_recovery.py [--out DIR]   (default DIR: target/fatigue_fit)
About 1-3 minutes.
"""
import csv
import json
import math
import os

import numpy as np
from scipy.optimize import brentq, minimize, minimize_scalar

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA_DIRS = [os.path.join(ROOT, "tests", "data", "fatigue_fit"),
             os.path.join(ROOT, "tests", "data", "fatigue", "literature")]
OUT = os.path.join(ROOT, "target", "fatigue_fit")
LOG10 = math.log(10.0)          # cap of |log(model/data)| (model off by more than x10, or infinite)
K_CV = 0.29 / 0.96              # between-subject CV of k (elbow, Ergonomics 2018, doi:10.1080/00140139.2017.1416180)
REGIONS = ["trunk", "neck", "shoulder", "elbow", "grip", "hip", "knee", "ankle"]
CURVE_OF = {"trunk": "trunk", "neck": "general", "shoulder": "shoulder", "elbow": "elbow",
            "grip": "grip", "hip": "general", "knee": "knee", "ankle": "ankle"}


# ----------------------------------------------------------------------------------------------
# data
# ----------------------------------------------------------------------------------------------
def read_csv(name):
    """Rows of the data file <name> as dicts; '#' lines are the provenance header; numbers are converted."""
    path = next((os.path.join(d, name) for d in DATA_DIRS if os.path.exists(os.path.join(d, name))), None)
    if path is None:
        raise SystemExit("data file %s not found in %s" % (name, " or ".join(DATA_DIRS)))
    with open(path, newline="") as fh:
        lines = [ln for ln in fh if not ln.lstrip().startswith("#") and ln.strip()]
    rows = []
    for row in csv.DictReader(lines):
        out = {}
        for key, val in row.items():
            try:
                out[key] = float(val)
            except (TypeError, ValueError):
                out[key] = val
        rows.append(out)
    return rows


def load_data():
    d = {}
    d["curves"] = {r["region"]: r for r in read_csv("frey_law_avin_2010_power_curves.csv")}
    d["ma2009"] = read_csv("ma_2009_table2_met_models.csv")
    d["mathiassen"] = read_csv("mathiassen_ahsberg_1999_shoulder.csv")
    d["bjorksten"] = {r["condition"]: r for r in read_csv("bjorksten_jonsson_1977_limits.csv")}
    d["sjogaard"] = read_csv("sjogaard_1986_low_level.csv")[0]
    d["gonzales"] = {r["group"]: r for r in read_csv("gonzales_scheuermann_2007_intermittent_grip.csv")}
    d["bystrom"] = {r["condition"]: r for r in read_csv("bystrom_1991_micropauses.csv")}
    d["sahlin"] = read_csv("sahlin_ren_1989_recovery.csv")
    d["stull"] = read_csv("stull_kearney_1978_endurance_recovery.csv")
    d["avin"] = read_csv("avin_2010_sex_differences.csv")
    d["kspread"] = read_csv("fatigability_k_spread.csv")[0]
    d["threecc"] = {r["region"]: r for r in read_csv("frey_law_2012_3cc_and_looft_rest_multiplier.csv")}
    return d


def power_points(curve, lo=None, hi=None, step=0.05):
    lo = curve["fit_lo"] if lo is None else lo
    hi = curve["fit_hi"] if hi is None else hi
    f = np.round(np.arange(lo, hi + 1e-9, step), 4)
    return f, curve["b0"] * f ** curve["b1"] / 60.0          # minutes


# ----------------------------------------------------------------------------------------------
# recovery forms R(f) [1/min]; all >= 0, C1 in f, constant while f is constant
# ----------------------------------------------------------------------------------------------
class Recovery:
    def __init__(self, form, **p):
        self.form, self.p = form, p

    def __call__(self, f):
        p = self.p
        if self.form == "none":
            return 0.0
        if self.form == "constant":
            return p["R"]
        if self.form in ("quadratic", "smoothstep"):
            if f >= p["f_occ"]:
                return 0.0
            x = 1.0 - f / p["f_occ"]
            s = x * x if self.form == "quadratic" else x * x * (3.0 - 2.0 * x)
            return p["R_rest"] * s
        if self.form == "rest_multiplier":
            return p["R_work"] * (1.0 + (p["r"] - 1.0) * math.exp(-f / p["f_s"]))
        raise ValueError(self.form)

    def describe(self):
        return {"form": self.form, **{k: float(v) for k, v in self.p.items()}}


# ----------------------------------------------------------------------------------------------
# exact closed forms
# ----------------------------------------------------------------------------------------------
def hold(c0, f, k, R, t):
    """Capacity after holding load f for t minutes from c0 (exact)."""
    a = k * f + R
    if a == 0.0:
        return c0
    cinf = R / a
    return cinf + (c0 - cinf) * math.exp(-a * t)


def time_to(c0, f, k, R, target, tmax=math.inf):
    """First time (min) at which c reaches `target` while f is held, or None if not within tmax."""
    if c0 <= target:
        return 0.0
    a = k * f + R
    if a == 0.0:
        return None
    cinf = R / a
    if cinf >= target:
        return None
    t = math.log((c0 - cinf) / (target - cinf)) / a
    return t if t <= tmax else None


def met(f, k, rec, c0=1.0):
    """Endurance time (min) of a sustained hold at f; inf if the hold never exhausts."""
    t = time_to(c0, f, k, rec(f), f)
    return math.inf if t is None else t


def intermittent_et(f, on, off, k, rec, tmax):
    """Time to exhaustion (min) of a square-wave task: f for `on` min, rest for `off` min, repeated.
    Simulated step by step with the exact closed form.  Returns inf if not exhausted before tmax
    (or if the periodic steady state is provably above the failure threshold)."""
    Rw, Rr = rec(f), rec(0.0)
    # failure threshold at the start of a work step: capacity that ends the work step exactly at f
    a = k * f + Rw
    cinf = Rw / a
    if cinf >= f:
        return math.inf
    c_crit = cinf + (f - cinf) * math.exp(a * on)
    # one cycle is an affine map c -> alpha c + beta; its fixed point decides if failure ever happens
    ew, er = math.exp(-a * on), math.exp(-(Rr) * off)
    alpha = ew * er
    beta = (cinf * (1 - ew)) * er + (1 - er)
    c_fp = beta / (1 - alpha) if alpha < 1 else 1.0
    if c_fp > c_crit + 1e-12:
        return math.inf
    c, t = 1.0, 0.0
    while t < tmax:
        tf = time_to(c, f, k, Rw, f, on)
        if tf is not None:
            return t + tf
        c = hold(c, f, k, Rw, on)
        t += on
        c = hold(c, 0.0, k, Rr, off)
        t += off
    return math.inf


def second_bout_ratio(f, rest, k, rec):
    """Hold f to exhaustion from c=1, rest `rest` min, hold f again: second / first endurance time."""
    first = met(f, k, rec)
    c = hold(f, 0.0, k, rec(0.0), rest)
    second = time_to(c, f, k, rec(f), f)
    second = math.inf if second is None else second
    return second / first


def fstar(k, rec):
    """Sustainable load: largest f whose hold never exhausts, root of R(f)(1-f) = k f^2."""
    if rec(0.0) <= 0.0:
        return 0.0
    return brentq(lambda f: rec(f) * (1 - f) - k * f * f, 1e-9, 1.0 - 1e-12, xtol=1e-12)


def k_for_met(f, et, rec):
    """k such that the model's sustained endurance at f equals et (min) (within-study calibration)."""
    g = lambda lk: math.log(min(met(f, math.exp(lk), rec), 1e9)) - math.log(et)
    return math.exp(brentq(g, math.log(1e-4), math.log(1e3)))


def logerr(model, data):
    if not np.isfinite(model) or model <= 0:
        return LOG10
    return float(np.clip(math.log(model / data), -LOG10, LOG10))


# ----------------------------------------------------------------------------------------------
# fitting
# ----------------------------------------------------------------------------------------------
def fit_k(curve, rec):
    f, et = power_points(curve)

    def loss(lk):
        k = math.exp(lk)
        return float(np.mean([logerr(met(fi, k, rec), ei) ** 2 for fi, ei in zip(f, et)]))

    res = minimize_scalar(loss, bounds=(math.log(0.02), math.log(20.0)), method="bounded",
                          options={"xatol": 1e-10})
    return math.exp(res.x), res.fun


def evaluate(rec, D, kfix=None):
    """All fitted targets for a recovery form. Returns dict with per-target errors and block losses."""
    ks, sus = {}, {}
    for name, curve in D["curves"].items():
        if kfix is None:
            ks[name], sus[name] = fit_k(curve, rec)
        else:
            ks[name] = kfix
            f, et = power_points(curve)
            sus[name] = float(np.mean([logerr(met(fi, kfix, rec), ei) ** 2 for fi, ei in zip(f, et)]))
    t = {}
    # --- recovery / intermittent block
    g = D["gonzales"]["pooled"]
    et = intermittent_et(g["f"], g["on_s"] / 60, g["off_s"] / 60, ks["grip"], rec, tmax=20 * g["et_s"] / 60)
    t["gonzales_2007_grip_50pct_5s5s"] = ("recovery", et * 60, g["et_s"], "s")
    bc, bi = D["bystrom"]["continuous"], D["bystrom"]["intermittent"]
    try:
        kb = k_for_met(bc["f"], bc["tlim_min"], rec)
        et = intermittent_et(bi["f"], bi["on_s"] / 60, bi["off_s"] / 60, kb, rec, tmax=20 * bi["tlim_min"])
    except ValueError:
        et = math.inf
    t["bystrom_1991_grip_25pct_3min_10s"] = ("recovery", et, bi["tlim_min"], "min")
    s = [r for r in D["sahlin"] if r["use"] == "fit"][0]
    t["sahlin_ren_1989_knee_66pct_endurance_halftime"] = (
        "recovery", second_bout_ratio(s["f"], s["rest_min"], ks["knee"], rec), s["value"], "ratio")
    # --- low-load block
    b = D["bjorksten"]["sustained"]
    t["bjorksten_1977_sustained_limit_60min"] = ("lowload", met(b["mean_force_frac"], ks["general"], rec),
                                                 b["duration_min"], "min")
    sj = D["sjogaard"]
    c60 = hold(1.0, sj["f"], ks["knee"], rec(sj["f"]), sj["duration_min"])
    t["sjogaard_1986_knee_5pct_60min_mvc_loss"] = ("lowload", 1.0 - c60, 1.0 - sj["capacity_after"], "fraction")
    for r in D["mathiassen"]:
        t["mathiassen_1999_shoulder_%dpct" % round(100 * r["f"])] = (
            "lowload_m", met(r["f"], ks["shoulder"], rec), r["met_min"], "min")
    errs = {key: logerr(v[1], v[2]) for key, v in t.items()}
    rec_block = np.mean([errs[k] ** 2 for k, v in t.items() if v[0] == "recovery"])
    m = np.mean([errs[k] ** 2 for k, v in t.items() if v[0] == "lowload_m"])
    low_block = np.mean([errs[k] ** 2 for k, v in t.items() if v[0] == "lowload"] + [m])
    sus_block = float(np.mean(list(sus.values())))
    return {"k": ks, "sus_msle": sus, "targets": t, "logerr": errs,
            "loss": float(sus_block + rec_block + low_block),
            "blocks": {"sustained": sus_block, "recovery": float(rec_block), "lowload": float(low_block)}}


FORMS = {
    # name: (form, parameter names, log-space start grid, fixed params)
    "constant": ("constant", ["R"], [np.geomspace(0.003, 3, 25)], {}),
    "quadratic": ("quadratic", ["R_rest", "f_occ"], [np.geomspace(0.05, 5, 15), np.linspace(0.05, 0.6, 12)], {}),
    "smoothstep": ("smoothstep", ["R_rest", "f_occ"], [np.geomspace(0.05, 5, 15), np.linspace(0.05, 0.6, 12)], {}),
    "rest_multiplier_fs0.01": ("rest_multiplier", ["R_work", "r"], [np.geomspace(1e-4, 0.3, 12), np.geomspace(2, 500, 12)], {"f_s": 0.01}),
    "rest_multiplier_fs0.02": ("rest_multiplier", ["R_work", "r"], [np.geomspace(1e-4, 0.3, 12), np.geomspace(2, 500, 12)], {"f_s": 0.02}),
    "rest_multiplier_fs0.03": ("rest_multiplier", ["R_work", "r"], [np.geomspace(1e-4, 0.3, 12), np.geomspace(2, 500, 12)], {"f_s": 0.03}),
}


def make(form, names, x, fixed):
    return Recovery(form, **dict(zip(names, x)), **fixed)


def fit_form(key, D):
    form, names, grids, fixed = FORMS[key]
    best = None
    for x in (np.array(np.meshgrid(*grids, indexing="ij")).reshape(len(grids), -1).T):
        L = evaluate(make(form, names, x, fixed), D)["loss"]
        if best is None or L < best[0]:
            best = (L, x)
    x0 = np.log(best[1])
    obj = lambda lx: evaluate(make(form, names, np.exp(lx), fixed), D)["loss"]
    res = minimize(obj, x0, method="Nelder-Mead", options={"xatol": 1e-6, "fatol": 1e-9, "maxiter": 600})
    x = np.exp(res.x)
    rec = make(form, names, x, fixed)
    return rec, evaluate(rec, D)


def single_param_range(rec, D, pname, groups, bounds, n=400):
    """Re-fit one parameter to one dataset at a time (other parameters fixed), by dense log grid:
    returns the best value and the interval of values whose error is within 0.02 (log units) of the best
    (objectives are flat where R(f) = 0 over the whole dataset)."""
    out = {}
    grid = np.geomspace(bounds[0], bounds[1], n)
    for gname, tks in groups.items():
        errs = []
        for v in grid:
            p = dict(rec.p)
            p[pname] = v
            le = evaluate(Recovery(rec.form, **p), D, kfix=None)["logerr"]
            errs.append(math.sqrt(np.mean([le[t] ** 2 for t in tks])))
        errs = np.array(errs)
        i = int(np.argmin(errs))
        ok = grid[errs <= errs[i] + 0.02]
        out[gname] = {"value": float(grid[i]), "residual_logerr": float(errs[i]),
                      "near_optimal_interval": [float(ok.min()), float(ok.max())]}
    return out


# ----------------------------------------------------------------------------------------------
# reporting helpers
# ----------------------------------------------------------------------------------------------
def sustained_stats(curve, k, rec, lo=None, hi=None):
    f, et = power_points(curve, lo, hi)
    m = np.array([met(fi, k, rec) for fi in f])
    fin = np.isfinite(m)
    res_s = (m[fin] - et[fin]) * 60
    res_p = (m[fin] / et[fin] - 1) * 100
    r = float(np.corrcoef(m[fin], et[fin])[0, 1]) if fin.sum() > 2 else float("nan")
    return {"rms_s": float(np.sqrt(np.mean(res_s ** 2))), "rms_pct": float(np.sqrt(np.mean(res_p ** 2))),
            "max_abs_pct": float(np.max(np.abs(res_p))), "r": r, "n_infinite": int((~fin).sum())}


def ma2009_met(row, f):
    a, b, c = row["a"], row["b"], row["c"]
    if row["form"] == "power":
        return a * f ** b
    if row["form"] == "exp":
        return a * math.exp(b * f)
    if row["form"] == "shifted":
        return a * (f - c) ** b if f > c else math.inf
    if row["form"] == "huijgens":
        return a * ((1 - f) / (f - c)) ** b if f > c else math.inf
    if row["form"] == "rohmert":
        return -1.5 + 2.1 / f - 0.6 / f ** 2 + 0.1 / f ** 3
    raise ValueError(row["form"])


def fmt(x, nd=3):
    return "inf" if not np.isfinite(x) else ("%.*f" % (nd, x))


# ----------------------------------------------------------------------------------------------
def main():
    D = load_data()
    results = {}
    print("=" * 100)
    print("1. Baselines")
    print("=" * 100)
    base = {
        "ma2009 (k=1, R=0)": (Recovery("none"), 1.0),
        "legacy tool (k=1, constant R=0.3/min)": (Recovery("constant", R=0.3), 1.0),
        "Eq.8 alone (k fitted per region, R=0)": (Recovery("none"), None),
    }
    for name, (rec, kfix) in base.items():
        ev = evaluate(rec, D, kfix)
        results[name] = (rec, ev)
        fs = {r: fstar(ev["k"][r], rec) for r in ev["k"]}
        print("%-42s loss %.3f  blocks %s" % (name, ev["loss"], {k: round(v, 3) for k, v in ev["blocks"].items()}))
        print("    f* per curve: %s" % {r: round(v, 3) for r, v in fs.items()})

    print("\n" + "=" * 100)
    print("2. Candidate recovery forms (k per region re-fitted jointly)")
    print("=" * 100)
    fits = {}
    for key in FORMS:
        rec, ev = fit_form(key, D)
        fits[key] = (rec, ev)
        print("%-24s loss %.4f blocks %s params %s" % (
            key, ev["loss"], {k: round(v, 4) for k, v in ev["blocks"].items()},
            {k: round(v, 5) for k, v in rec.p.items()}))
    # recommended = smoothstep (see docs/fatigue-parameters.md); report the ranking anyway
    ranking = sorted(fits, key=lambda k: fits[k][1]["loss"])
    print("ranking by total loss:", ranking)
    REC_KEY = "smoothstep"
    rec_opt, ev_opt = fits[REC_KEY]
    # Recommended values = optimum rounded to 2 significant figures: the data support no more precision
    # (dataset-wise estimates spread by +/-20-80 %), and the exact optimum sits on a discontinuity of the
    # intermittent prediction (Gonzales: +2 % R_rest -> never exhausted), which rounding moves away from.
    sig2 = lambda v: float("%.2g" % v)
    rec = Recovery(REC_KEY, R_rest=sig2(rec_opt.p["R_rest"]), f_occ=sig2(rec_opt.p["f_occ"]))
    ev = evaluate(rec, D)
    print("optimum %s: R_rest %.5f f_occ %.5f loss %.4f -> recommended (2 s.f.) R_rest %.3g f_occ %.3g loss %.4f" % (
        REC_KEY, rec_opt.p["R_rest"], rec_opt.p["f_occ"], ev_opt["loss"], rec.p["R_rest"], rec.p["f_occ"], ev["loss"]))

    print("\n" + "=" * 100)
    print("3. Per-target errors (model vs published) for every form")
    print("=" * 100)
    allforms = {**{n: v for n, v in results.items()}, **fits}
    tkeys = list(ev["targets"].keys())
    print("%-48s %10s " % ("target", "data") + " ".join("%12s" % n[:12] for n in allforms))
    for tk in tkeys:
        unit = ev["targets"][tk][3]
        row = "%-48s %10s " % (tk, fmt(ev["targets"][tk][2], 3))
        row += " ".join("%12s" % fmt(allforms[n][1]["targets"][tk][1], 3) for n in allforms)
        print(row + "  [%s]" % unit)

    print("\n" + "=" * 100)
    print("4. Recommended form: %s   R(f) = R_rest * s(1 - f/f_occ), s(x) = x^2 (3 - 2x), R = 0 for f >= f_occ" % REC_KEY)
    print("=" * 100)
    print("R_rest = %.4f /min (half-time %.2f min), f_occ = %.4f" % (rec.p["R_rest"], math.log(2) / rec.p["R_rest"], rec.p["f_occ"]))
    # ranges: dataset-wise re-fits
    rr = single_param_range(rec, D, "R_rest", {k: [k] for k, v in ev["targets"].items() if v[0] == "recovery"}, (0.05, 5), 150)
    fr = single_param_range(rec, D, "f_occ", {
        "bjorksten_1977_sustained_limit_60min": ["bjorksten_1977_sustained_limit_60min"],
        "sjogaard_1986_knee_5pct_60min_mvc_loss": ["sjogaard_1986_knee_5pct_60min_mvc_loss"],
        "mathiassen_1999_shoulder_10_21pct": [k for k, v in ev["targets"].items() if v[0] == "lowload_m"]}, (0.03, 0.6), 150)
    print("R_rest re-fitted to one dataset at a time:")
    for kk, vv in rr.items():
        print("   %-50s %.4f  (residual log err %.3f; near-optimal %.3f-%.3f)" % (kk, vv["value"], vv["residual_logerr"], *vv["near_optimal_interval"]))
    print("f_occ re-fitted to one dataset at a time:")
    for kk, vv in fr.items():
        print("   %-50s %.4f  (residual log err %.3f; near-optimal %.3f-%.3f)" % (kk, vv["value"], vv["residual_logerr"], *vv["near_optimal_interval"]))
    # validation-only: Stull & Kearney fast component estimate of R_rest
    st5 = [r for r in D["stull"] if r["rest_s"] == 5][0]
    def sk_obj(lv):
        p = dict(rec.p); p["R_rest"] = math.exp(lv)
        r2 = Recovery(rec.form, **p)
        ksk = k_for_met(st5["f"], st5["first_bout_s"] / 60, r2)
        return (math.log(second_bout_ratio(st5["f"], st5["rest_s"] / 60, ksk, r2) / st5["second_over_first"])) ** 2
    R_fast = math.exp(minimize_scalar(sk_obj, bounds=(math.log(0.05), math.log(50)), method="bounded").x)
    R_vals = [v["value"] for v in rr.values()]
    R_lo, R_hi = min(R_vals), max(R_vals)
    # f_occ range: lower end = Bjorksten & Jonsson's 60-min sustained limit itself (R = 0 from 7.9 %MVC up);
    # upper end = the largest classic sustainable level, the 15 %MVC asymptote of Rohmert / Huijgens
    # (Ma et al. 2009 Table 2).  The Sjogaard-only estimate (printed above) conflicts with Mathiassen &
    # Ahsberg and Bjorksten & Jonsson and is reported, not used as a bound.
    fo_lo = D["bjorksten"]["sustained"]["mean_force_frac"]
    fo_hi = max(r["asymptote"] for r in D["ma2009"] if isinstance(r["asymptote"], float))
    print("R_rest implied by Stull & Kearney 5-s point (fast component, validation only): %.3f /min" % R_fast)

    print("\nGoodness of fit of the recommended form, fitted recovery/low-load datasets:")
    gof = {}
    to_s = {"s": 1.0, "min": 60.0}
    et_pairs = []
    for tk, (blk, mval, dval, unit) in ev["targets"].items():
        err_pct = (mval / dval - 1) * 100 if np.isfinite(mval) else float("inf")
        if unit in to_s:
            err_abs = (mval - dval) * to_s[unit] if np.isfinite(mval) else float("inf")
            et_pairs.append((mval * to_s[unit], dval * to_s[unit]))
            print("   %-50s data %9.1f s  model %9.1f s  error %+8.1f s (%+6.1f %%)" % (tk, dval * to_s[unit], mval * to_s[unit], err_abs, err_pct))
        else:
            err_abs = mval - dval
            print("   %-50s data %9.3f    model %9.3f    error %+8.3f   (%+6.1f %%)  [%s]" % (tk, dval, mval, err_abs, err_pct, unit))
        gof[tk] = {"data": dval, "model": mval, "unit": unit, "error_abs": err_abs, "error_pct": err_pct}
    m_ = np.array([p[0] for p in et_pairs]); d_ = np.array([p[1] for p in et_pairs])
    pooled = {"n": len(m_), "rms_s": float(np.sqrt(np.mean((m_ - d_) ** 2))),
              "rms_pct": float(np.sqrt(np.mean((m_ / d_ - 1) ** 2)) * 100),
              "r_log": float(np.corrcoef(np.log(m_), np.log(d_))[0, 1])}
    print("   endurance-type targets pooled: n=%d RMS %.1f s, RMS %.1f %%, r(log) = %.4f" % (pooled["n"], pooled["rms_s"], pooled["rms_pct"], pooled["r_log"]))
    # sensitivity of the intermittent endurance to R_rest (threshold behaviour)
    sens = {}
    for fac in (0.9, 0.95, 1.0, 1.02, 1.05):
        p = dict(rec.p); p["R_rest"] *= fac
        r2 = Recovery(rec.form, **p)
        g_ = D["gonzales"]["pooled"]
        sens[str(fac)] = intermittent_et(g_["f"], g_["on_s"] / 60, g_["off_s"] / 60, ev["k"]["grip"], r2, 1e3) * 60
    print("   Gonzales ET [s] vs R_rest x (0.9, 0.95, 1, 1.02, 1.05): %s" % ", ".join(fmt(v, 0) for v in sens.values()))
    print("\nRegion table (curve, k, k range (+/-1 SD, CV %.2f), f*, sustained fit 20-80 %%MVC)" % K_CV)
    region_out = {}
    for reg in REGIONS:
        cname = CURVE_OF[reg]
        k = ev["k"][cname]
        st = sustained_stats(D["curves"][cname], k, rec)
        st_ext = sustained_stats(D["curves"][cname], k, rec, 0.10, 0.90)
        fs = fstar(k, rec)
        fs_lo = fstar(k * (1 + K_CV), Recovery(rec.form, R_rest=R_lo, f_occ=fo_lo))
        fs_hi = fstar(k * (1 - K_CV), Recovery(rec.form, R_rest=R_hi, f_occ=fo_hi))
        f4, et4 = np.array([0.2, 0.4, 0.6, 0.8]), D["curves"][cname]["b0"] * np.array([0.2, 0.4, 0.6, 0.8]) ** D["curves"][cname]["b1"]
        m4 = [met(x, k, rec) * 60 for x in f4]
        region_out[reg] = {"curve": cname, "k": k, "k_low": k * (1 - K_CV), "k_high": k * (1 + K_CV),
                           "f_star": fs, "f_star_low": fs_lo, "f_star_high": fs_hi,
                           "fit_20_80": st, "extrapolation_10_90": st_ext,
                           "met_s_at_20_40_60_80": m4, "data_s_at_20_40_60_80": list(map(float, et4))}
        print("  %-8s %-8s k=%.4f [%.3f, %.3f]  f*=%.4f [%.3f-%.3f]  RMS %.1f s (%.1f %%), max %.0f %%, r=%.4f | 10-90: RMS %.0f %%"
              % (reg, cname, k, k * (1 - K_CV), k * (1 + K_CV), fs, fs_lo, fs_hi, st["rms_s"], st["rms_pct"],
                 st["max_abs_pct"], st["r"], st_ext["rms_pct"]))
        print("           MET model/data at 20/40/60/80 %%: %s" % "  ".join(
            "%.0f/%.0f" % (a, b) for a, b in zip(m4, et4)))

    # ---------------------------------------------------------------- validation (not fitted)
    print("\n" + "=" * 100)
    print("5. Validation against data NOT used in the fit")
    print("=" * 100)
    val = {}
    for r in D["stull"]:
        ksk = k_for_met(r["f"], r["first_bout_s"] / 60, rec)
        ratio = second_bout_ratio(r["f"], r["rest_s"] / 60, ksk, rec)
        val["stull_kearney_1978_rest_%ds" % r["rest_s"]] = {"model": ratio, "data": r["second_over_first"]}
        print("Stull & Kearney 1978 grip 50%%: rest %5d s  second/first model %.3f  data %.3f" % (r["rest_s"], ratio, r["second_over_first"]))
    kk = ev["k"]["knee"]
    c15 = hold(0.66, 0.0, kk, rec(0.0), 0.25)
    c2 = hold(0.66, 0.0, kk, rec(0.0), 2.0)
    e2 = second_bout_ratio(0.66, 2.0, kk, rec)
    e4 = second_bout_ratio(0.66, 4.0, kk, rec)
    val["sahlin_capacity_after_15s"] = {"model": c15, "data": "MVC half-time < 15 s -> > 0.83"}
    val["sahlin_capacity_after_2min"] = {"model": c2, "data": "MVC back to pre (n.s.) within 2 min"}
    val["sahlin_endurance_ratio_2min"] = {"model": e2, "data": "< 1 (still depressed)"}
    val["sahlin_endurance_ratio_4min"] = {"model": e4, "data": "< 1 (still depressed)"}
    print("Sahlin & Ren 1989 knee 66%%: capacity after 15 s rest %.3f (data: MVC t1/2 < 15 s -> > 0.83); after 2 min %.3f (data: ~1.0)" % (c15, c2))
    print("   endurance ratio after 2 min %.3f, after 4 min %.3f (data: both still < 1)" % (e2, e4))
    # Avin sex differences (elbow) with the ratio-derived sex k
    av = {(r["region"], r["sex"]): r for r in D["avin"]}
    ke = ev["k"]["elbow"]
    pooled_elbow = 0.5 * (av[("elbow", "female")]["et_s"] + av[("elbow", "male")]["et_s"])
    k_sex = {s: ke * pooled_elbow / av[("elbow", s)]["et_s"] for s in ("female", "male")}
    for s in ("female", "male"):
        m = met(0.5, k_sex[s], rec) * 60
        val["avin_elbow_50pct_%s" % s] = {"model": m, "data": av[("elbow", s)]["et_s"], "k": k_sex[s]}
        print("Avin 2010 elbow 50%% %-6s: k=%.4f  MET %.1f s  (data %.1f s; pooled-k model %.1f s)" % (
            s, k_sex[s], m, av[("elbow", s)]["et_s"], met(0.5, ke, rec) * 60))
    for s in ("female", "male"):
        m = met(0.5, ev["k"]["ankle"], rec) * 60
        print("Avin 2010 ankle 50%% %-6s: MET %.1f s (data %.1f s; no significant sex difference)" % (s, m, av[("ankle", s)]["et_s"]))
    # elbow k vs subject-specific study
    print("Elbow k fitted to Frey-Law & Avin: %.3f /min vs subject-specific mean %.2f +/- %.2f /min" % (
        ke, D["kspread"]["k_mean_per_min"], D["kspread"]["k_sd_per_min"]))
    # Bjorksten intermittent 14 % mean force: highest mean force held 60 min for common patterns
    print("Bjorksten & Jonsson 1977 intermittent limit (mean force 14.0 % over 60 min), general k; model limit:")
    bj_int = {}
    for dc in (0.3, 0.5, 0.7):
        for cyc_s in (6, 10, 30, 60):
            on, off = dc * cyc_s / 60, (1 - dc) * cyc_s / 60
            lasts = lambda mean_f: not np.isfinite(intermittent_et(mean_f / dc, on, off, ev["k"]["general"], rec, 60.0))
            lo, hi = 0.001, 0.99 * dc          # bisection on "lasts 60 min" (monotone in the load)
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if lasts(mid) else (lo, mid)
            bj_int["dc%.1f_cycle%ds" % (dc, cyc_s)] = lo
    print("   " + "  ".join("%s: %.3f" % (k2, v) for k2, v in bj_int.items()))
    val["bjorksten_intermittent_mean_force_limit_60min"] = {"model": bj_int, "data": 0.14}
    # 3CC comparisons
    print("Published 3CC(-r) models for comparison (not fitted):")
    cmp3 = {}
    for reg, r in D["threecc"].items():
        rR = r["r_rest_multiplier"] * r["R_per_s"] * 60
        asym = r["R_per_s"] / (r["F_per_s"] + r["R_per_s"])
        cmp3[reg] = {"rest_rate_per_min": rR, "halftime_min": math.log(2) / rR, "asymptote": asym}
        print("   %-8s r*R = %.3f /min (t1/2 %.2f min)   3CC sustainable load R/(F+R) = %.3f   vs fitted f* %.3f" % (
            reg, rR, math.log(2) / rR, asym, fstar(ev["k"][reg], rec)))
    # 3CC-r steady state for the Gonzales task (grip, r = 30): fatigued fraction
    tc = D["threecc"]["grip"]
    F_, R_, r_ = tc["F_per_s"], tc["R_per_s"], tc["r_rest_multiplier"]
    mf_ss = F_ * 0.5 * 0.5 / (r_ * R_ * 0.5 + R_ * 0.5)
    print("   3CC-r (grip, r=30) periodic mean fatigued fraction for 50 %% MVC 5s/5s: %.3f (< 0.5 -> predicts no task failure; data: failure at 739 s)" % mf_ss)
    val["threecc_r_gonzales_mean_MF"] = mf_ss
    # Ma 2009 Table 2 classic general models
    print("Ma et al. 2009 Table 2 general models: asymptotes vs fitted f*(general) = %.3f" % fstar(ev["k"]["general"], rec))
    for row in D["ma2009"]:
        if row["group"] == "general" and isinstance(row["asymptote"], float):
            print("   %-20s asymptote %.2f" % (row["model"], row["asymptote"]))
    print("Back/hip models of Table 2 vs hip (general k) at 20/40/60 %MVC [min]:")
    for row in D["ma2009"]:
        if row["group"] == "back_hip":
            print("   %-26s %s   model %s" % (row["model"], " ".join("%6.2f" % ma2009_met(row, x) for x in (0.2, 0.4, 0.6)),
                                              " ".join("%6.2f" % met(x, ev["k"]["general"], rec) for x in (0.2, 0.4, 0.6))))

    # ---------------------------------------------------------------- tests
    print("\n" + "=" * 100)
    print("6. Expected values for the tests")
    print("=" * 100)
    tests = {}
    ks_ = {reg: region_out[reg]["k"] for reg in REGIONS}
    for reg in REGIONS:
        tests["met_%s" % reg] = {str(int(100 * f)): met(f, ks_[reg], rec) * 60 for f in (0.2, 0.4, 0.6, 0.8, 0.15, 0.10)}
    tests["fstar"] = {reg: region_out[reg]["f_star"] for reg in REGIONS}
    # recovery after exhaustion at 50 % (any region; R(0) only): capacity after t min
    tests["capacity_after_exhaustion_50pct"] = {str(t): hold(0.5, 0.0, 1.0, rec(0.0), t) for t in (0.25, 0.5, 1, 2, 5, 10)}
    tests["gonzales"] = ev["targets"]["gonzales_2007_grip_50pct_5s5s"][1]
    tests["bystrom"] = ev["targets"]["bystrom_1991_grip_25pct_3min_10s"][1]
    tests["sahlin_ratio_1.2min"] = ev["targets"]["sahlin_ren_1989_knee_66pct_endurance_halftime"][1]
    tests["sjogaard_capacity_60min"] = 1 - ev["targets"]["sjogaard_1986_knee_5pct_60min_mvc_loss"][1]
    tests["bjorksten_met_7.9pct_general"] = ev["targets"]["bjorksten_1977_sustained_limit_60min"][1]
    tests["ma2009_met"] = {str(f): -math.log(f) / f for f in (0.2, 0.4, 0.6, 0.8)}
    tests["legacy_fstar_k1_R0.3"] = fstar(1.0, Recovery("constant", R=0.3))
    tests["R_of_f"] = {str(f): rec(f) for f in (0.0, 0.02, 0.05, 0.08, 0.1, 0.2)}
    tests["closed_form_step"] = {"c0": 0.8, "f": 0.3, "k": 1.0, "t_min": 2.0,
                                 "R": rec(0.3), "c": hold(0.8, 0.3, 1.0, rec(0.3), 2.0)}
    tests["closed_form_rest"] = {"c0": 0.5, "f": 0.0, "k": 1.0, "t_min": 2.0, "R": rec(0.0), "c": hold(0.5, 0.0, 1.0, rec(0.0), 2.0)}
    tests["closed_form_low"] = {"c0": 0.9, "f": 0.05, "k": 1.0, "t_min": 30.0, "R": rec(0.05), "c": hold(0.9, 0.05, 1.0, rec(0.05), 30.0)}
    for kk2, vv in tests.items():
        print(kk2, json.dumps(vv) if not isinstance(vv, float) else "%.6g" % vv)
    tests["gonzales_sensitivity"] = sens
    tests["bystrom_k_study"] = k_for_met(D["bystrom"]["continuous"]["f"], D["bystrom"]["continuous"]["tlim_min"], rec)
    print("\nMarkdown: endurance table with test tolerances (tol = |err| rounded up to 5 %% + 5 points)")
    print("| region | f | model MET [s] | Frey-Law & Avin [s] | error | test tolerance |")
    print("|---|---|---|---|---|---|")
    for reg in REGIONS:
        v = region_out[reg]
        for fi, a, b in zip((20, 40, 60, 80), v["met_s_at_20_40_60_80"], v["data_s_at_20_40_60_80"]):
            e = 100 * (a / b - 1)
            tol = 5 * math.ceil(abs(e) / 5) + 5
            print("| %s | %d %%%% | %.2f | %.1f | %+.1f %%%% | ±%d %%%% |" % (reg, fi, a, b, e, tol) % ())

    # ---------------------------------------------------------------- outputs
    def ev_json(ev_):
        return {"k": ev_["k"], "loss": ev_["loss"], "blocks": ev_["blocks"],
                "targets": {k2: {"block": v[0], "model": v[1] if np.isfinite(v[1]) else "inf", "data": v[2],
                                 "unit": v[3], "error_pct": (v[1] / v[2] - 1) * 100 if np.isfinite(v[1]) else "inf"}
                            for k2, v in ev_["targets"].items()}}
    out = {
        "model": "dc/dt = -k f c + R(f)(1-c); time in minutes; exhaustion when c <= f",
        "recommended": {"recovery": rec.describe(), "R_rest_range": [R_lo, R_hi], "f_occ_range": [fo_lo, fo_hi],
                        "R_rest_dataset_estimates": rr, "f_occ_dataset_estimates": fr,
                        "R_rest_fast_component_stull_kearney": R_fast, "k_cv": K_CV, "regions": region_out,
                        "sex_specific_elbow_k": k_sex,
                        "goodness_of_fit": gof, "pooled_endurance_targets": pooled,
                        "gonzales_sensitivity_to_R_rest": sens},
        "optimum_unrounded": {"recovery": rec_opt.describe(), **ev_json(ev_opt)},
        "forms": {k2: {"recovery": v[0].describe(), **ev_json(v[1])} for k2, v in fits.items()},
        "baselines": {k2: {"recovery": v[0].describe(), **ev_json(v[1])} for k2, v in results.items()},
        "validation": val, "threecc_comparison": cmp3, "tests": tests,
    }
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "fitted.json"), "w") as fh:
        json.dump(out, fh, indent=2, default=float)
    write_yaml(out, D)
    print("\nwrote %s and %s" % (os.path.join(OUT, "fitted.json"), os.path.join(OUT, "parameter_sets.yaml")))


def write_yaml(out, D):
    R = out["recommended"]
    rec = R["recovery"]
    regs = R["regions"]
    eq8 = out["baselines"]["Eq.8 alone (k fitted per region, R=0)"]["k"]
    src_k = "Frey-Law & Avin 2010 (Ergonomics 53:109) Table 2 power curve '%s', fitted in log space at 20-80 %%MVC (fit_recovery.py)"
    src_range = "+/-1 SD, CV 0.30 of individual k (elbow, Ergonomics 61(6):806, 2018), applied to every region (assumption)"
    L = []
    w = L.append
    w("# Parameter sets as fitted by docs/tools/fit_recovery.py (for comparison with data/fatigue_sets.yaml).")
    w("# Model: dc/dt = -k f c + R(f) (1 - c), dU/dt = f/c^2, time in minutes, exhaustion when c <= f.")
    w("# Recovery forms: none: R = 0.")
    w("#   smoothstep: R(f) = R_rest * x^2 (3 - 2 x), x = 1 - f/f_occ for f < f_occ; R = 0 for f >= f_occ.")
    w("#   (C1 in f, >= 0, constant while f is constant -> exact closed form per held step.)")
    w("# f_star = sustainable load, root of R(f)(1 - f) = k f^2 (holds below f_star never exhaust).")
    w("# The shipped sets are data/fatigue_sets.yaml; docs/fatigue-parameters.md gives sources and fit quality.")
    w("default_set: default-2026")
    w("sets:")

    def recovery_block(indent="    "):
        w(indent + "recovery:")
        w(indent + "  form: smoothstep")
        w(indent + "  scope: global        # the data do not support per-region recovery parameters")
        w(indent + "  R_rest: {value: %.4f, low: %.4f, high: %.4f, unit: per_min}" % (rec["R_rest"], *R["R_rest_range"]))
        w(indent + "  f_occ: {value: %.4f, low: %.4f, high: %.4f, unit: fraction_mvc}" % (rec["f_occ"], *R["f_occ_range"]))
        w(indent + "  sources:")
        w(indent + "    R_rest: \"joint fit (fit_recovery.py; optimum 0.372 rounded to 2 s.f.) to Gonzales & Scheuermann 2007 (J Sports Sci Med 6:98), Bystrom et al. 1991 (Eur J Appl Physiol 63), Sahlin & Ren 1989 (J Appl Physiol 67:648); low/high = dataset-wise re-fits\"")
        w(indent + "    f_occ: \"joint fit (optimum 0.0847 rounded to 2 s.f.) to Bjorksten & Jonsson 1977 (Scand J Work Environ Health 3:23), Sjogaard et al. 1986 (Acta Physiol Scand 128:475), Mathiassen & Ahsberg 1999 (Int J Ind Ergon 24:315); low = Bjorksten & Jonsson 60-min sustained limit 0.079, high = classic 15 %MVC asymptote (Rohmert, Huijgens; Ma et al. 2009 Table 2)\"")

    def region_block(kmap, fs=True, note=None, ksrc=None, overrides=None):
        w("    regions:")
        for reg in REGIONS:
            k = kmap[reg]
            if overrides and reg in overrides:
                k, src = overrides[reg]
            else:
                src = (ksrc or src_k) % CURVE_OF[reg] if "%s" in (ksrc or src_k) else (ksrc or src_k)
            line = "      %-8s {curve: %-8s k: %.4f, k_low: %.4f, k_high: %.4f" % (
                reg + ":", CURVE_OF[reg] + ",", k, k * (1 - K_CV), k * (1 + K_CV))
            if fs:
                line += ", f_star: %.4f, f_star_low: %.4f, f_star_high: %.4f" % (
                    fstar(k, Recovery("smoothstep", R_rest=rec["R_rest"], f_occ=rec["f_occ"])),
                    fstar(k * (1 + K_CV), Recovery("smoothstep", R_rest=R["R_rest_range"][0], f_occ=R["f_occ_range"][0])),
                    fstar(k * (1 - K_CV), Recovery("smoothstep", R_rest=R["R_rest_range"][1], f_occ=R["f_occ_range"][1])))
            w(line + "}")
            w("      # %s: %s" % (reg, src))
        w("    k_range_source: \"%s\"" % src_range)
        if fs:
            w("    f_star_range: \"low = k_high with R_rest low and f_occ low; high = k_low with R_rest high and f_occ high\"")
        if note:
            w("    note: \"%s\"" % note)

    # ma2009
    w("  ma2009:")
    w("    description: \"Ma, Chablat, Bennis & Zhang (2009) Int J Ind Ergon 39:211, Table 1: k = 1 /min for every muscle group, no recovery (R = 0).\"")
    w("    recovery: {form: none}")
    w("    regions:")
    for reg in REGIONS:
        w("      %-8s {k: 1.0, k_low: %.4f, k_high: %.4f, f_star: 0.0}" % (reg + ":", 1 - K_CV, 1 + K_CV))
    w("    k_source: \"Ma et al. 2009 Table 1 (k = 1, constant)\"")
    w("    k_range_source: \"%s\"" % src_range)
    # frey-law-avin-2010
    w("  frey-law-avin-2010:")
    w("    description: \"k per region from Eq. 8 fitted to the Frey-Law & Avin (2010) power curves (20-80 %MVC) with R = 0, plus the recommended recovery. Neck and hip have no curve and use 'general'.\"")
    recovery_block()
    region_block({reg: eq8[CURVE_OF[reg]] for reg in REGIONS})
    # default
    w("  default-2026:")
    w("    description: \"Recommended default. k per region re-fitted jointly with the recovery term (identical to frey-law-avin-2010 because f_occ < 0.20, so R(f) = 0 over the fitted 20-80 %MVC range); perfusion-limited recovery.\"")
    recovery_block()
    region_block({reg: regs[reg]["k"] for reg in REGIONS})
    # sex-specific
    ks = R["sex_specific_elbow_k"]
    for sex in ("female", "male"):
        w("  default-2026-%s:" % sex)
        w("    description: \"default-2026 with a sex-specific elbow k (Avin et al. 2010, Med Sci Sports Exerc 42:1943: 50 %%MVC elbow flexion %s). No other region has a published, verified quantitative sex difference: ankle n.s. (Avin 2010), handgrip intermittent n.s. (Gonzales & Scheuermann 2007); Hunter 2018 (Cold Spring Harb Perspect Med 8:a029728) reports directions only -> default k kept.\"" % (
            "women 112.3 s" if sex == "female" else "men 80.3 s"))
        recovery_block()
        region_block({reg: regs[reg]["k"] for reg in REGIONS},
                     overrides={"elbow": (ks[sex], "default elbow k x (pooled 96.3 s / %s %.1f s) from Avin et al. 2010" % (
                         sex, 112.3 if sex == "female" else 80.3))})
    with open(os.path.join(OUT, "parameter_sets.yaml"), "w") as fh:
        fh.write("\n".join(L) + "\n")


if __name__ == "__main__":
    import sys
    if "--out" in sys.argv:
        OUT = os.path.abspath(sys.argv[sys.argv.index("--out") + 1])
    main()
