//! The largest growth rate over the Brillouin zone, not only over a k-grid: a compass search
//! (pattern search along ± each axis, the step halved when no neighbour is better) from the
//! best points of the grid. The growth rate is smooth near an isolated maximum, so the value
//! found is exact to O(curvature · step²) once the step has shrunk to [`MIN_STEP`] of the
//! grid spacing; where two branches cross at the maximum (a kink), the search still climbs to
//! it, since it compares values only.

use crate::error::Result;

/// Smallest step, relative to the starting step (the grid spacing): 2⁻²⁰ ≈ 1e-6, so the
/// value is exact to ~1e-12 relative at a smooth maximum (error ∝ step²), far below the 1e-6
/// that reports need.
pub const MIN_STEP: f64 = 1.0 / (1u64 << 20) as f64;

/// Evaluations allowed per start: 20 halvings with 2D evaluations each and room for a walk
/// of a few hundred steps.
const MAX_EVALS_PER_START: usize = 4000;

/// How many of the grid's best points the search starts from (at most one per basin, and one
/// per set of symmetric copies of a maximum).
pub const STARTS: usize = 8;

/// The maximum of `f` near `start` (value `f_start`) by compass search with the first step
/// `step`: the point and the value. `f` must be finite; a non-finite value is never a move.
pub fn climb<const D: usize>(
    f: &impl Fn([f64; D]) -> Result<f64>,
    start: [f64; D],
    f_start: f64,
    step: f64,
) -> Result<([f64; D], f64)> {
    let (mut x, mut fx, mut s) = (start, f_start, step);
    let mut evals = 0;
    while s > MIN_STEP * step && evals < MAX_EVALS_PER_START {
        let mut best: Option<([f64; D], f64)> = None;
        for a in 0..D {
            for sign in [-1.0, 1.0] {
                let mut y = x;
                y[a] += sign * s;
                let fy = f(y)?;
                evals += 1;
                // a move must gain more than rounding (a few ulps): at a maximum on a grid
                // or symmetry point the search then stays there
                let floor = best.map_or(fx, |b| b.1);
                if fy.is_finite() && fy > floor + 4.0 * f64::EPSILON * floor.abs() {
                    best = Some((y, fy));
                }
            }
        }
        match best {
            Some((y, fy)) => (x, fx) = (y, fy),
            None => s *= 0.5,
        }
    }
    Ok((x, fx))
}

/// The maximum of `f` over the points of `grid` (values `values`) refined by [`climb`] from
/// the [`STARTS`] best grid points (one per basin) with the first step `step` (the grid
/// spacing): the point and the value, never below the grid's maximum. `None` when `grid` is
/// empty.
pub fn refine_grid_max<const D: usize>(
    f: &(impl Fn([f64; D]) -> Result<f64> + Sync),
    grid: &[[f64; D]],
    values: &[f64],
    step: f64,
) -> Result<Option<([f64; D], f64)>> {
    use rayon::prelude::*;
    let mut order: Vec<usize> = (0..grid.len()).filter(|&i| values[i].is_finite()).collect();
    order.sort_by(|&a, &b| values[b].total_cmp(&values[a]));
    // one start per basin: not next to a start already taken (within 1.5 grid spacings, where
    // the search from that start will look), and not a symmetric copy of one (equal value to
    // rounding)
    let mut starts: Vec<usize> = Vec::with_capacity(STARTS);
    for i in order {
        if starts.len() == STARTS {
            break;
        }
        let v = values[i];
        let near = |j: usize| {
            let d2: f64 = (0..D).map(|a| (grid[i][a] - grid[j][a]).powi(2)).sum();
            d2 < (1.5 * step).powi(2)
        };
        if starts
            .iter()
            .all(|&j| !near(j) && (values[j] - v).abs() > 1e-12 * v.abs().max(1e-300))
        {
            starts.push(i);
        }
    }
    let found: Vec<([f64; D], f64)> = starts
        .par_iter()
        .map(|&i| climb(f, grid[i], values[i], step))
        .collect::<Result<_>>()?;
    // the first of equal maxima (starts are in decreasing grid value): deterministic
    Ok(found
        .into_iter()
        .fold(None, |best: Option<([f64; D], f64)>, c| match best {
            Some(b) if b.1 >= c.1 => Some(b),
            _ => Some(c),
        }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth peak off the grid and off the axes, next to a lower one: the search finds the
    /// higher peak's exact value from a coarse grid (analytic maximum 2 at (0.3137, −0.1))
    #[test]
    fn finds_an_off_grid_peak() {
        let f = |k: [f64; 2]| -> Result<f64> {
            let a = (k[0] - 0.3137).powi(2) + 2.0 * (k[1] + 0.1).powi(2);
            let b = (k[0] + 0.5).powi(2) + (k[1] - 0.5).powi(2);
            // the larger of two peaks (as the growth rate is the largest over branches)
            Ok((2.0 * (-a).exp()).max(1.5 * (-4.0 * b).exp()))
        };
        let n = 5;
        let grid: Vec<[f64; 2]> = (0..n * n)
            .map(|i| [(i % n) as f64 * 0.5 - 1.0, (i / n) as f64 * 0.5 - 1.0])
            .collect();
        let values: Vec<f64> = grid.iter().map(|&k| f(k).unwrap()).collect();
        let (k, v) = refine_grid_max(&f, &grid, &values, 0.5).unwrap().unwrap();
        assert!((v - 2.0).abs() < 1e-12, "{v}");
        assert!(
            (k[0] - 0.3137).abs() < 1e-5 && (k[1] + 0.1).abs() < 1e-5,
            "{k:?}"
        );
    }
}
