//! `sphstab kernels`: the kernel table, and with `--table` the kernel guide
//! ([`sphstab::studies::kernel_guide`]).

use anyhow::{Result, bail};
use sphstab::budget::Budget;
use sphstab::studies::kernel_guide::{DEFAULT_H_STEP, GuideConfig, kernel_guide, markdown};

/// Flags of `kernels`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print one JSON document instead of a table.
    #[arg(long)]
    json: bool,
    /// The kernel guide: per kernel, critical CFL and phase error (kdk), the h/Δx stable in
    /// compression (1D, 2D), the tensile onset and the sign of W* (1D, 2D, 3D), all measured by
    /// the engine (Markdown; JSON with --json).
    #[arg(long)]
    table: bool,
    /// With --table: comma-separated kernel names (default: all eleven).
    #[arg(long, value_delimiter = ',')]
    kernels: Vec<String>,
    /// With --table: step of the h/Δx scans over [0.8, 6], in [0.01, 1] (default 0.05).
    #[arg(long)]
    h_step: Option<f64>,
}

fn guide(a: &Args) -> Result<()> {
    let mut cfg = GuideConfig {
        h_step: a.h_step.unwrap_or(DEFAULT_H_STEP),
        ..GuideConfig::default()
    };
    if !a.kernels.is_empty() {
        cfg.kernels = a
            .kernels
            .iter()
            .map(|k| sphstab::kernel::by_name(k))
            .collect::<sphstab::error::Result<_>>()?;
    }
    let g = kernel_guide(&cfg)?;
    if a.json {
        println!(
            "{}",
            sphstab::units::json(&g, sphstab::units::System::Normalised, false)?
        );
    } else {
        print!("{}", markdown(&g));
    }
    Ok(())
}

/// `_budget`: neither the kernel table nor the guide has work to bound (the guide's 2D columns
/// are closed forms, no linearised patch).
pub fn run(a: Args, _budget: &Budget) -> Result<()> {
    if a.table {
        return guide(&a);
    }
    if !a.kernels.is_empty() {
        bail!("--kernels applies to the kernel guide only: add --table");
    }
    if a.h_step.is_some() {
        bail!("--h-step applies to the kernel guide only: add --table");
    }
    let rows = sphstab::kernel::table();
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
