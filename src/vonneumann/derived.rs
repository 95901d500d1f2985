//! Closed forms derived in this project (not printed in the papers) for the SPH forms whose
//! linearisation the papers simplify. They are written in lattice sums of the uniform-lattice
//! shape function and are independent of the numeric engine; the derivations are in
//! `analysis/ERRATA.md` (items E1–E3).
//!
//! Notation (Δx = 1, V = 1, ρ = 1, C = 1, σ̄ = σ/C, C̃ = 1 + σ̄):
//! `S1(κ) = Σ_j φ'(j) sin κj`, `S2(κ) = Σ_j φ''(j)·2 sin²(κj/2)`, `M1 = −Σ_j j φ'(j)` (the
//! discrete first moment; 1 for a linearly consistent gradient). φ is the `sph` lattice shape
//! for the SPH forms and the corrected shape for the local part.

/// Lattice sums of a uniform-lattice shape function.
#[derive(Clone, Copy, Debug)]
pub struct LatticeSums {
    /// S1(κ).
    pub s1: f64,
    /// S2(κ).
    pub s2: f64,
    /// Discrete first moment M1 = −Σ_j j φ'(j).
    pub m1: f64,
}

impl LatticeSums {
    /// Computes S1, S2 (via [`super::closed_form::lattice_sums`]) and M1 at κ for the lattice
    /// shape `phi` (`[φ, φ', φ'']` at x) with support radius `support` (units of Δx).
    pub fn new(phi: &dyn Fn(f64) -> [f64; 3], support: f64, kappa: f64) -> Self {
        let b = super::closed_form::lattice_sums(phi, support, kappa);
        let r = support.ceil() as i64 + 1;
        let m1 = -(-r..=r).map(|j| j as f64 * phi(j as f64)[1]).sum::<f64>();
        Self {
            s1: b.s1_master,
            s2: b.s2_master,
            m1,
        }
    }
}

/// `classical` (Monaghan's sum form, continuity density, `sph` shape):
/// ω² = C̃ S1² − 2σ̄ (S2 − S1²). Twice the stress term of \[B00\] eq 74 (ERRATA E1).
pub fn classical_sum(s: LatticeSums, sigma_bar: f64) -> f64 {
    (1.0 + sigma_bar) * s.s1 * s.s1 - 2.0 * sigma_bar * (s.s2 - s.s1 * s.s1)
}

/// `nonlocal` (difference form): ω² = C̃ S1²; no stress–kernel term at all (ERRATA E2).
pub fn nonlocal_difference(s: LatticeSums, sigma_bar: f64) -> f64 {
    (1.0 + sigma_bar) * s.s1 * s.s1
}

/// `local` (corrected derivatives G_j = φ'(j)/M1 of the sph lattice shape):
/// ω² = C̃ (S1/M1)².
pub fn local_corrected(s: LatticeSums, sigma_bar: f64) -> f64 {
    (1.0 + sigma_bar) * (s.s1 / s.m1).powi(2)
}

/// `lnl` with partition c: ω² = (1 − c) C̃ S1² + c C̃ (S1/M1)².
pub fn lnl(s: LatticeSums, sigma_bar: f64, c: f64) -> f64 {
    (1.0 - c) * nonlocal_difference(s, sigma_bar) + c * local_corrected(s, sigma_bar)
}

/// `cll` with partition c (density from the mixed continuity equation, c_ρ = c):
/// ω² = (1 − c)[C̃ S1² − 2σ̄ S2 + 2σ̄ ((1 − c) S1² + c S1²/M1)] + c C̃ (S1/M1)².
pub fn cll(s: LatticeSums, sigma_bar: f64, c: f64) -> f64 {
    let (s1, m1) = (s.s1, s.m1);
    let dens = (1.0 - c) * s1 * s1 + c * s1 * s1 / m1;
    (1.0 - c) * ((1.0 + sigma_bar) * s1 * s1 - 2.0 * sigma_bar * s.s2 + 2.0 * sigma_bar * dens)
        + c * local_corrected(s, sigma_bar)
}
