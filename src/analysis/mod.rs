//! High-level questions in every dimension: is a configuration stable ([`query`]), its
//! dispersion ([`dispersion`]), its critical time step ([`timestep`]), growth-rate maps and the
//! finite-box prediction. One question type, [`Query<D>`] for D ∈ {1, 2, 3}, and one report type
//! per question with one JSON schema ([`report`], [`SCHEMA_VERSION`]). Inputs are validated here
//! so the library and the CLI give the same errors.
//!
//! Behind the three functions are two engines of the von Neumann layer, chosen by D: the chain
//! linearisation over κΔx ∈ (0, π] in 1D ([`chain`], every form of \[B00\]) and the Bloch
//! linearisation of a lattice over its Brillouin zone for D ≥ 2 ([`zone`], [`maps`]).

pub mod chain;
pub mod common;
pub mod maps;
pub mod query;
pub mod report;
pub mod spec;
pub mod work;
pub mod zone;

pub use common::{IntegratorReport, Setup, linearised_av};
pub use maps::{
    GrowthMap, MAX_BOX, MAX_BOX_3D, MAX_MAP_N, Plane, box_prediction, growth_map, max_box,
};
pub use query::{MAX_GRID, MaterialSpec, Query, default_grid, max_grid, max_path_points};
pub use report::{
    DispersionReport, Header, Instability, Polarisation, QueryReport, SCHEMA_VERSION,
    TimestepReport,
};
pub use spec::QuerySpec;

use crate::error::{Error, Result};

/// Answers a stability question: growing modes and their kinds, zero-energy modes, the critical
/// Δt of `q.integrator` and, with `q.dt`, the fully discrete check.
pub fn query<const D: usize>(q: &Query<D>) -> Result<QueryReport> {
    if D == 1 {
        chain::query(q)
    } else {
        zone::query(q)
    }
}

/// The dispersion ω²(κ) along the high-symmetry path of the lattice, `points` per segment (1D:
/// κΔx = πk/points, k = 1..points).
pub fn dispersion<const D: usize>(q: &Query<D>, points: usize) -> Result<DispersionReport> {
    if D == 1 {
        chain::dispersion(q, points)
    } else {
        zone::dispersion(q, points)
    }
}

/// The unit polarisations of the D branches at each wave vector of `kappa` (D components
/// each, as a [`DispersionReport`]'s `kappa`): `[point][branch][component]`, the branches in
/// the order of the report's `omega2` (ascending). In 1D the one branch is longitudinal, 1.
pub fn polarisations<const D: usize>(
    q: &Query<D>,
    kappa: &[Vec<f64>],
) -> Result<Vec<Vec<[num_complex::Complex64; D]>>> {
    if D == 1 {
        return Ok(vec![
            vec![[num_complex::Complex64::new(1.0, 0.0); D]];
            kappa.len()
        ]);
    }
    let lin = q.linearise_at(q.stress)?;
    kappa
        .iter()
        .map(|k| {
            let k: [f64; D] = k.as_slice().try_into().map_err(|_| Error::OutOfRange {
                field: "kappa",
                value: k.len() as f64,
                range: format!("a wave vector has {D} components").into(),
            })?;
            let mut b = lin.branches(k);
            orthonormalise_degenerate(&mut b);
            Ok(b.into_iter().map(|b| b.1).collect())
        })
        .collect()
}

/// Branches with equal ω² (to 1e-10 of the largest |ω²|, at least 1e-10) span a space in
/// which any basis is a set of polarisations; the closed forms return the same vector twice
/// there (at Γ, D = 0). Replaces each such group's polarisations by an orthonormal basis of
/// their span, completed with the coordinate axes (Gram–Schmidt).
fn orthonormalise_degenerate<const D: usize>(
    b: &mut [(num_complex::Complex64, [num_complex::Complex64; D])],
) {
    use num_complex::Complex64 as C;
    let tol = 1e-10 * b.iter().map(|x| x.0.norm()).fold(1.0, f64::max);
    let mut start = 0;
    while start < b.len() {
        let mut end = start + 1;
        while end < b.len() && (b[end].0 - b[start].0).norm() <= tol {
            end += 1;
        }
        if end - start > 1 {
            let axes = (0..D).map(|a| {
                let mut e = [C::new(0.0, 0.0); D];
                e[a] = C::new(1.0, 0.0);
                e
            });
            let mut basis: Vec<[C; D]> = Vec::new();
            for v in b[start..end].iter().map(|x| x.1).chain(axes) {
                if basis.len() == end - start {
                    break;
                }
                let mut w = v;
                for u in &basis {
                    let p: C = (0..D).map(|c| u[c].conj() * w[c]).sum();
                    for c in 0..D {
                        w[c] -= p * u[c];
                    }
                }
                let n = w.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
                if n > 1e-6 {
                    basis.push(w.map(|z| z / n));
                }
            }
            for (i, u) in basis.into_iter().enumerate() {
                b[start + i].1 = u;
            }
        }
        start = end;
    }
}

/// The critical Δt (Δx/c) of `q.integrator` at `tol` growth per step beyond the semi-discrete
/// system ([`crate::vonneumann::amplification::step_stability_to`]; [`timestep`]'s
/// `critical_dt` is the one at 1e-7): what a measurement that resolves `tol` per step can see.
/// None for a weak instability.
pub fn critical_dt_to<const D: usize>(q: &Query<D>, tol: f64) -> Result<Option<f64>> {
    use crate::vonneumann::amplification::step_stability_to;
    use work::{Question, check};
    crate::error::check_range("tol", tol, 0.0, 1.0, false, true)?;
    let st = if D == 1 {
        let lin = q.chain()?;
        check(q, &lin, q.kappa_sample(), q.modes(), Question::CriticalDt)?;
        step_stability_to(&lin, &q.kappas(), q.integrator, tol)?
    } else {
        let lin = q.linearise_at(q.stress)?;
        check(q, &lin, q.k_sample(), q.modes(), Question::CriticalDt)?;
        step_stability_to(&lin, &q.kgrid(), q.integrator, tol)?
    };
    Ok(st.critical_dt)
}

/// The critical time step of `q.integrator` (with 2/ω_max and, for dissipative systems,
/// \[B00\] eq 120) and its spurious growth at `q.dt` (default 1/ω_max).
pub fn timestep<const D: usize>(q: &Query<D>) -> Result<TimestepReport> {
    let mut r = if D == 1 {
        chain::timestep(q)?
    } else {
        zone::timestep(q)?
    };
    if q.av.is_some() {
        let mut q0 = *q;
        q0.av = None;
        r.critical_dt_inviscid = if D == 1 {
            chain::timestep(&q0)?
        } else {
            zone::timestep(&q0)?
        }
        .step
        .critical_dt;
    }
    if r.step.physical_growth_rate > 0.0 {
        // the kind of the fastest growth, exactly as `query` classifies it
        use crate::vonneumann::classify::Kind;
        let qr = query(q)?;
        r.physical_growth_kind = qr
            .instabilities
            .iter()
            .filter(|i| i.growth_rate > 0.0 && !matches!(i.kind, Kind::TimeStep | Kind::Integrator))
            .max_by(|a, b| a.growth_rate.total_cmp(&b.growth_rate))
            .map(|i| i.kind);
    }
    Ok(r)
}
