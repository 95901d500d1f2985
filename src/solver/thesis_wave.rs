//! Wave reflection and transmission at a density interface \[T §4.6.3.6, eq 4.45–4.46\]: a bar
//! (E = 200 GPa, ρ_A = 8000 kg/m³ left of mid-span, ρ_B = r ρ_A right of it), a smooth
//! right-going pulse v = g(x), σ = −ρ_A c_A g(x) (sin² of width `width` spacings) starting in the
//! left half. When the incident pulse has been split, the reflected pulse in A and the
//! transmitted pulse in B are measured; linear theory gives, with Z = ρc,
//! stress: C_r = (Z_B/Z_A − 1)/(Z_B/Z_A + 1), C_t = 2(Z_B/Z_A)/(Z_B/Z_A + 1);
//! particle velocity: v_r/v_i = −C_r, v_t/v_i = 2 Z_A/(Z_A + Z_B).
//! Seeding a stress pulse needs a form that carries stress (the Eulerian forms).
//!
//! Any ratio in [1e-4, 1e4] runs ([T] Figs 4.18, 4.19: a very large increase makes mid-span act
//! as a fixed end, v_r → −v_i; a very large decrease as a free one, v_r → +v_i, with a time
//! step set by the fast material, Δt ∝ √(ρ_B/ρ_A)). The run ends when the incident pulse has
//! split and both pulses are clear of the interface, or earlier if one of them would reach an
//! end of the bar: then the transmitted pulse cannot be measured (`transmitted` is None) —
//! for ρ_B/ρ_A below ~0.011 it outruns the bar before the split ends; below ~0.003 it comes
//! back to the interface before then, and the run is refused.

use super::run::Run;
use crate::budget::Budget;
use crate::error::{Error, Result, check_range, field};
use crate::forms::{FormKind, Material, Model, ModelParams};
use crate::kernel::Kernel;
use crate::shape::KernelParams;
use serde::Serialize;
use std::f64::consts::PI;

/// Configuration.
#[derive(Clone, Copy, Debug)]
pub struct ThesisWave {
    /// Form (must carry stress).
    pub form: FormKind,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// h/Δx.
    pub h_over_dx: f64,
    /// ρ_B/ρ_A.
    pub density_ratio: f64,
    /// Particles.
    pub particles: usize,
    /// Pulse width in spacings.
    pub width: f64,
    /// Pulse amplitude (m/s).
    pub amplitude: f64,
    /// The budget the run must stay within.
    pub budget: Budget,
}

impl ThesisWave {
    /// 0.15 m bar, 601 particles, pulse 30Δx wide, 1 m/s, h = 1.3Δx.
    pub fn new(form: FormKind, kernel: &'static dyn Kernel, density_ratio: f64) -> Self {
        Self {
            form,
            kernel,
            h_over_dx: 1.3,
            density_ratio,
            particles: 601,
            width: 30.0,
            amplitude: 1.0,
            budget: Budget::default(),
        }
    }
}

/// Measured and analytic coefficients.
#[derive(Clone, Debug, Serialize)]
pub struct ThesisWaveReport {
    /// ρ_B/ρ_A.
    pub density_ratio: f64,
    /// Measured reflected/incident peak velocity.
    pub reflected: f64,
    /// −C_r.
    pub reflected_exact: f64,
    /// Measured transmitted/incident velocity (None when the transmitted pulse would reach the
    /// bar's far end before the incident one has split: module docs).
    pub transmitted: Option<f64>,
    /// 2Z_A/(Z_A + Z_B).
    pub transmitted_exact: f64,
    /// The time step (s): 0.2 Δx over the faster wave speed.
    pub time_step: f64,
    /// Steps taken.
    pub steps: usize,
}

/// Runs the interface test. The amplitude ratios are measured from pulse integrals ∫v dx, the
/// pulse's k = 0 content, which dispersion does not change: reflected/incident = ∫_A v / ∫ g and
/// transmitted/incident = (∫_B v / ∫ g)(c_A/c_B) (the transmitted pulse is c_B/c_A as wide).
pub fn run_thesis_wave(cfg: &ThesisWave) -> Result<ThesisWaveReport> {
    if !matches!(
        cfg.form,
        FormKind::Classical | FormKind::Nonlocal | FormKind::Local | FormKind::EulerianNodal
    ) {
        return Err(Error::Incompatible(format!(
            "thesis-wave seeds a stress pulse: use a form that carries stress (classical, nonlocal, local, eulerian-nodal), not {}",
            cfg.form.name()
        ).into()));
    }
    check_range("density_ratio", cfg.density_ratio, 1e-4, 1e4, true, true)?;
    let (e, rho_a, len) = (200e9, 8000.0, 0.15);
    let rho_b = rho_a * cfg.density_ratio;
    let n = cfg.particles;
    let dx = len / (n - 1) as f64;
    let x: Vec<f64> = (0..n).map(|i| i as f64 * dx).collect();
    let p = ModelParams {
        form: cfg.form,
        shape: cfg.form.default_shape(),
        kp: KernelParams {
            kernel: cfg.kernel,
            h: cfg.h_over_dx * dx,
        },
        material: Material::bar(e),
        rho0: rho_a,
        c_partition: 0.5,
        av: None,
        art_stress: None,
        diffusion: None,
        alpha_s: 0.0,
        ls_length: dx,
        hourglass: None,
    };
    let x_ref: Vec<[f64; 1]> = x.iter().map(|&xi| [xi]).collect();
    let mut model = Model::new(p, x_ref, vec![dx; n], rho_a, 0.0, None)?;
    let a = 0.5 * len;
    let rho_of = |xi: f64| if xi < a { rho_a } else { rho_b };
    // a bar of two materials
    model.mass = x.iter().map(|&xi| rho_of(xi) * dx).collect();
    let mut z = model.rest_state(rho_a);
    for (r, &xi) in z.rho.iter_mut().zip(&x) {
        *r = rho_of(xi);
    }
    let (ca, cb) = ((e / rho_a).sqrt(), (e / rho_b).sqrt());
    let w = cfg.width * dx;
    let x0 = 0.25 * len;
    let g = |xi: f64| {
        if (xi - x0).abs() < w / 2.0 {
            cfg.amplitude * (PI * (xi - x0 + w / 2.0) / w).sin().powi(2)
        } else {
            0.0
        }
    };
    let mut incident = 0.0;
    for ((v, s), &xi) in z.v.iter_mut().zip(z.sigma.iter_mut()).zip(&x) {
        *v = [g(xi)];
        *s = [[-rho_a * ca * g(xi)]];
        incident += g(xi) * dx;
    }
    let mut run = Run::with_prescribed(model, z, &vec![None; n])?;
    // the incident pulse reaches the interface after (a − x0)/c_A; wait until the reflected and
    // transmitted pulses are clear of it, but stop before either reaches an end of the bar:
    // the reflected head (it left the interface at t_hit at c_A) two pulse widths short of the
    // left end — nearer, the free end changes its measured integral (by 0.02 at ρB/ρA = 100
    // with 10Δx) —
    // and the transmitted one (at c_B) 10Δx short of the right end
    let t_hit = (a - x0 - w / 2.0) / ca;
    let t_split = t_hit + w / ca;
    let clear = (a - x0) / ca + 1.5 * w / cb.min(ca);
    let t_left = t_hit + (a - 2.0 * w) / ca;
    let t_right = t_hit + (len - a - 10.0 * dx) / cb;
    let t_end = clear.min(t_left).min(t_right.max(t_split + 2.0 * dx / ca));
    let transmitted_ok = t_end <= t_right && t_end >= t_split;
    // the transmitted head, reflected at the far end, must not be back at the interface before
    // the end: c_B/c_A ≤ 2(L − a)/(c_A (t_end − t_hit)), i.e. ρB/ρA ≥ that ratio's inverse square
    let back = t_hit + 2.0 * (len - a) / cb;
    if back < t_end {
        let min_ratio = ((t_end - t_hit) * ca / (2.0 * (len - a))).powi(2);
        return Err(Error::OutOfRange {
            field: "density_ratio",
            value: cfg.density_ratio,
            range: format!(
                "must be at least {min_ratio:.2e}: below it the transmitted pulse comes back from the bar's far end before the incident one has split, and neither can be measured"
            )
            .into(),
        });
    }
    let dt = 0.2 * dx / ca.max(cb);
    let steps = (t_end / dt).ceil();
    cfg.budget.steps(
        field("density_ratio"),
        &format!(
            "the thesis-wave run ({} steps of {} particles at ρB/ρA = {})",
            crate::budget::fmt_count(steps),
            n,
            cfg.density_ratio
        ),
        steps * n as f64,
    )?;
    while run.t < t_end {
        run.step(dt)?;
    }
    let (mut left, mut right) = (0.0, 0.0);
    for (xi, [vi]) in x.iter().zip(&run.z.v) {
        if *xi < a {
            left += vi * dx;
        } else {
            right += vi * dx;
        }
    }
    let (za, zb) = (rho_a * ca, rho_b * cb);
    let cr = (zb / za - 1.0) / (zb / za + 1.0);
    Ok(ThesisWaveReport {
        density_ratio: cfg.density_ratio,
        reflected: left / incident,
        reflected_exact: -cr,
        transmitted: transmitted_ok.then_some(right / incident * ca / cb),
        transmitted_exact: 2.0 * za / (za + zb),
        time_step: dt,
        steps: run.steps,
    })
}
