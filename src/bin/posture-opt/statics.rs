//! `posture-opt statics`: positions, Jacobian and holding torques of any URDF at one posture.

use crate::common::{bad, print_json, stdout};
use nalgebra::Vector3;
use posture_opt::body::{BodyModel, GRAVITY_M_S2, statics_report};
use std::fmt::Write;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// URDF file.
    #[arg(long)]
    robot: PathBuf,
    /// Link or joint whose frame origin is the hand point.
    #[arg(long)]
    frame: String,
    /// Joint positions NAME=RAD[,NAME=RAD...]; joints not named are at 0.
    #[arg(long)]
    q: Option<String>,
    /// A carried load in the hand [kg] (force = mass × gravity).
    #[arg(long, conflicts_with = "hand_force")]
    hand_load_kg: Option<f64>,
    /// Force the environment applies on the hand, FX,FY,FZ [N], world frame.
    #[arg(long, allow_hyphen_values = true)]
    hand_force: Option<String>,
    /// Gravity GX,GY,GZ [m/s²] (default 0,0,-9.81).
    #[arg(long, allow_hyphen_values = true)]
    gravity: Option<String>,
    #[arg(long)]
    json: bool,
}

fn parse_vec3(opt: &str, s: &str, max: f64) -> anyhow::Result<Vector3<f64>> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(bad(format!("{opt}: expected X,Y,Z, got '{s}'")));
    }
    let mut v = [0.0; 3];
    for (i, p) in parts.iter().enumerate() {
        v[i] = p
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && x.abs() <= max)
            .ok_or_else(|| bad(format!("{opt}: '{p}' is not a number within ±{max}")))?;
    }
    Ok(Vector3::from(v))
}

fn parse_q(s: &str) -> anyhow::Result<Vec<(String, f64)>> {
    let mut out: Vec<(String, f64)> = Vec::new();
    for p in s.split(',').filter(|p| !p.trim().is_empty()) {
        let (name, val) = p
            .split_once('=')
            .ok_or_else(|| bad(format!("--q: '{p}' is not NAME=RAD")))?;
        let name = name.trim().to_string();
        let v = val
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && x.abs() <= 1e3)
            .ok_or_else(|| bad(format!("--q: {name}: '{val}' is not a number of radians")))?;
        if out.iter().any(|(n, _)| *n == name) {
            return Err(bad(format!("--q: joint '{name}' is given twice")));
        }
        out.push((name, v));
    }
    Ok(out)
}

pub fn run(a: Args) -> anyhow::Result<()> {
    let model = BodyModel::from_urdf_file_for_statics(&a.robot).map_err(|e| bad(e.to_string()))?;
    let gravity = match &a.gravity {
        Some(g) => {
            let g = parse_vec3("--gravity", g, 3.0 * 9.81)?;
            if g.norm() > 3.0 * 9.81 {
                return Err(bad("--gravity: magnitude above 3 g"));
            }
            g
        }
        None => GRAVITY_M_S2,
    };
    let force = match (a.hand_load_kg, &a.hand_force) {
        (Some(m), _) if !(m.is_finite() && (0.0..=1000.0).contains(&m)) => {
            return Err(bad(format!(
                "--hand-load-kg must be within 0..1000 kg, got {m}"
            )));
        }
        (Some(m), _) => gravity * m,
        (None, Some(f)) => parse_vec3("--hand-force", f, 1e4)?,
        (None, None) => Vector3::zeros(),
    };
    let q = a.q.as_deref().map(parse_q).transpose()?.unwrap_or_default();
    let report = statics_report(&model, &a.frame, &q, force, gravity)
        .map_err(|e| bad(format!("{}: {e}", a.robot.display())))?;
    if a.json {
        return print_json(&report);
    }
    let mut o = String::new();
    let _ = writeln!(
        o,
        "frame {} at ({:.4}, {:.4}, {:.4}) m",
        report.frame, report.position_m[0], report.position_m[1], report.position_m[2]
    );
    let _ = writeln!(
        o,
        "{:<26} {:>9} {:>12} {:>12} {:>12}",
        "joint", "q [rad]", "gravity N·m", "load N·m", "total N·m"
    );
    for j in &report.joints {
        let _ = writeln!(
            o,
            "{:<26} {:>9.4} {:>12.3} {:>12.3} {:>12.3}",
            j.name, j.q_rad, j.gravity_torque_nm, j.load_torque_nm, j.torque_nm
        );
    }
    stdout(o.as_bytes())
}
