//! # sphstab — stability of SPH forms, kernels, smoothing lengths and time steps
//!
//! For a chosen SPH form ([`forms::FormKind`]), kernel ([`kernel`]), shape-function family
//! ([`shape::ShapeFamily`]), smoothing length, pre-stress and time step, sphstab computes in 1D,
//! 2D and 3D the dispersion relation ω²(κ), the amplification factors and the critical time step
//! of any of twelve time integrators, and names every instability
//! ([`vonneumann::classify::Kind`]). A reference particle solver runs the same forms, and the
//! studies ([`studies`]) set the two against each other and against the papers.
//!
//! ## The architecture rule
//! Each form is defined once, as the rate function of its semi-discrete particle system
//! ([`forms`], in D = 1, 2, 3). The reference solver ([`solver`]: 1D scenes, 2D and 3D blocks)
//! integrates it with any of the twelve time integrators of [`integrator`]; the numeric von
//! Neumann engine ([`vonneumann::linearise`]: the 1D chain and the D-dimensional
//! [`vonneumann::linearise::Bloch`] front ends of one core) linearises *the same function*
//! exactly (forward-mode [`scalar::Dual`] numbers) about the uniformly pre-stressed periodic
//! lattice and projects it onto Fourier modes; the amplification matrix is the same integrator
//! step applied to one mode ([`vonneumann::amplification`]). The papers' closed forms
//! ([`vonneumann::closed_form`]) and this project's derived ones ([`vonneumann::derived`]) are
//! independent checks; disagreements are listed in `analysis/ERRATA.md`.
//!
//! ## Layers
//! Bottom to top, each importing only from below (docs/ARCHITECTURE.md; `tests/it/layers.rs`
//! checks it): core → integrator → forms → engine → analysis | solver → studies → figures. The
//! solver never imports the analysis or the engine (it is their independent check); [`plot`]
//! takes plain series and imports core only. The library knows no command line: errors name
//! fields ([`error::Text`]), the budget is passed in ([`budget::Budget`]), long work reports to
//! a [`progress::Progress`].
//!
//! ## Conventions
//! - Lengths in units of the particle spacing Δx; wave number κΔx ∈ (0, π].
//! - Material speed c = sqrt(C/ρ0), C the tangent modulus (Truesdell rate, as in \[B00\]: in 1D
//!   σ̇ = (C + σ) ∂v/∂x, continuum modulus C̄ = C + σ). Frequencies and growth rates in c/Δx,
//!   times and time steps in Δx/c (a field or flag that sets Δt in Δx/c is named `dt`).
//! - The CFL number is c Δt/h, h in the kernel's own convention (`critical_cfl` =
//!   `critical_dt` / (h/Δx)); it is never a name for Δt in Δx/c.
//! - A run with physical units (a 1D scene in SI, the Swegle test in its own units) reports what
//!   it measures in those units, with the scales that normalise them (fields named `_physical`:
//!   Δt, Δx, c and, for a scene, C).
//! - Stress σ̄ = σ/C, positive in tension; pressure p = −σ.
//! - Perturbation ~ exp(iκX + st); semi-discrete ω² = −s²; growth rate γ = max Re s ≥ 0.
//!   Fully discrete: amplification factor λ per step, amplifying when |λ| > 1 + 1e-7
//!   ([`vonneumann::amplification::AMPLIFICATION_TOL`]). Every tolerance is a named constant.
//! - Kernels: W(r, h) = σ_d h^−d f(r/h), support radius R = ζh; `h` is in the kernel's own
//!   convention and R/Δx is Belytschko's dilation D_mx.
//! - Results in normalised units do not depend on the physical Δx, ρ0 or C
//!   ([`vonneumann::linearise::Lattice1D`]).
//!
//! ## Catalogue
//! | layer | module | contents |
//! |---|---|---|
//! | core | [`scalar`], [`kernel`], [`shape`], [`lattice`], [`neighbours`] | dual numbers; the eleven kernels of SPEC §2; `sph`, `shepard`, `mls`, `corrected`; lattices in 1D–3D; cell lists |
//! | core | [`error`], [`display`], [`params`], [`budget`], [`progress`] | errors naming fields; numbers as people read them; the shared parameter checks; the resource budget; progress reports |
//! | integrator | [`integrator`] | twelve time integrators: one step for the solver, one amplification for the engine |
//! | forms | [`forms`] | the rate functions (allocation-free evaluation with [`forms::RateWorkspace`]) |
//! | engine | [`vonneumann`] | linearisation, amplification, classification, closed forms, kernel transforms |
//! | analysis | [`analysis`] | `query`, `dispersion`, `timestep`, maps, box prediction (1D chain, 2D/3D zone) |
//! | solver | [`solver`] | the reference solver: 1D scenes, 2D and 3D blocks, any integrator |
//! | studies | [`studies`] | Swegle test, box operator, throughput, trade-off, atlas, pairing, artificial stress, kernel guide |
//! | figures | [`figures`], [`plot`] | figures from `analysis/configs`; SVG plots from plain series |
//!
//! References: \[B00] Belytschko, Guo, Liu, Xiao 2000; [V21\] Vignjevic, De Vuyst, Campbell 2021;
//! \[B98] Belytschko, Krongauz, Dolbow, Gerlach 1998; [T\] thesis on total-Lagrangian SPH.

pub mod analysis;
pub mod budget;
pub mod display;
pub mod error;
pub mod figures;
pub mod forms;
pub mod integrator;
pub mod kernel;
pub mod lattice;
pub mod neighbours;
pub mod params;
pub mod plot;
pub mod progress;
pub mod scalar;
pub mod shape;
pub mod solver;
pub mod studies;
pub mod units;
pub mod vonneumann;
