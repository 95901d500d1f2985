//! Criterion benches of the 1D solver (issue 13, item 5): one time step of a 2,000-particle
//! open chain (kdk, Δt = 0.2 Δx/c, m4, h = 1.3Δx) for the classical, eulerian-stress-points,
//! total-lagrangian and least-squares forms (divide by 2,000 for ns per particle-step), and the
//! least-squares consistent-mass solve M a = f ([`BandedLu`]: factorisation and one solve) on
//! periodic chains of N = 10³, 10⁴, 10⁵ (O(N): the time per particle stays flat), and one step
//! of the classical chain per integrator (kdk, dkd, symplectic Euler, epec, rk4, euler).
//! `cargo bench --features bench --bench solver1d` runs them.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use sphstab::forms::{BandedLu, FormKind, MassOperator, Material, Model, ModelParams};
use sphstab::integrator::Integrator;
use sphstab::kernel;
use sphstab::shape::KernelParams;
use sphstab::solver::Run;

fn params(form: FormKind) -> ModelParams {
    ModelParams {
        form,
        shape: form.default_shape(),
        kp: KernelParams {
            kernel: kernel::by_name("m4").unwrap(),
            h: 1.3,
        },
        material: Material::bar(1.0),
        rho0: 1.0,
        c_partition: 0.5,
        alpha_s: 0.1,
        ls_length: 1.0,
        hourglass: None,
        av: None,
        art_stress: None,
        diffusion: None,
    }
}

/// An open chain of `n` particles, 3 fixed layers at each end, a smooth velocity field.
fn chain(form: FormKind, n: usize) -> Run<1> {
    let x: Vec<[f64; 1]> = (0..n).map(|i| [i as f64]).collect();
    let model = Model::new(params(form), x.clone(), vec![1.0; n], 1.0, 0.0, None).unwrap();
    let mut z = model.rest_state(1.0);
    for (v, &[xi]) in z.v.iter_mut().zip(&x) {
        *v = [1e-3 * (2.0 * std::f64::consts::PI * xi / n as f64).sin()];
    }
    let prescribed: Vec<Option<[f64; 1]>> = (0..n)
        .map(|i| (i < 3 || i + 3 >= n).then_some([0.0]))
        .collect();
    Run::with_prescribed(model, z, &prescribed).unwrap()
}

fn benches(c: &mut Criterion) {
    let mut g = c.benchmark_group("solver1d step, 2000 particles (kdk, m4)");
    for form in [
        FormKind::Classical,
        FormKind::EulerianStressPoints,
        FormKind::TotalLagrangian,
        FormKind::LeastSquares,
    ] {
        let mut run = chain(form, 2000);
        g.bench_function(form.name(), |b| b.iter(|| run.step(0.2).unwrap()));
    }
    g.finish();

    // the cost of one step per integrator on the same chain (classical, no viscosity): the
    // step-cost ratios behind the trade-off study's integrator rows
    let mut g = c.benchmark_group("solver1d step per integrator, 2000 particles (classical, m4)");
    for integ in [
        Integrator::Kdk,
        Integrator::Dkd,
        Integrator::SymplecticEulerVx,
        Integrator::Epec,
        Integrator::Rk4,
        Integrator::Euler,
    ] {
        let mut run = chain(FormKind::Classical, 2000);
        run.set_integrator(integ);
        g.bench_function(integ.name(), |b| b.iter(|| run.step(0.01).unwrap()));
    }
    g.finish();

    let mut g = c.benchmark_group("consistent mass (least-squares, periodic, m4 mls)");
    g.sample_size(10);
    for n in [1_000, 10_000, 100_000] {
        let x: Vec<[f64; 1]> = (0..n).map(|i| [i as f64]).collect();
        let model = Model::new(
            params(FormKind::LeastSquares),
            x,
            vec![1.0; n],
            1.0,
            0.0,
            Some([[n as f64]]),
        )
        .unwrap();
        let MassOperator::Consistent(rows) = model.mass_operator() else {
            unreachable!("least squares has a consistent mass")
        };
        g.bench_with_input(BenchmarkId::new("factorise", n), &n, |b, _| {
            b.iter(|| BandedLu::new(rows, true).unwrap())
        });
        let lu = BandedLu::new(rows, true).unwrap();
        let f: Vec<f64> = (0..n).map(|i| (0.37 * i as f64).sin()).collect();
        let (mut a, mut work) = (vec![0.0; n], Vec::new());
        g.bench_with_input(BenchmarkId::new("solve", n), &n, |b, _| {
            b.iter(|| lu.solve(&f, &mut a, &mut work))
        });
    }
    g.finish();
}

criterion_group!(solver1d, benches);
criterion_main!(solver1d);
