//! The 1D stability atlas (`sphstab atlas`): every form × kernel × h/Δx × σ̄ cell, each the
//! largest growth rate over κΔx ∈ (0, π] (the engine's [`crate::vonneumann::linearise::Linearisation`]),
//! computed in parallel (rayon) and splittable into shards for a batch system's job array:
//! cell `c` (in the fixed order form, kernel, h, σ̄) belongs to shard `c mod n`; `merge` checks
//! that the shards share one configuration and cover 0..n exactly once.

use crate::analysis::Query1D;
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::kernel::{self, Kernel};
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::linearise::{Linearisation, PhaseTable, has_consistent_mass};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The sweep.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AtlasConfig {
    /// Form names (all ten by default).
    pub forms: Vec<String>,
    /// Kernel names (all eleven by default).
    pub kernels: Vec<String>,
    /// h/Δx values per kernel, evenly over its customary range.
    pub h_points: usize,
    /// σ̄ values, evenly over `stress_range` (ends included).
    pub stress_points: usize,
    /// σ̄ range.
    pub stress_range: (f64, f64),
    /// κΔx points in (0, π].
    pub kappas: usize,
}

impl Default for AtlasConfig {
    fn default() -> Self {
        Self {
            forms: FormKind::ALL.iter().map(|f| f.1.to_string()).collect(),
            kernels: kernel::all().iter().map(|k| k.name().to_string()).collect(),
            h_points: 64,
            stress_points: 64,
            stress_range: (-0.5, 0.5),
            kappas: 512,
        }
    }
}

/// One shard of n (0 ≤ index < count).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
pub struct Shard {
    /// This shard.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// Parses `i/n` (0 ≤ i < n ≤ 100000).
    pub fn parse(s: &str) -> Result<Self> {
        let bad = || {
            Error::Incompatible(format!(
                "--shard '{s}': must be i/n with integers 0 ≤ i < n ≤ 100000 (e.g. 0/8)"
            ))
        };
        let (a, b) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (usize, usize) = (
            a.trim().parse().map_err(|_| bad())?,
            b.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || count > 100_000 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

/// One cell of the atlas.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct Cell {
    /// Position in the full sweep.
    pub index: usize,
    /// Form.
    pub form: String,
    /// Kernel.
    pub kernel: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// σ̄.
    pub stress: f64,
    /// No mode grows (γ ≤ 1e-6 c/Δx at every κ).
    pub stable: bool,
    /// Largest growth rate (c/Δx).
    pub max_growth_rate: f64,
    /// κΔx of the largest growth rate (null if stable).
    pub kappa_at_max: Option<f64>,
    /// Why the cell could not be computed (e.g. a singular MLS moment matrix).
    pub error: Option<String>,
}

/// An atlas (or one shard of it).
#[derive(Clone, Debug, Deserialize, Serialize)]
pub struct AtlasReport {
    /// The sweep.
    pub config: AtlasConfig,
    /// The shard (null: the whole sweep, or merged shards).
    pub shard: Option<Shard>,
    /// Cells in the full sweep.
    pub total_cells: usize,
    /// Worker threads.
    pub threads: usize,
    /// Wall-clock seconds (sum over shards after a merge).
    pub runtime_s: f64,
    /// The cells of this shard, in sweep order.
    pub cells: Vec<Cell>,
}

/// One cell's parameters: (form, kernel, h/Δx, σ̄).
pub type CellSpec = (FormKind, &'static dyn Kernel, f64, f64);

/// The validated grid in sweep order.
pub fn grid(cfg: &AtlasConfig) -> Result<Vec<CellSpec>> {
    for (name, v, lo, hi) in [
        ("--h-points", cfg.h_points, 1, 4096),
        ("--stress-points", cfg.stress_points, 1, 4096),
        ("--kappas", cfg.kappas, 2, 1_000_000),
    ] {
        if v < lo || v > hi {
            return Err(Error::OutOfRange {
                name,
                value: v as f64,
                range: format!("must be an integer in [{lo}, {hi}]"),
            });
        }
    }
    let (s0, s1) = cfg.stress_range;
    crate::error::check_range("--stress-min", s0, -0.999, 10.0, true, true)?;
    crate::error::check_range("--stress-max", s1, s0, 10.0, true, true)?;
    let forms: Vec<FormKind> = cfg
        .forms
        .iter()
        .map(|f| FormKind::by_name(f))
        .collect::<Result<_>>()?;
    let kernels: Vec<&'static dyn Kernel> = cfg
        .kernels
        .iter()
        .map(|k| kernel::by_name(k))
        .collect::<Result<_>>()?;
    let lin = |lo: f64, hi: f64, n: usize, i: usize| {
        if n == 1 {
            0.5 * (lo + hi)
        } else {
            lo + (hi - lo) * i as f64 / (n - 1) as f64
        }
    };
    // resources before the grid is built (crate::budget): the cell list, results and their
    // JSON text (~400 B per cell), and the κ-evaluations, which cost ~0.3 µs each on 2 threads
    // (66 s for the full 450,560 × 512 atlas) and are checked against 10 × --max-steps
    let cells = (forms.len() * kernels.len()) as f64 * (cfg.h_points * cfg.stress_points) as f64;
    crate::budget::check_memory(
        "--h-points/--stress-points",
        &format!("the atlas ({} cells)", crate::budget::fmt_count(cells)),
        cells * 400.0 + 64.0 * cfg.kappas as f64 * 16.0,
    )?;
    let evals = cells * cfg.kappas as f64;
    let b = crate::budget::current();
    b.work(
        "--h-points/--stress-points/--kappas",
        &format!("the atlas ({} cells)", crate::budget::fmt_count(cells)),
        evals,
        "κ-evaluations",
        10.0 * b.max_steps,
    )?;
    let mut out = Vec::new();
    for &f in &forms {
        for &k in &kernels {
            let (hlo, hhi) = k.customary_h();
            for ih in 0..cfg.h_points {
                let h = lin(hlo, hhi, cfg.h_points, ih);
                for is in 0..cfg.stress_points {
                    out.push((f, k, h, lin(s0, s1, cfg.stress_points, is)));
                }
            }
        }
    }
    Ok(out)
}

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
        let mut q = Query1D::new(form, k, h, s);
        q.points = points;
        q.linearise()
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

/// Computes the atlas (or one shard), calling `progress(done, total)` as cells finish.
pub fn run(
    cfg: &AtlasConfig,
    shard: Option<Shard>,
    progress: impl Fn(usize, usize) + Sync,
) -> Result<AtlasReport> {
    let all = grid(cfg)?;
    let total_cells = all.len();
    // the σ̄ grid (the same for every form, kernel and h: the innermost loop of the sweep)
    let sgrid: Vec<f64> = all[..cfg.stress_points].iter().map(|c| c.3).collect();
    let mine: Vec<(usize, _)> = all
        .into_iter()
        .enumerate()
        .filter(|(i, _)| shard.is_none_or(|s| i % s.count == s.index))
        .collect();
    let start = std::time::Instant::now();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let n = mine.len();
    // one κ grid for every cell (Query1D::kappas), its phase factors tabulated once per thread
    let mut q = Query1D::new(FormKind::Classical, kernel::by_name("m4")?, 1.0, 0.0);
    q.points = cfg.kappas;
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
    let cells: Vec<Cell> = groups
        .into_par_iter()
        .map_init(
            || PhaseTable::new(&kappas, 0),
            |table, g| {
                let out = group(g, &sgrid, table);
                let d = done.fetch_add(out.len(), std::sync::atomic::Ordering::Relaxed) + out.len();
                if d / 256 != (d - out.len()) / 256 || d == n {
                    progress(d, n);
                }
                out
            },
        )
        .flatten()
        .collect();
    Ok(AtlasReport {
        config: cfg.clone(),
        shard,
        total_cells,
        threads: rayon::current_num_threads(),
        runtime_s: start.elapsed().as_secs_f64(),
        cells,
    })
}

/// The work the atlas cannot avoid: for every cell, one Fourier term per κ point per lattice
/// neighbour inside the kernel support (offsets j ≠ 0 with |j|Δx < R = ζh). At the 1 ns a term
/// costs (a multiply-add with a tabulated phase and the loop around it), this many
/// nanoseconds of CPU is the "lattice-sum limit" the README compares the atlas with; it
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

/// Merges shards into the whole atlas: same configuration, shard counts equal, every shard
/// index present exactly once (errors name the file).
pub fn merge(parts: &[(String, AtlasReport)]) -> Result<AtlasReport> {
    let Some((first_name, first)) = parts.first() else {
        return Err(Error::Incompatible("merge: no shard files given".into()));
    };
    let count = first.shard.map_or(1, |s| s.count);
    let mut seen = vec![None::<&str>; count];
    let mut cells = Vec::with_capacity(first.total_cells);
    let mut runtime = 0.0;
    for (name, r) in parts {
        if r.config != first.config {
            return Err(Error::Incompatible(format!(
                "merge: {name} was computed with a different configuration than {first_name}"
            )));
        }
        let s = r.shard.unwrap_or(Shard { index: 0, count: 1 });
        if s.count != count {
            return Err(Error::Incompatible(format!(
                "merge: {name} is shard {}/{} but {first_name} is one of {count}",
                s.index, s.count
            )));
        }
        if let Some(other) = seen[s.index] {
            return Err(Error::Incompatible(format!(
                "merge: shard {}/{count} given twice ({other} and {name})",
                s.index
            )));
        }
        seen[s.index] = Some(name);
        runtime += r.runtime_s;
        cells.extend(r.cells.iter().cloned());
    }
    if let Some(missing) = seen.iter().position(|s| s.is_none()) {
        return Err(Error::Incompatible(format!(
            "merge: shard {missing}/{count} is missing"
        )));
    }
    cells.sort_by_key(|c| c.index);
    if cells.len() != first.total_cells || cells.iter().enumerate().any(|(i, c)| c.index != i) {
        return Err(Error::Incompatible(
            "merge: the shards do not add up to the whole sweep".into(),
        ));
    }
    Ok(AtlasReport {
        config: first.config.clone(),
        shard: None,
        total_cells: first.total_cells,
        threads: first.threads,
        runtime_s: runtime,
        cells,
    })
}

/// Summary table: per form × kernel, the fraction of stable cells in tension (σ̄ > 0) and in
/// compression (σ̄ < 0), the largest growth rate, and cells with errors.
pub fn summary(r: &AtlasReport) -> String {
    let mut s = format!(
        "{:<24} {:<12} {:>10} {:>10} {:>10} {:>7}\n",
        "form", "kernel", "stable σ̄>0", "stable σ̄<0", "max γ", "errors"
    );
    let mut i = 0;
    let cells = &r.cells;
    while i < cells.len() {
        let (f, k) = (&cells[i].form, &cells[i].kernel);
        let mut j = i;
        let (mut tp, mut tn, mut sp, mut sn, mut err, mut gmax) = (0, 0, 0, 0, 0, 0.0f64);
        while j < cells.len() && &cells[j].form == f && &cells[j].kernel == k {
            let c = &cells[j];
            if c.error.is_some() {
                err += 1;
            } else if c.stress > 0.0 {
                tp += 1;
                sp += c.stable as usize;
            } else if c.stress < 0.0 {
                tn += 1;
                sn += c.stable as usize;
            }
            gmax = gmax.max(c.max_growth_rate);
            j += 1;
        }
        let pct = |a: usize, b: usize| {
            if b == 0 {
                "-".to_string()
            } else {
                format!("{:.1}%", 100.0 * a as f64 / b as f64)
            }
        };
        s += &format!(
            "{:<24} {:<12} {:>10} {:>10} {:>10.4} {:>7}\n",
            f,
            k,
            pct(sp, tp),
            pct(sn, tn),
            gmax,
            err
        );
        i = j;
    }
    s
}
