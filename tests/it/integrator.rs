//! The leapfrog step shared by solver and analysis: its amplification matrices against the
//! analytic leapfrog relation, the critical time step, and single-mode runs of the real rate
//! function on periodic chains against the engine's frequency and growth rate.

use crate::common;

use common::*;
use sphstab::forms::{FormKind, Model};
use sphstab::integrator::{Scratch, kdk_step};
use sphstab::shape::ShapeFamily;
use sphstab::solver::{BoundaryDensity, System, SystemBuffers};
use sphstab::vonneumann::amplification::{
    AMPLIFICATION_TOL, amplification_matrix, critical_dt, critical_dt_bisection, spectral_radius,
};
use sphstab::vonneumann::linearise::eigen;
use std::f64::consts::PI;

/// For a non-dissipative mode the leapfrog pair satisfies λ² − (2 − ω²Δt²)λ + 1 = 0, so below
/// the limit |λ| = 1 and Re λ = 1 − ω²Δt²/2 (analytic central-difference relation).
#[test]
fn amplification_matrix_reproduces_the_leapfrog_relation() {
    for (form, shape, sig) in [
        (FormKind::Classical, ShapeFamily::Sph, -0.2),
        (FormKind::Cll, ShapeFamily::Sph, -0.1),
        (FormKind::TotalLagrangian, ShapeFamily::Mls, 0.3),
        (FormKind::EulerianStressPoints, ShapeFamily::Mls, 0.1),
    ] {
        let l = lin(form, "m4", shape, 1.3, sig);
        for kap in [0.4, 1.5, 2.7] {
            let w2 = l.omega2(kap).0;
            let dt = 0.5;
            let ev = eigen(amplification_matrix(&l, kap, dt)).unwrap();
            // the mechanical pair: the two eigenvalues farthest from 1
            let mut mech: Vec<_> = ev.to_vec();
            mech.sort_by(|a, b| (b - 1.0).norm().partial_cmp(&(a - 1.0).norm()).unwrap());
            let want_re = 1.0 - 0.5 * w2 * dt * dt;
            for lam in &mech[..2] {
                assert!(
                    (lam.norm() - 1.0).abs() < 1e-10,
                    "{form:?} κ={kap}: |λ| = {}",
                    lam.norm()
                );
                assert!(
                    (lam.re - want_re).abs() < 1e-10,
                    "{form:?} κ={kap}: Re λ {} vs {want_re}",
                    lam.re
                );
            }
        }
    }
}

/// Δt_crit = 2/ω_max: below it (−1e−6 relative) no mode amplifies; above it (+1e−4) one does;
/// bisection on the amplification matrices finds the same value.
#[test]
fn critical_time_step_is_where_amplification_starts() {
    for (form, shape, kern, h, sig) in [
        (
            FormKind::TotalLagrangian,
            ShapeFamily::Mls,
            "efg-quartic",
            1.5,
            0.0,
        ),
        (
            FormKind::LagrangianStressPoints,
            ShapeFamily::Mls,
            "efg-quartic",
            1.5,
            0.0,
        ),
        (
            FormKind::Nonlocal,
            ShapeFamily::Sph,
            "wendland-c2",
            1.5,
            0.05,
        ),
        (FormKind::Classical, ShapeFamily::Sph, "m4", 1.2, -0.05),
    ] {
        let l = lin(form, kern, shape, h, sig);
        let ks = grid(512);
        let dtc = critical_dt(&l, &ks).unwrap();
        let below = ks
            .iter()
            .map(|&k| spectral_radius(&l, k, dtc * (1.0 - 1e-6)).unwrap())
            .fold(0.0, f64::max);
        let above = ks
            .iter()
            .map(|&k| spectral_radius(&l, k, dtc * (1.0 + 1e-4)).unwrap())
            .fold(0.0, f64::max);
        assert!(below <= 1.0 + AMPLIFICATION_TOL, "{form:?}: below {below}");
        assert!(above > 1.0 + 1e-4, "{form:?}: above {above}");
        let bis = critical_dt_bisection(&l, &ks).unwrap();
        // the double root at the limit makes |λ| − 1 grow like sqrt(Δt − Δt_c): 1e-9 of |λ| is
        // ~1e-18 of Δt, so bisection agrees to the bisection tolerance
        assert!(
            (bis - dtc).abs() < 1e-6 * dtc,
            "{form:?}: bisection {bis} vs 2/ω_max {dtc}"
        );
        eprintln!("{form:?} {kern} h={h} σ̄={sig}: Δt_crit = {dtc:.6} Δx/c");
    }
    // [B00] Table II: λ_max = 1.0 (nodal) → Δt_crit = 2; 2.0 (Lagrangian stress points) → √2.
    let l = lin(
        FormKind::TotalLagrangian,
        "efg-quartic",
        ShapeFamily::Mls,
        1.5,
        0.0,
    );
    assert!((critical_dt(&l, &grid(4096)).unwrap() - 2.0).abs() < 1e-6);
    let l = lin(
        FormKind::LagrangianStressPoints,
        "efg-quartic",
        ShapeFamily::Mls,
        1.5,
        0.0,
    );
    assert!((critical_dt(&l, &grid(4096)).unwrap() - 2f64.sqrt()).abs() < 1e-9);
}

/// Runs the real rate function on a periodic chain of `n` particles seeded with one Fourier
/// mode (velocity amplitude `amp` c, wave number 2πm/n) and returns the displacement history
/// of that mode (projection on it) every step.
#[allow(clippy::too_many_arguments)]
fn run_mode_k(
    kern: &str,
    form: FormKind,
    shape: ShapeFamily,
    h: f64,
    sig: f64,
    n: usize,
    m: usize,
    amp: f64,
    dt: f64,
    steps: usize,
) -> Vec<f64> {
    let p = params(form, kern, shape, h);
    let x_ref: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let model = Model::new(
        p,
        x_ref.iter().map(|&x| [x]).collect(),
        vec![1.0; n],
        1.0,
        sig,
        Some([[n as f64]]),
    )
    .unwrap();
    let rest = model.rest_state(1.0);
    let bufs = SystemBuffers::new(&model).unwrap();
    let fixed = vec![false; n];
    let sys = System::new(&model, &fixed, BoundaryDensity::Evolve, &bufs);
    let (mut x, mut v) = (
        rest.x.as_flattened().to_vec(),
        rest.v.as_flattened().to_vec(),
    );
    let mut q = Vec::new();
    sys.flatten_into(&rest, &mut q);
    let kap = 2.0 * PI * m as f64 / n as f64;
    // Seed a velocity (not a displacement: displacing particles while keeping ρ and σ uniform
    // is itself an equilibrium of the rate-form system).
    for (i, vi) in v.iter_mut().enumerate() {
        *vi = amp * (kap * i as f64).cos();
    }
    let norm: f64 = (0..n).map(|i| (kap * i as f64).cos().powi(2)).sum();
    let proj = |x: &[f64]| -> f64 {
        x.iter()
            .zip(&x_ref)
            .enumerate()
            .map(|(i, (a, b))| (a - b) * (kap * i as f64).cos())
            .sum::<f64>()
            / norm
    };
    let mut hist = vec![proj(&x)];
    let mut s = Scratch::default();
    for _ in 0..steps {
        kdk_step(&sys, &mut x, &mut v, &mut q, dt, &mut s);
        hist.push(proj(&x));
    }
    hist
}

/// Stable forms: the seeded mode oscillates at the engine's frequency — measured through the
/// leapfrog's exact discrete relation cos(ω_d Δt) = 1 − ω²Δt²/2 — to 1%.
#[test]
fn single_mode_frequency_matches_engine() {
    for (form, shape, sig) in [
        (FormKind::Classical, ShapeFamily::Sph, -0.1),
        (FormKind::Nonlocal, ShapeFamily::Sph, 0.2),
        (FormKind::Lnl, ShapeFamily::Sph, 0.2),
        (FormKind::TotalLagrangian, ShapeFamily::Mls, 0.2),
        (FormKind::EulerianStressPoints, ShapeFamily::Mls, 0.0),
        (FormKind::EulerianNodal, ShapeFamily::Mls, 0.5),
        // consistent mass: the system solves M a = f (banded LU)
        (FormKind::LeastSquares, ShapeFamily::Mls, 0.2),
    ] {
        let (n, m, dt) = (32, 5, 0.05);
        let kap = 2.0 * PI * m as f64 / n as f64;
        let w2 = lin(form, "m4", shape, 1.3, sig).omega2(kap).0;
        let wd = (1.0 - 0.5 * w2 * dt * dt).acos() / dt;
        let period = 2.0 * PI / wd;
        let steps = (4.0 * period / dt) as usize;
        let hist = run_mode_k("m4", form, shape, 1.3, sig, n, m, 1e-7, dt, steps);
        // zero crossings (linear interpolation) → measured period
        let mut cross = Vec::new();
        for i in 1..hist.len() {
            if hist[i - 1] > 0.0 && hist[i] <= 0.0 || hist[i - 1] < 0.0 && hist[i] >= 0.0 {
                cross.push((i - 1) as f64 + hist[i - 1] / (hist[i - 1] - hist[i]));
            }
        }
        assert!(
            cross.len() >= 6,
            "{form:?}: {} crossings, history starts {:?}",
            cross.len(),
            &hist[..5]
        );
        let measured = 2.0 * (cross[cross.len() - 1] - cross[0]) / (cross.len() - 1) as f64 * dt;
        let err = (measured / period - 1.0).abs();
        eprintln!("{form:?}: period measured {measured:.5}, engine {period:.5} (error {err:.2e})");
        assert!(err < 0.01, "{form:?}: {measured} vs {period}");
    }
}

/// Classical SPH in tension: the seeded sawtooth-side mode grows at the engine's rate (1%).
#[test]
fn single_mode_growth_matches_engine() {
    let (n, m, dt, sig) = (32, 14, 0.02, 0.05);
    let kap = 2.0 * PI * m as f64 / n as f64;
    let w2 = lin(FormKind::Classical, "m4", ShapeFamily::Sph, 1.2, sig)
        .omega2(kap)
        .0;
    assert!(w2 < 0.0);
    let gamma = (-w2).sqrt();
    // leapfrog growth per step: λ = 1 + γ²Δt²/2 + sqrt((1 + γ²Δt²/2)² − 1)
    let b = 1.0 + 0.5 * gamma * gamma * dt * dt;
    let gd = (b + (b * b - 1.0).sqrt()).ln() / dt;
    let steps = (12.0 / gamma / dt) as usize;
    let hist = run_mode_k(
        "m4",
        FormKind::Classical,
        ShapeFamily::Sph,
        1.2,
        sig,
        n,
        m,
        1e-12,
        dt,
        steps,
    );
    let (i1, i2) = (steps / 2, steps);
    let measured = (hist[i2].abs() / hist[i1].abs()).ln() / ((i2 - i1) as f64 * dt);
    eprintln!(
        "classical m4 h=1.2 σ̄={sig} κ={:.4}π: growth measured {measured:.6}, engine {gd:.6}",
        kap / PI
    );
    assert!((measured / gd - 1.0).abs() < 0.01, "{measured} vs {gd}");
}

/// No spurious compressive growth: a compressed classical chain, run for 20,000 steps at
/// Δt = 0.99 Δt_crit, keeps its perturbation bounded (the q-update uses v½, not the lagging
/// v^{n−½}, which would anti-damp every mode at ≈ ω²Δt/2).
#[test]
fn no_growth_in_stable_compressed_run_up_to_critical_step() {
    let l = lin(FormKind::Classical, "m4", ShapeFamily::Sph, 1.3, -0.05);
    let dtc = critical_dt(&l, &grid(512)).unwrap();
    for frac in [0.3, 0.99] {
        let hist = run_mode_k(
            "m4",
            FormKind::Classical,
            ShapeFamily::Sph,
            1.3,
            -0.05,
            16,
            8,
            1e-8,
            frac * dtc,
            20_000,
        );
        // amplitude of the first and last quarter of the run
        let q = hist.len() / 4;
        let first = hist[..q].iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        let last = hist[3 * q..].iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        eprintln!(
            "Δt = {frac} Δt_crit: amplitude first quarter {first:.6e}, last quarter {last:.6e}"
        );
        assert!(
            last <= first * (1.0 + 1e-6),
            "Δt = {frac} Δt_crit: {first:e} → {last:e}"
        );
    }
}

/// ERRATA E3 end to end: B00's eq 74 says Eulerian nodal EFG (mls, quartic weight, D_mx = 1.5)
/// is unstable in tension above κΔx ≈ 0.61π at σ̄ = 0.5; the full linearisation says it is
/// not. A time-domain run of the real (nonlinear) rate function with the mode κΔx = 3π/4 seeded
/// decides: it oscillates at the engine's frequency (1%) and does not grow.
#[test]
fn eulerian_nodal_mls_in_tension_oscillates_as_the_engine_says() {
    let (n, m, dt, sig) = (32, 12, 0.02, 0.5);
    let kap = 2.0 * PI * m as f64 / n as f64;
    let phi = shape_fn(ShapeFamily::Mls, "efg-quartic", 1.5);
    assert!(
        sphstab::vonneumann::closed_form::b00_eq74_eulerian_nodal(&phi, 1.5, sig, kap) < 0.0,
        "eq 74 predicts growth here"
    );
    let w2 = lin(
        FormKind::EulerianNodal,
        "efg-quartic",
        ShapeFamily::Mls,
        1.5,
        sig,
    )
    .omega2(kap)
    .0;
    assert!(w2 > 0.0);
    let wd = (1.0 - 0.5 * w2 * dt * dt).acos() / dt;
    let period = 2.0 * PI / wd;
    let steps = (6.0 * period / dt) as usize;
    let hist = run_mode_k(
        "efg-quartic",
        FormKind::EulerianNodal,
        ShapeFamily::Mls,
        1.5,
        sig,
        n,
        m,
        1e-7,
        dt,
        steps,
    );
    let mut cross = Vec::new();
    for i in 1..hist.len() {
        if hist[i - 1] > 0.0 && hist[i] <= 0.0 || hist[i - 1] < 0.0 && hist[i] >= 0.0 {
            cross.push((i - 1) as f64 + hist[i - 1] / (hist[i - 1] - hist[i]));
        }
    }
    let measured = 2.0 * (cross[cross.len() - 1] - cross[0]) / (cross.len() - 1) as f64 * dt;
    let max_late = hist[hist.len() / 2..]
        .iter()
        .fold(0.0f64, |a, &b| a.max(b.abs()));
    let max_early = hist[..hist.len() / 2]
        .iter()
        .fold(0.0f64, |a, &b| a.max(b.abs()));
    eprintln!(
        "eulerian-nodal/mls σ̄=0.5 κ=0.75π: period measured {measured:.5}, engine {period:.5}; amplitude {max_early:.3e} → {max_late:.3e}"
    );
    assert!((measured / period - 1.0).abs() < 0.01);
    // sampled peaks vary by O((πΔt/T)²) ≈ 1e-3 between halves; eq 74's growth rate would
    // multiply the amplitude by e^{γ t} ≫ 2 over this run
    assert!(max_late <= max_early * 1.01);
}

/// Issue 24, item 2: `timestep` gives a Δt with its defaults (classical m4, h = 1.2Δx, σ̄ = 0.01,
/// kdk), although the semi-discrete system grows there (tensile, which it reports as physical
/// growth with its kind). The Δt is checked in the time domain, by the solver's own rate
/// function: the mode nearest the fastest oscillating one (ω² at its maximum over the modes
/// that do not grow), seeded on a 200-particle periodic chain, stays bounded for 40 steps at
/// 0.98 Δt_crit and grows by orders of magnitude at 1.02 Δt_crit (the leapfrog's |λ| ≈ 1.5 per
/// step there); 40 steps are far too short for the physical growth (0.15 c/Δx, seeded by
/// rounding only) to matter.
#[test]
fn default_timestep_gives_a_step_that_holds_in_the_time_domain() {
    use sphstab::analysis::{Query, timestep};
    let q = Query::<1>::new(FormKind::Classical, k("m4"), 1.2, 0.01);
    let r = timestep(&q).unwrap();
    assert!(
        r.step.physical_growth_rate > 0.1,
        "{}",
        r.step.physical_growth_rate
    );
    assert_eq!(
        r.physical_growth_kind,
        Some(sphstab::vonneumann::classify::Kind::Tensile)
    );
    let dtc = r.step.critical_dt.expect("a Δt with the defaults");
    assert!(dtc.is_finite() && dtc > 0.0);
    // the fastest oscillating mode, and the nearest mode of the chain
    let l = lin(FormKind::Classical, "m4", ShapeFamily::Sph, 1.2, 0.01);
    let (_, kap) = grid(2000)
        .into_iter()
        .map(|kap| (l.omega2(kap).0, kap))
        .filter(|p| p.0 > 0.0)
        .fold((f64::MIN, 0.0), |a, b| if b.0 > a.0 { b } else { a });
    let n = 200;
    let m = (kap * n as f64 / (2.0 * PI)).round() as usize;
    let peak = |frac: f64| {
        let hist = run_mode_k(
            "m4",
            FormKind::Classical,
            ShapeFamily::Sph,
            1.2,
            0.01,
            n,
            m,
            1e-8,
            frac * dtc,
            40,
        );
        let first = hist[0].abs().max(hist[1].abs());
        hist.iter().fold(0.0f64, |a, &b| a.max(b.abs())) / first
    };
    let (below, above) = (peak(0.98), peak(1.02));
    eprintln!(
        "Δt_crit = {dtc}: peak/initial amplitude at 0.98 Δt_crit {below:.3e}, at 1.02 {above:.3e}"
    );
    assert!(below < 20.0, "{below}");
    assert!(above > 1e4, "{above}");
}

/// Issue 24, item 3: the labels of every integrator's `timestep` report agree with each other
/// and with what the scheme does at a probe Δt, without and with viscosity (classical m4,
/// h = 1.2Δx, σ̄ = 0.01: the defaults, a growing system). A weakly unstable scheme has no
/// critical Δt and no closed form; any other scheme's `critical_dt` is a real boundary: at
/// 0.95 of it the scheme adds no growth (`added_growth_kind` null, rate 0), at 1.05 it adds
/// growth named `time-step`; `decay_rate_max` is present exactly with viscosity, and
/// `omega_max` is then the oscillation frequency, below the decay-inclusive |s| that sets
/// the default probe Δt.
#[test]
fn timestep_labels_agree_for_every_integrator() {
    use sphstab::analysis::{Query, timestep};
    use sphstab::integrator::Integrator;
    for av in [None, Some((1.0, 0.0))] {
        for integ in Integrator::all(40) {
            let mut q = Query::<1>::new(FormKind::Classical, k("m4"), 1.2, 0.01);
            q.grid = 128;
            q.av = av;
            q.integrator = integ;
            let r = timestep(&q).unwrap().step;
            let name = format!("{} (viscosity {av:?})", integ.name());
            assert_eq!(r.decay_rate_max.is_some(), av.is_some(), "{name}");
            assert!(r.physical_growth_rate > 0.0, "{name}");
            if r.weak_instability {
                assert!(
                    r.critical_dt.is_none() && r.critical_dt_closed_form.is_none(),
                    "{name}: weak, yet a critical Δt"
                );
                assert_eq!(r.added_growth_kind, Some("integrator"), "{name}");
                continue;
            }
            let dtc = r.critical_dt.unwrap_or_else(|| panic!("{name}: no Δt"));
            match r.added_growth_kind {
                None => assert!(r.spurious_growth_rate == 0.0 && r.spurious_growth_dt <= dtc),
                Some(kind) => assert!(
                    kind == "time-step" && r.spurious_growth_dt > dtc,
                    "{name}: {kind} at {} (critical {dtc})",
                    r.spurious_growth_dt
                ),
            }
            for (frac, adds) in [(0.95, false), (1.05, true)] {
                let mut qd = q;
                qd.dt = Some(frac * dtc);
                let s = timestep(&qd).unwrap().step;
                assert_eq!(
                    s.added_growth_kind,
                    adds.then_some("time-step"),
                    "{name} at {frac} Δt_crit: rate {}",
                    s.spurious_growth_rate
                );
                assert_eq!(s.spurious_growth_rate > 0.0, adds, "{name} at {frac}");
            }
        }
    }
}
