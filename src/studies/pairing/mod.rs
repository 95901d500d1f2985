//! The pairing study (SPEC §5.7): classical SPH (sum form, `sph` shapes) with a hydrodynamic
//! material under positive pressure (σ̄ < 0) on the simple-cubic, bcc and fcc lattices, for every
//! kernel × lattice × h/Δx — the largest growth rate over the Brillouin zone and its wave
//! vector and polarisation, against the neighbour number N_H and next to the kernel's 3D
//! Fourier-transform sign criterion ([`wstar`], Dehnen & Aly 2012).
//!
//! Conventions (crate docs): Δx = (volume per particle)^⅓, so the three lattices have the same
//! density; growth rates in c/Δx, c² = K/ρ0; wave vectors κΔx in the first zone. N_H is the
//! number of lattice particles inside the support, |r| < R = ζh, the particle itself included
//! (the support test of every neighbour search); `n_h_continuum` = (4π/3)(R/Δx)³ is the
//! neighbour number of a uniform continuum (Dehnen & Aly's N_H = 4πH³n/3, H the support radius).
//!
//! A mode grows when γ > [`GROWTH_TOL`](crate::vonneumann::classify::GROWTH_TOL) (1e-6 c/Δx); below it the row reports growth 0 and no
//! wave vector. A mode is longitudinal when its longitudinal fraction |ê·k̂|² is ≥ ½ (degenerate
//! eigenspaces: see [`DEGENERACY_TOL`]) — pairing is the longitudinal instability (particles
//! approach each other in pairs along k); in a zero-shear material under pressure the sum form
//! can also grow through transverse modes, reported separately.
//! Rows whose linearisation would exceed the memory budget ([`crate::budget`]; large supports of
//! the ζ = 3 kernels) and rows whose support holds no neighbour are reported as skipped, with the
//! reason, not as errors.
//!
//! The full study runs ~47 min: [`PairingStudy`] splits its rows into shards for a job array
//! ([`crate::studies::shard`]), merged bit for bit into the report of one run.

mod config;
pub mod report;
mod run;
mod shard;
pub mod wstar;
pub mod wstar_scan;
mod zone;

pub use config::{
    FULL_STUDY_CONFIG, H_LIMITS, LATTICES, MAX_H_VALUES, MAX_STRESSES, PairingConfig, Plan,
    QUICK_DESCRIPTION, STRESS_LIMITS, parse_config, plan,
};
pub use report::{Onset, PairingReport, PairingRow, figure_svg, table};
pub use run::{evaluate_row, neighbour_count, onsets, row_query, run};
pub use shard::PairingStudy;
pub use zone::{DEGENERACY_TOL, LONGITUDINAL, ZoneGrowth, zone_growth, zone_growth_of};
