//! The 1D front end: is a configuration stable (`query`), its dispersion curve
//! (`dispersion`), and its critical time step (`timestep`), over κΔx ∈ (0, π] of the chain
//! engine ([`Linearisation`]; every 1D form).

use super::common::{IntegratorReport, Setup, density_diffusion, linearised_av};
use crate::error::{Error, Result, check_range};
use crate::forms::{DiffusionForm, FormKind, Material, ModelParams};
use crate::integrator::Integrator;
use crate::kernel::Kernel;
use crate::params::{check_common, check_count};
use crate::shape::{KernelParams, ShapeFamily};
use crate::vonneumann::amplification::{
    AMPLIFICATION_TOL, critical_dt_given, leapfrog_limit, spectral_radius_with, step_stability,
};
use crate::vonneumann::classify::{
    GROWTH_TOL, Instability, Kind, ZERO_OMEGA2_TOL, branch, growth_kind, runs,
};
use crate::vonneumann::damping::{branch_eigenvalues, critical_dt_eq120, damping_ratio};
use crate::vonneumann::linearise::{Lattice1D, Linearisation, PhaseTable};
use serde::Serialize;
use std::f64::consts::PI;

/// A 1D stability question.
#[derive(Clone, Copy, Debug)]
pub struct Query1D {
    /// Form.
    pub form: FormKind,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// Shape family.
    pub shape: ShapeFamily,
    /// h/Δx in the kernel's own convention.
    pub h_over_dx: f64,
    /// σ̄ = σ/C (positive in tension).
    pub stress: f64,
    /// Partition coefficient c of `lnl`/`cll`.
    pub c_partition: f64,
    /// Least-squares α_s.
    pub alpha_s: f64,
    /// Monaghan artificial viscosity (α, β), linearised (acting on all pairs).
    pub av: Option<(f64, f64)>,
    /// Time step Δt in Δx/c for the fully discrete check.
    pub dt: Option<f64>,
    /// Time integrator of the fully discrete check and the critical Δt (default `kdk`).
    pub integrator: Integrator,
    /// δ-SPH density diffusion (δ, form).
    pub diffusion: Option<(f64, DiffusionForm)>,
    /// Number of κ points in (0, π].
    pub points: usize,
    /// Physical lattice (results in normalised units do not depend on it).
    pub lattice: Lattice1D,
}

impl Query1D {
    /// A query with the defaults of the CLI.
    pub fn new(form: FormKind, kernel: &'static dyn Kernel, h_over_dx: f64, stress: f64) -> Self {
        Self {
            form,
            kernel,
            shape: form.default_shape(),
            h_over_dx,
            stress,
            c_partition: 0.5,
            alpha_s: 0.0,
            av: None,
            dt: None,
            integrator: Integrator::Kdk,
            diffusion: None,
            points: 512,
            lattice: Lattice1D::default(),
        }
    }

    /// Validates every number (one-line errors naming the parameter and its range).
    pub fn validate(&self) -> Result<()> {
        check_common(
            self.kernel,
            self.h_over_dx,
            self.stress,
            self.c_partition,
            self.av,
            self.dt,
        )?;
        check_range("alpha_s", self.alpha_s, 0.0, 100.0, true, true)?;
        check_count("points", self.points, 2, 10_000_000)?;
        density_diffusion(self.diffusion, 1.0, self.form)?;
        check_range(
            "lattice dx",
            self.lattice.dx,
            0.0,
            f64::INFINITY,
            false,
            false,
        )?;
        self.form.check_shape(self.shape)
    }

    /// Support radius R/Δx.
    pub fn support_over_dx(&self) -> f64 {
        Setup::new(
            self.form,
            self.kernel,
            self.shape,
            self.h_over_dx,
            self.stress,
        )
        .support_over_dx
    }

    /// Model parameters in physical units of the lattice ([`Material::bar`]).
    pub fn params(&self) -> ModelParams {
        let lat = self.lattice;
        let c = (lat.modulus / lat.rho0).sqrt();
        ModelParams {
            form: self.form,
            shape: self.shape,
            kp: KernelParams {
                kernel: self.kernel,
                h: self.h_over_dx * lat.dx,
            },
            material: Material::bar(lat.modulus),
            rho0: lat.rho0,
            c_partition: self.c_partition,
            av: linearised_av(self.av, c),
            art_stress: None,
            // checked by `validate`
            diffusion: density_diffusion(self.diffusion, c, self.form).unwrap_or(None),
            alpha_s: self.alpha_s,
            ls_length: lat.dx,
        }
    }

    /// The pre-stress σ0 = σ̄ C of normalised stress `stress`, physical units.
    pub fn sigma0(&self, stress: f64) -> f64 {
        stress * self.lattice.modulus
    }

    /// Linearisation at normalised stress `stress` (not validated: [`Self::linearise`] is).
    pub fn linearise_at(&self, stress: f64) -> Result<Linearisation> {
        Linearisation::new(self.params(), self.sigma0(stress), self.lattice)
    }

    /// The κΔx grid π k / n, k = 1..n.
    pub fn kappas(&self) -> Vec<f64> {
        (1..=self.points)
            .map(|k| PI * k as f64 / self.points as f64)
            .collect()
    }

    /// Linearisation at the query's stress.
    pub fn linearise(&self) -> Result<Linearisation> {
        self.validate()?;
        self.linearise_at(self.stress)
    }
}

/// Header common to every 1D report: the [`Setup`] and the 1D form parameters.
#[derive(Clone, Debug, Serialize)]
pub struct Header {
    /// Form, kernel, shape, h, R, σ̄.
    #[serde(flatten)]
    pub setup: Setup,
    /// Partition coefficient c (mixed forms).
    pub c_partition: f64,
    /// α_s (least squares).
    pub alpha_s: f64,
}

impl std::fmt::Display for Header {
    /// One line: form / kernel / shape, h and R in Δx, σ̄.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.setup.fmt(f)
    }
}

impl Header {
    fn of(q: &Query1D) -> Self {
        Self {
            setup: Setup::new(q.form, q.kernel, q.shape, q.h_over_dx, q.stress),
            c_partition: q.c_partition,
            alpha_s: q.alpha_s,
        }
    }
}

/// Verdict of `query`.
#[derive(Clone, Debug, Serialize)]
pub struct QueryReport {
    /// Configuration.
    #[serde(flatten)]
    pub header: Header,
    /// No exponentially growing mode (and no time-step amplification if Δt was given).
    pub stable: bool,
    /// Largest growth rate (c/Δx), 0 if stable.
    pub max_growth_rate: f64,
    /// κΔx of the largest growth rate (null if stable).
    pub kappa_at_max: Option<f64>,
    /// Every unstable or marginal branch.
    pub instabilities: Vec<Instability>,
    /// Zero-energy (rank-deficiency) modes exist.
    pub has_zero_energy_modes: bool,
    /// Critical leapfrog Δt in Δx/c (null if the semi-discrete system grows).
    pub critical_dt: Option<f64>,
    /// Critical CFL number c Δt_crit / h.
    pub critical_cfl: Option<f64>,
    /// The Δt checked (Δx/c), if any.
    pub dt: Option<f64>,
    /// Largest |λ| at that Δt.
    pub max_amplification: Option<f64>,
    /// Time integrator of `critical_dt` and of the check at `dt`.
    pub integrator: &'static str,
    /// Growth per unit time (c/Δx) the integrator adds to the non-growing modes at `dt`
    /// (max ln|λ|/Δt; 0 if none, or no `dt`).
    pub spurious_growth_rate: f64,
}

/// Dispersion curve.
#[derive(Clone, Debug, Serialize)]
pub struct DispersionReport {
    /// Configuration.
    #[serde(flatten)]
    pub header: Header,
    /// κΔx grid.
    pub kappa_dx: Vec<f64>,
    /// ω²Δx²/c² of the mechanical branch.
    pub omega2: Vec<f64>,
    /// Growth rate (c/Δx) at each κ.
    pub growth_rate: Vec<f64>,
    /// Continuum ω²Δx²/c² = (1 + σ̄)(κΔx)² \[B00 eq 32\].
    pub omega2_continuum: Vec<f64>,
    /// Dissipative systems only (absent otherwise): damping rate Re s (c/Δx, ≤ 0 when damped)
    /// of the mechanical branch at each κ, from the exact eigenvalues of J(κ); null where the
    /// matching of eigenvalue to branch is ambiguous (overdamped: two real eigenvalues; rule in
    /// [`crate::vonneumann::damping`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_rate: Option<Vec<Option<f64>>>,
    /// Dissipative systems only: modal damping ratio ξ = −Re s/|s| of the same eigenvalue.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_ratio: Option<Vec<Option<f64>>>,
}

/// Critical time step.
#[derive(Clone, Debug, Serialize)]
pub struct TimestepReport {
    /// Configuration.
    #[serde(flatten)]
    pub header: Header,
    /// 2/ω_max, the leapfrog limit \[B00 eq 120, ξ = 0\] (non-dissipative systems).
    pub critical_dt_from_omega_max: Option<f64>,
    /// Dissipative systems only (absent otherwise, where eq 120 is `critical_dt_from_omega_max`):
    /// \[B00\] eq 120, min over the modes of (2/ω)(√(ξ² + 1) − ξ) with the modal (ω, ξ) of the
    /// semi-discrete eigenvalues ([`crate::vonneumann::damping::critical_dt_eq120`]); Δx/c. Null
    /// when the semi-discrete system grows or no mode oscillates.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub critical_dt_eq120: Option<f64>,
    /// The integrator's critical Δt, CFL number, weak instability and spurious growth
    /// (`critical_dt` is null if the semi-discrete system grows).
    #[serde(flatten)]
    pub step: IntegratorReport,
}

/// Growth rates and ω² on the grid (phase factors tabulated once: [`PhaseTable`]).
fn curve(lin: &Linearisation, kappas: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut w2 = Vec::with_capacity(kappas.len());
    let mut g = Vec::with_capacity(kappas.len());
    let table = PhaseTable::new(kappas, lin.reach());
    for k in 0..kappas.len() {
        let (o, _) = lin.omega2_tabulated(&table, k);
        if !o.is_finite() {
            return Err(Error::NonFinite("ω²"));
        }
        w2.push(o);
        g.push(if lin.is_dissipative() {
            lin.growth_tabulated(&table, k)?
        } else {
            (-o).max(0.0).sqrt()
        });
    }
    Ok((w2, g))
}

/// Answers a stability query.
pub fn query(q: &Query1D) -> Result<QueryReport> {
    let lin = q.linearise()?;
    let kappas = q.kappas();
    let (w2, g) = curve(&lin, &kappas)?;
    let growing: Vec<bool> = g.iter().map(|&x| x > GROWTH_TOL).collect();
    let mut inst = Vec::new();
    let cbar = 1.0 + q.stress;
    let scale = w2.iter().fold(0.0f64, |m, &x| m.max(x.abs()));
    // the zero-stress linearisation, built once when a growing branch needs it
    let mut lin0 = None;
    for r in runs(&growing) {
        let b = branch(Kind::Material, &kappas, &g, r);
        let kind = growth_kind(cbar <= 0.0, q.stress, || {
            let l0 = match &mut lin0 {
                Some(l) => l,
                slot @ None => slot.insert(q.linearise_at(0.0)?),
            };
            l0.growth(b.kappa_at_max)
        })?;
        // a pole: ω² changes sign between neighbours through ±∞ (both sides large), not
        // through 0; the first one at or before the branch
        let pole_at = (r.0.max(1)..=r.1).find_map(|i| {
            let (a, b) = (w2[i - 1], w2[i]);
            (a.signum() != b.signum() && a.abs().min(b.abs()) > 0.05 * scale)
                .then(|| 0.5 * (kappas[i - 1] + kappas[i]))
        });
        inst.push(Instability { kind, pole_at, ..b });
    }
    // cbar ≤ 0 with nothing growing (C̄ = 0: ω ≡ 0 in the continuum): still material
    if cbar <= 0.0 && !inst.iter().any(|i| i.kind == Kind::Material) {
        inst.push(branch(
            Kind::Material,
            &kappas,
            &vec![0.0; kappas.len()],
            (0, kappas.len() - 1),
        ));
    }
    let zero: Vec<bool> = w2
        .iter()
        .zip(&growing)
        .zip(&kappas)
        .map(|((&o, &gr), &k)| {
            !gr && o.abs() <= ZERO_OMEGA2_TOL * scale.max(1e-300)
                && o.abs() <= ZERO_OMEGA2_TOL.sqrt() * cbar.abs().max(1e-3) * k * k
        })
        .collect();
    let zero_runs = runs(&zero);
    let has_zero = !zero_runs.is_empty();
    for r in zero_runs {
        let zeros = vec![0.0; kappas.len()];
        inst.push(branch(Kind::RankDeficiency, &kappas, &zeros, r));
    }
    let semi_stable = !growing.iter().any(|&x| x);
    let integ = q.integrator;
    // the integrator's verdict (kdk: the leapfrog limit or bisection, as always)
    let (cdt, weak) = if integ == Integrator::Kdk {
        let d = semi_stable
            .then(|| critical_dt_given(&lin, &kappas, w2.iter().fold(0.0, |m, &x| m.max(x))))
            .transpose()?;
        (d, false)
    } else {
        let st = step_stability(&lin, &kappas, integ)?;
        (st.critical_dt.filter(|_| semi_stable), st.weak)
    };
    let cfl = cdt.map(|d| d / q.h_over_dx);
    let mut max_amp = None;
    let mut ts_unstable = false;
    let mut spurious = 0.0f64;
    if let Some(dt) = q.dt {
        let rho: Vec<f64> = kappas
            .iter()
            .map(|&k| spectral_radius_with(&lin, k, dt, integ))
            .collect::<Result<_>>()?;
        max_amp = Some(rho.iter().fold(0.0f64, |m, &x| m.max(x)));
        let flags: Vec<bool> = rho
            .iter()
            .zip(&growing)
            .map(|(&r, &gr)| !gr && r > 1.0 + AMPLIFICATION_TOL)
            .collect();
        let rate: Vec<f64> = rho.iter().map(|r| r.ln().max(0.0) / dt).collect();
        for r in runs(&flags) {
            ts_unstable = true;
            let kind = if weak {
                Kind::Integrator
            } else {
                Kind::TimeStep
            };
            let b = branch(kind, &kappas, &rate, r);
            spurious = spurious.max(b.growth_rate);
            inst.push(b);
        }
    }
    // the largest growth over every row, time-step rows (growth per unit time ln|λ|/Δt) included,
    // so that the verdict line and the JSON agree with the rows
    let (mut gmax, mut kmax) = (0.0, None);
    for i in &inst {
        if i.growth_rate > GROWTH_TOL && i.growth_rate > gmax {
            gmax = i.growth_rate;
            kmax = Some(i.kappa_at_max);
        }
    }
    let material = cbar <= 0.0;
    Ok(QueryReport {
        header: Header::of(q),
        stable: semi_stable && !ts_unstable && !material,
        max_growth_rate: gmax,
        kappa_at_max: kmax,
        instabilities: inst,
        has_zero_energy_modes: has_zero,
        critical_dt: cdt,
        critical_cfl: cfl,
        dt: q.dt,
        max_amplification: max_amp,
        integrator: integ.name(),
        spurious_growth_rate: spurious,
    })
}

/// The dispersion curve ω²(κ).
pub fn dispersion(q: &Query1D) -> Result<DispersionReport> {
    let lin = q.linearise()?;
    let kappas = q.kappas();
    let (w2, g) = curve(&lin, &kappas)?;
    let cont = kappas.iter().map(|k| (1.0 + q.stress) * k * k).collect();
    let (mut rate, mut ratio) = (None, None);
    if lin.is_dissipative() {
        let (mut r, mut x) = (Vec::with_capacity(kappas.len()), Vec::new());
        for (&k, &w) in kappas.iter().zip(&w2) {
            let s = branch_eigenvalues(&lin.eigenvalues(k)?, &[w])[0];
            r.push(s.map(|s| s.re));
            x.push(s.map(damping_ratio));
        }
        (rate, ratio) = (Some(r), Some(x));
    }
    Ok(DispersionReport {
        header: Header::of(q),
        kappa_dx: kappas,
        omega2: w2,
        growth_rate: g,
        omega2_continuum: cont,
        damping_rate: rate,
        damping_ratio: ratio,
    })
}

/// The critical time step.
pub fn timestep(q: &Query1D) -> Result<TimestepReport> {
    timestep_with(q, Integrator::Kdk, None)
}

/// The critical time step of `integ` (and its spurious growth at `dt`, default 1/ω_max) over
/// the κ grid of `q`.
pub fn timestep_with(q: &Query1D, integ: Integrator, dt: Option<f64>) -> Result<TimestepReport> {
    let lin = q.linearise()?;
    let kappas = q.kappas();
    let (w2, g) = curve(&lin, &kappas)?;
    let w2max = w2.iter().fold(0.0f64, |m, &x| m.max(x));
    let grows = g.iter().any(|&x| x > GROWTH_TOL);
    let from_w = if lin.is_dissipative() || grows || w2max == 0.0 {
        None
    } else {
        Some(leapfrog_limit(w2max))
    };
    if let Some(d) = dt {
        check_range("dt", d, 0.0, 1e6, false, true)?;
    }
    let eq120 = if lin.is_dissipative() && !grows {
        Some(critical_dt_eq120(&lin, &kappas)?).filter(|d| d.is_finite())
    } else {
        None
    };
    Ok(TimestepReport {
        header: Header::of(q),
        critical_dt_from_omega_max: from_w,
        critical_dt_eq120: eq120,
        step: IntegratorReport::of(&lin, &kappas, integ, dt, q.h_over_dx, grows)?,
    })
}
