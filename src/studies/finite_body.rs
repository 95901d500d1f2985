//! The largest eigenvalue of a finite Galerkin body (\[B00\] §5, Figs 17–18): the wave
//! equation M ü = −c² K u of a bar of N nodes (1D) or an N × N square (2D, the anti-plane or
//! scalar wave), assembled with EFG / MLS shape functions over background cells with 2 Gauss
//! points per cell (2 × 2 in 2D), the nodes at 0, 1, …, N − 1 (units of Δx), free boundaries (the
//! weak form's natural condition: nothing is prescribed). Near a boundary each quadrature point
//! sees only the nodes that exist, so its shape functions are those of the truncated node set —
//! the boundary effect the infinite-lattice bounds of [`crate::vonneumann::timestep_bounds`]
//! leave out.
//!
//! K_IJ = Σ_Q w_Q ∇φ_I(x_Q)·∇φ_J(x_Q), M_IJ = Σ_Q w_Q φ_I(x_Q) φ_J(x_Q) (consistent), or the
//! row sum M_I = Σ_J M_IJ (lumped, \[B00\] eq 131), normalised by c²/Δx². λ_max of K u = λ M u
//! is found densely (every eigenvalue; nalgebra's symmetric eigensolver on M^{-1/2} K M^{-1/2},
//! or L⁻¹ K L⁻ᵀ with the Cholesky factor L of the consistent mass) up to [`MAX_DENSE`] unknowns,
//! and beyond it (lumped mass) by thick-restart Lanczos on the products of M^{-1/2} K M^{-1/2}
//! ([`fastest_mode`], the box operator's eigensolver). The critical leapfrog step is
//! Δt = 2/√λ_max (Δx/c).

#![allow(clippy::needless_range_loop)]

use super::box_operator::{ArnoldiParams, fastest_mode};
use crate::budget::Budget;
use crate::error::{Error, Result, fields};
use crate::kernel::Kernel;
use crate::params::check_count;
use crate::shape::{KernelParams, ShapeFamily, eval_d};
use crate::vonneumann::timestep_bounds::{ALPHA_1D, ALPHA1_2D, ALPHA2_2D};
use nalgebra::{DMatrix, SymmetricEigen};
use rayon::prelude::*;
use serde::Serialize;

/// Unknowns up to which the eigenvalues are found densely (and the consistent mass allowed).
pub const MAX_DENSE: usize = 1600;
/// Nodes per side: 1D range.
pub const NODES_1D: (usize, usize) = (3, 100_000);
/// Nodes per side: 2D range.
pub const NODES_2D: (usize, usize) = (3, 300);
/// Shape-function products (a quadrature point's node pairs, or its nodes once per Lanczos
/// product) counted as one particle-step against the budget's `max_steps`.
pub const PRODUCTS_PER_STEP: f64 = 30.0;
/// Lanczos products assumed by the budget estimate.
const LANCZOS_PRODUCTS: f64 = 500.0;

/// The mass matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BodyMass {
    /// Row sum (\[B00\] eq 131).
    Lumped,
    /// ∫ φ_I φ_J.
    Consistent,
}

/// A finite body's largest eigenvalue and the bounds it is compared with.
#[derive(Clone, Debug, Serialize)]
pub struct FiniteBody {
    /// Dimension.
    pub dim: usize,
    /// Nodes per side.
    pub nodes: usize,
    /// Support radius D_max (units of Δx).
    pub d_max: f64,
    /// Weight (kernel) name.
    pub kernel: &'static str,
    /// Shape family.
    pub shape: &'static str,
    /// λ_max with the lumped mass (c²/Δx²).
    pub lambda_max_lumped: f64,
    /// λ_max with the consistent mass (None beyond [`MAX_DENSE`] unknowns).
    pub lambda_max_consistent: Option<f64>,
    /// Whether the lumped λ_max came from the dense solve (else Lanczos).
    pub dense: bool,
    /// The closed-form bounds: eq 136/137 (1D: α c²/h², α = 12.42), or eq 146 and eq 148 (2D).
    pub bounds: Vec<(String, f64)>,
    /// Each bound over the lumped λ_max (\[B00\] §5.1: "approaches 1.1").
    pub ratio_lumped: Vec<f64>,
    /// Each bound over the consistent λ_max.
    pub ratio_consistent: Option<Vec<f64>>,
    /// Critical leapfrog step 2/√λ_max with the lumped mass (Δx/c).
    pub critical_dt_lumped: f64,
}

/// One quadrature point: its weight and (node, φ, ∇φ) of every node that covers it.
type Point<const D: usize> = (f64, Vec<(usize, f64, [f64; D])>);

/// The body's quadrature points.
struct Points<const D: usize> {
    points: Vec<Point<D>>,
    count: usize,
}

impl<const D: usize> Points<D> {
    /// Row-sum masses Σ_Q w φ_I Σ_J φ_J.
    fn lumped(&self) -> Vec<f64> {
        let mut m = vec![0.0; self.count];
        for (w, st) in &self.points {
            let sum: f64 = st.iter().map(|e| e.1).sum();
            for &(i, p, _) in st {
                m[i] += w * p * sum;
            }
        }
        m
    }

    /// Dense K and consistent M.
    fn dense(&self) -> (DMatrix<f64>, DMatrix<f64>) {
        let n = self.count;
        let (mut k, mut m) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        for (w, st) in &self.points {
            for &(i, pi, gi) in st {
                for &(j, pj, gj) in st {
                    let mut kij = 0.0;
                    for c in 0..D {
                        kij += gi[c] * gj[c];
                    }
                    k[(i, j)] += w * kij;
                    m[(i, j)] += w * pi * pj;
                }
            }
        }
        (k, m)
    }

    /// y = K x, matrix-free: Σ_Q w ∇φ_I (Σ_J ∇φ_J x_J).
    fn apply_k(&self, x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        for (w, st) in &self.points {
            let mut g = [0.0; D];
            for &(j, _, gj) in st {
                for c in 0..D {
                    g[c] += gj[c] * x[j];
                }
            }
            for &(i, _, gi) in st {
                let mut v = 0.0;
                for c in 0..D {
                    v += gi[c] * g[c];
                }
                y[i] += w * v;
            }
        }
    }
}

/// Gauss points of one cell [0, 1]^D: the tensor product of the 2-point rule of
/// [`points_1d`](crate::vonneumann::timestep_bounds::points_1d), the one the lattice bounds use.
fn gauss_points<const D: usize>() -> Vec<([f64; D], f64)> {
    let p1 = crate::vonneumann::timestep_bounds::points_1d(true);
    let mut out = Vec::new();
    for m in 0..p1.len().pow(D as u32) {
        let mut x = [0.0; D];
        let mut w = 1.0;
        let mut rest = m;
        for xa in x.iter_mut() {
            let (p, wp) = p1[rest % p1.len()];
            rest /= p1.len();
            *xa = p;
            w *= wp;
        }
        out.push((x, w));
    }
    out
}

fn assemble<const D: usize>(n: usize, family: ShapeFamily, kp: KernelParams) -> Result<Points<D>> {
    let count = n.pow(D as u32);
    let r = kp.support();
    let reach = r.ceil() as i64 + 1;
    let cells = (n - 1).pow(D as u32);
    let pts = gauss_points::<D>();
    // per cell, per point: (node, φ, ∇φ) — in parallel, then added in cell order
    let per_cell: Vec<Vec<Point<D>>> = (0..cells)
        .into_par_iter()
        .map(|c| {
            let mut corner = [0i64; D];
            let mut rest = c;
            for a in 0..D {
                corner[a] = (rest % (n - 1)) as i64;
                rest /= n - 1;
            }
            pts.iter()
                .map(|&(xi, w)| {
                    let mut xq = [0.0; D];
                    for a in 0..D {
                        xq[a] = corner[a] as f64 + xi[a];
                    }
                    let mut ids = Vec::new();
                    let mut nodes = Vec::new();
                    let span = (2 * reach + 1) as usize;
                    for m in 0..span.pow(D as u32) {
                        let mut j = [0i64; D];
                        let mut rr = m;
                        for a in 0..D {
                            j[a] = corner[a] + (rr % span) as i64 - reach;
                            rr /= span;
                        }
                        if j.iter().any(|&ja| ja < 0 || ja >= n as i64) {
                            continue;
                        }
                        let mut d = [0.0; D];
                        let mut r2 = 0.0;
                        for a in 0..D {
                            d[a] = j[a] as f64 - xq[a];
                            r2 += d[a] * d[a];
                        }
                        if r2 >= r * r {
                            continue;
                        }
                        let mut flat = 0usize;
                        for a in (0..D).rev() {
                            flat = flat * n + j[a] as usize;
                        }
                        ids.push(flat);
                        nodes.push((d, 1.0));
                    }
                    let mut out = Vec::new();
                    eval_d(family, kp, &nodes, xq[0], &mut out)?;
                    Ok((
                        w,
                        ids.iter()
                            .zip(out)
                            .map(|(&i, (p, g))| (i, p, g))
                            .collect::<Vec<_>>(),
                    ))
                })
                .collect::<Result<Vec<_>>>()
        })
        .collect::<Result<_>>()?;
    Ok(Points {
        points: per_cell.into_iter().flatten().collect(),
        count,
    })
}

fn largest(s: DMatrix<f64>) -> f64 {
    SymmetricEigen::new(s)
        .eigenvalues
        .iter()
        .cloned()
        .fold(f64::MIN, f64::max)
}

/// (λ_max lumped, λ_max consistent if dense, whether dense).
fn solve<const D: usize>(
    pts: &Points<D>,
    d_max: f64,
    family: ShapeFamily,
) -> Result<(f64, Option<f64>, bool)> {
    let count = pts.count;
    let lumped_m = pts.lumped();
    if let Some(i) = lumped_m.iter().position(|&m| m <= 0.0 || !m.is_finite()) {
        return Err(Error::Incompatible(
            format!(
                "node {i} has lumped mass {} ≤ 0: the support D_max = {d_max} is too small for the {} shapes",
                lumped_m[i],
                family.name()
            )
            .into(),
        ));
    }
    let inv_sqrt: Vec<f64> = lumped_m.iter().map(|m| 1.0 / m.sqrt()).collect();
    if count <= MAX_DENSE {
        let (k, m) = pts.dense();
        let mut s = k.clone();
        for i in 0..count {
            for j in 0..count {
                s[(i, j)] *= inv_sqrt[i] * inv_sqrt[j];
            }
        }
        let lumped = largest(s);
        let chol = nalgebra::Cholesky::new(m).ok_or_else(|| {
            Error::Incompatible("the consistent mass matrix is not positive definite".into())
        })?;
        let l = chol.l();
        // S = L⁻¹ K L⁻ᵀ
        let x = l
            .solve_lower_triangular(&k)
            .ok_or_else(|| Error::Incompatible("singular Cholesky factor".into()))?;
        let s = l
            .solve_lower_triangular(&x.transpose())
            .ok_or_else(|| Error::Incompatible("singular Cholesky factor".into()))?;
        let consistent = largest((&s + s.transpose()) * 0.5);
        return Ok((lumped, Some(consistent), true));
    }
    // the fastest mode of D = −S is its most negative ω² = −λ_max (growth √λ_max)
    let p = ArnoldiParams {
        basis: 60,
        keep: 20,
        rtol: 1e-10,
        atol: 1e-13,
        max_products: 20_000,
        stable_after: None,
        zero: 0.0,
    };
    let start: Vec<f64> = (0..count)
        .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    let mut xs = vec![0.0; count];
    let mode = fastest_mode(count, &start, p, |x, y| {
        for i in 0..count {
            xs[i] = x[i] * inv_sqrt[i];
        }
        pts.apply_k(&xs, y);
        for i in 0..count {
            y[i] *= -inv_sqrt[i];
        }
        Ok(())
    })?;
    Ok((-mode.omega2.re, None, false))
}

/// The largest eigenvalue of the finite body of `nodes` nodes per side in dimension `dim`
/// (1 or 2), weight `kernel` with support radius `d_max` Δx, shape family `family` (module
/// docs). The consistent-mass eigenvalue is computed up to [`MAX_DENSE`] unknowns.
pub fn finite_body(
    dim: usize,
    nodes: usize,
    kernel: &'static dyn Kernel,
    d_max: f64,
    family: ShapeFamily,
    budget: &Budget,
) -> Result<FiniteBody> {
    let (lo, hi) = match dim {
        1 => NODES_1D,
        2 => NODES_2D,
        _ => {
            return Err(Error::OutOfRange {
                field: "dim",
                value: dim as f64,
                range: "must be 1 or 2 (the Galerkin body of [B00] §5)".into(),
            });
        }
    };
    check_count("nodes", nodes, lo, hi)?;
    crate::error::check_range("support", d_max, 1.0, 50.0, false, true)?;
    let kp = KernelParams {
        kernel,
        h: d_max / kernel.zeta(),
    };
    // the work: every quadrature point's node pairs (dense) or its nodes per Lanczos product
    let count = nodes.pow(dim as u32);
    let points = (2.0 * (nodes - 1) as f64).powi(dim as i32);
    let cover = if dim == 1 {
        2.0 * d_max
    } else {
        std::f64::consts::PI * d_max * d_max
    };
    let work = if count <= MAX_DENSE {
        points * cover * cover
    } else {
        points * cover * LANCZOS_PRODUCTS
    };
    budget.work(
        fields(&["nodes", "support", "dim"]),
        &format!("the finite body ({count} nodes)"),
        work,
        "shape-function products",
        budget.max_steps * PRODUCTS_PER_STEP,
    )?;
    let (lumped, consistent, dense_ok) = if dim == 1 {
        solve(&assemble::<1>(nodes, family, kp)?, d_max, family)?
    } else {
        solve(&assemble::<2>(nodes, family, kp)?, d_max, family)?
    };
    let h2 = d_max * d_max;
    let bounds: Vec<(String, f64)> = if dim == 1 {
        vec![("eq 137".into(), ALPHA_1D / h2)]
    } else {
        vec![
            ("eq 146".into(), ALPHA1_2D / h2),
            ("eq 148".into(), ALPHA2_2D / h2),
        ]
    };
    Ok(FiniteBody {
        dim,
        nodes,
        d_max,
        kernel: kernel.name(),
        shape: family.name(),
        lambda_max_lumped: lumped,
        lambda_max_consistent: consistent,
        dense: dense_ok,
        ratio_lumped: bounds.iter().map(|b| b.1 / lumped).collect(),
        ratio_consistent: consistent.map(|c| bounds.iter().map(|b| b.1 / c).collect()),
        bounds,
        critical_dt_lumped: 2.0 / lumped.sqrt(),
    })
}
