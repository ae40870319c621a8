//! Body statics against a hand-worked two-link arm, finite differences, and joint-order invariance.

use nalgebra::Vector3;
use posture_opt::body::{
    holding_torque_derivative, holding_torques, BodyModel, StaticsData, GRAVITY_M_S2,
};

fn data_path(name: &str) -> String {
    format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn two_link_arm_by_hand() {
    let m = BodyModel::from_urdf_file(data_path("two_link.urdf")).unwrap();
    let mut d = StaticsData::new(&m);
    let (q1, q2) = (0.3f64, 0.5f64);
    let load_kg = 4.0;
    let g = 9.81;
    let hand = m.frame_link("tip").unwrap();
    holding_torques(
        &m,
        &mut d,
        &[q1, q2],
        hand,
        &Vector3::new(0.0, 0.0, -load_kg * g),
        &GRAVITY_M_S2,
    );
    let (c1, s1, c12, s12) = (q1.cos(), q1.sin(), (q1 + q2).cos(), (q1 + q2).sin());
    // hand position: shoulder at z = 1, links 0.3 and 0.25 in the x-z plane
    let p = Vector3::new(0.3 * c1 + 0.25 * c12, 0.0, 1.0 + 0.3 * s1 + 0.25 * s12);
    assert!((d.hand_pos_m - p).norm() < 1e-12);
    // gravity: horizontal lever arms times weights; upper 2 kg at 0.15, fore 1.5 kg at 0.1
    let tg1 = g * (2.0 * 0.15 * c1 + 1.5 * (0.3 * c1 + 0.1 * c12));
    let tg2 = g * 1.5 * 0.1 * c12;
    assert!((d.tau_gravity_nm[0] - tg1).abs() < 1e-12);
    assert!((d.tau_gravity_nm[1] - tg2).abs() < 1e-12);
    // 4 kg in the hand
    let tl1 = g * load_kg * (0.3 * c1 + 0.25 * c12);
    let tl2 = g * load_kg * 0.25 * c12;
    assert!((d.tau_load_nm[0] - tl1).abs() < 1e-12);
    assert!((d.tau_load_nm[1] - tl2).abs() < 1e-12);
    assert!((d.tau_nm[0] - tg1 - tl1).abs() < 1e-12);
    // Jacobian columns
    let j1 = Vector3::new(-0.3 * s1 - 0.25 * s12, 0.0, 0.3 * c1 + 0.25 * c12);
    let j2 = Vector3::new(-0.25 * s12, 0.0, 0.25 * c12);
    assert!((d.jacobian.column(0) - j1).norm() < 1e-12);
    assert!((d.jacobian.column(1) - j2).norm() < 1e-12);
    // derivative of τ2 = g(1.5·0.1 + 4·0.25) cos(q1+q2) wrt q1 and q2: −g(0.15 + 1.0) sin(q1+q2)
    holding_torque_derivative(&m, &mut d);
    let dt2 = -g * (0.15 + 1.0) * s12;
    assert!((d.dtau_dq[(1, 0)] - dt2).abs() < 1e-12);
    assert!((d.dtau_dq[(1, 1)] - dt2).abs() < 1e-12);
    let dt1_dq1 = -g * (2.0 * 0.15 * s1 + 1.5 * (0.3 * s1 + 0.1 * s12))
        - g * load_kg * (0.3 * s1 + 0.25 * s12);
    assert!((d.dtau_dq[(0, 0)] - dt1_dq1).abs() < 1e-12);
}

fn fd_check(m: &BodyModel, hand: &str, q: &[f64], force: Vector3<f64>, gravity: Vector3<f64>) {
    let hand = m.frame_link(hand).unwrap();
    let mut d = StaticsData::new(m);
    holding_torques(m, &mut d, q, hand, &force, &gravity);
    holding_torque_derivative(m, &mut d);
    let (jac, dtau) = (d.jacobian.clone(), d.dtau_dq.clone());
    let h = 1e-6;
    for i in 0..m.nq() {
        let mut qp = q.to_vec();
        let mut qm = q.to_vec();
        qp[i] += h;
        qm[i] -= h;
        holding_torques(m, &mut d, &qp, hand, &force, &gravity);
        let (pp, tp) = (d.hand_pos_m, d.tau_nm.clone());
        holding_torques(m, &mut d, &qm, hand, &force, &gravity);
        let (pm, tm) = (d.hand_pos_m, d.tau_nm.clone());
        let jcol = (pp - pm) / (2.0 * h);
        assert!(
            (jac.column(i) - jcol).norm() < 1e-7,
            "J column {i}: {} vs {}",
            jac.column(i),
            jcol
        );
        let dcol = (tp - tm) / (2.0 * h);
        for r in 0..m.nq() {
            assert!(
                (dtau[(r, i)] - dcol[r]).abs() < 1e-6,
                "dtau[{r},{i}] {} vs fd {}",
                dtau[(r, i)],
                dcol[r]
            );
        }
    }
}

#[test]
fn jacobian_and_torque_derivative_match_finite_differences() {
    let m = BodyModel::from_urdf_file(data_path("tree.urdf")).unwrap();
    assert_eq!(m.nq(), 6);
    for q in [
        [0.0; 6],
        [0.3, -0.7, 0.1, 1.1, 0.4, -0.9],
        [-1.2, 0.9, -0.15, -0.4, 2.0, 0.3],
    ] {
        fd_check(&m, "tip", &q, Vector3::new(3.0, -20.0, -45.0), GRAVITY_M_S2);
        fd_check(
            &m,
            "side2",
            &q,
            Vector3::new(0.0, 5.0, -10.0),
            Vector3::new(0.5, -1.0, -9.7),
        );
        fd_check(&m, "l2", &q, Vector3::new(-8.0, 0.0, 2.0), GRAVITY_M_S2);
    }
}

#[test]
fn joint_order_in_the_file_does_not_matter() {
    let text = std::fs::read_to_string(data_path("tree.urdf")).unwrap();
    // reverse the order of the <joint> blocks
    let start = text.find("  <joint").unwrap();
    let end = text.rfind("</joint>").unwrap() + "</joint>".len();
    let blocks: Vec<String> = text[start..end]
        .split("</joint>")
        .filter(|b| b.contains("<joint"))
        .map(|b| format!("{}</joint>", b.trim_start_matches('\n')))
        .collect();
    let reversed = format!(
        "{}{}{}",
        &text[..start],
        blocks.iter().rev().cloned().collect::<Vec<_>>().join("\n"),
        &text[end..]
    );
    let a = BodyModel::from_urdf_str(&text, "a").unwrap();
    let b = BodyModel::from_urdf_str(&reversed, "b").unwrap();
    let names = |m: &BodyModel| {
        (0..m.nq())
            .map(|i| m.q_joint(i).name.clone())
            .collect::<Vec<_>>()
    };
    assert_ne!(
        names(&a),
        names(&b),
        "the test must actually reorder the joints"
    );
    let q_named = [
        ("j1", 0.3),
        ("j2", -0.7),
        ("j3", 0.1),
        ("j4", 1.1),
        ("js", 0.4),
        ("js2", -0.9),
    ];
    let torques = |m: &BodyModel| {
        let mut q = vec![0.0; m.nq()];
        for (n, v) in q_named {
            q[m.q_index(n).unwrap()] = v;
        }
        let mut d = StaticsData::new(m);
        holding_torques(
            m,
            &mut d,
            &q,
            m.frame_link("tip").unwrap(),
            &Vector3::new(1.0, 2.0, -30.0),
            &GRAVITY_M_S2,
        );
        q_named
            .iter()
            .map(|(n, _)| d.tau_nm[m.q_index(n).unwrap()])
            .collect::<Vec<_>>()
    };
    let (ta, tb) = (torques(&a), torques(&b));
    for (x, y) in ta.iter().zip(&tb) {
        assert!((x - y).abs() < 1e-12);
    }
}
