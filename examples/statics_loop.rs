//! Holding torques of the default worker for many postures (used for profiling).
use nalgebra::Vector3;
use posture_opt::body::{holding_torques, BodyModel, StaticsData, GRAVITY_M_S2};

fn main() {
    let m = BodyModel::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf"))
        .unwrap();
    let mut d = StaticsData::new(&m);
    let hand = m.frame_link("hand_grip").unwrap();
    let f = Vector3::new(0.0, 0.0, -49.05);
    let mut q = [0.3, -0.1, 0.2, 1.1, 0.3, -0.2, 0.8, 0.4, -0.3, 0.1];
    let mut acc = 0.0;
    for i in 0..2_000_000 {
        q[0] = (i % 100) as f64 * 0.01;
        holding_torques(&m, &mut d, &q, hand, &f, &GRAVITY_M_S2);
        acc += d.tau_nm[0];
    }
    println!("sum of lumbar torques: {acc:.3} N·m over 2e6 postures");
}
