//! The compression columns of the guide: classical SPH (`sph` shapes) at σ̄ = [`COMPRESSION`]
//! over the h/Δx grid, 1D (elastic bar, [`KAPPAS_1D`] κ points) and 2D (hydro, square lattice,
//! [`GRID_2D`]² − 1 wave vectors), from the derived closed form of the sum form
//! ([`crate::vonneumann::derived`]: ρD = (λ' + G' + 2s) S1S1ᵀ + G'|S1|² I − 2s S2, checked
//! against the engine's linearisation in `tests/it/vonneumann.rs`, `tests/it/vonneumann2d.rs`
//! and, for every kernel on these scans' h (1D every one, 2D every fifth),
//! `tests/it/kernel_guide.rs`).
//!
//! Why not the engine: its 2D linearisation differentiates a periodic patch of ~(4R + 5)²
//! particles, ~R⁴ work per h — 8 s of CPU for the 663 values of h of the default table, two
//! thirds of the guide's CPU time before issue 25. The closed form needs the kernel's
//! derivatives at the ~πR² lattice offsets once per h ([`SphSums`]) and, per wave vector, a sum
//! over them with phases tabulated once per scan ([`PhaseGrid`]): the lattice sums are those of
//! [`crate::vonneumann::derived::sums`] to the last bit. The zone scan is the pairing study's
//! ([`zone_growth_of`]: the eigenspace rule of [`crate::studies::pairing::zone_growth`] on the
//! same wave vectors).

use super::config::{COMPRESSION, GRID_2D, KAPPAS_1D, MAX_SUPPORT_2D};
use super::report::{CompressionScan, Interval};
use crate::analysis::{MaterialSpec, Query};
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::kernel::Kernel;
use crate::lattice::Lattice;
use crate::shape::ShapeFamily;
use crate::studies::pairing::{ZoneGrowth, zone_growth_of};
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::derived::{SphSums, omega2_1d, rho_d};
use crate::vonneumann::linearise::base_state;
use num_complex::Complex64;
use rayon::prelude::*;

/// The 1D question of the scan: classical, `sph`, elastic bar, [`KAPPAS_1D`] κ points.
pub fn query_1d(k: &'static dyn Kernel, h: f64, stress: f64) -> Query<1> {
    let mut q = Query::<1>::new(FormKind::Classical, k, h, stress);
    q.shape = ShapeFamily::Sph;
    q.grid = KAPPAS_1D;
    q
}

/// The 2D question of the scan: classical, `sph`, hydro, square lattice, [`GRID_2D`]².
pub fn query_2d(k: &'static dyn Kernel, h: f64, stress: f64) -> Query<2> {
    let mut q = Query::<2>::new(FormKind::Classical, k, h, stress);
    q.shape = ShapeFamily::Sph;
    q.material = MaterialSpec::Hydro;
    q.grid = GRID_2D;
    q
}

/// (sin θ, sin(θ/2)) of θ = k·R for every wave vector of a grid and every lattice offset
/// R = Σ mᵢaᵢ with |mᵢ| ≤ `reach`, θ formed as [`SphSums::at`] forms it: computed once and
/// shared by every h of a scan.
pub struct PhaseGrid<const D: usize> {
    reach: i64,
    side: usize,
    rows: Vec<Vec<(f64, f64)>>,
}

impl<const D: usize> PhaseGrid<D> {
    /// The table of wave vectors `ks` on `lat` for offsets |mᵢ| ≤ `reach`.
    pub fn new(lat: &Lattice<D>, ks: &[[f64; D]], reach: i64) -> Self {
        let side = (2 * reach + 1) as usize;
        let offsets: Vec<[f64; D]> = (0..side.pow(D as u32))
            .map(|idx| lat.point_at(Self::coords(idx, reach, side)))
            .collect();
        let rows = ks
            .iter()
            .map(|k| {
                offsets
                    .iter()
                    .map(|rr| {
                        let mut t = k[0] * rr[0];
                        for a in 1..D {
                            t += k[a] * rr[a];
                        }
                        (t.sin(), (0.5 * t).sin())
                    })
                    .collect()
            })
            .collect();
        Self { reach, side, rows }
    }

    /// The integer coordinates of table index `idx` (first coordinate slowest).
    fn coords(mut idx: usize, reach: i64, side: usize) -> [i64; D] {
        let mut m = [0i64; D];
        for a in (0..D).rev() {
            m[a] = (idx % side) as i64 - reach;
            idx /= side;
        }
        m
    }

    /// The phases of wave vector `i`, for [`SphSums::with_phases`] (panics for an offset
    /// beyond the reach).
    pub fn row(&self, i: usize) -> impl Fn(&[i64; D], &[f64; D]) -> (f64, f64) + '_ {
        let row = &self.rows[i];
        move |m, _| {
            let mut idx = 0;
            for &c in m {
                idx = idx * self.side + (c + self.reach) as usize;
            }
            row[idx]
        }
    }
}

/// The lattice sums of `q`'s kernel at every h of `hs` (its lattice, `sph` shape) and the phase
/// table of `ks` reaching all of them.
fn sums_and_phases<const D: usize>(
    q: &Query<D>,
    hs: &[f64],
    ks: &[[f64; D]],
) -> Result<(Vec<SphSums<D>>, PhaseGrid<D>)> {
    let sums: Vec<SphSums<D>> = hs
        .iter()
        .map(|&h| {
            let q = Query::<D> { h_over_dx: h, ..*q };
            q.validate()?;
            Ok(SphSums::new(&q.lattice, q.params()?.kp))
        })
        .collect::<Result<_>>()?;
    let reach = sums.iter().map(SphSums::reach).max().unwrap_or(0);
    Ok((sums, PhaseGrid::new(&q.lattice, ks, reach)))
}

/// The largest growth rate (c/Δx) of the 1D question [`query_1d`] at σ̄ = `stress` over its κ
/// grid, from the closed form ω² = C̃S1² − 2σ̄(S2 − S1²) ([`omega2_1d`]), at every h of `hs`.
pub fn closed_form_growth_1d(k: &'static dyn Kernel, hs: &[f64], stress: f64) -> Result<Vec<f64>> {
    let q = query_1d(k, hs.first().copied().unwrap_or(1.0), stress);
    let ks: Vec<[f64; 1]> = q.kappas().into_iter().map(|x| [x]).collect();
    let (sums, phases) = sums_and_phases(&q, hs, &ks)?;
    sums.iter()
        .map(|sm| {
            let mut g: f64 = 0.0;
            for i in 0..ks.len() {
                let w2 = omega2_1d(
                    FormKind::Classical,
                    &sm.with_phases(phases.row(i)),
                    stress,
                    0.0,
                )
                .ok_or(Error::NonFinite("closed-form ω²"))?;
                if !w2.is_finite() {
                    return Err(Error::NonFinite("closed-form ω²"));
                }
                g = g.max((-w2).max(0.0).sqrt());
            }
            Ok(g)
        })
        .collect()
}

/// The zone growth of the 2D question [`query_2d`] at σ̄ = `stress` from the closed form
/// D(k)Δx²/c² = ρD/(ρK) ([`rho_d`]) on the question's wave vectors, at every h of `hs`
/// (rayon over h).
pub fn closed_form_zone_2d(
    k: &'static dyn Kernel,
    hs: &[f64],
    stress: f64,
) -> Result<Vec<ZoneGrowth>> {
    let q = query_2d(k, hs.first().copied().unwrap_or(1.0), stress);
    let ks = q.kgrid();
    let (sums, phases) = sums_and_phases(&q, hs, &ks)?;
    let p = q.params()?;
    let (rho, s) = base_state(&p.material, p.rho0, stress)?;
    let ratio = rho / p.rho0;
    let scale = 1.0 / (ratio * p.material.modulus());
    sums.par_iter()
        .map(|sm| {
            zone_growth_of(ks.iter().enumerate().map(|(i, &kv)| {
                let d = rho_d(
                    FormKind::Classical,
                    &p.material,
                    s,
                    ratio,
                    &sm.with_phases(phases.row(i)),
                )
                .unwrap_or([[f64::NAN; 2]; 2]);
                (kv, d.map(|r| r.map(|x| Complex64::new(x * scale, 0.0))))
            }))
        })
        .collect()
}

/// Merges the grid values where `ok` into closed intervals.
pub fn intervals(h: &[f64], ok: &[bool]) -> Vec<Interval> {
    let mut out: Vec<Interval> = Vec::new();
    let mut open: Option<Interval> = None;
    for (&x, &good) in h.iter().zip(ok) {
        if !good {
            out.extend(open.take());
        } else if let Some(iv) = open.as_mut() {
            iv.to = x;
        } else {
            open = Some(Interval { from: x, to: x });
        }
    }
    out.extend(open);
    out
}

/// The compression scan of `k` in `dim` ∈ {1, 2} over `h` (module docs): the grid values with a
/// neighbour in the support (ζh > Δx), in 2D up to R = ζh ≤ [`MAX_SUPPORT_2D`] Δx.
pub fn compression_scan(k: &'static dyn Kernel, dim: u8, h: &[f64]) -> Result<CompressionScan> {
    let hs: Vec<f64> = h
        .iter()
        .copied()
        .filter(|&x| k.zeta() * x > 1.0 && (dim == 1 || k.zeta() * x <= MAX_SUPPORT_2D + 1e-9))
        .collect();
    let (stable, no_pair): (Vec<bool>, Vec<bool>) = if hs.is_empty() {
        (Vec::new(), Vec::new())
    } else if dim == 1 {
        closed_form_growth_1d(k, &hs, COMPRESSION)?
            .into_iter()
            .map(|g| (g <= GROWTH_TOL, g <= GROWTH_TOL))
            .unzip()
    } else {
        closed_form_zone_2d(k, &hs, COMPRESSION)?
            .into_iter()
            .map(|z| (z.max_growth_rate == 0.0, z.pairing_growth_rate == 0.0))
            .unzip()
    };
    Ok(CompressionScan {
        dim,
        material: if dim == 1 { "elastic" } else { "hydro" }.into(),
        stress: COMPRESSION,
        scanned: hs.first().map(|&a| Interval {
            from: a,
            to: *hs.last().unwrap_or(&a),
        }),
        computed: hs.len(),
        stable: intervals(&hs, &stable),
        no_pairing: intervals(&hs, &no_pair),
    })
}
