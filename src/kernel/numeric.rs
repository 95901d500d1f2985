//! Numerical helpers for the kernels without closed forms: Gauss–Legendre quadrature for the
//! normalisation σ_d and a bracketing root finder for the inflection point q*.
//!
//! Both are evaluated once per kernel and cached by the caller (`std::sync::OnceLock`).

use std::f64::consts::PI;

/// Number of Gauss–Legendre points per panel.
const GL_ORDER: usize = 20;
/// Number of equal panels on [0, ζ].
const GL_PANELS: usize = 64;
/// Number of equal intervals scanned for the first sign change before bisecting.
const ROOT_SCAN: usize = 1000;

/// Measure of the unit sphere S^(d−1): 2 (d = 1), 2π (d = 2), 4π (d = 3).
pub(super) fn unit_sphere(dim: usize) -> f64 {
    match super::dim_index(dim) {
        0 => 2.0,
        1 => 2.0 * PI,
        _ => 4.0 * PI,
    }
}

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    (p1, n as f64 * (x * p1 - p0) / (x * x - 1.0))
}

/// Gauss–Legendre nodes and weights on [−1, 1], by Newton iteration on P_n.
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            for _ in 0..100 {
                let (p, dp) = legendre(n, x);
                let dx = p / dp;
                x -= dx;
                if dx.abs() <= 4.0 * f64::EPSILON {
                    break;
                }
            }
            let (_, dp) = legendre(n, x);
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// σ_1, σ_2, σ_3 of a shape function `g` that is smooth on [0, ζ) and zero beyond:
/// σ_d = 1 / (|S^(d−1)| ∫_0^ζ q^(d−1) g(q) dq), by composite Gauss–Legendre quadrature
/// (64 panels of 20 points; the error is at rounding level for the smooth kernels it serves).
pub(super) fn sigma_by_quadrature(g: impl Fn(f64) -> f64, zeta: f64) -> [f64; 3] {
    let nodes = gauss_legendre(GL_ORDER);
    let width = zeta / GL_PANELS as f64;
    let mut moments = [0.0; 3];
    for panel in 0..GL_PANELS {
        let mid = (panel as f64 + 0.5) * width;
        for &(x, wt) in &nodes {
            let q = mid + 0.5 * width * x;
            let gq = wt * g(q);
            moments[0] += gq;
            moments[1] += gq * q;
            moments[2] += gq * q * q;
        }
    }
    [1, 2, 3].map(|d| 1.0 / (unit_sphere(d) * 0.5 * width * moments[d - 1]))
}

/// The first sign change of `g` in (a, b], located by a scan of 1000 intervals and then
/// bisected until the bracket cannot shrink further (full double precision).
/// Returns `b` if `g` keeps the sign of `g(a)` throughout.
pub(super) fn first_root(g: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let neg = g(a) < 0.0;
    let same_side = |v: f64| v != 0.0 && (v < 0.0) == neg;
    let mut lo = a;
    for i in 1..=ROOT_SCAN {
        let hi = a + (b - a) * i as f64 / ROOT_SCAN as f64;
        if same_side(g(hi)) {
            lo = hi;
            continue;
        }
        let mut hi = hi;
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if same_side(g(mid)) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        return if g(lo).abs() < g(hi).abs() { lo } else { hi };
    }
    b
}

/// The Gauss–Legendre rule of [`GL_ORDER`] points, computed once.
fn gl_nodes() -> &'static [(f64, f64)] {
    static NODES: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    NODES.get_or_init(|| gauss_legendre(GL_ORDER))
}

/// ∫_0^b g(q) dq, b ≥ 0, by Gauss–Legendre quadrature on 4 panels in each interval between
/// the multiples of ½ below b (and from the last one to b): the B-splines, whose pieces join at
/// multiples of ½, are then integrated piece by piece, exactly to rounding (m4 against its
/// closed form to 1e-13); every kernel's I(ζ) = 1 to 1e-9 (`tests/it/boundary_loads.rs`).
pub(super) fn integrate_by_halves(g: impl Fn(f64) -> f64, b: f64) -> f64 {
    let mut sum = 0.0;
    let mut a = 0.0;
    while a < b {
        let end = (a + 0.5).min(b);
        let width = (end - a) / 4.0;
        for panel in 0..4 {
            let mid = a + (panel as f64 + 0.5) * width;
            for &(x, wt) in gl_nodes() {
                sum += 0.5 * width * wt * g(mid + 0.5 * width * x);
            }
        }
        a = end;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_of_degree_2n_minus_1_exactly() {
        let nodes = gauss_legendre(GL_ORDER);
        let integral: f64 = nodes.iter().map(|&(x, w)| w * x.powi(38)).sum();
        assert!((integral - 2.0 / 39.0).abs() < 1e-15);
        let total: f64 = nodes.iter().map(|&(_, w)| w).sum();
        assert!((total - 2.0).abs() < 1e-14);
    }

    #[test]
    fn first_root_finds_the_smaller_of_two_roots() {
        let r = first_root(|x| (x - 0.3) * (x - 0.7), 0.0, 1.0);
        assert!((r - 0.3).abs() < 1e-15);
    }
}
