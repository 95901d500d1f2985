//! Validation of the parameters every question and run shares (h/Δx, σ̄, c, artificial
//! viscosity, Δt) and of integer counts: one path for the library API, the command line, scene
//! files and configs. Errors name the caller's field ([`ParamNames`]); the binary maps fields
//! to flags.

use crate::error::{Error, Result, check_range, field};
use crate::kernel::Kernel;

/// Allowed range of h/Δx.
pub const H_RANGE: (f64, f64) = (0.05, 50.0);
/// Allowed range of σ̄.
pub const STRESS_RANGE: (f64, f64) = (-10.0, 10.0);

/// The fields that hold the common parameters in the caller's struct or file (errors name
/// them).
#[derive(Clone, Copy, Debug)]
pub struct ParamNames {
    /// h/Δx.
    pub h: &'static str,
    /// σ̄.
    pub stress: &'static str,
    /// Partition coefficient.
    pub c: &'static str,
    /// Viscosity α.
    pub av_alpha: &'static str,
    /// Viscosity β.
    pub av_beta: &'static str,
    /// Δt.
    pub dt: &'static str,
}

impl ParamNames {
    /// The fields of the questions ([`crate::analysis::Query`]).
    pub const QUERY: ParamNames = ParamNames {
        h: "h_over_dx",
        stress: "stress",
        c: "c_partition",
        av_alpha: "av_alpha",
        av_beta: "av_beta",
        dt: "dt",
    };
}

/// Validates the parameters shared by every question and run, naming them as the questions'
/// fields ([`ParamNames::QUERY`]).
pub fn check_common(
    kernel: &'static dyn Kernel,
    h: f64,
    stress: f64,
    c: f64,
    av: Option<(f64, f64)>,
    dt: Option<f64>,
) -> Result<()> {
    check_common_named(&ParamNames::QUERY, kernel, h, stress, c, av, dt)
}

/// [`check_common`] with the field names of the caller (e.g. scene fields).
pub fn check_common_named(
    names: &ParamNames,
    kernel: &'static dyn Kernel,
    h: f64,
    stress: f64,
    c: f64,
    av: Option<(f64, f64)>,
    dt: Option<f64>,
) -> Result<()> {
    check_range(names.h, h, H_RANGE.0, H_RANGE.1, true, true)?;
    check_range(
        names.stress,
        stress,
        STRESS_RANGE.0,
        STRESS_RANGE.1,
        true,
        true,
    )?;
    check_range(names.c, c, 0.0, 1.0, true, true)?;
    if let Some((a, b)) = av {
        check_range(names.av_alpha, a, 0.0, 100.0, true, true)?;
        check_range(names.av_beta, b, 0.0, 100.0, true, true)?;
    }
    if let Some(dt) = dt {
        check_range(names.dt, dt, 0.0, 1e6, false, true)?;
    }
    if kernel.zeta() * h <= 1.0 {
        return Err(Error::OutOfRange {
            field: names.h,
            value: h,
            range: format!(
                "the support ζh must exceed Δx so that particles have neighbours: h/Δx > {} for {} (ζ = {})",
                1.0 / kernel.zeta(),
                kernel.name(),
                kernel.zeta()
            )
            .into(),
        });
    }
    Ok(())
}

/// `Err(OutOfRange)` naming `field` unless `lo ≤ n ≤ hi`.
pub fn check_count(field: &'static str, n: usize, lo: usize, hi: usize) -> Result<()> {
    if (lo..=hi).contains(&n) {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            field,
            value: n as f64,
            range: format!("must be an integer in [{lo}, {hi}]").into(),
        })
    }
}

/// Refuses artificial stress (the field `art_eps`) in `dim` 3: it is implemented in 2D only.
pub fn check_art_stress_dim(dim: usize, art_stress: bool) -> Result<()> {
    if dim == 3 && art_stress {
        return Err(Error::Incompatible(
            field("art_eps") + " (artificial stress) is available with " + field("dim") + " 2 only",
        ));
    }
    Ok(())
}
