//! Closed forms derived in this project (not printed in the papers) for the SPH forms whose
//! linearisation the papers simplify: dynamical matrices of uniformly, isotropically
//! pre-stressed lattices in D ∈ {1, 2, 3} dimensions, one definition for every D (the dimension
//! is the const parameter of [`Sums`], [`sums`] and [`rho_d`]). They are written in lattice sums
//! of the uniform-lattice shape function and are independent of the numeric engine (no rate
//! function is called); the 1D derivations are in `analysis/ERRATA.md` (items E1–E3).
//!
//! Lattice sums of the node-0 shape function φ over the lattice offsets R ([`Lattice`]; in 1D
//! the unit chain [`Lattice::chain`], R = j), units Δx = 1, V = volume per particle (1 on the
//! chain, the cell area in 2D):
//! `S1(k) = Σ_R ∇φ(R) sin(k·R)` (vector), `S2(k) = Σ_R ∇∇φ(R) · 2 sin²(k·R/2)` (matrix),
//! `M1 = −Σ_R ∇φ(R) ⊗ R` (first moment, the identity for a linearly consistent gradient; the
//! corrected gradient symbol is M1⁻¹ S1). In 1D these are the scalars
//! `S1(κ) = Σ_j φ'(j) sin κj`, `S2(κ) = Σ_j φ''(j)·2 sin²(κj/2)`, `M1 = −Σ_j j φ'(j)`.
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
//! engine on the chain in `tests/it/vonneumann.rs`, on square and hexagonal lattices in
//! `tests/it/vonneumann2d.rs` and on sc, bcc and fcc lattices in `tests/it/vonneumann3d.rs`): every
//! step is an index contraction that holds for any D. The incremental moduli: for σ = sI the
//! Truesdell terms Lσ + σLᵀ − tr(L)σ = 2s d − s tr(d) I and the Jaumann terms Wσ − σW = 0 in any
//! D, and continuity gives the hydro λ' = Kρ/ρ0; the stress increment λ' tr(δL) I + 2G' sym δL
//! contracted with the gradient symbol gives (λ' + G') S1S1ᵀ + G'|S1|² I; the density and
//! kernel-variation terms of the sum form (E1) involve only S1 and ∇∇φ; for total-Lagrangian
//! hydro, δ(cof F) = tr(δF) I − δFᵀ at F = I in every dimension, so the pressure terms ∓s cancel
//! and only −p'(J) = Kρ_ref/ρ0 remains. Only the lattice sums depend on D.
//!
//! # The 1D scalar forms (D = 1)
//!
//! The 1D forms use the 1D stress law σ̇ = (C + σ) ∂v/∂x (the Truesdell rate with P-wave
//! modulus λ + 2G = C, as the 1D model; normalised Δx = V = ρ = C = 1, σ̄ = σ/C, C̃ = 1 + σ̄),
//! i.e. [`MATERIAL_1D`] (in 1D only λ' + 2G' = C̃ enters). [`omega2_1d`] is ω² = ρD/(ρC) of
//! [`rho_d`] with D = 1 on the chain sums of the `sph` shape (rigidly moving with its node, as
//! the derivation assumes, ERRATA E3), and gives the 1D relations of ERRATA E1 and E2:
//! ```text
//! classical:        ω² = C̃ S1² − 2σ̄ (S2 − S1²)  (twice the stress term of [B00] eq 74, E1)
//! nonlocal:         ω² = C̃ S1²                   (no stress–kernel term at all, E2)
//! local:            ω² = C̃ (S1/M1)²              (corrected derivatives G_j = φ'(j)/M1)
//! total-Lagrangian: ω² = C̃ S1²                   ([B00] eq 82)
//! ```
//! `lnl` and `cll` ([`lnl`], [`cll`]) mix the forms with partition c and carry a second stress
//! (τ) and, for `cll`, a mixed continuity equation. Their closed forms were derived (and are
//! checked against the engine, `tests/it/vonneumann.rs`) in 1D only: the D-dimensional
//! linearisation of the τ and mixed-density terms has not been carried out here, so they are
//! functions of [`Sums<1>`] only, written on the D = 1 expressions of [`omega2_1d`].

// Small-tensor algebra (D × D, D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::error::Result;
use crate::forms::{FormKind, Material, ObjectiveRate};
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

/// The 1D lattice sums (scalars as 1-arrays).
pub type Sums1 = Sums<1>;
/// The 2D lattice sums.
pub type Sums2 = Sums<2>;
/// The 3D lattice sums.
pub type Sums3 = Sums<3>;

/// |r| (2D: `hypot`, as this module always computed it, so that 2D sums are unchanged; 1D:
/// |x| exactly).
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

/// One lattice offset of [`SphSums`]: integer coordinates m, position R = Σ mᵢaᵢ, ∇φ(R), ∇∇φ(R).
type SphTerm<const D: usize> = ([i64; D], [f64; D], [f64; D], [[f64; D]; D]);

/// The `sph` lattice sums of one lattice, kernel and h at many wave vectors: ∇φ and ∇∇φ at every
/// offset within the support computed once ([`sums`] evaluates the kernel at every k). The
/// sums are [`sums`]'s, bit for bit: the same products added in the same order.
#[derive(Clone, Debug)]
pub struct SphSums<const D: usize> {
    terms: Vec<SphTerm<D>>,
}

impl<const D: usize> SphSums<D> {
    /// The derivatives of the `sph` shape of node 0 at every offset of `lat` within the support.
    pub fn new(lat: &Lattice<D>, kp: KernelParams) -> Self {
        let vol = lat.area();
        let terms = lat
            .offsets_within(kp.support() + 1e-12)
            .into_iter()
            .map(|(m, rr)| {
                let (g, h) = sph_derivs(kp, vol, rr);
                (m, rr, g, h)
            })
            .collect();
        Self { terms }
    }

    /// Largest |mᵢ| of an offset (0 without offsets): how far a table of phases must reach.
    pub fn reach(&self) -> i64 {
        self.terms
            .iter()
            .flat_map(|t| t.0)
            .map(i64::abs)
            .max()
            .unwrap_or(0)
    }

    /// The sums at wave vector k ([`sums`] with `ShapeFamily::Sph`).
    pub fn at(&self, k: [f64; D]) -> Sums<D> {
        self.with_phases(|_, rr| {
            let mut t = k[0] * rr[0];
            for a in 1..D {
                t += k[a] * rr[a];
            }
            (t.sin(), (0.5 * t).sin())
        })
    }

    /// The sums with (sin θ, sin(θ/2)) of θ = k·R given by `phase(m, R)` (a table computed once
    /// for a grid of wave vectors, for instance).
    pub fn with_phases(&self, phase: impl Fn(&[i64; D], &[f64; D]) -> (f64, f64)) -> Sums<D> {
        let mut s = Sums {
            s1: [0.0; D],
            s2: [[0.0; D]; D],
            m1: [[0.0; D]; D],
        };
        for (m, rr, g, h) in &self.terms {
            let (sn, hv) = phase(m, rr);
            add_term(&mut s, g, h, rr, sn, hv);
        }
        s
    }
}

/// Adds one offset's terms to the sums (the one expression of [`sums`] and [`SphSums`]).
#[inline]
fn add_term<const D: usize>(
    s: &mut Sums<D>,
    g: &[f64; D],
    h: &[[f64; D]; D],
    rr: &[f64; D],
    sn: f64,
    hv: f64,
) {
    for a in 0..D {
        s.s1[a] += g[a] * sn;
        for b in 0..D {
            s.s2[a][b] += h[a][b] * 2.0 * hv * hv;
            s.m1[a][b] -= g[a] * rr[b];
        }
    }
}

/// Lattice sums of `lat` for `family` at wave vector k (S2 only for `sph`, zero otherwise);
/// in 1D `sums(&Lattice::chain(), family, kp, [κ])`. Many wave vectors of one `sph` lattice:
/// [`SphSums`].
pub fn sums<const D: usize>(
    lat: &Lattice<D>,
    family: ShapeFamily,
    kp: KernelParams,
    k: [f64; D],
) -> Result<Sums<D>> {
    if family == ShapeFamily::Sph {
        return Ok(SphSums::new(lat, kp).at(k));
    }
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
        let g = i0.map(|i| out[i].1).unwrap_or([0.0; D]);
        let mut t = k[0] * rr[0];
        for a in 1..D {
            t += k[a] * rr[a];
        }
        add_term(&mut s, &g, &[[0.0; D]; D], &rr, t.sin(), (0.5 * t).sin());
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

/// M⁻¹ v by Cramer's rule (1D: v/M; 2D: the explicit 2 × 2 inverse).
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

fn incremental(mat: &Material, s: f64, rho_over_rho0: f64) -> (f64, f64) {
    match *mat {
        Material::Hydro { bulk } => (bulk * rho_over_rho0, 0.0),
        Material::NeoHookean { lambda, shear } => (lambda, shear),
        Material::Elastic {
            lambda,
            shear,
            rate: ObjectiveRate::Jaumann,
        } => (lambda, shear),
        Material::Elastic {
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
    mat: &Material,
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
            Material::Hydro { bulk } => {
                for a in 0..D {
                    for b in 0..D {
                        d[a][b] = bulk * rho_ratio * ss[a][b];
                    }
                }
            }
            Material::NeoHookean { lambda, shear } => {
                // linearises to Hooke's law about the unstressed state (s = 0)
                for a in 0..D {
                    for b in 0..D {
                        d[a][b] = (lambda + shear) * ss[a][b] + shear * n2 * id(a, b);
                    }
                }
            }
            Material::Elastic {
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

/// The 1D stress law of the scalar forms, σ̇ = (C + σ) ∂v/∂x: Truesdell elastic with
/// C = λ + 2G = 1, written with G = 0, λ = C as the 1D model does
/// (`forms::ModelParams::nd_params`; in 1D only λ + 2G enters), so that λ' + 2G' = 1 + σ̄ = C̃
/// at pre-stress s = σ̄.
pub const MATERIAL_1D: Material = Material::Elastic {
    lambda: 1.0,
    shear: 0.0,
    rate: ObjectiveRate::Truesdell,
};

/// Normalised 1D ω² (Δx = 1, ρ = 1, C = 1) of `form` from the chain sums `s` (sph sums; `local`
/// uses M1⁻¹S1) at σ̄ = `sigma_bar`, partition `c` for `lnl` and `cll`: [`rho_d`] with D = 1 and
/// [`MATERIAL_1D`] for classical, nonlocal, local and total-Lagrangian, [`lnl`] and [`cll`] for
/// the mixed forms; `None` for a form without a derived closed form.
pub fn omega2_1d(form: FormKind, s: &Sums<1>, sigma_bar: f64, c: f64) -> Option<f64> {
    match form {
        FormKind::Lnl => Some(lnl(s, sigma_bar, c)),
        FormKind::Cll => Some(cll(s, sigma_bar, c)),
        _ => rho_d(form, &MATERIAL_1D, sigma_bar, 1.0, s).map(|d| d[0][0]),
    }
}

/// The D = 1 expression of [`rho_d`] for `form` (one of classical, nonlocal, local).
fn d1(form: FormKind, s: &Sums<1>, sigma_bar: f64) -> f64 {
    rho_d(form, &MATERIAL_1D, sigma_bar, 1.0, s).map_or(f64::NAN, |d| d[0][0])
}

/// `lnl` with partition c (1D only, see the module docs):
/// ω² = (1 − c) C̃ S1² + c C̃ (S1/M1)², the partition of the nonlocal and local ω².
pub fn lnl(s: &Sums<1>, sigma_bar: f64, c: f64) -> f64 {
    (1.0 - c) * d1(FormKind::Nonlocal, s, sigma_bar) + c * d1(FormKind::Local, s, sigma_bar)
}

/// `cll` with partition c (density from the mixed continuity equation, c_ρ = c; 1D only, see
/// the module docs): ω² = (1 − c)[C̃ S1² − 2σ̄ S2 + 2σ̄ ((1 − c) S1² + c S1²/M1)] + c C̃ (S1/M1)²,
/// i.e. (1 − c)[classical ω² + 2σ̄ c (S1²/M1 − S1²)] + c · local ω².
pub fn cll(s: &Sums<1>, sigma_bar: f64, c: f64) -> f64 {
    let (s1, m1) = (s.s1[0], s.m1[0][0]);
    let dens = c * (s1 * s1 / m1 - s1 * s1);
    (1.0 - c) * (d1(FormKind::Classical, s, sigma_bar) + 2.0 * sigma_bar * dens)
        + c * d1(FormKind::Local, s, sigma_bar)
}
