//! `eulerian-stress-points`: Eulerian kernel with stress points at the mid-intervals
//! \[B00 §4.2.1, eq 83–92\]; without stress points (`eulerian-nodal`) the same code is the
//! Galerkin form with nodal integration \[B00 §4.1.1, eq 65–68\], master weight m_J/ρ_J.
//! 1D only.
//!
//! Masters carry x, v, ρ, σ; stress points carry their position x^S, stress σ^S and volume V^S.
//! Shape functions are built on the *current* master positions. With the interpolated velocity
//! v̄_p = Σ_K φ_K(x_p) v_K / Σ_K φ_K(x_p) and gradient (∂v/∂x)_p = Σ_K φ'_K(x_p)(v_K − v̄_p) [eq 85]:
//! ```text
//! ẋ^S = v̄_S                                                          [eq 58]
//! σ̇_p = (C + σ_p)(∂v/∂x)_p,  ρ̇_I = −ρ_I (∂v/∂x)_I,  V̇^S = V^S (∂v/∂x)_S
//! m_I v̇_I = −Σ_J (m_J / 2ρ_J) φ'_I(x_J) σ_J − Σ_S V^S φ'_I(x^S) σ^S    [eq 83–84]
//! ```

use super::chain_data::{ChainModel, ChainState};
use super::chain_search::{ChainWorkspace, Nb, StencilScratch, Stencils};
use crate::error::Result;
use crate::scalar::Scalar;
use crate::shape::{self, ShapeFamily};

fn interp<S: Scalar>(v: &[S], st: &[Nb<S>]) -> (S, S) {
    let mut sphi = S::zero();
    let mut vbar = S::zero();
    for nb in st {
        sphi += nb.phi;
        vbar += nb.phi * v[nb.j];
    }
    let vbar = vbar / sphi;
    let mut g = S::zero();
    for nb in st {
        g += (v[nb.j] - vbar) * nb.dphi;
    }
    (vbar, g)
}

/// Stencils of the masters around the evaluation points `pts` on the current configuration
/// (master positions `x`), with shape family `family` and master volumes `vol`, into `out`
/// (cleared and refilled). `sc.search` must have been prepared for `x`
/// ([`super::chain_search::ChainSearch::prepare_positions`]).
fn stencils<S: Scalar>(
    m: &ChainModel<'_>,
    x: &[S],
    pts: &[S],
    family: ShapeFamily,
    vol: &[S],
    sc: &mut StencilScratch<S>,
    out: &mut Stencils<S>,
) -> Result<()> {
    let r = m.p.kp.support();
    out.nb.clear();
    out.start.clear();
    out.start.push(0);
    sc.search.restart();
    for &xp in pts {
        sc.nodes.clear();
        sc.idx.clear();
        sc.search.candidates(xp.re(), r, &mut sc.idx);
        sc.idx.retain(|&j| m.data.rel(xp, x[j]).re().abs() < r);
        for &j in sc.idx.iter() {
            sc.nodes.push(([m.data.rel(xp, x[j])], vol[j]));
        }
        shape::eval_d(family, m.p.kp, &sc.nodes, xp.re(), &mut sc.vals)?;
        out.nb.extend(
            sc.idx
                .iter()
                .zip(&sc.vals)
                .map(|(&j, &(phi, [dphi]))| Nb { j, phi, dphi }),
        );
        out.start.push(out.nb.len());
    }
    Ok(())
}

pub(crate) fn rate<S: Scalar>(
    m: &ChainModel<'_>,
    z: ChainState<'_, S>,
    ws: &mut ChainWorkspace<S>,
) -> Result<()> {
    // current master volumes V_J = m_J / ρ_J
    ws.vol.clear();
    ws.vol.extend(
        z.rho
            .iter()
            .zip(m.mass)
            .map(|(&rho, &mass)| S::cst(mass) / rho),
    );
    ws.scratch
        .search_mut()
        .prepare_positions(m.data.period, z.x.iter().map(|x| x.re()));
    let vol = &ws.vol;
    stencils(m, z.x, z.x, m.p.shape, vol, &mut ws.scratch, &mut ws.st_m)?;
    stencils(
        m,
        z.x,
        z.sp_x,
        m.p.shape,
        vol,
        &mut ws.scratch,
        &mut ws.st_s,
    )?;
    let out = &mut ws.rate;
    out.x.copy_from_slice(z.v);
    for a in out.v.iter_mut() {
        *a = S::zero();
    }
    let c = m.modulus;
    let stress_points = m.p.form.has_stress_points();
    for (i, &vi) in vol.iter().enumerate() {
        let st = ws.st_m.get(i);
        let (_, g) = interp(z.v, st);
        out.rho[i] = -z.rho[i] * g;
        out.sigma[i] = (z.sigma[i] + c) * g;
        let w = if stress_points { vi * 0.5 } else { vi };
        for nb in st {
            out.v[nb.j] -= w * nb.dphi * z.sigma[i];
        }
    }
    for s in 0..ws.st_s.len() {
        let st = ws.st_s.get(s);
        let (vbar, g) = interp(z.v, st);
        out.sp_x[s] = vbar;
        out.sp_sigma[s] = (z.sp_sigma[s] + c) * g;
        out.sp_vol[s] = z.sp_vol[s] * g;
        for nb in st {
            out.v[nb.j] -= z.sp_vol[s] * nb.dphi * z.sp_sigma[s];
        }
    }
    for (a, &mass) in out.v.iter_mut().zip(m.mass) {
        *a = *a / mass;
    }
    Ok(())
}
