//! Shape-function families (SPEC §3): how a particle approximation is built from a kernel —
//! one definition of every family for every dimension D ∈ {1, 2, 3} ([`eval_d`]).
//!
//! All families are evaluated at an arbitrary point `x` (nodes and mid-points alike). Nodes are
//! passed as *relative* positions `d_J = x_J − x` (already minimum-imaged for periodic
//! systems) and volumes `V_J`; the result is `φ_J(x)` and `∇φ_J(x)` (nodes held fixed). Every
//! routine is generic over [`Scalar`] so that the von Neumann engine can differentiate through
//! it exactly (moment matrices included). [`eval`] is a thin 1D wrapper with scalar (rather
//! than 1-array) positions, for the 1D-only \[B00\] forms.
//!
//! | family | definition | reference |
//! |---|---|---|
//! | `sph` | φ_J = V_J W(x − x_J) | \[B98 eq 33\], \[B00 eq 41\] |
//! | `shepard` | ψ_J = V_J W_J / Σ_K V_K W_K | \[B98 §4.2\], \[V21 eq 40\] |
//! | `mls` | linear basis p = [1, d_1 … d_D] about x, no volumes: φ_J = W_J cᵀp(d_J), A c = e₁, A = Σ_K W_K p pᵀ | \[B00 eq 36–38\], \[B98 eq 46\] |
//! | `corrected` | Shepard functions with gradients G_J = M⁻¹ ∇ψ_J, M = Σ_K ∇ψ_K ⊗ d_K (1D: ψ'_J / Σ_K ψ'_K d_K) | \[B98 §4.4.3, eq 55–61\], \[V21 eq 43\] |

// Small-tensor algebra (D ≤ 3, moment matrices up to 4 × 4) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::error::{Error, Result};
use crate::kernel::{self, Kernel};
use crate::scalar::{Dual, Scalar};

/// A shape-function family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShapeFamily {
    /// Plain kernel approximation φ_J = V_J W_J.
    Sph,
    /// Shepard (zeroth-order complete) functions.
    Shepard,
    /// Moving least squares with a linear basis (EFG / RKPM).
    Mls,
    /// Shepard functions with first-order corrected derivatives.
    Corrected,
}

impl ShapeFamily {
    /// All families with their CLI names.
    pub const ALL: [(ShapeFamily, &'static str); 4] = [
        (ShapeFamily::Sph, "sph"),
        (ShapeFamily::Shepard, "shepard"),
        (ShapeFamily::Mls, "mls"),
        (ShapeFamily::Corrected, "corrected"),
    ];

    /// CLI name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }

    /// Looks a family up by CLI name.
    pub fn by_name(name: &str) -> Result<Self> {
        crate::error::lookup("shape family", &Self::ALL, name)
    }

    /// Whether the family reproduces linear functions' derivatives exactly
    /// (first-order consistent gradient).
    pub fn linear_consistent_gradient(self) -> bool {
        matches!(self, ShapeFamily::Mls | ShapeFamily::Corrected)
    }
}

/// Determinants below this fraction of the scale of the moment matrix are treated as singular.
pub const SINGULAR_MOMENT_TOL: f64 = 1e-10;

/// Kernel parameters for shape-function evaluation in 1D.
#[derive(Clone, Copy, Debug)]
pub struct KernelParams {
    /// The kernel.
    pub kernel: &'static dyn Kernel,
    /// Smoothing length h (same length unit as positions).
    pub h: f64,
}

impl KernelParams {
    /// Support radius R = ζ h.
    pub fn support(&self) -> f64 {
        self.kernel.zeta() * self.h
    }

    /// W(|d|) and ∇_x W(|x − x_J|) = −W'(r) d/r for d = x_J − x in D dimensions,
    /// differentiable through d = 0 ([`kernel::w_and_grad`]).
    #[inline]
    pub fn w_and_grad<S: Scalar, const D: usize>(&self, d: [S; D]) -> (S, [S; D]) {
        crate::kernel::w_and_grad(self.kernel, self.h, d)
    }
}

/// Evaluates `φ_J(x)` and `∂φ_J/∂x` for all nodes `(d_J, V_J)` (relative positions
/// `d_J = x_J − x`) in 1D: [`eval_d`] with D = 1. `out` is cleared and filled in node order.
/// `x_abs` is only used in error messages.
pub fn eval<S: Scalar>(
    family: ShapeFamily,
    kp: KernelParams,
    nodes: &[(S, S)],
    x_abs: f64,
    out: &mut Vec<(S, S)>,
) -> Result<()> {
    let nd: Vec<([S; 1], S)> = nodes.iter().map(|&(d, v)| ([d], v)).collect();
    let mut o = Vec::with_capacity(nodes.len());
    eval_d(family, kp, &nd, x_abs, &mut o)?;
    out.clear();
    out.extend(o.into_iter().map(|(p, [g])| (p, g)));
    Ok(())
}

/// The names of the moment matrices in error messages, per dimension.
fn moment_names(d: usize) -> (&'static str, &'static str, &'static str) {
    match d {
        1 => (
            "Shepard sum Σ V W",
            "corrected-derivative moment Σ ψ'_K (x_K − x)",
            "MLS moment matrix",
        ),
        2 => (
            "Shepard sum Σ V W (2D)",
            "corrected-derivative matrix (2D)",
            "MLS moment matrix (2D)",
        ),
        _ => (
            "Shepard sum Σ V W (3D)",
            "corrected-derivative matrix (3D)",
            "MLS moment matrix (3D)",
        ),
    }
}

/// Determinant and inverse of the leading `n` × `n` block of `a` (n ≤ 4): closed forms for
/// n = 1, 2, cofactors for n = 3, Gauss–Jordan with partial pivoting (on the value part) for
/// n = 4. `None` when a pivot is exactly zero.
fn inv_small<S: Scalar>(a: &[[S; 4]; 4], n: usize) -> Option<(S, [[S; 4]; 4])> {
    let mut inv = [[S::zero(); 4]; 4];
    match n {
        1 => {
            inv[0][0] = S::cst(1.0) / a[0][0];
            Some((a[0][0], inv))
        }
        2 => {
            let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
            inv[0][0] = a[1][1] / det;
            inv[0][1] = -a[0][1] / det;
            inv[1][0] = -a[1][0] / det;
            inv[1][1] = a[0][0] / det;
            Some((det, inv))
        }
        3 => {
            let c = |i: usize, j: usize| -> S {
                let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
                let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
                a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]
            };
            let det = a[0][0] * c(0, 0) + a[0][1] * c(0, 1) + a[0][2] * c(0, 2);
            for (i, row) in inv.iter_mut().enumerate().take(3) {
                for (j, v) in row.iter_mut().enumerate().take(3) {
                    *v = c(j, i) / det;
                }
            }
            Some((det, inv))
        }
        _ => {
            let mut m = *a;
            for (i, row) in inv.iter_mut().enumerate() {
                row[i] = S::cst(1.0);
            }
            let mut det = S::cst(1.0);
            for col in 0..4 {
                let piv = (col..4)
                    .max_by(|&x, &y| m[x][col].re().abs().total_cmp(&m[y][col].re().abs()))
                    .unwrap_or(col);
                if m[piv][col].re() == 0.0 {
                    return None;
                }
                if piv != col {
                    m.swap(piv, col);
                    inv.swap(piv, col);
                    det = -det;
                }
                let p = m[col][col];
                det *= p;
                for j in 0..4 {
                    m[col][j] = m[col][j] / p;
                    inv[col][j] = inv[col][j] / p;
                }
                for r in 0..4 {
                    if r != col {
                        let f = m[r][col];
                        for j in 0..4 {
                            m[r][j] -= f * m[col][j];
                            inv[r][j] -= f * inv[col][j];
                        }
                    }
                }
            }
            Some((det, inv))
        }
    }
}

/// Evaluates `(φ_J, ∇φ_J)` at x in dimension `D` ∈ {1, 2, 3} for all nodes `(d_J, V_J)`
/// (relative positions `d_J = x_J − x`, volumes); `out` is cleared and filled in node order.
/// One definition of every family for every dimension (the table in the module docs);
/// `x_abs` (the first coordinate of x) is used in error messages only.
pub fn eval_d<S: Scalar, const D: usize>(
    family: ShapeFamily,
    kp: KernelParams,
    nodes: &[([S; D], S)],
    x_abs: f64,
    out: &mut Vec<(S, [S; D])>,
) -> Result<()> {
    out.clear();
    let (shepard_name, corrected_name, mls_name) = moment_names(D);
    match family {
        ShapeFamily::Sph => {
            for &(d, vol) in nodes {
                let (w, g) = kernel::w_and_grad(kp.kernel, kp.h, d);
                out.push((vol * w, g.map(|ga| vol * ga)));
            }
        }
        ShapeFamily::Shepard | ShapeFamily::Corrected => {
            let mut s0 = S::zero();
            let mut s1 = [S::zero(); D];
            for &(d, vol) in nodes {
                let (w, g) = kernel::w_and_grad(kp.kernel, kp.h, d);
                s0 += vol * w;
                for a in 0..D {
                    s1[a] += vol * g[a];
                }
                out.push((vol * w, g.map(|ga| vol * ga)));
            }
            if s0.re() <= 0.0 {
                return Err(Error::SingularMoment {
                    what: shepard_name,
                    x: x_abs,
                    det: s0.re(),
                });
            }
            // ψ_J = V W / s0, ∇ψ_J = (V ∇W s0 − V W s1) / s0²
            let s02 = s0 * s0;
            for p in out.iter_mut() {
                let (vw, g) = *p;
                let mut gp = [S::zero(); D];
                for a in 0..D {
                    gp[a] = (g[a] * s0 - vw * s1[a]) / s02;
                }
                *p = (vw / s0, gp);
            }
            if family == ShapeFamily::Corrected {
                // M_ab = Σ_K ∂_a ψ_K d_Kb; G_J = M⁻¹ ∇ψ_J (reproduces gradients of linear
                // fields exactly) [B98 eq 55–61]
                let mut m = [[S::zero(); 4]; 4];
                let mut scale = 0.0;
                for (p, (d, _)) in out.iter().zip(nodes) {
                    for a in 0..D {
                        for b in 0..D {
                            m[a][b] += p.1[a] * d[b];
                            scale += (p.1[a].re() * d[b].re()).abs();
                        }
                    }
                }
                let inv = inv_small(&m, D);
                let det = inv.map_or(0.0, |(det, _)| det.re());
                if det.abs() <= SINGULAR_MOMENT_TOL * scale.max(f64::MIN_POSITIVE).powi(D as i32) {
                    return Err(Error::SingularMoment {
                        what: corrected_name,
                        x: x_abs,
                        det,
                    });
                }
                let Some((det, mi)) = inv else {
                    return Err(Error::NonFinite("corrected-derivative matrix"));
                };
                for p in out.iter_mut() {
                    let g = p.1;
                    let mut gc = [S::zero(); D];
                    match D {
                        // the closed forms of M⁻¹g for D = 1, 2 (fewer roundings)
                        1 => gc[0] = g[0] / m[0][0],
                        2 => {
                            gc[0] = (m[1][1] * g[0] - m[0][1] * g[1]) / det;
                            gc[1] = (m[0][0] * g[1] - m[1][0] * g[0]) / det;
                        }
                        _ => {
                            for a in 0..D {
                                for b in 0..D {
                                    gc[a] += mi[a][b] * g[b];
                                }
                            }
                        }
                    }
                    p.1 = gc;
                }
            }
        }
        ShapeFamily::Mls if D == 1 => {
            // D = 1 in closed form: moments m0 = Σ W, m1 = Σ W d, m2 = Σ W d² about x and
            // their x-derivatives (∂d/∂x = −1); φ_J = W_J (m2 − m1 d_J)/(m0 m2 − m1²)
            let (mut m0, mut m1, mut m2) = (S::zero(), S::zero(), S::zero());
            let (mut m0x, mut m1x, mut m2x) = (S::zero(), S::zero(), S::zero());
            for &(d, _) in nodes {
                let (w, [wx]) = kernel::w_and_grad(kp.kernel, kp.h, [d[0]]);
                let d = d[0];
                m0 += w;
                m1 += w * d;
                m2 += w * d * d;
                m0x += wx;
                m1x += wx * d - w;
                m2x += wx * d * d - w * d * 2.0;
                let mut g = [S::zero(); D];
                g[0] = wx;
                out.push((w, g));
            }
            let det = m0 * m2 - m1 * m1;
            let scale = (m0.re() * m2.re()).abs();
            if det.re() <= SINGULAR_MOMENT_TOL * scale.max(f64::MIN_POSITIVE) {
                return Err(Error::SingularMoment {
                    what: mls_name,
                    x: x_abs,
                    det: det.re(),
                });
            }
            let detx = m0x * m2 + m0 * m2x - m1 * m1x * 2.0;
            for (p, &(d, _)) in out.iter_mut().zip(nodes) {
                let (w, g) = *p;
                let (d, wx) = (d[0], g[0]);
                let num = m2 - m1 * d;
                let numx = m2x - m1x * d + m1;
                let phi = w * num / det;
                let mut dphi = [S::zero(); D];
                dphi[0] = (wx * num + w * numx) / det - w * num * detx / (det * det);
                *p = (phi, dphi);
            }
        }
        ShapeFamily::Mls => {
            // linear basis p = [1, d_1, …, d_D] about x (no volumes): A = Σ W p pᵀ,
            // c = A⁻¹ e₁, φ_J = W_J cᵀ p(d_J) [B00 eq 36–38]; ∂p/∂x_α = −e_{α+1},
            // ∂c = −A⁻¹ (∂A) c
            let n = D + 1;
            let mut a = [[S::zero(); 4]; 4];
            let mut ax = [[[S::zero(); 4]; 4]; 3];
            let mut ws: Vec<(S, [S; D], [S; 4])> = Vec::with_capacity(nodes.len());
            for &(d, _) in nodes {
                let (w, g) = kernel::w_and_grad(kp.kernel, kp.h, d);
                let mut p = [S::zero(); 4];
                p[0] = S::cst(1.0);
                p[1..n].copy_from_slice(&d);
                for i in 0..n {
                    for j in 0..n {
                        a[i][j] += w * p[i] * p[j];
                        for al in 0..D {
                            let mut t = g[al] * p[i] * p[j];
                            if i == al + 1 {
                                t -= w * p[j];
                            }
                            if j == al + 1 {
                                t -= w * p[i];
                            }
                            ax[al][i][j] += t;
                        }
                    }
                }
                ws.push((w, g, p));
            }
            let inv = inv_small(&a, n);
            let det = inv.map_or(0.0, |(det, _)| det.re());
            let scale = (0..n).map(|i| a[i][i].re()).product::<f64>().abs();
            if det <= SINGULAR_MOMENT_TOL * scale.max(f64::MIN_POSITIVE) {
                return Err(Error::SingularMoment {
                    what: mls_name,
                    x: x_abs,
                    det,
                });
            }
            let Some((_, inv)) = inv else {
                return Err(Error::NonFinite("MLS moment matrix"));
            };
            let mut c = [S::zero(); 4];
            for i in 0..n {
                c[i] = inv[i][0];
            }
            let mut dc = [[S::zero(); 4]; 3];
            for al in 0..D {
                let mut t = [S::zero(); 4];
                for (i, ti) in t.iter_mut().enumerate().take(n) {
                    for (j, cj) in c.iter().enumerate().take(n) {
                        *ti += ax[al][i][j] * *cj;
                    }
                }
                for i in 0..n {
                    let mut s = S::zero();
                    for (j, tj) in t.iter().enumerate().take(n) {
                        s += inv[i][j] * *tj;
                    }
                    dc[al][i] = -s;
                }
            }
            for (w, g, p) in ws {
                let mut cp = S::zero();
                for i in 0..n {
                    cp += c[i] * p[i];
                }
                let mut grad = [S::zero(); D];
                for al in 0..D {
                    let mut dcp = S::zero();
                    for i in 0..n {
                        dcp += dc[al][i] * p[i];
                    }
                    grad[al] = g[al] * cp + w * dcp - w * c[al + 1];
                }
                out.push((w * cp, grad));
            }
        }
    }
    Ok(())
}

/// `[φ_J, φ'_J, φ''_J]` at x for nodes given by relative positions and volumes (f64), the
/// second derivative obtained exactly by differentiating [`eval`] with a dual number.
pub fn eval_with_second(
    family: ShapeFamily,
    kp: KernelParams,
    nodes: &[(f64, f64)],
    x_abs: f64,
) -> Result<Vec<[f64; 3]>> {
    // Moving x by +ε moves every relative position d_J by −ε.
    let dn: Vec<(Dual, Dual)> = nodes
        .iter()
        .map(|&(d, v)| (Dual::new(d, -1.0), Dual::cst(v)))
        .collect();
    let mut out = Vec::with_capacity(nodes.len());
    eval(family, kp, &dn, x_abs, &mut out)?;
    Ok(out.iter().map(|(p, dp)| [p.v, dp.v, dp.d]).collect())
}

/// The shape function of the node at 0 on the infinite uniform 1D lattice of unit spacing and
/// unit volumes, evaluated at `x` (units of Δx): `[φ, φ', φ'']`. Used by the papers' closed
/// forms, which are written in terms of these lattice values.
pub fn lattice_shape(family: ShapeFamily, kp: KernelParams, x: f64) -> Result<[f64; 3]> {
    let r = kp.support();
    if (x).abs() >= r {
        return Ok([0.0; 3]);
    }
    let lo = (x - r).floor() as i64 - 1;
    let hi = (x + r).ceil() as i64 + 1;
    let mut nodes = Vec::new();
    let mut idx0 = None;
    for j in lo..=hi {
        let d = j as f64 - x;
        if d.abs() < r {
            if j == 0 {
                idx0 = Some(nodes.len());
            }
            nodes.push((d, 1.0));
        }
    }
    let vals = eval_with_second(family, kp, &nodes, x)?;
    Ok(idx0.map(|i| vals[i]).unwrap_or([0.0; 3]))
}
