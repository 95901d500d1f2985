//! The fastest mode of a large operator from its products alone: thick-restart Arnoldi
//! (Krylov–Schur in exact arithmetic, \[S01\]; for a symmetric operator thick-restart Lanczos
//! with full reorthogonalisation, \[WS00\]), with the products stored next to the basis.
//!
//! The basis V (orthonormal, reorthogonalised twice per vector) and the products W = D·V are
//! both kept, so the projection H = Vᵀ W is computed, not inferred from recurrences, and every
//! Ritz residual ‖D u − θ u‖ = ‖W y − θ V y‖ is exact (to round-off) without another product.
//! At a restart the `keep` wanted Ritz vectors (or, for complex ones, an orthonormal basis of
//! their real and imaginary parts) replace the basis, their products following by linearity
//! (W Y), and the expansion continues from the last Arnoldi vector, which is orthogonal to
//! them: the basis stays a Krylov space of the kept vectors.
//!
//! "Wanted" means fastest growing: the Ritz values θ (= ω²) in decreasing order of
//! Re √(−θ) − Re √θ, which is Re √(−θ) for the growing ones and orders the rest by increasing
//! real part (the most negative ω² first on the real axis).
//!
//! \[S01\] G. W. Stewart, A Krylov–Schur algorithm for large eigenproblems, SIAM J. Matrix
//! Anal. Appl. 23 (2001) 601–614. \[WS00\] K. Wu, H. Simon, Thick-restart Lanczos method for
//! large symmetric eigenvalue problems, SIAM J. Matrix Anal. Appl. 22 (2000) 602–616.

use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

/// Relative asymmetry ‖H − Hᵀ‖_F / ‖H‖_F of the projection up to which the operator counts as
/// symmetric (round-off of a symmetric operator's products: ~1e-15).
const SYMMETRY_TOL: f64 = 1e-12;

/// Settings of [`fastest_mode`].
#[derive(Clone, Copy, Debug)]
pub struct ArnoldiParams {
    /// Basis size (products) at which the method restarts.
    pub basis: usize,
    /// Ritz vectors kept at a restart.
    pub keep: usize,
    /// Convergence of the fastest Ritz pair (θ, u), ‖u‖ = 1: ‖D u − θ u‖ ≤ max(`rtol` |θ|,
    /// `atol` ‖D‖), ‖D‖ estimated by the largest |Ritz value|. For a symmetric D an eigenvalue
    /// lies within ‖D u − θ u‖ of θ, so θ is then an eigenvalue to `rtol` relative (or `atol`
    /// ‖D‖ absolute, near zero).
    pub rtol: f64,
    /// See `rtol`.
    pub atol: f64,
    /// Products after which the method gives up ([`Error::NotConverged`]).
    pub max_products: usize,
    /// Products after which the method stops, with [`FastestMode::converged`] false, if the
    /// fastest Ritz value θ does not grow (Re √(−θ) ≤ √(`zero` ‖D‖): a real θ ≥ −`zero` ‖D‖):
    /// a fastest mode in a cluster at ω² ≈ 0 (zero-energy modes) is out of reach of a Krylov
    /// method. None: never.
    pub stable_after: Option<usize>,
    /// See `stable_after`.
    pub zero: f64,
}

/// The fastest mode found, with how it was found.
#[derive(Clone, Debug)]
pub struct FastestMode {
    /// Its eigenvalue ω².
    pub omega2: Complex64,
    /// Its eigenvector (the real part, normalised).
    pub vector: Vec<f64>,
    /// ‖D u − θ u‖ at convergence (u of unit norm).
    pub residual: f64,
    /// The estimate of ‖D‖: the largest |Ritz value| (a lower bound of ‖D‖₂).
    pub norm: f64,
    /// Products of D with a vector.
    pub products: usize,
    /// Restarts.
    pub restarts: usize,
    /// Whether the projection was symmetric (Lanczos), not general (Arnoldi).
    pub symmetric: bool,
    /// Whether the residual reached the tolerance; false only when the method stopped on a
    /// fastest Ritz value that does not grow ([`ArnoldiParams::stable_after`]).
    pub converged: bool,
}

/// The ordering of Ritz values: larger is faster growing (module docs).
fn key(theta: Complex64) -> f64 {
    (-theta).sqrt().re - theta.sqrt().re
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// Orthogonalises `w` against the orthonormal `basis` (classical Gram–Schmidt, twice) and
/// returns its remaining norm.
fn orthogonalise(basis: &[Vec<f64>], w: &mut [f64]) -> f64 {
    for _ in 0..2 {
        let c: Vec<f64> = basis.iter().map(|v| dot(v, w)).collect();
        for (v, ci) in basis.iter().zip(c) {
            for (wi, vi) in w.iter_mut().zip(v) {
                *wi -= ci * vi;
            }
        }
    }
    norm(w)
}

/// A deterministic pseudo-random vector in [−1, 1)ⁿ (splitmix64): a start vector with a
/// component along every eigenvector, and fresh directions after a breakdown.
pub(super) fn pseudo_random(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = s;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        })
        .collect()
}

/// `Σ_j y_j basis_j` (the first `y.len()` vectors).
fn combine(basis: &[Vec<f64>], y: &[f64]) -> Vec<f64> {
    let mut u = vec![0.0; basis[0].len()];
    for (v, &c) in basis.iter().zip(y) {
        for (ui, vi) in u.iter_mut().zip(v) {
            *ui += c * vi;
        }
    }
    u
}

/// The Ritz pairs of the projection `h` (q × q), in decreasing order of growth ([`key`]),
/// the first `keep` with vectors: (values, vectors as an orthonormal q × k matrix spanning the
/// kept ones, the coordinate vectors of the fastest: real and imaginary part).
struct Ritz {
    values: Vec<Complex64>,
    span: DMatrix<f64>,
    fastest: (DVector<f64>, DVector<f64>),
}

fn ritz(h: &DMatrix<f64>, keep: usize, symmetric: bool) -> Result<Ritz> {
    let q = h.nrows();
    let fail = || Error::NonFinite("box operator projection eigenvalues (no convergence)");
    if symmetric {
        let e = nalgebra::linalg::SymmetricEigen::try_new(
            (h + h.transpose()) * 0.5,
            4.0 * f64::EPSILON,
            100 * q.max(10),
        )
        .ok_or_else(fail)?;
        let mut order: Vec<usize> = (0..q).collect();
        order.sort_by(|&a, &b| e.eigenvalues[a].total_cmp(&e.eigenvalues[b]));
        let k = keep.min(q);
        let span = DMatrix::from_fn(q, k, |i, j| e.eigenvectors[(i, order[j])]);
        let fastest = (span.column(0).into_owned(), DVector::zeros(q));
        return Ok(Ritz {
            values: order
                .iter()
                .map(|&i| Complex64::new(e.eigenvalues[i], 0.0))
                .collect(),
            span,
            fastest,
        });
    }
    // nalgebra's Schur decomposition can stall on (nearly) degenerate eigenvalues: then that
    // of h + μI, μ = ‖h‖₁ + 1, with ε = 4 f64::EPSILON, then 1e-12 (as the dense reference)
    let cap = 100 * q.max(10);
    let mu = h.column_iter().map(|c| c.abs().sum()).fold(0.0, f64::max) + 1.0;
    let mut values: Vec<Complex64> =
        match nalgebra::linalg::Schur::try_new(h.clone(), 4.0 * f64::EPSILON, cap) {
            Some(s) => s.complex_eigenvalues().iter().copied().collect(),
            None => [4.0 * f64::EPSILON, 1e-12]
                .into_iter()
                .find_map(|eps| {
                    nalgebra::linalg::Schur::try_new(
                        h + DMatrix::<f64>::identity(q, q) * mu,
                        eps,
                        cap,
                    )
                })
                .ok_or_else(fail)?
                .complex_eigenvalues()
                .iter()
                .map(|w| w - mu)
                .collect(),
        };
    // (of a conjugate pair, the one with Im ≥ 0 first: its vector stands for both)
    values.sort_by(|a, b| key(*b).total_cmp(&key(*a)).then(b.im.total_cmp(&a.im)));
    // eigenvectors of h by inverse iteration (two steps, shift off by 1e-10 ‖h‖), real and
    // imaginary parts orthonormalised into the kept span
    let scale = h.norm().max(f64::MIN_POSITIVE);
    let hc = h.map(|x| Complex64::new(x, 0.0));
    let mut cols: Vec<DVector<f64>> = Vec::new();
    let mut fastest = None;
    for &theta in values.iter() {
        if cols.len() >= keep.min(q) {
            break;
        }
        // one vector per conjugate pair
        if theta.im < 0.0 && values.iter().any(|w| (*w - theta.conj()).norm() == 0.0) {
            continue;
        }
        let shift = theta + Complex64::new(1e-10 * scale, 0.0);
        let lu = (&hc - DMatrix::<Complex64>::identity(q, q) * shift).lu();
        let mut y = DVector::from_element(q, Complex64::new(1.0, 0.0));
        for _ in 0..2 {
            y = lu
                .solve(&y)
                .ok_or(Error::NonFinite("box operator projection eigenvectors"))?;
            let ny = y.norm();
            y /= Complex64::new(ny, 0.0);
        }
        let (re, im) = (y.map(|c| c.re), y.map(|c| c.im));
        if fastest.is_none() {
            fastest = Some((re.clone(), im.clone()));
        }
        for mut c in [re, im] {
            for _ in 0..2 {
                for b in &cols {
                    let d = b.dot(&c);
                    c -= b * d;
                }
            }
            let nc = c.norm();
            if nc > 1e-8 && cols.len() < q {
                cols.push(c / nc);
            }
        }
    }
    let fastest = fastest.ok_or_else(fail)?;
    Ok(Ritz {
        values,
        span: DMatrix::from_columns(&cols),
        fastest,
    })
}

/// The fastest mode of the operator `apply` (y = D u on vectors of length `n`): the eigenvalue
/// ω² of largest Re √(−ω²) (the most negative ω² when D is symmetric), from `start` (any
/// nonzero vector; it must not be orthogonal to the wanted eigenvector). Errors: the method's
/// [`Error::NotConverged`] after `max_products` products, and the product's own.
pub fn fastest_mode(
    n: usize,
    start: &[f64],
    p: ArnoldiParams,
    mut apply: impl FnMut(&[f64], &mut [f64]) -> Result<()>,
) -> Result<FastestMode> {
    let m = p.basis.min(n).max(1);
    let keep = p.keep.min(m.saturating_sub(1)).max(1);
    let mut v: Vec<Vec<f64>> = Vec::with_capacity(m + 1);
    let mut w: Vec<Vec<f64>> = Vec::with_capacity(m);
    let mut first = start.to_vec();
    let n0 = norm(&first);
    if !(n0 > 0.0 && n0.is_finite()) {
        return Err(Error::NonFinite("box operator start vector"));
    }
    first.iter_mut().for_each(|x| *x /= n0);
    v.push(first);
    // h[(i, j)] = v_i · w_j for the q × q block of vectors with products
    let mut h = DMatrix::<f64>::zeros(m + 1, m);
    let (mut products, mut restarts) = (0usize, 0usize);
    // the smallest residual / tolerance so far (for the error)
    let mut best = f64::INFINITY;
    loop {
        // expand: the product of the newest basis vector, and the next basis vector
        let j = w.len();
        let mut wj = vec![0.0; n];
        apply(&v[j], &mut wj)?;
        products += 1;
        for i in 0..=j {
            h[(i, j)] = dot(&v[i], &wj);
        }
        let mut next = wj.clone();
        w.push(wj);
        let mut nn = orthogonalise(&v, &mut next);
        let mut seed = products as u64;
        let floor = 1e-10 * norm(&w[j]).max(f64::MIN_POSITIVE);
        while (nn <= floor || !nn.is_finite()) && v.len() < n {
            // an invariant subspace: continue with a fresh direction
            next = pseudo_random(n, seed);
            seed += 1;
            nn = orthogonalise(&v, &mut next);
        }
        let q = w.len();
        if v.len() < n {
            next.iter_mut().for_each(|x| *x /= nn);
            for (jj, wjj) in w.iter().enumerate() {
                h[(q, jj)] = dot(&next, wjj);
            }
            v.push(next);
        }
        // Rayleigh–Ritz every few products and at a restart
        let full = q == m || v.len() == q;
        if !(full || q.is_multiple_of(8)) {
            continue;
        }
        let hq = h.view((0, 0), (q, q)).into_owned();
        let hn = hq.norm();
        let symmetric = (&hq - hq.transpose()).norm() <= SYMMETRY_TOL * hn;
        // (the kept span only at a restart: the eigenvectors of a general h cost O(q³) each)
        let r = ritz(&hq, if q == m { keep } else { 1 }, symmetric)?;
        let scale = r.values.iter().map(|z| z.norm()).fold(0.0, f64::max);
        let theta = r.values[0];
        let (yr, yi) = (&r.fastest.0, &r.fastest.1);
        let (ur, ui) = (combine(&v, yr.as_slice()), combine(&v, yi.as_slice()));
        let (dr, di) = (combine(&w, yr.as_slice()), combine(&w, yi.as_slice()));
        // residual of the complex pair: D(ur + i ui) − θ (ur + i ui)
        let mut res2 = 0.0;
        let mut un2 = 0.0;
        for k in 0..n {
            let re = dr[k] - (theta.re * ur[k] - theta.im * ui[k]);
            let im = di[k] - (theta.re * ui[k] + theta.im * ur[k]);
            res2 += re * re + im * im;
            un2 += ur[k] * ur[k] + ui[k] * ui[k];
        }
        let residual = (res2 / un2).sqrt();
        let tol = (p.rtol * theta.norm()).max(p.atol * scale);
        best = best.min(residual / tol);
        let mode = |converged: bool| {
            let nu = norm(&ur).max(f64::MIN_POSITIVE);
            FastestMode {
                omega2: theta,
                vector: ur.iter().map(|x| x / nu).collect(),
                residual,
                norm: scale,
                products,
                restarts,
                symmetric,
                converged,
            }
        };
        // (the whole space spanned: the Ritz values are the eigenvalues)
        if residual <= tol || v.len() == q {
            return Ok(mode(true));
        }
        if p.stable_after.is_some_and(|s| products >= s)
            && (-theta).sqrt().re <= (p.zero * scale).sqrt()
        {
            return Ok(mode(false));
        }
        if products >= p.max_products {
            return Err(Error::NotConverged {
                what: "box operator eigenvalue (thick-restart Arnoldi)",
                iterations: products,
                residual: best,
            });
        }
        if q == m {
            // thick restart: the kept Ritz vectors, their products, then the last Arnoldi
            // vector (orthogonal to all of them)
            let y = &r.span;
            let k = y.ncols();
            let last = v.pop().expect("the continuation vector");
            let nv: Vec<Vec<f64>> = (0..k)
                .map(|c| combine(&v, y.column(c).as_slice()))
                .collect();
            let nw: Vec<Vec<f64>> = (0..k)
                .map(|c| combine(&w, y.column(c).as_slice()))
                .collect();
            v = nv;
            w = nw;
            h.fill(0.0);
            for a in 0..k {
                for b in 0..k {
                    h[(a, b)] = dot(&v[a], &w[b]);
                }
            }
            for (b, wb) in w.iter().enumerate() {
                h[(k, b)] = dot(&last, wb);
            }
            v.push(last);
            restarts += 1;
        }
    }
}
