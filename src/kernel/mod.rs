//! Smoothing kernels (SPEC §2).
//!
//! Convention: `W(r, h) = σ_d h^(-d) f(q)`, `q = r / h`, support radius `R = ζ h`.
//! `f`, `f'`, `f''` are derivatives with respect to `q`. A kernel is picked at run time from
//! its name and used as a `&'static dyn Kernel`.
//!
//! Every kernel is a zero-sized type with analytic `f`, `f'`, `f''`. All three are exactly zero
//! for `q ≥ ζ`; a negative `q` is read as `|q|` (the kernels are even). The dimension argument
//! `dim` is 1, 2 or 3; other values are clamped into that range. `σ_d` is a closed form where
//! one exists, otherwise a Gauss–Legendre quadrature evaluated once and cached; the inflection
//! point `q*` is a closed form or a bisection on the analytic `f''` to full double precision,
//! also cached.
//!
//! | name | f(q) for q < ζ | ζ | σ_1 | σ_2 | σ_3 |
//! |---|---|---|---|---|---|
//! | [`m4`](M4) | ¼(2−q)³ − (1−q)³₊ | 2 | 2/3 | 10/(7π) | 1/π |
//! | [`m5`](M5) | (5/2−q)⁴ − 5(3/2−q)⁴₊ + 10(1/2−q)⁴₊ | 2.5 | 1/24 | 96/(1199π) | 1/(20π) |
//! | [`m6`](M6) | (3−q)⁵ − 6(2−q)⁵₊ + 15(1−q)⁵₊ | 3 | 1/120 | 7/(478π) | 1/(120π) |
//! | [`wendland-c2`](WendlandC2) | ψ_{2,1}(q/2) (1D), ψ_{3,1}(q/2) (2D, 3D) | 2 | 5/8 | 7/(4π) | 21/(16π) |
//! | [`wendland-c4`](WendlandC4) | ψ_{2,2}(q/2) (1D), ψ_{3,2}(q/2) (2D, 3D) | 2 | 3/4 | 9/(4π) | 495/(256π) |
//! | [`wendland-c6`](WendlandC6) | ψ_{2,3}(q/2) (1D), ψ_{3,3}(q/2) (2D, 3D) | 2 | 55/64 | 39/(14π) | 1365/(512π) |
//! | [`gaussian`](Gaussian) | exp(−q²), truncated | 3 | 0.564202… | 0.318349… | 0.179666… |
//! | [`lucy`](Lucy) | (1+3q)(1−q)³ | 1 | 5/4 | 5/π | 105/(16π) |
//! | [`efg-cubic`](EfgCubic) | 2/3 − 4q² + 4q³ (q ≤ ½), (4/3)(1−q)³ | 1 | 2 | 60/(7π) | 12/π |
//! | [`efg-quartic`](EfgQuartic) | 1 − 6q² + 8q³ − 3q⁴ | 1 | 5/4 | 5/π | 105/(16π) |
//! | [`mollifier`](Mollifier) | exp(−1/(1−q²)) (1−q²)⁸ | 1 | 4.80967… | 8.74622… | 16.3222… |

use crate::error::{Error, Result};
use crate::scalar::Scalar;

mod bspline;
mod efg;
mod gaussian;
mod lucy;
mod mollifier;
mod numeric;
mod wendland;

pub use bspline::{M4, M5, M6};
pub use efg::{EfgCubic, EfgQuartic};
pub use gaussian::Gaussian;
pub use lucy::Lucy;
pub use mollifier::Mollifier;
pub use wendland::{WendlandC2, WendlandC4, WendlandC6};

/// A radially symmetric smoothing kernel with compact support.
pub trait Kernel: Send + Sync + std::fmt::Debug {
    /// CLI name, e.g. `"m4"`.
    fn name(&self) -> &'static str;
    /// Support radius in units of h (ζ).
    fn zeta(&self) -> f64;
    /// Shape function f(q) in dimension `dim` (1, 2, 3). Zero for q ≥ ζ.
    fn f(&self, dim: usize, q: f64) -> f64;
    /// df/dq. Zero for q ≥ ζ.
    fn df(&self, dim: usize, q: f64) -> f64;
    /// d²f/dq². Zero for q ≥ ζ.
    fn d2f(&self, dim: usize, q: f64) -> f64;
    /// Normalisation σ_d such that ∫ σ_d h^-d f(|x|/h) dx = 1 in dimension `dim`.
    fn sigma(&self, dim: usize) -> f64;
    /// Inflection point q* in (0, ζ) where f''(q*) = 0 (the first sign change of f'').
    fn inflection(&self, dim: usize) -> f64;
    /// Literature reference (short).
    fn reference(&self) -> &'static str;
    /// Customary range of h/Δx used with this kernel (inclusive).
    fn customary_h(&self) -> (f64, f64);
}

/// The 1D kernel's cumulative integral I(q) = ∫_{−∞}^{q} σ_1 f(|r|) dr (the fraction of the
/// normalised 1D kernel left of q, in units of h): 0 for q ≤ −ζ, ½ at 0, 1 for q ≥ ζ. A step
/// smoothed by the continuous SPH interpolation with smoothing length h is I(t/h)
/// (`solver::scene::Pulse`). Gauss–Legendre quadrature on the pieces of [0, |q|] between
/// multiples of ½ (4 panels of 20 points each): the B-splines' pieces are integrated exactly.
pub fn cumulative_1d(k: &dyn Kernel, q: f64) -> f64 {
    let z = k.zeta();
    if q <= -z {
        return 0.0;
    }
    if q >= z {
        return 1.0;
    }
    let half = k.sigma(1) * numeric::integrate_by_halves(|r| k.f(1, r), q.abs());
    if q < 0.0 { 0.5 - half } else { 0.5 + half }
}

/// W(r, h) in dimension `dim` for a scalar distance `r ≥ 0` of any [`Scalar`] type
/// (value and exact derivative for dual numbers).
#[inline]
pub fn w<S: Scalar>(k: &dyn Kernel, dim: usize, r: S, h: f64) -> S {
    let Some(q) = q_inside(k, r.re(), h) else {
        return r.lift(0.0, 0.0);
    };
    let s = k.sigma(dim) / h.powi(dim as i32);
    // the derivative part only for types that carry one (`lift` ignores it otherwise)
    let g1 = if S::TANGENT {
        s * k.df(dim, q) / h
    } else {
        0.0
    };
    r.lift(s * k.f(dim, q), g1)
}

/// dW/dr(r, h) in dimension `dim`.
#[inline]
pub fn dw<S: Scalar>(k: &dyn Kernel, dim: usize, r: S, h: f64) -> S {
    let Some(q) = q_inside(k, r.re(), h) else {
        return r.lift(0.0, 0.0);
    };
    let s = k.sigma(dim) / h.powi(dim as i32 + 1);
    let g1 = if S::TANGENT {
        s * k.d2f(dim, q) / h
    } else {
        0.0
    };
    r.lift(s * k.df(dim, q), g1)
}

/// `W(|d|)` and `∇_x W(|x − x_J|)` in dimension `D` ∈ {1, 2, 3} as functions of the relative
/// position `d = x_J − x` (the gradient is `−W'(r) d/r`, `r = |d|`), with exact tangents
/// everywhere, **including d = 0** — one definition for every dimension.
///
/// `|d|` is not differentiable at 0, but the composites are: every kernel has `f'(0) = 0`, so
/// `W(|d|)` is stationary there and `W'(r)/r → W''(0)`; the gradient has Jacobian `−W''(0) I`
/// at d = 0 and is returned as `−W''(0) d` (value 0, that Jacobian applied to the tangent of
/// `d`). In 1D the kernel is lifted directly from `d` (W(|d|) with tangent sign(d)W'(|d|), the
/// gradient −sign(d)W'(|d|) with tangent −W''(|d|)), never through `|d|` or `sqrt(d²)`. For
/// r > 0 in 2D/3D the chain rule through `sqrt` applies. At r ≥ R the kernel's convention holds
/// (`f = f' = f'' = 0` for `q ≥ ζ`, the support test `|r| ≥ ζh` of every neighbour search).
#[inline]
pub fn w_and_grad<S: Scalar, const D: usize>(k: &dyn Kernel, h: f64, d: [S; D]) -> (S, [S; D]) {
    let mut g = [S::zero(); D];
    if D == 1 {
        let dv = d[0].re();
        let r = dv.abs();
        let sgn = if dv > 0.0 {
            1.0
        } else if dv < 0.0 {
            -1.0
        } else {
            0.0
        };
        let w0 = w(k, 1, r, h);
        let w1 = dw(k, 1, r, h);
        let w2 = if S::TANGENT { d2w(k, 1, r, h) } else { 0.0 };
        g[0] = d[0].lift(-sgn * w1, -w2);
        return (d[0].lift(w0, sgn * w1), g);
    }
    let mut r2 = S::zero();
    for a in d {
        r2 += a * a;
    }
    if r2.re() == 0.0 {
        let c = -d2w(k, D, 0.0, h);
        for (ga, &da) in g.iter_mut().zip(&d) {
            *ga = da * c;
        }
        return (S::cst(w(k, D, 0.0f64, h)), g);
    }
    let r = r2.sqrt();
    let f = -dw(k, D, r, h) / r;
    for (ga, &da) in g.iter_mut().zip(&d) {
        *ga = f * da;
    }
    (w(k, D, r, h), g)
}

/// d²W/dr²(r, h) in dimension `dim` (value only; its derivative is not available).
#[inline]
pub fn d2w(k: &dyn Kernel, dim: usize, r: f64, h: f64) -> f64 {
    let Some(q) = q_inside(k, r, h) else {
        return 0.0;
    };
    k.sigma(dim) / h.powi(dim as i32 + 2) * k.d2f(dim, q)
}

/// `q = |r|/h` inside the support, `None` on or beyond it. The support test is `|r| ≥ ζh`,
/// exactly the test every neighbour search applies (`|d| < R` with `R = ζh`), so a node sitting
/// on the support edge is outside for the kernel too: `r/h` alone can round to just below ζ
/// there (3 · 1.4 = 4.199999999999999 but 4.199999999999999 / 1.4 < 3), which for the
/// truncated Gaussian, discontinuous at ζ, would switch the node back on.
#[inline]
fn q_inside(k: &dyn Kernel, r: f64, h: f64) -> Option<f64> {
    let r = r.abs();
    if r >= k.zeta() * h { None } else { Some(r / h) }
}

/// One row of the kernel table (`sphstab kernels --json`, Python `sphstab.kernels()`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct KernelRow {
    /// Name.
    pub name: &'static str,
    /// Support radius in units of h.
    pub zeta: f64,
    /// Normalisation σ in 1D, 2D, 3D.
    pub sigma_1: f64,
    /// 2D normalisation.
    pub sigma_2: f64,
    /// 3D normalisation.
    pub sigma_3: f64,
    /// Inflection point q* of W (1D).
    pub inflection_1d: f64,
    /// Inflection point q* of W (2D).
    pub inflection_2d: f64,
    /// Customary h/Δx range.
    pub customary_h: (f64, f64),
    /// Where the kernel comes from.
    pub reference: &'static str,
}

/// The kernel table: every kernel of [`all`] with its support, normalisations, inflection
/// points, customary h/Δx range and reference.
pub fn table() -> Vec<KernelRow> {
    all()
        .iter()
        .map(|k| KernelRow {
            name: k.name(),
            zeta: k.zeta(),
            sigma_1: k.sigma(1),
            sigma_2: k.sigma(2),
            sigma_3: k.sigma(3),
            inflection_1d: k.inflection(1),
            inflection_2d: k.inflection(2),
            customary_h: k.customary_h(),
            reference: k.reference(),
        })
        .collect()
}

/// All kernels, in the order of SPEC §2.
pub fn all() -> &'static [&'static dyn Kernel] {
    ALL
}

static ALL: &[&dyn Kernel] = &[
    &M4,
    &M5,
    &M6,
    &WendlandC2,
    &WendlandC4,
    &WendlandC6,
    &Gaussian,
    &Lucy,
    &EfgCubic,
    &EfgQuartic,
    &Mollifier,
];

/// Looks a kernel up by its CLI name.
pub fn by_name(name: &str) -> Result<&'static dyn Kernel> {
    all()
        .iter()
        .copied()
        .find(|k| k.name() == name)
        .ok_or_else(|| Error::UnknownName {
            what: "kernel".into(),
            given: name.to_string(),
            valid: all()
                .iter()
                .map(|k| k.name())
                .collect::<Vec<_>>()
                .join(", ")
                .into(),
        })
}

/// Index 0, 1, 2 of a per-dimension table for `dim` = 1, 2, 3 (other values clamped).
fn dim_index(dim: usize) -> usize {
    dim.clamp(1, 3) - 1
}
