//! # sphstab — stability of SPH forms, kernels, smoothing lengths and time steps
//!
//! For a chosen SPH form ([`forms::FormKind`]), kernel ([`kernel`]), shape-function family
//! ([`shape::ShapeFamily`]), smoothing length, pre-stress and time step, sphstab computes the
//! dispersion relation ω²(κ), the leapfrog amplification factors and the critical time step, and
//! names every instability ([`vonneumann::classify::Kind`]).
//!
//! ## The architecture rule
//! Each form is defined once, as the rate function of its semi-discrete particle system
//! ([`forms::Model1D::rate`]). A solver integrates it with [`integrator::kdk_step`]; the numeric
//! von Neumann engine ([`vonneumann::linearise`]: the 1D chain and the D-dimensional
//! [`vonneumann::linearise::Bloch`] front ends of one core) linearises *the same function*
//! exactly (forward-mode [`scalar::Dual`] numbers) about the uniformly pre-stressed periodic
//! lattice and projects it onto Fourier modes; the amplification matrix is the same leapfrog
//! step applied to one mode ([`vonneumann::amplification`]). The papers' closed forms
//! ([`vonneumann::closed_form`]) and this project's derived ones ([`vonneumann::derived`]) are
//! independent checks; disagreements are listed in `analysis/ERRATA.md`.
//!
//! ## Conventions
//! - Lengths in units of the particle spacing Δx; wave number κΔx ∈ (0, π].
//! - Material speed c = sqrt(C/ρ0), C the tangent modulus (Truesdell rate, as in \[B00\]: in 1D
//!   σ̇ = (C + σ) ∂v/∂x, continuum modulus C̄ = C + σ). Frequencies and growth rates in c/Δx,
//!   time steps in Δx/c.
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
//! | module | contents |
//! |---|---|
//! | [`kernel`] | the eleven kernels of SPEC §2 |
//! | [`shape`] | `sph`, `shepard`, `mls`, `corrected` |
//! | [`forms`] | the rate functions (2D: allocation-free evaluation with [`forms::RateWorkspace`]) |
//! | [`integrator`] | kick–drift–kick leapfrog |
//! | [`vonneumann`] | linearisation, amplification, classification, closed forms, kernel transforms |
//! | [`analysis`] | `query`, `dispersion`, `timestep`, maps, box prediction (1D chain, 2D/3D zone) |
//! | [`solver`] | the reference solver (1D, 2D), the Swegle test, [`solver::throughput`] |
//! | [`pairing`] | the 3D pairing study: growth under pressure vs neighbour number, kernel W* sign |
//! | [`kernel_guide`] | `kernels --table`: per kernel, critical CFL, phase error, h/Δx stable in compression (1D, 2D), tensile onset, W* sign (1D–3D) |
//! | [`tradeoff`], [`study`] | the speed/accuracy trade-off study; config and report plumbing of the `analysis/` studies |
//! | [`plot`], [`figures`] | SVG output |
//!
//! References: \[B00] Belytschko, Guo, Liu, Xiao 2000; [V21\] Vignjevic, De Vuyst, Campbell 2021;
//! \[B98] Belytschko, Krongauz, Dolbow, Gerlach 1998; [T\] thesis on total-Lagrangian SPH.

pub mod analysis;
pub mod budget;
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
pub mod vonneumann;
