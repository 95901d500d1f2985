//! The pairing study (SPEC §5.7): classical SPH (sum form, `sph` shapes) with a hydrodynamic
//! material under positive pressure (σ̄ < 0) on the simple-cubic, bcc and fcc lattices, for every
//! kernel × lattice × h/Δx — the largest growth rate over the Brillouin zone and its wave
//! vector and polarisation, against the neighbour number N_H and next to the kernel's 3D
//! Fourier-transform sign criterion ([`wstar`], Dehnen & Aly 2012).
//!
//! Conventions (crate docs): Δx = (volume per particle)^⅓, so the three lattices have the same
//! density; growth rates in c/Δx, c² = K/ρ0; wave vectors κΔx in the first zone. N_H is the
//! number of lattice particles inside the support, |r| < R = ζh, the particle itself included
//! (the support test of every neighbour search); `n_h_continuum` = (4π/3)(R/Δx)³ is the
//! neighbour number of a uniform continuum (Dehnen & Aly's N_H = 4πH³n/3, H the support radius).
//!
//! A mode grows when γ > [`GROWTH_TOL`] (1e-6 c/Δx); below it the row reports growth 0 and no
//! wave vector. A mode is longitudinal when its longitudinal fraction |ê·k̂|² is ≥ ½ (degenerate
//! eigenspaces: see [`DEGENERACY_TOL`]) — pairing is the longitudinal instability (particles
//! approach each other in pairs along k); in a zero-shear material under pressure the sum form
//! can also grow through transverse modes, reported separately.
//! Rows whose linearisation would exceed the memory budget ([`crate::budget`]; large supports of
//! the ζ = 3 kernels) and rows whose support holds no neighbour are reported as skipped, with the
//! reason, not as errors.

pub mod report;
pub mod wstar;

pub use report::{figure_svg, figure_title, table};

use crate::analysis::{MaterialSpec, Query, max_grid};
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::kernel::{self, Kernel};
use crate::lattice::Lattice3D;
use crate::shape::ShapeFamily;
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::linearise::Bloch;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use wstar::WStarSign;

/// Names of the lattices of the study.
pub const LATTICES: [&str; 3] = ["sc", "bcc", "fcc"];
/// Largest number of h/Δx values.
pub const MAX_H_VALUES: usize = 1000;
/// Largest number of stresses.
pub const MAX_STRESSES: usize = 16;
/// h/Δx range accepted by `--h-min`/`--h-max`.
pub const H_LIMITS: (f64, f64) = (0.1, 10.0);
/// σ̄ range accepted by `--stresses` (hydro: σ̄ = 1 − ρ/ρ0 < 1).
pub const STRESS_LIMITS: (f64, f64) = (-10.0, 1.0);
/// A branch with |ê·k̂|² ≥ this is longitudinal.
pub const LONGITUDINAL: f64 = 0.5;

/// What to compute (CLI flags or an `analysis/` JSON config).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PairingConfig {
    /// Kernel names (empty: all eleven).
    #[serde(default)]
    pub kernels: Vec<String>,
    /// Lattice names (sc, bcc, fcc; empty: all three).
    #[serde(default)]
    pub lattices: Vec<String>,
    /// Smallest h/Δx.
    #[serde(default = "default_h_min")]
    pub h_min: f64,
    /// Largest h/Δx.
    #[serde(default = "default_h_max")]
    pub h_max: f64,
    /// Step of h/Δx.
    #[serde(default = "default_h_step")]
    pub h_step: f64,
    /// Pre-stresses σ̄ (negative: pressure).
    #[serde(default = "default_stresses")]
    pub stresses: Vec<f64>,
    /// Wave vectors per reciprocal direction (grid³ − 1 sampled).
    #[serde(default = "default_grid")]
    pub grid: usize,
    /// Figure file written into figures/ (with the data next to it, same name, .json).
    #[serde(default)]
    pub output: Option<String>,
    /// What the figure shows (kept with the config).
    #[serde(default)]
    pub note: String,
}

fn default_h_min() -> f64 {
    0.8
}
fn default_h_max() -> f64 {
    3.0
}
fn default_h_step() -> f64 {
    0.1
}
fn default_stresses() -> Vec<f64> {
    vec![-0.01, -0.1]
}
fn default_grid() -> usize {
    crate::analysis::default_grid(3)
}

impl Default for PairingConfig {
    fn default() -> Self {
        Self {
            kernels: Vec::new(),
            lattices: Vec::new(),
            h_min: default_h_min(),
            h_max: default_h_max(),
            h_step: default_h_step(),
            stresses: default_stresses(),
            grid: default_grid(),
            output: None,
            note: String::new(),
        }
    }
}

/// The analysis config of the full study (every kernel × sc, bcc, fcc × h/Δx = 0.8…3 step 0.1
/// × σ̄ = −0.01, −0.1 at 16³ wave vectors: 1,518 rows, ~47 min), which writes
/// `figures/pairing3d.{svg,json}`.
pub const FULL_STUDY_CONFIG: &str = "analysis/pairing3d.json";

/// What [`PairingConfig::quick`] computes, in words (printed by bare `sphstab pairing`).
pub const QUICK_DESCRIPTION: &str = "default quick subset: m4 (W* < 0) and wendland-c2 (W* ≥ 0) on sc, h/Δx = 0.8…2 step 0.2, σ̄ = −0.01, −0.1, 16³ wave vectors (its rows are rows of the full study)";

impl PairingConfig {
    /// The command line's default (bare `sphstab pairing`): a subset that runs in seconds — one
    /// kernel whose W* turns negative (m4) and one whose W* does not (wendland-c2), on the
    /// simple-cubic lattice, h/Δx = 0.8…2 in steps of 0.2, both stresses, the full study's 16³
    /// wave vectors (so its 28 rows are rows of [`FULL_STUDY_CONFIG`]'s study). Flags not given
    /// keep these values.
    pub fn quick() -> Self {
        Self {
            kernels: vec!["m4".into(), "wendland-c2".into()],
            lattices: vec!["sc".into()],
            h_min: 0.8,
            h_max: 2.0,
            h_step: 0.2,
            ..Self::default()
        }
    }
}

/// Parses a study config; `file` names it in errors (unknown fields are rejected by name, as is
/// an `output` that is not a plain .svg file name: [`crate::studies::config`]).
pub fn parse_config(file: &str, text: &str) -> Result<PairingConfig> {
    let cfg: PairingConfig = crate::studies::config::parse_json(file, text)?;
    crate::studies::config::check_output(file, cfg.output.as_deref())?;
    Ok(cfg)
}

/// The validated grid of a study.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Kernels.
    pub kernels: Vec<&'static dyn Kernel>,
    /// Lattices with their names.
    pub lattices: Vec<(&'static str, Lattice3D)>,
    /// h/Δx values (rounded to 1e-10, so 0.8 + 3·0.1 is 1.1).
    pub h: Vec<f64>,
    /// σ̄ values.
    pub stresses: Vec<f64>,
    /// Wave vectors per direction.
    pub grid: usize,
}

impl Plan {
    /// Rows of the study (kernel × lattice × h × σ̄).
    pub fn rows(&self) -> usize {
        self.kernels.len() * self.lattices.len() * self.h.len() * self.stresses.len()
    }
}

fn no_duplicates(flag: &'static str, names: &[&str]) -> Result<()> {
    for (i, n) in names.iter().enumerate() {
        if names[..i].contains(n) {
            return Err(Error::Incompatible(format!("{flag}: `{n}` is given twice")));
        }
    }
    Ok(())
}

/// Validates a config (errors name the CLI flag) and checks the work against the budget: the
/// rows × (grid³ − 1) wave-vector evaluations count against 10 × `--max-steps`, as in the atlas.
pub fn plan(cfg: &PairingConfig) -> Result<Plan> {
    let kernels: Vec<&'static dyn Kernel> = if cfg.kernels.is_empty() {
        kernel::all().to_vec()
    } else {
        cfg.kernels
            .iter()
            .map(|k| kernel::by_name(k))
            .collect::<Result<_>>()?
    };
    no_duplicates(
        "--kernels",
        &kernels.iter().map(|k| k.name()).collect::<Vec<_>>(),
    )?;
    let lattice_names: Vec<&str> = if cfg.lattices.is_empty() {
        LATTICES.to_vec()
    } else {
        cfg.lattices.iter().map(String::as_str).collect()
    };
    no_duplicates("--lattices", &lattice_names)?;
    let lattices =
        lattice_names
            .iter()
            .map(|&n| {
                let name = LATTICES.iter().copied().find(|&l| l == n).ok_or_else(|| {
                    Error::UnknownName {
                        what: "lattice (--lattices)",
                        given: n.to_string(),
                        valid: LATTICES.join(", "),
                    }
                })?;
                Ok((name, Lattice3D::by_name(name)?))
            })
            .collect::<Result<Vec<_>>>()?;
    let (lo, hi) = H_LIMITS;
    crate::error::check_range("--h-min", cfg.h_min, lo, hi, true, true)?;
    crate::error::check_range("--h-max", cfg.h_max, lo, hi, true, true)?;
    if cfg.h_max < cfg.h_min {
        return Err(Error::OutOfRange {
            name: "--h-max",
            value: cfg.h_max,
            range: format!("must be ≥ --h-min = {}", cfg.h_min),
        });
    }
    crate::error::check_range("--h-step", cfg.h_step, 1e-3, hi, true, true)?;
    let steps = ((cfg.h_max - cfg.h_min) / cfg.h_step + 1e-9).floor() as usize;
    if steps + 1 > MAX_H_VALUES {
        return Err(Error::OutOfRange {
            name: "--h-step",
            value: cfg.h_step,
            range: format!(
                "gives {} h values; at most {MAX_H_VALUES} (raise --h-step or narrow --h-min/--h-max)",
                steps + 1
            ),
        });
    }
    let h = (0..=steps)
        .map(|i| ((cfg.h_min + i as f64 * cfg.h_step) * 1e10).round() / 1e10)
        .collect();
    if cfg.stresses.is_empty() || cfg.stresses.len() > MAX_STRESSES {
        return Err(Error::OutOfRange {
            name: "--stresses",
            value: cfg.stresses.len() as f64,
            range: format!("give 1 to {MAX_STRESSES} values"),
        });
    }
    for &s in &cfg.stresses {
        crate::error::check_range(
            "--stresses",
            s,
            STRESS_LIMITS.0,
            STRESS_LIMITS.1,
            true,
            false,
        )?;
    }
    crate::analysis::check_count("--grid", cfg.grid, 2, max_grid(3))?;
    let plan = Plan {
        kernels,
        lattices,
        h,
        stresses: cfg.stresses.clone(),
        grid: cfg.grid,
    };
    let budget = crate::budget::current();
    budget.work(
        "--grid/--kernels/--lattices/--h-step/--stresses",
        "the pairing study",
        plan.rows() as f64 * (cfg.grid.pow(3) - 1) as f64,
        "wave-vector evaluations",
        10.0 * budget.max_steps,
    )?;
    Ok(plan)
}

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

/// Particles within |r| < `r` (units Δx) of a lattice point, itself included.
pub fn neighbour_count(lat: &Lattice3D, r: f64) -> usize {
    lat.offsets_within(r).len()
}

#[derive(Clone, Copy, Default)]
struct Mode {
    growth: f64,
    k: [f64; 3],
    lf: f64,
}

impl Mode {
    fn take(&mut self, o: Mode) {
        if o.growth > self.growth {
            *self = o;
        }
    }
    fn merge(mut self, o: Mode) -> Mode {
        self.take(o);
        self
    }
    fn grows(&self) -> bool {
        self.growth > GROWTH_TOL
    }
    fn rate(&self) -> f64 {
        if self.grows() { self.growth } else { 0.0 }
    }
}

/// The fastest mode, the fastest longitudinal and the fastest transverse mode over a set of
/// wave vectors, and the largest relative asymmetry |D − Dᴴ|/max|D_ab| met.
#[derive(Clone, Copy, Default)]
struct Scan {
    all: Mode,
    long: Mode,
    trans: Mode,
    asymmetry: f64,
}

impl Scan {
    fn merge(self, o: Scan) -> Scan {
        Scan {
            all: self.all.merge(o.all),
            long: self.long.merge(o.long),
            trans: self.trans.merge(o.trans),
            asymmetry: self.asymmetry.max(o.asymmetry),
        }
    }
}

/// Eigenvalues closer than this (relative to the largest |ω²| at k) form one eigenspace.
pub const DEGENERACY_TOL: f64 = 1e-9;

/// The modes at one wave vector. The dynamical matrix of the classical form with `sph` shapes
/// is real symmetric (ρD = (ρ + 2σ̄)S1S1ᵀ − 2σ̄S2 with real lattice sums; the engine's D agrees to
/// round-off, recorded as `max_asymmetry`), so its symmetric part is diagonalised
/// ([`nalgebra::SymmetricEigen`], orthonormal eigenvectors) and degenerate eigenvalues are
/// grouped into eigenspaces: an eigenspace with ω² < 0 is longitudinal when it holds a mode with
/// |ê·k̂|² ≥ [`LONGITUDINAL`] (its longitudinal fraction = |P k̂|², P the projector onto it) and
/// transverse when it holds one with |ê·k̂|² < ½ (dimension ≥ 2, or a single mode with
/// |ê·k̂|² < ½). A degenerate longitudinal + transverse pair (e.g. at the M point of sc by
/// symmetry) counts for both.
fn scan_k<const D: usize>(lin: &Bloch<D>, k: [f64; D]) -> Result<Scan> {
    let d = lin.dynamical(k);
    let big = d.iter().flatten().map(|c| c.norm()).fold(0.0f64, f64::max);
    let m = nalgebra::DMatrix::from_fn(D, D, |a, b| 0.5 * (d[a][b].re + d[b][a].re));
    let asym = (0..D * D)
        .map(|i| (d[i / D][i % D] - d[i % D][i / D].conj()).norm())
        .fold(0.0f64, f64::max);
    let eig = nalgebra::SymmetricEigen::try_new(m, 1e-15, 1000)
        .ok_or(Error::NonFinite("pairing: symmetric eigen-decomposition"))?;
    let kn = k.iter().map(|c| c * c).sum::<f64>().sqrt();
    let mut k3 = [0.0; 3];
    k3[..D].copy_from_slice(&k);
    let mut idx: Vec<usize> = (0..D).collect();
    idx.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let scale = eig.eigenvalues.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut out = Scan {
        asymmetry: if big > 0.0 { asym / big } else { 0.0 },
        ..Scan::default()
    };
    let mut i = 0;
    while i < D {
        let lam = eig.eigenvalues[idx[i]];
        let mut j = i + 1;
        while j < D && eig.eigenvalues[idx[j]] - lam <= DEGENERACY_TOL * scale {
            j += 1;
        }
        if !lam.is_finite() {
            return Err(Error::NonFinite("pairing: dynamical matrix"));
        }
        let lf: f64 = if kn > 0.0 {
            idx[i..j]
                .iter()
                .map(|&c| {
                    let v = eig.eigenvectors.column(c);
                    let dot: f64 = (0..D).map(|a| v[a] * k[a]).sum();
                    (dot / kn).powi(2)
                })
                .sum::<f64>()
                .min(1.0)
        } else {
            0.0
        };
        let mode = Mode {
            growth: (-lam).max(0.0).sqrt(),
            k: k3,
            lf,
        };
        out.all.take(mode);
        if lf >= LONGITUDINAL {
            out.long.take(mode);
        }
        if j - i >= 2 || lf < LONGITUDINAL {
            out.trans.take(mode);
        }
        i = j;
    }
    Ok(out)
}

/// Growth over the sampled zone of a D-dimensional question (2D or 3D): the fastest mode, the
/// fastest longitudinal (pairing) and the fastest transverse mode (c/Δx, 0 when below
/// [`GROWTH_TOL`]), as [`evaluate_row`] scans them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ZoneGrowth {
    /// Largest growth rate of any mode.
    pub max_growth_rate: f64,
    /// Largest growth of a longitudinal mode (|ê·k̂|² ≥ ½): pairing.
    pub pairing_growth_rate: f64,
    /// Largest growth of a transverse mode.
    pub transverse_growth_rate: f64,
}

/// Linearises `q` at its stress and scans its wave-vector grid ([`Query::kgrid`], rayon) for
/// the fastest, the fastest longitudinal and the fastest transverse mode (module docs, the
/// eigenspace rule of the row scan). The dynamical matrix must be (nearly) Hermitian: the
/// classical form with `sph` shapes and no dissipation, as in the pairing study.
pub fn zone_growth<const D: usize>(q: &Query<D>) -> Result<ZoneGrowth> {
    let lin = q.linearise_at(q.stress)?;
    let scan = q
        .kgrid()
        .par_iter()
        .map(|&k| scan_k(&lin, k))
        .try_reduce(Scan::default, |x, y| Ok(x.merge(y)))?;
    if !scan.all.growth.is_finite() {
        return Err(Error::NonFinite("pairing growth rate"));
    }
    Ok(ZoneGrowth {
        max_growth_rate: scan.all.rate(),
        pairing_growth_rate: scan.long.rate(),
        transverse_growth_rate: scan.trans.rate(),
    })
}

/// The 3D question of one row (classical, sph, hydro).
pub fn row_query(
    kernel: &'static dyn Kernel,
    lattice: Lattice3D,
    h: f64,
    stress: f64,
    grid: usize,
) -> Query<3> {
    let mut q = Query::<3>::new(FormKind::Classical, kernel, h, stress);
    q.shape = ShapeFamily::Sph;
    q.material = MaterialSpec::Hydro;
    q.lattice = lattice;
    q.grid = grid;
    q
}

/// Computes one row: linearises once, scans the grid³ − 1 wave vectors of the zone (rayon).
/// Over the memory budget or with no neighbour in the support: a skipped row, not an error.
pub fn evaluate_row(
    kernel: &'static dyn Kernel,
    lattice: (&str, Lattice3D),
    h: f64,
    stress: f64,
    grid: usize,
    wstar_first_negative_k: Option<f64>,
) -> Result<PairingRow> {
    let r = kernel.zeta() * h;
    let n_h = neighbour_count(&lattice.1, r);
    let mut row = PairingRow {
        kernel: kernel.name().to_string(),
        lattice: lattice.0.to_string(),
        h_over_dx: h,
        support_over_dx: r,
        n_h,
        n_h_continuum: 4.0 / 3.0 * PI * r.powi(3),
        stress,
        skipped: None,
        max_growth_rate: None,
        kappa_at_max: None,
        kappa_abs_over_pi: None,
        longitudinal_fraction: None,
        pairing_growth_rate: None,
        pairing_kappa: None,
        transverse_growth_rate: None,
        transverse_kappa: None,
        max_asymmetry: None,
        wstar_first_negative_kdx: wstar_first_negative_k.map(|k| k / h),
    };
    if n_h <= 1 {
        row.skipped = Some(format!(
            "no neighbour inside the support (R = {r:.4}Δx, shorter than the nearest-neighbour distance)"
        ));
        return Ok(row);
    }
    let q = row_query(kernel, lattice.1, h, stress, grid);
    let lin = match q.linearise_at(stress) {
        Ok(l) => l,
        Err(e @ Error::Budget { .. }) => {
            row.skipped = Some(e.to_string());
            return Ok(row);
        }
        Err(e) => return Err(e),
    };
    let scan = q
        .kgrid()
        .par_iter()
        .map(|&k| scan_k(&lin, k))
        .try_reduce(Scan::default, |x, y| Ok(x.merge(y)))?;
    let (all, long, trans) = (scan.all, scan.long, scan.trans);
    if !all.growth.is_finite() {
        return Err(Error::NonFinite("pairing growth rate"));
    }
    row.max_asymmetry = Some(scan.asymmetry);
    row.max_growth_rate = Some(all.rate());
    if all.grows() {
        row.kappa_at_max = Some(all.k);
        row.kappa_abs_over_pi = Some(all.k.iter().map(|c| c * c).sum::<f64>().sqrt() / PI);
        row.longitudinal_fraction = Some(all.lf);
    }
    row.pairing_growth_rate = Some(long.rate());
    row.pairing_kappa = long.grows().then_some(long.k);
    row.transverse_growth_rate = Some(trans.rate());
    row.transverse_kappa = trans.grows().then_some(trans.k);
    Ok(row)
}

/// Onsets per kernel × lattice × σ̄ from the rows (in row order: h ascending).
pub fn onsets(rows: &[PairingRow]) -> Vec<Onset> {
    let mut out: Vec<Onset> = Vec::new();
    for r in rows {
        let i = match out
            .iter()
            .position(|o| o.kernel == r.kernel && o.lattice == r.lattice && o.stress == r.stress)
        {
            Some(i) => i,
            None => {
                out.push(Onset {
                    kernel: r.kernel.clone(),
                    lattice: r.lattice.clone(),
                    stress: r.stress,
                    computed: 0,
                    skipped: 0,
                    h_max_computed: None,
                    first_growth: None,
                    first_pairing: None,
                    pairing_rows: 0,
                    max_pairing_growth: 0.0,
                });
                out.len() - 1
            }
        };
        let o = &mut out[i];
        if r.skipped.is_some() {
            o.skipped += 1;
            continue;
        }
        o.computed += 1;
        o.h_max_computed = Some(r.h_over_dx);
        if r.max_growth_rate.unwrap_or(0.0) > 0.0 && o.first_growth.is_none() {
            o.first_growth = Some((r.h_over_dx, r.n_h));
        }
        let p = r.pairing_growth_rate.unwrap_or(0.0);
        if p > 0.0 {
            o.pairing_rows += 1;
            o.max_pairing_growth = o.max_pairing_growth.max(p);
            if o.first_pairing.is_none() {
                o.first_pairing = Some((r.h_over_dx, r.n_h));
            }
        }
    }
    out
}

/// Runs the study. Rows one after the other (each linearisation and wave-vector scan uses the
/// rayon pool, so memory stays within one row's budget check); `progress(done, total)` after
/// each row.
pub fn run(cfg: &PairingConfig, progress: impl Fn(usize, usize)) -> Result<PairingReport> {
    let t0 = std::time::Instant::now();
    let plan = plan(cfg)?;
    let signs: Vec<WStarSign> = plan
        .kernels
        .par_iter()
        .map(|&k| wstar::sign_criterion(k))
        .collect();
    let total = plan.rows();
    let mut rows = Vec::with_capacity(total);
    for (ki, &k) in plan.kernels.iter().enumerate() {
        for &lat in &plan.lattices {
            for &h in &plan.h {
                for &s in &plan.stresses {
                    rows.push(evaluate_row(
                        k,
                        lat,
                        h,
                        s,
                        plan.grid,
                        signs[ki].first_negative_k,
                    )?);
                    progress(rows.len(), total);
                }
            }
        }
    }
    Ok(PairingReport {
        form: FormKind::Classical.name().into(),
        shape: ShapeFamily::Sph.name().into(),
        material: "hydro".into(),
        dx: "(volume per particle)^(1/3)".into(),
        grid: plan.grid,
        growth_tol: GROWTH_TOL,
        h_values: plan.h.clone(),
        stresses: plan.stresses.clone(),
        onsets: onsets(&rows),
        kernels: signs,
        rows,
        runtime_s: t0.elapsed().as_secs_f64(),
        threads: rayon::current_num_threads(),
    })
}
