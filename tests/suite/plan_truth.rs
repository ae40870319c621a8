//! The planner's answers checked against things it does not compute itself: the timeline against
//! hold-by-hold replay of its own postures, its KKT claims against its settings, determinism, the
//! solver's precision, and monotone families (a heavier load can never be planned to tire less;
//! a shelf moved in small steps does not flip the verdict). No total is copied from a run.

use crate::common::held;
use posture_opt::fatigue::{MaParams, MaState};
use posture_opt::plan::qp::QpPrecision;
use posture_opt::plan::search::SearchSettings;
use posture_opt::plan::sqp::SqpSettings;
use posture_opt::plan::{Plan, PlanOptions, Task, plan_task_with};
use std::path::Path;

fn task_from(dir: &Path, name: &str, yaml: &str) -> Task {
    let path = dir.join(format!("{name}.yaml"));
    std::fs::write(&path, yaml).unwrap();
    Task::from_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// One phase (the right hand holds `load_kg` at `target`) and a rest, `cycles` times.
fn one_phase(load_kg: f64, target: [f64; 3], hold_s: f64, rest_s: f64, cycles: u32) -> String {
    format!(
        "name: hold\nworker: {{sex: female, stature_m: 1.62, mass_kg: 60.0}}\nworkstation:\n  obstacles:\n    - {{name: floor, plane: {{normal: [0, 0, 1]}}, position_m: [0, 0, 0]}}\nphases:\n  - {{name: hold, target_m: [{}, {}, {}], load_kg: {load_kg}, duration_s: {hold_s}}}\nrest_s: {rest_s}\ncycles: {cycles}\n",
        target[0], target[1], target[2]
    )
}

/// Replays the plan's steps hold by hold (each step's posture loads, each half-joint's k and
/// recovery as reported) and compares every step's capacity and U.
fn assert_timeline_is_the_replay(plan: &Plan, what: &str) {
    let params: Vec<MaParams> = plan
        .half_joints
        .iter()
        .map(|h| MaParams::with_recovery(h.k_per_min, h.recovery).unwrap())
        .collect();
    let mut state = vec![MaState::FRESH; params.len()];
    let st = &plan.steps;
    let mut timeline = st.replay();
    for i in 0..st.len() {
        let loads = &plan.postures[st.posture[i]].load;
        let row = timeline.next().expect("one state per step");
        for (h, p) in params.iter().enumerate() {
            p.hold(&mut state[h], loads[h], st.duration_s[i]);
            let (c, u) = (row[h].capacity, row[h].fatigue_u_min);
            assert!(
                (c - state[h].capacity).abs() <= 1e-9 * state[h].capacity.max(1e-12),
                "{what}: step {i}, {}: capacity {c} vs replay {}",
                plan.half_joints[h].id,
                state[h].capacity
            );
            assert!(
                (u - state[h].fatigue_u_min).abs() <= 1e-9 * state[h].fatigue_u_min.max(1e-9),
                "{what}: step {i}, {}: U {u} vs replay {}",
                plan.half_joints[h].id,
                state[h].fatigue_u_min
            );
        }
    }
    assert!(timeline.next().is_none(), "{what}: more states than steps");
    for (h, s) in state.iter().enumerate() {
        assert!(
            (plan.summary.final_capacity[h] - s.capacity).abs() <= 1e-9,
            "{what}: {} final capacity {} vs replay {}",
            plan.half_joints[h].id,
            plan.summary.final_capacity[h],
            s.capacity
        );
    }
    let total: f64 = state.iter().map(|s| s.fatigue_u_min).sum();
    assert!(
        (plan.summary.total_u - total).abs() <= 1e-9 * total,
        "{what}: total U {} vs replay {total}",
        plan.summary.total_u
    );
}

#[test]
fn the_timeline_is_the_hold_by_hold_replay_of_the_plans_postures() {
    let dir = tempfile::tempdir().unwrap();
    let task = task_from(
        dir.path(),
        "hold",
        &one_phase(3.0, [0.40, -0.20, 1.05], 4.0, 2.0, 30),
    );
    let mut totals = Vec::new();
    for adapt in [false, true] {
        let plan = plan_task_with(
            &task,
            PlanOptions {
                adapt,
                baselines: false,
                ..PlanOptions::default()
            },
        )
        .unwrap();
        assert_timeline_is_the_replay(&plan, if adapt { "adaptive" } else { "held" });
        totals.push(plan.summary.total_u);
    }
    // a re-plan is kept only when it lowers the remaining horizon's objective: adapting never
    // ends above holding the first plan (issue 37.4)
    assert!(
        totals[1] <= totals[0] * (1.0 + 1e-9),
        "adaptive {} above held {}",
        totals[1],
        totals[0]
    );
    // and a shipped multi-phase task with a pushing force
    let (_, plan) = crate::common::shipped_plan("bench_assembly");
    assert_timeline_is_the_replay(plan, "bench assembly");
}

/// A phase reported converged met the documented KKT test; every phase reports its residual and
/// iterations; and the converged ones are the rule on a shipped task.
#[test]
fn converged_phases_meet_the_kkt_tolerance() {
    let (_, plan) = crate::common::shipped_plan("bench_assembly");
    let tol = SqpSettings::default().tol_kkt;
    let mut converged = 0;
    for p in &plan.summary.phases {
        assert!(
            p.kkt_residual.is_finite() && p.kkt_residual >= 0.0,
            "{}",
            p.phase
        );
        // a solve that starts at a KKT point takes no step but one QP (its multipliers)
        assert!(p.solve.qp_solves >= 1, "{}", p.phase);
        assert_eq!(p.iterations, p.solve.iterations, "{}", p.phase);
        if p.converged {
            converged += 1;
            assert!(
                p.kkt_residual <= tol,
                "{}: converged with KKT residual {} > {tol}",
                p.phase,
                p.kkt_residual
            );
        }
        assert!(
            p.hand_error_m < 0.01,
            "{}: hand error {}",
            p.phase,
            p.hand_error_m
        );
    }
    assert!(
        converged >= plan.summary.phases.len() - 1,
        "{converged} of {} converged",
        plan.summary.phases.len()
    );
    // coordination passes never raise the objective
    for w in plan.summary.passes.windows(2) {
        assert!(
            w[1] <= w[0] * (1.0 + 1e-9),
            "passes {:?}",
            plan.summary.passes
        );
    }
}

/// A search stage only extends the passes: those without it (`without`) are exactly the first of
/// those with it (`with`), and `with` ends no higher.
fn assert_only_extends(what: &str, with: &[f64], without: &[f64]) {
    assert!(
        with.len() >= without.len() && with[..without.len()] == without[..],
        "{what}: the passes without it {without:?} are not the first of {with:?}"
    );
    assert!(
        with.last().unwrap() <= &(without.last().unwrap() * (1.0 + 1e-12)),
        "{what}: {with:?} ends above {without:?}"
    );
}

/// The pool swap (each group's posture traded for another local optimum the search found, where
/// that lowers the whole objective) only extends the first plan: the passes without it are the
/// first passes with it, it never ends higher, every swapped-in posture still reaches its own
/// phase's target (a pool holds only its group's optima), it brings no new exhaustion and parks
/// no more phases at a joint limit.
///
/// And the same for the cross-seeding and forearm rounds before it, both without the pool swap
/// (shelf_high: a phase that ends unconverged made the passes after its forearm round rise, and
/// the round is undone).
#[test]
fn the_pool_swap_and_cross_seeding_only_lower_the_first_plans_objective() {
    for name in ["shelf", "bench_assembly", "shelf_high"] {
        let (task, plan) = crate::common::shipped_plan(name);
        let with = &plan.summary;
        let no_swap = PlanOptions {
            pool_swap: false,
            ..held(false)
        };
        let without = plan_task_with(task, no_swap).unwrap().summary;
        assert_only_extends(&format!("{name}, the swap"), &with.passes, &without.passes);
        let without_round = plan_task_with(
            task,
            PlanOptions {
                cross_seeding: false,
                ..no_swap
            },
        )
        .unwrap()
        .summary;
        assert_only_extends(
            &format!("{name}, the round"),
            &without.passes,
            &without_round.passes,
        );
        for p in &with.phases {
            assert!(
                p.hand_error_m < 0.01,
                "{name} '{}': hand error {} m after the swap",
                p.phase,
                p.hand_error_m
            );
        }
        if without.exhaustion.is_none() {
            assert!(
                with.exhaustion.is_none(),
                "{name}: the swap exhausts: {:?}",
                with.exhaustion
            );
        }
        let [parked_with, parked_without] =
            [with, &without].map(|s| s.phases.iter().filter(|p| !p.at_limits.is_empty()).count());
        assert!(
            parked_with <= parked_without,
            "{name}: the swap parks {parked_with} phases at a limit, against {parked_without}"
        );
    }
}

#[test]
fn planning_is_deterministic() {
    let dir = tempfile::tempdir().unwrap();
    let task = task_from(
        dir.path(),
        "hold",
        &one_phase(2.0, [0.45, -0.25, 1.20], 5.0, 3.0, 20),
    );
    let a = plan_task_with(&task, held(false)).unwrap();
    let b = plan_task_with(&task, held(false)).unwrap();
    assert_eq!(a.summary.total_u.to_bits(), b.summary.total_u.to_bits());
    assert_eq!(a.summary.phases[0].q_rad, b.summary.phases[0].q_rad);
}

/// The multi-start's local solves run in parallel; each is a function of its problem and start
/// alone, so the whole plan (postures, timeline, baselines, search records, counts of QPs) is the
/// same document on one thread as on three, the same on a second run too.
#[test]
fn a_plan_does_not_depend_on_the_number_of_threads() {
    let dir = tempfile::tempdir().unwrap();
    let task = task_from(
        dir.path(),
        "two",
        "name: two\nworker: {sex: male, stature_m: 1.755, mass_kg: 78.0}\nphases:\n  - {name: pick, target_m: [0.45, -0.30, 0.80], load_kg: 3, duration_s: 4}\n  - {name: place, target_m: [0.40, 0.25, 1.30], load_kg: 3, duration_s: 4}\nrest_s: 4\ncycles: 30\n",
    );
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let plan = pool.install(|| plan_task_with(&task, PlanOptions::default()).unwrap());
        serde_json::to_string(&plan).unwrap()
    };
    let one = on(1);
    assert!(one == on(3), "the plan on three threads differs from one");
    assert!(one == on(1), "a second run on one thread differs");
}

/// Settings that only change the QP solver's precision must not change the plan's objective by
/// more than 0.005 (its fatigue term is ln of the total: 0.5 %), its total fatigue by more than
/// 0.5 % (the planner issue's bound),
/// nor flip the exhaustion or the shift verdict: on every shipped task (the default plan, held).
/// And no baseline the plan reports reaches a lower objective than the plan (issue 37.5); and the
/// seeds screened in reverse order, or the first phase's work moved 1 mm forward, move the
/// total by at most 0.5 % and flip no verdict (37.3).
#[test]
fn the_solvers_precision_does_not_decide_the_plan() {
    let names = [
        "shelf",
        "shelf_lowered",
        "shelf_high",
        "shelf_heavy",
        "shelf_two_hands",
        "bench_assembly",
        "overhead_drilling",
        "pallet",
        "pallet_raised",
        "side_transfer",
        "bench_seated",
    ];
    // every task is checked and every miss reported (a panic would hide the tasks after it)
    let bad: Vec<String> = std::thread::scope(|s| {
        let handles: Vec<_> = names
            .chunks(6)
            .map(|chunk| {
                s.spawn(move || {
                    chunk
                        .iter()
                        .flat_map(|n| solver_precision_does_not_decide(n))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    assert!(bad.is_empty(), "\n  {}", bad.join("\n  "));
}

/// Where a variation moves a plan's total beyond the 0.5 %, measured and held as a
/// bound (task, variation, relative change): docs/results.md, "The QP's precision and the
/// numerical path".
const KNOWN_MISSES: &[(&str, &str, f64)] = &[
    // measured 2026-12-07 (session 15, a free hand hangs): the placed-feet plan's 'carry' faces
    // forward (257.16 min) or, with the first target 1 mm forward, half-turned toward the bin
    // (252.00 min, 2.0e-2 lower): two stances two steps apart whose fatigue differs by 2 %, which
    // the search finds by its path; no verdict flips
    ("side_transfer", "with the target 1 mm forward", 0.025),
];

/// What moves a task's plan beyond the bounds, one line per miss.
fn solver_precision_does_not_decide(name: &str) -> Vec<String> {
    let mut bad = Vec::new();
    let mut check = |ok: bool, what: String| {
        if !ok {
            bad.push(what);
        }
    };
    // the default plan (the QP's tolerance 1e-9), with its baselines, shared with other tests
    let (task, a) = crate::common::shipped_plan(name);
    assert_eq!(SqpSettings::default().precision.tol_gap, 1e-9);
    let b = plan_task_with(
        task,
        PlanOptions {
            sqp: SqpSettings {
                precision: QpPrecision {
                    tol_gap: 1e-8,
                    tol_feas: 1e-8,
                },
                ..SqpSettings::default()
            },
            ..held(false)
        },
    )
    .unwrap();
    let (ja, jb) = (
        *a.summary.passes.last().unwrap(),
        *b.summary.passes.last().unwrap(),
    );
    // no baseline beats the plan on the plan's own objective (their postures are seeds); one
    // that exhausts a muscle group breaks the plan's capacity constraint, so its objective is not
    // a feasible plan's (overhead_drilling's three baselines exhaust the right shoulder flexors
    // within 3 min)
    check(
        a.summary.baselines.len() == 3,
        format!("{name}: {} baselines", a.summary.baselines.len()),
    );
    for base in a
        .summary
        .baselines
        .iter()
        .filter(|b| b.exhaustion.is_none())
    {
        check(
            base.objective >= ja - 1e-9 * ja.abs().max(1.0),
            format!(
                "{name}: baseline {} reaches the objective {} below the plan's {ja}",
                base.name, base.objective
            ),
        );
    }
    // the objective's fatigue term is ln of the total: 0.005 is 0.5 % of it, the bound
    let d_j = (ja - jb).abs();
    check(
        d_j <= 5e-3,
        format!("{name}: objective {ja} vs {jb} at the QP's two precisions (difference {d_j:.1e})"),
    );
    let verdict = |p: &Plan| posture_opt::assess::assess(task, p, 0.7).verdict.status;
    let verdict_a = verdict(a);
    // the total within the bound, and the same shift verdict
    let compare = |check: &mut dyn FnMut(bool, String), what: &str, other: &Plan| {
        let rel = (a.summary.total_u - other.summary.total_u).abs() / a.summary.total_u;
        eprintln!(
            "{name}: {what} {:.3} vs {:.3} min ({rel:.1e})",
            other.summary.total_u, a.summary.total_u
        );
        let bound = KNOWN_MISSES
            .iter()
            .find(|(n, w, _)| *n == name && *w == what)
            .map_or(5e-3, |m| m.2);
        check(
            rel <= bound,
            format!(
                "{name}: total U {} {what} vs {} (relative {rel:.1e}, bound {bound:.1e})",
                other.summary.total_u, a.summary.total_u
            ),
        );
        check(
            verdict(other) == verdict_a,
            format!("{name}: the shift verdict flips {what}"),
        );
    };
    compare(&mut check, "at the QP's tolerance 1e-8", &b);
    check(
        a.summary.exhaustion.is_some() == b.summary.exhaustion.is_some(),
        format!("{name}: exhaustion flips with the QP's precision"),
    );
    // the seeds screened in reverse order: the same bounds on the total and the verdict
    let c = plan_task_with(
        task,
        PlanOptions {
            search: SearchSettings {
                reversed: true,
                ..SearchSettings::default()
            },
            ..held(false)
        },
    )
    .unwrap();
    // the order did change: a phase searched from several starts names its best by position
    check(
        a.summary
            .phases
            .iter()
            .zip(&c.summary.phases)
            .any(|(x, y)| x.search.seeds > 1 && x.search.best_seed != y.search.best_seed),
        format!("{name}: the reversed search reports the same seed positions"),
    );
    compare(&mut check, "with the seeds reversed", &c);
    // the first phase's work 1 mm further forward (every phase working at that point moves with
    // it, its held object too, so that the phases sharing a posture keep sharing it; the gaze
    // follows the targets)
    let mut moved = task.clone();
    let first = task.phases[0].targets_m;
    for ph in moved.phases.iter_mut().filter(|p| p.targets_m == first) {
        for t in ph.targets_m.iter_mut().flatten() {
            t.x += 0.001;
        }
        if let Some(o) = ph.object.as_mut() {
            o.center_m[0] += 0.001;
        }
    }
    let m = plan_task_with(&moved, held(false)).unwrap();
    compare(&mut check, "with the target 1 mm forward", &m);
    bad
}

/// Any posture that holds a heavier load also holds a lighter one with less fatigue in every
/// group, so the optimum can only rise with the load: a planner caught in a worse local minimum
/// for a lighter load breaks this.
#[test]
fn a_heavier_load_is_never_planned_to_tire_less() {
    let dir = tempfile::tempdir().unwrap();
    let mut last = 0.0;
    for (i, kg) in [0.5, 1.5, 2.5, 3.5, 4.5].into_iter().enumerate() {
        let task = task_from(
            dir.path(),
            &format!("load{i}"),
            &one_phase(kg, [0.45, -0.25, 1.10], 5.0, 3.0, 40),
        );
        let plan = plan_task_with(
            &task,
            PlanOptions {
                fatigue_only: true,
                ..held(false)
            },
        )
        .unwrap();
        let u = plan.summary.total_u;
        assert!(
            u >= last * (1.0 - 1e-3),
            "{kg} kg: U {u} below the lighter load's {last}"
        );
        last = u;
    }
}

/// A shelf moved up in 5 cm steps: the totals change smoothly (no jump bigger than a few times
/// the neighbours' steps) and the verdict does not flip back and forth.
#[test]
fn a_target_moved_in_small_steps_gives_smooth_totals() {
    let dir = tempfile::tempdir().unwrap();
    let heights = [0.95, 1.00, 1.05, 1.10, 1.15, 1.20, 1.25];
    let mut totals = Vec::new();
    let mut verdicts = Vec::new();
    for (i, z) in heights.iter().enumerate() {
        let task = task_from(
            dir.path(),
            &format!("h{i}"),
            &one_phase(3.0, [0.45, -0.25, *z], 5.0, 3.0, 40),
        );
        let plan = plan_task_with(&task, held(false)).unwrap();
        totals.push(plan.summary.total_u);
        verdicts.push(plan.summary.exhaustion.is_some());
    }
    let flips = verdicts.windows(2).filter(|w| w[0] != w[1]).count();
    assert!(flips <= 1, "verdict flips {flips} times: {verdicts:?}");
    let steps: Vec<f64> = totals.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    let mean = steps.iter().sum::<f64>() / steps.len() as f64;
    let largest = steps.iter().cloned().fold(0.0, f64::max);
    let typical = totals.iter().sum::<f64>() / totals.len() as f64;
    assert!(
        largest <= 3.0 * mean + 0.02 * typical,
        "totals {totals:?}: a jump of {largest} against a mean step of {mean}"
    );
}

/// Whole shifts of 12 h and 24 h: the plan's timeline is still the exact replay of its postures,
/// every number is finite, and the plan is never worse than the fatigue-unaware baseline (the
/// same optimiser blind to fatigue), nor exhausted where that baseline is not.
#[test]
fn twelve_and_twenty_four_hour_shifts_plan_exactly() {
    let dir = tempfile::tempdir().unwrap();
    for hours in [12u32, 24] {
        let cycles = hours * 3600 / 20;
        let task = task_from(
            dir.path(),
            &format!("shift{hours}"),
            &one_phase(2.0, [0.40, -0.20, 1.05], 8.0, 12.0, cycles),
        );
        assert!((task.duration_s() - f64::from(hours) * 3600.0).abs() < 1e-6);
        let plan = plan_task_with(&task, held(true)).unwrap();
        assert_timeline_is_the_replay(&plan, &format!("{hours} h"));
        assert!(plan.summary.total_u.is_finite());
        let blind = plan
            .summary
            .baselines
            .iter()
            .find(|b| b.name == "fatigue_unaware")
            .expect("the fatigue-unaware baseline");
        if blind.exhaustion.is_none() {
            assert!(
                plan.summary.exhaustion.is_none(),
                "{hours} h: the plan exhausts where the fatigue-blind one does not"
            );
            assert!(
                plan.summary.total_u <= blind.total_u * (1.0 + 1e-6),
                "{hours} h: U {} above the fatigue-blind baseline's {}",
                plan.summary.total_u,
                blind.total_u
            );
        }
    }
}

/// The time to exhaustion at this pace (`assess::meaning`) against a cycle-by-cycle replay of the
/// plan's postures written here: every step held in turn with `MaParams::hold` (checked against
/// numerical integration in `fatigue_model`), a group gives out in a step when its capacity at the
/// step's start or end is below the step's load (capacity is monotone within a step), the moment
/// found by bisection on the held time; "never" when every cycle-start capacity moves by less than
/// 1e-12 per cycle. A family of paces from a few cycles to thousands, and one that lasts.
#[test]
fn time_to_exhaustion_is_the_cycle_by_cycle_replay() {
    use posture_opt::assess::meaning::meaning;
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (9.0, 60.0, 2.0),
        (6.0, 40.0, 2.0),
        (4.0, 20.0, 4.0),
        (3.0, 12.0, 6.0),
        (2.5, 8.0, 8.0),
        (1.0, 4.0, 20.0),
        (0.5, 2.0, 30.0),
        (0.0, 2.0, 60.0),
    ];
    let (mut later_cycles, mut lasting, mut in_plan) = (0, 0, 0);
    for (load_kg, hold_s, rest_s) in cases {
        let what = format!("{load_kg} kg, {hold_s} s on, {rest_s} s off");
        let task = task_from(
            dir.path(),
            "pace",
            &one_phase(load_kg, [0.45, -0.2, 1.35], hold_s, rest_s, 10),
        );
        let plan = plan_task_with(&task, held(false)).unwrap();
        let m = meaning(&task, &plan);
        let params: Vec<MaParams> = plan
            .half_joints
            .iter()
            .map(|h| MaParams::with_recovery(h.k_per_min, h.recovery).unwrap())
            .collect();
        // the held posture of the phase and of the rest (one each without adaptation)
        let load_of = |phase: &str| {
            plan.postures
                .iter()
                .rev()
                .find(|p| p.phase == phase)
                .unwrap()
                .load
                .clone()
        };
        let steps = [(load_of("hold"), hold_s), (load_of("rest"), rest_s)];
        let nh = params.len();
        let mut state = vec![MaState::FRESH; nh];
        let (mut t_s, mut replayed) = (0.0, None);
        let mut settled = false;
        'cycles: for _ in 0..200_000 {
            let before: Vec<f64> = state.iter().map(|s| s.capacity).collect();
            for (loads, d) in &steps {
                // the earliest group to give out in this step, and when
                let mut first: Option<(f64, usize)> = None;
                for h in 0..nh {
                    let f = loads[h];
                    let mut end = state[h];
                    params[h].hold(&mut end, f, *d);
                    if f <= 0.0 || (state[h].capacity >= f && end.capacity >= f) {
                        continue;
                    }
                    let te = if state[h].capacity < f {
                        0.0
                    } else {
                        let (mut lo, mut hi) = (0.0, *d);
                        for _ in 0..200 {
                            let mid = 0.5 * (lo + hi);
                            let mut s = state[h];
                            params[h].hold(&mut s, f, mid);
                            if s.capacity < f { hi = mid } else { lo = mid }
                        }
                        hi
                    };
                    if first.is_none_or(|(t0, _)| te < t0) {
                        first = Some((te, h));
                    }
                }
                if let Some((te, h)) = first {
                    replayed = Some((t_s + te, h));
                    break 'cycles;
                }
                for h in 0..nh {
                    params[h].hold(&mut state[h], loads[h], *d);
                }
                t_s += d;
            }
            if state
                .iter()
                .zip(&before)
                .all(|(s, c)| (s.capacity - c).abs() < 1e-12)
            {
                settled = true;
                break;
            }
        }
        match replayed {
            Some((te_s, h)) => {
                let minutes = m.minutes_to_exhaustion.unwrap_or_else(|| {
                    panic!(
                        "{what}: the replay gives out at {te_s} s, meaning says {}",
                        m.words
                    )
                });
                assert!(
                    (minutes * 60.0 - te_s).abs() <= 1e-6 * te_s.max(1.0),
                    "{what}: {minutes} min vs replay {} min",
                    te_s / 60.0
                );
                assert_eq!(m.exhaustion_verdict, "gives_out", "{what}");
                // a plan that itself gives out within the task is never "can be done"
                if plan.summary.exhaustion.is_some() {
                    in_plan += 1;
                    assert!(
                        !m.words.contains("can be done") && m.words.contains("give out after"),
                        "{what}: the plan gives out, yet: {}",
                        m.words
                    );
                }
                assert_eq!(
                    m.first_to_give_out.as_deref(),
                    Some(plan.half_joints[h].group.as_str()),
                    "{what}"
                );
                if te_s > 3.0 * (hold_s + rest_s) {
                    later_cycles += 1;
                }
            }
            None => {
                assert!(settled, "{what}: the replay neither gave out nor settled");
                assert_eq!(m.exhaustion_verdict, "never", "{what}: {}", m.words);
                assert!(m.minutes_to_exhaustion.is_none(), "{what}");
                lasting += 1;
            }
        }
    }
    assert!(
        later_cycles >= 2 && lasting >= 1 && in_plan >= 1,
        "family too narrow: {later_cycles} gave out after 3 cycles, {lasting} lasted, {in_plan} within the plan"
    );
}

/// Standing still is sustainable: in the rest posture (standing, arms hanging, no load) every
/// muscle group's load is below the load it can hold indefinitely (its recovery limit), for both
/// sexes and stances from feet under the hips to wider than the shoulders, default included. A
/// wide stance puts the legs in an A-frame; each foot's centre of pressure moves on its sole to
/// carry it, as a standing person's does, instead of loading the weak ankle evertors.
#[test]
fn standing_at_rest_is_sustainable_in_any_stance() {
    let dir = tempfile::tempdir().unwrap();
    for sex in ["female", "male"] {
        for stance in ["", "stance: {width_m: 0.18}\n", "stance: {width_m: 0.42}\n"] {
            let yaml = one_phase(0.0, [0.45, -0.2, 1.2], 2.0, 60.0, 2)
                .replace("sex: female", &format!("sex: {sex}"))
                .replace("phases:", &format!("{stance}phases:"));
            let task = task_from(dir.path(), "rest", &yaml);
            let plan = plan_task_with(&task, held(false)).unwrap();
            let rest = plan.postures.iter().find(|p| p.phase == "rest").unwrap();
            for (h, f) in plan.half_joints.iter().zip(&rest.load) {
                assert!(
                    *f < h.sustainable_load,
                    "{sex} {stance:?}: {} at {:.2} %MVC at rest, above its limit {:.2} %MVC",
                    h.id,
                    100.0 * f,
                    100.0 * h.sustainable_load
                );
            }
        }
    }
}

/// `objective.zone_weight` prices the directions RULA and REBA score beyond their zones (trunk
/// twist and side bend beyond 10°, leaning back beyond 5°, the wrist bent beyond 15° or deviated
/// beyond 10°): at 300 no phase of the shelf job leaves a zone by more than 6° (the zones are
/// priced, not bounds: a phase leaves one where that buys enough fatigue; measured 2026-12-04,
/// 5.2° of trunk twist on 'place low board' is the largest). With
/// `--fatigue-only` the zones are off with the rest of the discomfort term: the same plan at any
/// zone_weight (checked on a one-phase hold, a quicker plan than the shelf's: the switch does
/// not depend on the task).
#[test]
fn zone_weight_keeps_the_shelf_postures_in_the_assessment_zones() {
    use posture_opt::plan::objective::assessment_zone_deg;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let base = Task::from_file(root.join("tasks/shelf.yaml")).unwrap();
    assert_eq!(base.objective.zone_weight, 0.0, "zones are off by default");
    let mut zoned = base.clone();
    zoned.objective.zone_weight = 300.0;
    let names = zoned.joint_names();
    // the head free: looking at the low board, 0.45 m below the eyes and 22° to the right, takes
    // a neck turn of about 16° within the standards' zones, beyond the 10° RULA and REBA score
    let plan = plan_task_with(
        &zoned,
        PlanOptions {
            gaze: false,
            ..held(false)
        },
    )
    .unwrap();
    for ph in &plan.summary.phases {
        for (k, name) in names.iter().enumerate() {
            let Some((below, above)) = assessment_zone_deg(name) else {
                continue;
            };
            let d_deg = ph.q_rad[k].to_degrees();
            let excess = (d_deg - above).max(-below - d_deg).max(0.0);
            assert!(
                excess <= 6.0,
                "{}: {name} at {d_deg:.1}°, {excess:.1}° beyond its zone ({below}°, {above}°)",
                ph.phase
            );
        }
    }
    let fatigue_only = PlanOptions {
        fatigue_only: true,
        ..held(false)
    };
    let dir = tempfile::tempdir().unwrap();
    let base = task_from(
        dir.path(),
        "hold",
        &one_phase(2.0, [0.40, -0.35, 1.30], 5.0, 3.0, 20),
    );
    let mut zoned = base.clone();
    zoned.objective.zone_weight = 300.0;
    let (a, b) = (
        plan_task_with(&base, fatigue_only).unwrap(),
        plan_task_with(&zoned, fatigue_only).unwrap(),
    );
    assert_eq!(a.summary.total_u, b.summary.total_u);
    assert_eq!(a.summary.phases[0].q_rad, b.summary.phases[0].q_rad);
    // while with the discomfort term on the weight does move this plan (the switch is what
    // keeps the fatigue-only plans equal)
    let (c, d) = (
        plan_task_with(&base, held(false)).unwrap(),
        plan_task_with(&zoned, held(false)).unwrap(),
    );
    assert_ne!(c.summary.phases[0].q_rad, d.summary.phases[0].q_rad);
}

/// Adaptation never loses: a re-plan replaces the held postures only when it lowers the
/// predicted fatigue over the remaining horizon (and the objective there), so by induction over
/// the re-plans the adaptive plan's total U is never above the held plan's. Checked on the
/// shipped tasks whose re-plans used to lose (shelf and bench_assembly, each re-planned several
/// times), without baselines.
#[test]
fn adaptive_plan_never_ends_above_the_held_plan() {
    for name in ["shelf", "bench_assembly"] {
        let task =
            Task::from_file(format!("{}/tasks/{name}.yaml", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let adaptive = plan_task_with(
            &task,
            PlanOptions {
                baselines: false,
                ..PlanOptions::default()
            },
        )
        .unwrap();
        let (_, held) = crate::common::shipped_plan(name);
        let (a, h) = (adaptive.summary.total_u, held.summary.total_u);
        assert!(
            a <= h * (1.0 + 1e-9),
            "{name}: adaptive {a} min above held {h} min"
        );
    }
}

/// Starting postures for the search (another worker's plan, in `sweep`'s retry) are checked:
/// one posture of the model's coordinates per phase, finite; a plan seeded with a plan's own
/// postures reaches every target.
#[test]
fn a_hinted_plan_checks_its_hint_and_reaches_the_targets() {
    use posture_opt::plan::{PlanError, Planner};
    let (task, plan) = crate::common::shipped_plan("bench_assembly");
    let hint: Vec<Vec<f64>> = plan
        .summary
        .phases
        .iter()
        .map(|p| p.q_rad.clone())
        .collect();
    let mut planner = Planner::new(task, PlanOptions::default().sqp).unwrap();
    assert!(hint.len() > 1);
    assert!(matches!(
        planner.hint(&hint[1..]),
        Err(PlanError::Hint { .. })
    ));
    let mut short = hint.clone();
    short[0].pop();
    assert!(matches!(planner.hint(&short), Err(PlanError::Hint { .. })));
    let mut nan = hint.clone();
    nan[0][0] = f64::NAN;
    assert!(matches!(planner.hint(&nan), Err(PlanError::Hint { .. })));
    planner.hint(&hint).unwrap();
    let seeded = planner.plan(held(false)).unwrap();
    for p in &seeded.summary.phases {
        assert!(p.reachable, "{}", p.phase);
    }
}
