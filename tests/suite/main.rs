//! Every integration test of posture-opt, in one test binary: one compile and one link for all of
//! them, and one process whose test threads keep both cores busy (`cargo test --release`; a part
//! by name, e.g. `cargo test --release --test suite -- hostile::`).
//!
//! Each module is one subject; `common` runs the command-line program and checks its contract.

mod common;

mod assess_angles;
mod body_golden;
mod body_loading;
mod body_statics;
mod capable;
mod cli;
mod compare_sweep;
mod evaluate;
mod fatigue_fit;
mod fatigue_model;
mod fatigue_recovery;
mod hostile;
mod html_report;
mod low_back;
mod niosh;
mod paper_validation;
mod plan_reference;
mod plan_truth;
mod posture_zones;
mod reba;
mod rula;
mod seated;
mod shift_verdict;
mod stance_placement;
mod statistics;
mod task_files;
mod three_compartment;
mod work_rest;
mod worker_strength;
mod workstation;
