//! Planner speed: whole plans of the shipped tasks, held postures and adaptive.

use criterion::{Criterion, criterion_group, criterion_main};
use posture_opt::plan::{PlanOptions, Task, plan_task_with};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("plan");
    g.sample_size(10);
    for name in ["bench_assembly", "shelf"] {
        let path = format!("{}/tasks/{name}.yaml", env!("CARGO_MANIFEST_DIR"));
        let task = Task::from_file(&path).expect("shipped task");
        for adapt in [false, true] {
            let opts = PlanOptions {
                adapt,
                baselines: false,
                ..PlanOptions::default()
            };
            let label = format!("{name}/{}", if adapt { "adaptive" } else { "held" });
            g.bench_function(label, |b| {
                b.iter(|| plan_task_with(&task, opts).expect("plans"))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
