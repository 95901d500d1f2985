//! The pairing report: its rows and onsets, the text table and the figure (growth against N_H,
//! one panel per lattice and stress, one curve per kernel).

use super::wstar::WStarSign;
use crate::error::Result;
use crate::plot::{StripPanel, strips_svg};
use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// One row: a kernel on a lattice at one h/Δx and σ̄.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct PairingRow {
    /// Kernel name.
    pub kernel: String,
    /// `sc`, `bcc` or `fcc`.
    pub lattice: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// R/Δx = ζh/Δx.
    pub support_over_dx: f64,
    /// Particles inside the support (|r| < R), the particle itself included.
    pub n_h: usize,
    /// (4π/3)(R/Δx)³, Dehnen & Aly's N_H.
    pub n_h_continuum: f64,
    /// σ̄ (negative: pressure −σ̄K).
    pub stress: f64,
    /// Why the row was not computed (null when it was).
    pub skipped: Option<String>,
    /// Largest growth rate over the sampled zone (c/Δx; 0 if none above 1e-6; null if skipped).
    pub max_growth_rate: Option<f64>,
    /// Its wave vector [κxΔx, κyΔx, κzΔx] (null if no growth).
    pub kappa_at_max: Option<[f64; 3]>,
    /// |κ|Δx/π of that wave vector.
    pub kappa_abs_over_pi: Option<f64>,
    /// Longitudinal fraction |ê·k̂|² of the fastest mode (1 longitudinal, 0 transverse; for a
    /// degenerate eigenspace the largest over it, |P k̂|²).
    pub longitudinal_fraction: Option<f64>,
    /// Largest growth of a longitudinal mode (|ê·k̂|² ≥ ½): pairing (c/Δx; 0 if none).
    pub pairing_growth_rate: Option<f64>,
    /// Its wave vector.
    pub pairing_kappa: Option<[f64; 3]>,
    /// Largest growth of a transverse mode (|ê·k̂|² < ½) (c/Δx; 0 if none).
    pub transverse_growth_rate: Option<f64>,
    /// Its wave vector.
    pub transverse_kappa: Option<[f64; 3]>,
    /// Largest |D − Dᴴ| / max|D_ab| over the zone (the symmetric part is diagonalised).
    pub max_asymmetry: Option<f64>,
    /// Where the kernel's W* first turns negative, as κΔx = k_h/(h/Δx) (null if never in the
    /// scanned range).
    pub wstar_first_negative_kdx: Option<f64>,
}

/// Where growth starts for one kernel × lattice × σ̄ (smallest h of the grid).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Onset {
    /// Kernel.
    pub kernel: String,
    /// Lattice.
    pub lattice: String,
    /// σ̄.
    pub stress: f64,
    /// Rows computed (not skipped).
    pub computed: usize,
    /// Rows skipped.
    pub skipped: usize,
    /// Largest h/Δx computed.
    pub h_max_computed: Option<f64>,
    /// Smallest h/Δx with any growth, and its N_H.
    pub first_growth: Option<(f64, usize)>,
    /// Smallest h/Δx with longitudinal (pairing) growth, and its N_H.
    pub first_pairing: Option<(f64, usize)>,
    /// Computed rows with pairing growth.
    pub pairing_rows: usize,
    /// Largest pairing growth over h (c/Δx).
    pub max_pairing_growth: f64,
}

/// The study.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct PairingReport {
    /// Always `classical`.
    pub form: String,
    /// Always `sph`.
    pub shape: String,
    /// Always `hydro` (p = K(ρ/ρ0 − 1), σ̄ = 1 − ρ/ρ0).
    pub material: String,
    /// How Δx is defined.
    pub dx: String,
    /// Wave vectors per reciprocal direction.
    pub grid: usize,
    /// Growth threshold (c/Δx).
    pub growth_tol: f64,
    /// h/Δx values.
    pub h_values: Vec<f64>,
    /// σ̄ values.
    pub stresses: Vec<f64>,
    /// W* sign criterion per kernel.
    pub kernels: Vec<WStarSign>,
    /// Rows, kernel × lattice × h × σ̄ in that order.
    pub rows: Vec<PairingRow>,
    /// Onsets per kernel × lattice × σ̄.
    pub onsets: Vec<Onset>,
    /// Wall-clock time (s).
    pub runtime_s: f64,
    /// Rayon threads.
    pub threads: usize,
}

fn opt(v: Option<f64>, prec: usize) -> String {
    v.map_or_else(|| "—".into(), |x| format!("{x:.prec$}"))
}

/// The human-readable table: the W* criterion per kernel, then one line per row, then the
/// onsets.
pub fn table(rep: &PairingReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "pairing study: {} / {} / {} material, Δx = {}, zone sampled {}³, growth > {:e} c/Δx",
        rep.form, rep.shape, rep.material, rep.dx, rep.grid, rep.growth_tol
    );
    let _ = writeln!(
        s,
        "units: growth rates (growth, pairing, transverse, max pairing) in c/Δx, c = √(K/ρ0); σ̄ = σ/K (negative: pressure); h, R in Δx"
    );
    let _ = writeln!(
        s,
        "\nkernel 3D Fourier transform W*(k)/W*(0), k in 1/h over [0, {}]",
        rep.kernels.first().map_or(0.0, |k| k.k_max)
    );
    let _ = writeln!(
        s,
        "{:<12} {:>4} {:>13} {:>9} {:>9} {:>13}",
        "kernel", "ζ", "min W*", "k at min", "negative", "first k < 0"
    );
    for k in &rep.kernels {
        let _ = writeln!(
            s,
            "{:<12} {:>4} {:>13.4e} {:>9.4} {:>9} {:>13}",
            k.kernel,
            k.zeta,
            k.min,
            k.k_at_min,
            if k.negative { "yes" } else { "no" },
            opt(k.first_negative_k, 6)
        );
    }
    let _ = writeln!(
        s,
        "\n{:<12} {:<4} {:>5} {:>6} {:>5} {:>7} {:>11} {:>8} {:>6} {:>11} {:>11} {:>9}",
        "kernel",
        "lat",
        "h/Δx",
        "R/Δx",
        "N_H",
        "σ̄",
        "growth",
        "|κ|Δx/π",
        "L-frac",
        "pairing",
        "transverse",
        "W*<0 κΔx"
    );
    for r in &rep.rows {
        let _ = writeln!(s, "{}", row_line(r));
    }
    let _ = writeln!(
        s,
        "\nonsets (smallest h/Δx with growth; pairing = a longitudinal mode, |ê·k̂|² ≥ ½)"
    );
    let _ = writeln!(
        s,
        "{:<12} {:<4} {:>7} {:>16} {:>16} {:>13} {:>9}",
        "kernel", "lat", "σ̄", "growth at h (N_H)", "pairing at h (N_H)", "max pairing", "computed"
    );
    let at =
        |v: Option<(f64, usize)>| v.map_or_else(|| "none".into(), |(h, n)| format!("{h:.2} ({n})"));
    for o in &rep.onsets {
        let _ = writeln!(
            s,
            "{:<12} {:<4} {:>7} {:>16} {:>16} {:>13.6} {:>5}/{:<3}",
            o.kernel,
            o.lattice,
            crate::display::num(o.stress),
            at(o.first_growth),
            at(o.first_pairing),
            o.max_pairing_growth,
            o.computed,
            o.computed + o.skipped
        );
    }
    s
}

fn row_line(r: &PairingRow) -> String {
    let head = format!(
        "{:<12} {:<4} {:>5.2} {:>6.3} {:>5} {:>7}",
        r.kernel,
        r.lattice,
        r.h_over_dx,
        r.support_over_dx,
        r.n_h,
        crate::display::num(r.stress)
    );
    if let Some(why) = &r.skipped {
        return format!("{head}  skipped: {why}");
    }
    format!(
        "{head} {:>11.6} {:>8} {:>6} {:>11.6} {:>11.6} {:>9}",
        r.max_growth_rate.unwrap_or(0.0),
        opt(r.kappa_abs_over_pi, 4),
        opt(r.longitudinal_fraction, 3),
        r.pairing_growth_rate.unwrap_or(0.0),
        r.transverse_growth_rate.unwrap_or(0.0),
        opt(r.wstar_first_negative_kdx, 4)
    )
}

/// Which growth rate a panel row shows.
#[derive(Clone, Copy)]
enum Quantity {
    Pairing,
    Transverse,
}

/// The figure: one strip per kernel (label: its W* sign) against N_H (log), coloured by the
/// largest growth rate (c/Δx; white: stable, grey: not computed), so the pairing onset — where
/// a strip turns from white to colour — reads at a glance. One column of panels per lattice;
/// one row per σ̄ (most negative first) with the pairing (longitudinal) growth, then one row
/// with the transverse growth at the most negative σ̄. Where several h give one N_H, the
/// largest growth is drawn.
pub fn figure_svg(rep: &PairingReport) -> Result<String> {
    let mut lattices: Vec<&str> = Vec::new();
    for r in &rep.rows {
        if !lattices.contains(&r.lattice.as_str()) {
            lattices.push(&r.lattice);
        }
    }
    let mut stresses = rep.stresses.clone();
    stresses.sort_by(f64::total_cmp);
    let mut rows: Vec<(Quantity, f64)> = stresses.iter().map(|&s| (Quantity::Pairing, s)).collect();
    if let Some(&s) = stresses.first() {
        rows.push((Quantity::Transverse, s));
    }
    let mut panels = Vec::new();
    for &(what, s) in &rows {
        for &l in &lattices {
            let strips = rep
                .kernels
                .iter()
                .map(|k| {
                    rep.rows
                        .iter()
                        .filter(|r| r.kernel == k.kernel && r.lattice == l && r.stress == s)
                        .filter(|r| r.n_h > 0)
                        .map(|r| {
                            let g = match what {
                                Quantity::Pairing => r.pairing_growth_rate,
                                Quantity::Transverse => r.transverse_growth_rate,
                            };
                            (r.n_h as f64, if r.skipped.is_some() { None } else { g })
                        })
                        .collect()
                })
                .collect();
            panels.push(StripPanel {
                title: l.to_string(),
                rows: strips,
            });
        }
    }
    let row_titles: Vec<String> = rows
        .iter()
        .map(|&(what, s)| {
            let label = match what {
                Quantity::Pairing => "pairing: largest longitudinal growth",
                Quantity::Transverse => "largest transverse growth",
            };
            format!("{label}, σ̄ = {}", crate::display::num(s).replace('-', "−"))
        })
        .collect();
    let labels: Vec<String> = rep
        .kernels
        .iter()
        .map(|k| {
            format!(
                "{} ({})",
                k.kernel,
                if k.negative { "W* < 0" } else { "W* ≥ 0" }
            )
        })
        .collect();
    strips_svg(
        "N_H (particles inside the support)",
        "largest growth rate (c/Δx)",
        &labels,
        &panels,
        lattices.len(),
        &row_titles,
        rep.growth_tol,
    )
}
