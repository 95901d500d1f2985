//! Shape-function families: reproducing conditions on irregular point sets (at nodes and
//! mid-points), and the exact (dual-number) derivatives with respect to node positions against
//! central finite differences — the independent check of what the von Neumann engine
//! differentiates through.

use sphstab::kernel;
use sphstab::scalar::Dual;
use sphstab::shape::{KernelParams, ShapeFamily, eval, eval_with_second};

/// An irregular 1D point set: x_j = j + 0.23 sin(1.7 j), volumes from the mid-point rule.
fn points() -> (Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = (-8..=8)
        .map(|j| j as f64 + 0.23 * (1.7 * j as f64).sin())
        .collect();
    let v = (0..x.len())
        .map(|i| {
            let l = if i > 0 { x[i] - x[i - 1] } else { x[1] - x[0] };
            let r = if i + 1 < x.len() { x[i + 1] - x[i] } else { l };
            0.5 * (l + r)
        })
        .collect();
    (x, v)
}

fn at(family: ShapeFamily, kern: &str, h: f64, xe: f64) -> Vec<(f64, f64)> {
    let (x, v) = points();
    let kp = KernelParams {
        kernel: kernel::by_name(kern).unwrap(),
        h,
    };
    let nodes: Vec<(f64, f64)> = x
        .iter()
        .zip(&v)
        .filter(|(xj, _)| (**xj - xe).abs() < kp.support())
        .map(|(&xj, &vj)| (xj - xe, vj))
        .collect();
    let mut out = Vec::new();
    eval(family, kp, &nodes, xe, &mut out).unwrap();
    // return (φ_J, φ'_J) paired with x_J in the second slot for the sums below
    out
}

fn nodes_near(kern: &str, h: f64, xe: f64) -> Vec<f64> {
    let (x, _) = points();
    let r = kernel::by_name(kern).unwrap().zeta() * h;
    x.into_iter().filter(|xj| (xj - xe).abs() < r).collect()
}

const EVAL_POINTS: [f64; 6] = [0.0, 0.5, -1.27, 2.31, 0.23 * 1.7f64, -2.5];

#[test]
fn mls_reproduces_linear_functions_and_derivatives() {
    for kern in ["m4", "wendland-c2", "efg-quartic", "gaussian"] {
        for h in [1.3, 2.0] {
            let h = if kernel::by_name(kern).unwrap().zeta() < 2.0 {
                2.0 * h
            } else {
                h
            };
            for xe in EVAL_POINTS {
                let phi = at(ShapeFamily::Mls, kern, h, xe);
                let xs = nodes_near(kern, h, xe);
                let (mut s0, mut s1, mut d0, mut d1) = (0.0, 0.0, 0.0, 0.0);
                for ((p, dp), xj) in phi.iter().zip(&xs) {
                    s0 += p;
                    s1 += p * (3.0 * xj - 2.0);
                    d0 += dp;
                    d1 += dp * (3.0 * xj - 2.0);
                }
                assert!((s0 - 1.0).abs() < 1e-12, "{kern} h={h} x={xe}: Σφ = {s0}");
                assert!((s1 - (3.0 * xe - 2.0)).abs() < 1e-12, "{kern}: linear {s1}");
                assert!(d0.abs() < 1e-12, "{kern}: Σφ' = {d0}");
                assert!(
                    (d1 - 3.0).abs() < 1e-12,
                    "{kern}: derivative of linear {d1}"
                );
            }
        }
    }
}

#[test]
fn shepard_reproduces_constants_and_corrected_reproduces_linear_derivatives() {
    for kern in ["m4", "m6", "lucy"] {
        let h = if kern == "lucy" { 2.6 } else { 1.4 };
        for xe in EVAL_POINTS {
            let xs = nodes_near(kern, h, xe);
            let sh = at(ShapeFamily::Shepard, kern, h, xe);
            let s0: f64 = sh.iter().map(|p| p.0).sum();
            let d0: f64 = sh.iter().map(|p| p.1).sum();
            assert!(
                (s0 - 1.0).abs() < 1e-13 && d0.abs() < 1e-12,
                "{kern} x={xe}: shepard {s0} {d0}"
            );
            let co = at(ShapeFamily::Corrected, kern, h, xe);
            let g0: f64 = co.iter().map(|p| p.1).sum();
            let g1: f64 = co.iter().zip(&xs).map(|(p, x)| p.1 * (5.0 * x + 1.0)).sum();
            assert!(
                g0.abs() < 1e-12 && (g1 - 5.0).abs() < 1e-12,
                "{kern} x={xe}: corrected {g0} {g1}"
            );
            // plain SPH does not reproduce the derivative on an irregular set (sanity: the test can fail)
            let sp = at(ShapeFamily::Sph, kern, h, xe);
            let s1: f64 = sp.iter().zip(&xs).map(|(p, x)| p.1 * (5.0 * x + 1.0)).sum();
            assert!(
                (s1 - 5.0).abs() > 1e-6,
                "{kern} x={xe}: sph unexpectedly exact"
            );
        }
    }
}

/// ∂φ'_J(x)/∂x_K by dual numbers (what the engine uses) against central differences of the
/// f64 evaluation with node K moved by ±ε, for every family, J, K; plus φ'' (dual in x)
/// against differences of φ'.
#[test]
fn dual_derivatives_through_shape_functions_match_finite_differences() {
    let (x, v) = points();
    for family in [
        ShapeFamily::Sph,
        ShapeFamily::Shepard,
        ShapeFamily::Mls,
        ShapeFamily::Corrected,
    ] {
        for (kern, h) in [("m4", 1.3), ("efg-quartic", 1.7), ("wendland-c4", 1.5)] {
            let kp = KernelParams {
                kernel: kernel::by_name(kern).unwrap(),
                h,
            };
            let xe = 0.37;
            let idx: Vec<usize> = (0..x.len())
                .filter(|&j| (x[j] - xe).abs() < kp.support() - 0.05)
                .collect();
            let base = |shift: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
                let nodes: Vec<(f64, f64)> =
                    idx.iter().map(|&j| (x[j] + shift(j) - xe, v[j])).collect();
                let mut out = Vec::new();
                eval(family, kp, &nodes, xe, &mut out).unwrap();
                out
            };
            let eps = 1e-6;
            for &kk in &idx {
                let nodes: Vec<(Dual, Dual)> = idx
                    .iter()
                    .map(|&j| {
                        (
                            Dual::new(x[j] - xe, if j == kk { 1.0 } else { 0.0 }),
                            Dual::new(v[j], 0.0),
                        )
                    })
                    .collect();
                let mut dual = Vec::new();
                eval(family, kp, &nodes, xe, &mut dual).unwrap();
                let plus = base(&|j| if j == kk { eps } else { 0.0 });
                let minus = base(&|j| if j == kk { -eps } else { 0.0 });
                for (n, d) in dual.iter().enumerate() {
                    let fd_phi = (plus[n].0 - minus[n].0) / (2.0 * eps);
                    let fd_dphi = (plus[n].1 - minus[n].1) / (2.0 * eps);
                    assert!(
                        (d.0.d - fd_phi).abs() < 1e-6 * (1.0 + fd_phi.abs()),
                        "{family:?} {kern}: ∂φ/∂x_K"
                    );
                    assert!(
                        (d.1.d - fd_dphi).abs() < 1e-6 * (1.0 + fd_dphi.abs()),
                        "{family:?} {kern}: ∂φ'/∂x_K {} vs {fd_dphi}",
                        d.1.d
                    );
                }
            }
            // second derivative in x
            let rel: Vec<(f64, f64)> = idx.iter().map(|&j| (x[j] - xe, v[j])).collect();
            let w = eval_with_second(family, kp, &rel, xe).unwrap();
            let sh = |dx: f64| -> Vec<(f64, f64)> {
                let nodes: Vec<(f64, f64)> = idx.iter().map(|&j| (x[j] - xe - dx, v[j])).collect();
                let mut out = Vec::new();
                eval(family, kp, &nodes, xe + dx, &mut out).unwrap();
                out
            };
            let (p, m) = (sh(eps), sh(-eps));
            for (n, wn) in w.iter().enumerate() {
                let fd = (p[n].1 - m[n].1) / (2.0 * eps);
                assert!(
                    (wn[2] - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                    "{family:?} {kern}: φ'' {} vs {fd}",
                    wn[2]
                );
            }
        }
    }
}
