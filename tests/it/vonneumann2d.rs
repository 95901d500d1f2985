//! 2D in-plane Bloch analysis: derived closed-form dynamical matrices vs the engine, the Swegle
//! tension statements, and the reduction to 1D along an axis.

use sphstab::forms::{FormKind, Material, ModelParams, ObjectiveRate};
use sphstab::kernel;
use sphstab::lattice::Lattice;
use sphstab::shape::KernelParams;
use sphstab::shape::ShapeFamily;
use sphstab::vonneumann::derived::{Sums, omega2_1d, rho_d, sums};
use sphstab::vonneumann::linearise::{Bloch, base_state};
use std::f64::consts::PI;

fn params(
    form: FormKind,
    kern: &str,
    shape: ShapeFamily,
    h: f64,
    material: Material,
) -> ModelParams {
    ModelParams {
        form,
        shape,
        kp: KernelParams {
            kernel: kernel::by_name(kern).unwrap(),
            h,
        },
        material,
        rho0: 1.0,
        c_partition: 0.5,
        av: None,
        art_stress: None,
        diffusion: None,
        alpha_s: 0.0,
        ls_length: 1.0,
        hourglass: None,
    }
}

fn materials() -> Vec<(&'static str, Material)> {
    vec![
        ("hydro", Material::Hydro { bulk: 1.0 }),
        (
            "elastic-jaumann",
            Material::elastic(1.0, 0.3, ObjectiveRate::Jaumann).unwrap(),
        ),
        (
            "elastic-truesdell",
            Material::elastic(1.0, 0.25, ObjectiveRate::Truesdell).unwrap(),
        ),
    ]
}

fn kgrid(lat: &Lattice<2>, n: usize) -> Vec<[f64; 2]> {
    let b = lat.reciprocal();
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
            out.push([s * b[0][0] + t * b[1][0], s * b[0][1] + t * b[1][1]]);
        }
    }
    out
}

/// Closed-form D(k) (src/vonneumann/derived.rs) vs the engine's D(k) to 1e-8 relative, on
/// square and hexagonal lattices, three materials, tension and compression.
#[test]
fn derived_dynamical_matrices_agree_with_engine() {
    for lat in [
        Lattice::<2>::square(1.0).unwrap(),
        Lattice::<2>::hexagonal(),
    ] {
        for (mname, mat) in materials() {
            for (form, shape) in [
                (FormKind::Classical, ShapeFamily::Sph),
                (FormKind::Nonlocal, ShapeFamily::Sph),
                (FormKind::Local, ShapeFamily::Corrected),
                (FormKind::TotalLagrangian, ShapeFamily::Sph),
                (FormKind::TotalLagrangian, ShapeFamily::Mls),
            ] {
                for (kern, h) in [("m4", 1.2), ("wendland-c2", 1.5)] {
                    for sb in [0.05, -0.05] {
                        let p = params(form, kern, shape, h, mat);
                        let lin = Bloch::<2>::new(p, &lat, 1.0, sb).unwrap();
                        let (rho, s) = base_state(&mat, 1.0, sb).unwrap();
                        let sum_shape = if form == FormKind::TotalLagrangian {
                            shape
                        } else {
                            ShapeFamily::Sph
                        };
                        let mut worst: f64 = 0.0;
                        let mut scale: f64 = 0.0;
                        for k in kgrid(&lat, 9) {
                            let sm = sums(&lat, sum_shape, p.kp, k).unwrap();
                            let cf = rho_d(form, &mat, s, rho, &sm).unwrap();
                            let en = lin.dynamical(k);
                            for a in 0..2 {
                                for b in 0..2 {
                                    let want = cf[a][b] / (rho * mat.modulus());
                                    worst = worst
                                        .max((en[a][b].re - want).abs())
                                        .max(en[a][b].im.abs());
                                    scale = scale.max(want.abs());
                                }
                            }
                        }
                        assert!(
                            worst <= 1e-8 * scale,
                            "{:?} {mname} {form:?}/{shape:?} {kern} h={h} σ̄={sb}: {worst:e} (scale {scale})",
                            lat.kind
                        );
                    }
                }
            }
        }
    }
}

/// Classical SPH on a square lattice, hydrodynamic material (the Swegle test's), m4,
/// h/Δx ∈ {1.0, 1.2, 1.3}, f = ρ/ρ0 ∈ {0.95, 0.99}: unstable in tension; nonlocal and
/// total-Lagrangian are not. The fastest wave vector and its polarisation are reported.
#[test]
fn swegle_lattice_classical_unstable_in_tension_nonlocal_and_tl_not() {
    let lat = Lattice::<2>::square(1.0).unwrap();
    let hydro = Material::Hydro { bulk: 1.0 };
    let n = 24;
    for h in [1.0, 1.2, 1.3] {
        for f in [0.95, 0.99] {
            let sb = 1.0 - f;
            let mut best = (0.0, [0.0; 2], 0.0);
            let cl = Bloch::<2>::new(
                params(FormKind::Classical, "m4", ShapeFamily::Sph, h, hydro),
                &lat,
                1.0,
                sb,
            )
            .unwrap();
            for i in 0..=n {
                for j in 0..=n {
                    let k = [PI * i as f64 / n as f64, PI * j as f64 / n as f64];
                    let (g, pol) = cl.growth(k).unwrap();
                    if g > best.0 {
                        let kn = k[0].hypot(k[1]);
                        best = (g, k, ((pol[0] * k[0] + pol[1] * k[1]).norm() / kn).powi(2));
                    }
                }
            }
            eprintln!(
                "classical hydro m4 h={h} f={f}: max growth {:.5} c/Δx at k = ({:.3}π, {:.3}π), longitudinal fraction {:.2}",
                best.0,
                best.1[0] / PI,
                best.1[1] / PI,
                best.2
            );
            assert!(best.0 > 1e-3);
            for form in [FormKind::Nonlocal, FormKind::TotalLagrangian] {
                let l = Bloch::<2>::new(
                    params(form, "m4", ShapeFamily::Sph, h, hydro),
                    &lat,
                    1.0,
                    sb,
                )
                .unwrap();
                for i in 0..=n {
                    for j in 0..=n {
                        let k = [PI * i as f64 / n as f64, PI * j as f64 / n as f64];
                        assert!(
                            l.growth(k).unwrap().0 < 1e-6,
                            "{form:?} h={h} f={f} grows at {k:?}"
                        );
                    }
                }
            }
        }
    }
}

/// Reduction to 1D: for k = (κ, 0) the longitudinal branch of the 2D classical form (Truesdell
/// elastic, the 1D law) is the 1D relation ω² = C̃S1² − 2σ̄(S2 − S1²) of `derived::omega2_1d`,
/// evaluated with the column sums of the 2D lattice shape (the 2D kernel summed over each
/// lattice column: φ₁(x) = Σ_y φ(x, y)). Checked to 1e-8.
#[test]
fn along_an_axis_the_2d_classical_form_reduces_to_the_1d_relation() {
    let lat = Lattice::<2>::square(1.0).unwrap();
    let mat = Material::elastic(1.0, 0.2, ObjectiveRate::Truesdell).unwrap();
    for h in [1.0, 1.3] {
        for sb in [0.1, -0.3] {
            let p = params(FormKind::Classical, "m4", ShapeFamily::Sph, h, mat);
            let lin = Bloch::<2>::new(p, &lat, 1.0, sb).unwrap();
            for i in 1..=16 {
                let kap = PI * i as f64 / 16.0;
                let sm = sums(&lat, ShapeFamily::Sph, p.kp, [kap, 0.0]).unwrap();
                // column sums: S1x(κ) and S2xx(κ) are exactly the 1D sums of φ₁
                let col = Sums::<1> {
                    s1: [sm.s1[0]],
                    s2: [[sm.s2[0][0]]],
                    m1: [[sm.m1[0][0]]],
                };
                let one_d = omega2_1d(FormKind::Classical, &col, sb, 0.5).unwrap();
                let d = lin.dynamical([kap, 0.0]);
                assert!(d[0][1].norm() < 1e-12, "mixing at κ={kap}");
                assert!(
                    (d[0][0].re - one_d).abs() < 1e-8 * one_d.abs().max(1e-3),
                    "h={h} σ̄={sb} κ={kap}: {} vs {one_d}",
                    d[0][0].re
                );
            }
        }
    }
}

/// Finite-box prediction: a Swegle box of n × n particles with 3 fixed layers per side admits
/// standing modes k = (mπ/(n_free+1), lπ/(n_free+1)); its growth rate is below the
/// infinite-lattice maximum and converges to it as the box grows (21 → 41 → 81).
#[test]
fn finite_box_prediction_converges_to_the_infinite_lattice() {
    use sphstab::analysis::box_prediction;
    let lat = Lattice::<2>::square(1.0).unwrap();
    let hydro = Material::Hydro { bulk: 1.0 };
    let lin = Bloch::<2>::new(
        params(FormKind::Classical, "m4", ShapeFamily::Sph, 1.2, hydro),
        &lat,
        1.0,
        0.01,
    )
    .unwrap();
    let n = 128;
    let mut inf: f64 = 0.0;
    for i in 0..=n {
        for j in 0..=n {
            inf = inf.max(
                lin.growth([PI * i as f64 / n as f64, PI * j as f64 / n as f64])
                    .unwrap()
                    .0,
            );
        }
    }
    let mut prev = 0.0;
    for size in [21usize, 41, 81] {
        let (g, k) = box_prediction(&lin, size - 6).unwrap();
        eprintln!(
            "box {size}×{size} (free {}): predicted growth {g:.5} at k = ({:.4}π, {:.4}π); infinite lattice {inf:.5}; ratio {:.4}",
            size - 6,
            k[0] / PI,
            k[1] / PI,
            g / inf
        );
        assert!(g <= inf * (1.0 + 1e-9));
        assert!(g > prev);
        prev = g;
    }
    assert!(prev / inf > 0.9);
}

/// The neo-Hookean total-Lagrangian law [T eq 3.64] linearises to Hooke's law about the
/// unstressed state: its dynamical matrix equals (λ + G)S1S1ᵀ + G|S1|²I (derived closed form),
/// and the same as the linear elastic TL at zero pre-stress, to 1e-8.
#[test]
fn neo_hookean_linearises_to_hooke() {
    let lat = Lattice::<2>::square(1.0).unwrap();
    let (lambda, shear) = match Material::elastic(1.0, 0.3, ObjectiveRate::Truesdell).unwrap() {
        Material::Elastic { lambda, shear, .. } => (lambda, shear),
        _ => unreachable!(),
    };
    let nh = Material::NeoHookean { lambda, shear };
    for shape in [ShapeFamily::Sph, ShapeFamily::Mls] {
        let p = params(FormKind::TotalLagrangian, "m4", shape, 1.3, nh);
        let lin = Bloch::<2>::new(p, &lat, 1.0, 0.0).unwrap();
        for k in kgrid(&lat, 7) {
            let sm = sums(&lat, shape, p.kp, k).unwrap();
            let cf = rho_d(FormKind::TotalLagrangian, &nh, 0.0, 1.0, &sm).unwrap();
            let d = lin.dynamical(k);
            for a in 0..2 {
                for b in 0..2 {
                    assert!(
                        (d[a][b].re - cf[a][b]).abs() < 1e-8 * (1.0 + cf[a][b].abs()),
                        "{shape:?} k={k:?}"
                    );
                }
            }
        }
    }
}

/// Monaghan–Gray artificial stress on the Swegle lattice (classical, hydro, m4, h = 1.2,
/// σ̄ = 0.05): ε lowers the growth of the longitudinal zone-edge mode (0.387 → 0.243 at ε = 0.1
/// → 0.137 at ε = 0.2), but from ε ≈ 0.2 the fastest mode is transverse — for a zero-shear
/// material the extra repulsion cannot stabilise it — and growth rises again (0.167 at ε = 0.3).
#[test]
fn artificial_stress_trades_longitudinal_for_transverse_growth() {
    use sphstab::analysis::{MaterialSpec, Query, query};
    let mut rates = Vec::new();
    for eps in [0.0, 0.1, 0.2, 0.3] {
        let mut q = Query::<2>::new(
            FormKind::Classical,
            kernel::by_name("m4").unwrap(),
            1.2,
            0.05,
        );
        q.material = MaterialSpec::Hydro;
        q.grid = 32;
        if eps > 0.0 {
            q.art_stress = Some((eps, 4));
        }
        let r = query(&q).unwrap();
        let lf = r.polarisation.as_ref().unwrap().longitudinal_fraction;
        eprintln!(
            "ε = {eps}: growth {:.5} c/Δx, longitudinal fraction {lf:.3}",
            r.max_growth_rate
        );
        rates.push((r.max_growth_rate, lf));
    }
    assert!(rates[1].0 < rates[0].0 && rates[2].0 < rates[1].0);
    assert!(rates[0].1 > 0.99 && rates[1].1 > 0.99);
    assert!(rates[2].1 < 0.01 && rates[3].1 < 0.01);
    assert!(rates[3].0 > rates[2].0);
}
