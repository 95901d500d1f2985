//! A 1D particle run: a [`Model1D`] stepped by one of the shared integrators (default `kdk`), with particles whose
//! velocity is prescribed (fixed: v = 0) and which still take part in every sum.
//!
//! The run keeps everything a step needs between steps — the integrator's work arrays, the
//! flat (x, v, q) arrays, the rate workspace and the factorised consistent mass
//! ([`FlatCache`]) — so the time loop does not allocate once the buffers have grown (the
//! first step), which `tests/no_alloc1d.rs` asserts.

use crate::error::{Error, Result};
use crate::forms::{FlatCache, FlatSystem, Model1D, State1D};
use crate::integrator::{Integrator, SecondOrderSystem, Stepper};

/// A 1D run.
#[derive(Clone, Debug)]
pub struct Run1D {
    /// The model.
    pub model: Model1D,
    /// State.
    pub z: State1D<f64>,
    /// Prescribed velocity per particle (None: free).
    pub prescribed: Vec<Option<f64>>,
    /// Time.
    pub t: f64,
    /// Steps taken.
    pub steps: usize,
    stepper: Stepper<f64>,
    /// Buffers of the system, kept across steps.
    cache: FlatCache,
    /// The flat state (x, v, q) the integrator advances.
    flat: [Vec<f64>; 3],
}

struct Masked<'a> {
    flat: FlatSystem<'a>,
    prescribed: &'a [Option<f64>],
}

impl Masked<'_> {
    fn mask(&self, a: &mut [f64]) {
        for (ai, p) in a.iter_mut().zip(self.prescribed) {
            if p.is_some() {
                *ai = 0.0;
            }
        }
    }
}

impl SecondOrderSystem<f64> for Masked<'_> {
    fn accel(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64]) {
        self.flat.accel(x, v, q, a);
        self.mask(a);
    }
    fn qrate(&self, x: &[f64], v: &[f64], q: &[f64], r: &mut [f64]) {
        self.flat.qrate(x, v, q, r);
    }
    fn rates(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64], r: &mut [f64]) {
        self.flat.rates(x, v, q, a, r);
        self.mask(a);
    }
    fn accel_depends_on_velocity(&self) -> bool {
        self.flat.accel_depends_on_velocity()
    }
}

impl Run1D {
    /// A run of `model` from `z`; particles with `prescribed[i] = Some(v)` move at v.
    pub fn new(model: Model1D, mut z: State1D<f64>, prescribed: Vec<Option<f64>>) -> Result<Self> {
        if prescribed.len() != z.x.len() {
            return Err(Error::Incompatible(
                "prescribed-velocity list length differs from the particle count".into(),
            ));
        }
        for (v, p) in z.v.iter_mut().zip(&prescribed) {
            if let Some(pv) = p {
                *v = *pv;
            }
        }
        Ok(Self {
            model,
            z,
            prescribed,
            t: 0.0,
            steps: 0,
            stepper: Stepper::new(Integrator::Kdk),
            cache: FlatCache::default(),
            flat: Default::default(),
        })
    }

    /// The time integrator of the following steps (default `kdk`); changing it starts the new
    /// scheme afresh.
    pub fn set_integrator(&mut self, integrator: Integrator) {
        if self.stepper.integrator != integrator {
            self.stepper = Stepper::new(integrator);
        }
    }

    /// The time integrator.
    pub fn integrator(&self) -> Integrator {
        self.stepper.integrator
    }

    /// Whole evaluations of the rate function so far (each serves every `accel`/`qrate`
    /// request of the integrator at its state).
    pub fn evaluations(&self) -> usize {
        self.cache.evaluations()
    }

    /// One step of the run's integrator.
    ///
    /// For the Eulerian forms of every dimension, whose rate function runs parallel loops
    /// (rayon), the step runs on a thread of rayon's pool (`rayon::scope`: the current thread
    /// when it is one of the pool's, else one hand-over to the global pool per step), so those
    /// loops are not each injected into the pool from outside — a cross-thread round trip per
    /// loop, which dominated short chains. The other forms' rates are sequential and step on
    /// the calling thread.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        let form = self.model.p.form;
        if form.in_2d() && !form.is_lagrangian() {
            rayon::scope(|_| self.step_here(dt))
        } else {
            self.step_here(dt)
        }
    }

    fn step_here(&mut self, dt: f64) -> Result<()> {
        let mut cache = std::mem::take(&mut self.cache);
        cache.shape_like(&self.z);
        let flat = FlatSystem::with_cache(&self.model, cache)?;
        let [x, v, q] = &mut self.flat;
        flat.flatten_into(&self.z, x, v, q);
        let sys = Masked {
            flat,
            prescribed: &self.prescribed,
        };
        self.stepper.step(&sys, x, v, q, dt);
        let finite = v.iter().all(|a| a.is_finite());
        if finite {
            sys.flat.unflatten_into(x, v, q, &mut self.z);
        }
        self.cache = sys.flat.into_cache();
        if !finite {
            return Err(Error::NonFinite("solver state (the run diverged)"));
        }
        self.t += dt;
        self.steps += 1;
        Ok(())
    }
}
