//! Fully discrete analysis: the leapfrog step of [`crate::integrator::kdk_step`] applied to
//! one Fourier mode of the linearised system gives the amplification matrix G(κ, Δt);
//! its spectral radius decides time-step stability. The critical-Δt search is one generic code
//! path ([`Modes`]) for the 1D chain (modes κΔx) and the D-dimensional lattice (wave vectors k).

use super::classify::GROWTH_TOL;
use super::linearise::eigen;
use crate::error::Result;
use crate::integrator::{Integrator, SecondOrderSystem, Stepper};
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::cell::Cell;

/// |λ| above 1 + this is amplification. Not smaller: a double eigenvalue with a Jordan block
/// (ω = 0 zero-energy modes, λ = 1; the leapfrog limit, λ = −1) is computed only to
/// O(√ε ‖G‖) ≈ 1e-8, so a tighter tolerance would report rounding as amplification.
pub const AMPLIFICATION_TOL: f64 = 1e-7;

/// The linear system of one Fourier mode: J split into position, velocity and auxiliary rows.
pub struct ModeSystem {
    j: DMatrix<Complex64>,
    ix: Vec<usize>,
    iv: Vec<usize>,
    iq: Vec<usize>,
}

impl ModeSystem {
    /// A mode system from J and the indices of positions, velocities and auxiliary states.
    pub fn new(j: DMatrix<Complex64>, ix: Vec<usize>, iv: Vec<usize>, iq: Vec<usize>) -> Self {
        Self { j, ix, iv, iq }
    }

    fn row(&self, a: usize, x: &[Complex64], v: &[Complex64], q: &[Complex64]) -> Complex64 {
        let mut s = Complex64::new(0.0, 0.0);
        for (k, &b) in self.ix.iter().enumerate() {
            s += self.j[(a, b)] * x[k];
        }
        for (k, &b) in self.iv.iter().enumerate() {
            s += self.j[(a, b)] * v[k];
        }
        for (k, &b) in self.iq.iter().enumerate() {
            s += self.j[(a, b)] * q[k];
        }
        s
    }

    /// Amplification matrix of one leapfrog (`kdk`) step of size `dt` (same units as J⁻¹).
    pub fn amplification(&self, dt: f64) -> DMatrix<Complex64> {
        self.amplification_with(Integrator::Kdk, dt)
    }

    /// Amplification matrix of one cycle ([`Integrator::cycle`] steps, 1 for all schemes but
    /// `verlet-euler`) of `integ` with step `dt`, acting on the mode's state followed by what the
    /// scheme carries between steps ([`Integrator::memory`]: x, v, q parts in that order, each
    /// in the order of the state's indices). Its spectral radius to the power 1/cycle is the
    /// growth per step.
    pub fn amplification_with(&self, integ: Integrator, dt: f64) -> DMatrix<Complex64> {
        self.steps_matrix(integ, dt, 0, integ.cycle())
    }

    /// The growth per step of `integ` at `dt`: the spectral radius of one cycle's amplification
    /// to the power 1/cycle. For `verlet-euler` the cycle is E·V^(N_s−1) (N_s − 1 Verlet steps V,
    /// then the Euler step E): the power is taken by repeated squaring with the scale kept apart
    /// as a logarithm, so that a cycle whose entries would overflow (growth per step 2 over 1000
    /// steps) or whose eigenvalues span hundreds of decades still gives a finite answer.
    pub fn growth_per_step(&self, integ: Integrator, dt: f64) -> Result<f64> {
        let n = integ.cycle();
        if n == 1 {
            let ev = eigen(self.steps_matrix(integ, dt, 0, 1))?;
            return Ok(ev.iter().map(|l| l.norm()).fold(0.0, f64::max));
        }
        // (matrix, ln of its scale): the product is m·e^{ln_s}
        let normalise = |m: DMatrix<Complex64>, ln_s: f64| -> (DMatrix<Complex64>, f64) {
            let top = m.iter().map(|z| z.norm()).fold(0.0, f64::max);
            if top > 0.0 && top.is_finite() {
                (m.map(|z| z / top), ln_s + top.ln())
            } else {
                (m, ln_s)
            }
        };
        let verlet = self.steps_matrix(integ, dt, 0, 1);
        let euler = self.steps_matrix(integ, dt, n - 1, 1);
        let dim = verlet.nrows();
        let (mut acc, mut acc_ln) = (DMatrix::<Complex64>::identity(dim, dim), 0.0);
        let (mut base, mut base_ln) = normalise(verlet, 0.0);
        let mut e = n - 1;
        while e > 0 {
            if e & 1 == 1 {
                (acc, acc_ln) = normalise(&acc * &base, acc_ln + base_ln);
            }
            e >>= 1;
            if e > 0 {
                (base, base_ln) = normalise(&base * &base, 2.0 * base_ln);
            }
        }
        let (cyc, ln_s) = normalise(&euler * &acc, acc_ln);
        let rho = eigen(cyc)?.iter().map(|l| l.norm()).fold(0.0, f64::max);
        Ok(if rho > 0.0 {
            ((ln_s + rho.ln()) / n as f64).exp()
        } else {
            0.0
        })
    }

    /// Amplification matrix of `count` steps of `integ` starting at step `first` of its cycle
    /// (memory as in [`ModeSystem::amplification_with`]).
    fn steps_matrix(
        &self,
        integ: Integrator,
        dt: f64,
        first: usize,
        count: usize,
    ) -> DMatrix<Complex64> {
        let n = self.j.nrows();
        let parts = [&self.ix, &self.iv, &self.iq];
        let mem = integ.memory();
        let mem_len: Vec<usize> = (0..3)
            .map(|p| if mem[p] { parts[p].len() } else { 0 })
            .collect();
        let total = n + mem_len.iter().sum::<usize>();
        let mut g = DMatrix::<Complex64>::zeros(total, total);
        let one = Complex64::new(1.0, 0.0);
        let zero = Complex64::new(0.0, 0.0);
        let mut st = Stepper::new(integ);
        for col in 0..total {
            // the unit vector of column `col`: a state dof (its index in J) or a memory entry
            let mut z: Vec<Vec<Complex64>> = parts
                .iter()
                .map(|idx| {
                    idx.iter()
                        .map(|&k| if k == col { one } else { zero })
                        .collect()
                })
                .collect();
            st.memory.x = vec![zero; mem_len[0]];
            st.memory.v = vec![zero; mem_len[1]];
            st.memory.q = vec![zero; mem_len[2]];
            if col >= n {
                let mut k = col - n;
                for m in [&mut st.memory.x, &mut st.memory.v, &mut st.memory.q] {
                    if k < m.len() {
                        m[k] = one;
                        break;
                    }
                    k -= m.len();
                }
            }
            st.memory_valid = true;
            st.steps = first;
            let [x, v, q] = &mut z[..] else {
                unreachable!()
            };
            for _ in 0..count {
                st.step(self, x, v, q, dt);
            }
            for (idx, vals) in parts.iter().zip(&z) {
                for (k, &b) in idx.iter().enumerate() {
                    g[(b, col)] = vals[k];
                }
            }
            let mem_vals = st.memory.x.iter().chain(&st.memory.v).chain(&st.memory.q);
            for (row, &val) in (n..total).zip(mem_vals) {
                g[(row, col)] = val;
            }
        }
        g
    }
}

impl SecondOrderSystem<Complex64> for ModeSystem {
    fn accel(&self, x: &[Complex64], v: &[Complex64], q: &[Complex64], a: &mut [Complex64]) {
        for (k, &b) in self.iv.iter().enumerate() {
            a[k] = self.row(b, x, v, q);
        }
    }
    fn qrate(&self, x: &[Complex64], v: &[Complex64], q: &[Complex64], r: &mut [Complex64]) {
        for (k, &b) in self.iq.iter().enumerate() {
            r[k] = self.row(b, x, v, q);
        }
    }
}

/// What the fully discrete analysis needs of a linearisation whose modes are indexed by `K`:
/// κΔx for the 1D chain ([`super::linearise::Linearisation`]), the wave vector for
/// [`super::linearise::Bloch`].
pub trait Modes {
    /// Mode index.
    type K: Copy;
    /// Whether velocities enter the accelerations (artificial viscosity).
    fn is_dissipative(&self) -> bool;
    /// Largest Re ω²Δx²/c² of the mechanical branches at k.
    fn omega2_top(&self, k: Self::K) -> f64;
    /// Amplification matrix of one cycle of `integ` at k ([`ModeSystem::amplification_with`]);
    /// `dt` in Δx/c.
    fn amplification_with(&self, k: Self::K, dt: f64, integ: Integrator) -> DMatrix<Complex64>;
    /// Growth per step of `integ` at k ([`ModeSystem::growth_per_step`]); `dt` in Δx/c.
    fn growth_per_step(&self, k: Self::K, dt: f64, integ: Integrator) -> Result<f64>;
    /// Amplification matrix G(k, Δt) of one leapfrog step; `dt` in Δx/c.
    fn amplification(&self, k: Self::K, dt: f64) -> DMatrix<Complex64> {
        self.amplification_with(k, dt, Integrator::Kdk)
    }
    /// Eigenvalues s of the semi-discrete J(k), in c/Δx.
    fn eigenvalues(&self, k: Self::K) -> Result<Vec<Complex64>>;
}

/// Amplification matrix G(k, Δt) of one leapfrog step; `dt` in Δx/c.
pub fn amplification_matrix<L: Modes>(lin: &L, k: L::K, dt: f64) -> DMatrix<Complex64> {
    lin.amplification(k, dt)
}

/// Spectral radius of G(k, Δt).
pub fn spectral_radius<L: Modes>(lin: &L, k: L::K, dt: f64) -> Result<f64> {
    let ev = eigen(lin.amplification(k, dt))?;
    Ok(ev.iter().map(|l| l.norm()).fold(0.0, f64::max))
}

/// Spectral radius of G(k, Δt) at every mode of `ks`.
pub fn spectral_radii<L: Modes>(lin: &L, ks: &[L::K], dt: f64) -> Result<Vec<f64>> {
    ks.iter().map(|&k| spectral_radius(lin, k, dt)).collect()
}

/// The leapfrog limit 2/ω_max (\[B00\] eq 120 with ξ = 0) for the largest ω² (normalised);
/// infinite when ω_max = 0.
pub fn leapfrog_limit(omega2_max: f64) -> f64 {
    let wmax = omega2_max.sqrt();
    if wmax > 0.0 {
        2.0 / wmax
    } else {
        f64::INFINITY
    }
}

/// Critical time step (Δx/c) over the modes `ks`. Non-dissipative systems: the leapfrog limit
/// 2/ω_max ([`leapfrog_limit`]; tests check it against the amplification matrices). Dissipative
/// systems: the largest Δt with max_k |λ| ≤ 1 + tol, by bisection.
pub fn critical_dt<L: Modes>(lin: &L, ks: &[L::K]) -> Result<f64> {
    let w2 = if lin.is_dissipative() {
        0.0
    } else {
        ks.iter().map(|&k| lin.omega2_top(k)).fold(0.0, f64::max)
    };
    critical_dt_given(lin, ks, w2)
}

/// [`critical_dt`] when the largest ω² over `ks` is already known (`omega2_max`, unused for
/// dissipative systems).
pub fn critical_dt_given<L: Modes>(lin: &L, ks: &[L::K], omega2_max: f64) -> Result<f64> {
    if lin.is_dissipative() {
        critical_dt_bisection(lin, ks)
    } else {
        Ok(leapfrog_limit(omega2_max))
    }
}

/// Critical time step by bisection on the spectral radius of the amplification matrices: Δt is
/// stable when |λ| ≤ 1 + [`AMPLIFICATION_TOL`] at every mode of `ks`.
pub fn critical_dt_bisection<L: Modes>(lin: &L, ks: &[L::K]) -> Result<f64> {
    let stable = |dt: f64| -> Result<bool> {
        for &k in ks {
            if spectral_radius(lin, k, dt)? > 1.0 + AMPLIFICATION_TOL {
                return Ok(false);
            }
        }
        Ok(true)
    };
    largest_stable(0.0, 1.0, stable)
}

/// The largest Δt with `stable(Δt)`, given that `lo` is stable (or 0): doubling from `hi` until
/// unstable (∞ past 1e6), then bisection to a relative gap of 1e-12 (at most 60 halvings).
fn largest_stable(mut lo: f64, mut hi: f64, stable: impl Fn(f64) -> Result<bool>) -> Result<f64> {
    while stable(hi)? {
        lo = hi;
        hi *= 2.0;
        if hi > 1e6 {
            return Ok(f64::INFINITY);
        }
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if stable(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-12 * hi {
            break;
        }
    }
    Ok(lo)
}

/// Growth per step of `integ` at k: the spectral radius of one cycle's amplification matrix to
/// the power 1/cycle; `dt` in Δx/c.
pub fn spectral_radius_with<L: Modes>(lin: &L, k: L::K, dt: f64, integ: Integrator) -> Result<f64> {
    crate::progress::interrupted()?;
    lin.growth_per_step(k, dt, integ)
}

/// The largest growth per step of `integ` over `ks` at `dt` (Δx/c), and where.
pub fn max_spectral_radius_with<L: Modes>(
    lin: &L,
    ks: &[L::K],
    dt: f64,
    integ: Integrator,
) -> Result<Option<(f64, L::K)>> {
    let mut best: Option<(f64, L::K)> = None;
    for &k in ks {
        let r = spectral_radius_with(lin, k, dt, integ)?;
        if best.is_none_or(|b| r > b.0) {
            best = Some((r, k));
        }
    }
    Ok(best)
}

/// What an integrator does to the modes of a linearisation (units Δx/c, c/Δx).
#[derive(Clone, Copy, Debug)]
pub struct StepStability {
    /// The scheme.
    pub integrator: Integrator,
    /// Largest |s| over the eigenvalues that do not grow in the semi-discrete system (ω_max for
    /// a non-dissipative one; with viscosity |s|² = ω² + decay²), c/Δx.
    pub s_max: f64,
    /// Largest oscillation frequency |Im s| over the same eigenvalues, c/Δx.
    pub omega_max: f64,
    /// Largest decay rate −Re s over the same eigenvalues (0 without dissipation), c/Δx.
    pub decay_rate_max: f64,
    /// Largest growth rate of the semi-discrete system, max Re s over every mode (0 if none
    /// exceeds [`GROWTH_TOL`]), c/Δx: the physical (spatial) growth, present at every Δt.
    pub growth_rate: f64,
    /// The largest Δt at which the scheme adds no growth to any mode beyond the semi-discrete
    /// one: growth per step ≤ e^{γ(k)(1 + [`GROWTH_REL_TOL`])Δt}(1 + [`AMPLIFICATION_TOL`]) at
    /// every mode k, γ(k) = max(0, max Re s(k)) (for a system that does not grow, |λ| ≤ 1 + tol), by bisection;
    /// `None` when the scheme adds growth already at s_max Δt = [`WEAK_PROBE`] (a weak
    /// instability, below every Δt), ∞ when no Δt up to 1e6 adds growth.
    pub critical_dt: Option<f64>,
    /// The closed form [`Integrator::imaginary_axis_limit`]/ω_max, for non-dissipative systems
    /// and schemes that are not weakly unstable.
    pub closed_form_dt: Option<f64>,
    /// Whether the scheme amplifies a non-growing mode at every Δt (the weak instability).
    pub weak: bool,
}

/// Relative excess of a growing mode's discrete growth rate over its semi-discrete one that
/// still counts as no added growth: the scheme's truncation error (a second-order scheme's
/// rate is off by O((sΔt)²), with viscosity the damped branch's sΔt included) is accuracy, not
/// instability. 1%: a time-step instability adds growth at a rate of order 1/Δt, far beyond.
pub const GROWTH_REL_TOL: f64 = 0.01;

/// ω_max Δt at which a weak instability is looked for: there |λ| − 1 is ≈ y²/2 for `euler`
/// and the lagged velocity, y⁴/8 = 1.25e-5 for RK2 — far above [`AMPLIFICATION_TOL`].
pub const WEAK_PROBE: f64 = 0.1;

/// The semi-discrete spectrum of `ks` as the time-step analysis needs it: every mode with its
/// growth rate γ(k) = max Re s, or 0 when that is ≤ [`GROWTH_TOL`] (a mode that does not
/// grow), and over the eigenvalues with Re s ≤ [`GROWTH_TOL`] at every mode (the oscillating
/// branches of a mode whose other branch grows included): the largest |s|, |Im s| and −Re s.
struct Spectrum<K> {
    modes: Vec<(K, f64)>,
    s_max: f64,
    omega_max: f64,
    decay_max: f64,
}

fn spectrum<L: Modes>(lin: &L, ks: &[L::K]) -> Result<Spectrum<L::K>> {
    let mut out = Spectrum {
        modes: Vec::with_capacity(ks.len()),
        s_max: 0.0,
        omega_max: 0.0,
        decay_max: 0.0,
    };
    for &k in ks {
        let ev = lin.eigenvalues(k)?;
        let top = ev.iter().map(|s| s.re).fold(f64::NEG_INFINITY, f64::max);
        out.modes
            .push((k, if top > GROWTH_TOL { top } else { 0.0 }));
        for s in ev.iter().filter(|s| s.re <= GROWTH_TOL) {
            out.s_max = out.s_max.max(s.norm());
            out.omega_max = out.omega_max.max(s.im.abs());
            out.decay_max = out.decay_max.max(-s.re);
        }
    }
    Ok(out)
}

/// ln(growth per step) of `integ` at k beyond the semi-discrete growth γ Δt with its
/// [`GROWTH_REL_TOL`] (≤ 0: the scheme adds no growth).
fn added_log_growth<L: Modes>(
    lin: &L,
    k: L::K,
    gamma: f64,
    dt: f64,
    integ: Integrator,
) -> Result<f64> {
    Ok(spectral_radius_with(lin, k, dt, integ)?.ln() - gamma * (1.0 + GROWTH_REL_TOL) * dt)
}

/// Whether `integ` at `dt` adds no growth beyond the semi-discrete one at any mode (to `tol`
/// per step). The mode in `last_failed` (the one that failed the previous call of a search,
/// usually the one that limits the step) is tried first and the index of a failing mode is
/// stored there: a failing Δt of a bisection then costs one mode, not the modes before it in
/// the grid. The answer does not depend on the order.
fn adds_no_growth<L: Modes>(
    lin: &L,
    modes: &[(L::K, f64)],
    dt: f64,
    integ: Integrator,
    tol: f64,
    last_failed: &Cell<usize>,
) -> Result<bool> {
    let first = last_failed.get().min(modes.len().saturating_sub(1));
    let order = std::iter::once(first).chain((0..modes.len()).filter(|&i| i != first));
    for i in order.take(modes.len()) {
        let (k, g) = modes[i];
        let r = spectral_radius_with(lin, k, dt, integ)?;
        // the same test as |λ| ≤ 1 + tol for a mode that does not grow (γ = 0), bit for bit
        let ok = if g == 0.0 {
            r <= 1.0 + tol
        } else {
            r <= (g * (1.0 + GROWTH_REL_TOL) * dt).exp() * (1.0 + tol)
        };
        if !ok {
            last_failed.set(i);
            return Ok(false);
        }
    }
    Ok(true)
}

/// The time-step stability of `integ` over the modes of `ks` ([`StepStability`]): the largest
/// Δt at which the scheme adds no growth beyond the semi-discrete system's, whether or not
/// that system grows.
pub fn step_stability<L: Modes>(lin: &L, ks: &[L::K], integ: Integrator) -> Result<StepStability> {
    step_stability_to(lin, ks, integ, AMPLIFICATION_TOL)
}

/// [`step_stability`] with `tol` per step in place of [`AMPLIFICATION_TOL`]: growth per step
/// ≤ e^{γ(k)(1 + [`GROWTH_REL_TOL`])Δt}(1 + tol). A coarser `tol` is the limit a measurement
/// that resolves `tol` per step sees (a time-domain run of a few thousand steps: its
/// [`crate::studies::stable_dt`] check); it differs from the strict limit where the added growth
/// rises slowly beyond it.
pub fn step_stability_to<L: Modes>(
    lin: &L,
    ks: &[L::K],
    integ: Integrator,
    tol: f64,
) -> Result<StepStability> {
    let sp = spectrum(lin, ks)?;
    let growth_rate = sp.modes.iter().map(|m| m.1).fold(0.0, f64::max);
    let closed_form_dt = if lin.is_dissipative() || sp.omega_max == 0.0 {
        None
    } else {
        integ.imaginary_axis_limit().map(|y| y / sp.omega_max)
    };
    let result = |critical_dt: Option<f64>| StepStability {
        integrator: integ,
        s_max: sp.s_max,
        omega_max: sp.omega_max,
        decay_rate_max: sp.decay_max,
        growth_rate,
        critical_dt,
        closed_form_dt,
        weak: false,
    };
    if sp.s_max == 0.0 {
        return Ok(result(Some(f64::INFINITY)));
    }
    let last_failed = Cell::new(sp.modes.len().saturating_sub(1));
    let stable = |dt: f64| adds_no_growth(lin, &sp.modes, dt, integ, tol, &last_failed);
    let lo = WEAK_PROBE / sp.s_max;
    if !stable(lo)? {
        return Ok(StepStability {
            weak: true,
            closed_form_dt: None,
            ..result(None)
        });
    }
    Ok(result(Some(largest_stable(lo, 2.0 * lo, stable)?)))
}

/// Growth that `integ` at step `dt` (Δx/c) adds beyond the semi-discrete system: the largest
/// (ln(growth per step) − γ(k)(1 + [`GROWTH_REL_TOL`])Δt)/Δt over the modes, in c/Δx (0 if no mode gains more than
/// [`AMPLIFICATION_TOL`] per step; for a system that does not grow, the spurious growth
/// ln|λ|/Δt), and the mode where it is largest.
pub fn spurious_growth_rate<L: Modes>(
    lin: &L,
    ks: &[L::K],
    integ: Integrator,
    dt: f64,
) -> Result<(f64, Option<L::K>)> {
    let sp = spectrum(lin, ks)?;
    let mut best: Option<(f64, L::K)> = None;
    for &(k, g) in &sp.modes {
        let a = added_log_growth(lin, k, g, dt, integ)?;
        if best.is_none_or(|b| a > b.0) {
            best = Some((a, k));
        }
    }
    Ok(match best {
        Some((a, k)) if a > AMPLIFICATION_TOL.ln_1p() => (a / dt, Some(k)),
        b => (0.0, b.map(|b| b.1)),
    })
}
