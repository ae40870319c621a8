//! `posture-opt robot`: the URDF of a worker and its strength table, written together.

use crate::common::{Outputs, lib_err, parse_sex, stdout};
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
    /// Output URDF file (its strength table goes to NAME.strength.yaml beside it); stdout if absent.
    #[arg(long)]
    out: Option<PathBuf>,
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
