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
//! The 1D model [`Model1D`] evaluates the forms of every dimension through its
//! [`Model<1>`](Model) (views of its fields, no copies) and adds the stress points and the
//! consistent mass of the 1D-only forms of \[B00\]. Its reusable buffers are one
//! [`Workspace1D<S>`](Workspace1D) ([`Model1D::rate_with`]; it holds the D = 1
//! [`RateWorkspace`]), which may serve any number of models in turn; the least-squares
//! consistent mass is solved in O(N) by [`BandedLu`].
//!
//! Material law: hypo-elastic with the Truesdell (or Jaumann) rate and tangent modulus
//! C = λ + 2G, as in \[B00 §2\]; in 1D `σ̇ = (C + σ) ∂v/∂x`, so the continuum modulus is
//! `C̄ = C + σ` (\[B00\] eq 29/75) and a compressive pre-stress σ̄ = σ/C ≤ −1 is a material
//! instability. The total-Lagrangian forms integrate the same law: `P(F) = (σ0 + C) F − C` in
//! 1D, whose tangent at F = 1 is `C̄^{SE} = C + σ0` (\[B00\] eq 81); in 2D/3D St Venant–Kirchhoff
//! with the tangent of the Eulerian law. Hydrodynamic (p = K(ρ/ρ0 − 1)) and neo-Hookean
//! materials in 2D and 3D.

mod eulerian_common;
mod lagrangian_stress_points;
mod least_squares;
mod model;
mod model_nd;
mod rates;
mod stress_points;
pub(crate) mod workspace;

pub use least_squares::BandedLu;
pub use model::{
    ArtificialViscosity, Field, FieldKind, FlatCache, FlatSystem, MassOperator, Model1D,
    ModelParams, State1D, Workspace1D,
};
pub use model_nd::{
    ArtificialStress, AuxRates, AuxRates2D, Comp, Comp2, DELTA_RANGE, DIFFUSION_FORM_NAMES,
    DensityDiffusion, DiffusionForm, Material, Material2D, Model, Model2D, Model3D, ModelParams2D,
    ObjectiveRate, RateOut, RateOut2D, State, State2D, State3D, StateView, StateView2D, Tensor,
    n_sym, voigt,
};
pub use workspace::RateWorkspace;

use crate::error::{Error, Result};
use crate::shape::ShapeFamily;

/// The nine SPH forms.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FormKind {
    /// Eulerian kernel, collocation, Monaghan's symmetric "sum" momentum form \[V21 eq 55\].
    Classical,
    /// Eulerian kernel, "difference" momentum form \[V21 eq 54\].
    Nonlocal,
    /// Normalised corrected SPH \[V21 eq 43–44\].
    Local,
    /// Mixed local–nonlocal with partition coefficient c \[V21 eq 50–56\].
    Lnl,
    /// Mixed classical–local with coefficient c \[V21 §7.2\].
    Cll,
    /// Lagrangian kernel, nodal integration \[B00 eq 77–81\].
    TotalLagrangian,
    /// Stress points at mid-intervals, Eulerian kernel \[B00 eq 83–92\].
    EulerianStressPoints,
    /// Stress points at mid-intervals, Lagrangian kernel \[B00 eq 99–102\].
    LagrangianStressPoints,
    /// Beissel–Belytschko least-squares stabilised nodal integration \[B00 eq 104–107\].
    LeastSquares,
    /// Eulerian kernel, nodal integration of the Galerkin weak form \[B00 §4.1.1, eq 65–68\]:
    /// the system whose linearisation is \[B00 eq 74\]. Not one of SPEC's nine names; added
    /// because the sum-form `classical` differs from eq 74 (analysis/ERRATA.md).
    EulerianNodal,
}

impl FormKind {
    /// All forms with their CLI names.
    pub const ALL: [(FormKind, &'static str); 10] = [
        (FormKind::Classical, "classical"),
        (FormKind::Nonlocal, "nonlocal"),
        (FormKind::Local, "local"),
        (FormKind::Lnl, "lnl"),
        (FormKind::Cll, "cll"),
        (FormKind::TotalLagrangian, "total-lagrangian"),
        (FormKind::EulerianStressPoints, "eulerian-stress-points"),
        (FormKind::LagrangianStressPoints, "lagrangian-stress-points"),
        (FormKind::LeastSquares, "least-squares"),
        (FormKind::EulerianNodal, "eulerian-nodal"),
    ];

    /// CLI name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }

    /// Looks a form up by CLI name.
    pub fn by_name(name: &str) -> Result<Self> {
        crate::error::lookup("form", &Self::ALL, name)
    }

    /// Lagrangian kernel (reference-configuration shape functions, fixed neighbours).
    pub fn is_lagrangian(self) -> bool {
        matches!(
            self,
            FormKind::TotalLagrangian | FormKind::LagrangianStressPoints | FormKind::LeastSquares
        )
    }

    /// Default shape family: `sph` for the SPH (V21) forms, `corrected` for the local form,
    /// and `mls` (EFG, the choice of \[B00\]) for the B00 forms.
    pub fn default_shape(self) -> ShapeFamily {
        match self {
            FormKind::Classical | FormKind::Nonlocal | FormKind::Lnl | FormKind::Cll => {
                ShapeFamily::Sph
            }
            FormKind::Local => ShapeFamily::Corrected,
            FormKind::TotalLagrangian
            | FormKind::EulerianStressPoints
            | FormKind::LagrangianStressPoints
            | FormKind::LeastSquares
            | FormKind::EulerianNodal => ShapeFamily::Mls,
        }
    }

    /// Checks that `shape` is meaningful for this form.
    pub fn check_shape(self, shape: ShapeFamily) -> Result<()> {
        if self == FormKind::Local && !shape.linear_consistent_gradient() {
            return Err(Error::Incompatible(format!(
                "--shape {} is not allowed with --form local: the local form needs a first-order \
                 corrected gradient (allowed: corrected, mls)",
                shape.name()
            ).into()));
        }
        Ok(())
    }

    /// The state fields this form carries.
    pub fn fields(self) -> &'static [Field] {
        use Field::*;
        match self {
            FormKind::Classical
            | FormKind::Nonlocal
            | FormKind::Local
            | FormKind::EulerianNodal => &[X, V, Rho, Sigma],
            FormKind::Lnl | FormKind::Cll => &[X, V, Rho, Sigma, Tau],
            FormKind::TotalLagrangian
            | FormKind::LagrangianStressPoints
            | FormKind::LeastSquares => &[X, V],
            FormKind::EulerianStressPoints => &[X, V, Rho, Sigma, SpX, SpSigma, SpVol],
        }
    }

    /// Whether the form has stress points.
    pub fn has_stress_points(self) -> bool {
        matches!(
            self,
            FormKind::EulerianStressPoints | FormKind::LagrangianStressPoints
        )
    }
}

impl Model1D {
    /// The rate function of the semi-discrete system: fills `out` with the time derivatives of
    /// every field of `z`. For [`MassOperator::Lumped`] the `v` rate is the acceleration; for
    /// [`MassOperator::Consistent`] it is the generalised force `f` of `M a = f`. Allocates a
    /// fresh [`Workspace1D`]: a loop of evaluations uses [`Model1D::rate_with`].
    pub fn rate<S: crate::scalar::Scalar>(
        &self,
        z: &State1D<S>,
        out: &mut State1D<S>,
    ) -> Result<()> {
        self.rate_with(z, out, &mut Workspace1D::new())
    }

    /// [`Model1D::rate`] with reusable buffers: `out` is resized to the shape of `z` (no
    /// allocation when it already has it) and the workspace's buffers are reused, so a loop
    /// of evaluations — the solver's time loop, or the linearisation over many cells — does
    /// not allocate once they have grown. The result does not depend on what the workspace
    /// was used for before (any model, any state).
    pub fn rate_with<S: crate::scalar::Scalar>(
        &self,
        z: &State1D<S>,
        out: &mut State1D<S>,
        ws: &mut Workspace1D<S>,
    ) -> Result<()> {
        out.resize_like(z);
        if let Some(nd) = &self.nd {
            if nd.mass != self.mass {
                return Err(Error::Incompatible(
                    "Model1D: masses edited in place; use Model1D::set_masses".into(),
                ));
            }
            // the forms of every dimension: the D = 1 rate on views of the 1D fields
            let view = StateView::<S, 1> {
                x: z.x.as_chunks().0,
                v: z.v.as_chunks().0,
                rho: &z.rho,
                sigma: z.sigma.as_chunks::<1>().0.as_chunks::<1>().0,
                tau: z.tau.as_chunks::<1>().0.as_chunks::<1>().0,
            };
            let rates = RateOut::<S, 1> {
                x: Some(out.x.as_chunks_mut().0),
                v: Some(out.v.as_chunks_mut().0),
                aux: Some(AuxRates {
                    rho: &mut out.rho,
                    sigma: out.sigma.as_chunks_mut::<1>().0.as_chunks_mut::<1>().0,
                    tau: out.tau.as_chunks_mut::<1>().0.as_chunks_mut::<1>().0,
                }),
            };
            return nd.rate_into(view, rates, &mut ws.nd);
        }
        match self.p.form {
            FormKind::LagrangianStressPoints => lagrangian_stress_points::rate(self, z, out, ws),
            FormKind::EulerianStressPoints | FormKind::EulerianNodal => {
                stress_points::rate(self, z, out, ws)
            }
            FormKind::LeastSquares => least_squares::rate(self, z, out),
            f => Err(Error::Incompatible(
                format!("--form {}: no 1D model was built", f.name()).into(),
            )),
        }
    }
}
