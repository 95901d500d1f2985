//! Throughput of the solver ([`Run::step`], D ∈ {2, 3}) on a square or cubic block: time per
//! particle-step, neighbours per particle, memory per particle, and the scaling exponent of
//! the time per step with the particle count.
//!
//! The block is n^D particles on a square (simple-cubic) lattice, Δx = 1, ρ0 = 1, tangent
//! modulus C = 1 (so c = 1 and times are in Δx/c), no fixed particles, initially unstressed at
//! ρ0 with the smooth velocity field v_a = A c sin(k x_{a+1}) (axes cyclic: v_x depends on y,
//! v_y on z, or on x in 2D, v_z on x). Open block ([`Domain::Open`], the 2D default):
//! k = π/L, L = (n − 1)Δx; periodic box ([`Domain::Periodic`], the 3D default, period nΔx per
//! axis): k = 2π/(nΔx). One warm-up step (the buffers grow), then `repeats` × `steps` timed
//! steps; the time per step is the median over the repeats. Memory is measured by the
//! caller's allocator ([`MemoryProbe`]): the peak of the bytes allocated while the block is
//! built and run, above those allocated before, per particle.

use crate::error::{Error, Result, check_range};
use crate::forms::{
    ArtificialStress, ArtificialViscosity, FormKind, Material2D, Model, ModelParams2D,
    ObjectiveRate,
};
use crate::kernel::Kernel;
use crate::neighbours::CellList;
use crate::shape::KernelParams;
use crate::shape::ShapeFamily;
use crate::solver::run2d::{BoundaryDensity, Run, Run2D};
use serde::Serialize;
use std::time::Instant;

/// Material of the block (ρ0 = 1 and tangent modulus 1 in both cases).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BlockMaterial {
    /// p = K(ρ/ρ0 − 1), K = 1.
    Hydro,
    /// Hypo-elastic, P-wave modulus 1, Poisson ratio ν (plane strain in 2D).
    Elastic {
        /// ν.
        poisson: f64,
        /// Objective stress rate.
        rate: ObjectiveRate,
    },
}

/// Boundary of the block.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Domain {
    /// Free surfaces all round.
    Open,
    /// Periodic in every direction (period n Δx).
    Periodic,
}

impl Domain {
    /// CLI name.
    pub fn name(self) -> &'static str {
        match self {
            Domain::Open => "open",
            Domain::Periodic => "periodic",
        }
    }
}

/// What to run.
#[derive(Clone, Copy, Debug)]
pub struct ThroughputConfig {
    /// Dimension D (2 or 3): the block holds n^D particles.
    pub dim: usize,
    /// Open block or periodic box.
    pub domain: Domain,
    /// The form.
    pub form: FormKind,
    /// Shape family.
    pub shape: ShapeFamily,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// h/Δx.
    pub h_over_dx: f64,
    /// Material.
    pub material: BlockMaterial,
    /// Monaghan artificial viscosity (α, β), `None`: off.
    pub av: Option<(f64, f64)>,
    /// Monaghan–Gray artificial stress (ε, n), classical and cll forms; `None`: off.
    pub art_stress: Option<(f64, i32)>,
    /// Time step in Δx/c.
    pub dt: f64,
    /// Timed steps per repeat.
    pub steps: usize,
    /// Repeats (the median is reported).
    pub repeats: usize,
    /// Amplitude A of the initial velocity field, in units of c.
    pub amplitude: f64,
    /// Whether stencil builds reuse provably unchanged pairs ([`Run::set_pair_reuse`]).
    pub pair_reuse: bool,
}

impl ThroughputConfig {
    /// The 2D defaults of `sphstab throughput`: open block, classical / m4, h = 1.3Δx, elastic
    /// (Jaumann, ν = 0.3), AV (1, 1), artificial stress (0.3, 4), Δt = 0.2Δx/c, 50 steps × 3
    /// repeats, A = 10⁻³.
    pub fn new(kernel: &'static dyn Kernel) -> Self {
        Self {
            dim: 2,
            domain: Domain::Open,
            form: FormKind::Classical,
            shape: FormKind::Classical.default_shape_2d(),
            kernel,
            h_over_dx: 1.3,
            material: BlockMaterial::Elastic {
                poisson: 0.3,
                rate: ObjectiveRate::Jaumann,
            },
            av: Some((1.0, 1.0)),
            art_stress: Some((0.3, 4)),
            dt: 0.2,
            steps: 50,
            repeats: 3,
            amplitude: 1e-3,
            pair_reuse: true,
        }
    }

    /// The defaults in dimension `dim`: in 3D a periodic box and no artificial stress (not
    /// available in 3D), everything else as in 2D.
    pub fn with_dim(self, dim: usize) -> Self {
        Self {
            dim,
            domain: if dim == 3 {
                Domain::Periodic
            } else {
                Domain::Open
            },
            art_stress: if dim == 3 { None } else { self.art_stress },
            ..self
        }
    }

    /// Checks every parameter; errors name the CLI flag.
    pub fn validate(&self) -> Result<()> {
        if !(2..=3).contains(&self.dim) {
            return Err(Error::OutOfRange {
                name: "--dim",
                value: self.dim as f64,
                range: "2 or 3".into(),
            });
        }
        if !self.form.in_2d() {
            return Err(Error::Incompatible(format!(
                "--form {} is not available in {}D (classical, nonlocal, local, lnl, cll, total-lagrangian)",
                self.form.name(),
                self.dim
            )));
        }
        if self.dim == 3 && self.art_stress.is_some() {
            return Err(Error::Incompatible(
                "--art-eps (artificial stress) is available with --dim 2 only".into(),
            ));
        }
        self.form.check_shape(self.shape)?;
        check_range("--h", self.h_over_dx, 0.0, 10.0, false, true)?;
        // the same checks as every other command (support must reach the neighbours, …)
        crate::analysis::check_common_named(
            &crate::analysis::ParamNames {
                av_alpha: "--av",
                av_beta: "--av",
                ..crate::analysis::ParamNames::CLI
            },
            self.kernel,
            self.h_over_dx,
            0.0,
            0.5,
            self.av,
            None,
        )?;
        if let BlockMaterial::Elastic { poisson, .. } = self.material {
            check_range("--poisson", poisson, -0.99, 0.5, true, false)?;
        }
        if let Some((a, b)) = self.av {
            check_range("--av", a, 0.0, 100.0, true, true)?;
            check_range("--av", b, 0.0, 100.0, true, true)?;
        }
        if let Some((eps, n)) = self.art_stress {
            check_range("--art-eps", eps, 0.0, 10.0, true, true)?;
            check_range("--art-n", n as f64, 1.0, 12.0, true, true)?;
            if !matches!(self.form, FormKind::Classical | FormKind::Cll) {
                return Err(Error::Incompatible(format!(
                    "--art-eps: artificial stress is defined for the classical and cll forms, not {}",
                    self.form.name()
                )));
            }
        }
        check_range("--dt", self.dt, 0.0, 2.0, false, true)?;
        check_range("--steps", self.steps as f64, 1.0, 1e6, true, true)?;
        check_range("--repeats", self.repeats as f64, 1.0, 1000.0, true, true)?;
        check_range("--amplitude", self.amplitude, 0.0, 0.1, true, true)?;
        Ok(())
    }

    fn params(&self) -> Result<ModelParams2D> {
        let material = match self.material {
            BlockMaterial::Hydro => Material2D::Hydro { bulk: 1.0 },
            BlockMaterial::Elastic { poisson, rate } => Material2D::elastic(1.0, poisson, rate)?,
        };
        Ok(ModelParams2D {
            form: self.form,
            shape: self.shape,
            kp: KernelParams {
                kernel: self.kernel,
                h: self.h_over_dx,
            },
            material,
            rho0: 1.0,
            c_partition: 0.5,
            av: self.av.map(|(alpha, beta)| ArtificialViscosity {
                alpha,
                beta,
                sound_speed: 1.0,
                approaching_only: true,
            }),
            art_stress: self.art_stress.map(|(eps, n)| ArtificialStress {
                eps,
                n,
                spacing: 1.0,
            }),
            diffusion: None,
        })
    }
}

/// Smallest and largest block side in 2D.
pub const SIZE_RANGE: (usize, usize) = (4, 3000);

/// Largest block side in 3D (8 × 10⁶ particles).
pub const MAX_SIZE_3D: usize = 200;

/// Checks a block side in dimension `dim` for `domain` (the flag is named in the error): in
/// [4, 3000] (2D) or [4, 200] (3D), and a periodic box more than two support radii `support`
/// wide, so that every neighbour has one image within the support.
pub fn check_size(
    name: &'static str,
    size: usize,
    dim: usize,
    domain: Domain,
    support: f64,
) -> Result<()> {
    let lo = if domain == Domain::Periodic {
        SIZE_RANGE.0.max((2.0 * support).floor() as usize + 1)
    } else {
        SIZE_RANGE.0
    };
    let hi = if dim == 3 { MAX_SIZE_3D } else { SIZE_RANGE.1 };
    if size < lo || size > hi {
        return Err(Error::OutOfRange {
            name,
            value: size as f64,
            range: format!(
                "particles per side must be an integer in [{lo}, {hi}] ({}D, {} domain)",
                dim,
                domain.name()
            ),
        });
    }
    Ok(())
}

/// The 2D block of the module docs, ready to run ([`build_block_nd`] with D = 2).
pub fn build_block(cfg: &ThroughputConfig, size: usize) -> Result<Run2D> {
    build_block_nd::<2>(cfg, size)
}

/// The `size`^D block of the module docs, ready to run; D must be [`ThroughputConfig::dim`].
pub fn build_block_nd<const D: usize>(cfg: &ThroughputConfig, size: usize) -> Result<Run<D>> {
    cfg.validate()?;
    if D != cfg.dim {
        return Err(Error::Incompatible(format!(
            "a {D}D block from a --dim {} configuration",
            cfg.dim
        )));
    }
    let support = cfg.kernel.zeta() * cfg.h_over_dx;
    check_size("--size", size, D, cfg.domain, support)?;
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

/// Timing of one block size.
#[derive(Clone, Debug, Serialize)]
pub struct BlockTiming {
    /// Particles per side.
    pub size: usize,
    /// Particles N = size^D.
    pub particles: usize,
    /// Median time per step over the repeats (s).
    pub seconds_per_step: f64,
    /// Time per step of each repeat (s).
    pub seconds_per_step_repeats: Vec<f64>,
    /// Median time per particle-step (ns).
    pub ns_per_particle_step: f64,
    /// Particle-steps per second (N / median time per step).
    pub particle_steps_per_second: f64,
    /// Mean neighbours per particle within the support ζh, itself included, at the end.
    pub neighbours_per_particle: f64,
    /// Measured peak bytes while building and running the block, per particle (null without
    /// a memory probe).
    pub bytes_per_particle: Option<f64>,
    /// Bytes per particle held by the run at the end ([`Run::state_bytes`]: state, model,
    /// step buffers, rate workspace with its stencils, integrator arrays; capacities).
    pub state_bytes_per_particle: f64,
    /// Allocations per timed step (null without a memory probe).
    pub allocations_per_step: Option<f64>,
    /// max |v| at the end (c), a sanity check that the run stayed small and finite.
    pub max_speed_end: f64,
    /// Full stencil builds (neighbour search) per timed step.
    pub full_builds_per_step: f64,
    /// Stencil builds per timed step that reused the pairs of the last full build (only their
    /// kernel data recomputed; bitwise the same stencils, [`Run::set_pair_reuse`]).
    pub pair_refreshes_per_step: f64,
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
/// `progress(f)` gets the fraction of this block's steps done.
pub fn time_block(
    cfg: &ThroughputConfig,
    size: usize,
    mem: Option<&dyn MemoryProbe>,
    progress: impl FnMut(f64),
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
    mut progress: impl FnMut(f64),
) -> Result<BlockTiming> {
    let before = mem.map(|m| {
        m.reset_peak();
        m.current()
    });
    let mut run = build_block_nd::<D>(cfg, size)?;
    run.set_pair_reuse(cfg.pair_reuse);
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
                progress(((r * cfg.steps + s + 1) as f64) / total);
                by_progress += mem.map_or(0, |m| m.allocations()) - a;
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
    progress(1.0);
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

/// A throughput run over one or more block sizes.
#[derive(Clone, Debug, Serialize)]
pub struct ThroughputReport {
    /// Dimension.
    pub dim: usize,
    /// Open block or periodic box.
    pub domain: Domain,
    /// Form.
    pub form: &'static str,
    /// Shape family.
    pub shape: &'static str,
    /// Kernel.
    pub kernel: &'static str,
    /// h/Δx.
    pub h_over_dx: f64,
    /// "hydro", "elastic-jaumann" or "elastic-truesdell".
    pub material: String,
    /// Poisson ratio (elastic).
    pub poisson: Option<f64>,
    /// Artificial viscosity [α, β] (null: off).
    pub av: Option<[f64; 2]>,
    /// Artificial stress ε (null: off).
    pub art_eps: Option<f64>,
    /// Artificial-stress exponent n.
    pub art_n: Option<i32>,
    /// Time step (Δx/c).
    pub dt: f64,
    /// Timed steps per repeat.
    pub steps: usize,
    /// Repeats.
    pub repeats: usize,
    /// Threads of the rayon pool.
    pub threads: usize,
    /// One entry per size, in the order given.
    pub blocks: Vec<BlockTiming>,
    /// p in time per step ∝ N^p (least squares on log–log), null with fewer than 2 sizes.
    pub scaling_exponent: Option<f64>,
}

/// Times the block at each size in `sizes` on a rayon pool of `threads` threads (`None`: one
/// per core). `progress(f)` gets the fraction of the whole run done (weighted by N).
pub fn run_throughput(
    cfg: &ThroughputConfig,
    sizes: &[usize],
    threads: Option<usize>,
    mem: Option<&dyn MemoryProbe>,
    mut progress: impl FnMut(f64) + Send,
) -> Result<ThroughputReport> {
    cfg.validate()?;
    if sizes.is_empty() {
        return Err(Error::Incompatible(
            "--sizes: give at least one size".into(),
        ));
    }
    // resources of the largest block and of all runs together (crate::budget): compact
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
    let flag = if sizes.len() > 1 { "--sizes" } else { "--size" };
    for &n in sizes {
        check_size(flag, n, cfg.dim, cfg.domain, r)?;
    }
    let largest = sizes.iter().copied().max().unwrap_or(0) as f64;
    crate::budget::check_memory(
        "--size/--sizes",
        &format!(
            "the {} block (~{neighbours:.0} neighbours per particle)",
            vec![largest.to_string(); cfg.dim].join(" × ")
        ),
        largest.powi(dim) * (neighbours * entry + state),
    )?;
    let steps = (1 + cfg.steps * cfg.repeats) as f64;
    let particle_steps: f64 = sizes.iter().map(|&n| (n as f64).powi(dim) * steps).sum();
    crate::budget::check_steps(
        "--steps/--repeats/--size",
        &format!(
            "timing the blocks ({} steps per size)",
            crate::budget::fmt_count(steps)
        ),
        particle_steps,
    )?;
    if let Some(t) = threads {
        check_range("--threads", t as f64, 1.0, 1024.0, true, true)?;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| Error::Incompatible(format!("--threads: cannot start the pool: {e}")))?;
    // every worker runs once before anything is timed or counted: a thread that starts late
    // (a loaded machine) would otherwise allocate its thread-locals inside the timed steps
    pool.broadcast(|_| ());
    let weights: Vec<f64> = sizes.iter().map(|&s| (s as f64).powi(dim)).collect();
    let total: f64 = weights.iter().sum();
    let mut done = 0.0;
    let mut blocks = Vec::with_capacity(sizes.len());
    for (&s, &w) in sizes.iter().zip(&weights) {
        let b = pool.install(|| time_block(cfg, s, mem, |f| progress((done + f * w) / total)))?;
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
