//! The tensile-or-hourglass study's report, its table and the findings it states.

use super::config::{HourglassConfig, StressState};
use super::experiment::ExperimentReport;
use crate::display::num;
use serde::{Deserialize, Serialize};

/// One point of a growth curve (at the reference ν).
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CurvePoint {
    /// |σ̄|.
    pub stress: f64,
    /// Growth rate of the discretisation (c/Δx; 0 when stable or when only the continuum grows).
    pub growth: f64,
    /// Growth rate on hourglass modes (zero-energy at zero stress).
    pub hourglass: f64,
    /// Growth rate on the other modes (tensile, compressive, indefinite).
    pub other: f64,
    /// Whether the continuum itself is unstable there (its growth is not the discretisation's).
    pub material: bool,
}

/// One remedy in one pre-stress state.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct StateReport {
    /// The state.
    pub state: StressState,
    /// The smallest |σ̄| at which the discretisation grows (reference ν): 0 when a zero-energy
    /// mode grows at the smallest grid stress (it grows at any stress of that sign), else
    /// refined by bisection in the grid interval where growth appears (the smallest grid stress
    /// itself when a mode with stiffness grows there already: the onset is at most that); null:
    /// stable up to the largest grid stress (or the material limit).
    pub onset_stress: Option<f64>,
    /// The smallest |σ̄| at which the continuum is unstable (null: not on the grid).
    pub material_limit: Option<f64>,
    /// Growth against |σ̄| at the reference ν.
    pub curve: Vec<CurvePoint>,
    /// Onset |σ̄| per ν of `poisson` (as `onset_stress`).
    pub onsets: Vec<Option<f64>>,
    /// Growth rate per (ν of `poisson`, |σ̄|) (null where the continuum is unstable).
    pub map: Vec<Vec<Option<f64>>>,
    /// Whether hourglass modes grow there.
    pub map_hourglass: Vec<Vec<bool>>,
}

/// Relative wave-speed errors of a remedy at rest (reference ν).
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Cost {
    /// κΔx along the first lattice vector.
    pub kappa: Vec<f64>,
    /// √(ω²/ω²_continuum) − 1 of the transverse (lowest) branch.
    pub transverse: Vec<f64>,
    /// The same of the longitudinal (highest) branch.
    pub longitudinal: Vec<f64>,
}

/// One remedy.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RemedyReport {
    /// Label.
    pub label: String,
    /// Its form.
    pub form: String,
    /// Zero-energy modes at rest (reference ν).
    pub zero_energy_modes: bool,
    /// Its dispersion error at rest.
    pub cost: Cost,
    /// Per pre-stress state.
    pub states: Vec<StateReport>,
}

/// The study's report (also the stored data the figure is redrawn from, with its "units").
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct HourglassReport {
    /// The config.
    pub config: HourglassConfig,
    /// G/K of each ν of the maps.
    pub shear_over_bulk: Vec<f64>,
    /// Per remedy.
    pub remedies: Vec<RemedyReport>,
}

/// An onset as text: "0 (hourglass)", the value (4 decimals), or "> max" (stable on the grid).
pub fn onset_text(onset: Option<f64>, max: f64) -> String {
    match onset {
        Some(0.0) => "0 (hourglass)".into(),
        Some(o) => format!("{o:.4}"),
        None => format!("> {}", num(max)),
    }
}

/// The table: per remedy its zero-energy modes, onset stress per state (reference ν), and
/// wave-speed errors at κΔx = π/2.
pub fn table(r: &HourglassReport) -> String {
    let cfg = &r.config;
    let max = cfg.stress.last().copied().unwrap_or(0.0);
    let mut out = format!(
        "tensile or hourglass: {}D, ν = {} (G/K = {:.4}), |σ̄| in [{}, {}], grid {}\n",
        cfg.dim,
        num(cfg.reference_poisson),
        super::run::shear_over_bulk(cfg.reference_poisson),
        num(cfg.stress[0]),
        num(max),
        cfg.grid
    );
    out += "onset |σ̄| of growth (0: a zero-energy mode grows at any stress); zero-energy modes at rest; wave-speed error at κΔx = π/2 (transverse, longitudinal)\n";
    let mut head = format!("{:<22} {:>5}", "remedy", "ZEM");
    for s in &cfg.states {
        head += &format!(" {:>22}", s.name());
    }
    head += &format!(" {:>9} {:>9}\n", "c_T err", "c_L err");
    out += &head;
    for rem in &r.remedies {
        let mut line = format!(
            "{:<22} {:>5}",
            rem.label,
            if rem.zero_energy_modes { "yes" } else { "no" }
        );
        for s in &rem.states {
            let mut t = onset_text(s.onset_stress, max);
            if let Some(m) = s.material_limit {
                t += &format!(" (mat {m:.4})");
            }
            line += &format!(" {t:>22}");
        }
        let last = |v: &[f64]| v.last().copied().unwrap_or(f64::NAN);
        line += &format!(
            " {:>9} {:>9}\n",
            format!("{:+.3}", last(&rem.cost.transverse)),
            format!("{:+.3}", last(&rem.cost.longitudinal))
        );
        out += &line;
    }
    out
}

/// The grid point of `curve` nearest (in log |σ̄|) to `s`.
fn nearest(curve: &[CurvePoint], s: f64) -> Option<&CurvePoint> {
    curve.iter().min_by(|a, b| {
        (a.stress.ln() - s.ln())
            .abs()
            .total_cmp(&(b.stress.ln() - s.ln()).abs())
    })
}

/// An onset in a table cell of the note: as [`onset_text`], "stable to max" for none.
fn onset_cell(o: Option<f64>, max: f64) -> String {
    match o {
        None => format!("stable to {}", num(max)),
        o => onset_text(o, max),
    }
}

/// The study's findings as Markdown (analysis/tensile_or_hourglass.md): every number is the
/// report's, the experiments' and the other lattices' (`others`: (config file, report), each
/// shown as its onset table); the sentences are chosen by the numbers (which remedy has
/// zero-energy modes, grows from zero stress, grows only beyond an onset).
pub fn note_markdown(
    r: &HourglassReport,
    experiments: &[(String, ExperimentReport)],
    others: &[(String, HourglassReport)],
) -> String {
    let cfg = &r.config;
    let max = cfg.stress.last().copied().unwrap_or(0.0);
    let g_over_c = |nu: f64| (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu));
    let lattice = cfg
        .lattice
        .clone()
        .unwrap_or_else(|| if cfg.dim == 3 { "sc" } else { "square" }.into());
    let mut s = String::from("# Tensile or hourglass?\n\n");
    s += "Issue 30. Generated from the report of `sphstab hourglass --config analysis/tensile_or_hourglass.json` \
          by `SPHSTAB_WRITE_NOTE=1 cargo test --release --test it -- hourglass::note`, which fails when a number here \
          drifts; the figure is `figures/tensile_or_hourglass.svg`. Do not edit by hand.\n\n";
    s += &format!(
        "Set-up: {}D {} lattice; each remedy is its `query` in the config (kernel, h, shape, coefficient); \
         elastic material with the Jaumann rate, Poisson ratio ν = {} (G/C = {:.4}, G/K = {:.4}) unless a table says otherwise; \
         {} wave vectors per reciprocal direction; |σ̄| = |σ|/C on {} values from {} to {} (C = λ + 2G). \
         An onset is the smallest |σ̄| at which the discretisation itself grows (the continuum stable), \
         refined by bisection; \"0 (hourglass)\" means a mode that is zero-energy at rest grows at the \
         smallest stress of the grid, and so at any stress of that sign.\n\n",
        cfg.dim,
        lattice,
        num(cfg.reference_poisson),
        g_over_c(cfg.reference_poisson),
        super::run::shear_over_bulk(cfg.reference_poisson),
        cfg.grid,
        cfg.stress.len(),
        num(cfg.stress[0]),
        num(max)
    );
    // 1. which remedy removes which mode
    s += "## Which remedy removes which mode\n\n";
    s += "| remedy | zero-energy modes at rest |";
    for st in &cfg.states {
        s += &format!(" onset, {} |", st.name());
    }
    s += "\n|---|---|";
    s += &"---|".repeat(cfg.states.len());
    s += "\n";
    for rem in &r.remedies {
        s += &format!(
            "| {} | {} |",
            rem.label,
            if rem.zero_energy_modes { "yes" } else { "no" }
        );
        for st in &rem.states {
            s += &format!(" {} |", onset_cell(st.onset_stress, max));
        }
        s += "\n";
    }
    let limits: Vec<String> = cfg
        .states
        .iter()
        .enumerate()
        .filter_map(|(i, st)| {
            r.remedies[0].states[i]
                .material_limit
                .map(|m| format!("{} at |σ̄| = {m:.4}", st.name()))
        })
        .collect();
    if !limits.is_empty() {
        s += &format!(
            "\nThe continuum itself (the Jaumann law) fails in {}: growth beyond it is the material's, not counted in the onsets.\n",
            limits.join(", ")
        );
    }
    // 2. hourglass or tensile growth
    s += "\n## Growth in each state: on hourglass modes, or on modes with stiffness?\n\n";
    s += "Growth rate γ (c/Δx) at ν = ";
    s += &num(cfg.reference_poisson);
    s += ", total and split by the classification: on modes that are zero-energy at rest (hourglass) and on the others.\n\n";
    s += "| remedy | state | |σ̄| | γ | hourglass part | the rest |\n|---|---|---|---|---|---|\n";
    for rem in &r.remedies {
        for st in &rem.states {
            for target in [0.01, 0.1] {
                let Some(p) = nearest(&st.curve, target) else {
                    continue;
                };
                if p.growth == 0.0 {
                    continue;
                }
                s += &format!(
                    "| {} | {} | {} | {:.4} | {:.4} | {:.4} |\n",
                    rem.label,
                    st.state.name(),
                    num(p.stress),
                    p.growth,
                    p.hourglass,
                    p.other
                );
            }
        }
    }
    // 3. onsets against G/K
    s += "\n## Does a tensile instability remain without zero-energy modes?\n\n";
    s += "Onset |σ̄| against the Poisson ratio for the remedies without zero-energy modes at rest \
          (\"stable to\": no growth of the discretisation up to the largest |σ̄|, or up to where the continuum fails).\n\n";
    s += "| remedy | state |";
    for &nu in &cfg.poisson {
        s += &format!(" ν = {} (G/C {:.4}) |", num(nu), g_over_c(nu));
    }
    s += "\n|---|---|";
    s += &"---|".repeat(cfg.poisson.len());
    s += "\n";
    let mut remaining = Vec::new();
    for rem in r.remedies.iter().filter(|r| !r.zero_energy_modes) {
        for st in &rem.states {
            if st.onsets.iter().all(Option::is_none) {
                continue;
            }
            s += &format!("| {} | {} |", rem.label, st.state.name());
            for (i, o) in st.onsets.iter().enumerate() {
                s += &format!(" {} |", onset_cell(*o, max));
                if let Some(o) = o.filter(|&o| o > 0.0) {
                    remaining.push((rem.label.clone(), st.state, cfg.poisson[i], o));
                }
            }
            s += "\n";
        }
    }
    if remaining.is_empty() {
        s += "| (none grows) | | \n";
    }
    // 4. costs
    s += "\n## What each remedy costs at rest\n\n";
    s += "Relative wave-speed errors √(ω²/ω²_continuum) − 1 along the first lattice vector, transverse and longitudinal.\n\n| remedy |";
    let kap = r
        .remedies
        .first()
        .map(|x| x.cost.kappa.clone())
        .unwrap_or_default();
    for k in &kap {
        s += &format!(" c_T, κΔx = {k:.3} |");
    }
    for k in &kap {
        s += &format!(" c_L, κΔx = {k:.3} |");
    }
    s += "\n|---|";
    s += &"---|".repeat(2 * kap.len());
    s += "\n";
    for rem in &r.remedies {
        s += &format!("| {} |", rem.label);
        for e in rem.cost.transverse.iter().chain(&rem.cost.longitudinal) {
            s += &format!(" {e:+.4} |");
        }
        s += "\n";
    }
    // 4a. where the artificial stress is not differentiable
    let art: Vec<&str> = r
        .config
        .remedies
        .iter()
        .filter(|rem| rem.query.art_eps.is_some_and(|e| e > 0.0))
        .map(|rem| rem.label.as_str())
        .collect();
    let uniaxial = r.config.states.iter().any(|st| {
        matches!(
            st,
            StressState::UniaxialTension | StressState::UniaxialCompression
        )
    });
    if !art.is_empty() && uniaxial {
        s += &format!(
            "\nIn the uniaxial states the transverse principal pre-stress is exactly 0, a kink of the artificial \
             stress (R = −ε Σ_{{λ>0}} λ P_λ/ρ² switches on with the sign of the perturbation's own stress), so the \
             rows of {} there are the linearisation of that direction's compression side (`query` flags it: \
             `art_stress_kink`); a run may grow where they show none.\n",
            art.join(", ")
        );
    }
    // 4b. other lattices
    if !others.is_empty() {
        s += "\n## Other lattices\n\n";
        s += "The same remedies on the hexagonal lattice and in 3D (simple cubic; artificial stress has no 3D \
              form here), at ν = 0.3 on coarser grids, as `sphstab hourglass --config FILE` prints them:\n";
        for (file, o) in others {
            s += &format!("\n`{file}`:\n\n```text\n{}```\n", table(o));
            let compression = |rep: &HourglassReport| -> Vec<String> {
                rep.remedies
                    .iter()
                    .filter(|rem| {
                        rem.states.iter().any(|st| {
                            matches!(
                                st.state,
                                StressState::IsotropicCompression
                                    | StressState::UniaxialCompression
                            ) && st.onset_stress == Some(0.0)
                        })
                    })
                    .map(|rem| rem.label.clone())
                    .collect()
            };
            let (here, square) = (compression(o), compression(r));
            let new: Vec<&String> = here.iter().filter(|l| !square.contains(l)).collect();
            if !new.is_empty() {
                s += &format!(
                    "\nHere the hourglass modes of {} grow in compression too (onset 0), which they do not \
                     on the square lattice: which zero-energy modes a stress drives, and with which sign, \
                     depends on the lattice.\n",
                    new.iter()
                        .map(|l| l.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                );
            }
        }
    }
    // 5. the time domain
    if !experiments.is_empty() {
        s += "\n## The disc and the plate in the time domain\n\n";
        s += "As `sphstab simulate` runs them (analysis/scenes). The disc is the experiment the SPHinXsys group \
              proposes: a 2D disc of radius 8Δx (lattice points), held at a uniform isotropic tension by the boundary \
              load that makes the stressed rest state an equilibrium of each form. The plate is Gray, Monaghan & \
              Swift's cantilever (6 rows, L/H = 10, ν = 0.3975, clamped by the columns behind it), at rest. Each is \
              seeded with random velocities; the growth of max |v| is fitted over a window (for the plates after \
              `cycles` renormalisations, so that the fastest mode dominates the seed), against the fastest mode of \
              the exact operator of the same particle set (every eigenvalue) and of the infinite lattice (c/Δx).\n\n";
        s += "| scene | remedy | σ̄ | measured | predicted, body | measured / body | predicted, infinite lattice | max \\|v\\| at the end (c) |\n|---|---|---|---|---|---|---|---|\n";
        for (file, e) in experiments.iter().filter(|e| e.1.steps > 0) {
            s += &format!(
                "| `{}` | {} | {} | {} | {:.6} | {} | {:.6} | {:.3e} |\n",
                file,
                e.remedy,
                num(e.stress),
                e.measured_growth_rate
                    .map_or("none in the window".into(), |m| format!("{m:.6}")),
                e.predicted_growth_rate_body,
                if e.kink {
                    "— (kink)".into()
                } else {
                    e.ratio_body.map_or("—".into(), |x| format!("{x:.4}"))
                },
                e.predicted_growth_rate_infinite,
                e.max_velocity_end
            );
        }
        let grow: Vec<f64> = experiments.iter().filter_map(|d| d.1.ratio_body).collect();
        if !grow.is_empty() {
            let worst = grow.iter().map(|x| (x - 1.0).abs()).fold(0.0, f64::max);
            let differ: Vec<&str> = experiments
                .iter()
                .filter(|d| {
                    let (b, i) = (
                        d.1.predicted_growth_rate_body,
                        d.1.predicted_growth_rate_infinite,
                    );
                    !d.1.kink && (b > 2.0 * i || i > 2.0 * b)
                })
                .map(|d| d.1.remedy.as_str())
                .fold(Vec::new(), |mut v, r| {
                    if !v.contains(&r) {
                        v.push(r);
                    }
                    v
                });
            s += &format!(
                "\nWhere the body's operator grows, the measured growth is within {:.1}% of it ({} scenes). \
                 The body's and the infinite lattice's growth differ by more than a factor 2 for {}: \
                 the free surface (and the plate's clamp) changes which modes grow.\n",
                100.0 * worst,
                grow.len(),
                if differ.is_empty() {
                    "none".to_string()
                } else {
                    differ.join(", ")
                }
            );
            let at_rest: Vec<String> = experiments
                .iter()
                .filter(|d| {
                    d.1.steps > 0 && d.1.stress == 0.0 && d.1.predicted_growth_rate_body > 0.0
                })
                .map(|d| {
                    format!(
                        "{} (the {}, {:.6} c/Δx)",
                        d.1.remedy, d.1.experiment, d.1.predicted_growth_rate_body
                    )
                })
                .collect();
            if !at_rest.is_empty() {
                s += &format!(
                    "\nUnstressed, the body still grows for {}: no stress drives that growth, the finite \
                     body's operator is indefinite at its free surface (the lattice of the same form is stable); \
                     it is neither a tensile nor an hourglass instability.\n",
                    at_rest.join(", ")
                );
            }
        }
        let kinks: Vec<&str> = experiments
            .iter()
            .filter(|d| d.1.kink && d.1.steps > 0)
            .map(|d| d.0.as_str())
            .collect();
        if !kinks.is_empty() {
            s += &format!(
                "\nAt zero stress artificial stress sits on a kink of its rate (R ∝ the tensile part of the stress \
                 switches on with the sign of the perturbation's own stress), so no linear operator predicts its \
                 growth there ({}): the measured max |v| is reported alone.\n",
                kinks
                    .iter()
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        let osc: Vec<(&String, &ExperimentReport, &super::experiment::Oscillation)> = experiments
            .iter()
            .filter_map(|(f, e)| e.oscillation.as_ref().map(|o| (f, e, o)))
            .collect();
        if !osc.is_empty() {
            s += "\n### The oscillating plate and the breathing disc\n\n";
            s += "The same plate started in its first bending mode (Gray et al.'s velocity field, the tip at the \
                  speed given, 0.05 c0 = 0.044 c being the paper's): the period of the tip's deflection against \
                  Euler–Bernoulli's (plane strain, kL = 1.875) and against the same mode of the exact operator of \
                  the particle set at rest (its eigenvalue nearest Euler–Bernoulli's). The disc (radius 8Δx, \
                  unstressed) started in its first radial mode, u_r ∝ J1(kr), the rim at the speed given: the group's \
                  experiment, a disc with a radial velocity, in which isotropic tension comes and goes; the period of \
                  the rim's radial displacement against plane-strain elasticity's, (λ + 2G) kR J0(kR) = 2G J1(kR). \
                  For both, the fraction of the mode's energy lost per period (1 − (A_{n+1}/A_n)² of the positive \
                  peaks; negative: the peaks grew, energy exchanged with other modes), and when max |v| first exceeded twice the mode's initial speed (something else grew) or \
                  exceeded c (the run was stopped). No linear operator predicts a growth under a stress that comes \
                  and goes: these are measurements only.\n\n";
            s += "| scene | remedy | mode speed (c) | period (Δx/c) | continuum | error | body's operator | error | energy lost per period | first peak (Δx) | \\|v\\| above twice the mode's at | stopped at |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
            let t = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.1}"));
            for (file, e, o) in &osc {
                s += &format!(
                    "| `{}` | {} | {} | {} | {:.1} | {} | {} | {} | {} | {:.3} | {} | {} |\n",
                    file,
                    e.remedy,
                    num(o.mode_velocity),
                    t(o.period),
                    o.period_theory,
                    o.period_error
                        .map_or("—".into(), |x| format!("{:+.2}%", 100.0 * x)),
                    t(o.period_body),
                    o.period_error_body
                        .map_or("—".into(), |x| format!("{:+.2}%", 100.0 * x)),
                    o.energy_loss_per_period
                        .map_or("—".into(), |x| format!("{:.3}%", 100.0 * x)),
                    o.first_peak_displacement,
                    t(o.departed_at),
                    t(o.stopped_at),
                );
            }
        }
    }
    // 6. the answer
    s += "\n## The answer, from these numbers\n\n";
    for rem in &r.remedies {
        let tension: Vec<&StateReport> = rem
            .states
            .iter()
            .filter(|st| {
                matches!(
                    st.state,
                    StressState::IsotropicTension | StressState::UniaxialTension
                )
            })
            .collect();
        let from_zero = tension
            .iter()
            .filter(|st| st.onset_stress == Some(0.0))
            .count();
        let line = if rem.zero_energy_modes && from_zero > 0 {
            format!(
                "- **{}** has zero-energy modes at rest, and in tension they grow from zero stress: its tensile instability is the hourglass mode driven by the stress.",
                rem.label
            )
        } else if rem.zero_energy_modes {
            format!(
                "- **{}** has zero-energy modes at rest, but the stress does not drive them in tension (onsets {}).",
                rem.label,
                tension
                    .iter()
                    .map(|st| onset_cell(st.onset_stress, max))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        } else {
            let own: Vec<String> = remaining
                .iter()
                .filter(|x| x.0 == rem.label)
                .map(|x| {
                    format!(
                        "{} at ν = {} from |σ̄| = {:.4} ({:.2} G/C)",
                        x.1.name(),
                        num(x.2),
                        x.3,
                        x.3 / g_over_c(x.2)
                    )
                })
                .collect();
            if own.is_empty() {
                format!(
                    "- **{}** has no zero-energy mode and does not grow in any state up to |σ̄| = {} at any ν of the map.",
                    rem.label,
                    num(max)
                )
            } else {
                format!(
                    "- **{}** has no zero-energy mode, yet grows on modes with stiffness, a tensile instability: {}.",
                    rem.label,
                    own.join("; ")
                )
            }
        };
        s += &line;
        let rest: Vec<String> = experiments
            .iter()
            .filter(|d| {
                d.1.remedy == rem.label && d.1.stress == 0.0 && d.1.predicted_growth_rate_body > 0.0
            })
            .map(|d| {
                format!(
                    "the {} at {:.6} c/Δx",
                    d.1.experiment, d.1.predicted_growth_rate_body
                )
            })
            .fold(Vec::new(), |mut v, x| {
                // (the breathing disc's rest state is the unstressed disc's)
                if !v.contains(&x) {
                    v.push(x);
                }
                v
            });
        if !rest.is_empty() {
            s += &format!(
                " Unstressed, its finite bodies grow ({}): an indefinite operator at the free surface.",
                rest.join(", ")
            );
        }
        let osc: Vec<String> = experiments
            .iter()
            .filter_map(|d| d.1.oscillation.as_ref().map(|o| (d, o)))
            .filter(|(d, _)| d.1.remedy == rem.label)
            .map(|(d, o)| {
                let what = format!("the {} at {} c", d.1.experiment, num(o.mode_velocity));
                match (o.departed_at, o.period) {
                    (Some(t), _) => format!("{what} leaves its mode at t = {t:.1} Δx/c"),
                    (None, Some(p)) => format!(
                        "{what} oscillates with period {p:.1} Δx/c ({:+.1}% of the continuum's), losing {:.2}% of the mode's energy per period",
                        100.0 * o.period_error.unwrap_or(0.0),
                        100.0 * o.energy_loss_per_period.unwrap_or(0.0)
                    ),
                    (None, None) => {
                        format!("{what} stays in its mode but completes no period in the run")
                    }
                }
            })
            .collect();
        if !osc.is_empty() {
            s += &format!(" In the time domain, {}.", osc.join("; "));
        }
        s += "\n";
    }
    s
}
