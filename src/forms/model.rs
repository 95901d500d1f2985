//! The constant part of a 1D particle system (model) and its state.
//!
//! The forms defined in every dimension (classical, nonlocal, local, lnl, cll,
//! total-lagrangian) are evaluated by the one rate function of [`super::Model`] with D = 1:
//! [`Model1D`] holds that model and lends it its state's fields without copying (a `Vec<S>` is
//! viewed as `[[S; 1]]`). The 1D-only forms of \[B00\] (stress points, least squares,
//! eulerian-nodal) add the stress-point fields and the consistent mass kept here.

use super::FormKind;
use super::eulerian_common::{ChainSearch, StencilScratch, Stencils};
use super::least_squares::BandedLu;
use super::workspace::RateWorkspace;
use crate::error::Result;
use crate::scalar::Scalar;
use crate::shape::{self, KernelParams, ShapeFamily};
use std::cell::RefCell;

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

/// Physical parameters of a 1D model (everything but the particle set).
#[derive(Clone, Copy, Debug)]
pub struct ModelParams {
    /// The form.
    pub form: FormKind,
    /// Shape-function family.
    pub shape: ShapeFamily,
    /// Kernel and smoothing length.
    pub kp: KernelParams,
    /// Tangent modulus C (Truesdell rate), physical units.
    pub modulus: f64,
    /// Reference density ρ0.
    pub rho0: f64,
    /// Initial (pre-)stress σ0, physical units; used by the total-Lagrangian P(F).
    pub sigma0: f64,
    /// Partition-of-unity coefficient c of `lnl`/`cll` (c = 1: fully local).
    pub c_partition: f64,
    /// Least-squares stabilisation α_s (β = α_s l_c², l_c = Δx).
    pub alpha_s: f64,
    /// Optional artificial viscosity.
    pub av: Option<ArtificialViscosity>,
    /// Characteristic spacing Δx (for β of the least-squares form).
    pub dx: f64,
    /// Optional δ-SPH density diffusion (the forms of the dimension-generic model only).
    pub diffusion: Option<super::DensityDiffusion>,
}

impl ModelParams {
    /// The same system as parameters of the dimension-generic model: the 1D law σ̇ = (C + σ)
    /// ∂v/∂x is the hypo-elastic law with the Truesdell rate and P-wave modulus λ + 2G = C
    /// (written with G = 0, λ = C: in 1D only λ + 2G enters).
    pub fn nd_params(&self) -> super::ModelParams2D {
        super::ModelParams2D {
            form: self.form,
            shape: self.shape,
            kp: crate::shape::KernelParams {
                kernel: self.kp.kernel,
                h: self.kp.h,
            },
            material: super::Material::Elastic {
                lambda: self.modulus,
                shear: 0.0,
                rate: super::ObjectiveRate::Truesdell,
            },
            rho0: self.rho0,
            c_partition: self.c_partition,
            av: self.av,
            art_stress: None,
            diffusion: self.diffusion,
        }
    }
}

/// Mass operator of the semi-discrete system.
#[derive(Clone, Debug)]
pub enum MassOperator {
    /// Diagonal (lumped) masses: the `v` rate is the acceleration.
    Lumped,
    /// Consistent mass rows `M_IK` (sparse): the `v` rate is the force of `M a = f`.
    Consistent(Vec<Vec<(usize, f64)>>),
}

/// Shape functions of the masters near one evaluation point, on the reference configuration.
#[derive(Clone, Debug, Default)]
pub(crate) struct RefStencil {
    /// Master index, φ, φ', φ''.
    pub(crate) entries: Vec<(usize, [f64; 3])>,
}

/// A 1D particle model: parameters plus the constant per-particle data.
#[derive(Clone, Debug)]
pub struct Model1D {
    /// Parameters.
    pub p: ModelParams,
    /// Period of a periodic chain (None: open chain).
    pub period: Option<f64>,
    /// Master masses (change them with [`Model1D::set_masses`]: the rate function refuses a
    /// model whose masses were edited in place).
    pub mass: Vec<f64>,
    /// Master reference positions X.
    pub x_ref: Vec<f64>,
    /// Master reference volumes V0.
    pub vol_ref: Vec<f64>,
    /// Stress-point reference positions (stress-point forms only).
    pub sp_x_ref: Vec<f64>,
    /// Stress-point reference volumes.
    pub sp_vol_ref: Vec<f64>,
    /// Master-node integration weights of the stress-point forms (V0/2 in \[B00 eq 84/100\]).
    pub(crate) master_weight_ref: Vec<f64>,
    /// Reference stencils at masters (Lagrangian forms).
    pub(crate) ref_master: Vec<RefStencil>,
    /// Reference stencils at stress points (Lagrangian stress points).
    pub(crate) ref_sp: Vec<RefStencil>,
    /// Least-squares stiffness rows K_IK.
    pub(crate) ls_stiffness: Vec<Vec<(usize, f64)>>,
    /// Mass operator.
    pub mass_op: MassOperator,
    /// The D = 1 particle model of the forms defined in every dimension (`None` for the
    /// 1D-only forms of \[B00\]).
    pub(crate) nd: Option<super::Model<1>>,
}

/// State fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Field {
    /// Master positions.
    X,
    /// Master velocities.
    V,
    /// Master densities.
    Rho,
    /// Master (nonlocal / classical) stress.
    Sigma,
    /// Master local stress τ (mixed forms).
    Tau,
    /// Stress-point positions.
    SpX,
    /// Stress-point stress.
    SpSigma,
    /// Stress-point volume.
    SpVol,
}

/// What a field is, mechanically.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FieldKind {
    /// Master position (translation invariance applies).
    Position,
    /// Master velocity.
    Velocity,
    /// Any other state (its rate vanishes at rest).
    Auxiliary,
}

impl Field {
    /// Mechanical role.
    pub fn kind(self) -> FieldKind {
        match self {
            Field::X => FieldKind::Position,
            Field::V => FieldKind::Velocity,
            _ => FieldKind::Auxiliary,
        }
    }
    /// Lives on stress points (else on masters).
    pub fn on_stress_points(self) -> bool {
        matches!(self, Field::SpX | Field::SpSigma | Field::SpVol)
    }
}

/// State of a 1D particle system. Fields a form does not carry are empty.
#[derive(Clone, Debug, Default)]
pub struct State1D<S> {
    /// Master positions.
    pub x: Vec<S>,
    /// Master velocities.
    pub v: Vec<S>,
    /// Master densities.
    pub rho: Vec<S>,
    /// Master stress σ.
    pub sigma: Vec<S>,
    /// Master local stress τ.
    pub tau: Vec<S>,
    /// Stress-point positions.
    pub sp_x: Vec<S>,
    /// Stress-point stress.
    pub sp_sigma: Vec<S>,
    /// Stress-point volumes.
    pub sp_vol: Vec<S>,
}

impl<S: Scalar> State1D<S> {
    /// The vector of one field.
    pub fn field(&self, f: Field) -> &Vec<S> {
        match f {
            Field::X => &self.x,
            Field::V => &self.v,
            Field::Rho => &self.rho,
            Field::Sigma => &self.sigma,
            Field::Tau => &self.tau,
            Field::SpX => &self.sp_x,
            Field::SpSigma => &self.sp_sigma,
            Field::SpVol => &self.sp_vol,
        }
    }
    /// The vector of one field, mutable.
    pub fn field_mut(&mut self, f: Field) -> &mut Vec<S> {
        match f {
            Field::X => &mut self.x,
            Field::V => &mut self.v,
            Field::Rho => &mut self.rho,
            Field::Sigma => &mut self.sigma,
            Field::Tau => &mut self.tau,
            Field::SpX => &mut self.sp_x,
            Field::SpSigma => &mut self.sp_sigma,
            Field::SpVol => &mut self.sp_vol,
        }
    }
    /// Makes every field of `self` as long as in `other`, filled with zeros.
    pub fn resize_like<T>(&mut self, other: &State1D<T>) {
        let fit = |v: &mut Vec<S>, n: usize| {
            v.clear();
            v.resize(n, S::zero());
        };
        fit(&mut self.x, other.x.len());
        fit(&mut self.v, other.v.len());
        fit(&mut self.rho, other.rho.len());
        fit(&mut self.sigma, other.sigma.len());
        fit(&mut self.tau, other.tau.len());
        fit(&mut self.sp_x, other.sp_x.len());
        fit(&mut self.sp_sigma, other.sp_sigma.len());
        fit(&mut self.sp_vol, other.sp_vol.len());
    }
    /// Converts every entry with `f`.
    pub fn map<T: Scalar>(&self, f: impl Fn(S) -> T) -> State1D<T> {
        let m = |v: &Vec<S>| v.iter().map(|&a| f(a)).collect();
        State1D {
            x: m(&self.x),
            v: m(&self.v),
            rho: m(&self.rho),
            sigma: m(&self.sigma),
            tau: m(&self.tau),
            sp_x: m(&self.sp_x),
            sp_sigma: m(&self.sp_sigma),
            sp_vol: m(&self.sp_vol),
        }
    }
}

impl Model1D {
    /// Builds a model for masters at reference positions `x_ref` with volumes `vol_ref`
    /// (masses ρ0 V0). Stress points (for the stress-point forms) are placed at the
    /// mid-points of consecutive masters (and of the last and first for a periodic chain).
    pub fn new(
        p: ModelParams,
        x_ref: Vec<f64>,
        vol_ref: Vec<f64>,
        period: Option<f64>,
    ) -> Result<Self> {
        p.form.check_shape(p.shape)?;
        let n = x_ref.len();
        let mass = vol_ref.iter().map(|v| p.rho0 * v).collect();
        let (mut sp_x_ref, mut sp_vol_ref) = (Vec::new(), Vec::new());
        let mut master_weight_ref = vol_ref.clone();
        if p.form.has_stress_points() {
            let m = if period.is_some() {
                n
            } else {
                n.saturating_sub(1)
            };
            for i in 0..m {
                let j = (i + 1) % n;
                let mut xj = x_ref[j];
                if let (Some(l), 0) = (period, j) {
                    xj += l;
                }
                sp_x_ref.push(0.5 * (x_ref[i] + xj));
                sp_vol_ref.push(0.25 * (vol_ref[i] + vol_ref[j]));
            }
            master_weight_ref = vol_ref.iter().map(|v| 0.5 * v).collect();
        }
        let mut model = Model1D {
            p,
            period,
            mass,
            x_ref,
            vol_ref,
            sp_x_ref,
            sp_vol_ref,
            master_weight_ref,
            ref_master: Vec::new(),
            ref_sp: Vec::new(),
            ls_stiffness: Vec::new(),
            mass_op: MassOperator::Lumped,
            nd: None,
        };
        if p.av.is_some() && !p.form.in_2d() {
            return Err(crate::error::Error::Incompatible(format!(
                "--av-alpha (artificial viscosity) is available for classical, nonlocal, local, lnl and cll, not --form {}",
                p.form.name()
            ).into()));
        }
        if p.diffusion.is_some() && !p.form.in_2d() {
            return Err(crate::error::Error::Incompatible(format!(
                "--delta (density diffusion) is available for classical, nonlocal, local, lnl and cll, not --form {}",
                p.form.name()
            ).into()));
        }
        if p.form.in_2d() {
            let vols = model.vol_ref.clone();
            model.nd = Some(super::Model::new(
                p.nd_params(),
                model.x_ref.iter().map(|&x| [x]).collect(),
                vols,
                p.rho0,
                p.sigma0,
                period.map(|l| [[l]]),
            )?);
            return Ok(model);
        }
        if p.form.is_lagrangian() {
            let mut search = ChainSearch::default();
            search.prepare_positions(period, model.x_ref.iter().copied());
            model.ref_master = (0..n)
                .map(|i| model.ref_stencil(model.x_ref[i], &mut search))
                .collect::<Result<_>>()?;
            if p.form == FormKind::LagrangianStressPoints {
                search.restart();
                model.ref_sp = model
                    .sp_x_ref
                    .clone()
                    .iter()
                    .map(|&x| model.ref_stencil(x, &mut search))
                    .collect::<Result<_>>()?;
            }
            if p.form == FormKind::LeastSquares {
                super::least_squares::assemble(&mut model);
            }
        }
        Ok(model)
    }

    /// Replaces the master masses (e.g. a bar of two materials), in this model and in the
    /// D = 1 model that evaluates the forms of every dimension.
    pub fn set_masses(&mut self, mass: Vec<f64>) -> Result<()> {
        if mass.len() != self.x_ref.len() {
            return Err(crate::error::Error::Incompatible(
                format!(
                    "masses: {} given for {} particles",
                    mass.len(),
                    self.x_ref.len()
                )
                .into(),
            ));
        }
        if let Some(nd) = &mut self.nd {
            nd.mass.clone_from(&mass);
        }
        self.mass = mass;
        Ok(())
    }

    /// Minimum-image relative position `b − a`.
    #[inline]
    pub fn rel<S: Scalar>(&self, a: S, b: S) -> S {
        let d = b - a;
        match self.period {
            Some(l) => {
                let k = (d.re() / l).round();
                if k != 0.0 { d - k * l } else { d }
            }
            None => d,
        }
    }

    /// Shape functions of all masters within the support of reference point `x` (masters
    /// found by `search`, prepared for the reference positions; O(1) per point along an
    /// ordered chain).
    fn ref_stencil(&self, x: f64, search: &mut ChainSearch) -> Result<RefStencil> {
        let r = self.p.kp.support();
        let mut nodes = Vec::new();
        let mut idx = Vec::new();
        let mut cand = Vec::new();
        search.candidates(x, r, &mut cand);
        for j in cand {
            let d = self.rel(x, self.x_ref[j]);
            if d.abs() < r {
                nodes.push((d, self.vol_ref[j]));
                idx.push(j);
            }
        }
        let vals = shape::eval_with_second(self.p.shape, self.p.kp, &nodes, x)?;
        Ok(RefStencil {
            entries: idx.into_iter().zip(vals).collect(),
        })
    }

    /// The state at rest in the reference configuration with uniform density ρ0 and
    /// stress σ0 (the linearisation base state, and a solver's initial state).
    pub fn rest_state(&self) -> State1D<f64> {
        let n = self.x_ref.len();
        let mut z = State1D {
            x: self.x_ref.clone(),
            v: vec![0.0; n],
            ..Default::default()
        };
        for &f in self.p.form.fields() {
            match f {
                Field::Rho => z.rho = vec![self.p.rho0; n],
                Field::Sigma => z.sigma = vec![self.p.sigma0; n],
                Field::Tau => z.tau = vec![self.p.sigma0; n],
                Field::SpX => z.sp_x = self.sp_x_ref.clone(),
                Field::SpSigma => z.sp_sigma = vec![self.p.sigma0; self.sp_x_ref.len()],
                Field::SpVol => z.sp_vol = self.sp_vol_ref.clone(),
                Field::X | Field::V => {}
            }
        }
        z
    }
}

/// Reusable buffers of the 1D rate evaluation ([`Model1D::rate_with`]), generic over the
/// scalar `S` (`f64` for the solver, a dual number for the linearisation): the D = 1
/// [`RateWorkspace`] of the forms of every dimension (cell list, stencils, per-particle rates),
/// and for the 1D-only forms the master volumes, the flat stencils of masters and stress
/// points, the neighbour search of the chain and the displacements. Buffers are cleared and
/// refilled, never freed: once grown, an evaluation does not allocate.
///
/// One workspace may serve any number of models and states, one after another: results do not
/// depend on what it was used for before (the D = 1 part keeps its stencils only for an
/// evaluation at bitwise the same positions, densities, masses and kernel parameters). So the
/// linearisation can hold one `Workspace1D<Dual>` for a whole sweep — build each cell's
/// [`Model1D`], call [`Model1D::rate_with`] once per direction with the same workspace — and
/// allocate only in the first cell (and when a cell has more neighbours than any before).
#[derive(Clone, Debug)]
pub struct Workspace1D<S> {
    pub(crate) nd: RateWorkspace<S, 1>,
    pub(crate) vol: Vec<S>,
    pub(crate) st_m: Stencils<S>,
    pub(crate) st_s: Stencils<S>,
    pub(crate) scratch: StencilScratch<S>,
    pub(crate) u: Vec<S>,
}

impl<S> Default for Workspace1D<S> {
    fn default() -> Self {
        Self {
            nd: RateWorkspace::default(),
            vol: Vec::new(),
            st_m: Stencils::default(),
            st_s: Stencils::default(),
            scratch: StencilScratch::default(),
            u: Vec::new(),
        }
    }
}

impl<S: Scalar> Workspace1D<S> {
    /// An empty workspace (allocates nothing until first used).
    pub fn new() -> Self {
        Self::default()
    }

    /// Bytes reserved by the buffers (capacities), for memory reports.
    pub fn reserved_bytes(&self) -> usize {
        let s = std::mem::size_of::<S>();
        self.nd.reserved_bytes()
            + (self.vol.capacity() + self.u.capacity()) * s
            + self.st_m.capacity_bytes()
            + self.st_s.capacity_bytes()
            + self.scratch.capacity_bytes()
    }
}

/// Buffers of a [`FlatSystem`] kept across time steps (a run holds one, see
/// [`FlatSystem::with_cache`]): the state and rate buffers, the [`Workspace1D`], the factorised
/// consistent mass, and the last evaluation with the exact state it was made at.
#[derive(Clone, Debug, Default)]
pub struct FlatCache {
    z: State1D<f64>,
    out: State1D<f64>,
    ws: Workspace1D<f64>,
    /// The consistent-mass rows the factorisation was made of, and the factorisation.
    mass_rows: Vec<Vec<(usize, f64)>>,
    mass_lu: Option<BandedLu>,
    solve_work: Vec<f64>,
    /// Accelerations of the last evaluation (M⁻¹ f for a consistent mass).
    acc: Vec<f64>,
    /// (x, v, q) of the last evaluation, as bits (`None`: no valid evaluation).
    key: Vec<u64>,
    valid: bool,
    /// Whole evaluations of the rate function made through this cache.
    evaluations: usize,
}

impl FlatCache {
    /// Gives the state buffer the field lengths of `z`.
    pub fn shape_like(&mut self, z: &State1D<f64>) {
        self.z.resize_like(z);
    }

    /// Whole evaluations of the rate function made through this cache so far.
    pub fn evaluations(&self) -> usize {
        self.evaluations
    }
}

/// The model as a [`crate::integrator::SecondOrderSystem`] over flat `f64` arrays: `x`, `v`
/// the masters, `q` the auxiliary fields of the form concatenated in [`FormKind::fields`]
/// order. For a consistent mass (least squares) the acceleration solves M a = f with a banded
/// LU factorisation ([`BandedLu`]: O(N) per solve; periodic chains reordered to be banded),
/// computed once per run (M is constant: reference configuration).
///
/// One rate evaluation serves every request at the same state: the last evaluation is kept
/// with the exact (bitwise) state it was made at, so `accel` and `qrate` at one state — a
/// `rates` call, or the two separate calls — cost one evaluation. And the accelerations do not
/// depend on the velocities unless the model has artificial viscosity
/// ([`crate::integrator::SecondOrderSystem::accel_depends_on_velocity`]), which lets `kdk` reuse its end-of-step
/// acceleration. Neither changes a result: the rate function is deterministic.
pub struct FlatSystem<'a> {
    model: &'a Model1D,
    cache: RefCell<FlatCache>,
}

impl<'a> FlatSystem<'a> {
    /// Wraps `model`; `template` fixes the field lengths (e.g. [`Model1D::rest_state`]).
    pub fn new(model: &'a Model1D, template: State1D<f64>) -> Result<Self> {
        let cache = FlatCache {
            z: template,
            ..Default::default()
        };
        Self::with_cache(model, cache)
    }

    /// Wraps `model` with the buffers of an earlier [`FlatSystem`] ([`FlatSystem::into_cache`]),
    /// whose `z` buffer has the field lengths (a run keeps one across steps: no allocation,
    /// no refactorisation of the mass). The cached evaluation is dropped (the model may differ);
    /// the mass factorisation is kept when the model's consistent mass is the same.
    pub fn with_cache(model: &'a Model1D, mut cache: FlatCache) -> Result<Self> {
        cache.valid = false;
        match &model.mass_op {
            MassOperator::Lumped => {
                cache.mass_lu = None;
                cache.mass_rows.clear();
            }
            MassOperator::Consistent(rows) => {
                if cache.mass_lu.is_none() || cache.mass_rows != *rows {
                    cache.mass_lu = BandedLu::new(rows, model.period.is_some());
                    cache.mass_rows.clone_from(rows);
                    if cache.mass_lu.is_none() {
                        return Err(crate::error::Error::SingularMoment {
                            what: "consistent mass matrix",
                            x: 0.0,
                            det: 0.0,
                        });
                    }
                }
            }
        }
        Ok(Self {
            model,
            cache: RefCell::new(cache),
        })
    }

    /// The buffers, for the next [`FlatSystem::with_cache`].
    pub fn into_cache(self) -> FlatCache {
        self.cache.into_inner()
    }

    /// Whole evaluations of the rate function made so far (tests, cost models).
    pub fn evaluations(&self) -> usize {
        self.cache.borrow().evaluations
    }

    fn aux(&self) -> impl Iterator<Item = Field> + '_ {
        aux_fields(self.model)
    }

    /// Splits a state into (x, v, q).
    pub fn flatten(&self, z: &State1D<f64>) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (mut x, mut v, mut q) = (Vec::new(), Vec::new(), Vec::new());
        self.flatten_into(z, &mut x, &mut v, &mut q);
        (x, v, q)
    }

    /// Splits a state into (x, v, q), reusing the vectors' storage.
    pub fn flatten_into(
        &self,
        z: &State1D<f64>,
        x: &mut Vec<f64>,
        v: &mut Vec<f64>,
        q: &mut Vec<f64>,
    ) {
        x.clone_from(&z.x);
        v.clone_from(&z.v);
        q.clear();
        for f in self.aux() {
            q.extend_from_slice(z.field(f));
        }
    }

    /// Rebuilds a state from (x, v, q).
    pub fn unflatten(&self, x: &[f64], v: &[f64], q: &[f64]) -> State1D<f64> {
        let mut z = self.cache.borrow().z.clone();
        unflatten_into(self.model, x, v, q, &mut z);
        z
    }

    /// Writes (x, v, q) into `z`, whose fields have the right lengths.
    pub fn unflatten_into(&self, x: &[f64], v: &[f64], q: &[f64], z: &mut State1D<f64>) {
        unflatten_into(self.model, x, v, q, z);
    }

    /// Evaluates the rate function at (x, v, q) unless the last evaluation was made at exactly
    /// this state; returns the cache.
    fn eval(&self, x: &[f64], v: &[f64], q: &[f64]) -> std::cell::RefMut<'_, FlatCache> {
        let mut guard = self.cache.borrow_mut();
        let c = &mut *guard;
        let same = c.valid
            && c.key.len() == x.len() + v.len() + q.len()
            && c.key
                .iter()
                .zip(x.iter().chain(v).chain(q))
                .all(|(k, a)| *k == a.to_bits());
        if !same {
            unflatten_into(self.model, x, v, q, &mut c.z);
            // The rate function only fails on singular moment matrices, which a lumped-mass
            // system at a valid state does not have; a failure here is reported as NaN so the
            // caller's divergence check (never NaN in output) stops the run.
            if self.model.rate_with(&c.z, &mut c.out, &mut c.ws).is_err() {
                c.out.resize_like(&c.z);
                for a in c.out.v.iter_mut() {
                    *a = f64::NAN;
                }
            }
            c.acc.clear();
            match &c.mass_lu {
                None => c.acc.extend_from_slice(&c.out.v),
                Some(lu) => {
                    c.acc.resize(c.out.v.len(), 0.0);
                    lu.solve(&c.out.v, &mut c.acc, &mut c.solve_work);
                }
            }
            c.key.clear();
            c.key
                .extend(x.iter().chain(v).chain(q).map(|a| a.to_bits()));
            c.valid = true;
            c.evaluations += 1;
        }
        guard
    }

    fn copy_aux(&self, c: &FlatCache, r: &mut [f64]) {
        let mut at = 0;
        for f in self.aux() {
            let src = c.out.field(f);
            r[at..at + src.len()].copy_from_slice(src);
            at += src.len();
        }
    }
}

fn aux_fields(model: &Model1D) -> impl Iterator<Item = Field> + '_ {
    model
        .p
        .form
        .fields()
        .iter()
        .copied()
        .filter(|f| f.kind() == FieldKind::Auxiliary)
}

fn unflatten_into(model: &Model1D, x: &[f64], v: &[f64], q: &[f64], z: &mut State1D<f64>) {
    z.x.copy_from_slice(x);
    z.v.copy_from_slice(v);
    let mut at = 0;
    for f in aux_fields(model) {
        let dst = z.field_mut(f);
        let n = dst.len();
        dst.copy_from_slice(&q[at..at + n]);
        at += n;
    }
}

impl crate::integrator::SecondOrderSystem<f64> for FlatSystem<'_> {
    fn accel(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64]) {
        let c = self.eval(x, v, q);
        a.copy_from_slice(&c.acc);
    }
    fn qrate(&self, x: &[f64], v: &[f64], q: &[f64], r: &mut [f64]) {
        let c = self.eval(x, v, q);
        self.copy_aux(&c, r);
    }
    fn rates(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64], r: &mut [f64]) {
        let c = self.eval(x, v, q);
        a.copy_from_slice(&c.acc);
        self.copy_aux(&c, r);
    }
    /// Only the artificial viscosity makes the force depend on the velocity (every 1D form's
    /// momentum rate reads positions, densities and stresses; δ-SPH acts on the density rate).
    fn accel_depends_on_velocity(&self) -> bool {
        self.model.p.av.is_some()
    }
}
