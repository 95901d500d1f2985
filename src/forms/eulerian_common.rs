//! Pieces of the 1D-only Eulerian-kernel forms of \[B00\] (stress points, nodal Galerkin):
//! neighbour stencils on the current configuration and the master volumes, built into the
//! reusable buffers of a [`Workspace1D`](super::Workspace1D) (no allocation once grown).

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

/// Stencils of several evaluation points, stored flat: the neighbours of point p are
/// `nb[start[p]..start[p + 1]]`.
#[derive(Clone, Debug)]
pub(crate) struct Stencils<S> {
    nb: Vec<Nb<S>>,
    start: Vec<usize>,
}

impl<S> Default for Stencils<S> {
    fn default() -> Self {
        Self {
            nb: Vec::new(),
            start: Vec::new(),
        }
    }
}

impl<S> Stencils<S> {
    /// The stencil of point `p`.
    #[inline]
    pub(crate) fn get(&self, p: usize) -> &[Nb<S>] {
        &self.nb[self.start[p]..self.start[p + 1]]
    }

    /// Number of points.
    pub(crate) fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    /// Total neighbour entries (for memory reports).
    pub(crate) fn capacity_bytes(&self) -> usize {
        self.nb.capacity() * std::mem::size_of::<Nb<S>>()
            + self.start.capacity() * std::mem::size_of::<usize>()
    }
}

/// Scratch of the stencil build: (relative position, volume), indices, (φ, φ').
#[derive(Clone, Debug)]
pub(crate) struct StencilScratch<S> {
    nodes: Vec<([S; 1], S)>,
    idx: Vec<usize>,
    vals: Vec<(S, [S; 1])>,
    search: ChainSearch,
}

impl<S> Default for StencilScratch<S> {
    fn default() -> Self {
        Self {
            nodes: Vec::new(),
            idx: Vec::new(),
            vals: Vec::new(),
            search: ChainSearch::default(),
        }
    }
}

impl<S> StencilScratch<S> {
    pub(crate) fn search_mut(&mut self) -> &mut ChainSearch {
        &mut self.search
    }

    pub(crate) fn capacity_bytes(&self) -> usize {
        use std::mem::size_of;
        self.nodes.capacity() * size_of::<([S; 1], S)>()
            + self.idx.capacity() * size_of::<usize>()
            + self.vals.capacity() * size_of::<(S, [S; 1])>()
            + self.search.capacity_bytes()
    }
}

/// Stencils of the masters around the evaluation points `pts` on the current configuration,
/// with shape family `family` and master volumes `vol`, into `out` (cleared and refilled).
/// `sc.search` must have been prepared for `z` ([`ChainSearch::prepare`]).
pub(crate) fn stencils<S: Scalar>(
    m: &Model1D,
    z: &State1D<S>,
    pts: &[S],
    family: ShapeFamily,
    vol: &[S],
    sc: &mut StencilScratch<S>,
    out: &mut Stencils<S>,
) -> Result<()> {
    let r = m.p.kp.support();
    out.nb.clear();
    out.start.clear();
    out.start.push(0);
    sc.search.restart();
    for &xp in pts {
        sc.nodes.clear();
        sc.idx.clear();
        sc.search.candidates(xp.re(), r, &mut sc.idx);
        sc.idx.retain(|&j| m.rel(xp, z.x[j]).re().abs() < r);
        for &j in sc.idx.iter() {
            sc.nodes.push(([m.rel(xp, z.x[j])], vol[j]));
        }
        shape::eval_d(family, m.p.kp, &sc.nodes, xp.re(), &mut sc.vals)?;
        out.nb.extend(
            sc.idx
                .iter()
                .zip(&sc.vals)
                .map(|(&j, &(phi, [dphi]))| Nb { j, phi, dphi }),
        );
        out.start.push(out.nb.len());
    }
    Ok(())
}

/// Neighbour search along a 1D chain, O(N) for an ordered chain: the masters' (wrapped)
/// positions and their order, and for each of the three periodic images a sliding window
/// [lo, hi) that moves forward while the evaluation points increase.
///
/// Ordered chain (the usual case: particles sorted along x, no crossing, evaluation points in
/// increasing order): no sort and no binary search, each window end advances monotonically —
/// O(N + pairs) per stencil build. When the order breaks, it falls back, and the result is the
/// same: masters out of order (after a crossing, or a periodic chain whose particles moved
/// across the period's origin) → an index sort by position (`sort_unstable_by`, in place, no
/// allocation); an evaluation point left of the previous one → a binary search for that
/// window, which then slides on from there. Candidates are returned sorted by index, so every
/// sum over a stencil runs in index order whatever path found it.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChainSearch {
    order: Vec<usize>,
    sorted: Vec<f64>,
    /// `order` is the identity (the chain is ordered).
    identity: bool,
    period: Option<f64>,
    /// Window per image (centre offset 0, −L, +L): (lo, hi, last centre).
    win: [(usize, usize, f64); 3],
    /// Counters of the paths taken (tests): builds that had to sort, binary searches.
    pub(crate) sorts: usize,
    pub(crate) bisections: usize,
}

impl ChainSearch {
    fn capacity_bytes(&self) -> usize {
        self.order.capacity() * std::mem::size_of::<usize>()
            + self.sorted.capacity() * std::mem::size_of::<f64>()
    }

    /// Prepares the search for the masters of `z`.
    pub(crate) fn prepare<S: Scalar>(&mut self, m: &Model1D, z: &State1D<S>) {
        self.prepare_positions(m.period, z.x.iter().map(|x| x.re()));
    }

    /// Prepares the search for masters at `pos` in a chain of period `period`.
    pub(crate) fn prepare_positions(
        &mut self,
        period: Option<f64>,
        pos: impl Iterator<Item = f64>,
    ) {
        let wrap = |x: f64| match period {
            Some(l) => x.rem_euclid(l),
            None => x,
        };
        self.period = period;
        self.sorted.clear();
        self.sorted.extend(pos.map(wrap));
        self.order.clear();
        self.order.extend(0..self.sorted.len());
        self.identity = self.sorted.windows(2).all(|w| w[0] <= w[1]);
        if !self.identity {
            self.sorts += 1;
            let pos = &self.sorted;
            self.order
                .sort_unstable_by(|&a, &b| pos[a].total_cmp(&pos[b]).then(a.cmp(&b)));
            self.gather_sorted();
        }
        self.restart();
    }

    /// Rewrites `sorted` as the positions in `order` (in place, by cycles of the permutation).
    fn gather_sorted(&mut self) {
        let n = self.order.len();
        // sorted[k] ← sorted[order[k]] along each cycle; visited entries of `order` are
        // marked by adding n, removed afterwards
        for start in 0..n {
            if self.order[start] >= n {
                continue;
            }
            let first = self.sorted[start];
            let mut k = start;
            loop {
                let src = self.order[k];
                self.order[k] = src + n; // visited
                if src == start {
                    self.sorted[k] = first;
                    break;
                }
                self.sorted[k] = self.sorted[src];
                k = src;
            }
        }
        for o in self.order.iter_mut() {
            *o -= n;
        }
    }

    /// Starts a new pass over evaluation points (windows back at the chain's start).
    pub(crate) fn restart(&mut self) {
        self.win = [(0, 0, f64::NEG_INFINITY); 3];
    }

    /// Every master within `r` of `x` (and possibly a few more), sorted by index.
    pub(crate) fn candidates(&mut self, x: f64, r: f64, idx: &mut Vec<usize>) {
        // a slightly wider window: the caller applies the exact |x_J − x| < r test
        let r = r * (1.0 + 1e-9);
        let n = self.order.len();
        match self.period {
            // a support wider than half the period: every master, once
            Some(l) if 2.0 * r >= l => {
                idx.extend(0..n);
                return;
            }
            Some(l) => {
                let c = x.rem_euclid(l);
                self.window(0, c, r, idx);
                self.window(1, c - l, r, idx);
                self.window(2, c + l, r, idx);
            }
            None => self.window(0, x, r, idx),
        }
        idx.sort_unstable();
        idx.dedup();
    }

    /// The masters with position in (c − r, c + r), by window `w`.
    fn window(&mut self, w: usize, c: f64, r: f64, idx: &mut Vec<usize>) {
        let s = &self.sorted;
        let (mut lo, mut hi, last) = self.win[w];
        if c >= last {
            // slide forward: the partition points only move right as c grows
            while lo < s.len() && s[lo] <= c - r {
                lo += 1;
            }
            hi = hi.max(lo);
            while hi < s.len() && s[hi] < c + r {
                hi += 1;
            }
        } else {
            self.bisections += 1;
            lo = s.partition_point(|&p| p <= c - r);
            hi = s.partition_point(|&p| p < c + r).max(lo);
        }
        self.win[w] = (lo, hi, c);
        if self.identity {
            idx.extend(lo..hi);
        } else {
            idx.extend_from_slice(&self.order[lo..hi]);
        }
    }
}

/// Current master volumes V_J = m_J / ρ_J, into `out`.
pub(crate) fn volumes<S: Scalar>(m: &Model1D, z: &State1D<S>, out: &mut Vec<S>) {
    out.clear();
    out.extend(
        z.rho
            .iter()
            .zip(&m.mass)
            .map(|(&rho, &mass)| S::cst(mass) / rho),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::forms::{FormKind, ModelParams};
    use crate::shape::KernelParams;

    fn model(n: usize, period: Option<f64>) -> Model1D {
        let p = ModelParams {
            form: FormKind::EulerianStressPoints,
            shape: ShapeFamily::Mls,
            kp: KernelParams {
                kernel: crate::kernel::by_name("m4").unwrap(),
                h: 1.3,
            },
            modulus: 1.0,
            rho0: 1.0,
            sigma0: 0.0,
            c_partition: 0.5,
            alpha_s: 0.0,
            av: None,
            dx: 1.0,
            diffusion: None,
        };
        Model1D::new(p, (0..n).map(|i| i as f64).collect(), vec![1.0; n], period).unwrap()
    }

    /// The brute-force neighbour list: every master within r (minimum image), by index.
    fn brute(m: &Model1D, x: &[f64], c: f64, r: f64) -> Vec<usize> {
        (0..x.len()).filter(|&j| m.rel(c, x[j]).abs() < r).collect()
    }

    /// Ordered, crossed and wrapped chains, evaluation points in order and out of order: the
    /// sliding window and each fallback give the brute-force neighbour sets.
    #[test]
    fn sliding_window_and_fallbacks_match_a_full_scan() {
        for period in [None, Some(20.0)] {
            let m = model(20, period);
            let r = m.p.kp.support();
            let mut z = m.rest_state();
            let mut cases = Vec::new();
            cases.push((z.x.clone(), false));
            // two particles crossed
            z.x.swap(7, 8);
            z.x[7] += 0.1;
            cases.push((z.x.clone(), true));
            // the chain shifted across the periodic origin (or to negative x)
            let shifted: Vec<f64> = m.x_ref.iter().map(|x| x - 2.5).collect();
            cases.push((shifted, period.is_some()));
            for (x, unordered) in cases {
                let mut zz = m.rest_state();
                zz.x = x.clone();
                let mut s = ChainSearch::default();
                s.prepare(&m, &zz);
                assert_eq!(s.sorts, usize::from(unordered), "{period:?} {x:?}");
                // points in increasing order, then a few going back (bisection fallback)
                let mut pts: Vec<f64> = (0..40).map(|i| -1.0 + 0.55 * i as f64).collect();
                pts.extend([3.0, 15.2, 0.4, 19.9, -0.7]);
                s.restart();
                for &c in &pts {
                    let mut idx = Vec::new();
                    s.candidates(c, r, &mut idx);
                    idx.retain(|&j| m.rel(c, x[j]).abs() < r);
                    assert_eq!(idx, brute(&m, &x, c, r), "{period:?} at {c}");
                }
                assert!(s.bisections > 0);
            }
        }
    }
}
