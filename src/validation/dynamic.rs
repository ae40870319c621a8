//! Dynamic validation (paper §4) and endurance-curve anchors, as numbers.
//!
//! * Liu, Brown & Yue (2002) active-motor model at MVC (Eq. 12–15).
//! * Freund & Takala (2001) reservoir model (Eq. 11).
//! * Wexler et al. (1997): the qualitative trend "the larger the load, the faster the decline".
//! * Frey-Law & Avin (2010) endurance-time curves per body region against Eq. 8, and the
//!   three-compartment model with Frey-Law et al. (2012) parameters against the same curves.

use crate::fatigue::stats::{icc_oneway, pearson_r};
use crate::fatigue::units::s_to_min;
use crate::fatigue::{MaParams, MaState, Region, ThreeCompartment, ThreeCompartmentState, met_min};
use serde::Serialize;

/// Liu et al. (2002) Eq. 13 + 14: `(M_A + M_uc)/M0` at time `t_s` for fatigue rate `f_per_s`,
/// `β = B/F`, `γ = R/F`, from `M_A = M_F = 0`.
///
/// The paper's Eq. 15 prints the coefficient of `e^{−βFt}` in the sum as `+1/(β−1−γ)`; adding
/// Eq. 13 and 14 gives `1 − (β−γ)/(β−1−γ) = −1/(β−1−γ)` (a sign slip in Eq. 15: with `+` the sum
/// would not start at 1). The limit `γ = 0, β → ∞` is `e^{−Ft}` either way.
pub fn liu_capacity(t_s: f64, f_per_s: f64, beta: f64, gamma: f64) -> f64 {
    let ft = f_per_s * t_s;
    let d = beta - 1.0 - gamma;
    let ma = gamma / (1.0 + gamma) + beta / ((1.0 + gamma) * d) * (-(1.0 + gamma) * ft).exp()
        - (beta - gamma) / d * (-beta * ft).exp();
    let muc = (-beta * ft).exp();
    ma + muc
}

#[derive(Debug, Clone, Serialize)]
pub struct LiuCase {
    pub beta: f64,
    pub gamma: f64,
    /// Largest |Liu − Ma| over the 3-min trial.
    pub max_abs_diff: f64,
    pub capacity: Vec<f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct LiuValidation {
    /// F [1/s] used: the value for which Eq. 15's limit equals the model at k (F = k / 60 s).
    pub f_per_s: f64,
    pub note: String,
    pub t_s: Vec<f64>,
    /// Ma model at MVC (f = 1): c(t) = e^{−k t}.
    pub model_capacity: Vec<f64>,
    pub cases: Vec<LiuCase>,
}

#[derive(Debug, Clone, Serialize)]
pub struct FreundTakalaValidation {
    pub note: String,
    /// Fatigue rate β [1/min] of the depletion form (no recovery), fitted to Eq. 8 in log space.
    pub beta_per_min: f64,
    pub fmvc: Vec<f64>,
    pub met_min: Vec<f64>,
    pub model_met_min: Vec<f64>,
    pub r: f64,
    pub icc: f64,
    /// As printed (one rate for recovery and depletion): the lowest load that can exhaust.
    pub printed_form_min_exhausting_fmvc: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct WexlerLevel {
    pub fmvc: f64,
    /// Initial slope of capacity [1/min] (−k f).
    pub initial_slope_per_min: f64,
    /// Time for capacity to halve \[min\].
    pub half_capacity_min: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct WexlerValidation {
    pub note: String,
    pub levels: Vec<WexlerLevel>,
    /// Higher load ⇒ steeper and faster decline, at every level.
    pub trend_reproduced: bool,
}

#[derive(Debug, Clone, Serialize)]
pub struct RegionAnchor {
    pub region: String,
    pub b0_s: f64,
    pub b1: f64,
    /// Eq. 8 at k = 1 against the curve.
    pub r: f64,
    pub icc_k1: f64,
    /// k [1/min] that best fits the curve (least squares on ln MET, 20–80 %MVC).
    pub fitted_k_per_min: f64,
    pub icc_fitted_k: f64,
    /// 3CC (Frey-Law et al. 2012 F, R) simulated endurance vs the curve, 10–90 %MVC.
    pub three_compartment_rms_s: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct DynamicValidation {
    pub k_per_min: f64,
    pub liu: LiuValidation,
    pub freund_takala: FreundTakalaValidation,
    pub wexler: WexlerValidation,
    pub frey_law_avin: Vec<RegionAnchor>,
}

/// Frey-Law & Avin (2010), Ergonomics 53:109, power model `ET = b0 f^b1` \[s\].
pub fn frey_law_avin_curve(region: Region) -> Option<(f64, f64)> {
    Some(match region {
        Region::General => (21.92, -1.98),
        Region::Ankle => (34.71, -2.06),
        Region::Trunk => (22.69, -2.27),
        Region::Elbow => (17.98, -2.21),
        Region::Grip => (33.55, -1.61),
        Region::Knee => (19.38, -1.88),
        Region::Shoulder => (14.86, -1.83),
    })
}

fn liu(k_per_min: f64) -> LiuValidation {
    let f_per_s = k_per_min / 60.0;
    let t_s: Vec<f64> = (0..=180).map(|i| i as f64).collect();
    let p = MaParams::new(k_per_min, 0.0).expect("validated k");
    let model: Vec<f64> = t_s
        .iter()
        .map(|&t| {
            let mut s = MaState::FRESH;
            p.hold(&mut s, 1.0, t);
            s.capacity
        })
        .collect();
    let cases = [(10.0, 0.0), (100.0, 0.0), (1000.0, 0.0), (100.0, 0.1)]
        .iter()
        .map(|&(beta, gamma)| {
            let cap: Vec<f64> = t_s
                .iter()
                .map(|&t| liu_capacity(t, f_per_s, beta, gamma))
                .collect();
            let max_abs_diff = cap
                .iter()
                .zip(&model)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            LiuCase {
                beta,
                gamma,
                max_abs_diff,
                capacity: cap,
            }
        })
        .collect();
    LiuValidation {
        f_per_s,
        note: "Liu et al.'s fitted F and R are not used: Ma et al. compare at gamma = 0, beta -> inf, where Eq. 15 is exp(-F t); F = k/60 s is the rate at which it equals the model. Finite beta and gamma > 0 show the distance to the limit.".into(),
        t_s,
        model_capacity: model,
        cases,
    }
}

fn freund_takala(k_per_min: f64) -> FreundTakalaValidation {
    // Depletion form (no recovery): dS0/dt = −β S with S = f·S1 held ⇒ ET = (1 − f)/(β f).
    let fmvc: Vec<f64> = (21..=99).map(|i| i as f64 / 100.0).collect();
    let model: Vec<f64> = fmvc.iter().map(|&f| met_min(f, k_per_min)).collect();
    let ln_beta = fmvc
        .iter()
        .zip(&model)
        .map(|(&f, &m)| ((1.0 - f) / f).ln() - m.ln())
        .sum::<f64>()
        / fmvc.len() as f64;
    let beta = ln_beta.exp();
    let met: Vec<f64> = fmvc.iter().map(|&f| (1.0 - f) / (beta * f)).collect();
    FreundTakalaValidation {
        note: "Eq. 11 as printed uses one rate beta for recovery and depletion: dS0/dt = beta (S1 - S0) - beta S; held at S = f S1 the capacity settles at (1 - f) S1 and reaches S only if f > 0.5. Freund & Takala's fitted constants are not reproduced here; the depletion form (no recovery) is fitted to Eq. 8 instead.".into(),
        beta_per_min: beta,
        r: pearson_r(&met, &model),
        icc: icc_oneway(&met, &model),
        fmvc,
        met_min: met,
        model_met_min: model,
        printed_form_min_exhausting_fmvc: 0.5,
    }
}

fn wexler(k_per_min: f64) -> WexlerValidation {
    let p = MaParams::new(k_per_min, 0.0).expect("validated k");
    let levels: Vec<WexlerLevel> = [0.2, 0.4, 0.6, 0.8, 1.0]
        .iter()
        .map(|&f| WexlerLevel {
            fmvc: f,
            initial_slope_per_min: -k_per_min * f,
            half_capacity_min: p.time_to_capacity_s(1.0, f, 0.5).map_or(f64::NAN, s_to_min),
        })
        .collect();
    let trend_reproduced = levels.windows(2).all(|w| {
        w[1].initial_slope_per_min < w[0].initial_slope_per_min
            && w[1].half_capacity_min < w[0].half_capacity_min
    });
    WexlerValidation {
        note: "Wexler et al.'s Ca2+ model cannot be compared quantitatively (stimulated, not voluntary, contractions); the paper's claim is the trend: higher load, faster decline.".into(),
        levels,
        trend_reproduced,
    }
}

/// Simulated 3CC endurance \[s\]: time until the target can no longer be met (capacity < f).
fn simulate_3cc_endurance_s(m: &ThreeCompartment, f: f64) -> f64 {
    let mut s = ThreeCompartmentState::FRESH;
    let dt = 0.1;
    let mut t = 0.0;
    while t < 36_000.0 {
        m.hold(&mut s, f, dt);
        t += dt;
        if s.capacity() < f {
            return t;
        }
    }
    t
}

fn frey_law_avin(k_per_min: f64) -> Vec<RegionAnchor> {
    let grid: Vec<f64> = (21..=99).map(|i| i as f64 / 100.0).collect();
    let fit_grid: Vec<f64> = (20..=80).map(|i| i as f64 / 100.0).collect();
    Region::ALL
        .iter()
        .filter_map(|&region| {
            let (b0, b1) = frey_law_avin_curve(region)?;
            let curve_min = |f: f64| s_to_min(b0 * f.powf(b1));
            let et: Vec<f64> = grid.iter().map(|&f| curve_min(f)).collect();
            let ma: Vec<f64> = grid.iter().map(|&f| met_min(f, k_per_min)).collect();
            let ln_k = fit_grid
                .iter()
                .map(|&f| (-f.ln() / f).ln() - curve_min(f).ln())
                .sum::<f64>()
                / fit_grid.len() as f64;
            let k_fit = ln_k.exp();
            let ma_fit: Vec<f64> = grid.iter().map(|&f| met_min(f, k_fit)).collect();
            let m3 = ThreeCompartment::for_region(region);
            let levels: Vec<f64> = (1..=9).map(|i| i as f64 / 10.0).collect();
            let sq: f64 = levels
                .iter()
                .map(|&f| {
                    let d = simulate_3cc_endurance_s(&m3, f) - b0 * f.powf(b1);
                    d * d
                })
                .sum();
            Some(RegionAnchor {
                region: region.name().into(),
                b0_s: b0,
                b1,
                r: pearson_r(&et, &ma),
                icc_k1: icc_oneway(&et, &ma),
                fitted_k_per_min: k_fit,
                icc_fitted_k: icc_oneway(&et, &ma_fit),
                three_compartment_rms_s: (sq / levels.len() as f64).sqrt(),
            })
        })
        .collect()
}

/// Runs all dynamic validations at fatigue rate `k_per_min`.
pub fn dynamic_validation(k_per_min: f64) -> DynamicValidation {
    DynamicValidation {
        k_per_min,
        liu: liu(k_per_min),
        freund_takala: freund_takala(k_per_min),
        wexler: wexler(k_per_min),
        frey_law_avin: frey_law_avin(k_per_min),
    }
}
