//! `posture-opt schema`: the task files' JSON Schema.

use crate::common::print_json;

#[derive(clap::Args)]
pub struct Args {}

pub fn run(_a: Args) -> anyhow::Result<()> {
    print_json(&posture_opt::schema::task_schema())
}
