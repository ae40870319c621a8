//! posture-opt command line: clap parses, the library does the work, one module per subcommand.
//! Exit codes: 0 ok, 2 bad input (the message names the file, field, line or option), 1 internal
//! failure. A standard output that is closed (`>&-`) or whose reader left (a pipe) is exit 2
//! with a message: the answer was not delivered.

mod common;
mod compare;
mod evaluate;
mod fit;
mod met;
mod plan;
mod robot;
mod schema;
mod statics;
mod sweep;
mod validate;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "posture-opt",
    version,
    about = "Fatigue-aware posture planning for manual work (Ma et al. 2009 dynamic muscle fatigue model)"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Reproduce the paper's validations.
    Validate(validate::Args),
    /// Maximum endurance time and the capacity / fatigue-index curve for a held load.
    Met(met::Args),
    /// Joint positions, Jacobian and holding torques of any URDF at one posture.
    Statics(statics::Args),
    /// Write the URDF of a standing whole-body worker (and its strength table beside it).
    Robot(robot::Args),
    /// Plan postures for a task file.
    Plan(plan::Args),
    /// Compare workstation layouts (task files): side by side, ranked.
    Compare(compare::Args),
    /// Plan one task for a population of workers: who cannot do it, and where.
    Sweep(sweep::Args),
    /// Evaluate recorded work (joint angles and hand loads over time) into a fatigue timeline.
    Evaluate(evaluate::Args),
    /// Print the JSON Schema of task files.
    Schema(schema::Args),
    /// Fit fatigue parameters to measured endurance times or capacity decline.
    Fit(fit::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let r = match cli.command {
        Command::Validate(a) => validate::run(a),
        Command::Met(a) => met::run(a),
        Command::Statics(a) => statics::run(a),
        Command::Robot(a) => robot::run(a),
        Command::Plan(a) => plan::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Sweep(a) => sweep::run(a),
        Command::Evaluate(a) => evaluate::run(a),
        Command::Schema(a) => schema::run(a),
        Command::Fit(a) => fit::run(a),
    };
    common::exit(r)
}
