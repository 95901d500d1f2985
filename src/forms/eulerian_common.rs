//! Pieces shared by the Eulerian-kernel forms: neighbour stencils on the current
//! configuration, velocity gradients and the artificial-viscosity force.

use super::model::{Model1D, State1D};
use crate::error::Result;
use crate::scalar::Scalar;
use crate::shape::{self, ShapeFamily};

/// One neighbour J of an evaluation point: index, relative position d = x_J − x, φ_J, ∂φ_J/∂x.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Nb<S> {
    pub j: usize,
    pub d: S,
    pub phi: S,
    pub dphi: S,
}

/// Stencils of the masters around the evaluation points `pts` on the current configuration,
/// with shape family `family`; volumes V_J = m_J / ρ_J when the state carries density,
/// `vol_fallback` otherwise.
pub(crate) fn stencils<S: Scalar>(
    m: &Model1D,
    z: &State1D<S>,
    pts: &[S],
    family: ShapeFamily,
    vol: &[S],
) -> Result<Vec<Vec<Nb<S>>>> {
    let r = m.p.kp.support();
    let mut out = Vec::with_capacity(pts.len());
    let mut nodes = Vec::new();
    let mut idx = Vec::new();
    let mut vals = Vec::new();
    let search = SortedSearch::new(m, z);
    for &xp in pts {
        nodes.clear();
        idx.clear();
        search.candidates(xp.re(), r, &mut idx);
        idx.retain(|&j| m.rel(xp, z.x[j]).re().abs() < r);
        for &j in idx.iter() {
            nodes.push(([m.rel(xp, z.x[j])], vol[j]));
        }
        shape::eval_d(family, m.p.kp, &nodes, xp.re(), &mut vals)?;
        out.push(
            idx.iter()
                .zip(&nodes)
                .zip(&vals)
                .map(|((&j, &([d], _)), &(phi, [dphi]))| Nb { j, d, phi, dphi })
                .collect(),
        );
    }
    Ok(out)
}

/// O(N log N) neighbour search in 1D: masters sorted by (wrapped) position, candidates found by
/// binary search, returned in index order (so sums run in the same order as a full scan).
struct SortedSearch {
    order: Vec<usize>,
    sorted: Vec<f64>,
    period: Option<f64>,
}

impl SortedSearch {
    fn new<S: Scalar>(m: &Model1D, z: &State1D<S>) -> Self {
        let wrap = |x: f64| match m.period {
            Some(l) => x.rem_euclid(l),
            None => x,
        };
        let pos: Vec<f64> = z.x.iter().map(|x| wrap(x.re())).collect();
        let mut order: Vec<usize> = (0..pos.len()).collect();
        order.sort_by(|&a, &b| pos[a].total_cmp(&pos[b]));
        let sorted = order.iter().map(|&i| pos[i]).collect();
        Self {
            order,
            sorted,
            period: m.period,
        }
    }

    /// Every master within `r` of `x` (and possibly a few more), sorted by index.
    fn candidates(&self, x: f64, r: f64, idx: &mut Vec<usize>) {
        // a slightly wider window: the caller applies the exact |x_J − x| < r test
        let r = r * (1.0 + 1e-9);
        let mut window = |c: f64| {
            let lo = self.sorted.partition_point(|&p| p <= c - r);
            let hi = self.sorted.partition_point(|&p| p < c + r);
            idx.extend_from_slice(&self.order[lo..hi.max(lo)]);
        };
        match self.period {
            // a support wider than half the period: every master, once
            Some(l) if 2.0 * r >= l => idx.extend(0..self.order.len()),
            Some(l) => {
                let c = x.rem_euclid(l);
                window(c);
                window(c - l);
                window(c + l);
            }
            None => window(x),
        }
        idx.sort_unstable();
        idx.dedup();
    }
}

/// Current master volumes V_J = m_J / ρ_J.
pub(crate) fn volumes<S: Scalar>(m: &Model1D, z: &State1D<S>) -> Vec<S> {
    z.rho
        .iter()
        .zip(&m.mass)
        .map(|(&rho, &mass)| S::cst(mass) / rho)
        .collect()
}

/// Velocity gradient at master I from its stencil: Σ_J (v_J − v_I) ∂φ_J(x_I) \[V21 eq 53\].
#[inline]
pub(crate) fn grad_v<S: Scalar>(z: &State1D<S>, i: usize, st: &[Nb<S>]) -> S {
    let mut g = S::zero();
    for nb in st {
        g += (z.v[nb.j] - z.v[i]) * nb.dphi;
    }
    g
}

/// Difference-form stress divergence (1/ρ_I) Σ_J (s_J − s_I) ∂φ_J(x_I) \[V21 eq 54\].
#[inline]
pub(crate) fn div_difference<S: Scalar>(s: &[S], rho_i: S, i: usize, st: &[Nb<S>]) -> S {
    let mut a = S::zero();
    for nb in st {
        a += (s[nb.j] - s[i]) * nb.dphi;
    }
    a / rho_i
}

/// Monaghan's sum form Σ_J (s_I/ρ_I² + s_J/ρ_J²) ρ_J ∂φ_J(x_I) \[V21 eq 55\]; for `sph`
/// shapes ρ_J ∂φ_J(x_I) = m_J ∇_I W_IJ.
#[inline]
pub(crate) fn div_sum<S: Scalar>(s: &[S], rho: &[S], i: usize, st: &[Nb<S>]) -> S {
    let ti = s[i] / (rho[i] * rho[i]);
    let mut a = S::zero();
    for nb in st {
        let rj = rho[nb.j];
        a += (ti + s[nb.j] / (rj * rj)) * rj * nb.dphi;
    }
    a
}

/// Artificial-viscosity acceleration −Σ_J m_J Π_IJ ∇_I W_IJ at master I (kernel gradient,
/// whatever the shape family).
pub(crate) fn av_accel<S: Scalar>(m: &Model1D, z: &State1D<S>, i: usize, st: &[Nb<S>]) -> S {
    let Some(av) = m.p.av else { return S::zero() };
    let h = m.p.kp.h;
    let mut a = S::zero();
    for nb in st {
        if nb.j == i {
            continue;
        }
        // x_IJ = x_I − x_J = −d, v_IJ = v_I − v_J
        let xij = -nb.d;
        let vij = z.v[i] - z.v[nb.j];
        let vx = vij * xij;
        if av.approaching_only && vx.re() >= 0.0 {
            continue;
        }
        let mu = vx * h / (xij * xij + 0.01 * h * h);
        let rho_bar = (z.rho[i] + z.rho[nb.j]) * 0.5;
        let pi = (mu * (-av.alpha * av.sound_speed) + mu * mu * av.beta) / rho_bar;
        // ∇_I W(x_I − x_J) = W'(|d|) sign(x_I − x_J), differentiable through d = 0
        let (_, [grad]) = crate::kernel::w_and_grad(m.p.kp.kernel, h, [nb.d]);
        a -= pi * grad * m.mass[nb.j];
    }
    a
}

/// ẋ = v for the masters.
pub(crate) fn kinematics<S: Scalar>(z: &State1D<S>, out: &mut State1D<S>) {
    out.x.copy_from_slice(&z.v);
}
