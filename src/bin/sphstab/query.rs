//! `sphstab query`.

use crate::common::Config;
use anyhow::Result;

/// Flags of `query`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// Number of κ points in (0, π].
    #[arg(long, default_value_t = 512)]
    points: usize,
    /// Print one JSON document instead of a table.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<()> {
    let q = a.cfg.query(a.points)?;
    let r = sphstab::analysis::query(&q)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("{}", r.header);
    if r.stable {
        println!("verdict: STABLE (no exponentially growing mode)");
    } else {
        println!(
            "verdict: UNSTABLE — max growth rate {:.6} c/Δx at κΔx = {:.4}π",
            r.max_growth_rate,
            r.kappa_at_max.unwrap_or(0.0) / std::f64::consts::PI
        );
    }
    if r.instabilities.is_empty() {
        println!("no unstable or marginal branch");
    } else {
        println!(
            "{:<16} {:>12} {:>12} {:>14}",
            "kind", "κΔx/π min", "κΔx/π max", "growth (c/Δx)"
        );
        for i in &r.instabilities {
            let kind = serde_json::to_value(i.kind)?
                .as_str()
                .unwrap_or("?")
                .to_string();
            println!(
                "{:<16} {:>12.4} {:>12.4} {:>14.6}",
                kind,
                i.kappa_min / std::f64::consts::PI,
                i.kappa_max / std::f64::consts::PI,
                i.growth_rate
            );
        }
    }
    match (r.critical_dt, r.critical_cfl) {
        (Some(dt), Some(cfl)) => {
            println!("critical leapfrog Δt = {dt:.6} Δx/c  (CFL c Δt/h = {cfl:.6})")
        }
        _ => println!("critical Δt: not computed (the semi-discrete system grows)"),
    }
    if let (Some(dt), Some(a)) = (r.dt, r.max_amplification) {
        println!("at Δt = {dt} Δx/c: max |λ| = {a:.9}");
    }
    Ok(())
}
