//! `sphstab tradeoff`: the speed/accuracy trade-off study (cost, accuracy, robustness of every
//! form × kernel × h/Δx), as a table, JSON and a Pareto figure.

use crate::progress;
use anyhow::{Context, Result};
use sphstab::tradeoff::{TradeoffConfig, TradeoffReport};
use std::path::PathBuf;

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
    /// A study config (JSON: dim, forms, kernels, h_points, repeats, output, note); its
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
}

/// Title of the Pareto figure.
pub fn title(rep: &TradeoffReport) -> String {
    format!(
        "speed/accuracy trade-off, {}D: every form × kernel × h (filled: stable at σ̄ = ±0.01)",
        rep.dim
    )
}

pub fn run(a: Args) -> Result<()> {
    if let Some(p) = &a.plot {
        crate::common::check_writable("--plot", p)?;
    }
    if let Some(from) = &a.from {
        let text = std::fs::read_to_string(from)
            .with_context(|| format!("--from: cannot read {}", from.display()))?;
        let rep: TradeoffReport =
            serde_json::from_str(&text).map_err(|e| sphstab::error::Error::Config {
                file: from.display().to_string(),
                msg: e.to_string(),
            })?;
        let path = a.plot.as_ref().ok_or_else(|| {
            sphstab::error::Error::Incompatible("--from needs --plot (where to draw)".into())
        })?;
        write_plot(&rep, path)?;
        return Ok(());
    }
    let (cfg, config_out) = match &a.config {
        Some(p) => {
            let text = std::fs::read_to_string(p)
                .with_context(|| format!("--config: cannot read {}", p.display()))?;
            let cfg = sphstab::tradeoff::parse_config(&p.display().to_string(), &text)?;
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
                ..Default::default()
            },
            None,
        ),
    };
    let total = sphstab::tradeoff::grid(&cfg)?.len();
    let pb = progress::bar(progress::wanted(a.json));
    let rep = sphstab::tradeoff::run(&cfg, Some(&crate::alloc::Probe), |d, t| {
        progress::set(&pb, d as f64 / t.max(1) as f64)
    })?;
    pb.finish_and_clear();
    if let Some(path) = &a.plot {
        write_plot(&rep, path)?;
    }
    if let Some(name) = config_out {
        let svg = PathBuf::from("figures").join(&name);
        write_plot(&rep, &svg)?;
        let data = svg.with_extension("json");
        std::fs::write(&data, serde_json::to_string_pretty(&rep)? + "\n")
            .with_context(|| format!("cannot write {}", data.display()))?;
        eprintln!("wrote {} and {}", svg.display(), data.display());
    }
    if a.json {
        println!("{}", serde_json::to_string(&rep)?);
    } else {
        print!("{}", sphstab::tradeoff::table(&rep));
        println!(
            "{} configurations in {:.1} s ({} threads); scene: {}",
            total, rep.runtime_s, rep.threads, rep.scene
        );
    }
    Ok(())
}

fn write_plot(rep: &TradeoffReport, path: &std::path::Path) -> Result<()> {
    let svg = sphstab::tradeoff::pareto_svg(rep, &title(rep))?;
    std::fs::write(path, svg)
        .with_context(|| format!("--plot: cannot write {}", path.display()))?;
    Ok(())
}
