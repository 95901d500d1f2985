//! `sphstab timestep`.

use crate::common::{Config, IntegratorArgs};
use anyhow::Result;
use sphstab::analysis::IntegratorReport;
use sphstab::budget::Budget;

/// Flags of `timestep`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// 1D: κ points in (0, π], in [2, 10000000] (default 512); the same as --grid.
    #[arg(long)]
    points: Option<usize>,
    #[command(flatten)]
    integ: IntegratorArgs,
    /// Print one JSON document instead of text.
    #[arg(long)]
    json: bool,
}

/// The integrator part of the text output.
fn print_step(s: &IntegratorReport) {
    let name = match s.euler_every {
        Some(n) => format!("{} (N_s = {n})", s.integrator),
        None => s.integrator.to_string(),
    };
    let closed = s
        .critical_dt_closed_form
        .map(|v| format!("{v:.9}"))
        .unwrap_or_else(|| "n/a".into());
    match s.critical_dt {
        Some(dt) if dt.is_finite() => println!(
            "critical Δt ({name}) = {dt:.9} Δx/c (bisection on the amplification matrices); closed form {closed}; CFL c Δt/h = {:.9}",
            s.critical_cfl.unwrap_or(f64::NAN)
        ),
        Some(_) => println!("critical Δt ({name}): none (no Δt up to 1e6 amplifies)"),
        None if s.weak_instability => println!(
            "critical Δt ({name}): none — weak instability (integrator): it amplifies every non-growing mode at any Δt"
        ),
        None => {
            println!("no critical Δt: the semi-discrete system already grows (see `sphstab query`)")
        }
    }
    println!(
        "spurious growth ({name}) at Δt = {:.6} Δx/c: {:.6e} c/Δx",
        s.spurious_growth_dt, s.spurious_growth_rate
    );
}

/// The \[B00\] eq 120 line of a dissipative system.
fn print_eq120(v: Option<f64>) {
    if let Some(v) = v {
        println!("[B00] eq 120 (ω, ξ per mode): Δt ≤ {v:.9} Δx/c");
    }
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let dim = a.cfg.dim()?;
    crate::by_dim!(dim, run_in(a, budget))
}

fn run_in<const D: usize>(mut a: Args, budget: &Budget) -> Result<()> {
    a.cfg.grid = crate::query::points_as_grid(D as u8, a.points, a.cfg.grid)?;
    let mut q = a.cfg.query::<D>(budget)?;
    q.integrator = a.integ.integrator()?;
    let r = sphstab::analysis::timestep(&q)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("{}", r.header);
    println!("ω_max = {:.9} c/Δx", r.step.omega_max);
    match r.critical_dt_from_omega_max {
        Some(v) => println!("leapfrog limit 2/ω_max = {v:.9} Δx/c"),
        None if r.critical_dt_eq120.is_some() => {
            println!("dissipative: no 2/ω_max limit")
        }
        None => {}
    }
    print_eq120(r.critical_dt_eq120);
    print_step(&r.step);
    Ok(())
}
