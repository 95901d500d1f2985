//! Parameters of a particle model (any dimension): the material, the artificial viscosity and
//! stress, the δ-SPH density diffusion, and [`ModelParams`] that gathers them with the form,
//! shape family and kernel.

use super::kind::FormKind;
use crate::error::{Error, Result, field};
use crate::shape::{KernelParams, ShapeFamily};

/// Objective stress rate of the hypo-elastic law.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ObjectiveRate {
    /// Jaumann: σ̇ = C:d + Wσ − σW.
    Jaumann,
    /// Truesdell: σ̇ = C:d + Lσ + σLᵀ − tr(L)σ.
    Truesdell,
}

/// Material of the particle model (any dimension).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Material {
    /// p = K(ρ/ρ0 − 1), G = 0.
    Hydro {
        /// Bulk modulus K.
        bulk: f64,
    },
    /// Compressible neo-Hookean \[T eq 3.62–3.64\], total-Lagrangian forms only:
    /// P = μ(F − F⁻ᵀ) + λ ln J F⁻ᵀ (plane strain in 2D), linearised about the unstressed state.
    NeoHookean {
        /// Lamé λ.
        lambda: f64,
        /// Shear modulus μ.
        shear: f64,
    },
    /// Linear hypo-elastic.
    Elastic {
        /// Lamé λ.
        lambda: f64,
        /// Shear modulus G.
        shear: f64,
        /// Objective rate.
        rate: ObjectiveRate,
    },
}

impl Material {
    /// Elastic material with P-wave modulus `c` and Poisson ratio ν (3D Lamé constants; plane
    /// strain in 2D):
    /// G = c(1 − 2ν)/(2(1 − ν)), λ = cν/(1 − ν).
    pub fn elastic(c: f64, nu: f64, rate: ObjectiveRate) -> Result<Self> {
        crate::error::check_range("poisson", nu, -0.99, 0.5, true, false)?;
        Ok(Material::Elastic {
            lambda: c * nu / (1.0 - nu),
            shear: c * (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu)),
            rate,
        })
    }
    /// The material of a 1D bar of modulus C: the 1D law σ̇ = (C + σ) ∂v/∂x (\[B00 eq 29\]) is
    /// the hypo-elastic law with the Truesdell rate and P-wave modulus λ + 2G = C (written with
    /// G = 0, λ = C: in 1D only λ + 2G enters).
    pub fn bar(modulus: f64) -> Self {
        Material::Elastic {
            lambda: modulus,
            shear: 0.0,
            rate: ObjectiveRate::Truesdell,
        }
    }
    /// Tangent modulus C of the normalisation (K for hydro, λ + 2G for elastic).
    pub fn modulus(&self) -> f64 {
        match *self {
            Material::Hydro { bulk } => bulk,
            Material::Elastic { lambda, shear, .. } | Material::NeoHookean { lambda, shear } => {
                lambda + 2.0 * shear
            }
        }
    }
}

/// The shape Ŝ of a uniform pre-stress σ0 = σ̄ C Ŝ (σ̄ > 0 in tension): what a stability
/// question holds the lattice under.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PrestressKind {
    /// Ŝ = I: equal principal stresses (a stretched sheet, the Swegle test's pressure).
    #[default]
    Isotropic,
    /// Ŝ = e_x ⊗ e_x: one principal stress along the first lattice vector (a pulled bar).
    Uniaxial,
    /// Ŝ = e_x ⊗ e_y + e_y ⊗ e_x: pure shear, principal stresses ±σ̄C at 45° (D ≥ 2).
    Shear,
}

impl PrestressKind {
    /// The names, as the CLI and files spell them.
    pub const ALL: [(PrestressKind, &'static str); 3] = [
        (PrestressKind::Isotropic, "isotropic"),
        (PrestressKind::Uniaxial, "uniaxial"),
        (PrestressKind::Shear, "shear"),
    ];

    /// The variant of a name.
    pub fn by_name(name: &str) -> Result<Self> {
        crate::error::lookup("prestress", &Self::ALL, name)
    }

    /// The name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }

    /// Ŝ in D dimensions (the shear needs D ≥ 2: an error names `prestress` otherwise).
    pub fn unit<const D: usize>(self) -> Result<[[f64; D]; D]> {
        let mut t = [[0.0; D]; D];
        match self {
            PrestressKind::Isotropic => (0..D).for_each(|a| t[a][a] = 1.0),
            PrestressKind::Uniaxial => t[0][0] = 1.0,
            PrestressKind::Shear if D >= 2 => {
                t[0][1] = 1.0;
                t[1][0] = 1.0;
            }
            PrestressKind::Shear => {
                return Err(Error::Incompatible(
                    field("prestress") + " shear needs " + field("dim") + " 2 or 3",
                ));
            }
        }
        Ok(t)
    }
}

/// Monaghan (2000) / Gray, Monaghan & Swift (2001) artificial stress for the classical form:
/// R_I = −ε Σ_{λ>0} λ P_λ / ρ_I² from the tensile principal stresses of σ_I, adding
/// Σ_J m_J (R_I + R_J) f_IJⁿ ∇_I W_IJ with f_IJ = W(r_IJ)/W(Δp).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArtificialStress {
    /// ε (typically 0.2–0.3).
    pub eps: f64,
    /// Exponent n (typically 4).
    pub n: i32,
    /// Δp, the particle spacing of W(Δp).
    pub spacing: f64,
}

/// The δ-SPH density-diffusion term of the continuity equation (Molteni & Colagrossi 2009;
/// Antuono et al. 2010), added to ρ̇_I:
///
/// ```text
/// D_I = δ h c0 Σ_J ψ_IJ · ∇_I W_IJ V_J,   V_J = m_J/ρ_J,   x_JI = x_J − x_I,
/// molteni-colagrossi:  ψ_IJ = 2(ρ_J − ρ_I) x_JI/|x_JI|²
/// antuono:             ψ_IJ = 2(ρ_J − ρ_I) x_JI/|x_JI|² − (⟨∇ρ⟩_I + ⟨∇ρ⟩_J),
///                      ⟨∇ρ⟩_I = M_I⁻¹ Σ_J (ρ_J − ρ_I) ∇_I W_IJ V_J,  M_I = Σ_J ∇_I W_IJ ⊗ x_JI V_J
/// ```
///
/// The Molteni–Colagrossi term diffuses any density variation (O(k²) damping of long waves, and
/// of a hydrostatic gradient); Antuono's renormalised-gradient correction removes the part a
/// linear density field produces, so long waves are damped at O(k⁴) while the shortest (k = π/Δx,
/// where the gradient estimate vanishes) are damped as strongly as without it. Both act on the
/// density only, and need a density state (not the total-Lagrangian form).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DensityDiffusion {
    /// δ (typically 0.1).
    pub delta: f64,
    /// Which ψ.
    pub form: DiffusionForm,
    /// c0 (physical units).
    pub sound_speed: f64,
}

/// The two δ-SPH diffusion terms of [`DensityDiffusion`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiffusionForm {
    /// Molteni & Colagrossi (2009).
    MolteniColagrossi,
    /// Antuono, Colagrossi, Marrone & Molteni (2010).
    Antuono,
}

/// The CLI names of [`DiffusionForm`].
pub const DIFFUSION_FORM_NAMES: [&str; 2] = ["molteni-colagrossi", "antuono"];

/// Allowed range of δ.
pub const DELTA_RANGE: (f64, f64) = (0.0, 10.0);

impl DiffusionForm {
    /// The form of a CLI name.
    pub fn from_name(name: &str) -> Result<Self> {
        match name {
            "molteni-colagrossi" => Ok(Self::MolteniColagrossi),
            "antuono" => Ok(Self::Antuono),
            _ => Err(Error::UnknownName {
                what: "density-diffusion form".into(),
                given: name.to_string(),
                valid: DIFFUSION_FORM_NAMES.join(", ").into(),
            }),
        }
    }
    /// The CLI name.
    pub fn name(self) -> &'static str {
        match self {
            Self::MolteniColagrossi => DIFFUSION_FORM_NAMES[0],
            Self::Antuono => DIFFUSION_FORM_NAMES[1],
        }
    }
}

impl DensityDiffusion {
    /// Checks δ (the field `name`, e.g. `delta`) and the form's compatibility.
    pub fn check(&self, name: &'static str, form: FormKind) -> Result<()> {
        crate::error::check_range(name, self.delta, DELTA_RANGE.0, DELTA_RANGE.1, true, true)?;
        if form.is_total_lagrangian() {
            return Err(Error::Incompatible(
                field(name)
                    + " (density diffusion) does not apply to "
                    + field("form")
                    + format!(" {}: it has no density state", form.name()),
            ));
        }
        Ok(())
    }
}

/// Monaghan artificial viscosity Π_IJ = (−α c μ_IJ + β μ_IJ²)/ρ̄_IJ,
/// μ_IJ = h v_IJ·x_IJ / (x_IJ² + 0.01 h²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArtificialViscosity {
    /// Linear coefficient α.
    pub alpha: f64,
    /// Quadratic coefficient β (vanishes in a linearisation about rest).
    pub beta: f64,
    /// Sound speed used in Π (physical units).
    pub sound_speed: f64,
    /// `true`: act only on approaching pairs (v_IJ·x_IJ < 0), as in running codes.
    /// `false`: act on all pairs — the linearisation used by \[V21 App. B\] (Q ≈ −α Δẋ).
    pub approaching_only: bool,
}

/// Which pairs Monaghan viscosity acts on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ViscosityPairs {
    /// Approaching pairs only (v_IJ·x_IJ < 0), as SPH codes apply it: the solver's default.
    #[default]
    OneSided,
    /// Every pair, receding ones too: the linearisation of the analysis (\[V21 App. B\]).
    TwoSided,
}

impl ViscosityPairs {
    /// The names, as the CLI and the scene files spell them.
    pub const ALL: [(ViscosityPairs, &'static str); 2] = [
        (ViscosityPairs::OneSided, "one-sided"),
        (ViscosityPairs::TwoSided, "two-sided"),
    ];

    /// The variant of a name (`what`: the flag or field in the error).
    pub fn by_name(what: &'static str, name: &str) -> Result<Self> {
        crate::error::lookup(what, &Self::ALL, name)
    }

    /// The name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }

    /// [`ArtificialViscosity::approaching_only`].
    pub fn approaching_only(self) -> bool {
        self == ViscosityPairs::OneSided
    }
}

/// Parameters of a particle model (any dimension).
#[derive(Clone, Copy, Debug)]
pub struct ModelParams {
    /// The form.
    pub form: FormKind,
    /// Shape family.
    pub shape: ShapeFamily,
    /// Kernel and h.
    pub kp: KernelParams,
    /// Material.
    pub material: Material,
    /// Reference density ρ0.
    pub rho0: f64,
    /// Partition coefficient c of lnl / cll.
    pub c_partition: f64,
    /// Optional artificial viscosity.
    pub av: Option<ArtificialViscosity>,
    /// Optional artificial stress (classical and cll forms).
    pub art_stress: Option<ArtificialStress>,
    /// Optional δ-SPH density diffusion (forms with a density state).
    pub diffusion: Option<DensityDiffusion>,
    /// Least-squares stabilisation α_s (`least-squares` form only; β = α_s l_c²).
    pub alpha_s: f64,
    /// The length l_c of the least-squares stabilisation, physical units (the particle
    /// spacing Δx, as in \[B00 §4.3\]).
    pub ls_length: f64,
    /// The coefficient of the form's hourglass (zero-energy) control, dimensionless; `None`
    /// takes the form's default:
    /// - `enog`: ζ of the shear acceleration (default 0.7D + 2.1, SPHinXsys's);
    /// - `tl-enog`: κ of the pairwise shear term (default 1.07, SPHinXsys's);
    /// - `total-lagrangian`: Ganzenmüller's α (default: none, no hourglass control);
    ///
    /// refused for the other forms.
    pub hourglass: Option<f64>,
}
