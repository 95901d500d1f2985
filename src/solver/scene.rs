//! Scenes as JSON: bars along x in 1D, 2D or 3D (`dim`; the 2D Swegle box has its own
//! command), with built-ins by name: `uniform-bar` \[V21 §7.1\], `compressive-wave`
//! \[V21 §7.4\], `tensile-wave` \[V21 §7.5\] and `rod` \[B00 §4.1.2\]. Unknown fields are
//! rejected with the field named.
//!
//! One scene type for every dimension: a bar of `particles` columns along x and a `section`
//! of n_y (× n_z) particles across, on a square (cubic) lattice of spacing Δx. The ends
//! (`left`, `right`) act on whole columns; each side face is free or a symmetry plane
//! (`sides`), whose ghost particles ([`crate::solver::Mirror`]) make the bar's neighbourhoods
//! whole across it, so that half, a quarter or an eighth of a symmetric bar is simulated, and a
//! bar between symmetry planes on every side is in uniaxial (1D) strain.
//!
//! Each built-in carries its analytic solution (linear elasticity, small strain; the velocity
//! field, which every form has), and a run reports the relative L2 error of the axial velocity
//! of the free particles at `t_end`: ‖v − v_exact‖₂ / ‖v_exact‖₂ (or / (v_scale √N) where
//! v_exact ≡ 0). In 2D and 3D an analytic solution needs symmetry planes on every side (the
//! 1D-strain bar), with c = √((λ + 2G)/ρ0).

use super::output::FinalState;
use super::run::{Mirror, Run};
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
    /// A symmetry plane half a spacing beyond the end column (as a `symmetry` side): the bar
    /// meets its mirror image there, which is a frictionless rigid wall for the bar.
    #[serde(default, skip_serializing_if = "is_false")]
    pub symmetry: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
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

/// The field names of the pulses' keys, at the ends and across (error messages name fields by
/// `&'static str`).
const END_FIELDS: &[&str] = &[
    "left.traction",
    "left.symmetry",
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
    "right.symmetry",
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
    "transverse_stretch_rate.amplitude",
    "transverse_stretch_rate.duration",
    "transverse_stretch_rate.smoothing",
    "transverse_stretch_rate.start",
];

/// The static name of the end field `name` (one of [`END_FIELDS`]).
fn end_field(name: &str) -> &'static str {
    END_FIELDS
        .iter()
        .find(|f| **f == name)
        .copied()
        .unwrap_or("left/right")
}

/// A side face of a 2D or 3D bar.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    /// A free (traction-free) surface.
    #[default]
    Free,
    /// A symmetry plane half a spacing beyond the outermost particles: ghost particles mirror
    /// the bar across it (no normal motion, no shear traction on the plane).
    Symmetry,
}

/// A probe's position: X on the bar's axis (`0.05`), or the point [X, Y(, Z)] (the lattice row
/// nearest to (Y, Z) is read).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(untagged)]
pub enum Probe {
    /// X (m), on the axis.
    Axis(f64),
    /// [X, Y(, Z)] (m).
    Point(Vec<f64>),
}

impl Probe {
    /// X (m).
    pub fn x(&self) -> f64 {
        match self {
            Probe::Axis(x) => *x,
            Probe::Point(p) => p.first().copied().unwrap_or(f64::NAN),
        }
    }

    /// The transverse coordinates (Y, Z) given (empty: on the axis).
    pub fn across(&self) -> &[f64] {
        match self {
            Probe::Axis(_) => &[],
            Probe::Point(p) => p.get(1..).unwrap_or(&[]),
        }
    }
}

/// The material of a scene.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(rename_all = "kebab-case", tag = "kind", deny_unknown_fields)]
pub enum SceneMaterial {
    /// In 1D the law σ̇ = (C + σ) ∂v/∂x of modulus C = `modulus` (\[B00\] eq 29); in 2D
    /// (plane strain) and 3D the hypo-elastic law with the Truesdell rate, of Young's modulus
    /// E = `modulus` and Poisson ratio `poisson` (λ = Eν/((1 + ν)(1 − 2ν)), G = E/(2(1 + ν));
    /// its uniaxial-strain law is the 1D one with C = λ + 2G).
    Linear {
        /// Poisson ratio ν in [−0.99, 0.5) (2D and 3D only).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        poisson: Option<f64>,
        /// Initial yield stress σ_Y (Pa) of von Mises (J2) plasticity with linear isotropic
        /// hardening ([`crate::solver::J2`]; 3D, forms classical, nonlocal and local; null:
        /// elastic). The elastic part then takes the Jaumann rate.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        yield_stress: Option<f64>,
        /// Plastic hardening modulus H = dσ_y/dε̄ᵖ (Pa; null: 0), with `yield_stress`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        hardening: Option<f64>,
    },
    /// Compressible neo-Hookean \[T eq 3.62–3.64\] in uniaxial strain (λ2 = λ3 = 1), with
    /// Young's modulus `modulus` and Poisson ratio `poisson`: P = μ(F − 1/F) + λ ln F / F, the
    /// small-strain (P-wave) modulus λ + 2μ; `total-lagrangian` only.
    NeoHookean {
        /// Poisson ratio ν in [−0.99, 0.5).
        poisson: f64,
    },
}

impl Default for SceneMaterial {
    fn default() -> Self {
        SceneMaterial::Linear {
            poisson: None,
            yield_stress: None,
            hardening: None,
        }
    }
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

/// A scene: a bar along x in 1D, 2D or 3D.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Name (free text).
    pub name: String,
    /// Dimension: 1 (default), 2 (plane strain) or 3.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub dim: usize,
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
    /// Number of particles along x (columns of the section in 2D and 3D).
    pub particles: usize,
    /// Particles across the bar, spacing Δx: [n_y] in 2D, [n_y, n_z] in 3D (none in 1D).
    /// The section is centred on the axis, unless one side of an axis is a symmetry plane
    /// and the other free: that plane is then at 0 (the mid-plane of the whole bar).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub section: Vec<usize>,
    /// The side faces, [lower, upper] for y (and z): `free` (default) or `symmetry`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sides: Vec<[Side; 2]>,
    /// A round bar (3D): only the lattice rows within the radius R of the axis are kept
    /// (y² + z² ≤ R²), R the distance from the axis to the section's free faces (n Δx/2 for a
    /// free section of n × n rows, n Δx for a quarter between two symmetry planes on the
    /// axis). Needs n_y = n_z and the same sides on y and z, not two planes on one axis.
    #[serde(default, skip_serializing_if = "is_false")]
    pub round: bool,
    /// The rate λ̇ (1/s) of a homogeneous transverse stretch λ(t) = 1 + ∫λ̇ dt about the axis,
    /// as a pulse: every symmetry plane at P moves to λ(t) P, and the end layers' transverse
    /// velocity follows (λ̇ Y, λ̇ Z). Needs a symmetry plane off the axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transverse_stretch_rate: Option<Pulse>,
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
    /// Reference positions of the probes, at most [`MAX_PROBES`], X in [origin, origin +
    /// length] (and Y, Z within the section): the axial displacement, velocity and stress
    /// there are recorded at every step ([`ProbeHistory`]; linear between the two particles
    /// around X of the lattice row nearest to (Y, Z)).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub probes: Vec<Probe>,
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
fn one() -> usize {
    1
}
fn is_one(d: &usize) -> bool {
    *d == 1
}
fn dt_default() -> f64 {
    0.2
}

/// Built-in scenes by name.
pub fn builtin(name: &str) -> Result<Scene> {
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
pub fn parse(file: &str, text: &str) -> Result<Scene> {
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
    /// Dimension.
    pub dim: usize,
    /// Particles (without the ghosts).
    pub particles: usize,
    /// Ghost particles of the symmetry planes.
    pub ghosts: usize,
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
    /// The times of the `round` bar's extent records (every step, and t = 0).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub extent_t: Vec<f64>,
    /// The bar's length then: the largest minus the smallest x of its particles, plus Δx (a
    /// particle's cell); with a symmetry plane at the left end (a wall), from the plane.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub extent_length: Vec<f64>,
    /// The radius of its first column (the particles at the left end): the bar's radius R
    /// plus the largest radial displacement of one of them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub extent_radius: Vec<f64>,
    /// The largest equivalent plastic strain ε̄ᵖ at the end (J2 plasticity; null: elastic).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_plastic_strain: Option<f64>,
    /// Every particle's ε̄ᵖ at the end (empty: elastic; not serialised).
    #[serde(skip)]
    pub plastic_strain: Vec<f64>,
    /// The probes' histories, in the order of the scene's `probes`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub probes: Vec<ProbeHistory>,
    /// History: (t, max |v|, kinetic energy).
    #[serde(skip)]
    pub history: Vec<(f64, f64, f64)>,
    /// The particles of the lattice row nearest to the axis, one per column (every particle
    /// in 1D): the bar's profile along x.
    #[serde(skip)]
    pub centre_row: Vec<usize>,
    /// The final axial stress σ_xx of every particle ([`Model::particle_stress`]; empty for
    /// a form without one), in lattice order (ghosts left out).
    #[serde(skip)]
    pub final_stress: Vec<f64>,
    /// Final positions, velocities and stresses of the particles (ghosts left out; the
    /// total-Lagrangian form's σ is its law's stress, [`Model::particle_stress`]).
    #[serde(skip)]
    pub final_state: Option<FinalState>,
}

/// What a probe recorded at reference position X, at the times [`SceneReport::probe_t`]: each
/// axial quantity linear between the two particles around X (exact on a particle).
#[derive(Clone, Debug, Serialize)]
pub struct ProbeHistory {
    /// X (m).
    pub reference_position: f64,
    /// The transverse coordinates (Y, Z) the probe named (empty: on the axis).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub across: Vec<f64>,
    /// Axial displacement u = x − X (m).
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
    /// The `end-pulse` solution's velocity at X ([`Scene::end_waves_at`]; empty for a
    /// scene without it).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub exact_velocity: Vec<f64>,
    /// The `end-pulse` solution's stress at X.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub exact_stress: Vec<f64>,
}

impl ProbeHistory {
    /// The probe's position as a label: `X`, or `X;Y(;Z)` for a point off the axis.
    pub fn label(&self) -> String {
        std::iter::once(self.reference_position)
            .chain(self.across.iter().copied())
            .map(crate::display::num)
            .collect::<Vec<_>>()
            .join(";")
    }
}

/// The particles and weights of a scene's probes: probe p reads (1 − w) q_a + w q_b of each
/// quantity q, (a, b, w) = `at[p]` (a, b: the particles of two neighbouring columns in one
/// lattice row).
struct ProbeSet {
    at: Vec<(usize, usize, f64)>,
    /// Whether the form has a particle stress.
    stress: bool,
    /// Whether it has a deformation gradient (total-Lagrangian).
    stretch: bool,
}

impl ProbeSet {
    fn new<const D: usize>(scene: &Scene, geo: &Geometry, model: &Model<D>) -> Self {
        let n = scene.particles;
        let dx = scene.length / (n - 1) as f64;
        let at = scene
            .probes
            .iter()
            .map(|p| {
                let f = ((p.x() - scene.origin) / dx).clamp(0.0, (n - 1) as f64);
                let i = (f.floor() as usize).min(n - 2);
                let row = geo.nearest_row(p.across());
                (
                    i * geo.per_column + row,
                    (i + 1) * geo.per_column + row,
                    f - i as f64,
                )
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

    /// Appends the current axial values of `run` to the histories `h`.
    fn record<const D: usize>(&self, run: &Run<D>, h: &mut [ProbeHistory]) {
        let z = &run.z;
        let m = &run.model;
        for (&(i, j, w), p) in self.at.iter().zip(h) {
            let mix = |a: f64, b: f64| (1.0 - w) * a + w * b;
            p.displacement
                .push(mix(z.x[i][0] - m.x_ref[i][0], z.x[j][0] - m.x_ref[j][0]));
            p.velocity.push(mix(z.v[i][0], z.v[j][0]));
            if self.stress {
                let s = |k: usize| m.particle_stress_of(z, k).map_or(0.0, |t| t[0][0]);
                let (a, b) = (s(i), if w > 0.0 { s(j) } else { 0.0 });
                p.stress.push(mix(a, b));
            }
            if self.stretch {
                let f = |k: usize| m.deformation_gradient_of(z, k).map_or(1.0, |f| f[0][0]);
                let (a, b) = (f(i), if w > 0.0 { f(j) } else { 1.0 });
                p.stretch.push(mix(a, b));
            }
        }
    }
}

/// The particles of a scene: the real ones in lattice order (x outermost, then y, then z),
/// then the ghosts of its symmetry planes.
struct Geometry {
    /// Reference positions (x, y, z; the coordinates beyond the dimension 0).
    x: Vec<[f64; 3]>,
    /// Number of real particles.
    real: usize,
    /// Particles per column (n_y n_z; 1 in 1D).
    per_column: usize,
    /// The transverse coordinates of the lattice rows, per transverse axis.
    across: Vec<Vec<f64>>,
    /// A round section's kept rows (their transverse coordinates; None: every lattice row).
    rows: Option<Vec<Vec<f64>>>,
    /// The ghosts, particle `real + g`: (source, S, b0) of [`Mirror`]; a transverse stretch λ
    /// moves every plane P to λ P, so b = λ b0.
    ghosts: Vec<(usize, [f64; 3], [f64; 3])>,
}

impl Geometry {
    /// The column (x index) of particle `i` (a ghost's is its source's).
    fn column(&self, i: usize) -> usize {
        let src = if i < self.real {
            i
        } else {
            self.ghosts[i - self.real].0
        };
        src / self.per_column
    }

    /// The lattice row nearest to the transverse point `p` (missing coordinates: 0).
    fn nearest_row(&self, p: &[f64]) -> usize {
        if let Some(rows) = &self.rows {
            let d2 = |r: &Vec<f64>| {
                r.iter()
                    .enumerate()
                    .map(|(a, y)| (y - p.get(a).copied().unwrap_or(0.0)).powi(2))
                    .sum::<f64>()
            };
            return (0..rows.len())
                .min_by(|&u, &w| d2(&rows[u]).total_cmp(&d2(&rows[w])))
                .unwrap_or(0);
        }
        let mut row = 0;
        for (a, coords) in self.across.iter().enumerate() {
            let target = p.get(a).copied().unwrap_or(0.0);
            let j = coords
                .iter()
                .enumerate()
                .min_by(|(_, u), (_, w)| (*u - target).abs().total_cmp(&(*w - target).abs()))
                .map_or(0, |(j, _)| j);
            row = row * coords.len() + j;
        }
        row
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
    /// scene's analytic stress ([`Scene::exact_profile`]); null without an analytic solution
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

impl Scene {
    /// Validates every field through the same checks as the questions' fields, then the
    /// resources (memory, particle-steps) against [`Scene::budget`]. Returns (form, kernel,
    /// shape).
    pub fn validate(&self) -> Result<(FormKind, &'static dyn kernel::Kernel, ShapeFamily)> {
        let form = FormKind::by_name(&self.form)?;
        let k = kernel::by_name(&self.kernel)?;
        let shape = match &self.shape {
            Some(s) => ShapeFamily::by_name(s)?,
            None => form.default_shape(),
        };
        form.check_shape(shape)?;
        crate::error::check_range("dim", self.dim as f64, 1.0, 3.0, true, true)?;
        crate::error::check_range("particles", self.particles as f64, 4.0, 1e7, true, true)?;
        self.check_section(form)?;
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
        for p in &self.probes {
            crate::error::check_range(
                "probes",
                p.x(),
                self.origin,
                self.origin + self.length,
                true,
                true,
            )?;
            if let Probe::Point(q) = p
                && q.len() != self.dim
            {
                return Err(Error::OutOfRange {
                    field: "probes",
                    value: q.len() as f64,
                    range: format!(
                        "a probe point has dim = {} coordinates [X{}]",
                        self.dim,
                        [", Y", ", Y, Z"][..self.dim - 1].concat()
                    )
                    .into(),
                });
            }
            for (a, &y) in p.across().iter().enumerate() {
                let (lo, hi) = self.section_bounds(a, dx);
                crate::error::check_range("probes", y, lo, hi, true, true)?;
            }
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
        let n = self.particle_estimate(k.zeta() * self.h_over_dx);
        let neighbours = (2.0 * k.zeta() * self.h_over_dx + 1.0).powi(self.dim as i32);
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
            // bar crossings (Scene::end_waves_at), each a pulse evaluation, counted as a
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
                "the scene ({} particles, ghosts included, ~{neighbours:.0} neighbours each)",
                fmt_count(n)
            ),
            n * (neighbours * 32.0 * 3.0 + 480.0)
                + 8.0 * steps * (3.0 + 7.0 * self.probes.len() as f64),
        )?;
        Ok((form, k, shape))
    }

    /// The model's material: `linear` is the 1D bar of modulus C in 1D, the hypo-elastic
    /// solid (Truesdell rate) of E = `modulus` and ν = `poisson` in 2D and 3D; `neo-hookean`
    /// has λ = Eν/((1 + ν)(1 − 2ν)), μ = E/(2(1 + ν)).
    pub fn material_model(&self) -> Result<Material> {
        let lame = |e: f64, nu: f64| {
            (
                e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
                e / (2.0 * (1.0 + nu)),
            )
        };
        Ok(match self.material {
            SceneMaterial::Linear { poisson: None, .. } if self.dim == 1 => {
                Material::bar(self.modulus)
            }
            SceneMaterial::Linear {
                poisson: Some(_), ..
            } if self.dim == 1 => {
                return Err(Error::Incompatible(
                    field("material.poisson")
                        + " applies with "
                        + field("dim")
                        + " 2 or 3 (the 1D law has the one modulus C)",
                ));
            }
            SceneMaterial::Linear { poisson: None, .. } => {
                return Err(Error::Incompatible(
                    field("dim")
                        + format!(" {} needs ", self.dim)
                        + field("material.poisson")
                        + " (the linear solid of Young's modulus E = "
                        + field("modulus")
                        + " and Poisson ratio ν)",
                ));
            }
            SceneMaterial::Linear {
                poisson: Some(nu),
                yield_stress,
                ..
            } => {
                crate::error::check_range("material.poisson", nu, -0.99, 0.5, true, false)?;
                let (lambda, shear) = lame(self.modulus, nu);
                // a plastic solid takes the Jaumann rate (corotational: large plastic flow
                // rotates the stress, it does not stretch it)
                let rate = if yield_stress.is_some() {
                    crate::forms::ObjectiveRate::Jaumann
                } else {
                    crate::forms::ObjectiveRate::Truesdell
                };
                Material::Elastic {
                    lambda,
                    shear,
                    rate,
                }
            }
            SceneMaterial::NeoHookean { poisson } => {
                crate::error::check_range("material.poisson", poisson, -0.99, 0.5, true, false)?;
                if self.initial_stress != 0.0 {
                    return Err(Error::OutOfRange {
                        field: "initial_stress",
                        value: self.initial_stress,
                        range: "must be 0 with the neo-hookean material (its reference state is unstressed)".into(),
                    });
                }
                let (lambda, shear) = lame(self.modulus, poisson);
                Material::NeoHookean { lambda, shear }
            }
        })
    }

    /// The J2 plasticity of the `linear` material (`material.yield_stress`,
    /// `material.hardening`; None: elastic), checked for form `form`.
    pub fn plasticity(&self, form: FormKind) -> Result<Option<crate::solver::J2>> {
        let (yield_stress, hardening) = match self.material {
            SceneMaterial::Linear {
                yield_stress,
                hardening,
                ..
            } => (yield_stress, hardening),
            SceneMaterial::NeoHookean { .. } => (None, None),
        };
        let Some(sy) = yield_stress else {
            if hardening.is_some() {
                return Err(Error::Incompatible(
                    field("material.hardening") + " applies with " + field("material.yield_stress"),
                ));
            }
            return Ok(None);
        };
        if self.dim != 3
            || !matches!(
                form,
                FormKind::Classical | FormKind::Nonlocal | FormKind::Local
            )
        {
            return Err(Error::Incompatible(
                field("material.yield_stress")
                    + " (J2 plasticity) applies with "
                    + field("dim")
                    + " 3 and the forms classical, nonlocal and local, not "
                    + format!("dim {} and {}", self.dim, form.name()),
            ));
        }
        if self.integrator()?.memory()[2] {
            return Err(Error::Incompatible(
                field("material.yield_stress")
                    + " is returned to the yield surface after each step: it needs an "
                    + field("integrator")
                    + " that carries no stress from one step to the next (not pec or verlet-euler)",
            ));
        }
        crate::error::check_range("material.yield_stress", sy, 0.0, SCALE_RANGE.1, false, true)?;
        let h = hardening.unwrap_or(0.0);
        crate::error::check_range("material.hardening", h, 0.0, SCALE_RANGE.1, true, true)?;
        Ok(Some(crate::solver::J2 {
            yield_stress: sy,
            hardening: h,
        }))
    }

    /// Checks `section`, `sides`, `transverse_stretch_rate` and what depends on the dimension
    /// (`initial_stress`, the analytic solution) for form `form`.
    fn check_section(&self, form: FormKind) -> Result<()> {
        let across = self.dim - 1;
        if self.section.len() != across {
            return Err(Error::OutOfRange {
                field: "section",
                value: self.section.len() as f64,
                range: format!(
                    "give dim − 1 = {across} particle counts ([n_y] in 2D, [n_y, n_z] in 3D, none in 1D)"
                )
                .into(),
            });
        }
        for &m in &self.section {
            crate::error::check_range("section", m as f64, 1.0, 1e4, true, true)?;
        }
        let total = self.particles as f64 * self.section.iter().map(|&m| m as f64).product::<f64>();
        crate::error::check_range("particles × section", total, 4.0, 1e7, true, true)?;
        if !self.sides.is_empty() && self.sides.len() != across {
            return Err(Error::OutOfRange {
                field: "sides",
                value: self.sides.len() as f64,
                range: format!(
                    "give dim − 1 = {across} pairs [lower, upper] (y, then z), or none (free)"
                )
                .into(),
            });
        }
        let symmetric = self.sides.iter().flatten().any(|&s| s == Side::Symmetry);
        if symmetric && !form.in_every_dimension() {
            return Err(Error::Incompatible(
                field("sides")
                    + format!(
                        " symmetry is not available for {} (its stress points have no image)",
                        form.name()
                    ),
            ));
        }
        if self.round {
            let ok = self.dim == 3
                && self.section[0] == self.section[1]
                && self.sides_of(0) == self.sides_of(1)
                && self.sides_of(0) != [Side::Symmetry, Side::Symmetry];
            if !ok {
                return Err(Error::Incompatible(
                    field("round")
                        + " (a round bar) needs "
                        + field("dim")
                        + " 3, "
                        + field("section")
                        + " [n, n] and the same "
                        + field("sides")
                        + " on y and z, not a symmetry plane on both sides of an axis",
                ));
            }
        }
        if self.dim > 1 && self.initial_stress != 0.0 {
            return Err(Error::Incompatible(
                field("initial_stress")
                    + " applies with "
                    + field("dim")
                    + " 1 (a 2D or 3D bar starts unstressed)",
            ));
        }
        if self.dim > 1
            && self.analytic.is_some()
            && !self.sides.iter().flatten().all(|&s| s == Side::Symmetry)
        {
            return Err(Error::Incompatible(
                field("analytic")
                    + " (a 1D solution) needs symmetry planes on every side in 2D and 3D: give "
                    + field("sides")
                    + " symmetry (the bar in uniaxial strain)",
            ));
        }
        if let Some(p) = &self.transverse_stretch_rate {
            let dx = self.length / (self.particles - 1) as f64;
            let off_axis =
                (0..across).any(|a| self.planes(a, dx).iter().flatten().any(|&pl| pl != 0.0));
            if !off_axis {
                return Err(Error::Incompatible(
                    field("transverse_stretch_rate")
                        + " moves the symmetry planes off the axis: give "
                        + field("sides")
                        + " a symmetry plane that is not the mid-plane",
                ));
            }
            let c = (self.tangent_modulus() / self.rho0).sqrt();
            p.check("transverse_stretch_rate", 100.0 * c / self.length.max(dx))?;
        }
        Ok(())
    }

    /// The side conditions [lower, upper] of transverse axis `a` (0: y, 1: z).
    fn sides_of(&self, a: usize) -> [Side; 2] {
        self.sides.get(a).copied().unwrap_or_default()
    }

    /// The coordinates of the lattice rows along transverse axis `a` (spacing `dx`).
    fn row_coordinates(&self, a: usize, dx: f64) -> Vec<f64> {
        let m = self.section[a];
        let first = match self.sides_of(a) {
            [Side::Symmetry, Side::Free] => 0.5 * dx,
            [Side::Free, Side::Symmetry] => -(m as f64 - 0.5) * dx,
            _ => -0.5 * (m - 1) as f64 * dx,
        };
        (0..m).map(|j| first + j as f64 * dx).collect()
    }

    /// The positions of the symmetry planes [lower, upper] of transverse axis `a`, half a
    /// spacing beyond the outermost rows (None: a free side).
    fn planes(&self, a: usize, dx: f64) -> [Option<f64>; 2] {
        let y = self.row_coordinates(a, dx);
        let (lo, hi) = (y[0] - 0.5 * dx, y[y.len() - 1] + 0.5 * dx);
        let [sl, su] = self.sides_of(a);
        [
            (sl == Side::Symmetry).then_some(lo),
            (su == Side::Symmetry).then_some(hi),
        ]
    }

    /// The radius of a `round` bar: the distance from the axis to its free faces.
    fn radius(&self, dx: f64) -> f64 {
        let m = self.section.first().copied().unwrap_or(1) as f64;
        if self.sides_of(0).contains(&Side::Symmetry) {
            m * dx
        } else {
            0.5 * m * dx
        }
    }

    /// The transverse coordinates of the rows the section keeps, in lattice order (every row
    /// of the rectangular section; of a `round` one, those within its radius).
    fn kept_rows(&self, dx: f64) -> Vec<Vec<f64>> {
        let across: Vec<Vec<f64>> = (0..self.dim - 1)
            .map(|a| self.row_coordinates(a, dx))
            .collect();
        let total: usize = across.iter().map(Vec::len).product();
        let r2 = self.radius(dx).powi(2) * (1.0 + 1e-12);
        (0..total)
            .map(|r| {
                let mut p = vec![0.0; across.len()];
                let mut rest = r;
                for a in (0..across.len()).rev() {
                    let m = across[a].len();
                    p[a] = across[a][rest % m];
                    rest /= m;
                }
                p
            })
            .filter(|p| !self.round || p.iter().map(|y| y * y).sum::<f64>() <= r2)
            .collect()
    }

    /// The range of transverse coordinate `a` a probe may name: the section and half a
    /// spacing beyond.
    fn section_bounds(&self, a: usize, dx: f64) -> (f64, f64) {
        let y = self.row_coordinates(a, dx);
        (y[0] - 0.5 * dx, y[y.len() - 1] + 0.5 * dx)
    }

    /// The depth of the ghost layer beyond a symmetry plane, for support radius `support`
    /// and spacing `dx`. A ghost at depth d is at least d + Δx/2 from every particle of the
    /// bar. A form whose rates are one pass over the pairs (an Eulerian form with plain
    /// kernel gradients, `sph` shapes) needs the ghosts within R of the bar: depth R + Δx/2,
    /// which leaves a margin of Δx for the particles' motion. A form that computes a quantity
    /// from its neighbours and then uses the neighbours' (the total-Lagrangian F, a corrected
    /// gradient) needs each such ghost's own neighbourhood whole: depth 2R.
    fn ghost_depth(&self, support: f64, dx: f64) -> f64 {
        let one_pass = FormKind::by_name(&self.form).is_ok_and(|f| {
            let shape = match &self.shape {
                Some(s) => ShapeFamily::by_name(s).ok(),
                None => Some(f.default_shape()),
            };
            !f.is_total_lagrangian() && shape == Some(ShapeFamily::Sph)
        });
        if one_pass {
            support + 0.5 * dx
        } else {
            2.0 * support
        }
    }

    /// The number of particles, ghosts included (an upper estimate for the budget), with a
    /// support radius of `support_dx` spacings.
    fn particle_estimate(&self, support_dx: f64) -> f64 {
        let rows = self.ghost_depth(support_dx, 1.0).ceil();
        let ends = [&self.left, &self.right]
            .into_iter()
            .flatten()
            .filter(|e| e.symmetry)
            .count();
        (0..self.dim.saturating_sub(1)).fold(self.particles as f64 + ends as f64 * rows, |n, a| {
            let sym = self
                .sides_of(a)
                .iter()
                .filter(|&&s| s == Side::Symmetry)
                .count();
            // both planes: the images repeat with period 2 n_a beyond each plane
            n * (self.section.get(a).copied().unwrap_or(1) as f64 + sym as f64 * rows)
        })
    }

    /// The scene's particles ([`Geometry`]) with spacing `dx` and support radius `support`.
    fn geometry(&self, dx: f64, support: f64) -> Geometry {
        let across: Vec<Vec<f64>> = (0..self.dim - 1)
            .map(|a| self.row_coordinates(a, dx))
            .collect();
        let rows = self.kept_rows(dx);
        let per_column = rows.len();
        let mut x = Vec::with_capacity(self.particles * per_column);
        for i in 0..self.particles {
            let xi = self.origin + i as f64 * dx;
            for row in &rows {
                let mut p = [xi, 0.0, 0.0];
                p[1..=row.len()].copy_from_slice(row);
                x.push(p);
            }
        }
        let real = x.len();
        // images: (position, source, S, b0, the plane it was last reflected across)
        type Image = ([f64; 3], usize, [f64; 3], [f64; 3], Option<usize>);
        let mut images: Vec<Image> = x
            .iter()
            .enumerate()
            .map(|(i, &p)| (p, i, [1.0; 3], [0.0; 3], None))
            .collect();
        let depth = self.ghost_depth(support, dx);
        // the axes with planes: x (the ends' planes), then y and z (the sides'); coordinate
        // index, planes [lower, upper], the body's extent [lo, hi] along it
        let ends = [&self.left, &self.right].map(|e| e.as_ref().is_some_and(|e| e.symmetry));
        let (x0, x1) = (self.origin - 0.5 * dx, self.origin + self.length + 0.5 * dx);
        let mut axes: Vec<(usize, [Option<f64>; 2], f64, f64)> =
            vec![(0, [ends[0].then_some(x0), ends[1].then_some(x1)], x0, x1)];
        for a in 0..across.len() {
            axes.push((
                a + 1,
                self.planes(a, dx),
                across[a][0] - 0.5 * dx,
                across[a][across[a].len() - 1] + 0.5 * dx,
            ));
        }
        for (ax, planes, lo, hi) in axes {
            // reflect every image across this axis' planes until the images lie beyond the
            // ghost depth (with two planes the reflections alternate outwards)
            let mut frontier: Vec<usize> = (0..images.len()).collect();
            while !frontier.is_empty() {
                let mut next = Vec::new();
                for &e in &frontier {
                    for (side, plane) in planes.iter().enumerate() {
                        let Some(pl) = *plane else { continue };
                        if images[e].4 == Some(side) {
                            continue;
                        }
                        let (pos, src, sign, b, _) = images[e];
                        let mut q = pos;
                        q[ax] = 2.0 * pl - pos[ax];
                        let outside = (lo - q[ax]).max(q[ax] - hi);
                        if outside >= depth {
                            continue;
                        }
                        let mut sign2 = sign;
                        let mut b2 = b;
                        sign2[ax] = -sign[ax];
                        b2[ax] = 2.0 * pl - b[ax];
                        images.push((q, src, sign2, b2, Some(side)));
                        next.push(images.len() - 1);
                    }
                }
                frontier = next;
            }
            // later axes reflect these images again: clear the last-plane marks
            for im in &mut images {
                im.4 = None;
            }
        }
        let ghosts = images[real..]
            .iter()
            .map(|&(_, src, sign, b, _)| (src, sign, b))
            .collect();
        x.extend(images[real..].iter().map(|im| im.0));
        Geometry {
            x,
            real,
            per_column,
            across,
            rows: self.round.then_some(rows),
            ghosts,
        }
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
        if e.symmetry
            && (e.layers > 0
                || e.velocity.is_some()
                || e.velocity_pulse.is_some()
                || e.traction.is_some())
        {
            return Err(Error::Incompatible(
                field(given("symmetry"))
                    + " makes the end a mirror plane: give no "
                    + field(given("layers"))
                    + ", "
                    + field(given("velocity"))
                    + ", "
                    + field(given("velocity_pulse"))
                    + " or "
                    + field(given("traction")),
            ));
        }
        if e.symmetry && self.analytic.is_some() {
            return Err(Error::Incompatible(
                field(given("symmetry"))
                    + " has no analytic solution: give no "
                    + field("analytic"),
            ));
        }
        if e.symmetry && !FormKind::by_name(&self.form).is_ok_and(|f| f.in_every_dimension()) {
            return Err(Error::Incompatible(
                field(given("symmetry"))
                    + format!(
                        " is not available for {} (its stress points have no image)",
                        self.form
                    ),
            ));
        }
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
        match self.dim {
            1 => self.run_in::<1>(progress),
            2 => self.run_in::<2>(progress),
            3 => self.run_in::<3>(progress),
            d => Err(Error::OutOfRange {
                field: "dim",
                value: d as f64,
                range: "must be 1, 2 or 3".into(),
            }),
        }
    }

    fn run_in<const D: usize>(&self, progress: impl Progress) -> Result<SceneReport>
    where
        FinalState: From<State<f64, D>>,
    {
        let (form, k, shape) = self.validate()?;
        let n = self.particles;
        let dx = self.length / (n - 1) as f64;
        let c = (self.tangent_modulus() / self.rho0).sqrt();
        let h = self.h_over_dx * dx;
        let p = ModelParams {
            form,
            shape,
            kp: KernelParams { kernel: k, h },
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
            hourglass: None,
        };
        let geo = self.geometry(dx, k.zeta() * h);
        let (real, total) = (geo.real, geo.x.len());
        let x_ref: Vec<[f64; D]> = geo
            .x
            .iter()
            .map(|q| std::array::from_fn(|a| q[a]))
            .collect();
        let vol = dx.powi(D as i32);
        let mut model = Model::new(
            p,
            x_ref.clone(),
            vec![vol; total],
            self.rho0,
            self.initial_stress,
            None,
        )?;
        if self.classical_layers != [0, 0] {
            let [l, r] = self.classical_layers;
            model.set_classical_layer(
                (0..total)
                    .map(|i| {
                        let col = geo.column(i);
                        col < l || col >= n - r
                    })
                    .collect(),
            )?;
        }
        let mut z = model.rest_state(self.rho0);
        if let InitialVelocity::Point { index, .. } = self.initial_velocity
            && index >= real
        {
            return Err(Error::OutOfRange {
                field: "initial_velocity.index",
                value: index as f64,
                range: format!("must be < the number of particles, {real}").into(),
            });
        }
        let x_axial: Vec<f64> = x_ref[..real].iter().map(|q| q[0]).collect();
        let v_init = self.initial_velocities(&x_axial);
        for (v, &vi) in z.v.iter_mut().zip(&v_init) {
            v[0] = vi;
        }
        let stretch = self.transverse_stretch_rate.as_ref();
        let lam_rate = |t: f64| stretch.map_or(0.0, |p| p.at(k, t));
        // a prescribed particle: its axial value, and (λ̇ Y, λ̇ Z) across
        let full = |axial: Vec<Option<f64>>, rate: f64| -> Vec<Option<[f64; D]>> {
            let mut out: Vec<Option<[f64; D]>> = axial
                .into_iter()
                .enumerate()
                .map(|(i, v)| {
                    v.map(|v| std::array::from_fn(|a| if a == 0 { v } else { rate * x_ref[i][a] }))
                })
                .collect();
            out.resize(total, None);
            out
        };
        let prescribed = self.prescribed_at(&v_init, 0.0, k, geo.per_column);
        let free: Vec<bool> = prescribed.iter().map(|p| p.is_none()).collect();
        let pv = full(prescribed.clone(), lam_rate(0.0));
        // the traction ends' load pattern: −b_K on the particles of the loaded half
        let tractions =
            [self.left.as_ref(), self.right.as_ref()].map(|e| e.and_then(|e| e.traction.as_ref()));
        let unit = if tractions.iter().any(Option::is_some) {
            model.unit_stress_force(0)?
        } else {
            Vec::new()
        };
        let mid = self.origin + 0.5 * self.length;
        let pulsed = stretch.is_some()
            || [&self.left, &self.right]
                .into_iter()
                .flatten()
                .any(|e| e.velocity_pulse.is_some());
        let mut run = Run::with_prescribed(model, z, &pv)?;
        run.set_mirror(
            geo.ghosts
                .iter()
                .enumerate()
                .map(|(g, &(source, sign, b0))| Mirror {
                    ghost: real + g,
                    source,
                    sign: std::array::from_fn(|a| sign[a]),
                    offset: std::array::from_fn(|a| b0[a]),
                    offset_rate: [0.0; D],
                })
                .collect(),
        )?;
        if let Some(j2) = self.plasticity(form)? {
            run.set_plasticity(j2)?;
        }
        let integ = self.integrator()?;
        run.set_integrator(integ);
        let dt = self.dt * dx / c;
        let steps = (self.t_end / dt).ceil() as usize;
        let dt = self.t_end / steps as f64;
        let mass = self.rho0 * vol;
        let mut history = Vec::with_capacity(steps + 1);
        let mut vmax: f64 = 0.0;
        let runaway = RUNAWAY_FACTOR
            * (c + v_init.iter().fold(0.0f64, |m, v| m.max(v.abs()))
                + prescribed
                    .iter()
                    .flatten()
                    .fold(0.0f64, |m, v| m.max(v.abs()))
                + self.pulse_speed_bound(c));
        let probes = ProbeSet::new(self, &geo, &run.model);
        let mut probe_t = Vec::with_capacity(if probes.is_empty() { 0 } else { steps + 1 });
        let mut probe_h: Vec<ProbeHistory> = self
            .probes
            .iter()
            .map(|p| ProbeHistory {
                reference_position: p.x(),
                across: p.across().to_vec(),
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
        let speed = |v: &[f64; D]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
        let (mut extent_t, mut extent_length, mut extent_radius) =
            (Vec::new(), Vec::new(), Vec::new());
        let wall = self.left.as_ref().is_some_and(|e| e.symmetry);
        let mut extent = |run: &Run<D>| {
            if !self.round {
                return;
            }
            let z = &run.z;
            let (lo, hi) = z.x[..real]
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| {
                    (l.min(q[0]), h.max(q[0]))
                });
            let radial = |q: &[f64; D]| q[1..].iter().map(|y| y * y).sum::<f64>().sqrt();
            let grow = z.x[..geo.per_column]
                .iter()
                .zip(&x_ref)
                .map(|(q, q0)| radial(q) - radial(q0))
                .fold(f64::NEG_INFINITY, f64::max);
            extent_t.push(run.t);
            // from the wall (a left symmetry plane, half a spacing before the first column)
            // or the lowest particle's cell face, to the highest's
            extent_length.push(if wall {
                hi - self.origin + dx
            } else {
                hi - lo + dx
            });
            extent_radius.push(self.radius(dx) + grow);
        };
        extent(&run);
        let start = std::time::Instant::now();
        for s in 0..steps {
            // time-dependent ends and planes, held at the step's midpoint
            let t_mid = run.t + 0.5 * dt;
            if !unit.is_empty() {
                let [sl, sr] = tractions.map(|t| t.map_or(0.0, |p| p.at(k, t_mid)));
                let load = unit
                    .iter()
                    .zip(&x_ref)
                    .map(|(b, xi)| {
                        let s = if xi[0] < mid { sl } else { sr };
                        std::array::from_fn(|a| -s * b[a])
                    })
                    .collect();
                run.set_load(load)?;
            }
            let rate = lam_rate(t_mid);
            if stretch.is_some() {
                for (m, g) in run.mirror_mut().iter_mut().zip(&geo.ghosts) {
                    m.offset_rate = std::array::from_fn(|a| rate * g.2[a]);
                }
            }
            if pulsed {
                let now = full(self.prescribed_at(&v_init, t_mid, k, geo.per_column), rate);
                for (v, p) in run.z.v.iter_mut().zip(now) {
                    if let Some(p) = p {
                        *v = p;
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
            let vm = run.z.v[..real].iter().map(speed).fold(0.0f64, f64::max);
            if vm > runaway {
                return Err(Error::Diverged {
                    step: s + 1,
                    t: run.t,
                    what: "max |v| above 1000 × (c + the largest initial or prescribed speed)",
                    max_amplitude: vm,
                });
            }
            vmax = vmax.max(vm);
            let ke = 0.5
                * mass
                * run.z.v[..real]
                    .iter()
                    .map(|v| v.iter().map(|c| c * c).sum::<f64>())
                    .sum::<f64>();
            history.push((run.t, vm, ke));
            if !probes.is_empty() {
                probe_t.push(run.t);
                probes.record(&run, &mut probe_h);
            }
            extent(&run);
            if s % 256 == 0 {
                progress.advance(run.t / self.t_end);
                if progress.cancelled() {
                    return Err(Error::Cancelled);
                }
            }
        }
        let runtime_s = start.elapsed().as_secs_f64();
        // the analytic solution per column, at every real particle
        let exact = self.exact_profile(run.t).map(|(v, s)| {
            let at = |f: &[f64]| (0..real).map(|i| f[geo.column(i)]).collect::<Vec<_>>();
            (at(&v), at(&s))
        });
        let error = exact.as_ref().map(|(exact, _)| {
            let (mut num, mut den, mut cnt) = (0.0, 0.0, 0usize);
            let mut scale: f64 = 0.0;
            for i in (0..real).filter(|&i| free[i]) {
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
        let plastic_strain: Vec<f64> = run.plastic_strain.iter().take(real).copied().collect();
        let max_plastic_strain = (!plastic_strain.is_empty())
            .then(|| plastic_strain.iter().fold(0.0f64, |m, &e| m.max(e)));
        let mut tensors = run.model.particle_stress(&run.z);
        tensors.truncate(real);
        let final_stress: Vec<f64> = tensors.iter().map(|t| t[0][0]).collect();
        let stress = Self::stress_summary(&final_stress, exact.as_ref().map(|e| &e.1[..]), &free);
        let mut z = run.z;
        for f in [&mut z.x, &mut z.v] {
            f.truncate(real);
        }
        z.rho.truncate(real);
        z.sigma.truncate(real);
        z.tau.truncate(real);
        if form.is_total_lagrangian() {
            // the law's stress at each particle's F, for the snapshot (the form has no σ state)
            z.sigma = tensors;
        }
        Ok(SceneReport {
            name: self.name.clone(),
            form: form.name(),
            integrator: integ.name(),
            dim: D,
            particles: real,
            ghosts: total - real,
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
            extent_t,
            extent_length,
            extent_radius,
            max_plastic_strain,
            plastic_strain,
            probes: probe_h,
            history,
            centre_row: (0..n)
                .map(|i| i * geo.per_column + geo.nearest_row(&[]))
                .collect(),
            final_stress,
            final_state: Some(z.into()),
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

    /// The prescribed axial velocity of every particle at time `t` (None: free), from the end
    /// layers (their constant velocity or pulse, with the scene's kernel `k`; a layer is
    /// `per_column` particles) and the initial velocities `v`.
    fn prescribed_at(
        &self,
        v: &[f64],
        t: f64,
        k: &dyn kernel::Kernel,
        per_column: usize,
    ) -> Vec<Option<f64>> {
        let n = v.len();
        let mut prescribed = vec![None; n];
        let value = |e: &EndLayer, vi: f64| match (&e.velocity_pulse, e.velocity) {
            (Some(p), _) => p.at(k, t),
            (None, Some(v)) => v,
            (None, None) => vi,
        };
        if let Some(l) = &self.left {
            for (i, p) in prescribed
                .iter_mut()
                .enumerate()
                .take((l.layers * per_column).min(n))
            {
                *p = Some(value(l, v[i]));
            }
        }
        if let Some(r) = &self.right {
            let first = n.saturating_sub(r.layers * per_column);
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
    /// ([`Scene::reference_positions`]): (velocity, stress), None without `analytic`. The
    /// velocity is the one the error norm of [`Scene::run`] uses. The stress follows from it
    /// for sphstab's 1D law σ̇ = (C + σ) ∂v/∂x (\[B00\] eq 72):
    /// - `uniform-strain` (v = g X): x = X(1 + g t), ∂v/∂x = g/(1 + g t), so C + σ =
    ///   (C + σ0)(1 + g t), **σ = σ0 + (C + σ0) g t** (0 for an initial velocity that is not
    ///   `linear`);
    /// - `wall-impact` (linear, small strain, c = √(C/ρ0)): across a front moving right σ
    ///   jumps by −ρ0 c \[v\], so σ = σ0 + ρ0 c (v_0 − v) behind the wall's front;
    /// - `end-pulse`: [`Scene::end_waves_at`] at every particle.
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

    /// The [`StressSummary`] of the final axial stress `s` (one per particle) against the
    /// analytic one `exact` (`free`: the particles whose velocity is not prescribed); None for
    /// a form without a stress.
    fn stress_summary(s: &[f64], exact: Option<&[f64]>, free: &[bool]) -> Option<StressSummary> {
        if s.is_empty() {
            return None;
        }
        let error_max = exact.and_then(|exact| {
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
