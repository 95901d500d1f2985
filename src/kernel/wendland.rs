//! Wendland kernels C2, C4, C6 with the usual SPH scaling ζ = 2: f(q) = ψ(t), t = q/2.
//!
//! The Wendland function depends on the dimension (Dehnen & Aly 2012, Table 1): 1D uses
//! ψ_{2,k}, 2D and 3D use ψ_{3,k}. The derivatives below are the factored forms of ψ' and ψ''
//! (exact, no cancellation near t = 1); f' = ψ'(t)/2 and f'' = ψ''(t)/4.
//! σ_d = 1 / (|S^(d−1)| 2^d ∫_0^1 t^(d−1) ψ(t) dt), exact rationals (1D) and rationals/π.

use std::f64::consts::PI;
use std::sync::OnceLock;

use super::{Kernel, dim_index, numeric};

/// Support radius in units of h.
const ZETA: f64 = 2.0;

/// ψ, ψ' and ψ'' of one Wendland function on t ∈ [0, 1).
struct Psi {
    v: fn(f64) -> f64,
    d1: fn(f64) -> f64,
    d2: fn(f64) -> f64,
}

/// ψ_{2,1} = (1 − t)³(1 + 3t).
const PSI_2_1: Psi = Psi {
    v: |t| (1.0 - t).powi(3) * (1.0 + 3.0 * t),
    d1: |t| -12.0 * t * (1.0 - t).powi(2),
    d2: |t| -12.0 * (1.0 - t) * (1.0 - 3.0 * t),
};
/// ψ_{2,2} = (1 − t)⁵(1 + 5t + 8t²).
const PSI_2_2: Psi = Psi {
    v: |t| (1.0 - t).powi(5) * (1.0 + t * (5.0 + 8.0 * t)),
    d1: |t| -14.0 * t * (1.0 - t).powi(4) * (1.0 + 4.0 * t),
    d2: |t| 14.0 * (1.0 - t).powi(3) * (t * (24.0 * t - 3.0) - 1.0),
};
/// ψ_{2,3} = (1 − t)⁷(1 + 7t + 19t² + 21t³).
const PSI_2_3: Psi = Psi {
    v: |t| (1.0 - t).powi(7) * (1.0 + t * (7.0 + t * (19.0 + 21.0 * t))),
    d1: |t| -6.0 * t * (1.0 - t).powi(6) * (3.0 + t * (18.0 + 35.0 * t)),
    d2: |t| 18.0 * (1.0 - t).powi(5) * (t * (t * (105.0 * t + 13.0) - 5.0) - 1.0),
};
/// ψ_{3,1} = (1 − t)⁴(1 + 4t).
const PSI_3_1: Psi = Psi {
    v: |t| (1.0 - t).powi(4) * (1.0 + 4.0 * t),
    d1: |t| -20.0 * t * (1.0 - t).powi(3),
    d2: |t| 20.0 * (1.0 - t).powi(2) * (4.0 * t - 1.0),
};
/// ψ_{3,2} = (1 − t)⁶(1 + 6t + 35t²/3).
const PSI_3_2: Psi = Psi {
    v: |t| (1.0 - t).powi(6) * (1.0 + t * (6.0 + 35.0 / 3.0 * t)),
    d1: |t| -56.0 / 3.0 * t * (1.0 - t).powi(5) * (1.0 + 5.0 * t),
    d2: |t| 56.0 / 3.0 * (1.0 - t).powi(4) * (t * (35.0 * t - 4.0) - 1.0),
};
/// ψ_{3,3} = (1 − t)⁸(1 + 8t + 25t² + 32t³).
const PSI_3_3: Psi = Psi {
    v: |t| (1.0 - t).powi(8) * (1.0 + t * (8.0 + t * (25.0 + 32.0 * t))),
    d1: |t| -22.0 * t * (1.0 - t).powi(7) * (1.0 + t * (7.0 + 16.0 * t)),
    d2: |t| 22.0 * (1.0 - t).powi(6) * (t * (t * (160.0 * t + 15.0) - 6.0) - 1.0),
};

/// The `order`-th q-derivative (0, 1, 2) of f(q) = ψ(q/2), ψ = `psi1d` in 1D, else `psi`.
fn eval(psi1d: &Psi, psi: &Psi, dim: usize, order: u8, q: f64) -> f64 {
    let q = q.abs();
    if q >= ZETA {
        return 0.0;
    }
    let p = if dim_index(dim) == 0 { psi1d } else { psi };
    let t = 0.5 * q;
    match order {
        0 => (p.v)(t),
        1 => 0.5 * (p.d1)(t),
        _ => 0.25 * (p.d2)(t),
    }
}

const REFERENCE: &str =
    "Wendland (1995) Adv. Comput. Math. 4:389; Dehnen & Aly (2012) MNRAS 425:1068";

/// Wendland C2, ζ = 2: f = ψ_{2,1}(q/2) in 1D, ψ_{3,1}(q/2) in 2D and 3D.
/// σ = 5/8, 7/(4π), 21/(16π); q* = 2/3 (1D), 1/2 (2D, 3D).
#[derive(Debug, Clone, Copy, Default)]
pub struct WendlandC2;

impl Kernel for WendlandC2 {
    fn name(&self) -> &'static str {
        "wendland-c2"
    }
    fn zeta(&self) -> f64 {
        ZETA
    }
    fn f(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_1, &PSI_3_1, dim, 0, q)
    }
    fn df(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_1, &PSI_3_1, dim, 1, q)
    }
    fn d2f(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_1, &PSI_3_1, dim, 2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        [5.0 / 8.0, 7.0 / (4.0 * PI), 21.0 / (16.0 * PI)][dim_index(dim)]
    }
    /// ψ''_{2,1} vanishes at t = 1/3, ψ''_{3,1} at t = 1/4.
    fn inflection(&self, dim: usize) -> f64 {
        if dim_index(dim) == 0 { 2.0 / 3.0 } else { 0.5 }
    }
    fn reference(&self) -> &'static str {
        REFERENCE
    }
    fn customary_h(&self) -> (f64, f64) {
        (1.0, 2.0)
    }
}

/// Wendland C4, ζ = 2: f = ψ_{2,2}(q/2) in 1D, ψ_{3,2}(q/2) in 2D and 3D.
/// σ = 3/4, 9/(4π), 495/(256π); q* = (3 + √105)/24 (1D), 2(2 + √39)/35 (2D, 3D).
#[derive(Debug, Clone, Copy, Default)]
pub struct WendlandC4;

impl Kernel for WendlandC4 {
    fn name(&self) -> &'static str {
        "wendland-c4"
    }
    fn zeta(&self) -> f64 {
        ZETA
    }
    fn f(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_2, &PSI_3_2, dim, 0, q)
    }
    fn df(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_2, &PSI_3_2, dim, 1, q)
    }
    fn d2f(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_2, &PSI_3_2, dim, 2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        [3.0 / 4.0, 9.0 / (4.0 * PI), 495.0 / (256.0 * PI)][dim_index(dim)]
    }
    /// Positive roots of 24t² − 3t − 1 (1D) and 35t² − 4t − 1 (2D, 3D), q* = 2t.
    fn inflection(&self, dim: usize) -> f64 {
        if dim_index(dim) == 0 {
            (3.0 + 105.0_f64.sqrt()) / 24.0
        } else {
            2.0 * (2.0 + 39.0_f64.sqrt()) / 35.0
        }
    }
    fn reference(&self) -> &'static str {
        REFERENCE
    }
    fn customary_h(&self) -> (f64, f64) {
        (1.0, 2.0)
    }
}

/// Wendland C6, ζ = 2: f = ψ_{2,3}(q/2) in 1D, ψ_{3,3}(q/2) in 2D and 3D.
/// σ = 55/64, 39/(14π), 1365/(512π); q* ≈ 0.479967 (1D), 0.430572 (2D, 3D), bisected.
#[derive(Debug, Clone, Copy, Default)]
pub struct WendlandC6;

impl Kernel for WendlandC6 {
    fn name(&self) -> &'static str {
        "wendland-c6"
    }
    fn zeta(&self) -> f64 {
        ZETA
    }
    fn f(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_3, &PSI_3_3, dim, 0, q)
    }
    fn df(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_3, &PSI_3_3, dim, 1, q)
    }
    fn d2f(&self, dim: usize, q: f64) -> f64 {
        eval(&PSI_2_3, &PSI_3_3, dim, 2, q)
    }
    fn sigma(&self, dim: usize) -> f64 {
        [55.0 / 64.0, 39.0 / (14.0 * PI), 1365.0 / (512.0 * PI)][dim_index(dim)]
    }
    /// First root of 105t³ + 13t² − 5t − 1 (1D) or 160t³ + 15t² − 6t − 1 (2D, 3D), q* = 2t.
    fn inflection(&self, dim: usize) -> f64 {
        static Q: OnceLock<[f64; 2]> = OnceLock::new();
        let q =
            Q.get_or_init(|| [1, 3].map(|d| numeric::first_root(|q| self.d2f(d, q), 0.0, ZETA)));
        q[dim_index(dim).min(1)]
    }
    fn reference(&self) -> &'static str {
        REFERENCE
    }
    fn customary_h(&self) -> (f64, f64) {
        (1.0, 2.0)
    }
}
