//! `sphstab figures`: regenerate every figure from its config.

use anyhow::{Context, Result};
use sphstab::budget::Budget;
use std::path::PathBuf;

/// Flags of `figures`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Directory of figure configs (*.json).
    #[arg(long, default_value = "analysis/configs")]
    configs: PathBuf,
    /// Output directory for the SVG files. The figures are regenerated: an SVG of the same name
    /// there is replaced (no --force needed; never a config file).
    #[arg(long, default_value = "figures")]
    out: PathBuf,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(&a.configs)
        .with_context(|| format!("--configs: cannot read {}", a.configs.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("--out: cannot create {}", a.out.display()))?;
    // every config read and every output checked before the first figure is drawn
    let mut configs = Vec::with_capacity(files.len());
    let mut check = crate::files::Files::new();
    for f in &files {
        check = check.input("--configs", f);
    }
    for f in files {
        let name = f.display().to_string();
        let text = std::fs::read_to_string(&f).with_context(|| format!("cannot read {name}"))?;
        let cfg = sphstab::figures::FigureConfig {
            budget: *budget,
            ..sphstab::figures::parse(&name, &text)?
        };
        check = check.regenerated("--out", a.out.join(&cfg.output));
        configs.push((name, cfg));
    }
    check.check()?;
    for (name, cfg) in configs {
        let svg = sphstab::figures::render(&cfg).with_context(|| name.clone())?;
        let out = a.out.join(&cfg.output);
        std::fs::write(&out, svg).with_context(|| format!("cannot write {}", out.display()))?;
        println!("{name} -> {}", out.display());
    }
    Ok(())
}
