//! Static validation (paper §3): MET of Eq. 8 against the 24 models of Table 2.

use crate::fatigue::met_min;
use crate::fatigue::met_models::{Deviation, MetModel, TABLE2, table2_grid};
use crate::fatigue::stats::{icc_oneway, pearson_r};
use serde::Serialize;

/// Agreement needed to call a printed figure reproduced (Table 2 prints 4 decimals; the
/// Rohmert posture-5 ICC prints only 3).
pub const TOLERANCE: f64 = 1e-3;

#[derive(Debug, Clone, Serialize)]
pub struct Evidence {
    pub explanation: String,
    /// The equation that reproduces the printed figures.
    pub equation: String,
    /// The row whose equation it is, when the figures belong to another row.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub row: Option<String>,
    pub r: f64,
    pub icc: f64,
    /// Whether this evidence reproduces the printed r and ICC within [`TOLERANCE`].
    pub reproduces: bool,
}

#[derive(Debug, Clone, Serialize)]
pub struct ModelRow {
    pub id: String,
    pub group: String,
    pub reference: String,
    /// The printed equation, as evaluated.
    pub equation: String,
    pub met_min: Vec<f64>,
    pub r: f64,
    pub icc: f64,
    pub published_r: f64,
    pub published_icc: f64,
    /// "reproduced", "explained" (the evidence reproduces the printed figures) or "unexplained".
    pub verdict: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub evidence: Option<Evidence>,
}

#[derive(Debug, Clone, Serialize)]
pub struct StaticValidation {
    pub k_per_min: f64,
    pub fmvc: Vec<f64>,
    pub dynamic_met_min: Vec<f64>,
    pub models: Vec<ModelRow>,
}

fn close(r: f64, icc: f64, m: &MetModel) -> bool {
    (r - m.published_r).abs() <= TOLERANCE && (icc - m.published_icc).abs() <= TOLERANCE
}

/// Runs the static validation with fatigue rate `k_per_min` (the paper: 1).
pub fn static_validation(k_per_min: f64) -> StaticValidation {
    let fmvc = table2_grid();
    let dynamic: Vec<f64> = fmvc.iter().map(|&f| met_min(f, k_per_min)).collect();
    let stats = |eq: &crate::fatigue::met_models::MetEquation| {
        let met: Vec<f64> = fmvc.iter().map(|&f| eq.met_min(f)).collect();
        let r = pearson_r(&met, &dynamic);
        let icc = icc_oneway(&met, &dynamic);
        (met, r, icc)
    };
    let models = TABLE2
        .iter()
        .map(|m| {
            let (met, r, icc) = stats(&m.equation);
            let evidence = m.deviation.map(|d| {
                let (explanation, eq, row) = match d {
                    Deviation::Equation {
                        equation,
                        explanation,
                    } => (explanation, equation, None),
                    Deviation::FiguresOfRow { id, explanation } => {
                        let other =
                            crate::fatigue::met_models::by_id(id).expect("row ids are static");
                        (explanation, other.equation, Some(id.to_string()))
                    }
                };
                let (_, er, eicc) = stats(&eq);
                Evidence {
                    explanation: explanation.to_string(),
                    equation: eq.describe(),
                    row,
                    r: er,
                    icc: eicc,
                    reproduces: close(er, eicc, m),
                }
            });
            let verdict = if close(r, icc, m) {
                "reproduced"
            } else if evidence.as_ref().is_some_and(|e| e.reproduces) {
                "explained"
            } else {
                "unexplained"
            };
            ModelRow {
                id: m.id.to_string(),
                group: m.group.to_string(),
                reference: m.reference.to_string(),
                equation: m.equation.describe(),
                met_min: met,
                r,
                icc,
                published_r: m.published_r,
                published_icc: m.published_icc,
                verdict: verdict.to_string(),
                evidence,
            }
        })
        .collect();
    StaticValidation {
        k_per_min,
        fmvc,
        dynamic_met_min: dynamic,
        models,
    }
}
