//! Figures regenerated from JSON configs (`analysis/configs/*.json`), each rendered to one SVG.
//! A config lists 1D `series` — a form at a kernel, smoothing length, shape and stress,
//! computed by the numeric engine, by one of \[B00\]'s closed forms or as the linear finite
//! element of \[B00\] Fig 10 — plotted as ω²Δx²/c² against κΔx/π:
//!
//! ```json
//! { "output": "b00_fig3_eq74.svg", "title": "...", "note": "...",
//!   "points": 256, "y_range": [-1.5, 1.5],
//!   "series": [ { "form": "eulerian-nodal", "kernel": "efg-quartic", "support": 1.5,
//!                 "shape": "mls", "stress": 0.5, "route": "b00-eq74", "label": "σ̄ = 0.5" } ] }
//! ```
//!
//! or 2D `antiplane` series — the anti-plane Galerkin wave of \[B00\] §4.4 computed by
//! [`crate::vonneumann::antiplane`] (the code of `sphstab stiffness`), ωΔx/c along a direction
//! θ up to the zone boundary, against κΔx/π with the cut-offs marked:
//!
//! ```json
//! { "output": "b00_fig13.svg", "title": "...", "note": "...",
//!   "antiplane": [ { "quadrature": "nodal", "theta": 45, "kernel": "efg-cubic",
//!                    "support": 2.0, "shape": "mls" },
//!                  { "route": "continuum", "theta": 45, "dashed": true } ] }
//! ```
//!
//! or `swegle` series — the Swegle test of \[V21 §7.2\] run by
//! [`crate::studies::swegle::run_swegle`] (the code of `sphstab swegle`), log10 of a velocity
//! history against time in Δx/c, with the box prediction's growth rate drawn dashed over the fit
//! window, anchored on the least-squares fit of the plotted history ([`SwegleSeries`]):
//!
//! ```json
//! { "output": "v21_fig12.svg", "title": "...", "note": "...",
//!   "swegle": [ { "form": "classical", "kernel": "m4", "h": 1.2, "density_ratio": 0.99 } ] }
//! ```
//!
//! or `scene` series — a scene (1D, 2D or 3D: its central row) run by [`crate::solver::scene::Scene::run`] (the code of
//! `sphstab simulate`), or its analytic solution
//! ([`crate::solver::scene::Scene::exact_profile`]), as a stress or velocity profile along
//! the bar at the scene's end time ([`SceneSeries`]); `x_desc` and `y_desc` name the axes:
//!
//! ```json
//! { "output": "v21_fig17.svg", "title": "...", "note": "...",
//!   "x_desc": "X (mm)", "y_desc": "σ (GPa)",
//!   "scene": [ { "scene": "compressive-wave", "form": "nonlocal", "x_scale": 1e3, "y_scale": 1e-9 },
//!              { "scene": "compressive-wave", "route": "analytic", "x_scale": 1e3, "y_scale": 1e-9,
//!                "dashed": true } ] }
//! ```
//!
//! A figure of several panels (stacked top to bottom, as the paper's (a), (b), …) gives
//! `panels`, each with its `title`, optional `y_range` and its curves of one kind, instead of
//! top-level curves.

use crate::analysis::{Query, dispersion};
use crate::budget::Budget;
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::kernel;
use crate::plot::print::Width;
use crate::plot::{Curve, KAPPA_DESC, LinePlot, OMEGA2_DESC, stack_svg};
use crate::shape::{KernelParams, ShapeFamily, lattice_shape};
use crate::vonneumann::closed_form as cf;
use rayon::prelude::*;

mod antiplane;
mod finite_body;
mod galerkin;
mod interpolation;
mod scene;
mod swegle;

use antiplane::cutoff_marks;
pub use antiplane::{AntiPlaneRoute, AntiPlaneSeries, KAPPA_THETA_DESC, OMEGA_DESC};
pub use finite_body::{FiniteBodyRoute, FiniteBodySeries};
pub use galerkin::{GalerkinNorm, GalerkinSeries};
pub use interpolation::{InterpolationQuantity, InterpolationSeries};
pub use scene::{SceneQuantity, SceneRoute, SceneSeries};
use serde::Deserialize;
use std::f64::consts::PI;
pub use swegle::{SWEGLE_TIME_DESC, SwegleHistory, SwegleSeries};

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
    /// The two-node linear finite element with lumped mass, \[B00\] Fig 10's comparison
    /// curve: [`fe_linear_lumped`].
    FeLinearLumped,
}

/// Two-node linear finite elements with lumped mass on a uniform mesh of spacing Δx, the
/// comparison curve of \[B00\] Fig 10: ω²Δx²/c² = (1 + σ̄) · 4 sin²(κΔx/2).
///
/// Element stiffness (C̄/Δx)[[1, −1], [−1, 1]] with C̄ = C + σ (\[B00\] eq 81 at F = 1, as
/// in eq 82), lumped nodal mass ρΔx: m ü_j = (C̄/Δx)(u_{j+1} − 2u_j + u_{j−1}), so
/// ω² = (C̄/ρΔx²)(2 − 2 cos κΔx) = (C̄/ρΔx²) 4 sin²(κΔx/2). `kappa` is κΔx.
pub fn fe_linear_lumped(sigma_bar: f64, kappa: f64) -> f64 {
    let s = (0.5 * kappa).sin();
    (1.0 + sigma_bar) * 4.0 * s * s
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
    /// a curve leaving it is marked as clipped. With `panels`: the range of every panel that
    /// gives none.
    pub y_range: Option<(f64, f64)>,
    /// 1D curves (ω²Δx²/c² against κΔx/π).
    #[serde(default)]
    pub series: Vec<Series>,
    /// 2D anti-plane curves (ωΔx/c against κΔx/π).
    #[serde(default)]
    pub antiplane: Vec<AntiPlaneSeries>,
    /// Swegle growth histories (log10 |v| against t c/Δx).
    #[serde(default)]
    pub swegle: Vec<SwegleSeries>,
    /// Scene profiles (stress or velocity along the central row against the reference position).
    #[serde(default)]
    pub scene: Vec<SceneSeries>,
    /// Interpolations of a test function (against position).
    #[serde(default)]
    pub interpolation: Vec<InterpolationSeries>,
    /// Finite bodies' largest eigenvalues (against the support D_max).
    #[serde(default)]
    pub finite_body: Vec<FiniteBodySeries>,
    /// Static Galerkin errors (against log10 Δx, on a log axis).
    #[serde(default)]
    pub galerkin: Vec<GalerkinSeries>,
    /// Abscissa description (default: that of the curves' kind; scene figures give theirs).
    pub x_desc: Option<String>,
    /// Ordinate description (default: that of the curves' kind; scene figures give theirs).
    pub y_desc: Option<String>,
    /// Panels stacked top to bottom (instead of top-level curves).
    #[serde(default)]
    pub panels: Vec<Panel>,
    /// The budget the swegle and scene runs must stay within (not read from the file).
    #[serde(skip)]
    pub budget: Budget,
}

/// One panel of a figure: its curves, 1D `series` or 2D `antiplane` (not both).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Panel {
    /// Panel title, e.g. "(a) D_mx = 1.5".
    pub title: String,
    /// Fixed vertical range (default: the figure's, else from the data).
    pub y_range: Option<(f64, f64)>,
    /// 1D curves.
    #[serde(default)]
    pub series: Vec<Series>,
    /// 2D anti-plane curves.
    #[serde(default)]
    pub antiplane: Vec<AntiPlaneSeries>,
    /// Swegle growth histories.
    #[serde(default)]
    pub swegle: Vec<SwegleSeries>,
    /// Scene profiles.
    #[serde(default)]
    pub scene: Vec<SceneSeries>,
    /// Interpolations of a test function.
    #[serde(default)]
    pub interpolation: Vec<InterpolationSeries>,
    /// Finite bodies' largest eigenvalues.
    #[serde(default)]
    pub finite_body: Vec<FiniteBodySeries>,
    /// Static Galerkin errors.
    #[serde(default)]
    pub galerkin: Vec<GalerkinSeries>,
}

fn default_points() -> usize {
    256
}

impl Series {
    fn query(&self, points: usize) -> Result<Query<1>> {
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
        let mut q = Query::<1>::new(form, k, h, self.stress);
        if let Some(s) = &self.shape {
            q.shape = ShapeFamily::by_name(s)?;
        }
        if let Some(c) = self.c {
            q.c_partition = c;
        }
        if let Some(a) = self.alpha_s {
            q.alpha_s = a;
        }
        q.grid = points;
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
            Route::Engine => dispersion(&q, q.grid)?.omega2_branch(0),
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
            Route::FeLinearLumped => kappas.iter().map(|&k| fe_linear_lumped(s, k)).collect(),
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

/// A panel's curves and extras, as [`render`] draws them.
struct PanelSpec<'a> {
    title: &'a str,
    y_range: Option<(f64, f64)>,
    series: &'a [Series],
    antiplane: &'a [AntiPlaneSeries],
    swegle: &'a [SwegleSeries],
    scene: &'a [SceneSeries],
    interpolation: &'a [InterpolationSeries],
    finite_body: &'a [FiniteBodySeries],
    galerkin: &'a [GalerkinSeries],
}

impl FigureConfig {
    fn panel_specs(&self) -> Vec<PanelSpec<'_>> {
        if self.panels.is_empty() {
            return vec![PanelSpec {
                title: &self.title,
                y_range: self.y_range,
                series: &self.series,
                antiplane: &self.antiplane,
                swegle: &self.swegle,
                scene: &self.scene,
                interpolation: &self.interpolation,
                finite_body: &self.finite_body,
                galerkin: &self.galerkin,
            }];
        }
        self.panels
            .iter()
            .map(|p| PanelSpec {
                title: &p.title,
                y_range: p.y_range.or(self.y_range),
                series: &p.series,
                antiplane: &p.antiplane,
                swegle: &p.swegle,
                scene: &p.scene,
                interpolation: &p.interpolation,
                finite_body: &p.finite_body,
                galerkin: &p.galerkin,
            })
            .collect()
    }
}

/// The data of every panel of a figure (one panel without `panels`), curve by curve as drawn:
/// abscissa κΔx/π; ordinate ω²Δx²/c² (1D `series`) or ωΔx/c (`antiplane`); or log10 |v|
/// against t c/Δx (`swegle`: each run's history, then its predicted line when drawn); or a
/// scene's profile against X (`scene`).
pub fn panel_curves(cfg: &FigureConfig) -> Result<Vec<Vec<Curve>>> {
    cfg.panel_specs()
        .iter()
        .map(|p| {
            if !p.antiplane.is_empty() {
                p.antiplane.iter().map(|s| s.curve(cfg.points)).collect()
            } else if !p.swegle.is_empty() {
                // independent runs, in parallel; collected in order
                let c = p
                    .swegle
                    .par_iter()
                    .map(|s| s.curves(&cfg.budget))
                    .collect::<Result<Vec<_>>>()?;
                Ok(c.into_iter().flatten().collect())
            } else if !p.scene.is_empty() {
                p.scene.iter().map(|s| s.curve(&cfg.budget)).collect()
            } else if !p.interpolation.is_empty() {
                p.interpolation
                    .iter()
                    .map(|s| s.curve(&cfg.budget))
                    .collect()
            } else if !p.finite_body.is_empty() {
                p.finite_body.iter().map(|s| s.curve(&cfg.budget)).collect()
            } else if !p.galerkin.is_empty() {
                p.galerkin.iter().map(|s| s.curve()).collect()
            } else {
                p.series.iter().map(|s| s.curve(cfg.points)).collect()
            }
        })
        .collect()
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
    /// go into the output directory), 2–100000 points, increasing finite `y_range`s, and either
    /// top-level curves or 1–8 `panels`, each place with 1–64 curves of one kind (`series` or
    /// `antiplane`).
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
        let curves = |what: &str, counts: [usize; 7]| {
            let kinds = counts.iter().filter(|&&n| n > 0).count();
            let n: usize = counts.iter().sum();
            match kinds {
                0 => Err(format!(
                    "{what}: give 1 to 64 curves in `series` (1D), `antiplane` (2D), `swegle`, `scene`, `interpolation`, `finite_body` or `galerkin`"
                )),
                1 if n <= 64 => Ok(()),
                1 => Err(format!("{what} has {n} curves: give 1 to 64")),
                _ => Err(format!(
                    "{what}: give one of `series` (1D), `antiplane` (2D), `swegle`, `scene`, `interpolation`, `finite_body`, `galerkin`, not several (their axes differ)"
                )),
            }
        };
        let range = |what: &str, r: Option<(f64, f64)>| match r {
            Some((lo, hi)) if !(lo.is_finite() && hi.is_finite() && lo < hi) => Err(format!(
                "{what} = [{lo}, {hi}] must be two finite numbers, the smaller first"
            )),
            _ => Ok(()),
        };
        if self.panels.is_empty() {
            curves(
                "the figure",
                [
                    self.series.len(),
                    self.antiplane.len(),
                    self.swegle.len(),
                    self.scene.len(),
                    self.interpolation.len(),
                    self.finite_body.len(),
                    self.galerkin.len(),
                ],
            )?;
        } else {
            if !self.series.is_empty()
                || !self.antiplane.is_empty()
                || !self.swegle.is_empty()
                || !self.scene.is_empty()
                || !self.interpolation.is_empty()
                || !self.finite_body.is_empty()
                || !self.galerkin.is_empty()
            {
                return Err(
                    "give the curves either at the top level or in `panels`, not both".into(),
                );
            }
            if self.panels.len() > 8 {
                return Err(format!(
                    "`panels` has {} entries: give 1 to 8",
                    self.panels.len()
                ));
            }
            for (i, p) in self.panels.iter().enumerate() {
                curves(
                    &format!("`panels[{i}]`"),
                    [
                        p.series.len(),
                        p.antiplane.len(),
                        p.swegle.len(),
                        p.scene.len(),
                        p.interpolation.len(),
                        p.finite_body.len(),
                        p.galerkin.len(),
                    ],
                )?;
                range(&format!("`panels[{i}].y_range`"), p.y_range)?;
            }
        }
        if !(2..=100_000).contains(&self.points) {
            return Err(format!(
                "`points` = {} must be an integer in [2, 100000]",
                self.points
            ));
        }
        range("`y_range`", self.y_range)
    }
}

/// Renders a figure to an SVG string: the curves, the vertical range from the data unless
/// `y_range` fixes it (curves leaving it are marked as clipped). The title and the note are
/// the caption (`figures` writes them to the captions file), not drawn: a figure of one panel is 170 mm wide with its legend
/// right of the data; panels are 85 mm wide, two side by side, each with its letter and its
/// legend under it. Anti-plane panels mark the cut-off of every θ.
pub fn render(cfg: &FigureConfig) -> Result<String> {
    let specs = cfg.panel_specs();
    let data = panel_curves(cfg)?;
    let paneled = !cfg.panels.is_empty();
    let parts = specs
        .iter()
        .zip(data)
        .map(|(p, curves)| {
            let (x_desc, y_desc, x_marks) = if !p.antiplane.is_empty() {
                (KAPPA_THETA_DESC, OMEGA_DESC, cutoff_marks(p.antiplane)?)
            } else if let Some(s) = p.swegle.first() {
                (SWEGLE_TIME_DESC, s.history.desc(), Vec::new())
            } else if !p.scene.is_empty() {
                (
                    "reference position X",
                    "stress σ (+ tension) or velocity",
                    Vec::new(),
                )
            } else if !p.interpolation.is_empty() {
                ("position x", "f, ∂f/∂x or ∂²f/∂x²", Vec::new())
            } else if !p.finite_body.is_empty() {
                ("support D_max (Δx)", "λ_max (c²/Δx²)", Vec::new())
            } else if !p.galerkin.is_empty() {
                ("log10 Δx", "relative error", Vec::new())
            } else {
                (KAPPA_DESC, OMEGA2_DESC, Vec::new())
            };
            let x_desc = cfg.x_desc.as_deref().unwrap_or(x_desc);
            let y_desc = cfg.y_desc.as_deref().unwrap_or(y_desc);
            LinePlot {
                y_range: p.y_range,
                zero_line: p.swegle.is_empty() && p.galerkin.is_empty(),
                y_log: !p.swegle.is_empty() || !p.galerkin.is_empty(),
                names: crate::studies::series_names(),
                x_marks,
                width: if paneled {
                    Width::Single
                } else {
                    Width::Double
                },
                ..LinePlot::new(if paneled { p.title } else { "" }, x_desc, y_desc, curves)
            }
            .svg()
        })
        .collect::<Result<Vec<_>>>()?;
    if !paneled {
        return parts
            .into_iter()
            .next()
            .ok_or_else(|| Error::Incompatible("figure without curves".into()));
    }
    stack_svg("", &parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lumped linear element from its assembled stencil: nodal mass ρΔx, element
    /// stiffness (C̄/Δx)[[1, −1], [−1, 1]] gives row (−1, 2, −1)·C̄/Δx, whose symbol over the
    /// mass is (C̄/ρΔx²) Σ_j a_j e^{iκj} = (1 + σ̄)(2 − 2 cos κ) in units of c²/Δx².
    #[test]
    fn fe_route_is_the_assembled_lumped_element() {
        for sigma in [0.0, 0.3, -0.5] {
            for i in 0..=16 {
                let k = PI * i as f64 / 16.0;
                let stencil = [(-1i32, -1.0), (0, 2.0), (1, -1.0)];
                let sym: f64 = stencil
                    .iter()
                    .map(|&(j, a)| (1.0 + sigma) * a * (k * f64::from(j)).cos())
                    .sum();
                assert!((fe_linear_lumped(sigma, k) - sym).abs() < 1e-12);
            }
        }
        assert!((fe_linear_lumped(0.0, PI) - 4.0).abs() < 1e-15);
    }

    #[test]
    fn continuum_route_is_the_identity_up_to_the_cut_off() {
        let a: AntiPlaneSeries =
            serde_json::from_str(r#"{"route":"continuum","theta":45}"#).unwrap();
        let c = a.curve(8).unwrap();
        assert_eq!(c.x.len(), 8);
        // square lattice, θ = 45°: the zone boundary is at √2π (B00 §4.4)
        assert!((c.x[7] - 2f64.sqrt()).abs() < 1e-12);
        for (x, y) in c.x.iter().zip(&c.y) {
            assert!((y - x * PI).abs() < 1e-12);
        }
    }

    #[test]
    fn cut_off_marks_merge_equal_cut_offs() {
        let s = |t: f64| -> AntiPlaneSeries {
            serde_json::from_str(&format!(r#"{{"route":"continuum","theta":{t}}}"#)).unwrap()
        };
        let m = cutoff_marks(&[s(0.0), s(90.0), s(45.0), s(0.0)]).unwrap();
        assert_eq!(m.len(), 2);
        assert_eq!(m[0].1, "cut-off θ = 0°, 90°");
        assert!((m[0].0 - 1.0).abs() < 1e-12);
        assert!((m[1].0 - 2f64.sqrt()).abs() < 1e-12);
    }
}
