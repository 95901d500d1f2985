//! `sphstab stiffness`: anti-plane Galerkin stiffness K_jk [B00 §4.4, Table I] and, with
//! `--theta`, the normalised frequency ωΔx/c along that direction.

use anyhow::Result;
use sphstab::lattice::Lattice;
use sphstab::shape::KernelParams;
use sphstab::shape::ShapeFamily;
use sphstab::vonneumann::antiplane::{AntiPlane, Mass, Quadrature};

/// Flags of `stiffness`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Weight/kernel (Table I: efg-cubic).
    #[arg(long, default_value = "efg-cubic")]
    kernel: String,
    /// Support radius R/Δx (Belytschko's D_mx), in (1, 50]: it must reach the nearest
    /// neighbours.
    #[arg(long, default_value_t = 2.0, allow_hyphen_values = true)]
    support: f64,
    /// Shape family (Table I: mls).
    #[arg(long, default_value = "mls")]
    shape: String,
    /// nodal, cell-1, cell-2x2, stress-quad, stress-tri, stress-star, stress-hex.
    #[arg(long, default_value = "nodal")]
    quadrature: String,
    /// square or hex (stress-hex needs hex).
    #[arg(long, default_value = "square")]
    lattice: String,
    /// Square-lattice aspect ratio γ = Δy/Δx, in [0.1, 10] (default 1; square lattice only).
    #[arg(long, allow_hyphen_values = true)]
    gamma: Option<f64>,
    /// Also print ω along this direction θ (degrees, in [−360, 360]), in c/Δx (ωΔx/c), for
    /// κΔx ∈ (0, κ_cut].
    #[arg(long, allow_hyphen_values = true)]
    theta: Option<f64>,
    /// Points along θ, in [2, 1000000] (default 32; needs --theta).
    #[arg(long)]
    points: Option<usize>,
    /// Use the consistent mass (default lumped, as Table I / eq 119).
    #[arg(long)]
    consistent: bool,
    /// The largest eigenvalue of a finite body of N nodes per side instead ([B00] §5,
    /// Figs 17–18): a bar of N nodes (--dim 1) or an N × N square (--dim 2), 2 Gauss points
    /// per cell (2 × 2), free boundaries, lumped and consistent mass, against the bounds eq
    /// 137 (1D) or eqs 146, 148 (2D). N in [3, 100000] (1D) or [3, 300] (2D); dense up to 1600
    /// nodes, Lanczos (lumped mass only) beyond.
    #[arg(long)]
    body: Option<usize>,
    /// Dimension of --body: 1 or 2 (default 2).
    #[arg(long)]
    dim: Option<usize>,
    /// JSON output (K_jk entries, κΔx and ωΔx/c; its "units" name them).
    #[arg(long)]
    json: bool,
}

/// `--body N`: the finite body's largest eigenvalue.
fn body(a: &Args, n: usize, budget: &sphstab::budget::Budget) -> Result<()> {
    if a.quadrature != "nodal" && a.quadrature != "cell-2x2" {
        return Err(crate::query::not_in(
            "--quadrature",
            "--body (the finite body has 2 Gauss points per cell, 2 × 2 in 2D, as [B00] Figs 17–18)",
        ));
    }
    if a.theta.is_some()
        || a.points.is_some()
        || a.consistent
        || a.lattice != "square"
        || a.gamma.is_some()
    {
        return Err(crate::query::not_in(
            "--theta/--points/--consistent/--lattice/--gamma",
            "--body (it reports the largest eigenvalue with both masses, on a square body)",
        ));
    }
    let k = sphstab::kernel::by_name(&a.kernel)?;
    let fam = ShapeFamily::by_name(&a.shape)?;
    let dim = a.dim.unwrap_or(2);
    let r = sphstab::studies::finite_body::finite_body(dim, n, k, a.support, fam, budget)?;
    if !(r.lambda_max_lumped.is_finite() && r.lambda_max_consistent.is_none_or(f64::is_finite)) {
        return Err(sphstab::error::Error::NonFinite("the finite body's eigenvalue").into());
    }
    if a.json {
        println!(
            "{}",
            sphstab::units::json(&r, sphstab::units::System::Normalised, true)?
        );
        return Ok(());
    }
    let shape = if dim == 1 {
        format!("bar of {n} nodes")
    } else {
        format!("{n} × {n} square")
    };
    println!(
        "finite body [B00 §5]: {shape}, {} / {}, D_max = {}, 2 Gauss points per cell{}, free boundaries ({})",
        a.shape,
        a.kernel,
        sphstab::display::num(a.support),
        if dim == 2 { " and axis" } else { "" },
        if r.dense {
            "dense eigensolver"
        } else {
            "Lanczos"
        }
    );
    let plain = |x: f64| sphstab::display::num_sig(x, 6);
    let ratios = |v: &[f64]| {
        r.bounds
            .iter()
            .zip(v)
            .map(|(b, x)| format!("{} / λ_max = {}", b.0, plain(*x)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    println!(
        "λ_max (lumped mass) = {} c²/Δx² (critical leapfrog Δt = {} Δx/c); {}",
        plain(r.lambda_max_lumped),
        plain(r.critical_dt_lumped),
        ratios(&r.ratio_lumped)
    );
    match (&r.lambda_max_consistent, &r.ratio_consistent) {
        (Some(c), Some(rc)) => println!(
            "λ_max (consistent mass) = {} c²/Δx²; {}",
            plain(*c),
            ratios(rc)
        ),
        _ => println!("λ_max (consistent mass): not computed beyond 1600 nodes"),
    }
    let b: Vec<String> = r
        .bounds
        .iter()
        .map(|(n, v)| format!("{n}: {} c²/Δx²", plain(*v)))
        .collect();
    println!("bounds: {}", b.join(", "));
    Ok(())
}

pub fn run(a: Args, budget: &sphstab::budget::Budget) -> Result<()> {
    if let Some(n) = a.body {
        return body(&a, n, budget);
    }
    if a.dim.is_some() {
        return Err(crate::query::not_in(
            "--dim",
            "no --body (the anti-plane stiffness is 2D; --dim 1 selects the finite bar of --body)",
        ));
    }
    let k = sphstab::kernel::by_name(&a.kernel)?;
    sphstab::error::check_range("--support", a.support, 0.0, 50.0, false, true)?;
    if a.support <= 1.0 {
        return Err(sphstab::error::Error::OutOfRange {
            field: "support",
            value: a.support,
            range: "must be in (1, 50]: the support R/Δx must exceed 1 so that particles have neighbours (Table I uses 2)".into(),
        }
        .into());
    }
    if a.consistent && a.theta.is_none() {
        return Err(crate::query::not_in(
            "--consistent",
            "no --theta (the mass matrix enters the frequencies along θ, not K_jk or the zero-frequency check)",
        ));
    }
    if a.lattice != "square" && a.gamma.is_some() {
        return Err(crate::query::not_in(
            "--gamma",
            "--lattice hex (the aspect ratio is for the square lattice)",
        ));
    }
    let points = match (a.points, a.theta) {
        (Some(_), None) => {
            return Err(crate::query::not_in(
                "--points",
                "no --theta (it is the number of points along θ)",
            ));
        }
        (p, _) => p.unwrap_or(32),
    };
    sphstab::params::check_count("points", points, 2, 1_000_000)?;
    let lat = Lattice::<2>::by_name(&a.lattice, a.gamma.unwrap_or(1.0))?;
    let q = Quadrature::by_name(&a.quadrature)?;
    let fam = ShapeFamily::by_name(&a.shape)?;
    let ap = AntiPlane::new(
        &lat,
        q,
        fam,
        KernelParams {
            kernel: k,
            h: a.support / k.zeta(),
        },
    )
    .map_err(|e| match e {
        sphstab::error::Error::SingularMoment { what, .. } => {
            sphstab::error::Error::OutOfRange {
                field: "support",
                value: a.support,
                range: format!(
                    "the {what} is singular: the support covers too few neighbours for --shape {}; use a larger --support (Table I uses 2)",
                    a.shape
                )
                .into(),
            }
        }
        e => e,
    })?;
    let mass = if a.consistent {
        Mass::Consistent
    } else {
        Mass::Lumped
    };
    let mut disp = Vec::new();
    if let Some(th) = a.theta {
        sphstab::error::check_range("--theta", th, -360.0, 360.0, true, true)?;
        let t = th.to_radians();
        let (c, s) = (t.cos(), t.sin());
        // cut-off: the first-zone boundary along θ
        let kcut = lat.zone_boundary(t);
        for i in 1..=points {
            let kap = kcut * i as f64 / points as f64;
            let w2 = ap.omega2([kap * c, kap * s], mass)?;
            disp.push((
                kap,
                w2.iter().map(|w| w.max(0.0).sqrt()).collect::<Vec<_>>(),
            ));
        }
    }
    let gamma = if let sphstab::lattice::LatticeKind::Square { gamma } = lat.kind {
        gamma
    } else {
        1.0
    };
    let spurious = if matches!(lat.kind, sphstab::lattice::LatticeKind::Square { .. }) {
        Some(ap.spurious_at_cutoff(gamma)?)
    } else {
        None
    };
    // a result that is not a number is an error, not `null` in the JSON
    let table = if ap.pattern.sites.len() == 1 {
        ap.stiffness_table()?
    } else {
        Vec::new()
    };
    if table.iter().any(|e| !e.2.is_finite())
        || disp.iter().any(|d| d.1.iter().any(|w| !w.is_finite()))
    {
        return Err(sphstab::error::Error::NonFinite("the stiffness K_jk or ωΔx/c").into());
    }
    if a.json {
        let entries = if ap.pattern.sites.len() == 1 {
            table
                .iter()
                .map(|(j, k, v)| serde_json::json!({"j": j, "k": k, "value": v}))
                .collect()
        } else {
            Vec::new()
        };
        let d: Vec<_> = disp
            .iter()
            .map(|(k, w)| serde_json::json!({"kappa_dx": k, "omega_dx_over_c": w}))
            .collect();
        let doc = serde_json::json!({"quadrature": q.name(), "entries": entries, "dispersion": d,
            "spurious_zero_frequency": spurious.map(|(a, b)| serde_json::json!({"theta_0": a, "theta_45": b}))});
        println!(
            "{}",
            sphstab::units::json(&doc, sphstab::units::System::Normalised, true)?
        );
        return Ok(());
    }
    if ap.pattern.sites.len() == 1 {
        let half = if a.lattice == "square" {
            "entries j, k ≥ 0; K is even in j and in k"
        } else {
            "offsets j a1 + k a2 over a half-plane; K(−j, −k) = K(j, k)"
        };
        println!(
            "K_jk = ∫ ∇φ_0·∇φ_jk dΩ (dimensionless: the stiffness per unit thickness is G K_jk) ({}, {} / {}, D_mx = R/Δx = {}, {}; {half}):",
            q.name(),
            a.shape,
            a.kernel,
            sphstab::display::num(a.support),
            a.lattice
        );
        for &(j, kk, v) in &table {
            if v.abs() > 1e-14 {
                println!("{j:>3} {kk:>3} {v:>14.6e}");
            }
        }
    } else {
        println!(
            "{}: {} nodes per periodic cell; no single K_jk table (use --theta)",
            q.name(),
            ap.pattern.sites.len()
        );
    }
    if let Some((s0, s45)) = spurious {
        println!(
            "spurious zero-frequency mode at the cut-off: θ = 0°: {}, θ = 45°: {}",
            if s0 { "yes" } else { "no" },
            if s45 { "yes" } else { "no" }
        );
    }
    for (kap, w) in disp {
        println!(
            "κΔx = {:>8.5}  ωΔx/c = {}",
            kap,
            w.iter()
                .map(|x| format!("{x:.6}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(())
}
