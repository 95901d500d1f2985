//! Flags shared by `query`, `dispersion` and `timestep`.

use anyhow::Result;
use sphstab::analysis::Query;
use sphstab::budget::Budget;
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
    /// Partition coefficient c ∈ [0, 1] of lnl/cll (c = 1: fully local; default 0.5).
    #[arg(long, allow_hyphen_values = true)]
    pub c: Option<f64>,
    /// Least-squares stabilisation α_s of the least-squares form, dimensionless (β = α_s Δx²),
    /// in [0, 100] (default 0).
    #[arg(long = "alpha-s", allow_hyphen_values = true)]
    pub alpha_s: Option<f64>,
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
    /// The dimension (`--dim`, default 1); any other value than 1, 2 or 3 is an error.
    pub fn dim(&self) -> Result<u8> {
        match self.dim.unwrap_or(1) {
            d @ 1..=3 => Ok(d),
            d => Err(sphstab::error::Error::OutOfRange {
                field: "dim",
                value: d as f64,
                range: "must be 1, 2 or 3".into(),
            }
            .into()),
        }
    }

    /// Builds and validates the question in D dimensions, within `budget`: the flags every
    /// dimension shares, then the lattice and material flags of D ≥ 2 (refused in 1D).
    pub fn query<const D: usize>(&self, budget: &Budget) -> Result<Query<D>> {
        if D == 1 {
            self.reject_2d_flags()?;
            if self.art_eps.is_some() {
                return Err(sphstab::error::Error::Incompatible(
                    "--art-eps: artificial stress is implemented in 2D (--dim 2) only".into(),
                )
                .into());
            }
        }
        let form = FormKind::by_name(&self.form)?;
        let k = kernel::by_name(&self.kernel)?;
        let h = match (self.h, self.support) {
            (Some(h), _) => h,
            (None, Some(r)) => {
                let (lo, hi) = sphstab::params::H_RANGE;
                sphstab::error::check_range(
                    "--support",
                    r,
                    lo * k.zeta(),
                    hi * k.zeta(),
                    true,
                    true,
                )?;
                if r <= 1.0 {
                    return Err(sphstab::error::Error::OutOfRange {
                        field: "support",
                        value: r,
                        range: "the support R/Δx must exceed 1 so that particles have neighbours"
                            .into(),
                    }
                    .into());
                }
                r / k.zeta()
            }
            (None, None) => 1.2,
        };
        let mut q = Query::<D>::new(form, k, h, self.stress);
        if let Some(s) = &self.shape {
            q.shape = ShapeFamily::by_name(s)?;
        }
        let mixed = matches!(form, FormKind::Lnl | FormKind::Cll);
        if self.c.is_some() && !mixed {
            return Err(crate::query::not_in(
                "--c",
                &format!(
                    "--form {} (the partition coefficient is of lnl and cll)",
                    form.name()
                ),
            ));
        }
        if self.alpha_s.is_some() && form != FormKind::LeastSquares {
            return Err(crate::query::not_in(
                "--alpha-s",
                &format!(
                    "--form {} (α_s is the stabilisation of least-squares)",
                    form.name()
                ),
            ));
        }
        q.c_partition = self.c.unwrap_or(0.5);
        q.alpha_s = self.alpha_s.unwrap_or(0.0);
        q.dt = self.dt;
        if self.av_alpha.is_some() || self.av_beta.is_some() {
            q.av = Some((self.av_alpha.unwrap_or(0.0), self.av_beta.unwrap_or(0.0)));
        }
        q.diffusion = self.diffusion.get()?;
        if let Some(g) = self.grid {
            q.grid = g;
        }
        q.budget = *budget;
        if D > 1 {
            self.lattice_and_material(&mut q)?;
        }
        q.validate()?;
        Ok(q)
    }

    /// The D ≥ 2 flags: `--art-eps/--art-n`, `--lattice/--gamma`, `--material/--poisson/--rate`.
    fn lattice_and_material<const D: usize>(&self, q: &mut Query<D>) -> Result<()> {
        use sphstab::analysis::MaterialSpec;
        use sphstab::forms::ObjectiveRate;
        q.art_stress = art_stress(self.art_eps, self.art_n)?;
        let lattice = self
            .lattice
            .as_deref()
            .unwrap_or(if D == 3 { "sc" } else { "square" });
        if lattice != "square" && self.gamma.is_some() {
            return Err(crate::query::not_in(
                "--gamma",
                &format!("--lattice {lattice} (the aspect ratio is for the 2D square lattice)"),
            ));
        }
        q.lattice = sphstab::lattice::Lattice::<D>::named(lattice, self.gamma.unwrap_or(1.0))?;
        let material = self.material.as_deref().unwrap_or("elastic");
        if material == "hydro" && (self.poisson.is_some() || self.rate.is_some()) {
            return Err(crate::query::not_in(
                "--poisson/--rate",
                "--material hydro (G = 0)",
            ));
        }
        if material == "neo-hookean" && self.rate.is_some() {
            return Err(crate::query::not_in(
                "--rate",
                "--material neo-hookean (a hyperelastic law has no stress rate)",
            ));
        }
        let poisson = self.poisson.unwrap_or(0.3);
        let rate = match self.rate.as_deref().unwrap_or("jaumann") {
            "jaumann" => ObjectiveRate::Jaumann,
            "truesdell" => ObjectiveRate::Truesdell,
            r => {
                return Err(sphstab::error::Error::UnknownName {
                    what: "rate".into(),
                    given: r.into(),
                    valid: "jaumann, truesdell".into(),
                }
                .into());
            }
        };
        q.material = match material {
            "hydro" => MaterialSpec::Hydro,
            "neo-hookean" => {
                sphstab::error::check_range("--poisson", poisson, -0.99, 0.5, true, false)?;
                MaterialSpec::NeoHookean { poisson }
            }
            "elastic" => {
                sphstab::error::check_range("--poisson", poisson, -0.99, 0.5, true, false)?;
                MaterialSpec::Elastic { poisson, rate }
            }
            m => {
                return Err(sphstab::error::Error::UnknownName {
                    what: "material".into(),
                    given: m.into(),
                    valid: "hydro, elastic, neo-hookean".into(),
                }
                .into());
            }
        };
        Ok(())
    }

    /// Errors for 2D/3D-only flags given with `--dim 1`.
    pub fn reject_2d_flags(&self) -> Result<()> {
        let given = [
            ("--lattice", self.lattice.is_some()),
            ("--gamma", self.gamma.is_some()),
            ("--material", self.material.is_some()),
            ("--poisson", self.poisson.is_some()),
            ("--rate", self.rate.is_some()),
            ("--art-n", self.art_n.is_some()),
        ];
        match given.iter().find(|(_, g)| *g) {
            Some((flag, _)) => Err(crate::query::not_in(
                flag,
                "--dim 1 (it is a 2D/3D flag; add --dim 2 or --dim 3)",
            )),
            None => Ok(()),
        }
    }
}

/// Errors for flags of [`Config`] that cannot act in `command`: each (flag, given, why).
pub fn refuse(command: &str, flags: &[(&str, bool, &str)]) -> Result<()> {
    match flags.iter().find(|f| f.1) {
        Some((flag, _, why)) => Err(crate::query::not_in(flag, &format!("{command} ({why})"))),
        None => Ok(()),
    }
}

/// Why `--av-beta` cannot act in the analysis.
pub const AV_BETA_WHY: &str = "β multiplies the squared velocity divergence, which vanishes in the linearisation; only timestep --verify runs the solver";

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

/// `--art-eps` / `--art-n` (Monaghan–Gray artificial stress): ε ∈ [0, 10], n ∈ [1, 12]
/// (default 4); `--art-n` alone is an error.
pub fn art_stress(eps: Option<f64>, n: Option<i32>) -> Result<Option<(f64, i32)>> {
    match (eps, n) {
        (Some(eps), n) => {
            let n = n.unwrap_or(4);
            sphstab::error::check_range("--art-eps", eps, 0.0, 10.0, true, true)?;
            sphstab::error::check_range("--art-n", n as f64, 1.0, 12.0, true, true)?;
            Ok(Some((eps, n)))
        }
        (None, Some(_)) => Err(crate::query::not_in(
            "--art-n",
            "no --art-eps (it is the exponent of the artificial stress)",
        )),
        (None, None) => Ok(None),
    }
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
        use sphstab::integrator::{DEFAULT_EULER_EVERY, Integrator};
        let i = Integrator::from_name(
            &self.integrator,
            self.euler_every.unwrap_or(DEFAULT_EULER_EVERY),
        )?;
        if self.euler_every.is_some() && !matches!(i, Integrator::VerletEuler { .. }) {
            return Err(crate::query::not_in(
                "--euler-every",
                &euler_every_context(&self.integrator),
            ));
        }
        Ok(i)
    }
}

/// Why `--euler-every` cannot act with the integrator `name`.
pub fn euler_every_context(name: &str) -> String {
    format!("--integrator {name} (N_s is the Euler period of verlet-euler)")
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

impl DiffusionArgs {
    /// (δ, form), or None without `--delta`; `--delta-form` alone is an error.
    pub fn get(&self) -> Result<Option<(f64, sphstab::forms::DiffusionForm)>> {
        use sphstab::forms::{DELTA_RANGE, DiffusionForm};
        match (self.delta, &self.delta_form) {
            (Some(d), f) => {
                sphstab::error::check_range(
                    "--delta",
                    d,
                    DELTA_RANGE.0,
                    DELTA_RANGE.1,
                    true,
                    true,
                )?;
                let form = DiffusionForm::from_name(f.as_deref().unwrap_or("antuono"))?;
                Ok(Some((d, form)))
            }
            (None, Some(_)) => Err(crate::query::not_in(
                "--delta-form",
                "no --delta (it chooses the density-diffusion term)",
            )),
            (None, None) => Ok(None),
        }
    }
}
