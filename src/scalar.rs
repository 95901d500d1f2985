//! A minimal scalar abstraction so that one rate function serves both the solver (`f64`) and
//! the von Neumann engine, which linearises it exactly with forward-mode dual numbers
//! ([`Dual`]). Derivatives obtained this way are exact to rounding: no finite-difference step.

use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// Arithmetic needed by rate functions and shape functions.
pub trait Scalar:
    Copy
    + Send
    + Sync
    + PartialEq
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// Whether the type carries a derivative part. `false` lets value-only evaluations (the
    /// solver's `f64`) skip computing derivatives that [`Scalar::lift`] would discard.
    const TANGENT: bool = true;
    /// A constant (zero derivative part).
    fn cst(v: f64) -> Self;
    /// The value part.
    fn re(self) -> f64;
    /// `g(self)` for a scalar function `g` with `g(self.re()) = g0` and `g'(self.re()) = g1`.
    fn lift(self, g0: f64, g1: f64) -> Self;
    /// Square root. At 0 the derivative is infinite; the tangent is set to 0 there, which is
    /// right only when the argument's own tangent vanishes too (as for r² = |d|² at d = 0,
    /// where |d| itself has no derivative). Rate and shape code never differentiates through
    /// `sqrt(0)`: the kernel composites W(|d|), ∇W(|d|) are lifted directly from d
    /// ([`crate::kernel::w_and_grad`]), and the derivative audit test checks it.
    fn sqrt(self) -> Self {
        let s = self.re().sqrt();
        self.lift(s, if s > 0.0 { 0.5 / s } else { 0.0 })
    }
    /// Absolute value (derivative sign(x); at the kink x = 0 the subgradient 0). Not used to
    /// differentiate a kernel of |d|: W(|d|) is smooth at d = 0 although |d| is not, and is
    /// lifted directly ([`crate::kernel::w_and_grad`]) so that its second
    /// derivative W''(0) survives.
    fn abs(self) -> Self {
        let v = self.re();
        self.lift(
            v.abs(),
            if v > 0.0 {
                1.0
            } else if v < 0.0 {
                -1.0
            } else {
                0.0
            },
        )
    }
    /// Natural logarithm.
    fn ln(self) -> Self {
        let v = self.re();
        self.lift(v.ln(), 1.0 / v)
    }
    /// Zero.
    fn zero() -> Self {
        Self::cst(0.0)
    }
}

impl Scalar for f64 {
    const TANGENT: bool = false;
    #[inline]
    fn cst(v: f64) -> Self {
        v
    }
    #[inline]
    fn re(self) -> f64 {
        self
    }
    #[inline]
    fn lift(self, g0: f64, _g1: f64) -> Self {
        g0
    }
}

/// Forward-mode dual number `v + d ε`, ε² = 0.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Dual {
    /// Value.
    pub v: f64,
    /// Derivative (tangent) part.
    pub d: f64,
}

impl Dual {
    /// A dual number with the given value and tangent.
    pub fn new(v: f64, d: f64) -> Self {
        Self { v, d }
    }
}

impl Scalar for Dual {
    #[inline]
    fn cst(v: f64) -> Self {
        Self { v, d: 0.0 }
    }
    #[inline]
    fn re(self) -> f64 {
        self.v
    }
    #[inline]
    fn lift(self, g0: f64, g1: f64) -> Self {
        Self {
            v: g0,
            d: g1 * self.d,
        }
    }
}

impl Add for Dual {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self {
            v: self.v + o.v,
            d: self.d + o.d,
        }
    }
}
impl Sub for Dual {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self {
            v: self.v - o.v,
            d: self.d - o.d,
        }
    }
}
impl Mul for Dual {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self {
            v: self.v * o.v,
            d: self.d * o.v + self.v * o.d,
        }
    }
}
impl Div for Dual {
    type Output = Self;
    #[inline]
    fn div(self, o: Self) -> Self {
        let v = self.v / o.v;
        Self {
            v,
            d: (self.d - v * o.d) / o.v,
        }
    }
}
impl Neg for Dual {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            d: -self.d,
        }
    }
}
impl AddAssign for Dual {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl SubAssign for Dual {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl MulAssign for Dual {
    #[inline]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}
impl Add<f64> for Dual {
    type Output = Self;
    #[inline]
    fn add(self, o: f64) -> Self {
        Self {
            v: self.v + o,
            d: self.d,
        }
    }
}
impl Sub<f64> for Dual {
    type Output = Self;
    #[inline]
    fn sub(self, o: f64) -> Self {
        Self {
            v: self.v - o,
            d: self.d,
        }
    }
}
impl Mul<f64> for Dual {
    type Output = Self;
    #[inline]
    fn mul(self, o: f64) -> Self {
        Self {
            v: self.v * o,
            d: self.d * o,
        }
    }
}
impl Div<f64> for Dual {
    type Output = Self;
    #[inline]
    fn div(self, o: f64) -> Self {
        Self {
            v: self.v / o,
            d: self.d / o,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dual_derivative_of_rational_function_matches_calculus() {
        // g(x) = (x^2 + 1) / (3x), g'(x) = (x^2 - 1) / (3x^2); at x = 2: g' = 3/12.
        let x = Dual::new(2.0, 1.0);
        let g = (x * x + 1.0) / (x * 3.0);
        assert!((g.v - 5.0 / 6.0).abs() < 1e-15);
        assert!((g.d - 0.25).abs() < 1e-15);
        let s = Dual::new(4.0, 1.0).sqrt();
        assert!((s.d - 0.25).abs() < 1e-15);
    }
}
