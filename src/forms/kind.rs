//! The SPH forms by name ([`FormKind`]) and what each needs: kernel kind (Eulerian or
//! Lagrangian), default shape family, stress points.

use crate::error::{Error, Result, field};
use crate::shape::ShapeFamily;

/// The SPH forms.
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
    /// SPH-ENOG, the "essentially non-hourglass" updated-Lagrangian elastic SPH of Zhang,
    /// Lourenço, Wu, Zhang & Hu (J. Comput. Phys. 510, 2024): the pressure of the equation
    /// of state in the symmetric form −(1/ρ_I) Σ_J (p_I + p_J) ∇_I W_IJ V_J, and the shear as
    /// an accumulated, non-nested Laplacian-type acceleration a^s (a state); D ≥ 2, elastic.
    Enog,
    /// The total-Lagrangian form with SPHinXsys's pairwise shear term (Wu, Zhang, Tang & Hu,
    /// Comput. Methods Appl. Mech. Engrg. 407, 2023): the part G J^{−2/d} F of the first
    /// Piola–Kirchhoff stress taken by a pairwise Laplacian, scaled by κ; D ≥ 2.
    TlEnog,
}

impl FormKind {
    /// All forms with their CLI names.
    pub const ALL: [(FormKind, &'static str); 12] = [
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
        (FormKind::Enog, "enog"),
        (FormKind::TlEnog, "tl-enog"),
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
            FormKind::TotalLagrangian
                | FormKind::TlEnog
                | FormKind::LagrangianStressPoints
                | FormKind::LeastSquares
        )
    }

    /// Default shape family: `sph` for the SPH (V21) forms, `corrected` for the local form,
    /// and `mls` (EFG, the choice of \[B00\]) for the B00 forms.
    pub fn default_shape(self) -> ShapeFamily {
        match self {
            FormKind::Classical
            | FormKind::Nonlocal
            | FormKind::Lnl
            | FormKind::Cll
            | FormKind::Enog => ShapeFamily::Sph,
            // SPHinXsys's total-Lagrangian SPH: the kernel gradient corrected by B = A⁻¹
            FormKind::Local | FormKind::TlEnog => ShapeFamily::Corrected,
            FormKind::TotalLagrangian
            | FormKind::EulerianStressPoints
            | FormKind::LagrangianStressPoints
            | FormKind::LeastSquares
            | FormKind::EulerianNodal => ShapeFamily::Mls,
        }
    }

    /// Checks that `shape` is meaningful for this form.
    pub fn check_shape(self, shape: ShapeFamily) -> Result<()> {
        if self == FormKind::Enog && shape != ShapeFamily::Sph {
            return Err(Error::Incompatible(
                field("shape")
                    + format!(" {} is not allowed with ", shape.name())
                    + field("form")
                    + " enog: its pressure and shear terms are pair sums of the kernel gradient (allowed: sph)",
            ));
        }
        if self == FormKind::Local && !shape.linear_consistent_gradient() {
            return Err(Error::Incompatible(
                field("shape")
                    + format!(" {} is not allowed with ", shape.name())
                    + field("form")
                    + " local: the local form needs a first-order corrected gradient (allowed: \
                       corrected, mls)",
            ));
        }
        Ok(())
    }

    /// Whether the form is total-Lagrangian (reference stencils, nodal integration:
    /// `total-lagrangian`, `tl-enog`).
    pub fn is_total_lagrangian(self) -> bool {
        matches!(self, FormKind::TotalLagrangian | FormKind::TlEnog)
    }

    /// Whether the form is one of the forms of D ≥ 2 only (`enog`, `tl-enog`: shear terms of
    /// a solid, which a 1D bar does not have).
    pub fn needs_2d(self) -> bool {
        matches!(self, FormKind::Enog | FormKind::TlEnog)
    }

    /// Whether the form has stress points.
    pub fn has_stress_points(self) -> bool {
        matches!(
            self,
            FormKind::EulerianStressPoints | FormKind::LagrangianStressPoints
        )
    }
}
