//! `least-squares`: Beissel–Belytschko stabilised nodal integration \[B00 §4.3, eq 104–107\],
//! Lagrangian kernel. The weak form adds (β/E)∫δσ_{,x}(σ_{,x} − ρü) with β = α_s l_c²
//! (l_c = Δx), giving constant matrices built once on the reference configuration:
//! ```text
//! M_IK = Σ_J ρ0 V_J [φ_I(X_J) φ_K(X_J) − β φ''_I(X_J) φ_K(X_J)]               [eq 106]
//! K_IK = Σ_J C̄ V_J [φ'_I(X_J) φ'_K(X_J) + β φ''_I(X_J) φ''_K(X_J)]            [eq 107]
//! M ü = −K u,   C̄ = C + σ0 (the tangent of the pre-stressed material, = E when σ0 = 0)
//! ```
//! The matrices are assembled with the model (`chain_data.rs`). The `v` rate returned is the
//! force f = −K u; the mass operator is consistent. The solver
//! solves M a = f with [`BandedLu`], an O(N) banded factorisation (periodic chains reordered
//! to be banded), which replaced a dense LU (O(N²) per solve, O(N³) to factorise).

// Band algebra reads best with explicit row and column indices.
#![allow(clippy::needless_range_loop)]

use super::chain_data::{ChainModel, ChainState};
use super::chain_search::ChainRates;
use crate::scalar::Scalar;

/// The force f = −K u of the least-squares form (the `v` rate of a consistent mass).
pub(crate) fn rate<S: Scalar>(m: &ChainModel<'_>, z: ChainState<'_, S>, out: &mut ChainRates<S>) {
    out.x.copy_from_slice(z.v);
    for (i, row) in m.data.ls_stiffness.iter().enumerate() {
        let mut f = S::zero();
        for &(k, kik) in row {
            f -= (z.x[k] - m.x_ref[k]) * kik;
        }
        out.v[i] = f;
    }
}

/// The consistent mass of the least-squares form factorised for an O(N) solve: the matrix,
/// reordered so that it is banded, as an LU factorisation with partial pivoting in band
/// storage (LAPACK `gbtrf`/`gbtrs` layout, row-major).
///
/// An open chain is banded as it stands (M_IK ≠ 0 only for |I − K| ≤ b, b the support in
/// spacings). A periodic chain adds corners (I near 0, K near N); the "zig-zag" order
/// 0, N−1, 1, N−2, 2, … puts every pair at cyclic distance d at most 2d + 1 rows apart, so the
/// reordered matrix is banded with bandwidth ≤ 2b + 1 and the same banded LU applies (no
/// corner correction, and the pivoting keeps the stability of the dense LU it replaces).
/// Factorisation O(N w²), solve O(N w), memory O(N w), w the bandwidth.
#[derive(Clone, Debug)]
pub struct BandedLu {
    n: usize,
    /// Sub- and super-diagonals of the reordered matrix.
    kl: usize,
    ku: usize,
    /// Row stride: 2 kl + ku + 1 (kl extra super-diagonals for the fill of the pivoting).
    w: usize,
    /// Row r, column c of the reordered matrix (then its factors) at `a[r * w + c + kl − r]`.
    a: Vec<f64>,
    piv: Vec<usize>,
    /// Reordered row of each master.
    pos: Vec<usize>,
}

impl BandedLu {
    /// Factorises the sparse rows `rows` (row I: (K, M_IK)); `periodic` selects the zig-zag
    /// order. `None` when a pivot vanishes (singular matrix).
    pub fn new(rows: &[Vec<(usize, f64)>], periodic: bool) -> Option<Self> {
        let n = rows.len();
        let pos: Vec<usize> = (0..n)
            .map(|i| {
                if !periodic {
                    i
                } else if 2 * i < n {
                    2 * i
                } else {
                    2 * (n - 1 - i) + 1
                }
            })
            .collect();
        let (mut kl, mut ku) = (0, 0);
        for (i, row) in rows.iter().enumerate() {
            for &(k, _) in row {
                let (r, c) = (pos[i], pos[k]);
                kl = kl.max(r.saturating_sub(c));
                ku = ku.max(c.saturating_sub(r));
            }
        }
        let w = 2 * kl + ku + 1;
        let mut lu = Self {
            n,
            kl,
            ku,
            w,
            a: vec![0.0; n * w],
            piv: vec![0; n],
            pos,
        };
        for (i, row) in rows.iter().enumerate() {
            for &(k, v) in row {
                let (r, c) = (lu.pos[i], lu.pos[k]);
                *lu.at(r, c) += v;
            }
        }
        lu.factorise().then_some(lu)
    }

    #[inline]
    fn idx(&self, r: usize, c: usize) -> usize {
        r * self.w + c + self.kl - r
    }

    #[inline]
    fn at(&mut self, r: usize, c: usize) -> &mut f64 {
        let i = self.idx(r, c);
        &mut self.a[i]
    }

    fn factorise(&mut self) -> bool {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        for k in 0..n {
            let last = (k + kl).min(n - 1);
            let mut p = k;
            let mut best = self.a[self.idx(k, k)].abs();
            for r in k + 1..=last {
                let v = self.a[self.idx(r, k)].abs();
                if v > best {
                    best = v;
                    p = r;
                }
            }
            if best == 0.0 || !best.is_finite() {
                return false;
            }
            self.piv[k] = p;
            let cend = (k + ku + kl).min(n - 1);
            if p != k {
                for c in k..=cend {
                    let (i, j) = (self.idx(k, c), self.idx(p, c));
                    self.a.swap(i, j);
                }
            }
            let d = self.a[self.idx(k, k)];
            for r in k + 1..=last {
                let ir = self.idx(r, k);
                let l = self.a[ir] / d;
                self.a[ir] = l;
                if l != 0.0 {
                    for c in k + 1..=cend {
                        let (i, j) = (self.idx(r, c), self.idx(k, c));
                        self.a[i] -= l * self.a[j];
                    }
                }
            }
        }
        true
    }

    /// Bandwidths (sub-, super-diagonals) of the reordered matrix.
    pub fn bandwidths(&self) -> (usize, usize) {
        (self.kl, self.ku)
    }

    /// Solves M a = f; `work` is a buffer of N entries (resized once).
    pub fn solve(&self, f: &[f64], a: &mut [f64], work: &mut Vec<f64>) {
        work.resize(self.n, 0.0);
        for (i, &fi) in f.iter().enumerate() {
            work[self.pos[i]] = fi;
        }
        self.solve_reordered(work);
        for (i, ai) in a.iter_mut().enumerate() {
            *ai = work[self.pos[i]];
        }
    }

    /// Solves the reordered system in place (row interchanges, L, then U).
    fn solve_reordered(&self, b: &mut [f64]) {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                b.swap(k, p);
            }
            let bk = b[k];
            for r in k + 1..=(k + kl).min(n - 1) {
                b[r] -= self.a[self.idx(r, k)] * bk;
            }
        }
        for r in (0..n).rev() {
            let mut s = b[r];
            for c in r + 1..=(r + ku + kl).min(n - 1) {
                s -= self.a[self.idx(r, c)] * b[c];
            }
            b[r] = s / self.a[self.idx(r, r)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::BandedLu;

    /// A deterministic pseudo-random sequence in [−1, 1).
    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// A banded (open) or cyclic-banded (periodic) nonsymmetric matrix, diagonal not dominant
    /// (so pivoting happens), as sparse rows.
    fn matrix(n: usize, b: usize, periodic: bool, seed: &mut u64) -> Vec<Vec<(usize, f64)>> {
        (0..n)
            .map(|i| {
                let mut row = Vec::new();
                for k in 0..n {
                    let d = i.abs_diff(k);
                    let d = if periodic { d.min(n - d) } else { d };
                    if d <= b {
                        let v = lcg(seed) + if d == 0 { 1.5 } else { 0.0 };
                        row.push((k, v));
                    }
                }
                row
            })
            .collect()
    }

    /// The banded solve against nalgebra's dense LU (the solve it replaced) on random
    /// right-hand sides: 1e-12 relative to the solution's largest entry.
    #[test]
    fn banded_solve_matches_the_dense_lu() {
        let mut seed = 7;
        for (n, b, periodic) in [
            (1, 0, false),
            (2, 1, true),
            (7, 2, true),
            (40, 3, false),
            (41, 3, true),
            (64, 5, true),
            (9, 4, true),
        ] {
            let rows = matrix(n, b, periodic, &mut seed);
            let mut dense = nalgebra::DMatrix::<f64>::zeros(n, n);
            for (i, row) in rows.iter().enumerate() {
                for &(k, v) in row {
                    dense[(i, k)] += v;
                }
            }
            let lu = dense.clone().lu();
            let band = BandedLu::new(&rows, periodic).expect("nonsingular");
            if periodic && n > 4 * b + 2 {
                assert!(band.kl <= 2 * b + 1 && band.ku <= 2 * b + 1);
            }
            let mut work = Vec::new();
            for _ in 0..5 {
                let f: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
                let want = lu.solve(&nalgebra::DVector::from_vec(f.clone())).unwrap();
                let mut got = vec![0.0; n];
                band.solve(&f, &mut got, &mut work);
                let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for (g, w) in got.iter().zip(want.iter()) {
                    assert!((g - w).abs() <= 1e-12 * scale, "n {n} b {b}: {g} vs {w}");
                }
            }
        }
    }

    #[test]
    fn singular_matrix_is_refused() {
        let rows = vec![vec![(0, 1.0), (1, 2.0)], vec![(0, 2.0), (1, 4.0)]];
        assert!(BandedLu::new(&rows, false).is_none());
    }
}
