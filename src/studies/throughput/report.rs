//! The throughput report: one timing per block and the scaling exponent.

use super::config::Domain;
use serde::Serialize;

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
    /// Bytes per particle held by the run at the end ([`Run::state_bytes`](crate::solver::Run::state_bytes): state, model,
    /// step buffers, rate workspace with its stencils, integrator arrays; capacities).
    pub state_bytes_per_particle: f64,
    /// Allocations per timed step (null without a memory probe).
    pub allocations_per_step: Option<f64>,
    /// max |v| at the end (c), a sanity check that the run stayed small and finite.
    pub max_speed_end: f64,
    /// Full stencil builds (neighbour search) per timed step.
    pub full_builds_per_step: f64,
    /// Stencil builds per timed step that reused the pairs of the last full build (only their
    /// kernel data recomputed; bitwise the same stencils, [`Run::set_pair_reuse`](crate::solver::Run::set_pair_reuse)).
    pub pair_refreshes_per_step: f64,
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
    /// Amplitude of the initial velocity field (c).
    pub amplitude: f64,
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
