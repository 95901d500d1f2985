//! `sphstab interpolate`: interpolation and gradient accuracy of a kernel approximation on a
//! finite particle set, ghosts or not ([`sphstab::studies::interpolation`]; \[T\] §2.7).

use crate::files::Files;
use anyhow::{Result, bail};
use sphstab::shape::ShapeFamily;
use sphstab::studies::interpolation::{
    ErrorNorms, InterpolationConfig, InterpolationReport, Normalisation, TestFunction, interpolate,
};
use std::fmt::Write;

/// Flags of `interpolate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// quartic ((x − 0.5)⁴, [T] Fig 2.10), sine (sin x), linear (x), edge (a falling edge
    /// from 1 to 0 over --edge-width spacings, centred on the interval) or step (the
    /// discontinuous edge). In 2D the function is summed over both axes, f = g(x) + g(y).
    #[arg(long, default_value = "quartic")]
    function: String,
    /// The interval "A,B" (each a number, optionally times pi: "0,3pi"). Default 0,1, and
    /// 0,3pi for sine.
    #[arg(long, allow_hyphen_values = true)]
    interval: Option<String>,
    /// Particles per axis on the interval, ends included: in [3, 1000000] in 1D, [3, 1000]
    /// in 2D.
    #[arg(long, default_value_t = 101)]
    particles: usize,
    /// Kernel name (default mollifier, the thesis's modified mollifier, whose support radius
    /// is h: --h is then the thesis's cover in particle spacings).
    #[arg(long, default_value = "mollifier")]
    kernel: String,
    /// Smoothing lengths h/Δx in the kernel's own convention, comma-separated (one row each, at
    /// most 64), each in [0.05, 20] with a support ζh > Δx. Default 5.5 ([T] §2.7.3's
    /// compromise).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    h: Vec<f64>,
    /// Shape family: sph (the plain kernel sums of [T] eqs 2.24–2.25), shepard, corrected or
    /// mls.
    #[arg(long, default_value = "sph")]
    shape: String,
    /// Ghost particles beyond both ends, two support radii deep, carrying the function's own
    /// values ([T] §2.7's "ghost particle approach").
    #[arg(long)]
    ghosts: bool,
    /// The kernel's normalisation (sph shapes): continuum (its own constant, ∫W = 1) or
    /// lattice (divided by its sum over the particles of a full cover, so that interior sums
    /// reproduce a constant: [T] §2.2.2's numerical normalisation).
    #[arg(long, default_value = "continuum")]
    normalisation: String,
    /// Dimension: 1, or 2 (an N × N lattice on the interval squared).
    #[arg(long, default_value_t = 1)]
    dim: usize,
    /// Width of the falling edge in particle spacings, in (0, 1e6] (default 10; edge only).
    #[arg(long)]
    edge_width: Option<f64>,
    /// Write every particle's exact and interpolated value, gradient and second derivative to
    /// this CSV file (one block of rows per h).
    #[arg(long)]
    out: Option<std::path::PathBuf>,
    /// Print one JSON document instead of text: "reports", one per h, and "units".
    #[arg(long)]
    json: bool,
}

/// One end of --interval: a number, or a number times pi ("3pi", "-0.5pi", "pi").
fn end(s: &str) -> Result<f64> {
    let t = s.trim();
    let v = match t.strip_suffix("pi") {
        Some(m) => {
            let m = m.trim();
            let f = if m.is_empty() {
                1.0
            } else if m == "-" {
                -1.0
            } else {
                m.parse::<f64>().map_err(|_| bad_interval(s))?
            };
            f * std::f64::consts::PI
        }
        None => t.parse::<f64>().map_err(|_| bad_interval(s))?,
    };
    Ok(v)
}

fn bad_interval(s: &str) -> anyhow::Error {
    anyhow::anyhow!("--interval: `{s}` is not a number or a multiple of pi (e.g. 0,1 or 0,3pi)")
}

fn config(a: &Args, budget: &sphstab::budget::Budget) -> Result<Vec<InterpolationConfig>> {
    if a.edge_width.is_some() && a.function != "edge" {
        bail!("--edge-width applies to --function edge only");
    }
    let function = TestFunction::by_name(&a.function, a.edge_width.unwrap_or(10.0))?;
    let kernel = sphstab::kernel::by_name(&a.kernel)?;
    let shape = ShapeFamily::by_name(&a.shape)?;
    let normalisation = Normalisation::by_name(&a.normalisation)?;
    let interval = match &a.interval {
        None => function.default_interval(),
        Some(s) => {
            let parts: Vec<&str> = s.split(',').collect();
            if parts.len() != 2 {
                bail!("--interval: give two ends \"A,B\" (e.g. 0,1 or 0,3pi), got `{s}`");
            }
            (end(parts[0])?, end(parts[1])?)
        }
    };
    if a.h.len() > 64 {
        bail!("--h: give 1 to 64 values, got {}", a.h.len());
    }
    let hs = if a.h.is_empty() {
        vec![5.5]
    } else {
        a.h.clone()
    };
    hs.iter()
        .map(|&h| {
            let c = InterpolationConfig {
                dim: a.dim,
                function,
                interval,
                particles: a.particles,
                kernel,
                h_over_dx: h,
                shape,
                ghosts: a.ghosts,
                normalisation,
                budget: *budget,
            };
            c.validate()?;
            Ok(c)
        })
        .collect()
}

fn pct(x: f64) -> String {
    format!("{:.3}%", 100.0 * x)
}

fn norms_cells(n: &Option<ErrorNorms>) -> String {
    match n {
        Some(n) => format!(
            "{:>10} {:>10} {:>10} {:>10}",
            pct(n.max),
            pct(n.rms),
            pct(n.boundary_max),
            n.interior_max.map_or("-".into(), pct)
        ),
        None => format!("{:>10} {:>10} {:>10} {:>10}", "-", "-", "-", "-"),
    }
}

fn text(reps: &[InterpolationReport]) -> String {
    let r0 = &reps[0];
    let mut s = String::new();
    let fname = match (r0.function, r0.edge_width) {
        ("edge", Some(w)) => format!("edge (width {w} Δx)"),
        (f, _) => f.to_string(),
    };
    let _ = writeln!(
        s,
        "sphstab interpolate: {fname} on [{}, {}]{}, {} particles per axis (Δx = {}), {} ({} normalisation), {} shapes, {}",
        sphstab::display::num_sig(r0.interval[0], 6),
        sphstab::display::num_sig(r0.interval[1], 6),
        if r0.dim == 2 { " squared (2D)" } else { "" },
        r0.particles,
        sphstab::display::num_sig(r0.spacing, 6),
        r0.kernel,
        r0.normalisation,
        r0.shape,
        if r0.ghosts {
            "ghosts beyond both ends"
        } else {
            "no ghosts"
        }
    );
    let _ = writeln!(
        s,
        "errors relative to the largest exact magnitude on the interval; boundary: the particles within one support radius R of an end; S0: the kernel's lattice sum Σ W ΔV over a full cover"
    );
    let _ = writeln!(
        s,
        "  h/Δx   R/Δx       S0 | f: max        rms   boundary   interior | ∇f: max      rms   boundary   interior | ∇²f: max     rms   boundary   interior | f(a): rel. error"
    );
    for r in reps {
        let _ = writeln!(
            s,
            "{:>6} {:>6} {:>8} | {} | {} | {} | {}",
            sphstab::display::num_sig(r.h_over_dx, 4),
            sphstab::display::num_sig(r.support_over_dx, 4),
            sphstab::display::num_sig(r.lattice_sum, 5),
            norms_cells(&Some(r.value)),
            norms_cells(&r.gradient),
            norms_cells(&r.laplacian),
            r.value_at_start.map_or("-".into(), pct)
        );
    }
    if reps[0].gradient_peak_width.is_some() {
        for r in reps {
            let _ = writeln!(
                s,
                "h/Δx = {}: gradient peak width (FWHM) {} Δx, Σ⟨f′⟩Δx = {} (exact −1)",
                sphstab::display::num_sig(r.h_over_dx, 4),
                sphstab::display::num_sig(r.gradient_peak_width.unwrap_or(0.0), 4),
                sphstab::display::num_sig(r.gradient_integral.unwrap_or(0.0), 6)
            );
        }
    }
    s
}

fn csv(reps: &[InterpolationReport]) -> String {
    let mut s = String::from(
        "h_over_dx,position,f,f_approx,gradient_x,gradient_x_approx,laplacian_exact,laplacian_approx\n",
    );
    for r in reps {
        for i in 0..r.position.len() {
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{},{}",
                r.h_over_dx,
                r.position[i],
                r.f[i],
                r.f_approx[i],
                r.gradient_x[i],
                r.gradient_x_approx[i],
                r.laplacian_exact[i],
                r.laplacian_approx[i]
            );
        }
    }
    s
}

pub fn run(a: Args, budget: &sphstab::budget::Budget) -> Result<()> {
    let cfgs = config(&a, budget)?;
    if let Some(p) = &a.out {
        Files::new().output("--out", p).check()?;
    }
    let reps = cfgs
        .iter()
        .map(interpolate)
        .collect::<sphstab::error::Result<Vec<_>>>()?;
    if let Some(p) = &a.out {
        std::fs::write(p, csv(&reps))
            .map_err(|e| anyhow::anyhow!("--out: cannot write {}: {e}", p.display()))?;
    }
    if a.json {
        /// The JSON document: the reports, then their units.
        #[derive(serde::Serialize)]
        struct Doc<'a> {
            reports: &'a [InterpolationReport],
        }
        println!(
            "{}",
            sphstab::units::json(
                &Doc { reports: &reps },
                sphstab::units::System::Normalised,
                false
            )?
        );
    } else {
        print!("{}", text(&reps));
    }
    Ok(())
}
