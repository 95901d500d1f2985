//! Every config in analysis/configs renders, and the committed figures/ are exactly what the
//! configs regenerate (run `cargo run --release -- figures` after changing either).

use sphstab::figures::{parse, render};
use std::path::Path;

#[test]
fn committed_figures_are_regenerated_from_configs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut n = 0;
    for e in std::fs::read_dir(root.join("analysis/configs")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_none_or(|x| x != "json") {
            continue;
        }
        let cfg = parse(
            &p.display().to_string(),
            &std::fs::read_to_string(&p).unwrap(),
        )
        .unwrap();
        assert!(
            !cfg.note.is_empty(),
            "{}: every figure needs a note",
            p.display()
        );
        let svg = render(&cfg).unwrap();
        let committed = std::fs::read_to_string(root.join("figures").join(&cfg.output))
            .unwrap_or_else(|_| panic!("figures/{} missing: run `sphstab figures`", cfg.output));
        assert!(
            svg == committed,
            "figures/{} is stale: run `cargo run --release -- figures`",
            cfg.output
        );
        n += 1;
    }
    assert!(n >= 5);
}

#[test]
fn unknown_fields_are_rejected_by_name() {
    let e = parse(
        "x.json",
        r#"{"output":"a.svg","title":"t","series":[],"colour":"red"}"#,
    )
    .unwrap_err();
    match e {
        sphstab::error::Error::Config { file, msg } => {
            assert_eq!(file, "x.json");
            assert!(msg.contains("colour"));
        }
        other => panic!("{other:?}"),
    }
    let e = parse("y.json", r#"{"output":"a.svg","title":"t","series":[{"form":"classical","kernel":"m4","stress":0,"hh":1}]}"#)
        .unwrap_err();
    assert!(e.to_string().contains("hh"));
}

/// The study figures (measured by `sphstab tradeoff --config analysis/tradeoff*.json` and
/// `sphstab pairing --config analysis/pairing3d.json`, which also write the data next to the
/// figure) are what the CLI draws from their committed data: `--from figures/X.json --plot`
/// redraws without measuring, and must give the committed SVG byte for byte (after a change
/// of the drawing code, redraw them with that command).
#[test]
fn committed_study_figures_are_redrawn_from_their_data() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = std::env::temp_dir().join(format!("sphstab-study-figures-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    for (cmd, name) in [
        ("tradeoff", "tradeoff"),
        ("tradeoff", "tradeoff2d"),
        ("tradeoff", "tradeoff_integrators"),
        ("pairing", "pairing3d"),
    ] {
        let out = tmp.join(format!("{name}.svg"));
        let data = root.join("figures").join(format!("{name}.json"));
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_sphstab"))
            .args([cmd, "--from"])
            .arg(&data)
            .arg("--plot")
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            run.status.success(),
            "sphstab {cmd} --from {}: {}",
            data.display(),
            String::from_utf8_lossy(&run.stderr)
        );
        let drawn = std::fs::read(&out).unwrap();
        let committed = std::fs::read(root.join("figures").join(format!("{name}.svg"))).unwrap();
        assert!(
            drawn == committed,
            "figures/{name}.svg is not what its data draws: run `cargo run --release -- {cmd} --from figures/{name}.json --plot figures/{name}.svg`"
        );
    }
    std::fs::remove_dir_all(&tmp).unwrap();
}

fn config(name: &str) -> sphstab::figures::FigureConfig {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("analysis/configs")
        .join(name);
    parse(
        &p.display().to_string(),
        &std::fs::read_to_string(&p).unwrap(),
    )
    .unwrap()
}

/// The y value of `c` at the abscissa `x` (a grid point).
fn at(c: &sphstab::plot::Curve, x: f64) -> f64 {
    let i =
        c.x.iter()
            .position(|v| (v - x).abs() < 1e-12)
            .unwrap_or_else(|| panic!("{}: no point at {x}", c.label));
    c.y[i]
}

/// B00 Fig 10's comparison curve, linear FE with lumped mass: ω²Δx²/c² = 2 − 2 cos κΔx from the
/// assembled stencil (C/Δx)(−1, 2, −1) over the nodal mass ρΔx — 4 at the cut-off, 2 at π/2.
#[test]
fn fig10_fe_curve_is_the_lumped_linear_element() {
    let cfg = config("b00_fig10_lagrangian_stress_points.json");
    let curves = sphstab::figures::panel_curves(&cfg).unwrap();
    let fe = curves[0]
        .iter()
        .find(|c| c.label.starts_with("linear FE"))
        .unwrap();
    assert!(fe.dashed);
    assert!((at(fe, 1.0) - 4.0).abs() < 1e-12);
    assert!((at(fe, 0.5) - 2.0).abs() < 1e-12);
    for (x, y) in fe.x.iter().zip(&fe.y) {
        let k = x * std::f64::consts::PI;
        assert!((y - (2.0 - 2.0 * k.cos())).abs() < 1e-12);
    }
}

/// ωΔx/c by B00 eq 119 from the stiffness values printed in B00 Table I (γ = 1, lumped mass):
/// ω² = Σ_jk K_jk cos(κ(j cos θ + k sin θ)), each (j, k) entry standing for its sign and
/// transposition images. Table I prints 4 significant digits: |Δω²| ≤ 2e-3 covers ~40 rounded
/// entries.
fn eq119_table1(column: &[((i64, i64), f64)], kappa: f64, theta_deg: f64) -> f64 {
    let (c, s) = (theta_deg.to_radians().cos(), theta_deg.to_radians().sin());
    let mut w2 = 0.0;
    for &((j, k), v) in column {
        let mut images = std::collections::BTreeSet::new();
        for (a, b) in [(j, k), (k, j)] {
            for sa in [-1, 1] {
                for sb in [-1, 1] {
                    images.insert((sa * a, sb * b));
                }
            }
        }
        for (a, b) in images {
            w2 += v * (kappa * (a as f64 * c + b as f64 * s)).cos();
        }
    }
    w2
}

#[test]
fn antiplane_figures_match_b00_table1_and_the_continuum() {
    use std::f64::consts::PI;
    // B00 Table I, "Cell integration 2×2" column (with the (±3, ±2) entry, ERRATA E7) and the
    // "Nodal integration" column (blank entries are 0).
    let cell2x2 = [
        ((0, 0), 0.6507),
        ((1, 0), 0.1016),
        ((1, 1), -0.05933),
        ((2, 0), -0.08733),
        ((2, 1), -0.05223),
        ((2, 2), -0.008851),
        ((3, 0), -0.002663),
        ((3, 1), -0.0008141),
        ((3, 2), -0.9193e-5),
    ];
    let nodal = [
        ((0, 0), 0.5062),
        ((1, 0), 0.1101),
        ((2, 0), -0.1132),
        ((2, 1), -0.05504),
        ((2, 2), -0.01338),
    ];
    let fig14 = sphstab::figures::panel_curves(&config("b00_fig14_antiplane_cells.json")).unwrap();
    let fig13 = sphstab::figures::panel_curves(&config("b00_fig13_antiplane_nodal.json")).unwrap();
    let find = |p: &[sphstab::plot::Curve], l: &str| {
        p.iter()
            .find(|c| c.label.starts_with(l))
            .unwrap_or_else(|| panic!("no curve {l}"))
            .clone()
    };
    let c0 = find(&fig14[1], "cell-2x2, θ = 0°");
    let c45 = find(&fig14[1], "cell-2x2, θ = 45°");
    let n0 = find(&fig13[0], "nodal, θ = 0°");
    let n45 = find(&fig13[0], "nodal, θ = 45°");
    for (curve, col, theta, xs) in [
        (&c0, &cell2x2[..], 0.0, [0.25, 0.5, 1.0]),
        (&c45, &cell2x2[..], 45.0, [0.5, 1.0, 2f64.sqrt()]),
        (&n0, &nodal[..], 0.0, [0.25, 0.5, 1.0]),
        (&n45, &nodal[..], 45.0, [0.5, 1.0, 2f64.sqrt()]),
    ] {
        for x in xs {
            // the figure's grid point nearest x (κ_i = cut-off · i / points)
            let i = curve
                .x
                .iter()
                .enumerate()
                .min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs()))
                .unwrap()
                .0;
            let k = curve.x[i] * PI;
            let paper = eq119_table1(col, k, theta);
            let w2 = curve.y[i] * curve.y[i];
            assert!(
                (w2 - paper).abs() < 2e-3,
                "{} at κΔx/π = {}: ω² = {w2}, eq 119 with Table I: {paper}",
                curve.label,
                curve.x[i]
            );
        }
    }
    // the zero-frequency modes of B00 §4.4 at the cut-offs: nodal at 0° and 45°, not 2×2
    assert!(at(&n0, 1.0) < 1e-6 && n45.y.last().unwrap().abs() < 1e-6);
    assert!(at(&c0, 1.0) > 0.5 && *c45.y.last().unwrap() > 0.1);
    // long waves: ω → cκ, the continuum of B00 eq 110 (first grid point, κΔx = π/200 or
    // √2π/200: the dispersion error is O(κ²), about 1e-4 there)
    for panel in fig13.iter().chain(&fig14) {
        for c in panel {
            let k = c.x[0] * PI;
            assert!(
                (c.y[0] / k - 1.0).abs() < 1e-3,
                "{}: {}",
                c.label,
                c.y[0] / k
            );
        }
    }
}

#[test]
fn new_config_fields_are_checked_by_name() {
    let e = parse(
        "a.json",
        r#"{"output":"a.svg","title":"t","antiplane":[{"quadrature":"nodal","theta":0,"kernel":"efg-cubic","support":2,"quad":1}]}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("quad"), "{e}");
    let e = parse(
        "b.json",
        r#"{"output":"a.svg","title":"t","panels":[{"title":"p","antiplane":[],"colour":1}]}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("colour"), "{e}");
    // one kind of curve per panel, curves either at the top level or in panels
    let s = r#"{"form":"classical","kernel":"m4","h":1.2,"stress":0}"#;
    let a = r#"{"quadrature":"nodal","theta":0,"kernel":"efg-cubic","support":2}"#;
    for bad in [
        format!(r#"{{"output":"a.svg","title":"t","series":[{s}],"antiplane":[{a}]}}"#),
        format!(
            r#"{{"output":"a.svg","title":"t","series":[{s}],"panels":[{{"title":"p","series":[{s}]}}]}}"#
        ),
        r#"{"output":"a.svg","title":"t","panels":[{"title":"p"}]}"#.to_string(),
        r#"{"output":"a.svg","title":"t"}"#.to_string(),
    ] {
        assert!(parse("c.json", &bad).is_err(), "{bad}");
    }
    let ok =
        format!(r#"{{"output":"a.svg","title":"t","panels":[{{"title":"p","antiplane":[{a}]}}]}}"#);
    parse("d.json", &ok).unwrap();
    // the engine route needs a quadrature
    let cfg = parse(
        "e.json",
        r#"{"output":"a.svg","title":"t","antiplane":[{"theta":0,"kernel":"efg-cubic","support":2}]}"#,
    )
    .unwrap();
    assert!(sphstab::figures::render(&cfg).is_err());
}
