//! Statics against golden values from Pinocchio 4.1 (tests/data/pinocchio_golden.py).

use nalgebra::Vector3;
use posture_opt::body::{holding_torques, BodyModel, StaticsData, GRAVITY_M_S2};

#[test]
fn matches_pinocchio() {
    let root = env!("CARGO_MANIFEST_DIR");
    let golden: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(format!("{root}/tests/data/pinocchio_golden.json")).unwrap(),
    )
    .unwrap();
    let cases = golden["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 5);
    for case in cases {
        let m = BodyModel::from_urdf_file(format!("{root}/{}", case["robot"].as_str().unwrap()))
            .unwrap();
        let hand = m.frame_link(case["frame"].as_str().unwrap()).unwrap();
        let f: Vec<f64> = case["force_n"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let joints = case["joints"].as_object().unwrap();
        assert_eq!(joints.len(), m.nq());
        let mut q = vec![0.0; m.nq()];
        for (name, j) in joints {
            q[m.q_index(name).unwrap()] = j["q_rad"].as_f64().unwrap();
        }
        let mut d = StaticsData::new(&m);
        holding_torques(
            &m,
            &mut d,
            &q,
            hand,
            &Vector3::new(f[0], f[1], f[2]),
            &GRAVITY_M_S2,
        );
        let p: Vec<f64> = case["position_m"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!((d.hand_pos_m - Vector3::new(p[0], p[1], p[2])).norm() < 1e-9);
        for (name, j) in joints {
            let i = m.q_index(name).unwrap();
            let g = j["gravity_torque_nm"].as_f64().unwrap();
            let l = j["load_torque_nm"].as_f64().unwrap();
            assert!(
                (d.tau_gravity_nm[i] - g).abs() < 1e-9,
                "{name}: gravity {} vs pinocchio {g}",
                d.tau_gravity_nm[i]
            );
            assert!(
                (d.tau_load_nm[i] - l).abs() < 1e-9,
                "{name}: load {} vs pinocchio {l}",
                d.tau_load_nm[i]
            );
            let jc: Vec<f64> = j["jacobian"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            assert!(
                (d.jacobian.column(i) - Vector3::new(jc[0], jc[1], jc[2])).norm() < 1e-9,
                "{name}: jacobian"
            );
        }
    }
}
