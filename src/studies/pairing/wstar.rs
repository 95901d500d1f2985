//! The kernel's 3D Fourier transform and its sign: the pairing criterion of Dehnen & Aly (2012,
//! §4): SPH with a kernel whose 3D transform is negative somewhere pairs at large neighbour
//! numbers, and the Wendland functions ψ_{3,k} are positive definite in 3D (Wendland 1995).
//! The same scan runs in 1D and 2D ([`Transform`], [`sign_criterion_in`]; the kernel guide).
//!
//! Convention: for the 3D kernel W(r) = σ₃ h⁻³ f(r/h), with k in units of 1/h,
//!
//! ```text
//! W*(k) = (4π/k) ∫₀^ζ q f(q) sin(kq) dq  /  4π ∫₀^ζ q² f(q) dq      (W*(0) = 1)
//! ```
//!
//! evaluated as ∫ q² f(q) j₀(kq) dq / ∫ q² f(q) dq with j₀(x) = sin x / x by the crate's one
//! kernel-transform quadrature, [`radial_integral`]`::<3>` (the 1D transform of \[V21\],
//! [`crate::vonneumann::transform::kernel_ft_at`], is its D = 1 case): piecewise 16-point
//! Gauss–Legendre, exact to round-off (~1e-16) for the piecewise-polynomial kernels, spectrally
//! convergent for the Gaussian and the mollifier.

use crate::kernel::Kernel;
use crate::vonneumann::transform::radial_integral;
use serde::Serialize;

/// The sign scan covers k ∈ [0, `K_MAX`] (units 1/h) ...
pub const K_MAX: f64 = 40.0;
/// ... in steps of `K_STEP` (then refined by bisection / golden section).
pub const K_STEP: f64 = 0.005;
/// W*(k) counts as negative when below −`NEGATIVE_TOL` (relative to W*(0) = 1): far above the
/// quadrature's round-off (~1e-16) and far below any physically meaningful value.
pub const NEGATIVE_TOL: f64 = 1e-12;

/// The normalised transform W*(k)/W*(0) of one kernel in dimension `dim` ∈ {1, 2, 3} (its
/// normalisation ∫ q^{D−1} f(q) dq computed once), with the dimension's own shape function
/// (`f(dim, q)`: the Wendland kernels change with the dimension):
///
/// ```text
/// W*(k)/W*(0) = ∫₀^ζ q^{D−1} f(q) φ_D(kq) dq / ∫₀^ζ q^{D−1} f(q) dq,   φ₁ = cos, φ₂ = J₀, φ₃ = j₀
/// ```
///
/// ([`radial_integral`]; 1D: the \[V21\] transform of [`crate::vonneumann::transform::kernel_ft_at`],
/// 2D: the Hankel transform, 3D: Dehnen & Aly's criterion).
#[derive(Clone, Debug)]
pub struct Transform {
    pub(super) kernel: &'static dyn Kernel,
    pub(super) dim: usize,
    pub(super) norm: f64,
}

impl Transform {
    /// Computes the normalisation (`dim` clamped into 1..=3).
    pub fn new(kernel: &'static dyn Kernel, dim: usize) -> Self {
        let mut t = Self {
            kernel,
            dim: dim.clamp(1, 3),
            norm: 1.0,
        };
        t.norm = t.raw(0.0);
        t
    }

    /// ∫₀^ζ q^{D−1} f(q) φ_D(kq) dq.
    pub(super) fn raw(&self, k: f64) -> f64 {
        let (kern, d) = (self.kernel, self.dim);
        let g = |q: f64| kern.f(d, q);
        match d {
            1 => radial_integral::<1>(&g, kern.zeta(), k),
            2 => radial_integral::<2>(&g, kern.zeta(), k),
            _ => radial_integral::<3>(&g, kern.zeta(), k),
        }
    }

    /// W*(k)/W*(0), k in units of 1/h.
    pub fn at(&self, k: f64) -> f64 {
        self.raw(k) / self.norm
    }

    /// The dimension.
    pub fn dim(&self) -> usize {
        self.dim
    }
}

/// The normalised 3D transform of one kernel ([`Transform`] with D = 3).
#[derive(Clone, Debug)]
pub struct Transform3D(Transform);

impl Transform3D {
    /// Computes the normalisation ∫ q² f(q) dq.
    pub fn new(kernel: &'static dyn Kernel) -> Self {
        Self(Transform::new(kernel, 3))
    }

    /// W*(k)/W*(0), k in units of 1/h.
    pub fn at(&self, k: f64) -> f64 {
        self.0.at(k)
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
    sign_criterion_in(kernel, 3)
}

/// [`sign_criterion`] in dimension `dim` ∈ {1, 2, 3} ([`Transform`]).
pub fn sign_criterion_in(kernel: &'static dyn Kernel, dim: usize) -> WStarSign {
    sign_criterion_with(kernel, dim, K_STEP)
}

/// The scan grid of [`sign_criterion_with`]: k = i·`k_step`, i = 0 ..= round([`K_MAX`]/step),
/// with `k_step` clamped into [1e-4, 1] ([`K_STEP`] if not finite).
pub fn scan_grid(k_step: f64) -> Vec<f64> {
    let k_step = if k_step.is_finite() {
        k_step.clamp(1e-4, 1.0)
    } else {
        K_STEP
    };
    let n = (K_MAX / k_step).round() as usize;
    (0..=n).map(|i| i as f64 * k_step).collect()
}

/// What the scan decides from its samples w_i = W*(k_i) (then refined by [`refine`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Decisions {
    /// The first index of the smallest sample (`total_cmp`).
    pub(super) imin: usize,
    /// w_imin.
    pub(super) wmin: f64,
    /// With i the first index with w_i < −[`NEGATIVE_TOL`]: the last j < i with w_j ≥ 0 (0 if
    /// none) and whether w_{j+1} < 0.
    pub(super) first: Option<(usize, bool)>,
}

/// [`sign_criterion_in`] with scan step `k_step` (units 1/h; clamped into [1e-4, 1]): every
/// sample evaluated, the slow and obviously correct scan. [`sign_criterion_fast`] gives the
/// same result to the last bit with a fraction of the evaluations.
///
/// [`sign_criterion_fast`]: super::wstar_scan::sign_criterion_fast
pub fn sign_criterion_with(kernel: &'static dyn Kernel, dim: usize, k_step: f64) -> WStarSign {
    let t = Transform::new(kernel, dim);
    let ks = scan_grid(k_step);
    let w: Vec<f64> = ks.iter().map(|&k| t.at(k)).collect();
    let imin = (0..w.len())
        .min_by(|&a, &b| w[a].total_cmp(&w[b]))
        .unwrap_or(0);
    let first = w.iter().position(|&v| v < -NEGATIVE_TOL).map(|i| {
        // the last non-negative sample before i
        let j = (0..i).rev().find(|&j| w[j] >= 0.0).unwrap_or(0);
        (j, w[j + 1] < 0.0)
    });
    let d = Decisions {
        imin,
        wmin: w[imin],
        first,
    };
    refine(kernel, &ks, d, |k| t.at(k))
}

/// The result of the scan from its decisions: the minimum refined by golden section on
/// [k_{imin−1}, k_{imin+1}], the first zero bisected on the sign of W* (`at`, W*(k)/W*(0)).
pub(super) fn refine(
    kernel: &'static dyn Kernel,
    ks: &[f64],
    d: Decisions,
    mut at: impl FnMut(f64) -> f64,
) -> WStarSign {
    let n = ks.len() - 1;
    let imin = d.imin;
    // golden section on [k_{i−1}, k_{i+1}]
    let (mut lo, mut hi) = (ks[imin.saturating_sub(1)], ks[(imin + 1).min(n)]);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if at(c) < at(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    let kmin = 0.5 * (lo + hi);
    let (k_at_min, min) = if at(kmin) < d.wmin {
        (kmin, at(kmin))
    } else {
        (ks[imin], d.wmin)
    };
    let first = d.first.map(|(j, bracketed)| {
        // bisect on the sign between the last non-negative sample and the next
        let (mut a, mut b) = (ks[j], ks[j + 1]);
        if bracketed {
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if at(m) >= 0.0 {
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
    fn normalised_at_zero() {
        for &k in crate::kernel::all() {
            assert!((wstar_3d(k, 0.0) - 1.0).abs() < 1e-14, "{}", k.name());
        }
    }
}
