//! Fitting the model to a user's own measurements: k per body region (and the recovery rate at
//! rest) from endurance times or capacity decline, sustained or intermittent holds.
//!
//! **Data** (CSV, header first; one row per measurement):
//!
//! | column | meaning |
//! |---|---|
//! | `region` | body region: general, trunk, neck, shoulder, elbow, grip, hip, knee, ankle |
//! | `load_fmvc` | the held load, fraction of MVC (0 < f ≤ 1) |
//! | `on_s`, `off_s` | intermittent holds: seconds on, seconds off (both empty or `off_s` = 0: sustained) |
//! | `endurance_s` | measured time until the load could no longer be held (from the start), or empty |
//! | `t_s`, `capacity` | or: capacity (fraction of MVC, 0..1] measured at time `t_s` from the start |
//!
//! Each row gives either `endurance_s`, or `t_s` and `capacity`.
//!
//! **Model**: `dc/dt = −k f c + R(f)(1 − c)` with the perfusion-limited recovery
//! `R(f) = R_rest · x²(3 − 2x)`, `x = 1 − f/f_lim` (no recovery above `f_lim`), held exactly
//! over each on and off interval. **Fitted**: ln k per region, and ln R_rest (shared) when the data
//! contain intermittent holds; `f_lim` is fixed (given). **Residuals** are log ratios (predicted
//! over measured endurance time or capacity), so every row counts as a relative error; a
//! predicted endurance beyond 24 h counts as 24 h. **Method**: Levenberg–Marquardt on the log
//! parameters with a finite-difference Jacobian. **Confidence intervals** (95 %): the
//! asymptotic covariance `s² (JᵀJ)⁻¹`, `s² = SSR/(n − p)`, with Student's t for n − p degrees of
//! freedom, on the log parameters, then exponentiated (so they stay positive). Intermittent
//! endurance rows predict a staircase in the parameters (exhaustion moves from one work period
//! to the next); their Jacobian rows take the slope over ±0.1 in the log parameters, so a fit
//! whose optimum sits on a step does not report a collapsed interval.

use super::ma::{K_MAX_PER_MIN, K_MIN_PER_MIN, MaParams, MaState, Recovery};
use super::params::{ParameterSet, RecoverySpec, RegionK};
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::collections::BTreeMap;

/// Regions a row may name.
pub const REGIONS: [&str; 9] = [
    "general", "trunk", "neck", "shoulder", "elbow", "grip", "hip", "knee", "ankle",
];

/// Longest endurance a prediction may reach \[s\] (24 h).
pub const MAX_ENDURANCE_S: f64 = 86_400.0;

/// Most rows read.
pub const MAX_ROWS: usize = 100_000;

/// One measurement.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub line: usize,
    pub region: String,
    pub load_fmvc: f64,
    /// (on, off) seconds for intermittent holds.
    pub cycle_s: Option<(f64, f64)>,
    pub what: Measured,
}

/// What a row measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measured {
    EnduranceS(f64),
    Capacity {
        t_s: f64,
        capacity: f64,
    },
    /// A hold to exhaustion from rest, a rest of `rest_s`, and the same hold again to
    /// exhaustion: the second endurance over the first (Stull & Kearney 1978's protocol).
    SecondBout {
        rest_s: f64,
        ratio: f64,
    },
}

/// Why the data or the fit were refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("{file}: line {line}: {problem}")]
    Row {
        file: String,
        line: usize,
        problem: String,
    },
    #[error("{file}: {problem}")]
    Data { file: String, problem: String },
}

/// Parses the data (`file` names it in messages).
pub fn parse_rows(text: &str, file: &str) -> Result<Vec<Row>, FitError> {
    let mut rdr = ::csv::ReaderBuilder::new()
        .trim(::csv::Trim::All)
        .flexible(false)
        .from_reader(text.as_bytes());
    let data_err = |problem: String| FitError::Data {
        file: file.to_string(),
        problem,
    };
    let headers = rdr.headers().map_err(|e| data_err(e.to_string()))?.clone();
    let col = |name: &str| headers.iter().position(|h| h == name);
    const KNOWN: [&str; 9] = [
        "region",
        "load_fmvc",
        "on_s",
        "off_s",
        "endurance_s",
        "t_s",
        "capacity",
        "rest_s",
        "second_over_first",
    ];
    for h in headers.iter() {
        if !KNOWN.contains(&h) {
            return Err(data_err(format!(
                "unknown column '{h}'{}; the columns are {}",
                crate::schema::did_you_mean(h, KNOWN.iter().copied()),
                KNOWN.join(", ")
            )));
        }
    }
    let (Some(c_region), Some(c_load)) = (col("region"), col("load_fmvc")) else {
        return Err(data_err(
            "the header needs the columns region and load_fmvc".into(),
        ));
    };
    let (c_on, c_off, c_end, c_t, c_cap) = (
        col("on_s"),
        col("off_s"),
        col("endurance_s"),
        col("t_s"),
        col("capacity"),
    );
    let (c_rest, c_ratio) = (col("rest_s"), col("second_over_first"));
    let mut rows = Vec::new();
    // newlines before byte `counted_to`, counted once as the reader advances (linear in the file)
    let (mut counted_to, mut newlines) = (0usize, 0usize);
    for (i, rec) in rdr.records().enumerate() {
        // the file's own line (blank lines skipped by the reader count too)
        let line = rec
            .as_ref()
            .ok()
            .and_then(|r| r.position())
            .and_then(|p| {
                // the reader's position is where it started reading: before any blank lines
                let start = p.byte() as usize;
                let rest = text.get(start..)?;
                let blank = rest.len() - rest.trim_start_matches(['\r', '\n']).len();
                let end = start + blank;
                let gap = text.as_bytes().get(counted_to..end)?;
                newlines += gap.iter().filter(|&&b| b == b'\n').count();
                counted_to = end;
                Some(newlines + 1)
            })
            .unwrap_or(i + 2);
        let bad = |problem: String| FitError::Row {
            file: file.to_string(),
            line,
            problem,
        };
        let rec = rec.map_err(|e| bad(e.to_string()))?;
        if rows.len() >= MAX_ROWS {
            return Err(bad(format!("more than {MAX_ROWS} rows")));
        }
        let get = |c: Option<usize>, name: &str| -> Result<Option<f64>, FitError> {
            match c.and_then(|c| rec.get(c)).filter(|s| !s.is_empty()) {
                None => Ok(None),
                Some(s) => match s.parse::<f64>() {
                    Ok(v) if v.is_finite() => Ok(Some(v)),
                    _ => Err(bad(format!("{name}: '{s}' is not a finite number"))),
                },
            }
        };
        let region = rec.get(c_region).unwrap_or_default().to_string();
        if !REGIONS.contains(&region.as_str()) {
            return Err(bad(format!(
                "region '{region}' is not one of {}{}",
                REGIONS.join(", "),
                crate::schema::did_you_mean(&region, REGIONS.iter().copied())
            )));
        }
        let load =
            get(Some(c_load), "load_fmvc")?.ok_or_else(|| bad("load_fmvc is empty".into()))?;
        if !(load > 0.0 && load <= 1.0) {
            return Err(bad(format!("load_fmvc must be in (0, 1], got {load}")));
        }
        let on = get(c_on, "on_s")?;
        let off = get(c_off, "off_s")?;
        let cycle_s = match (on, off) {
            (None, None) | (Some(_), None) | (_, Some(0.0)) => None,
            (Some(a), Some(b))
                if a > 0.0 && b > 0.0 && a <= MAX_ENDURANCE_S && b <= MAX_ENDURANCE_S =>
            {
                Some((a, b))
            }
            (None, Some(_)) => return Err(bad("off_s needs on_s".into())),
            (Some(a), Some(b)) => {
                return Err(bad(format!(
                    "on_s and off_s must be in (0, 86400] s, got {a} and {b}"
                )));
            }
        };
        let second = (get(c_rest, "rest_s")?, get(c_ratio, "second_over_first")?);
        let what = match (
            get(c_end, "endurance_s")?,
            get(c_t, "t_s")?,
            get(c_cap, "capacity")?,
        ) {
            _ if second != (None, None) => match second {
                (Some(rest_s), Some(ratio))
                    if cycle_s.is_none()
                        && rest_s > 0.0
                        && rest_s <= MAX_ENDURANCE_S
                        && ratio > 0.0
                        && ratio <= 10.0 =>
                {
                    Measured::SecondBout { rest_s, ratio }
                }
                (Some(_), Some(_)) if cycle_s.is_some() => {
                    return Err(bad(
                        "rest_s and second_over_first describe two holds to exhaustion with a rest between: not with on_s and off_s".into(),
                    ));
                }
                (Some(r), Some(q)) => {
                    return Err(bad(format!(
                        "rest_s must be in (0, 86400] s and second_over_first in (0, 10], got {r} and {q}"
                    )));
                }
                _ => return Err(bad("rest_s and second_over_first go together".into())),
            },
            (Some(e), None, None) if e > 0.0 && e <= MAX_ENDURANCE_S => Measured::EnduranceS(e),
            (Some(e), None, None) => {
                return Err(bad(format!("endurance_s must be in (0, 86400] s, got {e}")));
            }
            (None, Some(t), Some(c)) if t > 0.0 && t <= MAX_ENDURANCE_S && c > 0.0 && c <= 1.0 => {
                Measured::Capacity {
                    t_s: t,
                    capacity: c,
                }
            }
            (None, Some(t), Some(c)) => {
                return Err(bad(format!(
                    "t_s must be in (0, 86400] s and capacity in (0, 1], got {t} and {c}"
                )));
            }
            _ => {
                return Err(bad(
                    "give endurance_s, or t_s and capacity, or rest_s and second_over_first".into(),
                ));
            }
        };
        rows.push(Row {
            line,
            region,
            load_fmvc: load,
            cycle_s,
            what,
        });
    }
    if rows.is_empty() {
        return Err(data_err("no measurements after the header".into()));
    }
    Ok(rows)
}

/// The model's prediction for a row: endurance time \[s\] (capped at 24 h) or capacity.
///
/// Intermittent holds are summed in closed form, so a row costs the same however short its
/// cycles: one on-off cycle maps the capacity at its start affinely, `c ↦ A c + B` (each held
/// step is `c ↦ c∞ + (c − c∞) e^{−λt}`), so the capacity at the start of cycle `n` is
/// `c* + (1 − c*) Aⁿ` with `c* = B/(1 − A)`; exhaustion comes in the first cycle whose start lies
/// at or below the capacity from which the work period reaches the load.
pub fn predict(p: &MaParams, row: &Row) -> f64 {
    let f = row.load_fmvc;
    let mut s = MaState::FRESH;
    let routed = matches!(p.recovery, Recovery::Routed { .. });
    match (row.cycle_s, row.what) {
        (_, Measured::SecondBout { rest_s, .. }) => second_over_first(p, f, rest_s),
        (None, Measured::EnduranceS(_)) => p
            .time_to_exhaustion_within_s(&s, f, MAX_ENDURANCE_S)
            .unwrap_or(MAX_ENDURANCE_S),
        (None, Measured::Capacity { t_s, .. }) => {
            p.hold(&mut s, f, t_s);
            s.capacity
        }
        (Some((on, off)), Measured::EnduranceS(_)) if routed => {
            predict_stepped(p, f, (on, off), None)
        }
        (Some((on, off)), Measured::Capacity { t_s, .. }) if routed => {
            predict_stepped(p, f, (on, off), Some(t_s))
        }
        (Some((on, off)), Measured::EnduranceS(_)) => Cycle::new(p, f, on, off).endurance_s(p, f),
        (Some((on, off)), Measured::Capacity { t_s, .. }) => {
            let period = on + off;
            let n = (t_s / period).floor();
            s.capacity = Cycle::new(p, f, on, off).start_capacity(n);
            last_cycle(p, &mut s, f, (on, off), t_s - n * period)
        }
    }
}

/// Second endurance over the first: `f` held to exhaustion from rest, a rest of `rest_s`, `f` held
/// to exhaustion again (each bout capped at 24 h).
fn second_over_first(p: &MaParams, f: f64, rest_s: f64) -> f64 {
    let mut s = MaState::FRESH;
    let first = p
        .time_to_exhaustion_within_s(&s, f, MAX_ENDURANCE_S)
        .unwrap_or(MAX_ENDURANCE_S);
    p.hold(&mut s, f, first);
    p.hold(&mut s, 0.0, rest_s);
    p.time_to_exhaustion_within_s(&s, f, MAX_ENDURANCE_S)
        .unwrap_or(MAX_ENDURANCE_S)
        / first
}

/// The capacity after the first `left_s` of an on-off cycle from `s`.
fn last_cycle(p: &MaParams, s: &mut MaState, f: f64, (on, off): (f64, f64), left_s: f64) -> f64 {
    let d = on.min(left_s);
    if d > 0.0 {
        p.hold(s, f, d);
    }
    let d = off.min(left_s - d.max(0.0));
    if d > 0.0 {
        p.hold(s, 0.0, d);
    }
    s.capacity
}

/// [`predict`] for the routed recovery, whose state (capacity and fast deficit) moves by a 2 × 2
/// map per cycle: the intermittent holds are held cycle by cycle, each step exactly, until the
/// group gives out, its state stops changing (it never will), or 24 h have passed.
fn predict_stepped(p: &MaParams, f: f64, (on, off): (f64, f64), capacity_at_s: Option<f64>) -> f64 {
    let mut s = MaState::FRESH;
    let (work, rest) = (p.prepare(f, on), p.prepare(0.0, off));
    let mut t = 0.0;
    match capacity_at_s {
        None => loop {
            if t >= MAX_ENDURANCE_S {
                return MAX_ENDURANCE_S;
            }
            if let Some(te) = p.time_to_exhaustion_within_s(&s, f, on) {
                return (t + te).min(MAX_ENDURANCE_S);
            }
            let before = s;
            work.advance(&mut s);
            rest.advance(&mut s);
            t += on + off;
            if s.capacity == before.capacity && s.fast_deficit == before.fast_deficit {
                return MAX_ENDURANCE_S;
            }
        },
        Some(t_s) => {
            while t + on + off <= t_s {
                work.advance(&mut s);
                rest.advance(&mut s);
                t += on + off;
            }
            last_cycle(p, &mut s, f, (on, off), t_s - t)
        }
    }
}

/// One on-off cycle of an intermittent hold as an affine map of the capacity at its start.
struct Cycle {
    on_s: f64,
    off_s: f64,
    /// The work period: `c ↦ a_on c + b_on`.
    a_on: f64,
    b_on: f64,
    /// `ln A` and `c*` of the whole cycle's map.
    ln_a: f64,
    c_star: f64,
}

impl Cycle {
    fn new(p: &MaParams, f: f64, on_s: f64, off_s: f64) -> Self {
        // a held step: (ln a, b) of c ↦ a c + b, a = e^{−λt}, b = c∞ (1 − a)
        let step = |load: f64, t_s: f64| {
            let r = p.r_at(load);
            let lambda = p.k_per_min * load + r;
            let ln_a = -lambda * t_s / 60.0;
            let c_inf = if lambda > 0.0 { r / lambda } else { 0.0 };
            (ln_a, c_inf * -ln_a.exp_m1())
        };
        let (ln_on, b_on) = step(f, on_s);
        let (ln_off, b_off) = step(0.0, off_s);
        let a_off = ln_off.exp();
        let ln_a = ln_on + ln_off;
        let b = a_off * b_on + b_off;
        let one_minus_a = -ln_a.exp_m1();
        let c_star = if one_minus_a > 0.0 {
            (b / one_minus_a).min(1.0)
        } else {
            1.0
        };
        Cycle {
            on_s,
            off_s,
            a_on: ln_on.exp(),
            b_on,
            ln_a,
            c_star,
        }
    }

    /// Capacity at the start of cycle `n` (from rested).
    fn start_capacity(&self, n: f64) -> f64 {
        (self.c_star + (1.0 - self.c_star) * (self.ln_a * n).exp()).clamp(f64::MIN_POSITIVE, 1.0)
    }

    /// Endurance \[s\] (capped at 24 h): the first cycle whose work period reaches the load.
    fn endurance_s(&self, p: &MaParams, f: f64) -> f64 {
        let period = self.on_s + self.off_s;
        // a cycle starting at c is exhausted iff min(c, a_on c + b_on) ≤ f
        let thr = if self.a_on > 0.0 {
            f.max((f - self.b_on) / self.a_on)
        } else if self.b_on <= f {
            f64::INFINITY
        } else {
            f
        };
        let exhausted = |n: f64| self.start_capacity(n) <= thr;
        let n = if thr >= 1.0 {
            0.0
        } else if thr <= self.c_star || self.ln_a >= 0.0 {
            return MAX_ENDURANCE_S;
        } else {
            let n = (((thr - self.c_star) / (1.0 - self.c_star)).ln() / self.ln_a)
                .ceil()
                .max(0.0);
            if n * period >= MAX_ENDURANCE_S {
                return MAX_ENDURANCE_S;
            }
            // the closed form's rounding: settle on the first exhausted cycle
            let mut n = n;
            while n > 0.0 && exhausted(n - 1.0) {
                n -= 1.0;
            }
            while !exhausted(n) {
                n += 1.0;
                if n * period >= MAX_ENDURANCE_S {
                    return MAX_ENDURANCE_S;
                }
            }
            n
        };
        let t = n * period;
        if t >= MAX_ENDURANCE_S {
            return MAX_ENDURANCE_S;
        }
        let te = p
            .time_to_exhaustion_s(self.start_capacity(n), f)
            .unwrap_or(self.on_s)
            .min(self.on_s);
        (t + te).min(MAX_ENDURANCE_S)
    }
}

fn measured(row: &Row) -> f64 {
    match row.what {
        Measured::EnduranceS(e) => e,
        Measured::Capacity { capacity, .. } => capacity,
        Measured::SecondBout { ratio, .. } => ratio,
    }
}

/// A fitted value with its 95 % confidence interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    pub value: f64,
    pub low: f64,
    pub high: f64,
}

/// Fit quality of one region.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegionFit {
    pub region: String,
    pub rows: usize,
    pub k_per_min: Estimate,
    /// Root mean square of the log-ratio residuals.
    pub rms_log_error: f64,
    /// Largest |predicted/measured − 1|.
    pub max_relative_error: f64,
    /// The largest load this region holds forever with the fitted k and recovery (fraction of
    /// MVC).
    pub sustainable_load: f64,
}

/// The fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fit {
    pub source: String,
    pub rows: usize,
    pub parameters: usize,
    pub regions: Vec<RegionFit>,
    /// Recovery rate at rest \[1/min\]: fitted (with CI) or the given value.
    pub rest_per_min: Estimate,
    pub rest_fitted: bool,
    pub limit_fmvc: f64,
    /// The routed recovery's fast deficit, fitted or kept as given (`None`: the perfusion form).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fast: Option<FastFit>,
    pub rms_log_error: f64,
    pub iterations: usize,
    pub converged: bool,
    pub method: &'static str,
}

pub const METHOD: &str = "Levenberg-Marquardt on ln k per region (and ln R_rest when the data hold intermittent work or second bouts; with the routed recovery and second bouts also ln R_fast and logit of the fast share); residuals ln(predicted/measured); 95 % CIs from s²(JᵀJ)⁻¹ with Student's t, transformed back";

/// The fast deficit of the routed recovery ([`Recovery::Routed`]): the start of its fit where
/// the rows hold second bouts after a rest, else kept as given (continuous and intermittent
/// holds do not pin it down: it shows in the first seconds of a rest after a heavy hold).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FastDeficit {
    pub rest_per_min: f64,
    pub share_max: f64,
}

/// The fast deficit of a fit: its rate at rest \[1/min\] and largest share of new fatigue, with
/// 95 % intervals when fitted (the rows hold second bouts after a rest), else as given.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FastFit {
    pub rest_per_min: Estimate,
    pub share_max: Estimate,
    pub fitted: bool,
}

/// Fitting options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// R_rest \[1/min\] to start from (and to keep when not fitted); the slow deficit's rate
    /// under the routed recovery.
    pub rest_per_min: f64,
    pub limit_fmvc: f64,
    /// Fit R_rest: `None` = when the data hold intermittent holds.
    pub fit_rest: Option<bool>,
    /// `Some`: the routed recovery with this fast deficit; `None`: the perfusion form.
    pub fast: Option<FastDeficit>,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            rest_per_min: 0.37,
            limit_fmvc: 0.085,
            fit_rest: None,
            fast: None,
        }
    }
}

impl FitOptions {
    /// The recovery with rate `rest` at rest (none when 0).
    fn recovery(&self, rest: f64) -> Recovery {
        match self.fast {
            _ if rest <= 0.0 => Recovery::None,
            None => Recovery::Perfusion {
                rest_per_min: rest,
                limit_fmvc: self.limit_fmvc,
            },
            Some(fast) => Recovery::Routed {
                slow_rest_per_min: rest,
                fast_rest_per_min: fast.rest_per_min.max(rest),
                limit_fmvc: self.limit_fmvc,
                fast_share_max: fast.share_max,
            },
        }
    }
}

struct Problem<'a> {
    rows: &'a [Row],
    regions: Vec<String>,
    region_of: Vec<usize>,
    fit_rest: bool,
    /// Fit the fast deficit's rate and share too (routed recovery, second-bout rows present).
    fit_fast: bool,
    opts: FitOptions,
}

impl Problem<'_> {
    fn n_params(&self) -> usize {
        self.regions.len() + usize::from(self.fit_rest) + 2 * usize::from(self.fit_fast)
    }

    /// The fast deficit at `theta` (`ln R_fast`, `logit φ_max` last).
    fn fast(&self, theta: &[f64]) -> Option<FastDeficit> {
        let given = self.opts.fast?;
        if !self.fit_fast {
            return Some(given);
        }
        let np = self.n_params();
        Some(FastDeficit {
            rest_per_min: theta[np - 2].exp().min(super::ma::R_MAX_PER_MIN),
            share_max: 1.0 / (1.0 + (-theta[np - 1]).exp()),
        })
    }

    fn params(&self, theta: &[f64], g: usize) -> MaParams {
        let k = theta[g].exp().clamp(K_MIN_PER_MIN, K_MAX_PER_MIN);
        let rest = if self.fit_rest {
            theta[self.regions.len()]
                .exp()
                .min(super::ma::R_MAX_PER_MIN)
        } else {
            self.opts.rest_per_min
        };
        let opts = FitOptions {
            fast: self.fast(theta),
            ..self.opts
        };
        MaParams {
            k_per_min: k,
            recovery: opts.recovery(rest),
        }
    }

    fn residuals(&self, theta: &[f64], out: &mut [f64]) {
        for (i, row) in self.rows.iter().enumerate() {
            let p = self.params(theta, self.region_of[i]);
            out[i] = (predict(&p, row).max(1e-12) / measured(row)).ln();
        }
    }
}

fn ssr(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// Fits the rows (`source` names the data in the result).
pub fn fit(rows: &[Row], source: &str, opts: FitOptions) -> Result<Fit, FitError> {
    let mut regions: Vec<String> = Vec::new();
    let region_of: Vec<usize> = rows
        .iter()
        .map(|r| match regions.iter().position(|g| g == &r.region) {
            Some(i) => i,
            None => {
                regions.push(r.region.clone());
                regions.len() - 1
            }
        })
        .collect();
    let intermittent = rows.iter().any(|r| r.cycle_s.is_some());
    let second_bouts = rows
        .iter()
        .any(|r| matches!(r.what, Measured::SecondBout { .. }));
    let fit_rest = opts.fit_rest.unwrap_or(intermittent || second_bouts);
    let pr = Problem {
        rows,
        regions,
        region_of,
        fit_rest,
        fit_fast: second_bouts && opts.fast.is_some(),
        opts,
    };
    let np = pr.n_params();
    let n = rows.len();
    if n <= np {
        return Err(FitError::Data {
            file: source.to_string(),
            problem: format!(
                "{n} measurements cannot fit {np} parameters with confidence intervals: give more rows than parameters"
            ),
        });
    }
    // rows repeated exactly carry one measurement, and no scatter to estimate an interval from
    let mut distinct: Vec<&Row> = Vec::new();
    for r in rows {
        if !distinct.iter().any(|d| {
            d.region == r.region
                && d.load_fmvc == r.load_fmvc
                && d.cycle_s == r.cycle_s
                && d.what == r.what
        }) {
            distinct.push(r);
            if distinct.len() > np {
                break;
            }
        }
    }
    if distinct.len() <= np {
        return Err(FitError::Data {
            file: source.to_string(),
            problem: format!(
                "the {n} rows hold only {} distinct measurement(s) (the others repeat them exactly): that cannot fit {np} parameter(s) with confidence intervals (no scatter to estimate one from); give distinct measurements",
                distinct.len()
            ),
        });
    }
    // start: k from each region's rows by the closed form of a sustained hold without recovery
    let mut theta = vec![0.0; np];
    for (g, _) in pr.regions.iter().enumerate() {
        let ks: Vec<f64> = rows
            .iter()
            .zip(&pr.region_of)
            .filter(|(_, rg)| **rg == g)
            .map(|(r, _)| match r.what {
                Measured::EnduranceS(e) => -r.load_fmvc.ln() / (r.load_fmvc * e / 60.0),
                Measured::Capacity { t_s, capacity } => {
                    (-capacity.ln() / (r.load_fmvc * t_s / 60.0)).max(K_MIN_PER_MIN)
                }
                Measured::SecondBout { .. } => f64::NAN,
            })
            .filter(|k| k.is_finite() && *k > 0.0)
            .collect();
        let k0 = if ks.is_empty() {
            1.0
        } else {
            ks.iter().map(|k| k.ln()).sum::<f64>() / ks.len() as f64
        };
        theta[g] = k0.clamp(K_MIN_PER_MIN.ln(), K_MAX_PER_MIN.ln());
    }
    if fit_rest {
        theta[pr.regions.len()] = opts.rest_per_min.max(1e-3).ln();
    }
    if let (true, Some(fast)) = (pr.fit_fast, opts.fast) {
        let share = fast.share_max.clamp(0.01, 0.99);
        theta[np - 2] = fast.rest_per_min.max(1e-3).ln();
        theta[np - 1] = (share / (1.0 - share)).ln();
    }
    let mut r = vec![0.0; n];
    let mut r2 = vec![0.0; n];
    let mut jac = nalgebra::DMatrix::<f64>::zeros(n, np);
    pr.residuals(&theta, &mut r);
    let mut cost = ssr(&r);
    let mut lambda = 1e-3;
    let (mut iterations, mut converged) = (0, false);
    let jacobian = |theta: &[f64], jac: &mut nalgebra::DMatrix<f64>, r2: &mut [f64], h: f64| {
        let mut t = theta.to_vec();
        let mut rp = vec![0.0; n];
        for j in 0..np {
            t[j] = theta[j] + h;
            pr.residuals(&t, &mut rp);
            t[j] = theta[j] - h;
            pr.residuals(&t, r2);
            t[j] = theta[j];
            for i in 0..n {
                jac[(i, j)] = (rp[i] - r2[i]) / (2.0 * h);
            }
        }
    };
    // a parameter the predictions do not depend on (e.g. every row of a region at 100 %MVC,
    // which gives out at once whatever k is) is not identified by the data: the fit would stop
    // at its starting value and call it converged
    // (looked at from the start, over ±0.1 in the log: intermittent rows are staircases)
    jacobian(&theta, &mut jac, &mut r2, 0.1);
    for j in 0..np {
        if jac.column(j).amax() < 1e-9 {
            let what = if j >= pr.regions.len() + usize::from(fit_rest) {
                "the predictions do not depend on the fast deficit's rate or share: the second-bout rows cannot identify them".to_string()
            } else if j < pr.regions.len() {
                format!(
                    "the predictions for region '{}' do not depend on its k (its rows are all at loads the model says give out at once, such as 100 %MVC): the data cannot identify k; give measurements at loads below 100 %MVC",
                    pr.regions[j]
                )
            } else {
                "the predictions do not depend on the recovery rate R_rest: the data cannot identify it; keep it fixed (--no-recovery-fit)".to_string()
            };
            return Err(FitError::Data {
                file: source.to_string(),
                problem: what,
            });
        }
    }
    while iterations < 200 {
        iterations += 1;
        jacobian(&theta, &mut jac, &mut r2, 1e-6);
        let jt = jac.transpose();
        let jtj = &jt * &jac;
        let g = &jt * nalgebra::DVector::from_column_slice(&r);
        if g.amax() < 1e-10 {
            converged = true;
            break;
        }
        let mut improved = false;
        for _ in 0..30 {
            let mut a = jtj.clone();
            for d in 0..np {
                a[(d, d)] += lambda * jtj[(d, d)].max(1e-12);
            }
            let Some(step) = a.cholesky().map(|c| c.solve(&(-&g))) else {
                lambda *= 10.0;
                continue;
            };
            let trial: Vec<f64> = theta.iter().zip(step.iter()).map(|(t, s)| t + s).collect();
            pr.residuals(&trial, &mut r2);
            let c2 = ssr(&r2);
            if c2 < cost {
                let rel = (cost - c2) / cost.max(1e-300);
                theta = trial;
                r.copy_from_slice(&r2);
                cost = c2;
                lambda = (lambda / 3.0).max(1e-12);
                improved = true;
                if rel < 1e-12 || step.amax() < 1e-10 {
                    converged = true;
                }
                break;
            }
            lambda *= 4.0;
        }
        if !improved || converged {
            converged = converged || !improved;
            break;
        }
    }
    // Covariance. The predicted endurance of intermittent work is a staircase in the
    // parameters (exhaustion moves from one work period to the next, jumping by an off period):
    // its local derivative is zero or a jump. Those rows take the slope over ±0.1 in ln k
    // (several periods' steps averaged), the smooth rows their local derivative.
    jacobian(&theta, &mut jac, &mut r2, 1e-6);
    let stepped: Vec<usize> = (0..n)
        .filter(|&i| {
            matches!(rows[i].what, Measured::EnduranceS(_))
                && rows[i].cycle_s.is_some_and(|(_, off)| off > 0.0)
        })
        .collect();
    if !stepped.is_empty() {
        let mut wide = nalgebra::DMatrix::<f64>::zeros(n, np);
        jacobian(&theta, &mut wide, &mut r2, 0.1);
        for &i in &stepped {
            jac.set_row(i, &wide.row(i));
        }
    }
    let dof = (n - np) as f64;
    let s2 = cost / dof;
    let cov = (jac.transpose() * &jac).try_inverse();
    let t = StudentsT::new(0.0, 1.0, dof)
        .map(|d| d.inverse_cdf(0.975))
        .unwrap_or(1.96);
    // intervals are kept within the values the model accepts (k within its limits, R_rest at
    // most its limit): an interval reaching a limit means the data do not pin the value down
    let est = |j: usize| {
        let se = cov
            .as_ref()
            .map_or(f64::INFINITY, |c| (s2 * c[(j, j)].max(0.0)).sqrt());
        let v = theta[j];
        let (lo, hi) = if j < pr.regions.len() {
            (K_MIN_PER_MIN, K_MAX_PER_MIN)
        } else {
            (0.0, super::ma::R_MAX_PER_MIN)
        };
        let bound = |x: f64, nan: f64| if x.is_nan() { nan } else { x.clamp(lo, hi) };
        Estimate {
            value: v.exp(),
            low: bound((v - t * se).exp(), lo).min(v.exp()),
            high: bound((v + t * se).min(700.0).exp(), hi).max(v.exp()),
        }
    };
    let rest_per_min = if fit_rest {
        theta[pr.regions.len()].exp()
    } else {
        opts.rest_per_min
    };
    let regions = pr
        .regions
        .iter()
        .enumerate()
        .map(|(g, name)| {
            let idx: Vec<usize> = (0..n).filter(|&i| pr.region_of[i] == g).collect();
            let sustainable_load =
                MaParams::with_recovery(theta[g].exp(), opts.recovery(rest_per_min))
                    .map_or(0.0, |p| p.sustainable_load());
            RegionFit {
                region: name.clone(),
                rows: idx.len(),
                k_per_min: est(g),
                sustainable_load,
                rms_log_error: (idx.iter().map(|&i| r[i] * r[i]).sum::<f64>() / idx.len() as f64)
                    .sqrt(),
                max_relative_error: idx
                    .iter()
                    .map(|&i| (r[i].exp() - 1.0).abs())
                    .fold(0.0, f64::max),
            }
        })
        .collect();
    Ok(Fit {
        source: source.to_string(),
        rows: n,
        parameters: np,
        regions,
        rest_per_min: if fit_rest {
            est(pr.regions.len())
        } else {
            Estimate {
                value: opts.rest_per_min,
                low: opts.rest_per_min,
                high: opts.rest_per_min,
            }
        },
        rest_fitted: fit_rest,
        limit_fmvc: opts.limit_fmvc,
        fast: pr.fast(&theta).map(|f| {
            if pr.fit_fast {
                let j = np - 1;
                let se = cov
                    .as_ref()
                    .map_or(f64::INFINITY, |c| (s2 * c[(j, j)].max(0.0)).sqrt());
                let logistic = |x: f64| 1.0 / (1.0 + (-x).exp());
                let v = theta[j];
                FastFit {
                    rest_per_min: est(np - 2),
                    share_max: Estimate {
                        value: f.share_max,
                        low: logistic(v - t * se).min(f.share_max),
                        high: logistic(v + t * se).max(f.share_max),
                    },
                    fitted: true,
                }
            } else {
                let fixed = |v: f64| Estimate {
                    value: v,
                    low: v,
                    high: v,
                };
                FastFit {
                    rest_per_min: fixed(f.rest_per_min),
                    share_max: fixed(f.share_max),
                    fitted: false,
                }
            }
        }),
        rms_log_error: (cost / n as f64).sqrt(),
        iterations,
        converged,
        method: METHOD,
    })
}

impl Fit {
    /// The fit as a parameter set a task can use (`fatigue: {parameters_file: ...}`): the fitted
    /// regions with their CIs as ranges; the other regions from `base`.
    pub fn parameter_set(&self, base: &ParameterSet) -> ParameterSet {
        let mut regions: BTreeMap<String, RegionK> = base.regions.clone();
        let mut female = base.female.clone();
        let mut male = base.male.clone();
        for r in &self.regions {
            let v = RegionK {
                k: r.k_per_min.value,
                k_low: r.k_per_min.low.max(K_MIN_PER_MIN),
                k_high: r.k_per_min.high.min(K_MAX_PER_MIN),
            };
            regions.insert(r.region.clone(), v);
            female.remove(&r.region);
            male.remove(&r.region);
        }
        let (rest_low, rest_high, limit_low, limit_high) = match base.recovery.ranges() {
            Some((_, rest_low, rest_high, _, limit_low, limit_high)) => {
                (rest_low, rest_high, limit_low, limit_high)
            }
            None => (0.0, 0.0, self.limit_fmvc, self.limit_fmvc),
        };
        let (rl, rh) = if self.rest_fitted {
            (
                self.rest_per_min.low,
                self.rest_per_min.high.min(super::ma::R_MAX_PER_MIN),
            )
        } else {
            (
                rest_low.min(self.rest_per_min.value),
                rest_high.max(self.rest_per_min.value),
            )
        };
        let (rest_per_min, limit_fmvc) = (self.rest_per_min.value, self.limit_fmvc);
        let (limit_low, limit_high) = (limit_low.min(limit_fmvc), limit_high.max(limit_fmvc));
        ParameterSet {
            name: "fitted".into(),
            description: format!(
                "fitted by posture-opt fit to {} ({} measurements); regions not in the data from '{}'",
                self.source, self.rows, base.name
            ),
            recovery: match self.fast {
                None => RecoverySpec::Perfusion {
                    rest_per_min,
                    rest_low: rl,
                    rest_high: rh,
                    limit_fmvc,
                    limit_low,
                    limit_high,
                },
                Some(fast) => RecoverySpec::Routed {
                    rest_per_min,
                    rest_low: rl,
                    rest_high: rh,
                    limit_fmvc,
                    limit_low,
                    limit_high,
                    fast_rest_per_min: fast.rest_per_min.value.max(rh),
                    fast_share_max: fast.share_max.value,
                },
            },
            recovery_source: base.recovery_source.clone(),
            k_source: format!(
                "fit to {} (95 % confidence intervals as ranges)",
                self.source
            ),
            regions,
            female,
            male,
            unlisted_regions_use_general: base.unlisted_regions_use_general,
        }
    }
}
