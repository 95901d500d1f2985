//! Reusing the pairs of the last full stencil build (workspace module docs, "Reusing the
//! pairs") changes nothing: every run below is stepped twice, once with the reuse (default) and
//! once with a full neighbour search at every build (`Run::set_pair_reuse(false)`), and the
//! final states must be **bitwise** equal — positions, velocities, densities, stresses.
//!
//! The runs cover what could break the proof: small motions (reuse nearly every build), large
//! ones (a particle moves several Δx: pairs change and particles change cells, so full builds
//! must be triggered), an exponentially growing Swegle instability (any last-bit difference
//! would be amplified to a visible one), an open domain whose cell-list origin moves, periodic
//! boxes, and 3D. Each run also checks that both kinds of build happened where expected, so the
//! test cannot pass by never reusing.

use sphstab::forms::FormKind;
use sphstab::kernel;
use sphstab::solver::Run;
use sphstab::studies::swegle::SwegleConfig;
use sphstab::studies::throughput::{BlockMaterial, Domain, ThroughputConfig, build_block_nd};

/// Bits of the whole state.
fn bits<const D: usize>(run: &Run<D>) -> Vec<u64> {
    let z = &run.z;
    let mut b: Vec<u64> = Vec::new();
    b.extend(z.x.iter().flatten().map(|c| c.to_bits()));
    b.extend(z.v.iter().flatten().map(|c| c.to_bits()));
    b.extend(z.rho.iter().map(|c| c.to_bits()));
    b.extend(z.sigma.iter().flatten().flatten().map(|c| c.to_bits()));
    b.extend(z.tau.iter().flatten().flatten().map(|c| c.to_bits()));
    b
}

/// Steps `make()` `steps` times with and without the reuse; returns the (full, refreshed)
/// build counts of the run with reuse, after asserting bitwise equality.
fn same_with_and_without<const D: usize>(
    what: &str,
    make: impl Fn() -> Run<D>,
    dt: f64,
    steps: usize,
) -> (u64, u64) {
    let mut a = make();
    let mut b = make();
    b.set_pair_reuse(false);
    for s in 0..steps {
        let ra = a.step(dt);
        let rb = b.step(dt);
        assert_eq!(ra.is_ok(), rb.is_ok(), "{what}: step {s}");
        assert!(
            bits(&a) == bits(&b),
            "{what}: states differ after step {}",
            s + 1
        );
        if ra.is_err() {
            break;
        }
    }
    let (full_b, refr_b) = b.stencil_builds();
    assert_eq!(refr_b, 0, "{what}: reuse switched off still refreshed");
    let (full, refr) = a.stencil_builds();
    assert_eq!(full + refr, full_b, "{what}: the same number of builds");
    eprintln!("{what}: {steps} steps, {full} full builds, {refr} pair refreshes, bitwise equal");
    (full, refr)
}

fn block(dim: usize, domain: Domain, amplitude: f64) -> ThroughputConfig {
    let mut c = ThroughputConfig::new(kernel::by_name("m4").unwrap()).with_dim(dim);
    c.domain = domain;
    c.amplitude = amplitude;
    c
}

#[test]
fn small_motion_reuses_and_matches() {
    // the `throughput` block: elastic, AV, artificial stress; displacements ~1e-4 Δx per step
    let cfg = block(2, Domain::Open, 1e-3);
    let (full, refr) = same_with_and_without(
        "2D open block",
        || build_block_nd::<2>(&cfg, 24).unwrap(),
        cfg.dt,
        60,
    );
    assert!(
        refr > 10 * full,
        "2D open block: {full} full, {refr} refreshed"
    );
}

#[test]
fn lattice_neighbours_on_the_support_radius_reuse_and_match() {
    // h/Δx = 1 with the cubic spline (ζ = 2): the lattice's second neighbours sit exactly on
    // the support radius, so no margin to the support exists; the skin of the list reuses the
    // pairs all the same (the margin rule this replaced rebuilt at every evaluation)
    for (dim, domain) in [(2, Domain::Open), (3, Domain::Periodic)] {
        let mut cfg = block(dim, domain, 1e-3);
        cfg.h_over_dx = 1.0;
        let what = format!("{dim}D {domain:?} h = 1.0Δx");
        let (full, refr) = if dim == 2 {
            same_with_and_without(&what, || build_block_nd::<2>(&cfg, 16).unwrap(), cfg.dt, 40)
        } else {
            same_with_and_without(&what, || build_block_nd::<3>(&cfg, 8).unwrap(), cfg.dt, 20)
        };
        assert!(refr > 10 * full, "{what}: {full} full, {refr} refreshed");
    }
}

#[test]
fn every_skin_gives_the_same_bits() {
    // the skin changes how many pairs are listed (zero data beyond the support) and how
    // often the list is rebuilt, never a bit of the result; A = 0.1: the list is rebuilt
    // often at every skin
    let cfg = block(2, Domain::Open, 0.1);
    for skin in [0.0, 0.02, 0.3, 1.0] {
        let what = format!("2D open A = 0.1, skin {skin}");
        let (full, refr) = same_with_and_without(
            &what,
            || {
                let mut run = build_block_nd::<2>(&cfg, 16).unwrap();
                run.set_skin(skin);
                run
            },
            cfg.dt,
            80,
        );
        if skin == 0.0 {
            assert_eq!(refr, 0, "{what}: no skin, no reuse");
        } else {
            assert!(
                full > 1 && refr > 1,
                "{what}: {full} full, {refr} refreshed"
            );
        }
    }
}

#[test]
fn large_motion_rebuilds_and_matches() {
    // velocity amplitude 0.1c (the largest `throughput` takes): particles move ~Δx over the
    // run, pairs and cells change
    for (form, material) in [
        (FormKind::Classical, None),
        (FormKind::Nonlocal, Some(BlockMaterial::Hydro)),
    ] {
        for domain in [Domain::Open, Domain::Periodic] {
            let mut cfg = block(2, domain, 0.1);
            cfg.form = form;
            cfg.shape = form.default_shape_in(2);
            if let Some(m) = material {
                cfg.material = m;
            }
            if form != FormKind::Classical {
                cfg.art_stress = None;
            }
            let what = format!("2D {form:?} {domain:?} A = 0.1");
            let (full, refr) = same_with_and_without(
                &what,
                || build_block_nd::<2>(&cfg, 16).unwrap(),
                cfg.dt,
                150,
            );
            assert!(
                full > 5 && refr > 5,
                "{what}: {full} full, {refr} refreshed"
            );
        }
    }
}

#[test]
fn three_d_matches() {
    let cfg = block(3, Domain::Periodic, 0.1);
    let (full, refr) = same_with_and_without(
        "3D periodic box A = 0.1",
        || build_block_nd::<3>(&cfg, 8).unwrap(),
        cfg.dt,
        40,
    );
    assert!(full > 1 && refr > 1, "3D: {full} full, {refr} refreshed");
}

#[test]
fn swegle_instability_matches_bitwise() {
    // the tensile instability grows from a 1e-10 kick by orders of magnitude: a last-bit
    // difference anywhere would grow with it
    let mut cfg = SwegleConfig::new(
        FormKind::Classical,
        kernel::by_name("m4").unwrap(),
        1.2,
        0.95,
    );
    cfg.size = 15;
    let c = cfg.sound_speed();
    let dt = cfg.dt * cfg.dx / c;
    let (full, refr) = same_with_and_without("Swegle box", || cfg.build::<2>().unwrap(), dt, 1200);
    // the run did go unstable (its speed grew from the kick), and both kinds of build occurred
    let mut run = cfg.build::<2>().unwrap();
    for _ in 0..1200 {
        if run.step(dt).is_err() {
            break;
        }
    }
    let vmax = run.max_free_speed();
    assert!(
        vmax > 1e3 * cfg.kick,
        "Swegle box did not grow: max |v| = {vmax:e}"
    );
    assert!(
        full >= 1 && refr > 100,
        "Swegle box: {full} full, {refr} refreshed"
    );
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    // every particle's sums are gathered by one thread in a fixed neighbour order (no scatter,
    // no atomics), so a run on 1 thread and on 3 is bitwise the same; the moving 2D block
    // (0.1 c: full searches and refreshes both happen) and the 3D box
    let cfg2 = block(2, Domain::Open, 0.1);
    let cfg3 = block(3, Domain::Periodic, 0.1);
    let run_on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut a = build_block_nd::<2>(&cfg2, 24).unwrap();
            let mut b = build_block_nd::<3>(&cfg3, 9).unwrap();
            for _ in 0..40 {
                a.step(cfg2.dt).unwrap();
                b.step(cfg3.dt).unwrap();
            }
            assert!(
                a.stencil_builds().0 >= 2,
                "2D block: no full search after the first"
            );
            (bits(&a), bits(&b))
        })
    };
    let (one, three) = (run_on(1), run_on(3));
    assert!(one.0 == three.0, "2D block: 1 and 3 threads differ");
    assert!(one.1 == three.1, "3D box: 1 and 3 threads differ");
}
