//! `finite_body` series of the figure configs: the largest eigenvalue of a finite Galerkin body
//! against the support D_max, or a \[B00\] §5 bound ([`FiniteBodySeries`]; the code of
//! `sphstab stiffness --body`).

use crate::budget::Budget;
use crate::error::{Error, Result};
use crate::kernel;
use crate::plot::Curve;
use crate::shape::ShapeFamily;
use crate::studies::finite_body::finite_body;
use crate::vonneumann::timestep_bounds::{ALPHA_1D, ALPHA1_2D, ALPHA2_2D};
use rayon::prelude::*;
use serde::Deserialize;

/// What a finite-body curve shows.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum FiniteBodyRoute {
    /// λ_max with the row-sum mass.
    #[default]
    Lumped,
    /// λ_max with the consistent mass (dense bodies only).
    Consistent,
    /// \[B00\] eq 137 (1D), α c²/h² with α = 12.42.
    Eq137,
    /// \[B00\] eq 146 (2D), α₁ = 13.30.
    Eq146,
    /// \[B00\] eq 148 (2D), α₂ = 15.00.
    Eq148,
}

/// λ_max (c²/Δx²) of a bar (`dim` 1) or square (`dim` 2) of `nodes` nodes per side at each
/// support D_max of `supports`, or a bound there.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FiniteBodySeries {
    /// 1 or 2.
    pub dim: usize,
    /// Nodes per side.
    pub nodes: usize,
    /// Weight (default efg-cubic).
    pub kernel: Option<String>,
    /// Shape family (default mls).
    pub shape: Option<String>,
    /// The supports D_max (units of Δx), increasing.
    pub supports: Vec<f64>,
    /// What to draw (default: the lumped λ_max).
    #[serde(default)]
    pub route: FiniteBodyRoute,
    /// Legend label (default: generated).
    pub label: Option<String>,
    /// Draw dashed.
    #[serde(default)]
    pub dashed: bool,
}

impl FiniteBodySeries {
    /// The curve.
    pub(super) fn curve(&self, budget: &Budget) -> Result<Curve> {
        if self.supports.is_empty() || self.supports.len() > 200 {
            return Err(Error::Incompatible(
                "finite_body series: give 1 to 200 `supports`".into(),
            ));
        }
        let k = kernel::by_name(self.kernel.as_deref().unwrap_or("efg-cubic"))?;
        let fam = ShapeFamily::by_name(self.shape.as_deref().unwrap_or("mls"))?;
        let y: Vec<f64> = match self.route {
            FiniteBodyRoute::Lumped | FiniteBodyRoute::Consistent => self
                .supports
                .par_iter()
                .map(|&d| {
                    let r = finite_body(self.dim, self.nodes, k, d, fam, budget)?;
                    match self.route {
                        FiniteBodyRoute::Lumped => Ok(r.lambda_max_lumped),
                        _ => r.lambda_max_consistent.ok_or_else(|| {
                            Error::Incompatible(
                                "finite_body series: the consistent mass needs a body of at most 1600 nodes"
                                    .into(),
                            )
                        }),
                    }
                })
                .collect::<Result<_>>()?,
            FiniteBodyRoute::Eq137 | FiniteBodyRoute::Eq146 | FiniteBodyRoute::Eq148 => {
                let alpha = match self.route {
                    FiniteBodyRoute::Eq137 => ALPHA_1D,
                    FiniteBodyRoute::Eq146 => ALPHA1_2D,
                    _ => ALPHA2_2D,
                };
                for &d in &self.supports {
                    crate::error::check_range("supports", d, 1.0, 50.0, false, true)?;
                }
                self.supports.iter().map(|d| alpha / (d * d)).collect()
            }
        };
        if y.iter().any(|v| !v.is_finite()) {
            return Err(Error::NonFinite("finite_body series"));
        }
        let label = self.label.clone().unwrap_or_else(|| match self.route {
            FiniteBodyRoute::Lumped => format!("{} nodes, lumped mass", self.nodes),
            FiniteBodyRoute::Consistent => format!("{} nodes, consistent mass", self.nodes),
            FiniteBodyRoute::Eq137 => "eq 137".into(),
            FiniteBodyRoute::Eq146 => "eq 146".into(),
            FiniteBodyRoute::Eq148 => "eq 148".into(),
        });
        Ok(Curve {
            label,
            x: self.supports.clone(),
            y,
            dashed: self.dashed,
        })
    }
}
