//! The pairing study's config (`analysis/pairing3d.json` or the flags of `sphstab pairing`),
//! checked field by field, and the plan of rows it gives.

use crate::analysis::max_grid;
use crate::budget::Budget;
use crate::error::{Error, Result, Text, field, fields};
use crate::kernel::{self, Kernel};
use crate::lattice::Lattice;
use crate::params::check_count;
use crate::studies::config::no_duplicates;
use serde::{Deserialize, Serialize};

/// Names of the lattices of the study.
pub const LATTICES: [&str; 3] = ["sc", "bcc", "fcc"];
/// Largest number of h/Δx values.
pub const MAX_H_VALUES: usize = 1000;
/// Largest number of stresses.
pub const MAX_STRESSES: usize = 16;
/// h/Δx range accepted by `h_min`/`h_max`.
pub const H_LIMITS: (f64, f64) = (0.1, 10.0);
/// σ̄ range accepted by `stresses` (hydro: σ̄ = 1 − ρ/ρ0 < 1).
pub const STRESS_LIMITS: (f64, f64) = (-10.0, 1.0);
/// What to compute (CLI flags or an `analysis/` JSON config).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PairingConfig {
    /// Kernel names (empty: all eleven).
    #[serde(default)]
    pub kernels: Vec<String>,
    /// Lattice names (sc, bcc, fcc; empty: all three).
    #[serde(default)]
    pub lattices: Vec<String>,
    /// Smallest h/Δx.
    #[serde(default = "default_h_min")]
    pub h_min: f64,
    /// Largest h/Δx.
    #[serde(default = "default_h_max")]
    pub h_max: f64,
    /// Step of h/Δx.
    #[serde(default = "default_h_step")]
    pub h_step: f64,
    /// Pre-stresses σ̄ (negative: pressure).
    #[serde(default = "default_stresses")]
    pub stresses: Vec<f64>,
    /// Wave vectors per reciprocal direction (grid³ − 1 sampled).
    #[serde(default = "default_grid")]
    pub grid: usize,
    /// Figure file written into figures/ (with the data next to it, same name, .json).
    #[serde(default)]
    pub output: Option<String>,
    /// What the figure shows (kept with the config).
    #[serde(default)]
    pub note: String,
    /// The budget the study must stay within (not read from the file).
    #[serde(skip)]
    pub budget: Budget,
}

fn default_h_min() -> f64 {
    0.8
}
fn default_h_max() -> f64 {
    3.0
}
fn default_h_step() -> f64 {
    0.1
}
fn default_stresses() -> Vec<f64> {
    vec![-0.01, -0.1]
}
fn default_grid() -> usize {
    crate::analysis::default_grid(3)
}

impl Default for PairingConfig {
    fn default() -> Self {
        Self {
            kernels: Vec::new(),
            lattices: Vec::new(),
            h_min: default_h_min(),
            h_max: default_h_max(),
            h_step: default_h_step(),
            stresses: default_stresses(),
            grid: default_grid(),
            output: None,
            note: String::new(),
            budget: Budget::default(),
        }
    }
}

/// The analysis config of the full study (every kernel × sc, bcc, fcc × h/Δx = 0.8…3 step 0.1
/// × σ̄ = −0.01, −0.1 at 16³ wave vectors: 1,518 rows, ~47 min), which writes
/// `figures/pairing3d.{svg,json}`.
pub const FULL_STUDY_CONFIG: &str = "analysis/pairing3d.json";

/// What [`PairingConfig::quick`] computes, in words (printed by bare `sphstab pairing`).
pub const QUICK_DESCRIPTION: &str = "default quick subset: m4 (W* < 0) and wendland-c2 (W* ≥ 0) on sc, h/Δx = 0.8…2 step 0.2, σ̄ = −0.01, −0.1, 16³ wave vectors (its rows are rows of the full study)";

impl PairingConfig {
    /// The command line's default (bare `sphstab pairing`): a subset that runs in seconds — one
    /// kernel whose W* turns negative (m4) and one whose W* does not (wendland-c2), on the
    /// simple-cubic lattice, h/Δx = 0.8…2 in steps of 0.2, both stresses, the full study's 16³
    /// wave vectors (so its 28 rows are rows of [`FULL_STUDY_CONFIG`]'s study). Flags not given
    /// keep these values.
    pub fn quick() -> Self {
        Self {
            kernels: vec!["m4".into(), "wendland-c2".into()],
            lattices: vec!["sc".into()],
            h_min: 0.8,
            h_max: 2.0,
            h_step: 0.2,
            ..Self::default()
        }
    }
}

/// Parses a study config; `file` names it in errors (unknown fields are rejected by name, as is
/// an `output` that is not a plain .svg file name: [`crate::studies::config`]).
pub fn parse_config(file: &str, text: &str) -> Result<PairingConfig> {
    let cfg: PairingConfig = crate::studies::config::parse_json(file, text)?;
    crate::studies::config::check_output(file, cfg.output.as_deref())?;
    Ok(cfg)
}

/// The validated grid of a study.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Kernels.
    pub kernels: Vec<&'static dyn Kernel>,
    /// Lattices with their names.
    pub lattices: Vec<(&'static str, Lattice<3>)>,
    /// h/Δx values (rounded to 1e-10, so 0.8 + 3·0.1 is 1.1).
    pub h: Vec<f64>,
    /// σ̄ values.
    pub stresses: Vec<f64>,
    /// Wave vectors per direction.
    pub grid: usize,
}

impl Plan {
    /// Rows of the study (kernel × lattice × h × σ̄).
    pub fn rows(&self) -> usize {
        self.kernels.len() * self.lattices.len() * self.h.len() * self.stresses.len()
    }
}

/// Validates a config (errors name the field) and checks the work against its budget: the
/// rows × (grid³ − 1) wave-vector evaluations count against 10 × `max_steps`, as in the atlas.
pub fn plan(cfg: &PairingConfig) -> Result<Plan> {
    let kernels: Vec<&'static dyn Kernel> = if cfg.kernels.is_empty() {
        kernel::all().to_vec()
    } else {
        cfg.kernels
            .iter()
            .map(|k| kernel::by_name(k))
            .collect::<Result<_>>()?
    };
    no_duplicates(
        "kernels",
        &kernels.iter().map(|k| k.name()).collect::<Vec<_>>(),
    )?;
    let lattice_names: Vec<&str> = if cfg.lattices.is_empty() {
        LATTICES.to_vec()
    } else {
        cfg.lattices.iter().map(String::as_str).collect()
    };
    no_duplicates("lattices", &lattice_names)?;
    let lattices =
        lattice_names
            .iter()
            .map(|&n| {
                let name = LATTICES.iter().copied().find(|&l| l == n).ok_or_else(|| {
                    Error::UnknownName {
                        what: Text::from("lattice (") + field("lattices") + ")",
                        given: n.to_string(),
                        valid: LATTICES.join(", ").into(),
                    }
                })?;
                Ok((name, Lattice::<3>::by_name(name)?))
            })
            .collect::<Result<Vec<_>>>()?;
    let (lo, hi) = H_LIMITS;
    crate::error::check_range("h_min", cfg.h_min, lo, hi, true, true)?;
    crate::error::check_range("h_max", cfg.h_max, lo, hi, true, true)?;
    if cfg.h_max < cfg.h_min {
        return Err(Error::OutOfRange {
            field: "h_max",
            value: cfg.h_max,
            range: Text::from("must be ≥ ") + field("h_min") + format!(" = {}", cfg.h_min),
        });
    }
    crate::error::check_range("h_step", cfg.h_step, 1e-3, hi, true, true)?;
    let steps = ((cfg.h_max - cfg.h_min) / cfg.h_step + 1e-9).floor() as usize;
    if steps + 1 > MAX_H_VALUES {
        return Err(Error::OutOfRange {
            field: "h_step",
            value: cfg.h_step,
            range: Text::from(format!(
                "gives {} h values; at most {MAX_H_VALUES} (raise ",
                steps + 1
            )) + field("h_step")
                + " or narrow "
                + fields(&["h_min", "h_max"])
                + ")",
        });
    }
    let h = (0..=steps)
        .map(|i| ((cfg.h_min + i as f64 * cfg.h_step) * 1e10).round() / 1e10)
        .collect();
    if cfg.stresses.is_empty() || cfg.stresses.len() > MAX_STRESSES {
        return Err(Error::OutOfRange {
            field: "stresses",
            value: cfg.stresses.len() as f64,
            range: format!("give 1 to {MAX_STRESSES} values").into(),
        });
    }
    for &s in &cfg.stresses {
        crate::error::check_range("stresses", s, STRESS_LIMITS.0, STRESS_LIMITS.1, true, false)?;
    }
    check_count("grid", cfg.grid, 2, max_grid(3))?;
    let plan = Plan {
        kernels,
        lattices,
        h,
        stresses: cfg.stresses.clone(),
        grid: cfg.grid,
    };
    let budget = &cfg.budget;
    budget.work(
        fields(&["grid", "kernels", "lattices", "h_step", "stresses"]),
        "the pairing study",
        plan.rows() as f64 * (cfg.grid.pow(3) - 1) as f64,
        "wave-vector evaluations",
        10.0 * budget.max_steps,
    )?;
    Ok(plan)
}
