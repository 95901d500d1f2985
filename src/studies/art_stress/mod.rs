//! The artificial-stress study (`sphstab art-stress`): how much Monaghan–Gray artificial stress
//! (R = −ε σ⁺/ρ², force Σ m (R_I + R_J) fⁿ ∇W, f = W(r)/W(Δx)) slows the Swegle growth of the
//! classical form in a zero-shear material under tension, predicted by the engine on the
//! infinite lattice and for the finite Swegle box, and measured by Swegle runs — all three from
//! the one rate function of [`crate::forms`] ([`crate::studies::swegle`]).
//!
//! For every h/Δx and density ratio f of the config, the growth rate is computed on a grid of ε
//! (infinite lattice: the fastest mode over the zone with its polarisation; box: the dense
//! operator of the same finite particle set), and Swegle runs are made at a subset of ε. A
//! stored set of runs of another code (PySPH, `analysis/pysph/results-art-stress.json`) can be
//! drawn next to them. The figure has one panel per (h, f).

use crate::error::{Error, Result, check_range};
use crate::forms::FormKind;
use crate::plot::axes::{Frame, Scale, auto_range};
use crate::plot::style::{
    Dash, GREY, Style, draw_line, draw_marker, draw_sample, plot_err, series_style, text, text_at,
    text_width, wrap,
};
use crate::solver::BoundaryDensity;
use crate::studies::swegle::{SwegleConfig, predict_swegle, run_swegle};
use rayon::prelude::*;
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
    /// working directory; read by the command line, see [`Comparison`]).
    #[serde(default)]
    pub compare: Option<String>,
    /// Figure written to figures/ (with its data next to it as .json).
    #[serde(default)]
    pub output: Option<String>,
    /// What the figure shows (kept with the config and the data).
    #[serde(default)]
    pub note: String,
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
        }
    }

    /// Checks every field; errors name the config field.
    pub fn validate(&self) -> Result<()> {
        self.validate_named(false)
    }

    /// Checks every field; errors name the command-line flag (`cli`) or the config field.
    pub fn validate_named(&self, cli: bool) -> Result<()> {
        let name = |field: &'static str, flag: &'static str| if cli { flag } else { field };
        let form = FormKind::by_name(&self.form)?;
        if !matches!(form, FormKind::Classical | FormKind::Cll) {
            return Err(Error::Incompatible(format!(
                "form {} has no artificial stress (allowed: classical, cll)",
                self.form
            )));
        }
        crate::kernel::by_name(&self.kernel)?;
        let count = |name: &'static str, n: usize, lo: usize, hi: usize| {
            if n < lo || n > hi {
                Err(Error::OutOfRange {
                    name,
                    value: n as f64,
                    range: format!("{lo} to {hi} values"),
                })
            } else {
                Ok(())
            }
        };
        count(name("h", "--h"), self.h.len(), 1, 4)?;
        count(
            name("density_ratio", "--density-ratio"),
            self.density_ratio.len(),
            1,
            4,
        )?;
        count(name("eps", "--eps"), self.eps.len(), 1, 200)?;
        count(name("runs", "--runs"), self.runs.len(), 0, 40)?;
        for &h in &self.h {
            check_range(name("h", "--h"), h, 0.8, 6.0, true, true)?;
        }
        for &f in &self.density_ratio {
            check_range(
                name("density_ratio", "--density-ratio"),
                f,
                0.5,
                1.5,
                true,
                true,
            )?;
        }
        for &e in &self.eps {
            check_range(name("eps", "--eps"), e, 0.0, 10.0, true, true)?;
        }
        for &e in &self.runs {
            check_range(name("runs", "--runs"), e, 0.0, 10.0, true, true)?;
        }
        check_range(
            name("art_n", "--art-n"),
            self.art_n as f64,
            1.0,
            12.0,
            true,
            true,
        )?;
        check_range(
            name("size", "--size"),
            self.size as f64,
            9.0,
            81.0,
            true,
            true,
        )?;
        if let Some(o) = &self.output {
            crate::studies::config::check_output("art-stress config", Some(o))?;
        }
        Ok(())
    }

    /// The Swegle configuration of one point (ε = 0: no artificial stress).
    pub fn swegle(&self, h: f64, f: f64, eps: f64) -> Result<SwegleConfig> {
        let form = FormKind::by_name(&self.form)?;
        let mut c = SwegleConfig::new(form, crate::kernel::by_name(&self.kernel)?, h, f);
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

/// One ε of the prediction grid.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct Point {
    /// ε.
    pub eps: f64,
    /// Infinite-lattice growth rate (c/Δx).
    pub infinite: f64,
    /// Wave vector (κΔx per axis) of the infinite lattice's fastest mode.
    pub infinite_kappa: Vec<f64>,
    /// Its longitudinal fraction |p·κ̂|² (1 longitudinal, 0 transverse).
    pub longitudinal: f64,
    /// Growth rate of the finite box (c/Δx).
    pub in_box: f64,
}

/// One Swegle run.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct RunPoint {
    /// ε.
    pub eps: f64,
    /// Measured growth rate (c/Δx); None when nothing grew into the fit window.
    pub measured: Option<f64>,
    /// The box prediction at this ε (c/Δx).
    pub predicted_box: f64,
    /// measured / box.
    pub ratio_box: Option<f64>,
    /// Dominant standing mode of the growing pattern (κΔx per axis) and its power share.
    pub dominant_kappa: Option<(Vec<f64>, f64)>,
    /// Time steps taken.
    pub steps: usize,
}

/// Another code's measured growth rate at one ε.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct ComparePoint {
    /// ε.
    pub eps: f64,
    /// Measured growth rate (c/Δx); None when nothing grew into the fit window.
    pub measured: Option<f64>,
}

/// One (h, f) panel.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct Case {
    /// h/Δx.
    pub h: f64,
    /// f = ρ/ρ0.
    pub density_ratio: f64,
    /// σ̄ = 1 − f (tension positive).
    pub sigma_bar: f64,
    /// The prediction grid.
    pub points: Vec<Point>,
    /// ε of the smallest infinite-lattice growth on the grid, and that growth.
    pub min_infinite: (f64, f64),
    /// ε of the smallest box growth on the grid, and that growth.
    pub min_box: (f64, f64),
    /// Smallest ε of the grid from which the infinite lattice's fastest mode is transverse
    /// (longitudinal fraction < 1/2) at every larger grid ε; None if it never is.
    pub transverse_from: Option<f64>,
    /// The Swegle runs.
    pub runs: Vec<RunPoint>,
    /// Another code's runs (empty without `compare`).
    #[serde(default)]
    pub compare: Vec<ComparePoint>,
}

/// Another code's measurements, as read from `compare` (the command line reads the file).
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
pub struct Comparison {
    /// Name in the legend (e.g. "PySPH 1.0b2").
    pub label: String,
    /// (h, f, ε, measured rate).
    pub points: Vec<(f64, f64, f64, Option<f64>)>,
}

/// The study's report (also the stored data the figure is redrawn from).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct ArtStressReport {
    /// The config.
    pub config: ArtStressConfig,
    /// Legend name of the compared code (empty: none).
    #[serde(default)]
    pub compare_label: String,
    /// One per (h, f), h-major.
    pub cases: Vec<Case>,
}

/// Runs the study; `progress(done, total)` after every prediction and run.
pub fn run(
    cfg: &ArtStressConfig,
    compare: Option<&Comparison>,
    mut progress: impl FnMut(usize, usize),
) -> Result<ArtStressReport> {
    cfg.validate()?;
    let total = cfg.h.len() * cfg.density_ratio.len() * (cfg.eps.len() + cfg.runs.len());
    let mut done = 0;
    let mut cases = Vec::new();
    for &h in &cfg.h {
        for &f in &cfg.density_ratio {
            // the grid points are independent: in parallel (the dense box eigenproblem dominates)
            let points = cfg
                .eps
                .par_iter()
                .map(|&eps| {
                    let p = predict_swegle(&cfg.swegle(h, f, eps)?)?;
                    Ok(Point {
                        eps,
                        infinite: p.infinite_rate,
                        infinite_kappa: p.infinite_kappa,
                        longitudinal: p.infinite_longitudinal,
                        in_box: p.box_rate,
                    })
                })
                .collect::<Result<Vec<Point>>>()?;
            done += points.len();
            progress(done, total);
            let mut runs = Vec::with_capacity(cfg.runs.len());
            for &eps in &cfg.runs {
                let r = run_swegle(&cfg.swegle(h, f, eps)?, |_| {})?;
                runs.push(RunPoint {
                    eps,
                    measured: r.measured_growth_rate,
                    predicted_box: r.predicted_growth_rate_box,
                    ratio_box: r.ratio_box,
                    dominant_kappa: r.dominant_kappa,
                    steps: r.steps,
                });
                done += 1;
                progress(done, total);
            }
            let argmin = |g: &dyn Fn(&Point) -> f64| {
                points
                    .iter()
                    .map(|p| (p.eps, g(p)))
                    .fold(
                        (f64::NAN, f64::INFINITY),
                        |a, b| if b.1 < a.1 { b } else { a },
                    )
            };
            let transverse_from = points
                .iter()
                .rposition(|p| p.longitudinal >= 0.5 || p.infinite <= 0.0)
                .map_or(Some(0), |i| (i + 1 < points.len()).then_some(i + 1))
                .map(|i| points[i].eps);
            let compare = compare
                .map(|c| {
                    c.points
                        .iter()
                        .filter(|p| close(p.0, h) && close(p.1, f))
                        .map(|p| ComparePoint {
                            eps: p.2,
                            measured: p.3,
                        })
                        .collect()
                })
                .unwrap_or_default();
            cases.push(Case {
                h,
                density_ratio: f,
                sigma_bar: 1.0 - f,
                min_infinite: argmin(&|p| p.infinite),
                min_box: argmin(&|p| p.in_box),
                transverse_from,
                points,
                runs,
                compare,
            });
        }
    }
    Ok(ArtStressReport {
        config: cfg.clone(),
        compare_label: compare.map(|c| c.label.clone()).unwrap_or_default(),
        cases,
    })
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// The report as a table (one line per grid ε, runs and compared measurements beside it).
pub fn table(r: &ArtStressReport) -> String {
    let mut s = String::new();
    let c = &r.config;
    s += &format!(
        "# artificial stress: {} {} (n = {}), Swegle box {}×{} ({} boundary density); rates in c/Δx\n",
        c.form,
        c.kernel,
        c.art_n,
        c.size,
        c.size,
        match c.boundary_density {
            BoundaryDensity::Frozen => "frozen",
            BoundaryDensity::Evolve => "evolving",
        }
    );
    let other = if r.compare_label.is_empty() {
        String::new()
    } else {
        format!("  {:>10}", short(&r.compare_label))
    };
    for case in &r.cases {
        s += &format!(
            "\nh = {}Δx, f = {} (σ̄ = {:.3}): least growth at ε = {} (infinite lattice, {:.4}) and ε = {} (box, {:.4}); fastest mode transverse from ε = {}\n",
            case.h,
            case.density_ratio,
            case.sigma_bar,
            trim(case.min_infinite.0),
            case.min_infinite.1,
            trim(case.min_box.0),
            case.min_box.1,
            case.transverse_from.map_or("never".to_string(), trim)
        );
        s += &format!(
            "{:>6}  {:>9}  {:>18}  {:>6}  {:>9}  {:>9}  {:>6}{other}\n",
            "ε", "infinite", "κΔx/π of fastest", "long.", "box", "run", "run/box"
        );
        let mut eps: Vec<f64> = case
            .points
            .iter()
            .map(|p| p.eps)
            .chain(case.runs.iter().map(|p| p.eps))
            .chain(case.compare.iter().map(|p| p.eps))
            .collect();
        eps.sort_by(f64::total_cmp);
        eps.dedup_by(|a, b| close(*a, *b));
        let rate = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.4}"));
        for e in eps {
            let p = case.points.iter().find(|p| close(p.eps, e));
            let run = case.runs.iter().find(|p| close(p.eps, e));
            let cmp = case.compare.iter().find(|p| close(p.eps, e));
            let k = p.map_or("".to_string(), |p| {
                p.infinite_kappa
                    .iter()
                    .map(|k| format!("{:.3}", k / std::f64::consts::PI))
                    .collect::<Vec<_>>()
                    .join(", ")
            });
            s += &format!(
                "{:>6}  {:>9}  {:>18}  {:>6}  {:>9}  {:>9}  {:>6}",
                trim(e),
                rate(p.map(|p| p.infinite)),
                k,
                p.map_or("".into(), |p| format!("{:.2}", p.longitudinal)),
                rate(p.map(|p| p.in_box)),
                rate(run.and_then(|r| r.measured)),
                run.and_then(|r| r.ratio_box)
                    .map_or("-".into(), |x| format!("{x:.3}")),
            );
            if !r.compare_label.is_empty() {
                s += &format!("  {:>10}", rate(cmp.and_then(|c| c.measured)));
            }
            s += "\n";
        }
    }
    s
}

fn short(label: &str) -> String {
    label.split_whitespace().next().unwrap_or(label).to_string()
}

/// Panel size (pixels).
const PANEL_W: f64 = 430.0;
const PANEL_H: f64 = 330.0;

/// Legend entries: (label, style, line, marker).
fn legend(r: &ArtStressReport) -> Vec<(String, Style, bool, bool)> {
    let inf = series_style(0, Dash::Solid);
    let mut v = vec![
        (
            "infinite lattice, fastest mode longitudinal".to_string(),
            inf,
            true,
            true,
        ),
        (
            "infinite lattice, fastest mode transverse".to_string(),
            Style {
                filled: false,
                ..inf
            },
            true,
            true,
        ),
        (
            format!("{}×{} box (dense operator)", r.config.size, r.config.size),
            Style {
                marker: crate::plot::style::Marker::Square,
                ..series_style(1, Dash::Dashed)
            },
            true,
            false,
        ),
        (
            "sphstab Swegle run, measured".to_string(),
            series_style(2, Dash::Solid),
            false,
            true,
        ),
    ];
    if !r.compare_label.is_empty() {
        v.push((
            format!("{} Swegle run, measured", r.compare_label),
            Style {
                filled: false,
                ..series_style(3, Dash::Solid)
            },
            false,
            true,
        ));
    }
    v
}

/// The figure: one panel per (h, f) (rows h, columns f), growth rate against ε.
pub fn figure_svg(r: &ArtStressReport) -> Result<String> {
    use plotters::prelude::*;
    use plotters::style::text_anchor::{HPos, VPos};
    let cols = r.config.density_ratio.len().max(1);
    let rows = r.cases.len().div_ceil(cols).max(1);
    let leg = legend(r);
    let legend_w = 60.0 + leg.iter().map(|l| text_width(&l.0, 13)).fold(0.0, f64::max);
    let width = PANEL_W * cols as f64 + 30.0 + legend_w;
    let title = format!(
        "Artificial stress against the Swegle growth: {} {}, zero-shear material in tension, ε of R = −ε σ⁺/ρ² (n = {}); {} boundary density",
        r.config.form,
        r.config.kernel,
        r.config.art_n,
        match r.config.boundary_density {
            BoundaryDensity::Frozen => "frozen",
            BoundaryDensity::Evolve => "evolving",
        }
    );
    let lines = wrap(&title, ((width - 40.0) / (0.56 * 18.0)) as usize);
    let th = 16.0 + 23.0 * lines.len() as f64;
    let height = th + PANEL_H * rows as f64 + 5.0;
    let xs: Vec<f64> = r
        .cases
        .iter()
        .flat_map(|c| {
            c.points
                .iter()
                .map(|p| p.eps)
                .chain(c.runs.iter().map(|p| p.eps))
                .chain(c.compare.iter().map(|p| p.eps))
        })
        .collect();
    let xmax = xs.iter().copied().fold(0.0f64, f64::max);
    let xmax = if xmax > 0.0 { xmax } else { 1.0 };
    let x_scale = Scale::Linear(-0.02 * xmax, 1.03 * xmax);
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (width as u32, height as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        for (k, line) in lines.iter().enumerate() {
            text_at(
                &root,
                line,
                (width / 2.0, 10.0 + 23.0 * k as f64),
                18,
                (HPos::Center, VPos::Top),
                false,
            )?;
        }
        for (ci, case) in r.cases.iter().enumerate() {
            let (row, col) = (ci / cols, ci % cols);
            let ys: Vec<f64> = case
                .points
                .iter()
                .flat_map(|p| [p.infinite, p.in_box])
                .chain(case.runs.iter().filter_map(|p| p.measured))
                .chain(case.compare.iter().filter_map(|p| p.measured))
                .collect();
            let yr = auto_range(&[&ys], true);
            let top = if yr.hi > 0.0 { yr.hi } else { 1.0 };
            let (cx, cy) = (col as f64 * PANEL_W, th + row as f64 * PANEL_H);
            let frame = Frame {
                rect: (
                    cx + 78.0,
                    cy + 26.0,
                    cx + PANEL_W - 14.0,
                    cy + PANEL_H - 58.0,
                ),
                x: x_scale,
                y: Scale::Linear(-0.02 * top, 1.06 * top),
                grid: true,
            };
            text_at(
                &root,
                &format!(
                    "h = {}Δx, f = {} (σ̄ = {})",
                    case.h,
                    case.density_ratio,
                    trim(case.sigma_bar)
                ),
                ((frame.rect.0 + frame.rect.2) / 2.0, frame.rect.1 - 5.0),
                14,
                (HPos::Center, VPos::Bottom),
                false,
            )?;
            frame.draw(
                &root,
                &format!("artificial-stress ε (n = {})", r.config.art_n),
                "growth rate γ (c/Δx)",
                None,
            )?;
            let px = |x: f64, y: f64| frame.map(x, y);
            // infinite lattice: one line, markers filled where the fastest mode is longitudinal
            let line: Vec<(f64, f64)> = case.points.iter().map(|p| px(p.eps, p.infinite)).collect();
            draw_line(&root, &line, &leg[0].1)?;
            for p in &case.points {
                let s = if p.longitudinal >= 0.5 {
                    &leg[0].1
                } else {
                    &leg[1].1
                };
                draw_marker(&root, px(p.eps, p.infinite), s)?;
            }
            let boxline: Vec<(f64, f64)> =
                case.points.iter().map(|p| px(p.eps, p.in_box)).collect();
            draw_line(&root, &boxline, &leg[2].1)?;
            // the compared code's hollow markers first, sphstab's filled ones on top (they
            // coincide when the codes agree; the legend then says so)
            if leg.len() > 4 {
                for p in &case.compare {
                    if let Some(m) = p.measured {
                        draw_marker(&root, px(p.eps, m), &leg[4].1)?;
                    }
                }
            }
            for p in &case.runs {
                if let Some(m) = p.measured {
                    draw_marker(&root, px(p.eps, m), &leg[3].1)?;
                }
            }
            // runs that did not grow into the fit window, named under the panel
            let silent: Vec<String> = case
                .runs
                .iter()
                .filter(|p| p.measured.is_none())
                .map(|p| trim(p.eps))
                .collect();
            if !silent.is_empty() {
                text(
                    &root,
                    &format!("no growth measured at ε = {}", silent.join(", ")),
                    (frame.rect.0, frame.rect.3 + 34.0),
                    11,
                    GREY,
                )?;
            }
        }
        let (lx, top) = (PANEL_W * cols as f64 + 20.0, th + 26.0);
        let mut y = top + 6.0;
        let agree = max_relative_difference(r);
        for (i, (label, style, line, marker)) in leg.iter().enumerate() {
            draw_sample(&root, (lx, y + 7.0), 36.0, style, *line, *marker)?;
            if i == 4 {
                // sphstab's marker inside, as in the panels
                draw_marker(&root, (lx + 18.0, y + 7.0), &leg[3].1)?;
            }
            text(&root, label, (lx + 44.0, y), 13, BLACK)?;
            y += 22.0;
            if let (4, Some(d)) = (i, agree) {
                for line in [
                    "coincides with sphstab's runs (▲ inside ◇):".to_string(),
                    format!("max relative difference {d:.1e}"),
                ] {
                    text(&root, &line, (lx + 44.0, y - 5.0), 11, GREY)?;
                    y += 13.0;
                }
            }
        }
        root.draw(&Rectangle::new(
            [
                ((lx - 8.0) as i32, top as i32),
                ((lx + legend_w) as i32, (y + 4.0) as i32),
            ],
            GREY.stroke_width(1),
        ))
        .map_err(plot_err)?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}

/// The largest relative difference between the compared code's measured rates and sphstab's
/// runs at the same (h, f, ε); None without common points.
pub fn max_relative_difference(r: &ArtStressReport) -> Option<f64> {
    let mut d: Option<f64> = None;
    for case in &r.cases {
        for c in &case.compare {
            let run = case.runs.iter().find(|p| close(p.eps, c.eps));
            if let (Some(a), Some(b)) = (c.measured, run.and_then(|p| p.measured)) {
                let x = (a - b).abs() / b.abs();
                d = Some(d.map_or(x, |y| y.max(x)));
            }
        }
    }
    d
}

/// A number without trailing zeros (0.05, not 0.050000000000000044).
fn trim(v: f64) -> String {
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Reads the stored PySPH measurements (`analysis/pysph/results-art-stress.json`, written by
/// `analysis/pysph/swegle_art_stress.py`): `pysph_version` and `runs[]` with `h`,
/// `density_ratio`, `art_eps` and `pysph.growth_rate` (null: nothing grew into the window).
pub fn comparison_from_pysph(file: &str, text: &str) -> Result<Comparison> {
    let bad = |msg: String| Error::Config {
        file: file.into(),
        msg,
    };
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| bad(e.to_string()))?;
    let version = v["pysph_version"].as_str().unwrap_or("?");
    let runs = v["runs"]
        .as_array()
        .ok_or_else(|| bad("`runs` must be an array".into()))?;
    let mut points = Vec::with_capacity(runs.len());
    for (i, r) in runs.iter().enumerate() {
        let num = |k: &str| {
            r[k].as_f64()
                .ok_or_else(|| bad(format!("runs[{i}].{k} must be a number")))
        };
        let g = &r["pysph"]["growth_rate"];
        let rate = if g.is_null() {
            None
        } else {
            Some(g.as_f64().filter(|x| x.is_finite()).ok_or_else(|| {
                bad(format!(
                    "runs[{i}].pysph.growth_rate must be a number or null"
                ))
            })?)
        };
        points.push((num("h")?, num("density_ratio")?, num("art_eps")?, rate));
    }
    Ok(Comparison {
        label: format!("PySPH {version}"),
        points,
    })
}
