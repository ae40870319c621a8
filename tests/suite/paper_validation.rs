//! The validations of Ma, Chablat, Bennis & Zhang (2009, Int J Ind Ergon 39:211) keep
//! reproducing: the static validation (§3, Table 2: r and ICC of Eq. 8 against 24 published MET
//! models) and the dynamic one (§4: Liu et al. 2002, Wexler et al. 1997, Freund & Takala 2001).
//!
//! Expected values are the paper's printed figures (`tests/data/fatigue/ma2009_table2.csv`,
//! transcribed from the paper) and derivations by hand; the statistics are also computed here
//! from the printed equations, independently of the library.

use posture_opt::fatigue::met_models::TABLE2;
use posture_opt::fatigue::params::ParameterSets;
use posture_opt::validation::dynamic::{frey_law_avin_curve, liu_capacity};
use posture_opt::validation::{dynamic_validation, static_validation};
use std::collections::HashMap;

/// One printed row of Table 2.
struct Printed {
    id: String,
    form: String,
    a: f64,
    b: f64,
    shift: f64,
    r: f64,
    icc: f64,
}

fn table2() -> Vec<Printed> {
    let path = format!(
        "{}/tests/data/fatigue/ma2009_table2.csv",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            let m: HashMap<&str, &str> = header.iter().copied().zip(l.split(',')).collect();
            let n = |k: &str| {
                if m[k].is_empty() {
                    0.0
                } else {
                    m[k].parse::<f64>().unwrap()
                }
            };
            Printed {
                id: m["id"].to_string(),
                form: m["form"].to_string(),
                a: n("a"),
                b: n("b"),
                shift: n("shift"),
                r: n("r"),
                icc: n("icc"),
            }
        })
        .collect()
}

impl Printed {
    /// MET \[min\] of the printed equation.
    fn met(&self, f: f64) -> f64 {
        match self.form.as_str() {
            "rohmert" => -1.5 + 2.1 / f - 0.6 / (f * f) + 0.1 / (f * f * f),
            "power" => self.a * (f - self.shift).powf(-self.b),
            "exp" => self.a * (-self.b * f).exp(),
            "huijgens" => self.a * ((1.0 - f) / (f - self.shift)).powf(-self.b),
            other => panic!("form {other}"),
        }
    }
}

/// Pearson's r, paper Eq. 9.
fn pearson(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let sab: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let saa: f64 = a.iter().map(|x| (x - ma) * (x - ma)).sum();
    let sbb: f64 = b.iter().map(|y| (y - mb) * (y - mb)).sum();
    sab / (saa * sbb).sqrt()
}

/// One-way ICC of two models, paper Eq. 10 with p = 2: MS_between over the n loads
/// (df n − 1), MS_within between the two models at each load (df n).
fn icc(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let grand = (a.iter().sum::<f64>() + b.iter().sum::<f64>()) / (2.0 * n);
    let mut ssb = 0.0;
    let mut ssw = 0.0;
    for (x, y) in a.iter().zip(b) {
        let m = (x + y) / 2.0;
        ssb += 2.0 * (m - grand) * (m - grand);
        ssw += (x - m) * (x - m) + (y - m) * (y - m);
    }
    let (msb, msw) = (ssb / (n - 1.0), ssw / n);
    (msb - msw) / (msb + msw)
}

/// The loads at which Table 2 was computed: 21–100 %MVC in 1 % steps (the paper does not say;
/// this grid is the one with which the printed figures reproduce).
fn grid() -> Vec<f64> {
    (21..=100).map(|i| i as f64 / 100.0).collect()
}

/// The rows whose printed r and ICC follow from their printed equations (18 of 24).
const REPRODUCED: [&str; 18] = [
    "rohmert-general",
    "sato-general",
    "manenica-general",
    "sjogaard",
    "rose-general",
    "mathiassen-shoulder",
    "hagberg-elbow",
    "manenica-elbow",
    "sato-elbow",
    "rose2000-elbow",
    "rose1992-elbow",
    "manenica-hand",
    "manenica-body-pull",
    "manenica-body-torque",
    "manenica-back",
    "rohmert-posture3",
    "rohmert-posture4",
    "rohmert-posture5",
];

/// Table 2 recomputed here from the printed equations and Eq. 8 (k = 1): 18 rows reproduce the
/// printed r and ICC to the printed precision (±1e−3; the posture-5 ICC is printed to 3 digits).
#[test]
fn table2_recomputed_independently() {
    let g = grid();
    let eq8: Vec<f64> = g.iter().map(|&f| -f64::ln(f) / f).collect();
    let rows = table2();
    assert_eq!(rows.len(), 24);
    for p in &rows {
        let met: Vec<f64> = g.iter().map(|&f| p.met(f)).collect();
        let (r, i) = (pearson(&met, &eq8), icc(&met, &eq8));
        let ok = (r - p.r).abs() <= 1e-3 && (i - p.icc).abs() <= 1e-3;
        assert_eq!(
            ok,
            REPRODUCED.contains(&p.id.as_str()),
            "{}: r {r:.4} ({}) ICC {i:.4} ({})",
            p.id,
            p.r,
            p.icc
        );
    }
}

/// The six that do not reproduce from the printed equation do with a documented correction
/// (recomputed here): Monod & Scherrer with 0.04167 (a decimal slip), Huijgens with the exponent
/// 1/1.4, Garg with 1.8551 (a digit slip); the two shoulder rows' figures are swapped; the
/// Rohmert elbow row carries the Rohmert shoulder row's figures.
#[test]
fn table2_deviations_explained_independently() {
    let g = grid();
    let eq8: Vec<f64> = g.iter().map(|&f| -f64::ln(f) / f).collect();
    let rows = table2();
    let row = |id: &str| rows.iter().find(|p| p.id == id).unwrap();
    let stats = |met: &dyn Fn(f64) -> f64| {
        let m: Vec<f64> = g.iter().map(|&f| met(f)).collect();
        (pearson(&m, &eq8), icc(&m, &eq8))
    };
    let check = |id: &str, (r, i): (f64, f64)| {
        let p = row(id);
        assert!(
            (r - p.r).abs() <= 1e-3 && (i - p.icc).abs() <= 1e-3,
            "{id}: r {r} ICC {i} vs {} {}",
            p.r,
            p.icc
        );
    };
    check(
        "monod-scherrer",
        stats(&|f| 0.04167 * (f - 0.14).powf(-2.4)),
    );
    check(
        "huijgens",
        stats(&|f| 0.865 * ((1.0 - f) / (f - 0.15)).powf(1.0 / 1.4)),
    );
    check("garg-shoulder", stats(&|f| 0.5618 * f.powf(-1.8551)));
    let sato = row("sato-shoulder");
    let rohmert = row("rohmert-shoulder");
    check("sato-shoulder", stats(&|f| rohmert.met(f)));
    check("rohmert-shoulder", stats(&|f| sato.met(f)));
    check("rohmert-elbow", stats(&|f| rohmert.met(f)));
}

/// The library's static validation gives the paper's printed r and ICC for the 18 reproducible
/// rows and, for the other six, evidence that reproduces them; its table holds the printed
/// coefficients and figures.
#[test]
fn library_static_validation_reproduces_the_paper() {
    let v = static_validation(1.0);
    let printed = table2();
    assert_eq!(v.fmvc, grid());
    assert_eq!(v.models.len(), 24);
    for ((m, lib), p) in v.models.iter().zip(TABLE2.iter()).zip(&printed) {
        assert_eq!(m.id, p.id);
        assert_eq!(
            (lib.published_r, lib.published_icc),
            (p.r, p.icc),
            "{}",
            p.id
        );
        if REPRODUCED.contains(&p.id.as_str()) {
            assert_eq!(m.verdict, "reproduced", "{}", p.id);
            assert!(
                (m.r - p.r).abs() <= 1e-3 && (m.icc - p.icc).abs() <= 1e-3,
                "{}: {} {}",
                p.id,
                m.r,
                m.icc
            );
            // the printed equation, evaluated
            for (&f, &met) in v.fmvc.iter().zip(&m.met_min) {
                assert!(
                    (met - p.met(f)).abs() <= 1e-12 * met.abs(),
                    "{} at {f}",
                    p.id
                );
            }
        } else {
            assert_eq!(m.verdict, "explained", "{}", p.id);
            let e = m.evidence.as_ref().unwrap();
            assert!(e.reproduces);
            assert!(
                (e.r - p.r).abs() <= 1e-3 && (e.icc - p.icc).abs() <= 1e-3,
                "{}: evidence {} {}",
                p.id,
                e.r,
                e.icc
            );
        }
    }
    // Eq. 8 itself: MET(0.5) = 2 ln 2 min at k = 1
    let i = v
        .fmvc
        .iter()
        .position(|&f| (f - 0.5).abs() < 1e-12)
        .unwrap();
    assert!((v.dynamic_met_min[i] - 2.0 * 2f64.ln()).abs() < 1e-14);
}

// ---------------------------------------------------------------------------------------------
// §4, dynamic validation.
// ---------------------------------------------------------------------------------------------

/// Liu, Brown & Yue (2002) Eq. 12 integrated numerically here (RK4, 1 ms) against Eq. 13 + 14,
/// for a general β, γ.
#[test]
fn liu_eq13_14_solve_eq12() {
    let (f, b, r) = (0.02, 0.5, 0.004); // 1/s
    let (beta, gamma) = (b / f, r / f);
    let (mut ma, mut mf, mut muc) = (0.0f64, 0.0f64, 1.0f64);
    let h = 1e-3;
    let d = |ma: f64, mf: f64, muc: f64| (b * muc - f * ma + r * mf, f * ma - r * mf, -b * muc);
    for i in 1..=120_000 {
        let k1 = d(ma, mf, muc);
        let k2 = d(
            ma + h / 2.0 * k1.0,
            mf + h / 2.0 * k1.1,
            muc + h / 2.0 * k1.2,
        );
        let k3 = d(
            ma + h / 2.0 * k2.0,
            mf + h / 2.0 * k2.1,
            muc + h / 2.0 * k2.2,
        );
        let k4 = d(ma + h * k3.0, mf + h * k3.1, muc + h * k3.2);
        ma += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        mf += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        muc += h / 6.0 * (k1.2 + 2.0 * k2.2 + 2.0 * k3.2 + k4.2);
        if i % 10_000 == 0 {
            let t = i as f64 * h;
            assert!(
                (ma + muc - liu_capacity(t, f, beta, gamma)).abs() < 1e-9,
                "t = {t}"
            );
        }
    }
    // the sum starts at M_A + M_uc = M0 (the sign of Eq. 15's last term as printed would not)
    assert!((liu_capacity(0.0, f, beta, gamma) - 1.0).abs() < 1e-15);
}

/// Eq. 15's limit (γ = 0, β → ∞) is the model at MVC, `e^{−Ft}`; by hand, with γ = 0 the sum is
/// `(β e^{−Ft} − e^{−βFt})/(β − 1)`, so its distance to `e^{−Ft}` is at most `1/(β − 1)`.
#[test]
fn liu_limit_is_the_model_at_mvc() {
    let v = dynamic_validation(1.0);
    assert!((v.liu.f_per_s - 1.0 / 60.0).abs() < 1e-15);
    for (t, c) in v.liu.t_s.iter().zip(&v.liu.model_capacity) {
        assert!((c - (-t / 60.0f64).exp()).abs() < 1e-14);
    }
    let mut last = f64::INFINITY;
    for case in v.liu.cases.iter().filter(|c| c.gamma == 0.0) {
        assert!(
            case.max_abs_diff <= 1.0 / (case.beta - 1.0),
            "β = {}: {}",
            case.beta,
            case.max_abs_diff
        );
        assert!(case.max_abs_diff < last / 5.0);
        last = case.max_abs_diff;
    }
    assert!(last < 2e-3);
    for t in [1.0, 30.0, 120.0] {
        assert!((liu_capacity(t, 0.02, 1e7, 0.0) - (-0.02 * t).exp()).abs() < 1e-6);
    }
}

/// Wexler et al. (1997), qualitatively: the larger the load, the faster the decline. By hand the
/// model's initial slope is −k f and capacity halves after ln 2/(k f).
#[test]
fn wexler_trend() {
    let v = dynamic_validation(1.0);
    assert!(v.wexler.trend_reproduced);
    for l in &v.wexler.levels {
        assert!((l.initial_slope_per_min + l.fmvc).abs() < 1e-15);
        assert!(
            (l.half_capacity_min - 2f64.ln() / l.fmvc).abs() < 1e-12,
            "{}",
            l.fmvc
        );
    }
}

/// Freund & Takala (2001), Eq. 11 as printed: with one rate β for recovery and depletion and
/// S = f S1 held, capacity settles at (1 − f) S1 and reaches the load only if f > 0.5; the
/// depletion form's endurance `(1 − f)/(β f)` fitted to Eq. 8 correlates closely.
#[test]
fn freund_takala() {
    let v = dynamic_validation(1.0);
    assert_eq!(v.freund_takala.printed_form_min_exhausting_fmvc, 0.5);
    let ft = &v.freund_takala;
    for (f, met) in ft.fmvc.iter().zip(&ft.met_min) {
        assert!((met - (1.0 - f) / (ft.beta_per_min * f)).abs() < 1e-12);
    }
    // β by hand: the log-space least squares fit of (1 − f)/(β f) to −ln f/f
    let n = ft.fmvc.len() as f64;
    let ln_beta = ft
        .fmvc
        .iter()
        .map(|&f| ((1.0 - f) / f).ln() - (-f.ln() / f).ln())
        .sum::<f64>()
        / n;
    assert!((ft.beta_per_min - ln_beta.exp()).abs() < 1e-12);
    assert!(ft.r > 0.99, "{}", ft.r);
}

/// Frey-Law & Avin (2010): the validation's curves are the published Table 2 coefficients, and the
/// k it fits to each (Eq. 8, log space, 20–80 %MVC in 1 % steps) is within 3 % of the shipped
/// set's (the same fit on a 5 % grid). k = 1 is optimistic for the shoulder and pessimistic for
/// the ankle (fitted 1.40 and 0.50).
#[test]
fn frey_law_avin_fitted_k() {
    let v = dynamic_validation(1.0);
    let sets = ParameterSets::shipped();
    let set = sets.get("frey-law-avin-2010").unwrap();
    let published = [
        ("general", 21.92, -1.98),
        ("ankle", 34.71, -2.06),
        ("trunk", 22.69, -2.27),
        ("elbow", 17.98, -2.21),
        ("grip", 33.55, -1.61),
        ("knee", 19.38, -1.88),
        ("shoulder", 14.86, -1.83),
    ];
    assert_eq!(v.frey_law_avin.len(), published.len());
    for (region, b0, b1) in published {
        let a = v.frey_law_avin.iter().find(|a| a.region == region).unwrap();
        assert_eq!((a.b0_s, a.b1), (b0, b1), "{region}");
        let r = posture_opt::fatigue::Region::ALL
            .iter()
            .find(|r| r.name() == region)
            .unwrap();
        assert_eq!(frey_law_avin_curve(*r), Some((b0, b1)));
        let k_set = set.regions[region].k;
        assert!(
            (a.fitted_k_per_min / k_set - 1.0).abs() < 0.03,
            "{region}: {} vs {k_set}",
            a.fitted_k_per_min
        );
    }
    let k = |g: &str| {
        v.frey_law_avin
            .iter()
            .find(|a| a.region == g)
            .unwrap()
            .fitted_k_per_min
    };
    assert!(k("shoulder") > 1.3 && k("ankle") < 0.6);
}
