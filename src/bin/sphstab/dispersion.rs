//! `sphstab dispersion`.

use crate::common::Config;
use anyhow::{Context, Result};
use sphstab::analysis::DispersionReport;
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
        crate::files::Files::new().output("--plot", p).check()?;
    }
    if a.cfg.grid.is_some() {
        return Err(crate::query::not_in(
            "--grid",
            "dispersion (it samples the high-symmetry path: use --points)",
        ));
    }
    crate::common::refuse(
        "dispersion",
        &[
            (
                "--dt",
                a.cfg.dt.is_some(),
                "ω² is semi-discrete; the check at a Δt is query --dt or timestep --dt",
            ),
            (
                "--av-beta",
                a.cfg.av_beta.is_some(),
                crate::common::AV_BETA_WHY,
            ),
        ],
    )?;
    let dim = a.cfg.dim()?;
    crate::by_dim!(dim, run_in(a, budget))
}

/// Names of the D branches of a dispersion plot (sorted by ω² at each wave vector; named after
/// the continuum's order, the shear branches below the longitudinal one).
fn branch_names(d: usize) -> Vec<&'static str> {
    match d {
        1 => vec!["mechanical branch"],
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

/// `--plot`: ω² against κΔx/π with the continuum in 1D, along the high-symmetry path with both
/// continuum branches for D ≥ 2; the damping rate to FILE-damping.svg for dissipative systems.
fn plot<const D: usize>(path: &std::path::Path, r: &DispersionReport) -> Result<()> {
    use sphstab::plot::{Curve, LinePlot};
    if r.damping_rate.is_some() {
        // the second figure of a dissipative system, checked before either is written
        crate::files::Files::new()
            .output("--plot", path)
            .output("--plot (its damping figure)", damping_path(path))
            .check()?;
    }
    let title = r.header.to_string();
    let form = r.header.setup.form;
    if D == 1 {
        let k = r.path.clone();
        let svg = sphstab::plot::dispersion_svg(
            &title,
            form,
            &k,
            &r.omega2_branch(0),
            &r.continuum_branch(0),
        )?;
        write_svg(path, svg)?;
        if let Some(rate) = r.damping_rate_branch(0) {
            let svg = sphstab::plot::damping_svg(&title, form, &k, &rate)?;
            write_svg(&damping_path(path), svg)?;
        }
        return Ok(());
    }
    let names = branch_names(D);
    let mut curves: Vec<Curve> = (0..D)
        .map(|b| Curve {
            label: format!("{form}: {}", names[b]),
            x: r.path.clone(),
            y: r.omega2_branch(b),
            dashed: false,
        })
        .collect();
    curves.push(Curve {
        label: "continuum S (transverse)".into(),
        x: r.path.clone(),
        y: r.continuum_branch(0),
        dashed: true,
    });
    curves.push(Curve {
        label: "continuum P (longitudinal)".into(),
        x: r.path.clone(),
        y: r.continuum_branch(D - 1),
        dashed: true,
    });
    let ticks: Vec<(f64, String)> = r.labels.iter().map(|(l, s)| (*s, l.clone())).collect();
    let names_path: Vec<&str> = r.labels.iter().map(|(l, _)| l.as_str()).collect();
    let x_desc = format!(
        "wave vector along the path {} (arc length |Δκ|Δx, dimensionless)",
        names_path.join("–")
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
    if r.damping_rate.is_some() {
        let branches: Vec<(String, Vec<Option<f64>>)> = (0..D)
            .map(|b| {
                (
                    format!("{form}: {}", names[b]),
                    r.damping_rate_branch(b).unwrap_or_default(),
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
    Ok(())
}

fn run_in<const D: usize>(a: Args, budget: &Budget) -> Result<()> {
    let q = a.cfg.query::<D>(budget)?;
    let r = sphstab::analysis::dispersion(&q, a.points)?;
    if let Some(path) = &a.plot {
        plot::<D>(path, &r)?;
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
    println!("# {} — path {}", r.header, path.join(" – "));
    let axes = ["κxΔx/π", "κyΔx/π", "κzΔx/π"];
    let mut head = String::new();
    if D == 1 {
        head += &format!("{:>10}", "κΔx/π");
    } else {
        head += &format!("{:>8}", "s");
        for ax in &axes[..D] {
            head += &format!(" {ax:>10}");
        }
    }
    let sub = |b: usize| if D == 1 { String::new() } else { b.to_string() };
    for b in 1..=D {
        head += &format!(" {:>14}", format!("ω²{}Δx²/c²", sub(b)));
    }
    for b in 1..=D {
        head += &format!(" {:>14}", format!("continuum{}", sub(b)));
    }
    head += &format!(" {:>12}", "growth c/Δx");
    let damped = r.damping_rate.as_ref().zip(r.damping_ratio.as_ref());
    if damped.is_some() {
        for b in 1..=D {
            head += &format!(" {:>12}", format!("Re s{} c/Δx", sub(b)));
        }
        for b in 1..=D {
            head += &format!(" {:>10}", format!("ξ{}", sub(b)));
        }
    }
    println!("{head}");
    for i in 0..r.path.len() {
        let mut line = String::new();
        if D > 1 {
            line += &format!("{:>8.4} ", r.path[i]);
        }
        let ks: Vec<String> = r.kappa[i]
            .iter()
            .map(|c| format!("{:>10.6}", c / std::f64::consts::PI))
            .collect();
        line += &ks.join(" ");
        for w in r.omega2[i].iter().chain(&r.omega2_continuum[i]) {
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
