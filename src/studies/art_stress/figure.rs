//! The artificial-stress figure: one panel per (h, f), growth rate against ε.

use super::report::ArtStressReport;
use super::run::{max_relative_difference, trim};
use crate::error::Result;
use crate::plot::axes::{Frame, Scale, auto_range};
use crate::plot::style::{
    Dash, GREY, Style, draw_line, draw_marker, draw_sample, plot_err, series_style, text, text_at,
    text_width, wrap,
};
use crate::solver::BoundaryDensity;

/// Panel size (pixels).
const PANEL_W: f64 = 430.0;
const PANEL_H: f64 = 330.0;

/// Legend entries: (label, style, line, marker).
fn legend(r: &ArtStressReport) -> Vec<(String, Style, bool, bool)> {
    let inf = series_style(0, Dash::Solid);
    let mut v = vec![
        (
            "infinite lattice, fastest mode longitudinal".to_string(),
            inf,
            true,
            true,
        ),
        (
            "infinite lattice, fastest mode transverse".to_string(),
            Style {
                filled: false,
                ..inf
            },
            true,
            true,
        ),
        (
            format!("{}×{} box (dense operator)", r.config.size, r.config.size),
            Style {
                marker: crate::plot::style::Marker::Square,
                ..series_style(1, Dash::Dashed)
            },
            true,
            false,
        ),
        (
            "sphstab Swegle run, measured".to_string(),
            series_style(2, Dash::Solid),
            false,
            true,
        ),
    ];
    if !r.compare_label.is_empty() {
        v.push((
            format!("{} Swegle run, measured", r.compare_label),
            Style {
                filled: false,
                ..series_style(3, Dash::Solid)
            },
            false,
            true,
        ));
    }
    v
}

/// The figure: one panel per (h, f) (rows h, columns f), growth rate against ε.
pub fn figure_svg(r: &ArtStressReport) -> Result<String> {
    use plotters::prelude::*;
    use plotters::style::text_anchor::{HPos, VPos};
    let cols = r.config.density_ratio.len().max(1);
    let rows = r.cases.len().div_ceil(cols).max(1);
    let leg = legend(r);
    let legend_w = 60.0 + leg.iter().map(|l| text_width(&l.0, 13)).fold(0.0, f64::max);
    let width = PANEL_W * cols as f64 + 30.0 + legend_w;
    let title = format!(
        "Artificial stress against the Swegle growth: {} {}, zero-shear material in tension, ε of R = −ε σ⁺/ρ² (n = {}); {} boundary density",
        r.config.form,
        r.config.kernel,
        r.config.art_n,
        match r.config.boundary_density {
            BoundaryDensity::Frozen => "frozen",
            BoundaryDensity::Evolve => "evolving",
        }
    );
    let lines = wrap(&title, ((width - 40.0) / (0.56 * 18.0)) as usize);
    let th = 16.0 + 23.0 * lines.len() as f64;
    let height = th + PANEL_H * rows as f64 + 5.0;
    let xs: Vec<f64> = r
        .cases
        .iter()
        .flat_map(|c| {
            c.points
                .iter()
                .map(|p| p.eps)
                .chain(c.runs.iter().map(|p| p.eps))
                .chain(c.compare.iter().map(|p| p.eps))
        })
        .collect();
    let xmax = xs.iter().copied().fold(0.0f64, f64::max);
    let xmax = if xmax > 0.0 { xmax } else { 1.0 };
    let x_scale = Scale::Linear(-0.02 * xmax, 1.03 * xmax);
    let mut svg = String::new();
    {
        let root = crate::plot::canvas::Canvas::new(
            &mut svg,
            crate::plot::print::Width::Double,
            (width, height),
        )
        .into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        for (k, line) in lines.iter().enumerate() {
            text_at(
                &root,
                line,
                (width / 2.0, 10.0 + 23.0 * k as f64),
                18,
                (HPos::Center, VPos::Top),
                false,
            )?;
        }
        for (ci, case) in r.cases.iter().enumerate() {
            let (row, col) = (ci / cols, ci % cols);
            let ys: Vec<f64> = case
                .points
                .iter()
                .flat_map(|p| [p.infinite, p.in_box])
                .chain(case.runs.iter().filter_map(|p| p.measured))
                .chain(case.compare.iter().filter_map(|p| p.measured))
                .collect();
            let yr = auto_range(&[&ys], true);
            let top = if yr.hi > 0.0 { yr.hi } else { 1.0 };
            let (cx, cy) = (col as f64 * PANEL_W, th + row as f64 * PANEL_H);
            let frame = Frame {
                rect: (
                    cx + 78.0,
                    cy + 26.0,
                    cx + PANEL_W - 14.0,
                    cy + PANEL_H - 58.0,
                ),
                x: x_scale,
                y: Scale::Linear(-0.02 * top, 1.06 * top),
                grid: true,
            };
            text_at(
                &root,
                &format!(
                    "h = {}Δx, f = {} (σ̄ = {})",
                    case.h,
                    case.density_ratio,
                    trim(case.sigma_bar)
                ),
                ((frame.rect.0 + frame.rect.2) / 2.0, frame.rect.1 - 5.0),
                14,
                (HPos::Center, VPos::Bottom),
                false,
            )?;
            frame.draw(
                &root,
                &format!("artificial-stress ε (n = {})", r.config.art_n),
                "growth rate γ (c/Δx)",
                None,
            )?;
            let px = |x: f64, y: f64| frame.map(x, y);
            // infinite lattice: one line, markers filled where the fastest mode is longitudinal
            let line: Vec<(f64, f64)> = case.points.iter().map(|p| px(p.eps, p.infinite)).collect();
            draw_line(&root, &line, &leg[0].1)?;
            for p in &case.points {
                let s = if p.longitudinal >= 0.5 {
                    &leg[0].1
                } else {
                    &leg[1].1
                };
                draw_marker(&root, px(p.eps, p.infinite), s)?;
            }
            let boxline: Vec<(f64, f64)> =
                case.points.iter().map(|p| px(p.eps, p.in_box)).collect();
            draw_line(&root, &boxline, &leg[2].1)?;
            // the compared code's hollow markers first, sphstab's filled ones on top (they
            // coincide when the codes agree; the legend then says so)
            if leg.len() > 4 {
                for p in &case.compare {
                    if let Some(m) = p.measured {
                        draw_marker(&root, px(p.eps, m), &leg[4].1)?;
                    }
                }
            }
            for p in &case.runs {
                if let Some(m) = p.measured {
                    draw_marker(&root, px(p.eps, m), &leg[3].1)?;
                }
            }
            // runs that did not grow into the fit window, named under the panel
            let silent: Vec<String> = case
                .runs
                .iter()
                .filter(|p| p.measured.is_none())
                .map(|p| trim(p.eps))
                .collect();
            if !silent.is_empty() {
                text(
                    &root,
                    &format!("no growth measured at ε = {}", silent.join(", ")),
                    (frame.rect.0, frame.rect.3 + 34.0),
                    11,
                    GREY,
                )?;
            }
        }
        let (lx, top) = (PANEL_W * cols as f64 + 20.0, th + 26.0);
        let mut y = top + 6.0;
        let agree = max_relative_difference(r);
        for (i, (label, style, line, marker)) in leg.iter().enumerate() {
            draw_sample(&root, (lx, y + 7.0), 36.0, style, *line, *marker)?;
            if i == 4 {
                // sphstab's marker inside, as in the panels
                draw_marker(&root, (lx + 18.0, y + 7.0), &leg[3].1)?;
            }
            text(&root, label, (lx + 44.0, y), 13, BLACK)?;
            y += 22.0;
            if let (4, Some(d)) = (i, agree) {
                for line in [
                    "coincides with sphstab's runs (▲ inside ◇):".to_string(),
                    format!("max relative difference {d:.1e}"),
                ] {
                    text(&root, &line, (lx + 44.0, y - 5.0), 11, GREY)?;
                    y += 13.0;
                }
            }
        }
        root.draw(&Rectangle::new(
            [
                ((lx - 8.0) as i32, top as i32),
                ((lx + legend_w) as i32, (y + 4.0) as i32),
            ],
            GREY.stroke_width(1),
        ))
        .map_err(plot_err)?;
        root.present().map_err(plot_err)?;
    }
    crate::plot::print::finish(&svg, crate::plot::print::Width::Double)
}
