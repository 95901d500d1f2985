//! Plots as pure functions returning SVG strings (plotters SVG backend, no system fonts).

use crate::analysis::DispersionReport;
use crate::error::{Error, Result};
use plotters::prelude::*;

/// ω²Δx²/c² against κΔx/π with the continuum curve overlaid.
pub fn dispersion_svg(r: &DispersionReport) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(|_| Error::NonFinite("plot"))?;
        let xs: Vec<f64> = r
            .kappa_dx
            .iter()
            .map(|k| k / std::f64::consts::PI)
            .collect();
        let all = r.omega2.iter().chain(&r.omega2_continuum);
        let (mut lo, mut hi) = all.fold((0.0f64, 0.0f64), |(a, b), &y| (a.min(y), b.max(y)));
        // Keep the discrete curve readable: clip the continuum at 1.3× the discrete maximum.
        let dmax = r.omega2.iter().fold(0.0f64, |m, &y| m.max(y));
        if dmax > 0.0 {
            hi = hi.min(1.3 * dmax.max(lo.abs()));
        }
        if hi - lo < 1e-12 {
            hi = lo + 1.0;
        }
        let pad = 0.05 * (hi - lo);
        lo -= pad;
        hi += pad;
        let title = format!(
            "{} / {} / {}  h = {:.3}Δx (R = {:.3}Δx), σ̄ = {}",
            r.header.form,
            r.header.kernel,
            r.header.shape,
            r.header.h_over_dx,
            r.header.support_over_dx,
            r.header.stress
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..1.0f64, lo..hi)
            .map_err(|_| Error::NonFinite("plot"))?;
        chart
            .configure_mesh()
            .x_desc("κΔx / π  (wave number, units of π/Δx)")
            .y_desc("ω² Δx² / c²")
            .draw()
            .map_err(|_| Error::NonFinite("plot"))?;
        chart
            .draw_series(LineSeries::new([(0.0, 0.0), (1.0, 0.0)], BLACK.mix(0.4)))
            .map_err(|_| Error::NonFinite("plot"))?;
        chart
            .draw_series(LineSeries::new(
                xs.iter()
                    .zip(&r.omega2_continuum)
                    .filter(|(_, y)| **y <= hi)
                    .map(|(&x, &y)| (x, y)),
                BLUE.stroke_width(2),
            ))
            .map_err(|_| Error::NonFinite("plot"))?
            .label("continuum (1 + σ̄)(κΔx)²  [B00 eq 32]")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLUE.stroke_width(2)));
        chart
            .draw_series(LineSeries::new(
                xs.iter().zip(&r.omega2).map(|(&x, &y)| (x, y)),
                RED.stroke_width(2),
            ))
            .map_err(|_| Error::NonFinite("plot"))?
            .label(format!("{} (numeric engine)", r.header.form))
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RED.stroke_width(2)));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(|_| Error::NonFinite("plot"))?;
        root.present().map_err(|_| Error::NonFinite("plot"))?;
    }
    Ok(svg)
}
