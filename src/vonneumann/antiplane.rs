//! Anti-plane (scalar wave) analysis in 2D \[B00 §4.4\]: Galerkin stiffness
//! K_IJ = ∫ ∇φ_I · ∇φ_J dΩ and mass M_IJ = ∫ φ_I φ_J dΩ (or lumped), integrated with the
//! quadrature and stress-point patterns of \[B00\] Fig 12, and the normalised frequency ωΔx/c of
//! a plane wave along any direction θ \[B00 eq 116–119\].
//!
//! A *pattern* is a periodic cell (possibly a supercell of the node lattice) holding node sites
//! and integration points with weights. Stress-point weights are Voronoi areas of the combined
//! point set (nodes + stress points, \[B00\] eq 60); background-cell rules use the cell area.

use crate::error::{Error, Result, field};
use crate::lattice::{Lattice, LatticeKind};
use crate::shape::ShapeFamily;
use crate::shape::{KernelParams, eval_d};
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::collections::BTreeMap;

/// Integration scheme of the Galerkin integrals.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Quadrature {
    /// Nodal integration (one point per node, weight = cell area).
    Nodal,
    /// One point per background cell, at its centre.
    Cell1,
    /// 2×2 Gauss points per background cell.
    Cell2x2,
    /// Nodes + stress points at the centres of the quadrilaterals \[B00 Fig 12(a)\].
    StressQuad,
    /// Nodes + stress points at the centroids of the two triangles of each quadrilateral,
    /// all diagonals parallel \[Fig 12(b)\].
    StressTri,
    /// Nodes + triangle centroids with alternating diagonals (star pattern) \[Fig 12(c)\].
    StressStar,
    /// Hexagonal node lattice + the centroids of all its triangles \[Fig 12(d)\].
    StressHex,
}

impl Quadrature {
    /// All schemes with CLI names.
    pub const ALL: [(Quadrature, &'static str); 7] = [
        (Quadrature::Nodal, "nodal"),
        (Quadrature::Cell1, "cell-1"),
        (Quadrature::Cell2x2, "cell-2x2"),
        (Quadrature::StressQuad, "stress-quad"),
        (Quadrature::StressTri, "stress-tri"),
        (Quadrature::StressStar, "stress-star"),
        (Quadrature::StressHex, "stress-hex"),
    ];

    /// CLI name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }

    /// By CLI name.
    pub fn by_name(name: &str) -> Result<Self> {
        crate::error::lookup("quadrature", &Self::ALL, name)
    }
}

/// Nodes and integration points of one periodic cell.
#[derive(Clone, Debug)]
pub struct Pattern {
    /// Cell vectors (a supercell of the node lattice for the star pattern).
    pub cell: [[f64; 2]; 2],
    /// Node sites in the cell.
    pub sites: Vec<[f64; 2]>,
    /// Integration points in the cell with their weights (areas).
    pub points: Vec<([f64; 2], f64)>,
}

fn polygon_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    (0..n)
        .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
        .sum::<f64>()
        .abs()
        / 2.0
}

/// Clips a convex polygon to the half-plane {x : (x − m)·n ≤ 0}.
fn clip(poly: &[[f64; 2]], m: [f64; 2], n: [f64; 2]) -> Vec<[f64; 2]> {
    let side = |p: [f64; 2]| (p[0] - m[0]) * n[0] + (p[1] - m[1]) * n[1];
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (sa, sb) = (side(a), side(b));
        if sa <= 0.0 {
            out.push(a);
        }
        if (sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0) {
            let t = sa / (sa - sb);
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}

/// Voronoi cell areas of a periodic point set (points in one cell, periodic with `cell`), by
/// clipping a large square with the bisector half-planes of every nearby image.
pub fn voronoi_areas(cell: [[f64; 2]; 2], pts: &[[f64; 2]]) -> Vec<f64> {
    let size = (cell[0][0].abs() + cell[1][0].abs()).max(cell[0][1].abs() + cell[1][1].abs()) * 2.0;
    pts.iter()
        .map(|&p| {
            let mut poly = vec![
                [p[0] - size, p[1] - size],
                [p[0] + size, p[1] - size],
                [p[0] + size, p[1] + size],
                [p[0] - size, p[1] + size],
            ];
            for m in -3i64..=3 {
                for n in -3i64..=3 {
                    for &q in pts {
                        let qi = [
                            q[0] + m as f64 * cell[0][0] + n as f64 * cell[1][0],
                            q[1] + m as f64 * cell[0][1] + n as f64 * cell[1][1],
                        ];
                        let d = [qi[0] - p[0], qi[1] - p[1]];
                        if d[0].abs() < 1e-12 && d[1].abs() < 1e-12 {
                            continue;
                        }
                        poly = clip(&poly, [p[0] + d[0] / 2.0, p[1] + d[1] / 2.0], d);
                    }
                }
            }
            polygon_area(&poly)
        })
        .collect()
}

impl Pattern {
    /// The pattern of `q` on lattice `lat`.
    pub fn new(lat: &Lattice<2>, q: Quadrature) -> Result<Self> {
        let (a1, a2) = (lat.a[0], lat.a[1]);
        let at = |s: f64, t: f64| [s * a1[0] + t * a2[0], s * a1[1] + t * a2[1]];
        let area = lat.area();
        let with_voronoi = |cell: [[f64; 2]; 2], sites: Vec<[f64; 2]>, extra: Vec<[f64; 2]>| {
            let all: Vec<[f64; 2]> = sites.iter().chain(&extra).copied().collect();
            let w = voronoi_areas(cell, &all);
            Pattern {
                cell,
                sites,
                points: all.into_iter().zip(w).collect(),
            }
        };
        let square = matches!(lat.kind, LatticeKind::Square { .. });
        match (q, square) {
            (Quadrature::Nodal, _) => Ok(Pattern {
                cell: lat.a,
                sites: vec![[0.0, 0.0]],
                points: vec![([0.0, 0.0], area)],
            }),
            (Quadrature::Cell1, true) => Ok(Pattern {
                cell: lat.a,
                sites: vec![[0.0, 0.0]],
                points: vec![(at(0.5, 0.5), area)],
            }),
            (Quadrature::Cell2x2, true) => {
                let g = 0.5 / 3f64.sqrt();
                let pts = [
                    (0.5 - g, 0.5 - g),
                    (0.5 + g, 0.5 - g),
                    (0.5 - g, 0.5 + g),
                    (0.5 + g, 0.5 + g),
                ];
                Ok(Pattern {
                    cell: lat.a,
                    sites: vec![[0.0, 0.0]],
                    points: pts.iter().map(|&(s, t)| (at(s, t), area / 4.0)).collect(),
                })
            }
            (Quadrature::StressQuad, true) => {
                Ok(with_voronoi(lat.a, vec![[0.0, 0.0]], vec![at(0.5, 0.5)]))
            }
            (Quadrature::StressTri, true) => Ok(with_voronoi(
                lat.a,
                vec![[0.0, 0.0]],
                vec![at(2.0 / 3.0, 1.0 / 3.0), at(1.0 / 3.0, 2.0 / 3.0)],
            )),
            (Quadrature::StressStar, true) => {
                // 2×2 supercell; the diagonal of cell (i, j) joins (0,0)-(1,1) when i + j is even,
                // (1,0)-(0,1) otherwise: the diagonals meet at the supercell centre (star).
                let cell = [[2.0 * a1[0], 2.0 * a1[1]], [2.0 * a2[0], 2.0 * a2[1]]];
                let mut sites = Vec::new();
                let mut sp = Vec::new();
                for i in 0..2 {
                    for j in 0..2 {
                        let (fi, fj) = (i as f64, j as f64);
                        sites.push(at(fi, fj));
                        if (i + j) % 2 == 0 {
                            sp.push(at(fi + 2.0 / 3.0, fj + 1.0 / 3.0));
                            sp.push(at(fi + 1.0 / 3.0, fj + 2.0 / 3.0));
                        } else {
                            sp.push(at(fi + 1.0 / 3.0, fj + 1.0 / 3.0));
                            sp.push(at(fi + 2.0 / 3.0, fj + 2.0 / 3.0));
                        }
                    }
                }
                Ok(with_voronoi(cell, sites, sp))
            }
            (Quadrature::StressHex, false) => Ok(with_voronoi(
                lat.a,
                vec![[0.0, 0.0]],
                vec![at(1.0 / 3.0, 1.0 / 3.0), at(2.0 / 3.0, 2.0 / 3.0)],
            )),
            (q, _) => Err(Error::Incompatible(
                field("quadrature")
                    + format!(
                        " {} is not defined on a {} lattice (square: nodal, cell-1, cell-2x2, stress-quad, stress-tri, stress-star; hex: nodal, stress-hex)",
                        q.name(),
                        if square { "square" } else { "hex" }
                    ),
            )),
        }
    }
}

/// Galerkin matrices of the anti-plane problem on a periodic pattern, stored per pair of sites
/// and cell offset.
#[derive(Clone, Debug)]
pub struct AntiPlane {
    /// The pattern.
    pub pattern: Pattern,
    /// K_{s,t}(offset): stiffness between site s of cell 0 and site t of cell `offset`.
    pub stiffness: BTreeMap<(usize, usize, [i64; 2]), f64>,
    /// Consistent mass, same indexing.
    pub mass: BTreeMap<(usize, usize, [i64; 2]), f64>,
    /// Lumped (row-sum) masses per site.
    pub lumped: Vec<f64>,
}

/// Mass treatment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mass {
    /// Row-sum lumped mass (for partition-of-unity shapes, the integration weights).
    Lumped,
    /// Consistent mass ∫ φ_I φ_J.
    Consistent,
}

impl AntiPlane {
    /// Assembles K and M for shape `family` with kernel parameters `kp` (h in units of Δx).
    pub fn new(
        lat: &Lattice<2>,
        q: Quadrature,
        family: ShapeFamily,
        kp: KernelParams,
    ) -> Result<Self> {
        let pattern = Pattern::new(lat, q)?;
        let r = kp.support();
        let c = pattern.cell;
        let ns = pattern.sites.len();
        let cell_area = (c[0][0] * c[1][1] - c[0][1] * c[1][0]).abs();
        let vol = cell_area / ns as f64;
        let nmax = (r / (cell_area / c[0][0].hypot(c[0][1]).max(c[1][0].hypot(c[1][1])))).ceil()
            as i64
            + 2;
        let mut stiffness = BTreeMap::new();
        let mut mass = BTreeMap::new();
        let mut out = Vec::new();
        for &(xq, w) in &pattern.points {
            let mut nodes = Vec::new();
            let mut ids = Vec::new();
            for m in -nmax..=nmax {
                for n in -nmax..=nmax {
                    for (s, site) in pattern.sites.iter().enumerate() {
                        let p = [
                            site[0] + m as f64 * c[0][0] + n as f64 * c[1][0],
                            site[1] + m as f64 * c[0][1] + n as f64 * c[1][1],
                        ];
                        let d = [p[0] - xq[0], p[1] - xq[1]];
                        if d[0].hypot(d[1]) < r {
                            nodes.push((d, vol));
                            ids.push((s, [m, n]));
                        }
                    }
                }
            }
            eval_d(family, kp, &nodes, xq[0], &mut out)?;
            for (a, &(sa, ra)) in ids.iter().enumerate() {
                for (b, &(sb, rb)) in ids.iter().enumerate() {
                    let key = (sa, sb, [rb[0] - ra[0], rb[1] - ra[1]]);
                    let kab = w * (out[a].1[0] * out[b].1[0] + out[a].1[1] * out[b].1[1]);
                    *stiffness.entry(key).or_insert(0.0) += kab;
                    *mass.entry(key).or_insert(0.0) += w * out[a].0 * out[b].0;
                }
            }
        }
        let mut lumped = vec![0.0; ns];
        for (&(s, _, _), &m) in &mass {
            lumped[s] += m;
        }
        Ok(Self {
            pattern,
            stiffness,
            mass,
            lumped,
        })
    }

    fn symbol(
        &self,
        map: &BTreeMap<(usize, usize, [i64; 2]), f64>,
        k: [f64; 2],
    ) -> DMatrix<Complex64> {
        let ns = self.pattern.sites.len();
        let c = self.pattern.cell;
        let mut m = DMatrix::<Complex64>::zeros(ns, ns);
        for (&(s, t, off), &v) in map {
            let r = [
                off[0] as f64 * c[0][0] + off[1] as f64 * c[1][0] + self.pattern.sites[t][0]
                    - self.pattern.sites[s][0],
                off[0] as f64 * c[0][1] + off[1] as f64 * c[1][1] + self.pattern.sites[t][1]
                    - self.pattern.sites[s][1],
            ];
            m[(s, t)] += Complex64::from_polar(v, k[0] * r[0] + k[1] * r[1]);
        }
        m
    }

    /// (ωΔx/c)² of every branch at wave vector k (units of 1/Δx), ascending.
    pub fn omega2(&self, k: [f64; 2], mass: Mass) -> Result<Vec<f64>> {
        let kk = self.symbol(&self.stiffness, k);
        let ns = kk.nrows();
        let a = match mass {
            Mass::Lumped => {
                let mut a = kk.clone();
                for i in 0..ns {
                    for j in 0..ns {
                        a[(i, j)] /= (self.lumped[i] * self.lumped[j]).sqrt();
                    }
                }
                a
            }
            Mass::Consistent => {
                let m = self.symbol(&self.mass, k);
                let l = m
                    .cholesky()
                    .ok_or(Error::NonFinite("consistent mass not positive definite"))?;
                let linv = l.l().try_inverse().ok_or(Error::NonFinite("mass factor"))?;
                &linv * kk * linv.adjoint()
            }
        };
        let h = (&a + a.adjoint()) * Complex64::new(0.5, 0.0);
        let mut ev: Vec<f64> = nalgebra::SymmetricEigen::try_new(h, f64::EPSILON, 10_000)
            .ok_or(Error::NonFinite("Hermitian eigenvalues"))?
            .eigenvalues
            .iter()
            .copied()
            .collect();
        ev.sort_by(|a, b| a.total_cmp(b));
        Ok(ev)
    }

    /// Stiffness entries K_{0,(j,k)} of a single-site pattern, j ≥ 0, k ≥ 0 (the table is
    /// symmetric under j → −j and k → −k).
    pub fn stiffness_table(&self) -> Result<Vec<(i64, i64, f64)>> {
        if self.pattern.sites.len() != 1 {
            return Err(Error::Incompatible(
                "the stiffness table is defined for one node per cell (not stress-star)".into(),
            ));
        }
        // Square lattices: j ≥ 0, k ≥ 0 (K even in j and in k); others: the half-plane
        // j > 0 or (j = 0, k ≥ 0), since only K(−o) = K(o) holds.
        let c = self.pattern.cell;
        let rectangular = c[0][1] == 0.0 && c[1][0] == 0.0;
        Ok(self
            .stiffness
            .iter()
            .filter(|((_, _, o), _)| {
                if rectangular {
                    o[0] >= 0 && o[1] >= 0
                } else {
                    o[0] > 0 || (o[0] == 0 && o[1] >= 0)
                }
            })
            .map(|((_, _, o), &v)| (o[0], o[1], v))
            .collect())
    }
}

impl AntiPlane {
    /// Spurious zero-frequency modes at the cut-off of a square lattice: (θ = 0°, θ = 45°) —
    /// true where more branches than the rigid mode (only at the supercell Γ) have ω² ≤ tol.
    pub fn spurious_at_cutoff(&self, gamma: f64) -> Result<(bool, bool)> {
        use std::f64::consts::PI;
        let tol = 1e-10;
        let count = |k: [f64; 2]| -> Result<usize> {
            Ok(self
                .omega2(k, Mass::Lumped)?
                .iter()
                .filter(|w| w.abs() <= tol)
                .count())
        };
        // for a supercell, the primitive cut-off wave vectors may fold onto Γ (rigid mode)
        let rigid = |k: [f64; 2]| -> usize {
            let c = self.pattern.cell;
            let ph0 = (k[0] * c[0][0] + k[1] * c[0][1]) / (2.0 * PI);
            let ph1 = (k[0] * c[1][0] + k[1] * c[1][1]) / (2.0 * PI);
            usize::from((ph0 - ph0.round()).abs() < 1e-12 && (ph1 - ph1.round()).abs() < 1e-12)
        };
        let k0 = [PI, 0.0];
        let k45 = [PI, PI / gamma];
        Ok((count(k0)? > rigid(k0), count(k45)? > rigid(k45)))
    }
}
