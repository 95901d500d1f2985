//! `sphstab merge`: join the shards of an atlas computed with `atlas --shard i/n --out f`.

use anyhow::{Context, Result};
use sphstab::atlas::AtlasReport;
use std::path::PathBuf;

/// Flags of `merge`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The shard files (JSON written by `atlas --shard i/n --out FILE`), all n of them.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Write the merged atlas (JSON) here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the merged JSON on stdout instead of the summary.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<()> {
    if let Some(p) = &a.out {
        crate::common::check_writable("--out", p)?;
    }
    let mut parts = Vec::with_capacity(a.files.len());
    for f in &a.files {
        let name = f.display().to_string();
        let text = std::fs::read_to_string(f).with_context(|| format!("cannot read {name}"))?;
        let r: AtlasReport =
            serde_json::from_str(&text).map_err(|e| sphstab::error::Error::Config {
                file: name.clone(),
                msg: e.to_string(),
            })?;
        parts.push((name, r));
    }
    let rep = sphstab::atlas::merge(&parts)?;
    crate::atlas::output(&rep, a.out.as_ref(), a.json)
}
