//! The time integrators SPH codes use, as one step function each. Every function serves the
//! solver (real state) and the analysis (complex Fourier amplitudes of one mode): the
//! amplification matrix of an integrator is its step applied to the linearised system
//! ([`crate::vonneumann::amplification`]).
//!
//! The system is x' = v, v' = a(x, v, q), q' = r(x, v, q) ([`SecondOrderSystem`]): x positions,
//! v velocities, q the auxiliary state (density, stress). Writing F(y) = (v, a, r) for the rate of
//! the whole state y = (x, v, q), one step of size Δt is:
//!
//! | name | update | follows |
//! |---|---|---|
//! | `kdk` | v½ = vⁿ + Δt/2 a(yⁿ); x½ = xⁿ + Δt/2 v½; qⁿ⁺¹ = qⁿ + Δt r(x½, v½, qⁿ); xⁿ⁺¹ = xⁿ + Δt v½; vⁿ⁺¹ = v½ + Δt/2 a(xⁿ⁺¹, v½, qⁿ⁺¹) | this project's default ([`kdk_step`]); velocity Verlet with q advanced by the mid-step velocity |
//! | `dkd` | x½ = xⁿ + Δt/2 vⁿ; q½ = qⁿ + Δt/2 r(yⁿ); vⁿ⁺¹ = vⁿ + Δt a(x½, vⁿ, q½); xⁿ⁺¹ = x½ + Δt/2 vⁿ⁺¹; qⁿ⁺¹ = q½ + Δt/2 r(x½, vⁿ⁺¹, q½) | position Verlet (drift–kick–drift), q treated as a position-like variable |
//! | `verlet-lagged` | v^{n+½} = v^{n−½} + Δt a(xⁿ, v^{n−½}, qⁿ); xⁿ⁺¹ = xⁿ + Δt v^{n+½}; qⁿ⁺¹ = qⁿ + Δt r(xⁿ, v^{n−½}, qⁿ) | the staggered leapfrog of many SPH codes, whose density/stress rate sees the velocity half a step late; the stored v is v^{n−½} (v^{−½} = v⁰) |
//! | `symplectic-euler-vx` | vⁿ⁺¹ = vⁿ + Δt a(yⁿ); xⁿ⁺¹ = xⁿ + Δt vⁿ⁺¹; qⁿ⁺¹ = qⁿ + Δt r(xⁿ, vⁿ⁺¹, qⁿ) | symplectic Euler, kick then drift (q drifts with the new velocity) |
//! | `symplectic-euler-xv` | xⁿ⁺¹ = xⁿ + Δt vⁿ; qⁿ⁺¹ = qⁿ + Δt r(yⁿ); vⁿ⁺¹ = vⁿ + Δt a(xⁿ⁺¹, vⁿ, qⁿ⁺¹) | symplectic Euler, drift then kick |
//! | `pec` | y½ = yⁿ + Δt/2 F_{n−½}; F_{n+½} = F(y½); yⁿ⁺¹ = yⁿ + Δt F_{n+½} (F_{−½} = F(y⁰)) | PySPH's `PECIntegrator`: predict with the rates of the previous evaluation, one evaluation per step |
//! | `epec` | y½ = yⁿ + Δt/2 F(yⁿ); yⁿ⁺¹ = yⁿ + Δt F(y½) | PySPH's `EPECIntegrator` (evaluate, predict, evaluate, correct); the same map as `rk2-midpoint` |
//! | `verlet-euler` | xⁿ⁺¹ = xⁿ + Δt vⁿ + Δt²/2 a(yⁿ); (v, q)ⁿ⁺¹ = (v, q)ⁿ⁻¹ + 2Δt (a, r)(yⁿ), except every N_s-th step: (v, q)ⁿ⁺¹ = (v, q)ⁿ + Δt (a, r)(yⁿ) | DualSPHysics' Verlet scheme (`--euler-every N_s`, default 40); as there, the stored (v, q)ⁿ⁻¹ start equal to (v, q)⁰ |
//! | `rk2-midpoint` | y½ = yⁿ + Δt/2 F(yⁿ); yⁿ⁺¹ = yⁿ + Δt F(y½) | explicit midpoint rule |
//! | `rk2-heun` | y* = yⁿ + Δt F(yⁿ); yⁿ⁺¹ = yⁿ + Δt/2 (F(yⁿ) + F(y*)) | Heun's method |
//! | `rk4` | the classical four-stage Runge–Kutta scheme | Kutta (1901) |
//! | `euler` | yⁿ⁺¹ = yⁿ + Δt F(yⁿ) | forward Euler: the control, unstable for every Δt without damping |
//!
//! On the undamped oscillator x'' = −ω²x (no q) the schemes are stable up to ωΔt = 2 (`kdk`,
//! `dkd`, `verlet-lagged`, both symplectic Euler variants), 2√2 (`rk4`), and never (`euler`,
//! `rk2-*`, `epec`: |λ| > 1 by O(Δt²) or O(Δt⁴) — the *weak* instability). `verlet-lagged` is
//! weakly unstable as soon as the stiffness acts through q (density, stress): the lag gives
//! |λ|² = 1 + ω²Δt², a growth ≈ ω²Δt/2 per unit time. [`Integrator::imaginary_axis_limit`]
//! gives the closed forms; the analysis finds the rest numerically.

use crate::error::{Error, Result};
use std::ops::{Add, Mul};

/// A second-order system x' = v, v' = a(x, v, q), q' = r(x, v, q).
pub trait SecondOrderSystem<T> {
    /// Accelerations.
    fn accel(&self, x: &[T], v: &[T], q: &[T], a: &mut [T]);
    /// Rates of the auxiliary state.
    fn qrate(&self, x: &[T], v: &[T], q: &[T], r: &mut [T]);
    /// Both at one state (a system that computes them in one pass overrides this).
    fn rates(&self, x: &[T], v: &[T], q: &[T], a: &mut [T], r: &mut [T]) {
        self.accel(x, v, q, a);
        self.qrate(x, v, q, r);
    }
    /// Whether the accelerations depend on the velocities (artificial viscosity). When they do
    /// not, `kdk` reuses the acceleration at the end of a step for the first kick of the next
    /// one (same state, same value): two rate evaluations per step instead of three.
    fn accel_depends_on_velocity(&self) -> bool {
        true
    }
}

/// N_s of `verlet-euler` when `euler_every` is not given (DualSPHysics' default).
pub const DEFAULT_EULER_EVERY: usize = 40;

/// Allowed range of `euler_every`.
/// The amplification of one cycle takes N_s steps per column, per mode and per bisection step, so
/// the bound keeps the analysis time bounded (3D `timestep --integrator verlet-euler
/// --euler-every 1000`: 0.3 s); DualSPHysics uses 40.
pub const EULER_EVERY_RANGE: (usize, usize) = (1, 1_000);

/// A time integrator (module docs for the update formulas).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// Kick–drift–kick leapfrog.
    Kdk,
    /// Drift–kick–drift leapfrog.
    Dkd,
    /// Staggered leapfrog with the density/stress rate at the lagged velocity v^{n−½}.
    VerletLagged,
    /// Symplectic Euler, kick then drift.
    SymplecticEulerVx,
    /// Symplectic Euler, drift then kick.
    SymplecticEulerXv,
    /// PySPH predict–evaluate–correct.
    Pec,
    /// PySPH evaluate–predict–evaluate–correct.
    Epec,
    /// DualSPHysics Verlet with an Euler step every `every` steps.
    VerletEuler {
        /// N_s.
        every: usize,
    },
    /// Explicit midpoint RK2.
    Rk2Midpoint,
    /// Heun RK2.
    Rk2Heun,
    /// Classical RK4.
    Rk4,
    /// Forward Euler.
    Euler,
}

/// The CLI names, in the order of the module docs.
pub const INTEGRATOR_NAMES: [&str; 12] = [
    "kdk",
    "dkd",
    "verlet-lagged",
    "symplectic-euler-vx",
    "symplectic-euler-xv",
    "pec",
    "epec",
    "verlet-euler",
    "rk2-midpoint",
    "rk2-heun",
    "rk4",
    "euler",
];

impl Integrator {
    /// The integrator of a name ([`INTEGRATOR_NAMES`]); `euler_every` is N_s of `verlet-euler`
    /// (checked for every name, so that a bad `euler_every` is reported whatever the
    /// integrator).
    pub fn from_name(name: &str, euler_every: usize) -> Result<Self> {
        let (lo, hi) = EULER_EVERY_RANGE;
        if !(lo..=hi).contains(&euler_every) {
            return Err(Error::OutOfRange {
                field: "euler_every",
                value: euler_every as f64,
                range: format!("an integer in [{lo}, {hi}]").into(),
            });
        }
        Ok(match name {
            "kdk" => Self::Kdk,
            "dkd" => Self::Dkd,
            "verlet-lagged" => Self::VerletLagged,
            "symplectic-euler-vx" => Self::SymplecticEulerVx,
            "symplectic-euler-xv" => Self::SymplecticEulerXv,
            "pec" => Self::Pec,
            "epec" => Self::Epec,
            "verlet-euler" => Self::VerletEuler { every: euler_every },
            "rk2-midpoint" => Self::Rk2Midpoint,
            "rk2-heun" => Self::Rk2Heun,
            "rk4" => Self::Rk4,
            "euler" => Self::Euler,
            _ => {
                return Err(Error::UnknownName {
                    what: "integrator".into(),
                    given: name.to_string(),
                    valid: INTEGRATOR_NAMES.join(", ").into(),
                });
            }
        })
    }

    /// The integrator of the parameters `integrator` (default `kdk`) and `euler_every` (N_s of
    /// `verlet-euler`, default [`DEFAULT_EULER_EVERY`]): `euler_every` with another integrator
    /// is an error naming both, since it would not act.
    pub fn by_names(name: Option<&str>, euler_every: Option<usize>) -> Result<Self> {
        let name = name.unwrap_or("kdk");
        let i = Self::from_name(name, euler_every.unwrap_or(DEFAULT_EULER_EVERY))?;
        if euler_every.is_some() && !matches!(i, Self::VerletEuler { .. }) {
            return Err(Error::Incompatible(
                crate::error::field("euler_every")
                    + " does not apply with "
                    + crate::error::field("integrator")
                    + format!(" {name} (N_s is the Euler period of verlet-euler)"),
            ));
        }
        Ok(i)
    }

    /// Every integrator (N_s = `euler_every` for `verlet-euler`).
    pub fn all(euler_every: usize) -> Vec<Self> {
        INTEGRATOR_NAMES
            .iter()
            .map(|n| Self::from_name(n, euler_every.max(1)).expect("a listed name"))
            .collect()
    }

    /// The CLI name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Kdk => "kdk",
            Self::Dkd => "dkd",
            Self::VerletLagged => "verlet-lagged",
            Self::SymplecticEulerVx => "symplectic-euler-vx",
            Self::SymplecticEulerXv => "symplectic-euler-xv",
            Self::Pec => "pec",
            Self::Epec => "epec",
            Self::VerletEuler { .. } => "verlet-euler",
            Self::Rk2Midpoint => "rk2-midpoint",
            Self::Rk2Heun => "rk2-heun",
            Self::Rk4 => "rk4",
            Self::Euler => "euler",
        }
    }

    /// Steps after which the update repeats (N_s for `verlet-euler`, else 1): the amplification
    /// of one cycle is the product of its steps' matrices.
    pub fn cycle(self) -> usize {
        match self {
            Self::VerletEuler { every } => every,
            _ => 1,
        }
    }

    /// Which of (x, v, q) the scheme carries from one step to the next besides the state itself
    /// (`pec`: the rates of the last evaluation, of all three; `verlet-euler`: vⁿ⁻¹ and qⁿ⁻¹).
    /// The amplification matrix acts on the state extended by these.
    pub fn memory(self) -> [bool; 3] {
        match self {
            Self::Pec => [true, true, true],
            Self::VerletEuler { .. } => [false, true, true],
            _ => [false, false, false],
        }
    }

    /// The largest ωΔt for which the scheme is stable on the undamped oscillator x'' = −ω²x
    /// (eigenvalues ±iω on the imaginary axis), from its stability polynomial; `None` where no
    /// Δt > 0 is stable (weakly unstable schemes) or where the limit has no closed form here
    /// (`pec`, `verlet-euler`: found numerically). For `kdk` this is \[B00\] eq 120 with ξ = 0.
    pub fn imaginary_axis_limit(self) -> Option<f64> {
        match self {
            Self::Kdk
            | Self::Dkd
            | Self::VerletLagged
            | Self::SymplecticEulerVx
            | Self::SymplecticEulerXv => Some(2.0),
            Self::Rk4 => Some(2.0 * std::f64::consts::SQRT_2),
            Self::Pec
            | Self::Epec
            | Self::VerletEuler { .. }
            | Self::Rk2Midpoint
            | Self::Rk2Heun
            | Self::Euler => None,
        }
    }

    /// Order of accuracy of the scheme (global error O(Δt^p)) on a smooth solution.
    pub fn order(self) -> u32 {
        match self {
            Self::Kdk | Self::Dkd | Self::Pec | Self::Epec => 2,
            Self::Rk2Midpoint | Self::Rk2Heun => 2,
            Self::VerletLagged | Self::VerletEuler { .. } => 1,
            Self::SymplecticEulerVx | Self::SymplecticEulerXv | Self::Euler => 1,
            Self::Rk4 => 4,
        }
    }
}

impl std::fmt::Display for Integrator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::VerletEuler { every } => write!(f, "verlet-euler (N_s = {every})"),
            _ => f.write_str(self.name()),
        }
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

/// Three state-shaped buffers (x, v, q parts).
#[derive(Clone, Debug, Default)]
pub struct Triple<T> {
    /// Position part.
    pub x: Vec<T>,
    /// Velocity part.
    pub v: Vec<T>,
    /// Auxiliary part.
    pub q: Vec<T>,
}

impl<T: Copy + Default> Triple<T> {
    fn shape(&mut self, nx: usize, nv: usize, nq: usize) {
        self.x.resize(nx, T::default());
        self.v.resize(nv, T::default());
        self.q.resize(nq, T::default());
    }
}

/// The per-run state of an integrator: its work arrays (allocated at the first step, reused
/// after, so a time loop does not allocate), what it carries between steps (module docs,
/// [`Integrator::memory`]) and the step count (the `verlet-euler` cycle).
#[derive(Clone, Debug)]
pub struct Stepper<T> {
    /// The scheme.
    pub integrator: Integrator,
    /// What the scheme carries between steps: `pec` the rates (ẋ, v̇, q̇) of the last
    /// evaluation; `verlet-euler` (unused, vⁿ⁻¹, qⁿ⁻¹).
    pub memory: Triple<T>,
    /// Whether `memory` holds values (false before the first step).
    pub memory_valid: bool,
    /// Steps taken.
    pub steps: usize,
    kdk: Scratch<T>,
    start: Triple<T>,
    stage: Triple<T>,
    rate: Triple<T>,
    sum: Triple<T>,
}

impl<T: Copy + Default> Stepper<T> {
    /// A stepper with nothing allocated yet.
    pub fn new(integrator: Integrator) -> Self {
        Self {
            integrator,
            memory: Triple::default(),
            memory_valid: false,
            steps: 0,
            kdk: Scratch::default(),
            start: Triple::default(),
            stage: Triple::default(),
            rate: Triple::default(),
            sum: Triple::default(),
        }
    }
}

/// y ← y + c·k, elementwise.
fn axpy<T: Copy + Add<Output = T> + Mul<f64, Output = T>>(y: &mut [T], k: &[T], c: f64) {
    for (yi, &ki) in y.iter_mut().zip(k) {
        *yi = *yi + ki * c;
    }
}

/// out ← y + c·k, elementwise.
fn set_axpy<T: Copy + Add<Output = T> + Mul<f64, Output = T>>(
    out: &mut [T],
    y: &[T],
    k: &[T],
    c: f64,
) {
    for ((oi, &yi), &ki) in out.iter_mut().zip(y).zip(k) {
        *oi = yi + ki * c;
    }
}

impl<T> Stepper<T>
where
    T: Copy + Default + PartialEq + Add<Output = T> + Mul<f64, Output = T>,
{
    /// Rate evaluations (`rates`, `accel` or `qrate` calls on the whole system) per step, after
    /// the first step; `kdk` does 2 when the acceleration does not depend on the velocity.
    pub fn evaluations_per_step(&self, accel_depends_on_velocity: bool) -> usize {
        match self.integrator {
            Integrator::Kdk => 2 + accel_depends_on_velocity as usize,
            Integrator::Dkd => 3,
            Integrator::VerletLagged | Integrator::Pec | Integrator::Euler => 1,
            Integrator::VerletEuler { .. } => 1,
            Integrator::SymplecticEulerVx | Integrator::SymplecticEulerXv => 2,
            Integrator::Epec | Integrator::Rk2Midpoint | Integrator::Rk2Heun => 2,
            Integrator::Rk4 => 4,
        }
    }

    /// F at the stage state into `rate`: (v, a, r).
    fn eval_stage<D: SecondOrderSystem<T>>(&mut self, sys: &D) {
        let (s, k) = (&self.stage, &mut self.rate);
        k.x.copy_from_slice(&s.v);
        sys.rates(&s.x, &s.v, &s.q, &mut k.v, &mut k.q);
    }

    /// F at (x, v, q) into `rate`.
    fn eval_at<D: SecondOrderSystem<T>>(&mut self, sys: &D, x: &[T], v: &[T], q: &[T]) {
        let k = &mut self.rate;
        k.x.copy_from_slice(v);
        sys.rates(x, v, q, &mut k.v, &mut k.q);
    }

    /// stage ← start + c·rate.
    fn stage_from_start(&mut self, c: f64) {
        set_axpy(&mut self.stage.x, &self.start.x, &self.rate.x, c);
        set_axpy(&mut self.stage.v, &self.start.v, &self.rate.v, c);
        set_axpy(&mut self.stage.q, &self.start.q, &self.rate.q, c);
    }

    /// One step of size `dt`, in place (module docs for the update of each scheme).
    pub fn step<D: SecondOrderSystem<T>>(
        &mut self,
        sys: &D,
        x: &mut [T],
        v: &mut [T],
        q: &mut [T],
        dt: f64,
    ) {
        let (nx, nv, nq) = (x.len(), v.len(), q.len());
        for t in [
            &mut self.start,
            &mut self.stage,
            &mut self.rate,
            &mut self.sum,
        ] {
            t.shape(nx, nv, nq);
        }
        let [mx, mv, mq] = self.integrator.memory();
        self.memory.shape(
            if mx { nx } else { 0 },
            if mv { nv } else { 0 },
            if mq { nq } else { 0 },
        );
        match self.integrator {
            Integrator::Kdk => kdk_step(sys, x, v, q, dt, &mut self.kdk),
            Integrator::Dkd => {
                let r = &mut self.rate.q;
                sys.qrate(x, v, q, r);
                axpy(x, v, 0.5 * dt);
                axpy(q, r, 0.5 * dt);
                let a = &mut self.rate.v;
                sys.accel(x, v, q, a);
                axpy(v, a, dt);
                sys.qrate(x, v, q, r);
                axpy(x, v, 0.5 * dt);
                axpy(q, r, 0.5 * dt);
            }
            Integrator::VerletLagged => {
                let (a, r) = (&mut self.rate.v, &mut self.rate.q);
                sys.rates(x, v, q, a, r);
                axpy(v, a, dt);
                axpy(x, v, dt);
                axpy(q, r, dt);
            }
            Integrator::SymplecticEulerVx => {
                let (a, r) = (&mut self.rate.v, &mut self.rate.q);
                sys.accel(x, v, q, a);
                axpy(v, a, dt);
                sys.qrate(x, v, q, r);
                axpy(x, v, dt);
                axpy(q, r, dt);
            }
            Integrator::SymplecticEulerXv => {
                let (a, r) = (&mut self.rate.v, &mut self.rate.q);
                sys.qrate(x, v, q, r);
                axpy(x, v, dt);
                axpy(q, r, dt);
                sys.accel(x, v, q, a);
                axpy(v, a, dt);
            }
            Integrator::Pec => {
                if !self.memory_valid {
                    self.eval_at(sys, x, v, q);
                    self.memory.x.copy_from_slice(&self.rate.x);
                    self.memory.v.copy_from_slice(&self.rate.v);
                    self.memory.q.copy_from_slice(&self.rate.q);
                }
                set_axpy(&mut self.stage.x, x, &self.memory.x, 0.5 * dt);
                set_axpy(&mut self.stage.v, v, &self.memory.v, 0.5 * dt);
                set_axpy(&mut self.stage.q, q, &self.memory.q, 0.5 * dt);
                self.eval_stage(sys);
                self.memory.x.copy_from_slice(&self.rate.x);
                self.memory.v.copy_from_slice(&self.rate.v);
                self.memory.q.copy_from_slice(&self.rate.q);
                axpy(x, &self.rate.x, dt);
                axpy(v, &self.rate.v, dt);
                axpy(q, &self.rate.q, dt);
            }
            Integrator::Epec | Integrator::Rk2Midpoint => {
                self.start.x.copy_from_slice(x);
                self.start.v.copy_from_slice(v);
                self.start.q.copy_from_slice(q);
                self.eval_at(sys, x, v, q);
                self.stage_from_start(0.5 * dt);
                self.eval_stage(sys);
                axpy(x, &self.rate.x, dt);
                axpy(v, &self.rate.v, dt);
                axpy(q, &self.rate.q, dt);
            }
            Integrator::Rk2Heun => {
                self.start.x.copy_from_slice(x);
                self.start.v.copy_from_slice(v);
                self.start.q.copy_from_slice(q);
                self.eval_at(sys, x, v, q);
                self.stage_from_start(dt);
                axpy(x, &self.rate.x, 0.5 * dt);
                axpy(v, &self.rate.v, 0.5 * dt);
                axpy(q, &self.rate.q, 0.5 * dt);
                self.eval_stage(sys);
                axpy(x, &self.rate.x, 0.5 * dt);
                axpy(v, &self.rate.v, 0.5 * dt);
                axpy(q, &self.rate.q, 0.5 * dt);
            }
            Integrator::Rk4 => {
                self.start.x.copy_from_slice(x);
                self.start.v.copy_from_slice(v);
                self.start.q.copy_from_slice(q);
                // k1; the increments are added to the state as each stage is known
                self.eval_at(sys, x, v, q);
                for (c_stage, c_sum) in [(0.5, 1.0 / 6.0), (0.5, 1.0 / 3.0), (1.0, 1.0 / 3.0)] {
                    axpy(x, &self.rate.x, c_sum * dt);
                    axpy(v, &self.rate.v, c_sum * dt);
                    axpy(q, &self.rate.q, c_sum * dt);
                    self.stage_from_start(c_stage * dt);
                    self.eval_stage(sys);
                }
                axpy(x, &self.rate.x, dt / 6.0);
                axpy(v, &self.rate.v, dt / 6.0);
                axpy(q, &self.rate.q, dt / 6.0);
            }
            Integrator::Euler => {
                let (a, r) = (&mut self.rate.v, &mut self.rate.q);
                sys.rates(x, v, q, a, r);
                axpy(x, v, dt);
                axpy(v, a, dt);
                axpy(q, r, dt);
            }
            Integrator::VerletEuler { every } => {
                if !self.memory_valid {
                    // DualSPHysics starts with (v, q)ⁿ⁻¹ = (v, q)⁰
                    self.memory.v.copy_from_slice(v);
                    self.memory.q.copy_from_slice(q);
                }
                let (a, r) = (&mut self.sum.v, &mut self.sum.q);
                sys.rates(x, v, q, a, r);
                // xⁿ⁺¹ = xⁿ + Δt vⁿ + Δt²/2 aⁿ
                axpy(x, v, dt);
                axpy(x, a, 0.5 * dt * dt);
                let euler = (self.steps + 1).is_multiple_of(every);
                // (v, q)ⁿ⁺¹ from (v, q)ⁿ (Euler) or (v, q)ⁿ⁻¹ (Verlet); memory ← (v, q)ⁿ
                for (cur, old, rate) in [
                    (&mut *v, &mut self.memory.v, &*a),
                    (&mut *q, &mut self.memory.q, &*r),
                ] {
                    for ((ci, oi), &ri) in cur.iter_mut().zip(old.iter_mut()).zip(rate) {
                        let now = *ci;
                        *ci = if euler {
                            now + ri * dt
                        } else {
                            *oi + ri * (2.0 * dt)
                        };
                        *oi = now;
                    }
                }
            }
        }
        self.memory_valid = true;
        self.steps += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_bad_input_is_refused() {
        for n in INTEGRATOR_NAMES {
            assert_eq!(Integrator::from_name(n, 40).unwrap().name(), n);
        }
        let e = Integrator::from_name("nosuch", 40).unwrap_err().to_string();
        assert!(e.contains("integrator") && e.contains("rk4"), "{e}");
        let e = Integrator::from_name("verlet-euler", 0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("euler_every"), "{e}");
    }
}
