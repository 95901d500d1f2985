//! The 2D Eulerian and total-Lagrangian rate functions exactly as they were before the
//! reusable workspace (commit d129d53), kept as the obviously-correct reference that the
//! allocation-free path is tested against (`tests/rate_workspace.rs`). Not used elsewhere.
//! Only the public API of the crate is used; the total-Lagrangian reference stencils are
//! rebuilt here the way `Model2D::new` builds them.

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use rayon::prelude::*;
use sphstab::error::Result;
use sphstab::forms::{FormKind, Material2D, Model2D, ObjectiveRate, State2D};
use sphstab::kernel;
use sphstab::neighbours::CellList;
use sphstab::scalar::Scalar;
use sphstab::shape::ShapeFamily;
use sphstab::shape2d::eval2;

/// Per-worker buffers of the stencil search: (relative position, volume), indices, (φ, ∇φ).
type StencilBuffers<S> = (Vec<([S; 2], S)>, Vec<usize>, Vec<(S, [S; 2])>);

/// Per-particle rates: (ρ̇, σ̇, τ̇, a).
type ParticleRates<S> = (S, [S; 3], [S; 3], [S; 2]);

/// Neighbour J of an evaluation point: index, d = x_J − x, φ_J, ∇φ_J.
#[derive(Clone, Copy, Debug)]
struct Nb2<S> {
    pub j: usize,
    pub d: [S; 2],
    pub g: [S; 2],
}

fn stencils<S: Scalar>(
    m: &Model2D,
    z: &State2D<S>,
    family: ShapeFamily,
    vol: &[S],
) -> Result<Vec<Vec<Nb2<S>>>> {
    let r = m.p.kp.support();
    let pos: Vec<[f64; 2]> = z.x.iter().map(|p| [p[0].re(), p[1].re()]).collect();
    // cell list for open domains and rectangular periodic boxes; direct scan otherwise
    let grid = match m.period {
        None => Some(CellList::new(&pos, r, None)),
        Some(l) if l[0][1] == 0.0 && l[1][0] == 0.0 => {
            Some(CellList::new(&pos, r, Some([l[0][0], l[1][1]])))
        }
        Some(_) => None,
    };
    // one stencil per particle, in parallel (rayon); each worker keeps its own buffers
    (0..z.x.len())
        .into_par_iter()
        .map_init(
            || (Vec::new(), Vec::new(), Vec::new()),
            |(nodes, idx, vals): &mut StencilBuffers<S>, i| {
                nodes.clear();
                idx.clear();
                let xi = z.x[i];
                let mut visit = |j: usize| {
                    let d = m.rel(xi, z.x[j]);
                    if d[0].re().hypot(d[1].re()) < r {
                        nodes.push((d, vol[j]));
                        idx.push(j);
                    }
                };
                match &grid {
                    Some(g) => g.for_candidates(pos[i], &mut visit),
                    None => (0..z.x.len()).for_each(&mut visit),
                }
                eval2(family, m.p.kp, nodes, pos[i], vals)?;
                Ok(idx
                    .iter()
                    .zip(nodes.iter())
                    .zip(vals.iter())
                    .map(|((&j, &(d, _)), &(_, g))| Nb2 { j, d, g })
                    .collect())
            },
        )
        .collect()
}

fn vel_grad<S: Scalar>(z: &State2D<S>, i: usize, st: &[Nb2<S>]) -> [[S; 2]; 2] {
    let mut l = [[S::zero(); 2]; 2];
    for nb in st {
        for a in 0..2 {
            let dv = z.v[nb.j][a] - z.v[i][a];
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
fn stress_rate<S: Scalar>(mat: &Material2D, s: [S; 3], l: [[S; 2]; 2]) -> [S; 3] {
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

fn av_accel<S: Scalar>(m: &Model2D, z: &State2D<S>, i: usize, st: &[Nb2<S>]) -> [S; 2] {
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
        let r = r2.sqrt();
        let dw = kernel::dw(m.p.kp.kernel, 2, r, h);
        for c in 0..2 {
            a[c] -= pi * dw * xij[c] / r * m.mass[nb.j];
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
        let rr = (nb.d[0] * nb.d[0] + nb.d[1] * nb.d[1]).sqrt();
        let f = kernel::w(m.p.kp.kernel, 2, rr, h) / w_dp;
        let mut fnn = S::cst(1.0);
        for _ in 0..a.n {
            fnn *= f;
        }
        // ∇_I W(x_I − x_J) = W'(r) (x_I − x_J)/r = −W'(r) d/r
        let dw = kernel::dw(m.p.kp.kernel, 2, rr, h);
        let g = [-dw * nb.d[0] / rr, -dw * nb.d[1] / rr];
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

/// The 2D rate of an Eulerian form.
fn rate<S: Scalar>(m: &Model2D, z: &State2D<S>, out: &mut State2D<S>) -> Result<()> {
    let form = m.p.form;
    let vol: Vec<S> = z
        .rho
        .iter()
        .zip(&m.mass)
        .map(|(&r, &ms)| S::cst(ms) / r)
        .collect();
    let st_a = stencils(m, z, m.p.shape, &vol)?;
    let mixed = matches!(form, FormKind::Lnl | FormKind::Cll);
    let st_b = if mixed {
        stencils(m, z, ShapeFamily::Corrected, &vol)?
    } else {
        Vec::new()
    };
    let hydro_stress: Vec<[S; 3]> = match m.p.material {
        Material2D::Hydro { bulk } => z
            .rho
            .iter()
            .map(|&r| {
                let sg = (r / m.p.rho0 - 1.0) * (-bulk);
                [sg, sg, S::zero()]
            })
            .collect(),
        _ => Vec::new(),
    };
    let (sig, tau): (&[[S; 3]], &[[S; 3]]) = match m.p.material {
        Material2D::Hydro { .. } => (&hydro_stress, &hydro_stress),
        _ => (&z.sigma, if mixed { &z.tau } else { &z.sigma }),
    };
    let c = m.p.c_partition;
    let art: Vec<[S; 3]> = match (m.p.art_stress, form) {
        (Some(a), FormKind::Classical | FormKind::Cll) => sig
            .iter()
            .zip(&z.rho)
            .map(|(&s, &r)| art_tensor(s, r, a.eps))
            .collect(),
        _ => Vec::new(),
    };
    // per-particle rates in parallel (rayon), then scattered into `out`
    let zero3 = [S::zero(); 3];
    let rates: Vec<ParticleRates<S>> = (0..z.x.len())
        .into_par_iter()
        .map(|i| {
            let la = vel_grad(z, i, &st_a[i]);
            let lb = if mixed { vel_grad(z, i, &st_b[i]) } else { la };
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
            let a = match form {
                FormKind::Classical => div_sum(sig, &z.rho, i, &st_a[i]),
                FormKind::Nonlocal | FormKind::Local => div_difference(sig, z.rho[i], i, &st_a[i]),
                FormKind::Lnl | FormKind::Cll => {
                    let p = if form == FormKind::Lnl {
                        div_difference(sig, z.rho[i], i, &st_a[i])
                    } else {
                        div_sum(sig, &z.rho, i, &st_a[i])
                    };
                    let q = div_difference(tau, z.rho[i], i, &st_b[i]);
                    [p[0] * (1.0 - c) + q[0] * c, p[1] * (1.0 - c) + q[1] * c]
                }
                _ => [S::zero(); 2],
            };
            let av = av_accel(m, z, i, &st_a[i]);
            let mut a = [a[0] + av[0], a[1] + av[1]];
            if !art.is_empty() {
                let ar = art_accel(m, &art, i, &st_a[i]);
                let w = if form == FormKind::Cll { 1.0 - c } else { 1.0 };
                a = [a[0] + ar[0] * w, a[1] + ar[1] * w];
            }
            (rho_rate, sig_rate, tau_rate, a)
        })
        .collect();
    for (i, (rho_rate, sig_rate, tau_rate, a)) in rates.into_iter().enumerate() {
        out.x[i] = z.v[i];
        out.rho[i] = rho_rate;
        if !z.sigma.is_empty() {
            out.sigma[i] = sig_rate;
        }
        if !z.tau.is_empty() {
            out.tau[i] = tau_rate;
        }
        out.v[i] = a;
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
fn rate_tl<S: Scalar>(m: &Model2D, z: &State2D<S>, out: &mut State2D<S>) -> Result<()> {
    let s0 = m.sigma0;
    let ref_master = reference_stencils(m)?;
    for (i, a) in out.v.iter_mut().enumerate() {
        out.x[i] = z.v[i];
        *a = [S::zero(); 2];
    }
    let u: Vec<[S; 2]> =
        z.x.iter()
            .zip(&m.x_ref)
            .map(|(x, xr)| [x[0] - xr[0], x[1] - xr[1]])
            .collect();
    for (j, st) in ref_master.iter().enumerate() {
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
                out.v[k][a] -= (p[a][0] * gr[0] + p[a][1] * gr[1]) * w;
            }
        }
    }
    for (a, &ms) in out.v.iter_mut().zip(&m.mass) {
        *a = [a[0] / ms, a[1] / ms];
    }
    Ok(())
}

/// The reference stencils of `Model2D::new` (direct scan at the reference positions).
#[allow(clippy::type_complexity)]
fn reference_stencils(m: &Model2D) -> Result<Vec<Vec<(usize, f64, [f64; 2])>>> {
    let r = m.p.kp.support();
    let mut out = Vec::new();
    let mut st = Vec::with_capacity(m.x_ref.len());
    for i in 0..m.x_ref.len() {
        let x = m.x_ref[i];
        let mut nodes = Vec::new();
        let mut idx = Vec::new();
        for (j, &xj) in m.x_ref.iter().enumerate() {
            let d = m.rel(x, xj);
            if d[0].hypot(d[1]) < r {
                nodes.push((d, m.vol_ref[j]));
                idx.push(j);
            }
        }
        eval2(m.p.shape, m.p.kp, &nodes, x, &mut out)?;
        st.push(
            idx.into_iter()
                .zip(&out)
                .map(|(j, &(phi, g))| (j, phi, g))
                .collect(),
        );
    }
    Ok(st)
}

/// The rate function of the 2D system as it was: a fresh zeroed output, then the form's rate.
pub fn reference_rate<S: Scalar>(m: &Model2D, z: &State2D<S>, out: &mut State2D<S>) -> Result<()> {
    *out = State2D::zeros_like(z);
    match m.p.form {
        FormKind::TotalLagrangian => rate_tl(m, z, out),
        _ => rate(m, z, out),
    }
}
