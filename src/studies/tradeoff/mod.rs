//! The speed/accuracy trade-off study (`sphstab tradeoff`): for every form × kernel × h/Δx on a
//! grid, what a configuration costs and what it buys, measured in one run on one machine.
//!
//! | column | how it is obtained |
//! |---|---|
//! | `ns_per_particle_step` | wall time of the wave scene below (the real solver, same rate function), median of `repeats` runs, divided by particles × steps |
//! | `neighbours_per_particle` | masters within the support radius R of a master (reference lattice, self excluded) |
//! | `bytes_per_particle` | peak heap bytes while building and running the scene, above the level before, per particle (needs a counting allocator: [`MemoryProbe`](crate::studies::throughput::MemoryProbe); `None` without one) |
//! | `phase_error_10ppw`, `_20ppw` | \|c_num/c − 1\| at κΔx = 2π/10, 2π/20 from the engine's ω²(κ) at σ̄ = 0 (2D: the longitudinal branch along x) |
//! | `wave_l2_error` | relative L2 error of the particle velocities of a standing wave v = V sin(kx) cos(ωt) (20 points per wavelength, periodic, Δt = 0.2 Δx/c, t = 2⅛ periods) against the continuum solution |
//! | `max_stable_tension` | largest σ̄ ≤ 0.999 (2D hydro: ≤ 0.95) up to which no mode grows (scan, then bisection to 1e-3 relative); 0 if a mode grows at σ̄ = 1e-6 |
//! | `stable_in_compression` | no growing mode at σ̄ = −0.01 |
//! | `critical_dt` | critical leapfrog Δt in Δx/c at σ̄ = 0 from the amplification matrices (the CFL number c Δt/h is `critical_dt` / (h/Δx)) |
//! | `ns_per_particle_time` | ns_per_particle_step / critical_dt: the cost of advancing one particle by Δx/c at the largest stable step |
//!
//! With `integrators` (1D only) the report gains `integrator_rows`: the integrator as a
//! dimension of the study, one row per configuration × integrator ([`integrators`]).
//! `sphstab tradeoff --cfl-table` prints the critical CFL table ([`cfl`]). [`TradeoffStudy`]
//! splits the configurations into shards for a job array ([`crate::studies::shard`]; the 2D
//! study takes ~5 min of CPU).
//!
//! The 1D grid covers the ten 1D forms, the 2D grid the six 2D forms (square lattice, hydro
//! material p = K(ρ/ρ0 − 1), as in the Swegle test). A configuration the engine rejects (e.g. an
//! MLS support that does not cover enough neighbours) is reported with its error, not dropped.

pub mod cfl;
mod config;
pub mod integrators;
mod report;
mod run;
mod scenes;
mod shard;

pub use config::{TradeoffConfig, grid, integrator_list, parse_config};
pub use integrators::IntegratorRow;
pub use report::{
    Row, TradeoffReport, figure_svg, integrator_table, integrators_svg, pareto_svg, table,
};
pub use run::run;
pub(crate) use run::tension_limit;
pub use scenes::scene_description;
pub use shard::{TradeoffCell, TradeoffStudy};
