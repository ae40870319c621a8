//! Standing on two feet (`posture_opt::body::stance`): the floor's reaction against sums and
//! rules worked out in this file, over random postures of the generated worker with random hand
//! loads.
//!
//! What is checked, and against what:
//! * the reactions (after `ground_reaction` and `settle_internal_force`) balance gravity and the
//!   hand loads exactly: forces and moments summed here, link by link (each link's weight at its
//!   centre of mass), not with the library's resultant;
//! * after the statics with the foot loads, the torques of the six unactuated pelvis joints vanish
//!   (the floor carries the body), and the `settle_internal_force` update equals a fresh
//!   `apply_loads` with the settled forces;
//! * the centre of pressure is the ratio of moments to vertical force computed here, each foot's
//!   vertical force is its share by the documented lever rule (projection of the centre of
//!   pressure on the segment between the sole centres, clamped), each foot's centre of pressure
//!   is its sole centre shifted by the part of the total one off that segment, each force points
//!   at the resultant's line of action at the height of the centre of mass (before settling);
//! * vertical foot forces are ≥ 0 whenever the centre of pressure is inside the support polygon;
//!   the polygon's margin against the rectangle worked out by hand;
//! * the centre of pressure on the left sole centre puts all the weight on the left foot, midway
//!   splits it in half, beyond the left foot clamps to the left foot;
//! * `settle_internal_force` minimises the sum of squared actuated torques along the internal
//!   force and changes no torque of a joint that carries no foot;
//! * `cop_jacobian` against central finite differences.
#![allow(clippy::needless_range_loop)]

use nalgebra::{Matrix2xX, Matrix3xX, Point3, Vector2, Vector3};
use posture_opt::body::stance::{
    Foot, GroundReaction, InternalWrench, Stance, cop_jacobian, foot_loads, ground_reaction,
    settle_internal_force,
};
use posture_opt::body::worker::{
    LEFT_FOOT_LINK, LEFT_HAND_FRAME, PELVIS_JOINTS, RIGHT_FOOT_LINK, RIGHT_HAND_FRAME, Worker,
    worker_geometry,
};
use posture_opt::body::{
    BodyModel, GRAVITY_M_S2, PointLoad, StaticsData, apply_loads, forward_kinematics, mass_moments,
};
use proptest::prelude::*;

struct Setup {
    m: BodyModel,
    stance: Stance,
    actuated: Vec<bool>,
    hands: [usize; 2],
}

fn setup() -> Setup {
    let m = BodyModel::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf"))
        .unwrap();
    let feet = [
        Foot::from_link(&m, LEFT_FOOT_LINK).unwrap(),
        Foot::from_link(&m, RIGHT_FOOT_LINK).unwrap(),
    ];
    let geo = worker_geometry(&Worker::MALE_50);
    // the feet under the hip joints, sole centres where q = 0 puts them
    let stance = Stance::new(feet, 2.0 * geo.hip_half_width_m, sole_centre_x(&m), 0.0);
    let actuated = (0..m.nq())
        .map(|k| !PELVIS_JOINTS.contains(&m.q_joint(k).name.as_str()))
        .collect();
    let hands = [
        m.frame_link(RIGHT_HAND_FRAME).unwrap(),
        m.frame_link(LEFT_HAND_FRAME).unwrap(),
    ];
    Setup {
        m,
        stance,
        actuated,
        hands,
    }
}

/// The sole centre of foot `link` (bottom face of its collision box) in the world, by hand from
/// the link's box.
fn sole_centre(m: &BodyModel, d: &StaticsData, link: usize) -> Vector3<f64> {
    let b = &m.links[link].boxes[0];
    let c = b.link_from_box * Point3::new(0.0, 0.0, -b.half_extents_m.z);
    d.link_point(m, link, &c.coords)
}

fn sole_centre_x(m: &BodyModel) -> f64 {
    let mut d = StaticsData::new(m, 0);
    forward_kinematics(m, &mut d, &vec![0.0; m.nq()]);
    sole_centre(m, &d, m.frame_link(LEFT_FOOT_LINK).unwrap()).x
}

/// Gravity and hand loads: (force, moment about the world origin), summed link by link.
fn external(s: &Setup, d: &StaticsData, hands: &[PointLoad]) -> (Vector3<f64>, Vector3<f64>) {
    let (mut f, mut mo) = (Vector3::zeros(), Vector3::zeros());
    for (l, link) in s.m.links.iter().enumerate() {
        let w = link.mass_kg * GRAVITY_M_S2;
        let c = d.link_point(&s.m, l, &link.com_m.coords);
        f += w;
        mo += c.cross(&w);
    }
    for h in hands {
        let p = d.link_point(&s.m, h.link, &h.point_in_link_m);
        f += h.force_n;
        mo += p.cross(&h.force_n) + h.moment_nm;
    }
    (f, mo)
}

struct Solved {
    d: StaticsData,
    before: GroundReaction,
    after: GroundReaction,
    wrench: InternalWrench,
    tau_before_settle: Vec<f64>,
}

/// The statics of a standing worker as the planner does them: kinematics, mass moments, ground
/// reaction, foot loads, loads applied, internal force settled.
fn solve(s: &Setup, q: &[f64], hands: &[PointLoad]) -> Solved {
    let m = &s.m;
    let mut d = StaticsData::new(m, 4);
    forward_kinematics(m, &mut d, q);
    mass_moments(m, &mut d);
    let r = ground_reaction(m, &d, &s.stance, hands, &GRAVITY_M_S2);
    let feet = foot_loads(m, &d, &s.stance, &r);
    let mut all = hands.to_vec();
    all.extend_from_slice(&feet);
    apply_loads(m, &mut d, &all, &GRAVITY_M_S2);
    let tau_before_settle = d.tau_nm.iter().copied().collect();
    let mut after = r;
    let mut scratch = Matrix3xX::zeros(m.nq());
    let wrench = settle_internal_force(m, &mut d, &s.stance, &mut after, &s.actuated, &mut scratch);
    Solved {
        d,
        before: r,
        after,
        wrench,
        tau_before_settle,
    }
}

/// Torques with hands and the given reaction applied afresh.
fn torques_with(s: &Setup, q: &[f64], hands: &[PointLoad], r: &GroundReaction) -> Vec<f64> {
    let mut d = StaticsData::new(&s.m, 4);
    forward_kinematics(&s.m, &mut d, q);
    mass_moments(&s.m, &mut d);
    let mut all = hands.to_vec();
    all.extend_from_slice(&foot_loads(&s.m, &d, &s.stance, r));
    apply_loads(&s.m, &mut d, &all, &GRAVITY_M_S2);
    d.tau_nm.iter().copied().collect()
}

/// Torques with hands, the given reaction and an extra internal wrench (`+dl e` force at
/// `at[0]` and `+dm` moment on the left foot, the opposite on the right at `at[1]`), applied
/// afresh.
#[allow(clippy::too_many_arguments)]
fn torques_with_extra(
    s: &Setup,
    q: &[f64],
    hands: &[PointLoad],
    r: &GroundReaction,
    at: [Vector3<f64>; 2],
    e: Vector3<f64>,
    dl: f64,
    dm: Vector2<f64>,
) -> Vec<f64> {
    let mut d = StaticsData::new(&s.m, 6);
    forward_kinematics(&s.m, &mut d, q);
    mass_moments(&s.m, &mut d);
    let mut all = hands.to_vec();
    all.extend_from_slice(&foot_loads(&s.m, &d, &s.stance, r));
    for (i, sign) in [(0usize, 1.0), (1usize, -1.0)] {
        let link = s.stance.feet[i].link;
        let (rot, pos) = d.link_pose(&s.m, link);
        all.push(PointLoad {
            link,
            point_in_link_m: rot.transpose() * (at[i] - pos),
            force_n: sign * dl * e,
            moment_nm: sign * Vector3::new(dm.x, dm.y, 0.0),
        });
    }
    apply_loads(&s.m, &mut d, &all, &GRAVITY_M_S2);
    d.tau_nm.iter().copied().collect()
}

/// Where a point lies in a foot's sole: (along the sole, across it), from its centre, by hand
/// from the link's pose and box.
fn in_sole(m: &BodyModel, d: &StaticsData, link: usize, p: &Vector3<f64>) -> Vector2<f64> {
    let (rot, _) = d.link_pose(m, link);
    let o = p - sole_centre(m, d, link);
    let u = Vector2::new(rot[(0, 0)], rot[(1, 0)]).normalize();
    let v = Vector2::new(rot[(0, 1)], rot[(1, 1)]).normalize();
    Vector2::new(o.xy().dot(&u), o.xy().dot(&v))
}

/// A posture from numbers in 0..1: pelvis translations within ±5 cm (height −20..+5 cm), every
/// other joint within its range.
fn posture(m: &BodyModel, u: &[f64]) -> Vec<f64> {
    (0..m.nq())
        .map(|k| {
            let j = m.q_joint(k);
            let x = u[k % u.len()];
            match j.name.as_str() {
                "pelvis_tx" | "pelvis_ty" => -0.05 + 0.1 * x,
                "pelvis_tz" => -0.2 + 0.25 * x,
                _ => j.lower_rad + x * (j.upper_rad - j.lower_rad),
            }
        })
        .collect()
}

fn hand_loads(s: &Setup, r: &[f64]) -> Vec<PointLoad> {
    (0..2)
        .map(|h| PointLoad {
            link: s.hands[h],
            point_in_link_m: 0.02 * Vector3::new(r[9 * h], r[9 * h + 1], r[9 * h + 2]),
            // mostly downward: a carried load, pushed and pulled
            force_n: Vector3::new(
                60.0 * r[9 * h + 3],
                60.0 * r[9 * h + 4],
                -100.0 - 100.0 * r[9 * h + 5],
            ),
            moment_nm: 5.0 * Vector3::new(r[9 * h + 6], r[9 * h + 7], r[9 * h + 8]),
        })
        .collect()
}

/// Everything about one solved posture that holds for any posture and loads.
fn check_standing(s: &Setup, q: &[f64], hands: &[PointLoad]) -> Result<(), TestCaseError> {
    let m = &s.m;
    let sv = solve(s, q, hands);
    let (d, r0, r) = (&sv.d, &sv.before, &sv.after);
    let (f_ext, m_ext) = external(s, d, hands);
    let weight = f_ext.norm();
    prop_assert!(r.supported, "downward loads: the floor carries the body");

    // balance, summed here: Σ F = 0, Σ M = 0 about the world origin
    let mut f = f_ext;
    let mut mo = m_ext;
    for i in 0..2 {
        f += r.force_n[i];
        mo += r.cop_m[i].cross(&r.force_n[i]) + Vector3::new(0.0, 0.0, r.free_moment_nm[i]);
    }
    prop_assert!(f.norm() < 1e-9 * weight, "Σ F = {f}");
    prop_assert!(mo.norm() < 1e-9 * weight, "Σ M = {mo}");

    // the unactuated pelvis joints hold nothing
    for k in 0..m.nq() {
        if !s.actuated[k] {
            prop_assert!(
                d.tau_nm[k].abs() < 1e-8 * weight,
                "{}: τ = {} after the statics",
                m.q_joint(k).name,
                d.tau_nm[k]
            );
        }
    }
    // settling updated the torques as a fresh apply_loads with the settled forces does
    let fresh = torques_with(s, q, hands, r);
    for k in 0..m.nq() {
        prop_assert!(
            (fresh[k] - d.tau_nm[k]).abs() < 1e-9 * weight,
            "{}: settled τ {} vs recomputed {}",
            m.q_joint(k).name,
            d.tau_nm[k],
            fresh[k]
        );
    }

    // the centre of pressure: the moment ratio of the reaction (−external)
    let (fg, mg) = (-f_ext, -m_ext);
    let p = Vector2::new(-mg.y / fg.z, mg.x / fg.z);
    prop_assert!(
        (r.cop_total_m - p).norm() < 1e-12,
        "CoP {} vs {p}",
        r.cop_total_m
    );
    // the free moment: what the vertical-axis moment leaves after p × F
    let t_z = mg.z - (p.x * fg.y - p.y * fg.x);
    prop_assert!((r0.free_moment_nm[0] + r0.free_moment_nm[1] - t_z).abs() < 1e-9 * weight);

    // the lever rule
    let cl = sole_centre(m, d, s.stance.feet[0].link);
    let cr = sole_centre(m, d, s.stance.feet[1].link);
    let (cl2, cr2) = (cl.xy(), cr.xy());
    let share = ((p - cr2).dot(&(cl2 - cr2)) / (cl2 - cr2).norm_squared()).clamp(0.0, 1.0);
    prop_assert!(
        (r.left_share - share).abs() < 1e-12,
        "share {} vs {share}",
        r.left_share
    );
    prop_assert!((r.force_n[0].z - share * fg.z).abs() < 1e-9 * weight);
    prop_assert!((r.force_n[1].z - (1.0 - share) * fg.z).abs() < 1e-9 * weight);
    prop_assert!((r0.free_moment_nm[0] - share * t_z).abs() < 1e-9 * weight);
    let delta = p - (share * cl2 + (1.0 - share) * cr2);
    for (i, c) in [cl2, cr2].iter().enumerate() {
        let pi = Vector3::new(c.x + delta.x, c.y + delta.y, 0.0);
        prop_assert!(
            (r0.cop_m[i] - pi).norm() < 1e-12,
            "foot {i} CoP {} vs {pi}",
            r0.cop_m[i]
        );
    }
    // before settling each force points at A = p + F h/F_z, h the CoM height
    let h = d.com_m.z.max(0.05);
    let apex = Vector3::new(p.x, p.y, 0.0) + fg * (h / fg.z);
    for i in 0..2 {
        let expect = [share, 1.0 - share][i] * fg.z * (apex - r0.cop_m[i]) / h;
        prop_assert!(
            (r0.force_n[i] - expect).norm() < 1e-9 * weight,
            "foot {i}: {} vs {expect}",
            r0.force_n[i]
        );
    }
    // settling adds ±λe, e horizontal from the right sole to the left one
    let e = Vector3::new(cl.x - cr.x, cl.y - cr.y, 0.0).normalize();
    let w = sv.wrench;
    prop_assert!((r.force_n[0] - r0.force_n[0] - w.lambda_n * e).norm() < 1e-9 * weight);
    prop_assert!((r.force_n[1] - r0.force_n[1] + w.lambda_n * e).norm() < 1e-9 * weight);
    // and the moments ±m move each foot's centre of pressure by σ(−m_y, m_x)/F_z, on its sole
    // (or no farther off it than before); when the soles bound the moments, one bound is met
    let mut on_edge = r.force_n.iter().any(|f| f.z <= 0.0);
    for (i, sigma) in [(0usize, 1.0), (1usize, -1.0)] {
        let link = s.stance.feet[i].link;
        let fz = r.force_n[i].z;
        let shift = if fz > 0.0 {
            sigma * Vector3::new(-w.moment_nm.y, w.moment_nm.x, 0.0) / fz
        } else {
            Vector3::zeros()
        };
        prop_assert!((r.cop_m[i] - r0.cop_m[i] - shift).norm() < 1e-9);
        let (before, after) = (
            in_sole(m, d, link, &r0.cop_m[i]),
            in_sole(m, d, link, &r.cop_m[i]),
        );
        let foot = &s.stance.feet[i];
        for (a, half) in [(0, foot.half_length_m), (1, foot.half_width_m)] {
            let bound = half.max(before[a].abs());
            prop_assert!(
                after[a].abs() <= bound + 1e-9,
                "foot {i} axis {a}: CoP {} off the sole ({bound})",
                after[a]
            );
            on_edge |= (after[a].abs() - bound).abs() < 1e-9;
        }
    }
    prop_assert!((0.0..=1.0).contains(&w.sole_factor));
    if w.sole_factor < 1.0 {
        prop_assert!(
            on_edge,
            "moments cut to {} with no sole edge met and both feet loaded",
            w.sole_factor
        );
    }

    // vertical forces ≥ 0 inside the support polygon
    if r.margin_m >= 0.0 {
        prop_assert!(r.force_n[0].z >= 0.0 && r.force_n[1].z >= 0.0);
    }

    // the foot loads sit at the feet's centres of pressure, with the free moments
    let fl = foot_loads(m, d, &s.stance, r);
    for i in 0..2 {
        prop_assert_eq!(fl[i].link, s.stance.feet[i].link);
        let pw = d.link_point(m, fl[i].link, &fl[i].point_in_link_m);
        prop_assert!((pw - r.cop_m[i]).norm() < 1e-12);
        prop_assert_eq!(fl[i].force_n, r.force_n[i]);
        prop_assert_eq!(fl[i].moment_nm, Vector3::new(0.0, 0.0, r.free_moment_nm[i]));
    }

    // settling: the sum of squared actuated torques is least along λ (applied at the centres of
    // pressure before settling, as documented), and, when the soles allow the least-effort
    // moments, along every moment too; joints that carry no foot keep their
    // torques
    let cost = |tau: &[f64]| -> f64 {
        tau.iter()
            .zip(&s.actuated)
            .filter(|(_, a)| **a)
            .map(|(t, _)| t * t)
            .sum()
    };
    let settled: Vec<f64> = d.tau_nm.iter().copied().collect();
    let c0 = cost(&settled);
    let mut moves = vec![];
    for step in [-1.0, -1e-2, 1e-2, 1.0] {
        moves.push((step, Vector2::zeros()));
        if w.sole_factor == 1.0 {
            moves.push((0.0, Vector2::new(step, 0.0)));
            moves.push((0.0, Vector2::new(0.0, step)));
            moves.push((step, Vector2::new(step, -step)));
        }
    }
    for (dl, dm) in moves {
        let c = cost(&torques_with_extra(s, q, hands, r, r0.cop_m, e, dl, dm));
        prop_assert!(
            c >= c0 - 1e-9 * c0.max(1.0),
            "λ{dl:+}, m{dm:?}: cost {c} < settled {c0}"
        );
    }
    let legs = ["hip", "knee", "ankle"];
    for k in 0..m.nq() {
        let name = &m.q_joint(k).name;
        if s.actuated[k] && !legs.iter().any(|l| name.contains(l)) {
            prop_assert!(
                (settled[k] - sv.tau_before_settle[k]).abs() < 1e-9 * weight,
                "{name} changed by settling: {} → {}",
                sv.tau_before_settle[k],
                settled[k]
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn the_floor_balances_random_postures_with_hand_loads(
        u in prop::collection::vec(0.0f64..1.0, 38),
        r in prop::collection::vec(-1.0f64..1.0, 18),
    ) {
        let s = setup();
        let q = posture(&s.m, &u);
        let hands = hand_loads(&s, &r);
        check_standing(&s, &q, &hands)?;
        check_standing(&s, &q, &[])?;
    }

    #[test]
    fn cop_jacobian_matches_finite_differences(
        u in prop::collection::vec(0.0f64..1.0, 38),
        r in prop::collection::vec(-1.0f64..1.0, 18),
    ) {
        let s = setup();
        let m = &s.m;
        let q = posture(m, &u);
        let hands = hand_loads(&s, &r);
        let cop = |q: &[f64]| {
            let mut d = StaticsData::new(m, 4);
            forward_kinematics(m, &mut d, q);
            mass_moments(m, &mut d);
            ground_reaction(m, &d, &s.stance, &hands, &GRAVITY_M_S2).cop_total_m
        };
        let sv = solve(&s, &q, &hands);
        let mut jac = Matrix3xX::zeros(m.nq());
        let mut out = Matrix2xX::zeros(m.nq());
        cop_jacobian(m, &sv.d, &hands, &GRAVITY_M_S2, &mut jac, &mut out);
        let h = 1e-6;
        for k in 0..m.nq() {
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[k] += h;
            qm[k] -= h;
            let fd = (cop(&qp) - cop(&qm)) / (2.0 * h);
            prop_assert!((out.column(k) - fd).norm() < 1e-7,
                "∂CoP/∂{}: {} vs finite differences {fd}", m.q_joint(k).name, out.column(k));
        }
    }
}

/// Upright and symmetric, no hand load: each foot carries half the weight, the centre of
/// pressure is under the centre of mass, the margin is its distance to the polygon's nearest
/// edge (a rectangle here: feet side by side, not turned out).
#[test]
fn standing_upright_splits_the_weight_in_half() {
    let s = setup();
    let m = &s.m;
    let q = vec![0.0; m.nq()];
    let sv = solve(&s, &q, &[]);
    let r = &sv.after;
    let w = m.total_mass_kg() * 9.81;
    assert!((r.left_share - 0.5).abs() < 1e-12, "{}", r.left_share);
    assert!((r.force_n[0].z - w / 2.0).abs() < 1e-9 && (r.force_n[1].z - w / 2.0).abs() < 1e-9);
    assert!((r.cop_total_m - sv.d.com_m.xy()).norm() < 1e-12);
    // the rectangle: soles 2·half_length long, from −(width/2 + half_width) to +(...)
    let foot = s.stance.feet[0];
    let geo = worker_geometry(&Worker::MALE_50);
    let x0 = sole_centre_x(m);
    let y_edge = geo.hip_half_width_m + foot.half_width_m;
    let p = r.cop_total_m;
    let by_hand = (foot.half_length_m - (p.x - x0).abs()).min(y_edge - p.y.abs());
    assert!(
        (r.margin_m - by_hand).abs() < 1e-12,
        "{} vs {by_hand}",
        r.margin_m
    );
    assert!(r.margin_m > 0.0);
    // left and right forces mirror each other
    let f = r.force_n;
    assert!((f[0].x - f[1].x).abs() < 1e-9 && (f[0].y + f[1].y).abs() < 1e-9);
    // and the pelvis is free
    for k in 0..6 {
        assert!(sv.d.tau_nm[k].abs() < 1e-9, "{}", sv.d.tau_nm[k]);
    }
}

/// A pure moment at the right hand puts the centre of pressure where it is wanted (a moment
/// about x shifts it sideways, about y back and forth): on the left sole centre all the weight
/// goes left, midway it splits in half, past the left foot it stays on the left foot.
#[test]
fn the_split_follows_the_centre_of_pressure() {
    let s = setup();
    let m = &s.m;
    let q = vec![0.0; m.nq()];
    let mut d = StaticsData::new(m, 4);
    forward_kinematics(m, &mut d, &q);
    mass_moments(m, &mut d);
    let (f0, m0) = external(&s, &d, &[]);
    let fz = -f0.z;
    let cl = sole_centre(m, &d, s.stance.feet[0].link).xy();
    let cr = sole_centre(m, &d, s.stance.feet[1].link).xy();
    // the hand moment that moves the centre of pressure to `target`:
    // p = (−M_y/F_z, M_x/F_z) with M = −(m0 + M_h)
    let moment_for =
        |target: Vector2<f64>| Vector3::new(-m0.x - target.y * fz, -m0.y + target.x * fz, 0.0);
    for (target, share) in [
        (cl, 1.0),
        (cr, 0.0),
        ((cl + cr) / 2.0, 0.5),
        (cl + 0.75 * (cr - cl), 0.25),
        (cl + 0.5 * (cl - cr), 1.0),
        (cr + Vector2::new(0.05, -0.3), 0.0),
    ] {
        let hand = [PointLoad {
            link: s.hands[0],
            point_in_link_m: Vector3::zeros(),
            force_n: Vector3::zeros(),
            moment_nm: moment_for(target),
        }];
        let sv = solve(&s, &q, &hand);
        let r = &sv.after;
        assert!(
            (r.cop_total_m - target).norm() < 1e-12,
            "{} vs {target}",
            r.cop_total_m
        );
        assert!(
            (r.left_share - share).abs() < 1e-12,
            "{target}: share {}",
            r.left_share
        );
        assert!((r.force_n[0].z - share * fz).abs() < 1e-9);
        assert!((r.force_n[1].z - (1.0 - share) * fz).abs() < 1e-9);
        if share == 1.0 {
            // all on the left, at the centre of pressure itself
            assert!((r.cop_m[0].xy() - target).norm() < 1e-12);
        }
        // the pelvis holds nothing whatever the split
        for k in 0..6 {
            assert!(sv.d.tau_nm[k].abs() < 1e-8, "{target}: {}", sv.d.tau_nm[k]);
        }
    }
}

/// A hand load that lifts the body: no stance can hold it, said so, no panic.
#[test]
fn a_lifting_load_is_not_supported() {
    let s = setup();
    let m = &s.m;
    let q = vec![0.0; m.nq()];
    let lift = [PointLoad::force_at(
        s.hands[0],
        Vector3::new(0.0, 0.0, 2.0 * m.total_mass_kg() * 9.81),
    )];
    let sv = solve(&s, &q, &lift);
    assert!(!sv.after.supported);
    assert!(
        sv.after
            .force_n
            .iter()
            .all(|f| f.iter().all(|x| x.is_finite()))
    );
}
