//! The integration tests, in one binary (`cargo test --release --test it`): one module per
//! topic, so that the suite links once instead of once per file. Run one topic with a filter,
//! e.g. `cargo test --release --test it -- damping::`. `common` holds the shared helpers.
//!
//! The allocation-counting tests are in their own binary (`tests/no_alloc/`): they install a
//! counting global allocator, which would see the allocations of every test running in
//! parallel here.

mod common;

mod antiplane;
mod art_stress;
mod classify;
mod cli;
mod cli2d;
mod cli_throughput;
mod closed_form;
mod core_claim;
mod damping;
mod derivative_audit;
mod derived;
mod diffusion;
mod extremes;
mod fast_paths;
mod figures;
mod fuzz_cli;
mod golden;
mod golden_analysis;
mod golden_solver1d;
mod golden_solver2d;
mod integrator;
mod integrators;
mod kernel_guide;
mod kernels;
mod limits;
mod long_run;
mod pair_reuse;
mod pairing;
mod papers;
mod properties;
mod rate_workspace;
mod readme;
mod reproduction;
mod rod;
mod scenes;
mod shape;
mod solver2d;
mod swegle;
mod swegle3d;
mod throughput3d;
mod timestep_bounds;
mod tradeoff;
mod vonneumann;
mod vonneumann2d;
mod vonneumann3d;
