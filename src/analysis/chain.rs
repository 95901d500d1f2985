//! The 1D engine behind [`super::query`], [`super::dispersion`] and [`super::timestep`]: the
//! chain linearisation ([`Linearisation`], every form of \[B00\]) over κΔx ∈ (0, π]. The κ line
//! is a segment, so unstable sets are contiguous runs of κ with a range and, where ω² passes a
//! pole, its position.

use super::common::IntegratorReport;
use super::query::Query;
use super::report::{
    DispersionReport, Header, Instability, Polarisation, QueryReport, TimestepReport,
};
use crate::error::{Error, Result, check_range};
use crate::integrator::Integrator;
use crate::params::check_count;
use crate::vonneumann::amplification::{
    AMPLIFICATION_TOL, critical_dt_given, leapfrog_limit, spectral_radius_with, step_stability,
};
use crate::vonneumann::classify::{GROWTH_TOL, Kind, ZERO_OMEGA2_TOL, branch, growth_kind, runs};
use crate::vonneumann::damping::{branch_eigenvalues, critical_dt_eq120, damping_ratio};
use crate::vonneumann::linearise::{Linearisation, PhaseTable};
use std::f64::consts::PI;

/// A branch of the κ line as a report row: the run `r` of `n` grid points.
fn row(b: crate::vonneumann::classify::Instability, r: (usize, usize), n: usize) -> Instability {
    Instability {
        kind: b.kind,
        growth_rate: b.growth_rate,
        kappa_at_max: vec![b.kappa_at_max],
        zone_fraction: (r.1 - r.0 + 1) as f64 / n as f64,
        kappa_min: Some(b.kappa_min),
        kappa_max: Some(b.kappa_max),
        pole_at: b.pole_at,
        unstressed_omega2: None,
        onset_stress: None,
    }
}

/// Growth rates and ω² on the grid (phase factors tabulated once: [`PhaseTable`]).
fn curve(lin: &Linearisation, kappas: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut w2 = Vec::with_capacity(kappas.len());
    let mut g = Vec::with_capacity(kappas.len());
    let table = PhaseTable::new(kappas, lin.reach());
    for k in 0..kappas.len() {
        if k % 4096 == 0 {
            crate::progress::interrupted()?;
        }
        let (o, _) = lin.omega2_tabulated(&table, k);
        if !o.is_finite() {
            return Err(Error::NonFinite("ω²"));
        }
        w2.push(o);
        g.push(if lin.is_dissipative() {
            lin.growth_tabulated(&table, k)?
        } else {
            (-o).max(0.0).sqrt()
        });
    }
    Ok((w2, g))
}

/// Answers a stability query.
pub(super) fn query<const D: usize>(q: &Query<D>) -> Result<QueryReport> {
    let lin = q.chain()?;
    super::work::check(
        q,
        &lin,
        q.kappa_sample(),
        q.modes(),
        super::work::Question::Query,
    )?;
    let kappas = q.kappas();
    let (w2, g) = curve(&lin, &kappas)?;
    let growing: Vec<bool> = g.iter().map(|&x| x > GROWTH_TOL).collect();
    let mut inst = Vec::new();
    let cbar = 1.0 + q.stress;
    let scale = w2.iter().fold(0.0f64, |m, &x| m.max(x.abs()));
    // the zero-stress linearisation, built once when a growing branch needs it
    let mut lin0 = None;
    for r in runs(&growing) {
        let b = branch(Kind::Material, &kappas, &g, r);
        let kind = growth_kind(cbar <= 0.0, q.stress, || {
            let l0 = match &mut lin0 {
                Some(l) => l,
                slot @ None => slot.insert(q.chain_at(0.0)?),
            };
            l0.growth(b.kappa_at_max)
        })?;
        // a pole: ω² changes sign between neighbours through ±∞ (both sides large), not
        // through 0; the first one at or before the branch
        let pole_at = (r.0.max(1)..=r.1).find_map(|i| {
            let (a, b) = (w2[i - 1], w2[i]);
            (a.signum() != b.signum() && a.abs().min(b.abs()) > 0.05 * scale)
                .then(|| 0.5 * (kappas[i - 1] + kappas[i]))
        });
        inst.push(row(
            crate::vonneumann::classify::Instability { kind, pole_at, ..b },
            r,
            kappas.len(),
        ));
    }
    // cbar ≤ 0 with nothing growing (C̄ = 0: ω ≡ 0 in the continuum): still material
    if cbar <= 0.0 && !inst.iter().any(|i| i.kind == Kind::Material) {
        let all = (0, kappas.len() - 1);
        let b = branch(Kind::Material, &kappas, &vec![0.0; kappas.len()], all);
        inst.push(row(b, all, kappas.len()));
    }
    let zero: Vec<bool> = w2
        .iter()
        .zip(&growing)
        .zip(&kappas)
        .map(|((&o, &gr), &k)| {
            !gr && o.abs() <= ZERO_OMEGA2_TOL * scale.max(1e-300)
                && o.abs() <= ZERO_OMEGA2_TOL.sqrt() * cbar.abs().max(1e-3) * k * k
        })
        .collect();
    let zero_runs = runs(&zero);
    let has_zero = !zero_runs.is_empty();
    for r in zero_runs {
        let zeros = vec![0.0; kappas.len()];
        let b = branch(Kind::RankDeficiency, &kappas, &zeros, r);
        inst.push(row(b, r, kappas.len()));
    }
    let semi_stable = !growing.iter().any(|&x| x);
    let integ = q.integrator;
    // the integrator's verdict (kdk: the leapfrog limit or bisection, as always)
    let (cdt, weak) = if integ == Integrator::Kdk {
        let d = semi_stable
            .then(|| critical_dt_given(&lin, &kappas, w2.iter().fold(0.0, |m, &x| m.max(x))))
            .transpose()?;
        (d, false)
    } else {
        let st = step_stability(&lin, &kappas, integ)?;
        (st.critical_dt.filter(|_| semi_stable), st.weak)
    };
    let cfl = cdt.map(|d| d / q.h_over_dx);
    let mut max_amp = None;
    let mut ts_unstable = false;
    let mut spurious = 0.0f64;
    if let Some(dt) = q.dt {
        let rho: Vec<f64> = kappas
            .iter()
            .map(|&k| spectral_radius_with(&lin, k, dt, integ))
            .collect::<Result<_>>()?;
        max_amp = Some(rho.iter().fold(0.0f64, |m, &x| m.max(x)));
        let flags: Vec<bool> = rho
            .iter()
            .zip(&growing)
            .map(|(&r, &gr)| !gr && r > 1.0 + AMPLIFICATION_TOL)
            .collect();
        let rate: Vec<f64> = rho.iter().map(|r| r.ln().max(0.0) / dt).collect();
        for r in runs(&flags) {
            ts_unstable = true;
            let kind = if weak {
                Kind::Integrator
            } else {
                Kind::TimeStep
            };
            let b = branch(kind, &kappas, &rate, r);
            spurious = spurious.max(b.growth_rate);
            inst.push(row(b, r, kappas.len()));
        }
    }
    // the largest growth over every row, time-step rows (growth per unit time ln|λ|/Δt) included,
    // so that the verdict line and the JSON agree with the rows
    let (mut gmax, mut kmax) = (0.0, None);
    for i in &inst {
        if i.growth_rate > GROWTH_TOL && i.growth_rate > gmax {
            gmax = i.growth_rate;
            kmax = Some(i.kappa_at_max.clone());
        }
    }
    let material = cbar <= 0.0;
    Ok(QueryReport {
        header: Header::of(q, 1.0),
        grid: q.grid,
        polarisation: (!semi_stable).then(|| Polarisation {
            vector: vec![1.0],
            longitudinal_fraction: 1.0,
        }),
        stable: semi_stable && !ts_unstable && !material,
        max_growth_rate: gmax,
        kappa_at_max: kmax,
        instabilities: inst,
        has_zero_energy_modes: has_zero,
        art_stress_kink: q.art_stress_kink(),
        critical_dt: cdt,
        critical_cfl: cfl,
        dt: q.dt,
        max_amplification: max_amp,
        integrator: integ.name(),
        spurious_growth_rate: spurious,
    })
}

/// The dispersion curve ω²(κ) at `points` κ in (0, π].
pub(super) fn dispersion<const D: usize>(q: &Query<D>, points: usize) -> Result<DispersionReport> {
    check_count("points", points, 2, super::query::max_path_points(1))?;
    let q = &Query { grid: points, ..*q };
    let lin = q.chain()?;
    let kappas = q.kappas();
    let (w2, g) = curve(&lin, &kappas)?;
    let cont = kappas
        .iter()
        .map(|k| vec![(1.0 + q.stress) * k * k])
        .collect();
    let (mut rate, mut ratio) = (None, None);
    if lin.is_dissipative() {
        let (mut r, mut x) = (Vec::with_capacity(kappas.len()), Vec::new());
        for (&k, &w) in kappas.iter().zip(&w2) {
            let s = branch_eigenvalues(&lin.eigenvalues(k)?, &[w])[0];
            r.push(vec![s.map(|s| s.re)]);
            x.push(vec![s.map(damping_ratio)]);
        }
        (rate, ratio) = (Some(r), Some(x));
    }
    Ok(DispersionReport {
        header: Header::of(q, 1.0),
        labels: vec![("Γ".into(), 0.0), ("X".into(), PI)],
        path: kappas.clone(),
        kappa: kappas.iter().map(|&k| vec![k]).collect(),
        omega2: w2.iter().map(|&w| vec![w]).collect(),
        growth_rate: g,
        omega2_continuum: cont,
        damping_rate: rate,
        damping_ratio: ratio,
    })
}

/// The critical time step of `q.integrator` (and its spurious growth at `q.dt`, default
/// 1/ω_max) over the κ grid of `q`.
pub(super) fn timestep<const D: usize>(q: &Query<D>) -> Result<TimestepReport> {
    let (integ, dt) = (q.integrator, q.dt);
    let lin = q.chain()?;
    super::work::check(
        q,
        &lin,
        q.kappa_sample(),
        q.modes(),
        super::work::Question::Timestep,
    )?;
    let kappas = q.kappas();
    let (w2, g) = curve(&lin, &kappas)?;
    let w2max = w2.iter().fold(0.0f64, |m, &x| m.max(x));
    let grows = g.iter().any(|&x| x > GROWTH_TOL);
    let from_w = if lin.is_dissipative() || grows || w2max == 0.0 {
        None
    } else {
        Some(leapfrog_limit(w2max))
    };
    if let Some(d) = dt {
        check_range("dt", d, 0.0, 1e6, false, true)?;
    }
    let eq120 = if lin.is_dissipative() && !grows {
        Some(critical_dt_eq120(&lin, &kappas)?).filter(|d| d.is_finite())
    } else {
        None
    };
    Ok(TimestepReport {
        header: Header::of(q, 1.0),
        grid: q.grid,
        critical_dt_from_omega_max: from_w,
        critical_dt_eq120: eq120,
        physical_growth_kind: None,
        critical_dt_inviscid: None,
        step: IntegratorReport::of(&lin, &kappas, integ, dt, q.h_over_dx)?,
    })
}
