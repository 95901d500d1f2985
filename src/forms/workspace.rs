//! Reusable buffers of the rate evaluation in D dimensions, so that a time loop does not
//! allocate.
//!
//! A [`RateWorkspace`] holds everything [`Model::rate_with`](super::Model::rate_with) and
//! [`Model::rate_into`](super::Model::rate_into) need besides the state and the output: the
//! cell list, the volumes V_J = m_J/ρ_J, the hydrodynamic and artificial stresses, the
//! neighbour stencils (one `Vec` per particle, cleared and refilled), per-chunk scratch for the
//! shape-function evaluation, and the per-particle auxiliary rates. Every buffer is cleared and
//! refilled, never freed: once the buffers have grown (the first evaluation, or the first in
//! which a particle has more neighbours than ever before), an evaluation does not allocate.
//!
//! Results do not depend on what the workspace was used for before, so one workspace may serve
//! several models. The stencils are a function of the positions, the volumes and the kernel,
//! shape family and period only; an evaluation whose positions, densities, masses and those
//! parameters are *exactly* (bitwise) those of the previous one reuses them instead of
//! rebuilding them. The solver meets this case once per step with artificial viscosity: the
//! first kick's acceleration is evaluated where the previous step's last one was (same x and ρ,
//! other v), so one stencil build of three is saved.

// Small-vector algebra (D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::model_nd::{Model, StateView, Tensor};
use crate::error::Result;
use crate::neighbours::CellList;
use crate::scalar::Scalar;
use crate::shape::{ShapeFamily, eval_d};
use rayon::prelude::*;

/// Neighbour J of an evaluation point: index, d = x_J − x, ∇φ_J.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NbD<S, const D: usize> {
    pub j: usize,
    pub d: [S; D],
    pub g: [S; D],
}

/// The stencils of one particle: `a` with the form's shape family, `b` with corrected shape
/// functions (mixed forms only; empty otherwise).
#[derive(Clone, Debug)]
pub(crate) struct Stencil<S, const D: usize> {
    pub a: Vec<NbD<S, D>>,
    pub b: Vec<NbD<S, D>>,
}

impl<S, const D: usize> Default for Stencil<S, D> {
    fn default() -> Self {
        Self {
            a: Vec::new(),
            b: Vec::new(),
        }
    }
}

/// Scratch of the shape-function evaluation of one chunk of particles: (relative position,
/// volume), neighbour indices, (φ, ∇φ).
#[derive(Clone, Debug)]
struct ShapeScratch<S, const D: usize> {
    nodes: Vec<([S; D], S)>,
    idx: Vec<usize>,
    vals: Vec<(S, [S; D])>,
}

impl<S, const D: usize> Default for ShapeScratch<S, D> {
    fn default() -> Self {
        Self {
            nodes: Vec::new(),
            idx: Vec::new(),
            vals: Vec::new(),
        }
    }
}

/// Per-particle auxiliary rates (ρ̇, σ̇, τ̇).
pub(crate) type AuxRate<S, const D: usize> = (S, Tensor<S, D>, Tensor<S, D>);

/// Particles per parallel work item of the stencil build (each item owns one scratch).
const CHUNK: usize = 128;

/// Reusable buffers of the rate evaluation (see the module docs). `S` is the scalar of the
/// state (`f64` for the solver, [`Dual`](crate::scalar::Dual) for the linearisation), `D` the
/// dimension (2 by default).
#[derive(Clone, Debug)]
pub struct RateWorkspace<S, const D: usize = 2> {
    /// Positions' values (for the cell list).
    pos: Vec<[f64; D]>,
    cells: CellList<D>,
    /// V_J = m_J / ρ_J.
    vol: Vec<S>,
    pub(crate) stencils: Vec<Stencil<S, D>>,
    scratch: Vec<ShapeScratch<S, D>>,
    /// Hydrodynamic stress −p I from the density.
    pub(crate) hydro: Vec<Tensor<S, D>>,
    /// Artificial-stress tensors R_I.
    pub(crate) art: Vec<Tensor<S, D>>,
    pub(crate) aux: Vec<AuxRate<S, D>>,
    /// Displacements (total-Lagrangian forms).
    pub(crate) disp: Vec<[S; D]>,
    /// Antuono's renormalised density gradients ⟨∇ρ⟩_I (δ-SPH).
    pub(crate) rho_grad: Vec<[S; D]>,
    /// What the current stencils were built for (`None`: nothing valid).
    key: Option<StencilKey<D>>,
    key_x: Vec<[S; D]>,
    key_rho: Vec<S>,
    key_mass: Vec<f64>,
}

/// The parameters the stencils depend on besides x, ρ and m.
#[derive(Clone, Copy, Debug, PartialEq)]
struct StencilKey<const D: usize> {
    family: ShapeFamily,
    with_corrected: bool,
    kernel: &'static str,
    h: f64,
    period: Option<[[f64; D]; D]>,
}

impl<S, const D: usize> Default for RateWorkspace<S, D> {
    fn default() -> Self {
        Self {
            pos: Vec::new(),
            cells: CellList::default(),
            vol: Vec::new(),
            stencils: Vec::new(),
            scratch: Vec::new(),
            hydro: Vec::new(),
            art: Vec::new(),
            aux: Vec::new(),
            disp: Vec::new(),
            rho_grad: Vec::new(),
            key: None,
            key_x: Vec::new(),
            key_rho: Vec::new(),
            key_mass: Vec::new(),
        }
    }
}

impl<S: Scalar, const D: usize> RateWorkspace<S, D> {
    /// An empty workspace (allocates nothing until first used).
    pub fn new() -> Self {
        Self::default()
    }

    /// Mean number of neighbours per particle (the particle itself included) in the stencils
    /// of the last Eulerian evaluation; `None` before any.
    pub fn mean_neighbours(&self) -> Option<f64> {
        if self.stencils.is_empty() {
            return None;
        }
        let total: usize = self.stencils.iter().map(|s| s.a.len()).sum();
        Some(total as f64 / self.stencils.len() as f64)
    }

    /// Bytes reserved by the buffers (capacities, not lengths), for memory reports.
    pub fn reserved_bytes(&self) -> usize {
        use std::mem::size_of;
        let st: usize = self
            .stencils
            .iter()
            .map(|s| (s.a.capacity() + s.b.capacity()) * size_of::<NbD<S, D>>())
            .sum();
        let sc: usize = self
            .scratch
            .iter()
            .map(|s| {
                s.nodes.capacity() * size_of::<([S; D], S)>()
                    + s.idx.capacity() * size_of::<usize>()
                    + s.vals.capacity() * size_of::<(S, [S; D])>()
            })
            .sum();
        st + sc
            + self.stencils.capacity() * size_of::<Stencil<S, D>>()
            + self.scratch.capacity() * size_of::<ShapeScratch<S, D>>()
            + self.pos.capacity() * size_of::<[f64; D]>()
            + self.vol.capacity() * size_of::<S>()
            + (self.hydro.capacity() + self.art.capacity()) * size_of::<Tensor<S, D>>()
            + self.aux.capacity() * size_of::<AuxRate<S, D>>()
            + self.disp.capacity() * size_of::<[S; D]>()
            + self.rho_grad.capacity() * size_of::<[S; D]>()
            + self.key_x.capacity() * size_of::<[S; D]>()
            + self.key_rho.capacity() * size_of::<S>()
            + self.key_mass.capacity() * size_of::<f64>()
    }

    /// Rebuilds the stencils of every particle of `z`: the neighbours within the support
    /// (cell list for open domains and rectangular periodic boxes, direct scan otherwise) with
    /// ∇φ_J of the model's shape family, and with corrected shape functions in `b` when
    /// `with_corrected`. In parallel over chunks of particles (rayon). Kept as they are when
    /// built for exactly the same inputs (module docs).
    pub(crate) fn build_stencils(
        &mut self,
        m: &Model<D>,
        z: StateView<'_, S, D>,
        with_corrected: bool,
    ) -> Result<()> {
        let key = StencilKey {
            family: m.p.shape,
            with_corrected,
            kernel: m.p.kp.kernel.name(),
            h: m.p.kp.h,
            period: m.period,
        };
        if self.key == Some(key)
            && self.key_x == z.x
            && self.key_rho == z.rho
            && self.key_mass == m.mass
        {
            return Ok(());
        }
        self.key = None;
        self.rebuild_stencils(m, z, with_corrected)?;
        self.key = Some(key);
        self.key_x.clear();
        self.key_x.extend_from_slice(z.x);
        self.key_rho.clear();
        self.key_rho.extend_from_slice(z.rho);
        self.key_mass.clear();
        self.key_mass.extend_from_slice(&m.mass);
        Ok(())
    }

    fn rebuild_stencils(
        &mut self,
        m: &Model<D>,
        z: StateView<'_, S, D>,
        with_corrected: bool,
    ) -> Result<()> {
        let n = z.x.len();
        let r = m.p.kp.support();
        // |d| < r tested as |d|² < r² (no hypot: a quarter of the time of the whole rate went
        // into libm's hypot). The two can differ only within an ulp of the support radius,
        // where W and ∇W vanish.
        let r2 = r * r;
        self.vol.clear();
        self.vol.extend(
            z.rho
                .iter()
                .zip(&m.mass)
                .map(|(&rho, &ms)| S::cst(ms) / rho),
        );
        self.pos.clear();
        self.pos.extend(z.x.iter().map(|p| p.map(|c| c.re())));
        let grid = match m.period {
            None => {
                self.cells.rebuild(&self.pos, r, None);
                true
            }
            Some(l) if is_diagonal(&l) => {
                let mut ext = [0.0; D];
                for (a, e) in ext.iter_mut().enumerate() {
                    *e = l[a][a];
                }
                self.cells.rebuild(&self.pos, r, Some(ext));
                true
            }
            Some(_) => false,
        };
        if self.stencils.len() < n {
            self.stencils.resize_with(n, Stencil::default);
        }
        self.stencils.truncate(n);
        let chunks = n.div_ceil(CHUNK);
        if self.scratch.len() < chunks {
            self.scratch.resize_with(chunks, ShapeScratch::default);
        }
        let (pos, vol, cells) = (&self.pos, &self.vol, &self.cells);
        let family = m.p.shape;
        let kp = crate::shape::KernelParams {
            kernel: m.p.kp.kernel,
            h: m.p.kp.h,
        };
        self.stencils
            .par_chunks_mut(CHUNK)
            .zip(self.scratch[..chunks].par_iter_mut())
            .enumerate()
            .try_for_each(|(c, (chunk, sc))| -> Result<()> {
                for (k, st) in chunk.iter_mut().enumerate() {
                    let i = c * CHUNK + k;
                    sc.nodes.clear();
                    sc.idx.clear();
                    let xi = z.x[i];
                    let mut visit = |j: usize| {
                        let d = m.rel(xi, z.x[j]);
                        let mut d2 = d[0].re() * d[0].re();
                        for c in 1..D {
                            d2 += d[c].re() * d[c].re();
                        }
                        if d2 < r2 {
                            sc.nodes.push((d, vol[j]));
                            sc.idx.push(j);
                        }
                    };
                    if grid {
                        cells.for_candidates(pos[i], &mut visit);
                    } else {
                        (0..n).for_each(&mut visit);
                    }
                    eval_d(family, kp, &sc.nodes, pos[i][0], &mut sc.vals)?;
                    fill(&mut st.a, sc);
                    if with_corrected {
                        eval_d(
                            ShapeFamily::Corrected,
                            kp,
                            &sc.nodes,
                            pos[i][0],
                            &mut sc.vals,
                        )?;
                        fill(&mut st.b, sc);
                    }
                }
                Ok(())
            })
    }
}

/// Refills a stencil from the scratch; on growth it reserves a quarter more than needed, so
/// that small changes of the neighbour count in a time loop do not reallocate.
fn fill<S: Scalar, const D: usize>(st: &mut Vec<NbD<S, D>>, sc: &ShapeScratch<S, D>) {
    st.clear();
    let k = sc.idx.len();
    if st.capacity() < k {
        st.reserve_exact(k + k / 4);
    }
    st.extend(
        sc.idx
            .iter()
            .zip(&sc.nodes)
            .zip(&sc.vals)
            .map(|((&j, &(d, _)), &(_, g))| NbD { j, d, g }),
    );
}

/// Whether a periodic cell is a rectangular box (off-diagonal entries exactly zero).
fn is_diagonal<const D: usize>(l: &[[f64; D]; D]) -> bool {
    (0..D).all(|a| (0..D).all(|b| a == b || l[a][b] == 0.0))
}
