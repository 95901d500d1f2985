//! The trade-off study: its numbers against independent closed forms, the committed figure
//! against its stored data, and the grid against the analysis config.

mod common;

use sphstab::tradeoff::{TradeoffConfig, TradeoffReport, grid, pareto_svg, parse_config, run};
use std::f64::consts::PI;
use std::path::Path;

/// m4 at h = Δx: the SPH derivative is the central difference, so ω(κ) = sin κ (c/Δx) at σ̄ = 0
/// for the classical and difference forms (uniform lattice, Σ_j W'(j) j = −1 exactly), the
/// leapfrog Δt_crit = 2/max ω = 2, and a standing wave of wave number k oscillates at ω_d with
/// cos(ω_d Δt) = 1 − ω²Δt²/2. Every expected value below is computed from these closed forms,
/// not from the code under test.
#[test]
fn tradeoff_numbers_match_closed_forms_for_m4_at_h_equal_dx() {
    // m4's customary range is [1, 2]: three h points are 1, 1.5, 2; the checks use h = 1
    let cfg = TradeoffConfig {
        dim: 1,
        forms: vec!["classical".into(), "nonlocal".into()],
        kernels: vec!["m4".into()],
        h_points: 3,
        repeats: 1,
        ..Default::default()
    };
    let rep = run(&cfg, None, |_, _| {}).unwrap();
    let rows: Vec<_> = rep.rows.iter().filter(|r| r.h_over_dx == 1.0).collect();
    assert_eq!(rows.len(), 2);
    for r in rows {
        assert!(r.error.is_none(), "{r:?}");
        for ppw in [10.0, 20.0] {
            let k = 2.0 * PI / ppw;
            let expect = 1.0 - k.sin() / k;
            let got = if ppw == 10.0 {
                r.phase_error_10ppw
            } else {
                r.phase_error_20ppw
            }
            .unwrap();
            assert!(
                (got - expect).abs() < 1e-12,
                "{}: {got} vs {expect}",
                r.form
            );
        }
        assert!((r.critical_dt.unwrap() - 2.0).abs() < 1e-6, "{r:?}");
        // standing wave, 20 ppw, Δt = 0.2, t = 2.125 periods (period 20 Δx/c)
        let (k, dt) = (2.0 * PI / 20.0, 0.2);
        let steps = (2.125f64 * 20.0 / dt).round();
        let t = steps * dt;
        let w = k.sin();
        let wd = (1.0 - 0.5 * w * w * dt * dt).acos() / dt;
        let expect = ((wd * t).cos() - (k * t).cos()).abs() / (k * t).cos().abs();
        let got = r.wave_l2_error.unwrap();
        assert!(
            (got / expect - 1.0).abs() < 1e-3,
            "{}: L2 {got} vs closed form {expect}",
            r.form
        );
        assert!(r.ns_per_particle_step.unwrap() > 0.0);
        assert_eq!(r.neighbours_per_particle, Some(2.0));
        assert!(r.bytes_per_particle.is_none(), "no probe, no memory column");
    }
    let by = |f: &str| {
        rep.rows
            .iter()
            .find(|r| r.form == f && r.h_over_dx == 1.0)
            .unwrap()
    };
    // Swegle: W''(Δx) > 0 for m4 at h = Δx, so the classical form grows at any tension
    assert_eq!(by("classical").max_stable_tension, Some(0.0));
    // the difference form has no stress term in its linearisation (ERRATA E2): stable to the cap
    assert_eq!(by("nonlocal").max_stable_tension, Some(0.999));
    assert_eq!(by("nonlocal").stable_in_compression, Some(true));
}

#[test]
fn least_squares_runs_with_its_consistent_mass() {
    let cfg = TradeoffConfig {
        dim: 1,
        forms: vec!["least-squares".into()],
        kernels: vec!["efg-quartic".into()],
        h_points: 1,
        repeats: 1,
        ..Default::default()
    };
    let rep = run(&cfg, None, |_, _| {}).unwrap();
    let r = &rep.rows[0];
    assert!(r.error.is_none(), "{r:?}");
    assert!(r.wave_l2_error.unwrap().is_finite());
}

#[test]
fn committed_tradeoff_figures_are_drawn_from_their_stored_data() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut n = 0;
    for e in std::fs::read_dir(root.join("analysis")).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if !(name.starts_with("tradeoff") && name.ends_with(".json")) {
            continue;
        }
        let cfg = parse_config(&name, &std::fs::read_to_string(&p).unwrap()).unwrap();
        assert!(!cfg.note.is_empty(), "{name}: every figure needs a note");
        let out = cfg.output.clone().unwrap();
        let data = root.join("figures").join(&out).with_extension("json");
        let rep: TradeoffReport =
            serde_json::from_str(&std::fs::read_to_string(&data).unwrap()).unwrap();
        // the stored study covers exactly the configured grid
        let g = grid(&cfg).unwrap();
        assert_eq!(rep.dim, cfg.dim);
        assert_eq!(rep.rows.len(), g.len(), "{name}");
        for (r, (f, k, h)) in rep.rows.iter().zip(&g) {
            assert_eq!((r.form.as_str(), r.kernel.as_str()), (f.name(), k.name()));
            assert!((r.h_over_dx - h).abs() < 1e-12);
        }
        let svg = pareto_svg(&rep, &sphstab_title(&rep)).unwrap();
        let committed = std::fs::read_to_string(root.join("figures").join(&out)).unwrap();
        assert!(
            svg == committed,
            "figures/{out} differs from its data: run `cargo run --release -- tradeoff --from figures/{} --plot figures/{out}`",
            data.file_name().unwrap().to_string_lossy()
        );
        n += 1;
    }
    assert!(n >= 1);
}

/// The CLI's title (src/bin/sphstab/tradeoff.rs), repeated here because the binary's modules
/// are not a library.
fn sphstab_title(rep: &TradeoffReport) -> String {
    format!(
        "speed/accuracy trade-off, {}D: every form × kernel × h (filled: stable at σ̄ = ±0.01)",
        rep.dim
    )
}

#[test]
fn tradeoff_bad_input_is_one_line_exit_2() {
    common::assert_bad_inputs(&[
        (&["tradeoff", "--dim", "3"], "--dim"),
        (&["tradeoff", "--h-points", "0"], "--h-points"),
        (&["tradeoff", "--repeats", "0"], "--repeats"),
        (&["tradeoff", "--kernels", "m7"], "kernel"),
        (
            &["tradeoff", "--dim", "2", "--forms", "least-squares"],
            "--forms",
        ),
    ]);
}

#[test]
fn atlas_shards_merge_into_the_whole_sweep() {
    let dir = std::env::temp_dir().join(format!("sphstab-atlas-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = [
        "atlas",
        "--forms",
        "classical,nonlocal",
        "--kernels",
        "m4",
        "--h-points",
        "3",
        "--stress-points",
        "4",
        "--kappas",
        "64",
    ];
    let whole = dir.join("whole.json");
    let mut args: Vec<String> = base.iter().map(|s| s.to_string()).collect();
    args.extend(["--out".into(), whole.display().to_string()]);
    let (code, _, _) = common::sphstab(&args.iter().map(|s| s.as_str()).collect::<Vec<_>>());
    assert_eq!(code, 0);
    let mut files = Vec::new();
    for i in 0..3 {
        let f = dir.join(format!("s{i}.json"));
        let mut a = args[..args.len() - 2].to_vec();
        a.extend([
            "--shard".into(),
            format!("{i}/3"),
            "--out".into(),
            f.display().to_string(),
        ]);
        let (code, _, _) = common::sphstab(&a.iter().map(|s| s.as_str()).collect::<Vec<_>>());
        assert_eq!(code, 0);
        files.push(f.display().to_string());
    }
    let merged = dir.join("merged.json");
    let mut m = vec!["merge".to_string()];
    m.extend(files.iter().cloned());
    m.extend(["--out".into(), merged.display().to_string()]);
    let (code, _, err) = common::sphstab(&m.iter().map(|s| s.as_str()).collect::<Vec<_>>());
    assert_eq!(code, 0, "{err}");
    let read = |p: &Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
    };
    assert_eq!(read(&whole)["cells"], read(&merged)["cells"]);
    assert_eq!(read(&whole)["cells"].as_array().unwrap().len(), 2 * 3 * 4);
    // a missing or repeated shard is an error, not a silent hole
    let (code, _, err) = common::sphstab(&["merge", &files[0], &files[1]]);
    assert_eq!(code, 2);
    assert!(err.contains("shard 2/3 is missing"), "{err}");
    let (code, _, err) = common::sphstab(&["merge", &files[0], &files[0], &files[1]]);
    assert_eq!(code, 2);
    assert!(err.contains("given twice"), "{err}");
    common::assert_bad_inputs(&[
        (&["atlas", "--shard", "3/3"], "--shard"),
        (&["atlas", "--shard", "x"], "--shard"),
        (&["atlas", "--kappas", "1"], "--kappas"),
        (&["atlas", "--stress-min", "-2"], "--stress-min"),
    ]);
    std::fs::remove_dir_all(&dir).ok();
}
