//! Not a correctness test: prints how long a 1,024-point dispersion curve takes by the closed
//! form and by the numeric engine, measured in the same run (ratio is what matters). Run with
//! `cargo test --release --test timing_probe -- --nocapture --ignored` (run on demand).

mod common;

use common::*;
use sphstab::forms::FormKind;
use sphstab::shape::ShapeFamily;
use sphstab::vonneumann::closed_form as cf;
use std::time::Instant;

#[test]
#[ignore = "timing probe, run on demand"]
fn dispersion_curve_cost_closed_form_vs_engine() {
    let ks = grid(1024);
    let reps = 20;
    let phi = shape_fn(ShapeFamily::Sph, "m4", 1.2);
    let t0 = Instant::now();
    let mut acc = 0.0;
    for _ in 0..reps {
        acc += ks
            .iter()
            .map(|&q| cf::b00_eq74_eulerian_nodal(&phi, 2.4, 0.01, q))
            .sum::<f64>();
    }
    let closed = t0.elapsed().as_secs_f64() / reps as f64;
    let t1 = Instant::now();
    for _ in 0..reps {
        let l = lin(FormKind::EulerianNodal, "m4", ShapeFamily::Sph, 1.2, 0.01);
        acc += ks.iter().map(|&q| l.omega2(q).0).sum::<f64>();
    }
    let engine = t1.elapsed().as_secs_f64() / reps as f64;
    let t2 = Instant::now();
    let l = lin(FormKind::EulerianNodal, "m4", ShapeFamily::Sph, 1.2, 0.01);
    let lin_only = t2.elapsed().as_secs_f64();
    eprintln!(
        "1024-point curve, eulerian-nodal/m4/h=1.2: closed form (eq 74, with lattice-shape evaluation) {:.3} ms, \
         numeric engine (linearise + 1024 Fourier sums) {:.3} ms, ratio engine/closed = {:.2}; linearisation alone {:.3} ms [{}]",
        closed * 1e3,
        engine * 1e3,
        engine / closed,
        lin_only * 1e3,
        acc.is_finite() && l.size() == 4
    );
}
