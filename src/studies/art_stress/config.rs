//! The artificial-stress study's config (`analysis/art_stress.json` or the flags of
//! `sphstab art-stress`), checked field by field.

use crate::budget::Budget;
use crate::error::{Error, Result, check_range, field};
use crate::forms::FormKind;
use crate::solver::BoundaryDensity;
use crate::studies::swegle::SwegleConfig;
use serde::{Deserialize, Serialize};

/// A study config (`analysis/art_stress.json`); unknown fields are rejected by name.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ArtStressConfig {
    /// Form: `classical` or `cll` (the forms with artificial stress).
    #[serde(default = "default_form")]
    pub form: String,
    /// Kernel name.
    #[serde(default = "default_kernel")]
    pub kernel: String,
    /// h/Δx values (one panel row each).
    pub h: Vec<f64>,
    /// Density ratios f = ρ/ρ0 (f < 1: tension σ̄ = 1 − f; one panel column each).
    pub density_ratio: Vec<f64>,
    /// ε grid of the predictions.
    pub eps: Vec<f64>,
    /// ε of the Swegle runs (may be empty).
    #[serde(default)]
    pub runs: Vec<f64>,
    /// Exponent n of f = W(r)/W(Δx).
    #[serde(default = "default_n")]
    pub art_n: i32,
    /// Boundary density of the Swegle box (prediction and runs).
    #[serde(default = "default_boundary")]
    pub boundary_density: BoundaryDensity,
    /// Particles per side of the Swegle box.
    #[serde(default = "default_size")]
    pub size: usize,
    /// Stored measurements of another code to draw next to sphstab's (path relative to the
    /// working directory; read by the command line, see [`Comparison`](super::Comparison)).
    #[serde(default)]
    pub compare: Option<String>,
    /// Figure written to figures/ (with its data next to it as .json).
    #[serde(default)]
    pub output: Option<String>,
    /// What the figure shows (kept with the config and the data).
    #[serde(default)]
    pub note: String,
    /// The budget the predictions and runs must stay within (not read from the file).
    #[serde(skip)]
    pub budget: Budget,
}

fn default_form() -> String {
    "classical".into()
}
fn default_kernel() -> String {
    "m4".into()
}
fn default_n() -> i32 {
    4
}
fn default_boundary() -> BoundaryDensity {
    BoundaryDensity::Frozen
}
fn default_size() -> usize {
    21
}

impl ArtStressConfig {
    /// The bare command's study: m4, h = 1.2, f = 0.99, ε = 0, 0.05, …, 0.6, no runs.
    pub fn quick() -> Self {
        Self {
            form: default_form(),
            kernel: default_kernel(),
            h: vec![1.2],
            density_ratio: vec![0.99],
            eps: (0..=12).map(|i| i as f64 / 20.0).collect(),
            runs: Vec::new(),
            art_n: 4,
            boundary_density: BoundaryDensity::Frozen,
            size: 21,
            compare: None,
            output: None,
            note: String::new(),
            budget: Budget::default(),
        }
    }

    /// Checks every field; errors name the field.
    pub fn validate(&self) -> Result<()> {
        let form = FormKind::by_name(&self.form)?;
        if !matches!(form, FormKind::Classical | FormKind::Cll) {
            return Err(Error::Incompatible(
                field("form")
                    + format!(
                        " {} has no artificial stress (allowed: classical, cll)",
                        self.form
                    ),
            ));
        }
        crate::kernel::by_name(&self.kernel)?;
        let count = crate::studies::config::check_len;
        count("h", self.h.len(), 1, 4)?;
        count("density_ratio", self.density_ratio.len(), 1, 4)?;
        count("eps", self.eps.len(), 1, 200)?;
        count("runs", self.runs.len(), 0, 40)?;
        for &h in &self.h {
            check_range("h", h, 0.8, 6.0, true, true)?;
        }
        for &f in &self.density_ratio {
            check_range("density_ratio", f, 0.5, 1.5, true, true)?;
        }
        for &e in &self.eps {
            check_range("eps", e, 0.0, 10.0, true, true)?;
        }
        for &e in &self.runs {
            check_range("runs", e, 0.0, 10.0, true, true)?;
        }
        check_range("art_n", self.art_n as f64, 1.0, 12.0, true, true)?;
        check_range("size", self.size as f64, 9.0, 81.0, true, true)?;
        if let Some(o) = &self.output {
            crate::studies::config::check_output("art-stress config", Some(o))?;
        }
        Ok(())
    }

    /// The Swegle configuration of one point (ε = 0: no artificial stress).
    pub fn swegle(&self, h: f64, f: f64, eps: f64) -> Result<SwegleConfig> {
        let form = FormKind::by_name(&self.form)?;
        let mut c = SwegleConfig::new(form, crate::kernel::by_name(&self.kernel)?, h, f);
        c.budget = self.budget;
        c.size = self.size;
        c.boundary = self.boundary_density;
        c.art_stress = (eps > 0.0).then_some((eps, self.art_n));
        c.until_window = true;
        Ok(c)
    }
}

/// Parses a config (errors name the file and the field) and validates it.
pub fn parse_config(file: &str, text: &str) -> Result<ArtStressConfig> {
    let c: ArtStressConfig = crate::studies::config::parse_json(file, text)?;
    c.validate().map_err(|e| Error::Config {
        file: file.into(),
        msg: e.to_string(),
    })?;
    Ok(c)
}
