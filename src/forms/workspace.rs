//! Reusable buffers of the rate evaluation in D dimensions, so that a time loop does not
//! allocate, and the compact neighbour stencils.
//!
//! A [`RateWorkspace`] holds everything [`Model::rate_with`](super::Model::rate_with) and
//! [`Model::rate_into`](super::Model::rate_into) need besides the state and the output: the
//! cell list, the volumes V_J = m_J/ρ_J, the hydrodynamic and artificial stresses, the
//! neighbour stencils and per-chunk scratch for the shape-function evaluation. Every buffer is
//! cleared and refilled, never freed: once the buffers have grown (the first evaluation, or the
//! first in which there are more neighbour pairs than ever before), an evaluation does not
//! allocate.
//!
//! # Compact stencils
//!
//! Everything the rate needs of a neighbour pair that depends on its separation only is
//! computed once per *unordered* pair {I, J} when the stencils are built, and stored once:
//!
//! - `ab = I xor J` (4 B): from either end, the other one is `ab xor I`;
//! - `f = −W'(r)/r` (one scalar): the kernel gradient is ∇_I W_IJ = f (x_J − x_I), antisymmetric,
//!   with x_J − x_I recomputed from the positions (a subtraction; minimum image in a periodic
//!   box), bitwise the separation the stencil was built from;
//! - with artificial stress, the factor fⁿ_IJ = (W(r)/W(Δp))ⁿ (one scalar).
//!
//! Each particle then lists its neighbours as 4-byte pair indices (CSR: `start`, `entry`), by
//! increasing neighbour index; the pairs it owns (J ≥ I) are numbered consecutively. The SPH shape functions need nothing more (∇φ_J = V_J ∇_I W_IJ
//! with the current volumes); other shape families (Shepard, corrected, MLS) are not symmetric
//! and store ∇φ_J per directed entry (`ga`), as do the corrected functions of the mixed forms
//! (`gb`). The particle itself is listed only where its ∇φ can be nonzero (non-SPH families).
//! No kernel is evaluated inside a rate evaluation besides the stencil build.
//!
//! Results do not depend on what the workspace was used for before, so one workspace may serve
//! several models. The stencils are a function of the positions (and, for the non-SPH shape
//! families, of the volumes), the kernel, shape family, artificial-stress factor and period
//! only; an evaluation whose inputs are *exactly* (bitwise) those of the previous one reuses
//! them instead of rebuilding them. The solver meets this case once per step with artificial
//! viscosity: the first kick's acceleration is evaluated where the previous step's last one
//! was (same x and ρ, other v), so one stencil build of three is saved.
//!
//! # Reusing the pairs: a Verlet list with a skin
//!
//! Each particle lists its neighbours by increasing index, whatever order the cell search finds
//! them in, so the stencils — and the summation order of every rate term — are a function of
//! the positions alone, not of the cell grid (whose origin follows the particles' bounding box).
//!
//! Between two builds the particles of a run move by a small fraction of the support, and the
//! pairs rarely change. A full build therefore lists every pair closer than r + s, the support
//! radius r = ζh plus a skin s = [`default_skin`] × r (the Verlet list of molecular
//! dynamics), and gives the pairs beyond r zero kernel data. A later build keeps that list and only recomputes the
//! pairs' data (−W'/r, fⁿ, zero beyond r) while every particle has moved less than s/2 since the
//! full build (the rule of LAMMPS and GROMACS): a pair not listed was at least r + s apart and
//! has closed by less than s, so no pair within r is missing. The pairs listed but beyond r add
//! exact zeros to every rate sum, which leaves each sum bitwise unchanged (x + 0 = x), so the
//! results are bitwise those of a full search at every evaluation (tested on stable,
//! large-motion, lattice-degenerate and unstable runs, [`RateWorkspace::set_pair_reuse`]). A
//! lattice whose neighbours sit exactly on the support radius (h/Δx = 1 with ζ = 2) is no special
//! case. Non-SPH shape families (whose ∇φ depend on every neighbour) and scalars with a tangent
//! always build in full, with s = 0. A diverging run (non-finite positions) makes every build
//! full.

// Small-vector algebra (D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::chain_search::ChainWorkspace;
use super::model::Model;
use super::state::{StateView, Tensor};
use crate::error::{Error, Result};
use crate::kernel;
use crate::neighbours::CellList;
use crate::scalar::Scalar;
use crate::shape::{ShapeFamily, eval_d};
use rayon::prelude::*;

/// One neighbour J of particle I as the rate loops see it (expanded from the compact stencil,
/// never stored): index, d = x_J − x_I, ∇_I W_IJ, ∇φ_J(x_I) of the form's shape family, and
/// the pair's index in the pair arrays.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NbD<S, const D: usize> {
    pub j: usize,
    pub d: [S; D],
    /// ∇_I W_IJ = −W'(r) d/r.
    pub gw: [S; D],
    /// ∇φ_J(x_I).
    pub g: [S; D],
    pub p: usize,
}

/// The compact stencils of every particle (module docs).
#[derive(Clone, Debug)]
pub(crate) struct Stencils<S, const D: usize> {
    /// Directed entries of particle I: `entry[start[I]..start[I + 1]]` (n + 1 offsets).
    start: Vec<u32>,
    /// Pairs owned by I (J ≥ I): `upper[I]..upper[I + 1]`.
    upper: Vec<u32>,
    /// Pair index of each directed entry.
    entry: Vec<u32>,
    /// I xor J of each pair.
    ab: Vec<u32>,
    /// −W'(r)/r of each pair.
    pub f: Vec<S>,
    /// Artificial-stress factor (W(r)/W(Δp))ⁿ of each pair (empty without artificial stress).
    pub fnn: Vec<S>,
    /// ∇φ_J of the form's family per directed entry (empty for the SPH family).
    ga: Vec<[S; D]>,
    /// Corrected ∇φ_J per directed entry (mixed forms only; empty otherwise).
    gb: Vec<[S; D]>,
    /// Whether a particle lists itself.
    with_self: bool,
}

impl<S, const D: usize> Default for Stencils<S, D> {
    fn default() -> Self {
        Self {
            start: Vec::new(),
            upper: Vec::new(),
            entry: Vec::new(),
            ab: Vec::new(),
            f: Vec::new(),
            fnn: Vec::new(),
            ga: Vec::new(),
            gb: Vec::new(),
            with_self: false,
        }
    }
}

impl<S: Scalar, const D: usize> Stencils<S, D> {
    /// Number of particles of the last build.
    fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    /// Calls `visit` for every neighbour of particle `i` in stencil `a` (`b`: the corrected
    /// one of the mixed forms), with the separation recomputed from `x` by `m.rel` and the
    /// volumes `vol` (∇φ of the SPH family).
    #[inline]
    pub(crate) fn for_each<const B: bool>(
        &self,
        m: &Model<D>,
        x: &[[S; D]],
        vol: &[S],
        i: usize,
        mut visit: impl FnMut(NbD<S, D>),
    ) {
        let (e0, e1) = (self.start[i] as usize, self.start[i + 1] as usize);
        let xi = x[i];
        for e in e0..e1 {
            let p = self.entry[e] as usize;
            let j = (self.ab[p] ^ i as u32) as usize;
            let d = m.rel(xi, x[j]);
            let f = self.f[p];
            let gw = d.map(|c| f * c);
            let g = if B {
                self.gb[e]
            } else if self.ga.is_empty() {
                let vj = vol[j];
                gw.map(|c| vj * c)
            } else {
                self.ga[e]
            };
            visit(NbD { j, d, gw, g, p });
        }
    }

    /// Directed entries in total.
    fn entries(&self) -> usize {
        self.entry.len()
    }

    /// Owned pairs in total.
    fn pairs(&self) -> usize {
        self.upper.last().map_or(0, |&u| u as usize)
    }
}

/// Scratch of the stencil build of one chunk of particles: the neighbours found (index,
/// relative position), their (relative position, volume) for the non-SPH shape functions, and
/// (φ, ∇φ) of the family and of the corrected functions.
#[derive(Clone, Debug)]
struct ShapeScratch<S, const D: usize> {
    /// Neighbours as the search finds them.
    found: Vec<u32>,
    nodes: Vec<([S; D], S)>,
    vals: Vec<(S, [S; D])>,
    vals_b: Vec<(S, [S; D])>,
}

impl<S, const D: usize> Default for ShapeScratch<S, D> {
    fn default() -> Self {
        Self {
            found: Vec::new(),
            nodes: Vec::new(),
            vals: Vec::new(),
            vals_b: Vec::new(),
        }
    }
}

/// Top bit of a directed entry between passes 2 and 3: a neighbour index, not yet a pair.
const LOWER: u32 = 1 << 31;

/// Particles per parallel work item of the stencil build (each item owns one scratch).
const CHUNK: usize = 128;

/// Cell side of the neighbour search over the list radius: slightly more than 1, so that the
/// rounding of the cell index can never put two particles closer than the list radius more
/// than one cell apart.
const CELL_SIDE: f64 = 1.0 + 1.0 / 16.0;

/// Cells per list radius of the neighbour search by dimension (index D): the candidates of a
/// particle are the (2s + 1)^D cells of side ≥ r/s around its own. Chosen from measured cost
/// (docs/throughput.md, "The skin").
const CELL_SUB: [usize; 4] = [1, 1, 1, 2];

/// The default skin of the pair list in `dim` dimensions, as a fraction s of the support radius
/// r: a full build lists the pairs within (1 + s) r, and later builds reuse them while no
/// particle has moved s r/2 (module docs). 0.05 in 1D and 2D, 0.1 in 3D, chosen from measured
/// cost (docs/throughput.md, "The skin"): a full search costs more against a step in 3D than
/// in 2D, so it pays to search half as often for the (1.1/1.05)³ − 1 = 15% more pairs the
/// wider skin lists.
pub const fn default_skin(dim: usize) -> f64 {
    if dim >= 3 { 0.1 } else { 0.05 }
}

/// Reusable buffers of the rate evaluation (see the module docs). `S` is the scalar of the
/// state (`f64` for the solver, [`Dual`](crate::scalar::Dual) for the linearisation), `D` the
/// dimension (2 by default).
#[derive(Clone, Debug)]
pub struct RateWorkspace<S, const D: usize = 2> {
    /// Positions' values (for the cell list; for a value-only `S`, the key of the stencils).
    pos: Vec<[f64; D]>,
    cells: CellList<D>,
    /// V_J = m_J / ρ_J.
    pub(crate) vol: Vec<S>,
    pub(crate) st: Stencils<S, D>,
    scratch: Vec<ShapeScratch<S, D>>,
    /// Hydrodynamic stress −p I from the density.
    pub(crate) hydro: Vec<Tensor<S, D>>,
    /// Artificial-stress tensors R_I.
    pub(crate) art: Vec<Tensor<S, D>>,
    /// Displacements (total-Lagrangian forms).
    pub(crate) disp: Vec<[S; D]>,
    /// Deformation gradients at the particles (total-Lagrangian forms with a pairwise term).
    pub(crate) defgrad: Vec<Tensor<S, D>>,
    /// Nodal first Piola–Kirchhoff stresses (tl-enog's pair form of the momentum).
    pub(crate) piola: Vec<Tensor<S, D>>,
    /// Antuono's renormalised density gradients ⟨∇ρ⟩_I (δ-SPH).
    pub(crate) rho_grad: Vec<[S; D]>,
    /// What the current stencils were built for (`None`: nothing valid).
    key: Option<StencilKey<D>>,
    /// Positions of the build, for scalars with a tangent (value-only ones use `pos`).
    key_x: Vec<[S; D]>,
    /// Densities and masses of the build (non-SPH shape families only).
    key_rho: Vec<S>,
    key_mass: Vec<f64>,
    /// Positions at the last full build (the reference of the skin rule).
    built: Vec<[f64; D]>,
    /// Radius of the pair list of the last full build (r + skin; 0: no list to reuse).
    list_r: f64,
    /// Skin as a fraction of the support radius ([`default_skin`]).
    skin: f64,
    /// Owned pairs within the support radius at the last build (the others have zero data).
    within: usize,
    /// Whether valid pairs are reused (default; off: every build is a full one).
    reuse: bool,
    /// Full builds and pair refreshes so far.
    builds: (u64, u64),
    /// The buffers of the 1D-only forms of \[B00\] (empty for the others).
    pub(crate) chain: ChainWorkspace<S>,
}

/// The parameters the stencils depend on besides x (and ρ, m for non-SPH families).
#[derive(Clone, Copy, Debug, PartialEq)]
struct StencilKey<const D: usize> {
    family: ShapeFamily,
    with_corrected: bool,
    kernel: &'static str,
    h: f64,
    period: Option<[[f64; D]; D]>,
    /// (n, Δp) of the artificial-stress factor.
    art: Option<(i32, f64)>,
}

impl<S, const D: usize> Default for RateWorkspace<S, D> {
    fn default() -> Self {
        Self {
            pos: Vec::new(),
            cells: CellList::default(),
            vol: Vec::new(),
            st: Stencils::default(),
            scratch: Vec::new(),
            hydro: Vec::new(),
            art: Vec::new(),
            disp: Vec::new(),
            defgrad: Vec::new(),
            piola: Vec::new(),
            rho_grad: Vec::new(),
            key: None,
            key_x: Vec::new(),
            key_rho: Vec::new(),
            key_mass: Vec::new(),
            built: Vec::new(),
            list_r: 0.0,
            skin: default_skin(D),
            within: 0,
            reuse: true,
            builds: (0, 0),
            chain: ChainWorkspace::default(),
        }
    }
}

/// Raw pointer to a buffer written in parallel at disjoint indices.
pub(crate) struct Shared<T>(pub(crate) *mut T);
impl<T> Clone for Shared<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Shared<T> {}
// SAFETY: used only to write disjoint elements from different threads (see each use).
unsafe impl<T> Send for Shared<T> {}
// SAFETY: as above.
unsafe impl<T> Sync for Shared<T> {}

impl<T> Shared<T> {
    /// Writes element `k`.
    ///
    /// # Safety
    /// `k` is in bounds of the buffer and no other thread reads or writes element `k`
    /// meanwhile.
    #[inline]
    pub(crate) unsafe fn write(self, k: usize, v: T) {
        // SAFETY: the caller's contract.
        unsafe { self.0.add(k).write(v) }
    }

    /// Reads element `k`.
    ///
    /// # Safety
    /// `k` is in bounds, initialised, and no other thread writes element `k` meanwhile.
    #[inline]
    pub(crate) unsafe fn read(self, k: usize) -> T {
        // SAFETY: the caller's contract.
        unsafe { self.0.add(k).read() }
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
        let n = self.st.len();
        if n == 0 {
            return None;
        }
        let own = if self.st.with_self { 0 } else { n };
        // listed within the skin but outside the support: not neighbours (zero data)
        let beyond = 2 * (self.st.pairs() - self.within);
        Some((self.st.entries() - beyond + own) as f64 / n as f64)
    }

    /// The skin of the pair list as a fraction of the support radius, in [0, 1] (default
    /// [`default_skin`]; module docs): larger lists more pairs, reused for longer. Results are
    /// bitwise the same for every skin.
    pub fn set_skin(&mut self, fraction: f64) {
        self.skin = fraction.clamp(0.0, 1.0);
        self.list_r = 0.0;
    }

    /// Whether stencil builds reuse the pairs of the last full build while they are provably
    /// unchanged (default `true`; module docs, "Reusing the pairs"). Results are bitwise the
    /// same either way; `false` makes every build a full one (for measuring what the reuse
    /// saves, and for testing it).
    pub fn set_pair_reuse(&mut self, on: bool) {
        self.reuse = on;
    }

    /// (full builds, pair refreshes) of the stencils since the workspace was created.
    pub fn stencil_builds(&self) -> (u64, u64) {
        self.builds
    }

    /// Bytes reserved by the buffers (capacities, not lengths), for memory reports.
    pub fn reserved_bytes(&self) -> usize {
        use std::mem::size_of;
        let st = &self.st;
        let stencils =
            (st.start.capacity() + st.upper.capacity() + st.entry.capacity() + st.ab.capacity())
                * size_of::<u32>()
                + (st.f.capacity() + st.fnn.capacity()) * size_of::<S>()
                + (st.ga.capacity() + st.gb.capacity()) * size_of::<[S; D]>();
        let sc: usize = self
            .scratch
            .iter()
            .map(|s| {
                s.found.capacity() * size_of::<u32>()
                    + s.nodes.capacity() * size_of::<([S; D], S)>()
                    + (s.vals.capacity() + s.vals_b.capacity()) * size_of::<(S, [S; D])>()
            })
            .sum();
        stencils
            + sc
            + self.scratch.capacity() * size_of::<ShapeScratch<S, D>>()
            + self.cells.reserved_bytes()
            + self.pos.capacity() * size_of::<[f64; D]>()
            + self.vol.capacity() * size_of::<S>()
            + (self.hydro.capacity() + self.art.capacity()) * size_of::<Tensor<S, D>>()
            + self.disp.capacity() * size_of::<[S; D]>()
            + self.rho_grad.capacity() * size_of::<[S; D]>()
            + self.key_x.capacity() * size_of::<[S; D]>()
            + self.key_rho.capacity() * size_of::<S>()
            + self.key_mass.capacity() * size_of::<f64>()
            + self.chain.reserved_bytes()
    }

    /// Fills the volumes V_J = m_J/ρ_J and (re)builds the stencils of every particle of `z`:
    /// the neighbours within the support (cell list for open domains and rectangular periodic
    /// boxes, direct scan otherwise), the pair data, and ∇φ_J of the model's shape family
    /// (non-SPH families) and of the corrected functions when `with_corrected`. In parallel
    /// (rayon). Kept as they are when built for exactly the same inputs (module docs).
    pub(crate) fn build_stencils(
        &mut self,
        m: &Model<D>,
        z: StateView<'_, S, D>,
        with_corrected: bool,
    ) -> Result<()> {
        self.vol.clear();
        self.vol.par_extend(
            z.rho
                .par_iter()
                .zip(&m.mass)
                .map(|(&rho, &ms)| S::cst(ms) / rho),
        );
        let key = StencilKey {
            family: m.p.shape,
            with_corrected,
            kernel: m.p.kp.kernel.name(),
            h: m.p.kp.h,
            period: m.period,
            art: m.p.art_stress.map(|a| (a.n, a.spacing)),
        };
        let sph = m.p.shape == ShapeFamily::Sph && !with_corrected;
        if self.key == Some(key)
            && self.st.len() == z.x.len()
            && self.same_positions(z.x)
            && (sph || (self.key_rho == z.rho && self.key_mass == m.mass))
        {
            return Ok(());
        }
        let refresh = self.reuse
            && !S::TANGENT
            && sph
            && self.key == Some(key)
            && self.st.len() == z.x.len()
            && self.pairs_still_valid(m, z.x);
        self.key = None;
        if refresh {
            self.refresh_pairs(m, z);
            self.builds.1 += 1;
        } else {
            self.rebuild_stencils(m, z, with_corrected)?;
            self.builds.0 += 1;
        }
        self.key = Some(key);
        self.key_x.clear();
        if S::TANGENT {
            self.key_x.extend_from_slice(z.x);
        }
        self.key_rho.clear();
        self.key_mass.clear();
        if !sph {
            self.key_rho.extend_from_slice(z.rho);
            self.key_mass.extend_from_slice(&m.mass);
        }
        Ok(())
    }

    /// Whether the pair list of the last full build still holds every pair within the support
    /// at `x` (module docs: no particle has moved half the skin since that build); updates the
    /// positions of the last build.
    fn pairs_still_valid(&mut self, m: &Model<D>, x: &[[S; D]]) -> bool {
        self.pos.clear();
        self.pos.par_extend(x.par_iter().map(|p| p.map(|c| c.re())));
        let r = m.p.kp.support();
        if self.built.len() != x.len() || self.list_r <= r {
            return false;
        }
        // half the skin, less a part in 10⁶ for the rounding of the distances
        let half = 0.5 * (self.list_r - r) * (1.0 - 1e-6);
        let limit = half * half;
        // the largest displacement since the full build; NaN (a diverged run) fails.
        // Serial: a few ns per particle, and one parallel loop fewer per evaluation
        self.built.iter().zip(&self.pos).all(|(p, q)| {
            let mut e2 = 0.0;
            for c in 0..D {
                let e = q[c] - p[c];
                e2 += e * e;
            }
            e2 < limit
        })
    }

    /// Recomputes the pair data (−W'/r and the artificial-stress factor) of the current pairs
    /// at the positions of `z`, as the full build computes them.
    fn refresh_pairs(&mut self, m: &Model<D>, z: StateView<'_, S, D>) {
        let n = z.x.len();
        let (kern, h) = (m.p.kp.kernel, m.p.kp.h);
        let art = m.p.art_stress;
        let w_dp = art.map(|a| kernel::w(kern, D, a.spacing, h));
        let art_n = art.map_or(0, |a| a.n);
        let pk = PairKernel::new::<D>(kern, h);
        let r = m.p.kp.support();
        let r2 = r * r;
        let st = &mut self.st;
        let (upper, ab) = (&st.upper, &st.ab);
        let fp = Shared(st.f.as_mut_ptr());
        let fnn = Shared(st.fnn.as_mut_ptr());
        self.within = (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let mut within = 0;
                for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                    let xi = z.x[i];
                    for p in upper[i] as usize..upper[i + 1] as usize {
                        let j = (ab[p] ^ i as u32) as usize;
                        // the full build's test and data: zero beyond the support
                        let (w, f, inside) = pair_data(&pk, m.rel(xi, z.x[j]), r2);
                        within += usize::from(inside);
                        // SAFETY: pair p is owned by particle i alone, and p < the pair count
                        // (the lengths of f and, with artificial stress, fnn)
                        unsafe {
                            fp.write(p, f);
                            if let Some(wd) = w_dp {
                                fnn.write(p, art_factor(w, wd, art_n));
                            }
                        }
                    }
                }
                within
            })
            .sum();
    }

    /// Whether `x` is bitwise the positions of the last build.
    fn same_positions(&self, x: &[[S; D]]) -> bool {
        if S::TANGENT {
            self.key_x == x
        } else {
            // a value-only scalar is its value: `pos` holds the positions of the build
            self.pos.len() == x.len()
                && self
                    .pos
                    .iter()
                    .zip(x)
                    .all(|(p, q)| (0..D).all(|c| p[c].to_bits() == q[c].re().to_bits()))
        }
    }

    fn rebuild_stencils(
        &mut self,
        m: &Model<D>,
        z: StateView<'_, S, D>,
        with_corrected: bool,
    ) -> Result<()> {
        let n = z.x.len();
        if n >= u32::MAX as usize / 2 {
            return Err(Error::Incompatible(
                format!("{n} particles: the stencils index particles with 32 bits").into(),
            ));
        }
        let r = m.p.kp.support();
        // |d| < r tested as |d|² < r² (no hypot: a quarter of the time of the whole rate went
        // into libm's hypot). The two can differ only within an ulp of the support radius,
        // where W and ∇W vanish.
        let r2 = r * r;
        // the list radius: the support plus the skin where the list can be reused (module
        // docs), the support alone otherwise
        let reusable = self.reuse
            && !S::TANGENT
            && m.p.shape == ShapeFamily::Sph
            && !with_corrected
            && self.skin > 0.0;
        let rl = if reusable { r * (1.0 + self.skin) } else { r };
        let rl2 = rl * rl;
        self.pos.clear();
        self.pos
            .par_extend(z.x.par_iter().map(|p| p.map(|c| c.re())));
        let grid = match m.period {
            None => {
                self.cells
                    .rebuild_subdivided(&self.pos, rl * CELL_SIDE, None, CELL_SUB[D]);
                true
            }
            Some(l) if is_diagonal(&l) => {
                let mut ext = [0.0; D];
                for (a, e) in ext.iter_mut().enumerate() {
                    *e = l[a][a];
                }
                self.cells
                    .rebuild_subdivided(&self.pos, rl * CELL_SIDE, Some(ext), CELL_SUB[D]);
                true
            }
            Some(_) => false,
        };
        let family = m.p.shape;
        let sph_a = family == ShapeFamily::Sph;
        let with_self = !sph_a;
        let (pos, cells) = (&self.pos, &self.cells);
        // the neighbours of i within the list radius, in a fixed order (cell list or index
        // order), appended to `found`: the distance test of `count` below on the positions'
        // values, the same decision, branch-free (each candidate is written, and kept when
        // listed)
        let scan = |i: usize, found: &mut Vec<u32>| {
            let pi = pos[i];
            if grid {
                cells.for_candidate_runs(pi, |run| {
                    keep_within(m, pi, pos, rl2, run.iter().copied(), run.len(), found)
                });
            } else {
                keep_within(m, pi, pos, rl2, 0..n as u32, n, found);
            }
        };
        // (entries, owned pairs) of i: the neighbours `scan` visits, counted without visiting
        // them (the same distance test on the positions' values, branch-free)
        let count = |i: usize| -> (u32, u32) {
            let pi = pos[i];
            let (mut all, mut own) = (0u32, 0u32);
            let mut test = |j: usize| {
                let listed = u32::from(dist2(m, pi, pos[j]) < rl2) & u32::from(j != i || with_self);
                all += listed;
                own += listed & u32::from(j >= i);
            };
            if grid {
                cells.for_candidate_runs(pi, |run| {
                    for &j in run {
                        test(j as usize);
                    }
                });
            } else {
                (0..n).for_each(&mut test);
            }
            (all, own)
        };

        // pass 1: directed entries and owned pairs of each particle
        let st = &mut self.st;
        st.with_self = with_self;
        st.start.resize(n + 1, 0);
        st.upper.resize(n + 1, 0);
        st.start[0] = 0;
        st.upper[0] = 0;
        st.start[1..]
            .par_iter_mut()
            .zip(st.upper[1..].par_iter_mut())
            .enumerate()
            .for_each(|(i, (s, u))| (*s, *u) = count(i));
        // the reference of the skin rule; no list to reuse until this build has succeeded
        self.list_r = 0.0;
        self.built.clear();
        self.built.extend_from_slice(&self.pos);
        for i in 0..n {
            st.start[i + 1] += st.start[i];
            st.upper[i + 1] += st.upper[i];
        }
        let (entries, pairs) = (st.start[n] as usize, st.upper[n] as usize);
        fit(&mut st.entry, entries, 0);
        fit(&mut st.ab, pairs, 0);
        fit(&mut st.f, pairs, S::zero());
        let art = m.p.art_stress;
        fit(
            &mut st.fnn,
            if art.is_some() { pairs } else { 0 },
            S::zero(),
        );
        fit(&mut st.ga, if sph_a { 0 } else { entries }, [S::zero(); D]);
        fit(
            &mut st.gb,
            if with_corrected { entries } else { 0 },
            [S::zero(); D],
        );

        // pass 2: pair data, owned pairs' indices, the other entries' neighbour index (for
        // pass 3), and ∇φ of the non-SPH families
        let chunks = n.div_ceil(CHUNK);
        if self.scratch.len() < chunks {
            self.scratch.resize_with(chunks, ShapeScratch::default);
        }
        let (kern, h) = (m.p.kp.kernel, m.p.kp.h);
        let kp = crate::shape::KernelParams { kernel: kern, h };
        let w_dp = art.map(|a| kernel::w(kern, D, a.spacing, h));
        let pk = PairKernel::new::<D>(kern, h);
        let art_n = art.map_or(0, |a| a.n);
        let (start, upper) = (&st.start, &st.upper);
        let entry = Shared(st.entry.as_mut_ptr());
        let ab = Shared(st.ab.as_mut_ptr());
        let fp = Shared(st.f.as_mut_ptr());
        let fnn = Shared(st.fnn.as_mut_ptr());
        let ga = Shared(st.ga.as_mut_ptr());
        let gb = Shared(st.gb.as_mut_ptr());
        let vol = &self.vol;
        let within = std::sync::atomic::AtomicUsize::new(0);
        self.scratch[..chunks]
            .par_iter_mut()
            .enumerate()
            .try_for_each(|(c, sc)| -> Result<()> {
                let mut inside_pairs = 0;
                for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                    // the neighbours by increasing index: the summation order of every rate
                    // term does not depend on the cell grid (module docs)
                    sc.found.clear();
                    scan(i, &mut sc.found);
                    sc.found.sort_unstable();
                    let xi = z.x[i];
                    sc.nodes.clear();
                    if !sph_a || with_corrected {
                        sc.nodes.extend(
                            sc.found
                                .iter()
                                .map(|&j| (m.rel(xi, z.x[j as usize]), vol[j as usize])),
                        );
                    }
                    if !sph_a {
                        eval_d(family, kp, &sc.nodes, pos[i][0], &mut sc.vals)?;
                    }
                    if with_corrected {
                        eval_d(
                            ShapeFamily::Corrected,
                            kp,
                            &sc.nodes,
                            pos[i][0],
                            &mut sc.vals_b,
                        )?;
                    }
                    // entries by increasing neighbour index (the summation order of every
                    // rate term: an unstable run amplifies a reordering's last bits), owned
                    // pairs numbered in that order
                    let mut e = start[i] as usize;
                    let mut p = upper[i] as usize;
                    for (k, &j) in sc.found.iter().enumerate() {
                        let j = j as usize;
                        if j == i && !with_self {
                            continue;
                        }
                        if j >= i {
                            let (w, f, inside) = pair_data(&pk, m.rel(xi, z.x[j]), r2);
                            inside_pairs += usize::from(inside);
                            // SAFETY: pair p and entry e belong to particle i alone (the
                            // offsets of pass 1 partition both arrays by particle)
                            unsafe {
                                entry.write(e, p as u32);
                                ab.write(p, (i ^ j) as u32);
                                fp.write(p, f);
                                if let Some(wd) = w_dp {
                                    fnn.write(p, art_factor(w, wd, art_n));
                                }
                            }
                            p += 1;
                        } else {
                            // SAFETY: as above (the pair index is found in pass 3; the top bit
                            // marks the entry, n < 2³¹)
                            unsafe { entry.write(e, j as u32 | LOWER) };
                        }
                        // SAFETY: entry e belongs to particle i alone
                        unsafe {
                            if !sph_a {
                                ga.write(e, sc.vals[k].1);
                            }
                            if with_corrected {
                                gb.write(e, sc.vals_b[k].1);
                            }
                        }
                        e += 1;
                    }
                }
                within.fetch_add(inside_pairs, std::sync::atomic::Ordering::Relaxed);
                Ok(())
            })?;
        self.within = within.into_inner();

        // pass 3: the pair index of each entry J < I, from J's owned pairs
        let (start, upper, ab) = (&st.start, &st.upper, &st.ab);
        let entry = Shared(st.entry.as_mut_ptr());
        (0..n).into_par_iter().try_for_each(|i| -> Result<()> {
            for e in start[i] as usize..start[i + 1] as usize {
                // SAFETY: entry e belongs to particle i alone; it was written in pass 2
                let v = unsafe { entry.read(e) };
                if v & LOWER == 0 {
                    continue;
                }
                let j = (v & !LOWER) as usize;
                let (p0, p1) = (upper[j] as usize, upper[j + 1] as usize);
                let k = ab[p0..p1]
                    .iter()
                    .position(|&x| (x ^ j as u32) as usize == i)
                    .ok_or_else(|| {
                        Error::Incompatible(
                            format!("neighbour search: particle {i} sees {j} but not the reverse")
                                .into(),
                        )
                    })?;
                // SAFETY: as above
                unsafe { entry.write(e, (p0 + k) as u32) };
            }
            Ok(())
        })?;
        self.list_r = rl;
        Ok(())
    }
}

/// The kernel's constants of one stencil build, so that a pair costs one evaluation of the
/// kernel's shape and its derivative (no normalisation or power of h per pair).
#[derive(Clone, Copy)]
struct PairKernel<'a> {
    k: &'a dyn kernel::Kernel,
    h: f64,
    /// ζh: W = W' = 0 from here on (the test of `kernel::w`).
    support: f64,
    /// σ/h^D and σ/h^(D+1), as `kernel::w` and `kernel::dw` compute them.
    s0: f64,
    s1: f64,
    /// W(0) and −W''(0).
    w0: f64,
    f0: f64,
}

impl<'a> PairKernel<'a> {
    fn new<const D: usize>(k: &'a dyn kernel::Kernel, h: f64) -> Self {
        Self {
            k,
            h,
            support: k.zeta() * h,
            s0: k.sigma(D) / h.powi(D as i32),
            s1: k.sigma(D) / h.powi(D as i32 + 1),
            w0: kernel::w(k, D, 0.0f64, h),
            f0: -kernel::d2w(k, D, 0.0, h),
        }
    }

    /// W(r) and f = −W'(r)/r of a separation d (so that ∇_x W(|x − x_J|) = f d), exactly as
    /// [`kernel::w_and_grad`] computes them (same values and tangents), including the limit
    /// −W''(0) at d = 0.
    #[inline]
    fn eval<S: Scalar, const D: usize>(&self, d: [S; D]) -> (S, S) {
        let mut r2 = S::zero();
        for a in d {
            r2 += a * a;
        }
        if r2.re() == 0.0 {
            return (S::cst(self.w0), S::cst(self.f0));
        }
        let r = r2.sqrt();
        let rv = r.re().abs();
        if rv >= self.support {
            return (r.lift(0.0, 0.0), -r.lift(0.0, 0.0) / r);
        }
        let q = rv / self.h;
        let (k, h) = (self.k, self.h);
        // the tangents only for types that carry one, as in `kernel::w` and `kernel::dw`
        let (g0, g1) = if S::TANGENT {
            (self.s0 * k.df(D, q) / h, self.s1 * k.d2f(D, q) / h)
        } else {
            (0.0, 0.0)
        };
        let w = r.lift(self.s0 * k.f(D, q), g0);
        let dw = r.lift(self.s1 * k.df(D, q), g1);
        (w, -dw / r)
    }
}

/// The data (W, −W'/r) of a pair at separation `d` as a full build computes it, and whether
/// the pair is within the support (|d|² < r², the test of the neighbour search); zeros for a
/// pair of the skin beyond it.
#[inline]
fn pair_data<S: Scalar, const D: usize>(pk: &PairKernel, d: [S; D], r2: f64) -> (S, S, bool) {
    let mut d2 = d[0].re() * d[0].re();
    for c in 1..D {
        d2 += d[c].re() * d[c].re();
    }
    if d2 < r2 {
        let (w, f) = pk.eval(d);
        (w, f, true)
    } else {
        (S::zero(), S::zero(), false)
    }
}

/// The artificial-stress factor fⁿ = (W(r)/W(Δp))ⁿ of a pair, by repeated multiplication.
#[inline]
fn art_factor<S: Scalar>(w: S, w_dp: f64, n: i32) -> S {
    let q = w / w_dp;
    let mut qn = S::cst(1.0);
    for _ in 0..n {
        qn *= q;
    }
    qn
}

/// Resizes `v` to `len`, contents unspecified (every entry is rewritten by the build). On
/// growth it frees the old buffer before allocating the new one (no copy, and no moment with
/// both alive) and reserves 1/32 more than needed instead of `Vec`'s doubling, so that the pair
/// count of a moving block, which changes by a few between steps, neither reallocates every
/// step nor doubles the largest buffers.
fn fit<T: Clone>(v: &mut Vec<T>, len: usize, fill: T) {
    if v.capacity() < len {
        *v = Vec::new();
        v.reserve_exact(len + len / 32);
    }
    v.resize(len, fill);
}

/// Appends to `found` the candidates `js` (`len` of them) closer to `pi` than √`rl2` (the
/// distance test of the neighbour search), in their order, branch-free: each candidate is
/// written, and kept when within.
#[inline(always)]
fn keep_within<const D: usize>(
    m: &Model<D>,
    pi: [f64; D],
    pos: &[[f64; D]],
    rl2: f64,
    js: impl Iterator<Item = u32>,
    len: usize,
    found: &mut Vec<u32>,
) {
    let k0 = found.len();
    found.resize(k0 + len, 0);
    let mut k = k0;
    for j in js {
        found[k] = j;
        k += usize::from(dist2(m, pi, pos[j as usize]) < rl2);
    }
    found.truncate(k);
}

/// |x_j − x_i|² (minimum image), the neighbour search's distance test: one definition for the
/// counting pass and the listing pass, so that both make the same decision.
#[inline(always)]
fn dist2<const D: usize>(m: &Model<D>, pi: [f64; D], pj: [f64; D]) -> f64 {
    let d = m.rel(pi, pj);
    let mut d2 = d[0] * d[0];
    for c in 1..D {
        d2 += d[c] * d[c];
    }
    d2
}

/// Whether a periodic cell is a rectangular box (off-diagonal entries exactly zero).
fn is_diagonal<const D: usize>(l: &[[f64; D]; D]) -> bool {
    (0..D).all(|a| (0..D).all(|b| a == b || l[a][b] == 0.0))
}
