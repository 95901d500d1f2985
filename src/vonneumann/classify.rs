//! Classification of unstable and marginal branches (SPEC §5.3, following \[B00 §4\]).
//!
//! | kind | criterion |
//! |---|---|
//! | `material` | C̄ = C + σ ≤ 0: the continuum itself is unstable (\[B00\] eq 33) |
//! | `tensile` / `compressive` | growth (ω² < 0) with C̄ > 0 that disappears when the pre-stress is set to zero |
//! | `hourglass` | (D ≥ 2, elastic) the `tensile` / `compressive` growth on modes that are zero-energy at zero stress: the growing mode's polarisation has ω² ≈ 0 under the unstressed operator |
//! | `rank-deficiency` | ω = 0 at κ ≠ 0 (zero-energy / hourglass mode, secular growth, growth rate 0); never a growing branch |
//! | `indefinite` | growth that persists at zero stress: the discrete operator itself (stiffness, or the stabilised mass of least squares) is indefinite; where ω² changes sign through ±∞ between two grid points the mass symbol vanished there, reported as `pole_at` |
//! | `time-step` | semi-discrete stable but the leapfrog amplification |λ| > 1 |
//!
//! A zero-energy mode needs ω² ≈ 0 relative to max|ω²| *and* relative to the long-wave
//! acoustic value C̄κ² at that κ, so that the acoustic zero at κ → 0 of a fine grid is not
//! reported as one.

use crate::error::Result;
use serde::Serialize;

/// Growth rates (c/Δx) at or below this are not growth.
pub const GROWTH_TOL: f64 = 1e-6;
/// |ω²| at or below this fraction of max|ω²| (and ≥ 0) is a zero-energy mode.
pub const ZERO_OMEGA2_TOL: f64 = 1e-10;

/// Kind of instability.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// Zero-energy (hourglass) mode: ω = 0 at κ ≠ 0 (no exponential growth).
    RankDeficiency,
    /// Growth, under a pre-stress, of modes whose stiffness vanishes at zero stress: a
    /// zero-energy (hourglass) mode that the stress drives (it grows at any stress of that
    /// sign, however small).
    Hourglass,
    /// Growth without stress: the discrete operator itself is indefinite.
    Indefinite,
    /// Stress–kernel interaction in tension.
    Tensile,
    /// Stress–kernel interaction in compression.
    Compressive,
    /// Continuum (material) instability, C̄ ≤ 0.
    Material,
    /// Time step too large for the integrator.
    TimeStep,
    /// The integrator amplifies at every Δt (weak instability: RK2, Euler, lagged velocity …).
    Integrator,
}

/// One unstable or marginal branch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Instability {
    /// Kind.
    pub kind: Kind,
    /// Smallest κΔx of the branch on the grid.
    pub kappa_min: f64,
    /// Largest κΔx of the branch on the grid.
    pub kappa_max: f64,
    /// Largest growth rate on the branch (c/Δx); 0 for zero-energy modes (they grow linearly).
    pub growth_rate: f64,
    /// κΔx where the growth rate is largest.
    pub kappa_at_max: f64,
    /// κΔx where ω² passes through ±∞ (a vanishing mass symbol), if it does on this branch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pole_at: Option<f64>,
}

/// Contiguous runs of `true` in `flags`, as index ranges.
pub fn runs(flags: &[bool]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, &f) in flags.iter().enumerate() {
        match (f, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                out.push((s, i - 1));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, flags.len() - 1));
    }
    out
}

/// Builds an [`Instability`] for the grid run `(a, b)` with rates `rate`.
pub fn branch(kind: Kind, kappas: &[f64], rate: &[f64], (a, b): (usize, usize)) -> Instability {
    let (mut g, mut km) = (0.0, kappas[a]);
    for i in a..=b {
        if rate[i] > g {
            g = rate[i];
            km = kappas[i];
        }
    }
    Instability {
        kind,
        kappa_min: kappas[a],
        kappa_max: kappas[b],
        growth_rate: g,
        kappa_at_max: km,
        pole_at: None,
    }
}

/// The kind of a growing branch (table above), in every dimension: `material` when the continuum
/// itself is unstable; otherwise `indefinite` if σ̄ = 0 or the branch also grows at zero stress
/// (`growth_at_zero_stress`, evaluated only for σ̄ ≠ 0), else `tensile` / `compressive` by the
/// sign of σ̄.
pub fn growth_kind(
    material: bool,
    stress: f64,
    growth_at_zero_stress: impl FnOnce() -> Result<f64>,
) -> Result<Kind> {
    Ok(if material {
        Kind::Material
    } else if stress == 0.0 || growth_at_zero_stress()? > GROWTH_TOL {
        Kind::Indefinite
    } else if stress > 0.0 {
        Kind::Tensile
    } else {
        Kind::Compressive
    })
}
