//! The command line: acceptance commands, JSON fields, plot output, and bad input (exit 2 with
//! a one-line message naming the flag; we check the flag name only, not the wording).

use crate::common;

use common::{assert_bad_inputs, json, sphstab};

#[test]
fn default_query_runs_and_prints_a_verdict() {
    let (code, out, _) = sphstab(&["query"]);
    assert_eq!(code, 0);
    assert!(out.contains("verdict: UNSTABLE"), "{out}");
    assert!(out.contains("tensile"));
}

#[test]
fn acceptance_classical_is_tensile_unstable_tl_and_nonlocal_do_not_grow() {
    let base = [
        "query", "--kernel", "m4", "--h", "1.2", "--stress", "0.01", "--json", "--form",
    ];
    let mut a = base.to_vec();
    a.push("classical");
    let v = json(&a);
    assert_eq!(v["stable"], false);
    assert!(v["max_growth_rate"].as_f64().unwrap() > 0.0);
    assert!(
        v["instabilities"]
            .as_array()
            .unwrap()
            .iter()
            .any(|i| i["kind"] == "tensile")
    );
    for key in [
        "form",
        "kernel",
        "shape",
        "h_over_dx",
        "support_over_dx",
        "stress",
        "stable",
        "max_growth_rate",
        "kappa_at_max",
        "instabilities",
        "critical_dt",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert!(v["critical_dt"].is_null());
    for form in ["total-lagrangian", "nonlocal"] {
        let mut a = base.to_vec();
        a.push(form);
        let v = json(&a);
        assert_eq!(v["stable"], true, "{form}");
        assert_eq!(v["max_growth_rate"].as_f64().unwrap(), 0.0);
        assert!(
            v["instabilities"]
                .as_array()
                .unwrap()
                .iter()
                .all(|i| i["growth_rate"].as_f64().unwrap() == 0.0)
        );
        assert!(v["critical_dt"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn support_flag_is_h_times_zeta() {
    let v = json(&[
        "query",
        "--form",
        "total-lagrangian",
        "--kernel",
        "m4",
        "--support",
        "2.4",
        "--json",
    ]);
    assert!((v["h_over_dx"].as_f64().unwrap() - 1.2).abs() < 1e-12);
    assert!((v["support_over_dx"].as_f64().unwrap() - 2.4).abs() < 1e-12);
}

#[test]
fn dispersion_json_and_svg() {
    let dir = std::env::temp_dir().join(format!("sphstab-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("fig.svg");
    let v = json(&[
        "dispersion",
        "--form",
        "classical",
        "--kernel",
        "efg-quartic",
        "--support",
        "1.5",
        "--shape",
        "mls",
        "--stress",
        "0.2",
        "--points",
        "64",
        "--json",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    // schema version 1: κ and the branch are one-component arrays in 1D, `path` is κΔx
    assert_eq!(v["schema_version"], 1);
    assert_eq!(v["kappa"].as_array().unwrap().len(), 64);
    assert_eq!(v["omega2"].as_array().unwrap().len(), 64);
    assert_eq!(v["omega2"][0].as_array().unwrap().len(), 1);
    let pi = std::f64::consts::PI;
    assert_eq!(v["path"][63].as_f64(), Some(pi));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") || text.contains("<svg"));
    assert!(text.contains("ω²Δx²/c²") && text.contains("κΔx/π") && text.contains("continuum"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn timestep_reports_table2_limit() {
    let v = json(&[
        "timestep",
        "--form",
        "total-lagrangian",
        "--kernel",
        "efg-quartic",
        "--support",
        "1.5",
        "--stress",
        "0",
        "--json",
    ]);
    assert!((v["critical_dt"].as_f64().unwrap() - 2.0).abs() < 1e-4);
    assert!((v["omega_max"].as_f64().unwrap() - 1.0).abs() < 1e-4);
}

#[test]
fn kernels_lists_all_eleven() {
    let v = json(&["kernels", "--json"]);
    assert_eq!(v.as_array().unwrap().len(), 11);
}

/// Each bad input: exit status 2, one line on stderr naming the offending flag, nothing on stdout.
#[test]
fn bad_input_exits_2_naming_the_flag() {
    let cases: &[(&[&str], &str)] = &[
        (&["query", "--kernel", "nope"], "kernel"),
        (&["query", "--form", "nope"], "form"),
        (&["query", "--shape", "nope"], "shape"),
        (&["query", "--h", "0"], "--h"),
        (&["query", "--h", "-1"], "--h"),
        (&["query", "--h", "NaN"], "--h"),
        (&["query", "--h", "inf"], "--h"),
        (&["query", "--support", "0"], "--support"),
        (&["query", "--stress", "nan"], "--stress"),
        (&["query", "--form", "lnl", "--c", "1.5"], "--c"),
        (&["query", "--form", "lnl", "--c", "-0.1"], "--c"),
        (&["query", "--dt", "0"], "--dt"),
        (&["query", "--dt", "-1"], "--dt"),
        (&["dispersion", "--points", "1"], "--points"),
        (&["timestep", "--h", "nan"], "--h"),
        (&["query", "--form", "local", "--shape", "sph"], "--shape"),
        (&["query", "--h", "abc"], "--h"),
    ];
    assert_bad_inputs(cases);
}

/// Unknown names list the valid ones.
#[test]
fn unknown_kernel_lists_valid_names() {
    let (_, _, err) = sphstab(&["query", "--kernel", "cubic"]);
    for k in ["m4", "wendland-c2", "mollifier"] {
        assert!(err.contains(k));
    }
}

/// Extremes of SPEC/DEVELOPERS: h/Δx from 0.8 to 6, σ̄ = ±0.999, κ up to π: finite output, no NaN.
#[test]
fn extremes_give_finite_output() {
    for h in ["0.8", "6"] {
        for s in ["0.999", "-0.999"] {
            for form in [
                "classical",
                "local",
                "lnl",
                "total-lagrangian",
                "eulerian-stress-points",
            ] {
                let (code, out, err) = sphstab(&[
                    "dispersion",
                    "--form",
                    form,
                    "--kernel",
                    "m4",
                    "--h",
                    h,
                    "--stress",
                    s,
                    "--points",
                    "32",
                    "--json",
                ]);
                assert_eq!(code, 0, "{form} h={h} σ̄={s}: {err}");
                assert!(
                    !out.contains("NaN") && !out.contains("null"),
                    "{form} h={h} σ̄={s}"
                );
            }
        }
    }
}

/// A reader that stops early (`sphstab dispersion … | head -1`) closes the pipe: the binary ends
/// quietly with the SIGPIPE status 141, no panic message (6 MB of output, far beyond a pipe's
/// buffer, so the write after the close is certain to fail).
#[test]
fn closed_pipe_ends_quietly() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_sphstab"))
        .args(["dispersion", "--form", "classical", "--kernel", "m4"])
        .args(["--h", "1.2", "--stress", "0.01", "--points", "100000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(first.starts_with("# classical"), "{first}");
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(141), "{err}");
    assert!(err.is_empty(), "{err}");
}

/// Issue 23: `query`, `dispersion` and `timestep` print one schema (version 1) in every
/// dimension — the same keys in 1D, 2D and 3D, except `alpha_s` (1D only); wave vectors have D
/// components.
#[test]
fn one_json_schema_in_every_dimension() {
    let keys = |v: &serde_json::Value| {
        let mut k: Vec<String> = v
            .as_object()
            .unwrap()
            .keys()
            // 1D only (α_s) and D ≥ 2 only (the pre-stress's shape)
            .filter(|k| *k != "alpha_s" && *k != "prestress")
            .cloned()
            .collect();
        k.sort();
        k
    };
    for verb in ["query", "dispersion", "timestep"] {
        let size = if verb == "dispersion" {
            "--points"
        } else {
            "--grid"
        };
        let out: Vec<serde_json::Value> = ["1", "2", "3"]
            .iter()
            .map(|d| json(&[verb, "--dim", d, "--stress", "0.05", size, "4", "--json"]))
            .collect();
        for (d, v) in out.iter().enumerate() {
            assert_eq!(v["schema_version"], 1, "{verb} --dim {}", d + 1);
            assert_eq!(v["dim"], d + 1);
            assert_eq!(keys(v), keys(&out[0]), "{verb} --dim {}", d + 1);
            assert_eq!(v.get("alpha_s").is_some(), d == 0, "{verb}");
        }
        if verb == "query" {
            for (d, v) in out.iter().enumerate() {
                // classical m4 h 1.2 in tension grows: a D-component fastest wave vector
                assert_eq!(v["kappa_at_max"].as_array().unwrap().len(), d + 1);
                let rows = v["instabilities"].as_array().unwrap();
                assert!(
                    rows.iter()
                        .all(|r| r["kappa_at_max"].as_array().unwrap().len() == d + 1)
                );
            }
        }
        if verb == "dispersion" {
            for (d, v) in out.iter().enumerate() {
                assert_eq!(v["kappa"][0].as_array().unwrap().len(), d + 1);
                assert_eq!(v["omega2"][0].as_array().unwrap().len(), d + 1);
            }
        }
    }
}
