//! Plots as pure functions returning SVG strings (plotters SVG backend, no system fonts).

use crate::analysis::DispersionReport;
use crate::error::{Error, Result};
use plotters::prelude::*;

/// One curve of a line plot.
#[derive(Clone, Debug)]
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates.
    pub y: Vec<f64>,
    /// Dashed (e.g. a reference curve) rather than solid.
    pub dashed: bool,
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(240, 228, 66),
];

fn plot_err<E: std::fmt::Debug>(_: E) -> Error {
    Error::NonFinite("plot")
}

/// A line plot of several curves with a zero line, axis descriptions and a legend.
/// `y_range` clips the vertical axis (None: fit all data).
pub fn lines_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    curves: &[Curve],
    y_range: Option<(f64, f64)>,
) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (820, 580)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        let xs = curves.iter().flat_map(|c| c.x.iter().copied());
        let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        let (mut lo, mut hi) = y_range.unwrap_or_else(|| {
            curves
                .iter()
                .flat_map(|c| c.y.iter().copied())
                .filter(|y| y.is_finite())
                .fold((0.0f64, 0.0f64), |(a, b), y| (a.min(y), b.max(y)))
        });
        if hi - lo < 1e-12 {
            hi = lo + 1.0;
        }
        let pad = 0.05 * (hi - lo);
        lo -= pad;
        hi += pad;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 19))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, lo..hi)
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .draw()
            .map_err(plot_err)?;
        chart
            .draw_series(LineSeries::new([(x0, 0.0), (x1, 0.0)], BLACK.mix(0.4)))
            .map_err(plot_err)?;
        for (i, c) in curves.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            // split into runs of points inside the vertical range (no lines across clipped gaps)
            let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for (&x, &y) in c.x.iter().zip(&c.y) {
                if y.is_finite() && y >= lo && y <= hi {
                    if let Some(s) = segments.last_mut() {
                        s.push((x, y));
                    }
                } else if !segments.last().is_some_and(|s| s.is_empty()) {
                    segments.push(Vec::new());
                }
            }
            let style = color.stroke_width(2);
            for (n, seg) in segments.into_iter().filter(|s| !s.is_empty()).enumerate() {
                let anno = if c.dashed {
                    chart
                        .draw_series(DashedLineSeries::new(seg, 8, 5, style))
                        .map_err(plot_err)?
                } else {
                    chart
                        .draw_series(LineSeries::new(seg, style))
                        .map_err(plot_err)?
                };
                if n == 0 {
                    anno.label(c.label.clone()).legend(move |(x, y)| {
                        PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2))
                    });
                }
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(plot_err)?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}

/// Axis descriptions of every dispersion plot.
pub const KAPPA_DESC: &str = "κΔx / π  (wave number, units of π/Δx)";
/// Ordinate description of every dispersion plot.
pub const OMEGA2_DESC: &str = "ω² Δx² / c²";

/// ω²Δx²/c² against κΔx/π with the continuum curve overlaid (clipped at 1.3× the discrete
/// maximum so the discrete curve stays readable).
pub fn dispersion_svg(r: &DispersionReport) -> Result<String> {
    let xs: Vec<f64> = r
        .kappa_dx
        .iter()
        .map(|k| k / std::f64::consts::PI)
        .collect();
    let dmax = r.omega2.iter().fold(0.0f64, |m, &y| m.max(y));
    let dmin = r.omega2.iter().fold(0.0f64, |m, &y| m.min(y));
    let title = r.header.to_string();
    let curves = [
        Curve {
            label: "continuum (1 + σ̄)(κΔx)²  [B00 eq 32]".into(),
            x: xs.clone(),
            y: r.omega2_continuum.clone(),
            dashed: true,
        },
        Curve {
            label: format!("{} (numeric engine)", r.header.form),
            x: xs,
            y: r.omega2.clone(),
            dashed: false,
        },
    ];
    let hi = if dmax > 0.0 {
        1.3 * dmax.max(dmin.abs())
    } else {
        1.0
    };
    lines_svg(
        &title,
        KAPPA_DESC,
        OMEGA2_DESC,
        &curves,
        Some((dmin.min(0.0), hi)),
    )
}

/// A heat map of z over a rectangular (x, y) grid (cell centres), white (0) to dark red (max).
pub fn heatmap_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    x: &[f64],
    y: &[f64],
    z: &[Vec<f64>],
) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (760, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        let (x0, x1) = (
            x[0] - 0.5 * (x[1] - x[0]),
            x[x.len() - 1] + 0.5 * (x[1] - x[0]),
        );
        let (y0, y1) = (
            y[0] - 0.5 * (y[1] - y[0]),
            y[y.len() - 1] + 0.5 * (y[1] - y[0]),
        );
        let zmax = z.iter().flatten().fold(0.0f64, |m, &v| m.max(v));
        let mut chart = ChartBuilder::on(&root)
            .caption(format!("{title}  (max {zmax:.4})"), ("sans-serif", 18))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .disable_mesh()
            .draw()
            .map_err(plot_err)?;
        let (dx, dy) = (x[1] - x[0], y[1] - y[0]);
        chart
            .draw_series(x.iter().enumerate().flat_map(|(i, &xi)| {
                y.iter().enumerate().map(move |(j, &yj)| {
                    let t = if zmax > 0.0 {
                        (z[i][j] / zmax).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let c = RGBColor(
                        255 - (100.0 * t) as u8,
                        (255.0 * (1.0 - t)) as u8,
                        (255.0 * (1.0 - t)) as u8,
                    );
                    Rectangle::new(
                        [
                            (xi - dx / 2.0, yj - dy / 2.0),
                            (xi + dx / 2.0, yj + dy / 2.0),
                        ],
                        c.filled(),
                    )
                })
            }))
            .map_err(plot_err)?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}

/// Ten distinguishable colours for the Pareto figure (one per form).
const PARETO_PALETTE: [RGBColor; 10] = [
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(150, 150, 150),
    RGBColor(128, 0, 128),
    RGBColor(160, 82, 45),
];

/// A log–log scatter of (group, x, y, filled) points, one colour per group (legend), filled
/// markers for `filled`, hollow otherwise; the lower-left Pareto front of the filled points is
/// drawn as a dashed staircase.
pub fn pareto_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    pts: &[(String, f64, f64, bool)],
) -> Result<String> {
    let pts: Vec<&(String, f64, f64, bool)> = pts
        .iter()
        .filter(|p| p.1.is_finite() && p.2.is_finite() && p.1 > 0.0 && p.2 > 0.0)
        .collect();
    if pts.is_empty() {
        return Err(Error::Incompatible(
            "nothing to plot: no configuration has both a cost and an error".into(),
        ));
    }
    let mut groups: Vec<&str> = Vec::new();
    for p in &pts {
        if !groups.contains(&p.0.as_str()) {
            groups.push(&p.0);
        }
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for p in &pts {
        x0 = x0.min(p.1);
        x1 = x1.max(p.1);
        y0 = y0.min(p.2);
        y1 = y1.max(p.2);
    }
    let (x0, x1, y0, y1) = (x0 / 1.3, x1 * 1.3, y0 / 2.0, y1 * 2.0);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(plot_err)?;
        // Pareto front of the filled points: sorted by cost, keep the running minimum error
        let mut front: Vec<(f64, f64)> = pts.iter().filter(|p| p.3).map(|p| (p.1, p.2)).collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut stairs = Vec::new();
        let mut best = f64::INFINITY;
        for (x, y) in front {
            if y < best {
                if best.is_finite() {
                    stairs.push((x, best));
                }
                stairs.push((x, y));
                best = y;
            }
        }
        if stairs.len() > 1 {
            chart
                .draw_series(DashedLineSeries::new(
                    stairs,
                    6,
                    4,
                    BLACK.mix(0.6).stroke_width(1),
                ))
                .map_err(plot_err)?
                .label("Pareto front of the stable configurations")
                .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK.stroke_width(1)));
        }
        for (gi, g) in groups.iter().enumerate() {
            let color = PARETO_PALETTE[gi % PARETO_PALETTE.len()];
            chart
                .draw_series(pts.iter().filter(|p| p.0 == *g).map(|p| {
                    let style = if p.3 {
                        color.filled()
                    } else {
                        color.stroke_width(2)
                    };
                    Circle::new((p.1, p.2), 4, style)
                }))
                .map_err(plot_err)?
                .label(g.to_string())
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(plot_err)?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}
