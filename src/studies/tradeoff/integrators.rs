//! The integrator as a dimension of the trade-off study (1D): for every form × kernel × h/Δx of
//! the grid and every integrator asked for, what advancing the wave costs per unit simulated
//! time and what it does to a resolved wave per wavelength travelled.
//!
//! | column | how it is obtained |
//! |---|---|
//! | `critical_dt` | [`IntegratorReport::of`] at σ̄ = 0 (the `timestep` code path: [`crate::vonneumann::amplification::step_stability`] on the amplification matrices of the scheme), Δx/c; null for a weakly unstable scheme |
//! | `weak_growth_rate` | weakly unstable schemes: their spurious growth per unit time at Δt = 1/ω_max, c/Δx (the `spurious_growth_rate` of `timestep`) |
//! | `dt_used` | `safety` × `critical_dt`; weakly unstable schemes: the largest Δt for which no mode of the κ grid grows by more than [`WEAK_TOL`] while a wave travels one wavelength at 10 points per wavelength ([`T_REF`] = 10 Δx/c), by bisection on the raw spectral radius of the scheme |
//! | `evaluations_per_step` | [`Stepper::evaluations_per_step`]: the scheme's nominal count (one `rates` call = one evaluation; `kdk` 2 without artificial viscosity, whose acceleration does not depend on v, 3 with it) |
//! | `rate_calls_per_step` | `accel` + `qrate` calls per step counted by the solver's run ([`Run::rate_calls`], steps 2–5 of a wave run; a `rates` call counts 2): `kdk` 2 without artificial viscosity (3 with it), `rk4` 8 |
//! | `ns_per_particle_step` | the wave scene of the study (real 1D solver, this integrator, the same number of steps, Δt = min(0.2, `dt_used`)), median of `repeats` runs |
//! | `ns_per_evaluation` | `ns_per_particle_step` / `rate_calls_per_step` |
//! | `ns_per_particle_time` | `ns_per_particle_step` / `dt_used`: the cost of advancing one particle by Δx/c |
//! | `phase_error_*ppw` | (ω_num − ω)·T at κΔx = 2π/10, 2π/20, radians per wavelength travelled (T = 2π/ω, ω = cκ the continuum): negative = the numerical wave lags; spatial and temporal error together |
//! | `amplitude_error_*ppw` | \|λ\|^{T/Δt} − 1 at the same modes: negative = damped |
//!
//! λ is the eigenvalue of the scheme's amplification matrix (one cycle; [`Modes::amplification_with`],
//! the matrix the stability analysis uses) for the physical branch: [`physical_eigenvalue`].

use crate::analysis::{IntegratorReport, Query};
use crate::error::{Error, Result};
use crate::forms::{FieldKind, FormKind, Model, State};
use crate::integrator::{Integrator, Stepper};
use crate::kernel::Kernel;
use crate::solver::Run;
use crate::vonneumann::amplification::{Modes, max_spectral_radius_with};
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::linearise::{Linearisation, eigen};
use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Largest amplitude growth a weakly unstable scheme may give any mode of the κ grid while the
/// 10-points-per-wavelength wave travels one wavelength ([`T_REF`]): 0.1 %, ten times below the
/// amplitude error of `kdk` at 10 ppw — small next to the errors the stable schemes make, so the
/// weak schemes are compared at a Δt where their spurious growth is not what limits accuracy.
pub const WEAK_TOL: f64 = 1e-3;
/// The time over which [`WEAK_TOL`] applies: one period of the wave at 10 points per wavelength,
/// 10 Δx/c.
pub const T_REF: f64 = 10.0;
/// Safety factor on the critical Δt when the study config does not give one.
pub const DEFAULT_SAFETY: f64 = 0.9;

/// One (configuration, integrator) of the study (module table).
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
pub struct IntegratorRow {
    /// Form.
    pub form: String,
    /// Kernel.
    pub kernel: String,
    /// Shape family.
    pub shape: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// Integrator (CLI name).
    pub integrator: String,
    /// N_s of `verlet-euler` (null for the others).
    pub euler_every: Option<usize>,
    /// Order of accuracy of the scheme.
    pub order: u32,
    /// Critical Δt (Δx/c) at σ̄ = 0; null for weakly unstable schemes.
    pub critical_dt: Option<f64>,
    /// Whether the scheme amplifies non-growing modes at every Δt.
    pub weak: bool,
    /// Weakly unstable schemes: spurious growth per unit time (c/Δx) at Δt = 1/ω_max.
    pub weak_growth_rate: Option<f64>,
    /// How `dt_used` was chosen: "safety" or "weak-tolerance".
    pub dt_rule: Option<String>,
    /// The Δt of the cost and error columns (Δx/c).
    pub dt_used: Option<f64>,
    /// Nominal rate evaluations per step of the scheme.
    pub evaluations_per_step: usize,
    /// accel + qrate calls per step counted on the 1D solver's system.
    pub rate_calls_per_step: Option<f64>,
    /// Solver ns per particle-step.
    pub ns_per_particle_step: Option<f64>,
    /// ns per rate call.
    pub ns_per_evaluation: Option<f64>,
    /// ns per particle per Δx/c of simulated time at `dt_used`.
    pub ns_per_particle_time: Option<f64>,
    /// Phase error per wavelength travelled (radians) at 10 points per wavelength.
    pub phase_error_10ppw: Option<f64>,
    /// Amplitude error per wavelength travelled at 10 points per wavelength.
    pub amplitude_error_10ppw: Option<f64>,
    /// Phase error per wavelength travelled (radians) at 20 points per wavelength.
    pub phase_error_20ppw: Option<f64>,
    /// Amplitude error per wavelength travelled at 20 points per wavelength.
    pub amplitude_error_20ppw: Option<f64>,
    /// Why the row could not be computed.
    pub error: Option<String>,
}

/// The physical branch of `integ` at mode κΔx = `kappa`, step `dt` (Δx/c): returns
/// (ln |λ| per step, arg λ per step) with the phase unwrapped, λ the eigenvalue of one cycle's
/// amplification matrix taken to the power 1/cycle.
///
/// Which eigenvalue: the amplification matrix acts on the mode's state (and, for `pec` and
/// `verlet-euler`, on what the scheme carries between steps), so it has more eigenvalues than
/// the two acoustic branches. The physical one is the eigenvalue whose eigenvector is a wave
/// with s ≈ −iω — velocity and displacement parts with Im(v x̄) < 0, i.e. e^{i(κX − ωt)} — and,
/// among those, the one closest to e^{−iωNΔt} (ω = κ c/Δx, N = cycle). The mirror branch
/// (s ≈ +iω) has the same modulus and opposite phase for these symmetric stencils, so the choice
/// of direction does not change the numbers. Auxiliary-only eigenvectors (a density change
/// without motion, λ = 1) and memory modes have no motion part or lie far from the target.
/// For a cycle of N steps (`verlet-euler`) the phase of the cycle eigenvalue is unwrapped to the
/// multiple of 2π nearest −ωNΔt and divided by N.
pub fn physical_eigenvalue(
    lin: &Linearisation,
    kappa: f64,
    dt: f64,
    integ: Integrator,
) -> Result<(f64, f64)> {
    let g = Modes::amplification_with(lin, kappa, dt, integ);
    let n = integ.cycle() as f64;
    let target = Complex64::from_polar(1.0, -kappa * n * dt);
    let find = |kind: FieldKind| lin.dofs.iter().position(|d| d.comp.kind() == kind);
    let (Some(ix), Some(iv)) = (find(FieldKind::Position), find(FieldKind::Velocity)) else {
        return Err(Error::Incompatible(
            "physical eigenvalue: the linearisation has no position or velocity dof".into(),
        ));
    };
    let ev = eigen(g.clone())?;
    let mut best: Option<(f64, Complex64)> = None;
    for &mu in &ev {
        let w = null_vector(&g, mu)?;
        let norm2: f64 = w.iter().map(|z| z.norm_sqr()).sum();
        let motion = w[ix].norm_sqr() + w[iv].norm_sqr();
        let forward = (w[iv] * w[ix].conj()).im < 0.0;
        if motion < 1e-6 * norm2 || !forward {
            continue;
        }
        let d = (mu - target).norm();
        if best.is_none_or(|b| d < b.0) {
            best = Some((d, mu));
        }
    }
    let Some((_, mu)) = best else {
        return Err(Error::NonFinite(
            "physical eigenvalue (no forward-travelling eigenvector)",
        ));
    };
    let phase0 = mu.arg();
    let m = ((-kappa * n * dt - phase0) / (2.0 * PI)).round();
    let phase = phase0 + 2.0 * PI * m;
    Ok((mu.norm().ln() / n, phase / n))
}

/// A unit vector w with (G − μI) w ≈ 0: the right singular vector of the smallest singular value.
fn null_vector(g: &DMatrix<Complex64>, mu: Complex64) -> Result<Vec<Complex64>> {
    let n = g.nrows();
    let a = g - DMatrix::<Complex64>::identity(n, n) * mu;
    let svd = a
        .try_svd(false, true, 1e-15, 10_000)
        .ok_or(Error::NonFinite("eigenvector (SVD did not converge)"))?;
    let vt = svd.v_t.ok_or(Error::NonFinite("eigenvector (no V)"))?;
    let i = svd
        .singular_values
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, _)| i)
        .unwrap_or(0);
    Ok(vt.row(i).iter().map(|z| z.conj()).collect())
}

/// Phase error (radians) and amplitude error per wavelength travelled of the physical branch at
/// κΔx = 2π/`ppw` ([`physical_eigenvalue`]; module table).
pub fn errors_per_wavelength(
    lin: &Linearisation,
    ppw: f64,
    dt: f64,
    integ: Integrator,
) -> Result<(f64, f64)> {
    let kappa = 2.0 * PI / ppw;
    let (ln_r, phase) = physical_eigenvalue(lin, kappa, dt, integ)?;
    let omega_num = -phase / dt;
    let period = 2.0 * PI / kappa;
    let phase_err = (omega_num - kappa) * period;
    let amp_err = (ln_r * period / dt).exp_m1();
    if !(phase_err.is_finite() && amp_err.is_finite()) {
        return Err(Error::NonFinite("phase/amplitude error per wavelength"));
    }
    Ok((phase_err, amp_err))
}

/// Amplitude growth of the worst mode of `ks` over [`T_REF`] at step `dt`: max |λ|^{T_REF/Δt} − 1
/// from the raw spectral radius (no [`crate::vonneumann::amplification::AMPLIFICATION_TOL`]: at
/// the small steps a weak scheme needs, 1e-7 per step would add up to more than [`WEAK_TOL`]).
pub fn growth_per_reference_wavelength(
    lin: &Linearisation,
    ks: &[f64],
    dt: f64,
    integ: Integrator,
) -> Result<f64> {
    let r = max_spectral_radius_with(lin, ks, dt, integ)?.map_or(1.0, |b| b.0);
    Ok((r.ln() * T_REF / dt).exp_m1())
}

/// The largest Δt (Δx/c) with [`growth_per_reference_wavelength`] ≤ [`WEAK_TOL`]: bracket by
/// halving/doubling from 1/ω_max, then bisection to a relative gap of 1e-9.
pub fn weak_dt(lin: &Linearisation, ks: &[f64], integ: Integrator, omega_max: f64) -> Result<f64> {
    let ok = |dt: f64| -> Result<bool> {
        Ok(growth_per_reference_wavelength(lin, ks, dt, integ)? <= WEAK_TOL)
    };
    let start = if omega_max > 0.0 {
        1.0 / omega_max
    } else {
        1.0
    };
    let (mut lo, mut hi);
    if ok(start)? {
        lo = start;
        hi = 2.0 * start;
        while ok(hi)? {
            lo = hi;
            hi *= 2.0;
            if hi > 1e6 {
                return Ok(lo);
            }
        }
    } else {
        hi = start;
        lo = 0.5 * start;
        while !ok(lo)? {
            hi = lo;
            lo *= 0.5;
            if lo < 1e-12 {
                return Err(Error::NonFinite(
                    "weak-instability Δt (no Δt ≥ 1e-12 keeps the growth below the tolerance)",
                ));
            }
        }
    }
    for _ in 0..80 {
        if hi - lo <= 1e-9 * hi {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if ok(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(lo)
}

/// The engine's part of a row: critical Δt, the Δt used and the errors per wavelength.
pub fn analyse(
    form: FormKind,
    k: &'static dyn Kernel,
    h: f64,
    integ: Integrator,
    safety: f64,
    points: usize,
    row: &mut IntegratorRow,
) -> Result<()> {
    let mut q = Query::<1>::new(form, k, h, 0.0);
    q.grid = points;
    let lin = q.chain()?;
    let ks = q.kappas();
    let mut grows = false;
    for &kap in &ks {
        grows |= lin.growth(kap)? > GROWTH_TOL;
    }
    // J(κ) once per mode, not once per mode and Δt of the bisection: the same report
    let rep = IntegratorReport::of(&lin.mode_table(&ks), &ks, integ, None, h)?;
    row.critical_dt = rep.critical_dt.filter(|d| d.is_finite() && !grows);
    row.weak = rep.weak_instability;
    row.weak_growth_rate = rep.weak_instability.then_some(rep.spurious_growth_rate);
    let (dt, rule) = match (row.critical_dt, rep.weak_instability, grows) {
        (Some(c), _, false) => (safety * c, "safety"),
        (None, true, false) => (weak_dt(&lin, &ks, integ, rep.omega_max)?, "weak-tolerance"),
        _ => return Ok(()), // the semi-discrete system grows: no time-step question to answer
    };
    row.dt_used = Some(dt);
    row.dt_rule = Some(rule.into());
    let (p10, a10) = errors_per_wavelength(&lin, 10.0, dt, integ)?;
    let (p20, a20) = errors_per_wavelength(&lin, 20.0, dt, integ)?;
    row.phase_error_10ppw = Some(p10);
    row.amplitude_error_10ppw = Some(a10);
    row.phase_error_20ppw = Some(p20);
    row.amplitude_error_20ppw = Some(a20);
    Ok(())
}

/// `accel` + `qrate` calls per step of `integ` on the solver's run of `model` (from `z`),
/// counted over steps 2–5 (the first step of `pec`/`verlet-euler` starts the memory).
pub fn rate_calls_per_step(
    model: &Model<1>,
    z: &State<f64, 1>,
    integ: Integrator,
    dt: f64,
) -> Result<f64> {
    let mut run = Run::with_prescribed(model.clone(), z.clone(), &vec![None; z.x.len()])?;
    run.set_integrator(integ);
    run.step(dt)?;
    let first = run.rate_calls();
    const STEPS: usize = 4;
    for _ in 0..STEPS {
        run.step(dt)?;
    }
    Ok((run.rate_calls() - first) as f64 / STEPS as f64)
}

/// The nominal evaluations per step of `integ` for the solver's run of `model`.
pub fn evaluations_per_step(model: &Model<1>, integ: Integrator) -> usize {
    Stepper::<f64>::new(integ).evaluations_per_step(model.p.av.is_some())
}
