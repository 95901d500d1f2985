//! Numerical stability at the extremes (issue 5, item 4): each test is named for what it probes.

use crate::common;

use common::*;
use sphstab::forms::FormKind;
use sphstab::shape::ShapeFamily;
use sphstab::vonneumann::amplification::spectral_radius;
use std::f64::consts::PI;

const FORMS: [(FormKind, ShapeFamily); 9] = [
    (FormKind::Classical, ShapeFamily::Sph),
    (FormKind::Nonlocal, ShapeFamily::Sph),
    (FormKind::Local, ShapeFamily::Corrected),
    (FormKind::Lnl, ShapeFamily::Sph),
    (FormKind::Cll, ShapeFamily::Sph),
    (FormKind::TotalLagrangian, ShapeFamily::Mls),
    (FormKind::EulerianStressPoints, ShapeFamily::Mls),
    (FormKind::LagrangianStressPoints, ShapeFamily::Mls),
    (FormKind::LeastSquares, ShapeFamily::Mls),
];

/// κΔx ∈ {1e−8, 1e−4, π − 1e−9, π}: finite ω² for every form, and ω² continuous at the
/// cut-off (|ω²(π − 1e−9) − ω²(π)| ≤ 1e−8 max|ω²|).
#[test]
fn wave_number_extremes_are_finite_and_continuous_at_the_cutoff() {
    for (form, shape) in FORMS {
        let l = lin(form, "m4", shape, 1.3, 0.3);
        let scale = grid(64)
            .iter()
            .map(|&k| l.omega2(k).0.abs())
            .fold(0.0, f64::max);
        for k in [1e-8, 1e-4, PI - 1e-9, PI] {
            let w2 = l.omega2(k).0;
            assert!(w2.is_finite(), "{form:?} κ={k}: {w2}");
        }
        let d = (l.omega2(PI - 1e-9).0 - l.omega2(PI).0).abs();
        assert!(d <= 1e-8 * scale, "{form:?}: jump {d:e} at the cut-off");
    }
}

/// h/Δx = 0.8 and 6 (m4: supports 1.6Δx and 12Δx): finite dispersion for every form; with
/// a ζ = 1 kernel, h = 0.8 has no neighbours and is an input error, not NaN.
#[test]
fn smoothing_length_extremes() {
    for h in [0.8, 6.0] {
        for (form, shape) in FORMS {
            // MLS needs at least two nodes besides the point itself at mid-points; at 0.8 the
            // m4 support 1.6Δx suffices
            let l = lin(form, "m4", shape, h, 0.1);
            for k in grid(32) {
                assert!(l.omega2(k).0.is_finite(), "{form:?} h={h} κ={k}");
            }
        }
    }
    let q = sphstab::analysis::Query::<1>::new(FormKind::Classical, k("lucy"), 0.8, 0.1);
    assert!(matches!(
        sphstab::analysis::query(&q),
        Err(sphstab::error::Error::OutOfRange {
            field: "h_over_dx",
            ..
        })
    ));
}

/// σ̄ = ±1e−12: the classical stress term at the cut-off is computed without cancellation,
/// ω²(π) = −2σ̄ S2(π) (derived closed form) to 1e−8 relative; σ̄ = ±0.999: finite everywhere,
/// and C̄ = 1 + σ̄ → 0.001 for compression sets the long-wave speed (ω²/κ² → 0.001).
#[test]
fn stress_extremes() {
    for sig in [1e-12, -1e-12] {
        let l = lin(FormKind::Classical, "m4", ShapeFamily::Sph, 1.2, sig);
        let cf = derived_omega2(FormKind::Classical, "m4", 1.2, sig, PI);
        let w2 = l.omega2(PI).0;
        assert!(
            (w2 - cf).abs() <= 1e-8 * cf.abs(),
            "σ̄={sig}: {w2:e} vs {cf:e}"
        );
        assert_eq!(w2 < 0.0, sig > 0.0);
    }
    for sig in [0.999, -0.999] {
        for (form, shape) in FORMS {
            let l = lin(form, "m4", shape, 1.3, sig);
            for k in grid(32) {
                assert!(l.omega2(k).0.is_finite(), "{form:?} σ̄={sig}");
            }
        }
    }
    let l = lin(
        FormKind::TotalLagrangian,
        "m4",
        ShapeFamily::Mls,
        1.3,
        -0.999,
    );
    assert!((l.omega2(1e-4).0 / 1e-8 - 0.001).abs() < 1e-9);
}

/// Δt exactly at, 1e−9 below and 1e−9 above the critical value: below, no amplification;
/// above, with ωΔt = 2(1 + ε) the leapfrog pair solves λ² + (2 + 8ε + 4ε²)λ + 1 = 0, so
/// |λ| − 1 = 4ε + √(8ε + …) ≈ 8.944e−5 for ε = 1e−9 — resolved; at the limit (double root
/// λ = −1) |λ| = 1 to the resolution of a defective eigenvalue.
#[test]
fn time_step_at_the_critical_value() {
    let l = lin(
        FormKind::TotalLagrangian,
        "efg-quartic",
        ShapeFamily::Mls,
        1.5,
        0.0,
    );
    // ω_max = 1 at κ = π/2 ([B00] Table II) → Δt_crit = 2 exactly
    let k = PI / 2.0;
    let at = spectral_radius(&l, k, 2.0).unwrap();
    let below = spectral_radius(&l, k, 2.0 * (1.0 - 1e-9)).unwrap();
    let above = spectral_radius(&l, k, 2.0 * (1.0 + 1e-9)).unwrap();
    eprintln!(
        "|λ| − 1: below {:e}, at {:e}, above {:e}",
        below - 1.0,
        at - 1.0,
        above - 1.0
    );
    assert!(below - 1.0 <= 1e-7);
    assert!((at - 1.0).abs() <= 1e-7);
    let eps = 1e-9f64;
    let b = 1.0 + 4.0 * eps + 2.0 * eps * eps;
    let exact = b + (b * b - 1.0).sqrt() - 1.0;
    assert!(
        (above - 1.0 - exact).abs() < 1e-3 * exact,
        "above: {} vs {exact}",
        above - 1.0
    );
}

/// 2D normalised results do not depend on Δx (1e−6 … 1e6).
#[test]
fn two_d_results_are_scale_free() {
    use sphstab::forms::{Material, ModelParams};
    use sphstab::lattice::Lattice;
    use sphstab::shape::KernelParams;
    use sphstab::vonneumann::linearise::Bloch;
    let lat = Lattice::<2>::square(1.0).unwrap();
    let mk = |dx: f64| {
        let p = ModelParams {
            form: FormKind::Classical,
            shape: ShapeFamily::Sph,
            kp: KernelParams {
                kernel: k("m4"),
                h: 1.2 * dx,
            },
            material: Material::Hydro { bulk: 1.0 },
            rho0: 1.0,
            c_partition: 0.5,
            av: None,
            art_stress: None,
            diffusion: None,
            alpha_s: 0.0,
            ls_length: 1.0,
            hourglass: None,
        };
        Bloch::<2>::new(p, &lat, dx, 0.02).unwrap()
    };
    let base = mk(1.0);
    for dx in [1e-6, 1e6] {
        let l = mk(dx);
        for kk in [[PI, 0.0], [0.3, 1.7], [PI, PI]] {
            let (a, b) = (base.growth(kk).unwrap().0, l.growth(kk).unwrap().0);
            assert!(
                (a - b).abs() <= 1e-9 * a.max(1e-3),
                "Δx={dx} k={kk:?}: {a} vs {b}"
            );
        }
    }
}
