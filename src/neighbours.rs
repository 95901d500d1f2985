//! Cell-list neighbour search in 2D: O(N) construction and queries for particles within a
//! radius, for open domains and rectangular periodic boxes. (Parallelogram periodic patches,
//! used only by the von Neumann engine on hexagonal lattices, fall back to a direct scan.)

/// A uniform grid of cells of side ≥ the search radius.
///
/// [`CellList::rebuild`] refills an existing list in place: once its buffers have grown to the
/// particle and cell counts, a rebuild does not allocate (the solver's time loop relies on it).
#[derive(Clone, Debug, Default)]
pub struct CellList {
    origin: [f64; 2],
    size: f64,
    dims: [usize; 2],
    /// Periodic extents (rectangular box) or None.
    period: Option<[f64; 2]>,
    start: Vec<usize>,
    items: Vec<usize>,
    /// Cell of each particle (construction buffer, kept for reuse).
    cell: Vec<usize>,
    /// Fill pointers (construction buffer, kept for reuse).
    fill: Vec<usize>,
}

impl CellList {
    /// Builds the list for `pts` with cell side ≥ `radius`. `period`: rectangular periodic box
    /// [Lx, Ly] with the particles' coordinates anywhere (they are wrapped into the box).
    pub fn new(pts: &[[f64; 2]], radius: f64, period: Option<[f64; 2]>) -> Self {
        let mut c = Self::default();
        c.rebuild(pts, radius, period);
        c
    }

    /// Rebuilds the list for `pts` in place, reusing its buffers (same result as
    /// [`CellList::new`]). O(N + number of cells).
    pub fn rebuild(&mut self, pts: &[[f64; 2]], radius: f64, period: Option<[f64; 2]>) {
        let (origin, ext) = match period {
            Some(l) => ([0.0, 0.0], l),
            None => {
                let mut lo = [f64::INFINITY; 2];
                let mut hi = [f64::NEG_INFINITY; 2];
                for p in pts {
                    for a in 0..2 {
                        lo[a] = lo[a].min(p[a]);
                        hi[a] = hi[a].max(p[a]);
                    }
                }
                if pts.is_empty() {
                    lo = [0.0; 2];
                    hi = [0.0; 2];
                }
                (lo, [hi[0] - lo[0], hi[1] - lo[1]])
            }
        };
        let size = radius.max(1e-300);
        let dims = [
            ((ext[0] / size).floor() as usize).max(1),
            ((ext[1] / size).floor() as usize).max(1),
        ];
        // periodic: cells must be at least `radius` wide, so use floor; open: one more cell
        let dims = if period.is_some() {
            dims
        } else {
            [dims[0] + 1, dims[1] + 1]
        };
        let cell_of = |p: &[f64; 2]| -> usize {
            let mut c = [0usize; 2];
            for a in 0..2 {
                let mut x = p[a] - origin[a];
                if let Some(l) = period {
                    x = x.rem_euclid(l[a]);
                    c[a] = ((x / l[a] * dims[a] as f64) as usize).min(dims[a] - 1);
                } else {
                    c[a] = ((x / size) as usize).min(dims[a] - 1);
                }
            }
            c[0] * dims[1] + c[1]
        };
        let ncell = dims[0] * dims[1];
        let count = &mut self.start;
        count.clear();
        count.resize(ncell + 1, 0);
        self.cell.clear();
        self.cell.extend(pts.iter().map(cell_of));
        for &c in &self.cell {
            count[c + 1] += 1;
        }
        for i in 0..ncell {
            count[i + 1] += count[i];
        }
        self.fill.clear();
        self.fill.extend_from_slice(count);
        self.items.clear();
        self.items.resize(pts.len(), 0);
        for (i, &c) in self.cell.iter().enumerate() {
            self.items[self.fill[c]] = i;
            self.fill[c] += 1;
        }
        self.origin = origin;
        self.size = size;
        self.dims = dims;
        self.period = period;
    }

    /// Calls `f(j)` for every particle j in the 3×3 block of cells around `p` (a superset of
    /// those within the radius; callers test the distance).
    pub fn for_candidates(&self, p: [f64; 2], mut f: impl FnMut(usize)) {
        let mut c = [0i64; 2];
        for a in 0..2 {
            let x = p[a] - self.origin[a];
            c[a] = match self.period {
                Some(l) => {
                    let xw = x.rem_euclid(l[a]);
                    ((xw / l[a] * self.dims[a] as f64) as i64).min(self.dims[a] as i64 - 1)
                }
                None => ((x / self.size).floor() as i64).clamp(0, self.dims[a] as i64 - 1),
            };
        }
        let mut seen = [usize::MAX; 9];
        let mut ns = 0;
        for di in -1..=1 {
            for dj in -1..=1 {
                let (mut ci, mut cj) = (c[0] + di, c[1] + dj);
                if self.period.is_some() {
                    ci = ci.rem_euclid(self.dims[0] as i64);
                    cj = cj.rem_euclid(self.dims[1] as i64);
                } else if ci < 0 || cj < 0 || ci >= self.dims[0] as i64 || cj >= self.dims[1] as i64
                {
                    continue;
                }
                let cell = ci as usize * self.dims[1] + cj as usize;
                // small periodic boxes (fewer than 3 cells per side) revisit cells: skip repeats
                if seen[..ns].contains(&cell) {
                    continue;
                }
                seen[ns] = cell;
                ns += 1;
                for &j in &self.items[self.start[cell]..self.start[cell + 1]] {
                    f(j);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The candidates always include every particle within the radius (checked against a
    /// direct scan, open and periodic, on a jittered lattice).
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
        for period in [None, Some([17.0 * 0.3, 13.0 * 0.3])] {
            let cl = CellList::new(&pts, r, period);
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
                        assert!(got.contains(&j), "{i} misses {j} ({period:?})");
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
}
