//! The numeric route: linearise a form's rate function about the uniformly pre-stressed
//! periodic lattice and project onto Fourier modes.
//!
//! A periodic chain of N cells is built (N large enough that the response to a perturbation
//! of cell 0 never wraps around). Each degree of freedom of cell 0 is perturbed with a dual
//! number and the *same* rate function the solver integrates is evaluated once: the dual
//! parts are the exact Jacobian column `A_ab(i) = ∂ż_{a,i}/∂z_{b,0}`. The per-mode Jacobian
//! block is `J_ab(κ) = Σ_i A_ab(i) e^{−iκ i}`. Entries whose κ = 0 sum vanishes to rounding
//! (translation and Galilean invariance) are summed as `Σ_i A_ab(i)(e^{−iκ i} − 1)` with
//! `e^{−iκi} − 1 = −2 sin²(κi/2) − i sin κi`, which keeps full relative accuracy as κ → 0.

use crate::error::{Error, Result};
use crate::forms::{Field, FieldKind, FormKind, MassOperator, Model1D, ModelParams, State1D};
use crate::scalar::{Dual, Scalar};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// A κ = 0 sum is treated as exactly zero when below this fraction of Σ|A_ab(i)|.
pub const ZERO_SUM_TOL: f64 = 1e-12;
/// A q-rate Jacobian entry ∂q̇/∂x or ∂q̇/∂q at rest larger than this (relative) is reported as an
/// error: the mechanical reduction assumes auxiliary rates vanish at rest.
pub const REST_RATE_TOL: f64 = 1e-9;

/// One degree of freedom of a lattice cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dof {
    /// The field.
    pub field: Field,
}

/// The Fourier-projected linearisation of a 1D form.
#[derive(Clone, Debug)]
pub struct Linearisation {
    /// Degrees of freedom of a cell, in order.
    pub dofs: Vec<Dof>,
    /// `cols[b]` = list of (cell offset i, column A_{·b}(i) of length `dofs.len()`).
    cols: Vec<Vec<(i64, Vec<f64>)>>,
    /// Consistent-mass stencil (cell offset K, M_{0K}), or empty for lumped masses.
    mass: Vec<(i64, f64)>,
    /// Whether the κ = 0 sum of entry (a, b) is zero to rounding.
    zero_sum: Vec<Vec<bool>>,
    /// Index of the position, velocity DOFs.
    ix: usize,
    iv: usize,
    /// Scale factors to normalised units: ω² · (Δx² ρ0 / C).
    omega2_scale: f64,
    /// Physical Δx and c.
    dx: f64,
    c: f64,
}

/// The physical setting of a linearisation.
#[derive(Clone, Copy, Debug)]
pub struct Lattice1D {
    /// Lattice spacing Δx (physical).
    pub dx: f64,
    /// Reference density ρ0.
    pub rho0: f64,
    /// Tangent modulus C.
    pub modulus: f64,
}

impl Default for Lattice1D {
    fn default() -> Self {
        Self {
            dx: 1.0,
            rho0: 1.0,
            modulus: 1.0,
        }
    }
}

impl Linearisation {
    /// Linearises the form described by `p` (its `sigma0` is the pre-stress, physical units) on
    /// the uniform periodic lattice `lat`.
    pub fn new(p: ModelParams, lat: Lattice1D) -> Result<Self> {
        let support_cells = p.kp.support() / lat.dx;
        // Coupling range: shape functions at a point depend on masters within R, the stress of a
        // master on velocities within R, and the force on stresses within R: < 3R + 2 cells.
        let range = (3.0 * support_cells).ceil() as usize + 3;
        let n = (2 * range + 1).max(9);
        let x_ref: Vec<f64> = (0..n).map(|i| i as f64 * lat.dx).collect();
        let vol = vec![lat.dx; n];
        let model = Model1D::new(p, x_ref, vol, Some(n as f64 * lat.dx))?;
        let base = model.rest_state();
        let fields: Vec<Field> = p.form.fields().to_vec();
        let dofs: Vec<Dof> = fields.iter().map(|&field| Dof { field }).collect();
        let nd = dofs.len();
        let ix = fields
            .iter()
            .position(|f| f.kind() == FieldKind::Position)
            .ok_or(Error::NonFinite("layout"))?;
        let iv = fields
            .iter()
            .position(|f| f.kind() == FieldKind::Velocity)
            .ok_or(Error::NonFinite("layout"))?;
        let offset = |i: usize| -> i64 {
            if i <= n / 2 {
                i as i64
            } else {
                i as i64 - n as i64
            }
        };
        let mut cols = Vec::with_capacity(nd);
        let mut out = State1D::<Dual>::default();
        for b in &dofs {
            let mut z: State1D<Dual> = base.map(Dual::cst);
            z.field_mut(b.field)[0].d = 1.0;
            model.rate(&z, &mut out)?;
            let mut col: Vec<(i64, Vec<f64>)> =
                (0..n).map(|i| (offset(i), vec![0.0; nd])).collect();
            for (a, da) in dofs.iter().enumerate() {
                for (i, val) in out.field(da.field).iter().enumerate() {
                    if !val.d.is_finite() {
                        return Err(Error::NonFinite("rate-function Jacobian"));
                    }
                    col[i].1[a] = val.d;
                }
            }
            col.retain(|(_, c)| c.iter().any(|&v| v != 0.0));
            cols.push(col);
        }
        let mass = match &model.mass_op {
            MassOperator::Lumped => Vec::new(),
            MassOperator::Consistent(rows) => {
                rows[0].iter().map(|&(k, mk)| (offset(k), mk)).collect()
            }
        };
        let zero_sum = zero_sums(&cols, nd);
        let c = (lat.modulus / lat.rho0).sqrt();
        let lin = Linearisation {
            dofs,
            cols,
            mass,
            zero_sum,
            ix,
            iv,
            omega2_scale: lat.dx * lat.dx / (c * c),
            dx: lat.dx,
            c,
        };
        lin.check_rest_structure()?;
        Ok(lin)
    }

    /// Number of degrees of freedom per cell.
    pub fn size(&self) -> usize {
        self.dofs.len()
    }

    /// Physical Δx and c of the lattice.
    pub fn units(&self) -> (f64, f64) {
        (self.dx, self.c)
    }

    fn check_rest_structure(&self) -> Result<()> {
        let (ix, iv) = (self.ix, self.iv);
        check_rest(&self.cols, |a| a != ix && a != iv, |b| b == iv)
    }

    /// Per-mode Jacobian block J(κ) (physical units; κ is κΔx), with the velocity rows
    /// multiplied by M̂(κ)⁻¹ for a consistent mass.
    pub fn jacobian(&self, kappa: f64) -> DMatrix<Complex64> {
        let nd = self.size();
        let mut j = bloch_sum(&self.cols, &self.zero_sum, |&i| kappa * i as f64);
        if !self.mass.is_empty() {
            let m = self.mass_symbol(kappa);
            for b in 0..nd {
                j[(self.iv, b)] /= m;
            }
        }
        j
    }

    /// M̂(κ) = Σ_K M_{0K} e^{iκK} (1 for lumped masses, in units of the lumped mass).
    pub fn mass_symbol(&self, kappa: f64) -> Complex64 {
        if self.mass.is_empty() {
            return Complex64::new(1.0, 0.0);
        }
        self.mass
            .iter()
            .map(|&(k, m)| Complex64::from_polar(m, kappa * k as f64))
            .sum()
    }

    /// Whether the velocity rows depend on velocities (artificial viscosity): then only the
    /// eigenvalue route applies.
    pub fn is_dissipative(&self) -> bool {
        self.cols[self.iv].iter().any(|(_, c)| c[self.iv] != 0.0)
    }

    /// Normalised ω²Δx²/c² of the mechanical branch from the reduced stiffness
    /// K(κ) = −(J_vx + Σ_q J_vq J_qv) (exact for non-dissipative systems).
    /// Returns (ω², |Im K| / max(|K|, 1) as a consistency diagnostic).
    pub fn omega2(&self, kappa: f64) -> (f64, f64) {
        let j = self.jacobian(kappa);
        let mut k = -j[(self.iv, self.ix)];
        for q in 0..self.size() {
            if q != self.ix && q != self.iv {
                k -= j[(self.iv, q)] * j[(q, self.iv)];
            }
        }
        let w2 = k.re * self.omega2_scale;
        (w2, k.im.abs() * self.omega2_scale / w2.abs().max(1.0))
    }

    /// Eigenvalues s of J(κ), normalised to c/Δx.
    pub fn eigenvalues(&self, kappa: f64) -> Result<Vec<Complex64>> {
        let j = self.jacobian(kappa) * Complex64::new(self.dx / self.c, 0.0);
        eigen(j)
    }

    /// Growth rate γ(κ) = max Re s ≥ 0 in c/Δx units. Non-dissipative systems use the exact
    /// reduced route γ = sqrt(max(0, −ω²)); dissipative ones the eigenvalues of J(κ).
    pub fn growth(&self, kappa: f64) -> Result<f64> {
        if self.is_dissipative() {
            let ev = self.eigenvalues(kappa)?;
            Ok(ev.iter().map(|s| s.re).fold(0.0, f64::max))
        } else {
            Ok((-self.omega2(kappa).0).max(0.0).sqrt())
        }
    }
}

/// The Bloch sum of Jacobian columns: J_ab(k) = Σ_j A_ab(j) e^{−iθ_j}, θ_j = `phase(offset_j)`
/// (= k·r_j), with the entries whose κ = 0 sum vanishes ([`zero_sums`]) summed as
/// Σ_j A_ab(j)(e^{−iθ_j} − 1), e^{−iθ} − 1 = −2 sin²(θ/2) − i sin θ — exact as k → 0. The one
/// projection of the 1D and the 2D/3D engines.
pub(crate) fn bloch_sum<O>(
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

/// For each Jacobian entry (a, b): whether its κ = 0 sum Σ_i A_ab(i) vanishes to rounding
/// ([`ZERO_SUM_TOL`]); such entries are summed with e^{−ik·R} − 1 (exact as k → 0).
pub(crate) fn zero_sums<O>(cols: &[Vec<(O, Vec<f64>)>], nd: usize) -> Vec<Vec<bool>> {
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

/// The mechanical reduction assumes the auxiliary rates depend on velocities only at rest:
/// entries (auxiliary row, non-velocity column) above [`REST_RATE_TOL`] of the largest are an error.
pub(crate) fn check_rest<O>(
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
    let mu = (0..n)
        .map(|j| m.column(j).iter().map(|z| z.norm()).sum::<f64>())
        .fold(0.0, f64::max)
        + 1.0;
    let shifted = m + DMatrix::<Complex64>::identity(n, n) * Complex64::new(mu, 0.0);
    let schur = nalgebra::linalg::Schur::try_new(shifted, 4.0 * f64::EPSILON, 100 * n * n)
        .ok_or(Error::NonFinite("Schur decomposition (no convergence)"))?;
    let ev = schur
        .eigenvalues()
        .ok_or(Error::NonFinite("Schur eigenvalues"))?;
    Ok(ev.iter().map(|&z| z - mu).collect())
}

/// Convenience: does this form use a consistent mass?
pub fn has_consistent_mass(form: FormKind) -> bool {
    form == FormKind::LeastSquares
}
