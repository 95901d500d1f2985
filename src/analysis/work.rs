//! The work of a question, estimated before it starts and checked against the budget
//! ([`crate::budget::Budget::work`]), so that a question asking for hours (a 3D time step over
//! 128³ wave vectors, 10⁷ κ points through a bisection) is refused in milliseconds, naming the
//! fields that drive it.
//!
//! The unit is one row of a mode's matrix evaluated once: a pass over the modes costs, per
//! mode, n rows for an eigen-solve of its n × n system (the semi-discrete J, or the
//! amplification matrix of one step, extended by what the integrator carries between steps),
//! times the integrator's stages for the amplification; the 1D dispersion of a non-dissipative
//! form is tabulated, one row per κ. Measured here, a row costs ~1 µs (1D classical: n = 3,
//! ~3 µs per mode and pass; 3D elastic: n = 13, ~13 µs), the cost of a particle-step of the
//! solver, so the limit is `max_steps` itself (about a minute by default).
//!
//! Passes: a bisection on the amplification matrices (the critical Δt of a dissipative system
//! or of any integrator but kdk) is at most [`BISECTION_PASSES`] (a few doublings, then halving
//! to a relative gap of 1e-12), a spectrum or a curve is one, the fully discrete check at a Δt
//! is one.

use super::query::Query;
use crate::error::{Result, fields};
use crate::integrator::Integrator;
use crate::vonneumann::amplification::Modes;

/// Passes over the modes of one bisection for a critical Δt (doublings from the weak probe
/// 0.1/|s|_max to the limit, ≤ 10 for every integrator here, then ~40 halvings to 1e-12
/// relative, 60 at most; an unstable probe may stop early, which the estimate ignores).
pub const BISECTION_PASSES: f64 = 64.0;

/// What is asked of the modes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Question {
    /// `query`: the curve or zone, the critical Δt of the integrator, the check at `dt`.
    Query,
    /// `timestep`: the above and the integrator's critical Δt, its spurious growth, \[B00\] eq
    /// 120, again without viscosity when there is viscosity, and the query when it grows.
    Timestep,
    /// One critical Δt of the integrator ([`super::critical_dt_to`]).
    CriticalDt,
}

/// Rows-evaluations a mode costs per amplification pass with `integ` whose matrix has `rows`
/// rows: the stages of one step build it (kdk: two rate evaluations), a `verlet-euler` cycle
/// takes log₂ N_s matrix products more.
fn amplification_cost(integ: Integrator, rows: f64) -> f64 {
    let stages = match integ {
        Integrator::Rk4 => 4.0,
        Integrator::Dkd => 3.0,
        Integrator::VerletEuler { every } => 2.0 + (every as f64).log2(),
        _ => 2.0,
    };
    rows * stages / 2.0
}

/// Refuses `question` on `count` modes of `lin` when its estimated work (module docs) exceeds
/// the budget of `q`, before any of it is done (before the modes are even listed); `sample` is
/// any mode (the size of a mode's matrix does not depend on it).
pub(super) fn check<const D: usize, L: Modes>(
    q: &Query<D>,
    lin: &L,
    sample: L::K,
    count: usize,
    question: Question,
) -> Result<()> {
    let k0 = sample;
    let integ = q.integrator;
    let rows = lin.amplification_with(k0, 1.0, integ).nrows() as f64;
    let semi_rows = lin.amplification_with(k0, 1.0, Integrator::Kdk).nrows() as f64;
    let amp = amplification_cost(integ, rows);
    let dissipative = lin.is_dissipative();
    // one pass over the semi-discrete modes (the curve, the zone, a spectrum)
    let curve = if D == 1 && !dissipative {
        1.0
    } else {
        semi_rows
    };
    let query = curve
        + if integ != Integrator::Kdk {
            semi_rows + BISECTION_PASSES * amp
        } else if dissipative {
            BISECTION_PASSES * amplification_cost(Integrator::Kdk, semi_rows)
        } else {
            0.0
        }
        + if q.dt.is_some() { amp } else { 0.0 };
    let per_mode = match question {
        Question::Query => query,
        Question::CriticalDt => semi_rows + BISECTION_PASSES * amp,
        Question::Timestep => {
            let own = curve
                + (semi_rows + BISECTION_PASSES * amp)
                + (semi_rows + amp)
                + if dissipative {
                    BISECTION_PASSES * amplification_cost(Integrator::Kdk, semi_rows) + semi_rows
                } else {
                    0.0
                };
            own * if q.av.is_some() { 2.0 } else { 1.0 } + query
        }
    };
    let n = count as f64;
    let what = format!(
        "the {} ({} {}, {}, matrices of {} rows)",
        match question {
            Question::Query => "stability query",
            Question::Timestep => "time-step analysis",
            Question::CriticalDt => "critical time step",
        },
        crate::budget::fmt_count(n),
        if D == 1 { "κ points" } else { "wave vectors" },
        integ.name(),
        rows
    );
    let mut names: Vec<&'static str> = vec!["grid"];
    if integ != Integrator::Kdk {
        names.push("integrator");
    }
    if let Integrator::VerletEuler { .. } = integ {
        names.push("euler_every");
    }
    if q.dt.is_some() && question == Question::Query {
        names.push("dt");
    }
    q.budget.work(
        fields(&names),
        &what,
        n * per_mode,
        "matrix-row evaluations",
        q.budget.max_steps,
    )
}
