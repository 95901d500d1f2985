//! The tensile-or-hourglass figure: (a) a stability map per remedy and state — growth rate over
//! |σ̄| (log axis) for each Poisson ratio (G/K), white where stable, grey where the continuum
//! itself is unstable; then one panel per state: the growth rate at the reference ν against
//! |σ̄|, its hourglass part dashed and the rest solid, for every remedy that grows.

use super::report::HourglassReport;
use super::run::shear_over_bulk;
use crate::display::num;
use crate::error::Result;
use crate::plot::{Curve, LinePlot, StripPanel, print::Width, stack_svg, strips_svg};

/// The figure's SVG.
pub fn figure_svg(r: &HourglassReport) -> Result<String> {
    let cfg = &r.config;
    let labels: Vec<String> = cfg
        .poisson
        .iter()
        .map(|&nu| format!("ν {nu} (G/K {:.3})", shear_over_bulk(nu)))
        .collect();
    let mut panels = Vec::new();
    let mut row_titles = Vec::new();
    for rem in &r.remedies {
        row_titles.push(format!(
            "{}{}",
            rem.label,
            if rem.zero_energy_modes {
                " (zero-energy modes at rest)"
            } else {
                ""
            }
        ));
        for s in &rem.states {
            panels.push(StripPanel {
                title: s.state.short().to_string(),
                rows: s
                    .map
                    .iter()
                    .map(|row| {
                        cfg.stress
                            .iter()
                            .copied()
                            .zip(row.iter().copied())
                            .collect()
                    })
                    .collect(),
            });
        }
    }
    let map = strips_svg(
        "|σ̄| = |σ|/C (log)",
        "growth rate γ (c/Δx)",
        &labels,
        &panels,
        cfg.states.len(),
        &row_titles,
        crate::vonneumann::classify::GROWTH_TOL,
    )?;
    let mut svgs = vec![map];
    for (si, state) in cfg.states.iter().enumerate() {
        let mut curves = Vec::new();
        for rem in &r.remedies {
            let s = &rem.states[si];
            if s.curve.iter().all(|p| p.growth == 0.0) {
                continue;
            }
            let x: Vec<f64> = s.curve.iter().map(|p| p.stress.log10()).collect();
            let pick = |f: &dyn Fn(&super::report::CurvePoint) -> f64| -> Vec<f64> {
                s.curve
                    .iter()
                    .map(|p| if p.material { f64::NAN } else { f(p) })
                    .collect()
            };
            curves.push(Curve {
                label: format!("{}: tensile part", rem.label),
                x: x.clone(),
                y: pick(&|p| p.other),
                dashed: false,
            });
            if s.curve.iter().any(|p| p.hourglass > 0.0) {
                curves.push(Curve {
                    label: format!("{}: hourglass part", rem.label),
                    x,
                    y: pick(&|p| p.hourglass),
                    dashed: true,
                });
            }
        }
        if curves.is_empty() {
            continue;
        }
        let plot = LinePlot {
            width: Width::Single,
            zero_line: true,
            notes: vec![format!(
                "ν = {}; a remedy that never grows here is not drawn",
                num(cfg.reference_poisson)
            )],
            ..LinePlot::new(state.short(), "log₁₀ |σ̄|", "growth rate γ (c/Δx)", curves)
        };
        svgs.push(plot.svg()?);
    }
    stack_svg(
        &format!(
            "Tensile or hourglass? Growth of each remedy over the pre-stress ({}D, {} lattice; map: white stable, grey where the continuum itself is unstable)",
            cfg.dim,
            cfg.lattice
                .as_deref()
                .unwrap_or(if cfg.dim == 3 { "sc" } else { "square" })
        ),
        &svgs,
    )
}
