//! Interpolation and gradient accuracy of a kernel approximation on a finite particle set
//! (`sphstab interpolate`; \[T\] §2.7, Figs 2.10–2.20): a known function f is sampled at the
//! particles of a uniform 1D or 2D lattice on an interval, and its kernel approximation
//!
//! ```text
//! ⟨f⟩(x_I) = Σ_J φ_J(x_I) f_J,   ⟨∇f⟩(x_I) = Σ_J ∇φ_J(x_I) f_J,   ⟨∇²f⟩(x_I) = Σ_J ∇φ_J(x_I) · ⟨∇f⟩_J
//! ```
//!
//! is compared with the exact values. φ_J are the shape functions of the chosen family
//! ([`crate::shape::eval_d`], the solver's own): `sph` gives the thesis's plain sums
//! (φ_J = V_J W(x_I − x_J), eqs 2.24–2.25, V_J = Δx^D); `shepard`, `corrected` and `mls` the
//! consistent families. The second derivative is "the gradient of the already computed first
//! gradient" (\[T\] §2.7), summed as the divergence (the Laplacian; f'' in 1D).
//!
//! Particles sit at a + iΔx, i = 0 … N − 1 per axis, ends included, Δx = (b − a)/(N − 1).
//! Without ghosts the sums see only these particles, so a particle within a support radius of
//! the boundary misses part of its cover (\[T\] Fig 2.10: "errors of up to 50% at the
//! boundary"). With ghosts (\[T\] §2.7, "the ghost particle approach": the function is extended
//! beyond the ends), the lattice continues 2R beyond each end with particles that carry the
//! function's own values; the first gradient is then formed at every particle within R of the
//! interval, so the second pass sees complete covers too. Errors are reported at the particles
//! of the interval only.
//!
//! The functions are sums over the axes, f(x) = Σ_a g(x_a), so that 1D and 2D share one
//! definition: `quartic` g = (x − ½)⁴ (\[T\] Fig 2.10, after Zhang & Batra), `sine` g = sin x
//! (Figs 2.13–2.16), `edge` a falling edge from 1 to 0 over `edge_width` spacings centred on
//! the interval (Figs 2.17–2.19: "a square wave with a linear falling edge of a known
//! gradient"), `step` the discontinuous edge (Fig 2.20), and `linear` g = x (a consistency
//! check: `corrected` and `mls` reproduce it and its gradient exactly, ghosts or not). The
//! edge's gradient has a jump and the step's is a Dirac: their second derivative (and the step's
//! gradient) have no pointwise error; for them the report gives the width of the computed
//! gradient's peak instead.

#![allow(clippy::needless_range_loop)]

use crate::budget::Budget;
use crate::error::{Error, Result, check_range, field, fields};
use crate::kernel::Kernel;
use crate::params::check_count;
use crate::shape::{KernelParams, ShapeFamily, eval_d};
use rayon::prelude::*;
use serde::Serialize;

/// Particles per axis: 1D range.
pub const PARTICLES_1D: (usize, usize) = (3, 1_000_000);
/// Particles per axis: 2D range.
pub const PARTICLES_2D: (usize, usize) = (3, 1000);
/// h/Δx range (the kernel's own convention; the support ζh must also exceed Δx).
pub const H_RANGE: (f64, f64) = (0.05, 20.0);
/// Shape-function evaluations counted as one particle-step against the budget's `max_steps`
/// (measured: ~30 ns of CPU per evaluation, ~1 μs per particle-step of the 2D solver).
pub const EVALUATIONS_PER_STEP: f64 = 30.0;

/// The function interpolated (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TestFunction {
    /// g = (x − ½)⁴.
    Quartic,
    /// g = sin x.
    Sine,
    /// g = x.
    Linear,
    /// 1 left of the edge, 0 right of it, linear over `width` spacings (`width` > 0).
    Edge {
        /// Edge width in particle spacings.
        width: f64,
    },
    /// The discontinuous edge: 1 left of the interval's midpoint, 0 right of it (½ on it).
    Step,
}

impl TestFunction {
    /// The CLI names.
    pub const NAMES: [&'static str; 5] = ["quartic", "sine", "linear", "edge", "step"];

    /// The function of a name; `edge_width` (spacings) is used by `edge` only.
    pub fn by_name(name: &str, edge_width: f64) -> Result<Self> {
        Ok(match name {
            "quartic" => Self::Quartic,
            "sine" => Self::Sine,
            "linear" => Self::Linear,
            "edge" => {
                check_range("edge_width", edge_width, 0.0, 1e6, false, true)?;
                Self::Edge { width: edge_width }
            }
            "step" => Self::Step,
            _ => {
                return Err(Error::UnknownName {
                    what: field("function"),
                    given: name.to_string(),
                    valid: Self::NAMES.join(", ").into(),
                });
            }
        })
    }

    /// CLI name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Quartic => "quartic",
            Self::Sine => "sine",
            Self::Linear => "linear",
            Self::Edge { .. } => "edge",
            Self::Step => "step",
        }
    }

    /// The default interval: (0, 1), or (0, 3π) for `sine` (\[T\] Figs 2.13, 2.14).
    pub fn default_interval(self) -> (f64, f64) {
        match self {
            Self::Sine => (0.0, 3.0 * std::f64::consts::PI),
            _ => (0.0, 1.0),
        }
    }

    /// Whether the gradient has a pointwise value everywhere (not the step's Dirac).
    pub fn smooth_gradient(self) -> bool {
        !matches!(self, Self::Step)
    }

    /// Whether the second derivative has a pointwise value everywhere (not at the kinks of
    /// `edge`, nor for `step`).
    pub fn smooth_second(self) -> bool {
        !matches!(self, Self::Step | Self::Edge { .. })
    }

    /// (g, g′, g″) at x on an interval with midpoint `mid` and spacing `dx`.
    fn eval(self, x: f64, mid: f64, dx: f64) -> [f64; 3] {
        match self {
            Self::Quartic => {
                let u = x - 0.5;
                [u.powi(4), 4.0 * u.powi(3), 12.0 * u * u]
            }
            Self::Sine => [x.sin(), x.cos(), -x.sin()],
            Self::Linear => [x, 1.0, 0.0],
            Self::Edge { width } => {
                let w = width * dx;
                let s = (x - mid) / w + 0.5;
                if s <= 0.0 {
                    [1.0, 0.0, 0.0]
                } else if s >= 1.0 {
                    [0.0, 0.0, 0.0]
                } else {
                    [1.0 - s, -1.0 / w, 0.0]
                }
            }
            Self::Step => {
                let v = if x < mid {
                    1.0
                } else if x > mid {
                    0.0
                } else {
                    0.5
                };
                [v, 0.0, 0.0]
            }
        }
    }
}

/// How the kernel's volume sums are normalised (`sph` shapes; the other families normalise
/// themselves, so both give them the same result).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Normalisation {
    /// The kernel's own constant (∫W = 1 over the continuum): V_J = Δx^D.
    Continuum,
    /// Divided by its lattice sum S0 = Σ_J W(x_I − x_J) Δx^D over a full cover, so that the
    /// interior sums reproduce a constant exactly: V_J = Δx^D/S0 (\[T\] §2.2.2: the
    /// mollifier's normalisation "must be enforced using a numerical integration").
    Lattice,
}

impl Normalisation {
    /// The CLI names.
    pub const ALL: [(Normalisation, &'static str); 2] = [
        (Normalisation::Continuum, "continuum"),
        (Normalisation::Lattice, "lattice"),
    ];

    /// CLI name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }

    /// Looks a normalisation up by name.
    pub fn by_name(name: &str) -> Result<Self> {
        crate::error::lookup("normalisation", &Self::ALL, name)
    }
}

/// What to interpolate, where and how.
#[derive(Clone, Copy, Debug)]
pub struct InterpolationConfig {
    /// 1 or 2.
    pub dim: usize,
    /// The function.
    pub function: TestFunction,
    /// The interval [a, b] (per axis in 2D).
    pub interval: (f64, f64),
    /// Particles per axis on the interval, ends included.
    pub particles: usize,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// h/Δx, the kernel's own convention (the support radius, the thesis's cover, is ζh).
    pub h_over_dx: f64,
    /// Shape-function family.
    pub shape: ShapeFamily,
    /// Ghost particles carrying the function's own values beyond the ends.
    pub ghosts: bool,
    /// The kernel's normalisation.
    pub normalisation: Normalisation,
    /// The budget the evaluation must stay within ([`EVALUATIONS_PER_STEP`]).
    pub budget: Budget,
}

impl InterpolationConfig {
    /// 1D, the function's default interval, 101 particles, sph shapes, no ghosts.
    pub fn new(function: TestFunction, kernel: &'static dyn Kernel, h_over_dx: f64) -> Self {
        Self {
            dim: 1,
            function,
            interval: function.default_interval(),
            particles: 101,
            kernel,
            h_over_dx,
            shape: ShapeFamily::Sph,
            ghosts: false,
            normalisation: Normalisation::Continuum,
            budget: Budget::default(),
        }
    }

    /// Checks every field (errors name the field and the allowed range).
    pub fn validate(&self) -> Result<()> {
        if !(1..=2).contains(&self.dim) {
            return Err(Error::OutOfRange {
                field: "dim",
                value: self.dim as f64,
                range: "must be 1 or 2".into(),
            });
        }
        let (lo, hi) = if self.dim == 1 {
            PARTICLES_1D
        } else {
            PARTICLES_2D
        };
        check_count("particles", self.particles, lo, hi)?;
        let (a, b) = self.interval;
        check_range("interval", a, -1e12, 1e12, true, true)?;
        check_range("interval", b, -1e12, 1e12, true, true)?;
        if b <= a {
            return Err(Error::OutOfRange {
                field: "interval",
                value: b,
                range: format!("the end b must exceed the start a = {a}").into(),
            });
        }
        check_range(
            "h_over_dx",
            self.h_over_dx,
            H_RANGE.0,
            H_RANGE.1,
            true,
            true,
        )?;
        if self.kernel.zeta() * self.h_over_dx <= 1.0 {
            return Err(Error::OutOfRange {
                field: "h_over_dx",
                value: self.h_over_dx,
                range: format!(
                    "the support ζh must exceed Δx so that particles have neighbours: h/Δx > {} for {}",
                    1.0 / self.kernel.zeta(),
                    self.kernel.name()
                )
                .into(),
            });
        }
        if let TestFunction::Edge { width } = self.function {
            check_range("edge_width", width, 0.0, 1e6, false, true)?;
        }
        Ok(())
    }

    /// Particle spacing Δx.
    pub fn dx(&self) -> f64 {
        (self.interval.1 - self.interval.0) / (self.particles - 1) as f64
    }
}

/// Errors of one quantity over the particles of the interval, each relative to the largest
/// exact magnitude of that quantity there (`scale`).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ErrorNorms {
    /// Largest |exact| over the interval (the scale of the relative errors).
    pub scale: f64,
    /// max |approx − exact| / scale over every particle of the interval.
    pub max: f64,
    /// RMS |approx − exact| / scale over every particle of the interval.
    pub rms: f64,
    /// max over the particles within one support radius of the boundary.
    pub boundary_max: f64,
    /// max over the others (None when every particle is within R of the boundary).
    pub interior_max: Option<f64>,
}

/// The accuracy of one interpolation.
#[derive(Clone, Debug, Serialize)]
pub struct InterpolationReport {
    /// Dimension.
    pub dim: usize,
    /// Function name.
    pub function: &'static str,
    /// Edge width in spacings (`edge` only).
    pub edge_width: Option<f64>,
    /// [a, b].
    pub interval: [f64; 2],
    /// Particles per axis.
    pub particles: usize,
    /// Δx (in the function's argument).
    pub spacing: f64,
    /// Kernel name.
    pub kernel: &'static str,
    /// h/Δx.
    pub h_over_dx: f64,
    /// Support radius R/Δx = ζh/Δx (the thesis's cover in particle spacings).
    pub support_over_dx: f64,
    /// Shape family.
    pub shape: &'static str,
    /// Whether ghosts were used.
    pub ghosts: bool,
    /// The kernel's normalisation.
    pub normalisation: &'static str,
    /// The lattice sum S0 = Σ_J W(x_I − x_J) Δx^D over a full cover (1 for an exact
    /// quadrature of ∫W = 1); the volumes are divided by it with the lattice normalisation.
    pub lattice_sum: f64,
    /// Errors of ⟨f⟩.
    pub value: ErrorNorms,
    /// |⟨f⟩ − f| / |f| at the first particle (x = a; None where f(a) = 0).
    pub value_at_start: Option<f64>,
    /// Errors of ⟨∇f⟩ (vector norm); None for the step.
    pub gradient: Option<ErrorNorms>,
    /// Errors of ⟨∇²f⟩; None for the edge and the step.
    pub laplacian: Option<ErrorNorms>,
    /// 1D edge and step: full width at half maximum of |⟨f′⟩|'s peak, in Δx (the exact edge's
    /// is its width; the step's is 0).
    pub gradient_peak_width: Option<f64>,
    /// 1D edge and step: Σ ⟨f′⟩ Δx over the interval (exact: −1, the drop of the edge).
    pub gradient_integral: Option<f64>,
    /// Per particle of the interval (first axis slowest in 2D): the first coordinate.
    pub position: Vec<f64>,
    /// f.
    pub f: Vec<f64>,
    /// ⟨f⟩.
    pub f_approx: Vec<f64>,
    /// ∂f/∂x₁ (the first axis).
    pub gradient_x: Vec<f64>,
    /// ⟨∂f/∂x₁⟩.
    pub gradient_x_approx: Vec<f64>,
    /// ∇²f (0 where not defined).
    pub laplacian_exact: Vec<f64>,
    /// ⟨∇²f⟩.
    pub laplacian_approx: Vec<f64>,
}

/// Runs one interpolation ([module docs](self)).
pub fn interpolate(cfg: &InterpolationConfig) -> Result<InterpolationReport> {
    cfg.validate()?;
    match cfg.dim {
        1 => interpolate_nd::<1>(cfg),
        _ => interpolate_nd::<2>(cfg),
    }
}

/// Relative error norms of `approx` against `exact` (vectors as rows of D values).
fn norms<const D: usize>(
    exact: &[[f64; D]],
    approx: &[[f64; D]],
    near_boundary: &[bool],
) -> ErrorNorms {
    let mag = |v: &[f64; D]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
    let scale = exact.iter().map(mag).fold(0.0, f64::max);
    let s = if scale > 0.0 { scale } else { 1.0 };
    let err: Vec<f64> = exact
        .iter()
        .zip(approx)
        .map(|(e, a)| {
            let mut d = [0.0; D];
            for c in 0..D {
                d[c] = a[c] - e[c];
            }
            mag(&d) / s
        })
        .collect();
    let max_of = |pick: bool| {
        err.iter()
            .zip(near_boundary)
            .filter(|(_, nb)| **nb == pick)
            .map(|(e, _)| *e)
            .fold(None, |m: Option<f64>, e| Some(m.map_or(e, |m| m.max(e))))
    };
    ErrorNorms {
        scale,
        max: err.iter().cloned().fold(0.0, f64::max),
        rms: (err.iter().map(|e| e * e).sum::<f64>() / err.len() as f64).sqrt(),
        boundary_max: max_of(true).unwrap_or(0.0),
        interior_max: max_of(false),
    }
}

/// A particle's neighbours (flat indices) and their (φ_J, ∇φ_J).
type Stencil<const D: usize> = (Vec<usize>, Vec<(f64, [f64; D])>);

fn interpolate_nd<const D: usize>(cfg: &InterpolationConfig) -> Result<InterpolationReport> {
    let (a, b) = cfg.interval;
    let n = cfg.particles;
    let dx = cfg.dx();
    let mid = 0.5 * (a + b);
    let h = cfg.h_over_dx * dx;
    let kp = KernelParams {
        kernel: cfg.kernel,
        h,
    };
    let r = kp.support();
    // index reach of a support radius, and the ghost layers (2R with ghosts)
    let reach = (r / dx).floor() as i64;
    let g = if cfg.ghosts {
        (2.0 * r / dx).ceil() as i64
    } else {
        0
    };
    let (lo, hi) = (-g, n as i64 - 1 + g);
    let side = (hi - lo + 1) as usize;
    let count = side.pow(D as u32);
    // two passes over the particles, each evaluating the shape functions of a full cover
    let evaluations = 2.0 * count as f64 * ((2 * reach + 1) as f64).powi(D as i32);
    cfg.budget.work(
        fields(&["particles", "h_over_dx", "dim"]),
        &format!("the interpolation ({count} particles with the ghosts)"),
        evaluations,
        "shape-function evaluations",
        cfg.budget.max_steps * EVALUATIONS_PER_STEP,
    )?;
    // lattice index ↔ flat index, first axis slowest
    let coords = |k: usize| {
        let mut c = [0i64; D];
        let mut rest = k;
        for ax in (0..D).rev() {
            c[ax] = (rest % side) as i64 + lo;
            rest /= side;
        }
        c
    };
    let flat = |c: [i64; D]| {
        let mut k = 0usize;
        for ax in 0..D {
            k = k * side + (c[ax] - lo) as usize;
        }
        k
    };
    let pos = |c: [i64; D]| c.map(|i| a + i as f64 * dx);
    let exact = |x: [f64; D]| {
        let mut f = 0.0;
        let mut grad = [0.0; D];
        let mut lap = 0.0;
        for ax in 0..D {
            let [v, d1, d2] = cfg.function.eval(x[ax], mid, dx);
            f += v;
            grad[ax] = d1;
            lap += d2;
        }
        (f, grad, lap)
    };
    // the lattice sum over a full cover, and the volumes
    let span0 = (2 * reach + 1) as usize;
    let mut lattice_sum = 0.0;
    for m in 0..span0.pow(D as u32) {
        let mut d = [0.0; D];
        let mut rest = m;
        for ax in 0..D {
            d[ax] = ((rest % span0) as i64 - reach) as f64 * dx;
            rest /= span0;
        }
        lattice_sum += kp.w_and_grad::<f64, D>(d).0;
    }
    lattice_sum *= dx.powi(D as i32);
    let vol = match cfg.normalisation {
        Normalisation::Continuum => dx.powi(D as i32),
        Normalisation::Lattice => dx.powi(D as i32) / lattice_sum,
    };
    let fvals: Vec<f64> = (0..count).map(|k| exact(pos(coords(k))).0).collect();
    // how far (in spacings) a lattice index lies outside the interval
    let outside = |c: [i64; D]| {
        c.iter()
            .map(|&i| (-i).max(i - (n as i64 - 1)).max(0))
            .max()
            .unwrap_or(0)
    };
    // (φ_J, ∇φ_J) at particle c over its neighbours that exist in the set
    let stencil = |c: [i64; D]| -> Result<Stencil<D>> {
        let xi = pos(c);
        let mut idx = Vec::new();
        let mut nodes = Vec::new();
        let span = (2 * reach + 1) as usize;
        for m in 0..span.pow(D as u32) {
            let mut cj = c;
            let mut rest = m;
            for ax in 0..D {
                cj[ax] += (rest % span) as i64 - reach;
                rest /= span;
            }
            if cj.iter().any(|&i| i < lo || i > hi) {
                continue;
            }
            let xj = pos(cj);
            let mut d = [0.0; D];
            let mut r2 = 0.0;
            for ax in 0..D {
                d[ax] = xj[ax] - xi[ax];
                r2 += d[ax] * d[ax];
            }
            if r2 >= r * r {
                continue;
            }
            idx.push(flat(cj));
            nodes.push((d, vol));
        }
        let mut out = Vec::with_capacity(nodes.len());
        eval_d(cfg.shape, kp, &nodes, xi[0], &mut out)?;
        Ok((idx, out))
    };
    // first pass: ⟨f⟩ and ⟨∇f⟩ at the interval's particles and, with ghosts, at every particle
    // within R of it
    let first_reach = if cfg.ghosts { reach } else { 0 };
    let first: Vec<Option<(f64, [f64; D])>> = (0..count)
        .into_par_iter()
        .map(|k| {
            let c = coords(k);
            if outside(c) > first_reach {
                return Ok(None);
            }
            let (idx, sh) = stencil(c)?;
            let mut f = 0.0;
            let mut grad = [0.0; D];
            for (&j, (phi, dphi)) in idx.iter().zip(&sh) {
                f += phi * fvals[j];
                for ax in 0..D {
                    grad[ax] += dphi[ax] * fvals[j];
                }
            }
            Ok(Some((f, grad)))
        })
        .collect::<Result<_>>()?;
    // second pass at the interval's particles: the divergence of the computed gradient over the
    // particles that have one
    let interval: Vec<usize> = (0..count).filter(|&k| outside(coords(k)) == 0).collect();
    let lap: Vec<f64> = interval
        .par_iter()
        .map(|&k| {
            let (idx, sh) = stencil(coords(k))?;
            let mut l = 0.0;
            for (&j, (_, dphi)) in idx.iter().zip(&sh) {
                if let Some((_, gj)) = first[j] {
                    for ax in 0..D {
                        l += dphi[ax] * gj[ax];
                    }
                }
            }
            Ok(l)
        })
        .collect::<Result<_>>()?;
    let mut rep = InterpolationReport {
        dim: D,
        function: cfg.function.name(),
        edge_width: match cfg.function {
            TestFunction::Edge { width } => Some(width),
            _ => None,
        },
        interval: [a, b],
        particles: n,
        spacing: dx,
        kernel: cfg.kernel.name(),
        h_over_dx: cfg.h_over_dx,
        support_over_dx: cfg.kernel.zeta() * cfg.h_over_dx,
        shape: cfg.shape.name(),
        ghosts: cfg.ghosts,
        normalisation: cfg.normalisation.name(),
        lattice_sum,
        value: norms::<1>(&[], &[], &[]),
        value_at_start: None,
        gradient: None,
        laplacian: None,
        gradient_peak_width: None,
        gradient_integral: None,
        position: Vec::with_capacity(interval.len()),
        f: Vec::with_capacity(interval.len()),
        f_approx: Vec::with_capacity(interval.len()),
        gradient_x: Vec::with_capacity(interval.len()),
        gradient_x_approx: Vec::with_capacity(interval.len()),
        laplacian_exact: Vec::with_capacity(interval.len()),
        laplacian_approx: lap,
    };
    let (mut fe, mut fa, mut ge, mut ga, mut le, mut nb) =
        (vec![], vec![], vec![], vec![], vec![], vec![]);
    for &k in &interval {
        let c = coords(k);
        let x = pos(c);
        let (f, grad, l) = exact(x);
        let (f_h, g_h) = first[k].expect("every particle of the interval has a first pass");
        // within one support radius of the boundary: fewer than a full cover without ghosts
        let near = c
            .iter()
            .any(|&i| (i as f64) * dx < r || ((n as i64 - 1 - i) as f64) * dx < r);
        rep.position.push(x[0]);
        rep.f.push(f);
        rep.f_approx.push(f_h);
        rep.gradient_x.push(grad[0]);
        rep.gradient_x_approx.push(g_h[0]);
        rep.laplacian_exact.push(l);
        fe.push([f]);
        fa.push([f_h]);
        ge.push(grad);
        ga.push(g_h);
        le.push([l]);
        nb.push(near);
    }
    rep.value = norms(&fe, &fa, &nb);
    let f0 = rep.f[0];
    if f0 != 0.0 {
        rep.value_at_start = Some((rep.f_approx[0] - f0).abs() / f0.abs());
    }
    if cfg.function.smooth_gradient() {
        rep.gradient = Some(norms(&ge, &ga, &nb));
    }
    if cfg.function.smooth_second() {
        let la: Vec<[f64; 1]> = rep.laplacian_approx.iter().map(|&l| [l]).collect();
        rep.laplacian = Some(norms(&le, &la, &nb));
    }
    if D == 1 && matches!(cfg.function, TestFunction::Edge { .. } | TestFunction::Step) {
        let gx = &rep.gradient_x_approx;
        rep.gradient_integral = Some(gx.iter().sum::<f64>() * dx);
        rep.gradient_peak_width = Some(half_max_width(gx));
    }
    if !rep.value.max.is_finite() {
        return Err(Error::Incompatible(
            field("h_over_dx")
                + " gives a non-finite interpolation (the cover holds too few particles)",
        ));
    }
    Ok(rep)
}

/// Full width at half maximum of |g|'s highest peak, in samples: the distance between the
/// half-maximum crossings on both flanks, each interpolated linearly between samples (a flank
/// that reaches the end of the samples ends there).
fn half_max_width(g: &[f64]) -> f64 {
    let a: Vec<f64> = g.iter().map(|v| v.abs()).collect();
    let (imax, &peak) = a
        .iter()
        .enumerate()
        .fold((0, &0.0), |m, (i, v)| if *v > *m.1 { (i, v) } else { m });
    if peak == 0.0 {
        return 0.0;
    }
    let half = 0.5 * peak;
    let mut left = 0.0;
    let mut i = imax;
    while i > 0 && a[i - 1] >= half {
        i -= 1;
    }
    if i > 0 {
        left = (i - 1) as f64 + (half - a[i - 1]) / (a[i] - a[i - 1]);
    }
    let mut j = imax;
    while j + 1 < a.len() && a[j + 1] >= half {
        j += 1;
    }
    let right = if j + 1 < a.len() {
        j as f64 + (a[j] - half) / (a[j] - a[j + 1])
    } else {
        (a.len() - 1) as f64
    };
    right - left
}
