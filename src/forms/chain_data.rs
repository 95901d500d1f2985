//! The reference data of the 1D-only forms of \[B00\], built once with the model: the stress
//! points (mid-intervals, \[B00 §4.2\]), the reference stencils of the Lagrangian forms (φ, φ',
//! φ'' at masters and stress points) and the constant matrices of the least-squares form
//! (\[B00 eq 106–107\]).

use super::chain_search::ChainSearch;
use super::kind::FormKind;
use super::params::ModelParams;
use crate::error::Result;
use crate::scalar::Scalar;
use crate::shape::{self, KernelParams, ShapeFamily};
use std::collections::BTreeMap;

/// Mass operator of the semi-discrete system.
#[derive(Clone, Debug, PartialEq)]
pub enum MassOperator {
    /// Diagonal (lumped) masses: the `v` rate is the acceleration.
    Lumped,
    /// Consistent mass rows `M_IK` (sparse): the `v` rate is the force of `M a = f`.
    Consistent(Vec<Vec<(usize, f64)>>),
}

/// Shape functions of the masters near one evaluation point, on the reference configuration.
#[derive(Clone, Debug, Default)]
pub(crate) struct RefStencil {
    /// Master index, φ, φ', φ''.
    pub(crate) entries: Vec<(usize, [f64; 3])>,
}

/// The data of a 1D-only form of \[B00\] (stress points, Lagrangian reference stencils,
/// least-squares matrices), on a chain of masters.
#[derive(Clone, Debug)]
pub(crate) struct ChainData {
    /// Period of a periodic chain (None: open chain).
    pub(crate) period: Option<f64>,
    /// Stress-point reference positions (stress-point forms only).
    pub(crate) sp_x_ref: Vec<f64>,
    /// Stress-point reference volumes.
    pub(crate) sp_vol_ref: Vec<f64>,
    /// Master-node integration weights of the stress-point forms (V0/2 in \[B00 eq 84/100\]).
    pub(crate) master_weight_ref: Vec<f64>,
    /// Reference stencils at masters (Lagrangian forms).
    pub(crate) ref_master: Vec<RefStencil>,
    /// Reference stencils at stress points (Lagrangian stress points).
    pub(crate) ref_sp: Vec<RefStencil>,
    /// Least-squares stiffness rows K_IK.
    pub(crate) ls_stiffness: Vec<Vec<(usize, f64)>>,
    /// Mass operator.
    pub(crate) mass_op: MassOperator,
}

impl ChainData {
    /// The data of form `p.form` for masters at `x_ref` with volumes `vol_ref`, tangent modulus
    /// `modulus` and pre-stress `sigma0`. Stress points (for the stress-point forms) are placed
    /// at the mid-points of consecutive masters (and of the last and first for a periodic
    /// chain).
    pub(crate) fn new(
        p: &ModelParams,
        modulus: f64,
        sigma0: f64,
        x_ref: &[f64],
        vol_ref: &[f64],
        period: Option<f64>,
    ) -> Result<Self> {
        let n = x_ref.len();
        let (mut sp_x_ref, mut sp_vol_ref) = (Vec::new(), Vec::new());
        let mut master_weight_ref = vol_ref.to_vec();
        if p.form.has_stress_points() {
            let m = if period.is_some() {
                n
            } else {
                n.saturating_sub(1)
            };
            for i in 0..m {
                let j = (i + 1) % n;
                let mut xj = x_ref[j];
                if let (Some(l), 0) = (period, j) {
                    xj += l;
                }
                sp_x_ref.push(0.5 * (x_ref[i] + xj));
                sp_vol_ref.push(0.25 * (vol_ref[i] + vol_ref[j]));
            }
            master_weight_ref = vol_ref.iter().map(|v| 0.5 * v).collect();
        }
        let mut data = ChainData {
            period,
            sp_x_ref,
            sp_vol_ref,
            master_weight_ref,
            ref_master: Vec::new(),
            ref_sp: Vec::new(),
            ls_stiffness: Vec::new(),
            mass_op: MassOperator::Lumped,
        };
        if p.form.is_lagrangian() {
            let kp = p.kp;
            let mut search = ChainSearch::default();
            search.prepare_positions(period, x_ref.iter().copied());
            data.ref_master = x_ref
                .iter()
                .map(|&x| data.ref_stencil(p.shape, kp, x_ref, vol_ref, x, &mut search))
                .collect::<Result<_>>()?;
            if p.form == FormKind::LagrangianStressPoints {
                search.restart();
                data.ref_sp = data
                    .sp_x_ref
                    .iter()
                    .map(|&x| data.ref_stencil(p.shape, kp, x_ref, vol_ref, x, &mut search))
                    .collect::<Result<_>>()?;
            }
            if p.form == FormKind::LeastSquares {
                data.assemble_least_squares(p, modulus, sigma0, vol_ref);
            }
        }
        Ok(data)
    }

    /// Minimum-image relative position `b − a` along the chain.
    #[inline]
    pub(crate) fn rel<S: Scalar>(&self, a: S, b: S) -> S {
        let d = b - a;
        match self.period {
            Some(l) => {
                let k = (d.re() / l).round();
                if k != 0.0 { d - k * l } else { d }
            }
            None => d,
        }
    }

    /// Shape functions of all masters within the support of reference point `x` (masters
    /// found by `search`, prepared for the reference positions; O(1) per point along an
    /// ordered chain).
    fn ref_stencil(
        &self,
        shape: ShapeFamily,
        kp: KernelParams,
        x_ref: &[f64],
        vol_ref: &[f64],
        x: f64,
        search: &mut ChainSearch,
    ) -> Result<RefStencil> {
        let r = kp.support();
        let mut nodes = Vec::new();
        let mut idx = Vec::new();
        let mut cand = Vec::new();
        search.candidates(x, r, &mut cand);
        for j in cand {
            let d = self.rel(x, x_ref[j]);
            if d.abs() < r {
                nodes.push((d, vol_ref[j]));
                idx.push(j);
            }
        }
        let vals = shape::eval_with_second(shape, kp, &nodes, x)?;
        Ok(RefStencil {
            entries: idx.into_iter().zip(vals).collect(),
        })
    }

    /// The constant matrices of the least-squares form \[B00 eq 106–107\], β = α_s l_c²:
    /// ```text
    /// M_IK = Σ_J ρ0 V_J [φ_I(X_J) φ_K(X_J) − β φ''_I(X_J) φ_K(X_J)]
    /// K_IK = Σ_J C̄ V_J [φ'_I(X_J) φ'_K(X_J) + β φ''_I(X_J) φ''_K(X_J)],   C̄ = C + σ0
    /// ```
    fn assemble_least_squares(&mut self, p: &ModelParams, modulus: f64, sigma0: f64, vol: &[f64]) {
        let n = vol.len();
        let beta = p.alpha_s * p.ls_length * p.ls_length;
        let cbar = modulus + sigma0;
        let mut k: Vec<BTreeMap<usize, f64>> = vec![BTreeMap::new(); n];
        let mut mm: Vec<BTreeMap<usize, f64>> = vec![BTreeMap::new(); n];
        for (j, st) in self.ref_master.iter().enumerate() {
            let vj = vol[j];
            for &(a, [pa, da, d2a]) in &st.entries {
                for &(b, [pb, db, d2b]) in &st.entries {
                    *k[a].entry(b).or_insert(0.0) += cbar * vj * (da * db + beta * d2a * d2b);
                    *mm[a].entry(b).or_insert(0.0) += p.rho0 * vj * (pa * pb - beta * d2a * pb);
                }
            }
        }
        self.ls_stiffness = k.into_iter().map(|r| r.into_iter().collect()).collect();
        self.mass_op =
            MassOperator::Consistent(mm.into_iter().map(|r| r.into_iter().collect()).collect());
    }
}

/// A 1D-only model seen as flat 1D data.
pub(crate) struct ChainModel<'a> {
    pub(crate) p: &'a ModelParams,
    pub(crate) data: &'a ChainData,
    pub(crate) mass: &'a [f64],
    pub(crate) x_ref: &'a [f64],
    /// Tangent modulus C.
    pub(crate) modulus: f64,
    /// Pre-stress σ0.
    pub(crate) sigma0: f64,
}

/// The state of a 1D-only form as flat 1D arrays (fields it does not carry are empty).
#[derive(Clone, Copy)]
pub(crate) struct ChainState<'a, S> {
    pub(crate) x: &'a [S],
    pub(crate) v: &'a [S],
    pub(crate) rho: &'a [S],
    pub(crate) sigma: &'a [S],
    pub(crate) sp_x: &'a [S],
    pub(crate) sp_sigma: &'a [S],
    pub(crate) sp_vol: &'a [S],
}
