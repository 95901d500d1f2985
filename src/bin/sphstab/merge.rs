//! `sphstab merge`: join the shards of a study computed with `<study> --shard i/n --out f`
//! (`atlas`, `pairing`, `tradeoff`, `art-stress`; [`crate::shard::merge`]).

use anyhow::Result;
use sphstab::budget::Budget;
use std::path::PathBuf;

/// Flags of `merge`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The shard files (JSON written by `atlas`, `pairing`, `tradeoff` or `art-stress` with
    /// `--shard i/n --out FILE`), all n of them.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Write the merged report (JSON, the bytes --json prints) here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the merged JSON on stdout instead of the summary or table.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    crate::shard::merge(&a.files, a.out.as_ref(), a.json, budget)
}
