//! The generated worker (`posture_opt::body::worker_urdf`) and its population strength
//! (`robots/worker.strength.yaml` through `posture_opt::body::strength`), against the published
//! tables, copied here with their citations:
//!
//! * segment masses, lengths and centres of mass: de Leva P (1996) Adjustments to
//!   Zatsiorsky-Seluyanov's segment inertia parameters. J Biomech 29(9):1223-1230, Table 4;
//! * joint ranges: AAOS (1965) Joint Motion: Method of Measuring and Recording, as reprinted in
//!   Greene WB, Heckman JD (1994) The Clinical Measurement of Joint Motion, AAOS;
//! * strength means and SDs: the sources named per row below (the table's `source` lines), and the
//!   rule MVC(p) = mean + z(p)·SD with z(0.05) = −1.6448536, z(0.5) = 0, z(0.95) = +1.6448536
//!   (standard normal quantiles, from tables, not computed by the code under test).
#![allow(clippy::needless_range_loop)]

use nalgebra::Vector3;
use posture_opt::body::strength::HalfJoint;
use posture_opt::body::worker::{JOINTS, PELVIS_JOINTS, RANGES_DEG};
use posture_opt::body::{
    BodyModel, Direction, GRAVITY_M_S2, Sex, StaticsData, StrengthTable, Worker,
    forward_kinematics, holding_torques, mass_moments, resolve_half_joints, worker_urdf,
};

const Z95: f64 = 1.6448536269514722;

fn worker(sex: Sex, stature_m: f64, mass_kg: f64, strength_percentile: f64) -> Worker {
    Worker {
        sex,
        stature_m,
        mass_kg,
        strength_percentile,
    }
}

/// P5, P50 and P95 men and women (stature, body mass), near the US Army ANSUR II (2012)
/// percentiles; the properties below hold for any worker, these only span the population.
fn population() -> Vec<(&'static str, Worker)> {
    vec![
        ("P5 man", worker(Sex::Male, 1.647, 61.6, 5.0)),
        ("P50 man", worker(Sex::Male, 1.755, 78.0, 50.0)),
        ("P95 man", worker(Sex::Male, 1.867, 104.0, 95.0)),
        ("P5 woman", worker(Sex::Female, 1.528, 49.5, 5.0)),
        ("P50 woman", worker(Sex::Female, 1.629, 65.0, 50.0)),
        ("P95 woman", worker(Sex::Female, 1.737, 88.0, 95.0)),
    ]
}

fn generate(w: &Worker) -> BodyModel {
    let text = worker_urdf(w, &StrengthTable::default_table()).unwrap();
    BodyModel::from_urdf_str(&text, "generated").unwrap()
}

// ---------------------------------------------------------------------------------------------
// de Leva (1996) Table 4: mass (% of body mass), CM (% of segment length from the first endpoint
// named), segment length (mm) of the reference subjects; stature 1741 mm (men), 1735 mm (women).
// ---------------------------------------------------------------------------------------------

struct Seg {
    mass_pct: f64,
    cm_pct: f64,
    len_mm: f64,
}

struct DeLeva {
    stature_mm: f64,
    head: Seg,         // VERT–CERV (vertex to C7), CM from VERT
    upper_trunk: Seg,  // SUPR–XIPH, CM from SUPR
    middle_trunk: Seg, // XIPH–OMPH, CM from XIPH
    lower_trunk: Seg,  // OMPH–MIDH, CM from OMPH
    upper_arm: Seg,    // SJC–EJC
    forearm: Seg,      // EJC–WJC
    hand: Seg,         // WJC–MET3
    thigh: Seg,        // HJC–KJC
    shank: Seg,        // KJC–LMAL
    foot: Seg,         // HEEL–TTIP, CM from HEEL
}

const fn s(mass_pct: f64, cm_pct: f64, len_mm: f64) -> Seg {
    Seg {
        mass_pct,
        cm_pct,
        len_mm,
    }
}

const MEN: DeLeva = DeLeva {
    stature_mm: 1741.0,
    head: s(6.94, 50.02, 242.9),
    upper_trunk: s(15.96, 29.99, 170.7),
    middle_trunk: s(16.33, 45.02, 215.5),
    lower_trunk: s(11.17, 61.15, 145.7),
    upper_arm: s(2.71, 57.72, 281.7),
    forearm: s(1.62, 45.74, 268.9),
    hand: s(0.61, 79.00, 86.2),
    thigh: s(14.16, 40.95, 422.2),
    shank: s(4.33, 44.59, 434.0),
    foot: s(1.37, 44.15, 258.1),
};

const WOMEN: DeLeva = DeLeva {
    stature_mm: 1735.0,
    head: s(6.68, 48.41, 243.7),
    upper_trunk: s(15.45, 20.77, 142.5),
    middle_trunk: s(14.65, 45.12, 205.3),
    lower_trunk: s(12.47, 49.20, 181.5),
    upper_arm: s(2.55, 57.54, 275.1),
    forearm: s(1.38, 45.59, 264.3),
    hand: s(0.56, 74.74, 78.0),
    thigh: s(14.78, 36.12, 368.5),
    shank: s(4.81, 44.16, 432.3),
    foot: s(1.29, 40.14, 228.3),
};

fn table(sex: Sex) -> &'static DeLeva {
    match sex {
        Sex::Male => &MEN,
        Sex::Female => &WOMEN,
    }
}

/// The URDF prints masses to 0.1 g, positions to 0.01 mm, box sizes and capsule radii and
/// lengths to 0.1 mm.
const MASS_TOL: f64 = 6e-5;
const POS_TOL: f64 = 3e-5;
const SHAPE_TOL: f64 = 1.2e-4;

struct Posed {
    m: BodyModel,
    d: StaticsData,
}

impl Posed {
    fn at_zero(w: &Worker) -> Self {
        let m = generate(w);
        let mut d = StaticsData::new(&m, 0);
        forward_kinematics(&m, &mut d, &vec![0.0; m.nq()]);
        mass_moments(&m, &mut d);
        Posed { m, d }
    }
    fn link(&self, name: &str) -> usize {
        self.m.frame_link(name).unwrap()
    }
    fn mass(&self, name: &str) -> f64 {
        self.m.links[self.link(name)].mass_kg
    }
    /// World origin of a joint (its child link's frame).
    fn joint_at(&self, joint: &str) -> Vector3<f64> {
        self.d.link_pose(&self.m, self.link(joint)).1
    }
    fn com(&self, name: &str) -> Vector3<f64> {
        let l = self.link(name);
        self.d.link_point(&self.m, l, &self.m.links[l].com_m.coords)
    }
}

#[test]
fn total_mass_is_the_workers() {
    for (who, w) in population() {
        let p = Posed::at_zero(&w);
        // de Leva's women's percentages add up to 99.99 %, the men's to 100.00 %
        let pct = match w.sex {
            Sex::Male => 100.0,
            Sex::Female => 99.99,
        };
        let expect = w.mass_kg * pct / 100.0;
        assert!(
            (p.m.total_mass_kg() - expect).abs() < 13.0 * MASS_TOL,
            "{who}: {} kg vs {expect}",
            p.m.total_mass_kg()
        );
        assert!((p.m.total_mass_kg() - w.mass_kg).abs() <= 1e-4 * w.mass_kg + 13.0 * MASS_TOL);
    }
}

#[test]
fn segment_masses_lengths_and_centres_of_mass_follow_de_leva() {
    for (who, w) in population() {
        let t = table(w.sex);
        let p = Posed::at_zero(&w);
        let k = w.stature_m / (t.stature_mm / 1000.0);
        let len = |g: &Seg| g.len_mm / 1000.0 * k;
        let mass = |g: &Seg| g.mass_pct / 100.0 * w.mass_kg;
        let near = |a: f64, b: f64, tol: f64, what: &str| {
            assert!((a - b).abs() < tol, "{who}: {what}: {a} vs de Leva {b}");
        };
        near(p.mass("head"), mass(&t.head), MASS_TOL, "head mass");
        near(
            p.mass("trunk"),
            mass(&t.upper_trunk) + mass(&t.middle_trunk),
            MASS_TOL,
            "trunk (upper + middle) mass",
        );
        near(
            p.mass("pelvis"),
            mass(&t.lower_trunk),
            MASS_TOL,
            "pelvis (lower trunk) mass",
        );
        for side in ["r_", "l_"] {
            for (link, g) in [
                ("upper_arm", &t.upper_arm),
                ("forearm", &t.forearm),
                ("hand", &t.hand),
                ("thigh", &t.thigh),
                ("shank", &t.shank),
                ("foot", &t.foot),
            ] {
                near(
                    p.mass(&format!("{side}{link}")),
                    mass(g),
                    MASS_TOL,
                    &format!("{side}{link} mass"),
                );
            }
            let at = |j: &str| p.joint_at(&format!("{side}{j}"));
            // lengths between joint centres, upright at q = 0
            let (sh, el, wr) = (
                at("shoulder_flexion"),
                at("elbow_flexion"),
                at("wrist_flexion"),
            );
            let (hip, knee, ankle) = (
                at("hip_flexion"),
                at("knee_flexion"),
                at("ankle_dorsiflexion"),
            );
            near(
                (sh - el).norm(),
                len(&t.upper_arm),
                POS_TOL,
                "upper arm length",
            );
            near((el - wr).norm(), len(&t.forearm), POS_TOL, "forearm length");
            near((hip - knee).norm(), len(&t.thigh), POS_TOL, "thigh length");
            near(
                (knee - ankle).norm(),
                len(&t.shank),
                POS_TOL,
                "shank length",
            );
            // segments hang straight down; CM at its fraction from the proximal end
            let com = |l: &str| p.com(&format!("{side}{l}"));
            near(
                com("upper_arm").z,
                sh.z - t.upper_arm.cm_pct / 100.0 * len(&t.upper_arm),
                POS_TOL,
                "upper arm CM",
            );
            near(
                com("forearm").z,
                el.z - t.forearm.cm_pct / 100.0 * len(&t.forearm),
                POS_TOL,
                "forearm CM",
            );
            near(
                com("hand").z,
                wr.z - t.hand.cm_pct / 100.0 * len(&t.hand),
                POS_TOL,
                "hand CM",
            );
            near(
                com("thigh").z,
                hip.z - t.thigh.cm_pct / 100.0 * len(&t.thigh),
                POS_TOL,
                "thigh CM",
            );
            near(
                com("shank").z,
                knee.z - t.shank.cm_pct / 100.0 * len(&t.shank),
                POS_TOL,
                "shank CM",
            );
            // the foot: a box heel to toe tip, CM from the heel
            let f = p.link(&format!("{side}foot"));
            let b = p.m.links[f].boxes[0];
            near(
                2.0 * b.half_extents_m.x,
                len(&t.foot),
                SHAPE_TOL,
                "foot length",
            );
            let heel_x =
                p.d.link_point(
                    &p.m,
                    f,
                    &(b.link_from_box * nalgebra::Point3::new(-b.half_extents_m.x, 0.0, 0.0))
                        .coords,
                )
                .x;
            near(
                com("foot").x,
                heel_x + t.foot.cm_pct / 100.0 * len(&t.foot),
                SHAPE_TOL,
                "foot CM",
            );
        }
        // head and trunk: C7 (the neck joint) one head length below the vertex, which is at
        // stature height; trunk segments stacked from the hip joint centres (MIDH) up
        let c7 = p.joint_at("neck_flexion");
        near(c7.z, w.stature_m - len(&t.head), POS_TOL, "C7 height");
        near(
            p.com("head").z,
            w.stature_m - t.head.cm_pct / 100.0 * len(&t.head),
            POS_TOL,
            "head CM",
        );
        let midh = (p.joint_at("r_hip_flexion") + p.joint_at("l_hip_flexion")) / 2.0;
        let omph = midh.z + len(&t.lower_trunk);
        let xiph = omph + len(&t.middle_trunk);
        let supr = xiph + len(&t.upper_trunk);
        near(
            p.com("pelvis").z,
            omph - t.lower_trunk.cm_pct / 100.0 * len(&t.lower_trunk),
            POS_TOL,
            "lower trunk CM",
        );
        let (mu, mm) = (t.upper_trunk.mass_pct, t.middle_trunk.mass_pct);
        let trunk_cm = (mu * (supr - t.upper_trunk.cm_pct / 100.0 * len(&t.upper_trunk))
            + mm * (xiph - t.middle_trunk.cm_pct / 100.0 * len(&t.middle_trunk)))
            / (mu + mm);
        near(p.com("trunk").z, trunk_cm, POS_TOL, "trunk CM");
        // the shoulders sit below SUPR (an assumption of the generator, 1.8 % of stature)
        let sh = p.joint_at("r_shoulder_flexion");
        assert!(
            sh.z < supr && sh.z > supr - 0.05 * w.stature_m,
            "{who}: shoulder {} vs SUPR {supr}",
            sh.z
        );
    }
}

#[test]
fn stature_is_the_head_top_and_the_feet_stand_flat_on_the_floor() {
    for (who, w) in population() {
        let p = Posed::at_zero(&w);
        // the head's top: its collision capsule's highest point
        let h = p.link("head");
        let top = p.m.links[h]
            .capsules
            .iter()
            .flat_map(|c| [c.a, c.b].map(|e| p.d.link_point(&p.m, h, &e.coords).z + c.radius_m))
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            (top - w.stature_m).abs() < SHAPE_TOL,
            "{who}: head top {top} vs stature {}",
            w.stature_m
        );
        // nothing is higher than the head
        for (l, link) in p.m.links.iter().enumerate() {
            for c in &link.capsules {
                for e in [c.a, c.b] {
                    assert!(
                        p.d.link_point(&p.m, l, &e.coords).z + c.radius_m <= top + 1e-9,
                        "{who}: {}",
                        link.name
                    );
                }
            }
        }
        for foot in ["r_foot", "l_foot"] {
            let f = p.link(foot);
            let (rot, _) = p.d.link_pose(&p.m, f);
            let b = p.m.links[f].boxes[0];
            let box_rot = rot * b.link_from_box.rotation.to_rotation_matrix().matrix();
            assert!(
                (box_rot - nalgebra::Matrix3::identity()).norm() < 1e-12,
                "{who}: {foot} is level"
            );
            for (sx, sy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                let corner = b.link_from_box
                    * nalgebra::Point3::new(
                        sx * b.half_extents_m.x,
                        sy * b.half_extents_m.y,
                        -b.half_extents_m.z,
                    );
                let z = p.d.link_point(&p.m, f, &corner.coords).z;
                assert!(z.abs() < SHAPE_TOL, "{who}: {foot} sole corner at z = {z}");
            }
        }
    }
}

/// Mirror image: with every left joint at its right twin's angle and the trunk, neck and pelvis
/// moved only in the sagittal plane, each left link is the right one reflected in the x-z plane,
/// each midline link stays on it, and the twins hold the same torques.
#[test]
fn the_left_side_mirrors_the_right() {
    let sagittal = [
        "pelvis_tx",
        "pelvis_tz",
        "pelvis_tilt",
        "lumbar_flexion",
        "neck_flexion",
    ];
    for (who, w) in population() {
        let m = generate(&w);
        let mut q = vec![0.0; m.nq()];
        for k in 0..m.nq() {
            let name = m.q_joint(k).name.clone();
            // a fixed pseudo-random angle per joint name, inside the joint's range
            let h = name
                .trim_start_matches("r_")
                .trim_start_matches("l_")
                .bytes()
                .fold(7u64, |a, b| a.wrapping_mul(31).wrapping_add(b as u64));
            let u = (h % 1000) as f64 / 1000.0;
            let j = m.q_joint(k);
            if name.starts_with("r_") || name.starts_with("l_") || sagittal.contains(&name.as_str())
            {
                q[k] = if j.kind == posture_opt::body::JointKind::Prismatic {
                    0.1 * (u - 0.5)
                } else {
                    j.lower_rad + u * (j.upper_rad - j.lower_rad)
                };
            }
        }
        let mut d = StaticsData::new(&m, 0);
        holding_torques(&m, &mut d, &q, &[], &GRAVITY_M_S2);
        let mirror = |v: Vector3<f64>| Vector3::new(v.x, -v.y, v.z);
        for (l, link) in m.links.iter().enumerate() {
            let (rot, pos) = d.link_pose(&m, l);
            if let Some(rest) = link.name.strip_prefix("r_") {
                let twin = m.frame_link(&format!("l_{rest}")).unwrap();
                let (rot2, pos2) = d.link_pose(&m, twin);
                assert!(
                    (pos2 - mirror(pos)).norm() < 1e-12,
                    "{who}: {} at {pos2} vs mirror {}",
                    m.links[twin].name,
                    mirror(pos)
                );
                assert_eq!(m.links[twin].mass_kg, link.mass_kg);
                let com = d.link_point(&m, l, &link.com_m.coords);
                let com2 = d.link_point(&m, twin, &m.links[twin].com_m.coords);
                assert!(
                    (com2 - mirror(com)).norm() < 1e-12,
                    "{who}: CoM of {}",
                    m.links[twin].name
                );
                // orientation: reflected, R' = S R S with S = diag(1, −1, 1)
                let sm = nalgebra::Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, 1.0));
                assert!(
                    (rot2 - sm * rot * sm).norm() < 1e-12,
                    "{who}: {} orientation",
                    m.links[twin].name
                );
            } else if !link.name.starts_with("l_") {
                assert!(pos.y.abs() < 1e-12, "{who}: {} off the midline", link.name);
            }
        }
        assert!(d.com_m.y.abs() < 1e-12);
        for k in 0..m.nq() {
            let name = &m.q_joint(k).name;
            if let Some(rest) = name.strip_prefix("r_") {
                let twin = m.q_index(&format!("l_{rest}")).unwrap();
                assert!(
                    (d.tau_nm[twin] - d.tau_nm[k]).abs() < 1e-9,
                    "{who}: {name} {} vs l_{rest} {}",
                    d.tau_nm[k],
                    d.tau_nm[twin]
                );
                let (a, b) = (m.q_joint(k), m.q_joint(twin));
                assert_eq!(
                    (a.lower_rad, a.upper_rad),
                    (b.lower_rad, b.upper_rad),
                    "{who}: {name} range"
                );
            }
        }
    }
}

#[test]
fn the_shipped_worker_is_the_generated_50th_percentile_man() {
    let shipped =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf"))
            .unwrap();
    // the file says who it is
    assert!(shipped.contains("male, stature 1.755 m, mass 78 kg, strength percentile 50"));
    let generated = worker_urdf(&Worker::MALE_50, &StrengthTable::default_table()).unwrap();
    if generated != shipped {
        let line = generated
            .lines()
            .zip(shipped.lines())
            .position(|(a, b)| a != b);
        panic!(
            "robots/worker.urdf is not what `posture-opt robot` generates for the 50th-percentile man \
             (regenerate it with `posture-opt robot --sex male --stature-m 1.755 --mass-kg 78 --out robots/worker.urdf`); \
             first difference at line {:?}:\n  generated: {:?}\n  shipped:   {:?}",
            line.map(|l| l + 1),
            line.and_then(|l| generated.lines().nth(l)),
            line.and_then(|l| shipped.lines().nth(l)),
        );
    }
    assert_eq!(Worker::MALE_50.sex, Sex::Male);
    assert_eq!(
        (
            Worker::MALE_50.stature_m,
            Worker::MALE_50.mass_kg,
            Worker::MALE_50.strength_percentile
        ),
        (1.755, 78.0, 50.0)
    );
}

// ---------------------------------------------------------------------------------------------
// Joint ranges: AAOS (1965), as reprinted in Greene & Heckman (1994), in the worker's signs
// (a negative lower limit is the opposite motion).
// ---------------------------------------------------------------------------------------------

const AAOS_DEG: [(&str, f64, f64); 19] = [
    ("lumbar_flexion", -25.0, 80.0), // thoracolumbar flexion 80, extension 25
    ("lumbar_lateral_bending", -35.0, 35.0), // thoracolumbar lateral bending 35 each side
    ("lumbar_axial_rotation", -45.0, 45.0), // thoracolumbar rotation 45 each side
    ("neck_flexion", -45.0, 45.0),   // cervical flexion 45, extension 45
    ("neck_lateral_bending", -45.0, 45.0), // cervical lateral bending 45
    ("neck_axial_rotation", -60.0, 60.0), // cervical rotation 60
    ("shoulder_flexion", -60.0, 180.0), // flexion 180, extension 60
    // abduction 180; adduction −30 is the project's ASSUMPTION (the arm meets the trunk in the
    // frontal plane; AAOS's 75° adduction is measured across the front of the body)
    ("shoulder_abduction", -30.0, 180.0),
    ("shoulder_rotation", -90.0, 70.0), // external 90, internal 70
    ("elbow_flexion", 0.0, 150.0),      // flexion 150
    ("forearm_pronation", -80.0, 80.0), // supination 80, pronation 80
    ("wrist_flexion", -70.0, 80.0),     // flexion 80, extension 70
    ("wrist_deviation", -30.0, 20.0),   // radial 20, ulnar 30
    ("hip_flexion", -30.0, 120.0),      // flexion 120, extension 30
    ("hip_abduction", -30.0, 45.0),     // abduction 45, adduction 30
    ("hip_rotation", -45.0, 45.0),      // internal 45, external 45
    ("knee_flexion", 0.0, 135.0),       // flexion 135
    ("ankle_dorsiflexion", -50.0, 20.0), // dorsiflexion 20, plantarflexion 50
    ("ankle_inversion", -15.0, 35.0),   // inversion 35, eversion 15
];

#[test]
fn joint_ranges_are_the_aaos_table() {
    for (joint, lo, hi) in AAOS_DEG {
        let r = RANGES_DEG
            .iter()
            .find(|r| r.0 == joint)
            .unwrap_or_else(|| panic!("{joint} in RANGES_DEG"));
        assert_eq!((r.1, r.2), (lo, hi), "RANGES_DEG {joint}");
    }
    for (who, w) in population() {
        let m = generate(&w);
        assert_eq!(m.nq(), JOINTS.len());
        for k in 0..m.nq() {
            let j = m.q_joint(k);
            assert_eq!(j.name, JOINTS[k], "{who}: joint order");
            if PELVIS_JOINTS.contains(&j.name.as_str()) {
                continue;
            }
            let base = j.name.trim_start_matches("r_").trim_start_matches("l_");
            let (_, lo, hi) = AAOS_DEG
                .iter()
                .find(|r| r.0 == base)
                .unwrap_or_else(|| panic!("{who}: {} has no AAOS range", j.name));
            // the URDF prints radians to 1e-6
            assert!(
                (j.lower_rad - lo.to_radians()).abs() < 1e-6,
                "{who}: {} lower {}",
                j.name,
                j.lower_rad.to_degrees()
            );
            assert!(
                (j.upper_rad - hi.to_radians()).abs() < 1e-6,
                "{who}: {} upper {}",
                j.name,
                j.upper_rad.to_degrees()
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Strength: robots/worker.strength.yaml's means and SDs [N·m] (men, women), with the table's
// sources (abridged; the file has the full lines, docs in the helper notes "strength.md").
// ---------------------------------------------------------------------------------------------

/// (joint without side prefix, direction, male mean, male SD, female mean, female SD, source)
type Row = (&'static str, &'static str, f64, f64, f64, f64, &'static str);

const STRENGTH: [Row; 38] = [
    (
        "lumbar_flexion",
        "+",
        128.0,
        45.0,
        64.0,
        22.5,
        "ASSUMPTION on Kahanovitz et al. 1987 Spine 12:105 (women 19-109 N m); men = women / 0.5 (NIOSHTIC-2 00178484)",
    ),
    (
        "lumbar_flexion",
        "-",
        206.0,
        66.0,
        103.0,
        32.5,
        "ASSUMPTION on Kahanovitz et al. 1987 (women 38-168 N m); men = women / 0.5",
    ),
    (
        "lumbar_lateral_bending",
        "+",
        140.0,
        45.0,
        75.0,
        24.0,
        "ASSUMPTION (engineering estimate)",
    ),
    (
        "lumbar_lateral_bending",
        "-",
        140.0,
        45.0,
        75.0,
        24.0,
        "ASSUMPTION (engineering estimate)",
    ),
    (
        "lumbar_axial_rotation",
        "+",
        80.0,
        26.0,
        45.0,
        14.0,
        "ASSUMPTION (engineering estimate)",
    ),
    (
        "lumbar_axial_rotation",
        "-",
        80.0,
        26.0,
        45.0,
        14.0,
        "ASSUMPTION (engineering estimate)",
    ),
    (
        "neck_flexion",
        "+",
        24.0,
        4.8,
        16.6,
        4.5,
        "Cagnie et al. 2007 Arch Phys Med Rehabil 88:1441; SD from Fice et al. 2014, Salo et al. 2006",
    ),
    (
        "neck_flexion",
        "-",
        36.4,
        7.9,
        26.5,
        4.3,
        "Cagnie et al. 2007; SD from Fice et al. 2014, Salo et al. 2006",
    ),
    (
        "neck_lateral_bending",
        "+",
        24.2,
        6.8,
        17.2,
        4.8,
        "DERIVED from Fice et al. 2014 Ann Biomed Eng 42:1746 and Cagnie et al. 2007",
    ),
    (
        "neck_lateral_bending",
        "-",
        24.2,
        6.8,
        17.2,
        4.8,
        "DERIVED from Fice et al. 2014 and Cagnie et al. 2007",
    ),
    (
        "neck_axial_rotation",
        "+",
        11.3,
        4.3,
        8.0,
        2.3,
        "Salo et al. 2006 J Orthop Sports Phys Ther 36:495 (women); men DERIVED",
    ),
    (
        "neck_axial_rotation",
        "-",
        11.3,
        4.3,
        8.0,
        2.3,
        "Salo et al. 2006 (women); men DERIVED",
    ),
    (
        "shoulder_flexion",
        "+",
        89.9,
        27.0,
        45.0,
        13.5,
        "KIN-COM shoulder flexion study (26 M, 25 F), static 89.9 N m at 0 deg; women 0.5 x men",
    ),
    (
        "shoulder_flexion",
        "-",
        112.4,
        33.7,
        56.2,
        16.9,
        "DERIVED: flexors x 1.25 (Ivey et al. 1985 Arch Phys Med Rehabil 66:384)",
    ),
    (
        "shoulder_abduction",
        "+",
        74.4,
        22.3,
        35.0,
        10.5,
        "Holzbaur et al. 2007 J Biomech 40:2442",
    ),
    (
        "shoulder_abduction",
        "-",
        93.7,
        28.1,
        42.1,
        12.6,
        "Holzbaur et al. 2007",
    ),
    (
        "shoulder_rotation",
        "+",
        50.0,
        15.0,
        25.0,
        7.5,
        "ASSUMPTION (Ivey et al. 1985 ratios)",
    ),
    (
        "shoulder_rotation",
        "-",
        33.0,
        10.0,
        16.5,
        5.0,
        "ASSUMPTION (IR:ER 3:2, Ivey et al. 1985)",
    ),
    (
        "elbow_flexion",
        "+",
        77.0,
        20.0,
        41.0,
        11.0,
        "Stobbe 1982 as tabulated in Chaffin, Andersson & Martin, Occupational Biomechanics",
    ),
    (
        "elbow_flexion",
        "-",
        59.2,
        15.4,
        31.5,
        8.5,
        "DERIVED: flexors / 1.3 (Holzbaur et al. 2007)",
    ),
    (
        "forearm_pronation",
        "+",
        13.1,
        3.9,
        7.7,
        2.3,
        "O'Sullivan & Gallwey 2002 J Electromyogr Kinesiol 12:275; women / 1.7 (Axelsson et al. 2018)",
    ),
    (
        "forearm_pronation",
        "-",
        16.2,
        4.9,
        9.5,
        2.9,
        "O'Sullivan & Gallwey 2002; women / 1.7 (Axelsson et al. 2018)",
    ),
    (
        "wrist_flexion",
        "+",
        12.2,
        3.7,
        7.2,
        2.2,
        "Delp, Grierson & Buchanan 1996 J Biomech 29:1371",
    ),
    ("wrist_flexion", "-", 7.1, 2.1, 4.2, 1.2, "Delp et al. 1996"),
    (
        "wrist_deviation",
        "+",
        11.0,
        2.0,
        6.5,
        1.2,
        "Delp et al. 1996",
    ),
    (
        "wrist_deviation",
        "-",
        9.5,
        2.2,
        5.6,
        1.3,
        "Delp et al. 1996",
    ),
    (
        "hip_flexion",
        "-",
        209.2,
        66.1,
        154.0,
        44.1,
        "Anderson, Madigan & Nussbaum 2007 J Biomech 40:3105 Table 3 x ICRP 89 reference adults",
    ),
    (
        "hip_flexion",
        "+",
        138.6,
        35.1,
        104.6,
        27.7,
        "Anderson et al. 2007 x ICRP 89",
    ),
    (
        "knee_flexion",
        "-",
        201.0,
        53.9,
        137.7,
        29.3,
        "Anderson et al. 2007 x ICRP 89",
    ),
    (
        "knee_flexion",
        "+",
        105.9,
        25.7,
        67.2,
        17.8,
        "Anderson et al. 2007 x ICRP 89",
    ),
    (
        "ankle_dorsiflexion",
        "-",
        131.7,
        37.6,
        94.5,
        32.0,
        "Anderson et al. 2007 x ICRP 89",
    ),
    (
        "ankle_dorsiflexion",
        "+",
        38.4,
        8.6,
        24.5,
        5.2,
        "Anderson et al. 2007 x ICRP 89",
    ),
    (
        "hip_abduction",
        "+",
        94.2,
        22.5,
        67.8,
        15.7,
        "Sugimoto et al. 2014 Clin J Sport Med 24:422 x ICRP 89 body mass",
    ),
    (
        "hip_abduction",
        "-",
        103.6,
        24.8,
        74.6,
        17.3,
        "ASSUMPTION: abductors x 1.1 (Cahalan et al. 1989)",
    ),
    (
        "hip_rotation",
        "+",
        45.0,
        13.5,
        32.0,
        9.6,
        "ASSUMPTION (Cahalan et al. 1989; Lindsay et al. 1992)",
    ),
    (
        "hip_rotation",
        "-",
        40.0,
        12.0,
        28.0,
        8.4,
        "ASSUMPTION (Lindsay et al. 1992)",
    ),
    (
        "ankle_inversion",
        "+",
        33.4,
        11.8,
        24.0,
        8.5,
        "DERIVED: da Fonseca et al. 2025 World J Orthop 16:108858 ratio x plantarflexors",
    ),
    (
        "ankle_inversion",
        "-",
        27.7,
        9.4,
        19.9,
        6.8,
        "DERIVED: da Fonseca et al. 2025 ratio x plantarflexors",
    ),
];

fn dir(s: &str) -> Direction {
    if s == "+" {
        Direction::Positive
    } else {
        Direction::Negative
    }
}

fn expected_mvc(row: &Row, sex: Sex, percentile: f64) -> f64 {
    let z = match percentile as i64 {
        5 => -Z95,
        50 => 0.0,
        95 => Z95,
        p => panic!("no z for P{p}"),
    };
    let (mean, sd) = match sex {
        Sex::Male => (row.2, row.3),
        Sex::Female => (row.4, row.5),
    };
    mean + z * sd
}

fn half_joints(w: &Worker) -> Vec<HalfJoint> {
    let m = generate(w);
    resolve_half_joints(
        &m,
        &StrengthTable::default_table(),
        w,
        "robots/worker.strength.yaml",
    )
    .unwrap()
}

#[test]
fn p5_p50_p95_strength_of_men_and_women_is_mean_plus_z_sd() {
    for (who, w) in population() {
        let hj = half_joints(&w);
        // two half-joints for each of the 32 actuated joints, all from the table
        assert_eq!(hj.len(), 2 * (JOINTS.len() - PELVIS_JOINTS.len()), "{who}");
        for h in &hj {
            let base = h.joint.trim_start_matches("r_").trim_start_matches("l_");
            let row = STRENGTH
                .iter()
                .find(|r| r.0 == base && dir(r.1) == h.direction)
                .unwrap_or_else(|| panic!("{who}: {} has no row", h.id));
            let expect = expected_mvc(row, w.sex, w.strength_percentile);
            assert!(
                (h.mvc_nm - expect).abs() < 1e-9 * expect.max(1.0) + 1e-9,
                "{who}: {} MVC {} vs {expect} ({})",
                h.id,
                h.mvc_nm,
                row.6
            );
            assert!(
                !h.source.contains("URDF <limit effort>"),
                "{who}: {} from the table",
                h.id
            );
            assert_eq!(
                (
                    h.male.mean_nm,
                    h.male.sd_nm,
                    h.female.mean_nm,
                    h.female.sd_nm
                ),
                (row.2, row.3, row.4, row.5),
                "{}",
                h.id
            );
        }
        // every row is used, on both sides where sided
        for row in &STRENGTH {
            let n = hj
                .iter()
                .filter(|h| h.joint.ends_with(row.0) && h.direction == dir(row.1))
                .count();
            let sided = !(row.0.starts_with("lumbar") || row.0.starts_with("neck"));
            assert_eq!(n, if sided { 2 } else { 1 }, "{who}: {}{}", row.0, row.1);
        }
    }
    // the example of the table's documentation: a P5 woman's elbow flexors 41.0 − 1.645·11.0
    let w = worker(Sex::Female, 1.6, 60.0, 5.0);
    let hj = half_joints(&w);
    let ef = hj.iter().find(|h| h.id == "r_elbow_flexion+").unwrap();
    assert!((ef.mvc_nm - 22.906610103534).abs() < 1e-6, "{}", ef.mvc_nm);
}

/// One scaling, by percentile only: body mass and stature do not change a half-joint's MVC.
#[test]
fn strength_does_not_scale_with_body_size() {
    let a = half_joints(&worker(Sex::Male, 1.60, 55.0, 95.0));
    let b = half_joints(&worker(Sex::Male, 2.00, 140.0, 95.0));
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x.id, y.id);
        assert_eq!(x.mvc_nm, y.mvc_nm, "{}", x.id);
    }
    // the URDF's effort, for tools that read only the URDF, is the stronger direction's MVC
    let m = generate(&Worker::MALE_50);
    let effort = |j: &str| m.q_joint(m.q_index(j).unwrap()).effort;
    assert_eq!(effort("r_elbow_flexion"), 77.0);
    assert_eq!(effort("lumbar_flexion"), 206.0);
    assert_eq!(effort("l_knee_flexion"), 201.0);
    assert_eq!(effort("pelvis_tz"), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Posture curves: factor (on the mean) at tabulated angles, 1 at the reference posture, and the
// direction the sources give.
// ---------------------------------------------------------------------------------------------

/// The P50 man's half-joints and his q at zero.
fn p50() -> (BodyModel, Vec<HalfJoint>) {
    let w = Worker::MALE_50;
    (generate(&w), half_joints(&w))
}

fn factor_at(m: &BodyModel, h: &HalfJoint, angles_deg: &[(&str, f64)]) -> f64 {
    let mut q = vec![0.0; m.nq()];
    for (j, deg) in angles_deg {
        q[m.q_index(j).unwrap()] = deg.to_radians();
    }
    h.mvc_at(&q) / h.mvc_nm
}

/// (half-joint, curve joint, tabulated (deg, factor) points, reference angle) from the table.
type Curve = (&'static str, &'static str, &'static [(f64, f64)], f64);
const CURVES: [Curve; 13] = [
    (
        "lumbar_flexion+",
        "lumbar_flexion",
        &[
            (-25.0, 0.85),
            (0.0, 1.0),
            (25.0, 1.2),
            (36.0, 1.2),
            (50.0, 1.1),
            (80.0, 0.85),
        ],
        0.0,
    ),
    (
        "lumbar_flexion-",
        "lumbar_flexion",
        &[
            (-25.0, 0.85),
            (0.0, 1.0),
            (20.0, 1.3981),
            (40.0, 1.1262),
            (60.0, 0.8301),
        ],
        0.0,
    ),
    (
        "r_shoulder_flexion+",
        "r_shoulder_flexion",
        &[
            (-60.0, 1.0),
            (0.0, 1.0),
            (45.0, 0.76),
            (90.0, 0.65),
            (180.0, 0.55),
        ],
        0.0,
    ),
    (
        "r_forearm_pronation-",
        "r_forearm_pronation",
        &[(-80.0, 0.6), (0.0, 0.85), (60.0, 1.0), (80.0, 1.0)],
        60.0,
    ),
    (
        "r_wrist_flexion+",
        "r_wrist_flexion",
        &[(-70.0, 0.6), (0.0, 0.9), (40.0, 1.0), (80.0, 0.9)],
        40.0,
    ),
    (
        "l_wrist_flexion-",
        "l_wrist_flexion",
        &[(-70.0, 1.0), (30.0, 1.0), (80.0, 0.9)],
        0.0,
    ),
    (
        "l_hip_flexion-",
        "l_hip_flexion",
        &[
            (-30.0, 0.25),
            (0.0, 0.56),
            (30.0, 0.86),
            (66.0, 1.0),
            (90.0, 0.94),
            (120.0, 0.69),
        ],
        66.0,
    ),
    (
        "r_hip_flexion+",
        "r_hip_flexion",
        &[
            (-30.0, 0.98),
            (-14.0, 1.0),
            (0.0, 0.99),
            (30.0, 0.85),
            (60.0, 0.59),
            (90.0, 0.25),
            (120.0, 0.25),
        ],
        -14.0,
    ),
    (
        "r_knee_flexion-",
        "r_knee_flexion",
        &[
            (0.0, 0.35),
            (10.0, 0.35),
            (20.0, 0.51),
            (30.0, 0.69),
            (45.0, 0.88),
            (68.0, 1.0),
            (90.0, 0.89),
            (110.0, 0.61),
            (135.0, 0.25),
        ],
        68.0,
    ),
    (
        "l_knee_flexion+",
        "l_knee_flexion",
        &[
            (0.0, 0.89),
            (30.0, 1.0),
            (60.0, 0.88),
            (90.0, 0.57),
            (110.0, 0.27),
            (135.0, 0.25),
        ],
        30.0,
    ),
    (
        "r_ankle_dorsiflexion-",
        "r_ankle_dorsiflexion",
        &[
            (-50.0, 0.25),
            (-30.0, 0.25),
            (-15.0, 0.53),
            (0.0, 0.81),
            (10.0, 0.93),
            (20.0, 0.99),
            (25.0, 1.0),
        ],
        25.0,
    ),
    (
        "r_hip_rotation+",
        "r_hip_flexion",
        &[
            (-30.0, 1.0),
            (0.0, 1.0),
            (40.0, 1.15),
            (90.0, 1.3),
            (120.0, 1.3),
        ],
        0.0,
    ),
    (
        "l_ankle_inversion+",
        "l_ankle_inversion",
        &[(-15.0, 1.15), (0.0, 1.0), (35.0, 0.6)],
        0.0,
    ),
];

#[test]
fn posture_curves_pass_through_the_table_and_are_one_at_the_reference() {
    let (m, hj) = p50();
    for (id, joint, points, reference) in CURVES {
        let h = hj.iter().find(|h| h.id == id).unwrap();
        assert!(h.posture_dependent(), "{id}");
        for &(deg, factor) in points {
            let f = factor_at(&m, h, &[(joint, deg)]);
            assert!(
                (f - factor).abs() < 1e-12,
                "{id} at {joint} = {deg}°: {f} vs {factor}"
            );
        }
        assert!(
            (factor_at(&m, h, &[(joint, reference)]) - 1.0).abs() < 1e-12,
            "{id}: 1 at the reference {reference}°"
        );
        // shape-preserving: between two points the curve stays within their values
        for w in points.windows(2) {
            let (lo, hi) = (w[0].1.min(w[1].1), w[0].1.max(w[1].1));
            for i in 1..20 {
                let deg = w[0].0 + (w[1].0 - w[0].0) * i as f64 / 20.0;
                let f = factor_at(&m, h, &[(joint, deg)]);
                if w[0].1 != w[1].1 {
                    assert!(
                        f >= lo - 1e-12 && f <= hi + 1e-12,
                        "{id} at {deg}°: {f} outside {lo}..{hi}"
                    );
                }
            }
        }
    }
    // elbow flexors: elbow angle and forearm rotation multiply (the documented example:
    // 30° elbow flexion, pronated forearm: 0.80 × 0.47)
    let h = hj.iter().find(|h| h.id == "r_elbow_flexion+").unwrap();
    let f = factor_at(
        &m,
        h,
        &[("r_elbow_flexion", 30.0), ("r_forearm_pronation", 80.0)],
    );
    assert!((f - 0.80 * 0.47).abs() < 1e-12, "{f}");
    assert!((factor_at(&m, h, &[("r_elbow_flexion", 90.0)]) - 1.0).abs() < 1e-12);
    // a group without a curve is flat
    let flat = hj.iter().find(|h| h.id == "r_shoulder_abduction+").unwrap();
    assert!(!flat.posture_dependent());
    assert_eq!(factor_at(&m, flat, &[("r_shoulder_abduction", 120.0)]), 1.0);
}

/// Monotone where the sources say so.
#[test]
fn posture_curves_are_monotone_where_the_sources_say_so() {
    let (m, hj) = p50();
    // (half-joint, joint, from, to, rising?, source)
    let cases: [(&str, &str, f64, f64, bool, &str); 7] = [
        (
            "r_forearm_pronation-",
            "r_forearm_pronation",
            -80.0,
            80.0,
            true,
            "supination strength rises as the forearm is more pronated (O'Sullivan & Gallwey 2002)",
        ),
        (
            "r_hip_rotation+",
            "r_hip_flexion",
            -30.0,
            120.0,
            true,
            "internal-rotation torque rises with hip flexion (Johnson & Hoffman 2010)",
        ),
        (
            "l_ankle_inversion+",
            "l_ankle_inversion",
            -15.0,
            35.0,
            false,
            "invertor torque falls from pronated to supinated positions (J Foot Ankle Res 8:64, 2015)",
        ),
        (
            "r_shoulder_flexion+",
            "r_shoulder_flexion",
            0.0,
            180.0,
            false,
            "overhead weakest (Garg et al.); 45° measured at 0.76",
        ),
        (
            "lumbar_flexion-",
            "lumbar_flexion",
            20.0,
            90.0,
            false,
            "torso extension strength falls from 20° to 60° of trunk flexion (Chaffin et al. Table 4.5)",
        ),
        (
            "r_ankle_dorsiflexion-",
            "r_ankle_dorsiflexion",
            -50.0,
            25.0,
            true,
            "plantarflexor torque peaks at 25° dorsiflexion (Anderson et al. 2007)",
        ),
        (
            "r_hip_flexion+",
            "r_hip_flexion",
            -14.0,
            120.0,
            false,
            "hip flexor torque peaks at 14° extension (Anderson et al. 2007)",
        ),
    ];
    for (id, joint, from, to, rising, why) in cases {
        let h = hj.iter().find(|h| h.id == id).unwrap();
        let mut last = factor_at(&m, h, &[(joint, from)]);
        for i in 1..=300 {
            let deg = from + (to - from) * i as f64 / 300.0;
            let f = factor_at(&m, h, &[(joint, deg)]);
            if rising {
                assert!(f >= last - 1e-12, "{id} falls at {deg}° ({why})");
            } else {
                assert!(f <= last + 1e-12, "{id} rises at {deg}° ({why})");
            }
            last = f;
        }
    }
    // peaks where the sources put them: wrist flexors at 40° (Delp et al. 1996), knee extensors
    // at 68° and flexors at 30° (Anderson et al. 2007), elbow flexors at 90°
    for (id, joint, peak, lo, hi) in [
        ("r_wrist_flexion+", "r_wrist_flexion", 40.0, -70.0, 80.0),
        ("r_knee_flexion-", "r_knee_flexion", 68.0, 0.0, 135.0),
        ("l_knee_flexion+", "l_knee_flexion", 30.0, 0.0, 135.0),
        ("r_elbow_flexion+", "r_elbow_flexion", 90.0, 0.0, 150.0),
    ] {
        let h = hj.iter().find(|h| h.id == id).unwrap();
        let top = factor_at(&m, h, &[(joint, peak)]);
        for i in 0..=300 {
            let deg = lo + (hi - lo) * i as f64 / 300.0;
            assert!(
                factor_at(&m, h, &[(joint, deg)]) <= top + 1e-12,
                "{id}: above its peak at {deg}°"
            );
        }
    }
}

/// The gradient of the MVC in posture against central differences.
#[test]
fn mvc_gradient_matches_finite_differences() {
    let (m, hj) = p50();
    let mut q = vec![0.0; m.nq()];
    for (k, x) in q.iter_mut().enumerate() {
        let j = m.q_joint(k);
        if j.lower_rad.is_finite() {
            *x = j.lower_rad + (0.37 + 0.011 * k as f64) % 1.0 * (j.upper_rad - j.lower_rad);
        }
    }
    let mut grad = Vec::new();
    for h in hj.iter().filter(|h| h.posture_dependent()) {
        h.mvc_gradient(&q, &mut grad);
        for &(k, g) in &grad {
            let e = 1e-6;
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[k] += e;
            qm[k] -= e;
            let fd = (h.mvc_at(&qp) - h.mvc_at(&qm)) / (2.0 * e);
            assert!(
                (g - fd).abs() < 1e-5 * h.mvc_nm,
                "{} ∂/∂{}: {g} vs {fd}",
                h.id,
                m.q_joint(k).name
            );
        }
    }
}

#[test]
fn absurd_workers_are_refused() {
    for w in [
        worker(Sex::Male, 0.5, 70.0, 50.0),
        worker(Sex::Male, f64::NAN, 70.0, 50.0),
        worker(Sex::Female, 1.6, 500.0, 50.0),
        worker(Sex::Female, 1.6, 60.0, 0.0),
        worker(Sex::Female, 1.6, 60.0, f64::INFINITY),
    ] {
        let e = worker_urdf(&w, &StrengthTable::default_table()).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("stature_m")
                || msg.contains("mass_kg")
                || msg.contains("strength_percentile"),
            "{msg}"
        );
    }
}

/// A strength-table entry naming a joint the robot lacks, or a region the fatigue parameters do
/// not know, is refused with the entry named — it used to be ignored in silence (the joint then
/// fell back to its URDF effort, once 60 % stronger).
#[test]
fn misspelt_strength_entries_are_refused() {
    let w = Worker::MALE_50;
    let m = generate(&w);
    let table = posture_opt::body::strength::DEFAULT_TABLE_YAML;
    for (from, to, expect) in [
        (
            "joint: lumbar_flexion",
            "joint: lumbar_flexon",
            "'lumbar_flexon' is not a moving joint",
        ),
        ("region: trunk", "region: spleen", "region 'spleen'"),
    ] {
        assert!(table.contains(from), "{from}");
        let text = table.replacen(from, to, 1);
        let t = StrengthTable::from_yaml_str(&text, "bad.strength.yaml").unwrap();
        let e = resolve_half_joints(&m, &t, &w, "bad.strength.yaml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("bad.strength.yaml") && e.contains(expect), "{e}");
    }
}

/// A posture curve may be keyed on a sum of joint angles (`plus`): the trunk extensors' curve is
/// on the trunk's inclination, pelvis tilt + lumbar flexion. The factor is the same curve keyed on
/// lumbar flexion alone, at the sum; the gradient has equal entries for both joints (checked
/// against finite differences), and a joint named twice is refused.
#[test]
fn a_posture_curve_on_a_sum_of_joint_angles() {
    let w = Worker::MALE_50;
    let m = generate(&w);
    let shipped = half_joints(&w);
    let table = posture_opt::body::strength::DEFAULT_TABLE_YAML;
    let summed = "- {joint: lumbar_flexion, plus: [pelvis_tilt], deg: [-25, 0, 20, 40, 60], factor: [0.85, 1.00, 1.3981, 1.1262, 0.8301]}";
    assert!(table.contains(summed), "the trunk extensors' curve changed");
    let from = summed.replace(" plus: [pelvis_tilt],", "");
    let t = StrengthTable::from_yaml_str(&table.replacen(summed, &from, 1), "one.strength.yaml")
        .unwrap();
    let lumbar = resolve_half_joints(&m, &t, &w, "one.strength.yaml").unwrap();
    let id = |v: &[HalfJoint]| v.iter().position(|h| h.id == "lumbar_flexion-").unwrap();
    let (h, h0) = (&shipped[id(&shipped)], &lumbar[id(&lumbar)]);
    // 15° of pelvis tilt and 25° of lumbar flexion: the shipped curve's factor at 40°
    let both = factor_at(&m, h, &[("pelvis_tilt", 15.0), ("lumbar_flexion", 25.0)]);
    let lumbar_only = factor_at(&m, h0, &[("lumbar_flexion", 40.0)]);
    assert!(
        (both - lumbar_only).abs() < 1e-12,
        "{both} vs {lumbar_only}"
    );
    assert!((factor_at(&m, h0, &[("pelvis_tilt", 15.0)]) - 1.0).abs() < 1e-12);
    let mut q = vec![0.0; m.nq()];
    let (tilt, lumbar) = (
        m.q_index("pelvis_tilt").unwrap(),
        m.q_index("lumbar_flexion").unwrap(),
    );
    q[tilt] = 0.3;
    q[lumbar] = 0.2;
    let mut grad = Vec::new();
    h.mvc_gradient(&q, &mut grad);
    assert_eq!(grad.len(), 2, "{grad:?}");
    for &(k, g) in &grad {
        assert!(k == tilt || k == lumbar);
        let e = 1e-6;
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[k] += e;
        qm[k] -= e;
        let fd = (h.mvc_at(&qp) - h.mvc_at(&qm)) / (2.0 * e);
        assert!((g - fd).abs() < 1e-6 * h.mvc_nm, "∂/∂q{k}: {g} vs {fd}");
        assert!(g.abs() > 1.0, "the curve is not flat at 29°");
    }
    assert!((grad[0].1 - grad[1].1).abs() < 1e-12);
    let twice = summed.replace("plus: [pelvis_tilt]", "plus: [lumbar_flexion]");
    let t = StrengthTable::from_yaml_str(&table.replacen(summed, &twice, 1), "twice.strength.yaml")
        .unwrap();
    let e = resolve_half_joints(&m, &t, &w, "twice.strength.yaml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("twice.strength.yaml") && e.contains("twice"),
        "{e}"
    );
}

/// The trunk extensors in a stoop, against the published table they come from: a 50th-percentile
/// man's mean torso-extension strength is 288 / 232 / 171 N·m at 20 / 40 / 60° of trunk flexion
/// (Chaffin, Andersson & Martin, *Occupational Biomechanics*, 3rd ed., Table 4.5), whether the
/// flexion is in the lumbar spine or at the hips (the pelvis tilted); upright it is 206 N·m (the
/// table's reference). P5 and P95 are the same factors on mean ∓ 1.645 SD (66 N·m), and a woman's
/// are half a man's (LIFTEST). The bug this replaces: 278 / 350 / 355 N·m, a stoop stronger than
/// standing upright.
#[test]
fn trunk_extensors_weaken_in_a_stoop_as_chaffin_tabulates() {
    let chaffin: [(f64, f64); 4] = [(0.0, 206.0), (20.0, 288.0), (40.0, 232.0), (60.0, 171.0)];
    for (sex, pct, scale) in [
        (Sex::Male, 50.0, 1.0),
        (Sex::Male, 5.0, (206.0 - Z95 * 66.0) / 206.0),
        (Sex::Male, 95.0, (206.0 + Z95 * 66.0) / 206.0),
        (Sex::Female, 50.0, 0.5),
    ] {
        let w = worker(sex, 1.755, 78.0, pct);
        let m = generate(&w);
        let hj = half_joints(&w);
        let h = hj.iter().find(|h| h.id == "lumbar_flexion-").unwrap();
        for (deg, nm) in chaffin {
            for split in [0.0, 0.5, 1.0] {
                let mut q = vec![0.0; m.nq()];
                q[m.q_index("lumbar_flexion").unwrap()] = (split * deg).to_radians();
                q[m.q_index("pelvis_tilt").unwrap()] = ((1.0 - split) * deg).to_radians();
                let got = h.mvc_at(&q);
                let want = nm * scale;
                assert!(
                    (got - want).abs() < 0.05,
                    "{sex:?} P{pct} at {deg}° ({split} lumbar): {got:.2} vs {want:.2} N·m"
                );
            }
        }
        // a deep stoop is no stronger than 60°
        let mut q = vec![0.0; m.nq()];
        q[m.q_index("lumbar_flexion").unwrap()] = 40f64.to_radians();
        q[m.q_index("pelvis_tilt").unwrap()] = 50f64.to_radians();
        assert!(h.mvc_at(&q) <= 171.0 * scale + 0.05);
    }
}
