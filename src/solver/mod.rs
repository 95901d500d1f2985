//! The reference time-domain solver: it integrates the forms' rate function
//! ([`crate::forms::Model::rate`], in 1D, 2D and 3D, every form) with the shared integrators
//! ([`crate::integrator`]) — the same definitions the von Neumann engine linearises (SPEC §4).

pub mod diagnostics;
pub mod output;
pub mod rod;
pub mod run;
pub mod scene;
pub mod thesis_wave;

pub use run::{BoundaryDensity, J2, Mirror, Run, System, SystemBuffers};
