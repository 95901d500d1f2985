//! `sphstab query`.

use crate::common::Config;
use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::units::{self, System};

/// Flags of `query`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    #[command(flatten)]
    integ: crate::common::IntegratorArgs,
    /// 1D: number of κ points in (0, π], in [2, 10000000] (default 512); the same as --grid.
    #[arg(long)]
    points: Option<usize>,
    /// Print one JSON document instead of a table (its "units" name the unit of every field).
    #[arg(long)]
    json: bool,
    /// 2D/3D: also predict the growth a box of N^D free particles between fixed layers can
    /// show (standing modes k = (m_1, …, m_D)π/(N+1)), N in [1, 1000] (3D: [1, 100]).
    #[arg(long = "box")]
    box_free: Option<usize>,
    #[command(flatten)]
    vary: crate::vary::VaryArgs,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    a.cfg
        .spec()
        .check_for(sphstab::analysis::spec::Command::Query)?;
    let dim = a.cfg.dim()?;
    crate::by_dim!(dim, run_in(a, budget))
}

/// A wave vector in units of π: "(0.1234π, 0.5000π)"; in 1D "0.1234π".
pub fn fmt_k(k: &[f64]) -> String {
    if let [k] = k {
        return format!("{:.4}π", k / std::f64::consts::PI);
    }
    let parts: Vec<String> = k
        .iter()
        .map(|c| format!("{:.4}π", c / std::f64::consts::PI))
        .collect();
    format!("({})", parts.join(", "))
}

/// `--points` (1D: the κ points, as `--grid`) of `query` and `timestep`.
pub fn points_as_grid(
    dim: u8,
    points: Option<usize>,
    grid: Option<usize>,
) -> Result<Option<usize>> {
    match (points, grid) {
        (Some(_), _) if dim > 1 => Err(not_in(
            "--points",
            &format!("--dim {dim} (use --grid for the zone sampling)"),
        )),
        (Some(_), Some(_)) => Err(not_in("--points", "--grid (give one of them)")),
        (Some(p), None) => {
            sphstab::params::check_count("points", p, 2, sphstab::analysis::max_grid(1))?;
            Ok(Some(p))
        }
        (None, g) => Ok(g),
    }
}

fn run_in<const D: usize>(mut a: Args, budget: &Budget) -> Result<()> {
    a.cfg.grid = points_as_grid(D as u8, a.points, a.cfg.grid)?;
    if D == 1 && a.box_free.is_some() {
        return Err(not_in("--box", "--dim 1 (it predicts a 2D or 3D box)"));
    }
    if crate::vary::active(&a.cfg, &a.vary) {
        if a.box_free.is_some() {
            return Err(not_in(
                "--box",
                "--vary or a list (compare the infinite lattice; ask for one box at a time)",
            ));
        }
        return compare::<D>(&a, budget);
    }
    let mut q = a.cfg.query::<D>(budget)?;
    q.integrator = a.integ.integrator()?;
    if let Some(n) = a.box_free {
        sphstab::params::check_count("box", n, 1, sphstab::analysis::max_box(D))?;
    }
    // in 1D the κ points are --points or --grid: the budget names the one given
    let r = sphstab::analysis::query(&q)
        .map_err(|e| crate::flags::alias(e, "grid", "--points", a.points.is_some()))?;
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
        println!("{}", units::json(&v, System::Normalised, true)?);
        return Ok(());
    }
    if let Some((g, k)) = boxp {
        println!(
            "box of {}^{D} free particles: predicted growth {g:.6} c/Δx at κΔx = {}",
            a.box_free.unwrap_or(0),
            fmt_k(&k)
        );
    }
    if D == 1 {
        println!("{}, {} κ points in (0, π]", r.header, r.grid);
    } else {
        println!("{}, first zone sampled {}^{D}", r.header, r.grid);
    }
    let kinds: Vec<String> = r.growth_kinds().into_iter().map(kind_name).collect();
    match (r.stable, &r.kappa_at_max, &r.polarisation) {
        (true, _, _) => println!("verdict: STABLE (no exponentially growing mode)"),
        (false, Some(k), pol) => println!(
            "verdict: UNSTABLE ({}) — max growth rate {:.6} c/Δx at κΔx = {}{}",
            kinds.join(", "),
            r.max_growth_rate,
            fmt_k(k),
            match pol {
                Some(p) if D > 1 => format!(
                    ", polarisation ({}), longitudinal fraction {:.3}",
                    p.vector
                        .iter()
                        .map(|c| format!("{c:.3}"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    p.longitudinal_fraction
                ),
                _ => String::new(),
            }
        ),
        (false, None, _) => println!(
            "verdict: UNSTABLE ({}) — no exponential growth on the grid (marginal)",
            kinds.join(", ")
        ),
    }
    if r.art_stress_kink {
        println!(
            "note: a principal pre-stress is exactly 0, a kink of the artificial stress (R switches with the perturbation's sign): the verdict is the compression side's linearisation; a run may grow where it says none"
        );
    }
    if r.instabilities.is_empty() {
        println!("no unstable or marginal branch");
    }
    for i in &r.instabilities {
        let range = match (i.kappa_min, i.kappa_max) {
            (Some(lo), Some(hi)) => format!(
                ", κΔx/π in [{:.4}, {:.4}]",
                lo / std::f64::consts::PI,
                hi / std::f64::consts::PI
            ),
            _ => String::new(),
        };
        println!(
            "{:<16} growth {:.6} c/Δx at κΔx = {}, {:.1}% of the {}{range}{}",
            kind_name(i.kind),
            i.growth_rate,
            fmt_k(&i.kappa_at_max),
            100.0 * i.zone_fraction,
            if D == 1 { "κ grid" } else { "zone" },
            i.pole_at
                .map(|p| format!(
                    "  (ω² passes a pole at κΔx ≈ {:.4}π: the mass symbol vanishes)",
                    p / std::f64::consts::PI
                ))
                .unwrap_or_default()
                + &match (i.unstressed_omega2, i.onset_stress) {
                    _ if i.kind == sphstab::vonneumann::classify::Kind::Hourglass => {
                        "; zero-energy at rest: grows at any σ̄ of this sign".to_string()
                    }
                    (Some(w), Some(o)) => format!(
                        "; at rest ω²Δx²/c² = {:.3e}, grows from σ̄ = {:.3e}",
                        w.max(0.0),
                        o
                    ),
                    _ => String::new(),
                }
        );
    }
    match (r.critical_dt, r.critical_cfl) {
        (Some(dt), Some(cfl)) => println!(
            "critical {} Δt = {dt:.6} Δx/c (CFL c Δt/h = {cfl:.6})",
            integrator_words(r.integrator)
        ),
        _ => println!("{}", no_critical(r.integrator)),
    }
    if let (Some(dt), Some(m)) = (r.dt, r.max_amplification) {
        println!(
            "at Δt = {} Δx/c: max |λ| = {m:.9}",
            sphstab::display::num(dt)
        );
    }
    Ok(())
}

/// `--vary` / lists: every question checked first, then answered; a table (or JSON
/// `{"series": [{"label", "query"}]}`).
fn compare<const D: usize>(a: &Args, budget: &Budget) -> Result<()> {
    let list = crate::vary::series(&a.cfg, &a.vary, true)?;
    let questions = crate::vary::questions::<D>(&list, &a.integ, budget)?;
    let reports = questions
        .iter()
        .map(sphstab::analysis::query)
        .collect::<sphstab::error::Result<Vec<_>>>()?;
    if a.json {
        let series: Vec<serde_json::Value> = list
            .iter()
            .zip(&reports)
            .map(|(s, r)| serde_json::json!({"label": s.label, "query": r}))
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
        "{:<width$}  {:<8}  {:>16}  {:<28}  {:>18}",
        "series", "verdict", "growth c/Δx", "kinds", "critical Δt Δx/c"
    );
    for (s, r) in list.iter().zip(&reports) {
        let kinds: Vec<String> = r.growth_kinds().into_iter().map(kind_name).collect();
        println!(
            "{:<width$}  {:<8}  {:>16}  {:<28}  {:>18}",
            s.label,
            if r.stable { "stable" } else { "UNSTABLE" },
            crate::vary::cell(Some(r.max_growth_rate)),
            if kinds.is_empty() {
                "—".to_string()
            } else {
                kinds.join(", ")
            },
            crate::vary::cell(r.critical_dt)
        );
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
