//! Gaussian kernel truncated at ζ = 3 and renormalised.

use std::sync::OnceLock;

use super::{Kernel, dim_index, numeric};

/// Truncation radius in units of h.
const ZETA: f64 = 3.0;

/// Gaussian f = exp(−q²) for q < 3, f = 0 for q ≥ 3 (Gingold & Monaghan 1977).
///
/// Truncation leaves a jump of e⁻⁹ ≈ 1.2·10⁻⁴ at q = 3; σ_d normalises the truncated kernel:
/// σ_1 = 1/(√π erf 3), σ_2 = 1/(π(1 − e⁻⁹)), σ_3 = 1/(π(√π erf 3 − 6e⁻⁹)), i.e.
/// 0.5642020470513833, 0.3183491735929349, 0.1796661482180872. They are computed once by
/// Gauss–Legendre quadrature (std has no erf) and cached. q* = 1/√2.
#[derive(Debug, Clone, Copy, Default)]
pub struct Gaussian;

impl Kernel for Gaussian {
    fn name(&self) -> &'static str {
        "gaussian"
    }
    fn zeta(&self) -> f64 {
        ZETA
    }
    fn f(&self, _dim: usize, q: f64) -> f64 {
        let q = q.abs();
        if q >= ZETA { 0.0 } else { (-q * q).exp() }
    }
    fn df(&self, _dim: usize, q: f64) -> f64 {
        let q = q.abs();
        if q >= ZETA {
            0.0
        } else {
            -2.0 * q * (-q * q).exp()
        }
    }
    fn d2f(&self, _dim: usize, q: f64) -> f64 {
        let q = q.abs();
        if q >= ZETA {
            0.0
        } else {
            (4.0 * q * q - 2.0) * (-q * q).exp()
        }
    }
    fn sigma(&self, dim: usize) -> f64 {
        static SIGMA: OnceLock<[f64; 3]> = OnceLock::new();
        SIGMA.get_or_init(|| numeric::sigma_by_quadrature(|q| self.f(1, q), ZETA))[dim_index(dim)]
    }
    /// f'' = (4q² − 2) e^(−q²): q* = 1/√2.
    fn inflection(&self, _dim: usize) -> f64 {
        std::f64::consts::FRAC_1_SQRT_2
    }
    fn reference(&self) -> &'static str {
        "Gingold & Monaghan (1977) MNRAS 181:375; truncated at 3h ([T] eq. 2.15)"
    }
    fn customary_h(&self) -> (f64, f64) {
        (0.8, 1.4)
    }
}
