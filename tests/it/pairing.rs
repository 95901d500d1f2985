//! The pairing study: the kernel transform against closed forms, the study's growth rates
//! against an independent closed-form dynamical matrix, the command line (JSON fields, bad
//! input), and the committed figure against its stored data.

use crate::common;

use common::{assert_bad_inputs, json, sphstab};
use sphstab::kernel::{self, Kernel};
use sphstab::lattice::Lattice;
use sphstab::studies::pairing::wstar::{NEGATIVE_TOL, Transform3D, sign_criterion};
use sphstab::studies::pairing::{
    PairingReport, evaluate_row, figure_svg, neighbour_count, parse_config, plan,
};
use std::f64::consts::PI;
use std::path::Path;

/// 3D transform of the centred B-spline of order n with unit knot spacing (m4, m5, m6 are
/// n = 4, 5, 6), normalised to 1 at k = 0, k in units of 1/h:
///
/// ```text
/// Ŵ_n(k) = (3/s³) sinc^{n−1}(s) (sin s − s cos s),   s = k/2
/// ```
///
/// Derivation: the 1D transform of the B-spline is F₁(k) = sinc^n(k/2) (n-fold convolution of
/// the unit box); for a radial profile g, the 3D transform is (4π/k)∫ r g(r) sin kr dr
/// = −(2π/k) F₁'(k), with F₁ the 1D transform of g(|x|). Normalising by its k → 0 limit
/// (−F₁'(k)/k → n/12) gives the formula. Sign: sin s − s cos s > 0 on (0, 4.4934) (first root
/// of tan s = s), so m4 and m6 (odd power of sinc) first turn negative where sinc does, at
/// s = π (k = 2π), and m5 (even power) at s = 4.493409457909064 (k = 8.986818915818128).
fn bspline_ft3(n: i32, k: f64) -> f64 {
    let s = 0.5 * k;
    // (sin s − s cos s)/s³ = Σ_{m≥1} (−1)^{m+1} 2m s^{2m−2}/(2m+1)!  (series below s = 1, where
    // the closed expression cancels; 12 terms leave < 1e-20)
    let j = if s < 1.0 {
        let mut sum = 0.0;
        let mut fact = 6.0; // (2m+1)!
        let mut pow = 1.0; // s^{2m−2}
        for m in 1..=12 {
            let mf = f64::from(m);
            if m > 1 {
                fact *= (2.0 * mf) * (2.0 * mf + 1.0);
                pow *= s * s;
            }
            let sign = if m % 2 == 1 { 1.0 } else { -1.0 };
            sum += sign * 2.0 * mf * pow / fact;
        }
        sum
    } else {
        (s.sin() - s * s.cos()) / (s * s * s)
    };
    let sinc = if s == 0.0 { 1.0 } else { s.sin() / s };
    3.0 * sinc.powi(n - 1) * j
}

#[test]
fn wstar_of_the_bsplines_matches_the_closed_form() {
    for (name, n) in [("m4", 4), ("m5", 5), ("m6", 6)] {
        let t = Transform3D::new(kernel::by_name(name).unwrap());
        let mut worst: f64 = 0.0;
        for i in 0..=4000 {
            let k = 0.01 * f64::from(i);
            worst = worst.max((t.at(k) - bspline_ft3(n, k)).abs());
        }
        assert!(
            worst < 1e-12,
            "{name}: worst |W* − closed form| = {worst:e}"
        );
    }
    // where W* first turns negative (closed-form roots, module doc above)
    let m4 = sign_criterion(kernel::by_name("m4").unwrap());
    assert!(m4.negative);
    // triple root (sinc³): W* ≈ 0.30((k − 2π)/2π)³ changes sign above round-off beyond ~4e-5
    assert!(
        (m4.first_negative_k.unwrap() - 2.0 * PI).abs() < 1e-4,
        "{m4:?}"
    );
    let m5 = sign_criterion(kernel::by_name("m5").unwrap());
    assert!(
        (m5.first_negative_k.unwrap() - 8.986_818_915_818_128).abs() < 1e-9,
        "{m5:?}"
    );
    // five-fold root (sinc⁵): W* ≈ −0.30((k − 2π)/2π)⁵ is below round-off for |k − 2π| ≲ 5e-3
    let m6 = sign_criterion(kernel::by_name("m6").unwrap());
    assert!(
        (m6.first_negative_k.unwrap() - 2.0 * PI).abs() < 1e-2,
        "{m6:?}"
    );
    // the minimum against a golden-section search on the closed form (first negative lobe
    // of m4, s ∈ (π, 4.4934), i.e. k ∈ (2π, 8.9868))
    let (mut lo, mut hi) = (2.0 * PI, 8.986_818_915_818_128);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if bspline_ft3(4, c) < bspline_ft3(4, d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    let kmin = 0.5 * (lo + hi);
    assert!(
        (m4.min - bspline_ft3(4, kmin)).abs() < 1e-12,
        "{m4:?} vs {}",
        bspline_ft3(4, kmin)
    );
    assert!((m4.k_at_min - kmin).abs() < 1e-5, "{m4:?} vs {kmin}");
}

/// The Gaussian exp(−q²) truncated at q = 3 and renormalised: W* differs from the untruncated
/// e^{−k²/4} by at most 2m/(1 − m), m = erfc(3) + (6/√π)e^{−9} = 4.398e-4 the 3D mass beyond
/// r = 3h of the normalised Gaussian π^{−3/2}e^{−r²} (the tail's transform is bounded by its mass).
#[test]
fn wstar_of_the_truncated_gaussian_is_within_its_truncation_bound() {
    let m = 2.209_049_699_858_544e-5 + 6.0 / PI.sqrt() * (-9.0f64).exp();
    let bound = 2.0 * m / (1.0 - m);
    let t = Transform3D::new(kernel::by_name("gaussian").unwrap());
    for i in 0..=200 {
        let k = 0.1 * f64::from(i);
        let d = (t.at(k) - (-0.25 * k * k).exp()).abs();
        assert!(d <= bound, "k = {k}: {d:e} > {bound:e}");
    }
}

/// Wendland's ψ_{3,k} are positive definite on R³ (Wendland 1995): W* > 0 for every k.
#[test]
fn wstar_of_the_wendland_kernels_is_never_negative() {
    for name in ["wendland-c2", "wendland-c4", "wendland-c6"] {
        let s = sign_criterion(kernel::by_name(name).unwrap());
        assert!(!s.negative, "{s:?}");
        assert!(s.min >= -NEGATIVE_TOL, "{s:?}");
        assert!(s.first_negative_k.is_none());
    }
}

/// The classical sum form with `sph` shapes on a hydro lattice at pre-stress σ̄ (ρ = 1 − σ̄,
/// V = 1, K = ρ0 = 1): ρD = (ρ + 2σ̄) S1S1ᵀ − 2σ̄ S2 with S1 = Σ_R ∇W(R) sin k·R and
/// S2 = Σ_R ∇∇W(R)(1 − cos k·R) — the derivation of analysis/ERRATA.md E1 carried to 3D
/// (src/vonneumann/derived.rs gives it for D = 1, 2, 3). Lattice sums written here from the kernel alone,
/// independent of the rate function and its linearisation.
fn closed_form_d(
    k: &'static dyn Kernel,
    lat: &Lattice<3>,
    h: f64,
    s: f64,
    kv: [f64; 3],
) -> nalgebra::Matrix3<f64> {
    let r = k.zeta() * h;
    let mut s1 = nalgebra::Vector3::zeros();
    let mut s2 = nalgebra::Matrix3::zeros();
    for (_, p) in lat.offsets_within(r) {
        let d = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        if d == 0.0 {
            continue;
        }
        let n = nalgebra::Vector3::new(p[0] / d, p[1] / d, p[2] / d);
        let (w1, w2) = (kernel::dw(k, 3, d, h), kernel::d2w(k, 3, d, h));
        let t = kv[0] * p[0] + kv[1] * p[1] + kv[2] * p[2];
        s1 += n * (w1 * t.sin());
        let hess =
            n * n.transpose() * w2 + (nalgebra::Matrix3::identity() - n * n.transpose()) * (w1 / d);
        s2 += hess * (1.0 - t.cos());
    }
    let rho = 1.0 - s;
    (s1 * s1.transpose() * (rho + 2.0 * s) - s2 * (2.0 * s)) / rho
}

/// Over the study's wave vectors: the largest growth √max(0, −λ) of the closed-form D, and the
/// largest growth of an eigenspace holding a mode with |ê·k̂|² ≥ ½ (degenerate eigenvalues,
/// within 1e-9 of the largest |λ|, grouped; |P k̂|² summed over their orthonormal eigenvectors).
fn closed_form_scan(
    k: &'static dyn Kernel,
    lat: &Lattice<3>,
    h: f64,
    s: f64,
    grid: usize,
) -> (f64, f64) {
    let q = sphstab::studies::pairing::row_query(k, *lat, h, s, grid);
    let (mut all, mut long) = (0.0f64, 0.0f64);
    for kv in q.kgrid() {
        let e = nalgebra::SymmetricEigen::try_new(closed_form_d(k, lat, h, s, kv), 1e-15, 1000)
            .unwrap();
        let kn = (kv[0] * kv[0] + kv[1] * kv[1] + kv[2] * kv[2]).sqrt();
        let scale = e.eigenvalues.amax();
        for i in 0..3 {
            let lam = e.eigenvalues[i];
            let g = (-lam).max(0.0).sqrt();
            all = all.max(g);
            let lf: f64 = (0..3)
                .filter(|&j| (e.eigenvalues[j] - lam).abs() <= 1e-9 * scale)
                .map(|j| {
                    let v = e.eigenvectors.column(j);
                    ((v[0] * kv[0] + v[1] * kv[1] + v[2] * kv[2]) / kn).powi(2)
                })
                .sum();
            if lf >= 0.5 {
                long = long.max(g);
            }
        }
    }
    let cut = |g: f64| if g > 1e-6 { g } else { 0.0 };
    (cut(all), cut(long))
}

#[test]
fn study_rows_agree_with_the_closed_form_dynamical_matrix() {
    let sc = Lattice::<3>::sc();
    let s = -0.1;
    let mut pairs = Vec::new();
    for name in ["m4", "wendland-c2"] {
        let k = kernel::by_name(name).unwrap();
        for h in [1.0, 1.2] {
            let row = evaluate_row(k, ("sc", sc), h, s, 8, None, &Default::default()).unwrap();
            assert!(row.skipped.is_none());
            let (all, long) = closed_form_scan(k, &sc, h, s, 8);
            let (got, got_long) = (
                row.max_growth_rate.unwrap(),
                row.pairing_growth_rate.unwrap(),
            );
            assert!(
                (got - all).abs() <= 1e-9 * all.max(1.0),
                "{name} h = {h}: study {got} vs closed form {all}"
            );
            assert!(
                (got_long - long).abs() <= 1e-9 * long.max(1.0),
                "{name} h = {h}: study pairing {got_long} vs closed form {long}"
            );
            assert!(row.max_asymmetry.unwrap() < 1e-10, "{row:?}");
            pairs.push((name, h, long));
        }
    }
    // what the closed form alone says at h = 1.2Δx on sc under pressure σ̄ = −0.1: m4 has a
    // growing longitudinal (pairing) mode, wendland-c2 none
    assert!(pairs[1].2 > 0.01, "{pairs:?}");
    assert_eq!(pairs[3].2, 0.0, "{pairs:?}");
}

/// First-order change of the nearest-neighbour distances in the standing Bloch pattern
/// u_j = ê cos(k·x_j) of the simple-cubic lattice at a wave vector with k_a ∈ {0, π} (X, M, R:
/// every phase cos(k·x_j) is ±1): for the particle at `site`, the neighbours `site + r`
/// (r = ±x̂, ±ŷ, ±ẑ) it approaches, δ|r| = r̂·ê (cos k·(site + r) − cos k·site) < 0.
fn approached_neighbours(k: [f64; 3], e: [f64; 3], site: [i32; 3]) -> Vec<[i32; 3]> {
    let phase = |p: [i32; 3]| {
        (k[0] * f64::from(p[0]) + k[1] * f64::from(p[1]) + k[2] * f64::from(p[2])).cos()
    };
    let mut out = Vec::new();
    for a in 0..3 {
        for sign in [1, -1] {
            let mut r = [0; 3];
            r[a] = sign;
            let nb = [site[0] + r[0], site[1] + r[1], site[2] + r[2]];
            let delta = f64::from(sign) * e[a] * (phase(nb) - phase(site));
            if delta < -1e-12 {
                out.push(r);
            }
        }
    }
    out
}

/// Issue 24 item 6: the pairing study labels the growth at R = (π,π,π) (m4, h = 1.4Δx) and at
/// M = (π,π,0) (m4, h = 1.8Δx) of the simple-cubic lattice as pairing; reproduced with
/// `sphstab pairing --kernels m4 --lattices sc --h-min 1.4 --h-max 1.8 --h-step 0.4
/// --stresses -0.1 --grid 2` (L-frac 1.000 at |κ|Δx/π = 1.7321 and 1.4142), while `sphstab query
/// --dim 3 --lattice sc --material hydro --stress -0.1 --h 1.4 --grid 2` prints the same R mode
/// with "longitudinal fraction 0.333". The label is right; this test says why, from routes
/// independent of the engine (the closed-form D of [`closed_form_d`], the B-spline transform
/// [`bspline_ft3`], the phase pattern):
///
/// 1. The eigenspace is degenerate by symmetry: at R, D = λI (every polarisation, so query's
///    (0, 0, 1) with |ê·k̂|² = 1/3 is one arbitrary member of it), at M, D = diag(λ, λ, λ_z).
///    The study's longitudinal fraction is that of the eigenspace, |P k̂|² = 1 (the largest over
///    it), and it does not depend on the image of k (k and k − G, e.g. (π,π,π) and (−π,π,π),
///    are the same lattice pattern; each one's k̂ lies in the eigenspace).
/// 2. The growth there is the limit of longitudinal modes with a unique k̂: inside the zone at
///    k = (1 − ε)R and (1 − ε)M the eigenvector along k̂ grows at a rate that tends to the
///    eigenspace's as ε → 0. R and M are where the longitudinal branches along [111] (R) and
///    [110], [1−10] (M) meet their transverse partners, so the largest longitudinal growth over
///    the zone is at least the R or M rate whatever label R and M get; the study counts them for
///    both, as documented.
/// 3. It is the pairing mechanism: its sign is that of the kernel's 3D transform at |k|
///    (Dehnen & Aly's criterion, W* < 0 under pressure), as for the X point's longitudinal mode:
///    m4 at R grows for h = 1.2 and 1.4 (W*(√3π h) < 0) and not at 1.8, at M (x, y) grows for
///    h = 1.8 only (W*(√2π h) < 0); Wendland C2 (W* > 0, Wendland 1995) never grows there. The
///    transverse modes whose growth is a lattice effect (ẑ at M, ŷ at X) grow against the sign
///    of W* (m4 h = 1.2 at M: W* > 0, ẑ grows) and change no neighbour distance.
/// 4. The eigenspace holds a mode that pairs neighbours: ê = x̂ moves every particle head-on
///    towards exactly one nearest neighbour, which moves towards it (the x-chains dimerise, the
///    1D κΔx = π pattern), at R and M as at X. Its longitudinal member along [111] at R moves
///    each particle towards three neighbours at once — that member alone would not be pairing,
///    but it is not the whole eigenspace.
#[test]
fn pairing_at_the_symmetric_points_r_and_m_of_sc() {
    use nalgebra::Vector3;
    let sc = Lattice::<3>::sc();
    let s = -0.1;
    let (xp, mp, rp) = ([PI, 0.0, 0.0], [PI, PI, 0.0], [PI, PI, PI]);
    let (ex, ey, ez) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    // the growth of polarisation e at k, checking that e is an eigenvector of the closed form
    let growth = |name: &str, h: f64, k: [f64; 3], e: [f64; 3]| -> (f64, f64) {
        let d = closed_form_d(kernel::by_name(name).unwrap(), &sc, h, s, k);
        let v = Vector3::from(e).normalize();
        let lam = v.dot(&(d * v));
        assert!(
            (d * v - v * lam).norm() <= 1e-12 * d.norm(),
            "{name} h = {h}: {e:?} is not an eigenvector at {k:?}"
        );
        (lam, (-lam).max(0.0).sqrt())
    };
    let grows = |g: f64| g > 1e-6;

    // 1. degeneracy: R isotropic, M (x, y) degenerate
    for h in [1.2, 1.4, 1.8] {
        let r: Vec<f64> = [ex, ey, ez, [1.0, 1.0, 1.0], [1.0, -2.0, 0.5]]
            .iter()
            .map(|&e| growth("m4", h, rp, e).0)
            .collect();
        assert!(
            r.iter().all(|l| (l - r[0]).abs() <= 1e-12 * r[0].abs()),
            "R, h = {h}: {r:?}"
        );
        let (mx, my, mxy) = (
            growth("m4", h, mp, ex).0,
            growth("m4", h, mp, ey).0,
            growth("m4", h, mp, [1.0, 1.0, 0.0]).0,
        );
        assert!((mx - my).abs() <= 1e-12 * mx.abs() && (mx - mxy).abs() <= 1e-12 * mx.abs());
    }

    // 3. the sign follows W*(|k|h) of the closed-form m4 transform
    let w4 = |k: f64, h: f64| bspline_ft3(4, k * h);
    let (kr, km) = (3f64.sqrt() * PI, 2f64.sqrt() * PI);
    for h in [1.2, 1.4, 1.8] {
        let (gr, gm) = (growth("m4", h, rp, ex).1, growth("m4", h, mp, ex).1);
        eprintln!(
            "m4 h = {h}: R growth {gr:.6} (W*(√3π h) = {:+.3e}), M (x, y) growth {gm:.6} (W*(√2π h) = {:+.3e})",
            w4(kr, h),
            w4(km, h)
        );
        assert_eq!(grows(gr), w4(kr, h) < 0.0, "R, h = {h}");
        assert_eq!(grows(gm), w4(km, h) < 0.0, "M, h = {h}");
    }
    assert!(grows(growth("m4", 1.2, mp, ez).1) && w4(km, 1.2) > 0.0);
    for h in [0.8, 1.2, 1.6, 2.0] {
        assert!(
            !grows(growth("wendland-c2", h, rp, ex).1),
            "wendland-c2 R, h = {h}"
        );
        assert!(
            !grows(growth("wendland-c2", h, mp, ex).1),
            "wendland-c2 M, h = {h}"
        );
    }

    // 4. x̂ pairs nearest neighbours at X, M and R; [111] at R, ẑ at M and ŷ at X do not
    for k in [xp, mp, rp] {
        assert_eq!(
            approached_neighbours(k, ex, [0, 0, 0]),
            vec![[1, 0, 0]],
            "{k:?}"
        );
        assert_eq!(
            approached_neighbours(k, ex, [1, 0, 0]),
            vec![[-1, 0, 0]],
            "{k:?}"
        );
    }
    assert_eq!(
        approached_neighbours(rp, [1.0, 1.0, 1.0], [0, 0, 0]).len(),
        3
    );
    assert!(approached_neighbours(mp, ez, [0, 0, 0]).is_empty());
    assert!(approached_neighbours(xp, ey, [0, 0, 0]).is_empty());

    // 2. continuity: inside the zone along [111] and [110] the longitudinal eigenvector's
    // growth tends to the R and M rate (linearly in ε)
    for (h, p) in [(1.4, rp), (1.8, mp)] {
        let g0 = growth("m4", h, p, ex).1;
        let mut gaps = Vec::new();
        for eps in [1e-3, 1e-4] {
            let k = p.map(|c| (1.0 - eps) * c);
            let kn = (k[0] * k[0] + k[1] * k[1] + k[2] * k[2]).sqrt();
            let e = nalgebra::SymmetricEigen::new(closed_form_d(
                kernel::by_name("m4").unwrap(),
                &sc,
                h,
                s,
                k,
            ));
            let (lf, lam) = (0..3)
                .map(|i| {
                    let v = e.eigenvectors.column(i);
                    (
                        ((v[0] * k[0] + v[1] * k[1] + v[2] * k[2]) / kn).powi(2),
                        e.eigenvalues[i],
                    )
                })
                .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
            assert!(
                lf > 1.0 - 1e-9,
                "h = {h}, ε = {eps}: no mode along k̂ ({lf})"
            );
            let gl = (-lam).max(0.0).sqrt();
            gaps.push((gl - g0).abs());
            eprintln!("h = {h}, k = (1 − {eps:e})·{p:?}: longitudinal growth {gl:.6} vs {g0:.6}");
        }
        assert!(
            gaps[1] < 1e-4 * g0 && gaps[1] < 0.2 * gaps[0],
            "h = {h}: {gaps:?}"
        );
    }

    // the study on the grid 2³, which samples X, M and R only: pairing is the growth of the
    // x̂ mode (the neighbour-pairing one) at the fastest of them; the degenerate eigenspaces
    // (R; M's (x, y)) count as transverse too, next to ŷ at X and ẑ at M
    for (h, at) in [(1.2, rp), (1.4, rp), (1.8, mp)] {
        let row = evaluate_row(
            kernel::by_name("m4").unwrap(),
            ("sc", sc),
            h,
            s,
            2,
            None,
            &Default::default(),
        )
        .unwrap();
        let pairing = [xp, mp, rp].map(|k| growth("m4", h, k, ex).1);
        let transverse = [
            growth("m4", h, xp, ey).1,
            growth("m4", h, mp, ez).1,
            growth("m4", h, mp, ex).1,
            growth("m4", h, rp, ex).1,
        ];
        let want = pairing.iter().copied().fold(0.0, f64::max);
        let want_t = transverse.iter().copied().fold(0.0, f64::max);
        let got = row.pairing_growth_rate.unwrap();
        assert!(
            (got - want).abs() <= 1e-9 * want,
            "h = {h}: pairing {got} vs {want}"
        );
        let got_t = row.transverse_growth_rate.unwrap();
        assert!(
            (got_t - want_t).abs() <= 1e-9 * want_t,
            "h = {h}: transverse {got_t} vs {want_t}"
        );
        let pk = row.pairing_kappa.unwrap();
        let count = |k: [f64; 3]| k.iter().filter(|c| (c.abs() - PI).abs() < 1e-12).count();
        assert_eq!(count(pk), count(at), "h = {h}: pairing at {pk:?}");
    }
}

#[test]
fn neighbour_numbers_count_the_shells_of_the_lattice() {
    // sc shells: 1 + 6 (r = 1) + 12 (√2) + 8 (√3) + 6 (2) + 24 (√5) = 57 inside r < 2.4
    let sc = Lattice::<3>::sc();
    assert_eq!(neighbour_count(&sc, 1.0), 1);
    assert_eq!(neighbour_count(&sc, 1.5), 19);
    assert_eq!(neighbour_count(&sc, 2.4), 57);
    // bcc with unit volume per particle: 8 neighbours at (√3/2)·2^⅓ = 1.0911, 6 at 2^⅓ = 1.2599
    let bcc = Lattice::<3>::bcc();
    assert_eq!(neighbour_count(&bcc, 1.2), 9);
    assert_eq!(neighbour_count(&bcc, 1.3), 15);
    // fcc: 12 neighbours at 4^⅓/√2 = 1.1225
    assert_eq!(neighbour_count(&Lattice::<3>::fcc(), 1.2), 13);
}

const SMALL: [&str; 13] = [
    "pairing",
    "--kernels",
    "m4,wendland-c2",
    "--lattices",
    "sc",
    "--h-min",
    "1.2",
    "--h-max",
    "1.6",
    "--h-step",
    "0.4",
    "--grid",
    "8",
];

#[test]
fn cli_json_has_the_rows_the_criterion_and_the_onsets() {
    let mut args = SMALL.to_vec();
    args.extend(["--stresses", "-0.1", "--json"]);
    let v = json(&args);
    assert_eq!(v["form"], "classical");
    assert_eq!(v["material"], "hydro");
    assert_eq!(v["grid"], 8);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4);
    for r in rows {
        for f in [
            "kernel",
            "lattice",
            "h_over_dx",
            "support_over_dx",
            "n_h",
            "n_h_continuum",
            "stress",
            "skipped",
            "max_growth_rate",
            "kappa_at_max",
            "kappa_abs_over_pi",
            "longitudinal_fraction",
            "pairing_growth_rate",
            "pairing_kappa",
            "transverse_growth_rate",
            "transverse_kappa",
            "max_asymmetry",
            "wstar_first_negative_kdx",
        ] {
            assert!(r.get(f).is_some(), "row lacks {f}: {r}");
        }
        assert_eq!(r["lattice"], "sc");
        assert!(r["max_growth_rate"].as_f64().unwrap() >= 0.0);
        if r["max_growth_rate"].as_f64().unwrap() > 0.0 {
            assert_eq!(r["kappa_at_max"].as_array().unwrap().len(), 3);
        }
    }
    // R = 2.4Δx on sc: 57 particles (shell count above)
    assert_eq!(rows[0]["n_h"], 57);
    let kernels = v["kernels"].as_array().unwrap();
    assert_eq!(kernels.len(), 2);
    assert_eq!(kernels[0]["kernel"], "m4");
    assert_eq!(kernels[0]["negative"], true);
    assert_eq!(kernels[1]["negative"], false);
    // m4's W* turns negative at k = 2π/h: κΔx = 2π/1.2 at h = 1.2Δx
    let kdx = rows[0]["wstar_first_negative_kdx"].as_f64().unwrap();
    assert!((kdx - 2.0 * PI / 1.2).abs() < 1e-3, "{kdx}");
    assert!(rows[2]["wstar_first_negative_kdx"].is_null());
    assert_eq!(v["onsets"].as_array().unwrap().len(), 2);
}

#[test]
fn cli_table_and_plot() {
    let dir = std::env::temp_dir().join(format!("sphstab-pairing-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("p.svg");
    let mut args = SMALL.to_vec();
    let s = svg.to_str().unwrap();
    args.extend(["--stresses", "-0.1", "--plot", s]);
    let (code, out, err) = sphstab(&args);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("pairing study") && out.contains("onsets"),
        "{out}"
    );
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cli_bad_input_is_one_line_exit_2() {
    assert_bad_inputs(&[
        (&["pairing", "--h-min", "0"], "--h-min"),
        (&["pairing", "--h-min", "nan"], "--h-min"),
        (&["pairing", "--h-min", "2", "--h-max", "1"], "--h-max"),
        (&["pairing", "--h-max", "11"], "--h-max"),
        (&["pairing", "--h-step", "0"], "--h-step"),
        (&["pairing", "--h-step", "0.001"], "--h-step"),
        (&["pairing", "--stresses", "1"], "--stresses"),
        (&["pairing", "--stresses", "-0.1,inf"], "--stresses"),
        (&["pairing", "--grid", "1"], "--grid"),
        (&["pairing", "--grid", "129"], "--grid"),
        (&["pairing", "--kernels", "m7"], "kernel"),
        (&["pairing", "--kernels", "m4,m4"], "--kernels"),
        (&["pairing", "--lattices", "hex"], "--lattices"),
        (
            &[
                "pairing",
                "--config",
                "analysis/pairing3d.json",
                "--grid",
                "8",
            ],
            "--grid",
        ),
        (&["pairing", "--from", "figures/pairing3d.json"], "--plot"),
        (&["pairing", "--config", "/nonexistent.json"], "--config"),
    ]);
}

#[test]
fn config_rejects_unknown_fields_by_name() {
    let e = parse_config("x.json", r#"{"kernels": ["m4"], "hh": 1}"#).unwrap_err();
    assert!(e.to_string().contains("hh") && e.to_string().contains("x.json"));
    let e = parse_config("x.json", r#"{"output": "../a.svg"}"#).unwrap_err();
    assert!(e.to_string().contains("output"));
}

#[test]
fn committed_figure_is_drawn_from_its_stored_data() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let name = "analysis/pairing3d.json";
    let cfg = parse_config(name, &std::fs::read_to_string(root.join(name)).unwrap()).unwrap();
    assert!(!cfg.note.is_empty(), "{name}: every figure needs a note");
    let out = cfg.output.clone().unwrap();
    let data = root.join("figures").join(&out).with_extension("json");
    let rep: PairingReport =
        serde_json::from_str(&std::fs::read_to_string(&data).unwrap()).unwrap();
    // the stored study covers exactly the configured grid
    let p = plan(&cfg).unwrap();
    assert_eq!(rep.rows.len(), p.rows());
    assert_eq!(rep.grid, cfg.grid);
    assert_eq!(rep.h_values, p.h);
    assert_eq!(rep.stresses, cfg.stresses);
    let mut i = 0;
    for k in &p.kernels {
        for (l, _) in &p.lattices {
            for h in &p.h {
                for s in &p.stresses {
                    let r = &rep.rows[i];
                    assert_eq!((r.kernel.as_str(), r.lattice.as_str()), (k.name(), *l));
                    assert_eq!((r.h_over_dx, r.stress), (*h, *s));
                    i += 1;
                }
            }
        }
    }
    let svg = figure_svg(&rep).unwrap();
    let committed = std::fs::read_to_string(root.join("figures").join(&out)).unwrap();
    assert!(
        svg == committed,
        "figures/{out} differs from its data: run `cargo run --release -- pairing --from figures/pairing3d.json --plot figures/{out}`"
    );
}
