//! `sphstab dispersion`.

use crate::common::Config;
use anyhow::{Context, Result};

/// Flags of `dispersion`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// Number of κ points in (0, π] (≥ 2).
    #[arg(long, default_value_t = 256)]
    points: usize,
    /// Print one JSON document instead of a table.
    #[arg(long)]
    json: bool,
    /// Write an SVG plot of ω²Δx²/c² against κΔx/π to this file.
    #[arg(long)]
    plot: Option<std::path::PathBuf>,
}

pub fn run(a: Args) -> Result<()> {
    let q = a.cfg.query(a.points)?;
    let r = sphstab::analysis::dispersion(&q)?;
    if let Some(path) = &a.plot {
        let svg = sphstab::plot::dispersion_svg(&r)?;
        std::fs::write(path, svg)
            .with_context(|| format!("--plot: cannot write {}", path.display()))?;
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("# {}", r.header);
    println!(
        "{:>12} {:>16} {:>16} {:>14}",
        "κΔx/π", "ω²Δx²/c²", "continuum", "growth c/Δx"
    );
    for i in 0..r.kappa_dx.len() {
        println!(
            "{:>12.6} {:>16.9e} {:>16.9e} {:>14.6e}",
            r.kappa_dx[i] / std::f64::consts::PI,
            r.omega2[i],
            r.omega2_continuum[i],
            r.growth_rate[i]
        );
    }
    Ok(())
}
