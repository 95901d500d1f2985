//! The 3D solver and the 3D Swegle test against the engine: the same rate functions as in 2D,
//! run on a cubic box. The predictions are independent of the time-domain run: the exact
//! linear operator of the same finite particle set (dense eigenvalues,
//! src/solver/box_operator.rs) and the Bloch linearisation of the infinite simple-cubic lattice.
//! Also: a uniformly pre-stressed periodic 3D lattice is an equilibrium of the solver, and the
//! 3D output (JSON with 3-vectors, legacy VTK with 3 coordinates) is well formed.

use crate::common;

use common::{json, sphstab};
use sphstab::forms::{FormKind, Material, Model, ModelParams2D, ObjectiveRate};
use sphstab::kernel;
use sphstab::lattice::Lattice3D;
use sphstab::shape::KernelParams;
use sphstab::solver::swegle::{
    SwegleConfig, SwegleReport, default_size, dense_size_limit, run_swegle,
};
use sphstab::solver::{BoundaryDensity, Run3D};
use sphstab::vonneumann::classify::GROWTH_TOL;
use sphstab::vonneumann::linearise::base_state;

/// A 9³ box (3³ free particles: 81 free degrees of freedom, dense operator), m4 h = 1.2Δx,
/// density ratio 0.9 (σ̄ = 0.1 tension), run to `t_end` (t = 1 ≈ 4.95 Δx/c).
fn small_box(form: FormKind, t_end: f64) -> SwegleReport {
    let mut cfg = SwegleConfig::new(form, kernel::by_name("m4").unwrap(), 1.2, 0.9).with_dim(3);
    cfg.size = 9;
    cfg.t_end = t_end;
    let r = run_swegle(&cfg, |_| {}).unwrap();
    eprintln!(
        "{} 9³ f = 0.9, t_end = {t_end}: measured {:?}, box {:.5} ({}), infinite {:.5}, measured/box {:?}, grew {}, max |v| end {:.3e}, {} steps in {:.2} s",
        r.form,
        r.measured_growth_rate,
        r.predicted_growth_rate_box,
        r.box_method,
        r.predicted_growth_rate_infinite,
        r.ratio_box,
        r.grew,
        r.max_velocity_end,
        r.steps,
        r.runtime_s
    );
    r
}

/// The sizes the help text and README state: dense operator up to 12³ (6³ free particles,
/// 648 ≤ 1,000 degrees of freedom), which is also the default 3D box; 2D unchanged (21, 28).
#[test]
fn documented_sizes() {
    assert_eq!(default_size(3), 12);
    assert_eq!(dense_size_limit(3, 3), 12);
    assert_eq!(default_size(2), 21);
    assert_eq!(dense_size_limit(2, 3), 28);
}

/// Classical SPH in tension grows at 0.90–1.00 of the fastest mode of the exact operator of
/// the same 9³ particle set (the kick excites slower modes too, so the fitted rate of max |v|
/// lies a little below the fastest), and the growing pattern is that operator's kind of mode:
/// its largest wave-vector component is the zone-edge-most one the box admits (3π/4 with 3
/// free particles per side), as the standing-mode prediction says.
#[test]
fn classical_tension_grows_at_the_box_operator_rate() {
    let r = small_box(FormKind::Classical, 25.0);
    assert_eq!(r.dim, 3);
    assert_eq!(r.box_method, "dense-operator");
    assert!(
        r.predicted_growth_rate_box > 0.1,
        "the box must be unstable"
    );
    let ratio = r.ratio_box.expect("no growth measured");
    assert!((0.90..=1.00).contains(&ratio), "measured/box {ratio}");
    // a 3³ free region cannot hold the infinite lattice's fastest mode
    assert!(r.predicted_growth_rate_box < r.predicted_growth_rate_infinite);
    assert!(r.fit.unwrap().r2 > 0.99);
    let (k, share) = r.dominant_kappa.clone().unwrap();
    let kmax = |v: &[f64]| v.iter().cloned().fold(0.0, f64::max);
    assert_eq!(k.len(), 3);
    assert_eq!(r.predicted_kappa_box.len(), 3);
    assert!(
        (kmax(&k) - kmax(&r.predicted_kappa_box)).abs() < 1e-12,
        "dominant {k:?} (share {share}), predicted {:?}",
        r.predicted_kappa_box
    );
}

/// The nonlocal and total-Lagrangian forms do not grow in the same box up to t = 12, by which
/// time classical SPH (box rate 0.261 c/Δx = 1.29 per unit time) has risen by e^15.5 ≈ 5 × 10⁶;
/// and the engine agrees: neither the box operator nor the infinite lattice has a growing mode.
#[test]
fn nonlocal_and_total_lagrangian_do_not_grow() {
    for form in [FormKind::Nonlocal, FormKind::TotalLagrangian] {
        let r = small_box(form, 12.0);
        assert!(!r.grew, "{form:?} grew: max |v| {}", r.max_velocity_end);
        assert!(r.measured_growth_rate.is_none(), "{form:?}");
        assert!(r.predicted_growth_rate_box <= GROWTH_TOL, "{form:?}");
        assert!(r.predicted_growth_rate_infinite <= GROWTH_TOL, "{form:?}");
    }
}

/// A uniformly, isotropically pre-stressed periodic lattice (simple cubic and bcc, tension and
/// compression, hydrodynamic and elastic, Eulerian and total-Lagrangian forms) is an
/// equilibrium: 20 leapfrog steps leave every particle at rest and every density and stress at
/// its initial value, to round-off (analytic value: exactly zero change).
#[test]
fn periodic_box_at_rest_stays_at_rest() {
    const TOL: f64 = 1e-12;
    let m4 = kernel::by_name("m4").unwrap();
    let jaumann = Material::elastic(1.0, 0.3, ObjectiveRate::Jaumann).unwrap();
    let hydro = Material::Hydro { bulk: 1.0 };
    for lattice in [Lattice3D::sc(), Lattice3D::bcc()] {
        // whole conventional cubes: an orthogonal periodic box, 5 cubes per side (> 2 supports)
        let (side, basis) = (lattice.cube_side(), lattice.cube_basis());
        let m = 5;
        let mut x = Vec::new();
        for c in 0..m * m * m {
            let cell = [c / (m * m), (c / m) % m, c % m];
            for b in &basis {
                x.push([0, 1, 2].map(|a| side * (cell[a] as f64 + b[a])));
            }
        }
        let l = side * m as f64;
        let period = [[l, 0.0, 0.0], [0.0, l, 0.0], [0.0, 0.0, l]];
        for form in [
            FormKind::Classical,
            FormKind::Nonlocal,
            FormKind::Lnl,
            FormKind::TotalLagrangian,
        ] {
            for material in [hydro, jaumann] {
                for sigma_bar in [0.05, -0.05] {
                    let p = ModelParams2D {
                        form,
                        shape: form.default_shape_2d(),
                        kp: KernelParams { kernel: m4, h: 1.2 },
                        material,
                        rho0: 1.0,
                        c_partition: 0.5,
                        av: None,
                        art_stress: None,
                        diffusion: None,
                    };
                    let (rho, s0) = base_state(&material, 1.0, sigma_bar).unwrap();
                    let vol = vec![lattice.area(); x.len()];
                    let model = Model::<3>::new(p, x.clone(), vol, rho, s0, Some(period)).unwrap();
                    let z0 = model.rest_state(rho);
                    let n = z0.x.len();
                    let mut run =
                        Run3D::new(model, z0.clone(), vec![false; n], BoundaryDensity::Evolve)
                            .unwrap();
                    for _ in 0..20 {
                        run.step(0.2).unwrap();
                    }
                    let what = format!("{:?} {form:?} {material:?} σ̄ = {sigma_bar}", lattice.kind);
                    let v = run.max_free_speed();
                    let drift = run
                        .z
                        .x
                        .iter()
                        .zip(&z0.x)
                        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()))
                        .fold(0.0, f64::max);
                    let drho = run
                        .z
                        .rho
                        .iter()
                        .map(|r| (r - rho).abs())
                        .fold(0.0, f64::max);
                    let dsig = run
                        .z
                        .sigma
                        .iter()
                        .zip(&z0.sigma)
                        .flat_map(|(a, b)| {
                            (0..9).map(move |k| (a[k / 3][k % 3] - b[k / 3][k % 3]).abs())
                        })
                        .fold(0.0, f64::max);
                    assert!(
                        v <= TOL && drift <= TOL && drho <= TOL && dsig <= TOL,
                        "{what}: max |v| {v:e}, position drift {drift:e}, Δρ {drho:e}, Δσ {dsig:e}"
                    );
                }
            }
        }
    }
}

/// `swegle --dim 3 --json --out DIR`: the JSON carries 3-vectors, and final.vtk is legacy VTK
/// with one line of 3 coordinates per particle (z varying: a 3D point set), vertices, and
/// per-point density and velocity (3 components).
#[test]
fn cli_writes_3d_json_and_vtk() {
    let dir = std::env::temp_dir().join(format!("sphstab-swegle3d-{}", std::process::id()));
    let d = dir.to_str().unwrap();
    let v = json(&[
        "swegle",
        "--dim",
        "3",
        "--size",
        "9",
        "--form",
        "total-lagrangian",
        "--density-ratio",
        "0.9",
        "--t-end",
        "2",
        "--json",
        "--out",
        d,
    ]);
    assert_eq!(v["dim"], 3);
    assert_eq!(v["size"], 9);
    assert_eq!(v["box_method"], "dense-operator");
    assert_eq!(v["predicted_kappa_box"].as_array().unwrap().len(), 3);
    assert_eq!(v["dominant_kappa"][0].as_array().unwrap().len(), 3);
    assert_eq!(v["grew"], false);
    let vtk = std::fs::read_to_string(dir.join("final.vtk")).unwrap();
    let lines: Vec<&str> = vtk.lines().collect();
    assert_eq!(lines[0], "# vtk DataFile Version 3.0");
    assert_eq!(lines[2], "ASCII");
    assert_eq!(lines[3], "DATASET POLYDATA");
    assert_eq!(lines[4], "POINTS 729 double");
    let pts: Vec<[f64; 3]> = lines[5..5 + 729]
        .iter()
        .map(|l| {
            let c: Vec<f64> = l
                .split_whitespace()
                .map(|t| t.parse::<f64>().unwrap())
                .collect();
            assert_eq!(c.len(), 3, "{l}");
            [c[0], c[1], c[2]]
        })
        .collect();
    for a in 0..3 {
        let lo = pts.iter().map(|p| p[a]).fold(f64::INFINITY, f64::min);
        let hi = pts.iter().map(|p| p[a]).fold(f64::NEG_INFINITY, f64::max);
        // 9 particles per side at spacing 0.1 around the origin, fixed outer layers
        assert!(
            (lo + 0.4).abs() < 1e-12 && (hi - 0.4).abs() < 1e-12,
            "axis {a}: {lo} {hi}"
        );
    }
    assert_eq!(lines[5 + 729], "VERTICES 729 1458");
    let data = vtk.find("POINT_DATA 729").expect("POINT_DATA");
    let vel = vtk[data..]
        .find("VECTORS velocity double")
        .expect("velocity");
    let vlines: Vec<&str> = vtk[data + vel..].lines().skip(1).take(729).collect();
    assert_eq!(vlines.len(), 729);
    assert!(vlines.iter().all(|l| {
        l.split_whitespace()
            .filter_map(|t| t.parse::<f64>().ok())
            .count()
            == 3
    }));
    // total-Lagrangian carries no density field; the stress is not written for a hydro run
    assert!(!vtk.contains("SCALARS density"));
    std::fs::remove_dir_all(&dir).ok();
}

/// Bad 3D input exits 2 naming the flag.
#[test]
fn cli_bad_3d_input() {
    common::assert_bad_inputs(&[
        (&["swegle", "--dim", "4"], "--dim"),
        (&["swegle", "--dim", "1"], "--dim"),
        (&["swegle", "--dim", "3", "--size", "8"], "--size"),
        (&["swegle", "--dim", "3", "--size", "202"], "--size"),
        (&["swegle", "--dim", "3", "--art-eps", "0.2"], "--art-eps"),
        (
            &["swegle", "--dim", "3", "--form", "least-squares"],
            "--form",
        ),
    ]);
    // the 2D range is unchanged
    let (code, _, err) = sphstab(&["swegle", "--size", "2002"]);
    assert!(code == 2 && err.contains("--size"), "{err}");
}
