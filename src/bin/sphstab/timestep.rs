//! `sphstab timestep`.

use crate::common::Config;
use anyhow::Result;

/// Flags of `timestep`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// Number of κ points in (0, π].
    #[arg(long, default_value_t = 512)]
    points: usize,
    /// Print one JSON document instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<()> {
    let q = a.cfg.query(a.points)?;
    let r = sphstab::analysis::timestep(&q)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("{}", r.header);
    println!("ω_max = {:.9} c/Δx", r.omega_max);
    match r.critical_dt {
        Some(dt) => println!(
            "critical leapfrog Δt = {:.9} Δx/c (bisection on the amplification matrices); 2/ω_max = {}; CFL c Δt/h = {:.9}",
            dt,
            r.critical_dt_from_omega_max
                .map(|v| format!("{v:.9}"))
                .unwrap_or_else(|| "n/a".into()),
            r.critical_cfl.unwrap_or(f64::NAN)
        ),
        None => {
            println!("no critical Δt: the semi-discrete system already grows (see `sphstab query`)")
        }
    }
    Ok(())
}
