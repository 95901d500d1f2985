//! Running the tensile-or-hourglass study: every remedy's questions over the states, the
//! stresses and the Poisson ratios, the onsets refined by bisection, and the dispersion costs.

use super::config::{HourglassConfig, Remedy, StressState};
use super::report::{Cost, CurvePoint, HourglassReport, RemedyReport, StateReport};
use crate::analysis::{Query, QueryReport};
use crate::error::Result;
use crate::forms::PrestressKind;
use crate::progress::{Counter, Progress};
use crate::vonneumann::classify::Kind;
use rayon::prelude::*;

/// Bisection steps of an onset: the interval of the stress grid shrinks 2³⁰-fold (~1e-9 of it).
const BISECTIONS: usize = 30;

/// Wave numbers κΔx (along the first lattice vector) of the dispersion costs.
pub const COST_KAPPAS: [f64; 3] = [
    0.1,
    std::f64::consts::FRAC_PI_4,
    std::f64::consts::FRAC_PI_2,
];

/// What one question says about growth: the fastest growth, that of hourglass modes, that of
/// the others (tensile, compressive, indefinite), and whether the continuum itself is unstable.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Growth {
    max: f64,
    hourglass: f64,
    other: f64,
    material: bool,
}

impl Growth {
    fn of(r: &QueryReport) -> Self {
        let mut g = Growth {
            max: r.max_growth_rate,
            ..Growth::default()
        };
        for i in &r.instabilities {
            match i.kind {
                Kind::Hourglass => g.hourglass = g.hourglass.max(i.growth_rate),
                Kind::Tensile | Kind::Compressive | Kind::Indefinite => {
                    g.other = g.other.max(i.growth_rate)
                }
                Kind::Material => g.material = true,
                _ => {}
            }
        }
        g
    }

    /// Growth of the discretisation (not of the continuum).
    fn numerical(self) -> bool {
        !self.material && self.max > crate::vonneumann::classify::GROWTH_TOL
    }
}

fn question<const D: usize>(
    cfg: &HourglassConfig,
    r: &Remedy,
    stress: f64,
    kind: PrestressKind,
    nu: f64,
) -> Result<Query<D>> {
    cfg.spec(r, stress, kind, nu).query::<D>(&cfg.budget)
}

fn growth<const D: usize>(
    cfg: &HourglassConfig,
    r: &Remedy,
    state: StressState,
    magnitude: f64,
    nu: f64,
) -> Result<Growth> {
    let (kind, sign) = state.prestress();
    let q = question::<D>(cfg, r, sign * magnitude, kind, nu)?;
    Ok(Growth::of(&crate::analysis::query(&q)?))
}

/// The smallest |σ̄| of the grid's range at which the discretisation grows at Poisson ratio
/// `nu` (`curve`: its growth on the grid), refined by
/// bisection in the grid interval where growth first appears (None: no growth of its own on
/// the grid), and whether it grows already at the first grid point on an hourglass mode (a
/// zero-energy mode grows at any stress of that sign: the onset is 0).
fn onset<const D: usize>(
    cfg: &HourglassConfig,
    r: &Remedy,
    state: StressState,
    nu: f64,
    curve: &[CurvePoint],
) -> Result<Option<f64>> {
    let Some(first) = curve.iter().position(|p| !p.material && p.growth > 0.0) else {
        return Ok(None);
    };
    if first == 0 {
        return Ok(Some(if curve[0].hourglass > 0.0 {
            0.0
        } else {
            // grows at the first grid point without an hourglass mode: below the grid
            curve[0].stress
        }));
    }
    let (mut lo, mut hi) = (curve[first - 1].stress, curve[first].stress);
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if growth::<D>(cfg, r, state, mid, nu)?.numerical() {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(Some(hi))
}

/// The smallest |σ̄| of the grid's range at which the continuum is unstable, refined by
/// bisection (None: stable on the whole grid).
fn material_limit<const D: usize>(
    cfg: &HourglassConfig,
    r: &Remedy,
    state: StressState,
) -> Result<Option<f64>> {
    let (kind, sign) = state.prestress();
    let nu = cfg.reference_poisson;
    let unstable =
        |s: f64| -> Result<bool> { question::<D>(cfg, r, sign * s, kind, nu)?.material_unstable() };
    let Some(first) = cfg
        .stress
        .iter()
        .position(|&s| unstable(s).unwrap_or(false))
    else {
        return Ok(None);
    };
    if first == 0 {
        return Ok(Some(cfg.stress[0]));
    }
    let (mut lo, mut hi) = (cfg.stress[first - 1], cfg.stress[first]);
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if unstable(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(Some(hi))
}

/// Relative errors of the transverse and longitudinal wave speeds at the wave numbers
/// [`COST_KAPPAS`] along the first lattice vector, unstressed, at the reference ν:
/// √(ω²/ω²_continuum) − 1 (the lowest and the highest branch).
fn cost<const D: usize>(cfg: &HourglassConfig, r: &Remedy) -> Result<(bool, Cost)> {
    let q = question::<D>(cfg, r, 0.0, PrestressKind::Isotropic, cfg.reference_poisson)?;
    let zero_energy = crate::analysis::query(&q)?.has_zero_energy_modes;
    let lin = q.linearise_at(0.0)?;
    let a = q.lattice.a[0];
    let len = a.iter().map(|c| c * c).sum::<f64>().sqrt();
    let mut c = Cost {
        kappa: COST_KAPPAS.to_vec(),
        ..Cost::default()
    };
    for &kappa in &COST_KAPPAS {
        let k: [f64; D] = std::array::from_fn(|i| kappa * a[i] / len);
        let b = lin.branches(k);
        let w = q.continuum_omega2(k)?;
        let err = |num: f64, den: f64| (num / den).sqrt() - 1.0;
        c.transverse.push(err(b[0].0.re, w[0].re));
        c.longitudinal.push(err(b[D - 1].0.re, w[D - 1].re));
    }
    Ok((zero_energy, c))
}

/// Runs the whole study, telling `progress` the fraction of questions done.
pub fn run(cfg: &HourglassConfig, progress: impl Progress) -> Result<HourglassReport> {
    cfg.validate()?;
    match cfg.dim {
        2 => run_in::<2>(cfg, &progress),
        _ => run_in::<3>(cfg, &progress),
    }
}

fn run_in<const D: usize>(
    cfg: &HourglassConfig,
    progress: &dyn Progress,
) -> Result<HourglassReport> {
    let (nr, ns, nm, nn) = (
        cfg.remedies.len(),
        cfg.states.len(),
        cfg.stress.len(),
        cfg.poisson.len(),
    );
    // the grid questions: remedy × state × ν (the reference ν first) × |σ̄|, in parallel
    let nus: Vec<f64> = std::iter::once(cfg.reference_poisson)
        .chain(cfg.poisson.iter().copied())
        .collect();
    let total = nr * ns * nus.len() * nm;
    let done = Counter::new(progress, total + nr * ns * nus.len() + nr, 1);
    let cells: Vec<Growth> = (0..total)
        .into_par_iter()
        .map(|c| {
            let m = c % nm;
            let n = (c / nm) % nus.len();
            let s = (c / (nm * nus.len())) % ns;
            let r = c / (nm * nus.len() * ns);
            let g = growth::<D>(cfg, &cfg.remedies[r], cfg.states[s], cfg.stress[m], nus[n])?;
            done.add(1)?;
            Ok(g)
        })
        .collect::<Result<_>>()?;
    let at =
        |r: usize, s: usize, n: usize, m: usize| cells[((r * ns + s) * nus.len() + n) * nm + m];
    let curve = |r: usize, s: usize, n: usize| -> Vec<CurvePoint> {
        (0..nm)
            .map(|m| {
                let g = at(r, s, n, m);
                CurvePoint {
                    stress: cfg.stress[m],
                    growth: if g.numerical() { g.max } else { 0.0 },
                    hourglass: g.hourglass,
                    other: g.other,
                    material: g.material,
                }
            })
            .collect()
    };
    // onsets per remedy × state × ν (the reference ν first), in parallel
    let onsets: Vec<Option<f64>> = (0..nr * ns * nus.len())
        .into_par_iter()
        .map(|c| {
            let (r, s, n) = (c / (ns * nus.len()), (c / nus.len()) % ns, c % nus.len());
            let on = onset::<D>(
                cfg,
                &cfg.remedies[r],
                cfg.states[s],
                nus[n],
                &curve(r, s, n),
            )?;
            done.add(1)?;
            Ok(on)
        })
        .collect::<Result<_>>()?;
    // the continuum's limits per remedy × state (reference ν)
    let limits: Vec<Option<f64>> = (0..nr * ns)
        .into_par_iter()
        .map(|c| material_limit::<D>(cfg, &cfg.remedies[c / ns], cfg.states[c % ns]))
        .collect::<Result<_>>()?;
    let costs: Vec<(bool, Cost)> = cfg
        .remedies
        .par_iter()
        .map(|r| {
            let c = cost::<D>(cfg, r)?;
            done.add(1)?;
            Ok(c)
        })
        .collect::<Result<_>>()?;
    let mut remedies = Vec::with_capacity(nr);
    for (r, remedy) in cfg.remedies.iter().enumerate() {
        let mut states = Vec::with_capacity(ns);
        for (s, &state) in cfg.states.iter().enumerate() {
            let on = |n: usize| onsets[(r * ns + s) * nus.len() + n];
            let map = (0..nn)
                .map(|n| {
                    (0..nm)
                        .map(|m| {
                            let g = at(r, s, n + 1, m);
                            (!g.material).then_some(if g.numerical() { g.max } else { 0.0 })
                        })
                        .collect()
                })
                .collect();
            let map_hourglass = (0..nn)
                .map(|n| {
                    (0..nm)
                        .map(|m| at(r, s, n + 1, m).hourglass > 0.0)
                        .collect()
                })
                .collect();
            states.push(StateReport {
                state,
                onset_stress: on(0),
                material_limit: limits[r * ns + s],
                curve: curve(r, s, 0),
                onsets: (1..nus.len()).map(on).collect(),
                map,
                map_hourglass,
            });
        }
        let (zero_energy_modes, cost) = costs[r].clone();
        remedies.push(RemedyReport {
            label: remedy.label.clone(),
            form: remedy
                .query
                .form
                .clone()
                .unwrap_or_else(|| "classical".into()),
            zero_energy_modes,
            cost,
            states,
        });
    }
    Ok(HourglassReport {
        config: cfg.clone(),
        shear_over_bulk: cfg.poisson.iter().map(|&nu| shear_over_bulk(nu)).collect(),
        remedies,
    })
}

/// G/K of Poisson ratio ν: 3(1 − 2ν)/(2(1 + ν)).
pub fn shear_over_bulk(nu: f64) -> f64 {
    3.0 * (1.0 - 2.0 * nu) / (2.0 * (1.0 + nu))
}
