//! Static Galerkin meshfree solutions of [B98 §6.2] (issue 29, capability 7): the cantilever
//! beam of [B98 §6.2.1] (Timoshenko's solution, plane stress) solved with nodal quadrature
//! (eq 95) and the shape-function families of [`crate::shape`], and measured with B98's error
//! norms (eqs 114–119 evaluated at the nodes).
//!
//! Methods ([B98 §6.2], items 1, 3, 4, 6):
//! - `sph`: φ_I = ΔV_I W, the symmetrised gradient ∇u_J = Σ_I ∇φ_I(x_J)(u_I − u_J) (eq 47),
//!   Bubnov–Galerkin;
//! - `rl`: the same with the Randles–Libersky correction, ∇u_J = [Σ_I (u_I − u_J) ⊗
//!   ∇φ_I(x_J)] B, B = [Σ_I (x_I − x_J) ⊗ ∇φ_I(x_J)]⁻¹ (eqs 68–70), Bubnov;
//! - `cd1`: Shepard test functions, trial derivatives corrected to first order (eqs 55–61,
//!   the `corrected` family), Petrov–Galerkin (eqs 96–97: a non-symmetric stiffness);
//! - `mls`: linear MLS (eqs 44–46), Bubnov.
//!
//! The weight is the cubic B-spline (eq 26, sphstab's `m4`) with s = √2 Δx (eq 126: h = s,
//! support 2s). The essential boundary x = 0 carries a row of bilinear finite elements
//! ([B98 §5.2.4], eqs 100–105): with nodal quadrature its nodes are interpolating (their
//! displacements prescribed by eqs 120–121) and their strains are the elements' (each node's
//! volume shared by its one or two elements); every other node uses the meshfree
//! derivatives (eq 105). The end x = L carries the traction σ_xy of eq 124 (resultant P) by
//! nodal boundary quadrature, and the stiffness K u = f is solved by a banded LU
//! ([`crate::forms::BandedLu`]; nodes in x-major order).
//!
//! Choices B98 leaves open (stated with the rows of REPRODUCTION.md): P = 1 (the errors are
//! relative); plane stress (eqs 120–124 are its solution); the nodal volumes ΔV = Δx² inside,
//! halved on an edge and quartered at a corner; the "nodal values" of the l2 norm are the
//! nodal coefficients u_I; the energy norm is the square root of eq 118 at the nodes, with the
//! trial strain of the method.

// Small-matrix algebra (2 × 2, 3 × 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::error::{Error, Result};
use crate::forms::BandedLu;
use crate::shape::{KernelParams, ShapeFamily, eval_d};
use serde::Serialize;

/// A meshfree Galerkin method of [B98 §6.2].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GalerkinMethod {
    /// SPH with the symmetrised gradient (eq 47).
    Sph,
    /// Randles–Libersky corrected SPH gradient (eqs 68–70).
    Rl,
    /// Corrected derivatives, Method 1 (eqs 55–61), Shepard test functions.
    Cd1,
    /// Linear moving least squares (eqs 44–46).
    Mls,
    /// Element-free Galerkin: MLS with 5 × 5 Gauss quadrature on the cells the nodes make
    /// (§6.2, item 7), the finite-element row blended in by eqs 100–104.
    Efg,
}

impl GalerkinMethod {
    /// Every method with its name.
    pub const ALL: [(GalerkinMethod, &'static str); 5] = [
        (GalerkinMethod::Sph, "sph"),
        (GalerkinMethod::Rl, "rl"),
        (GalerkinMethod::Cd1, "cd1"),
        (GalerkinMethod::Mls, "mls"),
        (GalerkinMethod::Efg, "efg"),
    ];

    /// The method of a name (`what`: the flag or field in the error).
    pub fn by_name(what: &'static str, name: &str) -> Result<Self> {
        crate::error::lookup(what, &Self::ALL, name)
    }

    /// The name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }
}

/// The cantilever of [B98 §6.2.1]: depth D, length L, end load P, plane stress; x from the
/// clamped end, −D/2 ≤ y ≤ D/2.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Cantilever {
    /// Young's modulus E.
    pub modulus: f64,
    /// Poisson ratio ν.
    pub poisson: f64,
    /// Depth D.
    pub depth: f64,
    /// Length L.
    pub length: f64,
    /// End load P (its resultant, + y).
    pub load: f64,
}

impl Cantilever {
    /// [B98] eq 126's beam: E = 1000, ν = 0.3, D = 1, L = 8 (P = 1: B98 gives none, the
    /// errors are relative).
    pub const B98: Cantilever = Cantilever {
        modulus: 1000.0,
        poisson: 0.3,
        depth: 1.0,
        length: 8.0,
        load: 1.0,
    };

    fn inertia(&self) -> f64 {
        self.depth.powi(3) / 12.0
    }

    /// The exact displacement (eqs 120–121).
    pub fn displacement(&self, x: f64, y: f64) -> [f64; 2] {
        let (p, e, nu, d, l) = (
            self.load,
            self.modulus,
            self.poisson,
            self.depth,
            self.length,
        );
        let c = p / (6.0 * e * self.inertia());
        [
            -c * y * ((6.0 * l - 3.0 * x) * x + (2.0 + nu) * (y * y - d * d / 4.0)),
            c * (3.0 * nu * y * y * (l - x)
                + (4.0 + 5.0 * nu) * d * d * x / 4.0
                + (3.0 * l - x) * x * x),
        ]
    }

    /// The exact stress (σ_xx, σ_yy, σ_xy) (eqs 122–124).
    pub fn stress(&self, x: f64, y: f64) -> [f64; 3] {
        let (p, d, l, i) = (self.load, self.depth, self.length, self.inertia());
        [
            -p * (l - x) * y / i,
            0.0,
            p / (2.0 * i) * (d * d / 4.0 - y * y),
        ]
    }

    /// The plane-stress elasticity (Voigt, engineering shear).
    fn elasticity(&self) -> [[f64; 3]; 3] {
        let (e, nu) = (self.modulus, self.poisson);
        let f = e / (1.0 - nu * nu);
        [
            [f, f * nu, 0.0],
            [f * nu, f, 0.0],
            [0.0, 0.0, f * (1.0 - nu) / 2.0],
        ]
    }

    /// The exact strain (ε_xx, ε_yy, γ_xy), from the stress by the compliance.
    fn strain(&self, x: f64, y: f64) -> [f64; 3] {
        let [sx, sy, sxy] = self.stress(x, y);
        let (e, nu) = (self.modulus, self.poisson);
        [
            (sx - nu * sy) / e,
            (sy - nu * sx) / e,
            2.0 * (1.0 + nu) / e * sxy,
        ]
    }
}

/// The plate with a hole of [B98 §6.2.2] (Figs 7–9): an infinite plate with a circular hole
/// of radius a under the unit traction σ_xx = 1 at infinity, plane stress, modelled on the
/// quadrant 0 ≤ x, y ≤ b outside the hole (its upper right quarter), with Kirsch's solution on
/// the outer edges.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PlateWithHole {
    /// Young's modulus E.
    pub modulus: f64,
    /// Poisson ratio ν.
    pub poisson: f64,
    /// Hole radius a.
    pub radius: f64,
    /// Half width b of the plate.
    pub half_width: f64,
}

impl PlateWithHole {
    /// [B98] §6.2.2: E = 1000, ν = 0.3, a = 1, b = 5.
    pub const B98: PlateWithHole = PlateWithHole {
        modulus: 1000.0,
        poisson: 0.3,
        radius: 1.0,
        half_width: 5.0,
    };

    /// Kirsch's stress (σ_xx, σ_yy, σ_xy) (eqs 127–129).
    pub fn stress(&self, x: f64, y: f64) -> [f64; 3] {
        let a = self.radius;
        let (r, t) = (x.hypot(y), y.atan2(x));
        let (a2, a4) = ((a / r).powi(2), (a / r).powi(4));
        let (c2, c4, s2, s4) = (
            (2.0 * t).cos(),
            (4.0 * t).cos(),
            (2.0 * t).sin(),
            (4.0 * t).sin(),
        );
        [
            1.0 - a2 * (1.5 * c2 + c4) + 1.5 * a4 * c4,
            -a2 * (0.5 * c2 - c4) - 1.5 * a4 * c4,
            -a2 * (0.5 * s2 + s4) + 1.5 * a4 * s4,
        ]
    }

    /// The displacement of Kirsch's solution in plane stress (B98 prints only the stresses;
    /// this is the standard field, μ = E/(2(1 + ν)), κ = (3 − ν)/(1 + ν)), zero on the
    /// symmetry axes' normal directions:
    /// u_x = a/(8μ) [(r/a)(κ + 1) cos θ + (2a/r)((1 + κ) cos θ + cos 3θ) − (2a³/r³) cos 3θ],
    /// u_y = a/(8μ) [(r/a)(κ − 3) sin θ + (2a/r)((1 − κ) sin θ + sin 3θ) − (2a³/r³) sin 3θ].
    pub fn displacement(&self, x: f64, y: f64) -> [f64; 2] {
        let (a, nu) = (self.radius, self.poisson);
        let mu = self.modulus / (2.0 * (1.0 + nu));
        let kappa = (3.0 - nu) / (1.0 + nu);
        let (r, t) = (x.hypot(y), y.atan2(x));
        let f = a / (8.0 * mu);
        [
            f * ((r / a) * (kappa + 1.0) * t.cos()
                + (2.0 * a / r) * ((1.0 + kappa) * t.cos() + (3.0 * t).cos())
                - 2.0 * (a / r).powi(3) * (3.0 * t).cos()),
            f * ((r / a) * (kappa - 3.0) * t.sin()
                + (2.0 * a / r) * ((1.0 - kappa) * t.sin() + (3.0 * t).sin())
                - 2.0 * (a / r).powi(3) * (3.0 * t).sin()),
        ]
    }
}

/// The solution of one discretisation.
#[derive(Clone, Debug, Serialize)]
pub struct GalerkinReport {
    /// Method.
    pub method: GalerkinMethod,
    /// Node spacing Δx.
    pub spacing: f64,
    /// Nodes.
    pub nodes: usize,
    /// Displacement error: for the nodal methods the nodal l2 error (eqs 114–115), (Σ ΔV
    /// |u_I − u(x_I)|²)^½ / (Σ ΔV |u(x_I)|²)^½; for `efg` the L2 error (eqs 116–117) by its
    /// own 5 × 5 Gauss quadrature.
    pub displacement_error: f64,
    /// Energy error (eqs 118–119, square-rooted): (Σ w (ε_h − ε):C:(ε_h − ε))^½ / (Σ w
    /// ε:C:ε)^½ over the quadrature points (the nodes, weights ΔV; `efg`: the Gauss points),
    /// ε_h the method's trial strain.
    pub energy_error: f64,
    /// The computed deflection u_y of the node at (L, 0).
    pub tip_deflection: f64,
    /// The exact one (eq 121).
    pub exact_tip_deflection: f64,
}

/// Nodes per unit depth allowed (Δx = D/n). At 32 the beam has 257 × 33 nodes, 17,000
/// unknowns in a band of about 280: the banded LU holds ~1e8 B (3 × band × unknowns × 8 B).
pub const PER_DEPTH_RANGE: (usize, usize) = (2, 32);

/// Solves the cantilever `beam` with `method` at Δx = D/`per_depth`.
pub fn cantilever(
    beam: &Cantilever,
    method: GalerkinMethod,
    per_depth: usize,
) -> Result<GalerkinReport> {
    crate::error::check_range(
        "per_depth",
        per_depth as f64,
        PER_DEPTH_RANGE.0 as f64,
        PER_DEPTH_RANGE.1 as f64,
        true,
        true,
    )?;
    let dx = beam.depth / per_depth as f64;
    let ny = per_depth + 1;
    let nx = (beam.length / dx).round() as usize + 1;
    let n = nx * ny;
    let at = |i: usize, j: usize| i * ny + j;
    let pos: Vec<[f64; 2]> = (0..nx)
        .flat_map(|i| (0..ny).map(move |j| [i as f64 * dx, -beam.depth / 2.0 + j as f64 * dx]))
        .collect();
    let vol: Vec<f64> = (0..n)
        .map(|k| {
            let (i, j) = (k / ny, k % ny);
            let fx = if i == 0 || i == nx - 1 { 0.5 } else { 1.0 };
            let fy = if j == 0 || j == ny - 1 { 0.5 } else { 1.0 };
            fx * fy * dx * dx
        })
        .collect();
    let kp = KernelParams {
        kernel: crate::kernel::by_name("m4")?,
        h: std::f64::consts::SQRT_2 * dx,
    };
    if method == GalerkinMethod::Efg {
        return efg(beam, kp, &pos, nx, ny, dx);
    }
    let support = kp.support();
    let cells = (support / dx).ceil() as isize;
    // each quadrature node's (trial, test) gradients: (node, gradient)
    let mut trial: Vec<Vec<(usize, [f64; 2])>> = Vec::with_capacity(n);
    let mut test: Vec<Vec<(usize, [f64; 2])>> = Vec::with_capacity(n);
    for k in 0..n {
        let (i, j) = ((k / ny) as isize, (k % ny) as isize);
        if i == 0 {
            // the finite-element row: the bilinear elements (0..Δx) × (y_j−1..y_j) and
            // (y_j..y_j+1) at their corner (0, y_j), each weighing half the node's volume
            let mut g: Vec<(usize, [f64; 2])> = Vec::new();
            let elements: Vec<isize> = [j - 1, j]
                .into_iter()
                .filter(|&e| e >= 0 && e < ny as isize - 1)
                .collect();
            let w = 1.0 / elements.len() as f64;
            for e in elements {
                // element corners (0, e), (1, e), (0, e+1), (1, e+1); the node sits at
                // ξ = 0, η = 0 (bottom) when e = j, η = 1 (top) when e = j − 1
                let top = e != j;
                let (lo, hi) = (e as usize, e as usize + 1);
                let (near, far) = if top { (hi, lo) } else { (lo, hi) };
                let s = if top { -1.0 } else { 1.0 };
                // N at the corner node: ∂/∂x of the x-neighbour pair, ∂/∂y of the y pair
                g.push((at(0, near), [-w / dx, -s * w / dx]));
                g.push((at(1, near), [w / dx, 0.0]));
                g.push((at(0, far), [0.0, s * w / dx]));
            }
            trial.push(merge(g));
            test.push(trial[k].clone());
            continue;
        }
        let mut nb: Vec<usize> = Vec::new();
        for a in (i - cells).max(0)..=(i + cells).min(nx as isize - 1) {
            for b in (j - cells).max(0)..=(j + cells).min(ny as isize - 1) {
                let m = at(a as usize, b as usize);
                let d = [pos[m][0] - pos[k][0], pos[m][1] - pos[k][1]];
                if (d[0] * d[0] + d[1] * d[1]).sqrt() < support {
                    nb.push(m);
                }
            }
        }
        let nodes: Vec<([f64; 2], f64)> = nb
            .iter()
            .map(|&m| ([pos[m][0] - pos[k][0], pos[m][1] - pos[k][1]], vol[m]))
            .collect();
        let family = |f: ShapeFamily| -> Result<Vec<(usize, [f64; 2])>> {
            let mut out = Vec::new();
            eval_d(f, kp, &nodes, pos[k][0], &mut out)?;
            Ok(nb.iter().zip(&out).map(|(&m, (_, g))| (m, *g)).collect())
        };
        let g = match method {
            // (efg returned above, by its Gauss quadrature)
            GalerkinMethod::Mls | GalerkinMethod::Efg => family(ShapeFamily::Mls)?,
            GalerkinMethod::Cd1 => family(ShapeFamily::Corrected)?,
            GalerkinMethod::Sph | GalerkinMethod::Rl => {
                let raw = family(ShapeFamily::Sph)?;
                // B = [Σ_I (x_I − x_J) ⊗ ∇φ_I]⁻¹ (identity for sph)
                let b = if method == GalerkinMethod::Rl {
                    let mut m = [[0.0; 2]; 2];
                    for &(i2, gi) in &raw {
                        let d = [pos[i2][0] - pos[k][0], pos[i2][1] - pos[k][1]];
                        for a in 0..2 {
                            for c in 0..2 {
                                m[a][c] += d[a] * gi[c];
                            }
                        }
                    }
                    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
                    if det.abs() < 1e-12 {
                        return Err(Error::SingularMoment {
                            what: "Randles–Libersky correction",
                            x: pos[k][0],
                            det,
                        });
                    }
                    [
                        [m[1][1] / det, -m[0][1] / det],
                        [-m[1][0] / det, m[0][0] / det],
                    ]
                } else {
                    [[1.0, 0.0], [0.0, 1.0]]
                };
                // ∇u_J = Σ_I (u_I − u_J) (∇φ_I B): G_I = ∇φ_I B, G_J = −Σ_I G_I
                let mut g: Vec<(usize, [f64; 2])> = raw
                    .iter()
                    .filter(|(m, _)| *m != k)
                    .map(|&(m, gi)| {
                        (
                            m,
                            [
                                gi[0] * b[0][0] + gi[1] * b[1][0],
                                gi[0] * b[0][1] + gi[1] * b[1][1],
                            ],
                        )
                    })
                    .collect();
                let sum = g
                    .iter()
                    .fold([0.0; 2], |s, (_, gi)| [s[0] + gi[0], s[1] + gi[1]]);
                g.push((k, [-sum[0], -sum[1]]));
                g
            }
        };
        let t = if method == GalerkinMethod::Cd1 {
            family(ShapeFamily::Shepard)?
        } else {
            g.clone()
        };
        trial.push(g);
        test.push(t);
    }
    // K = Σ_k ΔV_k B_test(x_k)ᵀ C B_trial(x_k), two DOFs per node
    let c = beam.elasticity();
    let quad: Vec<QuadPoint> = (0..n)
        .map(|k| (vol[k], &test[k][..], &trial[k][..]))
        .collect();
    // the load: σ_xy at x = L, by nodal boundary quadrature (ΔΓ = Δx, halved at the corners)
    let mut f = vec![0.0; 2 * n];
    for j in 0..ny {
        let k = at(nx - 1, j);
        let w = if j == 0 || j == ny - 1 { 0.5 * dx } else { dx };
        f[2 * k + 1] += beam.stress(pos[k][0], pos[k][1])[2] * w;
    }
    let u = solve(beam, &c, &quad, f, &pos, ny)?;
    // errors at the nodes
    let (mut du, mut un, mut de, mut en) = (0.0, 0.0, 0.0, 0.0);
    for k in 0..n {
        let ex = beam.displacement(pos[k][0], pos[k][1]);
        du += vol[k] * ((u[2 * k] - ex[0]).powi(2) + (u[2 * k + 1] - ex[1]).powi(2));
        un += vol[k] * (ex[0] * ex[0] + ex[1] * ex[1]);
        let mut eh = [0.0; 3];
        for &(m, g) in &trial[k] {
            let b = bmat(g);
            for r in 0..3 {
                eh[r] += b[r][0] * u[2 * m] + b[r][1] * u[2 * m + 1];
            }
        }
        let ee = beam.strain(pos[k][0], pos[k][1]);
        let energy = |e: [f64; 3]| {
            (0..3)
                .map(|r| (0..3).map(|s| e[r] * c[r][s] * e[s]).sum::<f64>())
                .sum::<f64>()
        };
        de += vol[k] * energy([eh[0] - ee[0], eh[1] - ee[1], eh[2] - ee[2]]);
        en += vol[k] * energy(ee);
    }
    let tip = at(nx - 1, ny / 2);
    let exact_tip = beam.displacement(pos[tip][0], pos[tip][1])[1];
    let out = GalerkinReport {
        method,
        spacing: dx,
        nodes: n,
        displacement_error: (du / un).sqrt(),
        energy_error: (de / en).sqrt(),
        tip_deflection: u[2 * tip + 1],
        exact_tip_deflection: exact_tip,
    };
    if !(out.displacement_error.is_finite() && out.energy_error.is_finite()) {
        return Err(Error::NonFinite("Galerkin solution"));
    }
    Ok(out)
}

/// A node's gradient: (node, ∇φ).
type Grad = (usize, [f64; 2]);
/// A quadrature point: (weight, test gradients, trial gradients).
type QuadPoint<'a> = (f64, &'a [Grad], &'a [Grad]);
/// An EFG quadrature point: (weight, position, (node, Φ⁰, ∇Φ⁰)).
type EfgPoint = (f64, [f64; 2], Vec<(usize, f64, [f64; 2])>);

/// B(∇φ): the strain (ε_xx, ε_yy, γ_xy) of a unit displacement of a node in x and in y.
fn bmat(g: [f64; 2]) -> [[f64; 2]; 3] {
    [[g[0], 0.0], [0.0, g[1]], [g[1], g[0]]]
}

/// Assembles K = Σ_p w_p B_test(x_p)ᵀ C B_trial(x_p) over the quadrature points `quad`
/// ((weight, test gradients, trial gradients)), prescribes the displacements of eqs 120–121
/// on the first `ny` nodes (the column x = 0: their rows become identities, their columns
/// move to the load), and solves K u = `f` by banded LU.
fn solve(
    beam: &Cantilever,
    c: &[[f64; 3]; 3],
    quad: &[QuadPoint],
    mut f: Vec<f64>,
    pos: &[[f64; 2]],
    ny: usize,
) -> Result<Vec<f64>> {
    let n = pos.len();
    let mut rows: Vec<std::collections::BTreeMap<usize, f64>> = vec![Default::default(); 2 * n];
    for &(w, test, trial) in quad {
        for &(a, ga) in test {
            let ba = bmat(ga);
            for &(b, gb) in trial {
                let bb = bmat(gb);
                for p in 0..2 {
                    for q in 0..2 {
                        let mut v = 0.0;
                        for r in 0..3 {
                            for s in 0..3 {
                                v += ba[r][p] * c[r][s] * bb[s][q];
                            }
                        }
                        *rows[2 * a + p].entry(2 * b + q).or_insert(0.0) += w * v;
                    }
                }
            }
        }
    }
    let mut u = vec![0.0; 2 * n];
    for k in 0..ny {
        let ex = beam.displacement(pos[k][0], pos[k][1]);
        u[2 * k] = ex[0];
        u[2 * k + 1] = ex[1];
    }
    let mut sparse: Vec<Vec<(usize, f64)>> = Vec::with_capacity(2 * n);
    for (r, row) in rows.iter().enumerate() {
        if r / 2 < ny {
            sparse.push(vec![(r, 1.0)]);
            f[r] = u[r];
            continue;
        }
        let mut out = Vec::with_capacity(row.len());
        for (&col, &v) in row {
            if col / 2 < ny {
                f[r] -= v * u[col];
            } else {
                out.push((col, v));
            }
        }
        sparse.push(out);
    }
    let lu = BandedLu::new(&sparse, false).ok_or(Error::SingularMoment {
        what: "Galerkin stiffness matrix",
        x: 0.0,
        det: 0.0,
    })?;
    let mut work = Vec::new();
    lu.solve(&f, &mut u, &mut work);
    Ok(u)
}

/// The five-point Gauss rule on [−1, 1]: (point, weight).
const GAUSS5: [(f64, f64); 5] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// EFG on the cantilever: MLS at the 5 × 5 Gauss points of every cell of the nodes, the
/// first column of cells the finite-element row (eqs 100–104: Φ⁰_I = r φ_I + (1 − r) N_I,
/// r = 3R² − 2R³, R = x/Δx the bilinear functions' sum over the second column), the end load
/// by 5 Gauss points per edge segment, the errors (eqs 116–119) by the same quadrature.
fn efg(
    beam: &Cantilever,
    kp: KernelParams,
    pos: &[[f64; 2]],
    nx: usize,
    ny: usize,
    dx: f64,
) -> Result<GalerkinReport> {
    let n = pos.len();
    let support = kp.support();
    let reach = (support / dx).ceil() as isize;
    // (φ_I, ∇φ_I) at the point p, over the nodes within the support
    let mls = |p: [f64; 2]| -> Result<Vec<(usize, f64, [f64; 2])>> {
        let (ci, cj) = (
            (p[0] / dx).floor() as isize,
            ((p[1] + beam.depth / 2.0) / dx).floor() as isize,
        );
        let mut nb = Vec::new();
        for a in (ci - reach).max(0)..=(ci + reach + 1).min(nx as isize - 1) {
            for b in (cj - reach).max(0)..=(cj + reach + 1).min(ny as isize - 1) {
                let m = a as usize * ny + b as usize;
                let d = [pos[m][0] - p[0], pos[m][1] - p[1]];
                if (d[0] * d[0] + d[1] * d[1]).sqrt() < support {
                    nb.push(m);
                }
            }
        }
        let nodes: Vec<([f64; 2], f64)> = nb
            .iter()
            .map(|&m| ([pos[m][0] - p[0], pos[m][1] - p[1]], 1.0))
            .collect();
        let mut out = Vec::new();
        eval_d(ShapeFamily::Mls, kp, &nodes, p[0], &mut out)?;
        Ok(nb.iter().zip(out).map(|(&m, (v, g))| (m, v, g)).collect())
    };
    // quadrature points: (weight, position, (node, Φ⁰, ∇Φ⁰))
    let mut points: Vec<EfgPoint> = Vec::new();
    for i in 0..nx - 1 {
        for j in 0..ny - 1 {
            let (x0, y0) = (i as f64 * dx, -beam.depth / 2.0 + j as f64 * dx);
            for &(gx, wx) in &GAUSS5 {
                for &(gy, wy) in &GAUSS5 {
                    let (xi, eta) = (0.5 * (1.0 + gx), 0.5 * (1.0 + gy));
                    let p = [x0 + xi * dx, y0 + eta * dx];
                    let mut phi = mls(p)?;
                    if i == 0 {
                        let r = 3.0 * xi * xi - 2.0 * xi.powi(3);
                        let dr = (6.0 * xi - 6.0 * xi * xi) / dx;
                        let corners = [
                            (
                                j,
                                (1.0 - xi) * (1.0 - eta),
                                [-(1.0 - eta) / dx, -(1.0 - xi) / dx],
                            ),
                            (ny + j, xi * (1.0 - eta), [(1.0 - eta) / dx, -xi / dx]),
                            (j + 1, (1.0 - xi) * eta, [-eta / dx, (1.0 - xi) / dx]),
                            (ny + j + 1, xi * eta, [eta / dx, xi / dx]),
                        ];
                        for (m, v, g) in phi.iter_mut() {
                            let (nv, ng) = corners
                                .iter()
                                .find(|c| c.0 == *m)
                                .map_or((0.0, [0.0; 2]), |c| (c.1, c.2));
                            let (pv, pg) = (*v, *g);
                            *v = r * pv + (1.0 - r) * nv;
                            *g = [
                                r * pg[0] + dr * (pv - nv) + (1.0 - r) * ng[0],
                                r * pg[1] + (1.0 - r) * ng[1],
                            ];
                        }
                    }
                    points.push((wx * wy * 0.25 * dx * dx, p, phi));
                }
            }
        }
    }
    let c = beam.elasticity();
    let grads: Vec<Vec<(usize, [f64; 2])>> = points
        .iter()
        .map(|(_, _, phi)| phi.iter().map(|&(m, _, g)| (m, g)).collect())
        .collect();
    let quad: Vec<QuadPoint> = points
        .iter()
        .zip(&grads)
        .map(|((w, _, _), g)| (*w, &g[..], &g[..]))
        .collect();
    // the end load: t_y = σ_xy(L, y) by 5 Gauss points on each edge segment
    let mut f = vec![0.0; 2 * n];
    for j in 0..ny - 1 {
        let y0 = -beam.depth / 2.0 + j as f64 * dx;
        for &(g, w) in &GAUSS5 {
            let p = [beam.length, y0 + 0.5 * (1.0 + g) * dx];
            let t = beam.stress(p[0], p[1])[2];
            for (m, v, _) in mls(p)? {
                f[2 * m + 1] += 0.5 * dx * w * t * v;
            }
        }
    }
    let u = solve(beam, &c, &quad, f, pos, ny)?;
    let energy = |e: [f64; 3]| {
        (0..3)
            .map(|r| (0..3).map(|s| e[r] * c[r][s] * e[s]).sum::<f64>())
            .sum::<f64>()
    };
    let (mut du, mut un, mut de, mut en) = (0.0, 0.0, 0.0, 0.0);
    for (w, p, phi) in &points {
        let (mut uh, mut eh) = ([0.0; 2], [0.0; 3]);
        for &(m, v, g) in phi {
            uh[0] += v * u[2 * m];
            uh[1] += v * u[2 * m + 1];
            let b = bmat(g);
            for r in 0..3 {
                eh[r] += b[r][0] * u[2 * m] + b[r][1] * u[2 * m + 1];
            }
        }
        let ex = beam.displacement(p[0], p[1]);
        du += w * ((uh[0] - ex[0]).powi(2) + (uh[1] - ex[1]).powi(2));
        un += w * (ex[0] * ex[0] + ex[1] * ex[1]);
        let ee = beam.strain(p[0], p[1]);
        de += w * energy([eh[0] - ee[0], eh[1] - ee[1], eh[2] - ee[2]]);
        en += w * energy(ee);
    }
    let tip_point = [beam.length, 0.0];
    let tip: f64 = mls(tip_point)?
        .iter()
        .map(|&(m, v, _)| v * u[2 * m + 1])
        .sum();
    let out = GalerkinReport {
        method: GalerkinMethod::Efg,
        spacing: dx,
        nodes: n,
        displacement_error: (du / un).sqrt(),
        energy_error: (de / en).sqrt(),
        tip_deflection: tip,
        exact_tip_deflection: beam.displacement(beam.length, 0.0)[1],
    };
    if !(out.displacement_error.is_finite() && out.energy_error.is_finite()) {
        return Err(Error::NonFinite("Galerkin solution"));
    }
    Ok(out)
}

/// Sums the gradients of repeated nodes.
fn merge(g: Vec<(usize, [f64; 2])>) -> Vec<(usize, [f64; 2])> {
    let mut m: std::collections::BTreeMap<usize, [f64; 2]> = Default::default();
    for (k, v) in g {
        let e = m.entry(k).or_insert([0.0; 2]);
        e[0] += v[0];
        e[1] += v[1];
    }
    m.into_iter().collect()
}

/// The convergence rate of `errors` against `spacings`: the least-squares slope of
/// log(error) on log(Δx).
pub fn rate(spacings: &[f64], errors: &[f64]) -> f64 {
    let n = spacings.len() as f64;
    let (xs, ys): (Vec<f64>, Vec<f64>) = spacings
        .iter()
        .zip(errors)
        .map(|(h, e)| (h.ln(), e.ln()))
        .unzip();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}
