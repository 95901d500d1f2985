//! Static Galerkin meshfree solutions of [B98 §6.2] (issue 29, capability 7): the cantilever
//! beam. The exact solution (eqs 120–124) is checked against itself (its stresses are Hooke's
//! law, plane stress, of its displacements' gradient, by central differences here), then the
//! methods' convergence is measured against it.

use sphstab::studies::galerkin::{
    Cantilever, GalerkinMethod, PlateWithHole, cantilever, plate_with_hole, rate,
};

/// Plane-stress Hooke's law (E, ν) of the displacement field `u` at (x, y), its gradient by
/// central differences of step `h`: (σ_xx, σ_yy, σ_xy).
fn hooke_by_differences(
    u: impl Fn(f64, f64) -> [f64; 2],
    (e, nu): (f64, f64),
    (x, y): (f64, f64),
    h: f64,
) -> [f64; 3] {
    let f = e / (1.0 - nu * nu);
    let d = |dx: f64, dy: f64| u(x + dx, y + dy);
    let ux_x = (d(h, 0.0)[0] - d(-h, 0.0)[0]) / (2.0 * h);
    let uy_y = (d(0.0, h)[1] - d(0.0, -h)[1]) / (2.0 * h);
    let shear = (d(0.0, h)[0] - d(0.0, -h)[0] + d(h, 0.0)[1] - d(-h, 0.0)[1]) / (2.0 * h);
    [
        f * (ux_x + nu * uy_y),
        f * (uy_y + nu * ux_x),
        f * (1.0 - nu) / 2.0 * shear,
    ]
}

/// Eqs 122–124 are plane-stress Hooke's law of eqs 120–121 (central differences, step 1e-5),
/// the end x = L carries only the shear σ_xy with resultant P (Simpson on 200 intervals), and
/// the edges y = ±D/2 are traction-free.
#[test]
fn the_beam_solution_is_plane_stress_elasticity_with_the_end_load() {
    let b = Cantilever::B98;
    for &(x, y) in &[(0.5, 0.3), (3.0, -0.2), (7.5, 0.45), (4.0, 0.0)] {
        let s = hooke_by_differences(
            |x, y| b.displacement(x, y),
            (b.modulus, b.poisson),
            (x, y),
            1e-5,
        );
        let want = b.stress(x, y);
        for k in 0..3 {
            assert!(
                // |σ| ≤ P L (D/2)/I = 48: 1e-5 is 2e-7 of it (the differences' rounding, E ε/h
                // ~ 1e3 · 1e-16 · 1/1e-5 = 1e-8, and truncation of a cubic field, ~h² = 1e-10)
                (s[k] - want[k]).abs() < 1e-5,
                "({x}, {y}) σ[{k}]: Hooke {} against eq 122–124 {}",
                s[k],
                want[k]
            );
        }
    }
    let n = 200;
    let resultant: f64 = (0..=n)
        .map(|i| {
            let y = -0.5 + i as f64 / n as f64;
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * b.stress(b.length, y)[2]
        })
        .sum::<f64>()
        / (3.0 * n as f64);
    assert!((resultant - b.load).abs() < 1e-12, "resultant {resultant}");
    for y in [-0.5, 0.5] {
        let s = b.stress(2.0, y);
        assert!(
            s[1].abs() < 1e-15 && s[2].abs() < 1e-12,
            "edge traction {s:?}"
        );
    }
}

/// The corrected (CD1), Randles–Libersky and MLS Galerkin solutions converge to the beam's
/// solution in the nodal l2 norm under nodal quadrature and SPH's does not ([B98] §6.2.1:
/// "convergence in the l2 norm" for CD1 and MLS; Table III: SPH NC). Measured at Δx = 1/4,
/// 1/8, 1/16 (2026-12-04): l2 errors MLS 0.156, 0.042, 0.010; CD1 0.170, 0.068, 0.021; RL
/// 0.410, 0.116, 0.033; SPH 0.326, 0.484, 0.246 (not monotone).
#[test]
fn corrected_and_mls_galerkin_converge_on_the_beam_and_sph_does_not() {
    let b = Cantilever::B98;
    let levels = [4usize, 8, 16];
    for (method, converges) in [
        (GalerkinMethod::Mls, true),
        (GalerkinMethod::Cd1, true),
        (GalerkinMethod::Rl, true),
        (GalerkinMethod::Sph, false),
    ] {
        let r: Vec<_> = levels
            .iter()
            .map(|&m| cantilever(&b, method, m).unwrap())
            .collect();
        let h: Vec<f64> = r.iter().map(|x| x.spacing).collect();
        let du: Vec<f64> = r.iter().map(|x| x.displacement_error).collect();
        let de: Vec<f64> = r.iter().map(|x| x.energy_error).collect();
        assert!(de.iter().all(|e| e.is_finite() && *e > 0.0));
        if converges {
            assert!(
                rate(&h, &du) > 1.0,
                "{}: l2 rate {}",
                method.name(),
                rate(&h, &du)
            );
            assert!(
                du.windows(2).all(|w| w[1] < w[0]),
                "{}: {du:?}",
                method.name()
            );
            assert!(du[2] < 0.05, "{}: l2 error {}", method.name(), du[2]);
        } else {
            assert!(
                du[2] > 0.1 && du[1] > du[0],
                "{}: l2 errors {du:?}",
                method.name()
            );
        }
    }
}

/// EFG (MLS with 5 × 5 Gauss quadrature on the node cells, the finite-element row blended in,
/// eqs 100–104) converges in energy at about B98's rate (Table III: 1.50) and is accurate in
/// L2. Measured (2026-12-04) at Δx = 1/4, 1/8, 1/16: energy errors 0.0243, 0.0086, 0.0031
/// (rate 1.48); L2 errors 1.0e-4, 1.1e-4, 4.0e-5 (a floor near 1e-4 the refinement does not
/// yet resolve; B98's L2 rate is 2.00).
#[test]
fn efg_converges_in_energy_at_the_b98_rate() {
    let b = Cantilever::B98;
    let r: Vec<_> = [4usize, 8, 16]
        .iter()
        .map(|&m| cantilever(&b, GalerkinMethod::Efg, m).unwrap())
        .collect();
    let h: Vec<f64> = r.iter().map(|x| x.spacing).collect();
    let de: Vec<f64> = r.iter().map(|x| x.energy_error).collect();
    let re = rate(&h, &de);
    assert!((re - 1.5).abs() < 0.1, "EFG energy rate {re} ({de:?})");
    for x in &r {
        assert!(
            x.displacement_error < 1e-3,
            "EFG L2 {}",
            x.displacement_error
        );
        assert!(
            (x.probe_displacement / x.exact_probe_displacement - 1.0).abs() < 1e-3,
            "tip {} against {}",
            x.probe_displacement,
            x.exact_probe_displacement
        );
    }
}

/// The plate with a hole's exact solution ([B98] eqs 127–129 and the plane-stress displacement
/// B98 does not print): the stresses are plane-stress Hooke's law of the displacements
/// (central differences), the hole is traction-free (σ·n = 0 at r = a), the far field is the
/// unit tension (σ_xx → 1 as a/r → 0), and the symmetry axes have no normal displacement
/// (u_y = 0 on y = 0, u_x = 0 on x = 0).
#[test]
fn the_plate_with_a_hole_solution_is_kirsch_in_plane_stress() {
    let p = PlateWithHole::B98;
    for &(x, y) in &[(1.2, 0.3), (0.5, 2.0), (3.0, 4.0), (4.9, 0.1), (0.7, 0.9)] {
        let s = hooke_by_differences(
            |x, y| p.displacement(x, y),
            (p.modulus, p.poisson),
            (x, y),
            1e-6,
        );
        let want = p.stress(x, y);
        for k in 0..3 {
            assert!(
                (s[k] - want[k]).abs() < 1e-6,
                "({x}, {y}) σ[{k}]: Hooke {} against Kirsch {}",
                s[k],
                want[k]
            );
        }
    }
    for i in 0..=8 {
        let t = std::f64::consts::FRAC_PI_2 * i as f64 / 8.0;
        let (c, s) = (t.cos(), t.sin());
        let [sx, sy, sxy] = p.stress(c, s);
        let traction = [sx * c + sxy * s, sxy * c + sy * s];
        assert!(
            traction[0].abs() < 1e-12 && traction[1].abs() < 1e-12,
            "hole at θ = {t}: {traction:?}"
        );
    }
    let far = p.stress(1e4, 3e3);
    assert!(
        (far[0] - 1.0).abs() < 1e-6 && far[1].abs() < 1e-6 && far[2].abs() < 1e-6,
        "{far:?}"
    );
    for v in [1.0, 2.5, 5.0] {
        assert!(p.displacement(v, 0.0)[1].abs() < 1e-15);
        assert!(p.displacement(0.0, v)[0].abs() < 1e-15);
    }
}

/// The plate with a hole ([B98] §6.2.2) with background quadrature converges as B98's Table III
/// and Fig 11 say: EFG at L2 and energy rates near 2.50 and 1.50, CD1 on the same Gauss points
/// ("excellent convergence for the corrected derivative and MLS approximations", §6.2.3). With
/// nodal quadrature, the MLS and CD1 solutions' Gauss-integrated energy errors do not converge
/// (Fig 10: "MLS Galerkin ... does not converge", nor CD1). Measured (2026-12-04) at Δx = 1,
/// 1/2, 1/4: EFG L2 1.87e-2, 4.28e-3, 7.45e-4 (rate 2.32), energy 0.081, 0.037, 0.015 (1.21),
/// u_x(a, 0) 2.99688e-3 against 3e-3 at 1/4; CD1 (Gauss) energy 0.142, 0.070, 0.035 (1.01);
/// nodal quadrature, integrated energy errors MLS 18.2, 16.9, 17.7, CD1 42.9, 34.8, 31.0.
#[test]
fn the_plate_converges_with_background_quadrature_and_not_with_nodal() {
    let p = PlateWithHole::B98;
    let levels = [1usize, 2, 4];
    let run = |m: GalerkinMethod| -> Vec<_> {
        levels
            .iter()
            .map(|&l| plate_with_hole(&p, m, l).unwrap())
            .collect()
    };
    let efg = run(GalerkinMethod::Efg);
    let h: Vec<f64> = efg.iter().map(|x| x.spacing).collect();
    assert_eq!(h, [1.0, 0.5, 0.25]);
    let du: Vec<f64> = efg.iter().map(|x| x.displacement_error).collect();
    let de: Vec<f64> = efg.iter().map(|x| x.energy_error).collect();
    assert!(du.windows(2).all(|w| w[1] < w[0]) && de.windows(2).all(|w| w[1] < w[0]));
    assert!(
        rate(&h, &du) > 2.0,
        "EFG L2 rate {} ({du:?})",
        rate(&h, &du)
    );
    assert!(
        rate(&h, &de) > 1.0,
        "EFG energy rate {} ({de:?})",
        rate(&h, &de)
    );
    let last = &efg[2];
    assert_eq!(last.probe, [p.radius, 0.0]);
    assert!(
        (last.probe_displacement / last.exact_probe_displacement - 1.0).abs() < 5e-3,
        "u_x(a, 0) {} against {}",
        last.probe_displacement,
        last.exact_probe_displacement
    );
    let cdg = run(GalerkinMethod::Cd1Gauss);
    let dc: Vec<f64> = cdg.iter().map(|x| x.energy_error).collect();
    assert!(
        dc.windows(2).all(|w| w[1] < w[0]) && rate(&h, &dc) > 0.8,
        "CD1 (Gauss) energy {dc:?}"
    );
    for m in [GalerkinMethod::Mls, GalerkinMethod::Cd1] {
        let r = run(m);
        for x in &r {
            let e = x.integrated_energy_error.unwrap();
            assert!(e > 1.0, "{} integrated energy error {e}", m.name());
        }
    }
    // sph and rl define gradients at the nodes only
    let s = plate_with_hole(&p, GalerkinMethod::Rl, 1).unwrap();
    assert!(s.integrated_energy_error.is_none());
    let err = plate_with_hole(&p, GalerkinMethod::Efg, 13).unwrap_err();
    assert!(err.to_string().contains("per_unit"), "{err}");
}
