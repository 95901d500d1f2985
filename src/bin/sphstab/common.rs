//! Flags shared by `query`, `dispersion` and `timestep`.

use anyhow::Result;
use sphstab::analysis::Query1D;
use sphstab::forms::FormKind;
use sphstab::kernel;
use sphstab::shape::ShapeFamily;

/// Configuration flags.
#[derive(clap::Args, Debug, Clone)]
pub struct Config {
    /// SPH form: classical, nonlocal, local, lnl, cll, total-lagrangian, eulerian-stress-points,
    /// lagrangian-stress-points, least-squares, eulerian-nodal.
    #[arg(long, default_value = "classical")]
    pub form: String,
    /// Kernel: m4 m5 m6 wendland-c2 wendland-c4 wendland-c6 gaussian lucy efg-cubic efg-quartic mollifier.
    #[arg(long, default_value = "m4")]
    pub kernel: String,
    /// Smoothing length h/Δx in the kernel's own convention (default 1.2 unless --support is given).
    #[arg(long, conflicts_with = "support", allow_hyphen_values = true)]
    pub h: Option<f64>,
    /// Support radius R/Δx = ζ h/Δx (Belytschko's dilation D_mx); alternative to --h.
    #[arg(long, allow_hyphen_values = true)]
    pub support: Option<f64>,
    /// Shape family: sph, shepard, mls, corrected. Default: sph for classical/nonlocal/lnl/cll,
    /// corrected for local, mls (EFG, as in Belytschko et al. 2000) for total-lagrangian, the
    /// stress-point forms, least-squares and eulerian-nodal.
    #[arg(long)]
    pub shape: Option<String>,
    /// Pre-stress σ̄ = σ/C, positive in tension, in [-10, 10].
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub stress: f64,
    /// Partition coefficient c ∈ [0, 1] of lnl/cll (c = 1: fully local).
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub c: f64,
    /// Least-squares stabilisation α_s ≥ 0 (β = α_s Δx²).
    #[arg(long = "alpha-s", default_value_t = 0.0, allow_hyphen_values = true)]
    pub alpha_s: f64,
    /// Time step Δt in Δx/c (> 0) for the fully discrete (leapfrog) check.
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Monaghan artificial viscosity α (linearised), ≥ 0.
    #[arg(long = "av-alpha", allow_hyphen_values = true)]
    pub av_alpha: Option<f64>,
    /// Monaghan artificial viscosity β (vanishes in the linearisation), ≥ 0.
    #[arg(long = "av-beta", allow_hyphen_values = true)]
    pub av_beta: Option<f64>,
}

impl Config {
    /// Builds and validates the library query.
    pub fn query(&self, points: usize) -> Result<Query1D> {
        let form = FormKind::by_name(&self.form)?;
        let k = kernel::by_name(&self.kernel)?;
        let h = match (self.h, self.support) {
            (Some(h), _) => h,
            (None, Some(r)) => {
                sphstab::error::check_range("--support", r, 0.0, f64::INFINITY, false, false)?;
                r / k.zeta()
            }
            (None, None) => 1.2,
        };
        let mut q = Query1D::new(form, k, h, self.stress);
        if let Some(s) = &self.shape {
            q.shape = ShapeFamily::by_name(s)?;
        }
        q.c_partition = self.c;
        q.alpha_s = self.alpha_s;
        q.dt = self.dt;
        q.points = points;
        if self.av_alpha.is_some() || self.av_beta.is_some() {
            q.av = Some((self.av_alpha.unwrap_or(0.0), self.av_beta.unwrap_or(0.0)));
        }
        q.validate()?;
        Ok(q)
    }
}
