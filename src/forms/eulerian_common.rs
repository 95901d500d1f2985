//! Pieces of the 1D-only Eulerian-kernel forms of \[B00\] (stress points, nodal Galerkin):
//! neighbour stencils on the current configuration and the master volumes.

use super::model::{Model1D, State1D};
use crate::error::Result;
use crate::scalar::Scalar;
use crate::shape::{self, ShapeFamily};

/// One neighbour J of an evaluation point: index, φ_J, ∂φ_J/∂x.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Nb<S> {
    pub j: usize,
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
                .map(|((&j, _), &(phi, [dphi]))| Nb { j, phi, dphi })
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
