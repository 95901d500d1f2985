//! The integration tests, in one binary (`cargo test --release --test it`): one module per
//! topic, so that the suite compiles and links once instead of once per file. Run one topic
//! with a filter, e.g. `cargo test --release --test it -- damping::`. `common` holds the shared
//! helpers.
//!
//! The allocation-counting tests are in their own binary (`tests/no_alloc/`): they install a
//! counting global allocator, which would see the allocations of every test running in
//! parallel here.
//!
//! Slow studies are `#[ignore]`d only where a faster test of the same claim runs in the default
//! suite (each names it); `.ci/run` runs them, with the documented commands (`docs::`).

mod common;

// kernels, shape functions, derivatives
mod derivative_audit;
mod interpolation;
mod kernels;
mod layers;
mod shape;

// the von Neumann engine: closed forms, classification, the papers' statements
mod antiplane;
mod classify;
mod closed_form;
mod core_claim;
mod damping;
mod derived;
mod diffusion;
mod extremes;
mod fast_paths;
mod papers;
mod properties;
mod solid_stabilisation;
mod timestep_bounds;
mod vonneumann;
mod vonneumann2d;
mod vonneumann3d;

// time integrators
mod integrator;
mod integrators;
mod long_run;
mod stable_dt;

// the reference solver against the engine
mod boundary_loads;
mod galerkin;
mod hourglass;
mod pair_reuse;
mod plasticity;
mod rate_workspace;
mod rod;
mod scenes;
mod solver2d;
mod swegle;
mod swegle3d;
mod symmetry;

// golden data of the engine and the solver
mod golden;
mod golden_analysis;
mod golden_solver1d;
mod golden_solver2d;

// studies, figures and the documents generated from the code
mod art_stress;
mod docs;
mod export;
mod figures;
mod kernel_guide;
mod pairing;
mod print;
mod reproduction;
mod shard;
mod tradeoff;

// the command line
mod cli;
mod cli2d;
mod cli_throughput;
mod compare;
mod fuzz_cli;
mod limits;
mod throughput3d;
mod units;
