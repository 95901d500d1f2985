//! `sphstab` command-line interface (thin: argument parsing and printing only).

mod alloc;
mod art_stress;
mod atlas;
mod common;
mod dispersion;
mod export;
mod figures;
mod files;
mod flags;
mod galerkin;
mod hourglass;
mod interpolate;
mod kernels;
mod map;
mod merge;
mod pairing;
mod progress;
mod query;
mod shard;
mod simulate;
mod stiffness;
mod study;
mod swegle;
mod throughput;
mod timestep;
mod tradeoff;
mod vary;

use clap::{Parser, Subcommand};
use sphstab::budget::Budget;

/// Stability of SPH forms, kernels, smoothing lengths, stress states and time steps.
///
/// Units: lengths in Δx, wave numbers as κΔx ∈ (0, π], frequencies and growth rates in c/Δx,
/// times and time steps in Δx/c, stress σ̄ = σ/C (positive in tension; C the tangent modulus,
/// c = √(C/ρ0)); the CFL number is c Δt/h (h in the kernel's own convention). A run with
/// physical units (simulate's scenes, SI; the Swegle test's own units) prints the physical value
/// and the normalised one; every JSON document names its units in "units". Bad input, or a run
/// whose estimated memory or particle-steps exceed --max-memory / --max-steps, exits with
/// status 2 before it starts; a time integration that diverges stops with status 3.
#[derive(Parser)]
#[command(name = "sphstab", version, about)]
pub(crate) struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
    /// Memory budget (bytes, or with K/M/G/T suffix): a run whose estimated memory exceeds it
    /// is refused before it starts. Default: 2G, or a quarter of the machine's RAM if less.
    #[arg(long = "max-memory", global = true, value_parser = sphstab::budget::parse_bytes)]
    max_memory: Option<f64>,
    /// Cap on particle-steps (particles × time steps) of one time integration (simulate,
    /// swegle, throughput, tradeoff): longer runs are refused before they start. Default 5e7
    /// (about a minute here).
    #[arg(long = "max-steps", global = true, value_parser = sphstab::budget::parse_steps)]
    max_steps: Option<f64>,
    /// Let --out and --plot overwrite existing files (without it a command that would write
    /// over a file stops before it starts). An output that is also an input of the command is
    /// refused even so. (`figures` and a study's --config regenerate their figures in place.)
    #[arg(long, global = true)]
    force: bool,
}

#[derive(Subcommand)]
pub(crate) enum Cmd {
    /// Is this configuration stable? Names and classifies every instability (growth rates in c/Δx).
    Query(query::Args),
    /// Dispersion curve ω²(κ) of the mechanical branch (ω² in c²/Δx², κ as κΔx), with the
    /// continuum overlaid.
    Dispersion(dispersion::Args),
    /// Critical time step Δt (in Δx/c) of the integrator, and the CFL number c Δt/h.
    Timestep(timestep::Args),
    /// The kernel table.
    Kernels(kernels::Args),
    /// Regenerate the figures in figures/ from the configs in analysis/configs/ and the studies'
    /// stored data, with their captions (README.md); --format pdf,png also as PDF and PNG.
    Figures(figures::Args),
    /// 2D stability map: growth rate (c/Δx) over (κxΔx, κyΔx) as a heat map.
    Map(map::Args),
    /// Anti-plane Galerkin stiffness K_jk for a quadrature pattern [B00 Table I].
    Stiffness(stiffness::Args),
    /// Interpolation and gradient accuracy of a kernel on a finite 1D/2D particle set, ghosts
    /// or not, against the exact values [T §2.7].
    Interpolate(interpolate::Args),
    /// Static meshfree Galerkin solutions of [B98 §6.2] (cantilever, plate with a hole) by
    /// SPH, RL, CD1, MLS and EFG, with their errors and convergence rates.
    Galerkin(galerkin::Args),
    /// The Swegle perturbed-particle test (2D or 3D), measured against the engine's predictions
    /// (rates in c/Δx, Δt in Δx/c, each also in the test's own units).
    Swegle(swegle::Args),
    /// Run a 1D scene (JSON file or built-in; SI units) and compare it with its analytic
    /// solution (times, speeds and stresses also in Δx/c, c and σ/C).
    Simulate(simulate::Args),
    /// Speed/accuracy trade-off: cost, accuracy and robustness of every form × kernel × h.
    Tradeoff(tradeoff::Args),
    /// 1D stability atlas: every form × kernel × h × σ̄ (parallel, shardable).
    Atlas(atlas::Args),
    /// Merge the shards of a study (atlas, pairing, tradeoff, art-stress; `--shard i/n`).
    Merge(merge::Args),
    /// Speed and memory of the solver on a 2D or 3D block (and its scaling with N).
    Throughput(throughput::Args),
    /// 3D pairing study: growth under pressure against neighbour number N_H, every kernel ×
    /// lattice (sc, bcc, fcc) × h/Δx, next to the kernel's W* sign criterion.
    Pairing(pairing::Args),
    /// Artificial stress against the Swegle growth: engine (infinite lattice, box) and Swegle
    /// runs over ε, for several h/Δx and tensions.
    ArtStress(art_stress::Args),
    /// Tensile or hourglass? Every solid remedy (artificial stress, Bonet–Lok, SPH-ENOG,
    /// Ganzenmüller, tl-enog) over pre-stress states, stresses and G/K: onsets, hourglass and
    /// tensile growth, stability maps, wave-speed costs.
    Hourglass(hourglass::Args),
}

/// A reader that closes the pipe early (`sphstab … | head`) makes `println!` panic with a broken
/// pipe; end quietly instead, with the status a shell gives a process killed by SIGPIPE.
fn quiet_on_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let msg = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if msg.contains("Broken pipe") {
            std::process::exit(141);
        }
        default(info);
    }));
}

fn main() {
    quiet_on_broken_pipe();
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(
                e.kind(),
                ErrorKind::DisplayHelp
                    | ErrorKind::DisplayVersion
                    | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
            ) {
                e.exit();
            }
            // One line: clap's first line names the flag and the problem; for a missing
            // argument the names are on the following lines, joined into that one line.
            let text = e.render().to_string();
            let mut lines = text.lines().filter(|l| !l.trim().is_empty());
            let first = lines
                .next()
                .unwrap_or("error: invalid arguments")
                .to_string();
            let line = if e.kind() == ErrorKind::MissingRequiredArgument {
                let names: Vec<&str> = lines
                    .take_while(|l| l.starts_with(' '))
                    .map(str::trim)
                    .collect();
                format!("{first} {}", names.join(", "))
            } else {
                first
            };
            eprintln!("{line}");
            std::process::exit(2);
        }
    };
    files::set_force(cli.force);
    let mut budget = Budget::for_machine();
    if let Some(m) = cli.max_memory {
        budget.max_memory = m;
    }
    if let Some(n) = cli.max_steps {
        budget.max_steps = n;
    }
    let b = &budget;
    let res = match cli.cmd {
        Cmd::Query(a) => query::run(a, b),
        Cmd::Dispersion(a) => dispersion::run(a, b),
        Cmd::Timestep(a) => timestep::run(a, b),
        Cmd::Kernels(a) => kernels::run(a, b),
        Cmd::Figures(a) => figures::run(a, b),
        Cmd::Map(a) => map::run(a, b),
        Cmd::Stiffness(a) => stiffness::run(a, b),
        Cmd::Interpolate(a) => interpolate::run(a, b),
        Cmd::Galerkin(a) => galerkin::run(a, b),
        Cmd::Swegle(a) => swegle::run(a, b),
        Cmd::Simulate(a) => simulate::run(a, b),
        Cmd::Tradeoff(a) => tradeoff::run(a, b),
        Cmd::Atlas(a) => atlas::run(a, b),
        Cmd::Merge(a) => merge::run(a, b),
        Cmd::Throughput(a) => throughput::run(a, b),
        Cmd::Pairing(a) => pairing::run(a, b),
        Cmd::ArtStress(a) => art_stress::run(a, b),
        Cmd::Hourglass(a) => hourglass::run(a, b),
    };
    if let Err(e) = res {
        eprintln!("error: {}", flags::message(&e));
        // 3: the run itself blew up (a result, not bad input); 2: bad input or over budget
        std::process::exit(if flags::diverged(&e) { 3 } else { 2 });
    }
}
