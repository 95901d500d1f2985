//! `sphstab tradeoff`: the speed/accuracy trade-off study (cost, accuracy, robustness of every
//! form × kernel × h/Δx), as a table, JSON and a Pareto figure.

use crate::{progress, study};
use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::studies::tradeoff::{TradeoffConfig, TradeoffReport, TradeoffStudy};
use sphstab::units::{self, System};
use std::path::{Path, PathBuf};

/// Flags of `tradeoff`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Dimension: 1 (ten forms, periodic chain; default) or 2 (six forms, square lattice,
    /// hydro).
    #[arg(long)]
    dim: Option<u8>,
    /// Comma-separated form names (default: every form of the dimension).
    #[arg(long, value_delimiter = ',')]
    forms: Vec<String>,
    /// Comma-separated kernel names (default: all eleven).
    #[arg(long, value_delimiter = ',')]
    kernels: Vec<String>,
    /// h/Δx values per kernel, evenly over its customary range, in [1, 64] (default 3).
    #[arg(long)]
    h_points: Option<usize>,
    /// Timed repeats of the wave scene (median reported), in [1, 100] (default 3).
    #[arg(long)]
    repeats: Option<usize>,
    /// Integrator dimension (1D): comma-separated integrator names or `all`; adds one row per
    /// configuration × integrator (cost per unit simulated time, phase and amplitude error per
    /// wavelength travelled).
    #[arg(long, value_delimiter = ',')]
    integrators: Vec<String>,
    /// Δt used for the integrator rows = safety × critical Δt, in (0, 1] (default 0.9; needs
    /// --integrators).
    #[arg(long)]
    safety: Option<f64>,
    /// Print the critical CFL table (c Δt_crit/h per integrator × kernel, classical and
    /// total-lagrangian, h/Δx = 1.2 and 2.0, σ̄ = 0) as Markdown (JSON with --json) and stop;
    /// the table is fixed: no other flag.
    #[arg(long)]
    cfl_table: bool,
    /// A study config (JSON: dim, forms, kernels, h_points, repeats, output, note, integrators,
    /// safety); its `output` names the figure regenerated in figures/ together with the data
    /// (same name, .json). Not combined with the study flags.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Re-draw the figure from stored data (a JSON written by --json or --config) without measuring.
    #[arg(long)]
    from: Option<PathBuf>,
    /// Print the JSON report instead of the table (its "units" name the unit of every field).
    #[arg(long)]
    json: bool,
    /// Write the Pareto figure (SVG) here.
    #[arg(long)]
    plot: Option<PathBuf>,
    #[command(flatten)]
    export: crate::export::ExportArgs,
    /// Compute only shard i of n (0 ≤ i < n): the configurations c with c mod n = i, written
    /// to --out for `sphstab merge`, which gives the table, JSON and figure of all the shards.
    /// The costs are timed on the machine that runs each shard. For job arrays:
    /// analysis/cluster/study_array.sh.
    #[arg(long)]
    shard: Option<String>,
    /// Write the JSON report here (the bytes --json prints); with --shard, the shard.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// The figure of a report (`--plot`, `--from`, a config's `output`, `figures`).
pub fn draw(rep: &TradeoffReport) -> sphstab::error::Result<String> {
    sphstab::studies::tradeoff::figure_svg(rep)
}

impl Args {
    /// The study flags given on the command line.
    fn study_flags(&self) -> Vec<&'static str> {
        [
            (self.dim.is_some(), "--dim"),
            (!self.forms.is_empty(), "--forms"),
            (!self.kernels.is_empty(), "--kernels"),
            (self.h_points.is_some(), "--h-points"),
            (self.repeats.is_some(), "--repeats"),
            (!self.integrators.is_empty(), "--integrators"),
            (self.safety.is_some(), "--safety"),
        ]
        .into_iter()
        .filter_map(|(g, n)| g.then_some(n))
        .collect()
    }

    /// Flags that cannot act together: --cfl-table takes only --json; --from redraws (only
    /// --plot); --config holds the whole study; --safety needs --integrators.
    fn check_combinations(&self) -> Result<()> {
        let flags = self.study_flags();
        if self.cfl_table {
            let others = [
                (self.config.is_some(), "--config"),
                (self.from.is_some(), "--from"),
                (self.plot.is_some(), "--plot"),
            ];
            let given = flags
                .iter()
                .copied()
                .chain(others.iter().filter_map(|(g, n)| g.then_some(*n)))
                .next();
            if let Some(f) = given {
                return Err(crate::query::not_in(
                    f,
                    "--cfl-table (the table is fixed: 1D, classical and total-lagrangian, h/Δx = 1.2 and 2.0, σ̄ = 0, every integrator and kernel; only --json applies)",
                ));
            }
        }
        if self.from.is_some() && (self.config.is_some() || !flags.is_empty() || self.json) {
            anyhow::bail!(
                "--from redraws stored data: it takes only --plot (not --config, --json or the study flags)"
            );
        }
        if self.config.is_some() && !flags.is_empty() {
            anyhow::bail!(
                "--config holds the whole study: do not combine it with {}",
                flags.join(", ")
            );
        }
        if let Some(s) = self.safety {
            // the value first: a safety out of range is that, whatever else is given
            sphstab::error::check_range("safety", s, 0.0, 1.0, false, true)?;
        }
        if self.safety.is_some() && self.integrators.is_empty() && self.config.is_none() {
            return Err(crate::query::not_in(
                "--safety",
                "no --integrators (it sets the Δt of the integrator rows)",
            ));
        }
        Ok(())
    }
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    a.check_combinations()?;
    let export = a
        .export
        .resolve(a.plot.is_some(), "no --plot (it sets the plot's formats)")?;
    let files = study::files(a.config.as_ref(), a.from.as_ref(), a.plot.as_ref(), &export);
    files.check()?;
    if a.cfl_table {
        if a.shard.is_some() || a.out.is_some() {
            anyhow::bail!("--cfl-table prints its table: not combined with --shard or --out");
        }
        let t = sphstab::studies::tradeoff::cfl::cfl_table()?;
        if a.json {
            println!("{}", units::json(&t, System::Normalised, false)?);
        } else {
            print!("{}", sphstab::studies::tradeoff::cfl::cfl_markdown(&t));
        }
        return Ok(());
    }
    if let Some(from) = &a.from {
        if a.shard.is_some() || a.out.is_some() {
            anyhow::bail!("--from redraws stored data: not combined with --shard or --out");
        }
        let rep: TradeoffReport = study::read_report(from)?;
        return study::write_plot(draw(&rep), (study::plot_path(a.plot.as_ref())?, &export));
    }
    let shard = crate::shard::flags(
        a.shard.as_deref(),
        a.out.as_ref(),
        &[(a.json, "--json"), (a.plot.is_some(), "--plot")],
    )?;
    let (cfg, config_out) = match &a.config {
        Some(p) => {
            let cfg = study::read_config(p, sphstab::studies::tradeoff::parse_config)?;
            let out = cfg.output.clone();
            if let Some(name) = &out {
                study::with_config_output(files, name).check()?;
            }
            (cfg, out)
        }
        None => {
            let d = TradeoffConfig::default();
            (
                TradeoffConfig {
                    dim: a.dim.unwrap_or(d.dim),
                    forms: a.forms.clone(),
                    kernels: a.kernels.clone(),
                    h_points: a.h_points.unwrap_or(d.h_points),
                    repeats: a.repeats.unwrap_or(d.repeats),
                    integrators: a.integrators.clone(),
                    safety: a.safety.unwrap_or(d.safety),
                    ..d
                },
                None,
            )
        }
    };
    let cfg = TradeoffConfig {
        budget: *budget,
        ..cfg
    };
    let study = TradeoffStudy {
        probe: Some(&crate::alloc::Probe),
    };
    if let Some((shard, out)) = shard {
        // a config's `output` (figure and data) is written by the merge
        return crate::shard::run(&study, &cfg, shard, &out);
    }
    let pb = progress::Bar::new(progress::wanted(a.json));
    let rep = sphstab::studies::shard::run_whole(&study, &cfg, pb.clone())?;
    pb.finish();
    output(
        &rep,
        a.out.as_deref(),
        a.json,
        a.plot.as_deref().map(|p| (p, &export)),
        config_out.as_deref(),
    )
}

/// Writes and prints a report (shared with `merge`): `--out` (JSON), `--plot`, a config's
/// `output` (the figure and its data in figures/), then the JSON (`--json`) or the tables.
pub fn output(
    rep: &TradeoffReport,
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
        draw,
        |r| {
            let mut t = sphstab::studies::tradeoff::table(r);
            if !r.integrator_rows.is_empty() {
                t += "\n";
                t += &sphstab::studies::tradeoff::integrator_table(r);
            }
            t + &format!(
                "{} configurations in {:.1} s ({} threads); scene: {}\n",
                r.rows.len() + r.integrator_rows.len(),
                r.runtime_s,
                r.threads,
                r.scene
            )
        },
    )
}
