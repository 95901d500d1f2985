//! The kernel guide (`sphstab kernels --table`): for every kernel, the numbers a user needs to
//! pick a kernel, h, form and time step — each measured by the engine through the code path of
//! the command that answers the question alone, never typed in:
//!
//! | column | code path |
//! |---|---|
//! | critical CFL c Δt_crit/h, `kdk`, σ̄ = 0 | the `tradeoff --cfl-table` cells ([`crate::studies::tradeoff::cfl::cfl_cell`]: `timestep`'s bisection on the amplification matrices, [`CFL_POINTS`](crate::studies::tradeoff::cfl::CFL_POINTS) κ points), through [`analyse`](crate::studies::tradeoff::integrators::analyse), which runs the same `IntegratorReport::of` |
//! | phase and amplitude error per wavelength travelled at 10 and 20 points per wavelength, `kdk` at [`SAFETY`] × Δt_crit | [`crate::studies::tradeoff::integrators::analyse`] (the trade-off study's `phase_error_10ppw`) |
//! | h/Δx stable in compression, 1D | [`Query<1>`](crate::analysis::Query) (classical, `sph`, elastic bar) at σ̄ = [`COMPRESSION`]: growth over the κ grid (`query`) |
//! | h/Δx without pairing / without any growth in compression, 2D | [`crate::studies::pairing::zone_growth`] (the pairing study's zone scan, on the square lattice): classical, `sph`, hydro, σ̄ = [`COMPRESSION`] |
//! | tensile onset | the trade-off study's tension scan and bisection ([`crate::studies::tradeoff`]), 1D classical |
//! | first κh with W* < 0 in 1D, 2D, 3D | [`crate::studies::pairing::wstar::sign_criterion_with`] (the pairing study's W* scan, step [`WSTAR_K_STEP`]) |
//!
//! Conventions as everywhere (crate docs): h/Δx in the kernel's own convention, R = ζh, time
//! steps in Δx/c, σ̄ = σ/C positive in tension, growth when γ > [`GROWTH_TOL`](crate::vonneumann::classify::GROWTH_TOL) c/Δx. The
//! h/Δx scans start at the first grid value whose support holds a neighbour (ζh > Δx); the 2D
//! scan stops at R ≤ [`MAX_SUPPORT_2D`] Δx (the linearisation of a 2D patch costs ~R⁴: a few
//! seconds per h at R = 18Δx).

mod config;
mod report;
mod run;

pub use config::{
    COMPRESSION, DEFAULT_H_STEP, GRID_2D, GUIDE_FORMS, GUIDE_H, GuideConfig, H_STEP_RANGE,
    KAPPAS_1D, MAX_SUPPORT_2D, ONSET_BISECTIONS, PPW, REFERENCE_TENSION, SAFETY, SCAN_H,
    TENSION_CAP, TENSION_FLOOR, WSTAR_K_MAX, WSTAR_K_STEP,
};
pub use report::{
    CompressionScan, Interval, KernelGuide, KernelGuideRow, Positivity, TensileOnset, TimeStepCell,
    markdown,
};
pub use run::{
    compression_scan, grows_1d, intervals, kernel_guide, kernel_row, max_growth_1d, query_2d,
    tensile_onset, time_step_cell,
};
