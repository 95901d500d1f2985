//! Wave reflection and transmission at a density interface \[T §4.6.3.6, eq 4.45–4.46\]: a bar
//! (E = 200 GPa, ρ_A = 8000 kg/m³ left of mid-span, ρ_B = r ρ_A right of it), a smooth
//! right-going pulse v = g(x), σ = −ρ_A c_A g(x) (sin² of width `width` spacings) starting in the
//! left half. When the incident pulse has been split, the reflected pulse in A and the
//! transmitted pulse in B are measured; linear theory gives, with Z = ρc,
//! stress: C_r = (Z_B/Z_A − 1)/(Z_B/Z_A + 1), C_t = 2(Z_B/Z_A)/(Z_B/Z_A + 1);
//! particle velocity: v_r/v_i = −C_r, v_t/v_i = 2 Z_A/(Z_A + Z_B).
//! Seeding a stress pulse needs a form that carries stress (the Eulerian forms).

use super::run::Run;
use crate::error::{Error, Result};
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
    /// Measured transmitted/incident peak velocity.
    pub transmitted: f64,
    /// 2Z_A/(Z_A + Z_B).
    pub transmitted_exact: f64,
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
    // transmitted pulses are clear of it
    let t_end = (a - x0) / ca + 1.5 * w / cb.min(ca);
    let dt = 0.2 * dx / ca.max(cb);
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
        transmitted: right / incident * ca / cb,
        transmitted_exact: 2.0 * za / (za + zb),
    })
}
