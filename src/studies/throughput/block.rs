//! One block of the throughput study: built with its smooth velocity field, then timed (median
//! over the repeats), with its neighbours and its memory ([`MemoryProbe`]).

use super::config::{Domain, ThroughputConfig, check_size};
use super::report::BlockTiming;
use crate::error::{Error, Result, Text, field};
use crate::forms::Model;
use crate::neighbours::CellList;
use crate::progress::Progress;
use crate::solver::run::{BoundaryDensity, Run};
use std::time::Instant;

/// The 2D block of the module docs, ready to run ([`build_block_nd`] with D = 2).
pub fn build_block(cfg: &ThroughputConfig, size: usize) -> Result<Run<2>> {
    build_block_nd::<2>(cfg, size)
}

/// The `size`^D block of the module docs, ready to run; D must be [`ThroughputConfig::dim`].
pub fn build_block_nd<const D: usize>(cfg: &ThroughputConfig, size: usize) -> Result<Run<D>> {
    cfg.validate()?;
    if D != cfg.dim {
        return Err(Error::Incompatible(
            Text::from(format!("a {D}D block from a "))
                + field("dim")
                + format!(" {} configuration", cfg.dim),
        ));
    }
    let support = cfg.kernel.zeta() * cfg.h_over_dx;
    check_size("size", size, D, cfg.domain, support)?;
    let count = size.pow(D as u32);
    let mut x = Vec::with_capacity(count);
    for k in 0..count {
        // first axis slowest
        let mut p = [0.0; D];
        let mut rest = k;
        for a in (0..D).rev() {
            p[a] = (rest % size) as f64;
            rest /= size;
        }
        x.push(p);
    }
    let pi = std::f64::consts::PI;
    let (period, l, wave) = match cfg.domain {
        Domain::Open => (None, (size - 1) as f64, pi),
        Domain::Periodic => {
            let mut per = [[0.0; D]; D];
            for (a, row) in per.iter_mut().enumerate() {
                row[a] = size as f64;
            }
            (Some(per), size as f64, 2.0 * pi)
        }
    };
    let model = Model::<D>::new(cfg.params()?, x, vec![1.0; count], 1.0, 0.0, period)?;
    let mut z = model.rest_state(1.0);
    for (v, x) in z.v.iter_mut().zip(&model.x_ref) {
        for (a, va) in v.iter_mut().enumerate() {
            *va = cfg.amplitude * (wave * x[(a + 1) % D] / l).sin();
        }
    }
    Run::new(model, z, vec![false; count], BoundaryDensity::Evolve)
}

/// The caller's view of its global allocator (the binary installs a tracking one).
pub trait MemoryProbe: Sync {
    /// Bytes allocated now.
    fn current(&self) -> usize;
    /// Peak of [`MemoryProbe::current`] since the last reset.
    fn peak(&self) -> usize;
    /// Sets the peak to the current value.
    fn reset_peak(&self);
    /// Allocations (and reallocations) so far.
    fn allocations(&self) -> u64;
}

/// Mean number of particles within the support of each particle (itself included): the
/// Eulerian stencils' sizes, or a cell-list count at the current positions (nearest images in
/// a periodic box) for the total-Lagrangian forms.
fn mean_neighbours<const D: usize>(run: &Run<D>) -> f64 {
    if let Some(m) = run.mean_neighbours() {
        return m;
    }
    let r = run.model.p.kp.support();
    let period = run.model.period.map(|l| {
        let mut p = [0.0; D];
        for (a, pa) in p.iter_mut().enumerate() {
            *pa = l[a][a];
        }
        p
    });
    let cl = CellList::new(&run.z.x, r, period);
    let mut total = 0usize;
    for p in &run.z.x {
        cl.for_candidates(*p, |j| {
            let d = run.model.rel(*p, run.z.x[j]);
            if d.iter().map(|c| c * c).sum::<f64>() < r * r {
                total += 1;
            }
        });
    }
    total as f64 / run.z.x.len().max(1) as f64
}

/// Builds and runs one block: 1 warm-up step, then `repeats` × `steps` timed steps.
/// `progress` is told the fraction of this block's steps done.
pub fn time_block(
    cfg: &ThroughputConfig,
    size: usize,
    mem: Option<&dyn MemoryProbe>,
    progress: impl Progress,
) -> Result<BlockTiming> {
    match cfg.dim {
        3 => time_block_nd::<3>(cfg, size, mem, progress),
        _ => time_block_nd::<2>(cfg, size, mem, progress),
    }
}

fn time_block_nd<const D: usize>(
    cfg: &ThroughputConfig,
    size: usize,
    mem: Option<&dyn MemoryProbe>,
    progress: impl Progress,
) -> Result<BlockTiming> {
    let before = mem.map(|m| {
        m.reset_peak();
        m.current()
    });
    let mut run = build_block_nd::<D>(cfg, size)?;
    run.set_pair_reuse(cfg.pair_reuse);
    run.set_skin(cfg.skin);
    let n = run.z.x.len();
    run.step(cfg.dt)?;
    let builds0 = run.stencil_builds();
    let total = (cfg.steps * cfg.repeats) as f64;
    let mut per_step = Vec::with_capacity(cfg.repeats);
    let allocs0 = mem.map(|m| m.allocations());
    // allocations of the progress callback (a progress bar drawing) are not the solver's
    let mut by_progress = 0;
    for r in 0..cfg.repeats {
        let t0 = Instant::now();
        for s in 0..cfg.steps {
            run.step(cfg.dt)?;
            if s % 16 == 15 {
                let a = mem.map_or(0, |m| m.allocations());
                progress.advance(((r * cfg.steps + s + 1) as f64) / total);
                by_progress += mem.map_or(0, |m| m.allocations()) - a;
                if progress.cancelled() {
                    return Err(Error::Cancelled);
                }
            }
        }
        per_step.push(t0.elapsed().as_secs_f64() / cfg.steps as f64);
    }
    let allocations_per_step = mem
        .zip(allocs0)
        .map(|(m, a0)| (m.allocations() - a0 - by_progress) as f64 / total);
    let bytes_per_particle = mem
        .zip(before)
        .map(|(m, b)| m.peak().saturating_sub(b) as f64 / n as f64);
    let mut sorted = per_step.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let builds1 = run.stencil_builds();
    progress.advance(1.0);
    Ok(BlockTiming {
        size,
        particles: n,
        seconds_per_step: median,
        seconds_per_step_repeats: per_step,
        ns_per_particle_step: median / n as f64 * 1e9,
        particle_steps_per_second: n as f64 / median,
        neighbours_per_particle: mean_neighbours(&run),
        bytes_per_particle,
        state_bytes_per_particle: run.state_bytes() as f64 / n as f64,
        allocations_per_step,
        max_speed_end: run.max_free_speed(),
        full_builds_per_step: (builds1.0 - builds0.0) as f64 / total,
        pair_refreshes_per_step: (builds1.1 - builds0.1) as f64 / total,
    })
}
