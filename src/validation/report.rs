//! Human-readable tables of the validations and of `met`.

use super::{DynamicValidation, RecoveryValidation, StaticValidation};
use crate::fatigue::MetReport;
use std::fmt::Write;

/// Table 2 reproduced: computed vs printed r and ICC, verdict and evidence per row.
pub fn static_table(v: &StaticValidation) -> String {
    let mut s = String::new();
    let g = &v.fmvc;
    let _ = writeln!(
        s,
        "Static validation (Ma et al. 2009, Table 2): MET = -ln f/(k f), k = {} /min, grid f = {:.2}..{:.2} step 0.01 ({} levels)\n",
        v.k_per_min,
        g[0],
        g[g.len() - 1],
        g.len()
    );
    let _ = writeln!(
        s,
        "{:<22} {:<9} {:>8} {:>8} {:>8} {:>8}  verdict",
        "model", "group", "r", "r pub", "ICC", "ICC pub"
    );
    for m in &v.models {
        let _ = writeln!(
            s,
            "{:<22} {:<9} {:>8.4} {:>8.4} {:>8.4} {:>8.4}  {}",
            m.id, m.group, m.r, m.published_r, m.icc, m.published_icc, m.verdict
        );
        if let Some(e) = &m.evidence {
            let _ = writeln!(
                s,
                "{:<32} with {}{}: r = {:.4}, ICC = {:.4} -> {}",
                "",
                e.equation,
                e.row
                    .as_ref()
                    .map(|r| format!(" (equation of {r})"))
                    .unwrap_or_default(),
                e.r,
                e.icc,
                if e.reproduces {
                    "reproduces the printed figures"
                } else {
                    "does not reproduce"
                }
            );
            let _ = writeln!(s, "{:<32} {}", "", e.explanation);
        }
    }
    let count = |v_: &str| v.models.iter().filter(|m| m.verdict == v_).count();
    let _ = writeln!(
        s,
        "\n{} reproduced from the printed equation (|dr|, |dICC| <= 1e-3), {} explained, {} unexplained",
        count("reproduced"),
        count("explained"),
        count("unexplained")
    );
    s
}

/// The planning model's check against endurance, intermittent and recovery data, as text.
pub fn recovery_table(v: &RecoveryValidation) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "The planning model against published data: parameter set '{}'{}\nrecovery: {}\n",
        v.parameters,
        if v.is_default {
            " (the one `plan` uses by default)"
        } else {
            ""
        },
        v.recovery
    );
    let _ = writeln!(
        s,
        "1. Sustained endurance against Frey-Law & Avin (2010) power curves: model / curve"
    );
    let _ = write!(s, "   {:<10} {:>8}", "region", "k [/min]");
    for f in &v.endurance[0].fmvc {
        let _ = write!(s, "  {:>5.0} %MVC", 100.0 * f);
    }
    let _ = writeln!(s, "  {:>18}", "sustainable load");
    for e in &v.endurance {
        let _ = write!(s, "   {:<10} {:>8.3}", e.region, e.k_per_min);
        for r in &e.model_over_curve {
            let _ = write!(s, "  {:>10.2}", r);
        }
        let _ = writeln!(s, "  {:>12.1} %MVC", 100.0 * e.sustainable_load);
    }
    let _ = writeln!(s, "\n2. Published figures");
    for (i, c) in v.checks.iter().enumerate() {
        let verdict = match (c.pass, c.band) {
            (true, Some(b)) => format!("within ±{:.0} %", 100.0 * b),
            (false, Some(b)) => format!("OUTSIDE ±{:.0} %", 100.0 * b),
            (true, None) => "holds".into(),
            (false, None) => "FAILS".into(),
        };
        let _ = writeln!(
            s,
            "   {}. {} — {}\n      {}: measured {:.4}, model {:.4}: {}",
            i + 1,
            c.source,
            c.condition,
            c.quantity,
            c.measured,
            c.model,
            verdict
        );
        if let Some(n) = &c.note {
            let _ = writeln!(s, "      ({n})");
        }
    }
    let _ = writeln!(s, "\n{} of {} checks hold", v.passed, v.total);
    s
}

/// The dynamic validations as text.
pub fn dynamic_table(v: &DynamicValidation) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Dynamic validation (Ma et al. 2009, section 4), k = {} /min\n",
        v.k_per_min
    );
    let _ = writeln!(
        s,
        "1. Liu et al. (2002) active-motor model at MVC, 0-180 s, F = {:.5} /s",
        v.liu.f_per_s
    );
    let _ = writeln!(s, "   {}", v.liu.note);
    for c in &v.liu.cases {
        let _ = writeln!(
            s,
            "   beta = {:>6}, gamma = {:>4}: max |Liu - model| = {:.5}",
            c.beta, c.gamma, c.max_abs_diff
        );
    }
    let ft = &v.freund_takala;
    let _ = writeln!(
        s,
        "\n2. Freund & Takala (2001) reservoir model (Eq. 11)\n   {}",
        ft.note
    );
    let _ = writeln!(
        s,
        "   depletion form fitted: beta = {:.4} /min; against Eq. 8 on f = 0.21..0.99: r = {:.4}, ICC = {:.4}",
        ft.beta_per_min, ft.r, ft.icc
    );
    let _ = writeln!(
        s,
        "\n3. Wexler et al. (1997): higher load, faster decline\n   {}",
        v.wexler.note
    );
    let _ = writeln!(
        s,
        "   {:>6} {:>18} {:>18}",
        "f", "dc/dt(0) [1/min]", "c = 0.5 at [min]"
    );
    for l in &v.wexler.levels {
        let _ = writeln!(
            s,
            "   {:>6.2} {:>18.3} {:>18.3}",
            l.fmvc, l.initial_slope_per_min, l.half_capacity_min
        );
    }
    let _ = writeln!(
        s,
        "   trend reproduced: {}",
        if v.wexler.trend_reproduced {
            "yes"
        } else {
            "NO"
        }
    );
    let _ = writeln!(
        s,
        "\n4. Frey-Law & Avin (2010) endurance curves ET = b0 f^b1 against Eq. 8 (f = 0.21..0.99)"
    );
    let _ = writeln!(
        s,
        "   {:<9} {:>7} {:>6} {:>8} {:>9} {:>12} {:>12} {:>14}",
        "region", "b0 [s]", "b1", "r", "ICC k=1", "fitted k", "ICC fitted", "3CC RMS [s]"
    );
    for a in &v.frey_law_avin {
        let _ = writeln!(
            s,
            "   {:<9} {:>7.2} {:>6.2} {:>8.4} {:>9.4} {:>12.3} {:>12.4} {:>14.1}",
            a.region,
            a.b0_s,
            a.b1,
            a.r,
            a.icc_k1,
            a.fitted_k_per_min,
            a.icc_fitted_k,
            a.three_compartment_rms_s
        );
    }
    let _ = writeln!(
        s,
        "   fitted k: least squares on ln MET over 20-80 %MVC; 3CC: Frey-Law et al. (2012) F, R, simulated, 10-90 %MVC"
    );
    s
}

/// `met` output as text.
pub fn met_table(r: &MetReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "k = {} /min, R = {} /min{}",
        r.k_per_min,
        r.recovery_per_min,
        if r.recovery_per_min > 0.0 {
            format!(
                "; sustainable load {:.1} %MVC (a load below it is held forever)",
                100.0 * r.sustainable_load
            )
        } else {
            String::new()
        }
    );
    for l in &r.levels {
        match l.met_min {
            Some(m) => {
                let _ = writeln!(
                    s,
                    "\nf = {:.3}: MET = {:.3} min ({:.1} s)",
                    l.fmvc,
                    m,
                    m * 60.0
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "\nf = {:.3}: held indefinitely (recovery balances the load)",
                    l.fmvc
                );
            }
        }
        let _ = writeln!(s, "  {:>10} {:>10} {:>12}", "t [s]", "capacity", "U [min]");
        for p in &l.curve {
            let _ = writeln!(
                s,
                "  {:>10.2} {:>10.4} {:>12.4}",
                p.t_s, p.capacity, p.fatigue_u_min
            );
        }
    }
    s
}
