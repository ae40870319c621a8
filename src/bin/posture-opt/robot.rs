//! `posture-opt robot`: the URDF of a worker and its strength table, written together.

use crate::common::{Outputs, bad, lib_err, parse_sex, stdout};
use posture_opt::body::{Sex, StrengthTable, Worker, worker_urdf};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// male or female.
    #[arg(long, value_parser = parse_sex)]
    sex: Sex,
    #[arg(long)]
    stature_m: f64,
    #[arg(long)]
    mass_kg: f64,
    /// Strength percentile (1-99) of the worker's sex.
    #[arg(long, default_value_t = 50.0)]
    strength_percentile: f64,
    /// Output URDF file NAME.urdf; its strength table is written beside it as NAME.strength.yaml
    /// (refused if that file already exists, unless --force). Standard output if absent.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Overwrite an existing NAME.strength.yaml beside --out (a regular file only: a symlink
    /// there is always refused).
    #[arg(long, requires = "out")]
    force: bool,
}

/// The strength table beside `--out` is a file the user did not name: refuse to replace one
/// that exists (unless `--force`) and never write through a symlink there.
fn check_sibling(sp: &std::path::Path, out: &std::path::Path, force: bool) -> anyhow::Result<()> {
    let Ok(meta) = std::fs::symlink_metadata(sp) else {
        return Ok(());
    };
    if meta.file_type().is_symlink() {
        return Err(bad(format!(
            "{}: is a symlink; the strength table written beside --out {} is never written through a symlink (remove it, or choose another --out)",
            sp.display(),
            out.display()
        )));
    }
    if force {
        return Ok(());
    }
    Err(bad(format!(
        "{}: already exists; the strength table of --out {} is written there (remove it, choose another --out, or pass --force to overwrite it)",
        sp.display(),
        out.display()
    )))
}

pub fn run(a: Args) -> anyhow::Result<()> {
    let w = Worker {
        sex: a.sex,
        stature_m: a.stature_m,
        mass_kg: a.mass_kg,
        strength_percentile: a.strength_percentile,
    };
    let urdf = worker_urdf(&w, &StrengthTable::default_table()).map_err(lib_err)?;
    match &a.out {
        Some(path) => {
            let sp = StrengthTable::path_beside(path);
            check_sibling(&sp, path, a.force)?;
            let mut out = Outputs::new(&[]);
            out.add("--out", &Some(path.clone()), || Ok(urdf.into_bytes()))?;
            out.add("strength table", &Some(sp.clone()), || {
                Ok(posture_opt::body::strength::DEFAULT_TABLE_YAML
                    .as_bytes()
                    .to_vec())
            })?;
            out.write()?;
            crate::common::say(format_args!(
                "wrote {} and {}",
                path.display(),
                sp.display()
            ));
            Ok(())
        }
        None => stdout(urdf.as_bytes()),
    }
}
