//! The fastest mode of a box of any size: thick-restart Arnoldi ([`fastest_mode`]) on the
//! matrix-free box operator ([`BoxOperator`]), within the run's budget. The same operator and
//! the same growth rate as the dense reference [`box_growth`](super::box_growth), without
//! forming the matrix: memory O(basis × dofs), time O(products × particles).

use super::arnoldi::{ArnoldiParams, fastest_mode};
use super::product::BoxOperator;
use crate::budget::{Budget, fmt_count};
use crate::error::{Error, Result, Text, field, fields};
use crate::progress::Progress;
use crate::solver::run::Run;
use num_complex::Complex64;

/// Basis size of the restarted Arnoldi method (products between restarts). The number of
/// products hardly depends on it (a 17³ box: 648, 632, 620, 608 products with bases of 80,
/// 120, 200, 300): the spectrum, not the restarts, sets it.
pub const BASIS: usize = 120;

/// Ritz vectors kept at a restart.
pub const KEEP: usize = 40;

/// Relative accuracy of ω²: the residual ‖D u − θ u‖ of the fastest Ritz pair must be at most
/// `RTOL` |θ| (or [`ATOL`] ‖D‖ near zero).
pub const RTOL: f64 = 1e-8;

/// Absolute accuracy of ω² relative to ‖D‖ (the largest |ω²|): a tenth of the zero-mode
/// threshold [`ZERO_OMEGA2_TOL`](crate::vonneumann::classify::ZERO_OMEGA2_TOL).
pub const ATOL: f64 = 1e-11;

/// Products after which the method gives up whatever the budget allows.
pub const MAX_PRODUCTS: usize = 20_000;

/// Products after which a fastest Ritz value that does not grow ends the search
/// ([`box_growth_iterative`] returns None). The growing modes of tension show a negative Ritz
/// value within the first Rayleigh–Ritz step (8 products); a box without them has its fastest
/// modes in the cluster of zero-energy modes at ω² ≈ 0 (nonlocal 12³: 72 eigenvalues below
/// 1e-6 (c/Δx)², ‖D‖ ≈ 0.7), which a Krylov method resolves only in tens of thousands of
/// products.
pub const STABLE_PROBE: usize = 64;

/// Rate evaluations per product, each counted as one particle-step against the budget's
/// `max_steps` (a solver step evaluates the rate once or twice).
const EVALUATIONS_PER_PRODUCT: f64 = 2.0;

/// Where the Krylov space starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// A fixed pseudo-random vector: every mode is in it, so the result is the box's fastest
    /// mode.
    Generic,
    /// The run's own initial velocities of the free particles: the solution of the linear
    /// system started from them stays in this Krylov space, so the result is the fastest
    /// mode that initial condition excites (none of the modes it is orthogonal to, e.g. by
    /// symmetry).
    Velocity,
}

/// The fastest mode of a box and how it was found.
#[derive(Clone, Debug)]
pub struct IterativeGrowth {
    /// Growth rate max Re √(−ω²) (1/time, physical; 0 when ω² is within
    /// [`ZERO_OMEGA2_TOL`](crate::vonneumann::classify::ZERO_OMEGA2_TOL) of zero or the mode
    /// oscillates).
    pub rate: f64,
    /// Its ω² (1/time², physical).
    pub omega2: Complex64,
    /// Free mechanical degrees of freedom (D × free particles).
    pub dofs: usize,
    /// Products of the operator with a vector (two rate evaluations each).
    pub products: usize,
    /// Restarts of the Arnoldi method.
    pub restarts: usize,
    /// ‖D u − θ u‖ / ‖D‖ of the returned pair (u of unit norm).
    pub residual: f64,
    /// Whether D was symmetric on the Krylov space (Lanczos), not general (Arnoldi).
    pub symmetric: bool,
    /// The mode: displacements of the free particles (D per particle, in index order), unit
    /// norm.
    pub mode: Vec<f64>,
}

/// The fastest mode of the finite particle set of `run` (the box operator about its current
/// rest state, boundary mask applied), from `start`, within `budget`: memory for the basis,
/// and products × particles × 2 rate evaluations within `max_steps`; at most `max_products`
/// products if given ([`MAX_PRODUCTS`] otherwise), [`Error::NotConverged`] beyond them.
/// `progress` is asked whether to stop between products. None: no growing mode after [`STABLE_PROBE`] products,
/// the fastest ones in the cluster at ω² ≈ 0 (not resolved: the box may be stable or grow
/// slower than the method can show). Errors: a budget or convergence failure (never a silent
/// unconverged value), artificial viscosity or density diffusion (not the undamped operator).
pub fn box_growth_iterative<const D: usize>(
    run: &Run<D>,
    start: Start,
    max_products: Option<usize>,
    budget: &Budget,
    progress: &dyn Progress,
) -> Result<Option<IterativeGrowth>> {
    let mut op = BoxOperator::new(run)?;
    let n = op.dofs();
    let particles = run.z.x.len() as f64;
    // the basis and its products, and two dual-number states and workspaces (~1 kB/particle)
    let bytes = (2 * BASIS + 2) as f64 * n as f64 * 8.0 + 2.0 * 1000.0 * particles;
    budget.memory(
        fields(&["size"]),
        &format!(
            "the box operator's Krylov basis ({BASIS} vectors of {n} degrees of freedom, twice)"
        ),
        bytes,
    )?;
    let by_budget = (budget.max_steps / (EVALUATIONS_PER_PRODUCT * particles)).floor();
    let by_budget = by_budget.max(0.0) as usize;
    let asked = max_products.unwrap_or(MAX_PRODUCTS).min(MAX_PRODUCTS);
    if by_budget < BASIS.min(n).min(asked) {
        return Err(budget_error(budget, n, by_budget, particles));
    }
    let max_products = asked.min(by_budget);
    let start_vector: Vec<f64> = match start {
        Start::Generic => super::arnoldi::pseudo_random(n, 0x5eed),
        Start::Velocity => op.free_velocities(),
    };
    let params = ArnoldiParams {
        basis: BASIS,
        keep: KEEP,
        rtol: RTOL,
        atol: ATOL,
        max_products,
        stable_after: Some(STABLE_PROBE),
        zero: crate::vonneumann::classify::ZERO_OMEGA2_TOL,
    };
    let found = fastest_mode(n, &start_vector, params, |u, y| {
        if progress.cancelled() {
            return Err(Error::Cancelled);
        }
        op.apply(u, y)
    });
    let m = match found {
        Err(Error::NotConverged { .. }) if max_products < asked => {
            return Err(budget_error(budget, n, max_products, particles));
        }
        other => other?,
    };
    if !m.converged {
        return Ok(None);
    }
    let zero = crate::vonneumann::classify::ZERO_OMEGA2_TOL * m.norm;
    let rate = if m.omega2.norm() > zero {
        (-m.omega2).sqrt().re.max(0.0)
    } else {
        0.0
    };
    Ok(Some(IterativeGrowth {
        rate,
        omega2: m.omega2,
        dofs: n,
        products: m.products,
        restarts: m.restarts,
        residual: m.residual / m.norm.max(f64::MIN_POSITIVE),
        symmetric: m.symmetric,
        mode: m.vector,
    }))
}

/// The eigenvalue search needs more products than `max_steps` allows.
fn budget_error(budget: &Budget, n: usize, products: usize, particles: f64) -> Error {
    Error::Budget {
        fields: fields(&["size"]),
        what: format!(
            "the box operator's fastest mode ({n} degrees of freedom; not found in {products} products of 2 rate evaluations)"
        ),
        estimate: format!(
            "more than {} particle-steps",
            fmt_count(EVALUATIONS_PER_PRODUCT * particles * products as f64)
        ),
        limit: Text::from(format!("{} particle-steps (", fmt_count(budget.max_steps)))
            + field("max_steps")
            + ")",
    }
}
