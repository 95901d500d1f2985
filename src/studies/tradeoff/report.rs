//! The trade-off report: its rows, the tables `sphstab tradeoff` prints and the figures it draws.

use super::integrators::IntegratorRow;
use crate::error::Result;
use serde::{Deserialize, Serialize};

/// One configuration's measurements (see the module table).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct Row {
    /// Form.
    pub form: String,
    /// Kernel.
    pub kernel: String,
    /// Shape family.
    pub shape: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// R/Δx.
    pub support_over_dx: f64,
    /// Solver cost (ns per particle per step).
    pub ns_per_particle_step: Option<f64>,
    /// Masters within R.
    pub neighbours_per_particle: Option<f64>,
    /// Peak heap bytes per particle.
    pub bytes_per_particle: Option<f64>,
    /// |c_num/c − 1| at 10 points per wavelength.
    pub phase_error_10ppw: Option<f64>,
    /// |c_num/c − 1| at 20 points per wavelength.
    pub phase_error_20ppw: Option<f64>,
    /// Relative L2 velocity error of the standing-wave scene.
    pub wave_l2_error: Option<f64>,
    /// Largest tensile σ̄ that stays stable.
    pub max_stable_tension: Option<f64>,
    /// Stable at σ̄ = −0.01.
    pub stable_in_compression: Option<bool>,
    /// Critical leapfrog Δt (Δx/c) at σ̄ = 0.
    pub critical_dt: Option<f64>,
    /// ns per particle per Δx/c of simulated time at the critical step.
    pub ns_per_particle_time: Option<f64>,
    /// Why the configuration could not be analysed or run.
    pub error: Option<String>,
}

impl Row {
    /// Stable at ±1% stress: the filled markers of the Pareto figure.
    pub fn stable_at_one_percent(&self) -> bool {
        self.max_stable_tension.is_some_and(|s| s >= 0.01)
            && self.stable_in_compression == Some(true)
    }
}

/// The whole study.
#[derive(Clone, Debug, Deserialize, Serialize)]
pub struct TradeoffReport {
    /// Dimension.
    pub dim: u8,
    /// Worker threads of the analysis part.
    pub threads: usize,
    /// Wall-clock seconds of the study.
    pub runtime_s: f64,
    /// The wave scene.
    pub scene: String,
    /// One row per configuration.
    pub rows: Vec<Row>,
    /// One row per configuration × integrator (only when integrators were asked for).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub integrator_rows: Vec<IntegratorRow>,
}

fn fmt_opt(v: Option<f64>, prec: usize) -> String {
    match v {
        Some(x) if x.abs() >= 1e4 || (x != 0.0 && x.abs() < 1e-3) => format!("{x:.prec$e}"),
        Some(x) => format!("{x:.prec$}"),
        None => "-".into(),
    }
}

/// The table printed by `sphstab tradeoff`.
pub fn table(rep: &TradeoffReport) -> String {
    let mut s = String::from(
        "units: h, R in Δx; ns/p·st = ns (wall clock) per particle-step; nb = neighbours within R; \
         B/part = peak heap bytes per particle; phase@10, @20 = |c_num/c − 1| at 10, 20 points per \
         wavelength; L2 wave relative; σ̄max+ = largest stable tension σ̄ = σ/C; comp = stable at \
         σ̄ = −0.01; Δt_crit in Δx/c; ns/p·Δx/c = ns per particle per Δx/c of simulated time\n",
    );
    s += &format!(
        "{:<24} {:<12} {:>5} {:>5} {:>8} {:>4} {:>7} {:>9} {:>9} {:>9} {:>8} {:>5} {:>7} {:>9}\n",
        "form",
        "kernel",
        "h/Δx",
        "R/Δx",
        "ns/p·st",
        "nb",
        "B/part",
        "phase@10",
        "phase@20",
        "L2 wave",
        "σ̄max+",
        "comp",
        "Δt_crit",
        "ns/p·Δx/c"
    );
    for r in &rep.rows {
        if let Some(e) = &r.error {
            s += &format!(
                "{:<24} {:<12} {:>5.2} {:>5.2} error: {e}\n",
                r.form, r.kernel, r.h_over_dx, r.support_over_dx
            );
            continue;
        }
        s += &format!(
            "{:<24} {:<12} {:>5.2} {:>5.2} {:>8} {:>4} {:>7} {:>9} {:>9} {:>9} {:>8} {:>5} {:>7} {:>9}\n",
            r.form,
            r.kernel,
            r.h_over_dx,
            r.support_over_dx,
            fmt_opt(r.ns_per_particle_step, 0),
            fmt_opt(r.neighbours_per_particle, 0),
            fmt_opt(r.bytes_per_particle, 0),
            fmt_opt(r.phase_error_10ppw, 2),
            fmt_opt(r.phase_error_20ppw, 2),
            fmt_opt(r.wave_l2_error, 2),
            fmt_opt(r.max_stable_tension, 3),
            match r.stable_in_compression {
                Some(true) => "yes",
                Some(false) => "no",
                None => "-",
            },
            fmt_opt(r.critical_dt, 3),
            fmt_opt(r.ns_per_particle_time, 0),
        );
    }
    s
}

/// The Pareto figure: cost (ns per particle per Δx/c at the critical step) against the phase
/// error at 10 points per wavelength, log–log, one marker per configuration, filled when stable
/// at σ̄ = ±0.01, one colour per form; the Pareto front of the stable ones is drawn.
pub fn pareto_svg(rep: &TradeoffReport) -> Result<String> {
    let pts: Vec<(String, f64, f64, bool)> = rep
        .rows
        .iter()
        .filter_map(|r| {
            let x = r.ns_per_particle_time?;
            let y = r.phase_error_10ppw?;
            (x > 0.0 && y.is_finite())
                .then(|| (r.form.clone(), x, y.max(1e-6), r.stable_at_one_percent()))
        })
        .collect();
    crate::plot::pareto_svg(
        "",
        "cost (ns per particle per Δx/c, at Δt_crit)",
        "phase-velocity error |c_num/c − 1| (10 ppw)",
        &pts,
        (
            "filled: stable at σ̄ = ±0.01",
            "hollow: unstable at σ̄ = +0.01 or −0.01",
        ),
        &crate::studies::series_names(),
    )
}

/// The table of the integrator rows printed by `sphstab tradeoff --integrators …`.
pub fn integrator_table(rep: &TradeoffReport) -> String {
    let mut s = String::from(
        "units: Δt_crit, Δt_used in Δx/c; weak γ = spurious growth in c/Δx; eval, calls = rate \
         evaluations per step; ns/p·st, ns/ev = ns (wall clock) per particle-step, per evaluation; \
         ns/p·Δx/c = ns per particle per Δx/c of simulated time; phase@10, @20 = phase error in \
         radians per wavelength travelled, amp@10, @20 = amplitude error per wavelength, at 10, 20 \
         points per wavelength\n",
    );
    s += &format!(
        "{:<18} {:<12} {:>5} {:<20} {:>8} {:>8} {:>8} {:>4} {:>5} {:>7} {:>6} {:>9} {:>10} {:>10} {:>10} {:>10}\n",
        "form",
        "kernel",
        "h/Δx",
        "integrator",
        "Δt_crit",
        "weak γ",
        "Δt_used",
        "eval",
        "calls",
        "ns/p·st",
        "ns/ev",
        "ns/p·Δx/c",
        "phase@10",
        "amp@10",
        "phase@20",
        "amp@20"
    );
    for r in &rep.integrator_rows {
        if let Some(e) = &r.error {
            s += &format!(
                "{:<18} {:<12} {:>5.2} {:<20} error: {e}\n",
                r.form, r.kernel, r.h_over_dx, r.integrator
            );
            continue;
        }
        s += &format!(
            "{:<18} {:<12} {:>5.2} {:<20} {:>8} {:>8} {:>8} {:>4} {:>5} {:>7} {:>6} {:>9} {:>10} {:>10} {:>10} {:>10}\n",
            r.form,
            r.kernel,
            r.h_over_dx,
            r.integrator,
            fmt_opt(r.critical_dt, 3),
            fmt_opt(r.weak_growth_rate, 1),
            fmt_opt(r.dt_used, 3),
            r.evaluations_per_step,
            fmt_opt(r.rate_calls_per_step, 0),
            fmt_opt(r.ns_per_particle_step, 0),
            fmt_opt(r.ns_per_evaluation, 0),
            fmt_opt(r.ns_per_particle_time, 0),
            fmt_opt(r.phase_error_10ppw, 2),
            fmt_opt(r.amplitude_error_10ppw, 2),
            fmt_opt(r.phase_error_20ppw, 2),
            fmt_opt(r.amplitude_error_20ppw, 2),
        );
    }
    s
}

/// The integrator figure: per form, cost per unit simulated time (ns per particle per Δx/c at
/// the Δt used) against |phase error| per wavelength travelled at 10 points per wavelength,
/// log–log, one marker per integrator, every kernel and h of the grid.
pub fn integrators_svg(rep: &TradeoffReport) -> Result<String> {
    let mut names: Vec<&str> = Vec::new();
    let mut forms: Vec<&str> = Vec::new();
    for r in &rep.integrator_rows {
        if !names.contains(&r.integrator.as_str()) {
            names.push(&r.integrator);
        }
        if !forms.contains(&r.form.as_str()) {
            forms.push(&r.form);
        }
    }
    let panels: Vec<crate::plot::ScatterPanel> = forms
        .iter()
        .map(|f| crate::plot::ScatterPanel {
            title: (*f).to_string(),
            points: rep
                .integrator_rows
                .iter()
                .filter(|r| r.form == *f)
                .filter_map(|r| {
                    let i = names.iter().position(|n| *n == r.integrator)?;
                    Some((i, r.ns_per_particle_time?, r.phase_error_10ppw?.abs()))
                })
                .collect(),
        })
        .collect();
    let legend: Vec<String> = names.iter().map(|s| s.to_string()).collect();
    crate::plot::scatter_panels_svg(
        "",
        "cost (ns per particle per Δx/c)",
        "|phase error| per λ, 10 ppw (rad)",
        &legend,
        &panels,
        &crate::studies::series_names(),
    )
}

/// The figure of a report: [`integrators_svg`] when it has integrator rows, else [`pareto_svg`]
/// (untitled: the study config's note is the caption).
pub fn figure_svg(rep: &TradeoffReport) -> Result<String> {
    if rep.integrator_rows.is_empty() {
        pareto_svg(rep)
    } else {
        integrators_svg(rep)
    }
}
