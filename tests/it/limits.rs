//! Issue 10: every input the new-user trial found — aborts, endless runs, wrong verdicts, two
//! validation paths, silently ignored flags, unreadable messages — now gives a correct result
//! or a one-line exit-2 error naming the right flag, before anything large is allocated (the
//! budget refuses estimates above 2 GiB by default; each refused case runs under a data limit
//! of half that, [`DATA_LIMIT_KIB`]) and before the run (runs the step budget refuses say so:
//! [`STEP_BUDGET`]; and each refused case runs under a CPU limit, [`CPU_LIMIT_S`]). No case is
//! timed by a clock: elapsed time measures the machine's load as much as the code.

use crate::common;

use common::*;

/// The data segment (heap and private writable mappings, `ulimit -d`) a refused case may use:
/// 1 GiB, half the default memory budget. A case refused only after allocating what the budget
/// refuses would die of this limit (allocation failure: abort) instead of exiting 2.
const DATA_LIMIT_KIB: u64 = 1024 * 1024;

/// The CPU time a refused case may use, in seconds (`ulimit -t`: the process's own CPU time,
/// which other jobs on the machine do not add to): the acceptance's 10 s. Refusing takes
/// milliseconds; a case that ran its work first (an atlas or a trade-off study: minutes) is
/// killed by the limit instead of exiting 2.
const CPU_LIMIT_S: u64 = 10;

/// The words of a refusal by the step budget (`budget::Budget::work`: "… needs about N
/// particle-steps, more than the limit M particle-steps (--max-steps)"): the run was estimated
/// and refused before its first step.
const STEP_BUDGET: &str = "(--max-steps)";

/// `sphstab args` under [`DATA_LIMIT_KIB`] and [`CPU_LIMIT_S`]: (exit code, -1 if killed;
/// stdout, stderr).
fn sphstab_capped(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -d {DATA_LIMIT_KIB} && ulimit -t {CPU_LIMIT_S} && exec \"$0\" \"$@\""
        ))
        .arg(env!("CARGO_BIN_EXE_sphstab"))
        .args(args)
        .output()
        .expect("run sphstab");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Exit 2, one line naming `flag`, nothing on stdout, under [`DATA_LIMIT_KIB`] and
/// [`CPU_LIMIT_S`]; returns the messages.
fn refused(cases: &[(&[&str], &str)]) -> Vec<String> {
    let mut messages = Vec::new();
    for (args, flag) in cases {
        let (code, out, err) = sphstab_capped(args);
        assert_eq!(code, 2, "{args:?}: exit {code}, stderr {err}");
        assert!(out.is_empty(), "{args:?}: stdout {out}");
        assert!(
            err.contains(flag),
            "{args:?}: stderr does not name {flag}: {err}"
        );
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        messages.push(err);
    }
    messages
}

/// [`refused`], each by the step budget ([`STEP_BUDGET`]).
fn refused_by_step_budget(cases: &[(&[&str], &str)]) {
    for ((args, _), err) in cases.iter().zip(refused(cases)) {
        assert!(
            err.contains(STEP_BUDGET),
            "{args:?}: not refused by the step budget: {err}"
        );
    }
}

/// A scene file in the temp directory: the `rod` built-in with `patch` merged in.
fn scene(name: &str, patch: serde_json::Value) -> String {
    let mut s = serde_json::json!({
        "name": "rod", "form": "total-lagrangian", "kernel": "efg-quartic", "h_over_dx": 1.5,
        "shape": "mls", "modulus": 1e10, "rho0": 2450.0, "initial_stress": 1e9, "particles": 41,
        "origin": 0.0, "length": 0.04,
        "initial_velocity": {"kind": "point", "index": 20, "value": 40.0},
        "left": {"layers": 3, "velocity": 0.0}, "right": {"layers": 3, "velocity": 0.0},
        "t_end": 1e-4, "dt": 0.2
    });
    for (k, v) in patch.as_object().unwrap() {
        s[k] = v.clone();
    }
    let dir = std::env::temp_dir().join(format!("sphstab-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(format!("{name}.json"));
    std::fs::write(&p, s.to_string()).unwrap();
    p.display().to_string()
}

/// "Aborts / unbounded memory": refused by the memory budget (or a size bound) before
/// allocating.
#[test]
fn memory_hogs_are_refused_before_allocating() {
    let big = scene("particles", serde_json::json!({"particles": 10_000_000}));
    refused(&[
        (&["query", "--dim", "2", "--h", "20"], "--h"),
        (&["query", "--dim", "2", "--h", "50"], "--h"),
        (
            &[
                "query", "--dim", "2", "--kernel", "gaussian", "--h", "50", "--grid", "2",
            ],
            "--h",
        ),
        (&["swegle", "--h", "50"], "--h"),
        (
            &["dispersion", "--dim", "2", "--points", "100000000"],
            "--points",
        ),
        (
            &[
                "atlas",
                "--h-points",
                "4096",
                "--stress-points",
                "4096",
                "--kappas",
                "1000000",
            ],
            "--h-points",
        ),
        (&["throughput", "--size", "3000"], "--size"),
        (&["simulate", &big], "particles"),
        (&["swegle", "--dt", "1e-9"], "--dt"),
        // a budget the user lowers is honoured, naming the flag that raises it
        (
            &["--max-memory", "100M", "query", "--dim", "2", "--h", "10"],
            "--max-memory",
        ),
    ]);
}

/// An endless character device as the scene: at most 1 MiB is read.
#[test]
fn endless_scene_file_is_cut_off() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    refused(&[
        (&["simulate", "/dev/zero"], "/dev/zero"),
        (&["merge", "/dev/zero"], "/dev/zero"),
    ]);
}

/// "Never finishes": refused by the step budget or a size bound.
#[test]
fn endless_runs_are_refused() {
    let s = |n: &str, p| scene(n, p);
    let modulus = s("modulus", serde_json::json!({"modulus": 1e308}));
    let rho0 = s("rho0", serde_json::json!({"rho0": 1e-308}));
    let length = s("length", serde_json::json!({"length": 1e-308}));
    let t308 = s("t308", serde_json::json!({"t_end": 1e308}));
    let t6 = s("t6", serde_json::json!({"t_end": 1e6}));
    refused_by_step_budget(&[
        (&["swegle", "--dt", "1e-308"], "--dt"),
        (&["simulate", &t308], "t_end"),
        (&["simulate", &t6], "t_end"),
        (&["swegle", "--t-end", "1000000"], "--t-end"),
        (&["simulate", "swegle", "--t-end", "1000000"], "--t-end"),
        (
            &["swegle", "--until-window", "--density-ratio", "0.9999999"],
            "--until-window",
        ),
        (&["throughput", "--steps", "1000000"], "--steps"),
    ]);
    // size bounds (a scene's scales in [1e-30, 1e30]: the step budget is not reached)
    refused(&[
        (&["simulate", &modulus], "modulus"),
        (&["simulate", &length], "length"),
        (&["simulate", &rho0], "rho0"),
        (&["query", "--dim", "2", "--grid", "4096"], "--grid"),
        (&["timestep", "--dim", "2", "--grid", "4096"], "--grid"),
        (&["map", "--n", "4096"], "--n"),
        (&["query", "--dim", "2", "--box", "10000"], "--box"),
        (
            &["stiffness", "--theta", "0", "--points", "1000000000"],
            "--points",
        ),
        (&["swegle", "--size", "2001"], "--size"),
    ]);
    // a figure config without series
    let dir = std::env::temp_dir().join(format!("sphstab-fig-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("a.json"),
        r#"{"output": "a.svg", "title": "t", "series": []}"#,
    )
    .unwrap();
    let d = dir.display().to_string();
    refused(&[(&["figures", "--configs", &d, "--out", &d], "series")]);
}

/// "False or misleading results": the verdicts follow the numbers.
#[test]
fn verdicts_follow_the_numbers() {
    // time-step only: the verdict names it and gives the growth per unit time of the row
    let v = json(&[
        "query",
        "--form",
        "total-lagrangian",
        "--kernel",
        "efg-quartic",
        "--support",
        "1.5",
        "--stress",
        "0",
        "--dt",
        "2.2",
        "--json",
    ]);
    assert_eq!(v["stable"], false);
    let ts = v["instabilities"]
        .as_array()
        .unwrap()
        .iter()
        .find(|i| i["kind"] == "time-step")
        .unwrap();
    assert_eq!(v["max_growth_rate"], ts["growth_rate"]);
    // leapfrog with ω² = sin²κ (eq 82, exact lattice values φ'(±1) = ∓1/2): at κ = π/2 and
    // Δt = 2.2, λ solves λ² − (2 − ω²Δt²)λ + 1 = 0: |λ| = the larger root of λ² + 2.84λ + 1
    let lam = (2.84 + (2.84f64 * 2.84 - 4.0).sqrt()) / 2.0;
    let g = lam.ln() / 2.2;
    assert!(
        (ts["growth_rate"].as_f64().unwrap() - g).abs() < 1e-9,
        "{ts}"
    );
    let (_, out, _) = sphstab(&[
        "query",
        "--form",
        "total-lagrangian",
        "--kernel",
        "efg-quartic",
        "--support",
        "1.5",
        "--stress",
        "0",
        "--dt",
        "2.2",
    ]);
    assert!(
        out.contains("UNSTABLE (time-step)") && out.contains(&format!("{g:.6}")),
        "{out}"
    );
    // σ̄ ≤ −1: C̄ = 1 + σ̄ ≤ 0 is a material instability ([B00] eq 32), even where ω = 0
    for s in ["-1", "-1.5"] {
        let v = json(&["query", "--stress", s, "--json"]);
        assert_eq!(v["stable"], false, "σ̄ = {s}");
        assert!(
            v["instabilities"]
                .as_array()
                .unwrap()
                .iter()
                .any(|i| i["kind"] == "material"),
            "σ̄ = {s}: {v}"
        );
    }
    // a fine κ grid does not turn the acoustic zero at κ → 0 into a zero-energy mode
    let v = json(&[
        "query", "--form", "nonlocal", "--stress", "0.01", "--points", "1000000", "--json",
    ]);
    let rd: Vec<_> = v["instabilities"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|i| i["kind"] == "rank-deficiency")
        .collect();
    // nonlocal has ω² = C̃S1² ([V21] eq 54, ERRATA E2): zero only at κ = π
    assert!(
        rd.iter().all(|i| i["kappa_min"].as_f64().unwrap() > 3.1),
        "{rd:?}"
    );
    // a growing branch is never `rank-deficiency`; a pole of the least-squares ω² is reported
    let v = json(&[
        "query",
        "--form",
        "least-squares",
        "--kernel",
        "m4",
        "--h",
        "2",
        "--shape",
        "mls",
        "--alpha-s",
        "10",
        "--stress",
        "0",
        "--json",
    ]);
    for i in v["instabilities"].as_array().unwrap() {
        if i["growth_rate"].as_f64().unwrap() > 0.0 {
            assert_ne!(i["kind"], "rank-deficiency", "{i}");
        }
    }
    // [B00 §4.3] with exact φ'' (issue 9): stable, where growth 11.8 was reported
    let v = json(&[
        "query",
        "--form",
        "least-squares",
        "--kernel",
        "efg-quartic",
        "--support",
        "2.5",
        "--stress",
        "0",
        "--alpha-s",
        "0.5",
        "--json",
    ]);
    assert_eq!(v["stable"], true);
    // Swegle with a form the engine says is stable: no measured/box ratio of noise
    let v = json(&[
        "swegle",
        "--form",
        "total-lagrangian",
        "--shape",
        "corrected",
        "--json",
    ]);
    assert!(v["ratio_box"].is_null(), "{}", v["ratio_box"]);
}

/// Scene files go through the CLI's checks (named fields), and runaways stop as DIVERGED.
#[test]
fn scenes_are_validated_like_flags_and_runaways_stop() {
    let cases = [
        (
            "stress",
            serde_json::json!({"initial_stress": 1e308}),
            "initial_stress",
        ),
        ("hsmall", serde_json::json!({"h_over_dx": 0.5}), "h_over_dx"),
        ("c5", serde_json::json!({"c_partition": 5.0}), "c_partition"),
        (
            "visc",
            serde_json::json!({"artificial_viscosity": [-1.0, 0.0]}),
            "artificial_viscosity",
        ),
        (
            "layers",
            serde_json::json!({"left": {"layers": 40, "velocity": 0.0}}),
            "layers",
        ),
        (
            "allfixed",
            serde_json::json!({"left": {"layers": 41, "velocity": 0.0}}),
            "layers",
        ),
        ("origin", serde_json::json!({"origin": 1e308}), "origin"),
    ];
    for (n, p, field) in cases {
        let f = scene(n, p);
        refused(&[(&["simulate", &f], field)]);
    }
    // σ̄ = −2: C̄ = C + σ < 0, a material instability of the continuum ([B00] eq 32) that the
    // total-Lagrangian form (linear in F) follows without bound: stopped and reported, exit 3
    let f = scene("runaway", serde_json::json!({"initial_stress": -2e10}));
    let (code, out, err) = sphstab(&["simulate", &f]);
    assert_eq!(code, 3, "{out} {err}");
    assert!(err.contains("DIVERGED at step"), "{err}");
    assert!(!out.contains("inf") && !out.contains("NaN"));
    // throughput validates like every command: lucy with h = 1 has no neighbours
    refused(&[(&["throughput", "--kernel", "lucy", "--h", "1"], "--h")]);
}

/// Flags that do not apply are errors, not silently ignored.
#[test]
fn inapplicable_flags_are_errors() {
    refused(&[
        (&["query", "--box", "15"], "--box"),
        (&["query", "--dim", "2", "--points", "64"], "--points"),
        (
            &["query", "--dim", "2", "--lattice", "hex", "--gamma", "2"],
            "--gamma",
        ),
        (
            &[
                "stiffness",
                "--lattice",
                "hex",
                "--quadrature",
                "stress-hex",
                "--gamma",
                "2",
            ],
            "--gamma",
        ),
        (&["query", "--dim", "2", "--art-n", "4"], "--art-n"),
        (&["timestep", "--dt", "0"], "--dt"),
        (&["map", "--dim", "1"], "--dim"),
        (&["simulate", "thesis-wave", "--t-end", "1"], "--t-end"),
        (&["query", "--lattice", "hex"], "--lattice"),
        // `--grid` samples κ in 1D too (schema version 1); with --points it is one too many,
        // and `dispersion` samples its path with --points only
        (&["query", "--grid", "32", "--points", "64"], "--points"),
        (&["dispersion", "--grid", "32"], "--grid"),
        (&["dispersion", "--dim", "2", "--points", "0"], "--points"),
        (&["stiffness", "--points", "8"], "--points"),
    ]);
}

/// Messages name the right flag and print numbers compactly.
#[test]
fn messages_name_the_flag_compactly() {
    refused(&[
        (&["swegle", "--density-ratio", "NaN"], "--density-ratio"),
        (&["query", "--support", "1"], "--support"),
        (&["stiffness", "--support", "1"], "--support"),
    ]);
    let (_, _, err) = sphstab(&["query", "--stress", "1e308"]);
    assert!(err.contains("1e308") && err.len() < 200, "{err}");
    // missing arguments are named; every scene is listed
    refused(&[
        (&["simulate"], "<SCENE>"),
        (&["merge"], "<FILES>"),
        (&["simulate", "nope"], "thesis-wave, swegle"),
    ]);
    // output paths are checked before the run (the atlas would take a minute first: the CPU
    // limit would kill it); for the atlas and swegle even before the run's estimate, which a
    // budget of one step refuses (the trade-off study has no step budget: `--max-steps 1
    // tradeoff` runs the whole study)
    refused(&[
        (&["map", "--plot", "/nonexistent-dir/x.svg"], "--plot"),
        (&["atlas", "--out", "/nonexistent-dir/a.json"], "--out"),
        (&["swegle", "--plot", "/nonexistent-dir/g.svg"], "--plot"),
        (&["tradeoff", "--plot", "/nonexistent-dir/t.svg"], "--plot"),
        (
            &[
                "--max-steps",
                "1",
                "atlas",
                "--out",
                "/nonexistent-dir/a.json",
            ],
            "--out",
        ),
        (
            &[
                "--max-steps",
                "1",
                "swegle",
                "--plot",
                "/nonexistent-dir/g.svg",
            ],
            "--plot",
        ),
    ]);
    // … and that budget does refuse those runs, with a writable path
    let dir = std::env::temp_dir().join(format!("sphstab-limits-out-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = |f: &str| dir.join(f).display().to_string();
    let (a, g) = (out("a.json"), out("g.svg"));
    refused_by_step_budget(&[
        (&["--max-steps", "1", "atlas", "--out", &a], "--kappas"),
        (&["--max-steps", "1", "swegle", "--plot", &g], "--t-end"),
    ]);
}

/// Human text has no Rust Debug formatting.
#[test]
fn text_output_has_no_debug_formatting() {
    for args in [
        &["query", "--dim", "2", "--material", "hydro"][..],
        &["query", "--dim", "2", "--lattice", "hex"],
        &["dispersion", "--dim", "2", "--points", "4"],
        &["stiffness", "--theta", "30", "--points", "4"],
    ] {
        let (code, out, err) = sphstab(args);
        assert_eq!(code, 0, "{args:?}: {err}");
        for bad in [
            "{ ",
            "Some(",
            "[(",
            "-0.000000e0",
            "Square",
            "Hydro",
            "Elastic",
        ] {
            assert!(!out.contains(bad), "{args:?}: `{bad}` in\n{out}");
        }
    }
}
