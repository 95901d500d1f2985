//! The 3D solver and the 3D Swegle test against the engine: the same rate functions as in 2D,
//! run on a cubic box. The predictions are independent of the time-domain run: the exact
//! linear operator of the same finite particle set (src/studies/box_operator/: dense
//! eigenvalues up to 12³, its fastest mode by thick-restart Arnoldi on the matrix-free operator
//! beyond, checked against the dense one) and the Bloch linearisation of the infinite
//! simple-cubic lattice. Also: a uniformly pre-stressed periodic 3D lattice is an equilibrium
//! of the solver, and the 3D output (JSON with 3-vectors, legacy VTK with 3 coordinates) is
//! well formed.

use crate::common;

use common::{json, sphstab};
use sphstab::budget::Budget;
use sphstab::error::Error;
use sphstab::forms::{FormKind, Material, Model, ModelParams, ObjectiveRate};
use sphstab::kernel;
use sphstab::lattice::Lattice;
use sphstab::shape::KernelParams;
use sphstab::solver::{BoundaryDensity, Run};
use sphstab::studies::box_operator::{Start, box_growth, box_growth_iterative};
use sphstab::studies::swegle::{
    SwegleConfig, SwegleReport, default_size, dense_size_limit, predict_swegle, run_swegle,
};
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

/// The sizes the help text and docs/swegle.md state: the dense operator (the reference, and the
/// prediction of a box in which the iterative search finds no growing mode) up to 12³ (6³ free
/// particles, 648 ≤ 1,000 degrees of freedom), which is also the default 3D box; 2D unchanged
/// (21, 28).
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
    assert_eq!(r.box_method, "iterative-operator");
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
    for lattice in [Lattice::<3>::sc(), Lattice::<3>::bcc()] {
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
                    let p = ModelParams {
                        form,
                        shape: form.default_shape_in(2),
                        kp: KernelParams { kernel: m4, h: 1.2 },
                        material,
                        rho0: 1.0,
                        c_partition: 0.5,
                        av: None,
                        art_stress: None,
                        diffusion: None,
                        alpha_s: 0.0,
                        ls_length: 1.0,
                        hourglass: None,
                    };
                    let (rho, s0) = base_state(&material, 1.0, sigma_bar).unwrap();
                    let vol = vec![lattice.area(); x.len()];
                    let model = Model::<3>::new(p, x.clone(), vol, rho, s0, Some(period)).unwrap();
                    let z0 = model.rest_state(rho);
                    let n = z0.x.len();
                    let mut run =
                        Run::<3>::new(model, z0.clone(), vec![false; n], BoundaryDensity::Evolve)
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
    // (the Krylov space spans the 81 degrees of freedom: the smallest ω² converges, > 0)
    assert_eq!(v["box_method"], "iterative-operator");
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
        (&["swegle", "--dim", "3", "--kick", "1e-20"], "--kick"),
        (&["swegle", "--dim", "3", "--kick", "1e-8"], "--kick"),
        (
            &["swegle", "--dim", "3", "--form", "least-squares"],
            "--form",
        ),
    ]);
    // the 2D range is unchanged
    let (code, _, err) = sphstab(&["swegle", "--size", "2002"]);
    assert!(code == 2 && err.contains("--size"), "{err}");
}

/// A classical m4 h = 1.2 box of `size`^dim particles at density ratio `f`.
fn config(dim: usize, size: usize, form: FormKind, f: f64) -> SwegleConfig {
    let mut cfg = SwegleConfig::new(form, kernel::by_name("m4").unwrap(), 1.2, f).with_dim(dim);
    cfg.size = size;
    cfg
}

/// The iterative eigen-solver (thick-restart Arnoldi on the matrix-free operator, two rate
/// evaluations per product) finds the dense operator's fastest mode (every eigenvalue of the
/// assembled matrix, an independent route: one rate evaluation per Jacobian column) to 1e-8
/// relative: a 3D box (9³, symmetric operator), and 2D boxes of 21² whose searches restart
/// (450 degrees of freedom, basis 120), symmetric (classical) and not (cll: the corrected
/// half's boundary rows make D asymmetric, 5e-6 relative in a 3D 9³ box, so the Arnoldi
/// branch runs).
#[test]
fn iterative_operator_finds_the_dense_fastest_mode() {
    fn check<const D: usize>(cfg: &SwegleConfig, symmetric: bool) {
        let run = cfg.build::<D>().unwrap();
        let unit = cfg.sound_speed() / cfg.dx;
        let (dense, dofs) = box_growth(&run).unwrap();
        let it = box_growth_iterative(&run, Start::Generic, None, &Budget::default(), &())
            .unwrap()
            .expect("a growing mode");
        eprintln!(
            "{}D {} {}^D f = {}: dense {:.12} iterative {:.12} c/Δx ({} dofs, {} products, {} restarts, residual {:.1e} ‖D‖)",
            D,
            cfg.form.name(),
            cfg.size,
            cfg.density_ratio,
            dense / unit,
            it.rate / unit,
            it.dofs,
            it.products,
            it.restarts,
            it.residual
        );
        assert_eq!(it.dofs, dofs);
        assert_eq!(it.symmetric, symmetric);
        assert!(dense > 0.0);
        assert!(
            (it.rate / dense - 1.0).abs() <= 1e-8,
            "{} vs {dense}",
            it.rate
        );
    }
    check::<3>(&config(3, 9, FormKind::Classical, 0.9), true);
    let classical = config(2, 21, FormKind::Classical, 0.99);
    check::<2>(&classical, true);
    check::<2>(&config(2, 21, FormKind::Cll, 0.95), false);
}

/// Issue 24 item 5: 13³ (7³ free particles, 1,029 degrees of freedom, beyond the dense limit)
/// grows at its iterative box prediction to 2% (measured 0.9985 of it). The kick is 1e-14
/// instead of 1e-10 so that the fastest mode has 9 more e-folds to outgrow the slower ones
/// before the fixed fit window (1e-8 < max |v| < 1e-4): with the published kick, max |v| is
/// fitted while modes a few percent slower still share it (0.986 here). f = 0.97 keeps the run
/// short (~1,000 steps); the default f = 0.99 and larger boxes are in the `#[ignore]`d
/// `large_boxes_grow_at_the_iterative_prediction`.
#[test]
fn thirteen_cube_grows_at_the_iterative_prediction() {
    let mut cfg = config(3, 13, FormKind::Classical, 0.97);
    cfg.kick = 1e-14;
    cfg.until_window = true;
    let r = run_swegle(&cfg, |_| {}).unwrap();
    let ratio = r.ratio_box.expect("no growth measured");
    eprintln!(
        "13³ f = 0.97, kick 1e-14: measured {:?}, box {:.6} ({}), infinite {:.6}, measured/box {ratio:.4}, {} steps in {:.1} s",
        r.measured_growth_rate,
        r.predicted_growth_rate_box,
        r.box_method,
        r.predicted_growth_rate_infinite,
        r.steps,
        r.runtime_s
    );
    assert_eq!(r.box_method, "iterative-operator");
    assert!((ratio - 1.0).abs() <= 0.02, "measured/box {ratio}");
    assert!(r.fit.unwrap().r2 > 0.9999);
    // the 7³ free block holds modes closer to the zone corner than 6³, not the lattice's fastest
    assert!(r.predicted_growth_rate_box < r.predicted_growth_rate_infinite);
}

/// A box without growing modes (nonlocal, f = 0.95) has its fastest modes in the cluster of
/// zero-energy modes at ω² ≈ 0, which the iterative method cannot resolve: it stops after
/// `STABLE_PROBE` products, and the prediction is the dense operator's up to the dense limit
/// (2D 21²: exact, no growth), beyond it the standing modes' (3D 13³: no growth, as for the
/// infinite lattice), labelled so. An eigenvalue search the step budget cannot afford beyond
/// the dense limit is refused before it starts, naming `size`.
#[test]
fn iterative_prediction_falls_back_and_keeps_the_budget() {
    let p = predict_swegle(&config(2, 21, FormKind::Nonlocal, 0.95)).unwrap();
    assert_eq!(p.box_method, "dense-operator");
    assert!(p.box_rate <= GROWTH_TOL);
    let p = predict_swegle(&config(3, 13, FormKind::Nonlocal, 0.95)).unwrap();
    assert_eq!(p.box_method, "standing-modes");
    assert!(p.box_rate <= GROWTH_TOL && p.infinite_rate <= GROWTH_TOL);
    let mut cfg = config(3, 13, FormKind::Classical, 0.99);
    cfg.t_end = 1.0;
    cfg.budget.max_steps = 1e5; // the run (2,197 particles × 25 steps) fits, 22 products do not
    match predict_swegle(&cfg) {
        Err(Error::Budget { fields, .. }) => {
            assert!(format!("{fields:?}").contains("size"), "{fields:?}")
        }
        other => panic!("{other:?}"),
    }
}

/// The table of the "3D Swegle" line of docs/results.md (classical m4 h = 1.2, f = 0.99, kick 1e-14,
/// `--until-window`): measured against the box prediction at 12³ (dense), 13³, 17³ and 21³
/// (iterative), each within 2%, with the fastest mode the centre kick can excite (the Krylov
/// space of the run's initial velocity; at odd sizes the kick sits on every mirror plane of the
/// box, so a mode odd under one of them is never excited: 13³'s fastest is such a mode), the
/// iterative solver's products and times, and the 12³ dense and iterative predictions against
/// each other. 6–9 minutes on this shared 2-core machine. The default suite runs 13³ at f = 0.97
/// (`thirteen_cube_grows_at_the_iterative_prediction`).
#[test]
#[ignore = "6–9 minutes: the 17³ and 21³ runs; run with --ignored --nocapture"]
fn large_boxes_grow_at_the_iterative_prediction() {
    let dense12 = {
        let run = config(3, 12, FormKind::Classical, 0.99)
            .build::<3>()
            .unwrap();
        let t = std::time::Instant::now();
        let d = box_growth(&run).unwrap().0;
        let td = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let it = box_growth_iterative(&run, Start::Generic, None, &Budget::default(), &())
            .unwrap()
            .unwrap();
        eprintln!(
            "12³ f = 0.99: dense {d:.12} ({td:.1} s), iterative {:.12} ({:.1} s, {} products), relative difference {:.1e}",
            it.rate,
            t.elapsed().as_secs_f64(),
            it.products,
            (it.rate / d - 1.0).abs()
        );
        assert!((it.rate / d - 1.0).abs() <= 1e-8);
        d
    };
    assert!(dense12 > 0.0);
    eprintln!(
        "| size | kick | measured | box | method | kicked | measured/box | measured/kicked | products | prediction s | run s |"
    );
    for (size, kick) in [
        (12, 1e-14),
        (13, 1e-10),
        (13, 1e-14),
        (17, 1e-14),
        (21, 1e-14),
    ] {
        let mut cfg = config(3, size, FormKind::Classical, 0.99);
        cfg.kick = kick;
        cfg.until_window = true;
        let unit = cfg.sound_speed() / cfg.dx;
        let run = cfg.build::<3>().unwrap();
        let t = std::time::Instant::now();
        let global = box_growth_iterative(&run, Start::Generic, None, &cfg.budget, &())
            .unwrap()
            .unwrap();
        let t_pred = t.elapsed().as_secs_f64();
        let kicked = box_growth_iterative(&run, Start::Velocity, None, &cfg.budget, &())
            .unwrap()
            .unwrap();
        let r = run_swegle(&cfg, |_| {}).unwrap();
        let m = r.measured_growth_rate.unwrap();
        let k = kicked.rate / unit;
        eprintln!(
            "| {size}³ | {kick:.0e} | {m:.5} | {:.5} | {} | {k:.5} | {:.4} | {:.4} | {} | {t_pred:.1} | {:.1} |",
            r.predicted_growth_rate_box,
            r.box_method,
            m / r.predicted_growth_rate_box,
            m / k,
            global.products,
            r.runtime_s
        );
        assert!((global.rate / unit / r.predicted_growth_rate_box - 1.0).abs() <= 1e-8);
        assert!(k <= r.predicted_growth_rate_box * (1.0 + 1e-8));
        assert!((m / r.predicted_growth_rate_box - 1.0).abs() <= 0.02);
    }
}
