//! Computing the kernel guide: per kernel, the critical CFL and phase errors, the h/Δx intervals
//! stable in compression (1D, 2D), the tensile onset and the W* sign.

use super::compression::{compression_scan, query_1d};
use super::config::{
    COMPRESSION, GRID_2D, GUIDE_FORMS, GUIDE_H, GuideConfig, MAX_SUPPORT_2D, ONSET_BISECTIONS,
    REFERENCE_TENSION, SAFETY, SCAN_H, TENSION_CAP, TENSION_FLOOR, WSTAR_K_MAX, WSTAR_K_STEP,
};
use super::report::{KernelGuide, KernelGuideRow, Positivity, TensileOnset, TimeStepCell};
use crate::analysis::Query;
use crate::error::Result;
use crate::forms::FormKind;
use crate::integrator::Integrator;
use crate::kernel::Kernel;
use crate::studies::pairing::wstar_scan::sign_criterion_fast;
use crate::studies::tradeoff::cfl::CFL_POINTS;
use crate::studies::tradeoff::integrators::{IntegratorRow, analyse};
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::linearise::Linearisation;
use rayon::prelude::*;

/// The time-step cell of `form` at `h`: [`analyse`] of the trade-off study at [`CFL_POINTS`] κ
/// points, whose critical Δt is the `timestep` code path of [`crate::studies::tradeoff::cfl::cfl_cell`]
/// (`IntegratorReport::of` on the same linearisation and κ grid; CFL = Δt_crit/h as there —
/// `tests/it/kernel_guide.rs` checks the two agree bit for bit).
pub fn time_step_cell(form: FormKind, k: &'static dyn Kernel, h: f64) -> Result<TimeStepCell> {
    let mut row = IntegratorRow::default();
    analyse(form, k, h, Integrator::Kdk, SAFETY, CFL_POINTS, &mut row)?;
    let q = Query::<1>::new(form, k, h, 0.0);
    q.validate()?;
    Ok(TimeStepCell {
        form: form.name().into(),
        shape: q.shape.name().into(),
        h_over_dx: h,
        support_over_dx: k.zeta() * h,
        critical_dt: row.critical_dt,
        critical_cfl: row.critical_dt.map(|d| d / h),
        dt_used: row.dt_used,
        phase_error_10ppw: row.phase_error_10ppw,
        phase_error_20ppw: row.phase_error_20ppw,
        amplitude_error_10ppw: row.amplitude_error_10ppw,
        amplitude_error_20ppw: row.amplitude_error_20ppw,
    })
}

/// The largest growth rate (c/Δx) of 1D classical SPH ([`query_1d`]: `sph` shapes, elastic
/// bar, [`KAPPAS_1D`](super::KAPPAS_1D) κ points) at σ̄, by the engine (the chain
/// linearisation).
pub fn max_growth_1d(k: &'static dyn Kernel, h: f64, stress: f64) -> Result<f64> {
    let q = query_1d(k, h, stress);
    let lin: Linearisation = q.chain()?;
    let mut g: f64 = 0.0;
    for kap in q.kappas() {
        g = g.max(lin.growth(kap)?);
    }
    Ok(g)
}

/// Whether [`max_growth_1d`] exceeds [`GROWTH_TOL`].
pub fn grows_1d(k: &'static dyn Kernel, h: f64, stress: f64) -> Result<bool> {
    Ok(max_growth_1d(k, h, stress)? > GROWTH_TOL)
}

/// The tensile onset of 1D classical SPH at `h`: growth at [`TENSION_FLOOR`] means `any`;
/// otherwise the trade-off study's scan and bisection ([`ONSET_BISECTIONS`] steps) up to
/// [`TENSION_CAP`].
pub fn tensile_onset(k: &'static dyn Kernel, h: f64) -> Result<TensileOnset> {
    let g = max_growth_1d(k, h, REFERENCE_TENSION)?;
    let growth_at_reference = if g > GROWTH_TOL { g } else { 0.0 };
    let grows = |s: f64| grows_1d(k, h, s);
    if grows(TENSION_FLOOR)? {
        return Ok(TensileOnset {
            h_over_dx: h,
            kind: "any".into(),
            onset: Some(TENSION_FLOOR),
            last_stable: Some(0.0),
            growth_at_reference,
        });
    }
    let (lo, hi) = crate::studies::tradeoff::tension_limit(
        TENSION_CAP,
        ONSET_BISECTIONS,
        TENSION_FLOOR,
        grows,
    )?;
    Ok(match hi {
        Some(s) => TensileOnset {
            h_over_dx: h,
            kind: "onset".into(),
            onset: Some(s),
            last_stable: Some(lo),
            growth_at_reference,
        },
        None => TensileOnset {
            h_over_dx: h,
            kind: "none".into(),
            onset: None,
            last_stable: Some(lo),
            growth_at_reference,
        },
    })
}

/// One kernel's row.
pub fn kernel_row(k: &'static dyn Kernel, h_grid: &[f64]) -> Result<KernelGuideRow> {
    let mut ts_jobs = Vec::new();
    for f in GUIDE_FORMS {
        for h in GUIDE_H {
            ts_jobs.push((FormKind::by_name(f)?, h));
        }
    }
    let time_step = ts_jobs
        .par_iter()
        .map(|&(f, h)| time_step_cell(f, k, h))
        .collect::<Result<Vec<_>>>()?;
    let compression = [1u8, 2]
        .par_iter()
        .map(|&d| compression_scan(k, d, h_grid))
        .collect::<Result<Vec<_>>>()?;
    let tension = GUIDE_H
        .par_iter()
        .map(|&h| tensile_onset(k, h))
        .collect::<Result<Vec<_>>>()?;
    let positivity = [1u8, 2, 3]
        .par_iter()
        .map(|&d| Positivity {
            dim: d,
            sign: sign_criterion_fast(k, d as usize, WSTAR_K_STEP),
        })
        .collect();
    Ok(KernelGuideRow {
        kernel: k.name().into(),
        zeta: k.zeta(),
        time_step,
        compression,
        tension,
        positivity,
    })
}

/// The guide (kernels in parallel).
pub fn kernel_guide(cfg: &GuideConfig) -> Result<KernelGuide> {
    cfg.validate()?;
    let h = cfg.h_grid();
    let rows = cfg
        .kernels
        .par_iter()
        .map(|&k| kernel_row(k, &h))
        .collect::<Result<Vec<_>>>()?;
    Ok(KernelGuide {
        integrator: Integrator::Kdk.name().into(),
        kappa_points: CFL_POINTS,
        safety: SAFETY,
        h_values: GUIDE_H.to_vec(),
        h_step: cfg.h_step,
        scan_h: SCAN_H,
        compression_stress: COMPRESSION,
        grid_2d: GRID_2D,
        max_support_2d: MAX_SUPPORT_2D,
        growth_tol: GROWTH_TOL,
        wstar_k_max: WSTAR_K_MAX,
        rows,
    })
}
