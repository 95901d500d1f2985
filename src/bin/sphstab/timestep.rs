//! `sphstab timestep`.

use crate::common::{Config, IntegratorArgs};
use anyhow::Result;
use sphstab::analysis::IntegratorReport;
use sphstab::budget::Budget;
use sphstab::studies::stable_dt::{self, ProbeRun, StableDtReport};
use sphstab::units::{self, System};

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
    /// Also measure the largest stable Δt in the time domain: the same solver on a periodic
    /// body of the lattice (64 particles in 1D), Δt bisected to 1% (wall time: seconds in 1D,
    /// up to minutes in 3D; budget --max-steps).
    #[arg(long)]
    verify: bool,
    /// Which pairs the viscosity of the --verify runs acts on: one-sided (approaching pairs
    /// only, as SPH codes apply it; default) or two-sided (every pair, as the analysis
    /// linearises it). Needs --verify and --av-alpha.
    #[arg(long)]
    viscosity: Option<String>,
    /// Print one JSON document instead of text (its "units" name the unit of every field).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    vary: crate::vary::VaryArgs,
}

/// A result as people read it: 6 significant digits ([`sphstab::display::num_sig`]).
fn plain(x: f64) -> String {
    sphstab::display::num_sig(x, 6)
}

/// The integrator part of the text output.
fn print_step(s: &IntegratorReport) {
    let name = match s.euler_every {
        Some(n) => format!("{} (N_s = {n})", s.integrator),
        None => s.integrator.to_string(),
    };
    let closed = s
        .critical_dt_closed_form
        .map_or_else(|| "n/a".into(), |d| format!("{} Δx/c", plain(d)));
    match s.critical_dt {
        Some(dt) if dt.is_finite() => println!(
            "critical Δt ({name}) = {} Δx/c, CFL c Δt/h = {} (largest Δt that adds no growth: |λ| ≤ 1 + 1e-7 per step on modes that do not grow, growth rate within 1% of the physical one on modes that do; bisection on the amplification matrices); closed form {closed}",
            plain(dt),
            s.critical_cfl.map_or("n/a".into(), plain)
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
    a.cfg
        .spec()
        .check_for(sphstab::analysis::spec::Command::Timestep { verify: a.verify })?;
    let dim = a.cfg.dim()?;
    crate::by_dim!(dim, run_in(a, budget))
}

fn run_in<const D: usize>(mut a: Args, budget: &Budget) -> Result<()> {
    a.cfg.grid = crate::query::points_as_grid(D as u8, a.points, a.cfg.grid)?;
    if crate::vary::active(&a.cfg, &a.vary) {
        if a.verify {
            return Err(crate::query::not_in(
                "--verify",
                "--vary or a list (measure one configuration at a time)",
            ));
        }
        return compare::<D>(&a, budget);
    }
    let mut q = a.cfg.query::<D>(budget)?;
    q.integrator = a.integ.integrator()?;
    let pairs = stable_dt::viscosity_pairs(a.verify, a.viscosity.as_deref(), q.av.is_some())?;
    // in 1D the κ points are --points or --grid: the budget names the one given
    let r = sphstab::analysis::timestep(&q)
        .map_err(|e| crate::flags::alias(e, "grid", "--points", a.points.is_some()))?;
    let verified = if a.verify {
        let pb = crate::progress::Bar::new(crate::progress::wanted(a.json));
        let v = sphstab::studies::stable_dt::stable_dt(&q, pairs, &pb)?;
        pb.finish();
        Some(v)
    } else {
        None
    };
    if a.json {
        let mut doc = serde_json::to_value(&r)?;
        if let (Some(v), Some(map)) = (&verified, doc.as_object_mut()) {
            map.insert("verify".into(), serde_json::to_value(v)?);
        }
        println!("{}", units::json(&doc, System::Normalised, true)?);
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
            "viscosity: the analysis applies it to every pair (two-sided); codes switch it off for receding pairs, which --verify measures (for schemes stable without viscosity that limit lies between this Δt and the inviscid one, {} Δx/c)",
            plain(d)
        );
    }
    if let Some(v) = &verified {
        print_verify(v);
    }
    Ok(())
}

/// `--vary` / lists: every question checked first, then answered; a table (or JSON
/// `{"series": [{"label", "timestep"}]}`).
fn compare<const D: usize>(a: &Args, budget: &Budget) -> Result<()> {
    if a.viscosity.is_some() {
        return Err(crate::query::not_in(
            "--viscosity",
            "timestep without --verify",
        ));
    }
    let list = crate::vary::series(&a.cfg, &a.vary, true)?;
    let questions = crate::vary::questions::<D>(&list, &a.integ, budget)?;
    let reports = questions
        .iter()
        .map(sphstab::analysis::timestep)
        .collect::<sphstab::error::Result<Vec<_>>>()?;
    if a.json {
        let series: Vec<serde_json::Value> = list
            .iter()
            .zip(&reports)
            .map(|(s, r)| serde_json::json!({"label": s.label, "timestep": r}))
            .collect();
        let doc = serde_json::json!({ "series": series });
        println!("{}", units::json(&doc, System::Normalised, true)?);
        return Ok(());
    }
    println!(
        "{} questions side by side; the first: {}",
        list.len(),
        reports[0].header
    );
    let width = list
        .iter()
        .map(|s| s.label.chars().count())
        .max()
        .unwrap_or(6)
        .max(6);
    println!(
        "{:<width$}  {:<20}  {:>18}  {:>14}  {:>22}  {:>18}",
        "series",
        "integrator",
        "critical Δt Δx/c",
        "ω_max c/Δx",
        "physical growth c/Δx",
        "inviscid Δt Δx/c"
    );
    for (s, r) in list.iter().zip(&reports) {
        let st = &r.step;
        let dt = match st.critical_dt {
            Some(d) => plain(d),
            None => "none (weak)".into(),
        };
        let growth = match (st.physical_growth_rate > 0.0, r.physical_growth_kind) {
            (false, _) => "0".to_string(),
            (true, k) => format!(
                "{} ({})",
                plain(st.physical_growth_rate),
                k.map(crate::query::kind_name)
                    .unwrap_or_else(|| "growth".into())
            ),
        };
        println!(
            "{:<width$}  {:<20}  {:>18}  {:>14}  {:>22}  {:>18}",
            s.label,
            st.integrator,
            dt,
            plain(st.omega_max),
            growth,
            crate::vary::cell(r.critical_dt_inviscid)
        );
    }
    Ok(())
}

/// The time-domain part of the text output (`--verify`).
fn print_verify(v: &StableDtReport) {
    let size = v
        .stable_run
        .as_ref()
        .or(v.unstable_run.as_ref())
        .map_or(0, |p| p.particles);
    println!(
        "time domain ({}, viscosity {}, periodic body of {size} particles, {} steps per run, {} runs): growth allowed = physical rate within 1% + {} per step",
        v.integrator,
        v.viscosity.map_or("none", |p| p.name()),
        stable_dt::STEPS,
        v.runs,
        plain(stable_dt::FLOOR_PER_STEP)
    );
    let rate = |p: &ProbeRun| {
        p.growth_rate
            .map_or("diverged".into(), |g| format!("{} c/Δx", plain(g)))
    };
    match (&v.measured_dt, &v.stable_run, &v.unstable_run) {
        (Some(dt), Some(s), Some(u)) => {
            println!(
                "largest stable Δt (measured) = {} Δx/c: the run at Δt = {} Δx/c grows at {} (allowed {} c/Δx); at Δt = {} Δx/c it grows at {}",
                plain(*dt),
                plain(s.dt),
                rate(s),
                plain(s.allowed_growth_rate),
                plain(u.dt),
                rate(u)
            );
            if let Some(p) = v.predicted_dt_at_resolution {
                println!(
                    "analysis at the runs' resolution ({}added growth ≤ {} per step): {} Δx/c; measured / analysis = {}",
                    if v.viscosity.is_some() {
                        "viscosity two-sided, "
                    } else {
                        ""
                    },
                    plain(stable_dt::FLOOR_PER_STEP),
                    plain(p),
                    v.ratio.map_or("n/a".into(), plain)
                );
            }
        }
        (_, Some(s), None) => println!(
            "no time-step limit found: stable up to Δt = {} Δx/c (growth {})",
            plain(s.dt),
            rate(s)
        ),
        (_, _, Some(u)) => println!(
            "no stable Δt found: the run at Δt = {} Δx/c still grows at {}",
            plain(u.dt),
            rate(u)
        ),
        _ => {}
    }
}
