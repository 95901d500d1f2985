//! The atlas's config (the flags of `sphstab atlas`): forms, kernels, the h/Δx × σ̄ grid, the κ
//! points and the shard, checked field by field, and the list of cells it gives.

use crate::budget::{Budget, fmt_count};
use crate::error::{Error, Result, field, fields};
use crate::forms::FormKind;
use crate::kernel::{self, Kernel};
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
    /// The budget the sweep must stay within (not part of the report).
    #[serde(skip)]
    pub budget: Budget,
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
            budget: Budget::default(),
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
            Error::Incompatible(
                field("shard")
                    + format!(" '{s}': must be i/n with integers 0 ≤ i < n ≤ 100000 (e.g. 0/8)"),
            )
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

/// One cell's parameters: (form, kernel, h/Δx, σ̄).
pub type CellSpec = (FormKind, &'static dyn Kernel, f64, f64);

/// The validated grid in sweep order.
pub fn grid(cfg: &AtlasConfig) -> Result<Vec<CellSpec>> {
    for (field, v, lo, hi) in [
        ("h_points", cfg.h_points, 1, 4096),
        ("stress_points", cfg.stress_points, 1, 4096),
        ("kappas", cfg.kappas, 2, 1_000_000),
    ] {
        if v < lo || v > hi {
            return Err(Error::OutOfRange {
                field,
                value: v as f64,
                range: format!("must be an integer in [{lo}, {hi}]").into(),
            });
        }
    }
    let (s0, s1) = cfg.stress_range;
    crate::error::check_range("stress_range[0]", s0, -0.999, 10.0, true, true)?;
    crate::error::check_range("stress_range[1]", s1, s0, 10.0, true, true)?;
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
    // resources before the grid is built (the budget): the cell list, results and their JSON
    // text (~400 B per cell), and the κ-evaluations, which cost ~0.3 µs each on 2 threads (66 s
    // for the full 450,560 × 512 atlas) and are checked against 10 × max_steps
    let cells = (forms.len() * kernels.len()) as f64 * (cfg.h_points * cfg.stress_points) as f64;
    let b = &cfg.budget;
    b.memory(
        fields(&["h_points", "stress_points"]),
        &format!("the atlas ({} cells)", fmt_count(cells)),
        cells * 400.0 + 64.0 * cfg.kappas as f64 * 16.0,
    )?;
    let evals = cells * cfg.kappas as f64;
    b.work(
        fields(&["h_points", "stress_points", "kappas"]),
        &format!("the atlas ({} cells)", fmt_count(cells)),
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
