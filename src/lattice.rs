//! Uniform Bravais lattices in D ∈ {1, 2, 3} dimensions ([`Lattice`]), their reciprocal vectors,
//! neighbour offsets within a radius, Brillouin-zone folding and the high-symmetry paths of the
//! first Brillouin zone. Lengths in units of Δx.
//!
//! | lattice | primitive vectors | Δx | path |
//! |---|---|---|---|
//! | `chain` (1D, no CLI name) | (1) | the spacing | Γ–X |
//! | `square` (γ) | (1, 0), (0, γ) | the x spacing | Γ–X–M–Γ |
//! | `hex` | (1, 0), (½, √3/2) | nearest-neighbour distance | Γ–M–K–Γ |
//! | `sc` | (1,0,0), (0,1,0), (0,0,1) | spacing = (volume per particle)^⅓ | Γ–X–M–Γ–R–X |
//! | `bcc` | (a/2)(−1,1,1), (a/2)(1,−1,1), (a/2)(1,1,−1), a = 2^⅓ | (volume per particle)^⅓ | Γ–H–N–Γ–P–H |
//! | `fcc` | (a/2)(0,1,1), (a/2)(1,0,1), (a/2)(1,1,0), a = 4^⅓ | (volume per particle)^⅓ | Γ–X–W–L–Γ–K |
//!
//! In 3D Δx is the cube root of the volume per particle, so that sc, bcc and fcc at the same Δx
//! have the same density; a is the side of the conventional cube (1, 2^⅓ ≈ 1.2599, 4^⅓ ≈
//! 1.5874) and the nearest-neighbour distance is 1, (√3/2)2^⅓ ≈ 1.0911 and 4^⅓/√2 ≈ 1.1225.

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::error::{Error, Result, Text, field};
use std::f64::consts::PI;

/// Lattice geometry.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LatticeKind {
    /// The uniform 1D chain of unit spacing (used by the closed forms; no 1D question names a
    /// lattice).
    Chain,
    /// Rectangular: a1 = (1, 0), a2 = (0, γ).
    Square {
        /// Aspect ratio γ = Δy/Δx.
        gamma: f64,
    },
    /// Triangular (hexagonal) with nearest-neighbour distance 1: a1 = (1, 0), a2 = (½, √3/2).
    Hexagonal,
    /// Simple cubic.
    Sc,
    /// Body-centred cubic.
    Bcc,
    /// Face-centred cubic.
    Fcc,
}

/// A Bravais lattice in D dimensions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice<const D: usize> {
    /// Geometry.
    pub kind: LatticeKind,
    /// Primitive vectors.
    pub a: [[f64; D]; D],
}

impl Lattice<1> {
    /// The uniform chain of unit spacing.
    pub fn chain() -> Self {
        Self {
            kind: LatticeKind::Chain,
            a: [[1.0]],
        }
    }
}

impl Lattice<2> {
    /// Square (rectangular) lattice with aspect ratio γ.
    pub fn square(gamma: f64) -> Result<Self> {
        crate::error::check_range("gamma", gamma, 0.1, 10.0, true, true)?;
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
                what: "lattice".into(),
                given: name.into(),
                valid: Text::from("square, hex (") + field("dim") + " 2)",
            }),
        }
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
}

impl Lattice<3> {
    /// Simple cubic lattice of unit spacing.
    pub fn sc() -> Self {
        Self {
            kind: LatticeKind::Sc,
            a: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        }
    }

    /// Body-centred cubic lattice with unit volume per particle (cube side 2^⅓).
    pub fn bcc() -> Self {
        let h = 0.5 * 2f64.cbrt();
        Self {
            kind: LatticeKind::Bcc,
            a: [[-h, h, h], [h, -h, h], [h, h, -h]],
        }
    }

    /// Face-centred cubic lattice with unit volume per particle (cube side 4^⅓).
    pub fn fcc() -> Self {
        let h = 0.5 * 4f64.cbrt();
        Self {
            kind: LatticeKind::Fcc,
            a: [[0.0, h, h], [h, 0.0, h], [h, h, 0.0]],
        }
    }

    /// By CLI name (`sc`, `bcc`, `fcc`).
    pub fn by_name(name: &str) -> Result<Self> {
        match name {
            "sc" => Ok(Self::sc()),
            "bcc" => Ok(Self::bcc()),
            "fcc" => Ok(Self::fcc()),
            _ => Err(Error::UnknownName {
                what: "lattice".into(),
                given: name.into(),
                valid: Text::from("sc, bcc, fcc (") + field("dim") + " 3)",
            }),
        }
    }

    /// Side of the conventional cube (1, 2^⅓, 4^⅓ for sc, bcc, fcc).
    pub fn cube_side(&self) -> f64 {
        match self.kind {
            LatticeKind::Bcc => 2f64.cbrt(),
            LatticeKind::Fcc => 4f64.cbrt(),
            _ => 1.0,
        }
    }

    /// Particles of one conventional cube of side [`Lattice::cube_side`] (1, 2, 4), in units
    /// of the cube side: a periodic box of whole cubes is orthogonal.
    pub fn cube_basis(&self) -> Vec<[f64; 3]> {
        match self.kind {
            LatticeKind::Bcc => vec![[0.0; 3], [0.5; 3]],
            LatticeKind::Fcc => vec![[0.0; 3], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5], [0.5, 0.5, 0.0]],
            _ => vec![[0.0; 3]],
        }
    }
}

impl<const D: usize> Lattice<D> {
    /// The lattice of `kind`; an error if `kind` is not a lattice of dimension D.
    pub fn of_kind(kind: LatticeKind) -> Result<Self> {
        let (dim, a3): (usize, [[f64; 3]; 3]) = match kind {
            LatticeKind::Chain => (1, [[1.0, 0.0, 0.0], [0.0; 3], [0.0; 3]]),
            LatticeKind::Square { gamma } => {
                crate::error::check_range("gamma", gamma, 0.1, 10.0, true, true)?;
                (2, [[1.0, 0.0, 0.0], [0.0, gamma, 0.0], [0.0; 3]])
            }
            LatticeKind::Hexagonal => (
                2,
                [[1.0, 0.0, 0.0], [0.5, 3f64.sqrt() / 2.0, 0.0], [0.0; 3]],
            ),
            LatticeKind::Sc => (3, Lattice::<3>::sc().a),
            LatticeKind::Bcc => (3, Lattice::<3>::bcc().a),
            LatticeKind::Fcc => (3, Lattice::<3>::fcc().a),
        };
        if dim != D {
            return Err(Error::Incompatible(
                field("lattice")
                    + format!(": the {kind} is {dim}-dimensional, not {D}-dimensional (")
                    + field("dim")
                    + " 2: square, hex; "
                    + field("dim")
                    + " 3: sc, bcc, fcc)",
            ));
        }
        let mut a = [[0.0; D]; D];
        for i in 0..D {
            a[i].copy_from_slice(&a3[i][..D]);
        }
        Ok(Self { kind, a })
    }

    /// By name: `square` (aspect ratio `gamma`) or `hex` in 2D, `sc`, `bcc` or `fcc` in 3D.
    pub fn named(name: &str, gamma: f64) -> Result<Self> {
        let kind = match name {
            "square" => LatticeKind::Square { gamma },
            "hex" => LatticeKind::Hexagonal,
            "sc" => LatticeKind::Sc,
            "bcc" => LatticeKind::Bcc,
            "fcc" => LatticeKind::Fcc,
            _ => {
                return Err(Error::UnknownName {
                    what: "lattice".into(),
                    given: name.into(),
                    valid: if D == 3 {
                        "sc, bcc, fcc".into()
                    } else {
                        "square, hex".into()
                    },
                });
            }
        };
        Self::of_kind(kind)
    }

    /// Cell length (1D), area (2D) or volume (3D): |det a|, the length, area or volume per
    /// particle.
    pub fn area(&self) -> f64 {
        det(&self.a).abs()
    }

    /// Smallest distance between two lattice planes spanned by D − 1 primitive vectors
    /// (|det a| / the largest |(D − 1)-face|): a box of n cells per direction holds a ball of
    /// radius n·spacing/2.
    pub fn plane_spacing(&self) -> f64 {
        if D == 1 {
            return self.area();
        }
        if D == 2 {
            let amax = self.a.iter().map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
            return self.area() / amax;
        }
        let mut fmax: f64 = 0.0;
        for i in 0..D {
            let (u, v) = (self.a[(i + 1) % D], self.a[(i + 2) % D]);
            let c = cross3(&u, &v);
            fmax = fmax.max(norm(&c));
        }
        self.area() / fmax
    }

    /// Position of lattice point m (integer coordinates).
    pub fn point_at(&self, m: [i64; D]) -> [f64; D] {
        let mut p = [0.0; D];
        for a in 0..D {
            for i in 0..D {
                p[a] += m[i] as f64 * self.a[i][a];
            }
        }
        p
    }

    /// Reciprocal vectors b_i with a_i · b_j = 2π δ_ij.
    pub fn reciprocal(&self) -> [[f64; D]; D] {
        let mut b = [[0.0; D]; D];
        let det = det(&self.a);
        if D == 1 {
            b[0][0] = 2.0 * PI / det;
            return b;
        }
        if D == 2 {
            let s = 2.0 * PI / det;
            b[0][0] = s * self.a[1][1];
            b[0][1] = -s * self.a[1][0];
            b[1][0] = -s * self.a[0][1];
            b[1][1] = s * self.a[0][0];
            return b;
        }
        // 3D: b_i = 2π (a_j × a_k) / det
        for i in 0..D {
            let c = cross3(&self.a[(i + 1) % 3], &self.a[(i + 2) % 3]);
            for a in 0..D {
                b[i][a] = 2.0 * PI * c[a] / det;
            }
        }
        b
    }

    /// All lattice offsets m with |Σ m_i a_i| < r, and their positions.
    pub fn offsets_within(&self, r: f64) -> Vec<([i64; D], [f64; D])> {
        let amin = self.a.iter().map(norm).fold(f64::INFINITY, f64::min);
        let nmax = (r / amin.min(self.plane_spacing())).ceil() as i64 + 2;
        let side = (2 * nmax + 1) as usize;
        let mut out = Vec::new();
        for idx in 0..side.pow(D as u32) {
            let mut m = [0i64; D];
            let mut rest = idx;
            for a in (0..D).rev() {
                m[a] = (rest % side) as i64 - nmax;
                rest /= side;
            }
            let p = self.point_at(m);
            if norm(&p) < r {
                out.push((m, p));
            }
        }
        out
    }

    /// The image of k in the first Brillouin zone (nearest to Γ among k − G, G a
    /// reciprocal-lattice vector with coefficients in −2..=2).
    pub fn fold(&self, k: [f64; D]) -> [f64; D] {
        self.fold_with(&self.reciprocal(), k)
    }

    /// [`Self::fold`] with the reciprocal vectors `b` given (computed once for many folds).
    pub fn fold_with(&self, b: &[[f64; D]; D], k: [f64; D]) -> [f64; D] {
        let mut best = k;
        // |·| as the 2D code always computed it (hypot), so that 2D folds are unchanged
        let len = |v: &[f64; D]| if D == 2 { v[0].hypot(v[1]) } else { norm(v) };
        let sq = |v: &[f64; D]| v.iter().map(|x| x * x).sum::<f64>();
        let mut bn = len(&k);
        let mut bs = sq(&k);
        for idx in 0..5usize.pow(D as u32) {
            let mut m = [0.0; D];
            let mut rest = idx;
            for i in (0..D).rev() {
                m[i] = (rest % 5) as f64 - 2.0;
                rest /= 5;
            }
            let mut q = k;
            for i in 0..D {
                for a in 0..D {
                    q[a] -= m[i] * b[i][a];
                }
            }
            // an image more than 1e-10 longer (squared) than the best cannot be shorter by
            // 1e-12: the length (a libm call) only for the others, with the same test
            if sq(&q) > bs * (1.0 + 1e-10) {
                continue;
            }
            let qn = len(&q);
            if qn < bn - 1e-12 {
                best = q;
                bn = qn;
                bs = sq(&q);
            }
        }
        best
    }

    /// The high-symmetry points of the first Brillouin zone, in path order, with labels.
    pub fn symmetry_points(&self) -> Vec<(&'static str, [f64; D])> {
        let pts: Vec<(&'static str, [f64; 3])> = match self.kind {
            LatticeKind::Chain => vec![("Γ", [0.0, 0.0, 0.0]), ("X", [PI, 0.0, 0.0])],
            LatticeKind::Square { gamma } => vec![
                ("Γ", [0.0, 0.0, 0.0]),
                ("X", [PI, 0.0, 0.0]),
                ("M", [PI, PI / gamma, 0.0]),
                ("Γ", [0.0, 0.0, 0.0]),
            ],
            LatticeKind::Hexagonal => vec![
                ("Γ", [0.0, 0.0, 0.0]),
                ("M", [PI, PI / 3f64.sqrt(), 0.0]),
                ("K", [4.0 * PI / 3.0, 0.0, 0.0]),
                ("Γ", [0.0, 0.0, 0.0]),
            ],
            LatticeKind::Sc => vec![
                ("Γ", [0.0, 0.0, 0.0]),
                ("X", [PI, 0.0, 0.0]),
                ("M", [PI, PI, 0.0]),
                ("Γ", [0.0, 0.0, 0.0]),
                ("R", [PI, PI, PI]),
                ("X", [PI, 0.0, 0.0]),
            ],
            LatticeKind::Bcc => {
                let u = 2.0 * PI / 2f64.cbrt();
                vec![
                    ("Γ", [0.0, 0.0, 0.0]),
                    ("H", [u, 0.0, 0.0]),
                    ("N", [0.5 * u, 0.5 * u, 0.0]),
                    ("Γ", [0.0, 0.0, 0.0]),
                    ("P", [0.5 * u, 0.5 * u, 0.5 * u]),
                    ("H", [u, 0.0, 0.0]),
                ]
            }
            LatticeKind::Fcc => {
                let u = 2.0 * PI / 4f64.cbrt();
                vec![
                    ("Γ", [0.0, 0.0, 0.0]),
                    ("X", [u, 0.0, 0.0]),
                    ("W", [u, 0.5 * u, 0.0]),
                    ("L", [0.5 * u, 0.5 * u, 0.5 * u]),
                    ("Γ", [0.0, 0.0, 0.0]),
                    ("K", [0.75 * u, 0.75 * u, 0.0]),
                ]
            }
        };
        pts.into_iter()
            .map(|(l, p)| {
                let mut q = [0.0; D];
                q.copy_from_slice(&p[..D]);
                (l, q)
            })
            .collect()
    }

    /// `n` points per segment along the high-symmetry path: (wave vector, arc length).
    pub fn symmetry_path(&self, n: usize) -> Vec<([f64; D], f64)> {
        let pts = self.symmetry_points();
        let mut out = Vec::new();
        let mut s = 0.0;
        for w in pts.windows(2) {
            let (a, b) = (w[0].1, w[1].1);
            let mut len2 = 0.0;
            for c in 0..D {
                len2 += (b[c] - a[c]).powi(2);
            }
            let len = len2.sqrt();
            for i in 0..n {
                let t = i as f64 / n as f64;
                let mut k = [0.0; D];
                for c in 0..D {
                    k[c] = a[c] + t * (b[c] - a[c]);
                }
                out.push((k, s + t * len));
            }
            s += len;
        }
        out.push((pts[pts.len() - 1].1, s));
        out
    }
}

/// The D indices (each in 0..n, the last running fastest) of entry `idx` of an n^D grid: the
/// one enumeration of the periodic patch, the sampled zone and the standing modes of a box.
pub fn grid_index<const D: usize>(idx: usize, n: usize) -> [usize; D] {
    let mut c = [0usize; D];
    let mut rest = idx;
    for a in (0..D).rev() {
        c[a] = rest % n;
        rest /= n;
    }
    c
}

/// Determinant of a D × D matrix, D ≤ 3.
pub fn det<const D: usize>(m: &[[f64; D]; D]) -> f64 {
    match D {
        1 => m[0][0],
        2 => m[0][0] * m[1][1] - m[0][1] * m[1][0],
        _ => {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        }
    }
}

fn cross3<const D: usize>(u: &[f64; D], v: &[f64; D]) -> [f64; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

fn norm<const D: usize>(v: &[f64; D]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

impl std::fmt::Display for LatticeKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LatticeKind::Chain => write!(f, "1D chain"),
            LatticeKind::Square { gamma } if *gamma == 1.0 => write!(f, "square lattice"),
            LatticeKind::Square { gamma } => {
                write!(f, "square lattice γ = {}", crate::display::num(*gamma))
            }
            LatticeKind::Hexagonal => write!(f, "hexagonal lattice"),
            LatticeKind::Sc => write!(f, "simple cubic lattice"),
            LatticeKind::Bcc => write!(f, "body-centred cubic lattice"),
            LatticeKind::Fcc => write!(f, "face-centred cubic lattice"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reciprocal_vectors_are_dual() {
        for l in [
            Lattice::<2>::square(1.3).unwrap(),
            Lattice::<2>::hexagonal(),
        ] {
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
    fn chain_offsets_reciprocal_and_fold() {
        let c = Lattice::<1>::chain();
        assert_eq!(c.area(), 1.0);
        assert_eq!(c.reciprocal(), [[2.0 * PI]]);
        let offs: Vec<i64> = c.offsets_within(2.5).iter().map(|(m, _)| m[0]).collect();
        assert_eq!(offs, vec![-2, -1, 0, 1, 2]);
        assert!((c.fold([1.5 * PI])[0] + 0.5 * PI).abs() < 1e-12);
        assert_eq!(Lattice::<1>::of_kind(LatticeKind::Chain).unwrap(), c);
        assert!(Lattice::<2>::of_kind(LatticeKind::Chain).is_err());
    }

    #[test]
    fn zone_boundary_distances() {
        let s = Lattice::<2>::square(1.0).unwrap();
        assert!((s.zone_boundary(0.0) - PI).abs() < 1e-12);
        assert!((s.zone_boundary(PI / 4.0) - PI * 2f64.sqrt()).abs() < 1e-12);
        let h = Lattice::<2>::hexagonal();
        // Γ–K along x: 4π/3; Γ–M along 30°: 2π/√3
        assert!((h.zone_boundary(0.0) - 4.0 * PI / 3.0).abs() < 1e-12);
        assert!((h.zone_boundary(PI / 6.0) - 2.0 * PI / 3f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn hexagonal_k_point_is_a_zone_corner() {
        // K is equidistant from Γ and from the nearest reciprocal lattice points b1 and b1 + b2.
        let l = Lattice::<2>::hexagonal();
        let b = l.reciprocal();
        let k = [4.0 * PI / 3.0, 0.0];
        let d = |p: [f64; 2]| ((k[0] - p[0]).powi(2) + (k[1] - p[1]).powi(2)).sqrt();
        let g = d([0.0, 0.0]);
        assert!((d(b[0]) - g).abs() < 1e-12);
        assert!((d([b[0][0] + b[1][0], b[0][1] + b[1][1]]) - g).abs() < 1e-12);
    }
}
