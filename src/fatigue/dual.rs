//! Second-order forward-mode derivatives of scalar functions of one variable, so the fatigue
//! schedule's closed forms give their value, slope and curvature in one pass.
//!
//! A [`Dual2`] carries `(v, d, dd)`: a value and its first and second derivatives with respect
//! to one chosen input. [`Real`] abstracts over `f64` (plain values) and `Dual2`, so one generic
//! function serves both the plan's evaluation and the optimiser's derivatives.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A number with its first and second derivative with respect to one input.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Dual2 {
    pub v: f64,
    pub d: f64,
    pub dd: f64,
}

impl Dual2 {
    /// The input variable itself: value `x`, slope 1, curvature 0.
    pub fn variable(x: f64) -> Self {
        Dual2 {
            v: x,
            d: 1.0,
            dd: 0.0,
        }
    }

    /// Applies a scalar function with value `f0`, first derivative `f1` and second `f2` at `self.v`.
    #[inline]
    fn chain(self, f0: f64, f1: f64, f2: f64) -> Self {
        Dual2 {
            v: f0,
            d: f1 * self.d,
            dd: f1 * self.dd + f2 * self.d * self.d,
        }
    }
}

/// What the fatigue closed forms need from a number type.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// A constant.
    fn cst(x: f64) -> Self;
    /// The value.
    fn val(self) -> f64;
    fn exp(self) -> Self;
    fn exp_m1(self) -> Self;
    fn ln(self) -> Self;
    fn ln_1p(self) -> Self;
    fn sqrt(self) -> Self;
}

impl Real for f64 {
    #[inline]
    fn cst(x: f64) -> Self {
        x
    }
    #[inline]
    fn val(self) -> f64 {
        self
    }
    #[inline]
    fn exp(self) -> Self {
        f64::exp(self)
    }
    #[inline]
    fn exp_m1(self) -> Self {
        f64::exp_m1(self)
    }
    #[inline]
    fn ln(self) -> Self {
        f64::ln(self)
    }
    #[inline]
    fn ln_1p(self) -> Self {
        f64::ln_1p(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
}

impl Real for Dual2 {
    #[inline]
    fn cst(x: f64) -> Self {
        Dual2 {
            v: x,
            d: 0.0,
            dd: 0.0,
        }
    }
    #[inline]
    fn val(self) -> f64 {
        self.v
    }
    #[inline]
    fn exp(self) -> Self {
        let e = self.v.exp();
        self.chain(e, e, e)
    }
    #[inline]
    fn exp_m1(self) -> Self {
        let e = self.v.exp();
        self.chain(self.v.exp_m1(), e, e)
    }
    #[inline]
    fn ln(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(self.v.ln(), r, -r * r)
    }
    #[inline]
    fn ln_1p(self) -> Self {
        let r = 1.0 / (1.0 + self.v);
        self.chain(self.v.ln_1p(), r, -r * r)
    }
    #[inline]
    fn sqrt(self) -> Self {
        let q = self.v.sqrt();
        self.chain(q, 0.5 / q, -0.25 / (q * self.v))
    }
}

impl Add for Dual2 {
    type Output = Dual2;
    #[inline]
    fn add(self, o: Dual2) -> Dual2 {
        Dual2 {
            v: self.v + o.v,
            d: self.d + o.d,
            dd: self.dd + o.dd,
        }
    }
}

impl Sub for Dual2 {
    type Output = Dual2;
    #[inline]
    fn sub(self, o: Dual2) -> Dual2 {
        Dual2 {
            v: self.v - o.v,
            d: self.d - o.d,
            dd: self.dd - o.dd,
        }
    }
}

impl Mul for Dual2 {
    type Output = Dual2;
    #[inline]
    fn mul(self, o: Dual2) -> Dual2 {
        Dual2 {
            v: self.v * o.v,
            d: self.d * o.v + self.v * o.d,
            dd: self.dd * o.v + 2.0 * self.d * o.d + self.v * o.dd,
        }
    }
}

impl Div for Dual2 {
    type Output = Dual2;
    #[inline]
    fn div(self, o: Dual2) -> Dual2 {
        // self · (1/o), with (1/x)' = −1/x², (1/x)'' = 2/x³
        let r = 1.0 / o.v;
        let inv = o.chain(r, -r * r, 2.0 * r * r * r);
        self * inv
    }
}

impl Neg for Dual2 {
    type Output = Dual2;
    #[inline]
    fn neg(self) -> Dual2 {
        Dual2 {
            v: -self.v,
            d: -self.d,
            dd: -self.dd,
        }
    }
}

impl Add<f64> for Dual2 {
    type Output = Dual2;
    #[inline]
    fn add(self, o: f64) -> Dual2 {
        Dual2 {
            v: self.v + o,
            ..self
        }
    }
}

impl Sub<f64> for Dual2 {
    type Output = Dual2;
    #[inline]
    fn sub(self, o: f64) -> Dual2 {
        Dual2 {
            v: self.v - o,
            ..self
        }
    }
}

impl Mul<f64> for Dual2 {
    type Output = Dual2;
    #[inline]
    fn mul(self, o: f64) -> Dual2 {
        Dual2 {
            v: self.v * o,
            d: self.d * o,
            dd: self.dd * o,
        }
    }
}

impl Div<f64> for Dual2 {
    type Output = Dual2;
    #[inline]
    fn div(self, o: f64) -> Dual2 {
        self * (1.0 / o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_of_a_composite_match_hand_derivation() {
        // h(x) = ln(1 + x²) / e^x at x = 0.7
        let x = Dual2::variable(0.7);
        let h = (x * x).ln_1p() / x.exp();
        let xv = 0.7f64;
        let (a, da, dda) = (
            (xv * xv).ln_1p(),
            2.0 * xv / (1.0 + xv * xv),
            (2.0 - 2.0 * xv * xv) / (1.0 + xv * xv).powi(2),
        );
        let e = (-xv).exp();
        // (a e^{-x})' = (a' − a) e^{-x}; '' = (a'' − 2a' + a) e^{-x}
        assert!((h.v - a * e).abs() < 1e-15);
        assert!((h.d - (da - a) * e).abs() < 1e-14);
        assert!((h.dd - (dda - 2.0 * da + a) * e).abs() < 1e-14);
    }
}
