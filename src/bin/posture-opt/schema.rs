//! `posture-opt schema`: the task files' JSON Schema, or (`--markdown`) the task file reference
//! rendered from it (`docs/task-format.md`).

use crate::common::{print_json, stdout};

#[derive(clap::Args)]
pub struct Args {
    /// Print the task file reference as Markdown (every field's meaning, unit, default and
    /// range, from the schema) instead of the JSON Schema.
    #[arg(long)]
    markdown: bool,
}

pub fn run(a: Args) -> anyhow::Result<()> {
    if a.markdown {
        stdout(posture_opt::schema::task_schema_markdown().as_bytes())
    } else {
        print_json(&posture_opt::schema::task_schema())
    }
}
