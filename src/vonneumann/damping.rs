//! Damping of the mechanical branches of a dissipative linearisation (artificial viscosity,
//! density diffusion): the damping rate Re s and damping ratio ξ = −Re s/|s| of each branch from
//! the exact eigenvalues s of J(k), and the critical step of central-difference integration
//! with damping, \[B00\] eq 120.
//!
//! ## Modal (ω, ξ) of an eigenvalue
//! A damped oscillator x'' + 2ξω x' + ω² x = 0 has the eigenvalues s = ω(−ξ ± i√(1 − ξ²)) when
//! underdamped, so ω = |s| and ξ = −Re s/|s|; when overdamped (ξ > 1) two real eigenvalues
//! s₁ s₂ = ω², s₁ + s₂ = −2ξω.
//!
//! ## Which eigenvalue belongs to which branch (the matching rule)
//! J(k) has 2·D mechanical eigenvalues (D position and D velocity dofs per cell) and one per
//! auxiliary dof (density, stresses: 0 at rest when they only follow the velocity; real and
//! negative with density diffusion). An eigenvalue is an *upper member of an oscillating pair*
//! when Im s > [`OSC_TOL`]·max(1, max|s|), real when |Im s| is below that (the rounding of the
//! zero and real eigenvalues is far below). When there are exactly as many upper members as branches
//! with ω > [`OSC_TOL`]·max(1, max|s|), both are sorted — the upper members by |s| (= ω of the oscillator, whatever its
//! damping), the branches by ω_b = √ω²_b of the mechanical reduction — and paired in order.
//! Otherwise (an overdamped branch shows as two real eigenvalues, a growing one as a real
//! positive one, an auxiliary dof may oscillate) the matching is ambiguous and every branch of
//! that mode gets `None` (printed "-", JSON null). A branch of zero frequency (the transverse
//! branch of a fluid) has only real eigenvalues and is always `None`.

use super::amplification::Modes;
use super::classify::GROWTH_TOL;
use crate::error::Result;
use num_complex::Complex64;

/// Relative tolerance on Im s for an eigenvalue to count as oscillating ([module docs](self)).
pub const OSC_TOL: f64 = 1e-9;

/// The upper members (Im s > 0) of the oscillating pairs among `eigs`, by the rule of the
/// module docs, sorted by |s|.
pub fn upper_members(eigs: &[Complex64]) -> Vec<Complex64> {
    let scale = eigs.iter().map(|s| s.norm()).fold(1.0, f64::max);
    let mut up: Vec<Complex64> = eigs
        .iter()
        .copied()
        .filter(|s| s.im > OSC_TOL * scale)
        .collect();
    up.sort_by(|a, b| a.norm().total_cmp(&b.norm()));
    up
}

/// Damping rate Re s (c/Δx, ≤ 0 when damped) of each mechanical branch with squared
/// frequencies `omega2` (in any order; the result is in the same order), from the eigenvalues
/// `eigs` of J at the same mode. `None` for every branch when the matching is ambiguous (rule in
/// the module docs).
pub fn branch_damping(eigs: &[Complex64], omega2: &[f64]) -> Vec<Option<f64>> {
    branch_eigenvalues(eigs, omega2)
        .into_iter()
        .map(|s| s.map(|s| s.re))
        .collect()
}

/// The eigenvalue (upper member) matched to each branch of `omega2`, or `None` for all when the
/// matching is ambiguous.
pub fn branch_eigenvalues(eigs: &[Complex64], omega2: &[f64]) -> Vec<Option<Complex64>> {
    let up = upper_members(eigs);
    let mut out = vec![None; omega2.len()];
    // the branches that oscillate: ω > OSC_TOL·max(1, max|s|), the threshold of the upper
    // members; a zero-frequency branch (the transverse branch of a fluid) has only real
    // eigenvalues and stays None
    let scale = eigs.iter().map(|s| s.norm()).fold(1.0, f64::max);
    let mut order: Vec<usize> = (0..omega2.len())
        .filter(|&b| omega2[b] > (OSC_TOL * scale).powi(2))
        .collect();
    if up.len() != order.len() {
        return out;
    }
    order.sort_by(|&a, &b| omega2[a].total_cmp(&omega2[b]));
    for (rank, &b) in order.iter().enumerate() {
        out[b] = Some(up[rank]);
    }
    out
}

/// Damping ratio ξ = −Re s/|s| of an eigenvalue (0 for s = 0).
pub fn damping_ratio(s: Complex64) -> f64 {
    let n = s.norm();
    if n > 0.0 { -s.re / n } else { 0.0 }
}

/// \[B00\] eq 120 for one mode: (2/ω)(√(ξ² + 1) − ξ), written 2/(ω(√(ξ² + 1) + ξ)) (no
/// cancellation at large ξ); ∞ for ω = 0. Exact for the leapfrog whose damping force uses the
/// lagged velocity v^{n−½} (`verlet-lagged`): its characteristic polynomial on the oscillator is
/// λ² − (2 − 2ξωΔt − ω²Δt²)λ + (1 − 2ξωΔt), stable (Jury) iff ω²Δt² + 4ξωΔt ≤ 4 and
/// ξωΔt ≤ 1; the first is eq 120 and implies the second. (The paper prints max_i; the bound is
/// the smallest over the modes.)
pub fn eq120(omega: f64, xi: f64) -> f64 {
    if omega > 0.0 {
        2.0 / (omega * ((xi * xi + 1.0).sqrt() + xi))
    } else {
        f64::INFINITY
    }
}

/// The limits of one J(k) for eq 120: the modal (ω, ξ) of every second-order mode among the
/// eigenvalues `eigs`, and the first-order decays left over. Each upper member s of an
/// oscillating pair gives (|s|, −Re s/|s|); the real eigenvalues with |s| > [`OSC_TOL`]·max(1,
/// max|s|) (overdamped pairs, diffusing auxiliary dofs) are paired as one overdamped oscillator
/// ω = √(s₁s₂), ξ = −(s₁ + s₂)/(2ω) when there are exactly two of the same sign; otherwise each
/// is returned as a first-order decay rate |s| (for [`critical_dt_eq120`]: a decay ṡ = s
/// advanced by forward Euler, as every scheme advances an auxiliary dof, is stable for
/// Δt ≤ 2/|s|).
pub fn modal_pairs(eigs: &[Complex64]) -> (Vec<(f64, f64)>, Vec<f64>) {
    let scale = eigs.iter().map(|s| s.norm()).fold(1.0, f64::max);
    let pairs: Vec<(f64, f64)> = upper_members(eigs)
        .into_iter()
        .map(|s| (s.norm(), damping_ratio(s)))
        .collect();
    let real: Vec<f64> = eigs
        .iter()
        .filter(|s| s.im.abs() <= OSC_TOL * scale && s.norm() > OSC_TOL * scale)
        .map(|s| s.re)
        .collect();
    if real.len() == 2 && real[0] * real[1] > 0.0 {
        let w = (real[0] * real[1]).sqrt();
        let mut pairs = pairs;
        pairs.push((w, -(real[0] + real[1]) / (2.0 * w)));
        (pairs, Vec::new())
    } else {
        (pairs, real.iter().map(|s| s.abs()).collect())
    }
}

/// \[B00\] eq 120 over the modes `ks` of `lin`: min over every mode whose eigenvalues do not grow
/// (max Re s ≤ [`GROWTH_TOL`], as in [`super::amplification::step_stability`]) of [`eq120`] of
/// every modal (ω, ξ) of [`modal_pairs`], and of 2/|s| for its lone first-order decays; Δx/c.
/// ∞ when no mode oscillates or decays.
pub fn critical_dt_eq120<L: Modes>(lin: &L, ks: &[L::K]) -> Result<f64> {
    let mut best = f64::INFINITY;
    for &k in ks {
        let ev = lin.eigenvalues(k)?;
        if ev.iter().any(|s| s.re > GROWTH_TOL) {
            continue;
        }
        let (pairs, decays) = modal_pairs(&ev);
        for (w, xi) in pairs {
            best = best.min(eq120(w, xi));
        }
        for a in decays {
            best = best.min(2.0 / a);
        }
    }
    Ok(best)
}
