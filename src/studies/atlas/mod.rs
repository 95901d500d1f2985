//! The 1D stability atlas (`sphstab atlas`): every form × kernel × h/Δx × σ̄ cell, each the
//! largest growth rate over κΔx ∈ (0, π] (the engine's [`crate::vonneumann::linearise::Linearisation`]),
//! computed in parallel (rayon) and splittable into shards for a batch system's job array
//! ([`crate::studies::shard`]): cell `c` (in the fixed order form, kernel, h, σ̄) belongs to
//! shard `c mod n`; the merge checks every stored cell against the sweep (`check`).

mod check;
mod config;
mod report;
mod run;
mod shard;

pub use check::MAX_GROWTH_RATE;
pub use config::{AtlasConfig, CellSpec, Sweep};
pub use report::{AtlasReport, Cell, summary};
pub use run::{AFFINE_TOL, lattice_sum_terms, run};
pub use shard::AtlasStudy;
