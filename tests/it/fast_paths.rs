//! The faster routes of the 1D engine (issue 13) against the exact per-κ matrix route
//! (`Linearisation::omega2`, the Bloch sum of every Jacobian entry with its own sin/cos):
//!
//! - the tabulated route (`omega2_tabulated`: phases from a `PhaseTable`, only the entries of
//!   the reduced stiffness) performs the same operations in the same order, so it must agree to
//!   the last bit;
//! - the cosine series (`cosine_series`: products of Fourier sums turned into one sum via
//!   (e^{−iκi} − 1)(e^{−iκj} − 1) = (e^{−iκ(i+j)} − 1) − (e^{−iκi} − 1) − (e^{−iκj} − 1)) rounds
//!   differently; it must agree to 1e-13 of the curve's scale, and keep full *relative*
//!   accuracy as κ → 0 (the reason for the form cos κm − 1 = −2 sin²(κm/2));
//! - the pre-stress enters every 1D rate function linearly, so the Jacobian columns are affine
//!   in σ̄ (the atlas interpolates them, `Linearisation::lerp`): the columns at σ̄ = 0 must equal
//!   the midpoint of those at ±0.9 to rounding, and a wrong interpolation must be detected.

use sphstab::analysis::Query;
use sphstab::forms::FormKind;
use sphstab::kernel;
use sphstab::vonneumann::linearise::PhaseTable;

/// The forms of the 1D chain (every form but the solid-shear ones of D ≥ 2).
fn forms() -> Vec<FormKind> {
    FormKind::ALL
        .iter()
        .map(|f| f.0)
        .filter(|f| !f.needs_2d())
        .collect()
}

#[test]
fn tabulated_route_is_bitwise_the_matrix_route() {
    let kappas: Vec<f64> = (1..=97)
        .map(|i| std::f64::consts::PI * i as f64 / 97.0)
        .collect();
    let mut n = 0;
    for form in forms() {
        for k in ["m4", "wendland-c4", "gaussian", "efg-quartic"] {
            for (h, s) in [(1.3, 0.05), (2.2, -0.4)] {
                let q = Query::<1>::new(form, kernel::by_name(k).unwrap(), h, s);
                let lin = q.chain().unwrap();
                let table = PhaseTable::new(&kappas, lin.reach());
                for (i, &kap) in kappas.iter().enumerate() {
                    assert_eq!(
                        lin.omega2_tabulated(&table, i).0.to_bits(),
                        lin.omega2(kap).0.to_bits(),
                        "{form:?} {k} h {h} σ̄ {s} κ {kap}"
                    );
                    n += 1;
                }
            }
        }
    }
    println!("{n} (cell, κ) pairs bitwise equal");
}

#[test]
fn cosine_series_matches_the_matrix_route_and_keeps_relative_accuracy_as_kappa_to_0() {
    let mut kappas: Vec<f64> = (1..=64)
        .map(|i| std::f64::consts::PI * i as f64 / 64.0)
        .collect();
    let small = [1e-6, 1e-4, 1e-2];
    kappas.extend(small);
    let (mut worst, mut worst_small, mut cells) = (0.0f64, 0.0f64, 0);
    for form in forms() {
        for k in ["m4", "m6", "wendland-c2", "gaussian", "lucy", "efg-cubic"] {
            for (h, s) in [(1.1, 0.3), (1.6, 0.0), (3.0, -0.6)] {
                let q = Query::<1>::new(form, kernel::by_name(k).unwrap(), h, s);
                let lin = q.chain().unwrap();
                let Some(cs) = lin.cosine_series() else {
                    // consistent mass (least squares) or dissipative: not a cosine series
                    assert!(form == FormKind::LeastSquares || lin.is_dissipative());
                    continue;
                };
                cells += 1;
                let table = PhaseTable::new(&kappas, lin.reach());
                let exact: Vec<f64> = kappas.iter().map(|&x| lin.omega2(x).0).collect();
                let scale = exact.iter().fold(0.0f64, |m, w| m.max(w.abs()));
                for (i, &w) in exact.iter().enumerate() {
                    let f = cs.omega2(&table, i);
                    if i < 64 {
                        worst = worst.max((f - w).abs() / scale);
                    } else {
                        // ω² ~ κ²: relative error, not relative to the curve's scale
                        worst_small = worst_small.max((f - w).abs() / w.abs());
                    }
                }
            }
        }
    }
    println!(
        "{cells} cells: worst |Δω²|/max|ω²| {worst:.2e}, worst relative at κ ≤ 1e-2 {worst_small:.2e}"
    );
    assert!(cells >= 100);
    assert!(worst < 1e-13, "{worst}");
    assert!(worst_small < 1e-9, "{worst_small}");
}

#[test]
fn jacobian_columns_are_affine_in_the_pre_stress() {
    let m4 = kernel::by_name("m4").unwrap();
    for form in forms() {
        for h in [1.2, 2.5] {
            let lin = |s: f64| Query::<1>::new(form, m4, h, s).chain().unwrap();
            let (a, mid, b) = (lin(-0.9), lin(0.0), lin(0.9));
            let d = a.lerp(&b, 0.5).unwrap().distance(&mid).unwrap();
            assert!(d < 1e-13, "{form:?} h {h}: {d:e}");
            // the check can fail: the midpoint is not the columns at σ̄ = 0.9
            let off = a.lerp(&b, 0.5).unwrap().distance(&b).unwrap();
            assert!(off > 1e-3, "{form:?} h {h}: {off:e}");
        }
    }
}
