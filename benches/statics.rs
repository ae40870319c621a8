//! Forward kinematics + hand Jacobian + holding torques for the default worker (10 joints),
//! and the analytic torque derivative.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use nalgebra::Vector3;
use posture_opt::body::{
    holding_torque_derivative, holding_torques, BodyModel, StaticsData, GRAVITY_M_S2,
};

fn bench(c: &mut Criterion) {
    let m = BodyModel::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf"))
        .unwrap();
    let mut d = StaticsData::new(&m);
    let hand = m.frame_link("hand_grip").unwrap();
    let q = [0.3, -0.1, 0.2, 1.1, 0.3, -0.2, 0.8, 0.4, -0.3, 0.1];
    let f = Vector3::new(0.0, 0.0, -49.05);
    c.bench_function("statics/worker_fk_jacobian_torques", |b| {
        b.iter(|| {
            holding_torques(&m, &mut d, black_box(&q), hand, &f, &GRAVITY_M_S2);
            black_box(d.tau_nm[0])
        })
    });
    c.bench_function("statics/worker_fk_only", |b| {
        b.iter(|| {
            posture_opt::body::forward_kinematics(&m, &mut d, black_box(&q));
            black_box(d.body_pos[3][0])
        })
    });
    c.bench_function("statics/sin_cos_10", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for x in black_box(&q) {
                let (a, c) = x.sin_cos();
                s += a + c;
            }
            s
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
