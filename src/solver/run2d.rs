//! A particle run in D ∈ {1, 2, 3} dimensions: model, state, boundary mask, time.
//!
//! Boundary particles are fixed (x and v held) but take part in every sum; their density (and
//! stress, for elastic materials) either evolves by continuity like everyone else's or is frozen
//! ([`BoundaryDensity`]).

use std::cell::RefCell;

use crate::error::{Error, Result};
use crate::forms::{AuxRates, Comp, Model, RateOut, RateWorkspace, State, StateView, Tensor};
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

/// A run in D dimensions ([`Run2D`], [`Run3D`]).
///
/// The time loop allocates nothing once its buffers have grown (first step): positions and
/// velocities are advanced in place in [`Run::z`], the auxiliary state (ρ, σ, τ) in one
/// persistent flat buffer, and the rate function works on borrowed slices with a reusable
/// [`RateWorkspace`].
#[derive(Clone, Debug)]
pub struct Run<const D: usize = 2> {
    /// The model (form, kernel, material, masses, reference positions).
    pub model: Model<D>,
    /// Current state.
    pub z: State<f64, D>,
    /// Fixed (boundary) particles.
    pub fixed: Vec<bool>,
    /// Boundary auxiliary-state treatment.
    pub boundary: BoundaryDensity,
    /// Time.
    pub t: f64,
    /// Steps taken.
    pub steps: usize,
    layout: AuxLayout,
    bufs: StepBuffers<D>,
    stepper: Stepper<f64>,
}

/// A 2D run.
pub type Run2D = Run<2>;
/// A 3D run.
pub type Run3D = Run<3>;

/// Which auxiliary fields the form integrates (the others are left untouched).
#[derive(Clone, Copy, Debug)]
struct AuxLayout {
    rho: bool,
    sigma: bool,
    tau: bool,
}

/// Buffers reused by every step.
#[derive(Clone, Debug, Default)]
struct StepBuffers<const D: usize> {
    /// The integrated auxiliary state, flat: [ρ (n) | σ (D²n) | τ (D²n)] (fields present only).
    q: Vec<f64>,
    /// Rate-function workspace.
    ws: RateWorkspace<f64, D>,
    /// The `kdk` work arrays: the default scheme is stepped here directly, so that the
    /// general [`Stepper`]'s four state-sized work triples (which `kdk` never uses) are not
    /// allocated (288 B per particle in 2D).
    kdk: Scratch<f64>,
}

impl AuxLayout {
    fn lens(&self, n: usize, d: usize) -> [usize; 3] {
        [
            if self.rho { n } else { 0 },
            if self.sigma { d * d * n } else { 0 },
            if self.tau { d * d * n } else { 0 },
        ]
    }
}

/// Splits a flat auxiliary buffer into (ρ, σ, τ).
#[allow(clippy::type_complexity)]
fn split_aux<const D: usize>(
    q: &[f64],
    lens: [usize; 3],
) -> (&[f64], &[Tensor<f64, D>], &[Tensor<f64, D>]) {
    let (rho, rest) = q.split_at(lens[0]);
    let (sigma, tau) = rest.split_at(lens[1]);
    (
        rho,
        sigma.as_chunks::<D>().0.as_chunks::<D>().0,
        tau.as_chunks::<D>().0.as_chunks::<D>().0,
    )
}

/// The same, mutable.
fn split_aux_mut<const D: usize>(q: &mut [f64], lens: [usize; 3]) -> AuxRates<'_, f64, D> {
    let (rho, rest) = q.split_at_mut(lens[0]);
    let (sigma, tau) = rest.split_at_mut(lens[1]);
    AuxRates {
        rho,
        sigma: sigma.as_chunks_mut::<D>().0.as_chunks_mut::<D>().0,
        tau: tau.as_chunks_mut::<D>().0.as_chunks_mut::<D>().0,
    }
}

/// The run as a second-order system for the integrator, on the integrator's flat slices.
struct Sys<'a, const D: usize> {
    model: &'a Model<D>,
    fixed: &'a [bool],
    frozen_aux: bool,
    lens: [usize; 3],
    ws: RefCell<&'a mut RateWorkspace<f64, D>>,
}

impl<const D: usize> Sys<'_, D> {
    fn view<'b>(&self, x: &'b [f64], v: &'b [f64], q: &'b [f64]) -> StateView<'b, f64, D> {
        let (rho, sigma, tau) = split_aux(q, self.lens);
        StateView {
            x: x.as_chunks().0,
            v: v.as_chunks().0,
            rho,
            sigma,
            tau,
        }
    }
}

impl<const D: usize> Sys<'_, D> {
    /// Fixed particles do not accelerate.
    fn mask_accel(&self, a: &mut [f64]) {
        for (ai, &f) in a.as_chunks_mut::<D>().0.iter_mut().zip(self.fixed) {
            let keep = if f { 0.0 } else { 1.0 };
            *ai = ai.map(|c| c * keep);
        }
    }

    /// Frozen boundary particles keep their density and stress.
    fn mask_qrate(&self, r: &mut [f64]) {
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
            }
        }
    }
}

impl<const D: usize> SecondOrderSystem<f64> for Sys<'_, D> {
    fn accel(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64]) {
        let out = RateOut {
            v: Some(a.as_chunks_mut().0),
            ..Default::default()
        };
        let mut ws = self.ws.borrow_mut();
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
        let out = RateOut {
            aux: Some(split_aux_mut(r, self.lens)),
            ..Default::default()
        };
        let mut ws = self.ws.borrow_mut();
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
        let out = RateOut {
            v: Some(a.as_chunks_mut().0),
            aux: Some(split_aux_mut(r, self.lens)),
            ..Default::default()
        };
        let mut ws = self.ws.borrow_mut();
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
        let comps = model.p.form.comps(D, &model.p.material);
        let layout = AuxLayout {
            rho: comps.contains(&Comp::Rho),
            sigma: comps.contains(&Comp::Sigma(0)),
            tau: comps.contains(&Comp::Tau(0)),
        };
        let run = Self {
            model,
            z,
            fixed,
            boundary,
            t: 0.0,
            steps: 0,
            layout,
            bufs: StepBuffers::default(),
            stepper: Stepper::new(Integrator::Kdk),
        };
        run.check_state()?;
        Ok(run)
    }

    /// The state has every field the form integrates, one entry per particle.
    fn check_state(&self) -> Result<()> {
        let n = self.z.x.len();
        let z = &self.z;
        let l = self.layout;
        if z.v.len() != n
            || self.fixed.len() != n
            || (l.rho && z.rho.len() != n)
            || (l.sigma && z.sigma.len() != n)
            || (l.tau && z.tau.len() != n)
        {
            return Err(Error::Incompatible(
                "particle state: x, v, the boundary mask and every integrated field (ρ, σ, τ) need one \
                 entry per particle"
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

    /// The time integrator.
    pub fn integrator(&self) -> Integrator {
        self.stepper.integrator
    }

    /// One step of size `dt` (physical time) of the run's integrator, in place. Fixed particles keep x and v.
    /// If the run diverges (a non-finite velocity), the error is returned and the state holds
    /// the non-finite values of the failed step.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        self.check_state()?;
        let n = self.z.x.len();
        let lens = self.layout.lens(n, D);
        let z = &mut self.z;
        let q = &mut self.bufs.q;
        q.clear();
        q.extend_from_slice(if self.layout.rho { &z.rho } else { &[] });
        q.extend_from_slice(if self.layout.sigma {
            z.sigma.as_flattened().as_flattened()
        } else {
            &[]
        });
        q.extend_from_slice(if self.layout.tau {
            z.tau.as_flattened().as_flattened()
        } else {
            &[]
        });
        let sys = Sys {
            model: &self.model,
            fixed: &self.fixed,
            frozen_aux: self.boundary == BoundaryDensity::Frozen,
            lens,
            ws: RefCell::new(&mut self.bufs.ws),
        };
        let (x, v) = (z.x.as_flattened_mut(), z.v.as_flattened_mut());
        if self.stepper.integrator == Integrator::Kdk {
            // what `Stepper::step` does for kdk, without its unused work arrays
            kdk_step(&sys, x, v, q, dt, &mut self.bufs.kdk);
        } else {
            self.stepper.step(&sys, x, v, q, dt);
        }
        let (rho, sigma, tau) = split_aux(q, lens);
        if self.layout.rho {
            z.rho.copy_from_slice(rho);
        }
        if self.layout.sigma {
            z.sigma.copy_from_slice(sigma);
        }
        if self.layout.tau {
            z.tau.copy_from_slice(tau);
        }
        if z.v.iter().any(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(Error::NonFinite("solver state (the run diverged)"));
        }
        self.t += dt;
        self.steps += 1;
        Ok(())
    }

    /// Whether the stencil builds reuse unchanged pairs (default `true`; bitwise the same
    /// results, see [`RateWorkspace::set_pair_reuse`]).
    pub fn set_pair_reuse(&mut self, on: bool) {
        self.bufs.ws.set_pair_reuse(on);
    }

    /// (full builds, pair refreshes) of the stencils so far ([`RateWorkspace::stencil_builds`]).
    pub fn stencil_builds(&self) -> (u64, u64) {
        self.bufs.ws.stencil_builds()
    }

    /// Mean number of neighbours per particle (itself included) in the last rate evaluation's
    /// stencils (Eulerian forms; `None` before the first step and for total-Lagrangian forms).
    pub fn mean_neighbours(&self) -> Option<f64> {
        self.bufs.ws.mean_neighbours()
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
        state + model + self.bufs.q.capacity() * 8 + self.bufs.ws.reserved_bytes() + kdk
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
