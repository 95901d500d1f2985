//! The atlas report: its cells, the merge of shards and the summary `sphstab atlas` prints.

use super::check::check_stored;
use super::config::{AtlasConfig, Shard};
use crate::budget::Budget;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

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

/// Merges shards into the whole atlas: every shard checked against its configuration
/// ([`check_stored`], within `budget`'s memory), the same configuration in all, shard counts
/// equal, every shard index present exactly once (errors name the file, and the cell).
pub fn merge(parts: &[(String, AtlasReport)], budget: &Budget) -> Result<AtlasReport> {
    let Some((first_name, first)) = parts.first() else {
        return Err(Error::Incompatible("merge: no shard files given".into()));
    };
    for (name, r) in parts {
        check_stored(name, r, budget)?;
    }
    let count = first.shard.map_or(1, |s| s.count);
    let mut seen = vec![None::<&str>; count];
    let mut cells = Vec::with_capacity(first.total_cells);
    let mut runtime = 0.0;
    for (name, r) in parts {
        if r.config != first.config {
            return Err(Error::Incompatible(
                format!(
                    "merge: {name} was computed with a different configuration than {first_name}"
                )
                .into(),
            ));
        }
        let s = r.shard.unwrap_or(Shard { index: 0, count: 1 });
        if s.count != count {
            return Err(Error::Incompatible(
                format!(
                    "merge: {name} is shard {}/{} but {first_name} is one of {count}",
                    s.index, s.count
                )
                .into(),
            ));
        }
        if let Some(other) = seen[s.index] {
            return Err(Error::Incompatible(
                format!(
                    "merge: shard {}/{count} given twice ({other} and {name})",
                    s.index
                )
                .into(),
            ));
        }
        seen[s.index] = Some(name);
        runtime += r.runtime_s;
        cells.extend(r.cells.iter().cloned());
    }
    if let Some(missing) = seen.iter().position(|s| s.is_none()) {
        return Err(Error::Incompatible(
            format!("merge: shard {missing}/{count} is missing").into(),
        ));
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
