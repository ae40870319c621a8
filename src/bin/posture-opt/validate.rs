//! `posture-opt validate static|dynamic|recovery`: the paper's validations, tables and figures,
//! and the planning model (with recovery) against published data.

use crate::common::{lib_err, print_json, stdout};
use posture_opt::fatigue::MaParams;
use posture_opt::fatigue::params::ParameterSets;
use posture_opt::validation::{
    dynamic_validation, plots, recovery_validation, report, static_validation,
};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    which: Which,
}

#[derive(clap::Subcommand)]
enum Which {
    /// Table 2: Eq. 8 against 24 published MET models (Pearson r, ICC).
    Static(Opts),
    /// §4: Liu et al. at MVC, Freund-Takala, Wexler's trend, Frey-Law & Avin endurance curves.
    Dynamic(Opts),
    /// The model `plan` uses (a named parameter set, with recovery) against published endurance,
    /// intermittent-work and recovery data.
    Recovery(RecoveryOpts),
}

#[derive(clap::Args)]
struct RecoveryOpts {
    /// The parameter set to check (default: the one `plan` uses).
    #[arg(long)]
    parameters: Option<String>,
    #[arg(long)]
    json: bool,
}

#[derive(clap::Args)]
struct Opts {
    #[arg(long, default_value_t = 1.0)]
    k_per_min: f64,
    #[arg(long)]
    json: bool,
    /// Write SVG figures into this directory.
    #[arg(long)]
    plot: Option<PathBuf>,
}

pub fn run(a: Args) -> anyhow::Result<()> {
    match a.which {
        Which::Static(o) => {
            MaParams::new(o.k_per_min, 0.0).map_err(|e| lib_err(format!("--k-per-min: {e}")))?;
            let v = static_validation(o.k_per_min);
            if let Some(dir) = &o.plot {
                let files = plots::static_figures(&v, dir).map_err(lib_err)?;
                crate::common::say(format_args!(
                    "wrote {} figures into {}",
                    files.len(),
                    dir.display()
                ));
            }
            if o.json {
                print_json(&v)
            } else {
                stdout(report::static_table(&v).as_bytes())
            }
        }
        Which::Dynamic(o) => {
            MaParams::new(o.k_per_min, 0.0).map_err(|e| lib_err(format!("--k-per-min: {e}")))?;
            let v = dynamic_validation(o.k_per_min);
            if let Some(dir) = &o.plot {
                let files = plots::dynamic_figures(&v, dir).map_err(lib_err)?;
                crate::common::say(format_args!(
                    "wrote {} figures into {}",
                    files.len(),
                    dir.display()
                ));
            }
            if o.json {
                print_json(&v)
            } else {
                stdout(report::dynamic_table(&v).as_bytes())
            }
        }
        Which::Recovery(o) => {
            let sets = ParameterSets::shipped();
            let name = o.parameters.unwrap_or_else(|| sets.default_set.clone());
            let set = sets.get(&name).ok_or_else(|| {
                lib_err(format!(
                    "--parameters: no set named '{name}' (the sets: {})",
                    sets.names().join(", ")
                ))
            })?;
            let v = recovery_validation(set, name == sets.default_set).map_err(lib_err)?;
            if o.json {
                print_json(&v)
            } else {
                stdout(report::recovery_table(&v).as_bytes())
            }
        }
    }
}
