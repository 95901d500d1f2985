//! Shape-function families in 2D (SPEC §3), evaluable at any point, generic over [`Scalar`].
//!
//! Nodes are passed as relative positions `d_J = x_J − x` and volumes `V_J`; the result is
//! `φ_J(x)` and `∇φ_J(x)` (nodes held fixed). The kernel is radial: `W(|d|)` with the 2D
//! normalisation σ₂.
//!
//! | family | definition |
//! |---|---|
//! | `sph` | φ_J = V_J W_J, ∇φ_J = V_J ∇W_J |
//! | `shepard` | ψ_J = V_J W_J / Σ_K V_K W_K |
//! | `mls` | linear basis p = [1, x, y], origin shifted to x, no volumes: φ_J = W_J cᵀp(d_J), A c = e₁, A = Σ_K W_K p(d_K)p(d_K)ᵀ \[B00 eq 36–38\] |
//! | `corrected` | Shepard functions with gradients G_J = M⁻¹ ∇ψ_J, M = Σ_K ∇ψ_K ⊗ d_K \[B98 eq 55–61\] |

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::error::{Error, Result};
use crate::kernel::{self, Kernel};
use crate::scalar::Scalar;
use crate::shape::{SINGULAR_MOMENT_TOL, ShapeFamily};

/// A 2D vector of scalars.
pub type V2<S> = [S; 2];

/// Kernel parameters in 2D.
#[derive(Clone, Copy, Debug)]
pub struct KernelParams2 {
    /// The kernel.
    pub kernel: &'static dyn Kernel,
    /// Smoothing length.
    pub h: f64,
}

impl KernelParams2 {
    /// Support radius ζh.
    pub fn support(&self) -> f64 {
        self.kernel.zeta() * self.h
    }

    /// W(|d|) and ∇_x W(|x − x_J|) = −W'(r) d/r for d = x_J − x, differentiable through
    /// d = 0 ([`kernel::w_and_grad`]).
    #[inline]
    pub fn w_and_grad<S: Scalar>(&self, d: V2<S>) -> (S, V2<S>) {
        kernel::w_and_grad(self.kernel, self.h, d)
    }
}

/// Determinant and inverse of a 3×3 matrix (cofactors).
fn inv3<S: Scalar>(a: &[[S; 3]; 3]) -> (S, [[S; 3]; 3]) {
    let c = |i: usize, j: usize| -> S {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
        a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]
    };
    let det = a[0][0] * c(0, 0) + a[0][1] * c(0, 1) + a[0][2] * c(0, 2);
    let mut inv = [[S::zero(); 3]; 3];
    for (i, row) in inv.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = c(j, i) / det;
        }
    }
    (det, inv)
}

/// Evaluates `(φ_J, ∇φ_J)` at x for all nodes `(d_J, V_J)`; `out` is cleared and filled in node
/// order. `x_abs` is used in error messages only.
pub fn eval2<S: Scalar>(
    family: ShapeFamily,
    kp: KernelParams2,
    nodes: &[(V2<S>, S)],
    x_abs: [f64; 2],
    out: &mut Vec<(S, V2<S>)>,
) -> Result<()> {
    out.clear();
    match family {
        ShapeFamily::Sph => {
            for &(d, vol) in nodes {
                let (w, g) = kp.w_and_grad(d);
                out.push((vol * w, [vol * g[0], vol * g[1]]));
            }
        }
        ShapeFamily::Shepard | ShapeFamily::Corrected => {
            let mut s0 = S::zero();
            let mut s1 = [S::zero(), S::zero()];
            for &(d, vol) in nodes {
                let (w, g) = kp.w_and_grad(d);
                s0 += vol * w;
                s1[0] += vol * g[0];
                s1[1] += vol * g[1];
                out.push((vol * w, [vol * g[0], vol * g[1]]));
            }
            if s0.re() <= 0.0 {
                return Err(Error::SingularMoment {
                    what: "Shepard sum Σ V W (2D)",
                    x: x_abs[0],
                    det: s0.re(),
                });
            }
            for p in out.iter_mut() {
                let (vw, g) = *p;
                let s02 = s0 * s0;
                *p = (
                    vw / s0,
                    [
                        (g[0] * s0 - vw * s1[0]) / s02,
                        (g[1] * s0 - vw * s1[1]) / s02,
                    ],
                );
            }
            if family == ShapeFamily::Corrected {
                // M_ab = Σ_K ∂_a ψ_K d_Kb ; G_J = M⁻¹ ∇ψ_J
                let mut m = [[S::zero(); 2]; 2];
                let mut scale = 0.0;
                for (p, &(d, _)) in out.iter().zip(nodes) {
                    for a in 0..2 {
                        for b in 0..2 {
                            m[a][b] += p.1[a] * d[b];
                            scale += (p.1[a].re() * d[b].re()).abs();
                        }
                    }
                }
                let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
                if det.re().abs() <= SINGULAR_MOMENT_TOL * (scale * scale).max(f64::MIN_POSITIVE) {
                    return Err(Error::SingularMoment {
                        what: "corrected-derivative matrix (2D)",
                        x: x_abs[0],
                        det: det.re(),
                    });
                }
                // G = M⁻¹ g; M⁻¹ = [[m11, −m01], [−m10, m00]] / det (solve M G = g)
                for p in out.iter_mut() {
                    let g = p.1;
                    p.1 = [
                        (m[1][1] * g[0] - m[0][1] * g[1]) / det,
                        (m[0][0] * g[1] - m[1][0] * g[0]) / det,
                    ];
                }
            }
        }
        ShapeFamily::Mls => {
            let mut a = [[S::zero(); 3]; 3];
            let mut ax = [[[S::zero(); 3]; 3]; 2];
            let mut ws = Vec::with_capacity(nodes.len());
            for &(d, _) in nodes {
                let (w, g) = kp.w_and_grad(d);
                let p = [S::cst(1.0), d[0], d[1]];
                // ∂p/∂x_α = −e_{α+1}
                for i in 0..3 {
                    for j in 0..3 {
                        a[i][j] += w * p[i] * p[j];
                        for al in 0..2 {
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
            let (det, inv) = inv3(&a);
            let scale = (a[0][0].re() * a[1][1].re() * a[2][2].re()).abs();
            if det.re() <= SINGULAR_MOMENT_TOL * scale.max(f64::MIN_POSITIVE) {
                return Err(Error::SingularMoment {
                    what: "MLS moment matrix (2D)",
                    x: x_abs[0],
                    det: det.re(),
                });
            }
            // c = A⁻¹ e₁, ∂c = −A⁻¹ (∂A) c
            let c = [inv[0][0], inv[1][0], inv[2][0]];
            let mut dc = [[S::zero(); 3]; 2];
            for al in 0..2 {
                let mut t = [S::zero(); 3];
                for (i, ti) in t.iter_mut().enumerate() {
                    for (j, cj) in c.iter().enumerate() {
                        *ti += ax[al][i][j] * *cj;
                    }
                }
                for i in 0..3 {
                    let mut s = S::zero();
                    for (j, tj) in t.iter().enumerate() {
                        s += inv[i][j] * *tj;
                    }
                    dc[al][i] = -s;
                }
            }
            for (w, g, p) in ws {
                let cp = c[0] * p[0] + c[1] * p[1] + c[2] * p[2];
                let mut grad = [S::zero(); 2];
                for al in 0..2 {
                    let dcp = dc[al][0] * p[0] + dc[al][1] * p[1] + dc[al][2] * p[2];
                    grad[al] = g[al] * cp + w * dcp - w * c[al + 1];
                }
                out.push((w * cp, grad));
            }
        }
    }
    Ok(())
}
