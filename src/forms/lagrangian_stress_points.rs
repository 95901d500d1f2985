//! `lagrangian-stress-points` (1D only): Lagrangian kernel (shape functions on the reference
//! configuration, fixed neighbours), Galerkin form with stress-point integration
//! \[B00 eq 99–102\] — the total-Lagrangian form of every dimension (`rates::rate_tl`,
//! \[B00 eq 77–81\]) with the mid-interval stress points added as integration points.
//!
//! ```text
//! F_p = 1 + Σ_K φ'_K(X_p) (u_K − ū_p),   ū_p = Σ_K φ_K(X_p) u_K / Σ_K φ_K(X_p),   u = x − X
//! P_p = (σ0 + C) F_p − C               (1D hypo-elastic law with the Truesdell rate, integrated)
//! m_I v̇_I = −Σ_p w_p φ'_I(X_p) P_p
//! ```
//! Integration points p: the masters (w_p = V0, or V0/2 with stress points) and, for
//! `lagrangian-stress-points`, the mid-points (w_p = V0/2). For `mls` shapes Σφ' = 0 so the
//! ū shift changes nothing; for `sph` it makes F invariant under rigid translation.

use super::chain_data::{ChainModel, ChainState, RefStencil};
use super::chain_search::ChainWorkspace;
use crate::scalar::Scalar;

pub(crate) fn rate<S: Scalar>(
    m: &ChainModel<'_>,
    z: ChainState<'_, S>,
    ws: &mut ChainWorkspace<S>,
) {
    let out = &mut ws.rate;
    out.x.copy_from_slice(z.v);
    for a in out.v.iter_mut() {
        *a = S::zero();
    }
    ws.u.clear();
    ws.u.extend(z.x.iter().zip(m.x_ref).map(|(&x, &xr)| x - xr));
    let u = &ws.u;
    let big = m.sigma0 + m.modulus;
    let mut scatter = |st: &RefStencil, w: f64| {
        let mut sphi = 0.0;
        let mut ubar = S::zero();
        for &(k, [phi, _, _]) in &st.entries {
            sphi += phi;
            ubar += u[k] * phi;
        }
        let ubar = ubar / sphi;
        let mut f = S::cst(1.0);
        for &(k, [_, dphi, _]) in &st.entries {
            f += (u[k] - ubar) * dphi;
        }
        let p = f * big - m.modulus;
        for &(k, [_, dphi, _]) in &st.entries {
            out.v[k] -= p * (w * dphi);
        }
    };
    let d = m.data;
    for (st, &w) in d.ref_master.iter().zip(&d.master_weight_ref) {
        scatter(st, w);
    }
    for (st, &w) in d.ref_sp.iter().zip(&d.sp_vol_ref) {
        scatter(st, w);
    }
    for (a, &mass) in out.v.iter_mut().zip(m.mass) {
        *a = *a / mass;
    }
}
