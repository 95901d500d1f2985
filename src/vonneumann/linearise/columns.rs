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
    /// Evaluates the rate function at the rest state with a unit dual part on dof `b` of cell 0.
    fn seeded_rate(&mut self, b: usize) -> Result<()>;
    /// Dual part of the rate of dof `a` of cell `i` after [`Self::seeded_rate`].
    fn tangent(&self, a: usize, i: usize) -> f64;
}

/// The Jacobian columns of a linearised periodic system, with the position, velocity and
/// auxiliary dofs of a cell.
#[derive(Clone, Debug)]
pub(crate) struct Columns<O> {
    /// `cols[b]` = (offset of cell i, column A_{·b}(i)) for every cell where it is nonzero.
    cols: Vec<Vec<(O, Vec<f64>)>>,
    /// Whether the k = 0 sum of entry (a, b) is zero to rounding.
    zero_sum: Vec<Vec<bool>>,
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
        for b in 0..nd {
            sys.seeded_rate(b)?;
            let mut col = Vec::new();
            for i in 0..sys.cells() {
                let v: Vec<f64> = (0..nd).map(|a| sys.tangent(a, i)).collect();
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(Error::NonFinite("rate-function Jacobian"));
                }
                if v.iter().any(|&x| x != 0.0) {
                    col.push((sys.offset(i), v));
                }
            }
            cols.push(col);
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
        bloch_sum(&self.cols, &self.zero_sum, phase)
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

/// The Bloch sum of Jacobian columns: J_ab(k) = Σ_j A_ab(j) e^{−iθ_j}, θ_j = `phase(offset_j)`
/// (= k·r_j), with the entries whose k = 0 sum vanishes ([`zero_sums`]) summed as
/// Σ_j A_ab(j)(e^{−iθ_j} − 1), e^{−iθ} − 1 = −2 sin²(θ/2) − i sin θ — exact as k → 0.
fn bloch_sum<O>(
    cols: &[Vec<(O, Vec<f64>)>],
    zero_sum: &[Vec<bool>],
    phase: impl Fn(&O) -> f64,
) -> DMatrix<Complex64> {
    let nd = cols.len();
    let mut j = DMatrix::<Complex64>::zeros(nd, nd);
    for (b, col) in cols.iter().enumerate() {
        for (o, c) in col {
            let t = phase(o);
            let (s, half) = (t.sin(), (0.5 * t).sin());
            let e = Complex64::new(t.cos(), -s);
            let em1 = Complex64::new(-2.0 * half * half, -s);
            for (a, &v) in c.iter().enumerate() {
                if v != 0.0 {
                    j[(a, b)] += if zero_sum[a][b] { em1 * v } else { e * v };
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

/// Eigenvalues of a small complex matrix by the complex Schur decomposition, with bounded
/// iterations (an error, never a hang, if it does not converge). nalgebra deflates when
/// |h_{i+1,i}| ≤ ε(|h_ii| + |h_{i+1,i+1}|), which never fires for zero eigenvalues on a zero
/// diagonal (our Jacobians are mostly zeros), so the matrix is shifted by μ = ‖J‖₁ + 1 first and
/// the eigenvalues shifted back; the absolute error stays O(ε‖J‖).
pub fn eigen(m: DMatrix<Complex64>) -> Result<Vec<Complex64>> {
    let n = m.nrows();
    if n == 1 {
        return Ok(vec![m[(0, 0)]]);
    }
    // nalgebra's Schur iteration has no exceptional shifts and occasionally stalls on a well-posed
    // matrix (seen on amplification matrices of multi-step cycles: highly non-normal, with
    // eigenvalues 0 and 1 of multiplicity 2, or eigenvalues spanning ten decades). Those go to
    // faer's eigenvalue solver (LAPACK-style multishift QR with aggressive deflation and
    // exceptional shifts); nalgebra stays first so that every result that converged before is
    // unchanged.
    if m.iter().any(|z| !(z.re.is_finite() && z.im.is_finite())) {
        return Err(Error::NonFinite("Schur decomposition (non-finite matrix)"));
    }
    let mut m = m;
    balance(&mut m);
    if let Some(ev) = shifted_schur(&m) {
        return Ok(ev);
    }
    let f = faer::Mat::<faer::c64>::from_fn(n, n, |i, j| {
        let z = m[(i, j)];
        faer::c64::new(z.re, z.im)
    });
    match f.eigenvalues() {
        Ok(ev) if ev.iter().all(|z| z.re.is_finite() && z.im.is_finite()) => {
            Ok(ev.into_iter().map(|z| Complex64::new(z.re, z.im)).collect())
        }
        _ => Err(Error::NonFinite(
            "eigenvalue decomposition (no convergence)",
        )),
    }
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

/// Eigenvalues by the Schur form of m + μI, μ = max column sum + 1 (every eigenvalue of the
/// shifted matrix then has positive real part, which steadies the iteration); `None` if the
/// iteration has not converged after 30 sweeps per eigenvalue (LAPACK's limit; a converging
/// iteration takes 2–3).
fn shifted_schur(m: &DMatrix<Complex64>) -> Option<Vec<Complex64>> {
    let n = m.nrows();
    let norm = (0..n)
        .map(|j| m.column(j).iter().map(|z| z.norm()).sum::<f64>())
        .fold(0.0, f64::max)
        + 1.0;
    let mu = Complex64::new(norm, 0.0);
    let shifted = m + DMatrix::<Complex64>::identity(n, n) * mu;
    let schur = nalgebra::linalg::Schur::try_new(shifted, 4.0 * f64::EPSILON, 30 * n)?;
    let ev = schur.eigenvalues()?;
    Some(ev.iter().map(|&z| z - mu).collect())
}
