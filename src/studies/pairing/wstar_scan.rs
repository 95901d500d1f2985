//! The sign scan of [`sign_criterion_with`] with a fraction of its evaluations and the same
//! result to the last bit ([`sign_criterion_fast`]; the kernel guide asks it for eleven kernels in
//! three dimensions).
//!
//! The scan samples w_i = W*(k_i)/W*(0) at k_i = iΔk and decides three things from the samples:
//! the first index of the smallest, the first sample below −[`NEGATIVE_TOL`] and the last
//! non-negative one before it; golden section and bisection then refine them with evaluations
//! of their own (`wstar::refine`). Each sample is the quadrature of
//! [`radial_integral`](crate::vonneumann::transform::radial_integral), whose rule depends on k
//! only through its panel layout ([`panel_layout`]): over a run of samples with one
//! layout the computed W* is one finite sum F(k) = Σᵢ cᵢ φ_D(k qᵢ) with qᵢ < ζ, an entire
//! function of exponential type ≤ ζ (|φ_D(z)| ≤ e^{|Im z|} for cos, J₀ and j₀). Its Chebyshev
//! interpolant of degree n on the run's interval (half-length ℓ) is within
//! T = 4Mρ^{−n}/(ρ − 1) of it for every ρ > 1 (Trefethen, *Approximation Theory and
//! Approximation Practice*, Thm 8.2), M = S e^{ζℓ(ρ − 1/ρ)/2} the bound of |F|/W*(0) on the
//! Bernstein ellipse, S = Σ|cᵢ|·(panel half-width)/W*(0) ([`RadialRule::abs_sum`]); n is the
//! smallest degree with T ≤ uS (u = 2⁻⁵³). Adding the rounding of a sample (γ_N S for a sum of
//! N products, a few ulp per φ_D), its amplification through the interpolant (Lebesgue constant
//! Λ ≤ (2/π) ln(n + 1) + 1), the rounding of the barycentric formula and of the nodes gives a
//! bound ε with |w̃_i − w_i| ≤ ε for every proxy value w̃_i (`bound`, twice the sum). A
//! decision the bound cannot settle is settled by evaluating the sample itself:
//! - the minimum: every i with w̃_i − ε_i ≤ w̃_p + ε_p (p the proxy's smallest) is evaluated; the
//!   others are larger than w_p;
//! - the first negative sample: in order, evaluated where w̃_i < −[`NEGATIVE_TOL`] + ε_i;
//! - the last non-negative sample before it: backwards, evaluated where |w̃_i| ≤ ε_i.
//!
//! Runs of fewer than 2(n + 1) samples are evaluated in full. Every evaluation — samples,
//! Chebyshev nodes, refinement — uses the rule of its layout with the kernel factors computed
//! once per layout ([`RadialRule`]): the numbers of [`Transform::at`], bit for bit.
//! `tests/it/kernel_guide.rs` checks the result against [`sign_criterion_with`] for every
//! kernel and dimension at the guide's step, and the proxy against every sample.

use super::wstar::{
    Decisions, NEGATIVE_TOL, Transform, WStarSign, refine, scan_grid, sign_criterion_with,
};
use crate::kernel::Kernel;
use crate::vonneumann::transform::{RadialRule, panel_layout};
use std::collections::HashMap;
use std::f64::consts::PI;

/// The unit roundoff 2⁻⁵³.
const U: f64 = f64::EPSILON / 2.0;
/// Largest proxy degree tried; a run needing more is evaluated in full.
const MAX_DEGREE: usize = 512;

/// [`sign_criterion_with`]`(kernel, dim, k_step)`, the same result to the last bit from a
/// Chebyshev proxy of the scan and exact evaluations where the proxy cannot decide (module docs).
pub fn sign_criterion_fast(kernel: &'static dyn Kernel, dim: usize, k_step: f64) -> WStarSign {
    match dim.clamp(1, 3) {
        1 => scan::<1>(kernel, k_step),
        2 => scan::<2>(kernel, k_step),
        _ => scan::<3>(kernel, k_step),
    }
}

/// The proxy values w̃_i of the scan and their bounds ε_i (`None` if one is not finite).
pub fn proxy_scan(kernel: &'static dyn Kernel, dim: usize, k_step: f64) -> Option<Proxy> {
    let ks = scan_grid(k_step);
    match dim.clamp(1, 3) {
        1 => proxy(&mut Exact::<1>::new(kernel), &ks),
        2 => proxy(&mut Exact::<2>::new(kernel), &ks),
        _ => proxy(&mut Exact::<3>::new(kernel), &ks),
    }
}

/// Proxy values and their bounds on the scan grid.
#[derive(Clone, Debug)]
pub struct Proxy {
    /// w̃_i.
    pub values: Vec<f64>,
    /// ε_i ≥ |w̃_i − w_i| (0 where w̃_i is the sample itself).
    pub bounds: Vec<f64>,
}

fn scan<const D: usize>(kernel: &'static dyn Kernel, k_step: f64) -> WStarSign {
    let ks = scan_grid(k_step);
    let mut ex = Exact::<D>::new(kernel);
    let Some(p) = proxy(&mut ex, &ks) else {
        return sign_criterion_with(kernel, D, k_step);
    };
    let d = decide(&mut ex, &ks, &p);
    refine(kernel, &ks, d, |k| ex.at(k))
}

/// W*(k)/W*(0) as [`Transform::at`] computes it, from the rule of k's layout (cached per
/// layout), memoised per k.
struct Exact<const D: usize> {
    t: Transform,
    rules: HashMap<Vec<usize>, RadialRule<D>>,
    memo: HashMap<u64, f64>,
}

impl<const D: usize> Exact<D> {
    fn new(kernel: &'static dyn Kernel) -> Self {
        Self {
            t: Transform::new(kernel, D),
            rules: HashMap::new(),
            memo: HashMap::new(),
        }
    }

    /// The rule of `layout` ([`Transform::raw`]'s integrand).
    fn rule(&mut self, layout: &[usize]) -> &RadialRule<D> {
        if !self.rules.contains_key(layout) {
            let (kern, d) = (self.t.kernel, self.t.dim);
            let g = move |q: f64| kern.f(d, q);
            let rule = RadialRule::new(&g, kern.zeta(), layout);
            self.rules.insert(layout.to_vec(), rule);
        }
        &self.rules[layout]
    }

    fn at(&mut self, k: f64) -> f64 {
        if let Some(&v) = self.memo.get(&k.to_bits()) {
            return v;
        }
        let layout = panel_layout(self.t.kernel.zeta(), k);
        let norm = self.t.norm;
        let v = self.rule(&layout).eval(k) / norm;
        self.memo.insert(k.to_bits(), v);
        v
    }
}

/// The proxy over the scan grid `ks`: run by run of one layout.
fn proxy<const D: usize>(ex: &mut Exact<D>, ks: &[f64]) -> Option<Proxy> {
    let zeta = ex.t.kernel.zeta();
    let layouts: Vec<Vec<usize>> = ks.iter().map(|&k| panel_layout(zeta, k)).collect();
    let mut p = Proxy {
        values: vec![0.0; ks.len()],
        bounds: vec![0.0; ks.len()],
    };
    let mut i0 = 0;
    while i0 < ks.len() {
        let mut i1 = i0;
        while i1 + 1 < ks.len() && layouts[i1 + 1] == layouts[i0] {
            i1 += 1;
        }
        let norm = ex.t.norm;
        let rule = ex.rule(&layouts[i0]);
        run(
            rule,
            norm,
            &ks[i0..=i1],
            &mut p.values[i0..=i1],
            &mut p.bounds[i0..=i1],
        )?;
        i0 = i1 + 1;
    }
    Some(p)
}

/// The proxy of one run `ks` (one layout, rule `rule`, W*(0) = `norm`) into `w` and `eps`.
fn run<const D: usize>(
    rule: &RadialRule<D>,
    norm: f64,
    ks: &[f64],
    w: &mut [f64],
    eps: &mut [f64],
) -> Option<()> {
    let (a, b) = (ks[0], ks[ks.len() - 1]);
    let ell = 0.5 * (b - a);
    let s = rule.abs_sum() / norm.abs();
    let (n, trunc) = degree(rule.max_node() * ell, s);
    if ks.len() <= 2 * (n + 1) || !(trunc.is_finite() && s.is_finite()) {
        for (wi, &k) in w.iter_mut().zip(ks) {
            *wi = rule.eval(k) / norm;
        }
        eps.fill(0.0);
        return Some(());
    }
    // Chebyshev points of the second kind, x_0 = b … x_n = a
    let mid = 0.5 * (a + b);
    let x: Vec<f64> = (0..=n)
        .map(|j| match j {
            0 => b,
            _ if j == n => a,
            _ => mid + ell * (PI * j as f64 / n as f64).cos(),
        })
        .collect();
    let v: Vec<f64> = x.iter().map(|&k| rule.eval(k) / norm).collect();
    let e = bound(rule, s, n, trunc, &v, a.abs().max(b.abs()));
    for ((wi, ei), &k) in w.iter_mut().zip(eps.iter_mut()).zip(ks) {
        *wi = barycentric(&x, &v, k);
        *ei = e;
        if !(wi.is_finite() && ei.is_finite()) {
            return None;
        }
    }
    Some(())
}

/// The smallest degree n ≥ 2 with T(n) = min_ρ 4 S e^{τℓ(ρ − 1/ρ)/2} ρ^{−n}/(ρ − 1) ≤ uS
/// (`tau_ell` = τℓ), and T(n); ([`MAX_DEGREE`], ∞) if none up to it.
fn degree(tau_ell: f64, s: f64) -> (usize, f64) {
    if s == 0.0 {
        return (2, 0.0);
    }
    let target = (U * s).ln();
    for n in 2..=MAX_DEGREE {
        // ln T over a geometric grid of ρ ∈ [1.05, ~2e4]
        let ln_t = (0..100)
            .map(|j| 1.05 * 1.1f64.powi(j))
            .map(|rho| {
                (4.0 * s).ln() + 0.5 * tau_ell * (rho - 1.0 / rho)
                    - n as f64 * rho.ln()
                    - (rho - 1.0).ln()
            })
            .fold(f64::INFINITY, f64::min);
        if ln_t <= target {
            return (n, ln_t.exp());
        }
    }
    (MAX_DEGREE, f64::INFINITY)
}

/// ε of a run (module docs): twice T + (Λ + 1)·e_q + the barycentric and node rounding, with
/// e_q = S(γ_N + 9u) the rounding of one value of the rule (N ≤ 2·nodes products and additions,
/// ≤ 4 ulp per φ_D and the product, the division by W*(0)), Λ the Lebesgue constant of n + 1
/// Chebyshev points, 6(n + 1)uΛ max|v| the barycentric formula (Higham 2004) and
/// 4u·|k|max·τS(Λ + 1) the nodes' own rounding (|F'| ≤ τS).
fn bound<const D: usize>(
    rule: &RadialRule<D>,
    s: f64,
    n: usize,
    trunc: f64,
    v: &[f64],
    kmax: f64,
) -> f64 {
    let terms = 2.0 * rule.len() as f64;
    let gamma = terms * U / (1.0 - terms * U);
    let e_q = s * (gamma + 9.0 * U);
    let lebesgue = 2.0 / PI * ((n + 1) as f64).ln() + 1.0;
    let vmax = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let bary = 6.0 * (n + 1) as f64 * U * lebesgue * vmax;
    let nodes = 4.0 * U * kmax * rule.max_node() * s * (lebesgue + 1.0);
    2.0 * (trunc + (lebesgue + 1.0) * e_q + bary + nodes)
}

/// The barycentric interpolant (second form, Chebyshev points of the second kind: weights
/// (−1)^j, halved at both ends) through (x_j, v_j) at k.
fn barycentric(x: &[f64], v: &[f64], k: f64) -> f64 {
    let n = x.len() - 1;
    let (mut num, mut den) = (0.0, 0.0);
    for (j, (&xj, &vj)) in x.iter().zip(v).enumerate() {
        if k == xj {
            return vj;
        }
        let mut wj = if j % 2 == 0 { 1.0 } else { -1.0 };
        if j == 0 || j == n {
            wj *= 0.5;
        }
        let c = wj / (k - xj);
        num += c * vj;
        den += c;
    }
    num / den
}

/// The scan's decisions from the proxy, evaluating the samples it cannot settle (module docs).
fn decide<const D: usize>(ex: &mut Exact<D>, ks: &[f64], p: &Proxy) -> Decisions {
    let (w, eps) = (&p.values, &p.bounds);
    // the minimum: every sample that may be the smallest
    let ip = (0..w.len())
        .min_by(|&a, &b| w[a].total_cmp(&w[b]))
        .unwrap_or(0);
    let upper = w[ip] + eps[ip];
    let mut best: Option<(usize, f64)> = None;
    for i in 0..w.len() {
        if w[i] - eps[i] <= upper {
            let v = ex.at(ks[i]);
            if best.is_none_or(|(_, bv)| v.total_cmp(&bv).is_lt()) {
                best = Some((i, v));
            }
        }
    }
    let (imin, wmin) = best.unwrap_or((0, ex.at(ks[0])));
    // the first sample below −NEGATIVE_TOL
    let first_i =
        (0..w.len()).find(|&i| w[i] < -NEGATIVE_TOL + eps[i] && ex.at(ks[i]) < -NEGATIVE_TOL);
    let first = first_i.map(|i| {
        // the last non-negative sample before it
        let j = (0..i)
            .rev()
            .find(|&j| {
                if w[j] - eps[j] >= 0.0 {
                    true
                } else if w[j] + eps[j] < 0.0 {
                    false
                } else {
                    ex.at(ks[j]) >= 0.0
                }
            })
            .unwrap_or(0);
        (j, ex.at(ks[j + 1]) < 0.0)
    });
    Decisions { imin, wmin, first }
}
