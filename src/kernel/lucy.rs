//! Lucy's quartic kernel, ζ = 1.

use std::f64::consts::PI;

use super::{Kernel, dim_index};

/// f = (1 + 3q)(1 − q)³ on [0, 1) and its q-derivatives; zero for |q| ≥ 1.
/// Shared with [`EfgQuartic`](super::EfgQuartic), whose polynomial is the same one expanded.
pub(super) fn quartic(order: u8, q: f64) -> f64 {
    let q = q.abs();
    if q >= 1.0 {
        return 0.0;
    }
    let s = 1.0 - q;
    match order {
        0 => (1.0 + 3.0 * q) * s * s * s,
        1 => -12.0 * q * s * s,
        _ => -12.0 * s * (1.0 - 3.0 * q),
    }
}

/// σ_d of the quartic (1 + 3q)(1 − q)³ with ζ = 1: 5/4, 5/π, 105/(16π).
pub(super) fn quartic_sigma(dim: usize) -> f64 {
    [5.0 / 4.0, 5.0 / PI, 105.0 / (16.0 * PI)][dim_index(dim)]
}

/// Lucy (1977) quartic, ζ = 1: f = (1 + 3q)(1 − q)³ (\[T\] eq. 2.13).
/// σ = 5/4, 5/π, 105/(16π); f'' = −12(1 − q)(1 − 3q), q* = 1/3.
#[derive(Debug, Clone, Copy, Default)]
pub struct Lucy;

impl Kernel for Lucy {
    fn name(&self) -> &'static str {
        "lucy"
    }
    fn zeta(&self) -> f64 {
        1.0
    }
    fn f(&self, _dim: usize, q: f64) -> f64 {
        quartic(0, q)
    }
    fn df(&self, _dim: usize, q: f64) -> f64 {
        quartic(1, q)
    }
    fn d2f(&self, _dim: usize, q: f64) -> f64 {
        quartic(2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        quartic_sigma(dim)
    }
    fn inflection(&self, _dim: usize) -> f64 {
        1.0 / 3.0
    }
    fn reference(&self) -> &'static str {
        "Lucy (1977) Astron. J. 82:1013; [T] eq. 2.13"
    }
    fn customary_h(&self) -> (f64, f64) {
        (1.5, 4.0)
    }
}
