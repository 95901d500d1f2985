//! The Swegle test by name: [`SwegleSpec`] holds its parameters as the user gives them (names,
//! optional values, the published defaults), and [`SwegleSpec::config`] turns them into a
//! validated [`SwegleConfig`]. The CLI's `swegle` fills it from its flags, the Python module
//! from keyword arguments; errors name the fields, which each front end prints as its own names.

use super::config::{SwegleConfig, default_size};
use crate::analysis::spec::{art_stress, diffusion, not_applicable};
use crate::budget::Budget;
use crate::error::{Error, Result, field};
use crate::forms::FormKind;
use crate::integrator::Integrator;
use crate::shape::ShapeFamily;
use crate::solver::BoundaryDensity;
use serde::Deserialize;

/// The parameters of a Swegle run, by name; `None` takes the default.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SwegleSpec {
    /// Dimension 2 (default) or 3.
    pub dim: Option<usize>,
    /// SPH form (default `classical`).
    pub form: Option<String>,
    /// Kernel (default `m4`).
    pub kernel: Option<String>,
    /// h/Δx in the kernel's convention (default 1.2).
    pub h: Option<f64>,
    /// Shape family (default: the form's).
    pub shape: Option<String>,
    /// f = ρ/ρ0 in [0.5, 1.5] (default 0.99): < 1 tension (σ̄ = 1 − f).
    pub density_ratio: Option<f64>,
    /// Particles per side (default 21 in 2D, 12 in 3D).
    pub size: Option<usize>,
    /// End time in the test's units (default 40).
    pub t_end: Option<f64>,
    /// Run past `t_end` until a mode growing at the box prediction reaches the fit window.
    pub until_window: Option<bool>,
    /// Initial v_x of the centre particle in the test's units (default 1e-10).
    pub kick: Option<f64>,
    /// Boundary layers' density: `evolve` (default) or `frozen`.
    pub boundary_density: Option<String>,
    /// Time step Δt in Δx/c (default 0.2).
    pub dt: Option<f64>,
    /// Partition coefficient c of lnl/cll (default 0.5).
    pub c: Option<f64>,
    /// Monaghan–Gray artificial stress ε (classical, cll; 2D).
    pub art_eps: Option<f64>,
    /// Artificial-stress exponent n (default 4; needs `art_eps`).
    pub art_n: Option<i32>,
    /// Time integrator (default `kdk`).
    pub integrator: Option<String>,
    /// N_s of `verlet-euler` (default 40).
    pub euler_every: Option<usize>,
    /// δ-SPH density diffusion δ.
    pub delta: Option<f64>,
    /// δ-SPH term: antuono (default) or molteni-colagrossi (needs `delta`).
    pub delta_form: Option<String>,
}

impl SwegleSpec {
    /// Builds and validates the run within `budget` ([`SwegleConfig::validate`]).
    pub fn config(&self, budget: &Budget) -> Result<SwegleConfig> {
        let dim = self.dim.unwrap_or(2);
        if !(2..=3).contains(&dim) {
            return Err(Error::OutOfRange {
                field: "dim",
                value: dim as f64,
                range: "2 or 3 (the 1D scenes are `simulate`)".into(),
            });
        }
        let form = FormKind::by_name(self.form.as_deref().unwrap_or("classical"))?;
        let kernel = crate::kernel::by_name(self.kernel.as_deref().unwrap_or("m4"))?;
        let mut cfg = SwegleConfig::new(
            form,
            kernel,
            self.h.unwrap_or(1.2),
            self.density_ratio.unwrap_or(0.99),
        )
        .with_dim(dim);
        cfg.budget = *budget;
        if let Some(s) = &self.shape {
            cfg.shape = ShapeFamily::by_name(s)?;
        }
        cfg.size = self.size.unwrap_or(default_size(dim));
        cfg.t_end = self.t_end.unwrap_or(cfg.t_end);
        cfg.dt = self.dt.unwrap_or(cfg.dt);
        if self.c.is_some() && !matches!(form, FormKind::Lnl | FormKind::Cll) {
            return Err(not_applicable(
                field("c_partition"),
                field("form")
                    + format!(
                        " {} (the partition coefficient is of lnl and cll)",
                        form.name()
                    ),
            ));
        }
        cfg.c_partition = self.c.unwrap_or(0.5);
        cfg.until_window = self.until_window.unwrap_or(false);
        cfg.kick = self.kick.unwrap_or(cfg.kick);
        cfg.integrator = Integrator::by_names(self.integrator.as_deref(), self.euler_every)?;
        cfg.diffusion = diffusion(self.delta, self.delta_form.as_deref())?;
        if let Some((eps, n)) = art_stress(self.art_eps, self.art_n)? {
            if !matches!(form, FormKind::Classical | FormKind::Cll) {
                return Err(not_applicable(
                    field("art_eps"),
                    field("form")
                        + format!(
                            " {} (artificial stress is defined for classical and cll)",
                            form.name()
                        ),
                ));
            }
            if dim == 3 {
                return Err(not_applicable(field("art_eps"), field("dim") + " 3"));
            }
            cfg.art_stress = Some((eps, n));
        }
        cfg.boundary = match self.boundary_density.as_deref().unwrap_or("evolve") {
            "evolve" => BoundaryDensity::Evolve,
            "frozen" => BoundaryDensity::Frozen,
            s => {
                return Err(Error::UnknownName {
                    what: field("boundary_density"),
                    given: s.into(),
                    valid: "evolve, frozen".into(),
                });
            }
        };
        cfg.validate()?;
        Ok(cfg)
    }
}
