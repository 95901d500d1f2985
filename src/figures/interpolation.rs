//! `interpolation` series of the figure configs: a kernel approximation of a test function
//! on a finite particle set, or the exact function, against position
//! ([`InterpolationSeries`]; the code of `sphstab interpolate`).

use crate::budget::Budget;
use crate::error::{Result, check_range};
use crate::kernel;
use crate::plot::Curve;
use crate::shape::ShapeFamily;
use crate::studies::interpolation::{
    InterpolationConfig, Normalisation, TestFunction, interpolate,
};
use serde::Deserialize;

/// Which quantity a curve shows.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum InterpolationQuantity {
    /// f.
    #[default]
    Value,
    /// ∂f/∂x₁.
    Gradient,
    /// ∇²f (f″ in 1D).
    Second,
}

/// The approximation (or, with `exact`, the function itself) at the particles of the interval,
/// against their first coordinate.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterpolationSeries {
    /// Test function (`quartic`, `sine`, `linear`, `edge`, `step`).
    pub function: String,
    /// Edge width in spacings (`edge`; default 10).
    pub edge_width: Option<f64>,
    /// Interval (default: the function's).
    pub interval: Option<(f64, f64)>,
    /// Particles on the interval (default 101).
    pub particles: Option<usize>,
    /// Kernel (default mollifier).
    pub kernel: Option<String>,
    /// h/Δx (the kernel's own convention).
    pub h: f64,
    /// Shape family (default sph).
    pub shape: Option<String>,
    /// Ghost particles beyond the ends.
    #[serde(default)]
    pub ghosts: bool,
    /// `continuum` (default) or `lattice`.
    pub normalisation: Option<String>,
    /// Quantity (default: value).
    #[serde(default)]
    pub quantity: InterpolationQuantity,
    /// The exact function instead of the approximation.
    #[serde(default)]
    pub exact: bool,
    /// Legend label (default: generated).
    pub label: Option<String>,
    /// Draw dashed.
    #[serde(default)]
    pub dashed: bool,
}

impl InterpolationSeries {
    /// The interpolation this series draws.
    pub fn config(&self, budget: &Budget) -> Result<InterpolationConfig> {
        let f = TestFunction::by_name(&self.function, self.edge_width.unwrap_or(10.0))?;
        let k = kernel::by_name(self.kernel.as_deref().unwrap_or("mollifier"))?;
        let mut c = InterpolationConfig::new(f, k, self.h);
        if let Some((a, b)) = self.interval {
            c.interval = (a, b);
        }
        if let Some(n) = self.particles {
            c.particles = n;
        }
        if let Some(s) = &self.shape {
            c.shape = ShapeFamily::by_name(s)?;
        }
        if let Some(n) = &self.normalisation {
            c.normalisation = Normalisation::by_name(n)?;
        }
        c.ghosts = self.ghosts;
        c.budget = *budget;
        c.validate()?;
        Ok(c)
    }

    /// The curve.
    pub(super) fn curve(&self, budget: &Budget) -> Result<Curve> {
        check_range("h", self.h, 0.0, f64::MAX, false, true)?;
        let c = self.config(budget)?;
        let r = interpolate(&c)?;
        let y = match (self.quantity, self.exact) {
            (InterpolationQuantity::Value, false) => r.f_approx,
            (InterpolationQuantity::Value, true) => r.f,
            (InterpolationQuantity::Gradient, false) => r.gradient_x_approx,
            (InterpolationQuantity::Gradient, true) => r.gradient_x,
            (InterpolationQuantity::Second, false) => r.laplacian_approx,
            (InterpolationQuantity::Second, true) => r.laplacian_exact,
        };
        let label = self.label.clone().unwrap_or_else(|| {
            if self.exact {
                "exact".into()
            } else {
                format!(
                    "{} h = {}Δx{}",
                    r.kernel,
                    r.h_over_dx,
                    if r.ghosts { ", ghosts" } else { "" }
                )
            }
        });
        Ok(Curve {
            label,
            x: r.position,
            y,
            dashed: self.dashed,
        })
    }
}
