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
