//! `local`: normalised corrected SPH \[V21 eq 40–44\].
//!
//! Velocity gradient and stress divergence both use the first-order corrected derivative
//! G_J(x_I) (shape family `corrected`, or `mls`), which reproduces derivatives of linear
//! fields exactly; since Σ_J G_J ≡ 0 the stress divergence is written in difference form:
//! ```text
//! v̇_I = (1/ρ_I) Σ_J (σ_J − σ_I) G_J(x_I),  (∂v/∂x)_I = Σ_J (v_J − v_I) G_J(x_I)
//! ```

use super::eulerian_common::{av_accel, div_difference, grad_v, kinematics, stencils, volumes};
use super::model::{Model1D, State1D};
use crate::error::Result;
use crate::scalar::Scalar;

pub(crate) fn rate<S: Scalar>(m: &Model1D, z: &State1D<S>, out: &mut State1D<S>) -> Result<()> {
    let vol = volumes(m, z);
    let st = stencils(m, z, &z.x, m.p.shape, &vol)?;
    kinematics(z, out);
    let c = m.p.modulus;
    for (i, sti) in st.iter().enumerate() {
        let g = grad_v(z, i, sti);
        out.rho[i] = -z.rho[i] * g;
        out.sigma[i] = (z.sigma[i] + c) * g;
        out.v[i] = div_difference(&z.sigma, z.rho[i], i, sti) + av_accel(m, z, i, sti);
    }
    Ok(())
}
