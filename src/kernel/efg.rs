//! The EFG spline weight functions used with MLS shape functions in \[B00\] (Belytschko, Lu &
//! Gu 1994), with support radius h (ζ = 1, so `--h` equals the dilation D_mx).

use std::f64::consts::PI;

use super::{Kernel, dim_index, lucy};

/// EFG cubic spline weight, ζ = 1:
/// f = 2/3 − 4q² + 4q³ for q ≤ 1/2, 4/3 − 4q + 4q² − (4/3)q³ = (4/3)(1 − q)³ for 1/2 < q ≤ 1.
///
/// It is the M4 spline rescaled to unit support, f(q) = (2/3) f_M4(2q).
/// σ = 2, 60/(7π), 12/π; f'' = −8 + 24q on [0, 1/2], q* = 1/3.
#[derive(Debug, Clone, Copy, Default)]
pub struct EfgCubic;

impl EfgCubic {
    /// The `order`-th q-derivative (0, 1, 2) at |q|; zero for |q| ≥ 1.
    fn eval(order: u8, q: f64) -> f64 {
        let q = q.abs();
        if q >= 1.0 {
            return 0.0;
        }
        if q <= 0.5 {
            match order {
                0 => 2.0 / 3.0 + q * q * (4.0 * q - 4.0),
                1 => q * (12.0 * q - 8.0),
                _ => 24.0 * q - 8.0,
            }
        } else {
            let s = 1.0 - q;
            match order {
                0 => 4.0 / 3.0 * s * s * s,
                1 => -4.0 * s * s,
                _ => 8.0 * s,
            }
        }
    }
}

impl Kernel for EfgCubic {
    fn name(&self) -> &'static str {
        "efg-cubic"
    }
    fn zeta(&self) -> f64 {
        1.0
    }
    fn f(&self, _dim: usize, q: f64) -> f64 {
        Self::eval(0, q)
    }
    fn df(&self, _dim: usize, q: f64) -> f64 {
        Self::eval(1, q)
    }
    fn d2f(&self, _dim: usize, q: f64) -> f64 {
        Self::eval(2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        [2.0, 60.0 / (7.0 * PI), 12.0 / PI][dim_index(dim)]
    }
    fn inflection(&self, _dim: usize) -> f64 {
        1.0 / 3.0
    }
    fn reference(&self) -> &'static str {
        "Belytschko, Lu & Gu (1994) IJNME 37:229, cubic spline weight; as used in [B00]"
    }
    fn customary_h(&self) -> (f64, f64) {
        (1.5, 4.0)
    }
}

/// EFG quartic spline weight, ζ = 1: f = 1 − 6q² + 8q³ − 3q⁴ for q ≤ 1.
///
/// This polynomial is (1 + 3q)(1 − q)³, i.e. the same function as [`Lucy`](super::Lucy)
/// (and as Wendland's ψ_{2,1}); it is evaluated in that factored form.
/// σ = 5/4, 5/π, 105/(16π); f'' = −12(1 − q)(1 − 3q), q* = 1/3.
#[derive(Debug, Clone, Copy, Default)]
pub struct EfgQuartic;

impl Kernel for EfgQuartic {
    fn name(&self) -> &'static str {
        "efg-quartic"
    }
    fn zeta(&self) -> f64 {
        1.0
    }
    fn f(&self, _dim: usize, q: f64) -> f64 {
        lucy::quartic(0, q)
    }
    fn df(&self, _dim: usize, q: f64) -> f64 {
        lucy::quartic(1, q)
    }
    fn d2f(&self, _dim: usize, q: f64) -> f64 {
        lucy::quartic(2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        lucy::quartic_sigma(dim)
    }
    fn inflection(&self, _dim: usize) -> f64 {
        1.0 / 3.0
    }
    fn reference(&self) -> &'static str {
        "Belytschko, Lu & Gu (1994) IJNME 37:229, quartic spline weight; as used in [B00]"
    }
    fn customary_h(&self) -> (f64, f64) {
        (1.5, 4.0)
    }
}
