//! Fully discrete analysis: the leapfrog step of [`crate::integrator::kdk_step`] applied to
//! one Fourier mode of the linearised system gives the amplification matrix G(κ, Δt);
//! its spectral radius decides time-step stability.

use super::linearise::{Linearisation, eigen};
use crate::error::Result;
use crate::forms::FieldKind;
use crate::integrator::{Scratch, SecondOrderSystem, kdk_step};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// |λ| above 1 + this is amplification. Not smaller: a double eigenvalue with a Jordan block
/// (ω = 0 zero-energy modes, λ = 1; the leapfrog limit, λ = −1) is computed only to
/// O(√ε ‖G‖) ≈ 1e-8, so a tighter tolerance would report rounding as amplification.
pub const AMPLIFICATION_TOL: f64 = 1e-7;

/// The linear system of one Fourier mode: J split into position, velocity and auxiliary rows.
pub struct ModeSystem {
    j: DMatrix<Complex64>,
    ix: Vec<usize>,
    iv: Vec<usize>,
    iq: Vec<usize>,
}

impl ModeSystem {
    /// A mode system from J and the indices of positions, velocities and auxiliary states.
    pub fn new(j: DMatrix<Complex64>, ix: Vec<usize>, iv: Vec<usize>, iq: Vec<usize>) -> Self {
        Self { j, ix, iv, iq }
    }

    fn row(&self, a: usize, x: &[Complex64], v: &[Complex64], q: &[Complex64]) -> Complex64 {
        let mut s = Complex64::new(0.0, 0.0);
        for (k, &b) in self.ix.iter().enumerate() {
            s += self.j[(a, b)] * x[k];
        }
        for (k, &b) in self.iv.iter().enumerate() {
            s += self.j[(a, b)] * v[k];
        }
        for (k, &b) in self.iq.iter().enumerate() {
            s += self.j[(a, b)] * q[k];
        }
        s
    }

    /// Amplification matrix of one leapfrog step of size `dt` (same units as J⁻¹).
    pub fn amplification(&self, dt: f64) -> DMatrix<Complex64> {
        let n = self.j.nrows();
        let mut g = DMatrix::<Complex64>::zeros(n, n);
        let mut scratch = Scratch::default();
        let unit = |idx: &[usize], col: usize| -> Vec<Complex64> {
            idx.iter()
                .map(|&k| Complex64::new((k == col) as u8 as f64, 0.0))
                .collect()
        };
        for col in 0..n {
            let mut x = unit(&self.ix, col);
            let mut v = unit(&self.iv, col);
            let mut q = unit(&self.iq, col);
            kdk_step(self, &mut x, &mut v, &mut q, dt, &mut scratch);
            for (idx, vals) in [(&self.ix, &x), (&self.iv, &v), (&self.iq, &q)] {
                for (k, &b) in idx.iter().enumerate() {
                    g[(b, col)] = vals[k];
                }
            }
        }
        g
    }
}

impl SecondOrderSystem<Complex64> for ModeSystem {
    fn accel(&self, x: &[Complex64], v: &[Complex64], q: &[Complex64], a: &mut [Complex64]) {
        for (k, &b) in self.iv.iter().enumerate() {
            a[k] = self.row(b, x, v, q);
        }
    }
    fn qrate(&self, x: &[Complex64], v: &[Complex64], q: &[Complex64], r: &mut [Complex64]) {
        for (k, &b) in self.iq.iter().enumerate() {
            r[k] = self.row(b, x, v, q);
        }
    }
}

/// Amplification matrix G(κ, Δt) of one leapfrog step; `dt` in Δx/c.
pub fn amplification_matrix(lin: &Linearisation, kappa: f64, dt: f64) -> DMatrix<Complex64> {
    let (dx, c) = lin.units();
    let dofs = &lin.dofs;
    let ix: Vec<usize> = (0..dofs.len())
        .filter(|&k| dofs[k].field.kind() == FieldKind::Position)
        .collect();
    let iv: Vec<usize> = (0..dofs.len())
        .filter(|&k| dofs[k].field.kind() == FieldKind::Velocity)
        .collect();
    let iq: Vec<usize> = (0..dofs.len())
        .filter(|&k| dofs[k].field.kind() == FieldKind::Auxiliary)
        .collect();
    ModeSystem::new(lin.jacobian(kappa), ix, iv, iq).amplification(dt * dx / c)
}

/// Spectral radius of G(κ, Δt).
pub fn spectral_radius(lin: &Linearisation, kappa: f64, dt: f64) -> Result<f64> {
    let ev = eigen(amplification_matrix(lin, kappa, dt))?;
    Ok(ev.iter().map(|l| l.norm()).fold(0.0, f64::max))
}

/// Largest spectral radius over the κ grid.
pub fn max_spectral_radius(lin: &Linearisation, kappas: &[f64], dt: f64) -> Result<(f64, f64)> {
    let mut best = (0.0, 0.0);
    for &k in kappas {
        let r = spectral_radius(lin, k, dt)?;
        if r > best.0 {
            best = (r, k);
        }
    }
    Ok(best)
}

/// Critical time step (Δx/c). Non-dissipative systems: the leapfrog limit 2/ω_max
/// (\[B00\] eq 120 with ξ = 0; tests check it against the amplification matrices). Dissipative
/// systems: the largest Δt with max_κ |λ| ≤ 1 + tol, by bisection.
pub fn critical_dt(lin: &Linearisation, kappas: &[f64]) -> Result<f64> {
    if !lin.is_dissipative() {
        let wmax = kappas
            .iter()
            .map(|&k| lin.omega2(k).0)
            .fold(0.0, f64::max)
            .sqrt();
        return Ok(if wmax > 0.0 {
            2.0 / wmax
        } else {
            f64::INFINITY
        });
    }
    critical_dt_bisection(lin, kappas)
}

/// Critical time step by bisection on the spectral radius of the amplification matrices.
pub fn critical_dt_bisection(lin: &Linearisation, kappas: &[f64]) -> Result<f64> {
    let stable = |dt: f64| -> Result<bool> {
        Ok(max_spectral_radius(lin, kappas, dt)?.0 <= 1.0 + AMPLIFICATION_TOL)
    };
    let mut lo = 0.0;
    let mut hi = 1.0;
    while stable(hi)? {
        lo = hi;
        hi *= 2.0;
        if hi > 1e6 {
            return Ok(f64::INFINITY);
        }
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if stable(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-12 * hi {
            break;
        }
    }
    Ok(lo)
}
