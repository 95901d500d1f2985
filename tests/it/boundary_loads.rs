//! Time-dependent ends and probes of the 1D scenes (issue 29, capability 2; [T §4.6.3]): a
//! traction pulse travels as T11 = s̄(t − x/c) ([T] eq 4.37), a velocity pulse as
//! σ = −ρ0 c v̄(t − x/c), the load makes a uniform stress an equilibrium of the form, and the
//! neo-Hookean bar stretched to λ = 6 ends on [T] eq 5.5. Every expected value is computed here
//! from the closed forms (the m4 kernel's cumulative integral, eq 4.37, eq 5.5), not by the
//! code under test.

use sphstab::forms::{FormKind, Material, Model, ModelParams, State};
use sphstab::kernel::{self, cumulative_1d};
use sphstab::shape::{KernelParams, ShapeFamily};
use sphstab::solver::scene::{Pulse, Scene, parse};

/// The m4 (cubic B-spline) kernel's 1D cumulative integral in closed form: σ1 = 2/3,
/// f = 1 − 3q²/2 + 3q³/4 on [0, 1], (2 − q)³/4 on [1, 2];
/// ∫_0^q f = q − q³/2 + 3q⁴/16 (q ≤ 1), 11/16 + (1 − (2 − q)⁴)/16 (1 ≤ q ≤ 2).
fn m4_cumulative(q: f64) -> f64 {
    let a = q.abs().min(2.0);
    let half = if a <= 1.0 {
        a - a.powi(3) / 2.0 + 3.0 * a.powi(4) / 16.0
    } else {
        11.0 / 16.0 + (1.0 - (2.0 - a).powi(4)) / 16.0
    };
    0.5 + q.signum() * (2.0 / 3.0) * half
}

/// The smoothed square pulse of [`Pulse`] with the m4 kernel, from the closed form.
fn m4_pulse(a: f64, duration: f64, h: f64, t: f64) -> f64 {
    let t0 = 2.0 * h;
    a * (m4_cumulative((t - t0) / h) - m4_cumulative((t - t0 - duration) / h))
}

#[test]
fn the_cumulative_kernel_and_the_pulse_match_their_closed_forms() {
    let m4 = kernel::by_name("m4").unwrap();
    for i in -25..=25 {
        let q = 0.1 * i as f64;
        let (got, want) = (cumulative_1d(m4, q), m4_cumulative(q));
        assert!(
            (got - want).abs() < 1e-13,
            "I({q}) = {got}, closed form {want}"
        );
    }
    // every kernel: I(0) = 1/2, I(ζ) = 1, odd about 1/2
    for &k in kernel::all() {
        let (name, z) = (k.name(), k.zeta());
        assert!((cumulative_1d(k, 0.0) - 0.5).abs() < 1e-15, "{name}");
        assert!(
            (cumulative_1d(k, 0.999_999 * z) - 1.0).abs() < 1e-9,
            "{name}"
        );
        for q in [0.1, 0.37, 0.8] {
            let s = cumulative_1d(k, q * z) + cumulative_1d(k, -q * z);
            assert!((s - 1.0).abs() < 1e-14, "{name}: I(q) + I(−q) = {s}");
        }
    }
    let p = Pulse {
        amplitude: -1e5,
        duration: 1e-5,
        smoothing: 1e-6,
        start: None,
    };
    for i in 0..=200 {
        let t = 1.5e-5 * i as f64 / 200.0;
        let (got, want) = (p.at(m4, t), m4_pulse(-1e5, 1e-5, 1e-6, t));
        assert!(
            (got - want).abs() < 1e-8,
            "g({t}) = {got}, closed form {want}"
        );
    }
    // smoothing keeps the impulse: ∫ g dt = A T (trapezoid on 20,000 intervals)
    let n = 20_000;
    let end = p.end(m4);
    let integral: f64 = (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n { 0.5 } else { 1.0 };
            w * p.at(m4, end * i as f64 / n as f64)
        })
        .sum::<f64>()
        * end
        / n as f64;
    assert!(
        (integral - (-1e5 * 1e-5)).abs() < 1e-6 * 1.0,
        "∫g = {integral}"
    );
}

/// A 0.15 m steel bar (E = 200 GPa, ρ = 8000, c = 5000 m/s), total-Lagrangian with MLS shapes
/// and m4 at h = 2Δx, 601 particles, a traction pulse (−100 kPa, 10 μs, smoothing 1 μs) on the
/// left end, the right end fixed, probes at 0.05 and 0.1 m.
fn steel_bar(left: &str) -> Scene {
    parse(
        "test",
        &format!(
            r#"{{"name": "t", "form": "total-lagrangian", "kernel": "m4", "h_over_dx": 2.0,
            "shape": "mls", "modulus": 200e9, "rho0": 8000.0, "particles": 601, "origin": 0.0,
            "length": 0.15, "initial_velocity": {{"kind": "rest"}}, "left": {left},
            "right": {{"layers": 1, "velocity": 0.0}}, "t_end": 3.2e-5, "dt": 0.5,
            "analytic": "end-pulse", "probes": [0.05, 0.1]}}"#
        ),
    )
    .unwrap()
}

/// [T] eq 4.37: before any reflection the stress at X is the boundary stress delayed by X/c,
/// T11(X, t) = s̄(t − X/c), and the velocity v = −T11/(ρ0 c). Measured (2026-12-04): plateau
/// −100.00 kPa, RMS deviation of the histories 1.2% and 1.4% of the amplitude, the first
/// front 1.6Δx/c late, the front speed between the probes 0.37% below c (the lattice
/// operator's dispersion at the front's wave numbers).
#[test]
fn a_traction_pulse_travels_as_eq_4_37() {
    let s = steel_bar(r#"{"traction": {"amplitude": -1e5, "duration": 1e-5, "smoothing": 1e-6}}"#);
    let r = s.run(|_| {}).unwrap();
    let (c, z, dx) = (5000.0, 8000.0 * 5000.0, 0.15 / 600.0);
    let exact = |x: f64, t: f64| m4_pulse(-1e5, 1e-5, 1e-6, t - x / c);
    let mut fronts = Vec::new();
    for p in &r.probes {
        let x = p.reference_position;
        // the plateau: midway through the pulse's flat part (t0 + 2h .. t0 + T − 2h, delayed)
        let t_mid = 2e-6 + 5e-6 + x / c;
        let i = r.probe_t.iter().position(|&t| t >= t_mid).unwrap();
        assert!(
            (p.stress[i] / -1e5 - 1.0).abs() < 5e-3,
            "X = {x}: plateau {} Pa",
            p.stress[i]
        );
        assert!(
            (p.velocity[i] / (1e5 / z) - 1.0).abs() < 5e-3,
            "X = {x}: plateau velocity {}",
            p.velocity[i]
        );
        let rms = (p
            .stress
            .iter()
            .zip(&r.probe_t)
            .map(|(s, &t)| (s - exact(x, t)).powi(2))
            .sum::<f64>()
            / p.stress.len() as f64)
            .sqrt();
        assert!(rms < 0.02 * 1e5, "X = {x}: RMS deviation {rms} Pa");
        // the front: first time the stress passes half the amplitude
        let cross = |f: &dyn Fn(usize) -> f64| {
            let j = (1..r.probe_t.len()).find(|&j| f(j) <= -0.5e5).unwrap();
            let (a, b) = (f(j - 1), f(j));
            r.probe_t[j - 1] + (r.probe_t[j] - r.probe_t[j - 1]) * (-0.5e5 - a) / (b - a)
        };
        fronts.push((
            x,
            cross(&|j| p.stress[j]),
            cross(&|j| exact(x, r.probe_t[j])),
        ));
    }
    // the first probe's front within 2Δx/c of eq 4.37's; the speed between the probes within
    // 1% of c (a figure's reading precision: the thesis's claim is "the expected wave speed")
    let (x1, t1, e1) = fronts[0];
    let (x2, t2, _) = fronts[1];
    assert!(
        (t1 - e1).abs() < 2.0 * dx / c,
        "front at {t1} s, eq 4.37 {e1} s"
    );
    let speed = (x2 - x1) / (t2 - t1);
    assert!((speed / c - 1.0).abs() < 0.01, "front speed {speed} m/s");
}

/// A velocity pulse on a prescribed layer sends σ = −ρ0 c v̄(t − x/c) (the impedance relation
/// of a right-moving wave); its plateau and front, as for the traction.
#[test]
fn a_velocity_pulse_sends_minus_rho_c_v() {
    let s = steel_bar(
        r#"{"layers": 2, "velocity_pulse": {"amplitude": 0.01, "duration": 1e-5, "smoothing": 1e-6}}"#,
    );
    let r = s.run(|_| {}).unwrap();
    let z = 8000.0 * 5000.0;
    for p in &r.probes {
        let x = p.reference_position;
        let i = r
            .probe_t
            .iter()
            .position(|&t| t >= 7e-6 + x / 5000.0)
            .unwrap();
        assert!(
            (p.stress[i] / (-z * 0.01) - 1.0).abs() < 5e-3,
            "X = {x}: plateau {} Pa, −ρ0 c v̄ = {}",
            p.stress[i],
            -z * 0.01
        );
        assert!((p.velocity[i] / 0.01 - 1.0).abs() < 5e-3);
    }
}

/// The traction load makes a uniform stress s̄ an equilibrium: a bar uniformly strained to
/// the stress s̄ with s̄ prescribed on both ends has zero acceleration everywhere (the
/// total-Lagrangian form with MLS shapes, whose strain is exact for a linear displacement,
/// and the classical form with σ = s̄ carried), to rounding.
#[test]
fn a_uniform_stress_is_an_equilibrium_of_the_traction_load() {
    let n = 61;
    let dx = 0.01;
    let e = 1e9;
    let s_bar = 3e6;
    for (form, shape) in [
        (FormKind::TotalLagrangian, ShapeFamily::Mls),
        (FormKind::Classical, ShapeFamily::Sph),
    ] {
        let x_ref: Vec<[f64; 1]> = (0..n).map(|i| [i as f64 * dx]).collect();
        let p = ModelParams {
            form,
            shape,
            kp: KernelParams {
                kernel: kernel::by_name("wendland-c2").unwrap(),
                h: 1.6 * dx,
            },
            material: Material::bar(e),
            rho0: 1000.0,
            c_partition: 0.5,
            av: None,
            art_stress: None,
            diffusion: None,
            alpha_s: 0.0,
            ls_length: dx,
            hourglass: None,
        };
        let model = Model::new(p, x_ref.clone(), vec![dx; n], 1000.0, 0.0, None).unwrap();
        let b = model.unit_stress_force(0).unwrap();
        let mut z: State<f64, 1> = model.rest_state(1000.0);
        if form == FormKind::TotalLagrangian {
            // the uniform strain of the stress s̄ (1D law P = C(F − 1))
            for (xi, xr) in z.x.iter_mut().zip(&x_ref) {
                xi[0] = xr[0] * (1.0 + s_bar / e);
            }
        } else {
            // the stress itself, carried, in the reference configuration
            z.sigma.iter_mut().for_each(|s| s[0][0] = s_bar);
        }
        let mut out = State::default();
        model.rate(&z, &mut out).unwrap();
        let scale = s_bar / (1000.0 * dx);
        for (i, (a, bk)) in out.v.iter().zip(&b).enumerate() {
            let load = -s_bar * bk[0] / model.mass[i];
            let total = a[0] + load;
            assert!(
                total.abs() < 1e-9 * scale,
                "{}: particle {i}: a = {} + load {load}",
                form.name(),
                a[0]
            );
        }
        // the load acts near the ends only, inward at the left under tension
        assert!(b[0][0] > 0.0 && b[n / 2][0].abs() < 1e-12 * b[0][0].abs());
    }
}

/// The nonlocal and local forms take the difference σ_J − σ_I: a uniform stress exerts no
/// force on their boundary particles, so there is nothing for a traction to balance and the
/// scene is refused rather than run without its load.
#[test]
fn a_traction_on_a_form_blind_to_uniform_stress_is_refused() {
    for form in ["nonlocal", "local", "lnl"] {
        let mut s = steel_bar(r#"{"traction": {"amplitude": -1e5, "duration": 1e-5}}"#);
        s.shape = None;
        s.form = form.into();
        let e = s.run(|_| {}).unwrap_err().to_string();
        assert!(e.contains("traction") && e.contains(form), "{form}: {e}");
    }
}

/// [T §5.3.2, Fig 5.5]: the 15 mm neo-Hookean bar (ν = 0.3) stretched to 90 mm over 30 transit
/// times ends on eq 5.5: T11/μ = 6.2813 at λ1 = 6 (the seed digest's value,
/// `../shared/seeds/004_digest.md` §4.5, derived independently of sphstab). Measured
/// (2026-12-04): centre stretch 6.009, T11/μ = 6.290.
#[test]
fn the_stretched_neo_hookean_bar_ends_on_eq_5_5() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/analysis/scenes/thesis-neo-hookean-stretch.json"
    );
    let s = parse(path, &std::fs::read_to_string(path).unwrap()).unwrap();
    let r = s.run(|_| {}).unwrap();
    let centre = &r.probes[0];
    let end = &r.probes[1];
    let mu = 200e9 / (2.0 * 1.3);
    // the right end moved 75 mm: the bar is 6 times its length
    let nominal = 1.0 + end.displacement.last().unwrap() / 0.015;
    assert!((nominal - 6.0).abs() < 1e-3, "nominal stretch {nominal}");
    let lc = *centre.stretch.last().unwrap();
    let tc = centre.stress.last().unwrap() / mu;
    assert!((lc - 6.0).abs() < 0.03, "centre stretch {lc}");
    // eq 5.5 at the centre's own stretch, T11/μ = (λ² − 1)/λ + (λ/μ) ln λ/λ, λ/μ = 1.5
    let eq55 = |l: f64| (l * l - 1.0) / l + 1.5 * l.ln() / l;
    assert!(
        (tc - eq55(lc)).abs() < 1e-9 * tc,
        "T11/μ {tc}, eq 5.5 {}",
        eq55(lc)
    );
    assert!(
        (tc / 6.2813 - 1.0).abs() < 5e-3,
        "T11/μ {tc} against 6.2813 at λ1 = 6"
    );
}

/// Ends and probes that cannot act are refused with the field named.
#[test]
fn bad_ends_and_probes_are_refused_by_name() {
    let base = r#"{"name": "t", "form": "total-lagrangian", "kernel": "m4", "h_over_dx": 2.0,
        "shape": "mls", "modulus": 200e9, "rho0": 8000.0, "particles": 101, "origin": 0.0,
        "length": 0.1, "t_end": 1e-6, "dt": 0.5"#;
    let refused = |extra: &str, field: &str| {
        let text = if extra.contains("initial_velocity") {
            format!("{base}, {extra}}}")
        } else {
            format!(r#"{base}, "initial_velocity": {{"kind": "rest"}}, {extra}}}"#)
        };
        let e = match parse("t.json", &text) {
            Ok(s) => s.validate().map(|_| ()).unwrap_err().to_string(),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(field), "{extra}: {e}");
    };
    refused(
        r#""left": {"layers": 2, "traction": {"amplitude": 1e5, "duration": 1e-6}}"#,
        "left.traction",
    );
    refused(
        r#""left": {"velocity_pulse": {"amplitude": 1.0, "duration": 1e-6}}"#,
        "left.velocity_pulse",
    );
    refused(
        r#""right": {"traction": {"amplitude": 1e5, "duration": 0.0}}"#,
        "right.traction.duration",
    );
    refused(
        r#""right": {"traction": {"amplitude": 1e12, "duration": 1e-6}}"#,
        "right.traction.amplitude",
    );
    refused(r#""probes": [0.2]"#, "probes");
    // the analytic histories of many probes over many reflections are budgeted too: 64 probes,
    // 4 particles, 10 s (3e6 steps, 1.2e7 particle-steps, within the default budget) would
    // need ~2e14 pulse evaluations
    let many: Vec<String> = (0..64).map(|i| format!("{}", 0.001 * i as f64)).collect();
    let text = format!(
        r#"{{"name": "t", "form": "total-lagrangian", "kernel": "m4", "h_over_dx": 2.0,
        "shape": "mls", "modulus": 200e9, "rho0": 8000.0, "particles": 4, "origin": 0.0,
        "length": 0.1, "t_end": 10.0, "dt": 0.5, "initial_velocity": {{"kind": "rest"}},
        "analytic": "end-pulse", "probes": [{}]}}"#,
        many.join(", ")
    );
    let e = parse("t.json", &text)
        .unwrap()
        .validate()
        .unwrap_err()
        .to_string();
    assert!(e.contains("probes") && e.contains("analytic"), "{e}");
    refused(
        r#""material": {"kind": "neo-hookean", "poisson": 0.5}"#,
        "material.poisson",
    );
    refused(
        r#""analytic": "end-pulse", "initial_velocity": {"kind": "uniform", "value": 1.0}"#,
        "initial_velocity",
    );
}

/// [V21 §7.4, Fig 18]: the difference forms do not see the free end — 2 μs after the
/// compressive wave reaches it, the unloaded zone still carries a large part of the impact
/// stress — and four particles in the classical (plus) form there release it, as the analytic
/// solution (σ = 0 behind the release front) requires. Measured (2026-12-04), mean |σ|/ρcv0 in
/// the unloaded zone at t = 12 μs: nonlocal 0.237, local 0.263, lnl 3.639 without the layer,
/// every form below 0.01 with it (row V21 Fig 18(b) of REPRODUCTION.md).
#[test]
fn a_classical_layer_gives_the_difference_forms_a_free_end() {
    use sphstab::solver::scene::builtin;
    let unloaded = |form: &str, layers: usize| {
        let mut s = builtin("compressive-wave").unwrap();
        s.form = form.into();
        s.classical_layers = [0, layers];
        s.t_end = 1.2e-5;
        let r = s.run(|_| {}).unwrap();
        let (n, len) = (s.particles, s.length);
        let (c, z) = (5000.0, 8000.0 * 5000.0);
        let dx = len / (n - 1) as f64;
        // the release front left the free end at L/c and is at L − c (t − L/c); the zone from
        // 10Δx behind it to the free end has σ = 0
        let front = len - c * (r.t - len / c);
        let zone: Vec<f64> = (0..n)
            .filter(|&i| i as f64 * dx > front + 10.0 * dx)
            .map(|i| r.final_stress[i].abs() / (z * 50.0))
            .collect();
        zone.iter().sum::<f64>() / zone.len() as f64
    };
    for form in ["nonlocal", "local", "lnl"] {
        let (without, with) = (unloaded(form, 0), unloaded(form, 4));
        assert!(without > 0.1, "{form}: {without} without the layer");
        assert!(with < 0.1, "{form}: {with} with four classical particles");
    }
    // the layer is refused where it cannot act
    let mut s = builtin("compressive-wave").unwrap();
    s.classical_layers = [0, 4];
    let e = s.validate().unwrap_err().to_string();
    assert!(
        e.contains("classical_layers") && e.contains("classical"),
        "{e}"
    );
}
