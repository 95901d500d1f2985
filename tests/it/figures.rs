//! Every config in analysis/configs renders, and the committed figures/ are exactly what the
//! configs regenerate (run `cargo run --release -- figures` after changing either).

use sphstab::figures::{parse, render};
use std::path::Path;

#[test]
fn committed_figures_are_regenerated_from_configs() {
    use rayon::prelude::*;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let configs: Vec<_> = std::fs::read_dir(root.join("analysis/configs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    // each config on its own (a few run simulations: most of the time), so in parallel
    configs.par_iter().for_each(|p| {
        let cfg = parse(
            &p.display().to_string(),
            &std::fs::read_to_string(p).unwrap(),
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
    });
    assert!(configs.len() >= 5);
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

/// The config `name` with only the `scene` series (top level or per panel) that `keep` accepts.
fn config_with(
    name: &str,
    keep: impl Fn(&serde_json::Value) -> bool,
) -> sphstab::figures::FigureConfig {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("analysis/configs")
        .join(name);
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
    let filter = |o: &mut serde_json::Value| {
        if let Some(series) = o.get_mut("scene").and_then(|s| s.as_array_mut()) {
            series.retain(&keep);
            assert!(!series.is_empty(), "{name}: nothing kept");
        }
    };
    filter(&mut v);
    if let Some(panels) = v.get_mut("panels").and_then(|p| p.as_array_mut()) {
        panels.iter_mut().for_each(filter);
    }
    parse(&p.display().to_string(), &v.to_string()).unwrap()
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

/// The Swegle kind: the abscissa is t c/Δx with c/Δx = √(K/ρ0)/Δx = √(0.686275/2.8)/0.1 =
/// 4.951 per V21 time unit (V21 §7.2's box); the dashed line has slope γ_box/ln 10 per Δx/c,
/// i.e. the report's `predicted_growth_rate_box` × c/Δx per V21 time unit in ln |v|, spans the
/// fit window of `sphstab swegle` (history max |v|: the history that command fits) and passes
/// through that fit (its rate, in the legend, is the command's measured growth rate).
#[test]
fn swegle_kind_draws_the_box_slope_over_the_fit() {
    use sphstab::studies::swegle::{predict_swegle, run_swegle};
    let cfg = parse(
        "s.json",
        r#"{"output":"s.svg","title":"t","note":"n","swegle":[{"form":"classical","kernel":"m4","h":1.2,"density_ratio":0.95,"t_end":20,"history":"max"}]}"#,
    )
    .unwrap();
    let curves = sphstab::figures::panel_curves(&cfg).unwrap().remove(0);
    assert_eq!(curves.len(), 2);
    let (hist, line) = (&curves[0], &curves[1]);
    assert!(!hist.dashed && line.dashed);
    let sc = cfg.swegle[0].config().unwrap();
    let unit = (0.686275f64 / 2.8).sqrt() / 0.1;
    assert!((unit - 4.951).abs() < 5e-4);
    let report = run_swegle(&sc, |_| {}).unwrap();
    let pred = predict_swegle(&sc).unwrap();
    assert_eq!(pred.box_rate, report.predicted_growth_rate_box);
    // abscissa: every recorded step, in Δx/c
    assert_eq!(hist.x.len(), report.history_full.len());
    for (x, h) in hist.x.iter().zip(&report.history_full) {
        assert!((x - h[0] * unit).abs() < 1e-9 * (1.0 + x));
    }
    // drawn on a log axis: the ordinates are |v|, the slope is that of log10 |v|
    let slope = (line.y[1].log10() - line.y[0].log10()) / (line.x[1] - line.x[0]);
    assert!(
        (slope * std::f64::consts::LN_10 - pred.box_rate).abs() < 1e-12,
        "slope {slope}, box rate {}",
        pred.box_rate
    );
    // per V21 time unit, in ln |v|: γ_box c/Δx
    assert!((slope * std::f64::consts::LN_10 * unit - pred.box_rate * unit).abs() < 1e-12);
    let fit = report
        .fit
        .expect("f = 0.95 grows through the window by t = 20");
    assert!((line.x[0] - fit.window.0 * unit).abs() < 1e-9);
    assert!((line.x[1] - fit.window.1 * unit).abs() < 1e-9);
    assert!(
        hist.label
            .contains(&format!("fitted {:.4} c/Δx", fit.rate / unit)),
        "{}",
        hist.label
    );
    // the dashed line meets the drawn history inside the window (box and measured rates
    // agree to a few per cent, and it passes through the centroid of the fitted samples)
    let mid = 0.5 * (line.x[0] + line.x[1]);
    let i = hist
        .x
        .iter()
        .position(|&x| x >= mid)
        .expect("history covers the window");
    let on_line = line.y[0].log10() + slope * (hist.x[i] - line.x[0]);
    assert!(
        (hist.y[i].log10() - on_line).abs() < 0.2,
        "{} vs {on_line}",
        hist.y[i]
    );
}

/// The scene kind against the analytic solutions, each from the scene's published data:
/// uniform bar (V21 §7.1: E = 2, v = 0.001 X) σ = E g t, derived in tests/it/reproduction.rs
/// (`v21_uniform`: "σ̇ = (C + σ) ∂v/∂x integrates to C + σ = C(1 + g t), i.e. σ = C g t
/// exactly"); wall impact (V21 §7.4: E = 200 GPa, ρ = 8000, v0 = 50 m/s) σ = −ρ c v0 =
/// −2 GPa behind X − X_wall = c t, c = 5000 m/s; end pull (V21 §7.5: E = 70.8 GPa, ρ = 1550,
/// ±70 m/s) σ1 = ρ c v behind each front, 2σ1 where they overlap.
///
/// The committed configs are read with only the series checked here kept ([`config_with`]):
/// the analytic ones and Fig 9's `local`. The others are simulations this test does not look
/// at (`committed_figures_are_regenerated_from_configs` draws them all); a series' curve does
/// not depend on the series next to it, so the kept curves are the committed figures' own.
#[test]
fn scene_kind_draws_the_analytic_profiles() {
    let keep = |s: &serde_json::Value| s["route"] == "analytic" || s["form"] == "local";
    let fig9 = sphstab::figures::panel_curves(&config_with("v21_fig9_uniform_tension.json", keep))
        .unwrap();
    for (panel, t) in fig9.iter().zip([1.0, 10.0]) {
        let exact = 2.0 * 0.001 * t;
        let a = panel.iter().find(|c| c.dashed).unwrap();
        assert_eq!(a.x.len(), 100);
        assert!((a.x[0] + 0.5).abs() < 1e-12 && (a.x[99] - 0.5).abs() < 1e-12);
        for y in &a.y {
            assert!((y - exact).abs() < 1e-15, "{y} vs {exact}");
        }
        // the local form (corrected gradient) is exact in the interior (REPRODUCTION: 2e-6)
        let local = panel.iter().find(|c| c.label == "local").unwrap();
        for y in &local.y[10..90] {
            assert!((y / exact - 1.0).abs() < 1e-4, "{y}");
        }
    }
    let fig17 =
        sphstab::figures::panel_curves(&config_with("v21_fig17_compressive_wave.json", keep))
            .unwrap();
    let a = fig17[0].iter().find(|c| c.dashed).unwrap();
    // X in mm, σ in GPa; 500 particles on 50 mm, the wall at the third particle
    let dx = 50.0 / 499.0;
    let ct = 5000.0 * 5e-6 * 1e3;
    for (x, y) in a.x.iter().zip(&a.y) {
        let want = if x - 2.0 * dx < ct { -2.0 } else { 0.0 };
        assert!((y - want).abs() < 1e-9, "X = {x} mm: {y} GPa");
    }
    let fig21 =
        sphstab::figures::panel_curves(&config_with("v21_fig21_tensile_wave.json", keep)).unwrap();
    let a = fig21[0].iter().find(|c| c.dashed).unwrap();
    let c = (70.8e9f64 / 1550.0).sqrt();
    let s1 = 1550.0 * c * 70.0 / 1e9;
    let dx = 200.0 / 199.0;
    let (xl, xr) = (-100.0 + 6.0 * dx, 100.0 - 6.0 * dx);
    let ct = c * 2e-5 * 1e3;
    for (x, y) in a.x.iter().zip(&a.y) {
        let mut want = 0.0;
        if x - xl < ct {
            want += s1;
        }
        if xr - x < ct {
            want += s1;
        }
        assert!((y - want).abs() < 1e-9, "X = {x} mm: {y} GPa, want {want}");
    }
    // the overlap (|X| < 41 mm at 20 μs) doubles the single-front stress
    let mid = a.y[a.x.len() / 2];
    assert!((mid - 2.0 * s1).abs() < 1e-9 && (s1 - 0.733).abs() < 5e-4);
}

#[test]
fn time_domain_kinds_check_their_fields() {
    for bad in [
        r#"{"output":"a.svg","title":"t","scene":[{"scene":"uniform-bar","colour":1}]}"#,
        r#"{"output":"a.svg","title":"t","swegle":[{"form":"classical","kernel":"m4","h":1.2,"density_ratio":0.99,"hh":1}]}"#,
    ] {
        let e = parse("k.json", bad).unwrap_err();
        assert!(
            e.to_string().contains("colour") || e.to_string().contains("hh"),
            "{e}"
        );
    }
    // one kind per place
    let bad = r#"{"output":"a.svg","title":"t","scene":[{"scene":"uniform-bar"}],"series":[{"form":"classical","kernel":"m4","h":1.2,"stress":0}]}"#;
    assert!(parse("m.json", bad).is_err());
    // a scene without analytic solution cannot draw one
    let cfg = parse(
        "r.json",
        r#"{"output":"a.svg","title":"t","scene":[{"scene":"rod","route":"analytic"}]}"#,
    )
    .unwrap();
    assert!(sphstab::figures::render(&cfg).is_err());
}
