//! `sphstab dispersion`.

use crate::common::Config;
use anyhow::{Context, Result};

/// Flags of `dispersion`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// 1D: κ points in (0, π], in [2, 10000000]; 2D: points per segment of the symmetry path,
    /// in [2, 100000].
    #[arg(long, default_value_t = 256)]
    points: usize,
    /// Print one JSON document instead of a table.
    #[arg(long)]
    json: bool,
    /// Write an SVG plot of ω²Δx²/c² against κΔx/π to this file.
    #[arg(long)]
    plot: Option<std::path::PathBuf>,
}

pub fn run(a: Args) -> Result<()> {
    if let Some(p) = &a.plot {
        crate::common::check_writable("--plot", p)?;
    }
    if a.cfg.is_2d()? {
        return run2d(a);
    }
    a.cfg.reject_2d_flags()?;
    let q = a.cfg.query(a.points)?;
    let r = sphstab::analysis::dispersion(&q)?;
    if let Some(path) = &a.plot {
        let svg = sphstab::plot::dispersion_svg(&r)?;
        std::fs::write(path, svg)
            .with_context(|| format!("--plot: cannot write {}", path.display()))?;
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("# {}", r.header);
    println!(
        "{:>12} {:>16} {:>16} {:>14}",
        "κΔx/π", "ω²Δx²/c²", "continuum", "growth c/Δx"
    );
    for i in 0..r.kappa_dx.len() {
        println!(
            "{:>12.6} {:>16.9e} {:>16.9e} {:>14.6e}",
            r.kappa_dx[i] / std::f64::consts::PI,
            r.omega2[i],
            r.omega2_continuum[i],
            r.growth_rate[i]
        );
    }
    Ok(())
}

fn run2d(a: Args) -> Result<()> {
    use sphstab::plot::{Curve, lines_svg};
    let q = a.cfg.query2d()?;
    let r = sphstab::analysis2d::dispersion2d(&q, a.points)?;
    if let Some(path) = &a.plot {
        let col = |i: usize, v: &Vec<[f64; 2]>| v.iter().map(|b| b[i]).collect::<Vec<_>>();
        let curves = [
            Curve {
                label: "continuum S".into(),
                x: r.path.clone(),
                y: col(0, &r.omega2_continuum),
                dashed: true,
            },
            Curve {
                label: "continuum P".into(),
                x: r.path.clone(),
                y: col(1, &r.omega2_continuum),
                dashed: true,
            },
            Curve {
                label: format!("{} branch 1", r.form),
                x: r.path.clone(),
                y: col(0, &r.omega2),
                dashed: false,
            },
            Curve {
                label: format!("{} branch 2", r.form),
                x: r.path.clone(),
                y: col(1, &r.omega2),
                dashed: false,
            },
        ];
        let labels: Vec<String> = r
            .labels
            .iter()
            .map(|(l, s)| format!("{l} {s:.2}"))
            .collect();
        let dmax = r.omega2.iter().flatten().fold(0.0f64, |m, &y| m.max(y));
        let dmin = r.omega2.iter().flatten().fold(0.0f64, |m, &y| m.min(y));
        let svg = lines_svg(
            &format!(
                "{} / {} h = {}Δx, σ̄ = {} (2D, high-symmetry path)",
                r.form, r.kernel, r.h_over_dx, r.stress
            ),
            &format!(
                "arc length along the path, units 1/Δx ({})",
                labels.join(", ")
            ),
            sphstab::plot::OMEGA2_DESC,
            &curves,
            Some((dmin.min(0.0), 1.3 * dmax.max(1e-12))),
        )?;
        std::fs::write(path, svg)
            .with_context(|| format!("--plot: cannot write {}", path.display()))?;
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    let path: Vec<String> = r
        .labels
        .iter()
        .map(|(l, s)| format!("{l} (s = {s:.4})"))
        .collect();
    println!(
        "# {} / {} h/Δx {} σ̄ {} — path {}",
        r.form,
        r.kernel,
        r.h_over_dx,
        r.stress,
        path.join(" – ")
    );
    println!(
        "{:>8} {:>10} {:>10} {:>14} {:>14} {:>12}",
        "s", "κxΔx/π", "κyΔx/π", "ω²₁Δx²/c²", "ω²₂Δx²/c²", "growth"
    );
    for i in 0..r.path.len() {
        println!(
            "{:>8.4} {:>10.5} {:>10.5} {:>14.6e} {:>14.6e} {:>12.4e}",
            r.path[i],
            r.kappa[i][0] / std::f64::consts::PI,
            r.kappa[i][1] / std::f64::consts::PI,
            r.omega2[i][0] + 0.0,
            r.omega2[i][1] + 0.0,
            // below the growth tolerance is not growth (eigenvalue round-off)
            if r.growth_rate[i] > sphstab::vonneumann::classify::GROWTH_TOL {
                r.growth_rate[i]
            } else {
                0.0
            }
        );
    }
    Ok(())
}
