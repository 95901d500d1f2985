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
            label: format!("{} (numeric engine)", r.header.setup.form),
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

/// Axis description of every damping plot.
pub const DAMPING_DESC: &str = "Re s Δx / c  (damping rate of the branch; < 0: damped)";

/// Damping curves Re s(x) of branches with labels; a null (ambiguous matching) leaves a gap.
pub fn damping_curves_svg(
    title: &str,
    x_desc: &str,
    x: &[f64],
    branches: &[(String, Vec<Option<f64>>)],
) -> Result<String> {
    let curves: Vec<Curve> = branches
        .iter()
        .map(|(label, y)| Curve {
            label: label.clone(),
            x: x.to_vec(),
            // a gap in the drawn line only (lines_svg splits at non-finite values)
            y: y.iter().map(|v| v.unwrap_or(f64::NAN)).collect(),
            dashed: false,
        })
        .collect();
    lines_svg(title, x_desc, DAMPING_DESC, &curves, None)
}

/// Damping rate Re s(κ) of a dissipative 1D dispersion report (`None` when it has none).
pub fn damping_svg(r: &DispersionReport) -> Result<Option<String>> {
    let Some(rate) = &r.damping_rate else {
        return Ok(None);
    };
    let xs: Vec<f64> = r
        .kappa_dx
        .iter()
        .map(|k| k / std::f64::consts::PI)
        .collect();
    damping_curves_svg(
        &format!("{} — damping", r.header),
        KAPPA_DESC,
        &xs,
        &[(
            format!("{} (eigenvalues of J(κ))", r.header.setup.form),
            rate.clone(),
        )],
    )
    .map(Some)
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

/// One curve of a multi-panel figure ([`panels_svg`]); curve i of every panel is drawn in the
/// style of legend entry i.
#[derive(Clone, Debug)]
pub struct PanelCurve {
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates.
    pub y: Vec<f64>,
}

/// One panel of [`panels_svg`].
#[derive(Clone, Debug)]
pub struct Panel {
    /// Panel caption.
    pub title: String,
    /// Curves, indexed like the legend (an empty curve draws nothing).
    pub curves: Vec<PanelCurve>,
}

/// Marker shapes of [`panels_svg`], cycled by curve index.
const MARKERS: usize = 6;
/// Panel size of [`panels_svg`] (pixels).
const PANEL_W: u32 = 400;
/// Panel height of [`panels_svg`] (pixels).
const PANEL_H: u32 = 330;

/// Draws a marker at pixel `at` of `area`: shape `kind` (circle, square, up-triangle,
/// diamond, down-triangle, cross), filled or hollow.
fn draw_marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    at: (i32, i32),
    kind: usize,
    color: RGBColor,
    filled: bool,
) -> Result<()> {
    let style = if filled {
        color.filled()
    } else {
        color.stroke_width(2)
    };
    let poly = |pts: Vec<(i32, i32)>| {
        if filled {
            area.draw(&(EmptyElement::at(at) + Polygon::new(pts, style)))
        } else {
            let mut closed = pts.clone();
            closed.push(pts[0]);
            area.draw(&(EmptyElement::at(at) + PathElement::new(closed, style)))
        }
    };
    match kind % MARKERS {
        0 => area.draw(&(EmptyElement::at(at) + Circle::new((0, 0), 4, style))),
        1 => area.draw(&(EmptyElement::at(at) + Rectangle::new([(-4, -4), (4, 4)], style))),
        2 => poly(vec![(0, -5), (5, 4), (-5, 4)]),
        3 => poly(vec![(0, -6), (5, 0), (0, 6), (-5, 0)]),
        4 => poly(vec![(0, 5), (5, -4), (-5, -4)]),
        _ => area.draw(&(EmptyElement::at(at) + Cross::new((0, 0), 4, color.stroke_width(2)))),
    }
    .map_err(plot_err)
}

/// Style of legend entry i: (colour, marker, filled marker and solid line).
fn panel_style(i: usize) -> (RGBColor, usize, bool) {
    (
        PARETO_PALETTE[i % PARETO_PALETTE.len()],
        i % MARKERS,
        (i / MARKERS).is_multiple_of(2),
    )
}

/// A grid of panels (`cols` per row) sharing the x axis (log scale, positive x only) and, per
/// row, the y range (from 0), with one legend column on the right: curve i is drawn with colour
/// i of the colour-blind-safe palette, marker shape i mod 6, filled markers and solid lines for
/// i < 6, hollow markers and dashed lines for 6 ≤ i < 12 — distinguishable in greyscale.
pub fn panels_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    legend: &[String],
    panels: &[Panel],
    cols: usize,
) -> Result<String> {
    let cols = cols.max(1);
    let rows = panels.len().div_ceil(cols).max(1);
    let pts = || {
        panels.iter().flat_map(|p| {
            p.curves
                .iter()
                .flat_map(|c| c.x.iter().copied().zip(c.y.iter().copied()))
        })
    };
    let (x0, x1) = pts()
        .filter(|(x, y)| x.is_finite() && *x > 0.0 && y.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(a, b), (x, _)| {
            (a.min(x), b.max(x))
        });
    if !(x0.is_finite() && x1 > 0.0) {
        return Err(Error::Incompatible(
            "nothing to plot: no finite points".into(),
        ));
    }
    let (x0, x1) = (x0 / 1.15, x1 * 1.15);
    let mut svg = String::new();
    {
        let (w, h) = (PANEL_W * cols as u32 + 200, PANEL_H * rows as u32 + 50);
        let base = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        base.fill(&WHITE).map_err(plot_err)?;
        let root = base.titled(title, ("sans-serif", 19)).map_err(plot_err)?;
        let (grid, side) = root.split_horizontally(PANEL_W * cols as u32);
        let areas = grid.split_evenly((rows, cols));
        for (pi, (panel, area)) in panels.iter().zip(&areas).enumerate() {
            let row = pi / cols;
            let ymax = panels[row * cols..((row + 1) * cols).min(panels.len())]
                .iter()
                .flat_map(|p| p.curves.iter().flat_map(|c| c.y.iter().copied()))
                .filter(|y| y.is_finite())
                .fold(0.0f64, f64::max);
            let ymax = if ymax > 0.0 { 1.08 * ymax } else { 1.0 };
            let mut chart = ChartBuilder::on(area)
                .caption(&panel.title, ("sans-serif", 15))
                .margin(8)
                .x_label_area_size(40)
                .y_label_area_size(55)
                .build_cartesian_2d((x0..x1).log_scale(), -0.02 * ymax..ymax)
                .map_err(plot_err)?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(y_desc)
                .x_label_formatter(&|v| format!("{v:.0}"))
                .y_label_formatter(&|v| format!("{v:.2}"))
                .label_style(("sans-serif", 12))
                .bold_line_style(BLACK.mix(0.12))
                .light_line_style(WHITE)
                .draw()
                .map_err(plot_err)?;
            for (i, c) in panel.curves.iter().enumerate() {
                let (color, kind, solid) = panel_style(i);
                let line: Vec<(f64, f64)> =
                    c.x.iter()
                        .copied()
                        .zip(c.y.iter().copied())
                        .filter(|(x, y)| x.is_finite() && *x > 0.0 && y.is_finite())
                        .collect();
                if solid {
                    chart
                        .draw_series(LineSeries::new(line.clone(), color.stroke_width(1)))
                        .map_err(plot_err)?;
                } else {
                    chart
                        .draw_series(DashedLineSeries::new(
                            line.clone(),
                            6,
                            4,
                            color.stroke_width(1),
                        ))
                        .map_err(plot_err)?;
                }
                for p in line {
                    draw_marker(&base, chart.backend_coord(&p), kind, color, solid)?;
                }
            }
        }
        // the legend column
        for (i, label) in legend.iter().enumerate() {
            let (color, kind, solid) = panel_style(i);
            let y = 60 + 24 * i as i32;
            let seg = vec![(10, y), (46, y)];
            if solid {
                side.draw(&PathElement::new(seg, color.stroke_width(1)))
                    .map_err(plot_err)?;
            } else {
                side.draw(&plotters::element::DashedPathElement::new(
                    seg,
                    6,
                    4,
                    color.stroke_width(1),
                ))
                .map_err(plot_err)?;
            }
            draw_marker(&side, (28, y), kind, color, solid)?;
            side.draw(&Text::new(label.clone(), (54, y - 7), ("sans-serif", 14)))
                .map_err(plot_err)?;
        }
        base.present().map_err(plot_err)?;
    }
    Ok(svg)
}

/// One panel of [`scatter_panels_svg`]: caption and points (legend index, x, y).
#[derive(Clone, Debug)]
pub struct ScatterPanel {
    /// Panel caption.
    pub title: String,
    /// Points: legend entry, x, y.
    pub points: Vec<(usize, f64, f64)>,
}

/// A row of log–log scatter panels sharing both axis ranges, with one legend column on the
/// right: point of legend entry i drawn in the style of [`panels_svg`] (colour i, marker shape
/// i mod 6, filled for i < 6, hollow for 6 ≤ i < 12). Points that are not finite and positive
/// are left out.
pub fn scatter_panels_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    legend: &[String],
    panels: &[ScatterPanel],
) -> Result<String> {
    let ok = |p: &&(usize, f64, f64)| p.1.is_finite() && p.1 > 0.0 && p.2.is_finite() && p.2 > 0.0;
    let all: Vec<&(usize, f64, f64)> = panels
        .iter()
        .flat_map(|p| p.points.iter())
        .filter(ok)
        .collect();
    if all.is_empty() {
        return Err(Error::Incompatible(
            "nothing to plot: no finite positive points".into(),
        ));
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for p in &all {
        x0 = x0.min(p.1);
        x1 = x1.max(p.1);
        y0 = y0.min(p.2);
        y1 = y1.max(p.2);
    }
    let (x0, x1, y0, y1) = (x0 / 1.5, x1 * 1.5, y0 / 2.0, y1 * 2.0);
    let cols = panels.len().max(1) as u32;
    let mut svg = String::new();
    {
        let (w, h) = (PANEL_W * cols + 220, PANEL_H + 110);
        let base = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        base.fill(&WHITE).map_err(plot_err)?;
        let root = base.titled(title, ("sans-serif", 19)).map_err(plot_err)?;
        let (grid, side) = root.split_horizontally(PANEL_W * cols);
        let areas = grid.split_evenly((1, cols as usize));
        for (panel, area) in panels.iter().zip(&areas) {
            let mut chart = ChartBuilder::on(area)
                .caption(&panel.title, ("sans-serif", 15))
                .margin(8)
                .x_label_area_size(40)
                .y_label_area_size(55)
                .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
                .map_err(plot_err)?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(y_desc)
                .x_label_formatter(&|v| format!("{v:.0e}"))
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .label_style(("sans-serif", 12))
                .bold_line_style(BLACK.mix(0.12))
                .light_line_style(WHITE)
                .draw()
                .map_err(plot_err)?;
            for p in panel.points.iter().filter(ok) {
                let (color, kind, solid) = panel_style(p.0);
                draw_marker(&base, chart.backend_coord(&(p.1, p.2)), kind, color, solid)?;
            }
        }
        for (i, label) in legend.iter().enumerate() {
            let (color, kind, solid) = panel_style(i);
            let y = 60 + 24 * i as i32;
            draw_marker(&side, (20, y), kind, color, solid)?;
            side.draw(&Text::new(label.clone(), (34, y - 7), ("sans-serif", 14)))
                .map_err(plot_err)?;
        }
        base.present().map_err(plot_err)?;
    }
    Ok(svg)
}
