//! `sphstab simulate`: run a 1D scene (JSON file or built-in name).

use crate::flags::InFile;
use anyhow::{Context, Result};
use sphstab::budget::Budget;
use sphstab::solver::output::csv;
use sphstab::solver::scene::{builtin, parse};

/// Flags of `simulate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene: a JSON file, or uniform-bar, compressive-wave, tensile-wave, rod, thesis-wave
    /// (density interface, ρB/ρA = 0.25, 0.5, 2, 4), swegle (the 2D Swegle box with its defaults;
    /// `sphstab swegle` has all its options).
    scene: String,
    /// Override the scene's form.
    #[arg(long)]
    form: Option<String>,
    /// Override the scene's end time t_end, > 0: in s for a scene (SI), in the test's units for
    /// swegle (as `swegle --t-end`).
    #[arg(long = "t-end", allow_hyphen_values = true)]
    t_end: Option<f64>,
    /// Time integrator (overrides the scene's `integrator`; default kdk): kdk, dkd, verlet-lagged,
    /// symplectic-euler-vx, symplectic-euler-xv, pec, epec, verlet-euler, rk2-midpoint, rk2-heun,
    /// rk4, euler.
    #[arg(long)]
    integrator: Option<String>,
    /// N_s of verlet-euler (overrides the scene's `euler_every`; default 40), in [1, 1000];
    /// verlet-euler only.
    #[arg(long = "euler-every", allow_hyphen_values = true)]
    euler_every: Option<usize>,
    /// JSON summary on stdout: physical values in SI with the scales that normalise them
    /// (dx_physical, sound_speed_physical, modulus_physical) and the step in Δx/c (dt); its
    /// "units" name the unit of every field.
    #[arg(long)]
    json: bool,
    /// Write history.csv (t, max |v|, kinetic energy; SI) and final.vtk here.
    #[arg(long)]
    out: Option<std::path::PathBuf>,
    /// thesis-wave only: the density ratios ρB/ρA to run, comma-separated (at most 64), each in
    /// [1e-4, 1e4] (default 0.25,0.5,2,4).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    density_ratio: Vec<f64>,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    if a.scene == "swegle" {
        let mut args = vec!["swegle".to_string()];
        if let Some(f) = &a.form {
            args.extend(["--form".into(), f.clone()]);
        }
        if let Some(t) = a.t_end {
            args.extend(["--t-end".into(), t.to_string()]);
        }
        if let Some(i) = &a.integrator {
            args.extend(["--integrator".into(), i.clone()]);
        }
        if let Some(n) = a.euler_every {
            args.extend(["--euler-every".into(), n.to_string()]);
        }
        if a.json {
            args.push("--json".into());
        }
        if let Some(o) = &a.out {
            args.extend(["--out".into(), o.display().to_string()]);
        }
        let parsed = <crate::swegle::Args as clap::FromArgMatches>::from_arg_matches(
            &<crate::swegle::Args as clap::Args>::augment_args(clap::Command::new("swegle"))
                .try_get_matches_from(args)?,
        )?;
        return crate::swegle::run(parsed, budget);
    }
    if let Some(e) = experiment(&a)? {
        return run_experiment(e, &a, budget);
    }
    if !a.density_ratio.is_empty() && a.scene != "thesis-wave" {
        return Err(crate::query::not_in(
            "--density-ratio",
            "a scene other than thesis-wave (the Swegle box's is `sphstab swegle --density-ratio`)",
        ));
    }
    if a.scene == "thesis-wave" {
        if a.t_end.is_some() || a.out.is_some() || a.integrator.is_some() || a.euler_every.is_some()
        {
            return Err(crate::query::not_in(
                "--t-end/--out/--integrator/--euler-every",
                "the thesis-wave scene (its four runs end when the pulse has crossed the interface)",
            ));
        }
        let form = sphstab::forms::FormKind::by_name(a.form.as_deref().unwrap_or("nonlocal"))?;
        let k = sphstab::kernel::by_name("m4")?;
        if a.density_ratio.len() > 64 {
            anyhow::bail!(
                "--density-ratio: give 1 to 64 values, got {}",
                a.density_ratio.len()
            );
        }
        let ratios = if a.density_ratio.is_empty() {
            vec![0.25, 0.5, 2.0, 4.0]
        } else {
            a.density_ratio.clone()
        };
        let mut rows = Vec::new();
        for r in ratios {
            let mut cfg = sphstab::solver::thesis_wave::ThesisWave::new(form, k, r);
            cfg.budget = *budget;
            rows.push(sphstab::solver::thesis_wave::run_thesis_wave(&cfg)?);
        }
        if a.json {
            println!("{}", serde_json::to_string_pretty(&rows)?);
        } else {
            println!(
                "thesis-wave / {}: particle-velocity reflection and transmission at a density interface [T eq 4.45–4.46]",
                form.name()
            );
            for r in rows {
                let t = r
                    .transmitted
                    .map_or("not measurable".to_string(), |t| format!("{t:.4}"));
                println!(
                    "ρB/ρA = {:<5} reflected {:+.4} (exact {:+.4})  transmitted {t} (exact {:.4})  Δt {:.3e} s, {} steps",
                    r.density_ratio,
                    r.reflected,
                    r.reflected_exact,
                    r.transmitted_exact,
                    r.time_step,
                    r.steps
                );
            }
        }
        return Ok(());
    }
    let mut scene = if a.scene.ends_with(".json") || std::path::Path::new(&a.scene).exists() {
        parse(&a.scene, &read_scene(&a.scene)?)?
    } else {
        builtin(&a.scene)?
    };
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("--out: cannot create {}", dir.display()))?;
        let mut files = crate::files::Files::new();
        if std::path::Path::new(&a.scene).is_file() {
            files = files.input("<SCENE>", &a.scene);
        }
        files = files
            .output("--out", dir.join("history.csv"))
            .output("--out", dir.join("final.vtk"));
        if !scene.probes.is_empty() {
            files = files.output("--out", dir.join("probes.csv"));
        }
        files.check()?;
    }
    if let Some(f) = &a.form {
        scene.override_form(f);
    }
    if let Some(t) = a.t_end {
        sphstab::error::check_range("--t-end", t, 0.0, f64::INFINITY, false, false)?;
        scene.t_end = t;
    }
    if a.integrator.is_some() || a.euler_every.is_some() {
        // validate the flags under their own names before they reach the scene
        let name = a.integrator.clone().or(scene.integrator.clone());
        let every = a.euler_every.or(scene.euler_every);
        let resolved = name.as_deref().unwrap_or("kdk");
        sphstab::integrator::Integrator::by_names(Some(resolved), a.euler_every)?;
        if let Some(n) = every {
            sphstab::integrator::Integrator::from_name(resolved, n)?;
        }
        scene.override_integrator(resolved.to_string(), every);
    }
    scene.budget = *budget;
    let pb = crate::progress::Bar::new(crate::progress::wanted(a.json));
    // the scene's fields are what the user wrote (a file) or chose (a built-in): named as such
    let r = scene.run(pb.clone()).map_err(InFile)?;
    pb.finish();
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("--out: cannot create {}", dir.display()))?;
        let h = csv(
            &sphstab::solver::scene::HISTORY_COLUMNS,
            r.history.iter().map(|&(t, v, e)| vec![t, v, e]),
        );
        std::fs::write(dir.join("history.csv"), h)
            .with_context(|| format!("--out: cannot write in {}", dir.display()))?;
        if !r.probes.is_empty() {
            std::fs::write(dir.join("probes.csv"), probes_csv(&r))
                .with_context(|| format!("--out: cannot write in {}", dir.display()))?;
        }
        if let Some(z) = &r.final_state {
            let form = sphstab::forms::FormKind::by_name(r.form)?;
            std::fs::write(
                dir.join("final.vtk"),
                z.vtk(
                    &format!("{} {} t={}", r.name, r.form, sphstab::display::num(r.t)),
                    form,
                    r.c_partition.unwrap_or(0.5),
                ),
            )
            .with_context(|| format!("--out: cannot write in {}", dir.display()))?;
        }
    }
    if a.json {
        println!(
            "{}",
            sphstab::units::json(&r, sphstab::units::System::Si, true)?
        );
        return Ok(());
    }
    // every physical value with its normalised one (Δx/c, c, σ̄ = σ/C)
    let time_unit = r.dx_physical / r.sound_speed_physical;
    println!(
        "{} / {}: t = {:.4e} s ({} Δx/c) in {} steps of Δt = {:.4e} s ({} Δx/c) ({:.2} s wall clock); max |v| {:.4e} m/s ({:.4e} c); velocity L2 error vs analytic (relative): {}",
        r.name,
        r.form,
        r.t,
        sphstab::display::num_sig(r.t / time_unit, 6),
        r.steps,
        r.dt_physical,
        sphstab::display::num_sig(r.dt, 6),
        r.runtime_s,
        r.max_velocity,
        r.max_velocity / r.sound_speed_physical,
        r.velocity_error_l2
            .map(|e| format!("{e:.4e}"))
            .unwrap_or("n/a".into()),
    );
    if !r.probes.is_empty() {
        let parts: Vec<String> = r
            .probes
            .iter()
            .map(|p| {
                let (lo, hi) = p
                    .stress
                    .iter()
                    .fold((0.0f64, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
                // X on the axis, (X, Y(, Z)) off it
                let at = if p.across.is_empty() {
                    format!("X = {} m", sphstab::display::num(p.reference_position))
                } else {
                    format!("({}) m", p.label().replace(';', ", "))
                };
                if p.stress.is_empty() {
                    format!("{at}: no stress")
                } else {
                    format!("{at}: [{lo:.4e}, {hi:.4e}]")
                }
            })
            .collect();
        println!(
            "probes, stress range (Pa): {}; histories in probes.csv (--out) and `probes` (--json)",
            parts.join("; ")
        );
    }
    if let Some(s) = r.stress {
        let c = r
            .c_partition
            .map(|c| format!(" ((1 − c)σ + cτ, c = {})", sphstab::display::num(c)))
            .unwrap_or_default();
        let modulus = r.modulus_physical;
        println!(
            "final stress{c} in [{:.4e}, {:.4e}] Pa (σ̄ = σ/C in [{:.4e}, {:.4e}]); max stress error vs analytic: {}",
            s.min,
            s.max,
            s.min / modulus,
            s.max / modulus,
            s.error_max
                .map(|e| format!("{e:.4e} of max |σ_exact|"))
                .unwrap_or("n/a".into()),
        );
    }
    Ok(())
}

/// The probes' histories as CSV: `t`, then for each probe at X the columns `u@X`, `v@X`,
/// `stress@X` (if the form has one), `stretch@X` (total-Lagrangian), `v_exact@X` and
/// `stress_exact@X` (with the `end-pulse` solution), SI units.
fn probes_csv(r: &sphstab::solver::scene::SceneReport) -> String {
    let mut header = vec!["t".to_string()];
    let mut cols: Vec<&[f64]> = Vec::new();
    for p in &r.probes {
        let x = p.label();
        for (name, v) in [
            ("u", &p.displacement),
            ("v", &p.velocity),
            ("stress", &p.stress),
            ("stretch", &p.stretch),
            ("v_exact", &p.exact_velocity),
            ("stress_exact", &p.exact_stress),
        ] {
            if !v.is_empty() {
                header.push(format!("{name}@{x}"));
                cols.push(v);
            }
        }
    }
    let names: Vec<&str> = header.iter().map(String::as_str).collect();
    csv(
        &names,
        r.probe_t.iter().enumerate().map(|(i, &t)| {
            std::iter::once(t)
                .chain(cols.iter().map(|c| c[i]))
                .collect()
        }),
    )
}

/// Largest scene file read (a scene is a few hundred bytes; this stops an endless device).
const MAX_SCENE_BYTES: u64 = 1 << 20;

/// Reads a scene file of at most [`MAX_SCENE_BYTES`].
fn read_scene(path: &str) -> Result<String> {
    use std::io::Read;
    let f = std::fs::File::open(path).with_context(|| format!("cannot read scene {path}"))?;
    let mut buf = Vec::new();
    f.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut buf)
        .with_context(|| format!("cannot read scene {path}"))?;
    if buf.len() as u64 > MAX_SCENE_BYTES {
        anyhow::bail!("scene {path}: larger than 1 MiB, not a scene file");
    }
    String::from_utf8(buf).map_err(|_| anyhow::anyhow!("scene {path}: not UTF-8 text"))
}

/// The scene file as an experiment of the tensile-or-hourglass study (a JSON object with an
/// `experiment` field), or None for any other scene.
fn experiment(a: &Args) -> Result<Option<sphstab::studies::hourglass::Experiment>> {
    let path = std::path::Path::new(&a.scene);
    if !path.is_file() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read the scene {}", a.scene))?;
    let is_experiment = serde_json::from_str::<serde_json::Value>(&text)
        .ok()
        .is_some_and(|v| v.get("experiment").is_some());
    if !is_experiment {
        return Ok(None);
    }
    Ok(Some(sphstab::studies::hourglass::parse_experiment(
        &a.scene, &text,
    )?))
}

/// Runs an experiment of the tensile-or-hourglass study (`--form`, `--t-end` in Δx/c and
/// `--json` apply).
fn run_experiment(
    mut e: sphstab::studies::hourglass::Experiment,
    a: &Args,
    budget: &Budget,
) -> Result<()> {
    if a.integrator.is_some() || a.euler_every.is_some() || a.out.is_some() {
        return Err(crate::query::not_in(
            "--integrator/--euler-every/--out",
            "an experiment (kdk; it reports its growth, no fields)",
        ));
    }
    if let Some(f) = &a.form {
        e.remedy.query.form = Some(f.clone());
        e.remedy.label = f.clone();
    }
    if let Some(t) = a.t_end {
        e.t_end = t;
    }
    e.budget = *budget;
    let pb = crate::progress::Bar::new(crate::progress::wanted(a.json));
    let r = e.run(pb.clone())?;
    pb.finish();
    if a.json {
        println!(
            "{}",
            sphstab::units::json(&r, sphstab::units::System::Normalised, true)?
        );
    } else {
        print!("{}", sphstab::studies::hourglass::experiment_text(&r));
    }
    Ok(())
}
