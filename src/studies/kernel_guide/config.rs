//! The kernel guide's settings: which kernels, the h/Δx step of its scans, and the fixed
//! parameters of every column.

use crate::error::{Error, Result, field};
use crate::kernel::{self, Kernel};
use crate::studies::config::no_duplicates;
use crate::studies::pairing::wstar;

/// Forms of the time-step columns.
pub const GUIDE_FORMS: [&str; 2] = ["classical", "total-lagrangian"];
/// h/Δx of the time-step and tension columns.
pub const GUIDE_H: [f64; 2] = [1.3, 2.0];
/// Points per wavelength of the phase-error columns.
pub const PPW: [f64; 2] = [10.0, 20.0];
/// Δt of the phase-error columns, as a fraction of the critical Δt.
pub const SAFETY: f64 = 0.9;
/// The h/Δx interval of the compression scans.
pub const SCAN_H: (f64, f64) = (0.8, 6.0);
/// Default step of the compression scans (`h_step`).
pub const DEFAULT_H_STEP: f64 = 0.05;
/// Allowed `h_step`.
pub const H_STEP_RANGE: (f64, f64) = (0.01, 1.0);
/// Pre-stress of the compression scans (pressure 0.01 C, as the trade-off study's
/// `stable_in_compression` and one of the pairing study's stresses).
pub const COMPRESSION: f64 = -0.01;
/// κ points in (0, π] of the 1D scans.
pub const KAPPAS_1D: usize = 256;
/// Wave vectors per direction of the 2D scan (16² − 1, the trade-off study's 2D grid).
pub const GRID_2D: usize = 16;
/// Largest support R/Δx of the 2D scan (the bound the engine's patch, ~R⁴ work per h, once
/// set; the closed form would go further at little cost, but the column is defined on this range).
pub const MAX_SUPPORT_2D: f64 = 6.0;
/// Largest tension of the onset scan.
pub const TENSION_CAP: f64 = 0.999;
/// Tension below the scan: growth already here means growth for any tension (the tensile
/// growth rate vanishes like √σ̄, so it is still ~1e-4 c/Δx ≫ [`GROWTH_TOL`](crate::vonneumann::classify::GROWTH_TOL) here).
pub const TENSION_FLOOR: f64 = 1e-8;
/// Bisection steps of the tensile onset (bracket = scan gap / 2³⁰).
pub const ONSET_BISECTIONS: usize = 30;
/// Upper end of the W* scan, κh (units 1/h).
pub const WSTAR_K_MAX: f64 = wstar::K_MAX;
/// Step of the W* scan (κh); twice the pairing study's [`wstar::K_STEP`] (the sign changes are
/// bisected to 1e-12 either way; the negative lobes are ≳ 1 wide in κh).
pub const WSTAR_K_STEP: f64 = 0.01;

/// What to compute.
#[derive(Clone, Debug)]
pub struct GuideConfig {
    /// Kernels (default: all).
    pub kernels: Vec<&'static dyn Kernel>,
    /// Step of the h/Δx scans.
    pub h_step: f64,
}

impl Default for GuideConfig {
    fn default() -> Self {
        Self {
            kernels: kernel::all().to_vec(),
            h_step: DEFAULT_H_STEP,
        }
    }
}

impl GuideConfig {
    /// Validates the step and the kernels (errors name the field).
    pub fn validate(&self) -> Result<()> {
        crate::error::check_range(
            "h_step",
            self.h_step,
            H_STEP_RANGE.0,
            H_STEP_RANGE.1,
            true,
            true,
        )?;
        if self.kernels.is_empty() {
            return Err(Error::Incompatible(
                field("kernels") + ": give at least one",
            ));
        }
        let names: Vec<&str> = self.kernels.iter().map(|k| k.name()).collect();
        no_duplicates("kernels", &names)
    }

    /// The h/Δx grid of the scans (rounded to 1e-10, so 0.8 + 3·0.05 is 0.95).
    pub fn h_grid(&self) -> Vec<f64> {
        let n = ((SCAN_H.1 - SCAN_H.0) / self.h_step + 1e-9).floor() as usize;
        (0..=n)
            .map(|i| ((SCAN_H.0 + i as f64 * self.h_step) * 1e10).round() / 1e10)
            .collect()
    }
}

/// The tension of [`TensileOnset::growth_at_reference`](super::TensileOnset::growth_at_reference).
pub const REFERENCE_TENSION: f64 = 0.01;
