//! The papers' closed forms ([B00], [V21]) against the numeric engine, where their assumptions
//! match a form's rate function (1e-8 relative to max|ω²|), and the papers' statements.
//! Measured values are printed (run with `--nocapture`) for the closing notes and ERRATA.

use crate::common;

use common::*;
use sphstab::forms::FormKind;
use sphstab::shape::ShapeFamily;
use sphstab::vonneumann::closed_form as cf;
use std::f64::consts::PI;

const MLS: ShapeFamily = ShapeFamily::Mls;
const SPH: ShapeFamily = ShapeFamily::Sph;

/// max |a − b| / max |b| over κΔx ∈ (0, π].
fn rel_diff(num: impl Fn(f64) -> f64, closed: impl Fn(f64) -> f64) -> f64 {
    let ks = grid(400);
    let scale = ks
        .iter()
        .map(|&k| closed(k).abs())
        .fold(0.0, f64::max)
        .max(1e-300);
    ks.iter()
        .map(|&k| (num(k) - closed(k)).abs())
        .fold(0.0, f64::max)
        / scale
}

#[test]
fn b00_eq82_matches_total_lagrangian_for_every_shape() {
    for shape in [SPH, MLS, ShapeFamily::Shepard, ShapeFamily::Corrected] {
        for (kern, h) in [
            ("efg-quartic", 1.5),
            ("m4", 1.3),
            ("wendland-c4", 1.7),
            ("mollifier", 3.0),
        ] {
            for sig in [-0.9, 0.0, 0.7] {
                let l = lin(FormKind::TotalLagrangian, kern, shape, h, sig);
                let phi = shape_fn(shape, kern, h);
                let r = k(kern).zeta() * h;
                let d = rel_diff(
                    |q| l.omega2(q).0,
                    |q| cf::b00_eq82_lagrangian_nodal(&phi, r, sig, q),
                );
                assert!(d < 1e-8, "{shape:?} {kern} h={h} σ̄={sig}: {d:e}");
            }
        }
    }
}

#[test]
fn b00_eq103_matches_lagrangian_stress_points() {
    for (kern, h) in [("efg-quartic", 1.5), ("efg-cubic", 2.5), ("m4", 1.2)] {
        for sig in [-0.5, 0.0, 0.5] {
            let l = lin(FormKind::LagrangianStressPoints, kern, MLS, h, sig);
            let phi = shape_fn(MLS, kern, h);
            let r = k(kern).zeta() * h;
            let d = rel_diff(
                |q| l.omega2(q).0,
                |q| cf::b00_eq103_lagrangian_stress_points(&phi, r, sig, q),
            );
            assert!(d < 1e-8, "{kern} h={h} σ̄={sig}: {d:e}");
        }
    }
}

/// [B00] eq 74 is the linearisation of the Galerkin nodal-integration force with a shape
/// function that moves rigidly with its node (eq 71). That is exact for `sph` shapes, so
/// `eulerian-nodal` + `sph` must match eq 74; with `mls` the shape functions re-adapt to the
/// perturbed neighbours and the engine differs (size printed, ERRATA E3).
#[test]
fn b00_eq74_matches_eulerian_nodal_with_sph_shapes() {
    for (kern, h) in [("m4", 1.2), ("wendland-c2", 1.6), ("efg-quartic", 2.5)] {
        for sig in [-0.5, 0.1, 1.0] {
            let l = lin(FormKind::EulerianNodal, kern, SPH, h, sig);
            let phi = shape_fn(SPH, kern, h);
            let r = k(kern).zeta() * h;
            let d = rel_diff(
                |q| l.omega2(q).0,
                |q| cf::b00_eq74_eulerian_nodal(&phi, r, sig, q),
            );
            assert!(d < 1e-8, "{kern} h={h} σ̄={sig}: {d:e}");
        }
    }
    for sig in [0.1, 1.0] {
        let l = lin(FormKind::EulerianNodal, "efg-quartic", MLS, 1.5, sig);
        let phi = shape_fn(MLS, "efg-quartic", 1.5);
        let d = rel_diff(
            |q| l.omega2(q).0,
            |q| cf::b00_eq74_eulerian_nodal(&phi, 1.5, sig, q),
        );
        eprintln!("eq 74 vs eulerian-nodal/mls/efg-quartic D_mx=1.5 σ̄={sig}: max rel diff {d:.3e}");
        // identical linearisations agree to 1e-8 here (the sph case above); the MLS
        // re-adaptation terms eq 71 drops must show far above that
        assert!(d > 1e-3, "the MLS re-adaptation term is expected to matter");
        // the eq 74 side of that size from an independent route: eq 74 written out with the
        // exact rational lattice values φ'(±1) = ∓1/2, φ''(±1) = 208/121 (common::exact)
        let ex = common::exact::mls_quartic_lattice(common::exact::Q::new(3, 2), false);
        for q in grid(400) {
            let s1: f64 = ex
                .iter()
                .map(|(j, v)| v[1].to_f64() * (q * *j as f64).sin())
                .sum();
            let s2: f64 = ex
                .iter()
                .map(|(j, v)| v[2].to_f64() * 2.0 * (0.5 * q * *j as f64).sin().powi(2))
                .sum();
            let exact = (1.0 + 2.0 * sig) * s1 * s1 - sig * s2;
            let code = cf::b00_eq74_eulerian_nodal(&phi, 1.5, sig, q);
            assert!(
                (code - exact).abs() <= 1e-12 * exact.abs().max(1.0),
                "κ={q}"
            );
        }
    }
    // The E3 verdict: eq 74 grows on (κ*, π] with cos κ* = 2σ̄φ''(1)/(1 + 2σ̄) − 1 (exact
    // φ''(1) = 208/121), while the exact linearisation of the same equations has ω² > 0 on the
    // whole of (0, π] — confirmed in the time domain by
    // `integrator.rs::eulerian_nodal_mls_in_tension_oscillates_as_the_engine_says`.
    for sig in [0.1, 0.2, 0.5, 1.0] {
        let l = lin(FormKind::EulerianNodal, "efg-quartic", MLS, 1.5, sig);
        let phi = shape_fn(MLS, "efg-quartic", 1.5);
        let kstar = (2.0 * sig * (208.0 / 121.0) / (1.0 + 2.0 * sig) - 1.0).acos();
        for q in grid(400) {
            assert!(l.omega2(q).0 > 0.0, "engine σ̄={sig} κ={q}");
            if q > kstar + 1e-9 {
                assert!(cf::b00_eq74_eulerian_nodal(&phi, 1.5, sig, q) < 0.0);
            }
        }
    }
}

/// The classical sum form doubles the stress term of eq 74 (ERRATA E1): with `sph` shapes the
/// engine equals eq 74 evaluated at 2σ̄ in the stress term, i.e. eq74(σ̄)·… — checked through
/// eq 74 itself: ω²_classical(σ̄) = 2·eq74(σ̄) − eq82(σ̄) − … is awkward, so we use the exact
/// identity ω²_classical = eq74(σ̄) + [eq74(σ̄) − eq82(σ̄)] (the stress term counted twice).
#[test]
fn classical_sum_form_is_eq74_with_the_stress_term_doubled() {
    for (kern, h) in [
        ("m4", 1.0),
        ("m4", 1.5),
        ("wendland-c6", 1.8),
        ("gaussian", 1.1),
    ] {
        for sig in [-0.5, 0.2, 1.0] {
            let l = lin(FormKind::Classical, kern, SPH, h, sig);
            let phi = shape_fn(SPH, kern, h);
            let r = k(kern).zeta() * h;
            let e74 = |q| cf::b00_eq74_eulerian_nodal(&phi, r, sig, q);
            let e82 = |q| cf::b00_eq82_lagrangian_nodal(&phi, r, sig, q);
            let d = rel_diff(|q| l.omega2(q).0, |q| 2.0 * e74(q) - e82(q));
            assert!(d < 1e-8, "{kern} h={h} σ̄={sig}: {d:e}");
        }
    }
}

/// [B00] eq 93 at F = 1 (the current configuration is the reference) against the
/// Eulerian stress-point form.
#[test]
fn b00_eq93_against_eulerian_stress_points() {
    for sig in [0.0, 0.2, 1.0] {
        let l = lin(FormKind::EulerianStressPoints, "efg-quartic", MLS, 1.5, sig);
        let phi = shape_fn(MLS, "efg-quartic", 1.5);
        let d = rel_diff(
            |q| l.omega2(q).0,
            |q| cf::b00_eq93_eulerian_stress_points(&phi, 1.5, sig, 1.0, q),
        );
        eprintln!(
            "eq 93 vs eulerian-stress-points/mls/efg-quartic D_mx=1.5 σ̄={sig}: max rel diff {d:.3e}"
        );
        if sig == 0.0 {
            assert!(
                d < 1e-8,
                "σ̄ = 0: eq 93 reduces to eq 103 and must match: {d:e}"
            );
        } else {
            // ERRATA E3: the MLS re-adaptation terms that eq 71 drops enter at σ̄ ≠ 0 — the
            // two routes must differ by far more than the 1e-8 at which identical
            // linearisations agree here
            assert!(d > 1e-3, "σ̄ = {sig}: {d:e}");
            // with sph shapes (which do move rigidly with their node) eq 93 is exact
            let l = lin(FormKind::EulerianStressPoints, "efg-quartic", SPH, 1.5, sig);
            let phi = shape_fn(SPH, "efg-quartic", 1.5);
            let d = rel_diff(
                |q| l.omega2(q).0,
                |q| cf::b00_eq93_eulerian_stress_points(&phi, 1.5, sig, 1.0, q),
            );
            assert!(d < 1e-8, "sph, σ̄ = {sig}: {d:e}");
        }
    }
}

/// [B00] eq 108 (consistent mass, nodal integration) against the least-squares form.
#[test]
fn b00_eq108_matches_least_squares() {
    for (kern, d_mx) in [
        ("efg-quartic", 1.5),
        ("efg-quartic", 2.5),
        ("efg-cubic", 2.0),
    ] {
        for alpha_s in [0.0, 0.001, 0.01, 0.1] {
            let mut p = params(FormKind::LeastSquares, kern, MLS, d_mx);
            p.alpha_s = alpha_s;
            let l = sphstab::vonneumann::linearise::Linearisation::new(p, 0.0, Default::default())
                .unwrap();
            let phi = shape_fn(MLS, kern, d_mx);
            let d = rel_diff(
                |q| l.omega2(q).0,
                |q| cf::b00_eq108_least_squares(&phi, d_mx, alpha_s, q),
            );
            assert!(d < 1e-8, "{kern} D_mx={d_mx} α_s={alpha_s}: {d:e}");
        }
    }
}

/// [B00] Fig 3 with its eq 74 (Eulerian kernel, nodal integration, mls, quartic weight):
/// "for D_mx = 1.5, the frequency becomes imaginary for tensile stress if the wave number κ is
/// greater than about 0.6π/Δx (the exact value depends on σ̄) … for D_mx = 2.5 the tensile
/// stress required for the onset of instability is greater".
///
/// Expected onsets from an independent route, not from the code under test: the exact
/// rational lattice values of the MLS shape function (`common::exact`, Taylor series in
/// fractions). At D_mx = 1.5 only j = 0, ±1 contribute, φ'(±1) = ∓1/2 and φ''(±1) = 208/121, so
/// S1 = −sin κ, S2 = 2 φ''(1)(1 − cos κ) and eq 74 factorises:
/// ω² = (1 + 2σ̄)S1² − σ̄S2 = (1 − cos κ)[(1 + 2σ̄)(1 + cos κ) − 2σ̄ φ''(1)], hence
/// cos κ* = 2σ̄ φ''(1)/(1 + 2σ̄) − 1 in closed form. At D_mx = 2.5 (j = 0, ±1, ±2) the onset is
/// the root of eq 74 written out with the exact values, found by bisection here.
#[test]
fn b00_fig3_tensile_onsets_match_exact_lattice_values() {
    use common::exact::{Q, mls_quartic_lattice};
    // first sign change of ω² in (0, π] on a fine grid, refined by bisection
    fn onset(w2: impl Fn(f64) -> f64) -> f64 {
        let n = 20_000;
        let mut lo = 0.0;
        let hi = (1..=n)
            .map(|i| PI * i as f64 / n as f64)
            .find(|&q| {
                let neg = w2(q) < 0.0;
                if !neg {
                    lo = q;
                }
                neg
            })
            .expect("eq 74 predicts a tensile instability");
        let (mut a, mut b) = (lo, hi);
        for _ in 0..100 {
            let m = 0.5 * (a + b);
            if w2(m) < 0.0 { b = m } else { a = m }
        }
        0.5 * (a + b)
    }
    let sigmas = [0.1, 0.2, 0.5, 1.0];
    let mut onsets = [[0.0; 4]; 2];
    for (row, (d_mx, r)) in [(1.5, Q::new(3, 2)), (2.5, Q::new(5, 2))]
        .into_iter()
        .enumerate()
    {
        let phi = shape_fn(MLS, "efg-quartic", d_mx);
        let exact: Vec<(f64, f64, f64)> = mls_quartic_lattice(r, false)
            .into_iter()
            .map(|(j, v)| (j as f64, v[1].to_f64(), v[2].to_f64()))
            .collect();
        for (col, &sig) in sigmas.iter().enumerate() {
            let code = onset(|q| cf::b00_eq74_eulerian_nodal(&phi, d_mx, sig, q));
            // eq 74 with the exact lattice values, S2 with 2 sin²(κj/2)
            let indep = onset(|q| {
                let s1: f64 = exact.iter().map(|&(j, d1, _)| d1 * (q * j).sin()).sum();
                let s2: f64 = exact
                    .iter()
                    .map(|&(j, _, d2)| d2 * 2.0 * (0.5 * q * j).sin().powi(2))
                    .sum();
                (1.0 + 2.0 * sig) * s1 * s1 - sig * s2
            });
            if d_mx == 1.5 {
                let b = 208.0 / 121.0;
                let closed = (2.0 * sig * b / (1.0 + 2.0 * sig) - 1.0).acos();
                assert!((indep - closed).abs() < 1e-12, "{indep} vs {closed}");
            }
            eprintln!(
                "B00 eq 74, mls/efg-quartic D_mx={d_mx}, σ̄={sig}: onset κΔx = {:.4}π (exact lattice values {:.4}π)",
                code / PI,
                indep / PI
            );
            assert!(
                (code - indep).abs() < 1e-9,
                "D_mx={d_mx} σ̄={sig}: {code} vs {indep}"
            );
            // unstable from the onset all the way to the cut-off
            assert!(cf::b00_eq74_eulerian_nodal(&phi, d_mx, sig, PI) < 0.0);
            onsets[row][col] = code / PI;
        }
    }
    // The paper's statements. Its σ̄ values are not recoverable (the figure did not survive the
    // text conversion), so "about 0.6π" is taken as the range [0.5π, 0.7π] of the onsets for
    // the intermediate stresses σ̄ = 0.2, 0.5 (0.6699π, 0.5449π); the onset falls as σ̄ grows
    // and a larger support needs more tension for the same onset.
    for row in &onsets {
        assert!(row.windows(2).all(|w| w[1] < w[0]), "{row:?}");
    }
    assert!(onsets[0][1..3].iter().all(|&o| (0.5..0.7).contains(&o)));
    assert!((0..4).all(|c| onsets[1][c] > onsets[0][c]), "{onsets:?}");
}

/// Swegle's discrete analysis [V21 App. B] for nearest-neighbour supports: the sum form is
/// unstable at κΔx = π exactly when W''σ > 0, and so is the engine's `classical`; the engine's
/// growth rate at π is √2 times Swegle's (the sum form counts the stress term twice, ERRATA E1).
#[test]
fn swegle_nearest_neighbour_criterion_and_growth() {
    let kern = k("m4");
    for h in [0.8, 0.9, 0.95] {
        // support 2h < 2Δx: only the nearest neighbours
        for sig in [0.05, -0.05] {
            let l = lin(FormKind::Classical, "m4", SPH, h, sig);
            let w2_engine = l.omega2(PI).0;
            let d2w = sphstab::kernel::d2w(kern, 1, 1.0, h);
            let dw = sphstab::kernel::dw(kern, 1, 1.0f64, h);
            let p = cf::SwegleParams {
                m: 1.0,
                rho: 1.0,
                rho0: 1.0,
                k_bulk: 1.0,
                w1: -dw,
                w2: d2w,
                t_stress: sig,
                alpha: 0.0,
            };
            let w2_swegle = cf::swegle_omega2_sum(&p, PI);
            assert_eq!(
                w2_engine < 0.0,
                cf::swegle_sum_unstable(d2w, sig),
                "h={h} σ̄={sig}"
            );
            assert_eq!(w2_swegle < 0.0, cf::swegle_sum_unstable(d2w, sig));
            assert!(
                (w2_engine - 2.0 * w2_swegle).abs() < 1e-10 * w2_swegle.abs(),
                "{w2_engine} vs 2×{w2_swegle}"
            );
        }
    }
}

/// [V21] eq A.72, the *continuous* nonlocal/LNL relation ω²/κ² = c² (c + (1 − c)|W*(κ)|²), with
/// W* by rustfft (checked against the analytic m4 transform (sin(k/2)/(k/2))⁴ in
/// tests/it/closed_form.rs), against the discrete `lnl` engine: they agree as κ → 0 (both → 1 for
/// the c-part, and S1 → −κ W*(κh)), and differ at finite κ by the lattice aliasing of the
/// discrete sums (printed; ERRATA E5). The FFT route and the analytic transform agree to 1e-8.
#[test]
fn v21_a72_continuum_against_discrete_lnl() {
    use sphstab::kernel::{self, Kernel};
    use sphstab::vonneumann::transform::{kernel_ft_fft, m4_ft};
    let m4: &dyn Kernel = kernel::by_name("m4").unwrap();
    let w = |x: f64| m4.sigma(1) * m4.f(1, x.abs());
    let (kk, ws) = kernel_ft_fft(&w, 2.0, 512);
    // The FFT table (k in units of 1/h) against the analytic transform on its own grid.
    for (&k, &v) in kk.iter().zip(&ws).take_while(|(k, _)| **k < 4.0 * PI) {
        assert!(
            (v - m4_ft(k)).abs() < 1e-8,
            "FFT vs analytic at k={k}: {v} vs {}",
            m4_ft(k)
        );
    }
    for c in [0.0, 0.5] {
        for h in [1.2, 2.0] {
            let mut p = params(FormKind::Lnl, "m4", SPH, h);
            p.c_partition = c;
            let l = sphstab::vonneumann::linearise::Linearisation::new(p, 0.0, Default::default())
                .unwrap();
            // Long waves: discrete ω²/κ² → (1 − c) M1² + c (M1 = −Σ j φ'(j), the discrete first
            // moment of the sph lattice shape), continuous → 1; the gap is the quadrature error
            // of the lattice sum.
            let small = 1e-4;
            let phi = shape_fn(SPH, "m4", h);
            let m1 = -(-6i64..=6)
                .map(|j| j as f64 * phi(j as f64)[1])
                .sum::<f64>();
            let ratio = l.omega2(small).0 / (small * small);
            assert!(
                (ratio - ((1.0 - c) * m1 * m1 + c)).abs() < 1e-7,
                "c={c} h={h}: {ratio} vs M1={m1}"
            );
            let a72 = cf::v21_a72_continuum(c, m4_ft(small * h), small) / (small * small);
            eprintln!(
                "A.72 vs lnl m4 h={h} c={c}: long-wave ω²/κ² discrete {ratio:.8} vs continuous {a72:.8} (M1 = {m1:.8})"
            );
            let mut worst: (f64, f64) = (0.0, 0.0);
            for q in grid(64) {
                let cont = cf::v21_a72_continuum(c, m4_ft(q * h), q);
                let d = (l.omega2(q).0 - cont).abs() / cont.abs().max(1e-300);
                if d > worst.0 {
                    worst = (d, q);
                }
            }
            let at = |q: f64| {
                let cont = cf::v21_a72_continuum(c, m4_ft(q * h), q);
                (l.omega2(q).0 - cont) / cont
            };
            eprintln!(
                "A.72 vs lnl m4 h={h} c={c}: relative difference {:+.3e} at π/4, {:+.3e} at π/2, {:+.3e} at π \
                 (max {:.3e} at {:.3}π; the discrete ω² vanishes at π, the continuum does not)",
                at(PI / 4.0),
                at(PI / 2.0),
                at(PI),
                worst.0,
                worst.1 / PI
            );
        }
    }
}

/// The least-squares critical leapfrog step at D_mx = 1.5 and 2.5 (mls, EFG quartic, σ = 0)
/// against eq 108 evaluated with the exact rational lattice values of φ, φ', φ'' on the nodes
/// (`common::exact`; no crate code), undamped leapfrog Δt_crit = 2/ω_max. The engine takes the
/// maximum over its 512-point κ grid, so the independent value is taken on the same grid (and
/// the continuous maximum, found by golden-section search, is printed next to it). Tolerance:
/// the bisection accepts |λ| ≤ 1 + 1e-7, which moves the leapfrog limit by far less than 1e-6.
#[test]
fn least_squares_critical_dt_matches_exact_lattice_values() {
    use common::exact::{Q, mls_quartic_lattice};
    use sphstab::analysis::{Query, query};
    for (d_mx, r) in [(1.5, Q::new(3, 2)), (2.5, Q::new(5, 2))] {
        let ex: Vec<(f64, [f64; 3])> = mls_quartic_lattice(r, false)
            .into_iter()
            .map(|(j, v)| (j as f64, [v[0].to_f64(), v[1].to_f64(), v[2].to_f64()]))
            .collect();
        for alpha_s in [0.01, 0.1, 0.5] {
            // eq 108 with β = α_s (l_c = Δx = 1)
            let w2 = |q: f64| {
                let s1: f64 = ex.iter().map(|(j, v)| v[1] * (q * j).sin()).sum();
                let p: f64 = ex.iter().map(|(j, v)| v[0] * (q * j).cos()).sum();
                let qq: f64 = ex.iter().map(|(j, v)| v[2] * (q * j).cos()).sum();
                (s1 * s1 + alpha_s * qq * qq) / (p * p - alpha_s * qq * p)
            };
            let grid = (1..=512).map(|i| PI * i as f64 / 512.0);
            let (wmax, kmax) = grid
                .map(|q| (w2(q), q))
                .fold((0.0f64, 0.0), |a, b| if b.0 > a.0 { b } else { a });
            let dt_grid = 2.0 / wmax.sqrt();
            // continuous maximum around the grid maximum (golden section, unimodal there)
            let (mut a, mut b) = ((kmax - PI / 512.0).max(1e-9), (kmax + PI / 512.0).min(PI));
            let g = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..200 {
                let (c, d) = (b - g * (b - a), a + g * (b - a));
                if w2(c) > w2(d) { b = d } else { a = c }
            }
            let wc = w2(0.5 * (a + b)).max(wmax);
            let mut qq = Query::<1>::new(FormKind::LeastSquares, k("efg-quartic"), d_mx, 0.0);
            qq.shape = MLS;
            qq.alpha_s = alpha_s;
            let rep = query(&qq).unwrap();
            assert!(rep.stable, "D_mx={d_mx} α_s={alpha_s}");
            let dt = rep.critical_dt.unwrap();
            eprintln!(
                "least-squares D_mx={d_mx} α_s={alpha_s}: critical Δt engine {dt:.6}, eq 108 with exact values {dt_grid:.6} (grid), {:.6} (continuous max at κΔx = {:.4}π)",
                2.0 / wc.sqrt(),
                kmax / PI
            );
            assert!(
                (dt - dt_grid).abs() <= 1e-6 * dt_grid,
                "D_mx={d_mx} α_s={alpha_s}: {dt} vs {dt_grid}"
            );
        }
    }
}
