//! Half-joint fatigue updates per second (Ma et al. exact update).

use criterion::{Criterion, Throughput, black_box, criterion_group, criterion_main};
use posture_opt::fatigue::{MaParams, MaState, hold_all};

fn bench(c: &mut Criterion) {
    // 16 half-joints (the default worker's 8 joints × 2 directions), mixed loads, 1 s steps.
    let n = 16;
    let loads: Vec<f64> = (0..n)
        .map(|i| {
            if i % 2 == 0 {
                0.05 * (i as f64 / 2.0 + 1.0)
            } else {
                0.0
            }
        })
        .collect();
    let mut g = c.benchmark_group("fatigue_update");
    g.throughput(Throughput::Elements(n as u64));
    for (name, r) in [("paper_no_recovery", 0.0), ("with_recovery", 0.3)] {
        let params = vec![MaParams::new(1.0, r).unwrap(); n];
        let mut states = vec![MaState::FRESH; n];
        g.bench_function(name, |b| {
            b.iter(|| {
                hold_all(&params, &mut states, black_box(&loads), black_box(1e-3));
                // keep the states from collapsing to the floor over many iterations
                if states[0].capacity < 0.5 {
                    states.fill(MaState::FRESH);
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
