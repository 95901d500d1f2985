//! A 2D particle run: model, state, boundary mask, time.
//!
//! Boundary particles are fixed (x and v held) but take part in every sum; their density (and
//! stress, for elastic materials) either evolves by continuity like everyone else's or is frozen
//! ([`BoundaryDensity`]).

use crate::error::{Error, Result};
use crate::forms::{Comp2, FieldKind, Model2D, State2D};
use crate::integrator::{Scratch, SecondOrderSystem, kdk_step};

/// Treatment of the boundary particles' auxiliary state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BoundaryDensity {
    /// Density (and stress) evolve by continuity.
    Evolve,
    /// Density (and stress) stay at their initial values.
    Frozen,
}

/// A 2D run.
#[derive(Clone, Debug)]
pub struct Run2D {
    /// The model (form, kernel, material, masses, reference positions).
    pub model: Model2D,
    /// Current state.
    pub z: State2D<f64>,
    /// Fixed (boundary) particles.
    pub fixed: Vec<bool>,
    /// Boundary auxiliary-state treatment.
    pub boundary: BoundaryDensity,
    /// Time.
    pub t: f64,
    /// Steps taken.
    pub steps: usize,
    flat: Flat,
    scratch: Scratch<f64>,
}

/// Flat (x, v, q) layout of a [`State2D`].
#[derive(Clone, Debug)]
struct Flat {
    aux: Vec<Comp2>,
    n: usize,
}

impl Flat {
    fn split(&self, z: &State2D<f64>) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let x = z.x.iter().flat_map(|p| [p[0], p[1]]).collect();
        let v = z.v.iter().flat_map(|p| [p[0], p[1]]).collect();
        let mut q = Vec::with_capacity(self.aux.len() * self.n);
        for &c in &self.aux {
            q.extend((0..self.n).map(|i| z.get(c, i)));
        }
        (x, v, q)
    }
    fn join(&self, template: &State2D<f64>, x: &[f64], v: &[f64], q: &[f64]) -> State2D<f64> {
        let mut z = template.clone();
        for i in 0..self.n {
            z.x[i] = [x[2 * i], x[2 * i + 1]];
            z.v[i] = [v[2 * i], v[2 * i + 1]];
        }
        for (k, &c) in self.aux.iter().enumerate() {
            for i in 0..self.n {
                *z.get_mut(c, i) = q[k * self.n + i];
            }
        }
        z
    }
}

/// The run as a second-order system for the integrator.
struct Sys<'a> {
    run: &'a Run2D,
}

impl Sys<'_> {
    fn rate(&self, x: &[f64], v: &[f64], q: &[f64]) -> State2D<f64> {
        let z = self.run.flat.join(&self.run.z, x, v, q);
        let mut out = State2D::default();
        if self.run.model.rate(&z, &mut out).is_err() {
            // A singular moment matrix mid-run: NaN rates stop the run at the divergence check.
            out = State2D::zeros_like(&z);
            for a in out.v.iter_mut() {
                *a = [f64::NAN; 2];
            }
        }
        out
    }
}

impl SecondOrderSystem<f64> for Sys<'_> {
    fn accel(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64]) {
        let out = self.rate(x, v, q);
        for (i, ai) in out.v.iter().enumerate() {
            let keep = if self.run.fixed[i] { 0.0 } else { 1.0 };
            a[2 * i] = ai[0] * keep;
            a[2 * i + 1] = ai[1] * keep;
        }
    }
    fn accel_depends_on_velocity(&self) -> bool {
        self.run.model.p.av.is_some()
    }
    fn qrate(&self, x: &[f64], v: &[f64], q: &[f64], r: &mut [f64]) {
        let out = self.rate(x, v, q);
        let n = self.run.flat.n;
        for (k, &c) in self.run.flat.aux.iter().enumerate() {
            for i in 0..n {
                let frozen = self.run.fixed[i] && self.run.boundary == BoundaryDensity::Frozen;
                r[k * n + i] = if frozen { 0.0 } else { out.get(c, i) };
            }
        }
    }
}

impl Run2D {
    /// A run of `model` from state `z` with boundary mask `fixed`.
    pub fn new(
        model: Model2D,
        z: State2D<f64>,
        fixed: Vec<bool>,
        boundary: BoundaryDensity,
    ) -> Result<Self> {
        if fixed.len() != z.x.len() {
            return Err(Error::Incompatible(
                "boundary mask length differs from the particle count".into(),
            ));
        }
        let aux = model
            .p
            .form
            .comps_2d(&model.p.material)
            .into_iter()
            .filter(|c| c.kind() == FieldKind::Auxiliary)
            .collect();
        let n = z.x.len();
        Ok(Self {
            model,
            z,
            fixed,
            boundary,
            t: 0.0,
            steps: 0,
            flat: Flat { aux, n },
            scratch: Scratch::default(),
        })
    }

    /// One leapfrog step of size `dt` (physical time). Fixed particles keep x and v.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        let (mut x, mut v, mut q) = self.flat.split(&self.z);
        let mut scratch = std::mem::take(&mut self.scratch);
        kdk_step(&Sys { run: self }, &mut x, &mut v, &mut q, dt, &mut scratch);
        self.scratch = scratch;
        let z = self.flat.join(&self.z, &x, &v, &q);
        if z.v.iter().any(|p| !p[0].is_finite() || !p[1].is_finite()) {
            return Err(Error::NonFinite("solver state (the run diverged)"));
        }
        self.z = z;
        self.t += dt;
        self.steps += 1;
        Ok(())
    }

    /// Largest |v| over the free particles.
    pub fn max_free_speed(&self) -> f64 {
        self.z
            .v
            .iter()
            .zip(&self.fixed)
            .filter(|(_, f)| !**f)
            .map(|(v, _)| v[0].hypot(v[1]))
            .fold(0.0, f64::max)
    }
}
