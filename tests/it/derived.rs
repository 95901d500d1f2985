//! The dimension-generic closed forms of `vonneumann::derived` at D = 1 (lattice sums of the
//! unit chain, `rho_d::<1>` with the 1D Truesdell law, and `lnl`/`cll` on `Sums<1>`) reproduce
//! the 1D scalar formulas they replaced, with expected values computed independently of
//! `derived.rs`:
//! - classical, nonlocal and total-Lagrangian from the papers' closed forms in
//!   `vonneumann::closed_form` (\[B00\] eqs 74 and 82 with the `sph` lattice shape, whose lattice
//!   sums are `closed_form::lattice_sums`): classical = 2·eq74 − eq82 (ERRATA E1), nonlocal
//!   = C̃S1² = eq 82's expression (ERRATA E2), total-Lagrangian = eq 82;
//! - local, lnl and cll from the previous 1D formulas of `derived.rs` written out here on lattice
//!   sums summed by hand over the chain from the dual-number lattice shape
//!   (`shape::lattice_shape`, not the kernel derivatives `derived::sums` uses):
//!   local = C̃(S1/M1)², lnl = (1 − c)C̃S1² + cC̃(S1/M1)²,
//!   cll = (1 − c)[C̃S1² − 2σ̄S2 + 2σ̄((1 − c)S1² + cS1²/M1)] + cC̃(S1/M1)² (ERRATA E1–E3 and
//!   the derivations behind them).
//!
//! The lattice sums S1, S2, M1 of `derived::sums::<1>` equal the hand sums exactly (both add
//! the same products in the same order); the closed forms differ by the arithmetic of the
//! expressions only. Tolerance: |generic − expected| ≤ 1e-12 · max(|expected|, 1e-4), i.e.
//! 1e-12 relative where |ω²| ≥ 1e-4 (normalised units, C/(ρΔx²)) and an absolute floor of
//! 1e-16 below: near κ → 0 (ω² ≈ C̃κ², below 1e-4 for κ ≲ 1e-2; pure relative differences
//! there are also reported) and where ω² passes near zero at finite κ by cancellation of O(0.1)
//! terms (wide kernels near κ = π, zero crossings in tension/compression), where the absolute
//! round-off of those terms, ~5e-17, is all that differs.

use crate::common;

use common::*;
use sphstab::forms::FormKind;
use sphstab::lattice::Lattice;
use sphstab::shape::{KernelParams, ShapeFamily};
use sphstab::vonneumann::closed_form as cf;
use sphstab::vonneumann::derived::{omega2_1d, sums};

const TOL: f64 = 1e-12;
const FLOOR: f64 = 1e-4;

/// (S1, S2, M1) summed by hand over |j| ≤ ceil(support) + 1 (the old `LatticeSums::new`).
fn hand_sums(phi: &dyn Fn(f64) -> [f64; 3], support: f64, kap: f64) -> (f64, f64, f64) {
    let n = support.ceil() as i64 + 1;
    let (mut s1, mut s2, mut m1) = (0.0, 0.0, 0.0);
    for j in -n..=n {
        let x = j as f64;
        let [_, p1, p2] = phi(x);
        let hs = (0.5 * kap * x).sin();
        s1 += p1 * (kap * x).sin();
        s2 += p2 * 2.0 * hs * hs;
        m1 -= x * p1;
    }
    (s1, s2, m1)
}

#[test]
fn generic_d1_reproduces_the_1d_scalar_formulas() {
    let chain = Lattice::<1>::chain();
    let mut kaps: Vec<f64> = vec![1e-6, 1e-3, 1e-2];
    kaps.extend(grid(64));
    let forms = [
        FormKind::Classical,
        FormKind::Nonlocal,
        FormKind::Local,
        FormKind::Lnl,
        FormKind::Cll,
        FormKind::TotalLagrangian,
    ];
    let mut worst = [0.0f64; 6];
    let mut worst_sums = [0.0f64; 3];
    let mut n = 0usize;
    let (mut worst_small_kappa, mut worst_abs) = (0.0f64, 0.0f64);
    for kern in ["m4", "m5", "m6", "wendland-c2", "wendland-c4", "gaussian"] {
        for h in [1.0, 1.3, 2.0] {
            let kp = KernelParams { kernel: k(kern), h };
            let support = kp.support();
            let phi = shape_fn(ShapeFamily::Sph, kern, h);
            for &kap in &kaps {
                let s = sums(&chain, ShapeFamily::Sph, kp, [kap]).unwrap();
                let (s1, s2, m1) = hand_sums(&phi, support, kap);
                for (w, (got, want)) in
                    worst_sums
                        .iter_mut()
                        .zip([(s.s1[0], s1), (s.s2[0][0], s2), (s.m1[0][0], m1)])
                {
                    *w = w.max((got - want).abs() / want.abs().max(FLOOR));
                }
                for sig in [-0.5, -0.01, 0.0, 0.01, 0.2, 0.9] {
                    let ct = 1.0 + sig;
                    let eq74 = cf::b00_eq74_eulerian_nodal(&phi, support, sig, kap);
                    let eq82 = cf::b00_eq82_lagrangian_nodal(&phi, support, sig, kap);
                    let local = ct * (s1 / m1).powi(2);
                    for c in [0.0, 0.3, 0.5, 1.0] {
                        for (i, form) in forms.iter().enumerate() {
                            let want = match form {
                                FormKind::Classical => 2.0 * eq74 - eq82,
                                FormKind::Nonlocal | FormKind::TotalLagrangian => eq82,
                                FormKind::Local => local,
                                FormKind::Lnl => (1.0 - c) * ct * s1 * s1 + c * local,
                                _ => {
                                    let dens = (1.0 - c) * s1 * s1 + c * s1 * s1 / m1;
                                    (1.0 - c) * (ct * s1 * s1 - 2.0 * sig * s2 + 2.0 * sig * dens)
                                        + c * local
                                }
                            };
                            let got = omega2_1d(*form, &s, sig, c).unwrap();
                            let rel = (got - want).abs() / want.abs().max(FLOOR);
                            assert!(
                                rel <= TOL,
                                "{form:?} {kern} h={h} σ̄={sig} c={c} κ={kap}: {got:e} vs {want:e} ({rel:e})"
                            );
                            worst[i] = worst[i].max(rel);
                            worst_abs = worst_abs.max((got - want).abs());
                            if kap <= 1e-2 {
                                worst_small_kappa =
                                    worst_small_kappa.max((got - want).abs() / want.abs());
                            }
                            n += 1;
                        }
                    }
                }
            }
        }
    }
    eprintln!("{n} comparisons; worst relative difference (floor {FLOOR:e}):");
    for (form, w) in forms.iter().zip(worst) {
        eprintln!("  {:<18} {w:.3e}", form.name());
    }
    eprintln!(
        "  worst |difference| {worst_abs:.3e}; worst pure relative at κ ≤ 1e-2: {worst_small_kappa:.3e}"
    );
    for (name, w) in ["S1", "S2", "M1"].iter().zip(worst_sums) {
        eprintln!("  sums {name:<13} {w:.3e}");
    }
}

/// The forms without a derived closed form have none at D = 1 either.
#[test]
fn forms_without_a_closed_form_return_none() {
    let s = chain_sums("m4", 1.2, 1.0);
    for form in [
        FormKind::EulerianNodal,
        FormKind::EulerianStressPoints,
        FormKind::LagrangianStressPoints,
        FormKind::LeastSquares,
    ] {
        assert!(omega2_1d(form, &s, 0.1, 0.5).is_none(), "{form:?}");
    }
}
