//! Flags shared by `query`, `dispersion` and `timestep`.

use anyhow::Result;
use sphstab::analysis::Query;
use sphstab::budget::Budget;

/// Configuration flags.
#[derive(clap::Args, Debug, Clone)]
pub struct Config {
    /// SPH form: classical, nonlocal, local, lnl, cll, total-lagrangian, eulerian-stress-points,
    /// lagrangian-stress-points, least-squares, eulerian-nodal; 2D/3D solids also enog
    /// (SPH-ENOG) and tl-enog (total-Lagrangian with a pairwise shear term).
    #[arg(long, default_value = "classical")]
    pub form: String,
    /// Kernel: m4 m5 m6 wendland-c2 wendland-c4 wendland-c6 gaussian lucy efg-cubic efg-quartic mollifier.
    #[arg(long, default_value = "m4")]
    pub kernel: String,
    /// Smoothing length h/Δx in the kernel's own convention, in [0.05, 50] with support ζh > Δx
    /// (default 1.2 unless --support is given).
    #[arg(long, conflicts_with = "support", allow_hyphen_values = true)]
    pub h: Option<f64>,
    /// Support radius R/Δx = ζ h/Δx (Belytschko's dilation D_mx), > 1; alternative to --h.
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
    /// 2D/3D: the pre-stress's shape, σ = σ̄ C Ŝ: isotropic (default, Ŝ = I), uniaxial
    /// (Ŝ = e_x ⊗ e_x) or shear (Ŝ = e_x ⊗ e_y + e_y ⊗ e_x); uniaxial and shear need the
    /// elastic material.
    #[arg(long)]
    pub prestress: Option<String>,
    /// Partition coefficient c ∈ [0, 1] of lnl/cll (c = 1: fully local; default 0.5).
    #[arg(long, allow_hyphen_values = true)]
    pub c: Option<f64>,
    /// Least-squares stabilisation α_s of the least-squares form, dimensionless (β = α_s Δx²),
    /// in [0, 100] (default 0).
    #[arg(long = "alpha-s", allow_hyphen_values = true)]
    pub alpha_s: Option<f64>,
    /// Hourglass-control coefficient, in [0, 1000]: ζ of the enog shear acceleration (default
    /// 0.7D + 2.1), κ of the tl-enog pairwise shear (default 1.07), or Ganzenmüller's α with
    /// total-lagrangian (default: none, no hourglass control; 2D/3D).
    #[arg(long, allow_hyphen_values = true)]
    pub hourglass: Option<f64>,
    /// Time step Δt in Δx/c, in (0, 1e6], for the fully discrete check with --integrator
    /// (default kdk); the CFL number is c Δt/h = dt/(h/Δx).
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Monaghan artificial viscosity α (linearised), dimensionless, in [0, 100].
    #[arg(long = "av-alpha", allow_hyphen_values = true)]
    pub av_alpha: Option<f64>,
    /// Monaghan artificial viscosity β, dimensionless, in [0, 100]: it multiplies the squared
    /// velocity divergence, which vanishes in the linearisation, so only `timestep --verify`
    /// (the solver) uses it.
    #[arg(long = "av-beta", allow_hyphen_values = true)]
    pub av_beta: Option<f64>,
    /// Dimension: 1 (plane wave in a bar, default), 2 (in-plane Bloch analysis of a lattice) or
    /// 3 (Bloch analysis of a 3D lattice).
    #[arg(long)]
    pub dim: Option<u8>,
    /// Lattice: 2D square (default) or hex; 3D sc (default), bcc or fcc (Δx = (volume per
    /// particle)^⅓).
    #[arg(long)]
    pub lattice: Option<String>,
    /// 2D square lattice aspect ratio γ = Δy/Δx, in [0.1, 10] (default 1; square lattice only).
    #[arg(long, allow_hyphen_values = true)]
    pub gamma: Option<f64>,
    /// 2D/3D material: hydro (p = K(ρ/ρ0 − 1), G = 0, σ̄ = 1 − ρ/ρ0), elastic, or neo-hookean
    /// (total-lagrangian only, unstressed reference). Default elastic.
    #[arg(long)]
    pub material: Option<String>,
    /// 2D/3D elastic Poisson ratio ν (plane strain in 2D), in [−0.99, 0.5) (default 0.3).
    #[arg(long, allow_hyphen_values = true)]
    pub poisson: Option<f64>,
    /// 2D/3D elastic objective stress rate: jaumann (default) or truesdell (the 1D law).
    #[arg(long)]
    pub rate: Option<String>,
    /// 2D classical/cll: Monaghan–Gray artificial stress ε, dimensionless, in [0, 10] (typical
    /// 0.2–0.3).
    #[arg(long = "art-eps", allow_hyphen_values = true)]
    pub art_eps: Option<f64>,
    /// Artificial-stress exponent n of f = W(r)/W(Δx), in [1, 12] (default 4; needs --art-eps).
    #[arg(long = "art-n")]
    pub art_n: Option<i32>,
    /// δ-SPH density diffusion.
    #[command(flatten)]
    pub diffusion: DiffusionArgs,
    /// Wave-vector sampling: 1D, κ points in (0, π] (default 512, same as --points); 2D/3D, wave
    /// vectors per reciprocal direction (the zone is sampled grid^D), 2D in [2, 1024] (default
    /// 64), 3D in [2, 128] (default 16). (`dispersion` samples its path with --points.)
    #[arg(long)]
    pub grid: Option<usize>,
}

impl Config {
    /// The question by name ([`sphstab::analysis::QuerySpec`]): the one translation of these
    /// flags, shared with the Python module.
    pub fn spec(&self) -> sphstab::analysis::QuerySpec {
        sphstab::analysis::QuerySpec {
            form: Some(self.form.clone()),
            kernel: Some(self.kernel.clone()),
            h: self.h,
            support: self.support,
            shape: self.shape.clone(),
            stress: Some(self.stress),
            prestress: self.prestress.clone(),
            c: self.c,
            alpha_s: self.alpha_s,
            hourglass: self.hourglass,
            dt: self.dt,
            av_alpha: self.av_alpha,
            av_beta: self.av_beta,
            dim: self.dim,
            lattice: self.lattice.clone(),
            gamma: self.gamma,
            material: self.material.clone(),
            poisson: self.poisson,
            rate: self.rate.clone(),
            art_eps: self.art_eps,
            art_n: self.art_n,
            delta: self.diffusion.delta,
            delta_form: self.diffusion.delta_form.clone(),
            grid: self.grid,
        }
    }

    /// The dimension (`--dim`, default 1); any other value than 1, 2 or 3 is an error.
    pub fn dim(&self) -> Result<u8> {
        Ok(self.spec().dim()?)
    }

    /// Builds and validates the question in D dimensions, within `budget`
    /// ([`sphstab::analysis::QuerySpec::query`]).
    pub fn query<const D: usize>(&self, budget: &Budget) -> Result<Query<D>> {
        Ok(self.spec().query::<D>(budget)?)
    }
}

/// Runs `f::<D>` for the dimension of `--dim`: the one place a command branches on it.
#[macro_export]
macro_rules! by_dim {
    ($dim:expr, $f:ident ( $($arg:expr),* )) => {
        match $dim {
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            _ => $f::<3>($($arg),*),
        }
    };
}

/// `--integrator` and `--euler-every`, shared by `timestep`, `swegle` and `simulate`.
#[derive(clap::Args, Debug, Clone)]
pub struct IntegratorArgs {
    /// Time integrator: kdk (default), dkd, verlet-lagged, symplectic-euler-vx,
    /// symplectic-euler-xv, pec, epec, verlet-euler, rk2-midpoint, rk2-heun, rk4, euler.
    #[arg(long, default_value = "kdk")]
    pub integrator: String,
    /// N_s of verlet-euler: an Euler step every N_s steps, in [1, 1000] (default 40;
    /// verlet-euler only).
    #[arg(long = "euler-every", allow_hyphen_values = true)]
    pub euler_every: Option<usize>,
}

impl IntegratorArgs {
    /// The integrator named by the flags (`--euler-every` with another integrator than
    /// verlet-euler is an error: it would not act).
    pub fn integrator(&self) -> anyhow::Result<sphstab::integrator::Integrator> {
        Ok(sphstab::integrator::Integrator::by_names(
            Some(&self.integrator),
            self.euler_every,
        )?)
    }
}

/// `--delta` / `--delta-form` (δ-SPH density diffusion), shared by `query`, `dispersion`,
/// `timestep` and `swegle`.
#[derive(clap::Args, Debug, Clone)]
pub struct DiffusionArgs {
    /// δ-SPH density diffusion δ, dimensionless, in [0, 10] (typical 0.1):
    /// D_I = δ h c Σ_J ψ_IJ·∇_I W_IJ V_J is added to the continuity equation (forms with a
    /// density state, not total-lagrangian).
    #[arg(long, allow_hyphen_values = true)]
    pub delta: Option<f64>,
    /// The δ-SPH term: antuono (default; renormalised-gradient correction, Antuono et al. 2010)
    /// or molteni-colagrossi (Molteni & Colagrossi 2009); needs --delta.
    #[arg(long = "delta-form")]
    pub delta_form: Option<String>,
}
