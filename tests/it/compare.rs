//! Side-by-side comparisons (`--vary`, lists in `--form`/`--kernel`) in `query`, `timestep` and
//! `dispersion`: every series is the answer the same command gives to that one question
//! (compared as JSON, to the last bit), the abscissa range of `dispersion`, and the refusals.

use crate::common::{assert_bad_inputs, json, sphstab};

/// (report key, comparison arguments, the single questions it stands for).
type Case<'a> = (&'a str, &'a [&'a str], Vec<Vec<&'a str>>);

/// Each series of a comparison equals the single question it stands for.
#[test]
fn every_series_is_the_single_answer() {
    let cases: [Case; 3] = [
        (
            "query",
            &[
                "query",
                "--stress",
                "-0.1",
                "--points",
                "64",
                "--vary",
                "delta=off,0.1",
            ],
            vec![
                vec!["query", "--stress", "-0.1", "--points", "64"],
                vec![
                    "query", "--stress", "-0.1", "--points", "64", "--delta", "0.1",
                ],
            ],
        ),
        (
            "timestep",
            &[
                "timestep",
                "--stress",
                "0",
                "--av-alpha",
                "1",
                "--points",
                "64",
                "--vary",
                "integrator=kdk,rk4",
                "--vary",
                "h=1.2,1.5",
            ],
            vec![
                vec![
                    "timestep",
                    "--stress",
                    "0",
                    "--av-alpha",
                    "1",
                    "--points",
                    "64",
                    "--integrator",
                    "kdk",
                    "--h",
                    "1.2",
                ],
                vec![
                    "timestep",
                    "--stress",
                    "0",
                    "--av-alpha",
                    "1",
                    "--points",
                    "64",
                    "--integrator",
                    "kdk",
                    "--h",
                    "1.5",
                ],
                vec![
                    "timestep",
                    "--stress",
                    "0",
                    "--av-alpha",
                    "1",
                    "--points",
                    "64",
                    "--integrator",
                    "rk4",
                    "--h",
                    "1.2",
                ],
                vec![
                    "timestep",
                    "--stress",
                    "0",
                    "--av-alpha",
                    "1",
                    "--points",
                    "64",
                    "--integrator",
                    "rk4",
                    "--h",
                    "1.5",
                ],
            ],
        ),
        (
            "dispersion",
            &[
                "dispersion",
                "--form",
                "classical,nonlocal",
                "--points",
                "32",
            ],
            vec![
                vec!["dispersion", "--form", "classical", "--points", "32"],
                vec!["dispersion", "--form", "nonlocal", "--points", "32"],
            ],
        ),
    ];
    for (key, args, singles) in cases {
        let mut a = args.to_vec();
        a.push("--json");
        let v = json(&a);
        let series = v["series"].as_array().unwrap();
        assert_eq!(series.len(), singles.len(), "{args:?}");
        for (s, single) in series.iter().zip(singles) {
            let mut b = single.clone();
            b.push("--json");
            // the units are the comparison's, once, not each series'
            let mut one = json(&b);
            let units = one.as_object_mut().unwrap().remove("units").unwrap();
            for (k, u) in units.as_object().unwrap() {
                assert_eq!(&v["units"][k], u, "{args:?}: units of {k}");
            }
            assert_eq!(s[key], one, "{args:?}: {}", s["label"]);
        }
    }
    // the labels name the values, first axis slowest
    let v = json(&[
        "timestep",
        "--stress",
        "0",
        "--points",
        "32",
        "--vary",
        "integrator=kdk,rk4",
        "--vary",
        "h=1.2,1.5",
        "--json",
    ]);
    let labels: Vec<&str> = v["series"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["label"].as_str().unwrap())
        .collect();
    assert_eq!(
        labels,
        [
            "integrator = kdk, h = 1.2",
            "integrator = kdk, h = 1.5",
            "integrator = rk4, h = 1.2",
            "integrator = rk4, h = 1.5"
        ]
    );
}

/// `--kappa-range` keeps exactly the table rows inside it; the text comparison has a row per
/// series.
#[test]
fn kappa_range_and_text_tables() {
    let (code, out, err) = sphstab(&["dispersion", "--points", "20", "--kappa-range", "0.5,0.8"]);
    assert_eq!(code, 0, "{err}");
    let ks: Vec<f64> = out
        .lines()
        .skip(2)
        .map(|l| l.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    // κΔx/π = k/20: 0.50, 0.55, …, 0.80
    assert_eq!(ks.len(), 7, "{out}");
    assert!(ks.iter().all(|k| (0.5..=0.8).contains(k)), "{ks:?}");
    let (code, out, err) = sphstab(&["query", "--points", "32", "--kernel", "m4,wendland-c2"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("kernel = m4 ") && out.contains("kernel = wendland-c2 "),
        "{out}"
    );
}

#[test]
fn comparison_refusals() {
    assert_bad_inputs(&[
        (&["query", "--vary", "h"], "--vary"),
        (&["query", "--vary", "colour=1,2"], "--vary parameter"),
        (&["query", "--vary", "h=1.2,abc"], "--vary"),
        (&["query", "--vary", "h=1.2,"], "--vary"),
        (&["query", "--vary", "h=1.2", "--vary", "h=1.5"], "--vary"),
        (
            &["query", "--vary", "h=1,2,3,4,5", "--vary", "c=0,0.5,1"],
            "--vary",
        ),
        (&["query", "--vary", "h=1.2,99"], "h"),
        (
            &["dispersion", "--vary", "integrator=kdk,rk4"],
            "--vary integrator",
        ),
        (&["dispersion", "--y-range", "0,1"], "--y-range"),
        (&["dispersion", "--kappa-range", "0.5,2"], "kappa-range"),
        (&["dispersion", "--kappa-range", "1,0.5"], "--kappa-range"),
        (&["timestep", "--verify", "--vary", "h=1.2,1.5"], "--verify"),
        (
            &["query", "--dim", "2", "--box", "5", "--vary", "h=1.2,1.5"],
            "--box",
        ),
    ]);
}
