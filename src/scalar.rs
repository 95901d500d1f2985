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
    /// x^p for x > 0.
    fn powf(self, p: f64) -> Self {
        let v = self.re();
        self.lift(v.powf(p), p * v.powf(p - 1.0))
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

/// Forward-mode dual number with `N` tangent lanes, `v + Σ_l d_l ε_l` (ε_l ε_m = 0): one
/// evaluation gives the directional derivatives along N seeds at once (the linearisation
/// differentiates a rate function with respect to N degrees of freedom in one pass). Each lane
/// is computed with exactly the operations of [`Dual`]'s tangent, so lane l equals, to the
/// last bit, a [`Dual`] evaluation seeded along direction l.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DualN<const N: usize> {
    /// Value.
    pub v: f64,
    /// Tangent lanes.
    pub d: [f64; N],
}

impl<const N: usize> Default for DualN<N> {
    fn default() -> Self {
        Self::cst(0.0)
    }
}

impl<const N: usize> DualN<N> {
    #[inline]
    fn zip(self, o: Self, v: f64, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut d = [0.0; N];
        for ((x, a), b) in d.iter_mut().zip(self.d).zip(o.d) {
            *x = f(a, b);
        }
        Self { v, d }
    }
    #[inline]
    fn each(self, v: f64, f: impl Fn(f64) -> f64) -> Self {
        let mut d = self.d;
        for x in d.iter_mut() {
            *x = f(*x);
        }
        Self { v, d }
    }
}

impl<const N: usize> Scalar for DualN<N> {
    #[inline]
    fn cst(v: f64) -> Self {
        Self { v, d: [0.0; N] }
    }
    #[inline]
    fn re(self) -> f64 {
        self.v
    }
    #[inline]
    fn lift(self, g0: f64, g1: f64) -> Self {
        self.each(g0, |d| g1 * d)
    }
}

impl<const N: usize> Add for DualN<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        self.zip(o, self.v + o.v, |a, b| a + b)
    }
}
impl<const N: usize> Sub for DualN<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        self.zip(o, self.v - o.v, |a, b| a - b)
    }
}
impl<const N: usize> Mul for DualN<N> {
    type Output = Self;
    #[inline]
    #[allow(clippy::suspicious_arithmetic_impl)] // the product rule
    fn mul(self, o: Self) -> Self {
        let (sv, ov) = (self.v, o.v);
        self.zip(o, sv * ov, |a, b| a * ov + sv * b)
    }
}
impl<const N: usize> Div for DualN<N> {
    type Output = Self;
    #[inline]
    #[allow(clippy::suspicious_arithmetic_impl)] // the quotient rule
    fn div(self, o: Self) -> Self {
        let v = self.v / o.v;
        let ov = o.v;
        self.zip(o, v, |a, b| (a - v * b) / ov)
    }
}
impl<const N: usize> Neg for DualN<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self.each(-self.v, |d| -d)
    }
}
impl<const N: usize> AddAssign for DualN<N> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<const N: usize> SubAssign for DualN<N> {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl<const N: usize> MulAssign for DualN<N> {
    #[inline]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}
impl<const N: usize> Add<f64> for DualN<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: f64) -> Self {
        Self {
            v: self.v + o,
            d: self.d,
        }
    }
}
impl<const N: usize> Sub<f64> for DualN<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: f64) -> Self {
        Self {
            v: self.v - o,
            d: self.d,
        }
    }
}
impl<const N: usize> Mul<f64> for DualN<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: f64) -> Self {
        self.each(self.v * o, |d| d * o)
    }
}
impl<const N: usize> Div<f64> for DualN<N> {
    type Output = Self;
    #[inline]
    fn div(self, o: f64) -> Self {
        self.each(self.v / o, |d| d / o)
    }
}

/// A dual number type with tangent lanes that a linearisation seeds one by one: [`Dual`] (one
/// lane) or [`DualN`] (N lanes).
pub trait Lanes: Scalar + Default {
    /// Number of tangent lanes.
    const LANES: usize;
    /// Sets lane `l` of the tangent to 1.
    fn seed(&mut self, l: usize);
    /// Lane `l` of the tangent.
    fn lane(&self, l: usize) -> f64;
}

impl Lanes for Dual {
    const LANES: usize = 1;
    #[inline]
    fn seed(&mut self, _l: usize) {
        self.d = 1.0;
    }
    #[inline]
    fn lane(&self, _l: usize) -> f64 {
        self.d
    }
}

impl<const N: usize> Lanes for DualN<N> {
    const LANES: usize = N;
    #[inline]
    fn seed(&mut self, l: usize) {
        self.d[l] = 1.0;
    }
    #[inline]
    fn lane(&self, l: usize) -> f64 {
        self.d[l]
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

    /// Each lane of a `DualN` is, bit for bit, a `Dual` seeded along that lane (the property the
    /// one-pass linearisation relies on), through every operation and the lifted functions.
    #[test]
    fn dual_n_lanes_equal_scalar_duals() {
        fn f<S: Scalar>(x: S, y: S) -> S {
            let r = (x * x + y * y).sqrt();
            ((x / y - 0.3) * r + x.abs() * 2.0 - (-y) / 1.7).ln() + (x - y) * (y + 0.5)
        }
        let (x0, y0) = (0.7, -1.3);
        let n = f(
            DualN {
                v: x0,
                d: [1.0, 0.0, 0.5],
            },
            DualN {
                v: y0,
                d: [0.0, 1.0, -2.0],
            },
        );
        let seeds = [(1.0, 0.0), (0.0, 1.0), (0.5, -2.0)];
        for (l, (dx, dy)) in seeds.into_iter().enumerate() {
            let s = f(Dual::new(x0, dx), Dual::new(y0, dy));
            assert_eq!(s.v.to_bits(), n.v.to_bits());
            assert_eq!(s.d.to_bits(), n.d[l].to_bits(), "lane {l}");
        }
    }
}
