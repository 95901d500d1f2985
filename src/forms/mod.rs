//! SPH forms (SPEC §4). Each form is ONE rate function of its semi-discrete particle system;
//! the solver integrates it and the von Neumann engine linearises the same function — in every
//! dimension.
//!
//! # The dimension is a parameter
//!
//! The model, its state and the rate functions are generic over the dimension with a const
//! generic `D ∈ {1, 2, 3}`: positions and velocities are `[S; D]`, the stress a symmetric
//! `[[S; D]; D]` (rates computed on the upper triangle and mirrored, so an integrated stress stays
//! exactly symmetric), small tensor algebra written with explicit indices over `0..D` (no
//! heap, no nalgebra in the inner loops: the scalar `S` is `f64` for the solver and a dual
//! number for the linearisation). [`Model<D>`](Model) holds the parameters, masses and
//! reference data; [`State<S, D>`](State) the fields; one [`RateWorkspace<S, D>`] the reusable
//! buffers (cell list [`crate::neighbours::CellList<D>`], stencils), so a time loop does not
//! allocate in any dimension.
//!
//! | form | where its rate is defined (1D, 2D and 3D alike) |
//! |---|---|
//! | classical, nonlocal, local, lnl, cll | `rates::rate`: one routine, the momentum term per form (\[V21 eq 53–56\]): `div_sum` (classical, cll's nonlocal part), `div_difference` (nonlocal, local, lnl); continuity and stress rates from the velocity gradient of the form's stencil |
//! | total-lagrangian | `rates::rate_tl` (\[B00 eq 77–81\] in D dimensions) |
//! | eulerian-stress-points, eulerian-nodal | `stress_points.rs` (1D only, \[B00 §4.1.1, §4.2.1\]) |
//! | lagrangian-stress-points | `lagrangian_stress_points.rs` (1D only, \[B00 eq 99–102\]) |
//! | least-squares | `least_squares.rs` (1D only, \[B00 §4.3\]) |
//!
//! The 1D-only forms of \[B00\] are forms of the same [`Model`]: with D = 1 it builds their
//! reference data (stress points, reference stencils, least-squares matrices) and
//! [`Model::rate`] evaluates them on the state's flat D = 1 fields (`chain_rates.rs`); for
//! D > 1 [`Model::new`] refuses them with an error naming the form and the dimension. The
//! least-squares form has a consistent mass ([`Model::mass_operator`]), solved in O(N) by
//! [`BandedLu`].
//!
//! Modules, each importing only those above it in this list: `kind` (the form names),
//! `params`, `state`, `chain_search`, `chain_data`, `model`, `workspace`, then the rate
//! functions (`rates`, `stress_points`, `lagrangian_stress_points`, `least_squares`,
//! `chain_rates`).
//!
//! Material law: hypo-elastic with the Truesdell (or Jaumann) rate and tangent modulus
//! C = λ + 2G, as in \[B00 §2\]; in 1D `σ̇ = (C + σ) ∂v/∂x`, so the continuum modulus is
//! `C̄ = C + σ` (\[B00\] eq 29/75) and a compressive pre-stress σ̄ = σ/C ≤ −1 is a material
//! instability. The total-Lagrangian forms integrate the same law: `P(F) = (σ0 + C) F − C` in
//! 1D, whose tangent at F = 1 is `C̄^{SE} = C + σ0` (\[B00\] eq 81); in 2D/3D St Venant–Kirchhoff
//! with the tangent of the Eulerian law. Hydrodynamic (p = K(ρ/ρ0 − 1)) and neo-Hookean
//! materials in 2D and 3D.

mod chain_data;
mod chain_rates;
mod chain_search;
mod kind;
mod lagrangian_stress_points;
mod least_squares;
mod model;
mod params;
mod rates;
mod state;
mod stress_points;
pub(crate) mod workspace;

pub use chain_data::MassOperator;
pub use kind::FormKind;
pub use least_squares::BandedLu;
pub use model::Model;
pub use params::{
    ArtificialStress, ArtificialViscosity, DELTA_RANGE, DIFFUSION_FORM_NAMES, DensityDiffusion,
    DiffusionForm, Material, ModelParams, ObjectiveRate, PrestressKind, ViscosityPairs,
};
pub use rates::neo_hookean_cauchy;
pub use state::{AuxRates, Comp, FieldKind, RateOut, State, StateView, Tensor, n_sym, voigt};
pub use workspace::{RateWorkspace, default_skin};
