//! The box operator `D = −(J_vx + J_vq J_qv)` applied to a vector without forming it: two
//! directional derivatives of the run's rate function per product, with one dual number per
//! state entry (forward mode, exact to round-off).
//!
//! About a rest state the auxiliary rates (ρ̇, σ̇) are linear in the velocities and the
//! accelerations do not depend on them, so a displacement u of the free particles, with the
//! auxiliary perturbation q = J_qv u it builds up, is accelerated by (J_vx + J_vq J_qv) u:
//!
//! 1. the velocities of the free particles seeded with u: the tangents of the auxiliary rates
//!    are w = J_qv u (zero for the frozen boundary's fields, as in the solver);
//! 2. the positions of the free particles seeded with u and the auxiliary fields with w, at
//!    once: the tangents of the free particles' accelerations are J_vx u + J_vq w.
//!
//! The same reduction as the dense operator ([`box_growth`](super::box_growth)), which
//! evaluates one Jacobian column per rate evaluation instead. The velocity-seeded evaluations
//! keep a workspace of their own: their positions carry no tangent, so its stencils are built
//! once and reused (the position-seeded ones rebuild theirs every time: a third of the cost).

use crate::error::{Error, Result};
use crate::forms::{Comp, FieldKind, RateOut, RateWorkspace, State};
use crate::scalar::Dual;
use crate::scalar::Scalar as _;
use crate::solver::run::{BoundaryDensity, Run};

/// The box operator of a run about its current (rest) state, applied matrix-free.
pub struct BoxOperator<'a, const D: usize> {
    run: &'a Run<D>,
    /// Free particles, in index order: degree of freedom D·k + a is axis a of `free[k]`.
    free: Vec<usize>,
    /// The auxiliary components of the form (ρ for the Eulerian hydrodynamic forms).
    aux: Vec<Comp>,
    /// The state as dual numbers with zero tangents, and the seeded copy.
    base: State<Dual, D>,
    z: State<Dual, D>,
    out: State<Dual, D>,
    /// The workspace of the velocity-seeded evaluations (positions without tangents: its
    /// stencils are built once and reused), and that of the position-seeded ones.
    ws_v: RateWorkspace<Dual, D>,
    ws_x: RateWorkspace<Dual, D>,
    /// w = J_qv u, per auxiliary component and particle.
    w: Vec<f64>,
    products: usize,
}

impl<'a, const D: usize> BoxOperator<'a, D> {
    /// The operator of `run` (refused with artificial viscosity or density diffusion: the
    /// reduction holds for the undamped system only).
    pub fn new(run: &'a Run<D>) -> Result<Self> {
        if run.model.p.av.is_some() || run.model.p.diffusion.is_some() {
            return Err(Error::Incompatible(
                "the box operator is defined without artificial viscosity and density diffusion"
                    .into(),
            ));
        }
        let n = run.z.x.len();
        let aux: Vec<Comp> = run
            .model
            .p
            .form
            .comps(D, &run.model.p.material)
            .into_iter()
            .filter(|c| c.kind() == FieldKind::Auxiliary)
            .collect();
        let base: State<Dual, D> = run.z.map(Dual::cst);
        Ok(Self {
            run,
            free: (0..n).filter(|&i| !run.fixed[i]).collect(),
            w: vec![0.0; aux.len() * n],
            aux,
            z: base.clone(),
            out: State::zeros_like(&base),
            base,
            ws_v: RateWorkspace::new(),
            ws_x: RateWorkspace::new(),
            products: 0,
        })
    }

    /// Number of degrees of freedom (D × free particles).
    pub fn dofs(&self) -> usize {
        D * self.free.len()
    }

    /// Products computed so far.
    pub fn products(&self) -> usize {
        self.products
    }

    /// The velocities of the free particles in the run's state (the layout of a vector).
    pub fn free_velocities(&self) -> Vec<f64> {
        self.free.iter().flat_map(|&i| self.run.z.v[i]).collect()
    }

    /// `y = D u` (both of length [`BoxOperator::dofs`]).
    pub fn apply(&mut self, u: &[f64], y: &mut [f64]) -> Result<()> {
        let n = self.base.x.len();
        // 1. velocities seeded: w = J_qv u (nothing to do for a form without auxiliary fields)
        if !self.aux.is_empty() {
            self.z.clone_from(&self.base);
            for (k, &i) in self.free.iter().enumerate() {
                for a in 0..D {
                    self.z.v[i][a].d = u[D * k + a];
                }
            }
            let RateOut { aux, .. } = self.out.as_rate_out();
            self.run.model.rate_into(
                self.z.view(),
                RateOut {
                    aux,
                    ..RateOut::default()
                },
                &mut self.ws_v,
            )?;
            let frozen = self.run.boundary == BoundaryDensity::Frozen;
            for (ci, &c) in self.aux.iter().enumerate() {
                for i in 0..n {
                    self.w[ci * n + i] = if frozen && self.run.fixed[i] {
                        0.0
                    } else {
                        self.out.get(c, i).d
                    };
                }
            }
        }
        // 2. positions seeded with u, auxiliary fields with w: J_vx u + J_vq w
        self.z.clone_from(&self.base);
        for (k, &i) in self.free.iter().enumerate() {
            for a in 0..D {
                self.z.x[i][a].d = u[D * k + a];
            }
        }
        for (ci, &c) in self.aux.iter().enumerate() {
            for i in 0..n {
                let mut t = self.z.get(c, i);
                t.d = self.w[ci * n + i];
                self.z.set(c, i, t);
            }
        }
        let RateOut { v, .. } = self.out.as_rate_out();
        self.run.model.rate_into(
            self.z.view(),
            RateOut {
                v,
                ..RateOut::default()
            },
            &mut self.ws_x,
        )?;
        for (k, &i) in self.free.iter().enumerate() {
            for a in 0..D {
                y[D * k + a] = -self.out.v[i][a].d;
            }
        }
        self.products += 1;
        if y.iter().any(|v| !v.is_finite()) {
            return Err(Error::NonFinite("box operator product"));
        }
        Ok(())
    }
}
