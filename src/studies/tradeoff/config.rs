//! The trade-off study's config (`analysis/tradeoff*.json` or the flags of `sphstab tradeoff`): the
//! grid of forms × kernels × h/Δx and the integrators it covers, checked field by field.

use super::integrators;
use crate::budget::Budget;
use crate::error::{Error, Result, field};
use crate::forms::FormKind;
use crate::integrator::{DEFAULT_EULER_EVERY, Integrator};
use crate::kernel::{self, Kernel};
use serde::{Deserialize, Serialize};

/// What to sweep.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TradeoffConfig {
    /// 1 or 2.
    #[serde(default = "one")]
    pub dim: u8,
    /// Form names (empty: every form of the dimension).
    #[serde(default)]
    pub forms: Vec<String>,
    /// Kernel names (empty: all eleven).
    #[serde(default)]
    pub kernels: Vec<String>,
    /// h/Δx values per kernel, evenly over its customary range.
    #[serde(default = "three")]
    pub h_points: usize,
    /// Timed repeats of the wave scene (median reported).
    #[serde(default = "three")]
    pub repeats: usize,
    /// Figure file name in figures/ (used by the analysis config).
    #[serde(default)]
    pub output: Option<String>,
    /// What the figure shows (analysis config).
    #[serde(default)]
    pub note: String,
    /// Integrators of the integrator dimension (`all`: every one; empty: none, the report has
    /// no `integrator_rows`). 1D only.
    #[serde(default)]
    pub integrators: Vec<String>,
    /// Δt used = `safety` × critical Δt for the integrator rows, in (0, 1].
    #[serde(default = "default_safety")]
    pub safety: f64,
    /// The budget the study's linearisations must stay within (not read from the file).
    #[serde(skip)]
    pub budget: Budget,
}

fn default_safety() -> f64 {
    integrators::DEFAULT_SAFETY
}

fn one() -> u8 {
    1
}
fn three() -> usize {
    3
}

impl Default for TradeoffConfig {
    fn default() -> Self {
        Self {
            dim: 1,
            forms: Vec::new(),
            kernels: Vec::new(),
            h_points: 3,
            repeats: 3,
            output: None,
            note: String::new(),
            integrators: Vec::new(),
            safety: integrators::DEFAULT_SAFETY,
            budget: Budget::default(),
        }
    }
}

/// The configurations of a study, validated (unknown names are errors).
pub fn grid(cfg: &TradeoffConfig) -> Result<Vec<(FormKind, &'static dyn Kernel, f64)>> {
    if cfg.dim != 1 && cfg.dim != 2 {
        return Err(Error::OutOfRange {
            field: "dim",
            value: cfg.dim as f64,
            range: "must be 1 or 2".into(),
        });
    }
    if cfg.h_points == 0 || cfg.h_points > 64 {
        return Err(Error::OutOfRange {
            field: "h_points",
            value: cfg.h_points as f64,
            range: "must be an integer in [1, 64]".into(),
        });
    }
    crate::studies::config::check_output("tradeoff config", cfg.output.as_deref())?;
    if cfg.repeats == 0 || cfg.repeats > 100 {
        return Err(Error::OutOfRange {
            field: "repeats",
            value: cfg.repeats as f64,
            range: "must be an integer in [1, 100]".into(),
        });
    }
    integrator_list(cfg)?;
    crate::error::check_range("safety", cfg.safety, 0.0, 1.0, false, true)?;
    let forms: Vec<FormKind> = if cfg.forms.is_empty() {
        FormKind::ALL
            .iter()
            .map(|f| f.0)
            // the forms of the papers (the solid stabilisations of issue 30 are opt-in)
            .filter(|f| !f.needs_2d() && (cfg.dim == 1 || f.in_every_dimension()))
            .collect()
    } else {
        let mut v = Vec::new();
        for name in &cfg.forms {
            let f = FormKind::by_name(name)?;
            if cfg.dim == 2 && !f.in_every_dimension() {
                return Err(Error::Incompatible(
                    field("forms")
                        + format!(": {name} is not available with ")
                        + field("dim")
                        + " 2 (classical, nonlocal, local, lnl, cll, total-lagrangian, enog, tl-enog)",
                ));
            }
            v.push(f);
        }
        v
    };
    let kernels: Vec<&'static dyn Kernel> = if cfg.kernels.is_empty() {
        kernel::all().to_vec()
    } else {
        cfg.kernels
            .iter()
            .map(|k| kernel::by_name(k))
            .collect::<Result<_>>()?
    };
    let mut out = Vec::new();
    for &f in &forms {
        for &k in &kernels {
            let (lo, hi) = k.customary_h();
            for i in 0..cfg.h_points {
                let h = if cfg.h_points == 1 {
                    0.5 * (lo + hi)
                } else {
                    lo + (hi - lo) * i as f64 / (cfg.h_points - 1) as f64
                };
                out.push((f, k, h));
            }
        }
    }
    Ok(out)
}

/// The integrators of the integrator dimension (validated; `all` expands to every one).
pub fn integrator_list(cfg: &TradeoffConfig) -> Result<Vec<Integrator>> {
    let mut out = Vec::new();
    for name in &cfg.integrators {
        if name == "all" {
            out.extend(Integrator::all(DEFAULT_EULER_EVERY));
        } else {
            out.push(Integrator::from_name(name, DEFAULT_EULER_EVERY)?);
        }
    }
    if out.is_empty() && cfg.safety != integrators::DEFAULT_SAFETY {
        return Err(Error::Incompatible(
            field("safety")
                + " sets the Δt of the integrator rows: it applies with "
                + field("integrators"),
        ));
    }
    if !out.is_empty() && cfg.dim != 1 {
        return Err(Error::Incompatible(
            field("integrators")
                + ": the integrator dimension is 1D only (use "
                + field("dim")
                + " 1)",
        ));
    }
    Ok(out)
}

/// Parses a study config; errors name the file and the field ([`crate::studies::config`]).
pub fn parse_config(file: &str, text: &str) -> Result<TradeoffConfig> {
    crate::studies::config::parse_json(file, text)
}
