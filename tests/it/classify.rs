//! Every instability kind is produced where an independent criterion says it must be.

use crate::common;

use common::*;
use sphstab::analysis::{Query, query};
use sphstab::forms::FormKind;
use sphstab::shape::ShapeFamily;
use sphstab::vonneumann::classify::Kind;
use sphstab::vonneumann::closed_form as cf;
use std::f64::consts::PI;

fn q(form: FormKind, kern: &str, h: f64, sig: f64) -> Query<1> {
    Query::<1>::new(form, k(kern), h, sig)
}

fn kinds(r: &sphstab::analysis::QueryReport) -> Vec<Kind> {
    r.instabilities.iter().map(|i| i.kind).collect()
}

#[test]
fn tensile_classical_m4() {
    let r = query(&q(FormKind::Classical, "m4", 1.2, 0.01)).unwrap();
    assert_eq!(kinds(&r), vec![Kind::Tensile]);
    // growth rate at κ = π from the derived closed form: γ = sqrt(−ω²(π))
    let w2 = derived_omega2(FormKind::Classical, "m4", 1.2, 0.01, PI);
    assert!((r.max_growth_rate - (-w2).sqrt()).abs() < 1e-9);
}

/// Classical SPH in compression with a wide quartic/Gaussian support: the derived closed form
/// has ω² < 0 for σ̄ < 0 and ω² ≥ 0 at σ̄ = 0 → `compressive`.
#[test]
fn compressive_classical_wide_support() {
    for (kern, h) in [("m5", 2.6), ("gaussian", 3.0)] {
        let r = query(&q(FormKind::Classical, kern, h, -0.1)).unwrap();
        assert!(!r.stable);
        assert!(
            kinds(&r).contains(&Kind::Compressive),
            "{kern}: {:?}",
            r.instabilities
        );
        let kap = r.kappa_at_max.unwrap()[0];
        assert!(derived_omega2(FormKind::Classical, kern, h, -0.1, kap) < 0.0);
        assert!(derived_omega2(FormKind::Classical, kern, h, 0.0, kap) >= 0.0);
    }
}

/// σ̄ ≤ −1: C̄ = C + σ ≤ 0, the continuum itself is unstable ([B00] eq 33) → `material`,
/// for a form without any stress–kernel term (total Lagrangian, eq 82 → ω² = C̄ S1² < 0).
#[test]
fn material_instability_below_minus_one() {
    let r = query(&q(FormKind::TotalLagrangian, "efg-quartic", 1.5, -1.5)).unwrap();
    assert!(!r.stable);
    assert!(
        kinds(&r)
            .iter()
            .all(|&k| k == Kind::Material || k == Kind::RankDeficiency)
    );
    assert!(kinds(&r).contains(&Kind::Material));
    // eq 82 with the MLS central-difference shape: ω² = −0.5 sin²κ, max growth sqrt(0.5) at π/2
    assert!((r.max_growth_rate - 0.5f64.sqrt()).abs() < 1e-6);
    assert!(cf::b00_eq32_continuum(-1.5, 1.0) < 0.0);
}

/// Leapfrog beyond Δt_crit = 2/ω_max = 2 ([B00] Table II, λ_max = 1) → `time-step` only.
#[test]
fn time_step_instability_above_critical() {
    let mut qq = q(FormKind::TotalLagrangian, "efg-quartic", 1.5, 0.0);
    qq.dt = Some(2.2);
    let r = query(&qq).unwrap();
    assert!(!r.stable);
    let ts: Vec<_> = r
        .instabilities
        .iter()
        .filter(|i| i.kind == Kind::TimeStep)
        .collect();
    assert_eq!(ts.len(), 1);
    // ω² = sin²κ; unstable where ωΔt > 2: sin κ > 1/1.1 → κ ∈ (asin(1/1.1), π − asin(1/1.1))
    let lo = (1.0f64 / 1.1).asin();
    assert!(
        (ts[0].kappa_min.unwrap() - lo).abs() < 2.0 * PI / 512.0,
        "{:?} vs {lo}",
        ts[0].kappa_min
    );
    assert!((ts[0].kappa_max.unwrap() - (PI - lo)).abs() < 2.0 * PI / 512.0);
    qq.dt = Some(1.9);
    let r = query(&qq).unwrap();
    assert!(r.stable && r.max_amplification.unwrap() <= 1.0 + 1e-9);
}

/// [B00 §4.3] states that least squares fails at D_mx ≥ 2.5 when α_s is too large: "the
/// stabilization term in the mass … will change to positive for large wave numbers, causing the
/// denominator [of eq 108] to be zero or negative". With the exact φ'' on the nodes it does not
/// (ERRATA E9). Independent route: the exact rational lattice values (`common::exact`) give
/// P(κ) = Σφ(j) cos κj > 0 and Q(κ) = Σφ''(j) cos κj ≤ 0 on (0, π] at D_mx = 1.5 and 2.5, so
/// the denominator P(P − α_s Q) is positive for every α_s ≥ 0; the engine agrees (stable, no
/// instability, for α_s up to 2). The paper's statement is what one gets with W''(0) dropped
/// from a node's own weight — the defect of issue 9: then Q(π) > 0 and α_s = 0.5 makes the
/// denominator negative at κ = π. At D_mx = 1.5 any α_s > 0 removes the spurious mode at π.
#[test]
fn least_squares_b00_section_4_3() {
    use common::exact::{Q, mls_quartic_lattice};
    let sums = |r: Q, defect: bool, kap: f64| -> (f64, f64) {
        mls_quartic_lattice(r, defect)
            .into_iter()
            .fold((0.0, 0.0), |(p, q), (j, v)| {
                let c = (kap * j as f64).cos();
                (p + v[0].to_f64() * c, q + v[2].to_f64() * c)
            })
    };
    for (d_mx, r) in [(1.5, Q::new(3, 2)), (2.5, Q::new(5, 2))] {
        for i in 1..=512 {
            let kap = PI * i as f64 / 512.0;
            let (p, qv) = sums(r, false, kap);
            assert!(p > 0.0 && qv <= 1e-14, "D_mx={d_mx} κ={kap}: P={p} Q={qv}");
        }
        for alpha_s in [0.001, 0.01, 0.1, 0.5, 1.0, 2.0] {
            let mut qq = q(FormKind::LeastSquares, "efg-quartic", d_mx, 0.0);
            qq.alpha_s = alpha_s;
            let r = query(&qq).unwrap();
            assert!(
                r.stable && r.instabilities.is_empty(),
                "D_mx={d_mx} α_s={alpha_s}"
            );
            assert!(!r.has_zero_energy_modes);
        }
    }
    // the defect reproduces the paper's statement
    let (p, qv) = sums(Q::new(5, 2), true, PI);
    assert!(qv > 0.0 && p * (p - 0.5 * qv) < 0.0, "P={p} Q={qv}");
    // α_s = 0 is plain nodal integration: the zero-energy mode at π
    let r = query(&q(FormKind::LeastSquares, "efg-quartic", 1.5, 0.0)).unwrap();
    assert!(r.stable && r.has_zero_energy_modes);
}

/// Linearised artificial viscosity (α = 1, acting on all pairs as in [V21 App. B]) damps every
/// stable mode (all Re s ≤ 0, some < 0) and bisection on the amplification matrices gives a
/// critical step; the eigenvalue route is used (dissipative system).
#[test]
fn artificial_viscosity_damps_and_has_a_critical_step() {
    let mut qq = q(FormKind::Nonlocal, "m4", 1.3, 0.05);
    qq.av = Some((1.0, 2.0));
    let lin = qq.chain().unwrap();
    assert!(lin.is_dissipative());
    let ev = lin.eigenvalues(2.0).unwrap();
    assert!(ev.iter().all(|s| s.re <= 1e-12));
    assert!(ev.iter().any(|s| s.re < -1e-3));
    let r = query(&qq).unwrap();
    assert!(r.stable);
    let dt = r.critical_dt.unwrap();
    // viscosity lowers the leapfrog limit below the inviscid 2/ω_max ([B00] eq 120, ξ > 0)
    let inviscid = query(&q(FormKind::Nonlocal, "m4", 1.3, 0.05))
        .unwrap()
        .critical_dt
        .unwrap();
    assert!(dt < inviscid && dt > 0.3 * inviscid, "{dt} vs {inviscid}");
}

#[test]
fn no_neighbours_is_an_input_error() {
    let e = query(&q(FormKind::Classical, "lucy", 1.0, 0.01)).unwrap_err();
    assert!(matches!(
        e,
        sphstab::error::Error::OutOfRange {
            field: "h_over_dx",
            ..
        }
    ));
}

/// A support that barely covers the nearest neighbours makes the MLS moment matrix nearly
/// singular: an error naming the cause, never NaN.
#[test]
fn near_singular_mls_is_an_error_not_nan() {
    let mut qq = q(FormKind::TotalLagrangian, "efg-quartic", 1.0 + 1e-9, 0.0);
    qq.shape = ShapeFamily::Mls;
    match query(&qq) {
        Err(sphstab::error::Error::SingularMoment { .. }) => {}
        Ok(r) => assert!(r.max_growth_rate.is_finite()),
        Err(e) => panic!("unexpected error {e}"),
    }
}
