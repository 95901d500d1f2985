//! `sphstab atlas`: the 1D stability atlas (forms × kernels × h × σ̄, max growth over κ), in
//! parallel, optionally one shard of a job array ([`crate::shard`]); `sphstab merge` joins the
//! shards.

use crate::progress;
use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::studies::atlas::{AtlasConfig, AtlasReport, AtlasStudy};
use sphstab::units::System;
use std::path::{Path, PathBuf};

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
    /// Compute only shard i of n (0 ≤ i < n): the cells c with c mod n = i, written to --out
    /// for `sphstab merge`, which gives the summary and JSON of all the shards. For job arrays:
    /// analysis/cluster/study_array.sh, or Slurm `--array=0-7` with
    /// `--shard $SLURM_ARRAY_TASK_ID/8`.
    #[arg(long)]
    shard: Option<String>,
    /// Write the atlas JSON here (the bytes --json prints); with --shard, the shard.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the atlas JSON on stdout instead of the summary.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let shard = crate::shard::flags(a.shard.as_deref(), a.out.as_ref(), &[(a.json, "--json")])?;
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
    if let Some((shard, out)) = shard {
        return crate::shard::run(&AtlasStudy, &cfg, shard, &out);
    }
    let pb = progress::Bar::new(progress::wanted(a.json));
    let rep = sphstab::studies::atlas::run(&cfg, pb.clone())?;
    pb.finish();
    output(&rep, a.out.as_deref(), a.json)
}

/// Writes/prints an atlas (shared with `merge`): `--out` (JSON), then the JSON (`--json`) or
/// the summary.
pub fn output(rep: &AtlasReport, out: Option<&Path>, json: bool) -> Result<()> {
    if let Some(path) = out {
        crate::shard::write_json(path, &sphstab::units::with_units(rep, System::Normalised)?)?;
    }
    if json {
        println!("{}", sphstab::units::json(rep, System::Normalised, false)?);
    } else {
        print!("{}", sphstab::studies::atlas::summary(rep));
        println!(
            "{} cells ({} κ each) in {:.1} s on {} threads",
            rep.total_cells, rep.config.kappas, rep.runtime_s, rep.threads
        );
        let terms = sphstab::studies::atlas::lattice_sum_terms(rep);
        println!(
            "lattice-sum limit: {terms:.3e} Fourier terms (κ points × neighbours within the support, over the cells) at 1 ns each = {:.2} s of CPU",
            terms * 1e-9
        );
    }
    Ok(())
}
