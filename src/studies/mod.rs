//! The studies: questions answered by running the analysis, the solver or both over many
//! configurations, each in its own folder (config, run, report), sharing the config plumbing of
//! [`config`] and, for the studies that run longer than a minute, the shards of [`shard`].

pub mod art_stress;
pub mod atlas;
pub mod box_operator;
pub mod config;
pub mod finite_body;
pub mod galerkin;
pub mod hourglass;
pub mod interpolation;
pub mod kernel_guide;
pub mod pairing;
pub mod shard;
pub mod stable_dt;
pub mod stored;
pub mod swegle;
pub mod throughput;
pub mod tradeoff;

/// The form, kernel and integrator names of the library, whose series every figure draws in
/// one style each ([`crate::plot::style::named_style`]): the lists of [`crate::forms::FormKind`],
/// [`crate::kernel::all`] and [`crate::integrator::INTEGRATOR_NAMES`], in their order.
pub fn series_names() -> crate::plot::style::Names {
    crate::plot::style::Names(vec![
        crate::forms::FormKind::ALL.iter().map(|f| f.1).collect(),
        crate::kernel::all().iter().map(|k| k.name()).collect(),
        crate::integrator::INTEGRATOR_NAMES.to_vec(),
    ])
}
