//! Criterion bench of `eigen` (the eigenvalues of every dissipative mode, amplification and
//! cycle matrix) on the matrices the crate builds: 1D `lnl` Jacobians with viscosity and δ-SPH
//! (5 × 5), 3D `lnl` Jacobians with viscosity (19 × 19), 3D `kdk` amplification matrices
//! (19 × 19), 3D and 2D `verlet-euler` cycles with viscosity (35 × 35, 14 × 14) and the 1D
//! `verlet-euler` cycles of `tests/integrators.rs::verlet_euler_with_viscosity_long_cycles`
//! (7 × 7), each family timed as one batch (stalling and converging matrices in the proportion
//! the crate meets them), and the cycles on which nalgebra's first attempt stalls. Columns: the
//! crate's `eigen` (nalgebra's complex Schur, retried on exactly similar matrices when it
//! stalls), `before` (the route it replaced: nalgebra, faer's eigenvalue solver when nalgebra
//! stalls) and faer alone. The set-up prints each family's size, how many matrices
//! stall nalgebra's first attempt, and the largest distance between the eigenvalues of `eigen`
//! and faer's (matched, relative to ‖m‖₁), then times the three interleaved (21 rounds in
//! rotating order, median ratios: robust to the load of a shared machine). Defective matrices
//! (Jordan blocks) are checked first. `cargo bench --bench eigen` runs them.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use nalgebra::DMatrix;
use num_complex::Complex64;
use sphstab::analysis::{Query, Query1D};
use sphstab::forms::{DiffusionForm, FormKind};
use sphstab::integrator::Integrator;
use sphstab::kernel;
use sphstab::vonneumann::amplification::Modes;
use sphstab::vonneumann::linearise::eigen;
use std::f64::consts::PI;
use std::time::Instant;

/// The route `eigen` replaced (its code at the parent commit): balance, nalgebra on m + μI,
/// faer's eigenvalue solver if that stalls.
mod before {
    use nalgebra::DMatrix;
    use num_complex::Complex64;

    pub fn balance(m: &mut DMatrix<Complex64>) {
        const RADIX: f64 = 2.0;
        let n = m.nrows();
        let l1 = |z: &Complex64| z.re.abs() + z.im.abs();
        for _ in 0..100 {
            let mut done = true;
            for i in 0..n {
                let (mut c, mut r) = (0.0, 0.0);
                for j in (0..n).filter(|&j| j != i) {
                    c += l1(&m[(j, i)]);
                    r += l1(&m[(i, j)]);
                }
                if c == 0.0 || r == 0.0 || !(c.is_finite() && r.is_finite()) {
                    continue;
                }
                let s = c + r;
                let mut f = 1.0;
                let (lo, hi) = (r / RADIX, r * RADIX);
                while c < lo {
                    f *= RADIX;
                    c *= RADIX * RADIX;
                }
                while c > hi {
                    f /= RADIX;
                    c /= RADIX * RADIX;
                }
                if (c + r) / f < 0.95 * s {
                    done = false;
                    for j in 0..n {
                        m[(i, j)] /= f;
                        m[(j, i)] *= f;
                    }
                }
            }
            if done {
                break;
            }
        }
    }

    pub fn shifted_schur(m: &DMatrix<Complex64>) -> Option<Vec<Complex64>> {
        let n = m.nrows();
        let norm = (0..n)
            .map(|j| m.column(j).iter().map(|z| z.norm()).sum::<f64>())
            .fold(0.0, f64::max)
            + 1.0;
        let mu = Complex64::new(norm, 0.0);
        let shifted = m + DMatrix::<Complex64>::identity(n, n) * mu;
        let schur = nalgebra::linalg::Schur::try_new(shifted, 4.0 * f64::EPSILON, 30 * n)?;
        let ev = schur.eigenvalues()?;
        Some(ev.iter().map(|&z| z - mu).collect())
    }

    pub fn faer(m: &DMatrix<Complex64>) -> Option<Vec<Complex64>> {
        let n = m.nrows();
        let f = faer::Mat::<faer::c64>::from_fn(n, n, |i, j| {
            let z = m[(i, j)];
            faer::c64::new(z.re, z.im)
        });
        let ev = f.eigenvalues().ok()?;
        Some(ev.into_iter().map(|z| Complex64::new(z.re, z.im)).collect())
    }

    pub fn eigen(mut m: DMatrix<Complex64>) -> Option<Vec<Complex64>> {
        balance(&mut m);
        shifted_schur(&m).or_else(|| faer(&m))
    }

    /// faer alone, on the balanced matrix.
    pub fn faer_only(mut m: DMatrix<Complex64>) -> Option<Vec<Complex64>> {
        balance(&mut m);
        faer(&m)
    }

    /// Whether nalgebra's first attempt stalls.
    pub fn stalls(m: &DMatrix<Complex64>) -> bool {
        let mut m = m.clone();
        balance(&mut m);
        shifted_schur(&m).is_none()
    }
}

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

fn norm1(m: &DMatrix<Complex64>) -> f64 {
    m.column_iter()
        .map(|c| c.iter().map(|z| z.norm()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// The matrix families: (name, matrices).
fn families() -> Vec<(String, Vec<DMatrix<Complex64>>)> {
    let m4 = kernel::by_name("m4").unwrap();
    let mut out = Vec::new();

    let mut q1 = Query1D::new(FormKind::Lnl, m4, 1.2, 0.01);
    q1.av = Some((1.0, 0.0));
    q1.diffusion = Some((0.1, DiffusionForm::Antuono));
    q1.points = 256;
    let lin1 = q1.linearise().unwrap();
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

    let mut qc = Query1D::new(FormKind::Nonlocal, m4, 1.3, 0.01);
    qc.av = Some((1.0, 0.0));
    let linc = qc.linearise().unwrap();
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
    ms.retain(|m| m.iter().all(|z| z.norm() < 1e300) && before::stalls(m));
    out.push((
        "verlet-euler cycles that stall nalgebra's first attempt".into(),
        ms,
    ));
    out
}

/// An eigenvalue route: `None` if it does not converge.
type Route = fn(DMatrix<Complex64>) -> Option<Vec<Complex64>>;

/// Seconds for `f` over a clone of `ms` (the clone untimed).
fn time_batch(ms: &[DMatrix<Complex64>], f: Route) -> f64 {
    let ms = ms.to_vec();
    let t = Instant::now();
    let n: usize = ms.into_iter().map(|m| f(m).unwrap().len()).sum();
    let s = t.elapsed().as_secs_f64();
    std::hint::black_box(n);
    s
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Interleaved timing of the three routes (rounds in rotating order, so that a change of the
/// machine's load hits all three alike): median of the per-round ratios before/eigen and
/// faer/eigen, and the median time of `eigen` per matrix.
fn interleaved(ms: &[DMatrix<Complex64>]) -> (f64, f64, f64) {
    let routes: [Route; 3] = [|m| eigen(m).ok(), before::eigen, before::faer_only];
    let (mut r_before, mut r_faer, mut t_eigen) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..21 {
        let mut t = [0.0; 3];
        for i in 0..3 {
            let r = (round + i) % 3;
            t[r] = time_batch(ms, routes[r]);
        }
        r_before.push(t[1] / t[0]);
        r_faer.push(t[2] / t[0]);
        t_eigen.push(t[0] / ms.len() as f64);
    }
    (median(r_before), median(r_faer), median(t_eigen))
}

/// Defective matrices (the zero-energy modes at Γ are Jordan blocks of eigenvalue 0): Q J Qᴴ
/// with J = J_k(λ) ⊕ diag(1, −2, 0.5i), Q a dense unitary (Householder) matrix. The eigenvalues
/// of a Jordan block of size k move by O(ε^{1/k}) under round-off; prints the largest distance
/// of `eigen`'s and faer's eigenvalues from the exact ones.
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
            let e = eigen(a.clone()).expect("eigen converges on a Jordan block");
            let f = before::faer_only(a).expect("faer converges");
            eprintln!(
                "Jordan block J_{k}({lambda}) in {n}×{n}: distance from the exact eigenvalues: eigen {:.1e}, faer {:.1e} (ε^(1/{k}) = {:.1e})",
                distance(&e, &exact),
                distance(&f, &exact),
                f64::EPSILON.powf(1.0 / k as f64)
            );
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
        let stalled = ms.iter().filter(|m| before::stalls(m)).count();
        let worst = ms
            .iter()
            .map(|m| {
                let a = eigen(m.clone()).expect("eigen converges");
                let b = before::faer_only(m.clone()).expect("faer converges");
                distance(&a, &b) / norm1(m).max(f64::MIN_POSITIVE)
            })
            .fold(0.0, f64::max);
        eprintln!(
            "{name}: {} matrices {n}, {stalled} stall nalgebra's first attempt; eigen vs faer: max distance/‖m‖₁ {worst:.1e}",
            ms.len()
        );
        assert!(worst < 1e-10, "{name}: eigen and faer disagree ({worst:e})");
        let (rb, rf, te) = interleaved(&ms);
        eprintln!(
            "    interleaved, 21 rounds: eigen {:.1} µs per matrix; time ratios before/eigen {rb:.2}, faer alone/eigen {rf:.2}",
            te * 1e6
        );
        let mut g = c.benchmark_group(format!("{name}, {} of {n}", ms.len()));
        g.sample_size(20);
        g.bench_function("eigen (nalgebra)", |b| {
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
        g.bench_function("before (nalgebra, faer when it stalls)", |b| {
            b.iter_batched(
                || ms.clone(),
                |ms| {
                    ms.into_iter()
                        .map(|m| before::eigen(m).unwrap().len())
                        .sum::<usize>()
                },
                BatchSize::LargeInput,
            )
        });
        g.bench_function("faer alone", |b| {
            b.iter_batched(
                || ms.clone(),
                |ms| {
                    ms.into_iter()
                        .map(|m| before::faer_only(m).unwrap().len())
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
