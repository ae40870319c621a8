//! The asymmetry cost: working off to the side of where the feet face, priced the way the
//! revised NIOSH lifting equation prices it.
//!
//! **The angle.** NIOSH's asymmetry angle `A` is the angle between the asymmetry line (from the
//! point between the feet to the load's centre, on the floor) and the mid-sagittal line of the
//! body's neutral position, the direction the feet face (Waters, Putz-Anderson, Garg & Fine
//! 1993, Ergonomics 36:749; Applications Manual for the Revised NIOSH Lifting Equation, DHHS
//! (NIOSH) 94-110, 1994). Here: `d = ℓ − m`, `ℓ` the horizontal mean of the phase's hand targets
//! (the load's centre), `m` the midpoint of the two sole centres (NIOSH measures from the
//! midpoint of the inner ankle bones, a few centimetres behind: ASSUMPTION, it moves `A` by
//! under 5° for a load 0.3 m or farther away), and the feet's mean heading `h` (each foot's
//! heading is its link's x axis): `A = wrap(atan2(d_y, d_x) − h)`.
//!
//! **The cost.** NIOSH multiplies the recommended weight limit by `AM = 1 − 0.0032 A` (A in
//! degrees, 0 beyond 135°). A phase at angle `A` costs `c(A) = −ln AM(|A|)`: added to the
//! objective, whose fatigue term is the logarithm of the total fatigue index, it counts as that
//! total divided by `AM` — the load made heavier in the proportion NIOSH would make it. So that
//! the cost is smooth and finite: `|A|` is `√(A² + a₀²) − a₀` with `a₀ =` [`SMOOTH_DEG`], the
//! logarithm continues along its tangent beyond [`KNEE_DEG`] (AM falls to 0 at 135°, which no
//! posture should make infinitely dear), and the cost fades where the load is over the feet,
//! where the angle means nothing: `× r²/(r² + r₀²)`, `r = |d|`, `r₀ =` [`FADE_M`]
//! (ASSUMPTION: NIOSH's smallest horizontal distance is 25 cm).
//!
//! The objective adds `w ·` the mean of `c(A_p)` over the cycle's phases (`w` the task's
//! `objective.asymmetry_weight`, default 1): a cycle done wholly at `A` counts as its total
//! divided by `AM(A)`. Where the feet are fixed, `A` is the layout's, not the plan's, and the
//! term is left out.

use crate::body::stance::{FeetNow, wrap_pi};
use nalgebra::Vector2;

/// NIOSH's asymmetric multiplier falls by this per degree (Waters et al. 1993).
pub const AM_PER_DEG: f64 = 0.0032;

/// Beyond this angle \[deg\] the cost continues along its tangent (ASSUMPTION: AM is 0 at 135°;
/// 120° keeps the cost finite and convex with AM still 0.62).
pub const KNEE_DEG: f64 = 120.0;

/// The smoothing of `|A|` at 0 \[deg\] (ASSUMPTION: below what an observer would measure).
pub const SMOOTH_DEG: f64 = 1.0;

/// The cost fades for a load closer than this to the point between the feet \[m\] (ASSUMPTION).
pub const FADE_M: f64 = 0.10;

/// `c(s)` and `dc/ds` of a smoothed |A| `s` \[deg\].
fn cost_of_deg(s: f64) -> (f64, f64) {
    if s <= KNEE_DEG {
        let am = 1.0 - AM_PER_DEG * s;
        (-am.ln(), AM_PER_DEG / am)
    } else {
        let am = 1.0 - AM_PER_DEG * KNEE_DEG;
        let slope = AM_PER_DEG / am;
        (-am.ln() + slope * (s - KNEE_DEG), slope)
    }
}

/// NIOSH's asymmetry angle `A` \[rad\] of a load at `load_xy` for feet `feet` (positive: the
/// load is to the left of where the feet face).
pub fn angle_rad(feet: &FeetNow, load_xy: &Vector2<f64>) -> f64 {
    let m = (feet.sole_center_m[0] + feet.sole_center_m[1]) / 2.0;
    let d = load_xy - m;
    wrap_pi(d.y.atan2(d.x) - feet.geometry().heading_rad)
}

/// The cost of one phase and its derivatives in the feet: `(c, ∂c/∂c_i, ∂c/∂ψ_i)` (left, right)
/// for the sole centres `c_i` and yaws `ψ_i`.
pub fn phase_cost(feet: &FeetNow, load_xy: &Vector2<f64>) -> (f64, [Vector2<f64>; 2], [f64; 2]) {
    let m = (feet.sole_center_m[0] + feet.sole_center_m[1]) / 2.0;
    let d = load_xy - m;
    let r2 = d.norm_squared();
    let a = wrap_pi(d.y.atan2(d.x) - feet.geometry().heading_rad).to_degrees();
    let a0 = SMOOTH_DEG;
    let root = (a * a + a0 * a0).sqrt();
    let (c, dc_ds) = cost_of_deg(root - a0);
    let fade = r2 / (r2 + FADE_M * FADE_M);
    // ∂c/∂A [per rad]
    let dc_da = dc_ds * (a / root) * 180.0 / std::f64::consts::PI;
    // A = atan2(d) − h: ∂A/∂d = (−d_y, d_x)/r², ∂d/∂c_i = −I/2; ∂A/∂ψ_i = −1/2
    let da_dd = if r2 > 0.0 {
        Vector2::new(-d.y, d.x) / r2
    } else {
        Vector2::zeros()
    };
    let dfade_dd = 2.0 * FADE_M * FADE_M * d / ((r2 + FADE_M * FADE_M).powi(2));
    let dd = fade * dc_da * da_dd + c * dfade_dd;
    let gc = -dd / 2.0;
    let gpsi = -fade * dc_da / 2.0;
    (fade * c, [gc, gc], [gpsi, gpsi])
}

/// The asymmetry cost of one posture: its phases' loads, each with its weight.
#[derive(Debug, Clone, Default)]
pub struct Asymmetry {
    /// Per phase the posture holds: the load's centre on the floor and the weight
    /// (`asymmetry_weight / phases in the cycle`).
    pub loads: Vec<(Vector2<f64>, f64)>,
}

impl Asymmetry {
    /// The cost of standing on `feet`.
    pub fn value(&self, feet: &FeetNow) -> f64 {
        self.loads
            .iter()
            .map(|(l, w)| w * phase_cost(feet, l).0)
            .sum()
    }

    /// The cost's derivatives in the feet (left, right): sole centres and yaws.
    pub fn feet_gradient(&self, feet: &FeetNow) -> ([Vector2<f64>; 2], [f64; 2]) {
        let (mut gc, mut gpsi) = ([Vector2::zeros(); 2], [0.0; 2]);
        for &(l, w) in &self.loads {
            let (_, c, p) = phase_cost(feet, &l);
            for i in 0..2 {
                gc[i] += w * c[i];
                gpsi[i] += w * p[i];
            }
        }
        (gc, gpsi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn feet(mid: [f64; 2], heading_deg: f64) -> FeetNow {
        let h = heading_deg.to_radians();
        let left = Vector2::new(-h.sin(), h.cos()) * 0.15;
        let m = Vector2::new(mid[0], mid[1]);
        FeetNow {
            sole_center_m: [m + left, m - left],
            yaw_rad: [h, h],
            corner_m: [[Vector2::zeros(); 4]; 2],
        }
    }

    /// Against NIOSH's own figures: AM = 1 − 0.0032·A (Waters et al. 1993), so at 90° the cost
    /// is −ln 0.712 for a load far enough away, and 0 (to the smoothing) facing it.
    #[test]
    fn the_cost_is_minus_the_log_of_niosh_multiplier() {
        let f = feet([0.0, 0.0], 0.0);
        let far = Vector2::new(0.0, 2.0); // 90° to the left, r = 2 m
        let (c, _, _) = phase_cost(&f, &far);
        let fade = 4.0 / (4.0 + FADE_M * FADE_M);
        let s = (90.0f64 * 90.0 + 1.0).sqrt() - 1.0;
        assert!((c - fade * -(1.0 - 0.0032 * s).ln()).abs() < 1e-12);
        // NIOSH's AM at 90° is 0.712: the smoothing takes about a0 = 1° off |A| (AM 0.715)
        assert!((c + (0.712f64).ln()).abs() < 1e-2, "{c}");
        let ahead = Vector2::new(2.0, 0.0);
        assert!(phase_cost(&f, &ahead).0 < 1e-12);
        // symmetric: the same to the right
        let right = Vector2::new(0.0, -2.0);
        assert!((phase_cost(&f, &right).0 - c).abs() < 1e-12);
        // turning the feet to face it removes it
        assert!(phase_cost(&feet([0.0, 0.0], 90.0), &far).0 < 1e-12);
        assert!((angle_rad(&f, &far).to_degrees() - 90.0).abs() < 1e-9);
    }

    /// The derivatives against central differences, at angles on both sides and beyond the knee.
    #[test]
    fn the_gradient_matches_differences() {
        let load = Vector2::new(0.4, 0.5);
        for heading in [-170.0, -60.0, 10.0, 45.0, 140.0] {
            let f = feet([0.05, -0.1], heading);
            let (_, gc, gp) = phase_cost(&f, &load);
            let h = 1e-6;
            for i in 0..2 {
                for ax in 0..2 {
                    let (mut a, mut b) = (f, f);
                    a.sole_center_m[i][ax] += h;
                    b.sole_center_m[i][ax] -= h;
                    let fd = (phase_cost(&a, &load).0 - phase_cost(&b, &load).0) / (2.0 * h);
                    assert!(
                        (fd - gc[i][ax]).abs() < 1e-6,
                        "{heading}: {fd} vs {}",
                        gc[i][ax]
                    );
                }
                let (mut a, mut b) = (f, f);
                a.yaw_rad[i] += h;
                b.yaw_rad[i] -= h;
                let fd = (phase_cost(&a, &load).0 - phase_cost(&b, &load).0) / (2.0 * h);
                assert!((fd - gp[i]).abs() < 1e-6, "{heading}: {fd} vs {}", gp[i]);
            }
        }
    }

    /// The cost grows with the angle all the way round (monotone in |A|), and is finite at 180°.
    #[test]
    fn the_cost_rises_with_the_angle() {
        let f = feet([0.0, 0.0], 0.0);
        let mut last = -1.0;
        for deg in (0..=180).step_by(5) {
            let a = f64::from(deg).to_radians();
            let c = phase_cost(&f, &Vector2::new(a.cos(), a.sin())).0;
            assert!(c.is_finite() && c > last, "{deg}°: {c} after {last}");
            last = c;
        }
    }
}
