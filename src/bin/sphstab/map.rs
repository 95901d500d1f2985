//! `sphstab map`: 2D stability map, growth rate over (κx, κy) as a heat map.

use crate::common::Config;
use anyhow::{Context, Result};

/// Flags of `map`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// Wave vectors per direction over [−π, π]² (n × n), in [2, 1024].
    #[arg(long, default_value_t = 128)]
    n: usize,
    /// Print one JSON document (kx, ky, growth) instead of a summary.
    #[arg(long)]
    json: bool,
    /// Write the heat map SVG to this file.
    #[arg(long)]
    plot: Option<std::path::PathBuf>,
}

pub fn run(a: Args) -> Result<()> {
    if a.cfg.dim.is_some_and(|d| d != 2) {
        return Err(crate::query::not_in(
            "--dim other than 2",
            "map (the map is over the 2D zone; omit --dim)",
        ));
    }
    if let Some(p) = &a.plot {
        crate::common::check_writable("--plot", p)?;
    }
    let mut cfg = a.cfg.clone();
    cfg.dim = Some(2);
    let q = cfg.query2d()?;
    let t = std::time::Instant::now();
    let m = sphstab::analysis2d::growth_map(&q, a.n)?;
    let secs = t.elapsed().as_secs_f64();
    if let Some(path) = &a.plot {
        let pi = std::f64::consts::PI;
        let xs: Vec<f64> = m.kx.iter().map(|k| k / pi).collect();
        let ys: Vec<f64> = m.ky.iter().map(|k| k / pi).collect();
        let svg = sphstab::plot::heatmap_svg(
            &format!(
                "growth rate (c/Δx): {} / {} h = {}Δx, σ̄ = {}; max {:.4} on this {}×{} grid",
                q.form.name(),
                q.kernel.name(),
                q.h_over_dx,
                q.stress,
                m.growth.iter().flatten().fold(0.0f64, |x, &y| x.max(y)),
                a.n,
                a.n
            ),
            "κxΔx / π",
            "κyΔx / π",
            &xs,
            &ys,
            &m.growth,
        )?;
        std::fs::write(path, svg)
            .with_context(|| format!("--plot: cannot write {}", path.display()))?;
    }
    if a.json {
        println!("{}", serde_json::to_string(&m)?);
        return Ok(());
    }
    let gmax = m.growth.iter().flatten().fold(0.0f64, |x, &y| x.max(y));
    println!(
        "{}×{} wave vectors (cell centres of [−π, π]², not the first-zone grid of `query --dim 2`, so maxima differ by the resolution) in {:.3} s; max growth rate {:.6} c/Δx",
        a.n, a.n, secs, gmax
    );
    Ok(())
}
