//! 2D solver against the engine: box-size convergence of the Swegle growth rate and single-mode
//! runs on a periodic box.

use sphstab::forms::{FormKind, Material, Model, ModelParams, ObjectiveRate};
use sphstab::kernel;
use sphstab::lattice::Lattice;
use sphstab::shape::KernelParams;
use sphstab::shape::ShapeFamily;
use sphstab::solver::{BoundaryDensity, Run};
use sphstab::studies::swegle::{SwegleConfig, run_swegle};
use sphstab::vonneumann::linearise::{Bloch, base_state};
use std::f64::consts::PI;

/// Classical m4, h = 1.2, f = 0.99: measured growth over the infinite-lattice rate rises with
/// the box size, 21 → 41 → 81 (the 21×21 box cannot hold the fastest wave number).
#[test]
fn swegle_growth_converges_with_box_size() {
    let k = kernel::by_name("m4").unwrap();
    let mut prev = 0.0;
    let mut last = 0.0;
    for size in [21, 41, 81] {
        let mut cfg = SwegleConfig::new(FormKind::Classical, k, 1.2, 0.99);
        cfg.size = size;
        let r = run_swegle(&cfg, |_| {}).unwrap();
        let ri = r.ratio_infinite.unwrap();
        eprintln!(
            "{size}×{size}: measured {:.5}, box ({}) {:.5}, infinite {:.5}, measured/box {:.4}, measured/infinite {:.4}, {:.1} s",
            r.measured_growth_rate.unwrap(),
            r.box_method,
            r.predicted_growth_rate_box,
            r.predicted_growth_rate_infinite,
            r.ratio_box.unwrap(),
            ri,
            r.runtime_s
        );
        assert!(
            ri > prev,
            "measured/infinite must increase with the box: {ri} after {prev}"
        );
        assert!(r.ratio_box.unwrap() <= 1.0);
        prev = ri;
        last = ri;
    }
    assert!(last > 0.9);
}

/// Runs a periodic n × n square box seeded with velocity amp·ê·cos(k·x) (ê the engine's
/// polarisation of the branch) and returns the history of the displacement projected on the mode.
fn periodic_mode(
    p: ModelParams,
    sb: f64,
    n: usize,
    m: [usize; 2],
    branch: usize,
    dt: f64,
    steps: usize,
) -> (Vec<f64>, f64) {
    let lat = Lattice::<2>::square(1.0).unwrap();
    let (rho, s0) = base_state(&p.material, p.rho0, sb).unwrap();
    let model = Model::<2>::periodic_patch(p, &lat, 1.0, [n, n], rho, s0).unwrap();
    let k = [
        2.0 * PI * m[0] as f64 / n as f64,
        2.0 * PI * m[1] as f64 / n as f64,
    ];
    let lin = Bloch::<2>::new(p, &lat, 1.0, sb).unwrap();
    let (w2, pol) = lin.branches(k)[branch];
    let e = [pol[0].re, pol[1].re];
    let ne = e[0].hypot(e[1]);
    let e = [e[0] / ne, e[1] / ne];
    let mut z = model.rest_state(rho);
    let x0 = z.x.clone();
    for (v, x) in z.v.iter_mut().zip(&x0) {
        let c = (k[0] * x[0] + k[1] * x[1]).cos();
        *v = [1e-7 * e[0] * c, 1e-7 * e[1] * c];
    }
    let fixed = vec![false; z.x.len()];
    let mut run = Run::<2>::new(model, z, fixed, BoundaryDensity::Evolve).unwrap();
    let proj = |zx: &[[f64; 2]]| -> f64 {
        let (mut s, mut nrm) = (0.0, 0.0);
        for (x, r) in zx.iter().zip(&x0) {
            let c = (k[0] * r[0] + k[1] * r[1]).cos();
            s += ((x[0] - r[0]) * e[0] + (x[1] - r[1]) * e[1]) * c;
            nrm += c * c;
        }
        s / nrm
    };
    let mut h = vec![proj(&run.z.x)];
    for _ in 0..steps {
        run.step(dt).unwrap();
        h.push(proj(&run.z.x));
    }
    (h, w2.re)
}

fn params(form: FormKind, shape: ShapeFamily, material: Material) -> ModelParams {
    ModelParams {
        form,
        shape,
        kp: KernelParams {
            kernel: kernel::by_name("m4").unwrap(),
            h: 1.2,
        },
        material,
        rho0: 1.0,
        c_partition: 0.5,
        av: None,
        art_stress: None,
        diffusion: None,
        alpha_s: 0.0,
        ls_length: 1.0,
        hourglass: None,
    }
}

/// Stable forms on a periodic 16×16 box: the seeded mode's period equals the engine's
/// (through the leapfrog relation cos ω_dΔt = 1 − ω²Δt²/2) to 1%.
#[test]
fn periodic_box_single_mode_frequency() {
    let elastic = Material::elastic(1.0, 0.3, ObjectiveRate::Jaumann).unwrap();
    for (form, shape, mat, sb, m, branch) in [
        (
            FormKind::Nonlocal,
            ShapeFamily::Sph,
            Material::Hydro { bulk: 1.0 },
            0.05,
            [3, 0],
            1,
        ),
        (
            FormKind::Classical,
            ShapeFamily::Sph,
            elastic,
            -0.05,
            [2, 3],
            0,
        ),
        (
            FormKind::TotalLagrangian,
            ShapeFamily::Sph,
            elastic,
            0.1,
            [4, 1],
            1,
        ),
        (FormKind::Lnl, ShapeFamily::Sph, elastic, 0.1, [3, 3], 1),
    ] {
        let dt = 0.05;
        let p = params(form, shape, mat);
        let (_, w2) = periodic_mode(p, sb, 16, m, branch, dt, 1);
        assert!(w2 > 0.0, "{form:?}: branch {branch} not oscillatory ({w2})");
        let wd = (1.0 - 0.5 * w2 * dt * dt).acos() / dt;
        let period = 2.0 * PI / wd;
        let (h, _) = periodic_mode(p, sb, 16, m, branch, dt, (4.0 * period / dt) as usize);
        let mut cross = Vec::new();
        for i in 1..h.len() {
            if (h[i - 1] > 0.0 && h[i] <= 0.0) || (h[i - 1] < 0.0 && h[i] >= 0.0) {
                cross.push((i - 1) as f64 + h[i - 1] / (h[i - 1] - h[i]));
            }
        }
        assert!(cross.len() >= 6, "{form:?}: {} crossings", cross.len());
        let measured = 2.0 * (cross[cross.len() - 1] - cross[0]) / (cross.len() - 1) as f64 * dt;
        let err = (measured / period - 1.0).abs();
        eprintln!(
            "2D periodic {form:?} σ̄={sb} m={m:?}: period measured {measured:.5}, engine {period:.5} (error {err:.2e})"
        );
        assert!(err < 0.01);
    }
}

/// Classical SPH in tension on a periodic box: the seeded zone-edge longitudinal mode grows at
/// the engine's rate (leapfrog-discrete) to 1%.
#[test]
fn periodic_box_single_mode_growth() {
    let p = params(
        FormKind::Classical,
        ShapeFamily::Sph,
        Material::Hydro { bulk: 1.0 },
    );
    // k = (π, 0), the fastest wave vector of the Swegle lattice (longitudinal)
    let (sb, n, m, dt) = (0.05, 16, [8, 0], 0.05);
    let (_, w2) = periodic_mode(p, sb, n, m, 0, dt, 1);
    assert!(w2 < 0.0);
    let g = (-w2).sqrt();
    let b = 1.0 + 0.5 * g * g * dt * dt;
    let gd = (b + (b * b - 1.0).sqrt()).ln() / dt;
    // e^8 ≈ 3000: the amplitude stays ~1e-3 Δx, well inside the linear range
    let steps = (8.0 / g / dt) as usize;
    let (h, _) = periodic_mode(p, sb, n, m, 0, dt, steps);
    let (i1, i2) = (steps / 2, steps);
    let measured = (h[i2].abs() / h[i1].abs()).ln() / ((i2 - i1) as f64 * dt);
    eprintln!(
        "2D periodic classical hydro σ̄={sb} k=({}/16)2π: growth measured {measured:.6}, engine {gd:.6}",
        m[0]
    );
    assert!((measured / gd - 1.0).abs() < 0.01, "{measured} vs {gd}");
}

/// The growing pattern of the Swegle box (rustfft sine transform of the free particles'
/// velocity at the top of the fit window) is the engine's fastest admitted standing mode: its
/// large component equals the prediction's (15π/16 in a 15×15 free region) and the small one is
/// within one mode index (nearly degenerate rates), up to the x ↔ y symmetry of the box.
#[test]
fn swegle_growing_pattern_is_the_predicted_standing_mode() {
    let k = kernel::by_name("m4").unwrap();
    let d = PI / 16.0;
    for h in [1.0, 1.2, 1.3] {
        for f in [0.95, 0.99] {
            let r = run_swegle(&SwegleConfig::new(FormKind::Classical, k, h, f), |_| {}).unwrap();
            let (m, share) = r.dominant_kappa.unwrap();
            let p = r.predicted_kappa_box;
            let (m_hi, m_lo) = (m[0].max(m[1]), m[0].min(m[1]));
            let (p_hi, p_lo) = (p[0].max(p[1]), p[0].min(p[1]));
            eprintln!(
                "h={h} f={f}: dominant ({:.4}π, {:.4}π) share {share:.2}; predicted ({:.4}π, {:.4}π)",
                m[0] / PI,
                m[1] / PI,
                p[0] / PI,
                p[1] / PI
            );
            assert!((m_hi - p_hi).abs() < 1e-12, "large component");
            assert!((m_lo - p_lo).abs() < 1.5 * d, "small component");
        }
    }
}
