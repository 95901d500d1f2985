//! Reusable buffers of the 2D rate evaluation, so that a time loop does not allocate.
//!
//! A [`RateWorkspace`] holds everything [`Model2D::rate_with`](super::Model2D::rate_with) and
//! [`Model2D::rate_into`](super::Model2D::rate_into) need besides the state and the output: the
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

use super::model2d::{Model2D, StateView2D};
use crate::error::Result;
use crate::neighbours::CellList;
use crate::scalar::Scalar;
use crate::shape::ShapeFamily;
use crate::shape2d::eval2;
use rayon::prelude::*;

/// Neighbour J of an evaluation point: index, d = x_J − x, ∇φ_J.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Nb2<S> {
    pub j: usize,
    pub d: [S; 2],
    pub g: [S; 2],
}

/// The stencils of one particle: `a` with the form's shape family, `b` with corrected shape
/// functions (mixed forms only; empty otherwise).
#[derive(Clone, Debug)]
pub(crate) struct Stencil<S> {
    pub a: Vec<Nb2<S>>,
    pub b: Vec<Nb2<S>>,
}

impl<S> Default for Stencil<S> {
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
struct ShapeScratch<S> {
    nodes: Vec<([S; 2], S)>,
    idx: Vec<usize>,
    vals: Vec<(S, [S; 2])>,
}

impl<S> Default for ShapeScratch<S> {
    fn default() -> Self {
        Self {
            nodes: Vec::new(),
            idx: Vec::new(),
            vals: Vec::new(),
        }
    }
}

/// Per-particle auxiliary rates (ρ̇, σ̇, τ̇).
pub(crate) type AuxRate<S> = (S, [S; 3], [S; 3]);

/// Particles per parallel work item of the stencil build (each item owns one scratch).
const CHUNK: usize = 128;

/// Reusable buffers of the 2D rate evaluation (see the module docs). `S` is the scalar of the
/// state (`f64` for the solver, [`Dual`](crate::scalar::Dual) for the linearisation).
#[derive(Clone, Debug)]
pub struct RateWorkspace<S> {
    /// Positions' values (for the cell list).
    pos: Vec<[f64; 2]>,
    cells: CellList,
    /// V_J = m_J / ρ_J.
    vol: Vec<S>,
    pub(crate) stencils: Vec<Stencil<S>>,
    scratch: Vec<ShapeScratch<S>>,
    /// Hydrodynamic stress −p I from the density.
    pub(crate) hydro: Vec<[S; 3]>,
    /// Artificial-stress tensors R_I.
    pub(crate) art: Vec<[S; 3]>,
    pub(crate) aux: Vec<AuxRate<S>>,
    /// Displacements (total-Lagrangian forms).
    pub(crate) disp: Vec<[S; 2]>,
    /// What the current stencils were built for (`None`: nothing valid).
    key: Option<StencilKey>,
    key_x: Vec<[S; 2]>,
    key_rho: Vec<S>,
    key_mass: Vec<f64>,
}

/// The parameters the stencils depend on besides x, ρ and m.
#[derive(Clone, Copy, Debug, PartialEq)]
struct StencilKey {
    family: ShapeFamily,
    with_corrected: bool,
    kernel: &'static str,
    h: f64,
    period: Option<[[f64; 2]; 2]>,
}

impl<S> Default for RateWorkspace<S> {
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
            key: None,
            key_x: Vec::new(),
            key_rho: Vec::new(),
            key_mass: Vec::new(),
        }
    }
}

impl<S: Scalar> RateWorkspace<S> {
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
            .map(|s| (s.a.capacity() + s.b.capacity()) * size_of::<Nb2<S>>())
            .sum();
        let sc: usize = self
            .scratch
            .iter()
            .map(|s| {
                s.nodes.capacity() * size_of::<([S; 2], S)>()
                    + s.idx.capacity() * size_of::<usize>()
                    + s.vals.capacity() * size_of::<(S, [S; 2])>()
            })
            .sum();
        st + sc
            + self.stencils.capacity() * size_of::<Stencil<S>>()
            + self.scratch.capacity() * size_of::<ShapeScratch<S>>()
            + self.pos.capacity() * size_of::<[f64; 2]>()
            + self.vol.capacity() * size_of::<S>()
            + (self.hydro.capacity() + self.art.capacity()) * size_of::<[S; 3]>()
            + self.aux.capacity() * size_of::<AuxRate<S>>()
            + self.disp.capacity() * size_of::<[S; 2]>()
            + self.key_x.capacity() * size_of::<[S; 2]>()
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
        m: &Model2D,
        z: StateView2D<'_, S>,
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
        m: &Model2D,
        z: StateView2D<'_, S>,
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
        self.pos.extend(z.x.iter().map(|p| [p[0].re(), p[1].re()]));
        let grid = match m.period {
            None => {
                self.cells.rebuild(&self.pos, r, None);
                true
            }
            Some(l) if l[0][1] == 0.0 && l[1][0] == 0.0 => {
                self.cells.rebuild(&self.pos, r, Some([l[0][0], l[1][1]]));
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
        let (family, kp) = (m.p.shape, m.p.kp);
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
                        let (dx, dy) = (d[0].re(), d[1].re());
                        if dx * dx + dy * dy < r2 {
                            sc.nodes.push((d, vol[j]));
                            sc.idx.push(j);
                        }
                    };
                    if grid {
                        cells.for_candidates(pos[i], &mut visit);
                    } else {
                        (0..n).for_each(&mut visit);
                    }
                    eval2(family, kp, &sc.nodes, pos[i], &mut sc.vals)?;
                    fill(&mut st.a, sc);
                    if with_corrected {
                        eval2(ShapeFamily::Corrected, kp, &sc.nodes, pos[i], &mut sc.vals)?;
                        fill(&mut st.b, sc);
                    }
                }
                Ok(())
            })
    }
}

/// Refills a stencil from the scratch; on growth it reserves a quarter more than needed, so
/// that small changes of the neighbour count in a time loop do not reallocate.
fn fill<S: Scalar>(st: &mut Vec<Nb2<S>>, sc: &ShapeScratch<S>) {
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
            .map(|((&j, &(d, _)), &(_, g))| Nb2 { j, d, g }),
    );
}
