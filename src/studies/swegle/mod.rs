//! The Swegle test \[V21 §7.2\] in D ∈ {2, 3} dimensions, one code path: a square (cubic) block
//! of `size`^D particles (spacing 0.1 on [−1, 1]^D for size 21), outer `layers` layers fixed but
//! taking part in every sum (their density evolving by continuity, or frozen), hydrodynamic
//! aluminium ρ0 = 2.8, K = 0.686275, G = 0, initial density f ρ0 (f < 1 tension), the centre
//! particle kicked with v_x = 1e−10, no artificial viscosity. The measured exponential growth of
//! max |v| over the free particles is compared with the growth rate of the exact linear operator
//! of the same finite particle set (dense, up to [`MAX_DENSE_BOX_DOFS`] free degrees of
//! freedom) or of its admitted standing modes, and with the infinite lattice.

use crate::analysis::box_prediction;
use crate::error::{Error, Result, check_range};
use crate::forms::{FormKind, Material2D, Model, ModelParams2D, State, State2D, State3D};
use crate::kernel::Kernel;
use crate::lattice::{Lattice, LatticeKind};
use crate::shape::KernelParams;
use crate::shape::ShapeFamily;
use crate::solver::diagnostics::{GrowthFit, growth_fit};
use crate::solver::run2d::{BoundaryDensity, Run};
use crate::studies::box_operator::{MAX_DENSE_DOFS, box_growth};
use crate::vonneumann::linearise::Bloch;
use num_complex::Complex64;
use serde::Serialize;
use std::f64::consts::PI;

/// Largest number of free mechanical degrees of freedom (D × free particles) for which the box
/// prediction is the dense exact operator ([`box_growth`]); larger boxes use the standing modes
/// the box admits ([`box_prediction`]). 1,000 in both dimensions: up to `--size` 28 in 2D
/// (22² free particles) and 12 in 3D (6³ free particles) with 3 fixed layers.
pub const MAX_DENSE_BOX_DOFS: usize = 1000;

/// Default particles per side: 21 in 2D (the published box), 12 in 3D (the largest box whose
/// prediction is the dense exact operator, [`dense_size_limit`]; the standing-mode prediction
/// of a 3D box is off by up to ~10% at 13³–15³).
pub const fn default_size(dim: usize) -> usize {
    if dim == 3 { 12 } else { 21 }
}

/// Largest particles per side: 2001 in 2D, 201 in 3D (both also bounded by the memory and
/// step budgets).
pub const fn max_size(dim: usize) -> usize {
    if dim == 3 { 201 } else { 2001 }
}

/// Wave vectors per axis of [0, π] sampled for the infinite-lattice rate (the irreducible wedge
/// κ_1 ≥ … ≥ κ_D ≥ 0 of the square / simple-cubic zone, spacing π/n): 96 in 2D, 48 in 3D.
pub const fn infinite_grid(dim: usize) -> usize {
    if dim == 3 { 48 } else { 96 }
}

/// Largest `--size` whose box prediction is the dense operator, with `layers` fixed layers.
pub fn dense_size_limit(dim: usize, layers: usize) -> usize {
    let mut nf = 0;
    while dim * (nf + 1usize).pow(dim as u32) <= MAX_DENSE_BOX_DOFS.min(MAX_DENSE_DOFS) {
        nf += 1;
    }
    nf + 2 * layers
}

/// Configuration of a Swegle run.
#[derive(Clone, Copy, Debug)]
pub struct SwegleConfig {
    /// Dimension D (2 or 3): the box holds `size`^D particles.
    pub dim: usize,
    /// Form.
    pub form: FormKind,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// Shape family.
    pub shape: ShapeFamily,
    /// h/Δx.
    pub h_over_dx: f64,
    /// f = ρ/ρ0 (< 1 tension).
    pub density_ratio: f64,
    /// Particles per side (21, 41, 81, … in 2D; [`default_size`]).
    pub size: usize,
    /// Fixed layers per side.
    pub layers: usize,
    /// Spacing Δx.
    pub dx: f64,
    /// ρ0.
    pub rho0: f64,
    /// Bulk modulus K.
    pub bulk: f64,
    /// End time.
    pub t_end: f64,
    /// Initial v_x of the centre particle.
    pub kick: f64,
    /// Boundary density treatment.
    pub boundary: BoundaryDensity,
    /// Time step in units of Δx/c.
    pub cfl: f64,
    /// Fit window for max |v|.
    pub window: (f64, f64),
    /// Partition coefficient (lnl / cll).
    pub c_partition: f64,
    /// Artificial stress (ε, n) of the classical form (None: off, as in the published test).
    pub art_stress: Option<(f64, i32)>,
    /// Extend `t_end` so that a mode growing at the box prediction can rise from the kick to the
    /// top of the fit window (1.5 ln(window top / kick) / γ_box), never shortening it.
    pub until_window: bool,
    /// Time integrator (default `kdk`; [`crate::integrator`]).
    pub integrator: crate::integrator::Integrator,
    /// δ-SPH density diffusion (δ, form); None: off, as in the published test.
    pub diffusion: Option<(f64, crate::forms::DiffusionForm)>,
}

impl SwegleConfig {
    /// The published test: 2D, 21×21, 3 fixed layers, Δx = 0.1, ρ0 = 2.8, K = 0.686275,
    /// t_end = 40.
    pub fn new(
        form: FormKind,
        kernel: &'static dyn Kernel,
        h_over_dx: f64,
        density_ratio: f64,
    ) -> Self {
        Self {
            dim: 2,
            form,
            kernel,
            shape: form.default_shape_2d(),
            h_over_dx,
            density_ratio,
            size: 21,
            layers: 3,
            dx: 0.1,
            rho0: 2.8,
            bulk: 0.686275,
            t_end: 40.0,
            kick: 1e-10,
            boundary: BoundaryDensity::Evolve,
            cfl: 0.2,
            window: (1e-8, 1e-4),
            c_partition: 0.5,
            until_window: false,
            art_stress: None,
            integrator: crate::integrator::Integrator::Kdk,
            diffusion: None,
        }
    }

    /// The same test in dimension `dim` with that dimension's [`default_size`].
    pub fn with_dim(self, dim: usize) -> Self {
        Self {
            dim,
            size: default_size(dim),
            ..self
        }
    }

    /// Validates the inputs (flag names as on the CLI).
    pub fn validate(&self) -> Result<()> {
        if !(2..=3).contains(&self.dim) {
            return Err(Error::OutOfRange {
                name: "--dim",
                value: self.dim as f64,
                range: "2 or 3".into(),
            });
        }
        // the density ratio first: the stress σ̄ = 1 − f checked below derives from it
        check_range("--density-ratio", self.density_ratio, 0.5, 1.5, true, true)?;
        crate::analysis::check_common(
            self.kernel,
            self.h_over_dx,
            1.0 - self.density_ratio,
            self.c_partition,
            None,
            None,
        )?;
        check_range("--t-end", self.t_end, 0.0, 1e6, false, true)?;
        check_range("--cfl", self.cfl, 0.0, 2.0, false, true)?;
        let top = max_size(self.dim);
        if self.size < 2 * self.layers + 3 || self.size > top {
            return Err(Error::OutOfRange {
                name: "--size",
                value: self.size as f64,
                range: format!(
                    "must be an integer in [{}, {top}] with --dim {}",
                    2 * self.layers + 3,
                    self.dim
                ),
            });
        }
        if !self.form.in_2d() {
            return Err(Error::Incompatible(format!(
                "--form {} is not available in {}D",
                self.form.name(),
                self.dim
            )));
        }
        if self.dim == 3 && self.art_stress.is_some() {
            return Err(Error::Incompatible(
                "--art-eps (artificial stress) is available with --dim 2 only".into(),
            ));
        }
        self.form.check_shape(self.shape)?;
        // resources, before anything is allocated (crate::budget)
        let particles = self.particles() as f64;
        let r = self.kernel.zeta() * self.h_over_dx;
        let neighbours = if self.dim == 3 {
            4.0 / 3.0 * PI * r * r * r + 1.0
        } else {
            PI * r * r + 1.0
        };
        let stencils = if matches!(self.form, FormKind::Lnl | FormKind::Cll) {
            2.0
        } else {
            1.0
        };
        // stencil entries (index, offset, gradient: 8 + 16D B) with a quarter spare, and ~50
        // f64 (2D) or ~125 f64 (3D) of state, integrator copies and diagnostics per particle
        let entry = 8.0 + 16.0 * self.dim as f64;
        let state = if self.dim == 3 { 1000.0 } else { 400.0 };
        let bytes = particles * (neighbours * entry * stencils * 1.25 + state);
        crate::budget::check_memory(
            "--size/--h",
            &format!(
                "the Swegle box ({} particles, ~{neighbours:.0} neighbours each)",
                self.shape_label()
            ),
            bytes,
        )?;
        let steps = (self.t_end / (self.cfl * self.dx / self.sound_speed())).ceil();
        crate::budget::check_steps(
            "--t-end/--cfl/--size",
            &format!(
                "the Swegle run ({} time steps)",
                crate::budget::fmt_count(steps)
            ),
            particles * steps,
        )
    }

    fn params(&self) -> ModelParams2D {
        ModelParams2D {
            form: self.form,
            shape: self.shape,
            kp: KernelParams {
                kernel: self.kernel,
                h: self.h_over_dx * self.dx,
            },
            material: Material2D::Hydro { bulk: self.bulk },
            rho0: self.rho0,
            c_partition: self.c_partition,
            av: None,
            art_stress: self
                .art_stress
                .map(|(eps, n)| crate::forms::ArtificialStress {
                    eps,
                    n,
                    spacing: self.dx,
                }),
            diffusion: self
                .diffusion
                .map(|(delta, form)| crate::forms::DensityDiffusion {
                    delta,
                    form,
                    sound_speed: self.sound_speed(),
                }),
        }
    }

    /// Sound speed c = sqrt(K/ρ0).
    pub fn sound_speed(&self) -> f64 {
        (self.bulk / self.rho0).sqrt()
    }

    /// Particles in the box, `size`^D.
    pub fn particles(&self) -> usize {
        self.size.pow(self.dim as u32)
    }

    /// "21 × 21" or "15 × 15 × 15".
    pub fn shape_label(&self) -> String {
        vec![self.size.to_string(); self.dim].join(" × ")
    }

    /// Index of the particle at lattice coordinates `c` (first coordinate slowest).
    fn index<const D: usize>(&self, c: [usize; D]) -> usize {
        c.iter().fold(0, |k, &ca| k * self.size + ca)
    }

    /// Lattice coordinates of particle `k` of an `n`^D block (first coordinate slowest).
    fn coords<const D: usize>(n: usize, k: usize) -> [usize; D] {
        let mut c = [0; D];
        let mut rest = k;
        for a in (0..D).rev() {
            c[a] = rest % n;
            rest /= n;
        }
        c
    }

    /// Builds the run at rest with the kick applied; D must be [`SwegleConfig::dim`].
    pub fn build<const D: usize>(&self) -> Result<Run<D>> {
        self.validate()?;
        if D != self.dim {
            return Err(Error::Incompatible(format!(
                "a {D}D Swegle run from a --dim {} configuration",
                self.dim
            )));
        }
        let (n, l) = (self.size, self.layers);
        let half = (n - 1) as f64 / 2.0;
        let count = self.particles();
        let mut x = Vec::with_capacity(count);
        let mut fixed = Vec::with_capacity(count);
        for k in 0..count {
            let c = Self::coords::<D>(n, k);
            x.push(c.map(|ca| (ca as f64 - half) * self.dx));
            fixed.push(c.iter().any(|&ca| ca < l || ca >= n - l));
        }
        let rho = self.density_ratio * self.rho0;
        let s0 = self.bulk * (1.0 - self.density_ratio);
        let model = Model::<D>::new(
            self.params(),
            x,
            vec![self.dx.powi(D as i32); count],
            rho,
            s0,
            None,
        )?;
        let mut z = model.rest_state(rho);
        z.v[self.index([n / 2; D])][0] = self.kick;
        Run::new(model, z, fixed, self.boundary)
    }
}

/// The final particle state of a run, in its dimension.
#[derive(Clone, Debug)]
pub enum FinalState {
    /// A 2D run.
    Two(State2D<f64>),
    /// A 3D run.
    Three(State3D<f64>),
}

impl FinalState {
    /// Legacy VTK of the particles ([`crate::solver::output::vtk_nd`]; 3D points in both cases).
    pub fn vtk(&self, title: &str) -> String {
        match self {
            FinalState::Two(z) => crate::solver::output::vtk_nd(title, z),
            FinalState::Three(z) => crate::solver::output::vtk_nd(title, z),
        }
    }
}

impl From<State2D<f64>> for FinalState {
    fn from(z: State2D<f64>) -> Self {
        FinalState::Two(z)
    }
}

impl From<State3D<f64>> for FinalState {
    fn from(z: State3D<f64>) -> Self {
        FinalState::Three(z)
    }
}

/// Result of a Swegle run (rates in c/Δx unless named `_physical`).
#[derive(Clone, Debug, Serialize)]
pub struct SwegleReport {
    /// The run stopped early because it diverged (first non-finite value or a runaway); the
    /// measurements cover the steps before it. The binary exits with status 3 then.
    pub diverged: Option<Diverged>,
    /// Time integrator (CLI name).
    pub integrator: &'static str,
    /// δ-SPH density diffusion: δ (0: off).
    pub delta: f64,
    /// δ-SPH form (CLI name; null when off).
    pub delta_form: Option<&'static str>,
    /// Form.
    pub form: &'static str,
    /// Kernel.
    pub kernel: &'static str,
    /// h/Δx.
    pub h_over_dx: f64,
    /// f = ρ/ρ0.
    pub density_ratio: f64,
    /// Dimension.
    pub dim: usize,
    /// Particles per side (the box holds size^dim).
    pub size: usize,
    /// Boundary treatment.
    pub boundary_density: BoundaryDensity,
    /// Measured growth rate of max |v| (c/Δx), null if nothing grew into the window.
    pub measured_growth_rate: Option<f64>,
    /// Prediction for this finite particle set (c/Δx).
    pub predicted_growth_rate_box: f64,
    /// How the box prediction was obtained: `dense-operator` or `standing-modes`.
    pub box_method: &'static str,
    /// Infinite-lattice prediction (c/Δx).
    pub predicted_growth_rate_infinite: f64,
    /// measured / box.
    pub ratio_box: Option<f64>,
    /// measured / infinite.
    pub ratio_infinite: Option<f64>,
    /// The fit.
    pub fit: Option<GrowthFit>,
    /// max |v| of the free particles at the end.
    pub max_velocity_end: f64,
    /// max |v| ever exceeded 2× the kick.
    pub grew: bool,
    /// Time step (physical) and number of steps.
    pub dt: f64,
    /// Steps taken.
    pub steps: usize,
    /// Wall-clock seconds of the time loop.
    pub runtime_s: f64,
    /// Dominant standing mode (m_1, …, m_D) of the free particles' velocity at the end of the
    /// fit window (or the end), as a wave vector [κ_1Δx, …, κ_DΔx] = (m_1π, …, m_Dπ)/(n_free + 1),
    /// with its power share.
    pub dominant_kappa: Option<(Vec<f64>, f64)>,
    /// Wave vector (D components) of the fastest standing mode the box admits (engine), for
    /// comparison.
    pub predicted_kappa_box: Vec<f64>,
    /// History (t, max |v|), at most ~400 samples.
    pub history: Vec<(f64, f64)>,
    /// Full history every step: t, centre |v|, max |v| and RMS |v| over the free particles,
    /// kinetic energy of all particles.
    #[serde(skip)]
    pub history_full: Vec<[f64; 5]>,
    /// Final particle state.
    #[serde(skip)]
    pub final_state: Option<FinalState>,
}

/// Runs the test in the configuration's dimension.
pub fn run_swegle(cfg: &SwegleConfig, progress: impl FnMut(f64)) -> Result<SwegleReport> {
    cfg.validate()?;
    match cfg.dim {
        3 => run_d::<3>(cfg, progress),
        _ => run_d::<2>(cfg, progress),
    }
}

/// |v| (hypot in 2D, as the 2D test always computed it).
fn speed<const D: usize>(v: &[f64; D]) -> f64 {
    if D == 2 {
        v[0].hypot(v[1])
    } else {
        v.iter().map(|c| c * c).sum::<f64>().sqrt()
    }
}

/// A wave vector (κΔx per axis) and a branch's polarisation there.
type FastestMode<const D: usize> = ([f64; D], [Complex64; D]);

/// The largest growth rate (c/Δx) over the irreducible wedge π ≥ κ_1 ≥ … ≥ κ_D ≥ 0 of the
/// square / simple-cubic zone, sampled at spacing π/[`infinite_grid`]; with the wave vector
/// (κΔx) where it is reached and that branch's polarisation (None when nothing grows).
fn infinite_rate<const D: usize>(lin: &Bloch<D>) -> Result<(f64, Option<FastestMode<D>>)> {
    let n = infinite_grid(D);
    let mut g: f64 = 0.0;
    let mut at = None;
    for idx in 0..(n + 1).pow(D as u32) {
        let c = SwegleConfig::coords::<D>(n + 1, idx);
        if c.windows(2).any(|w| w[1] > w[0]) {
            continue;
        }
        let k = c.map(|i| PI * i as f64 / n as f64);
        let (gk, p) = lin.growth(k)?;
        if gk > g {
            g = gk;
            at = Some((k, p));
        }
    }
    Ok((g, at))
}

/// The engine's predictions for a Swegle configuration, computed without running it (the
/// same numbers [`run_swegle`] reports next to its measurement).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct SweglePrediction {
    /// Growth rate of the finite particle set (c/Δx).
    pub box_rate: f64,
    /// `dense-operator` or `standing-modes` (as [`SwegleReport::box_method`]).
    pub box_method: &'static str,
    /// Wave vector (κΔx per axis) of the fastest standing mode the box admits.
    pub box_kappa: Vec<f64>,
    /// Growth rate of the infinite lattice (c/Δx).
    pub infinite_rate: f64,
    /// Wave vector (κΔx per axis) of the infinite lattice's fastest mode (empty: none grows).
    pub infinite_kappa: Vec<f64>,
    /// Longitudinal fraction |p·κ̂|² of that mode's polarisation p (1: longitudinal, 0:
    /// transverse; NaN-free: 0 when nothing grows).
    pub infinite_longitudinal: f64,
}

/// The predictions of [`run_swegle`] without the time integration: the dense box operator (or
/// the box's standing modes) and the infinite lattice, with the fastest modes.
pub fn predict_swegle(cfg: &SwegleConfig) -> Result<SweglePrediction> {
    cfg.validate()?;
    match cfg.dim {
        3 => predict_d::<3>(cfg, &cfg.build::<3>()?),
        _ => predict_d::<2>(cfg, &cfg.build::<2>()?),
    }
}

/// [`predict_swegle`] for a built run (before it is stepped).
fn predict_d<const D: usize>(cfg: &SwegleConfig, run: &Run<D>) -> Result<SweglePrediction> {
    let unit = cfg.sound_speed() / cfg.dx; // c/Δx: normalisation of rates
    let nfree = cfg.size - 2 * cfg.layers;
    let lin_unit = Bloch::<D>::new(
        ModelParams2D {
            kp: KernelParams {
                kernel: cfg.kernel,
                h: cfg.h_over_dx,
            },
            rho0: 1.0,
            material: Material2D::Hydro { bulk: 1.0 },
            art_stress: cfg
                .art_stress
                .map(|(eps, n)| crate::forms::ArtificialStress {
                    eps,
                    n,
                    spacing: 1.0,
                }),
            // normalised units: h in Δx, c = 1
            diffusion: cfg
                .diffusion
                .map(|(delta, form)| crate::forms::DensityDiffusion {
                    delta,
                    form,
                    sound_speed: 1.0,
                }),
            ..cfg.params()
        },
        &Lattice::<D>::of_kind(if D == 3 {
            LatticeKind::Sc
        } else {
            LatticeKind::Square { gamma: 1.0 }
        })?,
        1.0,
        1.0 - cfg.density_ratio,
    )?;
    let (standing_rate, standing_k) = box_prediction(&lin_unit, nfree)?;
    // the dense operator is the mechanical reduction ω² = eig(−(J_vx + J_vq J_qv)), exact only
    // without dissipation; with δ-SPH the standing modes' eigenvalues (of the full J) are used
    let (box_rate, box_method) = if D * nfree.pow(D as u32)
        <= MAX_DENSE_BOX_DOFS.min(MAX_DENSE_DOFS)
        && cfg.diffusion.is_none()
    {
        (box_growth(run)?.0 / unit, "dense-operator")
    } else {
        (standing_rate, "standing-modes")
    };
    let (infinite_rate, at) = infinite_rate(&lin_unit)?;
    let (infinite_kappa, infinite_longitudinal) = match at {
        Some((k, p)) => {
            let kk: f64 = k.iter().map(|a| a * a).sum::<f64>().sqrt();
            let dot: Complex64 = k.iter().zip(&p).map(|(a, pa)| pa * (a / kk)).sum();
            (k.to_vec(), dot.norm_sqr())
        }
        None => (Vec::new(), 0.0),
    };
    Ok(SweglePrediction {
        box_rate,
        box_method,
        box_kappa: standing_k.to_vec(),
        infinite_rate,
        infinite_kappa,
        infinite_longitudinal,
    })
}

fn run_d<const D: usize>(cfg: &SwegleConfig, mut progress: impl FnMut(f64)) -> Result<SwegleReport>
where
    FinalState: From<State<f64, D>>,
{
    let mut run = cfg.build::<D>()?;
    run.set_integrator(cfg.integrator);
    let c = cfg.sound_speed();
    let unit = c / cfg.dx; // c/Δx: normalisation of rates
    let nfree = cfg.size - 2 * cfg.layers;
    let pred = predict_d(cfg, &run)?;
    let (box_rate, method, inf) = (pred.box_rate, pred.box_method, pred.infinite_rate);
    let dt = cfg.cfl * cfg.dx / c;
    let t_end = if cfg.until_window && box_rate > 1e-6 {
        cfg.t_end
            .max(1.5 * (cfg.window.1 / cfg.kick).ln() / (box_rate * unit))
    } else {
        cfg.t_end
    };
    if t_end > cfg.t_end {
        let steps = (t_end / dt).ceil();
        crate::budget::check_steps(
            "--until-window/--density-ratio",
            &format!(
                "running until the predicted mode (growth {box_rate:.3e} c/Δx) reaches the fit window ({} time steps)",
                crate::budget::fmt_count(steps)
            ),
            cfg.particles() as f64 * steps,
        )?;
    }
    let steps = (t_end / dt).ceil() as usize;
    let mut t = vec![0.0];
    let mut y = vec![run.max_free_speed().max(cfg.kick)];
    let mut vmax_ever: f64 = 0.0;
    let mut snapshot: Option<Vec<Vec<f64>>> = None;
    let centre = cfg.index([cfg.size / 2; D]);
    let mut full = Vec::with_capacity(steps + 1);
    let record = |run: &Run<D>, full: &mut Vec<[f64; 5]>| {
        let mut s2 = 0.0;
        let mut nf = 0usize;
        let mut ke = 0.0;
        for (i, v) in run.z.v.iter().enumerate() {
            let v2: f64 = v.iter().map(|c| c * c).sum();
            ke += 0.5 * run.model.mass[i] * v2;
            if !run.fixed[i] {
                s2 += v2;
                nf += 1;
            }
        }
        full.push([
            run.t,
            speed(&run.z.v[centre]),
            run.max_free_speed(),
            (s2 / nf.max(1) as f64).sqrt(),
            ke,
        ]);
    };
    record(&run, &mut full);
    // the velocity components of the free particles, row-major over the free block
    let free_fields = |run: &Run<D>| -> Vec<Vec<f64>> {
        let count = nfree.pow(D as u32);
        let mut f = vec![Vec::with_capacity(count); D];
        for k in 0..count {
            let c = SwegleConfig::coords::<D>(nfree, k).map(|ca| ca + cfg.layers);
            let v = run.z.v[cfg.index(c)];
            for (fa, va) in f.iter_mut().zip(v) {
                fa.push(va);
            }
        }
        f
    };
    let start = std::time::Instant::now();
    // stop at the first non-finite value or a runaway (max |v| above
    // crate::solver::scene::RUNAWAY_FACTOR × c); the growth fit uses what was recorded
    let runaway = crate::solver::scene::RUNAWAY_FACTOR * c;
    let mut diverged = None;
    for s in 0..steps {
        if run.step(dt).is_err() {
            diverged = Some(Diverged {
                step: s + 1,
                t: run.t + dt,
                what: "a non-finite velocity",
            });
            break;
        }
        let v = run.max_free_speed();
        if v > runaway {
            diverged = Some(Diverged {
                step: s + 1,
                t: run.t,
                what: "max |v| above 1000 × c",
            });
            break;
        }
        vmax_ever = vmax_ever.max(v);
        t.push(run.t);
        y.push(v);
        record(&run, &mut full);
        if snapshot.is_none() && v >= cfg.window.1 {
            snapshot = Some(free_fields(&run));
        }
        if s % 64 == 0 {
            progress(run.t / t_end);
        }
        // beyond the window the perturbation is nonlinear; 1e3 × the window top is far enough
        if v > cfg.window.1 * 1e3 * unit * cfg.dx {
            break;
        }
    }
    let runtime_s = start.elapsed().as_secs_f64();
    let fields = snapshot.unwrap_or_else(|| free_fields(&run));
    let d = PI / (nfree as f64 + 1.0);
    let dominant = {
        let (m, share) = crate::solver::diagnostics::dominant_mode_nd(&fields, nfree, D);
        (share > 0.0).then(|| (m.iter().map(|&ma| ma as f64 * d).collect(), share))
    };
    let fit = growth_fit(&t, &y, cfg.window.0, cfg.window.1);
    let measured = fit.map(|f| f.rate / unit);
    let stride = (t.len() / 400).max(1);
    Ok(SwegleReport {
        diverged,
        integrator: cfg.integrator.name(),
        delta: cfg.diffusion.map_or(0.0, |d| d.0),
        delta_form: cfg.diffusion.map(|d| d.1.name()),
        form: cfg.form.name(),
        kernel: cfg.kernel.name(),
        h_over_dx: cfg.h_over_dx,
        density_ratio: cfg.density_ratio,
        dim: D,
        size: cfg.size,
        boundary_density: cfg.boundary,
        measured_growth_rate: measured,
        predicted_growth_rate_box: box_rate,
        box_method: method,
        predicted_growth_rate_infinite: inf,
        // a ratio only means something when the prediction is growth (above GROWTH_TOL)
        ratio_box: measured
            .filter(|_| box_rate > crate::vonneumann::classify::GROWTH_TOL)
            .map(|m| m / box_rate),
        ratio_infinite: measured
            .filter(|_| inf > crate::vonneumann::classify::GROWTH_TOL)
            .map(|m| m / inf),
        fit,
        max_velocity_end: *y.last().unwrap_or(&0.0),
        grew: vmax_ever > 2.0 * cfg.kick,
        dt,
        steps: run.steps,
        runtime_s,
        history_full: full,
        dominant_kappa: dominant,
        predicted_kappa_box: pred.box_kappa,
        history: t
            .iter()
            .zip(&y)
            .step_by(stride)
            .map(|(&a, &b)| (a, b))
            .collect(),
        final_state: Some(run.z.into()),
    })
}

/// Where and why a run diverged.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct Diverged {
    /// Time step index.
    pub step: usize,
    /// Time reached.
    pub t: f64,
    /// The criterion that fired.
    pub what: &'static str,
}
