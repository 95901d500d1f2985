//! The throughput study's config (the flags of `sphstab throughput`): the block, its material
//! and form, and the timing, checked field by field.

use crate::budget::Budget;
use crate::error::{Error, Result, check_range, field};
use crate::forms::{
    ArtificialStress, ArtificialViscosity, FormKind, Material, ModelParams, ObjectiveRate,
};
use crate::kernel::Kernel;
use crate::params::{ParamNames, check_art_stress_dim, check_common_named};
use crate::shape::{KernelParams, ShapeFamily};
use serde::Serialize;

/// Material of the block (ρ0 = 1 and tangent modulus 1 in both cases).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BlockMaterial {
    /// p = K(ρ/ρ0 − 1), K = 1.
    Hydro,
    /// Hypo-elastic, P-wave modulus 1, Poisson ratio ν (plane strain in 2D).
    Elastic {
        /// ν.
        poisson: f64,
        /// Objective stress rate.
        rate: ObjectiveRate,
    },
}

/// Boundary of the block.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Domain {
    /// Free surfaces all round.
    Open,
    /// Periodic in every direction (period n Δx).
    Periodic,
}

impl Domain {
    /// CLI name.
    pub fn name(self) -> &'static str {
        match self {
            Domain::Open => "open",
            Domain::Periodic => "periodic",
        }
    }
}

/// What to run.
#[derive(Clone, Copy, Debug)]
pub struct ThroughputConfig {
    /// Dimension D (2 or 3): the block holds n^D particles.
    pub dim: usize,
    /// Open block or periodic box.
    pub domain: Domain,
    /// The form.
    pub form: FormKind,
    /// Shape family.
    pub shape: ShapeFamily,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// h/Δx.
    pub h_over_dx: f64,
    /// Material.
    pub material: BlockMaterial,
    /// Monaghan artificial viscosity (α, β), `None`: off.
    pub av: Option<(f64, f64)>,
    /// Monaghan–Gray artificial stress (ε, n), classical and cll forms; `None`: off.
    pub art_stress: Option<(f64, i32)>,
    /// Time step in Δx/c.
    pub dt: f64,
    /// Timed steps per repeat.
    pub steps: usize,
    /// Repeats (the median is reported).
    pub repeats: usize,
    /// Amplitude A of the initial velocity field, in units of c.
    pub amplitude: f64,
    /// Whether stencil builds reuse provably unchanged pairs ([`Run::set_pair_reuse`](crate::solver::Run::set_pair_reuse)).
    pub pair_reuse: bool,
    /// Skin of the pair list, as a fraction of the support radius, in [0, 1]
    /// ([`Run::set_skin`](crate::solver::Run::set_skin)).
    pub skin: f64,
    /// The budget the timing runs must stay within.
    pub budget: Budget,
}

impl ThroughputConfig {
    /// The 2D defaults of `sphstab throughput`: open block, classical / m4, h = 1.3Δx, elastic
    /// (Jaumann, ν = 0.3), AV (1, 1), artificial stress (0.3, 4), Δt = 0.2Δx/c, 50 steps × 3
    /// repeats, A = 10⁻³.
    pub fn new(kernel: &'static dyn Kernel) -> Self {
        Self {
            dim: 2,
            domain: Domain::Open,
            form: FormKind::Classical,
            shape: FormKind::Classical.default_shape_in(2),
            kernel,
            h_over_dx: 1.3,
            material: BlockMaterial::Elastic {
                poisson: 0.3,
                rate: ObjectiveRate::Jaumann,
            },
            av: Some((1.0, 1.0)),
            art_stress: Some((0.3, 4)),
            dt: 0.2,
            steps: 50,
            repeats: 3,
            amplitude: 1e-3,
            pair_reuse: true,
            skin: crate::forms::default_skin(2),
            budget: Budget::default(),
        }
    }

    /// The defaults in dimension `dim`: in 3D a periodic box and no artificial stress (not
    /// available in 3D) and the pair list's skin of the dimension
    /// ([`default_skin`](crate::forms::default_skin)), everything else as in 2D.
    pub fn with_dim(self, dim: usize) -> Self {
        Self {
            dim,
            domain: if dim == 3 {
                Domain::Periodic
            } else {
                Domain::Open
            },
            art_stress: if dim == 3 { None } else { self.art_stress },
            skin: crate::forms::default_skin(dim),
            ..self
        }
    }

    /// Checks every parameter; errors name the field (`av` for both viscosity coefficients).
    pub fn validate(&self) -> Result<()> {
        if !(2..=3).contains(&self.dim) {
            return Err(Error::OutOfRange {
                field: "dim",
                value: self.dim as f64,
                range: "2 or 3".into(),
            });
        }
        if !self.form.in_every_dimension() {
            return Err(Error::Incompatible(
                field("form")
                    + format!(
                        " {} is not available in {}D (classical, nonlocal, local, lnl, cll, total-lagrangian, enog, tl-enog)",
                        self.form.name(),
                        self.dim
                    ),
            ));
        }
        check_art_stress_dim(self.dim, self.art_stress.is_some())?;
        self.form.check_shape(self.shape)?;
        check_range("h_over_dx", self.h_over_dx, 0.0, 10.0, false, true)?;
        // the same checks as every other command (support must reach the neighbours, …)
        check_common_named(
            &ParamNames {
                av_alpha: "av",
                av_beta: "av",
                ..ParamNames::QUERY
            },
            self.kernel,
            self.h_over_dx,
            0.0,
            0.5,
            self.av,
            None,
        )?;
        if let BlockMaterial::Elastic { poisson, .. } = self.material {
            check_range("poisson", poisson, -0.99, 0.5, true, false)?;
        }
        if let Some((a, b)) = self.av {
            check_range("av", a, 0.0, 100.0, true, true)?;
            check_range("av", b, 0.0, 100.0, true, true)?;
        }
        if let Some((eps, n)) = self.art_stress {
            check_range("art_eps", eps, 0.0, 10.0, true, true)?;
            check_range("art_n", n as f64, 1.0, 12.0, true, true)?;
            if !matches!(self.form, FormKind::Classical | FormKind::Cll) {
                return Err(Error::Incompatible(
                    field("art_eps")
                        + format!(
                            ": artificial stress is defined for the classical and cll forms, not {}",
                            self.form.name()
                        ),
                ));
            }
        }
        check_range("dt", self.dt, 0.0, 2.0, false, true)?;
        check_range("steps", self.steps as f64, 1.0, 1e6, true, true)?;
        check_range("repeats", self.repeats as f64, 1.0, 1000.0, true, true)?;
        check_range("amplitude", self.amplitude, 0.0, 0.1, true, true)?;
        check_range("skin", self.skin, 0.0, 1.0, true, true)?;
        Ok(())
    }

    pub(super) fn params(&self) -> Result<ModelParams> {
        let material = match self.material {
            BlockMaterial::Hydro => Material::Hydro { bulk: 1.0 },
            BlockMaterial::Elastic { poisson, rate } => Material::elastic(1.0, poisson, rate)?,
        };
        Ok(ModelParams {
            form: self.form,
            shape: self.shape,
            kp: KernelParams {
                kernel: self.kernel,
                h: self.h_over_dx,
            },
            material,
            rho0: 1.0,
            c_partition: 0.5,
            av: self.av.map(|(alpha, beta)| ArtificialViscosity {
                alpha,
                beta,
                sound_speed: 1.0,
                approaching_only: true,
            }),
            art_stress: self.art_stress.map(|(eps, n)| ArtificialStress {
                eps,
                n,
                spacing: 1.0,
            }),
            diffusion: None,
            alpha_s: 0.0,
            ls_length: 1.0,
            hourglass: None,
        })
    }
}

/// Smallest and largest block side in 2D.
pub const SIZE_RANGE: (usize, usize) = (4, 3000);

/// Largest block side in 3D (8 × 10⁶ particles).
pub const MAX_SIZE_3D: usize = 200;

/// Checks a block side in dimension `dim` for `domain` (the error names `field`): in
/// [4, 3000] (2D) or [4, 200] (3D), and a periodic box more than two support radii `support`
/// wide, so that every neighbour has one image within the support.
pub fn check_size(
    field: &'static str,
    size: usize,
    dim: usize,
    domain: Domain,
    support: f64,
) -> Result<()> {
    let lo = if domain == Domain::Periodic {
        SIZE_RANGE.0.max((2.0 * support).floor() as usize + 1)
    } else {
        SIZE_RANGE.0
    };
    let hi = if dim == 3 { MAX_SIZE_3D } else { SIZE_RANGE.1 };
    if size < lo || size > hi {
        return Err(Error::OutOfRange {
            field,
            value: size as f64,
            range: format!(
                "particles per side must be an integer in [{lo}, {hi}] ({}D, {} domain)",
                dim,
                domain.name()
            )
            .into(),
        });
    }
    Ok(())
}
