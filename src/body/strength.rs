//! Half-joint strength: each joint direction is a muscle group with its own MVC torque.
//!
//! Strength tables are YAML files beside the URDF (`NAME.strength.yaml` for `NAME.urdf`); see
//! `robots/worker.strength.yaml` for the format, sources and the scaling rule. Half-joint ids are
//! `JOINT+` (produces positive torque) and `JOINT-`. Load of a half-joint: `f± = max(±τ, 0) / MVC±`.

use super::model::BodyModel;
use super::worker::{Sex, Worker};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Torque direction of a half-joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Direction {
    #[serde(rename = "+")]
    Positive,
    #[serde(rename = "-")]
    Negative,
}

impl Direction {
    pub fn sign(self) -> f64 {
        match self {
            Direction::Positive => 1.0,
            Direction::Negative => -1.0,
        }
    }
    pub fn symbol(self) -> &'static str {
        match self {
            Direction::Positive => "+",
            Direction::Negative => "-",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceWorker {
    pub sex: Sex,
    pub stature_m: f64,
    pub mass_kg: f64,
}

/// One row of a strength table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrengthEntry {
    pub joint: String,
    pub direction: Direction,
    /// Muscle-group name.
    pub group: String,
    /// Body region (selects fatigue parameters: trunk, shoulder, elbow, grip, ...).
    pub region: String,
    /// MVC torque of the reference worker at q = 0 [N·m].
    pub mvc_nm: f64,
    /// Female / male strength ratio.
    pub female_factor: f64,
    /// Optional posture dependence: MVC(q) = MVC·clamp(1 + s·q, 0.5, 1.5), q this joint's angle.
    #[serde(default)]
    pub posture_slope_per_rad: Option<f64>,
    pub source: String,
}

/// A strength table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrengthTable {
    pub reference_worker: ReferenceWorker,
    pub mass_exponent: f64,
    pub coefficient_of_variation: f64,
    pub half_joints: Vec<StrengthEntry>,
}

/// Why a strength table could not be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StrengthError {
    #[error("{path}: cannot read: {message}")]
    Io { path: String, message: String },
    #[error("{path}: {message}")]
    Parse { path: String, message: String },
    #[error("{path}: half_joints[{index}] ({joint}{dir}): {problem}")]
    Entry {
        path: String,
        index: usize,
        joint: String,
        dir: &'static str,
        problem: String,
    },
    #[error("{path}: {field}: {problem}")]
    Field {
        path: String,
        field: &'static str,
        problem: String,
    },
}

/// The table shipped with the default worker.
pub const DEFAULT_TABLE_YAML: &str = include_str!("../../robots/worker.strength.yaml");

/// Standard normal quantile (Acklam's rational approximation, |error| < 1.2e-9).
pub fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969683028665376e1,
        2.209460984245205e2,
        -2.759285104469687e2,
        1.38357751867269e2,
        -3.066479806614716e1,
        2.506628277459239,
    ];
    const B: [f64; 5] = [
        -5.447609879822406e1,
        1.615858368580409e2,
        -1.556989798598866e2,
        6.680131188771972e1,
        -1.328068155288572e1,
    ];
    const C: [f64; 6] = [
        -7.784894002430293e-3,
        -3.223964580411365e-1,
        -2.400758277161838,
        -2.549732539343734,
        4.374664141464968,
        2.938163982698783,
    ];
    const D: [f64; 4] = [
        7.784695709041462e-3,
        3.224671290700398e-1,
        2.445134137142996,
        3.754408661907416,
    ];
    let pl = 0.02425;
    if p < pl {
        let q = (-2.0 * p.ln()).sqrt();
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    } else if p <= 1.0 - pl {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    } else {
        -normal_quantile(1.0 - p)
    }
}

impl StrengthTable {
    /// Parses and checks a table; `origin` names the file in messages.
    pub fn from_yaml_str(text: &str, origin: &str) -> Result<Self, StrengthError> {
        let t: StrengthTable = serde_saphyr::from_str(text).map_err(|e| StrengthError::Parse {
            path: origin.into(),
            message: e.to_string(),
        })?;
        let field = |field: &'static str, problem: String| StrengthError::Field {
            path: origin.into(),
            field,
            problem,
        };
        let rw = &t.reference_worker;
        if !(rw.mass_kg.is_finite() && rw.mass_kg > 0.0) {
            return Err(field(
                "reference_worker.mass_kg",
                format!("must be > 0, got {}", rw.mass_kg),
            ));
        }
        if rw.sex != Sex::Male {
            return Err(field(
                "reference_worker.sex",
                "must be male (female_factor scales to women)".into(),
            ));
        }
        if !(t.mass_exponent.is_finite() && (0.0..=2.0).contains(&t.mass_exponent)) {
            return Err(field(
                "mass_exponent",
                format!("must be in [0, 2], got {}", t.mass_exponent),
            ));
        }
        if !(t.coefficient_of_variation.is_finite()
            && (0.0..=0.5).contains(&t.coefficient_of_variation))
        {
            return Err(field(
                "coefficient_of_variation",
                format!("must be in [0, 0.5], got {}", t.coefficient_of_variation),
            ));
        }
        for (i, e) in t.half_joints.iter().enumerate() {
            let bad = |problem: String| StrengthError::Entry {
                path: origin.into(),
                index: i,
                joint: e.joint.clone(),
                dir: e.direction.symbol(),
                problem,
            };
            if !(e.mvc_nm.is_finite() && e.mvc_nm > 0.0) {
                return Err(bad(format!("mvc_nm must be > 0, got {}", e.mvc_nm)));
            }
            if !(e.female_factor.is_finite() && e.female_factor > 0.0 && e.female_factor <= 1.5) {
                return Err(bad(format!(
                    "female_factor must be in (0, 1.5], got {}",
                    e.female_factor
                )));
            }
            if e.posture_slope_per_rad.is_some_and(|s| !s.is_finite()) {
                return Err(bad("posture_slope_per_rad must be finite".into()));
            }
            if t.half_joints[..i]
                .iter()
                .any(|o| o.joint == e.joint && o.direction == e.direction)
            {
                return Err(bad("is listed twice".into()));
            }
        }
        Ok(t)
    }

    /// Reads a table file.
    pub fn from_file(path: &Path) -> Result<Self, StrengthError> {
        let p = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| StrengthError::Io {
            path: p.clone(),
            message: e.to_string(),
        })?;
        Self::from_yaml_str(&text, &p)
    }

    /// The table shipped with the default worker.
    pub fn default_table() -> Self {
        Self::from_yaml_str(DEFAULT_TABLE_YAML, "robots/worker.strength.yaml")
            .expect("the shipped strength table is valid")
    }

    /// The strength file that belongs to a URDF: `NAME.strength.yaml` beside `NAME.urdf`.
    pub fn path_beside(urdf: &Path) -> PathBuf {
        urdf.with_extension("strength.yaml")
    }

    pub fn entry(&self, joint: &str, dir: Direction) -> Option<&StrengthEntry> {
        self.half_joints
            .iter()
            .find(|e| e.joint == joint && e.direction == dir)
    }

    /// Scale factor from the reference worker to `w`.
    pub fn worker_factor(&self, e: &StrengthEntry, w: &Worker) -> f64 {
        let sex = if w.sex == Sex::Female {
            e.female_factor
        } else {
            1.0
        };
        let mass = (w.mass_kg / self.reference_worker.mass_kg).powf(self.mass_exponent);
        let z = normal_quantile(w.strength_percentile / 100.0);
        let pct = (1.0 + z * self.coefficient_of_variation).max(0.2);
        sex * mass * pct
    }

    /// MVC [N·m] of half-joint (`joint`, `dir`) for worker `w` at q = 0.
    pub fn mvc_nm(&self, joint: &str, dir: Direction, w: &Worker) -> Option<f64> {
        self.entry(joint, dir)
            .map(|e| e.mvc_nm * self.worker_factor(e, w))
    }

    /// The larger MVC of the two directions of `joint`, for `w`.
    pub fn max_mvc_nm(&self, joint: &str, w: &Worker) -> Option<f64> {
        let a = self.mvc_nm(joint, Direction::Positive, w);
        let b = self.mvc_nm(joint, Direction::Negative, w);
        match (a, b) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        }
    }
}

/// A resolved half-joint of a body model for one worker.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HalfJoint {
    /// `JOINT+` or `JOINT-`.
    pub id: String,
    pub joint: String,
    #[serde(skip)]
    pub q_index: usize,
    pub direction: Direction,
    pub group: String,
    pub region: String,
    /// MVC at q = 0 [N·m].
    pub mvc_nm: f64,
    #[serde(skip)]
    pub posture_slope_per_rad: Option<f64>,
    pub source: String,
}

impl HalfJoint {
    /// MVC [N·m] at joint angle `q_rad` (posture dependence, if any).
    #[inline]
    pub fn mvc_at(&self, q_rad: f64) -> f64 {
        match self.posture_slope_per_rad {
            Some(s) => self.mvc_nm * (1.0 + s * q_rad).clamp(0.5, 1.5),
            None => self.mvc_nm,
        }
    }

    /// Relative load `f = max(±τ, 0) / MVC` for holding torque `tau_nm` at angle `q_rad`.
    #[inline]
    pub fn load(&self, tau_nm: f64, q_rad: f64) -> f64 {
        (self.direction.sign() * tau_nm).max(0.0) / self.mvc_at(q_rad)
    }
}

/// Resolves the two half-joints of every moving joint of `model` for worker `w`: from the table
/// where it has an entry, else from the URDF `<limit effort>` (said so in `source`). A moving
/// joint with neither is an error.
pub fn resolve_half_joints(
    model: &BodyModel,
    table: &StrengthTable,
    w: &Worker,
    origin: &str,
) -> Result<Vec<HalfJoint>, StrengthError> {
    let mut out = Vec::with_capacity(2 * model.nq());
    for q in 0..model.nq() {
        let j = model.q_joint(q);
        for dir in [Direction::Positive, Direction::Negative] {
            let id = format!("{}{}", j.name, dir.symbol());
            let hj = match table.entry(&j.name, dir) {
                Some(e) => HalfJoint {
                    id,
                    joint: j.name.clone(),
                    q_index: q,
                    direction: dir,
                    group: e.group.clone(),
                    region: e.region.clone(),
                    mvc_nm: e.mvc_nm * table.worker_factor(e, w),
                    posture_slope_per_rad: e.posture_slope_per_rad,
                    source: e.source.clone(),
                },
                None if j.effort > 0.0 => HalfJoint {
                    id,
                    joint: j.name.clone(),
                    q_index: q,
                    direction: dir,
                    group: format!(
                        "{} {}",
                        j.name,
                        if dir == Direction::Positive {
                            "positive"
                        } else {
                            "negative"
                        }
                    ),
                    region: "general".into(),
                    mvc_nm: j.effort,
                    posture_slope_per_rad: None,
                    source:
                        "URDF <limit effort> (no strength-table entry; not scaled to the worker)"
                            .into(),
                },
                None => {
                    return Err(StrengthError::Entry {
                        path: origin.into(),
                        index: table.half_joints.len(),
                        joint: j.name.clone(),
                        dir: dir.symbol(),
                        problem: "no strength-table entry and no URDF <limit effort> > 0".into(),
                    })
                }
            };
            out.push(hj);
        }
    }
    Ok(out)
}
