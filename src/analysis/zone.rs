//! The D-dimensional front end (`--dim 2|3`, one generic code path, [`Query`]): stability over
//! the Brillouin zone of a lattice with the polarisation of the fastest mode, dispersion along the
//! high-symmetry path and the critical time step. Growth-rate maps and the finite-box prediction
//! are in [`super::maps`].

// Small-vector algebra (D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::common::{Setup, linearised_av};
use crate::budget::Budget;
use crate::error::{Error, Result, field};
use crate::forms::{FormKind, Material, ModelParams, ObjectiveRate};
use crate::kernel::Kernel;
use crate::lattice::{Lattice, LatticeKind, grid_index};
use crate::params::{check_art_stress_dim, check_common, check_count};
use crate::shape::KernelParams;
use crate::shape::ShapeFamily;
use crate::vonneumann::amplification::{AMPLIFICATION_TOL, critical_dt_given};
use crate::vonneumann::classify::{GROWTH_TOL, Kind, ZERO_OMEGA2_TOL, growth_kind};
use crate::vonneumann::damping::{branch_eigenvalues, damping_ratio};
use crate::vonneumann::linearise::Bloch;
use rayon::prelude::*;
use serde::Serialize;

/// Material choice of a 2D or 3D query.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum MaterialSpec {
    /// Hydrodynamic, p = K(ρ/ρ0 − 1); σ̄ = 1 − ρ/ρ0.
    Hydro,
    /// Compressible neo-Hookean with Poisson ratio ν at small strain (total-Lagrangian only).
    NeoHookean {
        /// ν.
        poisson: f64,
    },
    /// Linear elastic with Poisson ratio ν (plane strain in 2D) and an objective rate.
    Elastic {
        /// ν.
        poisson: f64,
        /// Objective rate.
        rate: ObjectiveRate,
    },
}

/// A stability question in D ∈ {2, 3} dimensions (units: Δx = 1, C = 1, ρ0 = 1).
#[derive(Clone, Copy, Debug)]
pub struct Query<const D: usize> {
    /// Form.
    pub form: FormKind,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// Shape family.
    pub shape: ShapeFamily,
    /// h/Δx.
    pub h_over_dx: f64,
    /// σ̄ (isotropic, positive in tension).
    pub stress: f64,
    /// Partition coefficient of lnl/cll.
    pub c_partition: f64,
    /// Material.
    pub material: MaterialSpec,
    /// Lattice.
    pub lattice: Lattice<D>,
    /// Artificial viscosity (α, β), linearised on all pairs.
    pub av: Option<(f64, f64)>,
    /// Leapfrog Δt (Δx/c) to check.
    pub dt: Option<f64>,
    /// Time integrator of the fully discrete check and the critical Δt (default `kdk`).
    pub integrator: crate::integrator::Integrator,
    /// Artificial stress (ε, n) of the classical form.
    pub art_stress: Option<(f64, i32)>,
    /// δ-SPH density diffusion (δ, form).
    pub diffusion: Option<(f64, crate::forms::DiffusionForm)>,
    /// Wave vectors per reciprocal-lattice direction (the zone is sampled n^D).
    pub grid: usize,
    /// The budget the linearisation must stay within.
    pub budget: Budget,
}

/// Default `grid`: 64 × 64 wave vectors in 2D, 16³ in 3D.
pub const fn default_grid(dim: usize) -> usize {
    if dim == 3 { 16 } else { 64 }
}

/// Largest `grid` in dimension `dim` (2D: [`MAX_GRID`]; 3D: 128³ ≈ 2.1e6 wave vectors).
pub const fn max_grid(dim: usize) -> usize {
    if dim == 3 { 128 } else { MAX_GRID }
}

impl<const D: usize> Query<D> {
    /// Defaults: square (2D) or simple cubic (3D) lattice, elastic ν = 0.3 (Jaumann),
    /// [`default_grid`] wave vectors per direction.
    pub fn new(form: FormKind, kernel: &'static dyn Kernel, h_over_dx: f64, stress: f64) -> Self {
        Self {
            form,
            kernel,
            shape: form.default_shape_in(2),
            h_over_dx,
            stress,
            c_partition: 0.5,
            material: MaterialSpec::Elastic {
                poisson: 0.3,
                rate: ObjectiveRate::Jaumann,
            },
            lattice: {
                let mut a = [[0.0; D]; D];
                for (i, row) in a.iter_mut().enumerate() {
                    row[i] = 1.0;
                }
                let kind = if D == 3 {
                    LatticeKind::Sc
                } else {
                    LatticeKind::Square { gamma: 1.0 }
                };
                Lattice { kind, a }
            },
            av: None,
            dt: None,
            integrator: crate::integrator::Integrator::Kdk,
            art_stress: None,
            diffusion: None,
            grid: default_grid(D),
            budget: Budget::default(),
        }
    }

    /// Validates the inputs.
    pub fn validate(&self) -> Result<()> {
        check_common(
            self.kernel,
            self.h_over_dx,
            self.stress,
            self.c_partition,
            self.av,
            self.dt,
        )?;
        check_count("grid", self.grid, 2, max_grid(D))?;
        if !self.form.in_every_dimension() {
            return Err(Error::Incompatible(
                field("form")
                    + format!(" {} is not available with ", self.form.name())
                    + field("dim")
                    + format!(" {D} (classical, nonlocal, local, lnl, cll, total-lagrangian)"),
            ));
        }
        check_art_stress_dim(D, self.art_stress.is_some())?;
        if self.material == MaterialSpec::Hydro && self.stress >= 1.0 {
            return Err(Error::OutOfRange {
                field: "stress",
                value: self.stress,
                range: "hydro: σ̄ = 1 − ρ/ρ0 must be < 1".into(),
            });
        }
        self.form.check_shape(self.shape)
    }

    /// The material.
    pub fn material(&self) -> Result<Material> {
        match self.material {
            MaterialSpec::Hydro => Ok(Material::Hydro { bulk: 1.0 }),
            MaterialSpec::Elastic { poisson, rate } => Material::elastic(1.0, poisson, rate),
            MaterialSpec::NeoHookean { poisson } => {
                match Material::elastic(1.0, poisson, ObjectiveRate::Truesdell)? {
                    Material::Elastic { lambda, shear, .. } => {
                        Ok(Material::NeoHookean { lambda, shear })
                    }
                    m => Ok(m),
                }
            }
        }
    }

    /// Model parameters (C = 1, ρ0 = 1, Δx = 1).
    pub fn params(&self) -> Result<ModelParams> {
        Ok(ModelParams {
            form: self.form,
            shape: self.shape,
            kp: KernelParams {
                kernel: self.kernel,
                h: self.h_over_dx,
            },
            material: self.material()?,
            rho0: 1.0,
            c_partition: self.c_partition,
            av: linearised_av(self.av, 1.0),
            art_stress: self
                .art_stress
                .map(|(eps, n)| crate::forms::ArtificialStress {
                    eps,
                    n,
                    spacing: 1.0,
                }),
            diffusion: super::common::density_diffusion(self.diffusion, 1.0, self.form)?,
            alpha_s: 0.0,
            ls_length: 1.0,
        })
    }

    /// Linearisation at stress `s`.
    pub fn linearise_at(&self, s: f64) -> Result<Bloch<D>> {
        self.validate()?;
        Bloch::with_budget(self.params()?, &self.lattice, 1.0, s, &self.budget)
    }

    /// Wave vectors sampling the reciprocal cell (n^D, without Γ, where the rigid modes live),
    /// folded into the first zone.
    pub fn kgrid(&self) -> Vec<[f64; D]> {
        let b = self.lattice.reciprocal();
        let n = self.grid;
        let count = n.pow(D as u32);
        let mut out = Vec::with_capacity(count);
        for idx in 1..count {
            let f = grid_index::<D>(idx, n).map(|i| i as f64 / n as f64);
            let mut k = [0.0; D];
            for c in 0..D {
                let mut v = f[0] * b[0][c];
                for a in 1..D {
                    v += f[a] * b[a][c];
                }
                k[c] = v;
            }
            out.push(self.lattice.fold(k));
        }
        out
    }
}

/// The image of k in the first Brillouin zone (nearest to Γ among k − G).
pub fn fold<const D: usize>(lat: &Lattice<D>, k: [f64; D]) -> [f64; D] {
    lat.fold(k)
}

/// Polarisation of a branch: real unit vector and the longitudinal fraction |ê·k̂|².
#[derive(Clone, Debug, Serialize)]
pub struct Polarisation {
    /// Unit polarisation (real part after removing the global phase).
    pub vector: Vec<f64>,
    /// |ê·k̂|² (1 longitudinal, 0 transverse).
    pub longitudinal_fraction: f64,
}

fn polarisation<const D: usize>(p: [num_complex::Complex64; D], k: [f64; D]) -> Polarisation {
    // remove the global phase: make the largest component real (the first of equals)
    let mut m = p[0];
    for &c in &p[1..] {
        if c.norm() > m.norm() {
            m = c;
        }
    }
    let ph = if m.norm() > 0.0 {
        m.conj() / m.norm()
    } else {
        num_complex::Complex64::new(1.0, 0.0)
    };
    let v: Vec<f64> = p.iter().map(|&c| (c * ph).re).collect();
    let len = |x: &[f64]| {
        if D == 2 {
            x[0].hypot(x[1])
        } else {
            x.iter().map(|a| a * a).sum::<f64>().sqrt()
        }
    };
    let nv = len(&v).max(1e-300);
    let kn = len(&k);
    let lf = if kn > 0.0 {
        let mut pk = p[0] * k[0];
        for a in 1..D {
            pk += p[a] * k[a];
        }
        (pk.norm() / kn).powi(2)
    } else {
        0.0
    };
    Polarisation {
        vector: v.iter().map(|x| x / nv).collect(),
        longitudinal_fraction: lf,
    }
}

/// One unstable or marginal set of wave vectors.
#[derive(Clone, Debug, Serialize)]
pub struct Instability2D {
    /// Kind.
    pub kind: Kind,
    /// Largest growth rate (c/Δx); 0 for zero-energy modes.
    pub growth_rate: f64,
    /// Wave vector of the largest growth [κxΔx, κyΔx(, κzΔx)].
    pub kappa_at_max: Vec<f64>,
    /// Fraction of the sampled zone affected.
    pub zone_fraction: f64,
}

/// Verdict of a 2D or 3D query.
#[derive(Clone, Debug, Serialize)]
pub struct QueryReport2D {
    /// 2 or 3.
    pub dim: u8,
    /// Form, kernel, shape, h, R, σ̄.
    #[serde(flatten)]
    pub setup: Setup,
    /// Material.
    pub material: MaterialSpec,
    /// Lattice.
    pub lattice: LatticeKind,
    /// Δx as defined for the lattice (crate::lattice: the spacing in 2D, the cube root of the
    /// volume per particle in 3D), and the nearest-neighbour distance in units of it.
    pub nearest_neighbour_over_dx: f64,
    /// Sampled wave vectors per direction.
    pub grid: usize,
    /// No exponentially growing mode (and no time-step amplification at `dt`).
    pub stable: bool,
    /// Largest growth rate (c/Δx), 0 if stable.
    pub max_growth_rate: f64,
    /// Fastest wave vector [κxΔx, κyΔx(, κzΔx)] (null if stable).
    pub kappa_at_max: Option<Vec<f64>>,
    /// Polarisation of the fastest mode (null if stable).
    pub polarisation: Option<Polarisation>,
    /// Unstable / marginal sets.
    pub instabilities: Vec<Instability2D>,
    /// Spurious zero-energy modes (beyond the continuum's own zero branches).
    pub has_zero_energy_modes: bool,
    /// Critical leapfrog Δt (Δx/c), null if the semi-discrete system grows.
    pub critical_dt: Option<f64>,
    /// c Δt_crit / h.
    pub critical_cfl: Option<f64>,
    /// Δt checked.
    pub dt: Option<f64>,
    /// Largest |λ| at Δt.
    pub max_amplification: Option<f64>,
    /// Time integrator of `critical_dt` and of the check at `dt`.
    pub integrator: &'static str,
    /// Growth per unit time (c/Δx) the integrator adds to the non-growing modes at `dt`
    /// (ln|λ|/Δt at the worst one; 0 if none, or no `dt`).
    pub spurious_growth_rate: f64,
}

/// Continuum branches (ω²/|k|² in units of c²) of the material at stress s: (P, S).
pub fn continuum_moduli<const D: usize>(q: &Query<D>) -> Result<(f64, f64)> {
    let s = q.stress;
    Ok(match q.material()? {
        Material::Hydro { .. } => (1.0, 0.0),
        Material::NeoHookean { shear, .. } => (1.0, shear),
        Material::Elastic {
            shear,
            rate: ObjectiveRate::Jaumann,
            ..
        } => (1.0, shear),
        Material::Elastic {
            shear,
            rate: ObjectiveRate::Truesdell,
            ..
        } => (1.0 + s, shear + s),
    })
}

/// Answers a 2D stability query ([`query_nd`] with D = 2).
pub fn query2d(q: &Query<2>) -> Result<QueryReport2D> {
    query_nd(q)
}

/// Nearest-neighbour distance of a lattice (units of its Δx).
fn nearest_neighbour<const D: usize>(lat: &Lattice<D>) -> f64 {
    lat.offsets_within(3.0)
        .iter()
        .map(|(_, p)| p.iter().map(|c| c * c).sum::<f64>().sqrt())
        .filter(|&r| r > 1e-12)
        .fold(f64::INFINITY, f64::min)
}

/// Answers a stability query in D dimensions.
pub fn query_nd<const D: usize>(q: &Query<D>) -> Result<QueryReport2D> {
    let lin = q.linearise_at(q.stress)?;
    let ks = q.kgrid();
    let (cp, cs) = continuum_moduli(q)?;
    // the continuum's own zero branches: the D − 1 transverse ones of a fluid
    let continuum_zero = if cs == 0.0 { D - 1 } else { 0 };
    let mut grow = Vec::with_capacity(ks.len());
    let mut pol = Vec::with_capacity(ks.len());
    let mut w2max: f64 = 0.0;
    let mut zeros = Vec::with_capacity(ks.len());
    // one J(k) per wave vector, in parallel
    let modes: Vec<_> = ks
        .par_iter()
        .map(|&k| lin.growth_and_branches(k))
        .collect::<Result<_>>()?;
    for (g, p, br) in modes {
        if !g.is_finite() || br.iter().any(|b| !b.0.re.is_finite()) {
            return Err(Error::NonFinite("dispersion branches (eigenvalues)"));
        }
        w2max = w2max.max(br[D - 1].0.re);
        zeros.push(br);
        grow.push(g);
        pol.push(p);
    }
    let growing: Vec<usize> = (0..ks.len()).filter(|&i| grow[i] > GROWTH_TOL).collect();
    let mut inst = Vec::new();
    let (mut gmax, mut kmax, mut pmax) = (0.0, None, None);
    if let Some(&imax) = growing
        .iter()
        .max_by(|&&a, &&b| grow[a].total_cmp(&grow[b]))
    {
        gmax = grow[imax];
        kmax = Some(ks[imax].to_vec());
        pmax = Some(polarisation(pol[imax], ks[imax]));
        let kind = growth_kind(cp <= 0.0 || cs < 0.0, q.stress, || {
            Ok(q.linearise_at(0.0)?.growth(ks[imax])?.0)
        })?;
        inst.push(Instability2D {
            kind,
            growth_rate: gmax,
            kappa_at_max: ks[imax].to_vec(),
            zone_fraction: growing.len() as f64 / ks.len() as f64,
        });
    }
    // zero-energy modes: more zero branches than the continuum has, at k ≠ 0
    let tol = ZERO_OMEGA2_TOL * w2max.max(1e-300);
    let spurious: Vec<usize> = (0..ks.len())
        .filter(|&i| {
            ks[i].iter().any(|c| c.abs() > 1e-12)
                && grow[i] <= GROWTH_TOL
                && zeros[i].iter().filter(|b| b.0.norm() <= tol).count() > continuum_zero
        })
        .collect();
    if let Some(&i0) = spurious.first() {
        inst.push(Instability2D {
            kind: Kind::RankDeficiency,
            growth_rate: 0.0,
            kappa_at_max: ks[i0].to_vec(),
            zone_fraction: spurious.len() as f64 / ks.len() as f64,
        });
    }
    let semi_stable = growing.is_empty();
    let integ = q.integrator;
    let (cdt, weak) = if integ == crate::integrator::Integrator::Kdk {
        (
            semi_stable
                .then(|| critical_dt_given(&lin, &ks, w2max))
                .transpose()?,
            false,
        )
    } else {
        let st = crate::vonneumann::amplification::step_stability(&lin, &ks, integ)?;
        (st.critical_dt.filter(|_| semi_stable), st.weak)
    };
    let mut max_amp = None;
    let mut ts = false;
    let mut spurious_rate = 0.0;
    if let Some(dt) = q.dt {
        let mut best = (0.0f64, [0.0; D], 0usize);
        let rho: Vec<f64> = ks
            .iter()
            .map(|&k| crate::vonneumann::amplification::spectral_radius_with(&lin, k, dt, integ))
            .collect::<Result<_>>()?;
        for (i, (&k, &r)) in ks.iter().zip(&rho).enumerate() {
            if r > 1.0 + AMPLIFICATION_TOL && grow[i] <= GROWTH_TOL {
                best.2 += 1;
            }
            if r > best.0 {
                best = (r, k, best.2);
            }
        }
        max_amp = Some(best.0);
        if best.2 > 0 {
            ts = true;
            spurious_rate = best.0.ln() / dt;
            inst.push(Instability2D {
                kind: if weak {
                    Kind::Integrator
                } else {
                    Kind::TimeStep
                },
                growth_rate: best.0.ln() / dt,
                kappa_at_max: best.1.to_vec(),
                zone_fraction: best.2 as f64 / ks.len() as f64,
            });
        }
    }
    Ok(QueryReport2D {
        dim: D as u8,
        setup: Setup::new(q.form, q.kernel, q.shape, q.h_over_dx, q.stress),
        material: q.material,
        lattice: q.lattice.kind,
        nearest_neighbour_over_dx: nearest_neighbour(&q.lattice),
        grid: q.grid,
        stable: semi_stable && !ts,
        max_growth_rate: gmax,
        kappa_at_max: kmax,
        polarisation: pmax,
        instabilities: inst,
        has_zero_energy_modes: !spurious.is_empty(),
        critical_dt: cdt,
        critical_cfl: cdt.map(|d| d / q.h_over_dx),
        dt: q.dt,
        integrator: integ.name(),
        spurious_growth_rate: spurious_rate,
        max_amplification: max_amp,
    })
}

/// Dispersion along the high-symmetry path.
#[derive(Clone, Debug, Serialize)]
pub struct Dispersion2D {
    /// Form, kernel, h, σ̄ as in `query`.
    pub form: &'static str,
    /// Kernel.
    pub kernel: &'static str,
    /// h/Δx.
    pub h_over_dx: f64,
    /// σ̄.
    pub stress: f64,
    /// Path labels and their arc-length positions.
    pub labels: Vec<(String, f64)>,
    /// Arc length along the path (units 1/Δx).
    pub path: Vec<f64>,
    /// Wave vectors [κxΔx, κyΔx(, κzΔx)].
    pub kappa: Vec<Vec<f64>>,
    /// Re ω²Δx²/c² of the D branches (ascending).
    pub omega2: Vec<Vec<f64>>,
    /// Growth rate at each point (c/Δx).
    pub growth_rate: Vec<f64>,
    /// Continuum branches ω²Δx²/c², ascending: the D − 1 S (transverse) branches, then P.
    pub omega2_continuum: Vec<Vec<f64>>,
    /// Dissipative systems only (absent otherwise): damping rate Re s (c/Δx, ≤ 0 when damped)
    /// of each of the D branches (order of `omega2`) from the exact eigenvalues of J(k); null
    /// where the matching is ambiguous (rule in [`crate::vonneumann::damping`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_rate: Option<Vec<Vec<Option<f64>>>>,
    /// Dissipative systems only: damping ratio ξ = −Re s/|s| of the same eigenvalues.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_ratio: Option<Vec<Vec<Option<f64>>>>,
}

/// Largest `grid` (wave vectors per reciprocal direction): 1024² wave vectors take ~8 s for
/// the elastic classical form on this project's 2-core machine (512²: 2.0 s, measured).
pub const MAX_GRID: usize = 1024;
/// Largest `points` of a 2D dispersion path (per path segment).
pub const MAX_PATH_POINTS: usize = 100_000;

/// Dispersion along the high-symmetry path of the lattice ([`Lattice::symmetry_points`]), `n`
/// points per segment.
pub fn dispersion2d<const D: usize>(q: &Query<D>, n: usize) -> Result<Dispersion2D> {
    check_count("points", n, 2, MAX_PATH_POINTS)?;
    let lin = q.linearise_at(q.stress)?;
    let (cp, cs) = continuum_moduli(q)?;
    let path = q.lattice.symmetry_path(n);
    let mut labels = Vec::new();
    let pts = q.lattice.symmetry_points();
    let mut s = 0.0;
    labels.push((pts[0].0.to_string(), 0.0));
    for w in pts.windows(2) {
        s += if D == 2 {
            (w[1].1[0] - w[0].1[0]).hypot(w[1].1[1] - w[0].1[1])
        } else {
            (0..D)
                .map(|a| (w[1].1[a] - w[0].1[a]).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        labels.push((w[1].0.to_string(), s));
    }
    let mut out = Dispersion2D {
        form: q.form.name(),
        kernel: q.kernel.name(),
        h_over_dx: q.h_over_dx,
        stress: q.stress,
        labels,
        path: Vec::new(),
        kappa: Vec::new(),
        omega2: Vec::new(),
        growth_rate: Vec::new(),
        omega2_continuum: Vec::new(),
        damping_rate: lin.is_dissipative().then(Vec::new),
        damping_ratio: lin.is_dissipative().then(Vec::new),
    };
    for (k, s) in path {
        let b = lin.branches(k);
        let mut k2 = k[0] * k[0];
        for a in 1..D {
            k2 += k[a] * k[a];
        }
        out.path.push(s);
        out.kappa.push(k.to_vec());
        let w2: Vec<f64> = b.iter().map(|x| x.0.re).collect();
        if let (Some(rate), Some(ratio)) = (&mut out.damping_rate, &mut out.damping_ratio) {
            let s = branch_eigenvalues(&lin.eigenvalues(k)?, &w2);
            rate.push(s.iter().map(|s| s.map(|s| s.re)).collect());
            ratio.push(s.iter().map(|s| s.map(damping_ratio)).collect());
        }
        out.omega2.push(w2);
        out.growth_rate.push(lin.growth(k)?.0);
        let mut cont = vec![cs * k2; D - 1];
        cont.push(cp * k2);
        out.omega2_continuum.push(cont);
    }
    Ok(out)
}

impl std::fmt::Display for MaterialSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MaterialSpec::Hydro => write!(f, "hydro"),
            MaterialSpec::NeoHookean { poisson } => write!(f, "neo-hookean ν = {poisson}"),
            MaterialSpec::Elastic { poisson, rate } => {
                let r = match rate {
                    ObjectiveRate::Jaumann => "jaumann",
                    ObjectiveRate::Truesdell => "truesdell",
                };
                write!(f, "elastic ν = {poisson}, {r} rate")
            }
        }
    }
}
