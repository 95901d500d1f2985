//! The atlas report: its cells and the summary `sphstab atlas` prints (its JSON's `units` are
//! the CLI's, from the one table of every report's units).

use super::config::AtlasConfig;
use crate::studies::shard::Timing;
use serde::{Deserialize, Serialize};

/// One cell of the atlas.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Cell {
    /// Position in the full sweep.
    pub index: usize,
    /// Form.
    pub form: String,
    /// Kernel.
    pub kernel: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// σ̄ = σ/C (positive in tension).
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

/// The atlas: every cell of the sweep.
#[derive(Clone, Debug, Serialize)]
pub struct AtlasReport {
    /// The sweep.
    pub config: AtlasConfig,
    /// Cells in the sweep.
    pub total_cells: usize,
    /// Worker threads (after a merge: the first shard's).
    pub threads: usize,
    /// Wall-clock seconds (after a merge: the sum over the shards).
    pub runtime_s: f64,
    /// The cells, in sweep order.
    pub cells: Vec<Cell>,
}

/// The report from every cell of the sweep, in index order.
pub(super) fn assemble(cfg: &AtlasConfig, cells: Vec<Cell>, timing: Timing) -> AtlasReport {
    AtlasReport {
        config: cfg.clone(),
        total_cells: cells.len(),
        threads: timing.threads,
        runtime_s: timing.runtime_s,
        cells,
    }
}

/// Summary table: per form × kernel, the fraction of stable cells in tension (σ̄ > 0) and in
/// compression (σ̄ < 0), the largest growth rate, and cells with errors.
pub fn summary(r: &AtlasReport) -> String {
    let mut s = String::from(
        "units: growth rate γ in c/Δx, h in Δx, κ in 1/Δx, σ̄ = σ/C (positive in tension)\n",
    );
    s += &format!(
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
