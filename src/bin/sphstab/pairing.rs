//! `sphstab pairing`: the 3D pairing study (classical SPH, hydro, under pressure) for every
//! kernel × lattice × h/Δx, next to the kernel's W* sign criterion; table, JSON and figure.
//! Bare, a quick subset ([`PairingConfig::quick`], seconds); the full study (~47 min) is
//! `--config analysis/pairing3d.json`.

use crate::{progress, study};
use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::studies::pairing::{PairingConfig, PairingReport, PairingStudy};
use std::path::{Path, PathBuf};

/// Flags of `pairing`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Comma-separated kernel names, or `all` for all eleven (default: m4,wendland-c2).
    #[arg(long, value_delimiter = ',')]
    kernels: Vec<String>,
    /// Comma-separated lattices: sc, bcc, fcc, or `all` (default: sc).
    #[arg(long, value_delimiter = ',')]
    lattices: Vec<String>,
    /// Smallest h/Δx, in [0.1, 10] (default 0.8).
    #[arg(long, allow_hyphen_values = true)]
    h_min: Option<f64>,
    /// Largest h/Δx, in [--h-min, 10] (default 2).
    #[arg(long, allow_hyphen_values = true)]
    h_max: Option<f64>,
    /// Step of h/Δx, in [0.001, 10], at most 1000 values (default 0.2).
    #[arg(long, allow_hyphen_values = true)]
    h_step: Option<f64>,
    /// Comma-separated pre-stresses σ̄ = σ/K, each in [−10, 1), 1 to 16 values (default
    /// −0.01,−0.1; negative = pressure).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    stresses: Vec<f64>,
    /// Wave vectors per reciprocal direction (grid³ − 1 sampled), in [2, 128] (default 16).
    #[arg(long)]
    grid: Option<usize>,
    /// A study config (JSON: kernels, lattices, h_min, h_max, h_step, stresses, grid, output,
    /// note); its `output` names the figure written to figures/ together with the data (same
    /// name, .json). Not combined with the study flags.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Re-draw the figure from stored data (a JSON written by --json or --config) without
    /// computing; needs --plot.
    #[arg(long)]
    from: Option<PathBuf>,
    /// Print the JSON report instead of the table (its "units" name the unit of every field).
    #[arg(long)]
    json: bool,
    /// Write the figure (SVG: growth against N_H, one panel per lattice and σ̄) here.
    #[arg(long)]
    plot: Option<PathBuf>,
    #[command(flatten)]
    export: crate::export::ExportArgs,
    /// Compute only shard i of n (0 ≤ i < n): the rows r with r mod n = i, written to --out
    /// for `sphstab merge`, which gives the table, JSON and figure of all the shards. For job
    /// arrays: analysis/cluster/study_array.sh.
    #[arg(long)]
    shard: Option<String>,
    /// Write the JSON report here (the bytes --json prints); with --shard, the shard.
    #[arg(long)]
    out: Option<PathBuf>,
}

impl Args {
    /// The study flags given on the command line.
    fn study_flags(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        let given = [
            (!self.kernels.is_empty(), "--kernels"),
            (!self.lattices.is_empty(), "--lattices"),
            (self.h_min.is_some(), "--h-min"),
            (self.h_max.is_some(), "--h-max"),
            (self.h_step.is_some(), "--h-step"),
            (!self.stresses.is_empty(), "--stresses"),
            (self.grid.is_some(), "--grid"),
        ];
        for (g, name) in given {
            if g {
                v.push(name);
            }
        }
        v
    }
}

/// A list flag: `all` alone is the whole set (an empty list for the library).
fn all_or(v: &[String]) -> Vec<String> {
    if v.len() == 1 && v[0] == "all" {
        Vec::new()
    } else {
        v.to_vec()
    }
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let export = a
        .export
        .resolve(a.plot.is_some(), "no --plot (it sets the plot's formats)")?;
    let files = study::files(a.config.as_ref(), a.from.as_ref(), a.plot.as_ref(), &export);
    files.check()?;
    let flags = a.study_flags();
    if let Some(from) = &a.from {
        let others = a.config.is_some()
            || !flags.is_empty()
            || a.json
            || a.shard.is_some()
            || a.out.is_some();
        return study::redraw::<PairingReport>(
            from,
            a.plot.as_ref(),
            &export,
            others,
            sphstab::studies::pairing::figure_svg,
        );
    }
    let shard = crate::shard::flags(
        a.shard.as_deref(),
        a.out.as_ref(),
        &[(a.json, "--json"), (a.plot.is_some(), "--plot")],
    )?;
    let (cfg, config_out) = match &a.config {
        Some(p) => {
            if !flags.is_empty() {
                anyhow::bail!(
                    "--config holds the whole study: do not combine it with {}",
                    flags.join(", ")
                );
            }
            let cfg = study::read_config(p, sphstab::studies::pairing::parse_config)?;
            let out = cfg.output.clone();
            (cfg, out)
        }
        None => {
            let d = PairingConfig::quick();
            (
                PairingConfig {
                    kernels: if a.kernels.is_empty() {
                        d.kernels
                    } else {
                        all_or(&a.kernels)
                    },
                    lattices: if a.lattices.is_empty() {
                        d.lattices
                    } else {
                        all_or(&a.lattices)
                    },
                    h_min: a.h_min.unwrap_or(d.h_min),
                    h_max: a.h_max.unwrap_or(d.h_max),
                    h_step: a.h_step.unwrap_or(d.h_step),
                    stresses: if a.stresses.is_empty() {
                        d.stresses
                    } else {
                        a.stresses.clone()
                    },
                    grid: a.grid.unwrap_or(d.grid),
                    ..d
                },
                None,
            )
        }
    };
    let cfg = PairingConfig {
        budget: *budget,
        ..cfg
    };
    // validate everything before the first row is computed
    sphstab::studies::pairing::plan(&cfg)?;
    if let Some((shard, out)) = shard {
        // a config's `output` (figure and data) is written by the merge
        return crate::shard::run(&PairingStudy, &cfg, shard, &out);
    }
    if let Some(name) = &config_out {
        study::with_config_output(files, name).check()?;
    }
    let pb = progress::Bar::new(progress::wanted(a.json));
    let rep = sphstab::studies::pairing::run(&cfg, pb.clone())?;
    pb.finish();
    output(
        &rep,
        a.out.as_deref(),
        a.json,
        a.plot.as_deref().map(|p| (p, &export)),
        config_out.as_deref(),
    )?;
    if !a.json && a.config.is_none() {
        println!(
            "{}\nthe full study (every kernel × sc, bcc, fcc × h/Δx = 0.8…3 step 0.1 × σ̄ = −0.01, −0.1 at 16³ wave vectors; ~47 min): cargo run --release -- pairing --config {}",
            if flags.is_empty() {
                sphstab::studies::pairing::QUICK_DESCRIPTION
            } else {
                "a subset of the pairing study"
            },
            sphstab::studies::pairing::FULL_STUDY_CONFIG
        );
    }
    Ok(())
}

/// Writes and prints a report (shared with `merge`): `--out` (JSON), `--plot`, a config's
/// `output` (the figure and its data in figures/), then the JSON (`--json`) or the table.
pub fn output(
    rep: &PairingReport,
    out: Option<&Path>,
    json: bool,
    plot: Option<study::Plot<'_>>,
    config_out: Option<&str>,
) -> Result<()> {
    study::output(
        rep,
        study::Outputs {
            out,
            json,
            plot,
            config_out,
        },
        sphstab::studies::pairing::figure_svg,
        |r| {
            format!(
                "{}{} rows in {:.1} s ({} threads)\n",
                sphstab::studies::pairing::table(r),
                r.rows.len(),
                r.runtime_s,
                r.threads
            )
        },
    )
}
