#!/usr/bin/env python3
"""Global search for the fatigue-only optimum of a task (independent reference).

    python3 optimise.py TASK [--budget SECONDS] [--out results/TASK.json]

Method (README.md beside this file):
  1. joint multi-start: the whole plan (all distinct phases) solved as one NLP from several
     deterministic seed families (SLSQP, then IPOPT polish); the best is the reference plan;
  2. per-phase global search: for every seed family and random seed, each phase's posture is
     re-solved with the other phases fixed at the current best plan (exact total-U objective,
     SLSQP->IPOPT and IPOPT paths); every improvement of the total is accepted at once
     (block-coordinate descent with multi-start blocks);
  3. basin hopping per phase: random perturbations of joint groups of the best posture;
  4. joint polish of the best plan, pool re-solve, joint polish again; strict feasibility check
     with the evaluator.
"""
import argparse
import json
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference import model as M  # noqa: E402
from reference import search as S  # noqa: E402
from reference.nlp import JointNLP  # noqa: E402

GROUPS = {
    "right_arm": ["r_shoulder_flexion", "r_shoulder_abduction", "r_shoulder_rotation",
                  "r_elbow_flexion", "r_forearm_pronation", "r_wrist_flexion", "r_wrist_deviation"],
    "left_arm": ["l_shoulder_flexion", "l_shoulder_abduction", "l_shoulder_rotation",
                 "l_elbow_flexion", "l_forearm_pronation", "l_wrist_flexion", "l_wrist_deviation"],
    "trunk": ["lumbar_flexion", "lumbar_lateral_bending", "lumbar_axial_rotation", "pelvis_rotation",
              "pelvis_tilt", "pelvis_list", "neck_flexion", "neck_lateral_bending",
              "neck_axial_rotation"],
    "legs": ["pelvis_tx", "pelvis_ty", "pelvis_tz", "r_hip_flexion", "r_hip_abduction",
             "r_hip_rotation", "r_knee_flexion", "r_ankle_dorsiflexion", "r_ankle_inversion",
             "l_hip_flexion", "l_hip_abduction", "l_hip_rotation", "l_knee_flexion",
             "l_ankle_dorsiflexion", "l_ankle_inversion"],
}


class Search:
    def __init__(self, key, budget, log=print, n_random=16, resume=None, seed_offset=0,
                 zones=False, checkpoint=None, checkpoint_every=100.0, rerun_joint=False,
                 joint_fraction=0.2, families=None, capacity=False):
        self.key = key
        self.t = M.load_task(key)
        self.zones = zones
        self.pr = M.Problem(self.t, zones=zones)
        # statement section 4, "capacity (no muscle group gives out)": rows in every NLP
        self.capacity = bool(capacity)
        self.pr.capacity = self.capacity
        self.checkpoint_fn = checkpoint
        self.checkpoint_every = checkpoint_every
        self.last_checkpoint = time.time()
        self.full = JointNLP(self.pr)
        self.b = self.t.body
        self.budget = budget
        self.t0 = time.time()
        self.log = log
        self.n_random = n_random
        self.best = None          # dict(U, qs, fs, origin per phase)
        self.joint_optima = []    # (objective, label, total U)
        self.phase_pool = {gi: [] for gi in range(self.t.P)}   # (q, label)
        self.starts = []          # labels of all local solves
        self.solves = 0
        self.resume = resume
        self.seed_offset = seed_offset
        self.prev_runtime = 0.0
        self.rerun_joint = rerun_joint
        # stage 1's share of the budget and its seed families, in order (default: all of
        # search.FAMILIES in their order, 20 %)
        self.joint_fraction = joint_fraction
        self.families = list(families) if families else list(S.FAMILIES)

    # --- helpers --------------------------------------------------------------------------------
    def elapsed(self):
        return time.time() - self.t0

    def plan_total(self, qs):
        """The plan's objective (the total U; with zones ln(U + 1e-3) + 10 sum v) and loads."""
        fs = [self.full.pm[gi].loads_from_q(qs[gi]) for gi in range(self.t.P)]
        U, c, tex = self.pr.fatigue(fs)
        return self.pr.objective(float(U.sum()), qs), fs

    def plan_u(self, qs):
        fs = [self.full.pm[gi].loads_from_q(qs[gi]) for gi in range(self.t.P)]
        U, c, tex = self.pr.fatigue(fs)
        return float(U.sum())

    def capacity_slack(self, qs):
        """Smallest capacity row (statement section 4, "capacity") at the plan's true loads;
        +inf without --capacity."""
        if not self.capacity:
            return np.inf
        fs = [self.full.pm[gi].loads_from_q(q) for gi, q in enumerate(qs)]
        v = self.full.capacity_rows(np.concatenate(list(qs) + list(fs)
                                                   + ([np.zeros(self.full.nz * self.t.P)]
                                                      if self.full.zones else [])))
        return float(v.min()) if len(v) else np.inf

    def capacity_ok(self, qs):
        return self.capacity_slack(qs) >= -1e-7

    def maybe_checkpoint(self, force=False):
        if self.checkpoint_fn is None or self.best is None:
            return
        if force or time.time() - self.last_checkpoint >= self.checkpoint_every:
            try:
                self.checkpoint_fn(self)
            except Exception as ex:  # a failed checkpoint must not stop the search
                self.log(f"   checkpoint failed {ex!r}")
            self.last_checkpoint = time.time()

    def feasible_q(self, gi, q):
        pm = self.full.pm[gi]
        f = pm.loads_from_q(q)
        e = pm.eq(q, f)
        if np.max(np.abs(e[:3 * len(pm.hands) + 12])) > 1e-6:
            return False
        if pm.min_clearance_slack(q) < -1e-7:
            return False
        e2 = pm.evaluate(q, False)
        bal = pm.edges_n @ e2["p"] - pm.edges_o - self.t.balance_margin
        if np.min(bal) < -1e-7:
            return False
        if np.any(q < self.b.lower - 1e-12) or np.any(q > self.b.upper + 1e-12):
            return False
        pts = self.pr.gaze_points[gi] if self.zones else []
        if pts and np.min(self.pr.zm.gaze_values(q, pts)) < -1e-7:
            return False
        return True

    def offer(self, qs, origins, label, force=False):
        """Accept a plan if it is better than the best: fewer infeasible phases, or as many and a
        lower total U (an infeasible phase only occurs while bootstrapping a hard task)."""
        feas = [self.feasible_q(gi, qs[gi]) for gi in range(self.t.P)]
        U, fs = self.plan_total(qs)
        # with --capacity a plan that exhausts a group counts as one more infeasible "phase"
        cap_bad = 0 if self.capacity_ok(qs) else 1
        nbad = feas.count(False) + cap_bad
        if self.best is not None and not force:
            key_old = (self.best["feas"].count(False) + self.best.get("cap_bad", 0), self.best["U"])
            if (nbad, U) >= (key_old[0], key_old[1] - 1e-12):
                return False
            if nbad > 0 and nbad == key_old[0]:
                return False
        old = None if self.best is None else self.best["U"]
        self.best = dict(U=U, qs=[q.copy() for q in qs], fs=fs, origin=list(origins), feas=feas,
                         cap_bad=cap_bad)
        self.best["total_u"] = self.plan_u(qs) if self.zones else U
        self.log(f"[{self.key} {self.elapsed():7.1f}s] best {U:.10g} (was {old}) by {label}"
                 + (f" [total U {self.best['total_u']:.8g}]" if self.zones else "")
                 + (f" [{nbad} phase(s) still infeasible]" if nbad else ""))
        self.maybe_checkpoint()
        return True

    # --- local solves ---------------------------------------------------------------------------
    def joint_solve(self, qs0, label):
        """All phases together: IPOPT from the seed, then a tight IPOPT polish."""
        nlp = self.full
        x0 = S.initial_x(nlp, qs0)
        cands = []
        self.starts.append(label)
        self.solves += 1
        try:
            r = S.solve_ipopt(nlp, x0, max_cpu_time=60)
            cands.append(r[0])
            r = S.solve_ipopt(nlp, r[0], max_cpu_time=30, tol=1e-10)
            cands.append(r[0])
        except Exception as ex:  # a failed start is recorded and skipped
            self.log(f"   {label}: failed {ex!r}")
        best = None
        for x in cands:
            qs, _ = nlp.split(x)
            qs = [np.clip(q, self.b.lower, self.b.upper) for q in qs]
            if all(self.feasible_q(gi, qs[gi]) for gi in range(self.t.P)) and self.capacity_ok(qs):
                U, _ = self.plan_total(qs)
                if best is None or U < best[0]:
                    best = (U, qs)
        if best is not None:
            self.joint_optima.append((best[0], label, self.plan_u(best[1])))
            for gi in range(self.t.P):
                self.phase_pool[gi].append((best[1][gi], label))
            self.offer(best[1], [label] * self.t.P, f"joint {label}")
            self.log(f"   joint {label}: {best[0]:.8g}")
        else:
            self.log(f"   joint {label}: no feasible result")
        self.maybe_checkpoint()
        return best

    def phase_solve(self, gi, q0, label, paths=("slsqp", "ipopt"), parent=None):
        nlp = JointNLP(self.pr, phases=[gi])
        nlp.pm = self.full.pm
        nlp.fixed_loads = self.best["fs"]
        x0 = S.initial_x(nlp, [q0])
        self.starts.append(f"{self.t.groups[gi]['name']}: {label}")
        self.solves += 1
        cands = []
        try:
            if "slsqp" in paths:
                x1, f1, v1, _ = S.solve(nlp, x0, maxiter=200, rounds=3)
                r = S.solve_ipopt(nlp, x1, max_cpu_time=15, tol=1e-10)
                cands.append((r[0], label + " [slsqp+ipopt]"))
                cands.append((x1, label + " [slsqp]"))
            if "ipopt" in paths:
                r = S.solve_ipopt(nlp, x0, max_cpu_time=20)
                cands.append((r[0], label + " [ipopt]"))
        except Exception as ex:
            self.log(f"   {label}: failed {ex!r}")
        out = None
        for x, lab in cands:
            q = np.clip(nlp.split(x)[0][0], self.b.lower, self.b.upper)
            if not self.feasible_q(gi, q):
                continue
            qs = [qq.copy() for qq in self.best["qs"]]
            qs[gi] = q
            U, _ = self.plan_total(qs)
            # with --capacity: plans meeting it first (a bootstrap plan may not yet)
            U = (0 if self.capacity_ok(qs) else 1, U)
            if out is None or U < out[0]:
                out = (U, q, lab)
        if out is not None:
            self.phase_pool[gi].append((out[1], out[2]))
            qs = [qq.copy() for qq in self.best["qs"]]
            qs[gi] = out[1]
            origins = list(self.best["origin"])
            origins[gi] = (parent + " > " if parent else "") + out[2]
            self.offer(qs, origins, f"{self.t.groups[gi]['name']}: {out[2]}")
        self.maybe_checkpoint()
        return out

    # --- stages ---------------------------------------------------------------------------------
    def seed_posture(self, gi, q_t):
        """A template brought onto the constraints. Without zones: the IK projection (hands and
        feet only). With zones (run 7): the zone-respecting feasibility restoration
        S.restore_zones from the template (hands, feet, clearance incl. held boxes, balance,
        gaze, zone excesses, closeness to the template), unless the IK projection is already
        feasible and within the zones; the IK projection alone put hold_and_place's seeds
        100-150 deg stooped, inside the table and off balance (run 6)."""
        pm = self.full.pm[gi]
        q_ik = S.ik_project(pm, q_t)
        if not self.zones:
            return q_ik
        if self.feasible_q(gi, q_ik) and np.max(self.pr.zone_slacks(gi, q_ik)) <= 1e-6:
            return q_ik
        try:
            return S.restore_zones(pm, q_t)
        except Exception as ex:  # a failed restoration falls back to the IK projection
            self.log(f"   restore_zones failed {ex!r}")
            return q_ik

    def seeds_for(self, fam, rs):
        rng = np.random.default_rng(rs) if rs is not None else None
        return [self.seed_posture(gi, S.template(self.b, self.t.rest_q, fam, rng))
                for gi in range(self.t.P)]

    def run(self):
        t = self.t
        P = t.P
        B = self.budget
        if self.resume:
            self.load_previous(self.resume)
        # 1. joint multi-start (on --resume: the seed families not started before)
        for fam in self.families:
            if self.elapsed() > self.joint_fraction * B:
                break
            if f"joint:{fam}" in self.starts:
                continue
            self.joint_solve(self.seeds_for(S.FAMILIES[fam], None), f"joint:{fam}")
        if self.best is None:
            # bootstrap: the IK projection of the rest posture (possibly infeasible); the
            # per-phase solves below make the phases feasible one by one
            self.offer(self.seeds_for({}, None), ["ik"] * P, "ik bootstrap", force=True)
        # 2-3. rounds of: per-phase multi-start from new seeds (exploration), basin hopping on the
        # best postures (exploitation), re-solve of the best pool postures with the current loads
        seeds = S.seed_list(self.n_random, offset=self.seed_offset)
        if self.resume:
            seeds = [sd for sd in seeds if sd[2] is not None]  # families were done before
        rng = np.random.default_rng(12345 + self.seed_offset)
        si = 0
        hop = 0
        resolved = {}
        while self.elapsed() < 0.85 * B:
            for _ in range(3):
                if si >= len(seeds) or self.elapsed() > 0.85 * B:
                    break
                name, fam, rs = seeds[si]
                qs0 = self.seeds_for(fam, rs)
                for gi in range(P):
                    paths = ("slsqp", "ipopt") if si % 2 == 0 else ("ipopt", "slsqp")
                    self.phase_solve(gi, qs0[gi], f"seed:{name}", paths=paths)
                si += 1
            for _ in range(2 * P):
                if self.elapsed() > 0.85 * B:
                    break
                gi = hop % P
                grp = list(GROUPS)[(hop // P) % len(GROUPS)]
                q = self.best["qs"][gi].copy()
                scale = 0.25 if (hop // (P * len(GROUPS))) % 2 == 0 else 0.5
                for jn in GROUPS[grp]:
                    i = self.b.qidx[jn]
                    span = min(self.b.upper[i] - self.b.lower[i], 2.0)
                    q[i] += rng.normal(0, scale) * span
                q = np.clip(q, self.b.lower, self.b.upper)
                q = self.seed_posture(gi, q)
                self.phase_solve(gi, q, f"hop{hop}:{grp}", paths=("ipopt",) if hop % 2 else ("slsqp",),
                                 parent=self.best["origin"][gi])
                hop += 1
            for gi in range(P):
                if self.elapsed() > 0.85 * B:
                    break
                pool = sorted(range(len(self.phase_pool[gi])),
                              key=lambda j: self.value_with(gi, self.phase_pool[gi][j][0]))
                done = 0
                for j in pool:
                    if done >= 2:
                        break
                    if resolved.get((gi, j)) == self.best["U"]:
                        continue
                    resolved[(gi, j)] = self.best["U"]
                    q, lab = self.phase_pool[gi][j]
                    if np.max(np.abs(q - self.best["qs"][gi])) < 1e-6:
                        continue
                    self.phase_solve(gi, q, "pool", paths=("ipopt",), parent=lab)
                    done += 1
            if si >= len(seeds):
                more = S.seed_list(self.n_random + 8, offset=self.seed_offset)
                seeds += [sd for sd in more if sd[2] is not None and sd not in seeds]
                self.n_random += 8
        # 4. joint polish and block sweeps, then the best pool posture of each phase
        self.polish("final")
        self.pool_swap()
        return self.result()

    def pool_swap(self):
        """Greedy block moves among the postures already found: each phase's pool posture that
        lowers the total with the other phases at the best plan is taken, until none does (a
        joint polish can move the other phases so that an earlier posture of a phase becomes
        better than its polished one)."""
        improved = True
        while improved:
            improved = False
            for gi in range(self.t.P):
                # a phase with an empty pool, or none of whose pool postures is feasible, has
                # nothing to swap in (run 6: min() of an empty list crashed the final pool swap)
                vals = [(self.value_with(gi, q), j) for j, (q, _) in enumerate(self.phase_pool[gi])]
                vals = [(u, j) for u, j in vals if np.isfinite(u)]
                if not vals:
                    continue
                u, j = min(vals)
                if u < self.best["U"] - 1e-9 * abs(self.best["U"]):
                    q, lab = self.phase_pool[gi][j]
                    qs = [qq.copy() for qq in self.best["qs"]]
                    qs[gi] = q.copy()
                    origins = list(self.best["origin"])
                    origins[gi] = lab + " > pool-swap"
                    improved |= self.offer(qs, origins, f"{self.t.groups[gi]['name']}: pool swap")

    def load_previous(self, path):
        """Continue a previous search: its best plan, pool and records."""
        with open(path) as fh:
            prev = json.load(fh)
        t = self.t
        qs = [self.b.q_from_dict(prev["postures"][g["name"]]) for g in t.groups]
        origins = [prev["best_found_by"][g["name"]] for g in t.groups]
        self.joint_optima = [(d.get("objective", d["total_u_min"]), d["start"], d["total_u_min"])
                             for d in prev["joint_local_optima"]]
        self.starts = list(prev["starts"]["labels"])
        self.solves = prev["starts"]["local_solves"]
        self.prev_runtime = prev["runtime_s"]
        pool_path = path.replace(".json", ".pool.json")
        if os.path.exists(pool_path):
            with open(pool_path) as fh:
                pool = json.load(fh)
            for g_i, g in enumerate(t.groups):
                for d in pool.get(g["name"], []):
                    self.phase_pool[g_i].append((self.b.q_from_dict(d["posture"]), d["label"]))
        if self.rerun_joint:
            # the previous run's whole-plan local optima were found (and valued) under an earlier
            # statement: drop them, relabel their starts and pool postures "prev:joint:<family>",
            # so that stage 1 solves every seed family again under the current rows
            self.joint_optima = []
            self.starts = ["prev:" + s if s.startswith("joint:") else s for s in self.starts]
            for gi in range(t.P):
                self.phase_pool[gi] = [(q, "prev:" + lab if lab.startswith("joint:") else lab)
                                       for q, lab in self.phase_pool[gi]]
        # the previous best plan is re-evaluated here with the current code (offer ->
        # plan_total); the stored objective is only printed
        ok = self.offer(qs, origins, f"previous run (stored {prev.get('best_objective', prev['best_total_u_min']):.10g})")
        if not ok:
            raise RuntimeError("previous best plan is not feasible")
        for gi in range(t.P):
            self.phase_pool[gi].append((qs[gi], origins[gi]))

    def value_with(self, gi, q):
        if not self.feasible_q(gi, q):
            return np.inf
        qs = [qq.copy() for qq in self.best["qs"]]
        qs[gi] = q
        if not self.capacity_ok(qs):
            return np.inf
        return self.plan_total(qs)[0]

    def polish(self, label, sweeps=3):
        """Joint IPOPT polish, then block sweeps (each phase re-solved from its best posture with
        both local solvers), then a joint polish again."""
        nlp = self.full
        for sweep in range(sweeps):
            before = self.best["U"]
            try:
                x0 = S.initial_x(nlp, self.best["qs"])
                r = S.solve_ipopt(nlp, x0, max_cpu_time=90, tol=1e-11)
                qs = [np.clip(q, self.b.lower, self.b.upper) for q in nlp.split(r[0])[0]]
                self.offer(qs, [o + f" > {label}-joint" for o in self.best["origin"]],
                           f"{label} joint ipopt")
            except Exception as ex:
                self.log(f"   polish failed {ex!r}")
            for gi in range(self.t.P):
                self.phase_solve(gi, self.best["qs"][gi].copy(), f"{label}-sweep{sweep}",
                                 paths=("slsqp", "ipopt"), parent=self.best["origin"][gi])
            if self.best["U"] > before - 1e-9 * abs(before):
                break

    def result(self, light=False):
        t, b = self.t, self.b
        rep = self.pr.evaluate(self.best["qs"])
        # spread of the per-phase local optima with the other phases at the best plan
        phase_optima = {}
        for gi in range(t.P):
            if light:
                continue
            vals = sorted(set(round(self.value_with(gi, q), 6) for q, _ in self.phase_pool[gi]))
            phase_optima[t.groups[gi]["name"]] = [v for v in vals if np.isfinite(v)]
        postures = {g["name"]: rep["phases"][gi]["posture"] for gi, g in enumerate(t.groups)}
        residuals = {g["name"]: rep["phases"][gi]["residuals"] for gi, g in enumerate(t.groups)}
        extra = {}
        if self.zones:
            extra = dict(
                zones_on=True,
                objective_formula="ln(total U [min] + 1e-3) + 10 * sum of zone slacks [rad] "
                                  "(per distinct posture)",
                best_objective=rep["objective"],
                zone_limits_deg={g["name"]: dict(zip(self.pr.Z.ROW_NAMES,
                                                     np.degrees(self.pr.zone_limits[gi]).tolist()))
                                 for gi, g in enumerate(t.groups)},
                holds_s={ph.name: h for ph, h in zip(t.phases, self.pr.holds)},
                zone_slack_sum_rad=float(sum(p["zone_slack_sum_rad"] for p in rep["phases"])),
                zones_exceeded_note="rows beyond their limit by more than 1e-4 deg (zone_slack_sum_rad counts every positive slack)",
                zones_exceeded={g["name"]: [dict(row=z["row"], angle_deg=z["angle_deg"],
                                                 limit_deg=z["limit_deg"], excess_deg=z["excess_deg"],
                                                 slack_rad=z["slack_rad"])
                                            for z in rep["phases"][gi]["zones"] if z["excess_deg"] > 1e-4]
                                for gi, g in enumerate(t.groups)},
                zone_angles_deg={g["name"]: {z["row"]: z["angle_deg"] for z in rep["phases"][gi]["zones"]}
                                 for gi, g in enumerate(t.groups)},
                gaze={g["name"]: dict(points=rep["phases"][gi].get("gaze_points"),
                                      margin=rep["phases"][gi]["residuals"].get("gaze_margin"),
                                      angle_deg=rep["phases"][gi]["residuals"].get("gaze_angle_deg"))
                      for gi, g in enumerate(t.groups)},
                joint_local_optima_objectives=sorted(o for o, _, _ in self.joint_optima),
                checkpoint=light,
            )
        if self.capacity:
            qs = list(self.best["qs"])
            fs = [self.full.pm[gi].loads_from_q(q) for gi, q in enumerate(qs)]
            cap = self.full.capacity_rows(self.full.pack(qs, fs))
            extra.update(capacity_on=True,
                         capacity_note="rows: step-end capacity (first and last cycle) - load - 0.02 "
                                       "per half-joint and step holding a phase posture; >= 0 when met",
                         capacity_min_slack=float(cap.min()) if len(cap) else None)
        return dict(
            task=t.key,
            task_name=t.name,
            **extra,
            best_total_u_min=rep["total_u_min"],
            exhausted=rep["exhausted"],
            exhaustion_time_min=rep["exhaustion_time_min"],
            exhausted_half_joints=rep["exhausted_half_joints"],
            feasible=rep["feasible"],
            max_unactuated_torque_nm=rep["max_unactuated_torque_nm"],
            phase_groups={g["name"]: g["members"] for g in t.groups},
            postures=postures,
            rest_posture=rep["rest"]["posture"],
            residuals=residuals,
            u_per_half_joint=rep["u_per_half_joint"],
            starts=dict(count=len(self.starts), local_solves=self.solves, labels=self.starts),
            best_found_by=dict(zip([g["name"] for g in t.groups], self.best["origin"])),
            local_optima_totals=sorted(u for _, _, u in self.joint_optima),
            joint_local_optima=sorted([dict(objective=o, total_u_min=u, start=lab)
                                       for o, lab, u in self.joint_optima],
                                      key=lambda d: d["objective"]),
            phase_local_optima_totals=phase_optima,
            runtime_s=self.elapsed() + self.prev_runtime,
            budget_s=self.budget,
        ), rep

    def pool_json(self):
        out = {}
        for gi, g in enumerate(self.t.groups):
            out[g["name"]] = [dict(label=lab, posture=self.b.q_to_dict(q)) for q, lab in self.phase_pool[gi]]
        return out


def _sha256(path):
    import hashlib
    with open(path, "rb") as fh:
        return hashlib.sha256(fh.read()).hexdigest()


def _stats(v):
    v = sorted(v)
    return dict(count=len(v), min=v[0] if v else None, median=float(np.median(v)) if v else None,
                max=v[-1] if v else None)


def augment(res, task, pool, zones=False):
    """Adds what a consumer of results/<task>.json needs without this package: the schedule of
    one cycle (to replay the best plan as a recording), whether each whole-plan local optimum
    exhausts a muscle group, the spread of the local optima, and the input files used (with their
    SHA-256). pool: distinct phase name -> list of (label, posture dict), as in <task>.pool.json;
    a whole-plan local optimum's postures carry its start label ("joint:<family>")."""
    res["schedule"] = task.schedule()
    prob = M.Problem(task, zones=zones)
    b = task.body
    for d in res.get("joint_local_optima", []):
        qs = []
        for g in task.groups:
            q = [p for lab, p in pool[g["name"]] if lab == d["start"]]
            qs.append(b.q_from_dict(q[0]) if q else None)
        if any(q is None for q in qs):
            continue
        rep = prob.evaluate(qs)
        assert abs(rep["total_u_min"] - d["total_u_min"]) <= 1e-9 * abs(d["total_u_min"]), d
        d["objective_check"] = rep["objective"]
        d["exhausted"] = rep["exhausted"]
        d["exhaustion_time_min"] = rep["exhaustion_time_min"]
        d["exhausted_half_joints"] = sorted(rep["exhausted_half_joints"])
    joint = [d["total_u_min"] for d in res.get("joint_local_optima", [])]
    sustainable = [d["total_u_min"] for d in res.get("joint_local_optima", [])
                   if d.get("exhausted") is False]
    res["spread"] = dict(
        joint_local_optima=_stats(joint),
        sustainable_joint_local_optima=_stats(sustainable),
        phase_local_optima={name: dict(count=len(v), min=v[0] if v else None,
                                       median=float(np.median(v)) if v else None,
                                       max=v[-1] if v else None)
                            for name, v in res.get("phase_local_optima_totals", {}).items()},
        note="joint_local_optima: total U [min] of every feasible whole-plan local optimum found "
             "by the joint multi-start (stage 1, one per seed family); sustainable_joint_local_optima: "
             "those that exhaust no muscle group (capacity stays above load all task); "
             "phase_local_optima: total U "
             "with one distinct phase replaced by each posture of its pool (the other phases at "
             "the best plan), distinct to 1e-6 min")
    urdf = task.body.urdf_path
    files = [task.path, urdf, os.path.join(M.INPUTS, "worker.strength.yaml"),
             os.path.join(M.INPUTS, "fatigue_sets.yaml"), os.path.join(M.INPUTS, f"{task.key}.rest_posture.json")]
    res["inputs"] = {os.path.relpath(f, os.path.dirname(M.INPUTS)): _sha256(f) for f in files}
    return res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("task")
    ap.add_argument("--budget", type=float, default=2400.0)
    ap.add_argument("--random", type=int, default=16)
    ap.add_argument("--out", default=None)
    ap.add_argument("--resume", default=None, help="results JSON of a previous run to continue")
    ap.add_argument("--seed-offset", type=int, default=0)
    ap.add_argument("--zones", action="store_true",
                    help="posture zones (elastic) and gaze on; objective ln(U + 1e-3) + 10 sum v; "
                         "results go to results_zones/ unless --out is given")
    ap.add_argument("--capacity", action="store_true",
                    help="capacity constraint of statement section 4 (each half-joint's load in a "
                         "phase <= min step-end capacity over the first and last cycle - 0.02) in "
                         "every NLP; off by default (results before 2026-12-08 are without it)")
    ap.add_argument("--checkpoint-every", type=float, default=100.0)
    ap.add_argument("--rerun-joint", action="store_true",
                    help="with --resume: drop the previous run's whole-plan local optima (relabel "
                         "their starts and pool postures prev:joint:<family>) and solve every "
                         "joint seed family again (for a resume after the statement changed)")
    ap.add_argument("--joint-fraction", type=float, default=0.2,
                    help="share of the budget stage 1 (the joint multi-start) may use (default 0.2)")
    ap.add_argument("--families", default=None,
                    help="comma-separated seed families for stage 1, in this order (default: all "
                         "of search.FAMILIES in their order); families started before are skipped")
    ap.add_argument("--pool-swap-only", action="store_true",
                    help="only apply the final pool swap (Search.pool_swap) to an existing result "
                         "and its .pool.json (--out or results/TASK.json), then rewrite both")
    ap.add_argument("--augment-only", action="store_true",
                    help="only (re)write the schedule, spread and inputs fields of an existing "
                         "results file (--out or results/TASK.json)")
    a = ap.parse_args()
    key = os.path.splitext(os.path.basename(a.task))[0]
    here = os.path.dirname(os.path.abspath(__file__))
    out = a.out or os.path.join(here, "results_zones" if a.zones else "results", f"{key}.json")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    if a.augment_only:
        with open(out) as fh:
            res = json.load(fh)
        with open(out.replace(".json", ".pool.json")) as fh:
            pool = {g: [(d["label"], d["posture"]) for d in v] for g, v in json.load(fh).items()}
        res = augment(res, M.load_task(key), pool, zones=a.zones)
        with open(out, "w") as fh:
            json.dump(res, fh, indent=1)
        return
    logf = open(out.replace(".json", ".log"), "a" if (a.resume or a.pool_swap_only) else "w")

    def log(msg):
        print(msg, flush=True)
        logf.write(msg + "\n")
        logf.flush()

    def checkpoint(srch):
        res_c, _ = srch.result(light=True)
        res_c["inputs"] = {}
        tmp = out + ".tmp"
        with open(tmp, "w") as fh:
            json.dump(res_c, fh, indent=1)
        os.replace(tmp, out)
        with open(out.replace(".json", ".pool.json") + ".tmp", "w") as fh:
            json.dump(srch.pool_json(), fh)
        os.replace(out.replace(".json", ".pool.json") + ".tmp", out.replace(".json", ".pool.json"))
        log(f"   checkpoint written ({srch.elapsed():.0f} s, best {srch.best['U']:.10g})")

    s = Search(key, a.budget, log=log, n_random=a.random, resume=a.resume, seed_offset=a.seed_offset,
               zones=a.zones, checkpoint=checkpoint, checkpoint_every=a.checkpoint_every,
               rerun_joint=a.rerun_joint, joint_fraction=a.joint_fraction, capacity=a.capacity,
               families=None if not a.families else [f.strip() for f in a.families.split(",")])
    S.PROGRESS_HOOK = s.maybe_checkpoint
    if a.pool_swap_only:
        with open(out) as fh:
            s.budget = json.load(fh).get("budget_s", a.budget)
        s.load_previous(out)
        s.pool_swap()
        res, rep = s.result()
    else:
        res, rep = s.run()
    res = augment(res, s.t, {g["name"]: [(lab, s.b.q_to_dict(q)) for q, lab in s.phase_pool[gi]]
                             for gi, g in enumerate(s.t.groups)}, zones=a.zones)
    with open(out.replace(".json", ".pool.json"), "w") as fh:
        json.dump(s.pool_json(), fh)
    with open(out, "w") as fh:
        json.dump(res, fh, indent=1)
    with open(out.replace(".json", ".report.json"), "w") as fh:
        json.dump(rep, fh, indent=1)
    if a.zones:
        log(f"{key}: best objective {res['best_objective']:.10g}, zone slack sum "
            f"{res['zone_slack_sum_rad']:.6g} rad")
    log(f"{key}: best total U {res['best_total_u_min']:.10g} min, exhausted {res['exhausted']}, "
        f"feasible {res['feasible']['ok']}, {res['starts']['count']} starts, {res['runtime_s']:.0f} s")


if __name__ == "__main__":
    main()
