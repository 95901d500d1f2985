//! The 1D solver's time loop does not allocate (issue 13, item 5): a counting global allocator
//! sees no allocation in 10 steps after 2 warm-up steps (the buffers grow in the first step),
//! for the forms the 1D solver integrates — classical with artificial viscosity and δ-SPH
//! density diffusion, lnl (two stresses), total-lagrangian, eulerian stress points, eulerian
//! nodal, lagrangian stress points, least squares (consistent mass, open and periodic) — with
//! `kdk` and `rk4` (and `verlet-euler` for one form).
//!
//! The forms of every dimension build their stencils with rayon, which allocates a little when
//! work is *injected* into its pool from outside (tests/no_alloc/solver2d.rs); as there, the steps run
//! inside one `ThreadPool::install`, where the count must be exactly zero. The pool's worker
//! threads still allocate now and then on their own, depending on timing (crossbeam's epoch
//! bags and deque buffers grow when threads steal from each other, which the machine's load
//! decides: one run in ~12 saw 1–2 such allocations in 10 steps). So each case counts three
//! consecutive windows of 10 steps and the fewest must be zero: an allocation the solver makes
//! per step (or per particle) shows in every window.
//!
//! Everything runs in one test function: the counter is global, and tests of one binary run in
//! parallel.

use crate::allocations;
use sphstab::forms::{
    ArtificialViscosity, DensityDiffusion, DiffusionForm, FormKind, Material, Model, ModelParams,
};
use sphstab::integrator::Integrator;
use sphstab::kernel;
use sphstab::shape::KernelParams;
use sphstab::solver::Run;

/// A chain of `n` particles (Δx = 1, ρ0 = 1, C = 1), periodic or with 3 fixed layers at each
/// end, with a smooth velocity field.
fn chain(form: FormKind, n: usize, periodic: bool, av: bool, integ: Integrator) -> Run<1> {
    let p = ModelParams {
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
        art_stress: None,
        av: av.then_some(ArtificialViscosity {
            alpha: 1.0,
            beta: 2.0,
            sound_speed: 1.0,
            approaching_only: true,
        }),
        diffusion: av.then_some(DensityDiffusion {
            delta: 0.1,
            form: DiffusionForm::Antuono,
            sound_speed: 1.0,
        }),
    };
    let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let x_ref: Vec<[f64; 1]> = x.iter().map(|&xi| [xi]).collect();
    let period = periodic.then_some([[n as f64]]);
    let model = Model::new(p, x_ref, vec![1.0; n], 1.0, 0.1, period).unwrap();
    let mut z = model.rest_state(1.0);
    for (v, &xi) in z.v.iter_mut().zip(&x) {
        *v = [0.05 * (2.0 * std::f64::consts::PI * xi / n as f64).sin()];
    }
    let fixed = if periodic { 0 } else { 3 };
    let prescribed: Vec<Option<[f64; 1]>> = (0..n)
        .map(|i| (i < fixed || i + fixed >= n).then_some([0.0]))
        .collect();
    let mut run = Run::with_prescribed(model, z, &prescribed).unwrap();
    run.set_integrator(integ);
    run
}

/// Allocations in 10 steps after 2 warm-up steps: the fewest over three consecutive windows of
/// 10 steps (module docs).
fn count(run: &mut Run<1>) -> u64 {
    for _ in 0..2 {
        run.step(0.2).unwrap();
    }
    (0..3)
        .map(|_| {
            let before = allocations();
            for _ in 0..10 {
                run.step(0.2).unwrap();
            }
            allocations() - before
        })
        .min()
        .unwrap()
}

pub fn the_1d_time_loop_does_not_allocate() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let kdk = Integrator::Kdk;
    let rk4 = Integrator::Rk4;
    // the pool's own first-use allocations (its threads' deques and epoch bags grow in the
    // first parallel loops they run) are not the solver's: warm the pool up first
    pool.install(|| {
        let mut run = chain(FormKind::Classical, 200, true, true, kdk);
        for _ in 0..20 {
            run.step(0.2).unwrap();
        }
    });
    let cases = [
        (FormKind::Classical, true, true, kdk),
        (FormKind::Classical, true, true, rk4),
        (
            FormKind::Classical,
            false,
            true,
            Integrator::VerletEuler { every: 5 },
        ),
        (FormKind::Lnl, false, false, kdk),
        (FormKind::TotalLagrangian, false, false, kdk),
        (FormKind::TotalLagrangian, true, false, rk4),
        (FormKind::EulerianStressPoints, true, false, kdk),
        (FormKind::EulerianStressPoints, false, false, rk4),
        (FormKind::EulerianNodal, false, false, kdk),
        (FormKind::LagrangianStressPoints, true, false, kdk),
        (FormKind::LagrangianStressPoints, false, false, rk4),
        (FormKind::LeastSquares, true, false, kdk),
        (FormKind::LeastSquares, false, false, rk4),
    ];
    for (form, periodic, av, integ) in cases {
        let mut run = chain(form, 200, periodic, av, integ);
        let n = pool.install(|| count(&mut run));
        assert_eq!(
            n,
            0,
            "{} ({}, {}): {n} allocations in 10 steps",
            form.name(),
            if periodic { "periodic" } else { "open" },
            integ.name()
        );
    }
}
