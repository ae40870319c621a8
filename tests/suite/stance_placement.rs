//! The feet as a decision: the planner places both feet in each phase within the task's
//! standing area, and the head looks at the work.
//!
//! * The optimiser's geometric rows (balance on the support hull of the feet where they stand
//!   now, sole corners inside the standing area, the stance's width, stagger and relative yaw,
//!   the gaze cone) and the step cost have the gradients their values have: central finite
//!   differences of the values, at postures away from the planned ones.
//! * A planned side transfer keeps every bound, checked from the posture alone with geometry
//!   written here (a brute-force convex hull of the eight sole corners, the area's half-planes):
//!   feet flat on the floor, soles inside the area, width, stagger and relative yaw within their
//!   ranges, the centre of pressure the task's margin inside the support polygon.
//! * Requirement: no trunk twist beyond 20° where turning the feet avoids it. The same side
//!   transfer with the feet fixed twists the trunk beyond 20° (so the test is not vacuous); with
//!   the feet placed, no phase twists beyond 20°, and the feet turn toward each side.
//! * A target 1.2 m to the side is not "out of reach" when the feet may step (it is with them
//!   fixed), and one 3 m away is out of reach either way.

use nalgebra::{Vector2, Vector3};
use posture_opt::assess::angles::BodyAngles;
use posture_opt::body::StaticsData;
use posture_opt::body::stance::{FeetNow, SOLE_CORNERS};
use posture_opt::plan::asymmetry::Asymmetry;
use posture_opt::plan::posture::PostureWork;
use posture_opt::plan::stepping::{FootPose, Stepping};
use posture_opt::plan::task::{
    STANCE_RELATIVE_YAW_RANGE_DEG, STANCE_STAGGER_MAX_M, STANCE_WIDTH_RANGE_M,
};
use posture_opt::plan::{Plan, PlanOptions, Task, plan_task_with};
use std::path::PathBuf;
use std::sync::OnceLock;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn side_transfer(fixed: bool) -> Task {
    let text = std::fs::read_to_string(root().join("tasks/side_transfer.yaml")).unwrap();
    let text = if fixed {
        let area = text.lines().find(|l| l.starts_with("stance:")).unwrap();
        text.replace(area, "")
    } else {
        text
    };
    Task::from_yaml_str(&text, &root().join("tasks/side_transfer.yaml")).unwrap()
}

/// Planned without the acceptable posture zones: the zones alone cap the twist at 10° and the
/// head's tilt at 5°, and these tests are of the stepping and gaze mechanisms themselves.
fn plan(task: &Task) -> Plan {
    plan_task_with(
        task,
        PlanOptions {
            zones: false,
            ..crate::common::held(false)
        },
    )
    .unwrap()
}

/// The side transfer planned with placed feet, once for the module.
fn placed() -> &'static (Task, Plan) {
    static P: OnceLock<(Task, Plan)> = OnceLock::new();
    P.get_or_init(|| {
        let t = side_transfer(false);
        let p = plan(&t);
        (t, p)
    })
}

/// A deterministic posture away from any plan: every joint at a pseudo-random point of its
/// middle half, the pelvis over the feet.
fn scrambled(task: &Task, seed: u64) -> Vec<f64> {
    let mut s = seed;
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let m = &task.model;
    (0..m.nq())
        .map(|k| {
            let j = m.q_joint(k);
            let name = j.name.as_str();
            match name {
                "pelvis_tz" => 0.95,
                "pelvis_tx" | "pelvis_ty" => 0.1 * (next() - 0.5),
                "pelvis_rotation" => 1.0 * (next() - 0.5),
                "pelvis_list" | "pelvis_tilt" => 0.1 * (next() - 0.5),
                _ if j.lower_rad.is_finite() && j.upper_rad.is_finite() => {
                    let mid = 0.5 * (j.lower_rad + j.upper_rad);
                    mid + 0.5 * (j.upper_rad - j.lower_rad) * (next() - 0.5)
                }
                _ => 0.0,
            }
        })
        .collect()
}

fn rows(task: &Task, pw: &mut PostureWork, q: &[f64], gaze: &Vector3<f64>) -> Vec<(f64, Vec<f64>)> {
    pw.statics(task, q, &[Vector3::zeros(); 2]);
    let mut out = Vec::new();
    pw.geometry_rows(task, Some(gaze), |_, g, grad| out.push((g, grad.to_vec())));
    out
}

#[test]
fn geometry_rows_have_the_gradients_of_their_values() {
    let task = side_transfer(false);
    let mut pw = PostureWork::new(&task);
    let gaze = Vector3::new(0.4, -0.3, 0.9);
    let h = 1e-6;
    let mut checked = 0;
    for seed in 1..=6 {
        let q = scrambled(&task, seed);
        let base = rows(&task, &mut pw, &q, &gaze);
        assert!(
            base.len() > 20,
            "gaze, balance, area and stance rows expected"
        );
        for k in 0..q.len() {
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[k] += h;
            qm[k] -= h;
            let (rp, rm) = (
                rows(&task, &mut pw, &qp, &gaze),
                rows(&task, &mut pw, &qm, &gaze),
            );
            if rp.len() != base.len() || rm.len() != base.len() {
                continue; // the support hull changed its vertices: not differentiable here
            }
            for (i, (_, grad)) in base.iter().enumerate() {
                let fd = (rp[i].0 - rm[i].0) / (2.0 * h);
                assert!(
                    (fd - grad[k]).abs() <= 1e-6 * (1.0 + fd.abs()),
                    "seed {seed}, row {i}, coordinate {} ({}): finite difference {fd}, gradient {}",
                    k,
                    task.model.q_joint(k).name,
                    grad[k]
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 10_000, "{checked} derivatives checked");
}

#[test]
fn step_cost_has_the_gradient_of_its_value() {
    let task = side_transfer(false);
    let st = task.stance.as_ref().unwrap();
    let mut data = StaticsData::new(&task.model, 0);
    let feet = |data: &mut StaticsData, q: &[f64]| {
        posture_opt::body::forward_kinematics(&task.model, data, q);
        FeetNow::at(&task.model, data, &st.feet)
    };
    let q0 = scrambled(&task, 11);
    let q1 = scrambled(&task, 12);
    let nb = feet(&mut data, &q1);
    // with the asymmetry of two phases' loads, one on each side
    let cost = Stepping {
        weight: 0.7,
        neighbours: vec![(nb, 1.0), (nb, 2.0)],
        asymmetry: Asymmetry {
            loads: vec![
                (Vector2::new(0.3, 0.6), 0.5),
                (Vector2::new(0.2, -0.5), 0.25),
            ],
        },
    };
    let f0 = feet(&mut data, &q0);
    let mut grad = vec![0.0; q0.len()];
    cost.add_gradient(&task, &data, &f0, &mut grad);
    assert!(cost.value(&task, &f0) > 0.0);
    let h = 1e-6;
    for k in 0..q0.len() {
        let (mut qp, mut qm) = (q0.clone(), q0.clone());
        qp[k] += h;
        qm[k] -= h;
        let vp = cost.value(&task, &feet(&mut data, &qp));
        let vm = cost.value(&task, &feet(&mut data, &qm));
        let fd = (vp - vm) / (2.0 * h);
        assert!(
            (fd - grad[k]).abs() <= 1e-6 * (1.0 + fd.abs()),
            "coordinate {k}: finite difference {fd}, gradient {}",
            grad[k]
        );
    }
    // no step, no cost
    let still = Stepping {
        weight: 0.7,
        neighbours: vec![(f0, 1.0)],
        asymmetry: Asymmetry::default(),
    };
    assert_eq!(still.value(&task, &f0), 0.0);
}

/// Signed distance of `p` inside the convex hull of `pts` (positive inside), by brute force:
/// the hull's edges are the pairs with every other point on one side.
fn hull_margin(pts: &[Vector2<f64>], p: &Vector2<f64>) -> f64 {
    let mut m = f64::INFINITY;
    for i in 0..pts.len() {
        for j in 0..pts.len() {
            let (a, b) = (pts[i], pts[j]);
            if (b - a).norm() < 1e-9 {
                continue;
            }
            let n = Vector2::new(b.y - a.y, a.x - b.x).normalize(); // right of a→b
            if pts.iter().all(|c| n.dot(&(c - a)) <= 1e-12) {
                m = m.min(-n.dot(&(p - a)));
            }
        }
    }
    m
}

#[test]
fn planned_feet_keep_every_bound() {
    let (task, plan) = placed();
    let st = task.stance.as_ref().unwrap();
    let area = &st.placement.as_ref().unwrap().area_m;
    let mut pw = PostureWork::new(task);
    for (p, ph) in plan.summary.phases.iter().enumerate() {
        let q = &ph.q_rad;
        pw.statics(task, q, &task.phases[p].hand_force_n);
        let m = &task.model;
        let mut corners = Vec::new();
        let mut centre = [Vector2::zeros(); 2];
        let mut yaw = [0.0; 2];
        for (i, f) in st.feet.iter().enumerate() {
            let (rot, _) = pw.data.link_pose(m, f.link);
            // flat on the floor: the sole's normal is vertical and the sole at z = 0
            assert!(
                (rot * Vector3::z()).z > 1.0 - 1e-7,
                "'{}': foot {i} tilted",
                ph.phase
            );
            for (sx, sy) in SOLE_CORNERS {
                let c = pw.data.link_point(
                    m,
                    f.link,
                    &(f.sole_center_in_link_m
                        + Vector3::new(sx * f.half_length_m, sy * f.half_width_m, 0.0)),
                );
                assert!(
                    c.z.abs() < 1e-4,
                    "'{}': sole corner at z = {}",
                    ph.phase,
                    c.z
                );
                // inside every half-plane of the (counter-clockwise) area
                for e in 0..area.len() {
                    let (a, b) = (area[e], area[(e + 1) % area.len()]);
                    let cross = (b - a).perp(&(c.xy() - a));
                    assert!(
                        cross >= -1e-6,
                        "'{}': a sole corner outside the area",
                        ph.phase
                    );
                }
                corners.push(c.xy());
            }
            centre[i] = pw.data.link_point(m, f.link, &f.sole_center_in_link_m).xy();
            yaw[i] = rot[(1, 0)].atan2(rot[(0, 0)]);
        }
        let rel = (yaw[0] - yaw[1]).to_degrees();
        let heading = yaw[1] + (yaw[0] - yaw[1]) / 2.0;
        let d = centre[0] - centre[1];
        let width = -heading.sin() * d.x + heading.cos() * d.y;
        let stagger = heading.cos() * d.x + heading.sin() * d.y;
        let tol = 1e-5;
        assert!(
            width >= STANCE_WIDTH_RANGE_M.0 - tol && width <= STANCE_WIDTH_RANGE_M.1 + tol,
            "'{}': width {width}",
            ph.phase
        );
        assert!(
            stagger.abs() <= STANCE_STAGGER_MAX_M + tol,
            "'{}': stagger {stagger}",
            ph.phase
        );
        assert!(
            rel >= STANCE_RELATIVE_YAW_RANGE_DEG.0 - 1e-3
                && rel <= STANCE_RELATIVE_YAW_RANGE_DEG.1 + 1e-3,
            "'{}': relative yaw {rel}°",
            ph.phase
        );
        let cop = pw.ground.unwrap().cop_total_m;
        let margin = hull_margin(&corners, &cop);
        assert!(
            margin >= task.objective.balance_margin_m - 1e-5,
            "'{}': centre of pressure {margin} m inside the support polygon",
            ph.phase
        );
        // the plan document reports these feet
        let f = ph.feet.as_ref().unwrap();
        assert!((f.left.sole_center_m[0] - centre[0].x).abs() < 1e-9);
        assert!((f.right.yaw_deg - yaw[1].to_degrees()).abs() < 1e-9);
    }
}

fn max_twist_deg(task: &Task, plan: &Plan) -> f64 {
    let mut data = StaticsData::new(&task.model, 0);
    plan.summary
        .phases
        .iter()
        .map(|ph| {
            BodyAngles::measure(&task.model, &mut data, &ph.q_rad, None)
                .unwrap()
                .trunk_twist_deg
                .abs()
        })
        .fold(0.0, f64::max)
}

/// Free to step and turn, the side transfer is done facing each side: without the acceptable
/// posture zones the fixed stance twists the trunk beyond 20° to reach the bin; with them (the
/// default) the twist is held at ISO 11226's 10° either way, and the fixed stance pays for it
/// elsewhere — the placed feet's plan tires at least a quarter less and goes beyond no zone.
/// (Measured 2026-12-05: 0.61 × the fixed stance's total with the worker looking at the work; 0.18
/// before, when the placed worker held the part behind the trunk, unseen.)
/// (Without the zones, how far the placed worker's trunk twists is a near-tie — a twist of
/// 10–25° costs almost no fatigue — so it is not asserted.)
#[test]
fn turning_the_feet_removes_the_twist_of_a_side_transfer() {
    let fixed = side_transfer(true);
    let fixed_free_of_zones = plan(&fixed);
    let twist_fixed = max_twist_deg(&fixed, &fixed_free_of_zones);
    assert!(
        twist_fixed > 20.0,
        "with the feet fixed the side transfer twists the trunk {twist_fixed:.1}°: the test needs a task that does"
    );
    let zoned = |task: &Task| plan_task_with(task, crate::common::held(false)).unwrap();
    let fixed_plan = zoned(&fixed);
    let task = side_transfer(false);
    let plan = zoned(&task);
    let twist = max_twist_deg(&task, &plan);
    assert!(
        twist <= 10.5,
        "trunk twisted {twist:.1}° with the feet free to turn"
    );
    for ph in &plan.summary.phases {
        assert!(
            ph.outside_zones.is_empty(),
            "'{}' goes beyond a zone with the feet free: {:?}",
            ph.phase,
            ph.outside_zones
        );
    }
    assert!(
        plan.summary.total_u < 0.75 * fixed_plan.summary.total_u,
        "placed feet U {} against fixed {}",
        plan.summary.total_u,
        fixed_plan.summary.total_u
    );
    // the feet turn toward each side: left for the bin, right for the fixture
    let feet = |name: &str| {
        plan.summary
            .phases
            .iter()
            .find(|p| p.phase == name)
            .and_then(|p| p.feet.clone())
            .unwrap()
    };
    let heading =
        |f: &posture_opt::plan::stepping::PhaseFeet| (f.left.yaw_deg + f.right.yaw_deg) / 2.0;
    let (pick, place) = (feet("pick from bin"), feet("place in fixture"));
    assert!(
        heading(&pick) > heading(&place) + 30.0,
        "the feet face {:.0}° at the bin and {:.0}° at the fixture",
        heading(&pick),
        heading(&place)
    );
}

#[test]
fn stepping_reaches_what_standing_still_cannot() {
    use posture_opt::plan::reach::beyond_reach_m;
    let placed = side_transfer(false);
    let fixed = side_transfer(true);
    // the nearest target to the side the fixed stance provably cannot reach
    let side = (100..500)
        .map(|cm| Vector3::new(0.0, -(cm as f64) / 100.0, 1.0))
        .find(|t| beyond_reach_m(&fixed, 0, t).is_some())
        .unwrap();
    assert_eq!(
        beyond_reach_m(&placed, 0, &side),
        None,
        "{side:?} is out of reach from the fixed stance, not once the feet may step"
    );
    // the proof holds the farther foot; placed, a foot may come 0.5 m (the area) plus its
    // sole's reach beyond the nominal stance's nearer edge: 1 m farther is out of reach again
    let farther = side - Vector3::new(0.0, 1.0, 0.0);
    assert!(beyond_reach_m(&placed, 0, &farther).is_some());
}

/// The angle \[deg\] between the line of sight (docs/optimisation-problem.md: the head link's x
/// turned 15° down, from the eye point 0.8 radii forward of the head cylinder's middle) and the
/// direction to `target`, at posture `q`.
fn gaze_angle_deg(task: &Task, q: &[f64], target: &Vector3<f64>) -> f64 {
    let m = &task.model;
    let mut data = StaticsData::new(m, 0);
    posture_opt::body::forward_kinematics(m, &mut data, q);
    let head = m.frame_link("head").unwrap();
    let c = &m.links[head].capsules[0];
    let eye_local = (c.a.coords + c.b.coords) / 2.0 + Vector3::x() * 0.8 * c.radius_m;
    let (rot, _) = data.link_pose(m, head);
    let eye = data.link_point(m, head, &eye_local);
    let down = 15f64.to_radians();
    let sight = rot * Vector3::new(down.cos(), 0.0, -down.sin());
    sight.angle(&(target - eye)).to_degrees()
}

#[test]
fn the_head_looks_at_the_gaze_point() {
    let panel = Vector3::new(0.35, -0.15, 1.80);
    let yaml = |gaze: &str| {
        format!(
            "name: hold a panel overhead\n\
             worker: {{sex: male, stature_m: 1.75, mass_kg: 75.0}}\n\
             workstation:\n  obstacles:\n    - {{name: floor, plane: {{normal: [0, 0, 1]}}, position_m: [0, 0, 0]}}\n\
             phases:\n  - {{name: hold, target_m: [0.35, -0.15, 1.80], load_kg: 1.0, duration_s: 5.0{gaze}}}\n\
             rest_s: 5.0\ncycles: 20\n"
        )
    };
    let free = Task::from_yaml_str(&yaml(", gaze_free: true"), &root().join("look.yaml")).unwrap();
    assert_eq!(free.phases[0].gaze_m(), None);
    // without gaze_m the worker looks at the middle of the phase's hand targets, here the panel
    let looking = Task::from_yaml_str(&yaml(""), &root().join("look.yaml")).unwrap();
    assert_eq!(looking.phases[0].gaze_m(), Some(panel));
    let given = Task::from_yaml_str(
        &yaml(", gaze_m: [0.35, -0.15, 1.80]"),
        &root().join("look.yaml"),
    )
    .unwrap();
    assert_eq!(given.phases[0].gaze_m(), looking.phases[0].gaze_m());
    let (pf, pl) = (plan(&free), plan(&looking));
    let (af, al) = (
        gaze_angle_deg(&free, &pf.summary.phases[0].q_rad, &panel),
        gaze_angle_deg(&looking, &pl.summary.phases[0].q_rad, &panel),
    );
    assert!(
        af > 20.0,
        "without a gaze point the head does not look up at the panel ({af:.1}°): the test needs a case where it must"
    );
    assert!(
        al <= 15.0 + 1e-3,
        "the panel is {al:.2}° off the line of sight"
    );
    // looking up is the neck's and the trunk's work: the head tilts back
    let mut data = StaticsData::new(&looking.model, 0);
    let tilt = |t: &Task, q: &[f64], d: &mut StaticsData| {
        BodyAngles::measure(&t.model, d, q, None)
            .unwrap()
            .head_inclination_deg
    };
    let (hf, hl) = (
        tilt(&free, &pf.summary.phases[0].q_rad, &mut data),
        tilt(&looking, &pl.summary.phases[0].q_rad, &mut data),
    );
    assert!(
        hl < hf - 10.0,
        "head inclination {hl:.1}° looking, {hf:.1}° free"
    );
}

/// Signed distance \[m\] from `p` to the axis-aligned box at `centre` with half-extents `half`
/// (negative inside), in closed form.
fn point_box_m(p: &Vector3<f64>, centre: &Vector3<f64>, half: &Vector3<f64>) -> f64 {
    let d = (p - centre).abs() - half;
    let outside = d.map(|x| x.max(0.0)).norm();
    outside + d.max().min(0.0)
}

/// A box lifted low from a pallet by a worker free to step: the planner keeps the legs, pelvis,
/// trunk and head clear of the held box as of any obstacle, at the task's clearance (before the
/// held object entered the planner's clearances, this plan carried the box 46 mm into the left
/// shank and reported a collision). Checked by an independent distance: 400 points along each
/// capsule's axis to the box, in closed form.
#[test]
fn the_body_keeps_clear_of_a_held_box() {
    let text = "name: pallet lift
worker: {sex: male, stature_m: 1.755, mass_kg: 78.0, strength_percentile: 50}
workstation:
  obstacles:
    - {name: pallet, box: {size_m: [0.80, 1.20, 0.30]}, position_m: [0.80, -0.10, 0.15]}
    - {name: conveyor, box: {size_m: [0.60, 1.60, 0.90]}, position_m: [0.55, 0.95, 0.45]}
    - {name: floor, plane: {normal: [0, 0, 1]}, position_m: [0, 0, 0]}
phases:
  - {name: grasp at pallet, object: {center_m: [0.55, -0.10, 0.40], grip_width_m: 0.30, size_m: [0.40, 0.30, 0.20]}, load_kg: 0.0, duration_s: 2.0}
  - {name: lift from pallet, object: {center_m: [0.50, -0.10, 0.42], grip_width_m: 0.30, size_m: [0.40, 0.30, 0.20]}, load_kg: 8.0, duration_s: 2.0}
rest_s: 12.0
cycles: 10
stance: {area_m: [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]}
";
    let t = Task::from_yaml_str(text, &root().join("tasks/pallet_lift.yaml")).unwrap();
    let p = plan_task_with(&t, crate::common::held(false)).unwrap();
    assert!(p.problems().is_empty(), "{:?}", p.problems());
    let m = &t.model;
    let body = [
        "pelvis", "trunk", "head", "r_thigh", "r_shank", "r_foot", "l_thigh", "l_shank", "l_foot",
    ];
    let mut d = StaticsData::new(m, 0);
    for (ph, s) in t.phases.iter().zip(&p.summary.phases) {
        let o = ph.object.unwrap();
        let centre = Vector3::from(o.center_m);
        let half = Vector3::from(o.size_m) / 2.0;
        posture_opt::body::forward_kinematics(m, &mut d, &s.q_rad);
        let mut closest = (f64::INFINITY, "");
        for name in body {
            let l = m.links.iter().position(|x| x.name == name).unwrap();
            for c in &m.links[l].capsules {
                let (a, b) = (
                    d.link_point(m, l, &c.a.coords),
                    d.link_point(m, l, &c.b.coords),
                );
                for i in 0..=400 {
                    let x = a + (b - a) * (i as f64 / 400.0);
                    let dist = point_box_m(&x, &centre, &half) - c.radius_m;
                    if dist < closest.0 {
                        closest = (dist, name);
                    }
                }
            }
        }
        // the task's clearance (10 mm), less the solver's tolerance and the sampling's 1 mm
        assert!(
            closest.0 >= t.objective.clearance_m - 2e-3,
            "'{}': {} is {:.1} mm from the held box",
            ph.name,
            closest.1,
            1000.0 * closest.0
        );
    }
}

/// A cycle ends back on the rest stance, and the step cost counts that transition: the plan
/// reports it (`summary.rest_feet`, the feet where the rest posture puts them) and counts its
/// steps in the cycle's steps. Recounted here from the poses the plan reports: a foot steps when
/// its sole centre moves more than 3 cm or it turns more than 10° (docs/worker.md).
#[test]
fn the_way_back_to_rest_is_reported_and_counted() {
    let (task, plan) = placed();
    let s = &plan.summary;
    let back = s.rest_feet.as_ref().expect("the feet's way back to rest");
    // the rest posture's feet, from its forward kinematics
    let mut pw = PostureWork::new(task);
    pw.statics(task, &s.rest_posture_rad, &[Vector3::zeros(); 2]);
    let st = task.stance.as_ref().unwrap();
    let rest = FeetNow::at(&task.model, &pw.data, &st.feet);
    for i in 0..2 {
        let pose = if i == 0 { &back.left } else { &back.right };
        assert!((pose.sole_center_m[0] - rest.sole_center_m[i].x).abs() < 1e-9);
        assert!((pose.sole_center_m[1] - rest.sole_center_m[i].y).abs() < 1e-9);
    }
    let stepped = |a: &FootPose, b: &FootPose| {
        let d = ((a.sole_center_m[0] - b.sole_center_m[0]).powi(2)
            + (a.sole_center_m[1] - b.sole_center_m[1]).powi(2))
        .sqrt();
        let turn = ((a.yaw_deg - b.yaw_deg + 540.0) % 360.0 - 180.0).abs();
        u32::from(d > 0.03 || turn > 10.0)
    };
    let last = s.phases.last().unwrap().feet.as_ref().unwrap();
    assert_eq!(
        back.steps,
        stepped(&last.left, &back.left) + stepped(&last.right, &back.right)
    );
    assert!(back.steps > 0, "the test needs a plan that steps back");
    let into: u32 = s
        .phases
        .iter()
        .map(|p| p.feet.as_ref().unwrap().steps)
        .sum();
    assert_eq!(s.steps_per_cycle(), into + back.steps);
}
