//! `sphstab throughput`: JSON fields, measured memory and allocations, the scaling fit, bad
//! input.

use crate::common;

use common::{assert_bad_inputs, json};

#[test]
fn throughput_reports_speed_neighbours_and_measured_memory() {
    let v = json(&[
        "throughput",
        "--size",
        "24",
        "--steps",
        "4",
        "--repeats",
        "3",
        "--threads",
        "2",
        "--json",
    ]);
    assert_eq!(v["form"], "classical");
    assert_eq!(v["kernel"], "m4");
    assert_eq!(v["material"], "elastic-jaumann");
    assert_eq!(v["av"], serde_json::json!([1.0, 1.0]));
    assert_eq!(v["art_eps"], 0.3);
    assert_eq!(v["threads"], 2);
    assert!(v["scaling_exponent"].is_null());
    let b = &v["blocks"][0];
    assert_eq!(b["particles"], 576);
    assert_eq!(b["seconds_per_step_repeats"].as_array().unwrap().len(), 3);
    let ns = b["ns_per_particle_step"].as_f64().unwrap();
    let rate = b["particle_steps_per_second"].as_f64().unwrap();
    assert!(
        ns > 0.0 && (ns * 1e-9 * rate - 1.0).abs() < 1e-9,
        "{ns} {rate}"
    );
    // h = 1.3Δx, support 2.6Δx: 21 lattice points inside (itself included), fewer at the edges
    let nb = b["neighbours_per_particle"].as_f64().unwrap();
    assert!(nb > 17.0 && nb < 21.0, "{nb}");
    // measured: at least the compact stencils (a 4-byte entry per neighbour and, once per
    // pair, 4 + 8 + 8 bytes: 14 bytes per neighbour) and the state
    let bytes = b["bytes_per_particle"].as_f64().unwrap();
    assert!(bytes > 14.0 * nb && bytes < 20_000.0, "{bytes}");
    assert_eq!(b["allocations_per_step"], 0.0);
    let vmax = b["max_speed_end"].as_f64().unwrap();
    assert!(vmax > 1e-4 && vmax < 1e-2, "{vmax}");
}

#[test]
fn throughput_fits_the_scaling_exponent_over_sizes() {
    let v = json(&[
        "throughput",
        "--sizes",
        "16,32",
        "--material",
        "hydro",
        "--av",
        "off",
        "--steps",
        "3",
        "--repeats",
        "1",
        "--json",
    ]);
    assert_eq!(v["material"], "hydro");
    assert!(v["av"].is_null());
    let blocks = v["blocks"].as_array().unwrap();
    assert_eq!(blocks.len(), 2);
    assert_eq!(blocks[1]["particles"], 1024);
    let p = v["scaling_exponent"].as_f64().unwrap();
    // the fit of the reported timings (ln t against ln N; through two points, their slope) —
    // not a claim about the timings themselves, which the machine's load decides
    let (n, t): (Vec<f64>, Vec<f64>) = blocks
        .iter()
        .map(|b| {
            (
                b["particles"].as_f64().unwrap().ln(),
                b["seconds_per_step"].as_f64().unwrap().ln(),
            )
        })
        .unzip();
    let slope = (t[1] - t[0]) / (n[1] - n[0]);
    assert!(
        p.is_finite() && (p - slope).abs() <= 1e-9 * slope.abs().max(1.0),
        "{p} vs {slope}"
    );
}

#[test]
fn throughput_bad_input() {
    assert_bad_inputs(&[
        (&["throughput", "--size", "2"], "--size"),
        (&["throughput", "--sizes", "10,1"], "--sizes"),
        (&["throughput", "--h", "-1"], "--h"),
        (&["throughput", "--h", "nan"], "--h"),
        (&["throughput", "--poisson", "0.5"], "--poisson"),
        (&["throughput", "--av", "1"], "--av"),
        (&["throughput", "--av", "-1,1"], "--av"),
        (
            &["throughput", "--form", "nonlocal", "--art-eps", "0.3"],
            "--art-eps",
        ),
        (&["throughput", "--art-n", "0"], "--art-n"),
        (&["throughput", "--material", "rubber"], "--material"),
        (&["throughput", "--rate", "oldroyd"], "--rate"),
        (&["throughput", "--dt", "0"], "--dt"),
        (&["throughput", "--steps", "0"], "--steps"),
        (&["throughput", "--repeats", "0"], "--repeats"),
        (&["throughput", "--threads", "0"], "--threads"),
        (&["throughput", "--form", "least-squares"], "--form"),
    ]);
}
