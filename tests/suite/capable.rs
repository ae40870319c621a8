//! Share of men and women strong enough for a phase (`posture_opt::assess::phase`): for each
//! muscle group, the torque it must produce at the planned posture against the population's
//! strength, normally distributed with the table's mean and SD (scaled by the posture factor):
//!
//! ```text
//! share = P(strength × posture factor > required) = 1 − Φ((required / factor − mean) / SD)
//! ```
//!
//! Expected values by hand from the standard normal distribution: required = mean → 1 − Φ(0) =
//! 0.5; required = mean + 1 SD → 1 − Φ(1) = 1 − 0.841345 = 0.158655 (Φ(1) = 0.8413447, e.g.
//! Abramowitz & Stegun, *Handbook of Mathematical Functions*, Table 26.1); required = mean − 1
//! SD → Φ(1) = 0.841345; required = mean + 2 SD → 1 − Φ(2) = 1 − 0.977250 = 0.022750.
//!
//! The posture is planned once for a one-phase task (5 kg held in the right hand in front of the
//! body at about elbow height, so the right elbow flexors must hold the load); the tests then
//! set the strength table's mean and SD of one muscle group around the torque that group must
//! produce at that posture, and make every other group far stronger than needed.

use posture_opt::assess::phase::assess_phases;
use posture_opt::plan::{Plan, Task, plan_task};
use std::path::PathBuf;
use std::sync::OnceLock;

const TASK_YAML: &str = r#"name: hold a part in front of the body
worker: {sex: male, stature_m: 1.75, mass_kg: 75.0, strength_percentile: 50}
workstation:
  obstacles:
    - {name: floor, plane: {normal: [0, 0, 1]}, position_m: [0, 0, 0]}
phases:
  - {name: hold, target_m: [0.35, -0.20, 1.05], load_kg: 5.0, duration_s: 10.0}
rest_s: 5.0
cycles: 2
"#;

const GROUP: &str = "r_elbow_flexion+";

/// Φ(1), Φ(2) of the standard normal distribution (tabulated).
const PHI_1: f64 = 0.841_344_7;
const PHI_2: f64 = 0.977_249_9;

struct Planned {
    _dir: tempfile::TempDir,
    path: PathBuf,
    plan: Plan,
}

fn planned() -> &'static Planned {
    static P: OnceLock<Planned> = OnceLock::new();
    P.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("hold.yaml");
        std::fs::write(&path, TASK_YAML).unwrap();
        let task = Task::from_file(&path).unwrap();
        let plan = plan_task(&task).unwrap();
        Planned {
            _dir: dir,
            path,
            plan,
        }
    })
}

/// The task (freshly read) with every muscle group far stronger than any load (mean 10⁹ N·m,
/// SD 1 N·m: share 1) except `GROUP`, which gets `male` and `female` (mean, SD) as computed by
/// `set` from the torque it must produce and its posture factor.
fn task_with(set: impl Fn(f64, f64) -> ((f64, f64), (f64, f64))) -> (Task, f64, f64) {
    let p = planned();
    let mut task = Task::from_file(&p.path).unwrap();
    let q = p.plan.summary.phases[0].q_rad.clone();
    for h in task.half_joints.iter_mut() {
        h.male.mean_nm = 1e9;
        h.male.sd_nm = 1.0;
        h.female.mean_nm = 1e9;
        h.female.sd_nm = 1.0;
    }
    // The torque the group must produce: read once with the group made weak enough to be the
    // least capable (so that it is listed first).
    let h = task
        .half_joints
        .iter()
        .position(|h| h.id == GROUP)
        .expect("the worker has right elbow flexors");
    task.half_joints[h].male.mean_nm = 0.0;
    task.half_joints[h].female.mean_nm = 0.0;
    let a = assess_phases(&task, &p.plan);
    let c = &a[0].capable[0];
    assert_eq!(c.half_joint, GROUP, "{:?}", a[0].capable);
    let required = c.required_nm;
    assert!(
        required > 1.0,
        "the elbow flexors hold the load: {required} N·m"
    );
    let factor = task.half_joints[h].posture_factor(&q);
    assert!(factor > 0.0);
    let ((mm, ms), (fm, fs)) = set(required, factor);
    task.half_joints[h].male.mean_nm = mm;
    task.half_joints[h].male.sd_nm = ms;
    task.half_joints[h].female.mean_nm = fm;
    task.half_joints[h].female.sd_nm = fs;
    (task, required, factor)
}

/// The required torque is the population mean (at this posture) for men: 50 % of men; and the
/// mean + 1 SD for women: 1 − Φ(1) = 15.87 % of women.
#[test]
fn mean_gives_half_and_mean_plus_one_sd_gives_15_87_percent() {
    let (task, required, factor) = task_with(|req, f| {
        let need = req / f; // strength needed at the reference posture
        ((need, 0.2 * need), (need - 10.0, 10.0))
    });
    let a = assess_phases(&task, &planned().plan);
    let c = &a[0].capable[0];
    assert_eq!(c.half_joint, GROUP);
    assert!((c.required_nm - required).abs() < 1e-9);
    assert!((c.men - 0.5).abs() < 1e-9, "men {}", c.men);
    assert!((c.women - (1.0 - PHI_1)).abs() < 1e-6, "women {}", c.women);
    assert!((c.women - 0.1587).abs() < 1e-4);
    // The phase's shares are the lowest over its groups: this group's.
    assert!((a[0].capable_men - 0.5).abs() < 1e-9);
    assert!((a[0].capable_women - (1.0 - PHI_1)).abs() < 1e-6);
    assert!(factor > 0.0);
}

/// The same with the sexes swapped: men at mean + 1 SD (15.87 %), women at the mean (50 %).
#[test]
fn swapped_sexes() {
    let (task, _, _) = task_with(|req, f| {
        let need = req / f;
        ((need - 30.0, 30.0), (need, 5.0))
    });
    let a = assess_phases(&task, &planned().plan);
    let c = &a[0].capable[0];
    assert!((c.men - (1.0 - PHI_1)).abs() < 1e-6, "men {}", c.men);
    assert!((c.women - 0.5).abs() < 1e-9, "women {}", c.women);
}

/// Required = mean − 1 SD: Φ(1) = 84.13 % are strong enough; mean + 2 SD: 1 − Φ(2) = 2.28 %.
#[test]
fn one_sd_below_and_two_sd_above() {
    let (task, _, _) = task_with(|req, f| {
        let need = req / f;
        ((need + 8.0, 8.0), (need - 2.0 * 4.0, 4.0))
    });
    let a = assess_phases(&task, &planned().plan);
    let c = &a[0].capable[0];
    assert!((c.men - PHI_1).abs() < 1e-6, "men {}", c.men);
    assert!((c.women - (1.0 - PHI_2)).abs() < 1e-6, "women {}", c.women);
    // The least capable share is listed first.
    assert_eq!(c.half_joint, GROUP);
}

/// The posture factor scales the strength: the share depends on required / factor. With the
/// mean at the required torque itself (not divided by the factor), the share is
/// 1 − Φ((required / factor − required) / SD); for a factor of 1 it is 50 %.
#[test]
fn the_posture_factor_scales_the_strength() {
    let sd = 7.0;
    let (task, required, factor) = task_with(|req, _| ((req, sd), (req, sd)));
    let a = assess_phases(&task, &planned().plan);
    let c = &a[0].capable[0];
    let z = (required / factor - required) / sd;
    // By hand for this z, from Φ(z) = ½ erfc(−z/√2) (z is small for a factor near 1).
    let phi = 0.5 * (1.0 + erf(z / std::f64::consts::SQRT_2));
    assert!((c.men - (1.0 - phi)).abs() < 1e-6, "men {} z {z}", c.men);
}

/// Without spread (SD 0) the share is all or nothing: 100 % when the mean strength at this
/// posture exceeds the requirement, 0 % otherwise.
#[test]
fn no_spread_is_all_or_nothing() {
    let (task, _, _) = task_with(|req, f| ((1.01 * req / f, 0.0), (0.99 * req / f, 0.0)));
    let a = assess_phases(&task, &planned().plan);
    let c = a[0].capable.iter().find(|c| c.half_joint == GROUP).unwrap();
    assert_eq!(c.men, 1.0);
    assert_eq!(c.women, 0.0);
}

/// Error function (Abramowitz & Stegun 7.1.26, |error| < 1.5·10⁻⁷), for the normal CDF by hand.
fn erf(x: f64) -> f64 {
    let t = 1.0 / (1.0 + 0.327_591_1 * x.abs());
    let y = 1.0
        - (((((1.061_405_429 * t - 1.453_152_027) * t) + 1.421_413_741) * t - 0.284_496_736) * t
            + 0.254_829_592)
            * t
            * (-x * x).exp();
    y.copysign(x)
}
