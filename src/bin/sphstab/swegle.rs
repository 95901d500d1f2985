//! `sphstab swegle`: the Swegle perturbed-particle test [V21 §7.2] against the engine, in 2D
//! or 3D (`--dim`).

use anyhow::{Context, Result};
use sphstab::budget::Budget;
use sphstab::display::num;
use sphstab::studies::swegle::{SwegleSpec, run_swegle};

/// Flags of `swegle`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    integ: crate::common::IntegratorArgs,
    #[command(flatten)]
    diffusion: crate::common::DiffusionArgs,
    /// Dimension: 2 (size² particles) or 3 (size³ particles).
    #[arg(long, default_value_t = 2)]
    dim: usize,
    /// classical, nonlocal, local, lnl, cll, total-lagrangian.
    #[arg(long, default_value = "classical")]
    form: String,
    /// Kernel name.
    #[arg(long, default_value = "m4")]
    kernel: String,
    /// Smoothing length h/Δx in the kernel's own convention, in [0.05, 50] (support ζh > Δx).
    #[arg(long, default_value_t = 1.2, allow_hyphen_values = true)]
    h: f64,
    /// Shape family (default: the form's).
    #[arg(long)]
    shape: Option<String>,
    /// f = ρ/ρ0, dimensionless, in [0.5, 1.5]: < 1 tension, > 1 compression (pre-stress
    /// σ̄ = σ/K = 1 − f).
    #[arg(
        long = "density-ratio",
        default_value_t = 0.99,
        allow_hyphen_values = true
    )]
    density_ratio: f64,
    /// Particles per side, at least 2 × 3 fixed layers + 3 = 9, at most 2001 (2D) or 201 (3D),
    /// and bounded by --max-memory / --max-steps. Default 21 in 2D (the published box), 12 in 3D.
    /// The box prediction is the fastest mode of the exact operator of the particle set, by an
    /// iterative eigen-solver (3D: ~4 s at 12, ~1 min at 21); with no growing mode, its dense
    /// eigenvalues up to 1,000 free degrees of freedom (--size 28 in 2D, 12 in 3D).
    #[arg(long)]
    size: Option<usize>,
    /// End time in the test's units (Δx = 0.1, c = √(K/ρ0) ≈ 0.495, so Δx/c ≈ 0.2020: t = 40 is
    /// ≈ 198 Δx/c), in (0, 1e6]; the run (size^dim × t_end/Δt particle-steps) must fit
    /// --max-steps.
    #[arg(long = "t-end", default_value_t = 40.0, allow_hyphen_values = true)]
    t_end: f64,
    /// Run past --t-end until a mode growing at the box prediction reaches the fit window.
    #[arg(long = "until-window")]
    until_window: bool,
    /// Initial v_x of the centre particle in the test's units (c ≈ 0.495), in [1e-15, 1e-9]
    /// (1e-10 as published). Smaller: the
    /// fastest mode outgrows the slower ones for longer before the fixed fit window
    /// (1e-8 < max |v| < 1e-4); large 3D boxes need 1e-14 to be fitted at their fastest rate.
    #[arg(long, default_value_t = 1e-10)]
    kick: f64,
    /// Boundary layers' density (and stress): evolve (continuity; default) or frozen.
    #[arg(long = "boundary-density")]
    boundary_density: Option<String>,
    /// Time step Δt in Δx/c, in (0, 2] (in the test's units Δt = dt × 0.2020; the CFL number
    /// c Δt/h is dt/(h/Δx)). `--cfl`, its old name, is read too.
    #[arg(long, alias = "cfl", default_value_t = 0.2, allow_hyphen_values = true)]
    dt: f64,
    /// Partition coefficient c of lnl/cll, in [0, 1] (default 0.5).
    #[arg(long, allow_hyphen_values = true)]
    c: Option<f64>,
    /// Monaghan–Gray artificial stress ε of the classical form, dimensionless, in [0, 10] (off
    /// by default, as published).
    #[arg(long = "art-eps", allow_hyphen_values = true)]
    art_eps: Option<f64>,
    /// Artificial-stress exponent n, in [1, 12] (needs --art-eps).
    #[arg(long = "art-n")]
    art_n: Option<i32>,
    /// JSON on stdout: rates in c/Δx, dt in Δx/c, what the run measures in the test's units
    /// with the scales that convert them (dt_physical, dx_physical, sound_speed_physical); its
    /// "units" name the unit of every field.
    #[arg(long)]
    json: bool,
    /// SVG of max |v| against time (in Δx/c) with the predicted slopes.
    #[arg(long)]
    plot: Option<std::path::PathBuf>,
    /// Write history.csv (t, centre |v|, max and RMS |v| of the free particles, kinetic energy;
    /// in the test's units) and final.vtk (particles) here.
    #[arg(long)]
    out: Option<std::path::PathBuf>,
    #[command(flatten)]
    export: crate::export::ExportArgs,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let export = a
        .export
        .resolve(a.plot.is_some(), "no --plot (it sets the plot's formats)")?;
    let mut files = crate::files::Files::new();
    if let Some(p) = &a.plot {
        files = export.output(files, "--plot", p);
    }
    if let Some(d) = &a.out {
        std::fs::create_dir_all(d)
            .with_context(|| format!("--out: cannot create {}", d.display()))?;
        files = files
            .output("--out", d.join("history.csv"))
            .output("--out", d.join("final.vtk"));
    }
    files.check()?;
    let spec = SwegleSpec {
        dim: Some(a.dim),
        form: Some(a.form.clone()),
        kernel: Some(a.kernel.clone()),
        h: Some(a.h),
        shape: a.shape.clone(),
        density_ratio: Some(a.density_ratio),
        size: a.size,
        t_end: Some(a.t_end),
        until_window: Some(a.until_window),
        kick: Some(a.kick),
        boundary_density: a.boundary_density.clone(),
        dt: Some(a.dt),
        c: a.c,
        art_eps: a.art_eps,
        art_n: a.art_n,
        integrator: Some(a.integ.integrator.clone()),
        euler_every: a.integ.euler_every,
        delta: a.diffusion.delta,
        delta_form: a.diffusion.delta_form.clone(),
    };
    let cfg = spec.config(budget)?;
    let pb = crate::progress::Bar::new(crate::progress::wanted(a.json));
    let r = run_swegle(&cfg, pb.clone())?;
    pb.finish();
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("--out: cannot create {}", dir.display()))?;
        let h = sphstab::solver::output::csv(
            &sphstab::studies::swegle::HISTORY_COLUMNS,
            r.history_full.iter().map(|row| row.to_vec()),
        );
        std::fs::write(dir.join("history.csv"), h)
            .with_context(|| format!("--out: cannot write in {}", dir.display()))?;
        if let Some(z) = &r.final_state {
            let title = format!(
                "swegle {} {} h={} f={} t={}",
                r.form,
                r.kernel,
                num(r.h_over_dx),
                num(r.density_ratio),
                num(r.dt_physical * r.steps as f64)
            );
            std::fs::write(
                dir.join("final.vtk"),
                z.vtk(&title, cfg.form, cfg.c_partition),
            )
            .with_context(|| format!("--out: cannot write in {}", dir.display()))?;
        }
    }
    if let Some(path) = &a.plot {
        use sphstab::plot::{Curve, LinePlot};
        // time in units of Δx/c, so the slopes read directly as growth rates in c/Δx
        let unit = cfg.sound_speed() / cfg.dx;
        let t: Vec<f64> = r.history.iter().map(|h| h.0 * unit).collect();
        let lv: Vec<f64> = r.history.iter().map(|h| h.1).collect();
        let mut curves = vec![Curve {
            label: "max |v| over the free particles (simulation)".into(),
            x: t.clone(),
            y: lv,
            dashed: false,
        }];
        let (wlo, whi) = (cfg.window.0.log10(), cfg.window.1.log10());
        let mut band = None;
        if let Some(f) = r.fit {
            let t0 = f.window.0 * unit;
            band = Some((
                t0,
                f.window.1 * unit,
                format!(
                    "fit window ({:.0e} < max |v| < {:.0e})",
                    cfg.window.0, cfg.window.1
                ),
            ));
            let mut lines = vec![
                ("box prediction", Some(r.predicted_growth_rate_box)),
                ("infinite lattice", Some(r.predicted_growth_rate_infinite)),
            ];
            lines.insert(0, ("fit to the simulation", r.measured_growth_rate));
            for (name, rate) in lines {
                let Some(rate) = rate else { continue };
                let slope = rate / std::f64::consts::LN_10;
                // each line only where it stays within a decade of the fit window
                let y: Vec<f64> = t
                    .iter()
                    .map(|&s| {
                        let v = wlo + slope * (s - t0);
                        if v >= wlo - 1.0 && v <= whi + 1.0 {
                            10f64.powf(v)
                        } else {
                            f64::NAN
                        }
                    })
                    .collect();
                curves.push(Curve {
                    label: format!("{name}: γ = {rate:.4} c/Δx"),
                    x: t.clone(),
                    y,
                    dashed: true,
                });
            }
        }
        let svg = LinePlot {
        names: sphstab::studies::series_names(),
            band,
            y_log: true,
            notes: vec![format!(
                "Straight lines: growth e^(γt) through the start of the fit window, slope γ/ln 10 per Δx/c; centre particle kicked with v_x = {:.0e}.",
                cfg.kick
            )],
            ..LinePlot::new(
                &format!(
                    "Swegle test: {} / {} h = {}Δx, f = ρ/ρ0 = {}, {}",
                    r.form,
                    r.kernel,
                    num(r.h_over_dx),
                    num(r.density_ratio),
                    cfg.shape_label().replace(' ', "")
                ),
                "time t (units of Δx/c)",
                "max |v| (the scene's velocity unit)",
                curves,
            )
        }
        .svg()?;
        export.write("--plot", &svg, path)?;
    }
    if a.json {
        let mut v = serde_json::to_value(&r)?;
        if let Some(o) = v.as_object_mut() {
            o.remove("history");
        }
        println!(
            "{}",
            sphstab::units::json(&v, sphstab::units::System::SwegleTest, true)?
        );
        return diverged(&r);
    }
    // the test has units of its own: every time, rate and speed also in them
    let per_time = r.sound_speed_physical / r.dx_physical;
    let rate = |g: f64| {
        format!(
            "{g:.5} c/Δx ({} /time unit)",
            sphstab::display::num_sig(g * per_time, 4)
        )
    };
    println!(
        "Swegle test {} ({}D): {} / {} h = {}Δx, f = ρ/ρ0 = {} (σ̄ = 1 − f = {}); test units Δx = {}, c = {:.4}, Δx/c = {:.4}",
        cfg.shape_label().replace(' ', ""),
        r.dim,
        r.form,
        r.kernel,
        num(r.h_over_dx),
        num(r.density_ratio),
        sphstab::display::num_sig(1.0 - r.density_ratio, 6),
        num(r.dx_physical),
        r.sound_speed_physical,
        1.0 / per_time
    );
    match r.measured_growth_rate {
        Some(m) if r.ratio_box.is_some() => println!(
            "measured growth {}; box prediction ({}) {}; infinite lattice {}; measured/box {:.4}{}",
            rate(m),
            r.box_method,
            rate(r.predicted_growth_rate_box),
            rate(r.predicted_growth_rate_infinite),
            r.ratio_box.unwrap_or(0.0),
            r.ratio_infinite
                .map(|x| format!(", measured/infinite {x:.4}"))
                .unwrap_or_default()
        ),
        Some(m) => println!(
            "max |v| rose through the fit window at {}, but the engine predicts no exponential growth (box {:.2e} c/Δx, infinite lattice {:.2e} c/Δx): secular growth of a zero-energy mode or a nonlinear effect, not a linear instability",
            rate(m),
            r.predicted_growth_rate_box,
            r.predicted_growth_rate_infinite
        ),
        None => println!(
            "no exponential growth measured (grew: {}); box prediction {}, infinite lattice {}",
            r.grew,
            rate(r.predicted_growth_rate_box),
            rate(r.predicted_growth_rate_infinite)
        ),
    }
    println!(
        "max |v| at the end {:.3e} ({:.3e} c); {} steps of Δt = {} in {:.2} s wall clock",
        r.max_velocity_end,
        r.max_velocity_end / r.sound_speed_physical,
        r.steps,
        sphstab::units::both(r.dt_physical, "time units", r.dt, "Δx/c"),
        r.runtime_s
    );
    diverged(&r)
}

/// Exit status 3 (via the error) after the report when the run diverged.
fn diverged(r: &sphstab::studies::swegle::SwegleReport) -> Result<()> {
    match r.diverged {
        Some(d) => Err(sphstab::error::Error::Diverged {
            step: d.step,
            t: d.t,
            what: d.what,
            max_amplitude: r.max_velocity_end,
        }
        .into()),
        None => Ok(()),
    }
}
