//! `swegle` series of the figure configs: a Swegle run's velocity history with the box
//! prediction's slope ([`SwegleSeries`]).

use crate::budget::Budget;
use crate::error::Result;
use crate::forms::FormKind;
use crate::kernel;
use crate::plot::Curve;
use crate::solver::diagnostics::growth_fit;
use crate::studies::swegle::{SwegleConfig, run_swegle};
use serde::Deserialize;

/// Which velocity history of a Swegle run is drawn ([`crate::studies::swegle::SwegleReport`]'s
/// `history_full` columns).
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum SwegleHistory {
    /// |v| of the kicked centre particle (the ordinate of \[V21\] Figs 12, 13).
    #[default]
    Centre,
    /// max |v| over the free particles (the history `sphstab swegle` fits).
    Max,
    /// RMS |v| over the free particles.
    Rms,
}

impl SwegleHistory {
    /// Column of `history_full`.
    fn column(self) -> usize {
        match self {
            SwegleHistory::Centre => 1,
            SwegleHistory::Max => 2,
            SwegleHistory::Rms => 3,
        }
    }

    /// Ordinate description.
    pub(super) fn desc(self) -> &'static str {
        match self {
            SwegleHistory::Centre => "|v| of the kicked centre particle (V21 units)",
            SwegleHistory::Max => "max |v| over the free particles (V21 units)",
            SwegleHistory::Rms => "RMS |v| over the free particles (V21 units)",
        }
    }
}

/// One Swegle run (\[V21 §7.2\]: the published box of [`SwegleConfig::new`], 21 × 21, 3
/// fixed layers, Δx = 0.1, ρ0 = 2.8, K = 0.686275, kick 1e−10, fit window 1e−8 to 1e−4):
/// the history drawn solid, and, when the box prediction grows and the history enters the fit
/// window, a dashed line of slope γ_box/ln 10 (γ_box the report's `predicted_growth_rate_box`
/// in c/Δx) over the fit window, through the centroid of the least-squares fit of ln of the
/// drawn history ([`growth_fit`], the fit of `sphstab swegle`, over the same window).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwegleSeries {
    /// Form (a 2D form).
    pub form: String,
    /// Kernel.
    pub kernel: String,
    /// h/Δx.
    pub h: f64,
    /// f = ρ/ρ0 (< 1 tension).
    pub density_ratio: f64,
    /// Partition coefficient c (lnl, cll; default 0.5).
    pub c: Option<f64>,
    /// End time in V21's time units (default 40, the published test).
    pub t_end: Option<f64>,
    /// History drawn (default: the centre particle).
    #[serde(default)]
    pub history: SwegleHistory,
    /// Legend label of the history (default: generated).
    pub label: Option<String>,
}

/// Abscissa description of the Swegle figures.
pub const SWEGLE_TIME_DESC: &str = "time t c/Δx (1 V21 time unit = 4.951 Δx/c)";

impl SwegleSeries {
    /// The run's configuration: [`SwegleConfig::new`] with this series' form, kernel, h, f,
    /// c and end time.
    pub fn config(&self) -> Result<SwegleConfig> {
        let mut cfg = SwegleConfig::new(
            FormKind::by_name(&self.form)?,
            kernel::by_name(&self.kernel)?,
            self.h,
            self.density_ratio,
        );
        if let Some(c) = self.c {
            cfg.c_partition = c;
        }
        if let Some(t) = self.t_end {
            cfg.t_end = t;
        }
        cfg.validate()?;
        Ok(cfg)
    }

    /// The history (solid) and, when drawn, the predicted growth line (dashed); the run
    /// within `budget`.
    pub(super) fn curves(&self, budget: &Budget) -> Result<Vec<Curve>> {
        let cfg = SwegleConfig {
            budget: *budget,
            ..self.config()?
        };
        let r = run_swegle(&cfg, ())?;
        let unit = cfg.sound_speed() / cfg.dx;
        let col = self.history.column();
        let t: Vec<f64> = r.history_full.iter().map(|h| h[0]).collect();
        let y: Vec<f64> = r.history_full.iter().map(|h| h[col]).collect();
        let tau: Vec<f64> = t.iter().map(|t| t * unit).collect();
        let box_rate = r.predicted_growth_rate_box;
        let name = self.label.clone().unwrap_or_else(|| {
            let mut l = format!("{} ρ/ρ0 = {}", r.form, self.density_ratio);
            if matches!(cfg.form, FormKind::Lnl | FormKind::Cll) {
                l += &format!(", c = {}", cfg.c_partition);
            }
            l
        });
        let fit = growth_fit(&t, &y, cfg.window.0, cfg.window.1);
        let mut label = name.clone();
        match fit {
            Some(f) => label += &format!(": fitted {:.4} c/Δx", f.rate / unit),
            None => label += ": no growth into the fit window",
        }
        let mut out = vec![Curve {
            label,
            x: tau.clone(),
            y: y.clone(),
            dashed: false,
        }];
        if let (Some(f), true) = (fit, box_rate > crate::vonneumann::classify::GROWTH_TOL) {
            // the least-squares line of ln y passes through the centroid of its samples
            let (lo, hi) = f.window;
            let pts: Vec<(f64, f64)> = t
                .iter()
                .zip(&y)
                .filter(|&(&ti, &yi)| ti >= lo && ti <= hi && yi > cfg.window.0)
                .map(|(&ti, &yi)| (ti * unit, yi.log10()))
                .collect();
            let n = pts.len() as f64;
            let (tc, yc) = pts
                .iter()
                .fold((0.0, 0.0), |a, p| (a.0 + p.0 / n, a.1 + p.1 / n));
            let slope = box_rate / std::f64::consts::LN_10;
            let ends = [lo * unit, hi * unit];
            out.push(Curve {
                label: format!(
                    "{name}: box {box_rate:.4} c/Δx ({}), slope through the fit",
                    r.box_method
                ),
                x: ends.to_vec(),
                y: ends
                    .iter()
                    .map(|&a| 10f64.powf(yc + slope * (a - tc)))
                    .collect(),
                dashed: true,
            });
        }
        Ok(out)
    }
}
