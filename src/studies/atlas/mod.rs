//! The 1D stability atlas (`sphstab atlas`): every form × kernel × h/Δx × σ̄ cell, each the
//! largest growth rate over κΔx ∈ (0, π] (the engine's [`crate::vonneumann::linearise::Linearisation`]),
//! computed in parallel (rayon) and splittable into shards for a batch system's job array:
//! cell `c` (in the fixed order form, kernel, h, σ̄) belongs to shard `c mod n`; `merge` checks
//! that the shards share one configuration and cover 0..n exactly once.

mod config;
mod report;
mod run;

pub use config::{AtlasConfig, CellSpec, Shard, grid};
pub use report::{AtlasReport, Cell, merge, summary};
pub use run::{AFFINE_TOL, lattice_sum_terms, run};
