//! Scenes as JSON (1D bars; the 2D Swegle box has its own command), with built-ins by name:
//! `uniform-bar` \[V21 §7.1\], `compressive-wave` \[V21 §7.4\], `tensile-wave` \[V21 §7.5\] and
//! `rod` \[B00 §4.1.2\]. Unknown fields are rejected with the field named.
//!
//! Each built-in carries its analytic solution (linear elasticity, small strain; the velocity
//! field, which every form has), and a run reports the relative L2 error of the velocity of the
//! free particles at `t_end`: ‖v − v_exact‖₂ / ‖v_exact‖₂ (or / (v_scale √N) where v_exact ≡ 0).

use super::run::Run;
use crate::budget::{Budget, fmt_count};
use crate::error::{Error, Result, field, fields};
use crate::forms::{
    ArtificialViscosity, FormKind, Material, Model, ModelParams, State, ViscosityPairs,
};
use crate::kernel;
use crate::params::{ParamNames, check_common_named};
use crate::progress::Progress;
use crate::shape::{KernelParams, ShapeFamily};
use serde::{Deserialize, Serialize};

/// Initial velocity field.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(rename_all = "kebab-case", tag = "kind", deny_unknown_fields)]
pub enum InitialVelocity {
    /// v = 0.
    Rest,
    /// v = value everywhere.
    Uniform {
        /// Value (m/s).
        value: f64,
    },
    /// v = gradient · x.
    Linear {
        /// dv/dx (1/s).
        gradient: f64,
    },
    /// One particle (index) moves at value.
    Point {
        /// Particle index.
        index: usize,
        /// Value.
        value: f64,
    },
}

/// What holds an end of the bar: a layer of particles at a prescribed velocity (constant or a
/// pulse), or a prescribed stress (traction) on the end face, whose particles move freely.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct EndLayer {
    /// Number of particles whose velocity is prescribed (0 with `traction`).
    #[serde(default)]
    pub layers: usize,
    /// Prescribed velocity (m/s); null: keep the initial velocity of each particle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<f64>,
    /// A velocity pulse (m/s) the layer follows instead of a constant velocity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_pulse: Option<Pulse>,
    /// A normal stress (Pa, + tension) prescribed on the end face: the load f_K = −s̄(t) b_K
    /// of [`crate::forms::Model::unit_stress_force`] on the particles of this half of the bar,
    /// which makes the uniform stress s̄ an equilibrium of the form there (the traction
    /// boundary \[T §4.6.3.1\]: T11 = s̄ at the face).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traction: Option<Pulse>,
}

/// A pulse in time \[T §4.6.3.2\]: the square pulse of `amplitude` on [start, start +
/// duration] smoothed by the continuous SPH interpolation with the scene's kernel at smoothing
/// length `smoothing` (s):
/// g(t) = A [I((t − t0)/h_t) − I((t − t0 − T)/h_t)], I the kernel's 1D cumulative integral
/// ([`kernel::cumulative_1d`]); `smoothing` 0 is the square pulse itself. `start` defaults to
/// the kernel's support ζ h_t, so that the load rises from zero at t = 0.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Pulse {
    /// Amplitude (Pa for a traction, m/s for a velocity).
    pub amplitude: f64,
    /// Duration T of the square pulse (s).
    pub duration: f64,
    /// Smoothing length h_t (s; 0: none).
    #[serde(default)]
    pub smoothing: f64,
    /// Start t0 of the square pulse (s; null: ζ h_t).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<f64>,
}

impl Pulse {
    /// The start t0 of the square pulse with kernel `k`.
    pub fn start(&self, k: &dyn kernel::Kernel) -> f64 {
        self.start.unwrap_or(k.zeta() * self.smoothing)
    }

    /// g(t) with the scene's kernel `k`.
    pub fn at(&self, k: &dyn kernel::Kernel, t: f64) -> f64 {
        let t0 = self.start(k);
        let (a, b) = (t - t0, t - t0 - self.duration);
        if self.smoothing == 0.0 {
            // the square pulse; half its value on the edges (the limit of the smoothed one)
            let step = |s: f64| match s.partial_cmp(&0.0) {
                Some(std::cmp::Ordering::Greater) => 1.0,
                Some(std::cmp::Ordering::Equal) => 0.5,
                _ => 0.0,
            };
            return self.amplitude * (step(a) - step(b));
        }
        let h = self.smoothing;
        self.amplitude * (kernel::cumulative_1d(k, a / h) - kernel::cumulative_1d(k, b / h))
    }

    /// The time after which g vanishes.
    pub fn end(&self, k: &dyn kernel::Kernel) -> f64 {
        self.start(k) + self.duration + k.zeta() * self.smoothing
    }

    fn check(&self, name: &str, bound: f64) -> Result<()> {
        crate::error::check_range(
            end_field(&format!("{name}.amplitude")),
            self.amplitude,
            -bound,
            bound,
            true,
            true,
        )?;
        crate::error::check_range(
            end_field(&format!("{name}.duration")),
            self.duration,
            0.0,
            SCALE_RANGE.1,
            false,
            true,
        )?;
        crate::error::check_range(
            end_field(&format!("{name}.smoothing")),
            self.smoothing,
            0.0,
            SCALE_RANGE.1,
            true,
            true,
        )?;
        if let Some(t0) = self.start {
            crate::error::check_range(
                end_field(&format!("{name}.start")),
                t0,
                0.0,
                SCALE_RANGE.1,
                true,
                true,
            )?;
        }
        Ok(())
    }
}

/// The field names of the ends' keys (error messages name fields by `&'static str`).
const END_FIELDS: &[&str] = &[
    "left.traction",
    "left.layers",
    "left.velocity",
    "left.velocity_pulse",
    "left.traction.amplitude",
    "left.traction.duration",
    "left.traction.smoothing",
    "left.traction.start",
    "left.velocity_pulse.amplitude",
    "left.velocity_pulse.duration",
    "left.velocity_pulse.smoothing",
    "left.velocity_pulse.start",
    "right.traction",
    "right.layers",
    "right.velocity",
    "right.velocity_pulse",
    "right.traction.amplitude",
    "right.traction.duration",
    "right.traction.smoothing",
    "right.traction.start",
    "right.velocity_pulse.amplitude",
    "right.velocity_pulse.duration",
    "right.velocity_pulse.smoothing",
    "right.velocity_pulse.start",
];

/// The static name of the end field `name` (one of [`END_FIELDS`]).
fn end_field(name: &str) -> &'static str {
    END_FIELDS
        .iter()
        .find(|f| **f == name)
        .copied()
        .unwrap_or("left/right")
}

/// The material of a scene.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(rename_all = "kebab-case", tag = "kind", deny_unknown_fields)]
pub enum SceneMaterial {
    /// The 1D law σ̇ = (C + σ) ∂v/∂x of modulus C = `modulus` (\[B00\] eq 29).
    #[default]
    Linear,
    /// Compressible neo-Hookean \[T eq 3.62–3.64\] in uniaxial strain (λ2 = λ3 = 1), with
    /// Young's modulus `modulus` and Poisson ratio `poisson`: P = μ(F − 1/F) + λ ln F / F, the
    /// small-strain (P-wave) modulus λ + 2μ; `total-lagrangian` only.
    NeoHookean {
        /// Poisson ratio ν in [−0.99, 0.5).
        poisson: f64,
    },
}

/// Analytic solution of a built-in.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq)]
#[serde(rename_all = "kebab-case")]
pub enum Analytic {
    /// v = gradient · x at all times (uniform strain rate).
    UniformStrain,
    /// A step wave from a wall at the left end: v = 0 behind the front x < x0 + c t, v0 ahead.
    WallImpact,
    /// Pulses from the ends of a bar at rest (its old name `end-pull`, two step waves from
    /// ends pulled at constant velocities, is the special case of constant end velocities), with every reflection (\[T eq 4.36–4.37\] and
    /// images): an end with a `traction` s̄(t) sends σ = s̄ (and reflects stress inverted, as a
    /// free end), an end with a `velocity_pulse` or a constant `velocity` v̄(t) sends
    /// σ = ∓ρ0 c v̄ (left/right; it reflects stress unchanged, as a fixed end); an end without
    /// either is free. Waves moving right carry v = −σ/(ρ0 c), moving left v = σ/(ρ0 c).
    #[serde(alias = "end-pull")]
    EndPulse,
}

/// A 1D scene.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Scene1D {
    /// Name (free text).
    pub name: String,
    /// Form.
    pub form: String,
    /// Kernel.
    pub kernel: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// Shape family (null: the form's default).
    #[serde(default)]
    pub shape: Option<String>,
    /// Partition coefficient of lnl / cll.
    #[serde(default = "half")]
    pub c_partition: f64,
    /// Modulus (Pa): the tangent modulus C of the `linear` material (E for a bar), Young's
    /// modulus E of the `neo-hookean` one.
    pub modulus: f64,
    /// Material (default `linear`).
    #[serde(default)]
    pub material: SceneMaterial,
    /// Density ρ0 (kg/m³).
    pub rho0: f64,
    /// Initial stress σ0 (Pa, + tension).
    #[serde(default)]
    pub initial_stress: f64,
    /// Number of particles.
    pub particles: usize,
    /// Position of the first particle (m).
    pub origin: f64,
    /// Bar length between the first and the last particle (m).
    pub length: f64,
    /// Initial velocity.
    pub initial_velocity: InitialVelocity,
    /// Left end layer.
    #[serde(default)]
    pub left: Option<EndLayer>,
    /// Right end layer.
    #[serde(default)]
    pub right: Option<EndLayer>,
    /// Particles at the left and right ends whose momentum equation takes the classical (plus)
    /// form: the free-surface treatment of the difference forms nonlocal, local and lnl
    /// \[V21 §7.4, Fig 18(b): the last four particles at the free end\]. Default none.
    #[serde(default, skip_serializing_if = "is_zero_pair")]
    pub classical_layers: [usize; 2],
    /// Monaghan viscosity (α, β).
    #[serde(default)]
    pub artificial_viscosity: Option<(f64, f64)>,
    /// Which pairs the viscosity acts on: `one-sided` (approaching pairs only, as SPH codes
    /// apply it; default) or `two-sided` (every pair, as the analysis linearises it).
    #[serde(default)]
    pub artificial_viscosity_pairs: ViscosityPairs,
    /// End time (s).
    pub t_end: f64,
    /// Time step Δt in Δx/c, in (0, 2] (the CFL number c Δt/h is dt/(h/Δx)); `cfl`, its old
    /// name, is read too.
    #[serde(default = "dt_default", alias = "cfl")]
    pub dt: f64,
    /// Time integrator ([`crate::integrator::INTEGRATOR_NAMES`]; null: `kdk`).
    #[serde(default)]
    pub integrator: Option<String>,
    /// N_s of `verlet-euler` (null: 40).
    #[serde(default)]
    pub euler_every: Option<usize>,
    /// Analytic solution for the error norm.
    #[serde(default)]
    pub analytic: Option<Analytic>,
    /// Reference positions X (m) of the probes, at most [`MAX_PROBES`], each in [origin,
    /// origin + length]: the displacement, velocity and stress there are recorded at every
    /// step ([`ProbeHistory`]; linear between the two particles around X).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub probes: Vec<f64>,
    /// The budget the run must stay within (not read from the file: [`Budget::default`]
    /// unless the caller sets it).
    #[serde(skip)]
    pub budget: Budget,
}

/// The physical scales of a scene (`length` in m, `modulus` in Pa, `rho0` in kg/m³) must lie
/// in [SCALE_RANGE.0, SCALE_RANGE.1]: far beyond, squared distances and masses leave the range
/// of f64 (a bar of 1e150 m stops moving, one of 1e-150 m diverges at the first step).
pub const SCALE_RANGE: (f64, f64) = (1e-30, 1e30);

fn is_zero_pair(p: &[usize; 2]) -> bool {
    *p == [0, 0]
}

/// Most probes a scene records.
pub const MAX_PROBES: usize = 64;

fn half() -> f64 {
    0.5
}
fn dt_default() -> f64 {
    0.2
}

/// Built-in scenes by name.
pub fn builtin(name: &str) -> Result<Scene1D> {
    let text = match name {
        "uniform-bar" => UNIFORM_BAR,
        "compressive-wave" => COMPRESSIVE_WAVE,
        "tensile-wave" => TENSILE_WAVE,
        "rod" => ROD,
        _ => {
            return Err(Error::UnknownName {
                what: "scene".into(),
                given: name.into(),
                valid: "uniform-bar, compressive-wave, tensile-wave, rod, thesis-wave, swegle (or a JSON file)".into(),
            });
        }
    };
    parse(name, text)
}

/// Parses a scene; errors name the file and the field.
pub fn parse(file: &str, text: &str) -> Result<Scene1D> {
    crate::error::parse_json(file, text)
}

/// [V21 §7.1]: bar of length 1 centred at 0, 100 particles, v = 0.001 x (tension), the 3 particles
/// at each end keep their initial velocity, ρ0 = 8, E = 2, t = 10.
const UNIFORM_BAR: &str = r#"{
  "name": "uniform-bar", "form": "nonlocal", "kernel": "m4", "h_over_dx": 1.3,
  "modulus": 2.0, "rho0": 8.0, "particles": 100, "origin": -0.5, "length": 1.0,
  "initial_velocity": {"kind": "linear", "gradient": 0.001},
  "left": {"layers": 3, "velocity": null}, "right": {"layers": 3, "velocity": null},
  "t_end": 10.0, "dt": 0.2, "analytic": "uniform-strain"
}"#;

/// [V21 §7.4]: 5 cm steel bar (E = 200 GPa, ρ = 8000) at −50 m/s onto a rigid wall at x = 0,
/// 500 particles, h = 1.3Δx, viscosity 0.5; compared at 5 μs, before the wave reaches the free end.
const COMPRESSIVE_WAVE: &str = r#"{
  "name": "compressive-wave", "form": "classical", "kernel": "m4", "h_over_dx": 1.3,
  "modulus": 200e9, "rho0": 8000.0, "particles": 500, "origin": 0.0, "length": 0.05,
  "initial_velocity": {"kind": "uniform", "value": -50.0},
  "left": {"layers": 3, "velocity": 0.0},
  "artificial_viscosity": [0.5, 0.0],
  "t_end": 5e-6, "dt": 0.2, "analytic": "wall-impact"
}"#;

/// [V21 §7.5]: 0.2 m bar (E = 70.8 GPa, ρ = 1550), 200 particles, the 7 particles at each end
/// pulled outwards at 70 m/s; viscosity 0.5; compared at 10 μs, before the waves meet.
const TENSILE_WAVE: &str = r#"{
  "name": "tensile-wave", "form": "nonlocal", "kernel": "m4", "h_over_dx": 1.3,
  "modulus": 70.8e9, "rho0": 1550.0, "particles": 200, "origin": -0.1, "length": 0.2,
  "initial_velocity": {"kind": "rest"},
  "left": {"layers": 7, "velocity": -70.0}, "right": {"layers": 7, "velocity": 70.0},
  "artificial_viscosity": [0.5, 0.0],
  "t_end": 1e-5, "dt": 0.2, "analytic": "end-pulse"
}"#;

/// [B00 §4.1.2]: rod fixed at both ends (3 layers), σ0 = 1 GPa, E = 10 GPa, ρ = 2450, l = 0.04 m,
/// 41 nodes, centre node at 40 m/s, t = 1e-4 s.
const ROD: &str = r#"{
  "name": "rod", "form": "total-lagrangian", "kernel": "efg-quartic", "h_over_dx": 1.5, "shape": "mls",
  "modulus": 1e10, "rho0": 2450.0, "initial_stress": 1e9, "particles": 41, "origin": 0.0, "length": 0.04,
  "initial_velocity": {"kind": "point", "index": 20, "value": 40.0},
  "left": {"layers": 3, "velocity": 0.0}, "right": {"layers": 3, "velocity": 0.0},
  "t_end": 1e-4, "dt": 0.2
}"#;

/// The columns of a scene's history ([`SceneReport::history`], `history.csv`): time (s), max
/// |v| (m/s), kinetic energy.
pub const HISTORY_COLUMNS: [&str; 3] = ["t", "max_abs_v", "kinetic_energy"];

/// Result of a scene run.
#[derive(Clone, Debug, Serialize)]
pub struct SceneReport {
    /// Scene name.
    pub name: String,
    /// Form.
    pub form: &'static str,
    /// Time integrator (CLI name).
    pub integrator: &'static str,
    /// Time reached (s).
    pub t: f64,
    /// Steps.
    pub steps: usize,
    /// The time step taken, in Δx/c: the scene's `dt`, rounded down so that the steps end at
    /// `t_end`.
    pub dt: f64,
    /// The time step taken (s).
    pub dt_physical: f64,
    /// The particle spacing Δx (m).
    pub dx_physical: f64,
    /// The sound speed c = √(C/ρ0) (m/s).
    pub sound_speed_physical: f64,
    /// The modulus C (Pa): σ̄ = σ/C.
    pub modulus_physical: f64,
    /// Relative L2 error of the free particles' velocity against the analytic solution.
    pub velocity_error_l2: Option<f64>,
    /// Largest |v| over the run (m/s).
    pub max_velocity: f64,
    /// Wall-clock seconds.
    pub runtime_s: f64,
    /// Partition coefficient c of the mixed forms (lnl, cll; absent for the others).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c_partition: Option<f64>,
    /// The final stress ([`SceneReport::final_stress`]; null for the forms without a particle
    /// stress, the stress-point ones).
    pub stress: Option<StressSummary>,
    /// The times of the probe records (s; empty without probes): t = 0 and every step.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub probe_t: Vec<f64>,
    /// The probes' histories, in the order of the scene's `probes`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub probes: Vec<ProbeHistory>,
    /// History: (t, max |v|, kinetic energy).
    #[serde(skip)]
    pub history: Vec<(f64, f64, f64)>,
    /// The final stress of every particle ([`Model::particle_stress`]; empty for a form
    /// without one).
    #[serde(skip)]
    pub final_stress: Vec<f64>,
    /// Final positions, velocities and (if carried) stresses.
    #[serde(skip)]
    pub final_state: Option<State<f64, 1>>,
}

/// What a probe recorded at reference position X, at the times [`SceneReport::probe_t`]: each
/// quantity linear between the two particles around X (exact on a particle).
#[derive(Clone, Debug, Serialize)]
pub struct ProbeHistory {
    /// X (m).
    pub reference_position: f64,
    /// Displacement u = x − X (m).
    pub displacement: Vec<f64>,
    /// Velocity (m/s).
    pub velocity: Vec<f64>,
    /// Stress (Pa, + tension; [`Model::particle_stress`]: the Cauchy stress of the
    /// total-Lagrangian form, σ of the others); empty for a form without one.
    pub stress: Vec<f64>,
    /// The stretch F = ∂x/∂X of the total-Lagrangian form ([`Model::deformation_gradient_of`]);
    /// empty for the other forms.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stretch: Vec<f64>,
    /// The `end-pulse` solution's velocity at X ([`Scene1D::end_waves_at`]; empty for a
    /// scene without it).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub exact_velocity: Vec<f64>,
    /// The `end-pulse` solution's stress at X.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub exact_stress: Vec<f64>,
}

/// The particles and weights of a scene's probes: probe p reads (1 − w) q_i + w q_{i+1} of
/// each quantity q, (i, w) = `at[p]`.
struct ProbeSet {
    at: Vec<(usize, f64)>,
    /// Whether the form has a particle stress.
    stress: bool,
    /// Whether it has a deformation gradient (total-Lagrangian).
    stretch: bool,
}

impl ProbeSet {
    fn new(scene: &Scene1D, model: &Model<1>) -> Self {
        let n = scene.particles;
        let dx = scene.length / (n - 1) as f64;
        let at = scene
            .probes
            .iter()
            .map(|&x| {
                let f = ((x - scene.origin) / dx).clamp(0.0, (n - 1) as f64);
                let i = (f.floor() as usize).min(n - 2);
                (i, f - i as f64)
            })
            .collect();
        let z = model.rest_state(scene.rho0);
        Self {
            at,
            stress: model.particle_stress_of(&z, 0).is_some(),
            stretch: model.deformation_gradient_of(&z, 0).is_some(),
        }
    }

    fn is_empty(&self) -> bool {
        self.at.is_empty()
    }

    /// Appends the current values of `run` to the histories `h`.
    fn record(&self, run: &Run<1>, h: &mut [ProbeHistory]) {
        let z = &run.z;
        let m = &run.model;
        for (&(i, w), p) in self.at.iter().zip(h) {
            let mix = |a: f64, b: f64| (1.0 - w) * a + w * b;
            p.displacement.push(mix(
                z.x[i][0] - m.x_ref[i][0],
                z.x[i + 1][0] - m.x_ref[i + 1][0],
            ));
            p.velocity.push(mix(z.v[i][0], z.v[i + 1][0]));
            if self.stress {
                let s = |j: usize| m.particle_stress_of(z, j).map_or(0.0, |t| t[0][0]);
                let (a, b) = (s(i), if w > 0.0 { s(i + 1) } else { 0.0 });
                p.stress.push(mix(a, b));
            }
            if self.stretch {
                let f = |j: usize| m.deformation_gradient_of(z, j).map_or(1.0, |f| f[0][0]);
                let (a, b) = (f(i), if w > 0.0 { f(i + 1) } else { 1.0 });
                p.stretch.push(mix(a, b));
            }
        }
    }
}

/// The final stress of a scene run, the one its form integrates: σ, or (1 − c)σ + cτ for the
/// mixed forms, the Cauchy stress of the total-Lagrangian one ([`SceneReport::final_stress`]), in Pa.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct StressSummary {
    /// Smallest stress over every particle (end layers included).
    pub min: f64,
    /// Largest stress over every particle.
    pub max: f64,
    /// max |σ − σ_exact| over the free particles, divided by max |σ_exact| over them: the
    /// scene's analytic stress ([`Scene1D::exact_profile`]); null without an analytic solution
    /// or where σ_exact vanishes on every free particle.
    pub error_max: Option<f64>,
}

/// A run is stopped as diverged when max |v| exceeds this multiple of c + max |v(0)|: a
/// particle crossing a thousand spacings per acoustic transit time is no longer a solution of
/// the continuum problem (the first non-finite value stops it too).
pub const RUNAWAY_FACTOR: f64 = 1e3;

/// Field names of a scene for the shared validation ([`crate::params::check_common_named`]).
const SCENE_NAMES: ParamNames = ParamNames {
    h: "h_over_dx",
    stress: "initial_stress / modulus",
    c: "c_partition",
    av_alpha: "artificial_viscosity[0]",
    av_beta: "artificial_viscosity[1]",
    dt: "dt",
};

impl Scene1D {
    /// Validates every field through the same checks as the questions' fields, then the
    /// resources (memory, particle-steps) against [`Scene1D::budget`]. Returns (form, kernel,
    /// shape).
    pub fn validate(&self) -> Result<(FormKind, &'static dyn kernel::Kernel, ShapeFamily)> {
        let form = FormKind::by_name(&self.form)?;
        let k = kernel::by_name(&self.kernel)?;
        let shape = match &self.shape {
            Some(s) => ShapeFamily::by_name(s)?,
            None => form.default_shape(),
        };
        form.check_shape(shape)?;
        crate::error::check_range("particles", self.particles as f64, 4.0, 1e7, true, true)?;
        let (lo, hi) = SCALE_RANGE;
        crate::error::check_range("length", self.length, lo, hi, true, true)?;
        crate::error::check_range("modulus", self.modulus, lo, hi, true, true)?;
        crate::error::check_range("rho0", self.rho0, lo, hi, true, true)?;
        self.check_keys_apply(form)?;
        crate::error::check_range("t_end", self.t_end, 0.0, f64::INFINITY, false, false)?;
        crate::error::check_range("dt", self.dt, 0.0, 2.0, false, true)?;
        crate::error::check_range(
            "initial_stress",
            self.initial_stress,
            f64::MIN,
            f64::MAX,
            true,
            true,
        )?;
        check_common_named(
            &SCENE_NAMES,
            k,
            self.h_over_dx,
            self.initial_stress / self.tangent_modulus(),
            self.c_partition,
            self.artificial_viscosity,
            None,
        )?;
        let dx = self.length / (self.particles - 1) as f64;
        // positions origin + i Δx must stay distinct to ~1e-7 Δx in f64
        crate::error::check_range("origin", self.origin, -1e9 * dx, 1e9 * dx, true, true)?;
        let material = self.material_model()?;
        let c = (self.tangent_modulus() / self.rho0).sqrt();
        if !(c.is_finite() && c > 0.0) {
            return Err(Error::OutOfRange {
                field: "modulus / rho0",
                value: self.modulus / self.rho0,
                range: "the sound speed sqrt(modulus/rho0) must be a positive finite number".into(),
            });
        }
        let vmax = self.initial_speed_bound();
        crate::error::check_range("initial_velocity", vmax, 0.0, 100.0 * c, true, true)?;
        let (l, r) = (
            self.left.as_ref().map_or(0, |e| e.layers),
            self.right.as_ref().map_or(0, |e| e.layers),
        );
        for (name, e) in [
            ("left.velocity", &self.left),
            ("right.velocity", &self.right),
        ] {
            if let Some(v) = e.as_ref().and_then(|e| e.velocity) {
                crate::error::check_range(name, v, -100.0 * c, 100.0 * c, true, true)?;
            }
        }
        for (name, e) in [("left", &self.left), ("right", &self.right)] {
            if let Some(e) = e {
                self.check_end(name, e, material, c)?;
            }
        }
        if self.probes.len() > MAX_PROBES {
            return Err(Error::OutOfRange {
                field: "probes",
                value: self.probes.len() as f64,
                range: format!("give at most {MAX_PROBES} probes").into(),
            });
        }
        for &x in &self.probes {
            crate::error::check_range(
                "probes",
                x,
                self.origin,
                self.origin + self.length,
                true,
                true,
            )?;
        }
        if self.classical_layers[0] + self.classical_layers[1] + 2 > self.particles {
            return Err(Error::OutOfRange {
                field: "classical_layers",
                value: (self.classical_layers[0] + self.classical_layers[1]) as f64,
                range: format!(
                    "must leave at least 2 particles in the difference form: at most {} for {} particles",
                    self.particles - 2,
                    self.particles
                )
                .into(),
            });
        }
        if l + r + 2 > self.particles {
            return Err(Error::OutOfRange {
                field: "left.layers + right.layers",
                value: (l + r) as f64,
                range: format!(
                    "must leave at least 2 free particles: at most {} for {} particles",
                    self.particles - 2,
                    self.particles
                )
                .into(),
            });
        }
        // resources (the budget): stencils of ~2R/Δx + 1 neighbours (index, φ, φ', φ'':
        // 32 B) per particle and evaluation point, ~60 f64 of state, integrator copies and
        // scratch per particle, the history (3 f64 per step)
        let n = self.particles as f64;
        let neighbours = 2.0 * k.zeta() * self.h_over_dx + 1.0;
        let steps = (self.t_end / (self.dt * dx / c)).ceil();
        self.budget.steps(
            field("t_end")
                + ", "
                + field("dt")
                + ", "
                + fields(&["length", "particles"])
                + ", "
                + fields(&["modulus", "rho0"])
                + " (steps = t_end c/(dt Δx))",
            &format!("the scene ({} time steps)", fmt_count(steps)),
            n * steps,
        )?;
        if self.analytic == Some(Analytic::EndPulse) && !self.probes.is_empty() {
            // the probes' analytic histories: at every record, 4 image terms per pair of
            // bar crossings (Scene1D::end_waves_at), each a pulse evaluation, counted as a
            // particle-step (measured, thesis-traction-pulse.json with 64 probes to 300 μs:
            // 1.3e7 evaluations took 0.42 s, the run's 1.0e7 particle-steps 0.98 s)
            let crossings = (self.t_end * c / (2.0 * self.length)).floor() + 1.0;
            self.budget.steps(
                field("probes")
                    + ", "
                    + field("t_end")
                    + ", "
                    + field("dt")
                    + " (analytic: probes × steps × 4 × reflections)",
                &format!(
                    "the probes' analytic histories ({} pulse evaluations)",
                    fmt_count(self.probes.len() as f64 * (steps + 1.0) * 4.0 * crossings)
                ),
                self.probes.len() as f64 * (steps + 1.0) * 4.0 * crossings,
            )?;
        }
        self.budget.memory(
            fields(&["particles", "h_over_dx"]),
            &format!(
                "the scene ({} particles, ~{neighbours:.0} neighbours each)",
                self.particles
            ),
            n * (neighbours * 32.0 * 3.0 + 480.0)
                + 8.0 * steps * (3.0 + 7.0 * self.probes.len() as f64),
        )?;
        Ok((form, k, shape))
    }

    /// The model's material: `linear` is the 1D bar of modulus C; `neo-hookean` has
    /// λ = Eν/((1 + ν)(1 − 2ν)), μ = E/(2(1 + ν)).
    pub fn material_model(&self) -> Result<Material> {
        Ok(match self.material {
            SceneMaterial::Linear => Material::bar(self.modulus),
            SceneMaterial::NeoHookean { poisson } => {
                crate::error::check_range("material.poisson", poisson, -0.99, 0.5, true, false)?;
                if self.initial_stress != 0.0 {
                    return Err(Error::OutOfRange {
                        field: "initial_stress",
                        value: self.initial_stress,
                        range: "must be 0 with the neo-hookean material (its reference state is unstressed)".into(),
                    });
                }
                let e = self.modulus;
                Material::NeoHookean {
                    lambda: e * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
                    shear: e / (2.0 * (1.0 + poisson)),
                }
            }
        })
    }

    /// The small-strain tangent modulus of the material: C (`linear`), λ + 2μ
    /// (`neo-hookean`); the sound speed is √(it/ρ0). `modulus` where the material is invalid
    /// (validation names it).
    pub fn tangent_modulus(&self) -> f64 {
        self.material_model().map_or(self.modulus, |m| m.modulus())
    }

    /// Checks an end (`name` = left or right) of material `material` and sound speed `c`.
    fn check_end(&self, name: &str, e: &EndLayer, material: Material, c: f64) -> Result<()> {
        let given = |key: &str| end_field(&format!("{name}.{key}"));
        if let Some(t) = &e.traction {
            if e.layers > 0 || e.velocity.is_some() || e.velocity_pulse.is_some() {
                return Err(Error::Incompatible(
                    field(given("traction"))
                        + " loads an end whose particles move freely: give no "
                        + field(given("layers"))
                        + ", "
                        + field(given("velocity"))
                        + " or "
                        + field(given("velocity_pulse")),
                ));
            }
            // the linear 1D law has C + σ > 0 for σ > −C; the neo-Hookean bar any stress
            let bound = match material {
                Material::NeoHookean { .. } => 100.0 * self.tangent_modulus(),
                _ => 0.5 * self.tangent_modulus(),
            };
            t.check(&format!("{name}.traction"), bound)?;
        }
        if let Some(p) = &e.velocity_pulse {
            if e.velocity.is_some() {
                return Err(Error::Incompatible(
                    field(given("velocity_pulse"))
                        + " replaces "
                        + field(given("velocity"))
                        + ": give one of them",
                ));
            }
            if e.layers == 0 {
                return Err(Error::Incompatible(
                    field(given("velocity_pulse"))
                        + " drives a layer of particles: give "
                        + field(given("layers"))
                        + " ≥ 1",
                ));
            }
            p.check(&format!("{name}.velocity_pulse"), 100.0 * c)?;
        }
        Ok(())
    }

    /// Refuses keys that cannot act: a `c_partition` other than its default 0.5 for a form
    /// other than lnl and cll, `euler_every` with another integrator than verlet-euler,
    /// `artificial_viscosity_pairs` other than its default without `artificial_viscosity`.
    /// (A key at its default acts as much as an absent one: a scene written back by serde
    /// holds every key.)
    fn check_keys_apply(&self, form: FormKind) -> Result<()> {
        if self.classical_layers != [0, 0]
            && !matches!(form, FormKind::Nonlocal | FormKind::Local | FormKind::Lnl)
        {
            return Err(Error::Incompatible(
                field("classical_layers")
                    + " (a boundary layer in the classical form) applies to the difference forms nonlocal, local and lnl, not "
                    + field("form")
                    + format!(" {}", form.name()),
            ));
        }
        if self.c_partition != half() && !matches!(form, FormKind::Lnl | FormKind::Cll) {
            return Err(Error::Incompatible(
                field("c_partition")
                    + " applies to the forms lnl and cll, not "
                    + field("form")
                    + format!(" {}", form.name()),
            ));
        }
        if self.analytic == Some(Analytic::EndPulse)
            && self.initial_velocity != InitialVelocity::Rest
        {
            return Err(Error::Incompatible(
                field("analytic")
                    + " end-pulse is the solution for a bar at rest: give "
                    + field("initial_velocity")
                    + " rest",
            ));
        }
        let integrator = self.integrator.as_deref().unwrap_or("kdk");
        if self.euler_every.is_some() && integrator != "verlet-euler" {
            return Err(Error::Incompatible(
                field("euler_every")
                    + " applies to "
                    + field("integrator")
                    + format!(" verlet-euler, not {integrator}"),
            ));
        }
        if self.artificial_viscosity_pairs != ViscosityPairs::default()
            && self.artificial_viscosity.is_none()
        {
            return Err(Error::Incompatible(
                field("artificial_viscosity_pairs")
                    + " applies with "
                    + field("artificial_viscosity")
                    + " (there is no viscosity to switch)",
            ));
        }
        Ok(())
    }

    /// Replaces the form (`simulate --form`): a `c_partition` the file gave then applies only
    /// if the new form is lnl or cll, `classical_layers` only if it is a difference form
    /// (nonlocal, local, lnl), and each returns to its default otherwise (the override
    /// replaces the scene's choice of form with what goes with it).
    pub fn override_form(&mut self, form: &str) {
        self.form = form.to_string();
        if !matches!(FormKind::by_name(form), Ok(FormKind::Lnl | FormKind::Cll)) {
            self.c_partition = half();
        }
        if !matches!(
            FormKind::by_name(form),
            Ok(FormKind::Nonlocal | FormKind::Local | FormKind::Lnl)
        ) {
            self.classical_layers = [0, 0];
        }
    }

    /// Replaces the integrator (`simulate --integrator`, `--euler-every`): an `euler_every` the
    /// file gave is forgotten with another integrator than verlet-euler.
    pub fn override_integrator(&mut self, name: String, euler_every: Option<usize>) {
        self.euler_every = if name == "verlet-euler" {
            euler_every
        } else {
            None
        };
        self.integrator = Some(name);
    }

    /// The largest initial speed of any particle.
    fn initial_speed_bound(&self) -> f64 {
        match self.initial_velocity {
            InitialVelocity::Rest => 0.0,
            InitialVelocity::Uniform { value } => value.abs(),
            InitialVelocity::Point { value, .. } => value.abs(),
            InitialVelocity::Linear { gradient } => {
                gradient.abs() * self.origin.abs().max((self.origin + self.length).abs())
            }
        }
    }

    /// The scene's time integrator (`integrator`, `euler_every`; default `kdk`, N_s = 40).
    pub fn integrator(&self) -> Result<crate::integrator::Integrator> {
        use crate::integrator::{DEFAULT_EULER_EVERY, Integrator};
        let every = self.euler_every.unwrap_or(DEFAULT_EULER_EVERY);
        Integrator::from_name(self.integrator.as_deref().unwrap_or("kdk"), every).map_err(|e| {
            let field = if matches!(e, Error::UnknownName { .. }) {
                "integrator"
            } else {
                "euler_every"
            };
            Error::Config {
                file: format!("scene `{}`", self.name),
                msg: format!("field `{field}`: {e}"),
            }
        })
    }

    /// Builds and runs the scene, telling `progress` the fraction done.
    pub fn run(&self, progress: impl Progress) -> Result<SceneReport> {
        let (form, k, shape) = self.validate()?;
        let n = self.particles;
        let dx = self.length / (n - 1) as f64;
        let x = self.reference_positions();
        let c = (self.tangent_modulus() / self.rho0).sqrt();
        let p = ModelParams {
            form,
            shape,
            kp: KernelParams {
                kernel: k,
                h: self.h_over_dx * dx,
            },
            material: self.material_model()?,
            rho0: self.rho0,
            c_partition: self.c_partition,
            av: self
                .artificial_viscosity
                .map(|(alpha, beta)| ArtificialViscosity {
                    alpha,
                    beta,
                    sound_speed: c,
                    approaching_only: self.artificial_viscosity_pairs.approaching_only(),
                }),
            art_stress: None,
            diffusion: None,
            alpha_s: 0.0,
            ls_length: dx,
        };
        let x_ref: Vec<[f64; 1]> = x.iter().map(|&xi| [xi]).collect();
        let mut model = Model::new(p, x_ref, vec![dx; n], self.rho0, self.initial_stress, None)?;
        if self.classical_layers != [0, 0] {
            let [l, r] = self.classical_layers;
            model.set_classical_layer((0..n).map(|i| i < l || i >= n - r).collect())?;
        }
        let mut z = model.rest_state(self.rho0);
        if let InitialVelocity::Point { index, .. } = self.initial_velocity
            && index >= n
        {
            return Err(Error::OutOfRange {
                field: "initial_velocity.index",
                value: index as f64,
                range: format!("must be < particles = {n}").into(),
            });
        }
        let v_init = self.initial_velocities(&x);
        z.v = v_init.iter().map(|&v| [v]).collect();
        let prescribed = self.prescribed_at(&v_init, 0.0, k);
        let free: Vec<bool> = prescribed.iter().map(|p| p.is_none()).collect();
        let pv: Vec<Option<[f64; 1]>> = prescribed.iter().map(|p| p.map(|v| [v])).collect();
        // the traction ends' load pattern: −b_K on the particles of the loaded half
        let tractions =
            [self.left.as_ref(), self.right.as_ref()].map(|e| e.and_then(|e| e.traction.as_ref()));
        let unit = if tractions.iter().any(Option::is_some) {
            model.unit_stress_force(0)?
        } else {
            Vec::new()
        };
        let mid = self.origin + 0.5 * self.length;
        let pulsed = self
            .left
            .as_ref()
            .is_some_and(|e| e.velocity_pulse.is_some())
            || self
                .right
                .as_ref()
                .is_some_and(|e| e.velocity_pulse.is_some());
        let mut run = Run::with_prescribed(model, z, &pv)?;
        let integ = self.integrator()?;
        run.set_integrator(integ);
        let dt = self.dt * dx / c;
        let steps = (self.t_end / dt).ceil() as usize;
        let dt = self.t_end / steps as f64;
        let mass = self.rho0 * dx;
        let mut history = Vec::with_capacity(steps + 1);
        let mut vmax: f64 = 0.0;
        let runaway = RUNAWAY_FACTOR
            * (c + v_init.iter().fold(0.0f64, |m, v| m.max(v.abs()))
                + prescribed
                    .iter()
                    .flatten()
                    .fold(0.0f64, |m, v| m.max(v.abs()))
                + self.pulse_speed_bound(c));
        let probes = ProbeSet::new(self, &run.model);
        let mut probe_t = Vec::with_capacity(if probes.is_empty() { 0 } else { steps + 1 });
        let mut probe_h: Vec<ProbeHistory> = self
            .probes
            .iter()
            .map(|&x| ProbeHistory {
                reference_position: x,
                displacement: Vec::with_capacity(steps + 1),
                velocity: Vec::with_capacity(steps + 1),
                stress: Vec::new(),
                stretch: Vec::new(),
                exact_velocity: Vec::new(),
                exact_stress: Vec::new(),
            })
            .collect();
        if !probes.is_empty() {
            probe_t.push(run.t);
            probes.record(&run, &mut probe_h);
        }
        let start = std::time::Instant::now();
        for s in 0..steps {
            // time-dependent ends, held at the step's midpoint
            let t_mid = run.t + 0.5 * dt;
            if !unit.is_empty() {
                let [sl, sr] = tractions.map(|t| t.map_or(0.0, |p| p.at(k, t_mid)));
                let load = unit
                    .iter()
                    .zip(&x)
                    .map(|(b, &xi)| [-(if xi < mid { sl } else { sr }) * b[0]])
                    .collect();
                run.set_load(load)?;
            }
            if pulsed {
                for (v, p) in run
                    .z
                    .v
                    .iter_mut()
                    .zip(self.prescribed_at(&v_init, t_mid, k))
                {
                    if let Some(p) = p {
                        *v = [p];
                    }
                }
            }
            if run.step(dt).is_err() {
                return Err(Error::Diverged {
                    step: s + 1,
                    t: run.t + dt,
                    what: "a non-finite velocity",
                    max_amplitude: f64::INFINITY,
                });
            }
            let vm = run.z.v.iter().fold(0.0f64, |m, [v]| m.max(v.abs()));
            if vm > runaway {
                return Err(Error::Diverged {
                    step: s + 1,
                    t: run.t,
                    what: "max |v| above 1000 × (c + the largest initial or prescribed speed)",
                    max_amplitude: vm,
                });
            }
            vmax = vmax.max(vm);
            let ke = 0.5 * mass * run.z.v.iter().map(|[v]| v * v).sum::<f64>();
            history.push((run.t, vm, ke));
            if !probes.is_empty() {
                probe_t.push(run.t);
                probes.record(&run, &mut probe_h);
            }
            if s % 256 == 0 {
                progress.advance(run.t / self.t_end);
                if progress.cancelled() {
                    return Err(Error::Cancelled);
                }
            }
        }
        let runtime_s = start.elapsed().as_secs_f64();
        let error = self.exact_profile(run.t).map(|(exact, _)| {
            let (mut num, mut den, mut cnt) = (0.0, 0.0, 0usize);
            let mut scale: f64 = 0.0;
            for i in (0..n).filter(|&i| free[i]) {
                num += (run.z.v[i][0] - exact[i]).powi(2);
                den += exact[i].powi(2);
                cnt += 1;
                scale = scale.max(exact[i].abs()).max(v_init[i].abs());
            }
            if den > 0.0 {
                (num / den).sqrt()
            } else {
                (num / cnt.max(1) as f64).sqrt() / scale.max(1e-300)
            }
        });
        if self.analytic == Some(Analytic::EndPulse) {
            for p in &mut probe_h {
                for &t in &probe_t {
                    if let Some((v, s)) = self.end_waves_at(p.reference_position, t) {
                        p.exact_velocity.push(v);
                        p.exact_stress.push(s);
                    }
                }
            }
        }
        let final_stress: Vec<f64> = run
            .model
            .particle_stress(&run.z)
            .iter()
            .map(|[[s]]| *s)
            .collect();
        let stress = self.stress_summary(&final_stress, run.t, &free);
        Ok(SceneReport {
            name: self.name.clone(),
            form: form.name(),
            integrator: integ.name(),
            t: run.t,
            steps: run.steps,
            dt: dt * c / dx,
            dt_physical: dt,
            dx_physical: dx,
            sound_speed_physical: c,
            modulus_physical: self.tangent_modulus(),
            velocity_error_l2: error,
            max_velocity: vmax,
            runtime_s,
            c_partition: matches!(form, FormKind::Lnl | FormKind::Cll).then_some(self.c_partition),
            stress,
            probe_t,
            probes: probe_h,
            history,
            final_stress,
            final_state: Some(run.z),
        })
    }

    /// The largest speed the ends' pulses drive: |v̄| of a velocity pulse, |s̄|/(ρ0 c) of a
    /// traction.
    fn pulse_speed_bound(&self, c: f64) -> f64 {
        [&self.left, &self.right]
            .into_iter()
            .flatten()
            .map(|e| {
                let v = e.velocity_pulse.as_ref().map_or(0.0, |p| p.amplitude.abs());
                let t = e
                    .traction
                    .as_ref()
                    .map_or(0.0, |p| p.amplitude.abs() / (self.rho0 * c));
                v.max(t)
            })
            .fold(0.0, f64::max)
    }

    /// The analytic velocity at reference position `xi` (initial velocity `v0`, end velocities
    /// `ends`) when the fronts have travelled `ct`.
    /// Initial velocity of every particle at the reference positions `x`.
    fn initial_velocities(&self, x: &[f64]) -> Vec<f64> {
        x.iter()
            .enumerate()
            .map(|(i, &xi)| match self.initial_velocity {
                InitialVelocity::Rest => 0.0,
                InitialVelocity::Uniform { value } => value,
                InitialVelocity::Linear { gradient } => gradient * xi,
                InitialVelocity::Point { index, value } => {
                    if i == index {
                        value
                    } else {
                        0.0
                    }
                }
            })
            .collect()
    }

    /// The prescribed velocity of every particle at time `t` (None: free), from the end
    /// layers (their constant velocity or pulse, with the scene's kernel `k`) and the initial
    /// velocities `v`.
    fn prescribed_at(&self, v: &[f64], t: f64, k: &dyn kernel::Kernel) -> Vec<Option<f64>> {
        let n = v.len();
        let mut prescribed = vec![None; n];
        let value = |e: &EndLayer, vi: f64| match (&e.velocity_pulse, e.velocity) {
            (Some(p), _) => p.at(k, t),
            (None, Some(v)) => v,
            (None, None) => vi,
        };
        if let Some(l) = &self.left {
            for (i, p) in prescribed.iter_mut().enumerate().take(l.layers.min(n)) {
                *p = Some(value(l, v[i]));
            }
        }
        if let Some(r) = &self.right {
            let first = n.saturating_sub(r.layers);
            for (p, &vi) in prescribed.iter_mut().zip(v).skip(first) {
                *p = Some(value(r, vi));
            }
        }
        prescribed
    }

    /// Reference positions X_i = origin + iΔx of the particles (m).
    pub fn reference_positions(&self) -> Vec<f64> {
        let n = self.particles;
        let dx = self.length / (n - 1) as f64;
        (0..n).map(|i| self.origin + i as f64 * dx).collect()
    }

    /// The scene's analytic solution at time `t` at the reference positions
    /// ([`Scene1D::reference_positions`]): (velocity, stress), None without `analytic`. The
    /// velocity is the one the error norm of [`Scene1D::run`] uses. The stress follows from it
    /// for sphstab's 1D law σ̇ = (C + σ) ∂v/∂x (\[B00\] eq 72):
    /// - `uniform-strain` (v = g X): x = X(1 + g t), ∂v/∂x = g/(1 + g t), so C + σ =
    ///   (C + σ0)(1 + g t), **σ = σ0 + (C + σ0) g t** (0 for an initial velocity that is not
    ///   `linear`);
    /// - `wall-impact` (linear, small strain, c = √(C/ρ0)): across a front moving right σ
    ///   jumps by −ρ0 c \[v\], so σ = σ0 + ρ0 c (v_0 − v) behind the wall's front;
    /// - `end-pulse`: [`Scene1D::end_waves_at`] at every particle.
    pub fn exact_profile(&self, t: f64) -> Option<(Vec<f64>, Vec<f64>)> {
        let a = self.analytic?;
        let n = self.particles;
        let x = self.reference_positions();
        if a == Analytic::EndPulse {
            return Some(
                x.iter()
                    .map(|&xi| self.end_waves_at(xi, t))
                    .collect::<Option<Vec<_>>>()?
                    .into_iter()
                    .unzip(),
            );
        }
        let c = (self.tangent_modulus() / self.rho0).sqrt();
        let v_init = self.initial_velocities(&x);
        let v: Vec<f64> = (0..n)
            .map(|i| self.exact_velocity(a, x[i], v_init[i], t * c))
            .collect();
        let z = self.rho0 * c;
        let s0 = self.initial_stress;
        let sigma = (0..n)
            .map(|i| match a {
                Analytic::UniformStrain => match self.initial_velocity {
                    InitialVelocity::Linear { gradient } => {
                        s0 + (self.tangent_modulus() + s0) * gradient * t
                    }
                    _ => s0,
                },
                _ => s0 + z * (v_init[i] - v[i]),
            })
            .collect();
        Some((v, sigma))
    }

    /// The `end-pulse` solution (velocity, stress) at reference position `xi` and time `t`
    /// (linear, small strain, c = √(C/ρ0), Z = ρ0 c; \[T eq 4.36–4.37\] for one end, with
    /// images for the reflections). Each end is a boundary at X_b with a source stress s(τ)
    /// and a stress reflection coefficient r:
    /// - a traction s̄(τ): X_b the end particle, s = s̄, r = −1;
    /// - a velocity layer (pulse or constant v̄, from τ = 0): X_b its innermost particle,
    ///   s = −Z v̄ at the left end, +Z v̄ at the right one, r = +1;
    /// - neither: X_b the end particle, s = 0, r = −1 (free).
    ///
    /// With L = X_R − X_L, ξ = xi − X_L, η = X_R − xi, q = r_L r_R:
    /// σ = σ0 + Σ_n qⁿ [s_L(t − (2nL + ξ)/c) + r_R s_L(t − (2(n+1)L − ξ)/c)
    ///                 + s_R(t − (2nL + η)/c) + r_L s_R(t − (2(n+1)L − η)/c)],
    /// and v the same sum with each right-moving wave times −1/Z, each left-moving one 1/Z.
    /// None unless the bar starts at rest (its initial stress σ0 uniform).
    pub fn end_waves_at(&self, xi: f64, t: f64) -> Option<(f64, f64)> {
        if self.initial_velocity != InitialVelocity::Rest {
            return None;
        }
        let k = kernel::by_name(&self.kernel).ok()?;
        let n = self.particles;
        let dx = self.length / (n - 1) as f64;
        let c = (self.tangent_modulus() / self.rho0).sqrt();
        let z = self.rho0 * c;
        // the source stress of end `e` at time τ after the start; `sign` is −1 at the left
        // end (a velocity v̄ there sends σ = −Z v̄), +1 at the right
        let source = |e: Option<&EndLayer>, sign: f64, tau: f64| -> f64 {
            if tau <= 0.0 {
                return 0.0;
            }
            match e {
                Some(EndLayer {
                    traction: Some(p), ..
                }) => p.at(k, tau),
                Some(EndLayer {
                    velocity_pulse: Some(p),
                    ..
                }) => sign * z * p.at(k, tau),
                Some(EndLayer {
                    velocity: Some(v),
                    layers,
                    ..
                }) if *layers > 0 => sign * z * v,
                _ => 0.0,
            }
        };
        // (boundary position, stress reflection coefficient) of an end
        let boundary = |e: Option<&EndLayer>, outer: f64, inward: f64| match e
            .filter(|e| e.layers > 0 && e.traction.is_none())
        {
            Some(e) => (outer + inward * (e.layers - 1) as f64 * dx, 1.0),
            None => (outer, -1.0),
        };
        let (left, right) = (self.left.as_ref(), self.right.as_ref());
        let (xl, rl) = boundary(left, self.origin, 1.0);
        let (xr, rr) = boundary(right, self.origin + self.length, -1.0);
        let sl = |tau: f64| source(left, -1.0, tau);
        let sr = |tau: f64| source(right, 1.0, tau);
        let len = xr - xl;
        let xi = xi.clamp(xl, xr);
        let (xi_l, eta) = (xi - xl, xr - xi);
        let (mut sigma, mut v) = (self.initial_stress, 0.0);
        let q = rl * rr;
        let mut w = 1.0;
        let mut m = 0usize;
        while (2 * m) as f64 * len / c <= t {
            let d = 2.0 * m as f64 * len;
            let d2 = 2.0 * (m + 1) as f64 * len;
            // left source: right-moving, then reflected at the right end
            let (a1, a2) = (w * sl(t - (d + xi_l) / c), w * rr * sl(t - (d2 - xi_l) / c));
            // right source: left-moving, then reflected at the left end
            let (b1, b2) = (w * sr(t - (d + eta) / c), w * rl * sr(t - (d2 - eta) / c));
            sigma += a1 + a2 + b1 + b2;
            v += (-a1 + a2 + b1 - b2) / z;
            w *= q;
            m += 1;
        }
        Some((v, sigma))
    }

    /// The [`StressSummary`] of the final stress `s` (one per particle) at time `t` (`free`:
    /// the particles whose velocity is not prescribed); None for a form without a stress.
    fn stress_summary(&self, s: &[f64], t: f64, free: &[bool]) -> Option<StressSummary> {
        if s.is_empty() {
            return None;
        }
        let error_max = self.exact_profile(t).and_then(|(_, exact)| {
            let (mut err, mut scale) = (0.0f64, 0.0f64);
            for i in (0..s.len()).filter(|&i| free[i]) {
                err = err.max((s[i] - exact[i]).abs());
                scale = scale.max(exact[i].abs());
            }
            (scale > 0.0).then_some(err / scale)
        });
        Some(StressSummary {
            min: s.iter().copied().fold(f64::INFINITY, f64::min),
            max: s.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            error_max,
        })
    }

    fn exact_velocity(&self, a: Analytic, xi: f64, v0: f64, ct: f64) -> f64 {
        match a {
            Analytic::WallImpact => {
                let dx = self.length / (self.particles - 1) as f64;
                let wall = self.origin
                    + self
                        .left
                        .as_ref()
                        .map(|l| l.layers.saturating_sub(1))
                        .unwrap_or(0) as f64
                        * dx;
                if xi - wall < ct { 0.0 } else { v0 }
            }
            _ => v0,
        }
    }
}
