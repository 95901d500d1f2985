//! Running the Swegle test: the time integration of the box, the growth fit of max |v| and the
//! dominant standing mode, next to the predictions.

use super::config::SwegleConfig;
use super::predict::predict_d;
use super::report::{Diverged, SwegleReport};
use crate::budget::fmt_count;
use crate::error::{Error, Result, fields};
use crate::forms::State;
use crate::progress::Progress;
use crate::solver::diagnostics::growth_fit;
use crate::solver::output::FinalState;
use crate::solver::run::Run;
use std::f64::consts::PI;

/// Runs the test in the configuration's dimension, telling `progress` the fraction of the
/// simulated time done.
pub fn run_swegle(cfg: &SwegleConfig, progress: impl Progress) -> Result<SwegleReport> {
    cfg.validate()?;
    match cfg.dim {
        3 => run_d::<3>(cfg, progress),
        _ => run_d::<2>(cfg, progress),
    }
}

/// |v| (hypot in 2D, as the 2D test always computed it).
fn speed<const D: usize>(v: &[f64; D]) -> f64 {
    if D == 2 {
        v[0].hypot(v[1])
    } else {
        v.iter().map(|c| c * c).sum::<f64>().sqrt()
    }
}

fn run_d<const D: usize>(cfg: &SwegleConfig, progress: impl Progress) -> Result<SwegleReport>
where
    FinalState: From<State<f64, D>>,
{
    let mut run = cfg.build::<D>()?;
    run.set_integrator(cfg.integrator);
    let c = cfg.sound_speed();
    let unit = c / cfg.dx; // c/Δx: normalisation of rates
    let nfree = cfg.size - 2 * cfg.layers;
    let pred = predict_d(cfg, &run, &progress)?;
    let (box_rate, method, inf) = (pred.box_rate, pred.box_method, pred.infinite_rate);
    let dt = cfg.dt_physical();
    let t_end = if cfg.until_window && box_rate > 1e-6 {
        cfg.t_end
            .max(1.5 * (cfg.window.1 / cfg.kick).ln() / (box_rate * unit))
    } else {
        cfg.t_end
    };
    if t_end > cfg.t_end {
        let steps = (t_end / dt).ceil();
        cfg.budget.steps(
            fields(&["until_window", "density_ratio"]),
            &format!(
                "running until the predicted mode (growth {box_rate:.3e} c/Δx) reaches the fit window ({} time steps)",
                fmt_count(steps)
            ),
            cfg.particles() as f64 * steps,
        )?;
    }
    let steps = (t_end / dt).ceil() as usize;
    let mut t = vec![0.0];
    let mut y = vec![run.max_free_speed().max(cfg.kick)];
    let mut vmax_ever: f64 = 0.0;
    let mut snapshot: Option<Vec<Vec<f64>>> = None;
    let centre = cfg.index([cfg.size / 2; D]);
    let mut full = Vec::with_capacity(steps + 1);
    let record = |run: &Run<D>, full: &mut Vec<[f64; 5]>| {
        let mut s2 = 0.0;
        let mut nf = 0usize;
        let mut ke = 0.0;
        for (i, v) in run.z.v.iter().enumerate() {
            let v2: f64 = v.iter().map(|c| c * c).sum();
            ke += 0.5 * run.model.mass[i] * v2;
            if !run.fixed[i] {
                s2 += v2;
                nf += 1;
            }
        }
        full.push([
            run.t,
            speed(&run.z.v[centre]),
            run.max_free_speed(),
            (s2 / nf.max(1) as f64).sqrt(),
            ke,
        ]);
    };
    record(&run, &mut full);
    // the velocity components of the free particles, row-major over the free block
    let free_fields = |run: &Run<D>| -> Vec<Vec<f64>> {
        let count = nfree.pow(D as u32);
        let mut f = vec![Vec::with_capacity(count); D];
        for k in 0..count {
            let c = SwegleConfig::coords::<D>(nfree, k).map(|ca| ca + cfg.layers);
            let v = run.z.v[cfg.index(c)];
            for (fa, va) in f.iter_mut().zip(v) {
                fa.push(va);
            }
        }
        f
    };
    let start = std::time::Instant::now();
    // stop at the first non-finite value or a runaway (max |v| above
    // crate::solver::scene::RUNAWAY_FACTOR × c); the growth fit uses what was recorded
    let runaway = crate::solver::scene::RUNAWAY_FACTOR * c;
    let mut diverged = None;
    for s in 0..steps {
        if run.step(dt).is_err() {
            diverged = Some(Diverged {
                step: s + 1,
                t: run.t + dt,
                what: "a non-finite velocity",
            });
            break;
        }
        let v = run.max_free_speed();
        if v > runaway {
            diverged = Some(Diverged {
                step: s + 1,
                t: run.t,
                what: "max |v| above 1000 × c",
            });
            break;
        }
        vmax_ever = vmax_ever.max(v);
        t.push(run.t);
        y.push(v);
        record(&run, &mut full);
        if snapshot.is_none() && v >= cfg.window.1 {
            snapshot = Some(free_fields(&run));
        }
        if s % 64 == 0 {
            progress.advance(run.t / t_end);
            if progress.cancelled() {
                return Err(Error::Cancelled);
            }
        }
        // beyond the window the perturbation is nonlinear; 1e3 × the window top is far enough
        if v > cfg.window.1 * 1e3 * unit * cfg.dx {
            break;
        }
    }
    let runtime_s = start.elapsed().as_secs_f64();
    let fields = snapshot.unwrap_or_else(|| free_fields(&run));
    let d = PI / (nfree as f64 + 1.0);
    let dominant = {
        let (m, share) = crate::solver::diagnostics::dominant_mode_nd(&fields, nfree, D);
        (share > 0.0).then(|| (m.iter().map(|&ma| ma as f64 * d).collect(), share))
    };
    let fit = growth_fit(&t, &y, cfg.window.0, cfg.window.1);
    let measured = fit.map(|f| f.rate / unit);
    let stride = (t.len() / 400).max(1);
    Ok(SwegleReport {
        diverged,
        integrator: cfg.integrator.name(),
        delta: cfg.diffusion.map_or(0.0, |d| d.0),
        delta_form: cfg.diffusion.map(|d| d.1.name()),
        form: cfg.form.name(),
        kernel: cfg.kernel.name(),
        h_over_dx: cfg.h_over_dx,
        density_ratio: cfg.density_ratio,
        dim: D,
        size: cfg.size,
        boundary_density: cfg.boundary,
        measured_growth_rate: measured,
        predicted_growth_rate_box: box_rate,
        box_method: method,
        predicted_growth_rate_infinite: inf,
        // a ratio only means something when the prediction is growth (above GROWTH_TOL)
        ratio_box: measured
            .filter(|_| box_rate > crate::vonneumann::classify::GROWTH_TOL)
            .map(|m| m / box_rate),
        ratio_infinite: measured
            .filter(|_| inf > crate::vonneumann::classify::GROWTH_TOL)
            .map(|m| m / inf),
        fit,
        max_velocity_end: *y.last().unwrap_or(&0.0),
        grew: vmax_ever > 2.0 * cfg.kick,
        dt: cfg.dt,
        dt_physical: dt,
        dx_physical: cfg.dx,
        sound_speed_physical: c,
        steps: run.steps,
        runtime_s,
        history_full: full,
        dominant_kappa: dominant,
        predicted_kappa_box: pred.box_kappa,
        history: t
            .iter()
            .zip(&y)
            .step_by(stride)
            .map(|(&a, &b)| (a, b))
            .collect(),
        final_state: Some(run.z.into()),
    })
}
