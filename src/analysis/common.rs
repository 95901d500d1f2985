//! What every question shares, in every dimension: validation of the common parameters (one
//! path for CLI flags, scene files, configs and the library API), integer counts, the
//! configuration line every report starts with, and the linearised artificial viscosity.

use crate::error::{Error, Result, check_range};
use crate::forms::{ArtificialViscosity, DensityDiffusion, DiffusionForm, FormKind};
use crate::kernel::Kernel;
use crate::shape::ShapeFamily;
use serde::Serialize;

/// Allowed range of h/Δx.
pub const H_RANGE: (f64, f64) = (0.05, 50.0);
/// Allowed range of σ̄.
pub const STRESS_RANGE: (f64, f64) = (-10.0, 10.0);

/// The names under which the common parameters reach the user: CLI flags or scene fields.
#[derive(Clone, Copy, Debug)]
pub struct ParamNames {
    /// h/Δx.
    pub h: &'static str,
    /// σ̄.
    pub stress: &'static str,
    /// Partition coefficient.
    pub c: &'static str,
    /// Viscosity α.
    pub av_alpha: &'static str,
    /// Viscosity β.
    pub av_beta: &'static str,
    /// Δt.
    pub dt: &'static str,
}

impl ParamNames {
    /// The CLI flags.
    pub const CLI: ParamNames = ParamNames {
        h: "--h",
        stress: "--stress",
        c: "--c",
        av_alpha: "--av-alpha",
        av_beta: "--av-beta",
        dt: "--dt",
    };
}

/// Validates the parameters shared by every question and run (one path for CLI flags, scene
/// files, configs and the library API), naming them as the CLI does.
pub fn check_common(
    kernel: &'static dyn Kernel,
    h: f64,
    stress: f64,
    c: f64,
    av: Option<(f64, f64)>,
    dt: Option<f64>,
) -> Result<()> {
    check_common_named(&ParamNames::CLI, kernel, h, stress, c, av, dt)
}

/// [`check_common`] with the names of the caller (e.g. scene fields).
pub fn check_common_named(
    names: &ParamNames,
    kernel: &'static dyn Kernel,
    h: f64,
    stress: f64,
    c: f64,
    av: Option<(f64, f64)>,
    dt: Option<f64>,
) -> Result<()> {
    check_range(names.h, h, H_RANGE.0, H_RANGE.1, true, true)?;
    check_range(
        names.stress,
        stress,
        STRESS_RANGE.0,
        STRESS_RANGE.1,
        true,
        true,
    )?;
    check_range(names.c, c, 0.0, 1.0, true, true)?;
    if let Some((a, b)) = av {
        check_range(names.av_alpha, a, 0.0, 100.0, true, true)?;
        check_range(names.av_beta, b, 0.0, 100.0, true, true)?;
    }
    if let Some(dt) = dt {
        check_range(names.dt, dt, 0.0, 1e6, false, true)?;
    }
    if kernel.zeta() * h <= 1.0 {
        return Err(Error::OutOfRange {
            name: names.h,
            value: h,
            range: format!(
                "the support ζh must exceed Δx so that particles have neighbours: h/Δx > {} for {} (ζ = {})",
                1.0 / kernel.zeta(),
                kernel.name(),
                kernel.zeta()
            ),
        });
    }
    Ok(())
}

/// `Err(OutOfRange)` unless `lo ≤ n ≤ hi`.
pub fn check_count(name: &'static str, n: usize, lo: usize, hi: usize) -> Result<()> {
    if (lo..=hi).contains(&n) {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            name,
            value: n as f64,
            range: format!("must be an integer in [{lo}, {hi}]"),
        })
    }
}

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
    /// One line: form / kernel / shape, h and R in Δx, σ̄.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} / {} / {}  h = {:.4}Δx (R = {:.4}Δx), σ̄ = {}",
            self.form, self.kernel, self.shape, self.h_over_dx, self.support_over_dx, self.stress
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
/// [`crate::forms::DELTA_RANGE`], a form with a density state; `--delta` in the messages).
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
    dd.check("--delta", form)?;
    if !form.in_2d() {
        return Err(Error::Incompatible(format!(
            "--delta (density diffusion) is available for classical, nonlocal, local, lnl and cll, not --form {}",
            form.name()
        )));
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
    /// Largest |s| over the modes that do not grow in the semi-discrete system (ω_max).
    pub omega_max: f64,
    /// Largest Δt with growth per step ≤ 1 + 1e-7 on every non-growing mode, by bisection on the
    /// amplification matrices; null when the integrator amplifies at every Δt (weak
    /// instability) or the semi-discrete system grows.
    pub critical_dt: Option<f64>,
    /// The integrator's stability limit on the imaginary axis over ω_max (2/ω_max for the
    /// leapfrog family, 2√2/ω_max for rk4), for non-dissipative systems; null where there is no
    /// closed form.
    pub critical_dt_closed_form: Option<f64>,
    /// c Δt_crit / h.
    pub critical_cfl: Option<f64>,
    /// Whether the integrator amplifies non-growing modes at every Δt (|λ| > 1 + 1e-7 already at
    /// ω_max Δt = 0.1): the weak instability, kind `integrator`.
    pub weak_instability: bool,
    /// Growth per unit time the integrator adds at `spurious_growth_dt` (max over the
    /// non-growing modes of ln|λ|/Δt; 0 if none amplifies).
    pub spurious_growth_rate: f64,
    /// The Δt of `spurious_growth_rate`: `--dt` if given, else 1/ω_max (half the leapfrog limit).
    pub spurious_growth_dt: f64,
}

impl IntegratorReport {
    /// The report of `integ` on `lin` over the modes `ks`; `dt` is where the spurious growth is
    /// evaluated (default 1/ω_max); `h_over_dx` gives the CFL number. `grows`: the
    /// semi-discrete system has growing modes (then no critical Δt is reported).
    pub fn of<L: crate::vonneumann::amplification::Modes>(
        lin: &L,
        ks: &[L::K],
        integ: crate::integrator::Integrator,
        dt: Option<f64>,
        h_over_dx: f64,
        grows: bool,
    ) -> Result<Self> {
        use crate::vonneumann::amplification::{spurious_growth_rate, step_stability};
        let st = step_stability(lin, ks, integ)?;
        let weak = st.weak;
        let critical_dt = if grows { None } else { st.critical_dt };
        let at = dt.unwrap_or(if st.omega_max > 0.0 {
            1.0 / st.omega_max
        } else {
            1.0
        });
        let (rate, _) = spurious_growth_rate(lin, ks, integ, at)?;
        Ok(Self {
            integrator: integ.name(),
            euler_every: match integ {
                crate::integrator::Integrator::VerletEuler { every } => Some(every),
                _ => None,
            },
            omega_max: st.omega_max,
            critical_dt,
            critical_dt_closed_form: st.closed_form_dt,
            critical_cfl: critical_dt.filter(|d| d.is_finite()).map(|d| d / h_over_dx),
            weak_instability: weak,
            spurious_growth_rate: rate,
            spurious_growth_dt: at,
        })
    }
}
