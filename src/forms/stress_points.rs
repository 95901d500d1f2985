//! `eulerian-stress-points`: Eulerian kernel with stress points at the mid-intervals
//! \[B00 §4.2.1, eq 83–92\]; without stress points (`eulerian-nodal`) the same code is the
//! Galerkin form with nodal integration \[B00 §4.1.1, eq 65–68\], master weight m_J/ρ_J.
//!
//! Masters carry x, v, ρ, σ; stress points carry their position x^S, stress σ^S and volume V^S.
//! Shape functions are built on the *current* master positions. With the interpolated velocity
//! v̄_p = Σ_K φ_K(x_p) v_K / Σ_K φ_K(x_p) and gradient (∂v/∂x)_p = Σ_K φ'_K(x_p)(v_K − v̄_p) [eq 85]:
//! ```text
//! ẋ^S = v̄_S                                                          [eq 58]
//! σ̇_p = (C + σ_p)(∂v/∂x)_p,  ρ̇_I = −ρ_I (∂v/∂x)_I,  V̇^S = V^S (∂v/∂x)_S
//! m_I v̇_I = −Σ_J (m_J / 2ρ_J) φ'_I(x_J) σ_J − Σ_S V^S φ'_I(x^S) σ^S    [eq 83–84]
//! ```

use super::eulerian_common::{Nb, stencils, volumes};
use super::model::{Model1D, State1D, Workspace1D};
use crate::error::Result;
use crate::scalar::Scalar;

fn interp<S: Scalar>(z: &State1D<S>, st: &[Nb<S>]) -> (S, S) {
    let mut sphi = S::zero();
    let mut vbar = S::zero();
    for nb in st {
        sphi += nb.phi;
        vbar += nb.phi * z.v[nb.j];
    }
    let vbar = vbar / sphi;
    let mut g = S::zero();
    for nb in st {
        g += (z.v[nb.j] - vbar) * nb.dphi;
    }
    (vbar, g)
}

pub(crate) fn rate<S: Scalar>(
    m: &Model1D,
    z: &State1D<S>,
    out: &mut State1D<S>,
    ws: &mut Workspace1D<S>,
) -> Result<()> {
    volumes(m, z, &mut ws.vol);
    ws.scratch.search_mut().prepare(m, z);
    let vol = &ws.vol;
    stencils(m, z, &z.x, m.p.shape, vol, &mut ws.scratch, &mut ws.st_m)?;
    stencils(m, z, &z.sp_x, m.p.shape, vol, &mut ws.scratch, &mut ws.st_s)?;
    out.x.copy_from_slice(&z.v);
    for a in out.v.iter_mut() {
        *a = S::zero();
    }
    let c = m.p.modulus;
    for (i, &vi) in vol.iter().enumerate() {
        let st = ws.st_m.get(i);
        let (_, g) = interp(z, st);
        out.rho[i] = -z.rho[i] * g;
        out.sigma[i] = (z.sigma[i] + c) * g;
        let w = if m.p.form.has_stress_points() {
            vi * 0.5
        } else {
            vi
        };
        for nb in st {
            out.v[nb.j] -= w * nb.dphi * z.sigma[i];
        }
    }
    for s in 0..ws.st_s.len() {
        let st = ws.st_s.get(s);
        let (vbar, g) = interp(z, st);
        out.sp_x[s] = vbar;
        out.sp_sigma[s] = (z.sp_sigma[s] + c) * g;
        out.sp_vol[s] = z.sp_vol[s] * g;
        for nb in st {
            out.v[nb.j] -= z.sp_vol[s] * nb.dphi * z.sp_sigma[s];
        }
    }
    for (a, &mass) in out.v.iter_mut().zip(&m.mass) {
        *a = *a / mass;
    }
    Ok(())
}
