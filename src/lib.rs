//! posture-opt: fatigue-aware posture planning for manual work.
//!
//! Built on the dynamic muscle fatigue model of Ma, Chablat, Bennis & Zhang (2009).
//!
//! # Conventions
//! * **Units**: SI inside (metres, radians, newtons, N·m, seconds). The paper's fatigue rate `k`
//!   and the recovery rate `R` are per minute and the fatigue index `U` is in minutes; names say
//!   so (`k_per_min`, `fatigue_u_min`) and [`fatigue::units`] is the only place that converts.
//! * **Loads** are relative: `f = F_load / MVC` (or joint torque / MVC torque) in [0, 1].
//! * **Capacity** `c = F_cem / MVC` in (0, 1]; 1 when rested.
//!
//! # Planning from code
//!
//! ```
//! use posture_opt::plan::plan_with_baseline;
//! use posture_opt::task::Task;
//!
//! let task = Task::from_file(concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/bench_assembly.yaml")).unwrap();
//! let (plan, baseline) = plan_with_baseline(&task, true).unwrap();
//! // an hour of work: 240 cycles of 3 phases and a rest, every step held at constant load
//! assert_eq!(plan.steps.len(), 240 * 4);
//! assert!((plan.summary.duration_s - 3600.0).abs() < 1e-9);
//! // every target is reached within 1 cm, and adaptation lowers the total fatigue index
//! assert!(plan.summary.phases.iter().all(|p| p.hand_error_m < 0.01));
//! assert!(plan.summary.total_u < baseline.summary.total_u);
//! ```
//!
//! For repeated planning of one task, [`plan::Planner`] keeps its statics workspace, QP solver
//! and last postures between calls.
//!
//! # Modules
//! * [`fatigue`]: the Ma et al. model (+ recovery), the three-compartment model, Table 2's MET
//!   models and the r / ICC statistics.
//! * [`validation`]: the paper's static and dynamic validations, as data and SVG figures.
//! * [`body`]: URDF body model, statics workspace (positions, Jacobians, holding torques and their
//!   derivatives), half-joint strength, the generated worker.
//! * [`workstation`]: obstacles and capsule clearances (parry3d).
//! * [`task`]: task files → validated tasks.
//! * [`optim`]: the per-phase sequential QP (clarabel).
//! * [`plan`]: the planning loop and the `Plan` document; [`report`]: its summary, CSV and the
//!   self-contained HTML report ([`report::html`]).
//! * [`rula`]: RULA from a posture, with the worksheet; [`rest`]: work/rest advice (the model's
//!   recovery against Rohmert's rule); [`compare`]: layouts ranked; [`sweep`]: populations.
//!
//! # Assessing a plan
//!
//! ```
//! use posture_opt::{plan::plan_with_baseline, rest::rest_advice, task::Task};
//!
//! let task = Task::from_file(concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/shelf_lowered.yaml")).unwrap();
//! let (plan, _) = plan_with_baseline(&task, true).unwrap();
//! // RULA per phase (the default worker body): grand scores 1-7
//! let rula: Vec<i32> = plan.summary.phases.iter().map(|p| p.rula.as_ref().unwrap().grand_score).collect();
//! assert!(rula.iter().all(|g| (1..=7).contains(g)));
//! // with the boards lowered, the task's 6 s of rest per cycle keeps every capacity >= 0.7
//! let rest = rest_advice(&task, &plan, 0.7);
//! assert!(rest.model.rest_s_per_cycle.unwrap() <= task.rest_s);
//! ```

pub mod assess;
pub mod body;
pub mod error;
pub mod fatigue;
pub mod io;
pub mod plan;
pub mod report;
pub mod record;
pub mod schema;
pub mod study;
pub mod validation;
pub mod workstation;

pub use error::Error;
