//! `sphstab throughput --dim 3` (periodic cubic box) and `--domain`: JSON fields, neighbour
//! counts against the lattice (exact: every particle of a periodic box sees the same shells),
//! measured memory and allocations, the scaling fit, bad input.

use crate::common;

use common::{assert_bad_inputs, json};

/// Lattice points of the simple-cubic (D = 3) or square (D = 2) unit lattice strictly within
/// radius r of the origin, the origin included.
fn lattice_count(dim: u32, r: f64) -> usize {
    let m = r.ceil() as i64;
    let side = (2 * m + 1) as usize;
    (0..side.pow(dim))
        .filter(|&k| {
            let mut rest = k;
            let mut r2 = 0.0;
            for _ in 0..dim {
                let c = (rest % side) as i64 - m;
                rest /= side;
                r2 += (c * c) as f64;
            }
            r2 < r * r
        })
        .count()
}

#[test]
fn throughput_3d_periodic_box() {
    let v = json(&[
        "throughput",
        "--dim",
        "3",
        "--size",
        "8",
        "--steps",
        "3",
        "--repeats",
        "2",
        "--threads",
        "2",
        "--json",
    ]);
    assert_eq!(v["dim"], 3);
    assert_eq!(v["domain"], "periodic");
    assert_eq!(v["form"], "classical");
    assert_eq!(v["kernel"], "m4");
    assert_eq!(v["h_over_dx"], 1.3);
    assert_eq!(v["material"], "elastic-jaumann");
    assert_eq!(v["av"], serde_json::json!([1.0, 1.0]));
    // artificial stress is 2D only: off by default in 3D
    assert!(v["art_eps"].is_null());
    let b = &v["blocks"][0];
    assert_eq!(b["particles"], 512);
    // h = 1.3Δx, support 2.6Δx: the shells |m|² ≤ 6 of the cubic lattice, 81 points
    let nb = b["neighbours_per_particle"].as_f64().unwrap();
    assert_eq!(lattice_count(3, 2.6), 81);
    assert_eq!(nb, 81.0);
    // measured: at least the compact stencils (a 4-byte entry per neighbour and, once per
    // pair, 4 + 8 bytes: 10 bytes per neighbour) and the state
    let bytes = b["bytes_per_particle"].as_f64().unwrap();
    assert!(bytes > 10.0 * nb && bytes < 40_000.0, "{bytes}");
    assert_eq!(b["allocations_per_step"], 0.0);
    let vmax = b["max_speed_end"].as_f64().unwrap();
    assert!(vmax > 1e-4 && vmax < 1e-2, "{vmax}");
}

/// The periodic domain in 2D and the total-Lagrangian neighbour count (a cell-list count at
/// the current positions, nearest images): the same lattice shells.
#[test]
fn throughput_periodic_2d_and_total_lagrangian_3d() {
    let v = json(&[
        "throughput",
        "--domain",
        "periodic",
        "--size",
        "12",
        "--steps",
        "2",
        "--repeats",
        "1",
        "--json",
    ]);
    assert_eq!(v["dim"], 2);
    assert_eq!(v["domain"], "periodic");
    assert_eq!(v["blocks"][0]["neighbours_per_particle"], 21.0);
    assert_eq!(lattice_count(2, 2.6), 21);
    let v = json(&[
        "throughput",
        "--dim",
        "3",
        "--form",
        "total-lagrangian",
        "--size",
        "7",
        "--steps",
        "2",
        "--repeats",
        "1",
        "--json",
    ]);
    assert_eq!(v["blocks"][0]["particles"], 343);
    assert_eq!(v["blocks"][0]["neighbours_per_particle"], 81.0);
}

#[test]
fn throughput_3d_fits_the_scaling_exponent() {
    let v = json(&[
        "throughput",
        "--dim",
        "3",
        "--sizes",
        "8,12",
        "--material",
        "hydro",
        "--av",
        "off",
        "--steps",
        "2",
        "--repeats",
        "1",
        "--json",
    ]);
    let blocks = v["blocks"].as_array().unwrap();
    assert_eq!(blocks[1]["particles"], 1728);
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
fn throughput_3d_bad_input() {
    assert_bad_inputs(&[
        (&["throughput", "--dim", "4"], "--dim"),
        (&["throughput", "--dim", "3", "--size", "201"], "--size"),
        // a periodic box must be wider than two supports (2 × 2.6Δx)
        (&["throughput", "--dim", "3", "--size", "5"], "--size"),
        (&["throughput", "--dim", "3", "--sizes", "8,5"], "--sizes"),
        (
            &["throughput", "--dim", "3", "--art-eps", "0.3"],
            "--art-eps",
        ),
        (&["throughput", "--domain", "moon"], "--domain"),
    ]);
}
