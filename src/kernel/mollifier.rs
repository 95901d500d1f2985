//! The modified mollifier of the thesis \[T\], eq. (2.19).

use std::sync::OnceLock;

use super::{Kernel, dim_index, numeric};

/// Modified mollifier, ζ = 1: f = exp(−1/(1 − q²)) (1 − q²)⁸ for q < 1 (\[T\] eq. 2.19).
///
/// C^∞ with compact support and close to a Gaussian of width h/3 near the centre. With
/// s = 1 − q²: f' = −2q s⁶ (9 − 8q²) e^(−1/s) and
/// f'' = 2 s⁴ (120q⁶ − 277q⁴ + 168q² − 9) e^(−1/s) (thesis digest §8.1). As q → 1 the factor
/// e^(−1/s) underflows to 0 before s⁴ does, so all three are finite and reach 0 smoothly.
///
/// There is no closed-form integral: σ_d is computed once by Gauss–Legendre quadrature and
/// cached; σ = 4.80967697848816, 8.74622021174746, 16.3222083037511 (the digest's
/// G_1, G_2, G_3). q* = 0.243314842884236, the only root of f'' in (0, 1), bisected.
#[derive(Debug, Clone, Copy, Default)]
pub struct Mollifier;

impl Mollifier {
    /// s = 1 − q² (computed as (1 − q)(1 + q)) and e^(−1/s), or `None` for |q| ≥ 1.
    fn parts(q: f64) -> Option<(f64, f64, f64)> {
        let q = q.abs();
        if q >= 1.0 {
            return None;
        }
        let s = (1.0 - q) * (1.0 + q);
        Some((q, s, (-1.0 / s).exp()))
    }
}

impl Kernel for Mollifier {
    fn name(&self) -> &'static str {
        "mollifier"
    }
    fn zeta(&self) -> f64 {
        1.0
    }
    fn f(&self, _dim: usize, q: f64) -> f64 {
        Self::parts(q).map_or(0.0, |(_, s, e)| e * s.powi(8))
    }
    fn df(&self, _dim: usize, q: f64) -> f64 {
        Self::parts(q).map_or(0.0, |(q, s, e)| {
            -2.0 * q * s.powi(6) * (9.0 - 8.0 * q * q) * e
        })
    }
    fn d2f(&self, _dim: usize, q: f64) -> f64 {
        Self::parts(q).map_or(0.0, |(q, s, e)| {
            let q2 = q * q;
            2.0 * s.powi(4) * (q2 * (q2 * (120.0 * q2 - 277.0) + 168.0) - 9.0) * e
        })
    }
    fn sigma(&self, dim: usize) -> f64 {
        static SIGMA: OnceLock<[f64; 3]> = OnceLock::new();
        SIGMA.get_or_init(|| numeric::sigma_by_quadrature(|q| self.f(1, q), 1.0))[dim_index(dim)]
    }
    fn inflection(&self, _dim: usize) -> f64 {
        static Q: OnceLock<f64> = OnceLock::new();
        *Q.get_or_init(|| numeric::first_root(|q| self.d2f(1, q), 0.0, 1.0))
    }
    fn reference(&self) -> &'static str {
        "[T] eq. 2.19, modified mollifier (thesis 004, digest §1.5, §8.1)"
    }
    fn customary_h(&self) -> (f64, f64) {
        (1.5, 4.0)
    }
}
