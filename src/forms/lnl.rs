//! Mixed forms with partition coefficient c: `lnl` (local–nonlocal, \[V21 eq 50–56\]) and `cll`
//! (classical–local, \[V21 §7.2\]).
//!
//! The nonlocal (or classical) part uses the shape family of the model (default `sph`) and its
//! own stress σ; the local part uses corrected derivatives and its own stress τ, both
//! hypo-elastic (\[V21 §7\]: "calculated and stored separately"). With c_ρ = c:
//! ```text
//! ρ̇_I = −ρ_I [(1 − c) (∂v/∂x)^nl_I + c (∂v/∂x)^loc_I]
//! σ̇_I = (C + σ_I) (∂v/∂x)^nl_I,   τ̇_I = (C + τ_I) (∂v/∂x)^loc_I
//! v̇_I = (1 − c) a^nl_I(σ) + c a^loc_I(τ) − Σ_J m_J Π_IJ ∇_I W_IJ              \[V21 eq 56\]
//! ```
//! where a^nl is the difference form (lnl) or Monaghan's sum form (cll).

use super::eulerian_common::{
    av_accel, div_difference, div_sum, grad_v, kinematics, stencils, volumes,
};
use super::model::{Model1D, State1D};
use crate::error::Result;
use crate::scalar::Scalar;
use crate::shape::ShapeFamily;

/// Which mixture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mix {
    LocalNonlocal,
    ClassicalLocal,
}

pub(crate) fn rate<S: Scalar>(
    m: &Model1D,
    z: &State1D<S>,
    out: &mut State1D<S>,
    mix: Mix,
) -> Result<()> {
    let vol = volumes(m, z);
    let st_nl = stencils(m, z, &z.x, m.p.shape, &vol)?;
    let st_loc = stencils(m, z, &z.x, ShapeFamily::Corrected, &vol)?;
    kinematics(z, out);
    let c = m.p.c_partition;
    let cm = m.p.modulus;
    for i in 0..z.x.len() {
        let g_nl = grad_v(z, i, &st_nl[i]);
        let g_loc = grad_v(z, i, &st_loc[i]);
        out.rho[i] = -z.rho[i] * (g_nl * (1.0 - c) + g_loc * c);
        out.sigma[i] = (z.sigma[i] + cm) * g_nl;
        out.tau[i] = (z.tau[i] + cm) * g_loc;
        let a_nl = match mix {
            Mix::LocalNonlocal => div_difference(&z.sigma, z.rho[i], i, &st_nl[i]),
            Mix::ClassicalLocal => div_sum(&z.sigma, &z.rho, i, &st_nl[i]),
        };
        let a_loc = div_difference(&z.tau, z.rho[i], i, &st_loc[i]);
        out.v[i] = a_nl * (1.0 - c) + a_loc * c + av_accel(m, z, i, &st_nl[i]);
    }
    Ok(())
}
