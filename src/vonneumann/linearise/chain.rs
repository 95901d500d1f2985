//! The 1D front end: a periodic chain of N cells of a [`Model1D`] — every 1D form, including the
//! \[B00\]-only ones with several points per cell (stress points) and a consistent mass (least
//! squares) — linearised by the shared core ([`super::columns`]) and projected onto Fourier modes
//! e^{iκX}.
//!
//! N is large enough that the response to a perturbation of cell 0 never wraps around. The
//! velocity rows of J(κ) are divided by the consistent-mass symbol M̂(κ); the mechanical branch
//! is the scalar reduced stiffness of the core.
//!
//! The six forms the chain shares with 2D and 3D are *not* routed through `Bloch<1>`: the chain
//! must serve the \[B00\] forms anyway (stress points, consistent mass, physical units of a
//! [`Lattice1D`]), so a second 1D engine for the common forms would add code, not remove it; the
//! rate function and every step after the dual-number seeding are already the same code.

use super::columns::{Columns, Linearisable, eigen};
use crate::error::Result;
use crate::forms::{Field, FieldKind, FormKind, MassOperator, Model1D, ModelParams, State1D};
use crate::integrator::Integrator;
use crate::scalar::{Dual, Scalar};
use crate::vonneumann::amplification::Modes;
use nalgebra::DMatrix;
use num_complex::Complex64;

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
    /// Jacobian columns per cell offset.
    core: Columns<i64>,
    /// Consistent-mass stencil (cell offset K, M_{0K}), or empty for lumped masses.
    mass: Vec<(i64, f64)>,
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

/// The periodic chain being differentiated.
struct Chain {
    model: Model1D,
    base: State1D<f64>,
    fields: Vec<Field>,
    out: State1D<Dual>,
    n: usize,
}

impl Chain {
    /// Cell offset of cell i, wrapped into (−n/2, n/2].
    fn wrap(&self, i: usize) -> i64 {
        if i <= self.n / 2 {
            i as i64
        } else {
            i as i64 - self.n as i64
        }
    }
}

impl Linearisable for Chain {
    type Offset = i64;
    fn kinds(&self) -> Vec<FieldKind> {
        self.fields.iter().map(|f| f.kind()).collect()
    }
    fn cells(&self) -> usize {
        self.n
    }
    fn offset(&self, i: usize) -> i64 {
        self.wrap(i)
    }
    fn seeded_rate(&mut self, b: usize) -> Result<()> {
        let mut z: State1D<Dual> = self.base.map(Dual::cst);
        z.field_mut(self.fields[b])[0].d = 1.0;
        self.model.rate(&z, &mut self.out)
    }
    fn tangent(&self, a: usize, i: usize) -> f64 {
        self.out.field(self.fields[a]).get(i).map_or(0.0, |v| v.d)
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
        let fields: Vec<Field> = p.form.fields().to_vec();
        let mut chain = Chain {
            base: model.rest_state(),
            model,
            fields,
            out: State1D::default(),
            n,
        };
        let core = Columns::of(&mut chain)?;
        let mass = match &chain.model.mass_op {
            MassOperator::Lumped => Vec::new(),
            MassOperator::Consistent(rows) => {
                rows[0].iter().map(|&(k, mk)| (chain.wrap(k), mk)).collect()
            }
        };
        let c = (lat.modulus / lat.rho0).sqrt();
        Ok(Linearisation {
            dofs: chain.fields.iter().map(|&field| Dof { field }).collect(),
            core,
            mass,
            omega2_scale: lat.dx * lat.dx / (c * c),
            dx: lat.dx,
            c,
        })
    }

    /// Number of degrees of freedom per cell.
    pub fn size(&self) -> usize {
        self.core.size()
    }

    /// Physical Δx and c of the lattice.
    pub fn units(&self) -> (f64, f64) {
        (self.dx, self.c)
    }

    /// Per-mode Jacobian block J(κ) (physical units; κ is κΔx), with the velocity rows
    /// multiplied by M̂(κ)⁻¹ for a consistent mass.
    pub fn jacobian(&self, kappa: f64) -> DMatrix<Complex64> {
        let mut j = self.core.jacobian(|&i| kappa * i as f64);
        if !self.mass.is_empty() {
            let m = self.mass_symbol(kappa);
            let iv = self.core.iv[0];
            for b in 0..self.size() {
                j[(iv, b)] /= m;
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
        self.core.is_dissipative()
    }

    /// Normalised ω²Δx²/c² of the mechanical branch from the reduced stiffness
    /// K(κ) = −(J_vx + Σ_q J_vq J_qv) (exact for non-dissipative systems).
    /// Returns (ω², |Im K| / max(|K|, 1) as a consistency diagnostic).
    pub fn omega2(&self, kappa: f64) -> (f64, f64) {
        let k = self.core.stiffness(&self.jacobian(kappa), 0, 0);
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

impl Modes for Linearisation {
    type K = f64;
    fn is_dissipative(&self) -> bool {
        self.core.is_dissipative()
    }
    fn omega2_top(&self, kappa: f64) -> f64 {
        self.omega2(kappa).0
    }
    fn amplification_with(&self, kappa: f64, dt: f64, integ: Integrator) -> DMatrix<Complex64> {
        self.core
            .amplification(self.jacobian(kappa), dt * self.dx / self.c, integ)
    }
    fn growth_per_step(&self, kappa: f64, dt: f64, integ: Integrator) -> Result<f64> {
        self.core
            .growth_per_step(self.jacobian(kappa), dt * self.dx / self.c, integ)
    }
    fn eigenvalues(&self, kappa: f64) -> Result<Vec<Complex64>> {
        Linearisation::eigenvalues(self, kappa)
    }
}

/// Convenience: does this form use a consistent mass?
pub fn has_consistent_mass(form: FormKind) -> bool {
    form == FormKind::LeastSquares
}
