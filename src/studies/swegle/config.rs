//! The Swegle test's configuration: the published box and its variants, checked field by field
//! (with the memory and step budget), and built into a run at rest with the kick applied.

use crate::budget::{Budget, fmt_count};
use crate::error::{Error, Result, Text, check_range, field, fields};
use crate::forms::{FormKind, Material, Model, ModelParams};
use crate::kernel::Kernel;
use crate::params::{check_art_stress_dim, check_common};
use crate::shape::{KernelParams, ShapeFamily};
use crate::solver::run::{BoundaryDensity, Run};
use crate::studies::box_operator::MAX_DENSE_DOFS;
use std::f64::consts::PI;

/// Largest number of free mechanical degrees of freedom (D × free particles) up to which the
/// dense exact operator ([`box_growth`](crate::studies::box_operator::box_growth): every
/// eigenvalue, exact for every form) decides the box prediction when the iterative search
/// ([`box_growth_iterative`](crate::studies::box_operator::box_growth_iterative)) finds no
/// growing mode within as many products as the box has degrees of freedom: the fastest modes
/// are then the zero-energy modes at ω² ≈ 0, a cluster no Krylov method resolves (larger boxes
/// fall back to the standing modes the box admits). 1,000 in both dimensions: up to `size` 28
/// in 2D (22² free particles) and 12 in 3D (6³ free particles) with 3 fixed layers.
pub const MAX_DENSE_BOX_DOFS: usize = 1000;

/// Default particles per side: 21 in 2D (the published box), 12 in 3D (the largest box the
/// dense operator covers, [`dense_size_limit`]; every box is predicted by the iterative
/// eigen-solver, 12³ in ~4 s, 21³ in ~1 min).
pub const fn default_size(dim: usize) -> usize {
    if dim == 3 { 12 } else { 21 }
}

/// Largest particles per side: 2001 in 2D, 201 in 3D (both also bounded by the memory and
/// step budgets).
pub const fn max_size(dim: usize) -> usize {
    if dim == 3 { 201 } else { 2001 }
}

/// Wave vectors per axis of [0, π] sampled for the infinite-lattice rate (the irreducible wedge
/// κ_1 ≥ … ≥ κ_D ≥ 0 of the square / simple-cubic zone, spacing π/n): 96 in 2D, 48 in 3D.
pub const fn infinite_grid(dim: usize) -> usize {
    if dim == 3 { 48 } else { 96 }
}

/// Largest `size` whose box prediction falls back to the dense operator (when the iterative
/// search finds no growing mode), with `layers` fixed layers.
pub fn dense_size_limit(dim: usize, layers: usize) -> usize {
    let mut nf = 0;
    while dim * (nf + 1usize).pow(dim as u32) <= MAX_DENSE_BOX_DOFS.min(MAX_DENSE_DOFS) {
        nf += 1;
    }
    nf + 2 * layers
}

/// Configuration of a Swegle run.
#[derive(Clone, Copy, Debug)]
pub struct SwegleConfig {
    /// Dimension D (2 or 3): the box holds `size`^D particles.
    pub dim: usize,
    /// Form.
    pub form: FormKind,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// Shape family.
    pub shape: ShapeFamily,
    /// h/Δx.
    pub h_over_dx: f64,
    /// f = ρ/ρ0 (< 1 tension).
    pub density_ratio: f64,
    /// Particles per side (21, 41, 81, … in 2D; [`default_size`]).
    pub size: usize,
    /// Fixed layers per side.
    pub layers: usize,
    /// Spacing Δx.
    pub dx: f64,
    /// ρ0.
    pub rho0: f64,
    /// Bulk modulus K.
    pub bulk: f64,
    /// End time, in the test's units (not Δx/c).
    pub t_end: f64,
    /// Initial v_x of the centre particle (1e−10, as published), in [1e−15, 1e−9]: below the
    /// fit window, above the rounding of the positions (a displacement of 1e−16 per step is
    /// lost in the rounding of a coordinate of 0.5). A smaller kick gives the fastest mode more
    /// e-folds to outgrow the slower ones before the fit window.
    pub kick: f64,
    /// Boundary density treatment.
    pub boundary: BoundaryDensity,
    /// Time step Δt in Δx/c, in (0, 2] (the CFL number c Δt/h is dt/(h/Δx));
    /// [`SwegleConfig::dt_physical`] in the test's units.
    pub dt: f64,
    /// Fit window for max |v|.
    pub window: (f64, f64),
    /// Partition coefficient (lnl / cll).
    pub c_partition: f64,
    /// Artificial stress (ε, n) of the classical form (None: off, as in the published test).
    pub art_stress: Option<(f64, i32)>,
    /// Extend `t_end` so that a mode growing at the box prediction can rise from the kick to the
    /// top of the fit window (1.5 ln(window top / kick) / γ_box), never shortening it.
    pub until_window: bool,
    /// Time integrator (default `kdk`; [`crate::integrator`]).
    pub integrator: crate::integrator::Integrator,
    /// δ-SPH density diffusion (δ, form); None: off, as in the published test.
    pub diffusion: Option<(f64, crate::forms::DiffusionForm)>,
    /// The budget the run (and its predictions) must stay within.
    pub budget: Budget,
}

impl SwegleConfig {
    /// The published test: 2D, 21×21, 3 fixed layers, Δx = 0.1, ρ0 = 2.8, K = 0.686275,
    /// t_end = 40.
    pub fn new(
        form: FormKind,
        kernel: &'static dyn Kernel,
        h_over_dx: f64,
        density_ratio: f64,
    ) -> Self {
        Self {
            dim: 2,
            form,
            kernel,
            shape: form.default_shape_in(2),
            h_over_dx,
            density_ratio,
            size: 21,
            layers: 3,
            dx: 0.1,
            rho0: 2.8,
            bulk: 0.686275,
            t_end: 40.0,
            kick: 1e-10,
            boundary: BoundaryDensity::Evolve,
            dt: 0.2,
            window: (1e-8, 1e-4),
            c_partition: 0.5,
            until_window: false,
            art_stress: None,
            integrator: crate::integrator::Integrator::Kdk,
            diffusion: None,
            budget: Budget::default(),
        }
    }

    /// The same test in dimension `dim` with that dimension's [`default_size`].
    pub fn with_dim(self, dim: usize) -> Self {
        Self {
            dim,
            size: default_size(dim),
            ..self
        }
    }

    /// Validates the inputs (errors name the fields; the stress σ̄ = 1 − f as `stress`).
    pub fn validate(&self) -> Result<()> {
        if !(2..=3).contains(&self.dim) {
            return Err(Error::OutOfRange {
                field: "dim",
                value: self.dim as f64,
                range: "2 or 3".into(),
            });
        }
        // the density ratio first: the stress σ̄ = 1 − f checked below derives from it
        check_range("density_ratio", self.density_ratio, 0.5, 1.5, true, true)?;
        check_common(
            self.kernel,
            self.h_over_dx,
            1.0 - self.density_ratio,
            self.c_partition,
            None,
            None,
        )?;
        check_range("t_end", self.t_end, 0.0, 1e6, false, true)?;
        check_range("dt", self.dt, 0.0, 2.0, false, true)?;
        check_range("kick", self.kick, 1e-15, 1e-9, true, true)?;
        let top = max_size(self.dim);
        if self.size < 2 * self.layers + 3 || self.size > top {
            return Err(Error::OutOfRange {
                field: "size",
                value: self.size as f64,
                range: Text::from(format!(
                    "must be an integer in [{}, {top}] with ",
                    2 * self.layers + 3
                )) + field("dim")
                    + format!(" {}", self.dim),
            });
        }
        if !self.form.in_every_dimension() {
            return Err(Error::Incompatible(
                field("form") + format!(" {} is not available in {}D", self.form.name(), self.dim),
            ));
        }
        check_art_stress_dim(self.dim, self.art_stress.is_some())?;
        self.form.check_shape(self.shape)?;
        // resources, before anything is allocated (the budget)
        let particles = self.particles() as f64;
        let r = self.kernel.zeta() * self.h_over_dx;
        let neighbours = if self.dim == 3 {
            4.0 / 3.0 * PI * r * r * r + 1.0
        } else {
            PI * r * r + 1.0
        };
        let stencils = if matches!(self.form, FormKind::Lnl | FormKind::Cll) {
            2.0
        } else {
            1.0
        };
        // stencil entries (index, offset, gradient: 8 + 16D B) with a quarter spare, and ~50
        // f64 (2D) or ~125 f64 (3D) of state, integrator copies and diagnostics per particle
        let entry = 8.0 + 16.0 * self.dim as f64;
        let state = if self.dim == 3 { 1000.0 } else { 400.0 };
        let bytes = particles * (neighbours * entry * stencils * 1.25 + state);
        self.budget.memory(
            fields(&["size", "h_over_dx"]),
            &format!(
                "the Swegle box ({} particles, ~{neighbours:.0} neighbours each)",
                self.shape_label()
            ),
            bytes,
        )?;
        let steps = (self.t_end / self.dt_physical()).ceil();
        self.budget.steps(
            fields(&["t_end", "dt", "size"]),
            &format!("the Swegle run ({} time steps)", fmt_count(steps)),
            particles * steps,
        )
    }

    pub(super) fn params(&self) -> ModelParams {
        ModelParams {
            form: self.form,
            shape: self.shape,
            kp: KernelParams {
                kernel: self.kernel,
                h: self.h_over_dx * self.dx,
            },
            material: Material::Hydro { bulk: self.bulk },
            rho0: self.rho0,
            c_partition: self.c_partition,
            av: None,
            art_stress: self
                .art_stress
                .map(|(eps, n)| crate::forms::ArtificialStress {
                    eps,
                    n,
                    spacing: self.dx,
                }),
            diffusion: self
                .diffusion
                .map(|(delta, form)| crate::forms::DensityDiffusion {
                    delta,
                    form,
                    sound_speed: self.sound_speed(),
                }),
            alpha_s: 0.0,
            ls_length: self.dx,
            hourglass: None,
        }
    }

    /// Sound speed c = sqrt(K/ρ0), in the test's units.
    pub fn sound_speed(&self) -> f64 {
        (self.bulk / self.rho0).sqrt()
    }

    /// The time step in the test's units: `dt` × Δx/c.
    pub fn dt_physical(&self) -> f64 {
        self.dt * self.dx / self.sound_speed()
    }

    /// Particles in the box, `size`^D.
    pub fn particles(&self) -> usize {
        self.size.pow(self.dim as u32)
    }

    /// "21 × 21" or "15 × 15 × 15".
    pub fn shape_label(&self) -> String {
        vec![self.size.to_string(); self.dim].join(" × ")
    }

    /// Index of the particle at lattice coordinates `c` (first coordinate slowest).
    pub(super) fn index<const D: usize>(&self, c: [usize; D]) -> usize {
        c.iter().fold(0, |k, &ca| k * self.size + ca)
    }

    /// Lattice coordinates of particle `k` of an `n`^D block (first coordinate slowest).
    pub(super) fn coords<const D: usize>(n: usize, k: usize) -> [usize; D] {
        let mut c = [0; D];
        let mut rest = k;
        for a in (0..D).rev() {
            c[a] = rest % n;
            rest /= n;
        }
        c
    }

    /// Builds the run at rest with the kick applied; D must be [`SwegleConfig::dim`].
    pub fn build<const D: usize>(&self) -> Result<Run<D>> {
        self.validate()?;
        if D != self.dim {
            return Err(Error::Incompatible(
                Text::from(format!("a {D}D Swegle run from a "))
                    + field("dim")
                    + format!(" {} configuration", self.dim),
            ));
        }
        let (n, l) = (self.size, self.layers);
        let half = (n - 1) as f64 / 2.0;
        let count = self.particles();
        let mut x = Vec::with_capacity(count);
        let mut fixed = Vec::with_capacity(count);
        for k in 0..count {
            let c = Self::coords::<D>(n, k);
            x.push(c.map(|ca| (ca as f64 - half) * self.dx));
            fixed.push(c.iter().any(|&ca| ca < l || ca >= n - l));
        }
        let rho = self.density_ratio * self.rho0;
        let s0 = self.bulk * (1.0 - self.density_ratio);
        let model = Model::<D>::new(
            self.params(),
            x,
            vec![self.dx.powi(D as i32); count],
            rho,
            s0,
            None,
        )?;
        let mut z = model.rest_state(rho);
        z.v[self.index([n / 2; D])][0] = self.kick;
        Run::new(model, z, fixed, self.boundary)
    }
}
