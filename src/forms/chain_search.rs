//! The neighbour search and stencil storage of the 1D-only forms of \[B00\] (stress points,
//! nodal Galerkin, least squares): a sliding-window search along a chain and flat stencils,
//! kept in the reusable buffers of a [`ChainWorkspace`] (no allocation once grown).

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
    pub(crate) nb: Vec<Nb<S>>,
    pub(crate) start: Vec<usize>,
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
    pub(crate) nodes: Vec<([S; 1], S)>,
    pub(crate) idx: Vec<usize>,
    pub(crate) vals: Vec<(S, [S; 1])>,
    pub(crate) search: ChainSearch,
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

/// Reusable buffers of the 1D-only forms of \[B00\] (part of a
/// [`RateWorkspace`](super::RateWorkspace)): the master volumes, the flat stencils of masters
/// and stress points, the neighbour search, the displacements, and the full rate the partial
/// outputs are copied from. Cleared and refilled, never freed.
#[derive(Clone, Debug)]
pub(crate) struct ChainWorkspace<S> {
    pub(crate) vol: Vec<S>,
    pub(crate) st_m: Stencils<S>,
    pub(crate) st_s: Stencils<S>,
    pub(crate) scratch: StencilScratch<S>,
    pub(crate) u: Vec<S>,
    /// The full rate the requested parts are copied from.
    pub(crate) rate: ChainRates<S>,
}

/// The rates of a 1D-only form, one entry per master or stress point (fields the form does
/// not carry are empty).
#[derive(Clone, Debug)]
pub(crate) struct ChainRates<S> {
    /// ẋ.
    pub(crate) x: Vec<S>,
    /// v̇ (lumped mass), or the force f of M a = f (consistent mass).
    pub(crate) v: Vec<S>,
    /// ρ̇.
    pub(crate) rho: Vec<S>,
    /// σ̇.
    pub(crate) sigma: Vec<S>,
    /// ẋ^S.
    pub(crate) sp_x: Vec<S>,
    /// σ̇^S.
    pub(crate) sp_sigma: Vec<S>,
    /// V̇^S.
    pub(crate) sp_vol: Vec<S>,
}

impl<S> Default for ChainRates<S> {
    fn default() -> Self {
        Self {
            x: Vec::new(),
            v: Vec::new(),
            rho: Vec::new(),
            sigma: Vec::new(),
            sp_x: Vec::new(),
            sp_sigma: Vec::new(),
            sp_vol: Vec::new(),
        }
    }
}

impl<S> ChainRates<S> {
    fn capacity(&self) -> usize {
        [
            &self.x,
            &self.v,
            &self.rho,
            &self.sigma,
            &self.sp_x,
            &self.sp_sigma,
            &self.sp_vol,
        ]
        .iter()
        .map(|v| v.capacity())
        .sum()
    }
}

impl<S> Default for ChainWorkspace<S> {
    fn default() -> Self {
        Self {
            vol: Vec::new(),
            st_m: Stencils::default(),
            st_s: Stencils::default(),
            scratch: StencilScratch::default(),
            u: Vec::new(),
            rate: Default::default(),
        }
    }
}

impl<S> ChainWorkspace<S> {
    /// Bytes reserved by the buffers (capacities).
    pub(crate) fn reserved_bytes(&self) -> usize {
        let s = std::mem::size_of::<S>();
        (self.vol.capacity() + self.u.capacity() + self.rate.capacity()) * s
            + self.st_m.capacity_bytes()
            + self.st_s.capacity_bytes()
            + self.scratch.capacity_bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Minimum-image b − a on a chain of period `period`.
    fn rel(period: Option<f64>, a: f64, b: f64) -> f64 {
        let d = b - a;
        match period {
            Some(l) => d - (d / l).round() * l,
            None => d,
        }
    }

    /// The brute-force neighbour list: every master within r (minimum image), by index.
    fn brute(period: Option<f64>, x: &[f64], c: f64, r: f64) -> Vec<usize> {
        (0..x.len())
            .filter(|&j| rel(period, c, x[j]).abs() < r)
            .collect()
    }

    /// Ordered, crossed and wrapped chains, evaluation points in order and out of order: the
    /// sliding window and each fallback give the brute-force neighbour sets.
    #[test]
    fn sliding_window_and_fallbacks_match_a_full_scan() {
        // m4 at h = 1.3Δx: support 2.6Δx
        let r = 2.6;
        for period in [None, Some(20.0)] {
            let x_ref: Vec<f64> = (0..20).map(|i| i as f64).collect();
            let mut cases = Vec::new();
            cases.push((x_ref.clone(), false));
            // two particles crossed
            let mut crossed = x_ref.clone();
            crossed.swap(7, 8);
            crossed[7] += 0.1;
            cases.push((crossed, true));
            // the chain shifted across the periodic origin (or to negative x)
            let shifted: Vec<f64> = x_ref.iter().map(|x| x - 2.5).collect();
            cases.push((shifted, period.is_some()));
            for (x, unordered) in cases {
                let mut s = ChainSearch::default();
                s.prepare_positions(period, x.iter().copied());
                assert_eq!(s.sorts, usize::from(unordered), "{period:?} {x:?}");
                // points in increasing order, then a few going back (bisection fallback)
                let mut pts: Vec<f64> = (0..40).map(|i| -1.0 + 0.55 * i as f64).collect();
                pts.extend([3.0, 15.2, 0.4, 19.9, -0.7]);
                s.restart();
                for &c in &pts {
                    let mut idx = Vec::new();
                    s.candidates(c, r, &mut idx);
                    idx.retain(|&j| rel(period, c, x[j]).abs() < r);
                    assert_eq!(idx, brute(period, &x, c, r), "{period:?} at {c}");
                }
                assert!(s.bisections > 0);
            }
        }
    }
}
