//! `galerkin` series of the figure configs: a static meshfree Galerkin solution's error against
//! the node spacing, as [B98] Figs 5, 6, 8–11 draw it ([`GalerkinSeries`]; the code of
//! `sphstab galerkin`).

use crate::error::{Error, Result};
use crate::plot::Curve;
use crate::studies::galerkin::{GalerkinMethod, GalerkinProblem, GalerkinReport, solve};
use rayon::prelude::*;
use serde::Deserialize;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// The solutions computed so far in this process: the panels of a figure draw several norms
/// of one solution (deterministic, so a solution is computed once).
fn solved(
    problem: GalerkinProblem,
    method: GalerkinMethod,
    level: usize,
) -> Result<GalerkinReport> {
    type Key = (&'static str, &'static str, usize);
    static CACHE: OnceLock<Mutex<HashMap<Key, GalerkinReport>>> = OnceLock::new();
    let key = (problem.name(), method.name(), level);
    let cache = CACHE.get_or_init(Default::default);
    if let Some(r) = cache
        .lock()
        .map_err(|_| Error::NonFinite("galerkin cache"))?
        .get(&key)
    {
        return Ok(r.clone());
    }
    let r = solve(problem, method, level)?;
    cache
        .lock()
        .map_err(|_| Error::NonFinite("galerkin cache"))?
        .insert(key, r.clone());
    Ok(r)
}

/// Which error a Galerkin curve shows.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum GalerkinNorm {
    /// The energy error at the quadrature points (eq 118).
    #[default]
    Energy,
    /// The displacement error (nodal l2, eq 114; Gauss L2 for the background methods).
    Displacement,
    /// The energy error by 5 × 5 Gauss quadrature on the node cells ([B98] Figs 10–11).
    IntegratedEnergy,
}

/// log10 of an error of `method` on `problem` against log10 Δx over `levels`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GalerkinSeries {
    /// `beam` or `plate`.
    pub problem: String,
    /// `sph`, `rl`, `cd1`, `mls`, `efg` or `cd1-gauss`.
    pub method: String,
    /// Refinement levels (1 to 8; default: the problem's, those of REPRODUCTION.md).
    #[serde(default)]
    pub levels: Vec<usize>,
    /// The error drawn (default: energy).
    #[serde(default)]
    pub norm: GalerkinNorm,
    /// Legend label (default: the method's name).
    pub label: Option<String>,
    /// Draw dashed.
    #[serde(default)]
    pub dashed: bool,
}

impl GalerkinSeries {
    /// The curve: x = log10 Δx, y = the error (drawn on a log axis).
    pub(super) fn curve(&self) -> Result<Curve> {
        let problem = GalerkinProblem::by_name("galerkin.problem", &self.problem)?;
        let method = GalerkinMethod::by_name("galerkin.method", &self.method)?;
        let levels = if self.levels.is_empty() {
            problem.default_levels().to_vec()
        } else {
            self.levels.clone()
        };
        if levels.len() > 8 {
            return Err(Error::Incompatible(
                "galerkin series: give 1 to 8 `levels`".into(),
            ));
        }
        let reps = levels
            .par_iter()
            .map(|&l| solved(problem, method, l))
            .collect::<Result<Vec<_>>>()?;
        let y = reps
            .iter()
            .map(|r| match self.norm {
                GalerkinNorm::Energy => Ok(r.energy_error),
                GalerkinNorm::Displacement => Ok(r.displacement_error),
                GalerkinNorm::IntegratedEnergy => r.integrated_energy_error.ok_or_else(|| {
                    Error::Incompatible(
                        format!(
                            "galerkin series: {} has no Gauss-integrated error (gradients at the nodes only)",
                            method.name()
                        )
                        .into(),
                    )
                }),
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Curve {
            label: self
                .label
                .clone()
                .unwrap_or_else(|| method.name().to_string()),
            x: reps.iter().map(|r| r.spacing.log10()).collect(),
            y,
            dashed: self.dashed,
        })
    }
}
