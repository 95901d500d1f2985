//! A question by name: [`QuerySpec`] holds the parameters of `query`, `dispersion` and
//! `timestep` as the user gives them (names, optional values, the same defaults), and
//! [`QuerySpec::query`] turns them into a validated [`Query`]. It is the one translation from
//! names to a question: the CLI fills it from its flags, the Python module from keyword
//! arguments, a file from JSON. Its errors name the fields ([`crate::error::field`]); each
//! front end prints them as its own names (`--c`, `c=`).

use super::query::{MaterialSpec, Query};
use crate::budget::Budget;
use crate::error::{Error, Result, Text, check_range, field, fields};
use crate::forms::{DELTA_RANGE, DiffusionForm, FormKind, ObjectiveRate, PrestressKind};
use crate::kernel;
use crate::shape::ShapeFamily;
use serde::{Deserialize, Serialize};

/// The parameters of a question, by name; `None` takes the default.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct QuerySpec {
    /// SPH form (default `classical`).
    pub form: Option<String>,
    /// Kernel (default `m4`).
    pub kernel: Option<String>,
    /// h/Δx in the kernel's convention (default 1.2 unless `support` is given).
    pub h: Option<f64>,
    /// Support radius R/Δx = ζ h/Δx, > 1; alternative to `h`.
    pub support: Option<f64>,
    /// Shape family (default: the form's).
    pub shape: Option<String>,
    /// Pre-stress σ̄ = σ/C, positive in tension (default 0.01).
    pub stress: Option<f64>,
    /// D ≥ 2: the pre-stress's shape, isotropic (default), uniaxial or shear.
    pub prestress: Option<String>,
    /// Partition coefficient c of lnl/cll (default 0.5).
    pub c: Option<f64>,
    /// Least-squares stabilisation α_s (default 0).
    pub alpha_s: Option<f64>,
    /// Hourglass-control coefficient: ζ of enog (default 0.7D + 2.1), κ of tl-enog (default
    /// 1.07), Ganzenmüller's α of total-lagrangian (default none).
    pub hourglass: Option<f64>,
    /// Time step Δt in Δx/c for the fully discrete check.
    pub dt: Option<f64>,
    /// Artificial viscosity α.
    pub av_alpha: Option<f64>,
    /// Artificial viscosity β.
    pub av_beta: Option<f64>,
    /// Dimension 1, 2 or 3 (default 1).
    pub dim: Option<u8>,
    /// 2D square (default) or hex; 3D sc (default), bcc or fcc.
    pub lattice: Option<String>,
    /// 2D square-lattice aspect ratio Δy/Δx (default 1).
    pub gamma: Option<f64>,
    /// 2D/3D material: hydro, elastic (default) or neo-hookean.
    pub material: Option<String>,
    /// 2D/3D Poisson ratio (default 0.3).
    pub poisson: Option<f64>,
    /// 2D/3D objective stress rate: jaumann (default) or truesdell.
    pub rate: Option<String>,
    /// 2D Monaghan–Gray artificial stress ε.
    pub art_eps: Option<f64>,
    /// Artificial-stress exponent n (default 4; needs `art_eps`).
    pub art_n: Option<i32>,
    /// δ-SPH density diffusion δ.
    pub delta: Option<f64>,
    /// δ-SPH term: antuono (default) or molteni-colagrossi (needs `delta`).
    pub delta_form: Option<String>,
    /// Wave-vector sampling (1D: κ points; 2D/3D: per reciprocal direction).
    pub grid: Option<usize>,
}

/// The command a [`QuerySpec`] is asked in ([`QuerySpec::check_for`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// `query`.
    Query,
    /// `dispersion`.
    Dispersion,
    /// `timestep`, with or without its time-domain check.
    Timestep {
        /// Whether the time-domain check (`verify`) runs.
        verify: bool,
    },
    /// `map`.
    Map,
}

/// "`what` does not apply with `context`": a parameter that would not act.
pub fn not_applicable(what: Text, context: Text) -> Error {
    Error::Incompatible(what + " does not apply with " + context)
}

/// `delta` / `delta_form` (δ-SPH density diffusion): δ in [`DELTA_RANGE`], the term by name
/// (default antuono); `delta_form` alone is an error.
pub fn diffusion(delta: Option<f64>, form: Option<&str>) -> Result<Option<(f64, DiffusionForm)>> {
    match (delta, form) {
        (Some(d), f) => {
            check_range("delta", d, DELTA_RANGE.0, DELTA_RANGE.1, true, true)?;
            Ok(Some((d, DiffusionForm::from_name(f.unwrap_or("antuono"))?)))
        }
        (None, Some(_)) => Err(not_applicable(
            field("delta_form"),
            Text::from("no ") + field("delta") + " (it chooses the density-diffusion term)",
        )),
        (None, None) => Ok(None),
    }
}

/// `art_eps` / `art_n` (Monaghan–Gray artificial stress): ε ∈ [0, 10], n ∈ [1, 12]
/// (default 4); `art_n` alone is an error.
pub fn art_stress(eps: Option<f64>, n: Option<i32>) -> Result<Option<(f64, i32)>> {
    match (eps, n) {
        (Some(eps), n) => {
            let n = n.unwrap_or(4);
            check_range("art_eps", eps, 0.0, 10.0, true, true)?;
            check_range("art_n", n as f64, 1.0, 12.0, true, true)?;
            Ok(Some((eps, n)))
        }
        (None, Some(_)) => Err(not_applicable(
            field("art_n"),
            Text::from("no ") + field("art_eps") + " (it is the exponent of the artificial stress)",
        )),
        (None, None) => Ok(None),
    }
}

impl QuerySpec {
    /// The dimension (default 1); any other value than 1, 2 or 3 is an error.
    pub fn dim(&self) -> Result<u8> {
        match self.dim.unwrap_or(1) {
            d @ 1..=3 => Ok(d),
            d => Err(Error::OutOfRange {
                field: "dim",
                value: d as f64,
                range: "must be 1, 2 or 3".into(),
            }),
        }
    }

    /// Refuses the parameters that would not act in `command`, each with why: `av_beta`
    /// everywhere but the time-domain check of `timestep` (`verify`), `dt` in the
    /// semi-discrete `dispersion` and `map`, `grid` in `map` (it samples `n` × `n`).
    pub fn check_for(&self, command: Command) -> Result<()> {
        let semi_discrete = Text::from("the check at a Δt is query ") + field("dt");
        let (name, given, why) = match command {
            Command::Map if self.grid.is_some() => (
                "grid",
                true,
                Text::from("it samples n × n wave vectors: use ") + field("n"),
            ),
            Command::Map | Command::Dispersion if self.dt.is_some() => (
                "dt",
                true,
                match command {
                    Command::Map => {
                        Text::from("the map is the semi-discrete growth rate; ") + semi_discrete
                    }
                    _ => {
                        Text::from("ω² is semi-discrete; ")
                            + semi_discrete
                            + " or timestep "
                            + field("dt")
                    }
                },
            ),
            Command::Timestep { verify: true } => ("av_beta", false, Text::default()),
            _ => (
                "av_beta",
                self.av_beta.is_some(),
                Text::from(
                    "β multiplies the squared velocity divergence, which vanishes in the linearisation; only timestep ",
                ) + field("verify")
                    + " runs the solver",
            ),
        };
        if !given {
            return Ok(());
        }
        let label = match command {
            Command::Query => Text::from("query"),
            Command::Dispersion => Text::from("dispersion"),
            Command::Map => Text::from("map"),
            Command::Timestep { .. } => Text::from("timestep without ") + field("verify"),
        };
        Err(not_applicable(field(name), label + " (" + why + ")"))
    }

    /// The dimension of a growth map (default 2; [`Command::Map`]'s refusals first): the map
    /// is over the 2D zone or a plane of the 3D zone, so `dim` 1 is refused.
    pub fn map_dim(&self) -> Result<u8> {
        self.check_for(Command::Map)?;
        match self.dim.unwrap_or(2) {
            1 => Err(not_applicable(
                field("dim") + " 1",
                Text::from("map (the map is over the 2D zone or a plane of the 3D zone; ")
                    + field("dim")
                    + " 2 or 3)",
            )),
            d => Self {
                dim: Some(d),
                ..Self::default()
            }
            .dim(),
        }
    }

    /// Builds and validates the question in D dimensions, within `budget`: the parameters
    /// every dimension shares, then the lattice and material of D ≥ 2 (refused in 1D).
    pub fn query<const D: usize>(&self, budget: &Budget) -> Result<Query<D>> {
        if D == 1 {
            self.reject_2d()?;
            if self.art_eps.is_some() {
                return Err(Error::Incompatible(
                    field("art_eps")
                        + ": artificial stress is implemented in 2D ("
                        + field("dim")
                        + " 2) only",
                ));
            }
        }
        let form = FormKind::by_name(self.form.as_deref().unwrap_or("classical"))?;
        let k = kernel::by_name(self.kernel.as_deref().unwrap_or("m4"))?;
        let h = match (self.h, self.support) {
            (Some(_), Some(_)) => {
                return Err(Error::Incompatible(
                    field("h") + " and " + field("support") + ": give one of them",
                ));
            }
            (Some(h), None) => h,
            (None, Some(r)) => {
                let (lo, hi) = crate::params::H_RANGE;
                check_range("support", r, lo * k.zeta(), hi * k.zeta(), true, true)?;
                if r <= 1.0 {
                    return Err(Error::OutOfRange {
                        field: "support",
                        value: r,
                        range: "the support R/Δx must exceed 1 so that particles have neighbours"
                            .into(),
                    });
                }
                r / k.zeta()
            }
            (None, None) => 1.2,
        };
        let mut q = Query::<D>::new(form, k, h, self.stress.unwrap_or(0.01));
        if let Some(s) = &self.shape {
            q.shape = ShapeFamily::by_name(s)?;
        }
        let mixed = matches!(form, FormKind::Lnl | FormKind::Cll);
        if self.c.is_some() && !mixed {
            return Err(not_applicable(
                field("c_partition"),
                field("form")
                    + format!(
                        " {} (the partition coefficient is of lnl and cll)",
                        form.name()
                    ),
            ));
        }
        if self.alpha_s.is_some() && form != FormKind::LeastSquares {
            return Err(not_applicable(
                field("alpha_s"),
                field("form")
                    + format!(
                        " {} (α_s is the stabilisation of least-squares)",
                        form.name()
                    ),
            ));
        }
        q.hourglass = self.hourglass;
        q.c_partition = self.c.unwrap_or(0.5);
        q.alpha_s = self.alpha_s.unwrap_or(0.0);
        q.dt = self.dt;
        if self.av_alpha.is_some() || self.av_beta.is_some() {
            q.av = Some((self.av_alpha.unwrap_or(0.0), self.av_beta.unwrap_or(0.0)));
        }
        q.diffusion = diffusion(self.delta, self.delta_form.as_deref())?;
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

    /// The D ≥ 2 parameters: `art_eps`/`art_n`, `lattice`/`gamma`,
    /// `material`/`poisson`/`rate`.
    fn lattice_and_material<const D: usize>(&self, q: &mut Query<D>) -> Result<()> {
        q.art_stress = art_stress(self.art_eps, self.art_n)?;
        if let Some(k) = &self.prestress {
            q.prestress = PrestressKind::by_name(k)?;
        }
        let lattice = self
            .lattice
            .as_deref()
            .unwrap_or(if D == 3 { "sc" } else { "square" });
        if lattice != "square" && self.gamma.is_some() {
            return Err(not_applicable(
                field("gamma"),
                field("lattice")
                    + format!(" {lattice} (the aspect ratio is for the 2D square lattice)"),
            ));
        }
        q.lattice = crate::lattice::Lattice::<D>::named(lattice, self.gamma.unwrap_or(1.0))?;
        let material = self.material.as_deref().unwrap_or("elastic");
        if material == "hydro" && (self.poisson.is_some() || self.rate.is_some()) {
            return Err(not_applicable(
                fields(&["poisson", "rate"]),
                field("material") + " hydro (G = 0)",
            ));
        }
        if material == "neo-hookean" && self.rate.is_some() {
            return Err(not_applicable(
                field("rate"),
                field("material") + " neo-hookean (a hyperelastic law has no stress rate)",
            ));
        }
        let poisson = self.poisson.unwrap_or(0.3);
        let rate = match self.rate.as_deref().unwrap_or("jaumann") {
            "jaumann" => ObjectiveRate::Jaumann,
            "truesdell" => ObjectiveRate::Truesdell,
            r => {
                return Err(Error::UnknownName {
                    what: "rate".into(),
                    given: r.into(),
                    valid: "jaumann, truesdell".into(),
                });
            }
        };
        q.material = match material {
            "hydro" => MaterialSpec::Hydro,
            "neo-hookean" => {
                check_range("poisson", poisson, -0.99, 0.5, true, false)?;
                MaterialSpec::NeoHookean { poisson }
            }
            "elastic" => {
                check_range("poisson", poisson, -0.99, 0.5, true, false)?;
                MaterialSpec::Elastic { poisson, rate }
            }
            m => {
                return Err(Error::UnknownName {
                    what: "material".into(),
                    given: m.into(),
                    valid: "hydro, elastic, neo-hookean".into(),
                });
            }
        };
        Ok(())
    }

    /// Errors for the 2D/3D-only parameters given in 1D.
    fn reject_2d(&self) -> Result<()> {
        let given = [
            ("lattice", self.lattice.is_some()),
            ("gamma", self.gamma.is_some()),
            ("material", self.material.is_some()),
            ("poisson", self.poisson.is_some()),
            ("rate", self.rate.is_some()),
            ("art_n", self.art_n.is_some()),
            ("prestress", self.prestress.is_some()),
        ];
        match given.iter().find(|(_, g)| *g) {
            Some(&(name, _)) => Err(not_applicable(
                field(name),
                field("dim")
                    + " 1 (it is a 2D/3D flag; add "
                    + field("dim")
                    + " 2 or "
                    + field("dim")
                    + " 3)",
            )),
            None => Ok(()),
        }
    }
}
