//! The kernel guide (`sphstab kernels --table`): for every kernel, the numbers a user needs to
//! pick a kernel, h, form and time step — each computed by the crate through the code path of
//! the command that answers the question alone, or a closed form checked against it, never typed
//! in:
//!
//! | column | code path |
//! |---|---|
//! | critical CFL c Δt_crit/h, `kdk`, σ̄ = 0 | the `tradeoff --cfl-table` cells ([`crate::studies::tradeoff::cfl::cfl_cell`]: `timestep`'s bisection on the amplification matrices, [`CFL_POINTS`](crate::studies::tradeoff::cfl::CFL_POINTS) κ points), through [`analyse`](crate::studies::tradeoff::integrators::analyse), which runs the same `IntegratorReport::of` |
//! | phase and amplitude error per wavelength travelled at 10 and 20 points per wavelength, `kdk` at [`SAFETY`] × Δt_crit | [`crate::studies::tradeoff::integrators::analyse`] (the trade-off study's `phase_error_10ppw`) |
//! | h/Δx stable in compression, 1D | [`compression_scan`]: the growth of [`query_1d`] (classical, `sph`, elastic bar) at σ̄ = [`COMPRESSION`] over its κ grid, from the derived closed form ω² = C̃S1² − 2σ̄(S2 − S1²) of [`crate::vonneumann::derived`] (the engine's `query` to rounding, same verdict at every h: `tests/it/kernel_guide.rs`) |
//! | h/Δx without pairing / without any growth in compression, 2D | [`compression_scan`]: the pairing study's zone scan ([`crate::studies::pairing::zone_growth_of`], the rule of [`crate::studies::pairing::zone_growth`]) of [`query_2d`] (classical, `sph`, hydro, square lattice, σ̄ = [`COMPRESSION`]) on the derived closed form ρD = (λ' + 2s) S1S1ᵀ − 2s S2 (the engine's Bloch linearisation to 1e-12: `tests/it/kernel_guide.rs`) |
//! | tensile onset | the trade-off study's tension scan and bisection ([`crate::studies::tradeoff`]), 1D classical, by the engine ([`max_growth_1d`]) |
//! | first κh with W* < 0 in 1D, 2D, 3D | the pairing study's W* scan ([`crate::studies::pairing::wstar::sign_criterion_with`], step [`WSTAR_K_STEP`]), computed by [`crate::studies::pairing::wstar_scan::sign_criterion_fast`]: the same result to the last bit from a fraction of the samples |
//!
//! Conventions as everywhere (crate docs): h/Δx in the kernel's own convention, R = ζh, time
//! steps in Δx/c, σ̄ = σ/C positive in tension, growth when γ > [`GROWTH_TOL`](crate::vonneumann::classify::GROWTH_TOL) c/Δx. The
//! h/Δx scans start at the first grid value whose support holds a neighbour (ζh > Δx); the 2D
//! scan stops at R ≤ [`MAX_SUPPORT_2D`] Δx.
//!
//! Cost (issue 25): `benches/kernel_table.rs` times the table and each column; the time-step
//! cells (a bisection over 256 amplification matrices per Δt) and the W* scans take most of it.

mod compression;
mod config;
mod report;
mod run;

pub use compression::{
    PhaseGrid, closed_form_growth_1d, closed_form_zone_2d, compression_scan, intervals, query_1d,
    query_2d,
};
pub use config::{
    COMPRESSION, DEFAULT_H_STEP, GRID_2D, GUIDE_FORMS, GUIDE_H, GuideConfig, H_STEP_RANGE,
    KAPPAS_1D, MAX_SUPPORT_2D, ONSET_BISECTIONS, PPW, REFERENCE_TENSION, SAFETY, SCAN_H,
    TENSION_CAP, TENSION_FLOOR, WSTAR_K_MAX, WSTAR_K_STEP,
};
pub use report::{
    CompressionScan, Interval, KernelGuide, KernelGuideRow, Positivity, TensileOnset, TimeStepCell,
    markdown,
};
pub use run::{grows_1d, kernel_guide, kernel_row, max_growth_1d, tensile_onset, time_step_cell};
