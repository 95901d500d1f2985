//! Running the throughput study: every block size on a pool of the requested threads, within
//! the memory and step budget, and the scaling exponent of the time per step.

use super::block::{MemoryProbe, time_block};
use super::config::{BlockMaterial, ThroughputConfig, check_size};
use super::report::{BlockTiming, ThroughputReport};
use crate::budget::fmt_count;
use crate::error::{Error, Result, check_range, field, fields};
use crate::forms::{FormKind, ObjectiveRate};
use crate::progress::Progress;
use crate::shape::ShapeFamily;

/// Least-squares slope p of ln(time per step) against ln N: time per step ∝ N^p. `None` with
/// fewer than two distinct particle counts.
pub fn scaling_exponent(blocks: &[BlockTiming]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = blocks
        .iter()
        .map(|b| ((b.particles as f64).ln(), b.seconds_per_step.ln()))
        .collect();
    let m = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / m;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / m;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 1e-12).then(|| sxy / sxx)
}

/// Times the block at each size in `sizes` on a rayon pool of `threads` threads (`None`: one
/// per core), within [`ThroughputConfig::budget`]. `progress` is told the fraction of the
/// whole run done (weighted by N).
pub fn run_throughput(
    cfg: &ThroughputConfig,
    sizes: &[usize],
    threads: Option<usize>,
    mem: Option<&dyn MemoryProbe>,
    progress: impl Progress,
) -> Result<ThroughputReport> {
    cfg.validate()?;
    if sizes.is_empty() {
        return Err(Error::Incompatible(
            field("sizes") + ": give at least one size",
        ));
    }
    // resources of the largest block and of all runs together (the budget): compact
    // stencils of a 4-byte entry per neighbour plus half a pair (4 + 8 + 8 B) with 1/32 spare,
    // 8D bytes more per entry and stencil for the non-SPH shape families, and ~350 B (2D) or
    // ~800 B (3D) of state per particle (measured: 586 B at 20.8 neighbours in 2D; 1,787 B at
    // 81 neighbours in 3D), and 1 warm-up + steps × repeats steps per size
    let r = cfg.kernel.zeta() * cfg.h_over_dx;
    let dim = cfg.dim as i32;
    let neighbours = if cfg.dim == 3 {
        4.0 / 3.0 * std::f64::consts::PI * r * r * r + 1.0
    } else {
        std::f64::consts::PI * r * r + 1.0
    };
    let mixed = matches!(cfg.form, FormKind::Lnl | FormKind::Cll);
    let per_stencil = 8.0 * cfg.dim as f64;
    let entry = (4.0 + 10.0) * 1.04
        + if cfg.shape != ShapeFamily::Sph {
            per_stencil
        } else {
            0.0
        }
        + if mixed { per_stencil } else { 0.0 };
    let state = if cfg.dim == 3 { 800.0 } else { 350.0 };
    let name = if sizes.len() > 1 { "sizes" } else { "size" };
    for &n in sizes {
        check_size(name, n, cfg.dim, cfg.domain, r)?;
    }
    let largest = sizes.iter().copied().max().unwrap_or(0) as f64;
    cfg.budget.memory(
        fields(&["size", "sizes"]),
        &format!(
            "the {} block (~{neighbours:.0} neighbours per particle)",
            vec![largest.to_string(); cfg.dim].join(" × ")
        ),
        largest.powi(dim) * (neighbours * entry + state),
    )?;
    let steps = (1 + cfg.steps * cfg.repeats) as f64;
    let particle_steps: f64 = sizes.iter().map(|&n| (n as f64).powi(dim) * steps).sum();
    cfg.budget.steps(
        fields(&["steps", "repeats", "size"]),
        &format!("timing the blocks ({} steps per size)", fmt_count(steps)),
        particle_steps,
    )?;
    if let Some(t) = threads {
        check_range("threads", t as f64, 1.0, 1024.0, true, true)?;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| {
            Error::Incompatible(field("threads") + format!(": cannot start the pool: {e}"))
        })?;
    // every worker runs once before anything is timed or counted: a thread that starts late
    // (a loaded machine) would otherwise allocate its thread-locals inside the timed steps
    pool.broadcast(|_| ());
    let weights: Vec<f64> = sizes.iter().map(|&s| (s as f64).powi(dim)).collect();
    let total: f64 = weights.iter().sum();
    let mut done = 0.0;
    let mut blocks = Vec::with_capacity(sizes.len());
    for (&s, &w) in sizes.iter().zip(&weights) {
        let part = |f: f64| progress.advance((done + f * w) / total);
        let b = pool.install(|| time_block(cfg, s, mem, part))?;
        if progress.cancelled() {
            return Err(Error::Cancelled);
        }
        done += w;
        blocks.push(b);
    }
    let (material, poisson) = match cfg.material {
        BlockMaterial::Hydro => ("hydro".to_string(), None),
        BlockMaterial::Elastic { poisson, rate } => (
            match rate {
                ObjectiveRate::Jaumann => "elastic-jaumann",
                ObjectiveRate::Truesdell => "elastic-truesdell",
            }
            .to_string(),
            Some(poisson),
        ),
    };
    Ok(ThroughputReport {
        dim: cfg.dim,
        domain: cfg.domain,
        form: cfg.form.name(),
        shape: cfg.shape.name(),
        kernel: cfg.kernel.name(),
        h_over_dx: cfg.h_over_dx,
        material,
        poisson,
        av: cfg.av.map(|(a, b)| [a, b]),
        art_eps: cfg.art_stress.map(|a| a.0),
        art_n: cfg.art_stress.map(|a| a.1),
        dt: cfg.dt,
        amplitude: cfg.amplitude,
        steps: cfg.steps,
        repeats: cfg.repeats,
        threads: pool.current_num_threads(),
        scaling_exponent: scaling_exponent(&blocks),
        blocks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn timing(particles: usize, seconds_per_step: f64) -> BlockTiming {
        BlockTiming {
            size: 0,
            particles,
            seconds_per_step,
            seconds_per_step_repeats: vec![seconds_per_step],
            ns_per_particle_step: 0.0,
            particle_steps_per_second: 0.0,
            neighbours_per_particle: 0.0,
            bytes_per_particle: None,
            state_bytes_per_particle: 0.0,
            allocations_per_step: None,
            max_speed_end: 0.0,
            full_builds_per_step: 0.0,
            pair_refreshes_per_step: 0.0,
        }
    }

    /// The fit recovers an exact power law and refuses a single size.
    #[test]
    fn scaling_exponent_of_a_power_law() {
        let b: Vec<_> = [1e4, 1e5, 1e6]
            .iter()
            .map(|&n: &f64| timing(n as usize, 3e-7 * n.powf(1.5)))
            .collect();
        let p = scaling_exponent(&b).unwrap();
        assert!((p - 1.5).abs() < 1e-12, "{p}");
        assert!(scaling_exponent(&b[..1]).is_none());
    }
}
