//! 2D closed-form dynamical matrices (derived in this project, independent of the numeric
//! engine) for uniformly, isotropically pre-stressed lattices. Lattice sums of the node-0 shape
//! function φ (units Δx = 1, V = cell area):
//! `S1(k) = Σ_R ∇φ(R) sin(k·R)` (vector), `S2(k) = Σ_R ∇∇φ(R) · 2 sin²(k·R/2)` (matrix),
//! `M1 = −Σ_R ∇φ(R) ⊗ R` (first moment; the corrected gradient symbol is M1⁻¹ S1).
//!
//! With s the pre-stress, ρ the current density and (λ', G') the incremental moduli of the
//! stress law (hydro: λ' = Kρ/ρ0, G' = 0; Jaumann: λ' = λ, G' = G; Truesdell: λ' = λ − s,
//! G' = G + s — for isotropic pre-stress), the derivations of `analysis/ERRATA.md` E1 carried
//! to 2D give (D = ω² matrix; divide by C/ρ0 for the normalised D of the engine):
//! ```text
//! classical (sph):  ρD = (λ' + G' + 2s) S1S1ᵀ + G'|S1|² I − 2s S2
//! nonlocal (sph):   ρD = (λ' + G') S1S1ᵀ + G'|S1|² I
//! local:            the nonlocal expression with S1 → M1⁻¹ S1
//! total-Lagrangian: ρ_ref D = (λ_T + G_T) S1S1ᵀ + (G_T + s)|S1|² I  (elastic, SVK tangent)
//!                   ρ_ref D = Kρ_ref/ρ0 S1S1ᵀ                         (hydro, P = −p cof F)
//! ```

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::error::Result;
use crate::forms::{FormKind, Material2D, ObjectiveRate};
use crate::kernel;
use crate::lattice::Lattice2D;
use crate::shape::ShapeFamily;
use crate::shape2d::{KernelParams2, eval2};

/// Lattice sums at one wave vector.
#[derive(Clone, Copy, Debug)]
pub struct Sums2 {
    /// S1(k).
    pub s1: [f64; 2],
    /// S2(k).
    pub s2: [[f64; 2]; 2],
    /// M1.
    pub m1: [[f64; 2]; 2],
}

/// ∇φ and ∇∇φ of the `sph` shape of node 0 (volume `vol`) at R.
fn sph_derivs(kp: KernelParams2, vol: f64, r: [f64; 2]) -> ([f64; 2], [[f64; 2]; 2]) {
    let d = r[0].hypot(r[1]);
    if d == 0.0 {
        let w2 = kernel::d2w(kp.kernel, 2, 0.0, kp.h);
        return ([0.0; 2], [[vol * w2, 0.0], [0.0, vol * w2]]);
    }
    let w1 = kernel::dw(kp.kernel, 2, d, kp.h);
    let w2 = kernel::d2w(kp.kernel, 2, d, kp.h);
    let n = [r[0] / d, r[1] / d];
    let mut h = [[0.0; 2]; 2];
    for a in 0..2 {
        for b in 0..2 {
            let id = if a == b { 1.0 } else { 0.0 };
            h[a][b] = vol * (w2 * n[a] * n[b] + w1 / d * (id - n[a] * n[b]));
        }
    }
    ([vol * w1 * n[0], vol * w1 * n[1]], h)
}

/// Lattice sums for `family` (S2 only for `sph`, zero otherwise).
pub fn sums(lat: &Lattice2D, family: ShapeFamily, kp: KernelParams2, k: [f64; 2]) -> Result<Sums2> {
    let r = kp.support();
    let vol = lat.area();
    let pts = lat.offsets_within(r + 1e-12);
    let mut s = Sums2 {
        s1: [0.0; 2],
        s2: [[0.0; 2]; 2],
        m1: [[0.0; 2]; 2],
    };
    let mut out = Vec::new();
    for &(_, rr) in &pts {
        let (g, h) = if family == ShapeFamily::Sph {
            sph_derivs(kp, vol, rr)
        } else {
            // shape of node 0 at x = R: nodes within the support of R
            let nodes: Vec<([f64; 2], f64)> = lat
                .offsets_within(2.0 * r + 2.0)
                .into_iter()
                .map(|(_, p)| [p[0] - rr[0], p[1] - rr[1]])
                .filter(|d| d[0].hypot(d[1]) < r)
                .map(|d| (d, vol))
                .collect();
            eval2(family, kp, &nodes, rr, &mut out)?;
            let i0 = nodes
                .iter()
                .position(|(d, _)| (d[0] + rr[0]).abs() < 1e-12 && (d[1] + rr[1]).abs() < 1e-12);
            (i0.map(|i| out[i].1).unwrap_or([0.0; 2]), [[0.0; 2]; 2])
        };
        let t = k[0] * rr[0] + k[1] * rr[1];
        let (sn, hv) = (t.sin(), (0.5 * t).sin());
        for a in 0..2 {
            s.s1[a] += g[a] * sn;
            for b in 0..2 {
                s.s2[a][b] += h[a][b] * 2.0 * hv * hv;
                s.m1[a][b] -= g[a] * rr[b];
            }
        }
    }
    Ok(s)
}

fn outer(a: [f64; 2], b: [f64; 2]) -> [[f64; 2]; 2] {
    [[a[0] * b[0], a[0] * b[1]], [a[1] * b[0], a[1] * b[1]]]
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
pub fn rho_d(
    form: FormKind,
    mat: &Material2D,
    s: f64,
    rho_ratio: f64,
    sm: &Sums2,
) -> Option<[[f64; 2]; 2]> {
    let (lp, gp) = incremental(mat, s, rho_ratio);
    let s1 = sm.s1;
    let n2 = s1[0] * s1[0] + s1[1] * s1[1];
    let ss = outer(s1, s1);
    let id = |a: usize, b: usize| if a == b { 1.0 } else { 0.0 };
    let mut d = [[0.0; 2]; 2];
    match form {
        FormKind::Classical => {
            for a in 0..2 {
                for b in 0..2 {
                    d[a][b] =
                        (lp + gp + 2.0 * s) * ss[a][b] + gp * n2 * id(a, b) - 2.0 * s * sm.s2[a][b];
                }
            }
        }
        FormKind::Nonlocal | FormKind::Local => {
            let v = if form == FormKind::Local {
                let m = sm.m1;
                let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
                [
                    (m[1][1] * s1[0] - m[0][1] * s1[1]) / det,
                    (m[0][0] * s1[1] - m[1][0] * s1[0]) / det,
                ]
            } else {
                s1
            };
            let vv = outer(v, v);
            let v2 = v[0] * v[0] + v[1] * v[1];
            for a in 0..2 {
                for b in 0..2 {
                    d[a][b] = (lp + gp) * vv[a][b] + gp * v2 * id(a, b);
                }
            }
        }
        FormKind::TotalLagrangian => match *mat {
            Material2D::Hydro { bulk } => {
                for a in 0..2 {
                    for b in 0..2 {
                        d[a][b] = bulk * rho_ratio * ss[a][b];
                    }
                }
            }
            Material2D::NeoHookean { lambda, shear } => {
                // linearises to Hooke's law about the unstressed state (s = 0)
                for a in 0..2 {
                    for b in 0..2 {
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
                for a in 0..2 {
                    for b in 0..2 {
                        d[a][b] = (lt + gt) * ss[a][b] + (gt + s) * n2 * id(a, b);
                    }
                }
            }
        },
        _ => return None,
    }
    Some(d)
}
