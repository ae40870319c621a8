//! Statics of the generated whole-body worker: forward kinematics, hand Jacobians and holding
//! torques with a load in each hand; the same standing on both feet (the floor's reaction split
//! between the feet and the internal wrench settled); and the analytic torque derivative.
//! Compare with Pinocchio on the same URDF in the same run (README, "Speed").

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Matrix3xX;
use nalgebra::Vector3;
use posture_opt::body::stance::{Foot, Stance, foot_loads, ground_reaction, settle_internal_force};
use posture_opt::body::worker::{LEFT_FOOT_LINK, PELVIS_JOINTS, RIGHT_FOOT_LINK};
use posture_opt::body::{
    BodyModel, GRAVITY_M_S2, PointLoad, StaticsData, apply_loads, forward_kinematics,
    holding_torque_derivative, holding_torques, mass_moments,
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
    // standing: feet where q = 0 puts them, both on the floor
    let feet = [LEFT_FOOT_LINK, RIGHT_FOOT_LINK].map(|l| Foot::from_link(&m, l).expect("foot"));
    forward_kinematics(&m, &mut d, &vec![0.0; m.nq()]);
    let sole = |i: usize| d.link_point(&m, feet[i].link, &feet[i].sole_center_in_link_m);
    let (left, right) = (sole(0), sole(1));
    let stance = Stance::new(feet, (left - right).norm(), left.x, 0.0);
    let actuated: Vec<bool> = (0..m.nq())
        .map(|k| !PELVIS_JOINTS.contains(&m.q_joint(k).name.as_str()))
        .collect();
    let mut ds = StaticsData::new(&m, loads.len() + 2);
    let mut scratch = Matrix3xX::zeros(m.nq());
    let mut all = Vec::with_capacity(loads.len() + 2);
    c.bench_function("statics/worker_standing_two_hands_torques", |b| {
        b.iter(|| {
            forward_kinematics(&m, &mut ds, black_box(&q));
            mass_moments(&m, &mut ds);
            let mut r = ground_reaction(&m, &ds, &stance, &loads, &GRAVITY_M_S2);
            all.clear();
            all.extend_from_slice(&loads);
            all.extend_from_slice(&foot_loads(&m, &ds, &stance, &r));
            apply_loads(&m, &mut ds, &all, &GRAVITY_M_S2);
            let w = settle_internal_force(&m, &mut ds, &stance, &mut r, &actuated, &mut scratch);
            black_box((ds.tau_nm[0], w.lambda_n))
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
