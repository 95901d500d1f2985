//! The 2D particle model (in-plane): parameters, materials and state.
//!
//! Stress is stored as [σ_xx, σ_yy, σ_xy]. Materials:
//! - `Hydro`: p = K(ρ/ρ0 − 1), σ = −p I, density by continuity (the Swegle test); tangent
//!   modulus C = K.
//! - `Elastic`: hypo-elastic σ̇ = λ tr(d) I + 2G d + (objective terms), with the Jaumann rate
//!   (Wσ − σW) or the Truesdell rate (Lσ + σLᵀ − tr(L)σ, which in 1D is the law of the 1D
//!   forms); tangent modulus C = λ + 2G (P-wave), λ = K − G (2D).
//! - total-Lagrangian forms: hydro is the fluid P = −p(J) cof F; elastic is St Venant–Kirchhoff
//!   about the pre-stress with the moduli that give the Eulerian law's tangent (see
//!   `eulerian2d::rate_tl`).

use super::FormKind;
use super::model::ArtificialViscosity;
use crate::error::{Error, Result};
use crate::lattice::Lattice2D;
use crate::scalar::Scalar;
use crate::shape::ShapeFamily;
use crate::shape2d::{KernelParams2, eval2};

/// Objective stress rate of the hypo-elastic law.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ObjectiveRate {
    /// Jaumann: σ̇ = C:d + Wσ − σW.
    Jaumann,
    /// Truesdell: σ̇ = C:d + Lσ + σLᵀ − tr(L)σ.
    Truesdell,
}

/// 2D material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Material2D {
    /// p = K(ρ/ρ0 − 1), G = 0.
    Hydro {
        /// Bulk modulus K.
        bulk: f64,
    },
    /// Compressible neo-Hookean \[T eq 3.62–3.64\], total-Lagrangian forms only:
    /// P = μ(F − F⁻ᵀ) + λ ln J F⁻ᵀ (plane strain), linearised about the unstressed state.
    NeoHookean {
        /// Lamé λ.
        lambda: f64,
        /// Shear modulus μ.
        shear: f64,
    },
    /// Linear hypo-elastic.
    Elastic {
        /// Lamé λ (2D: K − G).
        lambda: f64,
        /// Shear modulus G.
        shear: f64,
        /// Objective rate.
        rate: ObjectiveRate,
    },
}

impl Material2D {
    /// Elastic material with P-wave modulus `c` and Poisson ratio ν (plane strain):
    /// G = c(1 − 2ν)/(2(1 − ν)), λ = cν/(1 − ν).
    pub fn elastic(c: f64, nu: f64, rate: ObjectiveRate) -> Result<Self> {
        crate::error::check_range("--poisson", nu, -0.99, 0.5, true, false)?;
        Ok(Material2D::Elastic {
            lambda: c * nu / (1.0 - nu),
            shear: c * (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu)),
            rate,
        })
    }
    /// Tangent modulus C of the normalisation (K for hydro, λ + 2G for elastic).
    pub fn modulus(&self) -> f64 {
        match *self {
            Material2D::Hydro { bulk } => bulk,
            Material2D::Elastic { lambda, shear, .. }
            | Material2D::NeoHookean { lambda, shear } => lambda + 2.0 * shear,
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

/// Parameters of a 2D model.
#[derive(Clone, Copy, Debug)]
pub struct ModelParams2D {
    /// The form (classical, nonlocal, local, lnl, cll, total-lagrangian).
    pub form: FormKind,
    /// Shape family.
    pub shape: ShapeFamily,
    /// Kernel and h.
    pub kp: KernelParams2,
    /// Material.
    pub material: Material2D,
    /// Reference density ρ0.
    pub rho0: f64,
    /// Partition coefficient c of lnl / cll.
    pub c_partition: f64,
    /// Optional artificial viscosity.
    pub av: Option<ArtificialViscosity>,
    /// Optional artificial stress (classical and cll forms).
    pub art_stress: Option<ArtificialStress>,
}

/// A 2D particle model.
#[derive(Clone, Debug)]
pub struct Model2D {
    /// Parameters.
    pub p: ModelParams2D,
    /// Periodic cell vectors (None: open).
    pub period: Option<[[f64; 2]; 2]>,
    /// Masses.
    pub mass: Vec<f64>,
    /// Reference positions.
    pub x_ref: Vec<[f64; 2]>,
    /// Reference volumes.
    pub vol_ref: Vec<f64>,
    /// Isotropic pre-stress σ0 of the total-Lagrangian law.
    pub sigma0: f64,
    /// Reference stencils (total-Lagrangian): (master, φ, ∇φ) at each master.
    pub(crate) ref_master: Vec<Vec<(usize, f64, [f64; 2])>>,
}

/// State of a 2D system; fields a form does not carry are empty.
#[derive(Clone, Debug, Default)]
pub struct State2D<S> {
    /// Positions.
    pub x: Vec<[S; 2]>,
    /// Velocities.
    pub v: Vec<[S; 2]>,
    /// Densities.
    pub rho: Vec<S>,
    /// Stress σ (elastic), [xx, yy, xy].
    pub sigma: Vec<[S; 3]>,
    /// Local stress τ (mixed forms, elastic).
    pub tau: Vec<[S; 3]>,
}

/// A borrowed [`State2D`]: the same fields as slices, so that a rate can be evaluated on the
/// solver's own buffers without assembling a `State2D`.
#[derive(Debug)]
pub struct StateView2D<'a, S> {
    /// Positions.
    pub x: &'a [[S; 2]],
    /// Velocities.
    pub v: &'a [[S; 2]],
    /// Densities (empty if the form carries none).
    pub rho: &'a [S],
    /// Stress σ, [xx, yy, xy] (empty if not carried).
    pub sigma: &'a [[S; 3]],
    /// Local stress τ (empty if not carried).
    pub tau: &'a [[S; 3]],
}

impl<S> Clone for StateView2D<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S> Copy for StateView2D<'_, S> {}

/// Where a rate evaluation writes. A `None` part is neither computed nor written: the solver
/// asks for the accelerations and the auxiliary rates in separate calls.
#[derive(Debug, Default)]
pub struct RateOut2D<'a, S> {
    /// ẋ = v.
    pub x: Option<&'a mut [[S; 2]]>,
    /// Accelerations v̇.
    pub v: Option<&'a mut [[S; 2]]>,
    /// Auxiliary rates (ρ̇, σ̇, τ̇), each as long as the state's field (possibly empty).
    pub aux: Option<AuxRates2D<'a, S>>,
}

/// The auxiliary part of a [`RateOut2D`].
#[derive(Debug)]
pub struct AuxRates2D<'a, S> {
    /// ρ̇.
    pub rho: &'a mut [S],
    /// σ̇.
    pub sigma: &'a mut [[S; 3]],
    /// τ̇.
    pub tau: &'a mut [[S; 3]],
}

/// A scalar component of the 2D state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Comp2 {
    /// Position component.
    X(usize),
    /// Velocity component.
    V(usize),
    /// Density.
    Rho,
    /// σ component (0 xx, 1 yy, 2 xy).
    Sigma(usize),
    /// τ component.
    Tau(usize),
}

impl Comp2 {
    /// Position / velocity / auxiliary.
    pub fn kind(self) -> super::FieldKind {
        match self {
            Comp2::X(_) => super::FieldKind::Position,
            Comp2::V(_) => super::FieldKind::Velocity,
            _ => super::FieldKind::Auxiliary,
        }
    }
}

impl<S: Scalar> State2D<S> {
    /// Component `c` of particle `i`.
    pub fn get(&self, c: Comp2, i: usize) -> S {
        match c {
            Comp2::X(a) => self.x[i][a],
            Comp2::V(a) => self.v[i][a],
            Comp2::Rho => self.rho[i],
            Comp2::Sigma(a) => self.sigma[i][a],
            Comp2::Tau(a) => self.tau[i][a],
        }
    }
    /// Mutable component.
    pub fn get_mut(&mut self, c: Comp2, i: usize) -> &mut S {
        match c {
            Comp2::X(a) => &mut self.x[i][a],
            Comp2::V(a) => &mut self.v[i][a],
            Comp2::Rho => &mut self.rho[i],
            Comp2::Sigma(a) => &mut self.sigma[i][a],
            Comp2::Tau(a) => &mut self.tau[i][a],
        }
    }
    /// The state as a [`StateView2D`].
    pub fn view(&self) -> StateView2D<'_, S> {
        StateView2D {
            x: &self.x,
            v: &self.v,
            rho: &self.rho,
            sigma: &self.sigma,
            tau: &self.tau,
        }
    }
    /// Every field of the state as an output ([`RateOut2D`] with all parts).
    pub fn as_rate_out(&mut self) -> RateOut2D<'_, S> {
        RateOut2D {
            x: Some(&mut self.x),
            v: Some(&mut self.v),
            aux: Some(AuxRates2D {
                rho: &mut self.rho,
                sigma: &mut self.sigma,
                tau: &mut self.tau,
            }),
        }
    }
    /// Gives every field the length of `o`'s (new entries zero); allocates only when a field
    /// grows beyond its capacity.
    pub fn resize_like<T>(&mut self, o: &State2D<T>) {
        self.x.resize(o.x.len(), [S::zero(); 2]);
        self.v.resize(o.v.len(), [S::zero(); 2]);
        self.rho.resize(o.rho.len(), S::zero());
        self.sigma.resize(o.sigma.len(), [S::zero(); 3]);
        self.tau.resize(o.tau.len(), [S::zero(); 3]);
    }
    /// Zeroed state shaped like `o`.
    pub fn zeros_like<T>(o: &State2D<T>) -> Self {
        State2D {
            x: vec![[S::zero(); 2]; o.x.len()],
            v: vec![[S::zero(); 2]; o.v.len()],
            rho: vec![S::zero(); o.rho.len()],
            sigma: vec![[S::zero(); 3]; o.sigma.len()],
            tau: vec![[S::zero(); 3]; o.tau.len()],
        }
    }
    /// Converts every entry.
    pub fn map<T: Scalar>(&self, f: impl Fn(S) -> T + Copy) -> State2D<T> {
        State2D {
            x: self.x.iter().map(|p| [f(p[0]), f(p[1])]).collect(),
            v: self.v.iter().map(|p| [f(p[0]), f(p[1])]).collect(),
            rho: self.rho.iter().map(|&p| f(p)).collect(),
            sigma: self
                .sigma
                .iter()
                .map(|p| [f(p[0]), f(p[1]), f(p[2])])
                .collect(),
            tau: self
                .tau
                .iter()
                .map(|p| [f(p[0]), f(p[1]), f(p[2])])
                .collect(),
        }
    }
}

impl FormKind {
    /// Whether the form is available in 2D.
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

    /// Default shape family in 2D: as in 1D, except total-Lagrangian, whose closest 2D paper is
    /// the thesis [T] (TL SPH, `sph` shapes). (With `mls`, nodal integration of a pre-stressed
    /// rest state is not in equilibrium within two supports of a boundary: the residual force
    /// ∝ σ0 drifts a fixed-boundary box; see the closing notes of issue 4.)
    pub fn default_shape_2d(self) -> ShapeFamily {
        match self {
            FormKind::TotalLagrangian => ShapeFamily::Sph,
            f => f.default_shape(),
        }
    }

    /// The scalar components per particle in 2D for `material`.
    pub fn comps_2d(self, material: &Material2D) -> Vec<Comp2> {
        let mut c = vec![Comp2::X(0), Comp2::X(1), Comp2::V(0), Comp2::V(1)];
        if self == FormKind::TotalLagrangian {
            return c;
        }
        c.push(Comp2::Rho);
        if matches!(
            material,
            Material2D::Elastic { .. } | Material2D::NeoHookean { .. }
        ) {
            c.extend([Comp2::Sigma(0), Comp2::Sigma(1), Comp2::Sigma(2)]);
            if matches!(self, FormKind::Lnl | FormKind::Cll) {
                c.extend([Comp2::Tau(0), Comp2::Tau(1), Comp2::Tau(2)]);
            }
        }
        c
    }
}

impl Model2D {
    /// A model of particles at `x_ref` with volumes `vol_ref` and current density `rho`
    /// (masses ρ V); `sigma0` is the isotropic pre-stress of the total-Lagrangian law.
    pub fn new(
        p: ModelParams2D,
        x_ref: Vec<[f64; 2]>,
        vol_ref: Vec<f64>,
        rho: f64,
        sigma0: f64,
        period: Option<[[f64; 2]; 2]>,
    ) -> Result<Self> {
        if !p.form.in_2d() {
            return Err(Error::Incompatible(format!(
                "--form {} is not available in 2D (classical, nonlocal, local, lnl, cll, total-lagrangian)",
                p.form.name()
            )));
        }
        p.form.check_shape(p.shape)?;
        if let Material2D::NeoHookean { .. } = p.material {
            if p.form != FormKind::TotalLagrangian {
                return Err(Error::Incompatible(
                    "--material neo-hookean needs --form total-lagrangian".into(),
                ));
            }
            if sigma0 != 0.0 {
                return Err(Error::OutOfRange {
                    name: "--stress",
                    value: sigma0,
                    range: "neo-hookean: the reference state is unstressed, σ̄ must be 0".into(),
                });
            }
        }
        let mass = vol_ref.iter().map(|v| rho * v).collect();
        let mut m = Model2D {
            p,
            period,
            mass,
            x_ref,
            vol_ref,
            sigma0,
            ref_master: Vec::new(),
        };
        if p.form == FormKind::TotalLagrangian {
            let mut out = Vec::new();
            let mut st = Vec::with_capacity(m.x_ref.len());
            for i in 0..m.x_ref.len() {
                let (nodes, idx) = m.neighbours_ref(m.x_ref[i]);
                eval2(p.shape, p.kp, &nodes, m.x_ref[i], &mut out)?;
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

    /// A periodic patch of n1 × n2 cells of `lat` (spacing `dx`), at rest.
    pub fn periodic_patch(
        p: ModelParams2D,
        lat: &Lattice2D,
        dx: f64,
        n: [usize; 2],
        rho: f64,
        sigma0: f64,
    ) -> Result<Self> {
        let a = lat.a;
        let mut x = Vec::with_capacity(n[0] * n[1]);
        for i in 0..n[0] {
            for j in 0..n[1] {
                let (fi, fj) = (i as f64, j as f64);
                x.push([
                    dx * (fi * a[0][0] + fj * a[1][0]),
                    dx * (fi * a[0][1] + fj * a[1][1]),
                ]);
            }
        }
        let vol = vec![lat.area() * dx * dx; x.len()];
        let period = [
            [n[0] as f64 * dx * a[0][0], n[0] as f64 * dx * a[0][1]],
            [n[1] as f64 * dx * a[1][0], n[1] as f64 * dx * a[1][1]],
        ];
        Self::new(p, x, vol, rho, sigma0, Some(period))
    }

    /// Minimum-image relative position b − a.
    #[inline]
    pub fn rel<S: Scalar>(&self, a: [S; 2], b: [S; 2]) -> [S; 2] {
        let d = [b[0] - a[0], b[1] - a[1]];
        match self.period {
            None => d,
            Some(l) => {
                let det = l[0][0] * l[1][1] - l[0][1] * l[1][0];
                let (dx, dy) = (d[0].re(), d[1].re());
                let s = ((dx * l[1][1] - dy * l[1][0]) / det).round();
                let t = ((dy * l[0][0] - dx * l[0][1]) / det).round();
                if s == 0.0 && t == 0.0 {
                    d
                } else {
                    [
                        d[0] - (s * l[0][0] + t * l[1][0]),
                        d[1] - (s * l[0][1] + t * l[1][1]),
                    ]
                }
            }
        }
    }

    fn neighbours_ref(&self, x: [f64; 2]) -> (Vec<([f64; 2], f64)>, Vec<usize>) {
        let r = self.p.kp.support();
        let mut nodes = Vec::new();
        let mut idx = Vec::new();
        for (j, &xj) in self.x_ref.iter().enumerate() {
            let d = self.rel(x, xj);
            if d[0].hypot(d[1]) < r {
                nodes.push((d, self.vol_ref[j]));
                idx.push(j);
            }
        }
        (nodes, idx)
    }

    /// The state at rest at the reference positions with density `rho` and isotropic stress
    /// `sigma0` in every stress field the form carries.
    pub fn rest_state(&self, rho: f64) -> State2D<f64> {
        let n = self.x_ref.len();
        let comps = self.p.form.comps_2d(&self.p.material);
        let mut z = State2D {
            x: self.x_ref.clone(),
            v: vec![[0.0; 2]; n],
            ..Default::default()
        };
        if comps.contains(&Comp2::Rho) {
            z.rho = vec![rho; n];
        }
        if comps.contains(&Comp2::Sigma(0)) {
            z.sigma = vec![[self.sigma0, self.sigma0, 0.0]; n];
        }
        if comps.contains(&Comp2::Tau(0)) {
            z.tau = vec![[self.sigma0, self.sigma0, 0.0]; n];
        }
        z
    }
}
