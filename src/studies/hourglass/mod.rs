//! The tensile-or-hourglass study (`sphstab hourglass`, issue 30): is the growth that updated-
//! Lagrangian SPH solids show in tension a tensile instability, or a zero-energy (hourglass)
//! mode that the stress drives? Every remedy — the classical form, Monaghan–Gray artificial
//! stress, the corrected (Bonet–Lok) gradient, SPH-ENOG, the total-Lagrangian form with and
//! without Ganzenmüller's control, tl-enog — is asked, on the lattice, over pre-stress states
//! (isotropic and uniaxial tension, pure shear, compression), stress magnitudes and Poisson
//! ratios (G/K):
//! - whether it has zero-energy modes at rest;
//! - its growth against |σ̄|, split by the classification into the growth on hourglass modes
//!   (zero-energy at zero stress) and the rest;
//! - the onset stress of any growth of its own (refined by bisection; 0 when an hourglass mode
//!   grows: it grows at any stress), next to the stress at which the continuum itself fails;
//! - a stability map over (|σ̄|, G/K);
//! - the wave-speed errors it costs at rest.
//!
//! All from the one linearisation of each form's rate function ([`crate::analysis::query`]).

mod config;
mod experiment;
mod figure;
mod report;
mod run;

pub use config::{HourglassConfig, Remedy, StressState, default_remedies, parse_config};
pub use experiment::{
    Experiment, ExperimentKind, ExperimentReport, Oscillation, experiment_text, parse_experiment,
};
pub use figure::figure_svg;
pub use report::{
    Cost, CurvePoint, HourglassReport, RemedyReport, StateReport, note_markdown, onset_text, table,
};
pub use run::{COST_KAPPAS, run, shear_over_bulk};
