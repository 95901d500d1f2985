//! Classification of unstable and marginal branches (SPEC §5.3, following \[B00 §4\]).
//!
//! | kind | criterion |
//! |---|---|
//! | `material` | C̄ = C + σ ≤ 0: the continuum itself is unstable (\[B00\] eq 33) |
//! | `tensile` / `compressive` | growth (ω² < 0) with C̄ > 0 that disappears when the pre-stress is set to zero |
//! | `rank-deficiency` | ω = 0 at κ ≠ 0 (zero-energy / hourglass mode, secular growth), or growth that persists at zero stress (the discrete operator itself is indefinite) |
//! | `time-step` | semi-discrete stable but the leapfrog amplification |λ| > 1 |

use serde::Serialize;

/// Growth rates (c/Δx) at or below this are not growth.
pub const GROWTH_TOL: f64 = 1e-6;
/// |ω²| at or below this fraction of max|ω²| (and ≥ 0) is a zero-energy mode.
pub const ZERO_OMEGA2_TOL: f64 = 1e-10;

/// Kind of instability.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// Zero-energy (hourglass) mode or a stress-independent indefinite operator.
    RankDeficiency,
    /// Stress–kernel interaction in tension.
    Tensile,
    /// Stress–kernel interaction in compression.
    Compressive,
    /// Continuum (material) instability, C̄ ≤ 0.
    Material,
    /// Time step too large for the integrator.
    TimeStep,
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
    }
}
