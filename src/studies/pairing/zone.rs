//! The zone scan of the pairing study (any dimension): the largest growth rate over the Brillouin
//! zone, its wave vector and its polarisation, longitudinal or transverse.

use crate::analysis::Query;
use crate::error::{Error, Result};
use crate::vonneumann::classify::GROWTH_TOL;
use crate::vonneumann::linearise::Bloch;
use num_complex::Complex64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// A branch with |ê·k̂|² ≥ this is longitudinal.
pub const LONGITUDINAL: f64 = 0.5;

/// One mode: its growth rate (c/Δx), wave vector (κΔx) and longitudinal fraction.
#[derive(Clone, Copy, Default)]
pub(super) struct Mode {
    pub(super) growth: f64,
    pub(super) k: [f64; 3],
    pub(super) lf: f64,
}

impl Mode {
    fn take(&mut self, o: Mode) {
        if o.growth > self.growth {
            *self = o;
        }
    }
    fn merge(mut self, o: Mode) -> Mode {
        self.take(o);
        self
    }
    pub(super) fn grows(&self) -> bool {
        self.growth > GROWTH_TOL
    }
    pub(super) fn rate(&self) -> f64 {
        if self.grows() { self.growth } else { 0.0 }
    }
}

/// The fastest mode, the fastest longitudinal and the fastest transverse mode over a set of
/// wave vectors, and the largest relative asymmetry |D − Dᴴ|/max|D_ab| met.
#[derive(Clone, Copy, Default)]
pub(super) struct Scan {
    pub(super) all: Mode,
    pub(super) long: Mode,
    pub(super) trans: Mode,
    pub(super) asymmetry: f64,
}

impl Scan {
    pub(super) fn merge(self, o: Scan) -> Scan {
        Scan {
            all: self.all.merge(o.all),
            long: self.long.merge(o.long),
            trans: self.trans.merge(o.trans),
            asymmetry: self.asymmetry.max(o.asymmetry),
        }
    }
}

/// Eigenvalues closer than this (relative to the largest |ω²| at k) form one eigenspace.
pub const DEGENERACY_TOL: f64 = 1e-9;

/// The modes at one wave vector. The dynamical matrix of the classical form with `sph` shapes
/// is real symmetric (ρD = (ρ + 2σ̄)S1S1ᵀ − 2σ̄S2 with real lattice sums; the engine's D agrees to
/// round-off, recorded as `max_asymmetry`), so its symmetric part is diagonalised
/// ([`nalgebra::SymmetricEigen`], orthonormal eigenvectors) and degenerate eigenvalues are
/// grouped into eigenspaces: an eigenspace with ω² < 0 is longitudinal when it holds a mode with
/// |ê·k̂|² ≥ [`LONGITUDINAL`] (its longitudinal fraction = |P k̂|², P the projector onto it) and
/// transverse when it holds one with |ê·k̂|² < ½ (dimension ≥ 2, or a single mode with
/// |ê·k̂|² < ½). A degenerate longitudinal + transverse pair counts for both.
///
/// At the symmetric points of the zone the eigenspace is degenerate by symmetry (sc: all of R³
/// at R = (π,π,π), the (x, y) plane at M = (π,π,0)), so |P k̂|² = 1 there for every image of k
/// (k and k − G are one lattice pattern; each image's k̂ lies in P), and the growth is counted
/// as pairing and as transverse. That is the label the zone's interior gives it: R and M are
/// where the longitudinal branches along [111] (R) and [110], [1−10] (M) meet their transverse
/// partners, so modes along a unique k̂ grow arbitrarily close to the R or M rate. The growth
/// there has the sign of the kernel's W*(|k|) (the pairing mechanism), and the eigenspace holds
/// ê = x̂, which moves every particle head-on towards one nearest neighbour, as the
/// longitudinal mode at X does (tests/it/pairing.rs,
/// `pairing_at_the_symmetric_points_r_and_m_of_sc`). A single member of the eigenspace, such as
/// the polarisation `query` prints at R (|ê·k̂|² = 1/3), says nothing about the eigenspace.
pub(super) fn scan_k<const D: usize>(lin: &Bloch<D>, k: [f64; D]) -> Result<Scan> {
    scan_dynamical(&lin.dynamical(k), k)
}

/// [`scan_k`] of the normalised dynamical matrix `d` at k.
fn scan_dynamical<const D: usize>(d: &[[Complex64; D]; D], k: [f64; D]) -> Result<Scan> {
    let big = d.iter().flatten().map(|c| c.norm()).fold(0.0f64, f64::max);
    let m = nalgebra::DMatrix::from_fn(D, D, |a, b| 0.5 * (d[a][b].re + d[b][a].re));
    let asym = (0..D * D)
        .map(|i| (d[i / D][i % D] - d[i % D][i / D].conj()).norm())
        .fold(0.0f64, f64::max);
    let eig = nalgebra::SymmetricEigen::try_new(m, 1e-15, 1000)
        .ok_or(Error::NonFinite("pairing: symmetric eigen-decomposition"))?;
    let kn = k.iter().map(|c| c * c).sum::<f64>().sqrt();
    let mut k3 = [0.0; 3];
    k3[..D].copy_from_slice(&k);
    let mut idx: Vec<usize> = (0..D).collect();
    idx.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let scale = eig.eigenvalues.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut out = Scan {
        asymmetry: if big > 0.0 { asym / big } else { 0.0 },
        ..Scan::default()
    };
    let mut i = 0;
    while i < D {
        let lam = eig.eigenvalues[idx[i]];
        let mut j = i + 1;
        while j < D && eig.eigenvalues[idx[j]] - lam <= DEGENERACY_TOL * scale {
            j += 1;
        }
        if !lam.is_finite() {
            return Err(Error::NonFinite("pairing: dynamical matrix"));
        }
        let lf: f64 = if kn > 0.0 {
            idx[i..j]
                .iter()
                .map(|&c| {
                    let v = eig.eigenvectors.column(c);
                    let dot: f64 = (0..D).map(|a| v[a] * k[a]).sum();
                    (dot / kn).powi(2)
                })
                .sum::<f64>()
                .min(1.0)
        } else {
            0.0
        };
        let mode = Mode {
            growth: (-lam).max(0.0).sqrt(),
            k: k3,
            lf,
        };
        out.all.take(mode);
        if lf >= LONGITUDINAL {
            out.long.take(mode);
        }
        if j - i >= 2 || lf < LONGITUDINAL {
            out.trans.take(mode);
        }
        i = j;
    }
    Ok(out)
}

/// Growth over the sampled zone of a D-dimensional question (2D or 3D): the fastest mode, the
/// fastest longitudinal (pairing) and the fastest transverse mode (c/Δx, 0 when below
/// [`GROWTH_TOL`]), as [`evaluate_row`](super::evaluate_row) scans them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ZoneGrowth {
    /// Largest growth rate of any mode.
    pub max_growth_rate: f64,
    /// Largest growth of a longitudinal mode (|ê·k̂|² ≥ ½): pairing.
    pub pairing_growth_rate: f64,
    /// Largest growth of a transverse mode.
    pub transverse_growth_rate: f64,
}

/// Linearises `q` at its stress and scans its wave-vector grid ([`Query::kgrid`], rayon) for
/// the fastest, the fastest longitudinal and the fastest transverse mode (module docs, the
/// eigenspace rule of the row scan). The dynamical matrix must be (nearly) Hermitian: the
/// classical form with `sph` shapes and no dissipation, as in the pairing study.
pub fn zone_growth<const D: usize>(q: &Query<D>) -> Result<ZoneGrowth> {
    let lin = q.linearise_at(q.stress)?;
    let scan = q
        .kgrid()
        .par_iter()
        .map(|&k| scan_k(&lin, k))
        .try_reduce(Scan::default, |x, y| Ok(x.merge(y)))?;
    scan.growth()
}

/// [`zone_growth`] over given modes: each wave vector with its normalised dynamical matrix
/// D(k)Δx²/c² (a closed form, for instance), by the same eigenspace rule; serial (the caller
/// parallelises over its questions). A mode whose symmetric part is positive definite by a
/// margin (`surely_stable`) has no growth to report and is not diagonalised: the result is
/// the same.
pub fn zone_growth_of<const D: usize>(
    modes: impl IntoIterator<Item = ([f64; D], [[Complex64; D]; D])>,
) -> Result<ZoneGrowth> {
    let mut scan = Scan::default();
    for (k, d) in modes {
        if !surely_stable(&d) {
            scan = scan.merge(scan_dynamical(&d, k)?);
        }
    }
    scan.growth()
}

/// Whether every eigenvalue of the symmetric part of `d` is ≥ 0 with a margin of 64u times the
/// sum of its entries' moduli (u = 2⁻⁵³), above the rounding of the symmetric eigendecomposition:
/// then the eigenvalues [`scan_dynamical`] computes are > −[`GROWTH_TOL`]² (γ² = −ω²) for any
/// matrix of entries below ~1e3, and it would report no growth. 2 × 2: the smallest eigenvalue
/// in closed form; otherwise Gershgorin's lower bound. False for a non-finite entry.
fn surely_stable<const D: usize>(d: &[[Complex64; D]; D]) -> bool {
    let m = |a: usize, b: usize| 0.5 * (d[a][b].re + d[b][a].re);
    let size: f64 = (0..D * D).map(|i| m(i / D, i % D).abs()).sum();
    let lower = if D == 2 {
        let (a, b, c) = (m(0, 0), m(0, 1), m(1, 1));
        0.5 * (a + c) - (0.25 * (a - c) * (a - c) + b * b).sqrt()
    } else {
        (0..D)
            .map(|a| {
                m(a, a)
                    - (0..D)
                        .filter(|&b| b != a)
                        .map(|b| m(a, b).abs())
                        .sum::<f64>()
            })
            .fold(f64::INFINITY, f64::min)
    };
    size.is_finite() && lower - 64.0 * (f64::EPSILON / 2.0) * size >= 0.0
}

impl Scan {
    /// The growth rates of the scan (an error if the fastest is not finite).
    fn growth(&self) -> Result<ZoneGrowth> {
        if !self.all.growth.is_finite() {
            return Err(Error::NonFinite("pairing growth rate"));
        }
        Ok(ZoneGrowth {
            max_growth_rate: self.all.rate(),
            pairing_growth_rate: self.long.rate(),
            transverse_growth_rate: self.trans.rate(),
        })
    }
}
