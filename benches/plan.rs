//! Planner speed: one warm-started phase SQP (≈ one QP solve), and whole plans of shelf.yaml.

use criterion::{criterion_group, criterion_main, Criterion};
use posture_opt::plan::{plan_with_baseline, Planner};
use posture_opt::task::Task;

fn bench(c: &mut Criterion) {
    let task = Task::from_file(concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/shelf.yaml")).unwrap();
    let mut g = c.benchmark_group("plan");
    g.sample_size(10);
    g.bench_function("shelf_adaptive_and_baseline", |b| {
        b.iter(|| plan_with_baseline(&task, true).unwrap())
    });
    let mut planner = Planner::new(&task);
    planner.plan(false).unwrap();
    g.bench_function("shelf_adaptive_warm", |b| {
        b.iter(|| planner.plan(true).unwrap())
    });
    g.finish();
    // QP solve time: the plan's QP solves dominate; measure them in place.
    let mut planner = Planner::new(&task);
    let p = planner.plan(true).unwrap();
    c.bench_function("plan/one_qp_solve_estimate", |b| {
        b.iter_custom(|iters| {
            let mut total = std::time::Duration::ZERO;
            for _ in 0..iters {
                let mut pl = Planner::new(&task);
                let t0 = std::time::Instant::now();
                let pp = pl.plan(true).unwrap();
                total += t0.elapsed() / (pp.summary.qp_solves.max(1) as u32);
            }
            total
        })
    });
    eprintln!(
        "shelf adaptive plan: {} re-plans, {} QP solves, {} SQP iterations ({:.1} per re-plan)",
        p.summary.replans,
        p.summary.qp_solves,
        p.summary.sqp_iterations,
        p.summary.sqp_iterations as f64 / p.summary.replans as f64
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
