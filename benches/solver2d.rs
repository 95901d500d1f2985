//! Criterion benches of the 2D/3D solver (issue 13, item 4; issue 28): one `kdk` step of the
//! open 200×200 elastic block of `sphstab throughput` (classical m4, Jaumann, AV, artificial
//! stress) on one thread and on two, and one step of the 3D periodic 22³ box (classical m4,
//! elastic, AV) on one thread; the 2D block moving at 0.1 c with the pair list reused and with a
//! full neighbour search at every build; and the pieces of one rate evaluation of the moving 2D
//! block and 3D box (the pair loop of the accelerations alone, with a pair refresh, with a full
//! neighbour search). `cargo bench --features bench --bench solver2d`; divide the time per step
//! by the particle count (40,000 and 10,648) for the time per particle-step of `sphstab
//! throughput`.

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main};
use sphstab::forms::{RateOut, RateWorkspace, State};
use sphstab::kernel;
use sphstab::solver::Run;
use sphstab::studies::throughput::{ThroughputConfig, build_block, build_block_nd};

/// The pieces of one acceleration evaluation of `run` (issue 28), on one thread: the pair loop
/// alone (the same state evaluated again: the stencils are kept, nothing is searched or
/// refreshed), with a pair refresh (two states one step apart, alternated: each evaluation
/// recomputes the kernel data of the listed pairs; two evaluations per iteration), and with a
/// full neighbour search at each of them (pair reuse off). The differences are what a refresh
/// and a search cost on top of the loop.
fn rate_pieces<const D: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    run: &mut Run<D>,
    dt: f64,
) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    pool.install(|| run.step(dt).unwrap());
    let a: State<f64, D> = run.z.clone();
    pool.install(|| run.step(dt).unwrap());
    let b: State<f64, D> = run.z.clone();
    let model = &run.model;
    let mut acc = vec![[0.0; D]; a.x.len()];
    let mut ws = RateWorkspace::<f64, D>::new();
    let mut eval = |z: &State<f64, D>, ws: &mut RateWorkspace<f64, D>| {
        let out = RateOut {
            v: Some(&mut acc),
            ..Default::default()
        };
        pool.install(|| model.rate_into(z.view(), out, ws).unwrap());
    };
    eval(&a, &mut ws);
    g.bench_function(format!("{name}: pair loop of the accelerations"), |bch| {
        bch.iter(|| eval(&a, &mut ws))
    });
    g.bench_function(
        format!("{name}: pair refresh + pair loop, x2 (two states)"),
        |bch| {
            bch.iter(|| {
                eval(&b, &mut ws);
                eval(&a, &mut ws)
            })
        },
    );
    ws.set_pair_reuse(false);
    g.bench_function(
        format!("{name}: full neighbour search + pair loop, x2 (two states)"),
        |bch| {
            bch.iter(|| {
                eval(&b, &mut ws);
                eval(&a, &mut ws)
            })
        },
    );
}

fn benches(c: &mut Criterion) {
    let m4 = kernel::by_name("m4").unwrap();
    let cfg = ThroughputConfig::new(m4);
    let mut g = c.benchmark_group("solver");
    g.sample_size(10);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut run = build_block(&cfg, 200).unwrap();
        pool.install(|| run.step(cfg.dt).unwrap());
        g.bench_function(
            format!("step 2D, open 200x200 elastic block, AV + art. stress, {threads} thread(s)"),
            |b| b.iter(|| pool.install(|| run.step(cfg.dt).unwrap())),
        );
    }
    // the regime users run (issue 28): the block moving at up to 0.1 c, its pairs changing;
    // with the pair list reused (skin) and with a full neighbour search at every build, so the
    // difference is the cost of the searches the reuse saves
    let mut moving = ThroughputConfig::new(m4);
    moving.amplitude = 0.1;
    let pool1 = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for reuse in [true, false] {
        let mut run = build_block(&moving, 200).unwrap();
        run.set_pair_reuse(reuse);
        pool1.install(|| run.step(moving.dt).unwrap());
        g.bench_function(
            format!(
                "step 2D, open 200x200 elastic block at 0.1 c, {}, 1 thread",
                if reuse {
                    "pair list reused"
                } else {
                    "full search at every build"
                }
            ),
            |b| b.iter(|| pool1.install(|| run.step(moving.dt).unwrap())),
        );
    }
    let cfg3 = ThroughputConfig::new(m4).with_dim(3);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut run3 = build_block_nd::<3>(&cfg3, 22).unwrap();
    pool.install(|| run3.step(cfg3.dt).unwrap());
    g.bench_function("step 3D, periodic 22^3 elastic box, AV, 1 thread", |b| {
        b.iter(|| pool.install(|| run3.step(cfg3.dt).unwrap()))
    });
    g.finish();
    let mut g = c.benchmark_group("rate pieces");
    g.sample_size(10);
    let mut run = build_block(&moving, 200).unwrap();
    rate_pieces(&mut g, "2D 200x200 block at 0.1 c", &mut run, moving.dt);
    let mut moving3 = ThroughputConfig::new(m4).with_dim(3);
    moving3.amplitude = 0.1;
    let mut run3 = build_block_nd::<3>(&moving3, 22).unwrap();
    rate_pieces(&mut g, "3D 22^3 box at 0.1 c", &mut run3, moving3.dt);
    g.finish();
}

criterion_group!(solver2d, benches);
criterion_main!(solver2d);
