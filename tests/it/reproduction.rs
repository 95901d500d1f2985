//! `REPRODUCTION.md`: one row per table and figure with numbers in the four seeds, the paper's
//! values next to sphstab's. Every sphstab number in that file is computed here, and the test
//! fails when the committed file differs from what the code produces now. To rewrite it after
//! a deliberate change: `SPHSTAB_WRITE_REPRODUCTION=1 cargo test --release --test it -- reproduction::`.
//!
//! The paper columns are transcribed from the seeds (`../shared/seeds/`); the agreement column
//! is computed from the two. Items not reproduced are listed with the reason, and the closing
//! tally counts the verdicts.

use crate::common;

use common::*;
use rayon::prelude::*;
use sphstab::forms::FormKind;
use sphstab::lattice::Lattice;
use sphstab::shape::{KernelParams, ShapeFamily};
use sphstab::vonneumann::antiplane::{AntiPlane, Quadrature};
use sphstab::vonneumann::closed_form as cf;
use std::f64::consts::PI;
use std::fmt::Write;

const MLS: ShapeFamily = ShapeFamily::Mls;

/// One row of the table.
struct Row {
    item: &'static str,
    shows: &'static str,
    how: &'static str,
    paper: String,
    ours: String,
    agree: String,
}

/// First κ in (0, π] where `w2` turns negative (grid of 20,000, then bisection); None if never.
fn onset(w2: impl Fn(f64) -> f64) -> Option<f64> {
    let n = 20_000;
    let mut lo = 0.0;
    let hi = (1..=n).map(|i| PI * i as f64 / n as f64).find(|&q| {
        let neg = w2(q) < 0.0;
        if !neg {
            lo = q;
        }
        neg
    })?;
    let (mut a, mut b) = (lo, hi);
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        if w2(m) < 0.0 { b = m } else { a = m }
    }
    Some(0.5 * (a + b))
}

fn list(v: &[f64], digits: usize) -> String {
    v.iter()
        .map(|x| format!("{x:.digits$}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// ✔ when `ok`, else ✘; `note` in parentheses. A row whose disagreement is a recorded erratum
/// says so in its note (rows are tallied by their first word: ✔, erratum, partly, ✘). A ✘ must
/// cite the erratum that explains it as `erratum Ek` (an entry of analysis/ERRATA.md), or the
/// test fails ([`unexplained_failures`]).
fn verdict(ok: bool, note: &str) -> String {
    match (ok, note.is_empty()) {
        (true, true) => "✔".into(),
        (true, false) => format!("✔ ({note})"),
        (false, true) => "✘".into(),
        (false, false) => format!("✘ ({note})"),
    }
}

/// The paper's value differs and an erratum explains it (`ok`: everything else agrees).
fn erratum(ok: bool, e: &str, note: &str) -> String {
    if ok {
        format!("erratum {e} ({note})")
    } else {
        format!("✘ (expected {e}: {note})")
    }
}

/// The erratum ids (`E1`, `E2`, …) that analysis/ERRATA.md defines (its `## Ek.` headings).
fn errata_ids() -> Vec<String> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("analysis/ERRATA.md");
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("## "))
        .filter_map(|l| l.split_once('.').map(|(id, _)| id))
        .filter(|id| {
            id.len() > 1 && id.starts_with('E') && id[1..].bytes().all(|b| b.is_ascii_digit())
        })
        .map(str::to_string)
        .collect()
}

/// The (item, verdict) pairs whose verdict is ✘ without an erratum: a ✘ passes only when it
/// cites `erratum Ek` with `Ek` one of `errata`. (`erratum(false, …)`'s "✘ (expected Ek: …)"
/// does not: the erratum was expected to explain the row and does not.)
fn unexplained_failures<'a>(
    verdicts: &[(&'a str, &'a str)],
    errata: &[String],
) -> Vec<(&'a str, &'a str)> {
    let cites_erratum = |v: &str| {
        v.match_indices("erratum E").any(|(i, m)| {
            let rest = &v[i + m.len() - 1..];
            let id: String = rest
                .chars()
                .take(1)
                .chain(rest.chars().skip(1).take_while(char::is_ascii_digit))
                .collect();
            errata.contains(&id)
        })
    };
    verdicts
        .iter()
        .filter(|(_, v)| v.starts_with('✘') && !cites_erratum(v))
        .copied()
        .collect()
}

/// [B00] Table I, the 2×2-cell column as printed (j, k, value).
const TABLE_I_2X2: &[(i64, i64, f64)] = &[
    (0, 0, 0.6507),
    (1, 0, 0.1016),
    (1, 1, -0.5933e-1),
    (2, 0, -0.8733e-1),
    (2, 1, -0.5223e-1),
    (2, 2, -0.8851e-2),
    (3, 0, -0.2663e-2),
    (3, 1, -0.8141e-3),
];

fn b00_table1() -> Row {
    let lat = Lattice::<2>::square(1.0).unwrap();
    let kp = KernelParams {
        kernel: k("efg-cubic"),
        h: 2.0,
    };
    let m = AntiPlane::new(&lat, Quadrature::Cell2x2, MLS, kp).unwrap();
    let table = m.stiffness_table().unwrap();
    let get = |j: i64, kk: i64| {
        table
            .iter()
            .find(|e| e.0 == j && e.1 == kk)
            .map_or(0.0, |e| e.2)
    };
    // half a unit of the 4th significant digit, as printed
    let worst = TABLE_I_2X2
        .iter()
        .map(|&(j, kk, v)| {
            let half = 0.5 * 10f64.powf(v.abs().log10().floor() - 3.0);
            (get(j, kk) - v).abs() / half
        })
        .fold(0.0, f64::max);
    let e32 = get(3, 2);
    let e32_one = {
        let m1 = AntiPlane::new(&lat, Quadrature::Cell1, MLS, kp).unwrap();
        let t = m1.stiffness_table().unwrap();
        t.iter().find(|e| e.0 == 3 && e.1 == 2).map_or(0.0, |e| e.2)
    };
    Row {
        item: "B00 Table I",
        shows: "2D anti-plane stiffness K_jk, EFG (mls, efg-cubic), D_mx = 2, γ = 1; four quadratures",
        how: "`sphstab stiffness --kernel efg-cubic --support 2 --shape mls --quadrature cell-2x2` (also `nodal`, `cell-1`, `stress-quad`); all columns: tests/it/antiplane.rs",
        paper: format!(
            "2×2 column: {}; (±3, ±2) = −0.9193e-5 printed under one point",
            TABLE_I_2X2
                .iter()
                .map(|&(j, kk, v)| format!("({j},{kk}) {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        ours: format!(
            "2×2 column within {worst:.2} half-units of the last printed digit; (3,2): 2×2 {e32:.4e}, one point {e32_one:.1e}"
        ),
        agree: erratum(
            worst <= 1.0 && (e32 - -0.9193e-5).abs() < 0.5e-9 && e32_one.abs() < 1e-12,
            "E7",
            "every value reproduced; the (±3, ±2) entry belongs to the 2×2 column",
        ),
    }
}

fn b00_table2() -> Row {
    let d = 1.5;
    let w = |f: FormKind| max_omega2(&lin(f, "efg-quartic", MLS, d, 0.0), 4096).0;
    let vals = [
        w(FormKind::EulerianNodal),
        w(FormKind::TotalLagrangian),
        w(FormKind::EulerianStressPoints),
        w(FormKind::LagrangianStressPoints),
    ];
    let paper = [1.0, 1.0, 4.0, 2.0];
    let same = |a: f64, b: f64| (a - b).abs() < 1e-6;
    let ok = [0, 1, 3].iter().all(|&i| same(vals[i], paper[i]));
    Row {
        item: "B00 Table II",
        shows: "max eigenvalue ω²Δx²/c², σ = 0, D_mx = 1.5: nodal (Eulerian, Lagrangian kernel), stress points (Eulerian, Lagrangian kernel)",
        how: "`sphstab timestep --form F --kernel efg-quartic --support 1.5 --shape mls --stress 0`, F = eulerian-nodal, total-lagrangian, eulerian-stress-points, lagrangian-stress-points",
        paper: list(&paper, 1),
        ours: list(&vals, 4),
        agree: erratum(
            ok && !same(vals[2], paper[2]),
            "E4",
            "3 of 4 equal; the Eulerian stress-point value is 2.0, not 4.0",
        ),
    }
}

fn b00_fig3() -> Row {
    let sig = [0.1, 0.2, 0.5, 1.0];
    let mut rows = Vec::new();
    for d in [1.5, 2.5] {
        let phi = shape_fn(MLS, "efg-quartic", d);
        let o: Vec<f64> = sig
            .iter()
            .map(|&s| onset(|q| cf::b00_eq74_eulerian_nodal(&phi, d, s, q)).unwrap() / PI)
            .collect();
        rows.push(o);
    }
    // "about 0.6π": the intermediate stresses' onsets at D_mx = 1.5 within [0.5π, 0.7π]
    let ok = rows[0][1..3].iter().all(|o| (0.5..0.7).contains(o));
    Row {
        item: "B00 Fig 3",
        shows: "eq 74 (EFG nodal integration, Eulerian kernel, quartic spline): tensile onset κ* vs σ̄, D_mx = 1.5 and 2.5",
        how: "`sphstab figures` → figures/b00_fig3a_eq74.svg, b00_fig3b_eq74.svg, b00_fig3_eq74_vs_engine.svg",
        paper: "unstable for κ > \"about 0.6π/Δx\" (D_mx = 1.5; σ̄ values lost with the figure); a larger support needs more tension".into(),
        ours: format!(
            "κ*/π at σ̄ = 0.1, 0.2, 0.5, 1: D_mx = 1.5: {}; 2.5: {}",
            list(&rows[0], 4),
            list(&rows[1], 4)
        ),
        agree: verdict(
            ok && (0..4).all(|c| rows[1][c] > rows[0][c]),
            "read as σ̄ = 0.2, 0.5 in [0.5π, 0.7π]; E3: the exact EFG equations are stable at D_mx = 1.5",
        ),
    }
}

fn b00_fig9() -> Row {
    let l = lin(FormKind::EulerianStressPoints, "efg-quartic", MLS, 2.5, 1.0);
    let g = grid(1024);
    let unstable: Vec<f64> = g
        .iter()
        .copied()
        .filter(|&q| l.omega2(q).0 < -1e-12)
        .collect();
    let small = lin(FormKind::EulerianStressPoints, "efg-quartic", MLS, 1.5, 1.0);
    let small_ok = g.iter().all(|&q| small.omega2(q).0 >= -1e-12);
    let at_pi = l.omega2(PI).0;
    Row {
        item: "B00 Fig 9",
        shows: "stress points, Eulerian kernel (quartic spline), σ̄ = 1: ω² vs κ, D_mx = 1.5 and 2.5",
        how: "`sphstab figures` → figures/b00_fig9_stress_points.svg; `sphstab query --form eulerian-stress-points --kernel efg-quartic --shape mls --support 2.5 --stress 1`",
        paper: "no tensile instability at small support; at D_mx = 2.5 an instability at the cut-off wave number for σ̄ = 1".into(),
        ours: format!(
            "D_mx = 1.5: stable ({}); D_mx = 2.5: unstable for κΔx/π ∈ [{:.3}, 1], ω²(π) = {at_pi:.4}",
            if small_ok { "ω² ≥ 0 on 1,024 κ" } else { "UNSTABLE" },
            unstable.first().map_or(f64::NAN, |q| q / PI)
        ),
        agree: verdict(
            small_ok && at_pi < 0.0,
            "E3: eq 93 assumes rigid shape functions; exact with sph shapes",
        ),
    }
}

fn b00_fig10() -> Row {
    let ds = [1.5, 2.0, 2.5, 3.0, 3.5];
    let lins: Vec<_> = ds
        .iter()
        .map(|&d| lin(FormKind::LagrangianStressPoints, "efg-cubic", MLS, d, 0.0))
        .collect();
    let w: Vec<f64> = lins.iter().map(|l| l.omega2(PI).0).collect();
    let ok = w.iter().zip(ds).all(|(&v, d)| (d < 3.0) == (v > 1e-2));
    // two-node linear elements, lumped mass: ω² = 4 sin²(κ/2) (derived); EFG below it for
    // κΔx ≥ π/2 at every D_mx
    let fe = |q: f64| 4.0 * (0.5 * q).sin().powi(2);
    let below = lins.iter().all(|l| {
        grid(256)
            .into_iter()
            .filter(|&q| q >= 0.5 * PI)
            .all(|q| l.omega2(q).0 <= fe(q))
    });
    Row {
        item: "B00 Fig 10",
        shows: "stress points, Lagrangian kernel (cubic spline): ω² vs κ for D_mx = 1.5–3.5, against linear FE (lumped mass)",
        how: "`sphstab figures` → figures/b00_fig10_lagrangian_stress_points.svg (with the linear-FE lumped-mass curve)",
        paper: "no rank-deficient mode; frequency very small near the cut-off for D_mx ≥ 3.0 (§4.2.2); linear FE with lumped mass for comparison"
            .into(),
        ours: format!(
            "ω²(π)Δx²/c² at D_mx = 1.5, 2, 2.5, 3, 3.5: {}; linear FE lumped ω² = 4 sin²(κΔx/2) (derived), {:.1} at π; every EFG curve below it for κΔx ≥ π/2: {below}",
            w.iter()
                .map(|x| format!("{x:.3e}"))
                .collect::<Vec<_>>()
                .join(", "),
            fe(PI)
        ),
        agree: verdict(ok, "read as ω²(π) < 1e-2 exactly for D_mx ≥ 3"),
    }
}

fn b00_fig11() -> Row {
    let mut parts = Vec::new();
    let mut all_positive = true;
    for (d, alphas) in [
        (1.5, [0.001, 0.01, 0.1, 0.5]),
        (2.5, [0.001, 0.01, 0.1, 0.5]),
    ] {
        let w: Vec<f64> = alphas
            .iter()
            .map(|&a| {
                let mut p = params(FormKind::LeastSquares, "efg-quartic", MLS, d);
                p.alpha_s = a;
                let l = sphstab::vonneumann::linearise::Linearisation::new(
                    p,
                    0.0,
                    sphstab::vonneumann::linearise::Lattice1D::default(),
                )
                .unwrap();
                let min = grid(512)
                    .into_iter()
                    .map(|q| l.omega2(q).0)
                    .fold(f64::INFINITY, f64::min);
                all_positive &= min > 0.0;
                l.omega2(PI).0
            })
            .collect();
        parts.push(format!("D_mx = {d}: {}", list(&w, 4)));
    }
    Row {
        item: "B00 Fig 11",
        shows: "least-squares-stabilised nodal integration (eq 108), σ = 0: ω² vs κ for several α_s, D_mx = 1.5 and 2.5",
        how: "`sphstab figures` → figures/b00_fig11_least_squares.svg; `sphstab query --form least-squares --kernel efg-quartic --support 2.5 --stress 0 --alpha-s 0.5`",
        paper: "α_s = 0.001 not significant; any α_s removes the spurious mode at small dilation; at D_mx ≥ 2.5 a large α_s makes ω vanish or imaginary".into(),
        ours: format!(
            "ω²(π)Δx²/c² at α_s = 0.001, 0.01, 0.1, 0.5: {}; ω² > 0 on 512 κ for all: {all_positive}",
            parts.join("; ")
        ),
        agree: erratum(
            all_positive,
            "E9",
            "the small-dilation statements hold; no failure at D_mx = 2.5 with the exact φ'' on the nodes, reproduced only without W''(0)",
        ),
    }
}

fn v21_fig12() -> Row {
    use sphstab::studies::swegle::{SwegleConfig, run_swegle};
    let run = |form, f| {
        let cfg = SwegleConfig::new(form, k("m4"), 1.2, f);
        run_swegle(&cfg, |_| {}).unwrap()
    };
    let c99 = run(FormKind::Classical, 0.99);
    let c95 = run(FormKind::Classical, 0.95);
    let n99 = run(FormKind::Nonlocal, 0.99);
    let g99 = c99.measured_growth_rate.unwrap_or(f64::NAN);
    let g95 = c95.measured_growth_rate.unwrap_or(f64::NAN);
    let nonlocal_flat = n99.max_velocity_end < 2.0 * 1e-10;
    Row {
        item: "V21 Figs 10, 12",
        shows: "Swegle test (21×21, 3 fixed layers, ρ0 = 2.8, K = 0.686275): centre-particle speed vs time, classical and nonlocal, several density fractions",
        how: "`sphstab figures` → figures/v21_fig12_swegle.svg (Fig 12: centre-particle histories with the box prediction's slope, ρ/ρ0 = 0.95, 0.99, 1.01, 1.05); `sphstab swegle --form classical --kernel m4 --h 1.2 --density-ratio 0.99` (0.95; `--form nonlocal`); kernel and h are sphstab's choice (V21 does not state them)",
        paper: "classical unstable in tension, growth \"proportional to the level of stress\"; nonlocal no growth".into(),
        ours: format!(
            "classical growth in the box {g99:.4} (ρ/ρ0 = 0.99), {g95:.4} (0.95) c/Δx: ratio {:.2} for ×5 tension (infinite lattice {:.4}, {:.4}: ratio {:.2}); nonlocal max speed {:.2e} (kick 1e-10)",
            g95 / g99,
            c99.predicted_growth_rate_infinite,
            c95.predicted_growth_rate_infinite,
            c95.predicted_growth_rate_infinite / c99.predicted_growth_rate_infinite,
            n99.max_velocity_end
        ),
        agree: if g99 > 0.0 && nonlocal_flat && (g95 / g99) < 4.0 {
            format!(
                "partly (classical unstable and nonlocal stable ✔; growth ×{:.2} for ×5 tension: not proportional, note N1)",
                g95 / g99
            )
        } else {
            verdict(false, "")
        },
    }
}

fn b00_fig5() -> Row {
    let w: Vec<f64> = [FormKind::EulerianNodal, FormKind::TotalLagrangian]
        .iter()
        .map(|&f| lin(f, "efg-quartic", MLS, 1.5, 0.0).omega2(PI).0)
        .collect();
    Row {
        item: "B00 Fig 5",
        shows: "the spurious mode u_l = (−1)^l of nodal integration at κΔx = π (σ = 0, D_mx = 1.5)",
        how: "`sphstab query --form total-lagrangian --kernel efg-quartic --support 1.5 --shape mls --stress 0` (kind rank-deficiency at κΔx/π = 1)",
        paper: "ω = 0 at κΔx = π for eq 74 (Eulerian) and eq 82 (Lagrangian kernel)".into(),
        ours: format!(
            "ω²(π)Δx²/c²: Eulerian {:.1e}, Lagrangian {:.1e}",
            w[0], w[1]
        ),
        agree: verdict(w.iter().all(|v| v.abs() < 1e-12), ""),
    }
}

fn b00_figs13_15() -> Row {
    let lat = Lattice::<2>::square(1.0).unwrap();
    let kp = KernelParams {
        kernel: k("efg-cubic"),
        h: 2.0,
    };
    let cases = [
        (Quadrature::Nodal, "nodal", (true, true)),
        (Quadrature::Cell1, "one-point cells", (false, true)),
        (Quadrature::Cell2x2, "2×2 cells", (false, false)),
        (
            Quadrature::StressQuad,
            "stress points, quadrilateral",
            (false, true),
        ),
        (
            Quadrature::StressTri,
            "stress points, triangle",
            (false, false),
        ),
    ];
    let mut parts = Vec::new();
    let mut ok = true;
    for (q, name, want) in cases {
        let got = AntiPlane::new(&lat, q, MLS, kp)
            .unwrap()
            .spurious_at_cutoff(1.0)
            .unwrap();
        ok &= got == want;
        let at = match got {
            (true, true) => "θ = 0° and 45°",
            (false, true) => "θ = 45° only",
            (true, false) => "θ = 0° only",
            (false, false) => "none",
        };
        parts.push(format!("{name}: {at}"));
    }
    Row {
        item: "B00 Figs 13–15",
        shows: "2D anti-plane waves (EFG, efg-cubic, D_mx = 2): ωΔx/c vs κ per propagation angle, for nodal, cell and stress-point quadratures",
        how: "`sphstab figures` → figures/b00_fig13_antiplane_nodal.svg, b00_fig14_antiplane_cells.svg, b00_fig15_antiplane_stress_points.svg; `sphstab stiffness --kernel efg-cubic --support 2 --shape mls --quadrature Q --theta θ` (Q = nodal, cell-1, cell-2x2, stress-quad, stress-tri)",
        paper: "zero frequency at the cut-offs: nodal at θ = 0° and 45°; one-point cells and quadrilateral stress points at 45° only; 2×2 cells and triangle stress points none".into(),
        ours: format!(
            "spurious zero-frequency modes at the cut-off: {}",
            parts.join("; ")
        ),
        agree: verdict(ok, ""),
    }
}

fn v21_fig7() -> Row {
    let growth = |f: FormKind, sig: f64| {
        let l = lin(f, "m4", ShapeFamily::Sph, 1.2, sig);
        grid(512)
            .into_iter()
            .map(|q| (-l.omega2(q).0).max(0.0).sqrt())
            .fold(0.0, f64::max)
    };
    let (ct, cc) = (
        growth(FormKind::Classical, 0.1),
        growth(FormKind::Classical, -0.1),
    );
    let (nt, nc) = (
        growth(FormKind::Nonlocal, 0.1),
        growth(FormKind::Nonlocal, -0.1),
    );
    Row {
        item: "V21 Fig 7",
        shows: "Swegle's criterion W''σ > 0 (sum form unstable) and V21's reversed criterion W''σ < 0 for the difference forms (m4, h = 1.2Δx, q* = 2/3)",
        how: "`sphstab figures` → figures/forms_in_tension_m4.svg; `sphstab query --form nonlocal --kernel m4 --h 1.2 --stress 0.1` (and `--stress -0.1`)",
        paper: "sum form unstable in tension (W''σ > 0 at the neighbours); difference form unstable when W''σ < 0".into(),
        ours: format!(
            "max growth (c/Δx) at σ̄ = +0.1 / −0.1: classical {ct:.4} / {cc:.4}; nonlocal {nt:.1e} / {nc:.1e}"
        ),
        agree: erratum(
            ct > 1e-3 && cc < 1e-9 && nt < 1e-9 && nc < 1e-9,
            "E2",
            "Swegle's criterion holds for the sum form; the difference form is stable in tension and compression",
        ),
    }
}

// ---------------------------------------------------------------------------------------------
// Time-domain rows (the solver of `simulate` and `swegle`) and the thesis rows.

use sphstab::solver::output::FinalState;
use sphstab::solver::scene::{self, InitialVelocity, Scene, SceneReport};
use sphstab::studies::swegle::{SwegleConfig, run_swegle};

/// A built-in scene changed by `edit`, then sent through the JSON route of `simulate FILE`
/// (serialised and parsed back, so every field is validated as a scene file is).
fn scene_with(name: &str, edit: impl FnOnce(&mut Scene)) -> Scene {
    let mut s = scene::builtin(name).unwrap();
    edit(&mut s);
    scene::parse(&s.name, &serde_json::to_string(&s).unwrap()).unwrap()
}

/// Reference positions X_i = origin + iΔx and Δx of a scene.
fn ref_x(s: &Scene) -> (Vec<f64>, f64) {
    let dx = s.length / (s.particles - 1) as f64;
    (
        (0..s.particles).map(|i| s.origin + i as f64 * dx).collect(),
        dx,
    )
}

/// The stress a scene's form reports: σ, or for the mixed forms (1 − c)σ + cτ (each of σ and
/// τ is integrated from its own velocity gradient; the mix is what the momentum equation uses).
/// A 1D state's fields as plain arrays (the model's D = 1 state holds `[f64; 1]` and
/// `[[f64; 1]; 1]` entries).
struct Bar {
    x: Vec<f64>,
    v: Vec<f64>,
    sigma: Vec<f64>,
    tau: Vec<f64>,
}

impl From<FinalState> for Bar {
    fn from(z: FinalState) -> Self {
        let FinalState::One(z) = z else {
            panic!("a 1D scene's final state")
        };
        Bar {
            x: z.x.iter().map(|[a]| *a).collect(),
            v: z.v.iter().map(|[a]| *a).collect(),
            sigma: z.sigma.iter().map(|[[a]]| *a).collect(),
            tau: z.tau.iter().map(|[[a]]| *a).collect(),
        }
    }
}

fn total_stress(s: &Scene, z: &Bar) -> Vec<f64> {
    if z.tau.is_empty() {
        z.sigma.clone()
    } else {
        let c = s.c_partition;
        z.sigma
            .iter()
            .zip(&z.tau)
            .map(|(a, b)| (1.0 - c) * a + c * b)
            .collect()
    }
}

fn run_scene(s: &Scene) -> (SceneReport, Bar) {
    let mut r = s.run(|_| {}).unwrap();
    let z = r.final_state.take().unwrap();
    (r, z.into())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// [V21 §7.1] uniform bar: the analytic stress of sphstab's 1D law. The particles keep
/// v = g X (the stress is uniform, so no force acts), x = X(1 + g t), F = 1 + g t and
/// ∂v/∂x = g/(1 + g t); σ̇ = (C + σ) ∂v/∂x integrates to C + σ = C(1 + g t), i.e.
/// **σ = C g t** exactly (Truesdell; not C(e^{gt} − 1), which a constant ∂v/∂x would give).
fn v21_uniform(tension: bool) -> Row {
    let g = if tension { 0.001 } else { -0.001 };
    let forms = ["nonlocal", "local", "lnl"];
    let mut parts = Vec::new();
    let mut worst: f64 = 0.0;
    for t in [1.0, 10.0] {
        let mut devs = Vec::new();
        let mut exact = 0.0;
        for f in forms {
            let s = scene_with("uniform-bar", |s| {
                s.name = "uniform-bar-v21".into();
                s.initial_velocity = InitialVelocity::Linear { gradient: g };
                s.form = f.into();
                s.t_end = t;
            });
            exact = s.modulus * g * t;
            let (_, z) = run_scene(&s);
            let st = total_stress(&s, &z);
            let l = s.left.as_ref().unwrap().layers;
            let n = s.particles;
            let dev = (l..n - l)
                .map(|i| (st[i] - exact).abs())
                .fold(0.0, f64::max)
                / exact.abs();
            worst = worst.max(dev);
            devs.push(dev);
        }
        parts.push(format!(
            "t = {t}: σ_exact = {exact:.3}; max |σ − σ_exact|/|σ_exact| over the free particles: nonlocal {:.1e}, local {:.1e}, lnl {:.1e}",
            devs[0], devs[1], devs[2]
        ));
    }
    let good = worst <= 0.05;
    if tension {
        let s = scene_with("uniform-bar", |s| s.form = "classical".into());
        let classical = match s.run(|_| {}) {
            Ok(r) => (
                format!(
                    "classical reaches t = {:.0} with velocity error {:.2} (max |v| {:.2e}, exact max {:.1e})",
                    r.t,
                    r.velocity_error_l2.unwrap_or(f64::NAN),
                    r.max_velocity,
                    g * s.origin.abs().max(s.origin + s.length)
                ),
                r.velocity_error_l2.unwrap_or(f64::INFINITY) > 1.0,
            ),
            Err(e) => (format!("classical diverges: {e}"), true),
        };
        Row {
            item: "V21 Figs 9, 16 (1D)",
            shows: "1D uniform tension (bar of length 1, 100 particles, v = 0.001x, 3 prescribed particles per end, ρ0 = 8, E = 2; m4 and h = 1.3Δx are sphstab's choice: §7.1 gives neither kernel nor h, h = 1.3Δx is V21's value for §7.4): stress at t = 1 and 10",
            how: "`sphstab figures` → figures/v21_fig9_uniform_tension.svg; `sphstab simulate uniform-bar --form nonlocal --t-end 1 --out DIR` (also `--form local`, `lnl`; stress in final.vtk); `sphstab simulate uniform-bar --form classical --json`",
            paper: "nonlocal, local, lnl: \"good agreement with the analytical solutions\"; classical \"unstable and did not reach a solution time of t = 10.0\" (§7.1); analytic σ not printed".into(),
            ours: format!(
                "analytic σ = E g t (derived for sphstab's law, see the test); {}; {}",
                parts.join("; "),
                classical.0
            ),
            agree: verdict(
                good && classical.1,
                "read as max deviation ≤ 5%; classical's instability reproduced: it runs to t = 10 here because sphstab stops a run only above 1000 × (c + v)",
            ),
        }
    } else {
        Row {
            item: "V21 Figs 8, 15 (1D)",
            shows: "1D uniform compression (as Figs 9, 16 with v = −0.001x; m4 and h = 1.3Δx are sphstab's choice, §7.1 gives neither): stress at t = 1 and 10",
            how: "a scene file = the built-in `uniform-bar` with `\"initial_velocity\": {\"kind\": \"linear\", \"gradient\": -0.001}`: `sphstab simulate FILE --form nonlocal --t-end 1 --out DIR` (also `local`, `lnl`)",
            paper: "local, nonlocal and mixed forms in \"good agreement with the analytical solutions\" (§7.1)".into(),
            ours: format!("analytic σ = E g t; {}", parts.join("; ")),
            agree: verdict(good, "read as max deviation ≤ 5%"),
        }
    }
}

/// [V21 §7.2, Fig 11]: visible clumping at t = 30 and 42 (V21's time units; 1 c/Δx = 4.951 per
/// unit). Criterion fixed before the runs: a free particle has moved ≥ 1e-2 Δx from its lattice
/// site.
fn v21_fig11() -> Row {
    let crit = 1e-2;
    let mut parts = Vec::new();
    let mut seen = Vec::new();
    for t in [30.0, 42.0] {
        let mut cfg = SwegleConfig::new(FormKind::Classical, k("m4"), 1.2, 0.99);
        cfg.t_end = t;
        let x0 = cfg.build::<2>().unwrap().z.x.clone();
        let r = run_swegle(&cfg, |_| {}).unwrap();
        let last = *r.history_full.last().unwrap();
        let Some(FinalState::Two(z)) = r.final_state else {
            panic!("2D run")
        };
        let umax =
            z.x.iter()
                .zip(&x0)
                .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
                .fold(0.0, f64::max)
                / cfg.dx;
        seen.push(umax >= crit);
        let stopped = if last[0] < t - 1e-9 {
            format!(
                " (the run stops at t = {:.1}: max |v| passed 0.1c, the nonlinear regime)",
                last[0]
            )
        } else {
            String::new()
        };
        parts.push(format!(
            "t = {t}: max displacement {umax:.2e} Δx, max |v| {:.2e} c{stopped}",
            last[2] / cfg.sound_speed()
        ));
    }
    Row {
        item: "V21 Fig 11",
        shows: "Swegle test, classical (sum) form, ρ/ρ0 = 0.99: particle positions and x-velocity at t = 30 and 42 (clumping)",
        how: "`sphstab swegle --form classical --kernel m4 --h 1.2 --density-ratio 0.99 --t-end 30 --out DIR` (and `--t-end 42`; positions and velocity in final.vtk); kernel and h are sphstab's choice",
        paper: "visible clumping at t = 30 and t = 42 (picture; §7.2)".into(),
        ours: parts.join("; "),
        agree: match (seen[0], seen[1]) {
            (true, true) => verdict(
                true,
                "criterion fixed before the run: clumping is visible when a particle has moved ≥ 1e-2 Δx",
            ),
            (false, true) => "partly (clumping visible at t = 42 ✔, not yet at t = 30 by the criterion fixed before the run, a particle moved ≥ 1e-2 Δx; the growth rate depends on the kernel and h, which V21 does not give)".into(),
            _ => verdict(false, "no particle moved ≥ 1e-2 Δx by t = 42"),
        },
    }
}

/// [V21 §7.2, Fig 13]: the classical–local mix at constant c; growth should fall as c rises.
fn v21_fig13() -> Row {
    let cs = [0.0, 0.25, 0.5, 0.75, 1.0];
    let mut parts = Vec::new();
    let mut ok = true;
    for f in [0.99, 0.95] {
        let mut meas = Vec::new();
        let mut boxr = Vec::new();
        for &c in &cs {
            let mut cfg = SwegleConfig::new(FormKind::Cll, k("m4"), 1.2, f);
            cfg.c_partition = c;
            let r = run_swegle(&cfg, |_| {}).unwrap();
            meas.push(r.measured_growth_rate.unwrap_or(0.0));
            boxr.push(r.predicted_growth_rate_box);
        }
        let dec = |v: &[f64]| {
            v.windows(2)
                .all(|w| w[1] < w[0] || (w[0] == 0.0 && w[1] == 0.0))
        };
        ok &= dec(&meas) && dec(&boxr);
        parts.push(format!(
            "ρ/ρ0 = {f}: measured {} (box operator {}) c/Δx",
            list(&meas, 4),
            list(&boxr, 4)
        ));
    }
    Row {
        item: "V21 Fig 13",
        shows: "Swegle test, mixed classical–local form (cll), centre-particle speed for several c, ρ/ρ0 = 0.99 and 0.95",
        how: "`sphstab figures` → figures/v21_fig13_cll.svg; `sphstab swegle --form cll --c C --kernel m4 --h 1.2 --density-ratio 0.99 --json` (C = 0, 0.25, 0.5, 0.75, 1; also 0.95)",
        paper: "increasing c reduces the growth rate; c = 0.5 and c-calculated (eq 49, 0.497 < c < 0.502) almost identical (§7.2); Fig 13's caption and text name no other c (V21's only list of c values is Fig 17's caption, for the lnl compressive wave: 0, 0.25, 0.5, 0.75, 1.0 and calculated; its constant values are used here)".into(),
        ours: format!(
            "growth at c = 0, 0.25, 0.5, 0.75, 1: {} (0: no growth)",
            parts.join("; ")
        ),
        agree: if ok {
            "partly (growth falls monotonically with c ✔; c-calculated needs code: sphstab has one constant c per run, eq 49's per-particle c is not implemented)".into()
        } else {
            verdict(false, "growth not monotonic in c")
        },
    }
}

/// Compressive-wave profile measures at the scene's t_end: (plateau stress behind the front,
/// front offset from c t in Δx).
fn compressive_front(s: &Scene) -> (f64, f64, Bar) {
    let (_, z) = run_scene(s);
    let (x, dx) = ref_x(s);
    let wall = s.origin + (s.left.as_ref().unwrap().layers - 1) as f64 * dx;
    let c = (s.modulus / s.rho0).sqrt();
    let ct = c * s.t_end;
    let st = total_stress(s, &z);
    let plateau = median(
        (0..s.particles)
            .filter(|&i| (0.2 * ct..=0.8 * ct).contains(&(x[i] - wall)))
            .map(|i| st[i])
            .collect(),
    );
    let v0 = match s.initial_velocity {
        InitialVelocity::Uniform { value } => value,
        _ => unreachable!(),
    };
    let front = (0..s.particles)
        .find(|&i| x[i] > wall && z.v[i].abs() > 0.5 * v0.abs())
        .map_or(f64::NAN, |i| x[i]);
    (plateau, (front - wall - ct) / dx, z)
}

/// [V21 §7.4, Figs 17 and 18a].
fn v21_figs17_18() -> [Row; 3] {
    let base = scene::builtin("compressive-wave").unwrap();
    let c = (base.modulus / base.rho0).sqrt();
    let v0 = 50.0;
    let exact = -base.rho0 * c * v0;
    let nu: f64 = 0.3;
    let c_l = (base.modulus * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * base.rho0)).sqrt();
    let forms = [
        ("classical", 0.5),
        ("nonlocal", 0.5),
        ("local", 0.5),
        ("lnl", 0.5),
    ];
    let mut plateaus = Vec::new();
    let mut fronts = Vec::new();
    for (f, cp) in forms {
        let s = scene_with("compressive-wave", |s| {
            s.form = f.into();
            s.c_partition = cp;
        });
        let (p, fr, _) = compressive_front(&s);
        plateaus.push(p);
        fronts.push(fr);
    }
    // the caption's c set for lnl: 0, 0.25, 0.5, 0.75, 1 (and c from eq 49: needs code); the
    // text: "the curves lie between the curves for c values equal to 0 and equal to 1"
    let cs = [0.0, 0.25, 0.5, 0.75, 1.0];
    let sweep: Vec<(f64, f64)> = cs
        .iter()
        .map(|&cp| {
            let s = scene_with("compressive-wave", |s| {
                s.form = "lnl".into();
                s.c_partition = cp;
            });
            let (p, fr, _) = compressive_front(&s);
            (p, fr)
        })
        .collect();
    let mag_ok = plateaus
        .iter()
        .chain(sweep.iter().map(|r| &r.0))
        .all(|p| (p / exact - 1.0).abs() <= 0.05);
    let (f0, f1) = (sweep[0].1, sweep[4].1);
    let between_ok = sweep[1..4]
        .iter()
        .all(|r| r.1 >= f0.min(f1) - 0.5 && r.1 <= f0.max(f1) + 0.5);
    let speed_ok = fronts[0].abs() <= 3.0
        && fronts[1].abs() <= 3.0
        && fronts[3] >= fronts[1].min(fronts[2]) - 0.5
        && fronts[3] <= fronts[1].max(fronts[2]) + 0.5;
    let (x, dx) = ref_x(&base);
    let wall = base.origin + 2.0 * dx;
    let t_arrive = (x[base.particles - 1] - wall) / c;
    // long-wave speed of the unnormalised sph gradient (classical, nonlocal) on the lattice:
    // √ω²/κ of `nonlocal` (ω² = C̃ S1²) at small κ; the expected front lead over c t in Δx
    let kap = 1e-3;
    let gain = lin(
        FormKind::Nonlocal,
        "m4",
        ShapeFamily::Sph,
        base.h_over_dx,
        0.0,
    )
    .omega2(kap)
    .0
    .sqrt()
        / kap;
    let lead = (gain - 1.0) * c * base.t_end / dx;
    let fig17 = Row {
        item: "V21 Fig 17",
        shows: "compressive wave from a rigid wall (5 cm steel bar, v0 = 50 m/s, E = 200 GPa, ρ = 8000, 500 particles, h = 1.3Δx, viscosity 0.5; m4: sphstab's choice, V21 names no kernel), before the free-end reflection",
        how: "`sphstab figures` → figures/v21_fig17_compressive_wave.svg; `sphstab simulate compressive-wave --form F --out DIR` (F = classical, nonlocal, local, lnl; stress in final.vtk; t = 5 μs); lnl with c = C: a scene file = `compressive-wave` with `\"form\": \"lnl\", \"c_partition\": C`",
        paper: format!(
            "all forms \"predict the correct compressive stress magnitude\"; classical and nonlocal close to the analytic wave speed, lnl half-way between local and nonlocal; caption: lnl \"with different values of the c coefficient: 0, 0.25, 0.5, 0.75, 1.0 and calculated using density-based criterion\", and \"the curves lie between the curves for c values equal to 0 and equal to 1\" (§7.4); caption t = 10 μs; analytic σ = −ρ c v0 = {:.3} GPa (c = √(E/ρ); {:.3} GPa with c_L, ν = 0.3)",
            exact / 1e9,
            -base.rho0 * c_l * v0 / 1e9
        ),
        ours: format!(
            "at t = {:.0} μs (V21's 10 μs is the free-end arrival {:.2} μs for c = √(E/ρ), E13): plateau (median over 0.2–0.8 ct behind the wall) classical, nonlocal, local, lnl(c = 0.5): {} GPa; front (|v| = v0/2) − c t: {} Δx",
            base.t_end * 1e6,
            t_arrive * 1e6,
            list(&plateaus.iter().map(|p| p / 1e9).collect::<Vec<_>>(), 3),
            list(&fronts, 1)
        ) + &format!(
            "; lnl at c = 0, 0.25, 0.5, 0.75, 1 (the caption's set): plateau {} GPa, front − c t {} Δx",
            list(&sweep.iter().map(|r| r.0 / 1e9).collect::<Vec<_>>(), 3),
            list(&sweep.iter().map(|r| r.1).collect::<Vec<_>>(), 1)
        ) + &format!(
            "; the sph gradient's long-wave speed on the lattice is {gain:.5} c (h = 1.3Δx), a lead of {lead:.1} Δx at {:.0} μs (the local form's corrected gradient is exact)",
            base.t_end * 1e6
        ),
        agree: if mag_ok && speed_ok && between_ok {
            verdict(
                true,
                "read as plateau within 5%, classical and nonlocal fronts within 3Δx of c t, lnl's between local's and nonlocal's, every lnl front between those of c = 0 and c = 1 (±0.5Δx); c-calculated needs code (eq 49)",
            )
        } else if mag_ok {
            let mark = |ok: bool| if ok { "✔" } else { "✘" };
            let half_way = fronts[3] >= fronts[1].min(fronts[2]) - 0.5
                && fronts[3] <= fronts[1].max(fronts[2]) + 0.5;
            let on_time = fronts[0].abs() <= 3.0 && fronts[1].abs() <= 3.0;
            format!(
                "partly (stress magnitude ✔ for every form and every c, within 5%; lnl(0.5) between local and nonlocal {}; lnl fronts at c = 0.25, 0.5, 0.75 between those of c = 0 and c = 1 (±0.5Δx) {}; classical and nonlocal fronts within 3Δx of c t {}{}; c-calculated needs code, eq 49)",
                mark(half_way),
                mark(between_ok),
                mark(on_time),
                if on_time {
                    ""
                } else {
                    ": they lead by the lattice speed of the sph gradient while local is on time — V21 finds classical and nonlocal closest"
                }
            )
        } else {
            verdict(false, "plateau off by more than 5%")
        },
    };
    // Fig 18a: after the reflection; t = 12 μs, 2 μs after the arrival (E13)
    let t18 = 12e-6;
    let unloaded_zone = |f: &str, cp: f64, layers: usize| {
        let s = scene_with("compressive-wave", |s| {
            s.form = f.into();
            s.c_partition = cp;
            s.t_end = t18;
            s.classical_layers = [0, layers];
        });
        let (_, z) = run_scene(&s);
        let st = total_stress(&s, &z);
        let xr = x[base.particles - 1] - c * (t18 - t_arrive);
        let sel: Vec<f64> = (0..base.particles)
            .filter(|&i| x[i] >= xr + 10.0 * dx)
            .map(|i| st[i].abs())
            .collect();
        sel.iter().sum::<f64>() / sel.len() as f64 / exact.abs()
    };
    let unloaded: Vec<f64> = forms
        .iter()
        .map(|&(f, cp)| unloaded_zone(f, cp, 0))
        .collect();
    // Fig 18b: the last four particles in the classical (plus) form [V21 §7.4]
    let treated: Vec<f64> = forms[1..]
        .iter()
        .map(|&(f, cp)| unloaded_zone(f, cp, 4))
        .collect();
    let fig18b = Row {
        item: "V21 Fig 18(b)",
        shows: "release wave with the last 4 particles at the free end in the classical form: nonlocal, local, lnl",
        how: "`sphstab simulate analysis/scenes/release-wave-classical-layer.json --form F` (the built-in `compressive-wave` with `\"classical_layers\": [0, 4]`, t = 12 μs); `sphstab figures` → figures/v21_fig18_release_wave.svg",
        paper: "\"the results for all formulations now closely match the analytical solution\" (§7.4, Fig 18(b); caption t = 10 μs)".into(),
        ours: format!(
            "t = {:.0} μs, mean |σ|/ρcv0 in the unloaded zone (as Fig 18(a)) nonlocal, local, lnl: {} (without the layer: {})",
            t18 * 1e6,
            list(&treated, 3),
            list(&unloaded[1..], 3)
        ),
        agree: verdict(
            treated.iter().all(|&u| u < 0.1),
            "read as physical when the mean |σ| there is < 10% of ρcv0, as Fig 18(a); the layer's particles take the classical kernel gradient (for local, not its corrected one, which sees no free surface either)",
        ),
    };
    let physical: Vec<bool> = unloaded.iter().map(|&u| u < 0.1).collect();
    let fig18 = Row {
        item: "V21 Fig 18(a)",
        shows: "release wave from the free end, no boundary treatment: classical, local, nonlocal, lnl",
        how: "`sphstab simulate compressive-wave --form F --t-end 1.2e-5 --out DIR` (stress in final.vtk)",
        paper: "local, nonlocal and mixed non-physical at the free end; classical reproduces the free-end condition σ = 0 (§7.4; caption t = 10 μs)".into(),
        ours: format!(
            "t = {:.0} μs ({:.2} μs after the arrival, E13): mean |σ|/ρcv0 in the unloaded zone (from 10Δx behind the analytic release front to the free end; analytic 0) classical, nonlocal, local, lnl: {}",
            t18 * 1e6,
            (t18 - t_arrive) * 1e6,
            list(&unloaded, 3)
        ),
        agree: if physical == [true, false, false, false] {
            verdict(true, "read as physical when the mean |σ| there is < 10% of ρcv0")
        } else if physical[0] {
            format!(
                "partly (classical physical ✔; physical (< 10% of ρcv0) for nonlocal, local, lnl: {:?}, V21 finds all three non-physical)",
                &physical[1..]
            )
        } else {
            verdict(false, "classical does not unload")
        },
    };
    [fig17, fig18, fig18b]
}

/// The tensile wave of [V21 §7.5] against its analytic solution: two step waves of σ1 from the
/// pulled layers' inner ends `xl`, `xr`, at distance c t = `ct` by now, doubling where they
/// overlap. For the stress `st` at the reference positions `x` (spacing `dx`), over the free
/// particles `lw..n − rw`: (median σ in the overlap core, median σ in the singly loaded zones,
/// RMS |σ − σ_exact|/σ1), 5Δx around the fronts left out.
#[allow(clippy::too_many_arguments)]
fn tensile_wave_measure(
    x: &[f64],
    st: &[f64],
    (lw, rw): (usize, usize),
    (xl, xr): (f64, f64),
    ct: f64,
    s1: f64,
    dx: f64,
) -> (f64, f64, f64) {
    let n = x.len();
    let exact =
        |xi: f64| s1 * (f64::from(u8::from(xi - xl < ct)) + f64::from(u8::from(xr - xi < ct)));
    let near_front =
        |xi: f64| (xi - (xl + ct)).abs() < 5.0 * dx || (xi - (xr - ct)).abs() < 5.0 * dx;
    let free = lw..n - rw;
    let half = xl + ct - 0.5 * (xl + xr);
    let core = median(
        free.clone()
            .filter(|&i| (x[i] - 0.5 * (xl + xr)).abs() < 0.5 * half)
            .map(|i| st[i])
            .collect(),
    );
    let single = median(
        free.clone()
            .filter(|&i| (exact(x[i]) - s1).abs() < 1.0 && !near_front(x[i]))
            .filter(|&i| x[i] > xl + 5.0 * dx && x[i] < xr - 5.0 * dx)
            .map(|i| st[i])
            .collect(),
    );
    let sel: Vec<usize> = free.filter(|&i| !near_front(x[i])).collect();
    let rms = (sel
        .iter()
        .map(|&i| (st[i] - exact(x[i])).powi(2))
        .sum::<f64>()
        / sel.len() as f64)
        .sqrt()
        / s1;
    (core, single, rms)
}

/// [V21 §7.5, Figs 21a and 22]: the tensile wave at 20 μs against linear elasticity.
fn v21_figs21_22() -> [Row; 2] {
    let t = 20e-6;
    let base = scene::builtin("tensile-wave").unwrap();
    let (x, dx) = ref_x(&base);
    let n = base.particles;
    let lw = base.left.as_ref().unwrap().layers;
    let rw = base.right.as_ref().unwrap().layers;
    let (xl, xr) = (x[lw - 1], x[n - rw]);
    let c = (base.modulus / base.rho0).sqrt();
    let v = 70.0;
    let s1 = base.rho0 * c * v;
    let ct = c * t;
    // (median σ in the overlap core, median σ in the singly loaded zones, RMS deviation / σ1)
    let measure = |form: &str, cp: f64| -> (f64, f64, f64) {
        let s = scene_with("tensile-wave", |s| {
            s.form = form.into();
            s.c_partition = cp;
            s.t_end = t;
        });
        let (_, z) = run_scene(&s);
        let st = total_stress(&s, &z);
        tensile_wave_measure(&x, &st, (lw, rw), (xl, xr), ct, s1, dx)
    };
    let forms = [("classical", 0.5), ("nonlocal", 0.5), ("lnl", 0.5)];
    let m: Vec<(f64, f64, f64)> = forms.iter().map(|&(f, cp)| measure(f, cp)).collect();
    // later: max |v| to 40 μs (the exact solution never exceeds the pull, 70 m/s)
    let late: Vec<f64> = ["classical", "nonlocal"]
        .iter()
        .map(|&f| {
            let s = scene_with("tensile-wave", |s| {
                s.form = f.into();
                s.t_end = 4e-5;
            });
            run_scene(&s).0.max_velocity
        })
        .collect();
    let matches = |r: &(f64, f64, f64)| {
        (r.0 / (2.0 * s1) - 1.0).abs() <= 0.05 && (r.1 / s1 - 1.0).abs() <= 0.05 && r.2 < 0.1
    };
    let t_meet = (xr - xl) / (2.0 * c);
    let fmt = |r: &(f64, f64, f64)| {
        format!(
            "overlap {:.3} GPa, single {:.3} GPa, RMS dev. {:.3}",
            r.0 / 1e9,
            r.1 / 1e9,
            r.2
        )
    };
    let fig21 = Row {
        item: "V21 Figs 19, 20, 21(a) (1D)",
        shows: "tensile wave, 1D (0.2 m bar, E = 70.8 GPa, ρ = 1550, ends pulled at ±70 m/s, 200 particles, 7-particle end layers, viscosity 0.5; m4 and h = 1.3Δx are sphstab's choice: §7.5 gives neither kernel nor h, h = 1.3Δx is V21's value for §7.4) at t = 20 μs; Figs 19, 20 are its set-up",
        how: "`sphstab figures` → figures/v21_fig21_tensile_wave.svg; `sphstab simulate tensile-wave --form F --t-end 2e-5 --out DIR` (F = classical, nonlocal, lnl; stress in final.vtk)",
        paper: format!(
            "classical unstable, \"large unphysical oscillations\"; nonlocal and lnl match the analytic solution (§7.5); analytic (derived here): σ1 = ρcv = {:.0} MPa, fronts meet at {:.1} μs, overlap {:.3} GPa",
            s1 / 1e6,
            t_meet * 1e6,
            2.0 * s1 / 1e9
        ),
        ours: format!(
            "median σ and RMS |σ − σ_exact|/σ1 (free particles, 5Δx around the fronts left out): classical {}; nonlocal {}; lnl (c = 0.5) {}; max |v| to 40 μs: classical {:.0} m/s, nonlocal {:.0} m/s (pull {v:.0} m/s)",
            fmt(&m[0]),
            fmt(&m[1]),
            fmt(&m[2]),
            late[0],
            late[1]
        ),
        agree: if matches(&m[1]) && matches(&m[2]) && m[0].2 > 0.2 {
            verdict(
                true,
                "read as: matches = plateaus within 5% and RMS deviation < 0.1; unphysical = RMS deviation > 0.2",
            )
        } else if matches(&m[1]) && matches(&m[2]) {
            format!(
                "partly (nonlocal and lnl match ✔: plateaus within 5%, RMS deviation < 0.1; classical is not yet unphysical at 20 μs, RMS {:.3} ≤ 0.2, its instability shows later: max |v| {:.0} m/s by 40 μs)",
                m[0].2, late[0]
            )
        } else {
            verdict(false, "nonlocal or lnl off the analytic solution")
        },
    };
    let cs = [0.0, 0.25, 0.5, 0.75, 1.0];
    let sweep: Vec<(f64, f64, f64)> = cs.iter().map(|&cp| measure("lnl", cp)).collect();
    let fig22 = Row {
        item: "V21 Fig 22",
        shows: "tensile wave at 20 μs, lnl with several c",
        how: "a scene file = `tensile-wave` with `\"form\": \"lnl\", \"c_partition\": C, \"t_end\": 2e-5`; `sphstab simulate FILE --out DIR`",
        paper: "\"irrespective of the value used the response appears stable\" (§7.5); Fig 22's caption (\"Effect of different values of c parameter\") and text list no c values: the set used here is Fig 17's caption's, 0, 0.25, 0.5, 0.75, 1.0 (its c calculated by eq 49 needs code)".into(),
        ours: format!(
            "RMS |σ − σ_exact|/σ1 at c = 0, 0.25, 0.5, 0.75, 1: {}; overlap σ: {} GPa",
            list(&sweep.iter().map(|r| r.2).collect::<Vec<_>>(), 3),
            list(&sweep.iter().map(|r| r.0 / 1e9).collect::<Vec<_>>(), 3)
        ),
        agree: verdict(
            sweep.iter().all(matches),
            "read as stable when the criterion of Fig 21(a) holds for every c",
        ),
    };
    [fig21, fig22]
}

/// [B00 §4.1.2, Figs 6 and 7]: the rod in tension.
fn b00_figs6_7() -> Row {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("analysis/scenes/rod-in-tension.json");
    let eul = scene::parse(
        "rod-in-tension.json",
        &std::fs::read_to_string(path).unwrap(),
    )
    .unwrap();
    let lag = scene::builtin("rod").unwrap();
    let mls = scene_with("rod", |s| {
        s.form = "eulerian-nodal".into();
        s.shape = Some("mls".into());
    });
    let v0 = 40.0;
    let (re, _) = run_scene(&eul);
    let (rl, _) = run_scene(&lag);
    let (rm, _) = run_scene(&mls);
    let t10 = re
        .history
        .iter()
        .find(|h| h.1 >= 10.0 * v0)
        .map_or(f64::NAN, |h| h.0);
    // Fig 7: displacement along the rod at 4.3e-5 s
    let disp = |s: &Scene| {
        let s = {
            let mut s = s.clone();
            s.t_end = 4.3e-5;
            s
        };
        let (_, z) = run_scene(&s);
        let (x, _) = ref_x(&s);
        z.x.iter()
            .zip(&x)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    let (ue, ul) = (disp(&eul), disp(&lag));
    Row {
        item: "B00 Figs 6, 7",
        shows: "rod fixed at both ends in tension (σ0 = 1 GPa, E = 10 GPa, ρ = 2450, l = 0.04 m, centre node at v0 = 40 m/s; EFG nodal integration, D_mx = 1.5): velocity vs time (Fig 6), displacement at 4.3e-5 s (Fig 7), Eulerian vs Lagrangian kernel",
        how: "`sphstab simulate analysis/scenes/rod-in-tension.json --out DIR` (eulerian-nodal, sph shapes: eq 74's system); `sphstab simulate rod` (total-lagrangian, mls); `sphstab simulate rod --form eulerian-nodal` (mls); `--t-end 4.3e-5` for Fig 7",
        paper: "Eulerian kernel unstable, Lagrangian not; \"the velocity for the Eulerian kernel is 10 times larger\"; Fig 7 shows the instability in the displacement (node count and Δt not given; §4.1.2)".into(),
        ours: format!(
            "max |v| over the particles to 1e-4 s (41 nodes, 3 fixed layers per end, efg-quartic weight, Δt = 0.2Δx/c and this end time: sphstab's choice, not B00's): Eulerian (eq 74 system) {:.0} m/s, reaches 10 v0 at t = {:.2e} s; Lagrangian {:.1} m/s; Eulerian with mls shapes {:.1} m/s; max |u| at 4.3e-5 s: Eulerian {:.2e} m, Lagrangian {:.2e} m",
            re.max_velocity, t10, rl.max_velocity, rm.max_velocity, ue, ul
        ),
        agree: verdict(
            re.max_velocity >= 10.0 * v0 && rl.max_velocity <= 2.0 * v0 && ue > 10.0 * ul,
            "read as: Eulerian max |v| ≥ 10 v0 while the Lagrangian stays ≤ 2 v0 (B00's time axis is lost); E3: with the exact MLS shapes the Eulerian nodal EFG stays at v0",
        ),
    }
}

/// [B00 §4.4, Fig 16]: the spurious modes of nodal integration at the two cut-offs.
fn b00_fig16() -> Row {
    use sphstab::vonneumann::antiplane::Mass;
    let lat = Lattice::<2>::square(1.0).unwrap();
    let kp = KernelParams {
        kernel: k("efg-cubic"),
        h: 2.0,
    };
    let m = AntiPlane::new(&lat, Quadrature::Nodal, MLS, kp).unwrap();
    let w0 = m.omega2([PI, 0.0], Mass::Lumped).unwrap()[0];
    let w45 = m.omega2([PI, PI], Mass::Lumped).unwrap()[0];
    let w_cell = AntiPlane::new(&lat, Quadrature::Cell2x2, MLS, kp)
        .unwrap()
        .omega2([PI, PI], Mass::Lumped)
        .unwrap()[0];
    Row {
        item: "B00 Fig 16",
        shows: "spurious mode shapes of nodal integration (anti-plane, EFG, D_mx = 2): κΔx = π at θ = 0°, √2π at θ = 45° (hourglass)",
        how: "`sphstab stiffness --kernel efg-cubic --support 2 --shape mls --quadrature nodal --theta 0` (and `--theta 45`)",
        paper: "zero-frequency modes at k = (π, 0) (u = (−1)^j, stripes) and (π, π) (u = (−1)^{j+k}, hourglass)".into(),
        ours: format!(
            "(ωΔx/c)² of the one branch: (π, 0) {w0:.1e}, (π, π) {w45:.1e} (2×2 cells at (π, π): {w_cell:.4}); one node per cell, so the mode is the plane wave itself: (−1)^j and (−1)^{{j+k}}"
        ),
        agree: verdict(w0.abs() < 1e-10 && w45.abs() < 1e-10 && w_cell > 1e-3, ""),
    }
}

/// [B00 §5, Figs 17 and 18]: the largest eigenvalue of the finite EFG bar (41 and 101 nodes,
/// 2 Gauss points per cell) and square (21 × 21, 2 × 2 cells), free boundaries, row-sum mass,
/// MLS with a linear basis, against eq 137 (1D) and eqs 146, 148 (2D) (`stiffness --body`).
/// B00 names neither the weight, the mass nor the boundary of these runs: both EFG weights
/// are computed, the lumped mass the bounds assume is the reading, and the boundaries are free
/// (the weak form's natural condition).
fn b00_figs17_18() -> [Row; 2] {
    use sphstab::studies::finite_body::finite_body;
    let ds = [1.5, 2.0, 2.5, 3.0, 4.0, 6.0];
    let ratios = |dim: usize, n: usize, kern: &str, which: usize, ds: &[f64]| -> Vec<f64> {
        ds.iter()
            .map(|&d| {
                finite_body(dim, n, k(kern), d, MLS, &sphstab::budget::Budget::default())
                    .unwrap()
                    .ratio_lumped[which]
            })
            .collect()
    };
    let c41 = ratios(1, 41, "efg-cubic", 0, &ds);
    let c101 = ratios(1, 101, "efg-cubic", 0, &ds);
    let q101 = ratios(1, 101, "efg-quartic", 0, &ds);
    let diff = c41
        .iter()
        .zip(&c101)
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(0.0, f64::max);
    let same = diff < 1e-6;
    let falling = |v: &[f64]| v.windows(2).all(|w| w[1] < w[0]);
    let bounded = |v: &[f64]| v.iter().all(|&r| r > 1.0);
    // "approaches 1.1 as the domain of influence increases": falling, always above 1, within
    // 10% of 1.1 at the largest D_max computed
    let ok17 = same && bounded(&c101) && falling(&c101) && c101[5] <= 1.21;
    let d2 = [1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0];
    let e146 = ratios(2, 21, "efg-cubic", 0, &d2);
    let e148 = ratios(2, 21, "efg-cubic", 1, &d2);
    let q146 = ratios(2, 21, "efg-quartic", 0, &d2);
    let q148 = ratios(2, 21, "efg-quartic", 1, &d2);
    // B00: eq 146 below the numerical eigenvalue for D_max > 3.5, eq 148 above it except at 5.0
    let fails146 = d2.iter().zip(&e146).any(|(&d, &r)| d > 3.5 && r < 1.0)
        || d2.iter().zip(&q146).any(|(&d, &r)| d > 3.5 && r < 1.0);
    let holds_all = [&e146, &e148, &q146, &q148].iter().all(|v| bounded(v));
    [
        Row {
            item: "B00 Fig 17",
            shows: "max eigenvalue vs D_max, 1D bar of 41 and 101 nodes, 2 Gauss points per cell, against eq 137 (α = 12.42)",
            how: "`sphstab stiffness --body 101 --dim 1 --support D --kernel efg-cubic --shape mls` (and `--body 41`, `--kernel efg-quartic`)",
            paper: "\"the maximum eigenvalues are always bounded by the values given by Equation (137). The ratio of the eigenvalue estimate (137) to the numerical eigenvalue approaches 1.1 as the domain of influence increases\" (§5.1); bar of length 1, E = ρ = 1; weight, mass and boundary conditions not given".into(),
            ours: format!(
                "eq 137 / λ_max (row-sum mass, free ends) at D_max = 1.5, 2, 2.5, 3, 4, 6: cubic weight, 101 nodes {} (41 nodes: the same to {diff:.1e} relative: the largest mode sits at the ends); quartic weight {}; on the infinite lattice the same ratio is 2.15–2.92 (E8)",
                list(&c101, 3),
                list(&q101, 3)
            ),
            agree: if ok17 {
                "✔ (read as: eq 137 above λ_max at every D_max, the ratio falling and within 10% of 1.1 at D_max = 6; with the cubic weight and free ends — the end nodes raise λ_max above the lattice's, which settles E8: the 2–3× there is the interior's; the quartic weight falls more slowly, 1.30 at 6)".into()
            } else {
                verdict(false, "")
            },
        },
        Row {
            item: "B00 Fig 18",
            shows: "max eigenvalues of the 2D wave equation, 21×21 nodes, 2×2 cells, against eqs 146 (α1 = 13.30) and 148 (α2 = 15.00)",
            how: "`sphstab stiffness --body 21 --dim 2 --support D --kernel efg-cubic --shape mls` (and `--kernel efg-quartic`)",
            paper: "\"Equation (146) gives better upper bound for small D_max but the analytical eigenvalues are less than the numerical ones for D_max > 3.5. The eigenvalues given by Equation (148) are larger than the numerical ones except for D_max = 5.0\" (§5.2); weight, support shape, mass and boundaries not given".into(),
            ours: format!(
                "bound / λ_max (row-sum mass, free edges, circular supports) at D_max = 1.5, 2, …, 5: cubic eq 146 {}, eq 148 {}; quartic eq 146 {}, eq 148 {}",
                list(&e146, 3),
                list(&e148, 3),
                list(&q146, 3),
                list(&q148, 3)
            ),
            agree: if !fails146 && holds_all {
                "partly (eq 146 is tighter than eq 148 at every D_max ✔; both bounds hold at every D_max with either weight, so B00's failures of eq 146 beyond D_max = 3.5 and of eq 148 at 5.0 are not reproduced — they depend on what B00 does not give: the support's shape (circular here; EFG codes often use square, tensor-product ones), the weight and the mass)".into()
            } else {
                verdict(true, "B00's failures of the bounds reproduced")
            },
        },
    ]
}

/// [B00 §5.2, Fig 18] caption: eq 149 is cited for bound (b).
fn b00_fig18_caption() -> Row {
    Row {
        item: "B00 Fig 18 (caption)",
        shows: "the caption of Fig 18(b) names the bound \"(149)\"",
        how: "text only (the figure's eigenvalues: row B00 Fig 18)",
        paper: "caption: \"bound eq (149)\"; text §5.2: the bound with α2 = 15.00 is eq (148); eq (149) is the water EOS of §6.2".into(),
        ours: "no number: a citation".into(),
        agree: "erratum E12 (the caption's (149) is (148))".into(),
    }
}

/// [B00 §4.1.1, Fig 4]: σ̄ = −1, i.e. C̃ = C + σ = 0. At C̃ = 0 eq 74 is its stress term alone,
/// ω² = −(σ/ρ)(S2 − S1²): its sign is the sign of σ. σ̄ = σ/C = −1 holds for (a) C > 0, σ = −C
/// (compression) and for (b) C < 0, σ = −C > 0 (tension with a softening modulus); the caption
/// normalises by c² = −C/ρ, positive only in (b).
fn b00_fig4() -> Row {
    let mut parts = Vec::new();
    let mut counts = Vec::new();
    for d in [1.5, 2.5] {
        let phi = shape_fn(MLS, "efg-quartic", d);
        let g = grid(256);
        // eq 74 at C̃ = 0 normalised by |C|/ρ: (a) +(S2 − S1²), (b) −(S2 − S1²)
        let a: Vec<f64> = g
            .iter()
            .map(|&q| cf::b00_eq74_eulerian_nodal(&phi, d, -1.0, q))
            .collect();
        let neg_a = a.iter().filter(|&&w| w < 0.0).count();
        let neg_b = a.iter().filter(|&&w| -w < 0.0).count();
        // the exact EFG system (engine, mls), (a) C = 1, σ = −1 and (b) C = −1, σ = +1
        let engine = |modulus: f64, sigma: f64| {
            let mut p = params(FormKind::EulerianNodal, "efg-quartic", MLS, d);
            p.material = sphstab::forms::Material::bar(modulus);
            sphstab::vonneumann::linearise::Linearisation::new(
                p,
                sigma,
                sphstab::vonneumann::linearise::Lattice1D::default(),
            )
            .map(|l| g.iter().filter(|&&q| l.omega2(q).0 < -1e-12).count())
        };
        let ea = engine(1.0, -1.0).unwrap();
        let eb = engine(-1.0, 1.0).map_or("refused".to_string(), |n| n.to_string());
        counts.push((neg_a, neg_b));
        parts.push(format!(
            "D_mx = {d}: eq 74 ω² < 0 at (a) {neg_a}, (b) {neg_b} of 256 κ; exact EFG (engine, mls) (a) {ea}, (b) {eb}"
        ));
    }
    let ok = counts.iter().all(|&(a, b)| a == 0 && 2 * b > 256);
    Row {
        item: "B00 Fig 4",
        shows: "EFG nodal integration, Eulerian kernel, σ̄ = −1 (C̃ = C + σ = 0: material instability), D_mx = 1.5, 2.5; caption normalises by c² = −C/ρ",
        how: "`sphstab figures` → figures/b00_fig4_material.svg; (a) `sphstab dispersion --form eulerian-nodal --kernel efg-quartic --support 1.5 --shape mls --stress -1` (and `--support 2.5`); (b) C < 0 has no CLI flag: the test negates eq 74's stress term",
        paper: "\"when σ̄ = −1 … the discrete equations are also unstable for most wave numbers\"; the continuum (ω² = 0) for all (§4.1.1); the Conclusions call it \"(iii) An instability under compressive stress\", i.e. (a), while the caption's c² = −C/ρ > 0 means C < 0, i.e. (b)".into(),
        ours: format!(
            "(a) C > 0, σ = −C (compression); (b) C < 0, σ = −C > 0 (the caption's c² = −C/ρ > 0): {}",
            parts.join("; ")
        ),
        agree: erratum(
            ok,
            "E10",
            "reproduced by eq 74 only with C < 0 (b), as the caption's normalisation implies; with C > 0, the compression of B00's Conclusions (iii), eq 74 is stable at σ̄ = −1, ω² = c²(S2 − S1²) ≥ 0",
        ),
    }
}

// ---------------------------------------------------------------------------------------------
// Thesis rows.

/// Simpson's rule on [a, b] with n (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        s += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

/// Root of `f` in [a, b] by bisection (f(a), f(b) of opposite signs).
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let fa = f(a);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (f(m) > 0.0) == (fa > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// [T §2.2.2, Figs 2.3–2.8]: normalisation constants and inflection points from the thesis's
/// formulas (eqs 2.13–2.19, transcribed here) against sphstab's kernels.
fn thesis_kernels() -> Row {
    let mollifier_w = |r: f64| {
        let s = 1.0 - r * r;
        if s <= 0.0 {
            0.0
        } else {
            (-1.0 / s).exp() * s.powi(8)
        }
    };
    // thesis G_1D: Lucy 5/4, cubic B-spline 2/3, Gaussian 1/√π (printed 1/√3), modified
    // mollifier 1/∫w
    let g_moll = 1.0 / simpson(mollifier_w, -1.0, 1.0, 20_000);
    let thesis_g = [1.25, 2.0 / 3.0, 1.0 / PI.sqrt(), g_moll];
    // inflection points from the thesis formulas' w'' (T digest §1): Lucy −12(1 − r)(1 − 3r),
    // B-spline G(−3 + 4.5r), Gaussian (4r² − 2)e^{−r²}, modified mollifier
    // 2s⁴(120r⁶ − 277r⁴ + 168r² − 9)e^{−1/s}
    let thesis_q = [
        bisect(|r| -12.0 * (1.0 - r) * (1.0 - 3.0 * r), 0.0, 0.9),
        bisect(|r| -3.0 + 4.5 * r, 0.0, 1.0),
        bisect(|r| 4.0 * r * r - 2.0, 0.0, 1.5),
        bisect(
            |r| 120.0 * r.powi(6) - 277.0 * r.powi(4) + 168.0 * r * r - 9.0,
            0.0,
            0.5,
        ),
    ];
    let names = ["lucy", "m4", "gaussian", "mollifier"];
    let ours_g: Vec<f64> = names.iter().map(|n| k(n).sigma(1)).collect();
    let ours_q: Vec<f64> = names.iter().map(|n| k(n).inflection(1)).collect();
    let rel_g: Vec<f64> = ours_g
        .iter()
        .zip(&thesis_g)
        .map(|(a, b)| (a / b - 1.0).abs())
        .collect();
    let dq = ours_q
        .iter()
        .zip(&thesis_q)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    // Fig 2.8: un-normalised modified mollifier W, W'/2, W''/10 on its axes [−0.6, 0.4]
    let m = k("mollifier");
    let qs: Vec<f64> = (0..=2000).map(|i| i as f64 / 2000.0).collect();
    let min_d1 = qs
        .iter()
        .map(|&q| m.df(1, q) / 2.0)
        .fold(f64::INFINITY, f64::min);
    let d2_0 = m.d2f(1, 0.0) / 10.0;
    let max_d2 = qs
        .iter()
        .map(|&q| m.d2f(1, q) / 10.0)
        .fold(f64::MIN, f64::max);
    let below = d2_0 < -0.6;
    let ok =
        rel_g[0] < 1e-12 && rel_g[1] < 1e-12 && rel_g[3] < 1e-8 && rel_g[2] < 1e-4 && dq < 1e-6;
    Row {
        item: "Thesis Figs 2.3, 2.4, 2.5, 2.7, 2.8 (T-paper Fig 1)",
        shows: "the kernels Lucy, cubic B-spline, Gaussian, modified mollifier (eqs 2.13–2.19) with W' and W''",
        how: "`sphstab kernels --json` (σ_1, q*) ",
        paper: format!(
            "G_1D (from eqs 2.13–2.19): {}; inflection q* of the printed w'': {} (Gaussian G printed 1/√3: a typo for 1/√π); Fig 2.8 y axis −0.6 … 0.4",
            list(&thesis_g, 7),
            list(&thesis_q, 6)
        ),
        ours: format!(
            "σ_1: {} (relative difference {}); q*: {}; mollifier W(0) = {:.4}, min W'/2 = {:.3}, W''(0)/10 = {:.3}, max W''/10 = {:.3}",
            list(&ours_g, 7),
            rel_g
                .iter()
                .map(|x| format!("{x:.1e}"))
                .collect::<Vec<_>>()
                .join(", "),
            list(&ours_q, 6),
            m.f(1, 0.0),
            min_d1,
            d2_0,
            max_d2
        ),
        agree: verdict(
            ok,
            &format!(
                "constants and inflection points; sphstab's Gaussian is truncated at q = 3 and renormalised (2.2e-5); Fig 2.8's curves are lost, only its axis labels survive: W''(0)/10 {} the lowest label −0.6",
                if below { "lies below" } else { "lies within" }
            ),
        ),
    }
}

/// [T §4.6.3.3, Figs 4.10–4.12]: Δt = h/c (eq 4.47), h the cover (support radius), c = c_b.
fn thesis_dt() -> Row {
    use sphstab::analysis::{Query, query, timestep};
    let mut q = Query::<1>::new(FormKind::TotalLagrangian, k("mollifier"), 5.5, 0.0);
    q.shape = ShapeFamily::Sph;
    let r = timestep(&q).unwrap();
    let dt = r.step.critical_dt.unwrap();
    q.dt = Some(5.5);
    let rep = query(&q).unwrap();
    let amp = rep.max_amplification.unwrap();
    // the band the central difference amplifies at Δt = h/c: ωΔt > 2. Edges bisected on the
    // engine's ω²; `query`'s time-step rows give the same band on its κ grid
    let l = lin(
        FormKind::TotalLagrangian,
        "mollifier",
        ShapeFamily::Sph,
        5.5,
        0.0,
    );
    let over = |kap: f64| l.omega2(kap).0.max(0.0).sqrt() * 5.5 - 2.0;
    let g = grid(20_000);
    let edges: Vec<f64> = g
        .windows(2)
        .filter(|w| (over(w[0]) > 0.0) != (over(w[1]) > 0.0))
        .map(|w| bisect(over, w[0], w[1]) / PI)
        .collect();
    let rows: Vec<(f64, f64)> = rep
        .instabilities
        .iter()
        .filter(|i| i.growth_rate > 0.0)
        .map(|i| {
            (
                i.kappa_min.unwrap_or(f64::NAN) / PI,
                i.kappa_max.unwrap_or(f64::NAN) / PI,
            )
        })
        .collect();
    let band_ok = edges.len() == 2
        && rows.len() == 1
        && rows[0].0 >= edges[0]
        && rows[0].0 - edges[0] <= 1.0 / q.grid as f64
        && rows[0].1 <= edges[1]
        && edges[1] - rows[0].1 <= 1.0 / q.grid as f64;
    // thesis numbers: E = 200 GPa, ρ = 8000 → c_b = 5000 m/s (c = min(c_b, c_L)); 165 ns
    let cb = (200e9f64 / 8000.0).sqrt();
    let h = 165e-9 * cb;
    let dx = h / 5.5;
    let steps_30us = (30e-6 / 165e-9f64).round();
    Row {
        item: "Thesis Figs 4.10, 4.11, 4.12",
        shows: "probe histories below, at and above Δt = h/c (eq 4.47; TL, modified mollifier, cover 5.5Δx, central difference)",
        how: "`sphstab timestep --form total-lagrangian --kernel mollifier --h 5.5 --shape sph --stress 0`; `sphstab query … --dt 5.5` (Δt = h/c; the band is its time-step row)",
        paper: format!(
            "Δt = h/c = 165 ns \"stable\" (Fig 4.11), above it unstable (§4.6.3.3); h = cover = support radius (§2.1, eq 2.8), c = min(c_b, c_L) = {cb:.0} m/s, so h = {:.3} mm (derived); particle spacing not given: h = 5.5Δx, the cover §2.7.3 recommends, gives Δx = {:.3} mm (derived)",
            h * 1e3,
            dx * 1e3
        ),
        ours: format!(
            "critical Δt (kdk = central difference) {dt:.4} Δx/c = {:.4} h/c = {:.0} ns; at Δt = h/c the modes with ωΔt > 2 grow, κΔx ∈ [{}]π (query's {}-point grid: [{}]π), the largest amplification per step is {amp:.3} (over the thesis's ~{steps_30us:.0} steps to 30 μs: 10^{:.0})",
            dt / 5.5,
            dt / 5.5 * 165.0,
            list(&edges, 4),
            q.grid,
            rows.iter()
                .map(|r| format!("{:.3}, {:.3}", r.0, r.1))
                .collect::<Vec<_>>()
                .join("; "),
            steps_30us * amp.log10()
        ),
        agree: erratum(
            dt < 5.5 && amp > 1.01 && band_ok,
            "E11",
            "h/c is 1.38× the von Neumann limit; stable only if h were half the cover",
        ),
    }
}

/// [T §4.6.3.6, Figs 4.15–4.17]: reflection and transmission at a density interface.
fn thesis_interface() -> Row {
    use sphstab::solver::thesis_wave::{ThesisWave, run_thesis_wave};
    let ratios = [0.25, 0.5, 2.0, 4.0];
    let reps: Vec<_> = ratios
        .iter()
        .map(|&r| run_thesis_wave(&ThesisWave::new(FormKind::Nonlocal, k("m4"), r)).unwrap())
        .collect();
    let worst = reps
        .iter()
        .flat_map(|r| {
            [
                (r.reflected - r.reflected_exact).abs(),
                (r.transmitted.unwrap() - r.transmitted_exact).abs(),
            ]
        })
        .fold(0.0, f64::max);
    // the thesis's qualitative statements in velocity: decrease → reflected velocity of the
    // incident's sign (stress inverted) and transmitted > 1; increase → the opposite
    let signs = reps.iter().all(|r| {
        if r.density_ratio < 1.0 {
            r.reflected > 0.0 && r.transmitted.unwrap() > 1.0
        } else {
            r.reflected < 0.0 && r.transmitted.unwrap() < 1.0
        }
    });
    Row {
        item: "Thesis Figs 4.15, 4.16, 4.17",
        shows: "a wave crossing a density decrease (4.16) and increase (4.17) at mid-span (set-up Fig 4.15; densities not given)",
        how: "`sphstab simulate thesis-wave --form nonlocal --json` (m4, h = 1.3Δx, 601 particles, seeded pulse: sphstab's analogue of the thesis's TL bar)",
        paper: format!(
            "eqs 4.45–4.46 (particle velocity, Z = ρc, equal E): v_r/v_i = {}, v_t/v_i = {} for ρB/ρA = 0.25, 0.5, 2, 4; decrease: stress reflection inverted, transmitted wave larger; increase: same-sign reflection, smaller transmitted wave",
            list(
                &reps.iter().map(|r| r.reflected_exact).collect::<Vec<_>>(),
                4
            ),
            list(
                &reps.iter().map(|r| r.transmitted_exact).collect::<Vec<_>>(),
                4
            )
        ),
        ours: format!(
            "measured v_r/v_i = {}, v_t/v_i = {} (pulse integrals)",
            list(&reps.iter().map(|r| r.reflected).collect::<Vec<_>>(), 4),
            list(
                &reps
                    .iter()
                    .map(|r| r.transmitted.unwrap())
                    .collect::<Vec<_>>(),
                4
            )
        ),
        agree: verdict(
            worst < 0.01 && signs,
            &format!(
                "largest difference {worst:.4}; \"larger\" holds for velocity, not stress (C_t < 1 for a decrease)"
            ),
        ),
    }
}

/// [T §4.6.3.6, Figs 4.18 and 4.19]: very large density jumps at mid-span (no ratio given:
/// 100 and 10⁴ for the increase, 0.01 and 0.004 for the decrease, sphstab's choice; below ~0.003
/// the transmitted pulse returns from the far end before the split and the run is refused).
fn thesis_large_jumps() -> [Row; 2] {
    use sphstab::solver::thesis_wave::{ThesisWave, run_thesis_wave};
    let run = |r: f64| run_thesis_wave(&ThesisWave::new(FormKind::Nonlocal, k("m4"), r)).unwrap();
    let base = run(1.0);
    let up: Vec<_> = [100.0, 1e4].iter().map(|&r| run(r)).collect();
    let down: Vec<_> = [0.01, 4e-3].iter().map(|&r| run(r)).collect();
    // a fixed end reflects the particle velocity inverted (v_r = −v_i) and transmits nothing
    let ok18 =
        (up[1].reflected + 1.0).abs() < 0.05 && up[1].transmitted.is_some_and(|t| t.abs() < 0.05);
    let dev18 = up
        .iter()
        .map(|r| (r.reflected - r.reflected_exact).abs())
        .fold(0.0, f64::max);
    // the step is set by the fast material: Δt/Δt_uniform = √(ρB/ρA), the steps grow as
    // √(ρA/ρB); the interface acts as a free end (v_r → +v_i)
    let dt_ratio: Vec<f64> = down.iter().map(|r| r.time_step / base.time_step).collect();
    let ok19 = down
        .iter()
        .zip(&dt_ratio)
        .all(|(r, q)| (q - r.density_ratio.sqrt()).abs() < 1e-9 * q)
        && down
            .iter()
            .all(|r| (r.reflected - r.reflected_exact).abs() < 0.02);
    let fmt_t = |r: &sphstab::solver::thesis_wave::ThesisWaveReport| {
        r.transmitted.map_or(
            "not measurable (the pulse outruns the bar)".to_string(),
            |t| format!("{t:.4}"),
        )
    };
    [
        Row {
            item: "Thesis Fig 4.18",
            shows: "very large density increase at mid-span: the bar behaves as fixed there (ratio not given: ρB/ρA = 100 and 10⁴, sphstab's choice)",
            how: "`sphstab simulate thesis-wave --form nonlocal --density-ratio 100,10000`",
            paper: "the interface acts as a fixed end (§4.6.3.6, Fig 4.18); eq 4.45 gives v_r/v_i → −1, v_t/v_i → 0 as ρB/ρA → ∞".into(),
            ours: format!(
                "ρB/ρA = 100: v_r/v_i = {:.4} (exact {:.4}), v_t/v_i = {} (exact {:.4}); 10⁴: v_r/v_i = {:.4} (exact {:.4}), v_t/v_i = {} (exact {:.4})",
                up[0].reflected,
                up[0].reflected_exact,
                fmt_t(&up[0]),
                up[0].transmitted_exact,
                up[1].reflected,
                up[1].reflected_exact,
                fmt_t(&up[1]),
                up[1].transmitted_exact
            ),
            agree: verdict(
                ok18,
                &format!("read as: at 10⁴ the reflected velocity within 0.05 of −v_i (a fixed end) and the transmitted one below 0.05 v_i; both within {dev18:.4} of eq 4.45"),
            ),
        },
        Row {
            item: "Thesis Fig 4.19",
            shows: "very large density decrease at mid-span: the time step becomes prohibitive (ratio not given: ρB/ρA = 0.01 and 0.004, sphstab's choice)",
            how: "`sphstab simulate thesis-wave --form nonlocal --density-ratio 0.01,0.004 --json` (`time_step`, `steps`)",
            paper: "\"the required time step becomes prohibitively small\" (§4.6.3.6, Fig 4.19; no number)".into(),
            ours: format!(
                "Δt over the uniform bar's (ρB = ρA, {} steps): {} at ρB/ρA = 0.01, 0.004 (√(ρB/ρA): the light half's c_B = c_A √(ρA/ρB) sets the step); steps {}, {} for a run {:.2}× and {:.2}× as long; the interface reflects as a free end: v_r/v_i = {:.4}, {:.4} (exact {:.4}, {:.4}); v_t/v_i: {}, {}",
                base.steps,
                list(&dt_ratio, 4),
                down[0].steps,
                down[1].steps,
                down[0].steps as f64 * down[0].time_step / (base.steps as f64 * base.time_step),
                down[1].steps as f64 * down[1].time_step / (base.steps as f64 * base.time_step),
                down[0].reflected,
                down[1].reflected,
                down[0].reflected_exact,
                down[1].reflected_exact,
                fmt_t(&down[0]),
                fmt_t(&down[1])
            ),
            agree: verdict(
                ok19,
                "read as: Δt falls as √(ρB/ρA) — 10× and 16× smaller — while the reflection follows eq 4.45 within 0.02; below ρB/ρA ≈ 0.003 the 0.15 m bar cannot hold the measurement (the run is refused)",
            ),
        },
    ]
}

/// [T §4.7.3, Figs 4.20–4.22]: TL stable, the updated-Lagrangian (Eulerian-kernel) forms tensile
/// unstable, mollifier h = 5.5Δx. σ̄ is not given: 0.01 chosen.
fn thesis_tension() -> Row {
    use sphstab::analysis::{Query, query};
    let run = |f: FormKind, shape: ShapeFamily| {
        let mut q = Query::<1>::new(f, k("mollifier"), 5.5, 0.01);
        q.shape = shape;
        query(&q).unwrap()
    };
    let tl = run(FormKind::TotalLagrangian, ShapeFamily::Sph);
    let cl = run(FormKind::Classical, ShapeFamily::Sph);
    let en = run(FormKind::EulerianNodal, ShapeFamily::Sph);
    let band = |r: &sphstab::analysis::QueryReport| {
        r.instabilities
            .iter()
            .filter(|i| i.growth_rate > 0.0)
            .map(|i| {
                format!(
                    "[{:.3}π, {:.3}π]",
                    i.kappa_min.unwrap_or(f64::NAN) / PI,
                    i.kappa_max.unwrap_or(f64::NAN) / PI
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let kmax = |r: &sphstab::analysis::QueryReport| {
        r.kappa_at_max.as_ref().map_or(f64::NAN, |k| k[0]) / PI
    };
    Row {
        item: "Thesis Figs 4.20, 4.21, 4.22",
        shows: "pre-stressed bar in tension with a 5% kick of the centre particle: TL (4.21) vs updated Lagrangian (4.22); set-up Fig 4.20",
        how: "`sphstab query --form total-lagrangian --kernel mollifier --h 5.5 --shape sph --stress 0.01`; `--form classical`, `--form eulerian-nodal --shape sph`",
        paper: "TL: the particles follow the centre particle (stable); UL: adjacent particles out of phase (odd–even), clumping in tension (§4.7.3; prestress not given)".into(),
        ours: format!(
            "σ̄ = 0.01 (chosen): TL stable = {}, max growth {:.1e}; classical: unstable on {} (growth {:.5} c/Δx at {:.3}π); eulerian-nodal (sph): {} (growth {:.5} at {:.3}π)",
            tl.stable,
            tl.max_growth_rate,
            band(&cl),
            cl.max_growth_rate,
            kmax(&cl),
            band(&en),
            en.max_growth_rate,
            kmax(&en)
        ),
        agree: verdict(
            tl.stable && !cl.stable && !en.stable && kmax(&cl) > 0.5 && kmax(&en) > 0.5,
            "\"out of phase\" read as the fastest mode having κΔx > π/2; the thesis's UL scheme is nearest to classical / eulerian-nodal",
        ),
    }
}

/// [T §4.7.1] (text): the share of the 1D cover where W'' > 0 (tensile-unstable neighbours).
fn thesis_tensile_range() -> Row {
    let share = |n: &str| {
        let kk = k(n);
        1.0 - kk.inflection(1) / kk.zeta()
    };
    let (m4, moll) = (share("m4"), share("mollifier"));
    // the classical mollifier e^{−1/(1−r²)} (not in sphstab): w'' ∝ 3r⁴ − 1, inflection 3^{−1/4}
    let classical = 1.0 - bisect(|r| 3.0 * r.powi(4) - 1.0, 0.0, 1.0);
    Row {
        item: "Thesis §4.7.1 (text)",
        shows: "the share of the 1D cover where W'' > 0 (the tensile-instability range of Swegle's criterion)",
        how: "`sphstab kernels --json` (1 − q*/ζ)",
        paper: "cubic B-spline 67%, mollifier 82% (§4.7.1)".into(),
        ours: format!(
            "m4 {:.1}%; modified mollifier {:.1}%; classical mollifier (derived from eq 2.17) {:.1}%",
            100.0 * m4,
            100.0 * moll,
            100.0 * classical
        ),
        agree: erratum(
            (m4 - 0.67).abs() < 0.005
                && (moll - 0.82).abs() > 0.03
                && (classical - 0.82).abs() > 0.03,
            "E17",
            "67% ✔; 82% matches neither mollifier",
        ),
    }
}

/// [T §2.2.2, eq 2.17, Fig 2.6]: the classical mollifier w = e^{−1/(1−r²)} (Reddy), which is not
/// one of sphstab's kernels (`mollifier` is the thesis's modified one, eq 2.19): its
/// normalisation and inflection derived here from the formula, against the seed digest's values
/// (`../shared/seeds/004_digest.md` §1.4: ∫w = 0.4439938162, G_1D = 2.2522836, G_2D = 2.1435658,
/// G_3D = 2.2671167, inflection 3^{−1/4} = 0.75984).
fn thesis_fig26() -> Row {
    let w = |r: f64| {
        let s = 1.0 - r * r;
        if s <= 0.0 { 0.0 } else { (-1.0 / s).exp() }
    };
    let i1 = simpson(w, -1.0, 1.0, 20_000);
    let i2 = 2.0 * PI * simpson(|r| r * w(r), 0.0, 1.0, 20_000);
    let i3 = 4.0 * PI * simpson(|r| r * r * w(r), 0.0, 1.0, 20_000);
    let g = [1.0 / i1, 1.0 / i2, 1.0 / i3];
    let digest = [2.2522836, 2.1435658, 2.2671167];
    // w'' = 2(3r⁴ − 1) e^{−1/(1−r²)}/(1 − r²)⁴ (digest §1.4): the inflection is the root of 3r⁴ − 1;
    // checked against a central difference of w itself
    let q = bisect(|r| 3.0 * r.powi(4) - 1.0, 0.0, 1.0);
    let d2 = |r: f64| (w(r + 1e-4) - 2.0 * w(r) + w(r - 1e-4)) / 1e-8;
    let sign_change = d2(q - 1e-3) < 0.0 && d2(q + 1e-3) > 0.0;
    let dev = g
        .iter()
        .zip(&digest)
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0, f64::max);
    Row {
        item: "Thesis Fig 2.6",
        shows: "the classical mollifier e^{−1/(1−r²)} (eq 2.17; not one of sphstab's kernels, whose `mollifier` is the modified one of eq 2.19)",
        how: "derived in the test from eq 2.17 (Simpson, 20,000 intervals)",
        paper: "W = G e^{−1/(1−r²)} on r < 1, C∞ with compact support; no closed-form integral, so G is found by numerical quadrature (§2.2.2)".into(),
        ours: format!(
            "derived: ∫_{{−1}}^{{1}} w = {i1:.10}; G_1D, G_2D, G_3D = {} (the digest's {}: largest relative difference {dev:.1e}); w(0) = e^{{−1}} = {:.6}; w'' changes sign at r = 3^{{−1/4}} = {q:.5} (a finite difference of w agrees: {}), so W'' > 0 on {:.1}% of the 1D support",
            list(&g, 7),
            list(&digest, 7),
            w(0.0),
            if sign_change { "yes" } else { "no" },
            100.0 * (1.0 - q)
        ),
        agree: verdict(
            dev < 1e-6 && sign_change,
            "derived: the figure plots eq 2.17; read as its normalisation and shape reproduced from the formula",
        ),
    }
}

/// [T §4.6.3.5] unnumbered table: the printed wave speeds are c_L with ν = 0.3.
fn thesis_speeds() -> Row {
    let sets = [(8000.0, 200e9), (8000.0, 100e9), (4000.0, 200e9)];
    let printed = [5801.0, 4102.0, 8204.0];
    let nu: f64 = 0.3;
    let cl: Vec<f64> = sets
        .iter()
        .map(|&(rho, e)| (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * rho)).sqrt())
        .collect();
    let cb: Vec<f64> = sets.iter().map(|&(rho, e)| (e / rho).sqrt()).collect();
    Row {
        item: "Thesis table of §4.6.3.5 (unnumbered)",
        shows: "three material sets (ρ, E) and their wave speeds for Fig 4.14",
        how: "arithmetic in the test (c_L = √(E(1 − ν)/((1 + ν)(1 − 2ν)ρ)), ν = 0.3 from §5.3.1)",
        paper: format!("{} (printed in \"m.s⁻²\")", list(&printed, 0)),
        ours: format!("c_L: {}; c_b = √(E/ρ): {}", list(&cl, 1), list(&cb, 1)),
        agree: verdict(
            cl.iter().zip(&printed).all(|(a, b)| (a - b).abs() < 1.0),
            "the printed speeds are c_L; units are m/s, not m.s⁻²; Fig 4.14's histories: row Thesis Fig 4.14",
        ),
    }
}

/// [T §5.1, Figs 5.1 and 5.2]: the analytic T11(λ1) of eq 5.5 for fixed λ2 (plane strain,
/// λ3 = 1), compressible and nearly incompressible (values not given: ν = 0.3, §5.3.1's
/// validation material, and ν = 0.49, §5.3.2's), against sphstab's neo-Hookean law — the first
/// Piola–Kirchhoff stress the total-Lagrangian rate integrates, turned into Cauchy stress by
/// `neo_hookean_cauchy` — and against the thesis digest's independently derived values
/// (`../shared/seeds/004_digest.md` §4.5).
fn thesis_figs51_52() -> [Row; 2] {
    use sphstab::forms::neo_hookean_cauchy;
    // eq 5.5: T = (μ/J) diag(λ_i² − 1) + (λ/J) ln J I, J = λ1 λ2 (λ3 = 1)
    let eq55 = |l1: f64, l2: f64, lam: f64, mu: f64| {
        let j = l1 * l2;
        (mu / j) * (l1 * l1 - 1.0) + (lam / j) * j.ln()
    };
    let row = |nu: f64, item: &'static str, what: &'static str, digest: &[(f64, f64, f64)]| {
        let mu = 1.0;
        let lam = 2.0 * nu / (1.0 - 2.0 * nu) * mu;
        let mut worst: f64 = 0.0;
        for l2 in [0.5, 1.0, 1.5, 2.0] {
            for i in 0..=110 {
                let l1 = 0.5 + 0.05 * i as f64;
                let t = neo_hookean_cauchy([l1, l2], lam, mu)[0];
                let e = eq55(l1, l2, lam, mu);
                worst = worst.max((t - e).abs() / e.abs().max(1.0));
            }
        }
        let ours: Vec<f64> = digest
            .iter()
            .map(|&(l1, l2, _)| neo_hookean_cauchy([l1, l2], lam, mu)[0])
            .collect();
        let dev = digest
            .iter()
            .zip(&ours)
            .map(|(d, o)| (d.2 - o).abs())
            .fold(0.0, f64::max);
        let pts = digest
            .iter()
            .zip(&ours)
            .map(|(d, o)| format!("({}, {}) {o:.4}", d.0, d.1))
            .collect::<Vec<_>>()
            .join(", ");
        Row {
            item,
            shows: what,
            how: "derived in the test through `sphstab::forms::neo_hookean_cauchy` (the solver's neo-Hookean law); the stretched bar is row Thesis Fig 5.5",
            paper: "a family of curves T11(λ1) at fixed λ2 from eq 5.5 with λ3 = 1 (§5.1); parameter values not given".into(),
            ours: format!(
                "λ/μ = {:.1} (ν = {nu}): sphstab's law against eq 5.5 on λ2 = 0.5, 1, 1.5, 2 and λ1 = 0.5 … 6: largest relative difference {worst:.1e}; T11/μ at (λ1, λ2) = {pts}; the digest's derived values differ by at most {dev:.1e}",
                lam / mu
            ),
            agree: verdict(
                worst < 1e-13 && dev < 5e-5,
                "derived: the curves are eq 5.5 itself; read as sphstab's law giving them to rounding",
            ),
        }
    };
    [
        row(
            0.3,
            "Thesis Fig 5.1",
            "analytic T11 vs λ1, compressible neo-Hookean (eq 5.5), a family of λ2",
            &[
                (1.5, 1.0, 1.2388),
                (2.0, 1.0, 2.0199),
                (3.0, 1.0, 3.2160),
                (6.0, 1.0, 6.2813),
                (2.0, 2.0, 1.2699),
                (6.0, 2.0, 3.2273),
            ],
        ),
        row(
            0.49,
            "Thesis Fig 5.2",
            "as Fig 5.1, nearly incompressible (ν = 0.49)",
            &[
                (1.5, 1.0, 14.0785),
                (2.0, 1.0, 18.4821),
                (4.0, 1.0, 20.7321),
                (6.0, 1.0, 20.4660),
                (1.0, 2.0, 16.9821),
                (6.0, 2.0, 13.0634),
            ],
        ),
    ]
}

/// The 2D and 3D scenes (issue 29, capabilities 4 and 6): [T §5.4.2–5.4.3] (Figs 5.7–5.12),
/// 2D total-Lagrangian neo-Hookean bars (plane strain, ν = 0.3) with symmetry planes or free
/// sides, and [V21 §7.1, §7.5] (Figs 14–16, 20, 21(b)), 3D bars between symmetry planes. The
/// thesis gives the bars (6 particles thick; 31 × 6 for the stretch), the loads and the
/// probes' places; the 2D pulse bar's 301 columns, the mollifier at h = 2.5Δx with MLS shapes
/// (as the 1D stretch row) and the 3 held layers at each end of the stretch are sphstab's
/// choice. V21's 3D bars are 100 × 7 × 7 and 200 particles long with a 1 × 1 cm section; a bar
/// between symmetry planes on every side is laterally uniform (tests/it/symmetry.rs, and the
/// Fig 14 row below at 7 × 7), so the long runs use a 1 × 1 section with its ghosts.
mod multi_d {
    use super::{Row, erratum, list, verdict};
    use sphstab::solver::scene::{Scene, SceneReport, Side, parse};

    fn scene(file: &str) -> Scene {
        let path = format!("{}/analysis/scenes/{file}", env!("CARGO_MANIFEST_DIR"));
        parse(&path, &std::fs::read_to_string(&path).unwrap()).unwrap()
    }

    fn run(s: &Scene) -> SceneReport {
        s.run(|_| {}).unwrap()
    }

    /// The time `q` first crosses `level` upwards (linear between records).
    fn arrival(q: &[f64], t: &[f64], level: f64) -> f64 {
        let k = q
            .windows(2)
            .position(|w| w[0] < level && w[1] >= level)
            .expect("the front arrives");
        t[k] + (level - q[k]) / (q[k + 1] - q[k]) * (t[k + 1] - t[k])
    }

    /// E, ν, ρ0 of the thesis's steel; (c_L, plane-strain bar speed, c_b).
    fn thesis_speeds() -> (f64, f64, f64) {
        let (e, nu, rho): (f64, f64, f64) = (200e9, 0.3, 8000.0);
        (
            (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) / rho).sqrt(),
            (e / ((1.0 - nu * nu) * rho)).sqrt(),
            (e / rho).sqrt(),
        )
    }

    /// [T] Figs 5.7–5.9: a +100 kPa traction pulse (10 μs, smoothed over 1 μs) into the 2D
    /// bar of `thesis-2d-pulse.json`, between symmetry planes (1D strain) and with free sides
    /// (1D stress). Speeds from the half-amplitude arrivals at X = 0.05 and 0.1 m; plateaus
    /// midway through the pulse; the variation through the thickness between the probes on
    /// the axis and at Y = 1.25 mm (the outer row).
    pub fn thesis_pulse_rows() -> Vec<Row> {
        let (c_l, c_ps, c_b) = thesis_speeds();
        let amp = 1e5;
        let strain_scene = scene("thesis-2d-pulse.json");
        let mut stress_scene = strain_scene.clone();
        stress_scene.sides = vec![[Side::Free, Side::Free]];
        stress_scene.analytic = None;
        let (strain, stress) = rayon::join(|| run(&strain_scene), || run(&stress_scene));
        let speed = |r: &SceneReport| {
            0.05 / (arrival(&r.probes[1].stress, &r.probe_t, 0.5 * amp)
                - arrival(&r.probes[0].stress, &r.probe_t, 0.5 * amp))
        };
        // the plateau at 0.05 m: the mean and the RMS deviation from the load over the pulse's
        // flat part (t0 = ζ h_t = 1 μs for the mollifier, T = 10 μs; 2 μs left out at each
        // end for the smoothing and the front's spread)
        let plateau = |r: &SceneReport, c: f64| {
            let (a, b) = (1e-6 + 2e-6 + 0.05 / c, 1e-6 + 10e-6 - 2e-6 + 0.05 / c);
            let v: Vec<f64> = r
                .probe_t
                .iter()
                .zip(&r.probes[0].stress)
                .filter(|(t, _)| (a..=b).contains(*t))
                .map(|(_, s)| s / amp)
                .collect();
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let rms = (v.iter().map(|x| (x - 1.0).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
            (mean, rms)
        };
        let across = |r: &SceneReport| {
            [(0, 2), (1, 3)]
                .iter()
                .flat_map(|&(a, b)| {
                    r.probes[a]
                        .stress
                        .iter()
                        .zip(&r.probes[b].stress)
                        .map(|(x, y)| (x - y).abs())
                })
                .fold(0.0, f64::max)
                / amp
        };
        let (v_strain, v_stress) = (speed(&strain), speed(&stress));
        let (p_strain, p_stress) = (plateau(&strain, c_l), plateau(&stress, c_ps));
        let (a_strain, a_stress) = (across(&strain), across(&stress));
        let how = "`sphstab simulate analysis/scenes/thesis-2d-pulse.json --out DIR` (probes.csv); `sphstab figures` → figures/thesis_figs5_7_5_9_2d_pulse.svg";
        vec![
            Row {
                item: "Thesis Fig 5.7 (T-paper Fig 4)",
                shows: "2D TL neo-Hookean bar (ν = 0.3), 6 particles thick, 1D strain (sides held: symmetry planes), a +100 kPa tensile pulse; 301 × 6 particles, mollifier h = 2.5Δx, MLS: sphstab's choice",
                how,
                paper: format!(
                    "follows the 1D trends (Fig 5.3: the front at c_L = {c_l:.1} m/s, the plateau the load), \"little variation through the thickness\" (§5.4.2)"
                ),
                ours: format!(
                    "front speed {v_strain:.0} m/s ({:+.2}% of c_L); plateau at 0.05 m: mean {:.4} of the load, RMS deviation {:.4}; axis and outer row differ by at most {a_strain:.1e} of the load",
                    100.0 * (v_strain / c_l - 1.0),
                    p_strain.0,
                    p_strain.1
                ),
                agree: verdict(
                    (v_strain / c_l - 1.0).abs() < 0.01
                        && (p_strain.0 - 1.0).abs() < 0.02
                        && a_strain < 1e-3,
                    "read as: speed within 1% of c_L, plateau within 2%, the rows within 0.1% of the load",
                ),
            },
            Row {
                item: "Thesis Fig 5.8",
                shows: "the 1D-stress configuration: the bar of Fig 5.7 with free, traction-free sides",
                how,
                paper: "the sides free and traction-free; the pulse travels as a 1D-stress wave (§5.4.2)".into(),
                ours: format!(
                    "free sides (no ghosts): plateau at 0.05 m: mean {:.4} of the load, RMS deviation {:.4} (a ringing behind the front, absent between symmetry planes: {:.4}); axis and outer row differ by at most {a_stress:.3} of the load (the section's lateral motion)",
                    p_stress.0,
                    p_stress.1,
                    p_strain.1
                ),
                agree: verdict(
                    (p_stress.0 - 1.0).abs() < 0.02,
                    "read as: the load carried through the free-sided bar, the plateau's mean within 2%",
                ),
            },
            Row {
                item: "Thesis Fig 5.9",
                shows: "tensile wave, 2D TL neo-Hookean bar in 1D stress (free sides), plane strain",
                how,
                paper: format!(
                    "the speed changes from c_L to c_b = √(E/ρ) = {c_b:.0} m/s (§5.4.2); the model is plane strain, λ3 = 1 (§5.1.1; §5.4 does not restate it for the 2D code)"
                ),
                ours: format!(
                    "simulated: front speed {v_stress:.0} m/s with free sides against {v_strain:.0} m/s between symmetry planes; plane strain with free sides has modulus E/(1 − ν²): c = {c_ps:.0} m/s (derived), the simulation {:+.2}% from it and {:+.1}% from c_b",
                    100.0 * (v_stress / c_ps - 1.0),
                    100.0 * (v_stress / c_b - 1.0)
                ),
                agree: erratum(
                    (v_stress / c_ps - 1.0).abs() < 0.01 && (v_stress / c_b - 1.0).abs() > 0.03,
                    "E15",
                    "the speed does change (c_L → the bar speed), but in plane strain to √(E/((1 − ν²)ρ)), not c_b, which is the plane-stress bar speed",
                ),
            },
        ]
    }

    /// [T] eq 5.5 over μ, plane strain (λ3 = 1): T11/μ = (λ1² − 1)/(λ1λ2) + (λ/μ) ln(λ1λ2)/(λ1λ2).
    fn eq55(l1: f64, l2: f64) -> f64 {
        let lam_over_mu = 1.5; // ν = 0.3: λ/μ = 2ν/(1 − 2ν)
        let j = l1 * l2;
        (l1 * l1 - 1.0) / j + lam_over_mu * j.ln() / j
    }

    /// [T] Figs 5.10–5.12: the 31 × 6 bar of `thesis-2d-stretch.json` (its left 3 layers held,
    /// its right 3 pulled so that the 26Δx between the held layers reach λ1 = 6 over 30
    /// transit times; symmetry planes at its sides): the centre's T11 against the applied
    /// stretch λ1 = 1 + u_end/L (u_end the pulled end's displacement, L = 13 mm between the
    /// held layers: a quasi-static bar is uniform), with λ2 = 1, with λ2 = 2 (the planes moved
    /// out to 2 first, over 30 μs), and with λ2 ramped with λ1 (the same pulse, so λ2 − 1 =
    /// (λ1 − 1)/5 at every time). Deviation: max |T11/μ − eq 5.5| over the records with
    /// λ1 ≥ 1.5, relative to eq 5.5.
    pub fn thesis_stretch_rows() -> Vec<Row> {
        let base = scene("thesis-2d-stretch.json");
        let mu = 200e9 / 2.6;
        let dx = base.length / (base.particles - 1) as f64;
        let span = base.length - 2.0 * 2.0 * dx;
        let ramp = base.right.as_ref().unwrap().velocity_pulse.clone().unwrap();
        let mut held = base.clone();
        held.transverse_stretch_rate = Some(sphstab::solver::scene::Pulse {
            amplitude: 1.0 / 30e-6,
            duration: 30e-6,
            smoothing: 3e-6,
            start: None,
        });
        let mut pulled = ramp.clone();
        pulled.start = Some(40e-6);
        held.right.as_mut().unwrap().velocity_pulse = Some(pulled);
        held.t_end += 40e-6;
        let mut both = base.clone();
        both.transverse_stretch_rate = Some(sphstab::solver::scene::Pulse {
            amplitude: ramp.amplitude / (5.0 * span),
            ..ramp.clone()
        });
        let ((r1, r2), r3) =
            rayon::join(|| rayon::join(|| run(&base), || run(&held)), || run(&both));
        let applied = |r: &SceneReport, k: usize| 1.0 + r.probes[1].displacement[k] / span;
        // (max relative deviation, final λ1, final T11/μ, final eq 5.5, final F11 at the centre)
        let compare = |r: &SceneReport, l2: &dyn Fn(usize) -> f64| {
            let c = &r.probes[0];
            let mut dev = 0.0f64;
            for k in 0..r.probe_t.len() {
                let l1 = applied(r, k);
                if l1 >= 1.5 {
                    dev = dev.max((c.stress[k] / mu / eq55(l1, l2(k)) - 1.0).abs());
                }
            }
            let last = r.probe_t.len() - 1;
            let l1 = applied(r, last);
            (
                dev,
                l1,
                c.stress[last] / mu,
                eq55(l1, l2(last)),
                c.stretch[last],
            )
        };
        let a = compare(&r1, &|_| 1.0);
        let b = compare(&r2, &|_| 2.0);
        let path = |k: usize| 1.0 + (applied(&r3, k) - 1.0) / 5.0;
        let c = compare(&r3, &path);
        // the ramp's start: at λ1 = 1.2 the centre against the λ2 = 1 curve and the path's
        let k12 = (0..r3.probe_t.len())
            .find(|&k| applied(&r3, k) >= 1.2)
            .unwrap();
        let start = (
            r3.probes[0].stress[k12] / mu,
            eq55(applied(&r3, k12), 1.0),
            eq55(applied(&r3, k12), path(k12)),
        );
        let how = "`sphstab simulate analysis/scenes/thesis-2d-stretch.json --out DIR` (λ2 = 2 and the ramp: `transverse_stretch_rate`, see the test); `sphstab figures` → figures/thesis_figs5_10_5_12_2d_stretch.svg";
        let fmt = |x: &(f64, f64, f64, f64, f64)| {
            format!(
                "max deviation of the centre's T11 from eq 5.5 at the applied stretch {:.2}% (λ1 ≥ 1.5); at the end λ1 = {:.3} (the centre's F11 {:.3}), T11/μ = {:.4} (eq 5.5 {:.4})",
                100.0 * x.0,
                x.1,
                x.4,
                x.2,
                x.3
            )
        };
        let tol = 0.02;
        vec![
            Row {
                item: "Thesis Fig 5.10",
                shows: "31 × 6 particles, λ2 = 1 (the sides held: symmetry planes), λ1 ramped to 6 over 30 transit times, centre T11 against λ1",
                how,
                paper: "the curve deviates slightly from eq 5.5 (§5.4.3; causes suggested: 6 transverse particles, time integration, distortion); [DERIVED, digest] eq 5.5 at λ1 = 6: T11/μ = 6.2813".into(),
                ours: fmt(&a),
                agree: verdict(a.0 < tol, "read as: within 2% of eq 5.5 (sphstab's sides are exact symmetry planes; the thesis's slight deviations are not reproduced)"),
            },
            Row {
                item: "Thesis Fig 5.11",
                shows: "as Fig 5.10 with λ2 = 2 (the planes moved out to λ2 = 2 over 30 μs before λ1 is ramped)",
                how,
                paper: "deviates slightly from eq 5.5 at λ2 = 2 (§5.4.3); [DERIVED, digest] eq 5.5 at λ2 = 2: λ1 = 1 → 0.5199, 2 → 1.2699, 4 → 2.2649, 6 → 3.2273".into(),
                ours: format!(
                    "{}; eq 5.5 here at (1, 2), (2, 2), (4, 2), (6, 2): {}",
                    fmt(&b),
                    list(&[eq55(1.0, 2.0), eq55(2.0, 2.0), eq55(4.0, 2.0), eq55(6.0, 2.0)], 4)
                ),
                agree: verdict(b.0 < tol, "read as: within 2% of eq 5.5"),
            },
            Row {
                item: "Thesis Fig 5.12",
                shows: "λ1 ramped to 6 while λ2 ramps to 2 (the same pulse: λ2 − 1 = (λ1_applied − 1)/5)",
                how,
                paper: "should start on the λ2 = 1 curve and end on the λ2 = 2 curve; the thesis's run did not: its transverse stretch fell short of 2 (§5.4.3)".into(),
                ours: format!(
                    "{} (eq 5.5 on the path: λ2 from the planes); at λ1 = 1.2 T11/μ = {:.4}: λ2 = 1 curve {:.4}, the path's {:.4}",
                    fmt(&c),
                    start.0,
                    start.1,
                    start.2
                ),
                agree: verdict(
                    c.0 < tol && (c.2 / eq55(c.1, 2.0) - 1.0).abs() < 0.01,
                    "read as: on the path within 2%, ending within 1% of the λ2 = 2 curve (the thesis's own run did not reach it: its λ2 fell short)",
                ),
            },
        ]
    }

    /// [V21 §7.1, Figs 14–16]: the 3D uniform bar of `v21-3d-uniform-bar.json` (100 × 7 × 7,
    /// symmetry planes on the four sides, E = 2, ν = 0.3, ρ0 = 8, 3 end layers moving with
    /// v = g x; m4, h = 1.3Δx and Δt = 0.5Δx/c_L are sphstab's choice). In uniaxial strain the
    /// Truesdell law gives σ_xx = (λ + 2G) g t (the 1D derivation of row V21 Figs 9, 16 with
    /// C = λ + 2G = E(1 − ν)/((1 + ν)(1 − 2ν)) = 2.6923). Deviation: max |σ − σ_exact| over
    /// the free columns of the central row, over |σ_exact|.
    pub fn v21_uniform_rows() -> Vec<Row> {
        let base = scene("v21-3d-uniform-bar.json");
        let (e, nu): (f64, f64) = (2.0, 0.3);
        let modulus = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let dev = |r: &SceneReport, g: f64, t: f64| {
            let exact = modulus * g * t;
            let n = r.centre_row.len();
            (3..n - 3)
                .map(|k| (r.final_stress[r.centre_row[k]] - exact).abs())
                .fold(0.0, f64::max)
                / exact.abs()
        };
        let with = |g: f64, t: f64, form: &str, section: Vec<usize>| {
            let mut s = base.clone();
            s.initial_velocity = sphstab::solver::scene::InitialVelocity::Linear { gradient: g };
            s.t_end = t;
            s.form = form.into();
            s.section = section;
            s
        };
        // Fig 14: the 7 × 7 bar and the 1 × 1 one at t = 1
        let (wide, thin) = rayon::join(
            || run(&with(0.001, 1.0, "nonlocal", vec![7, 7])),
            || run(&with(0.001, 1.0, "nonlocal", vec![1, 1])),
        );
        let scale = wide.final_stress.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let same = wide
            .centre_row
            .iter()
            .enumerate()
            .map(|(k, &i)| (wide.final_stress[i] - thin.final_stress[k]).abs())
            .fold(0.0, f64::max)
            / scale;
        let dx = base.length / (base.particles - 1) as f64;
        let fig14 = Row {
            item: "V21 Fig 14",
            shows: "3D bar set-up: 100 × 7 × 7 particles, symmetry planes at Y, Z = ±0.035",
            how: "`sphstab simulate analysis/scenes/v21-3d-uniform-bar.json --out DIR`",
            paper: "100 particles along X as in 1D, 7 × 7 across \"to ensure that the particles along central region of the bar have no ghost particle neighbours\"; symmetry planes at Y, Z = ±0.035 generate the 1D strain state (§7.1)".into(),
            ours: format!(
                "{} particles and {} ghosts; Δx = 1/99 (sphstab's bar spans 1 between its end particles; V21's ±0.035 is 3.5 × 0.01), planes at ±{:.5}; the central row at t = 1 equals the 1 × 1 section's to {same:.1e} of max |σ| (the bar is laterally uniform)",
                wide.particles,
                wide.ghosts,
                3.5 * dx
            ),
            agree: verdict(same < 1e-10, "read as: the set-up built, and its central row independent of the section (to rounding)"),
        };
        let mut rows = vec![fig14];
        for (g, item, shows) in [
            (
                -0.001,
                "V21 Fig 15 (3D)",
                "uniform compression (v = −0.001x), central row of the 3D bar at t = 1, 10",
            ),
            (
                0.001,
                "V21 Fig 16 (3D)",
                "uniform tension (v = 0.001x), central row of the 3D bar at t = 1, 10",
            ),
        ] {
            let one = vec![1, 1];
            let ((n1, n10), l1) = rayon::join(
                || {
                    rayon::join(
                        || run(&with(g, 1.0, "nonlocal", one.clone())),
                        || run(&with(g, 10.0, "nonlocal", one.clone())),
                    )
                },
                || run(&with(g, 1.0, "lnl", one.clone())),
            );
            let d = [dev(&n1, g, 1.0), dev(&n10, g, 10.0), dev(&l1, g, 1.0)];
            rows.push(Row {
                item,
                shows,
                how: "`sphstab simulate analysis/scenes/v21-3d-uniform-bar.json --out DIR` (edit `gradient`, `t_end`, `form`)",
                paper: "\"These 3D results agree with the results from the equivalent test in 1D\" (§7.1; the forms are not named: the test validates the mixed local-nonlocal form in 3D)".into(),
                ours: format!(
                    "σ_exact = (λ + 2G) g t = {:.4} at t = 1, {:.4} at t = 10 (1D strain: {:.3} × the 1D bar's E g t at ν = 0.3); max |σ − σ_exact|/|σ_exact|: nonlocal {:.1e} (t = 1), {:.1e} (t = 10); lnl {:.1e} (t = 1; lnl's local stencils cost 7× nonlocal's per step in 3D: t = 10 is not run)",
                    modulus * g,
                    modulus * g * 10.0,
                    modulus / e,
                    d[0],
                    d[1],
                    d[2]
                ),
                agree: verdict(
                    d.iter().all(|&x| x <= 0.05),
                    "read as max deviation ≤ 5%, as the 1D rows; \"agree with 1D\" read as each agreeing with its own analytic solution: with ν = 0.3 the 1D-strain stress is 1.35 × the 1D bar's",
                ),
            });
        }
        rows
    }

    /// [V21 §7.5, Figs 20, 21(b)]: the tensile wave of `v21-3d-tensile-wave.json` in 3D (0.2 m,
    /// 200 particles, E = 70.8 GPa, ν = 0.108, ρ = 1550, 7-layer ends pulled at ±70 m/s,
    /// viscosity 0.5, symmetry planes on the four sides; m4, h = 1.3Δx, Δt = 0.5Δx/c_L
    /// sphstab's choice) at 20 μs, on the 1 × 1 section. Analytic in uniaxial strain: σ1 =
    /// ρ c_L v, c_L = √(E(1 − ν)/((1 + ν)(1 − 2ν))/ρ); the criteria of row V21 Figs 19, 20,
    /// 21(a).
    /// [B00 §6.1] (Figs 19, 20, Plate 1): the Taylor bar, `b00-taylor-bar.json` — classical SPH on
    /// a quarter of the bar in 3D (two symmetry planes on the axis, a round section of 5
    /// particles per radius) with the wall as a third symmetry plane, J2 plasticity (B00's
    /// material), V21's viscosity α = 0.5. B00 solves the axisymmetric problem with EFG (20 × 50
    /// nodes, cell quadrature or stress points); the SPH form, the resolution and the viscosity
    /// are sphstab's choice. The finer bar (10 particles per radius,
    /// `b00-taylor-bar-fine.json`, 4 minutes) is quoted from docs/simulate.md, not run here.
    pub fn b00_taylor_rows() -> Vec<Row> {
        let s = scene("b00-taylor-bar.json");
        let r = run(&s);
        let (t, len, rad) = (
            *r.extent_t.last().unwrap(),
            *r.extent_length.last().unwrap(),
            *r.extent_radius.last().unwrap(),
        );
        let (l0, r0) = (r.extent_length[0], r.extent_radius[0]);
        let ep = r.max_plastic_strain.unwrap();
        // the histories at 20, 40, 60 μs
        let at = |q: &[f64], when: f64| {
            let k = r.extent_t.iter().position(|&x| x >= when).unwrap();
            q[k]
        };
        let hist = |q: &[f64]| {
            [20e-6, 40e-6, 60e-6]
                .iter()
                .map(|&w| format!("{:.2}", at(q, w) * 1e3))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let how = "`sphstab simulate analysis/scenes/b00-taylor-bar.json --json` (extent_t, extent_length, extent_radius, max_plastic_strain); `sphstab figures` → figures/b00_fig20_taylor_bar.svg";
        let (dyna_r, dyna_h) = (7.03e-3, 21.47e-3);
        vec![
            Row {
                item: "B00 Fig 19",
                shows: "Taylor bar set-up (r = 3.2 mm, 32.4 mm, 227 m/s, J2 plasticity, 20×50 nodes)",
                how,
                paper: "a copper cylinder, r = 3.2 mm, 32.4 mm, at 227 m/s onto a rigid surface; ρ = 8930, E = 117 GPa, ν = 0.35, E_p = 100 MPa, σ_Y = 400 MPa, J2 flow with linear isotropic hardening; axisymmetric EFG, 20 × 50 nodes, Δt = 0.005 μs (§6.1)".into(),
                ours: format!(
                    "a quarter of the bar in 3D, {} particles ({} ghosts: the planes y = 0, z = 0 and the wall x = 0), Δx = {:.2} mm, initial radius {:.2} mm and height {:.2} mm (51 columns of 0.64 mm), {} steps of {:.3} μs; the wall is a symmetry plane (the bar meets its mirror image: a frictionless rigid wall, tests/it/plasticity.rs), J2 checked against uniaxial strain's closed form",
                    r.particles,
                    r.ghosts,
                    r.dx_physical * 1e3,
                    r0 * 1e3,
                    l0 * 1e3,
                    r.steps,
                    r.dt_physical * 1e6
                ),
                agree: verdict(
                    r.particles > 0 && (r0 - 3.2e-3).abs() < 1e-12,
                    "the set-up built (3D quarter for B00's axisymmetric half, classical SPH for EFG)",
                ),
            },
            Row {
                item: "B00 Fig 20",
                shows: "Taylor bar radius and height vs time to 80 μs (radius 7.13/6.98 mm, height 21.46 mm; DYNA3D 7.03/21.47)",
                how,
                paper: "at 80 μs: radius 7.13 mm (cell integration), 6.98 mm (stress points), DYNA3D 7.03 mm; height 21.46 mm (both), DYNA3D 21.47 mm".into(),
                ours: format!(
                    "radius at 20, 40, 60 μs: {} mm; at {:.0} μs {:.2} mm ({:+.1}% of DYNA3D); height at 20, 40, 60 μs: {} mm; at {:.0} μs {:.2} mm ({:+.1}%; shortening {:.2} mm against DYNA3D's 10.93)",
                    hist(&r.extent_radius),
                    t * 1e6,
                    rad * 1e3,
                    100.0 * (rad / dyna_r - 1.0),
                    hist(&r.extent_length),
                    t * 1e6,
                    len * 1e3,
                    100.0 * (len / dyna_h - 1.0),
                    (l0 - len) * 1e3
                ),
                agree: if (rad / dyna_r - 1.0).abs() < 0.03 && (len / dyna_h - 1.0).abs() < 0.1 {
                    format!(
                        "partly (the radius within {:.1}% of DYNA3D and between B00's two, the bar {:.1}% too long, at 5 particles per radius; at 10 per radius, b00-taylor-bar-fine.json in docs/simulate.md, the height is 21.72 mm, +1.2%, and the radius 7.67 mm, +9.1%: the impact face's edge particle runs out further)",
                        100.0 * (rad / dyna_r - 1.0).abs(),
                        100.0 * (len / dyna_h - 1.0)
                    )
                } else {
                    verdict(false, "radius or height off the criteria")
                },
            },
            Row {
                item: "B00 Plate 1",
                shows: "Taylor bar deformed shape, equivalent plastic strain (max 3.33 cell, 3.18 stress points, DYNA3D 2.96)",
                how,
                paper: "maximum equivalent plastic strain 3.33 (cell integration), 3.18 (stress points), DYNA3D 2.96, at the impact face's edge".into(),
                ours: format!("maximum ε̄ᵖ at {:.0} μs: {ep:.2}", t * 1e6),
                agree: if ep > 1.0 {
                    format!(
                        "partly (the peak, at the corner of the impact face, is {:.0}% of DYNA3D's at 5 particles per radius; at 10 per radius 3.60, 122% of DYNA3D's and 108% of B00's cell-integration value: the corner's peak is not converged in either)",
                        100.0 * ep / 2.96
                    )
                } else {
                    verdict(false, "the bar barely yields")
                },
            },
        ]
    }

    pub fn v21_tensile_rows() -> Vec<Row> {
        let base = scene("v21-3d-tensile-wave.json");
        let (e, nu, rho, v, t): (f64, f64, f64, f64, f64) = (70.8e9, 0.108, 1550.0, 70.0, 2e-5);
        let c = (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) / rho).sqrt();
        let s1 = rho * c * v;
        let n = base.particles;
        let dx = base.length / (n - 1) as f64;
        let x: Vec<f64> = (0..n).map(|i| base.origin + i as f64 * dx).collect();
        let (lw, rw) = (7, 7);
        let (xl, xr) = (x[lw - 1], x[n - rw]);
        let ct = c * t;
        let measure = |r: &SceneReport| {
            let st: Vec<f64> = r.centre_row.iter().map(|&i| r.final_stress[i]).collect();
            super::tensile_wave_measure(&x, &st, (lw, rw), (xl, xr), ct, s1, dx)
        };
        let with = |form: &str, section: Vec<usize>, t_end: f64| {
            let mut s = base.clone();
            s.form = form.into();
            s.section = section;
            s.t_end = t_end;
            s
        };
        // the set-up: one step of the 10 × 10 section (1 cm at Δx = 1.005 mm)
        let ((setup, cl), nl) = rayon::join(
            || {
                rayon::join(
                    || run(&with("nonlocal", vec![10, 10], 0.5 * dx / c)),
                    || run(&with("classical", vec![1, 1], t)),
                )
            },
            || run(&with("nonlocal", vec![1, 1], t)),
        );
        let (mc, mn) = (measure(&cl), measure(&nl));
        let matches = |r: &(f64, f64, f64)| {
            (r.0 / (2.0 * s1) - 1.0).abs() <= 0.05 && (r.1 / s1 - 1.0).abs() <= 0.05 && r.2 < 0.1
        };
        let fmt = |r: &(f64, f64, f64)| {
            format!(
                "overlap {:.3} GPa, single {:.3} GPa, RMS dev. {:.3}",
                r.0 / 1e9,
                r.1 / 1e9,
                r.2
            )
        };
        vec![
            Row {
                item: "V21 Fig 20 (3D)",
                shows: "3D tensile-wave set-up: 1 × 1 cm section, symmetry planes on ±Y, ±Z, the initial axial velocity (7-particle end layers at ∓70 m/s)",
                how: "`sphstab simulate analysis/scenes/v21-3d-tensile-wave.json --out DIR`",
                paper: "1 × 1 cm section with symmetry planes in ±Y, ±Z to generate a 1D strain state; 200 particles along the length, 7-particle end layers with the prescribed velocity (§7.5)".into(),
                ours: format!(
                    "200 × 10 × 10 particles (Δx = {:.4} mm, the section 10Δx = {:.3} cm) and {} ghosts; c_L = {c:.0} m/s (ν = 0.108: {:.2}% above √(E/ρ))",
                    dx * 1e3,
                    10.0 * dx * 100.0,
                    setup.ghosts,
                    100.0 * (c / (e / rho).sqrt() - 1.0)
                ),
                agree: verdict(setup.particles == 20_000, "the set-up built and run"),
            },
            Row {
                item: "V21 Fig 21(b)",
                shows: "tensile wave in 3D at 20 μs (the bar of Fig 20 between symmetry planes, central row)",
                how: "`sphstab simulate analysis/scenes/v21-3d-tensile-wave.json --form F --out DIR` (F = classical, nonlocal)",
                paper: format!(
                    "as in 1D: classical unstable with large oscillations, nonlocal and lnl match the analytic solution (§7.5); analytic (derived here, uniaxial strain): σ1 = ρ c_L v = {:.0} MPa, overlap {:.3} GPa",
                    s1 / 1e6,
                    2.0 * s1 / 1e9
                ),
                ours: format!(
                    "1 × 1 section: classical {}; nonlocal {} (lnl, 7× nonlocal's cost in 3D, left to the 1D row)",
                    fmt(&mc),
                    fmt(&mn)
                ),
                agree: if matches(&mn) && mc.2 > 0.2 {
                    verdict(true, "read as in 1D: matches = plateaus within 5%, RMS < 0.1; unphysical = RMS > 0.2")
                } else if matches(&mn) {
                    format!(
                        "partly (nonlocal matches ✔: plateaus within 5%, RMS < 0.1; classical is not yet unphysical at 20 μs, RMS {:.3} ≤ 0.2, as in 1D)",
                        mc.2
                    )
                } else {
                    verdict(false, "nonlocal off the analytic solution")
                },
            },
        ]
    }
}

/// [B98 §6.2.1]: the cantilever (E = 1000, ν = 0.3, D = 1, L = 8, plane stress; P = 1, which the
/// relative errors do not see) by `sphstab::studies::galerkin::cantilever` with nodal
/// quadrature at Δx = 1/4, 1/8, 1/16 (s = √2Δx, eq 126; B98 gives no refinement sequence:
/// these and the least-squares rate over them are sphstab's choice), errors at the nodes
/// (eqs 114–119; the nodal coefficients as "nodal values"). Methods SPH, RL, CD1, MLS, EFG; JB
/// and CD2 are not built yet. Table III's plate rates come from [`b98_plate`].
fn b98_beam(plate: &PlateResults) -> [Row; 4] {
    use sphstab::studies::galerkin::{Cantilever, GalerkinMethod, cantilever, rate};
    let b = Cantilever::B98;
    let levels = [4usize, 8, 16];
    let methods = [
        GalerkinMethod::Sph,
        GalerkinMethod::Rl,
        GalerkinMethod::Cd1,
        GalerkinMethod::Mls,
        GalerkinMethod::Efg,
    ];
    // per method: (l2 errors, energy errors, l2 rate, energy rate)
    let res: Vec<(Vec<f64>, Vec<f64>, f64, f64)> = methods
        .par_iter()
        .map(|&m| {
            let r: Vec<_> = levels
                .iter()
                .map(|&l| cantilever(&b, m, l).unwrap())
                .collect();
            let h: Vec<f64> = r.iter().map(|x| x.spacing).collect();
            let du: Vec<f64> = r.iter().map(|x| x.displacement_error).collect();
            let de: Vec<f64> = r.iter().map(|x| x.energy_error).collect();
            let (ru, re) = (rate(&h, &du), rate(&h, &de));
            (du, de, ru, re)
        })
        .collect();
    let monotone = |v: &[f64]| v.windows(2).all(|w| w[1] < w[0]);
    let show = |k: usize, energy: bool| {
        let (du, de, ru, re) = &res[k];
        let (v, r) = if energy { (de, re) } else { (du, ru) };
        let vals = if v.iter().all(|x| *x < 1e-2) {
            v.iter()
                .map(|x| format!("{x:.1e}"))
                .collect::<Vec<_>>()
                .join(", ")
        } else {
            list(v, 3)
        };
        if monotone(v) {
            format!("{} {vals} (rate {r:.2})", methods[k].name())
        } else {
            format!("{} {vals} (not monotone)", methods[k].name())
        }
    };
    let all = |energy: bool| {
        (0..methods.len())
            .map(|k| show(k, energy))
            .collect::<Vec<_>>()
            .join("; ")
    };
    let conv = |k: usize| monotone(&res[k].0) && res[k].2 > 1.0;
    let how = "`sphstab galerkin --problem beam` (levels 4, 8, 16: Δx = 1/4, 1/8, 1/16); `sphstab figures` → figures/b98_figs5_6_beam.svg";
    let mls = &res[3];
    let cd1 = &res[2];
    let efg = &res[4];
    [
        Row {
            item: "B98 Fig 3",
            shows: "cantilever beam set-up (E = 1000, ν = 0.3, D = 1, L = 8; eqs 120–124, displacements prescribed at x = 0 through a row of bilinear elements, the shear load at x = L)",
            how,
            paper: "Timoshenko's solution, eqs 120–124; s = √2Δx (eq 126), \"an average of 21 neighbours\" (§6.2.1)".into(),
            ours: "eqs 122–124 are plane-stress Hooke's law of eqs 120–121 (central differences, tests/it/galerkin.rs), the end shear's resultant is P, the edges traction-free; 21 lattice nodes within 2s = 2√2Δx of an interior node (the four at (±2, ±2)Δx lie on the support's edge, W = 0)".into(),
            agree: verdict(true, "the set-up built and its exact solution checked"),
        },
        Row {
            item: "B98 Fig 5",
            shows: "strain-energy convergence, beam (SPH, JB, CD1, CD2, MLS, EFG)",
            how,
            paper: "JB improves SPH \"slightly\"; CD1 and CD2 \"very close\" to MLS (§6.2.1); Table III energy rates: SPH NC, RL 0.98, CD1 1.29, MLS 1.50, EFG 1.50".into(),
            ours: format!("energy errors (at the nodes; EFG by its Gauss points), Δx = 1/4, 1/8, 1/16: {}", all(true)),
            agree: format!(
                "partly (EFG's rate {:.2} against 1.50 ✔, MLS's {:.2} against 1.50, CD1's {:.2} against 1.29: the trend; SPH's energy error {} here where B98 has NC: with the 2D normalisation of the kernel (B98 prints only the 1D one, eq 26) the symmetrised gradient is linear-exact inside a uniform grid, so its error lies in the boundary layer, which thins; JB, CD2 need code)",
                efg.3,
                mls.3,
                cd1.3,
                if monotone(&res[0].1) {
                    format!("falls, rate {:.2},", res[0].3)
                } else {
                    "does not fall".into()
                }
            ),
        },
        Row {
            item: "B98 Fig 6",
            shows: "L2 displacement convergence, beam",
            how,
            paper: "\"convergence in the l2 norm\" for CD1, CD2, MLS, EFG (§6.2.1); Table III L2 rates: SPH NC, RL 0.41, CD1 1.84, MLS 1.82, EFG 2.00".into(),
            ours: format!("displacement errors (nodal l2; EFG: L2 by its Gauss points), Δx = 1/4, 1/8, 1/16: {}", all(false)),
            agree: if conv(2) && conv(3) && !monotone(&res[0].0) {
                format!(
                    "partly (CD1 and MLS converge, rates {:.2} and {:.2} against 1.84 and 1.82; SPH does not; RL converges in the nodal norm, rate {:.2}, where B98's 0.41 is its Gauss-integrated L2 of a field RL does not define; EFG's L2 error is {:.0e} or less at every level, B98's rate 2.00 not seen: a floor near 1e-4 not yet explained; JB, CD2 need code)",
                    cd1.2,
                    mls.2,
                    res[1].2,
                    efg.0.iter().fold(0.0f64, |m, v| m.max(*v))
                )
            } else {
                verdict(false, "CD1 or MLS does not converge, or SPH does")
            },
        },
        Row {
            item: "B98 Table III",
            shows: "convergence rates, cantilever beam and plate with a hole (SPH, JB, RL, CD1, CD2, MLS, EFG)",
            how,
            paper: "beam energy / L2: SPH NC/NC, JB NC/NC, RL 0.98/0.41, CD1 1.29/1.84, CD2 1.29/1.84, MLS 1.50/1.82, EFG 1.50/2.00; plate: RL 0.51/0.62, CD1 0.54/1.10, CD2 0.49/1.30, MLS 0.65/1.22, EFG 1.50/2.50".into(),
            ours: format!(
                "beam, energy / nodal l2 rates over Δx = 1/4, 1/8, 1/16: SPH {}/{}, RL {:.2}/{:.2}, CD1 {:.2}/{:.2}, MLS {:.2}/{:.2}, EFG {:.2}/{} (Gauss-integrated)",
                if monotone(&res[0].1) { format!("{:.2}", res[0].3) } else { "NC".into() },
                if monotone(&res[0].0) { format!("{:.2}", res[0].2) } else { "NC".into() },
                res[1].3,
                res[1].2,
                cd1.3,
                cd1.2,
                mls.3,
                mls.2,
                efg.3,
                if monotone(&efg.0) { format!("{:.2}", efg.2) } else { "not monotone at 1e-4".into() }
            ) + &format!("; plate, over Δx = 1/2, 1/4, 1/8: {}", plate.rates()),
            agree: "partly (the beam with SPH, RL, CD1, MLS under nodal quadrature and EFG: the trend; the plate: EFG's rates as B98's, the nodal-quadrature methods' energy rates lower and their l2 errors not converging on sphstab's node set (rows B98 Figs 8–9); the rates depend on the refinement range and the node set, which B98 does not give; JB and CD2 need code)".into(),
        },
    ]
}

/// The plate with a hole's results: per method (name, l2 errors, energy errors, integrated
/// energy errors, l2 rate, energy rate), with the spacings, the node counts and the EFG probe.
struct PlateResults {
    spacings: Vec<f64>,
    nodes: Vec<usize>,
    methods: Vec<PlateMethod>,
    probe: (f64, f64),
}

/// One method's plate errors: (name, l2, energy, integrated energy, l2 rate, energy rate).
type PlateMethod = (&'static str, Vec<f64>, Vec<f64>, Vec<f64>, f64, f64);

impl PlateResults {
    fn get(&self, name: &str) -> &PlateMethod {
        self.methods.iter().find(|m| m.0 == name).unwrap()
    }

    fn rates(&self) -> String {
        let monotone = |v: &[f64]| v.windows(2).all(|w| w[1] < w[0]);
        let r = |v: &[f64], rate: f64| {
            if !monotone(v) {
                "NC".into()
            } else if v.iter().all(|e| *e > 1.0) {
                format!("{rate:.2} (errors above 1)")
            } else {
                format!("{rate:.2}")
            }
        };
        self.methods
            .iter()
            .map(|(name, du, de, _, ru, re)| format!("{name} {}/{}", r(de, *re), r(du, *ru)))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// [B98 §6.2.2]: the plate with a hole (E = 1000, ν = 0.3, a = 1, b = 5, unit traction at
/// infinity, plane stress) by `sphstab::studies::galerkin::plate_with_hole` at Δx = 1/2, 1/4,
/// 1/8 along the symmetry edges (s = √2Δx, eq 130; the mapped node set and the refinement
/// sequence are sphstab's choice, B98 gives neither), every method of the beam and CD1 with
/// background quadrature (Fig 11).
fn b98_plate_results() -> PlateResults {
    use sphstab::studies::galerkin::{GalerkinMethod, PlateWithHole, plate_with_hole, rate};
    let p = PlateWithHole::B98;
    let levels = [2usize, 4, 8];
    let mut out = PlateResults {
        spacings: Vec::new(),
        nodes: Vec::new(),
        methods: Vec::new(),
        probe: (0.0, 0.0),
    };
    let methods = [
        (GalerkinMethod::Sph, "SPH"),
        (GalerkinMethod::Rl, "RL"),
        (GalerkinMethod::Cd1, "CD1"),
        (GalerkinMethod::Mls, "MLS"),
        (GalerkinMethod::Efg, "EFG"),
        (GalerkinMethod::Cd1Gauss, "CD1 (Gauss)"),
    ];
    // the methods are independent: solved in parallel, collected in order
    let runs: Vec<Vec<_>> = methods
        .par_iter()
        .map(|&(m, _)| {
            levels
                .iter()
                .map(|&l| plate_with_hole(&p, m, l).unwrap())
                .collect()
        })
        .collect();
    for (&(m, name), r) in methods.iter().zip(&runs) {
        let h: Vec<f64> = r.iter().map(|x| x.spacing).collect();
        let du: Vec<f64> = r.iter().map(|x| x.displacement_error).collect();
        let de: Vec<f64> = r.iter().map(|x| x.energy_error).collect();
        let di: Vec<f64> = r
            .iter()
            .map(|x| x.integrated_energy_error.unwrap_or(f64::NAN))
            .collect();
        if m == GalerkinMethod::Efg {
            let last = &r[r.len() - 1];
            out.probe = (last.probe_displacement, last.exact_probe_displacement);
        }
        out.spacings = h.clone();
        out.nodes = r.iter().map(|x| x.nodes).collect();
        out.methods.push((
            name,
            du.clone(),
            de.clone(),
            di,
            rate(&h, &du),
            rate(&h, &de),
        ));
    }
    out
}

/// The rows of [B98] Figs 7–11 from [`b98_plate_results`].
fn b98_plate(res: &PlateResults) -> [Row; 5] {
    use sphstab::studies::galerkin::rate;
    let how = "`sphstab galerkin --problem plate` (levels 2, 4, 8: Δx = 1/2, 1/4, 1/8); `sphstab figures` → figures/b98_figs8_11_plate.svg";
    let monotone = |v: &[f64]| v.windows(2).all(|w| w[1] < w[0]);
    let fmt = |v: &[f64]| {
        v.iter()
            .map(|x| {
                if *x < 1e-2 {
                    format!("{x:.1e}")
                } else {
                    format!("{x:.3}")
                }
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let show = |which: usize, names: &[&str]| {
        names
            .iter()
            .map(|n| {
                let m = res.get(n);
                let (v, r) = match which {
                    0 => (&m.1, m.4),
                    1 => (&m.2, m.5),
                    _ => (&m.3, rate(&res.spacings, &m.3)),
                };
                if monotone(v) {
                    format!("{n} {} (rate {r:.2})", fmt(v))
                } else {
                    format!("{n} {} (not monotone)", fmt(v))
                }
            })
            .collect::<Vec<_>>()
            .join("; ")
    };
    let nodal = ["SPH", "RL", "CD1", "MLS"];
    let efg = res.get("EFG");
    let cdg = res.get("CD1 (Gauss)");
    let nodal_energy_falls = nodal.iter().all(|n| monotone(&res.get(n).2));
    let nodal_l2_diverges = nodal.iter().all(|n| res.get(n).1.iter().all(|e| *e > 1.0));
    let spacing = format!(
        "Δx = {} ({} nodes)",
        res.spacings
            .iter()
            .map(|h| format!("1/{:.0}", 1.0 / h))
            .collect::<Vec<_>>()
            .join(", "),
        res.nodes
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let (probe, exact) = res.probe;
    [
        Row {
            item: "B98 Fig 7",
            shows: "plate with a hole set-up (a = 1, b = 5, E = 1000, ν = 0.3)",
            how,
            paper: "quarter model, \"the tractions from the exact solution are applied to the outer boundaries\", zero normal displacement on the symmetry boundaries, s = √2Δx^boundary (eq 130); Kirsch's stresses (eqs 127–129)".into(),
            ours: format!(
                "eqs 127–129 are plane-stress Hooke's law of the displacement field B98 does not print, the hole traction-free, the far field the unit tension, no normal displacement on the axes (tests/it/galerkin.rs); a mapped grid, 2m + 1 nodes around and m + 1 along each radial line, m = 4/Δx, a row of finite elements on the symmetry edges; EFG's u_x(a, 0) at Δx = 1/8: {probe:.5e} against {exact:.5e}"
            ),
            agree: verdict(
                (probe / exact - 1.0).abs() < 1e-3,
                "the set-up built and its exact solution checked; the node set is sphstab's (B98's is drawn, not given)",
            ),
        },
        Row {
            item: "B98 Fig 8",
            shows: "strain-energy convergence, plate with a hole",
            how,
            paper: "Table III plate energy rates: SPH NC, RL 0.51, CD1 0.54, CD2 0.49, MLS 0.65, EFG 1.50; \"the convergence rates observed in the hole problem were much lower than in the beam problem\" (§6.2.3)".into(),
            ours: format!("energy errors (at the nodes; EFG and CD1 (Gauss) by their Gauss points), {spacing}: {}", show(1, &["SPH", "RL", "CD1", "MLS", "EFG", "CD1 (Gauss)"])),
            agree: if nodal_energy_falls && monotone(&efg.2) {
                format!(
                    "partly (EFG's rate {:.2} against 1.50; the nodal-quadrature methods' errors fall more slowly than the beam's, as B98 says, at rates {} against 0.51–0.65, and SPH's falls where B98 has NC: on this node set nodal quadrature has spurious modes near the hole, Fig 9)",
                    efg.5,
                    nodal.iter().map(|n| format!("{:.2}", res.get(n).5)).collect::<Vec<_>>().join(", ")
                )
            } else {
                verdict(false, "an energy error does not fall")
            },
        },
        Row {
            item: "B98 Fig 9",
            shows: "L2 convergence, plate with a hole",
            how,
            paper: "Table III plate L2 rates: SPH NC, RL 0.62, CD1 1.10, CD2 1.30, MLS 1.22, EFG 2.50".into(),
            ours: format!("displacement errors (nodal l2; EFG and CD1 (Gauss): L2 by their Gauss points), {spacing}: {}", show(0, &["SPH", "RL", "CD1", "MLS", "EFG", "CD1 (Gauss)"])),
            agree: if monotone(&efg.1) && nodal_l2_diverges {
                format!(
                    "partly (EFG's rate {:.2} against 2.50 ✔, CD1 with Gauss quadrature {:.2}; under nodal quadrature every method's nodal displacements are off by more than the solution itself: near the hole the nodes are 5 times closer around than along the radius, s follows the radial spacing (eq 130), and an odd–even mode around the hole, which nodal quadrature barely stiffens, takes the load; B98 reports convergence there, on a node set it does not give)",
                    efg.4, cdg.4
                )
            } else {
                verdict(false, "EFG does not converge, or the nodal methods do")
            },
        },
        Row {
            item: "B98 Fig 10",
            shows: "\"energy norm\" convergence with nodal quadrature",
            how,
            paper: "with nodal quadrature \"MLS Galerkin ... does not converge\", nor do Shepard Galerkin and CD1 (§6.2.3); the caption's energy norm is the text's L2 norm (E16)".into(),
            ours: format!("energy errors by 5 × 5 Gauss quadrature on the node cells, of the nodal-quadrature solutions, {spacing}: {}", show(2, &["CD1", "MLS"])),
            agree: verdict(
                ["CD1", "MLS"].iter().all(|n| res.get(n).3.iter().all(|e| *e > 1.0)),
                "neither converges: the integrated errors exceed the exact solution's energy at every level; Shepard Galerkin is not built",
            ),
        },
        Row {
            item: "B98 Fig 11",
            shows: "as Fig 10 with full background integration",
            how,
            paper: "\"excellent convergence for the corrected derivative and MLS approximations\" with 5 × 5 Gauss quadrature (§6.2.3); caption as Fig 10 (E16)".into(),
            ours: format!("energy errors of the Gauss-quadrature solutions, {spacing}: {}", show(2, &["EFG", "CD1 (Gauss)"])),
            agree: verdict(
                monotone(&efg.3) && monotone(&cdg.3) && rate(&res.spacings, &efg.3) > 1.0 && rate(&res.spacings, &cdg.3) > 0.8,
                "both converge, MLS (EFG) faster than CD1",
            ),
        },
    ]
}

/// The interpolations of [T §2.7] (Figs 2.10–2.20), by `sphstab interpolate`'s code. The thesis
/// names no kernel for §2.7 (§6.1: the modified mollifier "was used in all the SPH
/// implementations"), no particle count and only two covers (1.5 and 5.5 ps): the mollifier,
/// the counts and the covers 1.5, 2.5, 3.5, 5.5, 7.5 ps (= h/Δx, ζ = 1) are sphstab's choice,
/// fixed with each row's criterion before it was computed.
mod interp {
    use super::{Row, list, verdict};
    use sphstab::kernel;
    use sphstab::studies::interpolation::{
        InterpolationConfig, InterpolationReport, Normalisation, TestFunction, interpolate,
    };
    use std::f64::consts::PI;

    pub const COVERS: [f64; 5] = [1.5, 2.5, 3.5, 5.5, 7.5];

    fn run_k(
        kern: &str,
        f: TestFunction,
        interval: (f64, f64),
        n: usize,
        h: f64,
        ghosts: bool,
        norm: Normalisation,
    ) -> InterpolationReport {
        let mut c = InterpolationConfig::new(f, kernel::by_name(kern).unwrap(), h);
        c.interval = interval;
        c.particles = n;
        c.ghosts = ghosts;
        c.normalisation = norm;
        interpolate(&c).unwrap()
    }

    fn covers_k(
        kern: &str,
        f: TestFunction,
        interval: (f64, f64),
        n: usize,
        ghosts: bool,
        norm: Normalisation,
    ) -> Vec<InterpolationReport> {
        COVERS
            .iter()
            .map(|&h| run_k(kern, f, interval, n, h, ghosts, norm))
            .collect()
    }

    /// [`covers_k`] with the modified mollifier.
    fn covers(
        f: TestFunction,
        interval: (f64, f64),
        n: usize,
        ghosts: bool,
        norm: Normalisation,
    ) -> Vec<InterpolationReport> {
        covers_k("mollifier", f, interval, n, ghosts, norm)
    }

    fn pct(v: &[f64]) -> String {
        list(&v.iter().map(|x| 100.0 * x).collect::<Vec<_>>(), 1)
    }

    /// Max relative errors of f, f′, f″ per cover.
    fn errs(r: &[InterpolationReport]) -> [Vec<f64>; 3] {
        [
            r.iter().map(|r| r.value.max).collect(),
            r.iter().map(|r| r.gradient.unwrap().max).collect(),
            r.iter().map(|r| r.laplacian.unwrap().max).collect(),
        ]
    }

    const C: Normalisation = Normalisation::Continuum;
    const L: Normalisation = Normalisation::Lattice;
    const Q: TestFunction = TestFunction::Quartic;
    const S: TestFunction = TestFunction::Sine;

    /// Fig 2.10: (x − ½)⁴ without ghosts.
    fn fig210() -> Row {
        let r = covers(Q, (0.0, 1.0), 101, false, C);
        let at_a: Vec<f64> = r.iter().map(|r| r.value_at_start.unwrap()).collect();
        let interior: Vec<f64> = r.iter().map(|r| r.value.interior_max.unwrap()).collect();
        let ok = (0.25..=0.75).contains(&at_a[3])
            && r[1..]
                .iter()
                .all(|r| r.value.boundary_max > 10.0 * r.value.interior_max.unwrap());
        Row {
            item: "Thesis Fig 2.10",
            shows: "interpolation of (x − 0.5)⁴ on (0, 1) without ghosts (101 particles and the modified mollifier: sphstab's choice)",
            how: "`sphstab interpolate --function quartic --particles 101 --h 1.5,2.5,3.5,5.5,7.5`; `sphstab figures` → figures/thesis_fig2_10_interpolation.svg",
            paper: "\"the approximation can have an error of up to 50% at the boundary\" (§2.7); particle count and covers not given".into(),
            ours: format!(
                "relative error of ⟨f⟩ at x = 0, covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: {} %; largest error (relative to max f) away from the boundary: {} %",
                pct(&at_a),
                list(&interior.iter().map(|x| 100.0 * x).collect::<Vec<_>>(), 2)
            ),
            agree: verdict(
                ok,
                "read as: at the recommended 5.5 ps the error at x = 0 is between 25% and 75%, and for every cover ≥ 2.5 ps the largest error near the boundary is > 10× the interior's; the boundary particle sees half a cover",
            ),
        }
    }

    /// Figs 2.11 and 2.12: (x − ½)⁴ with ghosts, fine (101) and coarse (11 particles).
    fn fig211_212() -> [Row; 2] {
        let fine = covers(Q, (0.0, 1.0), 101, true, C);
        let [fv, fg, fl] = errs(&fine);
        let ok_fine =
            (1..5).all(|i| fv[i] <= 0.05 && fg[i] <= 0.05 && fl[i] <= 0.05) && fg[0] >= 0.2;
        let coarse = covers(Q, (0.0, 1.0), 11, true, C);
        let [cv, _, _] = errs(&coarse);
        let ok_coarse = cv.iter().all(|&e| e >= 0.05);
        [
            Row {
                item: "Thesis Fig 2.11",
                shows: "(x − 0.5)⁴ with ghosts, fine discretisation (101 particles: sphstab's choice): f and its first and second derivatives for several covers",
                how: "`sphstab interpolate --function quartic --particles 101 --ghosts --h 1.5,2.5,3.5,5.5,7.5`",
                paper: "\"most cover sizes interpolate the function and its first and second derivatives well\"; \"the very small cover size of 1.5 times the particle spacing does not approximate the gradients well\" (§2.7)".into(),
                ours: format!(
                    "max relative error at covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: f {} %, f′ {} %, f″ {} %",
                    pct(&fv),
                    pct(&fg),
                    pct(&fl)
                ),
                agree: verdict(
                    ok_fine,
                    "read as: every error ≤ 5% at the four covers ≥ 2.5 ps, and the gradient's ≥ 20% at 1.5 ps",
                ),
            },
            Row {
                item: "Thesis Fig 2.12",
                shows: "(x − 0.5)⁴ with ghosts, coarse discretisation (11 particles: sphstab's choice)",
                how: "`sphstab interpolate --function quartic --particles 11 --ghosts --h 1.5,2.5,3.5,5.5,7.5`",
                paper: "\"substantial errors are seen in the interpolation of the function, regardless of the cover sizes used\" (§2.7)".into(),
                ours: format!(
                    "max relative error of f at covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: {} %",
                    pct(&cv)
                ),
                agree: verdict(ok_coarse, "read as: ≥ 5% at every cover"),
            },
        ]
    }

    /// Figs 2.13–2.16: sin x with ghosts on (0, 3π) (fine 121, coarse 16 particles) and on
    /// (0, π) with the same counts (very fine, intermediate).
    fn sine_rows() -> [Row; 4] {
        let three = (0.0, 3.0 * PI);
        let one = (0.0, PI);
        let fine = covers(S, three, 121, true, C);
        let finer = covers(S, three, 241, true, C);
        let coarse = covers(S, three, 16, true, C);
        let vfine = covers(S, one, 121, true, C);
        let inter = covers(S, one, 16, true, C);
        let inter_l = covers(S, one, 16, true, L);
        // the gradient's amplitude at x = 0 (f′ = 1 there)
        let gain = |r: &InterpolationReport| r.gradient_x_approx[0];
        let [fv, fg, _] = errs(&fine);
        let [_, fg2, _] = errs(&finer);
        let g55 = gain(&fine[3]);
        let ok13 = fv[1..].iter().all(|&e| e <= 0.05) && g55 < 1.0 && fg2[3] < fg[3];
        let [cv, cg, _] = errs(&coarse);
        let ok14 = cv[3] >= 0.05 && cg[0] >= 0.2;
        let [vv, vg, vl] = errs(&vfine);
        // resolution lowers the errors that depend on it; at 1.5 and 2.5 ps the lattice sums
        // S0 = Σ W ΔV and S1 = Σ x W′ ΔV differ from 1 and set an error no resolution removes
        let ok15 = (2..5).all(|i| vv[i] < fv[i] && vg[i] < fg[i]);
        let ok15_all = (0..5).all(|i| vv[i] <= fv[i] && vg[i] <= fg[i]);
        let [iv, ig, _] = errs(&inter);
        let [ivl, igl, _] = errs(&inter_l);
        let ok16 = iv[0] <= 0.05 && ig[0] >= 0.2;
        let ok16_l = ivl[0] <= 0.05 && igl[0] >= 0.2;
        [
            Row {
                item: "Thesis Fig 2.13",
                shows: "sin x on (0, 3π) with ghosts, fine discretisation (121 particles, 80 per wavelength: sphstab's choice)",
                how: "`sphstab interpolate --function sine --particles 121 --ghosts --h 1.5,2.5,3.5,5.5,7.5` (and `--particles 241`)",
                paper: "\"a fine discretisation … results in a good interpolation approximation. The gradients, however, see an amplitude reduction … an increased number of particles reduces the error\" (§2.7.1)".into(),
                ours: format!(
                    "max relative error at covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: f {} %, f′ {} %; f′ amplitude at 5.5 ps {:.4} (exact 1); f′ error at 5.5 ps with 241 particles {:.2} % (121: {:.2} %)",
                    pct(&fv),
                    pct(&fg),
                    g55,
                    100.0 * fg2[3],
                    100.0 * fg[3]
                ),
                agree: verdict(
                    ok13,
                    "read as: f within 5% at the covers ≥ 2.5 ps, the gradient's amplitude < 1 at 5.5 ps, and its error smaller with twice the particles",
                ),
            },
            Row {
                item: "Thesis Fig 2.14",
                shows: "sin x on (0, 3π) with ghosts, coarse discretisation (16 particles, 10 per wavelength: sphstab's choice)",
                how: "`sphstab interpolate --function sine --particles 16 --ghosts --h 1.5,2.5,3.5,5.5,7.5`",
                paper: "\"a reduction in particle density … sees significant errors introduced into the interpolation. Once again, a cover size of 1.5 times the particle spacing performs poorly\" (§2.7.1)".into(),
                ours: format!(
                    "max relative error at covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: f {} %, f′ {} %",
                    pct(&cv),
                    pct(&cg)
                ),
                agree: verdict(
                    ok14,
                    "read as: f's error ≥ 5% at 5.5 ps, and the gradient's ≥ 20% at 1.5 ps",
                ),
            },
            Row {
                item: "Thesis Fig 2.15",
                shows: "sin x on (0, π) with ghosts, very fine (the 121 particles of Fig 2.13 on a third of the interval: 120 per wavelength)",
                how: "`sphstab interpolate --function sine --interval 0,pi --particles 121 --ghosts --h 1.5,2.5,3.5,5.5,7.5`",
                paper: "the function and its gradients \"at a finer resolution, keeping the total number of particles in the domain the same\" (§2.7.1); no statement specific to Fig 2.15".into(),
                ours: format!(
                    "max relative error at covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: f {} %, f′ {} %, f″ {} %",
                    pct(&vv),
                    pct(&vg),
                    pct(&vl)
                ),
                agree: match (ok15_all, ok15) {
                    (true, _) => verdict(true, "read as: at every cover the errors of f and f′ are no larger than Fig 2.13's"),
                    (false, true) => "partly (read as: at every cover the errors of f and f′ are no larger than Fig 2.13's: ✔ at 3.5, 5.5 and 7.5 ps; at 1.5 and 2.5 ps they are set by the kernel's lattice sums, S0 = Σ W ΔV ≠ 1 and the gradient's gain as κ → 0 ≠ 1, which no resolution removes)".into(),
                    _ => verdict(false, ""),
                },
            },
            Row {
                item: "Thesis Fig 2.16",
                shows: "sin x on (0, π) with ghosts, intermediate (the 16 particles of Fig 2.14 on a third of the interval: 30 per wavelength)",
                how: "`sphstab interpolate --function sine --interval 0,pi --particles 16 --ghosts --h 1.5,2.5,3.5,5.5,7.5` (and `--normalisation lattice`)",
                paper: "\"small cover sizes approximate the function well, but the derivative thereof poorly … (with a cover size of 1.5 times the particle spacing only two points are used to evaluate the gradient)\" (§2.7.1)".into(),
                ours: format!(
                    "max relative error at covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: f {} %, f′ {} %; with the kernel normalised on the lattice: f {} %, f′ {} % (the mollifier's lattice sum at 1.5 ps is S0 = {:.4})",
                    pct(&iv),
                    pct(&ig),
                    pct(&ivl),
                    pct(&igl),
                    inter[0].lattice_sum
                ),
                agree: if ok16 {
                    verdict(true, "read as: f within 5% and the gradient off by ≥ 20% at 1.5 ps")
                } else if ok16_l {
                    format!(
                        "partly (read as: f within 5% and the gradient off by ≥ 20% at 1.5 ps: the gradient ✔; the function ✔ only with the kernel normalised on the lattice, Σ W ΔV = 1 (§2.2.2: the mollifier's normalisation \"must be enforced using a numerical integration\"); with the kernel's own constant every value is S0 = {:.4} times too large at 1.5 ps)",
                        inter[0].lattice_sum
                    )
                } else {
                    verdict(false, "")
                },
            },
        ]
    }

    /// Figs 2.17, 2.19, 2.20: a falling edge 1 → 0 on (0, 1), 101 particles, with ghosts, over
    /// 40 and 4 spacings (very low and high gradient: sphstab's choice; over 2 spacings the
    /// samples are the step's) and the step, with the modified mollifier and with Lucy's kernel
    /// (eq 2.13, ζ = 1 like the mollifier: h is the cover); §2.7 names no kernel.
    fn edge_rows() -> [Row; 3] {
        let edge = |k: &str, w: f64| {
            covers_k(k, TestFunction::Edge { width: w }, (0.0, 1.0), 101, true, C)
        };
        // ⟨f′⟩ at the edge's centre (particle 50) over the exact −1/(WΔx)
        let centre = |r: &[InterpolationReport]| -> Vec<f64> {
            r.iter()
                .map(|r| r.gradient_x_approx[50] / r.gradient_x[50])
                .collect()
        };
        let rms = |r: &[InterpolationReport]| -> Vec<f64> {
            r.iter().map(|r| r.gradient.unwrap().rms).collect()
        };
        let [c40m, c40l] = ["mollifier", "lucy"].map(|k| centre(&edge(k, 40.0)));
        let ok17 = |c: &[f64]| c[1..].iter().all(|g| (0.9..=1.1).contains(g)) && c[0] < 1.0;
        let [r4m, r4l] = ["mollifier", "lucy"].map(|k| rms(&edge(k, 4.0)));
        let ok19 = |r: &[f64]| r[1..].iter().all(|&x| r[0] < x);
        let step = |k: &str| covers_k(k, TestFunction::Step, (0.0, 1.0), 101, true, C);
        let [sm, sl] = ["mollifier", "lucy"].map(step);
        let widths = |r: &[InterpolationReport]| -> Vec<f64> {
            r.iter().map(|r| r.gradient_peak_width.unwrap()).collect()
        };
        let integrals = |r: &[InterpolationReport]| -> Vec<f64> {
            r.iter().map(|r| r.gradient_integral.unwrap()).collect()
        };
        let ok20 = |r: &[InterpolationReport]| {
            let w = widths(r);
            w[1..].iter().all(|&x| w[0] < x) && (integrals(r)[0] + 1.0).abs() <= 0.05
        };
        let both = |m: bool, l: bool, reading: &str, why_m: &str| match (m, l) {
            (true, true) => verdict(true, &format!("{reading}; with either kernel")),
            (false, true) => format!(
                "partly ({reading}: ✔ with Lucy's kernel, not with the modified mollifier: {why_m}; note N2)"
            ),
            (true, false) => {
                format!("partly ({reading}: ✔ with the modified mollifier, not with Lucy's kernel)")
            }
            (false, false) => verdict(false, reading),
        };
        [
            Row {
                item: "Thesis Fig 2.17",
                shows: "falling edge, very low gradient (1 → 0 over 40 spacings, 101 particles on (0, 1), ghosts: sphstab's choice)",
                how: "`sphstab interpolate --function edge --edge-width 40 --ghosts --h 1.5,2.5,3.5,5.5,7.5` (and `--kernel lucy`)",
                paper: "\"all of the cover sizes perform well, with a cover size of 1.5 times the particle spacing under-predicting the gradient as before\" (§2.7.2)".into(),
                ours: format!(
                    "⟨f′⟩/f′ at the edge's centre, covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: modified mollifier {}; Lucy {}",
                    list(&c40m, 4),
                    list(&c40l, 4)
                ),
                agree: both(
                    ok17(&c40m),
                    ok17(&c40l),
                    "read as: within 10% of the exact gradient at the covers ≥ 2.5 ps, below it at 1.5 ps",
                    "",
                ),
            },
            Row {
                item: "Thesis Fig 2.19",
                shows: "falling edge, high gradient (over 4 spacings: sphstab's choice; over 2 the samples are the step's of Fig 2.20)",
                how: "`sphstab interpolate --function edge --edge-width 4 --ghosts --h 1.5,2.5,3.5,5.5,7.5` (and `--kernel lucy`)",
                paper: "\"the cover size of 1.5 times the particle spacing rapidly starts out-performing other cover sizes\" (§2.7.2)".into(),
                ours: format!(
                    "RMS gradient error relative to the exact −1/(4Δx), covers 1.5, 2.5, 3.5, 5.5, 7.5 ps: modified mollifier {} %; Lucy {} %",
                    pct(&r4m),
                    pct(&r4l)
                ),
                agree: both(
                    ok19(&r4m),
                    ok19(&r4l),
                    "read as: 1.5 ps has the smallest RMS gradient error",
                    "its 1.5-ps gradient has a gain of 0.15",
                ),
            },
            Row {
                item: "Thesis Fig 2.20",
                shows: "the discontinuous edge (a step at x = 0.5, 101 particles on (0, 1), ghosts)",
                how: "`sphstab interpolate --function step --ghosts --h 1.5,2.5,3.5,5.5,7.5` (and `--kernel lucy`); `sphstab figures` → figures/thesis_fig2_20_step_gradient.svg",
                paper: "\"a cover size of 1.5 times the particle spacing approximates the gradient very well, while the others are significantly different\" (§2.7.2); §2.7.3: 1.5 ps suits a square wave, 5.5 ps is \"a good compromise\"".into(),
                ours: format!(
                    "width (FWHM) of the computed gradient's peak, covers 1.5, 2.5, 3.5, 5.5, 7.5 ps (exact: a Dirac), and Σ⟨f′⟩Δx (exact −1): modified mollifier {} Δx, {}; Lucy {} Δx, {}",
                    list(&widths(&sm), 2),
                    list(&integrals(&sm), 3),
                    list(&widths(&sl), 2),
                    list(&integrals(&sl), 3)
                ),
                agree: both(
                    ok20(&sm),
                    ok20(&sl),
                    "read as: the narrowest peak at 1.5 ps, carrying the jump within 5%",
                    "its 1.5-ps peak is the narrowest but carries 15% of the jump",
                ),
            },
        ]
    }

    /// Every row of §2.7, in figure order.
    pub fn rows() -> Vec<Row> {
        let mut v = vec![fig210()];
        v.extend(fig211_212());
        v.extend(sine_rows());
        v.extend(edge_rows());
        v
    }
}

/// [T §4.6.3 and §5.3]: the 1D validation bar with a traction pulse and probes
/// (`analysis/scenes/thesis-traction-pulse.json`) and the stretched neo-Hookean bar
/// (`analysis/scenes/thesis-neo-hookean-stretch.json`). The thesis gives the bar, the load and
/// the probes; the pulse's length and smoothings, the particle count and the shape family are
/// sphstab's choice (stated in each row): 1001 particles (Δx = 0.15 mm, the spacing row Thesis
/// Figs 4.10–4.12 derives), the modified mollifier at h = 5.5Δx, total-Lagrangian with MLS
/// shapes (linear-exact at the ends, as the thesis's ghost particles make its boundary values),
/// a 10 μs pulse smoothed over h_t = 3 μs ("large"), 1 μs ("intermediate") and 0 ("none").
mod probes {
    use super::{FinalState, Row, erratum, list, verdict};
    use sphstab::solver::scene::{ProbeHistory, Scene, SceneReport, parse};

    const AMPLITUDE: f64 = 1e5;

    fn scene(file: &str) -> Scene {
        let path = format!("{}/analysis/scenes/{file}", env!("CARGO_MANIFEST_DIR"));
        parse(&path, &std::fs::read_to_string(&path).unwrap()).unwrap()
    }

    fn bar(smoothing: f64, t_end: f64) -> Scene {
        let mut s = scene("thesis-traction-pulse.json");
        s.left
            .as_mut()
            .unwrap()
            .traction
            .as_mut()
            .unwrap()
            .smoothing = smoothing;
        s.t_end = t_end;
        s
    }

    fn run(s: &Scene) -> SceneReport {
        s.run(|_| {}).unwrap()
    }

    /// RMS of the stress minus eq 4.37's over the times where eq 4.37 is on the pulse's
    /// plateau (within 0.1% of the amplitude), per unit amplitude: the noise behind the front.
    fn plateau_noise(p: &ProbeHistory) -> f64 {
        let w: Vec<f64> = p
            .stress
            .iter()
            .zip(&p.exact_stress)
            .filter(|(_, e)| (e.abs() / AMPLITUDE - 1.0).abs() < 1e-3)
            .map(|(s, e)| (s - e) / AMPLITUDE)
            .collect();
        (w.iter().map(|d| d * d).sum::<f64>() / w.len() as f64).sqrt()
    }

    /// The median of the stress where eq 4.37 is on the plateau.
    fn plateau(p: &ProbeHistory, t: &[f64], from: f64) -> f64 {
        let mut w: Vec<f64> = p
            .stress
            .iter()
            .zip(&p.exact_stress)
            .zip(t)
            .filter(|((_, e), ti)| **ti >= from && (e.abs() / AMPLITUDE - 1.0).abs() < 1e-3)
            .map(|((s, _), _)| *s)
            .collect();
        super::median(std::mem::take(&mut w))
    }

    /// First time after `from` that `q` crosses `level` (linear between records).
    fn crossing(q: &[f64], t: &[f64], level: f64, from: f64) -> f64 {
        let below = level < 0.0;
        let past = |v: f64| if below { v <= level } else { v >= level };
        let j = (1..t.len())
            .find(|&j| t[j] >= from && past(q[j]))
            .expect("the level is crossed");
        t[j - 1] + (t[j] - t[j - 1]) * (level - q[j - 1]) / (q[j] - q[j - 1])
    }

    /// Largest |stress − load| at the loaded end, per unit amplitude.
    fn end_deviation(p: &ProbeHistory) -> f64 {
        p.stress
            .iter()
            .zip(&p.exact_stress)
            .map(|(s, e)| (s - e).abs() / AMPLITUDE)
            .fold(0.0, f64::max)
    }

    pub fn wave_rows() -> Vec<Row> {
        let t_end = 2.5e-5;
        let [large, inter, none] = [3e-6, 1e-6, 0.0].map(|h| run(&bar(h, t_end)));
        let how = "`sphstab simulate analysis/scenes/thesis-traction-pulse.json --json` (probes: `probes[k].stress`, eq 4.37: `exact_stress`); `sphstab figures` → figures/thesis_figs4_7_4_9_probes.svg";
        let c = 5000.0;
        let t0 = 1e-6; // the intermediate pulse's start (ζ h_t, the mollifier's ζ = 1)
        // Fig 4.6: the plateau and the fronts at 0.05 and 0.1 m
        let p = &inter.probes;
        let plat = [
            plateau(&p[1], &inter.probe_t, 0.0),
            plateau(&p[2], &inter.probe_t, 0.0),
        ];
        let fronts: Vec<f64> = [1, 2]
            .iter()
            .map(|&k| crossing(&p[k].stress, &inter.probe_t, -0.5 * AMPLITUDE, 0.0))
            .collect();
        let exact_fronts: Vec<f64> = [1, 2]
            .iter()
            .map(|&k| crossing(&p[k].exact_stress, &inter.probe_t, -0.5 * AMPLITUDE, 0.0))
            .collect();
        let speed = 0.05 / (fronts[1] - fronts[0]);
        let held = p[3].displacement.iter().all(|&u| u == 0.0);
        let ok46 = plat.iter().all(|s| (s / -AMPLITUDE - 1.0).abs() < 5e-3)
            && (speed / c - 1.0).abs() < 0.01
            && held;
        let noise = [&large, &inter, &none].map(|r| plateau_noise(&r.probes[1]));
        let over = [&large, &inter, &none]
            .map(|r| r.probes[1].stress.iter().copied().fold(0.0, f64::min) / -AMPLITUDE - 1.0);
        let end = [&large, &inter, &none].map(|r| end_deviation(&r.probes[0]));
        let pct = |v: &[f64]| {
            v.iter()
                .map(|x| format!("{:.2}%", 100.0 * x))
                .collect::<Vec<_>>()
                .join(", ")
        };
        vec![
            Row {
                item: "Thesis Fig 4.6 (T-paper Fig 3)",
                shows: "validation bar: ρ = 8000, E = 200 GPa, 0.15 m, −100 kPa boundary pulse, the right end fixed, probes at 0, 0.05, 0.1, 0.15 m (pulse length and shape not given: 10 μs, smoothed over 1 μs; 1001 particles, mollifier h = 5.5Δx, TL with MLS shapes, the fixed end 6 particle layers: sphstab's choice)",
                how,
                paper: "a compressive pulse T̄11 = −100 kPa at the left end, the right end rigidly fixed, \"30 μs for a wave to travel from one side of the bar to the other\" (c = 5000 m/s, §4.6.3.1)".into(),
                ours: format!(
                    "plateau at 0.05, 0.1 m: {:.2}, {:.2} kPa (eq 4.37: −100); half-amplitude fronts at {:.3}, {:.3} μs (eq 4.37: {:.3}, {:.3}), speed {:.0} m/s, so {:.2} μs across 0.15 m; probe 4 displacement {} at every step",
                    plat[0] / 1e3,
                    plat[1] / 1e3,
                    fronts[0] * 1e6,
                    fronts[1] * 1e6,
                    exact_fronts[0] * 1e6,
                    exact_fronts[1] * 1e6,
                    speed,
                    0.15 / speed * 1e6,
                    if held { "0" } else { "not 0" }
                ),
                agree: verdict(
                    ok46,
                    &format!("read as: plateaus within 0.5% of −100 kPa, the speed within 1% of c = √(E/ρ); the pulse starts at t0 = {} μs", t0 * 1e6),
                ),
            },
            Row {
                item: "Thesis Fig 4.7",
                shows: "probe histories, large pulse smoothing (h_t = 3 μs, sphstab's choice)",
                how,
                paper: "clean propagation; \"no difference between the intended load and that calculated at point 1\": the Neumann condition is applied exactly (§4.6.3.2)".into(),
                ours: format!(
                    "point 1 within {:.2}% of the load at every step; behind the front at 0.05 m: RMS noise {:.3}%, overshoot {:.2}%",
                    100.0 * end[0],
                    100.0 * noise[0],
                    100.0 * over[0]
                ),
                agree: verdict(
                    end[0] < 0.02 && noise[0] < 0.005,
                    "read as: point 1 within 2% of the load (a line width at the figure's scale) and noise below 0.5%; sphstab's traction is the form's boundary integral, not the thesis's corrective treatment (§2.8.3)",
                ),
            },
            Row {
                item: "Thesis Fig 4.8",
                shows: "probe histories, intermediate smoothing (h_t = 1 μs, sphstab's choice)",
                how,
                paper: "\"far less smoothed than Figure 4.7, approximating a square wave well. A small amount of numerical noise is present\" (§4.6.3.2)".into(),
                ours: format!(
                    "RMS noise behind the front at 0.05 m (large, intermediate, none): {}; overshoot {}",
                    pct(&noise),
                    pct(&over)
                ),
                agree: verdict(
                    noise[0] < noise[1] && 2.0 * noise[1] < noise[2],
                    "read as: more noise than with the large smoothing, less than half that without",
                ),
            },
            Row {
                item: "Thesis Fig 4.9",
                shows: "probe histories, no smoothing (square pulse)",
                how,
                paper: "\"significant numerical noise\", greater than with finite elements, from the gradient error on square waves (§4.6.3.2); the dispersion behind it: ω² peaks at κΔx = 0.261π (E11), beyond it the group velocity is negative (figures/thesis_fig4_9_dispersion.svg)".into(),
                ours: format!(
                    "RMS noise behind the front at 0.05 m {:.2}% (×{:.1} the intermediate pulse's), overshoot {:.1}%; point 1 departs from the load by up to {:.0}% of it: the square pulse excites a slow oscillation of the loaded end's particles (a near-zero-energy mode of the nodal integration at a free end)",
                    100.0 * noise[2],
                    noise[2] / noise[1],
                    100.0 * over[2],
                    100.0 * end[2]
                ),
                agree: verdict(
                    noise[2] > 0.05,
                    "read as: noise above 5% of the amplitude; the FE comparison is not made (no FE run)",
                ),
            },
        ]
    }

    pub fn reflection_rows() -> Vec<Row> {
        let how =
            "`sphstab simulate analysis/scenes/thesis-traction-pulse.json --t-end 5e-5 --json`";
        let r = run(&bar(1e-6, 5e-5));
        let p = &r.probes;
        let held = p[3].displacement.iter().all(|&u| u == 0.0);
        // the reflected pulse at 0.1 m: after the incident one has passed (35 μs)
        let back = plateau(&p[2], &r.probe_t, 3.5e-5);
        let noise_back: f64 = {
            let w: Vec<f64> = p[2]
                .stress
                .iter()
                .zip(&p[2].exact_stress)
                .zip(&r.probe_t)
                .filter(|((_, e), t)| **t >= 3.5e-5 && (e.abs() / AMPLITUDE - 1.0).abs() < 1e-3)
                .map(|((s, e), _)| (s - e) / AMPLITUDE)
                .collect();
            (w.iter().map(|d| d * d).sum::<f64>() / w.len() as f64).sqrt()
        };
        let ok = held && (back / -AMPLITUDE - 1.0).abs() < 0.02;
        // three materials (§4.6.3.5): fronts at 0.05 m, and set 3's tensile wave there
        let sets = [(8000.0, 200e9), (8000.0, 100e9), (4000.0, 200e9)];
        let runs: Vec<(f64, SceneReport)> = sets
            .iter()
            .map(|&(rho, e)| {
                let mut s = bar(1e-6, 5.5e-5);
                s.rho0 = rho;
                s.modulus = e;
                ((e / rho).sqrt(), run(&s))
            })
            .collect();
        let t0 = 1e-6;
        let arrive: Vec<f64> = runs
            .iter()
            .map(|(_, r)| crossing(&r.probes[1].stress, &r.probe_t, -0.5 * AMPLITUDE, 0.0))
            .collect();
        let expect: Vec<f64> = runs.iter().map(|(c, _)| t0 + 0.05 / c).collect();
        let (c3, r3) = &runs[2];
        let tensile = crossing(&r3.probes[1].stress, &r3.probe_t, 0.5 * AMPLITUDE, 3e-5);
        let tensile_expect = t0 + 0.35 / c3;
        let ok14 = arrive
            .iter()
            .zip(&expect)
            .all(|(a, e)| (a / e - 1.0).abs() < 0.02)
            && (tensile / tensile_expect - 1.0).abs() < 0.01;
        vec![
            Row {
                item: "Thesis Fig 4.13",
                shows: "reflection from the fixed end, longer run (50 μs; intermediate pulse)",
                how,
                paper: "the displacement at point 4 \"held fixed exactly\"; total reflection (eq 4.43), with \"minor error accumulation\" where the reflected oscillations meet the incident wave (§4.6.3.4)".into(),
                ours: format!(
                    "point 4 displacement {} at every step; the reflected pulse at 0.1 m: plateau (median) {:.2} kPa (compression kept, eq 4.43: −100), RMS noise {:.1}% of the amplitude (the incident pulse's: {:.1}%)",
                    if held { "0" } else { "not 0" },
                    back / 1e3,
                    100.0 * noise_back,
                    100.0 * plateau_noise(&r.probes[1])
                ),
                agree: verdict(
                    ok,
                    "read as: point 4 fixed exactly and the reflected plateau within 2% of −100 kPa; the fixed end is 6 particle layers (the kernel's support): with 1 layer the reflected plateau is 28% low",
                ),
            },
            Row {
                item: "Thesis Fig 4.14",
                shows: "probe histories for three materials (ρ, E) = (8000, 200 GPa), (8000, 100 GPa), (4000, 200 GPa); the reflected tensile wave at point 2 \"after 50 μs\"",
                how: "`sphstab simulate analysis/scenes/thesis-traction-pulse.json --t-end 5.5e-5 --json` with `rho0`, `modulus` edited",
                paper: "the wave speed follows ρ and E; in the third set the tensile wave reflected off the free end \"is visible at stress point two after 50 μs\" (§4.6.3.5)".into(),
                ours: format!(
                    "half-amplitude fronts at 0.05 m: {} μs (t0 + 0.05/c_b: {} μs); set 3's tensile wave (fixed end, then the free left end) passes +50 kPa at 0.05 m at {:.2} μs (t0 + 0.35/c_b = {:.2} μs, c_b = {:.0} m/s)",
                    list(&arrive.iter().map(|t| t * 1e6).collect::<Vec<_>>(), 3),
                    list(&expect.iter().map(|t| t * 1e6).collect::<Vec<_>>(), 3),
                    tensile * 1e6,
                    tensile_expect * 1e6,
                    c3
                ),
                agree: verdict(
                    ok14,
                    "read as: fronts within 2%, the tensile arrival within 1%; the 1D bar runs at c_b = √(E/ρ) (the thesis's printed speeds are c_L: row §4.6.3.5)",
                ),
            },
        ]
    }

    pub fn neo_hookean_rows() -> Vec<Row> {
        // Fig 5.3/5.4: the validation bar with the neo-Hookean material (ν = 0.3) against the
        // linear bar of modulus λ + 2μ (its small-strain tangent)
        let nu = 0.3;
        let e = 200e9;
        let (lam, mu) = (
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            e / (2.0 * (1.0 + nu)),
        );
        let c_l = ((lam + 2.0 * mu) / 8000.0_f64).sqrt();
        let mut nh = bar(1e-6, 2.5e-5);
        nh.material = sphstab::solver::scene::SceneMaterial::NeoHookean { poisson: nu };
        let mut lin = bar(1e-6, 2.5e-5);
        lin.modulus = lam + 2.0 * mu;
        let (rn, rl) = (run(&nh), run(&lin));
        let fronts: Vec<f64> = [1, 2]
            .iter()
            .map(|&k| crossing(&rn.probes[k].stress, &rn.probe_t, -0.5 * AMPLITUDE, 0.0))
            .collect();
        let speed = 0.05 / (fronts[1] - fronts[0]);
        let diff = rn.probes[1..3]
            .iter()
            .zip(&rl.probes[1..3])
            .flat_map(|(a, b)| a.stress.iter().zip(&b.stress).map(|(x, y)| (x - y).abs()))
            .fold(0.0, f64::max)
            / AMPLITUDE;
        // Fig 5.5/5.6: the stretch
        let stretch = scene("thesis-neo-hookean-stretch.json");
        let rs = run(&stretch);
        let eq55 = |l: f64, lam_over_mu: f64| (l * l - 1.0) / l + lam_over_mu * l.ln() / l;
        let centre = &rs.probes[0];
        let nominal: Vec<f64> = rs.probes[1]
            .displacement
            .iter()
            .map(|u| 1.0 + u / 0.015)
            .collect();
        let lc = *centre.stretch.last().unwrap();
        let tc = centre.stress.last().unwrap() / mu;
        // the centre's stress about eq 5.5 at the applied (nominal) stretch, during the ramp
        let osc = centre
            .stress
            .iter()
            .zip(&nominal)
            .filter(|(_, n)| **n > 1.1)
            .map(|(s, &n)| (s / mu - eq55(n, 1.5)).abs() / eq55(n, 1.5))
            .fold(0.0, f64::max);
        let ok55 = (tc / 6.2813 - 1.0).abs() < 5e-3 && (lc - 6.0).abs() < 0.03;
        // the same stretch at the thesis's cover, h = 5.5Δx: the smallest final spacing of
        // neighbouring particles over Δx (< 0: particles have passed each other), MLS and sph
        let min_gap = |shape: &str| {
            let mut s = stretch.clone();
            s.h_over_dx = 5.5;
            s.shape = Some(shape.into());
            let mut r = run(&s);
            let Some(FinalState::One(z)) = r.final_state.take() else {
                panic!("a 1D final state")
            };
            let dx = s.length / (s.particles - 1) as f64;
            z.x.windows(2)
                .map(|w| (w[1][0] - w[0][0]) / dx)
                .fold(f64::INFINITY, f64::min)
        };
        let gaps = [min_gap("mls"), min_gap("sph")];
        // ν = 0.49: the same 30 transit times at its c_L; the onset is where the centre's
        // stretch leaves the applied one by 10%
        let nu49 = 0.49;
        let lm49 = 2.0 * nu49 / (1.0 - 2.0 * nu49);
        let mut s49 = stretch.clone();
        s49.material = sphstab::solver::scene::SceneMaterial::NeoHookean { poisson: nu49 };
        let c49 = (e * (1.0 - nu49) / ((1.0 + nu49) * (1.0 - 2.0 * nu49)) / 8000.0).sqrt();
        let (transit, right) = (0.015 / c49, s49.right.as_mut().unwrap());
        let pulse = right.velocity_pulse.as_mut().unwrap();
        pulse.duration = 30.0 * transit;
        pulse.smoothing = 2.0 * transit;
        pulse.amplitude = 0.075 / pulse.duration;
        s49.t_end = 34.0 * transit;
        let onset_at = |dt: f64| {
            let mut s = s49.clone();
            s.dt = dt;
            let r = run(&s);
            let nominal: Vec<f64> = r.probes[1]
                .displacement
                .iter()
                .map(|u| 1.0 + u / 0.015)
                .collect();
            r.probes[0]
                .stretch
                .iter()
                .zip(&nominal)
                .find(|(l, n)| (**l / **n - 1.0).abs() > 0.1)
                .map(|(_, n)| *n)
        };
        let (onset, onset_half) = (onset_at(0.5), onset_at(0.25));
        let a = |f: f64| (1.0 + 1.0 / (f * f)) + lm49 * (1.0 - f.ln()) / (f * f);
        let f0 = super::bisect(a, 2.0, 5.0);
        let how_stretch = "`sphstab simulate analysis/scenes/thesis-neo-hookean-stretch.json --json` (probe 0: the centre's `stretch` and `stress`; probe 1: the pulled end); `sphstab figures` → figures/thesis_fig5_5_stretch.svg";
        vec![
            Row {
                item: "Thesis Fig 5.3 (T-paper Fig 3)",
                shows: "neo-Hookean validation bar set-up (ρ = 8000, E = 200 GPa, ν = 0.3; the bar, pulse and probes of Fig 4.6)",
                how: "`sphstab simulate analysis/scenes/thesis-traction-pulse.json` with `\"material\": {\"kind\": \"neo-hookean\", \"poisson\": 0.3}`",
                paper: "\"If linear, c_L = 5801 m/s\" (§5.3.1)".into(),
                ours: format!(
                    "front speed between 0.05 and 0.1 m: {speed:.0} m/s (c_L = √((λ + 2μ)/ρ) = {c_l:.1} m/s)"
                ),
                agree: verdict(
                    (speed / c_l - 1.0).abs() < 0.01,
                    "read as: within 1% of c_L",
                ),
            },
            Row {
                item: "Thesis Fig 5.4",
                shows: "neo-Hookean bar, compressive pulse (−100 kPa, intermediate smoothing)",
                how: "as Fig 5.3, and the same bar with the linear law of modulus λ + 2μ",
                paper: "behaviour \"very similar\" to the linear case, Neo-Hooke reducing to Hooke at small strain (§5.3.1)".into(),
                ours: format!(
                    "largest difference of the stress histories at 0.05 and 0.1 m, neo-Hookean against linear: {:.2e} of the amplitude (strain ~3.7e-7)",
                    diff
                ),
                agree: verdict(diff < 1e-3, "read as: below 0.1% of the amplitude"),
            },
            Row {
                item: "Thesis Fig 5.5 (T-paper Fig 5)",
                shows: "15 mm bar stretched to 90 mm over 30 transit times, T11 vs λ1 at the centre (ν = 0.3; 151 particles, mollifier h = 2.5Δx, MLS, the end's velocity ramped up and down over 2 transit times: sphstab's choice)",
                how: how_stretch,
                paper: "follows the analytic curve (eq 5.5) with oscillations about it from the transient loading (§5.3.2)".into(),
                ours: format!(
                    "at the end the centre is at λ1 = {lc:.3}, T11/μ = {tc:.4} (eq 5.5 at λ1 = 6: 6.2813, the digest's value); during the ramp the centre's T11 stays within {:.1}% of eq 5.5 at the applied stretch; at h = 5.5Δx the smallest final spacing of neighbours is {:.1}Δx (MLS), {:.1}Δx (sph) for a mean of 6Δx",
                    100.0 * osc,
                    gaps[0],
                    gaps[1]
                ),
                agree: verdict(
                    ok55,
                    &format!(
                        "read as: ends within 0.5% of eq 5.5 at λ1 = 6 (at h = 2.5Δx); at h = 5.5Δx the zigzag (zero-energy) mode of the nodal integration grows until {}",
                        if gaps.iter().all(|&g| g < 0.0) {
                            "particles pass each other, with MLS and sph shapes alike"
                        } else {
                            "the spacing is far from uniform"
                        }
                    ),
                ),
            },
            Row {
                item: "Thesis Fig 5.6",
                shows: "large stretch of a nearly incompressible (ν = 0.49) neo-Hookean bar, T11 vs λ1 against eq 5.5 (the Fig 5.5 scene, 30 transit times at ν = 0.49's c_L)",
                how: "as Fig 5.5 with `\"material\": {\"kind\": \"neo-hookean\", \"poisson\": 0.49}` and the ramp scaled to its c_L",
                paper: "matches the exact curve, \"becomes unstable after a stretch of 3.6\", attributed to the time integration (§5.3.2)".into(),
                ours: format!(
                    "the centre's stretch leaves the applied one (by 10%) at applied λ1 = {} with Δt = 0.5Δx/c, {} with 0.25Δx/c; derived: A(F) = μ(1 + 1/F²) + λ(1 − ln F)/F² < 0 from F = {f0:.4} (λ/μ = {lm49:.0})",
                    onset.map_or("— (never)".to_string(), |n| format!("{n:.2}")),
                    onset_half.map_or("— (never)".to_string(), |n| format!("{n:.2}"))
                ),
                agree: erratum(
                    [onset, onset_half]
                        .iter()
                        .all(|o| o.is_some_and(|n| n > f0 && n < 5.0)),
                    "E14",
                    "the instability follows the loss of hyperbolicity at F = 3.63 (material), at the same stretch with half the time step: not the time integration",
                ),
            },
        ]
    }
}

/// Items not reproduced: (item, what it shows, verdict — "not reproducible" or "needs code" —
/// and the reason).
const NOT_REPRODUCED: &[(&str, &str, &str)] = &[
    (
        "B00 Fig 21",
        "fluid–structure set-up: shell R = 10.48 cm, 25 beam elements, 3715 fluid particles, 162 and 369 cm/s",
        "not reproducible: fluid–structure interaction, beams and contact are outside sphstab's scope",
    ),
    (
        "B00 Fig 22",
        "circumferential strains of the shell at six angles, 162 cm/s, vs experiment",
        "not reproducible: as Fig 21 (and an experiment)",
    ),
    (
        "B00 Fig 23",
        "shell shape and free surface, 162 cm/s",
        "not reproducible: as Fig 21",
    ),
    (
        "B00 Fig 24",
        "circumferential strains, 369 cm/s (computed drop at 4 ms, experiment ~6 ms)",
        "not reproducible: as Fig 21",
    ),
    (
        "B00 Fig 25",
        "shell shape and free surface, 369 cm/s",
        "not reproducible: as Fig 21",
    ),
    (
        "B00 Fig 26",
        "fluid particle velocities, 162 cm/s, t = 10 and 15 ms",
        "not reproducible: as Fig 21",
    ),
    (
        "B00 Fig 27",
        "fluid particle velocities, 369 cm/s, t = 10 and 15 ms",
        "not reproducible: as Fig 21",
    ),
    (
        "B00 Plate 2",
        "crack propagation, Lemaitre damage, plate 0.1 × 0.04 m, t = 15–60 μs",
        "needs code: a 2D scene with edge tractions (σ = 1 MPa) and the Lemaitre damage law (eqs 150–152; ρ, E, ν, ε_D0, A_t, B_t given, §6.3), EFG with a Lagrangian kernel; node count and D_mx not given (sphstab's choice)",
    ),
    (
        "B00 Plate 3",
        "damage zone in a disk with a hole, t = 1 ms",
        "not reproducible: the \"initial radial velocity … prescribed along the hole\" has no value (§6.3); otherwise as Plate 2",
    ),
    (
        "B00 Table III",
        "material parameters of the fluid–structure problem (steel shell, water B = 2.0e10 dyn/cm², γ = 7)",
        "not reproducible: parameters of Figs 21–27 (as Fig 21); no result to compare",
    ),
    (
        "V21 Fig 13 (c-calculated)",
        "the cll curve with c from eq 49",
        "needs code: a per-particle c from eq 49, the ratio of each particle's nonlocal to its local and nonlocal strains (the hydrodynamic Swegle test integrates no strain to take it from; sphstab's cll has one constant c); the constant-c curves are row V21 Fig 13",
    ),
    (
        "V21 Fig 23",
        "2D rubber-shell impact set-up (OD 4 cm, ID 3 cm, 50 m/s, 40 particles through the thickness)",
        "needs code: a 2D impact scene of two rings with a contact algorithm (V21's ref. [23], not described in V21) and a 2-particle boundary layer in the classical form (the per-particle form switch of Fig 18(b)); material, speed and 40 particles through the thickness given (§7.6), kernel, h and Δt not (sphstab's choice)",
    ),
    (
        "V21 Fig 24",
        "rubber shells: contact and separation",
        "needs code: as Fig 23",
    ),
    (
        "V21 Fig 25",
        "3D cylinder impact set-up (11,360 particles each, 50 m/s)",
        "needs code: a 3D impact scene of two cylinders with contact and the classical-form boundary layer, as Fig 23 (length 4 cm, diameter 1.9 cm, spacing ≈ 0.1 cm, ρ = 2.8 g/cm³, E = 1.0 GPa, ν = 0.3, 50 m/s: given in §7.6); kernel, h and Δt not given",
    ),
    (
        "V21 Fig 26",
        "cylinder impact, von Mises stress",
        "needs code: as Fig 25; the colour scale's values are lost with the figure, so only \"impact and separation\" can be compared",
    ),
    (
        "V21 Fig 27",
        "single cylinder on a symmetry plane, 100 m/s, E = 100 MPa",
        "needs code: the classical-form boundary layer on a round bar's lateral surface (`classical_layers` covers end columns only, and the lnl form has no free surface without it: the nonlocal Taylor bar diverges); the cylinder on a symmetry plane (`round`, `left.symmetry`) and the material are there; V21 gives no end time (instability began \"shortly after the final time shown\")",
    ),
    (
        "B98 Table II",
        "operation counts per node of the corrected approximations (nC_w + 101n + 32, …)",
        "not reproducible: counts of B98's implementation",
    ),
    (
        "B98 Table IV",
        "speed-up of corrected derivatives over MLS (3.06, 3.12, 2.43)",
        "not reproducible: timings of B98's code on its machine",
    ),
    (
        "B98 Fig 4",
        "a nodal arrangement with one row of finite elements",
        "not reproducible: a mesh picture (node counts per refinement not given)",
    ),
    (
        "B98 Fig 12",
        "end displacement of an elastoplastic cantilever, meshes 25×4, 33×7, 55×10",
        "needs code: an explicit dynamic Galerkin solver with 2 × 2 cell quadrature (EFG, CD1, CD2) and J2 plasticity in 2D (sphstab's J2 acts in its 3D SPH solver; B98 says neither plane stress nor plane strain, and gives no density: the problem is Belytschko and Bindeman's)",
    ),
    (
        "B98 Fig 13",
        "end displacement with nodal quadrature and conservative smoothing",
        "needs code: as Fig 12",
    ),
    (
        "B98 Fig 14",
        "particle positions at t = 10 s, cantilever",
        "needs code: as Fig 12 (nodal quadrature with conservative smoothing, coefficient 0.1, as Fig 13); which of the three meshes is drawn is not stated",
    ),
    (
        "B98 Plate 1",
        "effective strain, viscoplastic strain-softening bar",
        "not reproducible: the material is in B98's ref. [7], not in the paper",
    ),
    (
        "Thesis Fig 2.18",
        "falling edge, low gradient",
        "not reproducible: the statement (\"all of the cover sizes start to behave in a similar manner\", §2.7.2) names no measurable property, and the edge's gradient is not given; the edge rows computed are Figs 2.17, 2.19, 2.20 (`sphstab interpolate --function edge --edge-width W --ghosts`)",
    ),
    (
        "Thesis Fig 5.13",
        "sheet with a hole set-up (E = 70 MPa, ν = 0.49, 21 × 21, 5 MPa)",
        "not reproducible: hole radius and sheet size not given",
    ),
    (
        "Thesis Fig 5.14",
        "stress contours during loading",
        "not reproducible: as Fig 5.13",
    ),
    (
        "Thesis Fig 5.15",
        "final stress at rest (60 MPa at the hole edge)",
        "not reproducible: as Fig 5.13 (and the damping is not given)",
    ),
];

/// Items without numeric content, left out (one line per paper).
const SCHEMATICS: &[(&str, &str)] = &[
    (
        "B00",
        "Figs 1 (Voronoi stress points), 2 (domain of influence under x = X + 2Y), 8 (1D stress points), 12 (2D stress-point patterns: they define `--quadrature stress-*` of rows B00 Figs 13–15)",
    ),
    (
        "V21",
        "Figs 1–6 (imbricate continuum, neighbours, kernel domains, interaction area, integration domains, nonlocal interaction)",
    ),
    (
        "B98",
        "Figs 1, 2 (FE row at an essential boundary; nodal integration at boundary nodes); Table I (momentum equations and velocity gradients: formulas only)",
    ),
    (
        "Thesis",
        "Figs 1.1, 2.1, 2.2, 2.9, 2.21–2.26 (T-paper Fig 2), 3.1–3.3, 4.1–4.5 (concept and notation sketches); Tables 3.1, 4.1, 4.2 (notation and formulas only)",
    ),
];

fn render(rows: &[Row]) -> String {
    let mut s = String::new();
    s.push_str(
        "# Reproduction of the seeds' tables and figures\n\n\
         Generated by `tests/it/reproduction.rs` (`cargo test --release --test it -- reproduction::`): every \
         number in the sphstab column is computed by that test, which fails when this file no \
         longer matches the code (`SPHSTAB_WRITE_REPRODUCTION=1` rewrites it). Paper values are \
         transcribed from the seeds (`../shared/seeds/`: B00 = Belytschko, Guo, Liu, Xiao 2000; \
         V21 = Vignjevic, De Vuyst, Campbell 2021; B98 = Belytschko, Krongauz, Dolbow, Gerlach \
         1998; Thesis = 004, with the appended conference paper \"T-paper\"); errata E1–E17 and \
         notes N1, N2 are in `analysis/ERRATA.md`. Units: ω²Δx²/c², κΔx, growth rates in c/Δx, Δt in \
         Δx/c, unless a row says otherwise. A row marked *derived* computes its number in the \
         test from the paper's own formulas, not through sphstab's solver or engine.\n\n\
         Every numbered table and every figure with numeric content of the four seeds has a row: \
         the computed rows first, then the items not reproduced (with why), then the items \
         without numeric content. Where a paper gives only a curve (all figures are lost from \
         the seed text), the row compares what the text and caption state and says how that \
         statement was turned into a criterion.\n\n",
    );
    s.push_str("| item | what it shows | how to regenerate | paper | sphstab | agreement |\n");
    s.push_str("|---|---|---|---|---|---|\n");
    let cell = |t: &str| t.replace('|', "\\|");
    for r in rows {
        writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} |",
            cell(r.item),
            cell(r.shows),
            cell(r.how),
            cell(&r.paper),
            cell(&r.ours),
            cell(&r.agree)
        )
        .unwrap();
    }
    s.push_str(
        "\n## Not reproduced\n\n\
         *not reproducible*: needs physics or geometry outside sphstab's scope, parameters the \
         paper does not give, or another machine's timing; *needs code*: what is missing.\n\n\
         | item | what it shows | verdict and reason |\n|---|---|---|\n",
    );
    for (item, shows, why) in NOT_REPRODUCED {
        writeln!(s, "| {} | {} | {} |", cell(item), cell(shows), cell(why)).unwrap();
    }
    s.push_str("\n## Left out: no numeric content\n\n");
    for (paper, what) in SCHEMATICS {
        writeln!(s, "- {paper}: {what}.").unwrap();
    }
    let verdicts: Vec<&str> = rows
        .iter()
        .map(|r| r.agree.as_str())
        .chain(NOT_REPRODUCED.iter().map(|n| n.2))
        .collect();
    let count = |w: &str| verdicts.iter().filter(|v| v.starts_with(w)).count();
    let kinds = [
        "✔",
        "erratum",
        "partly",
        "✘",
        "not reproducible",
        "needs code",
    ];
    assert_eq!(
        kinds.iter().map(|w| count(w)).sum::<usize>(),
        verdicts.len(),
        "every verdict starts with one of {kinds:?}"
    );
    writeln!(
        s,
        "\n## Tally\n\n{} rows ({} computed, {} not reproduced): {} ✔, {} erratum (the paper's \
         value or statement differs and `analysis/ERRATA.md` explains it), {} partly, {} ✘, {} \
         not reproducible, {} needs code.",
        verdicts.len(),
        rows.len(),
        NOT_REPRODUCED.len(),
        count("✔"),
        count("erratum"),
        count("partly"),
        count("✘"),
        count("not reproducible"),
        count("needs code")
    )
    .unwrap();
    s
}

#[test]
fn reproduction_md_matches_the_code() {
    // the Taylor bar (a 3D run) and the Galerkin studies (single-threaded solves) side by side
    let (taylor, plate) = rayon::join(multi_d::b00_taylor_rows, b98_plate_results);
    // the two slowest rows (time-domain runs, most of this test's time) run next to the others:
    // every row is computed on its own, so the order of computing them changes nothing
    let (([f17, f18, f18b], fig13), rest) = rayon::join(
        || rayon::join(v21_figs17_18, v21_fig13),
        || {
            let [f21, f22] = v21_figs21_22();
            (f21, f22, v21_fig12(), v21_fig11())
        },
    );
    let (f21, f22, fig12, fig11) = rest;
    let [b00_f17, b00_f18] = b00_figs17_18();
    let [t418, t419] = thesis_large_jumps();
    let [t51, t52] = thesis_figs51_52();
    let rows = vec![
        b00_table1(),
        b00_table2(),
        b00_fig3(),
        b00_fig4(),
        b00_fig5(),
        b00_figs6_7(),
        b00_fig9(),
        b00_fig10(),
        b00_fig11(),
        b00_figs13_15(),
        b00_fig16(),
        b00_f17,
        b00_f18,
        b00_fig18_caption(),
        v21_fig7(),
        v21_uniform(false),
        v21_uniform(true),
        fig12,
        fig11,
        fig13,
        f17,
        f18,
        f18b,
        f21,
        f22,
        thesis_kernels(),
        thesis_dt(),
        thesis_speeds(),
        thesis_interface(),
        t418,
        t419,
        thesis_tension(),
        thesis_tensile_range(),
        t51,
        t52,
    ];
    // [T §2.7]: after the kernels' row, in figure order
    let at = rows
        .iter()
        .position(|r| r.item.starts_with("Thesis Figs 2.3"))
        .expect("the kernels' row")
        + 1;
    let mut rows = rows;
    let mut thesis_2 = vec![thesis_fig26()];
    thesis_2.extend(interp::rows());
    rows.splice(at..at, thesis_2);
    // [T §4.6.3]: before the time-step row; [T §5.3]: after Figs 5.1, 5.2
    let at = rows
        .iter()
        .position(|r| r.item.starts_with("Thesis Figs 4.10"))
        .expect("the time-step row");
    let mut wave = probes::wave_rows();
    wave.extend(probes::reflection_rows());
    let (early, late): (Vec<Row>, Vec<Row>) = wave.into_iter().partition(|r| {
        r.item.starts_with("Thesis Fig 4.6")
            || r.item.starts_with("Thesis Fig 4.7")
            || r.item.starts_with("Thesis Fig 4.8")
            || r.item.starts_with("Thesis Fig 4.9")
    });
    rows.splice(at..at, early);
    let at = rows
        .iter()
        .position(|r| r.item.starts_with("Thesis Figs 4.15"))
        .expect("the interface row");
    rows.splice(at..at, late);
    let at = rows
        .iter()
        .position(|r| r.item == "Thesis Fig 5.2")
        .expect("the Fig 5.2 row")
        + 1;
    let mut thesis_5 = probes::neo_hookean_rows();
    thesis_5.extend(multi_d::thesis_pulse_rows());
    thesis_5.extend(multi_d::thesis_stretch_rows());
    rows.splice(at..at, thesis_5);
    // [V21 §7.1, §7.5] in 3D: after the 1D rows of each
    let at = rows
        .iter()
        .position(|r| r.item == "V21 Figs 9, 16 (1D)")
        .expect("the uniform-tension row")
        + 1;
    rows.splice(at..at, multi_d::v21_uniform_rows());
    let at = rows
        .iter()
        .position(|r| r.item == "V21 Figs 19, 20, 21(a) (1D)")
        .expect("the tensile-wave row")
        + 1;
    rows.splice(at..at, multi_d::v21_tensile_rows());
    rows.extend(taylor);
    rows.extend(b98_beam(&plate));
    rows.extend(b98_plate(&plate));
    // a ✘ without an erratum fails here, before the file is compared (or rewritten)
    let verdicts: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r.item, r.agree.as_str()))
        .chain(NOT_REPRODUCED.iter().map(|n| (n.0, n.2)))
        .collect();
    let unexplained = unexplained_failures(&verdicts, &errata_ids());
    assert!(
        unexplained.is_empty(),
        "rows marked ✘ without an erratum (cite it as `erratum Ek` of analysis/ERRATA.md, or fix \
         the code): {unexplained:#?}"
    );
    let text = render(&rows);
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("REPRODUCTION.md");
    if std::env::var_os("SPHSTAB_WRITE_REPRODUCTION").is_some() {
        std::fs::write(&path, &text).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == text,
        "REPRODUCTION.md differs from what the code computes; if the change is deliberate, \
         rewrite it with SPHSTAB_WRITE_REPRODUCTION=1 cargo test --release --test it -- reproduction::\n\
         --- computed ---\n{text}"
    );
}

/// The ✘ check of [`reproduction_md_matches_the_code`] on synthetic rows: a ✘ without an
/// erratum, with an erratum the helper `erratum` expected but that does not explain the row,
/// or citing an id ERRATA.md does not define, is reported; a ✘ citing a defined erratum, and
/// every other verdict, is not.
#[test]
fn a_cross_without_an_erratum_is_reported() {
    let errata = errata_ids();
    assert!(
        errata.len() >= 17
            && ["E1", "E4", "E17"]
                .iter()
                .all(|e| errata.contains(&e.to_string())),
        "{errata:?}"
    );
    let bare = verdict(false, "");
    let noted = verdict(false, "growth 2× the paper's");
    let expected = erratum(false, "E4", "the other three values differ");
    let undefined = verdict(false, "erratum E99: no such entry");
    let explained = verdict(false, "erratum E4: the paper's value is misprinted");
    let explained_late = verdict(false, "2× the paper's; erratum E17");
    let ok = verdict(true, "");
    let recorded = erratum(true, "E4", "3 of 4 equal");
    let rows = [
        ("bare", bare.as_str()),
        ("noted", noted.as_str()),
        ("expected", expected.as_str()),
        ("undefined", undefined.as_str()),
        ("explained", explained.as_str()),
        ("explained late", explained_late.as_str()),
        ("ok", ok.as_str()),
        ("recorded", recorded.as_str()),
        ("partly", "partly (✘ for one of two statements)"),
        ("needs code", "needs code: a solver"),
    ];
    let names: Vec<&str> = unexplained_failures(&rows, &errata)
        .iter()
        .map(|r| r.0)
        .collect();
    assert_eq!(names, ["bare", "noted", "expected", "undefined"]);
    // the whole id counts: E12 is not E1
    let only_e1 = ["E1".to_string()];
    let e12 = verdict(false, "erratum E12: …");
    let e1 = verdict(false, "erratum E1: …");
    let cited = [("E12", e12.as_str()), ("E1", e1.as_str())];
    assert_eq!(
        unexplained_failures(&cited, &only_e1),
        [("E12", e12.as_str())]
    );
    assert_eq!(
        unexplained_failures(&[("bare", bare.as_str())], &[]).len(),
        1,
        "with no errata every ✘ is unexplained"
    );
}

/// Every figure REPRODUCTION.md cites is the output of a config in analysis/configs, so
/// `sphstab figures` regenerates it (tests/it/figures.rs checks that the committed file is exactly
/// what its config draws).
#[test]
fn every_cited_figure_is_regenerated_by_sphstab_figures() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let md = std::fs::read_to_string(root.join("REPRODUCTION.md")).unwrap();
    let mut outputs = Vec::new();
    for e in std::fs::read_dir(root.join("analysis/configs")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "json") {
            let cfg = sphstab::figures::parse(
                &p.display().to_string(),
                &std::fs::read_to_string(&p).unwrap(),
            )
            .unwrap();
            outputs.push(cfg.output);
        }
    }
    let mut cited = 0;
    for word in md.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '.')) {
        if let Some(stem) = word.strip_suffix(".svg") {
            if stem.is_empty() {
                continue;
            }
            let name = format!("{stem}.svg");
            assert!(
                outputs.contains(&name),
                "REPRODUCTION.md cites {name}, which no config in analysis/configs draws"
            );
            assert!(
                root.join("figures").join(&name).exists(),
                "figures/{name} missing"
            );
            cited += 1;
        }
    }
    // B00 Figs 3 (three files), 4, 9, 10, 11, 13, 14, 15, V21 Fig 7, thesis Fig 4.9
    assert!(cited >= 12, "only {cited} figures cited");
}
