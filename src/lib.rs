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
//! # Modules
//! * [`fatigue`]: the Ma et al. model (+ recovery), the three-compartment model, Table 2's MET
//!   models and the r / ICC statistics.
//! * [`validation`]: the paper's static and dynamic validations, as data and SVG figures.

pub mod body;
pub mod error;
pub mod fatigue;
pub mod io;
pub mod optim;
pub mod plan;
pub mod report;
pub mod task;
pub mod validation;
pub mod workstation;

pub use error::Error;
