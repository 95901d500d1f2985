//! `sphstab timestep`.

use crate::common::{Config, IntegratorArgs};
use anyhow::Result;
use sphstab::analysis::IntegratorReport;
use sphstab::budget::Budget;
use sphstab::integrator::Integrator;

/// Flags of `timestep`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// 1D: κ points in (0, π], in [2, 10000000] (2D uses --grid).
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
    let integ = a.integ.integrator()?;
    let dim = a.cfg.dim()?;
    if dim > 1 {
        if a.points.is_some() {
            return Err(crate::query::not_in(
                "--points",
                &format!("--dim {dim} (use --grid for the zone sampling)"),
            ));
        }
        return if dim == 3 {
            run_nd::<3>(a, integ, budget)
        } else {
            run_nd::<2>(a, integ, budget)
        };
    }
    a.cfg.reject_2d_flags()?;
    let q = a.cfg.query(a.points.unwrap_or(512))?;
    let r = sphstab::analysis::timestep_with(&q, integ, a.cfg.dt)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("{}", r.header);
    println!("ω_max = {:.9} c/Δx", r.step.omega_max);
    if let Some(v) = r.critical_dt_from_omega_max {
        println!("leapfrog limit 2/ω_max = {v:.9} Δx/c");
    }
    print_eq120(r.critical_dt_eq120);
    print_step(&r.step);
    Ok(())
}

fn run_nd<const D: usize>(a: Args, integ: Integrator, budget: &Budget) -> Result<()> {
    let q = a.cfg.query_nd::<D>(budget)?;
    let lin = q.linearise_at(q.stress)?;
    let ks = q.kgrid();
    let r = sphstab::analysis::query_nd(&q)?;
    if let Some(d) = a.cfg.dt {
        sphstab::error::check_range("--dt", d, 0.0, 1e6, false, true)?;
    }
    let grows = r.critical_dt.is_none();
    let step = IntegratorReport::of(&lin, &ks, integ, a.cfg.dt, r.setup.h_over_dx, grows)?;
    let eq120 = if lin.is_dissipative() && !grows {
        Some(sphstab::vonneumann::damping::critical_dt_eq120(&lin, &ks)?).filter(|d| d.is_finite())
    } else {
        None
    };
    // 2/ω_max is the leapfrog limit of a non-dissipative system only (the query's critical Δt
    // is found by bisection otherwise, and reported as `critical_dt`)
    let from_omega_max = if lin.is_dissipative() {
        None
    } else {
        r.critical_dt
    };
    let mut v = serde_json::json!({
        "dim": D, "form": r.setup.form, "kernel": r.setup.kernel, "h_over_dx": r.setup.h_over_dx,
        "support_over_dx": r.setup.support_over_dx, "stress": r.setup.stress,
        "critical_dt_from_omega_max": from_omega_max,
    });
    if let (Some(m), serde_json::Value::Object(s)) =
        (v.as_object_mut(), serde_json::to_value(&step)?)
    {
        m.extend(s);
        if let Some(d) = eq120 {
            m.insert("critical_dt_eq120".into(), d.into());
        }
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        println!(
            "{} / {} h = {}Δx σ̄ = {} ({D}D, {}): ω_max = {:.9} c/Δx{}",
            r.setup.form,
            r.setup.kernel,
            r.setup.h_over_dx,
            r.setup.stress,
            r.lattice,
            step.omega_max,
            match (from_omega_max, r.critical_dt) {
                (Some(v), _) => format!(", leapfrog limit 2/ω_max = {v:.9}"),
                (None, Some(_)) => " (dissipative: no 2/ω_max limit)".into(),
                (None, None) => ", leapfrog limit 2/ω_max = n/a".into(),
            },
        );
        print_eq120(eq120);
        print_step(&step);
    }
    Ok(())
}
