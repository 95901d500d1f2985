//! The question, in every dimension: [`Query<D>`] for D ∈ {1, 2, 3}. One struct holds every
//! input of `query`, `dispersion` and `timestep`; the engine behind it is the chain
//! linearisation in 1D ([`Linearisation`], κΔx ∈ (0, π], every form of \[B00\]) and the Bloch
//! linearisation of a lattice for D ≥ 2 ([`Bloch`], the Brillouin zone; the forms defined in
//! every dimension).

// Small-vector algebra (D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::common::{Setup, density_diffusion, linearised_av};
use crate::budget::Budget;
use crate::display::num;
use crate::error::{Error, Result, Text, check_range, field};
use crate::forms::{DiffusionForm, FormKind, Material, ModelParams, ObjectiveRate, PrestressKind};
use crate::integrator::Integrator;
use crate::kernel::Kernel;
use crate::lattice::{Lattice, LatticeKind, grid_index};
use crate::params::{check_art_stress_dim, check_common, check_count};
use crate::shape::{KernelParams, ShapeFamily};
use crate::vonneumann::linearise::{Bloch, Lattice1D, Linearisation};
use num_complex::Complex64;
use rayon::prelude::*;
use serde::Serialize;
use std::f64::consts::PI;

/// The material of a question.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum MaterialSpec {
    /// 1D: the elastic bar of modulus C, σ̇ = (C + σ) ∂v/∂x \[B00 eq 29\] ([`Material::bar`]);
    /// the only (and default) material of a 1D question.
    Bar,
    /// Hydrodynamic, p = K(ρ/ρ0 − 1); σ̄ = 1 − ρ/ρ0 (D ≥ 2).
    Hydro,
    /// Compressible neo-Hookean with Poisson ratio ν at small strain (total-Lagrangian only,
    /// D ≥ 2).
    NeoHookean {
        /// ν.
        poisson: f64,
    },
    /// Linear elastic with Poisson ratio ν (plane strain in 2D) and an objective rate (D ≥ 2).
    Elastic {
        /// ν.
        poisson: f64,
        /// Objective rate.
        rate: ObjectiveRate,
    },
}

impl std::fmt::Display for MaterialSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MaterialSpec::Bar => write!(f, "elastic bar"),
            MaterialSpec::Hydro => write!(f, "hydro"),
            MaterialSpec::NeoHookean { poisson } => write!(f, "neo-hookean ν = {}", num(*poisson)),
            MaterialSpec::Elastic { poisson, rate } => {
                let r = match rate {
                    ObjectiveRate::Jaumann => "jaumann",
                    ObjectiveRate::Truesdell => "truesdell",
                };
                write!(f, "elastic ν = {}, {r} rate", num(*poisson))
            }
        }
    }
}

/// A stability question in D ∈ {1, 2, 3} dimensions. Results are in normalised units (κΔx,
/// ω in c/Δx, Δt in Δx/c) and do not depend on the physical [`Query::units`].
#[derive(Clone, Copy, Debug)]
pub struct Query<const D: usize> {
    /// Form.
    pub form: FormKind,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// Shape family.
    pub shape: ShapeFamily,
    /// h/Δx in the kernel's own convention.
    pub h_over_dx: f64,
    /// σ̄ = σ/C (positive in tension): the pre-stress is σ̄ C Ŝ with Ŝ of [`Query::prestress`].
    pub stress: f64,
    /// The shape Ŝ of the pre-stress (D ≥ 2; isotropic by default, the only one in 1D).
    pub prestress: PrestressKind,
    /// Partition coefficient c of `lnl`/`cll`.
    pub c_partition: f64,
    /// Least-squares stabilisation α_s (form `least-squares`, 1D).
    pub alpha_s: f64,
    /// The hourglass-control coefficient ([`ModelParams::hourglass`]: ζ of `enog`, κ of
    /// `tl-enog`, Ganzenmüller's α of `total-lagrangian`); None: the form's default.
    pub hourglass: Option<f64>,
    /// Material ([`MaterialSpec::Bar`] in 1D).
    pub material: MaterialSpec,
    /// Lattice (the chain in 1D; Δx = 1).
    pub lattice: Lattice<D>,
    /// Physical spacing, density and modulus of the 1D chain (results in normalised units do not
    /// depend on them); D ≥ 2 questions are posed in Δx = ρ0 = C = 1 and keep the default.
    pub units: Lattice1D,
    /// Monaghan artificial viscosity (α, β), linearised on all pairs.
    pub av: Option<(f64, f64)>,
    /// Time step Δt (Δx/c) of the fully discrete check (`query`) and of the spurious growth
    /// (`timestep`).
    pub dt: Option<f64>,
    /// Time integrator of the fully discrete check and the critical Δt (default `kdk`).
    pub integrator: Integrator,
    /// Monaghan–Gray artificial stress (ε, n) of the classical form (2D).
    pub art_stress: Option<(f64, i32)>,
    /// δ-SPH density diffusion (δ, form).
    pub diffusion: Option<(f64, DiffusionForm)>,
    /// Sampling of the wave vectors: 1D, κΔx = πk/grid, k = 1..grid; D ≥ 2, grid wave vectors
    /// per reciprocal-lattice direction (the zone is sampled grid^D).
    pub grid: usize,
    /// The budget the linearisation must stay within.
    pub budget: Budget,
}

/// Default `grid`: 512 κ points in 1D, 64 × 64 wave vectors in 2D, 16³ in 3D.
pub const fn default_grid(dim: usize) -> usize {
    match dim {
        1 => 512,
        3 => 16,
        _ => 64,
    }
}

/// Largest `grid` in 2D: 1024² wave vectors take ~8 s for the elastic classical form on this
/// project's 2-core machine (512²: 2.0 s, measured).
pub const MAX_GRID: usize = 1024;

/// Largest `grid` in dimension `dim` (1D: 1e7 κ points; 2D: [`MAX_GRID`]; 3D: 128³ ≈ 2.1e6
/// wave vectors).
pub const fn max_grid(dim: usize) -> usize {
    match dim {
        1 => 10_000_000,
        3 => 128,
        _ => MAX_GRID,
    }
}

/// Largest `points` of a dispersion path (per path segment; 1D: κ points in (0, π]).
pub const fn max_path_points(dim: usize) -> usize {
    if dim == 1 { 10_000_000 } else { 100_000 }
}

/// The default lattice of dimension D: the chain, the square or the simple cubic lattice.
fn default_lattice<const D: usize>() -> Lattice<D> {
    let mut a = [[0.0; D]; D];
    for (i, row) in a.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    let kind = match D {
        1 => LatticeKind::Chain,
        3 => LatticeKind::Sc,
        _ => LatticeKind::Square { gamma: 1.0 },
    };
    Lattice { kind, a }
}

impl<const D: usize> Query<D> {
    /// A question with the defaults of the CLI: the form's default shape family, c = 0.5, no
    /// viscosity, `kdk`, [`default_grid`]; the bar in 1D, elastic ν = 0.3 (Jaumann) on the
    /// square (2D) or simple cubic (3D) lattice.
    pub fn new(form: FormKind, kernel: &'static dyn Kernel, h_over_dx: f64, stress: f64) -> Self {
        Self {
            form,
            kernel,
            shape: form.default_shape_in(D),
            h_over_dx,
            stress,
            prestress: PrestressKind::Isotropic,
            c_partition: 0.5,
            alpha_s: 0.0,
            hourglass: None,
            material: if D == 1 {
                MaterialSpec::Bar
            } else {
                MaterialSpec::Elastic {
                    poisson: 0.3,
                    rate: ObjectiveRate::Jaumann,
                }
            },
            lattice: default_lattice::<D>(),
            units: Lattice1D::default(),
            av: None,
            dt: None,
            integrator: Integrator::Kdk,
            art_stress: None,
            diffusion: None,
            grid: default_grid(D),
            budget: Budget::default(),
        }
    }

    /// Validates every input (one-line errors naming the field and its range).
    pub fn validate(&self) -> Result<()> {
        if !(1..=3).contains(&D) {
            return Err(Error::OutOfRange {
                field: "dim",
                value: D as f64,
                range: "must be 1, 2 or 3".into(),
            });
        }
        check_common(
            self.kernel,
            self.h_over_dx,
            self.stress,
            self.c_partition,
            self.av,
            self.dt,
        )?;
        check_count("grid", self.grid, 2, max_grid(D))?;
        check_range("alpha_s", self.alpha_s, 0.0, 100.0, true, true)?;
        if D > 1 && !self.form.in_every_dimension() {
            return Err(Error::Incompatible(
                field("form")
                    + format!(" {} is not available with ", self.form.name())
                    + field("dim")
                    + format!(
                        " {D} (classical, nonlocal, local, lnl, cll, total-lagrangian, enog, tl-enog)"
                    ),
            ));
        }
        if D == 1 && self.art_stress.is_some() {
            return Err(Error::Incompatible(
                field("art_eps") + " (artificial stress) is available with " + field("dim") + " 2",
            ));
        }
        check_art_stress_dim(D, self.art_stress.is_some())?;
        if self.art_stress.is_some() && !matches!(self.form, FormKind::Classical | FormKind::Cll) {
            return Err(Error::Incompatible(
                field("art_eps")
                    + " (artificial stress) applies to the classical and cll forms, not "
                    + field("form")
                    + format!(" {}", self.form.name()),
            ));
        }
        match (D, self.material) {
            (1, MaterialSpec::Bar) => {}
            (1, _) => {
                return Err(Error::Incompatible(
                    field("material")
                        + " applies with "
                        + field("dim")
                        + " 2 or 3 (a 1D question is the elastic bar)",
                ));
            }
            (_, MaterialSpec::Bar) => {
                return Err(Error::Incompatible(
                    field("material")
                        + " bar is the 1D material (D ≥ 2: hydro, elastic, neo-hookean)",
                ));
            }
            (_, MaterialSpec::Hydro) if self.stress >= 1.0 => {
                return Err(Error::OutOfRange {
                    field: "stress",
                    value: self.stress,
                    range: "hydro: σ̄ = 1 − ρ/ρ0 must be < 1".into(),
                });
            }
            _ => {}
        }
        if self.prestress != PrestressKind::Isotropic {
            if D == 1 {
                return Err(Error::Incompatible(
                    field("prestress")
                        + format!(" {} needs ", self.prestress.name())
                        + field("dim")
                        + " 2 or 3 (1D: the pre-stress is σ̄C along the chain)",
                ));
            }
            if !matches!(self.material, MaterialSpec::Elastic { .. }) {
                return Err(Error::Incompatible(
                    field("prestress")
                        + format!(" {} needs ", self.prestress.name())
                        + field("material")
                        + " elastic (hydro has no shear stress; neo-hookean's reference state is unstressed)",
                ));
            }
        }
        if D > 1 && self.units != Lattice1D::default() {
            return Err(Error::Incompatible(
                field("units")
                    + " are the physical units of the 1D chain (D ≥ 2 questions use Δx = ρ0 = C = 1)",
            ));
        }
        check_range("units.dx", self.units.dx, 0.0, f64::INFINITY, false, false)?;
        check_range(
            "units.rho0",
            self.units.rho0,
            0.0,
            f64::INFINITY,
            false,
            false,
        )?;
        check_range(
            "units.modulus",
            self.units.modulus,
            0.0,
            f64::INFINITY,
            false,
            false,
        )?;
        density_diffusion(self.diffusion, 1.0, self.form)?;
        self.form.check_shape(self.shape)
    }

    /// Form, kernel, shape, h, R and σ̄ of the question.
    pub fn setup(&self) -> Setup {
        Setup::new(
            self.form,
            self.kernel,
            self.shape,
            self.h_over_dx,
            self.stress,
        )
    }

    /// Support radius R/Δx.
    pub fn support_over_dx(&self) -> f64 {
        self.setup().support_over_dx
    }

    /// The material law.
    pub fn material(&self) -> Result<Material> {
        let c = self.units.modulus;
        match self.material {
            MaterialSpec::Bar => Ok(Material::bar(c)),
            MaterialSpec::Hydro => Ok(Material::Hydro { bulk: c }),
            MaterialSpec::Elastic { poisson, rate } => Material::elastic(c, poisson, rate),
            MaterialSpec::NeoHookean { poisson } => {
                match Material::elastic(c, poisson, ObjectiveRate::Truesdell)? {
                    Material::Elastic { lambda, shear, .. } => {
                        Ok(Material::NeoHookean { lambda, shear })
                    }
                    m => Ok(m),
                }
            }
        }
    }

    /// Model parameters in the physical units of [`Query::units`].
    pub fn params(&self) -> Result<ModelParams> {
        let u = self.units;
        let c = (u.modulus / u.rho0).sqrt();
        Ok(ModelParams {
            form: self.form,
            shape: self.shape,
            kp: KernelParams {
                kernel: self.kernel,
                h: self.h_over_dx * u.dx,
            },
            material: self.material()?,
            rho0: u.rho0,
            c_partition: self.c_partition,
            av: linearised_av(self.av, c),
            art_stress: self
                .art_stress
                .map(|(eps, n)| crate::forms::ArtificialStress {
                    eps,
                    n,
                    spacing: u.dx,
                }),
            diffusion: density_diffusion(self.diffusion, c, self.form)?,
            alpha_s: self.alpha_s,
            ls_length: u.dx,
            hourglass: self.hourglass,
        })
    }

    /// Whether the pre-stressed rest state sits on a kink of the artificial stress: with
    /// R = −ε Σ_{λ>0} λ P_λ/ρ², a principal pre-stress of exactly zero (σ̄ = 0; a uniaxial
    /// state's transverse direction, D ≥ 2) switches R on or off with the sign of the
    /// perturbation's own stress. The rate is not differentiable there: the linearisation is the
    /// compression side's (R's derivative 0 in that direction), and a time integration may grow
    /// where it predicts none.
    pub fn art_stress_kink(&self) -> bool {
        self.art_stress.is_some()
            && (self.stress == 0.0 || (D >= 2 && self.prestress == PrestressKind::Uniaxial))
    }

    /// The pre-stress σ0 = σ̄ C of normalised stress `stress`, physical units.
    pub fn sigma0(&self, stress: f64) -> f64 {
        stress * self.units.modulus
    }

    /// 1D: the chain linearisation at normalised stress `stress` (validated).
    pub fn chain_at(&self, stress: f64) -> Result<Linearisation> {
        self.validate()?;
        if D != 1 {
            return Err(Error::Incompatible(
                Text::from("the chain linearisation is the 1D engine, not for ")
                    + field("dim")
                    + format!(" {D} (use the Bloch linearisation)"),
            ));
        }
        Linearisation::new(self.params()?, self.sigma0(stress), self.units)
    }

    /// 1D: the chain linearisation at the question's stress.
    pub fn chain(&self) -> Result<Linearisation> {
        self.chain_at(self.stress)
    }

    /// D ≥ 2: the Bloch linearisation of the lattice at normalised stress `s` (validated).
    pub fn linearise_at(&self, s: f64) -> Result<Bloch<D>> {
        self.validate()?;
        if D == 1 {
            return Err(Error::Incompatible(
                Text::from("the Bloch linearisation is the engine of ")
                    + field("dim")
                    + " 2 or 3 (1D: the chain linearisation)",
            ));
        }
        Bloch::with_prestress(
            self.params()?,
            &self.lattice,
            1.0,
            s,
            self.prestress,
            &self.budget,
        )
    }

    /// The number of modes the question samples: grid κ points in 1D, grid^D − 1 wave vectors
    /// (Γ left out) for D ≥ 2.
    pub fn modes(&self) -> usize {
        if D == 1 {
            self.grid
        } else {
            self.grid.saturating_pow(D as u32).saturating_sub(1)
        }
    }

    /// 1D: one κΔx of the grid (the first), without listing them.
    pub fn kappa_sample(&self) -> f64 {
        PI / self.grid as f64
    }

    /// D ≥ 2: one wave vector of the zone, without listing them (a mode's matrices have the
    /// same size at every wave vector).
    pub fn k_sample(&self) -> [f64; D] {
        [PI / self.grid as f64; D]
    }

    /// 1D: the κΔx grid π k / grid, k = 1..grid.
    pub fn kappas(&self) -> Vec<f64> {
        (1..=self.grid)
            .map(|k| PI * k as f64 / self.grid as f64)
            .collect()
    }

    /// Wave vectors sampling the reciprocal cell (grid^D, without Γ, where the rigid modes
    /// live), folded into the first zone.
    pub fn kgrid(&self) -> Vec<[f64; D]> {
        let b = self.lattice.reciprocal();
        let n = self.grid;
        let count = n.pow(D as u32);
        (1..count)
            .into_par_iter()
            .map(|idx| {
                let f = grid_index::<D>(idx, n).map(|i| i as f64 / n as f64);
                let mut k = [0.0; D];
                for c in 0..D {
                    let mut v = f[0] * b[0][c];
                    for a in 1..D {
                        v += f[a] * b[a][c];
                    }
                    k[c] = v;
                }
                self.lattice.fold_with(&b, k)
            })
            .collect()
    }

    /// The continuum's ω² at wave vector `k` (units of c², k in 1/Δx), ascending in the real
    /// part: the eigenvalues of the acoustic tensor A_ac = k_b ∂σ'_ab/∂(∂_d u_c) k_d of the
    /// Eulerian law about the pre-stress σ0 (the linearisation of ρ v̇ = ∇·σ about a uniform
    /// state: the divergence of the uniform σ0 vanishes, so only the stress rate's σ' acts):
    /// σ' = λ tr ε I + 2G ε + R, R = Wσ0 − σ0W (Jaumann) or Lσ0 + σ0Lᵀ − tr(L) σ0 (Truesdell),
    /// L = u ⊗ k. An isotropic σ0 gives [`Query::continuum_moduli`] times |k|²; a deviatoric
    /// one (uniaxial, shear) turns the transverse branch along the stress by σ0/2 (Jaumann)
    /// or σ0 (Truesdell, the string's T/ρ).
    pub fn continuum_omega2(&self, k: [f64; D]) -> Result<Vec<Complex64>> {
        let k2: f64 = k.iter().map(|c| c * c).sum();
        if self.prestress == PrestressKind::Isotropic || D == 1 {
            let (cp, cs) = self.continuum_moduli()?;
            let mut v = vec![Complex64::new(cs * k2, 0.0); D - 1];
            v.push(Complex64::new(cp * k2, 0.0));
            v.sort_by(|a, b| a.re.total_cmp(&b.re));
            return Ok(v);
        }
        let c = self.units.modulus;
        let Material::Elastic {
            lambda,
            shear,
            rate,
        } = self.material()?
        else {
            return Err(Error::Incompatible(
                field("prestress")
                    + format!(" {} needs ", self.prestress.name())
                    + field("material")
                    + " elastic",
            ));
        };
        let (lam, g) = (lambda / c, shear / c);
        let s0 = self
            .prestress
            .unit::<D>()?
            .map(|r| r.map(|u| u * self.stress));
        let mut a = nalgebra::DMatrix::<f64>::zeros(D, D);
        for cc in 0..D {
            // L = e_c ⊗ k
            let l = |p: usize, q: usize| if p == cc { k[q] } else { 0.0 };
            let tr = l(cc, cc);
            for p in 0..D {
                let mut acc = 0.0;
                for b in 0..D {
                    let eps = 0.5 * (l(p, b) + l(b, p));
                    let mut sig = 2.0 * g * eps + if p == b { lam * tr } else { 0.0 };
                    for q in 0..D {
                        sig += match rate {
                            ObjectiveRate::Jaumann => {
                                0.5 * (l(p, q) - l(q, p)) * s0[q][b]
                                    - s0[p][q] * 0.5 * (l(q, b) - l(b, q))
                            }
                            ObjectiveRate::Truesdell => l(p, q) * s0[q][b] + s0[p][q] * l(b, q),
                        };
                    }
                    if rate == ObjectiveRate::Truesdell {
                        sig -= tr * s0[p][b];
                    }
                    acc += k[b] * sig;
                }
                a[(p, cc)] = acc;
            }
        }
        let mut v: Vec<Complex64> = a.complex_eigenvalues().iter().copied().collect();
        v.sort_by(|a, b| a.re.total_cmp(&b.re));
        Ok(v)
    }

    /// Whether the continuum itself is unstable at the question's pre-stress (the `material`
    /// kind): a branch with ω² ≤ 0 (or, for a fluid, < 0 on its transverse branches), or a
    /// complex ω² (flutter), in some direction. Isotropic: from [`Query::continuum_moduli`];
    /// uniaxial and shear: over 360 directions in the plane of the first two axes (2D) or, in
    /// 3D, the axes, the face and body diagonals and 400 more on the sphere (a Fibonacci set);
    /// the acoustic tensor is homogeneous of degree 2 in k, so directions suffice.
    pub fn material_unstable(&self) -> Result<bool> {
        if self.prestress == PrestressKind::Isotropic || D == 1 {
            let (cp, cs) = self.continuum_moduli()?;
            return Ok(cp <= 0.0 || cs < 0.0);
        }
        let dirs: Vec<[f64; D]> = if D == 2 {
            (0..360)
                .map(|i| {
                    let t = PI * i as f64 / 360.0;
                    std::array::from_fn(|a| if a == 0 { t.cos() } else { t.sin() })
                })
                .collect()
        } else {
            let n = 400;
            let golden = PI * (3.0 - 5f64.sqrt());
            // the axes, face and body diagonals (where the states' extremes lie), then a
            // Fibonacci set
            let mut dirs: Vec<[f64; D]> = Vec::new();
            for a in -1i32..=1 {
                for b in -1i32..=1 {
                    for c in 0i32..=1 {
                        let v = [a as f64, b as f64, c as f64];
                        let len = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                        if len > 0.0 {
                            dirs.push(std::array::from_fn(|i| v[i] / len));
                        }
                    }
                }
            }
            dirs.extend((0..n).map(|i| {
                let z = 1.0 - (i as f64 + 0.5) / n as f64 * 2.0;
                let r = (1.0 - z * z).sqrt();
                let t = golden * i as f64;
                let v = [r * t.cos(), r * t.sin(), z];
                std::array::from_fn(|a| v[a])
            }));
            dirs
        };
        for d in dirs {
            for w in self.continuum_omega2(d)? {
                if w.re <= 0.0 || w.im.abs() > 1e-12 * w.norm().max(1e-300) {
                    return Ok(true);
                }
            }
        }
        Ok(false)
    }

    /// Continuum branches ω²/|k|² (units of c²) of the material at the question's stress: (P, S).
    pub fn continuum_moduli(&self) -> Result<(f64, f64)> {
        let s = self.stress;
        let c = self.units.modulus;
        Ok(match self.material()? {
            Material::Hydro { .. } => (1.0, 0.0),
            Material::NeoHookean { shear, .. } => (1.0, shear / c),
            Material::Elastic {
                shear,
                rate: ObjectiveRate::Jaumann,
                ..
            } => (1.0, shear / c),
            Material::Elastic {
                shear,
                rate: ObjectiveRate::Truesdell,
                ..
            } => (1.0 + s, (shear / c) + s),
        })
    }
}
