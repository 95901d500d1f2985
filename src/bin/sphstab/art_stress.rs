//! `sphstab art-stress`: how much Monaghan–Gray artificial stress slows the Swegle growth of
//! the classical form (engine on the infinite lattice and the finite box, Swegle runs, and
//! optionally PySPH's stored measurements); table, JSON and figure. Bare, a quick prediction
//! grid (m4, h = 1.2, f = 0.99, no runs); the published study is
//! `--config analysis/art_stress.json`.

use crate::{progress, study};
use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::solver::BoundaryDensity;
use sphstab::studies::art_stress::{
    ArtStressConfig, ArtStressReport, ArtStressSetup, ArtStressStudy,
};
use std::path::{Path, PathBuf};

/// Flags of `art-stress`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Kernel (default m4).
    #[arg(long)]
    kernel: Option<String>,
    /// Form: classical or cll (default classical).
    #[arg(long)]
    form: Option<String>,
    /// Comma-separated smoothing lengths h/Δx, 1 to 4 values in [0.8, 6] (default 1.2).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    h: Vec<f64>,
    /// Comma-separated density ratios f = ρ/ρ0 (f < 1: tension σ̄ = 1 − f), 1 to 4 values in
    /// [0.5, 1.5] (default 0.99).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    density_ratio: Vec<f64>,
    /// Comma-separated artificial-stress ε (dimensionless) of the prediction grid, each in
    /// [0, 10] (default 0, 0.05, …, 0.6).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    eps: Vec<f64>,
    /// Comma-separated ε (dimensionless) of Swegle runs, each in [0, 10] (default none).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    runs: Vec<f64>,
    /// Exponent n of f = W(r)/W(Δx), in [1, 12] (default 4).
    #[arg(long, allow_hyphen_values = true)]
    art_n: Option<f64>,
    /// Boundary density of the box: frozen (default, as PySPH) or evolve.
    #[arg(long, value_enum)]
    boundary_density: Option<Boundary>,
    /// Stored measurements of PySPH to draw beside sphstab's
    /// (analysis/pysph/results-art-stress.json).
    #[arg(long)]
    compare: Option<PathBuf>,
    /// A study config (JSON: form, kernel, h, density_ratio, eps, runs, art_n,
    /// boundary_density, size, compare, output, note); its `output` names the figure written to
    /// figures/ together with the data (same name, .json). Not combined with the study flags.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Re-draw the figure from stored data (a JSON written by --json or --config) without
    /// computing; needs --plot.
    #[arg(long)]
    from: Option<PathBuf>,
    /// Print the JSON report instead of the table (its "units" name the unit of every field).
    #[arg(long)]
    json: bool,
    /// Write the figure (SVG: growth rate against ε, one panel per h and f) here.
    #[arg(long)]
    plot: Option<PathBuf>,
    #[command(flatten)]
    export: crate::export::ExportArgs,
    /// Compute only shard i of n (0 ≤ i < n): the cells c with c mod n = i (per h and f, one
    /// per ε of the grid, then one per run), written to --out for `sphstab merge`, which gives
    /// the table, JSON and figure of all the shards. For job arrays:
    /// analysis/cluster/study_array.sh.
    #[arg(long)]
    shard: Option<String>,
    /// Write the JSON report here (the bytes --json prints); with --shard, the shard.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// `--boundary-density`.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum Boundary {
    Frozen,
    Evolve,
}

impl Args {
    fn study_flags(&self) -> Vec<&'static str> {
        [
            (self.kernel.is_some(), "--kernel"),
            (self.form.is_some(), "--form"),
            (!self.h.is_empty(), "--h"),
            (!self.density_ratio.is_empty(), "--density-ratio"),
            (!self.eps.is_empty(), "--eps"),
            (!self.runs.is_empty(), "--runs"),
            (self.art_n.is_some(), "--art-n"),
            (self.boundary_density.is_some(), "--boundary-density"),
            (self.compare.is_some(), "--compare"),
        ]
        .into_iter()
        .filter_map(|(g, n)| g.then_some(n))
        .collect()
    }
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let export = a
        .export
        .resolve(a.plot.is_some(), "no --plot (it sets the plot's formats)")?;
    let mut files = study::files(a.config.as_ref(), a.from.as_ref(), a.plot.as_ref(), &export);
    if let Some(p) = &a.compare {
        files = files.input("--compare", p);
    }
    files.check()?;
    let flags = a.study_flags();
    if let Some(from) = &a.from {
        let others = a.config.is_some()
            || !flags.is_empty()
            || a.json
            || a.shard.is_some()
            || a.out.is_some();
        return study::redraw::<ArtStressReport>(
            from,
            a.plot.as_ref(),
            &export,
            others,
            sphstab::studies::art_stress::figure_svg,
        );
    }
    let shard = crate::shard::flags(
        a.shard.as_deref(),
        a.out.as_ref(),
        &[(a.json, "--json"), (a.plot.is_some(), "--plot")],
    )?;
    let cfg = match &a.config {
        Some(p) => {
            if !flags.is_empty() {
                anyhow::bail!(
                    "--config holds the whole study: do not combine it with {}",
                    flags.join(", ")
                );
            }
            study::read_config(p, sphstab::studies::art_stress::parse_config)?
        }
        None => {
            let d = ArtStressConfig::quick();
            let n = match a.art_n {
                Some(n) if n.fract() == 0.0 && (1.0..=12.0).contains(&n) => n as i32,
                Some(n) => {
                    return Err(sphstab::error::Error::OutOfRange {
                        field: "art_n",
                        value: n,
                        range: "an integer in [1, 12]".into(),
                    }
                    .into());
                }
                None => d.art_n,
            };
            ArtStressConfig {
                form: a.form.clone().unwrap_or(d.form),
                kernel: a.kernel.clone().unwrap_or(d.kernel),
                h: if a.h.is_empty() { d.h } else { a.h.clone() },
                density_ratio: if a.density_ratio.is_empty() {
                    d.density_ratio
                } else {
                    a.density_ratio.clone()
                },
                eps: if a.eps.is_empty() {
                    d.eps
                } else {
                    a.eps.clone()
                },
                runs: a.runs.clone(),
                art_n: n,
                boundary_density: match a.boundary_density {
                    Some(Boundary::Evolve) => BoundaryDensity::Evolve,
                    _ => BoundaryDensity::Frozen,
                },
                compare: a.compare.as_ref().map(|p| p.display().to_string()),
                ..d
            }
        }
    };
    let cfg = ArtStressConfig {
        budget: *budget,
        ..cfg
    };
    cfg.validate()?;
    if let Some(p) = &cfg.compare {
        files = files.input("--config (its `compare`)", p);
    }
    if let (None, Some(name)) = (&shard, &cfg.output) {
        files = study::with_config_output(files, name);
    }
    if let Some((_, out)) = &shard {
        files = files.output("--out", out);
    }
    files.check()?;
    let compare = match &cfg.compare {
        Some(p) => {
            let flag = if a.config.is_some() {
                "--config (its `compare`)"
            } else {
                "--compare"
            };
            let text = std::fs::read_to_string(p)
                .map_err(|e| anyhow::anyhow!("{flag}: cannot read {p}: {e}"))?;
            Some(sphstab::studies::art_stress::comparison_from_pysph(
                p, &text,
            )?)
        }
        None => None,
    };
    if let Some((shard, out)) = shard {
        // the comparison goes into every shard, so the merge reads nothing but the shards; a
        // config's `output` (figure and data) is written by the merge
        let setup = ArtStressSetup {
            config: cfg,
            compare,
        };
        return crate::shard::run(&ArtStressStudy, &setup, shard, &out);
    }
    let pb = progress::Bar::new(progress::wanted(a.json));
    let rep = sphstab::studies::art_stress::run(&cfg, compare.as_ref(), pb.clone())?;
    pb.finish();
    output(
        &rep,
        a.out.as_deref(),
        a.json,
        a.plot.as_deref().map(|p| (p, &export)),
    )
}

/// Writes and prints a report (shared with `merge`): `--out` (JSON), `--plot`, its config's
/// `output` (the figure and its data in figures/), then the JSON (`--json`) or the table.
pub fn output(
    rep: &ArtStressReport,
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
        sphstab::studies::art_stress::figure_svg,
        sphstab::studies::art_stress::table,
    )
}
