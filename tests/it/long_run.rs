//! 10⁶-step run of a stable scene with bounded energy drift (issue 5, item 4).

use crate::common;

use common::*;
use sphstab::forms::{FormKind, Model1D};
use sphstab::shape::ShapeFamily;
use sphstab::solver::Run1D;
use std::f64::consts::PI;

/// A periodic total-Lagrangian chain (mls, efg-quartic, D_mx = 1.5; 32 particles) with one
/// velocity mode seeded, 10⁶ leapfrog steps at half the critical step. The mode is linear, so the
/// peak kinetic energy over a period is its total energy; the leapfrog has |λ| = 1 exactly, so any
/// drift is rounding. Bound asserted: peak kinetic energy of the last 1% of the run within 1e−6
/// (relative) of the first 1%.
#[test]
fn million_steps_bounded_energy() {
    let n = 32;
    let p = params(
        FormKind::TotalLagrangian,
        "efg-quartic",
        ShapeFamily::Mls,
        1.5,
        0.0,
    );
    let model = Model1D::new(
        p,
        (0..n).map(|i| i as f64).collect(),
        vec![1.0; n],
        Some(n as f64),
    )
    .unwrap();
    let mut z = model.rest_state();
    let kap = 2.0 * PI * 5.0 / n as f64;
    for (i, v) in z.v.iter_mut().enumerate() {
        *v = 1e-6 * (kap * i as f64).cos();
    }
    let mut run = Run1D::new(model, z, vec![None; n]).unwrap();
    let dt = 1.0; // Δt_crit = 2 (ω_max = 1, [B00] Table II)
    let steps = 1_000_000;
    let window = steps / 100;
    let (mut first, mut last) = (0.0f64, 0.0f64);
    let t = std::time::Instant::now();
    for s in 0..steps {
        run.step(dt).unwrap();
        let ke: f64 = run.z.v.iter().map(|v| 0.5 * v * v).sum();
        if s < window {
            first = first.max(ke);
        } else if s >= steps - window {
            last = last.max(ke);
        }
    }
    let drift = (last / first - 1.0).abs();
    eprintln!(
        "10⁶ steps in {:.1} s: peak kinetic energy first 1% {first:.6e}, last 1% {last:.6e}, relative drift {drift:.2e}",
        t.elapsed().as_secs_f64()
    );
    assert!(drift < 1e-6);
}
