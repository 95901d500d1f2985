//! 2D questions: stability over the Brillouin zone (`query --dim 2`), dispersion along the
//! high-symmetry path, critical time step, growth-rate maps, and the finite-box prediction.

use crate::error::{Error, Result};
use crate::forms::{ArtificialViscosity, FormKind, Material2D, ModelParams2D, ObjectiveRate};
use crate::kernel::Kernel;
use crate::lattice::{Lattice2D, LatticeKind};
use crate::shape::ShapeFamily;
use crate::shape2d::KernelParams2;
use crate::vonneumann::amplification::AMPLIFICATION_TOL;
use crate::vonneumann::classify::{GROWTH_TOL, Kind, ZERO_OMEGA2_TOL};
use crate::vonneumann::linearise2d::Linearisation2D;
use serde::Serialize;
use std::f64::consts::PI;

/// Material choice of a 2D query.
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
    /// Linear elastic with Poisson ratio ν (plane strain) and an objective rate.
    Elastic {
        /// ν.
        poisson: f64,
        /// Objective rate.
        rate: ObjectiveRate,
    },
}

/// A 2D stability question (units: Δx = 1, C = 1, ρ0 = 1).
#[derive(Clone, Copy, Debug)]
pub struct Query2D {
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
    pub lattice: Lattice2D,
    /// Artificial viscosity (α, β), linearised on all pairs.
    pub av: Option<(f64, f64)>,
    /// Leapfrog Δt (Δx/c) to check.
    pub dt: Option<f64>,
    /// Artificial stress (ε, n) of the classical form.
    pub art_stress: Option<(f64, i32)>,
    /// Wave vectors per reciprocal-lattice direction (the zone is sampled n × n).
    pub grid: usize,
}

impl Query2D {
    /// Defaults: square lattice, elastic ν = 0.3 (Jaumann), 64 × 64 wave vectors.
    pub fn new(form: FormKind, kernel: &'static dyn Kernel, h_over_dx: f64, stress: f64) -> Self {
        Self {
            form,
            kernel,
            shape: form.default_shape_2d(),
            h_over_dx,
            stress,
            c_partition: 0.5,
            material: MaterialSpec::Elastic {
                poisson: 0.3,
                rate: ObjectiveRate::Jaumann,
            },
            lattice: Lattice2D {
                kind: LatticeKind::Square { gamma: 1.0 },
                a: [[1.0, 0.0], [0.0, 1.0]],
            },
            av: None,
            dt: None,
            art_stress: None,
            grid: 64,
        }
    }

    /// Validates the inputs.
    pub fn validate(&self) -> Result<()> {
        crate::analysis::check_common(
            self.kernel,
            self.h_over_dx,
            self.stress,
            self.c_partition,
            self.av,
            self.dt,
        )?;
        check_count("--grid", self.grid, 2, MAX_GRID)?;
        if !self.form.in_2d() {
            return Err(Error::Incompatible(format!(
                "--form {} is not available with --dim 2 (classical, nonlocal, local, lnl, cll, total-lagrangian)",
                self.form.name()
            )));
        }
        if self.material == MaterialSpec::Hydro && self.stress >= 1.0 {
            return Err(Error::OutOfRange {
                name: "--stress",
                value: self.stress,
                range: "hydro: σ̄ = 1 − ρ/ρ0 must be < 1".into(),
            });
        }
        self.form.check_shape(self.shape)
    }

    /// The material.
    pub fn material(&self) -> Result<Material2D> {
        match self.material {
            MaterialSpec::Hydro => Ok(Material2D::Hydro { bulk: 1.0 }),
            MaterialSpec::Elastic { poisson, rate } => Material2D::elastic(1.0, poisson, rate),
            MaterialSpec::NeoHookean { poisson } => {
                match Material2D::elastic(1.0, poisson, ObjectiveRate::Truesdell)? {
                    Material2D::Elastic { lambda, shear, .. } => {
                        Ok(Material2D::NeoHookean { lambda, shear })
                    }
                    m => Ok(m),
                }
            }
        }
    }

    /// Model parameters (C = 1, ρ0 = 1, Δx = 1).
    pub fn params(&self) -> Result<ModelParams2D> {
        Ok(ModelParams2D {
            form: self.form,
            shape: self.shape,
            kp: KernelParams2 {
                kernel: self.kernel,
                h: self.h_over_dx,
            },
            material: self.material()?,
            rho0: 1.0,
            c_partition: self.c_partition,
            av: self.av.map(|(alpha, beta)| ArtificialViscosity {
                alpha,
                beta,
                sound_speed: 1.0,
                approaching_only: false,
            }),
            art_stress: self
                .art_stress
                .map(|(eps, n)| crate::forms::ArtificialStress {
                    eps,
                    n,
                    spacing: 1.0,
                }),
        })
    }

    /// Linearisation at stress `s`.
    pub fn linearise_at(&self, s: f64) -> Result<Linearisation2D> {
        self.validate()?;
        Linearisation2D::new(self.params()?, &self.lattice, 1.0, s)
    }

    /// Wave vectors sampling the reciprocal cell (n × n, without Γ, where the rigid modes
    /// live), folded into the first zone.
    pub fn kgrid(&self) -> Vec<[f64; 2]> {
        let b = self.lattice.reciprocal();
        let n = self.grid;
        let mut out = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                if i == 0 && j == 0 {
                    continue;
                }
                let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
                out.push(fold(
                    &self.lattice,
                    [s * b[0][0] + t * b[1][0], s * b[0][1] + t * b[1][1]],
                ));
            }
        }
        out
    }
}

/// The image of k in the first Brillouin zone (nearest to Γ among k − G).
pub fn fold(lat: &Lattice2D, k: [f64; 2]) -> [f64; 2] {
    let b = lat.reciprocal();
    let mut best = k;
    let mut bn = k[0].hypot(k[1]);
    for m in -2i64..=2 {
        for n in -2i64..=2 {
            let q = [
                k[0] - m as f64 * b[0][0] - n as f64 * b[1][0],
                k[1] - m as f64 * b[0][1] - n as f64 * b[1][1],
            ];
            let qn = q[0].hypot(q[1]);
            if qn < bn - 1e-12 {
                best = q;
                bn = qn;
            }
        }
    }
    best
}

/// Polarisation of a branch: real unit vector and the longitudinal fraction |ê·k̂|².
#[derive(Clone, Debug, Serialize)]
pub struct Polarisation {
    /// Unit polarisation (real part after removing the global phase).
    pub vector: [f64; 2],
    /// |ê·k̂|² (1 longitudinal, 0 transverse).
    pub longitudinal_fraction: f64,
}

fn polarisation(p: [num_complex::Complex64; 2], k: [f64; 2]) -> Polarisation {
    // remove the global phase: make the largest component real
    let m = if p[0].norm() >= p[1].norm() {
        p[0]
    } else {
        p[1]
    };
    let ph = if m.norm() > 0.0 {
        m.conj() / m.norm()
    } else {
        num_complex::Complex64::new(1.0, 0.0)
    };
    let v = [(p[0] * ph).re, (p[1] * ph).re];
    let nv = v[0].hypot(v[1]).max(1e-300);
    let kn = k[0].hypot(k[1]);
    let lf = if kn > 0.0 {
        ((p[0] * k[0] + p[1] * k[1]).norm() / kn).powi(2)
    } else {
        0.0
    };
    Polarisation {
        vector: [v[0] / nv, v[1] / nv],
        longitudinal_fraction: lf,
    }
}

/// One unstable or marginal set of wave vectors in 2D.
#[derive(Clone, Debug, Serialize)]
pub struct Instability2D {
    /// Kind.
    pub kind: Kind,
    /// Largest growth rate (c/Δx); 0 for zero-energy modes.
    pub growth_rate: f64,
    /// Wave vector of the largest growth [κxΔx, κyΔx].
    pub kappa_at_max: [f64; 2],
    /// Fraction of the sampled zone affected.
    pub zone_fraction: f64,
}

/// Verdict of a 2D query.
#[derive(Clone, Debug, Serialize)]
pub struct QueryReport2D {
    /// Always 2.
    pub dim: u8,
    /// Form name.
    pub form: &'static str,
    /// Kernel name.
    pub kernel: &'static str,
    /// Shape family.
    pub shape: &'static str,
    /// h/Δx.
    pub h_over_dx: f64,
    /// R/Δx.
    pub support_over_dx: f64,
    /// σ̄.
    pub stress: f64,
    /// Material.
    pub material: MaterialSpec,
    /// Lattice.
    pub lattice: LatticeKind,
    /// Sampled wave vectors per direction.
    pub grid: usize,
    /// No exponentially growing mode (and no time-step amplification at `dt`).
    pub stable: bool,
    /// Largest growth rate (c/Δx), 0 if stable.
    pub max_growth_rate: f64,
    /// Fastest wave vector [κxΔx, κyΔx] (null if stable).
    pub kappa_at_max: Option<[f64; 2]>,
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
}

/// Continuum branches (ω²/|k|² in units of c²) of the material at stress s: (P, S).
pub fn continuum_moduli(q: &Query2D) -> Result<(f64, f64)> {
    let s = q.stress;
    Ok(match q.material()? {
        Material2D::Hydro { .. } => (1.0, 0.0),
        Material2D::NeoHookean { shear, .. } => (1.0, shear),
        Material2D::Elastic {
            shear,
            rate: ObjectiveRate::Jaumann,
            ..
        } => (1.0, shear),
        Material2D::Elastic {
            shear,
            rate: ObjectiveRate::Truesdell,
            ..
        } => (1.0 + s, shear + s),
    })
}

/// Answers a 2D stability query.
pub fn query2d(q: &Query2D) -> Result<QueryReport2D> {
    let lin = q.linearise_at(q.stress)?;
    let ks = q.kgrid();
    let (cp, cs) = continuum_moduli(q)?;
    let continuum_zero = usize::from(cs == 0.0);
    let mut grow = Vec::with_capacity(ks.len());
    let mut pol = Vec::with_capacity(ks.len());
    let mut w2max: f64 = 0.0;
    let mut zeros = Vec::with_capacity(ks.len());
    for &k in &ks {
        let (g, p) = lin.growth(k)?;
        let br = lin.branches(k);
        w2max = w2max.max(br[1].0.re);
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
        kmax = Some(ks[imax]);
        pmax = Some(polarisation(pol[imax], ks[imax]));
        let kind = if cp <= 0.0 || cs < 0.0 {
            Kind::Material
        } else if q.stress == 0.0 {
            Kind::Indefinite
        } else {
            let l0 = q.linearise_at(0.0)?;
            if l0.growth(ks[imax])?.0 > GROWTH_TOL {
                Kind::Indefinite
            } else if q.stress > 0.0 {
                Kind::Tensile
            } else {
                Kind::Compressive
            }
        };
        inst.push(Instability2D {
            kind,
            growth_rate: gmax,
            kappa_at_max: ks[imax],
            zone_fraction: growing.len() as f64 / ks.len() as f64,
        });
    }
    // zero-energy modes: more zero branches than the continuum has, at k ≠ 0
    let tol = ZERO_OMEGA2_TOL * w2max.max(1e-300);
    let spurious: Vec<usize> = (0..ks.len())
        .filter(|&i| {
            ks[i][0].hypot(ks[i][1]) > 1e-12
                && grow[i] <= GROWTH_TOL
                && zeros[i].iter().filter(|b| b.0.norm() <= tol).count() > continuum_zero
        })
        .collect();
    if let Some(&i0) = spurious.first() {
        inst.push(Instability2D {
            kind: Kind::RankDeficiency,
            growth_rate: 0.0,
            kappa_at_max: ks[i0],
            zone_fraction: spurious.len() as f64 / ks.len() as f64,
        });
    }
    let semi_stable = growing.is_empty();
    let cdt = if !semi_stable {
        None
    } else if lin.is_dissipative() {
        Some(critical_dt_2d(&lin, &ks)?)
    } else {
        Some(if w2max > 0.0 {
            2.0 / w2max.sqrt()
        } else {
            f64::INFINITY
        })
    };
    let mut max_amp = None;
    let mut ts = false;
    if let Some(dt) = q.dt {
        let mut best = (0.0f64, [0.0; 2], 0usize);
        for (i, &k) in ks.iter().enumerate() {
            let r = lin.spectral_radius(k, dt)?;
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
            inst.push(Instability2D {
                kind: Kind::TimeStep,
                growth_rate: best.0.ln() / dt,
                kappa_at_max: best.1,
                zone_fraction: best.2 as f64 / ks.len() as f64,
            });
        }
    }
    Ok(QueryReport2D {
        dim: 2,
        form: q.form.name(),
        kernel: q.kernel.name(),
        shape: q.shape.name(),
        h_over_dx: q.h_over_dx,
        support_over_dx: q.kernel.zeta() * q.h_over_dx,
        stress: q.stress,
        material: q.material,
        lattice: q.lattice.kind,
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
        max_amplification: max_amp,
    })
}

/// Critical Δt by bisection on the amplification matrices over the sampled zone.
pub fn critical_dt_2d(lin: &Linearisation2D, ks: &[[f64; 2]]) -> Result<f64> {
    let stable = |dt: f64| -> Result<bool> {
        for &k in ks {
            if lin.spectral_radius(k, dt)? > 1.0 + AMPLIFICATION_TOL {
                return Ok(false);
            }
        }
        Ok(true)
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    while stable(hi)? {
        lo = hi;
        hi *= 2.0;
        if hi > 1e6 {
            return Ok(f64::INFINITY);
        }
    }
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if stable(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(lo)
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
    /// Wave vectors [κxΔx, κyΔx].
    pub kappa: Vec<[f64; 2]>,
    /// Re ω²Δx²/c² of the two branches (ascending).
    pub omega2: Vec<[f64; 2]>,
    /// Growth rate at each point (c/Δx).
    pub growth_rate: Vec<f64>,
    /// Continuum P and S branches ω²Δx²/c².
    pub omega2_continuum: Vec<[f64; 2]>,
}

/// Largest `--grid` (wave vectors per reciprocal direction): 1024² wave vectors take ~8 s for
/// the elastic classical form on this project's 2-core machine (512²: 2.0 s, measured).
pub const MAX_GRID: usize = 1024;
/// Largest `map --n` (same cost per wave vector as `--grid`).
pub const MAX_MAP_N: usize = 1024;
/// Largest `--box` (free particles per side): 1000² standing modes take ~4 s.
pub const MAX_BOX: usize = 1000;
/// Largest `dispersion --dim 2 --points` (per path segment).
pub const MAX_PATH_POINTS: usize = 100_000;

/// `Err(OutOfRange)` unless `lo ≤ n ≤ hi`.
pub fn check_count(name: &'static str, n: usize, lo: usize, hi: usize) -> Result<()> {
    if (lo..=hi).contains(&n) {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            name,
            value: n as f64,
            range: format!("must be an integer in [{lo}, {hi}]"),
        })
    }
}

/// Dispersion along Γ–X–M–Γ (square) or Γ–M–K–Γ (hexagonal), `n` points per segment.
pub fn dispersion2d(q: &Query2D, n: usize) -> Result<Dispersion2D> {
    check_count("--points", n, 2, MAX_PATH_POINTS)?;
    let lin = q.linearise_at(q.stress)?;
    let (cp, cs) = continuum_moduli(q)?;
    let path = q.lattice.symmetry_path(n);
    let mut labels = Vec::new();
    let pts = q.lattice.symmetry_points();
    let mut s = 0.0;
    labels.push((pts[0].0.to_string(), 0.0));
    for w in pts.windows(2) {
        s += (w[1].1[0] - w[0].1[0]).hypot(w[1].1[1] - w[0].1[1]);
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
    };
    for (k, s) in path {
        let b = lin.branches(k);
        let k2 = k[0] * k[0] + k[1] * k[1];
        out.path.push(s);
        out.kappa.push(k);
        out.omega2.push([b[0].0.re, b[1].0.re]);
        out.growth_rate.push(lin.growth(k)?.0);
        out.omega2_continuum.push([cs * k2, cp * k2]);
    }
    Ok(out)
}

/// Growth-rate map over the zone: (κx, κy) grid and γ.
#[derive(Clone, Debug, Serialize)]
pub struct GrowthMap {
    /// κxΔx values.
    pub kx: Vec<f64>,
    /// κyΔx values.
    pub ky: Vec<f64>,
    /// γ at (kx\[i\], ky\[j\]), indexed `growth[i][j]` (c/Δx).
    pub growth: Vec<Vec<f64>>,
    /// Largest ω² (for the critical Δt).
    pub omega2_max: f64,
}

/// Growth over the square [−π, π] × [−π, π] (n × n), any lattice.
pub fn growth_map(q: &Query2D, n: usize) -> Result<GrowthMap> {
    check_count("--n", n, 2, MAX_MAP_N)?;
    let lin = q.linearise_at(q.stress)?;
    let ax: Vec<f64> = (0..n)
        .map(|i| -PI + 2.0 * PI * (i as f64 + 0.5) / n as f64)
        .collect();
    let mut g = vec![vec![0.0; n]; n];
    let mut w2: f64 = 0.0;
    for (i, &kx) in ax.iter().enumerate() {
        for (j, &ky) in ax.iter().enumerate() {
            g[i][j] = lin.growth([kx, ky])?.0;
            w2 = w2.max(lin.branches([kx, ky])[1].0.re);
        }
    }
    Ok(GrowthMap {
        kx: ax.clone(),
        ky: ax,
        growth: g,
        omega2_max: w2,
    })
}

/// The growth rate a box of `n_free` × `n_free` free particles between fixed boundary layers can
/// show: standing modes sin(mπi/(n+1)) admit k = (mπ/(n+1), lπ/(n+1)), m, l = 1..n; the largest
/// growth over those wave vectors, and where.
pub fn box_prediction(lin: &Linearisation2D, n_free: usize) -> Result<(f64, [f64; 2])> {
    check_count("--box", n_free, 1, MAX_BOX)?;
    let mut best = (0.0, [0.0; 2]);
    let d = PI / (n_free as f64 + 1.0);
    for m in 1..=n_free {
        for l in 1..=n_free {
            let k = [m as f64 * d, l as f64 * d];
            let g = lin.growth(k)?.0;
            if g > best.0 {
                best = (g, k);
            }
        }
    }
    Ok(best)
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
