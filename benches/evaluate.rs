//! Recorded work: per-sample cost of the evaluator (statics standing on both feet, every
//! half-joint's exact fatigue update) for the generated whole-body worker.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Vector3;
use posture_opt::body::Worker;
use posture_opt::record::{Evaluator, Sample, default_setup};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let task = default_setup(Worker::MALE_50, None).expect("default set-up");
    let mut ev = Evaluator::new(&task);
    let mut s = Sample::zeros(task.model.nq());
    for (name, v) in [
        ("lumbar_flexion", 0.3),
        ("r_shoulder_flexion", 1.1),
        ("r_elbow_flexion", 0.8),
    ] {
        if let Ok(k) = task.model.q_index(name) {
            s.q_rad[k] = v;
        }
    }
    s.hand_force_n[0] = Vector3::new(0.0, 0.0, -39.24);
    let mut g = c.benchmark_group("evaluate");
    g.throughput(Throughput::Elements(1));
    g.bench_function("sample_statics_and_fatigue", |b| {
        b.iter(|| {
            s.t_s += 0.01;
            black_box(ev.push(black_box(&s)).expect("valid sample"))
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
