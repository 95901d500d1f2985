//! Closed-form dynamical matrices in D ∈ {2, 3} dimensions (derived in this project,
//! independent of the numeric engine) for uniformly, isotropically pre-stressed lattices.
//! Lattice sums of the node-0 shape function φ (units Δx = 1, V = volume per particle, the
//! cell area in 2D):
//! `S1(k) = Σ_R ∇φ(R) sin(k·R)` (vector), `S2(k) = Σ_R ∇∇φ(R) · 2 sin²(k·R/2)` (matrix),
//! `M1 = −Σ_R ∇φ(R) ⊗ R` (first moment; the corrected gradient symbol is M1⁻¹ S1).
//!
//! With s the pre-stress, ρ the current density and (λ', G') the incremental moduli of the
//! stress law (hydro: λ' = Kρ/ρ0, G' = 0; Jaumann: λ' = λ, G' = G; Truesdell: λ' = λ − s,
//! G' = G + s — for isotropic pre-stress), the derivations of `analysis/ERRATA.md` E1 carried
//! to D dimensions give (D = ω² matrix; divide by C/ρ0 for the normalised D of the engine):
//! ```text
//! classical (sph):  ρD = (λ' + G' + 2s) S1S1ᵀ + G'|S1|² I − 2s S2
//! nonlocal (sph):   ρD = (λ' + G') S1S1ᵀ + G'|S1|² I
//! local:            the nonlocal expression with S1 → M1⁻¹ S1
//! total-Lagrangian: ρ_ref D = (λ_T + G_T) S1S1ᵀ + (G_T + s)|S1|² I  (elastic, SVK tangent)
//!                   ρ_ref D = Kρ_ref/ρ0 S1S1ᵀ                         (hydro, P = −p cof F)
//! ```
//!
//! **The derivation is dimension-agnostic** (checked for this generalisation, and against the
//! engine on sc, bcc and fcc lattices in `tests/vonneumann3d.rs`): every step is an index
//! contraction that holds for any D. The incremental moduli: for σ = sI the Truesdell terms
//! Lσ + σLᵀ − tr(L)σ = 2s d − s tr(d) I and the Jaumann terms Wσ − σW = 0 in any D, and
//! continuity gives the hydro λ' = Kρ/ρ0; the stress increment λ' tr(δL) I + 2G' sym δL
//! contracted with the gradient symbol gives (λ' + G') S1S1ᵀ + G'|S1|² I; the density and
//! kernel-variation terms of the sum form (E1) involve only S1 and ∇∇φ; for total-Lagrangian
//! hydro, δ(cof F) = tr(δF) I − δFᵀ at F = I in every dimension, so the pressure terms ∓s cancel
//! and only −p'(J) = Kρ_ref/ρ0 remains. Only the lattice sums depend on D.

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::error::Result;
use crate::forms::{FormKind, Material2D, ObjectiveRate};
use crate::kernel;
use crate::lattice::{Lattice, det};
use crate::shape::{KernelParams, ShapeFamily, eval_d};

/// Lattice sums at one wave vector.
#[derive(Clone, Copy, Debug)]
pub struct Sums<const D: usize> {
    /// S1(k).
    pub s1: [f64; D],
    /// S2(k).
    pub s2: [[f64; D]; D],
    /// M1.
    pub m1: [[f64; D]; D],
}

/// The 2D lattice sums.
pub type Sums2 = Sums<2>;
/// The 3D lattice sums.
pub type Sums3 = Sums<3>;

/// |r| (2D: `hypot`, as this module always computed it, so that 2D sums are unchanged).
fn len<const D: usize>(r: &[f64; D]) -> f64 {
    if D == 2 {
        r[0].hypot(r[1])
    } else {
        r.iter().map(|x| x * x).sum::<f64>().sqrt()
    }
}

/// ∇φ and ∇∇φ of the `sph` shape of node 0 (volume `vol`) at R.
fn sph_derivs<const D: usize>(
    kp: KernelParams,
    vol: f64,
    r: [f64; D],
) -> ([f64; D], [[f64; D]; D]) {
    let d = len(&r);
    let mut h = [[0.0; D]; D];
    if d == 0.0 {
        let w2 = kernel::d2w(kp.kernel, D, 0.0, kp.h);
        for a in 0..D {
            h[a][a] = vol * w2;
        }
        return ([0.0; D], h);
    }
    let w1 = kernel::dw(kp.kernel, D, d, kp.h);
    let w2 = kernel::d2w(kp.kernel, D, d, kp.h);
    let n = r.map(|c| c / d);
    for a in 0..D {
        for b in 0..D {
            let id = if a == b { 1.0 } else { 0.0 };
            h[a][b] = vol * (w2 * n[a] * n[b] + w1 / d * (id - n[a] * n[b]));
        }
    }
    (n.map(|c| vol * w1 * c), h)
}

/// Lattice sums for `family` (S2 only for `sph`, zero otherwise).
pub fn sums<const D: usize>(
    lat: &Lattice<D>,
    family: ShapeFamily,
    kp: KernelParams,
    k: [f64; D],
) -> Result<Sums<D>> {
    let r = kp.support();
    let vol = lat.area();
    let pts = lat.offsets_within(r + 1e-12);
    let mut s = Sums {
        s1: [0.0; D],
        s2: [[0.0; D]; D],
        m1: [[0.0; D]; D],
    };
    let mut out = Vec::new();
    for &(_, rr) in &pts {
        let (g, h) = if family == ShapeFamily::Sph {
            sph_derivs(kp, vol, rr)
        } else {
            // shape of node 0 at x = R: nodes within the support of R
            let nodes: Vec<([f64; D], f64)> = lat
                .offsets_within(2.0 * r + 2.0)
                .into_iter()
                .map(|(_, p)| {
                    let mut d = p;
                    for a in 0..D {
                        d[a] -= rr[a];
                    }
                    d
                })
                .filter(|d| len(d) < r)
                .map(|d| (d, vol))
                .collect();
            let kp1 = KernelParams {
                kernel: kp.kernel,
                h: kp.h,
            };
            eval_d(family, kp1, &nodes, rr[0], &mut out)?;
            let i0 = nodes
                .iter()
                .position(|(d, _)| (0..D).all(|a| (d[a] + rr[a]).abs() < 1e-12));
            (i0.map(|i| out[i].1).unwrap_or([0.0; D]), [[0.0; D]; D])
        };
        let mut t = k[0] * rr[0];
        for a in 1..D {
            t += k[a] * rr[a];
        }
        let (sn, hv) = (t.sin(), (0.5 * t).sin());
        for a in 0..D {
            s.s1[a] += g[a] * sn;
            for b in 0..D {
                s.s2[a][b] += h[a][b] * 2.0 * hv * hv;
                s.m1[a][b] -= g[a] * rr[b];
            }
        }
    }
    Ok(s)
}

fn outer<const D: usize>(a: [f64; D], b: [f64; D]) -> [[f64; D]; D] {
    let mut m = [[0.0; D]; D];
    for i in 0..D {
        for j in 0..D {
            m[i][j] = a[i] * b[j];
        }
    }
    m
}

/// |v|² summed in index order.
fn norm2<const D: usize>(v: [f64; D]) -> f64 {
    let mut n = v[0] * v[0];
    for a in 1..D {
        n += v[a] * v[a];
    }
    n
}

/// M⁻¹ v by Cramer's rule (2D: the explicit 2 × 2 inverse).
fn solve<const D: usize>(m: &[[f64; D]; D], v: [f64; D]) -> [f64; D] {
    let dm = det(m);
    let mut x = [0.0; D];
    for c in 0..D {
        let mut mc = *m;
        for a in 0..D {
            mc[a][c] = v[a];
        }
        x[c] = det(&mc) / dm;
    }
    x
}

fn incremental(mat: &Material2D, s: f64, rho_over_rho0: f64) -> (f64, f64) {
    match *mat {
        Material2D::Hydro { bulk } => (bulk * rho_over_rho0, 0.0),
        Material2D::NeoHookean { lambda, shear } => (lambda, shear),
        Material2D::Elastic {
            lambda,
            shear,
            rate: ObjectiveRate::Jaumann,
        } => (lambda, shear),
        Material2D::Elastic {
            lambda,
            shear,
            rate: ObjectiveRate::Truesdell,
        } => (lambda - s, shear + s),
    }
}

/// ρ·D(k) for `form` from lattice sums `sm` (sph sums for classical/nonlocal, the form's own
/// shape for total-Lagrangian), pre-stress `s`, density ratio ρ/ρ0.
pub fn rho_d<const D: usize>(
    form: FormKind,
    mat: &Material2D,
    s: f64,
    rho_ratio: f64,
    sm: &Sums<D>,
) -> Option<[[f64; D]; D]> {
    let (lp, gp) = incremental(mat, s, rho_ratio);
    let s1 = sm.s1;
    let n2 = norm2(s1);
    let ss = outer(s1, s1);
    let id = |a: usize, b: usize| if a == b { 1.0 } else { 0.0 };
    let mut d = [[0.0; D]; D];
    match form {
        FormKind::Classical => {
            for a in 0..D {
                for b in 0..D {
                    d[a][b] =
                        (lp + gp + 2.0 * s) * ss[a][b] + gp * n2 * id(a, b) - 2.0 * s * sm.s2[a][b];
                }
            }
        }
        FormKind::Nonlocal | FormKind::Local => {
            let v = if form == FormKind::Local {
                solve(&sm.m1, s1)
            } else {
                s1
            };
            let vv = outer(v, v);
            let v2 = norm2(v);
            for a in 0..D {
                for b in 0..D {
                    d[a][b] = (lp + gp) * vv[a][b] + gp * v2 * id(a, b);
                }
            }
        }
        FormKind::TotalLagrangian => match *mat {
            Material2D::Hydro { bulk } => {
                for a in 0..D {
                    for b in 0..D {
                        d[a][b] = bulk * rho_ratio * ss[a][b];
                    }
                }
            }
            Material2D::NeoHookean { lambda, shear } => {
                // linearises to Hooke's law about the unstressed state (s = 0)
                for a in 0..D {
                    for b in 0..D {
                        d[a][b] = (lambda + shear) * ss[a][b] + shear * n2 * id(a, b);
                    }
                }
            }
            Material2D::Elastic {
                lambda,
                shear,
                rate,
            } => {
                let (lt, gt) = if rate == ObjectiveRate::Truesdell {
                    (lambda, shear)
                } else {
                    (lambda + s, shear - s)
                };
                for a in 0..D {
                    for b in 0..D {
                        d[a][b] = (lt + gt) * ss[a][b] + (gt + s) * n2 * id(a, b);
                    }
                }
            }
        },
        _ => return None,
    }
    Some(d)
}
