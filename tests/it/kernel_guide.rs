//! The kernel guide (`sphstab kernels --table`): its cells against analytic results and
//! independent computations (each test names where its expected value comes from), its reuse of
//! the `tradeoff --cfl-table` code path, the command line, and the docs/kernels.md block against the
//! command's output.

use crate::common;

use common::{assert_bad_inputs, json, sphstab};
use rayon::prelude::*;
use sphstab::forms::FormKind;
use sphstab::integrator::Integrator;
use sphstab::kernel::{self, Kernel};
use sphstab::lattice::Lattice;
use sphstab::shape::{KernelParams, ShapeFamily};
use sphstab::studies::kernel_guide::{
    COMPRESSION, GUIDE_FORMS, GUIDE_H, GuideConfig, Interval, MAX_SUPPORT_2D, PhaseGrid,
    REFERENCE_TENSION, SAFETY, WSTAR_K_STEP, closed_form_growth_1d, closed_form_zone_2d,
    compression_scan, intervals, max_growth_1d, query_1d, query_2d, tensile_onset, time_step_cell,
};
use sphstab::studies::pairing::wstar::{NEGATIVE_TOL, Transform, scan_grid, sign_criterion_with};
use sphstab::studies::pairing::wstar_scan::{proxy_scan, sign_criterion_fast};
use sphstab::studies::pairing::{ZoneGrowth, zone_growth};
use sphstab::studies::tradeoff::cfl::cfl_cell;
use sphstab::vonneumann::classify::GROWTH_TOL;
use sphstab::vonneumann::derived::{SphSums, sums};
use sphstab::vonneumann::transform::{
    RadialRule, gauss_legendre, lucy_ft, panel_layout, radial_integral,
};
use std::f64::consts::PI;
use std::path::Path;

fn k(name: &str) -> &'static dyn Kernel {
    kernel::by_name(name).unwrap()
}

/// The CFL column is the `tradeoff --cfl-table` cell, bit for bit (same `IntegratorReport::of`
/// on the same linearisation and κ grid), for every kernel, form and h of the guide.
#[test]
fn cfl_is_the_cfl_table_cell() {
    for &kern in kernel::all() {
        for f in GUIDE_FORMS {
            let form = FormKind::by_name(f).unwrap();
            for h in GUIDE_H {
                let c = cfl_cell(form, kern, h, Integrator::Kdk).unwrap();
                let g = time_step_cell(form, kern, h).unwrap();
                assert_eq!(g.critical_cfl, c.critical_cfl, "{} {f} {h}", kern.name());
                assert_eq!(g.critical_dt, c.critical_dt, "{} {f} {h}", kern.name());
                assert_eq!(g.shape, c.shape);
            }
        }
    }
}

/// Expected values from a hand derivation: total-Lagrangian SPH with MLS shapes and a support
/// reaching only the nearest neighbours (Δx < R = ζh ≤ 2Δx; the ζ = 1 kernels at h = 1.3 and 2,
/// the neighbour at 2Δx = R being outside) differentiates with the linear MLS fit through three
/// points, the central difference (u_{j+1} − u_{j−1})/2Δx, whatever the kernel; nodal
/// integration applies it twice, so ω² = sin²κ (c = Δx = 1; [B00] Table II: max ω² = 1). The
/// leapfrog (kdk) is stable for ωΔt ≤ 2: Δt_crit = 2, CFL = 2/h, and its mode advances by
/// θ = 2 asin(ωΔt/2) per step, so the phase error per wavelength travelled is
/// (θ/Δt − κ)·2π/κ at Δt = 0.9·2.
#[test]
fn total_lagrangian_nearest_neighbour_mls_is_the_central_difference() {
    let tl = FormKind::by_name("total-lagrangian").unwrap();
    for name in ["lucy", "efg-cubic", "efg-quartic", "mollifier"] {
        for h in GUIDE_H {
            let c = time_step_cell(tl, k(name), h).unwrap();
            let cfl = c.critical_cfl.unwrap();
            assert!(
                (cfl - 2.0 / h).abs() < 1e-6 * cfl,
                "{name} h={h}: CFL {cfl}"
            );
            let dt = SAFETY * 2.0;
            for (ppw, got) in [(10.0, c.phase_error_10ppw), (20.0, c.phase_error_20ppw)] {
                let kap = 2.0 * PI / ppw;
                let w = kap.sin();
                let expected = (2.0 * (0.5 * w * dt).asin() / dt - kap) * 2.0 * PI / kap;
                let got = got.unwrap();
                // the guide's Δt is 0.9 × the bisected Δt_crit (relative gap 1e-9 or better)
                assert!(
                    (got - expected).abs() < 1e-6,
                    "{name} h={h} {ppw} ppw: {got} vs {expected}"
                );
            }
            // leapfrog: |λ| = 1 below the limit, no amplitude error
            assert!(c.amplitude_error_10ppw.unwrap().abs() < 1e-9);
        }
    }
}

/// Σ_{j odd, 0 < j < ζh} f''(j/h): the sign of S2(π) ([V21] App. B; this crate's derived
/// ω² = C̃S1² − 2σ̄(S2 − S1²) with S1(π) = 0, S2(π) = Σ_j φ''(j)·2 sin²(πj/2) = 4 Σ_{odd j>0}
/// φ''(j)), computed from the kernel's analytic f''.
fn odd_curvature_sum(kern: &dyn Kernel, h: f64) -> f64 {
    let mut s = 0.0;
    let mut j = 1;
    while (j as f64) < kern.zeta() * h {
        s += kern.d2f(1, j as f64 / h);
        j += 2;
    }
    s
}

/// Expected from the κΔx = π mode of classical 1D SPH: ω²(π) = −2σ̄ S2(π), so where
/// S2(π) > 0 (the kernel is convex at the odd neighbours, Swegle's criterion W'' > 0) the chain
/// grows for any tension, at γ(π) = √(2σ̄ S2(π)) ≤ the largest growth rate. For m4 with
/// 1 < h < 1.5 the only odd neighbour is j = 1 at q = 1/h > 2/3 = q*, m4's inflection point
/// (analytic: f'' = −3 + 9q/2 vanishes at q = 2/3) — the classical tensile criterion.
#[test]
fn tensile_onset_follows_the_inflection_point_criterion() {
    let m4 = k("m4");
    assert!((m4.inflection(1) - 2.0 / 3.0).abs() < 1e-15);
    for h in [1.05, 1.2, 1.3, 1.45] {
        assert!(1.0 / h > 2.0 / 3.0);
        let t = tensile_onset(m4, h).unwrap();
        assert_eq!(t.kind, "any", "m4 h = {h}: {t:?}");
    }
    for &kern in kernel::all() {
        for h in GUIDE_H {
            let s = odd_curvature_sum(kern, h);
            let t = tensile_onset(kern, h).unwrap();
            if s > 1e-9 {
                assert_eq!(t.kind, "any", "{} h = {h}: S2(π) ∝ {s} > 0", kern.name());
                // φ = V W with V = Δx = 1, W'' = σ₁ f''/h³
                let s2 = 4.0 * kern.sigma(1) * s / h.powi(3);
                let gamma_pi = (2.0 * REFERENCE_TENSION * s2).sqrt();
                assert!(
                    t.growth_at_reference >= gamma_pi * (1.0 - 1e-6),
                    "{} h = {h}: γ = {} < γ(π) = {gamma_pi}",
                    kern.name(),
                    t.growth_at_reference
                );
            }
            if let Some(o) = t.onset {
                assert!(o > 0.0 && t.last_stable.unwrap() < o);
            }
        }
    }
}

/// Expected values from the B-spline transforms (Schoenberg 1946): the 1D B-spline of order n
/// (n-fold convolution of the unit box) has W* = (sin(k/2)/(k/2))ⁿ — never negative for even n
/// (m4: n = 4, m6: n = 6; the EFG cubic is m4 compressed by 2), negative first beyond k = 2π
/// for odd n (m5: n = 5, a five-fold root, resolved to ~5e-3). In 3D the odd-power B-splines'
/// transform (3/s³) sincⁿ⁻¹(s)(sin s − s cos s) first turns negative at k = 2π too
/// (tests/it/pairing.rs derives it).
#[test]
fn bspline_transforms_sign() {
    for name in ["m4", "m6", "efg-cubic"] {
        let s = sign_criterion_with(k(name), 1, WSTAR_K_STEP);
        assert!(s.first_negative_k.is_none(), "{name}: {s:?}");
        assert!(s.min >= -NEGATIVE_TOL);
    }
    let m5 = sign_criterion_with(k("m5"), 1, WSTAR_K_STEP);
    let k0 = m5.first_negative_k.unwrap();
    assert!((k0 - 2.0 * PI).abs() < 1e-2, "m5 1D: {k0}");
    let m4 = sign_criterion_with(k("m4"), 3, WSTAR_K_STEP);
    assert!((m4.first_negative_k.unwrap() - 2.0 * PI).abs() < 1e-3);
}

/// Expected from Wendland (1995): ψ_{⌊d/2⌋+k+1,k} is positive definite on R^d, so its Fourier
/// transform is positive. The crate uses the 1D functions in 1D and the 3D functions (positive
/// definite on R³, hence on R²) in 2D and 3D (Dehnen & Aly 2012): never negative in any
/// dimension.
#[test]
fn wendland_transforms_never_negative() {
    for name in ["wendland-c2", "wendland-c4", "wendland-c6"] {
        for d in 1..=3 {
            let s = sign_criterion_with(k(name), d, WSTAR_K_STEP);
            assert!(s.first_negative_k.is_none(), "{name} {d}D: {s:?}");
            assert!(s.min > 0.0, "{name} {d}D: {s:?}");
        }
    }
}

/// Expected from the closed forms of `vonneumann::transform`: Lucy (= EFG quartic) has
/// W*(k) = (60/k⁴)(2 + cos k − 3 sin k/k) > 0 (integration by parts), so it is never negative
/// in 1D and the scan's minimum is the closed form's value there. The crate's Gaussian is
/// truncated at q = 3: its 1D W* differs from e^{−k²/4} by at most 2 erfc(3)/(1 − erfc(3)) =
/// 4.42e-5, so it cannot turn negative while e^{−k²/4} > 4.42e-5, i.e. below
/// k = 2√(ln(1/4.42e-5)) ≈ 6.33, and never dips below −4.42e-5.
#[test]
fn lucy_and_truncated_gaussian_transforms() {
    for name in ["lucy", "efg-quartic"] {
        let s = sign_criterion_with(k(name), 1, WSTAR_K_STEP);
        assert!(s.first_negative_k.is_none());
        assert!((s.min - lucy_ft(s.k_at_min)).abs() < 1e-12, "{name}: {s:?}");
    }
    let bound: f64 = 4.42e-5;
    let g = sign_criterion_with(k("gaussian"), 1, WSTAR_K_STEP);
    let k0 = g
        .first_negative_k
        .expect("the truncated Gaussian's 1D W* turns negative");
    assert!(k0 > 2.0 * (1.0 / bound).ln().sqrt(), "{k0}");
    assert!(g.min > -bound, "{g:?}");
}

/// Independent computation of the 2D transform (the Hankel transform with `libm::j0`): the
/// same W*(k) = ∫∫ W(|x|) cos(k x) dx dy by brute force, a tensor-product Gauss–Legendre rule on
/// the square [−ζ, ζ]² (no Bessel function), normalised by its value at k = 0.
#[test]
fn two_d_transform_against_a_cartesian_quadrature() {
    let (x, w) = gauss_legendre(8);
    for name in ["m4", "wendland-c2", "lucy"] {
        let kern = k(name);
        let zeta = kern.zeta();
        let panels = 240;
        let width = 2.0 * zeta / panels as f64;
        let mut nodes = Vec::new();
        for p in 0..panels {
            let mid = -zeta + (p as f64 + 0.5) * width;
            for (xi, wi) in x.iter().zip(&w) {
                nodes.push((mid + 0.5 * width * xi, 0.5 * width * wi));
            }
        }
        let brute = |kk: f64| -> f64 {
            let mut s = 0.0;
            for &(xa, wa) in &nodes {
                let c = (kk * xa).cos() * wa;
                for &(yb, wb) in &nodes {
                    s += c * wb * kern.f(2, xa.hypot(yb));
                }
            }
            s
        };
        let t = Transform::new(kern, 2);
        let norm = brute(0.0);
        for kk in [1.0, 3.0, 5.692, 8.0] {
            let b = brute(kk) / norm;
            assert!(
                (t.at(kk) - b).abs() < 2e-6,
                "{name} k = {kk}: Hankel {} vs Cartesian {b}",
                t.at(kk)
            );
        }
    }
}

/// Dehnen & Aly (2012, §4): SPH pairs under pressure when the kernel's transform turns negative
/// somewhere; with W* ≥ 0 it does not. The guide's 1D chain follows it on the whole scan: the
/// kernels whose 1D W* never turns negative (m4, m6, Wendland, Lucy: previous tests) are stable
/// in compression at every h/Δx of the scan, the others (m5, truncated Gaussian, mollifier) grow
/// somewhere; in 2D Wendland C2 (positive definite) never pairs up to R = 6Δx.
#[test]
fn compression_follows_the_transform_sign() {
    let h: Vec<f64> = (0..=52).map(|i| 0.8 + 0.1 * i as f64).collect();
    for &kern in kernel::all() {
        let w_neg = sign_criterion_with(kern, 1, WSTAR_K_STEP)
            .first_negative_k
            .is_some();
        let c = compression_scan(kern, 1, &h).unwrap();
        let whole = c.scanned.unwrap();
        let all_stable = c.stable == vec![whole];
        assert_eq!(all_stable, !w_neg, "{}: {:?}", kern.name(), c.stable);
    }
    let c = compression_scan(k("wendland-c2"), 2, &h).unwrap();
    assert_eq!(c.no_pairing, vec![c.scanned.unwrap()]);
}

/// The compression columns come from the derived closed form of the sum form
/// (`kernel_guide/compression.rs`); the engine's chain linearisation gives the same largest
/// growth rate to rounding (|Δγ| ≤ 1e-8 c/Δx: γ = √(−ω²) of an ω² that is zero up to ~1e-17 in
/// one and not the other) and the same verdict at GROWTH_TOL, at every h of the guide's 1D scans
/// (the engine's κ grid and stress), for every kernel.
#[test]
fn compression_1d_closed_form_is_the_engine() {
    let h = GuideConfig::default().h_grid();
    for &kern in kernel::all() {
        let hs: Vec<f64> = h
            .iter()
            .copied()
            .filter(|&x| kern.zeta() * x > 1.0)
            .collect();
        let cf = closed_form_growth_1d(kern, &hs, COMPRESSION).unwrap();
        for (&x, &g) in hs.iter().zip(&cf) {
            let e = max_growth_1d(kern, x, COMPRESSION).unwrap();
            let at = format!(
                "{} h = {x}: engine γ = {e:e}, closed form {g:e}",
                kern.name()
            );
            assert!((e - g).abs() <= 1e-8, "{at}");
            assert_eq!(e > GROWTH_TOL, g > GROWTH_TOL, "{at}");
        }
    }
}

/// The 2D column: the closed form on the pairing study's zone scan gives the engine's
/// `zone_growth` (the Bloch linearisation of the periodic patch) — all three rates to 1e-12
/// c/Δx (8e-15 measured) at every fifth h of each kernel's 2D scan (the patch costs ~10 ms per h;
/// the docs/kernels.md block, the command's output at every h, is checked below).
#[test]
fn compression_2d_closed_form_is_the_engine() {
    let h = GuideConfig::default().h_grid();
    for &kern in kernel::all() {
        let r = |x: f64| kern.zeta() * x;
        let hs: Vec<f64> = h
            .iter()
            .copied()
            .filter(|&x| r(x) > 1.0 && r(x) <= MAX_SUPPORT_2D + 1e-9)
            .step_by(5)
            .collect();
        let cf = closed_form_zone_2d(kern, &hs, COMPRESSION).unwrap();
        let en: Vec<ZoneGrowth> = hs
            .par_iter()
            .map(|&x| zone_growth(&query_2d(kern, x, COMPRESSION)).unwrap())
            .collect();
        for ((x, a), b) in hs.iter().zip(&en).zip(&cf) {
            let worst = (a.max_growth_rate - b.max_growth_rate)
                .abs()
                .max((a.pairing_growth_rate - b.pairing_growth_rate).abs())
                .max((a.transverse_growth_rate - b.transverse_growth_rate).abs());
            assert!(
                worst <= 1e-12,
                "{} h = {x}: engine {a:?}, closed form {b:?}",
                kern.name()
            );
        }
    }
}

/// The lattice sums of the compression scans, from derivatives cached per h (`SphSums`) and
/// phases tabulated per scan (`PhaseGrid`), are `derived::sums` to the last bit (1D chain and 2D
/// square lattice, every wave vector of the scans).
#[test]
fn tabulated_lattice_sums_are_derived_sums() {
    for name in ["m4", "lucy", "gaussian"] {
        for h in [1.05, 2.0, 3.0] {
            let kp = KernelParams { kernel: k(name), h };
            let chain = Lattice::<1>::chain();
            let ks1: Vec<[f64; 1]> = query_1d(k(name), h, 0.0)
                .kappas()
                .into_iter()
                .map(|x| [x])
                .collect();
            let s1 = SphSums::new(&chain, kp);
            let g1 = PhaseGrid::new(&chain, &ks1, s1.reach());
            for (i, &kv) in ks1.iter().enumerate() {
                let want = sums(&chain, ShapeFamily::Sph, kp, kv).unwrap();
                let got = s1.with_phases(g1.row(i));
                assert_eq!(
                    format!("{got:?}"),
                    format!("{want:?}"),
                    "{name} h={h} {kv:?}"
                );
            }
            let q = query_2d(k(name), h, 0.0);
            let ks2 = q.kgrid();
            let s2 = SphSums::new(&q.lattice, kp);
            let g2 = PhaseGrid::new(&q.lattice, &ks2, s2.reach());
            for (i, &kv) in ks2.iter().enumerate() {
                let want = sums(&q.lattice, ShapeFamily::Sph, kp, kv).unwrap();
                let got = s2.with_phases(g2.row(i));
                assert_eq!(
                    format!("{got:?}"),
                    format!("{want:?}"),
                    "{name} h={h} {kv:?}"
                );
            }
        }
    }
}

fn every_kernel_and_dimension() -> Vec<(&'static dyn Kernel, usize)> {
    kernel::all()
        .iter()
        .flat_map(|&kern| (1..=3).map(move |d| (kern, d)))
        .collect()
}

/// The guide's W* column (`wstar_scan::sign_criterion_fast`: a Chebyshev proxy of the samples
/// with a rigorous bound, the samples evaluated where the bound cannot decide) is the full scan
/// of `sign_criterion_with` to the last bit, for every kernel and dimension at the guide's step
/// — all the guide can ask.
#[test]
fn wstar_fast_scan_is_the_full_scan() {
    every_kernel_and_dimension()
        .par_iter()
        .for_each(|&(kern, d)| {
            let full = sign_criterion_with(kern, d, WSTAR_K_STEP);
            let fast = sign_criterion_fast(kern, d, WSTAR_K_STEP);
            assert_eq!(format!("{fast:?}"), format!("{full:?}"), "{d}D");
        });
}

/// The proxy's bound holds, with room to spare: |w̃_i − w_i| ≤ ε_i / 10 at every sample
/// (w_i = `Transform::at`, the full scan's sample), every kernel and dimension, at step 0.02 (runs
/// of 200 samples, long enough to be proxied).
#[test]
fn wstar_proxy_is_within_its_bound() {
    let step = 0.02;
    let ks = scan_grid(step);
    every_kernel_and_dimension()
        .par_iter()
        .for_each(|&(kern, d)| {
            let p = proxy_scan(kern, d, step).expect("finite proxy");
            let t = Transform::new(kern, d);
            let proxied = p.bounds.iter().filter(|&&e| e > 0.0).count();
            assert!(proxied > ks.len() / 2, "{} {d}D: {proxied}", kern.name());
            for (i, &kk) in ks.iter().enumerate() {
                let (w, e) = (t.at(kk), p.bounds[i]);
                assert!(
                    (p.values[i] - w).abs() <= 0.1 * e || p.values[i] == w,
                    "{} {d}D k = {kk}: proxy {} sample {w} bound {e:e}",
                    kern.name(),
                    p.values[i]
                );
            }
        });
}

/// The quadrature rule with its kernel factors cached per panel layout (`RadialRule`, the W*
/// scan's evaluations) is `radial_integral` to the last bit, at wave numbers in every layout
/// and at the layout changes.
#[test]
fn cached_quadrature_rule_is_radial_integral() {
    for (kern, d) in every_kernel_and_dimension() {
        let g = move |q: f64| kern.f(d, q);
        let z = kern.zeta();
        for kk in [
            0.0, 0.37, 4.0, 4.01, 7.99, 8.0, 8.01, 12.5, 33.3, 39.99, 40.0, 61.7,
        ] {
            let layout = panel_layout(z, kk);
            let (got, want) = match d {
                1 => (
                    RadialRule::<1>::new(&g, z, &layout).eval(kk),
                    radial_integral::<1>(&g, z, kk),
                ),
                2 => (
                    RadialRule::<2>::new(&g, z, &layout).eval(kk),
                    radial_integral::<2>(&g, z, kk),
                ),
                _ => (
                    RadialRule::<3>::new(&g, z, &layout).eval(kk),
                    radial_integral::<3>(&g, z, kk),
                ),
            };
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "{} {d}D k = {kk}",
                kern.name()
            );
        }
    }
}

/// Interval bookkeeping.
#[test]
fn intervals_merge_consecutive_values() {
    let h = [1.0, 1.1, 1.2, 1.3, 1.4];
    let iv = intervals(&h, &[true, true, false, true, false]);
    assert_eq!(
        iv,
        vec![
            Interval { from: 1.0, to: 1.1 },
            Interval { from: 1.3, to: 1.3 }
        ]
    );
    assert!(intervals(&h, &[false; 5]).is_empty());
}

#[test]
fn bad_flags_exit_2_with_one_line() {
    assert_bad_inputs(&[
        (&["kernels", "--h-step", "0.1"], "--h-step"),
        (&["kernels", "--kernels", "m4"], "--kernels"),
        (&["kernels", "--table", "--h-step", "0"], "--h-step"),
        (&["kernels", "--table", "--h-step", "nan"], "--h-step"),
        (&["kernels", "--table", "--kernels", "nosuch"], "kernel"),
        (&["kernels", "--table", "--kernels", "m4,m4"], "--kernels"),
    ]);
}

#[test]
fn json_subset_has_every_field() {
    let j = json(&[
        "kernels",
        "--table",
        "--json",
        "--kernels",
        "lucy",
        "--h-step",
        "0.5",
    ]);
    let r = &j["rows"][0];
    assert_eq!(r["kernel"], "lucy");
    assert_eq!(r["time_step"].as_array().unwrap().len(), 4);
    assert_eq!(r["compression"].as_array().unwrap().len(), 2);
    assert_eq!(r["tension"].as_array().unwrap().len(), 2);
    assert_eq!(r["positivity"].as_array().unwrap().len(), 3);
    assert_eq!(j["h_step"], 0.5);
}

/// The kernel guide of docs/kernels.md is the output of the command, verbatim.
#[test]
fn documented_kernel_guide_is_the_command_output() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("docs/kernels.md")).unwrap();
    let start = readme
        .find("<!-- kernel-guide -->\n")
        .expect("start marker")
        + 22;
    let end = readme.find("<!-- /kernel-guide -->").expect("end marker");
    let (code, out, err) = sphstab(&["kernels", "--table"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        readme[start..end].trim() == out.trim(),
        "docs/kernels.md's kernel guide differs from `cargo run --release -- kernels --table`"
    );
}
