//! Body statics: the two-link arm worked out by hand, and every Jacobian (point, angular, centre of
//! mass) and the holding-torque derivative against central finite differences of the quantities
//! they differentiate, over random postures and loads, on the worker (`robots/worker.urdf`), the
//! branched tree (`tests/data/tree.urdf`), the two-link arm and `tests/data/geometry.urdf` (fixed
//! joints mid-chain, continuous and prismatic joints, tilted and non-unit axes, rotated origins).
//! Also: the order of joints in the file does not matter, and malformed URDFs are refused by
//! element name.

use nalgebra::{DVector, Matrix3, Matrix3xX, Vector3};
use posture_opt::body::{
    BodyError, BodyModel, GRAVITY_M_S2, JointKind, PointLoad, StaticsData,
    holding_torque_derivative, holding_torques,
};
use proptest::prelude::*;

fn path(rel: &str) -> String {
    format!("{}/{rel}", env!("CARGO_MANIFEST_DIR"))
}

fn load_model(rel: &str) -> BodyModel {
    BodyModel::from_urdf_file(path(rel)).unwrap()
}

// ---------------------------------------------------------------------------------------------
// The two-link arm (tests/data/two_link.urdf) by hand.
//
// Shoulder at (0, 0, 1), both axes −y: a positive angle lifts the link (x toward +z). Upper link
// 0.3 m, 2 kg with its CoM at 0.15 m; forearm 1.5 kg with its CoM at 0.1 m; the tip 0.25 m past
// the elbow. With φ1 = θ1 and φ2 = θ1 + θ2 the angles of the links above the horizontal:
//   elbow E = (0.3 cos φ1, 0, 1 + 0.3 sin φ1), tip T = E + 0.25 (cos φ2, 0, sin φ2);
//   holding torque against gravity (weights times horizontal levers)
//     τ1 = g [2·0.15 cos φ1 + 1.5 (0.3 cos φ1 + 0.1 cos φ2)],  τ2 = g·1.5·0.1 cos φ2;
//   a force F = (Fx, Fy, Fz) at the tip adds −J_Tᵀ F, J_T = [∂T/∂θ1, ∂T/∂θ2]:
//     τ1 += Fx (0.3 sin φ1 + 0.25 sin φ2) − Fz (0.3 cos φ1 + 0.25 cos φ2),
//     τ2 += Fx 0.25 sin φ2 − Fz 0.25 cos φ2;
//   a moment M on the forearm adds −(−ŷ)·M = M_y to both.
// ---------------------------------------------------------------------------------------------

const G: f64 = 9.81;
const M1: f64 = 2.0;
const M2: f64 = 1.5;

struct TwoLink {
    tip: Vector3<f64>,
    com: Vector3<f64>,
    tip_jac: [Vector3<f64>; 2],
    com_jac: [Vector3<f64>; 2],
    tau_gravity: [f64; 2],
    tau: [f64; 2],
    dtau: [[f64; 2]; 2],
}

fn two_link_by_hand(t1: f64, t2: f64, f: Vector3<f64>, my: f64) -> TwoLink {
    let (s1, c1) = t1.sin_cos();
    let (s2, c2) = (t1 + t2).sin_cos();
    let tip = Vector3::new(0.3 * c1 + 0.25 * c2, 0.0, 1.0 + 0.3 * s1 + 0.25 * s2);
    let p1 = Vector3::new(0.15 * c1, 0.0, 1.0 + 0.15 * s1);
    let p2 = Vector3::new(0.3 * c1 + 0.1 * c2, 0.0, 1.0 + 0.3 * s1 + 0.1 * s2);
    let com = (M1 * p1 + M2 * p2) / (M1 + M2);
    let tip_jac = [
        Vector3::new(-0.3 * s1 - 0.25 * s2, 0.0, 0.3 * c1 + 0.25 * c2),
        Vector3::new(-0.25 * s2, 0.0, 0.25 * c2),
    ];
    let com_jac = [
        (M1 * Vector3::new(-0.15 * s1, 0.0, 0.15 * c1)
            + M2 * Vector3::new(-0.3 * s1 - 0.1 * s2, 0.0, 0.3 * c1 + 0.1 * c2))
            / (M1 + M2),
        M2 * Vector3::new(-0.1 * s2, 0.0, 0.1 * c2) / (M1 + M2),
    ];
    let tg = [
        G * (M1 * 0.15 * c1 + M2 * (0.3 * c1 + 0.1 * c2)),
        G * M2 * 0.1 * c2,
    ];
    let tau = [
        tg[0] + f.x * (0.3 * s1 + 0.25 * s2) - f.z * (0.3 * c1 + 0.25 * c2) + my,
        tg[1] + f.x * 0.25 * s2 - f.z * 0.25 * c2 + my,
    ];
    // derivatives of the expressions above
    let d22 = -G * M2 * 0.1 * s2 + f.x * 0.25 * c2 + f.z * 0.25 * s2;
    let d11 = -G * (M1 * 0.15 * s1 + M2 * (0.3 * s1 + 0.1 * s2))
        + f.x * (0.3 * c1 + 0.25 * c2)
        + f.z * (0.3 * s1 + 0.25 * s2);
    TwoLink {
        tip,
        com,
        tip_jac,
        com_jac,
        tau_gravity: tg,
        tau,
        dtau: [[d11, d22], [d22, d22]],
    }
}

#[test]
fn two_link_arm_by_hand_at_a_glance() {
    // arm horizontal, 5 kg at the tip: τ1 = 9.81 (0.3 + 1.5·0.4 + 5·0.55) = 35.7084
    let m = load_model("tests/data/two_link.urdf");
    let mut d = StaticsData::new(&m, 1);
    let tip = m.frame_link("tip").unwrap();
    let w = PointLoad::force_at(tip, Vector3::new(0.0, 0.0, -5.0 * G));
    holding_torques(&m, &mut d, &[0.0, 0.0], &[w], &GRAVITY_M_S2);
    assert!(
        (d.tau_nm[0] - 9.81 * (0.3 + 0.6 + 2.75)).abs() < 1e-12,
        "{}",
        d.tau_nm[0]
    );
    assert!(
        (d.tau_nm[1] - 9.81 * (0.15 + 1.25)).abs() < 1e-12,
        "{}",
        d.tau_nm[1]
    );
    // straight up: no lever, no torque
    holding_torques(
        &m,
        &mut d,
        &[std::f64::consts::FRAC_PI_2, 0.0],
        &[w],
        &GRAVITY_M_S2,
    );
    assert!(d.tau_nm.amax() < 1e-12);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn two_link_arm_matches_its_closed_forms(
        t1 in -3.0f64..3.0, t2 in 0.0f64..2.6,
        fx in -100.0f64..100.0, fy in -100.0f64..100.0, fz in -100.0f64..100.0,
        my in -10.0f64..10.0, mx in -10.0f64..10.0,
    ) {
        let m = load_model("tests/data/two_link.urdf");
        let (tip, fore) = (m.frame_link("tip").unwrap(), m.frame_link("fore").unwrap());
        let f = Vector3::new(fx, fy, fz);
        let loads = [
            PointLoad::force_at(tip, f),
            // a pure moment on the forearm: only its y component (along the axes) matters
            PointLoad { link: fore, point_in_link_m: Vector3::zeros(), force_n: Vector3::zeros(),
                        moment_nm: Vector3::new(mx, my, 0.0) },
        ];
        let mut d = StaticsData::new(&m, 2);
        holding_torques(&m, &mut d, &[t1, t2], &loads, &GRAVITY_M_S2);
        holding_torque_derivative(&m, &mut d);
        let e = two_link_by_hand(t1, t2, f, my);
        prop_assert!((d.link_point(&m, tip, &Vector3::zeros()) - e.tip).norm() < 1e-12);
        prop_assert!((d.com_m - e.com).norm() < 1e-12);
        let mut j = Matrix3xX::zeros(2);
        d.point_jacobian(&m, tip, &e.tip, &mut j);
        for k in 0..2 {
            prop_assert!((j.column(k) - e.tip_jac[k]).norm() < 1e-12);
            prop_assert!((d.com_jacobian.column(k) - e.com_jac[k]).norm() < 1e-12);
            prop_assert!((d.tau_gravity_nm[k] - e.tau_gravity[k]).abs() < 1e-11);
            prop_assert!((d.tau_nm[k] - e.tau[k]).abs() < 1e-10,
                "τ{k}: {} vs hand {}", d.tau_nm[k], e.tau[k]);
            for c in 0..2 {
                prop_assert!((d.dtau_dq[(k, c)] - e.dtau[k][c]).abs() < 1e-10,
                    "∂τ{k}/∂θ{c}: {} vs hand {}", d.dtau_dq[(k, c)], e.dtau[k][c]);
            }
        }
        d.angular_jacobian(&m, fore, &mut j);
        for k in 0..2 {
            prop_assert_eq!(j.column(k).into_owned(), Vector3::new(0.0, -1.0, 0.0));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Finite differences on every robot.
// ---------------------------------------------------------------------------------------------

const ROBOTS: [&str; 4] = [
    "robots/worker.urdf",
    "tests/data/tree.urdf",
    "tests/data/two_link.urdf",
    "tests/data/geometry.urdf",
];

/// A posture from uniform numbers in 0..1: inside the limits, continuous joints over ±π.
fn posture(m: &BodyModel, u: &[f64]) -> Vec<f64> {
    (0..m.nq())
        .map(|k| {
            let j = m.q_joint(k);
            let (lo, hi) = if j.kind == JointKind::Continuous {
                (-std::f64::consts::PI, std::f64::consts::PI)
            } else {
                (j.lower_rad, j.upper_rad)
            };
            lo + u[k % u.len()] * (hi - lo)
        })
        .collect()
}

/// Loads on links picked by `pick`, with points, forces and moments from the numbers in `r`
/// (each in −1..1).
fn loads(m: &BodyModel, pick: &[usize], r: &[f64]) -> Vec<PointLoad> {
    pick.iter()
        .enumerate()
        .map(|(i, &p)| {
            let x = |k: usize| r[(9 * i + k) % r.len()];
            PointLoad {
                link: p % m.links.len(),
                point_in_link_m: 0.2 * Vector3::new(x(0), x(1), x(2)),
                force_n: 80.0 * Vector3::new(x(3), x(4), x(5)),
                moment_nm: 8.0 * Vector3::new(x(6), x(7), x(8)),
            }
        })
        .collect()
}

/// (ω such that dR = [ω]× R) from R(q + h) and R(q − h): the axial part of (R₊ − R₋)/(2h) · Rᵀ.
fn angular_fd(rp: &Matrix3<f64>, rm: &Matrix3<f64>, r: &Matrix3<f64>, h: f64) -> Vector3<f64> {
    let s = (rp - rm) / (2.0 * h) * r.transpose();
    Vector3::new(
        s[(2, 1)] - s[(1, 2)],
        s[(0, 2)] - s[(2, 0)],
        s[(1, 0)] - s[(0, 1)],
    ) / 2.0
}

/// Point, angular and CoM Jacobians and ∂τ/∂q against central differences at `q` under `ld` and
/// gravity `g`. Returns the largest errors relative to the quantities' scales.
fn fd_check(m: &BodyModel, q: &[f64], ld: &[PointLoad], g: &Vector3<f64>) -> Result<(), String> {
    let nq = m.nq();
    let h = 1e-6;
    let mut d = StaticsData::new(m, ld.len());
    holding_torques(m, &mut d, q, ld, g);
    holding_torque_derivative(m, &mut d);
    let dtau = d.dtau_dq.clone();
    let com_jac = d.com_jacobian.clone();
    let tau_scale = d.tau_nm.amax().max(1.0);
    // Jacobians of each load point and link, at q
    let mut jp = Vec::new();
    let mut jw = Vec::new();
    for l in ld {
        let p = d.link_point(m, l.link, &l.point_in_link_m);
        let mut a = Matrix3xX::zeros(nq);
        let mut b = Matrix3xX::zeros(nq);
        d.point_jacobian(m, l.link, &p, &mut a);
        d.angular_jacobian(m, l.link, &mut b);
        jp.push(a);
        jw.push(b);
    }
    let rots: Vec<Matrix3<f64>> = ld.iter().map(|l| d.link_pose(m, l.link).0).collect();
    let mut dp = StaticsData::new(m, ld.len());
    let mut dm = StaticsData::new(m, ld.len());
    for k in 0..nq {
        let (mut qp, mut qm) = (q.to_vec(), q.to_vec());
        qp[k] += h;
        qm[k] -= h;
        holding_torques(m, &mut dp, &qp, ld, g);
        holding_torques(m, &mut dm, &qm, ld, g);
        let name = &m.q_joint(k).name;
        // ∂τ/∂q_k: the loads keep their world forces and their points on the links
        let col: DVector<f64> = (&dp.tau_nm - &dm.tau_nm) / (2.0 * h);
        for r in 0..nq {
            if (dtau[(r, k)] - col[r]).abs() > 2e-6 * tau_scale {
                return Err(format!(
                    "∂τ({})/∂q({name}) = {} but finite differences give {}",
                    m.q_joint(r).name,
                    dtau[(r, k)],
                    col[r]
                ));
            }
        }
        let cfd = (dp.com_m - dm.com_m) / (2.0 * h);
        if (com_jac.column(k) - cfd).norm() > 1e-8 {
            return Err(format!(
                "∂CoM/∂q({name}) = {} but finite differences give {cfd}",
                com_jac.column(k)
            ));
        }
        for (e, l) in ld.iter().enumerate() {
            let pfd = (dp.link_point(m, l.link, &l.point_in_link_m)
                - dm.link_point(m, l.link, &l.point_in_link_m))
                / (2.0 * h);
            if (jp[e].column(k) - pfd).norm() > 1e-8 {
                return Err(format!(
                    "point Jacobian of load {e} (link {}) column {name}: {} vs finite differences {pfd}",
                    m.links[l.link].name,
                    jp[e].column(k)
                ));
            }
            let wfd = angular_fd(
                &dp.link_pose(m, l.link).0,
                &dm.link_pose(m, l.link).0,
                &rots[e],
                h,
            );
            if (jw[e].column(k) - wfd).norm() > 1e-8 {
                return Err(format!(
                    "angular Jacobian of link {} column {name}: {} vs finite differences {wfd}",
                    m.links[l.link].name,
                    jw[e].column(k)
                ));
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn jacobians_and_torque_derivative_match_finite_differences(
        robot in 0usize..4,
        u in prop::collection::vec(0.0f64..1.0, 38),
        pick in prop::collection::vec(0usize..1000, 1..5),
        r in prop::collection::vec(-1.0f64..1.0, 36),
        tilted_gravity in any::<bool>(),
    ) {
        let m = load_model(ROBOTS[robot]);
        let q = posture(&m, &u);
        let ld = loads(&m, &pick, &r);
        let g = if tilted_gravity { Vector3::new(0.8, -1.1, -9.7) } else { GRAVITY_M_S2 };
        if let Err(e) = fd_check(&m, &q, &ld, &g) {
            prop_assert!(false, "{}: {e}", ROBOTS[robot]);
        }
    }
}

/// The same check at a few fixed, named postures of every robot (zero posture included), so a
/// failure reproduces without proptest.
#[test]
fn finite_differences_at_fixed_postures() {
    for rel in ROBOTS {
        let m = load_model(rel);
        for u in [
            vec![0.5],
            vec![0.2, 0.9, 0.35, 0.7, 0.05],
            vec![0.97, 0.03, 0.6],
        ] {
            let q = posture(&m, &u);
            let every_link: Vec<usize> = (0..m.links.len()).collect();
            let ld = loads(
                &m,
                &every_link,
                &[0.3, -0.7, 0.5, 0.9, -0.2, 0.1, -0.6, 0.4, 0.8, -0.9],
            );
            fd_check(&m, &q, &ld, &GRAVITY_M_S2).unwrap_or_else(|e| panic!("{rel}: {e}"));
        }
        // and at q = 0 exactly (axes aligned, sines zero)
        let q = vec![0.0; m.nq()];
        let ld = loads(
            &m,
            &[m.links.len() - 1, 1],
            &[0.1, 0.2, -0.3, 0.4, -0.5, 0.6, 0.7, -0.8, 0.9],
        );
        fd_check(&m, &q, &ld, &GRAVITY_M_S2).unwrap_or_else(|e| panic!("{rel} at 0: {e}"));
    }
}

/// Fixed joints fold into rigid bodies: one body per moving joint plus the root, and the model's
/// total mass is every link's.
#[test]
fn fixed_joints_fold_into_bodies() {
    let m = load_model("tests/data/geometry.urdf");
    assert_eq!(m.nq(), 7);
    assert_eq!(m.bodies.len(), 8);
    let masses = [4.0, 2.5, 0.7, 1.8, 0.4, 1.1, 0.9, 1.3, 0.6, 0.5];
    assert!((m.total_mass_kg() - masses.iter().sum::<f64>()).abs() < 1e-12);
    // a1 and its fixed child a1_plate share a body; a4 and a4_weight and tool too
    let body = |n: &str| m.link_in_body[m.frame_link(n).unwrap()].body;
    assert_eq!(body("a1"), body("a1_plate"));
    assert_eq!(body("a4"), body("a4_weight"));
    assert_eq!(body("a4"), body("tool"));
    assert_ne!(body("a2"), body("a3"));
    // the continuous joints have no limits; the non-unit axis is normalised
    let ja2 = m.q_joint(m.q_index("ja2").unwrap());
    assert_eq!(ja2.kind, JointKind::Continuous);
    assert!(ja2.lower_rad == f64::NEG_INFINITY && ja2.upper_rad == f64::INFINITY);
    let ja1 = m.q_joint(m.q_index("ja1").unwrap());
    assert!((ja1.axis - Vector3::new(0.0, 2.0, 1.0) / 5f64.sqrt()).norm() < 1e-15);
}

#[test]
fn joint_order_in_the_file_does_not_matter() {
    let text = std::fs::read_to_string(path("tests/data/geometry.urdf")).unwrap();
    // the same robot with its <joint> elements in reverse order
    let mut joints = Vec::new();
    let mut rest = String::new();
    let mut cur = text.as_str();
    while let Some(s) = cur.find("<joint ") {
        rest.push_str(&cur[..s]);
        let e = cur[s..].find("</joint>").unwrap() + s + "</joint>".len();
        joints.push(cur[s..e].to_string());
        cur = &cur[e..];
    }
    let close = cur.find("</robot>").unwrap();
    rest.push_str(&cur[..close]);
    joints.reverse();
    let reversed = format!("{rest}{}\n</robot>\n", joints.join("\n"));
    let a = BodyModel::from_urdf_str(&text, "a").unwrap();
    let b = BodyModel::from_urdf_str(&reversed, "b").unwrap();
    let names = |m: &BodyModel| {
        (0..m.nq())
            .map(|i| m.q_joint(i).name.clone())
            .collect::<Vec<_>>()
    };
    assert_ne!(names(&a), names(&b), "the test must reorder the joints");
    let named = [
        ("ja1", 0.4),
        ("ja2", -2.5),
        ("ja3", 0.12),
        ("ja4", 1.3),
        ("jb1", -0.1),
        ("jb2", 3.5),
        ("jc1", -0.8),
    ];
    let torques = |m: &BodyModel| {
        let mut q = vec![0.0; m.nq()];
        for (n, v) in named {
            q[m.q_index(n).unwrap()] = v;
        }
        let tool = m.frame_link("tool").unwrap();
        let mut d = StaticsData::new(m, 1);
        holding_torques(
            m,
            &mut d,
            &q,
            &[PointLoad::force_at(tool, Vector3::new(1.0, 2.0, -30.0))],
            &GRAVITY_M_S2,
        );
        let t: Vec<f64> = named
            .iter()
            .map(|(n, _)| d.tau_nm[m.q_index(n).unwrap()])
            .collect();
        (t, d.com_m)
    };
    let ((ta, ca), (tb, cb)) = (torques(&a), torques(&b));
    for (x, y) in ta.iter().zip(&tb) {
        assert!((x - y).abs() < 1e-12, "{x} vs {y}");
    }
    assert!((ca - cb).norm() < 1e-14);
}

#[test]
fn malformed_urdfs_are_refused_by_element() {
    let robot = |links: &str, joints: &str| {
        format!("<?xml version=\"1.0\"?><robot name=\"r\">{links}{joints}</robot>")
    };
    let two = |child: &str, joint: &str| robot(&format!("<link name=\"base\"/>{child}"), joint);
    let good_joint = "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>";
    let cases: Vec<(String, &[&str])> = vec![
        (
            two(
                "<link name=\"arm\"><collision><geometry><cylinder radius=\"20\" length=\"1\"/></geometry></collision></link>",
                good_joint,
            ),
            &["link 'arm'", "collision", "radius"],
        ),
        (
            two(
                "<link name=\"arm\"><collision><geometry><box size=\"0.1 1e9 0.1\"/></geometry></collision></link>",
                good_joint,
            ),
            &["link 'arm'", "box size"],
        ),
        (
            two(
                "<link name=\"arm\"><inertial><mass value=\"-2\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>",
                good_joint,
            ),
            &["link 'arm'", "mass"],
        ),
        (
            two(
                "<link name=\"arm\"/>",
                "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/><origin xyz=\"1e6 0 0\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>",
            ),
            &["joint 'j'", "origin"],
        ),
        (
            two(
                "<link name=\"arm\"/>",
                "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/><axis xyz=\"0 0 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>",
            ),
            &["joint 'j'", "axis"],
        ),
        (
            two(
                "<link name=\"arm\"/>",
                "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"nowhere\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>",
            ),
            &["joint 'j'", "nowhere"],
        ),
        (
            two(
                "<link name=\"arm\"/>",
                "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/><axis xyz=\"0 1 0\"/><limit lower=\"1\" upper=\"-1\" effort=\"1\" velocity=\"1\"/></joint>",
            ),
            &["joint 'j'", "limit"],
        ),
        (
            two(
                "<link name=\"arm\"><collision><geometry><mesh filename=\"arm.stl\"/></geometry></collision></link>",
                good_joint,
            ),
            &["link 'arm'", "mesh"],
        ),
    ];
    for (text, words) in cases {
        let e: BodyError = BodyModel::from_urdf_str(&text, "bad.urdf").unwrap_err();
        let msg = e.to_string();
        assert!(msg.starts_with("bad.urdf"), "{msg}");
        for w in words {
            assert!(msg.contains(w), "'{msg}' should name {w}");
        }
    }
}

/// The joints that move each rigid body, as the model lists them root first, are exactly those
/// its ancestry relation names, in increasing order.
#[test]
fn each_bodys_joint_path_is_its_ancestry() {
    for rel in ROBOTS {
        let m = load_model(rel);
        for b in 0..m.bodies.len() {
            let by_relation: Vec<usize> = (0..m.nq()).filter(|&k| m.q_moves_body(k, b)).collect();
            assert_eq!(
                m.q_path_of_body(b),
                by_relation.as_slice(),
                "{rel}: body {b}"
            );
        }
    }
}

/// One workspace reused for load sets on different links, of different sizes, gives bit for
/// bit what a fresh workspace gives: torques, centre-of-mass Jacobian and ∂τ/∂q (whose load
/// levers are kept between calls while the loads stay on the same bodies).
#[test]
fn a_reused_workspace_gives_what_a_fresh_one_gives() {
    for rel in ROBOTS {
        let m = load_model(rel);
        let n = m.links.len();
        let mut reused = StaticsData::new(&m, 3);
        let sets: [&[usize]; 6] = [
            &[n - 1, 1, n / 2],
            &[n - 1, 1, n / 2],
            &[0, n - 1],
            &[n / 3],
            &[],
            &[n - 1, n / 3, 2],
        ];
        for (i, pick) in sets.iter().enumerate() {
            let q = posture(&m, &[0.13 * i as f64 % 1.0, 0.7, 0.41, 0.88, 0.2]);
            let ld = loads(
                &m,
                pick,
                &[0.3, -0.7, 0.5, 0.9, -0.2, 0.1, -0.6, 0.4, 0.8, -0.9],
            );
            let mut fresh = StaticsData::new(&m, 3);
            for d in [&mut reused, &mut fresh] {
                holding_torques(&m, d, &q, &ld, &GRAVITY_M_S2);
                holding_torque_derivative(&m, d);
            }
            assert_eq!(reused.tau_nm, fresh.tau_nm, "{rel}: set {i}");
            assert_eq!(reused.com_jacobian, fresh.com_jacobian, "{rel}: set {i}");
            assert_eq!(reused.dtau_dq, fresh.dtau_dq, "{rel}: set {i}");
        }
    }
}
