//! A 1D particle run: a [`Model1D`] stepped by one of the shared integrators (default `kdk`), with particles whose
//! velocity is prescribed (fixed: v = 0) and which still take part in every sum.

use crate::error::{Error, Result};
use crate::forms::{FlatSystem, Model1D, State1D};
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
}

struct Masked<'a> {
    flat: FlatSystem<'a>,
    prescribed: &'a [Option<f64>],
}

impl SecondOrderSystem<f64> for Masked<'_> {
    fn accel(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64]) {
        self.flat.accel(x, v, q, a);
        for (ai, p) in a.iter_mut().zip(self.prescribed) {
            if p.is_some() {
                *ai = 0.0;
            }
        }
    }
    fn qrate(&self, x: &[f64], v: &[f64], q: &[f64], r: &mut [f64]) {
        self.flat.qrate(x, v, q, r);
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

    /// One step of the run's integrator.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        let flat = FlatSystem::new(&self.model, self.z.clone())?;
        let (mut x, mut v, mut q) = flat.flatten(&self.z);
        let sys = Masked {
            flat,
            prescribed: &self.prescribed,
        };
        self.stepper.step(&sys, &mut x, &mut v, &mut q, dt);
        let z = sys.flat.unflatten(&x, &v, &q);
        if z.v.iter().any(|a| !a.is_finite()) {
            return Err(Error::NonFinite("solver state (the run diverged)"));
        }
        self.z = z;
        self.t += dt;
        self.steps += 1;
        Ok(())
    }
}
