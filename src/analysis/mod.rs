//! High-level questions in every dimension: is a configuration stable (`query`), its dispersion,
//! its critical time step, growth-rate maps and the finite-box prediction. Inputs are validated
//! here so the library and the CLI give the same errors. One shared layer ([`common`]: report
//! setup; the engine's [`crate::vonneumann::amplification::critical_dt`] and
//! [`crate::vonneumann::classify::growth_kind`]) and two front ends: [`chain`] (1D, κΔx ∈ (0, π],
//! every 1D form) and [`zone`] / [`maps`] (D ∈ {2, 3}, the Brillouin zone of a lattice).

pub mod chain;
pub mod common;
pub mod maps;
pub mod zone;

pub use chain::{
    DispersionReport, Header, Query1D, QueryReport, TimestepReport, dispersion, query, timestep,
    timestep_with,
};
pub use common::{IntegratorReport, Setup, linearised_av};
pub use maps::{
    GrowthMap, MAX_BOX, MAX_BOX_3D, MAX_MAP_N, Plane, box_prediction, growth_map, max_box,
};
pub use zone::{
    Dispersion2D, Instability2D, MAX_GRID, MAX_PATH_POINTS, MaterialSpec, Polarisation, Query,
    QueryReport2D, continuum_moduli, default_grid, dispersion2d, fold, max_grid, query_nd, query2d,
};
