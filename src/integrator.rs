//! The time integrator: kick–drift–kick leapfrog (central difference) in which *every* state
//! variable is advanced with the half-step velocity. One function, [`kdk_step`], serves the
//! solver (real state) and the analysis (complex Fourier amplitudes of one mode): the
//! amplification matrix is this step applied to the linearised system.
//!
//! ```text
//! v½  = vⁿ + Δt/2 · a(xⁿ, vⁿ, qⁿ)
//! x½  = xⁿ + Δt/2 · v½
//! qⁿ⁺¹ = qⁿ + Δt · q̇(x½, v½, qⁿ)
//! xⁿ⁺¹ = xⁿ + Δt · v½
//! vⁿ⁺¹ = v½ + Δt/2 · a(xⁿ⁺¹, v½, qⁿ⁺¹)
//! ```
//! Evaluating q̇ with v½ (not v^{n−½}) avoids the one-step lag that anti-damps every acoustic
//! mode at a rate ≈ ω²Δt/2. Velocity-dependent forces (artificial viscosity) in the second
//! kick see v½.

use std::ops::{Add, Mul};

/// A second-order system x' = v, v' = a(x, v, q), q' = r(x, v, q).
pub trait SecondOrderSystem<T> {
    /// Accelerations.
    fn accel(&self, x: &[T], v: &[T], q: &[T], a: &mut [T]);
    /// Rates of the auxiliary state.
    fn qrate(&self, x: &[T], v: &[T], q: &[T], r: &mut [T]);
    /// Whether the accelerations depend on the velocities (artificial viscosity). When they do
    /// not, the acceleration at the end of a step is reused for the first kick of the next one
    /// (same state, same value): two rate evaluations per step instead of three.
    fn accel_depends_on_velocity(&self) -> bool {
        true
    }
}

/// Work arrays for [`kdk_step`] (allocated once, reused every step), and the end-of-step
/// acceleration with the state it belongs to.
#[derive(Clone, Debug, Default)]
pub struct Scratch<T> {
    a: Vec<T>,
    xh: Vec<T>,
    r: Vec<T>,
    end_state: Vec<T>,
}

/// One kick–drift–kick step of size `dt`, in place.
pub fn kdk_step<T, D>(sys: &D, x: &mut [T], v: &mut [T], q: &mut [T], dt: f64, s: &mut Scratch<T>)
where
    T: Copy + Default + PartialEq + Add<Output = T> + Mul<f64, Output = T>,
    D: SecondOrderSystem<T>,
{
    let reuse = !sys.accel_depends_on_velocity()
        && s.a.len() == v.len()
        && s.end_state.len() == x.len() + v.len() + q.len()
        && s.end_state
            .iter()
            .zip(x.iter().chain(v.iter()).chain(q.iter()))
            .all(|(a, b)| a == b);
    s.a.resize(v.len(), T::default());
    s.xh.resize(x.len(), T::default());
    s.r.resize(q.len(), T::default());
    if !reuse {
        sys.accel(x, v, q, &mut s.a);
    }
    for (vi, &ai) in v.iter_mut().zip(&s.a) {
        *vi = *vi + ai * (0.5 * dt);
    }
    for ((xh, &xi), &vi) in s.xh.iter_mut().zip(x.iter()).zip(v.iter()) {
        *xh = xi + vi * (0.5 * dt);
    }
    sys.qrate(&s.xh, v, q, &mut s.r);
    for (qi, &ri) in q.iter_mut().zip(&s.r) {
        *qi = *qi + ri * dt;
    }
    for (xi, &vi) in x.iter_mut().zip(v.iter()) {
        *xi = *xi + vi * dt;
    }
    sys.accel(x, v, q, &mut s.a);
    for (vi, &ai) in v.iter_mut().zip(&s.a) {
        *vi = *vi + ai * (0.5 * dt);
    }
    if !sys.accel_depends_on_velocity() {
        s.end_state.clear();
        s.end_state
            .extend(x.iter().chain(v.iter()).chain(q.iter()).copied());
    }
}
