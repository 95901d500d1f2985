//! The kernel guide (`sphstab kernels --table`): for every kernel, the numbers a user needs to
//! pick a kernel, h, form and time step — each measured by the engine through the code path of
//! the command that answers the question alone, never typed in:
//!
//! | column | code path |
//! |---|---|
//! | critical CFL c Δt_crit/h, `kdk`, σ̄ = 0 | the `tradeoff --cfl-table` cells ([`crate::studies::tradeoff::cfl::cfl_cell`]: `timestep`'s bisection on the amplification matrices, [`CFL_POINTS`] κ points), through [`analyse`], which runs the same `IntegratorReport::of` |
//! | phase and amplitude error per wavelength travelled at 10 and 20 points per wavelength, `kdk` at [`SAFETY`] × Δt_crit | [`crate::studies::tradeoff::integrators::analyse`] (the trade-off study's `phase_error_10ppw`) |
//! | h/Δx stable in compression, 1D | [`Query1D`] (classical, `sph`, elastic bar) at σ̄ = [`COMPRESSION`]: growth over the κ grid (`query`) |
//! | h/Δx without pairing / without any growth in compression, 2D | [`crate::studies::pairing::zone_growth`] (the pairing study's zone scan, on the square lattice): classical, `sph`, hydro, σ̄ = [`COMPRESSION`] |
//! | tensile onset | the trade-off study's tension scan and bisection ([`crate::studies::tradeoff`]), 1D classical |
//! | first κh with W* < 0 in 1D, 2D, 3D | [`crate::studies::pairing::wstar::sign_criterion_with`] (the pairing study's W* scan, step [`WSTAR_K_STEP`]) |
//!
//! Conventions as everywhere (crate docs): h/Δx in the kernel's own convention, R = ζh, time
//! steps in Δx/c, σ̄ = σ/C positive in tension, growth when γ > [`GROWTH_TOL`] c/Δx. The
//! h/Δx scans start at the first grid value whose support holds a neighbour (ζh > Δx); the 2D
//! scan stops at R ≤ [`MAX_SUPPORT_2D`] Δx (the linearisation of a 2D patch costs ~R⁴: a few
//! seconds per h at R = 18Δx).

use crate::analysis::{MaterialSpec, Query1D, Query2D};
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::integrator::Integrator;
use crate::kernel::{self, Kernel};
use crate::shape::ShapeFamily;
use crate::studies::pairing::wstar::{self, WStarSign};
use crate::studies::tradeoff::cfl::CFL_POINTS;
use crate::studies::tradeoff::integrators::{IntegratorRow, analyse};
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::linearise::Linearisation;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Forms of the time-step columns.
pub const GUIDE_FORMS: [&str; 2] = ["classical", "total-lagrangian"];
/// h/Δx of the time-step and tension columns.
pub const GUIDE_H: [f64; 2] = [1.3, 2.0];
/// Points per wavelength of the phase-error columns.
pub const PPW: [f64; 2] = [10.0, 20.0];
/// Δt of the phase-error columns, as a fraction of the critical Δt.
pub const SAFETY: f64 = 0.9;
/// The h/Δx interval of the compression scans.
pub const SCAN_H: (f64, f64) = (0.8, 6.0);
/// Default step of the compression scans (`--h-step`).
pub const DEFAULT_H_STEP: f64 = 0.05;
/// Allowed `--h-step`.
pub const H_STEP_RANGE: (f64, f64) = (0.01, 1.0);
/// Pre-stress of the compression scans (pressure 0.01 C, as the trade-off study's
/// `stable_in_compression` and one of the pairing study's stresses).
pub const COMPRESSION: f64 = -0.01;
/// κ points in (0, π] of the 1D scans.
pub const KAPPAS_1D: usize = 256;
/// Wave vectors per direction of the 2D scan (16² − 1, the trade-off study's 2D grid).
pub const GRID_2D: usize = 16;
/// Largest support R/Δx of the 2D scan.
pub const MAX_SUPPORT_2D: f64 = 6.0;
/// Largest tension of the onset scan.
pub const TENSION_CAP: f64 = 0.999;
/// Tension below the scan: growth already here means growth for any tension (the tensile
/// growth rate vanishes like √σ̄, so it is still ~1e-4 c/Δx ≫ [`GROWTH_TOL`] here).
pub const TENSION_FLOOR: f64 = 1e-8;
/// Bisection steps of the tensile onset (bracket = scan gap / 2³⁰).
pub const ONSET_BISECTIONS: usize = 30;
/// Upper end of the W* scan, κh (units 1/h).
pub const WSTAR_K_MAX: f64 = wstar::K_MAX;
/// Step of the W* scan (κh); twice the pairing study's [`wstar::K_STEP`] (the sign changes are
/// bisected to 1e-12 either way; the negative lobes are ≳ 1 wide in κh).
pub const WSTAR_K_STEP: f64 = 0.01;

/// What to compute.
#[derive(Clone, Debug)]
pub struct GuideConfig {
    /// Kernels (default: all).
    pub kernels: Vec<&'static dyn Kernel>,
    /// Step of the h/Δx scans.
    pub h_step: f64,
}

impl Default for GuideConfig {
    fn default() -> Self {
        Self {
            kernels: kernel::all().to_vec(),
            h_step: DEFAULT_H_STEP,
        }
    }
}

impl GuideConfig {
    /// Validates the step (errors name the CLI flag).
    pub fn validate(&self) -> Result<()> {
        crate::error::check_range(
            "--h-step",
            self.h_step,
            H_STEP_RANGE.0,
            H_STEP_RANGE.1,
            true,
            true,
        )?;
        if self.kernels.is_empty() {
            return Err(Error::Incompatible("--kernels: give at least one".into()));
        }
        for (i, k) in self.kernels.iter().enumerate() {
            if self.kernels[..i].iter().any(|o| o.name() == k.name()) {
                return Err(Error::Incompatible(format!(
                    "--kernels: `{}` is given twice",
                    k.name()
                )));
            }
        }
        Ok(())
    }

    /// The h/Δx grid of the scans (rounded to 1e-10, so 0.8 + 3·0.05 is 0.95).
    pub fn h_grid(&self) -> Vec<f64> {
        let n = ((SCAN_H.1 - SCAN_H.0) / self.h_step + 1e-9).floor() as usize;
        (0..=n)
            .map(|i| ((SCAN_H.0 + i as f64 * self.h_step) * 1e10).round() / 1e10)
            .collect()
    }
}

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
    /// Δt of the error columns (Δx/c) = [`SAFETY`] × `critical_dt`.
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

/// The tension of [`TensileOnset::growth_at_reference`].
pub const REFERENCE_TENSION: f64 = 0.01;

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
    /// [form × h] time-step cells, in the order of [`GUIDE_FORMS`] × [`GUIDE_H`].
    pub time_step: Vec<TimeStepCell>,
    /// 1D and 2D compression scans.
    pub compression: Vec<CompressionScan>,
    /// Tensile onset at each of [`GUIDE_H`].
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

/// The time-step cell of `form` at `h`: [`analyse`] of the trade-off study at [`CFL_POINTS`] κ
/// points, whose critical Δt is the `timestep` code path of [`crate::studies::tradeoff::cfl::cfl_cell`]
/// (`IntegratorReport::of` on the same linearisation and κ grid; CFL = Δt_crit/h as there —
/// `tests/kernel_guide.rs` checks the two agree bit for bit).
pub fn time_step_cell(form: FormKind, k: &'static dyn Kernel, h: f64) -> Result<TimeStepCell> {
    let mut row = IntegratorRow::default();
    analyse(form, k, h, Integrator::Kdk, SAFETY, CFL_POINTS, &mut row)?;
    let q = Query1D::new(form, k, h, 0.0);
    q.validate()?;
    Ok(TimeStepCell {
        form: form.name().into(),
        shape: q.shape.name().into(),
        h_over_dx: h,
        support_over_dx: k.zeta() * h,
        critical_dt: row.critical_dt,
        critical_cfl: row.critical_dt.map(|d| d / h),
        dt_used: row.dt_used,
        phase_error_10ppw: row.phase_error_10ppw,
        phase_error_20ppw: row.phase_error_20ppw,
        amplitude_error_10ppw: row.amplitude_error_10ppw,
        amplitude_error_20ppw: row.amplitude_error_20ppw,
    })
}

/// The largest growth rate (c/Δx) of 1D classical SPH (`sph` shapes, elastic bar) at σ̄ over
/// [`KAPPAS_1D`] κ points.
pub fn max_growth_1d(k: &'static dyn Kernel, h: f64, stress: f64) -> Result<f64> {
    let mut q = Query1D::new(FormKind::Classical, k, h, stress);
    q.shape = ShapeFamily::Sph;
    q.points = KAPPAS_1D;
    let lin: Linearisation = q.linearise()?;
    let mut g: f64 = 0.0;
    for kap in q.kappas() {
        g = g.max(lin.growth(kap)?);
    }
    Ok(g)
}

/// Whether [`max_growth_1d`] exceeds [`GROWTH_TOL`].
pub fn grows_1d(k: &'static dyn Kernel, h: f64, stress: f64) -> Result<bool> {
    Ok(max_growth_1d(k, h, stress)? > GROWTH_TOL)
}

/// The 2D question of the scan: classical, `sph`, hydro, square lattice, [`GRID_2D`]².
pub fn query_2d(k: &'static dyn Kernel, h: f64, stress: f64) -> Query2D {
    let mut q = Query2D::new(FormKind::Classical, k, h, stress);
    q.shape = ShapeFamily::Sph;
    q.material = MaterialSpec::Hydro;
    q.grid = GRID_2D;
    q
}

/// Merges the grid values where `ok` into closed intervals.
pub fn intervals(h: &[f64], ok: &[bool]) -> Vec<Interval> {
    let mut out: Vec<Interval> = Vec::new();
    let mut open: Option<Interval> = None;
    for (&x, &good) in h.iter().zip(ok) {
        if !good {
            out.extend(open.take());
        } else if let Some(iv) = open.as_mut() {
            iv.to = x;
        } else {
            open = Some(Interval { from: x, to: x });
        }
    }
    out.extend(open);
    out
}

/// The compression scan of `k` in `dim` ∈ {1, 2} over `h` (module docs).
pub fn compression_scan(k: &'static dyn Kernel, dim: u8, h: &[f64]) -> Result<CompressionScan> {
    let hs: Vec<f64> = h
        .iter()
        .copied()
        .filter(|&x| k.zeta() * x > 1.0 && (dim == 1 || k.zeta() * x <= MAX_SUPPORT_2D + 1e-9))
        .collect();
    let res: Vec<(bool, bool)> = hs
        .par_iter()
        .map(|&x| -> Result<(bool, bool)> {
            if dim == 1 {
                let g = grows_1d(k, x, COMPRESSION)?;
                Ok((!g, !g))
            } else {
                let z = crate::studies::pairing::zone_growth(&query_2d(k, x, COMPRESSION))?;
                Ok((z.max_growth_rate == 0.0, z.pairing_growth_rate == 0.0))
            }
        })
        .collect::<Result<_>>()?;
    let stable: Vec<bool> = res.iter().map(|r| r.0).collect();
    let no_pair: Vec<bool> = res.iter().map(|r| r.1).collect();
    Ok(CompressionScan {
        dim,
        material: if dim == 1 { "elastic" } else { "hydro" }.into(),
        stress: COMPRESSION,
        scanned: hs.first().map(|&a| Interval {
            from: a,
            to: *hs.last().unwrap_or(&a),
        }),
        computed: hs.len(),
        stable: intervals(&hs, &stable),
        no_pairing: intervals(&hs, &no_pair),
    })
}

/// The tensile onset of 1D classical SPH at `h`: growth at [`TENSION_FLOOR`] means `any`;
/// otherwise the trade-off study's scan and bisection ([`ONSET_BISECTIONS`] steps) up to
/// [`TENSION_CAP`].
pub fn tensile_onset(k: &'static dyn Kernel, h: f64) -> Result<TensileOnset> {
    let g = max_growth_1d(k, h, REFERENCE_TENSION)?;
    let growth_at_reference = if g > GROWTH_TOL { g } else { 0.0 };
    let grows = |s: f64| grows_1d(k, h, s);
    if grows(TENSION_FLOOR)? {
        return Ok(TensileOnset {
            h_over_dx: h,
            kind: "any".into(),
            onset: Some(TENSION_FLOOR),
            last_stable: Some(0.0),
            growth_at_reference,
        });
    }
    let (lo, hi) = crate::studies::tradeoff::tension_limit(
        TENSION_CAP,
        ONSET_BISECTIONS,
        TENSION_FLOOR,
        grows,
    )?;
    Ok(match hi {
        Some(s) => TensileOnset {
            h_over_dx: h,
            kind: "onset".into(),
            onset: Some(s),
            last_stable: Some(lo),
            growth_at_reference,
        },
        None => TensileOnset {
            h_over_dx: h,
            kind: "none".into(),
            onset: None,
            last_stable: Some(lo),
            growth_at_reference,
        },
    })
}

/// One kernel's row.
pub fn kernel_row(k: &'static dyn Kernel, h_grid: &[f64]) -> Result<KernelGuideRow> {
    let mut ts_jobs = Vec::new();
    for f in GUIDE_FORMS {
        for h in GUIDE_H {
            ts_jobs.push((FormKind::by_name(f)?, h));
        }
    }
    let time_step = ts_jobs
        .par_iter()
        .map(|&(f, h)| time_step_cell(f, k, h))
        .collect::<Result<Vec<_>>>()?;
    let compression = [1u8, 2]
        .par_iter()
        .map(|&d| compression_scan(k, d, h_grid))
        .collect::<Result<Vec<_>>>()?;
    let tension = GUIDE_H
        .par_iter()
        .map(|&h| tensile_onset(k, h))
        .collect::<Result<Vec<_>>>()?;
    let positivity = [1u8, 2, 3]
        .par_iter()
        .map(|&d| Positivity {
            dim: d,
            sign: wstar::sign_criterion_with(k, d as usize, WSTAR_K_STEP),
        })
        .collect();
    Ok(KernelGuideRow {
        kernel: k.name().into(),
        zeta: k.zeta(),
        time_step,
        compression,
        tension,
        positivity,
    })
}

/// The guide (kernels in parallel).
pub fn kernel_guide(cfg: &GuideConfig) -> Result<KernelGuide> {
    cfg.validate()?;
    let h = cfg.h_grid();
    let rows = cfg
        .kernels
        .par_iter()
        .map(|&k| kernel_row(k, &h))
        .collect::<Result<Vec<_>>>()?;
    Ok(KernelGuide {
        integrator: Integrator::Kdk.name().into(),
        kappa_points: CFL_POINTS,
        safety: SAFETY,
        h_values: GUIDE_H.to_vec(),
        h_step: cfg.h_step,
        scan_h: SCAN_H,
        compression_stress: COMPRESSION,
        grid_2d: GRID_2D,
        max_support_2d: MAX_SUPPORT_2D,
        growth_tol: GROWTH_TOL,
        wstar_k_max: WSTAR_K_MAX,
        rows,
    })
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
        "Kernel guide: every number measured by the engine (`sphstab kernels --table --json` gives them all). \
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
