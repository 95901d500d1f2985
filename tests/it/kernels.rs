//! Kernel checks, table-driven over every kernel of `sphstab::kernel::all()` and d = 1, 2, 3:
//! normalisation against an independent quadrature, compact support, derivatives against
//! finite differences, symmetry, inflection points, the thesis's mollifier constants, and the
//! `w`/`dw` helpers with dual numbers.

use std::f64::consts::PI;

use sphstab::kernel::{self, Kernel};
use sphstab::scalar::Dual;

const DIMS: [usize; 3] = [1, 2, 3];

const NAMES: [&str; 11] = [
    "m4",
    "m5",
    "m6",
    "wendland-c2",
    "wendland-c4",
    "wendland-c6",
    "gaussian",
    "lucy",
    "efg-cubic",
    "efg-quartic",
    "mollifier",
];

/// Piece boundaries of f in [0, ζ], written down here from the kernel definitions (SPEC §2)
/// rather than asked of the kernel.
fn pieces(name: &str) -> &'static [f64] {
    match name {
        "m4" => &[0.0, 1.0, 2.0],
        "m5" => &[0.0, 0.5, 1.5, 2.5],
        "m6" => &[0.0, 1.0, 2.0, 3.0],
        "wendland-c2" | "wendland-c4" | "wendland-c6" => &[0.0, 2.0],
        "gaussian" => &[0.0, 3.0],
        "efg-cubic" => &[0.0, 0.5, 1.0],
        "lucy" | "efg-quartic" | "mollifier" => &[0.0, 1.0],
        other => panic!("kernel `{other}` has no entry in the test's piece table"),
    }
}

/// f(q) for 0 ≤ q written as in the definitions (expanded polynomials, truncated powers),
/// independently of the library's factored forms.
fn reference_f(name: &str, dim: usize, q: f64) -> f64 {
    let p = |a: f64, n: i32| if q < a { (a - q).powi(n) } else { 0.0 };
    let t = q / 2.0;
    let inside = |z: f64, v: f64| if q < z { v } else { 0.0 };
    match (name, dim) {
        ("m4", _) if q < 1.0 => 1.0 - 1.5 * q * q + 0.75 * q.powi(3),
        ("m4", _) => 0.25 * p(2.0, 3),
        ("m5", _) => p(2.5, 4) - 5.0 * p(1.5, 4) + 10.0 * p(0.5, 4),
        ("m6", _) => p(3.0, 5) - 6.0 * p(2.0, 5) + 15.0 * p(1.0, 5),
        ("wendland-c2", 1) => inside(2.0, (1.0 - t).powi(3) * (1.0 + 3.0 * t)),
        ("wendland-c4", 1) => inside(2.0, (1.0 - t).powi(5) * (1.0 + 5.0 * t + 8.0 * t * t)),
        ("wendland-c6", 1) => inside(
            2.0,
            (1.0 - t).powi(7) * (1.0 + 7.0 * t + 19.0 * t * t + 21.0 * t.powi(3)),
        ),
        ("wendland-c2", _) => inside(2.0, (1.0 - t).powi(4) * (1.0 + 4.0 * t)),
        ("wendland-c4", _) => inside(
            2.0,
            (1.0 - t).powi(6) * (1.0 + 6.0 * t + 35.0 / 3.0 * t * t),
        ),
        ("wendland-c6", _) => inside(
            2.0,
            (1.0 - t).powi(8) * (1.0 + 8.0 * t + 25.0 * t * t + 32.0 * t.powi(3)),
        ),
        ("gaussian", _) => inside(3.0, (-q * q).exp()),
        ("lucy", _) => inside(1.0, (1.0 + 3.0 * q) * (1.0 - q).powi(3)),
        ("efg-cubic", _) if q <= 0.5 => 2.0 / 3.0 - 4.0 * q * q + 4.0 * q.powi(3),
        ("efg-cubic", _) => inside(
            1.0,
            4.0 / 3.0 - 4.0 * q + 4.0 * q * q - 4.0 / 3.0 * q.powi(3),
        ),
        ("efg-quartic", _) => inside(1.0, 1.0 - 6.0 * q * q + 8.0 * q.powi(3) - 3.0 * q.powi(4)),
        ("mollifier", _) => inside(1.0, (-1.0 / (1.0 - q * q)).exp() * (1.0 - q * q).powi(8)),
        (other, _) => panic!("kernel `{other}` has no reference formula in the test"),
    }
}

/// Gauss–Legendre rule on [−1, 1] with `n` points (Newton on the Legendre recurrence).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let legendre = |x: f64| {
        let (mut p_prev, mut p) = (1.0, x);
        for k in 2..=n {
            let k = k as f64;
            (p_prev, p) = (p, ((2.0 * k - 1.0) * x * p - (k - 1.0) * p_prev) / k);
        }
        (p, n as f64 * (p_prev - x * p) / (1.0 - x * x))
    };
    (1..=n)
        .map(|i| {
            let mut x = (PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            for _ in 0..50 {
                let (p, dp) = legendre(x);
                x -= p / dp;
            }
            let (_, dp) = legendre(x);
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// ∫ g over [a, b] split at `breaks`, with `panels` equal panels per piece of a 16-point rule.
fn integrate(g: &dyn Fn(f64) -> f64, breaks: &[f64], panels: usize) -> f64 {
    let rule = gauss_legendre(16);
    let mut total = 0.0;
    for piece in breaks.windows(2) {
        let width = (piece[1] - piece[0]) / panels as f64;
        for j in 0..panels {
            let mid = piece[0] + (j as f64 + 0.5) * width;
            let panel: f64 = rule
                .iter()
                .map(|&(x, w)| w * g(mid + 0.5 * width * x))
                .sum();
            total += 0.5 * width * panel;
        }
    }
    total
}

/// ∫ W dᵈx = |S^(d−1)| σ_d ∫_0^ζ q^(d−1) f(q) dq, with a refinement check on the quadrature.
fn unit_integral(k: &dyn Kernel, dim: usize) -> f64 {
    let surface = match dim {
        1 => 2.0,
        2 => 2.0 * PI,
        _ => 4.0 * PI,
    };
    let g = |q: f64| q.powi(dim as i32 - 1) * k.f(dim, q);
    let coarse = integrate(&g, pieces(k.name()), 32);
    let fine = integrate(&g, pieces(k.name()), 64);
    assert!(
        (fine - coarse).abs() <= 1e-13 * fine.abs(),
        "{} d={dim}: quadrature not converged",
        k.name()
    );
    surface * k.sigma(dim) * fine
}

/// Sample points in (0, ζ) at least `gap` away from every piece boundary.
fn interior_points(k: &dyn Kernel, n: usize, gap: f64) -> Vec<f64> {
    let breaks = pieces(k.name());
    (0..n)
        .map(|i| k.zeta() * (i as f64 + 0.5) / n as f64)
        .filter(|q| breaks.iter().all(|b| (q - b).abs() > gap))
        .collect()
}

#[test]
fn all_kernels_are_listed_in_spec_order_and_found_by_name() {
    let names: Vec<_> = kernel::all().iter().map(|k| k.name()).collect();
    assert_eq!(names, NAMES);
    for name in NAMES {
        assert_eq!(kernel::by_name(name).expect(name).name(), name);
    }
}

#[test]
fn unknown_kernel_name_is_an_error_listing_the_valid_names() {
    let err = kernel::by_name("nope").expect_err("`nope` is not a kernel");
    let message = err.to_string();
    assert!(
        message.contains("m4") && message.contains("mollifier"),
        "{message}"
    );
}

#[test]
fn gauss_legendre_rule_of_the_test_is_exact_for_degree_31() {
    let rule = gauss_legendre(16);
    let integral: f64 = rule
        .iter()
        .map(|&(x, w)| w * (x.powi(30) + x.powi(31)))
        .sum();
    assert!((integral - 2.0 / 31.0).abs() < 1e-15, "{integral}");
}

#[test]
fn every_kernel_integrates_to_one() {
    for &k in kernel::all() {
        for dim in DIMS {
            let total = unit_integral(k, dim);
            assert!(
                (total - 1.0).abs() <= 1e-10,
                "{} d={dim}: ∫W = {total}",
                k.name()
            );
        }
    }
}

#[test]
fn shape_function_matches_its_definition() {
    for &k in kernel::all() {
        for dim in DIMS {
            for i in 0..=400 {
                let q = 1.2 * k.zeta() * i as f64 / 400.0;
                let (got, want) = (k.f(dim, q), reference_f(k.name(), dim, q));
                assert!(
                    (got - want).abs() <= 1e-13 * want.abs().max(1.0),
                    "{} d={dim} q={q}: f = {got}, definition {want}",
                    k.name()
                );
            }
        }
    }
}

#[test]
fn kernel_and_derivatives_vanish_at_and_beyond_the_support() {
    for &k in kernel::all() {
        let z = k.zeta();
        for dim in DIMS {
            for q in [z, z + 1e-12, 1.5 * z, 10.0 * z, f64::INFINITY] {
                for (what, v) in [
                    ("f", k.f(dim, q)),
                    ("f'", k.df(dim, q)),
                    ("f''", k.d2f(dim, q)),
                ] {
                    assert_eq!(v, 0.0, "{} d={dim}: {what}({q}) = {v}", k.name());
                }
            }
        }
    }
}

#[test]
fn derivatives_match_central_finite_differences() {
    for &k in kernel::all() {
        let step = 1e-5 * k.zeta();
        for dim in DIMS {
            for q in interior_points(k, 50, 1e-3) {
                let fd1 = (k.f(dim, q + step) - k.f(dim, q - step)) / (2.0 * step);
                let fd2 = (k.df(dim, q + step) - k.df(dim, q - step)) / (2.0 * step);
                let (d1, d2) = (k.df(dim, q), k.d2f(dim, q));
                assert!(
                    (fd1 - d1).abs() <= 1e-6 * d1.abs().max(1.0),
                    "{} d={dim} q={q}: f' = {d1}, finite difference {fd1}",
                    k.name()
                );
                assert!(
                    (fd2 - d2).abs() <= 1e-6 * d2.abs().max(1.0),
                    "{} d={dim} q={q}: f'' = {d2}, finite difference {fd2}",
                    k.name()
                );
            }
        }
    }
}

#[test]
fn kernel_is_even_and_flat_at_the_origin() {
    let norm = |x: &[f64]| x.iter().map(|c| c * c).sum::<f64>().sqrt();
    for &k in kernel::all() {
        for dim in DIMS {
            assert_eq!(k.df(dim, 0.0), 0.0, "{} d={dim}: f'(0)", k.name());
            assert!(
                k.d2f(dim, 0.0) < 0.0,
                "{} d={dim}: f''(0) must be negative",
                k.name()
            );
            for i in 1..40 {
                let q = 1.1 * k.zeta() * i as f64 / 40.0;
                assert_eq!(k.f(dim, -q), k.f(dim, q), "{} d={dim} q={q}", k.name());
                // W at a point x and at −x, in physical units (h = 1.3).
                let x: Vec<f64> = (0..dim).map(|c| q * [0.6, -0.48, 0.64][c]).collect();
                let minus_x: Vec<f64> = x.iter().map(|c| -c).collect();
                let plus = kernel::w(k, dim, norm(&x), 1.3);
                let minus = kernel::w(k, dim, norm(&minus_x), 1.3);
                assert_eq!(plus, minus, "{} d={dim} x={x:?}", k.name());
            }
        }
    }
}

#[test]
fn inflection_point_is_the_first_sign_change_of_f2() {
    for &k in kernel::all() {
        for dim in DIMS {
            let qs = k.inflection(dim);
            let name = k.name();
            assert!(qs > 0.0 && qs < k.zeta(), "{name} d={dim}: q* = {qs}");
            assert!(
                k.d2f(dim, qs).abs() <= 1e-10,
                "{name} d={dim}: f''(q*) = {}",
                k.d2f(dim, qs)
            );
            assert!(
                k.d2f(dim, qs - 1e-6) < 0.0,
                "{name} d={dim}: f'' < 0 before q*"
            );
            assert!(
                k.d2f(dim, qs + 1e-6) > 0.0,
                "{name} d={dim}: f'' > 0 after q*"
            );
            for i in 0..1000 {
                let q = (qs - 1e-6) * i as f64 / 1000.0;
                assert!(
                    k.d2f(dim, q) < 0.0,
                    "{name} d={dim}: f''({q}) ≥ 0 before q*"
                );
            }
        }
    }
}

#[test]
fn mollifier_normalisation_matches_the_thesis_digest() {
    let k = kernel::by_name("mollifier").unwrap();
    for (dim, g) in DIMS
        .into_iter()
        .zip([4.8096769785, 8.7462202117, 16.3222083038])
    {
        let sigma = k.sigma(dim);
        assert!(
            (sigma - g).abs() <= 1e-8 * g,
            "d={dim}: σ = {sigma}, digest G = {g}"
        );
    }
    assert!((k.inflection(1) - 0.243315).abs() < 1e-6);
}

#[test]
fn gaussian_normalisation_matches_closed_forms() {
    let k = kernel::by_name("gaussian").unwrap();
    let e9 = (-9.0_f64).exp();
    assert!((k.sigma(2) - 1.0 / (PI * (1.0 - e9))).abs() <= 1e-14);
    // σ_1 = 1/(√π erf 3) and σ_3 = 1/(π(√π erf 3 − 6e⁻⁹)) share erf 3.
    let sqrt_pi_erf3 = 1.0 / k.sigma(1);
    assert!((k.sigma(3) - 1.0 / (PI * (sqrt_pi_erf3 - 6.0 * e9))).abs() <= 1e-14);
    assert!((k.sigma(1) - 0.564_202_047_051_383_3).abs() <= 1e-15);
}

#[test]
fn kernels_are_finite_for_any_finite_distance() {
    for &k in kernel::all() {
        for dim in DIMS {
            let mut q = f64::MIN_POSITIVE;
            while q < 1e300 {
                for x in [q, -q, k.zeta() - q, k.zeta() * (1.0 - 1e-16)] {
                    for v in [k.f(dim, x), k.df(dim, x), k.d2f(dim, x)] {
                        assert!(v.is_finite(), "{} d={dim} q={x}: {v}", k.name());
                    }
                }
                q *= 1.7;
            }
            assert!(k.sigma(dim).is_finite() && k.sigma(dim) > 0.0);
            let (lo, hi) = k.customary_h();
            assert!(0.0 < lo && lo < hi, "{}: customary h {lo}..{hi}", k.name());
            assert!(!k.reference().is_empty());
        }
    }
}

#[test]
fn dual_numbers_through_w_and_dw_give_the_analytic_derivatives() {
    let h = 1.3;
    for &k in kernel::all() {
        for dim in DIMS {
            for i in 0..60 {
                let r = 1.05 * k.zeta() * h * i as f64 / 60.0;
                let w = kernel::w(k, dim, Dual::new(r, 1.0), h);
                let dw = kernel::dw(k, dim, Dual::new(r, 1.0), h);
                let (dw0, d2w0) = (kernel::dw(k, dim, r, h), kernel::d2w(k, dim, r, h));
                assert_eq!(w.v, kernel::w(k, dim, r, h));
                assert!(
                    (w.d - dw0).abs() <= 1e-14 * dw0.abs().max(1.0),
                    "{} d={dim}",
                    k.name()
                );
                assert_eq!(dw.v, dw0);
                assert!(
                    (dw.d - d2w0).abs() <= 1e-14 * d2w0.abs().max(1.0),
                    "{} d={dim}",
                    k.name()
                );
            }
        }
    }
}
