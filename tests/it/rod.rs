//! [B00 §4.1.2] rod: Eulerian kernel unstable, Lagrangian kernel stable — and the verdict for
//! B00's own EFG setting (mls, quartic weight, D_mx = 1.5) from the engine, confirmed in time.

use crate::common;

use common::*;
use sphstab::analysis::{Query, query};
use sphstab::forms::FormKind;
use sphstab::shape::ShapeFamily;
use sphstab::solver::rod::{RodConfig, run_rod};

fn rod(form: FormKind, kern: &str, shape: ShapeFamily, h: f64) -> sphstab::solver::rod::RodReport {
    let mut cfg = RodConfig::new(form, k(kern), h, 41);
    cfg.shape = shape;
    let r = run_rod(&cfg).unwrap();
    eprintln!(
        "rod {} / {} / {kern} h={h}: max |v| {:.4e} m/s (v0 = 40), unstable {} at t = {:.2e} s",
        r.form, r.shape, r.max_velocity, r.unstable, r.t
    );
    r
}

#[test]
fn b00_rod_eulerian_unstable_lagrangian_stable() {
    // Eulerian kernels: classical SPH and the Galerkin nodal form with sph shapes (eq 74 exactly)
    assert!(rod(FormKind::Classical, "m4", ShapeFamily::Sph, 1.2).unstable);
    assert!(
        rod(
            FormKind::EulerianNodal,
            "efg-quartic",
            ShapeFamily::Sph,
            1.5
        )
        .unstable
    );
    // Lagrangian kernel: stable (σ̄ = σ0/E = 0.1)
    assert!(
        !rod(
            FormKind::TotalLagrangian,
            "efg-quartic",
            ShapeFamily::Mls,
            1.5
        )
        .unstable
    );
    assert!(!rod(FormKind::TotalLagrangian, "m4", ShapeFamily::Sph, 1.2).unstable);
}

/// B00's own setting, Eulerian EFG nodal integration with MLS shapes at D_mx = 1.5: the full
/// linearisation says stable at σ̄ = 0.1 (ERRATA E3), and so does the run.
#[test]
fn b00_rod_efg_mls_follows_the_engine() {
    let mut q = Query::<1>::new(FormKind::EulerianNodal, k("efg-quartic"), 1.5, 0.1);
    q.shape = ShapeFamily::Mls;
    let verdict = query(&q).unwrap().stable;
    let r = rod(
        FormKind::EulerianNodal,
        "efg-quartic",
        ShapeFamily::Mls,
        1.5,
    );
    assert_eq!(!r.unstable, verdict);
}
