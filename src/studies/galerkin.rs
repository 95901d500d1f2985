//! Static Galerkin meshfree solutions of [B98 §6.2] (issue 29, capability 7): the cantilever
//! beam of [B98 §6.2.1] (Timoshenko's solution) and the plate with a hole of [B98 §6.2.2]
//! (Kirsch's solution), plane stress, solved with nodal quadrature (eq 95) or 5 × 5 Gauss
//! background quadrature and the shape-function families of [`crate::shape`], and measured
//! with B98's error norms (eqs 114–119).
//!
//! Methods ([B98 §6.2], items 1, 3, 4, 6, 7):
//! - `sph`: φ_I = ΔV_I W, the symmetrised gradient ∇u_J = Σ_I ∇φ_I(x_J)(u_I − u_J) (eq 47),
//!   Bubnov–Galerkin;
//! - `rl`: the same with the Randles–Libersky correction, ∇u_J = [Σ_I (u_I − u_J) ⊗
//!   ∇φ_I(x_J)] B, B = [Σ_I (x_I − x_J) ⊗ ∇φ_I(x_J)]⁻¹ (eqs 68–70), Bubnov;
//! - `cd1`: Shepard test functions, trial derivatives corrected to first order (eqs 55–61,
//!   the `corrected` family), Petrov–Galerkin (eqs 96–97: a non-symmetric stiffness);
//! - `mls`: linear MLS (eqs 44–46), Bubnov;
//! - `efg`: MLS with unit nodal weights on the 5 × 5 Gauss points of the cells the nodes
//!   make; `cd1-gauss`: `cd1` on the same points (Fig 11).
//!
//! The weight is the cubic B-spline (eq 26, sphstab's `m4`) with s = √2 Δx (eqs 126, 130: h
//! = s, support 2s). Essential boundaries carry a row of bilinear finite elements ([B98
//! §5.2.4], eqs 100–105): with nodal quadrature the boundary nodes are interpolating and take
//! their elements' strains (each element weighing equally); with Gauss quadrature the
//! meshfree functions are blended into the elements' (eqs 100–104). Natural boundaries carry
//! the exact traction σ n (nodal boundary quadrature, or 5 Gauss points per segment), and
//! K u = f is solved by a banded LU ([`crate::forms::BandedLu`]).
//!
//! Choices B98 leaves open (stated with the rows of REPRODUCTION.md): P = 1 (the errors are
//! relative); the nodal volumes ΔV are a quarter of each adjacent cell's area (Δx² inside a
//! uniform grid); the "nodal values" of the l2 norm are the nodal coefficients u_I; the
//! energy norm is the square root of eq 118, with the trial strain of the method; the plate's
//! node set (a mapped grid, [`plate_with_hole`]) and its symmetry edges' finite-element row.

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
    /// CD1 (Shepard test functions, corrected trial derivatives) with the 5 × 5 Gauss
    /// background quadrature of `efg` ([B98] Fig 11).
    Cd1Gauss,
}

impl GalerkinMethod {
    /// Every method with its name.
    pub const ALL: [(GalerkinMethod, &'static str); 6] = [
        (GalerkinMethod::Sph, "sph"),
        (GalerkinMethod::Rl, "rl"),
        (GalerkinMethod::Cd1, "cd1"),
        (GalerkinMethod::Mls, "mls"),
        (GalerkinMethod::Efg, "efg"),
        (GalerkinMethod::Cd1Gauss, "cd1-gauss"),
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

/// A problem of [B98 §6.2] with its paper's parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GalerkinProblem {
    /// The cantilever [`Cantilever::B98`]; levels are nodes per unit depth.
    Beam,
    /// The plate with a hole [`PlateWithHole::B98`]; levels are nodes per unit length along
    /// its symmetry edges.
    Plate,
}

impl GalerkinProblem {
    /// Every problem with its name.
    pub const ALL: [(GalerkinProblem, &'static str); 2] = [
        (GalerkinProblem::Beam, "beam"),
        (GalerkinProblem::Plate, "plate"),
    ];

    /// The problem of a name (`what`: the flag or field in the error).
    pub fn by_name(what: &'static str, name: &str) -> Result<Self> {
        crate::error::lookup(what, &Self::ALL, name)
    }

    /// The name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }

    /// A one-line description with the parameters.
    pub fn describe(self) -> &'static str {
        match self {
            GalerkinProblem::Beam => {
                "cantilever (E = 1000, ν = 0.3, D = 1, L = 8, end shear P = 1; probe u_y(L, 0))"
            }
            GalerkinProblem::Plate => {
                "plate with a hole (E = 1000, ν = 0.3, a = 1, b = 5, unit tension at infinity; probe u_x(a, 0))"
            }
        }
    }

    /// The levels allowed ([`PER_DEPTH_RANGE`], [`PER_UNIT_RANGE`]).
    pub fn level_range(self) -> (usize, usize) {
        match self {
            GalerkinProblem::Beam => PER_DEPTH_RANGE,
            GalerkinProblem::Plate => PER_UNIT_RANGE,
        }
    }

    /// The levels of REPRODUCTION.md's rows: Δx = 1/4, 1/8, 1/16 (beam), 1/2, 1/4, 1/8
    /// (plate).
    pub fn default_levels(self) -> [usize; 3] {
        match self {
            GalerkinProblem::Beam => [4, 8, 16],
            GalerkinProblem::Plate => [2, 4, 8],
        }
    }
}

/// Solves `problem` with `method` at refinement `level` ([`cantilever`], [`plate_with_hole`]).
pub fn solve(
    problem: GalerkinProblem,
    method: GalerkinMethod,
    level: usize,
) -> Result<GalerkinReport> {
    match problem {
        GalerkinProblem::Beam => cantilever(&Cantilever::B98, method, level),
        GalerkinProblem::Plate => plate_with_hole(&PlateWithHole::B98, method, level),
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

/// An exact plane-stress solution of [B98 §6.2]: the material, the displacement and the
/// stress (σ_xx, σ_yy, σ_xy).
trait Exact {
    fn material(&self) -> (f64, f64);
    fn displacement(&self, x: f64, y: f64) -> [f64; 2];
    fn stress(&self, x: f64, y: f64) -> [f64; 3];

    /// The plane-stress elasticity (Voigt, engineering shear).
    fn elasticity(&self) -> [[f64; 3]; 3] {
        let (e, nu) = self.material();
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
        let (e, nu) = self.material();
        [
            (sx - nu * sy) / e,
            (sy - nu * sx) / e,
            2.0 * (1.0 + nu) / e * sxy,
        ]
    }
}

impl Exact for Cantilever {
    fn material(&self) -> (f64, f64) {
        (self.modulus, self.poisson)
    }
    fn displacement(&self, x: f64, y: f64) -> [f64; 2] {
        Cantilever::displacement(self, x, y)
    }
    fn stress(&self, x: f64, y: f64) -> [f64; 3] {
        Cantilever::stress(self, x, y)
    }
}

impl Exact for PlateWithHole {
    fn material(&self) -> (f64, f64) {
        (self.modulus, self.poisson)
    }
    fn displacement(&self, x: f64, y: f64) -> [f64; 2] {
        PlateWithHole::displacement(self, x, y)
    }
    fn stress(&self, x: f64, y: f64) -> [f64; 3] {
        PlateWithHole::stress(self, x, y)
    }
}

/// The solution of one discretisation.
#[derive(Clone, Debug, Serialize)]
pub struct GalerkinReport {
    /// Method.
    pub method: GalerkinMethod,
    /// Node spacing Δx (the plate: along its symmetry edges, eq 130); `node_spacing` in JSON.
    #[serde(rename = "node_spacing")]
    pub spacing: f64,
    /// Nodes.
    pub nodes: usize,
    /// Displacement error: for the nodal methods the nodal l2 error (eqs 114–115), (Σ ΔV
    /// |u_I − u(x_I)|²)^½ / (Σ ΔV |u(x_I)|²)^½; for the background-quadrature methods (`efg`,
    /// `cd1-gauss`) the L2 error (eqs 116–117) by their 5 × 5 Gauss quadrature.
    pub displacement_error: f64,
    /// Energy error (eqs 118–119, square-rooted): (Σ w (ε_h − ε):C:(ε_h − ε))^½ / (Σ w
    /// ε:C:ε)^½ over the quadrature points (the nodes, weights ΔV; `efg`, `cd1-gauss`: the
    /// Gauss points), ε_h the method's trial strain.
    pub energy_error: f64,
    /// The L2 displacement error (eqs 116–117) by 5 × 5 Gauss quadrature on the cells the
    /// nodes make, u_h = Σ φ_I u_I with the method's trial functions (`mls`, `cd1`, `efg`,
    /// `cd1-gauss`; `sph` and `rl` define gradients at the nodes only: `None`).
    pub integrated_displacement_error: Option<f64>,
    /// The energy error (eqs 118–119) by the same quadrature ([B98] Figs 10–11).
    pub integrated_energy_error: Option<f64>,
    /// The point where one displacement component is compared: the beam's u_y at (L, 0),
    /// the plate's u_x at (a, 0).
    pub probe: [f64; 2],
    /// The computed component there (the nodal coefficient; for the background methods the
    /// approximation's value).
    pub probe_displacement: f64,
    /// The exact one.
    pub exact_probe_displacement: f64,
}

/// Nodes per unit depth allowed (Δx = D/n). At 32 the beam has 257 × 33 nodes, 17,000
/// unknowns in a band of about 280: the banded LU holds ~1e8 B (3 × band × unknowns × 8 B).
pub const PER_DEPTH_RANGE: (usize, usize) = (2, 32);

/// Nodes per unit length along the plate's symmetry edges allowed (Δx = 1/n). At 12 the
/// plate has 49 × 97 nodes, 9,500 unknowns in a band of about 800: ~2e8 B.
pub const PER_UNIT_RANGE: (usize, usize) = (1, 12);

/// A discretised body: nodes, their volumes, the quadrilaterals they make, the essential
/// and the natural boundary.
struct Body {
    pos: Vec<[f64; 2]>,
    /// Nodal volumes: a quarter of each adjacent cell's area.
    vol: Vec<f64>,
    /// Cells, corners counter-clockwise at (ξ, η) = (0, 0), (1, 0), (1, 1), (0, 1).
    cells: Vec<[usize; 4]>,
    /// The cells of a finite-element row on the essential boundary ([B98 §5.2.4]; the
    /// beam), their corners 0 and 3 on that boundary.
    fe_cells: Vec<bool>,
    /// Prescribed degrees of freedom (2 × node + component) and their values.
    fixed: Vec<(usize, f64)>,
    /// Loaded boundary segments, counter-clockwise around the body (outward normal on the
    /// right), carrying the exact solution's traction σ n.
    edges: Vec<[usize; 2]>,
    /// The reported spacing.
    spacing: f64,
    /// The weight's smoothing length.
    h: f64,
    /// The probe: (node, component).
    probe: (usize, usize),
}

/// Nodal volumes from the cells: a quarter of each adjacent cell's area.
fn volumes(pos: &[[f64; 2]], cells: &[[usize; 4]]) -> Vec<f64> {
    let mut vol = vec![0.0; pos.len()];
    for c in cells {
        let p = c.map(|k| pos[k]);
        let area = 0.5
            * (0..4)
                .map(|a| {
                    let b = (a + 1) % 4;
                    p[a][0] * p[b][1] - p[b][0] * p[a][1]
                })
                .sum::<f64>();
        for &k in c {
            vol[k] += 0.25 * area;
        }
    }
    vol
}

/// Solves the cantilever `beam` with `method` at Δx = D/`per_depth`: a uniform grid, the
/// column x = 0 a row of finite elements with eqs 120–121 prescribed, the end x = L loaded
/// by eq 124.
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
    let at = |i: usize, j: usize| i * ny + j;
    let pos: Vec<[f64; 2]> = (0..nx)
        .flat_map(|i| (0..ny).map(move |j| [i as f64 * dx, -beam.depth / 2.0 + j as f64 * dx]))
        .collect();
    let cells: Vec<[usize; 4]> = (0..nx - 1)
        .flat_map(|i| {
            (0..ny - 1).map(move |j| [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
        })
        .collect();
    let fe_cells = cells.iter().map(|c| c[0] < ny).collect();
    let fixed = (0..ny)
        .flat_map(|j| {
            let k = at(0, j);
            let u = beam.displacement(pos[k][0], pos[k][1]);
            [(2 * k, u[0]), (2 * k + 1, u[1])]
        })
        .collect();
    let edges = (0..ny - 1)
        .map(|j| [at(nx - 1, j), at(nx - 1, j + 1)])
        .collect();
    let vol = volumes(&pos, &cells);
    let body = Body {
        pos,
        vol,
        cells,
        fe_cells,
        fixed,
        edges,
        spacing: dx,
        h: std::f64::consts::SQRT_2 * dx,
        probe: (at(nx - 1, ny / 2), 1),
    };
    run(beam, &body, method)
}

/// Solves the plate with a hole `plate` ([B98 §6.2.2], Fig 7) with `method` at Δx = 1/
/// `per_unit` along the symmetry edges (m = (b − a)/Δx segments, rounded), s = √2 Δx (eq
/// 130). The quadrant is a mapped grid (B98 does not print its node set): node (i, j) lies
/// at (1 − i/m) A_j + (i/m) B_j between the hole's point A_j = a(cos θ_j, sin θ_j), θ_j =
/// (π/2) j/(2m), and the outer edges' point B_j (b, b j/m) for j ≤ m, (b (2m − j)/m, b)
/// beyond (2m + 1 nodes around, m + 1 along each radial line; near the hole the nodes are
/// about 5 times closer around than along). The cells next to the symmetry edges are a row of
/// finite elements, so the normal displacement (u_y on y = 0, u_x on x = 0) is zero along
/// the whole edge, not only at its nodes: prescribing the nodal coefficients of
/// non-interpolating functions would leave the edge's reaction on the neighbouring nodes'
/// equations. The outer edges x = b and y = b carry Kirsch's traction, the hole its zero
/// traction.
pub fn plate_with_hole(
    plate: &PlateWithHole,
    method: GalerkinMethod,
    per_unit: usize,
) -> Result<GalerkinReport> {
    crate::error::check_range(
        "per_unit",
        per_unit as f64,
        PER_UNIT_RANGE.0 as f64,
        PER_UNIT_RANGE.1 as f64,
        true,
        true,
    )?;
    let (a, b) = (plate.radius, plate.half_width);
    let m = (((b - a) * per_unit as f64).round() as usize).max(1);
    let na = 2 * m + 1;
    let at = |i: usize, j: usize| i * na + j;
    let pos: Vec<[f64; 2]> = (0..=m)
        .flat_map(|i| {
            (0..na).map(move |j| {
                let th = std::f64::consts::FRAC_PI_2 * j as f64 / (2 * m) as f64;
                let inner = [a * th.cos(), a * th.sin()];
                let outer = if j <= m {
                    [b, b * j as f64 / m as f64]
                } else {
                    [b * (2 * m - j) as f64 / m as f64, b]
                };
                let t = i as f64 / m as f64;
                [
                    (1.0 - t) * inner[0] + t * outer[0],
                    (1.0 - t) * inner[1] + t * outer[1],
                ]
            })
        })
        .collect();
    // (i, j) → (i + 1, j) runs outward, (i, j) → (i, j + 1) anticlockwise about the origin:
    // the corners (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1) go counter-clockwise
    // the cells next to the symmetry edges (j = 0, j = 2m − 1) are a row of finite elements,
    // their corners rotated so that corners 0 and 3 lie on the edge
    let cells: Vec<[usize; 4]> = (0..m)
        .flat_map(|i| {
            (0..na - 1).map(move |j| {
                let c = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                if j == 0 {
                    [c[1], c[2], c[3], c[0]]
                } else if j == na - 2 {
                    [c[3], c[0], c[1], c[2]]
                } else {
                    c
                }
            })
        })
        .collect();
    let fe_cells = (0..m)
        .flat_map(|_| (0..na - 1).map(|j| j == 0 || j == na - 2))
        .collect();
    let mut fixed: Vec<(usize, f64)> = Vec::new();
    for i in 0..=m {
        fixed.push((2 * at(i, 0) + 1, 0.0));
        fixed.push((2 * at(i, na - 1), 0.0));
    }
    // the outer boundary i = m, counter-clockwise: j increasing; the hole i = 0 with the body
    // on its left: j decreasing (its exact traction is zero, a patch test's is not)
    let edges = (0..na - 1)
        .map(|j| [at(m, j), at(m, j + 1)])
        .chain((0..na - 1).map(|j| [at(0, j + 1), at(0, j)]))
        .collect();
    let vol = volumes(&pos, &cells);
    let dx = (b - a) / m as f64;
    let body = Body {
        pos,
        vol,
        cells,
        fe_cells,
        fixed,
        edges,
        spacing: dx,
        h: std::f64::consts::SQRT_2 * dx,
        probe: (at(0, 0), 0),
    };
    run(plate, &body, method)
}

/// A node's gradient: (node, ∇φ).
type Grad = (usize, [f64; 2]);
/// A node's value and gradient: (node, φ, ∇φ).
type Shape = (usize, f64, [f64; 2]);
/// A quadrature point: (weight, test gradients, trial gradients).
type QuadPoint<'a> = (f64, &'a [Grad], &'a [Grad]);

/// A bucket grid over the nodes for the neighbours within a radius.
struct Buckets {
    size: f64,
    lo: [f64; 2],
    dims: [usize; 2],
    cells: Vec<Vec<usize>>,
}

impl Buckets {
    fn new(pos: &[[f64; 2]], size: f64) -> Self {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in pos {
            for a in 0..2 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        let dims = [0, 1].map(|a| ((hi[a] - lo[a]) / size).floor() as usize + 1);
        let mut cells = vec![Vec::new(); dims[0] * dims[1]];
        let mut out = Buckets {
            size,
            lo,
            dims,
            cells: Vec::new(),
        };
        for (k, p) in pos.iter().enumerate() {
            let [i, j] = out.cell(*p);
            cells[i * dims[1] + j].push(k);
        }
        out.cells = cells;
        out
    }

    fn cell(&self, p: [f64; 2]) -> [usize; 2] {
        [0, 1].map(|a| {
            (((p[a] - self.lo[a]) / self.size).floor().max(0.0) as usize).min(self.dims[a] - 1)
        })
    }

    /// The nodes strictly within `radius` (≤ the bucket size) of `p`, in index order.
    fn near(&self, pos: &[[f64; 2]], p: [f64; 2], radius: f64) -> Vec<usize> {
        let [ci, cj] = self.cell(p);
        let mut out = Vec::new();
        for i in ci.saturating_sub(1)..=(ci + 1).min(self.dims[0] - 1) {
            for j in cj.saturating_sub(1)..=(cj + 1).min(self.dims[1] - 1) {
                for &k in &self.cells[i * self.dims[1] + j] {
                    let d = [pos[k][0] - p[0], pos[k][1] - p[1]];
                    if (d[0] * d[0] + d[1] * d[1]).sqrt() < radius {
                        out.push(k);
                    }
                }
            }
        }
        out.sort_unstable();
        out
    }
}

/// The bilinear map of a cell at (ξ, η).
struct Bilinear {
    /// The position.
    x: [f64; 2],
    /// The four shape functions.
    n: [f64; 4],
    /// Their gradients.
    grad: [[f64; 2]; 4],
    /// The Jacobian determinant.
    det: f64,
    /// ∇ξ.
    dxi: [f64; 2],
}

/// The bilinear map of the cell with corners `p` at (ξ, η).
fn bilinear(p: [[f64; 2]; 4], xi: f64, eta: f64) -> Bilinear {
    let n = [
        (1.0 - xi) * (1.0 - eta),
        xi * (1.0 - eta),
        xi * eta,
        (1.0 - xi) * eta,
    ];
    let dxi = [-(1.0 - eta), 1.0 - eta, eta, -eta];
    let deta = [-(1.0 - xi), -xi, xi, 1.0 - xi];
    let mut x = [0.0; 2];
    let mut j = [[0.0; 2]; 2];
    for a in 0..4 {
        for c in 0..2 {
            x[c] += n[a] * p[a][c];
            j[0][c] += dxi[a] * p[a][c];
            j[1][c] += deta[a] * p[a][c];
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let inv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    let g = [0, 1, 2, 3].map(|a| {
        [
            inv[0][0] * dxi[a] + inv[0][1] * deta[a],
            inv[1][0] * dxi[a] + inv[1][1] * deta[a],
        ]
    });
    Bilinear {
        x,
        n,
        grad: g,
        det,
        dxi: [inv[0][0], inv[1][0]],
    }
}

/// The shape functions of `family` at `p` over the nodes within the support, each weighted by
/// its volume (`volumes`) or by 1 (EFG's MLS).
fn shapes_at(
    body: &Body,
    buckets: &Buckets,
    kp: KernelParams,
    family: ShapeFamily,
    volumes: bool,
    p: [f64; 2],
) -> Result<Vec<Shape>> {
    let nb = buckets.near(&body.pos, p, kp.support());
    let nodes: Vec<([f64; 2], f64)> = nb
        .iter()
        .map(|&m| {
            (
                [body.pos[m][0] - p[0], body.pos[m][1] - p[1]],
                if volumes { body.vol[m] } else { 1.0 },
            )
        })
        .collect();
    let mut out = Vec::new();
    eval_d(family, kp, &nodes, p[0], &mut out)?;
    Ok(nb.iter().zip(out).map(|(&m, (v, g))| (m, v, g)).collect())
}

/// The trial and test gradients of `method` at node `k` (nodal quadrature).
fn nodal_shapes(
    body: &Body,
    buckets: &Buckets,
    kp: KernelParams,
    method: GalerkinMethod,
    k: usize,
) -> Result<(Vec<Grad>, Vec<Grad>)> {
    let pos = &body.pos;
    let family = |f: ShapeFamily| -> Result<Vec<Grad>> {
        Ok(shapes_at(body, buckets, kp, f, true, pos[k])?
            .into_iter()
            .map(|(m, _, g)| (m, g))
            .collect())
    };
    let g = match method {
        GalerkinMethod::Mls | GalerkinMethod::Efg => family(ShapeFamily::Mls)?,
        GalerkinMethod::Cd1 | GalerkinMethod::Cd1Gauss => family(ShapeFamily::Corrected)?,
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
            let mut g: Vec<Grad> = raw
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
    Ok((g, t))
}

/// The trial and test families of a method at points other than the nodes (background
/// quadrature, integrated norms), and whether they weigh by volume; `None` for the methods
/// defined at the nodes only.
fn point_families(method: GalerkinMethod) -> Option<(ShapeFamily, ShapeFamily, bool)> {
    match method {
        GalerkinMethod::Mls => Some((ShapeFamily::Mls, ShapeFamily::Mls, true)),
        GalerkinMethod::Efg => Some((ShapeFamily::Mls, ShapeFamily::Mls, false)),
        GalerkinMethod::Cd1 | GalerkinMethod::Cd1Gauss => {
            Some((ShapeFamily::Corrected, ShapeFamily::Shepard, true))
        }
        GalerkinMethod::Sph | GalerkinMethod::Rl => None,
    }
}

/// A background quadrature point: (weight, position, trial shapes, test shapes).
type GaussPoint = (f64, [f64; 2], Vec<Shape>, Vec<Shape>);

/// The 5 × 5 Gauss points of every cell with the method's trial and test functions; in a
/// finite-element cell the functions are blended with the cell's bilinear ones (eqs 100–104:
/// Φ⁰_I = r φ_I + (1 − r) N_I, r = 3ξ² − 2ξ³, ξ = 0 on the essential boundary).
fn gauss_points(
    body: &Body,
    buckets: &Buckets,
    kp: KernelParams,
    (trial_f, test_f, volumes): (ShapeFamily, ShapeFamily, bool),
) -> Result<Vec<GaussPoint>> {
    let mut points = Vec::with_capacity(25 * body.cells.len());
    for (ci, c) in body.cells.iter().enumerate() {
        let corners = c.map(|k| body.pos[k]);
        for &(gx, wx) in &GAUSS5 {
            for &(gy, wy) in &GAUSS5 {
                let (xi, eta) = (0.5 * (1.0 + gx), 0.5 * (1.0 + gy));
                let Bilinear {
                    x: p,
                    n: nv,
                    grad: ng,
                    det,
                    dxi,
                } = bilinear(corners, xi, eta);
                let mut trial = shapes_at(body, buckets, kp, trial_f, volumes, p)?;
                let mut test = if test_f == trial_f {
                    trial.clone()
                } else {
                    shapes_at(body, buckets, kp, test_f, volumes, p)?
                };
                if body.fe_cells[ci] {
                    let r = 3.0 * xi * xi - 2.0 * xi.powi(3);
                    let dr = 6.0 * xi - 6.0 * xi * xi;
                    let blend = |phi: &mut Vec<Shape>| {
                        for a in 0..4 {
                            if !phi.iter().any(|s| s.0 == c[a]) {
                                phi.push((c[a], 0.0, [0.0; 2]));
                            }
                        }
                        for (m, v, g) in phi.iter_mut() {
                            let (n0, g0) = c
                                .iter()
                                .position(|k| k == m)
                                .map_or((0.0, [0.0; 2]), |a| (nv[a], ng[a]));
                            let (pv, pg) = (*v, *g);
                            *v = r * pv + (1.0 - r) * n0;
                            for d in 0..2 {
                                g[d] = r * pg[d] + dr * dxi[d] * (pv - n0) + (1.0 - r) * g0[d];
                            }
                        }
                    };
                    blend(&mut trial);
                    blend(&mut test);
                }
                points.push((wx * wy * 0.25 * det, p, trial, test));
            }
        }
    }
    Ok(points)
}

/// The five-point Gauss rule on [−1, 1]: (point, weight).
const GAUSS5: [(f64, f64); 5] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// The exact traction σ n on the edge from `a` to `b` (counter-clockwise) at `p`.
fn traction(exact: &impl Exact, a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> [f64; 2] {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    let n = [dy / len, -dx / len];
    let s = exact.stress(p[0], p[1]);
    [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
}

/// Solves `body` against `exact` with `method` and measures the errors.
fn run(exact: &impl Exact, body: &Body, method: GalerkinMethod) -> Result<GalerkinReport> {
    let n = body.pos.len();
    let kp = KernelParams {
        kernel: crate::kernel::by_name("m4")?,
        h: body.h,
    };
    let buckets = Buckets::new(&body.pos, kp.support());
    let c = exact.elasticity();
    let background = matches!(method, GalerkinMethod::Efg | GalerkinMethod::Cd1Gauss);
    let families = point_families(method);
    let points = match families {
        Some(f) => gauss_points(body, &buckets, kp, f)?,
        None => Vec::new(),
    };
    let mut f = vec![0.0; 2 * n];
    let (trial, u) = if background {
        let grads: Vec<(Vec<Grad>, Vec<Grad>)> = points
            .iter()
            .map(|(_, _, tr, te)| {
                (
                    tr.iter().map(|&(m, _, g)| (m, g)).collect(),
                    te.iter().map(|&(m, _, g)| (m, g)).collect(),
                )
            })
            .collect();
        let quad: Vec<QuadPoint> = points
            .iter()
            .zip(&grads)
            .map(|((w, ..), (tr, te))| (*w, &te[..], &tr[..]))
            .collect();
        // the traction by 5 Gauss points per edge, on the test functions
        let test_f = families.map_or(ShapeFamily::Mls, |f| f.1);
        let volumes = families.is_some_and(|f| f.2);
        for e in &body.edges {
            let (a, b) = (body.pos[e[0]], body.pos[e[1]]);
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            for &(g, w) in &GAUSS5 {
                let t = 0.5 * (1.0 + g);
                let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                let tr = traction(exact, a, b, p);
                for (m, v, _) in shapes_at(body, &buckets, kp, test_f, volumes, p)? {
                    f[2 * m] += 0.5 * len * w * tr[0] * v;
                    f[2 * m + 1] += 0.5 * len * w * tr[1] * v;
                }
            }
        }
        let u = solve_system(&c, &quad, f, &body.fixed)?;
        (Vec::new(), u)
    } else {
        // nodal quadrature; the finite-element row's nodes take their elements' strains at
        // their corner, each element weighing equally
        let mut trial: Vec<Vec<Grad>> = Vec::with_capacity(n);
        let mut test: Vec<Vec<Grad>> = Vec::with_capacity(n);
        let mut fe: Vec<Vec<Grad>> = vec![Vec::new(); n];
        let mut fe_count = vec![0usize; n];
        for (ci, cell) in body.cells.iter().enumerate() {
            if !body.fe_cells[ci] {
                continue;
            }
            let corners = cell.map(|k| body.pos[k]);
            for (a, eta) in [(0, 0.0), (3, 1.0)] {
                let g = bilinear(corners, 0.0, eta).grad;
                fe[cell[a]].extend((0..4).map(|q| (cell[q], g[q])));
                fe_count[cell[a]] += 1;
            }
        }
        for k in 0..n {
            if fe_count[k] > 0 {
                let w = 1.0 / fe_count[k] as f64;
                let g = merge(
                    fe[k]
                        .iter()
                        .map(|&(m, g)| (m, [w * g[0], w * g[1]]))
                        .collect(),
                );
                trial.push(g.clone());
                test.push(g);
                continue;
            }
            let (tr, te) = nodal_shapes(body, &buckets, kp, method, k)?;
            trial.push(tr);
            test.push(te);
        }
        let quad: Vec<QuadPoint> = (0..n)
            .map(|k| (body.vol[k], &test[k][..], &trial[k][..]))
            .collect();
        // the traction by nodal boundary quadrature (each segment's ends take half of it)
        for e in &body.edges {
            let (a, b) = (body.pos[e[0]], body.pos[e[1]]);
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            for k in *e {
                let tr = traction(exact, a, b, body.pos[k]);
                f[2 * k] += 0.5 * len * tr[0];
                f[2 * k + 1] += 0.5 * len * tr[1];
            }
        }
        let u = solve_system(&c, &quad, f, &body.fixed)?;
        (trial, u)
    };
    let energy = |e: [f64; 3]| {
        (0..3)
            .map(|r| (0..3).map(|s| e[r] * c[r][s] * e[s]).sum::<f64>())
            .sum::<f64>()
    };
    // the integrated norms (eqs 116–119) at the Gauss points
    let integrated = if families.is_some() {
        let (mut du, mut un, mut de, mut en) = (0.0, 0.0, 0.0, 0.0);
        for (w, p, phi, _) in &points {
            let (mut uh, mut eh) = ([0.0; 2], [0.0; 3]);
            for &(m, v, g) in phi {
                uh[0] += v * u[2 * m];
                uh[1] += v * u[2 * m + 1];
                let b = bmat(g);
                for r in 0..3 {
                    eh[r] += b[r][0] * u[2 * m] + b[r][1] * u[2 * m + 1];
                }
            }
            let ex = exact.displacement(p[0], p[1]);
            du += w * ((uh[0] - ex[0]).powi(2) + (uh[1] - ex[1]).powi(2));
            un += w * (ex[0] * ex[0] + ex[1] * ex[1]);
            let ee = exact.strain(p[0], p[1]);
            de += w * energy([eh[0] - ee[0], eh[1] - ee[1], eh[2] - ee[2]]);
            en += w * energy(ee);
        }
        Some(((du / un).sqrt(), (de / en).sqrt()))
    } else {
        None
    };
    let (probe_node, probe_c) = body.probe;
    let probe = body.pos[probe_node];
    let exact_probe = exact.displacement(probe[0], probe[1])[probe_c];
    let out = if background {
        let (du, de) = integrated.unwrap_or((f64::NAN, f64::NAN));
        let (fam, vols) = families.map_or((ShapeFamily::Mls, false), |f| (f.0, f.2));
        let value: f64 = shapes_at(body, &buckets, kp, fam, vols, probe)?
            .iter()
            .map(|&(m, v, _)| v * u[2 * m + probe_c])
            .sum();
        GalerkinReport {
            method,
            spacing: body.spacing,
            nodes: n,
            displacement_error: du,
            energy_error: de,
            integrated_displacement_error: Some(du),
            integrated_energy_error: Some(de),
            probe,
            probe_displacement: value,
            exact_probe_displacement: exact_probe,
        }
    } else {
        // the nodal norms (eqs 114–115, 118–119 at the nodes)
        let (mut du, mut un, mut de, mut en) = (0.0, 0.0, 0.0, 0.0);
        for k in 0..n {
            let p = body.pos[k];
            let ex = exact.displacement(p[0], p[1]);
            du += body.vol[k] * ((u[2 * k] - ex[0]).powi(2) + (u[2 * k + 1] - ex[1]).powi(2));
            un += body.vol[k] * (ex[0] * ex[0] + ex[1] * ex[1]);
            let mut eh = [0.0; 3];
            for &(m, g) in &trial[k] {
                let b = bmat(g);
                for r in 0..3 {
                    eh[r] += b[r][0] * u[2 * m] + b[r][1] * u[2 * m + 1];
                }
            }
            let ee = exact.strain(p[0], p[1]);
            de += body.vol[k] * energy([eh[0] - ee[0], eh[1] - ee[1], eh[2] - ee[2]]);
            en += body.vol[k] * energy(ee);
        }
        GalerkinReport {
            method,
            spacing: body.spacing,
            nodes: n,
            displacement_error: (du / un).sqrt(),
            energy_error: (de / en).sqrt(),
            integrated_displacement_error: integrated.map(|x| x.0),
            integrated_energy_error: integrated.map(|x| x.1),
            probe,
            probe_displacement: u[2 * probe_node + probe_c],
            exact_probe_displacement: exact_probe,
        }
    };
    let finite = |x: f64| x.is_finite();
    if !(finite(out.displacement_error)
        && finite(out.energy_error)
        && out.integrated_energy_error.is_none_or(finite)
        && out.integrated_displacement_error.is_none_or(finite))
    {
        return Err(Error::NonFinite("Galerkin solution"));
    }
    Ok(out)
}

/// B(∇φ): the strain (ε_xx, ε_yy, γ_xy) of a unit displacement of a node in x and in y.
fn bmat(g: [f64; 2]) -> [[f64; 2]; 3] {
    [[g[0], 0.0], [0.0, g[1]], [g[1], g[0]]]
}

/// Assembles K = Σ_p w_p B_test(x_p)ᵀ C B_trial(x_p) over the quadrature points `quad`
/// ((weight, test gradients, trial gradients)), prescribes the degrees of freedom `fixed`
/// (their rows become identities, their columns move to the load), and solves K u = `f` by
/// banded LU.
fn solve_system(
    c: &[[f64; 3]; 3],
    quad: &[QuadPoint],
    mut f: Vec<f64>,
    fixed: &[(usize, f64)],
) -> Result<Vec<f64>> {
    let dofs = f.len();
    // K in band storage: row r holds columns r − band ..= r + band (the node pairs that share
    // a quadrature point bound the band)
    let band = quad
        .iter()
        .map(|&(_, test, trial)| {
            let span = |g: &[Grad]| {
                g.iter()
                    .fold((usize::MAX, 0), |(lo, hi), &(m, _)| (lo.min(m), hi.max(m)))
            };
            let ((l0, h0), (l1, h1)) = (span(test), span(trial));
            if test.is_empty() || trial.is_empty() {
                0
            } else {
                2 * (h0.max(h1) - l0.min(l1)) + 1
            }
        })
        .max()
        .unwrap_or(0);
    let width = 2 * band + 1;
    let mut k = vec![0.0; dofs * width];
    let mut cb: Vec<[[f64; 2]; 3]> = Vec::new();
    for &(w, test, trial) in quad {
        // C B_b once per trial node, then B_aᵀ (C B_b) per pair
        cb.clear();
        cb.extend(trial.iter().map(|&(_, gb)| {
            let bb = bmat(gb);
            let mut out = [[0.0; 2]; 3];
            for r in 0..3 {
                for q in 0..2 {
                    out[r][q] = w * (0..3).map(|s| c[r][s] * bb[s][q]).sum::<f64>();
                }
            }
            out
        }));
        for &(a, ga) in test {
            let ba = bmat(ga);
            for (&(b, _), m) in trial.iter().zip(&cb) {
                for p in 0..2 {
                    let row = 2 * a + p;
                    for q in 0..2 {
                        let v: f64 = (0..3).map(|r| ba[r][p] * m[r][q]).sum();
                        k[row * width + (2 * b + q + band - row)] += v;
                    }
                }
            }
        }
    }
    let rows: Vec<Vec<(usize, f64)>> = (0..dofs)
        .map(|r| {
            (r.saturating_sub(band)..(r + band + 1).min(dofs))
                .map(|col| (col, k[r * width + (col + band - r)]))
                .filter(|&(_, v)| v != 0.0)
                .collect()
        })
        .collect();
    drop(k);
    let mut u = vec![0.0; dofs];
    let mut is_fixed = vec![false; dofs];
    for &(d, v) in fixed {
        u[d] = v;
        is_fixed[d] = true;
    }
    let mut sparse: Vec<Vec<(usize, f64)>> = Vec::with_capacity(dofs);
    for (r, row) in rows.iter().enumerate() {
        if is_fixed[r] {
            sparse.push(vec![(r, 1.0)]);
            f[r] = u[r];
            continue;
        }
        let mut out = Vec::with_capacity(row.len());
        for &(col, v) in row {
            if is_fixed[col] {
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

/// Sums the gradients of repeated nodes.
fn merge(g: Vec<Grad>) -> Vec<Grad> {
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
