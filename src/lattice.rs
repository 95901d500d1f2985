//! Uniform 2D lattices (square with Δy = γΔx, and hexagonal), their reciprocal vectors,
//! neighbour offsets within a radius, and the high-symmetry paths of the first Brillouin zone
//! (square: Γ–X–M–Γ; hexagonal: Γ–M–K–Γ). Lengths in units of Δx.

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::error::{Error, Result};
use std::f64::consts::PI;

/// Lattice geometry.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LatticeKind {
    /// Rectangular: a1 = (1, 0), a2 = (0, γ).
    Square {
        /// Aspect ratio γ = Δy/Δx.
        gamma: f64,
    },
    /// Triangular (hexagonal) with nearest-neighbour distance 1: a1 = (1, 0), a2 = (½, √3/2).
    Hexagonal,
}

/// A 2D Bravais lattice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice2D {
    /// Geometry.
    pub kind: LatticeKind,
    /// Primitive vectors.
    pub a: [[f64; 2]; 2],
}

impl Lattice2D {
    /// Square (rectangular) lattice with aspect ratio γ.
    pub fn square(gamma: f64) -> Result<Self> {
        crate::error::check_range("--gamma", gamma, 0.1, 10.0, true, true)?;
        Ok(Self {
            kind: LatticeKind::Square { gamma },
            a: [[1.0, 0.0], [0.0, gamma]],
        })
    }

    /// Hexagonal (triangular) lattice of unit spacing.
    pub fn hexagonal() -> Self {
        Self {
            kind: LatticeKind::Hexagonal,
            a: [[1.0, 0.0], [0.5, 3f64.sqrt() / 2.0]],
        }
    }

    /// By CLI name (`square`, `hex`).
    pub fn by_name(name: &str, gamma: f64) -> Result<Self> {
        match name {
            "square" => Self::square(gamma),
            "hex" => Ok(Self::hexagonal()),
            _ => Err(Error::UnknownName {
                what: "lattice",
                given: name.into(),
                valid: "square, hex".into(),
            }),
        }
    }

    /// Cell area.
    pub fn area(&self) -> f64 {
        (self.a[0][0] * self.a[1][1] - self.a[0][1] * self.a[1][0]).abs()
    }

    /// Position of lattice point (m, n).
    pub fn point(&self, m: i64, n: i64) -> [f64; 2] {
        [
            m as f64 * self.a[0][0] + n as f64 * self.a[1][0],
            m as f64 * self.a[0][1] + n as f64 * self.a[1][1],
        ]
    }

    /// Reciprocal vectors b_i with a_i · b_j = 2π δ_ij.
    pub fn reciprocal(&self) -> [[f64; 2]; 2] {
        let det = self.a[0][0] * self.a[1][1] - self.a[0][1] * self.a[1][0];
        let s = 2.0 * PI / det;
        [
            [s * self.a[1][1], -s * self.a[1][0]],
            [-s * self.a[0][1], s * self.a[0][0]],
        ]
    }

    /// All lattice offsets (m, n) with |m a1 + n a2| < r, and their positions.
    pub fn offsets_within(&self, r: f64) -> Vec<([i64; 2], [f64; 2])> {
        let amin = self
            .a
            .iter()
            .map(|v| (v[0] * v[0] + v[1] * v[1]).sqrt())
            .fold(f64::INFINITY, f64::min);
        let hmin = self.area()
            / self
                .a
                .iter()
                .map(|v| (v[0] * v[0] + v[1] * v[1]).sqrt())
                .fold(0.0, f64::max);
        let nmax = (r / amin.min(hmin)).ceil() as i64 + 2;
        let mut out = Vec::new();
        for m in -nmax..=nmax {
            for n in -nmax..=nmax {
                let p = self.point(m, n);
                if (p[0] * p[0] + p[1] * p[1]).sqrt() < r {
                    out.push(([m, n], p));
                }
            }
        }
        out
    }

    /// Distance from Γ to the first-zone boundary along direction θ (radians): the smallest
    /// |G|²/(2 G·n̂) over the nearest reciprocal-lattice vectors G with G·n̂ > 0.
    pub fn zone_boundary(&self, theta: f64) -> f64 {
        let n = [theta.cos(), theta.sin()];
        let b = self.reciprocal();
        let mut best = f64::INFINITY;
        for m in -2i64..=2 {
            for l in -2i64..=2 {
                let g = [
                    m as f64 * b[0][0] + l as f64 * b[1][0],
                    m as f64 * b[0][1] + l as f64 * b[1][1],
                ];
                let gn = g[0] * n[0] + g[1] * n[1];
                if gn > 1e-12 {
                    best = best.min((g[0] * g[0] + g[1] * g[1]) / (2.0 * gn));
                }
            }
        }
        best
    }

    /// The high-symmetry points of the first Brillouin zone, in path order, with labels.
    pub fn symmetry_points(&self) -> Vec<(&'static str, [f64; 2])> {
        match self.kind {
            LatticeKind::Square { gamma } => {
                vec![
                    ("Γ", [0.0, 0.0]),
                    ("X", [PI, 0.0]),
                    ("M", [PI, PI / gamma]),
                    ("Γ", [0.0, 0.0]),
                ]
            }
            LatticeKind::Hexagonal => {
                vec![
                    ("Γ", [0.0, 0.0]),
                    ("M", [PI, PI / 3f64.sqrt()]),
                    ("K", [4.0 * PI / 3.0, 0.0]),
                    ("Γ", [0.0, 0.0]),
                ]
            }
        }
    }

    /// `n` points per segment along the high-symmetry path: (wave vector, arc length).
    pub fn symmetry_path(&self, n: usize) -> Vec<([f64; 2], f64)> {
        let pts = self.symmetry_points();
        let mut out = Vec::new();
        let mut s = 0.0;
        for w in pts.windows(2) {
            let (a, b) = (w[0].1, w[1].1);
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            for i in 0..n {
                let t = i as f64 / n as f64;
                out.push((
                    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])],
                    s + t * len,
                ));
            }
            s += len;
        }
        out.push((pts[pts.len() - 1].1, s));
        out
    }
}

impl std::fmt::Display for LatticeKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LatticeKind::Square { gamma } if *gamma == 1.0 => write!(f, "square lattice"),
            LatticeKind::Square { gamma } => write!(f, "square lattice γ = {gamma}"),
            LatticeKind::Hexagonal => write!(f, "hexagonal lattice"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reciprocal_vectors_are_dual() {
        for l in [Lattice2D::square(1.3).unwrap(), Lattice2D::hexagonal()] {
            let b = l.reciprocal();
            for i in 0..2 {
                for j in 0..2 {
                    let d = l.a[i][0] * b[j][0] + l.a[i][1] * b[j][1];
                    let want = if i == j { 2.0 * PI } else { 0.0 };
                    assert!((d - want).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn zone_boundary_distances() {
        let s = Lattice2D::square(1.0).unwrap();
        assert!((s.zone_boundary(0.0) - PI).abs() < 1e-12);
        assert!((s.zone_boundary(PI / 4.0) - PI * 2f64.sqrt()).abs() < 1e-12);
        let h = Lattice2D::hexagonal();
        // Γ–K along x: 4π/3; Γ–M along 30°: 2π/√3
        assert!((h.zone_boundary(0.0) - 4.0 * PI / 3.0).abs() < 1e-12);
        assert!((h.zone_boundary(PI / 6.0) - 2.0 * PI / 3f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn hexagonal_k_point_is_a_zone_corner() {
        // K is equidistant from Γ and from the nearest reciprocal lattice points b1 and b1 + b2.
        let l = Lattice2D::hexagonal();
        let b = l.reciprocal();
        let k = [4.0 * PI / 3.0, 0.0];
        let d = |p: [f64; 2]| ((k[0] - p[0]).powi(2) + (k[1] - p[1]).powi(2)).sqrt();
        let g = d([0.0, 0.0]);
        assert!((d(b[0]) - g).abs() < 1e-12);
        assert!((d([b[0][0] + b[1][0], b[0][1] + b[1][1]]) - g).abs() < 1e-12);
    }
}
