//! Cell-list neighbour search in D ∈ {1, 2, 3} dimensions: O(N) construction and queries for
//! particles within a radius, for open domains and rectangular (box) periodic domains.
//! (Parallelogram periodic patches, used only by the von Neumann engine on hexagonal, bcc and
//! fcc lattices, fall back to a direct scan.)

// Small-vector algebra (D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

/// The largest subdivision of [`CellList::rebuild_subdivided`].
pub const MAX_SUB: usize = 3;

/// A uniform grid of cells of side ≥ the search radius divided by the subdivision s (1 unless
/// built with [`CellList::rebuild_subdivided`]): the candidates of a point are the (2s + 1)^D
/// cells around its own.
///
/// [`CellList::rebuild`] refills an existing list in place: once its buffers have grown to the
/// particle and cell counts, a rebuild does not allocate (the solver's time loop relies on it).
#[derive(Clone, Debug)]
pub struct CellList<const D: usize = 2> {
    origin: [f64; D],
    size: f64,
    dims: [usize; D],
    /// Cells per search radius s: the candidates are the cells at offsets −s..=s per axis.
    sub: usize,
    /// Periodic extents (rectangular box) or None.
    period: Option<[f64; D]>,
    start: Vec<usize>,
    /// Particle indices, cell by cell (32 bits: the solver's memory per particle).
    items: Vec<u32>,
    /// Cell of each particle (construction buffer, kept for reuse).
    cell: Vec<u32>,
    /// Fill pointers (construction buffer, kept for reuse).
    fill: Vec<usize>,
}

impl<const D: usize> Default for CellList<D> {
    fn default() -> Self {
        Self {
            origin: [0.0; D],
            size: 0.0,
            dims: [1; D],
            sub: 1,
            period: None,
            start: Vec::new(),
            items: Vec::new(),
            cell: Vec::new(),
            fill: Vec::new(),
        }
    }
}

impl<const D: usize> CellList<D> {
    /// Builds the list for `pts` with cell side ≥ `radius`. `period`: rectangular periodic box
    /// [L_1, …, L_D] with the particles' coordinates anywhere (they are wrapped into the box).
    pub fn new(pts: &[[f64; D]], radius: f64, period: Option<[f64; D]>) -> Self {
        let mut c = Self::default();
        c.rebuild(pts, radius, period);
        c
    }

    /// Bytes reserved by the list's buffers (capacities), for memory reports.
    pub fn reserved_bytes(&self) -> usize {
        (self.start.capacity() + self.fill.capacity()) * std::mem::size_of::<usize>()
            + (self.items.capacity() + self.cell.capacity()) * std::mem::size_of::<u32>()
    }

    /// The grid a list for `pts` would have: origin, cell side, cells per axis.
    fn grid(
        pts: &[[f64; D]],
        radius: f64,
        period: Option<[f64; D]>,
    ) -> ([f64; D], f64, [usize; D]) {
        let (origin, ext) = match period {
            Some(l) => ([0.0; D], l),
            None => {
                let mut lo = [f64::INFINITY; D];
                let mut hi = [f64::NEG_INFINITY; D];
                for p in pts {
                    for a in 0..D {
                        lo[a] = lo[a].min(p[a]);
                        hi[a] = hi[a].max(p[a]);
                    }
                }
                if pts.is_empty() {
                    lo = [0.0; D];
                    hi = [0.0; D];
                }
                let mut ext = [0.0; D];
                for a in 0..D {
                    ext[a] = hi[a] - lo[a];
                }
                (lo, ext)
            }
        };
        let mut size = radius.max(1e-300);
        // at most 64 cells per point (and 4096): particles scattered far apart (a run that
        // is diverging) widen the cells instead of allocating the empty space between them;
        // cells wider than `radius` hold more candidates, never fewer
        let limit = (64.0 * pts.len() as f64).max(4096.0);
        let mut dims = [1usize; D];
        loop {
            let mut cells = 1.0;
            for a in 0..D {
                // periodic: cells must be at least `radius` wide, so use floor; open: one more
                let n = (ext[a] / size).floor().max(1.0) + f64::from(u8::from(period.is_none()));
                dims[a] = n as usize;
                cells *= n;
            }
            if cells <= limit {
                break;
            }
            size *= (cells / limit).powf(1.0 / D as f64) * 1.01;
        }
        (origin, size, dims)
    }

    /// Linear index of the cell of `p` in the grid (`origin`, `size`, `dims`, `period`).
    #[inline]
    fn cell_of(
        origin: [f64; D],
        size: f64,
        dims: [usize; D],
        period: Option<[f64; D]>,
        p: [f64; D],
    ) -> u32 {
        let mut k = 0;
        for a in 0..D {
            let x = p[a] - origin[a];
            let c = match period {
                Some(l) => {
                    let x = x.rem_euclid(l[a]);
                    ((x / l[a] * dims[a] as f64) as usize).min(dims[a] - 1)
                }
                None => ((x / size) as usize).min(dims[a] - 1),
            };
            k = k * dims[a] + c;
        }
        k as u32
    }

    /// Rebuilds the list for `pts` in place, reusing its buffers (same result as
    /// [`CellList::new`]). O(N + number of cells).
    pub fn rebuild(&mut self, pts: &[[f64; D]], radius: f64, period: Option<[f64; D]>) {
        self.rebuild_subdivided(pts, radius, period, 1);
    }

    /// [`CellList::rebuild`] with cells of side ≥ `radius`/`sub` (`sub` in 1..=3), whose
    /// candidates are the (2 sub + 1)^D cells around a point: in 3D, `sub` = 2 tests 5³ cells of
    /// half the side, 0.58× the volume of 3³ cells of the full side (fewer candidates to reject).
    pub fn rebuild_subdivided(
        &mut self,
        pts: &[[f64; D]],
        radius: f64,
        period: Option<[f64; D]>,
        sub: usize,
    ) {
        assert!((1..=MAX_SUB).contains(&sub), "cell list subdivision {sub}");
        self.sub = sub;
        let (origin, size, dims) = Self::grid(pts, radius / sub as f64, period);
        self.origin = origin;
        self.size = size;
        self.dims = dims;
        self.period = period;
        let ncell: usize = dims.iter().product();
        assert!(
            ncell < u32::MAX as usize && pts.len() < u32::MAX as usize,
            "cell list: {ncell} cells, {} particles (32-bit indices)",
            pts.len()
        );
        let count = &mut self.start;
        count.clear();
        count.resize(ncell + 1, 0);
        let mut cell = std::mem::take(&mut self.cell);
        cell.clear();
        cell.extend(
            pts.iter()
                .map(|&p| Self::cell_of(origin, size, dims, period, p)),
        );
        let count = &mut self.start;
        for &c in &cell {
            count[c as usize + 1] += 1;
        }
        for i in 0..ncell {
            count[i + 1] += count[i];
        }
        self.fill.clear();
        self.fill.extend_from_slice(count);
        self.items.clear();
        self.items.resize(pts.len(), 0);
        for (i, &c) in cell.iter().enumerate() {
            let c = c as usize;
            self.items[self.fill[c]] = i as u32;
            self.fill[c] += 1;
        }
        self.cell = cell;
    }

    /// Calls `f(j)` for every particle j in the (2s + 1)^D block of cells around `p` (s the
    /// subdivision, 1 by default: 3^D cells; a superset of those within the radius; callers test
    /// the distance). Cells are visited first axis slowest, offsets −s, …, s per axis; a cell is
    /// visited once even when a small periodic box (fewer than 2s + 1 cells on an axis) wraps
    /// onto it again.
    #[inline]
    pub fn for_candidates(&self, p: [f64; D], mut f: impl FnMut(usize)) {
        self.for_candidate_runs(p, |run| {
            for &j in run {
                f(j as usize);
            }
        });
    }

    /// The candidates of [`CellList::for_candidates`], in the same order, as contiguous runs of
    /// the cell-sorted particle indices: cells adjacent along the last axis are adjacent in
    /// memory, so a (2s + 1)^D block is (2s + 1)^(D−1) runs (more only where a periodic box
    /// wraps). A tight loop over a run is what the neighbour search spends its time in.
    #[inline]
    pub fn for_candidate_runs(&self, p: [f64; D], mut f: impl FnMut(&[u32])) {
        // per axis: the distinct cell coordinates of offsets −s..=s, in that order
        let s = self.sub as i64;
        let mut ax = [[0usize; 2 * MAX_SUB + 1]; D];
        let mut cnt = [0usize; D];
        for a in 0..D {
            let x = p[a] - self.origin[a];
            let n = self.dims[a] as i64;
            let c = match self.period {
                Some(l) => {
                    let xw = x.rem_euclid(l[a]);
                    ((xw / l[a] * self.dims[a] as f64) as i64).min(n - 1)
                }
                None => ((x / self.size).floor() as i64).clamp(0, n - 1),
            };
            for o in -s..=s {
                let mut ci = c + o;
                if self.period.is_some() {
                    ci = ci.rem_euclid(n);
                } else if ci < 0 || ci >= n {
                    continue;
                }
                let ci = ci as usize;
                if !ax[a][..cnt[a]].contains(&ci) {
                    ax[a][cnt[a]] = ci;
                    cnt[a] += 1;
                }
            }
        }
        // the last axis' cells as runs of consecutive coordinates (one run unless it wraps)
        let last = D - 1;
        let mut runs = [(0usize, 0usize); 2 * MAX_SUB + 1];
        let mut nruns = 0;
        for &ci in &ax[last][..cnt[last]] {
            if nruns > 0 && runs[nruns - 1].1 == ci {
                runs[nruns - 1].1 = ci + 1;
            } else {
                runs[nruns] = (ci, ci + 1);
                nruns += 1;
            }
        }
        // odometer over the leading axes, last leading axis fastest
        let mut k = [0usize; D];
        loop {
            let mut row = 0;
            for a in 0..last {
                row = row * self.dims[a] + ax[a][k[a]];
            }
            let row = row * self.dims[last];
            for &(c0, c1) in &runs[..nruns] {
                f(&self.items[self.start[row + c0]..self.start[row + c1]]);
            }
            let mut a = last;
            loop {
                if a == 0 {
                    return;
                }
                a -= 1;
                k[a] += 1;
                if k[a] < cnt[a] {
                    break;
                }
                k[a] = 0;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The candidates always include every particle within the radius (checked against a
    /// direct scan, open and periodic, on a jittered lattice), with every subdivision, and a
    /// finer subdivision visits fewer candidates.
    #[test]
    fn candidates_cover_the_radius() {
        let mut pts = Vec::new();
        for i in 0..17 {
            for j in 0..13 {
                let t = (i * 13 + j) as f64;
                pts.push([
                    i as f64 * 0.3 + 0.05 * (t * 1.7).sin(),
                    j as f64 * 0.3 + 0.05 * (t * 2.3).cos(),
                ]);
            }
        }
        let r = 0.71;
        for (period, sub) in [None, Some([17.0 * 0.3, 13.0 * 0.3])]
            .into_iter()
            .flat_map(|p| (1..=MAX_SUB).map(move |s| (p, s)))
        {
            let mut cl = CellList::default();
            cl.rebuild_subdivided(&pts, r, period, sub);
            let mut visited = 0;
            for p in &pts {
                cl.for_candidates(*p, |_| visited += 1);
            }
            if sub > 1 {
                let mut coarse = CellList::default();
                coarse.rebuild_subdivided(&pts, r, period, sub - 1);
                let mut before = 0;
                for p in &pts {
                    coarse.for_candidates(*p, |_| before += 1);
                }
                assert!(visited < before, "subdivision {sub}: {visited} ≥ {before}");
            }
            for (i, p) in pts.iter().enumerate() {
                let mut got = Vec::new();
                cl.for_candidates(*p, |j| got.push(j));
                for (j, q) in pts.iter().enumerate() {
                    let mut d = [q[0] - p[0], q[1] - p[1]];
                    if let Some(l) = period {
                        for a in 0..2 {
                            d[a] -= l[a] * (d[a] / l[a]).round();
                        }
                    }
                    if d[0].hypot(d[1]) < r {
                        assert!(got.contains(&j), "{i} misses {j} ({period:?}, {sub})");
                    }
                }
                let mut s = got.clone();
                s.sort();
                s.dedup();
                assert_eq!(s.len(), got.len(), "duplicates");
            }
        }
    }

    /// A rebuilt list (after a different, larger particle set and another radius) visits the
    /// same candidates in the same order as a fresh one.
    #[test]
    fn rebuild_matches_new() {
        let pts: Vec<[f64; 2]> = (0..300)
            .map(|k| {
                let t = k as f64;
                [(t * 0.37).sin() * 4.0, (t * 0.11).cos() * 3.0]
            })
            .collect();
        let few = &pts[..97];
        for period in [None, Some([8.0, 6.0])] {
            let mut cl = CellList::new(&pts, 0.4, period);
            cl.rebuild(few, 0.9, period);
            let fresh = CellList::new(few, 0.9, period);
            for p in few {
                let (mut a, mut b) = (Vec::new(), Vec::new());
                cl.for_candidates(*p, |j| a.push(j));
                fresh.for_candidates(*p, |j| b.push(j));
                assert_eq!(a, b);
            }
        }
    }
    /// The candidates come in the documented order: the 3^D cells around the query's cell,
    /// first axis slowest, offsets −1, 0, 1 (each distinct cell once), and in each cell its
    /// particles by increasing index. The expected sequence is built from the particles' own
    /// cell coordinates, floor((x − origin)/side), not from the list's buffers; open domains
    /// and periodic boxes with 2, 3 and 5 cells per axis, 2D and 3D.
    #[test]
    fn candidate_order_is_cell_by_cell() {
        fn check<const D: usize>(pts: &[[f64; D]], r: f64, period: Option<[f64; D]>) {
            let cl = CellList::new(pts, r, period);
            let coords = |p: [f64; D]| -> [i64; D] {
                let mut c = [0i64; D];
                for a in 0..D {
                    let x = p[a] - cl.origin[a];
                    c[a] = match period {
                        Some(l) => {
                            let x = x.rem_euclid(l[a]);
                            ((x / l[a] * cl.dims[a] as f64) as i64).min(cl.dims[a] as i64 - 1)
                        }
                        None => ((x / cl.size).floor() as i64).clamp(0, cl.dims[a] as i64 - 1),
                    };
                }
                c
            };
            for q in pts.iter().step_by(3) {
                let cq = coords(*q);
                // per axis the distinct neighbour coordinates in the order −1, 0, 1
                let per_axis: Vec<Vec<i64>> = (0..D)
                    .map(|a| {
                        let n = cl.dims[a] as i64;
                        let mut v: Vec<i64> = Vec::new();
                        for o in -1..=1 {
                            let c = cq[a] + o;
                            let c = if period.is_some() { c.rem_euclid(n) } else { c };
                            if (0..n).contains(&c) && !v.contains(&c) {
                                v.push(c);
                            }
                        }
                        v
                    })
                    .collect();
                let mut expected = Vec::new();
                let total: usize = per_axis.iter().map(Vec::len).product();
                for k in 0..total {
                    // k in mixed radix, last axis fastest
                    let mut cell = [0i64; D];
                    let mut rest = k;
                    for a in (0..D).rev() {
                        cell[a] = per_axis[a][rest % per_axis[a].len()];
                        rest /= per_axis[a].len();
                    }
                    expected.extend((0..pts.len()).filter(|&j| coords(pts[j]) == cell));
                }
                let mut got = Vec::new();
                cl.for_candidates(*q, |j| got.push(j));
                assert_eq!(got, expected, "{D}D, period {period:?}");
            }
        }
        let jitter = |t: f64| 0.04 * (t * 1.3).sin();
        let pts2: Vec<[f64; 2]> = (0..11 * 7)
            .map(|k| {
                let t = k as f64;
                [
                    (k % 11) as f64 * 0.5 + jitter(t),
                    (k / 11) as f64 * 0.5 + jitter(2.0 * t),
                ]
            })
            .collect();
        check(&pts2, 0.7, None);
        check(&pts2, 1.1, Some([5.5, 3.5]));
        check(&pts2, 1.6, Some([5.5, 3.5]));
        let pts3: Vec<[f64; 3]> = (0..5 * 4 * 6)
            .map(|k| {
                let t = k as f64;
                [
                    (k % 5) as f64 * 0.5 + jitter(t),
                    ((k / 5) % 4) as f64 * 0.5 + jitter(3.0 * t),
                    (k / 20) as f64 * 0.5 + jitter(5.0 * t),
                ]
            })
            .collect();
        check(&pts3, 0.6, None);
        check(&pts3, 0.9, Some([2.5, 2.0, 3.0]));
    }
}
