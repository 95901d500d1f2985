//! The engine for D ≥ 2 behind [`super::query`], [`super::dispersion`] and
//! [`super::timestep`]: the Bloch linearisation of a lattice ([`crate::vonneumann::linearise::Bloch`])
//! over the Brillouin zone, with the polarisation of the fastest mode and the dispersion along
//! the high-symmetry path. Growth-rate maps and the finite-box prediction are in
//! [`super::maps`].

// Small-vector algebra (D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::common::IntegratorReport;
use super::query::{Query, max_path_points};
use super::report::{
    DispersionReport, Header, Instability, Polarisation, QueryReport, TimestepReport,
};
use crate::error::{Error, Result, check_range};
use crate::integrator::Integrator;
use crate::lattice::{Lattice, grid_index};
use crate::params::check_count;
use crate::vonneumann::amplification::{
    AMPLIFICATION_TOL, critical_dt_given, spectral_radius_with, step_stability,
};
use crate::vonneumann::classify::{GROWTH_TOL, Kind, ZERO_OMEGA2_TOL, growth_kind};
use crate::vonneumann::damping::{branch_eigenvalues, critical_dt_eq120, damping_ratio};
use crate::vonneumann::linearise::Bloch;
use crate::vonneumann::maximise::refine_grid_max;
use num_complex::Complex64;
use rayon::prelude::*;

fn polarisation<const D: usize>(p: [num_complex::Complex64; D], k: [f64; D]) -> Polarisation {
    // remove the global phase: make the largest component real (the first of equals)
    let mut m = p[0];
    for &c in &p[1..] {
        if c.norm() > m.norm() {
            m = c;
        }
    }
    let ph = if m.norm() > 0.0 {
        m.conj() / m.norm()
    } else {
        num_complex::Complex64::new(1.0, 0.0)
    };
    let v: Vec<f64> = p.iter().map(|&c| (c * ph).re).collect();
    let len = |x: &[f64]| {
        if D == 2 {
            x[0].hypot(x[1])
        } else {
            x.iter().map(|a| a * a).sum::<f64>().sqrt()
        }
    };
    let nv = len(&v).max(1e-300);
    let kn = len(&k);
    let lf = if kn > 0.0 {
        let mut pk = p[0] * k[0];
        for a in 1..D {
            pk += p[a] * k[a];
        }
        (pk.norm() / kn).powi(2)
    } else {
        0.0
    };
    Polarisation {
        vector: v.iter().map(|x| x / nv).collect(),
        longitudinal_fraction: lf,
    }
}

/// Nearest-neighbour distance of a lattice (units of its Δx).
fn nearest_neighbour<const D: usize>(lat: &Lattice<D>) -> f64 {
    lat.offsets_within(3.0)
        .iter()
        .map(|(_, p)| p.iter().map(|c| c * c).sum::<f64>().sqrt())
        .filter(|&r| r > 1e-12)
        .fold(f64::INFINITY, f64::min)
}

/// Growth and branches ([`Bloch::growth_and_branches`]) at every wave vector of `q.kgrid()`
/// (`ks`: the grid^D zone sampling without Γ, in grid order), each pair {k, −k} evaluated once.
/// The Jacobian columns are real, so J(−k) = conj J(k): the same growth, and the conjugate
/// eigenvalues and polarisations, which the partner's entry gets (the grid index of −k is
/// (n − i) mod n per axis). Halves the work of a zone scan.
#[allow(clippy::type_complexity)]
fn zone_modes<const D: usize>(
    lin: &Bloch<D>,
    n: usize,
    ks: &[[f64; D]],
) -> Result<Vec<(f64, [Complex64; D], Vec<(Complex64, [Complex64; D])>)>> {
    let count = n.pow(D as u32);
    debug_assert_eq!(ks.len(), count - 1);
    // ks[i] is grid entry i + 1
    let partner = |i: usize| -> usize {
        let c = grid_index::<D>(i + 1, n);
        let mut idx = 0;
        for a in 0..D {
            idx = idx * n + (n - c[a]) % n;
        }
        idx - 1
    };
    let reps: Vec<usize> = (0..ks.len()).filter(|&i| i <= partner(i)).collect();
    let done: Vec<_> = reps
        .par_iter()
        .map(|&i| lin.growth_and_branches(ks[i]))
        .collect::<Result<_>>()?;
    let mut out: Vec<Option<(f64, [Complex64; D], Vec<(Complex64, [Complex64; D])>)>> =
        vec![None; ks.len()];
    for (&i, m) in reps.iter().zip(done) {
        let j = partner(i);
        if j != i {
            let conj = |v: [Complex64; D]| v.map(|c| c.conj());
            out[j] = Some((
                m.0,
                conj(m.1),
                m.2.iter().map(|&(l, v)| (l.conj(), conj(v))).collect(),
            ));
        }
        out[i] = Some(m);
    }
    Ok(out
        .into_iter()
        .map(|m| m.expect("every grid entry is a representative or its partner"))
        .collect())
}

/// ω²Δx²/c² of polarisation `p` under the unstressed operator at k: the Rayleigh quotient
/// Re(p* D0(k) p)/|p|² (D0 Hermitian for the conservative forms).
fn unstressed_omega2<const D: usize>(lin0: &Bloch<D>, k: [f64; D], p: &[Complex64; D]) -> f64 {
    let d0 = lin0.dynamical(k);
    let (mut num, mut den) = (Complex64::new(0.0, 0.0), 0.0);
    for a in 0..D {
        den += p[a].norm_sqr();
        for b in 0..D {
            num += p[a].conj() * d0[a][b] * p[b];
        }
    }
    num.re / den.max(1e-300)
}

/// Splits the `tensile` / `compressive` growth of an elastic lattice (`kind`) into the
/// growth of hourglass modes — the growing polarisation is zero-energy under the unstressed
/// operator `lin0` (ω² ≤ `tol`) — and the rest, which keeps `kind`: one entry each (when
/// present), each at its own fastest grid wave vector (no refinement: the fastest modes of
/// the rest lie next to the hourglass wave vectors, and a hill climb from there ends on them),
/// with the mode's unstressed ω² and its onset stress σ̄ E/(E + γ²).
#[allow(clippy::too_many_arguments)]
fn split_hourglass<const D: usize>(
    q: &Query<D>,
    lin0: &Bloch<D>,
    kind: Kind,
    ks: &[[f64; D]],
    grow: &[f64],
    pols: &[[Complex64; D]],
    growing: &[usize],
    tol: f64,
) -> Result<Vec<Instability>> {
    let e: Vec<f64> = growing
        .par_iter()
        .map(|&i| unstressed_omega2(lin0, ks[i], &pols[i]))
        .collect();
    let mut out = Vec::new();
    for hourglass in [true, false] {
        let set: Vec<(usize, f64)> = growing
            .iter()
            .zip(&e)
            .filter(|&(_, &ei)| (ei <= tol) == hourglass)
            .map(|(&i, &ei)| (i, ei))
            .collect();
        let Some(&(i, ei)) = set.iter().max_by(|a, b| grow[a.0].total_cmp(&grow[b.0])) else {
            continue;
        };
        let g = grow[i];
        out.push(Instability {
            kind: if hourglass { Kind::Hourglass } else { kind },
            growth_rate: g,
            kappa_at_max: ks[i].to_vec(),
            zone_fraction: set.len() as f64 / ks.len() as f64,
            kappa_min: None,
            kappa_max: None,
            pole_at: None,
            unstressed_omega2: Some(ei),
            onset_stress: Some(q.stress * ei.max(0.0) / (ei.max(0.0) + g * g)),
        });
    }
    Ok(out)
}

/// Answers a stability question in D ≥ 2 dimensions.
pub(super) fn query<const D: usize>(q: &Query<D>) -> Result<QueryReport> {
    let lin = q.linearise_at(q.stress)?;
    super::work::check(
        q,
        &lin,
        q.k_sample(),
        q.modes(),
        super::work::Question::Query,
    )?;
    let ks = q.kgrid();
    let (_, cs) = q.continuum_moduli()?;
    // the continuum's own zero branches: the D − 1 transverse ones of a fluid
    let continuum_zero = if cs == 0.0 { D - 1 } else { 0 };
    let mut grow = Vec::with_capacity(ks.len());
    let mut w2max: f64 = 0.0;
    let mut zeros = Vec::with_capacity(ks.len());
    let mut pols = Vec::with_capacity(ks.len());
    // one J(k) per pair {k, −k} of wave vectors, in parallel
    let modes = zone_modes(&lin, q.grid, &ks)?;
    for (g, p, br) in modes {
        pols.push(p);
        if !g.is_finite() || br.iter().any(|b| !b.0.re.is_finite()) {
            return Err(Error::NonFinite("dispersion branches (eigenvalues)"));
        }
        w2max = w2max.max(br[D - 1].0.re);
        zeros.push(br);
        grow.push(g);
    }
    let growing: Vec<usize> = (0..ks.len()).filter(|&i| grow[i] > GROWTH_TOL).collect();
    let mut inst = Vec::new();
    let (mut gmax, mut kmax, mut pmax) = (0.0, None, None);
    if !growing.is_empty() {
        // the maximum over the zone, not over the grid: refined from the grid's best points
        // (the grid spacing is the first step), independent of the grid to 1e-6 relative
        let b = q.lattice.reciprocal();
        let step = b
            .iter()
            .map(|r| r.iter().map(|c| c * c).sum::<f64>().sqrt())
            .fold(f64::INFINITY, f64::min)
            / q.grid as f64;
        let f = |k: [f64; D]| -> Result<f64> { Ok(lin.growth(k)?.0) };
        let Some((k, _)) = refine_grid_max(&f, &ks, &grow, step)? else {
            unreachable!("a growing grid point exists")
        };
        let k = q.lattice.fold(k);
        let (g, p) = lin.growth(k)?;
        if !g.is_finite() {
            return Err(Error::NonFinite("growth rate at the refined maximum"));
        }
        gmax = g;
        kmax = Some(k.to_vec());
        pmax = Some(polarisation(p, k));
        let mut lin0 = None;
        let kind = growth_kind(q.material_unstable()?, q.stress, || {
            let l = lin0.insert(q.linearise_at(0.0)?);
            Ok(l.growth(k)?.0)
        })?;
        match (kind, lin0) {
            (Kind::Tensile | Kind::Compressive, Some(lin0))
                if cs > 0.0 && !lin.is_dissipative() =>
            {
                let tol = ZERO_OMEGA2_TOL * w2max.max(1e-300);
                inst.extend(split_hourglass(
                    q, &lin0, kind, &ks, &grow, &pols, &growing, tol,
                )?);
            }
            _ => inst.push(Instability {
                kind,
                growth_rate: gmax,
                kappa_at_max: k.to_vec(),
                zone_fraction: growing.len() as f64 / ks.len() as f64,
                kappa_min: None,
                kappa_max: None,
                pole_at: None,
                unstressed_omega2: None,
                onset_stress: None,
            }),
        }
    }
    // zero-energy modes: more zero branches than the continuum has, at k ≠ 0
    let tol = ZERO_OMEGA2_TOL * w2max.max(1e-300);
    let spurious: Vec<usize> = (0..ks.len())
        .filter(|&i| {
            ks[i].iter().any(|c| c.abs() > 1e-12)
                && grow[i] <= GROWTH_TOL
                && zeros[i].iter().filter(|b| b.0.norm() <= tol).count() > continuum_zero
        })
        .collect();
    if let Some(&i0) = spurious.first() {
        inst.push(Instability {
            kind: Kind::RankDeficiency,
            growth_rate: 0.0,
            kappa_at_max: ks[i0].to_vec(),
            zone_fraction: spurious.len() as f64 / ks.len() as f64,
            kappa_min: None,
            kappa_max: None,
            pole_at: None,
            unstressed_omega2: None,
            onset_stress: None,
        });
    }
    let semi_stable = growing.is_empty();
    let integ = q.integrator;
    let (cdt, weak) = if integ == Integrator::Kdk {
        (
            semi_stable
                .then(|| critical_dt_given(&lin, &ks, w2max))
                .transpose()?,
            false,
        )
    } else {
        let st = step_stability(&lin, &ks, integ)?;
        (st.critical_dt.filter(|_| semi_stable), st.weak)
    };
    let mut max_amp = None;
    let mut ts = false;
    let mut spurious_rate = 0.0;
    if let Some(dt) = q.dt {
        let mut best = (0.0f64, [0.0; D], 0usize);
        let rho: Vec<f64> = ks
            .iter()
            .map(|&k| spectral_radius_with(&lin, k, dt, integ))
            .collect::<Result<_>>()?;
        for (i, (&k, &r)) in ks.iter().zip(&rho).enumerate() {
            if r > 1.0 + AMPLIFICATION_TOL && grow[i] <= GROWTH_TOL {
                best.2 += 1;
            }
            if r > best.0 {
                best = (r, k, best.2);
            }
        }
        max_amp = Some(best.0);
        if best.2 > 0 {
            ts = true;
            spurious_rate = best.0.ln() / dt;
            inst.push(Instability {
                kind: if weak {
                    Kind::Integrator
                } else {
                    Kind::TimeStep
                },
                growth_rate: best.0.ln() / dt,
                kappa_at_max: best.1.to_vec(),
                zone_fraction: best.2 as f64 / ks.len() as f64,
                kappa_min: None,
                kappa_max: None,
                pole_at: None,
                unstressed_omega2: None,
                onset_stress: None,
            });
        }
    }
    Ok(QueryReport {
        header: Header::of(q, nearest_neighbour(&q.lattice)),
        grid: q.grid,
        stable: semi_stable && !ts,
        max_growth_rate: gmax,
        kappa_at_max: kmax,
        polarisation: pmax,
        instabilities: inst,
        has_zero_energy_modes: !spurious.is_empty(),
        art_stress_kink: q.art_stress_kink(),
        critical_dt: cdt,
        critical_cfl: cdt.map(|d| d / q.h_over_dx),
        dt: q.dt,
        integrator: integ.name(),
        spurious_growth_rate: spurious_rate,
        max_amplification: max_amp,
    })
}

/// Dispersion along the high-symmetry path of the lattice ([`Lattice::symmetry_points`]), `n`
/// points per segment.
pub(super) fn dispersion<const D: usize>(q: &Query<D>, n: usize) -> Result<DispersionReport> {
    check_count("points", n, 2, max_path_points(D))?;
    let lin = q.linearise_at(q.stress)?;
    let path = q.lattice.symmetry_path(n);
    let mut labels = Vec::new();
    let pts = q.lattice.symmetry_points();
    let mut s = 0.0;
    labels.push((pts[0].0.to_string(), 0.0));
    for w in pts.windows(2) {
        s += if D == 2 {
            (w[1].1[0] - w[0].1[0]).hypot(w[1].1[1] - w[0].1[1])
        } else {
            (0..D)
                .map(|a| (w[1].1[a] - w[0].1[a]).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        labels.push((w[1].0.to_string(), s));
    }
    let mut out = DispersionReport {
        header: Header::of(q, nearest_neighbour(&q.lattice)),
        labels,
        path: Vec::new(),
        kappa: Vec::new(),
        omega2: Vec::new(),
        growth_rate: Vec::new(),
        omega2_continuum: Vec::new(),
        damping_rate: lin.is_dissipative().then(Vec::new),
        damping_ratio: lin.is_dissipative().then(Vec::new),
    };
    for (k, s) in path {
        let b = lin.branches(k);
        out.path.push(s);
        out.kappa.push(k.to_vec());
        let w2: Vec<f64> = b.iter().map(|x| x.0.re).collect();
        if let (Some(rate), Some(ratio)) = (&mut out.damping_rate, &mut out.damping_ratio) {
            let s = branch_eigenvalues(&lin.eigenvalues(k)?, &w2);
            rate.push(s.iter().map(|s| s.map(|s| s.re)).collect());
            ratio.push(s.iter().map(|s| s.map(damping_ratio)).collect());
        }
        out.omega2.push(w2);
        out.growth_rate.push(lin.growth(k)?.0);
        out.omega2_continuum
            .push(q.continuum_omega2(k)?.iter().map(|w| w.re).collect());
    }
    Ok(out)
}

/// The critical time step of `q.integrator` over the zone sampling of `q` (and its spurious
/// growth at `q.dt`, default 1/ω_max).
pub(super) fn timestep<const D: usize>(q: &Query<D>) -> Result<TimestepReport> {
    let lin = q.linearise_at(q.stress)?;
    super::work::check(
        q,
        &lin,
        q.k_sample(),
        q.modes(),
        super::work::Question::Timestep,
    )?;
    let ks = q.kgrid();
    let modes = zone_modes(&lin, q.grid, &ks)?;
    let mut w2max: f64 = 0.0;
    let mut grows = false;
    for (g, _, br) in &modes {
        if !g.is_finite() || br.iter().any(|b| !b.0.re.is_finite()) {
            return Err(Error::NonFinite("dispersion branches (eigenvalues)"));
        }
        w2max = w2max.max(br[D - 1].0.re);
        grows |= *g > GROWTH_TOL;
    }
    if let Some(d) = q.dt {
        check_range("dt", d, 0.0, 1e6, false, true)?;
    }
    // 2/ω_max is the leapfrog limit of a non-dissipative system only
    let from_omega_max = (!lin.is_dissipative() && !grows)
        .then(|| critical_dt_given(&lin, &ks, w2max))
        .transpose()?;
    let eq120 = if lin.is_dissipative() && !grows {
        Some(critical_dt_eq120(&lin, &ks)?).filter(|d| d.is_finite())
    } else {
        None
    };
    Ok(TimestepReport {
        header: Header::of(q, nearest_neighbour(&q.lattice)),
        grid: q.grid,
        critical_dt_from_omega_max: from_omega_max,
        critical_dt_eq120: eq120,
        physical_growth_kind: None,
        critical_dt_inviscid: None,
        step: IntegratorReport::of(&lin, &ks, q.integrator, q.dt, q.h_over_dx)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::forms::FormKind;
    use crate::kernel;

    /// The {k, −k} shortcut of [`zone_modes`] against evaluating every wave vector directly:
    /// the growth and the branches' ω² agree to rounding (1e-12 of the largest |ω²|) on a
    /// hexagonal lattice under tension (growing), with artificial viscosity (dissipative), and on
    /// a bcc lattice; so the partner index and J(−k) = conj J(k) hold beyond the square grid.
    #[test]
    fn pairs_of_opposite_wave_vectors_match_direct_evaluation() {
        let m4 = kernel::by_name("m4").unwrap();
        let mut q2 = Query::<2>::new(FormKind::Classical, m4, 1.2, 0.05);
        q2.lattice = Lattice::<2>::hexagonal();
        q2.grid = 7;
        let mut q2v = q2;
        q2v.av = Some((1.0, 1.0));
        let mut q3 = Query::<3>::new(FormKind::Classical, m4, 1.2, 0.01);
        q3.lattice = Lattice::<3>::bcc();
        q3.grid = 4;
        fn check<const D: usize>(q: &Query<D>) {
            let lin = q.linearise_at(q.stress).unwrap();
            let ks = q.kgrid();
            let fast = zone_modes(&lin, q.grid, &ks).unwrap();
            let direct: Vec<_> = ks
                .iter()
                .map(|&k| lin.growth_and_branches(k).unwrap())
                .collect();
            let scale = direct
                .iter()
                .flat_map(|d| d.2.iter().map(|b| b.0.norm()))
                .fold(1e-300, f64::max);
            for (i, (f, d)) in fast.iter().zip(&direct).enumerate() {
                assert!((f.0 - d.0).abs() <= 1e-12 * scale, "growth at {i}");
                for (a, b) in f.2.iter().zip(&d.2) {
                    assert!((a.0.re - b.0.re).abs() <= 1e-12 * scale, "ω² at {i}");
                }
            }
            assert!(direct.iter().any(|d| d.0 > GROWTH_TOL) || q.av.is_some());
        }
        check(&q2);
        check(&q2v);
        check(&q3);
    }
}
