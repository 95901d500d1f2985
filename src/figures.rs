//! Figures regenerated from JSON configs (`analysis/configs/*.json`): each config lists
//! series — a form at a kernel, smoothing length, shape and stress, computed either by the
//! numeric engine or by one of \[B00\]'s closed forms — and is rendered to one SVG.
//!
//! ```json
//! { "output": "b00_fig3_eq74.svg", "title": "...", "note": "...",
//!   "points": 256, "y_range": [-1.5, 1.5],
//!   "series": [ { "form": "eulerian-nodal", "kernel": "efg-quartic", "support": 1.5,
//!                 "shape": "mls", "stress": 0.5, "route": "b00-eq74", "label": "σ̄ = 0.5" } ] }
//! ```

use crate::analysis::{Query1D, dispersion};
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::kernel;
use crate::plot::{Curve, KAPPA_DESC, LinePlot, OMEGA2_DESC};
use crate::shape::{KernelParams, ShapeFamily, lattice_shape};
use crate::vonneumann::closed_form as cf;
use serde::Deserialize;
use std::f64::consts::PI;

/// How a series is computed.
#[derive(Clone, Copy, Debug, Default, Deserialize, serde::Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Route {
    /// The numeric von Neumann engine (the form's rate function, linearised).
    #[default]
    Engine,
    /// \[B00\] eq 32, the continuum.
    B00Eq32,
    /// \[B00\] eq 74.
    B00Eq74,
    /// \[B00\] eq 82.
    B00Eq82,
    /// \[B00\] eq 93 at F = 1.
    B00Eq93,
    /// \[B00\] eq 103.
    B00Eq103,
    /// \[B00\] eq 108.
    B00Eq108,
}

/// One curve of a figure.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Series {
    /// Form name (used by the engine route; closed forms ignore it).
    pub form: String,
    /// Kernel name.
    pub kernel: String,
    /// h/Δx (or give `support`).
    pub h: Option<f64>,
    /// R/Δx.
    pub support: Option<f64>,
    /// Shape family (default: the form's).
    pub shape: Option<String>,
    /// σ̄.
    pub stress: f64,
    /// Partition coefficient c.
    pub c: Option<f64>,
    /// Least-squares α_s.
    pub alpha_s: Option<f64>,
    /// Route (default: engine).
    #[serde(default)]
    pub route: Route,
    /// Legend label (default: generated).
    pub label: Option<String>,
    /// Draw dashed.
    #[serde(default)]
    pub dashed: bool,
}

/// One figure.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FigureConfig {
    /// Output file name (inside the output directory).
    pub output: String,
    /// Plot title.
    pub title: String,
    /// What the figure shows and which paper figure it reproduces (kept with the config).
    #[serde(default)]
    pub note: String,
    /// κ points in (0, π].
    #[serde(default = "default_points")]
    pub points: usize,
    /// Fixed vertical range (default: from the data, every curve whole unless it diverges);
    /// a curve leaving it is marked as clipped.
    pub y_range: Option<(f64, f64)>,
    /// Curves.
    pub series: Vec<Series>,
}

fn default_points() -> usize {
    256
}

impl Series {
    fn query(&self, points: usize) -> Result<Query1D> {
        let form = FormKind::by_name(&self.form)?;
        let k = kernel::by_name(&self.kernel)?;
        let h = match (self.h, self.support) {
            (Some(h), None) => h,
            (None, Some(r)) => r / k.zeta(),
            _ => {
                return Err(Error::Incompatible(
                    "series: give exactly one of `h`, `support`".into(),
                ));
            }
        };
        let mut q = Query1D::new(form, k, h, self.stress);
        if let Some(s) = &self.shape {
            q.shape = ShapeFamily::by_name(s)?;
        }
        if let Some(c) = self.c {
            q.c_partition = c;
        }
        if let Some(a) = self.alpha_s {
            q.alpha_s = a;
        }
        q.points = points;
        q.validate()?;
        Ok(q)
    }

    fn curve(&self, points: usize) -> Result<Curve> {
        let q = self.query(points)?;
        let kappas = q.kappas();
        let kp = KernelParams {
            kernel: q.kernel,
            h: q.h_over_dx,
        };
        let r = q.support_over_dx();
        let phi = |x: f64| lattice_shape(q.shape, kp, x).unwrap_or([f64::NAN; 3]);
        let s = q.stress;
        let y: Vec<f64> = match self.route {
            Route::Engine => dispersion(&q)?.omega2,
            Route::B00Eq32 => kappas
                .iter()
                .map(|&k| cf::b00_eq32_continuum(s, k))
                .collect(),
            Route::B00Eq74 => kappas
                .iter()
                .map(|&k| cf::b00_eq74_eulerian_nodal(&phi, r, s, k))
                .collect(),
            Route::B00Eq82 => kappas
                .iter()
                .map(|&k| cf::b00_eq82_lagrangian_nodal(&phi, r, s, k))
                .collect(),
            Route::B00Eq93 => kappas
                .iter()
                .map(|&k| cf::b00_eq93_eulerian_stress_points(&phi, r, s, 1.0, k))
                .collect(),
            Route::B00Eq103 => kappas
                .iter()
                .map(|&k| cf::b00_eq103_lagrangian_stress_points(&phi, r, s, k))
                .collect(),
            Route::B00Eq108 => kappas
                .iter()
                .map(|&k| cf::b00_eq108_least_squares(&phi, r, q.alpha_s, k))
                .collect(),
        };
        if y.iter().any(|v| !v.is_finite()) {
            return Err(Error::NonFinite("figure series (shape function failed)"));
        }
        let label = self.label.clone().unwrap_or_else(|| {
            format!(
                "{} {} {} R={}Δx σ̄={} [{}]",
                q.form.name(),
                q.kernel.name(),
                q.shape.name(),
                r,
                s,
                serde_json::to_value(self.route)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_default()
            )
        });
        Ok(Curve {
            label,
            x: kappas.iter().map(|k| k / PI).collect(),
            y,
            dashed: self.dashed,
        })
    }
}

/// Parses a figure config; `file` names it in errors (unknown fields are rejected by name).
pub fn parse(file: &str, text: &str) -> Result<FigureConfig> {
    let cfg: FigureConfig = serde_json::from_str(text).map_err(|e| Error::Config {
        file: file.to_string(),
        msg: e.to_string(),
    })?;
    cfg.validate().map_err(|msg| Error::Config {
        file: file.to_string(),
        msg,
    })?;
    Ok(cfg)
}

impl FigureConfig {
    /// The fields serde cannot check: a plain `.svg` file name (no directory, no `..`: figures
    /// go into the output directory), 1–64 series, 2–100000 points, an increasing finite
    /// `y_range`.
    pub fn validate(&self) -> std::result::Result<(), String> {
        let o = &self.output;
        if o.is_empty()
            || o.contains('/')
            || o.contains('\\')
            || o.contains("..")
            || !o.ends_with(".svg")
        {
            return Err(format!(
                "`output` = {o:?} must be a plain file name ending in .svg (no directory, no ..)"
            ));
        }
        if self.series.is_empty() || self.series.len() > 64 {
            return Err(format!(
                "`series` has {} entries: give 1 to 64 curves",
                self.series.len()
            ));
        }
        if !(2..=100_000).contains(&self.points) {
            return Err(format!(
                "`points` = {} must be an integer in [2, 100000]",
                self.points
            ));
        }
        if let Some((lo, hi)) = self.y_range
            && !(lo.is_finite() && hi.is_finite() && lo < hi)
        {
            return Err(format!(
                "`y_range` = [{lo}, {hi}] must be two finite numbers, the smaller first"
            ));
        }
        Ok(())
    }
}

/// Renders a figure to an SVG string: the curves, the vertical range from the data unless
/// `y_range` fixes it (curves leaving it are marked as clipped), the note as caption.
pub fn render(cfg: &FigureConfig) -> Result<String> {
    let curves = cfg
        .series
        .iter()
        .map(|s| s.curve(cfg.points))
        .collect::<Result<Vec<_>>>()?;
    LinePlot {
        y_range: cfg.y_range,
        zero_line: true,
        notes: if cfg.note.is_empty() {
            Vec::new()
        } else {
            vec![cfg.note.clone()]
        },
        ..LinePlot::new(&cfg.title, KAPPA_DESC, OMEGA2_DESC, curves)
    }
    .svg()
}
