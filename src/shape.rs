//! Shape-function families (SPEC §3): how a particle approximation is built from a kernel.
//!
//! All families are evaluated at an arbitrary point `x` of a 1D point set (nodes and
//! mid-points alike). Nodes are passed as *relative* positions `d_J = x_J − x` (already
//! minimum-imaged for periodic systems) and volumes `V_J`; the result is `φ_J(x)` and
//! `∂φ_J/∂x` (nodes held fixed). Every routine is generic over [`Scalar`] so that the von
//! Neumann engine can differentiate through it exactly (moment matrices included).
//!
//! | family | definition | reference |
//! |---|---|---|
//! | `sph` | φ_J = V_J W(x − x_J) | \[B98 eq 33\], \[B00 eq 41\] |
//! | `shepard` | ψ_J = V_J W_J / Σ_K V_K W_K | \[B98 §4.2\], \[V21 eq 40\] |
//! | `mls` | linear-basis moving least squares, origin shifted to x, no volumes | \[B00 eq 36–38\], \[B98 eq 46\] |
//! | `corrected` | Shepard functions with Krongauz–Belytschko / Randles–Libersky corrected derivatives G_J = ψ'_J / Σ_K ψ'_K d_K | \[B98 §4.4.3\], \[V21 eq 43\] |

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
    /// W(|d|) and ∂W(|x − x_J|)/∂x = −W'(|d|) sign(d) for relative position d = x_J − x,
    /// differentiable through d = 0 ([`kernel::w_and_grad`]).
    #[inline]
    fn w_and_dx<S: Scalar>(&self, d: S) -> (S, S) {
        let (w, g) = kernel::w_and_grad::<S, 1>(self.kernel, self.h, [d]);
        (w, g[0])
    }
}

/// Evaluates `φ_J(x)` and `∂φ_J/∂x` for all nodes `(d_J, V_J)` (relative positions
/// `d_J = x_J − x`). `out` is cleared and filled in node order. `x_abs` is only used in
/// error messages.
pub fn eval<S: Scalar>(
    family: ShapeFamily,
    kp: KernelParams,
    nodes: &[(S, S)],
    x_abs: f64,
    out: &mut Vec<(S, S)>,
) -> Result<()> {
    out.clear();
    match family {
        ShapeFamily::Sph => {
            for &(d, vol) in nodes {
                let (w, wx) = kp.w_and_dx(d);
                out.push((vol * w, vol * wx));
            }
        }
        ShapeFamily::Shepard | ShapeFamily::Corrected => {
            let mut s0 = S::zero();
            let mut s1 = S::zero();
            for &(d, vol) in nodes {
                let (w, wx) = kp.w_and_dx(d);
                s0 += vol * w;
                s1 += vol * wx;
                out.push((vol * w, vol * wx));
            }
            if s0.re() <= 0.0 {
                return Err(Error::SingularMoment {
                    what: "Shepard sum Σ V W",
                    x: x_abs,
                    det: s0.re(),
                });
            }
            // ψ_J = V W / s0, ψ'_J = (V W' s0 − V W s1) / s0²
            for p in out.iter_mut() {
                let (vw, vwx) = *p;
                *p = (vw / s0, (vwx * s0 - vw * s1) / (s0 * s0));
            }
            if family == ShapeFamily::Corrected {
                // G_J = ψ'_J / Σ_K ψ'_K d_K  (reproduces d/dx of linear fields exactly)
                let mut b = S::zero();
                let mut scale = 0.0;
                for (p, &(d, _)) in out.iter().zip(nodes) {
                    b += p.1 * d;
                    scale += (p.1.re() * d.re()).abs();
                }
                if b.re().abs() <= SINGULAR_MOMENT_TOL * scale.max(f64::MIN_POSITIVE) {
                    return Err(Error::SingularMoment {
                        what: "corrected-derivative moment Σ ψ'_K (x_K − x)",
                        x: x_abs,
                        det: b.re(),
                    });
                }
                for p in out.iter_mut() {
                    p.1 = p.1 / b;
                }
            }
        }
        ShapeFamily::Mls => {
            // Moments of the weights about x: m0 = Σ W, m1 = Σ W d, m2 = Σ W d²,
            // and their x-derivatives (∂d/∂x = −1).
            let (mut m0, mut m1, mut m2) = (S::zero(), S::zero(), S::zero());
            let (mut m0x, mut m1x, mut m2x) = (S::zero(), S::zero(), S::zero());
            for &(d, _) in nodes {
                let (w, wx) = kp.w_and_dx(d);
                m0 += w;
                m1 += w * d;
                m2 += w * d * d;
                m0x += wx;
                m1x += wx * d - w;
                m2x += wx * d * d - w * d * 2.0;
                out.push((w, wx));
            }
            let det = m0 * m2 - m1 * m1;
            let scale = (m0.re() * m2.re()).abs();
            if det.re() <= SINGULAR_MOMENT_TOL * scale.max(f64::MIN_POSITIVE) {
                return Err(Error::SingularMoment {
                    what: "MLS moment matrix",
                    x: x_abs,
                    det: det.re(),
                });
            }
            let detx = m0x * m2 + m0 * m2x - m1 * m1x * 2.0;
            for (p, &(d, _)) in out.iter_mut().zip(nodes) {
                let (w, wx) = *p;
                let num = m2 - m1 * d;
                let numx = m2x - m1x * d + m1;
                let phi = w * num / det;
                let dphi = (wx * num + w * numx) / det - w * num * detx / (det * det);
                *p = (phi, dphi);
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
