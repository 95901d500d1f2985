//! The reports of `query`, `dispersion` and `timestep`: one type each, one JSON schema in every
//! dimension ([`SCHEMA_VERSION`]). A field that does not apply in a dimension is absent, never
//! renamed; wave vectors are arrays of D components (1D: `[κΔx]`), branches are arrays of D
//! values (1D: the one mechanical branch). The schema is documented field by field here and in
//! docs/json.md.

use super::common::{IntegratorReport, Setup};
use super::query::{MaterialSpec, Query};
use crate::lattice::LatticeKind;
use crate::vonneumann::classify::Kind;
use serde::Serialize;

/// Version of the JSON schema of `query`, `dispersion` and `timestep` (every report carries it
/// as `schema_version`). Version 1: one schema for D = 1, 2, 3 (issue 23).
pub const SCHEMA_VERSION: u32 = 1;

/// The configuration every report starts with.
#[derive(Clone, Debug, Serialize)]
pub struct Header {
    /// [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// Dimension D (1, 2 or 3).
    pub dim: u8,
    /// Form, kernel, shape, h/Δx, R/Δx, σ̄.
    #[serde(flatten)]
    pub setup: Setup,
    /// Partition coefficient c (lnl, cll).
    pub c_partition: f64,
    /// 1D only: least-squares α_s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alpha_s: Option<f64>,
    /// D ≥ 2: the shape of the pre-stress σ̄ C Ŝ (absent in 1D, where it lies along the chain).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prestress: Option<crate::forms::PrestressKind>,
    /// Material (1D: the bar).
    pub material: MaterialSpec,
    /// Lattice (1D: the chain).
    pub lattice: LatticeKind,
    /// Nearest-neighbour distance in units of the lattice's Δx (crate::lattice: the spacing in
    /// 1D and 2D, the cube root of the volume per particle in 3D).
    pub nearest_neighbour_over_dx: f64,
}

impl Header {
    /// The header of question `q`; `nearest` is the nearest-neighbour distance (Δx).
    pub fn of<const D: usize>(q: &Query<D>, nearest: f64) -> Self {
        Self {
            schema_version: SCHEMA_VERSION,
            dim: D as u8,
            setup: q.setup(),
            c_partition: q.c_partition,
            alpha_s: (D == 1).then_some(q.alpha_s),
            prestress: (D > 1).then_some(q.prestress),
            material: q.material,
            lattice: q.lattice.kind,
            nearest_neighbour_over_dx: nearest,
        }
    }
}

impl std::fmt::Display for Header {
    /// One line: form / kernel / shape, h and R in Δx, σ̄; for D ≥ 2 also the material and the
    /// lattice.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.setup.fmt(f)?;
        if self.dim > 1 {
            if let Some(k) = self
                .prestress
                .filter(|&k| k != crate::forms::PrestressKind::Isotropic)
            {
                write!(f, " ({})", k.name())?;
            }
            write!(
                f,
                ", {}, {} (nearest neighbour {:.4}Δx)",
                self.material, self.lattice, self.nearest_neighbour_over_dx
            )?;
        }
        Ok(())
    }
}

/// Polarisation of a mode: real unit vector and the longitudinal fraction |ê·k̂|².
#[derive(Clone, Debug, Serialize)]
pub struct Polarisation {
    /// Unit polarisation (real part after removing the global phase); D components.
    pub vector: Vec<f64>,
    /// |ê·k̂|² (1 longitudinal, 0 transverse).
    pub longitudinal_fraction: f64,
}

/// One unstable or marginal set of wave vectors.
#[derive(Clone, Debug, Serialize)]
pub struct Instability {
    /// Kind.
    pub kind: Kind,
    /// Largest growth rate (c/Δx); 0 for zero-energy modes (they grow linearly); ln|λ|/Δt for
    /// time-step rows.
    pub growth_rate: f64,
    /// Wave vector of the largest growth (D components, units 1/Δx).
    pub kappa_at_max: Vec<f64>,
    /// Fraction of the sampled wave vectors affected.
    pub zone_fraction: f64,
    /// 1D only: smallest κΔx of the branch on the grid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kappa_min: Option<f64>,
    /// 1D only: largest κΔx of the branch on the grid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kappa_max: Option<f64>,
    /// 1D only: κΔx where ω² passes through ±∞ (a vanishing mass symbol), if it does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pole_at: Option<f64>,
    /// D ≥ 2, `hourglass` / `tensile` / `compressive`: ω²Δx²/c² of the growing mode's
    /// polarisation under the unstressed operator (its stiffness at zero stress, which the
    /// pre-stress overcomes; ≈ 0 for an hourglass mode).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unstressed_omega2: Option<f64>,
    /// D ≥ 2, with `unstressed_omega2`: the σ̄ at which that mode starts to grow, by linear
    /// continuation of its ω² from zero stress to the question's (σ̄ E/(E + γ²), E the
    /// unstressed ω², γ the growth rate; exact when the operator is linear in σ̄ and the
    /// polarisation does not turn with it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub onset_stress: Option<f64>,
}

/// Verdict of `query`.
#[derive(Clone, Debug, Serialize)]
pub struct QueryReport {
    /// Configuration.
    #[serde(flatten)]
    pub header: Header,
    /// Sampling of the wave vectors ([`Query::grid`]).
    pub grid: usize,
    /// No exponentially growing mode (and no time-step amplification at `dt`).
    pub stable: bool,
    /// Largest growth rate (c/Δx), 0 if stable.
    pub max_growth_rate: f64,
    /// Fastest wave vector (D components; null if nothing grows).
    pub kappa_at_max: Option<Vec<f64>>,
    /// Polarisation of the fastest growing mode of the semi-discrete system (null if none
    /// grows; 1D: the longitudinal `[1]`).
    pub polarisation: Option<Polarisation>,
    /// Unstable and marginal sets.
    pub instabilities: Vec<Instability>,
    /// Spurious zero-energy (rank-deficiency) modes, beyond the continuum's own zero branches.
    pub has_zero_energy_modes: bool,
    /// The rest state sits on a kink of the artificial stress ([`crate::analysis::Query::art_stress_kink`]):
    /// the verdict is one side's linearisation (only written when true).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub art_stress_kink: bool,
    /// Critical Δt of the integrator (Δx/c), null if the semi-discrete system grows.
    pub critical_dt: Option<f64>,
    /// c Δt_crit / h.
    pub critical_cfl: Option<f64>,
    /// The Δt checked (Δx/c), if any.
    pub dt: Option<f64>,
    /// Largest |λ| at that Δt.
    pub max_amplification: Option<f64>,
    /// Time integrator of `critical_dt` and of the check at `dt`.
    pub integrator: &'static str,
    /// Growth per unit time (c/Δx) the integrator adds to the non-growing modes at `dt`
    /// (ln|λ|/Δt at the worst one; 0 if none, or no `dt`).
    pub spurious_growth_rate: f64,
}

impl QueryReport {
    /// The names of the kinds of instability found (rank deficiency excluded), each once.
    pub fn growth_kinds(&self) -> Vec<Kind> {
        let mut v = Vec::new();
        for i in &self.instabilities {
            if i.kind != Kind::RankDeficiency && !v.contains(&i.kind) {
                v.push(i.kind);
            }
        }
        v
    }
}

/// Dispersion along the high-symmetry path of the lattice (1D: Γ–X, κΔx ∈ (0, π]).
#[derive(Clone, Debug, Serialize)]
pub struct DispersionReport {
    /// Configuration.
    #[serde(flatten)]
    pub header: Header,
    /// Path labels and their arc-length positions (1D: Γ at 0, X at π).
    pub labels: Vec<(String, f64)>,
    /// Arc length along the path (units 1/Δx; 1D: κΔx).
    pub path: Vec<f64>,
    /// Wave vectors (D components each).
    pub kappa: Vec<Vec<f64>>,
    /// ω²Δx²/c² of the D branches at each wave vector, ascending (1D: the mechanical branch).
    pub omega2: Vec<Vec<f64>>,
    /// Growth rate at each wave vector (c/Δx).
    pub growth_rate: Vec<f64>,
    /// Continuum branches ω²Δx²/c², ascending: the D − 1 S (transverse) branches, then P
    /// (1D: (1 + σ̄)(κΔx)² \[B00 eq 32\]).
    pub omega2_continuum: Vec<Vec<f64>>,
    /// Dissipative systems only (absent otherwise): damping rate Re s (c/Δx, ≤ 0 when damped)
    /// of each branch (order of `omega2`) from the exact eigenvalues of J(κ); null where the
    /// matching of eigenvalue to branch is ambiguous (rule in [`crate::vonneumann::damping`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_rate: Option<Vec<Vec<Option<f64>>>>,
    /// Dissipative systems only: modal damping ratio ξ = −Re s/|s| of the same eigenvalues.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_ratio: Option<Vec<Vec<Option<f64>>>>,
}

impl DispersionReport {
    /// Branch `b` (0 = lowest) of ω² along the path.
    pub fn omega2_branch(&self, b: usize) -> Vec<f64> {
        self.omega2.iter().map(|w| w[b]).collect()
    }

    /// Continuum branch `b` along the path.
    pub fn continuum_branch(&self, b: usize) -> Vec<f64> {
        self.omega2_continuum.iter().map(|w| w[b]).collect()
    }

    /// Damping rate of branch `b` along the path (dissipative systems).
    pub fn damping_rate_branch(&self, b: usize) -> Option<Vec<Option<f64>>> {
        self.damping_rate
            .as_ref()
            .map(|r| r.iter().map(|w| w[b]).collect())
    }

    /// Damping ratio of branch `b` along the path (dissipative systems).
    pub fn damping_ratio_branch(&self, b: usize) -> Option<Vec<Option<f64>>> {
        self.damping_ratio
            .as_ref()
            .map(|r| r.iter().map(|w| w[b]).collect())
    }
}

/// Critical time step.
#[derive(Clone, Debug, Serialize)]
pub struct TimestepReport {
    /// Configuration.
    #[serde(flatten)]
    pub header: Header,
    /// Sampling of the wave vectors ([`Query::grid`]).
    pub grid: usize,
    /// 2/ω_max, the leapfrog limit \[B00 eq 120, ξ = 0\] (non-dissipative systems; null when
    /// the system is dissipative or grows).
    pub critical_dt_from_omega_max: Option<f64>,
    /// Dissipative systems only (absent otherwise): \[B00\] eq 120, min over the modes of
    /// (2/ω)(√(ξ² + 1) − ξ) with the modal (ω, ξ) of the semi-discrete eigenvalues
    /// ([`crate::vonneumann::damping::critical_dt_eq120`]); Δx/c. Absent when the
    /// semi-discrete system grows or no mode oscillates.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub critical_dt_eq120: Option<f64>,
    /// With artificial viscosity only (absent otherwise): the same integrator's critical Δt
    /// without viscosity. The analysis linearises Monaghan viscosity on every pair (two-sided,
    /// `critical_dt`); codes switch it off for receding pairs, a switch no linear analysis
    /// represents, and their limit lies in the bracket of the two (measured by issue 24: kdk
    /// 2.15 in [2.031, 2.465], dkd 1.8 in [1.0155, 2.465], 1D nonlocal m4 h = 1.3, α = 1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub critical_dt_inviscid: Option<f64>,
    /// Kind of the semi-discrete system's fastest growth (`step.physical_growth_rate`), as
    /// `query` classifies it; absent when nothing grows.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub physical_growth_kind: Option<crate::vonneumann::classify::Kind>,
    /// The integrator's critical Δt (also when the semi-discrete system grows: the largest Δt
    /// that adds no growth to it), CFL number, weak instability and added growth.
    #[serde(flatten)]
    pub step: IntegratorReport,
}
