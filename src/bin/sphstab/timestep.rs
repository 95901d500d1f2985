//! `sphstab timestep`.

use crate::common::Config;
use anyhow::Result;

/// Flags of `timestep`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// 1D: κ points in (0, π], in [2, 10000000] (2D uses --grid).
    #[arg(long)]
    points: Option<usize>,
    /// Print one JSON document instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<()> {
    if a.cfg.dt.is_some() {
        return Err(crate::query::not_in(
            "--dt",
            "timestep (it computes the critical Δt; check a given Δt with `query --dt`)",
        ));
    }
    let dim = a.cfg.dim()?;
    if dim > 1 {
        if a.points.is_some() {
            return Err(crate::query::not_in(
                "--points",
                &format!("--dim {dim} (use --grid for the zone sampling)"),
            ));
        }
        return if dim == 3 {
            run_nd::<3>(a)
        } else {
            run_nd::<2>(a)
        };
    }
    a.cfg.reject_2d_flags()?;
    let q = a.cfg.query(a.points.unwrap_or(512))?;
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

fn run_nd<const D: usize>(a: Args) -> Result<()> {
    let q = a.cfg.query_nd::<D>()?;
    let lin = q.linearise_at(q.stress)?;
    let ks = q.kgrid();
    let r = sphstab::analysis::query_nd(&q)?;
    let bis = if r.critical_dt.is_some() {
        Some(sphstab::vonneumann::amplification::critical_dt_bisection(
            &lin, &ks,
        )?)
    } else {
        None
    };
    let v = serde_json::json!({
        "dim": D, "form": r.setup.form, "kernel": r.setup.kernel, "h_over_dx": r.setup.h_over_dx,
        "support_over_dx": r.setup.support_over_dx, "stress": r.setup.stress, "critical_dt": bis,
        "critical_dt_from_omega_max": r.critical_dt,
        "critical_cfl": bis.map(|d| d / r.setup.h_over_dx),
    });
    if a.json {
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        match bis {
            Some(dt) => println!(
                "{} / {} h = {}Δx σ̄ = {} ({D}D, {}): critical leapfrog Δt = {dt:.9} Δx/c (bisection on the amplification matrices), 2/ω_max = {:.9}, CFL c Δt/h = {:.9}",
                r.setup.form,
                r.setup.kernel,
                r.setup.h_over_dx,
                r.setup.stress,
                r.lattice,
                r.critical_dt.unwrap_or(f64::NAN),
                dt / r.setup.h_over_dx
            ),
            None => println!(
                "no critical Δt: the semi-discrete system already grows (see `sphstab query --dim {D}`)"
            ),
        }
    }
    Ok(())
}
