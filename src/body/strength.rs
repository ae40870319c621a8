//! Half-joint strength: each joint direction is a muscle group with its own MVC torque.
//!
//! Strength tables are YAML files beside the URDF (`NAME.strength.yaml` for `NAME.urdf`); the
//! shipped one, `robots/worker.strength.yaml`, gives for every half-joint of the generated worker
//! the population mean and standard deviation of maximum isometric torque for men and women, the
//! posture where they were measured, posture dependence, and the source of every number
//! (`docs/strength.md` has the table). Half-joint ids are `JOINT+` (produces positive torque) and
//! `JOINT-`. Load of a half-joint: `f± = max(±τ, 0) / MVC±(q)`.
//!
//! **One scaling.** A worker of sex s at strength percentile p has
//! `MVC = max(mean_s + z_p · sd_s, 0.05 · mean_s) × Π posture factors(q)`, `z_p` the standard
//! normal quantile. The population SDs already contain body size, so nothing else scales it.
//! Posture factors are shape-preserving cubic (PCHIP) interpolants of the table's points, so the
//! MVC is smooth in q for the optimiser and exact at every tabulated angle.

use super::model::BodyModel;
use super::worker::{Sex, Worker};
use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, Normal};
use std::path::{Path, PathBuf};

/// Torque direction of a half-joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
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

/// Body side of a two-sided entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TableSide {
    R,
    L,
}

impl TableSide {
    fn prefix(self) -> &'static str {
        match self {
            TableSide::R => "r_",
            TableSide::L => "l_",
        }
    }
    fn word(self) -> &'static str {
        match self {
            TableSide::R => "right",
            TableSide::L => "left",
        }
    }
}

/// Population mean and standard deviation of an MVC torque \[N·m\].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeanSd {
    pub mean_nm: f64,
    pub sd_nm: f64,
}

/// A posture factor on the mean: `factor` at `deg` of `joint` (same side as the muscle group
/// when written without a side prefix), or of the sum of `joint`'s and `plus`'s angles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PostureCurve {
    pub joint: String,
    /// Joints whose angles add to `joint`'s (same naming rule): the curve's angle is the sum,
    /// e.g. `lumbar_flexion` plus `pelvis_tilt`, the trunk's forward inclination from upright.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub plus: Vec<String>,
    pub deg: Vec<f64>,
    pub factor: Vec<f64>,
}

/// One row of a strength table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrengthEntry {
    /// Joint name, without the side prefix when `sides` is given.
    pub joint: String,
    #[serde(default)]
    pub sides: Option<Vec<TableSide>>,
    pub direction: Direction,
    /// Muscle-group name in words ("shoulder flexors"); two-sided groups get "right"/"left".
    pub group: String,
    /// Body region (selects fatigue parameters: trunk, neck, shoulder, elbow, grip, hip, knee, ankle).
    pub region: String,
    pub male: MeanSd,
    pub female: MeanSd,
    #[serde(default)]
    pub reference_posture: String,
    #[serde(default)]
    pub posture: Vec<PostureCurve>,
    pub source: String,
}

/// A strength table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrengthTable {
    /// Joints without muscles (a floating base): no half-joints, their torque must vanish.
    #[serde(default)]
    pub unactuated: Vec<String>,
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
    #[error("{path}: joint '{joint}': {problem}")]
    Joint {
        path: String,
        joint: String,
        problem: String,
    },
}

/// The table shipped with the default worker.
pub const DEFAULT_TABLE_YAML: &str = include_str!("../../robots/worker.strength.yaml");

/// Standard normal quantile of probability `p` in (0, 1).
pub fn normal_quantile(p: f64) -> f64 {
    standard_normal().inverse_cdf(p)
}

/// Standard normal cumulative probability of `z`.
pub fn normal_cdf(z: f64) -> f64 {
    standard_normal().cdf(z)
}

fn standard_normal() -> Normal {
    Normal::standard()
}

impl StrengthEntry {
    fn stats(&self, sex: Sex) -> MeanSd {
        match sex {
            Sex::Male => self.male,
            Sex::Female => self.female,
        }
    }

    /// MVC \[N·m\] at the reference posture for a worker of sex `sex` at strength percentile
    /// `percentile` (1–99).
    pub fn mvc_at_percentile(&self, sex: Sex, percentile: f64) -> f64 {
        let s = self.stats(sex);
        let z = normal_quantile(percentile / 100.0);
        (s.mean_nm + z * s.sd_nm).max(0.05 * s.mean_nm)
    }

    fn side_names(&self) -> Vec<(String, Option<TableSide>)> {
        match &self.sides {
            Some(sides) => sides
                .iter()
                .map(|s| (format!("{}{}", s.prefix(), self.joint), Some(*s)))
                .collect(),
            None => vec![(self.joint.clone(), None)],
        }
    }
}

impl StrengthTable {
    /// Parses and checks a table; `origin` names the file in messages.
    pub fn from_yaml_str(text: &str, origin: &str) -> Result<Self, StrengthError> {
        let t: StrengthTable = serde_saphyr::from_str(text).map_err(|e| StrengthError::Parse {
            path: origin.into(),
            message: e.to_string(),
        })?;
        let mut seen = std::collections::HashSet::new();
        for (i, e) in t.half_joints.iter().enumerate() {
            let bad = |problem: String| StrengthError::Entry {
                path: origin.into(),
                index: i,
                joint: e.joint.clone(),
                dir: e.direction.symbol(),
                problem,
            };
            for (sex, s) in [("male", e.male), ("female", e.female)] {
                if !(s.mean_nm.is_finite() && s.mean_nm > 0.0 && s.mean_nm <= 5000.0) {
                    return Err(bad(format!(
                        "{sex}.mean_nm must be within 0..5000 N·m, got {}",
                        s.mean_nm
                    )));
                }
                if !(s.sd_nm.is_finite() && s.sd_nm >= 0.0 && s.sd_nm <= s.mean_nm) {
                    return Err(bad(format!(
                        "{sex}.sd_nm must be within 0..mean ({}), got {}",
                        s.mean_nm, s.sd_nm
                    )));
                }
            }
            for (k, c) in e.posture.iter().enumerate() {
                let at = |what: &str| format!("posture[{k}] ({}): {what}", c.joint);
                if c.deg.len() < 2 || c.deg.len() != c.factor.len() {
                    return Err(bad(at(
                        "deg and factor must have the same length, at least 2",
                    )));
                }
                if !c.deg.iter().all(|x| x.is_finite()) || c.deg.windows(2).any(|w| w[1] <= w[0]) {
                    return Err(bad(at("deg must be finite and strictly increasing")));
                }
                if !c
                    .factor
                    .iter()
                    .all(|x| x.is_finite() && *x > 0.0 && *x <= 10.0)
                {
                    return Err(bad(at("factor values must be within 0..10 and > 0")));
                }
            }
            for (name, _) in e.side_names() {
                if !seen.insert((name.clone(), e.direction)) {
                    return Err(bad(format!(
                        "{name}{} is listed twice",
                        e.direction.symbol()
                    )));
                }
            }
        }
        Ok(t)
    }

    /// Reads a table file.
    pub fn from_file(path: &Path) -> Result<Self, StrengthError> {
        let p = path.display().to_string();
        let text = crate::io::read_text(path).map_err(|e| StrengthError::Io {
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

    /// The entry for a full joint name (with side prefix) and direction, with its side.
    pub fn entry(
        &self,
        joint: &str,
        dir: Direction,
    ) -> Option<(&StrengthEntry, Option<TableSide>)> {
        self.half_joints
            .iter()
            .filter(|e| e.direction == dir)
            .find_map(|e| {
                e.side_names()
                    .into_iter()
                    .find(|(n, _)| n == joint)
                    .map(|(_, s)| (e, s))
            })
    }

    /// MVC \[N·m\] of half-joint (`joint`, `dir`) for worker `w` at the reference posture.
    pub fn mvc_nm(&self, joint: &str, dir: Direction, w: &Worker) -> Option<f64> {
        self.entry(joint, dir)
            .map(|(e, _)| e.mvc_at_percentile(w.sex, w.strength_percentile))
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

    /// Whether a joint is listed as unactuated.
    pub fn is_unactuated(&self, joint: &str) -> bool {
        self.unactuated.iter().any(|j| j == joint)
    }
}

/// A shape-preserving cubic (PCHIP, Fritsch & Carlson 1980) through `(x_i, y_i)`, constant
/// beyond the ends. Smooth (C¹) and monotone wherever the data are.
#[derive(Debug, Clone, PartialEq)]
pub struct Pchip {
    x: Vec<f64>,
    y: Vec<f64>,
    d: Vec<f64>,
}

impl Pchip {
    /// `x` strictly increasing, at least two points (checked by the table's parser).
    pub fn new(x: Vec<f64>, y: Vec<f64>) -> Self {
        let n = x.len();
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let delta: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
        let mut d = vec![0.0; n];
        if n == 2 {
            d = vec![delta[0]; 2];
        } else {
            for i in 1..n - 1 {
                if delta[i - 1] * delta[i] > 0.0 {
                    let (w1, w2) = (2.0 * h[i] + h[i - 1], h[i] + 2.0 * h[i - 1]);
                    d[i] = (w1 + w2) / (w1 / delta[i - 1] + w2 / delta[i]);
                }
            }
            let end = |h0: f64, h1: f64, d0: f64, d1: f64| {
                let e = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
                if e * d0 <= 0.0 {
                    0.0
                } else if d0 * d1 <= 0.0 && e.abs() > 3.0 * d0.abs() {
                    3.0 * d0
                } else {
                    e
                }
            };
            d[0] = end(h[0], h[1], delta[0], delta[1]);
            d[n - 1] = end(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
        }
        Pchip { x, y, d }
    }

    /// Value, slope and curvature at `t` (slope and curvature 0 beyond the ends, where the
    /// value is held).
    pub fn eval2(&self, t: f64) -> (f64, f64, f64) {
        let n = self.x.len();
        if t.is_nan() || t <= self.x[0] || t >= self.x[n - 1] {
            let (v, dv) = self.eval(t);
            return (v, dv, 0.0);
        }
        let (v, dv) = self.eval(t);
        let i = self.x.partition_point(|&xi| xi <= t) - 1;
        let h = self.x[i + 1] - self.x[i];
        let s = (t - self.x[i]) / h;
        let (c00, c10, c01, c11) = (12.0 * s - 6.0, 6.0 * s - 4.0, 6.0 - 12.0 * s, 6.0 * s - 2.0);
        let ddv = (c00 * self.y[i] + c01 * self.y[i + 1]) / (h * h)
            + (c10 * self.d[i] + c11 * self.d[i + 1]) / h;
        (v, dv, ddv)
    }

    /// Value and slope at `t` (slope 0 beyond the ends, where the value is held).
    pub fn eval(&self, t: f64) -> (f64, f64) {
        let n = self.x.len();
        if t.is_nan() || t <= self.x[0] {
            return (self.y[0], 0.0);
        }
        if t >= self.x[n - 1] {
            return (self.y[n - 1], 0.0);
        }
        let i = self.x.partition_point(|&xi| xi <= t) - 1;
        let h = self.x[i + 1] - self.x[i];
        let s = (t - self.x[i]) / h;
        let (s2, s3) = (s * s, s * s * s);
        let (h00, h10, h01, h11) = (
            2.0 * s3 - 3.0 * s2 + 1.0,
            s3 - 2.0 * s2 + s,
            -2.0 * s3 + 3.0 * s2,
            s3 - s2,
        );
        let v =
            h00 * self.y[i] + h10 * h * self.d[i] + h01 * self.y[i + 1] + h11 * h * self.d[i + 1];
        let (d00, d10, d01, d11) = (
            6.0 * s2 - 6.0 * s,
            3.0 * s2 - 4.0 * s + 1.0,
            -6.0 * s2 + 6.0 * s,
            3.0 * s2 - 2.0 * s,
        );
        let dv =
            (d00 * self.y[i] + d01 * self.y[i + 1]) / h + d10 * self.d[i] + d11 * self.d[i + 1];
        (v, dv)
    }
}

/// A posture factor resolved onto a model: the q indices of the joints whose angles it sums
/// (usually one) and its curve (radians).
#[derive(Debug, Clone, PartialEq)]
pub struct PostureFactor {
    pub q_indices: Vec<usize>,
    pub curve: Pchip,
}

impl PostureFactor {
    /// The curve's angle at `q_rad` \[rad\].
    #[inline]
    pub fn angle(&self, q_rad: &[f64]) -> f64 {
        self.q_indices.iter().map(|&i| q_rad[i]).sum()
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
    /// Muscle group in words, with the side ("right shoulder flexors").
    pub group: String,
    pub region: String,
    /// MVC at the reference posture \[N·m\] for this worker.
    pub mvc_nm: f64,
    /// Population mean and SD of men and of women at the reference posture \[N·m\]
    /// (for % capable; equal for a URDF-effort fallback).
    pub male: MeanSd,
    pub female: MeanSd,
    #[serde(skip)]
    pub posture: Vec<PostureFactor>,
    pub source: String,
}

impl HalfJoint {
    /// Posture factor at `q` (product of the curves) and its gradient, written into `grad`
    /// (only the curves' joints; the caller zeroes `grad` once). Returns the factor.
    pub fn posture_factor(&self, q_rad: &[f64]) -> f64 {
        self.posture
            .iter()
            .map(|p| p.curve.eval(p.angle(q_rad)).0)
            .product()
    }

    /// MVC \[N·m\] at posture `q_rad`.
    #[inline]
    pub fn mvc_at(&self, q_rad: &[f64]) -> f64 {
        if self.posture.is_empty() {
            self.mvc_nm
        } else {
            self.mvc_nm * self.posture_factor(q_rad)
        }
    }

    /// ∂MVC/∂q as (q index, value) pairs at `q_rad`, one pair per index.
    pub fn mvc_gradient(&self, q_rad: &[f64], out: &mut Vec<(usize, f64)>) {
        out.clear();
        for (k, p) in self.posture.iter().enumerate() {
            let others: f64 = self
                .posture
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != k)
                .map(|(_, o)| o.curve.eval(o.angle(q_rad)).0)
                .product();
            let d = self.mvc_nm * p.curve.eval(p.angle(q_rad)).1 * others;
            for &i in &p.q_indices {
                match out.iter_mut().find(|(j, _)| *j == i) {
                    Some((_, v)) => *v += d,
                    None => out.push((i, d)),
                }
            }
        }
    }

    /// ∂²MVC/∂q_i∂q_k at `q_rad` as (i, k, value) triples (both orders of a pair; a pair may
    /// appear more than once, the values to be added), into `out`.
    pub fn mvc_hessian(&self, q_rad: &[f64], out: &mut Vec<(usize, usize, f64)>) {
        out.clear();
        let at = |p: &PostureFactor| p.curve.eval2(p.angle(q_rad));
        for (a, pa) in self.posture.iter().enumerate() {
            let (_, da, dda) = at(pa);
            for (b, pb) in self.posture.iter().enumerate() {
                // the product's second derivative in the angles of factors a and b
                let mut t = if a == b { dda } else { da * at(pb).1 };
                for (r, pr) in self.posture.iter().enumerate() {
                    if r != a && r != b {
                        t *= at(pr).0;
                    }
                }
                let t = self.mvc_nm * t;
                if t == 0.0 {
                    continue;
                }
                for &i in &pa.q_indices {
                    for &k in &pb.q_indices {
                        out.push((i, k, t));
                    }
                }
            }
        }
    }

    /// Relative load `f = max(±τ, 0) / MVC(q)` for holding torque `tau_nm` at posture `q_rad`.
    #[inline]
    pub fn load(&self, tau_nm: f64, q_rad: &[f64]) -> f64 {
        (self.direction.sign() * tau_nm).max(0.0) / self.mvc_at(q_rad)
    }

    /// Whether the MVC depends on posture.
    pub fn posture_dependent(&self) -> bool {
        !self.posture.is_empty()
    }
}

/// Smallest URDF `<limit effort>` taken as a strength \[N·m or N\] (a weaker "muscle" would
/// give relative loads of astronomical size).
pub const MIN_EFFORT_NM: f64 = 1e-3;

/// Resolves the two half-joints of every actuated moving joint of `model` for worker `w`: from
/// the table where it has an entry, else from the URDF `<limit effort>` (said so in `source`).
/// An actuated moving joint with neither is an error; so is an unactuated joint the model lacks.
pub fn resolve_half_joints(
    model: &BodyModel,
    table: &StrengthTable,
    w: &Worker,
    origin: &str,
) -> Result<Vec<HalfJoint>, StrengthError> {
    for j in &table.unactuated {
        if model.q_index(j).is_err() {
            return Err(StrengthError::Joint {
                path: origin.into(),
                joint: j.clone(),
                problem: "is listed as unactuated but is not a moving joint of the robot".into(),
            });
        }
    }
    // every entry must name a moving joint of the robot (on each side it lists) and a known
    // body region: a misspelt entry would otherwise be ignored in silence
    for (index, e) in table.half_joints.iter().enumerate() {
        let entry_err = |problem: String| StrengthError::Entry {
            path: origin.into(),
            index,
            joint: e.joint.clone(),
            dir: e.direction.symbol(),
            problem,
        };
        let names: Vec<String> = match &e.sides {
            Some(sides) => sides
                .iter()
                .map(|s| format!("{}{}", s.prefix(), e.joint))
                .collect(),
            None => vec![e.joint.clone()],
        };
        for n in &names {
            if model.q_index(n).is_err() {
                let joints = (0..model.nq()).map(|k| model.q_joint(k).name.as_str());
                return Err(entry_err(format!(
                    "'{n}' is not a moving joint of the robot{}",
                    crate::schema::did_you_mean(n, joints)
                )));
            }
        }
        if !crate::fatigue::fit::REGIONS.contains(&e.region.as_str()) {
            return Err(entry_err(format!(
                "region '{}' is not one of {}{}",
                e.region,
                crate::fatigue::fit::REGIONS.join(", "),
                crate::schema::did_you_mean(
                    &e.region,
                    crate::fatigue::fit::REGIONS.iter().copied()
                )
            )));
        }
    }
    let mut out = Vec::with_capacity(2 * model.nq());
    for q in 0..model.nq() {
        let j = model.q_joint(q);
        if table.is_unactuated(&j.name) {
            continue;
        }
        for dir in [Direction::Positive, Direction::Negative] {
            let id = format!("{}{}", j.name, dir.symbol());
            let hj = match table.entry(&j.name, dir) {
                Some((e, side)) => {
                    let mut posture = Vec::with_capacity(e.posture.len());
                    for c in &e.posture {
                        let mut q_indices = Vec::with_capacity(1 + c.plus.len());
                        for joint in std::iter::once(&c.joint).chain(&c.plus) {
                            let name = match side {
                                Some(s) if model.q_index(joint).is_err() => {
                                    format!("{}{}", s.prefix(), joint)
                                }
                                _ => joint.clone(),
                            };
                            let qi = model.q_index(&name).map_err(|_| StrengthError::Joint {
                                path: origin.into(),
                                joint: j.name.clone(),
                                problem: format!(
                                    "posture curve names joint '{name}', which the robot does not have"
                                ),
                            })?;
                            if q_indices.contains(&qi) {
                                return Err(StrengthError::Joint {
                                    path: origin.into(),
                                    joint: j.name.clone(),
                                    problem: format!("posture curve names joint '{name}' twice"),
                                });
                            }
                            q_indices.push(qi);
                        }
                        posture.push(PostureFactor {
                            q_indices,
                            curve: Pchip::new(
                                c.deg.iter().map(|d| d.to_radians()).collect(),
                                c.factor.clone(),
                            ),
                        });
                    }
                    HalfJoint {
                        id,
                        joint: j.name.clone(),
                        q_index: q,
                        direction: dir,
                        group: match side {
                            Some(s) => format!("{} {}", s.word(), e.group),
                            None => e.group.clone(),
                        },
                        region: e.region.clone(),
                        mvc_nm: e.mvc_at_percentile(w.sex, w.strength_percentile),
                        male: e.male,
                        female: e.female,
                        posture,
                        source: e.source.clone(),
                    }
                }
                None if j.effort >= MIN_EFFORT_NM => HalfJoint {
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
                    male: MeanSd {
                        mean_nm: j.effort,
                        sd_nm: 0.0,
                    },
                    female: MeanSd {
                        mean_nm: j.effort,
                        sd_nm: 0.0,
                    },
                    posture: Vec::new(),
                    source:
                        "URDF <limit effort> (no strength-table entry; not scaled to the worker)"
                            .into(),
                },
                None => {
                    return Err(StrengthError::Joint {
                        path: origin.into(),
                        joint: format!("{}{}", j.name, dir.symbol()),
                        problem: if j.effort > 0.0 {
                            format!(
                                "no strength-table entry, and its URDF <limit effort> {:e} is below {MIN_EFFORT_NM:e} N·m, too small for a muscle's strength",
                                j.effort
                            )
                        } else {
                            "no strength-table entry and no URDF <limit effort> > 0 (list it under `unactuated` if it has no muscles)".into()
                        },
                    });
                }
            };
            out.push(hj);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pchip_passes_through_points_and_its_slope_matches_differences() {
        let p = Pchip::new(vec![0.0, 1.0, 2.0, 4.0], vec![1.0, 0.8, 0.9, 0.3]);
        for (x, y) in [(0.0, 1.0), (1.0, 0.8), (2.0, 0.9), (4.0, 0.3)] {
            assert!((p.eval(x).0 - y).abs() < 1e-15);
        }
        for &t in &[0.3, 1.5, 2.7, 3.9] {
            let h = 1e-6;
            let fd = (p.eval(t + h).0 - p.eval(t - h).0) / (2.0 * h);
            assert!((p.eval(t).1 - fd).abs() < 1e-6, "{t}");
            // the curvature is the slope's central difference, value and slope as `eval`'s
            let fd2 = (p.eval(t + h).1 - p.eval(t - h).1) / (2.0 * h);
            let (v, dv, ddv) = p.eval2(t);
            assert!((ddv - fd2).abs() < 1e-6, "{t}: {ddv} vs {fd2}");
            assert_eq!((v, dv), p.eval(t));
        }
        // held beyond the ends: no slope, no curvature
        assert_eq!(p.eval2(-1.0), (1.0, 0.0, 0.0));
        assert_eq!(p.eval2(5.0), (0.3, 0.0, 0.0));
        // monotone data stay monotone between the points
        let m = Pchip::new(vec![0.0, 1.0, 3.0], vec![0.0, 0.1, 1.0]);
        let mut last = -1.0;
        for i in 0..=300 {
            let v = m.eval(i as f64 / 100.0).0;
            assert!(v >= last);
            last = v;
        }
    }

    /// ∂²MVC/∂q² of a half-joint whose strength is the product of two curves, one of them of
    /// two joints' summed angle, against central differences of its gradient.
    #[test]
    fn mvc_second_derivatives_match_differences_of_the_gradient() {
        let curve = |y: Vec<f64>| Pchip::new(vec![-1.0, 0.0, 0.8, 1.6], y);
        let hj = HalfJoint {
            id: "test+".into(),
            joint: "test".into(),
            q_index: 0,
            direction: Direction::Positive,
            group: "test".into(),
            region: "test".into(),
            mvc_nm: 120.0,
            male: MeanSd {
                mean_nm: 120.0,
                sd_nm: 10.0,
            },
            female: MeanSd {
                mean_nm: 80.0,
                sd_nm: 10.0,
            },
            posture: vec![
                PostureFactor {
                    q_indices: vec![0, 2],
                    curve: curve(vec![0.7, 1.0, 0.9, 0.5]),
                },
                PostureFactor {
                    q_indices: vec![2],
                    curve: curve(vec![0.8, 1.0, 1.1, 0.6]),
                },
            ],
            source: "test".into(),
        };
        let n = 3;
        for q in [[0.3, 0.0, 0.2], [-0.4, 0.5, 0.9], [0.7, -0.2, -0.5]] {
            let mut exact = vec![0.0; n * n];
            let mut pairs = Vec::new();
            hj.mvc_hessian(&q, &mut pairs);
            for &(i, k, v) in &pairs {
                exact[i * n + k] += v;
            }
            let h = 1e-6;
            let mut grad = Vec::new();
            for k in 0..n {
                let mut side = [vec![0.0; n], vec![0.0; n]];
                for (s, x) in [q[k] - h, q[k] + h].into_iter().enumerate() {
                    let mut moved = q;
                    moved[k] = x;
                    hj.mvc_gradient(&moved, &mut grad);
                    for &(i, v) in &grad {
                        side[s][i] += v;
                    }
                }
                for i in 0..n {
                    let fd = (side[1][i] - side[0][i]) / (2.0 * h);
                    assert!(
                        (exact[i * n + k] - fd).abs() < 1e-5 * 120.0,
                        "{q:?} ({i}, {k}): {} vs {fd}",
                        exact[i * n + k]
                    );
                }
            }
            // the joint no curve reads has no curvature; the two others do
            assert!((0..n).all(|k| exact[n + k] == 0.0 && exact[k * n + 1] == 0.0));
            assert!(exact[0] != 0.0 && exact[2 * n + 2] != 0.0 && exact[2] != 0.0);
        }
    }
}
