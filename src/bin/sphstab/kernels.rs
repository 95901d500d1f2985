//! `sphstab kernels`.

use anyhow::Result;
use serde::Serialize;

/// Flags of `kernels`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print one JSON document instead of a table.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Row {
    name: &'static str,
    zeta: f64,
    sigma_1: f64,
    sigma_2: f64,
    sigma_3: f64,
    inflection_1d: f64,
    inflection_2d: f64,
    customary_h: (f64, f64),
    reference: &'static str,
}

pub fn run(a: Args) -> Result<()> {
    let rows: Vec<Row> = sphstab::kernel::all()
        .iter()
        .map(|k| Row {
            name: k.name(),
            zeta: k.zeta(),
            sigma_1: k.sigma(1),
            sigma_2: k.sigma(2),
            sigma_3: k.sigma(3),
            inflection_1d: k.inflection(1),
            inflection_2d: k.inflection(2),
            customary_h: k.customary_h(),
            reference: k.reference(),
        })
        .collect();
    if a.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(());
    }
    println!(
        "{:<12} {:>5} {:>12} {:>12} {:>12} {:>9} {:>9} {:>12}  reference",
        "name", "ζ", "σ_1", "σ_2", "σ_3", "q* (1D)", "q* (2D)", "h/Δx range"
    );
    for r in rows {
        println!(
            "{:<12} {:>5} {:>12.8} {:>12.8} {:>12.8} {:>9.6} {:>9.6} {:>5}–{:<6}  {}",
            r.name,
            r.zeta,
            r.sigma_1,
            r.sigma_2,
            r.sigma_3,
            r.inflection_1d,
            r.inflection_2d,
            r.customary_h.0,
            r.customary_h.1,
            r.reference
        );
    }
    Ok(())
}
