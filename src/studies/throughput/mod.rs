//! Throughput of the solver ([`Run::step`](crate::solver::Run::step), D ∈ {2, 3}) on a square or cubic block: time per
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

mod block;
mod config;
mod report;
mod run;

pub use block::{MemoryProbe, build_block, build_block_nd, time_block};
pub use config::{BlockMaterial, Domain, MAX_SIZE_3D, SIZE_RANGE, ThroughputConfig, check_size};
pub use report::{BlockTiming, ThroughputReport};
pub use run::{run_throughput, scaling_exponent};
