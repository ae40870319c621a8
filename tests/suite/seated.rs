//! Seated work: the worker sits on a seat the task declares (issue 33.2).
//!
//! * Statics: the seat, the two feet and gravity balance exactly (the floating pelvis's six
//!   torques vanish, the reactions sum to the weight), and in upright sitting with hips and knees
//!   at 90° the feet carry the share of the weight measured on people: 19.5–30 % (Mbada et al.
//!   2016, 210 adults: 12.60 / 15.92 / 19.64 kg on the feet against 51.86 / 49.52 / 44.87 kg on
//!   the seat in sacro-ischial, ischio-femoral and ischial sitting; Collins 2001: 19 % through the
//!   feet at 90-90-90) — numbers from those studies, not from this code.
//! * The seat's rows have the gradients of their values (central differences).
//! * The task file's seat is checked at the boundary: ranges, no standing area with a seat, a
//!   seat above the standing hips or beyond the legs' reach from the feet, and only a body with
//!   the generated worker's pelvis sits.
//! * Planned: tasks/bench_seated.yaml (shortened to one cycle) keeps the pelvis on the seat in
//!   every phase, scores RULA's legs as supported and exempts REBA's knee adjustment, and says
//!   "sitting".

use nalgebra::Vector3;
use posture_opt::plan::posture::{PostureWork, Row};
use posture_opt::plan::search::seated_start;
use posture_opt::plan::{Plan, Task, plan_task_with};
use std::path::PathBuf;
use std::sync::OnceLock;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn seated_text() -> String {
    std::fs::read_to_string(root().join("tasks/bench_seated.yaml")).unwrap()
}

fn task_of(text: &str) -> Result<Task, String> {
    Task::from_yaml_str(text, &root().join("tasks/bench_seated.yaml")).map_err(|e| e.to_string())
}

fn seated() -> Task {
    task_of(&seated_text()).unwrap()
}

#[test]
fn seat_feet_and_gravity_balance_and_the_feet_carry_the_measured_share() {
    let task = seated();
    let q = seated_start(&task).expect("a seated task");
    let mut pw = PostureWork::new(&task);
    pw.statics(&task, &q, &[Vector3::zeros(); 2]);
    let g = pw.ground.expect("a floating body stands or sits");
    let seat = g.seat.expect("the seat carries part of the weight");
    // the six unactuated pelvis joints hold nothing: the supports balance the body
    for k in &task.unactuated {
        let tau = pw.data.tau_nm[*k];
        assert!(
            tau.abs() < 1e-8,
            "{}: {tau} N·m",
            task.model.q_joint(*k).name
        );
    }
    let weight = task.model.total_mass_kg() * 9.81;
    let total = seat.force_n + g.force_n[0] + g.force_n[1];
    assert!(
        (total - Vector3::new(0.0, 0.0, weight)).norm() < 1e-9 * weight,
        "{total}"
    );
    let feet = (g.force_n[0].z + g.force_n[1].z) / weight;
    assert!(
        (0.195..=0.30).contains(&feet),
        "feet carry {:.1} % of the weight; people sitting upright put 19.5–30 % on them",
        100.0 * feet
    );
    assert!((seat.share + feet - 1.0).abs() < 1e-12);
    // the two feet share symmetrically in a symmetric posture
    assert!((g.force_n[0].z - g.force_n[1].z).abs() < 1e-6 * weight);
}

#[test]
fn a_seat_in_front_of_the_centre_of_pressure_shifts_nothing_to_the_feet_it_cannot_carry() {
    // leaning back over the seat's back edge: the reaction's centre leaves the triangle of seat
    // point and soles; the weights stay in 0..1 and still sum to 1
    let task = seated();
    let mut q = seated_start(&task).unwrap();
    let k = task.model.q_index("lumbar_flexion").unwrap();
    q[k] = task.model.q_joint(k).lower_rad;
    let mut pw = PostureWork::new(&task);
    pw.statics(&task, &q, &[Vector3::zeros(); 2]);
    let g = pw.ground.unwrap();
    let s = g.seat.unwrap();
    let w = task.model.total_mass_kg() * 9.81;
    for share in [s.share, g.force_n[0].z / w, g.force_n[1].z / w] {
        assert!((-1e-12..=1.0 + 1e-12).contains(&share), "{share}");
    }
    let total = s.force_n + g.force_n[0] + g.force_n[1];
    assert!((total.z - w).abs() < 1e-9 * w);
}

fn seat_rows(task: &Task, pw: &mut PostureWork, q: &[f64]) -> Vec<(f64, Vec<f64>)> {
    pw.statics(task, q, &[Vector3::zeros(); 2]);
    let mut out = Vec::new();
    pw.geometry_rows(task, None, |kind, g, grad| {
        if kind == Row::Seat {
            out.push((g, grad.to_vec()));
        }
    });
    // the seat's height row
    let dz = pw.seat_error(task).unwrap();
    assert!(pw.seat_jacobian(task));
    out.push((dz, (0..q.len()).map(|k| -pw.jac[(2, k)]).collect()));
    out
}

#[test]
fn the_seat_rows_have_the_gradients_of_their_values() {
    let task = seated();
    let mut pw = PostureWork::new(&task);
    let q0 = seated_start(&task).unwrap();
    let h = 1e-6;
    let mut checked = 0;
    for seed in 0..4u32 {
        let q: Vec<f64> = q0
            .iter()
            .enumerate()
            .map(|(k, x)| x + 0.05 * ((k as f64 * 1.7 + seed as f64 * 0.9).sin()))
            .collect();
        let base = seat_rows(&task, &mut pw, &q);
        assert_eq!(base.len(), 5, "four outline edges and the height");
        for k in 0..q.len() {
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[k] += h;
            qm[k] -= h;
            let (rp, rm) = (
                seat_rows(&task, &mut pw, &qp),
                seat_rows(&task, &mut pw, &qm),
            );
            for (i, (_, grad)) in base.iter().enumerate() {
                let fd = (rp[i].0 - rm[i].0) / (2.0 * h);
                assert!(
                    (fd - grad[k]).abs() <= 1e-6 * (1.0 + fd.abs()),
                    "row {i}, {}: finite difference {fd}, gradient {}",
                    task.model.q_joint(k).name,
                    grad[k]
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 500);
}

#[test]
fn the_task_files_seat_is_checked_naming_the_field() {
    let text = seated_text();
    let with = |from: &str, to: &str| {
        assert!(text.contains(from), "{from}");
        task_of(&text.replace(from, to)).unwrap_err()
    };
    let e = with("height_m: 0.42", "height_m: 1.6");
    assert!(
        e.contains("seat.height_m") && e.contains("0.25..1.0"),
        "{e}"
    );
    let e = with("position_m: [-0.35, 0.00]", "position_m: [-0.35, .nan]");
    assert!(e.contains("seat.position_m[1]"), "{e}");
    let e = with(
        "position_m: [-0.35, 0.00]}",
        "position_m: [-0.35, 0.00], size_m: [0.05, 0.45]}",
    );
    assert!(e.contains("seat.size_m[0]"), "{e}");
    let e = with(
        "stance: {width_m: 0.20, forward_m: 0.05}",
        "stance: {width_m: 0.20, forward_m: 0.05, area_m: [[-1, -1], [1, -1], [1, 1], [-1, 1]]}",
    );
    assert!(e.contains("stance.area_m") && e.contains("seat"), "{e}");
    let e = with("seat: {", "seat: {yaw_deg: 400, ");
    assert!(e.contains("seat.yaw_deg"), "{e}");
    // a seat the worker cannot sit on with the feet on the stance: the legs' length decides
    // (the 1.62 m woman's hips stand about 0.81 m high)
    let e = with("height_m: 0.42", "height_m: 0.95");
    assert!(e.contains("seat.height_m") && e.contains("too high"), "{e}");
    let e = with("position_m: [-0.35, 0.00]", "position_m: [-1.5, 0.00]");
    assert!(
        e.contains("seat.position_m") && e.contains("legs reach"),
        "{e}"
    );
    // within reach it loads
    assert!(
        task_of(&text.replace("position_m: [-0.35, 0.00]", "position_m: [-0.45, 0.00]")).is_ok()
    );
}

fn planned() -> &'static (Task, Plan) {
    static P: OnceLock<(Task, Plan)> = OnceLock::new();
    P.get_or_init(|| {
        let text = seated_text().replace("cycles: 240", "cycles: 1");
        let t = task_of(&text).unwrap();
        let p = plan_task_with(&t, crate::common::held(false)).unwrap();
        (t, p)
    })
}

#[test]
fn the_planned_seated_worker_sits_on_the_seat_in_every_phase() {
    let (t, p) = planned();
    let seat = t.stance.as_ref().unwrap().seat.as_ref().unwrap();
    let mut pw = PostureWork::new(t);
    for ph in &p.summary.phases {
        pw.statics(t, &ph.q_rad, &[Vector3::zeros(); 2]);
        let c = pw
            .data
            .link_point(&t.model, seat.link, &seat.contact_in_link_m);
        assert!((c.z - seat.height_m).abs() < 1e-3, "{}: {c}", ph.phase);
        assert!(
            seat.margin_m(&c.xy()) > -1e-3,
            "{}: {c} off the seat",
            ph.phase
        );
    }
    for r in &p.postures {
        let s = r
            .seat_share
            .expect("a seated posture reports the seat's share");
        assert!((0.4..1.0).contains(&s), "{}: seat carries {s}", r.phase);
    }
}

#[test]
fn seated_postures_score_supported_legs_and_no_knee_adjustment() {
    let (t, p) = planned();
    let phases = posture_opt::assess::phase::assess_phases(t, p);
    for a in &phases {
        let angles = a.angles.as_ref().expect("the generated worker is measured");
        assert!(angles.seated, "{}", a.phase);
        let rula = a.rula.as_ref().unwrap();
        assert_eq!(rula.legs, 1, "{}: RULA legs", a.phase);
        let reba = a.reba.as_ref().unwrap();
        let legs = &reba.group_a.legs;
        assert_eq!(legs.score, 1, "{}: REBA legs {}", a.phase, legs.rule);
        let words = &a.posture_words;
        assert!(words.contains("sitting"), "{words}");
        assert!(!words.contains("knees bent"), "{words}");
    }
}

/// The "what would change it" finding moves a seated worker's work toward the seated elbow height
/// (where the seated rest posture, upper arms hanging, puts the elbow), not the standing one
/// (0.630 × stature would put it 0.3 m higher, at the seated worker's shoulder). For the seated
/// 1.62 m woman the elbow joint's centre hangs one upper-arm length below the shoulder's and sits
/// 0.185–0.33 m above the seat: sitting elbow heights run from 185 mm (5th-percentile woman) to
/// 295 mm (95th-percentile man) for British adults (Pheasant & Haslegrave, Bodyspace, 3rd ed.,
/// 2006), measured to the underside of the elbow, which lies below the joint's centre by about
/// the olecranon's depth (ASSUMPTION: up to 35 mm).
#[test]
fn a_seated_workers_work_moves_toward_the_seated_elbow_height() {
    let (t, p) = planned();
    let m = &t.model;
    let seat_m = t.stance.as_ref().unwrap().seat.as_ref().unwrap().height_m;
    let z = posture_opt::study::what_if::seated_elbow_height_m(t, p).unwrap();
    assert!(
        (0.185..=0.33).contains(&(z - seat_m)),
        "{z} m, seat {seat_m} m"
    );
    let mut d = posture_opt::body::StaticsData::new(m, 0);
    let at = |d: &mut posture_opt::body::StaticsData, q: &[f64], name: &str| {
        posture_opt::body::forward_kinematics(m, d, q);
        let l = m.links.iter().position(|x| x.name == name).unwrap();
        d.link_point(m, l, &Vector3::zeros())
    };
    let q = &p.summary.rest_posture_rad;
    let upper_arm_m = (at(&mut d, q, "r_upper_arm") - at(&mut d, q, "r_forearm")).norm();
    let hang_m = at(&mut d, q, "r_upper_arm").z - z;
    assert!(
        (hang_m - upper_arm_m).abs() < 0.01,
        "{hang_m} vs {upper_arm_m}"
    );
    let a = posture_opt::assess::assess(t, p, 0.7);
    let w = posture_opt::study::what_if::what_if(t, p, &a, crate::common::held(false), 0.7)
        .unwrap()
        .expect("the bench's work sits 0.15-0.3 m above the seated elbow: it is moved");
    let posture_opt::study::what_if::Change::MoveWork {
        dz_m,
        elbow_height_m,
        seated,
        surfaces,
        ..
    } = w.change
    else {
        panic!("{:?}", w.change)
    };
    assert!(seated);
    assert_eq!(elbow_height_m, z);
    // the bench top comes down with the work, and the parts bin standing on it
    assert_eq!(
        surfaces,
        vec!["bench top".to_string(), "parts bin".to_string()]
    );
    assert!(
        dz_m < 0.0,
        "the work moves down toward the seated elbow: {dz_m}"
    );
}

/// "What would change it" brings the work that lies farthest from the normal working area toward
/// it (an ergonomist's seated side-bin pick: the bin 0.45 m to the right of the seat centre, the
/// head turned 45° to reach into it). The normal area of a hand is the arc it sweeps with the
/// elbow at the side (Barnes 1963): checked here from the rest posture's own elbow and grip, the
/// chosen work is the bin's, moved horizontally toward the right hand's area until 5 cm from
/// its centre (at most 0.30 m), its height kept, the bin's lateral offset smaller.
#[test]
fn the_work_farthest_from_the_normal_area_is_brought_closer() {
    use posture_opt::study::what_if::{Change, MAX_CLOSER_M, NEAR_ELBOW_M, bring_work_closer};
    let text = "name: seated side-bin pick\nworker: {sex: female, stature_m: 1.65, mass_kg: 65.0}\nseat: {height_m: 0.43, position_m: [-0.35, 0.0]}\nstance: {width_m: 0.22, forward_m: 0.05}\nworkstation:\n  obstacles:\n    - {name: table, box: {size_m: [0.60, 1.40, 0.04]}, position_m: [0.15, 0.0, 0.70]}\n    - {name: bin, box: {size_m: [0.20, 0.25, 0.12]}, position_m: [-0.05, -0.45, 0.78]}\n    - {name: floor, plane: {normal: [0, 0, 1]}, position_m: [0, 0, 0]}\nphases:\n  - {name: reach into bin, target_m: [-0.05, -0.45, 0.88], duration_s: 2.0}\n  - {name: bring part, target_m: [0.05, -0.15, 0.82], load_kg: 0.5, duration_s: 2.0}\n  - {name: place in front, target_m: [0.10, 0.0, 0.78], load_kg: 0.5, duration_s: 4.0}\nrest_s: 2.0\ncycles: 30\n";
    let t = task_of(text).unwrap();
    let p = plan_task_with(&t, crate::common::held(false)).unwrap();
    // the right hand's normal area, from the rest posture
    let m = &t.model;
    let mut d = posture_opt::body::StaticsData::new(m, 0);
    posture_opt::body::forward_kinematics(m, &mut d, &p.summary.rest_posture_rad);
    let at = |name: &str| {
        let l = m.links.iter().position(|x| x.name == name).unwrap();
        d.link_point(m, l, &Vector3::zeros())
    };
    let (elbow, grip) = (at("r_forearm"), at("r_hand_grip"));
    let pelvis = m.links.iter().position(|x| x.name == "pelvis").unwrap();
    let (r, _) = d.link_pose(m, pelvis);
    let forward = Vector3::new(r[(0, 0)], r[(1, 0)], 0.0).normalize();
    assert!(forward.x > 0.95, "the seated worker faces +x: {forward:?}");
    let centre = elbow + forward * (grip - elbow).norm();
    let away = |p: usize| {
        let w = t.phases[p].targets_m[0].unwrap();
        (centre - w).xy().norm()
    };
    assert!(away(0) > away(1) && away(0) > away(2));
    let a = posture_opt::assess::assess(&t, &p, 0.7);
    let w = bring_work_closer(&t, &p, &a, crate::common::held(false), 0.7)
        .unwrap()
        .expect("the bin lies beyond the normal area");
    let Change::BringWorkCloser {
        phase,
        dx_m,
        dy_m,
        beyond_m,
        surfaces,
        short_of_feet,
    } = &w.change
    else {
        panic!("{:?}", w.change)
    };
    assert_eq!(phase, "reach into bin");
    assert!(
        (beyond_m - away(0)).abs() < 1e-9,
        "{beyond_m} vs {}",
        away(0)
    );
    let step = Vector3::new(*dx_m, *dy_m, 0.0);
    let want = (away(0) - NEAR_ELBOW_M).min(MAX_CLOSER_M);
    assert!(
        (step.norm() - want).abs() < 1e-9,
        "{} vs {want}",
        step.norm()
    );
    let dir = (centre - t.phases[0].targets_m[0].unwrap())
        .xy()
        .normalize();
    assert!((step.xy().normalize() - dir).norm() < 1e-9);
    assert!(dy_m > &0.0, "the bin comes in from the right side: {dy_m}");
    // the part would leave the bin (0.25 m across): the bin comes with it, the table stays
    assert!(dy_m.abs() > 0.125);
    assert_eq!(surfaces, &["bin"]);
    // the bin on the table passes over the feet: the move is not shortened for them
    assert!(!short_of_feet);
}
