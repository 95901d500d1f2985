//! `sphstab merge`: join the shards of an atlas computed with `atlas --shard i/n --out f`, or
//! of another study computed with `<study> --shard i/n --out f` ([`crate::shard::merge`]).

use anyhow::{Context, Result};
use sphstab::budget::Budget;
use sphstab::studies::atlas::AtlasReport;
use std::path::PathBuf;

/// Flags of `merge`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The shard files (JSON written by `atlas`, `pairing`, `tradeoff` or `art-stress` with
    /// `--shard i/n --out FILE`), all n of them.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Write the merged atlas (JSON) here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the merged JSON on stdout instead of the summary.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    if crate::shard::merge(&a.files, a.out.as_ref(), a.json, budget)? {
        return Ok(());
    }
    if let Some(p) = &a.out {
        a.files
            .iter()
            .fold(crate::files::Files::new(), |f, p| f.input("<FILES>", p))
            .output("--out", p)
            .check()?;
    }
    // every shard is held in memory as text and parsed (~3× its size), before the merge
    let total: u64 = a
        .files
        .iter()
        .map(|f| std::fs::metadata(f).map(|m| m.len()).unwrap_or(0))
        .sum();
    budget.memory(
        "<FILES>",
        &format!("merging {} shard files", a.files.len()),
        4.0 * total as f64,
    )?;
    let mut parts = Vec::with_capacity(a.files.len());
    for f in &a.files {
        let name = f.display().to_string();
        // bounded read: a device or a growing file cannot exhaust the memory budget
        let cap = (budget.max_memory / 4.0) as u64;
        let mut buf = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(
                std::fs::File::open(f).with_context(|| format!("cannot read {name}"))?,
                cap + 1,
            ),
            &mut buf,
        )
        .with_context(|| format!("cannot read {name}"))?;
        if buf.len() as u64 > cap {
            anyhow::bail!("{name}: larger than a quarter of --max-memory, not an atlas shard");
        }
        let text = String::from_utf8(buf).map_err(|_| anyhow::anyhow!("{name}: not UTF-8 text"))?;
        let r: AtlasReport = sphstab::error::parse_json(&name, &text)?;
        parts.push((name, r));
    }
    let rep = sphstab::studies::atlas::merge(&parts, budget)?;
    crate::atlas::output(&rep, a.out.as_ref(), a.json)
}
