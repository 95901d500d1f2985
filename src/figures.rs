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
//! or `swegle` series — the Swegle test of \[V21 §7.2\] run by [`run_swegle`] (the code of
//! `sphstab swegle`), log10 of a velocity history against time in Δx/c, with the box
//! prediction's growth rate drawn dashed over the fit window, anchored on the least-squares fit
//! of the plotted history ([`SwegleSeries`]):
//!
//! ```json
//! { "output": "v21_fig12.svg", "title": "...", "note": "...",
//!   "swegle": [ { "form": "classical", "kernel": "m4", "h": 1.2, "density_ratio": 0.99 } ] }
//! ```
//!
//! or `scene` series — a 1D scene run by [`Scene1D::run`] (the code of `sphstab simulate`), or
//! its analytic solution ([`Scene1D::exact_profile`]), as a stress or velocity profile along
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

use crate::analysis::{Query1D, dispersion};
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::kernel;
use crate::lattice::{Lattice2D, LatticeKind};
use crate::plot::{Curve, KAPPA_DESC, LinePlot, OMEGA2_DESC, stack_svg};
use crate::shape::{KernelParams, ShapeFamily, lattice_shape};
use crate::solver::diagnostics::growth_fit;
use crate::solver::scene::{Scene1D, builtin};
use crate::solver::swegle::{SwegleConfig, run_swegle};
use crate::vonneumann::antiplane::{AntiPlane, Mass, Quadrature};
use crate::vonneumann::closed_form as cf;
use rayon::prelude::*;
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
    /// 1D scene profiles (stress or velocity against the reference position).
    #[serde(default)]
    pub scene: Vec<SceneSeries>,
    /// Abscissa description (default: that of the curves' kind; scene figures give theirs).
    pub x_desc: Option<String>,
    /// Ordinate description (default: that of the curves' kind; scene figures give theirs).
    pub y_desc: Option<String>,
    /// Panels stacked top to bottom (instead of top-level curves).
    #[serde(default)]
    pub panels: Vec<Panel>,
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
    /// 1D scene profiles.
    #[serde(default)]
    pub scene: Vec<SceneSeries>,
}

/// Which velocity history of a Swegle run is drawn ([`crate::solver::swegle::SwegleReport`]'s
/// `history_full` columns).
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum SwegleHistory {
    /// |v| of the kicked centre particle (the ordinate of \[V21\] Figs 12, 13).
    #[default]
    Centre,
    /// max |v| over the free particles (the history `sphstab swegle` fits).
    Max,
    /// RMS |v| over the free particles.
    Rms,
}

impl SwegleHistory {
    /// Column of `history_full`.
    fn column(self) -> usize {
        match self {
            SwegleHistory::Centre => 1,
            SwegleHistory::Max => 2,
            SwegleHistory::Rms => 3,
        }
    }

    /// Ordinate description.
    fn desc(self) -> &'static str {
        match self {
            SwegleHistory::Centre => {
                "log10 |v| of the kicked centre particle (v in V21's units; kick 1e−10)"
            }
            SwegleHistory::Max => "log10 max |v| over the free particles (V21's units; kick 1e−10)",
            SwegleHistory::Rms => "log10 RMS |v| over the free particles (V21's units; kick 1e−10)",
        }
    }
}

/// One Swegle run (\[V21 §7.2\]: the published box of [`SwegleConfig::new`], 21 × 21, 3
/// fixed layers, Δx = 0.1, ρ0 = 2.8, K = 0.686275, kick 1e−10, fit window 1e−8 to 1e−4):
/// the history drawn solid, and, when the box prediction grows and the history enters the fit
/// window, a dashed line of slope γ_box/ln 10 (γ_box the report's `predicted_growth_rate_box`
/// in c/Δx) over the fit window, through the centroid of the least-squares fit of ln of the
/// drawn history ([`growth_fit`], the fit of `sphstab swegle`, over the same window).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwegleSeries {
    /// Form (a 2D form).
    pub form: String,
    /// Kernel.
    pub kernel: String,
    /// h/Δx.
    pub h: f64,
    /// f = ρ/ρ0 (< 1 tension).
    pub density_ratio: f64,
    /// Partition coefficient c (lnl, cll; default 0.5).
    pub c: Option<f64>,
    /// End time in V21's time units (default 40, the published test).
    pub t_end: Option<f64>,
    /// History drawn (default: the centre particle).
    #[serde(default)]
    pub history: SwegleHistory,
    /// Legend label of the history (default: generated).
    pub label: Option<String>,
}

/// How a scene curve is computed.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum SceneRoute {
    /// The scene run by [`Scene1D::run`].
    #[default]
    Run,
    /// The scene's analytic solution at its end time ([`Scene1D::exact_profile`]).
    Analytic,
}

/// Quantity of a scene profile.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum SceneQuantity {
    /// The stress the form reports ([`Scene1D::stress_profile`]).
    #[default]
    Stress,
    /// The particle velocity.
    Velocity,
}

/// A 1D scene's profile at its end time against the reference position X of every particle
/// (end layers included), multiplied by `x_scale` and `y_scale` (e.g. 1e3 for mm, 1e−9 for GPa).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSeries {
    /// Built-in scene name (`uniform-bar`, `compressive-wave`, `tensile-wave`, `rod`).
    pub scene: String,
    /// Form (default: the scene's).
    pub form: Option<String>,
    /// Partition coefficient c (default: the scene's).
    pub c: Option<f64>,
    /// End time (s; default: the scene's).
    pub t_end: Option<f64>,
    /// Route (default: run).
    #[serde(default)]
    pub route: SceneRoute,
    /// Quantity (default: stress).
    #[serde(default)]
    pub quantity: SceneQuantity,
    /// Factor on the position.
    #[serde(default = "one")]
    pub x_scale: f64,
    /// Factor on the quantity.
    #[serde(default = "one")]
    pub y_scale: f64,
    /// Legend label (default: generated).
    pub label: Option<String>,
    /// Draw dashed.
    #[serde(default)]
    pub dashed: bool,
}

fn one() -> f64 {
    1.0
}

/// Abscissa description of the Swegle figures.
pub const SWEGLE_TIME_DESC: &str =
    "time t c/Δx (units of Δx/c = 0.2020 V21 time units; 1 V21 time unit = 4.951 Δx/c)";

impl SwegleSeries {
    /// The run's configuration: [`SwegleConfig::new`] with this series' form, kernel, h, f,
    /// c and end time.
    pub fn config(&self) -> Result<SwegleConfig> {
        let mut cfg = SwegleConfig::new(
            FormKind::by_name(&self.form)?,
            kernel::by_name(&self.kernel)?,
            self.h,
            self.density_ratio,
        );
        if let Some(c) = self.c {
            cfg.c_partition = c;
        }
        if let Some(t) = self.t_end {
            cfg.t_end = t;
        }
        cfg.validate()?;
        Ok(cfg)
    }

    /// The history (solid) and, when drawn, the predicted growth line (dashed).
    fn curves(&self) -> Result<Vec<Curve>> {
        let cfg = self.config()?;
        let r = run_swegle(&cfg, |_| {})?;
        let unit = cfg.sound_speed() / cfg.dx;
        let col = self.history.column();
        let t: Vec<f64> = r.history_full.iter().map(|h| h[0]).collect();
        let y: Vec<f64> = r.history_full.iter().map(|h| h[col]).collect();
        let tau: Vec<f64> = t.iter().map(|t| t * unit).collect();
        let box_rate = r.predicted_growth_rate_box;
        let name = self.label.clone().unwrap_or_else(|| {
            let mut l = format!("{} ρ/ρ0 = {}", r.form, self.density_ratio);
            if matches!(cfg.form, FormKind::Lnl | FormKind::Cll) {
                l += &format!(", c = {}", cfg.c_partition);
            }
            l
        });
        let fit = growth_fit(&t, &y, cfg.window.0, cfg.window.1);
        let mut label = name.clone();
        match fit {
            Some(f) => label += &format!(": fitted {:.4} c/Δx", f.rate / unit),
            None => label += ": no growth into the fit window",
        }
        let mut out = vec![Curve {
            label,
            x: tau.clone(),
            y: y.iter()
                .map(|v| if *v > 0.0 { v.log10() } else { f64::NAN })
                .collect(),
            dashed: false,
        }];
        if let (Some(f), true) = (fit, box_rate > crate::vonneumann::classify::GROWTH_TOL) {
            // the least-squares line of ln y passes through the centroid of its samples
            let (lo, hi) = f.window;
            let pts: Vec<(f64, f64)> = t
                .iter()
                .zip(&y)
                .filter(|&(&ti, &yi)| ti >= lo && ti <= hi && yi > cfg.window.0)
                .map(|(&ti, &yi)| (ti * unit, yi.log10()))
                .collect();
            let n = pts.len() as f64;
            let (tc, yc) = pts
                .iter()
                .fold((0.0, 0.0), |a, p| (a.0 + p.0 / n, a.1 + p.1 / n));
            let slope = box_rate / std::f64::consts::LN_10;
            let ends = [lo * unit, hi * unit];
            out.push(Curve {
                label: format!(
                    "{name}: box prediction {box_rate:.4} c/Δx ({}), slope through the fit",
                    r.box_method
                ),
                x: ends.to_vec(),
                y: ends.iter().map(|&a| yc + slope * (a - tc)).collect(),
                dashed: true,
            });
        }
        Ok(out)
    }
}

impl SceneSeries {
    /// The scene: the built-in with this series' form, c and end time.
    pub fn scene(&self) -> Result<Scene1D> {
        let mut s = builtin(&self.scene)?;
        if let Some(f) = &self.form {
            s.form = f.clone();
        }
        if let Some(c) = self.c {
            s.c_partition = c;
        }
        if let Some(t) = self.t_end {
            s.t_end = t;
        }
        s.validate()?;
        Ok(s)
    }

    fn curve(&self) -> Result<Curve> {
        crate::error::check_range("x_scale", self.x_scale, 0.0, f64::MAX, false, true)?;
        crate::error::check_range("y_scale", self.y_scale, 0.0, f64::MAX, false, true)?;
        let s = self.scene()?;
        let x: Vec<f64> = s
            .reference_positions()
            .iter()
            .map(|x| x * self.x_scale)
            .collect();
        let (q, label) = match self.route {
            SceneRoute::Analytic => {
                let (v, sigma) = s.exact_profile(s.t_end).ok_or_else(|| {
                    Error::Incompatible(format!(
                        "scene series: `{}` has no analytic solution",
                        self.scene
                    ))
                })?;
                let q = match self.quantity {
                    SceneQuantity::Stress => sigma,
                    SceneQuantity::Velocity => v,
                };
                (q, "analytic".to_string())
            }
            SceneRoute::Run => {
                let mut r = s.run(|_| {})?;
                let z = r
                    .final_state
                    .take()
                    .ok_or(Error::NonFinite("scene series: no final state"))?;
                let q = match self.quantity {
                    SceneQuantity::Stress => s.stress_profile(&z),
                    SceneQuantity::Velocity => z.v,
                };
                let mut l = s.form.clone();
                if matches!(FormKind::by_name(&s.form)?, FormKind::Lnl | FormKind::Cll) {
                    l += &format!(" (c = {})", s.c_partition);
                }
                (q, l)
            }
        };
        Ok(Curve {
            label: self.label.clone().unwrap_or(label),
            x,
            y: q.iter().map(|v| v * self.y_scale).collect(),
            dashed: self.dashed,
        })
    }
}

/// How an anti-plane curve is computed.
#[derive(Clone, Copy, Debug, Default, Deserialize, serde::Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum AntiPlaneRoute {
    /// The Galerkin anti-plane system of [`crate::vonneumann::antiplane`] (as `sphstab
    /// stiffness --theta`): ωΔx/c of every branch.
    #[default]
    Engine,
    /// The continuum ü = c²Δu (\[B00\] eq 110): ωΔx/c = κΔx in every direction.
    Continuum,
}

/// One anti-plane curve (\[B00\] §4.4): ωΔx/c along the direction θ for κΔx from 0 to the
/// first-zone boundary along θ.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AntiPlaneSeries {
    /// Route (default: engine).
    #[serde(default)]
    pub route: AntiPlaneRoute,
    /// Quadrature (`sphstab stiffness --quadrature`); engine route only, required there.
    pub quadrature: Option<String>,
    /// Propagation angle θ in degrees, in [−360, 360].
    pub theta: f64,
    /// Node lattice, `square` (default) or `hex` (Δx = nearest-neighbour distance).
    pub lattice: Option<String>,
    /// Kernel name; engine route only, required there.
    pub kernel: Option<String>,
    /// Support radius R/Δx (\[B00\]'s D_mx); engine route only, required there.
    pub support: Option<f64>,
    /// Shape family (default mls).
    pub shape: Option<String>,
    /// Consistent mass (default: lumped, as \[B00\] eq 119).
    #[serde(default)]
    pub consistent: bool,
    /// Legend label (default: generated).
    pub label: Option<String>,
    /// Draw dashed.
    #[serde(default)]
    pub dashed: bool,
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

/// Ordinate description of the anti-plane figures.
pub const OMEGA_DESC: &str = "ωΔx/c (frequency in units of c/Δx)";
/// Abscissa description of the anti-plane figures.
pub const KAPPA_THETA_DESC: &str = "wave number κΔx/π along θ (dimensionless; dotted: the cut-off, the first-zone boundary along θ)";

impl AntiPlaneSeries {
    fn lattice(&self) -> Result<Lattice2D> {
        Lattice2D::by_name(self.lattice.as_deref().unwrap_or("square"), 1.0)
    }

    /// The cut-off κΔx along θ (the first-zone boundary of the node lattice).
    fn cutoff(&self) -> Result<f64> {
        crate::error::check_range("theta", self.theta, -360.0, 360.0, true, true)?;
        Ok(self.lattice()?.zone_boundary(self.theta.to_radians()))
    }

    /// The curve: ωΔx/c against κΔx/π at `points` wave numbers in (0, cut-off]. A pattern of
    /// several nodes per periodic cell (the star pattern's 2×2 supercell) has one branch per
    /// node (the plane wave's band folded into the smaller zone of the supercell, mixed where
    /// the folded branches meet): all are drawn, as `sphstab stiffness --theta` prints them,
    /// in one curve with gaps between branches. ω² < 0 (not met for K = ∫∇φ·∇φ) would be drawn
    /// as ω = 0, as `sphstab stiffness` prints it.
    fn curve(&self, points: usize) -> Result<Curve> {
        let lat = self.lattice()?;
        let kcut = self.cutoff()?;
        let (c, s) = (self.theta.to_radians().cos(), self.theta.to_radians().sin());
        let kappas: Vec<f64> = (1..=points)
            .map(|i| kcut * i as f64 / points as f64)
            .collect();
        let hex = matches!(lat.kind, LatticeKind::Hexagonal);
        let missing = |f: &str| {
            Error::Incompatible(format!("antiplane series: the engine route needs `{f}`"))
        };
        let (x, y, label) = match self.route {
            AntiPlaneRoute::Continuum => (
                kappas.iter().map(|k| k / PI).collect(),
                kappas.clone(),
                "continuum ωΔx/c = κΔx [B00 eq 110]".to_string(),
            ),
            AntiPlaneRoute::Engine => {
                let q =
                    Quadrature::by_name(self.quadrature.as_deref().ok_or(missing("quadrature"))?)?;
                let k = kernel::by_name(self.kernel.as_deref().ok_or(missing("kernel"))?)?;
                let r = self.support.ok_or(missing("support"))?;
                crate::error::check_range("support", r, 0.0, 50.0, false, true)?;
                let fam = ShapeFamily::by_name(self.shape.as_deref().unwrap_or("mls"))?;
                let ap = AntiPlane::new(
                    &lat,
                    q,
                    fam,
                    KernelParams {
                        kernel: k,
                        h: r / k.zeta(),
                    },
                )?;
                let mass = if self.consistent {
                    Mass::Consistent
                } else {
                    Mass::Lumped
                };
                let w2 = kappas
                    .iter()
                    .map(|&kap| ap.omega2([kap * c, kap * s], mass))
                    .collect::<Result<Vec<_>>>()?;
                let nb = ap.pattern.sites.len();
                let (mut x, mut y) = (Vec::new(), Vec::new());
                for b in 0..nb {
                    if b > 0 {
                        x.push(f64::NAN);
                        y.push(f64::NAN);
                    }
                    x.extend(kappas.iter().map(|k| k / PI));
                    y.extend(w2.iter().map(|w| w[b].max(0.0).sqrt()));
                }
                let mut label = format!("{}, θ = {}°", q.name(), self.theta);
                if nb > 1 {
                    label += &format!(
                        " (all {nb} branches: {nb} nodes per periodic cell, the band folded into its smaller zone)"
                    );
                }
                if hex {
                    label += ", hex lattice";
                }
                (x, y, label)
            }
        };
        Ok(Curve {
            label: self.label.clone().unwrap_or(label),
            x,
            y,
            dashed: self.dashed,
        })
    }
}

/// The cut-off marks of anti-plane curves: one per distinct cut-off, naming every θ (and the
/// lattice when hexagonal) that ends there.
fn cutoff_marks(series: &[AntiPlaneSeries]) -> Result<Vec<(f64, String)>> {
    let mut marks: Vec<(f64, Vec<String>)> = Vec::new();
    for a in series {
        let k = a.cutoff()? / PI;
        let name = format!("{}°", a.theta);
        match marks.iter_mut().find(|m| (m.0 - k).abs() < 1e-9) {
            Some(m) if !m.1.contains(&name) => m.1.push(name),
            Some(_) => {}
            None => marks.push((k, vec![name])),
        }
    }
    Ok(marks
        .into_iter()
        .map(|(k, names)| (k, format!("cut-off θ = {}", names.join(", "))))
        .collect())
}

/// A panel's curves and extras, as [`render`] draws them.
struct PanelSpec<'a> {
    title: &'a str,
    y_range: Option<(f64, f64)>,
    series: &'a [Series],
    antiplane: &'a [AntiPlaneSeries],
    swegle: &'a [SwegleSeries],
    scene: &'a [SceneSeries],
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
                    .map(SwegleSeries::curves)
                    .collect::<Result<Vec<_>>>()?;
                Ok(c.into_iter().flatten().collect())
            } else if !p.scene.is_empty() {
                p.scene.iter().map(SceneSeries::curve).collect()
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
        let curves = |what: &str, counts: [usize; 4]| {
            let kinds = counts.iter().filter(|&&n| n > 0).count();
            let n: usize = counts.iter().sum();
            match kinds {
                0 => Err(format!(
                    "{what}: give 1 to 64 curves in `series` (1D), `antiplane` (2D), `swegle` or `scene`"
                )),
                1 if n <= 64 => Ok(()),
                1 => Err(format!("{what} has {n} curves: give 1 to 64")),
                _ => Err(format!(
                    "{what}: give one of `series` (1D), `antiplane` (2D), `swegle`, `scene`, not several (their axes differ)"
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
                ],
            )?;
        } else {
            if !self.series.is_empty()
                || !self.antiplane.is_empty()
                || !self.swegle.is_empty()
                || !self.scene.is_empty()
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
/// `y_range` fixes it (curves leaving it are marked as clipped), the note as caption; panels
/// stacked under the figure title, the note under the last. Anti-plane panels mark the
/// cut-off of every θ.
pub fn render(cfg: &FigureConfig) -> Result<String> {
    let specs = cfg.panel_specs();
    let data = panel_curves(cfg)?;
    let n = specs.len();
    let parts = specs
        .iter()
        .zip(data)
        .enumerate()
        .map(|(i, (p, curves))| {
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
            } else {
                (KAPPA_DESC, OMEGA2_DESC, Vec::new())
            };
            let x_desc = cfg.x_desc.as_deref().unwrap_or(x_desc);
            let y_desc = cfg.y_desc.as_deref().unwrap_or(y_desc);
            LinePlot {
                y_range: p.y_range,
                zero_line: p.swegle.is_empty(),
                notes: if i + 1 == n && !cfg.note.is_empty() {
                    vec![cfg.note.clone()]
                } else {
                    Vec::new()
                },
                x_marks,
                ..LinePlot::new(p.title, x_desc, y_desc, curves)
            }
            .svg()
        })
        .collect::<Result<Vec<_>>>()?;
    if cfg.panels.is_empty() {
        return parts
            .into_iter()
            .next()
            .ok_or_else(|| Error::Incompatible("figure without curves".into()));
    }
    stack_svg(&cfg.title, &parts)
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
