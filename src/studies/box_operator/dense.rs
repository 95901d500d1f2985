//! The exact linear operator of a finite particle set: the run's rate function linearised with
//! dual numbers about its current (rest) state, with the boundary mask applied, reduced to the
//! mechanical degrees of freedom of the free particles,
//! `D = −(J_vx + J_vq J_qv)` (D·N_free × D·N_free in D dimensions), and its eigenvalues ω²; the growth rate is
//! max Re sqrt(−ω²). Dense: affordable up to a few thousand free degrees of freedom.

use crate::error::{Error, Result};
use crate::forms::{Comp, FieldKind, RateWorkspace, State};
use crate::scalar::{Dual, Scalar as _};
use crate::solver::run::{BoundaryDensity, Run};
use nalgebra::DMatrix;
use num_complex::Complex64;
use rayon::prelude::*;

/// Largest dense operator size (free mechanical degrees of freedom).
pub const MAX_DENSE_DOFS: usize = 3000;

/// Iterations of the Schur decomposition per degree of freedom before it counts as stalled
/// (LAPACK allows 30 per eigenvalue).
const SCHUR_ITERATIONS_PER_DOF: usize = 100;

/// Relative asymmetry ‖D − Dᵀ‖_F / ‖D‖_F up to which D counts as symmetric (a symmetric
/// operator assembled in floating point shows ~1e-16).
const SYMMETRY_TOL: f64 = 1e-12;

/// Deflation tolerance of the last attempt of the Schur decomposition (relative to the shifted
/// diagonal).
const SCHUR_RELAXED_EPS: f64 = 1e-12;

/// The dual-number seed of one Jacobian column: a position or velocity component (particle,
/// axis), or an auxiliary field of a particle.
#[derive(Clone, Copy)]
enum Seed {
    X(usize, usize),
    V(usize, usize),
    Aux(Comp, usize),
}

/// Growth rate (1/time, physical) of the fastest mode of the finite set, and the number of
/// free mechanical degrees of freedom.
pub fn box_growth<const D: usize>(run: &Run<D>) -> Result<(f64, usize)> {
    let ev = box_spectrum(run)?;
    Ok((growth_of(&ev), ev.len()))
}

/// The fastest growth max Re √(−ω²) of a spectrum, ignoring the eigenvalues within
/// ZERO_OMEGA2_TOL of zero (relative to the largest): zero-energy modes or round-off of the
/// non-symmetric Schur decomposition, no exponential growth.
pub fn growth_of(ev: &[Complex64]) -> f64 {
    let scale = ev.iter().map(|w| w.norm()).fold(0.0, f64::max);
    let tol = crate::vonneumann::classify::ZERO_OMEGA2_TOL * scale;
    ev.iter()
        .filter(|w| w.norm() > tol)
        .map(|&w2: &Complex64| (-w2).sqrt().re.abs())
        .fold(0.0, f64::max)
}

/// Every eigenvalue ω² (1/time², physical) of the operator D of the finite set, one per free
/// mechanical degree of freedom.
pub fn box_spectrum<const D: usize>(run: &Run<D>) -> Result<Vec<Complex64>> {
    let n = run.z.x.len();
    let free: Vec<usize> = (0..n).filter(|&i| !run.fixed[i]).collect();
    let nx = D * free.len();
    if nx > MAX_DENSE_DOFS {
        return Err(Error::Incompatible(format!(
            "dense box operator of {nx} degrees of freedom exceeds {MAX_DENSE_DOFS}; use the standing-mode prediction"
        ).into()));
    }
    if run.model.p.av.is_some() || run.model.p.diffusion.is_some() {
        return Err(Error::Incompatible(
            "the box operator is defined without artificial viscosity and density diffusion".into(),
        ));
    }
    let aux: Vec<Comp> = run
        .model
        .p
        .form
        .comps(D, &run.model.p.material)
        .into_iter()
        .filter(|c| c.kind() == FieldKind::Auxiliary)
        .collect();
    let nq = aux.len() * n;
    let base: State<Dual, D> = run.z.map(Dual::cst);
    // (the run's cached workspaces are not shared between threads: only its model is)
    let (model, fixed, boundary) = (&run.model, &run.fixed, run.boundary);
    let frozen = |i: usize| fixed[i] && boundary == BoundaryDensity::Frozen;
    // one column of the Jacobian per seed: a whole rate evaluation each, independent of the
    // others, so the columns are evaluated in parallel, each thread with its own workspace
    // (the same numbers as one after the other: a workspace's reuse of pair data is exact)
    // (only the rows needed: the accelerations for position and auxiliary seeds, the auxiliary
    // rates for velocity seeds)
    let columns = |seeds: &[Seed]| -> Result<Vec<Vec<f64>>> {
        seeds
            .par_iter()
            .map_init(
                || (State::<Dual, D>::default(), RateWorkspace::<Dual, D>::new()),
                |(out, ws), &seed| {
                    let mut z = base.clone();
                    match seed {
                        Seed::X(i, a) => z.x[i][a].d = 1.0,
                        Seed::V(i, a) => z.v[i][a].d = 1.0,
                        Seed::Aux(c, i) => {
                            let mut t = z.get(c, i);
                            t.d = 1.0;
                            z.set(c, i, t);
                        }
                    }
                    model.rate_with(&z, out, ws)?;
                    Ok(if let Seed::V(..) = seed {
                        let out = &*out;
                        aux.iter()
                            .flat_map(|&c| {
                                (0..n).map(move |i| if frozen(i) { 0.0 } else { out.get(c, i).d })
                            })
                            .collect()
                    } else {
                        free.iter().flat_map(|&i| out.v[i].map(|a| a.d)).collect()
                    })
                },
            )
            .collect()
    };
    // accelerations of free particles (rows of J_v·) and aux rates (rows of J_q·)
    let mut jvx = DMatrix::<f64>::zeros(nx, nx);
    let mut jvq = DMatrix::<f64>::zeros(nx, nq);
    let mut jqv = DMatrix::<f64>::zeros(nq, nx);
    let dofs: Vec<(usize, usize)> = free
        .iter()
        .flat_map(|&i| (0..D).map(move |a| (i, a)))
        .collect();
    let xs: Vec<Seed> = dofs.iter().map(|&(i, a)| Seed::X(i, a)).collect();
    for (col, acc) in columns(&xs)?.into_iter().enumerate() {
        for (r, v) in acc.iter().enumerate() {
            jvx[(r, col)] = *v;
        }
    }
    let vs: Vec<Seed> = dofs.iter().map(|&(i, a)| Seed::V(i, a)).collect();
    for (col, q) in columns(&vs)?.into_iter().enumerate() {
        for (r, v) in q.iter().enumerate() {
            jqv[(r, col)] = *v;
        }
    }
    // an auxiliary field no free velocity moves (deep in the boundary, or frozen) adds
    // nothing to J_vq J_qv: its column is not needed
    let (aux_cols, aux_seeds): (Vec<usize>, Vec<Seed>) = aux
        .iter()
        .enumerate()
        .flat_map(|(ci, &c)| (0..n).map(move |i| (ci, c, i)))
        .filter(|&(ci, _, i)| jqv.row(ci * n + i).iter().any(|&v| v != 0.0))
        .map(|(ci, c, i)| (ci * n + i, Seed::Aux(c, i)))
        .unzip();
    for (col, acc) in aux_cols.into_iter().zip(columns(&aux_seeds)?) {
        for (r, v) in acc.iter().enumerate() {
            jvq[(r, col)] = *v;
        }
    }
    let d = -(jvx + &jvq * &jqv);
    if d.iter().any(|v| !v.is_finite()) {
        return Err(Error::NonFinite("box operator"));
    }
    // nalgebra's Schur decomposition deflates when |h_{i+1,i}| ≤ ε(|h_ii| + |h_{i+1,i+1}|) and
    // has no exceptional shifts: on the many exactly degenerate (and zero) eigenvalues of a 3D
    // box it can stall. Then: a D symmetric to round-off (classical, nonlocal) goes to the
    // symmetric QR algorithm (Wilkinson shifts, always convergent) on its symmetric part; any
    // other D to the Schur decomposition of D + μI, μ = ‖D‖₁ + 1 (as in
    // crate::vonneumann::linearise::eigen), with ε = 4 f64::EPSILON, then SCHUR_RELAXED_EPS,
    // the eigenvalues shifted back. Errors: O(SYMMETRY_TOL‖D‖) or O(εμ) in ω², μ a small
    // multiple of the largest |ω²|, well below the ZERO_OMEGA2_TOL (1e-10) filter below.
    let cap = SCHUR_ITERATIONS_PER_DOF * nx.max(10);
    let ev: Vec<Complex64> =
        match nalgebra::linalg::Schur::try_new(d.clone(), 4.0 * f64::EPSILON, cap) {
            Some(s) => s.complex_eigenvalues().iter().copied().collect(),
            None if (&d - d.transpose()).norm() <= SYMMETRY_TOL * d.norm() => {
                let sym = (&d + d.transpose()) * 0.5;
                nalgebra::linalg::SymmetricEigen::try_new(sym, 4.0 * f64::EPSILON, cap)
                    .ok_or(Error::NonFinite(
                        "box operator eigenvalues (no convergence)",
                    ))?
                    .eigenvalues
                    .iter()
                    .map(|&w| Complex64::new(w, 0.0))
                    .collect()
            }
            None => {
                let mu = d.column_iter().map(|c| c.abs().sum()).fold(0.0, f64::max) + 1.0;
                let shifted = d + DMatrix::<f64>::identity(nx, nx) * mu;
                [4.0 * f64::EPSILON, SCHUR_RELAXED_EPS]
                    .into_iter()
                    .find_map(|eps| nalgebra::linalg::Schur::try_new(shifted.clone(), eps, cap))
                    .ok_or(Error::NonFinite(
                        "box operator eigenvalues (no convergence)",
                    ))?
                    .complex_eigenvalues()
                    .iter()
                    .map(|w| w - mu)
                    .collect()
            }
        };
    Ok(ev)
}
