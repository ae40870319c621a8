//! Planning: task files, the posture optimiser and the planning loop.
//!
//! * [`task`]: task files → validated tasks;
//! * [`posture`]: a posture evaluated (statics standing on both feet, loads, clearances, balance);
//! * [`objective`]: the exact multi-cycle fatigue cost, discomfort, the baselines' costs;
//! * [`qp`], [`sqp`]: the per-phase QP (clarabel) and the SQP around it (line search with
//!   second-order correction, KKT stopping test);
//! * [`ik`], [`search`]: starting postures and the deterministic multi-start;
//! * [`planner`]: coordination passes across phases, the time loop with re-planning, baselines;
//! * [`result`]: the plan document;
//! * [`held`]: the held object against the worker's own body (a collision of its phase);
//! * [`stepping`]: the feet's poses, the steps between phases, their cost and words;
//! * [`asymmetry`]: working off to the side of the feet, priced like NIOSH's multiplier;
//! * [`reach`]: when a target is provably out of reach (beyond the kinematic chain's length);
//! * [`zones`]: the standards' acceptable posture zones, as elastic constraints.

pub mod asymmetry;
pub mod held;
pub mod ik;
pub mod objective;
pub mod planner;
pub mod posture;
pub mod qp;
pub mod reach;
pub mod result;
pub mod search;
pub mod sqp;
pub mod stepping;
pub mod task;
pub mod zones;

pub use planner::{PlanError, PlanOptions, Planner, plan_task, plan_task_with};
pub use result::Plan;
pub use task::{Task, TaskError, TaskFile};
