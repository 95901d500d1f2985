//! δ-SPH density diffusion (issue 12 item 3): the Molteni–Colagrossi and Antuono terms in the
//! rate functions, hence in the linearisation and the solver.
//!
//! Expected values are closed forms derived by hand (below), evaluated from the kernel's W'
//! directly, never through the engine: in the 1D nonlocal form at rest the density does not feed
//! back into the accelerations (a_I ∝ Σ_J (σ_J − σ_I)∇φ_J vanishes at uniform stress for any ρ),
//! so the Jacobian is block-triangular and one of its eigenvalues is the diffusion symbol itself.
//! With Δx = 1, V_J = 1, c = 1 and g_j = ∇_I W at x_JI = j, i.e. g_j = −W'(|j|) sign j:
//!
//! ```text
//! molteni-colagrossi:  s_MC(κ) = −δ h Σ_{j≠0} 4 sin²(κj/2) (−W'(|j|))/|j|
//! antuono:             s_A(κ)  = s_MC(κ) + δ h S²/M,  S = Σ_j sin(κj) g_j,  M = Σ_j j g_j
//! ```
//!
//! (Antuono: ⟨∇ρ⟩_I = e^{iκI} iS/M for the mode ρ_J = e^{iκJ}, and −Σ_J (⟨∇ρ⟩_I + ⟨∇ρ⟩_J)·g_J
//! = −(iS/M)(iS) = S²/M, using Σ g_j = 0 and Σ e^{iκj} g_j = iS.) As κ → 0 both sums are
//! κ²M + O(κ⁴): MC damps long waves at O(κ²), Antuono at O(κ⁴); at κ = π, S = 0 and they agree.

use crate::common;

use num_complex::Complex64 as C;
use sphstab::forms::{DensityDiffusion, DiffusionForm, FormKind, Model};
use sphstab::kernel;
use sphstab::shape::ShapeFamily;
use sphstab::solver::Run;
use sphstab::vonneumann::linearise::{Lattice1D, Linearisation};
use std::f64::consts::PI;

fn symbol(kern: &str, h: f64, delta: f64, form: DiffusionForm, kappa: f64) -> f64 {
    let k = kernel::by_name(kern).unwrap();
    let reach = (k.zeta() * h).ceil() as i64 + 1;
    let (mut mc, mut s, mut m) = (0.0, 0.0, 0.0);
    for j in (-reach..=reach).filter(|&j| j != 0) {
        let r = j.abs() as f64;
        let dw: f64 = kernel::dw(k, 1, r, h);
        let g = -dw * (j.signum() as f64);
        mc -= 4.0 * (kappa * j as f64 / 2.0).sin().powi(2) * (-dw) / r;
        s += (kappa * j as f64).sin() * g;
        m += j as f64 * g;
    }
    delta
        * h
        * match form {
            DiffusionForm::MolteniColagrossi => mc,
            DiffusionForm::Antuono => mc + s * s / m,
        }
}

fn params(kern: &str, h: f64, delta: f64, form: DiffusionForm) -> sphstab::forms::ModelParams {
    let mut p = common::params(FormKind::Nonlocal, kern, ShapeFamily::Sph, h);
    p.diffusion = Some(DensityDiffusion {
        delta,
        form,
        sound_speed: 1.0,
    });
    p
}

/// The engine's eigenvalues contain the diffusion symbol, for both forms, four kernels, three
/// h and κ over (0, π], to 1e-12 of the largest |s|, on lattices of Δx = 1e-6, 1 and 1e6
/// (normalised results do not depend on Δx).
///
/// Skipped: the gaussian at h = Δx and 2Δx off the unit lattice. Its support R = 3h then lands
/// exactly on a neighbour, and the truncated gaussian jumps there (W(3h) = e⁻⁹/√π h). Whether that
/// neighbour counts depends on the rounding of x_J − x_I, and at Δx = 1e-6 it counts on one side
/// only, so J is off by ~1e-3. This is a limit of discontinuous kernels at r = R; it is left
/// open and named in the issue-12 note.
#[test]
fn engine_eigenvalue_is_the_diffusion_symbol() {
    let mut worst: f64 = 0.0;
    for form in [DiffusionForm::MolteniColagrossi, DiffusionForm::Antuono] {
        for kern in ["m4", "wendland-c2", "gaussian", "m6"] {
            for h in [1.0, 1.3, 2.0] {
                for dx in [1e-6, 1.0, 1e6] {
                    if kern == "gaussian" && (3.0f64 * h).fract() == 0.0 && dx != 1.0 {
                        continue;
                    }
                    let lat = Lattice1D {
                        dx,
                        ..Lattice1D::default()
                    };
                    let mut p = params(kern, h, 0.1, form);
                    p.kp.h = h * dx;
                    p.ls_length = dx;
                    // physical c of the lattice (√(C/ρ0)), as the analysis sets it
                    p.diffusion.as_mut().unwrap().sound_speed = (lat.modulus / lat.rho0).sqrt();
                    p.material = sphstab::forms::Material::bar(lat.modulus);
                    p.rho0 = lat.rho0;
                    let lin = Linearisation::new(p, 0.01 * lat.modulus, lat).unwrap();
                    for i in 1..=16 {
                        let kap = PI * i as f64 / 16.0;
                        let want = symbol(kern, h, 0.1, form, kap);
                        let ev = lin.eigenvalues(kap).unwrap();
                        let scale = ev.iter().map(|z| z.norm()).fold(want.abs(), f64::max);
                        let d = ev
                            .iter()
                            .map(|z| (z - C::new(want, 0.0)).norm())
                            .fold(f64::INFINITY, f64::min)
                            / scale;
                        let tol = 1e-12;
                        assert!(
                            d < tol,
                            "{form:?} {kern} h {h} Δx {dx} κ {kap}: {want} not among {ev:?}"
                        );
                        worst = worst.max(d);
                    }
                }
            }
        }
    }
    eprintln!("δ-SPH symbol vs engine eigenvalue: worst {worst:.1e} of the largest |s|");
}

/// The two forms: equal at κ = π (the gradient estimate of a sawtooth vanishes); as κ → 0 the
/// damping scales as κ² (MC) and κ⁴ (Antuono): halving κ divides it by 4 and 16 (to 1%).
#[test]
fn antuono_damps_long_waves_at_fourth_order() {
    let (mc, an) = (DiffusionForm::MolteniColagrossi, DiffusionForm::Antuono);
    let a = symbol("m4", 1.3, 0.1, mc, PI);
    let b = symbol("m4", 1.3, 0.1, an, PI);
    assert!((a / b - 1.0).abs() < 1e-14, "{a} vs {b}");
    let lin =
        |f| Linearisation::new(params("m4", 1.3, 0.1, f), 0.01, Lattice1D::default()).unwrap();
    let damping = |l: &Linearisation, kap: f64| {
        -l.eigenvalues(kap)
            .unwrap()
            .iter()
            .map(|z| z.re)
            .fold(f64::INFINITY, f64::min)
    };
    for (f, order) in [(mc, 2), (an, 4)] {
        let l = lin(f);
        let ratio = damping(&l, 0.02) / damping(&l, 0.01);
        let want = 2f64.powi(order);
        eprintln!("{f:?}: damping(0.02)/damping(0.01) = {ratio:.6} (κ^{order}: {want})");
        assert!((ratio / want - 1.0).abs() < 0.01, "{f:?}: {ratio}");
    }
}

/// The solver: a 1D periodic chain at rest with a density wave of mode m (amplitude 1e-8)
/// stepped by `kdk` (qⁿ⁺¹ = qⁿ + Δt r(qⁿ) for this decoupled mode): the density's Fourier
/// amplitude decays per step by 1 + Δt s(κ) of the closed-form symbol, to 1e-6.
#[test]
fn solver_density_wave_decays_at_the_symbol_rate() {
    for form in [DiffusionForm::MolteniColagrossi, DiffusionForm::Antuono] {
        let (n, m, dt, delta) = (64usize, 11usize, 0.3, 0.1);
        let p = params("m4", 1.3, delta, form);
        let model = Model::new(
            p,
            (0..n).map(|i| [i as f64]).collect(),
            vec![1.0; n],
            1.0,
            0.01,
            Some([[n as f64]]),
        )
        .unwrap();
        let mut z = model.rest_state(1.0);
        let q0 = z.rho.clone();
        let kap = 2.0 * PI * m as f64 / n as f64;
        for (j, r) in z.rho.iter_mut().enumerate() {
            *r += 1e-8 * (kap * j as f64).cos();
        }
        let amp = |q: &[f64]| -> f64 {
            (0..n)
                .map(|j| C::from_polar(q[j] - q0[j], -kap * j as f64))
                .sum::<C>()
                .norm()
        };
        let a0 = amp(&z.rho);
        let mut run = Run::with_prescribed(model, z, &vec![None; n]).unwrap();
        let steps = 20;
        for _ in 0..steps {
            run.step(dt).unwrap();
        }
        let meas = (amp(&run.z.rho) / a0).powf(1.0 / steps as f64);
        let want = 1.0 + dt * symbol("m4", 1.3, delta, form, kap);
        eprintln!("{form:?}: decay per step measured {meas:.12}, predicted {want:.12}");
        assert!(
            (meas / want - 1.0).abs() < 1e-6,
            "{form:?}: {meas} vs {want}"
        );
        assert!(
            run.z.v.iter().all(|[vi]| vi.abs() < 1e-14),
            "the density wave moved particles"
        );
    }
}

/// The CLI: `--delta`/`--delta-form` in `timestep`, `query`, `dispersion` (1D, 2D hydro) and
/// `swegle`; δ-SPH lowers kdk's critical Δt of a 2D hydro lattice below the inviscid 2/ω_max;
/// bad input is one line, exit 2, naming the flag (also `--av-alpha` with a 1D form whose rate
/// has no viscosity term). The 2D time steps on a 16² zone grid, not the default 64²: Δt_crit
/// and ω_max come from the same grid, so the comparison holds on any grid (16× cheaper).
#[test]
fn cli_delta() {
    for form in ["molteni-colagrossi", "antuono"] {
        let (code, out, err) = common::sphstab(&[
            "timestep",
            "--dim",
            "2",
            "--grid",
            "16",
            "--material",
            "hydro",
            "--form",
            "nonlocal",
            "--delta",
            "0.1",
            "--delta-form",
            form,
            "--json",
        ]);
        assert_eq!(code, 0, "{err}");
        let j: serde_json::Value = serde_json::from_str(&out).unwrap();
        let dt = j["critical_dt"].as_f64().unwrap();
        let wmax = j["omega_max"].as_f64().unwrap();
        assert!(
            dt > 0.0 && dt < 2.0 / wmax,
            "{form}: {dt} vs 2/ω_max = {}",
            2.0 / wmax
        );
    }
    // the damping curve of a fluid: the transverse branch (ω = 0) has none (null), the
    // longitudinal one is damped (the zero-frequency branch must not block the matching)
    let (code, out, err) = common::sphstab(&[
        "dispersion",
        "--dim",
        "2",
        "--material",
        "hydro",
        "--form",
        "nonlocal",
        "--h",
        "1.3",
        "--stress",
        "0",
        "--delta",
        "0.1",
        "--points",
        "4",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    let d = j["damping_rate"].as_array().unwrap();
    assert!(d.iter().all(|p| p[0].is_null()), "{out}");
    let damped: Vec<f64> = d.iter().filter_map(|p| p[1].as_f64()).collect();
    assert!(
        damped.len() >= 4 && damped.iter().all(|&r| r < 0.0),
        "{out}"
    );
    for args in [
        &["query", "--form", "classical", "--delta", "0.1"][..],
        &[
            "dispersion",
            "--form",
            "nonlocal",
            "--delta",
            "0.1",
            "--points",
            "8",
        ][..],
        &[
            "swegle", "--form", "nonlocal", "--delta", "0.1", "--t-end", "1",
        ][..],
    ] {
        let (code, _, err) = common::sphstab(args);
        assert_eq!(code, 0, "{args:?}: {err}");
    }
    for (args, flag) in [
        (&["timestep", "--delta", "-0.1"][..], "--delta"),
        (&["timestep", "--delta", "nan"][..], "--delta"),
        (
            &["query", "--delta", "0.1", "--delta-form", "nosuch"][..],
            "density-diffusion form",
        ),
        (&["query", "--delta-form", "antuono"][..], "--delta-form"),
        (
            &["query", "--form", "total-lagrangian", "--delta", "0.1"][..],
            "--delta",
        ),
        (
            &["query", "--form", "least-squares", "--delta", "0.1"][..],
            "--delta",
        ),
        (&["swegle", "--delta", "-1"][..], "--delta"),
        // the 1D [B00]-only forms have no viscosity term: they refuse it rather than ignore it
        (
            &["query", "--form", "least-squares", "--av-alpha", "1"][..],
            "--av-alpha",
        ),
    ] {
        let (code, _, err) = common::sphstab(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(flag), "{args:?}: {err}");
    }
}

/// 2D fluid (hydro, square lattice): with density diffusion the acoustic pair solves
/// s² + ν k² s + c²k² = 0 to leading order in k, so Re s = −ν k²/2. For Molteni–Colagrossi,
/// expanding ρ_J − ρ_I = x_JI·∇ρ + ½ x_JI x_JI : ∇∇ρ in D_I gives
/// ν = δ h c S_xx, S_xx = Σ_J x_J,x² (−W'(r_J))/r_J (V_J = 1) for k along x (lattice sum by hand
/// below, from the 2D kernel's W'). At kΔx = 0.01 the engine's damping equals −ν k²/2 to 1e-3
/// (the next order is O(k²) relative); Antuono's correction removes the k² term (its damping is
/// below 1e-3 of Molteni–Colagrossi's there), and at X = (π, 0) the two are equal.
#[test]
fn fluid_acoustic_damping_matches_the_diffusivity() {
    use sphstab::analysis::{MaterialSpec, Query};
    let (h, delta) = (1.3, 0.1);
    let k = kernel::by_name("m4").unwrap();
    let reach = (k.zeta() * h).ceil() as i64 + 1;
    let mut sxx = 0.0;
    for a in -reach..=reach {
        for b in -reach..=reach {
            let r = ((a * a + b * b) as f64).sqrt();
            if r > 0.0 {
                let dw: f64 = kernel::dw(k, 2, r, h);
                sxx += (a * a) as f64 * (-dw) / r;
            }
        }
    }
    let eigs = |form: DiffusionForm, kv: [f64; 2]| {
        let mut q = Query::<2>::new(FormKind::Nonlocal, k, h, 0.0);
        q.material = MaterialSpec::Hydro;
        q.diffusion = Some((delta, form));
        q.linearise_at(0.0).unwrap().eigenvalues(kv).unwrap()
    };
    // the acoustic pair: the eigenvalue of largest Im s
    let damping = |form: DiffusionForm, kv: [f64; 2]| -> f64 {
        eigs(form, kv)
            .iter()
            .max_by(|a, b| a.im.total_cmp(&b.im))
            .unwrap()
            .re
    };
    let kx = 0.01;
    let want = -delta * h * sxx * kx * kx / 2.0;
    let mc = damping(DiffusionForm::MolteniColagrossi, [kx, 0.0]);
    let an = damping(DiffusionForm::Antuono, [kx, 0.0]);
    eprintln!("2D fluid, kΔx = {kx}: Re s MC {mc:.6e} (−νk²/2 = {want:.6e}), Antuono {an:.3e}");
    assert!((mc / want - 1.0).abs() < 1e-3, "{mc} vs {want}");
    assert!(an.abs() < 1e-3 * mc.abs(), "Antuono {an} vs MC {mc}");
    // at X the gradient estimate of the mode vanishes: the same (real, damped) spectrum
    let fastest = |form| {
        eigs(form, [PI, 0.0])
            .iter()
            .map(|z| z.re)
            .fold(f64::INFINITY, f64::min)
    };
    let (a, b) = (
        fastest(DiffusionForm::MolteniColagrossi),
        fastest(DiffusionForm::Antuono),
    );
    eprintln!("2D fluid at X: strongest damping MC {a:.9e}, Antuono {b:.9e}");
    assert!(
        a < -1e-3 && (a - b).abs() <= 1e-12 * a.abs(),
        "X: {a} vs {b}"
    );
}

/// The 1D classical (sum-form) bar with δ-SPH, derived by hand (issue 24 item 7). Δx = 1,
/// V = m = ρ0 = 1, C = 1 (c = 1), pre-stress σ0; a mode u, v, ρ − 1, σ − σ0 ∝ e^{iκj + st}
/// with amplitudes U, V, R, S. The rate function of `classical`:
///
/// ```text
/// a_I = Σ_J m (σ_I/ρ_I² + σ_J/ρ_J²) G(x_I − x_J),   G(x) = W'(|x|) sign x
/// ρ̇_I = −ρ_I L_I + D_I,   σ̇_I = (C + σ_I) L_I,   L_I = Σ_J V (v_J − v_I) G(x_I − x_J)
/// ```
///
/// linearised (Σ_J G = 0 kills the I terms; δ(σ/ρ²) = δσ − 2σ0 δρ):
///
/// ```text
/// s U = V
/// s V = iα (S − 2σ0 R) + 4σ0 B U     α = −2 Σ_{n>0} W'(n) sin κn,  B = Σ_{n>0} W''(n)(1 − cos κn)
/// s R = −iα V − ν R                   ν = −(diffusion symbol) > 0, [`symbol`]: D_I is linear in
/// s S = iα (1 + σ0) V                 ρ alone (ψ and ⟨∇ρ⟩ vanish in the base state)
/// ```
///
/// Eliminating U, R, S: **s³ + ν s² + ω0² s + ν P = 0** with P = α²(1 + σ0) − 4σ0 B and
/// ω0² = P + 2σ0 α² (ν = 0: s² = −ω0², the classical dispersion). Routh–Hurwitz (ν > 0): stable
/// iff **P > 0** and ν ω0² > ν P, i.e. **2σ0 α² > 0**: under compression (σ0 < 0) every κ
/// with α ≠ 0 grows for any δ > 0 (for small ν the acoustic pair gets Re s = −ν σ0 α²/ω0²); in
/// tension the κ where the inviscid chain is stable only because of the density term
/// (ω0² > 0 > P) grow too: the tensile band widens. The density enters the sum form's
/// acceleration through σ0/ρ², and the diffusion takes that support away.
/// (The difference forms have no σ0/ρ² term: there δ-SPH only damps the density.)
fn classical_bar_growth(
    form: DiffusionForm,
    h: f64,
    delta: f64,
    s0: f64,
    kappa: f64,
) -> (f64, C, f64) {
    let k = kernel::by_name("m4").unwrap();
    let reach = (k.zeta() * h).ceil() as i64 + 1;
    let (mut alpha, mut b) = (0.0, 0.0);
    for n in 1..=reach {
        let r = n as f64;
        alpha -= 2.0 * kernel::dw(k, 1, r, h) * (kappa * r).sin();
        b += kernel::d2w(k, 1, r, h) * (1.0 - (kappa * r).cos());
    }
    let nu = -symbol("m4", h, delta, form, kappa);
    let p = alpha * alpha * (1.0 + s0) - 4.0 * s0 * b;
    let w2 = p + 2.0 * s0 * alpha * alpha;
    // roots of s³ + ν s² + ω0² s + ν P (Durand–Kerner, then Newton)
    let f = |s: C| ((s + nu) * s + w2) * s + nu * p;
    let df = |s: C| (s * 3.0 + 2.0 * nu) * s + w2;
    let mut z = [
        C::new(0.4, 0.9),
        C::new(0.4, 0.9).powi(2),
        C::new(0.4, 0.9).powi(3),
    ];
    for _ in 0..500 {
        for i in 0..3 {
            let den = (0..3)
                .filter(|&j| j != i)
                .fold(C::new(1.0, 0.0), |a, j| a * (z[i] - z[j]));
            z[i] -= f(z[i]) / den;
        }
    }
    for r in z.iter_mut() {
        for _ in 0..3 {
            *r -= f(*r) / df(*r);
        }
    }
    let top = *z.iter().max_by(|a, b| a.re.total_cmp(&b.re)).unwrap();
    (top.re.max(0.0), top, p)
}

/// δ-SPH destabilises 1D classical SPH under compression (issue 24 item 7; the README said it
/// does not). Three routes against the closed form of [`classical_bar_growth`]:
/// - the engine's eigenvalues (largest Re s) at 64 κ in (0, π], both δ-SPH forms, σ̄ = ±0.1,
///   ±0.01, δ = 0.01 and 0.1, to 1e-10;
/// - `sphstab query --form classical --h 1.3 --stress -0.1 --delta 0.1 --delta-form
///   molteni-colagrossi`: growth 0.020058 c/Δx at κΔx = 0.5625π, the issue author's independent
///   value, equal to the closed form's maximum over the same 512 κ;
/// - the time-domain solver: a periodic chain of 64 particles at κΔx = 2π·18/64 = 0.5625π,
///   seeded with the closed form's growing eigenvector (amplitude 1e-8) and stepped by `rk4`
///   (Δt = 0.05 Δx/c) to t = 150: the velocity's Fourier amplitude grows at the closed-form
///   rate to 1e-5 (measured 0.020058442 against 0.020058440).
///
/// Also from the closed form: under compression every κ in [0.05π, 0.95π] grows (Routh–
/// Hurwitz); in tension, of the κ where the inviscid chain is stable exactly those with P < 0
/// grow (σ̄ = 0.1: the band κΔx/π ∈ [0.787, 1] widens to [0.762, 1]), and in the tensile band
/// (ω0² < 0) the growth speeds up (up to 1.5× at some κ); at κΔx = π itself (α = 0: the mode
/// carries no density) the tensile maximum is unchanged.
#[test]
fn delta_sph_destabilises_classical_sph_in_compression() {
    use sphstab::integrator::Integrator;
    use sphstab::vonneumann::linearise::Lattice1D;
    let (mc, an) = (DiffusionForm::MolteniColagrossi, DiffusionForm::Antuono);
    let h = 1.3;
    let classical = |delta: f64, form| {
        let mut p = params("m4", h, delta, form);
        p.form = FormKind::Classical;
        p
    };
    // 1. the engine
    let mut worst: f64 = 0.0;
    let mut tensile_band_faster: f64 = 1.0;
    for form in [mc, an] {
        for s0 in [-0.1, -0.01, 0.01, 0.1] {
            for delta in [0.01, 0.1] {
                let lin =
                    Linearisation::new(classical(delta, form), s0, Lattice1D::default()).unwrap();
                for i in 1..=64 {
                    let kap = PI * i as f64 / 64.0;
                    let ev = lin.eigenvalues(kap).unwrap();
                    let got = ev.iter().map(|z| z.re).fold(0.0, f64::max);
                    let (want, _, p) = classical_bar_growth(form, h, delta, s0, kap);
                    let scale = ev.iter().map(|z| z.norm()).fold(0.0, f64::max);
                    let d = (got - want).abs() / scale;
                    assert!(
                        d < 1e-10,
                        "{form:?} σ̄ {s0} δ {delta} κ {kap}: engine {got} vs closed form {want}"
                    );
                    worst = worst.max(d);
                    if s0 < 0.0 && (0.05 * PI..=0.95 * PI).contains(&kap) {
                        assert!(want > 0.0, "compression, κ {kap}: no growth");
                    }
                    let (inviscid, _, _) = classical_bar_growth(form, h, 0.0, s0, kap);
                    if s0 > 0.0 && inviscid == 0.0 {
                        assert_eq!(want > 0.0, p < 0.0, "tension, κ {kap}: {want}, P = {p}");
                    }
                    if s0 > 0.0 && inviscid > 0.0 && want > inviscid {
                        tensile_band_faster = tensile_band_faster.max(want / inviscid);
                    }
                }
            }
        }
    }
    eprintln!(
        "classical + δ-SPH: engine vs closed form, worst {worst:.1e} of the largest |s|; in the \
         tensile band below κΔx = π growth up to {tensile_band_faster:.4}× the inviscid"
    );

    // 2. the CLI, the issue's case
    let v = common::json(&[
        "query",
        "--form",
        "classical",
        "--h",
        "1.3",
        "--stress",
        "-0.1",
        "--delta",
        "0.1",
        "--delta-form",
        "molteni-colagrossi",
        "--json",
    ]);
    let (want, at) = (1..=512)
        .map(|i| {
            let kap = PI * i as f64 / 512.0;
            (classical_bar_growth(mc, h, 0.1, -0.1, kap).0, kap)
        })
        .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
    let got = v["max_growth_rate"].as_f64().unwrap();
    eprintln!(
        "query: growth {got:.9} c/Δx, closed form {want:.9} at κΔx = {:.4}π",
        at / PI
    );
    assert!((got - want).abs() <= 1e-9 * want, "{got} vs {want}");
    assert!((want - 0.020058).abs() < 5e-7 && (at / PI - 0.5625).abs() < 1e-12);
    assert_eq!(v["instabilities"][0]["kind"], "compressive");

    // 3. the solver
    let (n, m, s0, delta) = (64usize, 18usize, -0.1, 0.1);
    let kap = 2.0 * PI * m as f64 / n as f64;
    let (gamma, s, _) = classical_bar_growth(mc, h, delta, s0, kap);
    let k = kernel::by_name("m4").unwrap();
    let alpha: f64 = (1..=4)
        .map(|j| -2.0 * kernel::dw(k, 1, j as f64, h) * (kap * j as f64).sin())
        .sum();
    let nu = -symbol("m4", h, delta, mc, kap);
    let i = C::new(0.0, 1.0);
    // the eigenvector of s: V = 1, U = V/s, R = −iαV/(s + ν), S = iα(1 + σ0)V/s
    let (eu, er, es) = (1.0 / s, -i * alpha / (s + nu), i * alpha * (1.0 + s0) / s);
    let model = Model::new(
        classical(delta, mc),
        (0..n).map(|j| [j as f64]).collect(),
        vec![1.0; n],
        1.0,
        s0,
        Some([[n as f64]]),
    )
    .unwrap();
    let mut z = model.rest_state(1.0);
    let eps = 1e-8;
    for j in 0..n {
        let ph = C::from_polar(1.0, kap * j as f64);
        z.x[j][0] += eps * (eu * ph).re;
        z.v[j][0] += eps * ph.re;
        z.rho[j] += eps * (er * ph).re;
        z.sigma[j][0][0] += eps * (es * ph).re;
    }
    let amp = |v: &[[f64; 1]]| -> f64 {
        (0..n)
            .map(|j| C::from_polar(v[j][0], -kap * j as f64))
            .sum::<C>()
            .norm()
    };
    let a0 = amp(&z.v);
    let mut run = Run::with_prescribed(model, z, &vec![None; n]).unwrap();
    run.set_integrator(Integrator::from_name("rk4", 40).unwrap());
    let (dt, steps) = (0.05, 3000);
    for _ in 0..steps {
        run.step(dt).unwrap();
    }
    let meas = (amp(&run.z.v) / a0).ln() / (dt * steps as f64);
    eprintln!(
        "solver: growth {meas:.9} c/Δx at κΔx = {:.4}π, closed form {gamma:.9}",
        kap / PI
    );
    assert!((meas / gamma - 1.0).abs() < 1e-5, "{meas} vs {gamma}");

    // 4. 2D, the statements of docs/delta-sph.md (16² zone grid): an elastic lattice carries its stress
    // as a state, so the sum form's σ/ρ² term is the 1D mechanism and δ-SPH adds growth under
    // compression; in a fluid the stress is the density, which the diffusion damps
    let grows_2d = |material: &str, delta: bool| {
        let mut args = vec![
            "query",
            "--dim",
            "2",
            "--material",
            material,
            "--form",
            "classical",
            "--h",
            "1.2",
            "--stress",
            "-0.1",
            "--grid",
            "16",
            "--json",
        ];
        if delta {
            args.extend(["--delta", "0.1", "--delta-form", "molteni-colagrossi"]);
        }
        common::json(&args)["max_growth_rate"].as_f64().unwrap() > 0.0
    };
    assert!(!grows_2d("elastic", false) && grows_2d("elastic", true));
    assert!(!grows_2d("hydro", false) && !grows_2d("hydro", true));
}
