//! The planning model itself — a named parameter set with its recovery form, by default the one
//! `plan` uses — against published endurance, intermittent-work and recovery data. Where the
//! paper's validations (`static`, `dynamic`) check Eq. 8 without recovery, this one checks the
//! model the planner runs.
//!
//! Every measured value below is restated from its source (cited per row); the model values are
//! computed here with the library's closed forms. A row's band is the tolerance the parameter fit
//! was accepted with (the fit's own residual at that point rounded up to the next 5 % plus 5
//! percentage points, as in `docs/fatigue-parameters.md`); rows marked "deviation" are known
//! limits of a one-time-constant model, reported rather than hidden.

use super::dynamic::frey_law_avin_curve;
use crate::body::Sex;
use crate::fatigue::fit::{Measured, Row, predict};
use crate::fatigue::params::ParameterSet;
use crate::fatigue::three_compartment::Region;
use crate::fatigue::{FatigueError, MaParams, MaState};
use serde::Serialize;

/// One published figure against the model.
#[derive(Debug, Clone, Serialize)]
pub struct RecoveryCheck {
    /// Short name of the source.
    pub source: String,
    /// The condition in words (muscle group, load, work/rest pattern).
    pub condition: String,
    /// What is compared, with its unit.
    pub quantity: String,
    pub measured: f64,
    pub model: f64,
    /// Accepted relative error |model/measured − 1|, or `None` for an inequality check.
    pub band: Option<f64>,
    /// `true` when the model meets the band (or the stated inequality).
    pub pass: bool,
    /// Why a row is only an inequality or a documented deviation.
    pub note: Option<String>,
}

/// Sustained endurance of one region against its Frey-Law & Avin (2010) power curve.
#[derive(Debug, Clone, Serialize)]
pub struct EnduranceRow {
    pub region: String,
    pub k_per_min: f64,
    /// Loads (fraction of MVC) and model/curve ratios of the endurance time there.
    pub fmvc: Vec<f64>,
    pub model_over_curve: Vec<f64>,
    /// Highest load held forever by this region under the set's recovery.
    pub sustainable_load: f64,
}

/// The whole check of a parameter set.
#[derive(Debug, Clone, Serialize)]
pub struct RecoveryValidation {
    /// The parameter set checked, and whether it is the one `plan` uses by default.
    pub parameters: String,
    pub is_default: bool,
    pub recovery: String,
    pub endurance: Vec<EnduranceRow>,
    pub checks: Vec<RecoveryCheck>,
    /// Number of checks that pass, and of all checks.
    pub passed: usize,
    pub total: usize,
}

const SK: &str = "Stull & Kearney (1978) Med Sci Sports 10:109";

const LOADS: [f64; 4] = [0.2, 0.4, 0.6, 0.8];

/// Endurance \[s\] of a fresh group working `on_s` at `f` and resting `off_s`, repeated (the
/// simulation `fit` predicts with; capped at 24 h).
fn intermittent_s(p: &MaParams, f: f64, on_s: f64, off_s: f64) -> f64 {
    let row = Row {
        line: 0,
        region: "general".into(),
        load_fmvc: f,
        cycle_s: Some((on_s, off_s)),
        what: Measured::EnduranceS(1.0),
    };
    predict(p, &row)
}

fn check(
    source: &str,
    condition: &str,
    quantity: &str,
    measured: f64,
    model: f64,
    band: f64,
) -> RecoveryCheck {
    RecoveryCheck {
        source: source.into(),
        condition: condition.into(),
        quantity: quantity.into(),
        measured,
        model,
        band: Some(band),
        pass: (model / measured - 1.0).abs() <= band,
        note: None,
    }
}

fn inequality(
    source: &str,
    condition: &str,
    quantity: &str,
    measured: f64,
    model: f64,
    pass: bool,
    note: &str,
) -> RecoveryCheck {
    RecoveryCheck {
        source: source.into(),
        condition: condition.into(),
        quantity: quantity.into(),
        measured,
        model,
        band: None,
        pass,
        note: Some(note.into()),
    }
}

/// Check `set` against the published data (`is_default`: it is the set `plan` uses by default).
pub fn recovery_validation(
    set: &ParameterSet,
    is_default: bool,
) -> Result<RecoveryValidation, FatigueError> {
    let params = |region: &str| set.params(region, Sex::Male);
    let mut endurance = Vec::new();
    for r in Region::ALL {
        let name = r.name();
        let p = params(name)?;
        let (b0, b1) = frey_law_avin_curve(r).expect("every region has a curve");
        let model_over_curve = LOADS
            .iter()
            .map(|&f| {
                let model_s = p.time_to_exhaustion_s(1.0, f).unwrap_or(f64::INFINITY);
                model_s / (b0 * f.powf(b1))
            })
            .collect();
        endurance.push(EnduranceRow {
            region: name.into(),
            k_per_min: p.k_per_min,
            fmvc: LOADS.to_vec(),
            model_over_curve,
            sustainable_load: p.sustainable_load(),
        });
    }

    let mut checks = Vec::new();
    // Sustained limits.
    let worst_sustainable = endurance
        .iter()
        .map(|e| e.sustainable_load)
        .fold(0.0, f64::max);
    checks.push(inequality(
        "classic limit (Rohmert 1960; Björkstén & Jonsson 1977)",
        "any region, load held without pause",
        "highest load held forever [fraction of MVC]",
        0.15,
        worst_sustainable,
        worst_sustainable < 0.15,
        "no sustained load well above ~15 %MVC may last forever: the model's must stay below 0.15",
    ));
    let general = params("general")?;
    let bj = general
        .time_to_exhaustion_s(1.0, 0.079)
        .map_or(f64::INFINITY, |s| s / 60.0);
    checks.push(inequality(
        "Björkstén & Jonsson (1977) Scand J Work Environ Health 3:23",
        "7.9 %MVC held, the 60-min endurance limit of sustained contractions",
        "endurance [min]",
        60.0,
        bj,
        bj >= 60.0,
        "the measured limit was held for 60 min: the model must last at least that long",
    ));
    // Intermittent work.
    let grip = params("grip")?;
    checks.push(check(
        "Gonzales & Scheuermann (2007) J Sports Sci Med 6:98",
        "grip 50 %MVC, 5 s on / 5 s off, to failure (22 adults, pooled)",
        "endurance [s]",
        739.05,
        intermittent_s(&grip, 0.5, 5.0, 5.0),
        0.25,
    ));
    // Byström et al.: k calibrated within the study on the continuous trial (16.2 min at 25 %).
    let k_bystrom = -f64::ln(0.25) / (0.25 * 16.2);
    let bystrom = MaParams::with_recovery(k_bystrom, set.recovery.recovery())?;
    let mut row = check(
        "Byström, Mathiassen & Fransson-Hall (1991) Eur J Appl Physiol 63",
        "grip 25 %MVC with a 10-s pause every 3 min (k from the same study's continuous trial, 16.2 min)",
        "endurance [min]",
        23.1,
        intermittent_s(&bystrom, 0.25, 180.0, 10.0) / 60.0,
        0.15,
    );
    if matches!(set.recovery, crate::fatigue::params::RecoverySpec::None) {
        row.note = Some(
            "without recovery the pauses cannot help: 16.2 min of work plus the pauses".into(),
        );
    }
    checks.push(row);
    // Recovery at rest: Sahlin & Ren, knee extension at 66 %MVC.
    let knee = params("knee")?;
    let first = knee
        .time_to_exhaustion_s(1.0, 0.66)
        .unwrap_or(f64::INFINITY);
    let after_rest = |rest_min: f64| {
        // the first bout to exhaustion (its fast deficit too, under the routed recovery)
        let mut s = MaState::FRESH;
        knee.hold(&mut s, 0.66, first);
        knee.hold(&mut s, 0.0, rest_min * 60.0);
        knee.time_to_exhaustion_s(s.capacity, 0.66).unwrap_or(0.0) / first
    };
    checks.push(check(
        "Sahlin & Ren (1989) J Appl Physiol 67:648",
        "knee extension 66 %MVC to fatigue, 1.2 min of rest, again",
        "second endurance / first",
        0.5,
        after_rest(1.2),
        0.30,
    ));
    let r4 = after_rest(4.0);
    checks.push(inequality(
        "Sahlin & Ren (1989) J Appl Physiol 67:648",
        "the same after 4 min of rest",
        "second endurance / first",
        1.0,
        r4,
        r4 < 1.0,
        "still significantly depressed after 4 min: the ratio must stay below 1",
    ));
    // Stull & Kearney: a documented deviation of one time constant.
    let k_sk = std::f64::consts::LN_2 / (0.5 * 120.25 / 60.0);
    let sk = MaParams::with_recovery(k_sk, set.recovery.recovery())?;
    let mut s = MaState::FRESH;
    sk.hold(&mut s, 0.5, 120.25);
    sk.hold(&mut s, 0.0, 5.0);
    let ratio = sk.time_to_exhaustion_s(s.capacity, 0.5).unwrap_or(0.0) / 120.25;
    let condition = "grip 50 %MVC to exhaustion, 5 s of rest, again";
    checks.push(if matches!(sk.recovery, crate::fatigue::Recovery::Routed { .. }) {
        // the fast deficit is there for this: the measured figure within 15 %
        check(SK, condition, "second endurance / first", 0.203, ratio, 0.15)
    } else {
        inequality(
            SK,
            condition,
            "second endurance / first",
            0.203,
            ratio,
            ratio > 0.0 && ratio < 0.203,
            "deviation: one recovery time constant cannot return the fast first seconds of recovery; only 0 < ratio < measured is required",
        )
    });

    let passed = checks.iter().filter(|c| c.pass).count();
    let total = checks.len();
    Ok(RecoveryValidation {
        parameters: set.name.clone(),
        is_default,
        recovery: match set.recovery.recovery() {
            crate::fatigue::Recovery::None => "none (Ma et al. 2009)".into(),
            crate::fatigue::Recovery::Constant { r_per_min } => {
                format!("constant R = {r_per_min} /min under load and at rest")
            }
            crate::fatigue::Recovery::Perfusion {
                rest_per_min,
                limit_fmvc,
            } => format!(
                "perfusion-limited: R = {rest_per_min} /min at rest, falling to 0 at {:.1} %MVC",
                100.0 * limit_fmvc
            ),
            crate::fatigue::Recovery::Routed {
                slow_rest_per_min,
                fast_rest_per_min,
                limit_fmvc,
                fast_share_max,
            } => format!(
                "two deficits, perfusion-limited: slow R = {slow_rest_per_min} /min and fast R = {fast_rest_per_min} /min at rest, both falling to 0 at {:.1} %MVC; up to {:.1} % of new fatigue to the fast deficit, from 25 %MVC (none) to 50 %MVC (all of it)",
                100.0 * limit_fmvc,
                100.0 * fast_share_max
            ),
        },
        endurance,
        checks,
        passed,
        total,
    })
}
