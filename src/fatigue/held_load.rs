//! A load held by a fresh muscle group: endurance time and the capacity / U curve.

use super::ma::{CurvePoint, MaParams};
use super::units::min_to_s;
use serde::Serialize;

/// Curve length when a load can be held indefinitely (recovery balances it) \[min\].
pub const UNLIMITED_CURVE_MIN: f64 = 60.0;

#[derive(Debug, Clone, Serialize)]
pub struct HeldLoad {
    pub fmvc: f64,
    /// Maximum endurance time \[min\]; null if the load can be held indefinitely.
    pub met_min: Option<f64>,
    /// Samples from 0 to the endurance time (or [`UNLIMITED_CURVE_MIN`]).
    pub curve: Vec<CurvePoint>,
}

#[derive(Debug, Clone, Serialize)]
pub struct MetReport {
    pub k_per_min: f64,
    pub recovery_per_min: f64,
    /// The largest load held forever under this recovery (fraction of MVC; 0 without recovery).
    pub sustainable_load: f64,
    pub levels: Vec<HeldLoad>,
}

/// MET and curve for each relative load in `levels` (each in (0, 1]).
///
/// ```
/// use posture_opt::fatigue::{met_report, MaParams};
/// let r = met_report(&MaParams::default(), &[0.3], 4);
/// let l = &r.levels[0];
/// assert!((l.met_min.unwrap() - (-(0.3f64).ln() / 0.3)).abs() < 1e-12);
/// // holding f for MET(f) brings capacity down to f
/// assert!((l.curve.last().unwrap().capacity - 0.3).abs() < 1e-12);
/// ```
pub fn met_report(p: &MaParams, levels: &[f64], points: usize) -> MetReport {
    let levels = levels
        .iter()
        .map(|&f| {
            let met_min = p.met_min(f);
            let t_end_s = min_to_s(met_min.unwrap_or(UNLIMITED_CURVE_MIN));
            HeldLoad {
                fmvc: f,
                met_min,
                curve: p.hold_curve(f, t_end_s, points),
            }
        })
        .collect();
    MetReport {
        k_per_min: p.k_per_min,
        recovery_per_min: p.r_at(0.0),
        sustainable_load: p.sustainable_load(),
        levels,
    }
}
