//! Criterion bench of `eigen` (the eigenvalues of every dissipative mode, amplification and
//! cycle matrix) on the matrices the crate builds: 1D `lnl` Jacobians with viscosity and δ-SPH
//! (5 × 5), 3D `lnl` Jacobians with viscosity (19 × 19), 3D `kdk` amplification matrices
//! (19 × 19), 3D and 2D `verlet-euler` cycles with viscosity (35 × 35, 14 × 14) and the 1D
//! `verlet-euler` cycles of `tests/integrators.rs::verlet_euler_with_viscosity_long_cycles`
//! (7 × 7), each family timed as one batch (stalling and converging matrices in the proportion
//! the crate meets them), and the cycles on which nalgebra's first attempt stalls (`eigen`'s
//! retries). The set-up checks defective matrices (Jordan blocks) against their exact
//! eigenvalues and prints each family's size and how many of its matrices stall the first
//! attempt. `cargo bench --features bench --bench eigen` runs them. (The comparison with faer that removed it
//! from the dependencies is this bench at the commit before.)

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use nalgebra::DMatrix;
use num_complex::Complex64;
use sphstab::analysis::Query;
use sphstab::forms::{DiffusionForm, FormKind};
use sphstab::integrator::Integrator;
use sphstab::kernel;
use sphstab::vonneumann::amplification::Modes;
use sphstab::vonneumann::linearise::{eigen, eigen_stalls_first_attempt};
use std::f64::consts::PI;

/// Largest distance between eigenvalues of `a` and `b`, matched greedily.
fn distance(a: &[Complex64], b: &[Complex64]) -> f64 {
    let mut used = vec![false; b.len()];
    let mut worst: f64 = 0.0;
    for x in a {
        let (j, d) = (0..b.len())
            .filter(|&j| !used[j])
            .map(|j| (j, (x - b[j]).norm()))
            .fold((0, f64::INFINITY), |p, q| if q.1 < p.1 { q } else { p });
        used[j] = true;
        worst = worst.max(d);
    }
    worst
}

/// The matrix families: (name, matrices).
fn families() -> Vec<(String, Vec<DMatrix<Complex64>>)> {
    let m4 = kernel::by_name("m4").unwrap();
    let mut out = Vec::new();

    let mut q1 = Query::<1>::new(FormKind::Lnl, m4, 1.2, 0.01);
    q1.av = Some((1.0, 0.0));
    q1.diffusion = Some((0.1, DiffusionForm::Antuono));
    q1.grid = 256;
    let lin1 = q1.chain().unwrap();
    let mut ms: Vec<_> = q1.kappas().iter().map(|&k| lin1.jacobian(k)).collect();
    ms.push(lin1.jacobian(0.0));
    out.push(("1D lnl Jacobians, viscosity and δ-SPH".into(), ms));

    let mut q3 = Query::<3>::new(FormKind::Lnl, m4, 1.2, 0.01);
    q3.av = Some((1.0, 0.0));
    q3.grid = 5;
    let lin3 = q3.linearise_at(q3.stress).unwrap();
    let ks = q3.kgrid();
    let mut ms: Vec<_> = ks.iter().map(|&k| lin3.jacobian(k)).collect();
    ms.push(lin3.jacobian([0.0; 3]));
    out.push(("3D lnl Jacobians, viscosity".into(), ms));

    let ms = ks
        .iter()
        .map(|&k| Modes::amplification_with(&lin3, k, 0.2, Integrator::Kdk))
        .collect();
    out.push(("3D lnl kdk amplification matrices, viscosity".into(), ms));

    let ve = Integrator::VerletEuler { every: 40 };
    let ms = ks
        .iter()
        .take(40)
        .map(|&k| lin3.amplification_with(k, 0.05, ve))
        .collect();
    out.push(("3D lnl verlet-euler cycles (N_s 40), viscosity".into(), ms));

    let mut q2 = Query::<2>::new(FormKind::Nonlocal, m4, 1.2, 0.01);
    q2.av = Some((1.0, 0.0));
    q2.grid = 12;
    let lin2 = q2.linearise_at(q2.stress).unwrap();
    let ms = q2
        .kgrid()
        .iter()
        .map(|&k| lin2.amplification_with(k, 0.05, ve))
        .collect();
    out.push((
        "2D nonlocal verlet-euler cycles (N_s 40), viscosity".into(),
        ms,
    ));

    let mut qc = Query::<1>::new(FormKind::Nonlocal, m4, 1.3, 0.01);
    qc.av = Some((1.0, 0.0));
    let linc = qc.chain().unwrap();
    let mut ms = Vec::new();
    for every in [40, 100] {
        for dt in [0.02, 0.05] {
            for m in 1..32 {
                let k = 2.0 * PI * m as f64 / 64.0;
                let g = Modes::amplification_with(&linc, k, dt, Integrator::VerletEuler { every });
                if g.iter().all(|z| z.norm() < 1e300) {
                    ms.push(g);
                }
            }
        }
    }
    out.push((
        "1D nonlocal verlet-euler cycles (N_s 40, 100), viscosity".into(),
        ms,
    ));

    // the matrices on which nalgebra's first attempt stalls, from 1D and 2D verlet-euler cycles
    let mut ms = Vec::new();
    for every in [2, 3, 5, 10, 40, 100] {
        let integ = Integrator::VerletEuler { every };
        for dt in [0.02, 0.05, 0.1, 0.3] {
            for m in 1..64 {
                let k = PI * m as f64 / 64.0;
                ms.push(Modes::amplification_with(&linc, k, dt, integ));
            }
        }
    }
    for dt in [0.02, 0.1] {
        for every in [10, 100] {
            let integ = Integrator::VerletEuler { every };
            ms.extend(
                q2.kgrid()
                    .iter()
                    .map(|&k| lin2.amplification_with(k, dt, integ)),
            );
        }
    }
    ms.retain(|m| m.iter().all(|z| z.norm() < 1e300) && eigen_stalls_first_attempt(m));
    out.push((
        "verlet-euler cycles that stall nalgebra's first attempt".into(),
        ms,
    ));
    out
}

/// Defective matrices (the zero-energy modes at Γ are Jordan blocks of eigenvalue 0): Q J Qᴴ
/// with J = J_k(λ) ⊕ diag(1, −2, 0.5i), Q a dense unitary (Householder) matrix. The eigenvalues
/// of a Jordan block of size k move by O(ε^{1/k}) under round-off: `eigen` must converge and
/// stay within a few ε^{1/k} of the exact ones.
fn jordan_checks() {
    for lambda in [Complex64::new(0.0, 0.0), Complex64::new(0.7, 0.2)] {
        for k in 2..=4 {
            let n = k + 3;
            let mut j = DMatrix::<Complex64>::zeros(n, n);
            for i in 0..k {
                j[(i, i)] = lambda;
                if i + 1 < k {
                    j[(i, i + 1)] = Complex64::new(1.0, 0.0);
                }
            }
            let rest = [
                Complex64::new(1.0, 0.0),
                Complex64::new(-2.0, 0.0),
                Complex64::new(0.0, 0.5),
            ];
            for (i, &z) in rest.iter().enumerate() {
                j[(k + i, k + i)] = z;
            }
            let v = nalgebra::DVector::<Complex64>::from_fn(n, |i, _| {
                Complex64::new(1.0 + i as f64, (i as f64 * 1.7).sin())
            });
            let v = &v / Complex64::new(v.norm(), 0.0);
            let q = DMatrix::<Complex64>::identity(n, n)
                - (&v * v.adjoint()) * Complex64::new(2.0, 0.0);
            let a = &q * &j * q.adjoint();
            let exact: Vec<Complex64> = (0..n).map(|i| j[(i, i)]).collect();
            let e = eigen(a).expect("eigen converges on a Jordan block");
            let d = distance(&e, &exact);
            let bound = f64::EPSILON.powf(1.0 / k as f64);
            eprintln!(
                "Jordan block J_{k}({lambda}) in {n}×{n}: distance from the exact eigenvalues {d:.1e} (ε^(1/{k}) = {bound:.1e})"
            );
            assert!(d < 10.0 * bound, "J_{k}({lambda}): {d:e}");
        }
    }
}

fn benches(c: &mut Criterion) {
    jordan_checks();
    for (name, ms) in families() {
        let n = ms[0].nrows();
        let n_max = ms.iter().map(|m| m.nrows()).max().unwrap();
        let n = if n_max == n {
            format!("{n}×{n}")
        } else {
            format!("{n}×{n} to {n_max}×{n_max}")
        };
        let stalled = ms.iter().filter(|m| eigen_stalls_first_attempt(m)).count();
        eprintln!(
            "{name}: {} matrices {n}, {stalled} stall nalgebra's first attempt",
            ms.len()
        );
        let mut g = c.benchmark_group(format!("{name}, {} of {n}", ms.len()));
        g.sample_size(20);
        g.bench_function("eigen", |b| {
            b.iter_batched(
                || ms.clone(),
                |ms| {
                    ms.into_iter()
                        .map(|m| eigen(m).unwrap().len())
                        .sum::<usize>()
                },
                BatchSize::LargeInput,
            )
        });
        g.finish();
    }
}

criterion_group!(eigen_benches, benches);
criterion_main!(eigen_benches);
