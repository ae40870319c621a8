//! `posture-opt fit DATA.csv`: k per body region (and the recovery rate) from a user's own
//! endurance times or capacity measurements, with confidence intervals; `--out` writes a
//! parameter file a task uses with `fatigue: {parameters_file: FILE}`.

use crate::common::{Outputs, bad, lib_err, print_json, stdout};
use posture_opt::fatigue::fit::{self, FastDeficit, Fit, FitOptions};
use posture_opt::fatigue::params::{ParameterSets, RecoverySpec};
use posture_opt::io::read_text;
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Measurements (CSV: region, load_fmvc, on_s, off_s, endurance_s | t_s, capacity | rest_s,
    /// second_over_first).
    data: PathBuf,
    /// Fit the recovery rate at rest too (default: when the data hold intermittent holds or
    /// second bouts).
    #[arg(long, conflicts_with = "no_recovery_fit")]
    recovery_fit: bool,
    /// Keep the recovery rate at rest at --rest-per-min.
    #[arg(long)]
    no_recovery_fit: bool,
    /// Recovery rate at rest [1/min] to start from (or keep); the slow deficit's under a routed
    /// recovery [default: the base set's, or 0.37].
    #[arg(long)]
    rest_per_min: Option<f64>,
    /// Load (fraction of MVC) from which recovery stops (kept fixed) [default: the base set's, or
    /// 0.085].
    #[arg(long)]
    limit_fmvc: Option<f64>,
    /// Parameter set whose values the regions not in the data keep, and whose recovery form is
    /// fitted (routed-2026: two deficits, the fast one kept as the set has it).
    #[arg(long, default_value = "default-2026")]
    base: String,
    /// Write the fitted parameter set (YAML) here.
    #[arg(long)]
    out: Option<PathBuf>,
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> anyhow::Result<()> {
    let name = a.data.display().to_string();
    let sets = ParameterSets::shipped();
    let Some(base) = sets.get(&a.base) else {
        return Err(bad(format!(
            "--base: unknown parameter set '{}'; choose one of {}",
            a.base,
            sets.names().join(", ")
        )));
    };
    let (base_rest, base_limit) = base.recovery.ranges().map_or((0.37, 0.085), |r| (r.0, r.3));
    let rest_per_min = a.rest_per_min.unwrap_or(base_rest);
    let limit_fmvc = a.limit_fmvc.unwrap_or(base_limit);
    if !(rest_per_min.is_finite()
        && (0.0..=posture_opt::fatigue::ma::R_MAX_PER_MIN).contains(&rest_per_min))
    {
        return Err(bad(format!(
            "--rest-per-min must be 0..{} 1/min",
            posture_opt::fatigue::ma::R_MAX_PER_MIN
        )));
    }
    let fast = match base.recovery {
        RecoverySpec::Routed {
            fast_rest_per_min,
            fast_share_max,
            ..
        } => Some(FastDeficit {
            rest_per_min: fast_rest_per_min,
            share_max: fast_share_max,
        }),
        _ => None,
    };
    let top = if fast.is_some() {
        posture_opt::fatigue::ma::ROUTE_FROM_FMVC
    } else {
        1.0
    };
    if !(limit_fmvc.is_finite() && (0.01..=top).contains(&limit_fmvc)) {
        return Err(bad(format!("--limit-fmvc must be 0.01..{top}")));
    }
    Outputs::precheck(&[("--out", &a.out)], &[&a.data])?;
    let text = read_text(&a.data).map_err(lib_err)?;
    let rows = fit::parse_rows(&text, &name).map_err(lib_err)?;
    let opts = FitOptions {
        rest_per_min,
        limit_fmvc,
        fast,
        fit_rest: if a.recovery_fit {
            Some(true)
        } else if a.no_recovery_fit {
            Some(false)
        } else {
            None
        },
    };
    let f = fit::fit(&rows, &name, opts).map_err(lib_err)?;
    let mut out = Outputs::new(&[&a.data]);
    out.add("--out", &a.out, || {
        let set = f.parameter_set(base);
        let mut y = format!(
            "# Fatigue parameters fitted by `posture-opt fit {name}`; use in a task with\n# fatigue: {{parameters_file: <this file>}}\n"
        );
        y.push_str(&serde_saphyr::to_string(&set).map_err(|e| anyhow::anyhow!(e.to_string()))?);
        Ok(y.into_bytes())
    })?;
    out.write()?;
    if a.json {
        print_json(&f)
    } else {
        stdout(text_summary(&f).as_bytes())
    }
}

fn text_summary(f: &Fit) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "{}: {} measurements, {} parameters ({})",
        f.source, f.rows, f.parameters, f.method
    );
    let _ = writeln!(
        o,
        "{:<10} {:>5} {:>9} {:>21} {:>10} {:>10} {:>12}",
        "region", "rows", "k [1/min]", "95 % CI", "rms log", "max error", "sustainable"
    );
    for r in &f.regions {
        let _ = writeln!(
            o,
            "{:<10} {:>5} {:>9.4} {:>10.4} – {:<8.4} {:>10.3} {:>9.0} % {:>6.1} %MVC",
            r.region,
            r.rows,
            r.k_per_min.value,
            r.k_per_min.low,
            r.k_per_min.high,
            r.rms_log_error,
            100.0 * r.max_relative_error,
            100.0 * r.sustainable_load
        );
    }
    if f.rest_fitted {
        let _ = writeln!(
            o,
            "recovery at rest R_rest = {:.4} /min (95 % CI {:.4} – {:.4}); recovery stops at {:.3} MVC",
            f.rest_per_min.value, f.rest_per_min.low, f.rest_per_min.high, f.limit_fmvc
        );
    } else {
        let _ = writeln!(
            o,
            "recovery at rest kept at {:.4} /min; stops at {:.3} MVC",
            f.rest_per_min.value, f.limit_fmvc
        );
    }
    if let Some(fast) = f.fast {
        if fast.fitted {
            let _ = writeln!(
                o,
                "two deficits (routed): the fast one recovers at {:.4} /min (95 % CI {:.4} – {:.4}) and takes up to {:.3} ({:.3} – {:.3}) of new fatigue above 25 %MVC; the rate above is the slow one's",
                fast.rest_per_min.value,
                fast.rest_per_min.low,
                fast.rest_per_min.high,
                fast.share_max.value,
                fast.share_max.low,
                fast.share_max.high
            );
        } else {
            let _ = writeln!(
                o,
                "two deficits (routed): the fast one recovers at {:.4} /min and takes up to {:.3} of new fatigue above 25 %MVC, both kept from the base set (no rows with rest_s and second_over_first); the rate above is the slow one's",
                fast.rest_per_min.value, fast.share_max.value
            );
        }
    }
    let _ = writeln!(
        o,
        "overall rms of ln(predicted/measured) = {:.3}; {} after {} iterations",
        f.rms_log_error,
        if f.converged {
            "converged"
        } else {
            "NOT converged"
        },
        f.iterations
    );
    o
}
