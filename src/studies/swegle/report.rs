//! The Swegle report: the measured and predicted growth rates, the history and the final state.

use crate::solver::diagnostics::GrowthFit;
pub use crate::solver::output::FinalState;
use crate::solver::run::BoundaryDensity;
use serde::Serialize;

/// The columns of a Swegle run's history ([`SwegleReport::history_full`], `history.csv`): time,
/// the centre particle's |v|, max and RMS |v| of the free particles, kinetic energy (the test's
/// units).
pub const HISTORY_COLUMNS: [&str; 5] = [
    "t",
    "centre_abs_v",
    "max_abs_v_free",
    "rms_v_free",
    "kinetic_energy",
];

/// Result of a Swegle run: rates in c/Δx, the time step in Δx/c; what the run measures in the
/// test's own units (Δx = 0.1, c = √(K/ρ0) ≈ 0.495: `max_velocity_end`, the `fit`'s rate (1/time)
/// and window, `history`, `diverged.t`) and the keys named `_physical`, which convert them.
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
    /// How the box prediction was obtained: `iterative-operator` (the fastest mode of the exact
    /// operator of the finite particle set, by thick-restart Arnoldi, to 1e−8 in ω²),
    /// `dense-operator` (every eigenvalue of the same operator, assembled: when the iterative
    /// search finds no growing mode in a box of up to
    /// [`MAX_DENSE_BOX_DOFS`](super::MAX_DENSE_BOX_DOFS) free degrees of freedom), or
    /// `standing-modes` (the infinite lattice's ω² at the wave vectors the box admits: with
    /// δ-SPH, where the operator is not the undamped one, and when a larger box shows no growing
    /// mode: its fastest modes are then its zero-energy modes at ω² ≈ 0, which the iterative
    /// method cannot resolve).
    pub box_method: &'static str,
    /// Infinite-lattice prediction (c/Δx).
    pub predicted_growth_rate_infinite: f64,
    /// measured / box.
    pub ratio_box: Option<f64>,
    /// measured / infinite.
    pub ratio_infinite: Option<f64>,
    /// The fit (in the test's units: rate per unit time, window in time).
    pub fit: Option<GrowthFit>,
    /// max |v| of the free particles at the end (test units).
    pub max_velocity_end: f64,
    /// max |v| ever exceeded 2× the kick.
    pub grew: bool,
    /// Time step Δt in Δx/c (`--dt`).
    pub dt: f64,
    /// Time step in the test's units.
    pub dt_physical: f64,
    /// The particle spacing Δx in the test's units.
    pub dx_physical: f64,
    /// The sound speed c = √(K/ρ0) in the test's units.
    pub sound_speed_physical: f64,
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
    /// History (t, max |v|) in the test's units, at most ~400 samples.
    pub history: Vec<(f64, f64)>,
    /// Full history every step: t, centre |v|, max |v| and RMS |v| over the free particles,
    /// kinetic energy of all particles.
    #[serde(skip)]
    pub history_full: Vec<[f64; 5]>,
    /// Final particle state.
    #[serde(skip)]
    pub final_state: Option<FinalState>,
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
