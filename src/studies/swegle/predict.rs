//! The engine's predictions for a Swegle box: the fastest mode of the exact operator of the
//! finite particle set (by thick-restart Arnoldi; the dense eigenvalues up to
//! [`MAX_DENSE_BOX_DOFS`] free degrees of freedom when that finds no growing mode; the standing
//! modes the box admits where the operator is not the undamped one, or a larger box has no
//! resolvable growing mode) and the infinite lattice, with the fastest modes.

use super::config::{MAX_DENSE_BOX_DOFS, SwegleConfig, infinite_grid};
use crate::analysis::box_prediction;
use crate::error::{Error, Result};
use crate::forms::{Material, ModelParams};
use crate::lattice::{Lattice, LatticeKind};
use crate::progress::Progress;
use crate::shape::KernelParams;
use crate::solver::run::Run;
use crate::studies::box_operator::{MAX_DENSE_DOFS, Start, box_growth, box_growth_iterative};
use crate::vonneumann::linearise::Bloch;
use num_complex::Complex64;
use serde::Serialize;
use std::f64::consts::PI;

/// A wave vector (κΔx per axis) and a branch's polarisation there.
type FastestMode<const D: usize> = ([f64; D], [Complex64; D]);

/// The largest growth rate (c/Δx) over the irreducible wedge π ≥ κ_1 ≥ … ≥ κ_D ≥ 0 of the
/// square / simple-cubic zone, sampled at spacing π/[`infinite_grid`]; with the wave vector
/// (κΔx) where it is reached and that branch's polarisation (None when nothing grows).
fn infinite_rate<const D: usize>(lin: &Bloch<D>) -> Result<(f64, Option<FastestMode<D>>)> {
    let n = infinite_grid(D);
    let mut g: f64 = 0.0;
    let mut at = None;
    for idx in 0..(n + 1).pow(D as u32) {
        let c = SwegleConfig::coords::<D>(n + 1, idx);
        if c.windows(2).any(|w| w[1] > w[0]) {
            continue;
        }
        let k = c.map(|i| PI * i as f64 / n as f64);
        let (gk, p) = lin.growth(k)?;
        if gk > g {
            g = gk;
            at = Some((k, p));
        }
    }
    Ok((g, at))
}

/// The engine's predictions for a Swegle configuration, computed without running it (the
/// same numbers [`run_swegle`](super::run_swegle) reports next to its measurement).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct SweglePrediction {
    /// Growth rate of the finite particle set (c/Δx).
    pub box_rate: f64,
    /// `dense-operator`, `iterative-operator` or `standing-modes` (as
    /// [`SwegleReport::box_method`](super::SwegleReport::box_method)).
    pub box_method: &'static str,
    /// Wave vector (κΔx per axis) of the fastest standing mode the box admits.
    pub box_kappa: Vec<f64>,
    /// Growth rate of the infinite lattice (c/Δx).
    pub infinite_rate: f64,
    /// Wave vector (κΔx per axis) of the infinite lattice's fastest mode (empty: none grows).
    pub infinite_kappa: Vec<f64>,
    /// Longitudinal fraction |p·κ̂|² of that mode's polarisation p (1: longitudinal, 0:
    /// transverse; NaN-free: 0 when nothing grows).
    pub infinite_longitudinal: f64,
}

/// The predictions of [`run_swegle`](super::run_swegle) without the time integration: the box
/// operator (or the box's standing modes) and the infinite lattice, with the fastest modes.
pub fn predict_swegle(cfg: &SwegleConfig) -> Result<SweglePrediction> {
    cfg.validate()?;
    match cfg.dim {
        3 => predict_d::<3>(cfg, &cfg.build::<3>()?, &()),
        _ => predict_d::<2>(cfg, &cfg.build::<2>()?, &()),
    }
}

/// [`predict_swegle`] for a built run (before it is stepped); `progress` may stop the
/// iterative eigenvalue search.
pub(super) fn predict_d<const D: usize>(
    cfg: &SwegleConfig,
    run: &Run<D>,
    progress: &dyn Progress,
) -> Result<SweglePrediction> {
    let unit = cfg.sound_speed() / cfg.dx; // c/Δx: normalisation of rates
    let nfree = cfg.size - 2 * cfg.layers;
    let lin_unit = Bloch::<D>::with_budget(
        ModelParams {
            kp: KernelParams {
                kernel: cfg.kernel,
                h: cfg.h_over_dx,
            },
            rho0: 1.0,
            material: Material::Hydro { bulk: 1.0 },
            art_stress: cfg
                .art_stress
                .map(|(eps, n)| crate::forms::ArtificialStress {
                    eps,
                    n,
                    spacing: 1.0,
                }),
            // normalised units: h in Δx, c = 1
            diffusion: cfg
                .diffusion
                .map(|(delta, form)| crate::forms::DensityDiffusion {
                    delta,
                    form,
                    sound_speed: 1.0,
                }),
            ..cfg.params()
        },
        &Lattice::<D>::of_kind(if D == 3 {
            LatticeKind::Sc
        } else {
            LatticeKind::Square { gamma: 1.0 }
        })?,
        1.0,
        1.0 - cfg.density_ratio,
        &cfg.budget,
    )?;
    let (standing_rate, standing_k) = box_prediction(&lin_unit, nfree)?;
    // the box operator is the mechanical reduction ω² = eig(−(J_vx + J_vq J_qv)), exact only
    // without dissipation; with δ-SPH the standing modes' eigenvalues (of the full J) are used.
    // Its fastest mode by thick-restart Arnoldi; up to MAX_DENSE_BOX_DOFS the search gets as
    // many products as the dense operator costs rate evaluations (~ its dofs) and the dense
    // eigenvalues decide when it finds no growing mode or runs out of products or budget
    // (the dense operator was never counted against it; exact for every form:
    // the fastest modes of a stable box are its zero-energy modes at ω² ≈ 0, a cluster no
    // Krylov method resolves); beyond, no growing mode found means the standing modes
    let dofs = D * nfree.pow(D as u32);
    let small = dofs <= MAX_DENSE_BOX_DOFS.min(MAX_DENSE_DOFS);
    let (box_rate, box_method) = if cfg.diffusion.is_some() {
        (standing_rate, "standing-modes")
    } else {
        let cap = small.then_some(dofs);
        match box_growth_iterative(run, Start::Generic, cap, &cfg.budget, progress) {
            Ok(Some(g)) => (g.rate / unit, "iterative-operator"),
            Ok(None) | Err(Error::NotConverged { .. } | Error::Budget { .. }) if small => {
                (box_growth(run)?.0 / unit, "dense-operator")
            }
            Ok(None) => (standing_rate, "standing-modes"),
            Err(e) => return Err(e),
        }
    };
    let (infinite_rate, at) = infinite_rate(&lin_unit)?;
    let (infinite_kappa, infinite_longitudinal) = match at {
        Some((k, p)) => {
            let kk: f64 = k.iter().map(|a| a * a).sum::<f64>().sqrt();
            let dot: Complex64 = k.iter().zip(&p).map(|(a, pa)| pa * (a / kk)).sum();
            (k.to_vec(), dot.norm_sqr())
        }
        None => (Vec::new(), 0.0),
    };
    Ok(SweglePrediction {
        box_rate,
        box_method,
        box_kappa: standing_k.to_vec(),
        infinite_rate,
        infinite_kappa,
        infinite_longitudinal,
    })
}
