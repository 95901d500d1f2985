//! The Swegle test \[V21 §7.2\] in D ∈ {2, 3} dimensions, one code path: a square (cubic) block
//! of `size`^D particles (spacing 0.1 on [−1, 1]^D for size 21), outer `layers` layers fixed but
//! taking part in every sum (their density evolving by continuity, or frozen), hydrodynamic
//! aluminium ρ0 = 2.8, K = 0.686275, G = 0, initial density f ρ0 (f < 1 tension), the centre
//! particle kicked with v_x = 1e−10, no artificial viscosity. The measured exponential growth of
//! max |v| over the free particles is compared with the growth rate of the exact linear operator
//! of the same finite particle set (its fastest mode by thick-restart Arnoldi; every eigenvalue,
//! dense, when that finds no growing mode in a box of up to [`MAX_DENSE_BOX_DOFS`] free degrees
//! of freedom; the standing modes the box admits with δ-SPH) and with the infinite lattice.

mod config;
mod predict;
mod report;
mod run;
mod spec;

pub use config::{
    MAX_DENSE_BOX_DOFS, SwegleConfig, default_size, dense_size_limit, infinite_grid, max_size,
};
pub use predict::{SweglePrediction, predict_swegle};
pub use report::{Diverged, FinalState, HISTORY_COLUMNS, SwegleReport};
pub use run::run_swegle;
pub use spec::SwegleSpec;
