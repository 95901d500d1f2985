//! The artificial-stress study (`sphstab art-stress`, `analysis/art_stress.json`,
//! `figures/art_stress.{svg,json}`): the engine's transverse branch against an independent
//! lattice sum, the Swegle runs against the box operator, and the committed figure and data
//! against what the code produces now.

use crate::common;

use common::*;
use sphstab::art_stress::{
    ArtStressConfig, ArtStressReport, comparison_from_pysph, figure_svg, parse_config,
};
use sphstab::kernel::Kernel;
use sphstab::solver::swegle::{predict_swegle, run_swegle};
use std::f64::consts::PI;
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// ω² (in c²/Δx²) of the transverse zone-edge mode κΔx = (π, 0), polarisation ŷ, of classical
/// SPH with Monaghan–Gray artificial stress in a zero-shear material under isotropic tension
/// σ̄ = s/K on the square lattice (Δx = 1, ρ0 = 1, K = 1, so c = 1), derived by hand:
///
/// - The mode moves whole columns up and down alternately. The continuity (or summation)
///   density change Σ_J m (v_I − v_J)·∇W_IJ vanishes: only odd columns differ in velocity, and
///   ∂_yW is odd in the y offset. So σ = s I and R = −ε s/ρ² I stay uniform and the force is
///   a central pair force: a_I = C Σ_J g(r_IJ) x̂_IJ with C = 2 s m/ρ² = 2 s/ρ (m = ρΔx²,
///   ρ = (1 − σ̄)ρ0) and g(r) = (1 − ε φ(r)ⁿ) W'(r), φ = W(r)/W(Δx).
/// - Linearised: δa_I = C Σ_J [g' x̂x̂ᵀ + (g/r)(I − x̂x̂ᵀ)](δx_I − δx_J), so
///   ω² = −C Σ_J (1 − cos κ·x_J) [g'(r) ŷ_J² + g(r)/r (1 − ŷ_J²)] with
///   g' = (1 − εφⁿ) W'' − ε n φⁿ⁻¹ W'²/W(Δx).
fn omega2_transverse(k: &dyn Kernel, h: f64, sigma_bar: f64, eps: f64, n: i32) -> f64 {
    let s2 = k.sigma(2);
    let w = |r: f64| s2 / (h * h) * k.f(2, r / h);
    let w1 = |r: f64| s2 / (h * h * h) * k.df(2, r / h);
    let w2 = |r: f64| s2 / (h * h * h * h) * k.d2f(2, r / h);
    let w_dx = w(1.0);
    let rho = 1.0 - sigma_bar;
    let c = 2.0 * sigma_bar / rho;
    let reach = (k.zeta() * h).ceil() as i64 + 1;
    let mut sum = 0.0;
    for i in -reach..=reach {
        for j in -reach..=reach {
            let (x, y) = (i as f64, j as f64);
            let r = x.hypot(y);
            if r == 0.0 || r >= k.zeta() * h {
                continue;
            }
            let phi = w(r) / w_dx;
            let g = (1.0 - eps * phi.powi(n)) * w1(r);
            let gp = (1.0 - eps * phi.powi(n)) * w2(r)
                - eps * n as f64 * phi.powi(n - 1) * w1(r) * w1(r) / w_dx;
            let yy = (y / r).powi(2);
            // 1 − cos(π i) = 2 sin²(π i / 2)
            let one_minus_cos = 2.0 * (PI * x / 2.0).sin().powi(2);
            sum += one_minus_cos * (gp * yy + g / r * (1.0 - yy));
        }
    }
    -c * sum
}

#[test]
fn transverse_branch_matches_the_pair_force_lattice_sum() {
    // where the engine's fastest mode is the transverse (π, 0) mode (ε ≥ 0.15 at these
    // settings, `sphstab art-stress`), its growth must be √(−ω²) of the hand derivation
    let m4 = k("m4");
    let mut checked = 0;
    for (h, f) in [(1.2, 0.99), (1.3, 0.95)] {
        for eps in [0.2, 0.4, 0.6] {
            let cfg = ArtStressConfig::quick().swegle(h, f, eps).unwrap();
            let p = predict_swegle(&cfg).unwrap();
            let w2 = omega2_transverse(m4, h, 1.0 - f, eps, 4);
            assert!(
                w2 < 0.0,
                "h {h} f {f} ε {eps}: ω² = {w2} (expected unstable)"
            );
            assert!(
                p.infinite_longitudinal < 1e-9
                    && (p.infinite_kappa[0] - PI).abs() < 1e-12
                    && p.infinite_kappa[1].abs() < 1e-12,
                "fastest mode not transverse at (π, 0): {p:?}"
            );
            let g = (-w2).sqrt();
            assert!(
                (p.infinite_rate - g).abs() < 1e-9 * g,
                "h {h} f {f} ε {eps}: engine {} vs lattice sum {g}",
                p.infinite_rate
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 6);
}

#[test]
fn transverse_branch_without_artificial_stress_is_slower_than_the_longitudinal() {
    // ε = 0: the longitudinal zone-edge mode is the fastest (Swegle), and the transverse one
    // of the same lattice sum is slower but still unstable in a zero-shear material
    let cfg = ArtStressConfig::quick().swegle(1.2, 0.99, 0.0).unwrap();
    let p = predict_swegle(&cfg).unwrap();
    let w2t = omega2_transverse(k("m4"), 1.2, 0.01, 0.0, 4);
    assert!(p.infinite_longitudinal > 1.0 - 1e-9);
    assert!(w2t < 0.0 && (-w2t).sqrt() < p.infinite_rate);
}

#[test]
fn swegle_runs_grow_at_the_box_rate() {
    // measurement (time stepping) against the dense box operator (dual-number linearisation of
    // the same rate function): the fit window starts at 100× the kick, where slower modes still
    // weigh, so the fitted rate lies a little below the fastest mode's; it cannot lie above it
    // by more than the kdk error O((γΔt)²) ≈ 1e-3 at Δt = 0.2 Δx/c
    for (h, f, eps) in [(1.2, 0.95, 0.3), (1.3, 0.95, 0.1)] {
        let cfg = ArtStressConfig::quick().swegle(h, f, eps).unwrap();
        let r = run_swegle(&cfg, |_| {}).unwrap();
        let ratio = r.ratio_box.expect("the run grew into the fit window");
        assert!(
            (0.9..=1.002).contains(&ratio),
            "h {h} f {f} ε {eps}: measured/box {ratio}"
        );
    }
}

#[test]
fn committed_figure_and_data_match_the_code() {
    let cfg_path = root().join("analysis/art_stress.json");
    let cfg = parse_config(
        &cfg_path.display().to_string(),
        &std::fs::read_to_string(&cfg_path).unwrap(),
    )
    .unwrap();
    let out = cfg.output.clone().expect("the config names its figure");
    let data_path = root().join("figures").join(&out).with_extension("json");
    let rep: ArtStressReport =
        serde_json::from_str(&std::fs::read_to_string(&data_path).unwrap()).unwrap();
    assert_eq!(
        rep.config, cfg,
        "figures/{out}: data from another config; run `cargo run --release -- art-stress --config analysis/art_stress.json`"
    );
    let svg = std::fs::read_to_string(root().join("figures").join(&out)).unwrap();
    assert!(
        figure_svg(&rep).unwrap() == svg,
        "figures/{out} is not the drawing of its data: `sphstab art-stress --from figures/art_stress.json --plot figures/art_stress.svg`"
    );
    // the stored predictions are what the code computes now (a sample: first and last case,
    // three ε each, to 1e-9 — the dense eigen-solve is deterministic)
    for case in [rep.cases.first().unwrap(), rep.cases.last().unwrap()] {
        for p in case.points.iter().step_by(8) {
            let now =
                predict_swegle(&cfg.swegle(case.h, case.density_ratio, p.eps).unwrap()).unwrap();
            assert!(
                (now.infinite_rate - p.infinite).abs() <= 1e-9 * p.infinite.max(1e-12)
                    && (now.box_rate - p.in_box).abs() <= 1e-9 * p.in_box.max(1e-12),
                "h {} f {} ε {}: stored ({}, {}), now ({}, {}): regenerate figures/{out}",
                case.h,
                case.density_ratio,
                p.eps,
                p.infinite,
                p.in_box,
                now.infinite_rate,
                now.box_rate
            );
        }
    }
    // the compared code's points are the stored file's
    if let Some(c) = &cfg.compare {
        let text = std::fs::read_to_string(root().join(c)).unwrap();
        let cmp = comparison_from_pysph(c, &text).unwrap();
        let stored: usize = rep.cases.iter().map(|c| c.compare.len()).sum();
        assert_eq!(stored, cmp.points.len(), "regenerate figures/{out}");
    }
}

#[test]
fn bad_configs_and_flags_are_named() {
    let e = parse_config(
        "a.json",
        r#"{"h":[1.2],"density_ratio":[0.99],"eps":[0],"epsilon":1}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("epsilon"), "{e}");
    let e = parse_config(
        "a.json",
        r#"{"h":[1.2],"density_ratio":[0.99],"eps":[-0.1]}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("eps"), "{e}");
    let e = parse_config(
        "a.json",
        r#"{"form":"nonlocal","h":[1.2],"density_ratio":[0.99],"eps":[0]}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("nonlocal"), "{e}");
    assert_bad_inputs(&[
        (&["art-stress", "--eps", "nan"], "--eps"),
        (&["art-stress", "--h", "0.5"], "--h = 0.5"),
        (&["art-stress", "--art-n", "2.5"], "--art-n"),
        (&["art-stress", "--density-ratio", "2"], "--density-ratio"),
        (&["art-stress", "--from", "x.json"], "--plot"),
    ]);
    let e = comparison_from_pysph("p.json", r#"{"runs":[{"h":1.2,"density_ratio":0.99}]}"#)
        .unwrap_err();
    assert!(e.to_string().contains("runs[0].art_eps"), "{e}");
    let c = comparison_from_pysph(
        "p.json",
        r#"{"pysph_version":"1.0b2","runs":[{"h":1.2,"density_ratio":0.99,"art_eps":0.2,"pysph":{"growth_rate":null}}]}"#,
    )
    .unwrap();
    assert_eq!(c.label, "PySPH 1.0b2");
    assert_eq!(c.points, vec![(1.2, 0.99, 0.2, None)]);
}
