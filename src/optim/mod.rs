//! The posture optimiser: a sequential QP per task phase (DESIGN §4), sole user of clarabel.
//! Knows no files: it takes a body model, a statics workspace, a workstation and the fatigue
//! objective's inputs.

pub mod objective;
pub mod qp;
pub mod sqp;

pub use objective::FatigueObjective;
pub use qp::{PhaseQp, QpError};
pub use sqp::{solve_phase, PhaseInput, PhaseSolution, SqpSettings, SqpWork};
