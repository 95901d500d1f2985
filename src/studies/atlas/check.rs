//! A stored atlas (a shard file before `merge`) checked against its own configuration: a merged
//! atlas is data that users keep, so a file whose cells do not fit the sweep its `config`
//! describes is refused, naming the file and the cell, instead of being merged.
//!
//! What is checked: the configuration itself (the ranges of [`super::grid`]), the shard
//! (0 ≤ index < count ≤ 100000), `total_cells`, `threads` and `runtime_s`, and every cell: its
//! index (in the sweep, in this shard, increasing), its form, kernel, h/Δx and σ̄ (exactly those
//! of the sweep at that index; JSON numbers read back bit for bit), its growth rate (finite, in
//! [0, [`MAX_GROWTH_RATE`]], zero exactly when it is stable), and its κΔx (a point of the κ
//! grid, present exactly when the cell grows). A changed growth rate that is still plausible
//! cannot be told from a computed one without computing it again.

use super::config::{AtlasConfig, Shard, grid};
use super::report::{AtlasReport, Cell};
use crate::budget::Budget;
use crate::display::num;
use crate::error::{Error, Result};
use crate::vonneumann::classify::GROWTH_TOL;
use std::f64::consts::PI;

/// Largest growth rate (c/Δx) a stored cell may hold. The largest over every form, kernel and
/// h/Δx of the atlas at σ̄ up to 10 (the top of `stress_range`) is ≈ 22 (eulerian-nodal,
/// mollifier, h = 1.5Δx, σ̄ = 10, at κΔx = π); a rate 450 times that is not the engine's.
pub const MAX_GROWTH_RATE: f64 = 1e4;

/// Largest `runtime_s` of a stored atlas (≈ 30 years).
pub const MAX_RUNTIME_S: f64 = 1e9;

/// Checks the atlas `r`, read from `file` (module docs); the sweep is rebuilt within `budget`'s
/// memory (the κ-evaluations are not done again, so their limit does not apply).
pub fn check_stored(file: &str, r: &AtlasReport, budget: &Budget) -> Result<()> {
    let bad = |msg: String| Error::Config {
        file: file.to_string(),
        msg,
    };
    let cfg = AtlasConfig {
        budget: Budget {
            max_memory: budget.max_memory,
            max_steps: f64::INFINITY,
        },
        ..r.config.clone()
    };
    let sweep = grid(&cfg).map_err(|e| bad(format!("config: {e}")))?;
    let shard = r.shard.unwrap_or(Shard { index: 0, count: 1 });
    if shard.count == 0 || shard.count > 100_000 || shard.index >= shard.count {
        return Err(bad(format!(
            "shard {}/{}: must be i/n with integers 0 ≤ i < n ≤ 100000",
            shard.index, shard.count
        )));
    }
    if r.total_cells != sweep.len() {
        return Err(bad(format!(
            "total_cells = {}, but its config has {} cells",
            r.total_cells,
            sweep.len()
        )));
    }
    if r.threads == 0 {
        return Err(bad("threads = 0: must be at least 1".into()));
    }
    if !(r.runtime_s.is_finite() && (0.0..=MAX_RUNTIME_S).contains(&r.runtime_s)) {
        return Err(bad(format!(
            "runtime_s = {} is out of range: must be a finite number in [0, {}]",
            num(r.runtime_s),
            num(MAX_RUNTIME_S)
        )));
    }
    let expected = sweep
        .len()
        .saturating_sub(shard.index)
        .div_ceil(shard.count);
    if r.cells.len() != expected {
        return Err(bad(format!(
            "{} cells, but shard {}/{} of {} cells has {expected}",
            r.cells.len(),
            shard.index,
            shard.count,
            sweep.len()
        )));
    }
    let mut last = None;
    for (j, c) in r.cells.iter().enumerate() {
        let cell_err = |what: String| bad(format!("cells[{j}] (index {}): {what}", c.index));
        if c.index >= sweep.len() || c.index % shard.count != shard.index {
            return Err(cell_err(format!(
                "not a cell of shard {}/{} of {} cells",
                shard.index,
                shard.count,
                sweep.len()
            )));
        }
        if last.is_some_and(|l| c.index <= l) {
            return Err(cell_err(
                "cells must be in increasing index order, each once".into(),
            ));
        }
        last = Some(c.index);
        let (form, kernel, h, s) = sweep[c.index];
        if c.form != form.name() {
            return Err(cell_err(format!(
                "form `{}`, but its config puts {} there",
                c.form,
                form.name()
            )));
        }
        if c.kernel != kernel.name() {
            return Err(cell_err(format!(
                "kernel `{}`, but its config puts {} there",
                c.kernel,
                kernel.name()
            )));
        }
        for (field, v, want) in [("h_over_dx", c.h_over_dx, h), ("stress", c.stress, s)] {
            if v.to_bits() != want.to_bits() {
                return Err(cell_err(format!(
                    "{field} = {}, but its config puts {} there",
                    num(v),
                    num(want)
                )));
            }
        }
        check_result(c, r.config.kappas).map_err(cell_err)?;
    }
    Ok(())
}

/// The computed part of a cell: growth rate, stability and κΔx consistent with each other and
/// with the κ grid of `kappas` points (a cell with an `error` stopped part-way: its rate and
/// κΔx are partial, and it is not stable).
fn check_result(c: &Cell, kappas: usize) -> std::result::Result<(), String> {
    let g = c.max_growth_rate;
    if !(g.is_finite() && (0.0..=MAX_GROWTH_RATE).contains(&g)) {
        return Err(format!(
            "max_growth_rate = {} is out of range: must be a finite number in [0, {}] (c/Δx)",
            num(g),
            num(MAX_GROWTH_RATE)
        ));
    }
    if let Some(k) = c.kappa_at_max {
        let i = (k * kappas as f64 / PI).round();
        let on_grid = k.is_finite()
            && (1.0..=kappas as f64).contains(&i)
            && (PI * i / kappas as f64).to_bits() == k.to_bits();
        if !on_grid {
            return Err(format!(
                "kappa_at_max = {} is not a point πk/{kappas} (k = 1..{kappas}) of its κ grid",
                num(k)
            ));
        }
    }
    let growing = c.kappa_at_max.is_some();
    if c.error.is_some() {
        if c.stable {
            return Err("stable = true with an error: a cell that failed is not stable".into());
        }
        return Ok(());
    }
    if c.stable == growing {
        return Err(format!(
            "stable = {} with kappa_at_max {}: a cell grows exactly when it has a κΔx of largest growth",
            c.stable,
            if growing { "given" } else { "null" }
        ));
    }
    if growing && g <= GROWTH_TOL {
        return Err(format!(
            "max_growth_rate = {} with a kappa_at_max: growth is a rate above {}",
            num(g),
            num(GROWTH_TOL)
        ));
    }
    if !growing && g != 0.0 {
        return Err(format!(
            "max_growth_rate = {} in a stable cell: must be 0",
            num(g)
        ));
    }
    Ok(())
}
