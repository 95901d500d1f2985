//! `interpolate` ([`sphstab::studies::interpolation`]): the kernel approximation of a known
//! function on a finite particle set against values obtained by other routes — the
//! reproducing property of the consistent families (analytic), the gradient's transfer
//! function from the von Neumann engine's total-Lagrangian dispersion (ω = c|D(κ)|), and the
//! half-lattice sum of a kernel at the boundary (symmetry of W).

use crate::common::lin;
use sphstab::forms::FormKind;
use sphstab::kernel;
use sphstab::shape::ShapeFamily;
use sphstab::studies::interpolation::{InterpolationConfig, TestFunction, interpolate};
use std::f64::consts::PI;

fn cfg(f: TestFunction, kern: &str, h: f64) -> InterpolationConfig {
    InterpolationConfig::new(f, kernel::by_name(kern).unwrap(), h)
}

#[test]
fn consistent_families_reproduce_a_linear_function_without_ghosts() {
    // MLS with a linear basis reproduces f = Σ x_a and its gradient exactly, at the boundary
    // too; the corrected family (Shepard values) reproduces the gradient exactly
    for dim in [1, 2] {
        for (shape, value_exact) in [(ShapeFamily::Mls, true), (ShapeFamily::Corrected, false)] {
            let mut c = cfg(TestFunction::Linear, "m4", 1.3);
            c.dim = dim;
            c.particles = if dim == 1 { 41 } else { 17 };
            c.interval = (-0.3, 2.1);
            c.shape = shape;
            let r = interpolate(&c).unwrap();
            let g = r.gradient.unwrap();
            assert!(
                g.max < 1e-12,
                "{dim}D {shape:?}: gradient error {:e}",
                g.max
            );
            if value_exact {
                assert!(
                    r.value.max < 1e-12,
                    "{dim}D mls: value error {:e}",
                    r.value.max
                );
            } else {
                // Shepard values miss the linear term where the cover is one-sided
                assert!(
                    r.value.boundary_max > 1e-3,
                    "{dim}D corrected: {:e}",
                    r.value.max
                );
            }
        }
    }
}

#[test]
fn sph_gradient_with_ghosts_has_the_engines_transfer_function() {
    // with ghosts the interval is a window of the infinite lattice: ⟨f′⟩ = G cos x and
    // ⟨f″⟩ = −G² sin x for f = sin x, with G = |D(κ)|/κ the gain of the sph gradient, which the
    // engine gives independently as √ω²/κ of the total-lagrangian form (ω² = C S1², unit c)
    for (h, ppw) in [(5.5, 40.0), (5.5, 10.0), (1.5, 40.0)] {
        let dx = 2.0 * PI / ppw;
        let mut c = cfg(TestFunction::Sine, "mollifier", h);
        c.ghosts = true;
        c.particles = (3.0 * PI / dx).round() as usize + 1;
        let r = interpolate(&c).unwrap();
        let kap = 2.0 * PI / ppw;
        let gain = lin(
            FormKind::TotalLagrangian,
            "mollifier",
            ShapeFamily::Sph,
            h,
            0.0,
        )
        .omega2(kap)
        .0
        .sqrt()
            / kap;
        for i in 0..r.position.len() {
            let x = r.position[i];
            let (g_exact, l_exact) = (gain * x.cos(), -gain * gain * x.sin());
            assert!(
                (r.gradient_x_approx[i] - g_exact).abs() < 1e-9,
                "h = {h}, {ppw} ppw, x = {x}: ⟨f′⟩ {} against G cos x {g_exact} (G = {gain})",
                r.gradient_x_approx[i]
            );
            assert!(
                (r.laplacian_approx[i] - l_exact).abs() < 1e-9,
                "h = {h}, {ppw} ppw, x = {x}: ⟨f″⟩ {} against −G² sin x {l_exact}",
                r.laplacian_approx[i]
            );
        }
    }
}

#[test]
fn sph_without_ghosts_sees_half_a_cover_at_the_boundary() {
    // the step is 1 on the left half: at x = a the plain sum is Σ_{j ≥ 0} W(jΔx)Δx, which by
    // the symmetry of W is (S0 + W(0)Δx)/2, S0 = Σ_{j ∈ Z} W(jΔx)Δx the full lattice sum
    // (computed here from the kernel directly); with ghosts it is S0; Shepard gives 1
    for (kern, h) in [("mollifier", 5.5), ("mollifier", 1.5), ("m4", 1.3)] {
        let k = kernel::by_name(kern).unwrap();
        let mut c = cfg(TestFunction::Step, kern, h);
        c.particles = 201;
        let dx = c.dx();
        let w = |j: i64| kernel::w::<f64>(k, 1, (j as f64 * dx).abs(), h * dx) * dx;
        let s0: f64 = (-100..=100).map(w).sum();
        let half = 0.5 * (s0 + w(0));
        let r = interpolate(&c).unwrap();
        assert!(
            (r.f_approx[0] - half).abs() < 1e-13,
            "{kern} h = {h}: ⟨f⟩(a) = {} against {half}",
            r.f_approx[0]
        );
        assert!((r.value_at_start.unwrap() - (1.0 - half).abs()).abs() < 1e-13);
        c.ghosts = true;
        let g = interpolate(&c).unwrap();
        assert!(
            (g.f_approx[0] - s0).abs() < 1e-13,
            "{kern} h = {h}: with ghosts"
        );
        c.ghosts = false;
        c.shape = ShapeFamily::Shepard;
        let s = interpolate(&c).unwrap();
        assert!(
            (s.f_approx[0] - 1.0).abs() < 1e-13,
            "{kern} h = {h}: shepard"
        );
    }
}

#[test]
fn bad_input_names_the_field() {
    let mut c = cfg(TestFunction::Quartic, "mollifier", 0.9);
    let e = interpolate(&c).unwrap_err().to_string();
    assert!(e.contains("h_over_dx"), "{e}");
    c.h_over_dx = 5.5;
    c.particles = 2;
    assert!(
        interpolate(&c)
            .unwrap_err()
            .to_string()
            .contains("particles")
    );
    c.particles = 11;
    c.interval = (1.0, 1.0);
    assert!(
        interpolate(&c)
            .unwrap_err()
            .to_string()
            .contains("interval")
    );
    assert!(TestFunction::by_name("edge", 0.0).is_err());
    assert!(TestFunction::by_name("cubic", 1.0).is_err());
}
