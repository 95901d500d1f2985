//! Computing the atlas: the cells of one shard in parallel, grouped so that cells affine in σ̄
//! share one linearisation.

use super::config::{AtlasConfig, CellSpec, Sweep};
use super::report::{AtlasReport, Cell};
use super::shard::AtlasStudy;
use crate::analysis::Query;
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::kernel;
use crate::progress::{Counter, Progress};
use crate::studies::shard::{Shard, run_whole};
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::linearise::{Linearisation, PhaseTable, has_consistent_mass};
use rayon::prelude::*;

/// Two linearisations' Jacobian columns count as equal below this relative difference
/// ([`Linearisation::distance`]); interpolation in σ̄ reproduces an affine dependence to a few
/// units of rounding (~1e-16).
pub const AFFINE_TOL: f64 = 1e-13;

/// The cells of one (form, kernel, h/Δx) in this shard, at σ̄ values of the sweep's σ̄ grid
/// `sgrid`. The pre-stress enters the rate functions linearly, so the Jacobian columns are
/// affine in σ̄: with five or more σ̄ values the group is linearised directly at four probes of
/// the grid (first, 1/3, 2/3, last), the affine interpolation between first and last is checked
/// against the two interior probes, and only if both agree to [`AFFINE_TOL`] are the other
/// cells interpolated ([`Linearisation::lerp`]); otherwise (and for the consistent-mass form)
/// every cell is linearised directly. Probes and decision depend on the grid, not on the
/// shard, so sharded atlases merge bit-identical to the unsharded one.
fn group(cells: &[(usize, CellSpec)], sgrid: &[f64], table: &mut PhaseTable) -> Vec<Cell> {
    let points = table.kappas().len();
    let (form, k, h, _) = cells[0].1;
    let lin = |s: f64| {
        let mut q = Query::<1>::new(form, k, h, s);
        q.grid = points;
        q.chain()
    };
    let n = sgrid.len();
    let mut probes: Vec<(f64, Result<Linearisation>)> = Vec::new();
    let mut affine = None;
    // not for a consistent mass: near κ = π its symbol M̂(κ) nearly vanishes and the growth
    // there changes at O(1) with a rounding-level change of the columns (pre-existing
    // ill-conditioning), so those cells keep their exact direct linearisation
    if n >= 5 && !has_consistent_mass(form) {
        probes = [0, n / 3, 2 * n / 3, n - 1]
            .iter()
            .map(|&i| (sgrid[i], lin(sgrid[i])))
            .collect();
        if let [(_, Ok(la)), (s1, Ok(l1)), (s2, Ok(l2)), (_, Ok(lb))] = &probes[..] {
            let t = |s: f64| (s - sgrid[0]) / (sgrid[n - 1] - sgrid[0]);
            let ok = |l: &Linearisation, s: f64| {
                la.lerp(lb, t(s))
                    .and_then(|m| m.distance(l))
                    .is_some_and(|d| d <= AFFINE_TOL)
            };
            if ok(l1, *s1) && ok(l2, *s2) {
                affine = Some((la.clone(), lb.clone()));
            }
        }
    }
    cells
        .iter()
        .map(|&c| {
            let s = c.1.3;
            let probe = probes.iter().find(|p| p.0.to_bits() == s.to_bits());
            let l = match (probe, &affine) {
                (Some((_, l)), _) => l.clone(),
                (None, Some((la, lb))) => {
                    let t = (s - sgrid[0]) / (sgrid[n - 1] - sgrid[0]);
                    la.lerp(lb, t).ok_or(Error::NonFinite("σ̄ interpolation"))
                }
                (None, None) => lin(s),
            };
            evaluate(c, l, table)
        })
        .collect()
}

/// One cell from its linearisation: the largest growth over the κ grid of `table` (the cosine
/// series of ω² where the form has one, the tabulated Jacobian otherwise).
fn evaluate(
    (index, (form, k, h, s)): (usize, CellSpec),
    lin: Result<Linearisation>,
    table: &mut PhaseTable,
) -> Cell {
    let mut c = Cell {
        index,
        form: form.name().into(),
        kernel: k.name().into(),
        h_over_dx: h,
        stress: s,
        stable: false,
        max_growth_rate: 0.0,
        kappa_at_max: None,
        error: None,
    };
    let res = (|| -> Result<()> {
        let lin = lin?;
        table.ensure(lin.reach());
        let series = lin.cosine_series();
        for (i, &kap) in table.kappas().iter().enumerate() {
            let g = match &series {
                Some(cs) => (-cs.omega2(table, i)).max(0.0).sqrt(),
                None => lin.growth_tabulated(table, i)?,
            };
            if !g.is_finite() {
                return Err(Error::NonFinite("growth rate"));
            }
            if g > GROWTH_TOL && g > c.max_growth_rate {
                c.max_growth_rate = g;
                c.kappa_at_max = Some(kap);
            }
        }
        c.stable = c.kappa_at_max.is_none();
        Ok(())
    })();
    if let Err(e) = res {
        c.error = Some(e.to_string());
    }
    c
}

/// Computes the cells `shard` owns, ascending, each with its index, telling `progress` the
/// fraction finished.
pub(super) fn compute_cells(
    cfg: &AtlasConfig,
    shard: Shard,
    progress: &dyn Progress,
) -> Result<Vec<(usize, Cell)>> {
    let sweep = Sweep::new(cfg)?;
    // the σ̄ grid (the same for every form, kernel and h: the innermost loop of the sweep)
    let sgrid: Vec<f64> = (0..cfg.stress_points).map(|i| sweep.stress(i)).collect();
    let mine: Vec<(usize, CellSpec)> = (0..sweep.len())
        .filter(|&i| shard.owns(i))
        .map(|i| (i, sweep.cell(i)))
        .collect();
    let done = Counter::new(progress, mine.len(), 256);
    // one κ grid for every cell (Query::kappas), its phase factors tabulated once per thread
    let mut q = Query::<1>::new(FormKind::Classical, kernel::by_name("m4")?, 1.0, 0.0);
    q.grid = cfg.kappas;
    let kappas = q.kappas();
    // cells of one (form, kernel, h) are consecutive in sweep order
    let mut groups: Vec<&[(usize, CellSpec)]> = Vec::new();
    let same = |a: &CellSpec, b: &CellSpec| a.0 == b.0 && std::ptr::addr_eq(a.1, b.1) && a.2 == b.2;
    let mut rest = &mine[..];
    while let Some(first) = rest.first() {
        let len = rest.iter().take_while(|c| same(&c.1, &first.1)).count();
        groups.push(&rest[..len]);
        rest = &rest[len..];
    }
    Ok(groups
        .into_par_iter()
        .map_init(
            || PhaseTable::new(&kappas, 0),
            |table, g| -> Result<Vec<Cell>> {
                let out = group(g, &sgrid, table);
                done.add(out.len())?;
                Ok(out)
            },
        )
        .collect::<Result<Vec<_>>>()?
        .into_iter()
        .flatten()
        .map(|c| (c.index, c))
        .collect())
}

/// Computes the whole atlas, telling `progress` the fraction of cells finished (one shard of
/// one: [`crate::studies::shard::run_whole`]).
pub fn run(cfg: &AtlasConfig, progress: impl Progress) -> Result<AtlasReport> {
    run_whole(&AtlasStudy, cfg, progress)
}

/// The work the atlas cannot avoid: for every cell, one Fourier term per κ point per lattice
/// neighbour inside the kernel support (offsets j ≠ 0 with |j|Δx < R = ζh). At the 1 ns a term
/// costs (a multiply-add with a tabulated phase and the loop around it), this many
/// nanoseconds of CPU is the "lattice-sum limit" docs/benchmarks.md compares the atlas with; it
/// ignores the linearisation of each cell and the reduction to ω².
pub fn lattice_sum_terms(rep: &AtlasReport) -> f64 {
    rep.cells
        .iter()
        .map(|c| {
            let r = kernel::by_name(&c.kernel).map_or(0.0, |k| k.zeta() * c.h_over_dx);
            // integers 0 < |j| < r
            let n = 2.0 * (r.ceil() - 1.0).max(0.0);
            n * rep.config.kappas as f64
        })
        .sum()
}
