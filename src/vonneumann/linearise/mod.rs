//! The numeric route: linearise a form's rate function about the uniformly pre-stressed periodic
//! lattice and project onto Fourier (Bloch) modes. One core ([`columns`]: dual-number Jacobian
//! columns, Bloch sum, rest-structure check, mechanical reduction, amplification of one mode) and
//! two front ends: [`chain`] (1D, every 1D form incl. stress points and consistent mass) and
//! [`bloch`] (any D on a lattice: polarisations, lattices, planes).

pub mod bloch;
pub mod chain;
pub mod columns;

pub use bloch::{Bloch, base_state, check_patch_budget, lattice_particles, periodic_lattice};
pub use chain::{Dof, Lattice1D, Linearisation, ModeTable, PhaseTable, has_consistent_mass};
pub use columns::{Phase, REST_RATE_TOL, ZERO_SUM_TOL, eigen, eigen_stalls_first_attempt};
