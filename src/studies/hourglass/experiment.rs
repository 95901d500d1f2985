//! The time-domain experiments of the tensile-or-hourglass study (issue 30): a JSON file in
//! `analysis/scenes/` with an `experiment` field, run by `sphstab simulate FILE`.
//!
//! `disc`: the 2D disc the SPHinXsys group proposes as the decisive experiment (a round solid in
//! isotropic tension), in normalised units (Δx = ρ0 = C = 1): the lattice points within the
//! radius R, held at a uniform isotropic pre-stress σ̄ by the constant boundary load
//! f_K = −m_K a_K(rest state) (the discrete traction that makes the uniformly stressed rest
//! state an equilibrium of the form), seeded with random velocities of amplitude `kick` (the
//! group's relaxed particle distribution breaks the lattice's symmetry; on the lattice the seed
//! does that, and the prediction applies). As the Swegle test does, the growth of max |v| is
//! fitted over a window and compared with the fastest mode of the exact operator of the same
//! finite particle set ([`crate::studies::box_operator`]), and with the infinite lattice's.

use super::config::Remedy;
use crate::analysis::QuerySpec;
use crate::budget::Budget;
use crate::error::{Error, Result, check_range, field};
use crate::forms::{FormKind, Material, Model, PrestressKind};
use crate::progress::Progress;
use crate::solver::BoundaryDensity;
use crate::solver::diagnostics::{GrowthFit, growth_fit};
use crate::solver::run::Run;
use crate::studies::box_operator::{MAX_DENSE_DOFS, Start, box_growth, box_growth_iterative};
use serde::{Deserialize, Serialize};

/// Which experiment.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum ExperimentKind {
    /// A disc held in isotropic tension or compression.
    Disc,
}

/// An experiment file (normalised units: Δx = ρ0 = C = 1, times in Δx/c, speeds in c).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Experiment {
    /// Name (free text).
    pub name: String,
    /// `disc`.
    pub experiment: ExperimentKind,
    /// The remedy: a label and its question (form, kernel, h, shape, coefficient, lattice,
    /// poisson; 2D).
    pub remedy: Remedy,
    /// Radius R/Δx of the disc, in [3, 40].
    pub radius: f64,
    /// Isotropic pre-stress σ̄ = σ/C held by the boundary load, in [−0.5, 0.5].
    pub stress: f64,
    /// Amplitude of the random seed velocities (c), in [1e-15, 1e-6] (default 1e-10).
    #[serde(default = "default_kick")]
    pub kick: f64,
    /// Seed of the random velocities (default 1).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Time step Δt (Δx/c), in (0, 2] (default 0.2).
    #[serde(default = "default_dt")]
    pub dt: f64,
    /// End time (Δx/c), in (0, 1e5].
    pub t_end: f64,
    /// Fit window of max |v| (c): from 100 × `kick` to 1e-5 by default.
    #[serde(default)]
    pub window: Option<(f64, f64)>,
    /// The budget the run must stay within (not read from the file).
    #[serde(skip)]
    pub budget: Budget,
}

fn default_kick() -> f64 {
    1e-10
}
fn default_seed() -> u64 {
    1
}
fn default_dt() -> f64 {
    0.2
}

/// What an experiment measured and predicted.
#[derive(Clone, Debug, Serialize)]
pub struct ExperimentReport {
    /// The experiment.
    pub name: String,
    /// The remedy's label.
    pub remedy: String,
    /// Its form.
    pub form: String,
    /// Particles.
    pub particles: usize,
    /// Isotropic pre-stress σ̄.
    pub stress: f64,
    /// Growth of max |v| fitted over the window (c/Δx; null: it never entered the window).
    pub measured_growth_rate: Option<f64>,
    /// The fit.
    pub fit: Option<GrowthFit>,
    /// Fastest growth of the exact operator of the particle set (c/Δx; 0: none grows).
    pub predicted_growth_rate_body: f64,
    /// Fastest growth of the infinite lattice at the same σ̄ (c/Δx).
    pub predicted_growth_rate_infinite: f64,
    /// measured / predicted for the body (null unless both grow).
    pub ratio_body: Option<f64>,
    /// max |v| at the end (c).
    pub max_velocity_end: f64,
    /// Time steps taken.
    pub steps: usize,
    /// End time (Δx/c).
    pub t: f64,
}

/// A small deterministic generator (SplitMix64): the seed velocities are the same on every
/// machine.
fn splitmix(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

impl Experiment {
    /// Checks every field (errors name it).
    pub fn validate(&self) -> Result<()> {
        check_range("radius", self.radius, 3.0, 40.0, true, true)?;
        check_range("stress", self.stress, -0.5, 0.5, true, true)?;
        check_range("kick", self.kick, 1e-15, 1e-6, true, true)?;
        check_range("dt", self.dt, 0.0, 2.0, false, true)?;
        check_range("t_end", self.t_end, 0.0, 1e5, false, true)?;
        if let Some((lo, hi)) = self.window
            && !(lo > 0.0 && hi > lo && hi <= 1.0)
        {
            return Err(Error::Incompatible(
                field("window") + ": [lo, hi] with 0 < lo < hi ≤ 1 (c)",
            ));
        }
        let q = &self.remedy.query;
        for (name, set) in [
            ("dim", q.dim.is_some_and(|d| d != 2)),
            ("stress", q.stress.is_some()),
            ("prestress", q.prestress.is_some()),
            ("dt", q.dt.is_some()),
        ] {
            if set {
                return Err(Error::Incompatible(
                    field("remedy") + ": " + field(name) + " is the experiment's (a 2D disc)",
                ));
            }
        }
        Ok(())
    }

    /// The question of the remedy at the experiment's stress.
    fn spec(&self) -> QuerySpec {
        QuerySpec {
            dim: Some(2),
            stress: Some(self.stress),
            prestress: Some(PrestressKind::Isotropic.name().into()),
            grid: Some(self.remedy.query.grid.unwrap_or(32)),
            ..self.remedy.query.clone()
        }
    }

    /// Runs the experiment.
    pub fn run(&self, progress: impl Progress) -> Result<ExperimentReport> {
        self.validate()?;
        let q = self.spec().query::<2>(&self.budget)?;
        let p = q.params()?;
        let lat = q.lattice;
        // the lattice points within the radius
        let r = self.radius;
        let n = r.ceil() as i64 + 2;
        let mut x = Vec::new();
        for i in -n..=n {
            for j in -n..=n {
                let y = [
                    i as f64 * lat.a[0][0] + j as f64 * lat.a[1][0],
                    i as f64 * lat.a[0][1] + j as f64 * lat.a[1][1],
                ];
                if y[0].hypot(y[1]) <= r + 1e-9 {
                    x.push(y);
                }
            }
        }
        let count = x.len();
        let steps = (self.t_end / self.dt).ceil();
        self.budget.steps(
            crate::error::fields(&["t_end", "radius"]),
            &format!("the disc ({count} particles, {steps} time steps)"),
            count as f64 * steps,
        )?;
        let s0 = q.sigma0(self.stress);
        let rho = match p.material {
            Material::Elastic { lambda, shear, .. } if p.form == FormKind::Enog => {
                p.rho0 * (1.0 - s0 / (lambda + 2.0 * shear / 3.0))
            }
            Material::Hydro { .. } => p.rho0 * (1.0 - self.stress),
            _ => p.rho0,
        };
        if rho <= 0.0 {
            return Err(Error::OutOfRange {
                field: "stress",
                value: self.stress,
                range: "the pre-stress must leave a positive density".into(),
            });
        }
        let vol = vec![lat.area(); count];
        let model = Model::new(p, x, vol, rho, s0, None)?;
        let z = model.rest_state(rho);
        // the load that holds the pre-stressed rest state: −m a(rest)
        let mut rate = crate::forms::State::default();
        model.rate(&z, &mut rate)?;
        let load: Vec<[f64; 2]> = rate
            .v
            .iter()
            .zip(&model.mass)
            .map(|(a, m)| a.map(|c| -c * m))
            .collect();
        let mut run = Run::new(model, z, vec![false; count], BoundaryDensity::Evolve)?;
        run.set_load(load)?;
        // every eigenvalue of the dense operator while it is small (the fastest mode is then
        // certain, however slowly it grows), the fastest by Arnoldi beyond
        let predicted = if 2 * count <= MAX_DENSE_DOFS {
            box_growth(&run)?.0
        } else {
            box_growth_iterative(&run, Start::Generic, None, &self.budget, &progress)?
                .map_or(0.0, |g| g.rate)
        };
        let infinite = crate::analysis::query(&q)?.max_growth_rate;
        // seed
        let mut state = self.seed;
        for v in run.z.v.iter_mut() {
            for c in v.iter_mut() {
                *c = self.kick * (2.0 * splitmix(&mut state) - 1.0);
            }
        }
        let (lo, hi) = self.window.unwrap_or((100.0 * self.kick, 1e-5));
        let mut t = vec![0.0];
        let mut y = vec![run.max_free_speed()];
        let total = steps as usize;
        for s in 0..total {
            run.step(self.dt)?;
            let v = run.max_free_speed();
            t.push(run.t);
            y.push(v);
            if !v.is_finite() || v > 1e3 {
                return Err(Error::Diverged {
                    step: s + 1,
                    t: run.t,
                    what: "max |v| above 1000 × c",
                    max_amplitude: v,
                });
            }
            if s % 64 == 0 {
                progress.advance(s as f64 / total as f64);
                if progress.cancelled() {
                    return Err(Error::Cancelled);
                }
            }
            if v > 100.0 * hi {
                break;
            }
        }
        let fit = growth_fit(&t, &y, lo, hi);
        let measured = fit.as_ref().map(|f| f.rate);
        let tol = crate::vonneumann::classify::GROWTH_TOL;
        Ok(ExperimentReport {
            name: self.name.clone(),
            remedy: self.remedy.label.clone(),
            form: q.form.name().into(),
            particles: count,
            stress: self.stress,
            measured_growth_rate: measured,
            fit,
            predicted_growth_rate_body: predicted,
            predicted_growth_rate_infinite: infinite,
            ratio_body: measured.filter(|_| predicted > tol).map(|m| m / predicted),
            max_velocity_end: *y.last().unwrap_or(&0.0),
            steps: run.steps,
            t: run.t,
        })
    }
}

/// Parses an experiment file (errors name the file and the field) and validates it.
pub fn parse_experiment(file: &str, text: &str) -> Result<Experiment> {
    let e: Experiment = crate::studies::config::parse_json(file, text)?;
    e.validate().map_err(|err| Error::Config {
        file: file.into(),
        msg: err.to_string(),
    })?;
    Ok(e)
}

/// The report as text.
pub fn experiment_text(r: &ExperimentReport) -> String {
    let f = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.6}"));
    format!(
        "{} / {} ({}): {} particles, σ̄ = {} (isotropic, held), t = {:.1} Δx/c in {} steps\n\
         measured growth {} c/Δx; predicted: body (exact operator) {:.6}, infinite lattice {:.6}; measured/body {}\n\
         max |v| at the end {:.3e} c\n",
        r.name,
        r.remedy,
        r.form,
        r.particles,
        r.stress,
        r.t,
        r.steps,
        f(r.measured_growth_rate),
        r.predicted_growth_rate_body,
        r.predicted_growth_rate_infinite,
        f(r.ratio_body),
        r.max_velocity_end
    )
}
