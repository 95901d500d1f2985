//! The von Neumann engine: closed forms from the papers and the numeric linearisation of the
//! forms' rate functions.

pub mod amplification;
pub mod antiplane;
pub mod classify;
pub mod closed_form;
pub mod damping;
pub mod derived;
pub mod linearise;
pub mod maximise;
pub mod timestep_bounds;
pub mod transform;
