//! Growth-rate maps over the Brillouin zone (3D: a plane through it) and the growth a finite box
//! of free particles can show, for any D ([`Query`]).

// Small-vector algebra (D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::query::Query;
use crate::error::Result;
use crate::lattice::grid_index;
use crate::params::check_count;
use crate::progress::{Counter, Progress};
use crate::vonneumann::linearise::Bloch;
use rayon::prelude::*;
use serde::Serialize;
use std::f64::consts::PI;

/// Largest `box` (free particles per side): 1000² standing modes take ~4 s.
pub const MAX_BOX: usize = 1000;
/// Largest `box` in 3D: 100³ = 1e6 standing modes (the 2D bound's count).
pub const MAX_BOX_3D: usize = 100;

/// Largest `box` in dimension `dim`.
pub const fn max_box(dim: usize) -> usize {
    if dim == 3 { MAX_BOX_3D } else { MAX_BOX }
}

/// Largest `n` of a growth map (same cost per wave vector as `grid`).
pub const MAX_MAP_N: usize = 1024;

/// Growth-rate map over the zone: (κx, κy) grid and γ; in 3D over a plane ([`Plane`]).
#[derive(Clone, Debug, Serialize)]
pub struct GrowthMap {
    /// κxΔx values (3D: the first in-plane coordinate).
    pub kx: Vec<f64>,
    /// κyΔx values (3D: the second in-plane coordinate).
    pub ky: Vec<f64>,
    /// γ at (kx\[i\], ky\[j\]), indexed `growth[i][j]` (c/Δx).
    pub growth: Vec<Vec<f64>>,
    /// Largest ω² (for the critical Δt).
    pub omega2_max: f64,
    /// 3D: the plane (in-plane unit vectors e_u, e_v; k = kx e_u + ky e_v); null in 2D.
    pub plane: Option<[[f64; 3]; 2]>,
}

/// A plane through Γ of the 3D zone for `map --dim 3 --plane`: k = u e_u + v e_v.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Plane {
    /// k_z = 0: e_u = x̂, e_v = ŷ.
    Xy,
    /// k_y = 0: e_u = x̂, e_v = ẑ.
    Xz,
    /// k_x = 0: e_u = ŷ, e_v = ẑ.
    Yz,
    /// The (1, −1, 0) mirror plane: e_u = (x̂ + ŷ)/√2, e_v = ẑ (contains Γ–M–R of sc).
    Diagonal,
}

impl Plane {
    /// All planes with their CLI names.
    pub const ALL: [(Plane, &'static str); 4] = [
        (Plane::Xy, "xy"),
        (Plane::Xz, "xz"),
        (Plane::Yz, "yz"),
        (Plane::Diagonal, "diagonal"),
    ];

    /// By CLI name.
    pub fn by_name(name: &str) -> Result<Self> {
        crate::error::lookup("plane", &Self::ALL, name)
    }

    /// The in-plane unit vectors (e_u, e_v).
    pub fn basis(self) -> [[f64; 3]; 2] {
        let r = std::f64::consts::FRAC_1_SQRT_2;
        match self {
            Plane::Xy => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            Plane::Xz => [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
            Plane::Yz => [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            Plane::Diagonal => [[r, r, 0.0], [0.0, 0.0, 1.0]],
        }
    }
}

/// Growth over the square [−π, π]² (n × n) of wave vectors: (κx, κy) in 2D, (u, v) on `plane`
/// in 3D (ignored in 2D), any lattice. Rows are computed in parallel; each finished row is
/// reported to `progress`, which can stop the map between rows.
pub fn growth_map<const D: usize>(
    q: &Query<D>,
    n: usize,
    plane: Plane,
    progress: &dyn Progress,
) -> Result<GrowthMap> {
    check_count("n", n, 2, MAX_MAP_N)?;
    let lin = q.linearise_at(q.stress)?;
    let ax: Vec<f64> = (0..n)
        .map(|i| -PI + 2.0 * PI * (i as f64 + 0.5) / n as f64)
        .collect();
    let e = plane.basis();
    let at = |u: f64, v: f64| {
        let mut k = [0.0; D];
        if D == 2 {
            k[0] = u;
            k[1] = v;
        } else {
            for c in 0..D {
                k[c] = u * e[0][c] + v * e[1][c];
            }
        }
        k
    };
    // rows in parallel, one J(k) per wave vector
    let done = Counter::new(progress, n, 1);
    let rows: Vec<(Vec<f64>, f64)> = ax
        .par_iter()
        .map(|&kx| {
            let mut row = Vec::with_capacity(n);
            let mut w2: f64 = 0.0;
            for &ky in &ax {
                let (g, _, top) = lin.growth_and_top(at(kx, ky))?;
                row.push(g);
                w2 = w2.max(top);
            }
            done.add(1)?;
            Ok((row, w2))
        })
        .collect::<Result<_>>()?;
    let w2 = rows.iter().fold(0.0f64, |m, r| m.max(r.1));
    let g: Vec<Vec<f64>> = rows.into_iter().map(|r| r.0).collect();
    Ok(GrowthMap {
        kx: ax.clone(),
        ky: ax,
        growth: g,
        omega2_max: w2,
        plane: (D == 3).then_some(e),
    })
}

/// The growth rate a box of n_free^D free particles between fixed boundary layers can show:
/// standing modes sin(mπi/(n+1)) admit k = (m_1, …, m_D)π/(n+1), m_a = 1..n; the largest growth
/// over those wave vectors, and where.
pub fn box_prediction<const D: usize>(lin: &Bloch<D>, n_free: usize) -> Result<(f64, [f64; D])> {
    check_count("box", n_free, 1, max_box(D))?;
    let mut best = (0.0, [0.0; D]);
    let d = PI / (n_free as f64 + 1.0);
    for idx in 0..n_free.pow(D as u32) {
        let k = grid_index::<D>(idx, n_free).map(|m| (m + 1) as f64 * d);
        let g = lin.growth(k)?.0;
        if g > best.0 {
            best = (g, k);
        }
    }
    Ok(best)
}
