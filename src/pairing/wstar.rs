//! The kernel's 3D Fourier transform and its sign: the pairing criterion of Dehnen & Aly (2012,
//! §4): SPH with a kernel whose 3D transform is negative somewhere pairs at large neighbour
//! numbers, and the Wendland functions ψ_{3,k} are positive definite in 3D (Wendland 1995).
//!
//! Convention: for the 3D kernel W(r) = σ₃ h⁻³ f(r/h), with k in units of 1/h,
//!
//! ```text
//! W*(k) = (4π/k) ∫₀^ζ q f(q) sin(kq) dq  /  4π ∫₀^ζ q² f(q) dq      (W*(0) = 1)
//! ```
//!
//! evaluated as ∫ q² f(q) j₀(kq) dq / ∫ q² f(q) dq with j₀(x) = sin x / x. Quadrature
//! ([`Transform3D::at`]): [0, ζ] is cut at every multiple of [`PIECE`] (so every breakpoint of the
//! piecewise-polynomial kernels — B-spline knots at integers and half-integers, the EFG cubic's
//! q = ½, the Wendland and Lucy supports — is a panel edge, as is the truncation of the
//! Gaussian at ζ = 3), each piece into equal panels with k·width ≤ [`MAX_PANEL_PHASE`], and each
//! panel is integrated by [`GL_POINTS`]-point Gauss–Legendre. The rule is exact for polynomials
//! of degree 2·[`GL_POINTS`] − 1 = 31: for the polynomial kernels (degree ≤ 11, times q²) the
//! only error is the truncated Taylor series of j₀ over one panel, of order
//! [`MAX_PANEL_PHASE`]^32/32! ≈ 4e-36 — the result is exact to round-off (~1e-16). The smooth
//! Gaussian and mollifier pieces converge spectrally at this resolution.

use crate::kernel::Kernel;
use serde::Serialize;

/// Gauss–Legendre points per panel.
pub const GL_POINTS: usize = 16;
/// Piece length in units of h: every multiple is a panel edge.
pub const PIECE: f64 = 0.25;
/// Largest k·(panel width) (radians of the oscillating factor per panel).
pub const MAX_PANEL_PHASE: f64 = 1.0;
/// The sign scan covers k ∈ [0, `K_MAX`] (units 1/h) ...
pub const K_MAX: f64 = 40.0;
/// ... in steps of `K_STEP` (then refined by bisection / golden section).
pub const K_STEP: f64 = 0.005;
/// W*(k) counts as negative when below −`NEGATIVE_TOL` (relative to W*(0) = 1): far above the
/// quadrature's round-off (~1e-16) and far below any physically meaningful value.
pub const NEGATIVE_TOL: f64 = 1e-12;

/// Gauss–Legendre nodes and weights on [−1, 1], n ≥ 2 (Newton iteration on the Legendre
/// polynomial from the Tricomi initial guesses; converged to machine precision).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let n = n.max(2);
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_n(z) and P_n'(z) by the three-term recurrence
            let (mut p0, mut p1) = (1.0, z);
            for j in 2..=n {
                let jf = j as f64;
                let p2 = ((2.0 * jf - 1.0) * z * p1 - (jf - 1.0) * p0) / jf;
                p0 = p1;
                p1 = p2;
            }
            dp = nf * (z * p1 - p0) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

/// sin x / x with its Taylor series near 0.
fn j0(x: f64) -> f64 {
    if x.abs() < 1e-3 {
        let x2 = x * x;
        1.0 - x2 / 6.0 * (1.0 - x2 / 20.0)
    } else {
        x.sin() / x
    }
}

/// The normalised 3D transform of one kernel (quadrature set up once).
#[derive(Clone, Debug)]
pub struct Transform3D {
    kernel: &'static dyn Kernel,
    nodes: Vec<f64>,
    weights: Vec<f64>,
    norm: f64,
}

impl Transform3D {
    /// Sets up the quadrature and the normalisation ∫ q² f(q) dq.
    pub fn new(kernel: &'static dyn Kernel) -> Self {
        let (nodes, weights) = gauss_legendre(GL_POINTS);
        let mut t = Self {
            kernel,
            nodes,
            weights,
            norm: 1.0,
        };
        t.norm = t.raw(0.0);
        t
    }

    /// ∫₀^ζ q² f(q) j₀(kq) dq.
    fn raw(&self, k: f64) -> f64 {
        let zeta = self.kernel.zeta();
        let pieces = (zeta / PIECE).ceil() as usize;
        let mut sum = 0.0;
        for p in 0..pieces {
            let a = p as f64 * PIECE;
            let b = (a + PIECE).min(zeta);
            if b <= a {
                continue;
            }
            let panels = ((k.abs() * (b - a) / MAX_PANEL_PHASE).ceil() as usize).max(2);
            let width = (b - a) / panels as f64;
            for m in 0..panels {
                let lo = a + m as f64 * width;
                let (mid, half) = (lo + 0.5 * width, 0.5 * width);
                let mut s = 0.0;
                for (&x, &w) in self.nodes.iter().zip(&self.weights) {
                    let q = mid + half * x;
                    s += w * q * q * self.kernel.f(3, q) * j0(k * q);
                }
                sum += s * half;
            }
        }
        sum
    }

    /// W*(k)/W*(0), k in units of 1/h.
    pub fn at(&self, k: f64) -> f64 {
        self.raw(k) / self.norm
    }
}

/// W*(k)/W*(0) of `kernel` in 3D at k (units 1/h); builds the quadrature each call.
pub fn wstar_3d(kernel: &'static dyn Kernel, k: f64) -> f64 {
    Transform3D::new(kernel).at(k)
}

/// The sign criterion of one kernel over k ∈ [0, [`K_MAX`]] (units 1/h).
#[derive(Clone, Debug, Serialize, serde::Deserialize, PartialEq)]
pub struct WStarSign {
    /// Kernel name.
    pub kernel: String,
    /// Support ζ (units h).
    pub zeta: f64,
    /// min_k W*(k)/W*(0) over the scanned range.
    pub min: f64,
    /// Where the minimum is (units 1/h).
    pub k_at_min: f64,
    /// W* < −[`NEGATIVE_TOL`] somewhere in the scanned range.
    pub negative: bool,
    /// The zero of W* where it first turns negative (units 1/h), null if it never does.
    pub first_negative_k: Option<f64>,
    /// Upper end of the scanned range (units 1/h).
    pub k_max: f64,
}

/// Scans W*(k) on [0, [`K_MAX`]] in steps of [`K_STEP`]; the zero before the first sample below
/// −[`NEGATIVE_TOL`] is bisected to 1e-12 on the sign of W* (near a root of odd multiplicity m,
/// W* ≈ c(k − k₀)^m, the sign is resolved only to |k − k₀| ≈ (1e-16/|c|)^{1/m}: ~4e-5 for m4's
/// triple root at k = 2π, ~5e-3 for m6's five-fold one), the minimum refined by golden section
/// between its neighbouring samples.
pub fn sign_criterion(kernel: &'static dyn Kernel) -> WStarSign {
    let t = Transform3D::new(kernel);
    let n = (K_MAX / K_STEP).round() as usize;
    let ks: Vec<f64> = (0..=n).map(|i| i as f64 * K_STEP).collect();
    let w: Vec<f64> = ks.iter().map(|&k| t.at(k)).collect();
    let imin = (0..w.len())
        .min_by(|&a, &b| w[a].total_cmp(&w[b]))
        .unwrap_or(0);
    // golden section on [k_{i−1}, k_{i+1}]
    let (mut lo, mut hi) = (ks[imin.saturating_sub(1)], ks[(imin + 1).min(n)]);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if t.at(c) < t.at(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    let kmin = 0.5 * (lo + hi);
    let (k_at_min, min) = if t.at(kmin) < w[imin] {
        (kmin, t.at(kmin))
    } else {
        (ks[imin], w[imin])
    };
    let first = w.iter().position(|&v| v < -NEGATIVE_TOL).map(|i| {
        // the last non-negative sample before i, then bisect on the sign
        let j = (0..i).rev().find(|&j| w[j] >= 0.0).unwrap_or(0);
        let (mut a, mut b) = (ks[j], ks[j + 1]);
        if w[j + 1] < 0.0 {
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if t.at(m) >= 0.0 {
                    a = m;
                } else {
                    b = m;
                }
                if b - a < 1e-12 {
                    break;
                }
            }
        }
        0.5 * (a + b)
    });
    WStarSign {
        kernel: kernel.name().to_string(),
        zeta: kernel.zeta(),
        min,
        k_at_min,
        negative: first.is_some(),
        first_negative_k: first,
        k_max: K_MAX,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        let (x, w) = gauss_legendre(GL_POINTS);
        assert!((w.iter().sum::<f64>() - 2.0).abs() < 1e-14);
        // ∫_{-1}^{1} x^{30} dx = 2/31 (degree 30 ≤ 31)
        let s: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(30)).sum();
        assert!((s - 2.0 / 31.0).abs() < 1e-14, "{s}");
    }

    #[test]
    fn normalised_at_zero() {
        for &k in crate::kernel::all() {
            assert!((wstar_3d(k, 0.0) - 1.0).abs() < 1e-14, "{}", k.name());
        }
    }
}
