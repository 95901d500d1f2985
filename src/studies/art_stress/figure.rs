//! The artificial-stress figure: one panel per (h, f), growth rate against ε.

use super::report::ArtStressReport;
use super::run::{max_relative_difference, trim};
use crate::error::Result;
use crate::plot::axes::{Scale, auto_range};
use crate::plot::style::{Dash, GREY, Style, draw_line, draw_marker, plot_err, series_style, text};

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

/// The figure: one panel per (h, f) (rows h, columns f), growth rate against ε, lettered
/// (a), (b), …; the configuration (form, kernel, n, boundary density) is the caption's.
pub fn figure_svg(r: &ArtStressReport) -> Result<String> {
    use crate::plot::print::{NOTE_PT, PAD, Width, page_pt};
    use crate::plot::{Entry, Grid, draw_panel, legend_block, legend_block_height, panel_letter};
    use plotters::prelude::*;
    let cols = r.config.density_ratio.len().max(1);
    let rows = r.cases.len().div_ceil(cols).max(1);
    let leg = legend(r);
    let agree = max_relative_difference(r);
    let agree_note = agree.map(|d| {
        format!(
            "on sphstab's (▲ in ◇): max rel. difference {}",
            crate::plot::axes::sci(d)
        )
    });
    let entries: Vec<Entry<'_>> = leg
        .iter()
        .enumerate()
        .map(|(i, (label, style, line, marker))| Entry {
            style: *style,
            label,
            note: if i == 4 { agree_note.as_deref() } else { None },
            line: *line,
            marker: *marker,
        })
        .collect();
    let page = page_pt(Width::Double);
    // panels over the page width, the legend in columns under them
    let mut grid = Grid::new(PAD, cols.max(2), 0.0, 0.6);
    grid.fit_left(Scale::Linear(0.0, 0.123), "growth rate γ (c/Δx)");
    let legend_top = PAD + grid.cell.1 * rows as f64 + 2.0;
    let height = legend_top + legend_block_height(&entries, page - 2.0 * PAD) + PAD;
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
        let root = crate::plot::canvas::Canvas::new(&mut svg, Width::Double, (page, height))
            .into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
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
            let frame = grid.frame(col, row, x_scale, Scale::Linear(-0.02 * top, 1.06 * top));
            draw_panel(
                &root,
                &frame,
                &format!(
                    "{} h = {}Δx, f = {} (σ̄ = {})",
                    panel_letter(ci),
                    case.h,
                    case.density_ratio,
                    trim(case.sigma_bar)
                ),
                &format!("artificial-stress ε (n = {})", r.config.art_n),
                "growth rate γ (c/Δx)",
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
            // runs that did not grow into the fit window, named in the panel
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
                    (frame.rect.0 + 2.0, frame.rect.1 + 2.0),
                    NOTE_PT,
                    GREY,
                )?;
            }
        }
        legend_block(&root, &entries, (PAD, legend_top), page - 2.0 * PAD)?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}
