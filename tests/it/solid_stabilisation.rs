//! The solid stabilisations of issue 30 (SPH-ENOG, tl-enog, Ganzenmüller's hourglass control)
//! and the hourglass / tensile split of the classification, against closed forms written here
//! from the papers' pair formulas, independently of the rate code:
//! - at a zero-energy wave vector (half a reciprocal-lattice vector, k·a_i ∈ πℤ: the nodal
//!   gradient Σ_J sin(k·X_J) ∇φ_J vanishes), every nodal term of a form drops out of the Bloch
//!   matrix and what is left is a lattice sum of the pair term alone;
//! - SPH-ENOG at any k: (K/ρ0) g ⊗ g (its pressure, g the nodal gradient symbol) plus the
//!   lattice sum of its shear acceleration;
//! - long waves on a fine kernel (h = 3Δx, where lattice sums are integrals to ~1e-3): the
//!   continuum limits derived from the pair formulas (ENOG: (ζ/(D + 2)) G [∇²u + 2∇(∇·u)];
//!   tl-enog: the law with its shear modulus scaled by κ).

use sphstab::analysis::{Query, QuerySpec, query};
use sphstab::budget::Budget;
use sphstab::forms::{FormKind, Material, ModelParams, ObjectiveRate};
use sphstab::kernel;
use sphstab::lattice::Lattice;
use sphstab::vonneumann::classify::Kind;
use sphstab::vonneumann::linearise::Bloch;

/// ν = 0.3 with P-wave modulus C = 1 (the engine's normalisation): (λ, G).
fn lame(nu: f64) -> (f64, f64) {
    (nu / (1.0 - nu), (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu)))
}

/// The 1D bar's parameters of the shared helper, as a 2D elastic solid (ν = 0.3, Jaumann).
fn params(form: FormKind, kern: &str, h: f64, hourglass: Option<f64>) -> ModelParams {
    ModelParams {
        material: Material::elastic(1.0, 0.3, ObjectiveRate::Jaumann).unwrap(),
        hourglass,
        ..crate::common::params(form, kern, form.default_shape_in(2), h)
    }
}

/// The lattice vectors X_J ≠ 0 of `lat` within the support R, with W(r), W'(r).
fn neighbours(lat: &Lattice<2>, kern: &str, h: f64) -> Vec<([f64; 2], f64, f64)> {
    let k = kernel::by_name(kern).unwrap();
    let r_max = k.zeta() * h;
    let n = (r_max / lat.plane_spacing()).ceil() as i64 + 2;
    let mut out = Vec::new();
    for m in -n..=n {
        for l in -n..=n {
            let x = [
                m as f64 * lat.a[0][0] + l as f64 * lat.a[1][0],
                m as f64 * lat.a[0][1] + l as f64 * lat.a[1][1],
            ];
            let r = x[0].hypot(x[1]);
            if r > 0.0 && r < r_max {
                out.push((x, kernel::w(k, 2, r, h), kernel::dw::<f64>(k, 2, r, h)));
            }
        }
    }
    out
}

/// Eigenvalues of a symmetric 2 × 2 matrix, ascending.
fn eig2(m: [[f64; 2]; 2]) -> [f64; 2] {
    let (tr, det) = (m[0][0] + m[1][1], m[0][0] * m[1][1] - m[0][1] * m[1][0]);
    let disc = (0.25 * tr * tr - det).max(0.0).sqrt();
    [0.5 * tr - disc, 0.5 * tr + disc]
}

/// The engine's two branches ω²Δx²/c² at k (real parts, ascending).
fn engine(lin: &Bloch<2>, k: [f64; 2]) -> [f64; 2] {
    let b = lin.branches(k);
    [b[0].0.re, b[1].0.re]
}

fn close(a: [f64; 2], b: [f64; 2], tol: f64, what: &str) {
    for c in 0..2 {
        assert!(
            (a[c] - b[c]).abs() <= tol * b[1].abs().max(1e-3),
            "{what}: engine {a:?} vs closed form {b:?}"
        );
    }
}

/// The zero-energy wave vectors of a lattice other than Γ: half a reciprocal vector.
fn half_reciprocal(lat: &Lattice<2>) -> Vec<[f64; 2]> {
    let b = lat.reciprocal();
    [(1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
        .iter()
        .map(|&(s, t)| {
            [
                0.5 * (s * b[0][0] + t * b[1][0]),
                0.5 * (s * b[0][1] + t * b[1][1]),
            ]
        })
        .collect()
}

/// SPH-ENOG's Bloch matrix from the paper's formulas, at rest (σ̄ = 0):
/// D(k) = (K/ρ0) g ⊗ g + 2ζ (G/ρ0) Σ_J V (1 − cos k·X_J)(−W′/r) ê ⊗ ê,
/// g = Σ_J sin(k·X_J) V ∇W_J, ∇W_J = −W′ X_J/r (its continuity ρ̇ = −ρ tr L and pressure
/// −(1/ρ) Σ (p_I + p_J) ∇W V give the first term; the shear acceleration, integrated once,
/// the second).
fn enog_closed(lat: &Lattice<2>, kern: &str, h: f64, zeta: f64, k: [f64; 2]) -> [f64; 2] {
    let (lam, g_mod) = lame(0.3);
    let bulk = lam + 2.0 * g_mod / 3.0;
    let v = lat.area();
    let mut g = [0.0; 2];
    let mut s = [[0.0; 2]; 2];
    for (x, _, dw) in neighbours(lat, kern, h) {
        let r = x[0].hypot(x[1]);
        let kx = k[0] * x[0] + k[1] * x[1];
        let e = [x[0] / r, x[1] / r];
        for a in 0..2 {
            g[a] += kx.sin() * v * (-dw * e[a]);
            for b in 0..2 {
                s[a][b] += 2.0 * zeta * g_mod * v * (1.0 - kx.cos()) * (-dw / r) * e[a] * e[b];
            }
        }
    }
    let mut d = [[0.0; 2]; 2];
    for a in 0..2 {
        for b in 0..2 {
            d[a][b] = bulk * g[a] * g[b] + s[a][b];
        }
    }
    eig2(d)
}

#[test]
fn enog_bloch_matrix_is_its_pair_formulas() {
    for (lattice, kern, h) in [("square", "m4", 1.2), ("hex", "wendland-c2", 1.5)] {
        let lat = Lattice::<2>::named(lattice, 1.0).unwrap();
        for zeta in [None, Some(1.0)] {
            let lin = Bloch::new(params(FormKind::Enog, kern, h, zeta), &lat, 1.0, 0.0).unwrap();
            let z = zeta.unwrap_or(3.5);
            let mut ks = half_reciprocal(&lat);
            ks.extend([[0.3, 0.1], [1.2, 2.0], [0.05, 0.0]]);
            for k in ks {
                close(
                    engine(&lin, k),
                    enog_closed(&lat, kern, h, z, k),
                    1e-10,
                    &format!("enog {lattice} ζ = {z} k = {k:?}"),
                );
            }
        }
    }
}

#[test]
fn hourglass_controls_stiffen_the_zero_energy_modes_by_their_pair_sums() {
    let (lam, g) = lame(0.3);
    let young = g * (3.0 * lam + 2.0 * g) / (lam + g);
    for (lattice, kern, h) in [("square", "m4", 1.2), ("hex", "wendland-c2", 1.5)] {
        let lat = Lattice::<2>::named(lattice, 1.0).unwrap();
        let v = lat.area();
        let nb = neighbours(&lat, kern, h);
        let plain = Bloch::new(
            params(FormKind::TotalLagrangian, kern, h, None),
            &lat,
            1.0,
            0.0,
        )
        .unwrap();
        let alpha = 10.0;
        let ganz = Bloch::new(
            params(FormKind::TotalLagrangian, kern, h, Some(alpha)),
            &lat,
            1.0,
            0.0,
        )
        .unwrap();
        let kappa = 1.07;
        let tlenog = Bloch::new(params(FormKind::TlEnog, kern, h, None), &lat, 1.0, 0.0).unwrap();
        for k in half_reciprocal(&lat) {
            // total-Lagrangian: nodal integration leaves these modes without stiffness
            let p = engine(&plain, k);
            assert!(p[1].abs() < 1e-12, "{lattice} {k:?}: TL ω² {p:?}");
            // Ganzenmüller: (α E/ρ0) Σ V W(r)(1 − cos k·X)/r² ê ⊗ ê
            let mut d = [[0.0; 2]; 2];
            // tl-enog: (2κG/ρ0) Σ V (−W′/r)(1 − cos k·X), isotropic
            let mut lap = 0.0;
            for &(x, w, dw) in &nb {
                let r = x[0].hypot(x[1]);
                let c = 1.0 - (k[0] * x[0] + k[1] * x[1]).cos();
                for a in 0..2 {
                    for b in 0..2 {
                        d[a][b] += alpha * young * v * w * c / (r * r) * x[a] * x[b] / (r * r);
                    }
                }
                lap += 2.0 * kappa * g * v * (-dw / r) * c;
            }
            close(
                engine(&ganz, k),
                eig2(d),
                1e-10,
                &format!("ganzenmüller {lattice} {k:?}"),
            );
            close(
                engine(&tlenog, k),
                [lap, lap],
                1e-10,
                &format!("tl-enog {lattice} {k:?}"),
            );
            assert!(
                eig2(d)[0] > 0.01 && lap > 0.01,
                "{lattice} {k:?}: stiffened"
            );
        }
    }
}

#[test]
fn long_waves_reach_the_continuum_of_the_pair_formulas() {
    // h = 3Δx (R = 6Δx): the lattice sums are the integrals; k = 0.02/Δx leaves the
    // truncation (k R)²/12 ≈ 1.2e-3 of the symbols; 1% is an order of magnitude above it
    let (lam, g) = lame(0.3);
    let bulk = lam + 2.0 * g / 3.0;
    let lat = Lattice::<2>::named("square", 1.0).unwrap();
    let k = 0.02;
    let enog = Bloch::new(params(FormKind::Enog, "m4", 3.0, None), &lat, 1.0, 0.0).unwrap();
    let w = engine(&enog, [k, 0.0]);
    let zeta = 3.5;
    let want = [
        zeta / 4.0 * g * k * k,
        (bulk + 3.0 * zeta / 4.0 * g) * k * k,
    ];
    for c in 0..2 {
        assert!(
            (w[c] / want[c] - 1.0).abs() < 0.01,
            "enog long waves {w:?} vs {want:?}"
        );
    }
    // tl-enog: the law (λ, G) plus (κ − 1) times the isochoric deviator of D dimensions,
    // G(∇u + ∇uᵀ − (2/D) tr ε I): shear κG k², P-wave (λ + 2G + (κ − 1) G (2 − 2/D)) k²
    let tl = Bloch::new(params(FormKind::TlEnog, "m4", 3.0, None), &lat, 1.0, 0.0).unwrap();
    let w = engine(&tl, [k, 0.0]);
    let kappa = 1.07;
    let want = [
        kappa * g * k * k,
        (lam + 2.0 * g + (kappa - 1.0) * g) * k * k,
    ];
    for c in 0..2 {
        assert!(
            (w[c] / want[c] - 1.0).abs() < 0.01,
            "tl-enog long waves {w:?} vs {want:?}"
        );
    }
}

fn ask(form: &str, stress: f64, prestress: &str, extra: impl Fn(&mut QuerySpec)) -> Query<2> {
    let mut s = QuerySpec {
        form: Some(form.into()),
        stress: Some(stress),
        prestress: Some(prestress.into()),
        dim: Some(2),
        grid: Some(16),
        ..QuerySpec::default()
    };
    extra(&mut s);
    s.query::<2>(&Budget::default()).unwrap()
}

#[test]
fn classical_uniaxial_tension_is_hourglass_and_tensile() {
    // At k = (π, 0) the classical form's nodal gradient vanishes, so neither the stress rate nor
    // the density moves, and what is left is the pre-stress acting through the kernel Hessian:
    // D = −(2m/ρ²) Σ_J (1 − cos k·X_J) σ0 H_J, H = W″ ê ⊗ ê + (W′/r)(I − ê ⊗ ê). With σ0 = s e_x
    // ⊗ e_x only its xx entry is non-zero: ω² = −2 s V Σ (1 − cos k·X) H_xx.
    let s = 0.05;
    let q = ask("classical", s, "uniaxial", |_| {});
    let r = query(&q).unwrap();
    let kinds: Vec<Kind> = r.instabilities.iter().map(|i| i.kind).collect();
    assert!(
        kinds.contains(&Kind::Hourglass) && kinds.contains(&Kind::Tensile),
        "{kinds:?}"
    );
    let hg = r
        .instabilities
        .iter()
        .find(|i| i.kind == Kind::Hourglass)
        .unwrap();
    let tens = r
        .instabilities
        .iter()
        .find(|i| i.kind == Kind::Tensile)
        .unwrap();
    assert!(hg.unstressed_omega2.unwrap().abs() < 1e-12);
    assert!(hg.onset_stress.unwrap() < 1e-12);
    assert!(tens.unstressed_omega2.unwrap() > 1e-6 && tens.onset_stress.unwrap() > 0.0);
    assert!(tens.onset_stress.unwrap() < s);
    let kern = kernel::by_name("m4").unwrap();
    let lat = Lattice::<2>::named("square", 1.0).unwrap();
    let best = half_reciprocal(&lat)
        .into_iter()
        .map(|k| {
            let mut sum = 0.0;
            for (x, _, dw) in neighbours(&lat, "m4", 1.2) {
                let r = x[0].hypot(x[1]);
                let ex = x[0] / r;
                let hxx = kernel::d2w(kern, 2, r, 1.2) * ex * ex + dw / r * (1.0 - ex * ex);
                sum += (1.0 - (k[0] * x[0] + k[1] * x[1]).cos()) * hxx;
            }
            (-(-2.0 * s * sum)).max(0.0).sqrt()
        })
        .fold(0.0, f64::max);
    assert!(
        (hg.growth_rate - best).abs() < 1e-10 * best,
        "hourglass growth {} vs closed form {best}",
        hg.growth_rate
    );
}

#[test]
fn stabilised_forms_have_no_hourglass_kind_and_enog_keeps_a_tensile_threshold() {
    // every remedy removes the zero-energy modes: no hourglass kind, no rank deficiency
    for (form, hg) in [
        ("enog", None),
        ("tl-enog", None),
        ("total-lagrangian", Some(10.0)),
    ] {
        for ps in ["isotropic", "uniaxial", "shear"] {
            let q = ask(form, 0.05, ps, |s| s.hourglass = hg);
            let r = query(&q).unwrap();
            assert!(
                r.stable && !r.has_zero_energy_modes,
                "{form} {ps}: {:?}",
                r.instabilities
            );
        }
    }
    // SPH-ENOG with little shear stiffness (ν = 0.499): the pressure's tension overcomes the
    // shear acceleration's stiffness at the former hourglass wave vectors, a tensile kind with
    // a finite onset stress below the question's
    let q = ask("enog", 0.05, "isotropic", |s| s.poisson = Some(0.499));
    let r = query(&q).unwrap();
    assert_eq!(r.instabilities.len(), 1, "{:?}", r.instabilities);
    let i = &r.instabilities[0];
    assert_eq!(i.kind, Kind::Tensile);
    let onset = i.onset_stress.unwrap();
    assert!(onset > 0.0 && onset < 0.05, "onset {onset}");
    // below the onset it is stable (the continuation's claim, checked by the engine itself)
    let q = ask("enog", 0.5 * onset, "isotropic", |s| {
        s.poisson = Some(0.499)
    });
    assert!(query(&q).unwrap().stable);
}
