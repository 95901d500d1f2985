//! `sphstab query`.

use crate::common::Config;
use anyhow::Result;
use sphstab::budget::Budget;

/// Flags of `query`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    #[command(flatten)]
    integ: crate::common::IntegratorArgs,
    /// 1D: number of κ points in (0, π], in [2, 10000000] (default 512).
    #[arg(long)]
    points: Option<usize>,
    /// Print one JSON document instead of a table.
    #[arg(long)]
    json: bool,
    /// 2D/3D: also predict the growth a box of N^D free particles between fixed layers can
    /// show (standing modes k = (m_1, …, m_D)π/(N+1)), N in [1, 1000] (3D: [1, 100]).
    #[arg(long = "box")]
    box_free: Option<usize>,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let dim = a.cfg.dim()?;
    if dim > 1 {
        if a.points.is_some() {
            return Err(not_in(
                "--points",
                &format!("--dim {dim} (use --grid for the zone sampling)"),
            ));
        }
        return if dim == 3 {
            run_nd::<3>(a, budget)
        } else {
            run_nd::<2>(a, budget)
        };
    }
    a.cfg.reject_2d_flags()?;
    if a.box_free.is_some() {
        return Err(not_in("--box", "--dim 1 (it predicts a 2D or 3D box)"));
    }
    let mut q = a.cfg.query(a.points.unwrap_or(512))?;
    q.integrator = a.integ.integrator()?;
    let r = sphstab::analysis::query(&q)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("{}", r.header);
    if r.stable {
        println!("verdict: STABLE (no exponentially growing mode)");
    } else {
        let kinds: Vec<String> = r
            .instabilities
            .iter()
            .filter(|i| i.kind != sphstab::vonneumann::classify::Kind::RankDeficiency)
            .map(|i| kind_name(i.kind))
            .fold(Vec::new(), |mut v, k| {
                if !v.contains(&k) {
                    v.push(k);
                }
                v
            });
        match r.kappa_at_max {
            Some(k) => println!(
                "verdict: UNSTABLE ({}) — max growth rate {:.6} c/Δx at κΔx = {:.4}π",
                kinds.join(", "),
                r.max_growth_rate,
                k / std::f64::consts::PI
            ),
            None => println!(
                "verdict: UNSTABLE ({}) — no exponential growth on the grid (marginal)",
                kinds.join(", ")
            ),
        }
    }
    if r.instabilities.is_empty() {
        println!("no unstable or marginal branch");
    } else {
        println!(
            "{:<16} {:>12} {:>12} {:>14}",
            "kind", "κΔx/π min", "κΔx/π max", "growth (c/Δx)"
        );
        for i in &r.instabilities {
            println!(
                "{:<16} {:>12.4} {:>12.4} {:>14.6}{}",
                kind_name(i.kind),
                i.kappa_min / std::f64::consts::PI,
                i.kappa_max / std::f64::consts::PI,
                i.growth_rate,
                i.pole_at
                    .map(|p| format!(
                        "  (ω² passes a pole at κΔx ≈ {:.4}π: the mass symbol vanishes)",
                        p / std::f64::consts::PI
                    ))
                    .unwrap_or_default()
            );
        }
    }
    match (r.critical_dt, r.critical_cfl) {
        (Some(dt), Some(cfl)) => println!(
            "critical {} Δt = {dt:.6} Δx/c  (CFL c Δt/h = {cfl:.6})",
            integrator_words(r.integrator)
        ),
        _ => println!("{}", no_critical(r.integrator)),
    }
    if let (Some(dt), Some(a)) = (r.dt, r.max_amplification) {
        println!("at Δt = {dt} Δx/c: max |λ| = {a:.9}");
    }
    Ok(())
}

/// A wave vector in units of π: "(0.1234π, 0.5000π)".
pub fn fmt_k(k: &[f64]) -> String {
    let parts: Vec<String> = k
        .iter()
        .map(|c| format!("{:.4}π", c / std::f64::consts::PI))
        .collect();
    format!("({})", parts.join(", "))
}

fn run_nd<const D: usize>(a: Args, budget: &Budget) -> Result<()> {
    let mut q = a.cfg.query_nd::<D>(budget)?;
    q.integrator = a.integ.integrator()?;
    if let Some(n) = a.box_free {
        sphstab::params::check_count("box", n, 1, sphstab::analysis::max_box(D))?;
    }
    let r = sphstab::analysis::query_nd(&q)?;
    let boxp = match a.box_free {
        Some(n) => Some(sphstab::analysis::box_prediction(
            &q.linearise_at(q.stress)?,
            n,
        )?),
        None => None,
    };
    if a.json {
        let mut v = serde_json::to_value(&r)?;
        if let Some((g, k)) = boxp {
            v["box_free_particles"] = serde_json::json!(a.box_free);
            v["box_growth_rate"] = serde_json::json!(g);
            v["box_kappa"] = serde_json::json!(k.to_vec());
        }
        println!("{}", serde_json::to_string_pretty(&v)?);
        return Ok(());
    }
    if let Some((g, k)) = boxp {
        println!(
            "box of {}^{D} free particles: predicted growth {g:.6} c/Δx at κΔx = {}",
            a.box_free.unwrap_or(0),
            fmt_k(&k)
        );
    }
    println!(
        "{}, {}, {} (nearest neighbour {:.4}Δx), first zone sampled {}^{D}",
        r.setup, r.material, r.lattice, r.nearest_neighbour_over_dx, r.grid
    );
    let kinds2: Vec<String> = r
        .instabilities
        .iter()
        .filter(|i| i.kind != sphstab::vonneumann::classify::Kind::RankDeficiency)
        .map(|i| kind_name(i.kind))
        .collect();
    match (r.stable, &r.kappa_at_max, &r.polarisation) {
        (true, _, _) => println!("verdict: STABLE (no exponentially growing mode)"),
        (false, Some(k), Some(p)) => println!(
            "verdict: UNSTABLE ({}) — max growth rate {:.6} c/Δx at κΔx = {}, polarisation ({}), longitudinal fraction {:.3}",
            kinds2.join(", "),
            r.max_growth_rate,
            fmt_k(k),
            p.vector
                .iter()
                .map(|c| format!("{c:.3}"))
                .collect::<Vec<_>>()
                .join(", "),
            p.longitudinal_fraction
        ),
        _ => println!("verdict: UNSTABLE (time-step: max |λ| > 1 at the given --dt)"),
    }
    for i in &r.instabilities {
        println!(
            "{:<16} growth {:.6} c/Δx at κΔx = {}, {:.1}% of the zone",
            kind_name(i.kind),
            i.growth_rate,
            fmt_k(&i.kappa_at_max),
            100.0 * i.zone_fraction
        );
    }
    match r.critical_dt {
        Some(dt) => println!(
            "critical {} Δt = {dt:.6} Δx/c (CFL c Δt/h = {:.6})",
            integrator_words(r.integrator),
            dt / r.setup.h_over_dx
        ),
        None => println!("{}", no_critical(r.integrator)),
    }
    if let (Some(dt), Some(m)) = (r.dt, r.max_amplification) {
        println!("at Δt = {dt} Δx/c: max |λ| = {m:.9}");
    }
    Ok(())
}

/// The error for a flag that does not apply here.
pub fn not_in(flag: &str, context: &str) -> anyhow::Error {
    sphstab::error::Error::Incompatible(format!("{flag} does not apply with {context}").into())
        .into()
}

/// The kebab-case name of an instability kind (as in the JSON).
pub fn kind_name(k: sphstab::vonneumann::classify::Kind) -> String {
    serde_json::to_value(k)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

/// "leapfrog" for the default kick–drift–kick, else the integrator's name.
fn integrator_words(name: &str) -> &str {
    if name == "kdk" { "leapfrog" } else { name }
}

/// The line printed when there is no critical Δt.
fn no_critical(integrator: &str) -> String {
    if integrator == "kdk" {
        "critical Δt: not computed (the semi-discrete system grows)".into()
    } else {
        format!(
            "critical {integrator} Δt: none (the semi-discrete system grows, or {integrator} amplifies at every Δt: see `timestep --integrator {integrator}`)"
        )
    }
}
