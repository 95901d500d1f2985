//! `--shard i/n` of the studies that run longer than a minute (`atlas`, `pairing`,
//! `tradeoff`, `art-stress`) and `sphstab merge` of their shards: one shard computed into its
//! file (`--out`), the files read back (bounded by the memory budget) and merged into the
//! report the unsharded command prints and writes. The library side is
//! [`sphstab::studies::shard`]; `analysis/cluster/study_array.sh` runs a study this way.

use crate::progress;
use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphstab::budget::Budget;
use sphstab::studies::art_stress::ArtStressStudy;
use sphstab::studies::atlas::AtlasStudy;
use sphstab::studies::pairing::PairingStudy;
use sphstab::studies::shard::{Shard, ShardOf, Sharded};
use sphstab::studies::tradeoff::TradeoffStudy;
use std::path::{Path, PathBuf};

/// Checks the shard flags of a study command: `--shard i/n` needs `--out` (the shard file)
/// and takes none of the report's outputs (`others`: whether each was given, and its flag),
/// which `sphstab merge` makes from all the shards. The shard and its file, if one is asked
/// for.
pub fn flags(
    shard: Option<&str>,
    out: Option<&PathBuf>,
    others: &[(bool, &str)],
) -> Result<Option<(Shard, PathBuf)>> {
    let Some(s) = shard else {
        if let Some(p) = out {
            crate::files::Files::new().output("--out", p).check()?;
        }
        return Ok(None);
    };
    let shard = Shard::parse(s)?;
    if let Some((_, flag)) = others.iter().find(|o| o.0) {
        bail!(
            "--shard writes one shard to --out: not combined with {flag} (`sphstab merge` of all the shards gives the report)"
        );
    }
    let Some(p) = out else {
        bail!("--shard needs --out FILE (where the shard is written, for `sphstab merge`)");
    };
    crate::files::Files::new().output("--out", p).check()?;
    Ok(Some((shard, p.clone())))
}

/// Writes `value` as one line of JSON to `path` (the bytes `--json` prints).
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let text = serde_json::to_string(value)? + "\n";
    std::fs::write(path, text).with_context(|| format!("--out: cannot write {}", path.display()))
}

/// Computes shard `shard` of `study` and writes it to `out`; says so on stdout.
pub fn run<S: Sharded>(study: &S, cfg: &S::Config, shard: Shard, out: &Path) -> Result<()> {
    let pb = progress::Bar::new(progress::wanted(false));
    let file = sphstab::studies::shard::run_shard(study, cfg, shard, pb.clone())?;
    pb.finish();
    write_json(out, &file)?;
    println!(
        "{} shard {}/{}: {} of {} cells in {:.1} s ({} threads), written to {}",
        S::STUDY,
        shard.index,
        shard.count,
        file.cells.len(),
        file.total_cells,
        file.runtime_s,
        file.threads,
        out.display()
    );
    Ok(())
}

/// Reads a file given to `merge`, bounded: a device or a growing file cannot exhaust the
/// memory budget.
fn read_bounded(path: &Path, budget: &Budget) -> Result<String> {
    let name = path.display().to_string();
    let cap = (budget.max_memory / 4.0) as u64;
    let mut buf = Vec::new();
    std::io::Read::read_to_end(
        &mut std::io::Read::take(
            std::fs::File::open(path).with_context(|| format!("cannot read {name}"))?,
            cap + 1,
        ),
        &mut buf,
    )
    .with_context(|| format!("cannot read {name}"))?;
    if buf.len() as u64 > cap {
        bail!("{name}: larger than a quarter of --max-memory, not a shard file");
    }
    String::from_utf8(buf).map_err(|_| anyhow::anyhow!("{name}: not UTF-8 text"))
}

/// Parses every file as a shard of `study`.
fn parse_all<S: Sharded>(texts: Vec<(String, String)>) -> Result<Vec<(String, ShardOf<S>)>> {
    texts
        .into_iter()
        .map(|(name, text)| {
            let s = sphstab::studies::shard::parse::<S>(&name, &text)?;
            Ok((name, s))
        })
        .collect()
}

/// `sphstab merge` of a study's shard files: each file checked and parsed as a shard of the
/// study the first one names. Prints and writes what the unsharded command does: the table or
/// `--json`, `--out` (the same JSON), and for a study run from a config with an `output`, the
/// figure and its data in figures/.
pub fn merge(files: &[PathBuf], out: Option<&PathBuf>, json: bool, budget: &Budget) -> Result<()> {
    let mut io = files
        .iter()
        .fold(crate::files::Files::new(), |f, p| f.input("<FILES>", p));
    if let Some(p) = out {
        io = io.output("--out", p);
    }
    io.check()?;
    let Some(first) = files.first() else {
        bail!("<FILES>: give the shard files");
    };
    // every shard is held in memory as text and parsed (~3× its size), before the merge
    let total: u64 = files
        .iter()
        .map(|f| std::fs::metadata(f).map(|m| m.len()).unwrap_or(0))
        .sum();
    budget.memory(
        "<FILES>",
        &format!("merging {} shard files", files.len()),
        4.0 * total as f64,
    )?;
    let mut texts = Vec::with_capacity(files.len());
    for f in files {
        texts.push((f.display().to_string(), read_bounded(f, budget)?));
    }
    let study = sphstab::studies::shard::study_of(&texts[0].0, &texts[0].1)?;
    let out = out.map(PathBuf::as_path);
    match study.as_str() {
        AtlasStudy::STUDY => {
            let parts = parse_all::<AtlasStudy>(texts)?;
            let rep = sphstab::studies::shard::merge(&AtlasStudy, parts)?;
            crate::atlas::output(&rep, out, json)?;
        }
        PairingStudy::STUDY => {
            let parts = parse_all::<PairingStudy>(texts)?;
            let output = parts[0].1.config.output.clone();
            let rep = sphstab::studies::shard::merge(&PairingStudy, parts)?;
            crate::pairing::output(&rep, out, json, None, output.as_deref())?;
        }
        TradeoffStudy::STUDY => {
            let parts = parse_all::<TradeoffStudy>(texts)?;
            let output = parts[0].1.config.output.clone();
            let rep = sphstab::studies::shard::merge(&TradeoffStudy::default(), parts)?;
            crate::tradeoff::output(&rep, out, json, None, output.as_deref())?;
        }
        ArtStressStudy::STUDY => {
            let parts = parse_all::<ArtStressStudy>(texts)?;
            let rep = sphstab::studies::shard::merge(&ArtStressStudy, parts)?;
            crate::art_stress::output(&rep, out, json, None)?;
        }
        other => bail!(
            "{}: a shard of the `{other}` study, which this sphstab cannot merge (atlas, pairing, tradeoff, art-stress)",
            first.display()
        ),
    }
    Ok(())
}
