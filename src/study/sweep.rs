//! Populations: one task planned for many workers, to find who cannot do it and where.
//!
//! Each worker gets a body generated from their sex, stature and mass (the task's `robot` file,
//! if any, is replaced: the sweep is about body size) and strength scaled to their percentile.
//!
//! * **Standard population**: 5th, 50th and 95th-percentile men and women, with stature and body
//!   mass at that percentile (the "all small" / "all large" design cases) and median strength:
//!   strength is sampled independently of body size, as 3DSSPP treats them; the spread of
//!   strength is what each plan's share of men and women strong enough reports. Stature: US adults 19–65, Pheasant's *Bodyspace* as tabulated by
//!   the CityU Online Anthropometry pages (men 1640 / 1755 / 1870 mm, SD 71; women 1520 / 1625 /
//!   1730 mm, SD 64). Body mass: ASSUMPTION, rounded typical adult values (men 60 / 78 / 100 kg,
//!   women 47 / 62 / 84 kg), not from a checked table.
//! * **Sampled population** (`n`, `seed`): sex alternates; stature normal with the means and SDs
//!   above; ln(mass) normal with the median and spread of the mass percentiles above and
//!   correlation 0.45 with stature (ASSUMPTION); strength percentile uniform on [1, 99],
//!   independent (ASSUMPTION). A SplitMix64 generator makes a seed reproduce the same sample on
//!   every platform.
//!
//! A worker **cannot do the task** when a load exceeds a muscle group's strength, a group is
//! exhausted within the task, or a target is out of reach (hand error > 1 cm) and proven so
//! (farther than the body is long). A target not reached within the body's length, a posture
//! that penetrates an obstacle (clearance < 0), a loss of balance or a phase whose local solve
//! did not converge is not proof: such a worker is planned again from the nearest determined
//! worker's postures (see [`sweep_members`]) and, if that fails too, reported as "the optimiser
//! could not plan", apart from those who cannot.
//!
//! **Share sustaining the shift**: for a sampled population, the share of workers who can do the
//! whole task, with a 95 % Wilson score interval (Wilson 1927), overall and per sex.
//!
//! **Shards**: worker `j` belongs to shard `j mod n`; [`merge`] joins shard results into the
//! document one run gives.

use super::shard::Shard;
use crate::assess::assess;
use crate::body::strength::normal_quantile;
use crate::body::{Sex, Worker};
use crate::plan::result::Exhaustion;
use crate::plan::{Plan, PlanError, PlanOptions, Planner, Task, TaskError, TaskFile};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::fmt::Write;
use std::path::Path;

/// One member of a population.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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

/// The strength percentile of every member of the standard population: strength is not tied
/// to body size (as in 3DSSPP, where the anthropometry is chosen and strength is reported as
/// the share of the population strong enough). The strength spread is what each plan's
/// "% capable" (men and women strong enough for every load) reports.
pub const STANDARD_STRENGTH_PERCENTILE: f64 = 50.0;

fn sex_data(sex: Sex) -> &'static SexData {
    match sex {
        Sex::Male => &MEN,
        Sex::Female => &WOMEN,
    }
}

/// The percentile (0–100) of a stature among workers of `sex` (the population the sweep samples:
/// normal stature).
pub fn stature_percentile(sex: Sex, stature_m: f64) -> f64 {
    use statrs::distribution::ContinuousCDF;
    let d = sex_data(sex);
    let z = (stature_m - d.stature_mean_m) / d.stature_sd_m;
    100.0 * statrs::distribution::Normal::standard().cdf(z)
}

/// The percentile (0–100) of a body mass among workers of `sex` (log-normal through the 5th,
/// 50th and 95th percentiles the sweep uses).
pub fn mass_percentile(sex: Sex, mass_kg: f64) -> f64 {
    use statrs::distribution::ContinuousCDF;
    let d = sex_data(sex);
    let sd_ln = (d.mass_kg[2].ln() - d.mass_kg[0].ln()) / (2.0 * Z95);
    let z = (mass_kg.ln() - d.mass_kg[1].ln()) / sd_ln;
    100.0 * statrs::distribution::Normal::standard().cdf(z)
}
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
                    strength_percentile: STANDARD_STRENGTH_PERCENTILE,
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

/// Why a worker cannot do the task.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Problem {
    /// A load above the group's strength from the first instant.
    ExceedsStrength {
        group: String,
        phase: String,
        load: f64,
    },
    Exhaustion {
        t_s: f64,
        group: String,
        phase: String,
        load: f64,
    },
    /// A target not reached; `proven`: beyond the body's full length (out of reach whatever
    /// the posture), else only not found by the optimiser.
    OutOfReach {
        phase: String,
        hand_error_m: f64,
        proven: bool,
    },
    Collision {
        phase: String,
        clearance_m: f64,
        with: Option<String>,
    },
    OffBalance {
        phase: String,
        margin_m: f64,
    },
}

/// One worker's outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WorkerOutcome {
    pub index: usize,
    pub label: String,
    pub worker: Worker,
    /// Able: the plan found has no problem (it is the witness).
    pub can_do: bool,
    pub problems: Vec<Problem>,
    /// Why the plan's problems do not prove that the worker cannot do the task (a target not
    /// reached within the body's length, a collision, a loss of balance, or a strength or
    /// exhaustion problem in a plan the optimiser did not finish): this worker is "the optimiser
    /// could not plan", not "cannot do it". Empty when the worker can, or is proven unable.
    #[serde(default)]
    pub could_not_plan: Vec<String>,
    /// The worker whose postures seeded a second attempt, when the first did not determine the
    /// answer.
    #[serde(default)]
    pub retried_from: Option<String>,
    /// Fatigue index summed over groups \[min\], over the simulated time: the simulation stops at
    /// an exhaustion, so an exhausted worker's U covers only the time until then.
    pub total_u_min: f64,
    pub simulated_s: f64,
    pub worst_group: String,
    /// Lowest capacity at any time of the task, and whose.
    pub lowest_capacity: f64,
    pub lowest_capacity_group: String,
    /// Minutes until a group gives out at this pace (`None`: read `exhaustion_verdict`).
    pub minutes_to_exhaustion: Option<f64>,
    /// As the plan's `meaning.exhaustion_verdict`, and how long the pace was followed \[min\].
    pub exhaustion_verdict: String,
    /// The shift verdict's status and headline (the plan's `assessment.verdict`).
    pub shift_status: crate::assess::verdict::Status,
    pub shift_verdict: String,
    pub minutes_followed: f64,
    pub exhaustion: Option<Exhaustion>,
    pub rula_max: Option<i32>,
    pub reba_max: Option<u8>,
    pub back_compression_max_n: Option<f64>,
    /// Rest per cycle the model needs to keep every capacity above the floor (`None`: rest
    /// cannot help).
    pub rest_needed_s: Option<f64>,
    /// Parameter variants (of 9) under which a group is exhausted within the task.
    pub exhausted_in_variants: Option<usize>,
}

/// A share with its 95 % confidence interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Share {
    pub share: f64,
    pub low: f64,
    pub high: f64,
    pub of: usize,
}

/// The 95 % Wilson score interval for `k` successes of `n`.
pub fn wilson(k: usize, n: usize) -> Share {
    if n == 0 {
        return Share {
            share: 0.0,
            low: 0.0,
            high: 1.0,
            of: 0,
        };
    }
    let z = 1.959_963_984_540_054;
    let (nf, p) = (n as f64, k as f64 / n as f64);
    let den = 1.0 + z * z / nf;
    let centre = (p + z * z / (2.0 * nf)) / den;
    let half = z * (p * (1.0 - p) / nf + z * z / (4.0 * nf * nf)).sqrt() / den;
    Share {
        share: p,
        low: (centre - half).max(0.0),
        high: (centre + half).min(1.0),
        of: n,
    }
}

/// The sweep document (`posture-opt sweep --json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sweep {
    pub task: String,
    pub population: String,
    pub adaptive: bool,
    pub capacity_floor: f64,
    pub workers: Vec<WorkerOutcome>,
    /// Workers proven unable (a problem, with the optimiser's answer determined).
    pub cannot_do: usize,
    /// Workers the optimiser could not plan (even from the nearest successful worker's postures).
    #[serde(default)]
    pub could_not_plan: usize,
    /// Sampled populations: the share who can do the whole task among the workers whose answer
    /// is determined, overall, women, men.
    pub sustain_all: Option<Share>,
    pub sustain_women: Option<Share>,
    pub sustain_men: Option<Share>,
    pub note: String,
}

/// A shard's result (`posture-opt sweep --shard i/n --json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepShard {
    pub kind: String,
    pub shard: String,
    pub task: String,
    pub population: String,
    pub sampled: bool,
    pub adaptive: bool,
    pub fatigue_only: bool,
    pub capacity_floor: f64,
    /// [`Task::fingerprint`](crate::plan::Task::fingerprint) of the task swept: shards merge
    /// only when they were made from the same files.
    pub task_fingerprint: String,
    pub workers_total: usize,
    pub workers: Vec<WorkerOutcome>,
}

impl SweepShard {
    /// A shard's result: `workers` of the `workers_total` of `population`, planned from `file`
    /// (read from `path`) with `opts`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        file: &TaskFile,
        path: &Path,
        shard: Shard,
        population: String,
        sampled: bool,
        opts: PlanOptions,
        capacity_floor: f64,
        workers_total: usize,
        workers: Vec<WorkerOutcome>,
    ) -> Self {
        let task_fingerprint = match crate::plan::Task::from_task_file(file.clone(), path) {
            Ok(t) => t.fingerprint(),
            Err(_) => {
                use sha2::{Digest, Sha256};
                let text = serde_json::to_vec(file).unwrap_or_default();
                format!("{:x}", Sha256::digest(&text))
            }
        };
        SweepShard {
            kind: SHARD_KIND.into(),
            shard: shard.to_string(),
            task: file.name.clone(),
            population,
            sampled,
            adaptive: opts.adapt,
            fatigue_only: opts.fatigue_only,
            capacity_floor,
            task_fingerprint,
            workers_total,
            workers,
        }
    }
}

pub const SHARD_KIND: &str = "posture-opt sweep shard";

/// Largest sampled population.
pub const MAX_SAMPLE: usize = 100_000;

/// The population to sweep: the standard one, or `n` sampled workers from `seed`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Population {
    Standard,
    Sampled { n: usize, seed: u64 },
}

impl Population {
    /// Its members; refuses an empty or too large sample.
    pub fn members(&self) -> Result<Vec<Member>, String> {
        match *self {
            Population::Standard => Ok(standard_population()),
            Population::Sampled { n: 0, .. } => Err("a sample needs at least 1 worker".into()),
            Population::Sampled { n, .. } if n > MAX_SAMPLE => Err(format!(
                "a sample of {n} workers: at most {MAX_SAMPLE} (split a larger study into shards)"
            )),
            Population::Sampled { n, seed } => Ok(sampled_population(n, seed)),
        }
    }

    /// Its name in documents.
    pub fn label(&self) -> String {
        match *self {
            Population::Standard => "P5/P50/P95 women and men".into(),
            Population::Sampled { n, seed } => format!("sampled n={n} seed={seed}"),
        }
    }

    pub fn is_sampled(&self) -> bool {
        matches!(self, Population::Sampled { .. })
    }
}

/// Why a sweep failed.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    #[error("worker {label}: {source}")]
    Task { label: String, source: TaskError },
    #[error("worker {label}: {source}")]
    Plan { label: String, source: PlanError },
    #[error("{file}: {problem}")]
    Merge { file: String, problem: String },
}

/// What the sweep says about U.
pub const NOTE: &str = "U is summed over the simulated time: a worker who is exhausted stops there, so their U can be smaller than a stronger worker's who works the whole task";

/// The task for one member: the file with their body (its `robot` replaced by the generated
/// worker).
fn member_task(file: &TaskFile, path: &Path, m: &Member) -> Result<Task, SweepError> {
    let mut f = file.clone();
    f.worker = m.worker;
    f.robot = None;
    Task::from_task_file(f, path).map_err(|source| SweepError::Task {
        label: m.label.clone(),
        source,
    })
}

/// Plans the task for one member, the first plan's search also starting from `hint` (one
/// posture per phase) when given.
fn plan_member(
    task: &Task,
    m: &Member,
    opts: PlanOptions,
    hint: Option<&[Vec<f64>]>,
) -> Result<Plan, SweepError> {
    let err = |source| SweepError::Plan {
        label: m.label.clone(),
        source,
    };
    let mut planner = Planner::new(task, opts.sqp).map_err(err)?;
    if let Some(h) = hint {
        planner.hint(h).map_err(err)?;
    }
    planner.plan(opts).map_err(err)
}

/// Plans and assesses the task for one member.
pub fn one(
    file: &TaskFile,
    path: &Path,
    index: usize,
    m: &Member,
    opts: PlanOptions,
    floor: f64,
) -> Result<WorkerOutcome, SweepError> {
    let task = member_task(file, path, m)?;
    let plan = plan_member(&task, m, opts, None)?;
    Ok(outcome_of(&task, &plan, index, m, floor))
}

/// [`one`] seeded with the postures of `from`'s plan (re-planned here): the second attempt for a
/// worker the optimiser could not plan.
fn retry(
    file: &TaskFile,
    path: &Path,
    index: usize,
    m: &Member,
    from: &Member,
    opts: PlanOptions,
    floor: f64,
) -> Result<WorkerOutcome, SweepError> {
    let donor_task = member_task(file, path, from)?;
    let donor = plan_member(&donor_task, from, opts, None)?;
    let hint: Vec<Vec<f64>> = donor
        .summary
        .phases
        .iter()
        .map(|p| p.q_rad.clone())
        .collect();
    let task = member_task(file, path, m)?;
    let plan = plan_member(&task, m, opts, Some(&hint))?;
    let mut o = outcome_of(&task, &plan, index, m, floor);
    o.retried_from = Some(from.label.clone());
    Ok(o)
}

/// Why `plan`'s problems do not prove that the worker cannot do the task (empty when they do,
/// or when there are none: a plan without problems is a witness that the worker can). Proof is
/// a target farther than the body is long, or a load above strength or an exhaustion in a plan
/// whose every phase the optimiser finished; a target not reached within the body's length, a
/// collision or a loss of balance is never proof.
fn could_not_plan(plan: &Plan, problems: &[Problem]) -> Vec<String> {
    if problems.is_empty() {
        return Vec::new();
    }
    let unfinished: Vec<String> = plan
        .summary
        .phases
        .iter()
        .filter(|p| !p.solve.determined())
        .map(|p| {
            format!(
                "the optimiser did not converge on '{}' (optimality residual {:.1e})",
                p.phase, p.kkt_residual
            )
        })
        .collect();
    let proven = |p: &Problem| match p {
        Problem::OutOfReach { proven, .. } => *proven,
        Problem::ExceedsStrength { .. } | Problem::Exhaustion { .. } => unfinished.is_empty(),
        Problem::Collision { .. } | Problem::OffBalance { .. } => false,
    };
    if problems.iter().all(proven) {
        return Vec::new();
    }
    problems
        .iter()
        .filter(|p| !proven(p))
        .map(|p| format!("not proven: {}", problem_text(p)))
        .chain(unfinished.iter().cloned())
        .collect()
}

fn outcome_of(task: &Task, plan: &Plan, index: usize, m: &Member, floor: f64) -> WorkerOutcome {
    let a = assess(task, plan, floor);
    let s = &plan.summary;
    let mut problems = Vec::new();
    if let Some(e) = &s.exhaustion {
        problems.push(if e.exceeds_strength {
            Problem::ExceedsStrength {
                group: e.group.clone(),
                phase: e.phase.clone(),
                load: e.load,
            }
        } else {
            Problem::Exhaustion {
                t_s: e.t_s,
                group: e.group.clone(),
                phase: e.phase.clone(),
                load: e.load,
            }
        });
    }
    for p in &s.phases {
        if !p.reachable {
            problems.push(Problem::OutOfReach {
                phase: p.phase.clone(),
                hand_error_m: p.hand_error_m,
                proven: p.beyond_reach_m.is_some(),
            });
        }
        if p.min_clearance_m < 0.0 {
            problems.push(Problem::Collision {
                phase: p.phase.clone(),
                clearance_m: p.min_clearance_m,
                with: p.closest.clone(),
            });
        }
        if let Some(mg) = p.balance_margin_m.filter(|m| *m < 0.0) {
            problems.push(Problem::OffBalance {
                phase: p.phase.clone(),
                margin_m: mg,
            });
        }
    }
    let group = |id: &str| {
        task.half_joints
            .iter()
            .find(|h| h.id == id)
            .map(|h| h.group.clone())
            .unwrap_or_else(|| id.to_string())
    };
    WorkerOutcome {
        index,
        label: m.label.clone(),
        worker: m.worker,
        can_do: problems.is_empty(),
        could_not_plan: could_not_plan(plan, &problems),
        problems,
        retried_from: None,
        total_u_min: s.total_u,
        simulated_s: s.duration_s,
        worst_group: group(&s.worst_half_joint),
        lowest_capacity: s.lowest_capacity,
        lowest_capacity_group: group(&s.lowest_capacity_half_joint),
        minutes_to_exhaustion: a.meaning.minutes_to_exhaustion,
        exhaustion_verdict: a.meaning.exhaustion_verdict.to_string(),
        shift_status: a.verdict.status,
        shift_verdict: a.verdict.headline.clone(),
        minutes_followed: a.meaning.minutes_followed,
        exhaustion: s.exhaustion.clone(),
        rula_max: a.rula_max,
        reba_max: a.reba_max,
        back_compression_max_n: a.back_compression_max_n,
        rest_needed_s: a.rest.model.rest_s_per_cycle,
        exhausted_in_variants: a.uncertainty.as_ref().map(|u| u.exhausted_in),
    }
}

impl Sweep {
    /// The sweep document from the workers' outcomes (one run or merged shards).
    pub fn from_outcomes(
        task: &str,
        population: &str,
        sampled: bool,
        adaptive: bool,
        floor: f64,
        mut workers: Vec<WorkerOutcome>,
    ) -> Self {
        workers.sort_by_key(|w| w.index);
        let share = |sex: Option<Sex>| {
            let of: Vec<&WorkerOutcome> = workers
                .iter()
                .filter(|w| sex.is_none_or(|s| w.worker.sex == s))
                .collect();
            let determined: Vec<&&WorkerOutcome> =
                of.iter().filter(|w| w.could_not_plan.is_empty()).collect();
            wilson(
                determined.iter().filter(|w| w.can_do).count(),
                determined.len(),
            )
        };
        Sweep {
            task: task.to_string(),
            population: population.to_string(),
            adaptive,
            capacity_floor: floor,
            cannot_do: workers
                .iter()
                .filter(|w| !w.can_do && w.could_not_plan.is_empty())
                .count(),
            could_not_plan: workers
                .iter()
                .filter(|w| !w.could_not_plan.is_empty())
                .count(),
            sustain_all: sampled.then(|| share(None)),
            sustain_women: sampled.then(|| share(Some(Sex::Female))),
            sustain_men: sampled.then(|| share(Some(Sex::Male))),
            note: NOTE.into(),
            workers,
        }
    }
}

/// Plans `file` (read from `path`) for the members of `shard`, in parallel; `on_done` is called
/// once per finished worker (from any thread) with its outcome, e.g. to stream it or advance a
/// progress bar.
///
/// A worker the optimiser could not plan (see [`WorkerOutcome::could_not_plan`]) is planned a
/// second time, its search also starting from the postures of the nearest worker of the shard
/// whose plan was determined (same sex first, then the closest stature, then mass); the second
/// attempt is kept when it is determined, else the first, marked with the worker tried from.
pub fn sweep_members(
    file: &TaskFile,
    path: &Path,
    members: &[Member],
    shard: Shard,
    opts: PlanOptions,
    floor: f64,
    on_done: &(dyn Fn(&WorkerOutcome) + Sync),
) -> Result<Vec<WorkerOutcome>, SweepError> {
    let first: Vec<WorkerOutcome> = shard
        .indices(members.len())
        .par_iter()
        .map(|&i| {
            let r = one(file, path, i, &members[i], opts, floor)?;
            if r.could_not_plan.is_empty() {
                on_done(&r);
            }
            Ok(r)
        })
        .collect::<Result<_, SweepError>>()?;
    let determined: Vec<usize> = first
        .iter()
        .filter(|w| w.could_not_plan.is_empty())
        .map(|w| w.index)
        .collect();
    first
        .into_par_iter()
        .map(|w| {
            if w.could_not_plan.is_empty() {
                return Ok(w);
            }
            let r = match nearest(members, w.index, &determined) {
                Some(d) => {
                    let second = retry(
                        file,
                        path,
                        w.index,
                        &members[w.index],
                        &members[d],
                        opts,
                        floor,
                    )?;
                    if second.could_not_plan.is_empty() {
                        second
                    } else {
                        WorkerOutcome {
                            retried_from: second.retried_from,
                            ..w
                        }
                    }
                }
                None => w,
            };
            on_done(&r);
            Ok(r)
        })
        .collect()
}

/// The member among `candidates` nearest to member `i`: same sex first, then the smallest
/// stature difference, then mass difference, then index.
fn nearest(members: &[Member], i: usize, candidates: &[usize]) -> Option<usize> {
    let w = &members[i].worker;
    candidates.iter().copied().min_by(|&a, &b| {
        let key = |j: usize| {
            let o = &members[j].worker;
            (
                o.sex != w.sex,
                (o.stature_m - w.stature_m).abs(),
                (o.mass_kg - w.mass_kg).abs(),
                j,
            )
        };
        let (ka, kb) = (key(a), key(b));
        ka.0.cmp(&kb.0)
            .then(ka.1.total_cmp(&kb.1))
            .then(ka.2.total_cmp(&kb.2))
            .then(ka.3.cmp(&kb.3))
    })
}

/// Checks every number of a shard read back from a file as an input: finite, within its range
/// (capacities 0..1, fatigue and durations >= 0, the worker valid, indices within the worker
/// count). The error names the field.
fn check_shard_values(s: &SweepShard) -> Result<(), String> {
    let big = f64::MAX;
    let num = |v: f64, f: String, lo: f64, hi: f64| -> Result<(), String> {
        if v.is_finite() && v >= lo && v <= hi {
            Ok(())
        } else {
            Err(format!(
                "{f}: must be a finite number within {lo}..{hi}, got {v}"
            ))
        }
    };
    if !(s.capacity_floor.is_finite() && s.capacity_floor > 0.0 && s.capacity_floor < 1.0) {
        return Err(format!(
            "capacity_floor: must be between 0 and 1, got {}",
            s.capacity_floor
        ));
    }
    if s.workers.len() > s.workers_total {
        return Err(format!(
            "workers: holds {} workers, more than workers_total ({})",
            s.workers.len(),
            s.workers_total
        ));
    }
    for (i, w) in s.workers.iter().enumerate() {
        let f = |name: &str| format!("workers[{i}].{name}");
        if w.index >= s.workers_total {
            return Err(format!(
                "{}: must be below workers_total ({}), got {}",
                f("index"),
                s.workers_total,
                w.index
            ));
        }
        w.worker
            .validate()
            .map_err(|e| format!("{}: {e}", f("worker")))?;
        num(w.total_u_min, f("total_u_min"), 0.0, big)?;
        num(w.simulated_s, f("simulated_s"), 0.0, big)?;
        num(w.lowest_capacity, f("lowest_capacity"), 0.0, 1.0)?;
        if let Some(m) = w.minutes_to_exhaustion {
            num(m, f("minutes_to_exhaustion"), 0.0, big)?;
        }
        num(w.minutes_followed, f("minutes_followed"), 0.0, big)?;
        if let Some(e) = &w.exhaustion {
            num(e.t_s, f("exhaustion.t_s"), 0.0, big)?;
            num(e.load, f("exhaustion.load"), 0.0, big)?;
        }
        if let Some(c) = w.back_compression_max_n {
            num(c, f("back_compression_max_n"), 0.0, big)?;
        }
        if let Some(r) = w.rest_needed_s {
            num(r, f("rest_needed_s"), 0.0, big)?;
        }
    }
    Ok(())
}

/// Merges shard results (name, shard) into one sweep; every shard's numbers are checked as
/// inputs first.
pub fn merge(shards: &[(String, SweepShard)]) -> Result<Sweep, SweepError> {
    let bad = |file: &str, problem: String| SweepError::Merge {
        file: file.to_string(),
        problem,
    };
    for (name, s) in shards {
        check_shard_values(s).map_err(|p| bad(name, p))?;
    }
    let Some((_, first)) = shards.first() else {
        return Err(bad("(none)", "no shard results given".into()));
    };
    // the shards must hold every worker: a claimed total beyond what they hold is refused
    // before anything is allocated for it
    let held: usize = shards.iter().map(|(_, s)| s.workers.len()).sum();
    if first.workers_total > held.saturating_add(super::compare::MERGE_SLACK) {
        return Err(bad(
            shards.first().map_or("(none)", |s| s.0.as_str()),
            format!(
                "missing {} workers: the shards hold {held} of the {} they claim",
                first.workers_total - held,
                first.workers_total
            ),
        ));
    }
    let mut seen = vec![false; first.workers_total];
    let mut workers = Vec::new();
    for (name, s) in shards {
        if s.kind != SHARD_KIND {
            return Err(bad(name, format!("not a sweep shard (kind '{}')", s.kind)));
        }
        if s.task != first.task
            || s.population != first.population
            || s.adaptive != first.adaptive
            || s.fatigue_only != first.fatigue_only
            || s.capacity_floor != first.capacity_floor
            || s.workers_total != first.workers_total
        {
            return Err(bad(
                name,
                "made for another task, population or options (adaptive, fatigue-only, capacity floor) than the first shard".into(),
            ));
        }
        if s.task_fingerprint != first.task_fingerprint {
            return Err(bad(
                name,
                "made from other files than the first shard (the task, its robot or its parameter file differs)".into(),
            ));
        }
        for w in &s.workers {
            match seen.get_mut(w.index) {
                Some(x) if !*x => *x = true,
                _ => {
                    return Err(bad(
                        name,
                        format!("worker {} appears twice or is out of range", w.index),
                    ));
                }
            }
            workers.push(w.clone());
        }
    }
    let missing: Vec<usize> = (0..seen.len()).filter(|&i| !seen[i]).collect();
    if !missing.is_empty() {
        return Err(bad(
            "(all shards)",
            format!(
                "{} of {} workers are missing, e.g. {:?}",
                missing.len(),
                seen.len(),
                &missing[..missing.len().min(10)]
            ),
        ));
    }
    Ok(Sweep::from_outcomes(
        &first.task,
        &first.population,
        first.sampled,
        first.adaptive,
        first.capacity_floor,
        workers,
    ))
}

/// One line describing a problem: what, where and when.
pub fn problem_text(p: &Problem) -> String {
    match p {
        Problem::ExceedsStrength { group, phase, load } => {
            format!(
                "{group} exceeds strength ({:.0} % MVC) in '{phase}'",
                100.0 * load
            )
        }
        Problem::Exhaustion {
            t_s,
            group,
            phase,
            load,
        } => format!(
            "{group} exhausted at {:.1} min in '{phase}' ({:.0} % MVC)",
            t_s / 60.0,
            100.0 * load
        ),
        Problem::OutOfReach {
            phase,
            hand_error_m,
            proven,
        } => {
            if *proven {
                format!("'{phase}' out of reach by {:.0} mm", 1000.0 * hand_error_m)
            } else {
                format!(
                    "'{phase}' not reached ({:.0} mm short; no balanced posture reaching it was found)",
                    1000.0 * hand_error_m
                )
            }
        }
        Problem::Collision {
            phase,
            clearance_m,
            with,
        } => format!(
            "'{phase}' collides ({:.0} mm into {})",
            -1000.0 * clearance_m,
            with.as_deref().unwrap_or("an obstacle")
        ),
        Problem::OffBalance { phase, margin_m } => format!(
            "'{phase}' off balance ({:.0} mm outside the feet)",
            -1000.0 * margin_m
        ),
    }
}

fn share_text(name: &str, s: &Option<Share>) -> String {
    match s {
        Some(s) => format!(
            "{name}: {:.0} % can do the whole task (95 % CI {:.0}–{:.0} %, n = {})",
            100.0 * s.share,
            100.0 * s.low,
            100.0 * s.high,
            s.of
        ),
        None => String::new(),
    }
}

/// How many of the workers able to do the task get each shift verdict ("; of the 6 able, the
/// shift is not acceptable for 2, caution for 4"), empty when there are none.
pub fn shift_counts(s: &Sweep) -> String {
    use crate::assess::verdict::Status;
    let able: Vec<&WorkerOutcome> = s
        .workers
        .iter()
        .filter(|w| w.can_do && w.could_not_plan.is_empty())
        .collect();
    let counts: Vec<String> = [
        (Status::Exceeded, "not acceptable"),
        (Status::NotDetermined, "not determined"),
        (Status::Caution, "conditionally acceptable"),
        (Status::Acceptable, "acceptable"),
    ]
    .into_iter()
    .filter_map(|(status, words)| {
        let n = able.iter().filter(|w| w.shift_status == status).count();
        (n > 0).then(|| format!("{words} for {n}"))
    })
    .collect();
    if counts.is_empty() {
        return String::new();
    }
    format!(
        "; of the {} able, the shift is {}",
        able.len(),
        counts.join(", ")
    )
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
        if s.adaptive { "adaptive" } else { "held" },
        s.capacity_floor
    );
    let _ = writeln!(
        o,
        "{:<12} {:>6} {:>8} {:>6} {:>7} {:>9} {:>6} {:>10}  verdict",
        "worker", "sex", "stature", "mass", "str.pct", "U [min]", "lowC", "rest/cycle"
    );
    for w in &s.workers {
        let _ = writeln!(
            o,
            "{:<12} {:>6} {:>7.3}m {:>4.0}kg {:>7.0} {:>9.2} {:>6.2} {:>10}  {}",
            w.label,
            w.worker.sex.name(),
            w.worker.stature_m,
            w.worker.mass_kg,
            w.worker.strength_percentile,
            w.total_u_min,
            w.lowest_capacity,
            w.rest_needed_s
                .map_or("none helps".into(), |r| format!("{r:.1} s")),
            if !w.could_not_plan.is_empty() {
                format!(
                    "THE OPTIMISER COULD NOT PLAN{}: {}",
                    w.retried_from
                        .as_ref()
                        .map(|f| format!(" (also tried from {f}'s postures)"))
                        .unwrap_or_default(),
                    w.could_not_plan.join("; ")
                )
            } else if w.problems.is_empty() {
                let how = if w.lowest_capacity < s.capacity_floor || w.rest_needed_s.is_none() {
                    format!(
                        "only by changing posture, capacity falls to {:.0} %",
                        100.0 * w.lowest_capacity
                    )
                } else {
                    match w.minutes_to_exhaustion {
                        Some(m) => format!(
                            "kept up, exhausted after {}",
                            if m < 90.0 {
                                format!("{m:.1} min")
                            } else {
                                format!("{:.1} h", m / 60.0)
                            }
                        ),
                        None if w.exhaustion_verdict == "not_determined" => format!(
                            "kept up: {}",
                            crate::assess::meaning::no_exhaustion_words(
                                &w.exhaustion_verdict,
                                w.minutes_followed
                            )
                        ),
                        None => "no group gives out".to_string(),
                    }
                };
                // the shift verdict's status and binding criterion first (its details are the
                // plan's): being able to do it says nothing of whether it is acceptable
                format!(
                    "shift: {}; physically able to do it ({how})",
                    w.shift_verdict.split(" — ").next().unwrap_or_default()
                )
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
        "\n{} of {} workers cannot do the task{}{}",
        s.cannot_do,
        s.workers.len(),
        shift_counts(s),
        if s.could_not_plan > 0 {
            format!(
                "; the optimiser could not plan {} (not counted as unable)",
                s.could_not_plan
            )
        } else {
            String::new()
        }
    );
    for (name, sh) in [
        ("all", &s.sustain_all),
        ("women", &s.sustain_women),
        ("men", &s.sustain_men),
    ] {
        let t = share_text(name, sh);
        if !t.is_empty() {
            let _ = writeln!(o, "{t}");
        }
    }
    let _ = writeln!(o, "note: {}", s.note);
    o
}
