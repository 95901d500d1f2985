//! `sphstab dispersion`.

use crate::common::Config;
use anyhow::Result;
use sphstab::analysis::DispersionReport;
use sphstab::budget::Budget;
use sphstab::units::{self, System};

/// Flags of `dispersion`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// 1D: κ points in (0, π], in [2, 10000000]; 2D/3D: points per segment of the symmetry
    /// path, in [2, 100000].
    #[arg(long, default_value_t = 256)]
    points: usize,
    /// Print one JSON document instead of a table (its "units" name the unit of every field).
    #[arg(long)]
    json: bool,
    /// Write an SVG plot of ω²Δx²/c² against κΔx/π to this file; for a dissipative system also
    /// the damping rate Re s to FILE-damping.svg (same directory). With --vary or a list in
    /// --form/--kernel, every series on one figure.
    #[arg(long)]
    plot: Option<std::path::PathBuf>,
    /// Only this range of the abscissa, LO,HI: 1D κΔx/π in [0, 1]; 2D/3D the path coordinate
    /// s of the table's first column (the plot's abscissa). Table rows and plot.
    #[arg(long = "kappa-range", value_name = "LO,HI", allow_hyphen_values = true)]
    kappa_range: Option<String>,
    /// Vertical range of the plot, LO,HI in ω²Δx²/c² (default: the data's within the
    /// abscissa range). Needs --plot.
    #[arg(long = "y-range", value_name = "LO,HI", allow_hyphen_values = true)]
    y_range: Option<String>,
    #[command(flatten)]
    export: crate::export::ExportArgs,
    #[command(flatten)]
    vary: crate::vary::VaryArgs,
}

/// A `LO,HI` flag: two finite numbers, LO < HI.
fn range(flag: &str, v: &Option<String>) -> Result<Option<(f64, f64)>> {
    let Some(v) = v else { return Ok(None) };
    let bad = || {
        anyhow::Error::from(sphstab::error::Error::Incompatible(
            format!("{flag} {v}: expected LO,HI, two finite numbers with LO < HI").into(),
        ))
    };
    let (lo, hi) = v.split_once(',').ok_or_else(bad)?;
    let (lo, hi): (f64, f64) = (
        lo.trim().parse().map_err(|_| bad())?,
        hi.trim().parse().map_err(|_| bad())?,
    );
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return Err(bad());
    }
    Ok(Some((lo, hi)))
}

/// The second figure of `--plot FILE.svg`: FILE-damping.svg next to it.
fn damping_path(p: &std::path::Path) -> std::path::PathBuf {
    let stem = p
        .file_stem()
        .map_or("dispersion".into(), |s| s.to_string_lossy());
    p.with_file_name(format!("{stem}-damping.svg"))
}

/// A damping cell of the table: Re s or ξ, "-" when the matching is ambiguous.
fn cell(v: Option<f64>, width: usize, prec: usize) -> String {
    match v {
        Some(x) => format!("{:>width$.prec$e}", x + 0.0),
        None => format!("{:>width$}", "-"),
    }
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let export = a
        .export
        .resolve(a.plot.is_some(), "no --plot (it sets the plot's formats)")?;
    if let Some(p) = &a.plot {
        export
            .output(crate::files::Files::new(), "--plot", p)
            .check()?;
    }
    if a.cfg.grid.is_some() {
        return Err(crate::query::not_in(
            "--grid",
            "dispersion (it samples the high-symmetry path: use --points)",
        ));
    }
    if a.y_range.is_some() && a.plot.is_none() {
        return Err(crate::query::not_in(
            "--y-range",
            "no --plot (it sets the plot's vertical range)",
        ));
    }
    a.cfg
        .spec()
        .check_for(sphstab::analysis::spec::Command::Dispersion)?;
    let dim = a.cfg.dim()?;
    crate::by_dim!(dim, run_in(a, budget, &export))
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
/// continuum branches for D ≥ 2, every series on one figure (named by its label; a single
/// question by its form); the damping rate to FILE-damping.svg for dissipative systems.
fn plot<const D: usize>(
    path: &std::path::Path,
    export: &crate::export::Export,
    title: &str,
    series: &[(String, DispersionReport)],
    x_range: Option<(f64, f64)>,
    y_range: Option<(f64, f64)>,
) -> Result<()> {
    use sphstab::plot::{Curve, LinePlot};
    if series.iter().any(|(_, r)| r.damping_rate.is_some()) {
        // the second figure of a dissipative system, checked before either is written
        let files = export.output(crate::files::Files::new(), "--plot", path);
        export
            .output(files, "--plot (its damping figure)", &damping_path(path))
            .check()?;
    }
    let pi = std::f64::consts::PI;
    let single = series.len() == 1;
    let name = |label: &str, r: &DispersionReport| {
        if single {
            r.header.setup.form.to_string()
        } else {
            label.to_string()
        }
    };
    let xs = |r: &DispersionReport| -> Vec<f64> {
        if D == 1 {
            r.path.iter().map(|k| k / pi).collect()
        } else {
            r.path.clone()
        }
    };
    let names = branch_names(D);
    let mut curves: Vec<Curve> = Vec::new();
    for (label, r) in series {
        for (b, bname) in names.iter().enumerate() {
            curves.push(Curve {
                label: if D == 1 {
                    format!("{} (numeric engine)", name(label, r))
                } else {
                    format!("{}: {bname}", name(label, r))
                },
                x: xs(r),
                y: r.omega2_branch(b),
                dashed: false,
            });
        }
    }
    // the continuum once per distinct one (it depends on the stress and the material only)
    let mut continua: Vec<(usize, &str, &DispersionReport)> = Vec::new();
    for (i, (label, r)) in series.iter().enumerate() {
        if !continua
            .iter()
            .any(|(_, _, c)| c.path == r.path && c.omega2_continuum == r.omega2_continuum)
        {
            continua.push((i, label, r));
        }
    }
    let own = continua.len() > 1;
    for (_, label, r) in &continua {
        let of = if own {
            format!(" of {label}")
        } else {
            String::new()
        };
        if D == 1 {
            curves.push(Curve {
                label: format!("continuum (1 + σ̄)(κΔx)²  [B00 eq 32]{of}"),
                x: xs(r),
                y: r.continuum_branch(0),
                dashed: true,
            });
        } else {
            for (b, what) in [(0, "S (transverse)"), (D - 1, "P (longitudinal)")] {
                curves.push(Curve {
                    label: format!("continuum {what}{of}"),
                    x: xs(r),
                    y: r.continuum_branch(b),
                    dashed: true,
                });
            }
        }
    }
    let first = &series[0].1;
    let ticks: Option<Vec<(f64, String)>> =
        (D > 1).then(|| first.labels.iter().map(|(l, s)| (*s, l.clone())).collect());
    let x_desc = if D == 1 {
        sphstab::plot::KAPPA_DESC.to_string()
    } else {
        let names_path: Vec<&str> = first.labels.iter().map(|(l, _)| l.as_str()).collect();
        format!(
            "wave vector along the path {} (arc length |Δκ|Δx, dimensionless)",
            names_path.join("–")
        )
    };
    let svg = LinePlot {
        names: sphstab::studies::series_names(),
        zero_line: true,
        x_ticks: ticks.clone(),
        x_range,
        y_range,
        notes: if D > 1 {
            vec!["Branches are sorted by ω² at each wave vector and named after the continuum's order (shear below longitudinal).".into()]
        } else {
            Vec::new()
        },
        ..LinePlot::new(title, &x_desc, sphstab::plot::OMEGA2_DESC, curves)
    }
    .svg()?;
    export.write("--plot", &svg, path)?;
    if series.iter().any(|(_, r)| r.damping_rate.is_some()) {
        if series.iter().any(|(_, r)| r.path != first.path) {
            eprintln!(
                "note: no damping plot: the series sample different wave vectors (a varied lattice)"
            );
            return Ok(());
        }
        let mut branches: Vec<(String, Vec<Option<f64>>)> = Vec::new();
        for (label, r) in series {
            for (b, bname) in names.iter().enumerate() {
                if let Some(rate) = r.damping_rate_branch(b) {
                    branches.push((
                        if D == 1 {
                            format!("{} (eigenvalues of J(κ))", name(label, r))
                        } else {
                            format!("{}: {bname}", name(label, r))
                        },
                        rate,
                    ));
                }
            }
        }
        let svg = LinePlot {
            names: sphstab::studies::series_names(),
            x_range,
            ..sphstab::plot::damping_plot(
                &format!("{title} — damping"),
                &x_desc,
                &xs(first),
                &branches,
                ticks,
            )
        }
        .svg()?;
        export.write("--plot", &svg, &damping_path(path))?;
    }
    Ok(())
}

fn run_in<const D: usize>(a: Args, budget: &Budget, export: &crate::export::Export) -> Result<()> {
    let x_range = range("--kappa-range", &a.kappa_range)?;
    let y_range = range("--y-range", &a.y_range)?;
    if D == 1
        && let Some((lo, hi)) = x_range
        && !(lo >= 0.0 && hi <= 1.0)
    {
        return Err(sphstab::error::Error::OutOfRange {
            field: "kappa-range",
            value: if lo < 0.0 { lo } else { hi },
            range: "1D: κΔx/π within [0, 1]".into(),
        }
        .into());
    }
    let compare = crate::vary::active(&a.cfg, &a.vary);
    let list = crate::vary::series(&a.cfg, &a.vary, false)?;
    // every question is checked before the first is answered
    let questions = list
        .iter()
        .map(|s| s.cfg.query::<D>(budget))
        .collect::<Result<Vec<_>>>()?;
    let mut reports = Vec::with_capacity(list.len());
    for (s, q) in list.iter().zip(&questions) {
        reports.push((s.label.clone(), sphstab::analysis::dispersion(q, a.points)?));
    }
    if let Some(path) = &a.plot {
        let title = if compare {
            format!("dispersion: {}", vary_title(&reports))
        } else {
            reports[0].1.header.to_string()
        };
        plot::<D>(path, export, &title, &reports, x_range, y_range)?;
    }
    if a.json {
        if compare {
            let series: Vec<serde_json::Value> = reports
                .iter()
                .map(|(label, r)| serde_json::json!({"label": label, "dispersion": r}))
                .collect();
            let doc = serde_json::json!({ "series": series });
            println!("{}", units::json(&doc, System::Normalised, true)?);
        } else {
            println!("{}", units::json(&reports[0].1, System::Normalised, true)?);
        }
        return Ok(());
    }
    for (label, r) in &reports {
        if compare {
            println!("## {label}");
        }
        print_table::<D>(r, x_range);
    }
    Ok(())
}

/// The title of a comparison: the labels.
fn vary_title(reports: &[(String, DispersionReport)]) -> String {
    let labels: Vec<&str> = reports.iter().map(|(l, _)| l.as_str()).collect();
    labels.join(" | ")
}

/// The text table of one dispersion (rows within `x_range`, when given).
fn print_table<const D: usize>(r: &DispersionReport, x_range: Option<(f64, f64)>) {
    let path: Vec<String> = r
        .labels
        .iter()
        .map(|(l, s)| format!("{l} (s = {s:.4})"))
        .collect();
    // the one line of units the columns without one need
    let units = if D == 1 {
        "continuum ω² in c²/Δx²"
    } else {
        "continuum ω² in c²/Δx², s = path length in κΔx (1/Δx)"
    };
    println!("# {} — path {}; {units}", r.header, path.join(" – "));
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
        let x = if D == 1 {
            r.path[i] / std::f64::consts::PI
        } else {
            r.path[i]
        };
        if x_range.is_some_and(|(lo, hi)| !(lo..=hi).contains(&x)) {
            continue;
        }
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
}
