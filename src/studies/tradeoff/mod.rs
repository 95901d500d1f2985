//! The speed/accuracy trade-off study (`sphstab tradeoff`): for every form × kernel × h/Δx on a
//! grid, what a configuration costs and what it buys, measured in one run on one machine.
//!
//! | column | how it is obtained |
//! |---|---|
//! | `ns_per_particle_step` | wall time of the wave scene below (the real solver, same rate function), median of `repeats` runs, divided by particles × steps |
//! | `neighbours_per_particle` | masters within the support radius R of a master (reference lattice, self excluded) |
//! | `bytes_per_particle` | peak heap bytes while building and running the scene, above the level before, per particle (needs a counting allocator: [`MemoryProbe`]; `None` without one) |
//! | `phase_error_10ppw`, `_20ppw` | \|c_num/c − 1\| at κΔx = 2π/10, 2π/20 from the engine's ω²(κ) at σ̄ = 0 (2D: the longitudinal branch along x) |
//! | `wave_l2_error` | relative L2 error of the particle velocities of a standing wave v = V sin(kx) cos(ωt) (20 points per wavelength, periodic, Δt = 0.2 Δx/c, t = 2⅛ periods) against the continuum solution |
//! | `max_stable_tension` | largest σ̄ ≤ 0.999 (2D hydro: ≤ 0.95) up to which no mode grows (scan, then bisection to 1e-3 relative); 0 if a mode grows at σ̄ = 1e-6 |
//! | `stable_in_compression` | no growing mode at σ̄ = −0.01 |
//! | `critical_dt` | critical leapfrog Δt c/Δx at σ̄ = 0 from the amplification matrices (the critical CFL number in Δx) |
//! | `ns_per_particle_time` | ns_per_particle_step / critical_dt: the cost of advancing one particle by Δx/c at the largest stable step |
//!
//! With `integrators` (1D only) the report gains `integrator_rows`: the integrator as a
//! dimension of the study, one row per configuration × integrator ([`integrators`]).
//! `sphstab tradeoff --cfl-table` prints the critical CFL table ([`cfl`]).
//!
//! The 1D grid covers the ten 1D forms, the 2D grid the six 2D forms (square lattice, hydro
//! material p = K(ρ/ρ0 − 1), as in the Swegle test). A configuration the engine rejects (e.g. an
//! MLS support that does not cover enough neighbours) is reported with its error, not dropped.

use crate::analysis::Query1D;
use crate::analysis::{MaterialSpec, Query2D};
use crate::error::{Error, Result};
use crate::forms::{FormKind, Model1D, Model2D};
use crate::integrator::{DEFAULT_EULER_EVERY, Integrator};
use crate::kernel::{self, Kernel};
use crate::lattice::Lattice2D;
use crate::studies::throughput::MemoryProbe;
use crate::solver::{BoundaryDensity, Run1D, Run2D};
use crate::vonneumann::amplification::{critical_dt, critical_dt_bisection};
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::linearise::Linearisation;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

pub mod cfl;
pub mod integrators;

pub use integrators::IntegratorRow;

/// What to sweep.
#[derive(Clone, Debug, Deserialize, Serialize)]
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
        }
    }
}

/// One configuration's measurements (see the module table).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct Row {
    /// Form.
    pub form: String,
    /// Kernel.
    pub kernel: String,
    /// Shape family.
    pub shape: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// R/Δx.
    pub support_over_dx: f64,
    /// Solver cost (ns per particle per step).
    pub ns_per_particle_step: Option<f64>,
    /// Masters within R.
    pub neighbours_per_particle: Option<f64>,
    /// Peak heap bytes per particle.
    pub bytes_per_particle: Option<f64>,
    /// |c_num/c − 1| at 10 points per wavelength.
    pub phase_error_10ppw: Option<f64>,
    /// |c_num/c − 1| at 20 points per wavelength.
    pub phase_error_20ppw: Option<f64>,
    /// Relative L2 velocity error of the standing-wave scene.
    pub wave_l2_error: Option<f64>,
    /// Largest tensile σ̄ that stays stable.
    pub max_stable_tension: Option<f64>,
    /// Stable at σ̄ = −0.01.
    pub stable_in_compression: Option<bool>,
    /// Critical leapfrog Δt (Δx/c) at σ̄ = 0.
    pub critical_dt: Option<f64>,
    /// ns per particle per Δx/c of simulated time at the critical step.
    pub ns_per_particle_time: Option<f64>,
    /// Why the configuration could not be analysed or run.
    pub error: Option<String>,
}

impl Row {
    /// Stable at ±1% stress: the filled markers of the Pareto figure.
    pub fn stable_at_one_percent(&self) -> bool {
        self.max_stable_tension.is_some_and(|s| s >= 0.01)
            && self.stable_in_compression == Some(true)
    }
}

/// The whole study.
#[derive(Clone, Debug, Deserialize, Serialize)]
pub struct TradeoffReport {
    /// Dimension.
    pub dim: u8,
    /// Worker threads of the analysis part.
    pub threads: usize,
    /// Wall-clock seconds of the study.
    pub runtime_s: f64,
    /// The wave scene.
    pub scene: String,
    /// One row per configuration.
    pub rows: Vec<Row>,
    /// One row per configuration × integrator (only when integrators were asked for).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub integrator_rows: Vec<IntegratorRow>,
}

/// σ̄ candidates of the tension scan (the first unstable one is refined by bisection).
const TENSION_SCAN: [f64; 12] = [
    1e-6, 1e-4, 1e-3, 1e-2, 0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 0.95, 0.999,
];
/// Bisection steps after the scan.
const BISECTION_STEPS: usize = 10;
/// Points per wavelength of the standing-wave scene.
const SCENE_PPW: usize = 20;
/// Time step of the scene in Δx/c.
const SCENE_DT: f64 = 0.2;
/// Scene length in periods.
const SCENE_PERIODS: f64 = 2.125;
/// Velocity amplitude of the scene in c (linear regime).
const SCENE_AMPLITUDE: f64 = 1e-6;
/// 1D scene: particles of the periodic chain.
const SCENE_1D_N: usize = 200;
/// 2D scene: periodic strip (along x, across y).
const SCENE_2D_N: [usize; 2] = [60, 20];
/// κ points of the 1D stability checks.
const KAPPAS_1D: usize = 256;
/// Wave vectors per direction of the 2D stability checks.
const GRID_2D: usize = 16;

/// The description of the wave scene written into the report.
pub fn scene_description(dim: u8) -> String {
    let (n, what) = if dim == 1 {
        (format!("{SCENE_1D_N}"), "periodic chain")
    } else {
        (
            format!("{}×{}", SCENE_2D_N[0], SCENE_2D_N[1]),
            "periodic strip, hydro",
        )
    };
    format!(
        "standing wave v = V sin(kx) cos(ωt), {SCENE_PPW} points per wavelength, {n} particles ({what}), Δt = {SCENE_DT} Δx/c, t = {SCENE_PERIODS} periods, V = {SCENE_AMPLITUDE} c"
    )
}

/// The configurations of a study, validated (unknown names are errors).
pub fn grid(cfg: &TradeoffConfig) -> Result<Vec<(FormKind, &'static dyn Kernel, f64)>> {
    if cfg.dim != 1 && cfg.dim != 2 {
        return Err(Error::OutOfRange {
            name: "--dim",
            value: cfg.dim as f64,
            range: "must be 1 or 2".into(),
        });
    }
    if cfg.h_points == 0 || cfg.h_points > 64 {
        return Err(Error::OutOfRange {
            name: "--h-points",
            value: cfg.h_points as f64,
            range: "must be an integer in [1, 64]".into(),
        });
    }
    crate::studies::config::check_output("tradeoff config", cfg.output.as_deref())?;
    if cfg.repeats == 0 || cfg.repeats > 100 {
        return Err(Error::OutOfRange {
            name: "--repeats",
            value: cfg.repeats as f64,
            range: "must be an integer in [1, 100]".into(),
        });
    }
    integrator_list(cfg)?;
    crate::error::check_range("--safety", cfg.safety, 0.0, 1.0, false, true)?;
    let forms: Vec<FormKind> = if cfg.forms.is_empty() {
        FormKind::ALL
            .iter()
            .map(|f| f.0)
            .filter(|f| cfg.dim == 1 || f.in_2d())
            .collect()
    } else {
        let mut v = Vec::new();
        for name in &cfg.forms {
            let f = FormKind::by_name(name)?;
            if cfg.dim == 2 && !f.in_2d() {
                return Err(Error::Incompatible(format!(
                    "--forms: {name} is not available with --dim 2 (classical, nonlocal, local, lnl, cll, total-lagrangian)"
                )));
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
    if !out.is_empty() && cfg.dim != 1 {
        return Err(Error::Incompatible(
            "--integrators: the integrator dimension is 1D only (use --dim 1)".into(),
        ));
    }
    Ok(out)
}

/// Masters within the support radius (self excluded) on the reference lattice.
fn neighbours(dim: u8, support: f64) -> f64 {
    let m = support.ceil() as i64 + 1;
    let mut n = 0usize;
    if dim == 1 {
        for i in -m..=m {
            if i != 0 && (i as f64).abs() < support {
                n += 1;
            }
        }
    } else {
        for i in -m..=m {
            for j in -m..=m {
                if (i, j) != (0, 0) && (i as f64).hypot(j as f64) < support {
                    n += 1;
                }
            }
        }
    }
    n as f64
}

/// Largest σ̄ ≤ `cap` up to which `grows(σ̄)` stays false: scan, then bisection.
fn max_stable(cap: f64, grows: impl Fn(f64) -> Result<bool>) -> Result<f64> {
    Ok(tension_limit(cap, BISECTION_STEPS, 0.0, grows)?.0)
}

/// The tension limit of `grows`: scan the σ̄ of [`TENSION_SCAN`] up to `cap`; at the first one
/// that grows, `steps` bisections between it and the last stable one — or, when the first scan
/// value (1e-6) already grows, between `floor` (a σ̄ the caller found stable) and it; with
/// `floor` = 0 no bisection then. Returns (the largest σ̄ found stable, 0 if 1e-6 grows and
/// `floor` = 0; the smallest σ̄ found growing, `None` if nothing up to `cap` grows). The bracket
/// after `steps` bisections is (hi − lo) = (scan gap)/2^steps.
pub(crate) fn tension_limit(
    cap: f64,
    steps: usize,
    floor: f64,
    grows: impl Fn(f64) -> Result<bool>,
) -> Result<(f64, Option<f64>)> {
    let mut last_stable = floor;
    for &s in TENSION_SCAN.iter().filter(|&&s| s <= cap) {
        if grows(s)? {
            if last_stable == 0.0 {
                return Ok((0.0, Some(s)));
            }
            let (mut lo, mut hi) = (last_stable, s);
            for _ in 0..steps {
                let mid = 0.5 * (lo + hi);
                if grows(mid)? {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return Ok((lo, Some(hi)));
        }
        last_stable = s;
    }
    Ok((last_stable, None))
}

/// The engine's part of a row (no timing): phase errors, stability, critical Δt.
fn analyse(dim: u8, form: FormKind, k: &'static dyn Kernel, h: f64, row: &mut Row) -> Result<()> {
    let phase = |w2: f64, kap: f64, c: f64| (w2.max(0.0).sqrt() / kap / c - 1.0).abs();
    let (k10, k20) = (2.0 * PI / 10.0, 2.0 * PI / 20.0);
    if dim == 1 {
        let mut q = Query1D::new(form, k, h, 0.0);
        q.points = KAPPAS_1D;
        q.validate()?;
        let kappas = q.kappas();
        let lin0 = q.linearise()?;
        row.phase_error_10ppw = Some(phase(lin0.omega2(k10).0, k10, 1.0));
        row.phase_error_20ppw = Some(phase(lin0.omega2(k20).0, k20, 1.0));
        let grows = |s: f64| -> Result<bool> {
            let lin = Linearisation::new(q.params(s), q.lattice)?;
            for &kap in &kappas {
                if lin.growth(kap)? > GROWTH_TOL {
                    return Ok(true);
                }
            }
            Ok(false)
        };
        let g0 = grows(0.0)?;
        row.critical_dt = if g0 {
            None
        } else {
            Some(critical_dt(&lin0, &kappas)?)
        };
        row.max_stable_tension = Some(if g0 { 0.0 } else { max_stable(0.999, grows)? });
        row.stable_in_compression = Some(!grows(-0.01)?);
    } else {
        let mut q = Query2D::new(form, k, h, 0.0);
        q.material = MaterialSpec::Hydro;
        q.grid = GRID_2D;
        q.validate()?;
        let ks = q.kgrid();
        let lin0 = q.linearise_at(0.0)?;
        let long = |kap: f64| -> f64 {
            lin0.branches([kap, 0.0])
                .iter()
                .map(|b| b.0.re)
                .fold(f64::NEG_INFINITY, f64::max)
        };
        row.phase_error_10ppw = Some(phase(long(k10), k10, 1.0));
        row.phase_error_20ppw = Some(phase(long(k20), k20, 1.0));
        let grows = |s: f64| -> Result<bool> {
            let lin = q.linearise_at(s)?;
            for &kv in &ks {
                if lin.growth(kv)?.0 > GROWTH_TOL {
                    return Ok(true);
                }
            }
            Ok(false)
        };
        let g0 = grows(0.0)?;
        row.critical_dt = if g0 {
            None
        } else {
            Some(critical_dt_bisection(&lin0, &ks)?)
        };
        row.max_stable_tension = Some(if g0 { 0.0 } else { max_stable(0.95, grows)? });
        row.stable_in_compression = Some(!grows(-0.01)?);
    }
    Ok(())
}

/// Result of one scene run: relative L2 error, particles × steps, peak bytes above baseline.
struct SceneRun {
    l2: f64,
    particle_steps: f64,
    seconds: f64,
    bytes: Option<usize>,
    particles: usize,
}

/// Measures peak heap above the current level while `f` runs.
fn with_memory<T>(probe: Option<&dyn MemoryProbe>, f: impl FnOnce() -> T) -> (T, Option<usize>) {
    let base = probe.map(|p| {
        p.reset_peak();
        p.current()
    });
    let out = f();
    let bytes = probe.zip(base).map(|(p, b)| p.peak().saturating_sub(b));
    (out, bytes)
}

fn relative_l2(num: f64, den: f64) -> f64 {
    (num / den.max(1e-300)).sqrt()
}

/// The standing-wave scene in 1D: periodic chain, the form's own solver.
fn scene_1d(
    form: FormKind,
    k: &'static dyn Kernel,
    h: f64,
    probe: Option<&dyn MemoryProbe>,
) -> Result<SceneRun> {
    scene_1d_with(form, k, h, probe, Integrator::Kdk, SCENE_DT, false).map(|s| s.0)
}

/// Steps of the wave scene (2⅛ periods at Δt = 0.2 Δx/c).
fn scene_steps() -> usize {
    let period = SCENE_PPW as f64; // 2π/(c k) with c = Δx = 1
    (SCENE_PERIODS * period / SCENE_DT).round() as usize
}

/// The 1D wave scene stepped by `integ` with step `dt` (the scene's number of steps whatever
/// `dt`); with `count`, also the rate calls per step counted on the same system
/// ([`integrators::rate_calls_per_step`], before the timed loop; 0 without).
fn scene_1d_with(
    form: FormKind,
    k: &'static dyn Kernel,
    h: f64,
    probe: Option<&dyn MemoryProbe>,
    integ: Integrator,
    dt: f64,
    count: bool,
) -> Result<(SceneRun, f64)> {
    let n = SCENE_1D_N;
    let kw = 2.0 * PI / SCENE_PPW as f64;
    let steps = scene_steps();
    let mut calls = 0.0;
    let (res, bytes) = with_memory(probe, || -> Result<(f64, f64)> {
        let q = Query1D::new(form, k, h, 0.0);
        let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let model = Model1D::new(q.params(0.0), x.clone(), vec![1.0; n], Some(n as f64))?;
        let mut z = model.rest_state();
        for (v, &xi) in z.v.iter_mut().zip(&x) {
            *v = SCENE_AMPLITUDE * (kw * xi).sin();
        }
        if count {
            calls = integrators::rate_calls_per_step(&model, &z, integ, dt)?;
        }
        let mut run = Run1D::new(model, z, vec![None; n])?;
        run.set_integrator(integ);
        let start = std::time::Instant::now();
        for _ in 0..steps {
            run.step(dt)?;
        }
        let secs = start.elapsed().as_secs_f64();
        let ct = (kw * run.t).cos();
        let (mut num, mut den) = (0.0, 0.0);
        for (v, &xi) in run.z.v.iter().zip(&x) {
            let e = SCENE_AMPLITUDE * (kw * xi).sin() * ct;
            num += (v - e).powi(2);
            den += e * e;
        }
        Ok((relative_l2(num, den), secs))
    });
    let (l2, seconds) = res?;
    Ok((
        SceneRun {
            l2,
            particle_steps: (n * steps) as f64,
            seconds,
            bytes,
            particles: n,
        },
        calls,
    ))
}

/// The standing-wave scene in 2D: periodic strip, hydro, plane wave along x.
fn scene_2d(
    form: FormKind,
    k: &'static dyn Kernel,
    h: f64,
    probe: Option<&dyn MemoryProbe>,
) -> Result<SceneRun> {
    let [nx, ny] = SCENE_2D_N;
    let kw = 2.0 * PI / SCENE_PPW as f64;
    let period = SCENE_PPW as f64;
    let t_end = SCENE_PERIODS * period;
    let steps = (t_end / SCENE_DT).round() as usize;
    let (res, bytes) = with_memory(probe, || -> Result<(f64, f64)> {
        let mut q = Query2D::new(form, k, h, 0.0);
        q.material = MaterialSpec::Hydro;
        let model = Model2D::periodic_patch(
            q.params()?,
            &Lattice2D::square(1.0)?,
            1.0,
            [nx, ny],
            1.0,
            0.0,
        )?;
        let mut z = model.rest_state(1.0);
        let x0 = z.x.clone();
        for (v, p) in z.v.iter_mut().zip(&x0) {
            v[0] = SCENE_AMPLITUDE * (kw * p[0]).sin();
        }
        let n = z.x.len();
        let mut run = Run2D::new(model, z, vec![false; n], BoundaryDensity::Evolve)?;
        let start = std::time::Instant::now();
        for _ in 0..steps {
            run.step(SCENE_DT)?;
        }
        let secs = start.elapsed().as_secs_f64();
        let ct = (kw * run.t).cos();
        let (mut num, mut den) = (0.0, 0.0);
        for (v, p) in run.z.v.iter().zip(&x0) {
            let e = SCENE_AMPLITUDE * (kw * p[0]).sin() * ct;
            num += (v[0] - e).powi(2) + v[1].powi(2);
            den += e * e;
        }
        Ok((relative_l2(num, den), secs))
    });
    let (l2, seconds) = res?;
    Ok(SceneRun {
        l2,
        particle_steps: (nx * ny * steps) as f64,
        seconds,
        bytes,
        particles: nx * ny,
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Runs the study. `progress(done, total)` is called as configurations finish. The engine part
/// runs in parallel (rayon); the timed scene runs one at a time so they do not compete.
pub fn run(
    cfg: &TradeoffConfig,
    probe: Option<&dyn MemoryProbe>,
    progress: impl Fn(usize, usize) + Sync,
) -> Result<TradeoffReport> {
    let configs = grid(cfg)?;
    let integs = integrator_list(cfg)?;
    let start = std::time::Instant::now();
    let total = 2 * configs.len() * (1 + integs.len());
    let done = std::sync::atomic::AtomicUsize::new(0);
    let mut rows: Vec<Row> = configs
        .par_iter()
        .map(|&(form, k, h)| {
            let shape = if cfg.dim == 1 {
                form.default_shape()
            } else {
                form.default_shape_2d()
            };
            let mut row = Row {
                form: form.name().into(),
                kernel: k.name().into(),
                shape: shape.name().into(),
                h_over_dx: h,
                support_over_dx: k.zeta() * h,
                ns_per_particle_step: None,
                neighbours_per_particle: Some(neighbours(cfg.dim, k.zeta() * h)),
                bytes_per_particle: None,
                phase_error_10ppw: None,
                phase_error_20ppw: None,
                wave_l2_error: None,
                max_stable_tension: None,
                stable_in_compression: None,
                critical_dt: None,
                ns_per_particle_time: None,
                error: None,
            };
            if let Err(e) = analyse(cfg.dim, form, k, h, &mut row) {
                row.error = Some(e.to_string());
            }
            let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(d, total);
            row
        })
        .collect();
    for (row, &(form, k, h)) in rows.iter_mut().zip(&configs) {
        if row.error.is_none() {
            let mut times = Vec::with_capacity(cfg.repeats);
            for r in 0..cfg.repeats {
                let res = if cfg.dim == 1 {
                    scene_1d(form, k, h, if r == 0 { probe } else { None })
                } else {
                    scene_2d(form, k, h, if r == 0 { probe } else { None })
                };
                match res {
                    Ok(s) => {
                        if r == 0 {
                            row.wave_l2_error = Some(s.l2);
                            row.bytes_per_particle = s.bytes.map(|b| b as f64 / s.particles as f64);
                        }
                        times.push(s.seconds * 1e9 / s.particle_steps);
                    }
                    Err(e) => {
                        row.error = Some(format!("wave scene: {e}"));
                        break;
                    }
                }
            }
            if row.error.is_none() {
                let ns = median(times);
                row.ns_per_particle_step = Some(ns);
                row.ns_per_particle_time = row.critical_dt.map(|dt| ns / dt);
            }
        }
        let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        progress(d, total);
    }
    let integrator_rows = integrator_rows(cfg, &configs, &integs, &done, total, &progress);
    Ok(TradeoffReport {
        dim: cfg.dim,
        threads: rayon::current_num_threads(),
        runtime_s: start.elapsed().as_secs_f64(),
        scene: scene_description(cfg.dim),
        rows,
        integrator_rows,
    })
}

/// The integrator dimension ([`integrators`]): the engine part in parallel, then the timed
/// scenes one at a time.
fn integrator_rows(
    cfg: &TradeoffConfig,
    configs: &[(FormKind, &'static dyn Kernel, f64)],
    integs: &[Integrator],
    done: &std::sync::atomic::AtomicUsize,
    total: usize,
    progress: &(impl Fn(usize, usize) + Sync),
) -> Vec<IntegratorRow> {
    let tick = || {
        let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        progress(d, total);
    };
    let jobs: Vec<(FormKind, &'static dyn Kernel, f64, Integrator)> = configs
        .iter()
        .flat_map(|&(f, k, h)| integs.iter().map(move |&i| (f, k, h, i)))
        .collect();
    let mut rows: Vec<IntegratorRow> = jobs
        .par_iter()
        .map(|&(form, k, h, integ)| {
            let mut row = IntegratorRow {
                form: form.name().into(),
                kernel: k.name().into(),
                shape: form.default_shape().name().into(),
                h_over_dx: h,
                integrator: integ.name().into(),
                euler_every: match integ {
                    Integrator::VerletEuler { every } => Some(every),
                    _ => None,
                },
                order: integ.order(),
                critical_dt: None,
                weak: false,
                weak_growth_rate: None,
                dt_rule: None,
                dt_used: None,
                evaluations_per_step: 0,
                rate_calls_per_step: None,
                ns_per_particle_step: None,
                ns_per_evaluation: None,
                ns_per_particle_time: None,
                phase_error_10ppw: None,
                amplitude_error_10ppw: None,
                phase_error_20ppw: None,
                amplitude_error_20ppw: None,
                error: None,
            };
            let res = integrators::analyse(form, k, h, integ, cfg.safety, KAPPAS_1D, &mut row)
                .and_then(|()| {
                    let q = Query1D::new(form, k, h, 0.0);
                    let x: Vec<f64> = (0..SCENE_1D_N).map(|i| i as f64).collect();
                    let model = Model1D::new(
                        q.params(0.0),
                        x,
                        vec![1.0; SCENE_1D_N],
                        Some(SCENE_1D_N as f64),
                    )?;
                    row.evaluations_per_step = integrators::evaluations_per_step(&model, integ)?;
                    Ok(())
                });
            if let Err(e) = res {
                row.error = Some(e.to_string());
            }
            tick();
            row
        })
        .collect();
    for (row, &(form, k, h, integ)) in rows.iter_mut().zip(&jobs) {
        if row.error.is_none() {
            let dt = row.dt_used.map_or(SCENE_DT, |d| d.min(SCENE_DT));
            let mut times = Vec::with_capacity(cfg.repeats);
            for r in 0..cfg.repeats {
                match scene_1d_with(form, k, h, None, integ, dt, r == 0) {
                    Ok((s, calls)) => {
                        if r == 0 {
                            row.rate_calls_per_step = Some(calls);
                        }
                        times.push(s.seconds * 1e9 / s.particle_steps);
                    }
                    Err(e) => {
                        row.error = Some(format!("wave scene: {e}"));
                        break;
                    }
                }
            }
            if row.error.is_none() {
                let ns = median(times);
                row.ns_per_particle_step = Some(ns);
                row.ns_per_evaluation =
                    row.rate_calls_per_step.filter(|&c| c > 0.0).map(|c| ns / c);
                row.ns_per_particle_time = row.dt_used.map(|dt| ns / dt);
            }
        }
        tick();
    }
    rows
}

fn fmt_opt(v: Option<f64>, prec: usize) -> String {
    match v {
        Some(x) if x.abs() >= 1e4 || (x != 0.0 && x.abs() < 1e-3) => format!("{x:.prec$e}"),
        Some(x) => format!("{x:.prec$}"),
        None => "-".into(),
    }
}

/// The table printed by `sphstab tradeoff`.
pub fn table(rep: &TradeoffReport) -> String {
    let mut s = format!(
        "{:<24} {:<12} {:>5} {:>5} {:>8} {:>4} {:>7} {:>9} {:>9} {:>9} {:>8} {:>5} {:>7} {:>9}\n",
        "form",
        "kernel",
        "h/Δx",
        "R/Δx",
        "ns/p·st",
        "nb",
        "B/part",
        "phase@10",
        "phase@20",
        "L2 wave",
        "σ̄max+",
        "comp",
        "Δt_crit",
        "ns/p·Δx/c"
    );
    for r in &rep.rows {
        if let Some(e) = &r.error {
            s += &format!(
                "{:<24} {:<12} {:>5.2} {:>5.2} error: {e}\n",
                r.form, r.kernel, r.h_over_dx, r.support_over_dx
            );
            continue;
        }
        s += &format!(
            "{:<24} {:<12} {:>5.2} {:>5.2} {:>8} {:>4} {:>7} {:>9} {:>9} {:>9} {:>8} {:>5} {:>7} {:>9}\n",
            r.form,
            r.kernel,
            r.h_over_dx,
            r.support_over_dx,
            fmt_opt(r.ns_per_particle_step, 0),
            fmt_opt(r.neighbours_per_particle, 0),
            fmt_opt(r.bytes_per_particle, 0),
            fmt_opt(r.phase_error_10ppw, 2),
            fmt_opt(r.phase_error_20ppw, 2),
            fmt_opt(r.wave_l2_error, 2),
            fmt_opt(r.max_stable_tension, 3),
            match r.stable_in_compression {
                Some(true) => "yes",
                Some(false) => "no",
                None => "-",
            },
            fmt_opt(r.critical_dt, 3),
            fmt_opt(r.ns_per_particle_time, 0),
        );
    }
    s
}

/// The Pareto figure: cost (ns per particle per Δx/c at the critical step) against the phase
/// error at 10 points per wavelength, log–log, one marker per configuration, filled when stable
/// at σ̄ = ±0.01, one colour per form; the Pareto front of the stable ones is drawn.
pub fn pareto_svg(rep: &TradeoffReport, title: &str) -> Result<String> {
    let pts: Vec<(String, f64, f64, bool)> = rep
        .rows
        .iter()
        .filter_map(|r| {
            let x = r.ns_per_particle_time?;
            let y = r.phase_error_10ppw?;
            (x > 0.0 && y.is_finite())
                .then(|| (r.form.clone(), x, y.max(1e-6), r.stable_at_one_percent()))
        })
        .collect();
    crate::plot::pareto_svg(
        title,
        "cost: ns per particle per Δx/c of simulated time (at Δt_crit)",
        "phase-velocity error |c_num/c − 1| at 10 ppw (dimensionless)",
        &pts,
        (
            "filled: stable at σ̄ = ±0.01",
            "hollow: unstable at σ̄ = +0.01 or −0.01",
        ),
    )
}

/// The table of the integrator rows printed by `sphstab tradeoff --integrators …`.
pub fn integrator_table(rep: &TradeoffReport) -> String {
    let mut s = format!(
        "{:<18} {:<12} {:>5} {:<20} {:>8} {:>8} {:>8} {:>4} {:>5} {:>7} {:>6} {:>9} {:>10} {:>10} {:>10} {:>10}\n",
        "form",
        "kernel",
        "h/Δx",
        "integrator",
        "Δt_crit",
        "weak γ",
        "Δt_used",
        "eval",
        "calls",
        "ns/p·st",
        "ns/ev",
        "ns/p·Δx/c",
        "phase@10",
        "amp@10",
        "phase@20",
        "amp@20"
    );
    for r in &rep.integrator_rows {
        if let Some(e) = &r.error {
            s += &format!(
                "{:<18} {:<12} {:>5.2} {:<20} error: {e}\n",
                r.form, r.kernel, r.h_over_dx, r.integrator
            );
            continue;
        }
        s += &format!(
            "{:<18} {:<12} {:>5.2} {:<20} {:>8} {:>8} {:>8} {:>4} {:>5} {:>7} {:>6} {:>9} {:>10} {:>10} {:>10} {:>10}\n",
            r.form,
            r.kernel,
            r.h_over_dx,
            r.integrator,
            fmt_opt(r.critical_dt, 3),
            fmt_opt(r.weak_growth_rate, 1),
            fmt_opt(r.dt_used, 3),
            r.evaluations_per_step,
            fmt_opt(r.rate_calls_per_step, 0),
            fmt_opt(r.ns_per_particle_step, 0),
            fmt_opt(r.ns_per_evaluation, 0),
            fmt_opt(r.ns_per_particle_time, 0),
            fmt_opt(r.phase_error_10ppw, 2),
            fmt_opt(r.amplitude_error_10ppw, 2),
            fmt_opt(r.phase_error_20ppw, 2),
            fmt_opt(r.amplitude_error_20ppw, 2),
        );
    }
    s
}

/// The integrator figure: per form, cost per unit simulated time (ns per particle per Δx/c at
/// the Δt used) against |phase error| per wavelength travelled at 10 points per wavelength,
/// log–log, one marker per integrator, every kernel and h of the grid.
pub fn integrators_svg(rep: &TradeoffReport, title: &str) -> Result<String> {
    let mut names: Vec<&str> = Vec::new();
    let mut forms: Vec<&str> = Vec::new();
    for r in &rep.integrator_rows {
        if !names.contains(&r.integrator.as_str()) {
            names.push(&r.integrator);
        }
        if !forms.contains(&r.form.as_str()) {
            forms.push(&r.form);
        }
    }
    let panels: Vec<crate::plot::ScatterPanel> = forms
        .iter()
        .map(|f| crate::plot::ScatterPanel {
            title: (*f).to_string(),
            points: rep
                .integrator_rows
                .iter()
                .filter(|r| r.form == *f)
                .filter_map(|r| {
                    let i = names.iter().position(|n| *n == r.integrator)?;
                    Some((i, r.ns_per_particle_time?, r.phase_error_10ppw?.abs()))
                })
                .collect(),
        })
        .collect();
    let legend: Vec<String> = names.iter().map(|s| s.to_string()).collect();
    crate::plot::scatter_panels_svg(
        title,
        "ns per particle per Δx/c (at the Δt used)",
        "|phase error| per wavelength, 10 ppw (rad)",
        &legend,
        &panels,
    )
}

/// The figure of a report: [`integrators_svg`] when it has integrator rows, else [`pareto_svg`].
pub fn figure_svg(rep: &TradeoffReport, title: &str) -> Result<String> {
    if rep.integrator_rows.is_empty() {
        pareto_svg(rep, title)
    } else {
        integrators_svg(rep, title)
    }
}

/// Parses a study config; errors name the file and the field ([`crate::studies::config`]).
pub fn parse_config(file: &str, text: &str) -> Result<TradeoffConfig> {
    crate::studies::config::parse_json(file, text)
}
