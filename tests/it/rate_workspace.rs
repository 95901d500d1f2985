//! The 2D rate (`Model::rate`, and `rate_with` / `rate_into` with a reusable `RateWorkspace`)
//! against golden data, on disordered states, for every 2D form, the materials, shape
//! families, artificial viscosity and artificial stress, open and periodic domains; in f64 and
//! in dual numbers (the linearisation's scalar).
//!
//! The golden file `tests/data/rates2d.json` holds the rates that the 2D rate function computed
//! before the forms became dimension-generic (commit 9751941, whose own test had checked them
//! against the pre-workspace rate to 1e-14), for exactly the configurations and states built
//! here; stresses there are stored as [xx, yy, xy].
use sphstab::forms::{
    ArtificialStress, ArtificialViscosity, FormKind, Material, Model, ModelParams, ObjectiveRate,
    RateOut, RateWorkspace, State,
};
use sphstab::kernel;
use sphstab::lattice::Lattice;
use sphstab::scalar::{Dual, Scalar};
use sphstab::shape::KernelParams;
use sphstab::shape::ShapeFamily;

/// A deterministic pseudo-random number in [−1, 1].
fn noise(k: usize, salt: f64) -> f64 {
    ((k as f64 * 12.9898 + salt * 78.233).sin() * 43758.5453).fract()
}

fn params(form: FormKind, shape: ShapeFamily, material: Material, kern: &str) -> ModelParams {
    ModelParams {
        form,
        shape,
        kp: KernelParams {
            kernel: kernel::by_name(kern).unwrap(),
            h: 1.3,
        },
        material,
        rho0: 1.0,
        c_partition: 0.4,
        av: None,
        art_stress: None,
        diffusion: None,
        alpha_s: 0.0,
        ls_length: 1.0,
        hourglass: None,
    }
}

/// An open, jittered 11 × 9 block (or a periodic 8 × 7 patch of `lat`) with a disordered state:
/// velocities, densities and anisotropic stresses (tensile and compressive) of every field the
/// form carries.
fn case(p: ModelParams, periodic: Option<&Lattice<2>>) -> (Model<2>, State<f64, 2>) {
    // the neo-Hookean reference state is unstressed
    let s0 = if matches!(p.material, Material::NeoHookean { .. }) {
        0.0
    } else {
        0.05
    };
    let model = match periodic {
        None => {
            let mut x = Vec::new();
            for i in 0..11 {
                for j in 0..9 {
                    x.push([i as f64, j as f64]);
                }
            }
            let n = x.len();
            Model::<2>::new(p, x, vec![1.0; n], 1.0, s0, None).unwrap()
        }
        Some(lat) => Model::<2>::periodic_patch(p, lat, 1.0, [8, 7], 1.0, s0).unwrap(),
    };
    let mut z = model.rest_state(1.0);
    for (k, x) in z.x.iter_mut().enumerate() {
        x[0] += 0.12 * noise(k, 1.0);
        x[1] += 0.12 * noise(k, 2.0);
    }
    for (k, v) in z.v.iter_mut().enumerate() {
        *v = [0.03 * noise(k, 3.0), 0.03 * noise(k, 4.0)];
    }
    for (k, r) in z.rho.iter_mut().enumerate() {
        *r = 1.0 + 0.03 * noise(k, 5.0);
    }
    // [[xx, xy], [xy, yy]]
    let sym = |xx: f64, yy: f64, xy: f64| [[xx, xy], [xy, yy]];
    for (k, s) in z.sigma.iter_mut().enumerate() {
        *s = sym(
            0.02 + 0.05 * noise(k, 6.0),
            0.05 * noise(k, 7.0),
            0.03 * noise(k, 8.0),
        );
    }
    for (k, s) in z.tau.iter_mut().enumerate() {
        *s = sym(
            0.05 * noise(k, 9.0),
            0.02 + 0.05 * noise(k, 10.0),
            0.03 * noise(k, 11.0),
        );
    }
    (model, z)
}

/// Largest |a − b| over a field, relative to the field's largest |b| (absolute below 1e-300).
fn field_err(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "field lengths differ");
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// Largest relative difference over the fields of two states (values and, for duals,
/// derivative parts), with the name of the worst field.
fn state_err<S: Scalar>(
    a: &State<S, 2>,
    b: &State<S, 2>,
    re: impl Fn(S) -> f64,
) -> (f64, &'static str) {
    let flat2 = |v: &[[S; 2]]| v.iter().flatten().map(|&s| re(s)).collect::<Vec<_>>();
    let flat3 = |v: &[[[S; 2]; 2]]| {
        v.iter()
            .flatten()
            .flatten()
            .map(|&s| re(s))
            .collect::<Vec<_>>()
    };
    let flat1 = |v: &[S]| v.iter().map(|&s| re(s)).collect::<Vec<_>>();
    [
        (field_err(&flat2(&a.x), &flat2(&b.x)), "x"),
        (field_err(&flat2(&a.v), &flat2(&b.v)), "v"),
        (field_err(&flat1(&a.rho), &flat1(&b.rho)), "rho"),
        (field_err(&flat3(&a.sigma), &flat3(&b.sigma)), "sigma"),
        (field_err(&flat3(&a.tau), &flat3(&b.tau)), "tau"),
    ]
    .into_iter()
    .fold((0.0, "-"), |m, e| if e.0 > m.0 { e } else { m })
}

const TOL: f64 = 1e-14;

/// Every configuration: (label, params, periodic lattice).
fn configs() -> Vec<(String, ModelParams, Option<Lattice<2>>)> {
    let elastic_j = Material::elastic(1.0, 0.3, ObjectiveRate::Jaumann).unwrap();
    let elastic_t = Material::elastic(1.0, 0.25, ObjectiveRate::Truesdell).unwrap();
    let hydro = Material::Hydro { bulk: 1.0 };
    let av = |approaching_only| ArtificialViscosity {
        alpha: 1.0,
        beta: 1.0,
        sound_speed: 1.0,
        approaching_only,
    };
    let art = ArtificialStress {
        eps: 0.3,
        n: 4,
        spacing: 1.0,
    };
    let square = Lattice::<2>::square(1.0).unwrap();
    let hex = Lattice::<2>::by_name("hex", 1.0).unwrap();
    let mut out = Vec::new();
    for form in [
        FormKind::Classical,
        FormKind::Nonlocal,
        FormKind::Local,
        FormKind::Lnl,
        FormKind::Cll,
        FormKind::TotalLagrangian,
    ] {
        let shape = form.default_shape_in(2);
        for (mname, mat) in [
            ("hydro", hydro),
            ("elastic-jaumann", elastic_j),
            ("elastic-truesdell", elastic_t),
        ] {
            for (extras, with_av, with_art) in [("plain", false, false), ("av+art", true, true)] {
                let mut p = params(form, shape, mat, "m4");
                // total-lagrangian: the golden rows (written when its rate function ignored the
                // viscosity) are its plain rates; with the viscosity now applied, its "av+art"
                // rows are computed without it (tests/it/damping.rs checks its viscosity)
                if with_av && form != FormKind::TotalLagrangian {
                    p.av = Some(av(true));
                }
                if with_art {
                    p.art_stress = Some(art);
                }
                let label = format!("{} {} {} {}", form.name(), shape.name(), mname, extras);
                out.push((format!("{label} open"), p, None));
                out.push((format!("{label} periodic square"), p, Some(square)));
            }
        }
    }
    // the other shape families, kernels, AV on all pairs, a parallelogram (direct-scan) patch
    let mut p = params(
        FormKind::Classical,
        ShapeFamily::Shepard,
        elastic_j,
        "wendland-c2",
    );
    p.av = Some(av(false));
    p.art_stress = Some(art);
    out.push((
        "classical shepard wendland-c2 av(all pairs)+art open".into(),
        p,
        None,
    ));
    let p = params(FormKind::Nonlocal, ShapeFamily::Mls, elastic_t, "m5");
    out.push(("nonlocal mls m5 open".into(), p, None));
    let mut p = params(FormKind::Cll, ShapeFamily::Sph, hydro, "m4");
    p.art_stress = Some(art);
    p.av = Some(av(true));
    out.push(("cll sph hydro av+art periodic hex".into(), p, Some(hex)));
    out.push(("cll sph hydro av+art open".into(), p, None));
    let p = params(
        FormKind::TotalLagrangian,
        ShapeFamily::Sph,
        Material::NeoHookean {
            lambda: 0.6,
            shear: 0.3,
        },
        "m4",
    );
    out.push(("total-lagrangian neo-hookean open".into(), p, None));
    out
}

/// The golden data file.
fn golden() -> serde_json::Value {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/rates2d.json"
    ))
    .unwrap();
    serde_json::from_str(&text).unwrap()
}

fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The fields of a rate as the golden file stores them: v, ρ, σ and τ as [xx, yy, xy].
fn fields<S: Scalar>(z: &State<S, 2>, re: impl Fn(S) -> f64) -> [(&'static str, Vec<f64>); 4] {
    let voigt = |t: &[[[S; 2]; 2]]| {
        t.iter()
            .flat_map(|s| [re(s[0][0]), re(s[1][1]), re(s[0][1])])
            .collect::<Vec<_>>()
    };
    [
        ("v", z.v.iter().flatten().map(|&s| re(s)).collect()),
        ("rho", z.rho.iter().map(|&s| re(s)).collect()),
        ("sigma", voigt(&z.sigma)),
        ("tau", voigt(&z.tau)),
    ]
}

/// Largest relative difference from a golden record over the fields, and the worst field.
fn golden_err<S: Scalar>(
    z: &State<S, 2>,
    want: &serde_json::Value,
    re: impl Fn(S) -> f64,
) -> (f64, &'static str) {
    fields(z, re)
        .into_iter()
        .map(|(name, got)| (field_err(&got, &numbers(&want[name])), name))
        .fold((0.0, "-"), |m, e| if e.0 > m.0 { e } else { m })
}

#[test]
fn rate_matches_the_golden_data() {
    let g = golden();
    let cases = g["cases"].as_array().unwrap();
    // one workspace for every configuration: leftovers of another model must not matter
    let mut ws = RateWorkspace::<f64>::new();
    let mut out_ws = State::<_, 2>::default();
    let mut checked = 0;
    let cfgs = configs();
    assert_eq!(
        cfgs.len(),
        cases.len(),
        "configurations differ from the golden file"
    );
    for ((label, p, lat), want) in cfgs.into_iter().zip(cases) {
        assert_eq!(want["label"].as_str().unwrap(), label);
        let (model, z) = case(p, lat.as_ref());
        let mut fresh = State::<_, 2>::default();
        model.rate(&z, &mut fresh).unwrap();
        let (e, f) = golden_err(&fresh, want, |s| s);
        assert!(
            e <= TOL,
            "{label}: rate differs from the golden data in {f} by {e:e}"
        );
        model.rate_with(&z, &mut out_ws, &mut ws).unwrap();
        let (e, f) = golden_err(&out_ws, want, |s| s);
        assert!(e <= TOL, "{label}: rate_with differs in {f} by {e:e}");
        // the parts separately, as the solver asks for them
        let mut acc = vec![[f64::NAN; 2]; z.x.len()];
        let out = RateOut {
            v: Some(&mut acc),
            ..Default::default()
        };
        model.rate_into(z.view(), out, &mut ws).unwrap();
        let flat = |v: &[[f64; 2]]| v.iter().flatten().copied().collect::<Vec<_>>();
        let e = field_err(&flat(&acc), &numbers(&want["v"]));
        assert!(e <= TOL, "{label}: accelerations alone differ by {e:e}");
        let mut aux = State::<_, 2>::zeros_like(&z);
        aux.rho.fill(f64::NAN);
        let out = RateOut {
            aux: aux.as_rate_out().aux,
            ..Default::default()
        };
        model.rate_into(z.view(), out, &mut ws).unwrap();
        for (name, got) in fields(&aux, |s| s).into_iter().skip(1) {
            let e = field_err(&got, &numbers(&want[name]));
            assert!(e <= TOL, "{label}: {name} rate alone differs by {e:e}");
        }
        // the comparison is not vacuous: the accelerations are nonzero
        assert!(fresh.v.iter().flatten().any(|a| a.abs() > 1e-8), "{label}");
        // an integrated stress stays symmetric: the rate is exactly symmetric
        for t in fresh.sigma.iter().chain(&fresh.tau) {
            assert_eq!(t[0][1].to_bits(), t[1][0].to_bits(), "{label}");
        }
        checked += 1;
    }
    assert!(checked >= 70, "{checked} configurations");
}

/// Dual numbers (the linearisation): value and derivative parts agree.
#[test]
fn rate_matches_the_golden_data_in_dual_numbers() {
    let g = golden();
    let duals = g["duals"].as_array().unwrap();
    let mut ws = RateWorkspace::<Dual>::new();
    let mut out = State::<_, 2>::default();
    let mut checked = 0;
    for ((label, p, lat), want) in configs().into_iter().step_by(5).zip(duals) {
        assert_eq!(want["label"].as_str().unwrap(), label);
        let (model, z) = case(p, lat.as_ref());
        let mut zd: State<Dual, 2> = z.map(Dual::cst);
        zd.x[17][0].d = 1.0;
        zd.v[23][1].d = 0.5;
        if !zd.rho.is_empty() {
            zd.rho[30].d = -0.7;
        }
        model.rate_with(&zd, &mut out, &mut ws).unwrap();
        let (e, f) = golden_err(&out, &want["value"], |s: Dual| s.v);
        assert!(e <= TOL, "{label}: value part differs in {f} by {e:e}");
        let (e, f) = golden_err(&out, &want["tangent"], |s: Dual| s.d);
        assert!(e <= TOL, "{label}: derivative part differs in {f} by {e:e}");
        assert!(out.v.iter().flatten().any(|a| a.d.abs() > 1e-8), "{label}");
        checked += 1;
    }
    assert_eq!(checked, duals.len());
}

/// The old solver step (state split into flat copies, joined back, the rate with a fresh output
/// per call) as a second-order system for the shared integrator.
struct ReferenceSys<'a> {
    model: &'a Model<2>,
    template: &'a State<f64, 2>,
    fixed: &'a [bool],
    frozen: bool,
    aux: Vec<sphstab::forms::Comp>,
}

impl ReferenceSys<'_> {
    fn join(&self, x: &[f64], v: &[f64], q: &[f64]) -> State<f64, 2> {
        let n = self.template.x.len();
        let mut z = self.template.clone();
        for i in 0..n {
            z.x[i] = [x[2 * i], x[2 * i + 1]];
            z.v[i] = [v[2 * i], v[2 * i + 1]];
        }
        for (k, &c) in self.aux.iter().enumerate() {
            for i in 0..n {
                z.set(c, i, q[k * n + i]);
            }
        }
        z
    }
    fn rate(&self, x: &[f64], v: &[f64], q: &[f64]) -> State<f64, 2> {
        let z = self.join(x, v, q);
        let mut out = State::<_, 2>::default();
        self.model.rate(&z, &mut out).unwrap();
        out
    }
}

impl sphstab::integrator::SecondOrderSystem<f64> for ReferenceSys<'_> {
    fn accel(&self, x: &[f64], v: &[f64], q: &[f64], a: &mut [f64]) {
        let out = self.rate(x, v, q);
        for (i, ai) in out.v.iter().enumerate() {
            let keep = if self.fixed[i] { 0.0 } else { 1.0 };
            a[2 * i] = ai[0] * keep;
            a[2 * i + 1] = ai[1] * keep;
        }
    }
    fn accel_depends_on_velocity(&self) -> bool {
        self.model.p.av.is_some()
    }
    fn qrate(&self, x: &[f64], v: &[f64], q: &[f64], r: &mut [f64]) {
        let out = self.rate(x, v, q);
        let n = self.template.x.len();
        for (k, &c) in self.aux.iter().enumerate() {
            for i in 0..n {
                r[k * n + i] = if self.fixed[i] && self.frozen {
                    0.0
                } else {
                    out.get(c, i)
                };
            }
        }
    }
}

/// Run<2>'s in-place step reproduces the old split/join step: 6 steps of an open elastic block
/// (Jaumann, AV, artificial stress) with a frozen fixed frame, a hydro mixed form, and a
/// total-Lagrangian block.
#[test]
fn in_place_step_matches_the_split_join_step() {
    use sphstab::forms::FieldKind;
    use sphstab::integrator::{Scratch, kdk_step};
    use sphstab::solver::{BoundaryDensity, Run};
    let elastic = Material::elastic(1.0, 0.3, ObjectiveRate::Jaumann).unwrap();
    let mut p1 = params(FormKind::Classical, ShapeFamily::Sph, elastic, "m4");
    p1.av = Some(ArtificialViscosity {
        alpha: 1.0,
        beta: 1.0,
        sound_speed: 1.0,
        approaching_only: true,
    });
    p1.art_stress = Some(ArtificialStress {
        eps: 0.3,
        n: 4,
        spacing: 1.0,
    });
    let p2 = params(
        FormKind::Lnl,
        ShapeFamily::Sph,
        Material::Hydro { bulk: 1.0 },
        "m4",
    );
    let p3 = params(FormKind::TotalLagrangian, ShapeFamily::Sph, elastic, "m4");
    for (p, boundary) in [
        (p1, BoundaryDensity::Frozen),
        (p2, BoundaryDensity::Evolve),
        (p3, BoundaryDensity::Evolve),
    ] {
        let (model, z) = case(p, None);
        let x0 = z.x.clone();
        let n = z.x.len();
        let fixed: Vec<bool> = (0..n).map(|i| i % 9 == 0 || i < 9).collect();
        let aux: Vec<_> = p
            .form
            .comps(2, &p.material)
            .into_iter()
            .filter(|c| c.kind() == FieldKind::Auxiliary)
            .collect();
        // reference: flat copies, split before and joined after every step
        let mut zr = z.clone();
        let mut scratch = Scratch::default();
        for _ in 0..6 {
            let mut x: Vec<f64> = zr.x.iter().flatten().copied().collect();
            let mut v: Vec<f64> = zr.v.iter().flatten().copied().collect();
            let mut q = Vec::new();
            for &c in &aux {
                q.extend((0..n).map(|i| zr.get(c, i)));
            }
            let sys = ReferenceSys {
                model: &model,
                template: &zr,
                fixed: &fixed,
                frozen: boundary == BoundaryDensity::Frozen,
                aux: aux.clone(),
            };
            kdk_step(&sys, &mut x, &mut v, &mut q, 0.2, &mut scratch);
            zr = sys.join(&x, &v, &q);
        }
        let mut run = Run::<2>::new(model, z, fixed, boundary).unwrap();
        for _ in 0..6 {
            run.step(0.2).unwrap();
        }
        let (e, f) = state_err(&run.z, &zr, |s| s);
        assert!(e <= TOL, "{}: state differs in {f} by {e:e}", p.form.name());
        let moved = run
            .z
            .x
            .iter()
            .zip(&x0)
            .any(|(a, b)| (a[0] - b[0]).abs() > 1e-3);
        assert!(moved, "{}: nothing moved", p.form.name());
    }
}
