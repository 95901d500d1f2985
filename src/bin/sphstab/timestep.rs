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

/// A number as people read it: plain notation from 1e-4 to 1e6 with 6 significant digits
/// (trailing zeros dropped), scientific outside, `0` for zero.
pub fn plain(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if (1e-4..1e6).contains(&a) {
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        let t = format!("{x:.decimals$}");
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        }
    } else {
        format!("{x:.3e}")
    }
}

/// The integrator part of the text output.
fn print_step(s: &IntegratorReport) {
    let name = match s.euler_every {
        Some(n) => format!("{} (N_s = {n})", s.integrator),
        None => s.integrator.to_string(),
    };
    let closed = s
        .critical_dt_closed_form
        .map(plain)
        .unwrap_or_else(|| "n/a".into());
    match s.critical_dt {
        Some(dt) if dt.is_finite() => println!(
            "critical Δt ({name}) = {} Δx/c, CFL c Δt/h = {} (largest Δt that adds no growth: |λ| ≤ 1 + 1e-7 per step on modes that do not grow, growth rate within 1% of the physical one on modes that do; bisection on the amplification matrices); closed form {closed}",
            plain(dt),
            plain(s.critical_cfl.unwrap_or(f64::NAN))
        ),
        Some(_) => println!("critical Δt ({name}): none (no Δt up to 1e6 adds growth)"),
        None => println!(
            "critical Δt ({name}): none — weak instability (integrator): it amplifies every non-growing mode at any Δt"
        ),
    }
    let at = plain(s.spurious_growth_dt);
    match s.added_growth_kind {
        Some("time-step") => println!(
            "time-step instability ({name}) at Δt = {at} Δx/c: adds growth {} c/Δx",
            plain(s.spurious_growth_rate)
        ),
        Some(_) => println!(
            "integrator (weak) instability ({name}) at Δt = {at} Δx/c: adds growth {} c/Δx",
            plain(s.spurious_growth_rate)
        ),
        None => println!("at Δt = {at} Δx/c ({name}) adds no growth"),
    }
}

/// The \[B00\] eq 120 line of a dissipative system.
fn print_eq120(v: Option<f64>) {
    if let Some(v) = v {
        println!("[B00] eq 120 (ω, ξ per mode): Δt ≤ {} Δx/c", plain(v));
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
    print!("ω_max = {} c/Δx", plain(r.step.omega_max));
    match r.step.decay_rate_max {
        Some(d) => println!(" (oscillation), largest decay rate {} c/Δx", plain(d)),
        None => println!(),
    }
    if r.step.physical_growth_rate > 0.0 {
        let kind = r
            .physical_growth_kind
            .and_then(|k| serde_json::to_value(k).ok())
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_else(|| "growth".into());
        println!(
            "physical growth: {} c/Δx ({kind}; the semi-discrete system grows at every Δt: `sphstab query` says where)",
            plain(r.step.physical_growth_rate)
        );
    }
    match r.critical_dt_from_omega_max {
        Some(v) => println!("leapfrog limit 2/ω_max = {} Δx/c", plain(v)),
        None if r.critical_dt_eq120.is_some() => {
            println!("dissipative: no 2/ω_max limit")
        }
        None => {}
    }
    print_eq120(r.critical_dt_eq120);
    print_step(&r.step);
    if let Some(d) = r.critical_dt_inviscid {
        println!(
            "viscosity: the analysis applies it to every pair (two-sided); codes switch it off for receding pairs, and their measured limits lay between this Δt and the inviscid one, {} Δx/c",
            plain(d)
        );
    }
    Ok(())
}
