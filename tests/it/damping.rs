//! Damping of the mechanical branch (issue 12 item 3): the damping rate Re s of `dispersion`
//! against the linearised Monaghan viscosity summed by hand, and \[B00\] eq 120 against the
//! numeric critical Δt of the integrators.
//!
//! ## The linearised viscosity (derivation; the expected values below come from it)
//! Monaghan's term on particle I is a_I = −Σ_J m_J Π_IJ ∇_I W_IJ with Π_IJ = (−α c μ_IJ +
//! β μ_IJ²)/ρ̄_IJ and μ_IJ = h v_IJ·x_IJ/(r² + 0.01h²). About the rest state (v = 0, uniform
//! lattice x_j = jΔx, ρ = ρ0, m = ρ0Δx) only the α term is first order, and every factor but
//! v_IJ takes its rest value. In 1D with I = 0, J = j: x_IJ = −x_j, ∇_I W_IJ = −W'(r_j) x_j/r_j,
//! so
//!
//! a_0 = Σ_j C_j (v_j − v_0),  C_j = −α c Δx h |x_j| W'(r_j) / (x_j² + 0.01h²) ≥ 0  (W' ≤ 0),
//!
//! a discrete velocity diffusion. For the mode v_j = V e^{iκx_j} it gives the Jacobian entry
//! J_vv(κ) = −Σ_j C_j (1 − cos κx_j) (real). The mode's Jacobian is, for the nonlocal form
//! (position, velocity, density; the density rate depends on velocities only),
//! [[0, 1, 0], [J_vx, J_vv, J_vq], [0, J_qv, 0]], whose characteristic polynomial is
//! s (s² − J_vv s + ω²) with ω² = −(J_vx + J_vq J_qv) the mechanical reduction: the acoustic pair
//! is exactly a damped oscillator, Re s = J_vv/2 while underdamped (J_vv²/4 < ω²), and
//! |s| = ω. Continuum limit (1 − cos x = x²/2 − O(x⁴)): J_vv ≈ −ν_eff κ² with
//! ν_eff = ½ Σ_j C_j x_j², so Re s ≈ −ν_eff κ²/2; the relative error of each term is at most
//! (κx_j)²/12.
//!
//! In normalised units (Δx = c = ρ0 = 1, h = H) C_j = −α H |j| W'(|j|)/(j² + 0.01H²) with
//! W'(r) = (2/3)/H² · f'(r/H), f the cubic B-spline M4 written out below by hand (not through
//! the crate's kernel).

use crate::common;

use common::k;
use nalgebra::DMatrix;
use num_complex::Complex64;
use sphstab::analysis::{Query, dispersion, timestep};
use sphstab::error::Result;
use sphstab::forms::FormKind;
use sphstab::integrator::Integrator;
use sphstab::vonneumann::amplification::{ModeSystem, Modes, step_stability};
use sphstab::vonneumann::damping::{branch_damping, critical_dt_eq120, eq120};
use sphstab::vonneumann::linearise::{Linearisation, eigen};
use std::f64::consts::PI;

const H: f64 = 1.3;

/// f'(q) of M4, f = 1 − (3/2)q² + (3/4)q³ on [0, 1), ¼(2 − q)³ on [1, 2).
fn m4_fprime(q: f64) -> f64 {
    if q >= 2.0 {
        0.0
    } else if q >= 1.0 {
        -0.75 * (2.0 - q).powi(2)
    } else {
        -3.0 * q + 2.25 * q * q
    }
}

/// The coefficients C_j of the linearised viscosity (module docs), j ≠ 0, normalised units.
fn viscosity_coefficients(alpha: f64) -> Vec<(f64, f64)> {
    (-4i32..=4)
        .filter(|&j| j != 0)
        .map(|j| {
            let x = f64::from(j);
            let dw = (2.0 / 3.0) / (H * H) * m4_fprime(x.abs() / H);
            (x, -alpha * H * x.abs() * dw / (x * x + 0.01 * H * H))
        })
        .collect()
}

/// J_vv(κ) = −Σ_j C_j (1 − cos κx_j).
fn jvv(c: &[(f64, f64)], kappa: f64) -> f64 {
    -c.iter()
        .map(|&(x, cj)| cj * (1.0 - (kappa * x).cos()))
        .sum::<f64>()
}

fn nonlocal(alpha: Option<f64>) -> Query<1> {
    let mut q = Query::<1>::new(FormKind::Nonlocal, k("m4"), H, 0.0);
    q.av = alpha.map(|a| (a, 0.0));
    q
}

#[test]
fn viscous_damping_matches_the_lattice_sum_and_its_continuum_limit() {
    let mut q = nonlocal(Some(1.0));
    q.grid = 256;
    let r = dispersion(&q, q.grid).unwrap();
    let (rate, ratio) = (
        r.damping_rate_branch(0).unwrap(),
        r.damping_ratio_branch(0).unwrap(),
    );
    let c = viscosity_coefficients(1.0);
    let nu: f64 = 0.5 * c.iter().map(|&(x, cj)| cj * x * x).sum::<f64>();
    let (mut under, mut over) = (0, 0);
    for i in 0..r.path.len() {
        let kap = r.path[i];
        let j = jvv(&c, kap);
        let w2 = r.omega2[i][0];
        // the matching is unambiguous exactly where the pair oscillates (margin for rounding)
        if 0.25 * j * j < w2 * (1.0 - 1e-6) {
            under += 1;
            let s = rate[i].expect("underdamped: matched");
            assert!(
                (s - 0.5 * j).abs() <= 1e-12,
                "κ {kap}: Re s {s} vs J_vv/2 {}",
                0.5 * j
            );
            // |s| = ω: ξ = −Re s/ω
            let xi = ratio[i].unwrap();
            assert!((xi + s / w2.sqrt()).abs() <= 1e-9, "κ {kap}: ξ {xi}");
        } else if 0.25 * j * j > w2 * (1.0 + 1e-6) {
            over += 1;
            assert!(
                rate[i].is_none() && ratio[i].is_none(),
                "κ {kap}: overdamped"
            );
        }
    }
    assert!(
        under > 100 && over > 50,
        "{under} underdamped, {over} overdamped"
    );
    // continuum limit at the smallest κ: |ratio − 1| ≤ (κ x_max)²/12, x_max = 2 (support 2.6)
    let kap = r.path[0];
    let s = rate[0].unwrap();
    let limit = -0.5 * nu * kap * kap;
    let bound = (2.0 * kap).powi(2) / 12.0;
    eprintln!(
        "ν_eff = {nu:.9} c Δx; κΔx = {kap:.6}: Re s = {s:.9e}, −ν_eff κ²/2 = {limit:.9e}, ratio − 1 = {:.3e} (bound {bound:.3e})",
        s / limit - 1.0
    );
    assert!((s / limit - 1.0).abs() <= bound);
}

#[test]
fn no_viscosity_no_damping() {
    let mut q = nonlocal(None);
    q.grid = 64;
    let r = dispersion(&q, q.grid).unwrap();
    assert!(r.damping_rate.is_none() && r.damping_ratio.is_none());
    let json = serde_json::to_value(&r).unwrap();
    assert!(json.get("damping_rate").is_none());
    // the eigenvalues of the non-dissipative J: Re s = 0 to rounding on every branch
    let lin = q.chain().unwrap();
    for (&kap, &w2) in r.path.iter().zip(&r.omega2_branch(0)) {
        if w2 <= 1e-12 {
            continue;
        }
        let d = branch_damping(&lin.eigenvalues(kap).unwrap(), &[w2])[0].unwrap();
        assert!(d.abs() <= 1e-13, "κ {kap}: Re s = {d}");
    }
    let t = timestep(&Query {
        integrator: Integrator::VerletLagged,
        ..q
    })
    .unwrap();
    assert!(t.critical_dt_eq120.is_none());
    assert!(
        serde_json::to_value(&t)
            .unwrap()
            .get("critical_dt_eq120")
            .is_none()
    );
}

/// One damped oscillator per κ: x'' = −ω²(κ) x + J_vv(κ) x', ω² of the total-Lagrangian form
/// (whose 1D mode has no auxiliary state) and J_vv of the linearised viscosity summed by hand,
/// assembled here and run through the crate's amplification matrices ([`ModeSystem`]): an
/// independent construction, against which the engine's own total-Lagrangian form with
/// viscosity (its rate function applies Monaghan's Π on the reference pairs) is checked too.
struct Oscillators {
    tl: Linearisation,
    c: Vec<(f64, f64)>,
}

impl Oscillators {
    fn new(alpha: f64) -> Self {
        let q = Query::<1>::new(FormKind::TotalLagrangian, k("m4"), H, 0.0);
        Self {
            tl: q.chain().unwrap(),
            c: viscosity_coefficients(alpha),
        }
    }
    fn omega_xi(&self, kappa: f64) -> (f64, f64) {
        let w = self.tl.omega2(kappa).0.max(0.0).sqrt();
        (w, -jvv(&self.c, kappa) / (2.0 * w))
    }
    fn system(&self, kappa: f64) -> ModeSystem {
        let z = Complex64::new(0.0, 0.0);
        let one = Complex64::new(1.0, 0.0);
        let w2 = Complex64::new(self.tl.omega2(kappa).0, 0.0);
        let j = DMatrix::from_row_slice(
            2,
            2,
            &[z, one, -w2, Complex64::new(jvv(&self.c, kappa), 0.0)],
        );
        ModeSystem::new(j, vec![0], vec![1], vec![])
    }
}

impl Modes for Oscillators {
    type K = f64;
    fn is_dissipative(&self) -> bool {
        true
    }
    fn omega2_top(&self, kappa: f64) -> f64 {
        self.tl.omega2(kappa).0
    }
    fn amplification_with(&self, kappa: f64, dt: f64, integ: Integrator) -> DMatrix<Complex64> {
        self.system(kappa).amplification_with(integ, dt)
    }
    fn growth_per_step(&self, kappa: f64, dt: f64, integ: Integrator) -> Result<f64> {
        self.system(kappa).growth_per_step(integ, dt)
    }
    fn eigenvalues(&self, kappa: f64) -> Result<Vec<Complex64>> {
        let z = Complex64::new(0.0, 0.0);
        let one = Complex64::new(1.0, 0.0);
        let w2 = Complex64::new(self.tl.omega2(kappa).0, 0.0);
        eigen(DMatrix::from_row_slice(
            2,
            2,
            &[z, one, -w2, Complex64::new(jvv(&self.c, kappa), 0.0)],
        ))
    }
}

fn grid(n: usize) -> Vec<f64> {
    (1..=n).map(|i| PI * i as f64 / n as f64).collect()
}

#[test]
fn eq120_is_the_critical_step_of_verlet_lagged_on_damped_oscillators() {
    let ks = grid(128);
    for alpha in [0.5, 1.0, 2.0] {
        let m = Oscillators::new(alpha);
        // eq 120 from the oscillator's own (ω, ξ) (ω = 0 at κ = π: the limit 1/(ξω) = 2/|J_vv|)
        let by_hand = ks
            .iter()
            .map(|&kap| {
                let (w, xi) = m.omega_xi(kap);
                if w > 1e-6 {
                    eq120(w, xi)
                } else {
                    2.0 / jvv(&m.c, kap).abs()
                }
            })
            .fold(f64::INFINITY, f64::min);
        // the same from the eigenvalues (ω = |s|, ξ = −Re s/|s|; overdamped: the real pair)
        let from_eigs = critical_dt_eq120(&m, &ks).unwrap();
        let lagged = step_stability(&m, &ks, Integrator::VerletLagged)
            .unwrap()
            .critical_dt
            .unwrap();
        let kdk = step_stability(&m, &ks, Integrator::Kdk)
            .unwrap()
            .critical_dt
            .unwrap();
        eprintln!(
            "TL + viscosity α = {alpha}: eq 120 = {from_eigs:.9} (by hand {by_hand:.9}); verlet-lagged {lagged:.9} (rel {:.2e}); kdk {kdk:.9} (eq 120 / kdk = {:.4})",
            lagged / from_eigs - 1.0,
            from_eigs / kdk
        );
        assert!((from_eigs / by_hand - 1.0).abs() <= 1e-9, "α {alpha}");
        assert!((lagged / from_eigs - 1.0).abs() <= 1e-6, "α {alpha}");
        // the engine: total-lagrangian with the viscosity in its rate function
        let mut q = Query::<1>::new(FormKind::TotalLagrangian, k("m4"), H, 0.0);
        q.av = Some((alpha, 0.0));
        q.grid = 128;
        let t = timestep(&Query {
            integrator: Integrator::VerletLagged,
            ..q
        })
        .unwrap();
        let (e120, crit) = (t.critical_dt_eq120.unwrap(), t.step.critical_dt.unwrap());
        eprintln!("  engine TL + viscosity: eq 120 {e120:.9}, verlet-lagged {crit:.9}");
        assert!((e120 / from_eigs - 1.0).abs() <= 1e-9, "α {alpha}: {e120}");
        assert!((crit / lagged - 1.0).abs() <= 1e-6, "α {alpha}: {crit}");
    }
}

#[test]
fn eq120_in_timestep_for_the_nonlocal_form() {
    // printed, not asserted beyond consistency: with the density as auxiliary state eq 120 is an
    // estimate for every integrator
    for alpha in [0.5, 1.0, 2.0] {
        let mut q = nonlocal(Some(alpha));
        q.grid = 128;
        let lagged = timestep(&Query {
            integrator: Integrator::VerletLagged,
            ..q
        })
        .unwrap();
        let kdk = timestep(&Query {
            integrator: Integrator::Kdk,
            ..q
        })
        .unwrap();
        let e = lagged.critical_dt_eq120.unwrap();
        let lin = q.chain().unwrap();
        assert_eq!(e, critical_dt_eq120(&lin, &q.kappas()).unwrap());
        assert_eq!(Some(e), kdk.critical_dt_eq120);
        let (l, k) = (
            lagged.step.critical_dt.unwrap(),
            kdk.step.critical_dt.unwrap(),
        );
        eprintln!(
            "nonlocal m4 h 1.3 α = {alpha}: eq 120 = {e:.9}; verlet-lagged {l:.9} (eq 120 / numeric {:.4}); kdk {k:.9} ({:.4})",
            e / l,
            e / k
        );
    }
}
