//! The 2D numeric route: the 2D rate function linearised exactly (dual numbers) about the
//! uniformly, isotropically pre-stressed periodic lattice and projected onto Bloch waves
//! exp(i k·X): per wave vector the Jacobian block J(k) of the full per-particle state, the 2×2
//! dynamical matrix D(k) = −(J_vx + J_vq J_qv) of the mechanical branches, growth rates and
//! polarisations.

// Small-tensor algebra (2×2, 3×3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::linearise::{check_rest, eigen, zero_sums};
use crate::error::{Error, Result};
use crate::forms::{Comp2, FieldKind, FormKind, Material2D, Model2D, ModelParams2D, State2D};
use crate::lattice::Lattice2D;
use crate::scalar::{Dual, Scalar};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// The Bloch-projected linearisation of a 2D form.
#[derive(Clone, Debug)]
pub struct Linearisation2D {
    /// Components per particle.
    pub comps: Vec<Comp2>,
    cols: Vec<Vec<([i64; 2], Vec<f64>)>>,
    zero_sum: Vec<Vec<bool>>,
    ix: [usize; 2],
    iv: [usize; 2],
    iq: Vec<usize>,
    /// Lattice (units of Δx).
    pub lattice: Lattice2D,
    omega2_scale: f64,
    time_scale: f64,
}

/// Base state of a pre-stressed lattice: (density, isotropic stress) for σ̄ = σ/C.
/// Hydro: σ = −K(ρ/ρ0 − 1) = σ̄K ⇒ ρ = (1 − σ̄)ρ0 (the Swegle density ratio f = 1 − σ̄).
/// Elastic: ρ = ρ0, σ = σ̄ C.
pub fn base_state(material: &Material2D, rho0: f64, sigma_bar: f64) -> Result<(f64, f64)> {
    let c = material.modulus();
    match material {
        Material2D::Hydro { .. } => {
            if sigma_bar >= 1.0 {
                return Err(Error::OutOfRange {
                    name: "--stress",
                    value: sigma_bar,
                    range: "hydrodynamic material: σ̄ = 1 − ρ/ρ0 must be < 1".into(),
                });
            }
            Ok(((1.0 - sigma_bar) * rho0, sigma_bar * c))
        }
        Material2D::Elastic { .. } | Material2D::NeoHookean { .. } => Ok((rho0, sigma_bar * c)),
    }
}

impl Linearisation2D {
    /// Linearises the 2D form `p` on lattice `lat` (spacing `dx`) at pre-stress σ̄.
    pub fn new(p: ModelParams2D, lat: &Lattice2D, dx: f64, sigma_bar: f64) -> Result<Self> {
        let (rho, s0) = base_state(&p.material, p.rho0, sigma_bar)?;
        let hmin = lat.area() / lat.a.iter().map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
        let range = (2.0 * p.kp.support() / (dx * hmin)).ceil() as usize + 2;
        let n = 2 * range + 1;
        check_patch_budget(&p, lat, dx, n)?;
        let model = Model2D::periodic_patch(p, lat, dx, [n, n], rho, s0)?;
        let base = model.rest_state(rho);
        let comps = p.form.comps_2d(&p.material);
        let nd = comps.len();
        let cell = |idx: usize| -> [i64; 2] {
            let (i, j) = ((idx / n) as i64, (idx % n) as i64);
            let w = |a: i64| if a <= n as i64 / 2 { a } else { a - n as i64 };
            [w(i), w(j)]
        };
        let mut cols = Vec::with_capacity(nd);
        let mut out = State2D::<Dual>::default();
        for &b in &comps {
            let mut z: State2D<Dual> = base.map(Dual::cst);
            z.get_mut(b, 0).d = 1.0;
            model.rate(&z, &mut out)?;
            let mut col: Vec<([i64; 2], Vec<f64>)> = Vec::new();
            for pidx in 0..base.x.len() {
                let v: Vec<f64> = comps.iter().map(|&a| out.get(a, pidx).d).collect();
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(Error::NonFinite("2D rate-function Jacobian"));
                }
                if v.iter().any(|&x| x != 0.0) {
                    col.push((cell(pidx), v));
                }
            }
            cols.push(col);
        }
        let zero_sum = zero_sums(&cols, nd);
        let find = |c: Comp2| {
            comps
                .iter()
                .position(|&x| x == c)
                .ok_or(Error::NonFinite("layout"))
        };
        let ix = [find(Comp2::X(0))?, find(Comp2::X(1))?];
        let iv = [find(Comp2::V(0))?, find(Comp2::V(1))?];
        let iq: Vec<usize> = (0..nd)
            .filter(|&k| comps[k].kind() == FieldKind::Auxiliary)
            .collect();
        let c2 = p.material.modulus() / p.rho0;
        let lin = Self {
            comps,
            cols,
            zero_sum,
            ix,
            iv,
            iq,
            lattice: *lat,
            omega2_scale: dx * dx / c2,
            time_scale: dx / c2.sqrt(),
        };
        lin.check_rest_structure()?;
        Ok(lin)
    }

    fn check_rest_structure(&self) -> Result<()> {
        check_rest(
            &self.cols,
            |a| self.iq.contains(&a),
            |b| self.iv.contains(&b),
        )
    }

    /// Whether velocities enter the accelerations (artificial viscosity).
    pub fn is_dissipative(&self) -> bool {
        self.iv.iter().any(|&b| {
            self.cols[b]
                .iter()
                .any(|(_, c)| c[self.iv[0]] != 0.0 || c[self.iv[1]] != 0.0)
        })
    }

    /// J(k) (physical units; k in units of 1/Δx).
    pub fn jacobian(&self, k: [f64; 2]) -> DMatrix<Complex64> {
        let nd = self.comps.len();
        let a = self.lattice.a;
        let mut j = DMatrix::<Complex64>::zeros(nd, nd);
        for (b, col) in self.cols.iter().enumerate() {
            for (o, c) in col {
                let r = [
                    o[0] as f64 * a[0][0] + o[1] as f64 * a[1][0],
                    o[0] as f64 * a[0][1] + o[1] as f64 * a[1][1],
                ];
                let t = k[0] * r[0] + k[1] * r[1];
                let (s, h) = (t.sin(), (0.5 * t).sin());
                let e = Complex64::new(t.cos(), -s);
                let em1 = Complex64::new(-2.0 * h * h, -s);
                for (ai, &v) in c.iter().enumerate() {
                    if v != 0.0 {
                        j[(ai, b)] += if self.zero_sum[ai][b] { em1 * v } else { e * v };
                    }
                }
            }
        }
        j
    }

    /// Normalised dynamical matrix D(k)Δx²/c² (2×2) of the mechanical branches.
    pub fn dynamical(&self, k: [f64; 2]) -> [[Complex64; 2]; 2] {
        let j = self.jacobian(k);
        let mut d = [[Complex64::new(0.0, 0.0); 2]; 2];
        for a in 0..2 {
            for b in 0..2 {
                let mut v = -j[(self.iv[a], self.ix[b])];
                for &q in &self.iq {
                    v -= j[(self.iv[a], q)] * j[(q, self.iv[b])];
                }
                d[a][b] = v * self.omega2_scale;
            }
        }
        d
    }

    /// The two branches at k: (ω² (complex in general), unit polarisation), ascending in Re ω².
    pub fn branches(&self, k: [f64; 2]) -> Vec<(Complex64, [Complex64; 2])> {
        let d = self.dynamical(k);
        let tr = d[0][0] + d[1][1];
        let det = d[0][0] * d[1][1] - d[0][1] * d[1][0];
        let disc = (tr * tr * 0.25 - det).sqrt();
        let mut out: Vec<(Complex64, [Complex64; 2])> = [tr * 0.5 - disc, tr * 0.5 + disc]
            .into_iter()
            .map(|l| {
                // eigenvector: (d01, l − d00) or (l − d11, d10)
                let v1 = [d[0][1], l - d[0][0]];
                let v2 = [l - d[1][1], d[1][0]];
                let n1 = v1[0].norm_sqr() + v1[1].norm_sqr();
                let n2 = v2[0].norm_sqr() + v2[1].norm_sqr();
                let (v, n) = if n1 >= n2 { (v1, n1) } else { (v2, n2) };
                let pol = if n > 1e-300 {
                    let s = n.sqrt();
                    [v[0] / s, v[1] / s]
                } else {
                    // degenerate (D ∝ I): any direction
                    [Complex64::new(1.0, 0.0), Complex64::new(0.0, 0.0)]
                };
                (l, pol)
            })
            .collect();
        out.sort_by(|a, b| a.0.re.total_cmp(&b.0.re));
        out
    }

    /// Growth rate (c/Δx) of a branch with ω² = `w2`: Re sqrt(−ω²) ≥ 0.
    pub fn growth_of(w2: Complex64) -> f64 {
        (-w2).sqrt().re.abs()
    }

    /// Largest growth rate at k and the polarisation of that branch.
    pub fn growth(&self, k: [f64; 2]) -> Result<(f64, [Complex64; 2])> {
        if self.is_dissipative() {
            let j = self.jacobian(k) * Complex64::new(self.time_scale, 0.0);
            let g = eigen(j)?.iter().map(|s| s.re).fold(0.0, f64::max);
            let b = self.branches(k);
            return Ok((g, b[0].1));
        }
        let b = self.branches(k);
        let (g0, g1) = (Self::growth_of(b[0].0), Self::growth_of(b[1].0));
        Ok(if g0 >= g1 { (g0, b[0].1) } else { (g1, b[1].1) })
    }

    /// Amplification matrix of one leapfrog step Δt (in Δx/c) for wave vector k.
    pub fn amplification(&self, k: [f64; 2], dt: f64) -> DMatrix<Complex64> {
        let ms = super::amplification::ModeSystem::new(
            self.jacobian(k),
            self.ix.to_vec(),
            self.iv.to_vec(),
            self.iq.clone(),
        );
        ms.amplification(dt * self.time_scale)
    }

    /// Spectral radius of the leapfrog amplification matrix at k.
    pub fn spectral_radius(&self, k: [f64; 2], dt: f64) -> Result<f64> {
        Ok(eigen(self.amplification(k, dt))?
            .iter()
            .map(|l| l.norm())
            .fold(0.0, f64::max))
    }

    /// Eigenvalues s of J(k), normalised to c/Δx.
    pub fn eigenvalues(&self, k: [f64; 2]) -> Result<Vec<Complex64>> {
        eigen(self.jacobian(k) * Complex64::new(self.time_scale, 0.0))
    }
}

/// Memory estimate of linearising on an n × n periodic patch, checked against the budget
/// ([`crate::budget`]) before anything is allocated: every particle keeps a stencil of dual
/// numbers per shape family (two for the mixed forms), ~πR²/A neighbours each (A the area per
/// particle), with a quarter of spare capacity; plus the dual state and rate of every particle.
pub fn check_patch_budget(p: &ModelParams2D, lat: &Lattice2D, dx: f64, n: usize) -> Result<()> {
    let r = p.kp.support() / dx;
    let particles = (n * n) as f64;
    let neighbours = std::f64::consts::PI * r * r / lat.area() + 1.0;
    let stencils = if matches!(p.form, FormKind::Lnl | FormKind::Cll) {
        2.0
    } else {
        1.0
    };
    let entry = std::mem::size_of::<crate::forms::workspace::Nb2<Dual>>() as f64;
    let bytes = particles * (neighbours * entry * stencils * 1.25 + 64.0 * 16.0);
    crate::budget::check_memory(
        "--h/--support",
        &format!(
            "the 2D linearisation ({n} × {n} periodic patch, ~{neighbours:.0} neighbours per particle)"
        ),
        bytes,
    )
}
