//! The critical CFL table (`sphstab tradeoff --cfl-table`): c Δt_crit / h per integrator ×
//! kernel for `classical` and `total-lagrangian` at h/Δx = 1.2 and 2.0, σ̄ = 0, default shape
//! families, no viscosity, 1D. Every cell is the `timestep` code path
//! ([`IntegratorReport::of`]: bisection on the amplification matrices of the scheme over
//! [`CFL_POINTS`] κ points); weakly unstable schemes are shown as `weak` with their spurious growth
//! rate at Δt = 1/ω_max (c/Δx).

use crate::analysis::{IntegratorReport, Query};
use crate::error::Result;
use crate::forms::FormKind;
use crate::integrator::{DEFAULT_EULER_EVERY, Integrator};
use crate::kernel;
use crate::vonneumann::classify::GROWTH_TOL;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Forms of the table.
pub const CFL_FORMS: [&str; 2] = ["classical", "total-lagrangian"];
/// h/Δx of the table.
pub const CFL_H: [f64; 2] = [1.2, 2.0];
/// κ points in (0, π] of each cell (`timestep --points`).
pub const CFL_POINTS: usize = 256;

/// One cell.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct CflCell {
    /// Form.
    pub form: String,
    /// Shape family.
    pub shape: String,
    /// h/Δx.
    pub h_over_dx: f64,
    /// Kernel.
    pub kernel: String,
    /// Integrator.
    pub integrator: String,
    /// ω_max (c/Δx).
    pub omega_max: f64,
    /// Critical Δt (Δx/c); null when weak or the semi-discrete system grows.
    pub critical_dt: Option<f64>,
    /// c Δt_crit / h.
    pub critical_cfl: Option<f64>,
    /// Weak instability.
    pub weak: bool,
    /// Spurious growth rate at Δt = 1/ω_max (c/Δx); 0 unless weak.
    pub weak_growth_rate: f64,
}

/// The table.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct CflTable {
    /// σ̄ of every cell.
    pub stress: f64,
    /// κ points per cell.
    pub points: usize,
    /// N_s of `verlet-euler`.
    pub euler_every: usize,
    /// Cells, by form, h, integrator, kernel.
    pub cells: Vec<CflCell>,
}

/// One cell of the table.
pub fn cfl_cell(
    form: FormKind,
    k: &'static dyn kernel::Kernel,
    h: f64,
    integ: Integrator,
) -> Result<CflCell> {
    let mut q = Query::<1>::new(form, k, h, 0.0);
    q.grid = CFL_POINTS;
    let lin = q.chain()?;
    let ks = q.kappas();
    let mut grows = false;
    for &kap in &ks {
        grows |= lin.growth(kap)? > GROWTH_TOL;
    }
    let r = IntegratorReport::of(&lin, &ks, integ, None, h)?;
    // a system that grows at σ̄ = 0 has no cell (as before the limit was defined for growing
    // systems too)
    let (critical_dt, critical_cfl) = if grows {
        (None, None)
    } else {
        (r.critical_dt, r.critical_cfl)
    };
    Ok(CflCell {
        form: form.name().into(),
        shape: q.shape.name().into(),
        h_over_dx: h,
        kernel: k.name().into(),
        integrator: integ.name().into(),
        omega_max: r.omega_max,
        critical_dt,
        critical_cfl,
        weak: r.weak_instability,
        weak_growth_rate: r.spurious_growth_rate,
    })
}

/// The whole table (cells in parallel).
pub fn cfl_table() -> Result<CflTable> {
    let mut jobs = Vec::new();
    for f in CFL_FORMS {
        let form = FormKind::by_name(f)?;
        for h in CFL_H {
            for integ in Integrator::all(DEFAULT_EULER_EVERY) {
                for &k in kernel::all() {
                    jobs.push((form, k, h, integ));
                }
            }
        }
    }
    let cells = jobs
        .par_iter()
        .map(|&(f, k, h, i)| cfl_cell(f, k, h, i))
        .collect::<Result<Vec<_>>>()?;
    Ok(CflTable {
        stress: 0.0,
        points: CFL_POINTS,
        euler_every: DEFAULT_EULER_EVERY,
        cells,
    })
}

/// The table as Markdown: one block per form and h, integrators as rows, kernels as columns.
pub fn cfl_markdown(t: &CflTable) -> String {
    let kernels: Vec<&str> = kernel::all().iter().map(|k| k.name()).collect();
    let mut s = format!(
        "Critical CFL number c Δt_crit / h (h in the kernel's own convention), 1D, σ̄ = {}, no viscosity, \
default shape family, {} κ points in (0, π], verlet-euler with N_s = {}. \
`weak (γ)`: no Δt is stable (weak instability), γ = spurious growth rate at Δt = 1/ω_max in c/Δx.\n",
        t.stress, t.points, t.euler_every
    );
    for f in CFL_FORMS {
        for h in CFL_H {
            let cells: Vec<&CflCell> = t
                .cells
                .iter()
                .filter(|c| c.form == f && c.h_over_dx == h)
                .collect();
            let shape = cells.first().map_or("", |c| c.shape.as_str());
            s += &format!("\n**{f}** ({shape}), h = {h} Δx\n\n| integrator |");
            for k in &kernels {
                s += &format!(" {k} |");
            }
            s += "\n|---|";
            s += &"---:|".repeat(kernels.len());
            s += "\n";
            for name in crate::integrator::INTEGRATOR_NAMES {
                s += &format!("| {name} |");
                for k in &kernels {
                    let cell = cells
                        .iter()
                        .find(|c| c.integrator == name && c.kernel == *k);
                    let txt = match cell {
                        Some(c) => match (c.critical_cfl, c.weak) {
                            (Some(v), _) => format!("{v:.3}"),
                            (None, true) => format!("weak ({:.2e})", c.weak_growth_rate),
                            (None, false) => "grows".into(),
                        },
                        None => "-".into(),
                    };
                    s += &format!(" {txt} |");
                }
                s += "\n";
            }
        }
    }
    s
}
