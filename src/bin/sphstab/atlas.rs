//! `sphstab atlas`: the 1D stability atlas (forms × kernels × h × σ̄, max growth over κ), in
//! parallel, optionally one shard of a job array; `sphstab merge` joins the shards.

use crate::progress;
use anyhow::{Context, Result};
use sphstab::budget::Budget;
use sphstab::studies::atlas::{AtlasConfig, AtlasReport, Shard};
use std::path::PathBuf;

/// Flags of `atlas`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Comma-separated form names (default: all ten).
    #[arg(long, value_delimiter = ',')]
    forms: Vec<String>,
    /// Comma-separated kernel names (default: all eleven).
    #[arg(long, value_delimiter = ',')]
    kernels: Vec<String>,
    /// h/Δx values per kernel, evenly over its customary range, in [1, 4096].
    #[arg(long, default_value_t = 64)]
    h_points: usize,
    /// σ̄ values over [--stress-min, --stress-max], in [1, 4096].
    #[arg(long, default_value_t = 64)]
    stress_points: usize,
    /// Smallest σ̄ (≥ −0.999).
    #[arg(long, default_value_t = -0.5, allow_hyphen_values = true)]
    stress_min: f64,
    /// Largest σ̄.
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    stress_max: f64,
    /// κΔx points in (0, π], in [2, 1000000].
    #[arg(long, default_value_t = 512)]
    kappas: usize,
    /// Compute only shard i of n (0 ≤ i < n): cells c with c mod n = i. For job arrays, e.g.
    /// Slurm `--array=0-7` with `--shard $SLURM_ARRAY_TASK_ID/8`.
    #[arg(long)]
    shard: Option<String>,
    /// Write the atlas (JSON) to this file.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the atlas JSON on stdout instead of the summary.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    if let Some(p) = &a.out {
        crate::files::Files::new().output("--out", p).check()?;
    }
    let d = AtlasConfig::default();
    let cfg = AtlasConfig {
        forms: if a.forms.is_empty() { d.forms } else { a.forms },
        kernels: if a.kernels.is_empty() {
            d.kernels
        } else {
            a.kernels
        },
        h_points: a.h_points,
        stress_points: a.stress_points,
        stress_range: (a.stress_min, a.stress_max),
        kappas: a.kappas,
        budget: *budget,
    };
    let shard = a.shard.as_deref().map(Shard::parse).transpose()?;
    let pb = progress::Bar::new(progress::wanted(a.json));
    let rep = sphstab::studies::atlas::run(&cfg, shard, pb.clone())?;
    pb.finish();
    output(&rep, a.out.as_ref(), a.json)
}

/// Writes/prints an atlas (shared with `merge`).
pub fn output(rep: &AtlasReport, out: Option<&PathBuf>, json: bool) -> Result<()> {
    if let Some(path) = out {
        let f = std::fs::File::create(path)
            .with_context(|| format!("--out: cannot write {}", path.display()))?;
        serde_json::to_writer(std::io::BufWriter::new(f), rep)
            .with_context(|| format!("--out: cannot write {}", path.display()))?;
    }
    if json {
        println!("{}", serde_json::to_string(rep)?);
    } else {
        print!("{}", sphstab::studies::atlas::summary(rep));
        let what = match rep.shard {
            Some(s) => format!("shard {}/{}: ", s.index, s.count),
            None => String::new(),
        };
        println!(
            "{what}{} of {} cells ({} κ each) in {:.1} s on {} threads",
            rep.cells.len(),
            rep.total_cells,
            rep.config.kappas,
            rep.runtime_s,
            rep.threads
        );
        let terms = sphstab::studies::atlas::lattice_sum_terms(rep);
        println!(
            "lattice-sum limit: {terms:.3e} Fourier terms (κ points × neighbours within the support, over the cells) at 1 ns each = {:.2} s of CPU",
            terms * 1e-9
        );
    }
    Ok(())
}
