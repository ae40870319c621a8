//! L5/S1 compression and shear from a single-equivalent-muscle (SEM) low-back model.
//!
//! Model (Chaffin DB, Andersson GBJ, Martin BJ, *Occupational Biomechanics*, 4th ed., Wiley
//! 2006, low-back biomechanics chapter; the "simple static sagittal-plane low-back model" that
//! 3DSSPP also reports): the back extensors (erector spinae) are lumped into one muscle whose
//! force acts parallel to the spine at a moment arm E ≈ 5 cm behind the L5/S1 joint centre.
//! That muscle alone balances the sagittal flexion moment of the loads above L5/S1:
//!
//! ```text
//! s = spine axis (up the spine at L5/S1), f = anterior axis, l = s × f (to the left)
//! M_sag = M · l            flexion moment of the loads (> 0: the trunk would bend forward)
//! F_muscle = M_sag / E     extensor force            (M_sag ≥ 0)
//!          = −M_sag / A    flexor (abdominal) force  (M_sag < 0; A = flexor moment arm)
//! compression  = F_muscle − F · s        (> 0 presses the upper body onto the lower)
//! shear_ap     = F · f                   (> 0: upper body pushed anteriorly)
//! shear_lat    = F · l                   (> 0: upper body pushed to the left)
//! ```
//!
//! where `M` and `F` are the resultant moment (about the L5/S1 joint centre) and force of
//! every external load on the body above L5/S1 — segment weights, hand loads and, for a
//! dynamic analysis, the d'Alembert inertial forces. Assumptions, as in the source:
//! * the equivalent muscle pulls parallel to the spine, so it adds to compression and not to
//!   shear (a real, oblique erector spinae reduces anterior shear, so the shear is
//!   conservative);
//! * the lateral-bending moment `M · f` and the twisting moment `M · s` are **not** balanced by
//!   the sagittal SEM; they are reported (`lateral_moment_nm`, `axial_moment_nm`) and add
//!   nothing to compression, which underestimates compression for asymmetric tasks;
//! * intra-abdominal pressure is ignored (Chaffin's optional abdominal-pressure term would
//!   reduce compression; leaving it out is conservative);
//! * no co-contraction of antagonists, no passive tissue (ligament) moment;
//! * an extension load moment (load behind the spine, pulling backwards) is balanced by an
//!   equivalent flexor at [`BackParams::flexor_moment_arm_m`]; that value is an assumption of
//!   this module, not part of Chaffin's SEM.
//!
//! The tool must supply the orientation of the spine at L5/S1 (the normal of the L5/S1 disc
//! plane, pointing up the spine, and the anterior direction in that plane), e.g. from the
//! pelvis/trunk posture of its body model; the world frame is x forward, y left, z up.
//!
//! Limits (reported, not enforced): compression action limit 3400 N and maximum permissible
//! limit 6400 N (NIOSH, *Work Practices Guide for Manual Lifting*, DHHS (NIOSH) Pub. 81-122,
//! 1981; Waters et al. 1993 use 3.4 kN as the biomechanical criterion of the revised
//! equation); shear limit 1000 N for occasional loading, i.e. up to about 100 loadings a day
//! (Gallagher S, Marras WS, 2012, "Tolerance of the lumbar spine to shear: a review and
//! recommended exposure limits", *Clinical Biomechanics* 27(10):973–978, who recommend 700 N
//! for 100–1000 loadings a day).

use serde::{Deserialize, Serialize};

/// Largest accepted deviation of an axis from unit length, and of the two axes' dot product
/// from 0 (about 0.06°). Axes within it are re-orthonormalised before use.
pub const AXIS_TOLERANCE: f64 = 1e-3;

/// Largest accepted magnitude of a force \[N\] or moment \[N·m\] component: far beyond any
/// load a body can bear, it only keeps the arithmetic from overflowing.
pub const MAX_LOAD_COMPONENT: f64 = 1e7;

/// Errors for inputs the back model cannot evaluate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LowBackError {
    /// A number is NaN or infinite.
    #[error("{field} must be a finite number, got {value}")]
    NotFinite {
        /// Input field, e.g. `load.moment_nm[1]`.
        field: String,
        /// The value given.
        value: f64,
    },
    /// A force or moment component beyond [`MAX_LOAD_COMPONENT`].
    #[error("{field} must be at most {max} in magnitude, got {value}")]
    TooLarge {
        /// Input field, e.g. `load.force_n[2]`.
        field: String,
        /// The value given.
        value: f64,
        /// The accepted magnitude.
        max: f64,
    },
    /// An axis is not a unit vector.
    #[error("{field} must be a unit vector (length 1 ± {tolerance}), got length {norm}")]
    NotUnit {
        /// `load.spine_axis` or `load.forward_axis`.
        field: &'static str,
        /// Its length.
        norm: f64,
        /// The accepted deviation.
        tolerance: f64,
    },
    /// The anterior axis is not perpendicular to the spine axis.
    #[error(
        "load.forward_axis must be perpendicular to load.spine_axis (|dot product| ≤ \
         {tolerance}), got dot product {dot}"
    )]
    NotPerpendicular {
        /// Dot product of the two axes.
        dot: f64,
        /// The accepted deviation.
        tolerance: f64,
    },
    /// A moment arm outside (0, 0.3] m.
    #[error(
        "{field} must be more than 0 and at most 0.3 m (a trunk-muscle moment arm at L5/S1), \
         got {value}"
    )]
    MomentArmOutOfRange {
        /// `params.erector_moment_arm_m` or `params.flexor_moment_arm_m`.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// A limit that is not a positive finite force.
    #[error("{field} must be a finite force above 0 N, got {value}")]
    LimitNotPositive {
        /// The limit's field.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// The action limit exceeds the maximum permissible limit.
    #[error(
        "params.compression_action_limit_n ({action_n} N) must not exceed \
         params.compression_max_limit_n ({max_n} N)"
    )]
    LimitsOutOfOrder {
        /// Action limit given \[N\].
        action_n: f64,
        /// Maximum permissible limit given \[N\].
        max_n: f64,
    },
}

/// The loads on the body above L5/S1 and the orientation of the spine there, in the world
/// frame (x forward, y left, z up).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LumbarLoad {
    /// Resultant moment about the L5/S1 joint centre of all external loads on the body above
    /// L5/S1 (segment weights, hand loads, inertial forces), Σ r × F \[N·m\].
    pub moment_nm: [f64; 3],
    /// Resultant of the same loads, ΣF: the force the upper body transmits to L5/S1 \[N\]
    /// (upright and still: (0, 0, −weight above L5/S1 − hand loads)).
    pub force_n: [f64; 3],
    /// Unit vector along the spine at L5/S1, pointing up (normal of the L5/S1 disc plane).
    pub spine_axis: [f64; 3],
    /// Unit vector perpendicular to `spine_axis`, pointing anteriorly (forward).
    pub forward_axis: [f64; 3],
}

/// Model parameters and the limits the result is compared with.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BackParams {
    /// Moment arm E of the equivalent extensor about L5/S1 \[m\]; Chaffin et al.: ≈ 0.05 m.
    pub erector_moment_arm_m: f64,
    /// Moment arm of the equivalent flexor (abdominal muscles) \[m\], used only when the load
    /// moment is an extension moment. Default 0.08 m: an assumption of this module (of the
    /// order of the rectus abdominis moment arm at L5/S1), not a value of Chaffin's SEM.
    pub flexor_moment_arm_m: f64,
    /// Compression action limit \[N\]; NIOSH (1981): 3400 N.
    pub compression_action_limit_n: f64,
    /// Compression maximum permissible limit \[N\]; NIOSH (1981): 6400 N.
    pub compression_max_limit_n: f64,
    /// Shear limit \[N\]; Gallagher & Marras (2012): 1000 N for up to ~100 loadings a day
    /// (700 N for 100–1000 a day).
    pub shear_limit_n: f64,
}

impl Default for BackParams {
    /// E = 0.05 m, flexor arm 0.08 m, 3400 N / 6400 N compression, 1000 N shear.
    fn default() -> Self {
        BackParams {
            erector_moment_arm_m: 0.05,
            flexor_moment_arm_m: 0.08,
            compression_action_limit_n: 3400.0,
            compression_max_limit_n: 6400.0,
            shear_limit_n: 1000.0,
        }
    }
}

/// Which equivalent muscle balances the sagittal moment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum BalancingMuscle {
    /// No sagittal moment to balance.
    None,
    /// Flexion moment: the back extensors (erector spinae).
    Extensors,
    /// Extension moment: the trunk flexors (abdominal muscles).
    Flexors,
}

/// Compression compared with the NIOSH (1981) limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum CompressionVerdict {
    /// At or below the action limit (3400 N).
    WithinActionLimit,
    /// Above the action limit, at or below the maximum permissible limit (6400 N).
    AboveActionLimit,
    /// Above the maximum permissible limit.
    AboveMaximumPermissibleLimit,
}

/// Resultant shear compared with the shear limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ShearVerdict {
    /// At or below the limit.
    WithinLimit,
    /// Above the limit.
    AboveLimit,
}

/// L5/S1 loads and every intermediate value of the SEM model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LowBack {
    /// Compression along the spine axis \[N\] (> 0 compresses; < 0 would be traction).
    pub compression_n: f64,
    /// Part of the compression due to the equivalent muscle \[N\].
    pub muscle_compression_n: f64,
    /// Part of the compression due to the loads, −F·s \[N\].
    pub load_compression_n: f64,
    /// Anterior–posterior shear F·f \[N\] (> 0: upper body pushed anteriorly).
    pub shear_ap_n: f64,
    /// Lateral shear F·l \[N\] (> 0: upper body pushed to the left).
    pub shear_lateral_n: f64,
    /// Resultant shear √(shear_ap² + shear_lateral²) \[N\], compared with the shear limit.
    pub shear_resultant_n: f64,
    /// Extensor (erector spinae) force \[N\].
    pub extensor_force_n: f64,
    /// Flexor (abdominal) force \[N\].
    pub flexor_force_n: f64,
    /// Which muscle balances the sagittal moment.
    pub balancing_muscle: BalancingMuscle,
    /// Sagittal moment M·l \[N·m\] (> 0: flexion, balanced by the extensors).
    pub sagittal_moment_nm: f64,
    /// Lateral-bending moment M·f \[N·m\] (> 0: bends the trunk to the right); not balanced
    /// by the model.
    pub lateral_moment_nm: f64,
    /// Twisting moment M·s \[N·m\] (> 0: turns the trunk to the left); not balanced by the
    /// model.
    pub axial_moment_nm: f64,
    /// Spine axis used (normalised) \[world frame\].
    pub spine_axis: [f64; 3],
    /// Anterior axis used (orthonormalised) \[world frame\].
    pub forward_axis: [f64; 3],
    /// Left axis l = s × f \[world frame\].
    pub lateral_axis: [f64; 3],
    /// Compression against the action and maximum permissible limits.
    pub compression_verdict: CompressionVerdict,
    /// Resultant shear against the shear limit.
    pub shear_verdict: ShearVerdict,
    /// The parameters and limits used.
    pub params: BackParams,
}

/// L5/S1 compression and shear for `load` with the single-equivalent-muscle model (module
/// documentation).
pub fn low_back(load: &LumbarLoad, params: &BackParams) -> Result<LowBack, LowBackError> {
    validate_params(params)?;
    for (name, v) in [
        ("load.moment_nm", load.moment_nm),
        ("load.force_n", load.force_n),
        ("load.spine_axis", load.spine_axis),
        ("load.forward_axis", load.forward_axis),
    ] {
        for (i, x) in v.iter().enumerate() {
            if !x.is_finite() {
                return Err(LowBackError::NotFinite {
                    field: format!("{name}[{i}]"),
                    value: *x,
                });
            }
            if x.abs() > MAX_LOAD_COMPONENT {
                return Err(LowBackError::TooLarge {
                    field: format!("{name}[{i}]"),
                    value: *x,
                    max: MAX_LOAD_COMPONENT,
                });
            }
        }
    }
    let s = unit(load.spine_axis, "load.spine_axis")?;
    let f_raw = unit(load.forward_axis, "load.forward_axis")?;
    let dot_sf = dot(s, f_raw);
    if dot_sf.abs() > AXIS_TOLERANCE {
        return Err(LowBackError::NotPerpendicular {
            dot: dot_sf,
            tolerance: AXIS_TOLERANCE,
        });
    }
    // Remove the small non-orthogonal part, then normalise (its length is ≥ 0.999).
    let f_perp = sub(f_raw, scale(s, dot_sf));
    let f = scale(f_perp, 1.0 / norm(f_perp));
    let l = cross(s, f);

    let sagittal = dot(load.moment_nm, l);
    let lateral = dot(load.moment_nm, f);
    let axial = dot(load.moment_nm, s);
    let (extensor, flexor, muscle) = if sagittal > 0.0 {
        (
            sagittal / params.erector_moment_arm_m,
            0.0,
            BalancingMuscle::Extensors,
        )
    } else if sagittal < 0.0 {
        (
            0.0,
            -sagittal / params.flexor_moment_arm_m,
            BalancingMuscle::Flexors,
        )
    } else {
        (0.0, 0.0, BalancingMuscle::None)
    };
    let muscle_compression = extensor + flexor;
    let load_compression = -dot(load.force_n, s);
    let compression = muscle_compression + load_compression;
    let shear_ap = dot(load.force_n, f);
    let shear_lat = dot(load.force_n, l);
    let shear = shear_ap.hypot(shear_lat);

    let compression_verdict = if compression > params.compression_max_limit_n {
        CompressionVerdict::AboveMaximumPermissibleLimit
    } else if compression > params.compression_action_limit_n {
        CompressionVerdict::AboveActionLimit
    } else {
        CompressionVerdict::WithinActionLimit
    };
    let shear_verdict = if shear > params.shear_limit_n {
        ShearVerdict::AboveLimit
    } else {
        ShearVerdict::WithinLimit
    };

    Ok(LowBack {
        compression_n: compression,
        muscle_compression_n: muscle_compression,
        load_compression_n: load_compression,
        shear_ap_n: shear_ap,
        shear_lateral_n: shear_lat,
        shear_resultant_n: shear,
        extensor_force_n: extensor,
        flexor_force_n: flexor,
        balancing_muscle: muscle,
        sagittal_moment_nm: sagittal,
        lateral_moment_nm: lateral,
        axial_moment_nm: axial,
        spine_axis: s,
        forward_axis: f,
        lateral_axis: l,
        compression_verdict,
        shear_verdict,
        params: *params,
    })
}

fn validate_params(p: &BackParams) -> Result<(), LowBackError> {
    for (field, value) in [
        ("params.erector_moment_arm_m", p.erector_moment_arm_m),
        ("params.flexor_moment_arm_m", p.flexor_moment_arm_m),
    ] {
        // `!(value > 0.0)` also refuses NaN.
        if !(value > 0.0 && value <= 0.3) {
            return Err(LowBackError::MomentArmOutOfRange { field, value });
        }
    }
    for (field, value) in [
        (
            "params.compression_action_limit_n",
            p.compression_action_limit_n,
        ),
        ("params.compression_max_limit_n", p.compression_max_limit_n),
        ("params.shear_limit_n", p.shear_limit_n),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(LowBackError::LimitNotPositive { field, value });
        }
    }
    if p.compression_action_limit_n > p.compression_max_limit_n {
        return Err(LowBackError::LimitsOutOfOrder {
            action_n: p.compression_action_limit_n,
            max_n: p.compression_max_limit_n,
        });
    }
    Ok(())
}

/// `v` normalised, if its length is within [`AXIS_TOLERANCE`] of 1.
fn unit(v: [f64; 3], field: &'static str) -> Result<[f64; 3], LowBackError> {
    let n = norm(v);
    if (n - 1.0).abs() > AXIS_TOLERANCE {
        return Err(LowBackError::NotUnit {
            field,
            norm: n,
            tolerance: AXIS_TOLERANCE,
        });
    }
    Ok(scale(v, 1.0 / n))
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn scale(a: [f64; 3], k: f64) -> [f64; 3] {
    [a[0] * k, a[1] * k, a[2] * k]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    const G: f64 = 9.81;

    /// Moment about L5/S1 and force of a mass `m_kg` whose centre is at `r_m` from L5/S1
    /// (world frame x forward, y left, z up): F = (0, 0, −m·g), M = r × F.
    fn weight_at(r_m: [f64; 3], m_kg: f64) -> ([f64; 3], [f64; 3]) {
        let f = [0.0, 0.0, -m_kg * G];
        (cross(r_m, f), f)
    }

    fn sum(parts: &[([f64; 3], [f64; 3])]) -> ([f64; 3], [f64; 3]) {
        parts.iter().fold(([0.0; 3], [0.0; 3]), |(m, f), (mi, fi)| {
            (
                [m[0] + mi[0], m[1] + mi[1], m[2] + mi[2]],
                [f[0] + fi[0], f[1] + fi[1], f[2] + fi[2]],
            )
        })
    }

    fn upright(moment_nm: [f64; 3], force_n: [f64; 3]) -> LumbarLoad {
        LumbarLoad {
            moment_nm,
            force_n,
            spine_axis: [0.0, 0.0, 1.0],
            forward_axis: [1.0, 0.0, 0.0],
        }
    }

    /// Upright trunk, 10 kg held 0.40 m in front of L5/S1, upper body 45 kg with its centre of
    /// mass 0.02 m in front of L5/S1 (0.30 m above it; the height does not matter).
    /// By hand: M_sag = 10·9.81·0.40 + 45·9.81·0.02 = 39.24 + 8.829 = 48.069 N·m;
    /// extensor = 48.069 / 0.05 = 961.38 N; load compression = 55·9.81 = 539.55 N;
    /// compression = 961.38 + 539.55 = 1500.93 N; shear 0 (the spine is vertical).
    #[test]
    fn upright_holding_10_kg_at_40_cm() {
        let (m, f) = sum(&[
            weight_at([0.40, 0.0, 0.25], 10.0),
            weight_at([0.02, 0.0, 0.30], 45.0),
        ]);
        let r = low_back(&upright(m, f), &BackParams::default()).unwrap();
        assert_abs_diff_eq!(r.sagittal_moment_nm, 48.069, epsilon = 1e-9);
        assert_abs_diff_eq!(r.extensor_force_n, 961.38, epsilon = 1e-9);
        assert_abs_diff_eq!(r.load_compression_n, 539.55, epsilon = 1e-9);
        assert_abs_diff_eq!(r.compression_n, 1500.93, epsilon = 1e-9);
        assert_abs_diff_eq!(r.shear_ap_n, 0.0, epsilon = 1e-9);
        assert_abs_diff_eq!(r.shear_lateral_n, 0.0, epsilon = 1e-9);
        assert_eq!(r.balancing_muscle, BalancingMuscle::Extensors);
        assert_eq!(r.flexor_force_n, 0.0);
        assert_eq!(r.compression_verdict, CompressionVerdict::WithinActionLimit);
        assert_eq!(r.shear_verdict, ShearVerdict::WithinLimit);
    }

    /// 45° stoop: spine axis s = (sin 45°, 0, cos 45°), anterior axis f = (cos 45°, 0,
    /// −sin 45°). Upper body 45 kg with its centre 0.25 m up the spine, i.e. 0.25·sin 45° =
    /// 0.176777 m in front of L5/S1; 10 kg held 0.50 m in front of L5/S1.
    /// By hand: M_sag = 45·9.81·0.176777 + 10·9.81·0.50 = 78.0381 + 49.05 = 127.0881 N·m;
    /// extensor = 127.0881 / 0.05 = 2541.761 N; W = 55·9.81 = 539.55 N;
    /// load compression = W·cos 45° = 381.519 N; compression = 2923.281 N;
    /// anterior shear = W·sin 45° = 381.519 N.
    #[test]
    fn stoop_45_degrees() {
        let (sn, cs) = (45f64.to_radians().sin(), 45f64.to_radians().cos());
        let (m, f) = sum(&[
            weight_at([0.25 * sn, 0.0, 0.25 * cs], 45.0),
            weight_at([0.50, 0.0, 0.10], 10.0),
        ]);
        let load = LumbarLoad {
            moment_nm: m,
            force_n: f,
            spine_axis: [sn, 0.0, cs],
            forward_axis: [cs, 0.0, -sn],
        };
        let r = low_back(&load, &BackParams::default()).unwrap();
        assert_abs_diff_eq!(r.sagittal_moment_nm, 127.0881, epsilon = 1e-4);
        assert_abs_diff_eq!(r.extensor_force_n, 2541.761, epsilon = 1e-3);
        assert_abs_diff_eq!(r.load_compression_n, 381.519, epsilon = 1e-3);
        assert_abs_diff_eq!(r.compression_n, 2923.281, epsilon = 1e-3);
        assert_abs_diff_eq!(r.shear_ap_n, 381.519, epsilon = 1e-3);
        assert_abs_diff_eq!(r.shear_lateral_n, 0.0, epsilon = 1e-9);
        assert_abs_diff_eq!(r.lateral_axis[1], 1.0, epsilon = 1e-12);
    }

    /// The same stoop seen by a worker facing +y: every world vector is turned 90° about z
    /// ((x, y, z) → (−y, x, z)). The results must not change.
    #[test]
    fn results_do_not_depend_on_the_facing_direction() {
        let turn = |v: [f64; 3]| [-v[1], v[0], v[2]];
        let (sn, cs) = (45f64.to_radians().sin(), 45f64.to_radians().cos());
        let (m, f) = sum(&[
            weight_at([0.25 * sn, 0.0, 0.25 * cs], 45.0),
            weight_at([0.50, 0.03, 0.10], 10.0),
        ]);
        let a = LumbarLoad {
            moment_nm: m,
            force_n: [f[0] + 20.0, f[1] - 15.0, f[2]],
            spine_axis: [sn, 0.0, cs],
            forward_axis: [cs, 0.0, -sn],
        };
        let b = LumbarLoad {
            moment_nm: turn(a.moment_nm),
            force_n: turn(a.force_n),
            spine_axis: turn(a.spine_axis),
            forward_axis: turn(a.forward_axis),
        };
        let p = BackParams::default();
        let (ra, rb) = (low_back(&a, &p).unwrap(), low_back(&b, &p).unwrap());
        assert_abs_diff_eq!(ra.compression_n, rb.compression_n, epsilon = 1e-9);
        assert_abs_diff_eq!(ra.shear_ap_n, rb.shear_ap_n, epsilon = 1e-9);
        assert_abs_diff_eq!(ra.shear_lateral_n, rb.shear_lateral_n, epsilon = 1e-9);
        assert_abs_diff_eq!(ra.lateral_moment_nm, rb.lateral_moment_nm, epsilon = 1e-9);
        assert_abs_diff_eq!(ra.axial_moment_nm, rb.axial_moment_nm, epsilon = 1e-9);
    }

    /// Pure compression: 500 N straight down the vertical spine, no moment.
    /// By hand: compression = 500 N, no muscle force, no shear.
    #[test]
    fn pure_compression_is_the_weight() {
        let r = low_back(
            &upright([0.0; 3], [0.0, 0.0, -500.0]),
            &BackParams::default(),
        )
        .unwrap();
        assert_eq!(r.compression_n, 500.0);
        assert_eq!(r.muscle_compression_n, 0.0);
        assert_eq!(r.shear_resultant_n, 0.0);
        assert_eq!(r.balancing_muscle, BalancingMuscle::None);
    }

    /// 10 kg in the right hand, 0.20 m to the right of L5/S1 (y = −0.20 m), upright, upper body
    /// 45 kg centred over L5/S1. By hand: M = r × F = (−0.20·(−98.1), 0, 0) = (19.62, 0, 0)
    /// N·m: a lateral-bending moment of +19.62 N·m (to the right), no sagittal moment, so no
    /// muscle force in the SEM; compression = (45 + 10)·9.81 = 539.55 N; the lateral moment is
    /// reported but not balanced.
    #[test]
    fn lateral_moment_is_reported_not_balanced() {
        let (m, f) = sum(&[
            weight_at([0.0, -0.20, 0.0], 10.0),
            weight_at([0.0, 0.0, 0.30], 45.0),
        ]);
        let r = low_back(&upright(m, f), &BackParams::default()).unwrap();
        assert_abs_diff_eq!(r.lateral_moment_nm, 19.62, epsilon = 1e-9);
        assert_abs_diff_eq!(r.sagittal_moment_nm, 0.0, epsilon = 1e-12);
        assert_eq!(r.extensor_force_n, 0.0);
        assert_abs_diff_eq!(r.compression_n, 539.55, epsilon = 1e-9);
        assert_abs_diff_eq!(r.axial_moment_nm, 0.0, epsilon = 1e-12);
    }

    /// Pushing sideways: upright, the hands push a load so that the upper body receives 50 N
    /// to the left (+y) on top of its 45 kg weight. By hand: lateral shear = +50 N,
    /// AP shear 0, resultant shear 50 N, compression = 441.45 N.
    #[test]
    fn lateral_force_gives_lateral_shear() {
        let r = low_back(
            &upright([0.0; 3], [0.0, 50.0, -45.0 * G]),
            &BackParams::default(),
        )
        .unwrap();
        assert_abs_diff_eq!(r.shear_lateral_n, 50.0, epsilon = 1e-12);
        assert_abs_diff_eq!(r.shear_ap_n, 0.0, epsilon = 1e-12);
        assert_abs_diff_eq!(r.shear_resultant_n, 50.0, epsilon = 1e-12);
        assert_abs_diff_eq!(r.compression_n, 441.45, epsilon = 1e-9);
    }

    /// Extension moment: 5 kg hanging 0.20 m behind L5/S1, upper body 45 kg centred over it.
    /// By hand: M_sag = −5·9.81·0.20 = −9.81 N·m; flexor = 9.81 / 0.08 = 122.625 N;
    /// compression = 122.625 + 50·9.81 = 613.125 N.
    #[test]
    fn extension_moment_uses_the_flexors() {
        let (m, f) = sum(&[
            weight_at([-0.20, 0.0, 0.0], 5.0),
            weight_at([0.0, 0.0, 0.30], 45.0),
        ]);
        let r = low_back(&upright(m, f), &BackParams::default()).unwrap();
        assert_abs_diff_eq!(r.sagittal_moment_nm, -9.81, epsilon = 1e-12);
        assert_eq!(r.balancing_muscle, BalancingMuscle::Flexors);
        assert_abs_diff_eq!(r.flexor_force_n, 122.625, epsilon = 1e-9);
        assert_eq!(r.extensor_force_n, 0.0);
        assert_abs_diff_eq!(r.compression_n, 613.125, epsilon = 1e-9);
    }

    /// A twisting load: a 30 N forward pull applied 0.25 m to the left of the spine at
    /// shoulder height gives a twisting moment (0.25 m × 30 N turning the trunk to the right).
    #[test]
    fn twisting_moment_is_reported() {
        // r = (0, 0.25, 0.40), F = (30, 0, 0): M = r × F = (0, 12, −7.5).
        let m = cross([0.0, 0.25, 0.40], [30.0, 0.0, 0.0]);
        let r = low_back(&upright(m, [30.0, 0.0, 0.0]), &BackParams::default()).unwrap();
        assert_abs_diff_eq!(r.axial_moment_nm, -7.5, epsilon = 1e-12);
        assert_abs_diff_eq!(r.sagittal_moment_nm, 12.0, epsilon = 1e-12);
        assert_abs_diff_eq!(r.extensor_force_n, 240.0, epsilon = 1e-9);
        assert_abs_diff_eq!(r.shear_ap_n, 30.0, epsilon = 1e-12);
    }

    #[test]
    fn verdicts_use_the_limits() {
        let p = BackParams::default();
        let at = |c: f64, s: f64| low_back(&upright([0.0; 3], [s, 0.0, -c]), &p).unwrap();
        assert_eq!(
            at(3400.0, 0.0).compression_verdict,
            CompressionVerdict::WithinActionLimit
        );
        assert_eq!(
            at(3400.5, 0.0).compression_verdict,
            CompressionVerdict::AboveActionLimit
        );
        assert_eq!(
            at(6400.0, 0.0).compression_verdict,
            CompressionVerdict::AboveActionLimit
        );
        assert_eq!(
            at(6400.5, 0.0).compression_verdict,
            CompressionVerdict::AboveMaximumPermissibleLimit
        );
        assert_eq!(at(500.0, 1000.0).shear_verdict, ShearVerdict::WithinLimit);
        assert_eq!(at(500.0, -1000.5).shear_verdict, ShearVerdict::AboveLimit);
        let frequent = BackParams {
            shear_limit_n: 700.0,
            ..p
        };
        let r = low_back(&upright([0.0; 3], [800.0, 0.0, -500.0]), &frequent).unwrap();
        assert_eq!(r.shear_verdict, ShearVerdict::AboveLimit);
    }

    #[test]
    fn nearly_orthonormal_axes_are_cleaned_up() {
        let load = LumbarLoad {
            moment_nm: [0.0, 10.0, 0.0],
            force_n: [0.0, 0.0, -400.0],
            spine_axis: [0.0, 0.0, 1.0005],
            forward_axis: [1.0, 0.0, 0.0008],
        };
        let r = low_back(&load, &BackParams::default()).unwrap();
        assert_abs_diff_eq!(norm(r.spine_axis), 1.0, epsilon = 1e-12);
        assert_abs_diff_eq!(norm(r.forward_axis), 1.0, epsilon = 1e-12);
        assert_abs_diff_eq!(dot(r.spine_axis, r.forward_axis), 0.0, epsilon = 1e-12);
        assert_abs_diff_eq!(r.compression_n, 600.0, epsilon = 1e-9);
    }

    #[test]
    fn invalid_inputs_are_refused_with_the_field_named() {
        let p = BackParams::default();
        let mut load = upright([0.0, 1.0, 0.0], [0.0, 0.0, -100.0]);
        load.force_n[2] = f64::NAN;
        assert_eq!(
            low_back(&load, &p).unwrap_err().to_string(),
            "load.force_n[2] must be a finite number, got NaN"
        );
        let mut load = upright([0.0; 3], [0.0; 3]);
        load.spine_axis = [0.0, 0.0, 2.0];
        assert_eq!(
            low_back(&load, &p).unwrap_err().to_string(),
            "load.spine_axis must be a unit vector (length 1 ± 0.001), got length 2"
        );
        let mut load = upright([0.0; 3], [0.0; 3]);
        load.forward_axis = [0.0, 0.0, 1.0];
        assert!(matches!(
            low_back(&load, &p),
            Err(LowBackError::NotPerpendicular { .. })
        ));
        let mut load = upright([0.0; 3], [0.0; 3]);
        load.forward_axis = [0.0; 3];
        assert!(matches!(
            low_back(&load, &p),
            Err(LowBackError::NotUnit { .. })
        ));
        let load = upright([0.0; 3], [0.0; 3]);
        for bad in [
            BackParams {
                erector_moment_arm_m: 0.0,
                ..p
            },
            BackParams {
                flexor_moment_arm_m: f64::NAN,
                ..p
            },
            BackParams {
                shear_limit_n: -1.0,
                ..p
            },
            BackParams {
                compression_action_limit_n: 7000.0,
                ..p
            },
        ] {
            assert!(low_back(&load, &bad).is_err());
        }
        assert_eq!(
            low_back(
                &load,
                &BackParams {
                    erector_moment_arm_m: 0.5,
                    ..p
                }
            )
            .unwrap_err()
            .to_string(),
            "params.erector_moment_arm_m must be more than 0 and at most 0.3 m (a trunk-muscle \
             moment arm at L5/S1), got 0.5"
        );
    }

    /// Every extreme value in every input component either gives an error or a result whose
    /// numbers are all finite.
    #[test]
    fn never_panics_and_never_returns_non_finite_numbers() {
        let extremes = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -1e308,
            -1e7,
            -1.0,
            -0.0,
            0.0,
            1e-300,
            0.5,
            1.0,
            1e7,
            1e308,
        ];
        let base = upright([0.0, 50.0, 0.0], [0.0, 0.0, -500.0]);
        let p = BackParams::default();
        for which in 0..12 {
            for &x in &extremes {
                let mut load = base;
                match which / 3 {
                    0 => load.moment_nm[which % 3] = x,
                    1 => load.force_n[which % 3] = x,
                    2 => load.spine_axis[which % 3] = x,
                    _ => load.forward_axis[which % 3] = x,
                }
                if let Ok(r) = low_back(&load, &p) {
                    for v in [
                        r.compression_n,
                        r.shear_ap_n,
                        r.shear_lateral_n,
                        r.shear_resultant_n,
                        r.extensor_force_n,
                        r.flexor_force_n,
                        r.sagittal_moment_nm,
                        r.lateral_moment_nm,
                        r.axial_moment_nm,
                    ] {
                        assert!(v.is_finite(), "component {which} = {x}: {r:?}");
                    }
                }
            }
        }
        let mut load = base;
        load.force_n = [1e7, -1e7, 1e7];
        load.moment_nm = [-1e7, 1e7, -1e7];
        let r = low_back(&load, &p).unwrap();
        assert!(r.compression_n.is_finite());
    }

    #[test]
    fn result_serializes() {
        fn is_serialize<T: Serialize>() {}
        is_serialize::<LowBack>();
    }
}
