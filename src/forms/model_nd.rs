//! The particle model in D ∈ {1, 2, 3} dimensions ([`Model`]): parameters, materials and state.
//!
//! Vectors are `[S; D]`; the stress is a symmetric `[[S; D]; D]` (the rates are computed
//! symmetric, so an integrated stress stays exactly symmetric); its independent components are
//! numbered in the nested Voigt order of [`voigt`] (xx, yy, xy, zz, xz, yz: the first one in 1D,
//! the first three in 2D). Materials:
//! - `Hydro`: p = K(ρ/ρ0 − 1), σ = −p I, density by continuity (the Swegle test); tangent
//!   modulus C = K.
//! - `Elastic`: hypo-elastic σ̇ = λ tr(d) I + 2G d + (objective terms), with the Jaumann rate
//!   (Wσ − σW) or the Truesdell rate (Lσ + σLᵀ − tr(L)σ, which in 1D is the law of the 1D
//!   forms); tangent modulus C = λ + 2G (P-wave modulus; plane strain in 2D).
//! - total-Lagrangian forms: hydro is the fluid P = −p(J) cof F; elastic is St Venant–Kirchhoff
//!   about the pre-stress with the moduli that give the Eulerian law's tangent (see
//!   `rates::rate_tl`).

// Small-tensor algebra (D × D, D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::FormKind;
use super::model::ArtificialViscosity;
use crate::error::{Error, Result};
use crate::lattice::Lattice;
use crate::scalar::Scalar;
use crate::shape::KernelParams;
use crate::shape::ShapeFamily;

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

/// The 2D name of [`Material`].
pub type Material2D = Material;

impl Material {
    /// Elastic material with P-wave modulus `c` and Poisson ratio ν (3D Lamé constants; plane
    /// strain in 2D):
    /// G = c(1 − 2ν)/(2(1 − ν)), λ = cν/(1 − ν).
    pub fn elastic(c: f64, nu: f64, rate: ObjectiveRate) -> Result<Self> {
        crate::error::check_range("--poisson", nu, -0.99, 0.5, true, false)?;
        Ok(Material::Elastic {
            lambda: c * nu / (1.0 - nu),
            shear: c * (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu)),
            rate,
        })
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
    /// Checks δ (named `name`, e.g. `--delta`) and the form's compatibility.
    pub fn check(&self, name: &'static str, form: FormKind) -> Result<()> {
        crate::error::check_range(name, self.delta, DELTA_RANGE.0, DELTA_RANGE.1, true, true)?;
        if form == FormKind::TotalLagrangian {
            return Err(Error::Incompatible(
                crate::error::field(name)
                    + " (density diffusion) does not apply to --form total-lagrangian: it has no density state",
            ));
        }
        Ok(())
    }
}

/// Parameters of a particle model (any dimension).
#[derive(Clone, Copy, Debug)]
pub struct ModelParams2D {
    /// The form (classical, nonlocal, local, lnl, cll, total-lagrangian).
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
}

/// A particle model in D dimensions: parameters plus the constant per-particle data.
#[derive(Clone, Debug)]
pub struct Model<const D: usize> {
    /// Parameters.
    pub p: ModelParams2D,
    /// Periodic cell vectors (rows; None: open).
    pub period: Option<[[f64; D]; D]>,
    /// Inverse of the periodic cell matrix (fractional coordinates s = d · period_inv).
    period_inv: [[f64; D]; D],
    /// Whether the periodic cell is a rectangular box (off-diagonal entries of it and of its
    /// inverse exactly zero): [`Model::rel`] then works per component.
    period_diagonal: bool,
    /// Masses.
    pub mass: Vec<f64>,
    /// Reference positions.
    pub x_ref: Vec<[f64; D]>,
    /// Reference volumes.
    pub vol_ref: Vec<f64>,
    /// Isotropic pre-stress σ0 of the total-Lagrangian law.
    pub sigma0: f64,
    /// Reference stencils (total-Lagrangian): (master, φ, ∇φ) at each master.
    pub(crate) ref_master: Vec<Vec<(usize, f64, [f64; D])>>,
}

/// A 2D model.
pub type Model2D = Model<2>;
/// A 3D model.
pub type Model3D = Model<3>;

/// A symmetric D × D tensor (stress).
pub type Tensor<S, const D: usize> = [[S; D]; D];

/// State of a particle system; fields a form does not carry are empty.
#[derive(Clone, Debug)]
pub struct State<S, const D: usize> {
    /// Positions.
    pub x: Vec<[S; D]>,
    /// Velocities.
    pub v: Vec<[S; D]>,
    /// Densities.
    pub rho: Vec<S>,
    /// Stress σ (elastic).
    pub sigma: Vec<Tensor<S, D>>,
    /// Local stress τ (mixed forms, elastic).
    pub tau: Vec<Tensor<S, D>>,
}

impl<S, const D: usize> Default for State<S, D> {
    fn default() -> Self {
        Self {
            x: Vec::new(),
            v: Vec::new(),
            rho: Vec::new(),
            sigma: Vec::new(),
            tau: Vec::new(),
        }
    }
}

/// A 2D state.
pub type State2D<S> = State<S, 2>;
/// A 3D state.
pub type State3D<S> = State<S, 3>;

/// A borrowed [`State`]: the same fields as slices, so that a rate can be evaluated on the
/// solver's own buffers without assembling a `State`.
#[derive(Debug)]
pub struct StateView<'a, S, const D: usize> {
    /// Positions.
    pub x: &'a [[S; D]],
    /// Velocities.
    pub v: &'a [[S; D]],
    /// Densities (empty if the form carries none).
    pub rho: &'a [S],
    /// Stress σ (empty if not carried).
    pub sigma: &'a [Tensor<S, D>],
    /// Local stress τ (empty if not carried).
    pub tau: &'a [Tensor<S, D>],
}

/// A 2D state view.
pub type StateView2D<'a, S> = StateView<'a, S, 2>;

impl<S, const D: usize> Clone for StateView<'_, S, D> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S, const D: usize> Copy for StateView<'_, S, D> {}

/// Where a rate evaluation writes. A `None` part is neither computed nor written: the solver
/// asks for the accelerations and the auxiliary rates in separate calls.
#[derive(Debug)]
pub struct RateOut<'a, S, const D: usize> {
    /// ẋ = v.
    pub x: Option<&'a mut [[S; D]]>,
    /// Accelerations v̇.
    pub v: Option<&'a mut [[S; D]]>,
    /// Auxiliary rates (ρ̇, σ̇, τ̇), each as long as the state's field (possibly empty).
    pub aux: Option<AuxRates<'a, S, D>>,
}

impl<S, const D: usize> Default for RateOut<'_, S, D> {
    fn default() -> Self {
        Self {
            x: None,
            v: None,
            aux: None,
        }
    }
}

/// A 2D rate output.
pub type RateOut2D<'a, S> = RateOut<'a, S, 2>;

/// The auxiliary part of a [`RateOut`].
#[derive(Debug)]
pub struct AuxRates<'a, S, const D: usize> {
    /// ρ̇.
    pub rho: &'a mut [S],
    /// σ̇.
    pub sigma: &'a mut [Tensor<S, D>],
    /// τ̇.
    pub tau: &'a mut [Tensor<S, D>],
}

/// A 2D auxiliary-rate output.
pub type AuxRates2D<'a, S> = AuxRates<'a, S, 2>;

/// The (row, column) of the k-th independent component of a symmetric tensor, in the nested
/// Voigt order xx, yy, xy, zz, xz, yz (the first D(D+1)/2 are those of dimension D).
#[inline]
pub const fn voigt(k: usize) -> (usize, usize) {
    match k {
        0 => (0, 0),
        1 => (1, 1),
        2 => (0, 1),
        3 => (2, 2),
        4 => (0, 2),
        _ => (1, 2),
    }
}

/// Number of independent components of a symmetric D × D tensor.
#[inline]
pub const fn n_sym(d: usize) -> usize {
    d * (d + 1) / 2
}

/// A scalar component of the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Comp {
    /// Position component.
    X(usize),
    /// Velocity component.
    V(usize),
    /// Density.
    Rho,
    /// σ component, nested Voigt index ([`voigt`]: 0 xx, 1 yy, 2 xy, 3 zz, 4 xz, 5 yz).
    Sigma(usize),
    /// τ component (same numbering).
    Tau(usize),
}

/// The 2D name of [`Comp`].
pub type Comp2 = Comp;

impl Comp {
    /// Position / velocity / auxiliary.
    pub fn kind(self) -> super::FieldKind {
        match self {
            Comp::X(_) => super::FieldKind::Position,
            Comp::V(_) => super::FieldKind::Velocity,
            _ => super::FieldKind::Auxiliary,
        }
    }
}

impl<S: Scalar, const D: usize> State<S, D> {
    /// Component `c` of particle `i`.
    pub fn get(&self, c: Comp, i: usize) -> S {
        match c {
            Comp::X(a) => self.x[i][a],
            Comp::V(a) => self.v[i][a],
            Comp::Rho => self.rho[i],
            Comp::Sigma(k) => {
                let (a, b) = voigt(k);
                self.sigma[i][a][b]
            }
            Comp::Tau(k) => {
                let (a, b) = voigt(k);
                self.tau[i][a][b]
            }
        }
    }
    /// Sets component `c` of particle `i` (both entries of an off-diagonal tensor component).
    pub fn set(&mut self, c: Comp, i: usize, val: S) {
        match c {
            Comp::X(a) => self.x[i][a] = val,
            Comp::V(a) => self.v[i][a] = val,
            Comp::Rho => self.rho[i] = val,
            Comp::Sigma(k) => {
                let (a, b) = voigt(k);
                self.sigma[i][a][b] = val;
                self.sigma[i][b][a] = val;
            }
            Comp::Tau(k) => {
                let (a, b) = voigt(k);
                self.tau[i][a][b] = val;
                self.tau[i][b][a] = val;
            }
        }
    }
    /// The state as a [`StateView`].
    pub fn view(&self) -> StateView<'_, S, D> {
        StateView {
            x: &self.x,
            v: &self.v,
            rho: &self.rho,
            sigma: &self.sigma,
            tau: &self.tau,
        }
    }
    /// Every field of the state as an output ([`RateOut`] with all parts).
    pub fn as_rate_out(&mut self) -> RateOut<'_, S, D> {
        RateOut {
            x: Some(&mut self.x),
            v: Some(&mut self.v),
            aux: Some(AuxRates {
                rho: &mut self.rho,
                sigma: &mut self.sigma,
                tau: &mut self.tau,
            }),
        }
    }
    /// Gives every field the length of `o`'s (new entries zero); allocates only when a field
    /// grows beyond its capacity.
    pub fn resize_like<T>(&mut self, o: &State<T, D>) {
        self.x.resize(o.x.len(), [S::zero(); D]);
        self.v.resize(o.v.len(), [S::zero(); D]);
        self.rho.resize(o.rho.len(), S::zero());
        self.sigma.resize(o.sigma.len(), [[S::zero(); D]; D]);
        self.tau.resize(o.tau.len(), [[S::zero(); D]; D]);
    }
    /// Zeroed state shaped like `o`.
    pub fn zeros_like<T>(o: &State<T, D>) -> Self {
        let mut z = Self::default();
        z.resize_like(o);
        z
    }
    /// Converts every entry.
    pub fn map<T: Scalar>(&self, f: impl Fn(S) -> T + Copy) -> State<T, D> {
        let vec = |p: &[S; D]| p.map(f);
        let ten = |p: &Tensor<S, D>| p.map(|r| r.map(f));
        State {
            x: self.x.iter().map(vec).collect(),
            v: self.v.iter().map(vec).collect(),
            rho: self.rho.iter().map(|&p| f(p)).collect(),
            sigma: self.sigma.iter().map(ten).collect(),
            tau: self.tau.iter().map(ten).collect(),
        }
    }
}

impl FormKind {
    /// Whether the form is available in 2D and 3D (the B00 stress-point, least-squares and
    /// eulerian-nodal forms are 1D only).
    pub fn in_2d(self) -> bool {
        matches!(
            self,
            FormKind::Classical
                | FormKind::Nonlocal
                | FormKind::Local
                | FormKind::Lnl
                | FormKind::Cll
                | FormKind::TotalLagrangian
        )
    }

    /// Default shape family in 2D and 3D: as in 1D, except total-Lagrangian, whose closest
    /// multi-dimensional paper is the thesis \[T\] (TL SPH, `sph` shapes). (With `mls`, nodal
    /// integration of a pre-stressed rest state is not in equilibrium within two supports of a
    /// boundary: the residual force ∝ σ0 drifts a fixed-boundary box; see the closing notes of
    /// issue 4.)
    pub fn default_shape_2d(self) -> ShapeFamily {
        match self {
            FormKind::TotalLagrangian => ShapeFamily::Sph,
            f => f.default_shape(),
        }
    }

    /// The scalar components per particle in 2D for `material`.
    pub fn comps_2d(self, material: &Material) -> Vec<Comp> {
        self.comps(2, material)
    }

    /// The scalar components per particle in dimension `dim` for `material`: positions,
    /// velocities, then (Eulerian forms) density, and for elastic materials the D(D+1)/2
    /// independent stress components (and as many of τ for the mixed forms).
    pub fn comps(self, dim: usize, material: &Material) -> Vec<Comp> {
        let mut c: Vec<Comp> = (0..dim).map(Comp::X).chain((0..dim).map(Comp::V)).collect();
        if self == FormKind::TotalLagrangian {
            return c;
        }
        c.push(Comp::Rho);
        if matches!(
            material,
            Material::Elastic { .. } | Material::NeoHookean { .. }
        ) {
            c.extend((0..n_sym(dim)).map(Comp::Sigma));
            if matches!(self, FormKind::Lnl | FormKind::Cll) {
                c.extend((0..n_sym(dim)).map(Comp::Tau));
            }
        }
        c
    }
}

impl<const D: usize> Model<D> {
    /// A model of particles at `x_ref` with volumes `vol_ref` and current density `rho`
    /// (masses ρ V); `sigma0` is the isotropic pre-stress of the total-Lagrangian law.
    pub fn new(
        p: ModelParams2D,
        x_ref: Vec<[f64; D]>,
        vol_ref: Vec<f64>,
        rho: f64,
        sigma0: f64,
        period: Option<[[f64; D]; D]>,
    ) -> Result<Self> {
        if !p.form.in_2d() {
            return Err(Error::Incompatible(format!(
                "--form {} is not available with --dim {D} (classical, nonlocal, local, lnl, cll, total-lagrangian)",
                p.form.name()
            ).into()));
        }
        p.form.check_shape(p.shape)?;
        if let Material::NeoHookean { .. } = p.material {
            if p.form != FormKind::TotalLagrangian {
                return Err(Error::Incompatible(
                    "--material neo-hookean needs --form total-lagrangian".into(),
                ));
            }
            if sigma0 != 0.0 {
                return Err(Error::OutOfRange {
                    field: "--stress",
                    value: sigma0,
                    range: "neo-hookean: the reference state is unstressed, σ̄ must be 0".into(),
                });
            }
        }
        if let Some(d) = p.diffusion {
            d.check("--delta", p.form)?;
        }
        if D == 3 && p.art_stress.is_some() {
            return Err(Error::Incompatible(
                "--art-eps (artificial stress) is available with --dim 2 only".into(),
            ));
        }
        let period_inv = match period {
            Some(l) => {
                let inv = invert(&l);
                if inv.iter().flatten().any(|v| !v.is_finite()) {
                    return Err(Error::Incompatible(
                        "periodic cell: the cell vectors are linearly dependent".into(),
                    ));
                }
                inv
            }
            None => [[0.0; D]; D],
        };
        let mass = vol_ref.iter().map(|v| rho * v).collect();
        let off_zero = |a: &[[f64; D]; D]| (0..D).all(|i| (0..D).all(|j| i == j || a[i][j] == 0.0));
        let period_diagonal = period.is_some_and(|l| off_zero(&l) && off_zero(&period_inv));
        let mut m = Model {
            p,
            period,
            period_inv,
            period_diagonal,
            mass,
            x_ref,
            vol_ref,
            sigma0,
            ref_master: Vec::new(),
        };
        if p.form == FormKind::TotalLagrangian {
            let mut out = Vec::new();
            let mut st = Vec::with_capacity(m.x_ref.len());
            let kp = crate::shape::KernelParams {
                kernel: p.kp.kernel,
                h: p.kp.h,
            };
            for i in 0..m.x_ref.len() {
                let (nodes, idx) = m.neighbours_ref(m.x_ref[i]);
                crate::shape::eval_d(p.shape, kp, &nodes, m.x_ref[i][0], &mut out)?;
                st.push(
                    idx.into_iter()
                        .zip(&out)
                        .map(|(j, &(phi, g))| (j, phi, g))
                        .collect(),
                );
            }
            m.ref_master = st;
        }
        Ok(m)
    }

    /// A periodic patch of n_1 × … × n_D primitive cells of `lat` (spacing `dx`), at rest.
    pub fn periodic_patch(
        p: ModelParams2D,
        lat: &Lattice<D>,
        dx: f64,
        n: [usize; D],
        rho: f64,
        sigma0: f64,
    ) -> Result<Self> {
        let a = lat.a;
        let count: usize = n.iter().product();
        let mut x = Vec::with_capacity(count);
        for idx in 0..count {
            // first index slowest
            let mut m = [0usize; D];
            let mut rest = idx;
            for c in (0..D).rev() {
                m[c] = rest % n[c];
                rest /= n[c];
            }
            let mut q = [0.0; D];
            for c in 0..D {
                let mut s = 0.0;
                for i in 0..D {
                    s += m[i] as f64 * a[i][c];
                }
                q[c] = dx * s;
            }
            x.push(q);
        }
        let vol = vec![lat.area() * dx.powi(D as i32); x.len()];
        let mut period = [[0.0; D]; D];
        for i in 0..D {
            for c in 0..D {
                period[i][c] = n[i] as f64 * dx * a[i][c];
            }
        }
        Self::new(p, x, vol, rho, sigma0, Some(period))
    }

    /// Minimum-image relative position b − a (exact for displacements within half a period of
    /// the cell; the rounding to the nearest image is the only non-smooth step, at half a
    /// period, never inside a support).
    #[inline]
    pub fn rel<S: Scalar>(&self, a: [S; D], b: [S; D]) -> [S; D] {
        let mut d = [S::zero(); D];
        for c in 0..D {
            d[c] = b[c] - a[c];
        }
        let Some(l) = self.period else { return d };
        if self.period_diagonal {
            // rectangular box: the same arithmetic as below without the zero terms (x + 0·y
            // is x), one component at a time
            for c in 0..D {
                let f = d[c].re() * self.period_inv[c][c];
                if f.abs() >= 0.5 {
                    d[c] = d[c] - f.round() * l[c][c];
                }
            }
            return d;
        }
        let mut s = [0.0; D];
        let mut any = false;
        for i in 0..D {
            let mut f = 0.0;
            for c in 0..D {
                f += d[c].re() * self.period_inv[c][i];
            }
            s[i] = f.round();
            any |= s[i] != 0.0;
        }
        if !any {
            return d;
        }
        for c in 0..D {
            let mut shift = 0.0;
            for i in 0..D {
                shift += s[i] * l[i][c];
            }
            d[c] = d[c] - shift;
        }
        d
    }

    fn neighbours_ref(&self, x: [f64; D]) -> (Vec<([f64; D], f64)>, Vec<usize>) {
        let r = self.p.kp.support();
        let mut nodes = Vec::new();
        let mut idx = Vec::new();
        for (j, &xj) in self.x_ref.iter().enumerate() {
            let d = self.rel(x, xj);
            let r2: f64 = d.iter().map(|c| c * c).sum();
            if r2 < r * r {
                nodes.push((d, self.vol_ref[j]));
                idx.push(j);
            }
        }
        (nodes, idx)
    }

    /// The state at rest at the reference positions with density `rho` and isotropic stress
    /// `sigma0` in every stress field the form carries.
    pub fn rest_state(&self, rho: f64) -> State<f64, D> {
        let n = self.x_ref.len();
        let comps = self.p.form.comps(D, &self.p.material);
        let mut z = State {
            x: self.x_ref.clone(),
            v: vec![[0.0; D]; n],
            ..Default::default()
        };
        if comps.contains(&Comp::Rho) {
            z.rho = vec![rho; n];
        }
        let mut iso = [[0.0; D]; D];
        for (a, row) in iso.iter_mut().enumerate() {
            row[a] = self.sigma0;
        }
        if comps.contains(&Comp::Sigma(0)) {
            z.sigma = vec![iso; n];
        }
        if comps.contains(&Comp::Tau(0)) {
            z.tau = vec![iso; n];
        }
        z
    }
}

/// Inverse of a D × D matrix, D ≤ 3 (non-finite entries when singular).
pub(crate) fn invert<const D: usize>(m: &[[f64; D]; D]) -> [[f64; D]; D] {
    let det = crate::lattice::det(m);
    let mut inv = [[0.0; D]; D];
    match D {
        1 => inv[0][0] = 1.0 / m[0][0],
        2 => {
            inv[0][0] = m[1][1] / det;
            inv[0][1] = -m[0][1] / det;
            inv[1][0] = -m[1][0] / det;
            inv[1][1] = m[0][0] / det;
        }
        _ => {
            for i in 0..3 {
                for j in 0..3 {
                    // cofactor of m[j][i]
                    let (r0, r1) = ((j + 1) % 3, (j + 2) % 3);
                    let (c0, c1) = ((i + 1) % 3, (i + 2) % 3);
                    inv[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
                }
            }
        }
    }
    inv
}
