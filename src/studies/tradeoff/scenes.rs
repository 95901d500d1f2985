//! The wave scene the trade-off study times and measures: a standing wave v = V sin(kx) cos(ωt)
//! (20 points per wavelength, periodic) run by the real solver, its cost, memory and L2 error.

use super::integrators;
use crate::analysis::{MaterialSpec, Query};
use crate::error::Result;
use crate::forms::{FormKind, Model};
use crate::integrator::Integrator;
use crate::kernel::Kernel;
use crate::lattice::Lattice;
use crate::solver::{BoundaryDensity, Run};
use crate::studies::throughput::MemoryProbe;
use std::f64::consts::PI;

/// Points per wavelength of the standing-wave scene.
const SCENE_PPW: usize = 20;
/// Time step of the scene in Δx/c.
pub(super) const SCENE_DT: f64 = 0.2;
/// Scene length in periods.
const SCENE_PERIODS: f64 = 2.125;
/// Velocity amplitude of the scene in c (linear regime).
const SCENE_AMPLITUDE: f64 = 1e-6;
/// 1D scene: particles of the periodic chain.
pub(super) const SCENE_1D_N: usize = 200;
/// 2D scene: periodic strip (along x, across y).
const SCENE_2D_N: [usize; 2] = [60, 20];
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

/// Result of one scene run: relative L2 error, particles × steps, peak bytes above baseline.
pub(super) struct SceneRun {
    /// Relative L2 error of the velocities against the continuum solution.
    pub(super) l2: f64,
    /// Particles × time steps of the run.
    pub(super) particle_steps: f64,
    /// Wall-clock seconds of the time loop.
    pub(super) seconds: f64,
    /// Peak heap bytes above the level before (with a [`MemoryProbe`]).
    pub(super) bytes: Option<usize>,
    /// Particles of the scene.
    pub(super) particles: usize,
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
pub(super) fn scene_1d(
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
pub(super) fn scene_1d_with(
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
        let q = Query::<1>::new(form, k, h, 0.0);
        let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let x_ref: Vec<[f64; 1]> = x.iter().map(|&xi| [xi]).collect();
        let model = Model::new(
            q.params()?,
            x_ref,
            vec![1.0; n],
            1.0,
            0.0,
            Some([[n as f64]]),
        )?;
        let mut z = model.rest_state(1.0);
        for (v, &xi) in z.v.iter_mut().zip(&x) {
            *v = [SCENE_AMPLITUDE * (kw * xi).sin()];
        }
        if count {
            calls = integrators::rate_calls_per_step(&model, &z, integ, dt)?;
        }
        let mut run = Run::with_prescribed(model, z, &vec![None; n])?;
        run.set_integrator(integ);
        let start = std::time::Instant::now();
        for _ in 0..steps {
            run.step(dt)?;
        }
        let secs = start.elapsed().as_secs_f64();
        let ct = (kw * run.t).cos();
        let (mut num, mut den) = (0.0, 0.0);
        for ([v], &xi) in run.z.v.iter().zip(&x) {
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
pub(super) fn scene_2d(
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
        let mut q = Query::<2>::new(form, k, h, 0.0);
        q.material = MaterialSpec::Hydro;
        let model = Model::<2>::periodic_patch(
            q.params()?,
            &Lattice::<2>::square(1.0)?,
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
        let mut run = Run::<2>::new(model, z, vec![false; n], BoundaryDensity::Evolve)?;
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

pub(super) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}
