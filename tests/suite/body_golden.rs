//! Whole-body statics against Pinocchio 4.1, an independent rigid-body library.
//!
//! The golden values in `tests/data/pinocchio/*.json` come from `tests/data/pinocchio_golden.py`
//! (run it from the repository root to regenerate them): inverse dynamics at rest
//! (`rnea(q, 0, 0, fext)`) with gravity and external loads (hand loads and arbitrary foot forces
//! at points of the foot links — and, on the worker, a seat's force at the pelvis — chosen in the
//! script, not posture-opt's ground reaction),
//! the gravity torques and their derivative, every link frame's placement, the load points'
//! positions and Jacobians, and the centre of mass with its Jacobian. Robots: the shipped worker
//! (its floating pelvis is the URDF's prismatic + revolute pelvis joints; eight postures, two of
//! them with the feet placed off the nominal stance as the planner places them: the whole body
//! turned 60° and moved sideways, and a staggered stance with the feet flat at different yaws;
//! one sitting, hips and knees at 90°),
//! the two-link arm, the
//! branched tree and `geometry.urdf` (fixed joints mid-chain, continuous joints, tilted and
//! non-unit axes, rotated origins).
//!
//! Pinocchio's inverse dynamics at rest is the torque the joints must produce to hold the posture
//! — posture-opt's holding torque, same sign (see `posture_opt::body::statics`). Joints are
//! matched by name. Pinocchio leaves a fixed root link's mass out of its centre of mass; the
//! script adds it back (`com_m`), since posture-opt counts every link.

use nalgebra::{Matrix3xX, Vector3};
use posture_opt::body::{
    BodyModel, GRAVITY_M_S2, PointLoad, StaticsData, apply_loads, forward_kinematics,
    holding_torque_derivative, holding_torques, mass_moments,
};
use serde_json::Value;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn golden(name: &str) -> Value {
    let path = format!("{ROOT}/tests/data/pinocchio/{name}.json");
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

fn v3(v: &Value) -> Vector3<f64> {
    let a = v.as_array().expect("a 3-vector");
    assert_eq!(a.len(), 3);
    Vector3::new(
        a[0].as_f64().unwrap(),
        a[1].as_f64().unwrap(),
        a[2].as_f64().unwrap(),
    )
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// `|a − b| ≤ tol` elementwise, with a message naming what is compared.
fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol,
        "{what}: posture-opt {a:.15e}, Pinocchio {b:.15e}, difference {:.3e} > {tol:.1e}",
        a - b
    );
}

fn close3(a: &Vector3<f64>, b: &Vector3<f64>, tol: f64, what: &str) {
    for k in 0..3 {
        close(a[k], b[k], tol, &format!("{what}[{k}]"));
    }
}

struct Case {
    q: Vec<f64>,
    loads: Vec<PointLoad>,
}

/// The posture (in posture-opt's q order, matched by joint name) and loads of a golden case.
fn case(model: &BodyModel, c: &Value) -> Case {
    let mut q = vec![f64::NAN; model.nq()];
    for (name, v) in c["q_rad"].as_object().unwrap() {
        q[model.q_index(name).unwrap()] = f(v);
    }
    assert!(q.iter().all(|x| x.is_finite()), "every joint has a value");
    let loads = c["loads"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| PointLoad {
            link: model.frame_link(l["link"].as_str().unwrap()).unwrap(),
            point_in_link_m: v3(&l["point_in_link_m"]),
            force_n: v3(&l["force_n"]),
            moment_nm: v3(&l["moment_nm"]),
        })
        .collect();
    Case { q, loads }
}

fn model_of(doc: &Value) -> BodyModel {
    BodyModel::from_urdf_file(format!("{ROOT}/{}", doc["robot"].as_str().unwrap())).unwrap()
}

/// Joint torques (with loads, gravity alone), link placements, load points, centre of mass.
fn check_robot(name: &str) {
    let doc = golden(name);
    let model = model_of(&doc);
    let names: Vec<&str> = doc["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_str().unwrap())
        .collect();
    assert_eq!(names.len(), model.nq(), "{name}: the same moving joints");
    close(
        model.total_mass_kg(),
        f(&doc["total_mass_kg"]),
        1e-12,
        &format!("{name}: total mass"),
    );
    let g = v3(&doc["gravity_m_s2"]);
    assert_eq!(g, GRAVITY_M_S2);
    let cases = doc["cases"].as_array().unwrap();
    assert!(!cases.is_empty());
    for c in cases {
        let cname = format!("{name}/{}", c["name"].as_str().unwrap());
        let Case { q, loads } = case(&model, c);
        let mut d = StaticsData::new(&model, loads.len());
        forward_kinematics(&model, &mut d, &q);
        mass_moments(&model, &mut d);
        apply_loads(&model, &mut d, &loads, &g);

        // torques, to ~1e-9 of the largest
        let scale = names
            .iter()
            .map(|n| f(&c["tau_nm"][n]).abs())
            .fold(1.0, f64::max);
        let gscale = names
            .iter()
            .map(|n| f(&c["tau_gravity_nm"][n]).abs())
            .fold(1.0, f64::max);
        for n in &names {
            let k = model.q_index(n).unwrap();
            close(
                d.tau_nm[k],
                f(&c["tau_nm"][n]),
                1e-9 * scale,
                &format!("{cname}: τ {n}"),
            );
            close(
                d.tau_gravity_nm[k],
                f(&c["tau_gravity_nm"][n]),
                1e-9 * gscale,
                &format!("{cname}: τ_gravity {n}"),
            );
            close(
                d.tau_load_nm[k],
                f(&c["tau_nm"][n]) - f(&c["tau_gravity_nm"][n]),
                1e-9 * scale,
                &format!("{cname}: τ_load {n}"),
            );
        }

        // every link frame
        for (link, p) in c["links"].as_object().unwrap() {
            let l = model.frame_link(link).unwrap();
            let (rot, pos) = d.link_pose(&model, l);
            close3(
                &pos,
                &v3(&p["position_m"]),
                1e-12,
                &format!("{cname}: {link} position"),
            );
            let r = p["rotation"].as_array().unwrap();
            for i in 0..3 {
                for j in 0..3 {
                    close(
                        rot[(i, j)],
                        f(&r[i][j]),
                        1e-12,
                        &format!("{cname}: {link} R[{i}][{j}]"),
                    );
                }
            }
        }

        // load points and their Jacobians
        let mut jp = Matrix3xX::zeros(model.nq());
        let mut jw = Matrix3xX::zeros(model.nq());
        for (e, l) in c["loads"].as_array().unwrap().iter().enumerate() {
            let p = d.link_point(&model, loads[e].link, &loads[e].point_in_link_m);
            close3(
                &p,
                &v3(&l["point_world_m"]),
                1e-12,
                &format!("{cname}: load {e} point"),
            );
            close3(
                &d.load_point_w[e],
                &p,
                1e-15,
                &format!("{cname}: load {e} cached point"),
            );
            d.point_jacobian(&model, loads[e].link, &p, &mut jp);
            d.angular_jacobian(&model, loads[e].link, &mut jw);
            for n in &names {
                let k = model.q_index(n).unwrap();
                close3(
                    &jp.column(k).into_owned(),
                    &v3(&l["jacobian_linear"][n]),
                    1e-12,
                    &format!("{cname}: load {e} ∂p/∂{n}"),
                );
                close3(
                    &jw.column(k).into_owned(),
                    &v3(&l["jacobian_angular"][n]),
                    1e-12,
                    &format!("{cname}: load {e} ∂ω/∂{n}"),
                );
            }
        }

        // centre of mass and its Jacobian (root link's mass included, see the module docs)
        close3(&d.com_m, &v3(&c["com_m"]), 1e-12, &format!("{cname}: CoM"));
        for n in &names {
            let k = model.q_index(n).unwrap();
            close3(
                &d.com_jacobian.column(k).into_owned(),
                &v3(&c["com_jacobian"][n]),
                1e-12,
                &format!("{cname}: ∂CoM/∂{n}"),
            );
        }

        // the one-call form gives the same torques
        let mut d2 = StaticsData::new(&model, loads.len());
        holding_torques(&model, &mut d2, &q, &loads, &g);
        assert_eq!(
            d2.tau_nm, d.tau_nm,
            "{cname}: holding_torques = fk + moments + loads"
        );

        // gravity alone: the torques and their derivative
        let mut d0 = StaticsData::new(&model, 0);
        holding_torques(&model, &mut d0, &q, &[], &g);
        holding_torque_derivative(&model, &mut d0);
        let dg = c["dtau_gravity_dq"].as_array().unwrap();
        let dscale = dg
            .iter()
            .flat_map(|r| r.as_array().unwrap().iter().map(|x| f(x).abs()))
            .fold(1.0, f64::max);
        for (r, rn) in names.iter().enumerate() {
            let kr = model.q_index(rn).unwrap();
            close(
                d0.tau_nm[kr],
                f(&c["tau_gravity_nm"][rn]),
                1e-9 * gscale,
                &format!("{cname}: τ without loads {rn}"),
            );
            for (col, cn) in names.iter().enumerate() {
                let kc = model.q_index(cn).unwrap();
                close(
                    d0.dtau_dq[(kr, kc)],
                    f(&dg[r][col]),
                    1e-9 * dscale,
                    &format!("{cname}: ∂τ_gravity({rn})/∂q({cn})"),
                );
            }
        }
    }
}

#[test]
fn worker_matches_pinocchio_in_eight_postures_with_hand_foot_and_seat_loads() {
    check_robot("worker");
}

#[test]
fn two_link_arm_matches_pinocchio() {
    check_robot("two_link");
}

#[test]
fn branched_tree_matches_pinocchio() {
    check_robot("tree");
}

#[test]
fn every_urdf_geometry_matches_pinocchio() {
    check_robot("geometry");
}

/// The golden files cover what the tests rely on: the worker's eight postures (one sitting),
/// both hands, both feet and the pelvis (a seat) loaded, the pelvis joints among the compared torques, and feet placed off the
/// nominal stance (issue 33): flat on the floor, turned and moved with the whole body, or
/// staggered at different yaws.
#[test]
fn golden_files_cover_the_worker() {
    let doc = golden("worker");
    let names: Vec<String> = doc["cases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(
        names,
        [
            "standing",
            "stoop",
            "squat",
            "reach",
            "asymmetric",
            "turned",
            "staggered",
            "seated"
        ]
    );
    let c = &doc["cases"][0];
    let links: Vec<&str> = c["loads"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["link"].as_str().unwrap())
        .collect();
    assert_eq!(
        links,
        ["r_hand_grip", "l_hand_grip", "r_foot", "l_foot", "pelvis"]
    );
    for j in posture_opt::body::worker::PELVIS_JOINTS {
        assert!(c["tau_nm"][j].is_f64(), "{j}");
    }
    // the pelvis joints' torques are not zero with unbalanced foot forces: the comparison
    // exercises them
    assert!(f(&doc["cases"][4]["tau_nm"]["pelvis_tz"]).abs() > 1.0);

    // the placed feet: (position, yaw of the x axis in degrees) of each foot link frame
    let foot = |case: usize, link: &str| {
        let p = &doc["cases"][case]["links"][link];
        let r = |i: usize, j: usize| f(&p["rotation"][i][j]);
        // flat: the link's z axis is the world's
        close(r(2, 2), 1.0, 1e-12, &format!("case {case}: {link} flat"));
        (v3(&p["position_m"]), r(1, 0).atan2(r(0, 0)).to_degrees())
    };
    let (l0, _) = foot(0, "l_foot");
    let (r0, _) = foot(0, "r_foot");
    // turned: the nominal stance turned 60° about the vertical and moved 0.3 m sideways
    let (l, l_yaw) = foot(5, "l_foot");
    let (r, r_yaw) = foot(5, "r_foot");
    close(l_yaw, 60.0, 1e-9, "turned: left yaw");
    close(r_yaw, 60.0, 1e-9, "turned: right yaw");
    close(
        (l - r).norm(),
        (l0 - r0).norm(),
        1e-12,
        "turned: stance width",
    );
    close(l.z, l0.z, 1e-12, "turned: left on the floor");
    close(r.z, r0.z, 1e-12, "turned: right on the floor");
    close(
        ((l + r) / 2.0 - (l0 + r0) / 2.0).norm(),
        0.3,
        1e-12,
        "turned: moved",
    );
    // staggered: the left foot 0.25 m ahead of the right, yaws +30° and −5°, both on the floor
    let (l, l_yaw) = foot(6, "l_foot");
    let (r, r_yaw) = foot(6, "r_foot");
    close(l_yaw, 30.0, 1e-9, "staggered: left yaw");
    close(r_yaw, -5.0, 1e-9, "staggered: right yaw");
    close(l.x - r.x, 0.25, 1e-12, "staggered: stagger");
    close(l.z, l0.z, 1e-12, "staggered: left on the floor");
    close(r.z, r0.z, 1e-12, "staggered: right on the floor");
}
