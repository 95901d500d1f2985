//! Schoenberg B-spline kernels M4 (cubic), M5 (quartic), M6 (quintic).
//!
//! Each is written in truncated powers, f(q) = Σ_j c_j (a_j − q)₊^p for q ≥ 0, which gives
//! f' = −p Σ c_j (a_j − q)₊^(p−1) and f'' = p(p−1) Σ c_j (a_j − q)₊^(p−2) directly. The knots
//! a_j are the piece boundaries; the largest is ζ.

use std::sync::OnceLock;

use super::{Kernel, dim_index, numeric};

/// f(q) = Σ_j c_j (a_j − q)₊^p with terms `(a_j, c_j)`, largest knot first (= ζ).
struct TruncatedPowers {
    p: i32,
    terms: &'static [(f64, f64)],
}

impl TruncatedPowers {
    /// The `order`-th derivative (0, 1 or 2) of f at |q|; zero for |q| ≥ ζ.
    fn eval(&self, order: i32, q: f64) -> f64 {
        let q = q.abs();
        if q >= self.terms[0].0 {
            return 0.0;
        }
        let p = self.p;
        let (e, scale) = match order {
            0 => (p, 1.0),
            1 => (p - 1, -f64::from(p)),
            _ => (p - 2, f64::from(p * (p - 1))),
        };
        let sum: f64 = self
            .terms
            .iter()
            .filter(|&&(a, _)| q < a)
            .map(|&(a, c)| c * (a - q).powi(e))
            .sum();
        scale * sum
    }
}

/// ¼(2 − q)³ − (1 − q)³₊ = 1 − (3/2)q² + (3/4)q³ on [0, 1).
const M4_POWERS: TruncatedPowers = TruncatedPowers {
    p: 3,
    terms: &[(2.0, 0.25), (1.0, -1.0)],
};
/// (5/2 − q)⁴ − 5(3/2 − q)⁴₊ + 10(1/2 − q)⁴₊.
const M5_POWERS: TruncatedPowers = TruncatedPowers {
    p: 4,
    terms: &[(2.5, 1.0), (1.5, -5.0), (0.5, 10.0)],
};
/// (3 − q)⁵ − 6(2 − q)⁵₊ + 15(1 − q)⁵₊.
const M6_POWERS: TruncatedPowers = TruncatedPowers {
    p: 5,
    terms: &[(3.0, 1.0), (2.0, -6.0), (1.0, 15.0)],
};

/// Cubic B-spline M4 (Monaghan & Lattanzio 1985), ζ = 2:
/// f = 1 − (3/2)q² + (3/4)q³ on [0, 1), ¼(2 − q)³ on [1, 2).
/// σ = 2/3, 10/(7π), 1/π. C², piecewise-linear f''; q* = 2/3 in every dimension.
#[derive(Debug, Clone, Copy, Default)]
pub struct M4;

impl Kernel for M4 {
    fn name(&self) -> &'static str {
        "m4"
    }
    fn zeta(&self) -> f64 {
        2.0
    }
    fn f(&self, _dim: usize, q: f64) -> f64 {
        M4_POWERS.eval(0, q)
    }
    fn df(&self, _dim: usize, q: f64) -> f64 {
        M4_POWERS.eval(1, q)
    }
    fn d2f(&self, _dim: usize, q: f64) -> f64 {
        M4_POWERS.eval(2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        use std::f64::consts::PI;
        [2.0 / 3.0, 10.0 / (7.0 * PI), 1.0 / PI][dim_index(dim)]
    }
    /// f'' = −3 + (9/2)q on [0, 1): q* = 2/3.
    fn inflection(&self, _dim: usize) -> f64 {
        2.0 / 3.0
    }
    fn reference(&self) -> &'static str {
        "Monaghan & Lattanzio (1985) A&A 149:135; [B98] eq. 26; [T] eq. 2.14"
    }
    fn customary_h(&self) -> (f64, f64) {
        (1.0, 2.0)
    }
}

/// Quartic B-spline M5 (Schoenberg 1946), ζ = 5/2:
/// f = (5/2 − q)⁴ − 5(3/2 − q)⁴₊ + 10(1/2 − q)⁴₊.
/// σ = 1/24, 96/(1199π), 1/(20π). C³; q* = (5 − √5)/4 in every dimension.
#[derive(Debug, Clone, Copy, Default)]
pub struct M5;

impl Kernel for M5 {
    fn name(&self) -> &'static str {
        "m5"
    }
    fn zeta(&self) -> f64 {
        2.5
    }
    fn f(&self, _dim: usize, q: f64) -> f64 {
        M5_POWERS.eval(0, q)
    }
    fn df(&self, _dim: usize, q: f64) -> f64 {
        M5_POWERS.eval(1, q)
    }
    fn d2f(&self, _dim: usize, q: f64) -> f64 {
        M5_POWERS.eval(2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        use std::f64::consts::PI;
        [1.0 / 24.0, 96.0 / (1199.0 * PI), 1.0 / (20.0 * PI)][dim_index(dim)]
    }
    /// f'' = 12(−5 + 10q − 4q²) on [1/2, 3/2) (f'' < 0 on [0, 1/2)): q* = (5 − √5)/4.
    fn inflection(&self, _dim: usize) -> f64 {
        (5.0 - 5.0_f64.sqrt()) / 4.0
    }
    fn reference(&self) -> &'static str {
        "Schoenberg (1946) Q. Appl. Math. 4:45; Monaghan (2005) Rep. Prog. Phys. 68:1703"
    }
    fn customary_h(&self) -> (f64, f64) {
        (0.9, 1.6)
    }
}

/// Quintic B-spline M6 (Schoenberg 1946; Morris et al. 1997), ζ = 3:
/// f = (3 − q)⁵ − 6(2 − q)⁵₊ + 15(1 − q)⁵₊.
/// σ = 1/120, 7/(478π), 1/(120π). C⁴; q* ≈ 0.759298 (root of a cubic on [0, 1), bisected).
#[derive(Debug, Clone, Copy, Default)]
pub struct M6;

impl Kernel for M6 {
    fn name(&self) -> &'static str {
        "m6"
    }
    fn zeta(&self) -> f64 {
        3.0
    }
    fn f(&self, _dim: usize, q: f64) -> f64 {
        M6_POWERS.eval(0, q)
    }
    fn df(&self, _dim: usize, q: f64) -> f64 {
        M6_POWERS.eval(1, q)
    }
    fn d2f(&self, _dim: usize, q: f64) -> f64 {
        M6_POWERS.eval(2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        use std::f64::consts::PI;
        [1.0 / 120.0, 7.0 / (478.0 * PI), 1.0 / (120.0 * PI)][dim_index(dim)]
    }
    fn inflection(&self, _dim: usize) -> f64 {
        static Q: OnceLock<f64> = OnceLock::new();
        *Q.get_or_init(|| numeric::first_root(|q| M6_POWERS.eval(2, q), 0.0, 3.0))
    }
    fn reference(&self) -> &'static str {
        "Schoenberg (1946) Q. Appl. Math. 4:45; Morris, Fox & Zhu (1997) J. Comput. Phys. 136:214"
    }
    fn customary_h(&self) -> (f64, f64) {
        (0.8, 1.4)
    }
}
