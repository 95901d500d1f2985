//! The kernel guide's rows and the markdown table `sphstab kernels --table` prints.

use super::config::{
    GUIDE_FORMS, ONSET_BISECTIONS, REFERENCE_TENSION, TENSION_CAP, TENSION_FLOOR, WSTAR_K_STEP,
};
use crate::studies::pairing::wstar::{self, WStarSign};
use serde::{Deserialize, Serialize};

/// Time step and accuracy of one form at one h.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct TimeStepCell {
    /// Form.
    pub form: String,
    /// Shape family (the form's default).
    pub shape: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// R/Δx.
    pub support_over_dx: f64,
    /// Critical Δt of `kdk` (Δx/c); null if the semi-discrete system grows at σ̄ = 0.
    pub critical_dt: Option<f64>,
    /// c Δt_crit / h.
    pub critical_cfl: Option<f64>,
    /// Δt of the error columns (Δx/c) = [`SAFETY`](super::SAFETY) × `critical_dt`.
    pub dt_used: Option<f64>,
    /// Phase error per wavelength travelled (radians; negative: the wave lags), 10 ppw.
    pub phase_error_10ppw: Option<f64>,
    /// The same at 20 ppw.
    pub phase_error_20ppw: Option<f64>,
    /// Amplitude error per wavelength travelled, 10 ppw (|λ|^{T/Δt} − 1).
    pub amplitude_error_10ppw: Option<f64>,
    /// The same at 20 ppw.
    pub amplitude_error_20ppw: Option<f64>,
}

/// A closed interval of the h/Δx grid.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
pub struct Interval {
    /// First grid value.
    pub from: f64,
    /// Last grid value.
    pub to: f64,
}

/// The compression scan of one kernel in one dimension.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct CompressionScan {
    /// 1 or 2.
    pub dim: u8,
    /// `elastic` (1D bar, C̄ = C + σ) or `hydro` (2D, square lattice).
    pub material: String,
    /// σ̄.
    pub stress: f64,
    /// First and last h/Δx computed (null if none).
    pub scanned: Option<Interval>,
    /// Grid values inside the scanned range that were computed (all of them).
    pub computed: usize,
    /// h/Δx where no mode grows.
    pub stable: Vec<Interval>,
    /// 2D: h/Δx where no longitudinal mode grows (no pairing; transverse modes of the
    /// zero-shear fluid may grow); 1D: every mode is longitudinal, the same as `stable`.
    pub no_pairing: Vec<Interval>,
}

/// Where classical SPH starts to grow in tension at one h (1D).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct TensileOnset {
    /// h/Δx.
    pub h_over_dx: f64,
    /// `any` (grows at σ̄ = [`TENSION_FLOOR`] already), `onset` or `none` (stable up to
    /// [`TENSION_CAP`]).
    pub kind: String,
    /// The smallest σ̄ found growing (`onset`; for `any`, [`TENSION_FLOOR`]).
    pub onset: Option<f64>,
    /// The largest σ̄ found stable below it (0 for `any`).
    pub last_stable: Option<f64>,
    /// How fast it grows in moderate tension: the largest growth rate at σ̄ =
    /// [`REFERENCE_TENSION`] (c/Δx; 0 if stable there).
    pub growth_at_reference: f64,
}

/// The W* sign in one dimension.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Positivity {
    /// 1, 2 or 3.
    pub dim: u8,
    /// The scan ([`wstar::sign_criterion_in`]): first κh with W* < 0, minimum of W*/W*(0).
    pub sign: WStarSign,
}

/// Everything about one kernel.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct KernelGuideRow {
    /// Kernel.
    pub kernel: String,
    /// ζ.
    pub zeta: f64,
    /// [form × h] time-step cells, in the order of [`GUIDE_FORMS`] × [`GUIDE_H`](super::GUIDE_H).
    pub time_step: Vec<TimeStepCell>,
    /// 1D and 2D compression scans.
    pub compression: Vec<CompressionScan>,
    /// Tensile onset at each of [`GUIDE_H`](super::GUIDE_H).
    pub tension: Vec<TensileOnset>,
    /// W* in 1D, 2D, 3D.
    pub positivity: Vec<Positivity>,
}

/// The guide.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct KernelGuide {
    /// Integrator of the time-step columns.
    pub integrator: String,
    /// κ points of the 1D analyses.
    pub kappa_points: usize,
    /// Δt of the error columns / Δt_crit.
    pub safety: f64,
    /// h/Δx of the time-step and tension columns.
    pub h_values: Vec<f64>,
    /// Step of the compression scans.
    pub h_step: f64,
    /// The h/Δx interval of the compression scans.
    pub scan_h: (f64, f64),
    /// σ̄ of the compression scans.
    pub compression_stress: f64,
    /// 2D wave vectors per direction.
    pub grid_2d: usize,
    /// Largest R/Δx of the 2D scan.
    pub max_support_2d: f64,
    /// Growth threshold (c/Δx).
    pub growth_tol: f64,
    /// Upper end of the W* scan (κh).
    pub wstar_k_max: f64,
    /// One row per kernel.
    pub rows: Vec<KernelGuideRow>,
}

fn opt(v: Option<f64>, prec: usize) -> String {
    v.map_or("—".into(), |x| format!("{x:.prec$}"))
}

fn fmt_intervals(v: &[Interval]) -> String {
    if v.is_empty() {
        return "none".into();
    }
    v.iter()
        .map(|i| {
            if i.from == i.to {
                format!("{:.2}", i.from)
            } else {
                format!("{:.2}–{:.2}", i.from, i.to)
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn fmt_onset(t: &TensileOnset) -> String {
    let at = match (t.kind.as_str(), t.onset) {
        ("any", _) => "any σ̄ > 0".into(),
        ("onset", Some(s)) if s >= 0.01 => format!("{s:.4}"),
        ("onset", Some(s)) => format!("{s:.3e}"),
        _ => return format!("none ≤ {TENSION_CAP}"),
    };
    if t.growth_at_reference > 0.0 {
        format!("{at} ({:.4})", t.growth_at_reference)
    } else {
        at
    }
}

fn fmt_min(m: f64) -> String {
    if m.abs() <= wstar::NEGATIVE_TOL {
        "0".into()
    } else {
        format!("{m:.2e}")
    }
}

/// The guide as Markdown (what `sphstab kernels --table` prints).
pub fn markdown(g: &KernelGuide) -> String {
    let [h1, h2] = [g.h_values[0], g.h_values[1]];
    let mut s = format!(
        "Kernel guide (`sphstab kernels --table --json` gives every number): time steps, phase errors and tensile onsets \
from the engine; the compression columns from the derived closed form of classical SPH on lattice sums \
(`vonneumann::derived`, equal to the engine to 1e-12 where tested); W* by quadrature of the kernel's transform. \
h = h/Δx in the kernel's own convention, support R = ζh; 1D periodic chain unless stated; no viscosity.\n\n\
**Time step and accuracy** (1D, σ̄ = 0, `{}`, {} κ points in (0, π]): CFL = c Δt_crit/h (the cells of \
`tradeoff --cfl-table`); phase error = (ω_num − ω)·T in radians per wavelength travelled (negative: the wave lags; \
spatial and temporal error together), `{}` at Δt = {} Δt_crit, at 10 and 20 points per wavelength (ppw).\n",
        g.integrator, g.kappa_points, g.integrator, g.safety
    );
    for f in GUIDE_FORMS {
        let shape = g
            .rows
            .first()
            .and_then(|r| r.time_step.iter().find(|c| c.form == f))
            .map_or("", |c| c.shape.as_str());
        s += &format!(
            "\n**{f}** ({shape})\n\n| kernel | ζ | CFL, h = {h1} | CFL, h = {h2} | phase 10 ppw, h = {h1} | phase 20 ppw, h = {h1} | phase 10 ppw, h = {h2} | phase 20 ppw, h = {h2} |\n|---|---:|---:|---:|---:|---:|---:|---:|\n"
        );
        for r in &g.rows {
            let cell = |h: f64| r.time_step.iter().find(|c| c.form == f && c.h_over_dx == h);
            let (a, b) = (cell(h1), cell(h2));
            s += &format!(
                "| {} | {} | {} | {} | {} | {} | {} | {} |\n",
                r.kernel,
                r.zeta,
                opt(a.and_then(|c| c.critical_cfl), 3),
                opt(b.and_then(|c| c.critical_cfl), 3),
                opt(a.and_then(|c| c.phase_error_10ppw), 4),
                opt(a.and_then(|c| c.phase_error_20ppw), 4),
                opt(b.and_then(|c| c.phase_error_10ppw), 4),
                opt(b.and_then(|c| c.phase_error_20ppw), 4),
            );
        }
    }
    s += &format!(
        "\n**Stability of classical SPH** (`sph` shapes). Compression: σ̄ = {} (pressure {} C), h/Δx scanned over \
[{}, {}] in steps of {} from the first value with a neighbour in the support (ζh > Δx); 1D elastic bar, {} κ points; \
2D hydro on the square lattice, {}² − 1 wave vectors, up to R = ζh ≤ {}Δx (column `2D scanned`), \
`no pairing` = no growing longitudinal mode (|ê·k̂|² ≥ ½), `no growth` = no growing mode at all (the zero-shear \
fluid also grows through transverse modes). Tension: the smallest σ̄ > 0 at which the 1D chain grows (scan, then \
{} bisections; `any σ̄ > 0`: it grows at σ̄ = {:e} already, where the growth rate ∝ √σ̄), in brackets the \
largest growth rate at σ̄ = {} (c/Δx).\n\n\
| kernel | 1D stable in compression | 2D scanned | 2D no pairing | 2D no growth | tensile onset σ̄, h = {h1} | tensile onset σ̄, h = {h2} |\n|---|---|---|---|---|---|---|\n",
        g.compression_stress,
        -g.compression_stress,
        g.scan_h.0,
        g.scan_h.1,
        g.h_step,
        g.kappa_points,
        g.grid_2d,
        g.max_support_2d,
        ONSET_BISECTIONS,
        TENSION_FLOOR,
        REFERENCE_TENSION,
    );
    for r in &g.rows {
        let c1 = r.compression.iter().find(|c| c.dim == 1);
        let c2 = r.compression.iter().find(|c| c.dim == 2);
        let t = |h: f64| {
            r.tension
                .iter()
                .find(|t| t.h_over_dx == h)
                .map_or("—".into(), fmt_onset)
        };
        s += &format!(
            "| {} | {} | {} | {} | {} | {} | {} |\n",
            r.kernel,
            c1.map_or("—".into(), |c| fmt_intervals(&c.stable)),
            c2.and_then(|c| c.scanned)
                .map_or("—".into(), |i| format!("{:.2}–{:.2}", i.from, i.to)),
            c2.map_or("—".into(), |c| fmt_intervals(&c.no_pairing)),
            c2.map_or("—".into(), |c| fmt_intervals(&c.stable)),
            t(h1),
            t(h2),
        );
    }
    s += &format!(
        "\n**Continuous-kernel positivity**: the first κh at which the kernel's Fourier transform W*(κ) turns \
negative (W*/W*(0) < −{:e}), per dimension (the dimension's own kernel: Wendland changes with it), scanned over \
κh ∈ [0, {}] in steps of {} (then bisected); `never` = not up to κh = {}. Smallest W*/W*(0) in brackets.\n\n\
| kernel | 1D | 2D | 3D |\n|---|---|---|---|\n",
        wstar::NEGATIVE_TOL,
        g.wstar_k_max,
        WSTAR_K_STEP,
        g.wstar_k_max
    );
    for r in &g.rows {
        let p = |d: u8| {
            r.positivity
                .iter()
                .find(|p| p.dim == d)
                .map_or("—".into(), |p| match p.sign.first_negative_k {
                    Some(k) => format!("{k:.3} ({})", fmt_min(p.sign.min)),
                    None => format!("never ({})", fmt_min(p.sign.min)),
                })
        };
        s += &format!("| {} | {} | {} | {} |\n", r.kernel, p(1), p(2), p(3));
    }
    s
}
