//! The one linearisation core of every dimension: the exact Jacobian columns of a rate function
//! about its rest state (dual numbers), their Bloch projection, the rest-structure check, the
//! mechanical reduction and the leapfrog amplification matrix of one mode. The 1D chain
//! ([`super::Linearisation`]) and the D-dimensional lattice ([`super::Bloch`]) are front ends that
//! say how their periodic system is built (the crate-internal `Linearisable` trait) and what a
//! phase k·r is.
//!
//! A perturbation of one degree of freedom b of cell 0 gives, through one evaluation of the rate
//! function, the column `A_ab(i) = ∂ż_{a,i}/∂z_{b,0}` for every cell i. The per-mode Jacobian block
//! is `J_ab(k) = Σ_i A_ab(i) e^{−ik·r_i}`. Entries whose k = 0 sum vanishes to rounding
//! (translation and Galilean invariance) are summed as `Σ_i A_ab(i)(e^{−ik·r_i} − 1)` with
//! `e^{−iθ} − 1 = −2 sin²(θ/2) − i sin θ`, which keeps full relative accuracy as k → 0.

use crate::error::{Error, Result};
use crate::forms::FieldKind;
use crate::integrator::Integrator;
use crate::vonneumann::amplification::ModeSystem;
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Tangent lanes of one rate evaluation of the linearisation ([`crate::scalar::DualN`]): the
/// Jacobian columns of a cell's dofs come from ⌈dofs / LANES⌉ evaluations instead of one per
/// dof. Each lane is bit for bit a [`crate::scalar::Dual`] evaluation, so the columns do not
/// depend on it. (A D-dim patch too large for the memory budget with LANES lanes uses one.)
pub const LANES: usize = 4;

/// A k = 0 sum is treated as exactly zero when below this fraction of Σ|A_ab(i)|.
pub const ZERO_SUM_TOL: f64 = 1e-12;
/// A q-rate Jacobian entry ∂q̇/∂x or ∂q̇/∂q at rest larger than this (relative) is reported as an
/// error: the mechanical reduction assumes auxiliary rates vanish at rest.
pub const REST_RATE_TOL: f64 = 1e-9;

/// A periodic particle system whose rate function can be differentiated at its rest state with
/// respect to the degrees of freedom of cell 0: the 1D chain (any 1D form, several points per cell)
/// and the D-dimensional periodic patch.
pub(crate) trait Linearisable {
    /// Position of a cell relative to cell 0 (a cell offset in 1D, a lattice vector in D dims).
    type Offset: Copy;
    /// Mechanical role of each degree of freedom of a cell, in order.
    fn kinds(&self) -> Vec<FieldKind>;
    /// Number of cells of the periodic system.
    fn cells(&self) -> usize;
    /// Position of cell `i` relative to cell 0.
    fn offset(&self, i: usize) -> Self::Offset;
    /// Tangent lanes of one evaluation ([`crate::scalar::Lanes`]).
    fn lanes(&self) -> usize;
    /// Evaluates the rate function at the rest state once, with dual numbers of
    /// [`Self::lanes`] lanes: lane l carries a unit tangent on dof `b0 + l` of cell 0 (lanes past
    /// the last dof stay zero).
    fn seeded_rates(&mut self, b0: usize) -> Result<()>;
    /// Lane `l` of the tangent of the rate of dof `a` of cell `i` after [`Self::seeded_rates`].
    fn tangent(&self, a: usize, i: usize, l: usize) -> f64;
}

/// The Jacobian columns of a linearised periodic system, with the position, velocity and
/// auxiliary dofs of a cell.
#[derive(Clone, Debug)]
pub(crate) struct Columns<O> {
    /// `cols[b]` = (offset of cell i, column A_{·b}(i)) for every cell where it is nonzero.
    cols: Vec<Vec<(O, Vec<f64>)>>,
    /// Whether the k = 0 sum of entry (a, b) is zero to rounding.
    zero_sum: Vec<Vec<bool>>,
    /// The distinct offsets of all columns, and for each column entry the index of its offset
    /// there: a Bloch sum evaluates the phase of each offset once, not once per column.
    offsets: Vec<O>,
    at: Vec<Vec<usize>>,
    /// Position dofs.
    pub ix: Vec<usize>,
    /// Velocity dofs (as many as positions).
    pub iv: Vec<usize>,
    /// Auxiliary dofs (density, stresses, stress points), ascending.
    pub iq: Vec<usize>,
}

impl<O: Copy> Columns<O> {
    /// Differentiates `sys` column by column, and checks the rest structure ([`check_rest`]).
    pub fn of<L: Linearisable<Offset = O>>(sys: &mut L) -> Result<Self> {
        let kinds = sys.kinds();
        let nd = kinds.len();
        let of_kind = |k: FieldKind| -> Vec<usize> { (0..nd).filter(|&a| kinds[a] == k).collect() };
        let (ix, iv, iq) = (
            of_kind(FieldKind::Position),
            of_kind(FieldKind::Velocity),
            of_kind(FieldKind::Auxiliary),
        );
        if ix.is_empty() || ix.len() != iv.len() {
            return Err(Error::NonFinite("layout"));
        }
        let mut cols = Vec::with_capacity(nd);
        let mut slot = vec![usize::MAX; sys.cells()];
        let (mut offsets, mut at) = (Vec::new(), Vec::with_capacity(nd));
        let lanes = sys.lanes();
        for b in 0..nd {
            let (b0, l) = (b - b % lanes, b % lanes);
            if l == 0 {
                // one evaluation differentiates along LANES dofs
                crate::progress::interrupted()?;
                sys.seeded_rates(b0)?;
            }
            let mut col_at = Vec::new();
            let mut col = Vec::new();
            for (i, si) in slot.iter_mut().enumerate() {
                let v: Vec<f64> = (0..nd).map(|a| sys.tangent(a, i, l)).collect();
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(Error::NonFinite("rate-function Jacobian"));
                }
                if v.iter().any(|&x| x != 0.0) {
                    if *si == usize::MAX {
                        *si = offsets.len();
                        offsets.push(sys.offset(i));
                    }
                    col_at.push(*si);
                    col.push((sys.offset(i), v));
                }
            }
            cols.push(col);
            at.push(col_at);
        }
        let zero_sum = zero_sums(&cols, nd);
        // auxiliary rates may depend on velocities, and on the auxiliary state itself (δ-SPH
        // density diffusion: J_qq ≠ 0, which makes the system dissipative), not on positions
        check_rest(
            &cols,
            |a| iq.contains(&a),
            |b| iv.contains(&b) || iq.contains(&b),
        )?;
        Ok(Self {
            cols,
            zero_sum,
            offsets,
            at,
            ix,
            iv,
            iq,
        })
    }

    /// Degrees of freedom per cell.
    pub fn size(&self) -> usize {
        self.cols.len()
    }

    /// J(k) (physical units) for the phase θ = k·r of an offset r.
    pub fn jacobian(&self, phase: impl Fn(&O) -> f64) -> DMatrix<Complex64> {
        let ph: Vec<Phase> = self.offsets.iter().map(|o| Phase::of(phase(o))).collect();
        bloch_sum(&self.cols, &self.at, &self.zero_sum, |i, _| ph[i])
    }

    /// J(k) from tabulated phase factors ([`Phase`] of each offset): the same sums as
    /// [`Self::jacobian`] without a libm call.
    pub fn jacobian_tabulated(&self, phase: impl Fn(&O) -> Phase) -> DMatrix<Complex64> {
        bloch_sum(&self.cols, &self.at, &self.zero_sum, |_, o| phase(o))
    }

    /// The entries of J that the mechanical reduction K = −(J_vx + Σ_q J_vq J_qv) reads
    /// ([`Self::stiffness`]): (v, x), (v, q) and (q, v), with their nonzero terms, and the
    /// offsets those terms use (a subset of all: a Bloch sum of these entries needs only their
    /// phases).
    pub fn mechanical_entries(&self) -> SparseJacobian<O> {
        let mut slot = vec![usize::MAX; self.offsets.len()];
        let mut offsets = Vec::new();
        let mut entries = Vec::new();
        for (b, (col, col_at)) in self.cols.iter().zip(&self.at).enumerate() {
            let rows: &[usize] = if self.iv.contains(&b) {
                &self.iq
            } else {
                &self.iv
            };
            for &a in rows {
                let mut terms = Vec::new();
                for ((o, c), &i) in col.iter().zip(col_at) {
                    if c[a] != 0.0 {
                        if slot[i] == usize::MAX {
                            slot[i] = offsets.len();
                            offsets.push(*o);
                        }
                        terms.push((slot[i], c[a]));
                    }
                }
                if !terms.is_empty() {
                    entries.push(Sparse {
                        a,
                        b,
                        minus_one: self.zero_sum[a][b],
                        terms,
                    });
                }
            }
        }
        SparseJacobian { offsets, entries }
    }

    /// J(k) with only the entries of `sp` filled (the others zero): the same sums, in the same
    /// order, as [`Self::jacobian`] for those entries, with the phase of each offset computed
    /// once.
    pub fn jacobian_sparse(
        &self,
        sp: &SparseJacobian<O>,
        phase: impl Fn(&O) -> f64,
    ) -> DMatrix<Complex64> {
        let ph: Vec<Phase> = sp.offsets.iter().map(|o| Phase::of(phase(o))).collect();
        let nd = self.cols.len();
        let mut j = DMatrix::<Complex64>::zeros(nd, nd);
        for e in &sp.entries {
            let mut acc = Complex64::new(0.0, 0.0);
            for &(i, v) in &e.terms {
                acc += ph[i].factor(e.minus_one) * v;
            }
            j[(e.a, e.b)] = acc;
        }
        j
    }

    /// The terms of entry (a, b) of J(k): the nonzero A_ab(i) with their offsets, in the order of
    /// the Bloch sum, and whether the entry is summed with e^{−iθ} − 1 ([`zero_sums`]).
    pub fn entry(&self, a: usize, b: usize) -> Entry<O> {
        Entry {
            terms: self.cols[b]
                .iter()
                .filter(|(_, c)| c[a] != 0.0)
                .map(|(o, c)| (*o, c[a]))
                .collect(),
            minus_one: self.zero_sum[a][b],
        }
    }

    /// Largest offset (by `norm`) of any nonzero column entry.
    pub fn reach(&self, norm: impl Fn(&O) -> i64) -> i64 {
        self.cols
            .iter()
            .flatten()
            .map(|(o, _)| norm(o))
            .max()
            .unwrap_or(0)
    }

    /// Whether velocities enter the accelerations (artificial viscosity) or the auxiliary state
    /// enters its own rate (δ-SPH density diffusion): then the mechanical reduction
    /// K = −(J_vx + J_vq J_qv) is not the whole system and only the eigenvalue route applies.
    pub fn is_dissipative(&self) -> bool {
        let enters = |cols: &[usize], rows: &[usize]| {
            cols.iter().any(|&b| {
                self.cols[b]
                    .iter()
                    .any(|(_, c)| rows.iter().any(|&a| c[a] != 0.0))
            })
        };
        enters(&self.iv, &self.iv) || enters(&self.iq, &self.iq)
    }

    /// Entry (a, b) of the reduced stiffness K = −(J_vx + Σ_q J_vq J_qv) of the mechanical
    /// branches (ω² = eigenvalues of K; exact for non-dissipative systems).
    pub fn stiffness(&self, j: &DMatrix<Complex64>, a: usize, b: usize) -> Complex64 {
        let mut v = -j[(self.iv[a], self.ix[b])];
        for &q in &self.iq {
            v -= j[(self.iv[a], q)] * j[(q, self.iv[b])];
        }
        v
    }

    /// Amplification matrix of one cycle of `integ` with step `dt` (units of J⁻¹) of the mode with
    /// Jacobian `j` ([`ModeSystem::amplification_with`]).
    pub fn amplification(
        &self,
        j: DMatrix<Complex64>,
        dt: f64,
        integ: Integrator,
    ) -> DMatrix<Complex64> {
        ModeSystem::new(j, self.ix.clone(), self.iv.clone(), self.iq.clone())
            .amplification_with(integ, dt)
    }

    /// Growth per step of `integ` with step `dt` (units of J⁻¹) of the mode with Jacobian `j`
    /// ([`ModeSystem::growth_per_step`]).
    pub fn growth_per_step(
        &self,
        j: DMatrix<Complex64>,
        dt: f64,
        integ: Integrator,
    ) -> Result<f64> {
        ModeSystem::new(j, self.ix.clone(), self.iv.clone(), self.iq.clone())
            .growth_per_step(integ, dt)
    }
}

impl<O: Copy + PartialEq> Columns<O> {
    /// The columns A(t) = A₀ + t (A₁ − A₀) between `self` (t = 0) and `other` (t = 1), when
    /// both have the same structure (dofs, and the same offsets in the same order in every
    /// column); `None` otherwise. Exact for a rate function whose Jacobian is affine in the
    /// parameter that distinguishes the two (the atlas verifies it before using it).
    pub fn lerp(&self, other: &Self, t: f64) -> Option<Self> {
        if self.ix != other.ix || self.iv != other.iv || self.iq != other.iq {
            return None;
        }
        let mut cols = Vec::with_capacity(self.cols.len());
        for (ca, cb) in self.cols.iter().zip(&other.cols) {
            if ca.len() != cb.len() || ca.iter().zip(cb).any(|(x, y)| x.0 != y.0) {
                return None;
            }
            cols.push(
                ca.iter()
                    .zip(cb)
                    .map(|((o, va), (_, vb))| {
                        (
                            *o,
                            va.iter().zip(vb).map(|(a, b)| a + t * (b - a)).collect(),
                        )
                    })
                    .collect(),
            );
        }
        let zero_sum = zero_sums(&cols, self.cols.len());
        Some(Self {
            cols,
            zero_sum,
            offsets: self.offsets.clone(),
            at: self.at.clone(),
            ix: self.ix.clone(),
            iv: self.iv.clone(),
            iq: self.iq.clone(),
        })
    }

    /// max |A_self − A_other| over every entry (an offset missing on one side counts as zero
    /// there), relative to the largest |A| of either; `None` if the dofs differ.
    pub fn distance(&self, other: &Self) -> Option<f64> {
        if self.ix != other.ix || self.iv != other.iv || self.iq != other.iq {
            return None;
        }
        let (mut diff, mut big) = (0.0f64, 0.0f64);
        for (ca, cb) in self.cols.iter().zip(&other.cols) {
            for (o, va) in ca {
                big = va.iter().fold(big, |m, v| m.max(v.abs()));
                match cb.iter().find(|(p, _)| p == o) {
                    Some((_, vb)) => {
                        diff = va
                            .iter()
                            .zip(vb)
                            .fold(diff, |m, (a, b)| m.max((a - b).abs()))
                    }
                    None => diff = va.iter().fold(diff, |m, v| m.max(v.abs())),
                }
            }
            for (o, vb) in cb {
                big = vb.iter().fold(big, |m, v| m.max(v.abs()));
                if !ca.iter().any(|(p, _)| p == o) {
                    diff = vb.iter().fold(diff, |m, v| m.max(v.abs()));
                }
            }
        }
        Some(if big > 0.0 { diff / big } else { diff })
    }
}

/// The phase factors of one offset at one wave vector, θ = k·r: cos θ, sin θ and
/// e^{−iθ} − 1's real part −2 sin²(θ/2) (exact as θ → 0). Computed once per (k, r) by
/// [`Phase::of`]; the 1D engine tabulates them once per κ grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Phase {
    /// cos θ.
    pub cos: f64,
    /// sin θ.
    pub sin: f64,
    /// −2 sin²(θ/2) = cos θ − 1 without cancellation.
    pub cos_m1: f64,
}

impl Phase {
    /// The factors of θ.
    #[inline]
    pub fn of(t: f64) -> Self {
        let half = (0.5 * t).sin();
        Self {
            cos: t.cos(),
            sin: t.sin(),
            cos_m1: -2.0 * half * half,
        }
    }

    /// e^{−iθ}, or e^{−iθ} − 1 when `minus_one`.
    #[inline]
    pub fn factor(self, minus_one: bool) -> Complex64 {
        Complex64::new(if minus_one { self.cos_m1 } else { self.cos }, -self.sin)
    }
}

/// Some entries of J with the offsets they use ([`Columns::mechanical_entries`]).
#[derive(Clone, Debug)]
pub(crate) struct SparseJacobian<O> {
    offsets: Vec<O>,
    entries: Vec<Sparse>,
}

/// One Jacobian entry (a, b) with its nonzero terms (index of the offset in
/// [`SparseJacobian`]'s offsets, A_ab) in the order of the Bloch sum.
#[derive(Clone, Debug)]
pub(crate) struct Sparse {
    a: usize,
    b: usize,
    minus_one: bool,
    terms: Vec<(usize, f64)>,
}

/// The terms of one Jacobian entry (a, b) ([`Columns::entry`]).
#[derive(Clone, Debug)]
pub(crate) struct Entry<O> {
    /// (offset r_i, A_ab(i)) for the nonzero terms, in the order of the Bloch sum.
    pub terms: Vec<(O, f64)>,
    /// Whether the entry is summed with e^{−ik·r} − 1 (its k = 0 sum vanishes).
    pub minus_one: bool,
}

impl<O> Entry<O> {
    /// J_ab(k) = Σ_i A_ab(i) (e^{−iθ_i} [− 1]) with θ_i's factors from `phase` — the same
    /// operations in the same order as [`bloch_sum`], so the same result to the last bit.
    #[inline]
    pub fn sum(&self, phase: impl Fn(&O) -> Phase) -> Complex64 {
        let mut acc = Complex64::new(0.0, 0.0);
        for (o, v) in &self.terms {
            acc += phase(o).factor(self.minus_one) * *v;
        }
        acc
    }
}

/// The Bloch sum of Jacobian columns: J_ab(k) = Σ_j A_ab(j) e^{−iθ_j}, θ_j = k·r_j with the
/// factors of θ_j from `phase(index of the offset in Columns::offsets, offset)`, with the entries whose k = 0 sum vanishes ([`zero_sums`])
/// summed as Σ_j A_ab(j)(e^{−iθ_j} − 1), e^{−iθ} − 1 = −2 sin²(θ/2) − i sin θ — exact as k → 0.
fn bloch_sum<O>(
    cols: &[Vec<(O, Vec<f64>)>],
    at: &[Vec<usize>],
    zero_sum: &[Vec<bool>],
    phase: impl Fn(usize, &O) -> Phase,
) -> DMatrix<Complex64> {
    let nd = cols.len();
    let mut j = DMatrix::<Complex64>::zeros(nd, nd);
    for (b, (col, col_at)) in cols.iter().zip(at).enumerate() {
        for ((o, c), &i) in col.iter().zip(col_at) {
            let p = phase(i, o);
            for (a, &v) in c.iter().enumerate() {
                if v != 0.0 {
                    j[(a, b)] += p.factor(zero_sum[a][b]) * v;
                }
            }
        }
    }
    j
}

/// For each Jacobian entry (a, b): whether its k = 0 sum Σ_i A_ab(i) vanishes to rounding
/// ([`ZERO_SUM_TOL`]); such entries are summed with e^{−ik·R} − 1 (exact as k → 0).
fn zero_sums<O>(cols: &[Vec<(O, Vec<f64>)>], nd: usize) -> Vec<Vec<bool>> {
    let mut zs = vec![vec![false; nd]; nd];
    for (b, col) in cols.iter().enumerate() {
        for (a, row) in zs.iter_mut().enumerate() {
            let s: f64 = col.iter().map(|(_, c)| c[a]).sum();
            let abs: f64 = col.iter().map(|(_, c)| c[a].abs()).sum();
            row[b] = s.abs() <= ZERO_SUM_TOL * abs;
        }
    }
    zs
}

/// The mechanical reduction assumes the auxiliary rates depend on velocities (and, when
/// dissipative, on the auxiliary state) only at rest: entries (auxiliary row, position column) above [`REST_RATE_TOL`] of the largest are an error.
fn check_rest<O>(
    cols: &[Vec<(O, Vec<f64>)>],
    aux_row: impl Fn(usize) -> bool,
    vel_col: impl Fn(usize) -> bool,
) -> Result<()> {
    let (mut big, mut bad) = (0.0f64, 0.0f64);
    for (b, col) in cols.iter().enumerate() {
        for (_, c) in col {
            for (a, &v) in c.iter().enumerate() {
                big = big.max(v.abs());
                if aux_row(a) && !vel_col(b) {
                    bad = bad.max(v.abs());
                }
            }
        }
    }
    if bad > REST_RATE_TOL * big {
        return Err(Error::NonFinite(
            "rest-state structure (auxiliary rate depends on positions)",
        ));
    }
    Ok(())
}

/// Eigenvalues of a small complex matrix by nalgebra's complex Schur decomposition
/// (`Schur::try_new`, bounded iterations: an error, never a hang, if it does not converge).
///
/// The matrix is balanced first (`balance`, exact). nalgebra deflates when
/// |h_{i+1,i}| ≤ ε(|h_ii| + |h_{i+1,i+1}|), which never fires for zero eigenvalues on a zero
/// diagonal (our Jacobians are mostly zeros), so the first attempt is on m + μI, μ = ‖m‖₁ + 1,
/// the eigenvalues shifted back (absolute error O(ε‖m‖)). The iteration has no exceptional
/// shifts and stalls on some well-posed matrices: highly non-normal ones with many zero
/// eigenvalues next to clusters of equal modulus, e.g. 9 % of the 14 × 14 `verlet-euler` cycles
/// of a 2D `timestep` with viscosity, 0.08 % of the 19 × 19 Jacobians of a 3D `lnl` query with
/// viscosity. Those are retried on exactly similar matrices, each attempt with the same bound:
/// m unshifted (converged on 98 % of 2,991 stalled matrices from the tests and CLI commands),
/// then P m P with P the order-reversing permutation (converged on all the rest), then m + iμI
/// (also converged on all the rest). The permutation is exact and the shifts add O(εμ) as in
/// the first attempt, so the accuracy is the Schur decomposition's own.
pub fn eigen(m: DMatrix<Complex64>) -> Result<Vec<Complex64>> {
    let n = m.nrows();
    if n == 1 {
        return Ok(vec![m[(0, 0)]]);
    }
    if m.iter().any(|z| !(z.re.is_finite() && z.im.is_finite())) {
        return Err(Error::NonFinite("Schur decomposition (non-finite matrix)"));
    }
    let mut m = m;
    balance(&mut m);
    let mu = Complex64::new(norm1(&m) + 1.0, 0.0);
    let zero = Complex64::new(0.0, 0.0);
    let reversed = || DMatrix::from_fn(n, n, |i, j| m[(n - 1 - i, n - 1 - j)]);
    shifted_schur(&m, mu)
        .or_else(|| shifted_schur(&m, zero))
        .or_else(|| shifted_schur(&reversed(), zero))
        .or_else(|| shifted_schur(&m, Complex64::new(0.0, mu.re)))
        .or_else(|| centred_schur(&m))
        .or_else(|| {
            let h = reflected(&m);
            shifted_schur(&h, mu).or_else(|| shifted_schur(&h, zero))
        })
        .ok_or(Error::NonFinite("Schur decomposition (no convergence)"))
}

/// Whether [`eigen`]'s first attempt (nalgebra's Schur form of the balanced m + μI) stalls on
/// `m`, so that a retry answers: for `benches/eigen.rs`, which times the retries on the matrices
/// that need them.
pub fn eigen_stalls_first_attempt(m: &DMatrix<Complex64>) -> bool {
    let mut m = m.clone();
    balance(&mut m);
    let mu = Complex64::new(norm1(&m) + 1.0, 0.0);
    shifted_schur(&m, mu).is_none()
}

/// Diagonal balancing (Parlett & Reinsch 1969, LAPACK's xGEBAL without permutations): m ←
/// D⁻¹ m D with D a diagonal of powers of 2 chosen so that each row and column have comparable
/// norms. Exact in floating point (powers of 2), so the eigenvalues are unchanged, while the
/// Schur shift and deflation tests then see entries of one scale: a Jacobian whose position
/// rows are in physical units next to normalised velocities (entries Δx/c and c/Δx side by side,
/// 1e6 and 1e-6 on a lattice of Δx = 1e6) otherwise loses ~ε Δx/c absolutely.
fn balance(m: &mut DMatrix<Complex64>) {
    const RADIX: f64 = 2.0;
    let n = m.nrows();
    let l1 = |z: &Complex64| z.re.abs() + z.im.abs();
    // converges in a few sweeps; the bound only guards against a pathological matrix
    for _ in 0..100 {
        let mut done = true;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for j in (0..n).filter(|&j| j != i) {
                c += l1(&m[(j, i)]);
                r += l1(&m[(i, j)]);
            }
            if c == 0.0 || r == 0.0 || !(c.is_finite() && r.is_finite()) {
                continue;
            }
            let s = c + r;
            let mut f = 1.0;
            let (lo, hi) = (r / RADIX, r * RADIX);
            while c < lo {
                f *= RADIX;
                c *= RADIX * RADIX;
            }
            while c > hi {
                f /= RADIX;
                c /= RADIX * RADIX;
            }
            if (c + r) / f < 0.95 * s {
                done = false;
                for j in 0..n {
                    m[(i, j)] /= f;
                    m[(j, i)] *= f;
                }
            }
        }
        if done {
            break;
        }
    }
}

/// Largest column sum of |m_ij|.
fn norm1(m: &DMatrix<Complex64>) -> f64 {
    m.column_iter()
        .map(|c| c.iter().map(|z| z.norm()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// Eigenvalues of a clustered matrix, c + s·λ((m − cI)/s) with c the mean of the diagonal and s
/// the 1-norm of m − cI: an amplification matrix at a small Δt is I plus entries of 1e-10, whose
/// eigenvalues agree to 10 digits, and the iteration stalls resolving them against a diagonal of
/// 1; centred and scaled, the same eigenvalue problem has entries of order 1 (the rounding of
/// m − cI is ε|c|, the backward error the iteration has anyway).
fn centred_schur(m: &DMatrix<Complex64>) -> Option<Vec<Complex64>> {
    let n = m.nrows();
    let c = m.trace() / Complex64::new(n as f64, 0.0);
    let d = m - DMatrix::<Complex64>::identity(n, n) * c;
    let s = norm1(&d);
    if s == 0.0 {
        return Some(vec![c; n]);
    }
    let unit = d.map(|z| z / s);
    let mu = Complex64::new(norm1(&unit) + 1.0, 0.0);
    let ev = shifted_schur(&unit, mu).or_else(|| shifted_schur(&unit, Complex64::new(0.0, 0.0)))?;
    Some(ev.into_iter().map(|z| c + z * s).collect())
}

/// H m H with the Householder reflection H = I − 2vv*/(v*v) of a fixed, irregular v: a unitary
/// similarity (rounding ~ε‖m‖, the order of the Schur iteration's own backward error) that
/// breaks the structure a stalled iteration cycles on — e.g. the Jordan blocks (eigenvalue 1,
/// twice) that zero-energy modes put into an amplification matrix, which the diagonal shifts
/// and the reversal above keep.
fn reflected(m: &DMatrix<Complex64>) -> DMatrix<Complex64> {
    let n = m.nrows();
    let v = nalgebra::DVector::<Complex64>::from_fn(n, |i, _| {
        let t = i as f64 + 1.0;
        Complex64::new(
            1.0 + (t * 0.618_033_988_7).fract(),
            (t * 0.414_213_562_4).fract(),
        )
    });
    let s = v.dotc(&v).re;
    let h =
        DMatrix::<Complex64>::identity(n, n) - (&v * v.adjoint()) * Complex64::new(2.0 / s, 0.0);
    &h * m * &h
}

/// Eigenvalues by the Schur form of m + μI, shifted back (with real μ > ‖m‖₁ every eigenvalue
/// of the shifted matrix has positive real part, which steadies the iteration); `None` if the
/// iteration has not converged after 30 sweeps per eigenvalue (LAPACK's limit; a converging
/// iteration takes 2–3).
fn shifted_schur(m: &DMatrix<Complex64>, mu: Complex64) -> Option<Vec<Complex64>> {
    let n = m.nrows();
    let shifted = m + DMatrix::<Complex64>::identity(n, n) * mu;
    let schur = nalgebra::linalg::Schur::try_new(shifted, 4.0 * f64::EPSILON, 30 * n)?;
    let ev = schur.eigenvalues()?;
    Some(ev.iter().map(|&z| z - mu).collect())
}
