//! The D-dimensional front end (D ∈ {2, 3}; the code is generic in D): the rate function of a
//! [`Model<D>`] linearised by the shared core ([`super::columns`]) about the uniformly,
//! isotropically pre-stressed periodic lattice and projected onto Bloch waves exp(i k·X): per wave
//! vector the Jacobian block J(k) of the full per-particle state, the D × D dynamical matrix
//! D(k) = −(J_vx + J_vq J_qv) of the mechanical branches, growth rates and polarisations.
//!
//! The periodic patch: 2D, n × n primitive cells with n·(plane spacing) ≥ 4R + 5 spacings;
//! 3D, m³ conventional cubes (orthogonal, so the cell list applies) with side m·a ≥ 2R_dep + 2a,
//! where R_dep is how far the rate of a particle reaches: R for the Eulerian forms (stencils,
//! volumes and stresses of the neighbours within the support) and 2R for total-Lagrangian
//! (F at every neighbour within R). Each Jacobian column is stored with the relative position
//! of the particle it belongs to, and J(k) = Σ_j J_j e^{−ik·r_j}.

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::columns::{Columns, LANES, Linearisable, SparseJacobian, eigen};
use crate::budget::Budget;
use crate::error::{Error, Result, fields};
use crate::forms::{
    Comp, FieldKind, FormKind, Material, Model, ModelParams, PrestressKind, RateWorkspace, State,
};
use crate::integrator::Integrator;
use crate::lattice::{Lattice, grid_index};
use crate::scalar::{Dual, DualN, Lanes};
use crate::vonneumann::amplification::{Modes, spectral_radius};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// The Bloch-projected linearisation of a form in D dimensions.
#[derive(Clone, Debug)]
pub struct Bloch<const D: usize> {
    /// Components per particle.
    pub comps: Vec<Comp>,
    /// Jacobian columns per relative particle position (units of Δx).
    core: Columns<[f64; D]>,
    /// Lattice (units of Δx).
    pub lattice: Lattice<D>,
    omega2_scale: f64,
    time_scale: f64,
    /// [`Columns::is_dissipative`], computed once.
    dissipative: bool,
    /// The entries the mechanical branches read ([`Columns::mechanical_entries`]).
    mechanical: SparseJacobian<[f64; D]>,
}

/// Base state of a pre-stressed lattice: (density, isotropic stress) for σ̄ = σ/C.
/// Hydro: σ = −K(ρ/ρ0 − 1) = σ̄K ⇒ ρ = (1 − σ̄)ρ0 (the Swegle density ratio f = 1 − σ̄).
/// Elastic: ρ = ρ0, σ = σ̄ C.
pub fn base_state(material: &Material, rho0: f64, sigma_bar: f64) -> Result<(f64, f64)> {
    let c = material.modulus();
    match material {
        Material::Hydro { .. } => {
            if sigma_bar >= 1.0 {
                return Err(Error::OutOfRange {
                    field: "stress",
                    value: sigma_bar,
                    range: "hydrodynamic material: σ̄ = 1 − ρ/ρ0 must be < 1".into(),
                });
            }
            Ok(((1.0 - sigma_bar) * rho0, sigma_bar * c))
        }
        Material::Elastic { .. } | Material::NeoHookean { .. } => Ok((rho0, sigma_bar * c)),
    }
}

/// The periodic patch of the linearisation (module docs) and the relative position of every
/// particle from particle 0.
fn patch<const D: usize>(
    p: ModelParams,
    lat: &Lattice<D>,
    dx: f64,
    rho: f64,
    s0: f64,
    budget: &Budget,
) -> Result<(Model<D>, Vec<[f64; D]>)> {
    let r = p.kp.support();
    let cells = if D == 2 {
        2 * ((2.0 * r / (dx * lat.plane_spacing())).ceil() as usize + 2) + 1
    } else {
        let reach = if p.form.is_total_lagrangian() {
            2.0 * r
        } else {
            r
        };
        (2.0 * reach / (dx * cube_side(lat))).ceil() as usize + 2
    };
    check_patch_budget(&p, lat, dx, lattice_particles(lat, cells), budget)?;
    periodic_lattice(p, lat, dx, rho, s0, cells)
}

/// Particles of [`periodic_lattice`] with `cells` cells per side.
pub fn lattice_particles<const D: usize>(lat: &Lattice<D>, cells: usize) -> usize {
    cells.pow(D as u32) * if D == 3 { cube_basis(lat).len() } else { 1 }
}

/// The uniformly pre-stressed periodic lattice `lat` (spacing `dx`) at rest, density `rho` and
/// isotropic stress `s0` ([`base_state`]), `cells` cells per side: 1D, `cells` particles; 2D,
/// `cells` × `cells` primitive cells; 3D, `cells`³ conventional cubes (orthogonal, so the
/// cell list applies). With the relative position of every particle from particle 0 (units
/// of `dx`, minimum image). The Bloch linearisation's patch, and the periodic body of a
/// time-domain check of the same lattice.
pub fn periodic_lattice<const D: usize>(
    p: ModelParams,
    lat: &Lattice<D>,
    dx: f64,
    rho: f64,
    s0: f64,
    cells: usize,
) -> Result<(Model<D>, Vec<[f64; D]>)> {
    let n = cells;
    if D <= 2 {
        let mut nn = [0; D];
        nn.fill(n);
        let model = Model::periodic_patch(p, lat, dx, nn, rho, s0)?;
        // relative positions from the cell indices, wrapped into (−n/2, n/2]
        let w = |a: usize| {
            let a = a as i64;
            if a <= n as i64 / 2 { a } else { a - n as i64 }
        };
        let a = lat.a;
        let offs = (0..n.pow(D as u32))
            .map(|idx| {
                let (o0, o1) = if D == 1 {
                    (w(idx) as f64, 0.0)
                } else {
                    (w(idx / n) as f64, w(idx % n) as f64)
                };
                let mut r = [0.0; D];
                for c in 0..D {
                    r[c] = o0 * a[0][c] + if D == 2 { o1 * a[1][c] } else { 0.0 };
                }
                r
            })
            .collect();
        return Ok((model, offs));
    }
    let side = cube_side(lat);
    let m = n;
    let basis = cube_basis(lat);
    let mut x = Vec::with_capacity(m.pow(D as u32) * basis.len());
    for idx in 0..m.pow(D as u32) {
        let c = grid_index::<D>(idx, m);
        for b in &basis {
            let mut q = [0.0; D];
            for a in 0..D {
                q[a] = dx * side * (c[a] as f64 + b[a]);
            }
            x.push(q);
        }
    }
    let mut period = [[0.0; D]; D];
    for a in 0..D {
        period[a][a] = dx * side * m as f64;
    }
    let vol = vec![lat.area() * dx.powi(D as i32); x.len()];
    let model = Model::new(p, x, vol, rho, s0, Some(period))?;
    let x0 = model.x_ref[0];
    let offs = model
        .x_ref
        .iter()
        .map(|&xj| model.rel(x0, xj).map(|c| c / dx))
        .collect();
    Ok((model, offs))
}

/// Side of the conventional cube of a 3D lattice (1 for any other).
fn cube_side<const D: usize>(lat: &Lattice<D>) -> f64 {
    use crate::lattice::LatticeKind;
    match lat.kind {
        LatticeKind::Bcc => 2f64.cbrt(),
        LatticeKind::Fcc => 4f64.cbrt(),
        _ => 1.0,
    }
}

/// Basis of the conventional cube in units of its side.
fn cube_basis<const D: usize>(lat: &Lattice<D>) -> Vec<[f64; D]> {
    let mut out = Vec::new();
    let three: Vec<[f64; 3]> = match lat.kind {
        crate::lattice::LatticeKind::Bcc => vec![[0.0; 3], [0.5; 3]],
        crate::lattice::LatticeKind::Fcc => {
            vec![[0.0; 3], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5], [0.5, 0.5, 0.0]]
        }
        _ => vec![[0.0; 3]],
    };
    for b in three {
        let mut q = [0.0; D];
        q.copy_from_slice(&b[..D]);
        out.push(q);
    }
    out
}

impl<const D: usize> Bloch<D> {
    /// Linearises the form `p` on lattice `lat` (spacing `dx`) at pre-stress σ̄, within the
    /// default budget.
    pub fn new(p: ModelParams, lat: &Lattice<D>, dx: f64, sigma_bar: f64) -> Result<Self> {
        Self::with_budget(p, lat, dx, sigma_bar, &Budget::default())
    }

    /// [`Bloch::new`] within `budget`: the periodic patch is refused before it is built when
    /// its estimated memory exceeds the budget ([`check_patch_budget`]).
    pub fn with_budget(
        p: ModelParams,
        lat: &Lattice<D>,
        dx: f64,
        sigma_bar: f64,
        budget: &Budget,
    ) -> Result<Self> {
        Self::with_prestress(p, lat, dx, sigma_bar, PrestressKind::Isotropic, budget)
    }

    /// [`Bloch::with_budget`] about the pre-stress σ̄ C Ŝ of shape `kind` ([`PrestressKind`]):
    /// isotropic as there; uniaxial and shear (elastic materials) hold every particle's stress
    /// field, and the total-Lagrangian law, at that tensor.
    pub fn with_prestress(
        p: ModelParams,
        lat: &Lattice<D>,
        dx: f64,
        sigma_bar: f64,
        kind: PrestressKind,
        budget: &Budget,
    ) -> Result<Self> {
        if D == 3
            && !matches!(
                lat.kind,
                crate::lattice::LatticeKind::Sc
                    | crate::lattice::LatticeKind::Bcc
                    | crate::lattice::LatticeKind::Fcc
            )
        {
            return Err(Error::Incompatible("3D lattices: sc, bcc, fcc".into()));
        }
        let (mut rho, s0) = base_state(&p.material, p.rho0, sigma_bar)?;
        if p.form == FormKind::Enog
            && let Material::Elastic { lambda, shear, .. } = p.material
        {
            // SPH-ENOG's stress is its pressure: the mean of the pre-stress, from the density
            // (its deviatoric part has no field to live in)
            let unit = kind.unit::<D>()?;
            let mean = s0 * (0..D).map(|a| unit[a][a]).sum::<f64>() / D as f64;
            rho = p.rho0 * (1.0 - mean / (lambda + 2.0 * shear / 3.0));
            if rho <= 0.0 {
                return Err(Error::OutOfRange {
                    field: "stress",
                    value: sigma_bar,
                    range: "enog: the mean pre-stress must stay below the bulk modulus K (ρ = ρ0(1 − σ_mean/K) > 0)".into(),
                });
            }
        }
        let (mut model, offs) = patch(p, lat, dx, rho, s0, budget)?;
        if kind != PrestressKind::Isotropic {
            let unit = kind.unit::<D>()?;
            model.set_prestress(unit.map(|row| row.map(|u| u * s0)))?;
        }
        let comps = p.form.comps(D, &p.material);
        let count = offs.len();
        // LANES tangents per rate evaluation when that fits the memory budget (the stencils
        // carry every lane), one otherwise; the columns are the same to the last bit
        let (wide, _) = patch_bytes::<DualN<LANES>, D>(&p, lat, dx, count);
        let (comps, core) = if budget.allows_memory(wide) {
            let mut sys = Patch::<DualN<LANES>, D>::new(model, rho, offs, comps);
            let core = Columns::of(&mut sys)?;
            (sys.comps, core)
        } else {
            let mut sys = Patch::<Dual, D>::new(model, rho, offs, comps);
            let core = Columns::of(&mut sys)?;
            (sys.comps, core)
        };
        let c2 = p.material.modulus() / p.rho0;
        Ok(Self {
            comps,
            dissipative: core.is_dissipative(),
            mechanical: core.mechanical_entries(),
            core,
            lattice: *lat,
            omega2_scale: dx * dx / c2,
            time_scale: dx / c2.sqrt(),
        })
    }

    /// Whether velocities enter the accelerations (artificial viscosity).
    pub fn is_dissipative(&self) -> bool {
        self.dissipative
    }

    /// The phase θ = k·r.
    fn phase(k: [f64; D]) -> impl Fn(&[f64; D]) -> f64 {
        move |r: &[f64; D]| {
            let mut t = k[0] * r[0];
            for a in 1..D {
                t += k[a] * r[a];
            }
            t
        }
    }

    /// J(k) (physical units; k in units of 1/Δx).
    pub fn jacobian(&self, k: [f64; D]) -> DMatrix<Complex64> {
        self.core.jacobian(Self::phase(k))
    }

    /// J(k) with only the entries the mechanical branches read (the others zero): enough for
    /// [`Self::dynamical_of`] of a non-dissipative system.
    fn jacobian_mechanical(&self, k: [f64; D]) -> DMatrix<Complex64> {
        self.core.jacobian_sparse(&self.mechanical, Self::phase(k))
    }

    /// Normalised dynamical matrix D(k)Δx²/c² (D × D) of the mechanical branches.
    pub fn dynamical(&self, k: [f64; D]) -> [[Complex64; D]; D] {
        self.dynamical_of(&self.jacobian_mechanical(k))
    }

    /// [`Self::dynamical`] from J(k).
    fn dynamical_of(&self, j: &DMatrix<Complex64>) -> [[Complex64; D]; D] {
        let mut d = [[Complex64::new(0.0, 0.0); D]; D];
        for a in 0..D {
            for b in 0..D {
                d[a][b] = self.core.stiffness(j, a, b) * self.omega2_scale;
            }
        }
        d
    }

    /// The D branches at k: (ω² (complex in general), unit polarisation), ascending in Re ω².
    pub fn branches(&self, k: [f64; D]) -> Vec<(Complex64, [Complex64; D])> {
        self.branches_of(&self.jacobian_mechanical(k))
    }

    /// [`Self::branches`] from J(k).
    fn branches_of(&self, j: &DMatrix<Complex64>) -> Vec<(Complex64, [Complex64; D])> {
        let d = self.dynamical_of(j);
        let mut out = match D {
            1 => vec![(d[0][0], [Complex64::new(1.0, 0.0); D])],
            2 => branches2(&d),
            _ => branches3(&d),
        };
        out.sort_by(|a, b| a.0.re.total_cmp(&b.0.re));
        out
    }

    /// Growth rate (c/Δx) of a branch with ω² = `w2`: Re sqrt(−ω²) ≥ 0.
    pub fn growth_of(w2: Complex64) -> f64 {
        (-w2).sqrt().re.abs()
    }

    /// Largest growth rate at k and the polarisation of that branch.
    pub fn growth(&self, k: [f64; D]) -> Result<(f64, [Complex64; D])> {
        self.growth_and_top(k).map(|(g, p, _)| (g, p))
    }

    /// [`Self::growth`] and Re ω² of the top branch (`branches(k)[D − 1]`), from one J(k).
    pub fn growth_and_top(&self, k: [f64; D]) -> Result<(f64, [Complex64; D], f64)> {
        let (g, p, b) = self.growth_and_branches(k)?;
        Ok((g, p, b[D - 1].0.re))
    }

    /// [`Self::growth`] and [`Self::branches`] from one J(k).
    #[allow(clippy::type_complexity)]
    pub fn growth_and_branches(
        &self,
        k: [f64; D],
    ) -> Result<(f64, [Complex64; D], Vec<(Complex64, [Complex64; D])>)> {
        crate::progress::interrupted()?;
        let j = if self.dissipative {
            self.jacobian(k)
        } else {
            self.jacobian_mechanical(k)
        };
        let b = self.branches_of(&j);
        if self.is_dissipative() {
            let j = j * Complex64::new(self.time_scale, 0.0);
            let g = eigen(j)?.iter().map(|s| s.re).fold(0.0, f64::max);
            let p = b[0].1;
            return Ok((g, p, b));
        }
        let mut best = (Self::growth_of(b[0].0), b[0].1);
        for br in &b[1..] {
            let g = Self::growth_of(br.0);
            if g > best.0 {
                best = (g, br.1);
            }
        }
        Ok((best.0, best.1, b))
    }

    /// Amplification matrix of one leapfrog step Δt (in Δx/c) for wave vector k.
    pub fn amplification(&self, k: [f64; D], dt: f64) -> DMatrix<Complex64> {
        self.amplification_with(k, dt, Integrator::Kdk)
    }

    /// Amplification matrix of one cycle of `integ` at k; `dt` in Δx/c.
    pub fn amplification_with(
        &self,
        k: [f64; D],
        dt: f64,
        integ: Integrator,
    ) -> DMatrix<Complex64> {
        self.core
            .amplification(self.jacobian(k), dt * self.time_scale, integ)
    }

    /// Spectral radius of the leapfrog amplification matrix at k.
    pub fn spectral_radius(&self, k: [f64; D], dt: f64) -> Result<f64> {
        spectral_radius(self, k, dt)
    }

    /// Eigenvalues s of J(k), normalised to c/Δx.
    pub fn eigenvalues(&self, k: [f64; D]) -> Result<Vec<Complex64>> {
        eigen(self.jacobian(k) * Complex64::new(self.time_scale, 0.0))
    }
}

impl<const D: usize> Modes for Bloch<D> {
    type K = [f64; D];
    fn is_dissipative(&self) -> bool {
        self.dissipative
    }
    fn omega2_top(&self, k: [f64; D]) -> f64 {
        self.branches(k)[D - 1].0.re
    }
    fn amplification_with(&self, k: [f64; D], dt: f64, integ: Integrator) -> DMatrix<Complex64> {
        Bloch::amplification_with(self, k, dt, integ)
    }
    fn growth_per_step(&self, k: [f64; D], dt: f64, integ: Integrator) -> Result<f64> {
        self.core
            .growth_per_step(self.jacobian(k), dt * self.time_scale, integ)
    }
    fn eigenvalues(&self, k: [f64; D]) -> Result<Vec<Complex64>> {
        Bloch::eigenvalues(self, k)
    }
}

/// The periodic patch being differentiated.
struct Patch<S, const D: usize> {
    model: Model<D>,
    base: State<f64, D>,
    offs: Vec<[f64; D]>,
    comps: Vec<Comp>,
    out: State<S, D>,
    ws: RateWorkspace<S, D>,
}

impl<S: Lanes, const D: usize> Patch<S, D> {
    fn new(model: Model<D>, rho: f64, offs: Vec<[f64; D]>, comps: Vec<Comp>) -> Self {
        Self {
            base: model.rest_state(rho),
            model,
            offs,
            comps,
            out: State::default(),
            ws: RateWorkspace::new(),
        }
    }
}

impl<S: Lanes, const D: usize> Linearisable for Patch<S, D> {
    type Offset = [f64; D];
    fn kinds(&self) -> Vec<FieldKind> {
        self.comps.iter().map(|c| c.kind()).collect()
    }
    fn cells(&self) -> usize {
        self.base.x.len()
    }
    fn offset(&self, i: usize) -> [f64; D] {
        self.offs[i]
    }
    fn lanes(&self) -> usize {
        S::LANES
    }
    fn seeded_rates(&mut self, b0: usize) -> Result<()> {
        let mut z: State<S, D> = self.base.map(S::cst);
        for (l, &c) in self.comps.iter().skip(b0).take(S::LANES).enumerate() {
            let mut t = z.get(c, 0);
            t.seed(l);
            z.set(c, 0, t);
        }
        self.model.rate_with(&z, &mut self.out, &mut self.ws)
    }
    fn tangent(&self, a: usize, i: usize, l: usize) -> f64 {
        self.out.get(self.comps[a], i).lane(l)
    }
}

/// The two branches of a 2 × 2 dynamical matrix (closed form), unsorted.
fn branches2<const D: usize>(d: &[[Complex64; D]; D]) -> Vec<(Complex64, [Complex64; D])> {
    let tr = d[0][0] + d[1][1];
    let det = d[0][0] * d[1][1] - d[0][1] * d[1][0];
    let disc = (tr * tr * 0.25 - det).sqrt();
    [tr * 0.5 - disc, tr * 0.5 + disc]
        .into_iter()
        .map(|l| {
            // eigenvector: (d01, l − d00) or (l − d11, d10)
            let v1 = [d[0][1], l - d[0][0]];
            let v2 = [l - d[1][1], d[1][0]];
            let n1 = v1[0].norm_sqr() + v1[1].norm_sqr();
            let n2 = v2[0].norm_sqr() + v2[1].norm_sqr();
            let (v, n) = if n1 >= n2 { (v1, n1) } else { (v2, n2) };
            let mut pol = [Complex64::new(0.0, 0.0); D];
            if n > 1e-300 {
                let s = n.sqrt();
                pol[0] = v[0] / s;
                pol[1] = v[1] / s;
            } else {
                // degenerate (D ∝ I): any direction
                pol[0] = Complex64::new(1.0, 0.0);
            }
            (l, pol)
        })
        .collect()
}

/// The three branches of a 3 × 3 dynamical matrix, unsorted: a Hermitian matrix (every
/// conservative form on these centro-symmetric lattices) by the Hermitian eigendecomposition
/// (orthonormal polarisations, also for degenerate branches); otherwise the eigenvalues of the
/// complex Schur decomposition of D/‖D‖ and each polarisation as the null vector of D − ω²I
/// (cross product of its two largest rows).
fn branches3<const D: usize>(d: &[[Complex64; D]; D]) -> Vec<(Complex64, [Complex64; D])> {
    let m = DMatrix::<Complex64>::from_fn(D, D, |a, b| d[a][b]);
    let scale = m.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let mut zero = [Complex64::new(0.0, 0.0); D];
    if scale == 0.0 || !scale.is_finite() {
        return (0..D)
            .map(|a| {
                let mut e = zero;
                e[a] = Complex64::new(1.0, 0.0);
                (Complex64::new(scale * 0.0, 0.0), e)
            })
            .collect();
    }
    let hermitian = |m: &DMatrix<Complex64>| {
        let h = (m + m.adjoint()) * Complex64::new(0.5, 0.0);
        let eig = nalgebra::SymmetricEigen::new(h);
        (0..D)
            .map(|i| {
                let mut e = [Complex64::new(0.0, 0.0); D];
                for a in 0..D {
                    e[a] = eig.eigenvectors[(a, i)];
                }
                (Complex64::new(eig.eigenvalues[i], 0.0), e)
            })
            .collect::<Vec<_>>()
    };
    // Hermitian up to round-off: relative to ‖D‖, or absolutely on the normalised O(1) scale
    // of ω²Δx²/c² (a nearly degenerate D, e.g. ≈ 4e-7·I at the bcc P point with h = 3Δx, has
    // round-off of 1e-19 in its off-diagonal entries that no relative test accepts)
    let herm = (0..D)
        .all(|a| (0..D).all(|b| (d[a][b] - d[b][a].conj()).norm() <= 1e-13 * scale.max(1e-3)));
    if herm {
        return hermitian(&m);
    }
    let Ok(vals) = eigen(m.clone() * Complex64::new(1.0 / scale, 0.0)) else {
        // no convergence of the general route (a degenerate, nearly Hermitian D): the
        // Hermitian part's eigenpairs
        return hermitian(&m);
    };
    vals.into_iter()
        .map(|l| {
            let l = l * scale;
            let mut a = m.clone();
            for i in 0..D {
                a[(i, i)] -= l;
            }
            let row = |i: usize| [a[(i, 0)], a[(i, 1)], a[(i, 2)]];
            let cross = |u: [Complex64; 3], v: [Complex64; 3]| {
                [
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                ]
            };
            let nrm = |v: &[Complex64; 3]| v.iter().map(|z| z.norm_sqr()).sum::<f64>();
            let mut best = [Complex64::new(0.0, 0.0); 3];
            for (i, j) in [(0, 1), (0, 2), (1, 2)] {
                let c = cross(row(i), row(j));
                if nrm(&c) > nrm(&best) {
                    best = c;
                }
            }
            let n = nrm(&best);
            let mut e = zero;
            if n > 1e-300 {
                for a in 0..D {
                    e[a] = best[a] / n.sqrt();
                }
            } else {
                e[0] = Complex64::new(1.0, 0.0);
            }
            zero = [Complex64::new(0.0, 0.0); D];
            (l, e)
        })
        .collect()
}

/// Memory estimate of linearising on a periodic patch of `count` particles, checked against the
/// `budget` before anything is allocated: every particle keeps a stencil of
/// dual numbers per shape family (two for the mixed forms), ~(ball of radius R)/(volume per
/// particle) neighbours each, with a quarter of spare capacity; plus the dual state and rate of
/// every particle.
pub fn check_patch_budget<const D: usize>(
    p: &ModelParams,
    lat: &Lattice<D>,
    dx: f64,
    count: usize,
    budget: &Budget,
) -> Result<()> {
    let (bytes, neighbours) = patch_bytes::<Dual, D>(p, lat, dx, count);
    budget.memory(
        fields(&["h_over_dx", "support"]),
        &format!(
            "the {D}D linearisation ({count} particles in the periodic patch, ~{neighbours:.0} neighbours per particle)"
        ),
        bytes,
    )
}

/// Estimated bytes of the linearisation of a patch of `count` particles whose rate is
/// evaluated with scalar type `S` (stencil entries of `NbD<S, D>`), and neighbours per
/// particle.
fn patch_bytes<S, const D: usize>(
    p: &ModelParams,
    lat: &Lattice<D>,
    dx: f64,
    count: usize,
) -> (f64, f64) {
    let r = p.kp.support() / dx;
    let particles = count as f64;
    let ball = match D {
        1 => 2.0 * r,
        2 => std::f64::consts::PI * r * r,
        _ => 4.0 / 3.0 * std::f64::consts::PI * r * r * r,
    };
    let neighbours = ball / lat.area() + 1.0;
    let stencils = if matches!(p.form, FormKind::Lnl | FormKind::Cll) {
        2.0
    } else {
        1.0
    };
    let entry = std::mem::size_of::<crate::forms::workspace::NbD<S, D>>() as f64;
    (
        particles * (neighbours * entry * stencils * 1.25 + 64.0 * 16.0),
        neighbours,
    )
}
