//! A particle run in D ∈ {1, 2, 3} dimensions, every form: model, state, boundary mask, time,
//! stepped by one of the shared integrators (default `kdk`).
//!
//! Boundary particles have a prescribed velocity (their initial one, zero for a fixed wall): they
//! do not accelerate but take part in every sum; their density (and stress, for elastic
//! materials) either evolves by continuity like everyone else's or is frozen
//! ([`BoundaryDensity`]). The least-squares form's consistent mass is solved in O(N) with the
//! model's banded factorisation ([`BandedLu`]), factorised once per run.

use std::cell::{Cell, RefCell};

use crate::error::{Error, Result};
use crate::forms::{
    AuxRates, BandedLu, Comp, MassOperator, Model, RateOut, RateWorkspace, State, StateView, Tensor,
};
use crate::integrator::{Integrator, Scratch, SecondOrderSystem, Stepper, kdk_step};

/// Treatment of the boundary particles' auxiliary state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BoundaryDensity {
    /// Density (and stress) evolve by continuity.
    Evolve,
    /// Density (and stress) stay at their initial values.
    Frozen,
}

/// A ghost particle of one or more symmetry planes: the image of a `source` particle, so that
/// the source's neighbourhood is whole across the plane. Across the planes x_a = p_a of the
/// axes a with `sign[a]` = −1 (`offset[a]` = 2 p_a; 0 and +1 on the other axes):
/// x_g = S x_s + b, v_g = S v_s + ḃ, ρ_g = ρ_s, σ_g = S σ_s S (S = diag(sign), b = `offset`,
/// ḃ = `offset_rate`, the velocity of a moving plane doubled, held over a step like a load:
/// [`Run::step`] advances b by ḃ Δt). A ghost takes part in every sum
/// of the rate function as a particle; its own rates are replaced by the mirrored rates of
/// its source, so the integrators keep it the image of its source (exactly, up to rounding,
/// which [`Run::step`] removes at each step's start and end). The ghost is a particle of the
/// model (reference position, volume, mass: its source's mirrored).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mirror<const D: usize> {
    /// The ghost's particle index.
    pub ghost: usize,
    /// Its source's particle index (a particle that is not itself a ghost).
    pub source: usize,
    /// S: −1 on the axes reflected, +1 on the others.
    pub sign: [f64; D],
    /// b (m): twice the plane's position on the reflected axes, 0 on the others.
    pub offset: [f64; D],
    /// ḃ (m/s): twice the plane's velocity on the reflected axes.
    pub offset_rate: [f64; D],
}

impl<const D: usize> Mirror<D> {
    /// σ_g = S σ_s S.
    fn tensor(&self, s: &Tensor<f64, D>) -> Tensor<f64, D> {
        std::array::from_fn(|a| std::array::from_fn(|b| self.sign[a] * self.sign[b] * s[a][b]))
    }
}

/// Von Mises (J2) plasticity with linear isotropic hardening, on the hypo-elastic material of
/// an Eulerian form in 3D: after each step the stress is returned radially to the yield
/// surface (the elastic predictor is the step, the plastic corrector the return: σ' ← σ'(1 −
/// 3G Δε̄ᵖ/q), Δε̄ᵖ = (q − σ_y)/(3G + H) where the von Mises stress q = √(3/2 σ':σ') exceeds
/// σ_y = σ_Y + H ε̄ᵖ; the pressure is elastic).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct J2 {
    /// Initial yield stress σ_Y (Pa).
    pub yield_stress: f64,
    /// Plastic (hardening) modulus H = dσ_y/dε̄ᵖ (Pa).
    pub hardening: f64,
}

/// A run in D dimensions.
///
/// The time loop allocates nothing once its buffers have grown (first step): positions and
/// velocities are advanced in place in [`Run::z`], the auxiliary state (ρ, σ, τ and the stress
/// points') in one persistent flat buffer, and the rate function works on borrowed slices with a
/// reusable [`RateWorkspace`].
#[derive(Clone, Debug)]
pub struct Run<const D: usize = 2> {
    /// The model (form, kernel, material, masses, reference positions).
    pub model: Model<D>,
    /// Current state.
    pub z: State<f64, D>,
    /// Boundary particles: their velocity is prescribed (kept at its initial value).
    pub fixed: Vec<bool>,
    /// Boundary auxiliary-state treatment.
    pub boundary: BoundaryDensity,
    /// External forces on the particles (N, or N per unit area in 1D and per unit thickness
    /// in 2D: the units of the model's masses times an acceleration), held constant over each
    /// step; empty: none. A time-dependent load is set before every step at the step's
    /// midpoint t + Δt/2 ([`Run::set_load`]).
    load: Vec<[f64; D]>,
    /// The ghost particles of symmetry planes ([`Mirror`]; empty: none), set by
    /// [`Run::set_mirror`].
    mirror: Vec<Mirror<D>>,
    /// J2 plasticity and the material's shear modulus G ([`Run::set_plasticity`]; None:
    /// elastic).
    plasticity: Option<(J2, f64)>,
    /// The equivalent plastic strain ε̄ᵖ of every particle (empty without plasticity).
    pub plastic_strain: Vec<f64>,
    /// Time.
    pub t: f64,
    /// Steps taken.
    pub steps: usize,
    bufs: StepBuffers<D>,
    stepper: Stepper<f64>,
}

/// Which auxiliary fields the form integrates (the others are left untouched).
#[derive(Clone, Copy, Debug)]
struct AuxLayout {
    rho: bool,
    sigma: bool,
    tau: bool,
    /// Number of stress points (0: none).
    sp: usize,
    /// The accumulated shear acceleration (`enog`).
    shear_acc: bool,
}

/// Buffers reused by every step.
#[derive(Clone, Debug)]
struct StepBuffers<const D: usize> {
    /// The integrated auxiliary state, flat ([`System::flatten_into`]).
    q: Vec<f64>,
    /// What the system of the model keeps between evaluations.
    sys: SystemBuffers<D>,
    /// The `kdk` work arrays: the default scheme is stepped here directly, so that the
    /// general [`Stepper`]'s four state-sized work triples (which `kdk` never uses) are not
    /// allocated (288 B per particle in 2D).
    kdk: Scratch<f64>,
}

/// What a [`System`] keeps between evaluations: the rate workspace, the factorised consistent
/// mass (least squares) and the work arrays of its solve, the auxiliary layout of the form, and
/// a count of the integrator's requests. Built once per model ([`SystemBuffers::new`]).
#[derive(Clone, Debug)]
pub struct SystemBuffers<const D: usize> {
    layout: AuxLayout,
    ws: RefCell<RateWorkspace<f64, D>>,
    mass: Option<BandedLu>,
    /// Work arrays of the consistent-mass solve: the force, and the solver's own.
    solve: RefCell<(Vec<f64>, Vec<f64>)>,
    /// `accel` + `qrate` requests of the integrator so far (a `rates` request counts 2).
    calls: Cell<u64>,
}

impl<const D: usize> SystemBuffers<D> {
    /// The buffers of `model`'s system (factorises a consistent mass once: O(N) banded LU).
    pub fn new(model: &Model<D>) -> Result<Self> {
        let comps = model.p.form.comps(D, &model.p.material);
        let layout = AuxLayout {
            rho: comps.contains(&Comp::Rho),
            sigma: comps.contains(&Comp::Sigma(0)),
            tau: comps.contains(&Comp::Tau(0)),
            sp: if comps.contains(&Comp::SpX(0)) {
                model.stress_points()
            } else {
                0
            },
            shear_acc: comps.contains(&Comp::ShearAcc(0)),
        };
        let mass = match model.mass_operator() {
            MassOperator::Lumped => None,
            MassOperator::Consistent(rows) => Some(
                BandedLu::new(rows, model.period.is_some()).ok_or(Error::SingularMoment {
                    what: "consistent mass matrix",
                    x: 0.0,
                    det: 0.0,
                })?,
            ),
        };
        Ok(Self {
            layout,
            ws: RefCell::new(RateWorkspace::default()),
            mass,
            solve: RefCell::default(),
            calls: Cell::new(0),
        })
    }

    /// The integrator's `accel` + `qrate` requests so far (a `rates` request counts 2).
    pub fn rate_calls(&self) -> u64 {
        self.calls.get()
    }
}

impl AuxLayout {
    /// Lengths of the flat parts: ρ, σ, τ, x^S, σ^S, V^S, a^s.
    fn lens(&self, n: usize, d: usize) -> [usize; 7] {
        [
            if self.rho { n } else { 0 },
            if self.sigma { d * d * n } else { 0 },
            if self.tau { d * d * n } else { 0 },
            d * self.sp,
            d * d * self.sp,
            self.sp,
            if self.shear_acc { d * n } else { 0 },
        ]
    }
}

/// The auxiliary fields of a flat buffer, as slices.
struct Aux<'a, const D: usize> {
    rho: &'a [f64],
    sigma: &'a [Tensor<f64, D>],
    tau: &'a [Tensor<f64, D>],
    sp_x: &'a [[f64; D]],
    sp_sigma: &'a [Tensor<f64, D>],
    sp_vol: &'a [f64],
    shear_acc: &'a [[f64; D]],
}

/// Splits a flat auxiliary buffer into its fields.
fn split_aux<const D: usize>(q: &[f64], lens: [usize; 7]) -> Aux<'_, D> {
    let (rho, rest) = q.split_at(lens[0]);
    let (sigma, rest) = rest.split_at(lens[1]);
    let (tau, rest) = rest.split_at(lens[2]);
    let (sp_x, rest) = rest.split_at(lens[3]);
    let (sp_sigma, rest) = rest.split_at(lens[4]);
    let (sp_vol, shear_acc) = rest.split_at(lens[5]);
    Aux {
        rho,
        sigma: sigma.as_chunks::<D>().0.as_chunks::<D>().0,
        tau: tau.as_chunks::<D>().0.as_chunks::<D>().0,
        sp_x: sp_x.as_chunks::<D>().0,
        sp_sigma: sp_sigma.as_chunks::<D>().0.as_chunks::<D>().0,
        sp_vol,
        shear_acc: shear_acc.as_chunks::<D>().0,
    }
}

/// The same, mutable.
fn split_aux_mut<const D: usize>(q: &mut [f64], lens: [usize; 7]) -> AuxRates<'_, f64, D> {
    let (rho, rest) = q.split_at_mut(lens[0]);
    let (sigma, rest) = rest.split_at_mut(lens[1]);
    let (tau, rest) = rest.split_at_mut(lens[2]);
    let (sp_x, rest) = rest.split_at_mut(lens[3]);
    let (sp_sigma, rest) = rest.split_at_mut(lens[4]);
    let (sp_vol, shear_acc) = rest.split_at_mut(lens[5]);
    AuxRates {
        rho,
        sigma: sigma.as_chunks_mut::<D>().0.as_chunks_mut::<D>().0,
        tau: tau.as_chunks_mut::<D>().0.as_chunks_mut::<D>().0,
        sp_x: sp_x.as_chunks_mut::<D>().0,
        sp_sigma: sp_sigma.as_chunks_mut::<D>().0.as_chunks_mut::<D>().0,
        sp_vol,
        shear_acc: shear_acc.as_chunks_mut::<D>().0,
    }
}

/// A model as a second-order system for the integrators ([`SecondOrderSystem`]), on flat
/// slices: `x`, `v` the particles' positions and velocities (D per particle), `q` the auxiliary
/// state [ρ (n) | σ (D²n) | τ (D²n) | x^S (D n_s) | σ^S (D² n_s) | V^S (n_s)] (the fields the
/// form carries). Boundary particles (`fixed`) do not accelerate; with a consistent mass the
/// acceleration solves M a = f. A [`Run`] steps one; tests and studies may drive one directly.
pub struct System<'a, const D: usize> {
    model: &'a Model<D>,
    fixed: &'a [bool],
    load: &'a [[f64; D]],
    mirror: &'a [Mirror<D>],
    frozen_aux: bool,
    lens: [usize; 7],
    bufs: &'a SystemBuffers<D>,
}

impl<'a, const D: usize> System<'a, D> {
    /// The system of `model` with boundary mask `fixed` (one entry per particle) and buffers
    /// `bufs` (made by [`SystemBuffers::new`] for this model).
    pub fn new(
        model: &'a Model<D>,
        fixed: &'a [bool],
        boundary: BoundaryDensity,
        bufs: &'a SystemBuffers<D>,
    ) -> Self {
        Self {
            model,
            fixed,
            load: &[],
            mirror: &[],
            frozen_aux: boundary == BoundaryDensity::Frozen,
            lens: bufs.layout.lens(fixed.len(), D),
            bufs,
        }
    }

    /// The system with external forces `load` (one per particle, or empty: none) added to
    /// the rate's forces.
    pub fn with_load(mut self, load: &'a [[f64; D]]) -> Self {
        self.load = load;
        self
    }

    /// The system with the ghost particles `mirror` ([`Mirror`]): their rates are replaced by
    /// their sources' mirrored ones.
    pub fn with_mirror(mut self, mirror: &'a [Mirror<D>]) -> Self {
        self.mirror = mirror;
        self
    }

    /// Writes the auxiliary state of `z` into the flat `q` (cleared first).
    pub fn flatten_into(&self, z: &State<f64, D>, q: &mut Vec<f64>) {
        let l = self.bufs.layout;
        q.clear();
        q.extend_from_slice(if l.rho { &z.rho } else { &[] });
        q.extend_from_slice(if l.sigma {
            z.sigma.as_flattened().as_flattened()
        } else {
            &[]
        });
        q.extend_from_slice(if l.tau {
            z.tau.as_flattened().as_flattened()
        } else {
            &[]
        });
        if l.sp > 0 {
            q.extend_from_slice(z.sp_x.as_flattened());
            q.extend_from_slice(z.sp_sigma.as_flattened().as_flattened());
            q.extend_from_slice(&z.sp_vol);
        }
        if l.shear_acc {
            q.extend_from_slice(z.shear_acc.as_flattened());
        }
    }

    /// Writes the flat auxiliary state `q` back into the fields of `z`.
    pub fn unflatten_into(&self, q: &[f64], z: &mut State<f64, D>) {
        let l = self.bufs.layout;
        let a = split_aux(q, self.lens);
        if l.rho {
            z.rho.copy_from_slice(a.rho);
        }
        if l.sigma {
            z.sigma.copy_from_slice(a.sigma);
        }
        if l.tau {
            z.tau.copy_from_slice(a.tau);
        }
        if l.sp > 0 {
            z.sp_x.copy_from_slice(a.sp_x);
            z.sp_sigma.copy_from_slice(a.sp_sigma);
            z.sp_vol.copy_from_slice(a.sp_vol);
        }
        if l.shear_acc {
            z.shear_acc.copy_from_slice(a.shear_acc);
        }
    }

    fn view<'b>(&self, x: &'b [f64], v: &'b [f64], q: &'b [f64]) -> StateView<'b, f64, D> {
        let a = split_aux(q, self.lens);
        StateView {
            x: x.as_chunks().0,
            v: v.as_chunks().0,
            rho: a.rho,
            sigma: a.sigma,
            tau: a.tau,
            sp_x: a.sp_x,
            sp_sigma: a.sp_sigma,
            sp_vol: a.sp_vol,
            shear_acc: a.shear_acc,
        }
    }
}

impl<const D: usize> System<'_, D> {
    /// Adds the external forces; fixed particles do not accelerate. With a consistent mass,
    /// `a` holds the force f on entry and is replaced by the solution of M a = f first.
    fn mask_accel(&self, a: &mut [f64]) {
        if !self.load.is_empty() {
            let consistent = self.bufs.mass.is_some();
            for ((ai, f), m) in a
                .as_chunks_mut::<D>()
                .0
                .iter_mut()
                .zip(self.load)
                .zip(&self.model.mass)
            {
                let w = if consistent { 1.0 } else { 1.0 / m };
                for (c, fc) in ai.iter_mut().zip(f) {
                    *c += fc * w;
                }
            }
        }
        if let Some(lu) = &self.bufs.mass {
            let mut guard = self.bufs.solve.borrow_mut();
            let (f, work) = &mut *guard;
            f.clear();
            f.extend_from_slice(a);
            lu.solve(f, a, work);
        }
        let a = a.as_chunks_mut::<D>().0;
        for (ai, &f) in a.iter_mut().zip(self.fixed) {
            let keep = if f { 0.0 } else { 1.0 };
            *ai = ai.map(|c| c * keep);
        }
        for m in self.mirror {
            let s = a[m.source];
            a[m.ghost] = std::array::from_fn(|k| m.sign[k] * s[k]);
        }
    }

    /// Frozen boundary particles keep their density and stress; ghosts take their sources'
    /// mirrored rates.
    fn mask_qrate(&self, r: &mut [f64]) {
        if !self.mirror.is_empty() {
            let out = split_aux_mut::<D>(r, self.lens);
            for m in self.mirror {
                if !out.rho.is_empty() {
                    out.rho[m.ghost] = out.rho[m.source];
                }
                if !out.sigma.is_empty() {
                    out.sigma[m.ghost] = m.tensor(&out.sigma[m.source]);
                }
                if !out.tau.is_empty() {
                    out.tau[m.ghost] = m.tensor(&out.tau[m.source]);
                }
                if !out.shear_acc.is_empty() {
                    let s = out.shear_acc[m.source];
                    out.shear_acc[m.ghost] = std::array::from_fn(|k| m.sign[k] * s[k]);
                }
            }
        }
        if self.frozen_aux {
            let out = split_aux_mut::<D>(r, self.lens);
            for (i, _) in self.fixed.iter().enumerate().filter(|(_, f)| **f) {
                if let Some(p) = out.rho.get_mut(i) {
                    *p = 0.0;
                }
                if let Some(p) = out.sigma.get_mut(i) {
                    *p = [[0.0; D]; D];
                }
                if let Some(p) = out.tau.get_mut(i) {
                    *p = [[0.0; D]; D];
                }
                if let Some(p) = out.shear_acc.get_mut(i) {
                    *p = [0.0; D];
                }
            }
        }
    }
}

impl<const D: usize> SecondOrderSystem<f64> for System<'_, D> {
    fn accel(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64]) {
        self.bufs.calls.set(self.bufs.calls.get() + 1);
        let out = RateOut {
            v: Some(a.as_chunks_mut().0),
            ..Default::default()
        };
        let mut ws = self.bufs.ws.borrow_mut();
        if self
            .model
            .rate_into(self.view(x, v, q), out, &mut ws)
            .is_err()
        {
            // A singular moment matrix mid-run: NaN rates stop the run at the divergence check.
            a.fill(f64::NAN);
        }
        self.mask_accel(a);
    }
    fn accel_depends_on_velocity(&self) -> bool {
        self.model.p.av.is_some()
    }
    fn qrate(&self, x: &[f64], v: &[f64], q: &[f64], r: &mut [f64]) {
        self.bufs.calls.set(self.bufs.calls.get() + 1);
        let out = RateOut {
            aux: Some(split_aux_mut(r, self.lens)),
            ..Default::default()
        };
        let mut ws = self.bufs.ws.borrow_mut();
        if self
            .model
            .rate_into(self.view(x, v, q), out, &mut ws)
            .is_err()
        {
            r.fill(0.0);
        }
        self.mask_qrate(r);
    }
    fn rates(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64], r: &mut [f64]) {
        self.bufs.calls.set(self.bufs.calls.get() + 2);
        let out = RateOut {
            v: Some(a.as_chunks_mut().0),
            aux: Some(split_aux_mut(r, self.lens)),
            ..Default::default()
        };
        let mut ws = self.bufs.ws.borrow_mut();
        if self
            .model
            .rate_into(self.view(x, v, q), out, &mut ws)
            .is_err()
        {
            a.fill(f64::NAN);
            r.fill(0.0);
        }
        self.mask_accel(a);
        self.mask_qrate(r);
    }
}

impl<const D: usize> Run<D> {
    /// A run of `model` from state `z` with boundary mask `fixed`.
    pub fn new(
        model: Model<D>,
        z: State<f64, D>,
        fixed: Vec<bool>,
        boundary: BoundaryDensity,
    ) -> Result<Self> {
        if fixed.len() != z.x.len() {
            return Err(Error::Incompatible(
                "boundary mask length differs from the particle count".into(),
            ));
        }
        let bufs = StepBuffers {
            q: Vec::new(),
            sys: SystemBuffers::new(&model)?,
            kdk: Scratch::default(),
        };
        let run = Self {
            model,
            z,
            fixed,
            boundary,
            load: Vec::new(),
            mirror: Vec::new(),
            plasticity: None,
            plastic_strain: Vec::new(),
            t: 0.0,
            steps: 0,
            bufs,
            stepper: Stepper::new(Integrator::Kdk),
        };
        run.check_state()?;
        Ok(run)
    }

    /// A run of `model` from `z` whose particles with `prescribed[i] = Some(v)` move at the
    /// constant velocity v (a velocity-prescribed boundary layer) and whose auxiliary state
    /// evolves everywhere ([`BoundaryDensity::Evolve`]).
    pub fn with_prescribed(
        model: Model<D>,
        mut z: State<f64, D>,
        prescribed: &[Option<[f64; D]>],
    ) -> Result<Self> {
        if prescribed.len() != z.v.len() {
            return Err(Error::Incompatible(
                "prescribed-velocity list length differs from the particle count".into(),
            ));
        }
        for (v, p) in z.v.iter_mut().zip(prescribed) {
            if let Some(pv) = p {
                *v = *pv;
            }
        }
        let fixed = prescribed.iter().map(Option::is_some).collect();
        Self::new(model, z, fixed, BoundaryDensity::Evolve)
    }

    /// The state has every field the form integrates, one entry per particle.
    fn check_state(&self) -> Result<()> {
        let n = self.z.x.len();
        let z = &self.z;
        let l = self.bufs.sys.layout;
        if z.v.len() != n
            || self.fixed.len() != n
            || (l.rho && z.rho.len() != n)
            || (l.sigma && z.sigma.len() != n)
            || (l.shear_acc && z.shear_acc.len() != n)
            || (l.tau && z.tau.len() != n)
            || z.sp_x.len() != l.sp
            || z.sp_sigma.len() != l.sp
            || z.sp_vol.len() != l.sp
        {
            return Err(Error::Incompatible(
                "particle state: x, v, the boundary mask and every integrated field (ρ, σ, τ) need one \
                 entry per particle, and the stress-point fields one per stress point"
                    .into(),
            ));
        }
        Ok(())
    }

    /// The time integrator of the following steps (default `kdk`; module docs of
    /// [`crate::integrator`]). Changing it starts the new scheme afresh (what a scheme carries
    /// between steps is rebuilt at its first step).
    pub fn set_integrator(&mut self, integrator: Integrator) {
        if self.stepper.integrator != integrator {
            self.stepper = Stepper::new(integrator);
            self.bufs.kdk = Scratch::default();
        }
    }

    /// Sets the external forces of the following steps (one per particle; an empty vector
    /// removes them). They are held constant over a step: a load that varies in time is set
    /// before each step at the step's midpoint, which integrates its impulse to second order
    /// in Δt with every integrator.
    pub fn set_load(&mut self, load: Vec<[f64; D]>) -> Result<()> {
        if !load.is_empty() && load.len() != self.z.x.len() {
            return Err(Error::Incompatible(
                "load: one force per particle (or none)".into(),
            ));
        }
        self.load = load;
        Ok(())
    }

    /// The external forces (empty: none).
    pub fn load(&self) -> &[[f64; D]] {
        &self.load
    }

    /// Sets the ghost particles of symmetry planes ([`Mirror`]) and makes each the image of
    /// its source now. Errors if an index is out of range, a source is itself a ghost, a
    /// ghost is listed twice, a sign is not ±1, or the form carries stress points (the 1D
    /// chain forms, whose stress points have no image).
    pub fn set_mirror(&mut self, mirror: Vec<Mirror<D>>) -> Result<()> {
        let n = self.z.x.len();
        let mut ghost = vec![false; n];
        for m in &mirror {
            if m.ghost >= n || m.source >= n || m.ghost == m.source || ghost[m.ghost] {
                return Err(Error::Incompatible(
                    "mirror: every ghost and source must be a particle, each ghost listed once and not its own source".into(),
                ));
            }
            ghost[m.ghost] = true;
            if m.sign.iter().any(|s| s.abs() != 1.0) {
                return Err(Error::Incompatible("mirror: every sign must be ±1".into()));
            }
        }
        if mirror.iter().any(|m| ghost[m.source]) {
            return Err(Error::Incompatible(
                "mirror: a source may not be a ghost (give a corner's ghost the composed reflection of a particle)".into(),
            ));
        }
        if !mirror.is_empty() && self.bufs.sys.layout.sp > 0 {
            return Err(Error::Incompatible(
                "symmetry planes are not available for the stress-point forms (their stress points have no image)".into(),
            ));
        }
        self.mirror = mirror;
        self.sync_mirror();
        Ok(())
    }

    /// Makes the material elastic–plastic ([`J2`]) from now on, every particle's ε̄ᵖ = 0. The
    /// return acts on the state after each step, so the integrator must carry no stress
    /// between steps ([`Integrator::memory`]: not `pec` or `verlet-euler`; the scenes check it).
    /// Errors unless the run is 3D (the plane-strain 2D state has no σ_zz to return) and its
    /// form is Eulerian with one hypo-elastic stress (classical, nonlocal, local), or if σ_Y or
    /// H is negative or not finite.
    pub fn set_plasticity(&mut self, j2: J2) -> Result<()> {
        let form = self.model.p.form;
        let shear = match self.model.p.material {
            crate::forms::Material::Elastic { shear, .. } => shear,
            _ => {
                return Err(Error::Incompatible(
                    "plasticity: the material must be the hypo-elastic `linear` one".into(),
                ));
            }
        };
        if D != 3
            || !matches!(
                form,
                crate::forms::FormKind::Classical
                    | crate::forms::FormKind::Nonlocal
                    | crate::forms::FormKind::Local
            )
        {
            return Err(Error::Incompatible(format!(
                "plasticity: in 3D with the forms classical, nonlocal and local (one stress), not {} in {D}D",
                form.name()
            )
            .into()));
        }
        crate::error::check_range("yield_stress", j2.yield_stress, 0.0, 1e30, true, true)?;
        crate::error::check_range("hardening", j2.hardening, 0.0, 1e30, true, true)?;
        self.plasticity = Some((j2, shear));
        self.plastic_strain = vec![0.0; self.z.x.len()];
        Ok(())
    }

    /// The plastic corrector of [`J2`] on every particle's stress.
    fn return_to_yield(&mut self) {
        let Some((j2, g)) = self.plasticity else {
            return;
        };
        for (s, ep) in self.z.sigma.iter_mut().zip(&mut self.plastic_strain) {
            let p = (0..D).map(|a| s[a][a]).sum::<f64>() / 3.0;
            let mut dev = *s;
            for (a, row) in dev.iter_mut().enumerate() {
                row[a] -= p;
            }
            let q = (1.5 * dev.iter().flatten().map(|v| v * v).sum::<f64>()).sqrt();
            let sy = j2.yield_stress + j2.hardening * *ep;
            if q <= sy {
                continue;
            }
            let dep = (q - sy) / (3.0 * g + j2.hardening);
            let f = 1.0 - 3.0 * g * dep / q;
            for a in 0..D {
                for b in 0..D {
                    s[a][b] = dev[a][b] * f + if a == b { p } else { 0.0 };
                }
            }
            *ep += dep;
        }
    }

    /// The ghost particles of symmetry planes. A moving plane sets `offset_rate` before each
    /// step (its value at the step's midpoint); each step advances `offset` by `offset_rate`
    /// Δt.
    pub fn mirror_mut(&mut self) -> &mut [Mirror<D>] {
        &mut self.mirror
    }

    /// Makes every ghost the image of its source ([`Mirror`]).
    fn sync_mirror(&mut self) {
        let z = &mut self.z;
        for m in &self.mirror {
            let (g, s) = (m.ghost, m.source);
            z.x[g] = std::array::from_fn(|k| m.sign[k] * z.x[s][k] + m.offset[k]);
            z.v[g] = std::array::from_fn(|k| m.sign[k] * z.v[s][k] + m.offset_rate[k]);
            if !z.rho.is_empty() {
                z.rho[g] = z.rho[s];
            }
            if !z.sigma.is_empty() {
                z.sigma[g] = m.tensor(&z.sigma[s]);
            }
            if !z.tau.is_empty() {
                z.tau[g] = m.tensor(&z.tau[s]);
            }
            if !z.shear_acc.is_empty() {
                z.shear_acc[g] = std::array::from_fn(|k| m.sign[k] * z.shear_acc[s][k]);
            }
        }
    }

    /// The time integrator.
    pub fn integrator(&self) -> Integrator {
        self.stepper.integrator
    }

    /// The integrator's `accel` + `qrate` requests of the rate function so far (a `rates`
    /// request, both at one state, counts 2).
    pub fn rate_calls(&self) -> u64 {
        self.bufs.sys.calls.get()
    }

    /// One step of size `dt` (physical time) of the run's integrator, in place. Boundary
    /// particles keep their velocity. If the run diverges (a non-finite velocity), the error is
    /// returned and the state holds the non-finite values of the failed step.
    ///
    /// For the Eulerian forms of every dimension, whose rate function runs parallel loops
    /// (rayon), the step runs on a thread of rayon's pool (`rayon::scope`: the current thread
    /// when it is one of the pool's, else one hand-over to the global pool per step), so those
    /// loops are not each injected into the pool from outside — a cross-thread round trip per
    /// loop, which dominated short chains and small 2D/3D boxes (the 21 × 21 Swegle box of
    /// \[V21\] Fig 13: 33 futex calls per step before, 3 after; its time loop 1.8× faster on one
    /// thread and on two).
    pub fn step(&mut self, dt: f64) -> Result<()> {
        let form = self.model.p.form;
        if form.in_every_dimension() && !form.is_lagrangian() {
            rayon::scope(|_| self.step_here(dt))
        } else {
            self.step_here(dt)
        }
    }

    fn step_here(&mut self, dt: f64) -> Result<()> {
        self.check_state()?;
        self.sync_mirror();
        let z = &mut self.z;
        let q = &mut self.bufs.q;
        let sys = System::new(&self.model, &self.fixed, self.boundary, &self.bufs.sys)
            .with_load(&self.load)
            .with_mirror(&self.mirror);
        sys.flatten_into(z, q);
        let (x, v) = (z.x.as_flattened_mut(), z.v.as_flattened_mut());
        if self.stepper.integrator == Integrator::Kdk {
            // what `Stepper::step` does for kdk, without its unused work arrays
            kdk_step(&sys, x, v, q, dt, &mut self.bufs.kdk);
        } else {
            self.stepper.step(&sys, x, v, q, dt);
        }
        sys.unflatten_into(q, z);
        if z.v.iter().any(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(Error::NonFinite("solver state (the run diverged)"));
        }
        self.return_to_yield();
        // a moving plane: b advances by ḃ Δt (ḃ held over the step, as a load)
        for m in &mut self.mirror {
            for (b, r) in m.offset.iter_mut().zip(m.offset_rate) {
                *b += r * dt;
            }
        }
        self.sync_mirror();
        self.t += dt;
        self.steps += 1;
        Ok(())
    }

    /// Scales the run's deviation from `base` by `s`: the state (positions, velocities and every
    /// integrated field, z ← base + s (z − base)) and what the integrator carries between steps
    /// (`pec`'s last rates, `verlet-euler`'s (v, q)ⁿ⁻¹). `base` must be an equilibrium at rest of
    /// the model (zero velocity, every rate zero), such as the rest state of a uniformly
    /// pre-stressed periodic lattice: a rate then is linear in the deviation to first order, so
    /// the run continues as the deviation scaled by `s` would. A growth measurement uses this to
    /// keep a small perturbation small without restarting the integrator (growth exponents by
    /// renormalisation).
    pub fn scale_perturbation(&mut self, base: &State<f64, D>, s: f64) -> Result<()> {
        if base.x.len() != self.z.x.len() || base.v.len() != self.z.v.len() {
            return Err(Error::Incompatible(
                "scale_perturbation: the base state has another particle count".into(),
            ));
        }
        if !s.is_finite() {
            return Err(Error::NonFinite("perturbation scale"));
        }
        let sys = System::new(&self.model, &self.fixed, self.boundary, &self.bufs.sys);
        let (mut qb, mut q) = (Vec::new(), Vec::new());
        sys.flatten_into(base, &mut qb);
        sys.flatten_into(&self.z, &mut q);
        if qb.len() != q.len() {
            return Err(Error::Incompatible(
                "scale_perturbation: the base state lacks a field the form integrates".into(),
            ));
        }
        let about = |y: &mut [f64], b: &[f64]| {
            for (yi, bi) in y.iter_mut().zip(b) {
                *yi = bi + s * (*yi - bi);
            }
        };
        about(&mut q, &qb);
        sys.unflatten_into(&q, &mut self.z);
        about(self.z.x.as_flattened_mut(), base.x.as_flattened());
        about(self.z.v.as_flattened_mut(), base.v.as_flattened());
        let m = &mut self.stepper.memory;
        if self.stepper.memory_valid {
            match self.stepper.integrator {
                // rates: zero at an equilibrium
                Integrator::Pec => {
                    for y in [&mut m.x, &mut m.v, &mut m.q] {
                        y.iter_mut().for_each(|c| *c *= s);
                    }
                }
                // (v, q)ⁿ⁻¹: states
                Integrator::VerletEuler { .. } => {
                    about(&mut m.v, base.v.as_flattened());
                    about(&mut m.q, &qb);
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Whether the stencil builds reuse unchanged pairs (default `true`; bitwise the same
    /// results, see [`RateWorkspace::set_pair_reuse`]).
    pub fn set_pair_reuse(&mut self, on: bool) {
        self.bufs.sys.ws.get_mut().set_pair_reuse(on);
    }

    /// The skin of the pair list as a fraction of the support radius (default
    /// [`crate::forms::default_skin`]; bitwise the same results for every skin, see
    /// [`RateWorkspace::set_skin`]).
    pub fn set_skin(&mut self, fraction: f64) {
        self.bufs.sys.ws.get_mut().set_skin(fraction);
    }

    /// (full builds, pair refreshes) of the stencils so far ([`RateWorkspace::stencil_builds`]).
    pub fn stencil_builds(&self) -> (u64, u64) {
        self.bufs.sys.ws.borrow().stencil_builds()
    }

    /// Mean number of neighbours per particle (itself included) in the last rate evaluation's
    /// stencils (Eulerian forms; `None` before the first step and for total-Lagrangian forms).
    pub fn mean_neighbours(&self) -> Option<f64> {
        self.bufs.sys.ws.borrow().mean_neighbours()
    }

    /// Bytes the run holds for its particles (capacities of every per-particle buffer): the
    /// state (x, v, ρ, σ, τ), the boundary mask, the model's masses, reference positions and
    /// volumes (and total-Lagrangian reference stencils), the flat auxiliary state of the step,
    /// the rate workspace ([`RateWorkspace::reserved_bytes`]: stencils, cell list, volumes,
    /// stresses, scratch) and the `kdk` integrator's work arrays (a, x½, q̇, and the end state
    /// when the forces do not depend on v), which it sizes to exactly these lengths (its
    /// capacities are private to it; other integrators' arrays are not counted).
    pub fn state_bytes(&self) -> usize {
        use std::mem::size_of;
        let z = &self.z;
        let m = &self.model;
        let vec = size_of::<[f64; D]>();
        let ten = size_of::<Tensor<f64, D>>();
        let state = (z.x.capacity() + z.v.capacity()) * vec
            + z.rho.capacity() * 8
            + (z.sigma.capacity() + z.tau.capacity()) * ten
            + self.fixed.capacity();
        let model = (m.mass.capacity() + m.vol_ref.capacity()) * 8
            + m.x_ref.capacity() * vec
            + m.ref_master
                .iter()
                .map(|s| s.capacity() * size_of::<(usize, f64, [f64; D])>())
                .sum::<usize>();
        let n = z.x.len();
        let nq = self.bufs.q.len();
        let kdk = if self.stepper.integrator == Integrator::Kdk && self.steps > 0 {
            let end = if self.model.p.av.is_some() {
                0
            } else {
                2 * n * D + nq
            };
            (2 * n * D + nq + end) * 8
        } else {
            0
        };
        state
            + model
            + self.bufs.q.capacity() * 8
            + self.bufs.sys.ws.borrow().reserved_bytes()
            + kdk
    }

    /// Largest |v| over the free particles.
    pub fn max_free_speed(&self) -> f64 {
        self.z
            .v
            .iter()
            .zip(&self.fixed)
            .filter(|(_, f)| !**f)
            .map(|(v, _)| norm(v))
            .fold(0.0, f64::max)
    }
}

/// |v| (hypot in 2D, as the 2D solver always computed it).
fn norm<const D: usize>(v: &[f64; D]) -> f64 {
    if D == 2 {
        v[0].hypot(v[1])
    } else {
        v.iter().map(|c| c * c).sum::<f64>().sqrt()
    }
}
