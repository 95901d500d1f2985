//! What every question shares, in every dimension: the configuration line every report starts
//! with, the linearised artificial viscosity and δ-SPH density diffusion, and the integrator's
//! part of a `timestep` report. (The common parameters are validated by [`crate::params`].)

use crate::error::{Error, Result, field};
use crate::forms::{ArtificialViscosity, DensityDiffusion, DiffusionForm, FormKind};
use crate::kernel::Kernel;
use crate::shape::ShapeFamily;
use serde::Serialize;

/// The configuration every report starts with: form, kernel, shape family, h and R (SPEC §1:
/// every output prints both) and σ̄.
#[derive(Clone, Debug, Serialize)]
pub struct Setup {
    /// Form name.
    pub form: &'static str,
    /// Kernel name.
    pub kernel: &'static str,
    /// Shape family name.
    pub shape: &'static str,
    /// h/Δx.
    pub h_over_dx: f64,
    /// R/Δx (Belytschko's D_mx).
    pub support_over_dx: f64,
    /// σ̄.
    pub stress: f64,
}

impl Setup {
    /// The setup of a question.
    pub fn new(
        form: FormKind,
        kernel: &'static dyn Kernel,
        shape: ShapeFamily,
        h_over_dx: f64,
        stress: f64,
    ) -> Self {
        Self {
            form: form.name(),
            kernel: kernel.name(),
            shape: shape.name(),
            h_over_dx,
            support_over_dx: kernel.zeta() * h_over_dx,
            stress,
        }
    }
}

impl std::fmt::Display for Setup {
    /// One line: form / kernel / shape, h and R in Δx, σ̄ (saying it is σ/C).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} / {} / {}  h = {:.4}Δx (R = {:.4}Δx), σ̄ = σ/C = {}",
            self.form,
            self.kernel,
            self.shape,
            self.h_over_dx,
            self.support_over_dx,
            crate::display::num(self.stress)
        )
    }
}

/// Monaghan viscosity (α, β) as the analysis linearises it: on all pairs, sound speed `c`.
pub fn linearised_av(av: Option<(f64, f64)>, c: f64) -> Option<ArtificialViscosity> {
    av.map(|(alpha, beta)| ArtificialViscosity {
        alpha,
        beta,
        sound_speed: c,
        approaching_only: false,
    })
}

/// δ-SPH density diffusion (δ, form) with sound speed `c`, checked for `form` (δ in
/// [`crate::forms::DELTA_RANGE`], a form with a density state; the field `delta` in the
/// messages).
pub fn density_diffusion(
    d: Option<(f64, DiffusionForm)>,
    c: f64,
    form: FormKind,
) -> Result<Option<DensityDiffusion>> {
    let Some((delta, kind)) = d else {
        return Ok(None);
    };
    let dd = DensityDiffusion {
        delta,
        form: kind,
        sound_speed: c,
    };
    dd.check("delta", form)?;
    if !form.in_every_dimension() {
        return Err(Error::Incompatible(
            field("delta")
                + " (density diffusion) is available for classical, nonlocal, local, lnl and cll, not "
                + field("form")
                + format!(" {}", form.name()),
        ));
    }
    Ok(Some(dd))
}

/// What a time integrator does to a configuration's modes ([`crate::integrator`],
/// [`crate::vonneumann::amplification::step_stability`]): the part of a `timestep` report that
/// depends on the integrator, in every dimension. Units Δx/c and c/Δx.
#[derive(Clone, Debug, Serialize)]
pub struct IntegratorReport {
    /// CLI name of the integrator.
    pub integrator: &'static str,
    /// N_s of `verlet-euler` (null for the others).
    pub euler_every: Option<usize>,
    /// Largest oscillation frequency |Im s| over the eigenvalues that do not grow in the
    /// semi-discrete system (ω_max; with the oscillating branches of modes whose other branch
    /// grows).
    pub omega_max: f64,
    /// Dissipative systems only (absent otherwise): the largest decay rate −Re s over the same
    /// eigenvalues.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub decay_rate_max: Option<f64>,
    /// The semi-discrete system's largest growth rate max Re s (0 if nothing grows): physical
    /// (spatial) growth, present at every Δt and reported by `query` with its kind.
    pub physical_growth_rate: f64,
    /// The largest Δt at which the scheme adds no growth beyond the semi-discrete system's:
    /// growth per step ≤ e^{1.01 γ(k)Δt}(1 + 1e-7) at every mode k, γ(k) the mode's own growth
    /// rate (1% for the scheme's truncation error; |λ| ≤ 1 + 1e-7 for a mode that does not grow), by bisection on the amplification
    /// matrices; null when the integrator adds growth at every Δt (weak instability).
    pub critical_dt: Option<f64>,
    /// The integrator's stability limit on the imaginary axis over ω_max (2/ω_max for the
    /// leapfrog family, 2√2/ω_max for rk4), for non-dissipative systems; null where there is no
    /// closed form, and for a weakly unstable scheme (no Δt is stable).
    pub critical_dt_closed_form: Option<f64>,
    /// c Δt_crit / h.
    pub critical_cfl: Option<f64>,
    /// Whether the integrator amplifies non-growing modes at every Δt (|λ| > 1 + 1e-7 already at
    /// |s|_max Δt = 0.1): the weak instability, kind `integrator`.
    pub weak_instability: bool,
    /// Growth per unit time the integrator adds at `spurious_growth_dt` beyond the semi-discrete
    /// system: max over the modes of (ln|λ| − 1.01 γ(k)Δt)/Δt; 0 if none gains more than 1e-7
    /// per step.
    pub spurious_growth_rate: f64,
    /// What the added growth is: `time-step` (Δt above `critical_dt`), `integrator` (the weak
    /// instability, at every Δt), null when there is none.
    pub added_growth_kind: Option<&'static str>,
    /// The Δt of `spurious_growth_rate`: `dt` if given, else 1/|s|_max (half the leapfrog limit
    /// without dissipation).
    pub spurious_growth_dt: f64,
}

impl IntegratorReport {
    /// The report of `integ` on `lin` over the modes `ks`; `dt` is where the spurious growth is
    /// evaluated (default 1/|s|_max); `h_over_dx` gives the CFL number.
    pub fn of<L: crate::vonneumann::amplification::Modes>(
        lin: &L,
        ks: &[L::K],
        integ: crate::integrator::Integrator,
        dt: Option<f64>,
        h_over_dx: f64,
    ) -> Result<Self> {
        use crate::vonneumann::amplification::{spurious_growth_rate, step_stability};
        let st = step_stability(lin, ks, integ)?;
        let weak = st.weak;
        let critical_dt = st.critical_dt;
        let at = dt.unwrap_or(if st.s_max > 0.0 { 1.0 / st.s_max } else { 1.0 });
        let (rate, _) = spurious_growth_rate(lin, ks, integ, at)?;
        Ok(Self {
            integrator: integ.name(),
            euler_every: match integ {
                crate::integrator::Integrator::VerletEuler { every } => Some(every),
                _ => None,
            },
            omega_max: st.omega_max,
            decay_rate_max: lin.is_dissipative().then_some(st.decay_rate_max),
            physical_growth_rate: st.growth_rate,
            critical_dt,
            critical_dt_closed_form: st.closed_form_dt,
            critical_cfl: critical_dt.filter(|d| d.is_finite()).map(|d| d / h_over_dx),
            weak_instability: weak,
            spurious_growth_rate: rate,
            added_growth_kind: (rate > 0.0).then_some(if weak {
                "integrator"
            } else {
                "time-step"
            }),
            spurious_growth_dt: at,
        })
    }
}
