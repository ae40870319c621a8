//! Statics of the generated whole-body worker: forward kinematics, hand Jacobians and holding
//! torques with a load in each hand, and the analytic torque derivative. Compare with Pinocchio
//! on the same URDF in the same run (see docs/body.md, "Speed").

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Vector3;
use posture_opt::body::{
    BodyModel, GRAVITY_M_S2, PointLoad, StaticsData, holding_torque_derivative, holding_torques,
};
use std::hint::black_box;

fn setup() -> (BodyModel, Vec<f64>, Vec<PointLoad>) {
    let m = BodyModel::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf"))
        .expect("the shipped worker loads");
    let mut q = vec![0.0; m.nq()];
    for (name, v) in [
        ("lumbar_flexion", 0.3),
        ("r_shoulder_flexion", 1.1),
        ("r_elbow_flexion", 0.8),
        ("l_shoulder_flexion", 0.9),
        ("l_elbow_flexion", 0.6),
    ] {
        q[m.q_index(name).expect("worker joint")] = v;
    }
    let f = Vector3::new(0.0, 0.0, -49.05);
    let loads = ["r_hand_grip", "l_hand_grip"]
        .iter()
        .map(|h| PointLoad::force_at(m.frame_link(h).expect("worker hand"), f))
        .collect();
    (m, q, loads)
}

fn bench(c: &mut Criterion) {
    let (m, q, loads) = setup();
    let mut d = StaticsData::new(&m, loads.len());
    c.bench_function("statics/worker_two_hands_torques", |b| {
        b.iter(|| {
            holding_torques(&m, &mut d, black_box(&q), &loads, &GRAVITY_M_S2);
            black_box(d.tau_nm[0])
        })
    });
    c.bench_function("statics/worker_torque_derivative", |b| {
        b.iter(|| {
            holding_torque_derivative(&m, &mut d);
            black_box(d.dtau_dq[(0, 0)])
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
