//! `sphstab galerkin`: the static meshfree Galerkin solutions of [B98 §6.2] — the cantilever and
//! the plate with a hole — and their errors against the exact solutions
//! ([`sphstab::studies::galerkin`]).

use anyhow::{Result, bail};
use sphstab::studies::galerkin::{GalerkinMethod, GalerkinProblem, GalerkinReport, rate, solve};
use std::fmt::Write;

/// Flags of `galerkin`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// beam (the cantilever of [B98] §6.2.1: levels are nodes per unit depth, Δx = 1/level)
    /// or plate (the plate with a hole of §6.2.2: levels are nodes per unit length along
    /// its symmetry edges).
    #[arg(long, default_value = "plate")]
    problem: String,
    /// Methods, comma-separated (at most 6): sph, rl, cd1, mls (nodal quadrature), efg,
    /// cd1-gauss (5 × 5 Gauss quadrature on the cells of the nodes). Default: all.
    #[arg(long, value_delimiter = ',')]
    methods: Vec<String>,
    /// Refinement levels, comma-separated (at most 8): beam in [2, 32] (default 4,8,16),
    /// plate in [1, 12] (default 2,4,8).
    #[arg(long, value_delimiter = ',')]
    levels: Vec<usize>,
    /// Print one JSON document instead of text: "reports" (one per method and level),
    /// "rates" and "units".
    #[arg(long)]
    json: bool,
}

/// A method's convergence rates over the levels: least-squares slopes of log(error) on
/// log(Δx) (null where an error is not defined).
#[derive(serde::Serialize)]
struct Rates {
    method: &'static str,
    displacement_rate: f64,
    energy_rate: f64,
    integrated_energy_rate: Option<f64>,
}

fn rates(reps: &[GalerkinReport]) -> Rates {
    let h: Vec<f64> = reps.iter().map(|r| r.spacing).collect();
    let du: Vec<f64> = reps.iter().map(|r| r.displacement_error).collect();
    let de: Vec<f64> = reps.iter().map(|r| r.energy_error).collect();
    let di: Option<Vec<f64>> = reps.iter().map(|r| r.integrated_energy_error).collect();
    Rates {
        method: reps[0].method.name(),
        displacement_rate: rate(&h, &du),
        energy_rate: rate(&h, &de),
        integrated_energy_rate: di.map(|d| rate(&h, &d)),
    }
}

fn text(problem: GalerkinProblem, all: &[Vec<GalerkinReport>], rs: &[Rates]) -> String {
    let num = |x: f64| sphstab::display::num_sig(x, 4);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "sphstab galerkin: [B98] {}, plane stress, cubic B-spline weight with s = √2 Δx",
        problem.describe()
    );
    let _ = writeln!(
        s,
        "errors relative to the exact solution's: displacement (nodal l2, eq 114; Gauss L2 for efg, cd1-gauss), energy (eq 118 at the quadrature points), energy by 5 × 5 Gauss on the cells (Figs 10–11)"
    );
    let _ = writeln!(
        s,
        "{:<10} {:>8} {:>6} {:>13} {:>10} {:>14} {:>12} {:>12}",
        "method", "Δx", "nodes", "displacement", "energy", "energy (Gauss)", "probe", "exact"
    );
    for reps in all {
        for r in reps {
            let _ = writeln!(
                s,
                "{:<10} {:>8} {:>6} {:>13} {:>10} {:>14} {:>12} {:>12}",
                r.method.name(),
                num(r.spacing),
                r.nodes,
                num(r.displacement_error),
                num(r.energy_error),
                r.integrated_energy_error.map_or("-".into(), num),
                num(r.probe_displacement),
                num(r.exact_probe_displacement)
            );
        }
    }
    let _ = writeln!(
        s,
        "rates over the levels (slope of log error on log Δx): method displacement / energy / energy (Gauss)"
    );
    for r in rs {
        let _ = writeln!(
            s,
            "{:<10} {:.2} / {:.2} / {}",
            r.method,
            r.displacement_rate,
            r.energy_rate,
            r.integrated_energy_rate
                .map_or("-".into(), |x| format!("{x:.2}"))
        );
    }
    s
}

pub fn run(a: Args, _budget: &sphstab::budget::Budget) -> Result<()> {
    let problem = GalerkinProblem::by_name("--problem", &a.problem)?;
    if a.methods.len() > GalerkinMethod::ALL.len() {
        bail!(
            "--methods: give at most the {} methods, got {}",
            GalerkinMethod::ALL.len(),
            a.methods.len()
        );
    }
    let methods: Vec<GalerkinMethod> = if a.methods.is_empty() {
        GalerkinMethod::ALL.iter().map(|m| m.0).collect()
    } else {
        a.methods
            .iter()
            .map(|m| GalerkinMethod::by_name("--methods", m))
            .collect::<sphstab::error::Result<_>>()?
    };
    let levels = if a.levels.is_empty() {
        problem.default_levels().to_vec()
    } else {
        a.levels.clone()
    };
    if levels.is_empty() || levels.len() > 8 {
        bail!("--levels: give 1 to 8 levels, got {}", levels.len());
    }
    let (lo, hi) = problem.level_range();
    for &l in &levels {
        if l < lo || l > hi {
            bail!(
                "--levels: {l} is out of range for --problem {}: each level must be in [{lo}, {hi}]",
                problem.name()
            );
        }
    }
    let all = methods
        .iter()
        .map(|&m| {
            levels
                .iter()
                .map(|&l| solve(problem, m, l))
                .collect::<sphstab::error::Result<Vec<_>>>()
        })
        .collect::<sphstab::error::Result<Vec<_>>>()?;
    let rs: Vec<Rates> = if levels.len() > 1 {
        all.iter().map(|r| rates(r)).collect()
    } else {
        Vec::new()
    };
    if a.json {
        /// The JSON document: the reports, the rates, then their units.
        #[derive(serde::Serialize)]
        struct Doc<'a> {
            problem: &'static str,
            reports: Vec<&'a GalerkinReport>,
            rates: &'a [Rates],
        }
        println!(
            "{}",
            sphstab::units::json(
                &Doc {
                    problem: problem.name(),
                    reports: all.iter().flatten().collect(),
                    rates: &rs,
                },
                sphstab::units::System::Normalised,
                false
            )?
        );
    } else {
        print!("{}", text(problem, &all, &rs));
    }
    Ok(())
}
