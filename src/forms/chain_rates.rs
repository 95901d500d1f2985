//! The rate function of the 1D-only forms of \[B00\] (`eulerian-stress-points`,
//! `eulerian-nodal`, `lagrangian-stress-points`, `least-squares`) on the fields of the one
//! [`Model`]: the model refuses these forms for D > 1, so the state's D = 1 fields are read as
//! flat 1D arrays (`[[S; 1]]` viewed as `[S]`, no copy).

use super::chain_data::{ChainData, ChainModel, ChainState};
use super::chain_search::{ChainRates, ChainWorkspace};
use super::kind::FormKind;
use super::model::Model;
use super::state::{RateOut, StateView};
use super::workspace::RateWorkspace;
use super::{lagrangian_stress_points, least_squares, stress_points};
use crate::error::{Error, Result};
use crate::scalar::Scalar;

fn fit<S: Scalar>(v: &mut Vec<S>, n: usize) {
    v.clear();
    v.resize(n, S::zero());
}

fn copy_into<S: Scalar>(dst: &mut [S], src: &[S]) -> Result<()> {
    if dst.len() != src.len() {
        return Err(Error::Incompatible(
            format!(
                "rate output: {} entries for a field of {}",
                dst.len(),
                src.len()
            )
            .into(),
        ));
    }
    dst.copy_from_slice(src);
    Ok(())
}

/// The rate of a 1D-only form into the requested parts of `out` (every part is computed; the
/// 1D chains are short).
pub(crate) fn rate<S: Scalar, const D: usize>(
    m: &Model<D>,
    data: &ChainData,
    z: StateView<'_, S, D>,
    out: RateOut<'_, S, D>,
    ws: &mut RateWorkspace<S, D>,
) -> Result<()> {
    debug_assert_eq!(D, 1, "the model refuses the 1D-only forms for D > 1");
    let cm = ChainModel {
        p: &m.p,
        data,
        mass: &m.mass,
        x_ref: m.x_ref.as_flattened(),
        modulus: m.p.material.modulus(),
        sigma0: m.sigma0,
    };
    let zc = ChainState {
        x: z.x.as_flattened(),
        v: z.v.as_flattened(),
        rho: z.rho,
        sigma: z.sigma.as_flattened().as_flattened(),
        sp_x: z.sp_x.as_flattened(),
        sp_sigma: z.sp_sigma.as_flattened().as_flattened(),
        sp_vol: z.sp_vol,
    };
    let ChainWorkspace { rate: r, .. } = &mut ws.chain;
    fit(&mut r.x, zc.x.len());
    fit(&mut r.v, zc.v.len());
    fit(&mut r.rho, zc.rho.len());
    fit(&mut r.sigma, zc.sigma.len());
    fit(&mut r.sp_x, zc.sp_x.len());
    fit(&mut r.sp_sigma, zc.sp_sigma.len());
    fit(&mut r.sp_vol, zc.sp_vol.len());
    match m.p.form {
        FormKind::LagrangianStressPoints => lagrangian_stress_points::rate(&cm, zc, &mut ws.chain),
        FormKind::EulerianStressPoints | FormKind::EulerianNodal => {
            stress_points::rate(&cm, zc, &mut ws.chain)?
        }
        FormKind::LeastSquares => least_squares::rate(&cm, zc, &mut ws.chain.rate),
        f => {
            return Err(Error::Incompatible(
                format!("form {}: not a 1D-only form of [B00]", f.name()).into(),
            ));
        }
    }
    let r: &ChainRates<S> = &ws.chain.rate;
    if let Some(x) = out.x {
        copy_into(x.as_flattened_mut(), &r.x)?;
    }
    if let Some(v) = out.v {
        copy_into(v.as_flattened_mut(), &r.v)?;
    }
    if let Some(a) = out.aux {
        let parts: [(&mut [S], &[S]); 5] = [
            (a.rho, &r.rho),
            (a.sigma.as_flattened_mut().as_flattened_mut(), &r.sigma),
            (a.sp_x.as_flattened_mut(), &r.sp_x),
            (
                a.sp_sigma.as_flattened_mut().as_flattened_mut(),
                &r.sp_sigma,
            ),
            (a.sp_vol, &r.sp_vol),
        ];
        for (dst, src) in parts {
            // an empty output part is not requested
            if !dst.is_empty() {
                copy_into(dst, src)?;
            }
        }
    }
    Ok(())
}
