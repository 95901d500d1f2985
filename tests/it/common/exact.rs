//! Exact rational arithmetic for an independent derivation of MLS shape-function values and
//! derivatives on lattice nodes (issue 9). Nothing here calls the crate: the EFG quartic weight,
//! the linear-basis MLS formula φ_J = w_J (m2 − m1 d_J)/(m0 m2 − m1²) ([B00] eq 36–38 with the
//! origin at x) and their Taylor expansions about x = 0 are written out again with fractions, so
//! the values are exact (no rounding at all) and independent of the dual-number code under test.

use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A reduced fraction num/den (den > 0). Overflow panics (checked arithmetic), never wraps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Q {
    pub num: i128,
    pub den: i128,
}

fn gcd(a: i128, b: i128) -> i128 {
    let (mut a, mut b) = (a.abs(), b.abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.max(1)
}

impl Q {
    pub fn new(num: i128, den: i128) -> Q {
        assert!(den != 0, "zero denominator");
        let s = if den < 0 { -1 } else { 1 };
        let g = gcd(num, den);
        Q {
            num: s * num / g,
            den: s * den / g,
        }
    }
    pub fn int(n: i128) -> Q {
        Q::new(n, 1)
    }
    pub fn zero() -> Q {
        Q::int(0)
    }
    pub fn to_f64(self) -> f64 {
        // exact enough: both parts are far below 2^53 in every use here, or the quotient is
        // correctly rounded by the division of two exactly represented values
        self.num as f64 / self.den as f64
    }
}

impl Add for Q {
    type Output = Q;
    fn add(self, o: Q) -> Q {
        let g = gcd(self.den, o.den);
        let a = self.num.checked_mul(o.den / g).expect("overflow");
        let b = o.num.checked_mul(self.den / g).expect("overflow");
        Q::new(
            a.checked_add(b).expect("overflow"),
            self.den.checked_mul(o.den / g).expect("overflow"),
        )
    }
}
impl Neg for Q {
    type Output = Q;
    fn neg(self) -> Q {
        Q::new(-self.num, self.den)
    }
}
impl Sub for Q {
    type Output = Q;
    fn sub(self, o: Q) -> Q {
        self + (-o)
    }
}
impl Mul for Q {
    type Output = Q;
    fn mul(self, o: Q) -> Q {
        let g1 = gcd(self.num, o.den);
        let g2 = gcd(o.num, self.den);
        Q::new(
            (self.num / g1).checked_mul(o.num / g2).expect("overflow"),
            (self.den / g2).checked_mul(o.den / g1).expect("overflow"),
        )
    }
}
impl Div for Q {
    type Output = Q;
    // division is multiplication by the reciprocal
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, o: Q) -> Q {
        assert!(o.num != 0, "division by zero");
        self * Q::new(o.den, o.num)
    }
}
impl PartialOrd for Q {
    fn partial_cmp(&self, o: &Q) -> Option<Ordering> {
        Some((self.num * o.den).cmp(&(o.num * self.den)))
    }
}

/// A Taylor polynomial c0 + c1 x + c2 x² truncated after x² (enough for values, first and
/// second derivatives at x = 0).
#[derive(Clone, Copy, Debug)]
pub struct T([Q; 3]);

impl T {
    pub fn cst(c: Q) -> T {
        T([c, Q::zero(), Q::zero()])
    }
    pub fn new(c0: Q, c1: Q, c2: Q) -> T {
        T([c0, c1, c2])
    }
    /// (value, first derivative, second derivative) at x = 0.
    pub fn derivs(self) -> [Q; 3] {
        [self.0[0], self.0[1], self.0[2] * Q::int(2)]
    }
    fn recip(self) -> T {
        let b = self.0;
        let c0 = Q::int(1) / b[0];
        let c1 = -(b[1] * c0) / b[0];
        let c2 = -(b[1] * c1 + b[2] * c0) / b[0];
        T([c0, c1, c2])
    }
}
impl Add for T {
    type Output = T;
    fn add(self, o: T) -> T {
        T([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
}
impl Sub for T {
    type Output = T;
    fn sub(self, o: T) -> T {
        T([self.0[0] - o.0[0], self.0[1] - o.0[1], self.0[2] - o.0[2]])
    }
}
impl Mul for T {
    type Output = T;
    fn mul(self, o: T) -> T {
        let (a, b) = (self.0, o.0);
        T([
            a[0] * b[0],
            a[0] * b[1] + a[1] * b[0],
            a[0] * b[2] + a[1] * b[1] + a[2] * b[0],
        ])
    }
}
impl Div for T {
    type Output = T;
    // division is multiplication by the reciprocal series
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, o: T) -> T {
        self * o.recip()
    }
}

/// The EFG quartic spline weight w(q) = 1 − 6q² + 8q³ − 3q⁴ ([B00] §4.1.2), as polynomial
/// coefficients in q (the normalisation cancels in MLS).
const QUARTIC: [i128; 5] = [1, 0, -6, 8, -3];

/// The weight of the node at integer position `j` seen from x (near 0) with support radius
/// `r`, as a Taylor polynomial in x: w(|j − x|/r). For j ≠ 0, |j − x| = |j| − sign(j) x is a
/// polynomial; for j = 0, w(|x|/r) = 1 − 6x²/r² + 8|x|³/r³ − …, whose |x|³ term does not reach
/// the second derivative. `drop_own_curvature` replaces the own node's 6x²/r² by 0 — the
/// defect of issue 9 (∂W'(|d|)/∂x taken as 0 at d = 0), reproduced here on purpose to show
/// what it did.
fn weight(j: i128, r: Q, drop_own_curvature: bool) -> T {
    if j == 0 {
        let c2 = if drop_own_curvature {
            Q::zero()
        } else {
            Q::int(-6) / (r * r)
        };
        return T::new(Q::int(1), Q::zero(), c2);
    }
    let s = if j > 0 { 1 } else { -1 };
    // q(x) = (|j| − s x)/r
    let q = T::new(Q::int(j.abs()) / r, Q::int(-s) / r, Q::zero());
    let mut out = T::cst(Q::zero());
    let mut p = T::cst(Q::int(1));
    for &c in &QUARTIC {
        out = out + p * T::cst(Q::int(c));
        p = p * q;
    }
    out
}

/// Exact lattice values of the MLS (linear basis, EFG quartic weight, support radius `r` in
/// units of Δx, r not an integer) shape function φ of the node at 0 on the unit lattice, at the
/// nodes x = j: `(j, [φ(j), φ'(j), φ''(j)])` for |j| < r. By translation invariance
/// φ_0(j) = φ_{−j}(0), so all of them follow from one expansion about x = 0.
pub fn mls_quartic_lattice(r: Q, drop_own_curvature: bool) -> Vec<(i128, [Q; 3])> {
    assert!(
        r.den != 1,
        "an integer support puts nodes on the support edge"
    );
    let jmax = r.num / r.den;
    let js: Vec<i128> = (-jmax..=jmax).collect();
    let ws: Vec<T> = js
        .iter()
        .map(|&j| weight(j, r, drop_own_curvature))
        .collect();
    // relative positions d_J = j − x
    let ds: Vec<T> = js
        .iter()
        .map(|&j| T::new(Q::int(j), Q::int(-1), Q::zero()))
        .collect();
    let zero = T::cst(Q::zero());
    let (mut m0, mut m1, mut m2) = (zero, zero, zero);
    for (w, d) in ws.iter().zip(&ds) {
        m0 = m0 + *w;
        m1 = m1 + *w * *d;
        m2 = m2 + *w * *d * *d;
    }
    let det = m0 * m2 - m1 * m1;
    let mut out: Vec<(i128, [Q; 3])> = js
        .iter()
        .zip(ws.iter().zip(&ds))
        .map(|(&j, (w, d))| (-j, (*w * (m2 - m1 * *d) / det).derivs()))
        .collect();
    out.sort_by_key(|e| e.0);
    out
}
