//! The atlas's config (the flags of `sphstab atlas`): forms, kernels, the h/Δx × σ̄ grid and
//! the κ points, checked field by field, and the sweep of cells it gives.

use crate::budget::{Budget, fmt_count};
use crate::error::{Error, Result, fields};
use crate::forms::FormKind;
use crate::kernel::{self, Kernel};
use serde::{Deserialize, Serialize};

/// The sweep.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AtlasConfig {
    /// Form names (all ten by default).
    pub forms: Vec<String>,
    /// Kernel names (all eleven by default).
    pub kernels: Vec<String>,
    /// h/Δx values per kernel, evenly over its customary range.
    pub h_points: usize,
    /// σ̄ values, evenly over `stress_range` (ends included).
    pub stress_points: usize,
    /// σ̄ range.
    pub stress_range: (f64, f64),
    /// κΔx points in (0, π].
    pub kappas: usize,
    /// The budget the sweep must stay within (not part of the report).
    #[serde(skip)]
    pub budget: Budget,
}

impl Default for AtlasConfig {
    fn default() -> Self {
        Self {
            // the 1D atlas: every form a bar has (not the solid-shear forms of D ≥ 2)
            forms: FormKind::ALL
                .iter()
                .filter(|f| !f.0.needs_2d())
                .map(|f| f.1.to_string())
                .collect(),
            kernels: kernel::all().iter().map(|k| k.name().to_string()).collect(),
            h_points: 64,
            stress_points: 64,
            stress_range: (-0.5, 0.5),
            kappas: 512,
            budget: Budget::default(),
        }
    }
}

/// One cell's parameters: (form, kernel, h/Δx, σ̄).
pub type CellSpec = (FormKind, &'static dyn Kernel, f64, f64);

/// The sweep of a config, validated field by field and within its budget: cell `i` in the order
/// form, kernel, h/Δx, σ̄ (σ̄ innermost), computed from its index alone.
pub struct Sweep {
    forms: Vec<FormKind>,
    kernels: Vec<&'static dyn Kernel>,
    h_points: usize,
    stress_points: usize,
    stress_range: (f64, f64),
}

/// `n` points evenly over [lo, hi] (ends included; one point: the middle), point `i`.
fn lin(lo: f64, hi: f64, n: usize, i: usize) -> f64 {
    if n == 1 {
        0.5 * (lo + hi)
    } else {
        lo + (hi - lo) * i as f64 / (n - 1) as f64
    }
}

impl Sweep {
    /// The sweep of `cfg`: its ranges, names and resources checked (errors name the field).
    pub fn new(cfg: &AtlasConfig) -> Result<Self> {
        for (field, v, lo, hi) in [
            ("h_points", cfg.h_points, 1, 4096),
            ("stress_points", cfg.stress_points, 1, 4096),
            ("kappas", cfg.kappas, 2, 1_000_000),
        ] {
            if v < lo || v > hi {
                return Err(Error::OutOfRange {
                    field,
                    value: v as f64,
                    range: format!("must be an integer in [{lo}, {hi}]").into(),
                });
            }
        }
        let (s0, s1) = cfg.stress_range;
        crate::error::check_range("stress_range[0]", s0, -0.999, 10.0, true, true)?;
        crate::error::check_range("stress_range[1]", s1, s0, 10.0, true, true)?;
        let forms: Vec<FormKind> = cfg
            .forms
            .iter()
            .map(|f| FormKind::by_name(f))
            .collect::<Result<_>>()?;
        let kernels: Vec<&'static dyn Kernel> = cfg
            .kernels
            .iter()
            .map(|k| kernel::by_name(k))
            .collect::<Result<_>>()?;
        // resources before the sweep starts (the budget): the cell list, results and their JSON
        // text (~400 B per cell), and the κ-evaluations, which cost ~0.3 µs each on 2 threads
        // (66 s for the full 450,560 × 512 atlas) and are checked against 10 × max_steps
        let cells =
            (forms.len() * kernels.len()) as f64 * (cfg.h_points * cfg.stress_points) as f64;
        let b = &cfg.budget;
        b.memory(
            fields(&["h_points", "stress_points"]),
            &format!("the atlas ({} cells)", fmt_count(cells)),
            cells * 400.0 + 64.0 * cfg.kappas as f64 * 16.0,
        )?;
        let evals = cells * cfg.kappas as f64;
        b.work(
            fields(&["h_points", "stress_points", "kappas"]),
            &format!("the atlas ({} cells)", fmt_count(cells)),
            evals,
            "κ-evaluations",
            10.0 * b.max_steps,
        )?;
        Ok(Self {
            forms,
            kernels,
            h_points: cfg.h_points,
            stress_points: cfg.stress_points,
            stress_range: cfg.stress_range,
        })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.forms.len() * self.kernels.len() * self.h_points * self.stress_points
    }

    /// Whether the sweep has no cells (no forms or no kernels).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// σ̄ value `i` of the σ̄ grid (the same for every form, kernel and h).
    pub fn stress(&self, i: usize) -> f64 {
        let (s0, s1) = self.stress_range;
        lin(s0, s1, self.stress_points, i)
    }

    /// Cell `i` (< [`Sweep::len`]): i = ((form · kernels + kernel) · h_points + h) ·
    /// stress_points + σ̄.
    pub fn cell(&self, i: usize) -> CellSpec {
        let (ns, nh, nk) = (self.stress_points, self.h_points, self.kernels.len());
        let k = self.kernels[i / (ns * nh) % nk];
        let (hlo, hhi) = k.customary_h();
        (
            self.forms[i / (ns * nh * nk)],
            k,
            lin(hlo, hhi, nh, i / ns % nh),
            self.stress(i % ns),
        )
    }
}
