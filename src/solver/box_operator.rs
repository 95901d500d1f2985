//! The exact linear operator of a finite particle set: the run's rate function linearised with
//! dual numbers about its current (rest) state, with the boundary mask applied, reduced to the
//! mechanical degrees of freedom of the free particles,
//! `D = −(J_vx + J_vq J_qv)` (D·N_free × D·N_free in D dimensions), and its eigenvalues ω²; the growth rate is
//! max Re sqrt(−ω²). Dense: affordable up to a few thousand free degrees of freedom.

use super::run2d::{BoundaryDensity, Run};
use crate::error::{Error, Result};
use crate::forms::{Comp, FieldKind, State};
use crate::scalar::{Dual, Scalar as _};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Largest dense operator size (free mechanical degrees of freedom).
pub const MAX_DENSE_DOFS: usize = 3000;

/// Growth rate (1/time, physical) of the fastest mode of the finite set, and the number of
/// free mechanical degrees of freedom.
pub fn box_growth<const D: usize>(run: &Run<D>) -> Result<(f64, usize)> {
    let n = run.z.x.len();
    let free: Vec<usize> = (0..n).filter(|&i| !run.fixed[i]).collect();
    let nx = D * free.len();
    if nx > MAX_DENSE_DOFS {
        return Err(Error::Incompatible(format!(
            "dense box operator of {nx} degrees of freedom exceeds {MAX_DENSE_DOFS}; use the standing-mode prediction"
        )));
    }
    if run.model.p.av.is_some() {
        return Err(Error::Incompatible(
            "the box operator is defined without artificial viscosity".into(),
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
    let mut out = State::<Dual, D>::default();
    let frozen = |i: usize| run.fixed[i] && run.boundary == BoundaryDensity::Frozen;
    // column helpers: accelerations of free particles (rows of J_v·) and aux rates (rows of J_q·)
    let mut jvx = DMatrix::<f64>::zeros(nx, nx);
    let mut jvq = DMatrix::<f64>::zeros(nx, nq);
    let mut jqv = DMatrix::<f64>::zeros(nq, nx);
    let mut eval = |seed: &dyn Fn(&mut State<Dual, D>)| -> Result<(Vec<f64>, Vec<f64>)> {
        let mut z = base.clone();
        seed(&mut z);
        run.model.rate(&z, &mut out)?;
        let acc: Vec<f64> = free.iter().flat_map(|&i| out.v[i].map(|a| a.d)).collect();
        let mut q = Vec::with_capacity(nq);
        for &c in &aux {
            q.extend((0..n).map(|i| if frozen(i) { 0.0 } else { out.get(c, i).d }));
        }
        Ok((acc, q))
    };
    for (k, &i) in free.iter().enumerate() {
        for a in 0..D {
            let (acc, _) = eval(&|z| z.x[i][a].d = 1.0)?;
            for (r, v) in acc.iter().enumerate() {
                jvx[(r, D * k + a)] = *v;
            }
            let (_, q) = eval(&|z| z.v[i][a].d = 1.0)?;
            for (r, v) in q.iter().enumerate() {
                jqv[(r, D * k + a)] = *v;
            }
        }
    }
    for (ci, &c) in aux.iter().enumerate() {
        for i in 0..n {
            let (acc, _) = eval(&|z| {
                let mut t = z.get(c, i);
                t.d = 1.0;
                z.set(c, i, t);
            })?;
            for (r, v) in acc.iter().enumerate() {
                jvq[(r, ci * n + i)] = *v;
            }
        }
    }
    let d = -(jvx + &jvq * &jqv);
    if d.iter().any(|v| !v.is_finite()) {
        return Err(Error::NonFinite("box operator"));
    }
    let ev = nalgebra::linalg::Schur::try_new(d, 4.0 * f64::EPSILON, 200 * nx * nx.max(10))
        .ok_or(Error::NonFinite(
            "box operator eigenvalues (no convergence)",
        ))?
        .complex_eigenvalues();
    // eigenvalues within ZERO_OMEGA2_TOL of zero (relative to the largest) are zero-energy
    // modes or round-off of the non-symmetric Schur decomposition: no exponential growth
    let scale = ev.iter().map(|w| w.norm()).fold(0.0, f64::max);
    let tol = crate::vonneumann::classify::ZERO_OMEGA2_TOL * scale;
    let g = ev
        .iter()
        .filter(|w| w.norm() > tol)
        .map(|&w2: &Complex64| (-w2).sqrt().re.abs())
        .fold(0.0, f64::max);
    Ok((g, nx))
}
