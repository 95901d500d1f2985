//! Criterion benches of the kernel guide (issue 25: `sphstab kernels --table` under 1 s): the
//! whole table through the library entry point the command calls ([`kernel_guide`] and
//! [`markdown`], default config: eleven kernels, h/Δx step 0.05) on the global rayon pool (one
//! thread per core, as the command runs) and on one thread; then each column of one kernel's
//! row on one thread (m4; Lucy for the 2D scan, whose ζ = 1 support scans the most h values).
//! `cargo bench --features bench --bench kernel_table`.

use criterion::{Criterion, criterion_group, criterion_main};
use sphstab::forms::FormKind;
use sphstab::kernel;
use sphstab::studies::kernel_guide::{
    GUIDE_FORMS, GUIDE_H, GuideConfig, WSTAR_K_STEP, compression_scan, kernel_guide, markdown,
    tensile_onset, time_step_cell,
};
use sphstab::studies::pairing::wstar_scan::sign_criterion_fast;

fn benches(c: &mut Criterion) {
    let cfg = GuideConfig::default();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut g = c.benchmark_group("kernel guide");
    g.sample_size(10);
    g.bench_function("kernels --table (all kernels, default pool)", |b| {
        b.iter(|| markdown(&kernel_guide(&cfg).unwrap()))
    });
    g.bench_function("kernels --table (all kernels, 1 thread)", |b| {
        b.iter(|| one.install(|| markdown(&kernel_guide(&cfg).unwrap())))
    });
    g.finish();

    let m4 = kernel::by_name("m4").unwrap();
    let lucy = kernel::by_name("lucy").unwrap();
    let h = cfg.h_grid();
    let mut g = c.benchmark_group("kernel guide columns, 1 thread");
    g.sample_size(10);
    g.bench_function("time step: 2 forms x 2 h (m4)", |b| {
        b.iter(|| {
            one.install(|| {
                for f in GUIDE_FORMS {
                    for hh in GUIDE_H {
                        time_step_cell(FormKind::by_name(f).unwrap(), m4, hh).unwrap();
                    }
                }
            })
        })
    });
    g.bench_function("compression 1D scan (m4)", |b| {
        b.iter(|| one.install(|| compression_scan(m4, 1, &h).unwrap()))
    });
    g.bench_function("compression 2D scan (lucy, 100 h)", |b| {
        b.iter(|| one.install(|| compression_scan(lucy, 2, &h).unwrap()))
    });
    g.bench_function("tensile onset at 2 h (m4)", |b| {
        b.iter(|| {
            one.install(|| {
                for hh in GUIDE_H {
                    tensile_onset(m4, hh).unwrap();
                }
            })
        })
    });
    g.bench_function("W* sign, 1D + 2D + 3D (m4)", |b| {
        b.iter(|| {
            for d in 1..=3 {
                sign_criterion_fast(m4, d, WSTAR_K_STEP);
            }
        })
    });
    g.finish();
}

criterion_group!(kernel_table, benches);
criterion_main!(kernel_table);
