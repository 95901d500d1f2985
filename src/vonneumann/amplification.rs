//! Fully discrete analysis: the leapfrog step of [`crate::integrator::kdk_step`] applied to
//! one Fourier mode of the linearised system gives the amplification matrix G(κ, Δt);
//! its spectral radius decides time-step stability. The critical-Δt search is one generic code
//! path ([`Modes`]) for the 1D chain (modes κΔx) and the D-dimensional lattice (wave vectors k).

use super::linearise::eigen;
use crate::error::Result;
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

/// What the fully discrete analysis needs of a linearisation whose modes are indexed by `K`:
/// κΔx for the 1D chain ([`super::linearise::Linearisation`]), the wave vector for
/// [`super::linearise::Bloch`].
pub trait Modes {
    /// Mode index.
    type K: Copy;
    /// Whether velocities enter the accelerations (artificial viscosity).
    fn is_dissipative(&self) -> bool;
    /// Largest Re ω²Δx²/c² of the mechanical branches at k.
    fn omega2_top(&self, k: Self::K) -> f64;
    /// Amplification matrix G(k, Δt) of one leapfrog step; `dt` in Δx/c.
    fn amplification(&self, k: Self::K, dt: f64) -> DMatrix<Complex64>;
}

/// Amplification matrix G(k, Δt) of one leapfrog step; `dt` in Δx/c.
pub fn amplification_matrix<L: Modes>(lin: &L, k: L::K, dt: f64) -> DMatrix<Complex64> {
    lin.amplification(k, dt)
}

/// Spectral radius of G(k, Δt).
pub fn spectral_radius<L: Modes>(lin: &L, k: L::K, dt: f64) -> Result<f64> {
    let ev = eigen(lin.amplification(k, dt))?;
    Ok(ev.iter().map(|l| l.norm()).fold(0.0, f64::max))
}

/// Spectral radius of G(k, Δt) at every mode of `ks`.
pub fn spectral_radii<L: Modes>(lin: &L, ks: &[L::K], dt: f64) -> Result<Vec<f64>> {
    ks.iter().map(|&k| spectral_radius(lin, k, dt)).collect()
}

/// The leapfrog limit 2/ω_max (\[B00\] eq 120 with ξ = 0) for the largest ω² (normalised);
/// infinite when ω_max = 0.
pub fn leapfrog_limit(omega2_max: f64) -> f64 {
    let wmax = omega2_max.sqrt();
    if wmax > 0.0 {
        2.0 / wmax
    } else {
        f64::INFINITY
    }
}

/// Critical time step (Δx/c) over the modes `ks`. Non-dissipative systems: the leapfrog limit
/// 2/ω_max ([`leapfrog_limit`]; tests check it against the amplification matrices). Dissipative
/// systems: the largest Δt with max_k |λ| ≤ 1 + tol, by bisection.
pub fn critical_dt<L: Modes>(lin: &L, ks: &[L::K]) -> Result<f64> {
    let w2 = if lin.is_dissipative() {
        0.0
    } else {
        ks.iter().map(|&k| lin.omega2_top(k)).fold(0.0, f64::max)
    };
    critical_dt_given(lin, ks, w2)
}

/// [`critical_dt`] when the largest ω² over `ks` is already known (`omega2_max`, unused for
/// dissipative systems).
pub fn critical_dt_given<L: Modes>(lin: &L, ks: &[L::K], omega2_max: f64) -> Result<f64> {
    if lin.is_dissipative() {
        critical_dt_bisection(lin, ks)
    } else {
        Ok(leapfrog_limit(omega2_max))
    }
}

/// Critical time step by bisection on the spectral radius of the amplification matrices: Δt is
/// stable when |λ| ≤ 1 + [`AMPLIFICATION_TOL`] at every mode of `ks`.
pub fn critical_dt_bisection<L: Modes>(lin: &L, ks: &[L::K]) -> Result<f64> {
    let stable = |dt: f64| -> Result<bool> {
        for &k in ks {
            if spectral_radius(lin, k, dt)? > 1.0 + AMPLIFICATION_TOL {
                return Ok(false);
            }
        }
        Ok(true)
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
