//! The Eulerian-kernel forms in 2D (classical, nonlocal, local, lnl, cll): one routine whose
//! momentum and continuity terms are chosen by the form, with the same definitions as in 1D:
//!
//! ```text
//! L_I = Σ_J (v_J − v_I) ⊗ ∇φ_J(x_I),   ρ̇_I = −ρ_I tr L_I   (mixed forms: (1−c) tr L^nl + c tr L^loc)
//! classical:  a_I = Σ_J (σ_I/ρ_I² + σ_J/ρ_J²) ρ_J · ∇φ_J(x_I)          [V21 eq 55]
//! difference: a_I = (1/ρ_I) Σ_J (σ_J − σ_I) · ∇φ_J(x_I)                [V21 eq 54] (local: corrected ∇φ)
//! lnl: (1 − c) a^diff(σ) + c a^loc(τ);  cll: (1 − c) a^classical(σ) + c a^loc(τ)
//! ```
//! plus −Σ_J m_J Π_IJ ∇_I W_IJ (Monaghan viscosity). Stress: hydro σ = −K(ρ/ρ0 − 1) I from the
//! density; elastic σ (and τ) are state with the hypo-elastic rate of [`Material2D`].
//!
//! Evaluation: neighbour stencils from a cell list, then per-particle sums, in parallel over
//! particles (rayon), with every buffer in a reusable [`RateWorkspace`]: a time loop that keeps
//! its workspace does not allocate. Accelerations and auxiliary rates can be asked for
//! separately ([`RateOut2D`]); each is the same function of the state either way.

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::FormKind;
use super::model2d::{
    AuxRates2D, Material2D, Model2D, ObjectiveRate, RateOut2D, State2D, StateView2D,
};
use super::workspace::{Nb2, RateWorkspace};
use crate::error::Result;
use crate::kernel;
use crate::scalar::Scalar;
use rayon::prelude::*;

fn vel_grad<S: Scalar>(v: &[[S; 2]], i: usize, st: &[Nb2<S>]) -> [[S; 2]; 2] {
    let mut l = [[S::zero(); 2]; 2];
    for nb in st {
        for a in 0..2 {
            let dv = v[nb.j][a] - v[i][a];
            for b in 0..2 {
                l[a][b] += dv * nb.g[b];
            }
        }
    }
    l
}

/// σ·g for σ stored as [xx, yy, xy].
#[inline]
fn dot<S: Scalar>(s: [S; 3], g: [S; 2]) -> [S; 2] {
    [s[0] * g[0] + s[2] * g[1], s[2] * g[0] + s[1] * g[1]]
}

fn div_sum<S: Scalar>(s: &[[S; 3]], rho: &[S], i: usize, st: &[Nb2<S>]) -> [S; 2] {
    let ri2 = rho[i] * rho[i];
    let mut a = [S::zero(); 2];
    for nb in st {
        let rj = rho[nb.j];
        let t = [
            s[i][0] / ri2 + s[nb.j][0] / (rj * rj),
            s[i][1] / ri2 + s[nb.j][1] / (rj * rj),
            s[i][2] / ri2 + s[nb.j][2] / (rj * rj),
        ];
        let f = dot(t, nb.g);
        a[0] += f[0] * rj;
        a[1] += f[1] * rj;
    }
    a
}

fn div_difference<S: Scalar>(s: &[[S; 3]], rho_i: S, i: usize, st: &[Nb2<S>]) -> [S; 2] {
    let mut a = [S::zero(); 2];
    for nb in st {
        let t = [
            s[nb.j][0] - s[i][0],
            s[nb.j][1] - s[i][1],
            s[nb.j][2] - s[i][2],
        ];
        let f = dot(t, nb.g);
        a[0] += f[0];
        a[1] += f[1];
    }
    [a[0] / rho_i, a[1] / rho_i]
}

/// Hypo-elastic stress rate for velocity gradient L.
pub(crate) fn stress_rate<S: Scalar>(mat: &Material2D, s: [S; 3], l: [[S; 2]; 2]) -> [S; 3] {
    let Material2D::Elastic {
        lambda,
        shear,
        rate,
    } = *mat
    else {
        return [S::zero(); 3];
    };
    let tr = l[0][0] + l[1][1];
    let dxy = (l[0][1] + l[1][0]) * 0.5;
    let mut r = [
        tr * lambda + l[0][0] * (2.0 * shear),
        tr * lambda + l[1][1] * (2.0 * shear),
        dxy * (2.0 * shear),
    ];
    let sm = [[s[0], s[2]], [s[2], s[1]]];
    // extra[a][b] for the objective terms
    let mut extra = [[S::zero(); 2]; 2];
    match rate {
        ObjectiveRate::Jaumann => {
            let w = [
                [S::zero(), (l[0][1] - l[1][0]) * 0.5],
                [(l[1][0] - l[0][1]) * 0.5, S::zero()],
            ];
            for a in 0..2 {
                for b in 0..2 {
                    for c in 0..2 {
                        extra[a][b] += w[a][c] * sm[c][b] - sm[a][c] * w[c][b];
                    }
                }
            }
        }
        ObjectiveRate::Truesdell => {
            for a in 0..2 {
                for b in 0..2 {
                    for c in 0..2 {
                        extra[a][b] += l[a][c] * sm[c][b] + sm[a][c] * l[b][c];
                    }
                    extra[a][b] -= tr * sm[a][b];
                }
            }
        }
    }
    r[0] += extra[0][0];
    r[1] += extra[1][1];
    r[2] += extra[0][1];
    r
}

fn av_accel<S: Scalar>(m: &Model2D, z: StateView2D<'_, S>, i: usize, st: &[Nb2<S>]) -> [S; 2] {
    let Some(av) = m.p.av else {
        return [S::zero(); 2];
    };
    let h = m.p.kp.h;
    let mut a = [S::zero(); 2];
    for nb in st {
        if nb.j == i {
            continue;
        }
        let xij = [-nb.d[0], -nb.d[1]];
        let vij = [z.v[i][0] - z.v[nb.j][0], z.v[i][1] - z.v[nb.j][1]];
        let vx = vij[0] * xij[0] + vij[1] * xij[1];
        if av.approaching_only && vx.re() >= 0.0 {
            continue;
        }
        let r2 = xij[0] * xij[0] + xij[1] * xij[1];
        let mu = vx * h / (r2 + 0.01 * h * h);
        let rho_bar = (z.rho[i] + z.rho[nb.j]) * 0.5;
        let pi = (mu * (-av.alpha * av.sound_speed) + mu * mu * av.beta) / rho_bar;
        // ∇_I W(x_I − x_J) = −W'(r) d/r, differentiable through d = 0
        let (_, grad) = kernel::w_and_grad(m.p.kp.kernel, h, nb.d);
        for c in 0..2 {
            a[c] -= pi * grad[c] * m.mass[nb.j];
        }
    }
    a
}

/// Artificial-stress tensor R = −ε Σ_{λ>0} λ P_λ / ρ² of a stress [xx, yy, xy] (principal
/// decomposition; an isotropic tensile stress gives R = −ε σ/ρ², smooth for linearisation).
fn art_tensor<S: Scalar>(s: [S; 3], rho: S, eps: f64) -> [S; 3] {
    let scale = S::cst(-eps) / (rho * rho);
    let mean = (s[0] + s[1]) * 0.5;
    let dh = (s[0] - s[1]) * 0.5;
    let rad2 = dh * dh + s[2] * s[2];
    if rad2.re() <= 1e-28 * mean.re().abs().max(f64::MIN_POSITIVE).powi(2) {
        // (numerically) isotropic
        return if mean.re() > 0.0 {
            [s[0] * scale, s[1] * scale, s[2] * scale]
        } else {
            [S::zero(); 3]
        };
    }
    let rad = rad2.sqrt();
    let (l1, l2) = (mean + rad, mean - rad);
    // P1 = (σ − λ2 I)/(λ1 − λ2), P2 = I − P1
    let p1 = [
        (s[0] - l2) / (rad * 2.0),
        (s[1] - l2) / (rad * 2.0),
        s[2] / (rad * 2.0),
    ];
    let p2 = [S::cst(1.0) - p1[0], S::cst(1.0) - p1[1], -p1[2]];
    let mut r = [S::zero(); 3];
    for (l, p) in [(l1, p1), (l2, p2)] {
        if l.re() > 0.0 {
            for k in 0..3 {
                r[k] += l * p[k] * scale;
            }
        }
    }
    r
}

/// Σ_J m_J (R_I + R_J) f_IJⁿ ∇_I W_IJ.
fn art_accel<S: Scalar>(m: &Model2D, r: &[[S; 3]], i: usize, st: &[Nb2<S>]) -> [S; 2] {
    let Some(a) = m.p.art_stress else {
        return [S::zero(); 2];
    };
    let h = m.p.kp.h;
    let w_dp = kernel::w(m.p.kp.kernel, 2, a.spacing, h);
    let mut acc = [S::zero(); 2];
    for nb in st {
        if nb.j == i {
            continue;
        }
        // W(r) and ∇_I W(x_I − x_J) = −W'(r) d/r, differentiable through d = 0
        let (w, g) = kernel::w_and_grad(m.p.kp.kernel, h, nb.d);
        let f = w / w_dp;
        let mut fnn = S::cst(1.0);
        for _ in 0..a.n {
            fnn *= f;
        }
        let t = [
            r[i][0] + r[nb.j][0],
            r[i][1] + r[nb.j][1],
            r[i][2] + r[nb.j][2],
        ];
        let f2 = dot(t, g);
        acc[0] += f2[0] * fnn * m.mass[nb.j];
        acc[1] += f2[1] * fnn * m.mass[nb.j];
    }
    acc
}

/// The 2D rate of an Eulerian form, into the requested parts of `out`.
pub(crate) fn rate<S: Scalar>(
    m: &Model2D,
    z: StateView2D<'_, S>,
    out: RateOut2D<'_, S>,
    ws: &mut RateWorkspace<S>,
) -> Result<()> {
    let form = m.p.form;
    let mixed = matches!(form, FormKind::Lnl | FormKind::Cll);
    ws.build_stencils(m, z, mixed)?;
    let c = m.p.c_partition;
    if let Some(xo) = out.x {
        xo.copy_from_slice(z.v);
    }
    if let Some(acc) = out.v {
        ws.hydro.clear();
        if let Material2D::Hydro { bulk } = m.p.material {
            ws.hydro.extend(z.rho.iter().map(|&r| {
                let sg = (r / m.p.rho0 - 1.0) * (-bulk);
                [sg, sg, S::zero()]
            }));
        }
        let (sig, tau): (&[[S; 3]], &[[S; 3]]) = match m.p.material {
            Material2D::Hydro { .. } => (&ws.hydro, &ws.hydro),
            _ => (z.sigma, if mixed { z.tau } else { z.sigma }),
        };
        ws.art.clear();
        if let (Some(a), FormKind::Classical | FormKind::Cll) = (m.p.art_stress, form) {
            ws.art.extend(
                sig.iter()
                    .zip(z.rho)
                    .map(|(&s, &r)| art_tensor(s, r, a.eps)),
            );
        }
        let (st, art) = (&ws.stencils, &ws.art);
        // per-particle accelerations in parallel (rayon)
        acc.par_iter_mut().enumerate().for_each(|(i, out_a)| {
            let (st_a, st_b) = (&st[i].a, &st[i].b);
            let a = match form {
                FormKind::Classical => div_sum(sig, z.rho, i, st_a),
                FormKind::Nonlocal | FormKind::Local => div_difference(sig, z.rho[i], i, st_a),
                FormKind::Lnl | FormKind::Cll => {
                    let p = if form == FormKind::Lnl {
                        div_difference(sig, z.rho[i], i, st_a)
                    } else {
                        div_sum(sig, z.rho, i, st_a)
                    };
                    let q = div_difference(tau, z.rho[i], i, st_b);
                    [p[0] * (1.0 - c) + q[0] * c, p[1] * (1.0 - c) + q[1] * c]
                }
                _ => [S::zero(); 2],
            };
            let av = av_accel(m, z, i, st_a);
            let mut a = [a[0] + av[0], a[1] + av[1]];
            if !art.is_empty() {
                let ar = art_accel(m, art, i, st_a);
                let w = if form == FormKind::Cll { 1.0 - c } else { 1.0 };
                a = [a[0] + ar[0] * w, a[1] + ar[1] * w];
            }
            *out_a = a;
        });
    }
    if let Some(AuxRates2D { rho, sigma, tau }) = out.aux {
        let zero3 = [S::zero(); 3];
        ws.aux.resize(z.x.len(), (S::zero(), zero3, zero3));
        let st = &ws.stencils;
        // per-particle auxiliary rates in parallel (rayon), then copied into `out`
        ws.aux.par_iter_mut().enumerate().for_each(|(i, r)| {
            let la = vel_grad(z.v, i, &st[i].a);
            let lb = if mixed {
                vel_grad(z.v, i, &st[i].b)
            } else {
                la
            };
            let tra = la[0][0] + la[1][1];
            let trb = lb[0][0] + lb[1][1];
            let rho_rate = -z.rho[i]
                * if mixed {
                    tra * (1.0 - c) + trb * c
                } else {
                    tra
                };
            let sig_rate = if z.sigma.is_empty() {
                zero3
            } else {
                stress_rate(&m.p.material, z.sigma[i], la)
            };
            let tau_rate = if z.tau.is_empty() {
                zero3
            } else {
                stress_rate(&m.p.material, z.tau[i], lb)
            };
            *r = (rho_rate, sig_rate, tau_rate);
        });
        let aux = &ws.aux;
        rho.par_iter_mut().zip(aux).for_each(|(o, r)| *o = r.0);
        sigma.par_iter_mut().zip(aux).for_each(|(o, r)| *o = r.1);
        tau.par_iter_mut().zip(aux).for_each(|(o, r)| *o = r.2);
    }
    Ok(())
}

/// The 2D total-Lagrangian rate: F = I + Σ_K (u_K − ū) ⊗ ∇φ_K(X_J) at every master J
/// (nodal integration, \[B00\] eq 79 in 2D), m_K a_K = −Σ_J V0_J P_J ∇φ_K(X_J), with
/// - hydro: the fluid itself, P = −p(J) cof F, p = K(ρ/ρ0 − 1), ρ = ρ_ref/J (transverse modes
///   neutral, longitudinal speed² K/ρ0, as for the Eulerian forms);
/// - elastic: St Venant–Kirchhoff about the pre-stress, S = σ0 I + λ_T tr E I + 2G_T E, P = F S,
///   with (λ_T, G_T) = (λ, G) for the Truesdell rate and (λ + σ0, G − σ0) for the Jaumann rate,
///   so that the tangent C_T + σ0 δ (\[B00\] eq 15) is that of the Eulerian law.
pub(crate) fn rate_tl<S: Scalar>(
    m: &Model2D,
    z: StateView2D<'_, S>,
    out: RateOut2D<'_, S>,
    ws: &mut RateWorkspace<S>,
) -> Result<()> {
    let s0 = m.sigma0;
    if let Some(xo) = out.x {
        xo.copy_from_slice(z.v);
    }
    if let Some(aux) = out.aux {
        // the total-Lagrangian forms carry no auxiliary state
        aux.rho.fill(S::zero());
        aux.sigma.fill([S::zero(); 3]);
        aux.tau.fill([S::zero(); 3]);
    }
    let Some(acc) = out.v else {
        return Ok(());
    };
    acc.fill([S::zero(); 2]);
    ws.disp.clear();
    ws.disp.extend(
        z.x.iter()
            .zip(&m.x_ref)
            .map(|(x, xr)| [x[0] - xr[0], x[1] - xr[1]]),
    );
    let u = &ws.disp;
    for (j, st) in m.ref_master.iter().enumerate() {
        let sphi: f64 = st.iter().map(|e| e.1).sum();
        let mut ubar = [S::zero(); 2];
        for &(k, phi, _) in st {
            ubar[0] += u[k][0] * phi;
            ubar[1] += u[k][1] * phi;
        }
        ubar = [ubar[0] / sphi, ubar[1] / sphi];
        let mut f = [[S::cst(1.0), S::zero()], [S::zero(), S::cst(1.0)]];
        for &(k, _, gr) in st {
            for a in 0..2 {
                let du = u[k][a] - ubar[a];
                for b in 0..2 {
                    f[a][b] += du * gr[b];
                }
            }
        }
        let p = match m.p.material {
            Material2D::Hydro { bulk } => {
                let jac = f[0][0] * f[1][1] - f[0][1] * f[1][0];
                let rho_ref = m.mass[j] / m.vol_ref[j];
                let pr = ((S::cst(rho_ref) / jac) / m.p.rho0 - 1.0) * bulk;
                // P = −p cof F, cof F = J F⁻ᵀ = [[F11, −F10], [−F01, F00]]
                [[-pr * f[1][1], pr * f[1][0]], [pr * f[0][1], -pr * f[0][0]]]
            }
            Material2D::NeoHookean { lambda, shear } => {
                // P = μ(F − F⁻ᵀ) + λ ln J F⁻ᵀ, F⁻ᵀ = cof F / J
                let jac = f[0][0] * f[1][1] - f[0][1] * f[1][0];
                let cof = [[f[1][1], -f[1][0]], [-f[0][1], f[0][0]]];
                let lnj = jac.ln();
                let mut p = [[S::zero(); 2]; 2];
                for a in 0..2 {
                    for b in 0..2 {
                        let fit = cof[a][b] / jac;
                        p[a][b] = (f[a][b] - fit) * shear + lnj * fit * lambda;
                    }
                }
                p
            }
            Material2D::Elastic {
                lambda,
                shear,
                rate,
            } => {
                let (lam, g) = match rate {
                    ObjectiveRate::Truesdell => (lambda, shear),
                    ObjectiveRate::Jaumann => (lambda + s0, shear - s0),
                };
                let mut e = [[S::zero(); 2]; 2];
                for a in 0..2 {
                    for b in 0..2 {
                        let mut s = S::zero();
                        for c in 0..2 {
                            s += f[c][a] * f[c][b];
                        }
                        e[a][b] = (s - if a == b { 1.0 } else { 0.0 }) * 0.5;
                    }
                }
                let tr = e[0][0] + e[1][1];
                let mut sm = [[S::zero(); 2]; 2];
                for a in 0..2 {
                    for b in 0..2 {
                        sm[a][b] =
                            e[a][b] * (2.0 * g) + if a == b { tr * lam + s0 } else { S::zero() };
                    }
                }
                let mut p = [[S::zero(); 2]; 2];
                for a in 0..2 {
                    for b in 0..2 {
                        for c in 0..2 {
                            p[a][b] += f[a][c] * sm[c][b];
                        }
                    }
                }
                p
            }
        };
        let w = m.vol_ref[j];
        for &(k, _, gr) in st {
            for a in 0..2 {
                acc[k][a] -= (p[a][0] * gr[0] + p[a][1] * gr[1]) * w;
            }
        }
    }
    for (a, &ms) in acc.iter_mut().zip(&m.mass) {
        *a = [a[0] / ms, a[1] / ms];
    }
    Ok(())
}

impl Model2D {
    /// The rate function of the 2D system (same definitions as the 1D forms). `out` is resized
    /// to the shape of `z`. Allocates a fresh [`RateWorkspace`]: the analysis' entry point; a
    /// time loop uses [`Model2D::rate_with`] or [`Model2D::rate_into`].
    pub fn rate<S: Scalar>(&self, z: &State2D<S>, out: &mut State2D<S>) -> Result<()> {
        self.rate_with(z, out, &mut RateWorkspace::new())
    }

    /// [`Model2D::rate`] with reusable buffers: `out` is resized to the shape of `z` (no
    /// allocation when it already has it) and the workspace's buffers are reused.
    pub fn rate_with<S: Scalar>(
        &self,
        z: &State2D<S>,
        out: &mut State2D<S>,
        ws: &mut RateWorkspace<S>,
    ) -> Result<()> {
        out.resize_like(z);
        self.rate_into(z.view(), out.as_rate_out(), ws)
    }

    /// The rate function on borrowed buffers, computing only the requested parts of `out`
    /// (accelerations, auxiliary rates, or both; each part is the same as in
    /// [`Model2D::rate`]). Every output slice must have the length of the state's field.
    pub fn rate_into<S: Scalar>(
        &self,
        z: StateView2D<'_, S>,
        out: RateOut2D<'_, S>,
        ws: &mut RateWorkspace<S>,
    ) -> Result<()> {
        match self.p.form {
            FormKind::TotalLagrangian => rate_tl(self, z, out, ws),
            _ => rate(self, z, out, ws),
        }
    }
}
