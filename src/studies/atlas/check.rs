//! A stored cell (in a shard file, before `merge`) checked against the configuration: a merged
//! atlas is data that users keep, so a cell that does not fit the sweep its configuration
//! describes is refused, naming the file and the cell, instead of being merged (the study's
//! [`crate::studies::shard::Sharded::check_cell`]; the shard, the cell indices, `total_cells`,
//! `threads` and `runtime_s` are checked for every study by [`crate::studies::shard::merge`]).
//!
//! What is checked of every cell: its `index` (the cell's own), its form, kernel, h/Δx and σ̄
//! (exactly those of the sweep at that index; JSON numbers read back bit for bit), its growth
//! rate (finite, in [0, [`MAX_GROWTH_RATE`]], zero exactly when it is stable), and its κΔx (a
//! point of the κ grid, present exactly when the cell grows). A changed growth rate that is
//! still plausible cannot be told from a computed one without computing it again.

use super::config::Sweep;
use super::report::Cell;
use crate::display::num;
use crate::error::Text;
use crate::vonneumann::classify::GROWTH_TOL;
use std::f64::consts::PI;

/// Largest growth rate (c/Δx) a stored cell may hold. The largest over every form, kernel and
/// h/Δx of the atlas at σ̄ up to 10 (the top of `stress_range`) is ≈ 22 (eulerian-nodal,
/// mollifier, h = 1.5Δx, σ̄ = 10, at κΔx = π); a rate 450 times that is not the engine's.
pub const MAX_GROWTH_RATE: f64 = 1e4;

/// Checks the stored cell `c`, cell `index` (< `sweep.len()`) of `sweep` with a κ grid of
/// `kappas` points (module docs).
pub fn check_cell(
    sweep: &Sweep,
    kappas: usize,
    index: usize,
    c: &Cell,
) -> std::result::Result<(), Text> {
    if c.index != index {
        return Err(format!("holds `index` {}: not this cell's", c.index).into());
    }
    let (form, kernel, h, s) = sweep.cell(index);
    for (field, v, want) in [
        ("form", &c.form, form.name()),
        ("kernel", &c.kernel, kernel.name()),
    ] {
        if v != want {
            return Err(format!("{field} `{v}`, but its configuration puts {want} there").into());
        }
    }
    for (field, v, want) in [("h_over_dx", c.h_over_dx, h), ("stress", c.stress, s)] {
        if v.to_bits() != want.to_bits() {
            return Err(format!(
                "{field} = {}, but its configuration puts {} there",
                num(v),
                num(want)
            )
            .into());
        }
    }
    check_result(c, kappas).map_err(Text::from)
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
