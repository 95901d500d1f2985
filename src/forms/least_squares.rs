//! `least-squares`: Beissel–Belytschko stabilised nodal integration \[B00 §4.3, eq 104–107\],
//! Lagrangian kernel. The weak form adds (β/E)∫δσ_{,x}(σ_{,x} − ρü) with β = α_s l_c²
//! (l_c = Δx), giving constant matrices built once on the reference configuration:
//! ```text
//! M_IK = Σ_J ρ0 V_J [φ_I(X_J) φ_K(X_J) − β φ''_I(X_J) φ_K(X_J)]               [eq 106]
//! K_IK = Σ_J C̄ V_J [φ'_I(X_J) φ'_K(X_J) + β φ''_I(X_J) φ''_K(X_J)]            [eq 107]
//! M ü = −K u,   C̄ = C + σ0 (the tangent of the pre-stressed material, = E when σ0 = 0)
//! ```
//! The `v` rate returned is the force f = −K u; the mass operator is consistent.

use super::model::{MassOperator, Model1D, State1D};
use crate::error::Result;
use crate::scalar::Scalar;
use std::collections::BTreeMap;

pub(crate) fn assemble(m: &mut Model1D) {
    let n = m.x_ref.len();
    let beta = m.p.alpha_s * m.p.dx * m.p.dx;
    let cbar = m.p.modulus + m.p.sigma0;
    let mut k: Vec<BTreeMap<usize, f64>> = vec![BTreeMap::new(); n];
    let mut mm: Vec<BTreeMap<usize, f64>> = vec![BTreeMap::new(); n];
    for (j, st) in m.ref_master.iter().enumerate() {
        let vj = m.vol_ref[j];
        for &(a, [pa, da, d2a]) in &st.entries {
            for &(b, [pb, db, d2b]) in &st.entries {
                *k[a].entry(b).or_insert(0.0) += cbar * vj * (da * db + beta * d2a * d2b);
                *mm[a].entry(b).or_insert(0.0) += m.p.rho0 * vj * (pa * pb - beta * d2a * pb);
            }
        }
    }
    m.ls_stiffness = k.into_iter().map(|r| r.into_iter().collect()).collect();
    m.mass_op = MassOperator::Consistent(mm.into_iter().map(|r| r.into_iter().collect()).collect());
}

pub(crate) fn rate<S: Scalar>(m: &Model1D, z: &State1D<S>, out: &mut State1D<S>) -> Result<()> {
    out.x.copy_from_slice(&z.v);
    for (i, row) in m.ls_stiffness.iter().enumerate() {
        let mut f = S::zero();
        for &(k, kik) in row {
            f -= (z.x[k] - m.x_ref[k]) * kik;
        }
        out.v[i] = f;
    }
    Ok(())
}
