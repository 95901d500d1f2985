//! Running the pairing study: one row per kernel × lattice × h/Δx × σ̄ (skipped, with the
//! reason, when over the memory budget or without neighbours), then the onsets.

use super::config::{PairingConfig, plan};
use super::report::{Onset, PairingReport, PairingRow};
use super::wstar;
use super::wstar::WStarSign;
use super::zone::{Scan, scan_k};
use crate::analysis::{MaterialSpec, Query};
use crate::budget::Budget;
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::kernel::Kernel;
use crate::lattice::Lattice;
use crate::progress::{Counter, Progress};
use crate::shape::ShapeFamily;
use crate::studies::shard::{Shard, Timing};
use crate::vonneumann::classify::GROWTH_TOL;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Particles within |r| < `r` (units Δx) of a lattice point, itself included.
pub fn neighbour_count(lat: &Lattice<3>, r: f64) -> usize {
    lat.offsets_within(r).len()
}

/// The 3D question of one row (classical, sph, hydro).
pub fn row_query(
    kernel: &'static dyn Kernel,
    lattice: Lattice<3>,
    h: f64,
    stress: f64,
    grid: usize,
) -> Query<3> {
    let mut q = Query::<3>::new(FormKind::Classical, kernel, h, stress);
    q.shape = ShapeFamily::Sph;
    q.material = MaterialSpec::Hydro;
    q.lattice = lattice;
    q.grid = grid;
    q
}

/// Computes one row: linearises once (within `budget`), scans the grid³ − 1 wave vectors of
/// the zone (rayon). Over the memory budget or with no neighbour in the support: a skipped row,
/// not an error.
pub fn evaluate_row(
    kernel: &'static dyn Kernel,
    lattice: (&str, Lattice<3>),
    h: f64,
    stress: f64,
    grid: usize,
    wstar_first_negative_k: Option<f64>,
    budget: &Budget,
) -> Result<PairingRow> {
    let r = kernel.zeta() * h;
    let n_h = neighbour_count(&lattice.1, r);
    let mut row = PairingRow {
        kernel: kernel.name().to_string(),
        lattice: lattice.0.to_string(),
        h_over_dx: h,
        support_over_dx: r,
        n_h,
        n_h_continuum: 4.0 / 3.0 * PI * r.powi(3),
        stress,
        skipped: None,
        max_growth_rate: None,
        kappa_at_max: None,
        kappa_abs_over_pi: None,
        longitudinal_fraction: None,
        pairing_growth_rate: None,
        pairing_kappa: None,
        transverse_growth_rate: None,
        transverse_kappa: None,
        max_asymmetry: None,
        wstar_first_negative_kdx: wstar_first_negative_k.map(|k| k / h),
    };
    if n_h <= 1 {
        row.skipped = Some(format!(
            "no neighbour inside the support (R = {r:.4}Δx, shorter than the nearest-neighbour distance)"
        ));
        return Ok(row);
    }
    let q = Query {
        budget: *budget,
        ..row_query(kernel, lattice.1, h, stress, grid)
    };
    let lin = match q.linearise_at(stress) {
        Ok(l) => l,
        Err(e @ Error::Budget { .. }) => {
            row.skipped = Some(e.to_string());
            return Ok(row);
        }
        Err(e) => return Err(e),
    };
    let scan = q
        .kgrid()
        .par_iter()
        .map(|&k| scan_k(&lin, k))
        .try_reduce(Scan::default, |x, y| Ok(x.merge(y)))?;
    let (all, long, trans) = (scan.all, scan.long, scan.trans);
    if !all.growth.is_finite() {
        return Err(Error::NonFinite("pairing growth rate"));
    }
    row.max_asymmetry = Some(scan.asymmetry);
    row.max_growth_rate = Some(all.rate());
    if all.grows() {
        row.kappa_at_max = Some(all.k);
        row.kappa_abs_over_pi = Some(all.k.iter().map(|c| c * c).sum::<f64>().sqrt() / PI);
        row.longitudinal_fraction = Some(all.lf);
    }
    row.pairing_growth_rate = Some(long.rate());
    row.pairing_kappa = long.grows().then_some(long.k);
    row.transverse_growth_rate = Some(trans.rate());
    row.transverse_kappa = trans.grows().then_some(trans.k);
    Ok(row)
}

/// Onsets per kernel × lattice × σ̄ from the rows (in row order: h ascending).
pub fn onsets(rows: &[PairingRow]) -> Vec<Onset> {
    let mut out: Vec<Onset> = Vec::new();
    for r in rows {
        let i = match out
            .iter()
            .position(|o| o.kernel == r.kernel && o.lattice == r.lattice && o.stress == r.stress)
        {
            Some(i) => i,
            None => {
                out.push(Onset {
                    kernel: r.kernel.clone(),
                    lattice: r.lattice.clone(),
                    stress: r.stress,
                    computed: 0,
                    skipped: 0,
                    h_max_computed: None,
                    first_growth: None,
                    first_pairing: None,
                    pairing_rows: 0,
                    max_pairing_growth: 0.0,
                });
                out.len() - 1
            }
        };
        let o = &mut out[i];
        if r.skipped.is_some() {
            o.skipped += 1;
            continue;
        }
        o.computed += 1;
        o.h_max_computed = Some(r.h_over_dx);
        if r.max_growth_rate.unwrap_or(0.0) > 0.0 && o.first_growth.is_none() {
            o.first_growth = Some((r.h_over_dx, r.n_h));
        }
        let p = r.pairing_growth_rate.unwrap_or(0.0);
        if p > 0.0 {
            o.pairing_rows += 1;
            o.max_pairing_growth = o.max_pairing_growth.max(p);
            if o.first_pairing.is_none() {
                o.first_pairing = Some((r.h_over_dx, r.n_h));
            }
        }
    }
    out
}

/// Computes the rows of `shard` (ascending, with their indices): one after the other, each
/// linearisation and wave-vector scan using the rayon pool, so memory stays within one row's
/// budget check; `progress` is told the fraction of the shard's rows done after each row.
pub(super) fn compute_rows(
    cfg: &PairingConfig,
    shard: Shard,
    progress: &dyn Progress,
) -> Result<Vec<(usize, PairingRow)>> {
    let plan = plan(cfg)?;
    let per_kernel = plan.lattices.len() * plan.h.len() * plan.stresses.len();
    let mine: Vec<usize> = (0..plan.rows()).filter(|&c| shard.owns(c)).collect();
    // the W* criterion of the kernels this shard has rows of
    let signs: Vec<Option<WStarSign>> = plan
        .kernels
        .par_iter()
        .enumerate()
        .map(|(ki, &k)| {
            mine.iter()
                .any(|&c| c / per_kernel == ki)
                .then(|| wstar::sign_criterion(k))
        })
        .collect();
    let done = Counter::new(progress, mine.len(), 1);
    let (nl, nh, ns) = (plan.lattices.len(), plan.h.len(), plan.stresses.len());
    let mut rows = Vec::with_capacity(mine.len());
    for c in mine {
        // c = ((kernel · lattices + lattice) · h values + h) · stresses + stress
        let (ki, li, hi, si) = (c / per_kernel, c / (nh * ns) % nl, c / ns % nh, c % ns);
        rows.push((
            c,
            evaluate_row(
                plan.kernels[ki],
                plan.lattices[li],
                plan.h[hi],
                plan.stresses[si],
                plan.grid,
                signs[ki].as_ref().and_then(|s| s.first_negative_k),
                &cfg.budget,
            )?,
        ));
        done.add(1)?;
    }
    Ok(rows)
}

/// The report from every row of the study (kernel × lattice × h × σ̄ order).
pub(super) fn assemble(
    cfg: &PairingConfig,
    rows: Vec<PairingRow>,
    timing: Timing,
) -> Result<PairingReport> {
    let plan = plan(cfg)?;
    let signs: Vec<WStarSign> = plan
        .kernels
        .par_iter()
        .map(|&k| wstar::sign_criterion(k))
        .collect();
    Ok(PairingReport {
        form: FormKind::Classical.name().into(),
        shape: ShapeFamily::Sph.name().into(),
        material: "hydro".into(),
        dx: "(volume per particle)^(1/3)".into(),
        grid: plan.grid,
        growth_tol: GROWTH_TOL,
        h_values: plan.h.clone(),
        stresses: plan.stresses.clone(),
        onsets: onsets(&rows),
        kernels: signs,
        rows,
        runtime_s: timing.runtime_s,
        threads: timing.threads,
    })
}

/// Runs the whole study ([`compute_rows`] of every row, then the W* criteria and the onsets);
/// `progress` is told the fraction of rows done after each row. Sharded:
/// [`PairingStudy`](super::PairingStudy).
pub fn run(cfg: &PairingConfig, progress: impl Progress) -> Result<PairingReport> {
    crate::studies::shard::run_whole(&super::PairingStudy, cfg, progress)
}
