//! Closed forms of [B00] and [V21] (src/vonneumann/closed_form.rs) and the kernel Fourier
//! transforms of [V21] App. A (src/vonneumann/transform.rs), against hand-derived values, the
//! papers' printed numbers and each other.

use approx::assert_relative_eq;
use nalgebra::{Matrix2, Schur};
use num_complex::Complex64;
use sphstab::vonneumann::closed_form::*;
use sphstab::vonneumann::transform::*;
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2};

// ---------------------------------------------------------------------------------------------
// Shapes
// ---------------------------------------------------------------------------------------------

/// Linear interpolation (hat) φ = 1 − |x| on |x| ≤ 1, φ' = −sign(x) (0 at x = 0, the one-sided
/// interior value ∓1 at x = ±1), φ'' = 0; support 1.
fn hat(x: f64) -> [f64; 3] {
    if x.abs() <= 1.0 {
        let d = if x > 0.0 {
            -1.0
        } else if x < 0.0 {
            1.0
        } else {
            0.0
        };
        [1.0 - x.abs(), d, 0.0]
    } else {
        [0.0; 3]
    }
}

/// A shape given only by its values at the lattice and half-lattice points (zero elsewhere):
/// `table` lists (x ≥ 0, [φ, φ', φ'']) and is extended as an even φ, φ'' and odd φ'.
fn lookup(table: &'static [(f64, [f64; 3])]) -> impl Fn(f64) -> [f64; 3] {
    move |x: f64| {
        for &(xt, [p0, p1, p2]) in table {
            if (x.abs() - xt).abs() < 1e-12 {
                let sgn = if x < 0.0 { -1.0 } else { 1.0 };
                return [p0, sgn * p1, p2];
            }
        }
        [0.0; 3]
    }
}

/// MLS-like central-difference shape of the Table II test: φ'(0) = 0, φ'(±1) = ∓½,
/// φ'(±½) = ∓1, φ(±½) = ½, φ(0) = 1, φ'' = 0.
const CENTRAL: &[(f64, [f64; 3])] = &[
    (0.0, [1.0, 0.0, 0.0]),
    (0.5, [0.5, -1.0, 0.0]),
    (1.0, [0.0, -0.5, 0.0]),
];

/// A shape with every eq. (93) sum non-zero: φ(0) = ½, φ''(0) = −2; at ±1: φ = ¼, φ' = ∓½,
/// φ'' = 1; at ±½: φ = ½, φ' = ∓1, φ'' = 1.
const RICH: &[(f64, [f64; 3])] = &[
    (0.0, [0.5, 0.0, -2.0]),
    (0.5, [0.5, -1.0, 1.0]),
    (1.0, [0.25, -0.5, 1.0]),
];

fn kappas(n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |i| PI * i as f64 / n as f64)
}

// ---------------------------------------------------------------------------------------------
// [B00] eq. 74 / 82 / 103 / 93 with the hat shape
// ---------------------------------------------------------------------------------------------

/// Hand derivation (hat, support 1, only j = 0, ±1 and j + ½ = ±½ contribute):
/// S₁ = φ'(1) sin κ + φ'(−1) sin(−κ) = −sin κ − sin κ = −2 sin κ;  S₂ = 0 (φ'' = 0);
/// S_S = φ'(½) sin(κ/2) + φ'(−½) sin(−κ/2) = −2 sin(κ/2).
/// eq. 82:  (1+σ̄) S₁² = 4(1+σ̄) sin²κ
/// eq. 74:  (1+σ̄) S₁² − σ̄(0 − S₁²) = 4(1+2σ̄) sin²κ
/// eq. 103: (1+σ̄)/2 (4 sin²κ + 4 sin²(κ/2)) = 2(1+σ̄)(sin²κ + sin²(κ/2))
/// eq. 93:  all φ'' sums vanish, brace = −S_M² − S_S², so (1+2σ̄)/2 (S_M² + S_S²) for any F.
#[test]
fn hat_shape_nodal_and_stress_point_closed_forms() {
    for sb in [-0.5, 0.0, 0.3, 1.0] {
        for kap in kappas(16) {
            let s2 = kap.sin().powi(2);
            let h2 = (0.5 * kap).sin().powi(2);
            let tol = 1e-14;
            assert_relative_eq!(
                b00_eq82_lagrangian_nodal(&hat, 1.0, sb, kap),
                4.0 * (1.0 + sb) * s2,
                epsilon = tol
            );
            assert_relative_eq!(
                b00_eq74_eulerian_nodal(&hat, 1.0, sb, kap),
                4.0 * (1.0 + 2.0 * sb) * s2,
                epsilon = tol
            );
            assert_relative_eq!(
                b00_eq103_lagrangian_stress_points(&hat, 1.0, sb, kap),
                2.0 * (1.0 + sb) * (s2 + h2),
                epsilon = tol
            );
            for f in [1.0, 0.8, 1.25] {
                assert_relative_eq!(
                    b00_eq93_eulerian_stress_points(&hat, 1.0, sb, f, kap),
                    2.0 * (1.0 + 2.0 * sb) * (s2 + h2),
                    epsilon = tol
                );
            }
        }
    }
}

/// eq. 93 literally, including the (F−1) terms, with the RICH table at κ = π/2, σ̄ = ½,
/// F = 5/4. With r = sin(π/4) = cos(π/4) = √2/2:
/// S_M = −2·½·sin(π/2) = −1 → S_M² = 1;   Σφ''_M(1−c_M) = 2·1·(1 − cos(π/2)) = 2;
/// S_S = −2·1·r = −√2 → S_S² = 2;          Σφ''_S = 2·1 = 2;
/// Σφ''_S c_S = 2r = √2;  Σφ_S c_S = 2·½·r = √2/2;  Σ(j+½)φ'_S c_S = ½(−1)r + (−½)(1)r = −√2/2;
/// Σ(j+½)φ''_S s_S = ½·r + (−½)(−r) = √2/2.
/// brace = 2 − 1 + 2 − 2 − (5/4)(√2·√2/2) + (¼)(√2)(−√2/2) + (¼)(√2/2)(−√2)
///       = 1 − 1.25 − 0.25 − 0.25 = −0.75
/// ω² = (1.5/2)(1 + 2) − (0.5/2)(−0.75) = 2.25 + 0.1875 = 2.4375.
#[test]
fn eq93_with_deformation_terms_hand_value() {
    let phi = lookup(RICH);
    let s = lattice_sums(&phi, 1.0, FRAC_PI_2);
    let r = SQRT_2 / 2.0;
    let tol = 1e-14;
    assert_relative_eq!(s.s1_master, -1.0, epsilon = tol);
    assert_relative_eq!(s.s2_master, 2.0, epsilon = tol);
    assert_relative_eq!(s.s1_stress, -SQRT_2, epsilon = tol);
    assert_relative_eq!(s.phi2_stress, 2.0, epsilon = tol);
    assert_relative_eq!(s.phi2_cos_stress, SQRT_2, epsilon = tol);
    assert_relative_eq!(s.phi_cos_stress, r, epsilon = tol);
    assert_relative_eq!(s.xphi1_cos_stress, -r, epsilon = tol);
    assert_relative_eq!(s.xphi2_sin_stress, r, epsilon = tol);
    assert_relative_eq!(
        b00_eq93_eulerian_stress_points(&phi, 1.0, 0.5, 1.25, FRAC_PI_2),
        2.4375,
        epsilon = 1e-13
    );
}

/// eq. 108 with the RICH table at κ = π/3 (cos = ½, sin = √3/2), α_s = 0.1:
/// S₁ = −2·½·√3/2 = −√3/2 → S₁² = ¾;  Σφ c = ½ + 2·¼·½ = ¾;  Σφ'' c = −2 + 2·1·½ = −1.
/// numerator = ¾ + 0.1·1 = 0.85;  denominator = (¾)² − 0.1·(−1)(¾) = 0.6375;  ω² = 4/3.
#[test]
fn eq108_least_squares_hand_value() {
    let phi = lookup(RICH);
    let (num, den) = b00_eq108_terms(&phi, 1.0, 0.1, PI / 3.0);
    assert_relative_eq!(num, 0.85, epsilon = 1e-14);
    assert_relative_eq!(den, 0.6375, epsilon = 1e-14);
    assert_relative_eq!(
        b00_eq108_least_squares(&phi, 1.0, 0.1, PI / 3.0),
        4.0 / 3.0,
        epsilon = 1e-13
    );
}

/// Small κ: the 2 sin²(κj/2) form keeps full relative accuracy. RICH table, hand formula
/// ω² = (1+2σ̄)·4·(½)² sin²κ − σ̄·2·1·2 sin²(κ/2). At κ = 1e-7 the naive 1 − cos κ would be
/// wrong by ~1e-2 relative.
#[test]
fn eq74_small_kappa_without_cancellation() {
    let phi = lookup(RICH);
    let sb = 0.7;
    for kap in [1e-3_f64, 1e-5, 1e-7] {
        let expect = (1.0 + 2.0 * sb) * kap.sin().powi(2) - sb * 4.0 * (0.5 * kap).sin().powi(2);
        assert_relative_eq!(
            b00_eq74_eulerian_nodal(&phi, 1.0, sb, kap),
            expect,
            epsilon = 0.0,
            max_relative = 1e-12
        );
    }
}

/// "Note that for small κ, the RHS in Equations (32) and (82) are approximately equal" [B00]:
/// with the central-difference shape S₁ = −sin κ, so eq. 82 = (1+σ̄) sin²κ = eq. 32 (1 + O(κ²)).
#[test]
fn eq82_tends_to_continuum_eq32() {
    let phi = lookup(CENTRAL);
    for sb in [-0.3, 0.0, 0.5] {
        for kap in [1e-4, 1e-3, 1e-2] {
            let c = b00_eq32_continuum(sb, kap);
            let d = b00_eq82_lagrangian_nodal(&phi, 1.5, sb, kap);
            assert_relative_eq!(d, c, epsilon = 0.0, max_relative = kap * kap);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// [B00] Table II
// ---------------------------------------------------------------------------------------------

fn max_over_kappa(f: impl Fn(f64) -> f64) -> (f64, f64) {
    kappas(4096).map(|k| (f(k), k)).fold(
        (f64::NEG_INFINITY, 0.0),
        |a, b| if b.0 > a.0 { b } else { a },
    )
}

/// Table II rows 1 and 3 with the central-difference shape (σ = 0, support 1.5):
/// eq. 82: S₁ = −sin κ, ω² = sin²κ, max 1 at κ = π/2.
/// eq. 103: S_S = −2 sin(κ/2), ω² = (sin²κ + 4 sin²(κ/2))/2 = 2s²(2 − s²), s = sin(κ/2),
/// increasing in s², max 2 at κ = π.
/// eq. 74 at σ = 0 equals eq. 82 ("both kernels").
#[test]
fn table2_nodal_and_lagrangian_stress_points() {
    let phi = lookup(CENTRAL);
    let rows = b00_table2();
    assert_eq!(rows.len(), 3);

    let (m82, k82) = max_over_kappa(|k| b00_eq82_lagrangian_nodal(&phi, 1.5, 0.0, k));
    assert_relative_eq!(m82, rows[0].1, epsilon = 1e-14);
    assert_relative_eq!(k82, FRAC_PI_2, epsilon = 1e-12);
    let (m74, _) = max_over_kappa(|k| b00_eq74_eulerian_nodal(&phi, 1.5, 0.0, k));
    assert_relative_eq!(m74, rows[0].1, epsilon = 1e-14);

    let (m103, k103) = max_over_kappa(|k| b00_eq103_lagrangian_stress_points(&phi, 1.5, 0.0, k));
    assert_relative_eq!(m103, rows[2].1, epsilon = 1e-14);
    assert_relative_eq!(k103, PI, epsilon = 1e-12);
}

/// Table II row 2 (Eulerian stress points, 4.0) is not what eq. 93 gives: at σ = 0 eq. 93 is
/// eq. 103 term by term (for any F and any shape), so its maximum for this shape is 2.0 — half
/// the printed value. This test pins the discrepancy (documented on `b00_table2`).
#[test]
fn table2_eulerian_stress_point_row_is_twice_eq93() {
    let central = lookup(CENTRAL);
    let rich = lookup(RICH);
    for kap in kappas(64) {
        for f in [0.9, 1.0, 1.1] {
            for phi in [&central as &dyn Fn(f64) -> [f64; 3], &rich] {
                assert_relative_eq!(
                    b00_eq93_eulerian_stress_points(phi, 1.0, 0.0, f, kap),
                    b00_eq103_lagrangian_stress_points(phi, 1.0, 0.0, kap),
                    epsilon = 1e-14
                );
            }
        }
    }
    let (m93, _) = max_over_kappa(|k| b00_eq93_eulerian_stress_points(&central, 1.5, 0.0, 1.0, k));
    assert_relative_eq!(m93, 2.0, epsilon = 1e-14);
    assert_relative_eq!(b00_table2()[1].1 / m93, 2.0, epsilon = 1e-14);
}

// ---------------------------------------------------------------------------------------------
// [V21] Appendix B (Swegle)
// ---------------------------------------------------------------------------------------------

fn swegle_base() -> SwegleParams {
    // m4 kernel with h = ΔX = 1 at the nearest neighbour (q = 1): W = (2/3) f,
    // dW/dr = (2/3)(−3q + 2.25q²) = −0.5 → W' = +0.5; d²W/dr² = (2/3)(−3 + 4.5q) = 1.
    SwegleParams {
        m: 1.0,
        rho: 1.0,
        rho0: 1.0,
        k_bulk: 1.0,
        w1: 0.5,
        w2: 1.0,
        t_stress: 0.2,
        alpha: 0.0,
    }
}

/// At λ = 2ΔX (κ = π) the stress-variation term vanishes and s reduces to (B.115). B.115 as
/// printed, −2mΔtW''T/ρ², is Δt·s/2 (errata on `swegle_s_rate`): s(π) = −4mW''T/ρ².
#[test]
fn swegle_s_at_cutoff_is_b115() {
    let dt = 0.01;
    for (w2, t) in [(1.0, 0.2), (1.0, -0.3), (-0.7, 0.4), (0.3, 0.0)] {
        let mut p = swegle_base();
        p.w2 = w2;
        p.t_stress = t;
        let b115_printed = -2.0 * p.m * dt * w2 * t / (p.rho * p.rho);
        let s = swegle_s_rate(&p, PI);
        assert_relative_eq!(s * dt, 2.0 * b115_printed, epsilon = 1e-15);
        // independent of K: change it, s(π) does not move (sin²π ≈ 1.5e-32)
        p.k_bulk = 100.0;
        assert_relative_eq!(swegle_s_rate(&p, PI), s, epsilon = 1e-13);
        // B.114 (s > 0) at the cut-off is V21's reversed criterion B.116
        assert_eq!(s > 0.0, swegle_difference_unstable(w2, t));
        // and the sum form's ω²(π) < 0 is Swegle's
        assert_eq!(swegle_omega2_sum(&p, PI) < 0.0, swegle_sum_unstable(w2, t));
    }
}

/// Stress term stabilising for W' > 0: with T = 0, s ≤ 0 and the two forms coincide.
#[test]
fn swegle_unstressed_lattice_is_neutral() {
    let mut p = swegle_base();
    p.t_stress = 0.0;
    for kap in kappas(32) {
        let s = swegle_s_rate(&p, kap);
        assert!(s <= 0.0);
        assert_relative_eq!(swegle_omega2_sum(&p, kap), -s, epsilon = 1e-15);
        assert_relative_eq!(s, -2.0 * kap.sin().powi(2) * 0.5, epsilon = 1e-15);
    }
}

fn schur_eigenvalues(a: Matrix2<f64>) -> Vec<Complex64> {
    let schur = Schur::try_new(a, 1e-14, 1000).expect("2×2 Schur converges");
    let ev = schur.complex_eigenvalues();
    let mut v: Vec<Complex64> = ev.iter().map(|c| Complex64::new(c.re, c.im)).collect();
    v.sort_by(|x, y| y.norm().total_cmp(&x.norm()).then(y.im.total_cmp(&x.im)));
    v
}

/// Amplification roots: Vieta (product det A = 1 − rΔt, sum tr A = 2 + sΔt² − rΔt) and the
/// eigenvalues of A = L⁻¹R built directly from (B.104). The printed constant 1 + rΔt of (B.108)
/// would fail the product check whenever α > 0.
#[test]
fn swegle_amplification_vieta_and_matrix() {
    for (alpha, t, dt, kap) in [
        (0.0, 0.2, 0.5, 2.0),
        (0.3, 0.2, 0.5, 2.0),
        (0.3, -0.4, 1.9, PI),
        (1.5, 0.6, 0.1, 3.0),
        (0.1, 0.0, 2.5, 1.0),
    ] {
        let mut p = swegle_base();
        p.alpha = alpha;
        p.t_stress = t;
        let s = swegle_s_rate(&p, kap);
        let r = swegle_r_rate(&p, kap);
        assert!(r >= 0.0);
        let [l1, l2] = swegle_amplification(&p, kap, dt);
        let prod = l1 * l2;
        let sum = l1 + l2;
        assert_relative_eq!(prod.re, 1.0 - r * dt, epsilon = 1e-13);
        assert_relative_eq!(prod.im, 0.0, epsilon = 1e-13);
        assert_relative_eq!(sum.re, 2.0 + s * dt * dt - r * dt, epsilon = 1e-13);
        assert_relative_eq!(sum.im, 0.0, epsilon = 1e-13);
        if alpha > 0.0 {
            assert!((prod.re - (1.0 + r * dt)).abs() > 1e-6);
        }

        // A = L⁻¹R, L = [[1, 0], [−Δt, 1]], R = [[1 − rΔt, sΔt], [0, 1]]
        let l = Matrix2::new(1.0, 0.0, -dt, 1.0);
        let rm = Matrix2::new(1.0 - r * dt, s * dt, 0.0, 1.0);
        let a = l.try_inverse().expect("L is unit lower triangular") * rm;
        let ev = schur_eigenvalues(a);
        let mut mine = [l1, l2];
        mine.sort_by(|x, y| y.norm().total_cmp(&x.norm()).then(y.im.total_cmp(&x.im)));
        for (x, y) in mine.iter().zip(ev.iter()) {
            assert_relative_eq!(x.re, y.re, epsilon = 1e-9);
            assert_relative_eq!(x.im, y.im, epsilon = 1e-9);
        }
    }
}

/// Leapfrog on the neutral lattice: |λ| = 1 up to the CFL limit Δt = 2/ω, then |λ| > 1.
#[test]
fn swegle_amplification_cfl() {
    let mut p = swegle_base();
    p.t_stress = 0.0;
    let kap = FRAC_PI_2;
    let omega = (-swegle_s_rate(&p, kap)).sqrt();
    let dt_crit = 2.0 / omega;
    let [a, b] = swegle_amplification(&p, kap, 0.99 * dt_crit);
    assert_relative_eq!(a.norm(), 1.0, epsilon = 1e-12);
    assert_relative_eq!(b.norm(), 1.0, epsilon = 1e-12);
    let [a, _] = swegle_amplification(&p, kap, 1.01 * dt_crit);
    assert!(a.norm() > 1.0 + 1e-3);
}

// ---------------------------------------------------------------------------------------------
// [V21] A.72 and the kernel transforms
// ---------------------------------------------------------------------------------------------

/// (A.72): c = 1 is the local continuum κ²; c = 0 with m4 is κ² sinc⁸(κ/2).
#[test]
fn v21_a72_limits() {
    for kap in [0.0, 0.5, 2.0, PI] {
        assert_relative_eq!(v21_a72_continuum(1.0, 0.3, kap), kap * kap, epsilon = 1e-15);
        let w = m4_ft(kap);
        assert_relative_eq!(
            v21_a72_continuum(0.0, w, kap),
            kap * kap * w * w,
            epsilon = 1e-15
        );
        assert_relative_eq!(
            v21_a72_continuum(0.25, w, kap),
            kap * kap * (0.25 + 0.75 * w * w),
            epsilon = 1e-15
        );
    }
}

fn m4(x: f64) -> f64 {
    let q = x.abs();
    let f = if q < 1.0 {
        1.0 - 1.5 * q * q + 0.75 * q * q * q
    } else if q < 2.0 {
        0.25 * (2.0 - q).powi(3)
    } else {
        0.0
    };
    2.0 / 3.0 * f
}

fn gaussian(x: f64) -> f64 {
    (-x * x).exp() / PI.sqrt()
}

/// m4: quadrature vs analytic to 1e-13 (16-point Gauss–Legendre is exact on each cubic piece up
/// to the cosine, whose panel error is far below round-off); FFT (n = 256, dx = 1/64) vs
/// analytic to 1e-8 on k ≤ 20: the aliasing bound 2.2·16·(dx/(2π − k dx))⁴ ≈ 2e-9.
#[test]
fn m4_transform_fft_quadrature_analytic() {
    for k in [0.0, 1e-6, 0.3, 1.0, PI, 2.0 * PI, 7.5, 20.0, 57.0] {
        assert_relative_eq!(kernel_ft_at(&m4, 2.0, k), m4_ft(k), epsilon = 1e-13);
    }
    let (ks, ws) = kernel_ft_fft(&m4, 2.0, 256);
    assert_relative_eq!(ks[1] - ks[0], PI / 16.0, epsilon = 1e-15);
    assert_eq!(ks.len(), 8 * 256 / 2 + 1);
    assert_relative_eq!(*ks.last().unwrap(), 256.0 * PI / 4.0, epsilon = 1e-10);
    let mut checked = 0;
    for (&k, &w) in ks.iter().zip(ws.iter()).filter(|(k, _)| **k <= 20.0) {
        assert_relative_eq!(w, m4_ft(k), epsilon = 1e-8);
        if checked % 7 == 0 {
            assert_relative_eq!(w, kernel_ft_at(&m4, 2.0, k), epsilon = 1e-8);
        }
        checked += 1;
    }
    assert!(checked > 100);
    // sinc⁴ touches zero at k = 2π: m4's |W*|² is not strictly positive.
    assert_relative_eq!(
        first_nonpositive_k(&ks, &ws).unwrap(),
        2.0 * PI,
        epsilon = 1e-12
    );
    assert!(!autocorrelation_positive(&ws));
}

/// Gaussian truncated at ζ = 3 (not renormalised): W*(0) = 1 − erfc(3) by quadrature to 1e-13;
/// |W*_trunc − e^{−k²/4}| ≤ erfc(3) (exact bound: the discarded mass). FFT (n = 600, dx = 0.01)
/// vs quadrature: the trapezoid rule with half weights at the jumps ±3 has the Euler–Maclaurin
/// error (dx²/12)|g'(3) − g'(−3)| ≤ (dx²/6)(|W'(3)| + k W(3)), g = W cos kx, W(3) = e^{−9}/√π
/// ≈ 7.0e-5, |W'(3)| = 6 W(3): ≈ 7e-9 at k = 0; the test allows 1.2× that bound.
#[test]
fn gaussian_transform_fft_quadrature_analytic() {
    let trunc = |x: f64| if x.abs() <= 3.0 { gaussian(x) } else { 0.0 };
    assert_relative_eq!(
        kernel_ft_at(&trunc, 3.0, 0.0),
        1.0 - GAUSSIAN_TRUNCATION_ERROR_ZETA3,
        epsilon = 1e-13
    );
    for k in [0.0, 0.5, 1.0, 2.0, 4.0, 6.0, 10.0] {
        let q = kernel_ft_at(&trunc, 3.0, k);
        assert!((q - gaussian_ft(k)).abs() <= GAUSSIAN_TRUNCATION_ERROR_ZETA3);
    }
    let (ks, ws) = kernel_ft_fft(&trunc, 3.0, 600);
    for (&k, &w) in ks
        .iter()
        .zip(ws.iter())
        .filter(|(k, _)| **k <= 15.0)
        .step_by(3)
    {
        let w3 = gaussian(3.0);
        let em = 1e-4 / 6.0 * (6.0 * w3 + k * w3);
        assert_relative_eq!(w, kernel_ft_at(&trunc, 3.0, k), epsilon = 1.2 * em + 1e-13);
        assert!((w - gaussian_ft(k)).abs() <= GAUSSIAN_TRUNCATION_ERROR_ZETA3 + 1.2 * em);
    }
    // The truncation tail ≈ 2W(3) sin(3k)/k makes W* change sign although e^{−k²/4} does not.
    let first = first_nonpositive_k(&ks, &ws).expect("truncated Gaussian W* goes negative");
    // The exact transform (1/√π)∫₋₃³ e^{−x²} cos kx dx first changes sign at k* = 7.5743823
    // (computed independently: composite Simpson with 20,000 intervals and bisection, in a
    // throw-away script; W* = +5.3e-6 at the grid point 57π/24 below it and −8.2e-7 at 58π/24
    // above it, both far above the FFT error ≈ 1e-8), so the FFT's first non-positive grid
    // point must be the first grid point above k*.
    let kstar = 7.5743823;
    let i = ks.iter().position(|&k| k == first).unwrap();
    assert!(
        ks[i - 1] < kstar && kstar <= first,
        "first non-positive k = {first}"
    );
    assert!(ws.iter().any(|&w| w < -1e-7));
}

/// Lucy (= normalised EFG quartic) and EFG cubic: analytic vs quadrature, across the series /
/// closed-form switch of `lucy_ft` at k = 2; Lucy's W* stays positive.
#[test]
fn lucy_and_efg_cubic_transforms() {
    let lucy = |x: f64| {
        let q = x.abs();
        if q < 1.0 {
            1.25 * (1.0 + 3.0 * q) * (1.0 - q).powi(3)
        } else {
            0.0
        }
    };
    let efg_cubic = |x: f64| {
        let q = x.abs();
        if q <= 0.5 {
            2.0 * (2.0 / 3.0 - 4.0 * q * q + 4.0 * q * q * q)
        } else if q <= 1.0 {
            2.0 * (4.0 / 3.0) * (1.0 - q).powi(3)
        } else {
            0.0
        }
    };
    for k in [0.0, 1e-4, 0.5, 1.999_999, 2.0, 2.000_001, 3.0, 10.0, 40.0] {
        assert_relative_eq!(lucy_ft(k), kernel_ft_at(&lucy, 1.0, k), epsilon = 1e-13);
        assert_relative_eq!(
            efg_cubic_ft(k),
            kernel_ft_at(&efg_cubic, 1.0, k),
            epsilon = 1e-13
        );
    }
    assert_relative_eq!(lucy_ft(1e-3), 1.0 - 1e-6 / 21.0, epsilon = 1e-15);
    let (ks, ws) = kernel_ft_fft(&lucy, 1.0, 256);
    let upto = ks.iter().position(|&k| k > 50.0).unwrap();
    assert!(autocorrelation_positive(&ws[..upto]));
    assert_eq!(first_nonpositive_k(&ks[..upto], &ws[..upto]), None);
}

/// Degenerate inputs: no panic, no NaN from the FFT path.
#[test]
fn transform_degenerate_inputs() {
    let (k, w) = kernel_ft_fft(&m4, f64::NAN, 64);
    assert!(k.is_empty() && w.is_empty());
    let (k, w) = kernel_ft_fft(&m4, 2.0, 1);
    assert_eq!(k.len(), FFT_PADDING * FFT_MIN_INTERVALS / 2 + 1);
    assert!(w.iter().all(|v| v.is_finite()));
    assert!(!autocorrelation_positive(&[]));
    assert!(!autocorrelation_positive(&[-1.0, 2.0]));
}
