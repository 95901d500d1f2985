//! `classical`: Eulerian kernel, collocation, Monaghan's symmetric sum form.
//!
//! ```text
//! ẋ_I = v_I
//! ρ̇_I = −ρ_I (∂v/∂x)_I,          (∂v/∂x)_I = Σ_J (v_J − v_I) ∂φ_J(x_I)          \[V21 eq 53\]
//! σ̇_I = (C + σ_I) (∂v/∂x)_I                                                        \[B00 eq 72, Truesdell\]
//! v̇_I = Σ_J (σ_I/ρ_I² + σ_J/ρ_J²) ρ_J ∂φ_J(x_I) − Σ_J m_J Π_IJ ∇_I W_IJ            \[V21 eq 55\]
//! ```
//! With `sph` shapes ρ_J ∂φ_J(x_I) = m_J ∇_I W_IJ, the textbook form. Closed forms: \[B00 eq 74\]
//! (which linearises the σ_J-only nodal-integration force: see analysis/ERRATA.md) and Swegle's
//! analysis \[V21 App. B\].

use super::eulerian_common::{av_accel, div_sum, grad_v, kinematics, stencils, volumes};
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
        out.v[i] = div_sum(&z.sigma, &z.rho, i, sti) + av_accel(m, z, i, sti);
    }
    Ok(())
}
