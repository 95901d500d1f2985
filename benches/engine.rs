//! Criterion benches: a 1,024-point dispersion curve, a 256-cell atlas, the three routes to ω²
//! over 512 κ of one linearised cell (per-κ Jacobian matrix, tabulated phases, cosine series),
//! the linearisation of one 1D cell, the default 2D and 3D queries, a 128×128 2D growth map,
//! one solver step of a periodic 200×200 hydro patch, and one step of the open 200×200 elastic
//! block of `sphstab throughput` (its defaults). `cargo bench --features bench --bench engine` runs them.

use criterion::{Criterion, criterion_group, criterion_main};
use sphstab::analysis::dispersion;
use sphstab::analysis::{MaterialSpec, Query, growth_map, query};
use sphstab::forms::{FormKind, Material, Model, ModelParams};
use sphstab::kernel;
use sphstab::lattice::Lattice;
use sphstab::shape::KernelParams;
use sphstab::shape::ShapeFamily;
use sphstab::solver::{BoundaryDensity, Run};
use sphstab::studies::atlas::AtlasConfig;
use sphstab::studies::throughput::{ThroughputConfig, build_block};
use sphstab::vonneumann::linearise::PhaseTable;

fn benches(c: &mut Criterion) {
    let m4 = kernel::by_name("m4").unwrap();
    let mut q = Query::<1>::new(FormKind::Classical, m4, 1.2, 0.01);
    q.grid = 1024;
    c.bench_function("dispersion 1D, 1024 points (classical m4)", |b| {
        b.iter(|| dispersion(&q, q.grid).unwrap())
    });

    // the three routes to ω² over a 512-point κ grid of one cell (issue 13, item 1)
    let mut qc = Query::<1>::new(FormKind::Classical, m4, 1.3, 0.05);
    qc.grid = 512;
    let lin = qc.chain().unwrap();
    let kappas = qc.kappas();
    let table = PhaseTable::new(&kappas, lin.reach());
    let series = lin.cosine_series().unwrap();
    let mut g1 = c.benchmark_group("omega2 over 512 kappa (classical m4 h 1.3)");
    g1.bench_function("per-kappa Jacobian matrix (pre-issue-13 route)", |b| {
        b.iter(|| kappas.iter().map(|&k| lin.omega2(k).0).sum::<f64>())
    });
    g1.bench_function("tabulated phases, reduced entries", |b| {
        b.iter(|| {
            (0..512)
                .map(|i| lin.omega2_tabulated(&table, i).0)
                .sum::<f64>()
        })
    });
    g1.bench_function("cosine series", |b| {
        b.iter(|| (0..512).map(|i| series.omega2(&table, i)).sum::<f64>())
    });
    g1.finish();
    c.bench_function("linearisation of one 1D cell (classical m4 h 1.3)", |b| {
        b.iter(|| qc.chain().unwrap())
    });
    let q2 = Query::<2>::new(FormKind::Classical, m4, 1.2, 0.01);
    c.bench_function(
        "query 2D, default (classical m4 elastic, 64x64 zone)",
        |b| b.iter(|| query(&q2).unwrap()),
    );
    let q3 = Query::<3>::new(FormKind::Classical, m4, 1.2, 0.01);
    c.bench_function(
        "query 3D, default (classical m4 elastic sc, 16^3 zone)",
        |b| b.iter(|| query(&q3).unwrap()),
    );

    let acfg = AtlasConfig {
        forms: vec!["classical".into()],
        kernels: vec!["m4".into()],
        h_points: 16,
        stress_points: 16,
        ..Default::default()
    };
    let mut g0 = c.benchmark_group("atlas");
    g0.sample_size(10);
    g0.bench_function("atlas 1D, 256 cells x 512 kappa (classical m4)", |b| {
        b.iter(|| sphstab::studies::atlas::run(&acfg, ()).unwrap())
    });
    g0.finish();

    let mut q2 = Query::<2>::new(FormKind::Classical, m4, 1.2, 0.01);
    q2.material = MaterialSpec::Hydro;
    let q2 = q2;
    let mut g = c.benchmark_group("slow");
    g.sample_size(10);
    g.bench_function("growth map 2D, 128x128 (classical m4 hydro)", |b| {
        b.iter(|| growth_map(&q2, 128, sphstab::analysis::Plane::Xy, &()).unwrap())
    });

    let p = ModelParams {
        form: FormKind::Classical,
        shape: ShapeFamily::Sph,
        kp: KernelParams { kernel: m4, h: 1.3 },
        material: Material::Hydro { bulk: 1.0 },
        rho0: 1.0,
        c_partition: 0.5,
        av: None,
        art_stress: None,
        diffusion: None,
        alpha_s: 0.0,
        ls_length: 1.0,
        hourglass: None,
    };
    let model = Model::<2>::periodic_patch(
        p,
        &Lattice::<2>::square(1.0).unwrap(),
        1.0,
        [200, 200],
        1.0,
        0.0,
    )
    .unwrap();
    let z = model.rest_state(1.0);
    let n = z.x.len();
    let mut run = Run::<2>::new(model, z, vec![false; n], BoundaryDensity::Evolve).unwrap();
    run.z.v[n / 2][0] = 1e-6;
    g.bench_function("solver step 2D, 200x200 (classical m4 hydro)", |b| {
        b.iter(|| run.step(0.1).unwrap())
    });
    let cfg = ThroughputConfig::new(m4);
    let mut block = build_block(&cfg, 200).unwrap();
    g.bench_function(
        "solver step 2D, open 200x200 block (classical m4 elastic Jaumann, AV, art. stress)",
        |b| b.iter(|| block.step(cfg.dt).unwrap()),
    );
    g.finish();
}

criterion_group!(engine, benches);
criterion_main!(engine);
