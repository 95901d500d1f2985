//! Running the trade-off study: per configuration, the engine's numbers (phase errors, tension
//! limit, critical Δt) and the solver's (cost and accuracy of the wave scene, [`super::scenes`]).

use super::config::{TradeoffConfig, grid, integrator_list};
use super::integrators;
use super::integrators::IntegratorRow;
use super::report::{Row, TradeoffReport};
use super::scenes::{
    SCENE_1D_N, SCENE_DT, median, scene_1d, scene_1d_with, scene_2d, scene_description,
};
use super::shard::TradeoffCell;
use crate::analysis::{MaterialSpec, Query};
use crate::budget::Budget;
use crate::error::Result;
use crate::forms::{FormKind, Model};
use crate::integrator::Integrator;
use crate::kernel::Kernel;
use crate::progress::{Counter, Progress};
use crate::studies::shard::{Shard, Timing};
use crate::studies::throughput::MemoryProbe;
use crate::vonneumann::amplification::{critical_dt, critical_dt_bisection};
use crate::vonneumann::classify::GROWTH_TOL;
use rayon::prelude::*;
use std::f64::consts::PI;

/// σ̄ candidates of the tension scan (the first unstable one is refined by bisection).
const TENSION_SCAN: [f64; 12] = [
    1e-6, 1e-4, 1e-3, 1e-2, 0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 0.95, 0.999,
];
/// Bisection steps after the scan.
const BISECTION_STEPS: usize = 10;
/// κ points of the 1D stability checks.
const KAPPAS_1D: usize = 256;
/// Wave vectors per direction of the 2D stability checks.
const GRID_2D: usize = 16;

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

/// The engine's part of a row (no timing): phase errors, stability, critical Δt; the 2D
/// linearisations within `budget`.
fn analyse(
    dim: u8,
    form: FormKind,
    k: &'static dyn Kernel,
    h: f64,
    budget: &Budget,
    row: &mut Row,
) -> Result<()> {
    let phase = |w2: f64, kap: f64, c: f64| (w2.max(0.0).sqrt() / kap / c - 1.0).abs();
    let (k10, k20) = (2.0 * PI / 10.0, 2.0 * PI / 20.0);
    if dim == 1 {
        let mut q = Query::<1>::new(form, k, h, 0.0);
        q.grid = KAPPAS_1D;
        q.validate()?;
        let kappas = q.kappas();
        let lin0 = q.chain()?;
        row.phase_error_10ppw = Some(phase(lin0.omega2(k10).0, k10, 1.0));
        row.phase_error_20ppw = Some(phase(lin0.omega2(k20).0, k20, 1.0));
        let grows = |s: f64| -> Result<bool> {
            let lin = q.chain_at(s)?;
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
        let mut q = Query::<2>::new(form, k, h, 0.0);
        q.material = MaterialSpec::Hydro;
        q.grid = GRID_2D;
        q.budget = *budget;
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

/// Runs the whole study, telling `progress` the fraction of configurations finished. Sharded:
/// [`TradeoffStudy`](super::TradeoffStudy).
pub fn run(
    cfg: &TradeoffConfig,
    probe: Option<&dyn MemoryProbe>,
    progress: impl Progress,
) -> Result<TradeoffReport> {
    crate::studies::shard::run_whole(&super::TradeoffStudy { probe }, cfg, progress)
}

/// The report from every configuration's cell, in the grid's order.
pub(super) fn assemble(
    cfg: &TradeoffConfig,
    cells: Vec<TradeoffCell>,
    timing: Timing,
) -> TradeoffReport {
    let mut rows = Vec::with_capacity(cells.len());
    let mut integrator_rows = Vec::new();
    for c in cells {
        rows.push(c.row);
        integrator_rows.extend(c.integrator_rows);
    }
    TradeoffReport {
        dim: cfg.dim,
        threads: timing.threads,
        runtime_s: timing.runtime_s,
        scene: scene_description(cfg.dim),
        rows,
        integrator_rows,
    }
}

/// Computes the configurations of `shard` (ascending, with their indices in the grid), telling
/// `progress` the fraction done. The engine part runs in parallel (rayon); the timed scenes run
/// one at a time so they do not compete.
pub(super) fn compute_cells(
    cfg: &TradeoffConfig,
    shard: Shard,
    probe: Option<&dyn MemoryProbe>,
    progress: &dyn Progress,
) -> Result<Vec<(usize, TradeoffCell)>> {
    let (index, configs): (Vec<usize>, Vec<_>) = grid(cfg)?
        .into_iter()
        .enumerate()
        .filter(|(c, _)| shard.owns(*c))
        .unzip();
    let integs = integrator_list(cfg)?;
    let done = Counter::new(progress, 2 * configs.len() * (1 + integs.len()), 1);
    let mut rows: Vec<Row> = configs
        .par_iter()
        .map(|&(form, k, h)| -> Result<Row> {
            let shape = if cfg.dim == 1 {
                form.default_shape()
            } else {
                form.default_shape_in(2)
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
            if let Err(e) = analyse(cfg.dim, form, k, h, &cfg.budget, &mut row) {
                row.error = Some(e.to_string());
            }
            done.add(1)?;
            Ok(row)
        })
        .collect::<Result<_>>()?;
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
        done.add(1)?;
    }
    let mut integrator_rows = integrator_rows(cfg, &configs, &integs, &done)?.into_iter();
    Ok(index
        .into_iter()
        .zip(rows)
        .map(|(c, row)| {
            let cell = TradeoffCell {
                row,
                integrator_rows: integrator_rows.by_ref().take(integs.len()).collect(),
            };
            (c, cell)
        })
        .collect())
}

/// The integrator dimension ([`integrators`]): the engine part in parallel, then the timed
/// scenes one at a time.
fn integrator_rows(
    cfg: &TradeoffConfig,
    configs: &[(FormKind, &'static dyn Kernel, f64)],
    integs: &[Integrator],
    done: &Counter,
) -> Result<Vec<IntegratorRow>> {
    let jobs: Vec<(FormKind, &'static dyn Kernel, f64, Integrator)> = configs
        .iter()
        .flat_map(|&(f, k, h)| integs.iter().map(move |&i| (f, k, h, i)))
        .collect();
    let mut rows: Vec<IntegratorRow> = jobs
        .par_iter()
        .map(|&(form, k, h, integ)| -> Result<IntegratorRow> {
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
                    let q = Query::<1>::new(form, k, h, 0.0);
                    let x: Vec<[f64; 1]> = (0..SCENE_1D_N).map(|i| [i as f64]).collect();
                    let model = Model::new(
                        q.params()?,
                        x,
                        vec![1.0; SCENE_1D_N],
                        1.0,
                        0.0,
                        Some([[SCENE_1D_N as f64]]),
                    )?;
                    row.evaluations_per_step = integrators::evaluations_per_step(&model, integ);
                    Ok(())
                });
            if let Err(e) = res {
                row.error = Some(e.to_string());
            }
            done.add(1)?;
            Ok(row)
        })
        .collect::<Result<_>>()?;
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
        done.add(1)?;
    }
    Ok(rows)
}
