//! `sphstab hourglass`: the tensile-or-hourglass study — every solid remedy (classical,
//! artificial stress, Bonet–Lok, SPH-ENOG, TLSPH, Ganzenmüller, tl-enog) over pre-stress
//! states, stresses and Poisson ratios: onsets, hourglass and tensile growth, stability maps,
//! wave-speed costs. Bare, a quick study (grid 12, 10 stresses); the published one is
//! `--config analysis/configs/tensile_or_hourglass.json`.

use crate::{progress, study};
use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::studies::hourglass::{HourglassConfig, HourglassReport};
use std::path::{Path, PathBuf};

/// Flags of `hourglass`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Dimension, 2 or 3 (default 2).
    #[arg(long)]
    dim: Option<u8>,
    /// Wave vectors per reciprocal direction of each question, even, in [4, 64] (default 12 in
    /// 2D, 6 in 3D).
    #[arg(long)]
    grid: Option<usize>,
    /// Lattice: 2D square (default) or hex; 3D sc (default), bcc or fcc.
    #[arg(long)]
    lattice: Option<String>,
    /// A study config (JSON: remedies (label and query), states, stress, poisson,
    /// reference_poisson, grid, dim, lattice, output, note); its `output` names the figure written to
    /// figures/ together with the data (same name, .json). Not combined with --dim, --grid,
    /// --lattice.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Re-draw the figure from stored data (a JSON written by --json or --config) without
    /// computing; needs --plot.
    #[arg(long)]
    from: Option<PathBuf>,
    /// Print the JSON report instead of the table (its "units" name the unit of every field).
    #[arg(long)]
    json: bool,
    /// Write the figure (SVG: stability maps, growth split into hourglass and tensile parts).
    #[arg(long)]
    plot: Option<PathBuf>,
    #[command(flatten)]
    export: crate::export::ExportArgs,
    /// Write the JSON report here (the bytes --json prints).
    #[arg(long)]
    out: Option<PathBuf>,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let export = a
        .export
        .resolve(a.plot.is_some(), "no --plot (it sets the plot's formats)")?;
    let mut files = study::files(a.config.as_ref(), a.from.as_ref(), a.plot.as_ref(), &export);
    files.check()?;
    let flags: Vec<&str> = [
        (a.dim.is_some(), "--dim"),
        (a.grid.is_some(), "--grid"),
        (a.lattice.is_some(), "--lattice"),
    ]
    .into_iter()
    .filter_map(|(g, n)| g.then_some(n))
    .collect();
    if let Some(from) = &a.from {
        let others = a.config.is_some() || !flags.is_empty() || a.json || a.out.is_some();
        return study::redraw::<HourglassReport>(
            from,
            a.plot.as_ref(),
            &export,
            others,
            sphstab::studies::hourglass::figure_svg,
        );
    }
    let cfg = match &a.config {
        Some(p) => {
            if !flags.is_empty() {
                anyhow::bail!(
                    "--config holds the whole study: do not combine it with {}",
                    flags.join(", ")
                );
            }
            study::read_config(p, sphstab::studies::hourglass::parse_config)?
        }
        None => {
            let d = HourglassConfig::quick(a.dim.unwrap_or(2));
            HourglassConfig {
                grid: a.grid.unwrap_or(d.grid),
                lattice: a.lattice.clone(),
                ..d
            }
        }
    };
    let cfg = HourglassConfig {
        budget: *budget,
        ..cfg
    };
    cfg.validate()?;
    if let Some(name) = &cfg.output {
        files = study::with_config_output(files, name);
    }
    if let Some(out) = &a.out {
        files = files.output("--out", out);
    }
    files.check()?;
    let pb = progress::Bar::new(progress::wanted(a.json));
    let rep = sphstab::studies::hourglass::run(&cfg, pb.clone())?;
    pb.finish();
    output(
        &rep,
        a.out.as_deref(),
        a.json,
        a.plot.as_deref().map(|p| (p, &export)),
    )
}

/// Writes and prints a report: `--out` (JSON), `--plot`, its config's `output` (the figure and
/// its data in figures/), then the JSON (`--json`) or the table.
pub fn output(
    rep: &HourglassReport,
    out: Option<&Path>,
    json: bool,
    plot: Option<study::Plot<'_>>,
) -> Result<()> {
    study::output(
        rep,
        study::Outputs {
            out,
            json,
            plot,
            config_out: rep.config.output.as_deref(),
        },
        sphstab::studies::hourglass::figure_svg,
        sphstab::studies::hourglass::table,
    )
}
