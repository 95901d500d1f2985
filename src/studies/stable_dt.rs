//! The largest stable time step measured in the time domain (`sphstab timestep --verify`): the
//! question's lattice, uniformly pre-stressed and periodic, run by the solver with a small random
//! perturbation, Δt bisected until a run adds no growth and a run 1% longer in Δt does.
//!
//! Why: the linear analysis applies Monaghan viscosity to every pair (two-sided), as a
//! linearisation must; SPH codes and this solver switch it off for receding pairs (one-sided),
//! which is not linear. With two-sided viscosity the measurement checks the analysis; with
//! one-sided viscosity it is the answer for the user's code, which the analysis can only bracket
//! between the two-sided and the inviscid limits.
//!
//! The measurement: a periodic body of the question's lattice ([`cells`] per side, the
//! wave vectors 2πm/N of the zone), at rest in the question's pre-stress, its positions and
//! velocities perturbed by a deterministic pseudo-random field of relative size
//! [`PERTURBATION`] (zero mean). The perturbation is measured every step in the norm
//! ‖(δx/Δx, δv/c)‖ and renormalised to its initial size whenever it has grown or decayed
//! a hundredfold ([`Run::scale_perturbation`]: state and integrator memory, so the scheme is not
//! restarted), so it stays in the linear regime at any growth rate; the growth exponent is
//! the accumulated log growth over the second half of [`STEPS`] steps. A run *adds growth*
//! when that exponent exceeds the physical growth rate of the semi-discrete system (the
//! analysis' rate, within [`GROWTH_REL_TOL`], inviscid for one-sided viscosity: switching the
//! viscosity off on receding pairs can only damp less) by more than [`FLOOR_PER_STEP`] per
//! step: the resolution of a run of [`STEPS`] steps (a mode that grows by 1 + 1e-3 per step
//! grows e³ ≈ 20-fold over the measured half; the transient of a stable run measured below
//! 2e-4 per step).

use crate::analysis::{self, Query};
use crate::budget::fmt_count;
use crate::error::{Error, Result, Text, field, fields};
use crate::forms::{State, ViscosityPairs};
use crate::lattice::LatticeKind;
use crate::progress::Progress;
use crate::solver::run::{BoundaryDensity, Run};
use crate::vonneumann::amplification::GROWTH_REL_TOL;
use crate::vonneumann::linearise::{base_state, lattice_particles, periodic_lattice};
use serde::Serialize;

/// Relative size of the initial perturbation (δx in Δx, δv in c).
pub const PERTURBATION: f64 = 1e-6;
/// Steps of one run; the growth exponent is measured over the second half.
pub const STEPS: usize = 6000;
/// Growth per step beyond the physical one that counts as added growth.
pub const FLOOR_PER_STEP: f64 = 1e-3;
/// Relative width of the final Δt bracket.
pub const DT_RESOLUTION: f64 = 0.01;
/// Factor of the bracketing search from the first guess.
const BRACKET_FACTOR: f64 = 1.25;
/// Largest number of bracketing steps up (stable at 1.25⁸ ≈ 6× the first guess: reported as
/// stable up to there) and down (nothing stable at 1.25⁻²⁰ ≈ 0.012×).
const BRACKET_UP: usize = 8;
const BRACKET_DOWN: usize = 20;
/// Largest number of runs of one check (bracketing and bisection), for the budget.
pub const MAX_RUNS: usize = 1 + BRACKET_DOWN + 5;
/// Renormalise when the perturbation has grown or decayed by this factor.
const RENORMALISE: f64 = 100.0;

/// Cells per side of the periodic body: 64 in 1D, and in 2D and 3D at least the Bloch
/// linearisation's patch (so no particle sees two images of a neighbour), at least 16 (2D) and
/// 6 (3D), rounded up so that the zone's symmetry points are sampled (a multiple of 2; 6 on the
/// hexagonal lattice (K, M); 4 on fcc (K, W)).
pub fn cells<const D: usize>(q: &Query<D>) -> usize {
    if D == 1 {
        return 64;
    }
    let r = q.h_over_dx * q.kernel.zeta();
    let lat = &q.lattice;
    let (min, patch) = if D == 2 {
        (
            16,
            2 * ((2.0 * r / lat.plane_spacing()).ceil() as usize + 2) + 1,
        )
    } else {
        let side = match lat.kind {
            LatticeKind::Bcc => 2f64.cbrt(),
            LatticeKind::Fcc => 4f64.cbrt(),
            _ => 1.0,
        };
        (6, (2.0 * r / side).ceil() as usize + 2)
    };
    let step = match lat.kind {
        LatticeKind::Hexagonal => 6,
        LatticeKind::Fcc => 4,
        _ => 2,
    };
    min.max(patch).div_ceil(step) * step
}

/// One time-domain run of the check.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct ProbeRun {
    /// Δt (Δx/c).
    pub dt: f64,
    /// Steps.
    pub steps: usize,
    /// Particles of the periodic body.
    pub particles: usize,
    /// Growth exponent of the perturbation over the second half of the run (c/Δx); null when
    /// the run diverged.
    pub growth_rate: Option<f64>,
    /// The largest growth exponent that adds no growth: the physical rate within
    /// [`GROWTH_REL_TOL`] plus [`FLOOR_PER_STEP`]/Δt (c/Δx).
    pub allowed_growth_rate: f64,
    /// Whether the run adds growth (the Δt is unstable).
    pub grows: bool,
}

/// The measured limit next to the analysis.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct StableDtReport {
    /// Which pairs the viscosity of the runs acts on (null without viscosity).
    pub viscosity: Option<ViscosityPairs>,
    /// Integrator.
    pub integrator: String,
    /// The analysis' critical Δt (Δx/c; viscosity, if any, on every pair); null when it has
    /// none (weak instability).
    pub predicted_dt: Option<f64>,
    /// The analysis' critical Δt at the runs' resolution, [`FLOOR_PER_STEP`] added growth per
    /// step in place of 1e-7 ([`analysis::critical_dt_to`]): the same criterion as the runs'.
    /// Above predicted_dt where the added growth rises slowly beyond it.
    pub predicted_dt_at_resolution: Option<f64>,
    /// The analysis' critical Δt without viscosity (null without `--av-alpha` or when weak).
    pub inviscid_dt: Option<f64>,
    /// Largest Δt (Δx/c) of the bracket at which a run adds no growth; the next run, at most
    /// 1% longer in Δt, adds growth. Null when no bracket was found.
    pub measured_dt: Option<f64>,
    /// measured_dt / predicted_dt_at_resolution.
    pub ratio: Option<f64>,
    /// The run that proves measured_dt stable.
    pub stable_run: Option<ProbeRun>,
    /// The run just above it that grows (or the smallest Δt tried, when every run grew).
    pub unstable_run: Option<ProbeRun>,
    /// Runs made.
    pub runs: usize,
}

/// splitmix64: a fixed pseudo-random sequence (the same perturbation in every run).
fn splitmix(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    // uniform in [−1, 1)
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// The periodic body of a check: the run's model with the chosen viscosity pairs, its rest
/// state, Δx and c.
struct Body<const D: usize> {
    run: Run<D>,
    base: State<f64, D>,
    dx: f64,
    c: f64,
}

fn body<const D: usize>(q: &Query<D>, pairs: ViscosityPairs) -> Result<Body<D>> {
    let mut p = q.params()?;
    if let Some(av) = &mut p.av {
        av.approaching_only = pairs.approaching_only();
    }
    let c = (p.material.modulus() / p.rho0).sqrt();
    let (dx, rho, s0) = if D == 1 {
        // as the chain linearisation: ρ0 and σ0 = σ̄ C, in the question's units
        (q.units.dx, p.rho0, q.sigma0(q.stress))
    } else {
        let (rho, s0) = base_state(&p.material, p.rho0, q.stress)?;
        (1.0, rho, s0)
    };
    let (model, _) = periodic_lattice(p, &q.lattice, dx, rho, s0, cells(q))?;
    let base = model.rest_state(rho);
    let n = base.x.len();
    let run = Run::new(model, base.clone(), vec![false; n], BoundaryDensity::Evolve)?;
    Ok(Body { run, base, dx, c })
}

/// ‖(δx/Δx, δv/c)‖ of the run's deviation from `base`.
fn deviation<const D: usize>(b: &Body<D>) -> f64 {
    let z = &b.run.z;
    let mut s = 0.0;
    for (x, xb) in z.x.iter().zip(&b.base.x) {
        for a in 0..D {
            s += ((x[a] - xb[a]) / b.dx).powi(2);
        }
    }
    for v in &z.v {
        for va in v {
            s += (va / b.c).powi(2);
        }
    }
    s.sqrt()
}

/// One run at `dt` (Δx/c): the growth exponent of the perturbation (c/Δx) over the second
/// half of [`STEPS`] steps, None when the run diverged.
fn probe<const D: usize>(
    q: &Query<D>,
    pairs: ViscosityPairs,
    dt: f64,
    progress: &dyn Progress,
) -> Result<Option<f64>> {
    let mut b = body(q, pairs)?;
    b.run.set_integrator(q.integrator);
    let n = b.base.x.len();
    // the perturbation, zero mean (no drift, no translation)
    let mut seed = 0x5eed_u64;
    let mut dxs = vec![[0.0; D]; n];
    let mut dvs = vec![[0.0; D]; n];
    for i in 0..n {
        for a in 0..D {
            dxs[i][a] = PERTURBATION * b.dx * splitmix(&mut seed);
            dvs[i][a] = PERTURBATION * b.c * splitmix(&mut seed);
        }
    }
    for f in [&mut dxs, &mut dvs] {
        for a in 0..D {
            let mean = f.iter().map(|p| p[a]).sum::<f64>() / n as f64;
            f.iter_mut().for_each(|p| p[a] -= mean);
        }
    }
    for i in 0..n {
        for a in 0..D {
            b.run.z.x[i][a] += dxs[i][a];
            b.run.z.v[i][a] = dvs[i][a];
        }
    }
    let a0 = deviation(&b);
    let step = dt * b.dx / b.c;
    let (mut logs, mut half) = (0.0, 0.0);
    for k in 1..=STEPS {
        if k % 256 == 0 && progress.cancelled() {
            return Err(Error::Cancelled);
        }
        match b.run.step(step) {
            Ok(()) => {}
            Err(Error::NonFinite(_)) => return Ok(None),
            Err(e) => return Err(e),
        }
        let a = deviation(&b);
        if !a.is_finite() {
            return Ok(None);
        }
        if k == STEPS / 2 {
            half = logs + (a / a0).ln();
        }
        if k == STEPS {
            logs += (a / a0).ln();
        } else if !(a0 / RENORMALISE..=a0 * RENORMALISE).contains(&a) {
            logs += (a / a0).ln();
            b.run.scale_perturbation(&b.base, a0 / a)?;
        }
    }
    Ok(Some((logs - half) / ((STEPS - STEPS / 2) as f64 * dt)))
}

/// The pairs the viscosity of the time-domain check acts on, by the name in `viscosity`:
/// one-sided (approaching pairs only, as SPH codes apply it; the default) or two-sided (every
/// pair, as the analysis linearises it). A name is refused without `verify` (the analysis
/// applies viscosity to every pair) and without viscosity (`viscous` false: nothing to switch).
pub fn viscosity_pairs(verify: bool, name: Option<&str>, viscous: bool) -> Result<ViscosityPairs> {
    let refuse = |context: Text| {
        Err(crate::analysis::spec::not_applicable(
            field("viscosity"),
            Text::from("timestep without ") + context,
        ))
    };
    match name {
        None => Ok(ViscosityPairs::OneSided),
        Some(_) if !verify => {
            refuse(field("verify") + " (the analysis applies viscosity to every pair)")
        }
        Some(_) if !viscous => refuse(field("av_alpha") + " (no viscosity to switch)"),
        Some(n) => ViscosityPairs::ALL
            .iter()
            .find(|(_, v)| *v == n)
            .map(|(p, _)| *p)
            .ok_or_else(|| Error::UnknownName {
                what: field("viscosity"),
                given: n.into(),
                valid: "one-sided, two-sided".into(),
            }),
    }
}

/// Measures the largest stable Δt of `q` (its form, lattice, pre-stress, viscosity and
/// integrator; `q.dt` is not read) with viscosity on `pairs`, to [`DT_RESOLUTION`], next to
/// the analysis' prediction. Refused before any work when one run (a time integration) would
/// exceed the budget's particle-steps; a check makes 7–12 runs, at most [`MAX_RUNS`].
pub fn stable_dt<const D: usize>(
    q: &Query<D>,
    pairs: ViscosityPairs,
    progress: &dyn Progress,
) -> Result<StableDtReport> {
    q.validate()?;
    let particles = lattice_particles(&q.lattice, cells(q));
    q.budget.steps(
        fields(&["dim", "h"]),
        &format!(
            "one run of the time-domain Δt check ({} particles × {} steps)",
            fmt_count(particles as f64),
            fmt_count(STEPS as f64)
        ),
        (particles * STEPS) as f64,
    )?;
    let r = analysis::timestep(q)?;
    let predicted_dt = r.step.critical_dt.filter(|d| d.is_finite());
    let inviscid_dt = r.critical_dt_inviscid.filter(|d| d.is_finite());
    let predicted_dt_at_resolution =
        analysis::critical_dt_to(q, FLOOR_PER_STEP.exp_m1())?.filter(|d| d.is_finite());
    // the physical growth the runs may show: the analysis' (two-sided viscosity damps it; a
    // one-sided one can only damp less than that, so its envelope is the inviscid rate)
    let physical = if q.av.is_some() && pairs == ViscosityPairs::OneSided {
        let mut q0 = *q;
        q0.av = None;
        analysis::timestep(&q0)?
            .step
            .physical_growth_rate
            .max(r.step.physical_growth_rate)
    } else {
        r.step.physical_growth_rate
    };
    let mut runs = 0;
    let mut run_at = |dt: f64| -> Result<ProbeRun> {
        runs += 1;
        progress.advance((runs as f64 / 12.0).min(0.95));
        let g = probe(q, pairs, dt, progress)?;
        let allowed = physical * (1.0 + GROWTH_REL_TOL) + FLOOR_PER_STEP / dt;
        Ok(ProbeRun {
            dt,
            steps: STEPS,
            particles,
            growth_rate: g,
            allowed_growth_rate: allowed,
            grows: g.is_none_or(|g| g > allowed),
        })
    };
    let first = predicted_dt_at_resolution
        .or(predicted_dt)
        .or(inviscid_dt)
        .unwrap_or(1.0 / r.step.omega_max.max(f64::MIN_POSITIVE));
    let mut lo: Option<ProbeRun> = None;
    let mut hi: Option<ProbeRun> = None;
    let p0 = run_at(first)?;
    if p0.grows {
        hi = Some(p0);
        for _ in 0..BRACKET_DOWN {
            let dt = hi.as_ref().map_or(first, |h| h.dt) / BRACKET_FACTOR;
            let p = run_at(dt)?;
            if p.grows {
                hi = Some(p);
            } else {
                lo = Some(p);
                break;
            }
        }
    } else {
        lo = Some(p0);
        for _ in 0..BRACKET_UP {
            let dt = lo.as_ref().map_or(first, |l| l.dt) * BRACKET_FACTOR;
            let p = run_at(dt)?;
            if p.grows {
                hi = Some(p);
                break;
            }
            lo = Some(p);
        }
    }
    if let (Some(l), Some(h)) = (&mut lo, &mut hi) {
        while h.dt / l.dt > 1.0 + DT_RESOLUTION {
            let p = run_at((l.dt * h.dt).sqrt())?;
            if p.grows {
                *h = p;
            } else {
                *l = p;
            }
        }
    }
    progress.advance(1.0);
    let measured_dt = match (&lo, &hi) {
        (Some(l), Some(_)) => Some(l.dt),
        _ => None,
    };
    Ok(StableDtReport {
        viscosity: q.av.map(|_| pairs),
        integrator: q.integrator.to_string(),
        predicted_dt,
        predicted_dt_at_resolution,
        inviscid_dt,
        measured_dt,
        ratio: measured_dt
            .zip(predicted_dt_at_resolution)
            .map(|(m, p)| m / p),
        stable_run: lo,
        unstable_run: hi,
        runs,
    })
}

/// The setup of [`viscosity_table`]: 1D classical SPH, M4, h = 1.3Δx, σ̄ = 0, Monaghan
/// viscosity α = 1, β = 0 (the case issue 24 measured).
pub fn table_query(integrator: crate::integrator::Integrator) -> Query<1> {
    let mut q = Query::<1>::new(
        crate::forms::FormKind::Classical,
        crate::kernel::by_name("m4").expect("m4 is a kernel"),
        1.3,
        0.0,
    );
    q.av = Some((1.0, 0.0));
    q.integrator = integrator;
    q
}

/// Every integrator × {two-sided, one-sided} viscosity on [`table_query`]: the analysis'
/// limits and the measured ones (cells in parallel).
pub fn viscosity_table(progress: &dyn Progress) -> Result<Vec<StableDtReport>> {
    use rayon::prelude::*;
    let cells: Vec<_> = crate::integrator::Integrator::all(crate::integrator::DEFAULT_EULER_EVERY)
        .into_iter()
        .flat_map(|i| {
            [ViscosityPairs::TwoSided, ViscosityPairs::OneSided]
                .into_iter()
                .map(move |p| (i, p))
        })
        .collect();
    let done = crate::progress::Counter::new(progress, cells.len(), 1);
    cells
        .par_iter()
        .map(|&(i, p)| {
            let r = stable_dt(&table_query(i), p, &())?;
            done.add(1)?;
            Ok(r)
        })
        .collect()
}

/// [`viscosity_table`] as a markdown table (Δt in Δx/c, 4 significant digits).
pub fn viscosity_markdown(rows: &[StableDtReport]) -> String {
    let f = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.4}"));
    let mut s = String::from(
        "| integrator | viscosity of the runs | analysis Δt, 1e-7/step | analysis Δt, 1e-3/step | inviscid analysis Δt | measured Δt (stable run) | next run (grows) | measured / analysis at 1e-3 |\n|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let predicted = match r.predicted_dt {
            Some(d) => format!("{d:.4}"),
            None => "weak".into(),
        };
        s += &format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} |\n",
            r.integrator,
            r.viscosity.map_or("none", |v| v.name()),
            predicted,
            f(r.predicted_dt_at_resolution),
            f(r.inviscid_dt),
            f(r.measured_dt),
            f(r.unstable_run.as_ref().map(|p| p.dt)),
            f(r.ratio),
        );
    }
    s
}
