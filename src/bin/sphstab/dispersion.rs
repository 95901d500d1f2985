//! `sphstab dispersion`.

use crate::common::Config;
use anyhow::{Context, Result};
use sphstab::budget::Budget;

/// Flags of `dispersion`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// 1D: κ points in (0, π], in [2, 10000000]; 2D/3D: points per segment of the symmetry
    /// path, in [2, 100000].
    #[arg(long, default_value_t = 256)]
    points: usize,
    /// Print one JSON document instead of a table.
    #[arg(long)]
    json: bool,
    /// Write an SVG plot of ω²Δx²/c² against κΔx/π to this file; for a dissipative system also
    /// the damping rate Re s to FILE-damping.svg (same directory).
    #[arg(long)]
    plot: Option<std::path::PathBuf>,
}

/// The second figure of `--plot FILE.svg`: FILE-damping.svg next to it.
fn damping_path(p: &std::path::Path) -> std::path::PathBuf {
    let stem = p
        .file_stem()
        .map_or("dispersion".into(), |s| s.to_string_lossy());
    p.with_file_name(format!("{stem}-damping.svg"))
}

fn write_svg(path: &std::path::Path, svg: String) -> Result<()> {
    std::fs::write(path, svg).with_context(|| format!("--plot: cannot write {}", path.display()))
}

/// A damping cell of the table: Re s or ξ, "-" when the matching is ambiguous.
fn cell(v: Option<f64>, width: usize, prec: usize) -> String {
    match v {
        Some(x) => format!("{:>width$.prec$e}", x + 0.0),
        None => format!("{:>width$}", "-"),
    }
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    if let Some(p) = &a.plot {
        crate::common::check_writable("--plot", p)?;
    }
    match a.cfg.dim()? {
        2 => return run_nd::<2>(a, budget),
        3 => return run_nd::<3>(a, budget),
        _ => {}
    }
    a.cfg.reject_2d_flags()?;
    let q = a.cfg.query(a.points)?;
    let r = sphstab::analysis::dispersion(&q)?;
    if let Some(path) = &a.plot {
        let (title, form) = (r.header.to_string(), r.header.setup.form);
        write_svg(
            path,
            sphstab::plot::dispersion_svg(
                &title,
                form,
                &r.kappa_dx,
                &r.omega2,
                &r.omega2_continuum,
            )?,
        )?;
        if let Some(rate) = &r.damping_rate {
            let svg = sphstab::plot::damping_svg(&title, form, &r.kappa_dx, rate)?;
            write_svg(&damping_path(path), svg)?;
        }
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("# {}", r.header);
    let damped = r.damping_rate.as_ref().zip(r.damping_ratio.as_ref());
    let mut head = format!(
        "{:>12} {:>16} {:>16} {:>14}",
        "κΔx/π", "ω²Δx²/c²", "continuum", "growth c/Δx"
    );
    if damped.is_some() {
        head += &format!(" {:>14} {:>12}", "Re s c/Δx", "ξ");
    }
    println!("{head}");
    for i in 0..r.kappa_dx.len() {
        let mut line = format!(
            "{:>12.6} {:>16.9e} {:>16.9e} {:>14.6e}",
            r.kappa_dx[i] / std::f64::consts::PI,
            r.omega2[i],
            r.omega2_continuum[i],
            r.growth_rate[i]
        );
        if let Some((rate, xi)) = damped {
            line += &format!(" {} {}", cell(rate[i], 14, 6), cell(xi[i], 12, 4));
        }
        println!("{line}");
    }
    Ok(())
}

/// Names of the D branches of a 2D/3D dispersion plot (sorted by ω² at each wave vector; named
/// after the continuum's order, the shear branches below the longitudinal one).
fn branch_names(d: usize) -> Vec<&'static str> {
    match d {
        2 => vec![
            "lower branch (≈ transverse)",
            "upper branch (≈ longitudinal)",
        ],
        _ => vec![
            "lowest branch (≈ transverse)",
            "middle branch (≈ transverse)",
            "upper branch (≈ longitudinal)",
        ],
    }
}

fn run_nd<const D: usize>(a: Args, budget: &Budget) -> Result<()> {
    use sphstab::plot::{Curve, LinePlot};
    let q = a.cfg.query_nd::<D>(budget)?;
    let r = sphstab::analysis::dispersion2d(&q, a.points)?;
    if let Some(path) = &a.plot {
        let col = |i: usize, v: &Vec<Vec<f64>>| v.iter().map(|b| b[i]).collect::<Vec<_>>();
        let names = branch_names(D);
        let mut curves: Vec<Curve> = (0..D)
            .map(|b| Curve {
                label: format!("{}: {}", r.form, names[b]),
                x: r.path.clone(),
                y: col(b, &r.omega2),
                dashed: false,
            })
            .collect();
        curves.push(Curve {
            label: "continuum S (transverse)".into(),
            x: r.path.clone(),
            y: col(0, &r.omega2_continuum),
            dashed: true,
        });
        curves.push(Curve {
            label: "continuum P (longitudinal)".into(),
            x: r.path.clone(),
            y: col(D - 1, &r.omega2_continuum),
            dashed: true,
        });
        let ticks: Vec<(f64, String)> = r.labels.iter().map(|(l, s)| (*s, l.clone())).collect();
        let names_path: Vec<&str> = r.labels.iter().map(|(l, _)| l.as_str()).collect();
        let x_desc = format!(
            "wave vector along the path {} (arc length |Δκ|Δx, dimensionless)",
            names_path.join("–")
        );
        let title = format!(
            "{} / {} h = {}Δx, σ̄ = {}, {}, {} ({D}D)",
            r.form, r.kernel, r.h_over_dx, r.stress, q.material, q.lattice.kind
        );
        let svg = LinePlot {
            zero_line: true,
            x_ticks: Some(ticks.clone()),
            notes: vec![
                "Branches are sorted by ω² at each wave vector and named after the continuum's order (shear below longitudinal).".into(),
            ],
            ..LinePlot::new(&title, &x_desc, sphstab::plot::OMEGA2_DESC, curves)
        }
        .svg()?;
        write_svg(path, svg)?;
        if let Some(rate) = &r.damping_rate {
            let branches: Vec<(String, Vec<Option<f64>>)> = (0..D)
                .map(|b| {
                    (
                        format!("{}: {}", r.form, names[b]),
                        rate.iter().map(|row| row[b]).collect(),
                    )
                })
                .collect();
            let svg = sphstab::plot::damping_curves_svg(
                &format!("{title} — damping"),
                &x_desc,
                &r.path,
                &branches,
                Some(ticks),
            )?;
            write_svg(&damping_path(path), svg)?;
        }
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
    let axes = ["κxΔx/π", "κyΔx/π", "κzΔx/π"];
    let mut head = format!("{:>8}", "s");
    for ax in &axes[..D] {
        head += &format!(" {ax:>10}");
    }
    for b in 1..=D {
        head += &format!(" {:>14}", format!("ω²{b}Δx²/c²"));
    }
    head += &format!(" {:>12}", "growth");
    let damped = r.damping_rate.as_ref().zip(r.damping_ratio.as_ref());
    if damped.is_some() {
        for b in 1..=D {
            head += &format!(" {:>12}", format!("Re s{b}"));
        }
        for b in 1..=D {
            head += &format!(" {:>10}", format!("ξ{b}"));
        }
    }
    println!("{head}");
    for i in 0..r.path.len() {
        let mut line = format!("{:>8.4}", r.path[i]);
        for c in &r.kappa[i] {
            line += &format!(" {:>10.5}", c / std::f64::consts::PI);
        }
        for w in &r.omega2[i] {
            line += &format!(" {:>14.6e}", w + 0.0);
        }
        // below the growth tolerance is not growth (eigenvalue round-off)
        let g = if r.growth_rate[i] > sphstab::vonneumann::classify::GROWTH_TOL {
            r.growth_rate[i]
        } else {
            0.0
        };
        line += &format!(" {g:>12.4e}");
        if let Some((rate, xi)) = damped {
            for v in &rate[i] {
                line += &format!(" {}", cell(*v, 12, 4));
            }
            for v in &xi[i] {
                line += &format!(" {}", cell(*v, 10, 3));
            }
        }
        println!("{line}");
    }
    Ok(())
}
