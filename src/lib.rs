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
//! ```no_run
//! use posture_opt::assess::assess;
//! use posture_opt::plan::{plan_task, Task};
//!
//! let task = Task::from_file(concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/bench_assembly.yaml")).unwrap();
//! let plan = plan_task(&task).unwrap();
//! // every target is reached within 1 cm, and every phase's solve met its KKT test
//! assert!(plan.summary.phases.iter().all(|p| p.hand_error_m < 0.01 && p.converged));
//! // the plan against the naive baselines (same task, postures not optimised for fatigue)
//! for b in &plan.summary.baselines {
//!     println!("{}: U {:.1} min, change {:+.0} %", b.name, b.total_u, 100.0 * b.change);
//! }
//! // what an ergonomist reports: RULA/REBA, L5/S1 compression, % capable, work/rest
//! let a = assess(&task, &plan, 0.7);
//! println!("women capable: {:.0} %", 100.0 * a.capable_women);
//! ```
//!
//! For repeated planning of one task, [`plan::Planner`] keeps its statics workspace, QP solver
//! and last postures between calls.
//!
//! # Modules
//! * [`fatigue`]: the Ma et al. model (+ recovery), the three-compartment model, Table 2's MET
//!   models, the r / ICC statistics, parameter sets and fitting to a user's data.
//! * [`validation`]: the paper's static and dynamic validations, as data and SVG figures.
//! * [`body`]: URDF body model, statics workspace (positions, Jacobians, holding torques and their
//!   derivatives, both feet on the floor), population strength, the generated whole-body worker.
//! * [`workstation`]: obstacles and capsule clearances (parry3d).
//! * [`plan`]: task files, the per-phase SQP (clarabel), multi-start, the planning loop and the
//!   `Plan` document.
//! * [`assess`]: RULA, REBA, NIOSH lifting, L5/S1 compression, % capable, work/rest advice and
//!   the fatigue parameters' uncertainty.
//! * [`study`]: layouts compared and population sweeps (with shards for big studies).
//! * [`record`]: recorded work (CSV, OpenSim .mot/.sto) evaluated, offline or streaming.
//! * [`report`]: text, CSV and the self-contained HTML report.

// Numeric kernels walk several parallel per-joint arrays with one index; iterator zips over
// four or five slices read worse than the index.
#![allow(clippy::needless_range_loop)]

pub mod assess;
pub mod body;
pub mod error;
pub mod fatigue;
pub mod io;
pub mod plan;
pub mod record;
pub mod report;
pub mod schema;
pub mod study;
pub mod validation;
pub mod workstation;

pub use error::Error;
