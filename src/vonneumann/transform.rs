//! Continuous Fourier transform of a 1D kernel, \[V21\] Appendix A; SPEC §5.4.
//!
//! Convention: W*(k) = ∫ e^{−ikx} W(x) dx, which for an even kernel is the real cosine
//! transform 2∫₀^ζ W(x) cos(kx) dx. The kernel is passed as a closure `W(x)` with x in units of
//! the kernel's h (so k is in units of 1/h) and compact support |x| ≤ ζ; W*(0) = ∫W, 1 for a
//! normalised kernel. \[V21\] requires |W*(k)|² > 0 for k ≠ 0 (eq. A.72, nonlocal continuum
//! stability) and W*(0) > 0 (Requirement I); since W*(0) > 0 and W* is continuous, both amount to
//! W*(k) > 0 for all k.
//!
//! Three evaluations, each checking the others:
//! - [`kernel_ft_fft`]: rustfft on a zero-padded uniform grid (fast, many k at once);
//! - [`kernel_ft_at`]: composite Gauss–Legendre quadrature (slow, obviously correct reference),
//!   the D = 1 case of [`radial_integral`], the quadrature the 3D transform of the pairing study
//!   uses too;
//! - analytic transforms: [`m4_ft`], [`gaussian_ft`], [`lucy_ft`] (= EFG quartic),
//!   [`efg_cubic_ft`].

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Zero-padding factor of [`kernel_ft_fft`]: the periodic FFT window is `FFT_PADDING` times the
/// support diameter 2ζ, so dk = π/(FFT_PADDING · ζ).
pub const FFT_PADDING: usize = 8;

/// Smallest number of sampling intervals across [−ζ, ζ] accepted by [`kernel_ft_fft`].
pub const FFT_MIN_INTERVALS: usize = 8;

/// Relative tolerance of the positivity tests: a sample counts as non-positive when
/// W*(k) ≤ `FT_ZERO_TOL` · W*(0). It sits well above the round-off and aliasing floor of
/// [`kernel_ft_fft`] at the default resolutions (≲ 1e-12 for n ≥ 256, see there) and well below
/// any physically meaningful value.
pub const FT_ZERO_TOL: f64 = 1.0e-9;

/// erfc(3) = ∫_{|x|>3} e^{−x²}/√π dx: the mass of the unit Gaussian (1/√π)e^{−x²} beyond the
/// truncation radius ζ = 3. Bound on |W*_trunc(k) − e^{−k²/4}| for the truncated, not
/// renormalised kernel; 2·erfc(3)/(1 − erfc(3)) ≈ 4.42e-5 bounds it for the renormalised one.
pub const GAUSSIAN_TRUNCATION_ERROR_ZETA3: f64 = 2.209_049_699_858_544e-5;

/// W*(k) of an even kernel by FFT. Returns `(k, W*(k))` for k = 0, dk, …, k_Nyquist.
///
/// Sampling: `n` intervals across the support diameter (rounded up to an even number ≥
/// [`FFT_MIN_INTERVALS`]), dx = 2ζ/n, samples x_m = m·dx with |m| ≤ n/2, so that x = ±ζ are grid
/// points and carry the trapezoid weight ½ (this matters only for kernels truncated with a jump,
/// like the Gaussian). The samples are zero-padded to N = [`FFT_PADDING`]·n points (window
/// 16ζ), placed in wrap-around order (x ≥ 0 first, x < 0 at the end) so that the transform of an
/// even kernel is real; the real part of dx·FFT is returned. k_j = j·dk, dk = 2π/(N dx) =
/// π/(8ζ), j = 0 … N/2, so k_Nyquist = π/dx = nπ/(2ζ).
///
/// Accuracy: by Poisson summation the value returned at k_j is exactly
/// Σ_p W*(k_j + 2πp/dx) (the trapezoid rule on a compactly supported function; padding adds no
/// error), so the error is the aliasing Σ_{p≠0} W*(k_j + 2πp/dx). For a kernel whose r-th
/// derivative jumps, W*(k) = O(k^{−r−1}) and the error is O(dx^{r+1}) — e.g. m4 (r = 3):
/// ≤ 2.2·16·(dx/(2π − k dx))⁴, ≈ 2e-9 at n = 256, ζ = 2, k ≤ 20 — and grows towards k_Nyquist,
/// where it is as large as W* itself. For a jump in W at ±ζ (truncated Gaussian) the half
/// weights make the rule second order: the Euler–Maclaurin error is (dx²/12)|g'(ζ) − g'(−ζ)| ≤
/// (dx²/6)(|W'(ζ)| + |k| W(ζ)), g = W cos kx (≈ 7e-9 at ζ = 3, dx = 0.01, k = 0). Only k well
/// below k_Nyquist should be trusted.
///
/// Invalid input (ζ not finite and positive) gives two empty vectors.
pub fn kernel_ft_fft(f: &dyn Fn(f64) -> f64, zeta: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
    if !(zeta.is_finite() && zeta > 0.0) {
        return (Vec::new(), Vec::new());
    }
    let n = n.max(FFT_MIN_INTERVALS);
    let n = n + n % 2;
    let half = n / 2;
    let big_n = FFT_PADDING * n;
    let dx = 2.0 * zeta / n as f64;
    let mut buf = vec![Complex::new(0.0, 0.0); big_n];
    for m in 0..=half {
        let x = m as f64 * dx;
        let w = if m == half { 0.5 } else { 1.0 };
        buf[m] = Complex::new(w * f(x), 0.0);
        if m > 0 {
            buf[big_n - m] = Complex::new(w * f(-x), 0.0);
        }
    }
    let mut planner = FftPlanner::<f64>::new();
    let fft = planner.plan_fft_forward(big_n);
    fft.process(&mut buf);
    let dk = 2.0 * PI / (big_n as f64 * dx);
    let len = big_n / 2 + 1;
    let k = (0..len).map(|j| j as f64 * dk).collect();
    let w = buf[..len].iter().map(|c| c.re * dx).collect();
    (k, w)
}

/// Gauss–Legendre points per panel of [`radial_integral`].
pub const GL_POINTS: usize = 16;
/// Piece length of [`radial_integral`] (units of h): every multiple is a panel edge, so every
/// breakpoint of the piecewise-polynomial kernels — B-spline knots at integers and
/// half-integers, the EFG cubic's q = ½, the Wendland and Lucy supports, the truncation of the
/// Gaussian at ζ = 3 — is one.
pub const PIECE: f64 = 0.25;
/// Largest k·(panel width) of [`radial_integral`] (radians of the oscillating factor per panel).
pub const MAX_PANEL_PHASE: f64 = 1.0;
/// Largest number of panels per piece of [`radial_integral`] (bounds the cost for huge k; the
/// phase bound then no longer holds, which happens only for k > 2.6e5).
pub const MAX_PANELS_PER_PIECE: usize = 1 << 16;

/// Gauss–Legendre nodes and weights on [−1, 1], n ≥ 2 (Newton iteration on the Legendre
/// polynomial from the Tricomi initial guesses; converged to machine precision).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let n = n.max(2);
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut z = (PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
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

/// The [`GL_POINTS`]-point rule, computed once.
fn gl_rule() -> &'static (Vec<f64>, Vec<f64>) {
    static RULE: OnceLock<(Vec<f64>, Vec<f64>)> = OnceLock::new();
    RULE.get_or_init(|| gauss_legendre(GL_POINTS))
}

/// The radial integral of the D-dimensional Fourier transform of a radial function g(|x|)
/// supported in |x| ≤ ζ (D = 1, 2 or 3, checked at compile time):
///
/// ```text
/// I_D(k) = ∫₀^ζ q^{D−1} g(q) φ_D(kq) dq,   φ₁ = cos,   φ₂ = J₀,   φ₃ = j₀ = sin x / x ([`sinc`])
/// ```
///
/// so that W*(k) = ∫ e^{−ik·x} W(|x|) d^D x = 2 I₁(k) in 1D ([`kernel_ft_at`]), 2π I₂(k) in 2D
/// (the Hankel transform; J₀ is the Bessel function of order 0, `libm::j0`, the FreeBSD msun
/// implementation, accurate to a few ulp) and 4π I₃(k) in 3D
/// (`pairing::wstar::Transform`, which normalises by I_D(0)). q and ζ in units of h, k in
/// units of 1/h. The one quadrature of the kernel transforms: [0, ζ] is cut at every multiple
/// of [`PIECE`], each piece into equal panels (at least two) with k·width ≤
/// [`MAX_PANEL_PHASE`] (at most [`MAX_PANELS_PER_PIECE`]), each panel integrated by
/// [`GL_POINTS`]-point Gauss–Legendre. The rule is exact for polynomials of degree
/// 2·[`GL_POINTS`] − 1 = 31: for a kernel that is polynomial between multiples of [`PIECE`]
/// (degree ≤ 11, times q² in 3D) the only error is the truncated Taylor series of φ_D over one
/// panel, of order [`MAX_PANEL_PHASE`]^32/32! ≈ 4e-36 — the result is exact to round-off
/// (~1e-16). Smooth pieces (Gaussian, mollifier) converge spectrally at this resolution.
pub fn radial_integral<const D: usize>(g: &dyn Fn(f64) -> f64, zeta: f64, k: f64) -> f64 {
    const { assert!(D >= 1 && D <= 3, "radial_integral: D = 1, 2 or 3") };
    let (nodes, weights) = gl_rule();
    let pieces = (zeta / PIECE).ceil() as usize;
    let mut sum = 0.0;
    for p in 0..pieces {
        let a = p as f64 * PIECE;
        let b = (a + PIECE).min(zeta);
        if b <= a {
            continue;
        }
        let panels = panels_of_piece(k, a, b);
        let width = (b - a) / panels as f64;
        for m in 0..panels {
            let lo = a + m as f64 * width;
            let (mid, half) = (lo + 0.5 * width, 0.5 * width);
            let mut s = 0.0;
            for (&x, &w) in nodes.iter().zip(weights) {
                let q = mid + half * x;
                s += if D == 1 {
                    w * g(q) * (k * q).cos()
                } else if D == 2 {
                    w * q * g(q) * libm::j0(k * q)
                } else {
                    w * q * q * g(q) * sinc(k * q)
                };
            }
            sum += s * half;
        }
    }
    sum
}

/// Panels of the piece [a, b] of [`radial_integral`] at wave number k.
fn panels_of_piece(k: f64, a: f64, b: f64) -> usize {
    ((k.abs() * (b - a) / MAX_PANEL_PHASE).ceil() as usize).clamp(2, MAX_PANELS_PER_PIECE)
}

/// The panels per piece [`radial_integral`] uses at wave number k on [0, ζ] (0 for an empty
/// piece): the quadrature rule is the same for every k with the same layout.
pub fn panel_layout(zeta: f64, k: f64) -> Vec<usize> {
    (0..(zeta / PIECE).ceil() as usize)
        .map(|p| {
            let a = p as f64 * PIECE;
            let b = (a + PIECE).min(zeta);
            if b <= a { 0 } else { panels_of_piece(k, a, b) }
        })
        .collect()
}

/// [`radial_integral`] for one panel layout ([`panel_layout`]) with the k-independent factors
/// w·q^{D−1}·g(q) of every node computed once: [`RadialRule::eval`] at a k of that layout is
/// `radial_integral::<D>(g, ζ, k)` to the last bit (the same products, added in the same order);
/// at any other k it is the same rule, a finite sum Σᵢ cᵢ φ_D(k qᵢ).
#[derive(Clone, Debug)]
pub struct RadialRule<const D: usize> {
    /// (q, w·q^{D−1}·g(q)) of every node, panel after panel.
    nodes: Vec<(f64, f64)>,
    /// Half-width of every panel (its nodes are the next [`GL_POINTS`] of `nodes`).
    halves: Vec<f64>,
    /// Σ half·Σ|c| over the panels: |eval(k)| ≤ abs_sum · max|φ_D|.
    abs_sum: f64,
}

impl<const D: usize> RadialRule<D> {
    /// The rule of `layout` for g on [0, ζ].
    pub fn new(g: &dyn Fn(f64) -> f64, zeta: f64, layout: &[usize]) -> Self {
        const { assert!(D >= 1 && D <= 3, "RadialRule: D = 1, 2 or 3") };
        let (gl_nodes, weights) = gl_rule();
        let (mut nodes, mut halves, mut abs_sum) = (Vec::new(), Vec::new(), 0.0);
        for (p, &panels) in layout.iter().enumerate() {
            let a = p as f64 * PIECE;
            let b = (a + PIECE).min(zeta);
            if b <= a || panels == 0 {
                continue;
            }
            let width = (b - a) / panels as f64;
            for m in 0..panels {
                let lo = a + m as f64 * width;
                let (mid, half) = (lo + 0.5 * width, 0.5 * width);
                let mut panel_abs = 0.0;
                for (&x, &w) in gl_nodes.iter().zip(weights) {
                    let q = mid + half * x;
                    let c = if D == 1 {
                        w * g(q)
                    } else if D == 2 {
                        w * q * g(q)
                    } else {
                        w * q * q * g(q)
                    };
                    panel_abs += c.abs();
                    nodes.push((q, c));
                }
                abs_sum += panel_abs * half;
                halves.push(half);
            }
        }
        Self {
            nodes,
            halves,
            abs_sum,
        }
    }

    /// Σ over panels of half·Σ c φ_D(kq).
    pub fn eval(&self, k: f64) -> f64 {
        let mut sum = 0.0;
        for (panel, &half) in self.nodes.chunks_exact(GL_POINTS).zip(&self.halves) {
            let mut s = 0.0;
            for &(q, c) in panel {
                s += c * if D == 1 {
                    (k * q).cos()
                } else if D == 2 {
                    libm::j0(k * q)
                } else {
                    sinc(k * q)
                };
            }
            sum += s * half;
        }
        sum
    }

    /// Number of nodes (terms of the sum).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the rule has no node (ζ ≤ 0).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Σ over panels of half·Σ|c|: |[`Self::eval`]| ≤ this (|φ_D| ≤ 1 on the real axis).
    pub fn abs_sum(&self) -> f64 {
        self.abs_sum
    }

    /// The largest node q.
    pub fn max_node(&self) -> f64 {
        self.nodes.iter().map(|n| n.0).fold(0.0, f64::max)
    }
}

/// W*(k) = 2∫₀^ζ W(x) cos(kx) dx = 2 [`radial_integral`]`::<1>`: the slow, obviously correct
/// reference for [`kernel_ft_fft`] and the analytic transforms (exact to round-off for kernels
/// that are polynomial between multiples of [`PIECE`], see there). Returns NaN for a non-finite
/// ζ or k, 0 for ζ ≤ 0.
pub fn kernel_ft_at(f: &dyn Fn(f64) -> f64, zeta: f64, k: f64) -> f64 {
    if !(zeta.is_finite() && k.is_finite()) {
        return f64::NAN;
    }
    if zeta <= 0.0 {
        return 0.0;
    }
    2.0 * radial_integral::<1>(f, zeta, k)
}

/// sin(y)/y (the spherical Bessel function j₀), with its Taylor series near 0.
pub fn sinc(y: f64) -> f64 {
    if y.abs() < 1e-3 {
        let y2 = y * y;
        // 1 − y²/6 + y⁴/120; the next term is < 2e-22 for |y| < 1e-3.
        1.0 - y2 / 6.0 * (1.0 - y2 / 20.0)
    } else {
        y.sin() / y
    }
}

/// Cubic B-spline m4, W(x) = (2/3) f(|x|), f = 1 − 1.5q² + 0.75q³ (q < 1), 0.25(2 − q)³
/// (1 ≤ q < 2): W*(k) = (sin(k/2)/(k/2))⁴.
///
/// Derivation: W is the cubic B-spline M₄ = B₀∗B₀∗B₀∗B₀ of the unit box B₀ = 1 on [−½, ½]
/// (M₄(0) = 2/3, M₄(1) = 1/6 = (2/3)·0.25), and B₀* = sin(k/2)/(k/2). W* ≥ 0 with zeros at
/// k = 2πn, n ≠ 0 (so |W*|² is not strictly positive there).
pub fn m4_ft(k: f64) -> f64 {
    let s = sinc(0.5 * k);
    let s2 = s * s;
    s2 * s2
}

/// EFG cubic spline weight of \[B00\] (ζ = 1) normalised to unit integral,
/// W(x) = (4/3) f_m4(2|x|) = 2(2/3 − 4x² + 4|x|³) (|x| ≤ ½), (8/3)(1 − |x|)³ (½ < |x| ≤ 1):
/// the m4 shape compressed by 2, so W*(k) = (sin(k/4)/(k/4))⁴.
pub fn efg_cubic_ft(k: f64) -> f64 {
    m4_ft(0.5 * k)
}

/// Untruncated Gaussian W(x) = (1/√π) e^{−x²}: W*(k) = e^{−k²/4}.
///
/// The SPEC kernel is truncated at ζ = 3 (and renormalised): its transform differs from this by
/// at most [`GAUSSIAN_TRUNCATION_ERROR_ZETA3`] (truncated) or 2·erfc(3)/(1 − erfc(3)) ≈ 4.4e-5
/// (renormalised). The truncation adds an oscillating tail ≈ 2W(3) sin(3k)/k that dominates
/// e^{−k²/4} for k ≳ 6, so the truncated kernel's W* changes sign although e^{−k²/4} does not.
pub fn gaussian_ft(k: f64) -> f64 {
    (-0.25 * k * k).exp()
}

/// Lucy kernel W(x) = (5/4)(1 + 3|x|)(1 − |x|)³ (ζ = 1), identical to the \[B00\] EFG quartic
/// spline 1 − 6q² + 8q³ − 3q⁴ normalised to unit integral:
///
/// ```text
/// W*(k) = (60/k⁴) (2 + cos k − 3 sin k / k)
/// ```
///
/// Derivation: with p(x) = 1 − 6x² + 8x³ − 3x⁴ (p(1) = p'(1) = p''(1) = 0, p'''(1) = −24,
/// p(0) = 1, p''(0) = −12, p'''(0) = 48, p'''' = −72), repeated integration by parts gives
/// ∫₀¹ p cos kx dx = (48 + 24 cos k − 72 sin k/k)/k⁴, times 2·(5/4). Small k (|k| < 2, where the
/// bracket cancels as k⁴/60): the moment series Σₙ (−1)ⁿ k²ⁿ M₂ₙ/(2n)!,
/// M₂ₙ = ∫ x²ⁿ W = (5/2)[1/(2n+1) − 6/(2n+3) + 8/(2n+4) − 3/(2n+5)] (W* = 1 − k²/21 + …).
/// Positive for all k (2 + cos k − 3 sin k/k > 0).
pub fn lucy_ft(k: f64) -> f64 {
    let k = k.abs();
    if k < 2.0 {
        // Terms decay like 2^{2n}/(2n)!: n ≤ 14 leaves < 1e-19.
        let k2 = k * k;
        let mut term = 1.0; // k^{2n}/(2n)! with sign
        let mut sum = 0.0;
        for n in 0..=14u32 {
            let nn = f64::from(2 * n);
            let moment =
                2.5 * (1.0 / (nn + 1.0) - 6.0 / (nn + 3.0) + 8.0 / (nn + 4.0) - 3.0 / (nn + 5.0));
            sum += term * moment;
            term *= -k2 / ((nn + 1.0) * (nn + 2.0));
        }
        sum
    } else {
        let k4 = k * k * k * k;
        60.0 / k4 * (2.0 + k.cos() - 3.0 * k.sin() / k)
    }
}

/// Index of the first sample with W*(k) ≤ [`FT_ZERO_TOL`]·W*(0) (index 0 if W*(0) ≤ 0).
fn first_nonpositive_index(w_star: &[f64]) -> Option<usize> {
    let w0 = *w_star.first()?;
    if w0.is_nan() || w0 <= 0.0 {
        return Some(0);
    }
    let floor = FT_ZERO_TOL * w0;
    w_star.iter().position(|&w| w.is_nan() || w <= floor)
}

/// \[V21\] A.72 / Requirement I on sampled data: true when every sample, starting with W*(0),
/// exceeds [`FT_ZERO_TOL`]·W*(0) (so |W*|² > 0 and W* > 0 on the grid). Pass only the resolved
/// part of a transform: a kernel whose transform decays below the tolerance (Gaussian beyond
/// k ≈ 9.1) cannot be shown positive there from samples, and is reported non-positive. An empty
/// slice is not positive.
pub fn autocorrelation_positive(w_star: &[f64]) -> bool {
    !w_star.is_empty() && first_nonpositive_index(w_star).is_none()
}

/// The first k at which W*(k) ≤ [`FT_ZERO_TOL`]·W*(0), if any (`k` and `w_star` as returned by
/// [`kernel_ft_fft`]; the shorter length is used). Same caveat as [`autocorrelation_positive`].
pub fn first_nonpositive_k(k: &[f64], w_star: &[f64]) -> Option<f64> {
    let len = k.len().min(w_star.len());
    first_nonpositive_index(&w_star[..len]).map(|i| k[i])
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
}
