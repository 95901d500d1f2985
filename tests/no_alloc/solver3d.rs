//! The 3D solver's time loop does not allocate either: a counting global allocator sees no
//! allocation in 10 steps after 2 warm-up steps on a periodic 3D box (the `throughput --dim 3`
//! block), for the classical form with a Jaumann elastic material and artificial viscosity,
//! for a hydrodynamic material with and without viscosity, for a mixed form and for the
//! total-Lagrangian form.
//!
//! As in tests/no_alloc/solver2d.rs (2D): inside one `ThreadPool::install` the count must be exactly
//! zero; from the test thread on the global pool (where rayon's injector may take a block now
//! and then: a block every 63 injected jobs, a step injecting a fixed number of parallel loops)
//! it must not depend on the number of particles: at most one block per step, and the counts
//! at 7³ and 9³ within one of each other (which run crosses a 63-job boundary depends on how
//! many jobs were injected before it, not on N).
//! Everything runs in one test function: the counter is global.

use crate::allocations;
use sphstab::forms::{FormKind, ObjectiveRate};
use sphstab::kernel;
use sphstab::solver::Run3D;
use sphstab::solver::throughput::{BlockMaterial, Domain, ThroughputConfig, build_block_nd};

/// The periodic n³ box of `throughput --dim 3` (m4, h = 1.3Δx, smooth velocity field).
fn block(n: usize, form: FormKind, material: BlockMaterial, av: bool) -> Run3D {
    let mut cfg = ThroughputConfig::new(kernel::by_name("m4").unwrap()).with_dim(3);
    assert_eq!(cfg.domain, Domain::Periodic);
    cfg.form = form;
    cfg.shape = form.default_shape_2d();
    cfg.material = material;
    cfg.av = av.then_some((1.0, 1.0));
    build_block_nd::<3>(&cfg, n).unwrap()
}

/// Allocations during 10 steps after 2 warm-up steps; `pool`: all 10 inside one `install`.
fn count(mut run: Run3D, pool: Option<&rayon::ThreadPool>) -> u64 {
    run.step(0.2).unwrap();
    run.step(0.2).unwrap();
    let steps = |run: &mut Run3D| {
        for _ in 0..10 {
            run.step(0.2).unwrap();
        }
    };
    let before = allocations();
    match pool {
        Some(p) => p.install(|| steps(&mut run)),
        None => steps(&mut run),
    }
    let n = allocations() - before;
    // the run did something
    assert!(run.max_free_speed() > 1e-4 && run.steps == 12);
    n
}

pub fn time_loop_does_not_allocate_in_3d() {
    let jaumann = BlockMaterial::Elastic {
        poisson: 0.3,
        rate: ObjectiveRate::Jaumann,
    };
    let hydro = BlockMaterial::Hydro;
    let cases = [
        (
            "classical elastic (Jaumann) + AV",
            FormKind::Classical,
            jaumann,
            true,
        ),
        ("classical hydro", FormKind::Classical, hydro, false),
        ("classical hydro + AV", FormKind::Classical, hydro, true),
        ("lnl elastic (Jaumann) + AV", FormKind::Lnl, jaumann, true),
        (
            "total-lagrangian elastic",
            FormKind::TotalLagrangian,
            jaumann,
            false,
        ),
    ];
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    // every worker starts (and allocates its thread-locals) before anything is counted
    pool.broadcast(|_| ());
    for (name, form, material, av) in cases {
        for n in [7, 9] {
            let inside = count(block(n, form, material, av), Some(&pool));
            eprintln!("{name}, {n}³, inside one install: {inside} allocations in 10 steps");
            assert_eq!(inside, 0, "{name}, {n}³: the time loop allocated");
        }
        let small = count(block(7, form, material, av), None);
        let large = count(block(9, form, material, av), None);
        eprintln!("{name}, global pool from the test thread: {small} (7³), {large} (9³)");
        assert!(
            small <= 10 && large <= 10,
            "{name}: more than one allocation per step on the global pool"
        );
        assert!(
            small.abs_diff(large) <= 1,
            "{name}: allocations grow with N"
        );
    }
}
