//! The Eulerian-kernel forms (classical, nonlocal, local, lnl, cll) and the total-Lagrangian
//! form in D ∈ {1, 2, 3} dimensions: one routine whose momentum and continuity terms are chosen
//! by the form, with the same definitions as in 1D:
//!
//! ```text
//! L_I = Σ_J (v_J − v_I) ⊗ ∇φ_J(x_I),   ρ̇_I = −ρ_I tr L_I   (mixed forms: (1−c) tr L^nl + c tr L^loc)
//! classical:  a_I = Σ_J (σ_I/ρ_I² + σ_J/ρ_J²) ρ_J · ∇φ_J(x_I)          [V21 eq 55]
//! difference: a_I = (1/ρ_I) Σ_J (σ_J − σ_I) · ∇φ_J(x_I)                [V21 eq 54] (local: corrected ∇φ)
//! lnl: (1 − c) a^diff(σ) + c a^loc(τ);  cll: (1 − c) a^classical(σ) + c a^loc(τ)
//! ```
//! plus −Σ_J m_J Π_IJ ∇_I W_IJ (Monaghan viscosity). Stress: hydro σ = −K(ρ/ρ0 − 1) I from the
//! density; elastic σ (and τ) are state with the hypo-elastic rate of [`Material`].
//!
//! Evaluation: neighbour stencils from a cell list, then per-particle sums, in parallel over
//! particles (rayon), with every buffer in a reusable [`RateWorkspace`]: a time loop that keeps
//! its workspace does not allocate. Accelerations and auxiliary rates can be asked for
//! separately ([`RateOut`]); each is the same function of the state either way.

// Small-tensor algebra (D × D, D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::kind::FormKind;
use super::model::Model;
use super::params::{
    ArtificialViscosity, DensityDiffusion, DiffusionForm, Material, ObjectiveRate,
};
use super::state::{AuxRates, RateOut, State, StateView, Tensor};
use super::workspace::{NbD, RateWorkspace, Shared, Stencils};
use crate::error::Result;
use crate::kernel;
use crate::scalar::Scalar;
use rayon::prelude::*;

/// σ·g.
#[inline]
fn dot<S: Scalar, const D: usize>(s: &Tensor<S, D>, g: [S; D]) -> [S; D] {
    let mut f = [S::zero(); D];
    for a in 0..D {
        let mut fa = s[a][0] * g[0];
        for b in 1..D {
            fa += s[a][b] * g[b];
        }
        f[a] = fa;
    }
    f
}

/// σ_I/ρ_I² (the upper triangle; the lower is not read), the particle's part of
/// [`sum_term`], computed once per particle.
#[inline]
fn over_rho2<S: Scalar, const D: usize>(si: &Tensor<S, D>, ri2: S) -> Tensor<S, D> {
    let mut t = [[S::zero(); D]; D];
    for p in 0..D {
        for q in p..D {
            t[p][q] = si[p][q] / ri2;
        }
    }
    t
}

/// (σ_I/ρ_I² + σ_J/ρ_J²) ρ_J · ∇φ_J, one term of the classical sum \[V21 eq 55\], with
/// `si_r` = σ_I/ρ_I² from [`over_rho2`] (the quotients as divisions: the Swegle runs amplify
/// a last-bit change of them to 1e-7).
#[inline]
fn sum_term<S: Scalar, const D: usize>(
    si_r: &Tensor<S, D>,
    sj: &Tensor<S, D>,
    rj: S,
    g: [S; D],
) -> [S; D] {
    let rj2 = rj * rj;
    let mut t = [[S::zero(); D]; D];
    // symmetric: the upper triangle, mirrored
    for p in 0..D {
        for q in p..D {
            t[p][q] = si_r[p][q] + sj[p][q] / rj2;
            t[q][p] = t[p][q];
        }
    }
    dot(&t, g).map(|f| f * rj)
}

/// (σ_J − σ_I) · ∇φ_J, one term of the difference form \[V21 eq 54\] (before the 1/ρ_I).
#[inline]
fn diff_term<S: Scalar, const D: usize>(si: &Tensor<S, D>, sj: &Tensor<S, D>, g: [S; D]) -> [S; D] {
    let mut t = [[S::zero(); D]; D];
    // symmetric: the upper triangle, mirrored
    for p in 0..D {
        for q in p..D {
            t[p][q] = sj[p][q] - si[p][q];
            t[q][p] = t[p][q];
        }
    }
    dot(&t, g)
}

/// (σ_I + σ_J) · V_J ∇_I W_IJ, one term of SPH-ENOG's pressure force (before the 1/ρ_I), with
/// `g` = V_J ∇_I W_IJ.
#[inline]
fn plus_term<S: Scalar, const D: usize>(si: &Tensor<S, D>, sj: &Tensor<S, D>, g: [S; D]) -> [S; D] {
    let mut t = [[S::zero(); D]; D];
    for p in 0..D {
        for q in p..D {
            t[p][q] = si[p][q] + sj[p][q];
            t[q][p] = t[p][q];
        }
    }
    dot(&t, g)
}

/// The bulk modulus of a stress that is a pressure of the density, σ = −K(ρ/ρ0 − 1) I: the
/// hydrodynamic material's K, and SPH-ENOG's K = λ + 2G/3 (its equation of state
/// p = c0²(ρ − ρ0) with c0² = K/ρ0, the three-dimensional bulk modulus in 2D too, as the
/// paper's); None for a form that integrates its stress.
fn pressure_bulk<const D: usize>(m: &Model<D>) -> Option<f64> {
    match (m.p.material, m.p.form) {
        (Material::Hydro { bulk }, _) => Some(bulk),
        (Material::Elastic { lambda, shear, .. }, FormKind::Enog) => {
            Some(lambda + 2.0 * shear / 3.0)
        }
        _ => None,
    }
}

/// SPH-ENOG's shear-acceleration rate of particle i \[Zhang et al. 2024\]:
/// ȧ^s_I = 2ζ (G/ρ_I) Σ_J (v_IJ · e_IJ)/r_IJ ∇_I W_IJ V_J, e_IJ = x_IJ/r_IJ, x_IJ = x_I − x_J;
/// with frozen neighbours its integral is the displacement Laplacian
/// ≈ (ζ/(D + 2)) (G/ρ) [∇²u + 2∇(∇·u)] (module tests).
fn enog_shear_rate<S: Scalar, const D: usize>(
    m: &Model<D>,
    z: StateView<'_, S, D>,
    ws: &RateWorkspace<S, D>,
    i: usize,
) -> [S; D] {
    let Material::Elastic { shear, .. } = m.p.material else {
        return [S::zero(); D];
    };
    let zeta = m.p.hourglass.unwrap_or(enog_default_zeta(D));
    let vol = &ws.vol;
    let mut sum = [S::zero(); D];
    ws.st.for_each::<false>(m, z.x, vol, i, |nb| {
        if nb.j == i {
            return;
        }
        // d = x_J − x_I = −x_IJ, so (v_IJ·e_IJ)/r_IJ = −(v_IJ·d)/r²
        let (mut vd, mut r2) = (S::zero(), S::zero());
        for c in 0..D {
            vd += (z.v[i][c] - z.v[nb.j][c]) * nb.d[c];
            r2 += nb.d[c] * nb.d[c];
        }
        let f = -vd / r2 * vol[nb.j];
        for c in 0..D {
            sum[c] += f * nb.gw[c];
        }
    });
    let scale = S::cst(2.0 * zeta * shear) / z.rho[i];
    sum.map(|c| c * scale)
}

/// SPH-ENOG's default ζ = 0.7D + 2.1 (SPHinXsys's `ShearAccelerationRelaxation`: 3.5 in 2D,
/// 4.2 in 3D).
pub fn enog_default_zeta(dim: usize) -> f64 {
    0.7 * dim as f64 + 2.1
}

#[inline]
fn add<S: Scalar, const D: usize>(a: &mut [S; D], f: [S; D]) {
    for c in 0..D {
        a[c] += f[c];
    }
}

/// Hypo-elastic stress rate for velocity gradient L: λ tr(d) I + 2G d plus the objective
/// terms; computed on the upper triangle and mirrored, so the rate is exactly symmetric.
pub(crate) fn stress_rate<S: Scalar, const D: usize>(
    mat: &Material,
    s: &Tensor<S, D>,
    l: &Tensor<S, D>,
) -> Tensor<S, D> {
    let mut r = [[S::zero(); D]; D];
    let Material::Elastic {
        lambda,
        shear,
        rate,
    } = *mat
    else {
        return r;
    };
    if D == 1 && rate == ObjectiveRate::Truesdell {
        // 1D: λ tr d + 2G d + Lσ + σL − tr(L)σ = (C + σ) ∂v/∂x with C = λ + 2G, the law of
        // \[B00\] eq 72, written as there
        r[0][0] = (s[0][0] + (lambda + 2.0 * shear)) * l[0][0];
        return r;
    }
    let mut tr = l[0][0];
    for a in 1..D {
        tr += l[a][a];
    }
    for a in 0..D {
        r[a][a] = tr * lambda + l[a][a] * (2.0 * shear);
        for b in a + 1..D {
            r[a][b] = (l[a][b] + l[b][a]) * 0.5 * (2.0 * shear);
        }
    }
    let sm = s;
    for a in 0..D {
        for b in a..D {
            let mut extra = S::zero();
            match rate {
                ObjectiveRate::Jaumann => {
                    let w = |p: usize, q: usize| {
                        if p == q {
                            S::zero()
                        } else {
                            (l[p][q] - l[q][p]) * 0.5
                        }
                    };
                    for c in 0..D {
                        extra += w(a, c) * sm[c][b] - sm[a][c] * w(c, b);
                    }
                }
                ObjectiveRate::Truesdell => {
                    for c in 0..D {
                        extra += l[a][c] * sm[c][b] + sm[a][c] * l[b][c];
                    }
                    extra -= tr * sm[a][b];
                }
            }
            r[a][b] += extra;
            r[b][a] = r[a][b];
        }
    }
    r
}

/// −m_J Π_IJ ∇_I W_IJ of one pair (Monaghan viscosity), `d` = x_J − x_I, `dv` = v_I − v_J,
/// ρ̄ the pair's mean density, `grad` = ∇_I W_IJ (computed when `None`); zero for a receding
/// pair when the viscosity acts on approaching pairs only.
#[inline(always)]
fn av_pair<S: Scalar, const D: usize>(
    m: &Model<D>,
    av: &ArtificialViscosity,
    d: [S; D],
    dv: [S; D],
    rho_bar: S,
    mass_j: f64,
    grad: Option<[S; D]>,
) -> [S; D] {
    let h = m.p.kp.h;
    // x_IJ = x_I − x_J = −d
    let mut vx = -(dv[0] * d[0]);
    let mut r2 = d[0] * d[0];
    for c in 1..D {
        vx -= dv[c] * d[c];
        r2 += d[c] * d[c];
    }
    let mut mu = vx * h / (r2 + 0.01 * h * h);
    if av.approaching_only {
        if S::TANGENT {
            if vx.re() >= 0.0 {
                return [S::zero(); D];
            }
        } else {
            // a receding pair: μ = 0, so Π = 0 and the pair adds ±0 (bitwise what returning
            // zero adds to a sum that starts at +0). A select, not a branch: whether a pair
            // approaches is a coin flip, and the mispredicted branch cost a quarter of a
            // solver step.
            mu *= S::cst(if vx.re() < 0.0 { 1.0 } else { 0.0 });
        }
    }
    let pi = (mu * (-av.alpha * av.sound_speed) + mu * mu * av.beta) / rho_bar;
    // ∇_I W(x_I − x_J) = −W'(r) d/r, differentiable through d = 0
    let grad = grad.unwrap_or_else(|| kernel::w_and_grad(m.p.kp.kernel, h, d).1);
    grad.map(|g| -(pi * g * mass_j))
}

/// Artificial-stress tensor R = −ε Σ_{λ>0} λ P_λ / ρ² of a stress (principal decomposition;
/// an isotropic tensile stress gives R = −ε σ/ρ², smooth for linearisation). D ≤ 2 (the model
/// refuses artificial stress in 3D).
fn art_tensor<S: Scalar, const D: usize>(s: &Tensor<S, D>, rho: S, eps: f64) -> Tensor<S, D> {
    let scale = S::cst(-eps) / (rho * rho);
    let mut r = [[S::zero(); D]; D];
    if D == 1 {
        if s[0][0].re() > 0.0 {
            r[0][0] = s[0][0] * scale;
        }
        return r;
    }
    if D != 2 {
        return r;
    }
    let (s0, s1, s2) = (s[0][0], s[1][1], s[0][1]);
    let mean = (s0 + s1) * 0.5;
    let dh = (s0 - s1) * 0.5;
    let rad2 = dh * dh + s2 * s2;
    if rad2.re() <= 1e-28 * mean.re().abs().max(f64::MIN_POSITIVE).powi(2) {
        // (numerically) isotropic
        if mean.re() > 0.0 {
            for a in 0..D {
                for b in 0..D {
                    r[a][b] = s[a][b] * scale;
                }
            }
        }
        return r;
    }
    let rad = rad2.sqrt();
    let (l1, l2) = (mean + rad, mean - rad);
    // P1 = (σ − λ2 I)/(λ1 − λ2), P2 = I − P1
    let p1 = [
        (s0 - l2) / (rad * 2.0),
        (s1 - l2) / (rad * 2.0),
        s2 / (rad * 2.0),
    ];
    let p2 = [S::cst(1.0) - p1[0], S::cst(1.0) - p1[1], -p1[2]];
    let mut v = [S::zero(); 3];
    for (l, p) in [(l1, p1), (l2, p2)] {
        if l.re() > 0.0 {
            for k in 0..3 {
                v[k] += l * p[k] * scale;
            }
        }
    }
    r[0][0] = v[0];
    r[1][1] = v[1];
    r[0][1] = v[2];
    r[1][0] = v[2];
    r
}

/// Antuono's renormalised density gradient ⟨∇ρ⟩_I = M_I⁻¹ Σ_J (ρ_J − ρ_I) ∇_I W_IJ V_J,
/// M_I = Σ_J ∇_I W_IJ ⊗ x_JI V_J (exact for a linear density field).
fn renormalised_density_gradient<S: Scalar, const D: usize>(
    m: &Model<D>,
    z: StateView<'_, S, D>,
    i: usize,
    st: &Stencils<S, D>,
    vol: &[S],
) -> [S; D] {
    let mut mm = [[S::zero(); D]; D];
    let mut g = [S::zero(); D];
    st.for_each::<false>(m, z.x, vol, i, |nb| {
        if nb.j == i {
            return;
        }
        let (gv, r2) = diffusion_pair(vol, &nb);
        if r2.re() == 0.0 {
            return;
        }
        let dr = z.rho[nb.j] - z.rho[i];
        for a in 0..D {
            g[a] += gv[a] * dr;
            for b in 0..D {
                mm[a][b] += gv[a] * nb.d[b];
            }
        }
    });
    // M⁻¹ g = cof(M)ᵀ g / det M
    let det = det_s(&mm);
    let cof = cof_s(&mm);
    let mut out = [S::zero(); D];
    for a in 0..D {
        for b in 0..D {
            out[a] += cof[b][a] * g[b];
        }
        out[a] = out[a] / det;
    }
    out
}

/// V_J ∇_I W_IJ and |x_JI|² of a neighbour, for the δ-SPH terms.
#[inline]
fn diffusion_pair<S: Scalar, const D: usize>(vol: &[S], nb: &NbD<S, D>) -> ([S; D], S) {
    let vj = vol[nb.j];
    let mut r2 = nb.d[0] * nb.d[0];
    for c in 1..D {
        r2 += nb.d[c] * nb.d[c];
    }
    (nb.gw.map(|gc| gc * vj), r2)
}

/// The accelerations of the Eulerian forms, one pass over each particle's neighbours: the
/// form's stress divergence, Monaghan's viscosity −Σ_J m_J Π_IJ ∇_I W_IJ and the artificial
/// stress Σ_J m_J (R_I + R_J) f_IJⁿ ∇_I W_IJ, each summed on its own and added in that order.
fn accelerations<S: Scalar, const D: usize>(
    m: &Model<D>,
    z: StateView<'_, S, D>,
    acc: &mut [[S; D]],
    ws: &mut RateWorkspace<S, D>,
    mixed: bool,
) {
    let form = m.p.form;
    let c = m.p.c_partition;
    ws.hydro.clear();
    if let Some(bulk) = pressure_bulk(m) {
        // per-particle buffers in parallel too: a serial loop here is a serial part of every
        // evaluation (Amdahl), on two threads a tenth of the step
        ws.hydro.par_extend(z.rho.par_iter().map(|&r| {
            let sg = (r / m.p.rho0 - 1.0) * (-bulk);
            let mut t = [[S::zero(); D]; D];
            for (a, row) in t.iter_mut().enumerate() {
                row[a] = sg;
            }
            t
        }));
    }
    let (sig, tau): (&[Tensor<S, D>], &[Tensor<S, D>]) = if pressure_bulk(m).is_some() {
        (&ws.hydro, &ws.hydro)
    } else {
        (z.sigma, if mixed { z.tau } else { z.sigma })
    };
    ws.art.clear();
    if let (Some(a), FormKind::Classical | FormKind::Cll) = (m.p.art_stress, form) {
        ws.art.par_extend(
            sig.par_iter()
                .zip(z.rho)
                .map(|(s, &r)| art_tensor(s, r, a.eps)),
        );
    }
    let (st, art, vol) = (&ws.st, &ws.art, &ws.vol);
    let sum_form = matches!(form, FormKind::Classical | FormKind::Cll);
    let diff_form = matches!(form, FormKind::Nonlocal | FormKind::Local | FormKind::Lnl);
    let enog = form == FormKind::Enog;
    let av = m.p.av;
    // per-particle accelerations in parallel (rayon)
    acc.par_iter_mut().enumerate().for_each(|(i, out_a)| {
        let (rho_i, si) = (z.rho[i], &sig[i]);
        let si_r = over_rho2(si, rho_i * rho_i);
        // a particle of the classical boundary layer takes the plus form [V21 §7.4]
        let layer = diff_form && m.classical_layer.get(i).copied().unwrap_or(false);
        let (mut fa, mut fav, mut far) = ([S::zero(); D], [S::zero(); D], [S::zero(); D]);
        st.for_each::<false>(m, z.x, vol, i, |nb| {
            let j = nb.j;
            if sum_form {
                add(&mut fa, sum_term(&si_r, &sig[j], z.rho[j], nb.g));
            } else if layer {
                // the classical kernel gradient V_J ∇_I W_IJ (the local form's stencil holds
                // the corrected one, which no more sees a free surface than the difference)
                let g = if form == FormKind::Local {
                    nb.gw.map(|c| c / z.rho[j] * m.mass[j])
                } else {
                    nb.g
                };
                add(&mut fa, sum_term(&si_r, &sig[j], z.rho[j], g));
            } else if diff_form {
                add(&mut fa, diff_term(si, &sig[j], nb.g));
            } else if enog {
                add(&mut fa, plus_term(si, &sig[j], nb.gw.map(|g| g * vol[j])));
            }
            if j == i {
                return;
            }
            if let Some(av) = &av {
                let mut dv = [S::zero(); D];
                for c in 0..D {
                    dv[c] = z.v[i][c] - z.v[j][c];
                }
                let rho_bar = (rho_i + z.rho[j]) * 0.5;
                add(
                    &mut fav,
                    av_pair(m, av, nb.d, dv, rho_bar, m.mass[j], Some(nb.gw)),
                );
            }
            if !art.is_empty() {
                let mut t = [[S::zero(); D]; D];
                // symmetric: the upper triangle, mirrored
                for p in 0..D {
                    for q in p..D {
                        t[p][q] = art[i][p][q] + art[j][p][q];
                        t[q][p] = t[p][q];
                    }
                }
                let f2 = dot(&t, nb.gw);
                let fnn = st.fnn[nb.p];
                for c in 0..D {
                    far[c] += f2[c] * fnn * m.mass[j];
                }
            }
        });
        let mut a = match form {
            FormKind::Classical => fa,
            FormKind::Nonlocal | FormKind::Local if layer => fa,
            FormKind::Nonlocal | FormKind::Local => fa.map(|x| x / rho_i),
            FormKind::Enog => {
                let mut a = fa.map(|x| x / rho_i);
                add(&mut a, z.shear_acc[i]);
                a
            }
            FormKind::Lnl | FormKind::Cll => {
                let p = if form == FormKind::Lnl && !layer {
                    fa.map(|x| x / rho_i)
                } else {
                    fa
                };
                let mut q = [S::zero(); D];
                if layer {
                    let ti_r = over_rho2(&tau[i], rho_i * rho_i);
                    st.for_each::<true>(m, z.x, vol, i, |nb| {
                        let g = nb.gw.map(|c| c / z.rho[nb.j] * m.mass[nb.j]);
                        add(&mut q, sum_term(&ti_r, &tau[nb.j], z.rho[nb.j], g));
                    });
                } else {
                    st.for_each::<true>(m, z.x, vol, i, |nb| {
                        add(&mut q, diff_term(&tau[i], &tau[nb.j], nb.g));
                    });
                    q = q.map(|x| x / rho_i);
                }
                let mut r = [S::zero(); D];
                for k in 0..D {
                    r[k] = p[k] * (1.0 - c) + q[k] * c;
                }
                r
            }
            _ => [S::zero(); D],
        };
        add(&mut a, fav);
        if !art.is_empty() {
            let w = if form == FormKind::Cll { 1.0 - c } else { 1.0 };
            for k in 0..D {
                a[k] += far[k] * w;
            }
        }
        *out_a = a;
    });
}

/// L_I = Σ_J (v_J − v_I) ⊗ ∇φ_J over stencil `B` of particle i, and with `diff` the δ-SPH
/// sum Σ_J ψ_IJ · ∇_I W_IJ V_J (without its factor δ h c0).
fn vel_grad_and_diffusion<S: Scalar, const D: usize, const B: bool>(
    m: &Model<D>,
    z: StateView<'_, S, D>,
    ws: &RateWorkspace<S, D>,
    i: usize,
    diff: bool,
) -> (Tensor<S, D>, S) {
    let (grad, vol) = (&ws.rho_grad, &ws.vol);
    let mut l = [[S::zero(); D]; D];
    let mut sum = S::zero();
    ws.st.for_each::<B>(m, z.x, vol, i, |nb| {
        for a in 0..D {
            let dv = z.v[nb.j][a] - z.v[i][a];
            for b in 0..D {
                l[a][b] += dv * nb.g[b];
            }
        }
        if !diff || nb.j == i {
            return;
        }
        let (gv, r2) = diffusion_pair(vol, &nb);
        if r2.re() == 0.0 {
            return;
        }
        // ψ_IJ = 2(ρ_J − ρ_I) x_JI/|x_JI|² [− (⟨∇ρ⟩_I + ⟨∇ρ⟩_J)]
        let f = (z.rho[nb.j] - z.rho[i]) * 2.0 / r2;
        for c in 0..D {
            let mut psi = nb.d[c] * f;
            if !grad.is_empty() {
                psi -= grad[i][c] + grad[nb.j][c];
            }
            sum += psi * gv[c];
        }
    });
    (l, sum)
}

/// The rate of an Eulerian form, into the requested parts of `out`.
pub(crate) fn rate<S: Scalar, const D: usize>(
    m: &Model<D>,
    z: StateView<'_, S, D>,
    out: RateOut<'_, S, D>,
    ws: &mut RateWorkspace<S, D>,
) -> Result<()> {
    let form = m.p.form;
    let mixed = matches!(form, FormKind::Lnl | FormKind::Cll);
    ws.build_stencils(m, z, mixed)?;
    let c = m.p.c_partition;
    if let Some(xo) = out.x {
        xo.copy_from_slice(z.v);
    }
    if let Some(acc) = out.v {
        accelerations(m, z, acc, ws, mixed);
    }
    if let Some(AuxRates {
        rho,
        sigma,
        tau,
        shear_acc,
        ..
    }) = out.aux
    {
        let n = z.x.len();
        ws.rho_grad.clear();
        if let Some(DensityDiffusion {
            form: DiffusionForm::Antuono,
            ..
        }) = m.p.diffusion
        {
            ws.rho_grad.resize(n, [S::zero(); D]);
            let (st, vol) = (&ws.st, &ws.vol);
            ws.rho_grad
                .par_iter_mut()
                .enumerate()
                .for_each(|(i, g)| *g = renormalised_density_gradient(m, z, i, st, vol));
        }
        let ws = &*ws;
        let diffusion = m.p.diffusion;
        let zero = [[S::zero(); D]; D];
        let (has_rho, has_sigma, has_tau) = (!rho.is_empty(), !sigma.is_empty(), !tau.is_empty());
        let has_shear = !shear_acc.is_empty() && form == FormKind::Enog;
        assert!(
            (!has_rho || rho.len() == n)
                && (!has_sigma || sigma.len() == n)
                && (!has_tau || tau.len() == n)
                && (!has_shear || shear_acc.len() == n),
            "auxiliary rate outputs: one entry per particle or none"
        );
        let (rho_o, sigma_o, tau_o, shear_o) = (
            Shared(rho.as_mut_ptr()),
            Shared(sigma.as_mut_ptr()),
            Shared(tau.as_mut_ptr()),
            Shared(shear_acc.as_mut_ptr()),
        );
        // per-particle auxiliary rates in parallel (rayon), written in place
        (0..n).into_par_iter().for_each(|i| {
            let (la, dsum) =
                vel_grad_and_diffusion::<S, D, false>(m, z, ws, i, diffusion.is_some());
            let lb = if mixed {
                vel_grad_and_diffusion::<S, D, true>(m, z, ws, i, false).0
            } else {
                la
            };
            let (mut tra, mut trb) = (la[0][0], lb[0][0]);
            for k in 1..D {
                tra += la[k][k];
                trb += lb[k][k];
            }
            let dd = match diffusion {
                Some(dd) => dsum * (dd.delta * m.p.kp.h * dd.sound_speed),
                None => S::zero(),
            };
            let rho_rate = -z.rho[i]
                * if mixed {
                    tra * (1.0 - c) + trb * c
                } else {
                    tra
                }
                + dd;
            let sig_rate = if z.sigma.is_empty() {
                zero
            } else {
                stress_rate(&m.p.material, &z.sigma[i], &la)
            };
            let tau_rate = if z.tau.is_empty() {
                zero
            } else {
                stress_rate(&m.p.material, &z.tau[i], &lb)
            };
            // SAFETY: index i is written by this iteration only, and is in bounds of every
            // non-empty output (checked above)
            unsafe {
                if has_rho {
                    rho_o.write(i, rho_rate);
                }
                if has_sigma {
                    sigma_o.write(i, sig_rate);
                }
                if has_tau {
                    tau_o.write(i, tau_rate);
                }
                if has_shear {
                    shear_o.write(i, enog_shear_rate(m, z, ws, i));
                }
            }
        });
    }
    Ok(())
}

/// det F of a D × D matrix of scalars, D ≤ 3.
fn det_s<S: Scalar, const D: usize>(f: &Tensor<S, D>) -> S {
    match D {
        1 => f[0][0],
        2 => f[0][0] * f[1][1] - f[0][1] * f[1][0],
        _ => {
            f[0][0] * (f[1][1] * f[2][2] - f[1][2] * f[2][1])
                - f[0][1] * (f[1][0] * f[2][2] - f[1][2] * f[2][0])
                + f[0][2] * (f[1][0] * f[2][1] - f[1][1] * f[2][0])
        }
    }
}

/// The cofactor matrix cof F = J F⁻ᵀ, D ≤ 3.
fn cof_s<S: Scalar, const D: usize>(f: &Tensor<S, D>) -> Tensor<S, D> {
    let mut c = [[S::zero(); D]; D];
    match D {
        1 => c[0][0] = S::cst(1.0),
        2 => {
            c[0][0] = f[1][1];
            c[0][1] = -f[1][0];
            c[1][0] = -f[0][1];
            c[1][1] = f[0][0];
        }
        _ => {
            for a in 0..3 {
                for b in 0..3 {
                    let (r0, r1) = ((a + 1) % 3, (a + 2) % 3);
                    let (c0, c1) = ((b + 1) % 3, (b + 2) % 3);
                    c[a][b] = f[r0][c0] * f[r1][c1] - f[r0][c1] * f[r1][c0];
                }
            }
        }
    }
    c
}

/// The first Piola–Kirchhoff stress of the compressible neo-Hookean law \[T eq 3.62–3.64\],
/// P = μ(F − F⁻ᵀ) + λ ln J F⁻ᵀ (F⁻ᵀ = cof F / J): the one definition the total-Lagrangian rate
/// and [`neo_hookean_cauchy`] use. In 2D the third stretch is 1 (plane strain).
pub(crate) fn neo_hookean_piola<S: Scalar, const D: usize>(
    f: &Tensor<S, D>,
    lambda: f64,
    shear: f64,
) -> Tensor<S, D> {
    let jac = det_s(f);
    let cof = cof_s(f);
    let lnj = jac.ln();
    let mut p = [[S::zero(); D]; D];
    for a in 0..D {
        for b in 0..D {
            let fit = cof[a][b] / jac;
            p[a][b] = (f[a][b] - fit) * shear + lnj * fit * lambda;
        }
    }
    p
}

/// The principal Cauchy stresses T = P Fᵀ / J of the neo-Hookean law ([`neo_hookean_piola`])
/// at the principal stretches `stretch` (F = diag(λ_a); in 2D plane strain, λ3 = 1), with Lamé
/// constants `lambda`, `shear` — \[T\] eq 5.5's T_aa, computed by the solver's own law.
pub fn neo_hookean_cauchy<const D: usize>(stretch: [f64; D], lambda: f64, shear: f64) -> [f64; D] {
    let mut f = [[0.0; D]; D];
    for a in 0..D {
        f[a][a] = stretch[a];
    }
    let p = neo_hookean_piola(&f, lambda, shear);
    let jac: f64 = stretch.iter().product();
    let mut t = [0.0; D];
    for a in 0..D {
        for b in 0..D {
            t[a] += p[a][b] * f[a][b];
        }
        t[a] /= jac;
    }
    t
}

/// The deformation gradient at master `st` of the total-Lagrangian rate ([`rate_tl`]):
/// F = I + Σ_K (u_K − ū) ⊗ ∇φ_K(X_J), ū = Σ_K φ_K u_K / Σ_K φ_K, from the displacements `u`.
pub(crate) fn tl_deformation_gradient<S: Scalar, const D: usize>(
    st: &[(usize, f64, [f64; D])],
    u: &[[S; D]],
) -> Tensor<S, D> {
    let sphi: f64 = st.iter().map(|e| e.1).sum();
    let mut ubar = [S::zero(); D];
    for &(k, phi, _) in st {
        for a in 0..D {
            ubar[a] += u[k][a] * phi;
        }
    }
    let ubar = ubar.map(|x| x / sphi);
    let mut f = [[S::zero(); D]; D];
    for (a, row) in f.iter_mut().enumerate() {
        row[a] = S::cst(1.0);
    }
    for &(k, _, gr) in st {
        for a in 0..D {
            let du = u[k][a] - ubar[a];
            for b in 0..D {
                f[a][b] += du * gr[b];
            }
        }
    }
    f
}

/// The first Piola–Kirchhoff stress P(F) at master `j` of the total-Lagrangian rate
/// ([`rate_tl`]; its material laws are listed there).
pub(crate) fn tl_piola<S: Scalar, const D: usize>(
    m: &Model<D>,
    j: usize,
    f: &Tensor<S, D>,
) -> Tensor<S, D> {
    let s0 = m.sigma0;
    match m.p.material {
        Material::Hydro { bulk } => {
            let jac = det_s(f);
            let rho_ref = m.mass[j] / m.vol_ref[j];
            let pr = ((S::cst(rho_ref) / jac) / m.p.rho0 - 1.0) * bulk;
            // P = −p cof F
            cof_s(f).map(|row| row.map(|c| -pr * c))
        }
        Material::NeoHookean { lambda, shear } => neo_hookean_piola(f, lambda, shear),
        Material::Elastic {
            lambda,
            shear,
            rate: ObjectiveRate::Truesdell,
        } if D == 1 => {
            // 1D: the Truesdell law σ̇ = (C + σ)Ḟ/F integrates exactly to
            // P = σ = (σ0 + C)F − C (\[B00\] eq 81's tangent C + σ0 at F = 1)
            let mut p = [[S::zero(); D]; D];
            p[0][0] = f[0][0] * (s0 + lambda + 2.0 * shear) - (lambda + 2.0 * shear);
            p
        }
        Material::Elastic {
            lambda,
            shear,
            rate,
        } => {
            let p0 = &m.prestress;
            let mut e = [[S::zero(); D]; D];
            for a in 0..D {
                for b in 0..D {
                    let mut s = S::zero();
                    for c in 0..D {
                        s += f[c][a] * f[c][b];
                    }
                    e[a][b] = (s - if a == b { 1.0 } else { 0.0 }) * 0.5;
                }
            }
            let mut tr = e[0][0];
            for a in 1..D {
                tr += e[a][a];
            }
            // S = σ0 + λ tr E I + 2G E, and for the Jaumann rate − (E σ0 + σ0 E) + tr E σ0:
            // the linearisation of Ṡ = J F⁻¹ σ^∇T F⁻ᵀ with the Truesdell rate of the Jaumann law,
            // σ^∇T = C:d − dσ − σd + tr(d)σ (isotropic σ0: λ + σ0 and G − σ0)
            let mut sm = [[S::zero(); D]; D];
            for a in 0..D {
                for b in 0..D {
                    let mut v = e[a][b] * (2.0 * shear) + p0[a][b];
                    if a == b {
                        v += tr * lambda;
                    }
                    if rate == ObjectiveRate::Jaumann {
                        v += tr * p0[a][b];
                        for c in 0..D {
                            v -= e[a][c] * p0[c][b] + e[c][b] * p0[a][c];
                        }
                    }
                    sm[a][b] = v;
                }
            }
            let mut p = [[S::zero(); D]; D];
            for a in 0..D {
                for b in 0..D {
                    for c in 0..D {
                        p[a][b] += f[a][c] * sm[c][b];
                    }
                }
            }
            p
        }
    }
}

/// The total-Lagrangian rate: F = I + Σ_K (u_K − ū) ⊗ ∇φ_K(X_J) at every master J
/// (nodal integration, \[B00\] eq 79 in D dimensions), m_K a_K = −Σ_J V0_J P_J ∇φ_K(X_J), with
/// - hydro: the fluid itself, P = −p(J) cof F, p = K(ρ/ρ0 − 1), ρ = ρ_ref/J (transverse modes
///   neutral, longitudinal speed² K/ρ0, as for the Eulerian forms);
/// - elastic: St Venant–Kirchhoff about the pre-stress, S = σ0 I + λ_T tr E I + 2G_T E, P = F S,
///   with (λ_T, G_T) = (λ, G) for the Truesdell rate and (λ + σ0, G − σ0) for the Jaumann rate,
///   so that the tangent C_T + σ0 δ (\[B00\] eq 15) is that of the Eulerian law;
/// - neo-Hookean: P = μ(F − F⁻ᵀ) + λ ln J F⁻ᵀ;
///
/// (tl-enog: its momentum is the pair sum of [`tl_enog_pairs`] instead of the nodal integration),
/// plus Monaghan's viscosity, as in the Eulerian forms, on the pairs of the reference stencils at
/// their current separation (reference densities in ρ̄).
pub(crate) fn rate_tl<S: Scalar, const D: usize>(
    m: &Model<D>,
    z: StateView<'_, S, D>,
    out: RateOut<'_, S, D>,
    ws: &mut RateWorkspace<S, D>,
) -> Result<()> {
    if let Some(xo) = out.x {
        xo.copy_from_slice(z.v);
    }
    if let Some(aux) = out.aux {
        // the total-Lagrangian forms carry no auxiliary state
        aux.rho.fill(S::zero());
        aux.sigma.fill([[S::zero(); D]; D]);
        aux.tau.fill([[S::zero(); D]; D]);
    }
    let Some(acc) = out.v else {
        return Ok(());
    };
    acc.fill([S::zero(); D]);
    ws.disp.clear();
    ws.disp.extend(z.x.iter().zip(&m.x_ref).map(|(x, xr)| {
        let mut u = [S::zero(); D];
        for a in 0..D {
            u[a] = x[a] - xr[a];
        }
        u
    }));
    let u = &ws.disp;
    let pairwise = m.p.form == FormKind::TlEnog || m.p.hourglass.is_some();
    ws.defgrad.clear();
    ws.piola.clear();
    for (j, st) in m.ref_master.iter().enumerate() {
        let f = tl_deformation_gradient(st, u);
        let mut p = tl_piola(m, j, &f);
        if pairwise {
            ws.defgrad.push(f);
        }
        if m.p.form == FormKind::TlEnog {
            // the momentum is a pair sum (below), not the nodal integration's
            tl_enog_nodal(m, &f, &mut p);
            ws.piola.push(p);
            continue;
        }
        let w = m.vol_ref[j];
        for &(k, _, gr) in st {
            for a in 0..D {
                let mut pg = p[a][0] * gr[0];
                for b in 1..D {
                    pg += p[a][b] * gr[b];
                }
                acc[k][a] -= pg * w;
            }
        }
    }
    match (m.p.form, m.p.hourglass) {
        (FormKind::TlEnog, _) => tl_enog_pairs(m, z, acc, &ws.defgrad, &ws.piola),
        (_, Some(alpha)) => ganzenmuller(m, z, acc, &ws.defgrad, alpha),
        _ => {}
    }
    for (a, &ms) in acc.iter_mut().zip(&m.mass) {
        *a = a.map(|x| x / ms);
    }
    // Monaghan viscosity on the reference neighbours at their current (minimum-image)
    // separation, with the reference densities m/V0 (the forms carry no density)
    if let Some(av) = m.p.av {
        for (i, st) in m.ref_master.iter().enumerate() {
            let rho_i = m.mass[i] / m.vol_ref[i];
            for &(k, _, _) in st {
                if k == i {
                    continue;
                }
                let d = m.rel(z.x[i], z.x[k]);
                let mut dv = [S::zero(); D];
                for c in 0..D {
                    dv[c] = z.v[i][c] - z.v[k][c];
                }
                let rho_bar = S::cst((rho_i + m.mass[k] / m.vol_ref[k]) * 0.5);
                let f = av_pair(m, &av, d, dv, rho_bar, m.mass[k], None);
                for c in 0..D {
                    acc[i][c] += f[c];
                }
            }
        }
    }
    Ok(())
}

/// The shear modulus and Young's modulus of a total-Lagrangian law (0 for a fluid).
fn tl_moduli<const D: usize>(m: &Model<D>) -> (f64, f64) {
    match m.p.material {
        Material::Elastic { lambda, shear, .. } | Material::NeoHookean { lambda, shear } => (
            shear,
            shear * (3.0 * lambda + 2.0 * shear) / (lambda + shear),
        ),
        Material::Hydro { .. } => (0.0, 0.0),
    }
}

/// tl-enog's nodal stress \[Wu, Zhang, Tang & Hu 2023\]: the law's P, less the part κG J^{−2/d} F
/// that [`tl_enog_pairs`] takes pairwise, plus (κ − 1) times the isochoric neo-Hookean
/// deviator G J^{−2/d}(F − (tr b/d) F⁻ᵀ) (κ scales the shear as the paper's), plus κG I (so
/// the rest state keeps the law's P(I)):
/// P̃ = P + (κ − 1) G J^{−2/d}(F − (tr b/d) F⁻ᵀ) − κ G J^{−2/d} F + κ G I.
/// For the paper's law (the isochoric neo-Hookean) the nodal part is its
/// (τ_vol − κ G J^{−2/d} tr b/d) F⁻ᵀ exactly.
fn tl_enog_nodal<S: Scalar, const D: usize>(m: &Model<D>, f: &Tensor<S, D>, p: &mut Tensor<S, D>) {
    let kappa = m.p.hourglass.unwrap_or(TL_ENOG_DEFAULT_KAPPA);
    let (g, _) = tl_moduli(m);
    let jac = det_s(f);
    let jm = jac.powf(-2.0 / D as f64);
    let cof = cof_s(f);
    let mut trb = S::zero();
    for a in 0..D {
        for b in 0..D {
            trb += f[a][b] * f[a][b];
        }
    }
    for a in 0..D {
        for b in 0..D {
            let fit = cof[a][b] / jac;
            let iso = (f[a][b] - trb / D as f64 * fit) * jm * g;
            p[a][b] += iso * (kappa - 1.0) - f[a][b] * jm * (kappa * g);
            if a == b {
                p[a][b] += S::cst(kappa * g);
            }
        }
    }
}

/// tl-enog's default κ = 1.07 (SPHinXsys's `DecomposedIntegration1stHalf`).
pub const TL_ENOG_DEFAULT_KAPPA: f64 = 1.07;

/// tl-enog's forces, added to `acc` (before the division by the mass), a pair sum over the
/// reference neighbours L of K \[Wu, Zhang, Tang & Hu 2023; SPHinXsys's
/// `DecomposedIntegration1stHalf`\]: the nodal stresses P̃ of [`tl_enog_nodal`] with the
/// kernel's own (uncorrected) reference gradient, and the pairwise shear,
/// f_K = Σ_L V_K V_L [(P̃_K + P̃_L) e⁰ + κ G (J_K^{−2/d} + J_L^{−2/d}) (x_K − x_L)/r⁰ − 2κG e⁰] W′(r⁰),
/// e⁰ = (X_K − X_L)/r⁰; J from the nodal F of each particle (the B-corrected gradient of the
/// default shape enters F only). The pair term's reference value −2κG e⁰ is taken out, as the
/// nodal κ G I of P̃ is in: the paper's split, whose two constants cancel pair by pair, with
/// P̃(I) the law's P(I) (the pre-stress).
fn tl_enog_pairs<S: Scalar, const D: usize>(
    m: &Model<D>,
    z: StateView<'_, S, D>,
    acc: &mut [[S; D]],
    defgrad: &[Tensor<S, D>],
    piola: &[Tensor<S, D>],
) {
    let kappa = m.p.hourglass.unwrap_or(TL_ENOG_DEFAULT_KAPPA);
    let (g, _) = tl_moduli(m);
    let jm = |k: usize| det_s(&defgrad[k]).powf(-2.0 / D as f64);
    acc.par_iter_mut()
        .zip(&m.ref_pairs)
        .enumerate()
        .for_each(|(k, (ak, pairs))| {
            let jk = jm(k);
            for p in pairs {
                // x_L − x_K (minimum image)
                let d = m.rel(z.x[k], z.x[p.l]);
                let w = kappa * g * p.vv * p.dw / p.r0;
                let jsum = jk + jm(p.l);
                let e0 = p.d0.map(|c| -c / p.r0);
                let (pk, pl) = (&piola[k], &piola[p.l]);
                for c in 0..D {
                    // (x_K − x_L)(J_K^{−2/d} + J_L^{−2/d}) − 2 (X_K − X_L)
                    ak[c] += (-(d[c] * jsum) + 2.0 * p.d0[c]) * w;
                    let mut pe = S::zero();
                    for b in 0..D {
                        pe += (pk[c][b] + pl[c][b]) * e0[b];
                    }
                    ak[c] += pe * (p.vv * p.dw);
                }
            }
        });
}

/// Ganzenmüller's hourglass control for total-Lagrangian SPH (Comput. Methods Appl. Mech.
/// Engrg. 286, 2015, eqs 17–24, as transcribed from the paper's form; LAMMPS's `smd/tlsph`
/// implements a variant), added to the forces `acc`: for each reference neighbour L of K,
/// with X = X_L − X_K, x = x_L − x_K (minimum image),
/// ε_K = F_K X − x (the predicted minus the actual separation), δ_K = ε_K · F_K X / |x|,
/// δ_L likewise with F_L, and
/// f_K = −½ α E V_K V_L W(|X|) (δ_K + δ_L)/|X|² · x/|x|,
/// a central pair force that vanishes for every linear motion (x = F X).
fn ganzenmuller<S: Scalar, const D: usize>(
    m: &Model<D>,
    z: StateView<'_, S, D>,
    acc: &mut [[S; D]],
    defgrad: &[Tensor<S, D>],
    alpha: f64,
) {
    let (_, young) = tl_moduli(m);
    acc.par_iter_mut()
        .zip(&m.ref_pairs)
        .enumerate()
        .for_each(|(k, (ak, pairs))| {
            for p in pairs {
                let d = m.rel(z.x[k], z.x[p.l]);
                let mut r2 = S::zero();
                for c in 0..D {
                    r2 += d[c] * d[c];
                }
                let r = r2.sqrt();
                let delta = |f: &Tensor<S, D>| {
                    let mut s = S::zero();
                    for a in 0..D {
                        let mut pred = S::zero();
                        for b in 0..D {
                            pred += f[a][b] * p.d0[b];
                        }
                        s += (pred - d[a]) * pred;
                    }
                    s / r
                };
                let sum = delta(&defgrad[k]) + delta(&defgrad[p.l]);
                let coef = -0.5 * alpha * young * p.vv * p.w0 / (p.r0 * p.r0);
                for c in 0..D {
                    ak[c] += sum * d[c] / r * coef;
                }
            }
        });
}

impl<const D: usize> Model<D> {
    /// The stress each particle of state `z` carries, the one its momentum equation uses:
    /// for the total-Lagrangian form the Cauchy stress T = P Fᵀ/J of its law at the particle's
    /// deformation gradient ([`rate_tl`]; in 1D T = P), for the others the integrated stress
    /// (σ, or (1 − c)σ + cτ for the mixed forms: [`State::total_stress`]). Empty for a form
    /// with neither (a hydrodynamic material in an Eulerian form, the stress-point forms,
    /// whose stress lives on the stress points).
    pub fn particle_stress(&self, z: &State<f64, D>) -> Vec<Tensor<f64, D>> {
        if !self.p.form.is_total_lagrangian() {
            return z.total_stress(self.p.c_partition);
        }
        (0..z.x.len())
            .filter_map(|i| self.particle_stress_of(z, i))
            .collect()
    }

    /// [`Model::particle_stress`] of particle `i` alone (None for a form without a particle
    /// stress, or `i` out of range).
    pub fn particle_stress_of(&self, z: &State<f64, D>, i: usize) -> Option<Tensor<f64, D>> {
        if !self.p.form.is_total_lagrangian() {
            let s = z.sigma.get(i)?;
            let Some(t) = z.tau.get(i) else {
                return Some(*s);
            };
            let c = self.p.c_partition;
            return Some(std::array::from_fn(|a| {
                std::array::from_fn(|b| (1.0 - c) * s[a][b] + c * t[a][b])
            }));
        }
        let f = self.deformation_gradient_of(z, i)?;
        let p = tl_piola(self, i, &f);
        let jac = det_s(&f);
        let mut t = [[0.0; D]; D];
        for a in 0..D {
            for b in 0..D {
                for c in 0..D {
                    t[a][b] += p[a][c] * f[b][c];
                }
                t[a][b] /= jac;
            }
        }
        Some(t)
    }

    /// The deformation gradient F of particle `i` of a total-Lagrangian state `z` (the F of
    /// its rate, [`rate_tl`]); None for the other forms or `i` out of range.
    pub fn deformation_gradient_of(&self, z: &State<f64, D>, i: usize) -> Option<Tensor<f64, D>> {
        if !self.p.form.is_total_lagrangian() {
            return None;
        }
        let st = self.ref_master.get(i)?;
        let mut u = Vec::with_capacity(st.len());
        let mut local = Vec::with_capacity(st.len());
        for (slot, &(k, phi, gr)) in st.iter().enumerate() {
            u.push(std::array::from_fn(|a| z.x[k][a] - self.x_ref[k][a]));
            local.push((slot, phi, gr));
        }
        Some(tl_deformation_gradient(&local, &u))
    }

    /// The force m_K a_K (the force of M a = f for a consistent mass) on each particle of the
    /// reference configuration at rest under the uniform stress σ = e_a ⊗ e_a (`axis` = a):
    /// zero on a particle whose support the body fills, and near a face normal to e_a the
    /// discrete ∮ φ_K n_a dΓ of the form (the momentum equation's boundary integral, + on a
    /// face of outward normal −e_a). A prescribed normal stress s̄ on such a face is the load
    /// f_K = −s̄ b_K on the particles near it: it makes the uniform stress s̄ an equilibrium of
    /// the form there, and its resultant is s̄ times the face area that the particles carry.
    /// - total-Lagrangian: b_K = −e_a Σ_J V_J ∂φ_K/∂X_a(X_J) (the rate's P at F = I);
    /// - the others: the rate at rest with every stress field (σ, τ, stress points) = e_a ⊗ e_a
    ///   and ρ = m/V.
    ///
    /// Errors for a hydrodynamic material (its stress is a pressure from the density), and for
    /// a form that a uniform stress does not move anywhere (nonlocal, local, lnl: their
    /// momentum equation takes σ_J − σ_I).
    pub fn unit_stress_force(&self, axis: usize) -> Result<Vec<[f64; D]>> {
        if axis >= D {
            return Err(crate::error::Error::OutOfRange {
                field: "axis",
                value: axis as f64,
                range: format!("must be < {D}").into(),
            });
        }
        if matches!(self.p.material, Material::Hydro { .. }) {
            return Err(crate::error::Error::Incompatible(
                "a prescribed stress (traction) needs an elastic or neo-Hookean material, not a hydrodynamic one".into(),
            ));
        }
        let n = self.x_ref.len();
        if self.p.form.is_total_lagrangian() {
            let mut b = vec![[0.0; D]; n];
            for (j, st) in self.ref_master.iter().enumerate() {
                for &(k, _, gr) in st {
                    b[k][axis] -= self.vol_ref[j] * gr[axis];
                }
            }
            return Ok(b);
        }
        let mut unit = [[0.0; D]; D];
        unit[axis][axis] = 1.0;
        let mut z = self.rest_state(self.p.rho0);
        for (r, (m, v)) in z.rho.iter_mut().zip(self.mass.iter().zip(&self.vol_ref)) {
            *r = m / v;
        }
        z.sigma.iter_mut().for_each(|s| *s = unit);
        z.tau.iter_mut().for_each(|s| *s = unit);
        z.sp_sigma.iter_mut().for_each(|s| *s = unit);
        let mut out = State::default();
        self.rate(&z, &mut out)?;
        if out.v.iter().all(|a| a.iter().all(|c| c.abs() < 1e-12)) {
            return Err(crate::error::Error::Incompatible(
                format!(
                    "a prescribed stress (traction) needs a form whose momentum equation sees a uniform stress at a free boundary; {} takes the difference σ_J − σ_I, so a uniform stress exerts no force and there is nothing to load (use total-lagrangian, classical or cll)",
                    self.p.form.name()
                )
                .into(),
            ));
        }
        Ok(match self.mass_operator() {
            super::chain_data::MassOperator::Consistent(_) => out.v,
            super::chain_data::MassOperator::Lumped => out
                .v
                .iter()
                .zip(&self.mass)
                .map(|(a, m)| a.map(|c| c * m))
                .collect(),
        })
    }

    /// The rate function of the system (same definitions as the 1D forms). `out` is resized
    /// to the shape of `z`. Allocates a fresh [`RateWorkspace`]: the analysis' entry point; a
    /// time loop uses [`Model::rate_with`] or [`Model::rate_into`].
    pub fn rate<S: Scalar>(&self, z: &State<S, D>, out: &mut State<S, D>) -> Result<()> {
        self.rate_with(z, out, &mut RateWorkspace::new())
    }

    /// [`Model::rate`] with reusable buffers: `out` is resized to the shape of `z` (no
    /// allocation when it already has it) and the workspace's buffers are reused.
    pub fn rate_with<S: Scalar>(
        &self,
        z: &State<S, D>,
        out: &mut State<S, D>,
        ws: &mut RateWorkspace<S, D>,
    ) -> Result<()> {
        out.resize_like(z);
        self.rate_into(z.view(), out.as_rate_out(), ws)
    }

    /// The rate function on borrowed buffers, computing only the requested parts of `out`
    /// (accelerations, auxiliary rates, or both; each part is the same as in
    /// [`Model::rate`]). Every output slice must have the length of the state's field.
    pub fn rate_into<S: Scalar>(
        &self,
        z: StateView<'_, S, D>,
        out: RateOut<'_, S, D>,
        ws: &mut RateWorkspace<S, D>,
    ) -> Result<()> {
        if let Some(data) = &self.chain {
            return super::chain_rates::rate(self, data, z, out, ws);
        }
        match self.p.form {
            FormKind::TotalLagrangian | FormKind::TlEnog => rate_tl(self, z, out, ws),
            _ => rate(self, z, out, ws),
        }
    }
}
