//! `sphstab tradeoff`: the speed/accuracy trade-off study (cost, accuracy, robustness of every
//! form × kernel × h/Δx), as a table, JSON and a Pareto figure.

use crate::{progress, study};
use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::studies::tradeoff::{TradeoffConfig, TradeoffReport, TradeoffStudy};
use std::path::{Path, PathBuf};

/// Flags of `tradeoff`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Dimension: 1 (ten forms, periodic chain) or 2 (six forms, square lattice, hydro).
    #[arg(long, default_value_t = 1)]
    dim: u8,
    /// Comma-separated form names (default: every form of the dimension).
    #[arg(long, value_delimiter = ',')]
    forms: Vec<String>,
    /// Comma-separated kernel names (default: all eleven).
    #[arg(long, value_delimiter = ',')]
    kernels: Vec<String>,
    /// h/Δx values per kernel, evenly over its customary range, in [1, 64].
    #[arg(long, default_value_t = 3)]
    h_points: usize,
    /// Timed repeats of the wave scene (median reported), in [1, 100].
    #[arg(long, default_value_t = 3)]
    repeats: usize,
    /// Integrator dimension (1D): comma-separated integrator names or `all`; adds one row per
    /// configuration × integrator (cost per unit simulated time, phase and amplitude error per
    /// wavelength travelled).
    #[arg(long, value_delimiter = ',')]
    integrators: Vec<String>,
    /// Δt used for the integrator rows = safety × critical Δt, in (0, 1].
    #[arg(long, default_value_t = sphstab::studies::tradeoff::integrators::DEFAULT_SAFETY)]
    safety: f64,
    /// Print the critical CFL table (c Δt_crit/h per integrator × kernel, classical and
    /// total-lagrangian, h/Δx = 1.2 and 2.0, σ̄ = 0) as Markdown (JSON with --json) and stop.
    #[arg(long)]
    cfl_table: bool,
    /// A study config (JSON: dim, forms, kernels, h_points, repeats, output, note, integrators,
    /// safety); its
    /// `output` names the figure written to figures/ together with the data (same name, .json).
    /// Overrides the grid flags.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Re-draw the figure from stored data (a JSON written by --json or --config) without measuring.
    #[arg(long)]
    from: Option<PathBuf>,
    /// Print the JSON report instead of the table.
    #[arg(long)]
    json: bool,
    /// Write the Pareto figure (SVG) here.
    #[arg(long)]
    plot: Option<PathBuf>,
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

/// Title of the figure (the Pareto figure, or the integrator figure when the report has
/// integrator rows).
pub fn title(rep: &TradeoffReport) -> String {
    if rep.integrator_rows.is_empty() {
        format!(
            "speed/accuracy trade-off, {}D: every form × kernel × h (filled: stable at σ̄ = ±0.01)",
            rep.dim
        )
    } else {
        format!(
            "integrator trade-off, {}D, σ̄ = 0: cost per unit time vs phase error per wavelength (every kernel × h)",
            rep.dim
        )
    }
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    if let Some(p) = &a.plot {
        crate::common::check_writable("--plot", p)?;
    }
    if a.cfl_table {
        if a.shard.is_some() || a.out.is_some() {
            anyhow::bail!("--cfl-table prints its table: not combined with --shard or --out");
        }
        let t = sphstab::studies::tradeoff::cfl::cfl_table()?;
        if a.json {
            println!("{}", serde_json::to_string(&t)?);
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
        return study::write_plot(
            sphstab::studies::tradeoff::figure_svg(&rep, &title(&rep)),
            study::plot_path(a.plot.as_ref())?,
        );
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
            (cfg, out)
        }
        None => (
            TradeoffConfig {
                dim: a.dim,
                forms: a.forms.clone(),
                kernels: a.kernels.clone(),
                h_points: a.h_points,
                repeats: a.repeats,
                integrators: a.integrators.clone(),
                safety: a.safety,
                ..Default::default()
            },
            None,
        ),
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
        a.plot.as_deref(),
        config_out.as_deref(),
    )
}

/// Writes and prints a report (shared with `merge`): `--out` (JSON), `--plot`, a config's
/// `output` (the figure and its data in figures/), then the JSON (`--json`) or the tables.
pub fn output(
    rep: &TradeoffReport,
    out: Option<&Path>,
    json: bool,
    plot: Option<&Path>,
    config_out: Option<&str>,
) -> Result<()> {
    if let Some(path) = out {
        crate::shard::write_json(path, rep)?;
    }
    if let Some(path) = plot {
        study::write_plot(
            sphstab::studies::tradeoff::figure_svg(rep, &title(rep)),
            path,
        )?;
    }
    if let Some(name) = config_out {
        study::write_figure_and_data(rep, name, |r| {
            sphstab::studies::tradeoff::figure_svg(r, &title(r))
        })?;
    }
    if json {
        println!("{}", serde_json::to_string(rep)?);
    } else {
        print!("{}", sphstab::studies::tradeoff::table(rep));
        if !rep.integrator_rows.is_empty() {
            println!();
            print!("{}", sphstab::studies::tradeoff::integrator_table(rep));
        }
        println!(
            "{} configurations in {:.1} s ({} threads); scene: {}",
            rep.rows.len() + rep.integrator_rows.len(),
            rep.runtime_s,
            rep.threads,
            rep.scene
        );
    }
    Ok(())
}
