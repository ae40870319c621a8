//! `posture-opt met`: maximum endurance time and the curve of a held load.

use crate::common::{bad, lib_err, print_json, stdout};
use posture_opt::fatigue::{FatigueError, MaParams, Recovery};

#[derive(clap::Args)]
pub struct Args {
    /// Relative load f = F_load/MVC in (0, 1], or a range START:END:STEP.
    #[arg(long)]
    fmvc: String,
    /// Fatigue rate k [1/min].
    #[arg(long, default_value_t = 1.0)]
    k_per_min: f64,
    /// A constant recovery rate R [1/min] acting under load as at rest (0 = the paper's model).
    #[arg(long, default_value_t = 0.0, conflicts_with_all = ["rest_per_min", "limit_fmvc"])]
    r_per_min: f64,
    /// Perfusion-limited recovery: the rate at rest [1/min] ...
    #[arg(long, requires = "limit_fmvc")]
    rest_per_min: Option<f64>,
    /// ... and the load (fraction of MVC) from which recovery stops.
    #[arg(long, requires = "rest_per_min")]
    limit_fmvc: Option<f64>,
    /// Samples of the curve between 0 and the endurance time.
    #[arg(long, default_value_t = 10)]
    points: usize,
    #[arg(long)]
    json: bool,
}

/// Smallest relative load `met` answers for.
const MIN_FMVC: f64 = 1e-6;

/// Most curve points `met` writes in one run (levels × points).
const MAX_CURVE_POINTS: usize = 1_000_000;

fn parse_fmvc(s: &str) -> anyhow::Result<Vec<f64>> {
    let num = |t: &str| -> anyhow::Result<f64> {
        t.trim()
            .parse::<f64>()
            .map_err(|_| bad(format!("--fmvc: '{t}' is not a number")))
    };
    let values = match s.split(':').collect::<Vec<_>>().as_slice() {
        [one] => vec![num(one)?],
        [a, b, c] => {
            let (a, b, c) = (num(a)?, num(b)?, num(c)?);
            if !(c.is_finite() && c > 0.0 && a.is_finite() && b.is_finite()) || b < a {
                return Err(bad(format!(
                    "--fmvc: range '{s}' needs START <= END and STEP > 0"
                )));
            }
            let n = ((b - a) / c + 1e-9).floor();
            if n > 10_000.0 {
                return Err(bad(format!(
                    "--fmvc: range '{s}' has more than 10000 levels"
                )));
            }
            (0..=n as usize).map(|i| a + c * i as f64).collect()
        }
        _ => {
            return Err(bad(format!(
                "--fmvc: '{s}' is neither a number nor START:END:STEP"
            )));
        }
    };
    for &f in &values {
        // below 1e-6 of MVC the MET of Eq. 8 exceeds what a double holds in minutes
        if f.is_finite() && f > 0.0 && f < MIN_FMVC {
            return Err(bad(format!(
                "--fmvc: {f:e} is below the smallest load handled, {MIN_FMVC:e} (a millionth of MVC)"
            )));
        }
        if !(f.is_finite() && f > 0.0 && f <= 1.0) {
            return Err(lib_err(FatigueError::BadLoad {
                what: "--fmvc",
                value: f,
            }));
        }
    }
    Ok(values)
}

pub fn run(a: Args) -> anyhow::Result<()> {
    let recovery = match (a.rest_per_min, a.limit_fmvc) {
        (Some(rest_per_min), Some(limit_fmvc)) => Recovery::Perfusion {
            rest_per_min,
            limit_fmvc,
        },
        _ if a.r_per_min == 0.0 => Recovery::None,
        _ => Recovery::Constant {
            r_per_min: a.r_per_min,
        },
    };
    let p = MaParams::with_recovery(a.k_per_min, recovery).map_err(lib_err)?;
    if a.points == 0 || a.points > 100_000 {
        return Err(bad("--points must be between 1 and 100000"));
    }
    let levels = parse_fmvc(&a.fmvc)?;
    if levels.len().saturating_mul(a.points) > MAX_CURVE_POINTS {
        return Err(bad(format!(
            "--fmvc and --points: {} levels × {} points is more than {MAX_CURVE_POINTS} curve points; use fewer levels or points",
            levels.len(),
            a.points
        )));
    }
    let report = posture_opt::fatigue::met_report(&p, &levels, a.points);
    if a.json {
        print_json(&report)
    } else {
        stdout(posture_opt::validation::report::met_table(&report).as_bytes())
    }
}
