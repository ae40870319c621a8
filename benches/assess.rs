//! Assessment speed: RULA of one posture, the work/rest search of a one-hour plan, the HTML
//! report, and a population sweep (6 workers, rayon over the machine's cores).

use criterion::{criterion_group, criterion_main, Criterion};
use posture_opt::body::StaticsData;
use posture_opt::plan::plan_with_baseline;
use posture_opt::report::html;
use posture_opt::rest::rest_advice;
use posture_opt::rula::{score, RulaActivity, RulaPosture};
use posture_opt::sweep::{standard_population, sweep};
use posture_opt::task::{Task, TaskFile};

fn bench(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/shelf.yaml");
    let task = Task::from_file(path).unwrap();
    let (plan, _) = plan_with_baseline(&task, true).unwrap();
    let mut data = StaticsData::new(&task.model);
    let q = vec![0.3; task.model.nq()];
    let activity = RulaActivity {
        load_kg: 4.0,
        held_s: 3.0,
        repeats_per_min: 6.0,
    };
    c.bench_function("assess/rula_posture_and_score", |b| {
        b.iter(|| {
            let p = RulaPosture::from_worker(&task.model, &mut data, &q).unwrap();
            score(&p, &activity)
        })
    });
    let mut g = c.benchmark_group("assess");
    g.sample_size(10);
    g.bench_function("rest_advice_shelf_1h", |b| {
        b.iter(|| rest_advice(&task, &plan, 0.7))
    });
    let rest = rest_advice(&task, &plan, 0.7);
    g.bench_function("html_report_shelf", |b| {
        b.iter(|| {
            html::plan_report(&html::Layout {
                file: "tasks/shelf.yaml",
                task: &task,
                plan: &plan,
                rest: &rest,
            })
            .unwrap()
        })
    });
    let file: TaskFile = serde_saphyr::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let members = standard_population();
    g.bench_function("sweep_shelf_standard_population", |b| {
        b.iter(|| {
            sweep(
                &file,
                std::path::Path::new(path),
                &members,
                "standard",
                true,
                0.7,
                &|| {},
            )
            .unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
