//! The state of a particle system in D ∈ {1, 2, 3} dimensions ([`State`]), its borrowed view
//! and rate outputs, and the scalar components ([`Comp`]) the linearisation perturbs.
//!
//! Vectors are `[S; D]`; the stress is a symmetric `[[S; D]; D]` (the rates are computed
//! symmetric, so an integrated stress stays exactly symmetric); its independent components are
//! numbered in the nested Voigt order of [`voigt`] (xx, yy, xy, zz, xz, yz: the first one in 1D,
//! the first three in 2D).

// Small-tensor algebra (D × D, D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::kind::FormKind;
use super::params::Material;
use crate::scalar::Scalar;
use crate::shape::ShapeFamily;

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
    /// Stress-point positions (the stress-point forms of \[B00\], 1D).
    pub sp_x: Vec<[S; D]>,
    /// Stress-point stress.
    pub sp_sigma: Vec<Tensor<S, D>>,
    /// Stress-point volumes.
    pub sp_vol: Vec<S>,
    /// The accumulated shear acceleration a^s of `enog` (SPH-ENOG: the time integral of its
    /// Laplacian-type shear term).
    pub shear_acc: Vec<[S; D]>,
}

impl<S, const D: usize> Default for State<S, D> {
    fn default() -> Self {
        Self {
            x: Vec::new(),
            v: Vec::new(),
            rho: Vec::new(),
            sigma: Vec::new(),
            tau: Vec::new(),
            sp_x: Vec::new(),
            sp_sigma: Vec::new(),
            sp_vol: Vec::new(),
            shear_acc: Vec::new(),
        }
    }
}

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
    /// Stress-point positions (empty if the form has no stress points).
    pub sp_x: &'a [[S; D]],
    /// Stress-point stress.
    pub sp_sigma: &'a [Tensor<S, D>],
    /// Stress-point volumes.
    pub sp_vol: &'a [S],
    /// Accumulated shear acceleration (`enog`; empty otherwise).
    pub shear_acc: &'a [[S; D]],
}

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
    /// Auxiliary rates (ρ̇, σ̇, τ̇ and the stress points'), each as long as the state's field
    /// (possibly empty).
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

/// The auxiliary part of a [`RateOut`].
#[derive(Debug)]
pub struct AuxRates<'a, S, const D: usize> {
    /// ρ̇.
    pub rho: &'a mut [S],
    /// σ̇.
    pub sigma: &'a mut [Tensor<S, D>],
    /// τ̇.
    pub tau: &'a mut [Tensor<S, D>],
    /// Stress-point velocities ẋ^S.
    pub sp_x: &'a mut [[S; D]],
    /// Stress-point σ̇^S.
    pub sp_sigma: &'a mut [Tensor<S, D>],
    /// Stress-point V̇^S.
    pub sp_vol: &'a mut [S],
    /// ȧ^s (`enog`).
    pub shear_acc: &'a mut [[S; D]],
}

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
    /// Stress-point position component (stress point i lies between particles i and i + 1).
    SpX(usize),
    /// Stress-point σ component (Voigt numbering).
    SpSigma(usize),
    /// Stress-point volume.
    SpVol,
    /// Component of the accumulated shear acceleration a^s (`enog`).
    ShearAcc(usize),
}

/// What a state component is, mechanically.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FieldKind {
    /// Particle position (translation invariance applies).
    Position,
    /// Particle velocity.
    Velocity,
    /// Any other state (its rate vanishes at rest).
    Auxiliary,
}

impl Comp {
    /// Position / velocity / auxiliary.
    pub fn kind(self) -> FieldKind {
        match self {
            Comp::X(_) => FieldKind::Position,
            Comp::V(_) => FieldKind::Velocity,
            _ => FieldKind::Auxiliary,
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
            Comp::SpX(a) => self.sp_x[i][a],
            Comp::SpSigma(k) => {
                let (a, b) = voigt(k);
                self.sp_sigma[i][a][b]
            }
            Comp::SpVol => self.sp_vol[i],
            Comp::ShearAcc(a) => self.shear_acc[i][a],
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
            Comp::SpX(a) => self.sp_x[i][a] = val,
            Comp::SpSigma(k) => {
                let (a, b) = voigt(k);
                self.sp_sigma[i][a][b] = val;
                self.sp_sigma[i][b][a] = val;
            }
            Comp::SpVol => self.sp_vol[i] = val,
            Comp::ShearAcc(a) => self.shear_acc[i][a] = val,
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
            sp_x: &self.sp_x,
            sp_sigma: &self.sp_sigma,
            sp_vol: &self.sp_vol,
            shear_acc: &self.shear_acc,
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
                sp_x: &mut self.sp_x,
                sp_sigma: &mut self.sp_sigma,
                sp_vol: &mut self.sp_vol,
                shear_acc: &mut self.shear_acc,
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
        self.sp_x.resize(o.sp_x.len(), [S::zero(); D]);
        self.sp_sigma.resize(o.sp_sigma.len(), [[S::zero(); D]; D]);
        self.sp_vol.resize(o.sp_vol.len(), S::zero());
        self.shear_acc.resize(o.shear_acc.len(), [S::zero(); D]);
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
            sp_x: self.sp_x.iter().map(vec).collect(),
            sp_sigma: self.sp_sigma.iter().map(ten).collect(),
            sp_vol: self.sp_vol.iter().map(|&p| f(p)).collect(),
            shear_acc: self.shear_acc.iter().map(vec).collect(),
        }
    }
}

impl<const D: usize> State<f64, D> {
    /// The stress the momentum equation integrates at each particle: σ, or for the mixed forms
    /// (lnl, cll: the state carries τ) (1 − c)σ + cτ with the partition coefficient
    /// `c_partition` (\[V21\] eq 50–56, §7.2; σ is integrated from the velocity gradient of the
    /// kernel, τ from the corrected local one). Empty when the state carries no stress: the
    /// Lagrangian forms (their stress is a function of the positions) and hydrodynamic
    /// materials (a function of the density).
    pub fn total_stress(&self, c_partition: f64) -> Vec<Tensor<f64, D>> {
        if self.tau.is_empty() {
            return self.sigma.clone();
        }
        let c = c_partition;
        self.sigma
            .iter()
            .zip(&self.tau)
            .map(|(s, t)| {
                let mut m = [[0.0; D]; D];
                for a in 0..D {
                    for b in 0..D {
                        m[a][b] = (1.0 - c) * s[a][b] + c * t[a][b];
                    }
                }
                m
            })
            .collect()
    }
}

impl FormKind {
    /// Whether the form is available in every dimension (the B00 stress-point, least-squares
    /// and eulerian-nodal forms are 1D only: [`super::Model::new`] refuses them for D > 1).
    pub fn in_every_dimension(self) -> bool {
        matches!(
            self,
            FormKind::Classical
                | FormKind::Nonlocal
                | FormKind::Local
                | FormKind::Lnl
                | FormKind::Cll
                | FormKind::TotalLagrangian
                | FormKind::Enog
                | FormKind::TlEnog
        )
    }

    /// Default shape family in dimension `dim`: [`FormKind::default_shape`] in 1D; in 2D
    /// and 3D the same except total-Lagrangian, whose closest multi-dimensional paper is the
    /// thesis \[T\] (TL SPH, `sph` shapes). (With `mls`, nodal integration of a pre-stressed
    /// rest state is not in equilibrium within two supports of a boundary: the residual force
    /// ∝ σ0 drifts a fixed-boundary box; see the closing notes of issue 4.)
    pub fn default_shape_in(self, dim: usize) -> ShapeFamily {
        match self {
            FormKind::TotalLagrangian if dim > 1 => ShapeFamily::Sph,
            f => f.default_shape(),
        }
    }

    /// The scalar components per particle in dimension `dim` for `material`: positions,
    /// velocities, then (Eulerian forms) density, and for elastic materials the D(D+1)/2
    /// independent stress components (and as many of τ for the mixed forms); the 1D-only
    /// forms of \[B00\]: `eulerian-stress-points` adds the stress point between the particle
    /// and the next (position, stress, volume), the Lagrangian ones carry x and v only.
    pub fn comps(self, dim: usize, material: &Material) -> Vec<Comp> {
        let mut c: Vec<Comp> = (0..dim).map(Comp::X).chain((0..dim).map(Comp::V)).collect();
        if self.is_lagrangian() {
            return c;
        }
        if self == FormKind::EulerianStressPoints {
            c.extend([
                Comp::Rho,
                Comp::Sigma(0),
                Comp::SpX(0),
                Comp::SpSigma(0),
                Comp::SpVol,
            ]);
            return c;
        }
        if self == FormKind::EulerianNodal {
            c.extend([Comp::Rho, Comp::Sigma(0)]);
            return c;
        }
        c.push(Comp::Rho);
        if self == FormKind::Enog {
            c.extend((0..dim).map(Comp::ShearAcc));
            return c;
        }
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
