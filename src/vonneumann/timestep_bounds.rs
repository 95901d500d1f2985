//! Time-step bounds of \[B00 §5\] against the exact maximum eigenvalue of the uniform lattice.
//!
//! The Galerkin wave equation M ü = −c² K u with lumped (row-sum) mass, integrated with
//! quadrature points Q of weights w_Q. The exact λ_max is the largest Bloch eigenvalue over the
//! Brillouin zone. The bounds:
//! - eq 124/132 (1D) and eq 144 (2D): the element-eigenvalue inequality, λ ≤ max_Q λ^Q with
//!   λ^Q = c² Σ_I φ_{I,x}²/φ_I (per direction in 2D), computed from the actual shape functions;
//! - eq 136 (1D): λ ≤ α c²/h², α = 12.42, h the support radius (D_mx Δx);
//! - eq 146 / eq 148 (2D): λ ≤ α₁ c²/h² (α₁ = 13.30, cubic spline) or α₂ c²/h² (α₂ = 15.00).
//!
//! All eigenvalues are normalised by c²/Δx²; Δt_crit = 2/√λ_max in Δx/c.

use super::antiplane::{AntiPlane, Mass, Quadrature};
use crate::error::Result;
use crate::lattice::Lattice;
use crate::shape::eval_d;
use crate::shape::{KernelParams, ShapeFamily, eval};
use std::f64::consts::PI;

/// \[B00\] eq 136.
pub const ALPHA_1D: f64 = 12.42;
/// \[B00\] eq 146 (cubic spline).
pub const ALPHA1_2D: f64 = 13.30;
/// \[B00\] eq 148.
pub const ALPHA2_2D: f64 = 15.00;

/// Exact and bounded maximum eigenvalues (normalised by c²/Δx²).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Bounds {
    /// Support radius D_mx (units of Δx).
    pub d_mx: f64,
    /// Exact λ_max (largest Bloch eigenvalue) with the lumped (row-sum) mass the bounds assume.
    pub exact: f64,
    /// Exact λ_max with the consistent mass ∫φ_Iφ_J (for comparison with B00 Figs 17–18).
    pub exact_consistent: f64,
    /// Element-eigenvalue bound (eq 124/132 in 1D, eq 144 in 2D), from the shape functions.
    pub element: f64,
    /// Closed-form bounds: eq 136 (1D), or eq 146 and eq 148 (2D).
    pub closed: Vec<(String, f64)>,
}

impl Bounds {
    /// Ratios bound/exact (≥ 1 where the bound holds), element bound first.
    pub fn ratios(&self) -> Vec<(String, f64)> {
        let mut r = vec![("element".to_string(), self.element / self.exact)];
        r.extend(self.closed.iter().map(|(n, v)| (n.clone(), v / self.exact)));
        r
    }
}

/// Quadrature points in one cell [0, 1) (1D): nodal or 2-point Gauss.
pub(crate) fn points_1d(gauss2: bool) -> Vec<(f64, f64)> {
    if gauss2 {
        let g = 0.5 / 3f64.sqrt();
        vec![(0.5 - g, 0.5), (0.5 + g, 0.5)]
    } else {
        vec![(0.0, 1.0)]
    }
}

/// 1D bar: EFG shapes `family` with weight `kp` (support kp.support() = D_mx), quadrature nodal
/// (`gauss2 = false`) or 2 Gauss points per cell (B00 Fig 17).
pub fn bounds_1d(
    family: ShapeFamily,
    kp: KernelParams,
    gauss2: bool,
    n_kappa: usize,
) -> Result<Bounds> {
    let r = kp.support();
    let pts = points_1d(gauss2);
    // per quadrature point: (j, φ_j, φ'_j) for all nodes j within the support
    let mut stencils = Vec::new();
    let mut element: f64 = 0.0;
    for &(xq, w) in &pts {
        let lo = (xq - r).floor() as i64 - 1;
        let hi = (xq + r).ceil() as i64 + 1;
        let ids: Vec<i64> = (lo..=hi).filter(|&j| (j as f64 - xq).abs() < r).collect();
        let nodes: Vec<(f64, f64)> = ids.iter().map(|&j| (j as f64 - xq, 1.0)).collect();
        let mut out = Vec::new();
        eval(family, kp, &nodes, xq, &mut out)?;
        let lam_q: f64 = out
            .iter()
            .filter(|p| p.0 > 0.0)
            .map(|p| p.1 * p.1 / p.0)
            .sum();
        element = element.max(lam_q);
        stencils.push((w, ids, out));
    }
    let mass: f64 = stencils
        .iter()
        .map(|(w, _, out)| w * out.iter().map(|p| p.0).sum::<f64>())
        .sum();
    let mut exact: f64 = 0.0;
    let mut exact_consistent: f64 = 0.0;
    for i in 0..=n_kappa {
        let kap = PI * i as f64 / n_kappa as f64;
        let (mut k, mut m) = (0.0, 0.0);
        for (w, ids, out) in &stencils {
            let (mut re, mut im, mut pre, mut pim) = (0.0, 0.0, 0.0, 0.0);
            for (&j, p) in ids.iter().zip(out) {
                let (c, s) = ((kap * j as f64).cos(), (kap * j as f64).sin());
                re += p.1 * c;
                im += p.1 * s;
                pre += p.0 * c;
                pim += p.0 * s;
            }
            k += w * (re * re + im * im);
            m += w * (pre * pre + pim * pim);
        }
        exact = exact.max(k / mass);
        if m > 0.0 {
            exact_consistent = exact_consistent.max(k / m);
        }
    }
    Ok(Bounds {
        d_mx: r,
        exact,
        exact_consistent,
        element,
        closed: vec![("eq 136".into(), ALPHA_1D / (r * r))],
    })
}

/// 2D anti-plane wave on a square lattice (γ = 1) with background cells and 2×2 Gauss points
/// (the setting of B00 Fig 18), or any other quadrature pattern.
pub fn bounds_2d(
    family: ShapeFamily,
    kp: KernelParams,
    q: Quadrature,
    n_grid: usize,
) -> Result<Bounds> {
    let lat = Lattice::<2>::square(1.0)?;
    let ap = AntiPlane::new(&lat, q, family, kp)?;
    let mut exact: f64 = 0.0;
    let mut exact_consistent: f64 = 0.0;
    for i in 0..=n_grid {
        for j in 0..=i {
            let k = [PI * i as f64 / n_grid as f64, PI * j as f64 / n_grid as f64];
            exact = exact.max(*ap.omega2(k, Mass::Lumped)?.last().unwrap_or(&0.0));
            exact_consistent =
                exact_consistent.max(*ap.omega2(k, Mass::Consistent)?.last().unwrap_or(&0.0));
        }
    }
    let r = kp.support();
    let mut element: f64 = 0.0;
    let mut out = Vec::new();
    for &(xq, _) in &ap.pattern.points {
        let n = r.ceil() as i64 + 2;
        let mut nodes = Vec::new();
        for a in -n..=n {
            for b in -n..=n {
                let d = [a as f64 - xq[0], b as f64 - xq[1]];
                if d[0].hypot(d[1]) < r {
                    nodes.push((d, 1.0));
                }
            }
        }
        eval_d(family, kp, &nodes, xq[0], &mut out)?;
        let pos = out.iter().filter(|p| p.0 > 0.0);
        let lx: f64 = pos.clone().map(|p| p.1[0] * p.1[0] / p.0).sum();
        let ly: f64 = pos.map(|p| p.1[1] * p.1[1] / p.0).sum();
        element = element.max(lx.max(ly));
    }
    Ok(Bounds {
        d_mx: r,
        exact,
        exact_consistent,
        element,
        closed: vec![
            ("eq 146".into(), ALPHA1_2D / (r * r)),
            ("eq 148".into(), ALPHA2_2D / (r * r)),
        ],
    })
}
