//! The von Neumann engine: closed forms from the papers and the numeric linearisation of the
//! forms' rate functions.

pub mod amplification;
pub mod antiplane;
pub mod classify;
pub mod closed_form;
pub mod derived;
pub mod derived2d;
pub mod linearise;
pub mod timestep_bounds;
pub mod transform;

/// The former path of [`linearise::bloch`] (kept for callers not yet moved).
pub use linearise::bloch as linearise2d;
