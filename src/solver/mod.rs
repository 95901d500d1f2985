//! The reference time-domain solver: it integrates the forms' rate functions
//! ([`crate::forms::Model2D::rate`], [`crate::forms::Model1D::rate`]) with the shared leapfrog
//! step [`crate::integrator::kdk_step`] — the same definitions the von Neumann engine
//! linearises (SPEC §4).

pub mod diagnostics;
pub mod output;
pub mod rod;
pub mod run1d;
pub mod run2d;
pub mod scene;
pub mod thesis_wave;

pub use run1d::Run1D;
pub use run2d::{BoundaryDensity, Run, Run2D, Run3D};
