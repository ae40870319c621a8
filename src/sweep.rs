//! Populations: one task planned for many workers, to find who cannot do it and where.
//!
//! Each worker gets a body generated from their sex, stature and mass (the task's `robot` file,
//! if any, is replaced: the sweep is about body size) and strength scaled to their percentile.
//!
//! * **Standard population**: 5th, 50th and 95th-percentile men and women, with stature, body
//!   mass and strength all at that percentile (the "all small" / "all large" design cases; real
//!   people mix percentiles). Stature: US adults 19–65, Pheasant's *Bodyspace* as tabulated by
//!   the CityU Online Anthropometry pages (men 1640 / 1755 / 1870 mm, SD 71; women 1520 / 1625 /
//!   1730 mm, SD 64). Body mass: ASSUMPTION, rounded typical adult values (men 60 / 78 / 100 kg,
//!   women 47 / 62 / 84 kg), not from a checked table.
//! * **Sampled population** (`n`, `seed`): sex alternates; stature normal with the means and SDs
//!   above; ln(mass) normal with the median and spread of the mass percentiles above and
//!   correlation 0.45 with stature (ASSUMPTION); strength percentile uniform on [1, 99],
//!   independent (ASSUMPTION). A SplitMix64 generator makes a seed reproduce the same sample on
//!   every platform.
//!
//! A worker **cannot do the task** when a muscle group is exhausted, a target is out of reach
//! (hand error > 1 cm) or a posture penetrates an obstacle (clearance < 0).

use crate::body::strength::normal_quantile;
use crate::body::{Sex, Worker};
use crate::plan::{plan_with_baseline, Exhaustion, PlanError};
use crate::rest::rest_advice;
use crate::task::{Task, TaskError, TaskFile};
use rayon::prelude::*;
use serde::Serialize;
use std::fmt::Write;
use std::path::Path;

/// One member of a population.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Member {
    pub label: String,
    pub worker: Worker,
}

/// Stature mean and SD \[m\], mass 5th/50th/95th percentiles \[kg\] per sex.
struct SexData {
    stature_mean_m: f64,
    stature_sd_m: f64,
    mass_kg: [f64; 3],
}

const MEN: SexData = SexData {
    stature_mean_m: 1.755,
    stature_sd_m: 0.071,
    mass_kg: [60.0, 78.0, 100.0],
};
const WOMEN: SexData = SexData {
    stature_mean_m: 1.625,
    stature_sd_m: 0.064,
    mass_kg: [47.0, 62.0, 84.0],
};
const Z95: f64 = 1.644_853_626_951_472_2;
/// Correlation of stature and ln(mass) in the sampled population (ASSUMPTION).
const STATURE_MASS_CORRELATION: f64 = 0.45;

fn data(sex: Sex) -> &'static SexData {
    match sex {
        Sex::Male => &MEN,
        Sex::Female => &WOMEN,
    }
}

/// 5th, 50th and 95th-percentile women and men.
pub fn standard_population() -> Vec<Member> {
    let mut v = Vec::with_capacity(6);
    for (sex, name) in [(Sex::Female, "woman"), (Sex::Male, "man")] {
        let d = data(sex);
        for (i, (pct, z)) in [(5.0, -Z95), (50.0, 0.0), (95.0, Z95)].iter().enumerate() {
            v.push(Member {
                label: format!("P{pct:.0} {name}"),
                worker: Worker {
                    sex,
                    stature_m: d.stature_mean_m + z * d.stature_sd_m,
                    mass_kg: d.mass_kg[i],
                    strength_percentile: *pct,
                },
            });
        }
    }
    v
}

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny, portable, reproducible generator.
struct SplitMix64(u64);
impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in (0, 1).
    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        normal_quantile(self.uniform())
    }
}

/// `n` sampled workers (see the module docs); the same seed gives the same sample.
pub fn sampled_population(n: usize, seed: u64) -> Vec<Member> {
    let mut rng = SplitMix64(seed);
    (0..n)
        .map(|i| {
            let sex = if i % 2 == 0 { Sex::Female } else { Sex::Male };
            let d = data(sex);
            let z1 = rng.normal();
            let z2 = rng.normal();
            let r = STATURE_MASS_CORRELATION;
            let zm = r * z1 + (1.0 - r * r).sqrt() * z2;
            let ln_sigma = (d.mass_kg[2] / d.mass_kg[0]).ln() / (2.0 * Z95);
            let worker = Worker {
                sex,
                stature_m: (d.stature_mean_m + z1 * d.stature_sd_m).clamp(1.3, 2.2),
                mass_kg: (d.mass_kg[1] * (zm * ln_sigma).exp()).clamp(35.0, 180.0),
                strength_percentile: 1.0 + 98.0 * rng.uniform(),
            };
            Member {
                label: format!("#{i:03}"),
                worker,
            }
        })
        .collect()
}

/// Why a worker cannot do the task (or what is marginal).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Problem {
    Exhaustion {
        t_s: f64,
        half_joint: String,
        group: String,
        phase: String,
    },
    OutOfReach {
        phase: String,
        hand_error_m: f64,
    },
    Collision {
        phase: String,
        clearance_m: f64,
    },
}

/// One worker's outcome.
#[derive(Debug, Clone, Serialize)]
pub struct WorkerOutcome {
    pub label: String,
    pub worker: Worker,
    pub can_do: bool,
    pub problems: Vec<Problem>,
    pub total_u_min: f64,
    pub worst_half_joint: String,
    /// Lowest capacity at any time of the task.
    pub min_capacity: f64,
    pub min_capacity_half_joint: String,
    pub exhaustion: Option<Exhaustion>,
    pub rula_max: Option<i32>,
    /// Rest per cycle the model needs to keep every capacity above the floor (`None`: rest
    /// cannot help).
    pub rest_needed_s: Option<f64>,
}

/// The sweep document (`posture-opt sweep --json`).
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    pub task: String,
    pub population: String,
    pub adaptive: bool,
    pub capacity_floor: f64,
    pub workers: Vec<WorkerOutcome>,
    pub cannot_do: usize,
}

/// Why a sweep failed.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    #[error("worker {label}: {source}")]
    Task { label: String, source: TaskError },
    #[error("worker {label}: {source}")]
    Plan { label: String, source: PlanError },
}

fn one(
    file: &TaskFile,
    path: &Path,
    m: &Member,
    adapt: bool,
    floor: f64,
) -> Result<WorkerOutcome, SweepError> {
    let mut f = file.clone();
    f.worker = m.worker;
    f.robot = None;
    let task = Task::from_task_file(f, path).map_err(|source| SweepError::Task {
        label: m.label.clone(),
        source,
    })?;
    let (plan, _) = plan_with_baseline(&task, adapt).map_err(|source| SweepError::Plan {
        label: m.label.clone(),
        source,
    })?;
    let s = &plan.summary;
    let mut problems = Vec::new();
    if let Some(e) = &s.exhaustion {
        problems.push(Problem::Exhaustion {
            t_s: e.t_s,
            half_joint: e.half_joint.clone(),
            group: e.group.clone(),
            phase: e.phase.clone(),
        });
    }
    for p in &s.phases {
        if !p.reachable {
            problems.push(Problem::OutOfReach {
                phase: p.phase.clone(),
                hand_error_m: p.hand_error_m,
            });
        }
        if p.min_clearance_m < 0.0 {
            problems.push(Problem::Collision {
                phase: p.phase.clone(),
                clearance_m: p.min_clearance_m,
            });
        }
    }
    let rest = rest_advice(&task, &plan, floor);
    let (min_capacity, min_capacity_half_joint) = plan.lowest_capacity();
    Ok(WorkerOutcome {
        label: m.label.clone(),
        worker: m.worker,
        can_do: problems.is_empty(),
        problems,
        total_u_min: s.total_u,
        worst_half_joint: s.worst_half_joint.clone(),
        min_capacity,
        min_capacity_half_joint,
        exhaustion: s.exhaustion.clone(),
        rula_max: s.rula_max,
        rest_needed_s: rest.model.rest_s_per_cycle,
    })
}

/// Plans `file` (read from `path`) for every member, in parallel; `on_done` is called once per
/// finished worker (from any thread), e.g. to advance a progress bar.
pub fn sweep(
    file: &TaskFile,
    path: &Path,
    members: &[Member],
    population: &str,
    adapt: bool,
    floor: f64,
    on_done: &(dyn Fn() + Sync),
) -> Result<Sweep, SweepError> {
    let workers: Vec<WorkerOutcome> = members
        .par_iter()
        .map(|m| {
            let r = one(file, path, m, adapt, floor);
            on_done();
            r
        })
        .collect::<Result<_, _>>()?;
    Ok(Sweep {
        task: file.name.clone(),
        population: population.to_string(),
        adaptive: adapt,
        capacity_floor: floor,
        cannot_do: workers.iter().filter(|w| !w.can_do).count(),
        workers,
    })
}

/// One line describing a problem: what, where and when.
pub fn problem_text(p: &Problem) -> String {
    match p {
        Problem::Exhaustion {
            t_s,
            half_joint,
            phase,
            ..
        } => format!("{half_joint} exhausted at {t_s:.0} s in '{phase}'"),
        Problem::OutOfReach {
            phase,
            hand_error_m,
        } => format!("'{phase}' out of reach by {:.0} mm", 1000.0 * hand_error_m),
        Problem::Collision { phase, clearance_m } => format!(
            "'{phase}' collides ({:.0} mm into an obstacle)",
            -1000.0 * clearance_m
        ),
    }
}

/// The sweep as a text table.
pub fn sweep_table(s: &Sweep) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "{} — {} workers ({}), {} plans, capacity floor {:.2}\n",
        s.task,
        s.workers.len(),
        s.population,
        if s.adaptive { "adaptive" } else { "baseline" },
        s.capacity_floor
    );
    let _ = writeln!(
        o,
        "{:<12} {:>6} {:>7} {:>6} {:>7} {:>9} {:>5} {:>9}  problems",
        "worker", "sex", "stature", "mass", "str.pct", "U [min]", "minC", "rest/cyc"
    );
    for w in &s.workers {
        let _ = writeln!(
            o,
            "{:<12} {:>6} {:>6.3}m {:>4.0}kg {:>7.0} {:>9.2} {:>5.2} {:>9}  {}",
            w.label,
            w.worker.sex.name(),
            w.worker.stature_m,
            w.worker.mass_kg,
            w.worker.strength_percentile,
            w.total_u_min,
            w.min_capacity,
            w.rest_needed_s
                .map_or("none helps".into(), |r| format!("{r:.1} s")),
            if w.problems.is_empty() {
                "can do the task".to_string()
            } else {
                format!(
                    "CANNOT: {}",
                    w.problems
                        .iter()
                        .map(problem_text)
                        .collect::<Vec<_>>()
                        .join("; ")
                )
            }
        );
    }
    let _ = writeln!(
        o,
        "\n{} of {} workers cannot do the task",
        s.cannot_do,
        s.workers.len()
    );
    o
}
