//! The Swegle test \[V21 §7.2\]: a square block of particles (spacing 0.1 on [−1, 1]² for
//! 21×21), outer `layers` layers fixed but taking part in every sum (their density evolving by
//! continuity, or frozen), hydrodynamic aluminium ρ0 = 2.8, K = 0.686275, G = 0, initial density
//! f ρ0 (f < 1 tension), the centre particle kicked with v_x = 1e−10, no artificial viscosity.
//! The measured exponential growth of max |v| over the free particles is compared with the
//! growth rate of the exact linear operator of the same finite particle set (dense, for small
//! boxes) or of its admitted standing modes, and with the infinite lattice.

use super::box_operator::{MAX_DENSE_DOFS, box_growth};
use super::diagnostics::{GrowthFit, growth_fit};
use super::run2d::{BoundaryDensity, Run2D};
use crate::analysis2d::box_prediction;
use crate::error::{Result, check_range};
use crate::forms::{FormKind, Material2D, Model2D, ModelParams2D};
use crate::kernel::Kernel;
use crate::lattice::Lattice2D;
use crate::shape::ShapeFamily;
use crate::shape2d::KernelParams2;
use crate::vonneumann::linearise2d::Linearisation2D;
use serde::Serialize;
use std::f64::consts::PI;

/// Configuration of a Swegle run.
#[derive(Clone, Copy, Debug)]
pub struct SwegleConfig {
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
    /// Particles per side (21, 41, 81, …).
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
}

impl SwegleConfig {
    /// The published test: 21×21, 3 fixed layers, Δx = 0.1, ρ0 = 2.8, K = 0.686275, t_end = 40.
    pub fn new(
        form: FormKind,
        kernel: &'static dyn Kernel,
        h_over_dx: f64,
        density_ratio: f64,
    ) -> Self {
        Self {
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
        }
    }

    /// Validates the inputs (flag names as on the CLI).
    pub fn validate(&self) -> Result<()> {
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
        if self.size < 2 * self.layers + 3 || self.size > 2001 {
            return Err(crate::error::Error::OutOfRange {
                name: "--size",
                value: self.size as f64,
                range: format!("must be an integer in [{}, 2001]", 2 * self.layers + 3),
            });
        }
        if !self.form.in_2d() {
            return Err(crate::error::Error::Incompatible(format!(
                "--form {} is not available in 2D",
                self.form.name()
            )));
        }
        self.form.check_shape(self.shape)?;
        // resources, before anything is allocated (crate::budget)
        let particles = (self.size * self.size) as f64;
        let r = self.kernel.zeta() * self.h_over_dx;
        let neighbours = PI * r * r + 1.0;
        let stencils = if matches!(self.form, FormKind::Lnl | FormKind::Cll) {
            2.0
        } else {
            1.0
        };
        // stencil entries (index, offset, gradient: 40 B) with a quarter spare, and ~50 f64 of
        // state, integrator copies and diagnostics per particle
        let bytes = particles * (neighbours * 40.0 * stencils * 1.25 + 400.0);
        crate::budget::check_memory(
            "--size/--h",
            &format!(
                "the Swegle box ({} × {} particles, ~{neighbours:.0} neighbours each)",
                self.size, self.size
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
            kp: KernelParams2 {
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
        }
    }

    /// Sound speed c = sqrt(K/ρ0).
    pub fn sound_speed(&self) -> f64 {
        (self.bulk / self.rho0).sqrt()
    }

    /// Builds the run at rest with the kick applied.
    pub fn build(&self) -> Result<Run2D> {
        self.validate()?;
        let n = self.size;
        let half = (n - 1) as f64 / 2.0;
        let mut x = Vec::with_capacity(n * n);
        let mut fixed = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                x.push([(i as f64 - half) * self.dx, (j as f64 - half) * self.dx]);
                let l = self.layers;
                fixed.push(i < l || j < l || i >= n - l || j >= n - l);
            }
        }
        let rho = self.density_ratio * self.rho0;
        let s0 = self.bulk * (1.0 - self.density_ratio);
        let model = Model2D::new(
            self.params(),
            x,
            vec![self.dx * self.dx; n * n],
            rho,
            s0,
            None,
        )?;
        let mut z = model.rest_state(rho);
        let centre = (n / 2) * n + n / 2;
        z.v[centre][0] = self.kick;
        Run2D::new(model, z, fixed, self.boundary)
    }
}

/// Result of a Swegle run (rates in c/Δx unless named `_physical`).
#[derive(Clone, Debug, Serialize)]
pub struct SwegleReport {
    /// The run stopped early because it diverged (first non-finite value or a runaway); the
    /// measurements cover the steps before it. The binary exits with status 3 then.
    pub diverged: Option<Diverged>,
    /// Form.
    pub form: &'static str,
    /// Kernel.
    pub kernel: &'static str,
    /// h/Δx.
    pub h_over_dx: f64,
    /// f = ρ/ρ0.
    pub density_ratio: f64,
    /// Box size.
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
    /// Dominant standing mode (m, l) of the free particles' velocity at the end of the fit window
    /// (or the end), as a wave vector [κxΔx, κyΔx] = (mπ, lπ)/(n_free + 1), with its power share.
    pub dominant_kappa: Option<([f64; 2], f64)>,
    /// Wave vector of the fastest standing mode the box admits (engine), for comparison.
    pub predicted_kappa_box: [f64; 2],
    /// History (t, max |v|), at most ~400 samples.
    pub history: Vec<(f64, f64)>,
    /// Full history every step: t, centre |v|, max |v| and RMS |v| over the free particles,
    /// kinetic energy of all particles.
    #[serde(skip)]
    pub history_full: Vec<[f64; 5]>,
    /// Final particle state.
    #[serde(skip)]
    pub final_state: Option<crate::forms::State2D<f64>>,
}

/// Runs the test.
pub fn run_swegle(cfg: &SwegleConfig, mut progress: impl FnMut(f64)) -> Result<SwegleReport> {
    let mut run = cfg.build()?;
    let c = cfg.sound_speed();
    let unit = c / cfg.dx; // c/Δx: normalisation of rates
    // predictions
    let nfree = cfg.size - 2 * cfg.layers;
    let lin_unit = Linearisation2D::new(
        ModelParams2D {
            kp: KernelParams2 {
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
            ..cfg.params()
        },
        &Lattice2D::square(1.0)?,
        1.0,
        1.0 - cfg.density_ratio,
    )?;
    let (standing_rate, standing_k) = box_prediction(&lin_unit, nfree)?;
    let (box_rate, method) = if 2 * nfree * nfree <= MAX_DENSE_DOFS.min(1000) {
        (box_growth(&run)?.0 / unit, "dense-operator")
    } else {
        (standing_rate, "standing-modes")
    };
    let inf = {
        let lin = &lin_unit;
        let n = 96;
        let mut g: f64 = 0.0;
        for i in 0..=n {
            for j in 0..=i {
                g = g.max(
                    lin.growth([PI * i as f64 / n as f64, PI * j as f64 / n as f64])?
                        .0,
                );
            }
        }
        g
    };
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
            (cfg.size * cfg.size) as f64 * steps,
        )?;
    }
    let steps = (t_end / dt).ceil() as usize;
    let mut t = vec![0.0];
    let mut y = vec![run.max_free_speed().max(cfg.kick)];
    let mut vmax_ever: f64 = 0.0;
    let mut snapshot: Option<Vec<Vec<f64>>> = None;
    let centre = (cfg.size / 2) * cfg.size + cfg.size / 2;
    let mut full = Vec::with_capacity(steps + 1);
    let record = |run: &Run2D, full: &mut Vec<[f64; 5]>| {
        let mut s2 = 0.0;
        let mut nf = 0usize;
        let mut ke = 0.0;
        for (i, v) in run.z.v.iter().enumerate() {
            let v2 = v[0] * v[0] + v[1] * v[1];
            ke += 0.5 * run.model.mass[i] * v2;
            if !run.fixed[i] {
                s2 += v2;
                nf += 1;
            }
        }
        let c = run.z.v[centre];
        full.push([
            run.t,
            c[0].hypot(c[1]),
            run.max_free_speed(),
            (s2 / nf.max(1) as f64).sqrt(),
            ke,
        ]);
    };
    record(&run, &mut full);
    let free_fields = |run: &Run2D| -> Vec<Vec<f64>> {
        let (n, l) = (cfg.size, cfg.layers);
        let mut vx = Vec::with_capacity(nfree * nfree);
        let mut vy = Vec::with_capacity(nfree * nfree);
        for i in l..n - l {
            for j in l..n - l {
                let v = run.z.v[i * n + j];
                vx.push(v[0]);
                vy.push(v[1]);
            }
        }
        vec![vx, vy]
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
        let ((m, l), share) = crate::solver::diagnostics::dominant_mode(&fields, nfree);
        if share > 0.0 {
            Some(([m as f64 * d, l as f64 * d], share))
        } else {
            None
        }
    };
    let fit = growth_fit(&t, &y, cfg.window.0, cfg.window.1);
    let measured = fit.map(|f| f.rate / unit);
    let stride = (t.len() / 400).max(1);
    Ok(SwegleReport {
        diverged,
        form: cfg.form.name(),
        kernel: cfg.kernel.name(),
        h_over_dx: cfg.h_over_dx,
        density_ratio: cfg.density_ratio,
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
        predicted_kappa_box: standing_k,
        history: t
            .iter()
            .zip(&y)
            .step_by(stride)
            .map(|(&a, &b)| (a, b))
            .collect(),
        final_state: Some(run.z),
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
