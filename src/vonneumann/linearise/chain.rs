//! The 1D front end: a periodic chain of N cells of a [`Model<1>`](Model) — every 1D form, including the
//! \[B00\]-only ones with several points per cell (stress points) and a consistent mass (least
//! squares) — linearised by the shared core ([`super::columns`]) and projected onto Fourier modes
//! e^{iκX}.
//!
//! N is large enough that the response to a perturbation of cell 0 never wraps around. The
//! velocity rows of J(κ) are divided by the consistent-mass symbol M̂(κ); the mechanical branch
//! is the scalar reduced stiffness of the core.
//!
//! The six forms the chain shares with 2D and 3D are *not* routed through `Bloch<1>`: the chain
//! must serve the \[B00\] forms anyway (stress points, consistent mass, physical units of a
//! [`Lattice1D`]), so a second 1D engine for the common forms would add code, not remove it; the
//! rate function and every step after the dual-number seeding are already the same code.

use super::columns::{Columns, Entry, LANES, Linearisable, Phase, eigen};
use crate::error::Result;
use crate::forms::{Comp, FieldKind, FormKind, MassOperator, Model, ModelParams, State};
use crate::integrator::Integrator;
use crate::scalar::{DualN, Scalar};
use crate::vonneumann::amplification::{ModeSystem, Modes};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// One degree of freedom of a lattice cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dof {
    /// The state component (of the cell's particle, or of its stress point).
    pub comp: Comp,
}

/// The Fourier-projected linearisation of a 1D form.
#[derive(Clone, Debug)]
pub struct Linearisation {
    /// Degrees of freedom of a cell, in order.
    pub dofs: Vec<Dof>,
    /// Jacobian columns per cell offset.
    core: Columns<i64>,
    /// Consistent-mass stencil (cell offset K, M_{0K}), or empty for lumped masses.
    mass: Vec<(i64, f64)>,
    /// Scale factors to normalised units: ω² · (Δx² ρ0 / C).
    omega2_scale: f64,
    /// Physical Δx and c.
    dx: f64,
    c: f64,
    /// Whether velocities or auxiliary states enter their own rates ([`Columns::is_dissipative`]).
    dissipative: bool,
    /// The entries of the reduced stiffness K(κ) = −(J_vx + Σ_q J_vq J_qv), for the tabulated route.
    reduced: Reduced,
}

/// The Jacobian entries the mechanical reduction needs ([`Linearisation::omega2_tabulated`]).
#[derive(Clone, Debug)]
struct Reduced {
    vx: Entry<i64>,
    vq: Vec<Entry<i64>>,
    qv: Vec<Entry<i64>>,
}

/// The phase factors e^{−iκj} (as [`Phase`]) of a κ grid for every cell offset |j| ≤ reach,
/// computed once and shared by every cell of a sweep (the atlas evaluates 450,560 cells on one
/// grid): the Fourier sums of the engine then make no libm call. [`Self::ensure`] widens the
/// table when a linearisation reaches further.
#[derive(Clone, Debug)]
pub struct PhaseTable {
    kappas: Vec<f64>,
    reach: i64,
    /// Row-major: κ index, then offset + reach.
    phases: Vec<Phase>,
    /// Row-major: κ index, then m = 0..=2·reach: cos κm − 1 = −2 sin²(κm/2) (the
    /// [`CosineSeries`] reach twice as far as the Jacobian entries).
    cos_m1: Vec<f64>,
}

impl PhaseTable {
    /// The table of `kappas` (κΔx) for offsets |j| ≤ `reach`.
    pub fn new(kappas: &[f64], reach: i64) -> Self {
        let mut t = Self {
            kappas: kappas.to_vec(),
            reach: -1,
            phases: Vec::new(),
            cos_m1: Vec::new(),
        };
        t.ensure(reach.max(0));
        t
    }

    /// Widens the table to offsets |j| ≤ `reach` (no-op if it already covers them).
    pub fn ensure(&mut self, reach: i64) {
        if reach <= self.reach {
            return;
        }
        let w = (2 * reach + 1) as usize;
        self.phases.clear();
        self.phases.reserve(w * self.kappas.len());
        for &kappa in &self.kappas {
            // θ = κ·j exactly as `Linearisation::jacobian` forms it
            self.phases
                .extend((-reach..=reach).map(|j| Phase::of(kappa * j as f64)));
        }
        self.cos_m1.clear();
        self.cos_m1
            .reserve((2 * reach + 1) as usize * self.kappas.len());
        for &kappa in &self.kappas {
            self.cos_m1
                .extend((0..=2 * reach).map(|m| Phase::of(kappa * m as f64).cos_m1));
        }
        self.reach = reach;
    }

    /// The κ grid.
    pub fn kappas(&self) -> &[f64] {
        &self.kappas
    }

    /// The factors of the offsets at κ index `k`.
    #[inline]
    fn row(&self, k: usize) -> impl Fn(&i64) -> Phase + '_ {
        let w = (2 * self.reach + 1) as usize;
        let row = &self.phases[k * w..(k + 1) * w];
        move |&j| row[(j + self.reach) as usize]
    }
}

/// The physical setting of a linearisation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice1D {
    /// Lattice spacing Δx (physical).
    pub dx: f64,
    /// Reference density ρ0.
    pub rho0: f64,
    /// Tangent modulus C.
    pub modulus: f64,
}

impl Default for Lattice1D {
    fn default() -> Self {
        Self {
            dx: 1.0,
            rho0: 1.0,
            modulus: 1.0,
        }
    }
}

/// The periodic chain being differentiated.
struct Chain {
    model: Model<1>,
    base: State<f64, 1>,
    comps: Vec<Comp>,
    out: State<DualN<LANES>, 1>,
    n: usize,
}

impl Chain {
    /// Cell offset of cell i, wrapped into (−n/2, n/2].
    fn wrap(&self, i: usize) -> i64 {
        if i <= self.n / 2 {
            i as i64
        } else {
            i as i64 - self.n as i64
        }
    }
}

impl Linearisable for Chain {
    type Offset = i64;
    fn kinds(&self) -> Vec<FieldKind> {
        self.comps.iter().map(|f| f.kind()).collect()
    }
    fn cells(&self) -> usize {
        self.n
    }
    fn offset(&self, i: usize) -> i64 {
        self.wrap(i)
    }
    fn lanes(&self) -> usize {
        LANES
    }
    fn seeded_rates(&mut self, b0: usize) -> Result<()> {
        let mut z: State<DualN<LANES>, 1> = self.base.map(DualN::cst);
        for (l, &c) in self.comps.iter().skip(b0).take(LANES).enumerate() {
            let mut seeded = z.get(c, 0);
            seeded.d[l] = 1.0;
            z.set(c, 0, seeded);
        }
        self.model.rate(&z, &mut self.out)
    }
    fn tangent(&self, a: usize, i: usize, l: usize) -> f64 {
        self.out.get(self.comps[a], i).d[l]
    }
}

/// ω²Δx²/c² of a lumped-mass, non-dissipative 1D form as a cosine series in κΔx,
/// `c0 + Σ_{m=1}^{M} d_m (cos κm − 1)`, assembled once from the Jacobian entries of the reduced
/// stiffness K = −(J_vx + Σ_q J_vq J_qv) ([`Linearisation::cosine_series`]): products of two
/// entries become single sums through (e^{−iκi} − 1)(e^{−iκj} − 1) = (e^{−iκ(i+j)} − 1) −
/// (e^{−iκi} − 1) − (e^{−iκj} − 1), so every term keeps the form cos κm − 1 = −2 sin²(κm/2) and
/// the series keeps full relative accuracy as κ → 0. One evaluation is a dot product of length
/// M (the coupling range, 2× the Jacobian's reach) with a tabulated row ([`PhaseTable`]).
#[derive(Clone, Debug)]
pub struct CosineSeries {
    /// ω² at every κ from terms that are constant in κ (zero for translation-invariant forms).
    pub c0: f64,
    /// d_m, m = 1..=M.
    pub d: Vec<f64>,
}

impl CosineSeries {
    /// ω²Δx²/c² at the κ of row `k` of `table`.
    ///
    /// # Panics
    /// If `table` does not reach M/2 ([`PhaseTable::ensure`] with [`Linearisation::reach`]).
    #[inline]
    pub fn omega2(&self, table: &PhaseTable, k: usize) -> f64 {
        let w = (2 * table.reach + 1) as usize;
        assert!(self.d.len() < w, "phase table too short");
        let row = &table.cos_m1[k * w + 1..(k + 1) * w];
        // four independent partial sums (vectorised)
        let mut acc = [0.0f64; 4];
        for (d, r) in self.d.chunks_exact(4).zip(row.chunks_exact(4)) {
            for ((a, x), y) in acc.iter_mut().zip(d).zip(r) {
                *a += x * y;
            }
        }
        let n = self.d.len() / 4 * 4;
        let mut tail = 0.0;
        for (d, r) in self.d[n..].iter().zip(&row[n..self.d.len()]) {
            tail += d * r;
        }
        self.c0 + ((acc[0] + acc[1]) + (acc[2] + acc[3]) + tail)
    }
}

impl Linearisation {
    /// Linearises the form described by `p` about the pre-stress `sigma0` (physical units) on
    /// the uniform periodic lattice `lat`.
    pub fn new(p: ModelParams, sigma0: f64, lat: Lattice1D) -> Result<Self> {
        let support_cells = p.kp.support() / lat.dx;
        // Coupling range: shape functions at a point depend on masters within R, the stress of a
        // master on velocities within R, and the force on stresses within R: < 3R + 2 cells.
        let range = (3.0 * support_cells).ceil() as usize + 3;
        let n = (2 * range + 1).max(9);
        let x_ref: Vec<[f64; 1]> = (0..n).map(|i| [i as f64 * lat.dx]).collect();
        let vol = vec![lat.dx; n];
        let model = Model::new(p, x_ref, vol, p.rho0, sigma0, Some([[n as f64 * lat.dx]]))?;
        let comps = p.form.comps(1, &p.material);
        let mut chain = Chain {
            base: model.rest_state(p.rho0),
            model,
            comps,
            out: State::default(),
            n,
        };
        let core = Columns::of(&mut chain)?;
        let mass = match chain.model.mass_operator() {
            MassOperator::Lumped => Vec::new(),
            MassOperator::Consistent(rows) => {
                rows[0].iter().map(|&(k, mk)| (chain.wrap(k), mk)).collect()
            }
        };
        let c = (lat.modulus / lat.rho0).sqrt();
        Ok(Self::assemble(
            chain.comps.iter().map(|&comp| Dof { comp }).collect(),
            core,
            mass,
            lat.dx * lat.dx / (c * c),
            lat.dx,
            c,
        ))
    }

    fn assemble(
        dofs: Vec<Dof>,
        core: Columns<i64>,
        mass: Vec<(i64, f64)>,
        omega2_scale: f64,
        dx: f64,
        c: f64,
    ) -> Self {
        let (ix, iv) = (core.ix[0], core.iv[0]);
        let reduced = Reduced {
            vx: core.entry(iv, ix),
            vq: core.iq.iter().map(|&q| core.entry(iv, q)).collect(),
            qv: core.iq.iter().map(|&q| core.entry(q, iv)).collect(),
        };
        Self {
            dofs,
            dissipative: core.is_dissipative(),
            core,
            mass,
            omega2_scale,
            dx,
            c,
            reduced,
        }
    }

    /// Largest cell offset the Fourier sums reach (columns and consistent mass): the
    /// [`PhaseTable`] this linearisation is evaluated on must cover it.
    pub fn reach(&self) -> i64 {
        let m = self.mass.iter().map(|(k, _)| k.abs()).max().unwrap_or(0);
        self.core.reach(|o| o.abs()).max(m)
    }

    /// M̂(κ) from tabulated phases ([`Self::mass_symbol`]'s sum, same operations).
    fn mass_symbol_tabulated(&self, phase: &impl Fn(&i64) -> Phase) -> Complex64 {
        self.mass
            .iter()
            .map(|&(k, m)| {
                let p = phase(&k);
                Complex64::new(m * p.cos, m * p.sin)
            })
            .fold(Complex64::new(0.0, 0.0), |a, b| a + b)
    }

    /// [`Self::omega2`] at the κ of row `k` of `table`: only the entries of the reduced
    /// stiffness are summed, from tabulated phases — no libm call, no allocation. The
    /// operations and their order are those of the matrix route, so the result is the same to
    /// the last bit (tests/it/golden_analysis.rs checks 1e-12).
    ///
    /// # Panics
    /// If `table` does not reach [`Self::reach`] (call [`PhaseTable::ensure`] first).
    pub fn omega2_tabulated(&self, table: &PhaseTable, k: usize) -> (f64, f64) {
        assert!(table.reach >= self.reach(), "phase table too short");
        let phase = table.row(k);
        let r = &self.reduced;
        let m = (!self.mass.is_empty()).then(|| self.mass_symbol_tabulated(&phase));
        let mut vx = r.vx.sum(&phase);
        if let Some(m) = m {
            vx /= m;
        }
        let mut kk = -vx;
        for (vq, qv) in r.vq.iter().zip(&r.qv) {
            let mut s = vq.sum(&phase);
            if let Some(m) = m {
                s /= m;
            }
            kk -= s * qv.sum(&phase);
        }
        let w2 = kk.re * self.omega2_scale;
        (w2, kk.im.abs() * self.omega2_scale / w2.abs().max(1.0))
    }

    /// J(κ) at the κ of row `k` of `table` ([`Self::jacobian`] without libm calls).
    pub fn jacobian_tabulated(&self, table: &PhaseTable, k: usize) -> DMatrix<Complex64> {
        assert!(table.reach >= self.reach(), "phase table too short");
        let phase = table.row(k);
        let mut j = self.core.jacobian_tabulated(&phase);
        if !self.mass.is_empty() {
            let m = self.mass_symbol_tabulated(&phase);
            let iv = self.core.iv[0];
            for b in 0..self.size() {
                j[(iv, b)] /= m;
            }
        }
        j
    }

    /// [`Self::growth`] at the κ of row `k` of `table`.
    pub fn growth_tabulated(&self, table: &PhaseTable, k: usize) -> Result<f64> {
        if self.dissipative {
            let j = self.jacobian_tabulated(table, k) * Complex64::new(self.dx / self.c, 0.0);
            Ok(eigen(j)?.iter().map(|s| s.re).fold(0.0, f64::max))
        } else {
            Ok((-self.omega2_tabulated(table, k).0).max(0.0).sqrt())
        }
    }

    /// Number of degrees of freedom per cell.
    pub fn size(&self) -> usize {
        self.core.size()
    }

    /// The linearisation at t ∈ [0, 1] between `self` and `other` (the same form, kernel, h and
    /// lattice at two pre-stresses), interpolating the Jacobian columns (`Columns::lerp`):
    /// exact when the columns are affine in the pre-stress (the atlas checks that with
    /// [`Self::distance`] before it relies on it). `None` if the two differ in anything but
    /// the column values.
    pub fn lerp(&self, other: &Self, t: f64) -> Option<Self> {
        if self.dofs != other.dofs
            || self.mass != other.mass
            || self.omega2_scale != other.omega2_scale
            || (self.dx, self.c) != (other.dx, other.c)
        {
            return None;
        }
        let core = self.core.lerp(&other.core, t)?;
        Some(Self::assemble(
            self.dofs.clone(),
            core,
            self.mass.clone(),
            self.omega2_scale,
            self.dx,
            self.c,
        ))
    }

    /// Largest difference of the Jacobian columns of two linearisations relative to their
    /// largest entry (`Columns::distance`); `None` if the degrees of freedom differ.
    pub fn distance(&self, other: &Self) -> Option<f64> {
        if self.dofs != other.dofs || self.mass != other.mass {
            return None;
        }
        self.core.distance(&other.core)
    }

    /// ω²Δx²/c² as a cosine series ([`CosineSeries`]), for lumped-mass non-dissipative forms
    /// (`None` otherwise: consistent mass divides by M̂(κ), damping needs the eigenvalues).
    pub fn cosine_series(&self) -> Option<CosineSeries> {
        if self.dissipative || !self.mass.is_empty() {
            return None;
        }
        let r = &self.reduced;
        let reach = self.reach();
        // coefficients of E_m = e^{−iκm} − 1, m ∈ [−2 reach, 2 reach]
        let mut coef = vec![0.0; (4 * reach + 1) as usize];
        let at = |m: i64| (m + 2 * reach) as usize;
        // an entry is f = C + Σ a_i E_i, with C = Σ a_i when summed with e^{−iκi} and C = 0
        // when summed with e^{−iκi} − 1 (its k = 0 sum is zero)
        let parts = |e: &Entry<i64>| {
            let sum: f64 = e.terms.iter().map(|t| t.1).sum();
            (if e.minus_one { 0.0 } else { sum }, sum)
        };
        let (cvx, _) = parts(&r.vx);
        let mut c0 = -cvx;
        for &(i, a) in &r.vx.terms {
            coef[at(i)] -= a;
        }
        // f g = C₁C₂ + Σ_j (C₁ − A) b_j E_j + Σ_i (C₂ − B) a_i E_i + Σ_ij a_i b_j E_{i+j}, from
        // E_i E_j = E_{i+j} − E_i − E_j (A = Σ a_i, B = Σ b_j)
        for (f, g) in r.vq.iter().zip(&r.qv) {
            let ((c1, sa), (c2, sb)) = (parts(f), parts(g));
            c0 -= c1 * c2;
            for &(j, b) in &g.terms {
                coef[at(j)] -= (c1 - sa) * b;
            }
            for &(i, a) in &f.terms {
                coef[at(i)] -= (c2 - sb) * a;
                for &(j, b) in &g.terms {
                    coef[at(i + j)] -= a * b;
                }
            }
        }
        // Re E_m = cos κm − 1 is even in m: fold ±m
        let d = (1..=2 * reach)
            .map(|m| (coef[at(m)] + coef[at(-m)]) * self.omega2_scale)
            .collect();
        Some(CosineSeries {
            c0: c0 * self.omega2_scale,
            d,
        })
    }

    /// Physical Δx and c of the lattice.
    pub fn units(&self) -> (f64, f64) {
        (self.dx, self.c)
    }

    /// Per-mode Jacobian block J(κ) (physical units; κ is κΔx), with the velocity rows
    /// multiplied by M̂(κ)⁻¹ for a consistent mass.
    pub fn jacobian(&self, kappa: f64) -> DMatrix<Complex64> {
        let mut j = self.core.jacobian(|&i| kappa * i as f64);
        if !self.mass.is_empty() {
            let m = self.mass_symbol(kappa);
            let iv = self.core.iv[0];
            for b in 0..self.size() {
                j[(iv, b)] /= m;
            }
        }
        j
    }

    /// M̂(κ) = Σ_K M_{0K} e^{iκK} (1 for lumped masses, in units of the lumped mass).
    pub fn mass_symbol(&self, kappa: f64) -> Complex64 {
        if self.mass.is_empty() {
            return Complex64::new(1.0, 0.0);
        }
        self.mass
            .iter()
            .map(|&(k, m)| Complex64::from_polar(m, kappa * k as f64))
            .sum()
    }

    /// Whether the velocity rows depend on velocities (artificial viscosity): then only the
    /// eigenvalue route applies.
    pub fn is_dissipative(&self) -> bool {
        self.dissipative
    }

    /// Normalised ω²Δx²/c² of the mechanical branch from the reduced stiffness
    /// K(κ) = −(J_vx + Σ_q J_vq J_qv) (exact for non-dissipative systems).
    /// Returns (ω², |Im K| / max(|K|, 1) as a consistency diagnostic).
    pub fn omega2(&self, kappa: f64) -> (f64, f64) {
        let k = self.core.stiffness(&self.jacobian(kappa), 0, 0);
        let w2 = k.re * self.omega2_scale;
        (w2, k.im.abs() * self.omega2_scale / w2.abs().max(1.0))
    }

    /// Eigenvalues s of J(κ), normalised to c/Δx.
    pub fn eigenvalues(&self, kappa: f64) -> Result<Vec<Complex64>> {
        let j = self.jacobian(kappa) * Complex64::new(self.dx / self.c, 0.0);
        eigen(j)
    }

    /// Growth rate γ(κ) = max Re s ≥ 0 in c/Δx units. Non-dissipative systems use the exact
    /// reduced route γ = sqrt(max(0, −ω²)); dissipative ones the eigenvalues of J(κ).
    pub fn growth(&self, kappa: f64) -> Result<f64> {
        if self.is_dissipative() {
            let ev = self.eigenvalues(kappa)?;
            Ok(ev.iter().map(|s| s.re).fold(0.0, f64::max))
        } else {
            Ok((-self.omega2(kappa).0).max(0.0).sqrt())
        }
    }
}

impl Modes for Linearisation {
    type K = f64;
    fn is_dissipative(&self) -> bool {
        self.dissipative
    }
    fn omega2_top(&self, kappa: f64) -> f64 {
        self.omega2(kappa).0
    }
    fn amplification_with(&self, kappa: f64, dt: f64, integ: Integrator) -> DMatrix<Complex64> {
        self.core
            .amplification(self.jacobian(kappa), dt * self.dx / self.c, integ)
    }
    fn growth_per_step(&self, kappa: f64, dt: f64, integ: Integrator) -> Result<f64> {
        self.core
            .growth_per_step(self.jacobian(kappa), dt * self.dx / self.c, integ)
    }
    fn eigenvalues(&self, kappa: f64) -> Result<Vec<Complex64>> {
        Linearisation::eigenvalues(self, kappa)
    }
}

/// The mode systems (J(κ) with its position, velocity and auxiliary rows) of a κ grid, built
/// once, as [`Modes`]: a time-step bisection asks the amplification matrices of the same modes
/// at ~50 Δt, and [`Linearisation`]'s own [`Modes`] rebuilds J(κ) (a Fourier sum) for each. The
/// same numbers bit for bit (the same J, the same arithmetic); a κ outside the grid is computed
/// as [`Linearisation`] computes it.
pub struct ModeTable<'a> {
    lin: &'a Linearisation,
    index: std::collections::HashMap<u64, usize>,
    systems: Vec<ModeSystem>,
}

impl Linearisation {
    /// The [`ModeTable`] of `kappas`.
    pub fn mode_table(&self, kappas: &[f64]) -> ModeTable<'_> {
        let c = &self.core;
        ModeTable {
            lin: self,
            index: kappas
                .iter()
                .enumerate()
                .map(|(i, k)| (k.to_bits(), i))
                .collect(),
            systems: kappas
                .iter()
                .map(|&k| {
                    ModeSystem::new(self.jacobian(k), c.ix.clone(), c.iv.clone(), c.iq.clone())
                })
                .collect(),
        }
    }
}

impl ModeTable<'_> {
    fn system(&self, kappa: f64) -> Option<&ModeSystem> {
        self.index.get(&kappa.to_bits()).map(|&i| &self.systems[i])
    }

    /// Δt (units of Δx/c) in the units of J⁻¹.
    fn dt(&self, dt: f64) -> f64 {
        dt * self.lin.dx / self.lin.c
    }
}

impl Modes for ModeTable<'_> {
    type K = f64;
    fn is_dissipative(&self) -> bool {
        self.lin.dissipative
    }
    fn omega2_top(&self, kappa: f64) -> f64 {
        self.lin.omega2_top(kappa)
    }
    fn amplification_with(&self, kappa: f64, dt: f64, integ: Integrator) -> DMatrix<Complex64> {
        match self.system(kappa) {
            Some(m) => m.amplification_with(integ, self.dt(dt)),
            None => self.lin.amplification_with(kappa, dt, integ),
        }
    }
    fn growth_per_step(&self, kappa: f64, dt: f64, integ: Integrator) -> Result<f64> {
        match self.system(kappa) {
            Some(m) => m.growth_per_step(integ, self.dt(dt)),
            None => Modes::growth_per_step(self.lin, kappa, dt, integ),
        }
    }
    fn eigenvalues(&self, kappa: f64) -> Result<Vec<Complex64>> {
        Linearisation::eigenvalues(self.lin, kappa)
    }
}

/// Convenience: does this form use a consistent mass?
pub fn has_consistent_mass(form: FormKind) -> bool {
    form == FormKind::LeastSquares
}
